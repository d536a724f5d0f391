"""A second-order cone program in Clarabel's standard form and its solve.

    minimize q^T x   subject to   A x + s = b,   s in K = {0}^n_eq x R_+^n_ineq x SOC_3^n_soc

Rows are built as three blocks (equalities, inequalities, 3-row cone blocks) in COO triplets and scaled to
unit infinity norm before the solve (the pitfall of badly scaled equalities). The solver's status is stored
but never trusted: the bound modules certify their answer from the returned point alone.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field

import clarabel
import numpy as np
import scipy.sparse as sp

__all__ = ["ConicSolution", "Rows", "solve_conic"]

# Clarabel's iterative refinement of each KKT solve: on unless SSI_LIMIT_REFINE=0. Off, chapter 10's Prandtl
# footing to a 1 % gap (bench_limit.py) took 11.0 s of CPU instead of 15.4 s with the same iterations and
# bracket, and the 28 ordinary zoo brackets moved by at most 0.5 %, all certified; but chapter 17's N_gamma
# sand (cohesionless: its lower bound's certification needs the solver's accuracy at the apex) then needed
# 12 meshes and 15 538 triangles for its 3 % gap instead of 10 and 7 159 (474 s against 185 s, measured on
# the loaded machine, 2026-12-04): kept on.
REFINE = os.environ.get("SSI_LIMIT_REFINE", "1") == "1"
# ... but only where it is needed: issue 46 measured the two-strip site's programs (cohesive soils, 1 527
# triangles) without it at 1.10 s (lower bound) and 0.76 s (upper) of CPU instead of 1.78 and 1.23 s, the
# same iterations and optima to 1e-7 relative. The bounds ask for it where a yielding material is
# cohesionless (``needs_refinement``): there the lower bound's certification at the apex needs the accuracy.


@dataclass
class Rows:
    """Triplets of one block of rows: ``add(cols, vals, rhs)`` appends one row."""

    rows: list = field(default_factory=list)
    cols: list = field(default_factory=list)
    vals: list = field(default_factory=list)
    rhs: list = field(default_factory=list)

    def add(self, cols, vals, rhs: float = 0.0) -> int:
        r = len(self.rhs)
        self.rows.extend([r] * len(cols))
        self.cols.extend(cols)
        self.vals.extend(vals)
        self.rhs.append(float(rhs))
        return r

    def add_many(self, rows: np.ndarray, cols: np.ndarray, vals: np.ndarray, rhs: np.ndarray) -> None:
        """Append a block: ``rows`` index the new rows from 0 (vectorised assembly)."""
        r0 = len(self.rhs)
        self.rows.extend((np.asarray(rows) + r0).tolist())
        self.cols.extend(np.asarray(cols).tolist())
        self.vals.extend(np.asarray(vals, float).tolist())
        self.rhs.extend(np.asarray(rhs, float).tolist())

    def matrix(self, n: int) -> tuple[sp.csr_matrix, np.ndarray]:
        A = sp.csr_matrix((self.vals, (self.rows, self.cols)), shape=(len(self.rhs), n))
        A.sum_duplicates()
        return A, np.array(self.rhs, float)


@dataclass
class ConicSolution:
    x: np.ndarray
    status: str
    iterations: int
    time: float
    n_soc: int
    z: np.ndarray | None = None  # the dual point of the scaled rows (None: no solve)
    s: np.ndarray | None = None  # the slacks b - A x of the scaled rows


def needs_refinement(materials) -> bool:
    """Whether the programs of a site with these materials keep Clarabel's iterative refinement (REFINE
    comment): a yielding cohesionless material (c = 0, not rigid), and REFINE not switched off."""
    return REFINE and any(m.c == 0.0 and not m.rigid for m in materials)


def solve_conic(
    q: np.ndarray,
    eq: Rows,
    ineq: Rows,
    soc: Rows,
    n: int,
    tol: float = 1e-9,
    max_iter: int = 200,
    refine: bool | None = None,
) -> ConicSolution:
    """Solve the program (module docstring) with Clarabel; ``soc`` holds 3 rows per cone. ``refine``:
    Clarabel's iterative refinement of each KKT solve (None: the module's REFINE)."""
    Ae, be = eq.matrix(n)
    Ai, bi = ineq.matrix(n)
    As, bs = soc.matrix(n)
    n_soc = As.shape[0] // 3
    # equality and inequality rows: each scaled to unit infinity norm; a cone block by one factor (a cone is
    # invariant under a positive scaling of all its three rows, not of one row)
    de = 1.0 / np.maximum(abs(Ae).max(axis=1).toarray().ravel(), 1e-300)
    di = 1.0 / np.maximum(abs(Ai).max(axis=1).toarray().ravel(), 1e-300)
    blk = abs(As).max(axis=1).toarray().ravel().reshape(-1, 3).max(axis=1) if n_soc else np.zeros(0)
    ds = np.repeat(1.0 / np.maximum(blk, 1e-300), 3)
    A = sp.vstack([sp.diags(de) @ Ae, sp.diags(di) @ Ai, sp.diags(ds) @ As]).tocsc()
    b = np.concatenate([de * be, di * bi, ds * bs])
    cones = [clarabel.ZeroConeT(Ae.shape[0])]
    if Ai.shape[0]:
        cones.append(clarabel.NonnegativeConeT(Ai.shape[0]))
    cones.extend(clarabel.SecondOrderConeT(3) for _ in range(n_soc))
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    settings.tol_gap_abs = tol
    settings.tol_gap_rel = tol
    settings.tol_feas = tol
    settings.max_iter = max_iter
    # QDLDL, single-threaded: Clarabel 0.11's "auto" picks faer with every core, which on these KKT systems
    # was 2.4x slower for the lower bound (2 956 triangles: 13.3 s against 5.5 s, measured) and no faster
    # for the upper bound, and competes with the other test workers for the machine's cores
    settings.direct_solve_method = "qdldl"
    if not (REFINE if refine is None else refine):
        settings.iterative_refinement_enable = False
    P = sp.csc_matrix((n, n))
    t0 = time.perf_counter()
    solver = clarabel.DefaultSolver(P, np.asarray(q, float), A, b, cones, settings)
    sol = solver.solve()
    elapsed = time.perf_counter() - t0
    return ConicSolution(
        np.array(sol.x), str(sol.status), int(sol.iterations), elapsed, n_soc, np.array(sol.z),
        np.array(sol.s),
    )  # fmt: skip
