"""``ssi run --estimate`` (issue 34 item 2): a push-over's capacity printed with its estimated discretisation
error, in the summary JSON, the result file (read back by ``ssi show``) and the HTML report; a capacity
whose estimated error exceeds 5 % says so in each.

The scene is a coarse copy of ``examples/pushover_footing.toml`` (a rough rigid strip B = 2 m on Tresca soil,
s_u = 50 kPa, pushed 0.3 m): h = 1 m under the footing, 8 increments, so that the run and its two refined
copies (h = 0.5, 0.25 m) take a few seconds. The refined copies' capacities are checked against separate
``ssi run`` of the same file with the mesh halved by hand, the extrapolation against Prandtl's exact value."""

import html
import json
import math
from pathlib import Path

import pytest

from ssi.io.cli import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
S_U, B = 50e3, 2.0  # [Pa] undrained strength, [m] footing width
PRANDTL = (2.0 + math.pi) * S_U * B  # [N/m] exact collapse load of a rigid strip on weightless Tresca soil

SCENE = """
width = 12.0
depth = 5.0
symmetric = true

[[layers]]
thickness = 5.0
E = 20e6
nu = 0.3
unit_weight = 0.0
K0 = 1.0
c = 50e3
phi_deg = 0.0
psi_deg = 0.0

[foundation]
type = "RigidFooting"
x0 = -1.0
x1 = 1.0
rough = true

[[loads]]
type = "Settlement"
w = 0.3

[mesh]
h_fine = {h_fine}
h_coarse = {h_coarse}
growth = 1.25

[solve]
n_steps = 8
method = "full"
line_search = true
stepping = "fixed"
max_cuts = 8
backend = "superlu"
"""


def _write(path, h_fine):
    path.write_text(SCENE.format(h_fine=h_fine, h_coarse=4 * h_fine))
    return path


@pytest.fixture(scope="module")
def estimated_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("estimate")
    scene = _write(folder / "push.toml", 1.0)
    return folder, scene


def _run(capsys, argv):
    code = main(argv)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_run_estimate_prints_stores_and_reports_the_capacity_error(estimated_run, capsys):
    folder, scene = estimated_run
    code, out, err = _run(capsys, ["run", str(scene), "--estimate", "--no-plots"])
    assert code == 0, err
    assert "estimating the discretisation error" in err  # the user is told why it takes longer
    s = json.loads((folder / "push_summary.json").read_text())
    cap, est = s["capacity"], s["error_estimate"]
    assert est["asked"] == "capacity" and est["refinements"] == ["mesh"]
    assert cap["estimate"]["values"][0] == pytest.approx(cap["load"], rel=1e-12)  # the run is the base level
    # printed: the capacity line, its estimated error with the three meshes, and the 5 % warning
    rel = cap["estimate"]["relative"]
    assert rel > 0.05  # a coarse mesh: ~30 % (asserted against the refined runs below)
    assert f"capacity error   {rel:.1%} estimated (mesh h, h/2, h/4: " in out
    assert "WARNING" in out and "more than 5%" in cap["warning"]
    assert "s (the error estimate's refined solves)" in out
    # the HTML report carries the estimate's rows, its table and the warning
    page = (folder / "push_report.html").read_text()
    assert "estimated discretisation error" in page and "Discretisation error" in page
    assert html.escape(cap["warning"]) in page

    # the result file keeps it: ssi show reprints the same lines from the file alone
    code, shown, err = _run(capsys, ["show", str(folder / "push.h5"), "--no-plots"])
    assert code == 0, err
    for line in out.splitlines():
        if line.startswith(("capacity", "WARNING")):
            assert line in shown
    code, shown_json, _ = _run(capsys, ["show", str(folder / "push.h5"), "--no-plots", "--json"])
    stored = json.loads(shown_json.split("\n}\n")[0] + "\n}")
    assert stored["error_estimate"] == est and stored["capacity"]["estimate"] == cap["estimate"]
    # the Python reader gives the estimate back on the result, and the load-settlement plot draws it
    import matplotlib.pyplot as plt

    from ssi.io.plot import load_settlement
    from ssi.io.results import read_result

    result = read_result(folder / "push.h5")
    assert result.capacity_error == cap["estimate"] and result.error_estimate == est
    fig = load_settlement(result)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    plt.close(fig)
    assert (
        f"extrapolated {cap['estimate']['extrapolated'] / 1e3:.1f} kN/m (estimated error {100 * rel:.1f} %)"
        in labels
    )


