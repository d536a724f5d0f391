"""Sparse direct factorisation kept and reused for many right-hand sides.

Modified Newton--Raphson (paper §8) factorises K0 once and back-substitutes every iteration, so the one
thing this module must do well is keep a factorisation. Backends:

* ``"superlu"`` -- scipy's SuperLU with the MMD_AT_PLUS_A ordering (3x faster than the default COLAMD on
  these meshes) and threshold partial pivoting that prefers the diagonal (``SUPERLU_PIVOT_THRESHOLD``);
  always available, the fallback. A matrix refactorised on one pattern (Newton's tangents) keeps the
  ordering of the pattern's first factorisation (:class:`_KeptOrdering`).
* ``"pardiso"`` -- MKL PARDISO through ``pypardiso`` (``pip install ssi[fast]``), SPD mode for K0; its solve
  phase is called on the kept factorisation directly, because ``pypardiso.spsolve``
  re-hashes the matrix on every call.

``backend="auto"`` takes PARDISO, when it is installed, for K0 (``spd``) of at least ``AUTO_PARDISO_MIN_DOFS``
rows and for other matrices of at least ``AUTO_PARDISO_MIN_DOFS_REFACTORISED`` rows, except a ``lagged``
tangent (the controlled path's, kept for ~10-40 solves), which takes SuperLU; else SuperLU.

Backends on the controlled path (issue 31), measured on chapter 11's scene at h = 0.125 m (6 063 free DOFs,
1.8e5 entries; SuperLU's fill 6.4e5), matrices taken from the run, same process, best of 7-30, on the shared
2-core machine (load ~2.3, so PARDISO's threads are measured as a user with other work sees them):

* unsymmetric consistent tangent, refactorised on its pattern: SuperLU (kept ordering) 19.1 ms + 0.82 ms per
  solve (two right-hand sides at once: 1.28 ms); PARDISO (mtype 11, analysis kept) 24.0 ms + 2.8 ms per solve.
  A lagged factor takes ~17 solves (two per iteration: the residual and f_ref), so SuperLU costs 33 ms per
  factor against PARDISO's 72 (ratio 0.46). Whole run (``ch11_h0125_controlled_s``, one process each, 10 load
  steps): tangents on PARDISO 34.0 s wall, 21.7 s of it in 3 477 solves (6.2 ms each); on SuperLU 11.2 s
  (1.2 ms per solve). Orderings of SuperLU on this tangent: MMD_AT_PLUS_A (kept) 6.4e5 fill, 19.5 ms;
  COLAMD 9.1e5 fill (1.42x), 36 ms (1.85x).
* symmetric tangent (associated or Davis-mode soil; measured on the symmetrised chapter-11 tangent, a proxy):
  PARDISO's symmetric-indefinite mode (mtype -2) refactorised in 8.5 ms (+ 2.2 ms per solve) but returned a
  relative residual |A x - b| / |b| of 1.2e3 without an error (perturbed pivots on a nearly singular
  softening tangent), SuperLU 50 ms with 2e-9: a lagged symmetric tangent stays on SuperLU under "auto".
  No symmetric (LDL^T / Cholesky) factorisation of a tangent is available otherwise: scipy has none, and
  scikit-sparse (CHOLMOD) has no wheel for this platform here (``pip install --only-binary :all:
  scikit-sparse``: no matching distribution), so it was not measured.
* K0 (SPD, factorised once per run, then many solves): SuperLU MMD_AT_PLUS_A 22-31 ms + 0.73-0.88 ms per
  solve (COLAMD 35 ms and 1.44x fill, MMD_ATA 80 ms); PARDISO SPD mode 8-52 ms (its threads under load) +
  0.71-0.73 ms per solve: the rule above (PARDISO from ``AUTO_PARDISO_MIN_DOFS``) stands.

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
import functools
import os
import sys
import tempfile
import weakref
from pathlib import Path

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numba import njit

BACKENDS = ("auto", "superlu", "pardiso")
# "auto" picks PARDISO (when installed) by the measured cost of the use, set-up included (MKL looked up once
# per process, the symbolic analysis of a pattern kept across refactorisations). Same process, best of 3 / 10,
# loaded 2-core machine (issue 16), factorisation + one back-substitution:
#   K0 (spd, then many solves):   5.8e3 DOFs SuperLU 105 ms + 1.01 ms/solve, PARDISO 145 ms + 0.30 ms/solve;
#                                 2.0e4 DOFs SuperLU 453 ms + 13.4 ms/solve, PARDISO 408 ms + 2.45 ms/solve
#   K_T (refactorised each iteration, one solve): 3.1e3 DOFs SuperLU 67 + 0.3 ms, PARDISO 12 + 12 ms;
#                                 5.8e3 DOFs 80 + 0.7 ms against 24 + 17 ms; 2.0e4 DOFs 455 + 15 against 177 +
#                                 51
AUTO_PARDISO_MIN_DOFS = 5_000  # K0: from here the faster back-substitutions repay PARDISO's slower set-up
AUTO_PARDISO_MIN_DOFS_REFACTORISED = 3_000  # other matrices: analysis kept, numeric phase only
# SuperLU keeps a diagonal pivot unless it is below this fraction of the largest entry of its column
# (threshold partial pivoting, UMFPACK's default 0.1) and takes the symmetric ordering for rows as well: the
# matrices here have a symmetric pattern and a strong diagonal, and strict partial pivoting (scipy's default
# 1.0) swapped rows of chapter 11's non-associated tangents (6 063 DOFs) for 1.5-1.6x the fill of the
# symmetric ordering and 1.5-2.7x the factorisation time, for the same residual |A x - b| / |b| ~ 5e-12.
# The tangent solve is checked against the matrix all the same (solver.TANGENT_SOLVE_TOL).
SUPERLU_PIVOT_THRESHOLD = 0.1


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

# descriptor -> the raw descriptor of the (unlinked) scratch file it is redirected to, created on first use
# and kept for the process's life; raw descriptors, not file objects: a file object left open until exit is
# reported as a ResourceWarning ("unclosed file") at interpreter shutdown
_SCRATCH: dict[int, int] = {}


def _scratch_descriptor() -> int:
    fd, name = tempfile.mkstemp(prefix="ssi-blas-", suffix=".txt")
    os.unlink(name)  # anonymous: gone with the process
    return fd


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
            _SCRATCH[fd] = _scratch_descriptor()
        saved[fd] = os.dup(fd)
        os.dup2(_SCRATCH[fd], fd)
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
        size = os.fstat(scratch).st_size
        if size == 0:
            continue
        os.lseek(scratch, 0, os.SEEK_SET)
        text = b""
        while len(text) < size and (chunk := os.read(scratch, size - len(text))):
            text += chunk
        os.lseek(scratch, 0, os.SEEK_SET)
        os.ftruncate(scratch, 0)
        if b"illegal value" in text:
            texts.append(text.decode(errors="replace"))
        else:
            os.write(fd, text)
    return "".join(texts)


@functools.cache
def pardiso_available() -> bool:
    """MKL's PARDISO found (the ``fast`` extra installs it with pypardiso; looked up once per process)."""
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
    lagged : bool, a tangent kept for many solves (the controlled path's lagged factorisation, ~10-40 solves
        each): ``"auto"`` takes SuperLU for it (see ``BACKENDS``), and only its first solve is trapped
    """

    def __init__(self, matrix, symmetric=True, backend="auto", spd=False, lagged=False):
        if backend not in BACKENDS:
            raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
        if backend == "auto":
            limit = AUTO_PARDISO_MIN_DOFS if spd else AUTO_PARDISO_MIN_DOFS_REFACTORISED
            pardiso = matrix.shape[0] >= limit and pardiso_available() and (spd or not lagged)
            backend = "pardiso" if pardiso else "superlu"
        if backend == "pardiso" and not pardiso_available():
            raise ValueError("backend 'pardiso' needs pypardiso: pip install 'ssi[fast]'")
        self.backend = backend
        self.n = matrix.shape[0]
        if not np.all(np.isfinite(matrix.data)):
            raise FloatingPointError("the matrix has non-finite entries (a tangent of a material law failed)")
        if self.n == 0:
            self._solve = lambda b: np.zeros(0)
        elif backend == "superlu":
            trap = "first" if lagged else not spd
            self._solve = _superlu_factor(matrix, trap_solves=trap, keep_ordering=not spd)
        else:
            self._solve = _pardiso_factor(matrix, symmetric, spd and symmetric, self)

        self._matrix = matrix

    def solve(self, rhs):
        """Solve for one right-hand side (n,) or several (n, k)."""
        rhs = np.ascontiguousarray(rhs, dtype=np.float64)
        if not np.all(np.isfinite(rhs)):
            raise FloatingPointError(
                f"the right-hand side has {np.count_nonzero(~np.isfinite(rhs))} non-finite "
                "entries (non-finite loads, prescribed values or internal forces)"
            )
        x = self._solve(rhs)
        if not np.all(np.isfinite(x)):
            raise SingularMatrix(
                "the factorised matrix is singular: the solution is not finite for a finite "
                "right-hand side (check supports: rigid-body modes)",
                self._matrix,
            )
        return x


def _superlu_factor(matrix, trap_solves=True, keep_ordering=False):
    """SuperLU factor of ``matrix`` and its solve, with BLAS's refusal on a broken-down (numerically singular)
    factorisation turned into :class:`SingularMatrix` instead of a message on the terminal.

    ``trap_solves=False`` (K0, positive definite once the model's supports hold every rigid-body mode, which
    ``Model.check`` verifies): the factorisation is trapped, the solves are not -- modified Newton makes
    hundreds of K0 solves and the trap costs ~20-100 us each; a broken K0 would still end in a named
    non-finite-solution error. ``trap_solves="first"`` (a lagged tangent, whose caller solves once right after
    factorising): BLAS's refusal comes from a factor that broke down, so it shows in the first solve if at
    all; the later ones are not trapped.

    ``keep_ordering=True`` (tangents, refactorised on one pattern every Newton iteration): the ordering of
    the pattern's first factorisation is kept and later ones factorise the permuted matrix (see
    :class:`_KeptOrdering`)."""
    kept = _kept_ordering(matrix) if keep_ordering else None
    if kept is None:
        a, order, options = sp.csc_matrix(matrix), "MMD_AT_PLUS_A", {}
    else:
        a, order = kept.permuted(matrix), "NATURAL"
        options = {"relax": 1, "panel_size": 1} if a.shape[0] <= SMALL_SUPERNODES_MAX_DOFS else {}
    try:
        lu, text = _trap_c_output(
            spla.splu,
            a,
            permc_spec=order,
            diag_pivot_thresh=SUPERLU_PIVOT_THRESHOLD,
            options={"SymmetricMode": True},
            **options,
        )
    except RuntimeError as err:  # "Factor is exactly singular", or scipy's stop after BLAS refused a call
        raise SingularMatrix(
            f"the matrix is singular or the factorisation broke down on a numerically "
            f"singular matrix ({err})",
            matrix,
        ) from err
    if "illegal value" in text:
        raise SingularMatrix(
            f"the factorisation broke down on a numerically singular matrix (BLAS: "
            f"{text.strip().splitlines()[0].strip(' *')})",
            matrix,
        )
    if keep_ordering and kept is None:
        _keep_ordering(matrix, lu.perm_c)
    factor_solve = lu.solve if kept is None else kept.solve_with(lu.solve)

    if not trap_solves:
        return factor_solve
    trapping = [True]

    def solve(b):
        if not trapping[0]:
            return factor_solve(b)
        x, text = _trap_c_output(factor_solve, b)
        if "illegal value" in text:
            raise SingularMatrix(
                f"the solve broke down on a numerically singular matrix (BLAS: "
                f"{text.strip().splitlines()[0].strip(' *')})",
                matrix,
            )
        trapping[0] = trap_solves != "first"  # a first solve that went through: the factor is sound
        return x

    return solve


# A tangent is refactorised on the same pattern at every Newton iteration. SuperLU's ordering
# (MMD_AT_PLUS_A and the elimination tree's postorder) depends on the pattern only, so it is computed once:
# later factorisations take the symmetrically permuted matrix in natural order, and below
# SMALL_SUPERNODES_MAX_DOFS rows with SuperLU's smallest supernodes (relax = panel_size = 1). Measured on
# tangents of zoo scene 66 (1 719 DOFs) and chapter 11 (6 063 DOFs), best of 9, same fill (+-4 entries):
# 3.78 -> 2.66 ms and 15.2 -> 12.4 ms per factorisation. On an elastic block, permuted in natural order,
# relax = panel_size = 1 was faster at 2.0e4 rows (104 -> 89 ms) and slower at 1e5 (873 -> 959 ms; 811
# with SuperLU's default supernodes).
SMALL_SUPERNODES_MAX_DOFS = 25_000


class _KeptOrdering:
    """The column ordering ``q`` of a pattern's first factorisation (the permuted matrix is A[q][:, q]) and
    where each of its CSC values comes from in the pattern's CSR values (built on the second use)."""

    def __init__(self, perm_c):
        self.q = np.argsort(perm_c)
        self.source = None

    def permuted(self, matrix):
        """A[q][:, q] in CSC, gathered from ``matrix``'s CSR values by a map built once."""
        if self.source is None:
            n, nnz = matrix.shape[0], matrix.indptr[-1]
            # each value's position, carried through scipy's permutation (exact in float64 up to 2^53)
            where = sp.csr_matrix((np.arange(1.0, nnz + 1.0), matrix.indices, matrix.indptr), shape=(n, n))
            moved = where[self.q][:, self.q].tocsc()
            index_type = np.int32 if nnz < 2**31 else np.int64  # the map of a 1e6-DOF tangent: 72 MB
            self.source = (moved.data - 1.0).astype(index_type)
            self.indices, self.indptr = moved.indices, moved.indptr
            self.canonical = moved.has_canonical_format  # sorted, no duplicates: true of every later copy
        values = np.empty(self.source.shape[0])
        _gather_values(matrix.data, self.source, values)
        permuted = sp.csc_matrix((values, self.indices, self.indptr), shape=matrix.shape)
        # splu checks the format again otherwise (O(nnz) in Python-level numpy: ~50 us at 1e5 entries)
        permuted.has_canonical_format = self.canonical
        return permuted

    def solve_with(self, permuted_solve):
        """The solve of A x = b from the permuted factor's: x[q] = solve(b[q])."""
        q = self.q

        def solve(b):
            x = np.empty_like(b)
            x[q] = permuted_solve(np.ascontiguousarray(b[q]))
            return x

        return solve


