"""A site's results through the same outputs as a scene's (issue 32 item 7): the result file (written, read
back, the site rebuilt), the ParaView series with a material id per element (scenes too) and units as field
data, the figures with the site's geometry, and ``ssi run site.toml`` writing all of it with the HTML
report; ``ssi show`` reads a site's file back. Small meshes (gmsh, a few hundred elements)."""

import json

import numpy as np
import pytest

from ssi.elements.section import homogeneous
from ssi.io.cli import main
from ssi.io.export import export_vtu, read_series, read_vtu
from ssi.io.results import read_result, write_result
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer
from ssi.scene.scene_file import read_scene_file, scene_to_dict, site_from_dict
from ssi.scene.site import Borehole, DepthVarying, RigidStrip, Site, Strip

SITE_TOML = """
width = 30.0
depth = 12.0
water_level = -3.0
[[layers]]
E = 10e6
nu = 0.3
unit_weight = 18e3
[[layers]]
E = 40e6
nu = 0.3
unit_weight = 20e3
[[boreholes]]
x = -10.0
boundaries = [-2.0]
[[boreholes]]
x = 10.0
boundaries = [-5.0]
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


@pytest.fixture(scope="module")
def site_run(tmp_path_factory):
    """``ssi run`` on the two-strip borehole site: (folder, toml path, printed summary)."""
    folder = tmp_path_factory.mktemp("site")
    path = folder / "two.toml"
    path.write_text(SITE_TOML)
    assert main(["run", str(path)]) == 0
    return folder, path


def _layer_by_geometry(site, xy_centre):
    """The layer index of points from the site's boundaries alone (below boundary k: layer k + 1), not from
    the mesher's element tags."""
    x, z = xy_centre[:, 0], xy_centre[:, 1]
    return sum((z < site.boundary_z(k, x)).astype(int) for k in range(len(site.layers) - 1))


def test_ssi_run_on_a_site_writes_result_paraview_figures_and_report(site_run):
    folder, path = site_run
    for name in ("two.h5", "two.pvd", "two_summary.json", "two_report.html"):
        assert (folder / name).is_file(), name
    figures = sorted(p.name for p in (folder / "two_plots").iterdir())
    assert figures == ["geometry_and_deformed_mesh.png", "settlement.png", "stress.png"]
    page = (folder / "two_report.html").read_text()
    s = json.loads((folder / "two_summary.json").read_text())
    assert all(f'src="two_plots/{name}"' in page for name in figures)  # every figure, linked relatively
    assert "http://" not in page and "https://" not in page  # nothing fetched: works offline
    # the per-foundation table and the differential settlement, the JSON's numbers in mm
    for f in s["foundations"]:
        assert f"{1e3 * f['mean_settlement_m']:.3f}" in page and f"{1e3 * f['tilt_rad']:.3f}" in page
    (d,) = s["differential_settlement"]
    assert f"{1e3 * d['mean_settlement_i_minus_j_m']:.3f}" in page


def test_site_result_file_reads_back_as_the_solved_site(site_run, capsys):
    """The file gives back a SiteResult whose site is rebuilt (same mesh) and whose displacements are the
    run's: equal to a direct solve of the same file to round-off (the same deterministic mesh and linear
    solve; 1e-12 of the largest). ``ssi show`` reprints the run's per-foundation lines from it."""
    folder, path = site_run
    stored = read_result(folder / "two.h5")
    site, n_steps, settings = read_scene_file(path)
    direct = site.build().solve(n_steps=n_steps, settings=settings)
    assert type(stored).__name__ == "SiteResult"
    np.testing.assert_array_equal(stored.built.model.coords, direct.built.model.coords)
    u, u_ref = np.asarray(stored.u[-1]), np.asarray(direct.u[-1])
    assert np.abs(u - u_ref).max() <= 1e-12 * np.abs(u_ref).max()
    for i in range(2):
        assert stored.strip_summary(i)["mean"] == pytest.approx(direct.strip_summary(i)["mean"], rel=1e-12)
    capsys.readouterr()
    assert main(["show", str(folder / "two.h5")]) == 0
    shown = capsys.readouterr().out
    s = json.loads((folder / "two_summary.json").read_text())
    d = s["differential_settlement"][0]["mean_settlement_i_minus_j_m"]
    assert f"differential settlement #0 - #1: {1e3 * d:.2f} mm" in shown
    assert (folder / "two_plots_2" / "report.html").is_file()  # redrawn beside the run's, not over it


