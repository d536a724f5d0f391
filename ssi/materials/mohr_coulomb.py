"""Mohr–Coulomb (and von Mises) stress integration at one plane-strain integration point.

Vectors: strain increment ``deps = [dexx, dezz, dgxz, deyy]`` (engineering shear; deyy = 0 in plane strain),
stress ``sig = [sxx, szz, txz, syy]`` with the out-of-plane stress ``syy`` kept; tension positive.

Yield function and plastic potential (paper §7, eq. 6.9 with g = f(φ → ψ)), principal stresses ordered
``s1 >= s2 >= s3`` (tension positive)::

    f = k s1 - s3 - 2 c sqrt(k),      k = (1 + sin φ) / (1 - sin φ)
    g = m s1 - s3,                    m = (1 + sin ψ) / (1 - sin ψ)

The apex (φ > 0) is the hydrostatic stress ``s_apex = c cot φ``.

Two integration schemes are provided, both pure numba kernels with the ``soil_update`` signature:

* :func:`mc_implicit` — return mapping in principal stresses (after Clausen, Damkilde & Andersen 2006/2007):
  the trial stress is returned to the main plane, to one of the two edges, or to the apex, found by trying
  them in that order and accepting the first whose multipliers are non-negative and whose result keeps the
  principal order. Because the surfaces are planes in principal space and isotropic elasticity keeps the
  principal axes, each return is one linear solve. Its consistent tangent (unsymmetric when ψ ≠ φ) adds the
  rotation of the principal axes.
* :func:`mc_explicit` — the paper's tangent scheme Δσ = D_ep(σ) Δε (forward Euler), with the elastic part of
  the increment split off at the yield surface, optional sub-stepping and optional drift correction.

History per point (``hist``): ``[0]`` accumulated plastic strain norm sqrt(Δεp·Δεp) summed over steps,
``[1]`` the return branch of the last update (0 elastic, 1 plane, 2 edge s1 = s2, 3 edge s2 = s3, 4 apex).

Parameter vector (``params``, float64) for both Mohr–Coulomb kinds, built and validated by
``ssi.materials.soil_laws.mohr_coulomb_params``::

    [E, nu, c, phi, psi, n_sub, drift, 0]     (angles in radians; n_sub, drift used by the explicit scheme)

Von Mises (plane-strain Tresca-equivalent, Smith & Griffiths' Program 6.1): ``[E, nu, cu, ...]`` with
``sqrt(J2) = cu``; radial return with its consistent tangent.
"""

import math

import numpy as np
from numba import njit

from ..core.protocol import K0_MATRIX

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


# ---------------------------------------------------------------------------------------------------------
# small helpers
# ---------------------------------------------------------------------------------------------------------
@njit(cache=True)
def lame(E, nu):
    """Return the Lamé constants (lambda, mu)."""
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), 0.5 * E / (1.0 + nu)


@njit(cache=True)
def principal_inplane(sxx, szz, sxz):
    """In-plane principal stresses ``pa >= pb`` and the direction ``n_a = (c, s)`` of ``pa``.

    Returns ``(pa, pb, c, s)``; the direction of ``pb`` is ``(-s, c)``.
    """
    mean = 0.5 * (sxx + szz)
    half = 0.5 * (sxx - szz)
    rad = math.sqrt(half * half + sxz * sxz)
    if rad == 0.0:
        return mean, mean, 1.0, 0.0
    # theta = atan2(sxz, half) / 2 in (-pi/2, pi/2] by the half-angle formulas: one square root instead of
    # atan2, cos and sin (those three were ~80 % of an elastic Mohr-Coulomb point's time); each branch takes
    # the root of the larger of 1 +- cos(2 theta), so neither loses digits near theta = 0 or +-pi/2
    if half >= 0.0:
        c = math.sqrt(0.5 * (1.0 + half / rad))
        return mean + rad, mean - rad, c, 0.5 * sxz / (rad * c)
    s = math.copysign(math.sqrt(0.5 * (1.0 - half / rad)), sxz)
    return mean + rad, mean - rad, 0.5 * sxz / (rad * s), s


