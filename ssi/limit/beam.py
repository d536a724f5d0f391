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

The axial force N (tension positive) likewise, with the horizontal load on the beam p_x = -t_x (linear):
N_b = N_a - L (p_xa + p_xb) / 2 and across a node N -= F_x. N is quadratic along the element, with
Bernstein points N_a, N_a - L p_xa / 2, N_b, raised to degree three (N_a, (N_a + 2 Q_1) / 3, (2 Q_1 + N_b) /
3, N_b): a facet a_N N + a_M M <= b of the M-N polygon (:meth:`~ssi.limit.geometry.Beam.facets`) is a
cubic along the element whose Bernstein points are a_N N_k + a_M M_k, so it holds along the whole element
when it holds at those four points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import Site

__all__ = ["BeamLayout", "beam_layout"]


@dataclass
class BeamLayout:
    """``nodes`` (n_k,) mesh corner nodes along the base, sorted by x (negative: a node of the beam alone,
    over a gap in the soil); ``x`` (n_k,) their x (scaled); ``length`` (n_e,) element lengths (scaled);
    ``edge`` (n_e,) the boundary-edge index (into :class:`ssi.limit._common.BoundaryEdges`) of each element
    (-1: it spans a gap, no soil below); ``left_is_p`` (n_e,) whether that edge's p
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
    by ``L`` [m]. Raises ValueError if the base is not straight and horizontal from x0 to x1 or a point load
    on soil is not at a base node."""
    ft = site.footings[f]
    beam = ft.beam
    virtual: dict = {}
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
    tol = 1e-9 * max(1.0, abs(beam.x1 - beam.x0) / L)
    # the chain of base edges, left to right; where it breaks (a trench, a void under the strip) the beam
    # spans the gap with elements of its own (edge -1, no soil below), a node at each point load there
    xl_all = [ld[0] / L for ld in beam.loads_ref + beam.loads_dead]
    nodes, edge, lip = [int(left[0])], [], []
    for i in range(len(js)):
        if i and left[i] != right[i - 1]:
            xa, xb = xy[right[i - 1], 0], xy[left[i], 0]
            if xb <= xa + tol:
                raise ValueError(f"footing {f}: the beam's base segments overlap at x = {xa * L:g} m")
            for xv in sorted({x_ for x_ in xl_all if xa + tol < x_ < xb - tol}):
                nodes.append(-1 - len(nodes))  # a node of the beam alone, at x = xv
                virtual[nodes[-1]] = xv
                edge.append(-1)
                lip.append(True)
            nodes.append(int(left[i]))
            edge.append(-1)
            lip.append(True)
        nodes.append(int(right[i]))
        edge.append(int(js[i]))
        lip.append(bool(left_is_p[i]))
    nodes = np.array(nodes)
    x = np.array([virtual[g] if g < 0 else xy[g, 0] for g in nodes])
    if abs(x[0] - beam.x0 / L) > tol or abs(x[-1] - beam.x1 / L) > tol:
        raise ValueError(
            f"footing {f}: its base runs over x = [{x[0] * L:g}, {x[-1] * L:g}] m, its Beam over "
            f"[{beam.x0:g}, {beam.x1:g}] m"
        )
    z = xy[nodes[nodes >= 0], 1]
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
    edge, lip = np.array(edge, np.int64), np.array(lip)
    return BeamLayout(nodes, x, np.diff(x), edge, lip, loads["loads_ref"], loads["loads_dead"])


