"""The incremental-iterative solver (paper §8) on problems whose answers are known in closed form: nonlinear
springs (``ssi.elements.spring``) and a linear Q8 block; plus the HDF5 result files.

Expected values come from the laws' closed forms (atanh of the load, the hardening rule), from finite
differences, or from the direct linear solve -- never from the solver under test.
"""

import numpy as np
import pytest

from ssi.core.mesh import structured_q8
from ssi.core.model import Model
from ssi.core.protocol import CONSISTENT, K0_MATRIX
from ssi.elements.spring import ELASTOPLASTIC, LINEAR, TANH, Spring
from ssi.elements.supports import fix_block, soil_group, spring_chain
from ssi.io.results import read_result, write_result
from ssi.lab.verify import fd_jacobian, residual_order
from ssi.materials.soil_laws import ELASTIC as SOIL_ELASTIC
from ssi.materials.soil_laws import elastic_params
from ssi.solver import METHODS, NonConvergence, Settings, run

K0, FU = 1e6, 1e3  # spring stiffness [N/m], tanh plateau [N]


# ---- the spring group itself ----------------------------------------------------------------------------
@pytest.mark.parametrize(
    "kind, params, d0, dd",
    [
        (TANH, [K0, FU, 0.0], 7e-4, 7e-4),  # tanh, on the softening part
        (ELASTOPLASTIC, [K0, FU, 2e5], 5e-4, 5e-4),  # elastic branch
        (ELASTOPLASTIC, [K0, FU, 2e5], 2e-3, 2e-3),  # plastic branch (loading)
        (ELASTOPLASTIC, [K0, FU, 2e5], -2e-3, -2e-3),  # plastic branch, compression
    ],
)
def test_spring_tangent_matches_finite_differences(kind, params, d0, dd):
    g = Spring([[0, 1]], kind, params)
    st = g.initial_state()
    h = 1e-9  # central differences: truncation ~h^2 F''' negligible, round-off ~1e-16 F / h ~ 1e-4 N/m

    def force(delta):
        u = np.array([[0.0, d0 + delta]])
        du = np.array([[0.0, dd + delta]])
        return g.evaluate(u, du, st, CONSISTENT)

    f, k, _ = force(0.0)
    fd = fd_jacobian(lambda d: force(d[0])[0][0, 1], [0.0], h)[0, 0]
    assert abs(k[0, 1, 1] - fd) < 1e-6 * K0
    assert np.allclose(k[0], k[0, 1, 1] * np.array([[1, -1], [-1, 1]]))
    assert abs(f[0, 0] + f[0, 1]) == 0.0  # action = reaction
    assert np.allclose(g.evaluate(np.zeros((1, 2)), np.zeros((1, 2)), st, K0_MATRIX)[1][0, 1, 1], K0)


def test_spring_bad_input():
    with pytest.raises(ValueError, match="k0"):
        Spring([[0, 1]], TANH, [0.0, 1.0, 0.0])
    with pytest.raises(ValueError, match="F_u"):
        Spring([[0, 1]], TANH, [1.0, -1.0, 0.0])
    with pytest.raises(ValueError, match="kinds"):
        Spring([[0, 1]], 7, [1.0, 1.0, 0.0])


# ---- solver ---------------------------------------------------------------------------------------------
def test_linear_problem_converges_in_one_iteration():
    """A linear scene: one correction lands on the solution (the second evaluation only confirms it) and
    equals the direct solve."""
    m = structured_q8(np.linspace(0, 2, 5), np.linspace(-1, 0, 3))
    model = Model()
    model.add_nodes(m.xy, 2)
    soil_group(model, m, [(SOIL_ELASTIC, elastic_params(20e6, 0.3))])
    fix_block(model, m, sides=False)
    model.add_load(m.surface, "w", -1e4)
    model.prescribe(m.surface[:1], "u", 1e-4)
    direct = model.solve_linear().u[-1]
    for method in ("bfgs", "modified", "full"):
        res = run(model, [0.5, 1.0], Settings(method=method, stepping="fixed"))
        assert all(len(r) == 2 for r in res.residuals[1:])  # one solve per step
        assert all(r[1] < 1e-12 for r in res.residuals[1:])  # ... already at round-off
        assert np.abs(res.u[-1] - direct).max() < 1e-10 * np.abs(direct).max()
        assert np.abs(res.u[1] - 0.5 * direct).max() < 1e-10 * np.abs(direct).max()
    assert res.factorizations >= 1


