"""Result files, ParaView export, scene files, plots, progress and the command line (issue 13).

References are independent of the code under test where one exists: the in-memory result a file was written
from (round trip, tolerance 0: HDF5 stores float64 bit for bit and JSON floats round-trip exactly), the
applied loads (statics of the contact resultant), a hand-built Scene (the TOML mapping)."""

import json
import os

import h5py
import matplotlib
import numpy as np
import pytest

from ssi.elements.section import homogeneous
from ssi.io import plot
from ssi.io.cli import main, summary
from ssi.io.export import export_series, export_vtu, read_series, read_vtu
from ssi.io.results import atomic_path, max_difference, read_info, read_result, write_result
from ssi.scene import (
    ColumnLoad,
    Contact,
    ContactSegment,
    Foundation,
    MeshSize,
    Phase,
    Scene,
    SceneResult,
    Settlement,
    SoilLayer,
    StripLoad,
    StripWeight,
    SurfacePressure,
)
from ssi.scene.file_schema import UNITS
from ssi.scene.scene_file import LOAD_TYPES, read_scene_file, scene_from_dict, scene_to_dict
from ssi.solver import NonConvergence, Settings
from ssi.solver.progress import progress_enabled, solver_progress

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "examples")
COARSE = MeshSize(h_fine=0.5, h_coarse=2.0, growth=1.5)


def mc_scene(N=300e3, H=50e3):
    """The scene of examples/strip_mohr_coulomb.toml, written in Python."""
    return Scene(
        width=12.0,
        depth=6.0,
        layers=[
            SoilLayer(2.0, E=20e6, nu=0.3, unit_weight=18e3, c=10e3, phi_deg=30.0, psi_deg=0.0),
            SoilLayer(4.0, E=60e6, nu=0.3, unit_weight=19e3),
        ],
        foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0),
        loads=[ColumnLoad(x=0.0, N=N, H=H)],
        mesh=COARSE,
    )


def phased_scene():
    """The scene of examples/phased_embedded.toml, written in Python: an embedded strip below a water table,
    loaded in phases (weight, building, half the building taken off)."""
    layers = [
        SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3),
        SoilLayer(
            5.0, E=50e6, nu=0.3, unit_weight=19e3, unit_weight_sat=20e3, c=2e3, phi_deg=32.0, psi_deg=0.0
        ),
    ]
    phases = [
        Phase("weight", (StripWeight(25e3),)),
        Phase("building", (ColumnLoad(0.0, N=250e3, H=20e3), SurfacePressure(3.0, 5.0, 20e3))),
        Phase("half_unload", factors={"building": 0.5}),
    ]
    return Scene(
        width=12.0,
        depth=6.0,
        layers=layers,
        foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0),
        phases=phases,
        embedment=1.0,
        water_table=2.0,
        gamma_w=9.81e3,
        mesh=COARSE,
    )


@pytest.fixture(scope="module")
def phased():
    return phased_scene().build().solve()


@pytest.fixture(scope="module")
def collapsed():
    """Ten times the bearing capacity with the default settings: a detected limit load."""
    return mc_scene(N=3e6, H=0.0).build().solve()


@pytest.fixture(scope="module")
def nonlinear():
    return mc_scene().build().solve(n_steps=4, settings=Settings(force_tol=1e-6))


@pytest.fixture(scope="module")
def viscous():
    """A record with viscous rows: the solver sets no viscosity (issue 31 removed its viscous fallback), but
    a file written before it, or a model whose groups were built with their own Duvaut-Lions viscosity,
    carries per-step viscosities; here the intermediate rows of a solved path are marked so. They belong
    to the result as much as its displacements."""
    out = mc_scene().build().solve(n_steps=4)
    visc = out.solver_result.step_viscosity
    visc[1:-1] = [1.0] * (len(visc) - 2)
    assert len(visc) >= 3
    return out


@pytest.fixture(scope="module")
def linear():
    scene = mc_scene()
    scene.layers[0] = SoilLayer(2.0, E=20e6, nu=0.3, unit_weight=18e3)
    scene.contact = Contact(kn=1e10, kt=1e9)
    return scene.build().solve()


# ---- SceneResult answers -------------------------------------------------------------------------------
def test_contact_resultant_balances_the_column(nonlinear):
    """Statics of the strip: the contact carries N and H, and its moment about x = 0 is H times the lever
    arm from the plate nodes (mid-depth, where H acts) down to the contact face (0.25 m)."""
    r = nonlinear.contact_resultant()
    assert r["N"] == pytest.approx(300e3, rel=1e-4)
    assert r["H"] == pytest.approx(50e3, rel=1e-4)
    assert r["M"] == pytest.approx(50e3 * 0.25, rel=1e-3)
    assert np.sum(nonlinear.contact_weights()) == pytest.approx(2.0, rel=1e-12)  # foundation width


def test_strip_forces_and_paths(nonlinear):
    f = nonlinear.strip_forces()
    # free ends: the moment falls towards zero at both ends of the strip (sampled at the Gauss points)
    assert abs(f["M"][0, 0]) < 0.1 * np.abs(f["M"]).max() and abs(f["M"][-1, -1]) < 0.1 * np.abs(f["M"]).max()
    path = nonlinear.load_settlement()
    assert np.all(np.diff(path["settlement"]) > 0) and path["column_load"][-1] == pytest.approx(300e3)
    assert nonlinear.plastic_points().any() and nonlinear.plastic_strain().max() > 0.0
    _, s = nonlinear.max_settlement()
    assert s == pytest.approx(nonlinear.settlement()[1].max())


