"""The component-built scene: only what it contains is instantiated, linear scenes are one solve, and the
contact carries exactly the applied column load (global equilibrium, an independent check)."""

import textwrap

import numpy as np
import pytest

from ssi.elements.interface import Interface6
from ssi.elements.plate import PlateStrip
from ssi.elements.section import homogeneous
from ssi.elements.soil_q8 import SoilQ8
from ssi.io.results import read_result, write_result
from ssi.lab.examples import surcharge_heave
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer
from ssi.scene.file_schema import UNITS
from ssi.scene.scene_file import scene_from_dict, scene_to_dict
from ssi.solver import Settings

COARSE = MeshSize(h_fine=0.5, h_coarse=2.0, growth=1.5)


def strip_scene(**changes):
    kwargs = dict(
        width=12.0,
        depth=6.0,
        layers=[
            SoilLayer(2.0, E=20e6, nu=0.3, unit_weight=18e3),
            SoilLayer(4.0, E=60e6, nu=0.3, unit_weight=19e3),
        ],
        foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9),
        loads=[ColumnLoad(x=0.0, N=300e3)],
        mesh=COARSE,
    )
    kwargs.update(changes)
    return Scene(**kwargs)


def test_soil_only_scene_has_one_group():
    built = strip_scene(foundation=None, contact=None, loads=[]).build()
    assert [type(g) for g in built.model.groups] == [SoilQ8]


def test_foundation_scene_has_plate_and_interface():
    built = strip_scene().build()
    assert [type(g) for g in built.model.groups] == [SoilQ8, PlateStrip, Interface6]
    assert built.is_linear


def test_linear_scene_contact_carries_the_column_load():
    out = strip_scene().build().solve()
    res = out.solver_result  # linear: one factorisation, no Newton loop
    assert res.factorizations == 1 and res.iterations == [0, 1] and res.load_factor == [0.0, 1.0]
    c = out.contact()
    w = out.built.interface.ip_weights()
    # vertical equilibrium of the plate: contact resultant = column force (to round-off)
    assert np.sum(c["sig_n"] * w) == pytest.approx(-300e3, rel=1e-9)
    x, s = out.settlement()
    assert np.all(s > 0.0)  # the foundation settles everywhere
    # symmetric scene, symmetric settlement
    assert np.allclose(s, s[::-1], rtol=1e-8)


def test_nonlinear_scene_reports_zones_and_balances_loads():
    scene = strip_scene(
        contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0), loads=[ColumnLoad(x=0.0, N=300e3, H=50e3)]
    )
    scene.layers[0] = SoilLayer(2.0, E=20e6, nu=0.3, unit_weight=18e3, c=10e3, phi_deg=30.0, psi_deg=0.0)
    built = scene.build()
    assert not built.is_linear
    out = built.solve(n_steps=4, settings=Settings(force_tol=1e-6))
    c = out.contact()
    w = built.interface.ip_weights()
    # equilibrium to the solver's force tolerance (relative to the largest force in the system)
    assert np.sum(c["sig_n"] * w) == pytest.approx(-300e3, rel=1e-3)
    assert np.sum(c["tau"] * w) == pytest.approx(50e3, rel=1e-3)
    assert set(np.unique(c["zone"])) <= {"stick", "slip", "open"}


def test_scene_result_roundtrip(tmp_path):
    built = strip_scene().build()
    lin = built.model.solve_linear()
    path = write_result(tmp_path / "scene.h5", lin)
    back = read_result(path)  # a bare model result (no SceneResult): arrays as stored
    assert np.array_equal(back.u, np.array(lin.u))
    assert back.model["scene"]["foundation"]["x0"] == -1.0
    with pytest.raises(FileExistsError):
        write_result(path, lin)


@pytest.mark.parametrize(
    "change, word",
    [
        (dict(layers=[]), "layers"),
        (dict(contact=None), "contact"),
        (dict(foundation=Foundation(x0=-7.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2))), "foundation"),
        (dict(loads=[ColumnLoad(x=3.0, N=300e3)]), "x=3.0"),  # off the strip
    ],
)
def test_bad_scenes_are_named(change, word):
    with pytest.raises(ValueError, match=word):
        strip_scene(**change).build()


