"""Sparse direct factorisation kept and reused for many right-hand sides.

Modified Newton--Raphson (paper §8) factorises K0 once and back-substitutes every iteration, so the one
thing this module must do well is keep a factorisation. Backends:

* ``"superlu"`` -- scipy's SuperLU with the MMD_AT_PLUS_A ordering (3x faster than the default COLAMD on
  these meshes); always available, the fallback.
* ``"pardiso"`` -- MKL PARDISO through ``pypardiso`` (``pip install ssi[fast]``), SPD mode for K0; its solve
  phase is called on the kept factorisation directly, because ``pypardiso.spsolve``
  re-hashes the matrix on every call.

``backend="auto"`` takes PARDISO, when it is installed, for K0 (``spd``) of at least ``AUTO_PARDISO_MIN_DOFS``
rows and for other matrices of at least ``AUTO_PARDISO_MIN_DOFS_REFACTORISED`` rows, else SuperLU.
"""

import ctypes
import functools
import weakref

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

BACKENDS = ("auto", "superlu", "pardiso")
# "auto" picks PARDISO (when installed) by the measured cost of the use, set-up included (MKL looked up once per
# process, the symbolic analysis of a pattern kept across refactorisations). Same process, best of 3 / 10,
# loaded 2-core machine (issue 16), factorisation + one back-substitution:
#   K0 (spd, then many solves):   5.8e3 DOFs SuperLU 105 ms + 1.01 ms/solve, PARDISO 145 ms + 0.30 ms/solve;
#                                 2.0e4 DOFs SuperLU 453 ms + 13.4 ms/solve, PARDISO 408 ms + 2.45 ms/solve
#   K_T (refactorised each iteration, one solve): 3.1e3 DOFs SuperLU 67 + 0.3 ms, PARDISO 12 + 12 ms;
#                                 5.8e3 DOFs 80 + 0.7 ms against 24 + 17 ms; 2.0e4 DOFs 455 + 15 against 177 + 51
AUTO_PARDISO_MIN_DOFS = 5_000  # K0: from here the faster back-substitutions repay PARDISO's slower set-up
AUTO_PARDISO_MIN_DOFS_REFACTORISED = 3_000  # other matrices: analysis kept, numeric phase only


@functools.cache
def pardiso_available() -> bool:
    """pypardiso importable and MKL found (looked up once per process)."""
    try:
        _mkl_pardiso()
    except (ImportError, OSError):
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
            limit = AUTO_PARDISO_MIN_DOFS if spd else AUTO_PARDISO_MIN_DOFS_REFACTORISED
            backend = "pardiso" if matrix.shape[0] >= limit and pardiso_available() else "superlu"
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


# ---- PARDISO -------------------------------------------------------------------------------------------
# pypardiso's solver object searches the environment for MKL when it is created and converts the index arrays
# to 1-based int32 on every call (factorisation and each solve). Here MKL is looked up once per process, the
# converted indices live with the handle, and a handle whose matrix pattern is seen again (full Newton
# refactorises the same K_T pattern every iteration) skips the symbolic analysis: phase 22 (numeric
# factorisation) instead of 12 (analysis + factorisation).
_MAX_IDLE_HANDLES = 4  # idle analysed handles kept per process (each holds one pattern's analysis)


@functools.cache
def _mkl_pardiso():
    """The ``pardiso`` entry point of MKL with its ctypes signature, found once per process."""
    import pypardiso

    return pypardiso.PyPardisoSolver()._mkl_pardiso


