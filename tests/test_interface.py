"""Interface law (Coulomb slip, dilation, tension cut-off) and the 6-node zero-thickness element.

References are independent of the code under test: closed-form Coulomb limits, eq. (6.10) written out by
hand, central finite differences, rigid-body motions, rotated copies of an element, and the consistent
"mass" matrix of the quadratic line, L/30 [[4, 2, -1], [2, 16, 2], [-1, 2, 4]].
"""

import math

import numpy as np
import pytest

from ssi.core.protocol import CONSISTENT, K0_MATRIX
from ssi.elements.interface import V_GN, V_GT, V_STATUS, Interface6
from ssi.lab.verify import fd_jacobian, zero_energy_modes
from ssi.materials.interface_law import (
    H_BROKEN,
    H_OPEN,
    H_STATUS,
    N_HIST,
    OPEN,
    SLIP,
    STICK,
    drive_point,
    interface_params,
    interface_update,
)

KT, KN = 2.0e7, 5.0e7  # Pa/m
C, PHI = 8.0e3, 30.0  # Pa, deg
TAN = math.tan(math.radians(PHI))


def update(params, dgap, t_old=(0.0, 0.0), hist_old=None, tangent=CONSISTENT):
    t_new, h_new, D = np.zeros(2), np.zeros(N_HIST), np.zeros((2, 2))
    h_old = np.zeros(N_HIST) if hist_old is None else np.asarray(hist_old, float)
    code = interface_update(
        params, np.asarray(dgap, float), np.asarray(t_old, float), h_old, t_new, h_new, D, tangent
    )
    return code, t_new, h_new, D


def fd_tangent(params, dgap, t_old, hist_old, h=1e-9):
    """Central differences of t_new with respect to dgap. The law is piecewise linear (rational when a point
    re-closes), so away from state boundaries the FD error is round-off only: ~ eps * |t| / h ~ 1e-7 kn."""
    return fd_jacobian(lambda d: update(params, d, t_old, hist_old)[1], dgap, h)


# ---- parameters ---------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "kwargs, word",
    [
        ({"kt": -1, "kn": 1}, "kt"),
        ({"kt": 1, "kn": 0}, "kn"),
        ({"kt": 1, "kn": 1, "phi_deg": 90}, "phi_deg"),
        ({"kt": 1, "kn": 1, "c": -1}, "c"),
        ({"kt": 1, "kn": 1, "phi_deg": 20, "psi_deg": 25}, "psi_deg"),
        ({"kt": 1, "kn": 1, "phi_deg": 30, "c": 1e3, "sig_t": 2e3}, "sig_t"),
        ({"kt": 1, "kn": 1, "sig_t": -1}, "sig_t"),
    ],
)
def test_params_reject_bad_input(kwargs, word):
    with pytest.raises(ValueError, match=word):
        interface_params(**kwargs)


def test_params_defaults():
    p = interface_params(KT, KN, PHI, C)
    assert p[4] == pytest.approx(TAN)  # psi = phi (the paper's associated rule)
    assert p[5] == pytest.approx(C / TAN)  # tension cut-off at the Coulomb apex
    assert interface_params(KT, KN, PHI, 0.0)[5] == 0.0  # cohesionless: opens at sig_n > 0


# ---- material point -----------------------------------------------------------------------------------
def test_driver_stick_then_slip_at_coulomb_limit():
    """Constant normal closure, growing slip: tau = kt g_t until |tau| = c - sig_n tan(phi), then flat
    (psi=0)."""
    p = interface_params(KT, KN, PHI, C, psi_deg=0.0)
    gn = -1e-3
    gt = np.linspace(0.0, 3e-3, 61)
    t, st, _, hist = drive_point(p, np.column_stack([gt, np.full_like(gt, gn)]))
    sig = KN * gn
    tau_f = C - sig * TAN
    np.testing.assert_allclose(t[:, 1], sig, rtol=1e-12)  # psi = 0: no dilation, sig_n constant
    np.testing.assert_allclose(t[:, 0], np.minimum(KT * gt, tau_f), rtol=1e-12)
    assert np.all(st[KT * gt < tau_f] == STICK) and np.all(st[KT * gt > tau_f] == SLIP)
    # the plastic slip is the part of the gap that the spring does not carry
    np.testing.assert_allclose(hist[-1, 3], gt[-1] - tau_f / KT, rtol=1e-12)


