"""What a failed increment reports: where the soil, the interface and the plate stand (point codes and
activity per group), and whether a yielding soil's rate problem is still well posed, for ``NonConvergence``.
"""

import math

import numpy as np

from ..materials.mc_localisation import mc_ellipticity
from .mechanism import ASSOCIATED_TOL


def _point_codes(group, state):
    """Per-point state codes of a group (interface: stick/slip/open; soil: elastic/plastic) and their
    names, or None (the group declares none: ``ElementGroup.point_codes``)."""
    codes = group.point_codes(state)
    if codes is None:
        return None
    return np.asarray(codes).ravel(), group.point_code_names


def _activity(model, outcome, worst_dof):
    """Which groups hold the worst DOF, and how many of their points changed state between the last two
    iterates (e.g. contact points flipping between slip and open)."""
    lines = []
    trial, prev = outcome.get("trial"), outcome.get("trial_prev")
    for g, i in zip(model.groups, range(len(model.groups))):
        if worst_dof not in g.edofs:
            continue
        text = g.name
        if trial is not None and prev is not None:
            now, before = _point_codes(g, trial[i]), _point_codes(g, prev[i])
            if now is not None:
                flipped = now[0] != before[0]
                if flipped.any():
                    names = now[1]
                    pairs = {f"{names[a]}->{names[b]}" for a, b in zip(before[0][flipped], now[0][flipped])}
                    text += f" ({int(flipped.sum())} points flipping: {', '.join(sorted(pairs))})"
        lines.append(text)
    return "; ".join(lines)


def ill_posed_soil(model, trial) -> str:
    """Why a step at a non-associated soil's plastic front may have no solution, for the report (key
    ``ill_posed``): the Mohr–Coulomb materials with psi < phi that have plastic points in the failed
    iterate ``trial`` (one state per group), with the smallest det Q_ep / det Q_e of each
    (:func:`ssi.materials.mc_localisation.mc_ellipticity`); '' if there are none (associated or Davis-mode
    soil, or no plastic point).

    Measured (issue 31): all 12 of the random zoo's stopped scenes (seed 1) stop with plastic points of
    such soils (100-401 of the top layer's, psi = 0 under phi = 20.4-34.2 deg, and up to 137 of the lower
    layer's, psi = 5 under phi = 35 deg; ratios -0.018 to -0.054), and their Davis-mode copies (associated:
    ratio 0) all end completed or at a limit."""
    if trial is None:
        return ""
    parts = []
    for g, state in zip(model.groups, trial):
        for row, count, nu, phi, psi in g.nonassociated_yielding(state, ASSOCIATED_TOL):
            ratio, theta = mc_ellipticity(phi, psi, nu)
            parts.append(
                f"{count} plastic points of {g.name} material {row} (phi = {math.degrees(phi):.4g} deg, "
                f"psi = {math.degrees(psi):.4g} deg: min det Q_ep / det Q_e = {ratio:.3f}, band normal "
                f"{math.degrees(min(theta, math.pi - theta)):.1f} deg from sigma_1)"
            )
    if not parts:
        return ""
    return (
        "; ".join(parts)
        + ": perfectly plastic flow with psi < phi has lost ellipticity wherever it yields (Rudnicki & Rice "
        "1975; Vermeer & de Borst 1984), so the continued path need not be unique or exist on this mesh. "
        "A capacity is a well-posed problem in Davis mode (Settings(flow='davis'))"
    )


def _failure_report(model, free, outcome, lam_from, lam_to):
    report = {
        "reason": outcome.get("reason", "unknown"),
        "load_factor_from": float(lam_from),
        "load_factor_to": float(lam_to),
        "iterations": outcome.get("iterations", 0),
    }
    r = outcome.get("residual")
    if r is not None and np.any(np.isfinite(r[free])):
        r_free = np.where(free, np.abs(np.nan_to_num(r, nan=np.inf)), 0.0)
        worst = int(np.argmax(r_free))
        start = np.concatenate([[0], np.cumsum(model.node_ndof)])
        node = int(np.searchsorted(start, worst, side="right") - 1)
        report.update(
            worst_dof=worst,
            worst_node=node,
            worst_component=("u", "w", "alpha")[worst - start[node]],
            node_xy=tuple(float(v) for v in model.coords[node]),
            worst_groups=_activity(model, outcome, worst),
            last_residual=float(outcome["residuals"][-1]) if outcome["residuals"] else float("nan"),
        )
    ill_posed = ill_posed_soil(model, outcome.get("trial"))
    if ill_posed:
        report.update(ill_posed=ill_posed)
    return report
