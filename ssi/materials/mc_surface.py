"""The Mohr–Coulomb surface in ordered principal stresses: its constants, the yield function and the return
onto it (shared by the implicit scheme and the explicit scheme's drift correction).

Yield function and plastic potential (paper §7, eq. 6.9 with g = f(φ → ψ)), principal stresses ordered
``s1 >= s2 >= s3`` (tension positive)::

    f = k s1 - s3 - 2 c sqrt(k),      k = (1 + sin φ) / (1 - sin φ)
    g = m s1 - s3,                    m = (1 + sin ψ) / (1 - sin ψ)

The apex (φ > 0) is the hydrostatic stress ``s_apex = c cot φ``. :func:`mc_yield_k` is the one yield
function (of a stress vector, with the material's constants); :func:`mc_yield` evaluates it from (c, φ).

History per point (``hist``) of every soil scheme: ``[0]`` accumulated plastic strain norm sqrt(Δεp·Δεp)
summed over steps, ``[1]`` the return branch of the last update (the ``B_*`` codes below); the schemes return
the ``ST_*`` status codes (the von Mises law uses the same codes).

Parameter vector (``params``, float64) for both Mohr–Coulomb kinds, built and validated by
``ssi.materials.soil_laws.mohr_coulomb_params``::

    [E, nu, c, phi, psi, n_sub, drift, 0]     (angles in radians; n_sub, drift used by the explicit scheme)
"""

import math

import numpy as np
from numba import njit

from .principal import dp_times, lame, principal_inplane

__all__ = [
    "B_APEX",
    "B_EDGE12",
    "B_EDGE23",
    "B_ELASTIC",
    "B_PLANE",
    "N_MC_CONSTANTS",
    "ST_ELASTIC",
    "ST_FAIL",
    "ST_PLASTIC",
    "mc_constants",
    "mc_material_constants",
    "mc_return_principal",
    "mc_yield",
    "mc_yield_k",
    "surface_vectors",
]

# branch codes stored in hist[1]
B_ELASTIC = 0
B_PLANE = 1
B_EDGE12 = 2
B_EDGE23 = 3
B_APEX = 4

# status codes (returned to the solver)
ST_ELASTIC = 0
ST_PLASTIC = 1
ST_FAIL = -1

N_MC_CONSTANTS = 6  # (lam, mu, k, m, kc, apex) of one material: see mc_material_constants


@njit(cache=True)
def mc_constants(c, phi, psi):
    """Return ``(k, m, kc, apex)``: slope factors of f and g, the constant 2 c sqrt(k) and c cot φ
    (``inf`` when φ = 0)."""
    sp = math.sin(phi)
    k = (1.0 + sp) / (1.0 - sp)
    sq = math.sin(psi)
    m = (1.0 + sq) / (1.0 - sq)
    kc = 2.0 * c * math.sqrt(k)
    apex = kc / (k - 1.0) if k > 1.0 + 1e-14 else math.inf
    return k, m, kc, apex


@njit(cache=True)
def mc_material_constants(params, out):
    """Fill ``out`` (N_MC_CONSTANTS,) with the constants of a Mohr–Coulomb parameter row that every point
    of the material shares: the Lamé pair and :func:`mc_constants` (an element kernel computes them once per
    material, not per point: three transcendentals and four divisions, ~40 ns of a ~110 ns elastic point)."""
    lam, mu = lame(params[0], params[1])
    k, m, kc, apex = mc_constants(params[2], params[3], params[4])
    out[0], out[1], out[2], out[3], out[4], out[5] = lam, mu, k, m, kc, apex


@njit(cache=True)
def mc_yield_k(sig, k, kc):
    """Yield function f = k s1 - s3 - kc of a stress vector [xx, zz, xz, yy], with the material's constants
    k and kc = 2 c sqrt(k) of :func:`mc_constants`."""
    pa, pb, _, _ = principal_inplane(sig[0], sig[1], sig[2])
    s1 = pa
    s3 = pb
    s1 = max(s1, sig[3])
    s3 = min(s3, sig[3])
    return k * s1 - s3 - kc


@njit(cache=True)
def mc_yield(sig, c, phi):
    """Mohr–Coulomb yield function f(σ) = k s1 - s3 - 2c√k of a stress vector [xx, zz, xz, yy]:
    :func:`mc_yield_k` with the constants of (c, φ)."""
    k, _, kc, _ = mc_constants(c, phi, phi)
    return mc_yield_k(sig, k, kc)


# surface index 0 typed int64, not the literal 0: numba compiles a separate copy of a kernel for each literal
# argument it is called with, and the other calls pass int64 indices
_MAIN_PLANE = np.int64(0)


