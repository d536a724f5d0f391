"""Viscous recovery: where a rate-independent path stalls, the groups' viscosity relaxes the load in stages
down to the rate-independent limit, and a limit load found so is bracketed. Moved here from the load-path
control as it was; its rules are the load-path control's.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..core.solution import LIMIT_LOAD, STOPPED
from .diagnostics import _failure_report
from .settings import NonConvergence

if TYPE_CHECKING:  # for annotations only: these modules import this one
    from .control import _Path


def _has_viscosity(model) -> bool:
    return any(g.viscous for g in model.groups)


def _viscosity_in_force(model) -> float:
    return max((g.viscosity for g in model.groups if g.viscous), default=0.0)


def _set_viscosity(model, tau):
    for g in model.groups:
        if g.viscous:
            g.viscosity = float(tau)


RELAX_GROWTH = 10.0  # tau grows tenfold from one relaxation stage to the next ...


RELAX_STAGES = 4  # ... over this many stages, then the last stage is rate independent (tau = 0)


RELAX_STEPS = 8  # increments at most per stage


RELAX_TOL = 1e-5  # a stage ends when the load measure changes by less than this (relative)


RELAX_MIN_GROWTH = 1.5  # a failing stage is retried with a smaller growth of tau, down to this


FLOW_MIN = 10.0 * RELAX_TOL  # a held increment smaller than this (relative to delta) is not flow but noise


BRACKET_TOL = 0.01  # a limit load found by relaxation is bracketed to 1 % of its load factor ...


BRACKET_REFINEMENTS = 4  # ... with at most this many extra relaxations


# A held load "flows" (evidence of a mechanism) when its flow stiffness is below this fraction of
# collapse_stiffness. Measured: the zoo's held loads above a detected limit flowed at 4e-9 .. 1.6e-3 of the
# initial stiffness; the graded h = 0.0625 m copy of chapter 11's foundation, which carries lambda = 1
# on every coarser copy, failed to relax at lambda = 0.615 with 0.044 (it relaxed by half per increment:
# slow, not flowing) and was taken for a collapse there while the threshold was collapse_stiffness itself.
FLOW_COLLAPSE_FRACTION = 0.1


class _RelaxationFailed(Exception):
    """No rate-independent equilibrium was found at the held load (the last relaxation stage failed)."""

    def __init__(self, outcome, tau, lam, flow_stiffness=np.nan):
        super().__init__(outcome.get("reason", ""))
        self.outcome, self.tau, self.lam = outcome, tau, lam
        self.flow_stiffness = flow_stiffness  # see _flow_stiffness (nan: unknown)


def _flow_stiffness(deltas, tau):
    """Current stiffness parameter of a held load's flow mode, from the loaded displacement of its last three
    increments at viscosity ``tau``: a mode of stiffness s (relative to the elastic one) relaxes by
    1 / (1 + tau s) per increment, so s = (1/r - 1) / tau with r the ratio of the last two displacement
    increments. nan when unknown (fewer than three, tau = 0, no motion beyond ``FLOW_MIN``)."""
    if len(deltas) < 3 or tau <= 0.0 or deltas[-2] == deltas[-3]:
        return np.nan
    if abs(deltas[-1] - deltas[-2]) <= FLOW_MIN * abs(deltas[-1]):
        return np.nan  # motion at the level of the convergence tolerance says nothing about a mechanism
    r = abs(deltas[-1] - deltas[-2]) / abs(deltas[-2] - deltas[-3])
    return (1.0 / r - 1.0) / tau if r > 0.0 else np.inf


def _relax_stages(path):
    """Hold the path's load while tau grows; raises :class:`_RelaxationFailed` if the state does not relax.
    A stage that fails is retried from its start with the square root of its growth (down to 1.5x): a
    sudden tenfold stiffening of the viscous law is a large jump of the problem, a smaller one may not be."""
    lam, tau, growth = path.lam, path.tau, RELAX_GROWTH
    tau_last = path.tau * RELAX_GROWTH**RELAX_STAGES
    try:
        while True:
            nxt = 0.0 if tau >= tau_last * (1.0 - 1e-12) else min(tau * growth, tau_last)
            start = path.save()
            try:
                _hold(path, lam, nxt)
            except _RelaxationFailed:
                path.restore(start)
                growth = growth**0.5
                if nxt == 0.0 or growth < RELAX_MIN_GROWTH:
                    raise
                continue
            if nxt == 0.0:
                return
            tau = nxt
    finally:
        _set_viscosity(path.model, path.tau)


def _hold(path, lam, tau):
    """One relaxation stage: up to ``RELAX_STEPS`` increments at the held load with viscosity ``tau``, until
    the load measure settles. A stage that ends unsettled leaves its flow stiffness in ``path.flow``."""
    _set_viscosity(path.model, tau)
    deltas = [path.measure.point(path.result.n_steps)[1]]
    for _ in range(RELAX_STEPS):
        before = np.array(path.measure.point(path.result.n_steps))
        outcome = path._increment(lam)
        if not outcome["converged"]:
            flow = _flow_stiffness(deltas, tau) if len(deltas) >= 3 else path.flow
            raise _RelaxationFailed(outcome, tau, lam, flow)
        path._commit(lam, outcome)
        after = np.array(path.measure.point(path.result.n_steps))
        deltas.append(after[1])
        if np.all(np.abs(after - before) <= RELAX_TOL * np.maximum(np.abs(after), 1e-30)):
            path.flow = np.nan
            return
    path.flow = _flow_stiffness(deltas, tau)


def relax(path: _Path) -> bool:
    """Hold the last target load of a viscous path while tau grows (10x per stage, then tau = 0): the
    overstress of each increment decays by 1/(1 + tau), and the last stage is the rate-independent law, so
    the final step is an equilibrium state of the inviscid problem (converged to the usual tolerances).
    Its step count is ``RELAX_STEPS`` per stage at most; each stage ends once the load measure settles.

    A viscous path can pass a limit load: the regularised problem has a solution above the rate-independent
    capacity (the overstress carries the excess). If the held load does not relax, the largest load factor
    of the viscous path that does relax is searched (bisection over its steps, then over lambda), and the
    result ends as ``"limit load reached"`` there, with ``limit_load_upper`` the smallest load factor where
    no rate-independent equilibrium was found -- provided the structure is at a limit: the held load kept
    flowing -- the nearest held load above that factor, with a current stiffness (:func:`_flow_stiffness`)
    below ``FLOW_COLLAPSE_FRACTION * collapse_stiffness`` -- or the two highest relaxed states' secant
    stiffness is below ``collapse_stiffness``. Else :class:`NonConvergence`."""
    first = path.result.n_steps
    saved = path.save()
    try:
        _relax_stages(path)
    except _RelaxationFailed as failure:
        path.restore(saved)
        _bracket_limit(path, saved, failure)
        path.result.relaxed_steps = None  # the path was cut back to the limit: its end is the relaxed state
        path.tau = 0.0
        return False
    path.result.relaxed_steps = path.result.n_steps - first
    path.tau = 0.0
    _set_viscosity(path.model, 0.0)
    return True


def _bracket_limit(path, saved, failure):
    """The held load of a viscous path did not relax: find the largest load factor that does (see
    :func:`relax`), or raise NonConvergence. ``saved`` is the path before the failed relaxation."""
    res = path.result
    if not path.settings.keep_states:  # the steps' states are needed to relax at an earlier step
        _raise_relaxation_failure(path, failure, np.nan, np.nan)
    lo = res.viscous_from if res.viscous_from is not None else 0
    hi = res.n_steps
    best = None
    relaxed = [path.measure.point(lo)]  # (load measure, loaded displacement) of rate-independent states
    failures = [failure]  # every held load that did not relax (any of them may show the flow)
    while hi - lo > 1:  # bisection over the committed viscous steps
        mid = (lo + hi) // 2
        path.restore(saved, mid)
        try:
            _relax_stages(path)
            best, lo = path.save(), mid
            relaxed.append(path.measure.point(path.result.n_steps))
        except _RelaxationFailed as nearer:
            hi = mid
            failures.append(nearer)
    if best is None:  # only the state before the viscous fallback (rate independent already)
        path.restore(saved, lo)
    else:
        path.restore(best)
    lam_hi = saved.lists["load_factor"][hi]
    lam_lo = path.lam
    for _ in range(BRACKET_REFINEMENTS):  # bisection over lambda from the relaxed state at lam_lo
        if lam_hi - lam_lo <= BRACKET_TOL * abs(lam_hi):
            break
        here = path.save()
        lam_mid = 0.5 * (lam_lo + lam_hi)
        try:
            _set_viscosity(path.model, path.tau)
            outcome = path._increment(lam_mid)
            if not outcome["converged"]:
                raise _RelaxationFailed(outcome, path.tau, lam_mid)
            path._commit(lam_mid, outcome)
            _relax_stages(path)
            lam_lo = lam_mid
            relaxed.append(path.measure.point(path.result.n_steps))
        except _RelaxationFailed as nearer:
            path.restore(here)
            lam_hi = lam_mid
            failures.append(nearer)
    path.tau = 0.0
    _set_viscosity(path.model, 0.0)
    stiff = _secant_stiffness(path.measure, relaxed)
    failure, flowing, collapsed = _collapse_evidence(failures, stiff, path.settings.collapse_stiffness)
    if collapsed:
        res.status, res.limit_load_factor, res.limit_load_upper = LIMIT_LOAD, float(lam_lo), float(lam_hi)
        res.limit_evidence = (
            f"held at lambda = {failure.lam:.6g} the body kept flowing, its current stiffness "
            f"{failure.flow_stiffness:.2g} of the initial"
            if flowing
            else f"the relaxed path's current stiffness fell to {stiff:.3g} of the initial"
        )
        return
    _raise_relaxation_failure(path, failure, lam_lo, stiff)


def _collapse_evidence(failures, secant_stiffness, collapse_stiffness):
    """(nearest failure, it flowed, the bracket is a collapse) for the held loads that did not relax
    (``failures``, :class:`_RelaxationFailed`) and the relaxed path's secant stiffness. The evidence is the
    held load at the bracket's upper end, the nearest failure: a flow far above it says nothing about the
    load just above the limit. It flowed when its flow stiffness is below ``FLOW_COLLAPSE_FRACTION *
    collapse_stiffness``; the bracket is a collapse when it flowed or the secant stiffness is below
    ``collapse_stiffness``."""
    failure = min(failures, key=lambda f: f.lam)
    flowing = bool(failure.flow_stiffness < FLOW_COLLAPSE_FRACTION * collapse_stiffness)  # nan: no
    flat = bool(np.isfinite(secant_stiffness) and secant_stiffness < collapse_stiffness)
    return failure, flowing, flowing or flat


def _secant_stiffness(measure, points):
    """Current stiffness parameter of the rate-independent path from its two highest relaxed points (P,
    delta): the viscous path's own stiffness says nothing about the limit, its overstress stiffens it."""
    if len(points) < 2 or measure.first is None:
        return np.nan
    (p1, d1), (p2, d2) = sorted(points)[-2:]
    return float((p2 - p1) / (d2 - d1) / measure.first) if d2 != d1 else np.nan


def _raise_relaxation_failure(path, failure, lam_lo, stiff):
    report = _failure_report(path.model, path.system.free, failure.outcome, failure.lam, failure.lam)
    report["reason"] = f"relaxation of the viscous path failed at tau={failure.tau:g}: {report['reason']}"
    if np.isfinite(lam_lo):
        report["reason"] += (
            f" (the largest load factor that relaxes is {lam_lo:.6g}; the relaxed path's current stiffness "
            f"there is {stiff:.3g} of the initial, not below collapse_stiffness="
            f"{path.settings.collapse_stiffness:g}, and the held load at lambda = {failure.lam:.6g} did not "
            f"flow (flow stiffness {failure.flow_stiffness:.2g}, not below "
            f"{FLOW_COLLAPSE_FRACTION * path.settings.collapse_stiffness:g}), so this is not taken for a "
            "collapse; softening (a cracking strip) and non-associated laws (soil psi < phi, contact "
            "psi_deg < phi_deg) can lose rate-independent solutions below the capacity on a fine mesh: try "
            "a coarser mesh where the worst DOF lies, or dilation closer to friction)"
        )
    path.result.status = STOPPED
    raise NonConvergence(report, path.result)