@dataclass
class BeamStatics:
    """The lower bound's beam of one footing, linear in the program's variables x: ``B`` (n_b, n) and
    ``b0`` (n_b,) the Bernstein control points of M [S L^2 units] (row i: B x + b0), ``BN`` and ``bN0``
    those of N [S L units] at the same points; ``facets`` (n_f, 3) the M-N polygon scaled, rows (a_N, a_M,
    b): a_N N + a_M M <= b in S L^2 units; ``M_left`` / ``M_right`` ((n_k, n) matrix, (n_k,) constant) the
    moment just left / right of each node (after its couple), ``N_left`` / ``N_right`` the axial force."""

    B: object
    b0: np.ndarray
    BN: object
    bN0: np.ndarray
    facets: np.ndarray
    M_left: tuple
    M_right: tuple
    N_left: tuple
    N_right: tuple

    def facet_values(self, x: np.ndarray) -> np.ndarray:
        """(n_f, n_b): a_N N + a_M M - b at every control point for the variables ``x`` (<= 0: inside)."""
        m, nn = self.B @ x + self.b0, self.BN @ x + self.bN0
        f = self.facets
        return f[:, :1] * nn[None, :] + f[:, 1:2] * m[None, :] - f[:, 2:3]


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
    px_loc = []  # and the horizontal load p_x = -t_x
    for e in range(n_e):
        j = lay.edge[e]
        if j < 0:  # over a gap: the beam's own pressure only
            v = np.zeros(m)
            v[4 * n_e] = -beam.pressure_ref / S / k
            v[4 * n_e + 1] = -beam.pressure_dead / S
            p_loc.append([v, v.copy()])
            px_loc.append([np.zeros(m), np.zeros(m)])
            continue
        nx, nz = be.n[j]
        ends = (be.lp[j], be.lq[j]) if lay.left_is_p[e] else (be.lq[j], be.lp[j])
        pair, pair_x = [], []
        for side, loc in enumerate(ends):
            s0 = 9 * be.el[j] + 3 * loc
            v = np.zeros(m)
            i = 4 * e + 2 * side
            cols[i], cols[i + 1] = s0 + 1, s0 + 2
            v[i], v[i + 1] = -nz, -nx  # -t_z = -(nx tau + nz sig_z)
            v[4 * n_e] = -beam.pressure_ref / S / k
            v[4 * n_e + 1] = -beam.pressure_dead / S
            pair.append(v)
            vx = np.zeros(m)
            vx[i + 1] = -nz  # -t_x = -(nx sig_x + nz tau), nx = 0 on the horizontal base
            pair_x.append(vx)
        p_loc.append(pair)
        px_loc.append(pair_x)
    fr, fd = lay.loads_ref, lay.loads_dead

    def node_load(kk: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        fx, fz, c = np.zeros(m), np.zeros(m), np.zeros(m)
        fx[4 * n_e], fx[4 * n_e + 1] = fr[kk, 0] / (S * L) / k, fd[kk, 0] / (S * L)
        fz[4 * n_e], fz[4 * n_e + 1] = fr[kk, 1] / (S * L) / k, fd[kk, 1] / (S * L)
        c[4 * n_e], c[4 * n_e + 1] = fr[kk, 2] / (S * L**2) / k, fd[kk, 2] / (S * L**2)
        return fx, fz, c

    V, M, N = np.zeros(m), np.zeros(m), np.zeros(m)
    rows, m_left, m_right, n_rows, n_left, n_right = [], [], [], [], [], []
    for kk in range(n_e + 1):
        m_left.append(M.copy())
        n_left.append(N.copy())
        fx, fz, c = node_load(kk)
        V, M, N = V + fz, M - c, N - fx
        m_right.append(M.copy())
        n_right.append(N.copy())
        if kk == n_e:
            break
        le = lay.length[kk]
        pa, pb = p_loc[kk]
        Vb = V + le * (pa + pb) / 2.0
        Mb = M + V * le + le**2 * (pa / 3.0 + pb / 6.0)
        rows += [M.copy(), M + le * V / 3.0, Mb - le * Vb / 3.0, Mb.copy()]
        qa, qb = px_loc[kk]
        q1 = N - le * qa / 2.0
        Nb = N - le * (qa + qb) / 2.0
        n_rows += [N.copy(), (N + 2.0 * q1) / 3.0, (2.0 * q1 + Nb) / 3.0, Nb.copy()]
        V, M, N = Vb, Mb, Nb

    def to_global(vs: list) -> tuple:
        a = np.array(vs)
        live = cols >= 0
        mat = sp.csr_matrix(a[:, :-1][:, live[:-1]])
        out = sp.csr_matrix((mat.data, cols[:-1][live[:-1]][mat.indices], mat.indptr), shape=(len(vs), n))
        return out, a[:, -1]

    B, b0 = to_global(rows)
    BN, bN0 = to_global(n_rows)
    fac = beam.facets() * np.array([1.0 / L, 1.0, 1.0 / (S * L**2)])  # a_N N = (a_N / L) N_s S L^2
    return BeamStatics(
        B, b0, BN, bN0, fac, to_global(m_left), to_global(m_right), to_global(n_left), to_global(n_right)
    )


# ---- the upper bound's beam: variables per footing
@dataclass
class BeamKinematics:
    """The upper bound's variables of one beam (column indices): ``w`` / ``phi`` (n_k,) each node's vertical
    velocity and rotation, ``u_node`` (n_k,) and ``u_el`` (n_e,) the horizontal velocities of the nodes and
    of the (rigid, inextensible) elements where hinges extend (None: the whole beam moves with the
    footing's U, no extension), ``lam`` (n_e, 2 ends, n_f) the flow-rule multipliers of each hinge, one per
    facet of the polygon; ``facets`` (n_f, 3) the polygon scaled (a_N, a_M, b) in S L^2 units."""

    lay: BeamLayout
    w: np.ndarray
    phi: np.ndarray
    u_node: np.ndarray | None
    u_el: np.ndarray | None
    lam: np.ndarray
    facets: np.ndarray


def beam_kinematics(beam, lay: BeamLayout, first: int, free_axial: bool, S: float, L: float):
    """The variables of a beam from column ``first`` on, and the number of columns they take. Its hinges
    extend (``free_axial``) only on a joint that lets the soil and the beam slide apart (a rough base ties
    each soil node to the beam, whose velocity would jump at an extending hinge) and with the footing free
    along x: otherwise the extension is zero and the hinge dissipates the polygon's support function at
    zero extension (the largest M of the polygon: rigorous, not tight where N matters)."""
    n_k = len(lay.nodes)
    fac = beam.facets() * np.array([1.0 / L, 1.0, 1.0 / (S * L**2)])
    n_f = len(fac)
    c = first
    w = np.arange(c, c + n_k)
    phi = np.arange(c + n_k, c + 2 * n_k)
    c += 2 * n_k
    u_node = u_el = None
    if free_axial:
        u_node = np.arange(c, c + n_k)
        u_el = np.arange(c + n_k, c + 2 * n_k - 1)
        c += 2 * n_k - 1
    lam = np.arange(c, c + 2 * (n_k - 1) * n_f).reshape(n_k - 1, 2, n_f)
    c += lam.size
    return BeamKinematics(lay, w, phi, u_node, u_el, lam, fac), c - first


def hinge_rows(bk: BeamKinematics, eq, ineq, q: np.ndarray) -> None:
    """The hinge at each end of each element: its rotation (left end theta_e - phi_left, right end
    phi_right - theta_e, theta_e = (w_right - w_left) / L_e) and extension (left u_e - u_left, right
    u_right - u_e; zero without axial variables) equal sum_i lam_i (a_M, a_N)_i, lam >= 0 (the associated
    flow rule: normal to the polygon), dissipating sum_i lam_i b_i (the polygon's support function)."""
    lay, fac = bk.lay, bk.facets
    has_n = bool(np.any(fac[:, 0] != 0.0))
    for e, le in enumerate(lay.length):
        th = ([bk.w[e + 1], bk.w[e]], [1.0 / le, -1.0 / le])  # the element's rotation
        for end, (k, sgn) in enumerate(((e, -1.0), (e + 1, 1.0))):
            lam = list(bk.lam[e, end])
            eq.add(th[0] + [bk.phi[k]] + lam, [-sgn * v for v in th[1]] + [sgn] + list(-fac[:, 1]), 0.0)
            if has_n:
                ext = ([bk.u_el[e], bk.u_node[k]], [-sgn, sgn]) if bk.u_el is not None else ([], [])
                eq.add(ext[0] + lam, ext[1] + list(-fac[:, 0]), 0.0)
            for li, b_ in zip(lam, fac[:, 2]):
                ineq.add([li], [-1.0], 0.0)
                q[li] += b_


def beam_powers(beam, bk: BeamKinematics, u_col: int, p_ref, p_dead, S: float, L: float, k: float):
    """The beam's loads' power coefficients: point forces on w and on u (each node's own, or U, the column
    ``u_col`` if free), couples on phi, the uniform downward pressure on w (linear along each element: its
    integral L (w_a + w_b) / 2); reference loads divided by the load scale ``k``."""
    lay, w_col, phi_col = bk.lay, bk.w, bk.phi
    for pw, loads, p, scale in (
        (p_ref, lay.loads_ref, beam.pressure_ref, 1 / k),
        (p_dead, lay.loads_dead, beam.pressure_dead, 1.0),
    ):
        if bk.u_node is not None:
            np.add.at(pw, bk.u_node, loads[:, 0] / (S * L) * scale)
        elif u_col >= 0:
            pw[u_col] += loads[:, 0].sum() / (S * L) * scale
        np.add.at(pw, w_col, loads[:, 1] / (S * L) * scale)
        np.add.at(pw, phi_col, loads[:, 2] / (S * L**2) * scale)
        np.add.at(pw, w_col[:-1], -p / S * lay.length / 2 * scale)
        np.add.at(pw, w_col[1:], -p / S * lay.length / 2 * scale)


def hinge_dissipation(beam, bk: BeamKinematics, x: np.ndarray, el: np.ndarray, diss: np.ndarray, S, L):
    """The hinges recomputed from the beam's w, phi (and u) in ``x``: their dissipation, the polygon's
    support function max over P of (N delta + M theta) (without an interaction mp_sag theta+ + mp_hog
    theta-; the extension is then zero), added to ``diss`` at the triangles ``el``; returns (w, phi,
    rotations (n_e, 2): left and right end, sagging positive, extensions (n_e, 2), u at the nodes, u of
    the elements), scaled."""
    lay = bk.lay
    w, phi = x[bk.w], x[bk.phi]
    theta = np.diff(w) / lay.length
    rot = np.stack([theta - phi[:-1], phi[1:] - theta], axis=1)
    if bk.u_el is not None:
        un, ue = x[bk.u_node], x[bk.u_el]
        ext = np.stack([ue - un[:-1], un[1:] - ue], axis=1)
    else:
        un, ue, ext = None, None, np.zeros_like(rot)
    if beam.axial:
        v = beam.vertices()
        nv, mv = v[:, 0] / (S * L), v[:, 1] / (S * L**2)
        d_h = np.max(nv[None, None, :] * ext[..., None] + mv[None, None, :] * rot[..., None], axis=2)
    else:
        d_h = (beam.mp_sag * np.maximum(rot, 0.0) + beam.mp_hog * np.maximum(-rot, 0.0)) / (S * L**2)
    np.add.at(diss, el, d_h.sum(axis=1))
    return w, phi, rot, ext, un, ue


def beam_elements(be, lay: BeamLayout) -> np.ndarray:
    """The triangle under each beam element (over a gap: the nearest one to its left, else right), where
    its hinges' dissipation is booked."""
    el = np.where(lay.edge >= 0, be.el[np.maximum(lay.edge, 0)], -1)
    have = np.flatnonzero(el >= 0)
    nearest = have[np.clip(np.searchsorted(have, np.arange(len(el))) - 1, 0, len(have) - 1)]
    return np.where(el >= 0, el, el[nearest])


def carry_beam(given: dict, x: np.ndarray, L: float):
    """A beam motion ``given`` (dict x [m], w [m/s], phi [1/s] and, where hinges extend, u, u_el [m/s] of an
    upper bound) at the nodes ``x`` [m] of a nested finer beam: w linear between the given nodes (rigid
    elements), phi the given node's where a node is kept, else the rotation of the element it splits (no
    hinge there), likewise u the node's or its element's; (w, phi scaled by L, u at the nodes, u of the
    elements (None without)) as the solver's variables."""
    xg, wg, pg = given["x"], given["w"], given["phi"]
    w = np.interp(x, xg, wg)
    slope = np.diff(wg) / np.diff(xg)
    e = np.clip(np.searchsorted(xg, x) - 1, 0, len(slope) - 1)
    same = np.isclose(x[:, None], xg[None, :], rtol=0.0, atol=1e-9 * max(1.0, np.ptp(xg))).any(axis=1)
    phi = np.where(same, np.interp(x, xg, pg), slope[e])
    if given.get("u_el") is None:
        return w, phi * L, None, None
    ug, ueg = given["u"], given["u_el"]
    u = np.where(same, np.interp(x, xg, ug), ueg[e])
    mid = 0.5 * (x[:-1] + x[1:])
    u_el = ueg[np.clip(np.searchsorted(xg, mid) - 1, 0, len(ueg) - 1)]
    return w, phi * L, u, u_el
