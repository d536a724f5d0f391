"""Reinforced-concrete layer laws (paper §5): closed-form features, both forms of eq. (5.3), crack-band
energy, FD tangents in every branch, parameter validation.

Tolerances: closed-form identities of rational/piecewise-linear functions hold to round-off, so 1e-12
(relative) unless a finite difference is involved. Central differences with step h on a smooth branch
have truncation error ~ h^2 |f'''| / 6 and round-off ~ 1e-16 |sig| / h; with h = 1e-9 both are below
1e-6 of the tangent (|sig| ~ 1e7 Pa, tangent ~ 1e9..1e10 Pa), hence FD_TOL = 1e-6.
"""

import numpy as np
import pytest

from ssi.core.protocol import CONSISTENT
from ssi.lab.verify import fd_jacobian
from ssi.materials import rc
from ssi.materials.concrete import (
    P_EPS_C,
    P_FC,
    compression_envelope,
    irreversible_strain,
    irreversible_strain_from_stress,
    softening_modulus,
)
from ssi.materials.layer_laws import CONCRETE, ELASTIC, N_LAYER_HIST, STEEL, layer_update

FD_TOL = 1e-6
H_FD = 1e-9

FC = 30.0e6
E0 = 30.0e9
EPS_C = 0.0022  # a = E0 eps_c / fc = 2.2 (> 2)
FR = 3.0e6
GF = 100.0
LS = 0.1
EPS_Y = 500.0e6 / 200.0e9


def concrete(alpha_ts=0.5, ls=LS, **kw):
    return rc.concrete_params(FC, E0, EPS_C, FR, GF, ls, EPS_Y, alpha_ts=alpha_ts, **kw)


def steel(EH=2.0e9):
    return rc.steel_params(500.0e6, 200.0e9, EH)


def hist(*values):
    h = np.zeros(N_LAYER_HIST)
    h[: len(values)] = values
    return h


def call(kind, p, eps, gam=0.0, h=None, tangent=CONSISTENT):
    h = hist() if h is None else h
    return layer_update(kind, p, eps, gam, h, np.zeros(N_LAYER_HIST), tangent)


def fd_check(kind, p, eps, gam, h):
    _sig, _tau, e_t, g_t = call(kind, p, eps, gam, h)
    jac = fd_jacobian(lambda x: call(kind, p, x[0], x[1], h)[:2], [eps, gam], H_FD)
    e_fd, g_fd = jac[0, 0], jac[1, 1]  # d sig / d eps, d tau / d gam
    scale_e = max(abs(e_t), 1e-3 * E0)
    scale_g = max(abs(g_t), 1e-6 * E0)
    assert abs(e_fd - e_t) <= FD_TOL * scale_e, (eps, e_fd, e_t)
    assert abs(g_fd - g_t) <= FD_TOL * scale_g, (gam, g_fd, g_t)


def test_compression_curve_features():
    f, df0 = compression_envelope(0.0, E0, FC, EPS_C, 0.0035)
    assert f == 0.0 and abs(df0 - E0) <= 1e-12 * E0  # initial slope E0
    f, dfc = compression_envelope(EPS_C, E0, FC, EPS_C, 0.0035)
    assert abs(f - FC) <= 1e-12 * FC  # peak fc at eps_c
    assert abs(dfc) <= 1e-12 * E0  # zero slope at the peak
    assert compression_envelope(0.0036, E0, FC, EPS_C, 0.0035) == (0.0, 0.0)  # crushed
    sig = call(CONCRETE, concrete(), -EPS_C)[0]
    assert abs(sig + FC) <= 1e-12 * FC  # sign: compression negative


@pytest.mark.parametrize("x_max", [0.0003, 0.001, 0.0018, EPS_C * 0.999, 0.0025, 0.003, 0.0034])
def test_irreversible_strain_both_forms_agree(x_max):
    p = concrete()
    sig, _ = compression_envelope(x_max, E0, FC, EPS_C, 0.0035)
    a = irreversible_strain(x_max, E0, FC, EPS_C, 0.0035)
    b = irreversible_strain_from_stress(sig, x_max > EPS_C, E0, p[P_FC], p[P_EPS_C])
    assert a > 0.0
    # the root formula loses digits near the peak (double root); 1e-9 of eps_c is far below any use
    assert abs(a - b) <= 1e-9 * EPS_C, (a, b)


