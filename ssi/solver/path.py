"""Controlled path following (``Settings(control="work")``): a limit only where the path peaks.

Each step prescribes an increment ds of a control that keeps rising through a limit point, and the load
factor lambda is an unknown of the step:

* force loads: the work of the reference load, s = f_ref . (u - u_0) (indirect displacement control); the
  load measure P whose peak is the limit is lambda;
* prescribed displacements and no force load: s = lambda (displacement control, monotone by itself); P is
  the reaction along the prescribed displacements.

One corrector (:mod:`.path_corrector`): Newton on a lagged factorisation of the consistent tangent,
refactorised only when the observed contraction |r_k| / |r_k-1| stays above ``poor_contraction`` for
``poor_run`` iterations (a new factor that does not solve its own matrix to ``TANGENT_SOLVE_TOL`` is not
used), L-BFGS updates on that factor, and a line search; no retry ladder. A symmetric tangent (associated or
Davis-mode soil, ``Settings.symmetric_tangent``) starts the path, and each step after a failed one, on K0 and
searches along Matthies & Strang's G, the slope of the increment's potential; an unsymmetric one (slipping
contact, non-associated soil) factorises the tangent of the committed state there instead and backtracks on
the residual norm, along G only where no step lowers it. With work control each iteration solves the bordered
system by two solves with that operator H ~ K^-1: a = H r, b = H f_ref, d lambda = -(f_ref . a) / (f_ref . b),
du = a + d lambda b, which keeps f_ref . du = 0 after a predictor that meets the constraint exactly (the
previous step scaled, or the tangent b at the first step). A step to a prescribed lambda without a previous
step starts from the committed tangent's linear response to it, prescribed displacements included
(``_prescribed_predictor``).

The pieces, FElupe-style: ``_Follower`` (here) holds the committed path, the step rule and one step's
iterations; it takes its corrector (:class:`.path_corrector._Corrector`: factorisation and line search), its
limit watch (:class:`.path_limit._LimitWatch`: the WATCH rows, the redo, the checks) and its relaxation
(:class:`.path_relax._Relaxing`, iterating with the injected ``relax``, :func:`.relax.relax`) from sibling
modules, and every tunable from ``policy`` (:class:`.policy.PathPolicy`; default ``POLICY``). The control
flow in one diagram: ``ssi/solver/README.md``; why each rule is as it is: ``docs/solver/decisions.md``.

State table (one row per transition; a "step" is one control increment ds; ITER one iteration of a step)::

    state  | event                                    | action                              | next
    -------+------------------------------------------+-------------------------------------+-------
    START  | no reference load, no prescribed         | one load-controlled step to the     | end
           |   displacement (dead load only)          |   last target (NonConvergence if it |
           |                                          |   fails: lambda scales nothing)     |
    START  | residual above the tolerance             | load-controlled step at lambda_0    | FIRST
    START  | balanced                                 | --                                  | FIRST
    FIRST  | --                                       | load-controlled step to             | WATCH
           |                                          |   lambda_0 + ds / (f_ref K0^-1 f_ref)|
    STEP   | secant predictor passes the target       | load-controlled step to the target  | FINAL
    STEP   | converged, lambda below the target       | commit; ds <- ds clip(sqrt(N*/N),   | WATCH
           |                                          |   growth) within [ds_min, ds_max]   |
    STEP   | converged, lambda passes the target      | redo as one load-controlled step    | FINAL
           |                                          |   to the target                     |
    START  | every law associated (``associated``)   | run as with symmetric_tangent=True  | (same)
    ITER   | contraction above poor_contraction for   | refactorise the tangent at the      | ITER
           |   poor_run iterations; or a step's first |   iterate (secant_rule picks the    |
           |   iterate on K0 with an unsymmetric one  |   flag); the old factor kept if the |
           |                                          |   new one misses its own solve      |
    ITER   | unsymmetric factor                       | backtrack t = 1, 1/2, ... down to   | ITER
           |                                          |   line_search_min on |r|; none      |
           |                                          |   lowers it: G's root if |r| grows  |
           |                                          |   < g_growth x, else least |r|      |
    ITER   | symmetric tangent, or K0                 | G's root (secant / regula falsi in  | ITER
           |                                          |   [0.05, 4])                        |
    ITER   | force and energy tests met               | the step converged                  | STEP
    ITER   | |r| not finite, grew divergence_ratio x, | the step failed; the next starts    | STEP
           |   stagnates, max_iter, or the load-      |   from K0                           |
           |   factor correction beyond its cap       |                                     |
    any    | a symmetric tangent's factor does not    | iterate on K_t + singular_shift     | (same)
           |   solve its own matrix (singular K_t)    |   diag(K0) (_regularised)           |
    any    | symmetric: the line search overshoots    | regula falsi on G below t = 0.05    | (same)
           |   (G(t) < 0, |r| grew)                   |   (_overshoot)                      |
    any    | not converged                            | ds <- ds / 2; next step from K0     | STEP
    any    | not converged, ds < ds_min               | RELAX: damped dynamics on K0 at a   | WATCH
           |                                          |   prescribed lambda (_relax,        |
           |                                          |   _dynamic); ds <- ds_min           |
    RELAX  | no load increment converges              | NonConvergence (diagnosis: groups,  | end
           |                                          |   points changing state, lambda, s) |
    FINAL  | converged                                | commit (ds kept)                    | WATCH,
           |                                          |                                     | next
           |                                          |                                     | target
    WATCH  | P below (1 - plateau_rise) P_max, for    | the steps around the peak redone    | LIMIT
           |   fall_steps steps or a continuation     |   at half size: uncertainty;        |
           |   as below                               |   checks: limit_suspect             |
    WATCH  | P within plateau_rise of P_max since the | as above                            | LIMIT
           |   control was s_p, and s - s_p >=        |                                     |
           |   plateau_control s_p over >=           |                                     |
           |   plateau_steps steps                    |                                     |
    WATCH  | (either above) after a relaxed step      | damped dynamics to (1 + 2           | STEP
           |                                          |   plateau_rise) x the peak (_above):|
           |                                          |   converged -> committed, no limit  |
    WATCH  | the peak is a relaxed state              | NonConvergence, never a limit       | end
    WATCH  | otherwise                                | --                                  | STEP

ds_max is ``max_step`` of the elastic work at the largest target, or of the work done so far if larger
(a softened path's work grows faster than the elastic one). FIRST exists because from the start state a
contact that carries no load yet lets a work step follow a mechanism at lambda = 0 (a weightless strip
lifting off).

A failure to converge is never read as a limit. A limit is reported with ``limit_uncertainty``, the
mechanism certificate of its increment (``limit_mechanism``, ``limit_stored_share``:
:mod:`ssi.solver.mechanism`) and, when a check fails, ``limit_suspect`` with the reason
(:func:`ssi.limit.flag_suspect` adds the limit-analysis bracket's verdict).

Where the corrector stalls at the smallest step: past a bifurcation of the non-associated soil the equilibrium
it sits on is a saddle (the tangent has a negative eigenvalue), and the step is found at a prescribed load
factor by damped dynamics on K0 (:mod:`ssi.solver.relax`), which leave the saddle and settle on a stable
equilibrium, accepted by the same tests as any step; the result then says the state is one of several
(``Result.relaxed_note``). A peak at such a state is never a limit. Why a corrector stalls there: perfectly
plastic Mohr-Coulomb flow with psi < phi has lost ellipticity wherever it yields (Rudnicki & Rice 1975;
:mod:`ssi.materials.mc_localisation`), so the rate problem at the plastic front has no unique solution; a
``NonConvergence`` there names the materials and their ratios (report key ``ill_posed``,
:func:`.diagnostics.ill_posed_soil`). What was measured: docs/solver/decisions.md (#relax,
#no-limit-from-a-relaxed-state, #stops-before-relax).
"""

