"""Material-point checks of the Mohr–Coulomb (and von Mises) soil laws.

References are independent of the code under test: the yield function evaluated from its definition, the
flow rule's closed-form direction, closed-form limit stresses of simple paths, and central finite
differences of the update itself for the tangents.

Tolerances: the return mapping is exact up to round-off (linear solves on planes), so f = 0 is checked to
1e-9 of the stress scale; central differences with step h = 1e-7·(strain scale) have truncation error
O(h²)·(third derivative) ≈ 0 on the piecewise-linear branches and round-off ≈ 1e-16·σ/h ≈ 1e-9 relative,
so 1e-6 leaves ample margin while any missing term (e.g. the principal-axis rotation, order 1) would fail.
"""

import math

import numpy as np
import pytest
from scipy.optimize import nnls

from ssi.core.protocol import CONSISTENT
from ssi.lab.verify import fd_jacobian
from ssi.materials.mc_surface import mc_yield
from ssi.materials.soil_laws import (
    ELASTIC,
    MOHR_COULOMB,
    MOHR_COULOMB_EXPLICIT,
    VON_MISES,
    SoilLayer,
    drive,
    elastic_matrix,
    elastic_params,
    geostatic_stress,
    k0_jaky,
    material_table,
    mohr_coulomb_params,
    soil_update,
    von_mises_params,
)

E, NU = 20e6, 0.3
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))
TOL_F = 1e-9  # relative yield-function residual after a return
TOL_FD = 1e-6  # relative tangent error against central differences


def update(kind, p, deps, sig0, tangent=CONSISTENT):
    s, h, D = np.zeros(4), np.zeros(2), np.zeros((4, 4))
    st = soil_update(kind, p, np.asarray(deps, float), np.asarray(sig0, float), np.zeros(2), s, h, D, tangent)
    return st, s, h, D


def fd_tangent(kind, p, deps, sig0, h=1e-9):
    # in-plane strain components only: they drive the plane-strain element (column 3 stays zero)
    return fd_jacobian(lambda d: update(kind, p, d, sig0)[1], deps, h, columns=range(3))


def principal(sig):
    m, r = 0.5 * (sig[0] + sig[1]), math.hypot(0.5 * (sig[0] - sig[1]), sig[2])
    return np.sort([m + r, m - r, sig[3]])[::-1]


