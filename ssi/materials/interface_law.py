"""Coulomb friction with separation at one point of a zero-thickness interface (paper §6.2, eqs. 6.2,
6.7-6.10).

The "strain" of an interface point is its gap, the relative displacement of the upper body with respect to the
lower one in the local frame, ``gap = [g_t, g_n]`` (tangential, normal; g_n > 0 opens the contact). The
"stress" is the traction ``t = [tau, sig_n]`` (sig_n > 0 tension, < 0 compression), and ``D`` is (2, 2) in
that order.

The update (one call per integration point and iteration), in numbered steps
-----------------------------------------------------------------------------
1. **Open point** (``hist[STATUS] == OPEN``): the stored ``open_gap`` g_o > 0 is the normal gap beyond the
   stress-free closure position. g_o + dg_n > 0 keeps the point open: t = 0, D = 0. Otherwise the contact
   re-closes during the step; the step is taken as a straight line in gap space, so only the closed fraction
   ``r = (g_o + dg_n)/dg_n`` of the tangential increment loads the spring:
   trial t_tr = [kt * r * dg_t, kn * (g_o + dg_n)]; continue with step 3.
2. **Closed point**: elastic predictor, eq. (6.2) in rate form: t_tr = t_old + De * dgap, De = diag(kt, kn).
   If sig_n,tr > sig_t (tension cut-off) the contact opens: t = 0, g_o = sig_n,tr / kn, D = 0, and the point
   loses its cohesion and tensile strength for good (``broken`` = 1): a debonded contact has no glue left --
   unless the dilatant slip return of step 4 lands on the closed side of the cut-off (sig_n <= sig_t): the
   corner of the Coulomb line and the cut-off is then split along the return direction De m, which keeps
   the traction a continuous function of the gap for c = 0 (no jump slip -> open at the apex).
3. **Coulomb check**, eq. (6.7): f_tr = |tau_tr| + sig_n,tr * tan(phi) - c. f_tr <= 0: stick, t = t_tr.
4. **Slip**: plastic potential g = |tau| + sig_n * tan(psi) (psi = phi is the paper's associated rule, psi = 0
   a slip without dilation). With m = dg/dt = [s, tan(psi)], n = df/dt = [s, tan(phi)], s = sign(tau_tr):
   dlam = f_tr / H, H = n . De m = kt + kn tan(phi) tan(psi), t = t_tr - dlam De m.
   The Coulomb line is straight, so this closest-point return is exact and its consistent tangent is the
   continuum matrix of eq. (6.9): D = De - De m n^T De / H; with psi = phi it is eq. (6.10),
   kt kn / (kt + kn tan^2 phi) [[tan^2 phi, -s tan phi], [-s tan phi, 1]]. Dilation (psi > 0) pushes
   sig_n further into compression, so the return never crosses the apex sig_n = c / tan(phi).
   When the trial came from a re-closing step (1), the tangent is chained with d t_tr / d dgap.

``tangent == K0_MATRIX`` (:mod:`ssi.core.protocol`) returns D = De in every state: the K0 of modified
Newton-Raphson (paper §8).

Parameter vector ``params`` (build it with :func:`interface_params`), indices ``P_*``:
[kt, kn, c, tan_phi, tan_psi, sig_t].
History vector ``hist`` (N_HIST,), indices ``H_*``:
[status, g_t, g_n, slip_t, slip_n, open_gap, broken]: the state code (STICK/SLIP/OPEN), the total gaps, the
accumulated plastic (Coulomb) gaps, the open gap beyond closure and the debonded flag.
"""

import math

import numpy as np
from numba import njit

from ..core.protocol import K0_MATRIX
from .soil_laws import davis_beta

__all__ = [
    "N_HIST",
    "N_PARAMS",
    "OPEN",
    "SLIP",
    "STICK",
    "drive_point",
    "interface_params",
    "interface_update",
]

STICK = 0
SLIP = 1
OPEN = 2
STATE_NAMES = {STICK: "stick", SLIP: "slip", OPEN: "open"}

P_KT, P_KN, P_C, P_TANPHI, P_TANPSI, P_SIGT = range(6)
N_PARAMS = 6
H_STATUS, H_GT, H_GN, H_SLIPT, H_SLIPN, H_OPEN, H_BROKEN = range(7)
N_HIST = 7


