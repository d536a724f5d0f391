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
from dataclasses import dataclass, field, replace

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
# adaptivity marks the lower bound's own indicator as well as the gap shares (refine_marks) unless
# SSI_LIMIT_LB_INDICATOR=0 (the marking before issue 46: the gap shares alone)
LOWER_INDICATOR = os.environ.get("SSI_LIMIT_LB_INDICATOR", "1") == "1"
# adaptive_pair runs the associated bracket first (SSI_LIMIT_DAVIS_FIRST=1: the Davis one). Issue 46's
# two-strip site to 3 %, fans at the strips' ends, lazy refinement, on the loaded machine: associated first
# 67.8 s of CPU (associated 5 meshes to 2 870 triangles, Davis 5 more to 5 636), Davis first 71.1 s (Davis
# 7 meshes to 6 426 triangles, then the associated one at 1.25 % on that mesh)
DAVIS_FIRST = os.environ.get("SSI_LIMIT_DAVIS_FIRST", "0") == "1"

__all__ = [
    "AdaptiveResult",
    "Bracket",
    "adaptive",
    "adaptive_pair",
    "bracket",
    "carry_stress",
    "carry_velocity",
    "gap_shares",
    "refine_marks",
    "safety_factor",
    "strength_reduction",
    "SafetyFactor",
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
    site: Site,
    mesh: TriMesh,
    label: str = "",
    previous: Bracket | None = None,
    threads: int | None = None,
    solve: tuple = ("lb", "ub"),
) -> Bracket:
    """Both bounds on one mesh and the gap shares. With ``previous``, a bracket on a mesh that ``mesh``
    refines (``mesh.parent`` set by :func:`ssi.limit.mesh.bisect`), its stress and velocity fields are
    carried to ``mesh`` (still admissible there) and each bound is the better of the solved and the carried
    field: nested refinement then never loses ground even when the solver stops short of the optimum.

    ``threads``: 2 solves the two bounds side by side (Clarabel releases the GIL while it solves, so on two
    cores the bracket takes the longer bound's time instead of the sum), 1 one after the other; None: the
    module's ``THREADS``. Either way the bounds are the same numbers (each program is solved alone).

    ``solve``: the bounds whose programs are solved ("lb", "ub"); a bound left out is ``previous``'s field
    carried to ``mesh`` (certified as such: its value is the previous bound's), which needs ``previous`` and
    a nested ``mesh`` (:func:`adaptive`'s ``lazy``)."""
    threads = THREADS if threads is None else check_int("threads", threads, lo=1, hi=2)
    solve = tuple(solve)
    if not solve or any(b not in ("lb", "ub") for b in solve):
        raise ValueError(f"solve must name 'lb' and/or 'ub', got {solve!r}")
    if len(solve) < 2 and (previous is None or mesh.parent is None):
        raise ValueError("solve: a bound left unsolved is carried from previous, which needs a nested mesh")
    if len(solve) == 1:
        lo = lower_bound(site, mesh) if "lb" in solve else _carried_lower(site, mesh, previous)
        up = upper_bound(site, mesh) if "ub" in solve else _carried_upper(site, mesh, previous)
        return Bracket(mesh, lo, up, gap_shares(site, mesh, lo, up), label)
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
        lo_c = _carried_lower(site, mesh, previous)
        if lo_c.certified and (not lo.certified or lo_c.lam > lo.lam):
            lo_c.time, lo_c.iterations, lo_c.status = lo.time, lo.iterations, f"carried ({lo.status})"
            lo_c.lam_solver = lo.lam_solver
            lo_c.yield_work = lo.yield_work  # the solve's own indicator (a carried field has no dual)
            lo = lo_c
    if previous is not None and mesh.parent is not None and up.lam > previous.ub:
        up_c = _carried_upper(site, mesh, previous)
        if up_c.lam < up.lam:
            up_c.time, up_c.iterations, up_c.status = up.time, up.iterations, f"carried ({up.status})"
            up_c.lam_solver = up.lam_solver
            up = up_c
    return Bracket(mesh, lo, up, gap_shares(site, mesh, lo, up), label)