def test_site_paraview_has_a_material_id_per_element_and_units(site_run):
    folder, path = site_run
    series = read_series(folder / "two.pvd")
    assert [t for t, _ in series] == [0.0, 1.0]  # a linear site: the unloaded and the solved state
    mesh = series[-1][1]
    site, _, _ = read_scene_file(path)
    built = site.build()
    quads = mesh.cells[0].data
    np.testing.assert_array_equal(quads, built.mesh.conn)
    ids = mesh.cell_data["material_id"][0]
    centre = built.mesh.xy[built.mesh.conn[:, :4]].mean(axis=1)
    np.testing.assert_array_equal(ids, _layer_by_geometry(site, centre))
    assert set(ids) == {0.0, 1.0}
    assert str(mesh.field_data["unit_material_id"][0]) == "-" and str(mesh.field_data["unit_szz"][0]) == "Pa"
    # meshio merges the line3 blocks on reading: strip 0's plate, its contact, strip 1's plate, its contact;
    # each contact's cells hold the element means of that strip's interface points (as a scene's), each
    # plate's the mean moment -- the blocks belong to the right strips
    out = read_result(folder / "two.h5")
    p, m = mesh.cell_data["contact_pressure"][1], mesh.cell_data["M"][1]
    start = 0
    for i in range(2):
        n = out.built.strips[i]["plate"].n_el
        m_ref = out.strip_forces(i)["M"].mean(axis=1)
        p_ref = -out.contact(i)["sig_n"].mean(axis=1)
        assert np.abs(m[start : start + n] - m_ref).max() <= 1e-12 * np.abs(m_ref).max()
        assert np.abs(p[start + n : start + 2 * n] - p_ref).max() <= 1e-12 * np.abs(p_ref).max()
        assert np.isnan(p[start : start + n]).all() and np.isnan(m[start + n : start + 2 * n]).all()
        start += 2 * n
    # hydrostatic pore pressure below the water table at z = -3 m, zero above
    pw = mesh.cell_data["pore_pressure"][0]
    z = centre[:, 1]
    assert np.all(pw[z > -2.5] == 0.0) and np.all(pw[z < -3.5] > 0.0)


def test_scene_paraview_has_the_material_id_of_its_layers(tmp_path):
    layers = [SoilLayer(2.0, E=20e6, nu=0.3), SoilLayer(4.0, E=60e6, nu=0.3)]
    strip = Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2))
    scene = Scene(width=12.0, depth=6.0, layers=layers, foundation=strip,
                  contact=Contact(kn=1e10, kt=1e9), loads=[ColumnLoad(0.0, N=100e3)],
                  mesh=MeshSize(h_fine=0.5, h_coarse=2.0))  # fmt: skip
    out = scene.build().solve()
    mesh = read_vtu(export_vtu(out, tmp_path / "s.vtu"))
    xy = out.built.mesh.xy
    centre_z = xy[out.built.mesh.conn[:, :4], 1].mean(axis=1)
    np.testing.assert_array_equal(mesh.cell_data["material_id"][0], (centre_z < -2.0).astype(float))


def test_site_to_dict_round_trips_rigid_strips_depth_variation_and_water():
    soft = DepthVarying(SoilLayer(1.0, E=5e6, nu=0.3, unit_weight=18e3), E_inc=1e6)
    strip = Strip(Foundation(1.0, 3.0, homogeneous(0.5, 30e9, 0.2)), Contact(kn=1e10, kt=1e9))
    site = Site(
        12.0, 6.0, [soft, SoilLayer(1.0, E=5e7, nu=0.3)],
        boreholes=[Borehole(-3.0, [-2.0]), Borehole(3.0, [-2.5])], water_level=-1.0,
        strips=[RigidStrip(-4.0, -2.0, settle=0.01), strip],
        loads=[ColumnLoad(2.0, N=100e3)], mesh=MeshSize(h_fine=0.5, h_coarse=2.0),
    )  # fmt: skip
    plain = scene_to_dict(site)
    again = site_from_dict(json.loads(json.dumps(plain)))
    assert scene_to_dict(again) == plain
    assert isinstance(again.strips[0], RigidStrip) and isinstance(again.layers[0], DepthVarying)
    assert again.layers[0].E_inc == 1e6 and again.water_level == -1.0


def test_a_rigid_strip_site_round_trips_through_its_file(tmp_path):
    site = Site(12.0, 5.0, [SoilLayer(1.0, E=20e6, nu=0.3)], strips=[RigidStrip(-1.0, 1.0, settle=0.01)],
                mesh=MeshSize(h_fine=0.5, h_coarse=3.0), mesher="gmsh")  # fmt: skip
    out = site.build().solve(load_factors=[0.5, 1.0])
    write_result(tmp_path / "r.h5", out)
    back = read_result(tmp_path / "r.h5")
    s, q = back.rigid_pressure(0)
    s_ref, q_ref = out.rigid_pressure(0)
    np.testing.assert_array_equal(s, s_ref)
    assert np.abs(q - q_ref).max() <= 1e-12 * np.abs(q_ref).max()
