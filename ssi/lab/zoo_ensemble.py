"""The random zoo's ensemble: each scene as drawn and in round-off copies, per linear-solver back end and CPU
target (``tools/zoo_ensemble.py --store``, ``reference_data/zoo_ensemble.csv``), read against the scenes'
Davis lower bounds (issue 45, item 3; chapter 06's rows ``zoo_service_completes``, ``zoo_path_reach`` and
``zoo_roundoff_outcomes``).

A run is a dict of the stored columns (``scene``, ``copy``, ``backend``, ``cpu``, ``status``, ``load_factor``,
``limit``, ``settlement_m``, ...; numbers as floats, NaN where empty). ``lb_davis`` maps a scene's name to its
certified Davis lower bound LB_Davis (NaN: not certified; absent: no bracket), the load factor of the scene's
column load. The checks:

* **within capacity** (:func:`within_capacity`): 1 <= 0.97 LB_Davis -- the reference load is below the floor
  of the conventional collapse load by more than the zoo's 3 % band, so the path must complete;
* :func:`service_completes`: every run of each scene within capacity completed (lambda = 1);
* :func:`path_reach`: the scene as drawn (copy ``drawn``, SuperLU, native CPU) carried min(1, 0.9 LB_Davis)
  (1 where LB_Davis is unknown): the largest load factor of its path, its limit's or its last converged one;
* :func:`roundoff_outcomes`: within capacity, one outcome over all runs and the settlement at lambda = 1
  within 1 % (spread (max - min) / max); the others, the ending load factor (a limit's, else the last
  converged) within 5 % and the limits' load factors within 1 %.
"""

from dataclasses import dataclass

import numpy as np

from ..solver import LIMIT_LOAD
from . import paths
from .digitize import read_reference

__all__ = [
    "ENSEMBLE_FILE",
    "SERVICE_MARGIN",
    "REACH_FRACTION",
    "SETTLEMENT_SPREAD",
    "ENDING_SPREAD",
    "LIMIT_SPREAD",
    "Spread",
    "as_drawn",
    "ending",
    "path_reach",
    "read_zoo_ensemble",
    "reached",
    "roundoff_outcomes",
    "service_completes",
    "spread",
    "within_capacity",
]

ENSEMBLE_FILE = paths.REFERENCE_DATA / "zoo_ensemble.csv"
SERVICE_MARGIN = 0.97  # within capacity: 1 <= 0.97 LB_Davis (the zoo's 3 % band below the Davis floor)
REACH_FRACTION = 0.9  # the path must carry min(1, 0.9 LB_Davis) (issue 45: Davis is an estimate, not a bound)
SETTLEMENT_SPREAD = 0.01  # within capacity: settlement at lambda = 1 over the copies
ENDING_SPREAD = 0.05  # beyond capacity: the ending load factor over the copies
LIMIT_SPREAD = 0.01  # beyond capacity: the limits' load factors over the copies
NUMBERS = ("load_factor", "limit", "settlement_m", "wall_s")


def read_zoo_ensemble(path=None) -> tuple[dict, dict[str, list[dict]]]:
    """``(meta, runs)`` of the stored ensemble: ``runs[scene name]`` its runs (dicts, numbers as floats, NaN
    where empty), in the file's order. ``FileNotFoundError`` when it has not been stored."""
    meta, cols = read_reference(ENSEMBLE_FILE if path is None else path)
    names = list(cols)
    runs: dict[str, list[dict]] = {}
    for i in range(len(cols["scene"])):
        row = {k: str(cols[k][i]) for k in names}
        for k in NUMBERS:
            text = row[k].strip()
            row[k] = float(text) if text and text.lower() != "nan" else np.nan
        runs.setdefault(row["scene"], []).append(row)
    return meta, runs


def within_capacity(lb_davis: float) -> bool:
    """The reference load (lambda = 1) lies at or below 0.97 LB_Davis (False when LB_Davis is unknown)."""
    return bool(np.isfinite(lb_davis) and 1.0 <= SERVICE_MARGIN * lb_davis)


def reached(run: dict) -> float:
    """The largest load factor a run's path carried: 1 when completed, else the larger of its limit and its
    last converged load factor (a controlled path past its peak ends below it)."""
    if run["status"] == "completed":
        return 1.0
    return float(np.nanmax([run["load_factor"], run["limit"]]))