def stress_from_principal(s_a, s_b, s_y, theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([c * c * s_a + s * s * s_b, s * s * s_a + c * c * s_b, c * s * (s_a - s_b), s_y])


def k_of(phi_deg):
    sp = math.sin(math.radians(phi_deg))
    return (1 + sp) / (1 - sp)


# ------------------------------------------------------------------------------------------------ inputs
@pytest.mark.parametrize(
    "kw, name",
    [
        (dict(E=0.0), "E"),
        (dict(E=-1.0), "E"),
        (dict(nu=0.5), "nu"),
        (dict(nu=-1.0), "nu"),
        (dict(c=-1.0), "c"),
        (dict(phi_deg=90.0), "phi_deg"),
        (dict(phi_deg=-1.0), "phi_deg"),
        (dict(psi_deg=31.0), "psi_deg"),
        (dict(psi_deg=-1.0), "psi_deg"),
        (dict(c=0.0, phi_deg=0.0, psi_deg=0.0), "c"),
        (dict(scheme="rk4"), "scheme"),
        (dict(n_sub=0), "n_sub"),
    ],
)
def test_bad_parameters_raise_naming_them(kw, name):
    args = dict(E=E, nu=NU, c=10e3, phi_deg=30.0, psi_deg=10.0) | kw
    with pytest.raises(ValueError, match=name):
        mohr_coulomb_params(**args)


def test_material_table_pads_rows_of_different_kinds():
    kinds, table = material_table(
        [(ELASTIC, elastic_params(E, NU)), mohr_coulomb_params(E, NU, 1e4, 20), (ELASTIC, [E, NU])]
    )
    assert kinds.tolist() == [ELASTIC, MOHR_COULOMB, ELASTIC]
    assert table.shape == (3, 8) and table[2, 0] == E and table[1, 3] == pytest.approx(math.radians(20))


# ------------------------------------------------------------------------------------------------ elastic
@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
def test_elastic_branch_is_hooke_and_tangent_is_elastic(scheme):
    kind, p = mohr_coulomb_params(E, NU, 50e3, 30, 10, scheme=scheme)
    sig0 = np.array([-100e3, -150e3, 5e3, -110e3])
    deps = np.array([1e-5, -2e-5, 1e-5, 0.0])
    st, s, h, D = update(kind, p, deps, sig0)
    De = np.zeros((4, 4))
    elastic_matrix(E, NU, De)
    assert st == 0 and h[1] == 0
    np.testing.assert_allclose(s, sig0 + De @ deps, rtol=1e-14, atol=1e-9)
    np.testing.assert_allclose(D, De, rtol=1e-14)
    np.testing.assert_allclose(
        fd_tangent(kind, p, deps, sig0)[:, :3], De[:, :3], rtol=TOL_FD, atol=TOL_FD * E
    )


# ------------------------------------------------------------------------------------------------ branches
# trial principal stresses (s1 >= s2 >= s3, kPa) that land in each return region for c = 10 kPa, phi = 30
BRANCH_TRIALS = {
    1: (-40.0, -80.0, -200.0),  # plane
    2: (-10.0, -12.0, -200.0),  # edge s1 = s2 (plane return would make s2 > s1)
    3: (0.0, -150.0, -155.0),  # edge s2 = s3
    4: (40.0, 30.0, 25.0),  # apex (c cot(phi) = 17.3 kPa)
}


def potential_gradients(m, branch):
    """Columns: gradients of the potential planes active on a branch (ordered principal space). At the apex
    all six planes of the pyramid meet, and the plastic strain may be any non-negative combination."""
    g = {
        1: [[m, 0, -1]],
        2: [[m, 0, -1], [0, m, -1]],
        3: [[m, 0, -1], [m, -1, 0]],
        4: [[m, 0, -1], [0, m, -1], [m, -1, 0], [-1, m, 0], [0, -1, m], [-1, 0, m]],
    }[branch]
    return np.array(g, float).T


def trial_sig(branch, theta=0.3, y_slot=1):
    s = np.array(BRANCH_TRIALS[branch]) * 1e3
    y = s[y_slot]
    inplane = np.delete(s, y_slot)
    return stress_from_principal(inplane[0], inplane[1], y, theta)


@pytest.mark.parametrize("psi", [30.0, 10.0, 0.0])
@pytest.mark.parametrize("branch", [1, 2, 3, 4])
@pytest.mark.parametrize("y_slot", [0, 1, 2])
def test_return_mapping_branch_surface_flow_and_fd_tangent(branch, psi, y_slot):
    c, phi = 10e3, 30.0
    kind, p = mohr_coulomb_params(E, NU, c, phi, psi)
    sigB = trial_sig(branch, 0.3 + 0.2 * y_slot, y_slot)
    deps = np.zeros(4)
    st, s, h, D = update(kind, p, deps, sigB)
    m = k_of(psi)
    scale = np.abs(sigB).max()
    assert st == 1
    # on the surface, principal order kept
    assert abs(mc_yield(s, c, math.radians(phi))) < TOL_F * scale
    # branch (edges and apex are geometry; which one is hit depends on psi for trials near a boundary)
    if branch == 1:
        assert h[1] == 1
    if branch == 4:
        assert h[1] == 4
        np.testing.assert_allclose(principal(s), c / math.tan(math.radians(phi)), rtol=1e-12)
    # flow direction: plastic strain = D^-1 (sigB - s) must be a non-negative combination of the potential
    # gradients of the active planes (principal space, same axes as the trial)
    pB, ps = principal(sigB), principal(s)
    dsig = pB - ps
    deps_p = ((1 + NU) * dsig - NU * dsig.sum()) / E
    # (for psi = 0 a trial in hydrostatic tension beyond the apex has no return that obeys a purely
    # deviatoric flow rule; the apex return then carries a volumetric plastic strain — documented choice)
    G = potential_gradients(m, int(h[1]))
    lam_, res = nnls(G, deps_p)
    if not (h[1] == 4 and psi == 0.0):
        assert res < 1e-9 * np.abs(deps_p).max()
    # consistent tangent against central differences
    Dfd = fd_tangent(kind, p, deps, sigB)
    np.testing.assert_allclose(D[:, :3], Dfd[:, :3], atol=TOL_FD * E)
    # symmetry only for associated flow (the apex tangent is zero, hence trivially symmetric); the full 4×4
    # (with the out-of-plane row and column) is used: on an edge made of the two in-plane stresses the
    # in-plane block alone can be symmetric
    asym = np.abs(D - D.T).max() / E
    if psi == phi or h[1] == 4:
        assert asym < 1e-12
    else:
        assert asym > 1e-3


@pytest.mark.parametrize("branch", [1, 2, 3])
def test_tresca_phi0_branches(branch):
    """phi = 0 (Tresca): no apex; plane and edge returns keep s1 - s3 = 2c."""
    c = 30e3
    kind, p = mohr_coulomb_params(E, NU, c, 0.0, 0.0)
    trial = {1: (100.0, 0.0, -100.0), 2: (100.0, 90.0, -100.0), 3: (100.0, -90.0, -100.0)}[branch]
    sigB = stress_from_principal(trial[0] * 1e3, trial[2] * 1e3, trial[1] * 1e3, 0.7)
    st, s, h, D = update(kind, p, np.zeros(4), sigB)
    ps = principal(s)
    assert st == 1 and h[1] == branch
    assert ps[0] - ps[2] == pytest.approx(2 * c, rel=1e-12)
    np.testing.assert_allclose(D[:, :3], fd_tangent(kind, p, np.zeros(4), sigB)[:, :3], atol=TOL_FD * E)
    np.testing.assert_allclose(D, D.T, atol=1e-12 * E)


@pytest.mark.parametrize("psi", [30.0, 15.0])
def test_apex_region_is_the_cone_of_the_potential_gradients(psi):
    """A trial returns to the apex exactly when D⁻¹(σB − σ_apex) is a non-negative combination of the six
    potential gradients meeting there (non-negative least squares, independent of the code's region tests)."""
    c, phi = 10e3, 30.0
    kind, p = mohr_coulomb_params(E, NU, c, phi, psi)
    apex = c / math.tan(math.radians(phi))
    G = potential_gradients(k_of(psi), 4)
    rng = np.random.default_rng(1)
    n_apex = 0
    for _ in range(300):
        pr = np.sort(rng.uniform(-40e3, 60e3, 3))[::-1]
        if k_of(phi) * pr[0] - pr[2] - 2 * c * math.sqrt(k_of(phi)) <= 0:
            continue
        sigB = stress_from_principal(pr[0], pr[2], pr[1], 0.4)
        st, s, h, D = update(kind, p, np.zeros(4), sigB)
        d = pr - apex
        deps_p = ((1 + NU) * d - NU * d.sum()) / E
        lam_, res = nnls(G, deps_p)
        in_cone = res < 1e-9 * np.abs(deps_p).max()
        assert (h[1] == 4) == in_cone, (pr, lam_, res, h[1])
        n_apex += in_cone
    assert n_apex > 10


def test_cohesionless_soil_returns_tension_to_zero_stress():
    kind, p = mohr_coulomb_params(E, NU, 0.0, 35.0, 0.0)
    st, s, h, D = update(kind, p, np.array([1e-3, 2e-3, 0.0, 0.0]), np.zeros(4))
    assert st == 1 and h[1] == 4
    np.testing.assert_allclose(s, 0.0, atol=1e-9)
    np.testing.assert_allclose(D, 0.0, atol=1e-12)


# ------------------------------------------------------------------------------------------------ paths
def biaxial_path(kind, p, p_conf, n_steps, dez, sig0=None):
    """Plane-strain biaxial compression: σxx = −p_conf held (mixed control by Newton on εxx), εzz imposed,
    γ = 0, εyy = 0. Returns stresses and the strain increments actually used."""
    sig = np.array([-p_conf, -p_conf, 0.0, -p_conf]) if sig0 is None else sig0.copy()
    hist = np.zeros(2)
    out, incs = [sig.copy()], []
    for _ in range(n_steps):
        deps = np.array([0.0, dez, 0.0, 0.0])
        for _ in range(50):
            s, h, D = np.zeros(4), np.zeros(2), np.zeros((4, 4))
            soil_update(kind, p, deps, sig, hist, s, h, D, CONSISTENT)
            r = s[0] + p_conf
            if abs(r) < 1e-9 * p_conf:
                break
            deps[0] -= r / D[0, 0]
        assert abs(r) < 1e-6 * p_conf
        sig, hist = s, h
        out.append(sig.copy())
        incs.append(deps.copy())
    return np.array(out), np.array(incs)


@pytest.mark.parametrize("psi", [30.0, 0.0])
def test_biaxial_compression_limit_and_dilatancy(psi):
    """Closed form: at failure σzz = −(k p + 2c√k); plastic dilatancy −Δεv/Δγ = sin ψ (Mohr circle of the
    plastic strain increment, plane strain, ψ constant)."""
    c, phi, p_conf = 10e3, 30.0, 100e3
    kind, p = mohr_coulomb_params(E, NU, c, phi, psi)
    sig, incs = biaxial_path(kind, p, p_conf, 60, -4e-4)
    k = k_of(phi)
    assert sig[-1, 1] == pytest.approx(-(k * p_conf + 2 * c * math.sqrt(k)), rel=1e-10)
    # dilatancy over the last (fully plastic) steps: total strain rate = plastic (stress no longer changes)
    d = incs[-1]
    dev, dgam = d[0] + d[1], abs(d[0] - d[1])
    assert dev / dgam == pytest.approx(math.sin(math.radians(psi)), abs=1e-9)


def test_tresca_pure_shear_limit():
    c = 25e3
    kind, p = mohr_coulomb_params(E, NU, c, 0.0)
    steps = np.tile([2e-4, -2e-4, 0.0, 0.0], (40, 1))
    sig, hist, status, _ = drive(kind, p, steps)
    np.testing.assert_allclose(sig[-1], [c, -c, 0.0, 0.0], atol=1e-6 * c)
    assert status[0] == 0 and status[-1] == 1


@pytest.mark.parametrize("n_sub, drift", [(1, False), (1, True), (8, False), (8, True)])
def test_explicit_scheme_reaches_the_same_limit(n_sub, drift):
    """The explicit scheme follows the same biaxial path; its limit σzz is exact on the plane branch because
    D_ep keeps the stress on a planar face (drift arises only from principal-axis rotation, absent here)."""
    c, phi, p_conf = 10e3, 30.0, 100e3
    kind, p = mohr_coulomb_params(E, NU, c, phi, 10.0, scheme="explicit", n_sub=n_sub, drift=drift)
    assert kind == MOHR_COULOMB_EXPLICIT
    sig, _ = biaxial_path(kind, p, p_conf, 30, -8e-4)
    k = k_of(phi)
    assert sig[-1, 1] == pytest.approx(-(k * p_conf + 2 * c * math.sqrt(k)), rel=1e-9)


def rotating_shear_path(kind, p, n):
    """Simple shear under a vertical stress: principal axes rotate, so forward Euler drifts off the
    surface."""
    sig0 = np.array([-50e3, -100e3, 0.0, -50e3])
    steps = np.tile([0.0, 0.0, 2e-2 / n, 0.0], (n, 1))
    return drive(kind, p, steps, sig0)[0]


def test_explicit_drift_and_substepping_converge_to_implicit_on_rotating_path():
    c, phi, psi = 5e3, 30.0, 0.0
    ref = rotating_shear_path(*mohr_coulomb_params(E, NU, c, phi, psi), 4000)[-1]
    errs = []
    for n_sub in (1, 4, 16):
        sig = rotating_shear_path(
            *mohr_coulomb_params(E, NU, c, phi, psi, scheme="explicit", n_sub=n_sub, drift=True), 10
        )
        assert abs(mc_yield(sig[-1], c, math.radians(phi))) < TOL_F * 1e5  # drift correction: on the surface
        errs.append(np.abs(sig[-1] - ref).max())
    assert errs[2] < errs[1] < errs[0]
    # without drift correction the stress leaves the surface on this path (the paper's plain scheme)
    sig = rotating_shear_path(*mohr_coulomb_params(E, NU, c, phi, psi, scheme="explicit"), 10)
    assert mc_yield(sig[-1], c, math.radians(phi)) > 1e-6 * 1e5


@pytest.mark.parametrize("psi", [30.0, 0.0])
def test_explicit_continuum_tangent_matches_one_sided_differences(psi):
    """From a stress on the main plane, a small loading increment gives Δσ = D_ep Δε exactly (planar face)."""
    c, phi = 10e3, 30.0
    kind, p = mohr_coulomb_params(E, NU, c, phi, psi, scheme="explicit")
    k = k_of(phi)
    s3 = -200e3
    s1 = (s3 + 2 * c * math.sqrt(k)) / k
    sig0 = stress_from_principal(s1, s3, 0.5 * (s1 + s3), 0.25)
    d = np.array([1.0, -1.0, 0.3, 0.0]) * 1e-4
    _, s_base, _, _ = update(kind, p, d, sig0)
    _, _, _, D = update(kind, p, d * 1e-9, sig0)  # D_ep reported at (almost) the starting stress
    h = 1e-6
    _, s_h, _, _ = update(kind, p, d * (1 + h), sig0)
    # one forward-Euler step is linear in the increment: sigma(d (1 + h)) - sigma(d) = D_ep(sig0) d h
    np.testing.assert_allclose(s_h - s_base, D @ (d * h), atol=1e-6 * np.abs(D @ d * h).max())
    asym = np.abs(D[:3, :3] - D[:3, :3].T).max() / E
    assert (asym < 1e-12) if psi == phi else (asym > 1e-3)


# ------------------------------------------------------------------------------------------------ extremes
def test_phi_to_zero_is_continuous_with_tresca():
    sigB = stress_from_principal(100e3, -100e3, -20e3, 0.2)
    _, s0, _, D0 = update(*mohr_coulomb_params(E, NU, 30e3, 0.0), np.zeros(4), sigB)
    _, s1, _, D1 = update(*mohr_coulomb_params(E, NU, 30e3, 1e-7), np.zeros(4), sigB)
    np.testing.assert_allclose(s1, s0, atol=1e-6 * 30e3)
    np.testing.assert_allclose(D1, D0, atol=1e-6 * E)


# every (phi, nu) with every return branch, except the apex (branch 4) at phi -> 0: the apex c cot(phi) then
# lies beyond 1e10 Pa, a stress no soil reaches, so there is no apex return to check
EXTREME_CASES = [
    (phi, nu, branch)
    for phi, nu in [(45.0, 0.3), (30.0, 0.49), (45.0, 0.49), (1e-6, 0.49)]
    for branch in (1, 2, 3, 4)
    if not (phi < 1e-3 and branch == 4)
]


@pytest.mark.parametrize("phi, nu, branch", EXTREME_CASES)
def test_extreme_angles_and_near_incompressibility(phi, nu, branch):
    c = 10e3
    kind, p = mohr_coulomb_params(E, nu, c, phi, 0.0)
    k = k_of(phi)
    apex = c / math.tan(math.radians(phi))
    base = {
        1: (-40.0, -80.0, -400.0),
        2: (-10.0, -12.0, -400.0),
        3: (0.0, -300.0, -305.0),
        4: (1.0, 0.9, 0.8),
    }[branch]
    pr = np.array(base) * 1e3
    if branch == 4:
        pr = np.array(base) * 2 * apex
    sigB = stress_from_principal(pr[0], pr[2], pr[1], 0.4)
    assert k * pr[0] - pr[2] - 2 * c * math.sqrt(k) > 0, "the trial stress must lie outside the surface"
    st, s, h, D = update(kind, p, np.zeros(4), sigB)
    assert st == 1 and np.all(np.isfinite(s)) and np.all(np.isfinite(D))
    assert abs(mc_yield(s, c, math.radians(phi))) < TOL_F * np.abs(sigB).max()
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    np.testing.assert_allclose(
        D[:, :3], fd_tangent(kind, p, np.zeros(4), sigB, h=1e-10)[:, :3], atol=TOL_FD * (lam + E)
    )


@pytest.mark.parametrize("size", [1e-14, 1e-8, 1e-2, 1.0])
@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
def test_tiny_and_huge_strain_steps(size, scheme):
    """Any step size ends on or inside the surface (explicit: with drift correction), never non-finite."""
    c, phi = 10e3, 30.0
    kind, p = mohr_coulomb_params(E, NU, c, phi, 0.0, scheme=scheme, drift=True, n_sub=4)
    sig0 = np.array([-100e3, -100e3, 0.0, -100e3])
    for d in ([1.0, -1.0, 0.5, 0.0], [1.0, 1.0, 0.0, 0.0], [-1.0, -1.0, 0.0, 0.0]):
        st, s, h, D = update(kind, p, np.array(d) * size, sig0)
        assert st >= 0 and np.all(np.isfinite(s)) and np.all(np.isfinite(D))
        assert mc_yield(s, c, math.radians(phi)) < TOL_F * max(np.abs(s).max(), 1e5)


# ------------------------------------------------------------------------------------------------ von Mises
def test_von_mises_return_and_tangent():
    cu = 100e3
    kind, p = von_mises_params(E, NU, cu)
    assert kind == VON_MISES
    sigB = np.array([100e3, -200e3, 80e3, -60e3])
    st, s, h, D = update(kind, p, np.zeros(4), sigB)
    sd = s - np.array([1, 1, 0, 1]) * (s[0] + s[1] + s[3]) / 3
    j2 = 0.5 * (sd[0] ** 2 + sd[1] ** 2 + sd[3] ** 2) + sd[2] ** 2
    assert st == 1 and math.sqrt(j2) == pytest.approx(cu, rel=1e-12)
    assert (s[0] + s[1] + s[3]) == pytest.approx(sigB[0] + sigB[1] + sigB[3], rel=1e-12)
    np.testing.assert_allclose(D[:, :3], fd_tangent(kind, p, np.zeros(4), sigB)[:, :3], atol=TOL_FD * E)
    np.testing.assert_allclose(D, D.T, atol=1e-12 * E)
    with pytest.raises(ValueError, match="cu"):
        von_mises_params(E, NU, 0.0)


# ------------------------------------------------------------------------------------------------ geostatic
def test_geostatic_stress_layers_and_k0():
    layers = [
        SoilLayer(2.0, E=E, nu=NU, unit_weight=18e3, phi_deg=30.0),
        SoilLayer(3.0, E=E, nu=NU, unit_weight=20e3, K0=0.8),
    ]
    z = np.array([0.0, -1.0, -2.0, -4.0, -10.0])
    s = geostatic_stress(z, layers, surcharge=10e3)
    szz = -np.array([10e3, 10e3 + 18e3, 10e3 + 36e3, 10e3 + 36e3 + 40e3, 10e3 + 36e3 + 160e3])
    np.testing.assert_allclose(s[:, 1], szz, rtol=1e-14)
    np.testing.assert_allclose(s[:2, 0], 0.5 * szz[:2], rtol=1e-14)  # 1 - sin 30 = 0.5
    np.testing.assert_allclose(s[3:, 0], 0.8 * szz[3:], rtol=1e-14)
    np.testing.assert_allclose(s[:, 3], s[:, 0])
    assert np.all(s[:, 2] == 0.0)
    assert k0_jaky(30.0) == pytest.approx(0.5)
    with pytest.raises(ValueError, match="surcharge"):
        geostatic_stress(z, layers, surcharge=-1.0)
    with pytest.raises(ValueError, match="surface"):
        geostatic_stress(np.array([1.0]), layers)
    with pytest.raises(TypeError, match=r"layers\[0\] must be a SoilLayer"):
        geostatic_stress(z, [dict(thickness=2.0, gamma=18e3, phi_deg=30.0)])  # the former dict form


def test_geostatic_stress_is_inside_the_mohr_coulomb_surface():
    """With K0 = 1 - sin φ and c >= 0 the at-rest state never violates Mohr–Coulomb (K0 > Ka)."""
    for phi in (10.0, 20.0, 30.0, 45.0):
        layer = SoilLayer(1.0, E=E, nu=NU, unit_weight=19e3, phi_deg=phi)
        s = geostatic_stress(np.linspace(0, -20, 41), [layer])
        for row in s:
            assert mc_yield(row, 0.0, math.radians(phi)) <= 1e-9 * (abs(row[1]) + 1.0)


@pytest.mark.parametrize("psi", [30.0, 0.0])
def test_explicit_continuum_tangent_on_an_edge(psi):
    """On the s1 = s2 edge (here sxx = syy) an isochoric load symmetric in x and y (the law accepts an
    out-of-plane strain) activates both planes (Koiter's rule); the forward-Euler step is again linear in
    the increment: Δσ = D_ep Δε with the two-plane D_ep."""
    c, phi = 10e3, 30.0
    kind, p = mohr_coulomb_params(E, NU, c, phi, psi, scheme="explicit")
    k = k_of(phi)
    s3 = -200e3
    s1 = (s3 + 2 * c * math.sqrt(k)) / k
    sig0 = np.array([s1, s3, 0.0, s1])
    d = np.array([0.5e-4, -3e-4, 0.0, 0.5e-4])
    st, s_base, h_base, _ = update(kind, p, d, sig0)
    _, _, _, D = update(kind, p, d * 1e-9, sig0)
    _, s_h, _, _ = update(kind, p, d * (1 + 1e-6), sig0)
    assert st == 1 and h_base[1] == 2  # edge branch
    np.testing.assert_allclose(s_h - s_base, D @ (d * 1e-6), atol=1e-6 * np.abs(D @ d * 1e-6).max())
    # the stress stays on both planes: s1 = s2 after the step, f = 0
    assert s_base[0] == pytest.approx(s_base[3], rel=1e-9)
    assert abs(mc_yield(s_base, c, math.radians(phi))) < TOL_F * 1e6
    asym = np.abs(D - D.T).max() / E
    assert (asym < 1e-12) if psi == phi else (asym > 1e-3)