# ---- result files --------------------------------------------------------------------------------------
@pytest.mark.parametrize("which", ["nonlinear", "linear", "phased", "viscous", "collapsed"])
def test_result_file_round_trip_is_exact(which, request, tmp_path):
    result = request.getfixturevalue(which)
    path = write_result(tmp_path / "r.h5", result, Settings())
    back = read_result(path)
    assert isinstance(back, SceneResult)
    diff, where = max_difference(result, back)
    assert diff == 0.0, where
    assert read_info(path)["complete"] is True
    assert os.listdir(tmp_path) == ["r.h5"]  # no temporary file left behind
    if which == "nonlinear":
        assert back.solver_result.iterations == result.solver_result.iterations
        assert back.solver_result.residuals == result.solver_result.residuals
    if which == "phased":
        assert [r["name"] for r in back.phases] == ["geostatic", "weight", "building", "half_unload"]
        # the scene's own result joins the phases' rows (each phase's after its first, its first being the
        # previous phase's last), f_int included; its status is the last phase's
        joined = back.solver_result
        assert joined.u is back.u and joined.status == back.phases[-1]["result"].status
        for record in back.phases[1:]:
            rows = joined.f_int[record["first"] : record["last"] + 1]
            assert len(rows) == record["result"].n_steps
            assert all(a is b for a, b in zip(rows, record["result"].f_int[1:]))
        # the geostatic phase's own rows came back from the file (on the controlled path, the default, a
        # dead-load-only phase is one balancing step: they are not SceneResult rows)
        assert back.phases[0]["result"].n_steps == result.phases[0]["result"].n_steps >= 1


def test_phased_file_keeps_the_phase_loads(phased, tmp_path):
    """Independent of the file: the contact carries, at the end of each phase, the loads applied by then
    (the strip's overburden of its base level 1 m x 18 kN/m^3 over 2 m, its weight 25 kN/m^3 x 0.5 m x 2 m,
    the column, half the column); the rebuilt scene of the file gives the same, and a changed number in a
    phase's own rows is found."""
    back = read_result(write_result(tmp_path / "p.h5", phased))
    expected = {
        "geostatic": 36e3,
        "weight": 36e3 + 25e3,
        "building": 61e3 + 250e3,
        "half_unload": 61e3 + 125e3,
    }
    for result in (phased, back):
        force = result.built.contact_force(result)
        for record in result.phases:
            assert force[record["last"]] == pytest.approx(expected[record["name"]], rel=1e-4), record["name"]
    res = back.phases[0]["result"]
    res.u[-1] = res.u[-1] + 1e-10
    assert max_difference(phased, back)[1] == "phases[0].solver.u"


def test_round_trip_of_a_single_phase_strip_load(tmp_path):
    scene = mc_scene()
    scene.layers[0] = SoilLayer(2.0, E=20e6, nu=0.3, unit_weight=18e3)
    scene.contact = Contact(kn=1e10, kt=1e9)
    scene.loads.append(StripLoad(10e3))
    result = scene.build().solve()
    assert max_difference(result, read_result(write_result(tmp_path / "s.h5", result)))[0] == 0.0


def test_round_trip_detects_a_changed_number(nonlinear, tmp_path):
    """The comparison can fail: one perturbed displacement is found."""
    back = read_result(write_result(tmp_path / "r.h5", nonlinear))
    back.u[-1] = back.u[-1].copy()
    back.u[-1][5] += 1e-9
    diff, where = max_difference(nonlinear, back)
    assert diff >= 0.999e-9 and where


def test_no_overwrite_and_atomic_failure(nonlinear, tmp_path):
    path = write_result(tmp_path / "r.h5", nonlinear)
    before = path.read_bytes()
    with pytest.raises(FileExistsError):
        write_result(path, nonlinear)
    with pytest.raises(RuntimeError), atomic_path(path, overwrite=True) as tmp:
        tmp.write_bytes(b"half a file")
        raise RuntimeError("crash while writing")
    assert path.read_bytes() == before and os.listdir(tmp_path) == ["r.h5"]


def test_stopped_run_is_written_incomplete(tmp_path):
    """Far beyond the bearing capacity, with the paper's equal steps and one step cut allowed, the solver
    stops before the path has flattened (a failure, not a detected collapse); the file keeps the converged
    steps and says so."""
    built = mc_scene(N=3e6, H=0.0).build()
    with pytest.raises(NonConvergence) as info:
        built.solve(n_steps=2, settings=Settings.paper(max_iter=40, max_cuts=1))
    r = info.value.result
    partial = SceneResult(built, r)
    path = write_result(tmp_path / "stop.h5", partial, stop=info.value.report)
    meta = read_info(path)
    assert meta["complete"] is False and meta["stop"]["reason"] == info.value.report["reason"]
    back = read_result(path)
    assert back.load_factor[-1] == r.load_factor[-1] < 1.0
    assert max_difference(partial, back)[0] == 0.0


def test_collapsed_run_is_complete_and_keeps_its_limit_load(collapsed, tmp_path, capsys):
    """With the default settings the same overload ends as a detected limit load: a complete answer, whose
    status and limit load factor come back from the file; ``ssi show`` reports it as a limit load (exit 0),
    not as a stopped run."""
    out = collapsed
    assert out.status == "limit load reached"
    path = write_result(tmp_path / "collapse.h5", out)
    assert read_info(path)["complete"] is True
    back = read_result(path)
    assert back.status == out.status and back.limit_load_factor == out.limit_load_factor
    assert max_difference(out, back)[0] == 0.0
    assert main(["show", str(path), "--no-plots"]) == 0
    text = capsys.readouterr().out
    assert f"limit load       reached at load factor {out.limit_load_factor:.4g}" in text
    assert "INCOMPLETE" not in text and "stopped" not in text
    s = summary(back)
    assert s["status"] == "limit load reached" and s["limit_load_factor"] == out.limit_load_factor < 1.0
    assert (
        s["column_load"] == pytest.approx(3e6 * out.load_factor[-1]) and s["stopped_at_column_load"] is None
    )


# ---- scene files ---------------------------------------------------------------------------------------
def test_toml_maps_onto_the_dataclasses():
    scene, n_steps, settings = read_scene_file(os.path.join(EXAMPLES, "strip_mohr_coulomb.toml"))
    assert scene_to_dict(scene) == scene_to_dict(mc_scene())
    assert n_steps == 4 and settings.force_tol == 1e-6
    assert scene_to_dict(scene_from_dict(scene_to_dict(scene))) == scene_to_dict(scene)
    scene, n_steps, _ = read_scene_file(os.path.join(EXAMPLES, "phased_embedded.toml"))
    assert scene_to_dict(scene) == scene_to_dict(phased_scene()) and n_steps is None  # automatic stepping
    assert scene.phases == phased_scene().phases and scene.layers == phased_scene().layers


