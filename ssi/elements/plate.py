"""The 3-node layered Mindlin (Timoshenko) plate-strip element (paper §4, §10; paper-notes §2).

Kinematics (eqs. 4.1-4.3), per unit width, z upwards from the reference surface on which the nodes lie::

    u(x, z) = ubar(x) - z alpha(x),   w(x, z) = wbar(x),   gamma = wbar' - alpha
    eps_x(z) = ubar' - z alpha' = eps0 - z kap

Each node carries (u, w, alpha); ``alpha`` is the rotation of the normal, equal to the slope w' when there is
no shear strain. Shape functions: quadratic Lagrange on the nodes (left, middle, right) at xi = -1, 0, +1.

Section resultants (per unit width; M positive in sagging, i.e. tension at the bottom)::

    N = int sig dz,   M = -int z sig dz,   Q = kappa_s int_{shear layers} tau dz

Virtual work: f = int (dEps0/du N + dKap/du M + dGam/du Q) dx, which reproduces the blocks of eq. (4.7b).

Through the thickness: **rectangular (midpoint) rule with a self-bending term**. The law is called once per
layer, at its mid-depth z_n; inside the layer the stress is taken as linear with modulus e_n::

    N = sum h_n sig_n
    M = -sum h_n z_n sig_n + sum e_n h_n^3/12 kap
    dN/deps0 = sum h_n E_n,  dN/dkap = dM/deps0 = -sum h_n z_n E_n,  dM/dkap = sum h_n (z_n^2 E_n + e_n
    h_n^2/12)

with E_n the law's tangent (``CONSISTENT``) or initial (``K0_MATRIX``: K0, constant) modulus, and e_n the
modulus of the layer's own bending (option ``self_bending``):

* ``"chord"`` (default): the stress is taken linear between the stresses the law gives at the layer's two
  faces (strains eps0 - (z_n -+ h_n/2) kap, with the layer's committed history), so
  M_self = h_n^2/12 (sig_bottom - sig_top), i.e. e_n = the chord modulus over the layer's strain range. f is
  continuous in the strains (the stresses are), the consistent tangent is exact (and non-symmetric:
  dM/deps0 != dN/dkap in a nonlinear layer), and a cracked or crushed layer loses its own bending stiffness.
  Cost: three law calls per layer instead of one.
* ``"tangent"``: e_n = the layer's tangent modulus at its mid-depth strain; as accurate as the chord, but f
  jumps by O(h_n^3) when a layer's law changes branch and the tangent omits d e_t / d eps.
* ``"initial"``: e_n = the layer's initial modulus e0_n (the D1 of eq. 4.4): f is continuous when a layer's
  law changes branch and the consistent tangent is exact, but a cracked or crushed layer keeps
  e0 h_n^3/12 of bending stiffness.

For a linear law the stress is exactly linear within a layer, so both *are* the integral: f_int = K0 u_el with
K0 of eq. (4.7b), for any number of layers (asserted in ``tests/test_plate.py`` and chapter 02). For nonlinear
layers the choice matters. Measured in chapter 02 (row ``section_selfbending``) on the Janney beam section
with the paper's 11 layers, N = 0, against the layer-free reference
(``ssi.elements.section_analysis.layer_free_moment_curvature``, adaptive quadrature of the continuous stress
profile): ``"initial"`` over-estimates M by +1.0 / +1.8 / +3.1 / +8.1 / +17.2 % at kap = 0.001 / 0.004 / 0.01
/ 0.03 / 0.06 1/m (the error grows with the curvature, as more of the depth cracks and crushes); ``"tangent"``
stays within -0.2 ... +1.05 % and ``"chord"`` within 0 ... +1.05 %. The chord is the default: equally
accurate, and its continuous f lets Newton converge where the tangent's jumps stop it (chapter 08, Janney beam
with the crack-spacing band: 8 + 8 elements reached 6.9 mm with "tangent", 32 mm with "chord"; chapter 11's h
= 0.25 m scene: "tangent" stalls, "chord" converges).

Integration along the element (option ``integration``): ``"selective"`` (default, paper §10): membrane and
bending with 3-point Gauss, shear with 2-point Gauss; ``"full"`` (3/3, locks in shear for thin strips);
``"reduced"`` (2/2); or a tuple ``(n_axial, n_shear)`` with each in 1..3. Sampling points hold their own
layer histories: with selective integration point 0-2 are the axial (membrane/bending) points and 3-4 the
shear points, so ``n_ip = 5``; when both rules coincide one set serves both (n_ip = n).

Array layout (see ``ssi.core.protocol``): edofs (n_el, 9) = (u, w, alpha) of nodes (left, mid, right);
coords (n_el, 3, 2); state (n_el, n_ip, n_layer, N_LAYER_HIST) = the layer laws' history variables (total
formulation: strains come from ``u_el``; ``du_el`` is not used).
"""