class _PardisoHandle:
    """One PARDISO instance (its ``pt`` handle) bound to one sparsity pattern and matrix type.

    ``upper`` (nnz_kept,) are the positions in the full CSR ``data`` of the entries PARDISO takes (the upper
    triangle for symmetric types, all for unsymmetric ones), so a refactorisation gathers the values only.
    """

    def __init__(self, matrix, mtype, spd):
        self.mtype = mtype
        self.n = matrix.shape[0]
        self.pt = np.zeros(64, np.int64)
        self.iparm = np.zeros(64, np.int32)
        if spd:  # as pypardiso was called before: iparm 1 = 1 (values are the user's), 2 = 0 (min. degree)
            self.iparm[0] = 1
            self.iparm[1] = 0
        # otherwise iparm 1 = 0: MKL's defaults for every entry (what pypardiso passed)
        indptr = matrix.indptr
        indices = matrix.indices
        rows = np.repeat(np.arange(self.n, dtype=np.int64), np.diff(indptr))
        keep = indices >= rows if mtype != 11 else np.ones(indices.size, bool)
        self.upper = np.flatnonzero(keep)
        counts = np.bincount(rows[keep], minlength=self.n)
        self.ia = np.empty(self.n + 1, np.int32)
        self.ia[0] = 1
        np.cumsum(counts, out=self.ia[1:])
        self.ia[1:] += 1
        self.ja = (indices[keep] + 1).astype(np.int32)
        self.pattern_key = _pattern_key(matrix)
        self.analysed = False
        self.a = np.empty(self.ja.size)
        self._dummy = np.zeros(1)

    def _call(self, phase, b, x, nrhs=1):
        err = ctypes.c_int32(0)
        i32 = ctypes.POINTER(ctypes.c_int32)
        f64 = ctypes.POINTER(ctypes.c_double)
        _mkl_pardiso()(self.pt.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)),
                       ctypes.byref(ctypes.c_int32(1)), ctypes.byref(ctypes.c_int32(1)),
                       ctypes.byref(ctypes.c_int32(self.mtype)), ctypes.byref(ctypes.c_int32(phase)),
                       ctypes.byref(ctypes.c_int32(self.n)), self.a.ctypes.data_as(f64),
                       self.ia.ctypes.data_as(i32), self.ja.ctypes.data_as(i32), None,
                       ctypes.byref(ctypes.c_int32(nrhs)), self.iparm.ctypes.data_as(i32),
                       ctypes.byref(ctypes.c_int32(0)), b.ctypes.data_as(f64), x.ctypes.data_as(f64),
                       ctypes.byref(err))
        if err.value != 0:
            raise RuntimeError(f"PARDISO failed with error {err.value} in phase {phase}")

    def factorize(self, data):
        """Numeric factorisation of the matrix with full CSR values ``data``; the symbolic analysis of the
        pattern is done on the first call only."""
        np.take(data, self.upper, out=self.a)
        self._call(22 if self.analysed else 12, self._dummy, self._dummy)
        self.analysed = True

    def solve(self, b):
        b = np.asfortranarray(b)
        x = np.empty_like(b)
        self._call(33, b, x, 1 if b.ndim == 1 else b.shape[1])
        return np.ascontiguousarray(x)

    def free(self):
        if self.analysed:
            self._call(-1, self._dummy, self._dummy)
            self.analysed = False


def _pattern_key(matrix):
    """Identity of a CSR pattern: the index arrays of ``SparsePattern.matrix`` are shared by every matrix
    assembled on one pattern, so their identity (with their sizes) names the pattern."""
    return (matrix.shape[0], matrix.indptr.size, matrix.indices.size, id(matrix.indptr), id(matrix.indices))


_IDLE_HANDLES: list = []  # [(weakref to indices, handle)] analysed, not owned by a live Factorization


def _pardiso_handle(matrix, mtype, spd):
    """An idle handle already analysed for this pattern and type, or a new one."""
    key = _pattern_key(matrix)
    for i, (ref, handle) in enumerate(_IDLE_HANDLES):
        if ref() is matrix.indices and handle.pattern_key == key and handle.mtype == mtype:
            del _IDLE_HANDLES[i]
            return handle
    return _PardisoHandle(matrix, mtype, spd)


def _release_handle(handle, indices_ref):
    """Back to the idle list when its Factorization is dropped (the oldest beyond the limit is freed)."""
    if indices_ref() is None:
        handle.free()
        return
    _IDLE_HANDLES.append((indices_ref, handle))
    while len(_IDLE_HANDLES) > _MAX_IDLE_HANDLES:
        _IDLE_HANDLES.pop(0)[1].free()


def _pardiso_factor(matrix, symmetric, spd, owner):
    # K0 (spd): mtype 2 with minimum-degree ordering (iparm 2 = 0) measured 0.77 s factor / 0.08 s solve at
    # 1.2e5 DOFs against 1.2-1.6 s / 0.2-0.3 s with pypardiso's defaults (METIS) in mtype 2 or -2, same run.
    # Other symmetric matrices (softening tangents may be indefinite): mtype -2; unsymmetric: mtype 11.
    mtype = 2 if spd else (-2 if symmetric else 11)
    if not (sp.issparse(matrix) and matrix.format == "csr"):
        matrix = sp.csr_matrix(matrix)  # (scipy's constructor copies the index arrays: only when needed)
    if not matrix.has_sorted_indices:
        matrix = matrix.copy()
        matrix.sort_indices()
    if np.any(np.diff(matrix.indptr) == 0):
        raise FloatingPointError("the matrix has an empty row: check supports (rigid-body modes)")
    handle = _pardiso_handle(matrix, mtype, spd)
    handle.factorize(matrix.data)
    weakref.finalize(owner, _release_handle, handle, weakref.ref(matrix.indices))
    return handle.solve
