"""Incremental--iterative solution (paper §8, eq. 8.1).

For each increment of the load factor lambda the solver iterates

    K_T du = F_ext(lambda) - F_int(u),     u <- u + du

until the residual is small, and only then commits the material state (the laws never see an unconverged
state as history). ``method``:

* ``"modified"`` (paper default): K_T = K0, the initial elastic stiffness, factorised **once** for the whole
  analysis and reused for every iteration of every increment. Converges linearly; robust; symmetric even when
  the material tangent is not (non-associated flow).
* ``"full"``: K_T = the consistent tangent, refactorised every iteration (unsymmetric if the laws are).
  Converges quadratically near the solution; if an increment diverges it is retried with K0 before the step
  is cut.

Load control scales the model's loads and prescribed displacements by lambda; displacement control is
load control of a model whose "load" is a prescribed displacement (``Model.prescribe``), and the reaction at
those DOFs is the load measure (``Result.reaction``).

Convergence (both must hold): the residual-force norm relative to the larger of |F_ext| and |F_int| (which
includes the reactions, so displacement control is covered), and the energy norm |du . r| relative to that of
the increment's first iteration (or to the work |u . F_int| of the total state, if larger). A step that does not converge is halved (``max_cuts`` times); if it still
fails, :class:`NonConvergence` is raised with what diverged, where and at which load -- no partial result is
ever returned as if it were converged.
"""

import time
from dataclasses import dataclass, field

import numpy as np

from .elements.base import CONSISTENT
from .linsolve import Factorization
from .model import Model, System

METHODS = ("modified", "full")


