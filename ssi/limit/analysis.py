"""Brackets of the collapse load factor: both bounds on one mesh, the gap split by element, adaptive nested
refinement, the Davis bracket for non-associated materials and a factor of safety by strength reduction.

The gap identity: with the lower-bound stress sig (in equilibrium with lambda_LB) and the upper-bound
velocity u (reference power 1) on the same triangles, virtual work gives

    lambda_UB - lambda_LB = sum_e [D_e(u) - int_e sig : eps(u) dA] + sum_(footing edges) int [D_i - t.d] ds

and every term is >= 0 because sig is admissible (D is the support function of the yield set). Each
element's term is its share of the gap: what adaptivity refines. The identity itself is a check of both
programs (``Bracket.identity_error``).
"""

from __future__ import annotations

import os
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np

from ..core.validate import check_int, check_real
from ._common import boundary_edges
from .geometry import Site
from .lower import LowerBound, lower_bound
from .mesh import TriMesh, bisect
from .upper import UpperBound, footing_velocity_at, upper_bound

# Both bounds of a bracket are solved side by side on two threads unless SSI_LIMIT_THREADS=1 (measured on
# chapter 10's Prandtl footing, 1 086 triangles: the lower bound's Clarabel solve 1.8 s let a Python thread
# tick 1 126 times, i.e. the GIL is released while it solves)
THREADS = 1 if os.environ.get("SSI_LIMIT_THREADS", "2") == "1" else 2

__all__ = [
    "AdaptiveResult",
    "Bracket",
    "adaptive",
    "bracket",
    "carry_stress",
    "carry_velocity",
    "gap_shares",
    "safety_factor",
]


@dataclass
class Bracket:
    """Both bounds of ``site`` on ``mesh``: ``lb`` <= lambda* <= ``ub`` (``lb`` NaN if not certified),
    ``gap`` = (ub - lb) / (ub + lb), ``shares`` (n_el,) each element's share of ub - lb, ``identity_error``
    |sum(shares) - (ub - lb)| / ub, and the two results."""

    mesh: TriMesh
    lower: LowerBound
    upper: UpperBound
    shares: np.ndarray
    label: str = ""

    @property
    def lb(self) -> float:
        return self.lower.lam

    @property
    def ub(self) -> float:
        return self.upper.lam

    @property
    def gap(self) -> float:
        return relative_gap(self.lb, self.ub)

    @property
    def identity_error(self) -> float:
        return abs(self.shares.sum() - (self.ub - self.lower.lam_projected)) / abs(self.ub)

    def contains(self, value: float) -> bool:
        return bool(self.lb <= value <= self.ub)


def gap_shares(site: Site, mesh: TriMesh, lower: LowerBound, upper: UpperBound) -> np.ndarray:
    """Each element's share of ub - lb (module docstring), (n_el,) in load-factor units."""
    sig = lower.stress  # (n_el, 3, 3)
    eps = upper.strain
    A = mesh.areas()
    # sig : eps is quadratic: the midpoint rule of the three sides is exact
    work = np.zeros(mesh.n_el)
    for i, j in ((0, 1), (1, 2), (2, 0)):
        s = 0.5 * (sig[:, i] + sig[:, j])
        e = 0.5 * (eps[:, i] + eps[:, j])
        work += (s * e).sum(axis=1) * A / 3.0
    share = upper.dissipation - work
    be = boundary_edges(mesh, mesh.xy)
    n_nodes = len(mesh.xy)
    vel = upper.velocity
    for j in range(len(be.p)):
        bnd = site.segments[be.seg[j]][2]
        if bnd.kind != "footing" or site.interface_of(bnd).kind == "rough":
            continue
        ends = np.array([mesh.xy[be.p[j]], 0.5 * (mesh.xy[be.p[j]] + mesh.xy[be.q[j]]), mesh.xy[be.q[j]]])
        Ua, Um, Ub = footing_velocity_at(site, upper, bnd.footing, ends)
        e = be.el[j]
        nx, nz = be.n[j]

        def trac(loc, e=e, nx=nx, nz=nz):
            sx, sz, tau = sig[e, loc]
            return np.array([sx * nx + tau * nz, tau * nx + sz * nz])

        ta, tb = trac(be.lp[j]), trac(be.lq[j])
        da, db = Ua - vel[be.p[j]], Ub - vel[be.q[j]]
        dm = Um - vel[n_nodes + be.edge[j]]
        share[e] -= be.length[j] / 6.0 * (ta @ da + 2.0 * (ta + tb) @ dm + tb @ db)
    # a beam's hinges: their dissipation - (M rotation + N extension), M and N the lower bound's at the hinge
    for f, b in upper.beam.items():
        m_lb = lower.beam[f]
        work_h = m_lb["M_right"][:-1] * b["hinge"][:, 0] + m_lb["M_left"][1:] * b["hinge"][:, 1]
        work_h += m_lb["N_right"][:-1] * b["extension"][:, 0] + m_lb["N_left"][1:] * b["extension"][:, 1]
        np.add.at(share, b["el"], -work_h)
    return share


