"""Arc-length control (``run_arc_length``): the load factor becomes an unknown and each step follows the path
a given length, through limit points.
"""

import time

import numpy as np

from ..core.model import Model
from ..core.solution import Result
from .diagnostics import _failure_report
from .increment import _converged, _energy_scale, _force_scale, _norm
from .record import _record, _start, _viscosity_in_force
from .settings import NonConvergence, Settings


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
