"""The verdict of `ssi run` (ssi.scene.verdict), the factor of safety of scenes and sites (Scene/Site
.safety_factor, `ssi limit --fos`), `ssi limit --help` defaults and the engineering stop sentence (issue 46).

Expected values are independent of the code: Prandtl's (2 + pi) s_u B for a strip on Tresca clay (exact for
phi = 0, rough or smooth, weight irrelevant), so a 400 kN/m column on a 2 m strip on s_u = 20 kPa is carried
at lambda* = 205.66 / 400 = 0.514 only.
"""

import json
import math

import pytest

from ssi.io.cli import main
from ssi.scene.verdict import stop_sentence, verdict

OVERLOADED = """
width = 12.0
depth = 5.0

[[layers]]
thickness = 5.0
E = 30e6
nu = 0.3
c = 20e3
phi_deg = 0.0
psi_deg = 0.0

[foundation]
x0 = -1.0
x1 = 1.0
section = { homogeneous = { thickness = 0.5, E = 30e9, nu = 0.2 } }

[contact]
kn = 1e10
kt = 1e9

[[loads]]
x = 0.0
N = %s

[mesh]
h_fine = 0.5
h_coarse = 2.0

[solve]
n_steps = 4
"""

SLOPE = """
width = 60.0
depth = 1.0
ground = [[-30.0, 10.0], [0.0, 10.0], [20.0, 0.0], [30.0, 0.0]]

[[layers]]
E = 20e6
nu = 0.3
unit_weight = 20e3
c = 10e3
phi_deg = 20.0
"""

LAM_STAR = (2.0 + math.pi) * 20e3 * 2.0 / 400e3  # 0.514


