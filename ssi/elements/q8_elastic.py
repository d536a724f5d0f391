"""Fast elastic stiffness K0 of 8-node serendipity plane-strain elements (the assembly hot path).

``SoilQ8.evaluate`` is general: it calls the soil-law dispatch at every integration point, evaluates the
shape functions afresh (two small heap arrays per call) and fills all 256 entries of every element matrix.
K0 -- the matrix modified Newton--Raphson factorises once, and the whole of a linear solve -- needs none of
that: every law's parameter row starts with [E, nu], so K0 depends only on the geometry and those two numbers.
This kernel

* takes the reference derivatives dN/dxi at the Gauss points once (not per element);
* uses the sparsity of B and the structure of the plane-strain D (entries lambda + 2 mu, lambda, mu), so each
  2x2 node block costs 8 multiply-adds;
* computes the upper triangle of node blocks and mirrors it (K0 is symmetric);
* runs over elements with ``prange`` (each element writes only its own slab of ``k_el``: disjoint memory).

It returns exactly the matrices of ``SoilQ8.elastic_stiffness()`` (``tests/test_soil_q8.py`` compares them to
round-off) and writes into a caller-owned buffer, so repeated assemblies reuse memory.

Layout: coords (n_el, 8, 2), E and nu (n_el,), dn_ref (n_ip, 8, 2), weights (n_ip,), k_el (n_el, 16, 16).
"""

import numpy as np
from numba import njit, prange

from ..core.quadrature import gauss_2d
from ..core.shapes import serendipity8

__all__ = ["q8_elastic_assemble", "q8_elastic_stiffness", "reference_derivatives"]


def reference_derivatives(n_gauss):
    """(dn_ref (n_ip, 8, 2), weights (n_ip,)) of the n_gauss x n_gauss Gauss rule."""
    pts, wts = gauss_2d(n_gauss)
    dn = np.empty((len(wts), 8, 2))
    for q, (xi, eta) in enumerate(pts):
        dn[q] = serendipity8(xi, eta)[1]
    return dn, wts


@njit(cache=True)
def _element_k0(coords, e, E, nu, dn_ref, wts, bx, bz, ke):
    """Fill ``ke`` (16, 16) with K0 of element ``e``; bx, bz (8,) are scratch."""
    n_ip = wts.shape[0]
    lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    mu = 0.5 * E / (1.0 + nu)
    l2m = lam + 2.0 * mu
    for i in range(16):
        for j in range(16):
            ke[i, j] = 0.0
    for q in range(n_ip):
        j00 = 0.0
        j01 = 0.0
        j10 = 0.0
        j11 = 0.0
        for a in range(8):
            x = coords[e, a, 0]
            z = coords[e, a, 1]
            j00 += dn_ref[q, a, 0] * x
            j01 += dn_ref[q, a, 0] * z
            j10 += dn_ref[q, a, 1] * x
            j11 += dn_ref[q, a, 1] * z
        det = j00 * j11 - j01 * j10
        inv = 1.0 / det
        for a in range(8):
            bx[a] = (j11 * dn_ref[q, a, 0] - j01 * dn_ref[q, a, 1]) * inv
            bz[a] = (-j10 * dn_ref[q, a, 0] + j00 * dn_ref[q, a, 1]) * inv
        w = wts[q] * det
        for a in range(8):
            ax = bx[a] * w
            az = bz[a] * w
            for b in range(a, 8):
                cx = bx[b]
                cz = bz[b]
                ke[2 * a, 2 * b] += ax * l2m * cx + az * mu * cz
                ke[2 * a, 2 * b + 1] += ax * lam * cz + az * mu * cx
                ke[2 * a + 1, 2 * b] += az * lam * cx + ax * mu * cz
                ke[2 * a + 1, 2 * b + 1] += az * l2m * cz + ax * mu * cx
    for a in range(8):  # mirror the node blocks b < a from the computed upper triangle
        for b in range(a):
            ke[2 * a, 2 * b] = ke[2 * b, 2 * a]
            ke[2 * a, 2 * b + 1] = ke[2 * b + 1, 2 * a]
            ke[2 * a + 1, 2 * b] = ke[2 * b, 2 * a + 1]
            ke[2 * a + 1, 2 * b + 1] = ke[2 * b + 1, 2 * a + 1]


