"""Verification tools shared by the chapters and the tests: one home for each check that both make.

* :func:`fd_jacobian` -- central-difference Jacobian of a vector function (tangent checks of every law and
  element: soil, interface, layer laws, plate strip, springs).
* :func:`zero_energy_modes` -- the number of zero eigenvalues of an unsupported stiffness matrix.
* :func:`dense_stiffness` -- the dense global K0 of element groups, for small reference computations.
* :func:`convergence_rate` -- the fitted order of an error under refinement (log-log least squares);
  :func:`residual_order` -- the fitted order of an iteration's residual sequence (Newton: 2).
* :func:`distorted_q8_mesh` -- the randomly distorted unit-square Q8 mesh of the element tests.

These are reference computations: dense, plain NumPy, for small systems. Nothing here is used by a solve.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable, Sequence

import numpy as np

from ..core.mesh import SoilMesh, structured_q8

__all__ = [
    "convergence_rate",
    "dense_stiffness",
    "distorted_q8_mesh",
    "fd_jacobian",
    "residual_order",
    "zero_energy_modes",
]


def fd_jacobian(
    fun: Callable[[np.ndarray], np.ndarray],
    x,
    h: float,
    columns: Iterable[int] | None = None,
) -> np.ndarray:
    """Central-difference Jacobian J[:, j] = (fun(x + h e_j) - fun(x - h e_j)) / (2 h).

    ``fun`` maps a float vector like ``x`` to a vector (any shape; it is flattened). ``columns``: the
    components of ``x`` to perturb (default all); the other columns of J stay zero. The error is the
    truncation h^2 |f'''| / 6 plus the round-off ~ eps |f| / h: choose h and the tolerance from both.
    """
    x = np.asarray(x, dtype=np.float64)
    f0 = np.asarray(fun(x.copy()), dtype=np.float64).ravel()
    cols = range(x.size) if columns is None else columns
    jac = np.zeros((f0.size, x.size))
    for j in cols:
        xp, xm = x.copy().ravel(), x.copy().ravel()
        xp[j] += h
        xm[j] -= h
        fp = np.asarray(fun(xp.reshape(x.shape)), dtype=np.float64).ravel()
        fm = np.asarray(fun(xm.reshape(x.shape)), dtype=np.float64).ravel()
        jac[:, j] = (fp - fm) / (2 * h)
    return jac


def zero_energy_modes(K, rel: float = 1e-10) -> int:
    """Number of eigenvalues of the symmetric matrix ``K`` below ``rel`` times its largest one: the
    zero-energy (rigid-body and spurious) modes of an unsupported stiffness matrix."""
    ev = np.linalg.eigvalsh(np.asarray(K, dtype=np.float64))
    return int(np.sum(ev < rel * ev.max()))


def dense_stiffness(n_dof: int, groups: Sequence) -> np.ndarray:
    """Dense (n_dof, n_dof) sum of the groups' initial element stiffnesses K0 (``elastic_stiffness()``)
    scattered by their ``edofs``: the unsupported global matrix of a small model."""
    K = np.zeros((n_dof, n_dof))
    for group in groups:
        for ed, ke in zip(group.edofs, group.elastic_stiffness()):
            K[np.ix_(ed, ed)] += ke
    return K


def convergence_rate(h, err) -> float:
    """Slope of log(err) against log(h) by least squares: the observed order p of err ~ C h^p (``h`` any
    refinement measure: element size, or element count for a negative slope)."""
    return float(np.polyfit(np.log(h), np.log(err), 1)[0])


def residual_order(residuals, lo: float = 1e-13, hi: float = 5e-2) -> tuple[float, int]:
    """``(p, n_pairs)``: the slope p of log e_{k+1} = p log e_k + c fitted over the consecutive residual
    pairs with lo < e_k < hi and lo < e_{k+1} (above the round-off floor, inside the asymptotic range);
    p = 2 for Newton's method with an exact tangent, 1 for a fixed-matrix iteration."""
    e = np.asarray(residuals)
    pairs = np.array([(a, b) for a, b in itertools.pairwise(e) if lo < a < hi and lo < b])
    return np.polyfit(np.log(pairs[:, 0]), np.log(pairs[:, 1]), 1)[0], len(pairs)


def distorted_q8_mesh(n: int = 3, seed: int = 1, amplitude: float = 0.18) -> tuple[SoilMesh, np.ndarray]:
    """``(mesh, xy)``: the n x n Q8 mesh of the unit square with its interior corners moved at random by up
    to ``amplitude / n`` in each direction (seeded) and straight edges (mid-side nodes at the middle of
    their edges). ``mesh`` keeps the undistorted coordinates; ``xy`` are the distorted ones."""
    m = structured_q8(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    rng = np.random.default_rng(seed)
    xy, g = m.xy.copy(), m.grid
    for i in range(2, 2 * n, 2):
        for j in range(2, 2 * n, 2):
            xy[g[i, j]] += amplitude / n * rng.uniform(-1, 1, 2)
    for i in range(2 * n + 1):
        for j in range(2 * n + 1):
            if g[i, j] >= 0 and (i % 2) != (j % 2):
                a, b = (g[i - 1, j], g[i + 1, j]) if i % 2 else (g[i, j - 1], g[i, j + 1])
                xy[g[i, j]] = 0.5 * (xy[a] + xy[b])
    return m, xy