import numpy as np
from numba import njit

from ..core.protocol import CONSISTENT, K0_MATRIX, SECANT_SOFTENING, ElementGroup
from ..core.quadrature import gauss_legendre
from ..core.shapes import lagrange3, lagrange3_into
from ..materials.layer_laws import (
    CONCRETE,
    ELASTIC,
    LAYER_HIST_FIELDS,
    N_LAYER_CONSTANTS,
    N_LAYER_HIST,
    P_LS,
    crack_band_width,
    layer_constants,
    layer_update_with,
)
from .section import Section

# the layer laws' tangent flag where the kernels always want the tangent: int64, not the literal 1, because
# numba compiles one more copy of every layer law for a literal flag (Python calls pass int64)
_ALWAYS_TANGENT = np.int64(CONSISTENT)

__all__ = [
    "N_LAYER_HIST",
    "PlateStrip",
    "add_plate_strip",
    "beam_mesh",
    "beam_mesh_from_ends",
    "integration_rule",
    "plate_kernel",
    "plate_resultants",
]

INTEGRATIONS = {"selective": (3, 2), "full": (3, 3), "reduced": (2, 2)}
SELF_BENDING = {"initial": 0, "tangent": 1, "chord": 2}  # modulus of each layer's own bending term


def integration_rule(integration):
    """Sampling points along the element for an integration option.

    Returns ``(xi, w, axial, shear)``: points on [-1, 1], weights, and int8 flags saying whether the point
    integrates the membrane/bending terms (``axial``) and/or the shear terms (``shear``)."""
    if isinstance(integration, str):
        if integration not in INTEGRATIONS:
            raise ValueError(
                f"integration must be one of {sorted(INTEGRATIONS)} or (n_axial, n_shear), "
                f"got {integration!r}"
            )
        n_ax, n_sh = INTEGRATIONS[integration]
    else:
        n_ax, n_sh = (int(v) for v in integration)
        if not (1 <= n_ax <= 3 and 1 <= n_sh <= 3):
            raise ValueError(f"(n_axial, n_shear) must each be in 1..3, got {integration!r}")
    pa, wa = gauss_legendre(n_ax)
    if n_ax == n_sh:
        one = np.ones(n_ax, np.int8)
        return pa, wa, one, one.copy()
    ps, ws = gauss_legendre(n_sh)
    xi = np.concatenate([pa, ps])
    w = np.concatenate([wa, ws])
    ax = np.concatenate([np.ones(n_ax, np.int8), np.zeros(n_sh, np.int8)])
    return xi, w, ax, (1 - ax).astype(np.int8)


@njit(cache=True)
def _point_b(x, xi, n_out, bx_out):
    """Shape values n_out (3,) and x-derivatives bx_out (3,) at xi; return the Jacobian dx/dxi."""
    lagrange3_into(xi, n_out, bx_out)  # bx_out holds dN/dxi until divided by the Jacobian
    jac = bx_out[0] * x[0] + bx_out[1] * x[1] + bx_out[2] * x[2]
    for a in range(3):
        bx_out[a] = bx_out[a] / jac
    return jac


@njit(cache=True)
def _crack_band(prm, const, kind, band, ls_index, ls):
    """Set the crack band width of the flagged layers (paper eq. 5.4 with ls = the point's length), and
    their law's constants, which depend on it."""
    for n in range(band.shape[0]):
        if band[n]:
            prm[n, ls_index] = ls
            layer_constants(kind[n], prm[n], const[n])


@njit(cache=True)
def _layer_constants(kind, prm):
    """(n_layer, N_LAYER_CONSTANTS) constants of the layers' laws (``layer_constants``)."""
    const = np.zeros((kind.shape[0], N_LAYER_CONSTANTS))
    for n in range(kind.shape[0]):
        layer_constants(kind[n], prm[n], const[n])
    return const


