"""Damped dynamics at a prescribed load factor: the controlled path's fallback where its corrector stalls.

Where the non-associated soil (psi < phi) has passed a bifurcation, the equilibrium the corrector sits on
is a saddle: the consistent tangent has a negative eigenvalue (random zoo scene 36 at lambda 0.537:
x.K_t.x / x.K0.x ~ -2.4e-3), Newton cannot go on from it and plain initial-stress iterations on K0
(u <- u + K0^-1 r) drift away along the unstable mode without settling. Damped dynamics with K0 (SPD) as
the mass, K0 u'' + c K0 u' = r(u), leave the saddle along that mode and come to rest on a stable
equilibrium of the same step: the heavy ball

    d = K0^-1 r(u),   v <- beta v + d,   u <- u + v,

with Barnes' kinetic damping (v <- 0 where the kinetic energy v.K0.v falls: the motion has passed a
minimum of the potential along its path, or, for a non-potential field, has stopped gaining). The result
is accepted only by the caller's own convergence test (``converged``), the same one as any step: what this
finds is an equilibrium, not an approximation of one. See docs/solver/decisions.md#relax for what was
measured and why these values.

The iteration is a function of injected pieces (as FElupe's ``tools/_newton.py``): the residual
evaluation, the solve with K0, the acceptance test; it knows nothing of elements or of the path.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .increment import _stagnates
from .policy import PATH_POLICY

# the defaults of beta, max_iter and window: the path's policy (PathPolicy.relax_beta, relax_max_iter,
# relax_window), with why each
BETA, MAX_ITER, WINDOW = PATH_POLICY.relax_beta, PATH_POLICY.relax_max_iter, PATH_POLICY.relax_window


@dataclass
class Relaxation:
    """The outcome of :func:`relax`: ``converged`` (the caller's test held at ``u``), the last iterate
    ``u`` and its evaluation ``data`` (whatever ``residual`` returned with it), the relative residual and
    the energy measure of every iteration, and why it ended if it did not converge."""

    converged: bool
    u: np.ndarray
    data: Any
    iterations: int
    residuals: list = field(default_factory=list)
    energies: list = field(default_factory=list)
    reason: str = ""


def relax(
    u: np.ndarray,
    residual: Callable[[np.ndarray], tuple | None],
    solve: Callable[[np.ndarray], np.ndarray],
    converged: Callable[[float, float, int, np.ndarray, Any], bool],
    *,
    beta: float = BETA,
    max_iter: int = MAX_ITER,
    window: int = WINDOW,
) -> Relaxation:
    """Damped dynamics from ``u`` (the free unknowns) at a fixed load.

    ``residual(u)`` -> (r, rel, data): the out-of-balance force r over the free unknowns, its relative norm
    and anything the caller wants back with the iterate (e.g. its internal forces and states); None if the
    state cannot be evaluated (a material update failed). ``solve(r)``: K0^-1 r, K0 symmetric positive
    definite (the mass and preconditioner). ``converged(rel, energy, it, u, data)``: the caller's test,
    ``energy`` = |K0^-1 r . r| (the energy norm of a K0 step from the iterate)."""
    v = np.zeros_like(u)
    w = np.zeros_like(u)  # K0 v, kept by the same recursion (w <- beta w + r): the kinetic energy is v.w
    residuals, energies = [], []
    out = Relaxation(False, u, None, 0, residuals, energies)
    ke_prev = 0.0
    for it in range(1, max_iter + 1):
        ev = residual(u)
        out.iterations = it
        if ev is None:
            out.reason = "material update failed"
            return out
        r, rel, data = ev
        out.u, out.data = u, data
        residuals.append(rel)
        if not np.isfinite(rel):
            out.reason = "residual is not finite"
            return out
        d = solve(r)
        energy = abs(float(d @ r))
        energies.append(energy)
        if converged(rel, energy, it, u, data):
            out.converged = True
            return out
        if _stagnates(residuals, window):
            out.reason = f"relaxation stagnates (no decrease over the last {window // 2} iterations)"
            return out
        v = beta * v + d
        w = beta * w + r
        ke = float(v @ w)
        if ke < ke_prev:  # past a peak of the kinetic energy: on from rest (Barnes' kinetic damping)
            v[:], w[:], ke = 0.0, 0.0, 0.0
        ke_prev = ke
        u = u + v
    out.reason = f"relaxation: no convergence in {max_iter} iterations"
    return out
