"""Closed-form elastic solutions for the soil element's verification (computed here, never stored).

Uniform strip load on an elastic half-plane (Boussinesq/Flamant integrated over the strip; e.g. Poulos &
Davis, *Elastic Solutions for Soil and Rock Mechanics*, 1974, §3.3). A pressure q acts downwards on the
surface z = 0 over -b <= x <= b. For a point at depth d = -z > 0 let theta_1 and theta_2 be the angles,
measured from the downward vertical, of the lines from the point to the left (x = -b) and right (x = +b)
edges, theta_i = atan2(x - x_i, d). With alpha = theta_1 - theta_2 (the angle the strip subtends at the point)
and delta = theta_2, the textbook form (compression positive) is

    sig_z = (q/pi) [alpha + sin(alpha) cos(alpha + 2 delta)]
    sig_x = (q/pi) [alpha - sin(alpha) cos(alpha + 2 delta)]
    tau   = (q/pi) sin(alpha) sin(alpha + 2 delta)

This module returns the project's convention (tension positive, z up): sxx = -sig_x, szz = -sig_z, and
txz = +(q/pi) sin(alpha) sin(alpha + 2 delta), the sign that integrating Flamant's radial line-load field over
the strip gives with z up (``tests/test_soil_q8.py`` checks all three against that quadrature). Plane strain
adds syy = nu (sxx + szz).
"""

import numpy as np
from scipy.integrate import quad

__all__ = [
    "flamant_strip_quadrature",
    "lame_cylinder_displacement",
    "strip_centreline_compression",
    "strip_load_stresses",
]


def _check(q, b):
    if not b > 0.0:
        raise ValueError(f"half-width b must be positive [m], got b={b}")
    if not np.isfinite(q):
        raise ValueError(f"pressure q must be finite [Pa], got q={q}")


def strip_load_stresses(x, z, q, b, nu=None):
    """Stresses (tension positive, z up) under a uniform strip pressure ``q`` on -b <= x <= b of a half-plane.

    Parameters
    ----------
    x, z : array-like, same shape; points with z < 0 (below the surface)
    q : pressure [Pa], positive downwards (compressive)
    b : half-width of the strip [m]
    nu : Poisson's ratio; if given, ``syy = nu (sxx + szz)`` is returned as the fourth array

    Returns
    -------
    (sxx, szz, txz) or (sxx, szz, txz, syy), arrays of the shape of ``x``
    """
    _check(q, b)
    x = np.asarray(x, dtype=np.float64)
    d = -np.asarray(z, dtype=np.float64)
    if np.any(d <= 0.0):
        raise ValueError("z must be negative (points below the loaded surface z = 0)")
    th1 = np.arctan2(x + b, d)
    th2 = np.arctan2(x - b, d)
    alpha = th1 - th2
    s = np.sin(alpha)
    c2 = np.cos(alpha + 2.0 * th2)
    s2 = np.sin(alpha + 2.0 * th2)
    sxx = -(q / np.pi) * (alpha - s * c2)
    szz = -(q / np.pi) * (alpha + s * c2)
    txz = (q / np.pi) * s * s2
    if nu is None:
        return sxx, szz, txz
    return sxx, szz, txz, nu * (sxx + szz)


def flamant_strip_quadrature(x, z, q, b, n=4000):
    """The same stresses by integrating Flamant's line-load solution over the strip (midpoint rule, ``n``
    panels) -- an independent check of :func:`strip_load_stresses`. Flamant: a line load P (downwards) at x =
    s gives a purely radial stress sig_rr = -2 P cos(theta) / (pi r) along e_r = (x - s, z) / r."""
    s = -b + (np.arange(n) + 0.5) * (2.0 * b / n)
    dx = x - s
    r2 = dx * dx + z * z
    d = -z
    # sig = sig_rr e_r e_r with sig_rr = -2 (q ds) d / (pi r^2), e_r = (dx, z)/r
    fac = -2.0 * q * (2.0 * b / n) * d / (np.pi * r2 * r2)
    return float(np.sum(fac * dx * dx)), float(np.sum(fac * z * z)), float(np.sum(fac * dx * z))


def strip_centreline_compression(depth, q, b, E, nu):
    """w(0, 0) - w(0, -depth) under the strip centre (negative = shortening) in plane strain:
    the integral of eps_zz = [(1 - nu^2) szz - nu (1 + nu) sxx] / E along x = 0 (adaptive quadrature)."""
    _check(q, b)

    def eps_zz(zz):
        sxx, szz, _ = strip_load_stresses(0.0, zz, q, b)
        return ((1.0 - nu * nu) * szz - nu * (1.0 + nu) * sxx) / E

    val, _ = quad(eps_zz, -depth, -1e-300 * depth, epsabs=0.0, epsrel=1e-12, limit=200)
    return val


def lame_cylinder_displacement(r, a, b, p, E, nu):
    """Radial displacement of a thick-walled cylinder (inner radius a, outer b, internal pressure p) in plane
    strain (Lamé): u_r = (1 + nu) p a^2 / (E (b^2 - a^2)) [(1 - 2 nu) r + b^2 / r]. It stays finite as
    nu -> 0.5, which makes it the standard probe of volumetric locking."""
    if not 0.0 < a < b:
        raise ValueError(f"radii must satisfy 0 < a < b, got a={a}, b={b}")
    r = np.asarray(r, dtype=np.float64)
    return (1.0 + nu) * p * a * a / (E * (b * b - a * a)) * ((1.0 - 2.0 * nu) * r + b * b / r)
