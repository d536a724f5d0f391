"""Unit tests of the layered plate-strip element (ssi.elements.plate) and the section builder
(ssi.elements.section).

References are independent of the element: Timoshenko closed forms, transformed-section formulas, finite
differences of the element's own internal force (tangent check), statics (load resultants), and linear algebra
(rank / rigid-body modes). Tolerances: round-off level (1e-10 relative) where the result is exact in exact
arithmetic; the FD check tolerance follows from the central-difference truncation + round-off of the step
used.
"""

import numpy as np
import pytest

from ssi.core.model import Model
from ssi.core.protocol import CONSISTENT, K0_MATRIX
from ssi.elements.plate import PlateStrip, add_plate_strip, beam_mesh, beam_mesh_from_ends, integration_rule
from ssi.elements.section import homogeneous, layered, paper_rc_section, rc_section
from ssi.lab.verify import fd_jacobian, zero_energy_modes
from ssi.materials import rc
from ssi.materials.layer_laws import CONCRETE, STEEL
from ssi.materials.layer_laws import ELASTIC as K_ELASTIC

E, NU, H, L = 30.0e9, 0.2, 0.5, 5.0
E1 = E / (1.0 - NU**2)  # D1 of eq. (4.4), cylindrical bending
G = E / (2.0 * (1.0 + NU))  # D2 before the shear factor
KAPPA = 5.0 / 6.0
EI = E1 * H**3 / 12.0
KGA = KAPPA * G * H
ROUND = 1e-10  # exact-in-exact-arithmetic results: a few hundred ulps of conditioning


def one_element(section, integration="selective", x=(0.0, 1.0, 2.0), **kw):
    xy = np.column_stack([np.asarray(x, float), np.zeros(3)])
    return PlateStrip(xy[None], np.arange(9)[None], section, integration=integration, **kw)


def rc_test_section():
    conc = rc.concrete_params(fc=30e6, E0=30e9, eps_c=0.002, fr=3e6, Gf=100.0, ls=0.1, eps_y=2.5e-3)
    steel = rc.steel_params(fy=500e6, Es=200e9, EH=2e9)
    return paper_rc_section(0.5, 0.05, 1.5e-3, 0.8e-3, (CONCRETE, conc), (STEEL, steel))


# ---- element properties ------------------------------------------------------------------------------------
@pytest.mark.parametrize("make", [lambda: homogeneous(H, E, NU, 3), rc_test_section])
def test_zero_force_at_zero_displacement(make):
    g = one_element(make(), x=(0.0, 0.25, 0.5))
    zero = np.zeros((1, 9))
    f, k, s = g.evaluate(zero, zero, g.initial_state(), CONSISTENT)
    assert np.all(f == 0.0)
    assert np.all(s == 0.0)
    assert np.all(np.isfinite(k))


@pytest.mark.parametrize("integration", ["selective", "full", "reduced"])
def test_symmetric_stiffness(integration):
    g = one_element(rc_test_section(), integration, x=(0.0, 0.22, 0.5))  # off-centre mid node: J varies
    k = g.elastic_stiffness()[0]
    assert np.abs(k - k.T).max() <= ROUND * np.abs(k).max()


@pytest.mark.parametrize("n_el", [1, 4])
def test_rigid_body_modes_selective(n_el):
    """A free strip has exactly 3 zero-energy modes (u, w translations, rigid rotation w = theta x,
    alpha = theta) with selective integration; the stiffness of a 1-pt rule shows the spurious ones."""
    sec = homogeneous(H, E, NU, 2)
    for integration, expected in (("selective", 3), ("full", 3), ("reduced", 3)):
        m = Model()
        g, ids, _ = add_plate_strip(m, np.linspace(0.0, 2.0 * n_el, n_el + 1), sec, integration=integration)
        kg = np.zeros((m.n_dof, m.n_dof))
        for e in range(g.n_el):
            kg[np.ix_(g.edofs[e], g.edofs[e])] += g.elastic_stiffness()[e]
        assert zero_energy_modes(kg) == expected, integration
        # the rigid rotation is one of them: K r = 0
        x = m.coords[ids, 0]
        r = np.zeros(m.n_dof)
        r[m.dof(ids, "w")] = x
        r[m.dof(ids, "alpha")] = 1.0
        assert np.abs(kg @ r).max() <= ROUND * np.abs(kg).max()
    # one point for everything: 3 spurious modes in one element (6 zero eigenvalues)
    g1 = one_element(sec, (1, 1))
    assert zero_energy_modes(g1.elastic_stiffness()[0]) == 6


