"""Reinforcing steel at one layer point (paper §5.4; paper-notes §3.6).

Bilinear uniaxial elasto-plasticity: modulus Es up to the yield stress fy, hardening modulus EH after,
unloading (and reloading) with slope Es. The bilinear curve is produced by linear *kinematic* hardening
with plastic modulus H = Es EH / (Es - EH) (so that the elasto-plastic tangent Es H / (Es + H) = EH);
on a load reversal the elastic range keeps its width 2 fy (Bauschinger-like, Prager). Steel layers
resist only the axial force in the bar direction: tau = 0 and d tau/d gam = 0.

Parameter vector: [Es, nu (unused, 0), fy, EH]  (indices ``S_*``).
History: [eps_p] (plastic strain; the back stress is H eps_p).

Return mapping (one call, from the committed eps_p):
1. trial stress s_tr = Es (eps - eps_p), relative stress xi = s_tr - H eps_p;
2. f = |xi| - fy <= 0: elastic, tangent Es;
3. else dg = f / (Es + H), eps_p += dg sign(xi), sig = s_tr - Es dg sign(xi), tangent EH.
"""

from numba import njit

from ..core.protocol import K0_MATRIX

S_ES, S_NU, S_FY, S_EH = range(4)
N_STEEL_PARAMS = 4
N_STEEL_HIST = 1
H_EPS_P = 0  # the history slot steel_update writes: the plastic strain eps_p [-]


@njit(cache=True)
def steel_update(params, eps, gam, hist_old, hist_new, tangent):
    """One steel layer point: return ``(sig, tau, e_t, g_t)`` and write ``hist_new[0]`` (eps_p).

    ``tangent`` = 0 returns the initial modulus Es (K0). Shapes: params (>= 4,), hist (>= 1,).
    """
    Es = params[S_ES]
    fy = params[S_FY]
    EH = params[S_EH]
    H = Es * EH / (Es - EH)
    eps_p = hist_old[0]
    s_tr = Es * (eps - eps_p)
    xi = s_tr - H * eps_p
    f = abs(xi) - fy
    if f <= 0.0:
        hist_new[0] = eps_p
        return s_tr, 0.0, Es, 0.0
    sgn = 1.0 if xi > 0.0 else -1.0
    dg = f / (Es + H)
    hist_new[0] = eps_p + dg * sgn
    sig = s_tr - Es * dg * sgn
    if tangent == K0_MATRIX:
        return sig, 0.0, Es, 0.0
    return sig, 0.0, EH, 0.0