@njit(cache=True)
def _section(
    u,
    nn,
    bx,
    z_mid,
    h,
    kind,
    params,
    const,
    cshear,
    kappa,
    e0,
    g0,
    self_mode,
    hist_old,
    hist_new,
    tangent,
    do_ax,
    do_sh,
    res,
    scratch,
):
    """Section response at one point: strains from the element vector ``u`` (9,), law per layer.

    Writes ``res`` (8,) = [N, M, Q, A, B, D, S, 0] with A = dN/deps0, B = dN/dkap = dM/deps0,
    D = dM/dkap, S = dQ/dgam (tangent CONSISTENT: the laws' tangent moduli; SECANT_SOFTENING: the same with
    the secant at points loading on a softening envelope, unless self_mode=1; K0_MATRIX: the initial moduli
    e0, g0, i.e. K0); hist_old/hist_new (n_layer, N_LAYER_HIST). The self-bending term of each layer uses e0
    (self_mode=0), the layer's tangent modulus (1) or the chord through the stresses at the layer's faces (2,
    evaluated with the layer's committed history; scratch (N_LAYER_HIST,) takes their unused new history).
    res[7] = dM/deps0 (differs from B only with the chord term)."""
    eps0 = 0.0
    kap = 0.0
    gam = 0.0
    for a in range(3):
        eps0 += bx[a] * u[3 * a]
        gam += bx[a] * u[3 * a + 1] - nn[a] * u[3 * a + 2]
        kap += bx[a] * u[3 * a + 2]
    # the flag the laws get: their tangent, or with SECANT_SOFTENING their secant at softening points; the
    # matrix below takes it unless K0 is asked for. Not with the "tangent" self-bending term, whose force uses
    # the modulus: the internal force never depends on the flag
    law_flag = tangent if tangent == SECANT_SOFTENING and self_mode != 1 else _ALWAYS_TANGENT
    moduli = tangent != K0_MATRIX
    N = 0.0
    M = 0.0
    Q = 0.0
    A = 0.0
    B = 0.0
    B2 = 0.0
    D = 0.0
    S = 0.0
    for n in range(h.shape[0]):
        z = z_mid[n]
        hn = h[n]
        # the law always returns its tangent; K0 (K0_MATRIX) uses the initial moduli instead, so that the
        # internal force never depends on which matrix the solver asks for
        sig, tau, e_t, g_t = layer_update_with(
            kind[n], params[n], const[n], eps0 - z * kap, gam, hist_old[n], hist_new[n], law_flag
        )
        if do_ax:
            i_n = hn * hn * hn / 12.0  # exact within-layer bending, eq. (4.7b) h_n^2/12
            e_k = e_t if moduli else e0[n]
            N += hn * sig
            M += -hn * z * sig
            A += hn * e_k
            B += -hn * z * e_k
            B2 += -hn * z * e_k
            D += hn * z * z * e_k
            if self_mode == 2:
                # chord: M_self = -int (z - z_n) sig dz with sig linear between the faces' stresses
                z_b = z - 0.5 * hn
                z_t = z + 0.5 * hn
                s_b, _, e_b, _ = layer_update_with(
                    kind[n], params[n], const[n], eps0 - z_b * kap, 0.0, hist_old[n], scratch, law_flag
                )
                s_t, _, e_tp, _ = layer_update_with(
                    kind[n], params[n], const[n], eps0 - z_t * kap, 0.0, hist_old[n], scratch, law_flag
                )
                c = hn * hn / 12.0
                M += c * (s_b - s_t)
                if moduli:
                    B2 += c * (e_b - e_tp)
                    D += c * (z_t * e_tp - z_b * e_b)
                else:
                    D += e0[n] * i_n
            else:
                e_self = e_t if self_mode == 1 else e0[n]
                M += e_self * i_n * kap
                D += (e_self if moduli else e0[n]) * i_n
        if do_sh and cshear[n]:
            Q += kappa * hn * tau
            S += kappa * hn * (g_t if moduli else g0[n])
    res[0] = N
    res[1] = M
    res[2] = Q
    res[3] = A
    res[4] = B
    res[5] = D
    res[6] = S
    res[7] = B2


@njit(cache=True)
def plate_kernel(
    x_el,
    u_el,
    state_old,
    state_new,
    f_el,
    k_el,
    xi,
    wt,
    ax,
    sh,
    z_mid,
    h,
    kind,
    params,
    cshear,
    kappa,
    e0,
    g0,
    self_mode,
    band,
    ls_index,
    tangent,
):
    """Internal forces and stiffness of all plate-strip elements; returns the number of bad Jacobians.

    x_el (n_el, 3) nodal x; u_el (n_el, 9); state_old/state_new (n_el, n_ip, n_layer, N_LAYER_HIST);
    f_el (n_el, 9) and k_el (n_el, 9, 9) are overwritten; xi, wt (n_ip,), ax, sh (n_ip,) int8 flags;
    z_mid, h, e0, g0 (n_layer,) (initial moduli: K0), kind (n_layer,) int64, params (n_layer, n_par), cshear
    (n_layer,) bool; band (n_layer,) bool: layers whose ``params[ls_index]`` is replaced at each point by the
    crack band width w_p L_e / 2 that the point represents (eq. 5.4; all False leaves params untouched).
    """
    nn = np.empty(3)
    bx = np.empty(3)
    be = np.zeros(9)  # d eps0 / d u_el
    bk = np.zeros(9)  # d kap / d u_el
    bg = np.zeros(9)  # d gam / d u_el
    res = np.zeros(8)
    scratch = np.zeros(state_old.shape[3])
    prm = params.copy()
    const = _layer_constants(kind, prm)
    return _plate_points(
        x_el, u_el, state_old, state_new, f_el, k_el, xi, wt, ax, sh, z_mid, h, kind, cshear, kappa, e0, g0,
        self_mode, band, ls_index, tangent, nn, bx, be, bk, bg, res, scratch, prm, const,
    )  # fmt: skip