def interface_params(
    kt: float, kn: float, phi_deg: float = 0.0, c: float = 0.0, psi_deg=None, sig_t=None
) -> np.ndarray:
    """Validated parameter vector of the interface law.

    Parameters
    ----------
    kt, kn : float
        Tangential and normal stiffness [Pa/m] of eq. (6.2); kt >= 0, kn > 0.
    phi_deg : float
        Interface friction angle phi [deg], 0 <= phi < 90.
    c : float
        Cohesion (adhesion) [Pa], c >= 0. ``c = inf`` makes the interface purely elastic (never slips).
    psi_deg : float or None
        Dilation angle psi [deg], 0 <= psi <= phi; None means psi = phi (the paper's associated rule).
    sig_t : float or None
        Tension cut-off [Pa], 0 <= sig_t <= c / tan(phi) (the Coulomb apex); None means the apex:
        c / tan(phi); 0 for a cohesionless contact (c = 0); ``inf`` for phi = 0 with c > 0 (a glued Tresca
        contact that never opens unless sig_t is given).

    Returns
    -------
    numpy.ndarray, shape (N_PARAMS,)
        [kt, kn, c, tan_phi, tan_psi, sig_t].
    """
    kt, kn, phi_deg, c = float(kt), float(kn), float(phi_deg), float(c)
    if not (kt >= 0.0 and math.isfinite(kt)):
        raise ValueError(f"kt must be finite and >= 0 [Pa/m], got {kt}")
    if not (kn > 0.0 and math.isfinite(kn)):
        raise ValueError(f"kn must be finite and > 0 [Pa/m], got {kn}")
    if not 0.0 <= phi_deg < 90.0:
        raise ValueError(f"phi_deg must be in [0, 90), got {phi_deg}")
    if not c >= 0.0:
        raise ValueError(f"c must be >= 0 [Pa] (inf for a never-slipping contact), got {c}")
    psi_deg = phi_deg if psi_deg is None else float(psi_deg)
    if not 0.0 <= psi_deg <= phi_deg:
        raise ValueError(f"psi_deg must be in [0, phi_deg] = [0, {phi_deg}], got {psi_deg}")
    tan_phi = math.tan(math.radians(phi_deg))
    tan_psi = math.tan(math.radians(psi_deg))
    apex = c / tan_phi if tan_phi > 0.0 else math.inf
    if sig_t is None:
        sig_t = 0.0 if c == 0.0 else apex
    sig_t = float(sig_t)
    if not 0.0 <= sig_t <= apex * (1.0 + 1e-12):
        raise ValueError(f"sig_t must be in [0, c/tan(phi)] = [0, {apex}] [Pa], got {sig_t}")
    return np.array([kt, kn, c, tan_phi, tan_psi, min(sig_t, apex)], dtype=np.float64)


@njit(cache=True)
def interface_update(params, dgap, t_old, hist_old, t_new, hist_new, D, tangent):
    """Traction update of one interface point for the gap increment ``dgap``; returns the state code.

    Shapes: params (N_PARAMS,), dgap (2,), t_old (2,), hist_old (N_HIST,) in; t_new (2,), hist_new (N_HIST,),
    D (2, 2) out. ``tangent`` 0: D = De (K0), 1: consistent tangent. Steps 1-4 of the module docstring.
    """
    kt = params[0]
    kn = params[1]
    broken = hist_old[H_BROKEN]
    c = params[2]
    sig_t = params[5]
    if broken > 0.5:
        c = 0.0
        sig_t = 0.0
    tan_phi = params[3]
    tan_psi = params[4]
    for i in range(N_HIST):
        hist_new[i] = hist_old[i]
    hist_new[H_GT] = hist_old[H_GT] + dgap[0]
    hist_new[H_GN] = hist_old[H_GN] + dgap[1]
    # J = d t_tr / d dgap (De unless the point re-closes within the step)
    j00 = kt
    j01 = 0.0
    j10 = 0.0
    j11 = kn
    if hist_old[H_STATUS] == OPEN:
        # step 1: open point
        g_o = hist_old[H_OPEN] + dgap[1]
        if g_o > 0.0:
            t_new[0] = 0.0
            t_new[1] = 0.0
            hist_new[H_OPEN] = g_o
            hist_new[H_STATUS] = OPEN
            _set_tangent(D, tangent, kt, kn, 0.0, 0.0, 0.0, 0.0)
            return OPEN
        # re-closes: only the closed fraction r of the straight path loads the springs
        r = g_o / dgap[1]
        tau_tr = kt * r * dgap[0]
        sig_tr = kn * g_o
        j00 = kt * r
        j01 = -kt * dgap[0] * hist_old[H_OPEN] / (dgap[1] * dgap[1])
        hist_new[H_OPEN] = 0.0
    else:
        # step 2: elastic predictor, eq. (6.2)
        tau_tr = t_old[0] + kt * dgap[0]
        sig_tr = t_old[1] + kn * dgap[1]
        if sig_tr > sig_t and not _slip_lands_closed(tau_tr, sig_tr, kt, kn, c, tan_phi, tan_psi, sig_t):
            t_new[0] = 0.0
            t_new[1] = 0.0
            hist_new[H_OPEN] = sig_tr / kn
            hist_new[H_BROKEN] = 1.0
            hist_new[H_STATUS] = OPEN
            _set_tangent(D, tangent, kt, kn, 0.0, 0.0, 0.0, 0.0)
            return OPEN
    # step 3: Coulomb condition, eq. (6.7)
    s = 1.0 if tau_tr >= 0.0 else -1.0
    f_tr = abs(tau_tr) + sig_tr * tan_phi - c
    if not f_tr > 0.0:
        t_new[0] = tau_tr
        t_new[1] = sig_tr
        hist_new[H_STATUS] = STICK
        _set_tangent(D, tangent, kt, kn, j00, j01, j10, j11)
        return STICK
    # step 4: return to the Coulomb line along De m, m = [s, tan_psi]
    h = kt + kn * tan_phi * tan_psi
    dlam = f_tr / h
    t_new[0] = tau_tr - dlam * kt * s
    t_new[1] = sig_tr - dlam * kn * tan_psi
    hist_new[H_SLIPT] = hist_old[H_SLIPT] + dlam * s
    hist_new[H_SLIPN] = hist_old[H_SLIPN] + dlam * tan_psi
    hist_new[H_STATUS] = SLIP
    # d t / d t_tr = I - De m n^T / H (eq. 6.9 written for the trial traction), n = [s, tan_phi]
    a00 = 1.0 - kt * s * s / h
    a01 = -kt * s * tan_phi / h
    a10 = -kn * tan_psi * s / h
    a11 = 1.0 - kn * tan_psi * tan_phi / h
    _set_tangent(
        D,
        tangent,
        kt,
        kn,
        a00 * j00 + a01 * j10,
        a00 * j01 + a01 * j11,
        a10 * j00 + a11 * j10,
        a10 * j01 + a11 * j11,
    )
    return SLIP


