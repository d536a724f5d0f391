"""Checks across the fields of a scene (what no single part can check alone): contact segments, symmetry, a
rigid footing's loads, phases and excavations, and a warning for values that look like non-SI units.
"""

import warnings

import numpy as np

from .parts import Contact, ContactSegment, Foundation


def _segments(scene):
    """The contact as a list of ContactSegment tiling the strip (checked)."""
    f, c = scene.foundation, scene.contact
    if isinstance(c, Contact):
        return [ContactSegment(f.x0, f.x1, c)]
    segs = sorted(c, key=lambda s: s.x0)
    if not segs or not all(isinstance(s, ContactSegment) for s in segs):
        raise TypeError("contact must be a Contact or a non-empty list of ContactSegment")
    tol = 1e-9 * max(1.0, f.x1 - f.x0)
    ends = [f.x0] + [v for s in segs for v in (s.x0, s.x1)] + [f.x1]
    gaps = [abs(a - b) for a, b in zip(ends[0::2], ends[1::2])]
    if max(gaps) > tol or any(s.x1 <= s.x0 for s in segs):
        raise ValueError(
            f"contact segments {[(s.x0, s.x1) for s in segs]} must tile the strip [{f.x0}, {f.x1}] "
            "without gaps or overlaps"
        )
    if len({s.contact.rule for s in segs}) != 1:
        raise ValueError("contact segments must share one integration rule")
    return segs


def _segment_at(segments, x):
    for seg in segments:
        if seg.x0 <= x <= seg.x1:
            return seg
    raise ValueError(f"x={x}: no contact segment covers this point of the strip")


def _check_symmetric(scene):
    """A symmetric scene: a RigidFooting (or no foundation) centred on the axis x = 0."""
    f = scene.foundation
    pushes = [ld for ld in scene._all_loads() if ld.drives == "horizontal"]
    if pushes:
        raise ValueError(
            f"Scene.symmetric=True: {pushes[0]!r} pushes the footing sideways, which is not symmetric about "
            "x = 0; model the whole block (symmetric=False)"
        )
    if isinstance(f, Foundation):
        raise ValueError(
            "Scene.symmetric=True models the half x >= 0 of a rigid footing or of bare ground; a plate "
            "Foundation's half model (its rotation held on the axis) is not built: use symmetric=False"
        )
    if f is not None and abs(f.x0 + f.x1) > 1e-9 * max(1.0, f.x1 - f.x0):
        raise ValueError(
            f"Scene.symmetric=True needs the foundation centred on the axis x = 0 (x0 = -x1), got "
            f"x0={f.x0!r}, x1={f.x1!r}"
        )


def _check_rigid_footing(scene):
    """A RigidFooting rests on the ground without an interface and takes only its settlement."""
    if scene.contact is not None:
        raise ValueError(
            "contact: a RigidFooting has no interface (its base is the soil's surface nodes); leave contact "
            "None, or use a plate Foundation"
        )
    if scene.embedment:
        raise ValueError(f"embedment={scene.embedment}: a RigidFooting sits on the ground (embedment 0)")
    for load in scene._all_loads():
        if load.on_rigid_footing():
            continue
        raise ValueError(
            f"loads: a RigidFooting takes only Settlement(w) (x=None: it settles as a whole), Push(u) and "
            f"the ground SurfacePressure; {load!r} needs a plate Foundation"
        )


def _check_phases(scene):
    names = [ph.name for ph in scene.load_phases()]
    if len(set(names)) != len(names) or "geostatic" in names:
        raise ValueError(f"phase names {names} must be unique and not 'geostatic' (the first phase's name)")
    for k, ph in enumerate(scene.phases):
        earlier = names[: names.index(ph.name)]
        unknown = [n for n in ph.factors if n not in earlier]
        if unknown:
            raise ValueError(
                f"phases[{k}] ({ph.name!r}): factors name {unknown}, which are not earlier phases ({earlier})"
            )
        if ph.n_steps is not None and int(ph.n_steps) < 1:
            raise ValueError(f"phases[{k}] ({ph.name!r}): n_steps must be >= 1, got {ph.n_steps}")
        _check_phase_soil(scene, k, ph)


