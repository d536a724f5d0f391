"""The solution of a model along a load path: ``Settings`` (the method, the stepping, the tolerances) and
``run`` (load-controlled, Newton-type iterations), ``run_arc_length`` (arc-length control), with L-BFGS
updates (``lbfgs``) and progress reporting (``progress``). The solver is the only place that commits state."""

from ..core.solution import COMPLETED, LIMIT_LOAD, STOPPED, Result
from .driver import METHODS, REFERENCES, STEPPINGS, NonConvergence, Settings, run, run_arc_length

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
