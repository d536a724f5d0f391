"""Richardson extrapolation over a sequence of halvings of a discretisation parameter h: the observed order
and the error estimates of three answers q0, q1, q2 at h, h/2, h/4 (the formulas: :mod:`ssi.scene.estimate`,
which re-solves a scene on its refined copies and calls :func:`richardson` per quantity)."""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["NOISE", "ORDER_MAX", "ORDER_MIN", "ROUND_OFF", "Richardson", "richardson"]

ORDER_MIN = 0.5  # below: the differences hardly shrink -- far from the asymptotic range
ORDER_MAX = 5.0  # above: the second difference collapsed by accident (cancellation), not convergence
ROUND_OFF = 1e-9  # relative differences below this are the solver's round-off: the refinement is exact
NOISE = 1e-3  # relative differences below this are the iteration error of a nonlinear solve (force_tol
# 1e-5 moves chapter 11's settlements by ~1e-4 between solvers): no order can be observed,
# the error is bounded by the differences themselves


@dataclass(frozen=True)
class Richardson:
    """Richardson analysis of three answers q0, q1, q2 at h, h/2, h/4 of one quantity.

    ``order`` observed p [-] (nan when the refinement changed nothing); ``error_base`` estimated q0 - q_exact
    and ``error_fine`` estimated q2 - q_exact (units of q); ``extrapolated`` q_exact estimate; ``asymptotic``
    whether d1, d2 have one sign and ORDER_MIN <= p <= ORDER_MAX (or both vanish)."""

    values: tuple
    order: float
    error_base: float
    error_fine: float
    extrapolated: float
    asymptotic: bool


def richardson(q0: float, q1: float, q2: float, ratio: float = 2.0, noise: float = NOISE) -> Richardson:
    """Observed order and error estimates from answers at h, h/ratio, h/ratio^2 (see the module docstring).

    Differences below ``noise`` (relative to the answers) carry no order: the error of q0 is then taken as
    q0 - q2 and the refinement counts as resolved (pass ``noise=0`` for answers free of iteration error,
    e.g. linear solves)."""
    if not ratio > 1.0:
        raise ValueError(f"ratio must be > 1 (refinement factor of h), got {ratio}")
    if not 0.0 <= noise < 1.0:
        raise ValueError(f"noise must be a relative size in [0, 1), got {noise}")
    q0, q1, q2 = float(q0), float(q1), float(q2)
    if not all(math.isfinite(v) for v in (q0, q1, q2)):
        raise ValueError(f"answers must be finite, got {(q0, q1, q2)}")
    scale = max(abs(q0), abs(q1), abs(q2), 1e-300)
    d1, d2 = q1 - q0, q2 - q1
    if abs(d1) <= ROUND_OFF * scale and abs(d2) <= ROUND_OFF * scale:
        return Richardson((q0, q1, q2), math.nan, 0.0, 0.0, q2, True)
    if abs(d1) <= noise * scale and abs(d2) <= noise * scale:
        return Richardson((q0, q1, q2), math.nan, -(d1 + d2), abs(d2), q2, True)
    if abs(d2) <= ROUND_OFF * scale or d1 * d2 <= 0.0:
        # converged at h/2 (or oscillating): no order; the error of q0 is at least |d1|, q2's is unknown
        return Richardson((q0, q1, q2), math.inf if d1 * d2 > 0 else math.nan, -(d1 + d2), abs(d2), q2, False)
    p = math.log(abs(d1 / d2)) / math.log(ratio)
    growth = ratio**p
    asymptotic = ORDER_MIN <= p <= ORDER_MAX
    return Richardson(
        (q0, q1, q2),
        p,
        -d1 * growth / (growth - 1.0),
        -d2 / (growth - 1.0),
        q2 + d2 / (growth - 1.0),
        asymptotic,
    )
