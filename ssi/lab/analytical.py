"""Closed-form reference solutions used by the verification chapters (a plain module of functions).

Every function here is an *independent* reference: it uses no element, law or solver of ``ssi``. Sources are
in ``reference-data`` of the project notes and in each docstring. Units: SI (m, N per unit width, Pa).

* :func:`sadowsky_pressure` -- rigid flat smooth punch on an elastic half-plane (Fig. 10).
* :func:`hetenyi_deflection`, :func:`hetenyi_moment` -- infinite beam on a Winkler bed under a point load.
* :func:`shear_lag_state`, :func:`shear_lag_from_slip`, :func:`shear_lag_slip_length`,
  :func:`shear_lag_displacement` -- an elastic bar pushed along a rigid plate through an elastic--perfectly
  plastic interface (the exact check behind Fig. 13).
* :func:`timoshenko_simply_supported_uniform`, :func:`timoshenko_simply_supported_point`,
  :func:`timoshenko_cantilever` -- shear-flexible beams (the plate strip's checks, chapter 02).
"""

import math

import numpy as np
from scipy.optimize import brentq

from ..core.validate import check_array, check_real

__all__ = [
    "hetenyi_deflection",
    "hetenyi_moment",
    "sadowsky_pressure",
    "shear_lag_displacement",
    "shear_lag_from_slip",
    "shear_lag_onset",
    "shear_lag_slip_length",
    "shear_lag_state",
    "timoshenko_cantilever",
    "timoshenko_simply_supported_point",
    "timoshenko_simply_supported_uniform",
]


# ---- Sadowsky ----------------------------------------------------------------------------------------------
def sadowsky_pressure(x, a, P):
    """Contact pressure p(x) = P / (pi sqrt(a^2 - x^2)) (compression positive) under a rigid smooth punch of
    half-width ``a`` pressed by ``P`` per unit length into an elastic half-plane; nan for |x| >= a."""
    x = check_array("x", x)
    check_real("a", a, lo=0.0, lo_open=True, unit="m")
    check_real("P", P, unit="N/m")
    with np.errstate(invalid="ignore", divide="ignore"):
        p = P / (math.pi * np.sqrt(a * a - x * x))
    return np.where(np.abs(x) < a, p, np.nan)


# ---- Hetenyi -----------------------------------------------------------------------------------------------
def _hetenyi_lambda(k, EI, P, x):
    check_real("k", k, lo=0.0, lo_open=True, unit="N/m^2")
    check_real("EI", EI, lo=0.0, lo_open=True, unit="N m^2")
    check_real("P", P, unit="N")
    check_array("x", x)
    return (k / (4.0 * EI)) ** 0.25


def hetenyi_deflection(x, P, k, EI):
    """Settlement (downward positive) of an infinite Euler--Bernoulli beam on a Winkler bed of modulus ``k``
    [N/m per m of beam] under a point load ``P`` at x = 0:
    w(x) = P lam / (2k) exp(-lam|x|) (cos lam x + sin lam|x|), lam = (k / 4EI)^(1/4) (Hetenyi 1946)."""
    lam = _hetenyi_lambda(k, EI, P, x)
    r = lam * np.abs(np.asarray(x, dtype=np.float64))
    return P * lam / (2.0 * k) * np.exp(-r) * (np.cos(r) + np.sin(r))


def hetenyi_moment(x, P, k, EI):
    """Bending moment (sagging positive) M(x) = P/(4 lam) exp(-lam|x|) (cos lam x - sin lam|x|)."""
    lam = _hetenyi_lambda(k, EI, P, x)
    r = lam * np.abs(np.asarray(x, dtype=np.float64))
    return P / (4.0 * lam) * np.exp(-r) * (np.cos(r) - np.sin(r))


# ---- shear lag with slip -----------------------------------------------------------------------------------
# A bar of axial stiffness EA (per unit width) lies on a rigid plate over 0 <= x <= L, is pushed by F at x = 0
# and is free at x = L. The interface carries tau = kt u up to |tau| = tau_f. Equilibrium EA u'' = tau(u).
# Elastic zone: u = A cosh(lam (L - x)), lam = sqrt(kt / EA). Slip zone 0 <= x <= s: tau = tau_f, so the axial
# force falls linearly, N(x) = F - tau_f x, and u(s) = tau_f / kt marks the slip front.
def _check_bar(EA, kt, L, tau_f):
    for name, value in (("EA", EA), ("kt", kt), ("L", L), ("tau_f", tau_f)):
        check_real(name, value, lo=0.0, lo_open=True)
    return math.sqrt(kt / EA)


def shear_lag_onset(EA, kt, L, tau_f):
    """Mean shear stress tau_bar = F/L at which the loaded edge starts to slip:
    tau_f / (L lam coth(lam L))."""
    lam = _check_bar(EA, kt, L, tau_f)
    return tau_f * math.tanh(lam * L) / (L * lam)