def bracket(
    site: Site, mesh: TriMesh, label: str = "", previous: Bracket | None = None, threads: int | None = None
) -> Bracket:
    """Both bounds on one mesh and the gap shares. With ``previous``, a bracket on a mesh that ``mesh``
    refines (``mesh.parent`` set by :func:`ssi.limit.mesh.bisect`), its stress and velocity fields are
    carried to ``mesh`` (still admissible there) and each bound is the better of the solved and the carried
    field: nested refinement then never loses ground even when the solver stops short of the optimum.

    ``threads``: 2 solves the two bounds side by side (Clarabel releases the GIL while it solves, so on two
    cores the bracket takes the longer bound's time instead of the sum), 1 one after the other; None: the
    module's ``THREADS``. Either way the bounds are the same numbers (each program is solved alone)."""
    threads = THREADS if threads is None else check_int("threads", threads, lo=1, hi=2)
    if threads == 2:
        with ThreadPoolExecutor(max_workers=2) as pool:
            lo_f = pool.submit(lower_bound, site, mesh)
            up = upper_bound(site, mesh)
            lo = lo_f.result()
    else:
        lo = lower_bound(site, mesh)
        up = upper_bound(site, mesh)
    # a carried field is the previous mesh's own field, so its bound is the previous bound: it is evaluated
    # (a projection, or an assembly) only where the solved bound fell short of that
    if previous is not None and mesh.parent is not None and not (lo.certified and lo.lam >= previous.lb):
        lo_c = lower_bound(
            site,
            mesh,
            stress=(carry_stress(previous.mesh, mesh, previous.lower.stress), previous.lower.lam_projected),
        )
        if lo_c.certified and (not lo.certified or lo_c.lam > lo.lam):
            lo_c.time, lo_c.iterations, lo_c.status = lo.time, lo.iterations, f"carried ({lo.status})"
            lo_c.lam_solver = lo.lam_solver
            lo = lo_c
    if previous is not None and mesh.parent is not None and up.lam > previous.ub:
        v, fv = carry_velocity(previous.mesh, mesh, previous.upper.velocity), previous.upper.footing_velocity
        motion = (v, fv, previous.upper.footing_rotation, previous.upper.beam)
        up_c = upper_bound(site, mesh, velocity=motion)
        if up_c.lam < up.lam:
            up_c.time, up_c.iterations, up_c.status = up.time, up.iterations, f"carried ({up.status})"
            up_c.lam_solver = up.lam_solver
            up = up_c
    return Bracket(mesh, lo, up, gap_shares(site, mesh, lo, up), label)


