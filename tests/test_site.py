"""Sites: the shared geometry, gmsh Q8 meshes, stratigraphy from boreholes, initial stress, depth-varying
stiffness and several strips, on small meshes."""

import numpy as np
import pytest

from ssi.core.geometry import GeometryError, from_cells
from ssi.core.gmsh_mesh import MeshQualityError, check_quality, mesh_geometry, q8_jacobians
from ssi.elements.section import homogeneous
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer, SurfacePressure
from ssi.scene.site import Borehole, DepthVarying, Site, Strip, gibson_settlement

SEC = homogeneous(0.5, 30e9, 0.2)
COARSE = MeshSize(h_fine=0.5, h_coarse=3.0)
LAYERS = [
    SoilLayer(3.0, E=20e6, nu=0.3, unit_weight=18e3),
    SoilLayer(7.0, E=60e6, nu=0.25, unit_weight=20e3),
]


def _strip(x0, x1):
    return Strip(Foundation(x0, x1, SEC), Contact(kn=1e10, kt=1e9))


def test_cells_share_edges_and_tags():
    polys = [[(0, -1), (2, -1), (2, 0), (0, 0)], [(0, -2), (2, -2), (2, -1), (0, -1)]]
    g = from_cells(polys, [0, 1])
    assert len(g.points) == 6  # the common edge's two points are shared
    assert sorted(g.segment_tags) == sorted(
        ["ground", "interior", "bottom", "left", "left", "right", "right"]
    )
    assert g.area() == pytest.approx(4.0, rel=1e-14)
    pslg = g.as_pslg()
    assert pslg["regions"].shape == (2, 4) and set(pslg["regions"][:, 2]) == {0.0, 1.0}


def test_gmsh_mesh_is_q8_deterministic_and_conforming():
    polys = [[(-5, -2), (5, -2), (5, 0), (-5, 0)], [(-5, -6), (5, -6), (5, -2), (-5, -2)]]
    g = from_cells(polys, [0, 1])
    m1 = mesh_geometry(g, 0.5, 2.0, 1.3, np.array([[-1.0, 0.0], [1.0, 0.0]]))
    m2 = mesh_geometry(g, 0.5, 2.0, 1.3, np.array([[-1.0, 0.0], [1.0, 0.0]]))
    assert np.array_equal(m1.xy, m2.xy) and np.array_equal(m1.conn, m2.conn)
    assert m1.conn.shape[1] == 8
    assert np.all(q8_jacobians(m1.xy, m1.conn) > 0.0)
    # mid-side nodes halfway between their corners (straight edges)
    for a, b, mid in ((0, 1, 4), (1, 2, 5), (2, 3, 6), (3, 0, 7)):
        np.testing.assert_allclose(
            m1.xy[m1.conn[:, mid]], 0.5 * (m1.xy[m1.conn[:, a]] + m1.xy[m1.conn[:, b]])
        )
    # conforming to the layer boundary: every element lies on one side of z = -2
    zc = m1.xy[m1.conn[:, :4], 1]
    assert np.all((zc.max(axis=1) <= -2.0 + 1e-9) | (zc.min(axis=1) >= -2.0 - 1e-9))
    assert np.all((zc.mean(axis=1) > -2.0) == (m1.el_layer == 0))
    # the areas of the elements sum to the block's
    det = q8_jacobians(m1.xy, m1.conn, n_gauss=2)
    assert det.sum() == pytest.approx(60.0, rel=1e-12)  # 2x2 Gauss weights are 1


def test_quality_check_names_an_inverted_element():
    xy = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0], [1, 0.5], [0.5, 1], [0, 0.5]], float)
    conn = np.array([[0, 3, 2, 1, 7, 6, 5, 4]])  # clockwise
    with pytest.raises(MeshQualityError, match="element 0 .*inverted"):
        check_quality(xy, conn)
    corners = np.array([[0, 0], [1, 0], [2, 0.2], [1, 0.2]], float)  # a parallelogram with 11.3 deg corners
    flat = np.vstack([corners, 0.5 * (corners + np.roll(corners, -1, axis=0))])
    assert np.all(q8_jacobians(flat, np.arange(8)[None]) > 0.0)  # valid, only distorted
    with pytest.raises(MeshQualityError, match="corner angles"):
        check_quality(flat, np.array([[0, 1, 2, 3, 4, 5, 6, 7]]))


