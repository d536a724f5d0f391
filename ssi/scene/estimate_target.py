"""Refinement to a target error: :func:`solve_to_target` fits each refinement's error C h^p from the error
estimate of the scene as given (:mod:`ssi.scene.estimate`), picks the cheapest number of halvings per
refinement predicted to bring the asked quantities below ``target_error``, solves it and returns it with the
predicted error (:class:`TargetResult`); it stops with a message when an observed order is not asymptotic.
Solves are cached by refinement level, so a level already solved for the estimate is not solved again."""

from __future__ import annotations

import itertools
import math
import warnings
from dataclasses import dataclass

from ..solver import Settings
from .estimate import (
    REFINEMENTS,
    ErrorEstimate,
    Level,
    RefinedSolver,
    _check_refine,
    _estimate,
    _keys,
)
from .richardson import ORDER_MAX, ORDER_MIN, Richardson

__all__ = ["TargetResult", "solve_to_target"]


@dataclass
class TargetResult:
    """Outcome of :func:`solve_to_target`: ``status`` "target met", "not asymptotic" or "limit of
    refinements"; ``message``; ``result`` the SceneResult delivered; ``key`` its (mesh, steps, layers)
    halvings; ``predicted`` {quantity: estimated relative error of ``result``}; ``estimate`` the
    ErrorEstimate of the scene as given it rests on; ``wall_time`` [s] of every solve made."""

    status: str
    message: str
    result: object
    key: tuple
    predicted: dict
    estimate: ErrorEstimate
    wall_time: float

    @property
    def met(self) -> bool:
        return self.status == "target met"


def _error_at(r: Richardson, j: int) -> float:
    """|estimated error| after j halvings from the base, from the base's fitted power law C h^p."""
    if r.error_base == 0.0:
        return 0.0
    if not math.isfinite(r.order):  # resolved to the noise: refining does not shrink the bound
        return abs(r.error_base) if j == 0 else abs(r.error_fine)
    return abs(r.error_base) * 2.0 ** (-r.order * j)


