"""The ensemble checks of issue 45 (ssi.lab.zoo_ensemble) on hand-made runs whose verdicts are worked out
by hand in each test, and the stored table's round trip through the project's reference format."""

import math

from ssi.lab.digitize import write_reference
from ssi.lab.zoo_ensemble import (
    path_reach,
    read_zoo_ensemble,
    roundoff_outcomes,
    service_completes,
    within_capacity,
)

NAN = math.nan


def run(scene, copy, status, lam, limit=NAN, settlement=NAN, backend="superlu", cpu="native (x)"):
    return {
        "scene": scene,
        "copy": copy,
        "backend": backend,
        "cpu": cpu,
        "status": status,
        "load_factor": lam,
        "limit": limit,
        "settlement_m": settlement,
        "message": f"{status} at {lam}",
    }


def test_within_capacity_is_one_at_most_097_lb_davis():
    assert within_capacity(1.0 / 0.97)  # exactly on the margin: 0.97 * LB = 1
    assert not within_capacity(1.0 / 0.97 - 1e-9)
    assert not within_capacity(NAN)  # an uncertified floor says nothing


def test_service_completes_lists_every_run_that_did_not_complete():
    runs = {
        "a": [run("a", "drawn", "completed", 1.0, settlement=0.1), run("a", "1+1e-13", "failed", 0.7)],
        "b": [run("b", "drawn", "failed", 0.3)],  # beyond capacity: not eligible
        "c": [run("c", "drawn", "completed", 1.0, settlement=0.2)],
    }
    eligible, failures = service_completes(runs, {"a": 2.0, "b": 0.5, "c": 1.5})
    assert eligible == ["a", "c"]
    assert [f[0] for f in failures] == ["a copy 1+1e-13 superlu native"]
    assert failures[0][1:3] == ("failed", 0.7)


def test_path_reach_counts_the_scene_as_drawn_against_min_one_and_09_lb_davis():
    runs = {
        # target min(1, 0.9 * 0.5) = 0.45: a limit at 0.46 whose path ended at 0.40 after the peak reaches it
        "peak": [run("peak", "drawn", "limit load reached", 0.40, limit=0.46)],
        # target 0.45: stopped at 0.44 does not
        "stop": [run("stop", "drawn", "failed", 0.44), run("stop", "1+1e-13", "failed", 0.6)],
        # target 1 (0.9 * 3 > 1): completed
        "done": [run("done", "drawn", "completed", 1.0, settlement=0.1)],
        # the generic-CPU run is not the as-drawn SuperLU native one: missing, so below
        "gen": [run("gen", "drawn", "completed", 1.0, cpu="generic")],
    }
    fraction, below = path_reach(runs, {"peak": 0.5, "stop": 0.5, "done": 3.0, "gen": 3.0})
    assert fraction == 0.5
    assert [b[0] for b in below] == ["stop", "gen"]
    assert below[0][1:4] == (0.44, 0.45, "failed")


def test_roundoff_outcomes_within_and_beyond_capacity():
    runs = {
        # within capacity, all completed, settlements 0.100 and 0.1012: spread 1.2e-3/0.1012 = 1.19 % > 1 %
        "w1": [
            run("w1", "drawn", "completed", 1.0, settlement=0.100),
            run("w1", "1+1e-13", "completed", 1.0, settlement=0.1012),
        ],
        # within capacity, 0.5 % apart: holds
        "w2": [
            run("w2", "drawn", "completed", 1.0, settlement=0.200),
            run("w2", "1+1e-13", "completed", 1.0, settlement=0.201),
        ],
        # within capacity, one copy stops: outcomes differ
        "w3": [run("w3", "drawn", "completed", 1.0, settlement=0.1), run("w3", "1-1e-13", "failed", 0.9)],
        # beyond: limits 0.500 and 0.504 (0.79 %), a stop at 0.490: ending spread 0.014/0.504 = 2.8 %: holds
        "b1": [
            run("b1", "drawn", "limit load reached", 0.45, limit=0.500),
            run("b1", "1+1e-13", "limit load reached", 0.47, limit=0.504),
            run("b1", "1-1e-13", "failed", 0.490),
        ],
        # beyond: limits 0.50 and 0.51 (1.96 % > 1 %), endings within 5 %
        "b2": [
            run("b2", "drawn", "limit load reached", 0.5, limit=0.50),
            run("b2", "1+1e-13", "limit load reached", 0.5, limit=0.51),
        ],
        # beyond: stops at 0.2 and 0.3: ending spread 33 % > 5 %
        "b3": [run("b3", "drawn", "failed", 0.2), run("b3", "1+1e-13", "failed", 0.3)],
    }
    lb = {"w1": 2.0, "w2": 2.0, "w3": 2.0, "b1": 0.6, "b2": 0.6, "b3": 0.6}
    by = {s.scene: s for s in roundoff_outcomes(runs, lb)}
    assert {n for n, s in by.items() if s.ok} == {"w2", "b1"}
    assert math.isclose(by["w1"].settlement, 0.0012 / 0.1012)
    assert "settlement" in by["w1"].why
    assert "outcomes differ" in by["w3"].why
    assert math.isclose(by["b1"].ending, 0.014 / 0.504) and math.isclose(by["b1"].limit, 0.004 / 0.504)
    assert "limit spread" in by["b2"].why
    assert "ending lambda spread" in by["b3"].why


def test_stored_table_reads_back_with_text_copies_and_empty_numbers(tmp_path):
    meta = {
        "source": "test",
        "figure": "test",
        "units": "-",
        "trust": "B (test)",
        "uncertainty": "none",
        "how_obtained": "by hand",
    }
    columns = {
        "scene": ["random 1", "random 1"],
        "copy": ["drawn", "1+1e-13"],
        "backend": ["superlu", "superlu"],
        "cpu": ["native (x)", "generic"],
        "status": ["completed", "failed"],
        "load_factor": ["1", "0.5"],
        "limit": ["", ""],
        "settlement_m": ["0.25", ""],
        "wall_s": ["1.0", "2.0"],
        "message": ["completed", "stopped"],
    }
    path = tmp_path / "ens.csv"
    write_reference(path, meta, columns)
    got_meta, runs = read_zoo_ensemble(path)
    assert got_meta["how_obtained"] == "by hand"
    first, second = runs["random 1"]
    assert first["copy"] == "drawn" and second["copy"] == "1+1e-13"
    assert first["settlement_m"] == 0.25 and math.isnan(second["settlement_m"])
    assert math.isnan(first["limit"]) and second["load_factor"] == 0.5


def test_zoo_outcome_settlement_is_the_results_largest_settlement_at_lambda_one():
    from ssi.lab.zoo import random_scenes, solve_zoo
    from ssi.solver import Settings

    name, scene = random_scenes(10, seed=1)[9]  # completes in 5 steps (stored table: 0.06 s)
    (o,) = solve_zoo([(name, scene)], Settings(control="work"))
    out = scene.build().solve(settings=Settings(control="work"))
    assert o.status == "completed" and out.load_factor[-1] == 1.0
    _, w = out.settlement()  # every foundation node's settlement at lambda = 1, positive down
    assert o.settlement == w.max() > 0.0