def test_refined_capacities_are_those_of_separate_runs_and_extrapolate_towards_prandtl(estimated_run, capsys):
    """The h/2 and h/4 values the estimate reports equal the capacities of the scene file run with the mesh
    halved by hand (the same deterministic solve: to 1e-9 relative, round-off of a different assembly
    order at most); the extrapolated capacity lies closer to Prandtl's 5.14 s_u B than the run's, and the
    run's estimated error is within a factor 2 of its true error (a factor: the coarse sequence is not
    asymptotic, and the estimate says so)."""
    folder, _ = estimated_run
    s = json.loads((folder / "push_summary.json").read_text())
    est = s["capacity"]["estimate"]
    for level, h in ((1, 0.5), (2, 0.25)):
        path = _write(folder / f"push_h{level}.toml", h)
        code, _, err = _run(capsys, ["run", str(path), "--no-plots"])
        assert code == 0, err
        direct = json.loads((folder / f"push_h{level}_summary.json").read_text())["capacity"]["load"]
        assert est["values"][level] == pytest.approx(direct, rel=1e-9)
    coarse = est["values"][0]
    assert abs(est["extrapolated"] - PRANDTL) < abs(coarse - PRANDTL)
    assert 0.5 < est["error"] / (coarse - PRANDTL) < 2.0
    assert not est["asymptotic"]


def test_estimate_flag_refuses_an_unknown_refinement(estimated_run, capsys):
    folder, scene = estimated_run
    code, _, err = _run(capsys, ["run", str(scene), "--estimate-over", "mesh,grid", "--overwrite"])
    assert code == 2
    assert "--estimate-over must be a comma list of mesh, steps, layers, got 'mesh,grid'" in err


def test_a_load_controlled_run_estimates_its_settlement(tmp_path, capsys):
    """``examples/strip_linear.toml`` (a linear strip under one column) with ``--estimate``: the settlement
    is the quantity asked for, printed first; its h/2 value is that of the file run with the mesh halved by
    hand (the same linear solve: 1e-12 relative); the corner pressure is named a singularity, not given an
    error."""
    import tomllib

    text = (EXAMPLES / "strip_linear.toml").read_text()
    (tmp_path / "strip.toml").write_text(text)
    # the flag before the path (argparse must not take the path for the flag's value)
    code, out, err = _run(capsys, ["run", "--estimate", str(tmp_path / "strip.toml"), "--no-plots"])
    assert code == 0, err
    s = json.loads((tmp_path / "strip_summary.json").read_text())
    est = s["error_estimate"]
    assert est["asked"] == "max_settlement" and s["capacity"]["estimate"] is None
    settle = est["quantities"]["max_settlement"]
    assert settle["values"]["mesh"][0] == s["max_settlement"]
    line = f"  max_settlement (asked for)     {1e3 * settle['value']:.4g} mm, error {settle['relative']:.1%}"
    assert line in out
    assert "max_contact_pressure" in out and "no error to estimate" in out
    mesh = tomllib.loads(text)["mesh"]
    half = text.replace(f"h_fine = {mesh['h_fine']}", f"h_fine = {mesh['h_fine'] / 2}").replace(
        f"h_coarse = {mesh['h_coarse']}", f"h_coarse = {mesh['h_coarse'] / 2}"
    )
    assert half != text
    (tmp_path / "half.toml").write_text(half)
    assert main(["run", str(tmp_path / "half.toml"), "--no-plots"]) == 0
    direct = json.loads((tmp_path / "half_summary.json").read_text())["max_settlement"]
    assert settle["values"]["mesh"][1] == pytest.approx(direct, rel=1e-12)
