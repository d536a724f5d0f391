"""A lens (a closed region of another soil) in a borehole site, and layer boundaries from boreholes and
polylines mixed. The lens's elements carry the lens's soil, its area is the outline's, and a soft lens under a
strip makes the strip settle more; in the limit analysis its triangles carry its strength."""

import math

import numpy as np
import pytest
from matplotlib.path import Path

from ssi.core.geometry import GeometryError
from ssi.elements.section import homogeneous
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, SoilLayer
from ssi.scene.site import Borehole, Lens, Site, Strip

CLAY = SoilLayer(1.0, E=20e6, nu=0.3, unit_weight=18e3)
SAND = SoilLayer(1.0, E=80e6, nu=0.3, unit_weight=20e3)
PEAT = SoilLayer(1.0, E=1e6, nu=0.3, unit_weight=11e3)
OUTLINE = [(-3.0, -2.5), (0.0, -3.5), (3.0, -2.5), (0.0, -1.5)]  # a rhombus, diagonals 6 m and 2 m: 6 m^2
MESH = MeshSize(h_fine=0.5, h_coarse=2.0)


def _site(lenses=()):
    strip = Strip(Foundation(-1.5, 1.5, homogeneous(0.5, 30e9, 0.2)), Contact(kn=1e10, kt=1e9))
    return Site(
        30.0, 12.0, [CLAY, SAND], boreholes=[Borehole(-10.0, [-5.0]), Borehole(10.0, [-7.0])],
        strips=[strip], loads=[ColumnLoad(0.0, N=300e3)], lenses=list(lenses), mesh=MESH,
    )  # fmt: skip


def _areas(built):
    xy = built.mesh.xy[built.mesh.conn[:, [0, 4, 1, 5, 2, 6, 3, 7]]]
    x, z = xy[..., 0], xy[..., 1]
    return 0.5 * np.abs(np.sum(x * np.roll(z, -1, axis=1) - np.roll(x, -1, axis=1) * z, axis=1))


@pytest.fixture(scope="module")
def with_lens():
    return _site([Lens(OUTLINE, PEAT)]).build()


def test_the_lens_elements_carry_the_lens_soil(with_lens):
    built = with_lens
    centre = built.mesh.xy[built.mesh.conn[:, :4]].mean(axis=1)
    inside = Path(OUTLINE).contains_points(centre)
    # the elements inside the outline (by a point-in-polygon test of their centres) are region 2, the lens
    np.testing.assert_array_equal(built.element_layer == 2, inside)
    assert _areas(built)[inside].sum() == pytest.approx(6.0, rel=1e-12)
    E = built.soil.params[built.soil.el_mat, 0]  # each element's Young's modulus
    assert np.all(E[inside] == PEAT.E) and not np.any(E[~inside] == PEAT.E)
    # the weight of the lens is the peat's: the body force of the lens elements sums to 11 kN/m3 x 6 m^2
    assert np.all(built.soil.unit_weight[built.soil.el_mat[inside]] == PEAT.unit_weight)


def test_a_soft_lens_under_the_strip_makes_it_settle_more(with_lens):
    w_lens = with_lens.solve().strip_summary(0)["mean"]
    w_none = _site().build().solve().strip_summary(0)["mean"]
    assert w_lens > 1.2 * w_none > 0.0


def test_boundaries_from_boreholes_and_polylines_mixed():
    """Boundary 0 from the boreholes (None in Site.boundaries), boundary 1 a polyline."""
    site = Site(
        30.0, 12.0, [CLAY, PEAT, SAND], boreholes=[Borehole(-10.0, [-2.0]), Borehole(10.0, [-4.0])],
        boundaries=[None, [(-15.0, -6.0), (0.0, -8.0), (15.0, -6.0)]], mesh=MESH,
    )  # fmt: skip
    xs = np.array([-15.0, -10.0, 0.0, 10.0, 15.0])
    np.testing.assert_allclose(site.boundary_z(0, xs), [-2.0, -2.0, -3.0, -4.0, -4.0])
    np.testing.assert_allclose(site.boundary_z(1, xs), [-6.0, -6.0 - 2.0 / 3.0, -8.0, -6.0 - 2.0 / 3.0, -6.0])
    built = site.build()
    area = _areas(built)
    # layer 1 between the two boundaries: its thickness 4, 14/3, 5, 8/3, 2 m at x = -15, -10, 0, 10, 15, so
    # its area is 5 (4 + 14/3) / 2 + 10 (14/3 + 5) / 2 + 10 (5 + 8/3) / 2 + 5 (8/3 + 2) / 2 = 120 m^2
    assert area[built.element_layer == 1].sum() == pytest.approx(120.0, rel=1e-12)
    with pytest.raises(GeometryError, match="lists 2 boundaries, the 3 layers need 1"):
        Site(30.0, 12.0, [CLAY, PEAT, SAND], boreholes=[Borehole(0.0, [-2.0, -5.0])],
             boundaries=[None, [(-15.0, -6.0), (15.0, -6.0)]])  # fmt: skip
    with pytest.raises(GeometryError, match="None takes a boundary from the boreholes"):
        Site(30.0, 12.0, [CLAY, SAND], boundaries=[None])


def test_lens_input_refused_by_name():
    with pytest.raises(GeometryError, match="not x-monotone"):
        Lens([(0.0, -1.0), (2.0, -1.0), (1.0, -2.0), (3.0, -3.0), (0.0, -3.0)], PEAT)
    with pytest.raises(GeometryError, match="rises above the ground"):
        _site([Lens([(-3.0, -1.0), (3.0, -1.0), (0.0, 1.0)], PEAT)])
    with pytest.raises(GeometryError, match="overlap"):
        _site([Lens(OUTLINE, PEAT), Lens([(-1.0, -3.0), (5.0, -3.0), (2.0, -2.0)], PEAT)])
    from ssi.capacity import limit_problem

    # an elastic lens never yields, in the run as in the bracket: its region (dry, wet) is the rigid material
    dry, wet = limit_problem(_tresca_site([Lens(WEDGE, PEAT)])).site.materials[2:4]
    assert dry.rigid and wet.rigid and dry.gamma == PEAT.unit_weight


