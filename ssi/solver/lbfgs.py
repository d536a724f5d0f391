"""The two loops of the L-BFGS recursion (Nocedal 1980) over the pairs kept in ring buffers.

The solver's :class:`~ssi.solver._Lbfgs` keeps up to ``memory`` pairs (s, y) as rows of two (memory, n)
arrays, row ``(head - 1 - j) % memory`` the j-th newest. In numpy the recursion costs two vector calls per
pair and loop, each paying ~1 us of call overhead: with 30 pairs on a 1.7 k-DOF zoo scene ~110 us a
direction, against ~10 us here. The dot products call BLAS ``ddot`` as numpy's ``@`` does, and the vector
updates do the same operations in the same order, so the directions are bit for bit those of the numpy
recursion.
"""

import numpy as np
from numba import njit


@njit(cache=True)
def _row(head, j, memory):
    k = head - 1 - j
    return k + memory if k < 0 else k


@njit(cache=True)
def lbfgs_first_loop(s_rows, y_rows, rho, head, count, q, alphas):
    """Newest pair first: alpha_j = rho_j s_j . q, q -= alpha_j y_j (q in place, alphas (memory,) out)."""
    memory = s_rows.shape[0]
    for j in range(count):
        k = _row(head, j, memory)
        a = rho[k] * np.dot(s_rows[k], q)
        y = y_rows[k]
        for i in range(q.size):
            q[i] -= a * y[i]
        alphas[j] = a


@njit(cache=True)
def lbfgs_second_loop(s_rows, y_rows, rho, head, count, z, alphas):
    """Oldest pair first: z += (alpha_j - rho_j y_j . z) s_j (z in place)."""
    memory = s_rows.shape[0]
    for j in range(count - 1, -1, -1):
        k = _row(head, j, memory)
        c = alphas[j] - rho[k] * np.dot(y_rows[k], z)
        s = s_rows[k]
        for i in range(z.size):
            z[i] += c * s[i]
