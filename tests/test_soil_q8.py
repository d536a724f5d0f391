"""The 8-node serendipity soil element and what it stands on: shape functions, quadrature, the element
stiffness, CSR assembly, elimination of supports, the strip-load closed form and the checks on bad input.

Every expected value is independent of the code under test: polynomial identities, closed-form integrals, a
dense NumPy re-implementation, patch-test fields, Flamant's line-load solution.
"""

import numpy as np
import pytest

from ssi.core.assembly import SparsePattern
from ssi.core.mesh import foundation_contact, soil_block, structured_q8
from ssi.core.model import Model
from ssi.core.protocol import CONSISTENT, FORCES_ONLY, K0_MATRIX
from ssi.core.quadrature import gauss_2d, gauss_legendre, newton_cotes
from ssi.core.shapes import LINE3_NODES, Q8_NODES, lagrange3, serendipity8
from ssi.elements.q8_elastic import q8_elastic_stiffness
from ssi.elements.soil_q8 import SoilQ8
from ssi.lab.analytical_soil import flamant_strip_quadrature, strip_load_stresses
from ssi.lab.verify import dense_stiffness, distorted_q8_mesh, fd_jacobian, zero_energy_modes
from ssi.materials.soil_laws import ELASTIC, elastic_params

# Round-off tolerances: all quantities below are O(1) sums of at most a few hundred O(1) terms in float64,
# so 1e-12 (relative) leaves a factor ~100 over the accumulated round-off; patch tests use the 1e-10.
TOL_ROUNDOFF = 1e-12
TOL_PATCH = 1e-10
E, NU = 30e6, 0.3


def q8_group(xy, conn, model, n_gauss=2, nu=NU):
    return SoilQ8(xy[conn], model.element_dofs(conn), 0, [ELASTIC], [elastic_params(E, nu)], n_gauss=n_gauss)


def dense_q8_stiffness(xy8, n_gauss, E_, nu):
    """Independent dense reference: K = sum_q w_q det J B^T D B with NumPy matrices (rows exx, ezz, gxz)."""
    lam = E_ * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E_ / (2 * (1 + nu))
    D = np.array([[lam + 2 * mu, lam, 0], [lam, lam + 2 * mu, 0], [0, 0, mu]])
    K = np.zeros((16, 16))
    for (xi, eta), w in zip(*gauss_2d(n_gauss)):
        _, dn = getattr(serendipity8, "py_func", serendipity8)(xi, eta)  # plain Python (also without JIT)
        J = dn.T @ xy8  # J[i, k] = d x_k / d xi_i
        dndx = dn @ np.linalg.inv(J).T
        B = np.zeros((3, 16))
        B[0, 0::2] = dndx[:, 0]
        B[1, 1::2] = dndx[:, 1]
        B[2, 0::2] = dndx[:, 1]
        B[2, 1::2] = dndx[:, 0]
        K += w * np.linalg.det(J) * B.T @ D @ B
    return K


# ---- shape functions ------------------------------------------------------------------------------------
def test_serendipity_identities():
    rng = np.random.default_rng(0)
    for xi, eta in rng.uniform(-1, 1, (20, 2)):
        n, dn = serendipity8(xi, eta)
        assert abs(n.sum() - 1.0) < TOL_ROUNDOFF  # partition of unity
        assert np.abs(dn.sum(axis=0)).max() < TOL_ROUNDOFF  # derivatives of a constant vanish
        # reproduces linear fields: sum N_a x_a = x
        assert abs(n @ Q8_NODES[:, 0] - xi) < TOL_ROUNDOFF and abs(n @ Q8_NODES[:, 1] - eta) < TOL_ROUNDOFF
        # derivatives against central differences, truncation O(h^2) ~ 1e-12 with h = 1e-6 plus round-off
        h = 1e-6
        fd = fd_jacobian(lambda p: serendipity8(p[0], p[1])[0], [xi, eta], h)
        assert np.abs(fd - dn).max() < 1e-8
    for a, (xi, eta) in enumerate(Q8_NODES):  # Kronecker property
        n, _ = serendipity8(xi, eta)
        assert np.abs(n - np.eye(8)[a]).max() < TOL_ROUNDOFF