def test_boreholes_interpolate_and_pinch_out():
    site = Site(
        20.0,
        10.0,
        LAYERS + [SoilLayer(1.0, E=80e6, nu=0.3)],
        boreholes=[Borehole(-5.0, [-2.0, -4.0]), Borehole(5.0, [-3.0, -3.0])],
        mesher="gmsh",
    )
    assert site.boundary_z(0, 0.0) == pytest.approx(-2.5)
    assert site.boundary_z(1, 0.0) == pytest.approx(-3.5)
    assert site.boundary_z(0, -9.0) == pytest.approx(-2.0)  # level beyond the outermost borehole
    g = site.geometry()
    # layer 1 has zero thickness right of x = 5: no cell of region 1 there
    for cell, region in zip(g.cells, g.cell_region):
        if region == 1:
            assert g.points[list(cell), 0].min() < 5.0 - 1e-9
    assert g.area() == pytest.approx(200.0, rel=1e-12)
    built = site.build()
    assert built.mesher == "gmsh" and built.initial_stress_method == "gravity"


def test_ground_cuts_a_boundary_and_a_slope_is_meshed():
    site = Site(
        30.0,
        10.0,
        LAYERS,
        boundaries=[[(-15.0, -1.0), (15.0, -1.0)]],
        ground=[(-15.0, 2.0), (-5.0, 2.0), (5.0, -2.0), (15.0, -2.0)],
        strips=[_strip(-12.0, -9.0)],
        loads=[ColumnLoad(-10.5, N=100e3)],
        mesh=COARSE,
    )
    xs = site.breaks()
    assert np.any(np.abs(xs - 2.5) < 1e-9)  # where the slope meets z = -1
    g = site.geometry()
    assert g.area() == pytest.approx(30.0 * 10 + 10 * 2 + 10 * 0.0 - 10 * 2, rel=1e-12)
    built = site.build()
    assert built.mesher == "gmsh" and built.initial_stress_method == "gravity"
    out = built.solve()
    assert out.strip_summary(0)["mean"] > 0.0


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"boreholes": [Borehole(12.0, [-3.0])]}, "outside the block"),
        ({"boreholes": [Borehole(0.0, [-3.0, -4.0])]}, "lists 2 boundaries"),
        ({"boreholes": [Borehole(0.0, [-11.0])]}, "below the block bottom"),
        ({"boundaries": [[(-10, -3.0), (10, -3.0)]], "strips": [_strip(-2, 1), _strip(0, 2)]}, "overlap"),
        ({"boreholes": [Borehole(0.0, [-3.0])], "ground": [(-10, 0.0), (10, 2.0)], "strips": [_strip(-1, 1)]},
         "not level"),
        ({"boreholes": [Borehole(0.0, [-3.0])], "strips": [Strip(Foundation(-1, 1, SEC), Contact(1e10, 1e9),
                                                                  level=0.5)]}, "in the air"),
        ({"boreholes": [Borehole(0.0, [-3.0])], "loads": [ColumnLoad(3.0, N=1.0)]}, "on no strip"),
    ],
)  # fmt: skip
def test_bad_geometry_gets_a_named_error(kwargs, match):
    with pytest.raises(GeometryError, match=match):
        Site(20.0, 10.0, LAYERS, **kwargs)


def test_crossing_polylines_and_k0_on_a_slope_are_refused():
    three = LAYERS + [SoilLayer(1.0, E=80e6, nu=0.3)]
    with pytest.raises(GeometryError, match="cross"):
        Site(20.0, 10.0, three, boundaries=[[(-10, -2.0), (10, -4.0)], [(-10, -3.0), (10, -3.0)]])
    with pytest.raises(GeometryError, match="lies above"):
        Borehole(0.0, [-3.0, -2.0])
    slope = Site(20.0, 10.0, LAYERS, boreholes=[Borehole(0.0, [-3.0])], ground=[(-10, 1.0), (10, 0.0)],
                 initial_stress="K0")  # fmt: skip
    with pytest.raises(ValueError, match="initial_stress='K0' is wrong here"):
        slope.build()