def test_driver_reverse_slip_and_associated_dilation():
    """psi = phi: slip under a fixed normal gap dilates, pushing sig_n into compression along the Coulomb
    line; on every slipping step |tau| = c - sig_n tan(phi) holds exactly (the return is exact)."""
    p = interface_params(KT, KN, PHI, C)
    gt = np.r_[np.linspace(0, 2e-3, 21), np.linspace(2e-3, -2e-3, 41)[1:]]
    path = np.column_stack([gt, np.full_like(gt, -2e-4)])
    t, st, _, hist = drive_point(p, path)
    slip = st == SLIP
    assert slip.any() and (t[slip, 0] < 0).any() and (t[slip, 0] > 0).any()
    np.testing.assert_allclose(np.abs(t[slip, 0]), C - t[slip, 1] * TAN, rtol=1e-10)
    # dilation: the normal plastic gap is tan(psi) times the accumulated |slip| increments
    assert t[-1, 1] < KN * -2e-4
    np.testing.assert_allclose(t[:, 1], KN * (path[:, 1] - hist[:, 4]), rtol=1e-10)


def test_associated_slip_tangent_is_eq_6_10():
    p = interface_params(KT, KN, PHI, C)
    for s in (1.0, -1.0):
        code, _t, _, D = update(p, [s * 5e-3, -1e-3])
        assert code == SLIP
        eq610 = KT * KN / (KT + KN * TAN**2) * np.array([[TAN**2, -s * TAN], [-s * TAN, 1.0]])
        np.testing.assert_allclose(D, eq610, rtol=1e-12)
        assert np.allclose(D, D.T)  # associated flow: symmetric


def test_nonassociated_tangent_is_unsymmetric():
    p = interface_params(KT, KN, PHI, C, psi_deg=0.0)
    code, _, _, D = update(p, [5e-3, -1e-3])
    assert code == SLIP
    # eq. (6.9) with g = |tau|: d tau = -tan(phi) kn d g_n, d sig_n = kn d g_n
    np.testing.assert_allclose(D, [[0.0, -TAN * KN], [0.0, KN]], atol=1e-6 * KN)
    assert not np.allclose(D, D.T)


def _open_hist(p, gap_open):
    """History of a point that opened on a step to normal gap ``gap_open``."""
    code, t, h, _ = update(p, [0.0, gap_open])
    assert code == OPEN and np.all(t == 0.0)
    return h


STATES = {
    # name: (params kwargs, dgap, t_old, hist builder or None, expected code)
    "stick": ({"psi_deg": 10.0}, [1e-4, -2e-4], [1e3, -5e3], None, STICK),
    "slip+ assoc": ({}, [3e-3, -1e-3], [1e3, -5e3], None, SLIP),
    "slip- assoc": ({}, [-3e-3, -1e-3], [1e3, -5e3], None, SLIP),
    "slip+ psi=10": ({"psi_deg": 10.0}, [3e-3, -1e-3], [1e3, -5e3], None, SLIP),
    "slip- psi=0": ({"psi_deg": 0.0}, [-3e-3, 2e-4], [1e3, -5e3], None, SLIP),
    "open (opening step)": ({}, [1e-4, 2e-3], [1e3, -5e3], None, OPEN),
    "open (stays open)": ({}, [1e-4, -1e-4], [0.0, 0.0], 1e-3, OPEN),
    "re-close, stick": ({}, [1e-5, -1.2e-3], [0.0, 0.0], 1e-3, STICK),
    "re-close, slip": ({"psi_deg": 5.0}, [2e-3, -1.1e-3], [0.0, 0.0], 1e-3, SLIP),
    # c = 0, associated: a trial in slight tension with large |tau| returns onto the slip line (the apex
    # corner is split along De m), and a trial in the apex region opens
    "c=0 assoc, tension trial slips": ({"c": 0.0}, [2e-3, 2e-5], [0.0, -1e2], None, SLIP),
    "c=0 assoc, apex region opens": ({"c": 0.0}, [1e-5, 2e-4], [0.0, -1e2], None, OPEN),
}


