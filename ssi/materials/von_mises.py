"""The von Mises law (plane strain, perfect plasticity): radial return with its consistent tangent, for the
Smith & Griffiths regression (their Program 6.1: ``[E, nu, cu, ...]`` with ``sqrt(J2) = cu``). Vectors and
history as the Mohr–Coulomb schemes (:mod:`.mc_surface`), whose branch and status codes it uses.
"""

import math

from numba import njit

from ..core.protocol import K0_MATRIX
from .mc_surface import B_ELASTIC, B_PLANE, ST_ELASTIC, ST_PLASTIC
from .principal import elastic_fill, elastic_increment, lame

__all__ = ["vm_implicit"]


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
    elastic_increment(sig_old, lam, mu, deps, 1.0, st)
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