def test_unloading_along_E0_from_compression():
    p = concrete()
    x_max = 0.0028
    h = hist(x_max, 0.0)
    eps_p = irreversible_strain(x_max, E0, FC, EPS_C, 0.0035)
    f_max, _ = compression_envelope(x_max, E0, FC, EPS_C, 0.0035)
    for eps in (-0.0027, -0.002, -eps_p * 1.001):
        sig, _, e_t, _ = call(CONCRETE, p, eps, 0.0, h)
        assert abs(sig - E0 * (eps + eps_p)) <= 1e-12 * FC and e_t == E0
    assert abs(call(CONCRETE, p, -x_max, 0.0, h)[0] + f_max) <= 1e-9 * FC  # back on the envelope
    assert abs(call(CONCRETE, p, -eps_p, 0.0, h)[0]) <= 1e-6  # zero stress at eps_p


def test_tension_linear_then_crack_band_softening():
    p = concrete(alpha_ts=0.0)
    eps_r = FR / E0
    assert abs(call(CONCRETE, p, eps_r)[0] - FR) <= 1e-12 * FR
    Es = softening_modulus(E0, FR, GF, LS)
    assert abs(Es - (-FR / (2 * GF / (FR * LS) - eps_r))) <= 1e-9 * abs(Es)
    eps_u = 2 * GF / (FR * LS)
    assert abs(call(CONCRETE, p, 0.5 * (eps_r + eps_u))[0] - 0.5 * FR) <= 1e-9 * FR
    assert call(CONCRETE, p, eps_u * 1.0001)[0] == 0.0


def test_crack_band_energy_equals_gf_over_ls():
    for ls in (0.02, 0.1, 0.3):
        p = concrete(alpha_ts=0.0, ls=ls)
        eps_u = 2 * GF / (FR * ls)
        # include the kinks eps_r and eps_u so that the trapezoid rule is exact on the piecewise-linear law
        path = np.unique(np.concatenate([np.linspace(0, 1.5 * eps_u, 2001), [FR / E0, eps_u]]))
        sig = rc.drive(CONCRETE, p, path)[0]
        energy = np.sum(0.5 * (sig[1:] + sig[:-1]) * np.diff(path))
        assert abs(energy - GF / ls) <= 1e-10 * GF / ls


def test_secant_unloading_of_cracked_point():
    p = concrete(alpha_ts=0.0)
    path = np.array([0.0, 2e-4, 4e-4, 2e-4, 0.0, -1e-5, 3e-4, 4e-4, 5e-4])
    sig, _, _, _, h = rc.drive(CONCRETE, p, path)
    s_env = sig[2]
    assert abs(sig[3] - 0.5 * s_env) <= 1e-9 * FR and abs(sig[4]) <= 1e-9 * FR
    f5, _ = compression_envelope(1e-5, E0, FC, EPS_C, 0.0035)
    assert abs(sig[5] + f5) <= 1e-9 * FR  # crack closed: back on the eq. (5.1) curve
    # reloading along the secant, from the (tiny) irreversible strain of the closing step
    e6 = 3e-4 + irreversible_strain(1e-5, E0, FC, EPS_C, 0.0035)
    assert abs(sig[6] - e6 / 4e-4 * s_env) <= 1e-9 * FR
    assert h[-1, 1] == pytest.approx(5e-4 + irreversible_strain(1e-5, E0, FC, EPS_C, 0.0035), rel=1e-14)


def test_tension_stiffening_and_shear_retention_vanish_at_yield():
    p = concrete(alpha_ts=0.5)
    eps_r = FR / E0
    eps_u = 2 * GF / (FR * LS)
    e = 0.5 * (max(eps_u, eps_r) + EPS_Y)
    assert e > eps_u
    sig = call(CONCRETE, p, e)[0]
    assert abs(sig - 0.5 * FR * (EPS_Y - e) / (EPS_Y - eps_r)) <= 1e-9 * FR
    assert call(CONCRETE, p, EPS_Y * 1.001)[0] == 0.0
    G = E0 / 2.4
    # shear retention follows the committed crack strain (hist[1]), not the trial strain
    _, tau, _, g_t = call(CONCRETE, p, 0.0, 1e-4, hist(0.0, e))
    assert abs(g_t - 0.25 * (1 - e / EPS_Y) * G) <= 1e-12 * G and abs(tau - g_t * 1e-4) <= 1e-12 * G * 1e-4
    assert abs(call(CONCRETE, p, e, 1e-4)[3] - G) <= 1e-12 * G  # not yet committed
    assert abs(call(CONCRETE, p, 0.0, 1e-4, hist(0.0, 1.5 * EPS_Y))[3] - 1e-4 * G) <= 1e-12 * G  # floor
    assert abs(call(CONCRETE, p, 0.0, 1e-4, hist(0.004, 0.0))[3] - 1e-4 * G) <= 1e-12 * G  # crushed
    assert abs(call(CONCRETE, p, 0.5 * eps_r, 1e-4)[3] - G) <= 1e-12 * G  # uncracked


