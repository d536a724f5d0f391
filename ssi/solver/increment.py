"""One increment: the iterations of the chosen method (modified or full Newton, L-BFGS with a line search)
from a converged state to the next, the tangent solve with its trust check, and the convergence test.

Each method's search direction is one function in the table ``DIRECTIONS`` (method name -> function of the
iteration's state, the element matrices and the free residual); a new method adds its row there and its
name to ``settings.METHODS``.
"""

import math

import numpy as np

from ..core.linsolve import Factorization
from ..core.protocol import CONSISTENT, SECANT_SOFTENING
from .lbfgs import lbfgs_first_loop, lbfgs_second_loop


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


class _Iteration:
    """What a direction function may read and change during one increment: ``use_k0`` (the iterations use
    K0, not the consistent tangent: modified Newton and L-BFGS always, full Newton after a tangent that
    could not be factorised) and the L-BFGS memory ``bfgs`` (None for the other methods)."""

    __slots__ = ("bfgs", "fac_k0", "result", "settings", "system", "tangent", "use_k0")

    def __init__(self, system, settings, fac_k0, result, use_k0, bfgs):
        self.system, self.settings, self.fac_k0, self.result = system, settings, fac_k0, result
        self.use_k0, self.bfgs = use_k0, bfgs
        self.tangent = CONSISTENT  # full Newton: SECANT_SOFTENING once the increment cycles (FULL_SECANT_RUN)


def _direction_modified(it, k_list, r_f):
    """Modified Newton: the one K0 factorisation."""
    return it.fac_k0.solve(r_f)


def _direction_full(it, k_list, r_f):
    """Full Newton: the consistent tangent; where it cannot be factorised (or its solve is not trusted),
    K0 for the rest of the increment (retrying a singular tangent every iteration measured slower)."""
    du = None if it.use_k0 else _tangent_solve(it.system, it.settings, k_list, r_f, it.result)
    if du is None:
        it.use_k0 = True
        du = it.fac_k0.solve(r_f)
    return du


def _direction_bfgs(it, k_list, r_f):
    """L-BFGS: the K0 factorisation updated with the increment's (step, force change) pairs."""
    return it.bfgs.direction(r_f)


FULL_SECANT_RUN = 3  # full Newton: this many iterations in a row that do not lower the increment's smallest
# residual by 20 % (FULL_SECANT_GAIN), and the increment starts again from its committed state on
# SECANT_SOFTENING (ssi.core.protocol: the consistent tangent with the secant sig / e at the concrete points
# loading on their cracked tension envelope), refactorised every iteration: the controlled path's secant_rule
# "poor". Why (issue 45): on chapter 11's RC strip on elastic soil at h = 0.25 m, and at h = 0.5 m with
# 1.5 x the column loads, the consistent tangent cycles where the strip cracks -- an exact period-3 cycle of
# |r| (1.65e-2, 5.04e-2, 3.40e-1, ...) or a slow rise, at every step down to min_step: cracked points flip
# between the softening branch and unloading -- and the runs stopped at lambda 0.408 / 0.279. Measured
# there and not kept: line_search=True (|r| still rises, 2.1e-4 -> 3.1e-4: at the kink Newton's direction
# does not lower |r|; 1.5 x loads then stops at 0.552), the secant with the line search (the same), a larger
# budget alone (the cycle is exact), the secant from the cycle's iterate (stagnates at h = 0.25 m). From
# the committed state the secant iterations contract, slowly (about 0.92 an iteration): FULL_SECANT_BUDGET.
FULL_SECANT_GAIN = 0.8
FULL_SECANT_BUDGET = 5  # full Newton on the secant: iterations beyond max_iter while |r| still falls
# (_stagnates on the secant iterations: a new smallest residual 10 % below the one before within 15
# iterations), up to this x max_iter. Only on a model with a cracking strip (cracking_strip): elsewhere
# SECANT_SOFTENING is the consistent tangent and a restart would repeat the increment


def cracking_strip(model) -> bool:
    """True if a group of the model can soften (``ElementGroup.softens``: a plate strip with a layer that is
    not elastic, RC concrete that can crack): where full Newton's secant restart (``FULL_SECANT_*``) and the
    path's ``PathPolicy.g_growth`` apply."""
    return any(g.softens() for g in model.groups)


# the search direction of each method (settings.METHODS): f(iteration state, element matrices, free residual)
DIRECTIONS = {"bfgs": _direction_bfgs, "modified": _direction_modified, "full": _direction_full}


