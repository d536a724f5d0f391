"""The verification report: ``check`` records a row and asserts it in one call; ``record`` only records."""

import csv

import pytest

from ssi.lab import paths, report


@pytest.fixture
def figures(tmp_path, monkeypatch):
    monkeypatch.setattr(paths, "FIGURES", tmp_path)
    return tmp_path


def row(folder, row_id):
    with open(folder / "report.d" / f"{row_id}.csv", newline="") as fh:
        return next(csv.reader(fh))


def test_check_records_a_passing_claim(figures):
    report.check("claim_ok", "relative error", -2e-4, 1e-3)  # |value| <= tolerance by default
    assert row(figures, "claim_ok") == ["claim_ok", "relative error", "-0.0002", "0.001", "PASS"]


def test_check_records_the_fail_row_before_it_raises(figures):
    with pytest.raises(
        AssertionError, match=r"claim_bad: value 0\.5, tolerance 0\.1 \(relative error\) see x"
    ):
        report.check("claim_bad", "relative error", 0.5, 0.1, note="see x")
    assert row(figures, "claim_bad")[-1] == "FAIL"


def test_check_takes_the_condition_when_the_claim_is_not_a_bound(figures):
    bound = 2.0
    for ratio, status in ((3.0, "PASS"), (1.0, "FAIL")):  # |ratio| <= bound would give the opposite
        if status == "PASS":
            report.check("lower_bound", "ratio (pass if >= tolerance)", ratio, bound, ratio >= bound)
        else:
            with pytest.raises(AssertionError):
                report.check("lower_bound", "ratio (pass if >= tolerance)", ratio, bound, ratio >= bound)
        assert row(figures, "lower_bound")[-1] == status


def test_record_alone_never_raises(figures):
    report.record("reported_only", "a reproduced number outside its reference", 0.4, 0.1, False)
    assert row(figures, "reported_only")[-1] == "FAIL"