@pytest.mark.parametrize("name", list(STATES))
def test_fd_tangent_in_every_state(name):
    kw, dgap, t_old, open_gap, expected = STATES[name]
    p = interface_params(KT, KN, PHI, **{"c": C, **kw})
    h_old = None if open_gap is None else _open_hist(p, open_gap)
    if h_old is not None:
        t_old = [0.0, 0.0]
    code, _, _, D = update(p, dgap, t_old, h_old)
    assert code == expected
    # tolerance: round-off of the central difference, ~1e-7 * kn (see fd_tangent)
    np.testing.assert_allclose(D, fd_tangent(p, dgap, t_old, h_old), atol=1e-6 * KN)
    # the K0_MATRIX flag always returns De = diag(kt, kn) (K0 of modified Newton-Raphson)
    np.testing.assert_array_equal(update(p, dgap, t_old, h_old, tangent=K0_MATRIX)[3], np.diag([KT, KN]))


@pytest.mark.parametrize("psi_deg", [0.0, 15.0, PHI])
def test_cohesionless_traction_is_continuous_across_the_apex(psi_deg):
    """c = 0: the traction is a continuous function of the gap at the apex (sig_n = 0), for any dilation.
    Before the corner was split, a dilatant trial just past sig_n = 0 with large |tau| jumped from a slip
    traction of order kt*dg_t to zero (open), and Newton cycled slip -> open -> stick at such a point."""
    p = interface_params(KT, KN, PHI, 0.0, psi_deg=psi_deg)
    t_old = [0.0, -1e3]
    g_t = 2e-3  # |tau_tr| = 4e4 Pa >> friction 1e3 tan(phi)
    for g_n in np.linspace(0.5e3 / KN, 2.0e3 / KN, 41):  # sig_n,trial from -0.5e3 to +1e3 Pa
        eps = 1e-12
        lo = update(p, [g_t, g_n - eps], t_old)[1]
        hi = update(p, [g_t, g_n + eps], t_old)[1]
        # tolerance: a Lipschitz map moves by at most max(kt, kn) * 2 eps ~ 1e-4 Pa
        assert np.abs(hi - lo).max() < 1e-3, (g_n, lo, hi)
    # the return of an associated slip lands on the line |tau| = -sig_n tan(phi) in compression
    code, t, _, _ = update(p, [g_t, 1.5e3 / KN], t_old)
    if psi_deg > 0.0:
        assert code == SLIP and t[1] < 0.0 and abs(abs(t[0]) + t[1] * TAN) < 1e-9 * KN
    else:
        assert code == OPEN and np.all(t == 0.0)


def test_tension_cutoff_opens_and_debonds():
    p = interface_params(KT, KN, PHI, C, psi_deg=0.0, sig_t=5e3)
    code, t, h, _ = update(p, [0.0, 0.9 * 5e3 / KN])
    assert code == STICK and t[1] == pytest.approx(0.9 * 5e3)
    code, t, h, _ = update(p, [0.0, 0.2 * 5e3 / KN], t, h)  # sig_n,trial = 1.1 sig_t -> opens
    assert code == OPEN and np.all(t == 0.0) and h[H_BROKEN] == 1.0 and h[H_STATUS] == OPEN
    assert h[H_OPEN] == pytest.approx(1.1 * 5e3 / KN)  # gap beyond the stress-free position
    # closing by more than the open gap: compression from the closure point on, and no cohesion left
    code, t, h, _ = update(p, [0.0, -1.1 * 5e3 / KN - 1e-4], t, h)
    assert code == STICK and t[1] == pytest.approx(-KN * 1e-4, rel=1e-9)
    code, t, h, _ = update(p, [1.0, 0.0], t, h)  # large slip: tau = -sig_n tan(phi), c lost
    assert code == SLIP and t[0] == pytest.approx(KN * 1e-4 * TAN, rel=1e-9)