# The loop over elements and points, compiled without numba's reference counting (the scratch comes from
# plate_kernel; nothing below allocates): the section update's array arguments and the per-point views of the
# states cost an atomic increment and decrement each. Numba compiles the functions a loop calls with the
# loop's own setting, so nothing that allocates may be reached from here.
@njit(cache=True, _nrt=False)
def _plate_points(
    x_el, u_el, state_old, state_new, f_el, k_el, xi, wt, ax, sh, z_mid, h, kind, cshear, kappa, e0, g0,
    self_mode, band, ls_index, tangent, nn, bx, be, bk, bg, res, scratch, prm, const,
):  # fmt: skip
    n_el = x_el.shape[0]
    bad = 0
    for e in range(n_el):
        for i in range(9):
            f_el[e, i] = 0.0
            for j in range(9):
                k_el[e, i, j] = 0.0
        for p in range(xi.shape[0]):
            jac = _point_b(x_el[e], xi[p], nn, bx)
            if jac <= 0.0:
                bad += 1
                for n in range(state_old.shape[2]):  # loops: no array-to-slice copy to compile
                    for i in range(state_old.shape[3]):
                        state_new[e, p, n, i] = state_old[e, p, n, i]
                continue
            wj = wt[p] * jac
            _crack_band(prm, const, kind, band, ls_index, crack_band_width(x_el[e, 2] - x_el[e, 0], wt[p]))
            for a in range(3):
                be[3 * a] = bx[a]
                bg[3 * a + 1] = bx[a]
                bg[3 * a + 2] = -nn[a]
                bk[3 * a + 2] = bx[a]
            _section(
                u_el[e],
                nn,
                bx,
                z_mid,
                h,
                kind,
                prm,
                const,
                cshear,
                kappa,
                e0,
                g0,
                self_mode,
                state_old[e, p],
                state_new[e, p],
                tangent,
                ax[p] != 0,
                sh[p] != 0,
                res,
                scratch,
            )
            Nr = res[0] * wj
            Mr = res[1] * wj
            Qr = res[2] * wj
            A = res[3] * wj
            B = res[4] * wj
            D = res[5] * wj
            S = res[6] * wj
            B2 = res[7] * wj  # dM/deps0 (= B = dN/dkap unless the chord term is used)
            for i in range(9):
                f_el[e, i] += be[i] * Nr + bk[i] * Mr + bg[i] * Qr
                ei = A * be[i] + B2 * bk[i]  # column j = eps0: d(N be_i + M bk_i)/d eps0
                ki = B * be[i] + D * bk[i]  # column j = kap
                gi = S * bg[i]
                for j in range(9):
                    k_el[e, i, j] += ei * be[j] + ki * bk[j] + gi * bg[j]
    return bad


@njit(cache=True)
def plate_resultants(
    x_el,
    u_el,
    state,
    xi,
    wt,
    ax,
    sh,
    z_mid,
    h,
    kind,
    params,
    cshear,
    kappa,
    e0,
    g0,
    self_mode,
    band,
    ls_index,
    out,
):
    """Stress resultants at sampling points: out (n_el, n_pt, 4) = [x, N, M, Q], NaN where a point does not
    carry the quantity (N, M at axial points, Q at shear points). ``state`` (n_el, n_pt, n_layer, n_hist) is
    the committed history at these points."""
    nn = np.empty(3)
    bx = np.empty(3)
    res = np.zeros(8)
    scratch = np.empty((h.shape[0], state.shape[3]))
    scratch1 = np.zeros(state.shape[3])
    prm = params.copy()
    const = _layer_constants(kind, prm)
    for e in range(x_el.shape[0]):
        for p in range(xi.shape[0]):
            _point_b(x_el[e], xi[p], nn, bx)
            _crack_band(prm, const, kind, band, ls_index, crack_band_width(x_el[e, 2] - x_el[e, 0], wt[p]))
            _section(
                u_el[e],
                nn,
                bx,
                z_mid,
                h,
                kind,
                prm,
                const,
                cshear,
                kappa,
                e0,
                g0,
                self_mode,
                state[e, p],
                scratch,
                0,
                ax[p] != 0,
                sh[p] != 0,
                res,
                scratch1,
            )
            out[e, p, 0] = nn[0] * x_el[e, 0] + nn[1] * x_el[e, 1] + nn[2] * x_el[e, 2]
            out[e, p, 1] = res[0] if ax[p] != 0 else np.nan
            out[e, p, 2] = res[1] if ax[p] != 0 else np.nan
            out[e, p, 3] = res[2] if sh[p] != 0 else np.nan