@njit(cache=True)
def _gather_values(data, source, out):
    """out[k] = data[source[k]]: numpy's fancy indexing first copies an int32 map to int64 (measured 250 us
    against 74 us here for 1.2e5 entries in random order; a 1.7 k-DOF tangent factorises in ~2 ms)."""
    for k in range(source.shape[0]):
        out[k] = data[source[k]]


_ORDERINGS: dict = {}  # pattern key (see _pattern_key) -> _KeptOrdering, dropped with the pattern's indices


def _kept_ordering(matrix):
    if not (sp.issparse(matrix) and matrix.format == "csr"):
        return None
    return _ORDERINGS.get(_pattern_key(matrix))


def _keep_ordering(matrix, perm_c):
    if not (sp.issparse(matrix) and matrix.format == "csr"):
        return
    key = _pattern_key(matrix)
    _ORDERINGS[key] = _KeptOrdering(perm_c)
    weakref.finalize(matrix.indices, _ORDERINGS.pop, key, None)


# ---- PARDISO -------------------------------------------------------------------------------------------
# pypardiso's solver object searches the environment for MKL when it is created and converts the index arrays
# to 1-based int32 on every call (factorisation and each solve). Here MKL is looked up once per process, the
# converted indices live with the handle, and a handle whose matrix pattern is seen again (full Newton
# refactorises the same K_T pattern every iteration) skips the symbolic analysis: phase 22 (numeric
# factorisation) instead of 12 (analysis + factorisation).
_MAX_IDLE_HANDLES = 4  # idle analysed handles kept per process (each holds one pattern's analysis)


