"""Sparse direct factorisation kept and reused for many right-hand sides.

Modified Newton--Raphson (paper §8) factorises K0 once and back-substitutes every iteration, so the one
thing this module must do well is keep a factorisation. Backends:

* ``"superlu"`` -- scipy's SuperLU with the MMD_AT_PLUS_A ordering (3x faster than the default COLAMD on
  these meshes); always available, the fallback.
* ``"pardiso"`` -- MKL PARDISO through ``pypardiso`` (``pip install ssi[fast]``), symmetric-indefinite mode
  for symmetric matrices; its solve phase is called on the kept factorisation directly, because ``pypardiso.spsolve``
  re-hashes the matrix on every call.

``backend="auto"`` takes PARDISO when it is installed, else SuperLU.
"""

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

BACKENDS = ("auto", "superlu", "pardiso")


def pardiso_available() -> bool:
    try:
        import pypardiso  # noqa: F401
    except ImportError:
        return False
    return True


class Factorization:
    """Factorise a square sparse matrix once; ``solve(b)`` reuses it.

    Parameters
    ----------
    matrix : scipy sparse (n, n)
    symmetric : bool, the matrix is symmetric (positive definite for PARDISO's SPD mode)
    backend : one of BACKENDS
    """

    def __init__(self, matrix, symmetric=True, backend="auto"):
        if backend not in BACKENDS:
            raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
        if backend == "auto":
            backend = "pardiso" if pardiso_available() else "superlu"
        if backend == "pardiso" and not pardiso_available():
            raise ValueError("backend 'pardiso' needs pypardiso: pip install 'ssi[fast]'")
        self.backend = backend
        self.n = matrix.shape[0]
        if self.n == 0:
            self._solve = lambda b: np.zeros(0)
        elif backend == "superlu":
            lu = spla.splu(sp.csc_matrix(matrix), permc_spec="MMD_AT_PLUS_A")
            self._solve = lu.solve
        else:
            self._solve = _pardiso_factor(matrix, symmetric)

    def solve(self, rhs):
        """Solve for one right-hand side (n,) or several (n, k)."""
        x = self._solve(np.ascontiguousarray(rhs, dtype=np.float64))
        if not np.all(np.isfinite(x)):
            raise FloatingPointError("the factorised matrix is singular: check supports (rigid-body modes)")
        return x


def _pardiso_factor(matrix, symmetric):
    import pypardiso

    # symmetric: mtype -2 (symmetric indefinite, Bunch-Kaufman) measured ~25% faster than the SPD mode 2 on
    # K0 here and also valid for the indefinite tangents of softening; unsymmetric: mtype 11
    solver = pypardiso.PyPardisoSolver(mtype=-2 if symmetric else 11)
    a = sp.triu(matrix, format="csr") if symmetric else sp.csr_matrix(matrix)
    a.sort_indices()
    solver.factorize(a)

    def solve(b):
        solver.set_phase(33)
        return solver._call_pardiso(a, np.asfortranarray(b))

    return solve
