"""Upper bound: a kinematically admissible velocity field on 6-node triangles, one SOCP, then recomputed.

Unknowns: velocities (u, w) at the corner and midside nodes (quadratic in each triangle, continuous),
each footing's translation (U, W) and rotation theta (where free; a bending footing's nodal w and phi and
its hinges instead), a plastic multiplier e at each vertex of each triangle (layout ``e[n_el, 3]``), and,
under a footing with a Coulomb or smooth interface, a slip bound s at each control point of the jump.

- The strain rate is linear in a triangle. At each vertex the associated Mohr-Coulomb flow rule reads
  eps_x + eps_z = sin phi e and ||(eps_x - eps_z, gamma_xz)|| <= e (a 3-D cone). e is linear between the
  vertices, so the rule holds everywhere in the triangle.
- Dissipation: c cos phi e per unit volume, integrated with the vertex rule (A/3) sum_k e_k. For phi > 0 the
  flow rule makes this exactly c cot phi times the integral of the volumetric rate (linear: exact); for
  phi = 0 it is the integral of the linear interpolant of e_k >= ||dev||, above the integral of the convex
  function ||dev(x)||: the computed dissipation can only overestimate, so the bound stays rigorous.
- Footing interface: the jump d = U - u (footing relative to soil) is quadratic along an edge; its Bernstein
  control points b_0 = d_a, b_1 = 2 d_m - (d_a + d_b)/2, b_2 = d_b contain the whole curve in their convex
  hull, so the Coulomb rule n.b_k = tan phi_i s_k, |t.b_k| <= s_k at the control points holds along the edge
  and the dissipation c_i sum_k s_k L/3 bounds c_i times the integral of |d_t| from above. With a tension
  cut-off t_i: n.b_k = tan phi_i s_k + o_k, o_k >= 0 (an opening beyond the dilation), dissipating
  (c_i s_k + t_i o_k) L/3 (t_i d_n exactly: the integral of a quadratic is L/3 times the sum of its
  Bernstein points). Rough: d = 0.
- Velocity conditions: fixed u = 0; symmetry u . n = 0 (axis-aligned rollers, eliminated); a footing's held
  translation or rotation is zero. A footing is a rigid body (U, W, theta about its centre): a point of it
  moves with (U - theta (z - z_c), W + theta (x - x_c)), linear along a straight edge and so exactly
  interpolated by the quadratic field; a rough base's nodes are tied to it (eliminated when the footing
  only translates, by equality rows when it rotates, and set to the rigid motion exactly before the
  recomputation). A footing with a :class:`~ssi.limit.geometry.Beam` bends instead: each base edge a rigid
  inextensible element (w linear along it, u = U), the nodes' vertical velocity w_k and rotation phi_k its
  variables, a hinge at each element end with rotation theta_e - phi_left (phi_right - theta_e) and,
  with an M-N polygon on a joint that is not rough, extension u_e - u_left (u_right - u_e), both equal to
  sum_i lam_i (a_M, a_N)_i over the polygon's facets (lam >= 0: normal to the polygon), dissipating sum_i
  lam_i b_i (without an interaction: mp_sag theta+ + mp_hog theta-); the beam's loads do work on w
  (forces), u (horizontal forces) and phi (couples).
- Normalisation: the power of the reference loads is 1; the objective is the dissipation minus the power
  of the dead loads (weight, surcharge, dead footing loads), which is lambda.

Recomputation: from the returned velocities alone, the strain rates at the vertices, the least e that
satisfies the cone, the flow-rule residual |eps_v - sin phi e| h / max |v| (h the element size; at the
interface |d_n - tan phi_i s| / max |v|), the jump control points, the dissipation, the dead and
reference powers, and lambda = (D - P_dead) / P_ref.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._common import boundary_edges, gradients, scales, strength
from .beam import (
    beam_elements,
    beam_kinematics,
    beam_layout,
    beam_powers,
    carry_beam,
    hinge_dissipation,
    hinge_rows,
)
from .conic import ConicSolution, Rows, needs_refinement, solve_conic
from .geometry import Site
from .mesh import TriMesh

__all__ = ["UpperBound", "upper_bound"]


@dataclass
class UpperBound:
    """A recomputed upper bound. ``lam`` from the velocity field, ``lam_solver`` the solver's objective;
    ``velocity`` (n_nodes + n_edges, 2) [m/s] (corner nodes, then one midside node per edge of
    ``mesh.edges()``; scaled so that the reference loads' power is 1 N/m . m/s); ``footing_velocity``
    (n_footings, 2) of each footing's centre, ``footing_rotation`` (n_footings,) [1/s] counter-clockwise
    (0 where held); ``beam``: per bending footing, dict of ``x`` [m] of its nodes, ``w`` [m/s] their
    vertical velocity, ``phi`` [1/s] their rotation, ``hinge`` (n_e, 2) [1/s] the hinge rotations at each
    element's left and right end (sagging positive), ``el`` the triangle under each element;
    ``dissipation`` (n_el,) each element's share of lambda (dissipation over the reference power; interface
    and hinge shares added to the element under the edge), ``dead_power`` the dead loads' share
    (lam = dissipation.sum() - dead_power); ``strain`` (n_el, 3, 3) vertex strain rates (eps_x, eps_z,
    gamma) [1/s];
    ``flow_residual`` the largest relative flow-rule residual; time [s], iterations, status, n_cones.

    ``certified``: the recomputed field is kinematically admissible — every flow-rule and interface residual
    within ``FLOW_TOL`` of the velocity scale and a positive reference power — so ``lam`` is an upper bound.
    Otherwise ``lam`` is +inf (no bound from this field) and ``lam_recomputed`` keeps the number the field
    would give: a field the solver returns with a status such as PrimalInfeasible (no mechanism exists on
    the mesh, e.g. a footing confined across the whole block) is not a mechanism, whatever its number."""

    lam: float
    lam_solver: float
    velocity: np.ndarray
    footing_velocity: np.ndarray
    footing_rotation: np.ndarray
    beam: dict
    dissipation: np.ndarray
    dead_power: float
    strain: np.ndarray
    flow_residual: float
    p_ref: float
    time: float
    iterations: int
    status: str
    n_cones: int
    n_rows: int
    certified: bool = True
    lam_recomputed: float = float("nan")
    admissible: bool = True
    power: tuple = (float("nan"), float("nan"), float("nan"))

    def collapse_proven(self, lam: float = 1.0) -> bool:
        """Whether the recomputed field proves that the site collapses under its dead loads plus ``lam``
        times its reference loads: a kinematically admissible field (flow rule met to ``FLOW_TOL``, whatever
        the solver's status) on which the loads do more work than the soil dissipates, D < P_dead + lam
        P_ref. With the solver's optimum (P_ref = 1) this is lam_UB < lam; with the ray of an unbounded
        program (status DualInfeasible: D - P_dead unbounded below) it holds for every lam when the dead
        loads alone do more work than the soil dissipates. The comparison keeps a relative margin of
        ``POWER_TOL`` of the largest term."""
        d, pd, pr = self.power
        if not (self.admissible and np.isfinite(d) and np.isfinite(pd) and np.isfinite(pr)):
            return False
        excess = pd + lam * pr - d
        return bool(excess > POWER_TOL * max(abs(d), abs(pd), abs(lam * pr)))


# Admissibility tolerance of a recomputed velocity field: flow-rule (eps_v >= sin(phi) e) and interface
# (dn >= tan(phi_i) |dt|) residuals relative to the velocity scale. Solved fields measured 1e-17 .. 1.4e-12
# on zoo scenes (two meshes each) and 2e-6 for chapter 17's beam over a trench on 20 MPa soil (a near-rigid
# soil takes the solver's slack); fields of infeasible programs 3 .. 7. Certified below 1e-4: four orders
# apart from either, and a residual that small changes the dissipation by about as much relatively.
FLOW_TOL = 1e-4
# the relative margin by which the loads' power must exceed the dissipation for a field to prove collapse
# (UpperBound.collapse_proven): the recomputed powers are sums of 1e3 .. 1e5 terms in double precision, the
# solver's slack enters through the flow-rule residual (<= FLOW_TOL, changing D by about as much)
POWER_TOL = 1e-6


def _vertex_gradients(b, c, A):
    """G (n_el, 3 vertices, 6 nodes, 2): gradients of the 6 quadratic shape functions (corners 0-2, then
    the midside node of side k = opposite vertex k) at each vertex, in the units of b, c / A."""
    n_el = len(A)
    gl = np.stack([b, c], axis=2) / (2 * A)[:, None, None]  # (n_el, 3, 2) grad L_k
    G = np.zeros((n_el, 3, 6, 2))
    for v in range(3):
        for i in range(3):
            G[:, v, i] = 3 * gl[:, v] if i == v else -gl[:, i]
        for k in range(3):
            if k != v:
                j = 3 - v - k  # side k joins v and j
                G[:, v, 3 + k] = 4 * gl[:, j]
    return G


def _dof_map(site: Site, mesh: TriMesh, be, n_nodes: int, n_mid: int, held=()):
    """Variable index of each nodal velocity component (-1: held at zero), footing variables, and the rows
    for symmetry rollers that are not axis-aligned. ``held``: nodes held at zero besides the boundary's
    (those of a rigid region that cannot move)."""
    n_all = n_nodes + n_mid
    state = np.zeros((n_all, 2), np.int64)  # 0 free, -1 zero, f+1: tied to footing f (rough)
    state[np.asarray(held, np.int64)] = -1
    oblique = []
    ties: dict = {}  # node: footing, for the rough base of a rotating footing
    for j in range(len(be.p)):
        bnd = site.segments[be.seg[j]][2]
        nodes = (be.p[j], be.q[j], n_nodes + be.edge[j])
        nx, nz = be.n[j]
        for g in nodes:
            if bnd.kind == "fixed":
                state[g] = -1
            elif bnd.kind == "symmetry":
                if abs(nz) < 1e-12:
                    state[g, 0] = -1
                elif abs(nx) < 1e-12:
                    state[g, 1] = -1
                else:
                    oblique.append((g, nx, nz))
            elif bnd.kind == "footing" and site.interface_of(bnd).kind == "rough":
                if site.footings[bnd.footing].rotates:  # (a beam rotates too)
                    ties.setdefault(int(g), bnd.footing)  # a free node tied by rows (its velocity varies)
                    continue
                for d in range(2):
                    if state[g, d] == 0:
                        state[g, d] = bnd.footing + 1
    n_f = len(site.footings)
    fvar = -np.ones((n_f, 3), np.int64)
    nxt = 0
    for f, ft in enumerate(site.footings):
        for d, name in enumerate("xzr"):
            # a beam: its nodes' own w, phi (and u where its hinges extend)
            if name in ft.moves and not (ft.beam is not None and (d > 0 or _free_axial(ft))):
                fvar[f, d] = nxt
                nxt += 1
    dof = -np.ones((n_all, 2), np.int64)
    for g in range(n_all):
        for d in range(2):
            s = state[g, d]
            if s == 0:
                dof[g, d] = nxt
                nxt += 1
            elif s > 0:
                dof[g, d] = fvar[s - 1, d]
    return dof, fvar, nxt, oblique, ties


def _rigid_rows(p: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """(2, 3): the velocity (u, w) at point ``p`` of a rigid motion (U, W, theta) about ``centre``."""
    return np.array([[1.0, 0.0, -(p[1] - centre[1])], [0.0, 1.0, p[0] - centre[0]]])


def _rigid_bodies(rigid_el, nodes6, xy_all, dof, oblique, ties, footing_vars) -> list:
    """The connected regions of rigid elements (sharing a node), each as a dict: ``nodes`` (its corner and
    midside nodes), ``centre`` (scaled), ``basis`` (3, k): the rigid motions (U, W, theta) its held nodes
    allow (fixed: none, k = 0; a symmetry roller: its normal component zero). A rigid region under a
    rough footing's base is refused: the two rigid bodies' rows would repeat each other."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components

    els = np.flatnonzero(rigid_el)
    if not len(els):
        return []
    inc = csr_matrix((np.ones(6 * len(els)), (np.repeat(np.arange(len(els)), 6), nodes6[els].ravel())))
    n_comp, label = connected_components(inc @ inc.T, directed=False)
    normal = {int(g): (nx, nz) for g, nx, nz in oblique}
    out = []
    for r in range(n_comp):
        nodes = np.unique(nodes6[els[label == r]])
        centre = xy_all[nodes].mean(axis=0)
        rows = []
        for g in nodes:
            R = _rigid_rows(xy_all[g], centre)
            if int(g) in normal:
                rows.append(normal[int(g)][0] * R[0] + normal[int(g)][1] * R[1])
            rows += [R[d] for d in range(2) if dof[g, d] == -1]
        if any(int(g) in ties for g in nodes) or np.any(np.isin(dof[nodes], footing_vars)):
            raise ValueError(
                "a rigid (elastic) material under a rough footing: the footing and the region would be one "
                "rigid body; give the footing a smooth or Coulomb interface, or the material a strength"
            )
        basis = np.eye(3)
        if rows:
            C = np.array(rows)
            _, sv, vt = np.linalg.svd(C)
            rank = int(np.sum(sv > 1e-10 * max(sv[0], 1e-300)))
            basis = vt[rank:].T
        out.append(dict(nodes=nodes, centre=centre, basis=basis))
    return out


def _free_axial(ft) -> bool:
    """Whether footing ``ft``'s beam hinges extend (:func:`ssi.limit.beam.beam_kinematics`)."""
    return ft.beam is not None and ft.beam.axial and ft.interface.kind != "rough" and "x" in ft.moves


def upper_bound(site: Site, mesh: TriMesh, tol: float = 1e-9, velocity=None) -> UpperBound:
    """The upper bound of the load factor lambda of ``site`` on ``mesh`` (module docstring), recomputed from
    the velocity field. ``tol``: Clarabel's tolerances. ``velocity``: (nodal (n_nodes + n_edges, 2), footing
    (n_footings, 2)[, footing rotation (n_footings,) [1/s]]) velocities to evaluate instead of solving (any
    scale; a held component must be zero)."""
    sc = scales(site)
    xy = mesh.xy / sc.L
    n_nodes, n_el = len(xy), mesh.n_el
    edges, el_edge = mesh.edges()
    n_mid = len(edges)
    be = boundary_edges(mesh, xy)
    dof, fvar, n_v, oblique, ties = _dof_map(site, mesh, be, n_nodes, n_mid)
    # every node's position (corners, then midsides of the straight edges) and each footing's centre
    xy_all = np.concatenate([xy, 0.5 * (xy[edges[:, 0]] + xy[edges[:, 1]])])
    nodes6 = np.concatenate([mesh.tri, n_nodes + el_edge], axis=1)  # (n_el, 6)
    rigid_el = np.array([m.rigid for m in site.materials], bool)[mesh.material]
    bodies = _rigid_bodies(rigid_el, nodes6, xy_all, dof, oblique, ties, fvar[fvar >= 0])
    held = [g for body in bodies if body["basis"].shape[1] == 0 for g in body["nodes"]]
    if held:  # a rigid region that cannot move (an elastic layer on the fixed base): its nodes are held
        dof, fvar, n_v, oblique, ties = _dof_map(site, mesh, be, n_nodes, n_mid, held)
    for body in bodies:  # the others move as rigid bodies: k variables each, the amplitudes of its basis
        body["vars"] = n_v + np.arange(body["basis"].shape[1])
        n_v += body["basis"].shape[1]
    on_body = {int(g) for body in bodies for g in body["nodes"]}
    cen = np.array([(0.0, 0.0) if ft.centre is None else ft.centre for ft in site.footings]).reshape(-1, 2)
    cen = cen / sc.L

    def arm(f: int, g: int) -> tuple[float, float]:
        """d(u, w)/d theta of footing f's rigid motion at node g: (-(z - z_c), x - x_c) (scaled)."""
        return -(xy_all[g, 1] - cen[f, 1]), xy_all[g, 0] - cen[f, 0]

    ie = n_v  # e variables
    n_e = 3 * n_el
    # interface control points (non-rough footings): keyed per corner node and per midside node
    cp = {}
    cp_rows = []  # (key, footing, edge j, which: 0/1/2, the edge's interface)
    for j in range(len(be.p)):
        bnd = site.segments[be.seg[j]][2]
        itf = site.interface_of(bnd) if bnd.kind == "footing" else None
        if itf is not None and itf.kind != "rough":
            # a corner's control point is shared by the edges of one line and one joint: one per normal and
            # interface (a trench wall's contact meets the base's at the corner with its own)
            nrm = (round(float(be.n[j, 0]), 9), round(float(be.n[j, 1]), 9), itf)
            if _free_axial(site.footings[bnd.footing]):  # each element its own u: a corner per edge
                nrm = (*nrm, j)
            keys = (("n", int(be.p[j]), nrm), ("m", int(be.edge[j])), ("n", int(be.q[j]), nrm))
            for w, key in enumerate(keys):
                if key not in cp:
                    cp[key] = len(cp)
                cp_rows.append((key, bnd.footing, j, w, itf))
    i_s = ie + n_e
    n = i_s + len(cp)
    # an opening o >= 0 beyond the Coulomb dilation at each control point of a joint with a tension cut-off
    cp_open = {}
    for key, _f, _j, _w, itf in cp_rows:
        if itf.tension is not None and key not in cp_open:
            cp_open[key] = n
            n += 1
    # a beam's variables: w and phi at each node (u at each node and element where its hinges extend),
    # the flow-rule multipliers of the hinge at each end of each element
    beams = {}
    el_of_edge = {}  # (footing, boundary edge j or mesh edge of a midside node) -> the beam element on it
    for f, ft in enumerate(site.footings):
        if ft.beam is not None:
            lay = beam_layout(site, f, be, xy, sc.L)
            beams[f], taken = beam_kinematics(ft.beam, lay, n, _free_axial(ft), sc.S, sc.L)
            n += taken
            for e, j in enumerate(lay.edge):
                if j >= 0:
                    el_of_edge[(f, "b", int(j))] = e
                    el_of_edge[(f, "m", int(be.edge[j]))] = e
    node_w = {}  # (footing, mesh node) -> the beam's w variable there
    for f, bk in beams.items():
        node_w.update({(f, int(g)): int(c) for g, c in zip(bk.lay.nodes, bk.w) if g >= 0})

    def terms(f: int, g: int, j: int = -1) -> tuple[list, list]:
        """Footing f's velocity at node g (a corner of boundary edge ``j``) as [(variable, coefficient)]
        for u and for w."""
        if f in beams:
            bk = beams[f]
            if bk.u_el is not None:  # the element's own u (a corner: that of the edge j's element)
                key = (f, "m", g - n_nodes) if g >= n_nodes else (f, "b", j)
                tu = [(int(bk.u_el[el_of_edge[key]]), 1.0)]
            else:
                tu = [(fvar[f, 0], 1.0)] if fvar[f, 0] >= 0 else []
            if g < n_nodes:
                return tu, [(node_w[(f, g)], 1.0)]
            a, b = edges[g - n_nodes]  # a midside node: the element is rigid, w linear along it
            return tu, [(node_w[(f, int(a))], 0.5), (node_w[(f, int(b))], 0.5)]
        ax, az = arm(f, g)
        tu = [(fvar[f, 0], 1.0), (fvar[f, 2], ax)]
        tw = [(fvar[f, 1], 1.0), (fvar[f, 2], az)]
        return [t for t in tu if t[0] >= 0], [t for t in tw if t[0] >= 0]

    eq, ineq, soc = Rows(), Rows(), Rows()
    q = np.zeros(n)
    # flow rule at the vertices
    b, c, A = gradients(xy, mesh.tri)
    G = _vertex_gradients(b, c, A)
    du, dw = dof[nodes6, 0], dof[nodes6, 1]
    c2, sphi, cphi = (np.array(v) for v in zip(*(strength(m, sc.S) for m in site.materials)))
    c_cos = 0.5 * c2[mesh.material]  # c cos phi / S
    sinm = sphi[mesh.material]
    # one flow-rule row and one cone (3 rows) per vertex, vertex index 3 e + v (vectorised over vertices):
    # eps_x = gx . u, eps_z = gz . w, gamma = gz . u + gx . w; a held velocity (dof -1) drops its entry
    nv = 3 * n_el
    gx = G[..., 0].reshape(nv, 6)
    gz = G[..., 1].reshape(nv, 6)
    cu = np.repeat(du, 3, axis=0)  # (nv, 6) the variables of u at the element's 6 nodes
    cw = np.repeat(dw, 3, axis=0)
    ev = ie + np.arange(nv)
    s_v = np.repeat(sinm, 3)
    # the flow rule's row of each yielding vertex (-1 in a rigid material: its strain rate is zero by the
    # rigid-body rows below, so it has no cone, and its multiplier e is zero)
    yv = np.repeat(~rigid_el, 3)
    vrow = np.full(nv, -1, np.int64)
    vrow[yv] = np.arange(int(yv.sum()))
    n_y = int(yv.sum())
    row = np.repeat(vrow, 12)
    cols_uw = np.concatenate([cu, cw], axis=1).ravel()
    keep = (cols_uw >= 0) & (row >= 0)

    def add_rows(block: Rows, rows, vals, rhs, extra=None):
        r, c, v = rows[keep], cols_uw[keep], vals.ravel()[keep]
        if extra is not None:  # (rows, cols, vals) appended
            r, c, v = (
                np.concatenate([r, extra[0]]),
                np.concatenate([c, extra[1]]),
                np.concatenate([v, extra[2]]),
            )
        order = np.argsort(r, kind="stable")
        block.add_many(r[order], c[order], v[order], rhs)

    # volumetric rate = sin(phi) e
    add_rows(eq, row, np.concatenate([gx, gz], axis=1), np.zeros(n_y), (vrow[yv], ev[yv], -s_v[yv]))
    # cone rows (s = b - A x): (e, eps_x - eps_z, gamma) in SOC_3
    soc_rows = 3 * row
    add_rows(
        soc,
        soc_rows + 1,
        np.concatenate([-gx, gz], axis=1),
        np.zeros(3 * n_y),
        (3 * vrow[yv], ev[yv], -np.ones(n_y)),
    )
    # the third row of each cone, appended as its own block of entries (the rhs is already there)
    r3 = (soc_rows + 2)[keep]
    v3 = np.concatenate([-gz, -gx], axis=1).ravel()[keep]
    r0 = len(soc.rhs) - 3 * n_y
    soc.rows.extend((r3 + r0).tolist())
    soc.cols.extend(cols_uw[keep].tolist())
    soc.vals.extend(v3.tolist())
    q[ev] += np.repeat(c_cos * A / 3.0, 3)
    if n_y < nv:  # a rigid material's multipliers
        eq.add_many(np.arange(nv - n_y), ev[~yv], np.ones(nv - n_y), np.zeros(nv - n_y))
    # a rigid body's nodes: each free velocity component is that of the body's motion there
    for body in bodies:
        for g in body["nodes"]:
            for d in range(2):
                if dof[g, d] >= 0 and body["vars"].size:
                    coef = _rigid_rows(xy_all[g], body["centre"])[d] @ body["basis"]
                    eq.add([int(dof[g, d])] + list(body["vars"]), [1.0] + list(-coef), 0.0)
    # oblique symmetry rollers (on a rigid body: met by its basis)
    for g, nx, nz in dict(((g, (g, nx, nz)) for g, nx, nz in oblique if g not in on_body)).values():
        cols = [dof[g, 0], dof[g, 1]]
        vals = [nx, nz]
        keep = [i for i, cc in enumerate(cols) if cc >= 0]
        if keep:
            eq.add([cols[i] for i in keep], [vals[i] for i in keep], 0.0)
    # interface control points: b_k in terms of (U - u) at a, m, b
    cp_done = set()
    for key, f, j, w, itf in cp_rows:
        L = be.length[j]
        ci, tphi = itf.strength
        k = i_s + cp[key]
        q[k] += ci / sc.S * L / 3.0
        o = cp_open.get(key, -1)
        if o >= 0:
            q[o] += itf.tension / sc.S * L / 3.0
        if key in cp_done:
            continue
        cp_done.add(key)
        nx, nz = be.n[j]
        a_, m_, b_ = be.p[j], n_nodes + be.edge[j], be.q[j]
        weights = {0: {a_: 1.0}, 2: {b_: 1.0}, 1: {m_: 2.0, a_: -0.5, b_: -0.5}}[w]
        for comp, (vx, vz) in (("n", (nx, nz)), ("t", (-nz, nx))):
            cols, vals = [], []
            for d, vv in ((0, vx), (1, vz)):
                for g, wt in weights.items():
                    for col, cf in terms(f, g, j)[d]:  # the footing's velocity at g
                        cols.append(col)
                        vals.append(wt * vv * cf)
                    if dof[g, d] >= 0:
                        cols.append(dof[g, d])
                        vals.append(-wt * vv)
            if comp == "n":  # n . b = tan phi s (+ o, o >= 0, with a cut-off)
                if o >= 0:
                    eq.add(cols + [k, o], vals + [-tphi, -1.0], 0.0)
                    ineq.add([o], [-1.0], 0.0)
                else:
                    eq.add(cols + [k], vals + [-tphi], 0.0)
            else:
                ineq.add(cols + [k], vals + [-1.0], 0.0)
                ineq.add(cols + [k], [-v for v in vals] + [-1.0], 0.0)
    # the rough base of a rotating or bending footing: each node moves with the footing
    for g, f in ties.items():
        for d in range(2):
            cols = [dof[g, d]] if dof[g, d] >= 0 else []
            vals = [1.0] * len(cols)
            for col, cf in terms(f, g)[d]:
                cols.append(col)
                vals.append(-cf)
            if cols:
                eq.add(cols, vals, 0.0)
    for bk in beams.values():  # hinge rows, their dissipation in the objective
        hinge_rows(bk, eq, ineq, q)
    # powers: reference (= 1) and dead (subtracted in the objective)
    p_ref = np.zeros(n)
    p_dead = np.zeros(n)
    gam = np.array([m.gamma for m in site.materials])[mesh.material] * sc.L / sc.S
    # weight (0, -gamma): the integral of a midside shape function is A/3, of a corner 0
    d_mid = dw[:, 3:].ravel()
    w_mid = np.repeat(-gam * A / 3.0, 3)
    np.add.at(p_dead, d_mid[d_mid >= 0], w_mid[d_mid >= 0])
    for j in range(len(be.p)):
        bnd = site.segments[be.seg[j]][2]
        if bnd.kind != "free":
            continue
        L = be.length[j]
        nx, nz = be.n[j]
        # Simpson's rule: exact for the quadratic velocity times a linear dead pressure
        ends = mesh.xy[be.p[j]], mesh.xy[be.q[j]]
        at = (ends[0], ends[1], 0.5 * (ends[0] + ends[1]))
        for g, wt, pt in zip((be.p[j], be.q[j], n_nodes + be.edge[j]), (L / 6, L / 6, 2 * L / 3), at):
            pd = bnd.dead_at(*pt)
            for d, nn in ((0, nx), (1, nz)):
                if dof[g, d] >= 0:
                    p_ref[dof[g, d]] += -bnd.pressure_ref / sc.S * nn * wt / sc.k
                    p_dead[dof[g, d]] += -pd / sc.S * nn * wt
    for f, bk in beams.items():  # the beam's loads do work on w, u and phi
        beam_powers(site.footings[f].beam, bk, fvar[f, 0], p_ref, p_dead, sc.S, sc.L, sc.k)
    for f, ft in enumerate(site.footings):
        if f in beams:
            continue
        for d in range(2):
            if fvar[f, d] >= 0:
                p_ref[fvar[f, d]] += ft.load_ref[d] / (sc.S * sc.L) / sc.k
                p_dead[fvar[f, d]] += ft.load_dead[d] / (sc.S * sc.L)
        if fvar[f, 2] >= 0:
            p_ref[fvar[f, 2]] += ft.moment_ref / (sc.S * sc.L**2) / sc.k
            p_dead[fvar[f, 2]] += ft.moment_dead / (sc.S * sc.L**2)
    if site.scale_all:  # lambda multiplies the dead loads and the weight too (Site.scale_all)
        p_ref = p_ref + p_dead / sc.k
        p_dead = np.zeros(n)
    nz_ = np.flatnonzero(p_ref)
    eq.add(list(nz_), list(p_ref[nz_]), 1.0)
    q -= p_dead
    if velocity is None:
        sol = solve_conic(q, eq, ineq, soc, n, tol=tol, refine=needs_refinement(site.materials))
        x = sol.x
    else:  # evaluate a given field (velocities of all nodes (n_nodes + n_edges, 2), footing motions)
        vel_in, fv_in = velocity[0], np.asarray(velocity[1], float)
        rot_in = np.asarray(velocity[2], float) if len(velocity) > 2 else np.zeros(len(fv_in))
        x = np.zeros(n)
        m_ = dof >= 0
        x[dof[m_]] = vel_in[m_]
        motion = np.column_stack([fv_in.reshape(-1, 2), rot_in.reshape(-1) * sc.L])  # theta in scaled units
        mf_ = fvar >= 0
        x[fvar[mf_]] = motion[mf_]
        for body in bodies:  # its amplitudes: the least-squares fit of the given field on its nodes
            if body["vars"].size:
                R = np.concatenate(
                    [_rigid_rows(xy_all[g], body["centre"]) @ body["basis"] for g in body["nodes"]]
                )
                x[body["vars"]] = np.linalg.lstsq(R, vel_in[body["nodes"]].ravel(), rcond=None)[0]
        given = velocity[3] if len(velocity) > 3 else {}
        for f, bk in beams.items():
            x[bk.w], x[bk.phi], u_n, u_e = carry_beam(given[f], bk.lay.x * sc.L, sc.L)
            if bk.u_el is not None:
                x[bk.u_node], x[bk.u_el] = u_n, u_e
        sol = ConicSolution(x, "given", 0, 0.0, len(soc.rhs) // 3)
    # ---- recomputation from the velocities alone
    vel = np.where(dof >= 0, x[np.maximum(dof, 0)], 0.0)
    fm = np.where(fvar >= 0, x[np.maximum(fvar, 0)], 0.0)  # (n_f, 3): U, W, theta (scaled)
    fv = fm[:, :2]

    def footing_vel(f: int, g: int, j: int = -1) -> np.ndarray:
        return np.array([sum(cf * x[col] for col, cf in t) for t in terms(f, g, j)])

    # a tied node takes its footing's motion exactly (the solver meets the tie rows to its tolerance
    # only): the field evaluated is then kinematically admissible, with no jump at the rough base
    for g, f in ties.items():
        fvg = footing_vel(f, g)
        for d in range(2):
            if dof[g, d] >= 0:
                vel[g, d] = fvg[d]

    # a rigid body's nodes take its motion exactly (its rows are met to the solver's tolerance only)
    for body in bodies:
        if body["vars"].size:
            for g in body["nodes"]:
                vel[g] = _rigid_rows(xy_all[g], body["centre"]) @ body["basis"] @ x[body["vars"]]

    ue, we = vel[nodes6, 0], vel[nodes6, 1]  # (n_el, 6)
    ex = np.einsum("evn,en->ev", G[..., 0], ue)
    ez = np.einsum("evn,en->ev", G[..., 1], we)
    gm = np.einsum("evn,en->ev", G[..., 1], ue) + np.einsum("evn,en->ev", G[..., 0], we)
    dev = np.hypot(ex - ez, gm)
    vol = ex + ez
    s_e = sinm[:, None]
    e_min = np.where(s_e > 0, np.maximum(dev, vol / np.where(s_e > 0, s_e, 1.0)), dev)
    # the flow-rule residual relative to the velocity scale: |eps_v - sin phi e| h / max |v|
    # (the mechanism's scale: a beam's own velocities count, which on a near-rigid soil are most of it)
    v_beam = [np.abs(x[np.concatenate([bk.w] + ([bk.u_el] if bk.u_el is not None else []))]).max()
              for bk in beams.values()]  # fmt: skip
    v_scale = max(np.abs(vel).max(), np.abs(fv).max(initial=0.0), *v_beam, 1e-300)
    h_el = np.sqrt(2.0 * A)[:, None]
    flow_res = float(np.max(np.abs(vol - s_e * e_min) * h_el) / v_scale)
    d_el = (c_cos * A / 3.0)[:, None] * e_min
    diss = d_el.sum(axis=1)
    # interface control points recomputed
    for _key, f, j, w, itf in cp_rows:
        ci, tphi = itf.strength
        a_, m_, b_ = be.p[j], n_nodes + be.edge[j], be.q[j]
        da, dm, db = (footing_vel(f, g, j) - vel[g] for g in (a_, m_, b_))
        bk = {0: da, 1: 2 * dm - 0.5 * (da + db), 2: db}[w]
        nx, nz = be.n[j]
        dn, dt = bk[0] * nx + bk[1] * nz, -bk[0] * nz + bk[1] * nx
        if itf.tension is not None:  # opening beyond dilation allowed: t_i d_n + (c - t_i tan phi) |d_t|
            flow_res = max(flow_res, max(tphi * abs(dt) - dn, 0.0) / v_scale)
            d_j = itf.tension * dn + (ci - itf.tension * tphi) * abs(dt)
            diss[be.el[j]] += d_j / sc.S * be.length[j] / 3.0
            continue
        s_need = abs(dt) if tphi == 0 else max(abs(dt), dn / tphi)
        flow_res = max(flow_res, abs(dn - tphi * s_need) / v_scale)
        diss[be.el[j]] += ci / sc.S * be.length[j] / 3.0 * s_need
    # beam hinges recomputed from w, phi and u
    beam_out = {}
    for f, bk in beams.items():
        el = beam_elements(be, bk.lay)
        beam_out[f] = hinge_dissipation(site.footings[f].beam, bk, x, el, diss, sc.S, sc.L)
    x_rec = np.zeros(n)  # the solution vector rebuilt from the recomputed velocities
    x_rec[dof[dof >= 0]] = vel[dof >= 0]
    x_rec[fvar[fvar >= 0]] = fm[fvar >= 0]
    for bk in beams.values():
        x_rec[bk.w], x_rec[bk.phi] = x[bk.w], x[bk.phi]
        if bk.u_el is not None:
            x_rec[bk.u_node], x_rec[bk.u_el] = x[bk.u_node], x[bk.u_el]
    pr, pd = float(p_ref @ x_rec), float(p_dead @ x_rec)
    with np.errstate(divide="ignore", invalid="ignore"):  # a ray of an unbounded program: P_ref ~ 0
        lam = (diss.sum() - pd) / pr / sc.k  # the objective is mu = k lambda (conic module's scaling)
    certified = bool(
        flow_res <= FLOW_TOL and pr > 0.0 and np.isfinite(lam) and "Infeasible" not in sol.status
    )
    # admissible whatever the status (the ray of an unbounded program too): a field the solver returns for
    # a primal-infeasible program (no mechanism) has flow-rule residuals of order one (FLOW_TOL comment)
    finite = bool(np.all(np.isfinite(x_rec)))
    admissible = bool(flow_res <= FLOW_TOL and finite and "PrimalInfeasible" not in sol.status)
    unit = 1.0 / (sc.S * sc.L * sc.k * pr)  # real velocities with a reference power of 1 N/m . m/s
    return UpperBound(
        lam=float(lam) if certified else float("inf"),
        lam_solver=float(q @ x) / sc.k,
        velocity=vel * unit,
        footing_velocity=fv * unit,
        footing_rotation=fm[:, 2] * unit / sc.L,
        beam={
            f: dict(
                x=beams[f].lay.x * sc.L,
                w=w * unit,
                phi=phi * unit / sc.L,
                hinge=rot * unit / sc.L,
                extension=ext * unit,
                u=None if un is None else un * unit,
                u_el=None if ue is None else ue * unit,
                el=beam_elements(be, beams[f].lay),
            )
            for f, (w, phi, rot, ext, un, ue) in beam_out.items()
        },
        dissipation=diss / (pr * sc.k),
        dead_power=pd / (pr * sc.k),
        strain=np.stack([ex, ez, gm], axis=2) * unit / sc.L,
        flow_residual=flow_res,
        p_ref=pr,
        time=sol.time,
        iterations=sol.iterations,
        status=sol.status,
        n_cones=sol.n_soc,
        n_rows=len(eq.rhs) + len(ineq.rhs) + len(soc.rhs),
        certified=certified,
        lam_recomputed=float(lam),
        admissible=admissible,
        power=(float(diss.sum()), pd, pr * sc.k),
    )


def footing_velocity_at(site: Site, upper: UpperBound, f: int, pts: np.ndarray) -> np.ndarray:
    """Footing ``f``'s velocity (n, 2) [m/s] at base points ``pts`` (n, 2) [m] in the field of ``upper``
    (a beam whose hinges extend: ``pts`` on one base edge, which moves with its element's u)."""
    ft = site.footings[f]
    if ft.beam is not None:
        b = upper.beam[f]
        if b["u_el"] is not None:  # hinges that extend: u of the element under the points' middle
            e = np.clip(np.searchsorted(b["x"], np.mean(pts[:, 0])) - 1, 0, len(b["u_el"]) - 1)
            u = np.full(len(pts), b["u_el"][e])
        else:
            u = np.full(len(pts), upper.footing_velocity[f, 0])
        return np.column_stack([u, np.interp(pts[:, 0], b["x"], b["w"])])
    return ft.velocity_at(np.append(upper.footing_velocity[f], upper.footing_rotation[f]), pts)
