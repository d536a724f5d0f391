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

Failures are told apart: a non-finite matrix or right-hand side raises ``FloatingPointError`` saying so; a
singular matrix (exactly, or so nearly that the solution is not finite or the factorisation breaks down)
raises :class:`SingularMatrix`, which finds the rows of the matrix's null space on request. On a numerically
singular matrix SuperLU's factorisation can produce NaN internally and then call BLAS with an inconsistent
leading dimension; BLAS refuses and prints "On entry to DTRSV (or DGEMV) parameter number N had an illegal
value" from C (to file descriptor 1 with scipy's OpenBLAS, 2 with reference BLAS). SuperLU calls therefore
run with descriptors 1 and 2 redirected to scratch files (:func:`_trap_c_output`): that message becomes a
:class:`SingularMatrix`; any other text written there is passed on unchanged.
"""

import ctypes
import os
import sys
import tempfile
import weakref

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

BACKENDS = ("auto", "superlu", "pardiso")
# below this size SuperLU factorises in well under 0.3 s and has no per-call setup cost (PARDISO: ~50 ms)
AUTO_PARDISO_MIN_DOFS = 50_000


class SingularMatrix(FloatingPointError):
    """The matrix is singular (or numerically so). ``rows``: matrix rows that carry its null space (computed
    on first access by one shifted factorisation, so a caller that only falls back pays nothing)."""

    def __init__(self, message, matrix):
        super().__init__(message)
        self._matrix = matrix
        self._rows = None

    @property
    def rows(self) -> np.ndarray:
        if self._rows is None:
            self._rows = null_space_rows(self._matrix)
        return self._rows


def null_space_rows(matrix, threshold=0.1) -> np.ndarray:
    """Rows where a near-null vector of ``matrix`` is large: solve (A + delta I) x = b for a fixed random b
    with delta = 1e-8 max|diag A|; the null-space part of x is amplified by 1/delta, so the rows with
    |x| > ``threshold`` max|x| are the unsupported DOFs (all of them for a rigid-body mode)."""
    a = sp.csc_matrix(matrix, dtype=np.float64)
    n = a.shape[0]
    scale = float(np.max(np.abs(a.diagonal()))) if n else 0.0
    delta = 1e-8 * (scale if scale > 0.0 else 1.0)
    b = np.random.default_rng(0).standard_normal(n)
    try:
        lu, _ = _trap_c_output(spla.splu, a + delta * sp.eye(n, format="csc"), permc_spec="MMD_AT_PLUS_A")
        x = lu.solve(b)
    except RuntimeError:
        return np.flatnonzero(np.abs(a).sum(axis=0).A1 == 0.0)  # only empty columns can be named
    x = np.abs(np.nan_to_num(x, nan=np.inf))
    return np.flatnonzero(x >= threshold * x.max()) if x.max() > 0 else np.arange(0)


def _c_flush():
    """fflush(NULL): C's stdout is block-buffered when it is not a terminal, so BLAS's printf text would
    otherwise surface at some later write, outside the call that caused it."""
    if _LIBC:
        _LIBC[0].fflush(None)


try:
    _LIBC = [ctypes.CDLL(None)]
except OSError:  # no C library handle (not POSIX): text may then surface late, it is still not lost
    _LIBC = []

_SCRATCH: dict[int, object] = {}  # descriptor -> scratch file it is redirected to, created on first use


def _trap_c_output(fn, *args, **kw):
    """Call ``fn`` with file descriptors 1 and 2 redirected to scratch files; return (result, text written).

    BLAS reports argument errors from C (OpenBLAS's xerbla prints to standard output, reference BLAS to
    standard error), below Python's ``sys.stdout``/``sys.stderr``. A refusal ("illegal value") is returned to
    the caller, which raises; any other text is written on to the descriptor it was meant for. If ``fn``
    raises, the text is collected all the same (and dropped if it is BLAS's refusal) and the error goes on."""
    sys.stdout.flush()
    sys.stderr.flush()
    _c_flush()
    saved = {}
    for fd in (1, 2):
        if fd not in _SCRATCH:
            _SCRATCH[fd] = tempfile.TemporaryFile()  # noqa: SIM115 -- kept open for the process's life
        saved[fd] = os.dup(fd)
        os.dup2(_SCRATCH[fd].fileno(), fd)
    try:
        out = fn(*args, **kw)
    finally:
        _c_flush()
        for fd, copy in saved.items():
            os.dup2(copy, fd)
            os.close(copy)
        text = _drain_scratch()
    return out, text


def _drain_scratch() -> str:
    """Empty the scratch files: BLAS refusals are returned, other text goes on to its descriptor."""
    texts = []
    for fd in (1, 2):
        scratch = _SCRATCH[fd]
        if os.fstat(scratch.fileno()).st_size == 0:
            continue
        scratch.seek(0)
        text = scratch.read()
        scratch.seek(0)
        scratch.truncate()
        if b"illegal value" in text:
            texts.append(text.decode(errors="replace"))
        else:
            os.write(fd, text)
    return "".join(texts)


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
            self._solve = _superlu_factor(matrix, trap_solves=not spd)
        else:
            self._solve = _pardiso_factor(matrix, symmetric, spd and symmetric, self)

        self._matrix = matrix

    def solve(self, rhs):
        """Solve for one right-hand side (n,) or several (n, k)."""
        rhs = np.ascontiguousarray(rhs, dtype=np.float64)
        if not np.all(np.isfinite(rhs)):
            raise FloatingPointError(f"the right-hand side has {np.count_nonzero(~np.isfinite(rhs))} non-finite "
                                     "entries (non-finite loads, prescribed values or internal forces)")
        x = self._solve(rhs)
        if not np.all(np.isfinite(x)):
            raise SingularMatrix("the factorised matrix is singular: the solution is not finite for a finite "
                                 "right-hand side (check supports: rigid-body modes)", self._matrix)
        return x


def _superlu_factor(matrix, trap_solves=True):
    """SuperLU factor of ``matrix`` and its solve, with BLAS's refusal on a broken-down (numerically singular)
    factorisation turned into :class:`SingularMatrix` instead of a message on the terminal.

    ``trap_solves=False`` (K0, positive definite once the model's supports hold every rigid-body mode, which
    ``Model.check`` verifies): the factorisation is trapped, the solves are not -- modified Newton makes
    hundreds of K0 solves and the trap costs ~20-100 us each; a broken K0 would still end in a named
    non-finite-solution error."""
    a = sp.csc_matrix(matrix)
    try:
        lu, text = _trap_c_output(spla.splu, a, permc_spec="MMD_AT_PLUS_A")
    except RuntimeError as err:  # "Factor is exactly singular", or scipy's stop after BLAS refused a call
        raise SingularMatrix(f"the matrix is singular or the factorisation broke down on a numerically "
                             f"singular matrix ({err})", a) from err
    if "illegal value" in text:
        raise SingularMatrix(f"the factorisation broke down on a numerically singular matrix (BLAS: "
                             f"{text.strip().splitlines()[0].strip(' *')})", a)

    if not trap_solves:
        return lu.solve

    def solve(b):
        x, text = _trap_c_output(lu.solve, b)
        if "illegal value" in text:
            raise SingularMatrix(f"the solve broke down on a numerically singular matrix (BLAS: "
                                 f"{text.strip().splitlines()[0].strip(' *')})", a)
        return x

    return solve


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