@njit(cache=True)
def plate_layer_stresses(eps, gam, state, kind, params, band, ls_index, wt, length, sig, tau):
    """Layer stresses at the sampling points from their strains and the committed history.

    eps (n_el, n_ip, n_layer), gam (n_el, n_ip), state (n_el, n_ip, n_layer, n_hist), length (n_el,);
    writes sig, tau (n_el, n_ip, n_layer) (tau unfactored by kappa, as the laws return it)."""
    prm = params.copy()
    const = _layer_constants(kind, prm)
    scratch = np.empty(state.shape[3])
    for e in range(eps.shape[0]):
        for p in range(eps.shape[1]):
            _crack_band(prm, const, kind, band, ls_index, crack_band_width(length[e], wt[p]))
            for n in range(eps.shape[2]):
                s, t, _, _ = layer_update_with(
                    kind[n],
                    prm[n],
                    const[n],
                    eps[e, p, n],
                    gam[e, p],
                    state[e, p, n],
                    scratch,
                    _ALWAYS_TANGENT,
                )
                sig[e, p, n] = s
                tau[e, p, n] = t


@njit(cache=True)
def _line_load(x_el, q_pts, xi, wt, comp, f_el):
    """Equivalent nodal forces of a load intensity sampled at points: q_pts (n_el, n_pt)."""
    nn = np.empty(3)
    bx = np.empty(3)
    for e in range(x_el.shape[0]):
        for i in range(9):
            f_el[e, i] = 0.0
        for p in range(xi.shape[0]):
            jac = _point_b(x_el[e], xi[p], nn, bx)
            for a in range(3):
                f_el[e, 3 * a + comp] += nn[a] * q_pts[e, p] * wt[p] * jac


