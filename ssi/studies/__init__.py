"""Studies built on scenes: error estimates by systematic refinement (``estimate``) and parameter sweeps on a
dask cluster (``sweep``). They solve scenes; no scene calls them."""

from .estimate import estimate, solve_to_target, solve_with_error

__all__ = ["estimate", "solve_to_target", "solve_with_error"]