def test_frictionless_contact():
    """phi = 0, c = 0: tau = 0 always, sig_n = kn g_n in compression, opens at any tension."""
    p = interface_params(KT, KN)
    code, t, _, D = update(p, [1e-3, -1e-3])
    assert code == SLIP and t[0] == 0.0 and t[1] == pytest.approx(-KN * 1e-3)
    np.testing.assert_allclose(D, [[0.0, 0.0], [0.0, KN]])
    assert update(p, [1e-3, 1e-9])[0] == OPEN


# ---- element --------------------------------------------------------------------------------------------
def straight(n_el=1, L=1.0, angle=0.0, plate_h=None, x0=0.0):
    """coords and edofs of a row of elements along a line through the origin at ``angle`` (rad)."""
    s = x0 + np.arange(2 * n_el + 1) * L / 2
    tx, tz = math.cos(angle), math.sin(angle)
    lower = np.column_stack([s * tx, s * tz])
    coords = np.empty((n_el, 6, 2))
    for e in range(n_el):
        low = lower[2 * e : 2 * e + 3]
        up = low.copy() if plate_h is None else low + [0.0, plate_h / 2]
        coords[e] = np.vstack([up, low])
    n_nodes = 2 * n_el + 1
    nd_up = 2 if plate_h is None else 3
    edofs = np.empty((n_el, 3 * nd_up + 6), np.int64)
    for e in range(n_el):
        up = [nd_up * (2 * e + a) + k for a in range(3) for k in range(nd_up)]
        lo = [nd_up * n_nodes + 2 * (2 * e + a) + k for a in range(3) for k in range(2)]
        edofs[e] = up + lo
    return coords, edofs, nd_up * n_nodes + 2 * n_nodes


def test_element_rejects_bad_input():
    coords, edofs, _ = straight(plate_h=0.4)
    p = interface_params(KT, KN)
    with pytest.raises(ValueError, match="offset"):
        Interface6(coords, edofs, p)
    with pytest.raises(ValueError, match="straight above"):
        Interface6(coords, edofs, p, offset=0.15)
    with pytest.raises(ValueError, match="rule"):
        Interface6(coords, edofs, p, offset=0.2, rule="lobatto")
    with pytest.raises(ValueError, match="params"):
        Interface6(coords, edofs, p[:4], offset=0.2)