def test_layers_must_be_valid():
    with pytest.raises(ValueError, match="E must be"):
        strip_scene(layers=[SoilLayer(6.0, E=-1.0, nu=0.3)]).build()
    with pytest.raises(ValueError, match="nu must"):
        strip_scene(layers=[SoilLayer(6.0, E=1e7, nu=0.5)]).build()
    with pytest.raises(ValueError, match="tile the depth"):
        strip_scene(layers=[SoilLayer(5.0, E=1e7, nu=0.3)]).build()


def test_a_layer_without_psi_does_not_dilate():
    """Issue 31: a SoilLayer without psi_deg has psi = 0 (PLAXIS's default; psi = phi overstated a user's
    push-over by 18 %), in Python and in a scene file (the reader builds the same dataclass); psi_deg=None
    is associated flow. The law's parameter row holds phi and psi in radians at columns 3 and 4 (set from
    the inputs here, not computed by the code under test)."""
    layer = SoilLayer(6.0, E=20e6, nu=0.3, c=10e3, phi_deg=30.0)
    assert layer.psi_deg == 0.0
    assert layer.law()[1][3:5] == pytest.approx([np.radians(30.0), 0.0], abs=0.0)
    associated = SoilLayer(6.0, E=20e6, nu=0.3, c=10e3, phi_deg=30.0, psi_deg=None)
    assert associated.law()[1][3:5] == pytest.approx([np.radians(30.0)] * 2, abs=0.0)
    data = scene_to_dict(strip_scene(layers=[layer]))
    del data["layers"][0]["psi_deg"]  # a scene file that leaves it out
    assert scene_from_dict(data).layers[0].psi_deg == 0.0
    assert "leave out: 0" in UNITS["SoilLayer"]["psi_deg"]


