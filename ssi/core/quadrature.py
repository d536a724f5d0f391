"""Integration rules used by the elements.

Every rule returns ``(points, weights)`` as float64 arrays on the reference interval [-1, 1]
(or, for the layer rule, the physical thickness coordinate).

* Gauss--Legendre with n points integrates polynomials of degree 2n-1 exactly.
* Newton--Cotes on the element nodes (trapezoid for 2, Simpson for 3 points) integrates degree 1 and 3
  exactly; sampling at the nodes is what makes the interface stiffness node-to-node (paper §6, §10).
* The layer rule splits a thickness into layers and samples each at its mid-depth; with the
  z_n**2 + h_n**2/12 correction of eq. (4.7b) it is exact for the quadratic bending integrand.
"""

import numpy as np

__all__ = ["gauss_legendre", "newton_cotes", "gauss_2d", "layer_rule"]


def gauss_legendre(n_points: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss--Legendre points and weights on [-1, 1], exact to degree 2n-1 (n = 1..5)."""
    if not 1 <= n_points <= 5:
        raise ValueError(f"n_points must be in 1..5, got {n_points}")
    points, weights = np.polynomial.legendre.leggauss(n_points)
    return points.astype(np.float64), weights.astype(np.float64)


def newton_cotes(n_points: int) -> tuple[np.ndarray, np.ndarray]:
    """Closed Newton--Cotes rule sampling the nodes of a 2- or 3-node line on [-1, 1].

    Trapezoid (weights 1, 1) for 2 points, Simpson (1/3, 4/3, 1/3) for 3 points.
    """
    if n_points == 2:
        return np.array([-1.0, 1.0]), np.array([1.0, 1.0])
    if n_points == 3:
        return np.array([-1.0, 0.0, 1.0]), np.array([1.0, 4.0, 1.0]) / 3.0
    raise ValueError(f"n_points must be 2 or 3 for Newton-Cotes, got {n_points}")


def gauss_2d(n_points: int) -> tuple[np.ndarray, np.ndarray]:
    """Tensor-product Gauss rule on [-1, 1]^2: points (n*n, 2) with xi varying slowest, weights (n*n,)."""
    p, w = gauss_legendre(n_points)
    xi, eta = np.meshgrid(p, p, indexing="ij")
    wx, wy = np.meshgrid(w, w, indexing="ij")
    return np.column_stack([xi.ravel(), eta.ravel()]), (wx * wy).ravel()


def layer_rule(thicknesses, z_bottom: float) -> tuple[np.ndarray, np.ndarray]:
    """Mid-depths ``z_n`` and thicknesses ``h_n`` of layers stacked upwards from ``z_bottom``.

    Returns ``(z_mid, h)``; sum(h * f(z_mid)) is the rectangular (midpoint) rule of a thickness
    integral, and sum(h * (z_mid**2 + h**2 / 12)) is exactly the integral of z**2.
    """
    h = np.asarray(thicknesses, dtype=np.float64)
    if h.ndim != 1 or h.size == 0 or np.any(h <= 0.0):
        raise ValueError("thicknesses must be a non-empty list of positive layer thicknesses")
    tops = z_bottom + np.cumsum(h)
    return tops - 0.5 * h, h