def test_level_borehole_site_equals_the_layered_scene():
    loads = [ColumnLoad(0.0, N=400e3)]
    scene = Scene(width=20.0, depth=10.0, layers=LAYERS, foundation=Foundation(-1.0, 1.0, SEC),
                  contact=Contact(kn=1e10, kt=1e9), loads=loads, mesh=COARSE)  # fmt: skip
    site = Site(20.0, 10.0, LAYERS, boreholes=[Borehole(-5.0, [-3.0]), Borehole(5.0, [-3.0])],
                strips=[_strip(-1.0, 1.0)], loads=loads, mesh=COARSE)  # fmt: skip
    ref = scene.build().solve()
    built = site.build()
    assert built.mesher == "structured" and built.initial_stress_method == "K0"
    out = built.solve()
    x_ref, w_ref = ref.settlement()
    x, w = out.strip_settlement(0)
    np.testing.assert_array_equal(x, x_ref)
    assert np.abs(w - w_ref).max() <= 1e-10 * np.abs(w_ref).max()


def test_gravity_loading_on_level_ground_is_the_elastic_k0_state():
    site = Site(12.0, 10.0, LAYERS, boreholes=[Borehole(0.0, [-3.0])], initial_stress="gravity",
                mesher="structured", mesh=COARSE)  # fmt: skip
    built = site.build()
    sig = built.soil.initial_stress
    z = built.soil.integration_points()[..., 1]
    sv = np.where(z > -3.0, 18e3 * z, -54e3 + 20e3 * (z + 3.0))
    nu = np.where(z > -3.0, 0.3, 0.25)
    assert np.abs(sig[..., 1] - sv).max() <= 1e-6 * np.abs(sv).max()
    assert np.abs(sig[..., 0] / sig[..., 1] - nu / (1.0 - nu)).max() <= 1e-6


def test_depth_varying_modulus_per_element():
    lay = DepthVarying(SoilLayer(1.0, E=1e6, nu=0.3, c=10e3, phi_deg=20.0), E_inc=2e6, c_inc=1e3)
    assert lay.at(3.0).E == pytest.approx(7e6) and lay.at(3.0).c == pytest.approx(13e3)
    assert lay.at(-1.0).E == pytest.approx(1e6)  # above the reference level: the reference value
    layers = [DepthVarying(SoilLayer(1.0, E=1e6, nu=0.3), E_inc=2e6)]
    load = [SurfacePressure(-1.0, 1.0, 1e3)]
    built = Site(10.0, 5.0, layers, mesh=COARSE, loads=load, depth_varying="centroid").build()
    zc = built.mesh.xy[built.mesh.conn].mean(axis=1)[:, 1]
    np.testing.assert_allclose(built.soil.params[built.soil.el_mat, 0], 1e6 + 2e6 * (-zc), rtol=1e-12)
    # the default: E at each Gauss point (a material row per point)
    built = Site(10.0, 5.0, layers, mesh=COARSE, loads=load).build()
    zg = built.soil.integration_points()[..., 1]
    e_points = np.column_stack([built.soil.params[m, 0] for m in built.soil.point_mat])
    np.testing.assert_allclose(e_points, 1e6 + 2e6 * (-zg), rtol=1e-12)


def test_gibson_settlement_small_mesh():
    """Gibson (1967): G = m z, nu -> 1/2, strip load q: the ground under the load settles q / (2m) relative
    to the far ground (in a closed box the incompressible soil heaves the far ground uniformly)."""
    nu, m, q = 0.499, 1e6, 100e3
    lay = DepthVarying(SoilLayer(1.0, E=1e-3 * m, nu=nu, nu_u=nu), E_inc=2.0 * (1.0 + nu) * m)
    site = Site(40.0, 20.0, [lay], loads=[SurfacePressure(-1.0, 1.0, q)], mesh=MeshSize(h_fine=0.25,
                h_coarse=4.0))  # fmt: skip
    out = site.build().solve()
    x, w = out.ground_settlement()
    rel = (w - w[0]) / gibson_settlement(q, m)
    assert np.all(np.abs(rel[np.abs(x) <= 0.5] - 1.0) < 0.03)
    assert np.all(np.abs(rel[np.abs(x) >= 2.0]) < 0.03)


def test_two_strips_superpose_on_one_mesh():
    bh = [Borehole(-10.0, [-2.0]), Borehole(10.0, [-4.0])]

    def site(n1, n2):
        return Site(30.0, 10.0, LAYERS, boreholes=bh, strips=[_strip(-6.0, -4.0), _strip(3.0, 5.0)],
                    loads=[ColumnLoad(-5.0, N=n1), ColumnLoad(4.0, N=n2)], mesh=COARSE)  # fmt: skip

    both, a, b = (site(*n).build() for n in ((300e3, 200e3), (300e3, 0.0), (0.0, 200e3)))
    assert np.array_equal(both.mesh.xy, a.mesh.xy) and np.array_equal(both.mesh.conn, b.mesh.conn)
    u, ua, ub = (s.solve().u[-1] for s in (both, a, b))
    assert np.abs(u - ua - ub).max() <= 1e-10 * np.abs(u).max()
    out = both.solve()
    s0, s1 = out.strip_summary(0), out.strip_summary(1)
    assert out.differential_settlement(0, 1) == pytest.approx(s0["mean"] - s1["mean"])
    assert s0["mean"] > 0.0 and s1["mean"] > 0.0