def solve_to_target(
    scene,
    target_error: float = 0.02,
    quantities=None,
    n_steps=None,
    settings: Settings | None = None,
    refine=REFINEMENTS,
    max_halvings: int = 3,
) -> TargetResult:
    """Solve ``scene`` refined just enough that the estimated relative error of every quantity in
    ``quantities`` is at most ``target_error`` (default None: the quantity the scene is solved for,
    :func:`asked_quantity` -- the capacity of a push-over, the largest settlement of a load-controlled
    scene). Of a push-over the delivered result carries its capacity's estimated error
    (``out.capacity_error``: the estimate of the scene as given, or the predicted error of a refined one).

    1. :func:`estimate` the scene as given (levels h, h/2, h/4 of every refinement in ``refine``);
    2. stop with status "not asymptotic" (and a warning naming the refinement, quantity and order) if a
       refinement whose answers change an asked quantity by more than a tenth of the target has no observed
       order in [ORDER_MIN, ORDER_MAX]: its estimate cannot be extrapolated, more refinement would be a guess;
    3. each refinement's error after j halvings is its fitted C h^p; the errors of the refinements add.
       Of the combinations of at most ``max_halvings`` halvings per refinement that meet the target, take
       the cheapest (cost per halving: the measured wall-time ratio of the levels solved) -- status
       "limit of refinements" if none does;
    4. solve it (or reuse the level already solved) and return it with its predicted errors."""
    if not 0.0 < target_error < 1.0:
        raise ValueError(f"target_error must be a relative error in (0, 1), got {target_error}")
    if int(max_halvings) != max_halvings or max_halvings < 0:
        raise ValueError(f"max_halvings must be an integer >= 0, got {max_halvings}")
    refine = _check_refine(refine, scene)
    solver = RefinedSolver(scene, n_steps, settings)
    est = _estimate(solver, (0, 0, 0), refine)
    if quantities is None:
        quantities = (est.quantity,)
    missing = [q for q in quantities if q not in est.value]
    if missing:
        raise ValueError(
            f"quantities {missing} are not answered by this scene (it answers {list(est.value)})"
        )

    def wall():
        return sum(lv.wall_time for lv in solver.cache.values())

    base = est.levels[(0, 0, 0)]
    rel0 = {q: est.relative[q] for q in quantities}
    if base.result is not None:
        base.result.capacity_error = est.capacity_error()
        base.result.error_estimate = est.to_dict()
    if all(r <= target_error for r in rel0.values()):
        return TargetResult(
            "target met",
            f"the scene as given meets the target: {_fmt(rel0)}",
            base.result,
            (0, 0, 0),
            rel0,
            est,
            wall(),
        )
    # a non-asymptotic refinement whose whole change is below a tenth of the target cannot decide it
    bad = [
        (r, q)
        for r in est.parts
        for q in quantities
        if not est.parts[r][q].asymptotic
        and abs(est.parts[r][q].error_base) > 0.1 * target_error * abs(est.value[q])
    ]
    if bad:
        r, q = bad[0]
        part = est.parts[r][q]
        msg = (
            f"stopped: the {r} refinement of {q} is not in the asymptotic range (answers at h, h/2, h/4: "
            f"{', '.join(f'{v:.6g}' for v in part.values)}; observed order {part.order:.2f}, outside "
            f"[{ORDER_MIN}, {ORDER_MAX}]): its error cannot be extrapolated; estimated errors of the scene "
            f"as given {_fmt(rel0)}. Start from a finer scene, or check the model"
        )
        warnings.warn(msg, RuntimeWarning, stacklevel=2)
        return TargetResult("not asymptotic", msg, base.result, (0, 0, 0), rel0, est, wall())
    names = list(est.parts)
    growth = {}
    for r in names:
        t = [est.levels[k].wall_time for k in _keys((0, 0, 0), r)]
        growth[r] = max(math.sqrt(t[2] / t[0]), 1.0) if t[0] > 0 else 2.0
    best = None
    for combo in itertools.product(range(int(max_halvings) + 1), repeat=len(names)):
        pred = {
            q: sum(_error_at(est.parts[r][q], j) for r, j in zip(names, combo)) / abs(est.value[q])
            for q in quantities
        }
        if all(v <= target_error for v in pred.values()):
            cost = math.prod(growth[r] ** j for r, j in zip(names, combo))
            if best is None or cost < best[0]:
                best = (cost, combo, pred)
    if best is None:
        msg = (
            f"stopped: no combination of at most {max_halvings} halvings of {names} is predicted to meet "
            f"{target_error:g} (scene as given: {_fmt(rel0)}); raise max_halvings or start finer"
        )
        warnings.warn(msg, RuntimeWarning, stacklevel=2)
        return TargetResult("limit of refinements", msg, base.result, (0, 0, 0), rel0, est, wall())
    _, combo, pred = best
    key = tuple(combo[names.index(r)] if r in names else 0 for r in REFINEMENTS)
    level = solver(key)
    if level.result is not None:
        level.result.capacity_error = _predicted_capacity_error(est, level, names, combo, pred)
    return TargetResult(
        "target met",
        f"halvings {dict(zip(REFINEMENTS, key))}: predicted errors {_fmt(pred)} <= {target_error:g}",
        level.result,
        key,
        pred,
        est,
        wall(),
    )


def _predicted_capacity_error(est: ErrorEstimate, level: Level, names, combo, pred) -> dict | None:
    """The capacity estimate a refined result of :func:`solve_to_target` carries: its error predicted from
    the base's fitted C h^p per refinement (``relative`` from ``pred`` when the capacity was asked for),
    the same extrapolated value; None if the scene answers no capacity."""
    base = est.capacity_error()
    if base is None or level.key == est.base_key:
        return base
    error = sum(_error_at(est.parts[r]["capacity"], j) for r, j in zip(names, combo))
    value = level.values.get("capacity", est.value["capacity"])
    return base | {
        "relative": float(pred.get("capacity", error / abs(value))),
        "error": float(error),
        "how": (
            f"predicted by solve_to_target from the C h^p fitted on the scene as given (halvings {level.key})"
        ),
    }


def _fmt(rel):
    return "{" + ", ".join(f"{q}: {r:.2%}" for q, r in rel.items()) + "}"
