"""The controlled path on a model whose laws are all associated (ssi/solver/path.py: ``associated`` and
``_overshoot``): an embedded rigid strip pushed sideways by a prescribed displacement, Tresca clay, a Tresca
base contact and smooth side walls (chapter 19's section 8 on a coarse mesh). On the parent commit the
controlled path stopped at lambda = 0 on it, as unsymmetric and with ``symmetric_tangent=True`` alike.

The expected push resistance is the one the former load-controlled path reached (a different algorithm:
prescribed load factors with its full-Newton retry, removed by issue 31; measured at 3a5ff09 on this scene, 20
steps): with associated laws each increment is a convex problem with one solution, so two algorithms converged
to ``force_tol`` must agree to a few times that tolerance. (Load control without that retry no longer reaches
the push on this scene: bfgs stagnates at lambda = 0.17, full Newton at 0.002.)

And the failure report's mode without stiffness (``_Follower._soft_mode``) on a spring chain.
"""

import numpy as np
import pytest

from ssi.core.protocol import CONSISTENT
from ssi.elements.section import homogeneous
from ssi.elements.spring import LINEAR, Spring
from ssi.elements.supports import spring_chain
from ssi.scene import Contact, Foundation, MeshSize, Push, Scene, SoilLayer
from ssi.solver import COMPLETED, Settings
from ssi.solver.path import _Follower, associated

C_I, B = 10e3, 2.0  # base adhesion [Pa] and strip width [m]: the base alone slides at C_I * B
LOAD_PATH_PUSH = 95884.96426488522  # [N/m] H at the full push, the former load path's (module docstring)


def _pushed_strip(soil_psi_deg=0.0, soil_phi_deg=0.0, side=None):
    def clay(t):
        return SoilLayer(
            t, E=10e6, nu=0.3, unit_weight=18e3, c=20e3, phi_deg=soil_phi_deg, psi_deg=soil_psi_deg
        )

    side = Contact(kn=1e10, kt=0.0, phi_deg=0.0, c=0.0) if side is None else side
    return Scene(
        width=16.0, depth=8.0, layers=[clay(0.5), clay(0.5), clay(7.0)],
        foundation=Foundation(-B / 2, B / 2, homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9, phi_deg=0.0, c=C_I), embedment=1.0,
        mesh=MeshSize(h_fine=0.5, h_coarse=2.0), side_contact=side, loads=[Push(0.05)],
    ).build()  # fmt: skip


def test_associated_laws_are_recognised():
    assert associated(_pushed_strip().model)
    assert not associated(_pushed_strip(soil_phi_deg=30.0, soil_psi_deg=0.0).model)  # non-associated soil
    assert not associated(_pushed_strip(side=Contact(kn=1e10, kt=1e9, phi_deg=25.0, psi_deg=0.0)).model)


@pytest.mark.parametrize("symmetric", [False, True])
def test_pushed_strip_with_smooth_side_walls_completes_on_the_controlled_path(symmetric):
    built = _pushed_strip()
    settings = Settings(control="work", symmetric_tangent=symmetric)
    out = built.solve(n_steps=20, settings=settings)
    assert out.solver_result.status == COMPLETED and out.load_factor[-1] == pytest.approx(1.0)
    push = out.foundation_load()[-1]
    assert push > 2.0 * C_I * B  # the passive side carries more than the sliding base
    assert push == pytest.approx(LOAD_PATH_PUSH, rel=10 * settings.force_tol)


class _GapChain(Spring):
    """Linear springs except element 1, a contact that carries no tension: open (d > 0) it has no force
    and no consistent stiffness, while K0 keeps its elastic k -- the 1-D analogue of chapter 19's unloaded
    weightless strip whose cohesionless contact opened."""

    def evaluate(self, u_el, du_el, state_old, tangent):
        d = u_el[:, 1] - u_el[:, 0]
        k = self.params[:, 0].copy()
        open_gap = (np.arange(len(d)) == 1) & (d > 0.0)
        f = np.where(open_gap, 0.0, k * d)
        if tangent == CONSISTENT:
            k = np.where(open_gap, 0.0, k)
        f_el = np.stack([-f, f], axis=1)
        k_el = k[:, None, None] * np.array([[1.0, -1.0], [-1.0, 1.0]])
        return f_el, k_el, state_old.copy()


def _gap_follower():
    model, group, nodes = spring_chain([LINEAR, LINEAR], [1e6, 0.0, 0.0])
    model.groups[0] = _GapChain(group.edofs, group.kinds, group.params, name="gap_chain")
    model.add_load(nodes[1], "u", 1e3)  # the load acts on node 1; node 2 only hangs on the gap
    follower = _Follower(model, Settings(control="work"), None, None, scale=1.0)
    return model, nodes, follower


def test_failure_report_names_a_body_without_stiffness_that_no_load_drives():
    model, nodes, follower = _gap_follower()
    u = np.zeros(model.n_dof)
    u[model.dof(nodes[2:], "u")] = 1e-3  # node 2 beyond node 1: the gap is open
    text = follower._soft_mode({"u": u})
    assert "mode without stiffness" in text and "gap_chain" in text
    assert "node 2 (u)" in text  # the floating node is named ...
    assert "almost no work" in text  # ... and the load on node 1 does no work on its motion
    u[model.dof(nodes[2:], "u")] = -1e-3  # closed: every DOF held, nothing to report
    assert follower._soft_mode({"u": u}) == ""