def _mkl_runtime_path():
    """MKL's runtime library: ``PYPARDISO_MKL_RT`` if set, else the one the ``mkl`` wheel (pypardiso's
    dependency) puts in this environment's library folder, else None. pypardiso itself searches the whole
    environment tree for it, once on import and again for every solver it creates (0.37 s each, measured on
    this project's venv): a user's process paid 0.74 s before its first factorisation."""
    if os.environ.get("PYPARDISO_MKL_RT"):
        return os.environ["PYPARDISO_MKL_RT"]
    for folder in (Path(sys.prefix) / "lib", Path(sys.prefix) / "Library" / "bin"):
        candidates = (
            sorted(folder.glob("*mkl_rt*"), key=lambda path: len(path.name)) if folder.is_dir() else []
        )
        if candidates:
            return str(candidates[0])
    return None


_PARDISO_ARGTYPES = (
    [ctypes.POINTER(ctypes.c_int64)]  # pt
    + [ctypes.POINTER(ctypes.c_int32)] * 5  # maxfct, mnum, mtype, phase, n
    + [ctypes.c_void_p]  # a
    + [ctypes.POINTER(ctypes.c_int32)] * 5  # ia, ja, perm, nrhs, iparm
    + [ctypes.POINTER(ctypes.c_int32), ctypes.c_void_p, ctypes.c_void_p, ctypes.POINTER(ctypes.c_int32)]
)  # msglvl, b, x, error -- the signature pypardiso declares