def every_feature_scene():
    """A scene using every field the scene file knows: each load type, phases with factors and n_steps,
    contact segments, a water table, embedment, an undrained-A layer and a total-stress undrained one."""
    return Scene(
        width=12.0,
        depth=6.0,
        layers=[
            SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3, K0=0.6, scheme="explicit"),
            SoilLayer(
                2.0,
                E=30e6,
                nu=0.3,
                unit_weight=19e3,
                unit_weight_sat=20e3,
                c=5e3,
                phi_deg=25.0,
                psi_deg=0.0,
                drainage="undrained_A",
                nu_u=0.49,
            ),
            SoilLayer.undrained(3.0, E_u=20e6, s_u=30e3, unit_weight=18e3, unit_weight_sat=19e3),
        ],
        foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2), self_weight=1e3),
        contact=[
            ContactSegment(-1.0, 0.25, Contact(kn=1e10, kt=0.0)),
            ContactSegment(0.25, 1.0, Contact(kn=1e10, kt=1e9, phi_deg=25.0, c=1e3, sig_t=0.0)),
        ],
        loads=[ColumnLoad(0.0, N=100e3, M=5e3)],
        surcharge=5e3,
        embedment=1.0,
        water_table=1.5,
        gamma_w=10e3,
        mesh=MeshSize(0.5, 2.0, 1.5, 3),
        phases=[
            Phase("weight", (StripWeight(24e3), StripLoad(10e3, q_end=2e3, x0=-0.5, x1=0.75)), n_steps=2),
            Phase("beside", (SurfacePressure(3.0, 5.0, 15e3), Settlement(0.01, x=(0.0,)))),
            Phase("push", (Settlement(0.02),), factors={"loads": 0.0, "beside": 0.5}),
        ],
    )


SEGMENTS_TOML = """
width = 12.0
depth = 6.0
embedment = 1.0
water_table = 1.5
[[layers]]
thickness = 1.0
E = 10e6
nu = 0.3
[[layers]]
thickness = 5.0
E = 30e6
nu = 0.3
drainage = "undrained_A"
nu_u = 0.49
[foundation]
x0 = -1.0
x1 = 1.0
section = { homogeneous = { thickness = 0.5, E = 30e9, nu = 0.2 } }
[[contact]]
x0 = -1.0
x1 = 0.25
contact = { kn = 1e10, kt = 0.0 }
[[contact]]
x0 = 0.25
x1 = 1.0
[contact.contact]
kn = 1e10
kt = 1e9
phi_deg = 25.0
[[loads]]
x = 0.0
N = 100e3
[[phases]]
name = "push"
factors = { loads = 0.0 }
n_steps = 3
[[phases.loads]]
type = "Settlement"
w = 0.01
x = [0.0]
[solve]
n_steps = 2
"""


def test_every_feature_survives_dict_and_json(tmp_path):
    """scene -> plain dict -> JSON (what result files store) -> scene gives the same dataclasses back."""
    scene = every_feature_scene()
    back = scene_from_dict(json.loads(json.dumps(scene_to_dict(scene))))
    for name in (
        "layers",
        "contact",
        "loads",
        "phases",
        "mesh",
        "surcharge",
        "embedment",
        "water_table",
        "gamma_w",
        "width",
        "depth",
    ):
        assert getattr(back, name) == getattr(scene, name), name
    assert scene_to_dict(back) == scene_to_dict(scene)
    assert [ld["type"] for ld in scene_to_dict(scene)["phases"][1]["loads"]] == [
        "SurfacePressure",
        "Settlement",
    ]
    built = scene.build()
    assert built.model.info["scene"] is scene  # the model keeps the scene; the file gets its plain form
    path = write_result(tmp_path / "phased.h5", built.model.solve_linear())
    assert read_result(path).model["scene"] == scene_to_dict(scene)


def test_toml_contact_segments_phases_and_settlement(tmp_path):
    path = tmp_path / "segments.toml"
    path.write_text(SEGMENTS_TOML)
    scene, n_steps, _ = read_scene_file(path)
    assert n_steps == 2
    assert scene.contact == [
        ContactSegment(-1.0, 0.25, Contact(kn=1e10, kt=0.0)),
        ContactSegment(0.25, 1.0, Contact(kn=1e10, kt=1e9, phi_deg=25.0)),
    ]
    assert scene.phases == [Phase("push", (Settlement(0.01, x=(0.0,)),), factors={"loads": 0.0}, n_steps=3)]
    assert scene.loads == [ColumnLoad(0.0, N=100e3)] and scene.embedment == 1.0 and scene.water_table == 1.5
    assert scene.layers[1] == SoilLayer(5.0, E=30e6, nu=0.3, drainage="undrained_A", nu_u=0.49)


@pytest.mark.parametrize(
    "text, key",
    [
        ("widht = 3.0\n", "widht"),
        ("width = 12.0\ndepth = 6.0\n[[loads]]\ntype = 'Column'\nx = 0.0\n", "Column"),
        (
            "width = 12.0\ndepth = 6.0\n[[loads]]\ntype = 'SurfacePressure'\nx0 = 1.0\nx1 = 2.0\nN = 1e3\n",
            "N",
        ),
        (
            (
                "width = 12.0\ndepth = 6.0\n[[phases]]\nname = 'a'\n"
                "[[phases.loads]]\ntype = 'StripWeight'\ngamma = 1.0\n"
            ),
            "gamma",
        ),
        ("width = 12.0\ndepth = 6.0\n[[contact]]\nx0 = 0.0\nx1 = 1.0\nkn = 1e10\n", "kn"),
        ("width = 12.0\ndepth = 6.0\n[solve]\nn_steps = 0\n", "n_steps"),
        ("width = 12.0\ndepth = 6.0\n[[layers]]\nthickness = 2.0\nE = 1e7\nnu = 0.3\nphi = 30.0\n", "phi"),
        ("width = 12.0\ndepth = 6.0\n[solve]\nmethd = 'full'\n", "methd"),
    ],
)
def test_unknown_keys_are_refused_by_name(tmp_path, text, key):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=repr(key)):
        read_scene_file(path)