def test_tanh_spring_load_control_and_convergence_orders():
    """F_u tanh(k0 d / F_u) = 0.9 F_u has d = atanh(0.9) F_u / k0. Full Newton converges quadratically,
    modified Newton (K0) linearly with the contraction 1 - k_T / k0 at the solution."""
    model, _, nodes = spring_chain([TANH], [K0, FU, 0.0])
    model.add_load(nodes[-1], "u", 0.9 * FU)
    exact = np.arctanh(0.9) * FU / K0
    orders = {}
    for method in ("bfgs", "modified", "full"):
        res = run(
            model,
            [1.0],
            Settings(method=method, stepping="fixed", force_tol=1e-12, energy_tol=1e-12, max_iter=400),
        )
        assert abs(res.displacement(nodes[-1], "u")[-1, 0] - exact) < 1e-9 * exact
        orders[method], n_pairs = residual_order(res.residuals[1])
        assert n_pairs >= 3
    # tolerances: the asymptotic orders are 2 and 1; the fit over the last few iterates is within ~0.2
    assert orders["full"] > 1.8, orders
    assert abs(orders["modified"] - 1.0) < 0.05, orders
    # BFGS on the one K0 factorisation: superlinear (a secant method's order is between 1 and 2)
    assert 1.3 < orders["bfgs"] < 2.0, orders


def test_phase_continuation_matches_one_path():
    """A second phase that starts from the first one's converged state and carries the first phase's load as
    dead load ends where one path to the total load ends (tanh spring: d = atanh(0.9) F_u / k0)."""
    model, _, nodes = spring_chain([TANH], [K0, FU, 0.0])
    model.add_load(nodes[-1], "u", 0.5 * FU)
    first = run(model, [0.5, 1.0], Settings(method="full", force_tol=1e-10))
    f_half, _ = model.load_vectors()
    second = run(
        model, [0.5, 1.0], Settings(method="full", force_tol=1e-10), start=first, loads=(0.8 * f_half, f_half)
    )  # 0.5 F_u already on, 0.4 F_u added
    exact = np.arctanh(0.9) * FU / K0
    assert abs(second.displacement(nodes[-1], "u")[-1, 0] - exact) < 1e-8 * exact
    assert np.array_equal(second.u[0], first.u[-1])  # step 0 of the phase is the previous end
    with pytest.raises(ValueError, match="loads"):
        run(model, [1.0], start=first, loads=(f_half[:-1], f_half))


def test_untrustworthy_tangent_solve_falls_back_to_k0(monkeypatch):
    """A tangent factorisation whose correction does not satisfy K_T du = r (what SuperLU can return after
    BLAS refused a call on a nearly singular matrix) is refused: the increment goes on with K0, linearly
    convergent, to the same closed-form answer -- never on the garbage correction."""
    import ssi.solver.increment as solver_module  # where the tangent is factorised and solved

    class Garbled(solver_module.Factorization):
        """K0 (factorised with spd=True) solves correctly; every tangent solve is off."""

        def __init__(self, matrix, symmetric=True, backend="auto", spd=False):
            super().__init__(matrix, symmetric, backend, spd)
            self.garble = not spd

        def solve(self, rhs):
            x = super().solve(rhs)
            return 0.37 * x + 1e-3 if self.garble else x

    model, _, nodes = spring_chain([TANH], [K0, FU, 0.0])
    model.add_load(nodes[-1], "u", 0.9 * FU)
    exact = np.arctanh(0.9) * FU / K0
    calls = []
    original = solver_module._tangent_solve

    def spy(*args):
        calls.append(original(*args))
        return calls[-1]

    monkeypatch.setattr(solver_module, "_tangent_solve", spy)
    monkeypatch.setattr(solver_module, "Factorization", Garbled)
    res = run(model, [1.0], Settings(method="full", force_tol=1e-10, energy_tol=1e-12, max_iter=400))
    assert calls and all(c is None for c in calls)  # every tangent correction was refused
    assert abs(res.displacement(nodes[-1], "u")[-1, 0] - exact) < 1e-8 * exact
    assert abs(residual_order(res.residuals[1])[0] - 1.0) < 0.05  # K0 iterations: linear, as modified Newton


