"""The explicit Mohr–Coulomb scheme: the paper's tangent scheme Δσ = D_ep(σ) Δε (forward Euler).

:func:`mc_explicit` splits off the elastic part of the increment at the yield surface, integrates the rest
with the continuum matrix D_ep (eq. 6.9, multi-surface form, :func:`continuum_dep`) in optional sub-steps,
and optionally corrects the drift back onto the surface (:func:`mc_drift_correct`). Vectors, history and
parameters: see :mod:`.mc_surface`.
"""

import math

import numpy as np
from numba import njit

from ..core.protocol import K0_MATRIX
from .mc_surface import (
    B_APEX,
    B_EDGE12,
    B_ELASTIC,
    B_PLANE,
    ST_ELASTIC,
    ST_PLASTIC,
    mc_constants,
    mc_return_principal,
    mc_yield_k,
    surface_vectors,
)
from .principal import (
    elastic_fill,
    elastic_increment,
    lame,
    plastic_strain_norm,
    sorted_principal,
    stress_on_axes,
)

__all__ = ["continuum_dep", "mc_drift_correct", "mc_explicit"]


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
def continuum_dep(sig, lam, mu, k, m, kc, apex, deps, Dep, use_deps):
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
            if mc_yield_k(st, k, kc) <= 0.0:
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
        surface_vectors(pl, k, m, a3, b3)
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
    elastic_increment(sig_old, lam, mu, deps, 1.0, st)
    f1 = mc_yield_k(st, k, kc)
    scale = abs(st[0]) + abs(st[1]) + abs(st[3]) + abs(st[2]) + kc + 1e-300
    hist_new[0] = hist_old[0]
    if f1 <= 1e-12 * scale:
        for i in range(4):
            sig_new[i] = st[i]
        hist_new[1] = B_ELASTIC
        elastic_fill(lam, mu, D)
        return ST_ELASTIC
    f0 = mc_yield_k(sig_old, k, kc)
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
            elastic_increment(sig_old, lam, mu, deps, a_, st)
            fa = mc_yield_k(st, k, kc)
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
    elastic_increment(sig_old, lam, mu, deps, alpha, sig)
    dsub = np.empty(4)
    for i in range(4):
        dsub[i] = (1.0 - alpha) * deps[i] / n_sub
    Dep = np.empty((4, 4))
    ep = 0.0
    branch = B_PLANE
    for _ in range(n_sub):
        nact = continuum_dep(sig, lam, mu, k, m, kc, apex, dsub, Dep, True)
        dsig = np.zeros(4)
        for i in range(4):
            v = 0.0
            for j in range(4):
                v += Dep[i, j] * dsub[j]
            dsig[i] = v
        # plastic strain increment D^{-1}(D Δε - Δσ) measured through the elastic part
        if nact > 0:
            de = np.empty(4)
            elastic_increment(np.zeros(4), lam, mu, dsub, 1.0, de)
            dd = np.empty(3)
            dd[0] = de[0] - dsig[0]
            dd[1] = de[1] - dsig[1]
            dd[2] = de[3] - dsig[3]
            en = plastic_strain_norm(lam, mu, dd)
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
        continuum_dep(sig, lam, mu, k, m, kc, apex, dsub, D, True)
    return ST_PLASTIC
