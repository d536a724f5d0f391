"""A limit analysis's result out (issue 30 item 5): ``ssi limit scene.toml`` writes the result file (bounds,
Davis bounds, gaps, the mesh, the mechanism's velocity, the dissipation, the stress field) and the ParaView
triangles beside the JSON and the mechanism plot; the file reads back to the same numbers and ``ssi show``
reprints and redraws it.

The scene is ``examples/pushover_footing.toml`` (a rough rigid strip B = 2 m pushed into weightless Tresca
soil, s_u = 50 kPa, symmetric half), bracketed coarsely (one mesh of ~200 triangles, < 1 s of solving):
its exact capacity is Prandtl's (2 + pi) s_u B, which the stored bracket must contain."""

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from ssi.io.cli import main
from ssi.io.export import read_vtu
from ssi.io.results import read_result
from ssi.io.results_limit import read_limit_result, write_limit_result

ROOT = Path(__file__).resolve().parent.parent
PRANDTL = (2.0 + math.pi) * 50e3 * 2.0  # [N/m] rigid rough strip on weightless Tresca soil, s_u = 50 kPa


@pytest.fixture(scope="module")
def limit_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("limit")
    scene = folder / "push.toml"
    shutil.copy(ROOT / "examples" / "pushover_footing.toml", scene)
    # a coarse bracket: every assertion on it holds on any mesh (bounds, identities, files)
    assert main(["limit", str(scene), "--gap", "0.3", "--max-elements", "600"]) == 0
    return folder


def test_ssi_limit_writes_the_result_file_and_paraview_beside_json_and_plot(limit_run, capsys):
    for name in ("push_limit.json", "push_limit.h5", "push_limit.vtu", "push_limit.png"):
        assert (limit_run / name).stat().st_size > 0, name
    data = json.loads((limit_run / "push_limit.json").read_text())
    stored = read_limit_result(limit_run / "push_limit.h5")
    # the file's numbers are the run's (JSON written from the same object): exact
    for key in ("lb", "ub", "gap", "lb_davis", "ub_davis", "gap_davis"):
        assert getattr(stored, key) == data[key], key
    assert stored.to_dict() == data
    # the stored bracket brackets the exact capacity, and is a bracket
    assert stored.lb <= PRANDTL <= stored.ub
    assert stored.gap == pytest.approx((stored.ub - stored.lb) / (stored.ub + stored.lb), rel=1e-12)
    # upper-bound identity on the stored fields: the triangles' dissipation sums to the upper bound (no dead
    # load does work on weightless soil without surcharge); 1e-9: round-off of summing ~200 terms
    assert stored.dissipation.sum() == pytest.approx(stored.ub, rel=1e-9)
    mesh = stored.mesh
    edges, _ = mesh.edges()
    assert stored.velocity.shape == (len(mesh.xy) + len(edges), 2)
    assert stored.stress.shape == (mesh.n_el, 3, 3) and np.isfinite(stored.stress).all()
    assert stored.davis is None  # an associated (Tresca, psi = phi = 0) scene: one run
    assert "scene" in stored.file_info  # the scene it came from, as plain data


def test_limit_paraview_triangles_carry_velocity_dissipation_and_stress(limit_run):
    """The VTU's 6-node triangles: each midside node lies halfway between its triangle's corners in VTK's
    order (0-1, 1-2, 2-0), the velocity at every node is the stored mechanism's, and the dissipation
    density times the area sums to the upper bound; units are field data."""
    stored = read_limit_result(limit_run / "push_limit.h5")
    vtu = read_vtu(limit_run / "push_limit.vtu")
    (block,) = vtu.cells
    assert block.type == "triangle6" and len(block.data) == stored.mesh.n_el
    c = block.data
    p = vtu.points[:, :2]
    for mid, (a, b) in zip((3, 4, 5), ((0, 1), (1, 2), (2, 0))):
        np.testing.assert_allclose(p[c[:, mid]], 0.5 * (p[c[:, a]] + p[c[:, b]]), rtol=0, atol=1e-12)
    np.testing.assert_array_equal(vtu.point_data["velocity"][:, :2], stored.velocity)
    area = stored.mesh.areas()
    assert np.sum(vtu.cell_data["dissipation_density"][0] * area) == pytest.approx(stored.ub, rel=1e-9)
    np.testing.assert_array_equal(vtu.cell_data["sig_z"][0], stored.stress[:, :, 1].mean(axis=1))
    assert str(vtu.field_data["unit_sig_x"][0]) == "Pa" and "unit_velocity" in vtu.field_data


