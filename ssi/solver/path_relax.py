"""The relaxation of the controlled path (:mod:`.path`): where the corrector stalls at the smallest control
step, the step at a prescribed load factor found by damped dynamics on K0 (the follower's injected ``relax``,
:func:`.relax.relax`), and the search for an equilibrium above a peak after such a step. A mixin of
``path._Follower``: it reads the follower's ``model``, ``settings``, ``policy``, ``system``, ``result``,
``k0``, ``prev``, ``u``, ``states``, ``lam``, ``scale``, ``ds_min``, ``w1``, ``f``, ``f_ref``, ``f_dead``,
``work``, ``bar``, ``relaxed``, ``last_failure`` and its ``_evaluate``, ``_prescribed_predictor`` and
``_commit``, and sets ``fac``. What was measured: ``docs/solver/decisions.md`` (#relax,
#no-limit-from-a-relaxed-state).
"""

from __future__ import annotations

from collections import deque

from .diagnostics import ill_posed_soil
from .increment import _converged, _energy_scale, _force_scale, _norm


class _Relaxing:
    """The relaxed steps of a controlled run (see the module docstring)."""

    def _relax(self, target):
        """A step the corrector could not take (the control step halved below ``min_step``): an equilibrium
        at a prescribed load factor found by damped dynamics on K0 (``_dynamic``). The load increment: the
        last committed step's (or the elastic one of ``min_step``), halved up to ``policy.relax_halvings``
        times; None if none converges (``last_failure`` then the corrector's own, for the diagnosis)."""
        failure = self.last_failure
        first = self.prev[1] if self.prev is not None and self.prev[1] > 0.0 else 0.0
        first = max(first, self.ds_min / self.w1)
        self.fac = self.k0  # the stalled step's factor is suspect: the next controlled step refactorises
        for k in range(self.policy.relax_halvings + 1):
            lam_to = min(target, self.lam + first * 0.5**k)
            out = self._dynamic(self.u, self.states, self.lam, lam_to)
            if out is not None:
                self.bar.note(f"relaxed step to lambda={lam_to:.6g} in {out['iterations']} iterations")
                self.last_failure = failure  # the corrector's failure, recorded against the relaxed step
                return out
        self.last_failure = failure
        return None

    def _above(self, peak) -> bool:
        """Where a path that took a relaxed step falls or levels off: is there an equilibrium above its peak?
        Damped dynamics (``_dynamic``) from the current state at (1 + 2 ``policy.plateau_rise``) x the peak
        load factor; converged -> committed (True). Why: a relaxed step finds one of several states of the
        ill-posed soil, from which the controlled steps may follow a descending branch that is no collapse
        (docs/solver/decisions.md#no-limit-from-a-relaxed-state)."""
        lam_to = min(peak * (1.0 + 2.0 * self.policy.plateau_rise), self.scale)
        if not lam_to > self.lam:
            return False
        failure = self.last_failure
        out = self._dynamic(self.u, self.states, self.lam, lam_to)
        self.fac = self.k0
        if out is None:
            self.last_failure = failure
            return False
        self._commit(out)
        self.relaxed[self.result.n_steps] = failure
        return True

    def _dynamic(self, u_n, states_n, lam_n, lam):
        """:func:`ssi.solver.relax.relax` from the committed state at the load factor ``lam``: the residual
        of the material update from the committed state over the whole increment (as in any step), K0 the
        mass, accepted by ``_converged`` with the force and energy references of a K0 step. Returns the
        step (dict, as ``_step``'s) or None (kept in ``last_failure``); counts the relaxation on the
        result."""
        st, sy = self.settings, self.system
        free = sy.free
        u = u_n.copy()
        if self.prev is not None:  # the secant predictor of a step to a prescribed lambda (see _step)
            du_p, dlam_p, _ = self.prev
            u[free] += (max((lam - lam_n) / dlam_p, 0.0) if dlam_p != 0.0 else 0.0) * du_p
        else:
            u = self._prescribed_predictor(u_n, states_n, lam)
        sy.apply_constraints(u, lam)
        f_ext = lam * self.f_ref + self.f_dead
        energies, trials = [], deque([None, None], maxlen=2)  # the last two iterates' states (diagnosis)

        def full(u_f):
            v = u.copy()
            v[free] = u_f
            return v

        def residual(u_f):
            ev = self._evaluate(full(u_f), u_n, states_n, lam)
            if ev is None:
                return None
            f_int, trial, r = ev
            trials.append(trial)
            rel = _norm(r[free]) / _force_scale(st, lam, self.f_ref, f_ext, f_int, self.result)
            return r[free], rel, (f_int, trial, r)

        energy0 = []

        def converged(rel, energy, it, u_f, data):
            if not energy0:
                energy0.append(energy)
            energies.append(energy / _energy_scale(energy0[0], full(u_f), data[0], self.result, st))
            return _converged(rel, energies[-1], it, st) or rel <= 1e-14 * st.force_tol

        pol = self.policy
        run = self.relax(
            u[free],
            residual,
            self.k0.solve,
            converged,
            beta=pol.relax_beta,
            max_iter=pol.relax_max_iter,
            window=pol.relax_window,
        )
        self.result.relaxed_iterations += run.iterations
        out = {"converged": run.converged, "residuals": run.residuals, "energies": energies}
        out.update(iterations=run.iterations, lam=lam, u=full(run.u), trial_prev=trials[0])
        if run.data is not None:
            f_int, trial, r = run.data
            out.update(residual=r, trial=trial, f_int=f_int, states=trial)
        if not run.converged:
            out.update(reason=run.reason)
            self.last_failure = out
            return None
        self.result.relaxed_steps += 1
        out["s"] = float(self.f @ (out["u"][free] - self.result.u_origin[free])) if self.work else lam
        note = ill_posed_soil(self.model, out["states"])
        if note and not self.result.relaxed_note:
            self.result.relaxed_note = note
        return out
