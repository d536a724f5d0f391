"""Validated parameters of the isotropic linear-elastic soil law (``soil_laws.ELASTIC``).

The numba kernels never check their inputs; this wrapper is where bad numbers are caught, with a message that
names the parameter and its allowed range.
"""

import math

import numpy as np

__all__ = ["check_elastic", "elastic_params"]


def check_elastic(E, nu):
    """Raise ``ValueError`` unless E > 0 (finite) and -1 < nu < 0.5 (plane strain needs 1 - 2 nu > 0)."""
    E = float(E)
    nu = float(nu)
    if not (math.isfinite(E) and E > 0.0):
        raise ValueError(f"Young's modulus E must be positive and finite [Pa], got E={E}")
    if not (math.isfinite(nu) and -1.0 < nu < 0.5):
        raise ValueError(f"Poisson's ratio nu must lie in the open interval (-1, 0.5), got nu={nu}")
    return E, nu


def elastic_params(E, nu) -> np.ndarray:
    """Parameter vector ``[E, nu]`` of the elastic soil law, after checking E > 0 and -1 < nu < 0.5."""
    E, nu = check_elastic(E, nu)
    return np.array([E, nu], dtype=np.float64)
