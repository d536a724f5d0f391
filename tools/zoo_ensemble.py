"""Solve every random zoo scene (seed 1) as drawn and in round-off copies, with each linear-solver back end
and once under a generic CPU target, and store the outcome table: issue 45, item 3 (chapter 06's rows
``zoo_service_completes``, ``zoo_path_reach`` and ``zoo_roundoff_outcomes``). Off-line only.

    python tools/zoo_ensemble.py [--scenes 21,22,23] [--workers N] [--runs FILE] [--no-generic]
    python tools/zoo_ensemble.py --store [--overwrite]

The runs of one scene, all on the controlled path with the user's psi (``Settings(control="work",
backend=...)``, the zoo's default path):

* copies: the scene as drawn (copy ``drawn``) and 4 copies with every soil layer's Young's modulus E
  multiplied by 1 - 2e-13, 1 - 1e-13, 1 + 1e-13 and 1 + 2e-13 (copies ``1-2e-13`` ... ``1+2e-13``;
  :func:`ssi.lab.zoo_limits.perturb_soil_modulus`): changes of the soil kernel's numbers at round-off level,
  nothing else;
* back ends: every copy with SuperLU, and again with PARDISO when it is installed (``pypardiso``; otherwise
  the table's header says "not installed");
* CPU: every copy above with numba compiling for the host CPU (``native``: its name is recorded), and the
  scene as drawn once more with SuperLU under ``NUMBA_CPU_NAME=generic`` -- numba reads that variable when it
  is imported, so those runs are a separate process (this script again) with its own kernel cache
  (``.numba_cache_generic``; a cache compiled for the host CPU must not be loaded for another target).

Per run: scene, copy, back end, cpu, status, the last converged load factor, the limit (a detected limit's
load factor, else empty), the largest settlement under the foundation at lambda = 1 (completed runs only:
``SceneResult.max_settlement``), the wall time and the solver's message.

Resumable: every finished run is appended at once to the runs file (``--runs``, default
``results/zoo_ensemble_runs.csv``) with the commit it was solved at; a later invocation at the same commit
skips the runs the file holds, so the zoo can be solved in scene subsets (``--scenes``), in several sittings,
and merged. Runs of another commit (or with uncommitted changes under ``ssi/``) are never mixed in.
``--store`` writes the runs of the current commit to ``reference_data/zoo_ensemble.csv`` (atomically;
an existing file only with ``--overwrite``): only scenes with every run done, its header naming which
scenes (all 100 or a subset), the machine, the commit and the date.

``--workers N`` solves N scenes at a time (a process pool, each scene a task; default 1). The CPU is shared:
run it under ``nice``. Last measured: see the stored table's ``how_obtained``.
"""

import argparse
import csv
import datetime
import multiprocessing
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
STORED = ROOT / "reference_data" / "zoo_ensemble.csv"
DEFAULT_RUNS = ROOT / "results" / "zoo_ensemble_runs.csv"
GENERIC_CACHE = ROOT / ".numba_cache_generic"
N_SCENES, SEED = 100, 1
# the round-off copies: label -> factor on every soil layer's E ("drawn": the scene as drawn); the labels are
# not numbers, so the stored column reads back as text
COPIES = {
    "drawn": 1.0,
    "1-2e-13": 1 - 2e-13,
    "1-1e-13": 1 - 1e-13,
    "1+1e-13": 1 + 1e-13,
    "1+2e-13": 1 + 2e-13,
}
RUN_COLUMNS = (
    "scene",
    "copy",
    "backend",
    "cpu",
    "status",
    "load_factor",
    "limit",
    "settlement_m",
    "wall_s",
    "message",
    "commit",
)


def cpu_label() -> str:
    """The target numba compiles for in this process: ``generic`` under NUMBA_CPU_NAME=generic, otherwise
    ``native`` with the host CPU's name (llvmlite's)."""
    name = os.environ.get("NUMBA_CPU_NAME", "")
    if name:
        return name
    import llvmlite.binding as llvm

    return f"native ({llvm.get_host_cpu_name()})"


def backends() -> tuple[str, ...]:
    """The linear-solver back ends available here: SuperLU always, PARDISO where installed."""
    from ssi.core.linsolve import pardiso_available

    return ("superlu", "pardiso") if pardiso_available() else ("superlu",)


def machine() -> str:
    """CPU model, cores and the versions the arithmetic depends on."""
    import numba
    import numpy
    import scipy

    model = platform.processor() or "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return (
        f"{model}, {os.cpu_count()} cores; python {platform.python_version()}, numba {numba.__version__}, "
        f"numpy {numpy.__version__}, scipy {scipy.__version__}"
    )


# what a run depends on: the package, but not this table's reader nor the guides
SOURCES = ("ssi", ":(exclude)ssi/lab/zoo_ensemble.py", ":(exclude)*.md")


