"""Benchmark of the robust-solution issue: the zoo of ordinary scenes (``ssi.lab.zoo.ordinary_scenes``) solved
with the default ``Settings()``, one process, JIT cached by a warm-up scene first.

Prints ``zoo_total_s`` (wall time of the whole zoo), ``zoo_solved_fraction`` (scenes that reached their load
or a detected collapse) and, on stderr, each scene's outcome and time.
"""

import sys
import time

from ssi.lab.zoo import ordinary_scenes, solve_zoo


def main():
    scenes = ordinary_scenes()
    t0 = time.perf_counter()
    solve_zoo(scenes[:1])  # JIT (cached after the first process)
    print(f"# jit+warm-up: {time.perf_counter() - t0:.2f} s", file=sys.stderr)
    t0 = time.perf_counter()
    outcomes = solve_zoo(scenes)
    total = time.perf_counter() - t0
    for o in outcomes:
        print(
            f"# {o.name:40s} {o.status:20s} lambda={o.load_factor:.3f} {o.wall_time:6.2f} s", file=sys.stderr
        )
    print(f"zoo_total_s: {total:.2f}")
    print(f"zoo_solved_fraction: {sum(o.solved for o in outcomes) / len(outcomes):.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
