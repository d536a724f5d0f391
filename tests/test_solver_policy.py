"""The controlled path's tunables (``ssi.solver.policy.PathPolicy``) and what the solver asks the element
groups in place of their class (``ElementGroup.symmetric_tangent``, ``associated_flow``, ``softens``,
``davis_params``, ``stored_energy``)."""

import math
from dataclasses import FrozenInstanceError, replace

import numpy as np
import pytest

from ssi.core.model import Model
from ssi.elements.interface import Interface6
from ssi.elements.soil_q8 import SoilQ8
from ssi.elements.spring import LINEAR, TANH, Spring
from ssi.elements.supports import spring_chain
from ssi.materials.interface_law import interface_params
from ssi.materials.soil_laws import SoilLayer, material_table
from ssi.solver import Settings, path, run
from ssi.solver.policy import PATH_POLICY, PathPolicy


def test_the_policy_is_frozen_and_validated():
    with pytest.raises(FrozenInstanceError):
        PATH_POLICY.plateau_rise = 0.1
    with pytest.raises(ValueError, match="PathPolicy.plateau_rise"):
        PathPolicy(plateau_rise=0.0)
    with pytest.raises(ValueError, match="PathPolicy.secant_rule"):
        PathPolicy(secant_rule="sometimes")
    with pytest.raises(ValueError, match=r"PathPolicy.growth\[0\]"):
        PathPolicy(growth=(1.5, 2.0))
    with pytest.raises(TypeError, match="PathPolicy.poor_run"):
        PathPolicy(poor_run=2.5)


def _tanh_chain():
    """A tanh spring (F_u = 1e3 N) pulled by 0.5 F_u x lambda: its force creeps towards the plateau at
    lambda = 2."""
    model, _, nodes = spring_chain([TANH], [1e6, 1e3, 0.0])
    model.add_load(nodes[-1], "u", 500.0)
    return model


def test_the_policy_in_force_is_the_one_the_path_reads(monkeypatch):
    """``path.POLICY`` is what ``run`` reads: a policy whose plateau is a rise below 20 % over 3 steps ends
    the tanh spring's path at a smaller load factor than the default's, which lies within 3 x 0.2 % of the
    plateau lambda = 2 (tests/test_solver_path.py)."""
    settings = Settings(control="work", force_tol=1e-10)
    default = run(_tanh_chain(), [5.0], settings)
    monkeypatch.setattr(path, "POLICY", replace(PATH_POLICY, plateau_rise=0.2, plateau_steps=3))
    loose = run(_tanh_chain(), [5.0], settings)
    assert default.status == loose.status == "limit load reached"
    assert default.limit_load_factor > 2.0 * (1.0 - 3 * PATH_POLICY.plateau_rise)
    assert loose.limit_load_factor < default.limit_load_factor


def _soil_group(psi_deg):
    model = Model()
    xy = np.array([[0, 0], [2, 0], [2, 1], [0, 1], [1, 0], [2, 0.5], [1, 1], [0, 0.5]], float)
    conn = np.array([model.add_nodes(xy, ndof=2)])
    kinds, params = material_table(
        [SoilLayer(1.0, E=2e7, nu=0.3, c=5e3, phi_deg=30.0, psi_deg=psi_deg).law()]
    )
    return SoilQ8(model.coords[conn], model.element_dofs(conn), np.array([0]), kinds, params)


def test_soil_group_answers_what_its_flow_is_and_gives_a_davis_copy():
    assoc, non = _soil_group(30.0), _soil_group(0.0)
    assert assoc.associated_flow() and assoc.symmetric_tangent()
    assert not non.associated_flow() and not non.symmetric_tangent()
    assert non.associated_flow(tol=math.radians(31.0))  # within a tolerance wider than phi - psi
    before = non.params.copy()
    davis = non.davis_params()
    assert np.array_equal(non.params, before)  # the group's own parameters are not touched
    assert davis is not non.params
    # Davis (1968): beta = cos psi cos phi / (1 - sin psi sin phi); psi = 0: beta = cos 30 deg
    beta = math.cos(math.radians(30.0))
    assert davis[0, 2] == pytest.approx(beta * 5e3, rel=1e-14)
    assert math.tan(davis[0, 3]) == pytest.approx(beta * math.tan(math.radians(30.0)), rel=1e-14)
    assert davis[0, 4] == davis[0, 3]


def test_interface_and_spring_groups_answer_their_capabilities():
    edofs = np.arange(12).reshape(1, 12)
    coords = np.array([[[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [0.0, 0.0], [0.5, 0.0], [1.0, 0.0]]])
    itf = Interface6(coords, edofs, interface_params(kt=1e7, kn=1e8, c=0.0, phi_deg=30.0, psi_deg=0.0))
    assert not itf.associated_flow() and not itf.symmetric_tangent()
    davis = itf.davis_params()
    assert davis[0, 3] == davis[0, 4] and itf.params[0, 4] == 0.0
    spring = Spring(np.array([[0, 1]]), [LINEAR], np.array([2.0, 0.0, 0.0]))
    assert spring.symmetric_tangent() and not spring.softens() and spring.davis_params() is None
    # a linear spring stores F dF / k0: from 0 to 2 N at k0 = 2 N/m, 2 x 2 / 2 = 2 J
    old, new = spring.initial_state(), spring.initial_state()
    spring.history(new, "force")[:] = 2.0
    assert spring.stored_energy(np.array([[0.0, 1.0]]), np.array([[0.0, 1.0]]), old, new, 2.0) == 2.0