def test_every_field_has_a_unit():
    """Every field of every dataclass a scene or a site is made of -- found in ssi.scene, so a new one is
    caught -- has an entry in UNITS (what `ssi schema` prints), and UNITS names no field that does not
    exist."""
    import dataclasses
    import inspect

    import ssi.scene as scene_module  # the face: every class a scene is made of

    runtime = {"BuiltScene", "SceneResult", "BuiltSite", "SiteResult"}  # built, not written in a file
    classes = [
        c
        for _, c in inspect.getmembers(scene_module, inspect.isclass)
        if dataclasses.is_dataclass(c) and c.__module__.startswith("ssi.scene.") and c.__name__ not in runtime
    ]
    assert {"Scene", "Phase", "ContactSegment", "Settlement", "SurfacePressure", "Site", "Borehole", "Strip",
            "RigidStrip", "DepthVarying"} <= {c.__name__ for c in classes}  # fmt: skip
    for cls in classes:
        assert set(UNITS[cls.__name__]) == {f.name for f in dataclasses.fields(cls)}, cls.__name__
    assert set(LOAD_TYPES) == {
        "ColumnLoad",
        "SurfacePressure",
        "StripLoad",
        "StripWeight",
        "Settlement",
        "Push",
    }


# ---- ParaView export -----------------------------------------------------------------------------------
def test_vtu_reads_back(nonlinear, tmp_path):
    path = export_vtu(nonlinear, tmp_path / "r.vtu")
    mesh = read_vtu(path)
    built = nonlinear.built
    # meshio's VTU reader merges the adjacent line3 blocks: strip elements, then contact elements
    assert [c.type for c in mesh.cells] == ["quad8", "line3"]
    assert np.array_equal(mesh.cells[0].data, built.mesh.conn)
    assert len(mesh.cells[1].data) == built.plate.n_el + built.interface.n_el
    u = nonlinear.u[-1]
    soil = np.arange(built.mesh.xy.shape[0])
    assert np.max(np.abs(mesh.point_data["displacement"][soil, 1] - u[built.model.dof(soil, "w")])) <= 1e-12
    sig = nonlinear.soil_stress().mean(axis=1)
    assert np.max(np.abs(mesh.cell_data["szz"][0] - sig[:, 1])) <= 1e-12 * np.abs(sig).max()
    m = nonlinear.strip_forces()["M"].mean(1)
    assert np.max(np.abs(mesh.cell_data["M"][1][: len(m)] - m)) <= 1e-12 * np.abs(m).max()
    p = -nonlinear.contact()["sig_n"].mean(1)
    assert np.max(np.abs(mesh.cell_data["contact_pressure"][1][len(m) :] - p)) <= 1e-12 * np.abs(p).max()
    # units as field data, one per exported field, and every soil element of a single-phase scene present
    assert {f"unit_{name}" for name in [*mesh.point_data, *mesh.cell_data]} <= set(mesh.field_data)
    assert str(mesh.field_data["unit_szz"][0]) == "Pa" and str(mesh.field_data["unit_M"][0]) == "N m/m"
    assert np.all(mesh.cell_data["active"][0] == 1.0)
    with pytest.raises(FileExistsError):
        export_vtu(nonlinear, path)


def test_vtu_pore_pressure_of_a_water_table(phased, tmp_path):
    """The exported pore pressure of the phased scene (drained, water table 2 m deep) is the hydrostatic
    gamma_w (depth - 2 m) averaged over each element's points, by hand from the stored point depths."""
    mesh = read_vtu(export_vtu(phased, tmp_path / "p.vtu"))
    depth = -phased.soil_points()[..., 1]
    by_hand = (9.81e3 * np.maximum(depth - 2.0, 0.0)).mean(axis=1)
    exported = mesh.cell_data["pore_pressure"][0]
    assert by_hand.max() > 9.81e3 * 2.0  # the lowest elements' points lie more than 4 m deep on average
    assert np.all(exported[(depth <= 2.0).all(axis=1)] == 0.0)  # dry above the table
    assert np.max(np.abs(exported - by_hand)) <= 1e-12 * by_hand.max()


def test_phased_series_is_numbered_by_step(phased, tmp_path):
    """The phased result's first two states share phase time 0: the series counts steps instead, and its
    last data set is the last step."""
    series = read_series(export_series(phased, tmp_path / "p.pvd"))
    assert [t for t, _ in series] == list(range(len(phased.load_factor)))
    assert [float(m.field_data["time"][0]) for _, m in series] == list(range(len(phased.load_factor)))
    w = phased.u[-1][phased.built.model.dof(phased.built.plate_nodes, "w")]
    assert np.max(np.abs(series[-1][1].point_data["displacement"][phased.built.plate_nodes, 1] - w)) <= 1e-12


def test_series_every_step_reads_back(nonlinear, tmp_path):
    path = export_series(nonlinear, tmp_path / "r.pvd")
    assert sorted(os.listdir(tmp_path)) == ["r.pvd", "r_steps"]
    series = read_series(path)
    times = [t for t, _ in series]
    # the time values are the load factors without binary noise (0.47500000000000003 was written before):
    # equal to 1e-12, and each written with at most 12 significant digits
    assert np.allclose(times, nonlinear.load_factor, rtol=1e-12, atol=0.0)
    assert any(repr(float(x)) != repr(t) for x, t in zip(nonlinear.load_factor, times))  # noise was there
    assert all(len(repr(t).replace("0.", "").lstrip("0")) <= 13 for t in times)
    text = path.read_text()
    assert "0000000" not in text and "9999999" not in text
    soil = np.arange(nonlinear.built.mesh.xy.shape[0])
    for k, (_, mesh) in enumerate(series):
        w = nonlinear.u[k][nonlinear.built.model.dof(soil, "w")]
        assert np.max(np.abs(mesh.point_data["displacement"][soil, 1] - w)) <= 1e-12


# ---- plots, progress, command line ---------------------------------------------------------------------
def test_every_plot_returns_a_figure(nonlinear, tmp_path):
    back = read_result(write_result(tmp_path / "r.h5", nonlinear))  # replots without the script
    figs = plot.standard_figures(back)
    assert {
        "settlement",
        "contact",
        "strip_forces",
        "plastic_points",
        "load_settlement",
        "deformed_mesh",
    } <= set(figs)
    assert "mechanism" not in figs  # a load-controlled run that carried its loads has no collapse to show
    for fig in figs.values():
        assert isinstance(fig, matplotlib.figure.Figure) and fig.axes
        matplotlib.pyplot.close(fig)


