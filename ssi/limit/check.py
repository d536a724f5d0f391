"""An incremental analysis's limit load checked against the scene's limit-analysis bracket (issue 30, item 6).

An incremental (displacement-based, elasto-plastic) analysis that reports "limit load reached" gives one
number; limit analysis gives the bracket it should lie in. For any psi <= phi the associated upper bound
UB_assoc is a rigorous ceiling of the collapse load (Radenkovic), and the Davis lower bound LB_Davis is the
floor of the conventional engineering value; the incremental limit is accepted in
[(1 - ``low``) LB_Davis, (1 + ``high``) UB_assoc] (3 % either side by default: the issue's band, for the
incremental solver's own step and tolerance). Below it the incremental analysis stopped before the soil
was exhausted (a **false collapse**: a solver stall, not a capacity); above it the incremental mesh carries
more than any mechanism allows (a **mesh overestimate**: a displacement-based mesh is too stiff, e.g.
chapter 10's psi = 0 footing on h = 0.25 m), reported with its size.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..core.validate import check_real

__all__ = ["LimitCheck", "check_limit", "flag_suspect"]

VERDICTS = ("inside", "false collapse", "mesh overestimate")


@dataclass(frozen=True)
class LimitCheck:
    """The verdict on one incremental limit: ``verdict`` one of "inside", "false collapse", "mesh
    overestimate"; ``limit_load`` the incremental limit and ``low``, ``high`` the accepted band's ends (in
    the bracket's units); ``size`` how far outside, relative: limit / high - 1 above the band, 1 -
    limit / low below it, 0 inside."""

    verdict: str
    limit_load: float
    low: float
    high: float
    size: float

    @property
    def ok(self) -> bool:
        return self.verdict == "inside"

    def __str__(self) -> str:
        band = f"[{self.low:.4g}, {self.high:.4g}]"
        if self.verdict == "inside":
            return f"limit {self.limit_load:.4g} inside {band} (0.97 LB_Davis, 1.03 UB_assoc)"
        if self.verdict == "false collapse":
            return (
                f"FALSE COLLAPSE: limit {self.limit_load:.4g} is {100 * self.size:.1f} % below {band}'s "
                "floor (the incremental solver stopped before the soil's capacity)"
            )
        return (
            f"MESH OVERESTIMATE: limit {self.limit_load:.4g} is {100 * self.size:.1f} % above {band}'s "
            "ceiling (the associated upper bound): refine the incremental mesh"
        )


def check_limit(limit_load: float, bracket, low: float = 0.03, high: float = 0.03) -> LimitCheck:
    """Check an incremental ``limit_load`` against a limit-analysis ``bracket`` (module docstring).

    ``bracket``: a :class:`ssi.capacity.CapacityResult` (its ``lb_davis`` and ``ub``) or a pair
    (LB_Davis, UB_assoc), in the same units as ``limit_load`` (a scene's load factor of the same phase, or
    the footing's force [N/m] of a Settlement push). ``low``, ``high``: the relative margins of the band."""
    if hasattr(bracket, "lb_davis") and hasattr(bracket, "ub"):
        lb_davis, ub_assoc = bracket.lb_davis, bracket.ub
    else:
        try:
            lb_davis, ub_assoc = bracket
        except (TypeError, ValueError):
            raise TypeError(
                f"bracket must be a CapacityResult or a pair (LB_Davis, UB_assoc), got {bracket!r}"
            ) from None
    limit_load = check_real("limit_load", limit_load, lo=0.0)
    lb_davis = check_real("bracket LB_Davis", lb_davis, lo=0.0, lo_open=True)
    ub_assoc = check_real("bracket UB_assoc", ub_assoc, lo=0.0, lo_open=True)
    if lb_davis > ub_assoc * (1.0 + 1e-9):
        raise ValueError(f"bracket: LB_Davis = {lb_davis:g} must not exceed UB_assoc = {ub_assoc:g}")
    low = check_real("low", low, lo=0.0, hi=1.0, hi_open=True)
    high = check_real("high", high, lo=0.0)
    lo_end, hi_end = (1.0 - low) * lb_davis, (1.0 + high) * ub_assoc
    if limit_load < lo_end:
        return LimitCheck("false collapse", limit_load, lo_end, hi_end, 1.0 - limit_load / lo_end)
    if limit_load > hi_end:
        return LimitCheck("mesh overestimate", limit_load, lo_end, hi_end, limit_load / hi_end - 1.0)
    return LimitCheck("inside", limit_load, lo_end, hi_end, 0.0)


def flag_suspect(result, check: LimitCheck) -> str:
    """Record a failed ``check`` on the incremental ``result`` (an :class:`ssi.core.solution.Result` whose
    limit it checked): its reason is appended to ``result.limit_suspect``. Returns the reason, "" when the
    limit is inside the band (nothing is recorded then)."""
    if check.ok:
        return ""
    reason = str(check)
    result.limit_suspect = "; ".join(x for x in (result.limit_suspect, reason) if x)
    return reason