def _carried_lower(site: Site, mesh: TriMesh, previous: Bracket) -> LowerBound:
    """``previous``'s stress field on the nested ``mesh``, certified there (no solve)."""
    sig = carry_stress(previous.mesh, mesh, previous.lower.stress)
    return lower_bound(site, mesh, stress=(sig, previous.lower.lam_projected))


def _carried_upper(site: Site, mesh: TriMesh, previous: Bracket) -> UpperBound:
    """``previous``'s velocity field on the nested ``mesh``, recomputed there (no solve)."""
    v, fv = carry_velocity(previous.mesh, mesh, previous.upper.velocity), previous.upper.footing_velocity
    return upper_bound(site, mesh, velocity=(v, fv, previous.upper.footing_rotation, previous.upper.beam))


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
    ``reason``: why the sequence stopped, in words ("gap reached"; "refinement cap (max_steps = 12)" or
    "(max_elements = 20000)", with "; the lower bound stalled" / "the upper bound stalled" when it did not
    improve by 0.1 % over the last three meshes; "no mechanism on the mesh"), ``monotone``: the nested
    meshes gave a non-decreasing lb and non-increasing ub (to ``mono_tol``
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
    reason: str = ""

    @property
    def gap(self) -> float:
        return relative_gap(self.lb, self.ub)

    def stalled(self, window: int = 3, rel: float = 1e-3) -> dict:
        """Which best bound did not improve by more than ``rel`` (relative) over the last ``window`` meshes:
        {"lb": bool, "ub": bool} (False for both with fewer meshes)."""
        h = self.history
        if len(h) <= window:
            return {"lb": False, "ub": False}
        a, b = h[-window - 1], h[-1]
        lb_moved = np.isfinite(a["best_lb"]) and b["best_lb"] > a["best_lb"] * (1 + rel)
        ub_moved = np.isfinite(b["best_ub"]) and b["best_ub"] < a["best_ub"] * (1 - rel)
        return {"lb": not lb_moved, "ub": not ub_moved}


def _doerfler(eta: np.ndarray, theta: float) -> np.ndarray:
    """The fewest elements holding ``theta`` of the summed indicator ``eta`` >= 0 (indices)."""
    if not np.any(eta > 0):
        return np.zeros(0, np.int64)
    order = np.argsort(-eta, kind="stable")
    csum = np.cumsum(eta[order])
    return order[: int(np.searchsorted(csum, theta * csum[-1]) + 1)]


def refine_marks(br: Bracket, theta: float = 0.5) -> np.ndarray:
    """The elements to bisect after bracket ``br`` (indices): Doerfler marking of the gap shares (where
    the upper bound's mechanism and the lower bound's stresses disagree) united with Doerfler marking of
    the lower bound's own indicator, the stress power of its program's dual mechanism
    (:attr:`LowerBound.yield_work`: where its yield conditions bind and limit lambda). The gap shares live
    where the upper bound's mechanism deforms; a lower bound limited elsewhere (a second footing, a soft
    lens, a layer boundary the mechanism does not cross) then never improves (issue 46: 0.95953 from mesh
    3 to 12)."""
    marks = _doerfler(np.maximum(br.shares, 0.0), theta)
    yw = getattr(br.lower, "yield_work", None)
    if yw is not None and len(yw) == br.mesh.n_el and np.any(yw > 0):
        marks = np.union1d(marks, _doerfler(np.maximum(yw, 0.0), theta))
    return np.sort(marks)


# adaptive(lazy=True): a bound is left unsolved on the next mesh when it gained less than this fraction of the
# other's gain on the last step (issue 46's two-strip site, Davis run: the upper bound gained 0.012 and 0.009
# while the lower bound gained 0.041 and 0.061). Measured on that site to 3 % (loaded machine, CPU time of
# the whole bracket): 0.25 left one upper bound unsolved, 67.8 s; 0.5 one lower and one upper, 54.1 s, the
# same meshes within 6 % and both gaps reached
LAZY_RATIO = 0.5


def _lazy_solve(history: list, last: tuple) -> tuple:
    """The bounds to solve on the next mesh (:func:`adaptive`'s ``lazy``): both, unless one gained less than
    LAZY_RATIO times the other's gain from the second-last mesh to the last one and was solved on the last
    one (a carried bound gains nothing, so it is never left out twice running)."""
    if len(history) < 2 or len(last) < 2:
        return ("lb", "ub")
    a, b = history[-2], history[-1]
    if not all(np.isfinite(r[k]) for r in (a, b) for k in ("best_lb", "best_ub")):
        return ("lb", "ub")
    d_lb = b["best_lb"] - a["best_lb"]
    d_ub = a["best_ub"] - b["best_ub"]
    if d_ub < LAZY_RATIO * d_lb:
        return ("lb",)
    if d_lb < LAZY_RATIO * d_ub:
        return ("ub",)
    return ("lb", "ub")


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
    lazy: bool = False,
) -> AdaptiveResult:
    """Refine ``mesh`` where the gap lives until (ub - lb)/(ub + lb) <= ``gap`` or ``max_elements``.

    Each step marks the fewest elements holding ``theta`` of the summed positive shares (Doerfler marking)
    and bisects them (nested, :func:`ssi.limit.mesh.bisect`). ``progress(row)`` is called per step.

    ``lazy``: a bound that gained less than ``LAZY_RATIO`` times what the other gained on the last step is
    not solved on the next mesh (never twice running): its field is carried (:func:`bracket`'s ``solve``),
    so it stays certified at its last value and the gap shares still have both fields, and the step costs
    one program instead of two. Where one bound lags (the lower bound of a site under two strips, issue
    46) the refinement then pays for that bound's program alone on every other mesh."""
    gap = check_real("gap", gap, lo=0.0, lo_open=True, hi=1.0)
    max_elements = check_int("max_elements", max_elements, lo=1)
    theta = check_real("theta", theta, lo=0.0, lo_open=True, hi=1.0)
    out = AdaptiveResult()
    best_lb, best_ub = -np.inf, np.inf
    br = None
    raw_lb, raw_ub = -np.inf, np.inf
    solve = ("lb", "ub")
    for step in range(max_steps + 1):
        t0 = time.perf_counter()
        br = bracket(site, mesh, previous=br, solve=solve)
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
            solved="+".join(solve),
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
            out.reason = "gap reached"
            break
        if mesh.n_el >= max_elements or step == max_steps:
            cap = f"max_steps = {max_steps}" if step == max_steps else f"max_elements = {max_elements}"
            out.reason = f"refinement cap ({cap}) at gap {100 * relative_gap(best_lb, best_ub):.2f} %"
            stall = out.stalled()
            out.reason += "".join(f"; the {w} bound stalled" for k, w in (("lb", "lower"), ("ub", "upper"))
                                  if stall[k])  # fmt: skip
            break
        if not br.upper.certified:  # no mechanism to compare with: the gap shares say nothing
            out.reason = f"no mechanism on the mesh (upper-bound status {br.upper.status})"
            break
        marks = refine_marks(br, theta) if LOWER_INDICATOR else _doerfler(np.maximum(br.shares, 0.0), theta)
        mesh = bisect(mesh, marks)
        solve = _lazy_solve(out.history, solve) if lazy else ("lb", "ub")
    out.lb, out.ub = float(best_lb), float(best_ub)
    return out