from __future__ import annotations

import math
import time
from collections import deque
from dataclasses import replace

import numpy as np

from ..core.assembly import scatter_vector
from ..core.model import Model
from ..core.protocol import CONSISTENT
from ..core.solution import STOPPED, Result
from .diagnostics import _failure_report
from .increment import _converged, _energy_scale, _force_scale, _Lbfgs, _norm, _stagnates, cracking_strip
from .path_corrector import _Corrector
from .path_limit import _LimitWatch
from .path_relax import _Relaxing
from .policy import PATH_POLICY, PathPolicy
from .progress import SolverProgress, solver_progress
from .record import _record, _start
from .relax import relax
from .settings import NonConvergence, Settings

POLICY = PATH_POLICY  # the policy run_path uses when given none (a study may set path.POLICY for a block)


def run_path(
    model: Model,
    targets: np.ndarray,
    settings: Settings,
    start: Result | None,
    loads: tuple | None,
    policy: PathPolicy | None = None,
) -> Result:
    """The controlled path through the rising ``targets`` (load factors); see the module docstring. Called by
    :func:`ssi.solver.run` when ``settings.control == "work"``; ``policy`` None: the module's ``POLICY``. The
    relaxation where the corrector stalls is this module's ``relax``, passed to the follower (injected)."""
    if np.any(np.diff(np.concatenate([[0.0], targets])) <= 0.0):
        raise ValueError(f"control='work' needs rising positive load_factors, got {targets.tolist()}")
    t0 = time.perf_counter()
    if not settings.symmetric_tangent and associated(model):
        settings = replace(settings, symmetric_tangent=True)
    policy = POLICY if policy is None else policy
    path = _Follower(model, settings, start, loads, float(targets[-1]), policy, relax)
    try:
        with solver_progress(settings.progress, total=path.scale) as path.bar:
            if path.dead_only:
                path.balance(float(targets[-1]))
            else:
                path.equilibrate()
                for target in targets:
                    if path.follow(float(target)):
                        break
    finally:
        path.result.wall_time = time.perf_counter() - t0
    return path.result


