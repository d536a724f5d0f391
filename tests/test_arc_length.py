"""Arc-length continuation: exact on a linear problem, and it levels off at the plastic limit load of a
Tresca footing instead of failing there as load control does."""

import numpy as np
import pytest

from ssi.core.mesh import structured_q8
from ssi.core.model import Model
from ssi.elements.supports import fix_block, soil_group, surface_pressure
from ssi.materials.soil_laws import elastic_params, von_mises_params
from ssi.solver import Settings, run, run_arc_length

PRANDTL = 2.0 + np.pi  # q_u / c_u of a smooth strip footing on weightless Tresca soil


def footing(kind, params, q_ref):
    """Half of a flexible strip footing (half-width 2 m) on a 12 m x 5 m block: the mesh of Smith and
    Griffiths' Program 6.1, which reaches 1.01 * Prandtl at its last converged load."""
    mesh = structured_q8([0.0, 1.0, 2.0, 3.0, 4.0, 5.5, 7.0, 9.0, 12.0], np.linspace(-5.0, 0.0, 5))
    model = Model()
    model.add_nodes(mesh.xy, 2)
    soil_group(model, mesh, [(kind, params)])
    fix_block(model, mesh)
    top, _ = surface_pressure(model, mesh, 0.0, 2.0, q_ref)
    return model, top


def test_arc_length_is_exact_on_a_linear_problem():
    model, top = footing(0, elastic_params(1e5, 0.3), 100.0)
    res = run_arc_length(model, 4, 0.25)
    lin = model.solve_linear()
    assert np.allclose(res.load_factor, [0.0, 0.25, 0.5, 0.75, 1.0], rtol=1e-12)
    assert np.allclose(res.u[-1], lin.u[-1], rtol=1e-9, atol=1e-15)
    assert max(res.iterations) <= 2


def test_arc_length_levels_off_at_the_tresca_limit_load():
    cu = 100.0
    model, top = footing(*von_mises_params(1e5, 0.3, cu), 1000.0)  # reference load ~2 x the limit
    res = run_arc_length(model, 14, 0.15, Settings(method="modified", force_tol=1e-4, max_iter=600))
    lam = np.array(res.load_factor)
    q_limit = PRANDTL * cu / 1000.0
    # the load factor rises monotonically and flattens just above Prandtl's value (coarse 8 x 4 mesh:
    # the peer code reaches 1.01 q_u on this mesh); it never overshoots by more than the mesh error
    assert np.all(np.diff(lam) > 0.0)
    assert lam[-1] == pytest.approx(q_limit, rel=0.03)
    assert lam[-1] - lam[-2] < 0.01 * lam[-1]
    # load control cannot pass the limit: with the default settings it stops there and says so, at the
    # arc-length path's plateau (to the mesh's ~1 % spread between the two path-following schemes)
    res_load = run(model, [0.3, 0.6])
    assert res_load.collapsed
    assert res_load.limit_load_factor == pytest.approx(lam[-1], rel=0.01)
