"""What a failed increment reports: where the soil, the interface and the plate stand (point codes and
activity per group), for ``NonConvergence``.
"""

import numpy as np


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
    return report