def test_lagrange3_identities():
    for a, xi in enumerate(LINE3_NODES):
        n, _ = lagrange3(xi)
        assert np.abs(n - np.eye(3)[a]).max() < TOL_ROUNDOFF
    for xi in np.linspace(-1, 1, 7):
        n, dn = lagrange3(xi)
        assert abs(n.sum() - 1) < TOL_ROUNDOFF and abs(dn.sum()) < TOL_ROUNDOFF
        assert abs(n @ LINE3_NODES**2 - xi**2) < TOL_ROUNDOFF  # quadratic reproduction


# ---- quadrature -----------------------------------------------------------------------------------------
@pytest.mark.parametrize("n", [1, 2, 3, 4, 5])
def test_gauss_legendre_exact_to_degree_2n_minus_1(n):
    p, w = gauss_legendre(n)
    for k in range(2 * n):
        exact = 0.0 if k % 2 else 2.0 / (k + 1)
        assert abs(w @ p**k - exact) < TOL_ROUNDOFF
    k = 2 * n  # the first degree it cannot integrate
    assert abs(w @ p**k - 2.0 / (k + 1)) > 1e-3


def test_newton_cotes_and_tensor_rule():
    p, w = newton_cotes(3)  # Simpson: exact to degree 3, not 4
    assert all(abs(w @ p**k - (0.0 if k % 2 else 2.0 / (k + 1))) < TOL_ROUNDOFF for k in range(4))
    assert abs(w @ p**4 - 0.4) > 1e-2
    p, w = newton_cotes(2)
    assert abs(w @ p - 0.0) < TOL_ROUNDOFF and abs(w.sum() - 2) < TOL_ROUNDOFF
    for n in (2, 3):
        pts, wts = gauss_2d(n)
        for i in range(2 * n):
            for j in range(2 * n):
                exact = (0.0 if i % 2 else 2 / (i + 1)) * (0.0 if j % 2 else 2 / (j + 1))
                assert abs(wts @ (pts[:, 0] ** i * pts[:, 1] ** j) - exact) < TOL_ROUNDOFF


# ---- element stiffness ----------------------------------------------------------------------------------
def single_element(n_gauss, xy8=None):
    xy8 = Q8_NODES * [1.5, 0.8] if xy8 is None else xy8
    return SoilQ8(xy8[None], np.arange(16)[None], 0, [ELASTIC], [elastic_params(E, NU)], n_gauss=n_gauss)


@pytest.mark.parametrize("n_gauss", [2, 3])
def test_q8_stiffness_matches_dense_reference(n_gauss):
    _, xy = distorted_q8_mesh(1, amplitude=0.0)
    xy8 = xy[structured_q8([0, 1], [0, 1]).conn[0]] + np.array(
        [[0.1, 0.05], [-0.1, 0.0], [0.05, 0.1], [0, -0.12], [0, 0], [0.02, 0], [0, 0.03], [0, 0]]
    )
    K = single_element(n_gauss, xy8).elastic_stiffness()[0]
    K_ref = dense_q8_stiffness(xy8, n_gauss, E, NU)
    assert np.abs(K - K_ref).max() < TOL_ROUNDOFF * np.abs(K_ref).max()
    assert np.abs(K - K.T).max() < TOL_ROUNDOFF * np.abs(K).max()


def test_zero_force_at_zero_state_and_rotation_covariance():
    g = single_element(2)
    z = np.zeros((1, 16))
    f, _, s = g.evaluate(z, z, g.initial_state(), K0_MATRIX)
    assert np.all(f == 0.0) and np.all(s == 0.0)
    # rotating the element by theta rotates K: K_rot = R K R^T with R = blockdiag(rot)
    theta = 0.7
    rot = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    xy8 = Q8_NODES * [1.5, 0.8]
    K = g.elastic_stiffness()[0]
    K_rot = single_element(2, xy8 @ rot.T).elastic_stiffness()[0]
    R = np.kron(np.eye(8), rot)
    assert np.abs(K_rot - R @ K @ R.T).max() < TOL_ROUNDOFF * np.abs(K).max()