@njit(cache=True)
def _slip_lands_closed(tau_tr, sig_tr, kt, kn, c, tan_phi, tan_psi, sig_t):
    """True if the Coulomb return of a trial beyond the tension cut-off lands on the closed side of it.

    A dilatant return (psi > 0) moves sig_n by -dlam kn tan(psi), into compression: a trial with large |tau|
    and small tension belongs to the slip line, not to the apex. Without this test the map from the gap
    to the traction jumps at sig_tr = sig_t (slip on one side, open on the other) and Newton cycles
    slip -> open -> stick at such a point; with it, the region that returns to the apex (open, t = 0) is
    bounded by the return direction De m through the corner, as for any closest-point projection."""
    f_tr = abs(tau_tr) + sig_tr * tan_phi - c
    if not f_tr > 0.0 or tan_psi == 0.0:
        return False
    sig_return = sig_tr - f_tr / (kt + kn * tan_phi * tan_psi) * kn * tan_psi
    return sig_return <= sig_t


@njit(cache=True)
def _set_tangent(D, tangent, kt, kn, d00, d01, d10, d11):
    if tangent == K0_MATRIX:
        D[0, 0] = kt
        D[0, 1] = 0.0
        D[1, 0] = 0.0
        D[1, 1] = kn
    else:
        D[0, 0] = d00
        D[0, 1] = d01
        D[1, 0] = d10
        D[1, 1] = d11


def drive_point(params, gap_path, tangent: int = 1):
    """Material-point driver: follow a path of total gaps ``gap_path`` (n, 2) from a virgin point.

    Returns ``(t, status, D, hist)``: tractions (n, 2), state codes (n,), tangents (n, 2, 2), histories
    (n, N_HIST) after each step (each row of the path is one converged step).
    """
    params = np.asarray(params, dtype=np.float64)
    if params.shape != (N_PARAMS,):
        raise ValueError(f"params must have shape ({N_PARAMS},); build it with interface_params()")
    path = np.atleast_2d(np.asarray(gap_path, dtype=np.float64))
    if path.ndim != 2 or path.shape[1] != 2:
        raise ValueError(f"gap_path must have shape (n, 2), got {path.shape}")
    n = len(path)
    t_all = np.zeros((n, 2))
    st = np.zeros(n, np.int64)
    d_all = np.zeros((n, 2, 2))
    h_all = np.zeros((n, N_HIST))
    t_old = np.zeros(2)
    h_old = np.zeros(N_HIST)
    g_old = np.zeros(2)
    for i in range(n):
        st[i] = interface_update(params, path[i] - g_old, t_old, h_old, t_all[i], h_all[i], d_all[i], tangent)
        t_old, h_old, g_old = t_all[i], h_all[i], path[i]
    return t_all, st, d_all, h_all


def davis_interface_row(row: np.ndarray) -> np.ndarray:
    """An interface parameter row [kt, kn, c, tan_phi, tan_psi, sig_t] made associated with Davis' reduced
    c*, tan phi* (tan psi* = tan phi*; the tension cut-off, at most the apex c / tan phi, is unchanged); a new
    array, ``row`` is not touched."""
    out = row.copy()
    beta = davis_beta(math.degrees(math.atan(row[3])), math.degrees(math.atan(row[4])))
    out[2] = beta * row[2]
    out[3] = out[4] = beta * row[3]
    return out