def _increment(system, settings, fac_k0, u_conv, states, lam, f_ref, f_dead, result):
    """Iterate one increment of load control from the committed (u_conv, states) to load factor ``lam``
    with the settings' method."""
    free = system.free
    f_ext = lam * f_ref + f_dead
    method, max_iter, line_search = settings.method, settings.max_iter, settings.line_search
    residuals, energies = [], []
    energy0 = r_first = None
    bfgs = _Lbfgs(fac_k0, settings.bfgs_memory) if method == "bfgs" else None
    it_state = _Iteration(system, settings, fac_k0, result, use_k0=method != "full", bfgs=bfgs)
    direction = DIRECTIONS[method]
    outcome = {"converged": False, "residuals": residuals, "energies": energies, "iterations": 0}
    u = system.apply_constraints(u_conv.copy(), lam)
    evaluated = _evaluate(system, u, u_conv, states, it_state.use_k0, f_ext)
    trial_prev = None
    poor, secant_from = 0, None  # full Newton: poor iterations in a row; first iteration on the secant
    secant_rule = method == "full" and cracking_strip(system.model)
    it = 0
    while True:
        it += 1
        if it > max_iter and not (
            secant_from is not None
            and it <= FULL_SECANT_BUDGET * max_iter
            and not _stagnates(residuals[secant_from:])
        ):
            break
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
        if secant_rule and not it_state.use_k0 and it_state.tangent == CONSISTENT:
            poor = poor + 1 if it > 1 and rel > FULL_SECANT_GAIN * min(residuals[:-1]) else 0
            if poor >= FULL_SECANT_RUN:  # the consistent tangent cycles: the increment again from its start,
                # on the secant variant (FULL_SECANT_RUN)
                it_state.tangent, secant_from = SECANT_SOFTENING, it
                u = system.apply_constraints(u_conv.copy(), lam)
                evaluated = _evaluate(system, u, u_conv, states, False, f_ext, SECANT_SOFTENING)
                continue
        du = direction(it_state, k_list, r_f)
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
                system,
                settings,
                u,
                du,
                u_conv,
                states,
                it_state.use_k0,
                f_ext,
                _norm(r_f),
                line_search,
                it_state.tangent,
            )
        u = u_new
    outcome.update(reason=f"no convergence in {it - 1} iterations")
    return outcome


def _stagnates(residuals, window=30):
    """True if the smallest relative residual of the last ``window // 2`` iterations is not below 0.9 x the
    smallest of the ``window // 2`` before them: the increment (or controlled step) is failed.

    Why 30 (issue 31, speed10): replayed on the residual histories of every step attempt of the controlled
    path at main e0722f3 -- the bench footing (psi = 0, h = 0.125 m: 196 attempts, 24 failed, 760 of 3 824
    iterations in the failed ones), chapter 11 at h = 0.125 m (11, none failed) and the 100 random zoo
    scenes, seed 1 (4 190, 519 failed, 17 068 of 80 363 iterations) -- an earlier test ends steps that
    converge later (converging attempts ended, footing / chapter 11 / zoo; iterations saved on the failed
    ones): window 20 4 / 1 / 139 (189 / 0 / 4 939), window 10 23 / 4 / 519; no new smallest residual for 10
    iterations 8 / 1 / 204, for 15 3 / 1 / 85; the smallest still above 1e-3 after 15 iterations 10 / 7 /
    297; the residual 1 000 x its smallest 0 / 0 / 19 (62 / 0 / 1 008 saved: too few to matter). The slow
    converging steps and the hopeless ones have the same histories. Run live, window 20 completed 1 of 5
    round-off copies of the footing (window 30: 4 of 5); with min_step 1e-6, where all complete, 4.9-8.1 s
    CPU against 5.9-6.9 s (25-66 failed steps against 24-37: an attempt ended early is a step halved)."""
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


def _evaluate(system, u, u_conv, states, use_k0, f_ext, tangent=CONSISTENT):
    """(f_int, element matrices, trial states, residual) at ``u``, or None if a material update failed;
    ``tangent``: the flag of the element matrices when not ``use_k0``."""
    try:
        f_int, k_list, trial = system.evaluate(u, u - u_conv, states, None if use_k0 else tangent)
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


def _advance(system, settings, u, du, u_conv, states, use_k0, f_ext, r_norm, line_search, tangent=CONSISTENT):
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
        evaluated = _evaluate(system, u_new, u_conv, states, forces_only, f_ext, tangent)
        taken = use_k0 or not line_search or step <= settings.line_search_min
        if taken or (evaluated is not None and _norm(evaluated[3][free]) < r_norm):
            if forces_only and not use_k0 and evaluated is not None:
                evaluated = _evaluate(system, u_new, u_conv, states, False, f_ext, tangent)
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
