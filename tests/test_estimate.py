"""Error estimates (ssi.studies.estimate): Richardson analysis against sequences whose limit and order are
known, refined copies that keep what they must keep, and the estimate of a linear scene."""

import math
from dataclasses import replace

import numpy as np
import pytest

from ssi.elements.section import homogeneous
from ssi.lab.zoo import rc_strip
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer
from ssi.solver import Settings
from ssi.studies.estimate import (
    Level,
    RefinedSolver,
    estimate,
    refined_scene,
    refined_steps,
    richardson,
    solve_to_target,
    solve_with_error,
    split_section,
)


def linear_scene(h_fine=1.0):
    return Scene(
        width=12.0,
        depth=6.0,
        layers=[SoilLayer(2.0, E=20e6, nu=0.3), SoilLayer(4.0, E=60e6, nu=0.3)],
        foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9),
        loads=[ColumnLoad(x=0.0, N=300e3)],
        mesh=MeshSize(h_fine=h_fine, h_coarse=4.0, growth=1.5),
    )


@pytest.mark.parametrize("p", [1.0, 2.0, 3.5])
def test_richardson_recovers_order_and_errors_of_a_power_law(p):
    exact, c, h = 3.0, 0.7, 0.4
    q = [exact + c * (h / 2**i) ** p for i in range(3)]
    r = richardson(*q, noise=0.0)
    assert r.order == pytest.approx(p, rel=1e-10)
    assert r.error_base == pytest.approx(q[0] - exact, rel=1e-9)
    assert r.error_fine == pytest.approx(q[2] - exact, rel=1e-9)
    assert r.extrapolated == pytest.approx(exact, rel=1e-12)
    assert r.asymptotic


def test_richardson_flags_oscillation_and_a_too_small_order():
    assert not richardson(1.0, 1.1, 1.05, noise=0.0).asymptotic  # the differences change sign
    assert not richardson(1.0, 1.1, 1.19, noise=0.0).asymptotic  # p = 0.15: hardly converging
    exact = richardson(2.0, 2.0, 2.0)
    assert exact.asymptotic and exact.error_base == 0.0


def test_richardson_noise_floor_bounds_the_error_by_the_differences():
    r = richardson(1.0, 1.0 + 2e-4, 1.0 - 1e-4)  # iteration-error noise
    assert r.asymptotic and math.isnan(r.order)
    assert r.error_base == pytest.approx(1.0 - (1.0 - 1e-4))


def test_richardson_rejects_bad_input():
    with pytest.raises(ValueError, match="ratio"):
        richardson(1.0, 2.0, 3.0, ratio=1.0)
    with pytest.raises(ValueError, match="finite"):
        richardson(1.0, math.nan, 3.0)


def test_split_section_keeps_the_section_stiffness():
    sec = rc_strip()
    fine = split_section(sec, 2)
    assert fine.n_layer == 2 * sec.n_layer
    assert fine.thickness == pytest.approx(sec.thickness)
    a, b = sec.elastic_resultant_stiffness(), fine.elastic_resultant_stiffness()
    for k in ("A", "B", "D", "S"):  # the rectangular rule with its h^2/12 term is exact for each layer
        assert b[k] == pytest.approx(a[k], rel=1e-12, abs=1e-6 * abs(a["A"]))
    assert list(fine.kind[::2]) == list(sec.kind[np.argsort(sec.z_mid)])


def test_refined_copies_do_not_change_the_scene():
    scene = linear_scene()
    fine = refined_scene(scene, mesh=2, layers=1)
    assert fine.mesh.h_fine == pytest.approx(0.25) and fine.mesh.h_coarse == pytest.approx(1.0)
    assert fine.foundation.section.n_layer == 2
    assert scene.mesh.h_fine == 1.0 and scene.foundation.section.n_layer == 1
    n, s = refined_steps(10, Settings(), 1)
    assert n == 20 and s.max_step == pytest.approx(Settings().max_step / 2)
    with pytest.raises(ValueError, match="mesh=-1"):
        refined_scene(scene, mesh=-1)


