"""The controlled path's fallback where its corrector stalls (ssi.solver.relax, issue 45): damped dynamics
on K0 at a fixed load leave a saddle and come to rest on a stable equilibrium."""

import numpy as np
import pytest

from ssi.solver.relax import relax

# A two-unknown system with a saddle: the potential P(x, y) = -x^2 / 2 + x^4 / 4 + y^2 / 2 + 0.3 x y (no
# load). Its equilibria (grad P = 0, y = -0.3 x): the saddle (0, 0), whose Hessian [[-1, 0.3], [0.3, 1]] has
# a negative eigenvalue -- as the non-associated tangent past a bifurcation -- and the two minima
# x = +-sqrt(1.09), y = -0.3 x (Hessian [[2.27, 0.3], [0.3, 1]], positive definite).
K0 = np.array([[3.0, 0.3], [0.3, 1.0]])  # SPD, stiffer than the tangent near the equilibria (the "elastic"
# operator); the dynamics' mass and preconditioner
TOL = 1e-10  # |r|: far below any distance between the equilibria (~1), so reaching it means reaching one


def _residual(u):
    x, y = u
    return -np.array([-x + x**3 + 0.3 * y, y + 0.3 * x])


def _hessian(u):
    return np.array([[-1.0 + 3.0 * u[0] ** 2, 0.3], [0.3, 1.0]])


START = np.array([1e-4, 0.02])  # near the saddle, out of balance (|r| ~ 2e-2)


def _run(u0, **kw):
    return relax(
        u0.copy(),
        lambda u: (_residual(u), float(np.linalg.norm(_residual(u))), None),
        lambda r: np.linalg.solve(K0, r),
        lambda rel, energy, it, u, data: rel <= TOL,
        **kw,
    )


def test_newton_from_the_start_converges_to_the_saddle():
    """Why the fallback exists: Newton on the consistent tangent from this start settles on the saddle, the
    state the controlled path's corrector sits on at a stall."""
    u = START.copy()
    for _ in range(30):
        u = u + np.linalg.solve(_hessian(u), _residual(u))
    assert np.linalg.norm(u) < 1e-12


def test_relaxation_leaves_the_saddle_for_a_stable_equilibrium():
    run = _run(START)
    assert run.converged and run.residuals[-1] <= TOL
    x, y = run.u
    assert abs(abs(x) - np.sqrt(1.09)) < 1e-9 and abs(y + 0.3 * x) < 1e-9  # a minimum, not the saddle
    assert np.all(np.linalg.eigvalsh(_hessian(run.u)) > 0.0)  # stable: the tangent positive definite there
    assert np.linalg.norm(_residual(run.u)) <= TOL  # an independent evaluation of the accepted state


def test_relaxation_without_an_unstable_component_stays_on_the_saddle():
    """From a start whose only error lies along the saddle's stable direction (x = 0 exactly, so no
    unstable component at all to grow), the dynamics converge to the saddle: an exact equilibrium, and
    the caller's test accepts it -- the relaxation adds no preference of its own beyond leaving unstable
    states that round-off or the start perturb."""
    run = _run(np.array([0.0, 0.02]))
    assert run.converged and np.linalg.norm(run.u) <= 1e-9


def test_no_equilibrium_is_no_convergence():
    """Beyond a limit there is nothing to find: a load of 2 on a resistance tanh(u) <= 1 (K0 = 1). The
    relaxation ends (stagnation) and says so; it never returns a state as converged."""
    run = relax(
        np.zeros(1),
        lambda u: (np.array([2.0 - np.tanh(u[0])]), abs(2.0 - np.tanh(u[0])), None),
        lambda r: r.copy(),
        lambda rel, energy, it, u, data: rel <= TOL,
        window=50,
    )
    assert not run.converged and "stagnates" in run.reason and run.iterations < 4000


def test_a_failed_evaluation_ends_the_relaxation():
    run = relax(np.ones(1), lambda u: None, lambda r: r, lambda *a: False)
    assert not run.converged and run.reason == "material update failed" and run.iterations == 1


@pytest.mark.parametrize("beta", [0.0, 0.95])
def test_a_balanced_start_is_accepted_at_once(beta):
    run = relax(
        np.zeros(2), lambda u: (np.zeros(2), 0.0, "data"), lambda r: r, lambda rel, *a: rel <= TOL, beta=beta
    )
    assert run.converged and run.iterations == 1 and run.data == "data"
