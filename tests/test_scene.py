"""The component-built scene: only what it contains is instantiated, linear scenes are one solve, and the
contact carries exactly the applied column load (global equilibrium, an independent check)."""

import numpy as np
import pytest

from ssi.elements.interface import Interface6
from ssi.elements.plate import PlateStrip
from ssi.elements.soil_q8 import SoilQ8
from ssi.results import read_result, write_result
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer
from ssi.section import homogeneous
from ssi.solver import Settings

COARSE = MeshSize(h_fine=0.5, h_coarse=2.0, growth=1.5)


def strip_scene(**changes):
    kwargs = dict(width=12.0, depth=6.0,
                  layers=[SoilLayer(2.0, E=20e6, nu=0.3, unit_weight=18e3),
                          SoilLayer(4.0, E=60e6, nu=0.3, unit_weight=19e3)],
                  foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
                  contact=Contact(kn=1e10, kt=1e9), loads=[ColumnLoad(x=0.0, N=300e3)], mesh=COARSE)
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
    assert out.solver_result is None  # linear: one factorisation, no Newton loop
    c = out.contact()
    w = out.built.interface.ip_weights()
    # vertical equilibrium of the plate: contact resultant = column force (to round-off)
    assert np.sum(c["sig_n"] * w) == pytest.approx(-300e3, rel=1e-9)
    x, s = out.settlement()
    assert np.all(s > 0.0)  # the foundation settles everywhere
    # symmetric scene, symmetric settlement
    assert np.allclose(s, s[::-1], rtol=1e-8)


def test_nonlinear_scene_reports_zones_and_balances_loads():
    scene = strip_scene(contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0),
                        loads=[ColumnLoad(x=0.0, N=300e3, H=50e3)])
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
    assert np.array_equal(back.u[-1], lin.u)
    assert back.model["scene"]["foundation"]["x0"] == -1.0
    with pytest.raises(FileExistsError):
        write_result(path, lin)


@pytest.mark.parametrize("change, word", [
    (dict(layers=[]), "layers"),
    (dict(contact=None), "contact"),
    (dict(foundation=Foundation(x0=-7.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2))), "foundation"),
    (dict(loads=[ColumnLoad(x=0.1, N=1.0)]), "x=0.1"),
])
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


def test_readme_scene_runs_as_written():
    """The README's 'Your own scene' block, executed as written: it converges (a NonConvergence would raise)
    and the column load is carried by the contact (equilibrium, independent of the solver's tolerance)."""
    import pathlib
    import re

    readme = (pathlib.Path(__file__).resolve().parent.parent / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", readme, re.S).group(1)
    env = {}
    exec(compile(code, "README.md", "exec"), env)
    out, settlement = env["out"], env["settlement"]
    assert out.solver_result.load_factor[-1] == 1.0
    assert 0.0 < settlement.max() < 0.2
    contact = out.contact()
    weights = env["scene"].build().interface.ip_weights()
    # the plate's own weight is not modelled (Foundation.self_weight = 0): the contact carries N alone
    assert np.sum(contact["sig_n"] * weights) == pytest.approx(-400e3, rel=1e-3)
    assert set(np.unique(contact["zone"])) <= {"stick", "slip", "open"}