def adaptive_pair(
    associated: Site,
    davis: Site | None,
    mesh: TriMesh,
    progress=None,
    davis_first: bool = DAVIS_FIRST,
    **kw,
) -> tuple[AdaptiveResult, AdaptiveResult | None]:
    """Both adaptive runs of a capacity (:func:`adaptive`, keywords ``kw``): the ``associated`` site's and,
    unless ``davis`` is None, the Davis site's, the second started from the first's last mesh (unparented:
    a new start), which is already refined where the same footings' mechanisms and binding stresses are.
    ``davis_first`` (default DAVIS_FIRST): the Davis run first. ``progress(label, row)`` with label
    "associated" or "Davis". Returns (associated, Davis) results."""

    def report(label):
        return None if progress is None else (lambda row: progress(label, row))

    if davis is None:
        return adaptive(associated, mesh, progress=report("associated"), **kw), None
    first, second = (davis, associated) if davis_first else (associated, davis)
    labels = ("Davis", "associated") if davis_first else ("associated", "Davis")
    a = adaptive(first, mesh, progress=report(labels[0]), **kw)
    b = adaptive(second, replace(a.final.mesh, parent=None), progress=report(labels[1]), **kw)
    return (b, a) if davis_first else (a, b)


@dataclass
class SafetyFactor:
    """A strength-reduction factor of safety as a certified bracket: F* in [``f_lower``, ``f_upper``].

    ``f_lower``: a factor whose reduced site (c / F, tan phi / F) has a certified lower bound >= 1 (a
    statically admissible stress field carrying the loads: F* >= f_lower); ``f_upper``: a factor whose
    reduced site has a kinematically admissible field on which the loads' power exceeds the dissipation
    (F* <= f_upper). 0 / +inf where no such factor was found (``reason`` says why). ``loads``: "all" (lambda
    multiplies every load, the weight included: the programs are bounded) or "ref" (the dead loads held,
    the reference loads at 1; an unbounded upper-bound program is read from its ray). ``trials``: one dict
    per solve (bound, F, lam, proven, status, n_el); ``history``: one row per mesh (n_el, f_lower, f_upper,
    gap, solves, time [s]); ``mesh`` the last mesh; ``converged``: the gap (f_upper - f_lower) / (f_upper +
    f_lower) reached ``gap``."""

    f_lower: float
    f_upper: float
    loads: str
    mesh: TriMesh
    trials: list = field(default_factory=list)
    history: list = field(default_factory=list)
    converged: bool = False
    reason: str = ""

    @property
    def gap(self) -> float:
        return relative_gap(self.f_lower, self.f_upper)

    def contains(self, value: float) -> bool:
        return bool(self.f_lower <= value <= self.f_upper)

    def summary(self) -> str:
        state = "gap reached" if self.converged else f"gap not reached: {self.reason}"
        return (
            f"factor of safety (strength reduction) F in [{self.f_lower:.4g}, {self.f_upper:.4g}], gap "
            f"{100 * self.gap:.2f} % ({state}); {self.mesh.n_el} triangles, {len(self.history)} meshes, "
            f"{len(self.trials)} bound solves"
        )