def commit() -> str:
    """The last commit that changed :data:`SOURCES` (a commit of tools, chapters, tests or the table's
    reader leaves a half-solved zoo resumable), " + uncommitted ssi/ changes" when the work tree differs
    there."""

    def git(*args):
        return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True).stdout.strip()

    at = git("log", "-1", "--format=%h", "--", *SOURCES)
    return at + (" + uncommitted ssi/ changes" if git("status", "--porcelain", "--", *SOURCES) else "")


def plan(cpu: str) -> list[tuple[str, str]]:
    """(copy, backend) of each run of one scene in a process compiling for ``cpu``: every copy with every
    back end natively; the scene as drawn with SuperLU under a generic target."""
    if cpu == "generic":
        return [("drawn", "superlu")]
    return [(c, b) for b in backends() for c in COPIES]


def solve_scene(task, emit=None) -> list[dict]:
    """The runs of one scene (a pool task): ``task`` = (scene index, [(copy, backend), ...], commit);
    ``emit([row])``, when given, is called after each run (a single process keeps each run at once)."""
    from ssi.lab.zoo import random_scenes, solve_zoo
    from ssi.lab.zoo_limits import perturb_soil_modulus
    from ssi.solver import Settings

    index, runs, at = task
    name, scene = random_scenes(N_SCENES, seed=SEED)[index]
    cpu = cpu_label()
    rows = []
    for copy, backend in runs:
        drawn = scene if copy == "drawn" else perturb_soil_modulus(scene, COPIES[copy])
        (o,) = solve_zoo([(name, drawn)], Settings(control="work", backend=backend))
        completed = o.status == "completed"
        rows.append(
            {
                "scene": name,
                "copy": copy,
                "backend": backend,
                "cpu": cpu,
                "status": o.status,
                "load_factor": f"{o.load_factor:.9g}",
                "limit": "" if o.limit_load is None else f"{o.limit_load:.9g}",
                "settlement_m": f"{o.settlement:.9g}" if completed and o.settlement is not None else "",
                "wall_s": f"{o.wall_time:.2f}",
                "message": " ".join(o.message.replace(",", ";").split())[:300],
                "commit": at,
            }
        )
        print(
            f"{name:10s} copy {copy:>6s} {backend:7s} {cpu[:7]:7s} {o.status:19s} lam={o.load_factor:.5f}"
            + ("" if o.limit_load is None else f" limit={o.limit_load:.5f}")
            + (f" s={1e3 * o.settlement:.3f} mm" if completed and o.settlement is not None else "")
            + f" {o.wall_time:6.1f}s",
            flush=True,
        )
        if emit is not None:
            emit(rows[-1:])
    return rows


def key(row: dict) -> tuple[str, str, str, str]:
    cpu = "generic" if row["cpu"] == "generic" else "native"
    return row["scene"], row["copy"], row["backend"], cpu


def read_runs(path: Path, at: str) -> list[dict]:
    """The runs of ``path`` solved at commit ``at`` (others are reported and left out)."""
    if not path.exists():
        return []
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    other = sum(r["commit"] != at for r in rows)
    if other:
        print(f"{path}: {other} runs of another commit (or uncommitted changes) left out", flush=True)
    return [r for r in rows if r["commit"] == at]


def append_runs(path: Path, rows: list[dict]) -> None:
    """Append finished runs (one writer per file: only the main process of an invocation writes)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    new = not path.exists() or path.stat().st_size == 0
    with open(path, "a", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=RUN_COLUMNS, lineterminator="\n")
        if new:
            w.writeheader()
        w.writerows(rows)


def run(indices: list[int], runs_file: Path, workers: int, at: str) -> float:
    """Solve the runs of ``indices`` in this process's CPU target not yet in ``runs_file``; the wall time."""
    cpu = "generic" if os.environ.get("NUMBA_CPU_NAME") == "generic" else "native"
    done = {key(r) for r in read_runs(runs_file, at)}
    tasks = []
    for i in indices:
        todo = [(c, b) for c, b in plan(cpu) if (f"random {i}", c, b, cpu) not in done]
        if todo:
            tasks.append((i, todo, at))
    print(f"{cpu}: {sum(len(t[1]) for t in tasks)} runs of {len(tasks)} scenes to solve", flush=True)
    t0 = time.perf_counter()
    if workers > 1 and len(tasks) > 1:
        with multiprocessing.get_context("spawn").Pool(workers) as pool:
            for rows in pool.imap_unordered(solve_scene, tasks):
                append_runs(runs_file, rows)
    else:
        for task in tasks:
            solve_scene(task, emit=lambda rows: append_runs(runs_file, rows))
    return time.perf_counter() - t0


def run_generic(indices: list[int], runs_file: Path, workers: int) -> None:
    """The generic-CPU runs: this script again in a process whose numba is imported with
    NUMBA_CPU_NAME=generic and its own cache directory."""
    env = dict(os.environ, NUMBA_CPU_NAME="generic", NUMBA_CACHE_DIR=str(GENERIC_CACHE))
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), env.get("PYTHONPATH", "")) if p)
    cmd = [sys.executable, str(Path(__file__).resolve()), "--scenes", ",".join(map(str, indices))]
    cmd += ["--runs", str(runs_file), "--workers", str(workers), "--no-generic"]
    subprocess.run(cmd, env=env, check=True)