def test_zero_energy_modes():
    # one element: 3 rigid-body modes with 3x3, plus one spurious (hourglass) mode with 2x2
    assert zero_energy_modes(single_element(3).elastic_stiffness()[0]) == 3
    assert zero_energy_modes(single_element(2).elastic_stiffness()[0]) == 4
    # an unsupported mesh of several elements with 2x2: the spurious mode does not survive assembly
    m, xy = distorted_q8_mesh(3)
    model = Model()
    model.add_nodes(xy, 2)
    g = q8_group(xy, m.conn, model, 2)
    K = dense_stiffness(model.n_dof, [g])
    assert zero_energy_modes(K) == 3


@pytest.mark.parametrize("n_gauss", [2, 3])
def test_distorted_patch_test(n_gauss):
    """Linear displacement on the boundary -> the same linear field inside and a constant stress."""
    m, xy = distorted_q8_mesh(3)
    model = Model()
    ids = model.add_nodes(xy, 2)
    g = model.add_group(q8_group(xy, m.conn, model, n_gauss))
    a = np.array([1e-3, 2e-3, -1.5e-3, 0.5e-3, 3e-3, -1e-3])  # u = a0 + a1 x + a2 z, w = a3 + a4 x + a5 z

    def exact(p):
        return np.column_stack(
            [a[0] + a[1] * p[:, 0] + a[2] * p[:, 1], a[3] + a[4] * p[:, 0] + a[5] * p[:, 1]]
        )

    boundary = np.unique(np.concatenate([m.left, m.right, m.bottom, m.surface]))
    ue = exact(xy[boundary])
    for k, node in enumerate(boundary):
        model.fix([node], "u", ue[k, 0])
        model.fix([node], "w", ue[k, 1])
    res = model.solve_linear()
    u = np.column_stack([res.displacement(ids, "u")[-1], res.displacement(ids, "w")[-1]])
    assert np.abs(u - exact(xy)).max() < TOL_PATCH * np.abs(a).max()
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    exx, ezz, gxz = a[1], a[5], a[2] + a[4]
    sig = np.array(
        [lam * (exx + ezz) + 2 * mu * exx, lam * (exx + ezz) + 2 * mu * ezz, mu * gxz, lam * (exx + ezz)]
    )
    s = g.stress(res.final_state[0])
    assert np.abs(s - sig).max() < TOL_PATCH * np.abs(sig).max()


# ---- assembly and supports ------------------------------------------------------------------------------
def test_csr_assembly_matches_dense():
    m, xy = distorted_q8_mesh(3)
    model = Model()
    model.add_nodes(xy, 2)
    g = q8_group(xy, m.conn, model, 3)
    K = dense_stiffness(model.n_dof, [g])
    free = np.ones(model.n_dof, bool)
    free[model.dof(m.bottom, "w")] = False
    free[model.dof(m.left, "u")] = False
    pattern = SparsePattern([g.edofs], free)
    Kff = pattern.matrix(pattern.assemble([g.elastic_stiffness()])).toarray()
    assert np.abs(Kff - K[np.ix_(free, free)]).max() < TOL_ROUNDOFF * np.abs(K).max()
    # the pattern holds exactly the structurally non-zero couplings (no explicit zeros beyond them)
    coupled = np.zeros_like(K, bool)
    for ed in g.edofs:
        coupled[np.ix_(ed, ed)] = True
    assert pattern.nnz == np.count_nonzero(coupled[np.ix_(free, free)])
    data = pattern.assemble([g.elastic_stiffness()])
    again = pattern.assemble([g.elastic_stiffness()], data)  # reused array: zeroed, not accumulated
    assert again is data and np.abs(pattern.matrix(again).toarray() - Kff).max() == 0.0


