"""Benchmark of issue 13: what the first run after an install costs, beside a warm run.

Runs the README's "A scene" block in a fresh Python process twice on one new, empty numba cache
folder: the first process compiles every kernel it needs (``first_run_cold_s``), the second finds them
cached (``readme_scene_s``, best of 3). Both are whole-process wall times (interpreter start, imports, build,
solve), with the processes' CPU times beside them. Goal (issue 16): cold <= 5 x warm + 10 s. A user who
installed with ``make`` never sees the cold case: the Makefile warms the cache right after installing.
``--python PATH``: the interpreter to measure (default: this one), e.g. the runtime-only venv of ``make
demo`` (issue 46: measured on the runtime install); ``first_run_notice`` says whether the cold process
printed the "compiling kernels once" notice. Prints ``key: value`` lines.
"""

import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from goals import verdict

ROOT = Path(__file__).resolve().parent.parent


def readme_block() -> str:
    text = (ROOT / "README.md").read_text()
    return re.search(r"```python\n(.*?)```", text, re.DOTALL).group(1)


PYTHON = sys.argv[sys.argv.index("--python") + 1] if "--python" in sys.argv else sys.executable


def timed_process(code: str, cache: str) -> tuple[float, float, str]:
    """(wall, CPU) seconds of one fresh process and its stderr; the CPU time (user + system of the child)
    is what a shared machine's load does not inflate."""
    env = {**os.environ, "NUMBA_CACHE_DIR": cache, "MPLBACKEND": "Agg"}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    run = subprocess.run(
        [PYTHON, "-c", code], env=env, check=True, cwd=ROOT, stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), run.stderr


def main():
    code = readme_block()
    with tempfile.TemporaryDirectory(prefix="ssi_numba_cold_") as cache:
        cold, cold_cpu, cold_err = timed_process(code, cache)
        warm, warm_cpu, _ = min(timed_process(code, cache) for _ in range(3))
    goal = 5.0 * warm + 10.0
    print(f"first_run_cold_s: {cold:.2f}{verdict(cold, '<=', goal, ' s = 5 x readme_scene_s + 10 s')}")
    print(f"readme_scene_s: {warm:.2f}   (best of 3)")
    print(f"first_run_notice: {'compiling kernels once' in cold_err}   (python: {PYTHON})")
    print(f"first_run_cold_cpu_s: {cold_cpu:.2f}")
    print(f"readme_scene_cpu_s: {warm_cpu:.2f}")


if __name__ == "__main__":
    main()