@njit(cache=True)
def order3(p, order):
    """Fill ``order`` (3,) int so that ``p[order[0]] >= p[order[1]] >= p[order[2]]`` (plain compares)."""
    i0, i1, i2 = 0, 1, 2
    if p[i0] < p[i1]:
        i0, i1 = i1, i0
    if p[i1] < p[i2]:
        i1, i2 = i2, i1
    if p[i0] < p[i1]:
        i0, i1 = i1, i0
    order[0] = i0
    order[1] = i1
    order[2] = i2


@njit(cache=True)
def _pick3(i, p0, p1, p2):
    """p_i of three scalars (the array-free form of ``p[i]``)."""
    if i == 0:
        return p0
    if i == 1:
        return p1
    return p2


@njit(cache=True)
def order3_scalars(p0, p1, p2):
    """The index triple of :func:`order3` for three scalars, without an array (same compares). The values
    are swapped beside their indices, not picked by index: a call ``_pick3(0, ...)`` would make numba compile
    one more copy of ``_pick3`` for each literal index (a cold first run pays every copy)."""
    i0, i1, i2 = 0, 1, 2
    v0, v1, v2 = p0, p1, p2
    if v0 < v1:
        i0, i1, v0, v1 = i1, i0, v1, v0
    if v1 < v2:
        i1, i2, v1, v2 = i2, i1, v2, v1
    if v0 < v1:
        i0, i1 = i1, i0
    return i0, i1, i2


@njit(cache=True)
def rotation_matrix(c, s, R):
    """Fill ``R`` (4, 4): sig_global = R sig_principal_frame, components [aa, bb, ab, yy] → [xx, zz, xz, yy].

    Strains (engineering shear) transform with the transpose: eps_principal_frame = R^T eps_global.
    """
    R[:, :] = 0.0
    R[0, 0] = c * c
    R[0, 1] = s * s
    R[0, 2] = -2.0 * c * s
    R[1, 0] = s * s
    R[1, 1] = c * c
    R[1, 2] = 2.0 * c * s
    R[2, 0] = c * s
    R[2, 1] = -c * s
    R[2, 2] = c * c - s * s
    R[3, 3] = 1.0


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
def mc_yield(sig, c, phi):
    """Mohr–Coulomb yield function f(σ) = k s1 - s3 - 2c√k of a stress vector [xx, zz, xz, yy]."""
    pa, pb, _, _ = principal_inplane(sig[0], sig[1], sig[2])
    s1 = pa
    s3 = pb
    s1 = max(s1, sig[3])
    s3 = min(s3, sig[3])
    sp = math.sin(phi)
    k = (1.0 + sp) / (1.0 - sp)
    return k * s1 - s3 - 2.0 * c * math.sqrt(k)


# ---------------------------------------------------------------------------------------------------------
# return mapping in ordered principal space
# ---------------------------------------------------------------------------------------------------------
# surface index 0 typed int64, not the literal 0: numba compiles a separate copy of a kernel for each literal
# argument it is called with, and the other calls pass int64 indices
_MAIN_PLANE = np.int64(0)


@njit(cache=True)
def _surface_vectors(i, k, m, a, b):
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
def _dp_times(lam, mu, v, out):
    """out = Dp v with the 3×3 isotropic principal elasticity Dp (diag λ+2μ, off-diagonal λ)."""
    tr = v[0] + v[1] + v[2]
    for i in range(3):
        out[i] = lam * tr + 2.0 * mu * v[i]


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
    _surface_vectors(_MAIN_PLANE, k, m, a0, b0)
    _dp_times(lam, mu, b0, r0)
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
        _surface_vectors(jj, k, m, a1, b1)
        _dp_times(lam, mu, b1, r1)
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


