"""A plate strip in the limit problem as a beam with plastic hinges (:class:`ssi.limit.Beam`): whether it is
one (:func:`beam_mode`) and its hinges' M_p from ssi's own RC section analysis (:func:`strip_beam_capacity`,
:func:`strip_beam_interaction`); its loads as a beam carries them are each load's ``limit_action``
(:func:`ssi.capacity.common.beam_loads`), and :mod:`ssi.capacity.scene_problem` assembles the beam."""

from __future__ import annotations

import warnings

import numpy as np

__all__ = ["beam_mode", "is_rc", "strip_beam_capacity", "strip_beam_interaction"]


def strip_beam_capacity(section, bar_diameter: float = 0.016) -> tuple[float, float]:
    """(M_p sagging, M_p hogging) [N m/m] of a plate strip's RC ``section`` as plastic hinges: its bending
    resistance M_Rd at N = 0 from ssi's own section analysis (:class:`ssi.elements.rc_design.RCDesign`,
    characteristic strengths, the extreme fibre at eps_cu), per metre width. Unsafe where the section is
    brittle: a face whose cracking moment exceeds its yield moment (below minimum reinforcement, or no
    bars) cracks and loses its moment at once, no plastic hinge forms, and the limit theorems (which need
    a ductile hinge that keeps M_p) do not hold: refused (ValueError). The axial force's effect on M_p:
    :func:`strip_beam_interaction`. Not represented: the rotation capacity (a hinge here rotates without
    limit)."""
    from ..elements.rc_design import RCDesign

    design = RCDesign(section, bar_diameter=bar_diameter)
    brittle = design.brittle()
    for face, b in brittle.items():
        if b["brittle"]:
            raise ValueError(
                f"the strip's section is brittle on its {face} face (cracking moment {b['M_cr']:.4g} N m/m > "
                f"yield moment {b['M_y']:.4g} N m/m: below minimum reinforcement): it forms no plastic "
                "hinge, so the beam's capacity by limit analysis is unsafe; add reinforcement or give "
                "strip='rigid' (which ignores the strip's bending: unsafe too)"
            )
    return float(design.M_Rd(0.0, 1)), float(-design.M_Rd(0.0, -1))


def strip_beam_interaction(section, bar_diameter: float = 0.016, steps: tuple = (40, 10)) -> tuple:
    """The M-N interaction of a plate strip's RC ``section`` as a :class:`ssi.limit.Beam`'s ``interaction``:
    points (N [N/m] tension positive, M_sag, M_hog [N m/m] >= 0) with the moment about the section's base (the
    beam's axis in the limit problem: M_base = M_ref - N (z_ref - z_bottom), M_ref about the section's z = 0),
    each from ssi's own section analysis (``RCDesign.M_Rd(N)``: the extreme fibre at eps_cu, characteristic
    strengths). N steps by 1 / ``steps[0]`` of the squash load f_ck h + f_y A_s (compression) and by 1 /
    ``steps[1]`` of the bars' tension capacity f_y A_s, from N = 0 outwards, up to the first N where M_Rd
    finds no strain plane (its search starts at a small curvature whose planes carry only a moderate N: for
    chapter 11's strip about -1 MN/m, a tenth of the squash load) or the moment about the base changes sign:
    the polygon then stops there (the beam yields axially at that N: inside the true resistance, safe, and
    pessimistic for larger compressions). Unsafe, as M_p at N = 0, for a brittle section (refused:
    :func:`strip_beam_capacity`), and the rotation capacity is unlimited."""
    from ..elements.rc_design import RCDesign

    mp_sag, mp_hog = strip_beam_capacity(section, bar_diameter)
    design = RCDesign(section, bar_diameter=bar_diameter)
    e = -float(section.z_bottom)  # the base below the reference z = 0
    a_s = design.faces["bottom"].As + design.faces["top"].As
    points = [(0.0, mp_sag, mp_hog)]
    for unit, n_steps in zip((-(design.fck * design.h + design.fyk * a_s), design.fyk * a_s), steps):
        for k in range(1, n_steps):
            n = k * unit / n_steps
            try:
                ms = design.M_Rd(n, 1) - n * e
                mh = -design.M_Rd(n, -1) + n * e
            except ValueError:
                break
            if ms < 0.0 or mh < 0.0:
                break
            points.append((float(n), float(ms), float(mh)))
    return tuple(sorted(points))


def is_rc(section) -> bool:
    from ..materials.layer_laws import CONCRETE, STEEL

    return bool(np.any(section.kind == CONCRETE) and np.any(section.kind == STEEL))


def beam_mode(scene, strip: str | None):
    """(mp_sag, mp_hog) [N m/m] if the scene's strip is a beam in the limit problem, else None."""
    f = scene.foundation
    if strip == "rigid" or f is None:
        return None
    if f.rigid:
        if strip == "beam":
            raise ValueError("strip='beam': a RigidFooting is rigid; a beam strip needs a plate Foundation")
        return None
    if not is_rc(f.section):
        if strip == "beam":
            raise ValueError(
                "strip='beam': the Foundation's section is not reinforced concrete (no CONCRETE and STEEL "
                "layers), so it has no bending resistance to form plastic hinges from; give strip='rigid'"
            )
        return None  # an elastic strip has no strength of its own: held rigid (the stronger assumption)
    if strip is None:
        try:
            return strip_beam_capacity(f.section)
        except ValueError as err:
            warnings.warn(f"{err}; the strip is taken rigid", stacklevel=3)
            return None
    return strip_beam_capacity(f.section)
