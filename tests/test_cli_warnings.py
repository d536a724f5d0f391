"""Warnings written for an engineer (issue 46 item 3): what, where, what to do -- on stderr as `WARNING: ...`
and in the run report, never as a Python warning with its category and source path, including those the
input file raises while it is read (before the solve) and those of `ssi limit`."""

import warnings

from ssi.io.cli import main, warning_text

SCENE = """
width = 12.0
depth = 5.0

[[layers]]
thickness = 5.0
E = 30e6
nu = 0.3
unit_weight = 18.0
c = 20e3
phi_deg = 0.0
psi_deg = 0.0

[foundation]
x0 = -1.0
x1 = 1.0

[foundation.section.rc]
depth = 0.6
bars = [[0.058, 1.34e-3], [0.544, 2.0e-4]]
n_concrete = 6
concrete = { fc = 38e6, ls = 0.1 }
steel = { fy = 500e6, Es = 200e9 }

[contact]
kn = 1e10
kt = 1e9

[[loads]]
x = 0.0
N = 100e3

[mesh]
h_fine = 0.5
h_coarse = 2.0

[solve]
n_steps = 2
"""


def test_run_warnings_read_as_sentences_with_what_to_do(tmp_path, capsys):
    """The unit weight 18 N/m^3 (kN/m^3 meant) is warned while the file is read; the top face's sparse bars
    (2 cm^2/m) give a crack spacing beyond the snap-back limit (a CrackBandWarning) while the scene builds.
    Both reach stderr and the report as sentences with what to do, and no Python warning escapes."""
    path = tmp_path / "warn.toml"
    path.write_text(SCENE)
    with warnings.catch_warnings(record=True) as leaked:
        warnings.simplefilter("always")
        assert main(["run", str(path), "--no-plots", "--no-capacity"]) == 0
    assert [str(w.message) for w in leaked] == []
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.startswith("WARNING: ")]
    units = [ln for ln in lines if "layers[0].unit_weight = 18 N/m^3 looks small" in ln]
    band = [ln for ln in lines if "crack band of the top face" in ln]
    assert len(units) == 1 and len(band) == 1, err
    assert all("What to do: " in ln for ln in units + band)
    assert ".py:" not in err and "Warning:" not in err  # no source path, no Python category
    page = (tmp_path / "warn_report.html").read_text()
    assert "looks small for SI units" in page and "crack band of the top face" in page
    assert page.count("What to do: ") >= 2 and ".py:" not in page


def test_a_warning_that_says_what_to_do_is_left_as_it_is():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.warn("x is odd. What to do: nothing", UserWarning, stacklevel=1)
        warnings.warn("y looks small for SI units", UserWarning, stacklevel=1)
    a, b = (warning_text(w) for w in caught)
    assert a == "x is odd. What to do: nothing"
    assert b.startswith("y looks small for SI units. What to do: check the value's unit")


def test_limit_warnings_read_as_sentences_in_its_report(tmp_path, capsys):
    """`ssi limit` of the same scene: the top face's bars are below the minimum (the section cracks above
    its yield moment), so the strip forms no plastic hinge and is taken rigid -- said once, on stderr and
    in the limit report, with what to do, and no Python warning escapes."""
    path = tmp_path / "warn.toml"
    path.write_text(SCENE)
    with warnings.catch_warnings(record=True) as leaked:
        warnings.simplefilter("always")
        assert main(["limit", str(path), "--gap", "0.3", "--max-elements", "600", "--no-plots"]) == 0
    assert [str(w.message) for w in leaked] == []
    err = capsys.readouterr().err
    (line,) = [ln for ln in err.splitlines() if ln.startswith("WARNING: ")]
    assert "brittle on its top face" in line and "What to do: read the bracket as a rigid strip's" in line
    page = (tmp_path / "warn_limit_report.html").read_text()
    assert "<h2>Warnings</h2>" in page and "brittle on its top face" in page and ".py:" not in page


def test_a_bad_fos_gap_is_refused_before_the_solve(tmp_path, capsys):
    path = tmp_path / "warn.toml"
    path.write_text(SCENE)
    assert main(["run", str(path), "--fos-gap", "2"]) == 2
    assert "fos_gap (--fos-gap) must be a finite number in (0, 1], got 2.0" in capsys.readouterr().err
    assert not (tmp_path / "warn.h5").exists()
