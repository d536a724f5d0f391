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
        quotient below ``SOFT_MODE`` of K0's along it, three inverse iterations on K_t + SINGULAR_SHIFT
        diag(K0)), which group carries it and whether the load does work on it, for the NonConvergence report
        (key ``soft_mode``) -- e.g. chapter 19's unloaded weightless strip whose cohesionless contact opened:
        a mechanism at lambda = 0 that no load drives, whose position the corrector cannot fix (residual
        stagnating at 7.5e-4; the mode: Rayleigh quotient 2.7e-5, on the strip's u DOFs, |f.x| / |f| |x| =
        8e-4). '' otherwise."""
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
        """The tangent flag of a factorisation (``SECANT_RULE``); ``poor``: asked for by a poor contraction
        (POOR_RUN)."""
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
        # a factor that does not solve its own matrix is not used (the old one is kept): e.g. a strip whose
        # contact points all slip (psi_i = 0: no tangential stiffness) or open has a singular tangent along
        # its horizontal translation, and SuperLU returns finite garbage (zoo scenes 1, 12, 24, 48, 58, 97
        # stopped at lambda = 0 on such directions; all complete with the check)
        if not error <= TANGENT_SOLVE_TOL * _norm(probe):
            return False
        self.fac = fac
        return True

    def _regularised(self, k_list, probe):
        """(factor, solve error) of K_t + ``SINGULAR_SHIFT`` diag(K0), the operator where a symmetric
        consistent tangent is singular; (None, inf) if it cannot be factorised.

        Measured (tools/path_spectrum.py, issue 31): Davis-mode zoo scenes 62 and 66 stopped on a plateau
        (f . K_t^-1 f 2 800 and 1 200 times its elastic value) where K_t had an eigenvalue 2e-13 and 5e-14 of
        its largest, its mode on one soil-surface node beside the footing (cohesionless top layer, contact
        points open there): a node without stiffness, not a fold or a bifurcation of the path. The old factor
        kept, the iterations stagnated; the shifted copy, a quasi-Newton operator that errs by 1e-6 of K0 on
        the other modes, carries both to their peak (limits 0.3142 and 0.5078). Only for symmetric tangents:
        with the user's non-associated laws the singular direction is a strip sliding on slipping contact
        (psi_i = 0), a real mechanism, and the shifted operator sent scene 24 sideways at lambda = 0 (kept
        factor: completed). The 100 random zoo scenes (seed 1) in Davis mode: completed / limit /
        NonConvergence 61 / 36 / 3 -> 61 / 38 / 1, none lost; of the 36 limits 33 moved by <= 0.31 %, three
        by more, all upward where the path no longer stalls on its slowly rising plateau (scenes 42 +0.53 %,
        3 +0.68 %, 78 +0.77 %; a shift of 1e-9 moved them further, +1.2 % on 42 and 78)."""
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
        """Step t along (du, dlam). On a factor of an unsymmetric consistent tangent: t = 1, 1/2, ... down
        to ``LINE_SEARCH_MIN``, the first whose residual norm is below the current one -- a Newton direction
        lowers |r|^2 whatever the tangent's symmetry. Otherwise (a symmetric tangent,
        ``Settings.symmetric_tangent``, or K0), and when no such t exists: Matthies & Strang's
        G(t) = du . r(u + t du, lambda + t dlam) ~ 0, t = 1 if |G(1)| <= |G(0)| / 2, else up to three
        secant / regula-falsi trials in [0.05, 4].

        Why both: G is the slope of a potential only for associated laws; with the slipping (psi = 0)
        contact and the non-associated soil of the random zoo it took steps whose residual grew, and the
        iterations cycled between slip, stick and open states. The norm rule alone stalls where chapter
        11's RC strip cracks (h = 0.125 m: NonConvergence at lambda = 0.394, |r| at 4.5e-4 with no t down
        to 1/64 lowering it, no soil or contact point changing state); the strip's direction is taken
        along G there.

        Measured where the controlled run failed at 3a5ff09, G's root always taken (chapter 11 at h = 0.125 m,
        10 targets; the run and four copies with the column load x (1 + eps), eps = +-1e-13, +-1e-12: 3 of the
        5 complete, with 2-6 failed steps, and the others stop in NonConvergence at lambda = 0.9407 and 0.8678
        -- bench key ch11_h0125_controlled_roundoff): the failed steps are corrector failures at kinks of the
        residual, not steps too long. (a) Where the strip first cracks (lambda ~ 0.39, 78 layer points at mid-
        strip) the iterations pass only by the root's extrapolation (t up to 4): with t <= 1 all 5 runs stop
        there, and so does the unperturbed run taking the trial of least |r| in place of the root. (b) At
        lambda = 0.9407 the iterations settle into an exact cycle of 8 in which 10 cracked layer points switch
        between loading on the softening envelope and secant unloading, |r| between 7e1 and 1.6e3 N (relative
        ~1e-4), a t = 4 step part of the cycle. (c) After such a step |r| grew 10-300 times, up to 400 soil
        points changing state, the step ending at the load-factor correction cap.

        Hence ``G_GROWTH``: the root is taken only if it raises |r| less than 10 times (see the constant for
        why not 30). As measured by crack8 against no rule: chapter 11 at h = 0.25
        m (and its four copies): 1 failed step -> 0 (tests/test_path_kinks.py); at h = 0.125 m 3 -> 4 of the 5
        complete (2-7 failed steps; the -1e-12 copy stops at 0.8704); chapter 13's graded h/4 copy
        (controlled) stops at lambda = 0.903 instead of 0.735, 46 soil points switching between elastic and
        plastic; the 100 random zoo scenes (seed 1) completed / limit / NonConvergence 57 / 31 / 12 -> 60 / 30
        / 10: scenes 46, 50, 82 now complete, scene 30 (a peak at 0.9449 before) stops at 0.9425 just below
        it, the 30 common limits move by <= 0.071 %. A growth of 3 stops chapter 11 at h = 0.125 m where it
        first cracks (5 of 5); 30 leaves chapter 11 as at 3a5ff09 (3 of 5 complete) and ends zoo scenes 30,
        46, 50, 82 at a limit 0.9468, a limit 0.9850, completed, completed; 100 stops scenes 30, 46 and 82.
        Also measured and rejected (crack8): t <= 1 for the root (0 of 5 complete), refactorising after each
        step taken along G (2 of 5, 9 and 12 failed steps), the tangent of the rejected full step (0 of 5:
        lambda = 0.414), the plate's K0 in the tangent (the unperturbed run: NonConvergence at 0.437). A
        secant modulus in place of the concrete's negative tangent on its softening envelope (tried in the
        law, not kept: the law is not this module's) with growths 3 and 10 here: 5 of 5 complete at h = 0.125
        m, 4 and 3 of them without a failed step in ~2 s; the failed steps left are soil points switching
        between elastic and plastic. That secant is now the tangent flag SECANT_SOFTENING, which the
        corrector asks for by ``SECANT_RULE`` (measured there; not the default)."""
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
            # no step lowers |r|: Matthies & Strang's root, unless it raises |r| G_GROWTH times or more
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
    potential's minimum along the direction lies below t) or the update failed, and the residual grew.

    Why: a direction through a nearly singular tangent is long -- on chapter 19's pushed strip (Tresca soil,
    smooth side walls whose kn is 1e3 times the soil's stiffness) 0.7 m for a push of 2.5 mm, the soil beside
    an opening wall having no stiffness left -- and t = 0.05 of it drives the wall nodes centimetres into
    their contact: the residual grew 1e2-1e5 times in a step and the path stopped at lambda = 0. Regula falsi
    on G over the bracket [t_lo (G > 0), t (G < 0 or failed)], bisection where the update failed, for up to
    ``OVERSHOOT_TRIALS`` trials down to ``OVERSHOOT_MIN``, until |G| <= G(0) / 2; else the largest trial
    with G > 0 (the potential, convex along the line, falls all the way to it), or, without one, the trial
    of the smallest residual (the corrector's divergence and stagnation tests then judge the step).
    Stopping at the first trial whose residual fell below the current one instead crept by t ~ 0.003 where
    the potential has a kink (a contact changing state along the line) and stopped Davis-mode zoo scene 74
    at lambda = 0.

    Only for symmetric tangents (``Settings.symmetric_tangent``, Davis mode, ``associated`` models): there G
    is the slope of the increment's convex potential and its root brackets the potential's minimum. Without
    that gate the user-flow random zoo (seed 1; no scene associated) changed where the K0 steps' search
    overshot: of its first 31 scenes, 30's limit 0.9477 became a NonConvergence at lambda = 0.943 and the
    limits of 3, 8, 11, 13, 17 moved by up to 0.12 %."""
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
