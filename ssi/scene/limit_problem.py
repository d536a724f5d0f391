"""A :class:`~ssi.scene.Scene` or a :class:`~ssi.scene.site.Site` as a limit-analysis problem
(:mod:`ssi.limit`): what its collapse load factor lambda scales and what is held (the bracket itself:
:mod:`ssi.scene.capacity`).

How the scene maps (anything else raises a ValueError naming the part):

- the block (``width`` x ``depth``, the half x >= 0 of a ``symmetric`` scene, the axis a symmetry roller),
  its sides on vertical rollers and its base fixed, as the incremental scene's supports; cut into cells
  at every layer boundary, the water table, the foundation's ends and every load's ends: one
  :class:`ssi.core.geometry.Geometry`, made a :class:`ssi.limit.Site` by
  :func:`ssi.limit.site_from_geometry`;
- each layer a rigid-plastic Mohr--Coulomb :class:`ssi.limit.Material` (c, phi, psi), with its unit weight
  above the water table and its buoyant unit weight gamma_sat - gamma_w below it (effective stress under
  hydrostatic pore pressure, which then does no work in any mechanism); an undrained layer
  (:meth:`SoilLayer.undrained`, phi = 0) is Tresca with c = s_u. Refused: an elastic layer (``c=None``,
  no strength), an effective-stress undrained layer (``drainage="undrained_A"``: its strength depends on
  the pore pressure the loading path generates, which limit analysis does not know);
- the foundation is a **rigid body**: a :class:`RigidFooting` (and any footing pushed by a Settlement,
  which prescribes a uniform settlement) translates only; a plate :class:`Foundation` of a full
  (non-symmetric) scene also rotates about the centre of its base (held where the whole problem is its
  own mirror image about that centre: the same exact load, a tighter bracket), so eccentric loads and a
  column's moment M are carried (the moment about that point: M - N (x - x_c) - H e, e = -section.z_bottom the
  plate nodes' height above the base); held loads with a moment before a Settlement push are refused;
- a plate strip with an RC section is by default (``strip=None`` or "beam") a **beam with plastic hinges**
  (:class:`ssi.limit.Beam`, :mod:`ssi.scene.limit_strip`): M_p sagging and hogging its section's M_Rd at
  N = 0, the columns point loads at base points (H at the base plus its couple -H e), self weight, strip
  weight, surcharge and a uniform StripLoad a uniform pressure. A brittle
  section (below minimum reinforcement) forms no hinge: refused as a beam, taken rigid by default with a
  warning, as is a load a beam does not represent (a StripLoad not uniform over the whole strip); an
  elastic section has no strength and stays rigid. ``strip="rigid"`` ignores the strip's bending (the
  stronger assumption: for a slender or lightly reinforced strip the beam's own mechanism may govern);
- the base: a RigidFooting ``rough`` / smooth; a plate strip's :class:`Contact` bonded (``phi_deg=None``)
  is rough (smooth if its ``kt`` is 0: no shear, no opening), else Coulomb with c_i, phi_i (its psi_deg
  enters the Davis bracket) and its tension cut-off ``sig_t`` (None: the Coulomb joint's own apex
  c / tan phi); refused: contact segments with different laws;
- loads: :class:`ColumnLoad` N, H, M, :class:`StripLoad`, :class:`StripWeight` (less its
  buoyancy in free water) and the strip's ``self_weight`` (a load of the first phase, as in the
  incremental scene) on the footing; :class:`SurfacePressure` and the ``surcharge`` on the ground beside
  it (a plate strip carries the surcharge over its own width, as the incremental scene's initial state
  does). Refused: excavations, drainage switches, a Settlement among the dead loads.

**Embedment** (``Scene.embedment`` D: the strip's base D below the ground in a trench, the side soil the
layers above depth D), by ``side_soil``:

- "surcharge" (default): the side soil is replaced by its overburden, the geostatic vertical stress of the
  base level p_0 = surcharge + sum gamma_i t_i, as a dead pressure on the ground beside the strip at the
  base level; the model is the block below the base, whose ground is then level, and the strip's sides
  touch nothing. Why this one: it is the smallest model that is rigorous for every embedded scene and exact
  for chapter 12's. Its lower bound is a lower bound of the scene with the side soil: a statically
  admissible field of it extends above the base by the geostatic state (sigma_zz = sigma_v, sigma_xx =
  K0 sigma_v, which also carries the walls' geostatic stress; admissible where K0 lies between the active
  and passive values, K0 = 1 always), so the side soil's strength can only add. Its upper bound is that of
  a strengthless backfill (Terzaghi's q = gamma D), the scene chapter 12 compares with gamma D N_q
  (its soft elastic backfill, whose strength is not used here and is therefore accepted; an incremental
  limit may exceed the upper bound by what the backfill's shear carries, chapter 12's trend with E_b;
  a backfill with c and phi gets a warning saying that the upper bound is not its ceiling). A side contact
  is ignored (the walls' geostatic traction, normal, is admissible for any Coulomb contact: the lower
  bound stays rigorous). The strip carries p_0 B as a dead load (the incremental scene's initial state);
  the footing's centre is the centre of its base (x_c, -D). Refused: a water table above the base (pore
  pressure on the base and the walls), a SurfacePressure on the ground (its spread through a strengthless
  layer to the base level is unknown);
- "soil": the side soil modelled (its layers with their strength and weight), the trench cut out of the
  cells; without a ``side_contact`` the trench walls touch nothing and carry the geostatic horizontal
  stress -sigma_xx0(z) as a dead pressure linear in z within each layer (:class:`ssi.limit.Boundary`
  ``pressure_dead_grad``), as the incremental scene's walls do. With a ``side_contact`` the walls are
  segments of the strip's footing on that contact (:class:`ssi.limit.Boundary` ``interface``: Coulomb
  c_i, phi_i, its psi_i in the Davis bracket, tension cut-off ``sig_t``; bonded: rough; bonded without
  shear stiffness: smooth), moving with the rigid strip, as the incremental scene's side interfaces move
  with its end sections; the walls' earth pressure on the strip is then part of the footing's equilibrium
  (at rest it is equal and opposite on the two walls, which is why no dead load replaces it). Its
  capacity is at least the surcharge model's (the argument above), and at least the free walls' (their
  geostatic traction is admissible for any contact that takes compression). Refused: an elastic side
  layer (no strength); a beam strip with a side contact (its end sections would carry the walls; taken
  rigid by default, with a warning).

A :class:`~ssi.scene.site.Site`'s embedded strip is always modelled with its side soil (the site's own
geometry; ``side_soil`` None or "soil"): its walls are free faces without a dead pressure (the incremental
site's trench is open while gravity loads it) or on the strip's ``side_contact`` as above.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..core.geometry import from_cells
from ..limit import Beam, Boundary, Footing, Interface, Material, site_from_geometry
from ..limit.geometry import Site
from ..materials.soil_laws import SoilLayer
from .limit_strip import NotOnBeam, beam_loads_of, beam_mode, strip_beam_interaction
from .loads import ColumnLoad, Settlement, StripLoad, StripWeight, SurfacePressure
from .parts import Contact, ContactSegment, Foundation, Phase, RigidFooting

__all__ = ["SIDE_SOIL", "LimitProblem", "limit_problem"]

SIDE_SOIL = ("surcharge", "soil")  # how an embedded strip's side soil enters (module docstring, Embedment)

_TOL = 1e-9  # relative: coordinates and moments this small (of the scene's size, of F B) count as zero


@dataclass
class LimitProblem:
    """A scene as a limit-analysis problem: ``site`` (:class:`ssi.limit.Site`), ``phase`` the name of the
    phase whose loads lambda scales, ``lam_unit`` what lambda is ("N/m": the footing's vertical force of a
    Settlement push; "": a factor of the phase's loads), ``reference`` a description of what lambda
    multiplies, ``singular`` (x, z) [m] points where the stress field is singular (footing and load ends:
    the initial mesh is finest there), ``footing_width`` [m] of the modelled footing (0: none) and
    ``symmetric``."""

    site: Site
    phase: str
    lam_unit: str
    reference: str
    singular: list = field(default_factory=list)
    footing_width: float = 0.0
    symmetric: bool = False
    scene: object = None
    ref_force: float = 0.0  # the whole footing's downward force at lambda = 1 [N/m] (0: none)


# the block's sides on vertical rollers (the symmetry boundary of ssi.limit) and its base fixed, as the
# incremental scene's supports; the ground edges are free or under a footing
_BLOCK_SUPPORTS = {"bottom": Boundary("fixed"), "left": Boundary("symmetry"), "right": Boundary("symmetry")}


def _ground_pressure(items, x: float) -> float:
    """The sum of the pressures (a, b, q) acting at ``x`` (ends included, to 1e-12 m)."""
    return sum(q for a, b, q in items if a - 1e-12 <= x <= b + 1e-12)


def _phases(scene) -> list:
    return ([Phase("loads", tuple(scene.loads))] if scene.loads else []) + list(scene.phases)


def _layer_material(i: int, layer, gamma: float) -> Material:
    name = f"Scene.layers[{i}]"
    if layer.c is None:
        raise ValueError(
            f"{name} is elastic (c=None): limit analysis needs every layer's strength; give c and phi_deg"
        )
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


def _interface(scene) -> Interface:
    f = scene.foundation
    if isinstance(f, RigidFooting):
        return Interface("rough" if f.rough else "smooth")
    contact = scene.contact
    if isinstance(contact, list | tuple):
        laws = {seg.contact for seg in contact if isinstance(seg, ContactSegment)}
        if len(laws) != 1:
            raise ValueError(
                "Scene.contact: contact segments with different laws are not represented by ssi.limit (one "
                "interface per footing); give one Contact"
            )
        contact = laws.pop()
    if not isinstance(contact, Contact):
        raise ValueError("Scene.contact: a plate Foundation needs a Contact")
    return _contact_interface(contact, "Scene.contact")


def _contact_interface(contact: Contact, what: str) -> Interface:
    """The :class:`ssi.limit.Interface` of a :class:`Contact` (``what`` names it in errors): bonded rough
    (smooth without shear stiffness), else Coulomb with its c, phi, psi and tension cut-off."""
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


def _footing_forces(scene, loads, first_phase: bool, x0: float, x1: float, what: str):
    """(Fx, Fz [N/m], moment [N m/m] counter-clockwise about the centre of the base (x_c, base level),
    settlement?) of ``loads`` on the footing. A column's H acts at the plate's nodes, the section's
    ``-z_bottom`` above the base (as in the incremental scene's plate kinematics)."""
    fx = fz = m = 0.0
    settle = False
    xc = 0.5 * (x0 + x1)
    f = scene.foundation
    for i, ld in enumerate(loads):
        if isinstance(ld, ColumnLoad):
            lever = -float(f.section.z_bottom) if isinstance(f, Foundation) else 0.0
            fx += ld.H
            fz -= ld.N
            m += ld.M - ld.N * (ld.x - xc) - ld.H * lever
        elif isinstance(ld, StripLoad):
            a = f.x0 if ld.x0 is None else ld.x0
            b = f.x1 if ld.x1 is None else ld.x1
            q0, q1 = ld.q, ld.q if ld.q_end is None else ld.q_end
            r = 0.5 * (q0 + q1) * (b - a)
            xr = a + (b - a) * (q0 + 2 * q1) / (3 * (q0 + q1)) if q0 + q1 != 0.0 else 0.5 * (a + b)
            fz -= r
            m -= r * (xr - xc)
        elif isinstance(ld, StripWeight):
            t = f.section.thickness
            wt = scene.water_table
            submerged = 0.0 if wt is None else min(max(-float(wt), 0.0), t)
            fz -= (ld.unit_weight * t - scene.gamma_w * submerged) * (f.x1 - f.x0)
        elif isinstance(ld, Settlement):
            if ld.x is not None:
                raise ValueError(
                    f"{what}[{i}]: Settlement at the columns x={ld.x!r} pushes a flexible strip; ssi.limit "
                    "pushes the footing as a rigid body: give Settlement(w) with x=None"
                )
            settle = True
    if first_phase and isinstance(f, Foundation) and f.self_weight:
        fz -= f.self_weight * (f.x1 - f.x0)
    return fx, fz, m, settle


def _mirror_symmetric(f, xl, xr, fref, fdead, mref, mdead, p_dead, p_ref, width) -> bool:
    """Whether the scene is its own mirror image about the foundation's centre: the block centred on it,
    the ground pressures mirrored, no moment and no horizontal force on the foundation (the layers and the
    water table are level)."""
    xc, tol = 0.5 * (f.x0 + f.x1), _TOL * width
    if abs(0.5 * (xl + xr) - xc) > tol or mref or mdead or fref[0] or fdead[0]:
        return False
    for items in (p_dead, p_ref):
        mirrored = sorted((round(2 * xc - b, 9), round(2 * xc - a, 9), q) for a, b, q in items)
        if mirrored != sorted((round(a, 9), round(b, 9), q) for a, b, q in items):
            return False
    return True


def limit_problem(
    scene,
    phase: str | None = None,
    strip: str | None = None,
    side_soil: str | None = None,
    unloaded: bool = False,
) -> LimitProblem:
    """The limit-analysis problem of ``scene`` with lambda scaling the loads of ``phase`` (module
    docstring; None: the last phase). ``strip``: "rigid" or "beam" (a plate Foundation's strip as a beam
    with plastic hinges of M_p at N = 0, :mod:`ssi.scene.limit_strip`) or "beam_mn" (the same beam, its
    hinges' capacity the section's M-N polygon, :func:`~ssi.scene.limit_strip.strip_beam_interaction`:
    safe where the beam's axial force lowers M_p; on a rough base its hinges cannot extend and the upper
    bound is then loose); None: "beam" for an RC section that is not
    brittle under force loads a beam represents, else "rigid" (with a warning for a brittle section or such
    a load). ``side_soil``: how an embedded strip's side soil enters, "surcharge" (its overburden on the
    ground at the base level) or "soil" (modelled; module docstring, *Embedment*); None: "surcharge" for a
    Scene, "soil" for a Site (the only model of a site's trench). ``unloaded``: a Site with no loads is
    accepted (its factor of safety under its own weight, :func:`ssi.scene.capacity.safety_factor`), else
    refused: nothing to scale. Raises ValueError naming
    whatever the scene holds that :mod:`ssi.limit` cannot represent."""
    if strip is not None and strip not in ("rigid", "beam", "beam_mn"):
        raise ValueError(f"strip must be 'rigid', 'beam', 'beam_mn' or None, got {strip!r}")
    if side_soil is not None and side_soil not in SIDE_SOIL:
        raise ValueError(f"side_soil must be one of {SIDE_SOIL} or None, got {side_soil!r}")
    with_mn = strip == "beam_mn"  # a beam whose hinges' capacity is the section's M-N polygon
    strip = "beam" if with_mn else strip
    kind = getattr(scene, "kind", None)  # any object may come in: a Scene or a Site says which it is
    if kind not in ("scene", "site"):
        raise TypeError(
            f"scene must be an ssi.scene.Scene or ssi.scene.site.Site, got {type(scene).__name__}"
        )
    if kind == "site":
        if phase is not None:
            raise ValueError(f"phase={phase!r}: a Site has one phase (its loads); give phase=None")
        if strip == "beam":
            raise ValueError("strip='beam': a Site's strips are rigid in ssi.limit (a beam strip: a Scene)")
        if side_soil == "surcharge" and scene.embedded():
            raise ValueError(
                "side_soil='surcharge': a Site's embedded strip stands in its trench with the side soil "
                "modelled (the site's geometry, the walls free faces or on its side_contact); give "
                "side_soil='soil' or None"
            )
        return _site_problem(scene, unloaded)
    side_soil = "surcharge" if side_soil is None else side_soil
    phases = _phases(scene)
    if not phases:
        raise ValueError("the scene has no loads (Scene.loads and Scene.phases are empty): nothing to scale")
    names = [ph.name for ph in phases]
    if phase is None:
        k = len(phases) - 1
    elif phase in names:
        k = names.index(phase)
    else:
        raise ValueError(f"phase={phase!r} is not a phase of the scene; its phases are {names}")
    d_base = float(scene.embedment)  # the strip's base below the ground [m]
    if d_base and scene.water_table is not None and float(scene.water_table) < d_base - _TOL * scene.depth:
        raise ValueError(
            f"Scene.water_table={scene.water_table!r} m lies above the embedded strip's base "
            f"(embedment={d_base!r} m): the pore pressure on the base and the trench walls is not "
            "represented by ssi.limit; give a water table at or below the base level"
        )
    surcharge_model = bool(d_base) and side_soil == "surcharge"
    side_itf = None  # the trench walls' contact with the strip (side_soil="soil" and a side_contact)
    if d_base and side_soil == "soil" and scene.side_contact is not None:
        side_itf = _contact_interface(scene.side_contact, "Scene.side_contact")
    for ph in phases[: k + 1]:
        if ph.excavate:
            raise ValueError(f"Phase({ph.name!r}).excavate: excavations are not represented by ssi.limit")
        if ph.drainage:
            raise ValueError(
                f"Phase({ph.name!r}).drainage: drainage switches are not represented by ssi.limit"
            )
    factors: dict = {}
    for ph in phases[: k + 1]:
        factors[ph.name] = 1.0
        factors.update(ph.factors)
    dead = [(factors[ph.name], ph, j == 0) for j, ph in enumerate(phases[:k]) if factors[ph.name] != 0.0]
    ref_phase = phases[k]

    f = scene.foundation
    xl, xr = scene._block()
    width = xr - xl
    fx0, fx1 = scene._footprint() if f is not None else (None, None)
    # ---- ground pressures and the footing's forces, dead and reference
    pressures_dead: list = []  # (x0, x1, q)
    pressures_ref: list = []
    fdead = np.zeros(2)
    fref = np.zeros(2)
    mdead = mref = 0.0  # moments about the centre of the base [N m/m], counter-clockwise
    settle_ref = False
    mp = beam_mode(scene, strip)  # (mp_sag, mp_hog) [N m/m] of a beam strip, None: rigid
    if mp is not None and side_itf is not None:
        msg = (
            "Scene.side_contact with side_soil='soil' on a beam strip: the walls' contact moves with the "
            "strip's end sections, which ssi.limit's beam (hinged along its base) does not represent"
        )
        if strip == "beam":
            raise ValueError(msg + "; give strip='rigid'")
        warnings.warn(msg + ": the strip is taken rigid", stacklevel=2)
        mp = None
    beam_loads = {"ref": [], "dead": [], "p_ref": 0.0, "p_dead": 0.0}  # point loads (x, Fx, Fz, C), pressures
    for factor, ph, first in dead + [(1.0, ref_phase, k == 0)]:
        is_ref = ph is ref_phase
        what = f"Phase({ph.name!r}).loads" if ph.name != "loads" or scene.phases else "Scene.loads"
        for i, ld in enumerate(ph.loads):
            if isinstance(ld, SurfacePressure):
                if surcharge_model:
                    raise ValueError(
                        f"{what}[{i}]: a SurfacePressure on the ground of an embedded scene with "
                        "side_soil='surcharge' (the side soil is replaced by its overburden at the base "
                        "level, where the spread of a local load through it is unknown); give "
                        "side_soil='soil' or the uniform Scene.surcharge"
                    )
                a, b = max(ld.x0, xl), min(ld.x1, xr)
                if b - a > _TOL * width:
                    (pressures_ref if is_ref else pressures_dead).append((a, b, factor * ld.q))
            elif isinstance(ld, Settlement) and not is_ref:
                raise ValueError(
                    f"{what}[{i}]: a Settlement among the held loads (phase {ph.name!r} before the scaled "
                    f"phase {ref_phase.name!r}) prescribes a displacement, not a force: ssi.limit cannot "
                    "hold it"
                )
        on_footing = [ld for ld in ph.loads if not isinstance(ld, SurfacePressure)]
        if f is None:
            continue
        if isinstance(f, RigidFooting) and any(not isinstance(ld, Settlement) for ld in on_footing):
            bad = next(ld for ld in on_footing if not isinstance(ld, Settlement))
            raise ValueError(
                f"{what}: a {type(bad).__name__} on a RigidFooting (it takes a Settlement push only; a force "
                "load needs a plate Foundation)"
            )
        fx, fz, m, settle = _footing_forces(scene, on_footing, first, f.x0, f.x1, what)
        if mp is not None:
            try:
                pts, p = beam_loads_of(scene, on_footing, first, what)
            except NotOnBeam as err:
                if strip == "beam":
                    raise
                warnings.warn(f"{err}: the strip is taken rigid", stacklevel=2)
                mp = None
        if mp is not None:
            key = "ref" if is_ref else "dead"
            beam_loads[key] += [(x, factor * a, factor * b, factor * c) for x, a, b, c in pts]
            beam_loads["p_" + key] += factor * p
        if abs(m) <= _TOL * (abs(fz) * (f.x1 - f.x0) + abs(fx) * (f.x1 - f.x0) + 1.0):
            m = 0.0  # round-off of loads symmetric about the centre
        if is_ref:
            fref += (fx, fz)
            mref += m
            settle_ref = settle
        else:
            fdead += (factor * fx, factor * fz)
            mdead += factor * m
    if settle_ref and (np.any(fref != 0.0) or pressures_ref):
        raise ValueError(
            f"Phase {ref_phase.name!r} mixes a Settlement with force loads: lambda scales either the loads "
            "or the pushed footing's force, not both"
        )
    # the geostatic vertical stress of the base level [Pa]: the surcharge, plus the overburden of an
    # embedded base
    p_base = -float(scene._geostatic(np.array([-d_base]))[0, 1]) if d_base else float(scene.surcharge)
    if isinstance(f, Foundation) and scene._has_geostatic_stress():
        fdead[1] -= p_base * (f.x1 - f.x0)  # the strip carries it over its width, as in the incremental scene
        beam_loads["p_dead"] += p_base
    if mp is not None and settle_ref:
        if strip == "beam":
            raise ValueError(
                "strip='beam' with a Settlement push: the push prescribes a uniform settlement of the strip, "
                "so it cannot bend; give strip='rigid' or force loads"
            )
        mp = None
    half = 0.5 if scene.symmetric else 1.0  # a symmetric scene's footing: the modelled half's share
    if settle_ref:
        fref = np.array([0.0, -half])  # lambda = the whole footing's vertical force [N/m]
    if f is None and (np.any(fref) or settle_ref):
        raise ValueError("loads on a foundation need Scene.foundation")
    if not (np.any(fref != 0.0) or any(q for _, _, q in pressures_ref)):
        raise ValueError(f"phase {ref_phase.name!r} has no load ssi.limit can scale (its loads are all zero)")

    # ---- the geometry: columns at every break, cells per (sub-)layer
    xs = {xl, xr}
    for a, b, _ in pressures_dead + pressures_ref:
        xs |= {a, b}
    if f is not None:
        xs |= {fx0, fx1}
    if mp is not None:  # a beam's point loads act at base points
        xs |= {x for x, *_ in beam_loads["ref"] + beam_loads["dead"]}
    xs = sorted(x for x in xs if xl - _TOL * width <= x <= xr + _TOL * width)
    sub = scene._mesh_layers()  # (thickness, layer, unit weight of its body force), split at the water table
    owner = [next(i for i, lay in enumerate(scene.layers) if lay is own) for _, own, _ in sub]
    z_tops = -np.concatenate([[0.0], np.cumsum([t for t, _, _ in sub])])
    n_above = 0  # sub-layers above an embedded base
    if d_base:
        hit = np.flatnonzero(np.abs(z_tops + d_base) <= _TOL * scene.depth)
        if not len(hit):
            raise ValueError(
                f"Scene.embedment={d_base!r} m is not a layer boundary (layer tops at depths "
                f"{[-float(z) for z in z_tops]} m)"
            )
        n_above = int(hit[0])
    first = n_above if surcharge_model else 0  # the surcharge model keeps only the soil below the base
    strong = [owner[r] for r in range(n_above) if sub[r][1].c is not None]
    if surcharge_model and strong:
        warnings.warn(
            f"Scene.layers{sorted(set(strong))} above the embedded base have strength, which "
            "side_soil='surcharge' ignores: the bracket's lower bound is a floor of the scene, its upper "
            "bound the capacity with a strengthless backfill (not a ceiling of this scene); "
            "side_soil='soil' models the side soil",
            stacklevel=2,
        )
    materials = tuple(_layer_material(i, lay, g) for i, (_, lay, g) in zip(owner[first:], sub[first:]))
    z_ground = float(z_tops[first])  # the model's ground: the base level of the surcharge model
    polys, regions = [], []
    for a, b in zip(xs[:-1], xs[1:]):
        in_trench = f is not None and d_base and fx0 - _TOL * width < 0.5 * (a + b) < fx1 + _TOL * width
        for r in range(first, len(sub)):
            zt, zb = z_tops[r], z_tops[r + 1]
            if in_trench and r < n_above:
                continue  # the trench the strip sits in
            polys.append([(a, zb), (b, zb), (b, zt), (a, zt)])
            regions.append(r - first)
    geo = from_cells(polys, regions)

    footings = ()
    if f is not None:
        itf = _interface(scene)
        if isinstance(f, RigidFooting) or scene.symmetric:
            moves = ("z",)  # the scene holds a rigid footing horizontally (rough: u = 0; the axis)
            if fref[0] or fdead[0]:
                raise ValueError("a horizontal load on a RigidFooting or on a symmetric scene's footing")
        elif itf.kind == "smooth":
            moves = ("z",)
        else:
            moves = ("x", "z")
        tilts = isinstance(f, Foundation) and not scene.symmetric and not settle_ref
        symmetric_problem = _mirror_symmetric(
            f, xl, xr, fref, fdead, mref, mdead, pressures_dead, pressures_ref, width
        )
        if tilts and (mp is not None or not symmetric_problem):
            # a plate strip tilts as freely as the incremental scene's: its rotation is free (a Settlement
            # push prescribes a uniform settlement and so holds it). Held where the whole problem is the
            # mirror image of itself about the strip's centre: the exact collapse load is then the same
            # (a tilting mechanism and its mirror image cost the same and their average does not tilt;
            # the dissipation is convex), and the held footing's bracket is tighter on a given mesh
            moves += ("r",)
        elif mref or mdead:
            raise ValueError(
                f"the loads on the foundation have a moment {mref or mdead:g} N m/m about the centre of its "
                f"base x = {0.5 * (f.x0 + f.x1):g} m, but its rotation is held (a Settlement push prescribes "
                "a uniform settlement): not represented by ssi.limit"
            )
        if itf.kind == "smooth" and (fref[0] or fdead[0]):
            raise ValueError("a smooth contact carries no horizontal load (ColumnLoad.H != 0)")
        centre = (0.5 * (f.x0 + f.x1), -d_base)
        forces = (tuple(fref.tolist()), tuple(fdead.tolist()))
        beam = None
        if mp is not None:
            inter = strip_beam_interaction(f.section) if with_mn else ()
            beam = Beam(f.x0, f.x1, mp[0], mp[1], tuple(beam_loads["ref"]), tuple(beam_loads["dead"]),
                        beam_loads["p_ref"], beam_loads["p_dead"], inter)  # fmt: skip
            # the footing's resultants are the beam's loads' (checked: the same loads, summed two ways)
            for which, fo, mo in (("ref", fref, mref), ("dead", fdead, mdead)):
                bx, bz, bm = beam.resultant(which, centre[0])
                scale = abs(fo).sum() * (f.x1 - f.x0) + abs(mo) + 1.0
                if abs(bx - fo[0]) + abs(bz - fo[1]) + abs(bm - mo) / (f.x1 - f.x0) > 1e-9 * scale:
                    raise AssertionError(f"beam loads {(bx, bz, bm)} differ from the footing's {(fo, mo)}")
        footings = (Footing(itf, *forces, moves, centre, float(mref), float(mdead), beam),)

    def boundary(tag, pa, pb):
        if tag in _BLOCK_SUPPORTS:
            return _BLOCK_SUPPORTS[tag]
        xm, zm = 0.5 * (pa + pb)
        if abs(pa[0] - pb[0]) <= _TOL * width:  # a trench wall
            if side_itf is not None:  # in contact with the strip: a footing segment with the side contact
                return Boundary("footing", footing=0, interface=side_itf)
            return _wall_pressure(scene, pa, pb)  # free, under its geostatic horizontal stress
        if f is not None and fx0 < xm < fx1:
            return Boundary("footing", footing=0)
        q_dead = _ground_pressure(pressures_dead, xm) + (p_base if surcharge_model else scene.surcharge)
        return Boundary("free", pressure_dead=q_dead, pressure_ref=_ground_pressure(pressures_ref, xm))

    site = site_from_geometry(geo, materials, boundary, footings)
    singular = []
    if f is not None:
        ends = [x for x in (fx0, fx1) if not (scene.symmetric and abs(x) < _TOL * width)]
        singular += [(x, -d_base) for x in ends]
        if d_base and not surcharge_model:
            singular += [(x, 0.0) for x in ends]  # the trench's top corners
    for a, b, _ in pressures_ref + pressures_dead:
        singular += [(x, z_ground) for x in (a, b) if xl < x < xr]
    if settle_ref:
        unit, ref = "N/m", "the footing's vertical force V [N/m] (Settlement push)"
    else:
        unit, ref = "", _describe(ref_phase, scene)
    if d_base:  # say which embedded model the bracket is of
        ref += (
            f"; embedded {d_base:g} m, side soil as its overburden {p_base / 1e3:g} kPa at the base level"
            if surcharge_model
            else f"; embedded {d_base:g} m, side soil modelled (trench walls under their geostatic stress)"
        )
    return LimitProblem(
        site,
        ref_phase.name,
        unit,
        ref,
        singular,
        0.0 if f is None else fx1 - fx0,
        bool(scene.symmetric),
        scene,
        0.0 if settle_ref else -float(fref[1]) / half,
    )


def _wall_pressure(scene, pa, pb) -> Boundary:
    """A trench wall from ``pa`` to ``pb`` (within one layer): free, under the wall's geostatic horizontal
    stress -sigma_xx0(z) [Pa] as a dead pressure, linear in z within a layer (the incremental scene's wall
    load, or the state its side contact starts from)."""
    za, zb = float(pa[1]), float(pb[1])
    inside = 0.25 * (zb - za)  # points inside the segment: an end on a layer boundary reads the layer above
    za, zb = za + inside, zb - inside
    sa, sb = (-float(scene._geostatic(np.array([z]))[0, 0]) for z in (za, zb))
    slope = (sb - sa) / (zb - za)
    return Boundary("free", pressure_dead=sa - slope * za, pressure_dead_grad=(0.0, slope))


def _site_problem(site, unloaded: bool = False) -> LimitProblem:
    """The limit problem of an :class:`ssi.scene.site.Site` (any layering and ground, several strips): its
    one geometry (:meth:`Site.geometry`, cells cut at the water table) with the buoyant unit weight below
    the water table, every :class:`Strip` a rigid footing on its contact, the site's loads
    (columns on the strips, pressures on level ground) scaled by lambda. A single :class:`RigidStrip` and no
    loads: lambda is its vertical force [N/m]. An embedded strip (``level`` below the ground) stands in its
    trench, the side soil modelled by the site's geometry (its strength and weight); the trench walls are
    free faces (the incremental site's trench is open while gravity loads it, so its walls start without
    traction and the strip carries no overburden) or, with the strip's ``side_contact``, footing segments
    on that contact (Coulomb c_i, phi_i, tension cut-off; bonded: rough), the wall moving with the strip as
    one rigid body. Refused: DepthVarying layers, a RigidStrip beside other strips or loads, a pressure on
    sloping ground."""
    for i, lay in enumerate(site.layers):
        if not isinstance(lay, SoilLayer):
            raise ValueError(
                f"Site.layers[{i}] is a {type(lay).__name__}: strength varying with depth is not represented "
                "by ssi.limit (one material per region)"
            )
    geo = site.geometry()
    xs = geo.points[:, 0]
    width = float(np.ptp(xs))
    strips = list(site.strips)
    rigid = [s for s in strips if s.rigid]
    if rigid and (len(strips) > 1 or site.loads):
        raise ValueError(
            "Site.strips: a RigidStrip is pushed by a settlement (lambda = its force); ssi.limit takes it "
            "only alone, without other strips or loads"
        )
    ends = []
    footings = []
    walls = {}  # (x of a trench wall, strip index) -> (base level [m], the wall's interface or None: free)
    for i, _x0, _x1, lv in site.embedded():
        st = strips[i]
        side = (
            None
            if st.side_contact is None
            else _contact_interface(st.side_contact, f"Site.strips[{i}].side_contact")
        )
        walls[i] = (lv, side)
    for i, st in enumerate(strips):
        if st.rigid:
            ends.append((st.x0, st.x1))
            itf = Interface("rough" if st.rough else "smooth")
            footings.append(Footing(itf, (0.0, -1.0), (0.0, 0.0), ("z",)))
            continue
        f = st.foundation
        ends.append((f.x0, f.x1))

        class _Holder:  # what _interface and _footing_forces read of a scene
            foundation, contact, water_table, gamma_w = f, st.contact, None, site.gamma_w

        loads = [ld for ld in site.loads if isinstance(ld, ColumnLoad) and f.x0 - 1e-9 <= ld.x <= f.x1 + 1e-9]
        fx, fz, m, _ = _footing_forces(_Holder, loads, True, f.x0, f.x1, f"Site.strips[{i}] loads")
        if abs(m) <= _TOL * ((abs(fz) + abs(fx)) * (f.x1 - f.x0) + 1.0):
            m = 0.0
        itf = _interface(_Holder)
        moves = (("z",) if itf.kind == "smooth" else ("x", "z")) + ("r",)
        if itf.kind == "smooth" and fx:
            raise ValueError(f"Site.strips[{i}]: a smooth contact carries no horizontal load")
        xc = 0.5 * (f.x0 + f.x1)
        centre = (xc, site.base_z(i))  # the centre of its base: the ground under it, or its trench's bottom
        footings.append(Footing(itf, (fx, fz), (0.0, 0.0), moves, centre, m))
    pressures = [(ld.x0, ld.x1, ld.q) for ld in site.loads if isinstance(ld, SurfacePressure)]
    # materials: each layer dry and (below the water table) buoyant; each cell by its centroid
    mats, region = [], []
    for i, lay in enumerate(site.layers):
        sat = lay.unit_weight if lay.unit_weight_sat is None else lay.unit_weight_sat
        mats.append(_layer_material(i, lay, lay.unit_weight))
        mats.append(_layer_material(i, lay, max(sat - site.gamma_w, 0.0)))
    for cell, k in zip(geo.cells, geo.cell_region):
        c = geo.points[list(cell)].mean(axis=0)
        wet = c[1] < float(site.water_z(np.array([c[0]]))[0])
        region.append(2 * int(k) + int(wet))
    geo = type(geo)(geo.points, geo.segments, geo.segment_tags, geo.cells, np.array(region, np.int64))

    def boundary(tag, pa, pb):
        if tag in _BLOCK_SUPPORTS:
            return _BLOCK_SUPPORTS[tag]
        xm = 0.5 * (pa[0] + pb[0])
        for j, (a, b) in enumerate(ends):
            if a < xm < b:
                return Boundary("footing", footing=j)
        if abs(pb[0] - pa[0]) <= _TOL * width:  # a vertical ground segment: a trench wall, or a step
            for j, (lv, side) in walls.items():
                on_wall = any(abs(xm - x) <= _TOL * width for x in ends[j])
                if on_wall and min(pa[1], pb[1]) >= lv - _TOL * width:
                    return (
                        Boundary("free") if side is None else Boundary("footing", footing=j, interface=side)
                    )
        q = _ground_pressure(pressures, xm)
        if q and abs(pb[1] - pa[1]) > _TOL * width:
            raise ValueError(
                f"Site.loads: a SurfacePressure on sloping ground at x = {xm:g} m (a vertical load per "
                "horizontal metre there is not a normal pressure): not represented by ssi.limit"
            )
        return Boundary("free", pressure_ref=q)

    lsite = site_from_geometry(geo, tuple(mats), boundary, tuple(footings))
    singular = [(x, site.base_z(i)) for i, (a, b) in enumerate(ends) for x in (a, b)]
    singular += [(x, float(site.ground_z(np.array([x]))[0])) for i in walls for x in ends[i]]  # wall tops
    singular += [(x, float(site.ground_z(np.array([x]))[0])) for a, b, _ in pressures for x in (a, b)]
    if rigid:
        unit, ref, ref_force = "N/m", "the RigidStrip's vertical force V [N/m]", 0.0
    else:
        n_total = sum(ld.N for ld in site.loads if isinstance(ld, ColumnLoad))
        parts = [
            f"column N={ld.N / 1e3:g} kN/m"
            + (f" H={ld.H / 1e3:g} kN/m" if ld.H else "")
            + f" at x={ld.x:g} m"
            for ld in site.loads
            if isinstance(ld, ColumnLoad)
        ]
        parts += [f"pressure q={q / 1e3:g} kPa on x=[{a:g}, {b:g}] m" for a, b, q in pressures]
        loads = "the site's loads: " + ", ".join(parts) if parts else "no load (the soil's weight alone)"
        unit, ref, ref_force = "", loads, float(n_total)
    if not (rigid or site.loads or unloaded):
        raise ValueError(
            "Site.loads: the site has no load to scale (its own factor of safety: Site.safety_factor)"
        )
    width_f = ends[0][1] - ends[0][0] if len(ends) == 1 else 0.0
    return LimitProblem(lsite, "loads", unit, ref, singular, width_f, False, site, ref_force)


def _describe(phase, scene) -> str:
    """What lambda = 1 means: the phase's loads in kN/m and kPa."""
    parts = []
    for ld in phase.loads:
        if isinstance(ld, ColumnLoad):
            parts.append(
                f"column N={ld.N / 1e3:g} kN/m"
                + (f" H={ld.H / 1e3:g} kN/m" if ld.H else "")
                + f" at x={ld.x:g} m"
            )
        elif isinstance(ld, SurfacePressure):
            parts.append(f"pressure q={ld.q / 1e3:g} kPa on x=[{ld.x0:g}, {ld.x1:g}] m")
        elif isinstance(ld, StripLoad):
            q1 = ld.q if ld.q_end is None else ld.q_end
            parts.append(f"strip load q={ld.q / 1e3:g}..{q1 / 1e3:g} kPa")
        elif isinstance(ld, StripWeight):
            parts.append(f"strip weight {ld.unit_weight / 1e3:g} kN/m^3")
    return f"the loads of phase {phase.name!r}: " + ", ".join(parts)