def test_displacement_control_and_committed_plastic_state():
    """Elastoplastic spring (k0, F_y, H) driven by a prescribed elongation d up to 3 d_y and back to 0: the
    reaction follows the bilinear law on loading and unloads with k0; the state is committed per step."""
    fy, h = FU, 2e5
    model, _, nodes = spring_chain([ELASTOPLASTIC], [K0, fy, h])
    dy = fy / K0
    model.prescribe(nodes[-1], "u", dy)
    path = [0.5, 1.0, 2.0, 3.0, 2.0, 1.0, 0.0]
    res = run(model, path, Settings(method="full", stepping="fixed"))
    f = res.reaction(nodes[-1], "u")
    kep = K0 * h / (K0 + h)
    f_peak = fy + kep * 2 * dy
    kappa_peak = 3 * dy - f_peak / K0  # plastic elongation = total - elastic at the peak
    # back to 0: the elastic trial f_peak - 3 k0 d_y passes the hardened reverse yield force
    # -(F_y + H kappa_peak) by `over`, and plastic flow of over / (k0 + H) brings it back to the surface
    over = -(f_peak - 3 * K0 * dy) - (fy + h * kappa_peak)
    f_back = -(fy + h * (kappa_peak + over / (K0 + h)))
    expected = [0.0, 0.5 * fy, fy, fy + kep * dy, f_peak, f_peak - K0 * dy, f_peak - 2 * K0 * dy, f_back]
    assert over > 0
    assert np.allclose(f, expected, rtol=1e-9, atol=1e-9 * fy)
    assert abs(res.states[-2][0][0, 0, 1] - kappa_peak) < 1e-12  # elastic unloading keeps kappa
    assert abs(res.final_state[0][0, 0, 1] - (kappa_peak + over / (K0 + h))) < 1e-12


def test_step_cutting_recovers():
    """Modified Newton contracts the residual by 1 - k_T/k0 per iteration (0.81 at 0.9 F_u): one step to
    0.9 F_u needs ~45 iterations. Capped at 30 it must cut the step, and smaller steps (which start with a
    smaller residual) then converge; the answer is still the exact one."""
    model, _, nodes = spring_chain([TANH], [K0, FU, 0.0])
    model.add_load(nodes[-1], "u", 0.9 * FU)
    res = run(model, [1.0], Settings(method="modified", stepping="fixed", max_iter=30, max_cuts=10))
    assert res.cuts > 0 and res.n_steps > 1
    assert max(res.iterations) <= 30
    # force_tol 1e-5 on a tangent k_T = 0.19 k0 gives a displacement error ~5e-5 relative
    exact = np.arctanh(0.9) * FU / K0
    assert abs(res.displacement(nodes[-1], "u")[-1, 0] - exact) < 1e-4 * exact
    assert np.all(np.diff(res.load_factor) > 0) and res.load_factor[-1] == 1.0