# ---------------------------------------------------------------------------------------------------------
# implicit scheme
# ---------------------------------------------------------------------------------------------------------
@njit(cache=True)
def sorted_principal(sig, sB, order):
    """Principal stresses of ``sig`` [xx, zz, xz, yy] sorted into ``sB`` (sB[0] >= sB[1] >= sB[2]);
    ``order[i]`` is where sB[i] came from (0, 1: the in-plane pair a, b; 2: the out-of-plane yy).
    Returns (pa, pb, cos, sin) of the in-plane principal axes."""
    pa, pb, cc, ss = principal_inplane(sig[0], sig[1], sig[2])
    py = sig[3]
    order[0], order[1], order[2] = order3_scalars(pa, pb, py)
    for i in range(3):
        sB[i] = _pick3(order[i], pa, pb, py)
    return pa, pb, cc, ss


@njit(cache=True)
def stress_on_axes(s, order, cc, ss, sig, q, R):
    """Inverse of :func:`sorted_principal`: the sorted principal values ``s`` back to their positions
    ``q`` [a, b, yy] and to ``sig`` [xx, zz, xz, yy] on the same axes; ``R`` gets the rotation matrix."""
    for i in range(3):
        q[order[i]] = s[i]
    rotation_matrix(cc, ss, R)
    for i in range(3):
        sig[i] = R[i, 0] * q[0] + R[i, 1] * q[1]
    sig[3] = q[2]


@njit(cache=True)
def elastic_fill(lam, mu, D):
    """Fill ``D`` (4, 4) with the isotropic elastic matrix of Lamé constants (lam, mu), order [xx, zz, xz,
    yy]."""
    D[:, :] = 0.0
    for i in (0, 1, 3):
        for j in (0, 1, 3):
            D[i, j] = lam
        D[i, i] = lam + 2.0 * mu
    D[2, 2] = mu


@njit(cache=True)
def _plastic_strain_norm(lam, mu, dsig):
    """sqrt(Δεpᵀ Δεp) of Δεp = Dp⁻¹ dsig in principal space (3D isotropic compliance)."""
    E = mu * (3.0 * lam + 2.0 * mu) / (lam + mu)
    nu = lam / (2.0 * (lam + mu))
    tr = dsig[0] + dsig[1] + dsig[2]
    inv_e = 1.0 / E
    s = 0.0
    for i in range(3):
        e = ((1.0 + nu) * dsig[i] - nu * tr) * inv_e
        s += e * e
    return math.sqrt(s)


N_MC_CONSTANTS = 6  # (lam, mu, k, m, kc, apex) of one material: see mc_material_constants
# float scratch of mc_implicit, shape (N_MC_WORK_ROWS, 4): rows 0-3 the vectors sB, s, q, ds, rows 4-23 five
# (4, 4) matrices, rows 24-29 the six gradient vectors of mc_return_principal -- each taken by slicing rows,
# not by reshaping a flat buffer: a numba reshape calls a C helper (~18 ns), and a plastic point made three
N_MC_WORK_ROWS = 30


@njit(cache=True)
def mc_material_constants(params, out):
    """Fill ``out`` (N_MC_CONSTANTS,) with the constants of a Mohr–Coulomb parameter row that every point
    of the material shares: the Lamé pair and :func:`mc_constants` (an element kernel computes them once per
    material, not per point: three transcendentals and four divisions, ~40 ns of a ~110 ns elastic point)."""
    lam, mu = lame(params[0], params[1])
    k, m, kc, apex = mc_constants(params[2], params[3], params[4])
    out[0], out[1], out[2], out[3], out[4], out[5] = lam, mu, k, m, kc, apex