F_RANGE = (1e-3, 1e3)  # the factors searched: a site outside is reported as such, not bracketed


def _fos_test(site: Site, mesh: TriMesh, kind: str, F: float, loads: str, interface: bool, trials: list):
    """One bound at factor F: (proven, lam, result). "lb": proven safe (a certified lambda_LB >= 1); "ub":
    proven unsafe (:meth:`UpperBound.collapse_proven` at lambda 1: the optimum's lambda_UB <= 1, or the ray
    of an unbounded program). Anything else proves nothing, whatever the status says: an infeasible
    lower-bound program means no admissible stress field on this mesh (a finer one may have one), a
    primal-infeasible upper-bound program no mechanism on this mesh."""
    s = site.reduced(F, interface=interface)
    if loads == "all":
        s = s.all_loads()
    if kind == "lb":
        r = lower_bound(s, mesh)
        lam = r.lam if r.certified else float("nan")
        proven = bool(r.certified and r.lam >= 1.0)
        if not proven and loads == "all" and "DualInfeasible" in str(r.status):
            # every load scaled together and the program unbounded: the friction the loads mobilise grows
            # with them faster than they do (a surcharge beside a footing), so lambda_all has no finite
            # optimum and the solver's iterate proves nothing; the same question with the weight and the
            # dead loads held at 1 is bounded, and its certified lambda_ref >= 1 proves the loads at 1
            # carried (issue 46: make demo's scene, F = 1, lambda_all "0.909" from an unbounded program)
            r = lower_bound(site.reduced(F, interface=interface), mesh)
            proven = bool(r.certified and r.lam >= 1.0)
            lam = float("inf") if proven else lam
    else:
        r = upper_bound(s, mesh)
        lam = r.lam if r.certified else -np.inf if r.collapse_proven(1.0) else float("nan")
        proven = r.collapse_proven(1.0)
    trials.append(dict(bound=kind, F=F, lam=float(lam), proven=proven, status=r.status, n_el=mesh.n_el))
    return proven, lam, r