def ending(run: dict) -> float:
    """The load factor a run ends with: its limit when it reports one, else its last converged one."""
    return run["limit"] if run["status"] == LIMIT_LOAD else run["load_factor"]


def spread(values) -> float:
    """(max - min) / max of positive values (0 for fewer than two)."""
    v = np.asarray([x for x in values if np.isfinite(x)], float)
    if len(v) < 2:
        return 0.0
    return float((v.max() - v.min()) / max(abs(v.max()), 1e-300))


def label(run: dict) -> str:
    """A run's name in a report: scene / copy / back end / cpu."""
    cpu = "generic" if run["cpu"] == "generic" else "native"
    return f"{run['scene']} copy {run['copy']} {run['backend']} {cpu}"


def as_drawn(runs: list[dict]) -> dict | None:
    """The scene as drawn, SuperLU, native CPU (the path a user gets here); None when ``runs`` lack it."""
    for r in runs:
        if r["copy"] == "drawn" and r["backend"] == "superlu" and r["cpu"] != "generic":
            return r
    return None


def service_completes(runs: dict[str, list[dict]], lb_davis: dict[str, float]):
    """``(eligible, failures)``: the scenes within capacity, and each run of them that did not complete
    (label, status, ending load factor, message)."""
    eligible = [n for n in runs if within_capacity(lb_davis.get(n, np.nan))]
    failures = [
        (label(r), r["status"], ending(r), r["message"])
        for n in eligible
        for r in runs[n]
        if r["status"] != "completed"
    ]
    return eligible, failures


def path_reach(runs: dict[str, list[dict]], lb_davis: dict[str, float]):
    """``(fraction, below)``: the fraction of scenes whose path as drawn carried min(1, 0.9 LB_Davis) (1 where
    LB_Davis is unknown), and each one below as (scene, reached, target, status, message). A scene without
    its as-drawn run counts as below."""
    below = []
    for n, rs in runs.items():
        lb = lb_davis.get(n, np.nan)
        target = min(1.0, REACH_FRACTION * lb) if np.isfinite(lb) else 1.0
        r = as_drawn(rs)
        if r is None:
            below.append((n, np.nan, target, "missing", "no as-drawn SuperLU run"))
        elif reached(r) < target:
            below.append((n, reached(r), target, r["status"], r["message"]))
    return 1.0 - len(below) / max(len(runs), 1), below


@dataclass
class Spread:
    """The round-off check of one scene over all its runs."""

    scene: str
    within: bool  # within capacity (1 <= 0.97 LB_Davis)
    outcomes: dict  # status -> number of runs
    settlement: float  # within capacity and all completed: spread of the settlement at lambda = 1; else NaN
    ending: float  # spread of the ending load factors (a limit's, else the last converged)
    limit: float  # spread of the limits' load factors (0 with fewer than two limits)
    ok: bool
    why: str  # "" when ok


def roundoff_outcomes(runs: dict[str, list[dict]], lb_davis: dict[str, float]) -> list[Spread]:
    """Each scene's :class:`Spread` over its runs (copies, back ends, CPU targets): within capacity one
    outcome and the settlement at lambda = 1 within 1 %; the others the ending load factor within 5 % and
    the limits' within 1 %."""
    out = []
    for n, rs in runs.items():
        within = within_capacity(lb_davis.get(n, np.nan))
        outcomes: dict[str, int] = {}
        for r in rs:
            outcomes[r["status"]] = outcomes.get(r["status"], 0) + 1
        completed = list(outcomes) == ["completed"]
        settle = spread(r["settlement_m"] for r in rs) if completed else np.nan
        end = spread(ending(r) for r in rs)
        lim = spread(r["limit"] for r in rs if r["status"] == LIMIT_LOAD)
        why = []
        if within:
            if len(outcomes) > 1:
                why.append("outcomes differ: " + ", ".join(f"{k} {v}" for k, v in outcomes.items()))
            if completed and settle > SETTLEMENT_SPREAD:
                why.append(f"settlement spread {100 * settle:.2g} % > {100 * SETTLEMENT_SPREAD:g} %")
        else:
            if end > ENDING_SPREAD:
                why.append(f"ending lambda spread {100 * end:.2g} % > {100 * ENDING_SPREAD:g} %")
            if lim > LIMIT_SPREAD:
                why.append(f"limit spread {100 * lim:.2g} % > {100 * LIMIT_SPREAD:g} %")
        out.append(Spread(n, within, outcomes, settle, end, lim, not why, "; ".join(why)))
    return out
