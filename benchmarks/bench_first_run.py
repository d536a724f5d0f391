"""Benchmark of issue 13: what the first run after an install costs, beside a warm run.

Runs the README's "Your own scene" block in a fresh Python process twice on one new, empty numba cache
folder: the first process compiles every kernel it needs (``first_run_cold_s``), the second finds them
cached (``readme_scene_s``). Both are whole-process wall times (interpreter start, imports, build, solve).
Prints ``key: value`` lines.
"""

import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def readme_block() -> str:
    text = (ROOT / "README.md").read_text()
    return re.search(r"```python\n(.*?)```", text, re.DOTALL).group(1)


def timed_process(code: str, cache: str) -> float:
    env = {**os.environ, "NUMBA_CACHE_DIR": cache, "MPLBACKEND": "Agg"}
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], env=env, check=True, cwd=ROOT, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main():
    code = readme_block()
    with tempfile.TemporaryDirectory(prefix="ssi_numba_cold_") as cache:
        cold = timed_process(code, cache)
        warm = timed_process(code, cache)
    print(f"first_run_cold_s: {cold:.2f}")
    print(f"readme_scene_s: {warm:.2f}")


if __name__ == "__main__":
    main()
