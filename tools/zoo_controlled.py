"""Solve the random zoo (seed 1) on the controlled path and print each scene's outcome, the counts and the
wall time: the measurement behind issue 31's switch (row zoo_solved_controlled). Off-line only.

    python tools/zoo_controlled.py [--scenes 0,24,66] [--n 100] [--control work] [--csv out.csv]
"""

import argparse
import csv
import sys
import time

from ssi.lab.zoo import random_scenes, solve_zoo
from ssi.solver import Settings


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100, help="random scenes drawn (seed 1)")
    ap.add_argument("--scenes", default="", help="comma-separated indices to run (default: all n)")
    ap.add_argument("--control", default="work", choices=("load", "work"))
    ap.add_argument("--csv", default="", help="write one row per scene here")
    args = ap.parse_args(argv)
    scenes = random_scenes(args.n, seed=1)
    if args.scenes:
        keep = {int(i) for i in args.scenes.split(",")}
        scenes = [s for i, s in enumerate(scenes) if i in keep]
    t0 = time.perf_counter()
    rows = []
    for name, scene in scenes:
        (o,) = solve_zoo([(name, scene)], Settings(control=args.control))
        rows.append(o)
        lim = "" if o.limit_load is None else f" limit={o.limit_load:.4f}"
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
    return 0


if __name__ == "__main__":
    sys.exit(main())