def test_elimination_with_prescribed_displacements_matches_dense_solve():
    m, xy = distorted_q8_mesh(3)
    model = Model()
    model.add_nodes(xy, 2)
    g = model.add_group(q8_group(xy, m.conn, model, 2))
    model.fix(m.bottom, "w")
    model.fix(m.bottom[:1], "u", 1e-4)  # a non-zero fixed value
    model.prescribe(m.surface[:3], "w", -2e-3)  # prescribed, scaled by the load factor (1 here)
    model.add_load(m.right, "u", 5e3)
    res = model.solve_linear()
    K = dense_stiffness(model.n_dof, [g])
    dofs, fixed, ref = model.constrained()
    u = np.zeros(model.n_dof)
    u[dofs] = fixed + ref
    f = model.load_vectors()[0]
    free = model.free_mask()
    u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free] - K[np.ix_(free, ~free)] @ u[~free])
    assert np.abs(res.u[-1] - u).max() < 1e-10 * np.abs(u).max()
    # reactions balance the applied load: sum over all DOFs of K u - f is zero on free DOFs
    assert np.abs(res.reactions()[free]).max() < 1e-8 * np.abs(f).max()
    # the two rows of a linear solve: the state at load factor 0 (the fixed value, nothing prescribed yet) and
    # the solution, each with its internal force K u (the dense K above: round-off of a sum of ~50 terms)
    u0 = np.zeros(model.n_dof)
    u0[dofs] = fixed
    assert res.load_factor == [0.0, 1.0] and np.array_equal(res.u[0], u0)
    for row, u_row in zip(res.f_int, (u0, u)):
        assert np.abs(row - K @ u_row).max() < 1e-10 * np.abs(K @ u).max()


# ---- the closed form used by the chapter ----------------------------------------------------------------
def test_strip_load_closed_form_matches_flamant_quadrature():
    q, b = 100e3, 1.0
    for x, z in [(0.0, -0.5), (0.7, -1.3), (1.7, -0.6), (-2.5, -3.0)]:
        ref = flamant_strip_quadrature(x, z, q, b, n=20000)
        got = strip_load_stresses(np.array(x), np.array(z), q, b)
        # midpoint rule with 20000 panels on a smooth integrand: error ~ (h/d)^2 ~ 1e-8 relative to q
        assert max(abs(g - r) for g, r in zip(got, ref)) < 1e-6 * q
    # on the surface under the strip the vertical stress is -q, sxx too (both are -q/pi * pi)
    sxx, szz, txz = strip_load_stresses(np.array(0.3), np.array(-1e-12), q, b)
    assert abs(szz + q) < 1e-6 * q and abs(sxx + q) < 1e-6 * q and abs(txz) < 1e-6 * q


# ---- bad input ------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "E_, nu, name",
    [
        (0.0, 0.3, "E"),
        (-1e6, 0.3, "E"),
        (float("nan"), 0.3, "E"),
        (1e6, 0.5, "nu"),
        (1e6, -1.0, "nu"),
        (1e6, 0.7, "nu"),
    ],
)
def test_bad_elastic_parameters(E_, nu, name):
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        elastic_params(E_, nu)


def test_bad_scene():
    with pytest.raises(ValueError, match="layer_thicknesses"):
        soil_block(20.0, 10.0, layer_thicknesses=[3.0, 4.0])  # 7 m of layers in a 10 m block
    with pytest.raises(ValueError, match="foundation"):
        soil_block(4.0, 10.0, foundation=(-3.0, 3.0))  # 6 m foundation on a 4 m block
    with pytest.raises(ValueError, match="empty"):
        Model().check()
    with pytest.raises(ValueError, match="empty"):
        Model().solve_linear()
    with pytest.raises(ValueError, match="n_gauss"):
        single_element(4)
    mesh = soil_block(10.0, 5.0, foundation=(-1.0, 1.0), h_fine=0.5)
    with pytest.raises(ValueError, match="foundation"):
        foundation_contact(mesh, -1.2, 1.0, 0.5)  # not on a mesh line


