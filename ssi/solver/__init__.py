"""The solution of a model along a load path: ``Settings`` (the method, the stepping, the tolerances) and
``run`` (by default the controlled path, :mod:`.path`; or load control, :mod:`.control`),
``run_arc_length`` (arc-length control). The solver is the only place that commits state.

* ``settings`` -- ``Settings`` and ``NonConvergence``;
* ``path`` -- controlled path following (``Settings(control="work")``, the default): a limit only where
  the path peaks; its pieces ``path_corrector`` (factorisation, line search), ``path_limit`` (the limit
  watch and checks), ``path_relax`` (relaxed steps; ``relax`` the damped dynamics) and ``policy``
  (``PathPolicy``, its tunables);
* ``control`` -- ``run``, and load control (``Settings(control="load")``): stepping and step cuts, no limit;
* ``increment`` -- one load-controlled increment: the iterations of each method, line search, tangent
  solve, convergence;
* ``mechanism`` -- the mechanism certificate of a controlled path's limit (its last increment's energy);
* ``davis`` -- Davis mode (``Settings(flow="davis")``); ``record`` -- the start of a path, its step record;
* ``arc_length`` -- ``run_arc_length``;
* ``diagnostics`` -- what a failed increment reports;
* ``lbfgs`` -- the L-BFGS two-loop kernels; ``progress`` -- the progress bar and the compile notice.
"""

from ..core.solution import COMPLETED, LIMIT_LOAD, STOPPED, Result
from .arc_length import run_arc_length
from .control import run
from .settings import METHODS, REFERENCES, STEPPINGS, NonConvergence, Settings

__all__ = [
    "COMPLETED",
    "LIMIT_LOAD",
    "METHODS",
    "REFERENCES",
    "STEPPINGS",
    "STOPPED",
    "NonConvergence",
    "Result",
    "Settings",
    "run",
    "run_arc_length",
]
