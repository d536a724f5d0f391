"""What a scene's limit problem and a site's share (:func:`ssi.capacity.problem.limit_problem` is the one
entry): the materials (:func:`layer_material`), the interfaces (:func:`contact_interface`,
:func:`footing_interface`), the loads of the phases summed into each footing's forces and the ground
pressures through each load's own ``limit_action`` (:func:`collect_loads`), and the boundary of every ground
segment with the :class:`LimitProblem` (:func:`assemble`) of the data a geometry gives (:class:`Parts`)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..core.geometry import Geometry
from ..limit import Boundary, Interface, Material, site_from_geometry
from ..limit.geometry import Site
from .action import FootingFrame, LimitAction

__all__ = ["SIDE_SOIL", "LimitProblem", "NotOnBeam", "Parts", "assemble", "collect_loads", "layer_material"]

SIDE_SOIL = ("surcharge", "soil")  # how an embedded strip's side soil enters (README, Embedment)

TOL = 1e-9  # relative: coordinates and moments this small (of the model's size, of F B) count as zero

# the block's sides on vertical rollers (the symmetry boundary of ssi.limit) and its base fixed, as the
# incremental scene's supports; the ground edges are free or under a footing
SUPPORTS = {"bottom": Boundary("fixed"), "left": Boundary("symmetry"), "right": Boundary("symmetry")}


@dataclass
class LimitProblem:
    """A scene or a site as a limit-analysis problem: ``site`` (:class:`ssi.limit.Site`), ``phase`` the name
    of the phase whose loads lambda scales, ``lam_unit`` what lambda is ("N/m": the footing's vertical force
    of a Settlement push; "": a factor of the phase's loads), ``reference`` a description of what lambda
    multiplies, ``singular`` (x, z) [m] points where the stress field is singular (footing and load ends:
    the initial mesh is finest there), ``footing_width`` [m] of the modelled footing (0: none or several)
    and ``symmetric``; ``scene`` the input; ``ref_force`` [N/m] the downward force of the loads lambda
    scales on all footings together (0: none, or a push); ``ref_forces`` [N/m] each footing's own (in the
    order of ``site.footings``; of a symmetric scene the whole footing's; empty for a push) and
    ``footing_spans`` (x0, x1) [m] of each footing (a symmetric scene's whole footing)."""

    site: Site
    phase: str
    lam_unit: str
    reference: str
    singular: list = field(default_factory=list)
    footing_width: float = 0.0
    symmetric: bool = False
    scene: object = None
    ref_force: float = 0.0
    ref_forces: tuple = ()
    footing_spans: tuple = ()


@dataclass
class Parts:
    """What a geometry (a Scene's block, a Site's polygon) gives :func:`assemble`: the cells
    (``geometry``, its regions indexing ``materials``), the ``footings`` with the ground ``spans`` (x0, x1)
    [m] their segments lie strictly inside, the trench ``walls`` {footing: (base level z [m], the wall's
    Interface or None: free)}, ``free_wall(pa, pb)`` the Boundary of a free wall, the ground pressures
    (x0, x1, q [Pa]) held (``pressures_dead``) and scaled (``pressures_ref``), ``dead_uniform`` [Pa] on all
    the ground beside the footings (a surcharge), the model's ``width`` [m] and what the LimitProblem
    reports (``phase``, ``lam_unit``, ``reference``, ``singular``, ``footing_width``, ``symmetric``,
    ``ref_forces``, ``footing_spans``)."""

    geometry: Geometry
    materials: tuple
    footings: tuple
    spans: list
    walls: dict
    free_wall: Callable
    pressures_dead: list
    pressures_ref: list
    dead_uniform: float
    width: float
    phase: str
    lam_unit: str
    reference: str
    singular: list
    footing_width: float
    symmetric: bool
    ref_forces: tuple
    footing_spans: tuple


def layer_material(i: int, layer, gamma: float, owner: str = "Scene", name: str | None = None) -> Material:
    """The rigid-plastic Mohr--Coulomb :class:`ssi.limit.Material` of ``layer`` (``owner``.layers[i], or
    ``name`` if given: a site's lens) with the body-force unit weight ``gamma`` [N/m^3]. An elastic layer
    (``c=None``) never yields in the incremental model, so its limit-analysis image is a region that never
    yields either (``Material.rigid_body``, as PLAXIS's linear-elastic cluster): the bracket is then the
    collapse load of the model as given. Refused: an effective-stress undrained layer."""
    name = f"{owner}.layers[{i}]" if name is None else name
    if layer.c is None:
        return Material.rigid_body(gamma=float(gamma))
    if layer.drainage != "drained":
        raise ValueError(
            f"{name}.drainage={layer.drainage!r}: an effective-stress undrained layer's strength depends on "
            "the pore pressure of the loading path, which limit analysis does not represent; use "
            "SoilLayer.undrained (total stress, phi = 0, c = s_u) for its undrained capacity"
        )
    try:
        return Material(float(layer.c), float(layer.phi_deg), gamma=float(gamma), psi_deg=layer.psi_deg)
    except ValueError as err:
        raise ValueError(f"{name}: {err}") from None


def refuse_strengthless(materials, what: str) -> None:
    """Refuse a problem in which no soil can yield (every layer elastic): it has no collapse load to bracket,
    whatever its loads."""
    if all(m.rigid for m in materials):
        raise ValueError(
            f"every layer of the {what} is elastic (c=None): nothing in it can yield, so it has no collapse "
            "load; give the layers that may fail c and phi_deg"
        )


def footing_interface(foundation, laws: list, what: str) -> Interface:
    """The base's :class:`ssi.limit.Interface`: a rigid footing's ``rough`` or smooth base, else the one
    contact law of ``laws`` (the distinct Contacts under the strip; ``what`` names them in errors)."""
    if foundation.rigid:
        return Interface("rough" if foundation.rough else "smooth")
    if len(laws) > 1:
        raise ValueError(
            f"{what}: contact segments with different laws are not represented by ssi.limit (one "
            "interface per footing); give one Contact"
        )
    if not laws:
        raise ValueError(f"{what}: a plate Foundation needs a Contact")
    return contact_interface(laws[0], what)


def contact_interface(contact, what: str) -> Interface:
    """The :class:`ssi.limit.Interface` of a Contact (``what`` names it in errors): bonded rough (smooth
    without shear stiffness), else Coulomb with its c, phi, psi and tension cut-off."""
    if contact.phi_deg is None and contact.kt == 0.0:
        # bonded without shear stiffness: it carries no shear and never opens, the smooth interface
        # (chapter 12's contact; the incremental scene refuses a horizontal load on it, as this does)
        return Interface("smooth")
    if contact.phi_deg is None or math.isinf(contact.c):
        return Interface("rough")
    if contact.phi_deg > 60.0:
        raise ValueError(f"{what}.phi_deg={contact.phi_deg!r}: ssi.limit takes 0 <= phi_deg <= 60")
    t = None if contact.sig_t is None else float(contact.sig_t)  # the contact's tension cut-off
    return Interface(
        "coulomb", c=float(contact.c), phi_deg=float(contact.phi_deg), psi_deg=contact.psi_deg, tension=t
    )


def frame_of(foundation, water_table: float | None, gamma_w: float) -> FootingFrame:
    """The :class:`FootingFrame` of a plate Foundation or a rigid footing under free water standing
    ``-water_table`` [m] above the ground (None or >= 0: none on the strip)."""
    if foundation.rigid:
        return FootingFrame(foundation.x0, foundation.x1)
    t = foundation.section.thickness
    submerged = 0.0 if water_table is None else min(max(-float(water_table), 0.0), t)
    return FootingFrame(
        foundation.x0, foundation.x1, -float(foundation.section.z_bottom), t, gamma_w * submerged
    )


class NotOnBeam(ValueError):
    """A load the beam strip does not represent (by default the strip is then taken rigid)."""


@dataclass
class FootingLoads:
    """The loads of the phases on one footing: ``ref`` / ``dead`` (Fx, Fz) [N/m] and ``m_ref`` / ``m_dead``
    [N m/m] about the centre of its base, lambda's and the held ones (the dead at their factors);
    ``settles``: the scaled phase pushes it down; ``beam``: {"ref", "dead": [(x, Fx, Fz, C)], "p_ref",
    "p_dead": Pa} its loads as a beam strip carries them, or the :class:`NotOnBeam` of the first load a
    beam does not represent (``beam_error``)."""

    ref: np.ndarray = field(default_factory=lambda: np.zeros(2))
    dead: np.ndarray = field(default_factory=lambda: np.zeros(2))
    m_ref: float = 0.0
    m_dead: float = 0.0
    settles: bool = False
    beam: dict = field(default_factory=lambda: {"ref": [], "dead": [], "p_ref": 0.0, "p_dead": 0.0})
    beam_error: NotOnBeam | None = None


def footing_forces(actions, first_phase: bool, foundation, what: str):
    """(Fx, Fz [N/m], moment [N m/m] counter-clockwise about the centre of the base, settles?) of the
    ``actions`` [(index, LimitAction)] on a footing (a plate strip's self weight with the first phase)."""
    fx = fz = m = 0.0
    settle = False
    for i, act in actions:
        if act.refused is not None:
            raise ValueError(f"{what}[{i}]: {act.refused}")
        dx, dz, dm = act.force
        fx += dx
        fz += dz
        m += dm
        settle = settle or act.settles
    if first_phase and not foundation.rigid and foundation.self_weight:
        fz -= foundation.self_weight * (foundation.x1 - foundation.x0)
    return fx, fz, m, settle


def beam_loads(actions, first_phase: bool, foundation, what: str) -> tuple[list, float]:
    """A beam strip's loads of ``actions`` [(index, LimitAction)]: point loads [(x [m], Fx, Fz [N/m], C
    [N m/m])] at the base and the uniform downward pressure [Pa]; :class:`NotOnBeam` for the first action
    a beam does not represent."""
    points, p = [], 0.0
    for i, act in actions:
        if act.not_on_beam is not None:
            raise NotOnBeam(f"{what}[{i}]: {act.not_on_beam}")
        points += list(act.beam_points)
        if act.beam_pressure:
            p += act.beam_pressure
    if first_phase and foundation.self_weight:
        p += foundation.self_weight
    return points, p


def collect_loads(
    phases, k: int, block, footings, clip_tol: float, what_of, with_beam: bool, no_ground: str | None = None
):
    """The loads of ``phases`` up to the scaled one ``phases[k]`` (the earlier ones held at their factors
    at its end): ground pressures clipped to ``block`` (x_left, x_right) [m], those shorter than
    ``clip_tol`` [m] dropped, as (pressures_dead, pressures_ref), and per footing of ``footings``
    [(foundation, frame)] its :class:`FootingLoads`. Every other load acts on the only footing, or with
    several on the one under its column. ``what_of(phase)`` names a phase's loads in errors;
    ``with_beam``: also the beam strip's loads; ``no_ground``: why a ground pressure is refused (None:
    taken)."""
    factors: dict = {}
    for ph in phases[: k + 1]:
        factors[ph.name] = 1.0
        factors.update(ph.factors)
    ref_phase = phases[k]
    held = [(factors[ph.name], ph, j == 0) for j, ph in enumerate(phases[:k]) if factors[ph.name] != 0.0]
    out = [FootingLoads() for _ in footings]
    p_dead: list = []
    p_ref: list = []
    xl, xr = block
    for factor, ph, first in held + [(1.0, ref_phase, k == 0)]:
        is_ref = ph is ref_phase
        what = what_of(ph)
        mine = [[] for _ in footings]  # (index, load) on each footing
        for i, ld in enumerate(ph.loads):
            act = ld.limit_action(None)
            if act.ground is not None:
                if no_ground is not None:
                    raise ValueError(f"{what}[{i}]: {no_ground}")
                a, b = max(act.ground[0], xl), min(act.ground[1], xr)
                if b - a > clip_tol:
                    (p_ref if is_ref else p_dead).append((a, b, factor * act.ground[2]))
                continue
            if ld.drives == "vertical" and not is_ref:
                raise ValueError(
                    f"{what}[{i}]: a Settlement among the held loads (phase {ph.name!r} before the scaled "
                    f"phase {ref_phase.name!r}) prescribes a displacement, not a force: ssi.limit cannot "
                    "hold it"
                )
            if len(footings) == 1:
                mine[0].append((i, ld))
                continue
            xs = [x for x, _ in ld.columns()]
            on = [j for j, (f, _) in enumerate(footings) if xs and f.x0 - 1e-9 <= xs[0] <= f.x1 + 1e-9]
            if footings and not on:
                raise ValueError(f"{what}[{i}]: {ld!r} is on none of the strips: ssi.limit cannot place it")
            if on:
                mine[on[0]].append((i, ld))
        for j, (f, frame) in enumerate(footings):
            loads = mine[j]
            if f.rigid and any(ld.drives != "vertical" for _, ld in loads):
                bad = next(ld for _, ld in loads if ld.drives != "vertical")
                raise ValueError(
                    f"{what}: a {type(bad).__name__} on a RigidFooting (it takes a Settlement push only; a "
                    "force load needs a plate Foundation)"
                )
            acts = [(i, ld.limit_action(frame)) for i, ld in loads]
            fx, fz, m, settle = footing_forces(acts, first, f, what)
            fl = out[j]
            if with_beam and fl.beam_error is None:
                try:
                    pts, p = beam_loads(acts, first, f, what)
                except NotOnBeam as err:
                    fl.beam_error = err
                else:
                    key = "ref" if is_ref else "dead"
                    fl.beam[key] += [(x, factor * a, factor * b, factor * c) for x, a, b, c in pts]
                    fl.beam["p_" + key] += factor * p
            if abs(m) <= TOL * (abs(fz) * (f.x1 - f.x0) + abs(fx) * (f.x1 - f.x0) + 1.0):
                m = 0.0  # round-off of loads symmetric about the centre
            if is_ref:
                fl.ref += (fx, fz)
                fl.m_ref += m
                fl.settles = settle
            else:
                fl.dead += (factor * fx, factor * fz)
                fl.m_dead += factor * m
    return p_dead, p_ref, out


def ground_pressure(items, x: float) -> float:
    """The sum of the pressures (a, b, q) acting at ``x`` (ends included, to 1e-12 m)."""
    return sum(q for a, b, q in items if a - 1e-12 <= x <= b + 1e-12)


def describe(actions: list[LimitAction]) -> str:
    """The texts of the actions that say something, joined."""
    return ", ".join(a.text for a in actions if a.text)


def assemble(parts: Parts, scene) -> LimitProblem:
    """The one boundary rule of every ground segment and the :class:`LimitProblem` of ``parts``: the
    supports; a trench wall of a footing (vertical, at one of its ends, above its base) on its interface
    or free; the ground strictly inside a footing's span under it; any other ground free, under the held
    pressures and the uniform dead pressure, lambda times the scaled ones (a scaled pressure on sloping
    ground is refused)."""
    width = parts.width
    tol = TOL * width

    def boundary(tag, pa, pb):
        if tag in SUPPORTS:
            return SUPPORTS[tag]
        xm = 0.5 * (pa[0] + pb[0])
        if abs(pb[0] - pa[0]) <= tol:  # a vertical ground segment: a trench wall, or a step
            for j, (level, side) in parts.walls.items():
                on_wall = any(abs(xm - x) <= tol for x in parts.spans[j])
                if on_wall and min(pa[1], pb[1]) >= level - tol:
                    return (
                        parts.free_wall(pa, pb)
                        if side is None
                        else Boundary("footing", footing=j, interface=side)
                    )
        for j, (a, b) in enumerate(parts.spans):
            if a < xm < b:
                return Boundary("footing", footing=j)
        q = ground_pressure(parts.pressures_ref, xm)
        if q and abs(pb[1] - pa[1]) > tol:
            raise ValueError(
                f"Site.loads: a SurfacePressure on sloping ground at x = {xm:g} m (a vertical load per "
                "horizontal metre there is not a normal pressure): not represented by ssi.limit"
            )
        q_dead = ground_pressure(parts.pressures_dead, xm) + parts.dead_uniform
        return Boundary("free", pressure_dead=q_dead, pressure_ref=q)

    site = site_from_geometry(parts.geometry, parts.materials, boundary, parts.footings)
    forces = tuple(float(f) for f in parts.ref_forces)
    return LimitProblem(
        site,
        parts.phase,
        parts.lam_unit,
        parts.reference,
        parts.singular,
        parts.footing_width,
        parts.symmetric,
        scene,
        float(sum(forces)) if not parts.lam_unit else 0.0,
        forces,
        tuple(parts.footing_spans),
    )