def test_example_site_files_build_and_solve():
    from pathlib import Path

    from ssi.scene.scene_file import read_scene_file

    root = Path(__file__).resolve().parents[1] / "examples"
    site, n_steps, settings = read_scene_file(root / "sites" / "boreholes.toml")
    assert len(site.strips) == 2 and len(site.boreholes) == 3
    out = site.build().solve(n_steps, settings)
    assert out.strip_summary(0)["mean"] > out.strip_summary(1)["mean"] > 0.0
    slope, n_steps, settings = read_scene_file(root / "sites" / "slope.toml")
    built = slope.build()
    assert built.mesher == "gmsh" and built.initial_stress_method == "gravity"
    assert isinstance(slope.layers[1], DepthVarying)
    out = built.solve(n_steps, settings)
    assert out.result.status == "completed" and out.strip_summary(0)["mean"] > 0.0


def test_site_file_refuses_unknown_keys():
    from ssi.scene.scene_file import site_from_dict

    with pytest.raises(ValueError, match="unknown|allowed"):
        site_from_dict({"width": 10.0, "depth": 5.0, "layers": [{"E": 1e7, "nu": 0.3}], "slope": 30.0})
    with pytest.raises(ValueError, match="not one a site takes"):
        site_from_dict({"width": 10.0, "depth": 5.0, "layers": [{"E": 1e7, "nu": 0.3}],
                        "loads": [{"type": "StripLoad", "q": 1.0}]})  # fmt: skip


def test_rigid_strip_push_on_elastic_soil_is_linear():
    from ssi.scene.site import RigidStrip

    site = Site(12.0, 5.0, [SoilLayer(1.0, E=20e6, nu=0.3)], strips=[RigidStrip(-1.0, 1.0, settle=0.01)],
                mesh=COARSE, mesher="gmsh")  # fmt: skip
    built = site.build()
    assert built.initial_stress_method == "none"
    out = built.solve(load_factors=[0.5, 1.0])
    s, q = out.rigid_pressure(0)
    assert s[-1] == pytest.approx(0.01, rel=1e-12)
    stiffness = q[1:] / s[1:]  # elastic: the pressure is proportional to the settlement along the path
    assert stiffness.min() > 0.0 and np.ptp(stiffness) <= 1e-9 * stiffness.max()


def test_plastic_gravity_loading_on_request():
    """A steep c-phi slope under its own weight: the elastic gravity state violates the strength somewhere;
    the plastic gravity phase ends inside the Mohr-Coulomb surface and in equilibrium with the weight."""
    soil = [SoilLayer(1.0, E=20e6, nu=0.3, unit_weight=18e3, c=5e3, phi_deg=20.0, psi_deg=0.0)]
    kw = dict(ground=[(-10.0, 3.0), (-1.0, 3.0), (1.0, 0.0), (10.0, 0.0)], mesh=COARSE)
    elastic = Site(20.0, 6.0, soil, initial_stress="gravity", **kw).build()
    plastic = Site(20.0, 6.0, soil, initial_stress="gravity_plastic", **kw).build()
    assert plastic.initial_stress_method == "gravity_plastic"
    s = plastic.soil.initial_stress
    # Mohr-Coulomb: the radius of Mohr's circle at most c cos(phi) - centre sin(phi) (+ round-off)
    centre = 0.5 * (s[..., 0] + s[..., 1])
    radius = np.hypot(0.5 * (s[..., 0] - s[..., 1]), s[..., 2])
    phi = np.radians(20.0)
    assert np.all(radius <= 5e3 * np.cos(phi) - centre * np.sin(phi) + 1e-6 * 18e3 * 9.0)
    # the plastic state balances the weight under the soil's own law: f_int(sigma_0) = f_body at the free DOFs
    from ssi.core.assembly import scatter_vector
    from ssi.core.protocol import FORCES_ONLY

    for built in (plastic,):
        g, n = built.soil, built.model.n_dof
        zero = np.zeros((g.n_el, 16))
        f_el, _, _ = g.evaluate(zero, zero, g.initial_state(), FORCES_ONLY)
        f_int, f_body = np.zeros(n), np.zeros(n)
        scatter_vector(g.edofs, f_el, f_int)
        scatter_vector(g.edofs, g.body_force(), f_body)
        free = built.model.free_mask()
        # the solver's convergence test: |r_free| <= force_tol (1e-5) x |F_int - F_int,0| (all DOFs, the
        # reactions included; the gravity phase starts stress-free, F_int,0 = 0)
        assert np.linalg.norm((f_int - f_body)[free]) <= 1e-5 * np.linalg.norm(f_int)
    # the elastic state violates the strength somewhere on this steep slope; the plastic one redistributes
    es = elastic.soil.initial_stress
    e_centre, e_radius = (
        0.5 * (es[..., 0] + es[..., 1]),
        np.hypot(0.5 * (es[..., 0] - es[..., 1]), es[..., 2]),
    )
    assert np.any(e_radius > 5e3 * np.cos(phi) - e_centre * np.sin(phi) + 1e3)