def associated(model: Model) -> bool:
    """True if every group of the model says its consistent tangent is symmetric
    (``ElementGroup.symmetric_tangent``: Mohr-Coulomb soil with psi = phi, elastic and von Mises soil,
    Coulomb contact with psi = phi, plates of elastic layers only, springs; a group that does not say so
    makes it False). The path then runs as with ``Settings.symmetric_tangent`` (each step starts on K0, the
    line search follows the potential's slope G, a singular tangent is factorised shifted), as in Davis mode:
    the increment is a convex problem (docs/solver/decisions.md#associated-path)."""
    return all(g.symmetric_tangent() for g in model.groups)


class _Follower(_Corrector, _LimitWatch, _Relaxing):
    """The committed path (u, states, lambda, control s), the step rule and one step's iterations of one
    controlled run; the corrector, the limit watch and the relaxation are its sibling modules' mixins, the
    tunables ``policy`` and the relaxation's iteration ``relax`` (:func:`.relax.relax`'s signature) are
    passed in."""

    def __init__(
        self,
        model: Model,
        settings: Settings,
        start: Result | None,
        loads: tuple | None,
        scale: float,
        policy: PathPolicy = PATH_POLICY,
        relax=relax,
    ):
        self.model, self.settings, self.policy, self.relax = model, settings, policy, relax
        # the root's growth limit is for a cracking strip's kinks only (policy.g_growth)
        self.g_growth = self.policy.g_growth if cracking_strip(model) else np.inf
        self.system, self.f_ref, self.f_dead, self.states, self.u, self.result, k0 = _start(
            model, settings, start, loads
        )
        self.k0 = self.fac = k0  # K0 (SPD): the operator only until the first step factorises its tangent
        free = self.system.free
        self.f = self.f_ref[free]
        self.work = bool(np.any(self.f))  # work control; else displacement control on lambda
        ref = np.zeros(model.n_dof)
        ref[self.system.cons_dofs] = self.system.cons_ref
        # no reference load and no prescribed displacement (a phase of dead load only, e.g. a phased scene's
        # geostatic phase): lambda scales nothing, and the path is one balancing step (see balance)
        self.dead_only = not self.work and not np.any(ref)
        self.ref = ref
        self.lam = 0.0
        self.s = float(self.f @ (self.u[free] - self.result.u_origin[free])) if self.work else 0.0
        self.scale = scale
        self.bar = SolverProgress(None, 1.0)
        self.w1 = float(self.f @ k0.solve(self.f)) if self.work else 1.0  # elastic d s / d lambda
        unit = self.w1 * scale  # the control of lambda = scale on the elastic path
        self.started = False  # the first step is load-controlled (see follow)
        self.ds = settings.first_step * unit  # elastically: the work of the first load step
        self.ds_min, self.ds_max = settings.min_step * unit, settings.max_step * unit
        self.dlam_cap = settings.max_step * scale  # the largest load-factor correction of one iteration
        self.prev = None  # (du, dlam, ds) of the last committed step: the secant predictor
        self._k0_diag = None  # diag(K0) over the free DOFs, for a singular tangent (see _regularised)
        self.kept = deque(maxlen=self.policy.kept_steps)  # (k, u, states, lam, s, P)
        self.relaxed = {}  # step -> the corrector's failure that a relaxed step (_relax) replaced
        self.loads = [self._load_measure(self.u, self.result.f_int[0], 0.0)]
        self.controls = [self.s]
        self.kept.append((0, self.u, self.states, 0.0, self.s, self.loads[0]))

    # ----------------------------------------------------------------------------------------------------
    def equilibrate(self):
        """Bring the start state into equilibrium at its own load factor first, under load control, when it
        is not (e.g. dead load added to a geostatic state): the controlled steps then carry only the
        reference load (measured: 8 of the random zoo's scenes failed at lambda ~ 0 while one step had to
        balance both). Recorded as a step only if it moved; raises NonConvergence if it fails."""
        r = (self.lam * self.f_ref + self.f_dead - self.result.f_int[-1])[self.system.free]
        reference = _norm(self.f) * self.scale if self.work else _norm(self.result.f_int[-1])
        if _norm(r) <= self.settings.force_tol * reference:  # balanced (to the tolerance of the first
            return  # step's load; the geostatic round-off is not to be iterated on: zoo scenes 2, 3, 9)
        out = self._step(self.u, self.states, self.lam, None, self.lam)
        if out is None:
            self._fail()
        if out["iterations"] > 1:
            self._commit(out)
        self.prev = None  # the balancing move is no predictor for the controlled steps

    def balance(self, target):
        """Nothing scales with lambda (``dead_only``): one load-controlled step to ``target`` balances the
        dead load, recorded as step 1 (a phased scene's geostatic phase has exactly that row); raises
        NonConvergence if it fails -- a smaller lambda would not change the load, so there is nothing to
        halve."""
        out = self._step(self.u, self.states, self.lam, None, target)
        if out is None:
            self._fail()
        self._commit(out, adapt=False)

    def follow(self, target) -> bool:
        """Advance to ``target``; True if the path ended at a limit."""
        while self.lam < target * (1.0 - 1e-12):
            if not self.started:  # from the start state, whose contact may carry no load yet, a work step
                # can follow a mechanism at lambda = 0 (a weightless strip lifting off: zoo scene 24)
                lam_next = min(target, self.lam + self.ds / self.w1)
                out = self._step(self.u, self.states, self.lam, None, lam_next)
                self.started, final = out is not None, False
            elif self._predicted_lam(self.ds) > target:  # the secant predictor passes the target: the
                out = self._step(self.u, self.states, self.lam, None, target)  # step ends on it instead
                final = True
            else:
                out = self._step(self.u, self.states, self.lam, self.ds)
                final = out is not None and out["lam"] > target
                if final:
                    out = self._step(self.u, self.states, self.lam, None, target)
            if out is None:
                self.result.cuts += 1
                self.ds *= 0.5
                if self.ds < self.ds_min * (1.0 - 1e-9):
                    out = self._relax(target)  # the corrector stalled: a stable equilibrium at a fixed lambda
                    if out is None:
                        self._fail()
                    self.started = True
                    self._commit(out)
                    self.relaxed[self.result.n_steps] = self.last_failure
                    self.ds = self.ds_min  # the controlled steps start again from the smallest
                    if self._limit():
                        return True
                continue
            self._commit(out, adapt=not final)  # a step cut short by the target says nothing of the size
            if self._limit():
                return True
        return False

    def _predicted_lam(self, ds):
        """The load factor the secant predictor reaches with the control step ``ds`` (current lambda if
        there is no previous step to scale)."""
        if self.prev is None:
            return self.lam
        return self.lam + ds / self.prev[2] * self.prev[1]

    def _fail(self):
        out = self.last_failure
        report = _failure_report(self.model, self.system.free, out, self.lam, out.get("lam", self.lam))
        report.update(control_value=self.s, control_step=self.ds, control="work" if self.work else "lambda")
        soft = self._soft_mode(out)
        if soft:
            report.update(soft_mode=soft)
        self.result.status = STOPPED
        raise NonConvergence(report, self.result)

    def _commit(self, out, adapt=True):
        du = out["u"][self.system.free] - self.u[self.system.free]
        ds = out["s"] - self.s
        self.prev = (du, out["lam"] - self.lam, ds) if ds > 0.0 else None
        self.u, self.states, self.lam, self.s = out["u"], out["states"], out["lam"], out["s"]
        _record(
            self.result, self.lam, self.u, out["f_int"], self.states, out["iterations"], out["residuals"],
            out["energies"], self.settings,
        )  # fmt: skip
        self.result.stiffness.append(np.nan)
        self.loads.append(self._load_measure(self.u, out["f_int"], self.lam))
        self.controls.append(self.s)
        self.kept.append((self.result.n_steps, self.u, self.states, self.lam, self.s, self.loads[-1]))
        self.bar.update(self.result.n_steps, self.lam, out["iterations"], out["residuals"][-1])
        if not adapt:
            return
        n = max(out["iterations"], 1)
        grow = min(
            max(math.sqrt(self.settings.desired_iterations / n), self.policy.growth[0]), self.policy.growth[1]
        )
        # the largest step: max_step of the elastic work at the largest target, or of the work done so far
        # where the path has softened (else a soft path crawls: 427 steps on chapter 11's scene at h = 1/8)
        ds_max = max(self.ds_max, self.settings.max_step * abs(self.s - self.controls[0]))
        self.ds = min(max(grow * max(ds, self.ds_min), self.ds_min), ds_max)

    def _load_measure(self, u, f_int, lam):
        if self.work:
            return float(lam)
        return float((f_int - self.result.f_int_origin) @ self.ref)

    def _step(self, u_n, states_n, lam_n, ds, lam_target=None):
        """One step from a committed state: work control (``ds``) or, with ``lam_target`` (or displacement
        control), the load factor prescribed. Returns the converged step (dict) or None (kept in
        ``last_failure``)."""
        st, sy = self.settings, self.system
        free = sy.free
        fixed_lam = lam_target is not None or not self.work
        if fixed_lam and lam_target is None:  # displacement control: the control is lambda itself
            lam_target = lam_n + ds
        u = u_n.copy()
        if self.prev is not None:  # secant predictor: the last step scaled (meets the constraint exactly)
            du_p, dlam_p, ds_p = self.prev
            if fixed_lam:
                ratio = max((lam_target - lam_n) / dlam_p, 0.0) if dlam_p != 0.0 else 0.0
            else:
                ratio = ds / ds_p
            lam = lam_target if fixed_lam else lam_n + ratio * dlam_p
            u[free] += ratio * du_p
        elif fixed_lam:
            lam = lam_target
            u = self._prescribed_predictor(u_n, states_n, lam)
        else:  # tangent predictor: du = dlam H f_ref with f_ref . du = ds
            b = self.fac.solve(self.f)
            lam = lam_n + ds / float(self.f @ b)
            u[free] += (lam - lam_n) * b
        sy.apply_constraints(u, lam)
        bfgs = _Lbfgs(self.fac, st.bfgs_memory)
        residuals, energies = [], []
        out = {"converged": False, "residuals": residuals, "energies": energies, "iterations": 0, "lam": lam}
        ev = self._evaluate(u, u_n, states_n, lam)
        energy0 = trial_prev = None  # trial_prev: the last iterate's states, for the failure's diagnosis
        poor = 0
        for it in range(1, st.max_iter + 1):
            if ev is None:
                out.update(reason="material update failed", iterations=it)
                break
            f_int, trial, r = ev
            r_f = r[free]
            f_ext = lam * self.f_ref + self.f_dead
            rel = _norm(r_f) / _force_scale(st, lam, self.f_ref, f_ext, f_int, self.result)
            residuals.append(rel)
            out.update(iterations=it, residual=r, u=u, trial=trial, trial_prev=trial_prev, lam=lam)
            trial_prev = trial
            if not np.isfinite(rel):
                out.update(reason="residual is not finite")
                break
            if it > 1 and rel > st.divergence_ratio * max(residuals[0], st.force_tol):
                out.update(reason=f"residual grew by more than {st.divergence_ratio:g}")
                break
            if _stagnates(residuals):
                out.update(reason="residual stagnates (no decrease over the last 15 iterations)")
                break
            poor = poor + 1 if it > 1 and rel > self.policy.poor_contraction * residuals[-2] else 0
            # with an unsymmetric tangent a step that starts on K0 (the first, or the one after a failure)
            # factorises the consistent tangent of the committed state first (decisions.md#refactorisation)
            stale = poor >= self.policy.poor_run or (
                it == 1 and self.fac is self.k0 and not st.symmetric_tangent
            )
            if stale and self._refactor(u, u_n, states_n, self._tangent_flag(poor >= self.policy.poor_run)):
                bfgs, poor = _Lbfgs(self.fac, st.bfgs_memory), 0
            a = bfgs.direction(r_f)
            dlam = 0.0
            if not fixed_lam:
                b = bfgs.direction(self.f)
                dlam = -float(self.f @ a) / float(self.f @ b)
                if not abs(dlam) <= self.dlam_cap:  # f . b ~ 0: the factor is nearly singular along f_ref
                    out.update(reason=f"load-factor correction {dlam:.3g} beyond the largest step")
                    break
                a = a + dlam * b
            if not np.all(np.isfinite(a)):
                out.update(reason="the correction is not finite (singular tangent factor)")
                break
            energy = abs(float(a @ r_f))
            energy0 = energy if energy0 is None else energy0
            energies.append(energy / _energy_scale(energy0, u, f_int, self.result, st))
            # no "energy == 0" shortcut: with work control du may vanish while lambda still moves
            if _converged(rel, energies[-1], it, st) or rel <= 1e-14 * st.force_tol:
                s = float(self.f @ (u[free] - self.result.u_origin[free])) if self.work else lam
                out.update(converged=True, f_int=f_int, states=trial, s=s)
                return out
            u, lam, ev_new, step = self._line_search(u, u_n, states_n, lam, a, dlam, r_f)
            if ev_new is not None:
                bfgs.update(step * a, ev_new[0][free] - f_int[free])
            ev = ev_new
        else:
            out.update(reason=f"no convergence in {st.max_iter} iterations")
        out.setdefault("reason", "unknown")
        self.last_failure = out
        self.fac = self.k0  # a failed step's factor is suspect: the next factorises its own tangent
        self.bar.note(f"step halved at lambda={lam_n:.6g}: {out['reason']}")
        return None

    def _prescribed_predictor(self, u_n, states_n, lam):
        """The tangent predictor of a step to the load factor ``lam`` without a previous step to scale: the
        committed state's linear response to the change of load and of the prescribed displacements,
        u = u_n + H (r_n + (lam - lam_n) f_ref - K_t,fc du_c) over the free DOFs (H the current factor),
        the prescribed DOFs at ``lam``.

        Why: the prescribed DOFs alone moved (the free ones left at u_n) make a first iterate that tears the
        elements beside them (docs/solver/decisions.md#prescribed-predictor)."""
        sy, free = self.system, self.system.free
        u = sy.apply_constraints(u_n.copy(), lam)
        delta = u - u_n
        if not np.any(delta):  # nothing prescribed moves: the first iteration is this predictor already
            return u
        try:
            f_int, k_list, _ = sy.evaluate(u_n, np.zeros_like(u_n), states_n, CONSISTENT)
        except FloatingPointError:
            return u
        f_lin = f_int.copy()
        for g, k_el in zip(self.model.groups, k_list):
            scatter_vector(g.edofs, np.einsum("eij,ej->ei", k_el, delta[g.edofs]), f_lin)
        du = self.fac.solve((lam * self.f_ref + self.f_dead - f_lin)[free])
        if np.all(np.isfinite(du)):
            u[free] += du
        return u

    def _evaluate(self, u, u_n, states_n, lam):
        try:
            f_int, _, trial = self.system.evaluate(u, u - u_n, states_n, None)
        except FloatingPointError:
            return None
        return f_int, trial, lam * self.f_ref + self.f_dead - f_int