# inlined (numba IR) into the element kernel: a call passes each array argument as its whole struct, and the
# call of this function was ~35 ns of a ~165 ns mixed elastic/plastic point (bench_kernels.py); +0.4 s compile
@njit(cache=True, inline="always")
def mc_implicit(constants, deps, sig_old, hist_old, sig_new, hist_new, D, tangent, work, iwork):
    """Implicit (backward-Euler) Mohr–Coulomb update; returns 0 elastic, 1 plastic, -1 failure.

    ``constants`` (N_MC_CONSTANTS,): the material's row of :func:`mc_material_constants`. Shapes: deps (4,),
    sig_old (4,), hist_old (2,), sig_new (4,), hist_new (2,), D (4, 4); scratch ``work`` (N_MC_WORK_ROWS, 4)
    float and ``iwork`` (3,) int, owned by the caller so that a plastic point allocates nothing either (four
    small allocations were most of a plastic point's time).

    1. Trial stress sB = σ_old + D Δε (elastic predictor).
    2. Principal values of sB: in-plane pair (pa, pb) with axes n_a, n_b and the out-of-plane syy; order them.
    3. If f(sB) <= 0: elastic. Else return in principal space (:func:`mc_return_principal`).
    4. Rebuild σ on the unchanged principal axes.
    5. Tangent (``tangent == CONSISTENT``): in the principal frame of sB,
       C = H Dp for the normal components and G* = μ (σa - σb) / (sBa - sBb) for the in-plane shear
       (rotation of the axes); rotate: D = R C Rᵀ. ``tangent == K0_MATRIX`` returns the elastic D.
    """
    lam, mu, k = constants[0], constants[1], constants[2]
    m, kc, apex = constants[3], constants[4], constants[5]
    # trial stress and its ordered principal values as scalars: an elastic point allocates nothing
    tr = deps[0] + deps[1] + deps[3]
    t0 = sig_old[0] + lam * tr + 2.0 * mu * deps[0]
    t1 = sig_old[1] + lam * tr + 2.0 * mu * deps[1]
    t2 = sig_old[2] + mu * deps[2]
    t3 = sig_old[3] + lam * tr + 2.0 * mu * deps[3]
    pa, pb, cc, ss = principal_inplane(t0, t1, t2)
    o0, o1, o2 = order3_scalars(pa, pb, t3)
    sB0 = _pick3(o0, pa, pb, t3)
    sB1 = _pick3(o1, pa, pb, t3)
    sB2 = _pick3(o2, pa, pb, t3)
    fB = k * sB0 - sB2 - kc
    scale = abs(sB0) + abs(sB1) + abs(sB2) + kc
    if fB <= 1e-12 * scale:
        sig_new[0] = t0
        sig_new[1] = t1
        sig_new[2] = t2
        sig_new[3] = t3
        hist_new[0] = hist_old[0]
        hist_new[1] = B_ELASTIC
        elastic_fill(lam, mu, D)
        return ST_ELASTIC
    # plastic: vectors, small matrices and the index triple live in the caller's scratch
    sB = work[0]
    s = work[1]
    q = work[2]
    ds = work[3]
    H = work[4:8]
    R = work[8:12]
    Cp = work[12:16]
    C4 = work[16:20]
    T = work[20:24]
    order = iwork
    order[0] = o0
    order[1] = o1
    order[2] = o2
    sB[0] = sB0
    sB[1] = sB1
    sB[2] = sB2
    branch = mc_return_principal(sB, lam, mu, k, m, kc, apex, s, H, work[24:30])
    if branch < 0:
        sig_new[0] = t0
        sig_new[1] = t1
        sig_new[2] = t2
        sig_new[3] = t3
        hist_new[0] = hist_old[0]
        hist_new[1] = -1.0
        elastic_fill(lam, mu, D)
        return ST_FAIL
    # back to [a, b, y] positions
    stress_on_axes(s, order, cc, ss, sig_new, q, R)
    for i in range(3):
        ds[i] = sB[i] - s[i]
    hist_new[0] = hist_old[0] + _plastic_strain_norm(lam, mu, ds)
    hist_new[1] = branch
    if tangent == K0_MATRIX:
        elastic_fill(lam, mu, D)
        return ST_PLASTIC
    # C (ordered) = H Dp, then permute to [a, b, y]
    for i in range(3):
        for j in range(3):
            v = 0.0
            for t in range(3):
                v += H[i, t] * (lam + (2.0 * mu if t == j else 0.0))
            Cp[order[i], order[j]] = v
    C4[:, :] = 0.0
    idx = (0, 1, 3)
    for i in range(3):
        for j in range(3):
            C4[idx[i], idx[j]] = Cp[i, j]
    dB = pa - pb
    if abs(dB) > 1e-10 * (abs(pa) + abs(pb) + kc + 1e-300):
        C4[2, 2] = mu * (q[0] - q[1]) / dB
    else:
        C4[2, 2] = 0.5 * (Cp[0, 0] - Cp[0, 1])
    # D = R C4 R^T
    for i in range(4):
        for j in range(4):
            v = 0.0
            for t in range(4):
                v += R[i, t] * C4[t, j]
            T[i, j] = v
    for i in range(4):
        for j in range(4):
            v = 0.0
            for t in range(4):
                v += T[i, t] * R[j, t]
            D[i, j] = v
    return ST_PLASTIC


