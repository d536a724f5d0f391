"""The corrector of the controlled path (:mod:`.path`): the factorisation of the tangent, its shifted copy
where a symmetric tangent is singular, the line search along a direction and the failure report's mode
without stiffness. A mixin of ``path._Follower``: it reads the follower's ``model``, ``settings``,
``policy``, ``system``, ``result``, ``k0``, ``fac``, ``f``, ``work``, ``u``, ``states``, ``lam``,
``g_growth``, ``_k0_diag`` and ``_evaluate``, and sets ``fac``. What was measured for each rule:
``docs/solver/decisions.md`` (#refactorisation, #secant-rule, #singular-shift, #line-search, #g-growth,
#overshoot).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..core.linsolve import Factorization
from ..core.protocol import CONSISTENT, SECANT_SOFTENING
from .increment import TANGENT_SOLVE_TOL, _norm


class _Corrector:
    """Factorisation and line search of one controlled step's iterations (see the module docstring)."""

    def _soft_mode(self, out) -> str:
        """The failed step's last iterate: if its consistent tangent has a mode without stiffness (Rayleigh
        quotient below ``policy.soft_mode`` of K0's along it, three inverse iterations on K_t +
        ``policy.singular_shift`` diag(K0)), which group carries it and whether the load does work on it, for
        the NonConvergence report (key ``soft_mode``): e.g. an unloaded weightless strip whose cohesionless
        contact opened, a mechanism that no load drives and whose position the corrector cannot fix (chapter
        19: quotient 2.7e-5, |f.x| / |f| |x| = 8e-4). '' otherwise."""
        u = out.get("u")
        if u is None:
            return ""
        try:
            _, k_list, _ = self.system.evaluate(u, u - self.u, self.states, CONSISTENT)
            pattern = self.system.pattern
            kt = pattern.matrix(pattern.assemble(k_list))
            k0 = pattern.matrix(pattern.assemble_elastic(self.model.groups))
            d = k0.diagonal()
            shifted = kt + self.policy.singular_shift * _diag(d)
            fac = Factorization(shifted, symmetric=False, backend=self.settings.backend)
            x = np.ones(kt.shape[0])
            for _ in range(3):
                x = fac.solve(d * x)
                x /= np.abs(x).max()
        except (FloatingPointError, RuntimeError, ValueError):
            return ""
        quotient = abs(float(x @ (kt @ x))) / float(x @ (k0 @ x))
        if not quotient < self.policy.soft_mode:
            return ""
        full = np.zeros(self.model.n_dof)
        full[self.system.free_dofs] = x
        total = float(x @ x)
        share = {}
        for g in self.model.groups:
            on = full[np.unique(g.edofs)]
            share[g.name] = float(on @ on) / total
        ranked = sorted(share.items(), key=lambda item: -item[1])
        carriers = ", ".join(f"{name} {100 * v:.0f} %" for name, v in ranked if v >= 0.5)
        top = np.argsort(-np.abs(x))[:4]
        where = self.system.describe_dofs(top, 4).replace("unsupported DOFs: ", "")
        work = abs(float(self.f @ x)) / (_norm(self.f) * _norm(x)) if self.work else 0.0
        driven = (
            f"the reference load does almost no work on it (|f.x| / |f| |x| = {work:.1e})"
            if work < 1e-2
            else f"|f.x| / |f| |x| = {work:.2g}"
        )
        return (
            f"the tangent has a mode without stiffness (x.K_t.x / x.K0.x = {quotient:.1e}), "
            f"on the DOFs of {carriers} ({where}); {driven}: a body or region that "
            f"nothing holds at lambda = {self.lam:.4g} (e.g. an unloaded weightless strip whose contact "
            "opened)"
        )

    def _tangent_flag(self, poor: bool) -> int:
        """The tangent flag of a factorisation (``policy.secant_rule``); ``poor``: asked for by a poor
        contraction (``policy.poor_run``)."""
        if self.policy.secant_rule == "always" or self.policy.secant_rule == "poor" and poor:
            return SECANT_SOFTENING
        return CONSISTENT

    def _refactor(self, u, u_n, states_n, tangent=CONSISTENT) -> bool:
        """Factorise the tangent ``tangent`` at ``u`` (False, the old factor kept, if it cannot be)."""
        try:
            _, k_list, _ = self.system.evaluate(u, u - u_n, states_n, tangent)
        except FloatingPointError:
            return False
        probe = None
        try:
            kt = self.system.pattern.matrix(self.system.pattern.assemble(k_list))
            probe = np.ones(kt.shape[0])  # a singular factor shows here, not in the next direction
            fac = Factorization(
                kt, symmetric=self.settings.symmetric_tangent, backend=self.settings.backend, lagged=True
            )
            error = _norm(kt @ fac.solve(probe) - probe)
            self.result.factorizations += 1
        except (FloatingPointError, RuntimeError):
            if probe is None:
                return False
            error = np.inf
        if not error <= TANGENT_SOLVE_TOL * _norm(probe) and self.settings.symmetric_tangent:
            fac, error = self._regularised(k_list, probe)  # a singular symmetric tangent: its shifted copy
        # a factor that does not solve its own matrix is not used (the old one is kept): SuperLU returns
        # finite garbage on a singular tangent (docs/solver/decisions.md#factor-check)
        if not error <= TANGENT_SOLVE_TOL * _norm(probe):
            return False
        self.fac = fac
        return True

    def _regularised(self, k_list, probe):
        """(factor, solve error) of K_t + ``policy.singular_shift`` diag(K0), the operator where a symmetric
        consistent tangent is singular (a node without stiffness, e.g. a soil-surface node beside an open
        contact); (None, inf) if it cannot be factorised. Only for symmetric tangents: with non-associated
        laws the singular direction may be a real mechanism (docs/solver/decisions.md#singular-shift)."""
        pattern = self.system.pattern
        if self._k0_diag is None:  # K0's diagonal as values of the tangent's pattern (its ordering is kept)
            k0 = pattern.matrix(pattern.assemble_elastic(self.model.groups))
            rows = np.repeat(np.arange(k0.shape[0]), np.diff(k0.indptr))
            self._k0_diag = np.where(rows == k0.indices, k0.data, 0.0)
        kt = pattern.matrix(pattern.assemble(k_list) + self.policy.singular_shift * self._k0_diag)
        try:
            fac = Factorization(
                kt, symmetric=self.settings.symmetric_tangent, backend=self.settings.backend, lagged=True
            )
            error = _norm(kt @ fac.solve(probe) - probe)
        except (FloatingPointError, RuntimeError):
            return None, np.inf
        self.result.factorizations += 1
        return fac, error

    def _line_search(self, u, u_n, states_n, lam, du, dlam, r_f):
        """(u, lambda, evaluation, t) of the step t along (du, dlam). On a factor of an unsymmetric
        consistent tangent: t = 1, 1/2, ... down to ``policy.line_search_min``, the first whose residual norm
        is below the current one -- a Newton direction lowers |r|^2 whatever the tangent's symmetry; where
        none does, Matthies & Strang's root of G (``_g_root``) if it raises |r| less than ``g_growth`` times
        (finite on a cracking strip only), else the trial of least |r|. Otherwise (a symmetric tangent,
        ``Settings.symmetric_tangent``, or K0): the root of G(t) = du . r(u + t du, lambda + t dlam), narrowed
        by ``_overshoot`` where it overshot on a symmetric tangent. G is the slope of a potential only for
        associated laws, and the norm rule alone stalls where an RC strip cracks: hence both
        (docs/solver/decisions.md#line-search, #g-growth)."""
        free = self.system.free
        g0 = float(du @ r_f)
        r0 = _norm(r_f)

        def trial(t):
            v = u.copy()
            v[free] += t * du
            lt = lam + t * dlam
            self.system.apply_constraints(v, lt)
            ev = self._evaluate(v, u_n, states_n, lt)
            return v, lt, ev, (np.inf if ev is None else float(du @ ev[2][free]))

        def norm(cand):
            return np.inf if cand[2] is None else _norm(cand[2][2][free])

        t = 1.0
        best = trial(t)
        if not self.settings.line_search:
            return best[0], best[1], best[2], t
        if self.fac is not self.k0 and not self.settings.symmetric_tangent:
            tried = [(norm(best), t, best)]
            while not norm(best) < r0 and t > self.policy.line_search_min:
                t *= 0.5
                best = trial(t)
                tried.append((norm(best), t, best))
            if norm(best) < r0:
                return best[0], best[1], best[2], t
            # no step lowers |r|: Matthies & Strang's root, unless it raises |r| g_growth times or more
            root, t_root, _, _ = self._g_root(tried[0][2], 1.0, g0, trial)
            if norm(root) < self.g_growth * r0:
                return root[0], root[1], root[2], t_root
            _, t, best = min(tried, key=lambda row: row[0])  # the trial of least |r| instead
            return best[0], best[1], best[2], t
        best, t, t_lo, g_lo = self._g_root(best, t, g0, trial)
        if self.settings.symmetric_tangent and norm(best) > r0 and (best[2] is None or best[3] < 0.0):
            t, best = _overshoot(trial, norm, r0, g0, t_lo, g_lo, t, best, self.policy)
        return best[0], best[1], best[2], t

    @staticmethod
    def _g_root(best, t, g0, trial):
        """Matthies & Strang's root of G = du . r from the trial ``best`` at ``t`` (a ``trial`` tuple (u,
        lambda, evaluation, G)): up to three secant / regula-falsi trials in [0.05, 4]; (trial, t, t_lo,
        g_lo), the last two the bracket's lower end, where G > 0 (``_overshoot`` narrows it)."""
        t_lo, g_lo = 0.0, g0
        for _ in range(3 if g0 > 0.0 else 0):
            g = best[3]
            if best[2] is not None and abs(g) <= 0.5 * g0:
                break
            if best[2] is None or not np.isfinite(g):
                t_new = 0.5 * (t_lo + t)
            elif g < 0.0:
                t_new = t - g * (t - t_lo) / (g - g_lo)
            else:
                t_lo, g_lo = t, g
                t_new = 2.0 * t
            t_new = min(max(t_new, 0.05), 4.0)
            if t_new == t:
                break
            t, best = t_new, trial(t_new)
        return best, t, t_lo, g_lo