@pytest.mark.parametrize("n_layers", [1, 2, 11, 50])
def test_internal_force_equals_K0_u_for_elastic_layers(n_layers):
    """Mid-depth sampling + the exact self-bending term reproduces eq. (4.7b): f_int = K0 u."""
    rng = np.random.default_rng(n_layers)
    for self_bending in ("initial", "tangent", "chord"):
        g = one_element(homogeneous(H, E, NU, n_layers), x=(0.0, 1.1, 2.0), self_bending=self_bending)
        u = rng.standard_normal((1, 9)) * 1e-3
        f, k, _ = g.evaluate(u, u, g.initial_state(), CONSISTENT)
        assert np.abs(f[0] - g.elastic_stiffness()[0] @ u[0]).max() <= ROUND * np.abs(f).max()
        assert np.abs(k - g.elastic_stiffness()).max() <= ROUND * np.abs(k).max()


def test_layer_rule_exact_and_composite():
    """1, 2, 11 and 50 layers give the same stiffness; an asymmetric composite section matches the
    transformed-section neutral axis and EI."""
    ks = [one_element(homogeneous(H, E, NU, n)).elastic_stiffness()[0] for n in (1, 2, 11, 50)]
    for k in ks[1:]:
        assert np.abs(k - ks[0]).max() <= ROUND * np.abs(ks[0]).max()
    # concrete 0.4 m + steel plate 0.01 m on the bottom (both elastic, nu = 0 for a plain transformed section)
    hc, hs, Ec, Es = 0.4, 0.01, 30e9, 200e9
    sec = layered([hs, hc], K_ELASTIC, [[Es, 0.0], [Ec, 0.0]], carries_shear=[False, True])
    # transformed section, measured from the bottom face
    zc, zs = hs + hc / 2, hs / 2
    zna = (Ec * hc * zc + Es * hs * zs) / (Ec * hc + Es * hs)
    ei = Ec * (hc**3 / 12 + hc * (zc - zna) ** 2) + Es * (hs**3 / 12 + hs * (zs - zna) ** 2)
    props = sec.elastic_resultant_stiffness()
    assert abs(props["z_na"] - (zna + sec.z_bottom)) <= ROUND * (hc + hs)
    assert abs(props["D_na"] - ei) <= ROUND * ei
    assert abs(props["S"] - KAPPA * Ec / 2 * hc) <= ROUND * props["S"]  # steel carries no shear
    # the element with this section: cantilever tip load, exact nodal deflection with EI and kGA;
    # reference surface at the neutral axis removes the membrane-bending coupling
    sec_na = layered([hs, hc], K_ELASTIC, [[Es, 0.0], [Ec, 0.0]], carries_shear=[False, True], z_ref=zna)
    P, Lc = 1e4, 3.0
    m = Model()
    _, ids, _ = add_plate_strip(m, np.linspace(0.0, Lc, 4), sec_na)
    m.fix(ids[0], "u")
    m.fix(ids[0], "w")
    m.fix(ids[0], "alpha")
    m.add_load(ids[-1], "w", -P)
    w_tip = m.solve_linear().displacement(ids[-1], "w")[-1, 0]
    exact = -(P * Lc**3 / (3 * ei) + P * Lc / props["S"])
    assert abs(w_tip / exact - 1.0) <= ROUND