# ---------------------------------------------------------------------------------------------------------
# explicit (tangent) scheme
# ---------------------------------------------------------------------------------------------------------
@njit(cache=True)
def _small_inverse(G):
    """Inverse of a small (n <= 3) matrix by Gauss–Jordan elimination with partial pivoting."""
    n = G.shape[0]
    A = G.copy()
    Inv = np.zeros((n, n))
    for i in range(n):
        Inv[i, i] = 1.0
    for col in range(n):
        piv = col
        for r in range(col + 1, n):
            if abs(A[r, col]) > abs(A[piv, col]):
                piv = r
        if piv != col:
            for j in range(n):
                A[col, j], A[piv, j] = A[piv, j], A[col, j]
                Inv[col, j], Inv[piv, j] = Inv[piv, j], Inv[col, j]
        d = A[col, col]
        for j in range(n):
            A[col, j] /= d
            Inv[col, j] /= d
        for r in range(n):
            if r != col:
                f = A[r, col]
                for j in range(n):
                    A[r, j] -= f * A[col, j]
                    Inv[r, j] -= f * Inv[col, j]
    return Inv


@njit(cache=True)
def _continuum_dep(sig, lam, mu, k, m, kc, apex, deps, Dep, use_deps):
    """Continuum elasto-plastic matrix D_ep at a stress on the surface (eq. 6.9, multi-surface form).

    Active planes: the main plane, plus an edge neighbour when two principal stresses coincide to a
    relative 1e-9 (Koiter's rule). When ``use_deps`` is true, planes whose multiplier
    Δλ = (Aᵀ...)⁻¹ aᵀ D Δε would be negative are dropped (elastic unloading from them); returns the number of
    active planes (0 = elastic). At the apex (all three equal to c cot φ) D_ep = 0 for loading.
    Dep (4, 4) is written in global components.
    """
    order = np.empty(3, np.int64)
    sB = np.empty(3)
    _, _, cc, ss = sorted_principal(sig, sB, order)
    s1, s2, s3 = sB[0], sB[1], sB[2]
    scale = abs(s1) + abs(s2) + abs(s3) + kc + 1e-300
    etol = 1e-9 * scale
    elastic_fill(lam, mu, Dep)
    # global gradient basis of each ordered principal value: Voigt vectors (xz doubled)
    Nv = np.zeros((3, 4))  # rows: [a, b, y] directions
    Nv[0, 0] = cc * cc
    Nv[0, 1] = ss * ss
    Nv[0, 2] = 2.0 * cc * ss
    Nv[1, 0] = ss * ss
    Nv[1, 1] = cc * cc
    Nv[1, 2] = -2.0 * cc * ss
    Nv[2, 3] = 1.0
    apex_here = apex < math.inf and (s1 - s3) < etol
    if apex_here:
        # on the apex: loading (trial outside) keeps σ, unloading is elastic
        if use_deps:
            st = np.empty(4)
            tr = deps[0] + deps[1] + deps[3]
            st[0] = sig[0] + lam * tr + 2.0 * mu * deps[0]
            st[1] = sig[1] + lam * tr + 2.0 * mu * deps[1]
            st[2] = sig[2] + mu * deps[2]
            st[3] = sig[3] + lam * tr + 2.0 * mu * deps[3]
            if _yield_k(st, k, kc) <= 0.0:
                return 0
        Dep[:, :] = 0.0
        return 3
    planes = np.zeros(3, np.int64)
    planes[0] = 1
    if s1 - s2 < etol:
        planes[1] = 1
    if s2 - s3 < etol:
        planes[2] = 1
    a3 = np.empty(3)
    b3 = np.empty(3)
    Av = np.zeros((3, 4))  # global a vectors of the candidate planes
    Bv = np.zeros((3, 4))
    for pl in range(3):
        _surface_vectors(pl, k, m, a3, b3)
        for i in range(3):
            for j in range(4):
                Av[pl, j] += a3[i] * Nv[order[i], j]
                Bv[pl, j] += b3[i] * Nv[order[i], j]
    DB = np.zeros((3, 4))  # D b, D a (D symmetric)
    DA = np.zeros((3, 4))
    for pl in range(3):
        for i in range(4):
            vb = 0.0
            va = 0.0
            for j in range(4):
                vb += Dep[i, j] * Bv[pl, j]
                va += Dep[i, j] * Av[pl, j]
            DB[pl, i] = vb
            DA[pl, i] = va
    for _ in range(3):
        act = np.empty(3, np.int64)
        n = 0
        for pl in range(3):
            if planes[pl] == 1:
                act[n] = pl
                n += 1
        if n == 0:
            return 0
        G = np.zeros((n, n))
        for i in range(n):
            for j in range(n):
                v = 0.0
                for t in range(4):
                    v += Av[act[i], t] * DB[act[j], t]
                G[i, j] = v
        Gi = _small_inverse(G)
        if use_deps:
            # multipliers for this strain increment
            ok = True
            for i in range(n):
                v = 0.0
                for j in range(n):
                    w = 0.0
                    for t in range(4):
                        w += DA[act[j], t] * deps[t]
                    v += Gi[i, j] * w
                if v < 0.0:
                    planes[act[i]] = 0
                    ok = False
            if not ok:
                continue
        for i in range(n):
            for j in range(n):
                g = Gi[i, j]
                for r in range(4):
                    for q in range(4):
                        Dep[r, q] -= DB[act[i], r] * g * DA[act[j], q]
        return n
    return 0