def test_readme_scene_runs_as_written():
    """The README's 'A scene' block, executed as written: it converges (a NonConvergence would raise)
    and the column load is carried by the contact (equilibrium, independent of the solver's tolerance)."""
    import pathlib
    import re

    readme = (pathlib.Path(__file__).resolve().parent.parent / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", readme, re.S).group(1)
    env = {}
    exec(compile(code, "README.md", "exec"), env)
    out, settlement = env["out"], env["settlement"]
    assert out.status == "completed" and out.solver_result.load_factor[-1] == 1.0
    assert 0.0 < settlement.max() < 0.2
    contact = out.contact()
    weights = env["scene"].build().interface.ip_weights()
    # the plate's own weight is not modelled (Foundation.self_weight = 0): the contact carries N alone
    assert np.sum(contact["sig_n"] * weights) == pytest.approx(-400e3, rel=1e-3)
    assert set(np.unique(contact["zone"])) <= {"stick", "slip", "open"}


# ---- issue 12: surcharge, loads, phases, groundwater, embedment, contact segments, units -------------------
from ssi.materials.soil_laws import geostatic_stress, pore_pressure  # noqa: E402
from ssi.scene import ContactSegment, Phase, Settlement, StripLoad, StripWeight, SurfacePressure  # noqa: E402

E_SOIL, NU_SOIL = 20e6, 0.3
M_OED = E_SOIL * (1 - NU_SOIL) / ((1 + NU_SOIL) * (1 - 2 * NU_SOIL))


@pytest.mark.parametrize("with_strip", [False, True])
def test_surcharge_alone_does_not_heave(with_strip):
    """Chapter 12's claim ``surcharge_no_heave`` (``ssi.lab.examples.surcharge_heave``): the old scene heaved
    q H / M under the surcharge alone; now the geostatic state is in equilibrium (round-off, 1e-8)."""
    q = 10e3
    ratio, built, out = surcharge_heave(with_strip, q=q, depth=6.0, E=E_SOIL, nu=NU_SOIL)
    assert ratio < 1e-8
    if with_strip:  # the strip carries the surcharge over its width from the start
        assert built.contact_force(out)[-1] == pytest.approx(q * 2.0, rel=1e-12)


def test_surcharge_default_path_is_also_in_equilibrium():
    """Without phases (one proportional path) a tiny column load gives a tiny settlement, not a heave."""
    scene = strip_scene(
        layers=[SoilLayer(6.0, E=E_SOIL, nu=NU_SOIL, unit_weight=18e3)],
        surcharge=10e3,
        loads=[ColumnLoad(0.0, N=1e3)],
    )
    out = scene.build().solve()
    x, s = out.settlement()
    assert np.all(s > 0.0) and s.max() < 0.05 * 10e3 * 6.0 / M_OED  # the old heave was -q H / M everywhere


def test_column_anywhere_on_the_strip_gets_a_node():
    built = strip_scene(loads=[ColumnLoad(x=0.1, N=300e3), ColumnLoad(x=-0.77, N=100e3)]).build()
    assert built.model.coords[built.plate_node_at(0.1), 0] == pytest.approx(0.1, abs=1e-12)
    assert built.model.coords[built.plate_node_at(-0.77), 0] == pytest.approx(-0.77, abs=1e-12)


def phased_scene(**changes):
    building = (
        ColumnLoad(-0.3, N=300e3, H=20e3),
        StripLoad(20e3, q_end=5e3, x0=-1.0, x1=0.5),
        SurfacePressure(2.0, 4.0, 15e3),
    )
    kwargs = dict(
        phases=[
            Phase("weight", (StripWeight(25e3),)),
            Phase("building", building),
            Phase("unload", factors={"building": 0.0}),
        ],
        loads=[],
        surcharge=10e3,
        water_table=1.0,
    )
    kwargs.update(changes)
    return strip_scene(**kwargs)


def test_phases_carry_each_load_and_unload_elastically():
    built = phased_scene().build()
    out = built.solve(n_steps=2)
    step = {r["name"]: r["last"] for r in out.phases}
    force = built.contact_force(out)
    weight = 25e3 * 0.5 * 2.0
    strip = 0.5 * (20e3 + 5e3) * 1.5  # linear load over 1.5 m
    assert force[step["geostatic"]] == pytest.approx(10e3 * 2.0, rel=1e-12)
    assert force[step["weight"]] == pytest.approx(20e3 + weight, rel=1e-10)
    assert force[step["building"]] == pytest.approx(20e3 + weight + 300e3 + strip, rel=1e-10)
    u = np.array(out.u)
    assert np.abs(u[step["geostatic"]]).max() < 1e-14
    moved = np.abs(u[step["building"]] - u[step["weight"]]).max()
    assert moved > 1e-3
    assert np.abs(u[step["unload"]] - u[step["weight"]]).max() < 1e-8 * moved
    kinds = [ld["type"] for ld in scene_to_dict(built.scene)["phases"][1]["loads"]]
    assert kinds == ["ColumnLoad", "StripLoad", "SurfacePressure"]


def test_water_table_geostatic_state_against_hand_calculation():
    """Effective stress with the buoyant weight below the table, K0 on effective stress, hydrostatic p."""
    layers = [
        SoilLayer(2.0, E=2e7, nu=0.3, unit_weight=18e3, unit_weight_sat=20e3, phi_deg=30.0),
        SoilLayer(4.0, E=6e7, nu=0.3, unit_weight=19e3, unit_weight_sat=21e3, K0=0.6),
    ]
    built = strip_scene(layers=layers, water_table=1.5, loads=[], phases=[Phase("nothing")]).build()
    out = built.solve(n_steps=1)
    assert np.abs(out.u[-1]).max() < 1e-14  # buoyant body force and effective initial stress balance
    d = -built.soil.integration_points()[..., 1]
    gw = 9.81e3
    sv = (
        18e3 * np.minimum(d, 1.5)
        + (20e3 - gw) * np.clip(d - 1.5, 0, 0.5)
        + (21e3 - gw) * np.maximum(d - 2, 0)
    )
    k0 = np.where(d < 2.0, 0.5, 0.6)
    sig = built.soil.stress(out.states[-1][0])
    assert np.allclose(-sig[..., 1], sv, rtol=1e-12)
    assert np.allclose(-sig[..., 0], k0 * sv, rtol=1e-12)
    assert np.allclose(built.pore_pressure(), gw * np.maximum(d - 1.5, 0.0), rtol=1e-12)
    assert np.allclose(pore_pressure(np.array([-3.0]), 1.5), gw * 1.5)


def test_geostatic_stress_water_table_function():
    sig = geostatic_stress(
        np.array([-1.0, -3.0]),
        [SoilLayer(2.0, E=20e6, nu=0.3, unit_weight=18e3, unit_weight_sat=20e3, K0=0.5)],
        water_table=1.0,
        gamma_w=10e3,
    )
    assert sig[:, 1] == pytest.approx([-18e3, -(18e3 + 2 * 10e3)])
    with pytest.raises(ValueError, match="unit_weight_sat"):
        geostatic_stress(
            np.array([-1.0]),
            [SoilLayer(1.0, E=20e6, nu=0.3, unit_weight=18e3, unit_weight_sat=5e3, K0=0.5)],
            water_table=0.5,
        )


@pytest.mark.parametrize("water_table", [None, 0.5, 3.0])
def test_embedded_strip_starts_in_equilibrium(water_table):
    """Trench walls carry the horizontal, the strip's base the vertical geostatic stress: nothing moves."""
    layers = [
        SoilLayer(1.0, E=1e6, nu=0.3, unit_weight=18e3, unit_weight_sat=20e3),
        SoilLayer(5.0, E=2e7, nu=0.3, unit_weight=19e3, unit_weight_sat=21e3, phi_deg=30.0),
    ]
    built = strip_scene(
        layers=layers,
        embedment=1.0,
        water_table=water_table,
        surcharge=5e3,
        loads=[],
        phases=[Phase("nothing")],
    ).build()
    out = built.solve(n_steps=1)
    assert np.abs(out.u[-1]).max() < 1e-14
    sv_base = 5e3 + (18e3 if water_table != 0.5 else 18e3 * 0.5 + (20e3 - 9.81e3) * 0.5)
    assert built.base_pressure == pytest.approx(sv_base, rel=1e-12)
    assert built.model.coords[built.plate_nodes, 1] == pytest.approx(-1.0 + 0.25)


def test_embedment_must_be_a_layer_boundary():
    with pytest.raises(ValueError, match="layer boundary"):
        strip_scene(embedment=1.0).build()


def test_rigid_settlement_reaction_is_the_contact_force():
    scene = strip_scene(loads=[], phases=[Phase("push", (Settlement(w=0.01),))])
    built = scene.build()
    out = built.solve(n_steps=2)
    res = out.solver_result
    w_dofs = built.model.dof(built.plate_nodes, "w")
    reaction = -np.array(res.f_int)[-1, w_dofs].sum()  # weightless scene: all plate force is reaction
    x, s = out.settlement()
    assert s == pytest.approx(0.01, rel=1e-12)  # rigid: every plate node settled by w
    assert built.contact_force(out)[-1] == pytest.approx(reaction, rel=1e-8)
    assert reaction > 0.0


def test_contact_segments_give_each_element_its_law():
    segs = [
        ContactSegment(-1.0, 0.2, Contact(kn=1e10, kt=0.0)),
        ContactSegment(0.2, 1.0, Contact(kn=2e10, kt=1e9)),
    ]
    built = strip_scene(contact=segs).build()
    mid = built.interface.ip_coords()[:, 1, 0]
    kt, kn = built.interface.params[:, 0], built.interface.params[:, 1]
    assert np.all(kt[mid < 0.2] == 0.0) and np.all(kn[mid < 0.2] == 1e10)
    assert np.all(kt[mid > 0.2] == 1e9) and np.all(kn[mid > 0.2] == 2e10)
    with pytest.raises(ValueError, match="tile the strip"):
        strip_scene(contact=segs[:1]).build()


def test_units_warn_but_do_not_refuse():
    with pytest.warns(UserWarning, match="kN/m\\^3"):
        strip_scene(layers=[SoilLayer(6.0, E=2e7, nu=0.3, unit_weight=18.0)]).build()
    with pytest.warns(UserWarning, match="kPa"):
        strip_scene(layers=[SoilLayer(6.0, E=2e4, nu=0.3)]).build()
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        strip_scene().build()  # an SI scene warns about nothing


@pytest.mark.parametrize(
    "change, word",
    [
        (dict(phases=[Phase("a", factors={"b": 0.0})]), "not earlier phases"),
        (dict(loads=[SurfacePressure(0.0, 2.0, 10e3)]), "overlaps the strip"),
        (dict(foundation=None, contact=None, loads=[StripLoad(1e4)]), "needs a foundation"),
        (dict(phases=[Phase("geostatic")]), "unique"),
    ],
)
def test_bad_phases_and_loads_are_named(change, word):
    with pytest.raises(ValueError, match=word):
        strip_scene(**change).build().solve(n_steps=1)


def test_undrained_A_elastic_is_elastic_with_nu_u():
    """Effective-stress undrained with the water penalty = elastic soil with G and nu_u (closed form)."""
    E, nu, nu_u = 20e6, 0.3, 0.495
    G = E / (2 * (1 + nu))
    a = strip_scene(layers=[SoilLayer(6.0, E=E, nu=nu, drainage="undrained_A", nu_u=nu_u)]).build().solve()
    b = strip_scene(layers=[SoilLayer(6.0, E=2 * G * (1 + nu_u), nu=nu_u)]).build().solve()
    assert np.abs(a.u[-1] - b.u[-1]).max() < 1e-10 * np.abs(b.u[-1]).max()
    k_u = 2 * G * (1 + nu_u) / (3 * (1 - 2 * nu_u))
    built = strip_scene(
        layers=[SoilLayer(6.0, E=E, nu=nu, drainage="undrained_A", nu_u=nu_u)],
        foundation=None,
        contact=None,
        loads=[SurfacePressure(-6.0, 6.0, 10e3)],
    ).build()
    out = built.solve()
    m_u = k_u + 4 * G / 3
    assert out.surface()[1] == pytest.approx(10e3 * 6.0 / m_u, rel=1e-10)
    assert built.excess_pore_pressure(out) == pytest.approx(
        10e3 * (k_u - E / (3 * (1 - 2 * nu))) / m_u, rel=1e-10
    )
    with pytest.raises(ValueError, match="nu_u"):
        strip_scene(layers=[SoilLayer(6.0, E=E, nu=nu, drainage="undrained_A", nu_u=0.2)]).build()


def test_settlement_in_a_single_phase_scene():
    """Without phases a Settlement is a prescribed displacement of the model (linear scene: one solve)."""
    out = strip_scene(loads=[Settlement(w=0.02, x=(0.0,))]).build().solve()
    x, s = out.settlement()
    assert s[np.argmin(np.abs(x))] == pytest.approx(0.02, rel=1e-12)
    assert out.solver_result.factorizations == 1 and out.n_steps == 1
    with pytest.raises(ValueError, match="outside the block"):
        strip_scene(foundation=None, contact=None, loads=[SurfacePressure(5.0, 7.0, 1e4)]).build()


def test_readme_phased_scene_runs_as_written():
    """The README's second block (phases, embedment, water table), executed as written with the default
    settings: every phase completes, the geostatic phase moves nothing, unloading a plastic soil leaves a
    permanent settlement smaller than the loaded one, and reloading brings it back near the loaded value."""
    import pathlib
    import re

    readme = (pathlib.Path(__file__).resolve().parent.parent / "README.md").read_text()
    code = re.findall(r"```python\n(.*?)```", readme, re.S)[1]
    env = {}
    exec(compile(code, "README.md", "exec"), env)
    out, step = env["out"], env["step"]
    assert out.status == "completed"
    assert np.abs(out.u[step["geostatic"]]).max() < 1e-9
    loaded = out.settlement(step["building"])[1].max()
    unloaded = out.settlement(step["unload"])[1].max()
    reloaded = out.settlement(step["reload"])[1].max()
    assert 0.0 < unloaded < loaded and reloaded == pytest.approx(loaded, rel=0.05)


@pytest.mark.parametrize("section", ["elastic", "rc"])
def test_no_internal_force_before_anything_is_displaced_or_stressed(section):
    """``Model.solve_linear`` skips the internal-force pass when u = 0 and every group's state is zero: that
    is exact only if every element type gives exactly zero force there, checked here for the soil, plate
    (elastic and RC layers) and interface groups, with tangents off and on."""
    from ssi.core.model import System
    from ssi.elements.section import rc_section
    from ssi.materials.layer_laws import CONCRETE, STEEL
    from ssi.materials.rc import concrete_params, steel_params

    changes = {}
    if section == "rc":
        concrete = (CONCRETE, concrete_params(30e6, 30e9, 2e-3, 2.9e6, 100.0, 0.1, 2.5e-3))
        rc = rc_section(0.5, [(0.05, 1e-3), (0.45, 1e-3)], concrete, (STEEL, steel_params(500e6, 200e9)))
        changes["foundation"] = Foundation(x0=-1.0, x1=1.0, section=rc)
    model = strip_scene(**changes).build().model  # (its soil starts geostatic: the states are zeroed here)
    states = [np.zeros_like(g.initial_state()) for g in model.groups]
    zero = np.zeros(model.n_dof)
    for tangent in (None, 1):
        f_int, _, _ = System(model).evaluate(zero, zero, states, tangent)
        assert not f_int.any()


def test_frictionless_contact_holds_the_strip_horizontally_without_a_reaction():
    """Every Contact.kt = 0: nothing resists a horizontal translation of the strip, so K0 was singular (strict
    pivoting factorised it on a round-off pivot; threshold pivoting meets the exact zero). The scene holds u
    at the middle plate node; the tractions of a frictionless contact are normal to the base, so under
    vertical loads -- here off-centre, so nothing is symmetric -- that support carries no force."""
    scene = strip_scene(contact=Contact(kn=1e10, kt=0.0), loads=[ColumnLoad(x=0.5, N=300e3)])
    built = scene.build()
    assert built.slide_support is not None
    out = built.solve()
    reaction = out.solver_result.reactions()[built.model.dof(built.slide_support, "u")]
    assert abs(reaction) <= 1e-9 * 300e3
    c = out.contact()
    assert np.sum(c["sig_n"] * built.interface.ip_weights()) == pytest.approx(-300e3, rel=1e-9)
    assert np.allclose(c["tau"], 0.0, atol=1e-9 * 300e3)


def test_horizontal_load_on_a_frictionless_contact_is_refused():
    scene = strip_scene(contact=Contact(kn=1e10, kt=0.0), loads=[ColumnLoad(x=0.0, N=300e3, H=10e3)])
    with pytest.raises(ValueError, match=r"ColumnLoad.H = 10000 .*Contact.kt > 0"):
        scene.build()


def test_readme_scene_compiles_one_copy_of_each_kernel():
    """A cold first run pays every compiled copy of a kernel: numba compiles one more for each distinct
    argument type, and a literal constant (``f(x, 1)``) is its own type. The README scene, run in a fresh
    process on the shared cache, leaves every ssi kernel with one signature (a copy loaded from the cache
    counts as well, so a warm cache sees the same)."""
    import pathlib
    import re
    import subprocess
    import sys

    readme = (pathlib.Path(__file__).resolve().parent.parent / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", readme, re.S).group(1)
    code += textwrap.dedent("""
        import importlib, pkgutil, numba, ssi
        for info in pkgutil.walk_packages(ssi.__path__, "ssi."):
            module = importlib.import_module(info.name)
            for name, obj in vars(module).items():
                if isinstance(obj, numba.core.registry.CPUDispatcher) and len(obj.signatures) > 1:
                    print("COPIES", info.name, name, obj.signatures)
    """)
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "completed" in run.stdout
    copies = [line for line in run.stdout.splitlines() if line.startswith("COPIES")]
    assert copies == [], "\n".join(copies)