@njit(cache=True, parallel=True)
def _kernel(coords, E, nu, dn_ref, wts, k_el):
    for e in prange(coords.shape[0]):
        bx = np.empty(8)
        bz = np.empty(8)
        _element_k0(coords, e, E[e], nu[e], dn_ref, wts, bx, bz, k_el[e])


@njit(cache=True)
def _assemble_kernel(coords, E, nu, dn_ref, wts, smap, data):
    """Add every element's K0 into the CSR values ``data`` through the scatter map ``smap`` (n_el, 256), one
    element at a time (the same sums in the same order as ``scatter_matrix`` of the stored matrices)."""
    bx = np.empty(8)
    bz = np.empty(8)
    ke = np.empty((16, 16))
    for e in range(coords.shape[0]):
        _element_k0(coords, e, E[e], nu[e], dn_ref, wts, bx, bz, ke)
        for a in range(16):
            for b in range(16):
                p = smap[e, a * 16 + b]
                if p >= 0:
                    data[p] += ke[a, b]


def _checked(coords, E, nu, n_gauss):
    """(coords, E, nu) as contiguous float64 arrays, E and nu one per element; ValueError on bad input."""
    coords = np.ascontiguousarray(coords, np.float64)
    n_el = coords.shape[0]
    if coords.shape != (n_el, 8, 2):
        raise ValueError(f"coords must have shape (n_el, 8, 2), got {coords.shape}")
    if n_gauss not in (2, 3):
        raise ValueError(f"n_gauss must be 2 (reduced) or 3 (full), got {n_gauss}")
    E = np.ascontiguousarray(np.broadcast_to(np.asarray(E, np.float64), (n_el,)))
    nu = np.ascontiguousarray(np.broadcast_to(np.asarray(nu, np.float64), (n_el,)))
    if np.any(~(E > 0.0)):
        raise ValueError("E must be > 0 (Young's modulus, Pa)")
    if np.any(~((nu > -1.0) & (nu < 0.5))):
        raise ValueError("nu must lie in (-1, 0.5) (Poisson's ratio)")
    return coords, E, nu


def q8_elastic_assemble(coords, E, nu, n_gauss, smap, data):
    """Add the elastic stiffness of Q8 elements into CSR values ``data`` through their scatter map ``smap``
    (n_el, 256) without storing the element matrices (2 kB per element: 343 MB of fresh memory at 1e6 DOFs,
    whose first touch cost more than computing them). Arguments as :func:`q8_elastic_stiffness`."""
    coords, E, nu = _checked(coords, E, nu, n_gauss)
    if smap.shape != (coords.shape[0], 256):
        raise ValueError(f"smap must have shape ({coords.shape[0]}, 256), got {smap.shape}")
    dn_ref, wts = reference_derivatives(n_gauss)
    _assemble_kernel(coords, E, nu, dn_ref, wts, smap, data)
    return data


def q8_elastic_stiffness(coords, E, nu, n_gauss=2, out=None):
    """Elastic stiffness matrices (n_el, 16, 16) of Q8 plane-strain elements.

    Parameters
    ----------
    coords : (n_el, 8, 2) nodal coordinates (node order of ``ssi.core.shapes.serendipity8``)
    E, nu : scalars or (n_el,) Young's modulus [Pa] and Poisson's ratio of each element
    n_gauss : 2 (reduced, the paper's) or 3 (full)
    out : optional (n_el, 16, 16) float64 C-contiguous buffer to fill (reused between calls)
    """
    coords, E, nu = _checked(coords, E, nu, n_gauss)
    n_el = coords.shape[0]
    if out is None:
        out = np.empty((n_el, 16, 16))
    elif out.shape != (n_el, 16, 16) or out.dtype != np.float64 or not out.flags.c_contiguous:
        raise ValueError(f"out must be a C-contiguous float64 array of shape ({n_el}, 16, 16)")
    dn_ref, wts = reference_derivatives(n_gauss)
    _kernel(coords, E, nu, dn_ref, wts, out)
    return out