def _fos_search(site, mesh, kind, loads, interface, trials, lo, hi, f0, rel_tol):
    """The factor where one bound changes its verdict, on one mesh: for "lb" the largest F proven safe
    (returned as ``lo``), for "ub" the smallest proven unsafe (``hi``). ``lo``: a factor known not to be
    proven unsafe / known safe, ``hi`` likewise above (None: unknown); ``f0`` the first trial. lambda(F) is
    non-increasing (the reduced yield sets are nested), about 1 / F (exactly for phi = 0 with every load
    scaled): the next trial is F lambda(F) (Newton's step in log F with slope -1), safeguarded by
    bisection in log F once both ends are known. Returns (lo, hi)."""
    F = f0
    g_lo = g_hi = None  # ln lambda at the ends, where known
    last = None
    # aim a little inside the side the bound proves (lambda_LB just above 1, lambda_UB just below): a trial
    # that lands on lambda = 1 to the solver's accuracy then proves its side instead of missing it
    g_aim = np.log1p(0.3 * rel_tol) if kind == "lb" else np.log1p(-0.3 * rel_tol)
    for _ in range(60):
        F = float(np.clip(F, *F_RANGE))
        proven, lam, _ = _fos_test(site, mesh, kind, F, loads, interface, trials)
        safe_side = proven if kind == "lb" else not proven
        g = float(np.log(lam)) if np.isfinite(lam) and lam > 0 else None
        if safe_side:
            lo, g_lo = F, g
        else:
            hi, g_hi = F, g
        if lo is not None and hi is not None and hi / lo - 1.0 <= rel_tol:
            return lo, hi
        if lo is None and F <= F_RANGE[0]:
            return None, hi
        if hi is None and F >= F_RANGE[1]:
            return lo, None
        # next trial: the secant through both ends in (ln F, ln lambda) once both are known (bisection in ln F
        # when the same end moved twice running: no creeping end), else Newton's step with slope -1 (F lambda)
        side = "lo" if safe_side else "hi"
        step = F * lam / np.exp(g_aim) if g is not None else None
        if lo is not None and hi is not None:
            a, b = np.log(lo), np.log(hi)
            x = 0.5 * (a + b)
            if side != last and g_lo is not None and g_hi is not None and g_lo > g_hi:
                x = a + (g_lo - g_aim) / (g_lo - g_hi) * (b - a)
            elif side != last and step is not None and step > 0:
                x = np.log(step)
            x = min(max(x, a + 0.05 * (b - a)), b - 0.05 * (b - a))
            F = float(np.exp(x))
        elif lo is None:  # everything tried so far is on the unsafe side: go down
            F = min(step, F / 1.05) if step is not None and step > 0 else F / 2.0
            F = max(F, hi / 4.0)
        else:  # everything tried so far on the safe side: go up
            F = max(step, F * 1.05) if step is not None else F * 2.0
            F = min(F, lo * 4.0)
        last = side
    return lo, hi


