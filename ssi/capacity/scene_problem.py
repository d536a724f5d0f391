"""A :class:`~ssi.scene.Scene`'s geometry for the limit problem (:func:`scene_parts`): its block (the
whole width, or the half x >= 0 of a symmetric scene) cut into cells at every layer boundary, the water
table, the foundation's ends and every load's end; its phases' loads; its one footing, rigid or a beam
strip; an embedded strip's side soil as its overburden ("surcharge") or modelled ("soil"). What each part
maps to and what is refused: this package's README.md; the rest of the problem is
:mod:`ssi.capacity.common`'s, common with a site's."""

from __future__ import annotations

import warnings

import numpy as np

from ..core.geometry import from_cells
from ..limit import Beam, Boundary, Footing
from .action import SceneInput
from .common import (
    TOL,
    Parts,
    collect_loads,
    contact_interface,
    describe,
    footing_interface,
    frame_of,
    layer_material,
    refuse_strengthless,
)
from .strip import beam_mode, strip_beam_interaction

__all__ = ["scene_parts"]


def _mirror_symmetric(f, xl, xr, fref, fdead, mref, mdead, p_dead, p_ref, width) -> bool:
    """Whether the scene is its own mirror image about the foundation's centre: the block centred on it,
    the ground pressures mirrored, no moment and no horizontal force on the foundation (the layers and the
    water table are level)."""
    xc, tol = 0.5 * (f.x0 + f.x1), TOL * width
    if abs(0.5 * (xl + xr) - xc) > tol or mref or mdead or fref[0] or fdead[0]:
        return False
    for items in (p_dead, p_ref):
        mirrored = sorted((round(2 * xc - b, 9), round(2 * xc - a, 9), q) for a, b, q in items)
        if mirrored != sorted((round(a, 9), round(b, 9), q) for a, b, q in items):
            return False
    return True


def _phase_index(phases, phase: str | None) -> int:
    if not phases:
        raise ValueError("the scene has no loads (Scene.loads and Scene.phases are empty): nothing to scale")
    names = [ph.name for ph in phases]
    if phase is None:
        return len(phases) - 1
    if phase in names:
        return names.index(phase)
    raise ValueError(f"phase={phase!r} is not a phase of the scene; its phases are {names}")


