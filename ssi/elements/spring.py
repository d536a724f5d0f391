"""Nonlinear two-DOF springs: the smallest element group that exercises the whole solver.

A spring joins two global DOFs i and j (edofs (n_el, 2)) and carries a force F(d) along them, d = u_j - u_i
(ground a spring by fixing DOF i). Element vectors follow the protocol of ``base``:
f_el = [-F, +F], k_el = k [[1, -1], [-1, 1]] with k the elastic stiffness k0 (``tangent`` K0_MATRIX) or
dF/dd (CONSISTENT).

Laws (``kinds``, ``params`` (n_el, 3)):

* ``LINEAR`` (0): F = k0 d. params [k0, -, -].
* ``TANH`` (1): F = F_u tanh(k0 d / F_u) -- smooth, softening towards the plateau F_u; a *total* law (no
  history), the 1-DOF analogue of a structure approaching its limit load. params [k0, F_u, -].
* ``ELASTOPLASTIC`` (2): linear hardening plasticity, elastic k0, yield force F_y, plastic modulus H (the
  slope after yield is k0 H / (k0 + H)); an *incremental* law with a committed history
  state = [F, d_plastic] per element (n_el, 1, 2); elastic unloading. params [k0, F_y, H].

Tangents are exact (TANH: k0 / cosh^2; ELASTOPLASTIC: k0 H / (k0 + H) while yielding), which is what makes
full Newton quadratic (``tests/test_solver.py`` checks them by finite differences).
"""

import numpy as np
from numba import njit

from ..core.protocol import CONSISTENT, K0_MATRIX, ElementGroup

__all__ = ["ELASTOPLASTIC", "LINEAR", "TANH", "Spring", "spring_force"]

LINEAR = 0
TANH = 1
ELASTOPLASTIC = 2
KIND_NAMES = {LINEAR: "linear", TANH: "tanh", ELASTOPLASTIC: "elastoplastic"}
N_VAR = 2  # [F, kappa]


@njit(cache=True)
def spring_force(kind, p0, p1, p2, d, dd, f_old, kappa_old, out):
    """Force and tangent of one spring. d: total elongation, dd: increment since the committed state,
    f_old, kappa_old: committed force and accumulated plastic elongation.
    Writes out[0] = F, out[1] = dF/dd, out[2] = new kappa."""
    if kind == TANH:
        x = p0 * d / p1
        t = np.tanh(x)
        out[0] = p1 * t
        out[1] = p0 * (1.0 - t * t)
        out[2] = 0.0
    elif kind == ELASTOPLASTIC:
        f_trial = f_old + p0 * dd
        over = abs(f_trial) - (p1 + p2 * kappa_old)
        if over <= 0.0:
            out[0] = f_trial
            out[1] = p0
            out[2] = kappa_old
        else:
            s = 1.0 if f_trial > 0.0 else -1.0
            dlam = over / (p0 + p2)  # |f_trial| - k0 dlam = F_y + H (kappa_old + dlam)
            out[0] = f_trial - s * p0 * dlam
            out[1] = p0 * p2 / (p0 + p2)
            out[2] = kappa_old + dlam
    else:
        out[0] = p0 * d
        out[1] = p0
        out[2] = 0.0


@njit(cache=True)
def _springs(kinds, params, u_el, du_el, state_old, tangent, f_el, k_el, state_new):
    out = np.empty(3)
    for e in range(u_el.shape[0]):
        d = u_el[e, 1] - u_el[e, 0]
        dd = du_el[e, 1] - du_el[e, 0]
        spring_force(
            kinds[e],
            params[e, 0],
            params[e, 1],
            params[e, 2],
            d,
            dd,
            state_old[e, 0, 0],
            state_old[e, 0, 1],
            out,
        )
        k = params[e, 0] if tangent == K0_MATRIX else out[1]
        f_el[e, 0] = -out[0]
        f_el[e, 1] = out[0]
        k_el[e, 0, 0] = k
        k_el[e, 1, 1] = k
        k_el[e, 0, 1] = -k
        k_el[e, 1, 0] = -k
        state_new[e, 0, 0] = out[0]
        state_new[e, 0, 1] = out[2]