@functools.cache
def _mkl_pardiso():
    """The ``pardiso`` entry point of MKL with its ctypes signature, found once per process: loaded from
    the library :func:`_mkl_runtime_path` names, or through pypardiso's own search when that fails."""
    # MKL's OpenMP threads spin while they wait for work by default: with any other busy process on the
    # machine (a second solve, a test worker, a sweep's workers) a back-substitution of K0 at 6 k DOFs took
    # 9.3 ms instead of 1.0 ms, and chapter 11's h = 0.125 m scene spent half its time there (measured, load
    # 4 on 2 cores). Passive waiting costs nothing measurable on a quiet machine; a user's own setting wins.
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    # MKL picks its code path and parallel reduction order per run unless told otherwise: chapter 11's
    # h = 0.125 m scene (6 413 DOFs, PARDISO) gave a bitwise different answer in each of three processes,
    # and a plastic path amplifies round-off (a graded copy ended "completed" in one process and "limit load
    # reached" in another). MKL_CBWR=AUTO (conditional numerical reproducibility on this processor) made
    # repeated runs identical at no measured cost (21.2 s against 22.5 s unset); a user's setting wins.
    os.environ.setdefault("MKL_CBWR", "AUTO")
    path = _mkl_runtime_path()
    if path is not None:
        try:
            entry = ctypes.CDLL(path).pardiso
        except (OSError, AttributeError):
            entry = None
        if entry is not None:
            entry.argtypes = _PARDISO_ARGTYPES
            entry.restype = None
            return entry
    import pypardiso

    return pypardiso.PyPardisoSolver()._mkl_pardiso