def _overshoot(trial, norm, r0, g0, t_lo, g_lo, t, best, policy):
    """(t, trial) below Matthies & Strang's smallest step 0.05 where their search overshot: G(t) < 0 (the
    potential's minimum along the direction lies below t) or the update failed, and the residual grew. Regula
    falsi on G over the bracket [t_lo (G > 0), t (G < 0 or failed)], bisection where the update failed, for up
    to ``policy.overshoot_trials`` trials down to ``policy.overshoot_min``, until |G| <= G(0) / 2; else the
    largest trial with G > 0 (the potential, convex along the line, falls all the way to it), or, without one,
    the trial of the smallest residual (the corrector's divergence and stagnation tests then judge the step).
    Only for symmetric tangents, where G is the slope of the increment's convex potential: a direction through
    a nearly singular tangent is long, and t = 0.05 of it may drive nodes deep into a contact
    (docs/solver/decisions.md#overshoot)."""
    t_hi, hi = t, best
    smallest = (norm(best), t, best)
    below = None  # the largest trial with G > 0
    for _ in range(policy.overshoot_trials):
        g_hi = hi[3]
        if hi[2] is None or not np.isfinite(g_hi):
            t_new = 0.5 * (t_lo + t_hi)
        else:
            t_new = t_hi - g_hi * (t_hi - t_lo) / (g_hi - g_lo)
        # strictly inside the bracket, away from its ends (regula falsi stalls at one end otherwise)
        t_new = min(
            max(t_new, t_lo + 0.05 * (t_hi - t_lo), policy.overshoot_min), t_lo + 0.95 * (t_hi - t_lo)
        )
        if not t_lo < t_new < t_hi:
            break
        cand = trial(t_new)
        if norm(cand) < smallest[0]:
            smallest = (norm(cand), t_new, cand)
        if cand[2] is not None and abs(cand[3]) <= 0.5 * g0:
            return t_new, cand
        if cand[2] is not None and cand[3] > 0.0:
            t_lo, g_lo, below = t_new, cand[3], (t_new, cand)
        else:
            t_hi, hi = t_new, cand
    return below if below is not None else smallest[1:]


def _diag(d):
    return sp.diags(d, format="csc")
