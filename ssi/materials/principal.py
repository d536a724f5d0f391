"""Principal stresses and isotropic elasticity at one plane-strain point: the utilities the soil laws'
schemes (:mod:`.mc_implicit_scheme`, :mod:`.mc_explicit_scheme`, :mod:`.von_mises`) share.

Vectors: strain increment ``deps = [dexx, dezz, dgxz, deyy]`` (engineering shear; deyy = 0 in plane strain),
stress ``sig = [sxx, szz, txz, syy]`` with the out-of-plane stress ``syy`` kept; tension positive. Principal
values are ordered ``s1 >= s2 >= s3``; the in-plane pair (a, b) and the out-of-plane ``yy`` are the three
candidates, on axes that isotropic elasticity keeps.
"""

import math

from numba import njit

__all__ = [
    "dp_times",
    "elastic_fill",
    "elastic_increment",
    "lame",
    "order3",
    "order3_scalars",
    "pick3",
    "plastic_strain_norm",
    "principal_inplane",
    "rotation_matrix",
    "sorted_principal",
    "stress_on_axes",
]


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
def pick3(i, p0, p1, p2):
    """p_i of three scalars (the array-free form of ``p[i]``)."""
    if i == 0:
        return p0
    if i == 1:
        return p1
    return p2


@njit(cache=True)
def order3_scalars(p0, p1, p2):
    """The index triple of :func:`order3` for three scalars, without an array (same compares). The values
    are swapped beside their indices, not picked by index: a call ``pick3(0, ...)`` would make numba compile
    one more copy of ``pick3`` for each literal index (a cold first run pays every copy)."""
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
def sorted_principal(sig, sB, order):
    """Principal stresses of ``sig`` [xx, zz, xz, yy] sorted into ``sB`` (sB[0] >= sB[1] >= sB[2]);
    ``order[i]`` is where sB[i] came from (0, 1: the in-plane pair a, b; 2: the out-of-plane yy).
    Returns (pa, pb, cos, sin) of the in-plane principal axes."""
    pa, pb, cc, ss = principal_inplane(sig[0], sig[1], sig[2])
    py = sig[3]
    order[0], order[1], order[2] = order3_scalars(pa, pb, py)
    for i in range(3):
        sB[i] = pick3(order[i], pa, pb, py)
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
def elastic_increment(sig, lam, mu, deps, alpha, out):
    tr = alpha * (deps[0] + deps[1] + deps[3])
    out[0] = sig[0] + lam * tr + 2.0 * mu * alpha * deps[0]
    out[1] = sig[1] + lam * tr + 2.0 * mu * alpha * deps[1]
    out[2] = sig[2] + mu * alpha * deps[2]
    out[3] = sig[3] + lam * tr + 2.0 * mu * alpha * deps[3]


@njit(cache=True)
def dp_times(lam, mu, v, out):
    """out = Dp v with the 3×3 isotropic principal elasticity Dp (diag λ+2μ, off-diagonal λ)."""
    tr = v[0] + v[1] + v[2]
    for i in range(3):
        out[i] = lam * tr + 2.0 * mu * v[i]


@njit(cache=True)
def plastic_strain_norm(lam, mu, dsig):
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
