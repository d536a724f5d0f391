"""A site's summary is a scene's: the solver's status (never "completed" past a limit), and for each plate
strip its contact resultant, bending moment and EN 1992 design lines (ssi.scene.foundation_result)."""

import json
import math

import pytest

from ssi.io.cli import main

SOFT_CLAY = """
width = 12.0
depth = 5.0
[[layers]]
E = 20e6
nu = 0.3
unit_weight = 0.0
c = 10e3
phi_deg = 0.0
psi_deg = 0.0
[[strips]]
foundation = { x0 = -1.0, x1 = 1.0, section = { homogeneous = { thickness = 0.4, E = 30e9, nu = 0.2 } } }
contact = { kn = 1e10, kt = 1e9 }
[[loads]]
x = 0.0
N = {N}
[mesh]
h_fine = 0.5
h_coarse = 2.0
"""


def test_a_site_loaded_beyond_its_capacity_reports_the_solvers_status(tmp_path, capsys):
    """A 2 m strip on weightless Tresca clay (c = 10 kPa) carries Prandtl's (2 + pi) c B = 102.8 kN/m; under
    three times that the run must report the limit the solver found (or a stop), in the printed summary, the
    JSON and the HTML report -- not "completed"."""
    c, b = 10e3, 2.0
    # [N/m], Prandtl 1920: the exact collapse load of a rough or smooth strip on weightless Tresca soil
    prandtl = (2.0 + math.pi) * c * b
    path = tmp_path / "overloaded.toml"
    path.write_text(SOFT_CLAY.replace("{N}", repr(3.0 * prandtl)))
    code = main(["run", str(path), "--no-plots"])
    printed = capsys.readouterr().out
    s = json.loads((tmp_path / "overloaded_summary.json").read_text())
    report = (tmp_path / "overloaded_report.html").read_text()
    assert s["status"] in ("limit load reached", "stopped") and "status: completed" not in printed
    assert "status: completed" not in report and s["load_factor"] < 1.0
    if s["status"] == "limit load reached":
        assert code == 0 and s["complete"] is True  # a limit is an answer, as for a scene
        assert "limit load reached" in printed and "limit load reached" in report
        carried = s["limit_load_factor"] * 3.0 * prandtl
        # a displacement mesh this coarse overstates a collapse load (by ~20 % here), never understates it by
        # much: the bracket is the hand estimate's, not the code's
        assert 0.95 * prandtl < carried < 1.4 * prandtl
        assert "limit_suspect" in s
    else:
        assert code == 3 and s["complete"] is False


TWO_STRIPS = """
width = 30.0
depth = 10.0
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
contact = { kn = 4e9, kt = 4e8 }
[strips.foundation]
x0 = -7.0
x1 = -3.0
[strips.foundation.section.rc]
depth = 0.4
bars = [[0.05, 1.5e-3], [0.35, 1.5e-3]]
n_concrete = 9
concrete = { fc = 38e6, ls = 0.1 }
steel = { fy = 500e6, Es = 200e9 }
[[strips]]
foundation = { x0 = 3.0, x1 = 5.0, section = { homogeneous = { thickness = 0.5, E = 30e9, nu = 0.2 } } }
contact = { kn = 4e9, kt = 4e8 }
[[loads]]
x = -6.5
N = 300e3
[[loads]]
x = -3.5
N = 300e3
[[loads]]
x = 4.0
N = 200e3
[mesh]
h_fine = 0.5
h_coarse = 3.0
[solve]
force_tol = 1e-10
"""


def test_two_strip_site_summary_has_contact_resultants_moments_and_rc_design(tmp_path, capsys):
    """Each plate strip's contact resultant equals the column loads on it (the strip's free-body equilibrium,
    to the solver's force tolerance); the RC strip gets the design lines a scene's strip gets (crack width,
    M_Ed/M_Rd, V_Ed/V_Rd,c); the moment between two columns 3 m apart hogs."""
    path = tmp_path / "two.toml"
    path.write_text(TWO_STRIPS)
    assert main(["run", str(path), "--no-plots"]) == 0
    printed = capsys.readouterr().out
    s = json.loads((tmp_path / "two_summary.json").read_text())
    assert s["status"] == "completed" and s["load_factor"] == 1.0
    rc, plain = s["foundations"]
    for f, applied in ((rc, 600e3), (plain, 200e3)):
        assert f["applied_N_N_per_m"] == applied  # the file's column loads, summed by hand
        assert f["contact_N_N_per_m"] == pytest.approx(applied, rel=1e-9)
        assert f["max_abs_moment_Nm_per_m"] > 0.0
    assert plain["design"] is None  # an elastic section has nothing to design
    d = rc["design"]
    assert d["w_k_max_mm"] >= 0.0 and 0.0 < d["util_M_max"] < 1.0 and 0.0 < d["util_V_max"] < 1.0
    assert d["phases"]["loading"]["M_min_kNm"] < -d["phases"]["loading"]["M_max_kNm"] < 0.0  # hogging wins
    assert "M_Ed/M_Rd" in printed and "V_Ed/V_Rd,c" in printed and "w_k max" in printed
    report = (tmp_path / "two_report.html").read_text()
    assert "RC design" in report and "contact resultant [kN/m]" in report


def test_schema_lists_the_site_keys(capsys):
    """`ssi schema` prints the keys of both inputs: the site's tables and every field of each."""
    import dataclasses

    from ssi.scene.site import Borehole, RigidStrip, Site, Strip

    assert main(["schema"]) == 0
    text = capsys.readouterr().out
    for cls in (Site, Borehole, Strip, RigidStrip):
        assert f"[{cls.__name__}]" in text
        block = text.split(f"[{cls.__name__}]", 1)[1].split("\n[", 1)[0]
        keys = {line.split()[0] for line in block.splitlines()[1:] if line.strip()}
        assert keys == {f.name for f in dataclasses.fields(cls)}, cls.__name__
    assert "ELEVATION" in text.split("[Site]", 1)[1].split("\n[", 1)[0]  # a site's water table