def _check_excavations(built):
    """No excavation removes soil under the strip or beside an embedded strip's trench walls (an element with
    an edge on the contact or on a wall)."""
    scene, mesh = built.scene, built.mesh
    f = scene.foundation
    if f is None or not any(ph.excavate for ph in scene.phases):
        return
    xy = mesh.xy
    on_base = (
        (np.abs(xy[:, 1] + scene.embedment) < 1e-9) & (xy[:, 0] > f.x0 - 1e-9) & (xy[:, 0] < f.x1 + 1e-9)
    )
    on_wall = (
        (np.minimum(np.abs(xy[:, 0] - f.x0), np.abs(xy[:, 0] - f.x1)) < 1e-9)
        & (xy[:, 1] > -scene.embedment - 1e-9)
        & (scene.embedment > 0.0)
    )
    touching = (on_base | on_wall)[mesh.conn].sum(axis=1) >= 2
    for k, ph in enumerate(scene.phases):
        if (built._excavated(ph) & touching).any():
            raise ValueError(
                f"phases[{k}] ({ph.name!r}): an excavation removes soil under the strip or beside its trench "
                f"walls (strip x0={f.x0}, x1={f.x1}, embedment {scene.embedment} m); keep it clear of them"
            )


def _check_phase_soil(scene, k, ph):
    """A phase's excavations lie in the block and leave the strip and its loads alone; its drainage names
    existing layers that can be undrained."""
    where = f"phases[{k}] ({ph.name!r})"
    for key, value in ph.drainage.items():
        if key >= len(scene.layers):
            raise ValueError(
                f"{where}: drainage names layer {key}; the scene has layers 0..{len(scene.layers) - 1}"
            )
        if value == "undrained_A":
            try:
                scene.layers[key].undrained_k_water()
            except ValueError as err:
                raise ValueError(f"{where}: drainage[{key}] = 'undrained_A': {err}") from err
    lo, hi = scene.block()
    loads = [ld for p in scene.phases for ld in p.loads] + list(scene.loads)
    spans = [ld.ground_span() for ld in loads if ld.ground_span() is not None]  # the ground pressures
    for j, ex in enumerate(ph.excavate):
        name = f"{where}.excavate[{j}]"
        if ex.x0 < lo - 1e-9 or ex.x1 > hi + 1e-9:
            raise ValueError(f"{name}: x0={ex.x0}, x1={ex.x1} must lie in the block [{lo:g}, {hi:g}] m")
        if ex.bottom >= scene.depth:
            raise ValueError(f"{name}: bottom={ex.bottom} m must be < the block depth {scene.depth:g} m")
        for x0, x1 in spans:
            if ex.top == 0.0 and min(ex.x1, x1) - max(ex.x0, x0) > 1e-9:
                raise ValueError(
                    f"{name}: ({ex.x0}, {ex.x1}) removes the ground under SurfacePressure({x0}, {x1})"
                )


# values below these in SI look like they were given in kN, kPa or kN/m^3
_PLAUSIBLE_MIN = {"E": 1e5, "unit_weight": 100.0, "c": 100.0, "pressure": 100.0, "force": 1e3, "kn": 1e5}


def _warn_implausible_units(scene):
    """Warn (never refuse) where a value looks like kN, kPa or kN/m^3 instead of N, Pa, N/m^3."""

    def warn(what, value, unit, key):
        size = abs(value) if key in ("force", "pressure") else value  # a negative modulus is the validator's
        if 0.0 < size < _PLAUSIBLE_MIN[key]:
            warnings.warn(
                f"{what} = {value:g} {unit} looks small for SI units (was it given in k{unit}?); "
                "the scene uses N, Pa, N/m^3",
                UserWarning,
                stacklevel=3,
            )

    for i, lay in enumerate(scene.layers):
        warn(f"layers[{i}].E", lay.E, "Pa", "E")
        warn(f"layers[{i}].unit_weight", lay.unit_weight, "N/m^3", "unit_weight")
        if lay.c is not None:
            warn(f"layers[{i}].c", lay.c, "Pa", "c")
    warn("surcharge", scene.surcharge, "Pa", "pressure")
    for c in (
        [scene.contact] if isinstance(scene.contact, Contact) else [s.contact for s in scene.contact or []]
    ):
        warn("contact.kn", c.kn, "Pa/m", "kn")
    for load in scene._all_loads():
        for label, value, unit, kind in load.magnitudes():
            warn(label, value, unit, kind)