def store(runs_file: Path, at: str) -> None:
    """Every scene whose runs are all done at commit ``at``, written atomically to :data:`STORED` with the
    machine, the commit and the date."""
    from ssi.lab.digitize import write_reference

    rows = read_runs(runs_file, at)
    expected = {(c, b, "native") for c, b in plan("native")} | {(c, b, "generic") for c, b in plan("generic")}
    by_scene: dict[str, dict] = {}
    for r in rows:
        by_scene.setdefault(r["scene"], {})[key(r)[1:]] = r  # the last run of a key wins
    complete = sorted(
        (n for n, runs in by_scene.items() if expected <= set(runs)), key=lambda n: int(n.split()[1])
    )
    if not complete:
        raise SystemExit(
            f"{runs_file}: no scene has all its {len(expected)} runs at commit {at}: nothing stored"
        )
    kept = [by_scene[n][k] for n in complete for k in sorted(expected, key=_order)]
    wall = sum(float(r["wall_s"]) for r in kept)
    cpus = sorted({r["cpu"] for r in kept})
    scenes = (
        f"all {N_SCENES}"
        if len(complete) == N_SCENES
        else f"{len(complete)} of {N_SCENES}: {', '.join(complete)}"
    )
    meta = {
        "source": "this project (ssi): the outcomes of the random zoo scenes (seed 1) on the controlled path "
        "with the user's psi, as drawn and in round-off copies, per linear-solver back end and CPU target",
        "figure": "chapter 06, rows zoo_service_completes, zoo_path_reach and zoo_roundoff_outcomes",
        "units": "load_factor (last converged) and limit [-] of each scene's reference load; settlement_m: "
        "the largest settlement under the foundation at lambda = 1 [m] (completed runs only); wall_s [s]",
        "trust": "B (numerical: the solver's own outcomes, as they ended)",
        "uncertainty": "none stated: outcomes; their spread over the copies is what the table measures",
        "how_obtained": f"python tools/zoo_ensemble.py --store: solve_zoo(random_scenes(100, seed=1)[i], "
        f"Settings(control='work', backend=...)), ssi/ at commit {at} (its last change but the table's "
        f"reader), {datetime.date.today().isoformat()}, "
        f"{wall:.0f} s of runs (summed)",
        "scenes": scenes,
        "copies": "drawn = as drawn; 1-2e-13, 1-1e-13, 1+1e-13, 1+2e-13 = every soil layer's E x that factor",
        "backends": "superlu" + ("" if "pardiso" in backends() else "; pardiso: not installed (pypardiso)"),
        "cpu": f"{', '.join(cpus)} (generic: NUMBA_CPU_NAME=generic, the scene as drawn with superlu, "
        "own kernel cache)",
        "machine": machine(),
    }
    columns = {k: [r[k] for r in kept] for k in RUN_COLUMNS if k != "commit"}
    write_reference(STORED, meta, columns)
    print(f"wrote {STORED}: {len(complete)} scenes, {len(kept)} runs", flush=True)


def _order(k):
    copy, backend, cpu = k
    return cpu != "native", backend, list(COPIES).index(copy)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--scenes", default="", help="indices of the random zoo, comma-separated (default: all 100)"
    )
    ap.add_argument("--workers", type=int, default=1, help="scenes solved at a time (process pool)")
    ap.add_argument("--runs", type=Path, default=DEFAULT_RUNS, help="the runs file (appended, resumable)")
    ap.add_argument("--no-generic", action="store_true", help="leave out the NUMBA_CPU_NAME=generic runs")
    ap.add_argument("--store", action="store_true", help=f"write the runs of this commit to {STORED}")
    ap.add_argument("--overwrite", action="store_true", help="with --store: replace an existing table")
    args = ap.parse_args(argv)
    if args.workers < 1:
        raise SystemExit(f"--workers must be >= 1, got {args.workers}")
    if args.store and STORED.exists() and not args.overwrite:
        raise SystemExit(f"{STORED} exists; pass --overwrite to replace it")
    indices = list(range(N_SCENES))
    if args.scenes:
        indices = [int(i) for i in args.scenes.split(",")]
        bad = [i for i in indices if not 0 <= i < N_SCENES]
        if bad:
            raise SystemExit(f"--scenes: indices {bad} outside 0..{N_SCENES - 1}")
    at = commit()
    print(f"commit {at}; {machine()}; cpu {cpu_label()}; back ends {', '.join(backends())}", flush=True)
    wall = run(indices, args.runs, args.workers, at)
    print(f"{cpu_label()}: {wall:.0f} s", flush=True)
    if not args.no_generic and os.environ.get("NUMBA_CPU_NAME") != "generic":
        run_generic(indices, args.runs, args.workers)
    if args.store:
        store(args.runs, at)
    return 0


if __name__ == "__main__":
    sys.exit(main())