@njit(cache=True)
def _kept_rows(indptr, indices, upper_only, start, ia):
    """Per row of a CSR matrix with sorted indices: ``start`` (n,) the first entry PARDISO takes (the
    diagonal or the first entry right of it when ``upper_only``, the row's first entry otherwise) and ``ia``
    (n + 1,) the 1-based row pointers of the kept entries."""
    n = indptr.size - 1
    ia[0] = 1
    for row in range(n):
        k = indptr[row]
        if upper_only:
            while k < indptr[row + 1] and indices[k] < row:
                k += 1
        start[row] = k
        ia[row + 1] = ia[row] + (indptr[row + 1] - k)


@njit(cache=True)
def _gather_kept(indptr, start, ia, source, out):
    """``out[ia[r] - 1 + j] = source[start[r] + j]`` over the kept entries of every row: the kept column
    indices (``source = indices``, then + 1) or values (``source = data``)."""
    for row in range(indptr.size - 1):
        base = ia[row] - 1 - start[row]
        for k in range(start[row], indptr[row + 1]):
            out[base + k] = source[k]


class _PardisoHandle:
    """One PARDISO instance (its ``pt`` handle) bound to one sparsity pattern and matrix type.

    ``start`` (n,) holds each row's first entry PARDISO takes (upper triangle for symmetric types, all for
    unsymmetric ones; the indices are sorted, so the kept entries of a row are one contiguous run), so a
    refactorisation gathers the values only. Two passes over the pattern, no temporaries of its size (the
    numpy version built row numbers, masks and positions of every entry: 1.9 s at 1e6 DOFs).
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
        self.indptr = matrix.indptr
        self.start = np.empty(self.n, np.int64)
        self.ia = np.empty(self.n + 1, np.int32)
        _kept_rows(matrix.indptr, matrix.indices, mtype != 11, self.start, self.ia)
        self.ja = np.empty(self.ia[-1] - 1, np.int32)
        _gather_kept(matrix.indptr, self.start, self.ia, matrix.indices, self.ja)
        self.ja += 1
        self.pattern_key = _pattern_key(matrix)
        self.analysed = False
        self.a = np.empty(self.ja.size)
        self._dummy = np.zeros(1)

    def _call(self, phase, b, x, nrhs=1):
        err = ctypes.c_int32(0)
        i32 = ctypes.POINTER(ctypes.c_int32)
        f64 = ctypes.POINTER(ctypes.c_double)
        _mkl_pardiso()(
            self.pt.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)),
            ctypes.byref(ctypes.c_int32(1)),
            ctypes.byref(ctypes.c_int32(1)),
            ctypes.byref(ctypes.c_int32(self.mtype)),
            ctypes.byref(ctypes.c_int32(phase)),
            ctypes.byref(ctypes.c_int32(self.n)),
            self.a.ctypes.data_as(f64),
            self.ia.ctypes.data_as(i32),
            self.ja.ctypes.data_as(i32),
            None,
            ctypes.byref(ctypes.c_int32(nrhs)),
            self.iparm.ctypes.data_as(i32),
            ctypes.byref(ctypes.c_int32(0)),
            b.ctypes.data_as(f64),
            x.ctypes.data_as(f64),
            ctypes.byref(err),
        )
        if err.value != 0:
            raise RuntimeError(f"PARDISO failed with error {err.value} in phase {phase}")

    def factorize(self, data):
        """Numeric factorisation of the matrix with full CSR values ``data``; the symbolic analysis of the
        pattern is done on the first call only."""
        _gather_kept(self.indptr, self.start, self.ia, data, self.a)
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
