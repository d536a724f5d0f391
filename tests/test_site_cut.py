"""A vertical cut: a ground polyline with a vertical step (two points at one x), meshed by gmsh. The cut's
face is a free boundary of the mesh, the gravity state carries the soil's weight to the supports, and a
cohesive cut well below its critical height (gamma H / c = 3.78 for a vertical cut in undrained clay, Pastor
et al.) stands under its own weight with the soil's own plastic law."""

import numpy as np
import pytest

from ssi.core.geometry import GeometryError
from ssi.scene import MeshSize, SoilLayer, SurfacePressure
from ssi.scene.site import Site

H, GAMMA = 4.0, 18e3  # the cut's height [m], the clay's unit weight [N/m^3]
CUT = [(-15.0, H), (0.0, H), (0.0, 0.0), (15.0, 0.0)]  # crest at x = 0, the face down to z = 0
AREA = 30.0 * 10.0 + 15.0 * H  # [m^2] of soil: the block to z = -10 plus the bench left of the face
MESH = MeshSize(h_fine=0.5, h_coarse=2.0)


def _areas(built):
    """(n_el,) area [m^2] of each Q8 element: the shoelace formula over its eight nodes in boundary order
    (exact for straight-sided elements)."""
    xy = built.mesh.xy[built.mesh.conn[:, [0, 4, 1, 5, 2, 6, 3, 7]]]
    x, z = xy[..., 0], xy[..., 1]
    return 0.5 * np.abs(np.sum(x * np.roll(z, -1, axis=1) - np.roll(x, -1, axis=1) * z, axis=1))


def test_a_cohesive_cut_below_its_critical_height_stands_and_its_weight_reaches_the_supports():
    c = GAMMA * H / 2.0  # gamma H / c = 2.0, about half the critical 3.78
    clay = SoilLayer(1.0, E=30e6, nu=0.3, unit_weight=GAMMA, c=c, phi_deg=0.0)
    built = Site(30.0, 10.0, [clay], ground=CUT, mesh=MESH, initial_stress="gravity_plastic").build()
    assert built.mesher == "gmsh" and built.initial_stress_method == "gravity_plastic"
    xy = built.mesh.xy
    # the face is a chain of mesh nodes, and no element lies in the air right of it
    face = np.flatnonzero((np.abs(xy[:, 0]) < 1e-9) & (xy[:, 1] > 1e-9) & (xy[:, 1] < H - 1e-9))
    assert len(face) >= 3
    centre = xy[built.mesh.conn[:, :4]].mean(axis=1)
    assert np.all(centre[:, 1] < built.site.ground_z(centre[:, 0]))
    assert _areas(built).sum() == pytest.approx(AREA, rel=1e-12)
    # no load: the gravity state is the answer; the bottom's reactions carry the whole weight
    out = built.solve()
    assert out.status == "completed"
    bottom = np.flatnonzero(np.abs(xy[:, 1] + 10.0) < 1e-9)
    assert out.result.support_reaction(bottom, "w")[-1] == pytest.approx(GAMMA * AREA, rel=1e-9)
    assert np.abs(out.u[-1]).max() < 1e-6  # in equilibrium from the start: nothing moves


def test_a_layer_boundary_across_the_face_gives_each_layer_its_hand_area():
    """A level boundary at z = 2 m meets the face: the upper layer is the bench's top 2 m left of the face
    (15 m x 2 m), the lower one the rest; the cells beside the face conform (gmsh meshes them)."""
    soft = SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=17e3)
    stiff = SoilLayer(1.0, E=50e6, nu=0.3, unit_weight=19e3)
    site = Site(30.0, 10.0, [soft, stiff], ground=CUT, boundaries=[[(-15.0, 2.0), (15.0, 2.0)]], mesh=MESH)
    built = site.build()
    area = _areas(built)
    assert area[built.element_layer == 0].sum() == pytest.approx(15.0 * 2.0, rel=1e-12)
    assert area[built.element_layer == 1].sum() == pytest.approx(AREA - 30.0, rel=1e-12)


def test_a_step_is_two_points_at_one_x_and_a_pressure_stays_off_its_face():
    soil = [SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=17e3)]
    with pytest.raises(GeometryError, match="three points at one x"):
        Site(30.0, 10.0, soil, ground=[(-15.0, 4.0), (0.0, 4.0), (0.0, 2.0), (0.0, 0.0), (15.0, 0.0)])
    with pytest.raises(GeometryError, match="must not decrease"):
        Site(30.0, 10.0, soil, ground=[(-15.0, 4.0), (0.0, 4.0), (-1.0, 0.0), (15.0, 0.0)])
    with pytest.raises(GeometryError, match="vertical step of the ground at x=0"):
        Site(30.0, 10.0, soil, ground=CUT, loads=[SurfacePressure(-2.0, 2.0, 10e3)])
    with pytest.raises(GeometryError, match="vertical step of the ground at x=0"):  # at the face's foot
        Site(30.0, 10.0, soil, ground=CUT, loads=[SurfacePressure(0.0, 2.0, 10e3)])
    # at the crest it is the ground's edge: accepted, and the surcharge is carried (w under it > 0)
    crest = SurfacePressure(-2.0, 0.0, 10e3)
    out = Site(30.0, 10.0, soil, ground=CUT, loads=[crest], mesh=MESH).build().solve()
    x, w = out.ground_settlement(-2.0, 0.0)
    assert np.all(w > 0.0)