def test_progress_is_quiet_in_tests_and_draws_when_asked(capsys):
    import io

    assert progress_enabled(None) is False  # PYTEST_CURRENT_TEST is set
    stream = io.StringIO()
    with solver_progress(True, total=1.0, stream=stream) as bar:
        bar.update(1, 0.5, 3, 1e-7)
        bar.update(2, 1.0, 2, 1e-8)
    assert "step 2" in stream.getvalue() and "1.000" in stream.getvalue()
    with solver_progress(None, total=1.0) as bar:
        bar.update(1, 1.0, 1, 0.0)
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("name", sorted(f for f in os.listdir(EXAMPLES) if f.endswith(".toml")))
def test_cli_runs_the_examples(name, tmp_path, capsys):
    scene_path = tmp_path / name
    with open(os.path.join(EXAMPLES, name)) as fh:
        scene_path.write_text(fh.read())
    # the verdict first (a loose gap keeps it cheap here: its content is tested in test_verdict.py)
    assert main(["run", str(scene_path), "--no-plots", "--capacity-gap", "0.25"]) == 0
    printed = capsys.readouterr().out
    assert "max settlement" in printed and printed.startswith("VERDICT")
    stored = json.loads((tmp_path / (scene_path.stem + "_summary.json")).read_text())
    assert next(iter(stored)) == "verdict" and stored["verdict"]["line"]
    scene, n_steps, settings = read_scene_file(scene_path)
    direct = summary(scene.build().solve(n_steps=n_steps, settings=settings))  # the Python API
    for key in (
        "max_settlement",
        "max_contact_pressure",
        "max_abs_moment",
        "contact_resultant",
        "complete",
        "status",
        "phase",
        "phase_load_factor",
        "column_load",
        "foundation_load",
        "capacity",
        "envelope",
        "phases",
    ):
        assert stored.get(key) == direct.get(key), key  # a RigidFooting's has no contact pressure
    assert (tmp_path / (scene_path.stem + "_report.html")).exists()
    assert main(["run", str(scene_path), "--no-plots"]) == 2  # outputs exist: refused
    assert main(["show", str(tmp_path / (scene_path.stem + ".h5")), "--json", "--no-plots"]) == 0
    shown = json.loads(capsys.readouterr().out.split("\n}")[0] + "\n}")
    assert shown["max_settlement"] == stored["max_settlement"]
    assert shown["verdict"]["line"] == stored["verdict"]["line"]  # kept by the result file


def test_show_right_after_run_reprints_and_redraws(tmp_path, capsys):
    """``ssi show x.h5`` right after ``ssi run x.toml``: the summary again and the figures in a new folder
    (the run's are kept); ``--overwrite`` redraws into the run's folder; a figure folder given explicitly
    that holds the figures is refused naming the flag ``--overwrite``, not the Python keyword."""
    scene_path = tmp_path / "strip_linear.toml"
    scene_path.write_text(open(os.path.join(EXAMPLES, "strip_linear.toml")).read())
    assert main(["run", str(scene_path)]) == 0
    ran = capsys.readouterr().out
    h5 = tmp_path / "strip_linear.h5"
    first = sorted(p.name for p in (tmp_path / "strip_linear_plots").iterdir())
    before = (tmp_path / "strip_linear_plots" / "settlement.png").stat().st_mtime_ns
    assert main(["show", str(h5)]) == 0
    shown = capsys.readouterr().out
    # the summary lines but the wall time (of the solve as stored, not build + solve)
    summary_lines = [ln for ln in ran.splitlines() if not ln.startswith(("wall time", "wrote"))]
    assert [ln for ln in shown.splitlines() if not ln.startswith(("wall time", "wrote"))] == summary_lines
    assert sorted(p.name for p in (tmp_path / "strip_linear_plots_2").iterdir()) == sorted(
        [*first, "report.html"]
    )
    assert f"wrote {tmp_path / 'strip_linear_plots_2' / 'settlement.png'}" in shown
    assert main(["show", str(h5)]) == 0 and (tmp_path / "strip_linear_plots_3").is_dir()
    capsys.readouterr()
    assert main(["show", str(h5), "--overwrite"]) == 0
    assert (tmp_path / "strip_linear_plots" / "settlement.png").stat().st_mtime_ns >= before
    assert not (tmp_path / "strip_linear_plots_4").exists()
    capsys.readouterr()
    assert main(["show", str(h5), "--plots", str(tmp_path / "strip_linear_plots")]) == 2
    err = capsys.readouterr().err
    assert "pass --overwrite to replace it" in err and "overwrite=True" not in err


def test_compile_notice_only_on_an_empty_cache(tmp_path, monkeypatch):
    import io

    from ssi.solver import progress

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(progress, "_announced", False)
    stream = io.StringIO()
    assert progress.announce_compilation(stream, estimate_s=60) is True
    assert stream.getvalue().startswith("ssi: compiling kernels once, ~60 s")
    assert progress.announce_compilation(stream) is False  # once per process
    monkeypatch.setattr(progress, "_announced", False)
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "kernel-1.py311.nbi").write_bytes(b"")
    assert progress.announce_compilation(io.StringIO()) is False  # kernels cached: silent


def test_compile_notice_from_the_python_api(tmp_path, monkeypatch, capsys):
    """Building a scene from Python (no ``ssi run``) prints the one-line notice on a cold cache, once."""
    from ssi.solver import progress

    monkeypatch.setattr(progress, "numba_cache_is_empty", lambda cache_dir=None: True)
    monkeypatch.setattr(progress, "_announced", False)
    mc_scene().build()
    mc_scene().build()
    err = capsys.readouterr().err
    assert err.count("ssi: compiling kernels once") == 1 and err.count("\n") == 1


@pytest.mark.parametrize("mask", [0o022, 0o077, 0o002])
def test_files_get_the_users_umask(nonlinear, tmp_path, mask):
    """Result, ParaView and figure files are created as open() would create them under the umask (mkstemp
    alone made them 0600, unreadable to a team on a shared drive); the writes stay atomic."""
    old = os.umask(mask)
    try:
        written = [write_result(tmp_path / "r.h5", nonlinear), export_vtu(nonlinear, tmp_path / "r.vtu")]
        with atomic_path(tmp_path / "t.txt") as tmp:
            tmp.write_text("x")
        written.append(tmp_path / "t.txt")
    finally:
        os.umask(old)
    for path in written:
        assert os.stat(path).st_mode & 0o777 == 0o666 & ~mask, path