@njit(cache=True)
def _elastic_increment(sig, lam, mu, deps, alpha, out):
    tr = alpha * (deps[0] + deps[1] + deps[3])
    out[0] = sig[0] + lam * tr + 2.0 * mu * alpha * deps[0]
    out[1] = sig[1] + lam * tr + 2.0 * mu * alpha * deps[1]
    out[2] = sig[2] + mu * alpha * deps[2]
    out[3] = sig[3] + lam * tr + 2.0 * mu * alpha * deps[3]


@njit(cache=True)
def _yield_k(sig, k, kc):
    pa, pb, _, _ = principal_inplane(sig[0], sig[1], sig[2])
    s1 = pa
    s3 = pb
    s1 = max(s1, sig[3])
    s3 = min(s3, sig[3])
    return k * s1 - s3 - kc


@njit(cache=True)
def mc_drift_correct(sig, lam, mu, k, m, kc, apex):
    """Drift correction: move a stress with f > 0 back to the surface along D b evaluated at that stress
    (Potts & Gens' 'consistent' correction). For Mohr–Coulomb's planes this single correction is exactly the
    principal-space return of :func:`mc_return_principal` with the drifted stress as trial. In place; returns
    the branch code, 0 if no correction was needed."""
    order = np.empty(3, np.int64)
    sB = np.empty(3)
    _, _, cc, ss = sorted_principal(sig, sB, order)
    fB = k * sB[0] - sB[2] - kc
    if fB <= 1e-12 * (abs(sB[0]) + abs(sB[1]) + abs(sB[2]) + kc):
        return 0
    s = np.empty(3)
    H = np.empty((3, 3))
    br = mc_return_principal(sB, lam, mu, k, m, kc, apex, s, H, np.empty((6, 3)))
    if br < 0:
        return br
    q = np.empty(3)
    R = np.empty((4, 4))
    stress_on_axes(s, order, cc, ss, sig, q, R)
    return br


