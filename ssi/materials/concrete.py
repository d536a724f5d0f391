"""Concrete at one layer point of the plate strip (paper §5.1-5.3; paper-notes §3.1-3.5).

Pure numba kernels: strain and committed history in, stress, tangent and new history out. Tension is
positive; the compression law (eq. 5.1) is written in magnitudes ``x = -eps >= 0``.

Parameter vector (``params``, float64, indices ``P_*`` below)
--------------------------------------------------------------
====  ==========  =============================================================================
idx   name        meaning
====  ==========  =============================================================================
0     E0          initial Young modulus [Pa]
1     nu          Poisson ratio (enters only the shear modulus G = E0 / (2 (1 + nu)))
2     fc          compressive strength, magnitude [Pa]
3     eps_c       strain at the peak fc, magnitude
4     eps_cu      ultimate (crushing) strain, magnitude; beyond it the point carries no stress (open)
5     fr          tensile strength [Pa]
6     Gf          fracture energy [N/m]
7     ls          crack band width [m] (eq. 5.4)
8     alpha_ts    tension-stiffening factor (open, default 0.5; 0 switches it off)
9     eps_y       yield strain of the reinforcement crossing the crack (fy / Es of the section)
10    beta0       shear retention just after cracking (open, default 0.25)
11    beta_floor  smallest shear retention (open, default 1e-4: keeps the matrix non-singular)
12    Gc          compressive (crushing) fracture energy beyond eps_cu [N/m]; 0: the cliff (stress 0
                  at eps_cu)
13    plane       1: plane strain (a strip of a long foundation): the axial law uses E0 / (1 - nu^2), the D1
                  of eq. (4.4), in place of E0; 0: uniaxial (plane stress, a beam). G = E0 / (2 (1 + nu))
====  ==========  =============================================================================

Crushing, regularised like cracking: eq. (5.1) is followed to eps_cu, where it still carries f_cu = f(eps_cu)
(about 0.9 fc for a = 2). Instead of dropping to zero there (a stress cliff: the paper leaves the post-eps_cu
behaviour open), the stress falls linearly from f_cu to zero at eps_cd = eps_cu + 2 Gc / (f_cu ls), so a band
of width ls dissipates Gc per unit area beyond eps_cu whatever the element size (the compressive analogue of
eq. 5.4). Unloading from the crushing branch follows E0 from the irreversible strain, in compression only (a
crushed point carries no tension). Gc = 0 restores the cliff.

The axial law is the *uniaxial* law of §5 unless ``plane`` = 1: then its modulus is E0 / (1 - nu^2), as for
an elastic layer of a plane-strain strip (eq. 4.4), while the strengths fc, fr and the strain eps_c stay; nu
enters G and that factor only.

History (``hist``, first ``N_CONCRETE_HIST`` entries of the layer history)
--------------------------------------------------------------------------
0. ``x_max``: largest compressive strain magnitude reached (irreversible strain, eq. 5.3; crushing);
1. ``e_max``: largest tensile strain reached, measured from the irreversible strain (crack opening).

Algorithm of :func:`concrete_update` (one call, total formulation)
-------------------------------------------------------------------
1. Crushed through (``max(x_max, x) >= eps_cd``): sig = 0 (shear retention beta_floor from the next
   increment).
2. Compression loading (``x > x_max``): sig = -f(x) on the envelope: eq. (5.1) up to eps_cu, then the
   regularised crushing branch (below), x_max <- x.
3. Otherwise shift by the irreversible strain eps_p = x_max - f(x_max)/E0 (eq. 5.3):
   e = eps + eps_p. e <= 0: unloading/reloading along E0 (sig = E0 e).
4. e > 0: tension. Uncracked (max(e, e_max) <= eps_r = fr/E0): sig = E0 e. Loading on the cracked
   envelope (e >= e_max > eps_r): sig = max(softening eq. 5.4, tension stiffening). Unloading
   (e < e_max): secant towards the origin (open choice of paper-notes §3.3). With the tangent flag
   ``SECANT_SOFTENING`` (:mod:`ssi.core.protocol`) a point loading on the cracked envelope returns the
   modulus of that secant, sig / e >= 0, in place of its negative tangent: a corrector iterating on it
   does not cycle between softening and unloading (issue 31; the converged state is the same, only the
   iteration matrix differs). The compression branch keeps its exact tangent.
5. Shear: tau = beta G gam with beta = 1 uncracked, max(beta0 (1 - e_max/eps_y), beta_floor) cracked
   (Fig. 6; vanishes at steel yield), beta_floor once crushed. beta is evaluated from the *committed*
   history (``hist_old``: the crack state at the start of the increment). Reasons: (i) beta jumps from
   1 to about beta0 when a point cracks; evaluated from the trial strain, that jump makes the
   iterations chatter between cracked and uncracked states (measured: modified Newton stalls on the
   beam of chapter 08); (ii) with beta fixed within an increment, tau depends on gam only, so the two
   returned moduli are the complete, exact tangent (no d tau/d eps term is lost). Cost: the shear
   retention lags the crack state by one increment -- an O(step) effect that vanishes as steps shrink.
"""