@pytest.mark.parametrize("self_bending", ["initial", "chord"])
@pytest.mark.parametrize("integration", ["selective", "full", "reduced"])
def test_tangent_matches_finite_differences(integration, self_bending):
    """Consistent tangent vs central differences of f_int, elastic and in a nonlinear RC state (cracked
    bottom, yielding steel, compressed top). Nonlinear states are pure bending on a straight element with a
    centred mid node, where gamma = 0 exactly, so the cross term d tau / d eps of cracked concrete that the
    layer interface does not return (layer_laws docstring) cannot enter; the elastic state uses an
    off-centre mid node (variable Jacobian).

    The tangent is exact for ``self_bending="initial"`` and ``"chord"`` (non-symmetric for the chord:
    dM/deps0 != dN/dkap once a layer is nonlinear); ``"tangent"`` omits d e_t/d eps of the
    self-bending term (plate docstring), so there only the elastic state is exact and is checked in
    :func:`test_tangent_self_bending_exact_while_elastic`."""
    sec = rc_test_section()
    eps0 = 2.0e-5  # well below the cracking strain fr/E0 = 1e-4 (a kink of the law)
    # elastic; cracked bottom; bottom steel (z = -0.2) strained 0.2 * 0.02 = 4e-3 > fy/Es = 2.5e-3
    for x_mid, kap in ((0.55, 1e-5), (0.5, 0.004), (0.5, 0.02)):
        g = one_element(sec, integration, x=(0.0, x_mid, 1.0), self_bending=self_bending)
        # pure bending with curvature kap: alpha = kap x, w = kap x^2 / 2, plus a small stretch
        x = g.coords[0, :, 0]
        u = np.zeros((1, 9))
        u[0, 0::3] = eps0 * x
        u[0, 1::3] = 0.5 * kap * x**2
        u[0, 2::3] = kap * x
        _f, k, _ = g.evaluate(u, u, g.initial_state(), CONSISTENT)
        k_fd = fd_jacobian(lambda v, g=g: g.evaluate(v, v, g.initial_state(), CONSISTENT)[0][0], u, 1e-9)
        # round-off of the difference: 2e-16 |f| / step ~ 2e-16 * 1e8 / 1e-9 = 20, against |k| ~ 1e10
        # (2e-9 relative); truncation step^2 |f'''| is far smaller; 1e-6 leaves room for neither kinks nor
        # bugs
        assert np.abs(k_fd - k[0]).max() <= 1e-6 * np.abs(k[0]).max(), kap


def test_tangent_self_bending_exact_while_elastic():
    """Self-bending "tangent": central differences of f_int equal the consistent tangent in the elastic state
    (off-centre mid node), where no layer's modulus depends on its strain."""
    assert one_element(rc_test_section(), x=(0.0, 0.5, 1.0)).self_bending == "chord"  # the default
    g = one_element(rc_test_section(), "selective", x=(0.0, 0.55, 1.0), self_bending="tangent")
    x = g.coords[0, :, 0]
    u = np.zeros((1, 9))
    u[0, 0::3] = 2.0e-5 * x
    u[0, 1::3] = 0.5e-5 * x**2
    u[0, 2::3] = 1e-5 * x
    k = g.evaluate(u, u, g.initial_state(), CONSISTENT)[1][0]
    k_fd = np.empty((9, 9))
    for j in range(9):
        up, um = u.copy(), u.copy()
        up[0, j] += 1e-9
        um[0, j] -= 1e-9
        k_fd[:, j] = (
            g.evaluate(up, up, g.initial_state(), CONSISTENT)[0][0]
            - g.evaluate(um, um, g.initial_state(), CONSISTENT)[0][0]
        ) / 2e-9
    assert np.abs(k_fd - k).max() <= 1e-6 * np.abs(k).max()


def test_force_independent_of_tangent_flag_and_K0_constant():
    """Modified Newton needs f(u) whatever matrix is requested, and the K0_MATRIX flag must give K0 in any
    state (cracked, yielding): checked in a strongly nonlinear bending state with shear."""
    g = one_element(rc_test_section(), x=(0.0, 0.45, 1.0))
    rng = np.random.default_rng(7)
    x = g.coords[0, :, 0]
    u = np.zeros((1, 9))
    u[0, 1::3] = 0.5 * 0.02 * x**2 + 1e-4 * rng.standard_normal(3)
    u[0, 2::3] = 0.02 * x
    f1, k1, s1 = g.evaluate(u, u, g.initial_state(), CONSISTENT)
    f0, k0, s0 = g.evaluate(u, u, g.initial_state(), K0_MATRIX)
    assert np.array_equal(f0, f1) and np.array_equal(s0, s1)
    assert np.array_equal(k0, g.elastic_stiffness())
    assert np.abs(k1 - k0).max() > 0.1 * np.abs(k0).max()  # the state is really nonlinear


