"""Progress of an analysis and what the solver says: a tqdm bar, a compile notice and ``logging``.

The solver loop calls (``ssi.solver.run``)::

    with solver_progress(settings.progress, total=float(targets[-1])) as bar:
        ...
        bar.update(step, lam, iterations, residual)      # after every converged step

The bar shows step, load factor lambda, iterations and the last residual; it is drawn only when ``enabled``
is True, or, with ``enabled=None`` (automatic), when stderr is a terminal and no test is running
(``PYTEST_CURRENT_TEST`` unset) -- so tests, notebooks run by nbmake and piped output stay quiet.
Everything else the solver reports goes through ``logging`` (logger ``"ssi.solver"``; the bar's steps are
also logged at DEBUG level): ``logging.basicConfig(level=logging.INFO)`` shows it.

:func:`announce_compilation` prints one line ("compiling kernels once, ~N s") when numba's on-disk cache
for this version of the sources is still empty, i.e. the first run after an install or an edit.
"""

import contextlib
import logging
import os
import shutil
import sys
from pathlib import Path

log = logging.getLogger("ssi.solver")

COMPILE_ESTIMATE_S = 20  # the README scene, 2-core machine: 15-17 s cold (2026-12-08; first_run_cold_s)


def progress_enabled(enabled: bool | None = None, stream=None) -> bool:
    """Resolve ``enabled``: True/False as given; None: stderr is a terminal and no pytest test runs."""
    if enabled is not None:
        return bool(enabled)
    stream = stream or sys.stderr
    return bool(getattr(stream, "isatty", lambda: False)()) and "PYTEST_CURRENT_TEST" not in os.environ


class SolverProgress:
    """What :func:`solver_progress` yields: ``update`` after each converged step, ``note`` for a step cut."""

    def __init__(self, bar, total):
        self.bar = bar
        self.total = float(total)
        self.steps = 0

    def update(self, step: int, lam: float, iterations: int, residual: float) -> None:
        """Step ``step`` converged at load factor ``lam`` after ``iterations`` with relative residual
        ``residual``."""
        self.steps = int(step)
        log.debug("step %4d  lambda=%.6g  iterations=%3d  residual=%.2e", step, lam, iterations, residual)
        if self.bar is not None:
            self.bar.n = min(float(lam), self.total) if self.total > 0 else float(lam)
            self.bar.set_postfix_str(f"step {step}, it {iterations}, r {residual:.1e}", refresh=False)
            self.bar.refresh()

    def note(self, message: str) -> None:
        """A message beside the bar (e.g. a step cut); logged at INFO."""
        log.info(message)
        if self.bar is not None:
            self.bar.set_description_str(message[:40])


@contextlib.contextmanager
def solver_progress(enabled: bool | None = None, total: float = 1.0, stream=None):
    """Context manager yielding a :class:`SolverProgress`; a tqdm bar over the load factor 0..``total``
    when :func:`progress_enabled` says so, else a silent one (updates only logged)."""
    bar = None
    if progress_enabled(enabled, stream):
        from tqdm.auto import tqdm

        columns = shutil.get_terminal_size((100, 24)).columns  # a pseudo-terminal may report 0 columns
        bar = tqdm(
            total=float(total),
            unit="λ",
            file=stream or sys.stderr,
            leave=True,
            ncols=min(columns, 120),
            bar_format="{l_bar}{bar}| λ={n:.3f}/{total:.3g} [{elapsed}] {postfix}",
        )
    try:
        yield SolverProgress(bar, total)
    finally:
        if bar is not None:
            bar.close()


def numba_cache_is_empty(cache_dir=None) -> bool:
    """True when numba's cache folder for the current sources holds no compiled kernel index (``*.nbi``)."""
    folder = Path(cache_dir or os.environ.get("NUMBA_CACHE_DIR", ""))
    if os.environ.get("NUMBA_DISABLE_JIT") == "1" or not str(folder):
        return False
    return not (folder.is_dir() and any(folder.rglob("*.nbi")))


_announced = False


def announce_compilation(stream=None, estimate_s: float = COMPILE_ESTIMATE_S) -> bool:
    """Print "compiling kernels once, ~N s" (once per process) if the numba cache is empty; return whether
    it printed. Call before the first kernel runs (``ssi run`` does; the solver should, see module doc)."""
    global _announced
    if _announced or not numba_cache_is_empty():
        return False
    _announced = True
    print(
        f"ssi: compiling kernels once, ~{estimate_s:.0f} s (cached afterwards in "
        f"{os.environ.get('NUMBA_CACHE_DIR')})",
        file=stream or sys.stderr,
        flush=True,
    )
    log.info("numba cache empty: compiling kernels")
    return True
