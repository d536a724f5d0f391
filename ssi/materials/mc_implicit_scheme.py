"""The implicit Mohr–Coulomb scheme: return mapping in principal stresses with its consistent tangent.

:func:`mc_implicit` (after Clausen, Damkilde & Andersen 2006/2007): the trial stress is returned to the main
plane, to one of the two edges, or to the apex (:func:`.mc_surface.mc_return_principal`), found by trying
them in that order and accepting the first whose multipliers are non-negative and whose result keeps the
principal order. Because the surfaces are planes in principal space and isotropic elasticity keeps the
principal axes, each return is one linear solve. Its consistent tangent (unsymmetric when ψ ≠ φ) adds the
rotation of the principal axes. Vectors, history and parameters: see :mod:`.mc_surface`.
"""

from numba import njit

from ..core.protocol import K0_MATRIX
from .mc_surface import B_ELASTIC, ST_ELASTIC, ST_FAIL, ST_PLASTIC, mc_return_principal
from .principal import (
    elastic_fill,
    order3_scalars,
    pick3,
    plastic_strain_norm,
    principal_inplane,
    stress_on_axes,
)

__all__ = ["N_MC_WORK_ROWS", "mc_implicit"]

# float scratch of mc_implicit, shape (N_MC_WORK_ROWS, 4): rows 0-3 the vectors sB, s, q, ds, rows 4-23 five
# (4, 4) matrices, rows 24-29 the six gradient vectors of mc_return_principal -- each taken by slicing rows,
# not by reshaping a flat buffer: a numba reshape calls a C helper (~18 ns), and a plastic point made three
# of them
N_MC_WORK_ROWS = 30


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
    sB0 = pick3(o0, pa, pb, t3)
    sB1 = pick3(o1, pa, pb, t3)
    sB2 = pick3(o2, pa, pb, t3)
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
    hist_new[0] = hist_old[0] + plastic_strain_norm(lam, mu, ds)
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
