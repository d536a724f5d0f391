"""Loss of ellipticity of perfectly plastic Mohr–Coulomb flow: is the rate problem of a yielding point
well posed?

A point's rate problem stays elliptic while the acoustic tensor Q(n) = n·D_ep·n of its tangent is
non-singular for every direction n; where det Q(n) <= 0 for some n, a velocity field with a jump across a
band of normal n satisfies the rate equations (Rudnicki & Rice 1975): the continuum's incremental solution
is then neither unique nor, on a finite mesh, sure to exist. For perfect plasticity on Mohr–Coulomb's main
plane (plane strain, the intermediate principal stress out of plane) the continuum tangent is
D_ep = D - (D:g)(f:D) / (f:D:g) with the yield and flow gradients f = k e1e1 - e3e3 and
g = m e1e1 - e3e3 (k, m of φ and ψ; tension positive, e1 the axis of the largest principal stress), so
det Q_ep(n) = det Q_e(n) (1 - (f:D·n)·Q_e(n)⁻¹·(n·D:g) / (f:D:g)) (a rank-one update). With ψ = φ its
minimum over n is exactly zero, at the normal 45° - φ/2 from e1 (Coulomb's band): associated perfect
plasticity sits on the boundary of ellipticity. With ψ < φ it is negative (Vermeer & de Borst 1984 on
non-associated soil): every yielding point of such a soil has already lost ellipticity, for a range of
normals around Arthur's 45° - (φ + ψ)/4 (between Coulomb's and Roscoe's 45° - ψ/2).

This is why a controlled path can stop at the plastic front of a non-associated soil (issue 31: the random
zoo's 12 stopped scenes, all with ψ < φ; their Davis-mode copies, associated, all end): the module's numbers
go into the ``NonConvergence`` diagnosis (:func:`ssi.solver.diagnostics.ill_posed_soil`). Plain Python: it is
evaluated once per material, not per point.
"""

import math

import numpy as np

from .principal import lame

__all__ = ["mc_ellipticity"]

_N_SCAN = 721  # normals scanned over half a turn (0.25 deg apart) before the minimum is refined


def _acoustic_ratio(theta, k, m, lam, mu):
    """det Q_ep(n) / det Q_e(n) for the in-plane normal n = (cos θ, sin θ) in the (e1, e3) frame."""
    n1, n3 = math.cos(theta), math.sin(theta)
    # D:A for A = diag(a1, 0, a3) in principal axes is lam tr(A) I + 2 mu A; here f = diag(k, 0, -1) and
    # g = diag(m, 0, -1)
    df1, df3 = lam * (k - 1.0) + 2.0 * mu * k, lam * (k - 1.0) - 2.0 * mu
    dg1, dg3 = lam * (m - 1.0) + 2.0 * mu * m, lam * (m - 1.0) - 2.0 * mu
    fdg = k * dg1 - dg3  # f:D:g (the out-of-plane entries of f and g are zero)
    u1, u3 = dg1 * n1, dg3 * n3  # n.(D:g)
    v1, v3 = df1 * n1, df3 * n3  # (f:D).n
    # Q_e = mu I + (lam + mu) n n, so Q_e^-1 = (I - (lam + mu) / (lam + 2 mu) n n) / mu
    along_n = (v1 * n1 + v3 * n3) * (u1 * n1 + u3 * n3)
    v_qinv_u = (v1 * u1 + v3 * u3 - (lam + mu) / (lam + 2.0 * mu) * along_n) / mu
    return 1.0 - v_qinv_u / fdg


def mc_ellipticity(phi: float, psi: float, nu: float) -> tuple[float, float]:
    """Smallest det Q_ep(n) / det Q_e(n) over the in-plane normals n of perfectly plastic Mohr–Coulomb flow
    on its main plane (plane strain), and the angle of that normal from the axis of the largest principal
    stress [rad]. ``phi``, ``psi``: friction and dilation angles [rad] (0 <= psi <= phi < pi/2); ``nu``:
    Poisson's ratio (-1 < nu < 0.5). Young's modulus and the stress level cancel. Negative: the point's rate
    problem has lost ellipticity (see the module docstring); zero (to round-off): associated flow."""
    if not 0.0 <= psi <= phi < 0.5 * math.pi:
        raise ValueError(f"mc_ellipticity: need 0 <= psi <= phi < pi/2 rad, got phi={phi!r}, psi={psi!r}")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"mc_ellipticity: nu={nu!r} outside (-1, 0.5)")
    lam, mu = lame(1.0, nu)
    sp, sq = math.sin(phi), math.sin(psi)
    k, m = (1.0 + sp) / (1.0 - sp), (1.0 + sq) / (1.0 - sq)
    thetas = np.linspace(0.0, math.pi, _N_SCAN)
    values = [_acoustic_ratio(t, k, m, lam, mu) for t in thetas]
    best = int(np.argmin(values))
    # golden-section refinement within the neighbouring scan points (the ratio is smooth in theta)
    lo, hi = thetas[max(best - 1, 0)], thetas[min(best + 1, _N_SCAN - 1)]
    golden = 0.5 * (math.sqrt(5.0) - 1.0)
    for _ in range(60):
        a, b = hi - golden * (hi - lo), lo + golden * (hi - lo)
        if _acoustic_ratio(a, k, m, lam, mu) < _acoustic_ratio(b, k, m, lam, mu):
            hi = b
        else:
            lo = a
    theta = 0.5 * (lo + hi)
    return _acoustic_ratio(theta, k, m, lam, mu), theta