def test_linear_scene_has_no_step_or_layer_error_and_a_mesh_error():
    est = estimate(linear_scene())
    assert set(est.parts) == {"mesh", "steps", "layers"}
    for q in est.value:
        assert est.parts["steps"][q].error_base == 0.0  # one linear solve per level
        assert abs(est.parts["layers"][q].error_base) <= 1e-8 * abs(est.value[q])
    assert est.error["max_settlement"] > 0.0
    # the estimate is of the right size: the finest mesh solved (h/4) differs from the base by about it
    q0, _, q2 = est.parts["mesh"]["max_settlement"].values
    assert 0.5 < est.error["max_settlement"] / abs(q2 - q0) < 2.0
    assert "max_settlement" in str(est)


def test_solve_with_error_returns_the_base_result():
    out, est = solve_with_error(linear_scene(), refine=("mesh",))
    assert out.max_settlement()[1] == est.value["max_settlement"]


def test_solve_to_target_refines_until_the_estimate_is_below_it():
    res = solve_to_target(linear_scene(), target_error=0.03, refine=("mesh",))
    assert res.met, res.message
    assert res.estimate.relative["max_settlement"] > 0.03  # the scene as given does not meet it
    assert res.key[0] >= 1 and res.predicted["max_settlement"] <= 0.03
    # the delivered answer is within the target of the finest level the estimate solved (h/4) and beyond
    finest = res.estimate.parts["mesh"]["max_settlement"].extrapolated
    got = res.result.max_settlement()[1]
    assert abs(got - finest) / abs(finest) <= 0.03


def test_solve_to_target_rejects_bad_input():
    with pytest.raises(ValueError, match="target_error"):
        solve_to_target(linear_scene(), target_error=0.0)
    with pytest.raises(ValueError, match="refine"):
        estimate(linear_scene(), refine=("time",))
    with pytest.raises(ValueError, match="quantities"):
        solve_to_target(
            replace(linear_scene(), foundation=None, contact=None, loads=[]),
            quantities=("max_moment",),
            refine=("mesh",),
        )


def _synthetic(monkeypatch, value_at_mesh_level):
    """Replace the solves by answers q(mesh level) with a wall time growing 4x per halving (no FE solve)."""

    def call(self, key):
        if key not in self.cache:
            self.cache[key] = Level(
                key, {"max_settlement": value_at_mesh_level(key[0])}, 4.0 ** key[0], 10, "completed", None
            )
        return self.cache[key]

    monkeypatch.setattr(RefinedSolver, "__call__", call)


def test_solve_to_target_refuses_an_oscillating_sequence(monkeypatch):
    _synthetic(monkeypatch, lambda m: [1.0, 1.1, 1.05, 1.07, 1.06][m])
    with pytest.warns(RuntimeWarning, match="not in the asymptotic range"):
        res = solve_to_target(linear_scene(), target_error=0.02, refine=("mesh",))
    assert res.status == "not asymptotic" and not res.met and res.key == (0, 0, 0)


def test_solve_to_target_picks_the_halvings_a_power_law_needs(monkeypatch):
    # q = 1 + 0.4 (h/h0)^1: the relative error of level j is 0.4 2^-j / 1.4, below 2 % from j = 4 on
    _synthetic(monkeypatch, lambda m: 1.0 + 0.4 * 2.0**-m)
    with pytest.warns(RuntimeWarning, match="max_halvings"):
        assert solve_to_target(linear_scene(), 0.02, refine=("mesh",)).status == "limit of refinements"
    res = solve_to_target(linear_scene(), 0.02, refine=("mesh",), max_halvings=5)
    assert res.met and res.key == (4, 0, 0)
    assert res.predicted["max_settlement"] == pytest.approx(0.4 / 16 / 1.4, rel=1e-9)
