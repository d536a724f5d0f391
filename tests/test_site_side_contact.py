"""Side contact of an embedded strip (issue 32 item 5): the rigid-face interface element against the six-node
interface it is built from, its friction against Coulomb's law, and a scene's initial state and push."""

import dataclasses

import numpy as np
import pytest

from ssi.core.model import Model
from ssi.elements.interface import V_SIG, V_TAU, Interface6
from ssi.elements.section import homogeneous
from ssi.elements.side_interface import SideInterface, add_side_interface
from ssi.materials.interface_law import interface_params
from ssi.scene import Contact, Foundation, MeshSize, Scene, SoilLayer


def _one_wall(params, t0=None):
    """One element on a vertical wall x = 1, z from 0 to -1, soil on its right (walk up), the body's node at
    (0.2, 0.3)."""
    model = Model()
    soil = model.add_nodes([[1.0, -1.0], [1.0, -0.5], [1.0, 0.0]], ndof=2)
    body = model.add_nodes([[0.2, 0.3]], ndof=3)[0]
    g = add_side_interface(model, body, soil[None], params, initial_traction=t0)
    return model, g


def test_side_element_is_the_six_node_interface_on_the_rigid_face():
    """Forces and stiffness equal those of an Interface6 whose face nodes move with the body (u = u_b -
    (z - z_b) alpha, w = w_b + (x - x_b) alpha), mapped back to the body: the transformation, checked
    against the element it wraps (tolerance 1e-12 relative: round-off of the einsum)."""
    p = interface_params(kt=2e8, kn=1e9, phi_deg=25.0, c=5e3)
    model, g = _one_wall(p)
    du = np.array([1e-4, -3e-4, 2e-4, 0.0, 1e-5, -2e-5, 0.0, 3e-5, 1e-5])  # u_b, w_b, alpha_b, soil
    f, k, _ = g.evaluate(du[None], du[None], g.initial_state(), 1)
    xy = np.array([[1.0, -1.0], [1.0, -0.5], [1.0, 0.0]])
    ref = Interface6(np.concatenate([xy, xy])[None], np.arange(12)[None], p)
    face = np.array([[du[0] - (z - 0.3) * du[2], du[1] + (x - 0.2) * du[2]] for x, z in xy]).ravel()
    f6, k6, _ = ref.evaluate(None, np.concatenate([face, du[3:]])[None], ref.initial_state(), 1)
    t = np.zeros((12, 9))
    for a, (x, z) in enumerate(xy):
        t[2 * a, [0, 2]] = 1.0, -(z - 0.3)
        t[2 * a + 1, [1, 2]] = 1.0, x - 0.2
    t[6:, 3:] = np.eye(6)
    assert np.allclose(f[0], t.T @ f6[0], rtol=1e-12, atol=1e-12 * np.abs(f6).max())
    assert np.allclose(k[0], t.T @ k6[0] @ t, rtol=1e-12, atol=1e-12 * np.abs(k6).max())
    # a rigid motion of body and soil together opens no gap: no force
    rigid = np.array(
        [1e-3, 2e-3, 1e-3] + [v for x, z in xy for v in (1e-3 - (z - 0.3) * 1e-3, 2e-3 + (x - 0.2) * 1e-3)]
    )
    f_r, _, _ = g.evaluate(rigid[None], rigid[None], g.initial_state(), 1)
    assert np.abs(f_r).max() < 1e-9 * 1e9 * 1e-3


def test_sliding_side_carries_tan_delta_times_the_normal_force():
    """The body slides down a wall that starts with a linear normal stress sig_h(z) = -K0 gamma depth:
    every point slips and the wall's friction is tan(delta) * integral sig_h dz (Simpson integrates the
    linear stress exactly: 1e-12 relative)."""
    delta, k0, gamma = 20.0, 0.5, 18e3
    z_ip = np.array([-1.0, -0.5, 0.0])  # Newton-Cotes points: the nodes
    t0 = np.zeros((1, 3, 2))
    t0[0, :, 1] = -k0 * gamma * (-z_ip)
    model, g = _one_wall(interface_params(kt=1e9, kn=1e9, phi_deg=delta, psi_deg=0.0), t0)
    du = np.zeros(9)
    du[1] = -0.01  # the body moves down 10 mm: far beyond the elastic slip tau/kt
    _, _, st = g.evaluate(du[None], du[None], g.initial_state(), 1)
    w = g.ip_weights()
    friction = np.sum(st[..., V_TAU] * w)
    normal = np.sum(st[..., V_SIG] * w)
    assert normal == pytest.approx(-0.5 * k0 * gamma * 1.0**2, rel=1e-12)  # no dilation: sig_n unchanged
    assert abs(friction) == pytest.approx(np.tan(np.radians(delta)) * abs(normal), rel=1e-12)


def _embedded(side, soil_c=20e3, h=0.25):
    def layer(t):
        return SoilLayer(t, E=10e6, nu=0.3, unit_weight=18e3, c=soil_c, phi_deg=0.0, psi_deg=0.0)

    return Scene(
        width=12.0, depth=6.0, layers=[layer(1.0), layer(5.0)],
        foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9, phi_deg=0.0, c=10e3), embedment=1.0,
        mesh=MeshSize(h_fine=h, h_coarse=2.0), side_contact=side,
    )  # fmt: skip


SMOOTH = Contact(kn=1e10, kt=0.0, phi_deg=0.0, c=0.0)


