"""Sparse direct factorisation kept and reused for many right-hand sides.

Modified Newton--Raphson (paper §8) factorises K0 once and back-substitutes every iteration, so the one
thing this module must do well is keep a factorisation. Backends:

* ``"superlu"`` -- scipy's SuperLU with the MMD_AT_PLUS_A ordering (3x faster than the default COLAMD on
  these meshes); always available, the fallback.
* ``"pardiso"`` -- MKL PARDISO through ``pypardiso`` (``pip install ssi[fast]``), SPD mode for K0; its solve
  phase is called on the kept factorisation directly, because ``pypardiso.spsolve``
  re-hashes the matrix on every call.

``backend="auto"`` takes PARDISO for matrices of at least ``AUTO_PARDISO_MIN_DOFS`` rows when it is
installed, else SuperLU.
"""

import weakref

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

BACKENDS = ("auto", "superlu", "pardiso")
# below this size SuperLU factorises in well under 0.3 s and has no per-call setup cost (PARDISO: ~50 ms)
AUTO_PARDISO_MIN_DOFS = 50_000


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
    symmetric : bool, the matrix is symmetric
    backend : one of BACKENDS
    spd : bool, the matrix is symmetric positive definite (K0 of a supported scene): PARDISO's fastest mode
    """

    def __init__(self, matrix, symmetric=True, backend="auto", spd=False):
        if backend not in BACKENDS:
            raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
        if backend == "auto":
            big = matrix.shape[0] >= AUTO_PARDISO_MIN_DOFS
            backend = "pardiso" if big and pardiso_available() else "superlu"
        if backend == "pardiso" and not pardiso_available():
            raise ValueError("backend 'pardiso' needs pypardiso: pip install 'ssi[fast]'")
        self.backend = backend
        self.n = matrix.shape[0]
        if not np.all(np.isfinite(matrix.data)):
            raise FloatingPointError("the matrix has non-finite entries (a tangent of a material law failed)")
        if self.n == 0:
            self._solve = lambda b: np.zeros(0)
        elif backend == "superlu":
            lu = spla.splu(sp.csc_matrix(matrix), permc_spec="MMD_AT_PLUS_A")
            self._solve = lu.solve
        else:
            self._solve = _pardiso_factor(matrix, symmetric, spd and symmetric, self)

    def solve(self, rhs):
        """Solve for one right-hand side (n,) or several (n, k)."""
        x = self._solve(np.ascontiguousarray(rhs, dtype=np.float64))
        if not np.all(np.isfinite(x)):
            raise FloatingPointError("the factorised matrix is singular: check supports (rigid-body modes)")
        return x


_PARDISO_POOL: dict[int, list] = {}  # idle solver objects by mtype


def _pardiso_solver(mtype):
    """A PARDISO solver object from the pool: creating one costs ~2 s (pypardiso searches the file system
    for MKL), which would dominate full Newton's refactorisation every iteration."""
    import pypardiso

    idle = _PARDISO_POOL.setdefault(mtype, [])
    return idle.pop() if idle else pypardiso.PyPardisoSolver(mtype=mtype)


def _release(solver, mtype):
    solver.free_memory(everything=True)
    _PARDISO_POOL.setdefault(mtype, []).append(solver)


def _pardiso_factor(matrix, symmetric, spd, owner):
    # K0 (spd): mtype 2 with minimum-degree ordering (iparm 2 = 0) measured 0.77 s factor / 0.08 s solve at
    # 1.2e5 DOFs against 1.2-1.6 s / 0.2-0.3 s with pypardiso's defaults (METIS) in mtype 2 or -2, same run.
    # Other symmetric matrices (softening tangents may be indefinite): mtype -2; unsymmetric: mtype 11.
    mtype = 2 if spd else (-2 if symmetric else 11)
    solver = _pardiso_solver(mtype)
    if spd:
        solver.set_iparm(1, 1)  # the iparm values below are the user's
        solver.set_iparm(2, 0)  # minimum-degree fill-in ordering
    a = sp.triu(matrix, format="csr") if symmetric else sp.csr_matrix(matrix)
    a.sort_indices()
    solver.factorize(a)
    weakref.finalize(owner, _release, solver, mtype)  # back to the pool when the factorisation is dropped

    def solve(b):
        solver.set_phase(33)
        return solver._call_pardiso(a, np.asfortranarray(b))

    return solve
