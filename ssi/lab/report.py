"""The verification report: one row per checked claim, merged into ``figures/report.csv``.

Chapters call :func:`check` (record a claim and assert it), :func:`record` (record a number that is reported
but not asserted) or :func:`record_empty` (a reference slot still waiting for data); each row
lands in its own file under ``figures/report.d/`` so that chapters can run in any order or in parallel.
``python -m ssi.lab.report`` merges them into ``figures/report.csv`` (``id,metric,value,tolerance,status``)
and prints it. A FAIL row is a result, not a crash: the command still succeeds and names the FAIL rows (a
chapter's own asserts are what stop ``make reproduce``).
"""

import csv
import sys

from . import paths

HEADER = ["id", "metric", "value", "tolerance", "status"]
STATUSES = ("PASS", "FAIL", "EMPTY")


def _row_file(row_id: str):
    folder = paths.FIGURES / "report.d"
    folder.mkdir(parents=True, exist_ok=True)
    return folder / f"{row_id}.csv"


def _write(row_id, metric, value, tolerance, status):
    if not row_id.replace("_", "").isalnum():
        raise ValueError(f"report id must be alphanumeric with underscores, got {row_id!r}")
    from ..io.results import atomic_path

    # written whole or not at all: `make test` runs chapters in parallel processes, and a row file cut short
    # by a crash must not be merged as a truncated row
    with atomic_path(_row_file(row_id), overwrite=True) as tmp, open(tmp, "w", newline="") as fh:
        csv.writer(fh).writerow([row_id, metric, value, tolerance, status])


def record(row_id: str, metric: str, value: float, tolerance: float, passed: bool) -> None:
    """Record a checked number: status PASS if ``passed`` else FAIL. ``metric`` says what ``value`` is."""
    _write(row_id, metric, f"{float(value):.6g}", f"{float(tolerance):.6g}", "PASS" if passed else "FAIL")


def check(
    row_id: str, metric: str, value: float, tolerance: float, passed: bool | None = None, note: str = ""
) -> None:
    """Record a claim and assert it, in one call: the row is written first (so a failing claim still shows
    as FAIL in the report), then ``AssertionError`` names the row, its value and tolerance if it fails.

    ``passed`` defaults to ``abs(value) <= tolerance``; pass the condition itself when the claim is another
    (a lower bound, a monotone sequence, ...). ``note`` is added to the error message. Use :func:`record`
    for a row that is reported but deliberately not asserted (a reproduced number outside its reference)."""
    ok = abs(float(value)) <= float(tolerance) if passed is None else bool(passed)
    record(row_id, metric, value, tolerance, ok)
    if not ok:  # raised, not asserted: python -O must not turn a failed claim into a pass
        message = f"{row_id}: value {float(value):.6g}, tolerance {float(tolerance):.6g} ({metric})"
        raise AssertionError(f"{message} {note}".rstrip())


def record_empty(row_id: str, metric: str) -> None:
    """Record a reference slot that has no data yet (status EMPTY)."""
    _write(row_id, metric, "", "", "EMPTY")


def save_figure(fig, name: str) -> None:
    """Save a matplotlib figure as ``figures/<name>.png``."""
    paths.FIGURES.mkdir(parents=True, exist_ok=True)
    fig.savefig(paths.FIGURES / f"{name}.png", dpi=120, bbox_inches="tight")


def collect() -> list[list[str]]:
    """Merge the per-row files into ``figures/report.csv`` and return the rows (sorted by id)."""
    folder = paths.FIGURES / "report.d"
    rows = []
    for path in sorted(folder.glob("*.csv")) if folder.exists() else []:
        with open(path, newline="") as fh:
            rows.extend(r for r in csv.reader(fh) if r)
    paths.FIGURES.mkdir(parents=True, exist_ok=True)
    with open(paths.FIGURES / "report.csv", "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(HEADER)
        writer.writerows(rows)
    return rows


def main() -> int:
    rows = collect()
    widths = [max(len(r[i]) for r in rows + [HEADER]) for i in range(len(HEADER))]
    for r in [HEADER] + rows:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)))
    n_fail = sum(r[4] == "FAIL" for r in rows)
    n_empty = sum(r[4] == "EMPTY" for r in rows)
    print(
        f"\n{len(rows)} rows: {len(rows) - n_fail - n_empty} PASS, {n_fail} FAIL, {n_empty} EMPTY "
        f"(EMPTY = a reference slot still waiting for measured data)"
    )
    if n_empty:
        print("empty slots: " + ", ".join(r[0] for r in rows if r[4] == "EMPTY"))
    if n_fail:
        print(
            "FAIL (a reproduced number outside its reference's tolerance, reported, not hidden): "
            + ", ".join(r[0] for r in rows if r[4] == "FAIL")
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
