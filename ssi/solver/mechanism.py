"""The mechanism certificate of a limit on the controlled path (issue 31, item 4): the energy balance of one
converged increment, split into the part the laws dissipate and the part they store elastically.

For one increment from the committed state n to n + 1 (displacement increment du), every group's internal
work is W_g = sum_e f_el(u_n+1) . du_el, the backward-Euler work sum_points sigma_n+1 : d_eps w of the
laws (f_el = sum B^T sigma w). Its elastic part, from the committed states before and after the increment:

* soil (``SoilQ8``, ``SoilQ8Points``): E_g = sum_points sigma_n+1 : C^-1 (sigma_n+1 - sigma_n) w |J| with
  the law's isotropic elasticity (E, nu: every soil law's first two parameters; the plane-strain stress
  [sxx, szz, txz, syy] with its out-of-plane syy), plus the pore water's -p_n+1 d_eps_v w |J| where the
  layer is undrained (its volumetric spring is elastic). W_g - E_g = sum sigma_n+1 : d_eps_p w |J|: the
  plastic strain of the return mapping is d_eps - C^-1 d_sigma exactly (the laws keep the stress, not the
  plastic strain tensor, so it is read this way);
* contact (``Interface6``, ``SideInterface``): E_g = sum_points t_n+1 . K^-1 (t_n+1 - t_n) w |J|, K =
  diag(kt, kn): W_g - E_g = sum t . d[u]_p w |J| with the slip and opening of the interface law;
* springs (``Spring`` itself): F_n+1 (F_n+1 - F_n) / k0 for the linear and elastoplastic laws (their
  committed force), all of the work for the (elastic, history-free) tanh law;
* a plate strip whose layers are all elastic: all of its work (a linear elastic group stores what it is
  given: f_n+1 . du = u_n+1 K du, the same backward-Euler form as the soil's);
* any other group (a cracking or yielding RC strip, a subclass with a law of its own): its work is not split
  here and is reported as ``unsplit`` (the strip's concrete is a total law with secant unloading in tension
  and E0 unloading in compression, whose stored energy is not read from the committed state alone); the
  certificate counts it as stored, and is not given where it is a noticeable share (``UNSPLIT_TOL``).

With associated flow (psi = phi, soil and contact, or Davis mode) sigma_n+1 lies on the yield surface and
d_eps_p is normal to it, so sigma_n+1 : d_eps_p is the associated dissipation function of d_eps_p, and

    lambda_k = (D - f_dead . du) / (f_ref . du),       D = sum_g (W_g - E_g),

is the kinematic multiplier of the increment's plastic strain field (Drucker's upper-bound functional
evaluated on it): the reference load's multiplier that the increment's mechanism dissipates. By the energy
balance W = sum_g W_g = (lambda_n+1 f_ref + f_dead) . du up to the equilibrium residual, so lambda_k /
lambda_n+1 = 1 - E / (lambda_n+1 f_ref . du), E = sum_g E_g: at a collapse the increment is a mechanism, the
stresses stop changing and E -> 0, so lambda_k -> lambda_peak; a stall (a numerical plateau, a solver that
crawls along a path still rising) stores a finite share elastically and lambda_k < lambda_peak. With
prescribed displacements and no force load the same ratio is taken of the prescribed motion's work, W -
f_dead . du (the reactions' work).

The limit's increment (``ssi.solver.path``): the last one on a plateau, the one that reached the peak
where the path fell past it.

What it certifies, and what not: that the limit's increment is (or is not) a plastic mechanism whose
dissipation balances the load at the peak -- an energy-balance certificate of the mechanism. It is not a
rigorous upper bound: d_eps_p of a displacement-based increment is kinematically admissible only as the
plastic part of a compatible strain, and the associated flow rule holds at the Gauss points only (an
explicit scheme's sub-steps, a blended viscous state or an unsplit group break it further). The rigorous
bracket is :mod:`ssi.limit`'s. With the user's psi < phi the same split gives the share of the increment's
work dissipated, but sigma : d_eps_p is then not the associated dissipation of anything: it is reported as
an energy share, never as a certificate (issue 31, item 5).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.assembly import gather_vector
from ..core.protocol import K0_MATRIX

__all__ = ["IncrementEnergy", "MechanismCheck", "check_mechanism", "flow_is_associated", "increment_energy"]

ASSOCIATED_TOL = 1e-9  # |psi - phi| [rad] (soil), |tan psi - tan phi| (contact): below it, associated flow
MECHANISM_TOL = 0.03  # |lambda_k / lambda_peak - 1| above this: the limit's increment is no mechanism.
# Measured (issue 31): the 38 limits of the random zoo (seed 1) in Davis mode 0.9817 (scene 61) to 1.00003,
# chapter 10's associated footing on h = 0.0625 m 0.9946 -- collapses store <= 1.8 % of the load's work;
# the same footing (h = 0.25 m) stopped early on its rising path by a looser plateau rule (rise 5 %, 2 %,
# 1 % over 3 steps: a stall read as a limit 0.7, 0.5, 0.4 % below the load at the end of its 6 cm push)
# 0.937, 0.961, 0.974.
# 3 %, the bracket band, flags the first and passes every collapse with 1.2 points to spare.
UNSPLIT_TOL = 0.01  # unsplit work (a cracking strip) above this share of the load's work: no certificate
# (counted as stored it would move lambda_k by up to this share, a third of MECHANISM_TOL)


@dataclass(frozen=True)
class IncrementEnergy:
    """The energy balance of one increment [J/m]: ``work`` the internal work of all groups (sum f_int . du),
    ``stored`` its elastic part over the groups whose split is computed (soil, contact, springs, elastic
    strips), ``dissipated`` = their work less their stored part, ``unsplit`` the work of the other groups
    (an RC strip, a group with a law of its own),
    ``dead_work`` f_dead . du, ``load_work`` work - dead_work (lambda f_ref . du, or the reactions' work on
    prescribed displacements)."""

    work: float
    stored: float
    dissipated: float
    unsplit: float
    dead_work: float

    @property
    def load_work(self) -> float:
        return self.work - self.dead_work

    @property
    def multiplier_ratio(self) -> float:
        """lambda_k / lambda_n+1 = (D - f_dead . du) / (W - f_dead . du) (module docstring); the unsplit
        groups' work counts as stored (not dissipated). nan when the load does no work on the increment."""
        if not abs(self.load_work) > 0.0:
            return math.nan
        return (self.dissipated - self.dead_work) / self.load_work

    @property
    def stored_share(self) -> float:
        """The share of the load's work on the increment that the laws store elastically (the unsplit groups'
        work counted as stored): 1 - lambda_k / lambda_n+1; 0 for a mechanism, 1 for an elastic increment."""
        return 1.0 - self.multiplier_ratio