# ---- the fast K0 kernel ---------------------------------------------------------------------------------
@pytest.mark.parametrize("n_gauss", [2, 3])
def test_fast_elastic_kernel_matches_the_element_group(n_gauss):
    """q8_elastic_stiffness (SoilQ8's K0) must equal the generic law-dispatch kernel of SoilQ8.evaluate and
    the dense reference on distorted elements with different materials per element."""
    m, xy = distorted_q8_mesh(3)
    model = Model()
    model.add_nodes(xy, 2)
    el_mat = np.arange(len(m.conn)) % 2
    params = np.array([elastic_params(E, NU), elastic_params(3 * E, 0.45)])
    g = SoilQ8(xy[m.conn], model.element_dofs(m.conn), el_mat, [ELASTIC, ELASTIC], params, n_gauss=n_gauss)
    out = np.full((g.n_el, 16, 16), np.nan)  # a reused buffer: every entry must be overwritten
    K = q8_elastic_stiffness(g.coords, params[el_mat, 0], params[el_mat, 1], n_gauss, out)
    assert K is out
    zero = np.zeros((g.n_el, 16))
    K_ref = g.evaluate(zero, zero, g.initial_state(), K0_MATRIX)[1]  # the generic kernel (law dispatch)
    assert np.abs(K - K_ref).max() < TOL_ROUNDOFF * np.abs(K_ref).max()
    assert np.abs(g.elastic_stiffness() - K_ref).max() < TOL_ROUNDOFF * np.abs(K_ref).max()
    K_dense = dense_q8_stiffness(g.coords[4], n_gauss, *params[el_mat[4], :2])
    assert np.abs(K[4] - K_dense).max() < TOL_ROUNDOFF * np.abs(K_dense).max()
    with pytest.raises(ValueError, match="nu"):
        q8_elastic_stiffness(g.coords, E, 0.5)
    with pytest.raises(ValueError, match="E"):
        q8_elastic_stiffness(g.coords, -E, NU)


@pytest.mark.parametrize("tangent", [FORCES_ONLY, CONSISTENT])
def test_duvaut_lions_blend_of_trial_and_inviscid_return(tangent):
    """A viscous group's forces, tangent and stress are (elastic trial + tau inviscid) / (1 + tau) of two
    rate-independent evaluations (one with every law elastic, one inviscid); its history is the inviscid
    return's. The kernel regression case: every soil law, points in every return branch; the blend is done
    per point inside the kernel."""
    from kernel_regression_case import case

    base, du, state = case(2)
    tau = 2.5

    def group(kinds, viscosity):
        return SoilQ8(base.coords, base.edofs, base.el_mat, kinds, base.params, viscosity=viscosity)

    f_v, k_v, s_v = group(base.kinds, tau).evaluate(du, du, state, tangent)
    f_i, k_i, s_i = group(base.kinds, 0.0).evaluate(du, du, state, tangent)
    f_e, k_e, s_e = group(np.zeros_like(base.kinds), 0.0).evaluate(du, du, state, tangent)
    assert len(np.unique(s_i[:, :, 5])) >= 3  # elastic and at least two return branches
    np.testing.assert_allclose(
        f_v, (f_e + tau * f_i) / (1.0 + tau), rtol=1e-12, atol=1e-9 * np.abs(f_i).max()
    )
    blend = (s_e[..., :4] + tau * s_i[..., :4]) / (1.0 + tau)
    np.testing.assert_allclose(s_v[..., :4], blend, rtol=1e-12, atol=1e-9 * np.abs(blend).max())
    np.testing.assert_array_equal(s_v[..., 4:], s_i[..., 4:])
    if tangent == CONSISTENT:
        k_blend = (k_e + tau * k_i) / (1.0 + tau)
        np.testing.assert_allclose(k_v, k_blend, rtol=1e-12, atol=1e-9 * np.abs(k_blend).max())
