"""Solve the h/16 graded copy of chapter 11's foundation once on the controlled path and store its outcome
(chapter 11's row ``ch11_h16`` reads it): the copy on which the old load-controlled path reported a false
collapse at lambda = 0.606.

    python tools/chapter11_h16.py [--out FILE] [--overwrite]

The copy is ``chapter11_foundation(0.0625, h_coarse=0.25, end_grading=1.75)`` (chapter 13's graded family,
h = 1 m halved four times; 70 989 DOFs), solved with ``Settings(control="work")`` (ssi/solver/path.py). Its
outcome is one row, whatever it is: "completed" at lambda = 1, a limit on the controlled path with its load
factor, or NonConvergence with its message -- never left out, because the row checks exactly that outcome
(completed, or an honest NonConvergence; a limit only at or above the foundation's certified lower bound).
Too long for every ``make reproduce`` (minutes on the project's 2-core machine): run once per solver change;
the commit is stored with it. The file is written atomically; an existing one is replaced only with
``--overwrite``.
"""

import argparse
import time
from pathlib import Path

from ssi.lab.digitize import source_commit, write_reference
from ssi.lab.examples import chapter11_foundation
from ssi.solver import NonConvergence, Settings

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_OUT = ROOT / "reference_data" / "chapter11_h16_controlled.csv"
H16 = 0.0625  # [m] h = 1 m halved four times
END_GRADING = 1.75  # chapter 13's graded family


def solve_h16() -> dict:
    """The copy's outcome: status, last load factor, max settlement [mm], steps, DOFs, wall time [s]."""
    built = chapter11_foundation(H16, h_coarse=4.0 * H16, end_grading=END_GRADING).build()
    t0 = time.perf_counter()
    try:
        out = built.solve(settings=Settings(control="work"))
        status, lam, message = out.status, float(out.load_factor[-1]), out.solver_result.message
        settlement = 1e3 * out.max_settlement()[1]
        steps = out.solver_result.n_steps
    except NonConvergence as err:  # its report names the load factor it stopped at
        status, message = "NonConvergence", str(err).splitlines()[0]
        lam = float(err.report.get("load_factor_from", float("nan")))
        settlement, steps = float("nan"), -1
    row = {
        "status": status,
        "load_factor": lam,
        "max_settlement_mm": settlement,
        "n_steps": steps,
        "n_dof": built.model.n_dof,
        "wall_s": round(time.perf_counter() - t0, 1),
        "message": message.replace(",", ";")[:300],
    }
    print(row)
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT)
    ap.add_argument("--overwrite", action="store_true")
    args = ap.parse_args(argv)
    if args.out.exists() and not args.overwrite:
        raise SystemExit(f"{args.out} exists; pass --overwrite to replace it")
    row = solve_h16()
    commit = source_commit(ROOT)
    meta = {
        "source": "this project (ssi): the outcome of one solve of the h/16 graded copy of chapter 11's "
        "foundation on the controlled path",
        "figure": "chapter 11, row ch11_h16",
        "units": "load_factor [-] of the columns' service load; max_settlement_mm [mm]; wall_s [s]",
        "trust": "B (numerical: the solver's own outcome, as it ended)",
        "uncertainty": "none stated: an outcome, not a measured value",
        "how_obtained": f"python tools/chapter11_h16.py: chapter11_foundation({H16}, h_coarse={4 * H16}, "
        f"end_grading={END_GRADING}).build().solve(settings=Settings(control='work')), commit {commit}, "
        f"{time.strftime('%Y-%m-%d')}",
    }
    write_reference(args.out, meta, {k: [v] for k, v in row.items()})  # atomic
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
