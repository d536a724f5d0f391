"""A scene or a site as a limit-analysis problem (:mod:`ssi.limit`): what its collapse load factor lambda
scales and what is held. The bracket itself: :mod:`ssi.capacity.bracket`; the mapping of each part, what is
refused and the embedded strip's side soil: this package's README.md.

One path for both. :func:`limit_problem` asks the input its ``kind`` and hands it to the geometry of that
kind -- :func:`ssi.capacity.scene_problem.scene_parts` (a Scene's block, cut at every layer boundary, load
end and trench) or :func:`ssi.capacity.site_problem.site_parts` (a Site's own geometry, several strips) --
which return the same data (:class:`~ssi.capacity.common.Parts`); everything else is common
(:mod:`ssi.capacity.common`): the materials, the interfaces, the loads of the phases summed into each
footing's forces and the ground pressures through each load's own ``limit_action``, the boundary of every
ground segment and the :class:`LimitProblem`. A scene or a site is read through the fields and methods the
README lists; this package never imports ``ssi.scene``.
"""

from __future__ import annotations

from .action import LimitInput
from .common import SIDE_SOIL, LimitProblem, assemble
from .scene_problem import scene_parts
from .site_problem import site_parts

__all__ = ["SIDE_SOIL", "LimitProblem", "limit_problem"]


def limit_problem(
    scene: LimitInput,
    phase: str | None = None,
    strip: str | None = None,
    side_soil: str | None = None,
    unloaded: bool = False,
) -> LimitProblem:
    """The limit-analysis problem of a Scene or a Site with lambda scaling the loads of ``phase`` (None: the
    last phase; a Site has one, its loads). ``strip``: "rigid" or "beam" (a plate Foundation's strip as a
    beam with plastic hinges of M_p at N = 0, :mod:`ssi.capacity.strip`) or "beam_mn" (the same beam, its
    hinges' capacity the section's M-N polygon, :func:`~ssi.capacity.strip.strip_beam_interaction`: safe
    where the beam's axial force lowers M_p; on a rough base its hinges cannot extend and the upper bound is
    then loose); None: "beam" for an RC section that is not brittle under force loads a beam represents,
    else "rigid" (with a warning for a brittle section or such a load). ``side_soil``: how an embedded
    strip's side soil enters, "surcharge" (its overburden on the ground at the base level) or "soil"
    (modelled; README, *Embedment*); None: "surcharge" for a Scene, "soil" for a Site (the only model of a
    site's trench). ``unloaded``: a Site with no loads is accepted (its factor of safety under its own
    weight, :func:`ssi.capacity.safety.safety_factor`), else refused: nothing to scale. Raises ValueError
    naming whatever the input holds that :mod:`ssi.limit` cannot represent."""
    if strip is not None and strip not in ("rigid", "beam", "beam_mn"):
        raise ValueError(f"strip must be 'rigid', 'beam', 'beam_mn' or None, got {strip!r}")
    if side_soil is not None and side_soil not in SIDE_SOIL:
        raise ValueError(f"side_soil must be one of {SIDE_SOIL} or None, got {side_soil!r}")
    kind = getattr(scene, "kind", None)  # any object may come in: a Scene or a Site says which it is
    if kind not in ("scene", "site"):
        raise TypeError(
            f"scene must be an ssi.scene.Scene or ssi.scene.site.Site, got {type(scene).__name__}"
        )
    if kind == "site":
        if phase is not None:
            raise ValueError(f"phase={phase!r}: a Site has one phase (its loads); give phase=None")
        if strip in ("beam", "beam_mn"):
            raise ValueError("strip='beam': a Site's strips are rigid in ssi.limit (a beam strip: a Scene)")
        if side_soil == "surcharge" and scene.embedded():
            raise ValueError(
                "side_soil='surcharge': a Site's embedded strip stands in its trench with the side soil "
                "modelled (the site's geometry, the walls free faces or on its side_contact); give "
                "side_soil='soil' or None"
            )
        parts = site_parts(scene, unloaded)
    else:
        parts = scene_parts(scene, phase, strip, "surcharge" if side_soil is None else side_soil)
    return assemble(parts, scene)