def increment_energy(model, u_n, u_new, states_n, states_new, f_dead) -> IncrementEnergy:
    """The energy balance of the increment from (``u_n``, ``states_n``) to the converged (``u_new``,
    ``states_new``) of ``model`` (see the module docstring); ``f_dead`` (n_dof,) the dead load [N/m]."""
    du = np.asarray(u_new, np.float64) - np.asarray(u_n, np.float64)
    work = stored = unsplit = 0.0
    for g, s_old, s_new in zip(model.groups, states_n, states_new):
        u_el = np.empty(g.edofs.shape)
        du_el = np.empty(g.edofs.shape)
        gather_vector(g.edofs, u_new, u_el)
        gather_vector(g.edofs, du, du_el)
        f_el = g.evaluate(u_el, du_el, s_old, K0_MATRIX)[0]  # the converged step's forces, recomputed
        w_g = float(np.einsum("ij,ij->", f_el, du_el))
        work += w_g
        part = g.stored_energy(u_el, du_el, s_old, s_new, w_g)  # None: the group does not split its work
        if part is None:
            unsplit += w_g
        else:
            stored += part
    dead = float(np.asarray(f_dead, np.float64) @ du)
    return IncrementEnergy(work=work, stored=stored, dissipated=work - stored - unsplit, unsplit=unsplit,
                           dead_work=dead)  # fmt: skip


def flow_is_associated(model, davis: bool) -> bool:
    """True when every soil and contact law of ``model`` flows normal to its yield surface (``davis``: Davis
    mode makes them so): Mohr-Coulomb rows with psi = phi, contacts with tan psi = tan phi; elastic and von
    Mises soil are associated by construction. Groups without such laws (plate strip, springs) do not
    enter (their work is reported unsplit)."""
    if davis:
        return True
    return all(g.associated_flow(ASSOCIATED_TOL) for g in model.groups)


@dataclass(frozen=True)
class MechanismCheck:
    """The certificate of a limit: ``ratio`` lambda_k / lambda_peak of the limit's increment (None where
    it is no certificate: non-associated flow, unsplit work above ``UNSPLIT_TOL``, no load work),
    ``stored`` the share of the load's work on it stored elastically (also for non-associated flow; None
    where not split), ``reason`` why the limit fails the check ("" if it passes or no certificate applies),
    ``note`` why no certificate was given ("" if one was)."""

    ratio: float | None
    stored: float | None
    reason: str = ""
    note: str = ""


def check_mechanism(energy: IncrementEnergy, load_end: float, load_peak: float, associated: bool,
                    tol: float | None = None) -> MechanismCheck:  # fmt: skip
    """The certificate of a limit at ``load_peak`` from the ``energy`` of the limit's increment, which
    ends at the load measure ``load_end`` (lambda, or the prescribed motion's reaction): lambda_k =
    ``load_end`` (D - f_dead . du) / (W - f_dead . du); the limit fails the check where |lambda_k /
    lambda_peak - 1| > ``tol`` (default ``MECHANISM_TOL``). Flow that is not ``associated``: only the
    stored share is reported (module docstring)."""
    tol = MECHANISM_TOL if tol is None else tol
    load_work = energy.load_work
    if not abs(load_work) > 0.0 or not load_peak > 0.0:
        return MechanismCheck(None, None, note="the load does no work on the limit's increment")
    unsplit = energy.unsplit / abs(load_work)
    if abs(unsplit) > UNSPLIT_TOL:
        note = f"{unsplit:.1%} of the work on the limit's increment goes to groups whose stored and"
        note += " dissipated parts are not split (an RC strip, a law of its own)"
        return MechanismCheck(None, None, note=note)
    stored = energy.stored_share
    if not associated:
        note = f"non-associated flow: {stored:.1%} of the load's work on the limit's increment stored"
        return MechanismCheck(None, stored, note=note + " elastically (an energy share, no certificate)")
    ratio = energy.multiplier_ratio * load_end / load_peak
    reason = ""
    if ratio < 1.0 - tol:
        reason = (
            f"the limit's increment is no collapse mechanism: its kinematic multiplier is {ratio:.4f} x the "
            f"peak, {stored:.1%} of the load's work on it stored elastically (a stall, or a path still "
            "rising)"
        )
    elif ratio > 1.0 + tol:
        reason = (
            f"the limit's increment is no collapse mechanism: its kinematic multiplier is {ratio:.4f} x the "
            "peak (it dissipates stored elastic energy: an unloading or softening increment)"
        )
    return MechanismCheck(ratio, stored, reason)
