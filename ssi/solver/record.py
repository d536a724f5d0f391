"""The start of a path and the record of its steps, shared by the load-path control (``control``), the
controlled path (``path``) and arc-length control (``arc_length``): ``_start`` builds the assembly
machinery, the loads, step 0 and the K0 factorisation; ``_record`` appends one converged step.
"""

import numpy as np

from ..core.model import System
from ..core.solution import Result


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


def _viscosity_in_force(model) -> float:
    """The largest Duvaut-Lions tau = dt/eta per increment set on the model's viscous groups (0: none; the
    solver sets none, a group built with ``viscosity > 0`` keeps its own), recorded per step."""
    return max((g.viscosity for g in model.groups if g.viscous), default=0.0)


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