class PlateStrip(ElementGroup):
    """A group of 3-node layered Mindlin plate-strip elements sharing one section.

    Parameters
    ----------
    coords : (n_el, 3, 2) nodal (x, z) of the nodes (left, middle, right) on the reference surface; the strip
        is horizontal (x increasing along each element; z may differ between elements, not within one)
    edofs : (n_el, 9) global DOFs, (u, w, alpha) per node (``Model.element_dofs(conn)`` for 3-DOF nodes)
    section : :class:`ssi.elements.section.Section` (layers: z_mid, h, kind, params, carries_shear)
    kappa : shear correction factor on D2 (default 5/6; kappa = 1 is the paper's literal eq. 4.4)
    integration : "selective" (default, 3-pt bending / 2-pt shear), "full" (3/3), "reduced" (2/2) or
        (n_axial, n_shear)
    self_weight : downward load per unit area of the strip [N/m^2] (e.g. 25e3 * depth), a dead body force
    crack_band : "point" (default): every CONCRETE layer's crack band width ls (eq. 5.4) is set, at each
        sampling point, to the length that point represents, w_p L_e / 2 (so a point cracking through
        dissipates Gf per unit crack area; checked against the snap-back limit); None: use ls as given
    self_bending : each layer's own bending term: "chord" (default: h_n^2/12 (sig_bottom - sig_top) from the
        stresses at the layer's faces; within about 1 % of the layer-free moment with 11 layers up to
        kap = 0.06 1/m, f continuous, tangent exact), "tangent" (e_t h_n^3/12 k: as accurate, but f jumps when
        a layer changes branch) or "initial" (e0 h_n^3/12 k: a cracked or crushed layer keeps its elastic
        bending stiffness, +17 % in M at kap = 0.06 1/m with 11 layers); all exact for linear layers (see the
        module docstring and chapter 02)
    name : group name

    Notes
    -----
    ``evaluate(u_el, du_el, state_old, tangent) -> (f_el, k_el, state_new)`` follows ``ssi.core.protocol``.
    Bottom face for the interface element: ``z_bottom`` (< 0, relative to the nodes) and ``bottom_offset =
    -z_bottom`` so that u_g = u_b + bottom_offset * alpha_b (eq. 6.1); ``thickness`` is the section depth.
    ``history(state, name)`` reads a layer-history slot by the name its law gives it (concrete: ``x_max``,
    ``e_max``; steel: ``eps_p``), shape (n_el, n_ip, n_layer).
    """

    history_fields = LAYER_HIST_FIELDS
    secant_softening = True  # SECANT_SOFTENING: the concrete's secant at its softening points (_section)

    def __init__(
        self,
        coords,
        edofs,
        section: Section,
        kappa: float = 5.0 / 6.0,
        integration="selective",
        self_weight: float = 0.0,
        crack_band="point",
        self_bending="chord",
        name: str = "plate",
    ):
        self.coords = np.ascontiguousarray(coords, np.float64)
        self.edofs = np.ascontiguousarray(edofs, np.int64)
        n_el = self.coords.shape[0] if self.coords.ndim == 3 else -1
        if self.coords.shape != (n_el, 3, 2) or self.edofs.shape != (n_el, 9):
            raise ValueError(
                f"coords must be (n_el, 3, 2) and edofs (n_el, 9); got {self.coords.shape}, "
                f"{self.edofs.shape}"
            )
        if not isinstance(section, Section):
            raise ValueError(
                "section must be an ssi.elements.section.Section "
                "(see ssi.elements.section.layered / rc_section)"
            )  # noqa: TRY004
        if not 0.0 < kappa <= 1.0:
            raise ValueError(f"kappa must be in (0, 1], got {kappa}")
        x = self.coords[:, :, 0]
        length = x[:, 2] - x[:, 0]
        if n_el and np.any(length <= 0.0):
            raise ValueError("coords: each element's x must increase from the left to the right node")
        if n_el and np.any(np.abs(x[:, 1] - 0.5 * (x[:, 0] + x[:, 2])) > 0.25 * length):
            raise ValueError("coords: the middle node must lie within the middle half of the element")
        if n_el and np.any(np.ptp(self.coords[:, :, 1], axis=1) > 1e-9 * length):
            raise ValueError("coords: the strip must be horizontal (equal z within each element)")
        self.section = section
        self.kappa = float(kappa)
        self.integration = integration
        self.xi, self.wt, self.ax, self.sh = integration_rule(integration)
        self.e0, self.g0 = section.initial_moduli()
        self.self_weight = float(self_weight)
        if crack_band not in ("point", None):
            raise ValueError(f"crack_band must be 'point' or None, got {crack_band!r}")
        self.crack_band = crack_band
        if self_bending not in SELF_BENDING:
            raise ValueError(f"self_bending must be one of {sorted(SELF_BENDING)}, got {self_bending!r}")
        self.self_bending = self_bending
        self.self_mode = SELF_BENDING[self_bending]
        self.band = np.ascontiguousarray((section.kind == CONCRETE) & (crack_band == "point"))
        if self.band.any() and n_el:
            from ..materials.concrete import P_E0, P_FR, P_GF
            from ..materials.rc import check_crack_band

            ls_max = crack_band_width(length.max(), self.wt.max())
            for n in np.flatnonzero(self.band):
                prm = section.params[n]
                check_crack_band(ls_max, prm[P_E0], prm[P_GF], prm[P_FR])
        self.name = name
        self._x = np.ascontiguousarray(x)
        self._k0 = None

    # ---- geometry ---------------------------------------------------------------------------------------
    @property
    def n_el(self) -> int:
        return self.coords.shape[0]

    @property
    def n_ip(self) -> int:
        return len(self.xi)

    @property
    def thickness(self) -> float:
        return self.section.thickness

    @property
    def z_bottom(self) -> float:
        return self.section.z_bottom

    @property
    def bottom_offset(self) -> float:
        """Lever arm from the nodes to the bottom face: u_bottom = u + bottom_offset * alpha (eq. 6.1)."""
        return -self.section.z_bottom

    # ---- protocol -----------------------------------------------------------------------------------------
    def initial_state(self) -> np.ndarray:
        return np.zeros((self.n_el, self.n_ip, self.section.n_layer, N_LAYER_HIST))

    def evaluate(self, u_el, du_el, state_old, tangent):
        """Total formulation: strains from ``u_el``; ``du_el`` unused. Returns (f_el, k_el, state_new)."""
        f_el = np.empty((self.n_el, 9))
        k_el = np.empty((self.n_el, 9, 9))
        state_new = np.empty_like(state_old)
        s = self.section
        bad = plate_kernel(
            self._x,
            np.ascontiguousarray(u_el, np.float64),
            state_old,
            state_new,
            f_el,
            k_el,
            self.xi,
            self.wt,
            self.ax,
            self.sh,
            s.z_mid,
            s.h,
            s.kind,
            s.params,
            s.carries_shear,
            self.kappa,
            self.e0,
            self.g0,
            self.self_mode,
            self.band,
            P_LS,
            int(tangent),
        )
        if bad:
            raise FloatingPointError(f"{self.name}: {bad} points with non-positive Jacobian")
        return f_el, k_el, state_new

    def elastic_stiffness(self) -> np.ndarray:
        if self._k0 is None:
            zero = np.zeros((self.n_el, 9))
            self._k0 = self.evaluate(zero, zero, self.initial_state(), K0_MATRIX)[1]
        return self._k0

    def body_force(self):
        if self.self_weight == 0.0:
            return None
        return self.distributed_load(-self.self_weight, comp="w")

    def describe(self) -> dict:
        return {
            "name": self.name,
            "type": "PlateStrip",
            "n_el": self.n_el,
            "kappa": self.kappa,
            "integration": str(self.integration),
            "self_weight": self.self_weight,
            "crack_band": str(self.crack_band),
            "self_bending": self.self_bending,
            "section": self.section.describe(),
        }

    # ---- loads and results --------------------------------------------------------------------------------
    # ---- what the solver asks (ssi.core.protocol.ElementGroup) -------------------------------------------
    def softens(self) -> bool:
        """A layer that is not elastic (RC concrete that cracks, steel): the cracking strip's rules apply."""
        return bool(np.any(self.section.kind != ELASTIC))

    def symmetric_tangent(self) -> bool:
        """Elastic layers only: a symmetric tangent."""
        return not self.softens()

    def stored_energy(self, u_el, du_el, state_old, state_new, work) -> float | None:
        """Elastic layers only: the whole ``work`` is stored; else None (not split)."""
        return work if np.all(np.asarray(self.section.kind) == ELASTIC) else None

    def distributed_load(self, q, comp="w", elements=None) -> np.ndarray:
        """Equivalent nodal forces (n_el, 9) of a distributed load along the strip (per unit width).

        q : float (uniform intensity), (n_el, 2) array of intensities at each element's left and right ends
            (linear in between), or a callable q(x) (exact for q up to cubic; 4-point Gauss)
        comp : "u" (tangential force), "w" (vertical force, positive up: a downward load is negative) or
            "alpha" (distributed moment)
        elements : optional boolean mask or index array; other elements get zero rows
        Use with ``Model.add_element_load(group.edofs, f_el)``.
        """
        c = {"u": 0, "w": 1, "alpha": 2}.get(comp, comp)
        if c not in (0, 1, 2):
            raise ValueError(f"comp must be 'u', 'w' or 'alpha', got {comp!r}")
        xi, wt = gauss_legendre(4)
        x = self._x
        # physical x of the Gauss points (quadratic map)
        nvals = np.array([lagrange3(float(s))[0] for s in xi])
        xq = x @ nvals.T  # (n_el, 4)
        if callable(q):
            q_pts = np.asarray(q(xq), np.float64) * np.ones_like(xq)
        else:
            qa = np.asarray(q, np.float64)
            if qa.ndim == 0:
                q_pts = np.full_like(xq, float(qa))
            elif qa.shape == (self.n_el, 2):
                t = 0.5 * (xi + 1.0)  # linear in xi between the ends
                q_pts = qa[:, :1] * (1.0 - t) + qa[:, 1:] * t
            else:
                raise ValueError(f"q must be a number, a callable or shape ({self.n_el}, 2); got {qa.shape}")
        if elements is not None:
            mask = np.zeros(self.n_el, bool)
            mask[np.asarray(elements)] = True
            q_pts = np.where(mask[:, None], q_pts, 0.0)
        f_el = np.empty((self.n_el, 9))
        _line_load(x, np.ascontiguousarray(q_pts), xi, wt, c, f_el)
        return f_el

    def resultants(self, u_el, state=None):
        """Stress resultants per unit width at the sampling points, from total displacements ``u_el``
        (n_el, 9) and the committed ``state`` (default: virgin).

        Returns a dict of arrays: ``x_ax`` (n_el, n_ax) with ``N``, ``M`` (axial/bending points) and
        ``x_sh`` (n_el, n_sh) with ``Q`` (shear points); M is positive in sagging (tension at the bottom)."""
        if state is None:
            state = self.initial_state()
        s = self.section
        out = np.empty((self.n_el, self.n_ip, 4))
        plate_resultants(
            self._x,
            np.ascontiguousarray(u_el, np.float64),
            state,
            self.xi,
            self.wt,
            self.ax,
            self.sh,
            s.z_mid,
            s.h,
            s.kind,
            s.params,
            s.carries_shear,
            self.kappa,
            self.e0,
            self.g0,
            self.self_mode,
            self.band,
            P_LS,
            out,
        )
        a = self.ax.astype(bool)
        b = self.sh.astype(bool)
        return {
            "x_ax": out[:, a, 0],
            "N": out[:, a, 1],
            "M": out[:, a, 2],
            "x_sh": out[:, b, 0],
            "Q": out[:, b, 3],
        }

    def _shape_at_points(self):
        """Quadratic Lagrange values and xi-derivatives (n_ip, 3) at the sampling points."""
        shape = [lagrange3(float(s)) for s in self.xi]
        return np.array([n for n, _ in shape]), np.array([dn for _, dn in shape])

    def point_x(self) -> np.ndarray:
        """x [m] of every sampling point (n_el, n_ip), axial and shear points alike (``self.ax``,
        ``self.sh`` say which is which)."""
        return self._x @ self._shape_at_points()[0].T

    def layer_strains(self, u_el):
        """Axial strain (n_el, n_ip, n_layer) at every layer's mid-depth and shear strain (n_el, n_ip)."""
        nvals, dvals = self._shape_at_points()
        jac = self._x @ dvals.T  # (n_el, n_ip)
        u = np.asarray(u_el).reshape(self.n_el, 3, 3)
        eps0 = (u[:, :, 0] @ dvals.T) / jac
        kap = (u[:, :, 2] @ dvals.T) / jac
        gam = (u[:, :, 1] @ dvals.T) / jac - u[:, :, 2] @ nvals.T
        eps = eps0[:, :, None] - self.section.z_mid[None, None, :] * kap[:, :, None]
        return eps, gam

    def layer_stresses(self, u_el, state=None):
        """Axial and shear stress (n_el, n_ip, n_layer) of every layer at its mid-depth, from total
        displacements and the committed ``state`` (default virgin); e.g. for crack and yield maps.
        Which points carry which stress: ``self.ax`` (axial) and ``self.sh`` (shear) flags per point."""
        if state is None:
            state = self.initial_state()
        eps, gam = self.layer_strains(u_el)
        sig = np.empty_like(eps)
        tau = np.empty_like(eps)
        s = self.section
        plate_layer_stresses(
            np.ascontiguousarray(eps),
            np.ascontiguousarray(gam),
            state,
            s.kind,
            s.params,
            self.band,
            P_LS,
            self.wt,
            np.ascontiguousarray(self._x[:, 2] - self._x[:, 0]),
            sig,
            tau,
        )
        return sig, tau