@pytest.mark.parametrize("rule", ["newton_cotes", "gauss"])
@pytest.mark.parametrize("plate_h", [None, 0.4])
def test_zero_force_at_zero_gap_and_rigid_motion(rule, plate_h):
    """Zero displacement and any small rigid motion of the glued pair (translation + rotation theta, with
    the plate rotating alpha = theta about its mid-surface) give zero gap, force and traction."""
    coords, edofs, n_dof = straight(n_el=1, L=0.8, angle=0.0, plate_h=plate_h, x0=0.3)
    g = Interface6(
        coords,
        edofs,
        interface_params(KT, KN, PHI, C),
        offset=None if plate_h is None else plate_h / 2,
        rule=rule,
    )
    f, _, st = g.evaluate(np.zeros(edofs.shape), np.zeros(edofs.shape), g.initial_state(), CONSISTENT)
    assert np.all(f == 0.0) and np.all(st == 0.0)
    theta, a, b = 1e-4, 2e-3, -3e-3
    u = np.zeros(n_dof)
    nd_up = 2 if plate_h is None else 3
    xz_up = coords[0, :3]
    for k in range(3):  # upper nodes (mid-surface for the plate): u = a - theta z, w = b + theta x
        u[edofs[0, nd_up * k]] = a - theta * xz_up[k, 1]
        u[edofs[0, nd_up * k + 1]] = b + theta * xz_up[k, 0]
        if plate_h is not None:
            u[edofs[0, nd_up * k + 2]] = theta
    for k in range(3):
        x, z = coords[0, 3 + k]
        u[edofs[0, 3 * nd_up + 2 * k]] = a - theta * z
        u[edofs[0, 3 * nd_up + 2 * k + 1]] = b + theta * x
    u_el = u[edofs]
    f, _, st = g.evaluate(u_el, u_el, g.initial_state(), CONSISTENT)
    scale = KN * 1e-3 * 0.8  # a force of a 1 mm gap over the element: round-off reference
    assert np.abs(f).max() < 1e-12 * scale
    assert np.abs(st[..., V_GT : V_GN + 1]).max() < 1e-15


def test_newton_cotes_is_node_to_node_and_gauss_is_the_consistent_matrix():
    L, k = 0.8, KN
    coords, edofs, _ = straight(n_el=1, L=L)
    p = interface_params(k, k, c=math.inf)
    K_nc = Interface6(coords, edofs, p).elastic_stiffness()[0]
    K_g = Interface6(coords, edofs, p, rule="gauss").elastic_stiffness()[0]
    # the w-DOFs of upper nodes are 1, 3, 5: stiffness k * (pair matrix) between them
    w_up = [1, 3, 5]
    np.testing.assert_allclose(K_nc[np.ix_(w_up, w_up)], k * L / 6 * np.diag([1.0, 4.0, 1.0]), rtol=1e-13)
    consistent = L / 30 * np.array([[4.0, 2.0, -1.0], [2.0, 16.0, 2.0], [-1.0, 2.0, 4.0]])
    np.testing.assert_allclose(K_g[np.ix_(w_up, w_up)], k * consistent, rtol=1e-13)
    # eigenvalue view: relative to the lumped (Newton-Cotes) matrix, the Gauss matrix has eigenvalues 1, 1
    # and 2/5, the last for the corner/mid alternating mode [1, -1/2, 1] -- that mode is the one Gauss
    # integration lets through with too little stiffness, hence oscillating tractions
    lam, vec = np.linalg.eig(np.linalg.solve(k * L / 6 * np.diag([1.0, 4.0, 1.0]), k * consistent))
    order = np.argsort(lam.real)
    np.testing.assert_allclose(lam.real[order], [0.4, 1.0, 1.0], atol=1e-12)
    v = vec[:, order[0]].real
    np.testing.assert_allclose(v / v[0], [1.0, -0.5, 1.0], atol=1e-12)


@pytest.mark.parametrize("rule, n_gauss, n_zero", [("newton_cotes", 3, 6), ("gauss", 3, 6), ("gauss", 2, 8)])
def test_number_of_zero_energy_modes(rule, n_gauss, n_zero):
    """Solid variant, 12 DOFs: the 6 modes with equal upper and lower motion are free; a 2-point Gauss rule
    leaves 2 spurious ones (rank 4 from 2 points x 2 components)."""
    coords, edofs, _ = straight(n_el=1, L=1.0, angle=0.3)
    K = Interface6(
        coords, edofs, interface_params(KT, KN, c=math.inf), rule=rule, n_gauss=n_gauss
    ).elastic_stiffness()[0]
    assert zero_energy_modes(K) == n_zero
    np.testing.assert_allclose(K, K.T, atol=1e-9 * np.linalg.eigvalsh(K).max())