def test_ssi_show_reprints_and_redraws_a_limit_file(limit_run, capsys):
    capsys.readouterr()
    assert main(["show", str(limit_run / "push_limit.h5")]) == 0
    out = capsys.readouterr().out
    stored = read_limit_result(limit_run / "push_limit.h5")
    assert stored.summary() in out and "associated [" in out
    assert (limit_run / "push_limit_plots" / "mechanism.png").stat().st_size > 0
    with pytest.raises(ValueError, match="a limit-analysis file; read it with"):
        read_result(limit_run / "push_limit.h5")


def test_a_stored_limit_writes_again_unchanged(limit_run, tmp_path):
    stored = read_limit_result(limit_run / "push_limit.h5")
    again = read_limit_result(write_limit_result(tmp_path / "copy.h5", stored))
    assert again.to_dict() == stored.to_dict() and again.summary() == stored.summary()
    for key in ("velocity", "dissipation", "stress"):
        np.testing.assert_array_equal(getattr(again, key), getattr(stored, key))
    with pytest.raises(FileExistsError):
        write_limit_result(tmp_path / "copy.h5", stored)


SITE = """
width = 12.0
depth = 5.0
mesher = "gmsh"
[[layers]]
E = 20e6
nu = 0.3
c = 50e3
phi_deg = 0.0
psi_deg = 0.0
[[strips]]
type = "RigidStrip"
x0 = -1.0
x1 = 1.0
settle = 0.1
"""


def test_ssi_limit_brackets_a_site_file_and_writes_its_result(tmp_path, capsys):
    """A site file (a lone rough RigidStrip, B = 2 m, on weightless Tresca soil, the whole block): lambda
    is the strip's vertical force, whose bracket holds Prandtl's; the result file and the VTU are written
    as for a scene; a phase is refused by name (a site has none)."""
    path = tmp_path / "site.toml"
    path.write_text(SITE)
    assert main(["limit", str(path), "--gap", "0.3", "--max-elements", "600"]) == 0  # coarse: any mesh
    stored = read_limit_result(tmp_path / "site_limit.h5")
    assert stored.lb <= PRANDTL <= stored.ub
    assert stored.dissipation.sum() == pytest.approx(stored.ub, rel=1e-9)
    assert read_vtu(tmp_path / "site_limit.vtu").cells[0].type == "triangle6"
    capsys.readouterr()
    assert main(["limit", str(path), "--phase", "loads", "--overwrite"]) == 2
    assert "phase='loads': a site has no phases" in capsys.readouterr().err


def test_ssi_limit_side_soil_reaches_the_limit_problem_and_refuses_a_bad_value(tmp_path, capsys):
    """``--side-soil`` reaches the limit problem: the site file's strip stands in a trench (level -1 m),
    where 'surcharge' has no meaning, refused by name before any solve; a value outside the two is
    argparse's error naming the flag, the value and the choices."""
    path = tmp_path / "trench.toml"
    path.write_text(SITE + "level = -1.0\n")
    assert main(["limit", str(path), "--side-soil", "surcharge"]) == 2
    assert "side_soil='surcharge': a Site's embedded strip stands in its trench" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stop:
        main(["limit", str(path), "--side-soil", "air"])
    assert stop.value.code == 2
    assert "argument --side-soil: invalid choice: 'air' (choose from 'surcharge', 'soil')" in (
        capsys.readouterr().err
    )