# ---- meshes ------------------------------------------------------------------------------------------------
def beam_mesh_from_ends(x_ends, z: float = 0.0):
    """Nodes and connectivity of a strip whose element ends are ``x_ends`` (increasing, n_el + 1 values).

    Returns ``(xy, conn)``: xy (2 n_el + 1, 2) nodes ordered along x (ends and mid-points interleaved, so
    node 2e is the left end of element e) and conn (n_el, 3) = (left, middle, right)."""
    xe = np.asarray(x_ends, np.float64)
    if xe.ndim != 1 or xe.size < 2 or np.any(np.diff(xe) <= 0.0):
        raise ValueError("x_ends must be an increasing 1-D array with at least 2 values")
    n_el = xe.size - 1
    x = np.empty(2 * n_el + 1)
    x[0::2] = xe
    x[1::2] = 0.5 * (xe[:-1] + xe[1:])
    xy = np.column_stack([x, np.full_like(x, float(z))])
    conn = np.column_stack([2 * np.arange(n_el), 2 * np.arange(n_el) + 1, 2 * np.arange(n_el) + 2])
    return xy, conn.astype(np.int64)


def beam_mesh(x0: float, x1: float, n_el: int, z: float = 0.0):
    """Uniform strip mesh from x0 to x1 with ``n_el`` 3-node elements; see :func:`beam_mesh_from_ends`."""
    if int(n_el) < 1:
        raise ValueError(f"n_el must be >= 1, got {n_el}")
    if not x1 > x0:
        raise ValueError(f"need x1 > x0, got x0={x0}, x1={x1}")
    return beam_mesh_from_ends(np.linspace(x0, x1, int(n_el) + 1), z)


def add_plate_strip(model, x_ends, section: Section, z: float = 0.0, **kwargs):
    """Add a strip's nodes (3 DOFs each) and its element group to ``model``.

    Returns ``(group, node_ids, conn_global)``; node_ids are ordered along x, node_ids[2e] is the left end
    of element e. Extra keyword arguments go to :class:`PlateStrip` (kappa, integration, self_weight, name).
    """
    xy, conn = beam_mesh_from_ends(x_ends, z)
    ids = model.add_nodes(xy, ndof=3)
    conn_g = ids[conn]
    group = PlateStrip(xy[conn], model.element_dofs(conn_g), section, **kwargs)
    model.add_group(group)
    return group, ids, conn_g