def _barycentric(coarse: TriMesh, parent: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Barycentric coordinates (n, 3) of points ``pts`` (n, 2) in the coarse triangles ``parent`` (n,)."""
    p = coarse.xy[coarse.tri[parent]]
    a = p[:, 0]
    m = np.stack([p[:, 1] - a, p[:, 2] - a], axis=2)  # (n, 2, 2): columns b - a, c - a
    l12 = np.linalg.solve(m, (pts - a)[..., None])[..., 0]
    return np.column_stack([1.0 - l12.sum(axis=1), l12])


def carry_stress(coarse: TriMesh, fine: TriMesh, stress: np.ndarray) -> np.ndarray:
    """The coarse linear stress field (n_el_coarse, 3, 3) at the vertices of the nested ``fine`` mesh."""
    par = fine.parent
    out = np.empty((fine.n_el, 3, 3))
    for v in range(3):
        lam = _barycentric(coarse, par, fine.xy[fine.tri[:, v]])
        out[:, v] = np.einsum("ek,ekc->ec", lam, stress[par])
    return out


def carry_velocity(coarse: TriMesh, fine: TriMesh, velocity: np.ndarray) -> np.ndarray:
    """The coarse quadratic velocity field at the corner and midside nodes of the nested ``fine`` mesh
    (layout of :class:`ssi.limit.upper.UpperBound`)."""
    _, ce = coarse.edges()
    f_edges, fe = fine.edges()
    nn_c, nn_f = len(coarse.xy), len(fine.xy)
    ids = np.concatenate([coarse.tri, nn_c + ce], axis=1)[fine.parent]  # (n_el_fine, 6) coarse nodes
    out = np.zeros((nn_f + len(f_edges), 2))
    for k in range(6):
        node = fine.tri[:, k] if k < 3 else nn_f + fe[:, k - 3]
        pts = (
            fine.xy[fine.tri[:, k]]
            if k < 3
            else 0.5 * (fine.xy[fine.tri[:, (k - 2) % 3]] + fine.xy[fine.tri[:, (k - 1) % 3]])
        )
        L = _barycentric(coarse, fine.parent, pts)
        N = np.column_stack(
            [L[:, i] * (2 * L[:, i] - 1) for i in range(3)]
            + [4 * L[:, (i + 1) % 3] * L[:, (i + 2) % 3] for i in range(3)]
        )
        out[node] = np.einsum("en,enc->ec", N, velocity[ids])
    return out


@dataclass
class AdaptiveResult:
    """The adaptive sequence: ``history`` rows (n_el, lb, ub, gap, t_lb [s], t_ub [s], iterations lb, ub,
    cones lb, ub), the last ``final`` bracket, ``lb``/``ub`` the best certified bounds of the sequence,
    ``monotone``: the nested meshes gave a non-decreasing lb and non-increasing ub (to ``mono_tol``
    relative), ``converged``: gap reached, ``solver_setbacks``: steps where the solver's own optimum was
    worse than the previous mesh's (impossible in exact arithmetic on nested meshes: the solver stopped
    short), which the carried fields of :func:`bracket` make up for."""

    history: list = field(default_factory=list)
    final: Bracket | None = None
    lb: float = float("nan")
    ub: float = float("nan")
    monotone: bool = True
    converged: bool = False
    solver_setbacks: int = 0

    @property
    def gap(self) -> float:
        return relative_gap(self.lb, self.ub)


def relative_gap(lb: float, ub: float) -> float:
    """(ub - lb) / (ub + lb); 1 (the largest gap) when no upper bound is certified (ub = +inf)."""
    if np.isinf(ub) and ub > 0:
        return 1.0
    return (ub - lb) / (ub + lb)


def adaptive(
    site: Site,
    mesh: TriMesh,
    gap: float = 0.02,
    max_elements: int = 20000,
    theta: float = 0.5,
    max_steps: int = 12,
    mono_tol: float = 1e-6,
    progress=None,
) -> AdaptiveResult:
    """Refine ``mesh`` where the gap lives until (ub - lb)/(ub + lb) <= ``gap`` or ``max_elements``.

    Each step marks the fewest elements holding ``theta`` of the summed positive shares (Doerfler marking)
    and bisects them (nested, :func:`ssi.limit.mesh.bisect`). ``progress(row)`` is called per step."""
    gap = check_real("gap", gap, lo=0.0, lo_open=True, hi=1.0)
    max_elements = check_int("max_elements", max_elements, lo=1)
    theta = check_real("theta", theta, lo=0.0, lo_open=True, hi=1.0)
    out = AdaptiveResult()
    best_lb, best_ub = -np.inf, np.inf
    br = None
    raw_lb, raw_ub = -np.inf, np.inf
    for step in range(max_steps + 1):
        t0 = time.perf_counter()
        br = bracket(site, mesh, previous=br)
        row = dict(
            step=step,
            n_el=mesh.n_el,
            lb=br.lb,
            ub=br.ub,
            gap=br.gap,
            t_lb=br.lower.time,
            t_ub=br.upper.time,
            t_step=time.perf_counter() - t0,
            it_lb=br.lower.iterations,
            it_ub=br.upper.iterations,
            cones_lb=br.lower.n_cones,
            cones_ub=br.upper.n_cones,
            certified=br.lower.certified,
        )
        if np.isfinite(best_lb) and br.lb < best_lb * (1 - mono_tol):
            out.monotone = False
        if np.isfinite(best_ub) and br.ub > best_ub * (1 + mono_tol):
            out.monotone = False
        # the solver's own fields (before the carried ones are compared): monotone in exact arithmetic
        solved_lb = br.lower.lam_solver
        solved_ub = br.upper.lam_solver
        row["solver_lb"], row["solver_ub"] = solved_lb, solved_ub
        if solved_lb < raw_lb * (1 - mono_tol) or solved_ub > raw_ub * (1 + mono_tol):
            out.solver_setbacks += 1
        raw_lb, raw_ub = max(raw_lb, solved_lb), min(raw_ub, solved_ub)
        if br.lower.certified:
            best_lb = max(best_lb, br.lb)
        best_ub = min(best_ub, br.ub)
        row["best_lb"], row["best_ub"] = best_lb, best_ub
        out.history.append(row)
        out.final = br
        if progress is not None:
            progress(row)
        if relative_gap(best_lb, best_ub) <= gap:
            out.converged = True
            break
        if mesh.n_el >= max_elements or step == max_steps:
            break
        if not br.upper.certified:  # no mechanism to compare with: the gap shares say nothing
            break
        eta = np.maximum(br.shares, 0.0)
        order = np.argsort(-eta, kind="stable")
        csum = np.cumsum(eta[order])
        n_mark = int(np.searchsorted(csum, theta * csum[-1]) + 1)
        mesh = bisect(mesh, np.sort(order[:n_mark]))
    out.lb, out.ub = float(best_lb), float(best_ub)
    return out


def safety_factor(
    site: Site,
    mesh: TriMesh,
    interface: bool = True,
    rel_tol: float = 2e-3,
    f_start: float = 1.0,
) -> tuple[float, float, list]:
    """The strength-reduction factor of safety as a bracket [F_LB, F_UB]: the loads are the site's dead
    loads plus 1 x its reference loads; F_LB is a verified F whose reduced site (c / F, tan phi / F; the
    interfaces too if ``interface``) has a certified lower bound >= 1 (so F* >= F_LB), F_UB a verified F whose
    upper bound is < 1 (so F* < F_UB). Both by bisection in log F to ``rel_tol``. Returns (F_LB, F_UB,
    trials) with trials rows (bound, F, lambda)."""
    trials = []

    def lam(kind, F):
        s = site.reduced(F, interface=interface)
        v = lower_bound(s, mesh).lam if kind == "lb" else upper_bound(s, mesh).lam
        # an uncertified lower bound (NaN) proves nothing safe; an uncertified upper bound (+inf) proves
        # nothing failing, and stays +inf
        v = -np.inf if kind == "lb" and not np.isfinite(v) else v
        trials.append((kind, F, v))
        return v

    def solve(kind):
        # safe(F): the bound says the reduced site carries the loads
        lo, hi = f_start, f_start
        if lam(kind, f_start) >= 1.0:
            while True:
                hi *= 2.0
                if lam(kind, hi) < 1.0:
                    break
                lo = hi
                if hi > 1e3:
                    raise ValueError("no strength reduction up to F = 1000 makes the site fail")
        else:
            while True:
                lo /= 2.0
                if lam(kind, lo) >= 1.0:
                    break
                hi = lo
                if lo < 1e-3:
                    raise ValueError("the site fails even with its strength multiplied by 1000")
        while hi / lo - 1.0 > rel_tol:
            mid = np.sqrt(lo * hi)
            if lam(kind, mid) >= 1.0:
                lo = mid
            else:
                hi = mid
        return lo, hi

    f_lb, _ = solve("lb")
    _, f_ub = solve("ub")
    return f_lb, f_ub, trials