import math

from numba import njit

from ..core.protocol import K0_MATRIX, SECANT_SOFTENING

(
    P_E0,
    P_NU,
    P_FC,
    P_EPS_C,
    P_EPS_CU,
    P_FR,
    P_GF,
    P_LS,
    P_ALPHA_TS,
    P_EPS_Y,
    P_BETA0,
    P_BETA_FLOOR,
    P_GC,
    P_PLANE,
) = range(14)
N_CONCRETE_PARAMS = 14
N_CONCRETE_HIST = 2
H_XMAX, H_EMAX = 0, 1


@njit(cache=True)
def compression_envelope(x, E0, fc, eps_c, eps_cu):
    """Eq. (5.1) in magnitudes: return ``(f, df/dx)`` at compressive strain magnitude ``x >= 0``.

    f = E0 x / (1 + (E0 eps_c / fc - 2) r + r^2), r = x / eps_c; df/dx = E0 (1 - r^2) / den^2.
    Zero stress and slope at and beyond ``eps_cu`` (open choice of paper-notes §3.1).
    """
    return _compression(x, E0, E0 * eps_c / fc, eps_c, eps_cu)


@njit(cache=True)
def _compression(x, E0, a, eps_c, eps_cu):
    """:func:`compression_envelope` with its constant a = E0 eps_c / fc given."""
    if x >= eps_cu:
        return 0.0, 0.0
    r = x / eps_c
    den = 1.0 + (a - 2.0) * r + r * r
    return E0 * x / den, E0 * (1.0 - r * r) / (den * den)


@njit(cache=True)
def crushing_end(E0, fc, eps_c, eps_cu, Gc, ls):
    """Return ``(f_cu, eps_cd)``: the stress of eq. (5.1) at eps_cu and the strain where the regularised
    crushing branch reaches zero, eps_cu + 2 Gc / (f_cu ls) (eps_cd = eps_cu for Gc = 0: the cliff)."""
    a = E0 * eps_c / fc
    r = eps_cu / eps_c
    f_cu = E0 * eps_cu / (1.0 + (a - 2.0) * r + r * r)
    if Gc <= 0.0:
        return f_cu, eps_cu
    return f_cu, eps_cu + 2.0 * Gc / (f_cu * ls)


@njit(cache=True)
def crushing_envelope(x, E0, fc, eps_c, eps_cu, Gc, ls):
    """Compression envelope with regularised crushing, in magnitudes: return ``(f, df/dx)``.

    Eq. (5.1) below eps_cu; then f_cu (eps_cd - x) / (eps_cd - eps_cu) down to zero at eps_cd
    (``crushing_end``); zero beyond. With Gc = 0 it is :func:`compression_envelope` (zero at and
    beyond eps_cu)."""
    f_cu, eps_cd = crushing_end(E0, fc, eps_c, eps_cu, Gc, ls)
    return _crushing(x, E0, E0 * eps_c / fc, eps_c, eps_cu, f_cu, eps_cd)


@njit(cache=True)
def _crushing(x, E0, a, eps_c, eps_cu, f_cu, eps_cd):
    """:func:`crushing_envelope` with its constants a, f_cu and eps_cd given."""
    if x < eps_cu:
        return _compression(x, E0, a, eps_c, eps_cu)
    if x >= eps_cd:
        return 0.0, 0.0
    slope = -f_cu / (eps_cd - eps_cu)
    return f_cu + slope * (x - eps_cu), slope


@njit(cache=True)
def irreversible_strain(x_max, E0, fc, eps_c, eps_cu):
    """Second form of eq. (5.3): eps_p = x_max - f(x_max) / E0 (magnitudes; 0 before any compression)."""
    return _irreversible(x_max, E0, E0 * eps_c / fc, eps_c, eps_cu)