@njit(cache=True)
def mc_explicit(params, deps, sig_old, hist_old, sig_new, hist_new, D, tangent):
    """Explicit tangent Mohr–Coulomb update (the paper's Δσ = D_ep Δε); returns 0 elastic, 1 plastic.

    Shapes as :func:`mc_implicit`. ``params[5]`` = number of equal sub-steps n_sub (>= 1, paper: 1),
    ``params[6]`` = drift correction flag (paper: 0).

    1. Elastic trial σ_old + D Δε; if f <= 0: elastic.
    2. If σ_old is inside (f < 0), find the fraction α of Δε that reaches f = 0 (Illinois regula falsi) and
       apply it elastically.
    3. Split the rest (1 - α) Δε into n_sub equal parts; each: Δσ = D_ep(σ) Δε_sub with D_ep the continuum
       matrix at the current stress (planes with negative multiplier dropped); then, if drift correction is
       on and f > 0, return the stress to the surface.
    4. Tangent: D_ep at the final stress for the last sub-step's direction (continuum tangent).
    """
    E = params[0]
    nu = params[1]
    c = params[2]
    phi = params[3]
    psi = params[4]
    n_sub = int(params[5])
    n_sub = max(n_sub, 1)
    drift = params[6] != 0.0
    lam, mu = lame(E, nu)
    k, m, kc, apex = mc_constants(c, phi, psi)
    st = np.empty(4)
    _elastic_increment(sig_old, lam, mu, deps, 1.0, st)
    f1 = _yield_k(st, k, kc)
    scale = abs(st[0]) + abs(st[1]) + abs(st[3]) + abs(st[2]) + kc + 1e-300
    hist_new[0] = hist_old[0]
    if f1 <= 1e-12 * scale:
        for i in range(4):
            sig_new[i] = st[i]
        hist_new[1] = B_ELASTIC
        elastic_fill(lam, mu, D)
        return ST_ELASTIC
    f0 = _yield_k(sig_old, k, kc)
    alpha = 0.0
    if f0 < -1e-12 * scale:
        # Illinois regula falsi on f(σ_old + α D Δε) = 0 over α in [0, 1]
        lo = 0.0
        hi = 1.0
        flo = f0
        fhi = f1
        side = 0
        for _ in range(60):
            a_ = (lo * fhi - hi * flo) / (fhi - flo)
            _elastic_increment(sig_old, lam, mu, deps, a_, st)
            fa = _yield_k(st, k, kc)
            if abs(fa) <= 1e-13 * scale or hi - lo < 1e-15:
                lo = a_
                break
            if fa > 0.0:
                hi = a_
                fhi = fa
                if side == -1:
                    flo *= 0.5
                side = -1
            else:
                lo = a_
                flo = fa
                if side == 1:
                    fhi *= 0.5
                side = 1
        alpha = lo
    sig = np.empty(4)
    _elastic_increment(sig_old, lam, mu, deps, alpha, sig)
    dsub = np.empty(4)
    for i in range(4):
        dsub[i] = (1.0 - alpha) * deps[i] / n_sub
    Dep = np.empty((4, 4))
    ep = 0.0
    branch = B_PLANE
    for _ in range(n_sub):
        nact = _continuum_dep(sig, lam, mu, k, m, kc, apex, dsub, Dep, True)
        dsig = np.zeros(4)
        for i in range(4):
            v = 0.0
            for j in range(4):
                v += Dep[i, j] * dsub[j]
            dsig[i] = v
        # plastic strain increment D^{-1}(D Δε - Δσ) measured through the elastic part
        if nact > 0:
            de = np.empty(4)
            _elastic_increment(np.zeros(4), lam, mu, dsub, 1.0, de)
            dd = np.empty(3)
            dd[0] = de[0] - dsig[0]
            dd[1] = de[1] - dsig[1]
            dd[2] = de[3] - dsig[3]
            en = _plastic_strain_norm(lam, mu, dd)
            gp = (de[2] - dsig[2]) / mu  # engineering plastic shear strain; tensor norm counts γ/2 twice
            ep += math.sqrt(en * en + 0.5 * gp * gp)
            branch = B_APEX if nact == 3 else (B_PLANE if nact == 1 else B_EDGE12)
        for i in range(4):
            sig[i] += dsig[i]
        if drift:
            mc_drift_correct(sig, lam, mu, k, m, kc, apex)
    for i in range(4):
        sig_new[i] = sig[i]
    hist_new[0] = hist_old[0] + ep
    hist_new[1] = branch
    if tangent == K0_MATRIX:
        elastic_fill(lam, mu, D)
    else:
        _continuum_dep(sig, lam, mu, k, m, kc, apex, dsub, D, True)
    return ST_PLASTIC


