"""A :class:`~ssi.scene.site.Site`'s geometry for the limit problem (:func:`site_parts`): its one polygon
(:meth:`Site.geometry`, cells cut at the water table and along each lens's outline, each cell the soil of its
region, a layer's or a lens's) with the buoyant unit weight below the water table,
every strip a rigid footing on its contact (a Strip translating and rotating, a RigidStrip pushed down),
its loads (columns on the strips, pressures on level ground) scaled by lambda. The rest of the problem is
:mod:`ssi.capacity.common`'s, common with a scene's."""

from __future__ import annotations

import numpy as np

from ..limit import Boundary, Footing, Interface
from ..materials.soil_laws import SoilLayer
from .action import SiteInput
from .common import (
    Parts,
    collect_loads,
    contact_interface,
    describe,
    footing_interface,
    frame_of,
    layer_material,
    refuse_strengthless,
)

__all__ = ["site_parts"]


class _Phase:
    """A site's one phase, its loads (what :func:`ssi.capacity.common.collect_loads` reads of a phase)."""

    name = "loads"
    factors: dict = {}

    def __init__(self, loads):
        self.loads = tuple(loads)


def site_parts(site: SiteInput, unloaded: bool = False) -> Parts:
    """The :class:`~ssi.capacity.common.Parts` of ``site``: its loads scaled by lambda; a single
    :class:`RigidStrip` and no loads: lambda is its vertical force [N/m]. An embedded strip (``level`` below
    the ground) stands in its trench, the side soil modelled by the site's geometry (its strength and
    weight); the trench walls are free faces (the incremental site's trench is open while gravity loads it,
    so its walls start without traction and the strip carries no overburden) or, with the strip's
    ``side_contact``, footing segments on that contact (Coulomb c_i, phi_i, tension cut-off; bonded: rough),
    the wall moving with the strip as one rigid body. ``unloaded``: a site without loads is accepted (its
    own factor of safety). Refused: DepthVarying layers, a RigidStrip beside other strips or loads, a
    pressure on sloping ground."""
    # the soil of every region of the geometry: the layers, then each lens's (region len(layers) + j), so
    # a lens's cells, cut along its outline by Site.geometry(), take the lens's strength and weight
    soils = site.soils()
    n_layers = len(site.layers)
    names = [f"layers[{i}]" for i in range(n_layers)]
    names += [f"lenses[{j}].layer" for j in range(len(soils) - n_layers)]
    for name, lay in zip(names, soils):
        if not isinstance(lay, SoilLayer):
            raise ValueError(
                f"Site.{name} is a {type(lay).__name__}: strength varying with depth is not represented "
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
    walls = {}  # strip index -> (base level [m], the wall's interface or None: free)
    for i, _x0, _x1, lv in site.embedded():
        side = strips[i].side_contact
        walls[i] = (lv, None if side is None else contact_interface(side, f"Site.strips[{i}].side_contact"))
    # a plate strip is its Foundation, a RigidStrip itself: each answers rigid, x0, x1 (and rough, or
    # section and self_weight) as a scene's foundation does
    parts = [s if s.rigid else s.foundation for s in strips]
    footings_in = [(f, frame_of(f, None, site.gamma_w)) for f in parts]
    pressures_dead, pressures_ref, loads = collect_loads(
        [_Phase(site.loads)], 0, (min(xs), max(xs)), footings_in, 0.0, lambda ph: "Site.loads", False
    )
    footings = []
    for i, (st, f, fl) in enumerate(zip(strips, parts, loads)):
        if st.rigid:
            footings.append(
                Footing(Interface("rough" if st.rough else "smooth"), (0.0, -1.0), (0.0, 0.0), ("z",))
            )
            continue
        itf = footing_interface(f, [st.contact], f"Site.strips[{i}].contact")
        moves = (("z",) if itf.kind == "smooth" else ("x", "z")) + ("r",)
        if itf.kind == "smooth" and fl.ref[0]:
            raise ValueError(f"Site.strips[{i}]: a smooth contact carries no horizontal load")
        centre = (
            0.5 * (f.x0 + f.x1),
            site.base_z(i),
        )  # the centre of its base: the ground, or its trench's bottom
        footings.append(Footing(itf, tuple(fl.ref.tolist()), (0.0, 0.0), moves, centre, float(fl.m_ref)))
    ends = [(f.x0, f.x1) for f in parts]
    # materials: each soil dry and (below the water table) buoyant; each cell by its centroid
    mats, region = [], []
    for name, lay in zip(names, soils):
        sat = lay.unit_weight if lay.unit_weight_sat is None else lay.unit_weight_sat
        mats.append(layer_material(0, lay, lay.unit_weight, name=f"Site.{name}"))
        mats.append(layer_material(0, lay, max(sat - site.gamma_w, 0.0), name=f"Site.{name}"))
    refuse_strengthless(mats, "site")
    for cell, k in zip(geo.cells, geo.cell_region):
        c = geo.points[list(cell)].mean(axis=0)
        wet = c[1] < float(site.water_z(np.array([c[0]]))[0])
        region.append(2 * int(k) + int(wet))
    geo = type(geo)(geo.points, geo.segments, geo.segment_tags, geo.cells, np.array(region, np.int64))

    def ground(x):
        return float(site.ground_z(np.array([x]))[0])

    singular = [(x, site.base_z(i)) for i, (a, b) in enumerate(ends) for x in (a, b)]
    singular += [(x, ground(x)) for i in walls for x in ends[i]]  # the trench walls' tops
    singular += [(x, ground(x)) for a, b, _ in pressures_ref for x in (a, b)]
    if rigid:
        unit, ref = "N/m", "the RigidStrip's vertical force V [N/m]"
    else:
        actions = [ld.limit_action(None) for ld in site.loads]
        # the columns first, then the pressures
        texts = describe(
            [a for a in actions if a.ground is None] + [a for a in actions if a.ground is not None]
        )
        unit, ref = "", "the site's loads: " + texts if texts else "no load (the soil's weight alone)"
    if not (rigid or site.loads or unloaded):
        raise ValueError(
            "Site.loads: the site has no load to scale (its own factor of safety: Site.safety_factor)"
        )
    return Parts(
        geometry=geo,
        materials=tuple(mats),
        footings=tuple(footings),
        spans=ends,
        walls=walls,
        free_wall=lambda pa, pb: Boundary("free"),
        pressures_dead=pressures_dead,
        pressures_ref=pressures_ref,
        dead_uniform=0.0,
        width=width,
        phase="loads",
        lam_unit=unit,
        reference=ref,
        singular=singular,
        footing_width=ends[0][1] - ends[0][0] if len(ends) == 1 else 0.0,
        symmetric=False,
        ref_forces=() if rigid else tuple(-float(fl.ref[1]) for fl in loads),
        footing_spans=tuple(ends),
    )