@njit(cache=True)
def _irreversible(x_max, E0, a, eps_c, eps_cu):
    if x_max <= 0.0:
        return 0.0
    f, _ = _compression(x_max, E0, a, eps_c, eps_cu)
    return x_max - f / E0


@njit(cache=True)
def irreversible_strain_from_stress(sig, descending, E0, fc, eps_c):
    """First form of eq. (5.3): eps_p from the stress magnitude ``sig`` on the envelope (0 < sig <= fc).

    Inverting eq. (5.1) for x = eps/eps_c gives sig x^2 + (sig (a - 2) - E0 eps_c) x + sig = 0,
    a = E0 eps_c / fc; the smaller root is on the ascending branch, the larger (``descending`` = True)
    on the descending one. Then eps_p = eps_c x - sig / E0.
    """
    a = E0 * eps_c / fc
    bq = sig * (a - 2.0) - E0 * eps_c
    disc = bq * bq - 4.0 * sig * sig
    disc = max(disc, 0.0)
    root = math.sqrt(disc)
    if descending:
        x = (-bq + root) / (2.0 * sig)
    else:
        x = (-bq - root) / (2.0 * sig)
    return eps_c * x - sig / E0


@njit(cache=True)
def softening_modulus(E0, fr, Gf, ls):
    """Eq. (5.4): Es = -E0 / (2 E0 Gf / (ls fr^2) - 1); negative only while ls < 2 E0 Gf / fr^2."""
    return -E0 / (2.0 * E0 * Gf / (ls * fr * fr) - 1.0)


@njit(cache=True)
def tension_envelope(e, E0, fr, Gf, ls, alpha_ts, eps_y):
    """Cracked tension envelope at strain ``e`` > eps_r = fr/E0: return ``(sig, dsig/de)``.

    max(linear softening eq. 5.4 reaching zero at eps_u = 2 Gf / (fr ls), tension stiffening
    alpha_ts fr (eps_y - e) / (eps_y - eps_r) reaching zero at eps_y).
    """
    eps_r = fr / E0
    eps_u = 2.0 * Gf / (fr * ls)
    return _tension(e, fr, eps_r, eps_u, softening_modulus(E0, fr, Gf, ls), alpha_ts, eps_y)


@njit(cache=True)
def _tension(e, fr, eps_r, eps_u, e_soft, alpha_ts, eps_y):
    """:func:`tension_envelope` with its constants eps_r, eps_u and the softening modulus e_soft given."""
    s_soft = 0.0
    d_soft = 0.0
    if e < eps_u:
        d_soft = e_soft
        s_soft = fr + d_soft * (e - eps_r)
    s_ts = 0.0
    d_ts = 0.0
    if alpha_ts > 0.0 and e < eps_y:
        d_ts = -alpha_ts * fr / (eps_y - eps_r)
        s_ts = alpha_ts * fr * (eps_y - e) / (eps_y - eps_r)
    if s_ts > s_soft:
        return s_ts, d_ts
    return s_soft, d_soft


@njit(cache=True)
def shear_retention(e_max, eps_r, eps_y, beta0, beta_floor):
    """Fig. 6: 1 before cracking, beta0 (1 - e_max/eps_y) after, never below ``beta_floor``."""
    if e_max <= eps_r:
        return 1.0
    b = beta0 * (1.0 - e_max / eps_y)
    if b < beta_floor:
        return beta_floor
    return b


# indices of concrete_constants' tuple
C_E0, C_G, C_EPS_R, C_A, C_F_CU, C_EPS_CD, C_EPS_U, C_E_SOFT = range(8)
N_CONCRETE_CONSTANTS = 8


@njit(cache=True)
def concrete_constants(params):
    """The law's constants, functions of ``params`` alone: (axial E0 -- D1 of eq. 4.4 in plane strain --, G,
    eps_r = fr/E0, a = E0 eps_c/fc of eq. 5.1, f_cu and eps_cd of ``crushing_end``, eps_u = 2 Gf/(fr ls) and
    the softening modulus of eq. 5.4), indexed by ``C_*``. A dozen divisions: the plate kernel computes them
    once per layer (and crack band) instead of at every layer point, with the same expressions, so the update
    is the same bit for bit. A parameter that would divide by zero (fr ls = 0, which validation rejects)
    gives inf."""
    E0 = params[P_E0]
    G = 0.5 * E0 / (1.0 + params[P_NU])
    if params[P_PLANE] != 0.0:
        E0 = E0 / (1.0 - params[P_NU] * params[P_NU])  # plane strain: D1 of eq. (4.4)
    fc = params[P_FC]
    eps_c = params[P_EPS_C]
    eps_cu = params[P_EPS_CU]
    fr = params[P_FR]
    Gf = params[P_GF]
    ls = params[P_LS]
    f_cu, eps_cd = crushing_end(E0, fc, eps_c, eps_cu, params[P_GC], ls)
    eps_u = math.inf
    e_soft = math.inf
    if fr * ls != 0.0:
        eps_u = 2.0 * Gf / (fr * ls)
        e_soft = softening_modulus(E0, fr, Gf, ls)
    return (E0, G, fr / E0, E0 * eps_c / fc, f_cu, eps_cd, eps_u, e_soft)