def test_ssi_show_reads_a_site_result_back_with_the_solvers_status(tmp_path, capsys):
    """The result file of an overloaded site read back by `ssi show`: the same status and limit load factor
    as the run's JSON (one result-file path for a scene and a site)."""
    c, b = 10e3, 2.0
    path = tmp_path / "over.toml"
    path.write_text(SOFT_CLAY.replace("{N}", repr(3.0 * (2.0 + math.pi) * c * b)))
    main(["run", str(path), "--no-plots"])
    ran = json.loads((tmp_path / "over_summary.json").read_text())
    capsys.readouterr()
    main(["show", str(tmp_path / "over.h5"), "--no-plots", "--json"])
    shown = json.loads(capsys.readouterr().out.split("\nwrote", 1)[0])
    assert shown["kind"] == "site" and shown["status"] == ran["status"] != "completed"
    assert (
        shown["load_factor"] == ran["load_factor"] and shown["limit_load_factor"] == ran["limit_load_factor"]
    )


def test_ssi_run_estimate_on_a_site_file(tmp_path, capsys):
    """`ssi run --estimate` on a site of two plate strips: the estimate of the largest settlement is of the
    value the summary reports (the largest over the strips), from meshes that really are finer, and
    `ssi show` reads it back from the result file."""
    path = tmp_path / "two.toml"
    path.write_text(TWO_STRIPS)
    assert main(["run", str(path), "--no-plots", "--estimate"]) == 0
    printed = capsys.readouterr().out
    s = json.loads((tmp_path / "two_summary.json").read_text())
    est = s["error_estimate"]["quantities"]
    assert s["error_estimate"]["asked"] == "max_settlement" and "error estimate" in printed
    largest = max(f["max_settlement_m"] for f in s["foundations"])
    assert est["max_settlement"]["value"] == largest
    h, h2, h4 = est["max_settlement"]["values"]["mesh"]
    assert h == largest and h2 != h and h4 != h2  # three different meshes
    assert est["max_settlement"]["relative"] < 0.05  # a 0.5 m mesh of 2-4 m strips: settlements converge
    main(["show", str(tmp_path / "two.h5"), "--no-plots", "--json"])
    shown = json.loads(capsys.readouterr().out.split("\nwrote", 1)[0])
    assert shown["error_estimate"] == s["error_estimate"]


def test_ssi_run_on_a_phased_site_prints_every_phase(tmp_path, capsys):
    """A site loaded, then unloaded (``factors = { loads = 0.0 }``), through `ssi run` as a phased scene goes:
    the printed summary and the JSON give both phases with each one's settlement at its end, read back from
    the run's own result file, and the column load each phase ends with (the input's: N, then 0)."""
    from ssi.io.results import read_result

    n = 0.5 * (2.0 + math.pi) * 10e3 * 2.0  # [N/m] half Prandtl's collapse load of the strip (see above)
    path = tmp_path / "phased.toml"
    path.write_text(
        SOFT_CLAY.replace("{N}", repr(n)) + '[[phases]]\nname = "unload"\nfactors = { loads = 0.0 }\n'
    )
    assert main(["run", str(path), "--no-plots"]) == 0
    printed = capsys.readouterr().out
    s = json.loads((tmp_path / "phased_summary.json").read_text())
    out = read_result(tmp_path / "phased.h5")
    assert s["status"] == out.status == "completed" and s["phase"] == "unload"
    assert [r["name"] for r in s["phases"]] == ["loads", "unload"] == [r["name"] for r in out.phases[1:]]
    for row, record, column in zip(s["phases"], out.phases[1:], (n, 0.0)):
        end = record["last"]
        mean = out.strip_summary(0, end)["mean"]
        f = row["foundations"][0]
        assert (row["first"], row["last"]) == (record["first"], end)
        assert f["mean_settlement_m"] == mean and f["max_settlement_m"] == out.strip_summary(0, end)["max"]
        assert f["column_N_N_per_m"] == column
        # the plate's equilibrium: the soil carries what stands on the strip at the phase's end
        assert out.contact_resultant(0, end)["N"] == pytest.approx(column, rel=1e-9, abs=1e-9 * n)
        line = printed.split(f"phase {row['name']!r} (steps {record['first']}-{end}", 1)[1].split("\n")[1]
        assert (
            f"settlement mean {1e3 * mean:.2f} mm" in line and f"column load {column / 1e3:.2f} kN/m" in line
        )
    loaded, unloaded = (r["foundations"][0]["mean_settlement_m"] for r in s["phases"])
    assert 0.0 <= unloaded < loaded  # unloading recovers the elastic part (the yielded edges keep theirs)
    assert s["foundations"][0]["applied_N_N_per_m"] == 0.0  # the run ends unloaded
    # the HTML report carries the same per-phase rows as the JSON (mm and kN/m, as printed)
    report = (tmp_path / "phased_report.html").read_text()
    assert "<h2>Per phase</h2>" in report
    for row in s["phases"]:
        f = row["foundations"][0]
        cells = (
            f"<td>{row['name']}</td><td>{row['first']}–{row['last']}</td><td>0</td>"
            f'<td class="num">{1e3 * f["mean_settlement_m"]:.3f}</td>'
        )
        assert cells in report and f'<td class="num">{f["column_N_N_per_m"] / 1e3:.2f}</td>' in report