@njit(cache=True)
def surface_vectors(i, k, m, a, b):
    """Gradient ``a`` of f_i and ``b`` of g_i (ordered principal space) for surface i.

    i = 0: main plane  k s1 - s3;  i = 1: edge neighbour k s2 - s3 (the s1 = s2 edge);
    i = 2: edge neighbour k s1 - s2 (the s2 = s3 edge).
    """
    a[0] = 0.0
    a[1] = 0.0
    a[2] = 0.0
    b[0] = 0.0
    b[1] = 0.0
    b[2] = 0.0
    if i == 0:
        a[0], a[2], b[0], b[2] = k, -1.0, m, -1.0
    elif i == 1:
        a[1], a[2], b[1], b[2] = k, -1.0, m, -1.0
    else:
        a[0], a[1], b[0], b[1] = k, -1.0, m, -1.0


@njit(cache=True)
def mc_return_principal(sB, lam, mu, k, m, kc, apex, sig, H, vec):
    """Return-map the ordered trial principal stresses ``sB`` (3,) onto the Mohr–Coulomb surface.

    Writes the returned ordered principal stresses ``sig`` (3,) and ``H`` (3, 3) = d sig / d sB (the leading
    3 x 3 block where the arrays are larger); ``vec`` (6, >= 3) is scratch for the gradient vectors.
    Returns the branch code (B_PLANE, B_EDGE12, B_EDGE23, B_APEX) or -1 if no branch was admissible.
    Assumes f(sB) > 0.

    Step 1 (plane): Δλ = f(sB) / (aᵀ Dp b); sig = sB - Δλ Dp b; accept if s1 >= s2 >= s3.
    Step 2 (edge): two active planes i = 0 and j (j = 1 if the plane return gave s2 > s1, else 2):
            solve A Δλ = f(sB), A_pq = a_pᵀ Dp b_q; accept if Δλ >= 0 and the result keeps its order
            (i.e. it lies on the edge below the apex).
    Step 3 (apex): sig = apex (φ > 0 only); H = 0.
    """
    a0 = vec[0]
    b0 = vec[1]
    a1 = vec[2]
    b1 = vec[3]
    r0 = vec[4]
    r1 = vec[5]
    fB = k * sB[0] - sB[2] - kc
    # --- plane
    surface_vectors(_MAIN_PLANE, k, m, a0, b0)
    dp_times(lam, mu, b0, r0)
    den = a0[0] * r0[0] + a0[1] * r0[1] + a0[2] * r0[2]
    dl = fB / den
    for i in range(3):
        sig[i] = sB[i] - dl * r0[i]
    scale = abs(sB[0]) + abs(sB[1]) + abs(sB[2]) + kc + 1e-300
    tol = 1e-12 * scale
    viol12 = sig[1] - sig[0] > tol
    viol23 = sig[2] - sig[1] > tol
    if not viol12 and not viol23:
        inv_den = 1.0 / den  # one division for the nine entries of H
        for i in range(3):
            for j in range(3):
                H[i, j] = (1.0 if i == j else 0.0) - r0[i] * a0[j] * inv_den
        return B_PLANE
    # --- edges (try the indicated one first, then the other)
    for attempt in range(2):
        if attempt == 0:
            jj = 1 if viol12 else 2
        else:
            jj = 2 if viol12 else 1
        surface_vectors(jj, k, m, a1, b1)
        dp_times(lam, mu, b1, r1)
        A00 = a0[0] * r0[0] + a0[1] * r0[1] + a0[2] * r0[2]
        A01 = a0[0] * r1[0] + a0[1] * r1[1] + a0[2] * r1[2]
        A10 = a1[0] * r0[0] + a1[1] * r0[1] + a1[2] * r0[2]
        A11 = a1[0] * r1[0] + a1[1] * r1[1] + a1[2] * r1[2]
        det = A00 * A11 - A01 * A10
        if abs(det) < 1e-300:
            continue
        f0 = fB
        f1 = a1[0] * sB[0] + a1[1] * sB[1] + a1[2] * sB[2] - kc
        # inverse of A
        I00 = A11 / det
        I01 = -A01 / det
        I10 = -A10 / det
        I11 = A00 / det
        dl0 = I00 * f0 + I01 * f1
        dl1 = I10 * f0 + I11 * f1
        if dl0 < -tol / (abs(A00) + 1e-300) or dl1 < -tol / (abs(A11) + 1e-300):
            continue
        for i in range(3):
            sig[i] = sB[i] - dl0 * r0[i] - dl1 * r1[i]
        if sig[0] - sig[2] < -tol:
            continue  # past the apex
        # H = I - [r0 r1] A^{-1} [a0 a1]^T
        for i in range(3):
            for j in range(3):
                H[i, j] = (
                    (1.0 if i == j else 0.0)
                    - r0[i] * (I00 * a0[j] + I01 * a1[j])
                    - r1[i] * (I10 * a0[j] + I11 * a1[j])
                )
        return B_EDGE12 if jj == 1 else B_EDGE23
    # --- apex
    if apex < math.inf:
        for i in range(3):
            sig[i] = apex
            for j in range(3):
                H[i, j] = 0.0
        return B_APEX
    return -1