def shear_lag_from_slip(s, EA, kt, L, tau_f):
    """Mean shear stress ``tau_bar`` and edge displacement ``u0`` at which the slip zone has length ``s``
    (0 <= s <= L); explicit, so it also serves to invert the other functions.

    F = tau_f s + tau_f tanh(lam (L - s)) / lam,   u0 = tau_f / kt + (F s - tau_f s^2 / 2) / EA."""
    lam = _check_bar(EA, kt, L, tau_f)
    s = check_array("s", s, lo=0.0, hi=L)
    F = tau_f * s + tau_f * np.tanh(lam * (L - s)) / lam
    u0 = tau_f / kt + (F * s - 0.5 * tau_f * s * s) / EA
    return F / L, u0


def shear_lag_slip_length(tau_bar, EA, kt, L, tau_f):
    """Slip length s(tau_bar): 0 below the onset, the root of (F - tau_f s) lam coth(lam (L - s)) = tau_f
    above it, L at tau_bar = tau_f (full sliding). Raises ValueError for tau_bar > tau_f."""
    _check_bar(EA, kt, L, tau_f)
    tb = np.atleast_1d(check_array("tau_bar", tau_bar, lo=0.0, hi=tau_f * (1 + 1e-12)))
    onset = shear_lag_onset(EA, kt, L, tau_f)
    out = np.zeros_like(tb)
    for i, t in enumerate(tb):
        if t <= onset:
            out[i] = 0.0
        elif t >= tau_f:
            out[i] = L
        else:
            out[i] = brentq(
                lambda s, t=t: shear_lag_from_slip(s, EA, kt, L, tau_f)[0] - t,
                0.0,
                L,
                xtol=1e-14 * L,
                rtol=1e-14,
            )
    return out if np.ndim(tau_bar) else float(out[0])


def shear_lag_displacement(x, tau_bar, EA, kt, L, tau_f):
    """Bar displacement u(x) at mean shear stress ``tau_bar`` (elastic and partial-slip regimes)."""
    lam = _check_bar(EA, kt, L, tau_f)
    x = check_array("x", x)
    tau_bar = check_real("tau_bar", tau_bar, lo=0.0, hi=tau_f, unit="Pa (a scalar here)")
    F = tau_bar * L
    s = shear_lag_slip_length(tau_bar, EA, kt, L, tau_f)
    if s >= L:
        raise ValueError("tau_bar = tau_f: the whole bar slides, the displacement is not determined")
    N_s = F - tau_f * s  # axial force at the slip front
    u_el = N_s * np.cosh(lam * (L - x)) / (EA * lam * np.sinh(lam * (L - s)))
    u_sl = tau_f / kt + (F * (s - x) - 0.5 * tau_f * (s * s - x * x)) / EA
    return np.where(x < s, u_sl, u_el)


def _is_positive_number(v) -> bool:
    return isinstance(v, int | float | np.floating | np.integer) and v > 0


def shear_lag_state(tau_bar, EA, kt, L, tau_f):
    """Dict with the slip length ``s``, edge displacement ``u0`` and edge shear stress ``tau0`` at
    ``tau_bar``."""
    check_real("tau_bar", tau_bar, lo=0.0, hi=tau_f if _is_positive_number(tau_f) else None, unit="Pa")
    s = shear_lag_slip_length(tau_bar, EA, kt, L, tau_f)
    u0 = float(shear_lag_displacement(0.0, tau_bar, EA, kt, L, tau_f)) if s < L else math.inf
    return {"s": s, "u0": u0, "tau0": min(kt * u0, tau_f)}


# ---- Timoshenko beams ------------------------------------------------------------------------------------
# Shear-flexible (Timoshenko) beams: bending stiffness EI and shear stiffness kGA per unit width [N m^2/m,
# N/m]; w positive up, so a downward load is negative. Each deflection is the Euler-Bernoulli one plus the
# shear part w_s'' = -q / kGA (closed forms, e.g. Timoshenko & Gere, *Mechanics of Materials*).
def timoshenko_simply_supported_uniform(x, span, q, EI, kGA):
    """Deflection w(x) [m] of a simply supported beam of ``span`` under a uniform load ``q`` [N/m/m]."""
    x = np.asarray(x, dtype=np.float64)
    return q * x * (span**3 - 2 * span * x**2 + x**3) / (24 * EI) + q * x * (span - x) / (2 * kGA)


def timoshenko_simply_supported_point(span, P, EI, kGA):
    """Mid-span deflection [m] of a simply supported beam of ``span`` under a point load ``P`` at mid-span."""
    return P * span**3 / (48 * EI) + P * span / (4 * kGA)


def timoshenko_cantilever(x, span, P, EI, kGA):
    """Deflection w(x) [m] of a cantilever (clamped at x = 0) of ``span`` under a tip load ``P``."""
    x = np.asarray(x, dtype=np.float64)
    return P * x**2 * (3 * span - x) / (6 * EI) + P * x / kGA