def test_steel_bilinear_hardening_and_unloading():
    EH = 2.0e9
    p = steel(EH)
    ey = 500e6 / 200e9
    path = np.array([0.0, 0.5 * ey, ey, 4 * ey, 3 * ey, 0.0, -4 * ey])
    sig, tau, e_t, _, h = rc.drive(STEEL, p, path)
    assert abs(sig[2] - 500e6) <= 1e-9 * 500e6
    assert abs(sig[3] - (500e6 + EH * 3 * ey)) <= 1e-9 * 500e6  # hardening slope EH
    assert abs(sig[4] - (sig[3] - 200e9 * ey)) <= 1e-9 * 500e6  # unloading slope Es
    assert abs(h[4, 0] - h[3, 0]) == 0.0 and np.all(tau == 0.0)
    assert e_t[3] == pytest.approx(EH, rel=1e-12) and e_t[4] == 200e9
    # perfectly plastic (EH = 0): plateau at fy
    sig0 = rc.drive(STEEL, steel(0.0), [0.0, ey, 3 * ey])[0]
    assert abs(sig0[-1] - 500e6) <= 1e-9 * 500e6


CONCRETE_BRANCHES = [
    ("elastic tension", 5e-5, hist()),
    ("elastic compression", -1e-4, hist()),
    ("ascending envelope", -1e-3, hist()),
    ("descending envelope", -0.003, hist(0.0025, 0.0)),
    ("unloading in compression", -0.002, hist(0.0028, 0.0)),
    ("reloading tension after compression", 2e-5, hist(0.0012, 0.0)),
    ("softening", 3e-4, hist(0.0, 2e-4)),
    ("tension stiffening", 1.5e-3, hist(0.0, 1.2e-3)),
    ("secant unloading", 1e-4, hist(0.0, 4e-4)),
    ("fully cracked", 4e-3, hist(0.0, 3e-3)),
    ("unloading from crushing", -0.001, hist(0.004, 0.0)),
    ("crushing branch", -0.005, hist(0.0045, 0.0)),
]


@pytest.mark.parametrize("name,eps,h", CONCRETE_BRANCHES, ids=[b[0] for b in CONCRETE_BRANCHES])
def test_concrete_fd_tangent_every_branch(name, eps, h):
    fd_check(CONCRETE, concrete(), eps, 1e-4, h)


@pytest.mark.parametrize(
    "eps,h",
    [(1e-3, hist()), (4e-3, hist()), (-4e-3, hist()), (2e-3, hist(5e-3)), (7e-3, hist(5e-3 - 2.0 / 200))],
)
def test_steel_fd_tangent_every_branch(eps, h):
    fd_check(STEEL, steel(), eps, 0.0, h)


def test_elastic_branch_unchanged_and_k0_moduli():
    E, nu = 30e9, 0.2
    assert call(ELASTIC, np.array([E, nu]), 1e-4, 2e-4) == pytest.approx(
        (E / (1 - nu**2) * 1e-4, E / 2.4 * 2e-4, E / (1 - nu**2), E / 2.4), rel=1e-14
    )
    # K0 (tangent = 0) always returns the pristine moduli, whatever the state
    assert call(CONCRETE, concrete(), 3e-4, 0.0, hist(0.0, 2e-4), tangent=0)[2:] == (E0, E0 / 2.4)
    assert call(STEEL, steel(), 0.01, 0.0, hist(), tangent=0)[2:] == (200e9, 0.0)