@pytest.mark.parametrize("rule", ["newton_cotes", "gauss"])
def test_rotation_covariance(rule):
    """A rotated copy of an element with rotated displacements has the same gaps, tractions and states,
    and rotated nodal forces (the local frame follows the geometry; inclined contacts work)."""
    p = interface_params(KT, KN, PHI, C)
    rng = np.random.default_rng(3)
    du = rng.normal(scale=1e-3, size=(1, 12))
    out = []
    for angle in (0.0, 0.7):
        coords, edofs, _ = straight(n_el=1, L=1.0, angle=angle)
        c, s = math.cos(angle), math.sin(angle)
        R = np.array([[c, -s], [s, c]])
        du_rot = (du.reshape(6, 2) @ R.T).reshape(1, 12)
        g = Interface6(coords, edofs, p, rule=rule)
        f, k, st = g.evaluate(du_rot, du_rot, g.initial_state(), CONSISTENT)
        out.append((f.reshape(6, 2) @ R, st, k))
    np.testing.assert_allclose(out[1][0], out[0][0], atol=1e-9 * np.abs(out[0][0]).max())
    np.testing.assert_allclose(out[1][1], out[0][1], atol=1e-9 * np.abs(out[0][1]).max())


@pytest.mark.parametrize("rule", ["newton_cotes", "gauss"])
def test_uniform_gap_gives_exact_tractions_and_consistent_forces(rule):
    """A uniform gap is reproduced exactly by both rules; nodal forces are t * L * (1/6, 2/3, 1/6)."""
    L, gt, gn = 0.6, 1e-4, -2e-4
    coords, edofs, _ = straight(n_el=1, L=L, plate_h=0.3)
    g = Interface6(coords, edofs, interface_params(KT, KN, c=math.inf), offset=0.15, rule=rule)
    u = np.zeros((1, 15))
    u[0, [0, 3, 6]] = gt
    u[0, [1, 4, 7]] = gn
    f, _, st = g.evaluate(u, u, g.initial_state(), CONSISTENT)
    np.testing.assert_allclose(st[0, :, 0], KT * gt, rtol=1e-12)
    np.testing.assert_allclose(st[0, :, 1], KN * gn, rtol=1e-12)
    np.testing.assert_allclose(f[0, [1, 4, 7]], KN * gn * L * np.array([1, 4, 1]) / 6, rtol=1e-12)
    np.testing.assert_allclose(f[0, [10, 12, 14]], -KN * gn * L * np.array([1, 4, 1]) / 6, rtol=1e-12)
    assert g.ip_weights().sum() == pytest.approx(L, rel=1e-14)


def test_plate_rotation_shears_the_bottom_face():
    """eq. (6.1a): a plate rotation alpha alone moves the bottom face by u_g = (h/2) alpha."""
    h, alpha = 0.5, 1e-3
    coords, edofs, _ = straight(n_el=1, L=1.0, plate_h=h)
    g = Interface6(coords, edofs, interface_params(KT, KN, c=math.inf), offset=h / 2)
    u = np.zeros((1, 15))
    u[0, [2, 5, 8]] = alpha
    _, _, st = g.evaluate(u, u, g.initial_state(), CONSISTENT)
    np.testing.assert_allclose(st[0, :, V_GT], h / 2 * alpha, rtol=1e-13)
    np.testing.assert_allclose(st[0, :, V_GN], 0.0, atol=1e-18)