def test_the_same_geometry_feeds_a_triangle_mesher():
    """One description, two meshers: Triangle (the limit-analysis meshes) meshes the site's graph conforming
    to every layer boundary, each triangle in its cell's layer; the areas per layer equal the Q8 mesh's."""
    triangle = pytest.importorskip("triangle")
    site = Site(20.0, 8.0, LAYERS, boreholes=[Borehole(-5.0, [-2.0]), Borehole(5.0, [-4.0])],
                ground=[(-10.0, 1.0), (-3.0, 1.0), (3.0, 0.0), (10.0, 0.0)], mesh=COARSE)  # fmt: skip
    pslg = site.geometry().as_pslg()
    tri = triangle.triangulate(
        {k: pslg[k] for k in ("vertices", "segments", "regions")}, "pqAa0.5"
    )  # p: the graph, q: quality, A: region attributes, a: area limit [m^2]
    p = tri["vertices"][tri["triangles"]]
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    region = tri["triangle_attributes"][:, 0].astype(int)
    built = site.build()
    q8_area = q8_jacobians(built.mesh.xy, built.mesh.conn, n_gauss=2).sum(axis=1)  # 2x2 Gauss weights 1
    for k in range(len(LAYERS)):
        assert area[region == k].sum() == pytest.approx(q8_area[built.element_layer == k].sum(), rel=1e-12)


@pytest.mark.parametrize("mesher", ["structured", "gmsh"])
def test_water_table_is_a_mesh_line_and_gravity_matches_buoyant_k0(mesher):
    """A level water table 2 m down in the top layer: every element lies wholly above or below it, and
    gravity loading gives sigma_v' = sum of gamma (above) and gamma_sat - gamma_w (below) times depth, the
    K0 (effective) state of the layered scene, to round-off on the structured block."""
    wet = [
        SoilLayer(3.0, E=20e6, nu=0.3, unit_weight=18e3, unit_weight_sat=20e3),
        SoilLayer(7.0, E=60e6, nu=0.25, unit_weight=19e3, unit_weight_sat=21e3),
    ]
    site = Site(12.0, 10.0, wet, boreholes=[Borehole(0.0, [-3.0])], water_level=-2.0, mesh=COARSE,
                mesher=mesher, initial_stress="gravity")  # fmt: skip
    built = site.build()
    zc = built.mesh.xy[built.mesh.conn[:, :4], 1]
    assert np.all((zc.max(axis=1) <= -2.0 + 1e-9) | (zc.min(axis=1) >= -2.0 - 1e-9))
    k0 = Site(12.0, 10.0, wet, boreholes=[Borehole(0.0, [-3.0])], water_level=-2.0, mesh=COARSE,
              mesher="structured", initial_stress="K0").build()  # fmt: skip
    gw = 9.81e3

    def sigma_v(z):  # effective vertical stress: dry 18 kN/m3 to 2 m, buoyant 20 - gw to 3 m, then 21 - gw
        below = np.where(
            z > -3.0, -36e3 + (20e3 - gw) * (z + 2.0), -36e3 - (20e3 - gw) + (21e3 - gw) * (z + 3.0)
        )
        return np.where(z > -2.0, 18e3 * z, below)

    tol = 1e-9 if mesher == "structured" else 1e-2  # gmsh: general quads do not hold the quadratic u exactly
    for b, t in ((built, tol), (k0, 1e-9)):
        sv = sigma_v(b.soil.integration_points()[..., 1])
        assert np.abs(b.soil.initial_stress[..., 1] - sv).max() <= t * np.abs(sv).max()


