"""Incremental--iterative solution (paper §8, eq. 8.1).

For each increment of the load factor lambda the solver iterates

    u <- u + s du,   du = H(u) (F_ext(lambda) - F_int(u)),

until the residual is small, and only then commits the material state (the laws never see an unconverged
state as history). ``method`` chooses H:

* ``"bfgs"`` (default): the inverse of K0, the initial elastic stiffness factorised **once**, updated with
  the secant pairs of the increment's iterations (L-BFGS, Matthies & Strang 1979), with a line search on
  du . r. Superlinear on smooth problems, one factorisation, symmetric and positive definite whatever the
  material tangent (non-associated flow).
* ``"modified"`` (the paper): H = K0^-1 for every iteration of every increment. Converges linearly.
* ``"full"``: H = the consistent tangent's inverse, refactorised every iteration (unsymmetric if the laws
  are). Converges quadratically near the solution.

An increment that fails is retried with ``Settings.fallback`` (full Newton with a line search after BFGS,
K0 after full Newton), then cut. ``stepping="auto"`` sizes the increments by the iteration count;
``"fixed"`` takes each target as one increment (the paper's equal steps). When the increments cannot
advance any more, the current stiffness of the path (load per loaded displacement, relative to the first
step's) decides: below ``collapse_stiffness`` the result ends as ``"limit load reached"`` with the converged
path; otherwise :class:`NonConvergence` is raised with what diverged, where and at which load.

Load control scales the model's loads and prescribed displacements by lambda; displacement control is
load control of a model whose "load" is a prescribed displacement (``Model.prescribe``), and the reaction at
those DOFs is the load measure (``Result.reaction``).

Convergence (both must hold): the residual-force norm relative to the structural load -- the applied
reference load and the change of internal force since the geostatic state (reactions included, so
displacement control is covered) -- and the energy norm |du . r| relative to that of the increment's first
iteration (or to the work of the structural load, if larger). The geostatic forces are left out of the
reference on purpose: in a deep or heavy block they would make a small structural residual invisible
(``convergence_reference="total"`` restores the old measure).
"""

import math
import time
from collections import deque
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..core.linsolve import BACKENDS, Factorization
from ..core.model import Model, System
from ..core.protocol import CONSISTENT
from ..core.solution import COMPLETED, LIMIT_LOAD, STOPPED, Result  # noqa: F401 (Result and the statuses live there)
from ..core.validate import check_bool, check_choice, check_int, check_real
from .lbfgs import lbfgs_first_loop, lbfgs_second_loop
from .progress import SolverProgress, announce_compilation, log, solver_progress

METHODS = ("bfgs", "modified", "full")
STEPPINGS = ("auto", "fixed")
REFERENCES = ("structural", "total")

# per method: default iteration cap of an increment and the iteration count automatic stepping aims at
_MAX_ITER = {"bfgs": 100, "modified": 300, "full": 30}
_DESIRED_ITER = {"bfgs": 20, "modified": 60, "full": 8}


