"""Benchmark of issue 46, item 4: is the capacity fast enough to be ``ssi run``'s default?

- ``capacity_readme_gap5pct_s``: the README's capacity scene ("Capacity and safety": chapter 10's
  rigid footing, c = 10 kPa, phi = 20 deg, psi = 0, a Settlement push; kept as measured since issue 46;
  the README's "A scene" has an elastic second layer, which never yields) bracketed to a 5 % gap, associated
  and Davis
  (``Scene.limit_analysis(gap=0.05)``); goal <= 5 s.
- ``capacity_two_strip_site_gap3pct_s``: a two-strip site of the issue's shape (``data/two_strip_site.toml``:
  two boreholes, a clay base dipping, a soft lens pinching out, a 1:3 slope, a water table; the shipped
  ``examples/sites/boreholes.toml`` has elastic layers only) to a 3 % gap (``Site.limit_analysis(gap=0.03)``);
  goal <= 30 s.

One line per mesh goes to stderr (triangles, best bounds, gap, seconds of each bound). ``SSI_LIMIT_LB_
INDICATOR=0`` runs the marking before issue 46 (the gap shares alone), for the before/after comparison.
``--only readme|site`` runs one of them.
"""

import sys
import time
from pathlib import Path

from goals import verdict

from ssi.scene import RigidFooting, Scene, Settlement, SoilLayer
from ssi.scene.scene_file import read_scene_file


def readme_scene() -> Scene:
    return Scene(
        width=12.0,
        depth=5.0,
        symmetric=True,
        layers=[SoilLayer(5.0, E=20e6, nu=0.3, c=10e3, phi_deg=20.0, psi_deg=0.0)],
        foundation=RigidFooting(-1.0, 1.0),
        loads=[Settlement(0.05)],
    )


def progress(label, r):
    print(
        f"  {label:10s} {r['n_el']:6d} triangles  LB {r['best_lb']:.5g}  UB {r['best_ub']:.5g}  gap "
        f"{100 * r['gap']:.2f} %  t_LB {r['t_lb']:.2f} s  t_UB {r['t_ub']:.2f} s",
        file=sys.stderr,
        flush=True,
    )


def run(name, what, gap, goal) -> bool:
    t0 = time.perf_counter()
    cap = what.limit_analysis(gap=gap, progress=progress)
    wall = time.perf_counter() - t0
    ok = cap.gap <= gap and cap.gap_davis <= gap
    print(f"{name}: {wall:.1f}" + verdict(wall, "<=", goal, " s"))
    print(f"{name}_bracket: associated [{cap.lb:.5g}, {cap.ub:.5g}] gap {100 * cap.gap:.2f} %, Davis "
          f"[{cap.lb_davis:.5g}, {cap.ub_davis:.5g}] gap {100 * cap.gap_davis:.2f} %, {cap.n_triangles} "
          f"triangles, gap {'reached' if ok else 'NOT reached'}")  # fmt: skip
    return ok


def main() -> int:
    only = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else None
    ok = True
    if only in (None, "readme"):
        ok &= run("capacity_readme_gap5pct_s", readme_scene(), 0.05, 5.0)
    if only in (None, "site"):
        site = read_scene_file(Path(__file__).parent / "data" / "two_strip_site.toml")[0]
        ok &= run("capacity_two_strip_site_gap3pct_s", site, 0.03, 30.0)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