def test_validation_messages():
    limit = rc.snap_back_limit(E0, GF, FR)
    with pytest.raises(ValueError) as err:
        concrete(ls=1.01 * limit)
    for word in ("ls", "Gf", "fr", "E0"):
        assert word in str(err.value)
    with pytest.raises(ValueError, match="E0"):
        rc.concrete_params(FC, -E0, EPS_C, FR, GF, LS, EPS_Y)
    with pytest.raises(ValueError, match="eps_c"):
        rc.concrete_params(FC, E0, 0.0015, FR, GF, LS, EPS_Y)  # a = 1.5 < 2
    with pytest.raises(ValueError, match="eps_y"):
        rc.concrete_params(FC, E0, EPS_C, FR, GF, LS, 0.5 * FR / E0)
    with pytest.raises(ValueError, match="EH"):
        rc.steel_params(500e6, 200e9, 200e9)
    with pytest.raises(ValueError, match="EH"):
        rc.steel_params(500e6, 200e9, -1e9)
    with pytest.raises(ValueError, match="Es"):
        rc.steel_params(500e6, -200e9)
    with pytest.raises(ValueError, match="beta_floor"):
        concrete(beta_floor=0.5)


def test_designer_values_mc2010():
    d = rc.designer_concrete(
        38e6
    )  # C30 (fck = 30 MPa): MC2010 tabulates Eci = 33.6 GPa, fctm = 2.9 MPa (rounded)
    assert d["E0"] == pytest.approx(33.6e9, rel=2e-3)
    assert d["fr"] == pytest.approx(2.9e6, rel=5e-3)
    assert d["E0"] * d["eps_c"] / 38e6 == pytest.approx(2.0, rel=1e-14)


def test_crushing_regularised_by_energy():
    """Beyond eps_cu the stress falls linearly from f(eps_cu) to zero (no cliff); the energy dissipated past
    eps_cu per unit volume is Gc / ls (trapezoid rule on a piecewise-linear curve: exact up to round-off and
    the one step that straddles eps_cd, 1e-3 with 20 000 steps); Gc = 0 is the cliff; a crushed point carries
    no tension on reloading."""
    Gc = 20e3
    p = concrete(Gc=Gc)
    f_cu = compression_envelope(0.0035 * (1 - 1e-12), E0, FC, EPS_C, 0.0035)[0]
    eps_cd = 0.0035 + 2 * Gc / (f_cu * LS)
    path = -np.linspace(0.0035, eps_cd * 1.05, 20001)
    sig = rc.drive(CONCRETE, p, path)[0]
    assert abs(sig[0] + f_cu) <= 1e-6 * FC  # continuous at eps_cu
    assert np.all(np.diff(-sig) <= 1e-9 * FC) and sig[-1] == 0.0  # falls to zero, then stays there
    energy = np.trapezoid(-sig, -path)
    assert energy == pytest.approx(Gc / LS, rel=1e-3)
    cliff = rc.drive(CONCRETE, concrete(Gc=0.0), -np.array([0.0034, 0.0035]))[0]
    assert cliff[-1] == 0.0 and cliff[0] < -0.5 * FC
    back = rc.drive(CONCRETE, p, np.array([-0.004, -0.0038, 0.001]))[0]  # eps_p = 0.004 - f/E0 ~ 0.0032
    assert back[1] < 0.0 and back[2] == 0.0
    with pytest.raises(ValueError, match="Gc"):
        concrete(Gc=-1.0)


def test_plane_strain_concrete():
    """Plane strain: the axial law's modulus is E0/(1 - nu^2) (the D1 of eq. 4.4, as for an ELASTIC layer),
    the strengths stay, G stays E0/(2(1 + nu)); the K0 modulus follows."""
    nu = 0.2
    ps = concrete(plane_strain=True, nu=nu)
    sig, _, e_t, g_t = call(CONCRETE, ps, 1e-5, 1e-4)
    assert e_t == pytest.approx(E0 / (1 - nu**2), rel=1e-12) and sig == pytest.approx(e_t * 1e-5, rel=1e-12)
    assert g_t == pytest.approx(E0 / (2 * (1 + nu)), rel=1e-12)
    assert call(CONCRETE, ps, 0.0, 0.0, tangent=0)[2] == pytest.approx(E0 / (1 - nu**2), rel=1e-12)
    assert call(CONCRETE, ps, -EPS_C)[0] == pytest.approx(-FC, rel=1e-12)  # peak unchanged
    assert call(CONCRETE, concrete(nu=nu), 1e-5)[2] == E0  # default: uniaxial
    elastic = call(ELASTIC, rc.elastic_params(E0, nu), 1e-5)[2]
    assert elastic == pytest.approx(e_t, rel=1e-12)  # consistent with ELASTIC