def test_load_control_above_capacity_is_nonconvergence_never_a_limit():
    """1.2 F_u exceeds the tanh spring's capacity F_u: the path flattens at F_u and load control cannot pass
    it. Each method ends in NonConvergence -- never "limit load reached" -- with the converged path up to
    where it stopped (within 1 % of 1/1.2: the steps are halved down to ``min_step`` = 1e-4 of the load), the
    path's current stiffness there (1 - tanh^2, far below the initial one) and a hint to the controlled path.
    The controlled path, the default, is what finds the limit (tests/test_solver_path.py)."""
    model, _, nodes = spring_chain([TANH], [K0, FU, 0.0])
    model.add_load(nodes[-1], "u", 1.2 * FU)
    for method in METHODS:
        with pytest.raises(NonConvergence) as info:
            run(model, [1.0], Settings(method=method))
        res, rep = info.value.result, info.value.report
        assert res.status == "stopped" and not res.collapsed and res.limit_load_factor is None, method
        assert 0.99 < res.load_factor[-1] * 1.2 <= 1.0, (method, res.load_factor[-1])
        assert rep["current_stiffness"] < 0.05, (method, rep["current_stiffness"])
        assert "control='work'" in rep["hint"]
        # every step of the returned path is converged: F_u tanh(k0 d / F_u) = lambda 1.2 F_u
        d = res.displacement(nodes[-1], "u")[:, 0]
        assert np.allclose(FU * np.tanh(K0 * d / FU), 1.2 * FU * np.array(res.load_factor), rtol=1e-4)


def test_nonconvergence_raises_with_report():
    """An increment that cannot converge while the path is still stiff (two K0 iterations allowed for a
    nonlinear spring) is a failure, not a collapse: the error says what, where and at which load, and keeps
    the converged steps for inspection."""
    model, _, nodes = spring_chain([TANH], [K0, FU, 0.0])
    model.add_load(nodes[-1], "u", 0.9 * FU)
    with pytest.raises(NonConvergence) as info:
        run(model, [1.0], Settings(method="modified", stepping="fixed", max_iter=2, max_cuts=4))
    rep = info.value.report
    assert {"reason", "load_factor_from", "load_factor_to", "worst_node", "worst_component"} <= set(rep)
    assert rep["worst_node"] == nodes[-1] and rep["worst_component"] == "u"
    assert "spring" in rep["worst_groups"]
    assert "did not converge" in str(info.value)
    assert info.value.result.load_factor[-1] < 1.0 and info.value.result.status == "stopped"


def test_settings_control_rule():
    """The default is the controlled path; naming a load-control algorithm (a method, fixed stepping) asks
    for load control, as the paper's settings do; a load-control option on the controlled path is an
    error naming it; the removed fallback options are unknown fields."""
    assert Settings().control == "work" and Settings().method is None
    assert Settings(method="modified").control == "load"
    assert Settings(method="bfgs").control == "load"
    assert Settings(stepping="fixed").control == "load" and Settings(stepping="fixed").method == "bfgs"
    assert Settings(control="load").method == "bfgs" and Settings(control="load").line_search
    assert Settings.paper().control == "load" and Settings.paper().method == "modified"
    assert Settings(flow="davis").control == "work"
    with pytest.raises(ValueError, match="Settings.method='full'.*control='load'"):
        Settings(method="full", control="work")
    with pytest.raises(ValueError, match="Settings.stepping='fixed'"):
        Settings(stepping="fixed", control="work")
    for removed in ("viscosity", "viscous_fallback", "fallback", "fallback_iter", "collapse_stiffness"):
        with pytest.raises(TypeError, match=removed):
            Settings(**{removed: 1})


def test_settings_validation():
    with pytest.raises(ValueError, match="method"):
        Settings(method="secant-ish")
    with pytest.raises(ValueError, match="force_tol"):
        Settings(force_tol=0.0)
    model, _, _ = spring_chain([LINEAR], [K0, 0.0, 0.0])
    with pytest.raises(ValueError, match="load_factors"):
        run(model, [])