def test_an_overloaded_scene_does_not_carry_its_loads(tmp_path, capsys):
    path = tmp_path / "over.toml"
    path.write_text(OVERLOADED % "400e3")
    assert main(["run", str(path), "--no-plots", "--capacity-gap", "0.08"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("VERDICT          does not carry its loads")
    s = json.loads((tmp_path / "over_summary.json").read_text())
    assert next(iter(s)) == "verdict"
    v = s["verdict"]
    assert v["carries"] is False
    lo, hi = v["margin"]
    assert lo <= LAM_STAR <= hi < 1.0
    html = (tmp_path / "over_report.html").read_text()
    assert html.index("does not carry its loads") < html.index("<h2>Summary</h2>")  # the first screen
    # the incremental limit against the bracket: flagged when above 1.03 x UB_assoc, with its excess
    lim = v["incremental_limit"]
    assert lim is not None and (lim["value"] > 1.03 * lim["ub_assoc"]) == bool(lim["flag"])


def test_a_scene_at_half_its_capacity_carries_its_loads_with_margin(tmp_path, capsys):
    """Both margins contain the hand value. On Tresca clay (phi = 0) strength reduction divides c alone and
    the strip's capacity (2 + pi) c B does not depend on the weight, so the factor of safety on strength is
    the load factor: F* = lambda* = (2 + pi) s_u B / N = 2.057 for N = 100 kN/m (Prandtl)."""
    path = tmp_path / "half.toml"
    path.write_text(OVERLOADED % "100e3")  # lambda* = 2 x 1.028 = 2.06
    assert main(["run", str(path), "--no-plots", "--capacity-gap", "0.08", "--fos-gap", "0.08"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("VERDICT          carries its loads with margin lambda in [")
    assert "(associated bracket) and factor of safety on strength F in [" in out[0]  # psi = phi = 0
    assert "  factor of safety on strength (c/F, tan(phi)/F, associated): F in [" in out[2]
    s = json.loads((tmp_path / "half_summary.json").read_text())
    lo, hi = s["verdict"]["margin"]
    assert 1.0 <= lo <= 4 * LAM_STAR <= hi
    f_lo, f_hi = s["verdict"]["fos_margin"]
    assert f_lo <= 4 * LAM_STAR <= f_hi and (f_hi - f_lo) / (f_hi + f_lo) <= 0.08
    assert s["verdict"]["fos"]["converged"] is True
    html = (tmp_path / "half_report.html").read_text()
    assert html.index("factor of safety on strength") < html.index("<h2>Summary</h2>")


def test_no_capacity_skips_and_an_elastic_layer_is_named(tmp_path, capsys):
    path = tmp_path / "half.toml"
    path.write_text(OVERLOADED % "100e3")
    assert main(["run", str(path), "--no-plots", "--no-capacity"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("VERDICT          not asked (--no-capacity)")
    assert "factor of safety" not in out  # skipped with the capacity
    elastic = (OVERLOADED % "100e3").replace("c = 20e3\nphi_deg = 0.0\npsi_deg = 0.0\n", "")
    path = tmp_path / "elastic.toml"
    path.write_text(elastic)
    assert main(["run", str(path), "--no-plots"]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("VERDICT          capacity not computed: every layer of the scene is elastic")


def test_rc_utilisations_above_one_are_flagged():
    s = {
        "kind": "scene",
        "status": "completed",
        "max_settlement": 0.01,
        "design": {"util_M_max": 0.8, "util_V_max": 1.14, "w_k_max_mm": 0.43},
    }
    v = verdict(s, None, bracket={"not_computed": "test"})
    u = v["foundations"][0]["utilisation"]
    assert u["V_Ed/V_Rd,c"] == 1.14 and u["w_k/w_lim"] == pytest.approx(0.43 / 0.3)
    assert len([f for f in v["flags"] if "> 1" in f]) == 2  # shear and crack width, not bending


def test_a_slope_site_has_its_own_factor_of_safety(tmp_path, capsys):
    """A Site without loads: its factor of safety under its weight alone (no "no load to scale")."""
    path = tmp_path / "slope.toml"
    path.write_text(SLOPE)
    assert main(["limit", "--fos", str(path), "--gap", "0.08"]) == 0
    out = capsys.readouterr().out
    assert "factor of safety (strength reduction" in out and "gap reached" in out
    d = json.loads((tmp_path / "slope_fos.json").read_text())
    # a 2:1 slope, phi = 20, c/(gamma H) = 0.05, base 1 m below the toe: near 1.38 (Bishop-Morgenstern D = 1)
    assert 1.0 < d["f_lower"] <= d["f_upper"] < 1.8


def test_limit_help_shows_defaults(capsys):
    with pytest.raises(SystemExit):
        main(["limit", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "(default: 0.02)" in text and "(default: 20000)" in text


def test_stop_sentence_names_where_and_what_to_do():
    text = stop_sentence(
        {"reason": "residual stagnates", "load_factor_from": 0.8, "node_xy": (1.0, -0.5), "ill_posed": "x"},
        "scene",
    )
    assert text.startswith("The scene's solver stopped at load factor 0.8, worst near x = 1.00 m")
    assert "Davis" in text and "What to do" in text and len(text) < 600


def test_readme_demo_verdict_is_what_ssi_run_prints(tmp_path, capsys):
    """The README's quick-start verdict block is what `ssi run examples/capacity.toml` (the file `make demo`
    runs) prints first, line for line; only the limit analysis' wall time in the closing parenthesis varies
    with the machine and is masked on both sides. A hand copy that drifted from the run would fail here."""
    import pathlib
    import re
    import shutil

    root = pathlib.Path(__file__).resolve().parent.parent
    readme = (root / "README.md").read_text()
    shown = re.search(r"```text\n(VERDICT.*?)```", readme, re.S).group(1).strip().splitlines()
    scene = tmp_path / "capacity.toml"
    shutil.copy(root / "examples" / "capacity.toml", scene)
    assert main(["run", str(scene), "--no-plots"]) == 0
    printed = capsys.readouterr().out.splitlines()
    start = next(i for i, line in enumerate(printed) if line.startswith("VERDICT"))
    seconds = re.compile(r", [0-9.]+ s\)$")
    assert [seconds.sub(", T s)", line) for line in printed[start : start + len(shown)]] == [
        seconds.sub(", T s)", line) for line in shown
    ]


def test_a_footing_on_soil_that_never_yields_has_no_mechanism(tmp_path, capsys):
    """The shipped embedded site stands its strip on an elastic layer (c=None), which the run never yields and
    the bracket takes as never yielding: no mechanism exists, so the lower-bound program is unbounded (every
    load factor has an admissible field). The verdict says so in words, not "undecided [0, inf]"."""
    import pathlib
    import shutil

    root = pathlib.Path(__file__).resolve().parent.parent
    site = tmp_path / "embedded.toml"
    shutil.copy(root / "examples" / "sites" / "embedded.toml", site)
    assert main(["run", str(site), "--no-plots"]) == 0
    s = json.loads((tmp_path / "embedded_summary.json").read_text())
    b = s["verdict"]["capacity"]
    assert b["no_mechanism"] and b["lb_davis"] is None and b["never_yield"] == ["Site.layers[1]"]
    assert s["verdict"]["carries"] is True
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("VERDICT          carries its loads: no collapse mechanism exists")