def test_layer_stresses_integrate_to_resultants():
    """Layer stresses recovered for plotting integrate (with the self-bending term) to N and M of the element,
    and vanish in steel layers' shear (self-bending with the initial moduli, which the sum below uses)."""
    sec = rc_test_section()
    g = one_element(sec, x=(0.0, 0.5, 1.0), self_bending="initial")
    x = g.coords[0, :, 0]
    u = np.zeros((1, 9))
    u[0, 0::3] = 2e-4 * x
    u[0, 1::3] = 0.5 * 0.006 * x**2 + 1e-4 * x  # plus a uniform shear strain 1e-4
    u[0, 2::3] = 0.006 * x
    sig, tau = g.layer_stresses(u)
    res = g.resultants(u)
    ax = g.ax.astype(bool)
    e0, _ = sec.initial_moduli()
    n_sum = (sig[0][ax] * sec.h).sum(axis=1)
    m_sum = (-sig[0][ax] * sec.h * sec.z_mid).sum(axis=1) + (e0 * sec.h**3 / 12).sum() * 0.006
    assert np.allclose(n_sum, res["N"][0], rtol=1e-12, atol=0)
    assert np.allclose(m_sum, res["M"][0], rtol=1e-12, atol=0)
    assert sig[0, 0, 0] > 0 > sig[0, 0, -1]  # sagging: bottom in tension, top compressed
    shear = g.sh.astype(bool)
    q_sum = g.kappa * (tau[0][shear] * np.where(sec.carries_shear, sec.h, 0.0)).sum(axis=1)
    assert np.allclose(q_sum, res["Q"][0], rtol=1e-12, atol=0) and np.all(res["Q"][0] > 0)


# ---- Timoshenko closed forms (global, through Model) -------------------------------------------------------
def strip(n_el, length=L, integration="selective", n_layers=1):
    m = Model()
    g, ids, _ = add_plate_strip(
        m, np.linspace(0.0, length, n_el + 1), homogeneous(H, E, NU, n_layers), integration=integration
    )
    return m, g, ids


@pytest.mark.parametrize("n_el", [2, 4, 8])
def test_simply_supported_uniform_load(n_el):
    q = -2.0e4
    m, g, ids = strip(n_el)
    m.fix(ids[0], "u")
    m.fix(ids[0], "w")
    m.fix(ids[-1], "w")
    m.add_element_load(g.edofs, g.distributed_load(q))
    r = m.solve_linear()
    ends = ids[0::2]  # element end nodes: nodally exact (superconvergent)
    x = m.coords[ends, 0]
    exact = (q / (24 * EI)) * x * (L**3 - 2 * L * x**2 + x**3) + (q / (2 * KGA)) * x * (L - x)
    # the shear part: w_s'' = -q/kGA with w_s(0) = w_s(L) = 0 (q negative, downwards)
    assert np.abs(r.displacement(ends, "w")[-1] - exact).max() <= ROUND * np.abs(exact).max()
    assert abs(r.reactions()[m.dof([ids[0], ids[-1]], "w")].sum() + q * L) <= ROUND * abs(q * L)