def scene_parts(scene: SceneInput, phase: str | None, strip: str | None, side_soil: str):
    """The :class:`~ssi.capacity.common.Parts` of ``scene`` with lambda scaling the loads of ``phase``
    (arguments as :func:`ssi.capacity.problem.limit_problem`'s, ``side_soil`` given)."""
    with_mn = strip == "beam_mn"  # a beam whose hinges' capacity is the section's M-N polygon
    strip = "beam" if with_mn else strip
    phases = scene.load_phases()
    k = _phase_index(phases, phase)
    d_base = float(scene.embedment)  # the strip's base below the ground [m]
    if d_base and scene.water_table is not None and float(scene.water_table) < d_base - TOL * scene.depth:
        raise ValueError(
            f"Scene.water_table={scene.water_table!r} m lies above the embedded strip's base "
            f"(embedment={d_base!r} m): the pore pressure on the base and the trench walls is not "
            "represented by ssi.limit; give a water table at or below the base level"
        )
    surcharge_model = bool(d_base) and side_soil == "surcharge"
    side_itf = None  # the trench walls' contact with the strip (side_soil="soil" and a side_contact)
    if d_base and side_soil == "soil" and scene.side_contact is not None:
        side_itf = contact_interface(scene.side_contact, "Scene.side_contact")
    for ph in phases[: k + 1]:
        if ph.excavate:
            raise ValueError(f"Phase({ph.name!r}).excavate: excavations are not represented by ssi.limit")
        if ph.drainage:
            raise ValueError(
                f"Phase({ph.name!r}).drainage: drainage switches are not represented by ssi.limit"
            )
    ref_phase = phases[k]

    f = scene.foundation
    xl, xr = scene.block()
    width = xr - xl
    fx0, fx1 = scene.footprint() if f is not None else (None, None)
    mp = beam_mode(scene, strip)  # (mp_sag, mp_hog) [N m/m] of a beam strip, None: rigid
    if mp is not None and side_itf is not None:
        msg = (
            "Scene.side_contact with side_soil='soil' on a beam strip: the walls' contact moves with the "
            "strip's end sections, which ssi.limit's beam (hinged along its base) does not represent"
        )
        if strip == "beam":
            raise ValueError(msg + "; give strip='rigid'")
        warnings.warn(msg + ": the strip is taken rigid", stacklevel=3)
        mp = None
    # ---- ground pressures and the footing's forces, dead and reference
    footings_in = [] if f is None else [(f, frame_of(f, scene.water_table, scene.gamma_w))]

    def what_of(ph):
        return f"Phase({ph.name!r}).loads" if ph.name != "loads" or scene.phases else "Scene.loads"

    no_ground = (
        "a SurfacePressure on the ground of an embedded scene with side_soil='surcharge' (the side soil "
        "is replaced by its overburden at the base level, where the spread of a local load through it is "
        "unknown); give side_soil='soil' or the uniform Scene.surcharge"
        if surcharge_model
        else None
    )
    pressures_dead, pressures_ref, loads = collect_loads(
        phases, k, (xl, xr), footings_in, TOL * width, what_of, mp is not None, no_ground
    )
    fl = loads[0] if loads else None
    if mp is not None and fl.beam_error is not None:
        if strip == "beam":
            raise fl.beam_error
        warnings.warn(f"{fl.beam_error}: the strip is taken rigid", stacklevel=3)
        mp = None
    fref, fdead = (fl.ref, fl.dead) if fl else (np.zeros(2), np.zeros(2))
    mref, mdead = (fl.m_ref, fl.m_dead) if fl else (0.0, 0.0)
    settle_ref = bool(fl and fl.settles)
    beam_loads = fl.beam if fl else None
    if settle_ref and (np.any(fref != 0.0) or pressures_ref):
        raise ValueError(
            f"Phase {ref_phase.name!r} mixes a Settlement with force loads: lambda scales either the loads "
            "or the pushed footing's force, not both"
        )
    # the geostatic vertical stress of the base level [Pa]: the surcharge, plus the overburden of an
    # embedded base
    p_base = -float(scene.geostatic(np.array([-d_base]))[0, 1]) if d_base else float(scene.surcharge)
    if f is not None and not f.rigid and scene.has_geostatic_stress():
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
    xs = sorted(x for x in xs if xl - TOL * width <= x <= xr + TOL * width)
    sub = scene.mesh_layers()  # (thickness, layer, unit weight of its body force), split at the water table
    owner = [next(i for i, lay in enumerate(scene.layers) if lay is own) for _, own, _ in sub]
    z_tops = -np.concatenate([[0.0], np.cumsum([t for t, _, _ in sub])])
    n_above = 0  # sub-layers above an embedded base
    if d_base:
        hit = np.flatnonzero(np.abs(z_tops + d_base) <= TOL * scene.depth)
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
            stacklevel=3,
        )
    materials = tuple(layer_material(i, lay, g) for i, (_, lay, g) in zip(owner[first:], sub[first:]))
    refuse_strengthless(materials, "scene")
    z_ground = float(z_tops[first])  # the model's ground: the base level of the surcharge model
    polys, regions = [], []
    for a, b in zip(xs[:-1], xs[1:]):
        in_trench = f is not None and d_base and fx0 - TOL * width < 0.5 * (a + b) < fx1 + TOL * width
        for r in range(first, len(sub)):
            zt, zb = z_tops[r], z_tops[r + 1]
            if in_trench and r < n_above:
                continue  # the trench the strip sits in
            polys.append([(a, zb), (b, zb), (b, zt), (a, zt)])
            regions.append(r - first)
    geo = from_cells(polys, regions)

    footings = ()
    if f is not None:
        itf = footing_interface(f, scene.contact_laws(), "Scene.contact")
        if f.rigid or scene.symmetric:
            moves = ("z",)  # the scene holds a rigid footing horizontally (rough: u = 0; the axis)
            if fref[0] or fdead[0]:
                raise ValueError("a horizontal load on a RigidFooting or on a symmetric scene's footing")
        elif itf.kind == "smooth":
            moves = ("z",)
        else:
            moves = ("x", "z")
        tilts = not f.rigid and not scene.symmetric and not settle_ref
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

    walls = {0: (-d_base, side_itf)} if f is not None and d_base and not surcharge_model else {}
    singular = []
    if f is not None:
        ends = [x for x in (fx0, fx1) if not (scene.symmetric and abs(x) < TOL * width)]
        singular += [(x, -d_base) for x in ends]
        if d_base and not surcharge_model:
            singular += [(x, 0.0) for x in ends]  # the trench's top corners
    for a, b, _ in pressures_ref + pressures_dead:
        singular += [(x, z_ground) for x in (a, b) if xl < x < xr]
    if settle_ref:
        unit, ref = "N/m", "the footing's vertical force V [N/m] (Settlement push)"
    else:
        texts = describe([ld.limit_action(None) for ld in ref_phase.loads])
        unit, ref = "", f"the loads of phase {ref_phase.name!r}: " + texts
    if d_base:  # say which embedded model the bracket is of
        ref += (
            f"; embedded {d_base:g} m, side soil as its overburden {p_base / 1e3:g} kPa at the base level"
            if surcharge_model
            else f"; embedded {d_base:g} m, side soil modelled (trench walls under their geostatic stress)"
        )
    return Parts(
        geometry=geo,
        materials=materials,
        footings=footings,
        spans=[] if f is None else [(fx0, fx1)],
        walls=walls,
        free_wall=lambda pa, pb: _wall_pressure(scene, pa, pb),
        pressures_dead=pressures_dead,
        pressures_ref=pressures_ref,
        dead_uniform=p_base if surcharge_model else scene.surcharge,
        width=width,
        phase=ref_phase.name,
        lam_unit=unit,
        reference=ref,
        singular=singular,
        footing_width=0.0 if f is None else fx1 - fx0,
        symmetric=bool(scene.symmetric),
        ref_forces=() if f is None or settle_ref else (-float(fref[1]) / half,),
        footing_spans=() if f is None else ((f.x0, f.x1),),
    )


def _wall_pressure(scene, pa, pb) -> Boundary:
    """A trench wall from ``pa`` to ``pb`` (within one layer): free, under the wall's geostatic horizontal
    stress -sigma_xx0(z) [Pa] as a dead pressure, linear in z within a layer (the incremental scene's wall
    load, or the state its side contact starts from)."""
    za, zb = float(pa[1]), float(pb[1])
    inside = 0.25 * (zb - za)  # points inside the segment: an end on a layer boundary reads the layer above
    za, zb = za + inside, zb - inside
    sa, sb = (-float(scene.geostatic(np.array([z]))[0, 0]) for z in (za, zb))
    slope = (sb - sa) / (zb - za)
    return Boundary("free", pressure_dead=sa - slope * za, pressure_dead_grad=(0.0, slope))