@pytest.mark.parametrize("rule", ["newton_cotes", "gauss"])
@pytest.mark.parametrize("plate_h", [None, 0.4])
def test_element_fd_tangent_with_mixed_states(rule, plate_h):
    """Consistent k_el equals the FD Jacobian of f_el on a curved element whose points are in different
    states (stick, slip, open), from a committed state that already slips."""
    p = interface_params(KT, KN, PHI, C, psi_deg=10.0)
    coords, edofs, _ = straight(n_el=1, L=1.0, plate_h=plate_h)
    if plate_h is None:
        coords[0, 1, 1] = coords[0, 4, 1] = 0.05  # curved contact line
    g = Interface6(coords, edofs, p, offset=None if plate_h is None else plate_h / 2, rule=rule)
    n = edofs.shape[1]
    # committed state: everything pressed and slipping a little
    u0 = np.zeros((1, n))
    nd_up = 2 if plate_h is None else 3
    u0[0, [nd_up * k for k in range(3)]] = 2e-3
    u0[0, [nd_up * k + 1 for k in range(3)]] = -1e-3
    _, _, st0 = g.evaluate(u0, u0, g.initial_state(), CONSISTENT)
    # increment: the normal gap varies along the element so that the end points differ in state
    du = np.zeros((1, n))
    du[0, [nd_up * k + 1 for k in range(3)]] = [4e-3, 0.0, -1e-3]
    du[0, [nd_up * k for k in range(3)]] = [0.0, -1e-4, 3e-3]
    _f, k, st = g.evaluate(u0 + du, du, st0, CONSISTENT)
    codes = set(np.rint(st[0, :, V_STATUS]).astype(int))
    assert codes == {STICK, SLIP, OPEN}, codes
    h = 1e-10
    K_fd = fd_jacobian(lambda e: g.evaluate(u0 + du + e, du + e, st0, CONSISTENT)[0][0], np.zeros((1, n)), h)
    # round-off of the central difference: ~ eps |f| / h ~ 1e-6 of kn * L
    np.testing.assert_allclose(k[0], K_fd, atol=1e-5 * KN)
    # the committed state is never touched
    st0_copy = st0.copy()
    g.evaluate(u0 + du, du, st0, CONSISTENT)
    np.testing.assert_array_equal(st0, st0_copy)


def test_initial_traction_is_a_prestressed_committed_state():
    """A pre-compressed contact: at zero displacement f_el holds the consistent forces of the initial
    traction (L (1/6, 2/3, 1/6) sig0 on the upper w-DOFs), and the first slip happens at tau = -sig0
    tan(phi)."""
    L, sig0 = 0.6, -40e3
    coords, edofs, _ = straight(n_el=1, L=L)
    g = Interface6(
        coords, edofs, interface_params(KT, KN, PHI, 0.0, psi_deg=0.0), initial_traction=(0.0, sig0)
    )
    z = np.zeros((1, 12))
    f, _, st = g.evaluate(z, z, g.initial_state(), CONSISTENT)
    np.testing.assert_allclose(f[0, [1, 3, 5]], sig0 * L * np.array([1, 4, 1]) / 6, rtol=1e-13)
    np.testing.assert_allclose(st[0, :, 1], sig0)
    du = np.zeros((1, 12))
    du[0, [0, 2, 4]] = 1e-2  # a large tangential push of the upper side
    _, _, st = g.evaluate(du, du, g.initial_state(), CONSISTENT)
    np.testing.assert_allclose(st[0, :, 0], -sig0 * TAN, rtol=1e-12)
    assert np.all(st[0, :, V_STATUS] == SLIP)
    with pytest.raises(ValueError, match="initial_traction"):
        Interface6(coords, edofs, interface_params(KT, KN), initial_traction=np.zeros((2, 2, 2)))