# ---- results files --------------------------------------------------------------------------------------
def test_hdf5_round_trip_and_no_overwrite(tmp_path):
    model, _, nodes = spring_chain([ELASTOPLASTIC, TANH], [[K0, FU, 1e5], [2 * K0, 2 * FU, 0.0]])
    model.add_load(nodes[-1], "u", 1.5 * FU)
    settings = Settings(method="full")
    res = run(model, [0.5, 1.0], settings)
    path = tmp_path / "spring.h5"
    write_result(path, res, settings)
    back = read_result(path)  # a bare model: the arrays as stored (StoredResult)
    assert np.array_equal(back.u, np.array(res.u))
    assert np.array_equal(back.load_factor, np.array(res.load_factor))
    assert np.array_equal(back.coords, model.coords)
    assert np.array_equal(np.stack([s[0] for s in back.states]), np.stack([s[0] for s in res.states]))
    assert back.model["n_dof"] == model.n_dof and back.info["settings"]["method"] == "full"
    assert back.model["groups"][0]["kinds"][:2] == ["elastoplastic", "tanh"]
    with pytest.raises(FileExistsError):
        write_result(path, res, settings)
    write_result(path, res, settings, overwrite=True)  # allowed when asked
    # a linear result round-trips too
    lin_model, _, lin_nodes = spring_chain([LINEAR], [K0, 0.0, 0.0])
    lin_model.add_load(lin_nodes[-1], "u", FU)
    lin = lin_model.solve_linear()
    write_result(tmp_path / "lin.h5", lin)
    assert np.array_equal(read_result(tmp_path / "lin.h5").u, np.array(lin.u))
    assert abs(lin.displacement(lin_nodes[-1], "u")[-1, 0] - FU / K0) < 1e-12


def test_old_convergence_measure_accepted_a_wrong_state_the_structural_one_does_not():
    """A light footing (10 kN/m) on a deep (60 m), soft, heavy sand block: the geostatic forces dwarf the
    structural load. The old measure (``convergence_reference="total"``: force relative to max(|F_ext|,
    |F_int|), energy relative to |u . F_int|, geostatic state included) accepts a state whose settlement is
    0.1 % off; the structural measure, with the same tolerances, lands within 1e-4. The reference is the same
    scene converged 1e4 times tighter (force_tol 1e-9)."""
    from ssi.lab.zoo import light_footing_on_deep_block

    scene = light_footing_on_deep_block()

    def settlement(**kw):
        return scene.build().solve(settings=Settings(**kw)).max_settlement()[1]

    reference = settlement(force_tol=1e-9, energy_tol=1e-16)
    old = settlement(convergence_reference="total")
    new = settlement()
    assert abs(old / reference - 1) > 5e-4, old / reference - 1
    assert abs(new / reference - 1) < 1e-4, new / reference - 1


def _two_loop_reference(pairs, solve, r):
    """Nocedal's recursion over the (s, y) pairs, oldest first, in numpy (what ssi.solver.lbfgs must
    reproduce)."""
    q = r.copy()
    alphas = []
    for s, y in reversed(pairs):
        a = (1.0 / float(s @ y)) * (s @ q)
        q -= a * y
        alphas.append(a)
    z = solve(q)
    for (s, y), a in zip(pairs, reversed(alphas)):
        z += (a - (1.0 / float(s @ y)) * (y @ z)) * s
    return z


def test_lbfgs_ring_buffer_gives_the_numpy_two_loop_bit_for_bit():
    """The numba two loops over ring buffers: the same direction as the list-based recursion, also once the
    ring has wrapped (7 pairs in a memory of 3) and after a pair with s . y <= 0 cleared the memory."""
    from ssi.solver.increment import _Lbfgs

    rng = np.random.default_rng(3)
    n = 257
    scale = rng.uniform(0.5, 2.0, n)

    class Diagonal:  # stands in for the K0 factorisation
        def solve(self, b):
            return b / scale

    lbfgs, kept = _Lbfgs(Diagonal(), memory=3), []
    for k in range(9):
        s = rng.normal(size=n)
        y = s * scale + 0.1 * rng.normal(size=n)
        if k == 5:
            y = -y  # s . y < 0: the memory is cleared
        lbfgs.update(s, y)
        kept = [] if k == 5 else (kept + [(s, y)])[-3:]
        r = rng.normal(size=n)
        expected = _two_loop_reference(kept, Diagonal().solve, r)
        assert np.array_equal(lbfgs.direction(r), expected)
    assert lbfgs.count == 3


def test_every_method_has_one_direction_function():
    """The increment's table of search directions has a row for every method Settings accepts, and no
    other: a method without a row would fail with a KeyError in its first increment."""
    from ssi.solver.increment import DIRECTIONS

    assert sorted(DIRECTIONS) == sorted(METHODS)
    assert len(set(DIRECTIONS.values())) == len(METHODS)  # one function each