@pytest.mark.parametrize("rule", ["newton_cotes", "gauss"])
def test_side_contact_starts_in_equilibrium_and_replaces_the_wall_load(rule):
    """The built scene with side contact is at rest under its dead loads (the interfaces carry the walls'
    geostatic stress): the residual at u = 0 is round-off, and the wall's own dead load plus the interface's
    force at rest is round-off on the soil (the wall is free once the contact opens). Both rules integrate
    the linear wall stress times a quadratic shape function exactly."""
    built = _embedded(dataclasses.replace(SMOOTH, rule=rule)).build()
    model = built.model
    assert [g.name for g in built.side_interfaces] == ["side_interface_left", "side_interface_right"]
    assert all(isinstance(g, SideInterface) for g in built.side_interfaces)
    f_int = np.zeros(model.n_dof)
    for g in model.groups:
        z = np.zeros(g.edofs.shape)
        np.add.at(f_int, g.edofs, g.evaluate(z, z, g.initial_state(), 0)[0])
    f_ext = built.geostatic_load.copy()
    for g in model.groups:
        if g.body_force() is not None:
            np.add.at(f_ext, g.edofs, g.body_force())
    free = np.ones(model.n_dof, bool)
    free[list(model._fixed)] = False
    scale = 18e3 * 6.0  # the largest geostatic stress [Pa] times 1 m
    assert np.abs((f_ext - f_int)[free]).max() < 1e-9 * scale
    walls = np.unique(np.concatenate([g.edofs[:, 3:].ravel() for g in built.side_interfaces]))
    walls = walls[~np.isin(walls, built.interface.edofs)]  # the base corner also carries the base's load
    assert np.abs(built.geostatic_load[walls]).max() < 1e-9 * scale


def test_side_contact_none_builds_no_side_groups():
    built = _embedded(None).build()
    assert built.side_interfaces is None
    assert not any(isinstance(g, SideInterface) for g in built.model.groups)


def test_side_contact_needs_an_embedded_plate():
    with pytest.raises(ValueError, match="side_contact"):
        Scene(
            width=12.0, depth=6.0, layers=[SoilLayer(6.0, E=1e7, nu=0.3)],
            foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)),
            contact=Contact(kn=1e10, kt=1e9), side_contact=SMOOTH,
        )  # fmt: skip


def test_push_with_side_contact_exceeds_base_sliding():
    """A rigid horizontal push of the embedded strip: without side contact the resistance is the base's
    Tresca sliding c_i B = 20 kN/m (to 1e-6: the interface's law); with smooth sides it exceeds that by the
    passive resistance, at least Rankine's 0.5 gamma D^2 + 2 s_u D = 49 kN/m (a displacement-based mesh
    overstates a capacity, never understates it beyond its convergence: chapter 19 measures how much)."""
    out = {}
    for name, side in (("base", None), ("side", SMOOTH)):
        built = _embedded(side).build()
        built.model.prescribe(built.plate_nodes, "u", 0.03)
        built.model.fix(built.plate_nodes, "alpha")
        res = built.solve(n_steps=8)
        out[name] = res.solver_result.support_reaction(built.plate_nodes, "u")[-1]
    assert out["base"] == pytest.approx(10e3 * 2.0, rel=1e-6)
    assert out["side"] - out["base"] > 0.5 * 18e3 + 2 * 20e3


def test_side_contact_in_a_scene_file_dict():
    """scene_to_dict / scene_from_dict carry side_contact (a Contact table), like contact."""
    from ssi.scene.scene_file import scene_from_dict, scene_to_dict

    scene = _embedded(SMOOTH)
    data = scene_to_dict(scene)
    assert data["side_contact"]["kn"] == 1e10 and data["side_contact"]["kt"] == 0.0
    assert scene_from_dict(data).side_contact == SMOOTH
    assert scene_from_dict(scene_to_dict(_embedded(None))).side_contact is None


def test_frictional_sides_carry_a_settling_strip():
    """A strip pushed down 10 mm between frictional sides (delta = 20 deg, c = 0): every closed side point
    slips with |tau| = tan(delta) |sig_n| (1e-9: the law's return), and the strip's vertical reaction is the
    base contact force plus the side friction minus the dead load holding the base's initial pressure p0 B
    (equilibrium of the strip, to the solver's force tolerance, 1e-6 relative): the friction of both walls
    acts upwards on the strip."""
    from ssi.elements.interface import V_STATUS
    from ssi.scene.loads import Settlement

    scene = _embedded(Contact(kn=1e10, kt=1e9, phi_deg=20.0, c=0.0))
    scene = dataclasses.replace(scene, contact=Contact(kn=1e10, kt=1e9), loads=[Settlement(0.01)])
    built = scene.build()
    out = built.solve(n_steps=4)
    model = built.model
    friction = 0.0
    for g in built.side_interfaces:
        st = out.states[-1][model.groups.index(g)]
        closed = st[..., V_STATUS] < 1.5  # the top point, at sig_n = 0, is open
        assert np.all(st[..., V_STATUS][closed & (st[..., V_SIG] < -1e3)] == 1.0)  # slipping
        tau, sig = st[..., V_TAU][closed], st[..., V_SIG][closed]
        assert np.allclose(np.abs(tau), np.tan(np.radians(20.0)) * np.abs(sig), rtol=1e-9, atol=1e-9 * 1e5)
        friction += np.sum(np.abs(st[..., V_TAU]) * g.ip_weights())
    reaction = -out.solver_result.support_reaction(built.plate_nodes, "w")[-1]
    base = built.contact_force(out)[-1]
    assert friction > 0.05 * base  # not a negligible term: the check below would not see its sign
    assert reaction == pytest.approx(base + friction - built.base_pressure * 2.0, rel=1e-6)
