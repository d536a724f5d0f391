"""Load control (``Settings(control="load")``): ``run`` follows the load factors from a start state, one
increment after another with the settings' method (``_Path``: automatic or fixed stepping, a failing
increment halved down to ``min_step`` or ``max_cuts`` times), and records each converged step with the
path's current stiffness (``_LoadMeasure``). An increment that cannot converge after its cuts is
:class:`NonConvergence`, never a limit load: a prescribed load factor cannot pass a peak of the path, so
where load control stops says nothing about the capacity. ``run`` hands ``control="work"`` to the
controlled path (:mod:`ssi.solver.path`).
"""

import time
from dataclasses import replace

import numpy as np
from numpy.typing import ArrayLike

from ..core.model import Model
from ..core.solution import STOPPED, Result
from .davis import davis_mode
from .diagnostics import _failure_report
from .increment import _increment
from .path import run_path
from .progress import SolverProgress, announce_compilation, log, solver_progress
from .record import _record, _start, _viscosity_in_force
from .settings import NonConvergence, Settings


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

    ``settings.control == "work"`` (the default): the controlled path of :mod:`ssi.solver.path` (rising
    targets only).
    ``settings.flow == "davis"``: the run in Davis mode (:mod:`ssi.solver.davis`).

    ``settings.control == "load"``: load control (this module); the targets may rise and fall.

    Returns a :class:`Result` whose ``status`` says whether the targets were reached or (controlled path
    only) a limit load was found. Raises :class:`NonConvergence` if a step fails before either.
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
    path = _Path(model, settings, start, loads, scale=float(np.abs(targets).max()) or 1.0)
    try:
        with solver_progress(settings.progress, total=path.scale) as path.bar:
            for target in targets:
                path.follow(float(target))
    finally:
        path.result.wall_time = time.perf_counter() - t_start
    return path.result


class _Path:
    """The incremental-iterative state of one load-controlled run: committed (u, states, lambda), the step."""

    def __init__(self, model, settings, start, loads, scale=1.0):
        """``scale``: the largest target |lambda|; step sizes are fractions of it."""
        self.model, self.settings = model, settings
        self.system, self.f_ref, self.f_dead, self.states, self.u, self.result, self.fac_k0 = _start(
            model, settings, start, loads
        )
        self.lam = 0.0
        self.scale = scale
        self.bar = SolverProgress(None, 1.0)  # silent until run() opens the real one
        self.step = settings.first_step * scale
        self.measure = _LoadMeasure(self.system, self.f_ref, self.result)

    def follow(self, target):
        """Advance the committed state to ``target``; raises :class:`NonConvergence` if it cannot."""
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
                continue
            self.result.cuts += 1
            self.bar.note(f"step cut at lambda={lam_next:.6g}: {outcome.get('reason', '')}")
            self.step = 0.5 * abs(lam_next - self.lam)
            if self.step < s.min_step * self.scale * (1.0 - 1e-9):
                self._stuck(outcome, lam_next)

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
                self._stuck(outcome, lam_next)
            cuts_here += 1
            self.result.cuts += 1
            self.bar.note(f"step cut at lambda={lam_next:.6g}: {outcome.get('reason', '')}")
            pending.append(0.5 * (self.lam + lam_next))

    def _increment(self, lam_next):
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

    def _stuck(self, outcome, lam_next):
        """The increment to ``lam_next`` failed at the smallest step: :class:`NonConvergence`, with the
        path's current stiffness (load increment per loaded displacement relative to the first step's; nan
        before two steps). A small one means the path is flattening -- perhaps towards a limit load, which
        load control cannot pass -- and only the controlled path can tell."""
        res = self.result
        report = _failure_report(self.model, self.system.free, outcome, self.lam, lam_next)
        stiff = res.stiffness[-1] if res.n_steps >= 2 else np.nan
        report["current_stiffness"] = float(stiff)
        report["hint"] = (
            "load control cannot pass a limit point and never reports one: follow the path with "
            "Settings(control='work') (the default) to find out whether the load is above the capacity"
        )
        res.status = STOPPED
        raise NonConvergence(report, res)


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