@dataclass
class Settings:
    """Solver options. The defaults solve ordinary nonlinear scenes; :meth:`paper` gives the paper's
    algorithm.

    ``method``: ``"bfgs"`` (default) -- quasi-Newton (L-BFGS) updates of the one K0 factorisation with a line
    search; ``"modified"`` -- the paper's modified Newton-Raphson (K0 for every iteration); ``"full"`` --
    Newton with the consistent tangent, refactorised every iteration.

    ``stepping``: ``"auto"`` (default) -- each target load factor is approached in increments that start at
    ``first_step``, grow or shrink with the iteration count (aiming at ``desired_iterations``) and are halved
    on failure down to ``min_step``; ``"fixed"`` -- each target is one increment, halved at most ``max_cuts``
    times on failure (the paper's equal increments).

    When an increment cannot advance, the path's current stiffness (load increment per loaded displacement,
    relative to the first step's) tells a collapse from a numerical failure: below ``collapse_stiffness``
    the result ends with ``status == "limit load reached"``; otherwise :class:`NonConvergence` is raised.
    Step sizes are fractions of the largest target load factor; tolerances are relative (dimensionless).
    """

    method: str = "bfgs"
    stepping: str = "auto"
    force_tol: float = 1e-5  # |r| <= force_tol * (structural load; see convergence_reference)
    energy_tol: float = 1e-8  # |du . r| <= energy_tol * max(|du_0 . r_0|, work of the structural load)
    convergence_reference: str = "structural"  # "total": the old measure, force relative to
    # max(|F_ext|, |F_int|) and energy relative to |u . F_int|, geostatic forces included
    max_iter: int | None = None  # per increment; None: 100 (bfgs), 300 (modified), 30 (full Newton: more
    # tangent factorisations than that cost more than the BFGS retry below)
    first_step: float = 0.1  # auto stepping: first increment of the load factor
    max_step: float = 0.25  # auto stepping: largest increment
    min_step: float = 1e-4  # auto stepping: smallest increment tried before the path is judged stuck
    desired_iterations: int | None = None  # auto stepping: None: 20 (bfgs), 60 (modified), 8 (full)
    max_cuts: int = 6  # fixed stepping: halvings of a failing increment
    collapse_stiffness: float = 0.05  # current stiffness / initial below which a stuck path is a collapse
    divergence_ratio: float = 1e6  # residual growth over the first iteration taken as divergence
    backend: str = "auto"
    symmetric_tangent: bool = False  # set True when every law's tangent is symmetric (associated flow)
    verbose: bool = False  # log every converged step at INFO level (logger "ssi.solver")
    progress: bool | None = None  # progress bar: None = only when stderr is a terminal and no test runs
    keep_states: bool = True  # keep the committed state of every step (False: only the last)
    line_search: bool | None = None  # None: on for bfgs, off for full Newton (on, it stopped chapter 11's
    # finest mesh at 95 % of its load); never for modified Newton
    line_search_min: float = 1.0 / 64.0  # full Newton: smallest step fraction the line search tries
    bfgs_memory: int = 30  # L-BFGS pairs kept within an increment
    viscous_fallback: bool = True  # a stuck path that has not stopped rising goes on viscous (tau = 1) and is
    # relaxed to the rate-independent state at its end (see ``viscosity``)
    viscosity: float = 0.0  # Duvaut-Lions regularisation tau = dt/eta per increment of the groups that
    # have it (soil); > 0: the path is viscous and, after the last target, the
    # load is held while tau grows (relaxation) until the state is the
    # rate-independent one -- see :func:`relax`
    fallback: str | None = "auto"  # method that retries a failed increment before it is cut; "auto": full
    # Newton with line search for bfgs (points that flip between elastic and
    # plastic stall the K0-based update), L-BFGS on K0 for full Newton (an
    # indefinite tangent can send Newton astray; K0 cannot, and the BFGS
    # updates and line search make the retry converge where plain K0
    # iterations crawl: chapter 10's psi = 0 footing at h = 0.125 m took
    # 59 s with the plain K0 retry, 1 of 64 retries converging in 300
    # iterations, and 11 s with BFGS); None: no retry
    fallback_iter: int = 300  # iterations of the fallback retry

    def __post_init__(self):
        check_choice("Settings.method", self.method, METHODS)
        check_choice("Settings.stepping", self.stepping, STEPPINGS)
        check_choice("Settings.convergence_reference", self.convergence_reference, REFERENCES)
        if self.max_iter is None:
            self.max_iter = _MAX_ITER[self.method]
        if self.desired_iterations is None:
            self.desired_iterations = _DESIRED_ITER[self.method]
        if self.line_search is None:
            self.line_search = self.method == "bfgs"
        if self.fallback == "auto":
            self.fallback = {"bfgs": "full", "full": "bfgs", "modified": None}[self.method]
        if self.fallback is not None:
            check_choice("Settings.fallback", self.fallback, METHODS)
        check_real("Settings.force_tol", self.force_tol, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
        check_real("Settings.energy_tol", self.energy_tol, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
        check_int("Settings.max_iter", self.max_iter, lo=1)
        check_int("Settings.max_cuts", self.max_cuts, lo=0)
        check_int("Settings.desired_iterations", self.desired_iterations, lo=1)
        check_int("Settings.fallback_iter", self.fallback_iter, lo=0)
        check_int("Settings.bfgs_memory", self.bfgs_memory, lo=0)
        check_real("Settings.max_step", self.max_step, lo=0.0, hi=1.0, lo_open=True)
        check_real("Settings.first_step", self.first_step, lo=0.0, hi=self.max_step, lo_open=True)
        check_real("Settings.min_step", self.min_step, lo=0.0, hi=self.first_step, lo_open=True)
        check_real("Settings.collapse_stiffness", self.collapse_stiffness, lo=0.0, hi=1.0, hi_open=True)
        check_real("Settings.viscosity", self.viscosity, lo=0.0, unit="(tau = dt/eta per increment)")
        check_real("Settings.divergence_ratio", self.divergence_ratio, lo=1.0, lo_open=True)
        check_choice("Settings.backend", self.backend, BACKENDS)
        for name in ("symmetric_tangent", "verbose", "keep_states", "line_search", "viscous_fallback"):
            check_bool(f"Settings.{name}", getattr(self, name))
        if self.progress is not None:
            check_bool("Settings.progress", self.progress)
        check_real("Settings.line_search_min", self.line_search_min, lo=0.0, hi=1.0, lo_open=True)

    @classmethod
    def paper(cls, **overrides: object) -> "Settings":
        """The paper's algorithm (§8): modified Newton--Raphson on K0 in the given, equal increments, without
        the viscous fallback.

        (The paper's explicit D_ep stress integration is a property of the soil law: ``scheme="explicit"``
        on a ``SoilLayer`` or in ``mohr_coulomb_params``.)"""
        return cls(**{"method": "modified", "stepping": "fixed", "viscous_fallback": False, **overrides})


class NonConvergence(RuntimeError):
    """An increment failed after all step cuts; ``report`` says what, where and at which load."""

    def __init__(self, report: dict, result: "Result") -> None:
        self.report = report
        self.result = result  # the converged steps before the failure, for inspection only
        text = ", ".join(f"{k}={v}" for k, v in report.items())
        super().__init__(f"increment did not converge: {text}")


def run(
    model: Model,
    load_factors: ArrayLike = (1.0,),
    settings: Settings | None = None,
    *,
    start: "Result | None" = None,
    loads: tuple | None = None,
) -> Result:
    """Follow the load path through the targets ``load_factors`` (increasing or not) from lambda = 0.

    With ``settings.stepping == "auto"`` the targets are waypoints, each reached by automatic increments;
    with ``"fixed"`` each target is one increment (halved on failure).

    ``start``: continue from the last converged step of an earlier result of the same model (its u and
    material state become step 0, at lambda = 0): the next phase of a phased analysis. ``loads``:
    ``(f_ref, f_dead)`` global vectors [N] replacing the model's own (F_ext = lambda f_ref + f_dead), e.g. the
    loads of the previous phase as dead load and the phase's change as reference load. Prescribed
    displacements are absolute: fixed value + lambda * prescribed value.

    Returns a :class:`Result` whose ``status`` says whether the targets were reached or a limit load was
    detected. Raises :class:`NonConvergence` if an increment fails before either.
    """
    settings = settings or Settings()
    targets = np.atleast_1d(np.asarray(load_factors, np.float64))
    if targets.size == 0 or not np.all(np.isfinite(targets)):
        raise ValueError("load_factors must be a non-empty sequence of finite numbers")
    model.check()
    announce_compilation()
    t_start = time.perf_counter()
    _set_viscosity(model, settings.viscosity)
    path = _Path(model, settings, start, loads, scale=float(np.abs(targets).max()) or 1.0)
    try:
        with solver_progress(settings.progress, total=path.scale) as path.bar:
            for target in targets:
                path.follow(float(target))
                if path.result.collapsed:
                    path.bar.note(path.result.message)
                    break
        if path.tau > 0.0 and not path.result.collapsed:
            relax(path)
    finally:
        _set_viscosity(model, 0.0)
        path.result.wall_time = time.perf_counter() - t_start
    return path.result


def _has_viscosity(model) -> bool:
    return any(hasattr(g, "viscosity") for g in model.groups)


def _viscosity_in_force(model) -> float:
    return max((g.viscosity for g in model.groups if hasattr(g, "viscosity")), default=0.0)


def _set_viscosity(model, tau):
    for g in model.groups:
        if hasattr(g, "viscosity"):
            g.viscosity = float(tau)


RELAX_GROWTH = 10.0  # tau grows tenfold from one relaxation stage to the next ...
RELAX_STAGES = 4  # ... over this many stages, then the last stage is rate independent (tau = 0)
RELAX_STEPS = 8  # increments at most per stage
RELAX_TOL = 1e-5  # a stage ends when the load measure changes by less than this (relative)
RELAX_MIN_GROWTH = 1.5  # a failing stage is retried with a smaller growth of tau, down to this
FLOW_MIN = 10.0 * RELAX_TOL  # a held increment smaller than this (relative to delta) is not flow but noise
BRACKET_TOL = 0.01  # a limit load found by relaxation is bracketed to 1 % of its load factor ...
BRACKET_REFINEMENTS = 4  # ... with at most this many extra relaxations
# A held load "flows" (evidence of a mechanism) when its flow stiffness is below this fraction of
# collapse_stiffness. Measured: the zoo's held loads above a detected limit flowed at 4e-9 .. 1.6e-3 of the
# initial stiffness; the graded h = 0.0625 m copy of chapter 11's foundation, which carries lambda = 1
# on every coarser copy, failed to relax at lambda = 0.615 with 0.044 (it relaxed by half per increment:
# slow, not flowing) and was taken for a collapse there while the threshold was collapse_stiffness itself.
FLOW_COLLAPSE_FRACTION = 0.1


class _RelaxationFailed(Exception):
    """No rate-independent equilibrium was found at the held load (the last relaxation stage failed)."""

    def __init__(self, outcome, tau, lam, flow_stiffness=np.nan):
        super().__init__(outcome.get("reason", ""))
        self.outcome, self.tau, self.lam = outcome, tau, lam
        self.flow_stiffness = flow_stiffness  # see _flow_stiffness (nan: unknown)


def _flow_stiffness(deltas, tau):
    """Current stiffness parameter of a held load's flow mode, from the loaded displacement of its last three
    increments at viscosity ``tau``: a mode of stiffness s (relative to the elastic one) relaxes by
    1 / (1 + tau s) per increment, so s = (1/r - 1) / tau with r the ratio of the last two displacement
    increments. nan when unknown (fewer than three, tau = 0, no motion beyond ``FLOW_MIN``)."""
    if len(deltas) < 3 or tau <= 0.0 or deltas[-2] == deltas[-3]:
        return np.nan
    if abs(deltas[-1] - deltas[-2]) <= FLOW_MIN * abs(deltas[-1]):
        return np.nan  # motion at the level of the convergence tolerance says nothing about a mechanism
    r = abs(deltas[-1] - deltas[-2]) / abs(deltas[-2] - deltas[-3])
    return (1.0 / r - 1.0) / tau if r > 0.0 else np.inf


def _relax_stages(path):
    """Hold the path's load while tau grows; raises :class:`_RelaxationFailed` if the state does not relax.
    A stage that fails is retried from its start with the square root of its growth (down to 1.5x): a
    sudden tenfold stiffening of the viscous law is a large jump of the problem, a smaller one may not be."""
    lam, tau, growth = path.lam, path.tau, RELAX_GROWTH
    tau_last = path.tau * RELAX_GROWTH**RELAX_STAGES
    try:
        while True:
            nxt = 0.0 if tau >= tau_last * (1.0 - 1e-12) else min(tau * growth, tau_last)
            start = path.save()
            try:
                _hold(path, lam, nxt)
            except _RelaxationFailed:
                path.restore(start)
                growth = growth**0.5
                if nxt == 0.0 or growth < RELAX_MIN_GROWTH:
                    raise
                continue
            if nxt == 0.0:
                return
            tau = nxt
    finally:
        _set_viscosity(path.model, path.tau)


def _hold(path, lam, tau):
    """One relaxation stage: up to ``RELAX_STEPS`` increments at the held load with viscosity ``tau``, until
    the load measure settles. A stage that ends unsettled leaves its flow stiffness in ``path.flow``."""
    _set_viscosity(path.model, tau)
    deltas = [path.measure.point(path.result.n_steps)[1]]
    for _ in range(RELAX_STEPS):
        before = np.array(path.measure.point(path.result.n_steps))
        outcome = path._increment(lam)
        if not outcome["converged"]:
            flow = _flow_stiffness(deltas, tau) if len(deltas) >= 3 else path.flow
            raise _RelaxationFailed(outcome, tau, lam, flow)
        path._commit(lam, outcome)
        after = np.array(path.measure.point(path.result.n_steps))
        deltas.append(after[1])
        if np.all(np.abs(after - before) <= RELAX_TOL * np.maximum(np.abs(after), 1e-30)):
            path.flow = np.nan
            return
    path.flow = _flow_stiffness(deltas, tau)


def relax(path: "_Path") -> bool:
    """Hold the last target load of a viscous path while tau grows (10x per stage, then tau = 0): the
    overstress of each increment decays by 1/(1 + tau), and the last stage is the rate-independent law, so
    the final step is an equilibrium state of the inviscid problem (converged to the usual tolerances).
    Its step count is ``RELAX_STEPS`` per stage at most; each stage ends once the load measure settles.

    A viscous path can pass a limit load: the regularised problem has a solution above the rate-independent
    capacity (the overstress carries the excess). If the held load does not relax, the largest load factor
    of the viscous path that does relax is searched (bisection over its steps, then over lambda), and the
    result ends as ``"limit load reached"`` there, with ``limit_load_upper`` the smallest load factor where
    no rate-independent equilibrium was found -- provided the structure is at a limit: the held load kept
    flowing -- the nearest held load above that factor, with a current stiffness (:func:`_flow_stiffness`)
    below ``FLOW_COLLAPSE_FRACTION * collapse_stiffness`` -- or the two highest relaxed states' secant
    stiffness is below ``collapse_stiffness``. Else :class:`NonConvergence`."""
    first = path.result.n_steps
    saved = path.save()
    try:
        _relax_stages(path)
    except _RelaxationFailed as failure:
        path.restore(saved)
        _bracket_limit(path, saved, failure)
        path.result.relaxed_steps = None  # the path was cut back to the limit: its end is the relaxed state
        path.tau = 0.0
        return False
    path.result.relaxed_steps = path.result.n_steps - first
    path.tau = 0.0
    _set_viscosity(path.model, 0.0)
    return True


def _bracket_limit(path, saved, failure):
    """The held load of a viscous path did not relax: find the largest load factor that does (see
    :func:`relax`), or raise NonConvergence. ``saved`` is the path before the failed relaxation."""
    res = path.result
    if not path.settings.keep_states:  # the steps' states are needed to relax at an earlier step
        _raise_relaxation_failure(path, failure, np.nan, np.nan)
    lo = res.viscous_from if res.viscous_from is not None else 0
    hi = res.n_steps
    best = None
    relaxed = [path.measure.point(lo)]  # (load measure, loaded displacement) of rate-independent states
    failures = [failure]  # every held load that did not relax (any of them may show the flow)
    while hi - lo > 1:  # bisection over the committed viscous steps
        mid = (lo + hi) // 2
        path.restore(saved, mid)
        try:
            _relax_stages(path)
            best, lo = path.save(), mid
            relaxed.append(path.measure.point(path.result.n_steps))
        except _RelaxationFailed as nearer:
            hi = mid
            failures.append(nearer)
    if best is None:  # only the state before the viscous fallback (rate independent already)
        path.restore(saved, lo)
    else:
        path.restore(best)
    lam_hi = saved.lists["load_factor"][hi]
    lam_lo = path.lam
    for _ in range(BRACKET_REFINEMENTS):  # bisection over lambda from the relaxed state at lam_lo
        if lam_hi - lam_lo <= BRACKET_TOL * abs(lam_hi):
            break
        here = path.save()
        lam_mid = 0.5 * (lam_lo + lam_hi)
        try:
            _set_viscosity(path.model, path.tau)
            outcome = path._increment(lam_mid)
            if not outcome["converged"]:
                raise _RelaxationFailed(outcome, path.tau, lam_mid)
            path._commit(lam_mid, outcome)
            _relax_stages(path)
            lam_lo = lam_mid
            relaxed.append(path.measure.point(path.result.n_steps))
        except _RelaxationFailed as nearer:
            path.restore(here)
            lam_hi = lam_mid
            failures.append(nearer)
    path.tau = 0.0
    _set_viscosity(path.model, 0.0)
    stiff = _secant_stiffness(path.measure, relaxed)
    failure, flowing, collapsed = _collapse_evidence(failures, stiff, path.settings.collapse_stiffness)
    if collapsed:
        res.status, res.limit_load_factor, res.limit_load_upper = LIMIT_LOAD, float(lam_lo), float(lam_hi)
        res.limit_evidence = (
            f"held at lambda = {failure.lam:.6g} the body kept flowing, its current stiffness "
            f"{failure.flow_stiffness:.2g} of the initial"
            if flowing
            else f"the relaxed path's current stiffness fell to {stiff:.3g} of the initial"
        )
        return
    _raise_relaxation_failure(path, failure, lam_lo, stiff)


def _collapse_evidence(failures, secant_stiffness, collapse_stiffness):
    """(nearest failure, it flowed, the bracket is a collapse) for the held loads that did not relax
    (``failures``, :class:`_RelaxationFailed`) and the relaxed path's secant stiffness. The evidence is the
    held load at the bracket's upper end, the nearest failure: a flow far above it says nothing about the
    load just above the limit. It flowed when its flow stiffness is below ``FLOW_COLLAPSE_FRACTION *
    collapse_stiffness``; the bracket is a collapse when it flowed or the secant stiffness is below
    ``collapse_stiffness``."""
    failure = min(failures, key=lambda f: f.lam)
    flowing = bool(failure.flow_stiffness < FLOW_COLLAPSE_FRACTION * collapse_stiffness)  # nan: no
    flat = bool(np.isfinite(secant_stiffness) and secant_stiffness < collapse_stiffness)
    return failure, flowing, flowing or flat


def _secant_stiffness(measure, points):
    """Current stiffness parameter of the rate-independent path from its two highest relaxed points (P,
    delta): the viscous path's own stiffness says nothing about the limit, its overstress stiffens it."""
    if len(points) < 2 or measure.first is None:
        return np.nan
    (p1, d1), (p2, d2) = sorted(points)[-2:]
    return float((p2 - p1) / (d2 - d1) / measure.first) if d2 != d1 else np.nan


def _raise_relaxation_failure(path, failure, lam_lo, stiff):
    report = _failure_report(path.model, path.system.free, failure.outcome, failure.lam, failure.lam)
    report["reason"] = f"relaxation of the viscous path failed at tau={failure.tau:g}: {report['reason']}"
    if np.isfinite(lam_lo):
        report["reason"] += (
            f" (the largest load factor that relaxes is {lam_lo:.6g}; the relaxed path's current stiffness "
            f"there is {stiff:.3g} of the initial, not below collapse_stiffness="
            f"{path.settings.collapse_stiffness:g}, and the held load at lambda = {failure.lam:.6g} did not "
            f"flow (flow stiffness {failure.flow_stiffness:.2g}, not below "
            f"{FLOW_COLLAPSE_FRACTION * path.settings.collapse_stiffness:g}), so this is not taken for a "
            "collapse; softening (a cracking strip) and non-associated laws (soil psi < phi, contact "
            "psi_deg < phi_deg) can lose rate-independent solutions below the capacity on a fine mesh: try "
            "a coarser mesh where the worst DOF lies, or dilation closer to friction)"
        )
    path.result.status = STOPPED
    raise NonConvergence(report, path.result)


@dataclass
class _Snapshot:
    """A committed path (see :meth:`_Path.save`): copies of the result's per-step lists and the state."""

    lists: dict
    u: np.ndarray
    states: list
    lam: float
    step: float


CRAWL_WINDOW = 12  # attempts over which a crawling rate-independent path is judged (see _Path._crawling)
FALLBACK_LEADS = 8  # increments the fallback leads after it converged where the settings' method failed


class _Path:
    """The incremental-iterative state of one run: committed (u, states, lambda) and the machinery."""

    def __init__(self, model, settings, start, loads, scale=1.0):
        """``scale``: the largest target |lambda|; step sizes are fractions of it."""
        self.model, self.settings = model, settings
        self.system, self.f_ref, self.f_dead, self.states, self.u, self.result, self.fac_k0 = _start(
            model, settings, start, loads
        )
        self.lam = 0.0
        self.tau = settings.viscosity  # the viscosity in force (the viscous fallback may switch it on)
        self.scale = scale
        self.bar = SolverProgress(None, 1.0)  # silent until run() opens the real one
        self.step = settings.first_step * scale
        self.measure = _LoadMeasure(self.system, self.f_ref, self.result)
        self.flow = np.nan  # flow stiffness of the last relaxation stage that ended unsettled
        self.fallback_leads = 0  # increments for which the fallback method is tried first
        self.advances = deque(maxlen=CRAWL_WINDOW)  # auto stepping: |delta lambda| of the last attempts (0
        # for a failed one)
        self.crawl_may_go_viscous = True  # a crawling path may try the viscous fallback (see _stuck)
        self.crawl_start = None  # the committed path where a crawl went viscous, to come back to

    def save(self) -> "_Snapshot":
        """The committed path (result lists and current state), to return to with :meth:`restore`."""
        r = self.result
        return _Snapshot(
            {name: list(getattr(r, name)) for name in Result.ROWS},
            self.u,
            self.states,
            self.lam,
            self.step,
        )

    def restore(self, snap: "_Snapshot", step: int | None = None):
        """Return to ``snap``, or to its committed step ``step`` (the later steps are dropped)."""
        k = len(snap.lists["load_factor"]) if step is None else step + 1
        for name, values in snap.lists.items():
            setattr(self.result, name, list(values[:k]))
        if step is None:
            self.u, self.states, self.lam, self.step = snap.u, snap.states, snap.lam, snap.step
        else:
            self.u, self.lam = self.result.u[-1].copy(), self.result.load_factor[-1]
            self.states = self.result.states[-1]

    def follow(self, target):
        """Advance the committed state to ``target``, or stop at a detected limit load."""
        if self.settings.stepping == "auto":
            self._follow_auto(target)
        else:
            self._follow_fixed(target)

    def _follow_auto(self, target):
        s = self.settings
        direction = np.sign(target - self.lam)
        while abs(target - self.lam) > 1e-12 * max(1.0, abs(target)):
            remaining = abs(target - self.lam)
            lam_next = target if self.step >= remaining else self.lam + direction * self.step
            outcome = self._increment(lam_next)
            if outcome["converged"]:
                last = abs(lam_next - self.lam)
                self._commit(lam_next, outcome)
                self._adapt(last, outcome["iterations"])
                self.advances.append(last)
                continue
            self.result.cuts += 1
            self.advances.append(0.0)
            self.bar.note(f"step cut at lambda={lam_next:.6g}: {outcome.get('reason', '')}")
            self.step = 0.5 * abs(lam_next - self.lam)
            # a crawl on a flattened path goes on to min_step (see _at_limit)
            crawling = self.crawl_may_go_viscous and self._crawling()
            crawling = crawling and self._can_go_viscous() and not self._at_limit()
            if crawling or self.step < s.min_step * self.scale * (1.0 - 1e-9):
                if not self._stuck(outcome, lam_next, crawling):
                    return
                self.step = s.first_step * self.scale

    def _follow_fixed(self, target):
        """The target in one increment; a failing increment is halved, at most ``max_cuts`` times."""
        pending = [target]
        cuts_here = 0
        while pending:
            lam_next = pending[-1]
            outcome = self._increment(lam_next)
            if outcome["converged"]:
                self._commit(lam_next, outcome)
                pending.pop()
                continue
            if cuts_here >= self.settings.max_cuts:
                if not self._stuck(outcome, lam_next):
                    return
                cuts_here = 0
                continue
            cuts_here += 1
            self.result.cuts += 1
            self.bar.note(f"step cut at lambda={lam_next:.6g}: {outcome.get('reason', '')}")
            pending.append(0.5 * (self.lam + lam_next))

    def _increment(self, lam_next):
        """One increment with the leading method, retried with the other one (the settings' method and its
        fallback) before a step cut. When the fallback converges where the settings' method failed, it leads
        the next ``FALLBACK_LEADS`` increments: on a stretch where the K0-based update stalls (cracking
        strip, flipping plastic points) every increment would otherwise pay a stalled BFGS run first
        (measured on chapter 11's h = 0.125 m mesh: 139 such failures, 61 % of its time)."""
        s = self.settings
        first = s.method if self.fallback_leads == 0 or not s.fallback else s.fallback
        outcome = self._attempt(lam_next, first)
        other = s.fallback if first == s.method else s.method
        if not outcome["converged"] and s.fallback and s.fallback != s.method:
            retry = self._attempt(lam_next, other)
            retry["iterations"] += outcome["iterations"]
            if retry["converged"]:
                self.fallback_leads = FALLBACK_LEADS if other == s.fallback else 0
                return retry
            return outcome
        self.fallback_leads = max(0, self.fallback_leads - 1) if first != s.method else 0
        return outcome

    def _attempt(self, lam_next, method):
        return _increment(
            self.system,
            self.settings,
            self.fac_k0,
            self.u,
            self.states,
            lam_next,
            self.f_ref,
            self.f_dead,
            self.result,
            method,
        )

    def _commit(self, lam, outcome):
        self.u, self.states, self.lam = outcome["u"], outcome["states"], lam
        _record(
            self.result,
            lam,
            self.u,
            outcome["f_int"],
            self.states,
            outcome["iterations"],
            outcome["residuals"],
            outcome["energies"],
            self.settings,
            _viscosity_in_force(self.model),
        )
        self.result.stiffness.append(self.measure.stiffness())
        residual = outcome["residuals"][-1] if outcome["residuals"] else 0.0
        self.bar.update(self.result.n_steps, lam, outcome["iterations"], residual)
        if self.settings.verbose:
            log.info(
                "step %4d  lambda=%.6g  iterations=%3d  residual=%.2e  stiffness=%.3g",
                self.result.n_steps,
                lam,
                outcome["iterations"],
                residual,
                self.result.stiffness[-1],
            )

    def _adapt(self, last_step, iterations):
        """Next increment from the last one: 1.5x after an easy increment (at most ``desired_iterations``),
        1.2x after one within half of ``max_iter``, the same up to three quarters, 0.7x beyond. The iteration
        count of a K0-based update on a plastic scene hardly falls with the step, so a rule that only held
        or shrank the step after slow increments let it crawl at ``min_step`` for thousands of steps once a
        failure had cut it (measured on the random zoo); failures halve it."""
        s = self.settings
        if iterations <= s.desired_iterations:
            factor = 1.5
        elif iterations <= 0.5 * s.max_iter:
            factor = 1.2
        elif iterations <= 0.75 * s.max_iter:
            factor = 1.0
        else:
            factor = 0.7
        self.step = self.scale * min(
            s.max_step, max(s.min_step, factor * max(last_step, self.step) / self.scale)
        )

    def _crawling(self) -> bool:
        """The rate-independent path advances, but too slowly to be worth following: of the last
        ``CRAWL_WINDOW`` attempts at least a third failed and together they gained less than one first step.
        Measured on chapter 11's foundation at h = 0.125 m: from lambda = 0.75 to 0.96 the path took 75
        increments and 50 cuts (each a stalled full-Newton run, 5 s) before it reached ``min_step``; the
        viscous path then went to lambda = 1 and relaxed in 16 increments."""
        recent = self.advances
        return (
            len(recent) == CRAWL_WINDOW
            and recent.count(0.0) >= CRAWL_WINDOW // 3
            and sum(recent) < self.settings.first_step * self.scale
        )

    def _current_stiffness(self) -> float:
        """The path's current stiffness parameter (nan before two committed steps)."""
        return self.result.stiffness[-1] if self.result.n_steps >= 2 else np.nan

    def _at_limit(self) -> bool:
        """The path has flattened: its current stiffness is below ``collapse_stiffness``. A crawl there goes
        on down to ``min_step`` before the limit is declared, as without the crawl test: the limit is then
        the highest load the path reached (measured on the random zoo: declared at the crawl instead, three
        limits came out 0.4-1.4 % lower)."""
        stiff = self._current_stiffness()
        return bool(np.isfinite(stiff) and stiff < self.settings.collapse_stiffness)

    def _can_go_viscous(self) -> bool:
        return self.settings.viscous_fallback and self.tau == 0.0 and _has_viscosity(self.model)

    def _stuck(self, outcome, lam_next, crawling=False) -> bool:
        """The path cannot advance (or, ``crawling``, hardly). A limit load if it had stopped rising (returns
        False: the path ends); else, once, the viscous fallback (returns True: go on viscous); else
        NonConvergence. A viscous path that a crawl started and that is stuck in its turn goes back to where
        it started and follows the rate-independent law down to ``min_step``, as without the crawl test: the
        viscosity regularises the soil and the contact, not a cracking strip (measured: chapter 11's
        foundation at h = 0.25 m with full Newton crawled to lambda = 1 that way, its viscous path stopped at
        0.86 on the strip)."""
        res = self.result
        stiff = self._current_stiffness()
        if self._at_limit():
            if self.tau > 0.0:
                relax(self)  # a viscous state must first relax to a rate-independent one (raises if not)
            res.status, res.limit_load_factor = LIMIT_LOAD, float(self.lam)
            return False
        if self._can_go_viscous():
            # the rate-independent increment may have no solution near the state (non-associated flow):
            # a viscous path has one; the end of the path is relaxed back to the rate-independent law
            self.crawl_start = self.save() if crawling else None
            self.tau = VISCOUS_FALLBACK_TAU
            _set_viscosity(self.model, self.tau)
            res.viscous_from = res.n_steps
            self.bar.note(f"viscous fallback from lambda={self.lam:.6g}")
            return True
        if self.crawl_start is not None:
            self.bar.note(f"viscous path stuck at lambda={self.lam:.6g}: back to the crawl's start")
            self.restore(self.crawl_start)
            self.crawl_start, self.crawl_may_go_viscous = None, False
            self.tau = 0.0
            _set_viscosity(self.model, self.tau)
            res.viscous_from = None
            return True
        report = _failure_report(self.model, self.system.free, outcome, self.lam, lam_next)
        report["current_stiffness"] = float(stiff)
        if res.viscous_from is not None:
            report["viscous_from_step"] = res.viscous_from
        res.status = STOPPED
        raise NonConvergence(report, res)


VISCOUS_FALLBACK_TAU = 1.0  # tau of the viscous fallback: the value chapter 10's psi = 0 study uses


class _LoadMeasure:
    """Scalar load P and loaded displacement delta of each step, for the current stiffness parameter
    S_k = (dP/d delta)_k / (dP/d delta)_1 (Bergan's idea, measured on the loaded DOFs only).

    Load control: P = lambda |f_ref|, delta = u . f_ref / |f_ref|. Displacement control (no force load):
    P = the reaction along the prescribed displacements, delta = their displacement along the same vector."""

    def __init__(self, system, f_ref, result):
        self.result = result
        if np.any(f_ref[system.free]):
            self.direction = f_ref / np.linalg.norm(f_ref)
            self.force_controlled = True
        else:
            ref = np.zeros(system.model.n_dof)
            ref[system.cons_dofs] = system.cons_ref
            norm = np.linalg.norm(ref)
            self.direction = ref / norm if norm > 0.0 else ref
            self.force_controlled = False
        self.first = None

    def point(self, k):
        r = self.result
        delta = float((r.u[k] - r.u_origin) @ self.direction)
        if self.force_controlled:
            return r.load_factor[k], delta
        return float((r.f_int[k] - r.f_int_origin) @ self.direction), delta

    def stiffness(self):
        """Current stiffness parameter of the last step (nan when it is not defined)."""
        k = self.result.n_steps
        (p1, d1), (p0, d0) = self.point(k), self.point(k - 1)
        if d1 == d0:
            return np.nan
        slope = (p1 - p0) / (d1 - d0)
        if self.first is None:
            self.first = slope if slope != 0.0 else np.nan
            return 1.0
        return float(slope / self.first)


def _start(model, settings, start=None, loads=None):
    """Assembly machinery, loads, the initial state recorded as step 0, and the one factorisation of K0."""
    system = System(model)
    f_ref, f_dead = model.load_vectors() if loads is None else (np.asarray(v, np.float64) for v in loads)
    if f_ref.shape != (model.n_dof,) or f_dead.shape != (model.n_dof,):
        raise ValueError(f"loads must be two vectors of length n_dof = {model.n_dof}")
    if start is None:
        u, states = system.start(0.0)
    else:
        if start.model is not model:
            raise ValueError("start must be a Result of the same model")
        states, u = start.final_state, start.u[-1].copy()
    f_int0, _, _ = system.evaluate(u, np.zeros_like(u), states, None)
    result = Result(model=model, f_ref=f_ref, f_dead=f_dead)
    if start is None:
        result.u_origin, result.f_int_origin = u.copy(), f_int0.copy()
    else:
        result.u_origin, result.f_int_origin = start.u_origin, start.f_int_origin
    _record(result, 0.0, u, f_int0, states, 0, [], [], settings)
    result.stiffness.append(np.nan)
    fac_k0 = system.factorize_k0(settings.backend)
    result.factorizations = 1
    return system, f_ref, f_dead, states, u, result, fac_k0


def _record(result, lam, u, f_int, states, iterations, residuals, energies, settings, viscosity=0.0):
    result.load_factor.append(lam)
    result.step_viscosity.append(float(viscosity))
    result.u.append(u.copy())
    result.f_int.append(f_int.copy())
    if settings.keep_states or not result.states:
        result.states.append(states)
    else:
        result.states[-1] = states
    result.iterations.append(iterations)
    result.residuals.append(list(residuals))
    result.energies.append(list(energies))


def _norm(x) -> float:
    """Euclidean norm of a 1-D float array: what np.linalg.norm computes (sqrt of BLAS ddot), bit for bit,
    without its ~3 us of dispatch (the solver takes several per iteration: 1.06 M in the random zoo)."""
    return math.sqrt(x.dot(x))


def _force_scale(settings, lam, f_ref, f_ext, f_int, result):
    """The force the residual is compared with. "structural": the structural load -- the applied reference
    load and the change of internal force (reactions included) since the geostatic state -- so that a large
    geostatic state cannot hide it; "total": max(|F_ext|, |F_int|), geostatic forces included."""
    if settings.convergence_reference == "total":
        return max(_norm(f_ext), _norm(f_int), 1e-30)
    structural = max(abs(lam) * _norm(f_ref), _norm(f_int - result.f_int_origin))
    return max(structural, 1e-7 * _norm(f_int), 1e-30)  # floor: round-off of the geostatic balance


def _increment(system, settings, fac_k0, u_conv, states, lam, f_ref, f_dead, result, method):
    """Iterate one increment from the committed (u_conv, states) to load factor ``lam`` with ``method``
    (the settings' own, or its fallback: then ``settings.fallback_iter`` iterations at most)."""
    free = system.free
    f_ext = lam * f_ref + f_dead
    use_k0 = method != "full"
    fallback = method != settings.method
    max_iter = min(settings.fallback_iter, _MAX_ITER[method]) if fallback else settings.max_iter
    line_search = settings.line_search or (fallback and method == "full")
    residuals, energies = [], []
    energy0 = r_first = None
    bfgs = _Lbfgs(fac_k0, settings.bfgs_memory) if method == "bfgs" else None
    outcome = {"converged": False, "residuals": residuals, "energies": energies, "iterations": 0}
    u = system.apply_constraints(u_conv.copy(), lam)
    evaluated = _evaluate(system, u, u_conv, states, use_k0, f_ext)
    trial_prev = None
    for it in range(1, max_iter + 1):
        if evaluated is None:
            outcome.update(reason="material update failed", iterations=it)
            return outcome
        f_int, k_list, trial, r = evaluated
        r_f = r[free]
        rel = _norm(r_f) / _force_scale(settings, lam, f_ref, f_ext, f_int, result)
        residuals.append(rel)
        outcome.update(iterations=it, residual=r, u=u, trial=trial, trial_prev=trial_prev)
        if not np.isfinite(rel):
            outcome.update(reason="residual is not finite")
            return outcome
        r_first = rel if r_first is None else r_first
        if it > 1 and rel > settings.divergence_ratio * max(r_first, settings.force_tol):
            outcome.update(reason=f"residual grew by more than {settings.divergence_ratio:g}")
            return outcome
        if bfgs is not None and _stagnates(residuals):
            outcome.update(reason="residual stagnates (no decrease over the last 15 iterations)")
            return outcome
        if bfgs is not None:
            du = bfgs.direction(r_f)
        else:
            du = None if use_k0 else _tangent_solve(system, settings, k_list, r_f, result)
            if du is None:  # modified Newton, or a tangent that cannot be factorised: K0 for the rest of the
                use_k0 = True  # increment (retrying a singular tangent every iteration measured slower)
                du = fac_k0.solve(r_f)
        energy = abs(float(du @ r_f))
        energy0 = energy if energy0 is None else energy0
        rel_energy = energy / _energy_scale(energy0, u, f_int, result, settings)
        energies.append(rel_energy)
        if _converged(rel, rel_energy, it, settings) or rel <= 1e-14 * settings.force_tol or energy == 0.0:
            outcome.update(converged=True, u=u, f_int=f_int, states=trial)
            return outcome
        trial_prev = trial
        if bfgs is not None:
            u_new, evaluated, step = _line_search_bfgs(system, u, du, r_f, u_conv, states, f_ext, line_search)
            if evaluated is not None:
                bfgs.update(step * du, r_f - evaluated[3][free])
        else:
            u_new, evaluated = _advance(
                system, settings, u, du, u_conv, states, use_k0, f_ext, _norm(r_f), line_search
            )
        u = u_new
    outcome.update(
        reason=f"no convergence in {max_iter} iterations" + (f" (fallback: {method})" if fallback else "")
    )
    return outcome


def _stagnates(residuals, window=30):
    return len(residuals) > window and min(residuals[-window // 2 :]) > 0.9 * min(
        residuals[-window : -window // 2]
    )


class _Lbfgs:
    """Inverse-Hessian approximation H ~ K_T^-1 built on the one K0 factorisation (Matthies & Strang 1979;
    the two-loop recursion of Nocedal 1980): H_0 = K0^-1, updated with the pairs (s, y) of the increment's
    iterations, s = the displacement step taken and y = the change of internal force it caused.

    A pair with y . s <= 0 (the path softens or the non-associated tangent is not positive along s) would
    make H indefinite: the memory is cleared and the next direction is the plain K0 one."""

    def __init__(self, fac_k0, memory):
        self.fac, self.memory = fac_k0, memory
        self.s_rows = self.y_rows = None  # (memory, n) ring buffers, allocated at the first pair kept
        self.rho = np.empty(memory)
        self.alphas = np.empty(memory)
        self.head = self.count = 0  # next row to write; pairs kept

    def direction(self, r):
        q = r.copy()
        if self.count:
            lbfgs_first_loop(self.s_rows, self.y_rows, self.rho, self.head, self.count, q, self.alphas)
        z = self.fac.solve(q)
        if self.count:
            lbfgs_second_loop(self.s_rows, self.y_rows, self.rho, self.head, self.count, z, self.alphas)
        return z

    def update(self, s, y):
        sy = float(s @ y)
        if not sy > 1e-12 * _norm(s) * _norm(y):
            self.count = 0
            return
        if self.memory == 0:
            return
        if self.s_rows is None:  # np.empty: rows not yet written cost no memory
            self.s_rows, self.y_rows = np.empty((self.memory, s.size)), np.empty((self.memory, s.size))
        self.s_rows[self.head] = s
        self.y_rows[self.head] = y
        self.rho[self.head] = 1.0 / sy
        self.head = (self.head + 1) % self.memory
        self.count = min(self.count + 1, self.memory)


LINE_SEARCH_TOL = 0.5  # accept a step s once |du . r(s)| <= LINE_SEARCH_TOL |du . r(0)|
LINE_SEARCH_MAX = 4  # extra residual evaluations per iteration at most
LINE_SEARCH_RANGE = (0.05, 4.0)


def _line_search_bfgs(system, u, du, r_f, u_conv, states, f_ext, line_search):
    """Step s along du such that the residual is nearly orthogonal to du (Matthies & Strang's line search:
    G(s) = du . r(u + s du) -> 0), by regula falsi once a sign change brackets the root, extrapolation
    before. Returns (u_new, evaluated, s)."""
    free = system.free
    g0 = float(du @ r_f)

    def trial(s):
        u_new = u.copy()
        u_new[free] += s * du
        ev = _evaluate(system, u_new, u_conv, states, True, f_ext)
        return u_new, ev, (np.inf if ev is None else float(du @ ev[3][free]))

    s_lo, g_lo = 0.0, g0
    s_hi = 1.0
    u_new, ev, g_hi = trial(s_hi)
    if not line_search or g0 <= 0.0:
        return u_new, ev, s_hi
    for _ in range(LINE_SEARCH_MAX):
        if ev is not None and abs(g_hi) <= LINE_SEARCH_TOL * g0:
            break
        if ev is None or not np.isfinite(g_hi):
            s_new = 0.5 * (s_lo + s_hi)
        elif g_hi < 0.0:  # bracketed between s_lo (G > 0) and s_hi (G < 0): regula falsi
            s_new = s_hi - g_hi * (s_hi - s_lo) / (g_hi - g_lo)
        else:  # still descending: secant extrapolation, at most doubling
            s_new = (
                min(2.0 * s_hi, s_hi - g_hi * (s_hi - s_lo) / (g_hi - g_lo)) if g_hi < g_lo else 2.0 * s_hi
            )
        s_new = min(max(s_new, LINE_SEARCH_RANGE[0]), LINE_SEARCH_RANGE[1])
        if s_new == s_hi:
            break
        cand = trial(s_new)
        if cand[1] is None:
            s_hi = s_new
            continue
        if g_hi > 0.0 and ev is not None and s_new > s_hi:
            s_lo, g_lo = s_hi, g_hi
        elif cand[2] > 0.0:
            s_lo, g_lo = s_new, cand[2]
        u_new, ev, g_hi = cand
        s_hi = s_new
    return u_new, ev, s_hi


def _evaluate(system, u, u_conv, states, use_k0, f_ext):
    """(f_int, element matrices, trial states, residual) at ``u``, or None if a material update failed."""
    try:
        f_int, k_list, trial = system.evaluate(u, u - u_conv, states, None if use_k0 else CONSISTENT)
    except FloatingPointError:
        return None
    return f_int, k_list, trial, f_ext - f_int


TANGENT_SOLVE_TOL = 1e-6  # |K_T du - r| / |r| above this: the factorisation of K_T is not to be trusted


def _tangent_solve(system, settings, k_list, r_f, result):
    """Newton correction with the consistent tangent, or None if the tangent cannot be factorised.

    The correction is checked against the tangent (one sparse product): on a nearly singular tangent
    (a plastic hinge, a fully softened band) SuperLU can return finite garbage after BLAS refused a call
    ("On entry to DTRSV parameter number 6 had an illegal value"), and Newton would then wander."""
    try:
        kt = system.pattern.matrix(system.pattern.assemble(k_list))
        du = Factorization(kt, symmetric=settings.symmetric_tangent, backend=settings.backend).solve(r_f)
    except (FloatingPointError, RuntimeError):
        return None
    result.factorizations += 1
    if _norm(kt @ du - r_f) > TANGENT_SOLVE_TOL * _norm(r_f):
        return None
    return du


def _advance(system, settings, u, du, u_conv, states, use_k0, f_ext, r_norm, line_search):
    """u + s du with s = 1, or, with the line search in full Newton, the first s = 1, 1/2, ... whose residual
    norm is below ``r_norm`` (a full step near a corner of the yield surface can overshoot far).

    The full step is evaluated with its consistent tangent, which it needs if it is taken; a shortened step
    is evaluated for its forces only and, once taken, again with its tangent. The path is the same with
    fewer tangent evaluations: on chapter 11's foundation at h = 0.125 m, 354 of the 420 full-Newton
    iterations shortened the step (1 774 shortened trials), and a tangent evaluation costs 1.7x a
    forces-only one."""
    free = system.free
    step = 1.0
    while True:
        u_new = u.copy()
        u_new[free] += step * du
        forces_only = use_k0 or step < 1.0
        evaluated = _evaluate(system, u_new, u_conv, states, forces_only, f_ext)
        taken = use_k0 or not line_search or step <= settings.line_search_min
        if taken or (evaluated is not None and _norm(evaluated[3][free]) < r_norm):
            if forces_only and not use_k0 and evaluated is not None:
                evaluated = _evaluate(system, u_new, u_conv, states, False, f_ext)
            return u_new, evaluated
        step *= 0.5


def _energy_scale(energy_first, u, f_int, result, settings):
    """Reference of the energy norm: the first iteration's |du . r|, or the work of the structural load
    |(u - u_0) . (F_int - F_int,0)| if larger -- a cut step's tiny first iteration must not make the test
    ever stricter. ``convergence_reference="total"``: the old reference |u . F_int|, geostatic forces
    included."""
    if settings.convergence_reference == "total":
        return max(energy_first, abs(float(u @ f_int)), 1e-300)
    work = abs(float((u - result.u_origin) @ (f_int - result.f_int_origin)))
    return max(energy_first, work, 1e-300)


def _converged(rel_force, rel_energy, iteration, settings):
    """Both norms small; or the force norm far below its tolerance (the energy ratio of a step that starts
    almost converged is meaningless)."""
    return rel_force <= settings.force_tol and (
        rel_energy <= settings.energy_tol or (iteration > 1 and rel_force <= 1e-3 * settings.force_tol)
    )


GROUP_ACTIVITY = {"interface": ("stick", "slip", "open"), "soil_q8": ("elastic", "plastic")}


def _point_codes(group, state):
    """Per-point state codes of a group (interface: stick/slip/open; soil: elastic/plastic), or None."""
    status = getattr(group, "status", None)
    if callable(status):
        return np.asarray(status(state)).ravel(), GROUP_ACTIVITY["interface"]
    if group.name == "soil_q8":
        from ..elements.soil_q8 import N_STRESS

        return (state[..., N_STRESS + 1] > 0).astype(int).ravel(), GROUP_ACTIVITY["soil_q8"]
    return None


def _activity(model, outcome, worst_dof):
    """Which groups hold the worst DOF, and how many of their points changed state between the last two
    iterates (e.g. contact points flipping between slip and open)."""
    lines = []
    trial, prev = outcome.get("trial"), outcome.get("trial_prev")
    for g, i in zip(model.groups, range(len(model.groups))):
        if worst_dof not in g.edofs:
            continue
        text = g.name
        if trial is not None and prev is not None:
            now, before = _point_codes(g, trial[i]), _point_codes(g, prev[i])
            if now is not None:
                flipped = now[0] != before[0]
                if flipped.any():
                    names = now[1]
                    pairs = {f"{names[a]}->{names[b]}" for a, b in zip(before[0][flipped], now[0][flipped])}
                    text += f" ({int(flipped.sum())} points flipping: {', '.join(sorted(pairs))})"
        lines.append(text)
    return "; ".join(lines)


def _failure_report(model, free, outcome, lam_from, lam_to):
    report = {
        "reason": outcome.get("reason", "unknown"),
        "load_factor_from": float(lam_from),
        "load_factor_to": float(lam_to),
        "iterations": outcome.get("iterations", 0),
    }
    r = outcome.get("residual")
    if r is not None and np.any(np.isfinite(r[free])):
        r_free = np.where(free, np.abs(np.nan_to_num(r, nan=np.inf)), 0.0)
        worst = int(np.argmax(r_free))
        start = np.concatenate([[0], np.cumsum(model.node_ndof)])
        node = int(np.searchsorted(start, worst, side="right") - 1)
        report.update(
            worst_dof=worst,
            worst_node=node,
            worst_component=("u", "w", "alpha")[worst - start[node]],
            node_xy=tuple(float(v) for v in model.coords[node]),
            worst_groups=_activity(model, outcome, worst),
            last_residual=float(outcome["residuals"][-1]) if outcome["residuals"] else float("nan"),
        )
    return report


def run_arc_length(
    model: Model,
    n_steps: int,
    first_increment: float,
    settings: Settings | None = None,
    max_load_factor: float = np.inf,
    min_arc_ratio: float = 1e-4,
) -> Result:
    """Follow the equilibrium path through limit points with Crisfield's cylindrical arc-length method.

    The load factor becomes an unknown; every iteration keeps the displacement increment of the step on a
    circle of radius ``arc`` (||du_step|| = arc), chosen so that the first step's predictor has load-factor
    increment ``first_increment``. With ``method="modified"`` both K0 solves (for the reference load and for
    the residual) reuse the one factorisation of K0. The sign of each predictor follows the previous step's
    direction, so the path turns over a limit point instead of stalling there. A step whose constraint has no
    real root, or that does not converge, is retried with half the arc (down to ``min_arc_ratio`` of the
    first).

    Only force loads (``Model.add_load``) are scaled; prescribed displacements are not supported here (use
    :func:`run`, i.e. displacement control, for those). Stops after ``n_steps`` steps or once the load factor
    passes ``max_load_factor``.
    """
    settings = settings or Settings()
    model.check()
    if np.any(model.constrained()[2] != 0.0):
        raise ValueError("run_arc_length scales force loads only: the model has prescribed displacements")
    if int(n_steps) < 1 or not first_increment > 0.0:
        raise ValueError("n_steps must be >= 1 and first_increment > 0")
    t_start = time.perf_counter()
    system, f_ref, f_dead, states, u, result, fac = _start(model, settings)
    free = system.free
    if not np.any(f_ref[free]):
        raise ValueError("run_arc_length needs a reference load on free DOFs (Model.add_load)")
    du_ref = fac.solve(f_ref[free])
    arc0 = first_increment * np.linalg.norm(du_ref)
    arc, lam, direction = arc0, 0.0, None
    while result.n_steps < n_steps and lam < max_load_factor:
        outcome = _arc_step(
            system, settings, fac, du_ref, u, states, lam, arc, direction, f_ref, f_dead, result
        )
        if not outcome["converged"]:
            arc *= 0.5
            result.cuts += 1
            if arc < min_arc_ratio * arc0:
                result.wall_time = time.perf_counter() - t_start
                raise NonConvergence(_failure_report(model, free, outcome, lam, lam), result)
            continue
        direction = outcome["u"][free] - u[free]
        u, states, lam = outcome["u"], outcome["states"], outcome["lam"]
        _record(
            result,
            lam,
            u,
            outcome["f_int"],
            states,
            outcome["iterations"],
            outcome["residuals"],
            outcome["energies"],
            settings,
            _viscosity_in_force(model),
        )
        result.stiffness.append(np.nan)
        if settings.verbose:
            print(
                f"arc step {result.n_steps:4d}  lambda={lam:.6g}  iterations={outcome['iterations']:3d}",
                flush=True,
            )
        if outcome["iterations"] <= 0.25 * settings.max_iter:
            arc = min(2.0 * arc, arc0)  # regrow after cuts while convergence is easy
    result.wall_time = time.perf_counter() - t_start
    return result


def _arc_step(system, settings, fac, du_ref, u_conv, states, lam_conv, arc, direction, f_ref, f_dead, result):
    free = system.free
    sign = 1.0 if direction is None or direction @ du_ref >= 0.0 else -1.0
    dlam = sign * arc / np.linalg.norm(du_ref)
    du_step = dlam * du_ref
    residuals, energies = [], []
    outcome = {"converged": False, "residuals": residuals, "energies": energies, "iterations": 0}
    energy0 = None
    for it in range(1, settings.max_iter + 1):
        u = u_conv.copy()
        u[free] += du_step
        lam = lam_conv + dlam
        try:
            f_int, _, trial = system.evaluate(u, u - u_conv, states, None)
        except FloatingPointError as err:
            outcome.update(reason=f"material update failed: {err}", iterations=it)
            return outcome
        r = lam * f_ref + f_dead - f_int
        rel = _norm(r[free]) / _force_scale(settings, lam, f_ref, lam * f_ref + f_dead, f_int, result)
        residuals.append(rel)
        outcome.update(iterations=it, residual=r, u=u)
        if not np.isfinite(rel):
            outcome.update(reason="residual is not finite")
            return outcome
        du_r = fac.solve(r[free])
        energy = abs(float(du_r @ r[free]))
        energy0 = energy if energy0 is None else energy0
        energies.append(energy / _energy_scale(energy0, u, f_int, result, settings))
        if it > 1 and _converged(rel, energies[-1], it, settings):
            outcome.update(converged=True, u=u, f_int=f_int, states=trial, lam=lam)
            return outcome
        # cylindrical constraint |du_step + du_r + d_lam du_ref| = arc, root closest to the current direction
        v = du_step + du_r
        a = du_ref @ du_ref
        b = 2.0 * (du_ref @ v)
        c = v @ v - arc * arc
        disc = b * b - 4.0 * a * c
        if disc < 0.0:
            outcome.update(reason="arc-length constraint has no real root")
            return outcome
        roots = ((-b + np.sqrt(disc)) / (2.0 * a), (-b - np.sqrt(disc)) / (2.0 * a))
        d_lam = max(roots, key=lambda s: (v + s * du_ref) @ du_step)
        du_step = v + d_lam * du_ref
        dlam += d_lam
    outcome.update(reason=f"no convergence in {settings.max_iter} iterations")
    return outcome