def test_a_lens_and_mixed_boundaries_read_from_a_site_file(tmp_path):
    import json

    from ssi.scene.scene_file import model_from_dict, read_scene_file, scene_to_dict

    path = tmp_path / "lens.toml"
    path.write_text(
        """
width = 30.0
depth = 12.0
boundaries = [[], [[-15.0, -6.0], [15.0, -6.0]]]
[[layers]]
E = 20e6
nu = 0.3
[[layers]]
E = 1e6
nu = 0.3
[[layers]]
E = 80e6
nu = 0.3
[[boreholes]]
x = 0.0
boundaries = [-2.0]
[[lenses]]
points = [[-3.0, -2.5], [0.0, -3.5], [3.0, -2.5], [0.0, -1.5]]
layer = { E = 1e6, nu = 0.3, unit_weight = 11e3 }
"""
    )
    site, _, _ = read_scene_file(path)
    assert isinstance(site.lenses[0], Lens) and site.lenses[0].layer.E == 1e6
    assert float(site.boundary_z(0, 5.0)) == -2.0 and float(site.boundary_z(1, 5.0)) == -6.0
    plain = scene_to_dict(site)  # and back: the same site
    again = model_from_dict(json.loads(json.dumps(plain)))
    assert isinstance(again, Site) and scene_to_dict(again) == plain
    np.testing.assert_array_equal(again.geometry().cell_region, site.geometry().cell_region)


# ---- the limit analysis of a site with a lens: its triangles take the lens's strength ----------------------
C, N_LIM = 20e3, 100e3  # [Pa] s_u of the clay, [N/m] the column lambda scales
REL = 1e-6  # the bounds' conic solver tolerance, as in tests/test_limit_scene.py
WEDGE = [(-1.5, -0.2), (1.5, -0.2), (0.0, -1.7)]  # [m] a lens under the 2 m strip, 3 m wide, 1.5 m deep


def _clay(s_u=C):
    return SoilLayer.undrained(5.0, E_u=30e6, s_u=s_u)


def _tresca_site(lenses=()):
    """Test_limit_scene's Prandtl site (a plate strip bonded to weightless Tresca clay, a central column)
    with ``lenses``."""
    strip = Strip(Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)), Contact(kn=1e10, kt=1e9))
    return Site(12.0, 5.0, [_clay()], strips=[strip], loads=[ColumnLoad(0.0, N=N_LIM)], lenses=list(lenses))


def test_the_limit_triangles_inside_a_lens_carry_its_strength():
    from ssi.capacity import initial_mesh, limit_problem

    problem = limit_problem(_tresca_site([Lens(WEDGE, _clay(5e3))]))
    mesh = initial_mesh(problem, None, None)
    inside = Path(WEDGE).contains_points(mesh.xy[mesh.tri].mean(axis=1))
    c = np.array([problem.site.materials[k].c for k in mesh.material])
    assert inside.sum() >= 4  # the lens is meshed
    assert np.all(c[inside] == 5e3) and np.all(c[~inside] == C)
    # the triangles conform to the outline: the lens's triangles cover its area exactly (2.25 m^2)
    assert mesh.areas()[inside].sum() == pytest.approx(0.5 * 3.0 * 1.5, rel=1e-12)


@pytest.fixture(scope="module")
def tresca_brackets():
    """(no lens, a lens of the host's own strength, a weak lens c = 5 kPa) brackets, gap 5 %."""
    kw = {"gap": 0.05, "davis": False}
    return (
        _tresca_site().limit_analysis(**kw),
        _tresca_site([Lens(WEDGE, _clay())]).limit_analysis(**kw),
        _tresca_site([Lens(WEDGE, _clay(5e3))]).limit_analysis(**kw),
    )


def test_a_lens_of_the_hosts_strength_brackets_the_same_load(tresca_brackets):
    """A lens whose soil is its host's changes only the mesh (its outline), not the problem: both brackets
    hold Prandtl's exact lambda* = (2 + pi) c B / N (Prandtl 1920, weightless Tresca, rough strip), so they
    overlap, each within its gap."""
    bare, same, _ = tresca_brackets
    exact = (2.0 + math.pi) * C * 2.0 / N_LIM
    for cap in (bare, same):
        assert cap.lb * (1 - REL) <= exact <= cap.ub * (1 + REL)
        assert (cap.ub - cap.lb) / (cap.ub + cap.lb) <= 0.05
    assert max(bare.lb, same.lb) <= min(bare.ub, same.ub) * (1 + REL)


def test_a_weak_lens_under_the_strip_lowers_both_bounds(tresca_brackets):
    """A quarter-strength lens right under the strip: its upper bound falls below the lens-free lower bound
    (a mechanism through the lens dissipates less than any through the clay) -- and below Prandtl's
    lambda* -- while its lower bound stays above the load the lens alone carries, (2 + pi) c_lens B / N
    (the whole site as weak as the lens)."""
    bare, _, weak = tresca_brackets
    assert weak.ub < bare.lb and weak.lb < bare.lb
    assert weak.ub < (2.0 + math.pi) * C * 2.0 / N_LIM
    assert weak.lb > (2.0 + math.pi) * 5e3 * 2.0 / N_LIM
