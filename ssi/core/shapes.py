"""Shape functions on reference coordinates, as numba kernels.

* ``lagrange3(xi)``: 1-D quadratic Lagrange on nodes xi = -1, 0, +1 (plate strip, interface).
* ``serendipity8(xi, eta)``: the 8-node serendipity quad (soil). Node order: corners
  counter-clockwise from (-1,-1), then mid-sides from the bottom edge counter-clockwise:
  (-1,-1) (1,-1) (1,1) (-1,1) (0,-1) (1,0) (0,1) (-1,0).
"""

import numpy as np
from numba import njit

Q8_NODES = np.array(
    [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0], [0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]
)
LINE3_NODES = np.array([-1.0, 0.0, 1.0])


@njit(cache=True)
def lagrange3(xi):
    """Values N (3,) and derivatives dN/dxi (3,) of the quadratic Lagrange line at ``xi``."""
    n = np.empty(3)
    dn = np.empty(3)
    lagrange3_into(xi, n, dn)
    return n, dn


@njit(cache=True)
def lagrange3_into(xi, n, dn):
    """:func:`lagrange3` written into ``n`` and ``dn`` (3,): for loops that must not allocate."""
    n[0] = 0.5 * xi * (xi - 1.0)
    n[1] = 1.0 - xi * xi
    n[2] = 0.5 * xi * (xi + 1.0)
    dn[0] = xi - 0.5
    dn[1] = -2.0 * xi
    dn[2] = xi + 0.5


@njit(cache=True)
def serendipity8(xi, eta):
    """Values N (8,) and derivatives dN (8, 2) [d/dxi, d/deta] of the 8-node serendipity quad."""
    n = np.empty(8)
    dn = np.empty((8, 2))
    for a in range(4):
        xa = (-1.0, 1.0, 1.0, -1.0)[a]
        ya = (-1.0, -1.0, 1.0, 1.0)[a]
        s = 1.0 + xa * xi
        t = 1.0 + ya * eta
        n[a] = 0.25 * s * t * (xa * xi + ya * eta - 1.0)
        dn[a, 0] = 0.25 * xa * t * (2.0 * xa * xi + ya * eta)
        dn[a, 1] = 0.25 * ya * s * (xa * xi + 2.0 * ya * eta)
    # mid-side nodes on eta = -1 and eta = +1 (xi_a = 0)
    for a, ya in ((4, -1.0), (6, 1.0)):
        n[a] = 0.5 * (1.0 - xi * xi) * (1.0 + ya * eta)
        dn[a, 0] = -xi * (1.0 + ya * eta)
        dn[a, 1] = 0.5 * ya * (1.0 - xi * xi)
    # mid-side nodes on xi = +1 and xi = -1 (eta_a = 0)
    for a, xa in ((5, 1.0), (7, -1.0)):
        n[a] = 0.5 * (1.0 + xa * xi) * (1.0 - eta * eta)
        dn[a, 0] = 0.5 * xa * (1.0 - eta * eta)
        dn[a, 1] = -eta * (1.0 + xa * xi)
    return n, dn