@dataclass
class Settings:
    """Solver options; the defaults reproduce the paper (modified Newton--Raphson with K0)."""

    method: str = "modified"
    force_tol: float = 1e-5       # |r_f| <= force_tol * max(|F_ext|, |F_int|)
    energy_tol: float = 1e-8      # |du . r| <= energy_tol * max(|du_0 . r_0|, |u . F_int|)
    max_iter: int | None = None   # per increment; None: 300 for modified Newton, 30 for full Newton (more
                                  # tangent factorisations than that cost more than the K0 retry below)
    max_cuts: int = 6             # halvings of a failing increment
    divergence_ratio: float = 1e6  # residual growth over the first iteration taken as divergence
    backend: str = "auto"
    symmetric_tangent: bool = False  # set True when every law's tangent is symmetric (associated flow)
    verbose: bool = False
    keep_states: bool = True      # keep the committed state of every step (False: only the last)
    line_search: bool = False     # full Newton: halve a step until the residual norm decreases. It breaks
                                  # the cycling of points that flip between elastic and plastic from one
                                  # iterate to the next (the README's psi = 0 scene), but is no cure-all:
                                  # chapter 11's finest mesh stops at 95 % of its load with it, not without
    line_search_min: float = 1.0 / 64.0  # smallest step fraction the line search tries
    fallback_iter: int = 300      # full Newton: iterations of the K0 retry of a failed increment (0: none)

    def __post_init__(self):
        from .linsolve import BACKENDS
        from .validate import check_bool, check_choice, check_int, check_real

        check_choice("Settings.method", self.method, METHODS)
        if self.max_iter is None:
            self.max_iter = 300 if self.method == "modified" else 30
        check_real("Settings.force_tol", self.force_tol, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
        check_real("Settings.energy_tol", self.energy_tol, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
        check_int("Settings.max_iter", self.max_iter, lo=1)
        check_int("Settings.max_cuts", self.max_cuts, lo=0)
        check_real("Settings.divergence_ratio", self.divergence_ratio, lo=1.0, lo_open=True)
        check_choice("Settings.backend", self.backend, BACKENDS)
        for name in ("symmetric_tangent", "verbose", "keep_states", "line_search"):
            check_bool(f"Settings.{name}", getattr(self, name))
        check_real("Settings.line_search_min", self.line_search_min, lo=0.0, hi=1.0, lo_open=True)
        check_int("Settings.fallback_iter", self.fallback_iter, lo=0)


class NonConvergence(RuntimeError):
    """An increment failed after all step cuts; ``report`` says what, where and at which load."""

    def __init__(self, report: dict, result: "Result"):
        self.report = report
        self.result = result  # the converged steps before the failure, for inspection only
        text = ", ".join(f"{k}={v}" for k, v in report.items())
        super().__init__(f"increment did not converge: {text}")


@dataclass
class Result:
    """Converged steps of an analysis. Row 0 is the initial state (lambda = 0)."""

    model: Model
    load_factor: list = field(default_factory=list)
    u: list = field(default_factory=list)
    f_int: list = field(default_factory=list)
    states: list = field(default_factory=list)
    iterations: list = field(default_factory=list)
    residuals: list = field(default_factory=list)   # per step: relative force norm of every iteration
    energies: list = field(default_factory=list)    # per step: relative energy norm of every iteration
    cuts: int = 0
    wall_time: float = 0.0
    factorizations: int = 0

    @property
    def n_steps(self):
        return len(self.load_factor) - 1

    def displacement(self, ids, comp):
        """(n_steps + 1, n_ids) history of a displacement component."""
        return np.array(self.u)[:, self.model.dof(ids, comp)]

    def reaction(self, ids, comp):
        """(n_steps + 1,) summed internal force (= support reaction) over ``ids`` in ``comp``."""
        d = self.model.dof(ids, comp)
        return np.array(self.f_int)[:, d].sum(axis=1)

    @property
    def final_state(self):
        return self.states[-1]


def run(model: Model, load_factors, settings: Settings | None = None, *, start: "Result | None" = None,
        loads: tuple | None = None) -> Result:
    """Follow the load path ``load_factors`` (increasing or not; each entry a target lambda).

    ``start``: continue from the last converged step of an earlier result of the same model (its u and
    material state become step 0, at lambda = 0): the next phase of a phased analysis. ``loads``:
    ``(f_ref, f_dead)`` global vectors [N] replacing the model's own (F_ext = lambda f_ref + f_dead), e.g. the
    loads of the previous phase as dead load and the phase's change as reference load.

    Raises :class:`NonConvergence` if an increment fails after ``settings.max_cuts`` halvings.
    """
    settings = settings or Settings()
    targets = np.atleast_1d(np.asarray(load_factors, np.float64))
    if targets.size == 0 or not np.all(np.isfinite(targets)):
        raise ValueError("load_factors must be a non-empty sequence of finite numbers")
    model.check()
    t_start = time.perf_counter()
    system, f_ref, f_dead, states, u, result, fac_k0 = _start(model, settings, start, loads)
    free = system.free
    lam = 0.0
    for target in targets:
        pending = [target]
        cuts_here = 0
        while pending:
            lam_next = pending[-1]
            outcome = _increment(system, settings, fac_k0, u, states, lam_next, f_ref, f_dead, result)
            if not outcome["converged"] and settings.method == "full" and settings.fallback_iter:
                # an indefinite or poor consistent tangent can send Newton astray; K0 cannot
                outcome = _increment(system, settings, fac_k0, u, states, lam_next, f_ref, f_dead, result,
                                     force_k0=True)
            if outcome["converged"]:
                u, states = outcome["u"], outcome["states"]
                lam = lam_next
                pending.pop()
                _record(result, lam, u, outcome["f_int"], states, outcome["iterations"],
                        outcome["residuals"], outcome["energies"], settings)
                if settings.verbose:
                    print(f"step {result.n_steps:4d}  lambda={lam:.6g}  iterations={outcome['iterations']:3d}"
                          f"  residual={outcome['residuals'][-1]:.2e}", flush=True)
                continue
            if cuts_here >= settings.max_cuts:
                result.wall_time = time.perf_counter() - t_start
                raise NonConvergence(_failure_report(model, free, outcome, lam, lam_next), result)
            cuts_here += 1
            result.cuts += 1
            pending.append(0.5 * (lam + lam_next))
    result.wall_time = time.perf_counter() - t_start
    return result


def _start(model, settings, start=None, loads=None):
    """Assembly machinery, loads, the initial state recorded as step 0, and the one factorisation of K0."""
    system = System(model)
    f_ref, f_dead = model.load_vectors() if loads is None else (np.asarray(v, np.float64) for v in loads)
    if f_ref.shape != (model.n_dof,) or f_dead.shape != (model.n_dof,):
        raise ValueError(f"loads must be two vectors of length n_dof = {model.n_dof}")
    if start is None:
        states = [g.initial_state() for g in model.groups]
        u = system.apply_constraints(np.zeros(model.n_dof), 0.0)
    else:
        if start.model is not model:
            raise ValueError("start must be a Result of the same model")
        states, u = start.final_state, start.u[-1].copy()
    f_int0, _, _ = system.evaluate(u, np.zeros_like(u), states, None)
    result = Result(model=model)
    _record(result, 0.0, u, f_int0, states, 0, [], [], settings)
    k0 = system.pattern.assemble([g.elastic_stiffness() for g in model.groups])
    fac_k0 = Factorization(system.pattern.matrix(k0), symmetric=True, backend=settings.backend, spd=True)
    result.factorizations = 1
    return system, f_ref, f_dead, states, u, result, fac_k0


def _record(result, lam, u, f_int, states, iterations, residuals, energies, settings):
    result.load_factor.append(lam)
    result.u.append(u.copy())
    result.f_int.append(f_int.copy())
    if settings.keep_states or not result.states:
        result.states.append(states)
    else:
        result.states[-1] = states
    result.iterations.append(iterations)
    result.residuals.append(list(residuals))
    result.energies.append(list(energies))


def _increment(system, settings, fac_k0, u_conv, states, lam, f_ref, f_dead, result, force_k0=False):
    """Iterate one increment from the committed (u_conv, states) to load factor ``lam``.

    ``force_k0`` iterates with K0 (modified Newton, ``settings.fallback_iter`` iterations) whatever the method.
    """
    free = system.free
    f_ext = lam * f_ref + f_dead
    scale_ext = np.linalg.norm(f_ext)
    use_k0 = force_k0 or settings.method != "full"
    max_iter = settings.fallback_iter if force_k0 else settings.max_iter
    residuals, energies = [], []
    energy0 = r_first = None
    outcome = {"converged": False, "residuals": residuals, "energies": energies, "iterations": 0}
    u = system.apply_constraints(u_conv.copy(), lam)
    evaluated = _evaluate(system, u, u_conv, states, use_k0, f_ext)
    for it in range(1, max_iter + 1):
        if evaluated is None:
            outcome.update(reason="material update failed", iterations=it)
            return outcome
        f_int, k_list, trial, r = evaluated
        r_f = r[free]
        rel = np.linalg.norm(r_f) / max(scale_ext, np.linalg.norm(f_int), 1e-30)
        residuals.append(rel)
        outcome.update(iterations=it, residual=r, u=u)
        if not np.isfinite(rel):
            outcome.update(reason="residual is not finite")
            return outcome
        r_first = rel if r_first is None else r_first
        if it > 1 and rel > settings.divergence_ratio * max(r_first, settings.force_tol):
            outcome.update(reason=f"residual grew by more than {settings.divergence_ratio:g}")
            return outcome
        du = None if use_k0 else _tangent_solve(system, settings, k_list, r_f, result)
        if du is None:  # modified Newton, or a tangent that cannot be factorised: K0 for the rest of the
            use_k0 = True  # increment (retrying a singular tangent every iteration measured slower)
            du = fac_k0.solve(r_f)
        energy = abs(float(du @ r_f))
        energy0 = energy if energy0 is None else energy0
        rel_energy = energy / _energy_scale(energy0, u, f_int)
        energies.append(rel_energy)
        if _converged(rel, rel_energy, it, settings) or rel <= 1e-14 * settings.force_tol or energy == 0.0:
            outcome.update(converged=True, u=u, f_int=f_int, states=trial)
            return outcome
        u, evaluated = _advance(system, settings, u, du, u_conv, states, use_k0, f_ext, np.linalg.norm(r_f))
    outcome.update(reason=f"no convergence in {max_iter} iterations" + (" with K0" if force_k0 else ""))
    return outcome


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
    if np.linalg.norm(kt @ du - r_f) > TANGENT_SOLVE_TOL * np.linalg.norm(r_f):
        return None
    return du


def _advance(system, settings, u, du, u_conv, states, use_k0, f_ext, r_norm):
    """u + s du with s = 1, or, with the line search in full Newton, the first s = 1, 1/2, ... whose residual
    norm is below ``r_norm`` (a full step near a corner of the yield surface can overshoot far)."""
    free = system.free
    step = 1.0
    while True:
        u_new = u.copy()
        u_new[free] += step * du
        evaluated = _evaluate(system, u_new, u_conv, states, use_k0, f_ext)
        if use_k0 or not settings.line_search or step <= settings.line_search_min:
            return u_new, evaluated
        if evaluated is not None and np.linalg.norm(evaluated[3][free]) < r_norm:
            return u_new, evaluated
        step *= 0.5


def _energy_scale(energy_first, u, f_int):
    """Reference of the energy norm: the first iteration's |du . r|, or the work |u . F_int| of the total
    state if larger -- a cut step's tiny first iteration must not make the test ever stricter."""
    return max(energy_first, abs(float(u @ f_int)), 1e-300)


def _converged(rel_force, rel_energy, iteration, settings):
    """Both norms small; or the force norm far below its tolerance (the energy ratio of a step that starts
    almost converged is meaningless)."""
    return rel_force <= settings.force_tol and (
        rel_energy <= settings.energy_tol or (iteration > 1 and rel_force <= 1e-3 * settings.force_tol))


def _failure_report(model, free, outcome, lam_from, lam_to):
    report = {"reason": outcome.get("reason", "unknown"), "load_factor_from": float(lam_from),
              "load_factor_to": float(lam_to), "iterations": outcome.get("iterations", 0)}
    r = outcome.get("residual")
    if r is not None and np.any(np.isfinite(r[free])):
        r_free = np.where(free, np.abs(np.nan_to_num(r, nan=np.inf)), 0.0)
        worst = int(np.argmax(r_free))
        start = np.concatenate([[0], np.cumsum(model.node_ndof)])
        node = int(np.searchsorted(start, worst, side="right") - 1)
        report.update(worst_dof=worst, worst_node=node, worst_component=("u", "w", "alpha")[worst - start[node]],
                      node_xy=tuple(float(v) for v in model.coords[node]),
                      last_residual=float(outcome["residuals"][-1]) if outcome["residuals"] else float("nan"))
    return report


def run_arc_length(model: Model, n_steps: int, first_increment: float, settings: Settings | None = None,
                   max_load_factor: float = np.inf, min_arc_ratio: float = 1e-4) -> Result:
    """Follow the equilibrium path through limit points with Crisfield's cylindrical arc-length method.

    The load factor becomes an unknown; every iteration keeps the displacement increment of the step on a
    circle of radius ``arc`` (||du_step|| = arc), chosen so that the first step's predictor has load-factor
    increment ``first_increment``. With ``method="modified"`` both K0 solves (for the reference load and for
    the residual) reuse the one factorisation of K0. The sign of each predictor follows the previous step's
    direction, so the path turns over a limit point instead of stalling there. A step whose constraint has no
    real root, or that does not converge, is retried with half the arc (down to ``min_arc_ratio`` of the first).

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
        outcome = _arc_step(system, settings, fac, du_ref, u, states, lam, arc, direction, f_ref, f_dead)
        if not outcome["converged"]:
            arc *= 0.5
            result.cuts += 1
            if arc < min_arc_ratio * arc0:
                result.wall_time = time.perf_counter() - t_start
                raise NonConvergence(_failure_report(model, free, outcome, lam, lam), result)
            continue
        direction = outcome["u"][free] - u[free]
        u, states, lam = outcome["u"], outcome["states"], outcome["lam"]
        _record(result, lam, u, outcome["f_int"], states, outcome["iterations"], outcome["residuals"],
                outcome["energies"], settings)
        if settings.verbose:
            print(f"arc step {result.n_steps:4d}  lambda={lam:.6g}  iterations={outcome['iterations']:3d}",
                  flush=True)
        if outcome["iterations"] <= 0.25 * settings.max_iter:
            arc = min(2.0 * arc, arc0)  # regrow after cuts while convergence is easy
    result.wall_time = time.perf_counter() - t_start
    return result


def _arc_step(system, settings, fac, du_ref, u_conv, states, lam_conv, arc, direction, f_ref, f_dead):
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
        scale = max(np.linalg.norm(lam * f_ref + f_dead), np.linalg.norm(f_int), 1e-30)
        rel = np.linalg.norm(r[free]) / scale
        residuals.append(rel)
        outcome.update(iterations=it, residual=r, u=u)
        if not np.isfinite(rel):
            outcome.update(reason="residual is not finite")
            return outcome
        du_r = fac.solve(r[free])
        energy = abs(float(du_r @ r[free]))
        energy0 = energy if energy0 is None else energy0
        energies.append(energy / _energy_scale(energy0, u, f_int))
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