def test_no_resource_warning_from_the_blas_guard():
    """The scratch files that catch BLAS's C-level text are raw descriptors: a process that used them ends
    without "ResourceWarning: unclosed file" (it did with tempfile.TemporaryFile objects)."""
    import subprocess
    import sys

    code = (
        "import sys; from ssi.core import linsolve; "
        "out, text = linsolve._trap_c_output(lambda: sys.stdout.write('') or 7); "
        "assert out == 7 and text == ''"
    )
    run = subprocess.run(
        [sys.executable, "-X", "dev", "-W", "always::ResourceWarning", "-c", code],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, run.stderr
    assert "ResourceWarning" not in run.stderr


def test_bare_model_file_keeps_mapping_access(nonlinear, tmp_path):
    """A solver Result (no scene) reads back as StoredResult; the earlier dict keys still work."""
    res = nonlinear.solver_result
    back = read_result(write_result(tmp_path / "m.h5", res))
    assert np.array_equal(back["u"], np.array(res.u)) and np.array_equal(back.f_int, np.array(res.f_int))
    assert list(back["state"]) == ["soil_q8", "plate", "interface"]
    assert np.array_equal(back["state"]["interface"][-1], res.states[-1][2])
    assert np.array_equal(back.conn["soil_q8"], nonlinear.built.mesh.conn)


def test_rc_section_table_equals_the_python_section():
    """examples/rc_strip.toml's `rc` section is chapter 11's rc_section built in Python, layer for layer."""
    from ssi.elements.section import rc_section
    from ssi.materials.layer_laws import CONCRETE, STEEL
    from ssi.materials.rc import concrete_params, designer_concrete, steel_params

    d = designer_concrete(38e6)
    concrete = (CONCRETE, concrete_params(38e6, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, 500e6 / 200e9))
    python = rc_section(
        0.4, [(0.05, 1.5e-3), (0.35, 1.5e-3)], concrete, (STEEL, steel_params(500e6, 200e9)), n_concrete=9
    )
    scene, _, settings = read_scene_file(os.path.join(EXAMPLES, "rc_strip.toml"))
    assert scene_to_dict(scene)["foundation"]["section"] == scene_to_dict(Foundation(0, 1, python))["section"]
    assert settings.control == "work" and len(scene.loads) == 2  # the default: the controlled path


def test_cli_writes_a_stopped_run_marked_incomplete(tmp_path, capsys):
    with open(os.path.join(EXAMPLES, "strip_mohr_coulomb.toml")) as fh:
        text = (
            fh.read()
            .replace("N = 300e3", "N = 3e6")
            .replace(
                "n_steps = 4",
                "n_steps = 2\nmax_iter = 40\nmax_cuts = 1\nmethod = 'modified'\nstepping = 'fixed'",
            )
        )
    scene_path = tmp_path / "overload.toml"
    scene_path.write_text(text)
    assert main(["run", str(scene_path), "--no-plots"]) == 3
    printed = capsys.readouterr().out
    assert "INCOMPLETE" in printed
    info = read_info(tmp_path / "overload.h5")
    assert info["complete"] is False and info["stop"]["reason"]
    s = json.loads((tmp_path / "overload_summary.json").read_text())
    assert s["stopped_at_column_load"] < 3e6 and s["stop_reason"] == info["stop"]["reason"]
    # the soil (psi = 0 < phi) yields where it stopped: the summary and the printout say its rate problem is
    # ill-posed there, with the material's ratio (diagnostics.ill_posed_soil)
    assert s["stop_ill_posed"] == info["stop"]["ill_posed"] and "lost ellipticity" in s["stop_ill_posed"]
    assert "ill-posed soil" in printed and "Davis mode" in printed
    # what it carried is not offered as a capacity, and the report says the run stopped
    assert not s["capacity"]["is_limit"] and "solver stopped" in s["capacity"]["how"]
    assert s["capacity"]["load"] == pytest.approx(s["stopped_at_column_load"], rel=1e-14)
    html = (tmp_path / "overload_report.html").read_text()
    assert "The run stopped before the end of its load path" in html
    assert "rate problem is ill-posed: " in html


# ---- files of the earlier layout -----------------------------------------------------------------------
OLD_RESULTS = os.path.join(os.path.dirname(__file__), "data", "old_results")
OLD_MESH = MeshSize(h_fine=1.0, h_coarse=3.0, growth=2.0)


def old_linear_scene():
    """The linear scene of tests/data/old_results (see its README)."""
    scene = mc_scene()
    scene.layers[0] = SoilLayer(2.0, E=20e6, nu=0.3, unit_weight=18e3)
    scene.contact = Contact(kn=1e10, kt=1e9)
    scene.mesh = OLD_MESH
    return scene


def stored(name, *keys):
    with h5py.File(os.path.join(OLD_RESULTS, name), "r") as h5:
        return [h5[k][...] for k in keys]


def test_files_of_the_earlier_layout_still_read(tmp_path):
    """Files written before a linear solve and a scene result were solver Results (commit 3ddd0b2,
    tests/data/old_results/README.md) read: their stored rows come back bit for bit; what the old layout did
    not store is rebuilt and checked against independent references -- a fresh linear solve of the same
    scene (one factorisation each: round-off, 1e-9 of the largest value), the statics of the loads (the
    column's 300 kN/m; each phase's loads as in test_phased_file_keeps_the_phase_loads, rel 1e-4, the
    solver's force tolerance) -- and the upgraded result writes and reads back exactly."""
    fresh = old_linear_scene().build().model.solve_linear()
    # a bare model's LinearResult: the arrays as stored (it kept no internal force)
    back = read_result(os.path.join(OLD_RESULTS, "linear_model.h5"))
    u, reactions = stored("linear_model.h5", "steps/u", "solver/reactions")
    assert np.array_equal(back.u, u) and back.f_int is None and list(back.load_factor) == [0.0, 1.0]
    assert np.abs(u[-1] - fresh.u[-1]).max() <= 1e-9 * np.abs(fresh.u[-1]).max()
    assert np.abs(reactions - fresh.reactions()).max() <= 1e-9 * np.abs(fresh.f_int[-1]).max()
    # a linear scene without a /solver group: a linear solve's Result, its internal force evaluated
    back = read_result(os.path.join(OLD_RESULTS, "linear_scene.h5"))
    (u,) = stored("linear_scene.h5", "steps/u")
    res = back.solver_result
    assert np.array_equal(np.array(back.u), u) and res.load_factor == [0.0, 1.0] and res.iterations == [0, 1]
    assert np.abs(res.f_int[-1] - fresh.f_int[-1]).max() <= 1e-9 * np.abs(fresh.f_int[-1]).max()
    assert np.abs(res.reactions() - fresh.reactions()).max() <= 1e-9 * np.abs(fresh.f_int[-1]).max()
    assert back.contact_resultant()["N"] == pytest.approx(300e3, rel=1e-9)
    again = read_result(write_result(tmp_path / "linear.h5", back))
    assert max_difference(back, again) == (0.0, "")  # the unstored wall time reads as nan both times
    # a phased scene with the attribute solver_phase: its phases joined as for a new file
    back = read_result(os.path.join(OLD_RESULTS, "phased_scene.h5"))
    lam, u = stored("phased_scene.h5", "steps/load_factor", "steps/u")
    assert np.array_equal(back.load_factor, lam) and np.array_equal(np.array(back.u), u)
    assert [r["name"] for r in back.phases] == ["geostatic", "weight", "building", "half_unload"]
    assert back.status == "completed" and back.solver_result.u is back.u
    expected = {"geostatic": 36e3, "weight": 61e3, "building": 311e3, "half_unload": 186e3}
    force = back.built.contact_force(back)
    for record in back.phases:
        assert force[record["last"]] == pytest.approx(expected[record["name"]], rel=1e-4), record["name"]
    again = read_result(write_result(tmp_path / "phased.h5", back))
    assert max_difference(back, again) == (0.0, "")


# ---- what an engineer reads (issue 34): loads, capacity, phases, contact pressure ----------------------
def test_phased_column_load_is_the_phases_columns(phased):
    """The column load of every row of the phased scene, by hand from its phases: 0 in the geostatic and
    'weight' phases, 250 kN/m ramped over 'building', back to 125 kN/m (factor 0.5) over 'half_unload'."""
    col = phased.column_load()
    by_name = {r["name"]: r for r in phased.phases}
    assert np.all(col[: by_name["weight"]["last"] + 1] == 0.0)
    b, h = by_name["building"], by_name["half_unload"]
    lam_b = np.asarray(b["result"].load_factor[1:])
    assert np.allclose(col[b["first"] : b["last"] + 1], 250e3 * lam_b, rtol=1e-14, atol=0.0)
    lam_h = np.asarray(h["result"].load_factor[1:])
    assert np.allclose(col[h["first"] : h["last"] + 1], 250e3 - 125e3 * lam_h, rtol=1e-14, atol=0.0)
    assert col[-1] == pytest.approx(125e3, rel=1e-14)
    assert np.array_equal(phased.load_settlement()["load"], col)  # load-controlled: the load is the columns


def test_phased_summary_gives_each_phase_and_the_envelope(phased):
    """examples/phased_embedded.toml: the largest settlement (end of 'building') is in the summary, not only
    the smaller one at the end; each phase's values are its rows' maxima, computed here row by row."""
    from ssi.io.cli import summary_text

    s = summary(phased)
    n = len(phased.load_factor)
    per_row = [phased.max_settlement(k)[1] for k in range(n)]
    env = s["envelope"]["max_settlement"]
    assert env["value"] == max(per_row) and env["phase"] == "building"
    assert env["value"] > 1.5 * s["max_settlement"]  # 6.77 mm against 4.24 mm at the end
    for row in s["phases"]:
        rows = range(row["first"], row["last"] + 1)
        assert row["max_settlement"] == max(per_row[k] for k in rows)
        m = max(float(np.abs(phased.strip_forces(k)["M"]).max()) for k in rows)
        assert row["max_abs_moment"] == m
    assert [r["name"] for r in s["phases"]] == ["weight", "building", "half_unload"]
    assert s["column_load"] == pytest.approx(125e3, rel=1e-14)
    text = summary_text(s)
    assert f"{1e3 * env['value']:.3f} mm largest over the phases (phase 'building')" in text
    assert "half_unload" in text and "building" in text


def test_phased_load_settlement_plot_shows_the_load(phased):
    fig = plot.load_settlement(phased)
    ax = fig.axes[0]
    assert ax.get_ylabel() == "column load [kN/m]"
    ys = np.concatenate([line.get_ydata() for line in ax.lines if len(line.get_ydata()) > 1])
    assert ys.max() == pytest.approx(250.0, rel=1e-12)  # kN/m: the building's column, not a phase time
    matplotlib.pyplot.close(fig)


def test_contact_pressure_mean_peak_and_corner(nonlinear):
    """Mean = contact resultant / B (B = 2 m, by hand); the headline peak leaves out the points within
    B/10 of the edges; the corner value is the largest anywhere and is printed as a singularity, after
    the mean and the peak."""
    from ssi.io.cli import summary_text

    cp = nonlinear.contact_pressure()
    c = nonlinear.contact()
    x, p = c["x"].ravel(), -c["sig_n"].ravel()
    assert cp["mean"] == pytest.approx(nonlinear.contact_resultant()["N"] / 2.0, rel=1e-14)
    inner = np.minimum(np.abs(x + 1.0), np.abs(1.0 - x)) > 0.2
    assert cp["peak"] == p[inner].max() and cp["edge"] == p.max()
    assert cp["edge"] > cp["peak"] > cp["mean"]
    text = summary_text(summary(nonlinear))
    assert text.index("kPa mean") < text.index("corner singularity")
    assert f"{cp['edge'] / 1e3:.2f} kPa" in text.split("edge pressure")[1].splitlines()[0]


def test_capacity_of_a_viscous_path_leaves_the_viscous_rows_out(viscous):
    """Rows solved with a viscosity carry overstress: never offered as the largest load."""
    visc = np.asarray(viscous.solver_result.step_viscosity)
    cap = viscous.capacity()
    assert cap["viscous_rows"] == int((visc > 0).sum()) > 0
    assert visc[cap["step"]] == 0.0
    ok = viscous.load_settlement()["equilibrium"]
    assert np.array_equal(ok, visc == 0.0)


def test_capacity_of_a_detected_limit(collapsed):
    """Ten times the bearing capacity: the solver's limit load, marked as a limit, is the capacity."""
    cap = collapsed.capacity()
    assert cap["is_limit"] and cap["how"].startswith("limit load detected by the solver")
    lam = np.asarray(collapsed.load_factor)
    ok = collapsed.equilibrium_rows()
    assert cap["load"] == pytest.approx(3e6 * lam[ok].max(), rel=1e-14)
    assert summary(collapsed)["capacity"] == cap


def test_run_writes_an_html_report_that_needs_no_network(tmp_path):
    """The report of the phased example: the summary with units, the per-phase table with the envelope,
    the warnings, and every figure linked relative to the page and present; no URL that leaves the machine
    (no script, no stylesheet from a CDN)."""
    import re

    from ssi.io.cli import run_scene_file

    scene_path = tmp_path / "phased_embedded.toml"
    scene_path.write_text(open(os.path.join(EXAMPLES, "phased_embedded.toml")).read())
    _, s, written = run_scene_file(scene_path)
    page = tmp_path / "phased_embedded_report.html"
    assert page in written
    text = page.read_text()
    srcs = re.findall(r'<img src="([^"]+)"', text)
    pngs = sorted(p for p in written if p.suffix == ".png")
    assert sorted(tmp_path / src for src in srcs) == pngs and all(not os.path.isabs(x) for x in srcs)
    assert "http://" not in text and "https://" not in text and "<script" not in text
    for label in ("largest settlement at the end", "contact pressure, mean", "Per phase", "Envelope"):
        assert label in text, label
    assert "<td>mm</td>" in text and "<td>kPa</td>" in text and "[kN/m]" in text
    env = s["envelope"]["max_settlement"]
    assert f"{1e3 * env['value']:.3f}</td><td>mm</td><td>building</td>" in text
    assert "corner" in text  # the edge pressure is labelled a singularity among the warnings


def test_readme_run_output_is_what_ssi_run_prints(tmp_path, capsys):
    """The README's printed ``ssi run examples/strip_mohr_coulomb.toml`` output, every line above the wall
    time (which varies with the machine), is what the command prints now (it had drifted: 4 -> 6 steps,
    336.31 -> 336.29 kPa)."""
    import re

    readme = open(os.path.join(os.path.dirname(__file__), "..", "README.md")).read()
    block = re.search(r"ssi run examples/strip_mohr_coulomb\.toml.*?\n```\n```\n(.*?)```", readme, re.S)
    seconds = re.compile(r", [0-9.]+ s\)$")  # the limit analyses' wall times vary with the machine too
    documented = [seconds.sub(", T s)", x) for x in block.group(1).split("wall time")[0].splitlines()]
    scene_path = tmp_path / "strip_mohr_coulomb.toml"
    scene_path.write_text(open(os.path.join(EXAMPLES, "strip_mohr_coulomb.toml")).read())
    assert main(["run", str(scene_path), "--no-plots"]) == 0
    printed = capsys.readouterr().out.split("wall time")[0].splitlines()
    assert [seconds.sub(", T s)", x) for x in printed] == documented


def test_readme_images_exist_in_a_fresh_clone():
    """Every image the README shows is a file under version control (a fresh clone has it; figures/ is
    made by `make reproduce` only)."""
    import re
    import subprocess

    root = os.path.join(os.path.dirname(__file__), "..")
    images = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", open(os.path.join(root, "README.md")).read())
    assert images
    for image in images:
        assert not image.startswith("figures/"), image
        assert os.path.isfile(os.path.join(root, image)), image
        tracked = subprocess.run(
            ["git", "ls-files", "--error-unmatch", image], cwd=root, capture_output=True, check=False
        )
        if tracked.returncode not in (0, 1):  # not a git checkout (an sdist): the file's presence is the test
            continue
        assert tracked.returncode == 0, f"{image} is not committed"


def test_rc_strip_export_has_steel_stress_and_cracks(tmp_path):
    """examples/rc_strip.toml: the VTU's steel_stress of each strip element is the largest |stress| of its
    bars (from steel_stress(), computed here point by point) and cracked_fraction the share of its cracked
    concrete layer points (from crack_map()); the summary's per-phase steel stress is the same maximum."""
    from ssi.materials.layer_laws import CONCRETE

    scene, n_steps, settings = read_scene_file(os.path.join(EXAMPLES, "rc_strip.toml"))
    out = scene.build().solve(n_steps=n_steps, settings=settings)
    mesh = read_vtu(export_vtu(out, tmp_path / "rc.vtu"))
    n_plate = out.built.plate.n_el
    st = out.steel_stress()
    by_element = np.abs(st["sig"]).reshape(n_plate, -1).max(axis=1)
    assert np.array_equal(mesh.cell_data["steel_stress"][1][:n_plate], by_element)
    cm = out.crack_map()
    concrete = out.built.plate.section.kind == CONCRETE
    share = cm["cracked"][..., concrete].reshape(n_plate, -1).mean(axis=1)
    assert np.array_equal(mesh.cell_data["cracked_fraction"][1][:n_plate], share) and share.max() > 0.0
    assert str(mesh.field_data["unit_steel_stress"][0]) == "Pa"
    # the file's crack width of each strip element is the widest at its axial points (crack_width())
    w_el = out.crack_width()["w_k"].max(axis=1)
    assert np.array_equal(mesh.cell_data["crack_width"][1][:n_plate], w_el) and w_el.max() > 0.0
    assert str(mesh.field_data["unit_crack_width"][0]) == "m"
    s = summary(out)
    assert s["phases"][-1]["max_steel_stress"] >= by_element.max()
    # the crack width of the design summary is a per-phase column and enters the envelope
    w_k = s["design"]["phases"]["loading"]["w_k_max_mm"]
    assert w_k > 0.0 and s["phases"][-1]["max_crack_width"] == 1e-3 * w_k
    assert s["envelope"]["max_crack_width"] == {"value": 1e-3 * w_k, "phase": "loading"}
    # the axial-force spikes at x = +-1.75 m (issue 34): the point values of the element where the crack
    # front lies jump by more than 100 kN/m, its Gauss-weighted mean lies between its neighbours' means
    f = out.strip_forces()
    plate = out.built.plate
    w = plate.wt[plate.ax.astype(bool)]
    mean = f["N"] @ w / w.sum()
    e = int(np.argmin(np.abs(f["x_ax"][:, 1] - 1.75)))
    assert np.ptp(f["N"][e]) > 100e3
    assert min(mean[e - 1], mean[e + 1]) < mean[e] < max(mean[e - 1], mean[e + 1])
