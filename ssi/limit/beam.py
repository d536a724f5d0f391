"""The beam of a bending footing (:class:`ssi.limit.geometry.Beam`) on one triangle mesh: its nodes (the
mesh's corner nodes along the footing's base, left to right), its elements (the base edges) and its point
loads at the nodes. Both bounds read this one layout.

The statics the lower bound uses, per element of length L from node a to node b with the upward load on the
beam p(s) linear (minus the soil's traction t_z, minus the beam's downward pressure): with M sagging
positive and V = dM/dx, walking from the free left end (V = M = 0),

    V_b = V_a + L (p_a + p_b) / 2,      M_b = M_a + V_a L + L^2 (p_a / 3 + p_b / 6),

and across a node the point loads: V += F_z, M -= C (C counter-clockwise). M is cubic along the element;
its Bernstein control points M_a, M_a + L V_a / 3, M_b - L V_b / 3, M_b bound it (convex hull), so
-mp_hog <= each <= mp_sag makes |M| admissible along the whole beam, not only at the nodes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import Site

__all__ = ["BeamLayout", "beam_layout"]


@dataclass
class BeamLayout:
    """``nodes`` (n_k,) mesh corner nodes along the base, sorted by x; ``x`` (n_k,) their x (scaled);
    ``length`` (n_e,) element lengths (scaled); ``edge`` (n_e,) the boundary-edge index (into
    :class:`ssi.limit._common.BoundaryEdges`) of each element; ``left_is_p`` (n_e,) whether that edge's p
    is the element's left node; ``loads_ref`` / ``loads_dead`` (n_k, 3): Fx, Fz [N/m], C [N m/m] at each
    node."""

    nodes: np.ndarray
    x: np.ndarray
    length: np.ndarray
    edge: np.ndarray
    left_is_p: np.ndarray
    loads_ref: np.ndarray
    loads_dead: np.ndarray


def beam_layout(site: Site, f: int, be, xy: np.ndarray, L: float) -> BeamLayout:
    """The layout of footing ``f``'s beam from the boundary edges ``be`` and node coordinates ``xy`` scaled
    by ``L`` [m]. Raises ValueError if the base is not one straight horizontal chain from x0 to x1 or a
    point load is not at a base node."""
    ft = site.footings[f]
    beam = ft.beam
    js = [j for j in range(len(be.p)) if site.segments[be.seg[j]][2].kind == "footing"]
    js = [j for j in js if site.segments[be.seg[j]][2].footing == f]
    if not js:
        raise ValueError(f"footing {f} has a beam but no base segment")
    js = np.array(js)
    if np.any(np.abs(be.n[js, 0]) > 1e-9) or np.any(be.n[js, 1] < 0.0):
        raise ValueError(f"footing {f}: a beam needs a straight horizontal base with the soil below it")
    xp, xq = xy[be.p[js], 0], xy[be.q[js], 0]
    order = np.argsort(np.minimum(xp, xq))
    js = js[order]
    left_is_p = xy[be.p[js], 0] < xy[be.q[js], 0]
    left = np.where(left_is_p, be.p[js], be.q[js])
    right = np.where(left_is_p, be.q[js], be.p[js])
    if np.any(left[1:] != right[:-1]):
        raise ValueError(f"footing {f}: the beam's base segments do not form one chain")
    nodes = np.append(left, right[-1])
    x = xy[nodes, 0]
    tol = 1e-9 * max(1.0, abs(beam.x1 - beam.x0) / L)
    if abs(x[0] - beam.x0 / L) > tol or abs(x[-1] - beam.x1 / L) > tol:
        raise ValueError(
            f"footing {f}: its base runs over x = [{x[0] * L:g}, {x[-1] * L:g}] m, its Beam over "
            f"[{beam.x0:g}, {beam.x1:g}] m"
        )
    z = xy[nodes, 1]
    if np.ptp(z) > tol:
        raise ValueError(
            f"footing {f}: a beam needs a horizontal base (z from {z.min() * L:g} to {z.max() * L:g} m)"
        )
    loads = {}
    for name in ("loads_ref", "loads_dead"):
        out = np.zeros((len(nodes), 3))
        for i, (xl, fx, fz, c) in enumerate(getattr(beam, name)):
            k = int(np.argmin(np.abs(x - xl / L)))
            if abs(x[k] - xl / L) > tol:
                raise ValueError(
                    f"Beam.{name}[{i}] at x = {xl:g} m is not at a node of the beam's base (nearest "
                    f"{x[k] * L:g} m): the site needs a point there"
                )
            out[k] += (fx, fz, c)
        loads[name] = out
    return BeamLayout(nodes, x, np.diff(x), js, left_is_p, loads["loads_ref"], loads["loads_dead"])


@dataclass
class BeamStatics:
    """The lower bound's beam of one footing, linear in the program's variables x: ``B`` (n_b, n) and
    ``b0`` (n_b,) the Bernstein control points of M [S L^2 units] (row i: B x + b0), ``mp_sag`` / ``mp_hog``
    (scaled) their bounds; ``M_left`` / ``M_right`` ((n_k, n) matrix, (n_k,) constant) the moment just left
    / right of each node (after its couple)."""

    B: object
    b0: np.ndarray
    mp_sag: float
    mp_hog: float
    M_left: tuple
    M_right: tuple


def lower_bound_statics(
    site: Site, f: int, lay: BeamLayout, be, n: int, imu: int, S: float, L: float, k: float
):
    """The beam's moments (module docstring) as linear expressions of the lower bound's variables: the
    vertex stresses (flat index 9 e + 3 v + c: sig_x, sig_z, tau) and mu = k lambda at ``imu``, in units of
    the stress ``S`` [Pa] and length ``L`` [m]."""
    import scipy.sparse as sp

    beam = site.footings[f].beam
    n_e = len(lay.length)
    m = 4 * n_e + 2  # local columns: sig_z, tau at the left and right end of each element; mu; the constant
    cols = np.full(m, -1, np.int64)
    cols[4 * n_e] = imu
    p_loc = []  # per element: the upward load on the beam at its left and right end, local vectors
    for e in range(n_e):
        j = lay.edge[e]
        nx, nz = be.n[j]
        ends = (be.lp[j], be.lq[j]) if lay.left_is_p[e] else (be.lq[j], be.lp[j])
        pair = []
        for side, loc in enumerate(ends):
            s0 = 9 * be.el[j] + 3 * loc
            v = np.zeros(m)
            i = 4 * e + 2 * side
            cols[i], cols[i + 1] = s0 + 1, s0 + 2
            v[i], v[i + 1] = -nz, -nx  # -t_z = -(nx tau + nz sig_z)
            v[4 * n_e] = -beam.pressure_ref / S / k
            v[4 * n_e + 1] = -beam.pressure_dead / S
            pair.append(v)
        p_loc.append(pair)
    fr, fd = lay.loads_ref, lay.loads_dead

    def node_load(kk: int) -> tuple[np.ndarray, np.ndarray]:
        fz, c = np.zeros(m), np.zeros(m)
        fz[4 * n_e], fz[4 * n_e + 1] = fr[kk, 1] / (S * L) / k, fd[kk, 1] / (S * L)
        c[4 * n_e], c[4 * n_e + 1] = fr[kk, 2] / (S * L**2) / k, fd[kk, 2] / (S * L**2)
        return fz, c

    V, M = np.zeros(m), np.zeros(m)
    rows, m_left, m_right = [], [], []
    for kk in range(n_e + 1):
        m_left.append(M.copy())
        fz, c = node_load(kk)
        V, M = V + fz, M - c
        m_right.append(M.copy())
        if kk == n_e:
            break
        le = lay.length[kk]
        pa, pb = p_loc[kk]
        Vb = V + le * (pa + pb) / 2.0
        Mb = M + V * le + le**2 * (pa / 3.0 + pb / 6.0)
        rows += [M.copy(), M + le * V / 3.0, Mb - le * Vb / 3.0, Mb.copy()]
        V, M = Vb, Mb

    def to_global(vs: list) -> tuple:
        a = np.array(vs)
        live = cols >= 0
        mat = sp.csr_matrix(a[:, :-1][:, live[:-1]])
        out = sp.csr_matrix((mat.data, cols[:-1][live[:-1]][mat.indices], mat.indptr), shape=(len(vs), n))
        return out, a[:, -1]

    B, b0 = to_global(rows)
    return BeamStatics(
        B, b0, beam.mp_sag / (S * L**2), beam.mp_hog / (S * L**2), to_global(m_left), to_global(m_right)
    )
