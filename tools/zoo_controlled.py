"""Solve the random zoo (seed 1) on the controlled path and print each scene's outcome, the counts and the
wall time: the measurement behind issue 31's switch (row zoo_solved_controlled). Off-line only.

    python tools/zoo_controlled.py [--scenes 0,24,66] [--n 100] [--control work] [--csv out.csv]
    python tools/zoo_controlled.py --store [--overwrite]

``--store`` runs all 100 scenes and writes their outcomes with the commit and date to
``reference_data/zoo_controlled_random.csv`` (atomically; an existing file only with ``--overwrite``), which
chapter 06's row ``zoo_solved_controlled`` reads: all 100 take minutes (too long for every ``make
reproduce``), so the chapter solves the first 20 and checks them against the stored outcomes (a stale table
fails the row). Run it once per solver change.
"""

import argparse
import csv
import sys
import time
from dataclasses import replace
from pathlib import Path

from ssi.lab.digitize import source_commit, write_reference
from ssi.lab.zoo import random_scenes, solve_zoo
from ssi.solver import Settings

ROOT = Path(__file__).resolve().parent.parent
STORED = ROOT / "reference_data" / "zoo_controlled_random.csv"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100, help="random scenes drawn (seed 1)")
    ap.add_argument("--scenes", default="", help="comma-separated indices to run (default: all n)")
    ap.add_argument("--control", default="work", choices=("load", "work"))
    ap.add_argument("--flow", default="user", choices=("user", "davis"))
    ap.add_argument("--symmetric", default=None, choices=("yes", "no"), help="Settings.symmetric_tangent")
    ap.add_argument("--csv", default="", help="write one row per scene here")
    ap.add_argument(
        "--store", action="store_true", help=f"all 100 on the controlled path, stored in {STORED}"
    )
    ap.add_argument("--overwrite", action="store_true", help="with --store: replace an existing table")
    args = ap.parse_args(argv)
    if args.store and (args.scenes or args.n != 100 or args.control != "work"):
        raise SystemExit(
            "--store runs the 100 scenes on the controlled path: leave out --scenes/--n/--control"
        )
    if args.store and STORED.exists() and not args.overwrite:
        raise SystemExit(f"{STORED} exists; pass --overwrite to replace it")
    scenes = random_scenes(args.n, seed=1)
    if args.scenes:
        keep = {int(i) for i in args.scenes.split(",")}
        scenes = [s for i, s in enumerate(scenes) if i in keep]
    settings = Settings(control=args.control, flow=args.flow)
    if args.symmetric is not None:
        settings = replace(settings, symmetric_tangent=args.symmetric == "yes")
    t0 = time.perf_counter()
    rows = []
    for name, scene in scenes:
        (o,) = solve_zoo([(name, scene)], settings)
        rows.append(o)
        lim = "" if o.limit_load is None else f" limit={o.limit_load:.4f}"
        lim += "" if o.limit_mechanism is None else f" mechanism={o.limit_mechanism:.4f}"
        print(
            f"{o.name:10s} {o.status:19s} lam={o.load_factor:.4f}{lim} {o.wall_time:6.2f}s "
            f"{o.message[:300] if o.status == 'failed' else ''}",
            flush=True,
        )
    counts = {s: sum(o.status == s for o in rows) for s in ("completed", "limit load reached", "failed")}
    print(f"counts {counts}; wall {time.perf_counter() - t0:.1f} s", flush=True)
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["name", "status", "lam", "limit", "wall_s", "message"])
            for o in rows:
                w.writerow([o.name, o.status, o.load_factor, o.limit_load, f"{o.wall_time:.3f}", o.message])
    if args.store:
        store(rows, time.perf_counter() - t0)
    return 0


def store(rows, wall: float) -> None:
    """The 100 outcomes with their provenance (commit, date, wall time), written atomically."""
    meta = {
        "source": "this project (ssi): the outcomes of the 100 random zoo scenes (seed 1) on the controlled "
        "path",
        "figure": "chapter 06, row zoo_solved_controlled",
        "units": "load_factor and limit [-] of each scene's reference load; wall_s [s]",
        "trust": "B (numerical: the solver's own outcome, as it ended)",
        "uncertainty": "none stated: outcomes, not measured values",
        "how_obtained": f"python tools/zoo_controlled.py --store: solve_zoo(random_scenes(100, seed=1), "
        f"Settings(control='work')), commit {source_commit(ROOT, uncommitted_in='ssi')}, "
        f"{time.strftime('%Y-%m-%d')}, {wall:.0f} s",
    }
    columns = {
        "name": [o.name for o in rows],
        "status": [o.status for o in rows],
        "load_factor": [float(o.load_factor) for o in rows],
        "limit": [float("nan") if o.limit_load is None else float(o.limit_load) for o in rows],
        "wall_s": [round(float(o.wall_time), 2) for o in rows],
        "message": [o.message.replace(",", ";").replace("\n", " ")[:200] for o in rows],
    }
    write_reference(STORED, meta, columns)
    print(f"wrote {STORED}")


if __name__ == "__main__":
    sys.exit(main())
