"""How every benchmark script prints a key that has a goal: the value, the goal beside it, the ratio of the
two measured in the same run, and MET or MISSED (issue 16: ``make bench`` shows each key against its goal)."""


def verdict(value: float, op: str, goal: float, unit: str = "") -> str:
    """``"   (goal <= 0.3 s; ratio 0.83 -> MET)"`` for ``value`` against ``goal`` (``op`` is "<=" or ">=")."""
    if op not in ("<=", ">="):
        raise ValueError(f"op must be '<=' or '>=', got {op!r}")
    met = value <= goal if op == "<=" else value >= goal
    ratio = value / goal if goal else float("nan")
    return f"   (goal {op} {goal:g}{unit}; value / goal = {ratio:.3g} -> {'MET' if met else 'MISSED'})"