@pytest.mark.parametrize("n_el", [2, 4])
def test_simply_supported_central_point_load(n_el):
    P = -1.0e5
    m, _g, ids = strip(n_el)
    m.fix(ids[0], "u")
    m.fix(ids[0], "w")
    m.fix(ids[-1], "w")
    mid = ids[len(ids) // 2]
    m.add_load(mid, "w", P)
    w = m.solve_linear().displacement(mid, "w")[-1, 0]
    exact = P * L**3 / (48 * EI) + P * L / (4 * KGA)
    assert abs(w / exact - 1.0) <= ROUND


@pytest.mark.parametrize("n_el", [1, 3])
def test_cantilever_tip_load_and_resultants(n_el):
    P = -1.0e5
    m, g, ids = strip(n_el)
    m.fix(ids[0], "u")
    m.fix(ids[0], "w")
    m.fix(ids[0], "alpha")
    m.add_load(ids[-1], "w", P)
    r = m.solve_linear()
    x = m.coords[ids, 0]
    w_exact = P * x**2 * (3 * L - x) / (6 * EI) + P * x / KGA
    a_exact = P * (2 * L * x - x**2) / (2 * EI)
    assert np.abs(r.displacement(ids, "w")[-1] - w_exact).max() <= ROUND * np.abs(w_exact).max()
    assert np.abs(r.displacement(ids, "alpha")[-1] - a_exact).max() <= ROUND * np.abs(a_exact).max()
    res = g.resultants(r.u[-1][g.edofs])
    # statics: M(x) = P (L - x) (sagging positive; a downward tip load P < 0 gives hogging M < 0) and the
    # shear force Q = kGA gamma = P (gamma = w' - alpha = P / kGA)
    assert np.abs(res["M"] - P * (L - res["x_ax"])).max() <= ROUND * abs(P * L)
    assert np.abs(res["Q"] - P).max() <= ROUND * abs(P)
    assert np.abs(res["N"]).max() <= ROUND * abs(P)


def test_full_integration_locks_selective_does_not():
    """Thin strip (span/depth 1000, simply supported, uniform load, 4 elements). Fully integrated shear forces
    gamma = 0 at every point, i.e. alpha'' = 0 in each element (Prathap's spurious constraint): the strip can
    only bend with piecewise-constant curvature: a deflection deficit 4/(5 n^2) (5 % with 4 elements) that
    does not vanish as the strip gets thinner, and wild shear-force oscillations. Selective integration is
    nodally exact at any slenderness."""
    q, length, n_el = -1.0, 1000.0 * H, 4
    exact = 5 * q * length**4 / (384 * EI) + q * length**2 / (8 * KGA)
    out = {}
    for integration in ("selective", "full"):
        m, g, ids = strip(n_el, length, integration)
        m.fix(ids[0], "u")
        m.fix(ids[0], "w")
        m.fix(ids[-1], "w")
        m.add_element_load(g.edofs, g.distributed_load(q))
        r = m.solve_linear()
        out[integration] = r.displacement(ids[len(ids) // 2], "w")[-1, 0] / exact
        out[integration + "_Q"] = g.resultants(r.u[-1][g.edofs])
    assert abs(out["selective"] - 1.0) <= 1e-6  # conditioning ~ (L/h)^2 = 1e6 times round-off
    # thin limit derived in chapter 02: curvature = element mean of M/EI, deficit 4/(5 n^2) = 0.05; the finite
    # shear penalty at L/h = 1000 (l_e/h = 250) leaves a remainder O((h/l_e)^2) ~ 1.6e-5
    assert abs(out["full"] - (1.0 - 4.0 / (5 * n_el**2))) <= 1e-4
    m, g, ids = strip(n_el, 10.0 * H, "full")  # the same mesh on a thick strip locks much less
    m.fix(ids[0], "u")
    m.fix(ids[0], "w")
    m.fix(ids[-1], "w")
    m.add_element_load(g.edofs, g.distributed_load(q))
    thick = m.solve_linear().displacement(ids[len(ids) // 2], "w")[-1, 0] / (
        5 * q * (10 * H) ** 4 / (384 * EI) + q * (10 * H) ** 2 / (8 * KGA)
    )
    assert 1.0 - thick < 0.5 * (1.0 - out["full"])
    # shear force at the shear points: selective matches statics Q = q (L/2 - x), full oscillates
    for key, tol in (("selective_Q", 1e-6), ("full_Q", None)):
        res = out[key]
        err = np.abs(res["Q"] - q * (length / 2 - res["x_sh"])).max() / abs(q * length / 2)
        if tol is None:
            assert err > 1.0
        else:
            assert err <= tol


# ---- loads, meshes, sections, input checks -----------------------------------------------------------------
def test_distributed_load_resultants():
    """Equivalent nodal forces carry the load's resultant and its moment (linear and callable loads)."""
    xy, conn = beam_mesh_from_ends([0.0, 0.7, 2.0, 2.3])
    g = PlateStrip(xy[conn], np.arange(27).reshape(3, 9), homogeneous(H, E, NU))
    x = xy[:, 0]
    qa, qb = 3.0, -5.0

    def lin(s):
        return qa + (qb - qa) * s / 2.3

    ends = np.column_stack([lin(x[conn[:, 0]]), lin(x[conn[:, 2]])])
    total = 2.3 * (qa + qb) / 2
    moment = qa * 2.3**2 / 2 + (qb - qa) * 2.3**2 / 3
    for q in (ends, lambda s: lin(s)):
        f = g.distributed_load(q, comp="w")
        fw = f[:, 1::3]
        xn = x[conn]
        assert abs(fw.sum() - total) <= 1e-12 * abs(total) * 10
        assert abs((fw * xn).sum() - moment) <= 1e-12 * abs(moment) * 10
        assert np.all(f[:, 0::3] == 0.0) and np.all(f[:, 2::3] == 0.0)
    # quadratic load through the callable (exact, 4-point rule), elements mask
    f = g.distributed_load(lambda s: s**2, comp="u", elements=[1])
    assert abs(f[:, 0::3].sum() - (2.0**3 - 0.7**3) / 3) <= 1e-12
    assert np.all(f[[0, 2]] == 0.0)


def test_self_weight_body_force():
    g = one_element(homogeneous(H, E, NU), x=(0.0, 1.0, 2.0), self_weight=25e3 * H)
    f = g.body_force()
    assert abs(f[0, 1::3].sum() + 25e3 * H * 2.0) <= 1e-9
    assert one_element(homogeneous(H, E, NU)).body_force() is None


def test_meshes_and_bottom_face():
    xy, conn = beam_mesh(1.0, 3.0, 4, z=0.25)
    assert xy.shape == (9, 2) and conn.shape == (4, 3)
    assert np.allclose(xy[conn[:, 1], 0], 0.5 * (xy[conn[:, 0], 0] + xy[conn[:, 2], 0]))
    assert np.all(xy[:, 1] == 0.25)
    g = one_element(homogeneous(0.6, E, NU))
    assert g.thickness == pytest.approx(0.6) and g.bottom_offset == pytest.approx(0.3)
    g = one_element(layered([0.2, 0.4], K_ELASTIC, [E, NU], z_ref=0.1))
    assert g.z_bottom == pytest.approx(-0.1) and g.bottom_offset == pytest.approx(0.1)


def test_paper_rc_section_layout():
    sec = rc_test_section()
    assert sec.n_layer == 11
    steel = np.flatnonzero(sec.kind == STEEL)
    assert steel.tolist() == [1, 9]  # layers 2 and 10, counted from 1
    assert not sec.carries_shear[steel].any() and sec.carries_shear[sec.kind == CONCRETE].all()
    assert sec.h.sum() == pytest.approx(0.5, rel=1e-14)
    assert sec.z_mid[1] == pytest.approx(-0.25 + 0.05) and sec.z_mid[9] == pytest.approx(0.25 - 0.05)
    assert sec.h[1] == pytest.approx(1.5e-3) and sec.h[9] == pytest.approx(0.8e-3)
    # general builder: 3 bar layers and the largest-remainder split of the concrete layers
    sec3 = rc_section(
        1.0,
        [(0.1, 1e-3), (0.5, 1e-3), (0.9, 1e-3)],
        (K_ELASTIC, [E, NU]),
        (K_ELASTIC, [200e9, 0.0]),
        n_concrete=10,
    )
    assert sec3.n_layer == 13 and (sec3.kind == K_ELASTIC).all()
    assert np.all(np.diff(sec3.z_mid) > 0)


def test_crack_band_width_per_point():
    """With crack_band='point' each concrete layer's ls is the length its point represents; a long element
    beyond the snap-back limit is refused with a clear error."""
    sec = rc_test_section()
    g = one_element(sec, x=(0.0, 0.5, 1.0))
    assert g.band.sum() == 9
    with pytest.raises(ValueError, match="crack band"):
        one_element(sec, x=(0.0, 50.0, 100.0))
    assert not one_element(sec, x=(0.0, 50.0, 100.0), crack_band=None).band.any()


def test_integration_rules_and_bad_input():
    xi, w, ax, sh = integration_rule("selective")
    assert len(xi) == 5 and ax.tolist() == [1, 1, 1, 0, 0] and sh.tolist() == [0, 0, 0, 1, 1]
    assert abs(w[ax == 1].sum() - 2.0) < 1e-15 and abs(w[sh == 1].sum() - 2.0) < 1e-15
    assert len(integration_rule("full")[0]) == 3 and len(integration_rule("reduced")[0]) == 2
    sec = homogeneous(H, E, NU)
    with pytest.raises(ValueError, match="integration"):
        one_element(sec, "exact")
    with pytest.raises(ValueError, match="self_bending"):
        one_element(sec, self_bending="secant")
    with pytest.raises(ValueError, match="kappa"):
        one_element(sec, kappa=0.0)
    with pytest.raises(ValueError, match="coords"):
        one_element(sec, x=(2.0, 1.0, 0.0))
    with pytest.raises(ValueError, match="thicknesses"):
        layered([0.1, -0.1], K_ELASTIC, [E, NU])
    with pytest.raises(ValueError, match="overlaps"):
        rc_section(0.5, [(0.001, 1e-2)], (K_ELASTIC, [E, NU]), (K_ELASTIC, [200e9, 0.0]))
    with pytest.raises(ValueError, match="x_ends"):
        beam_mesh_from_ends([0.0, 0.0])