@njit(cache=True)
def concrete_update(params, eps, gam, hist_old, hist_new, tangent):
    """One concrete layer point: return ``(sig, tau, e_t, g_t)`` and write ``hist_new``.

    ``tangent`` = 0 returns the initial moduli (E0, G) for K0, ``SECANT_SOFTENING`` the secant sig / e in
    place of the negative d sig/d eps on the cracked tension envelope (d sig/d eps elsewhere), any other flag
    d sig/d eps and d tau/d gam. The stresses and the history do not depend on the flag.
    Shapes: params (>= N_CONCRETE_PARAMS,), hist_old/hist_new (>= N_CONCRETE_HIST,).
    """
    return concrete_update_with(concrete_constants(params), params, eps, gam, hist_old, hist_new, tangent)


@njit(cache=True)
def concrete_update_with(const, params, eps, gam, hist_old, hist_new, tangent):
    """:func:`concrete_update` with the law's constants ``const`` (``concrete_constants(params)``, a tuple or
    an array row) given."""
    E0 = const[C_E0]
    G = const[C_G]
    eps_c = params[P_EPS_C]
    eps_cu = params[P_EPS_CU]
    fr = params[P_FR]
    eps_r = const[C_EPS_R]
    a = const[C_A]
    eps_y = params[P_EPS_Y]
    x_max = hist_old[H_XMAX]
    e_max = hist_old[H_EMAX]
    # 5. shear retention from the committed crack state (see the module docstring)
    if x_max >= eps_cu:
        beta = params[P_BETA_FLOOR]
    else:
        beta = shear_retention(e_max, eps_r, eps_y, params[P_BETA0], params[P_BETA_FLOOR])
    x = -eps
    sig = 0.0
    e_t = 0.0
    f_cu = const[C_F_CU]
    eps_cd = const[C_EPS_CD]
    if x_max >= eps_cd or x >= eps_cd:
        # 1. crushed through: no stress from now on
        x_max = max(x_max, x)
    elif x > x_max:
        # 2. compression loading on the envelope, eq. (5.1), then the regularised crushing branch
        f, df = _crushing(x, E0, a, eps_c, eps_cu, f_cu, eps_cd)
        sig = -f
        e_t = df
        x_max = x
    elif x_max >= eps_cu:
        # 3. unloading from the crushing branch: E0 from the irreversible strain, compression only
        f_m, _ = _crushing(x_max, E0, a, eps_c, eps_cu, f_cu, eps_cd)
        e = eps + x_max - f_m / E0
        if e < 0.0:
            sig = E0 * e
            e_t = E0
    else:
        # 3. shift by the irreversible strain, eq. (5.3)
        e = eps + _irreversible(x_max, E0, a, eps_c, eps_cu)
        if e <= 0.0 or e <= eps_r and e_max <= eps_r:
            sig = E0 * e
            e_t = E0
        elif e >= e_max:
            # 4. loading on the cracked envelope
            sig, e_t = _tension(e, fr, eps_r, const[C_EPS_U], const[C_E_SOFT], params[P_ALPHA_TS], eps_y)
            if tangent == SECANT_SOFTENING and e_t < 0.0:
                e_t = sig / e  # the secant of the unloading branch this point would follow (docstring)
            e_max = e
        else:
            # 4. unloading of a cracked point: secant towards the origin
            s_env, _ = _tension(e_max, fr, eps_r, const[C_EPS_U], const[C_E_SOFT], params[P_ALPHA_TS], eps_y)
            e_t = s_env / e_max
            sig = e_t * e
        e_max = max(e_max, e)
    hist_new[H_XMAX] = x_max
    hist_new[H_EMAX] = e_max
    g_t = beta * G
    tau = g_t * gam
    if tangent == K0_MATRIX:
        return sig, tau, E0, G
    return sig, tau, e_t, g_t