# ---------------------------------------------------------------------------------------------------------
# von Mises (plane strain), for the Smith & Griffiths regression
# ---------------------------------------------------------------------------------------------------------
@njit(cache=True)
def vm_implicit(params, deps, sig_old, hist_old, sig_new, hist_new, D, tangent, work):
    """Von Mises radial return, f = sqrt(J2) - cu, perfect plasticity; shapes as :func:`mc_implicit`, whose
    scratch ``work`` (at least 3 rows of 4) it shares, so that it allocates nothing either.

    s_tr = dev(σ_old + D Δε); if ||s_tr|| / √2 > cu: s = r s_tr with r = √2 cu / ||s_tr||; pressure unchanged.
    Consistent tangent: K 1⊗1 + 2μ r (I_dev - n⊗n), n = s_tr / ||s_tr|| (Simo & Hughes, Box 3.2 without
    hardening).
    """
    E = params[0]
    nu = params[1]
    cu = params[2]
    lam, mu = lame(E, nu)
    st = work[0]
    _elastic_increment(sig_old, lam, mu, deps, 1.0, st)
    pm = (st[0] + st[1] + st[3]) / 3.0
    sd = work[1]
    sd[0] = st[0] - pm
    sd[1] = st[1] - pm
    sd[2] = st[2]
    sd[3] = st[3] - pm
    nrm = math.sqrt(sd[0] * sd[0] + sd[1] * sd[1] + sd[3] * sd[3] + 2.0 * sd[2] * sd[2])
    elastic_fill(lam, mu, D)
    hist_new[0] = hist_old[0]
    if nrm <= math.sqrt(2.0) * cu * (1.0 + 1e-12):
        for i in range(4):
            sig_new[i] = st[i]
        hist_new[1] = B_ELASTIC
        return ST_ELASTIC
    r = math.sqrt(2.0) * cu / nrm
    for i in range(4):
        sig_new[i] = sd[i] * r
    sig_new[0] += pm
    sig_new[1] += pm
    sig_new[3] += pm
    hist_new[0] = hist_old[0] + (nrm - math.sqrt(2.0) * cu) / (2.0 * mu)
    hist_new[1] = B_PLANE
    if tangent != K0_MATRIX:
        K = lam + 2.0 * mu / 3.0
        n = work[2]
        for i in range(4):
            n[i] = sd[i] / nrm
        for i in range(4):
            for j in range(4):
                idev = 0.0
                if i != 2 and j != 2:
                    idev = (1.0 if i == j else 0.0) - 1.0 / 3.0
                elif i == 2 and j == 2:
                    idev = 0.5
                D[i, j] = (K if (i != 2 and j != 2) else 0.0) + 2.0 * mu * r * (idev - n[i] * n[j])
    return ST_PLASTIC