def test_ssi_run_on_a_site_file_prints_the_per_foundation_summary(tmp_path, capsys):
    """`ssi run` recognises a site file and reports each strip's settlement and tilt and the differential
    settlement, the same numbers as the site solved in Python (read back from the JSON it writes)."""
    import json

    from ssi.io.cli import main
    from ssi.scene.scene_file import is_site_file, read_scene_file

    text = """
width = 30.0
depth = 12.0
[[layers]]
E = 10e6
nu = 0.3
[[layers]]
E = 40e6
nu = 0.3
[[boreholes]]
x = -10.0
boundaries = [-2.0]
[[boreholes]]
x = 10.0
boundaries = [-4.0]
[[strips]]
foundation = { x0 = -6.0, x1 = -4.0, section = { homogeneous = { thickness = 0.5, E = 30e9, nu = 0.2 } } }
contact = { kn = 1e10, kt = 1e9 }
[[strips]]
foundation = { x0 = 3.0, x1 = 5.0, section = { homogeneous = { thickness = 0.5, E = 30e9, nu = 0.2 } } }
contact = { kn = 1e10, kt = 1e9 }
[[loads]]
x = -5.0
N = 300e3
[[loads]]
x = 4.0
N = 200e3
[mesh]
h_fine = 0.5
h_coarse = 3.0
"""
    path = tmp_path / "two.toml"
    path.write_text(text)
    assert is_site_file(path)
    assert main(["run", str(path)]) == 0
    out = capsys.readouterr().out
    assert "#0 strip [-6, -4] m: settlement mean" in out and "differential settlement #0 - #1" in out
    s = json.loads((tmp_path / "two_summary.json").read_text())
    site, _, _ = read_scene_file(path)
    ref = site.build().solve()  # independent of the command line: the same site solved directly
    # 1e-12: the same deterministic mesh and linear solve, so only the JSON round trip (exact) separates them
    for i, f in enumerate(s["foundations"]):
        assert f["mean_settlement_m"] == pytest.approx(ref.strip_summary(i)["mean"], rel=1e-12)
        assert f["tilt_rad"] == pytest.approx(ref.strip_summary(i)["tilt"], rel=1e-12)
    (d,) = s["differential_settlement"]
    assert d["mean_settlement_i_minus_j_m"] == pytest.approx(ref.differential_settlement(0, 1), rel=1e-12)
    assert d["mean_settlement_i_minus_j_m"] > 0.0  # 300 kN/m on the left strip against 200 on the right
    assert main(["run", str(path)]) == 2  # the summary exists: refused without --overwrite
    assert "exists" in capsys.readouterr().err


def test_a_scene_file_is_not_taken_for_a_site_file(tmp_path):
    from ssi.scene.scene_file import is_site_file

    scene = tmp_path / "scene.toml"
    scene.write_text("width = 10.0\ndepth = 5.0\n[foundation]\nx0 = -1.0\nx1 = 1.0\n")
    assert not is_site_file(scene)
    (tmp_path / "bad.toml").write_text("width = = 1")
    assert not is_site_file(tmp_path / "bad.toml")  # left to the scene reader's "not valid TOML" error


def test_site_summary_of_a_rigid_strip_reports_its_push_and_pressure():
    from ssi.io.cli import summary as site_summary
    from ssi.io.cli import summary_text as site_summary_text
    from ssi.scene.site import RigidStrip

    site = Site(12.0, 5.0, [SoilLayer(1.0, E=20e6, nu=0.3)], strips=[RigidStrip(-1.0, 1.0, settle=0.01)],
                mesh=COARSE, mesher="gmsh")  # fmt: skip
    out = site.build().solve(load_factors=[0.5, 1.0])
    s = site_summary(out)
    (f,) = s["foundations"]
    settle, q = out.rigid_pressure(0)
    assert f["type"] == "rigid strip" and f["settlement_m"] == pytest.approx(0.01, rel=1e-12)
    assert f["pressure_Pa"] == q[-1] > 0.0 and s["differential_settlement"] == []
    assert "rigid strip [-1, 1] m: settlement 10.00 mm" in site_summary_text(s)
