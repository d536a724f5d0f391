"""Benchmark of issue 30: chapter 11's foundation bracketed to a 2 % gap by finite-element limit analysis.

The scene of chapter 11 (``ssi.lab.examples.chapter11_foundation``: a 6 m RC strip, 0.4 m deep, under two
400 kN/m columns on layered soil with a Coulomb contact), its capacity by ``Scene.limit_analysis``: lambda
scales the columns, the strip's self weight with them (one phase). The strip is a beam with plastic hinges
(the default for its ductile RC section, M_p from ssi's section analysis); the associated bracket (psi =
phi of soil and contact) is refined until (UB - LB)/(UB + LB) <= 2 %. Prints ``fela_ch11_gap2pct_s`` (wall
time of the adaptive sequence; goal <= 60 s), the final bounds, the number of triangles, of cones and
Clarabel's iterations of each bound on the last mesh; one line per refinement goes to stderr.
"""

import sys
import time

from goals import verdict

from ssi.lab.examples import chapter11_foundation


def main() -> int:
    scene = chapter11_foundation()

    def progress(label, r):
        print(
            f"  {label} {r['n_el']:6d} triangles  LB {r['best_lb']:.4f}  UB {r['best_ub']:.4f}  "
            f"gap {100 * r['gap']:.2f} %  t_LB {r['t_lb']:.2f} s  t_UB {r['t_ub']:.2f} s",
            file=sys.stderr,
        )

    t0 = time.perf_counter()
    cap = scene.limit_analysis(gap=0.02, davis=False, progress=progress)
    wall = time.perf_counter() - t0
    res = cap.associated
    last = res.history[-1]
    print(f"fela_ch11_gap2pct_s: {wall:.1f}" + verdict(wall, "<=", 60.0, " s"))
    print(
        f"fela_ch11_gap2pct_bounds: lambda in [{res.lb:.4f}, {res.ub:.4f}] x the columns (gap {res.gap:.4f})"
    )
    print(f"fela_ch11_gap2pct_triangles: {last['n_el']}   (refinements: {len(res.history) - 1})")
    print(f"fela_ch11_gap2pct_cones: LB {last['cones_lb']}, UB {last['cones_ub']}")
    print(f"fela_ch11_gap2pct_iterations: LB {last['it_lb']}, UB {last['it_ub']}")
    return 0 if res.converged else 1


if __name__ == "__main__":
    sys.exit(main())