class Spring(ElementGroup):
    """A group of nonlinear springs between pairs of global DOFs.

    Parameters
    ----------
    edofs : int array (n_el, 2), the DOFs i, j of each spring (elongation d = u_j - u_i)
    kinds : int or int array (n_el,), LINEAR, TANH or ELASTOPLASTIC
    params : array (3,) or (n_el, 3), see the module docstring
    name : group name in result files
    """

    history_fields = {"force": 0, "kappa": 1}  # state (n_el, 1, 2): force F [N], plastic elongation [m]

    def __init__(self, edofs, kinds, params, name="spring"):
        self.edofs = np.ascontiguousarray(np.atleast_2d(edofs), np.int64)
        n_el = self.edofs.shape[0]
        if self.edofs.shape != (n_el, 2):
            raise ValueError(f"edofs must have shape (n_el, 2), got {self.edofs.shape}")
        self.kinds = np.ascontiguousarray(np.broadcast_to(np.asarray(kinds, np.int64), (n_el,)))
        if np.any((self.kinds < 0) | (self.kinds > 2)):
            raise ValueError(f"kinds must be LINEAR (0), TANH (1) or ELASTOPLASTIC (2), got {kinds}")
        params = np.asarray(params, np.float64)
        self.params = np.ascontiguousarray(np.broadcast_to(params, (n_el, 3)))
        if not np.all(np.isfinite(self.params)):
            raise ValueError("params must be finite")
        if np.any(self.params[:, 0] <= 0.0):
            raise ValueError("params[:, 0] (the elastic stiffness k0) must be > 0 [N/m]")
        if np.any((self.kinds != LINEAR) & (self.params[:, 1] <= 0.0)):
            raise ValueError("params[:, 1] (F_u of TANH, F_y of ELASTOPLASTIC) must be > 0 [N]")
        if np.any((self.kinds == ELASTOPLASTIC) & (self.params[:, 2] < 0.0)):
            raise ValueError("params[:, 2] (the plastic modulus H of ELASTOPLASTIC) must be >= 0 [N/m]")
        self.name = name
        self.n_el = n_el

    def initial_state(self):
        return np.zeros((self.n_el, 1, N_VAR))

    def evaluate(self, u_el, du_el, state_old, tangent):
        if tangent not in (K0_MATRIX, CONSISTENT):
            raise ValueError(f"tangent must be K0_MATRIX (0) or CONSISTENT (1), got {tangent}")
        f_el = np.empty((self.n_el, 2))
        k_el = np.empty((self.n_el, 2, 2))
        state_new = np.empty_like(state_old)
        _springs(
            self.kinds,
            self.params,
            np.ascontiguousarray(u_el, np.float64),
            np.ascontiguousarray(du_el, np.float64),
            state_old,
            int(tangent),
            f_el,
            k_el,
            state_new,
        )
        return f_el, k_el, state_new

    def elastic_stiffness(self):
        z = np.zeros((self.n_el, 2))
        return self.evaluate(z, z, self.initial_state(), K0_MATRIX)[1]

    def body_force(self):
        return None

    def symmetric_tangent(self) -> bool:
        """A one-DOF law: its tangent is symmetric."""
        return True

    def stored_energy(self, u_el, du_el, state_old, state_new, work) -> float | None:
        """F_n+1 dF / k0 per spring (linear, elastoplastic); the tanh law's whole work F_n+1 dd [J/m]. None
        for a subclass with a law of its own (its ``evaluate``): what it stores is not known here."""
        if type(self).evaluate is not Spring.evaluate:
            return None
        f_new, f_old = self.history(state_new, "force")[:, 0], self.history(state_old, "force")[:, 0]
        k0 = self.params[:, 0]
        dd = du_el[:, 1] - du_el[:, 0]
        # k0 = 0: a spring that carries no force stores nothing
        linear = np.divide(f_new * (f_new - f_old), k0, out=np.zeros_like(k0), where=k0 != 0.0)
        return float(np.sum(np.where(self.kinds == TANH, f_new * dd, linear)))

    def describe(self):
        return {
            "name": self.name,
            "n_el": self.n_el,
            "kinds": [KIND_NAMES[int(k)] for k in self.kinds],
            "params": self.params.tolist(),
        }