def test_analytical_references_against_reference_data():
    """ssi.lab.analytical against the numbers of reference-data.md (independent hand values) and
    equilibrium."""
    from ssi.lab.analytical import (
        hetenyi_deflection,
        sadowsky_pressure,
        shear_lag_from_slip,
        shear_lag_onset,
        shear_lag_slip_length,
    )

    EA, kt, L, tf = 4000e3, 2e7, 0.6, 50e3
    assert shear_lag_onset(EA, kt, L, tf) == pytest.approx(32.5e3, abs=0.05e3)
    for tb, s in ((38e3, 0.093), (40e3, 0.130), (45e3, 0.244), (49e3, 0.402), (49.9e3, 0.510)):
        assert shear_lag_slip_length(tb, EA, kt, L, tf) == pytest.approx(s, abs=0.0005)  # 3 decimals given
    assert shear_lag_from_slip(L, EA, kt, L, tf)[0] == pytest.approx(tf)  # full sliding
    xi = np.array([0, 0.2, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99])
    pp = [0.6366, 0.6497, 0.6946, 0.7351, 0.7958, 0.8914, 1.0610, 1.4605, 2.0388, 4.5129]
    np.testing.assert_allclose(sadowsky_pressure(xi, 1.0, 2.0), pp, atol=5e-5)  # P = 2 a: p_m = 1
    x = np.linspace(-40, 40, 400001)
    w = hetenyi_deflection(x, 1e3, 5e6, 3e5)
    assert np.trapezoid(5e6 * w, x) == pytest.approx(1e3, rel=1e-6)  # springs carry P


def test_viscous_interface_blends_elastic_trial_and_inviscid_response():
    """Duvaut--Lions regularisation (the solver's viscous fallback): with tau, tractions and forces are
    (elastic trial + tau inviscid) / (1 + tau) -- checked against the two responses computed separately --
    the consistent tangent is the FD Jacobian of the blended forces, and the history stays the inviscid
    law's."""
    p = interface_params(KT, KN, PHI, C, psi_deg=0.0)
    coords, edofs, _ = straight(n_el=1, L=1.0, plate_h=0.4)
    n = edofs.shape[1]
    inviscid = Interface6(coords, edofs, p, offset=0.2)
    u0 = np.zeros((1, n))
    u0[0, [0, 3, 6]] = 2e-3
    u0[0, [1, 4, 7]] = -1e-3
    _, _, st0 = inviscid.evaluate(u0, u0, inviscid.initial_state(), CONSISTENT)
    du = np.zeros((1, n))
    du[0, [1, 4, 7]] = [4e-3, 0.0, -1e-3]
    du[0, [0, 3, 6]] = [0.0, -1e-4, 3e-3]
    f_inv, _, st_inv = inviscid.evaluate(u0 + du, du, st0, CONSISTENT)
    assert set(np.rint(st_inv[0, :, V_STATUS]).astype(int)) == {STICK, SLIP, OPEN}
    # the elastic trial by hand: committed tractions + De * gap increment, through a never-slipping contact
    never = Interface6(coords, edofs, interface_params(KT, KN, PHI, np.inf), offset=0.2)
    closed = st0.copy()
    closed[..., V_STATUS] = STICK
    f_tr, _, st_tr = never.evaluate(u0 + du, du, closed, CONSISTENT)
    tau = 3.0
    viscous = Interface6(coords, edofs, p, offset=0.2, viscosity=tau)
    f, k, st = viscous.evaluate(u0 + du, du, st0, CONSISTENT)
    np.testing.assert_allclose(f, (f_tr + tau * f_inv) / (1 + tau), rtol=1e-12, atol=1e-12 * KN)
    np.testing.assert_allclose(st[..., :2], (st_tr[..., :2] + tau * st_inv[..., :2]) / (1 + tau), rtol=1e-12)
    np.testing.assert_array_equal(st[..., 2:], st_inv[..., 2:])
    h = 1e-10
    K_fd = np.empty((n, n))
    for j in range(n):
        e = np.zeros((1, n))
        e[0, j] = h
        fp = viscous.evaluate(u0 + du + e, du + e, st0, CONSISTENT)[0]
        fm = viscous.evaluate(u0 + du - e, du - e, st0, CONSISTENT)[0]
        K_fd[:, j] = (fp - fm)[0] / (2 * h)
    np.testing.assert_allclose(k[0], K_fd, atol=1e-5 * KN)
    with pytest.raises(ValueError, match="viscosity"):
        Interface6(coords, edofs, p, offset=0.2, viscosity=-1.0)
