"""The load-path control: ``run`` follows the load factors from a start state, one increment after another
(``_Path``: snapshots, automatic and fixed stepping, step cuts, the crawl and stuck rules, the fallback
method and the viscous fallback), records each converged step, and detects a limit load (``_LoadMeasure``).
Moved here as it was: the path-following issue rewrites these rules.
"""

import time
from collections import deque
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike

from ..core.model import Model
from ..core.solution import LIMIT_LOAD, STOPPED, Result
from .davis import davis_mode
from .diagnostics import _failure_report
from .increment import _increment
from .path import run_path
from .progress import SolverProgress, announce_compilation, log, solver_progress
from .record import _record, _start
from .settings import NonConvergence, Settings
from .viscous import _has_viscosity, _set_viscosity, _viscosity_in_force, relax


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

    ``settings.control == "work"``: the controlled path of :mod:`ssi.solver.path` (rising targets only).
    ``settings.flow == "davis"``: the run in Davis mode (:mod:`ssi.solver.davis`).

    Returns a :class:`Result` whose ``status`` says whether the targets were reached or a limit load was
    detected. Raises :class:`NonConvergence` if an increment fails before either.
    """
    settings = settings or Settings()
    if settings.flow == "davis" and not settings.symmetric_tangent:
        settings = replace(settings, symmetric_tangent=True)  # associated laws: a symmetric tangent
    targets = np.atleast_1d(np.asarray(load_factors, np.float64))
    if targets.size == 0 or not np.all(np.isfinite(targets)):
        raise ValueError("load_factors must be a non-empty sequence of finite numbers")
    model.check()
    announce_compilation()
    with davis_mode(model, settings.flow == "davis"):
        if settings.control == "work":
            return run_path(model, targets, settings, start, loads)
        return _run_load_control(model, targets, settings, start, loads)


def _run_load_control(model, targets, settings, start, loads):
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