def strength_reduction(
    site: Site,
    mesh: TriMesh,
    gap: float = 0.01,
    loads: str = "all",
    interface: bool = True,
    max_steps: int = 8,
    max_elements: int = 20000,
    theta: float = 0.5,
    f_start: float = 1.0,
    progress=None,
) -> SafetyFactor:
    """The strength-reduction factor of safety of ``site`` as a certified bracket (:class:`SafetyFactor`):
    the loads are the site's weight, its dead loads and 1 x its reference loads (a site with no reference
    load: its weight and dead loads alone, e.g. a slope). On each mesh both bounds are searched in F
    (:func:`_fos_search`, to a tenth of ``gap``); then, until (F_U - F_L)/(F_U + F_L) <= ``gap`` or
    ``max_steps`` / ``max_elements``, the mesh is bisected where the bracket at F = sqrt(F_L F_U) has its
    gap (:func:`refine_marks`: the gap shares and the lower bound's own indicator). A factor proven on a
    coarser mesh stays proven (it is a property of the site, not of the mesh), so each mesh only narrows
    the bracket. ``loads``: "all" (default; every program bounded) or "ref" (the dead loads held at 1: an
    unbounded upper-bound program, the dead loads alone collapsing the reduced site, is read from its ray).
    ``interface``: reduce the footing interfaces too."""
    gap = check_real("gap", gap, lo=0.0, lo_open=True, hi=1.0)
    if loads not in ("all", "ref"):
        raise ValueError(f"loads must be 'all' or 'ref', got {loads!r}")
    max_elements = check_int("max_elements", max_elements, lo=1)
    f_start = check_real("f_start", f_start, lo=F_RANGE[0], hi=F_RANGE[1])
    rel_tol = gap / 5.0
    out = SafetyFactor(0.0, float("inf"), loads, mesh)
    f_lo, f_hi = None, None  # proven safe, proven unsafe
    for step in range(max_steps + 1):
        t0 = time.perf_counter()
        n0 = len(out.trials)
        start = f_start if f_lo is None else f_lo
        lo_l, _ = _fos_search(site, mesh, "lb", loads, interface, out.trials, f_lo, f_hi, start, rel_tol)
        start = f_hi if f_hi is not None else (lo_l if lo_l is not None else f_start)
        _, hi_u = _fos_search(site, mesh, "ub", loads, interface, out.trials, lo_l, f_hi, start, rel_tol)
        if lo_l is not None:
            f_lo = lo_l if f_lo is None else max(f_lo, lo_l)
        if hi_u is not None:
            f_hi = hi_u if f_hi is None else min(f_hi, hi_u)
        out.f_lower = 0.0 if f_lo is None else f_lo
        out.f_upper = float("inf") if f_hi is None else f_hi
        out.mesh = mesh
        row = dict(
            step=step,
            n_el=mesh.n_el,
            f_lower=out.f_lower,
            f_upper=out.f_upper,
            gap=out.gap,
            solves=len(out.trials) - n0,
            time=time.perf_counter() - t0,
        )
        out.history.append(row)
        if progress is not None:
            progress(row)
        if f_hi is None:
            out.reason = (
                f"no factor up to F = {F_RANGE[1]:g} made the site fail on this mesh: no mechanism found (a "
                "confined site, or one whose loads do no work)"
            )
            break
        if f_lo is None:
            out.reason = f"no factor down to F = {F_RANGE[0]:g} was proven safe on this mesh"
            break
        if out.gap <= gap:
            out.converged = True
            out.reason = ""
            break
        if step == max_steps or mesh.n_el >= max_elements:
            out.reason = f"refinement cap ({'max_steps' if step == max_steps else 'max_elements'})"
            break
        # refine where the bracket at the middle factor has its gap
        fm = float(np.sqrt(f_lo * f_hi))
        s_m = site.reduced(fm, interface=interface)
        br = bracket(s_m.all_loads() if loads == "all" else s_m, mesh)
        if not br.upper.certified:
            out.reason = f"no mechanism at F = {fm:.4g} to refine by (upper-bound status {br.upper.status})"
            break
        mesh = bisect(mesh, refine_marks(br, theta))
    return out


def safety_factor(
    site: Site,
    mesh: TriMesh,
    interface: bool = True,
    rel_tol: float = 2e-3,
    f_start: float = 1.0,
    loads: str = "all",
) -> tuple[float, float, list]:
    """The strength-reduction factor of safety on one mesh as a bracket [F_LB, F_UB] (no refinement:
    :func:`strength_reduction` with ``max_steps=0``; its bisections to ``rel_tol``): the loads are the site's
    weight and dead loads plus 1 x its reference loads; F_LB a factor whose reduced site (c / F, tan phi / F;
    the interfaces too if ``interface``) has a certified lower bound >= 1 (F* >= F_LB), F_UB one whose
    reduced site has a kinematically admissible field with more load power than dissipation (F* <= F_UB).
    Returns (F_LB, F_UB, trials) with trials rows (bound, F, lambda). Raises ValueError when no factor in
    [1e-3, 1e3] is proven on one side."""
    rel_tol = check_real("rel_tol", rel_tol, lo=0.0, lo_open=True, hi=0.5)
    res = strength_reduction(site, mesh, gap=5.0 * rel_tol, loads=loads, interface=interface,
                             max_steps=0, f_start=f_start)  # fmt: skip
    if not np.isfinite(res.f_upper):
        raise ValueError(f"no strength reduction up to F = {F_RANGE[1]:g} makes the site fail: {res.reason}")
    if res.f_lower <= 0.0:
        raise ValueError(f"the site is not proven safe even with its strength multiplied by {F_RANGE[1]:g}")
    return res.f_lower, res.f_upper, [(t["bound"], t["F"], t["lam"]) for t in res.trials]
