"""Lower bound: a statically admissible stress field on linear-stress triangles, one SOCP, then certified.

Unknowns: the stresses (sig_x, sig_z, tau) at the three vertices of every triangle, each triangle with its
own nodes (layout ``sig[n_el, 3 vertices, 3 components]``, flat index 9 e + 3 k + c), and mu = k lambda.
Constraints (all linear in the nodal stresses, so met at the nodes means met everywhere):

- equilibrium in each triangle, d sig_x/dx + d tau/dz = 0, d tau/dx + d sig_z/dz = gamma (z up);
- on every interior edge, at both its ends, equal tractions (t_x, t_z) from the two triangles;
- on a free or loaded edge, t = -(p_dead + lambda p_ref) n at both ends; on a symmetry roller t . s = 0;
- under a rigid footing, the resultant of the soil tractions equals load_dead + lambda load_ref along each
  free translation (and, if the footing rotates, their moment about its centre moment_dead + lambda
  moment_ref), and at both ends of each edge the interface: smooth tau = 0, Coulomb |tau| <= c_i -
  sigma_n tan phi_i (two linear rows) and with a tension cut-off sigma_n <= t_i (one more), rough nothing
  (the soil's own strength governs);
- a bending footing (:class:`~ssi.limit.geometry.Beam`): its moment and axial force, from the base
  tractions and its loads (:mod:`ssi.limit.beam`), within its M-N polygon (without an interaction:
  -mp_hog <= M <= mp_sag) at the Bernstein points of every element;
- Mohr-Coulomb at every vertex as the 3-D cone ||(sig_x - sig_z, 2 tau)|| <= 2 c cos phi - (sig_x + sig_z)
  sin phi (Tresca: phi = 0), and, with a tension cut-off T, ||(sig_x - sig_z, 2 tau)|| <= 2 T - (sig_x +
  sig_z). A linear field in a convex set at the vertices stays in it inside the triangle. (The upper bound
  has no cut-off: its value is that of the material without one, still a ceiling for the one with it. A
  zero cut-off is met with equality on a traction-free surface and then rarely certifies.)

Certification (never the solver's status): the program is solved with the first component of each yield
cone shrunk by the factor (1 - ``margin``); the returned field is projected onto the equality constraints
(least-squares, the sparse KKT system of min ||x - x0|| s.t. A x = b, with refinement); every vertex is then
checked against the true cone and every interface row against its inequality, and lambda is recomputed
from the projected field. ``certified`` says whether all checks held, ``reason`` why not.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ._common import boundary_edges, gradients, interior_edges, scales, strength
from .beam import beam_layout, lower_bound_statics
from .conic import ConicSolution, Rows, needs_refinement, solve_conic
from .geometry import Site
from .mesh import TriMesh

__all__ = ["LowerBound", "lower_bound"]

APEX_TOL = 1e-9  # in units of the problem's stress scale S: a vertex this close to the apex counts as on it
CUT_TOL = 1e-12  # likewise on a tension cut-off (round-off of the projected field)
# A cohesionless cone has no inside at its apex, so a projected near-zero stress can only be on the cone to
# round-off: vertices of c = 0 materials outside it by at most APEX_SLACK S (measured on the zoo's sand
# scenes: up to 1.1e-8 S, at stresses of 1e-8 .. 1e-7 S beside a footing's edge) are accepted, and the
# bound is then rigorous for the soil with cohesion ``apex_slack`` / (2 cos phi) [Pa] added, reported as such
# (its share of the capacity, about N_c times that cohesion over the footing, is below 1e-6 of it here).
APEX_SLACK = 1e-7
# interface rows met to round-off (violations of 1e-23 .. 1e-20 S measured); a cohesionless joint
# (|tau| <= -sigma_n tan phi_i, right-hand side 0) has the same apex as a cohesionless soil and takes the same
# slack (violations of 3e-11 .. 3.2e-10 S measured on zoo scenes 66 and 80)
ITF_TOL = 1e-12


@dataclass
class LowerBound:
    """A certified lower bound. ``lam`` the certified load factor (NaN if not certified), ``lam_solver`` the
    solver's, ``lam_projected`` that of the projected field (= lam when certified); ``stress``
    (n_el, 3, 3) [Pa] the projected field (sig_x, sig_z, tau at each vertex); ``beam``: per bending
    footing, dict of ``M_left`` / ``M_right`` (n_k,) [N m/m] the moment just left / right of each beam
    node, ``N_left`` / ``N_right`` [N/m] the axial force, and ``utilisation`` the largest (a_N N + a_M M) /
    b over the polygon's facets and the beam's Bernstein points (|M| / M_p without an interaction);
    ``min_margin`` the smallest distance inside the true yield cone over all vertices [Pa] (negative:
    outside); ``n_apex`` vertices at the apex within APEX_TOL S; ``eq_residual`` the largest equality
    residual after projection [Pa]; time [s], iterations, status, n_cones, n_rows of the solve."""

    lam: float
    lam_solver: float
    lam_projected: float
    certified: bool
    reason: str
    stress: np.ndarray
    beam: dict
    min_margin: float
    n_apex: int
    eq_residual: float
    time: float
    iterations: int
    status: str
    n_cones: int
    n_rows: int
    yield_work: np.ndarray | None = None


def _assemble(site: Site, mesh: TriMesh, margin: float):
    sc = scales(site)
    xy = mesh.xy / sc.L
    n_el = mesh.n_el
    n = 9 * n_el + 1
    imu = n - 1
    eq, ineq, soc = Rows(), Rows(), Rows()
    b, c, A = gradients(xy, mesh.tri)
    gam = np.array([m.gamma for m in site.materials])[mesh.material] * sc.L / sc.S
    base = 9 * np.arange(n_el)
    # equilibrium (times 2A): sum_k b_k sx_k + c_k tau_k = 0 ; sum_k b_k tau_k + c_k sz_k = 2 A gamma
    r = np.repeat(np.arange(n_el), 6)
    cols = np.stack([base + 0, base + 2, base + 3, base + 5, base + 6, base + 8], axis=1).ravel()
    vals = np.stack([b[:, 0], c[:, 0], b[:, 1], c[:, 1], b[:, 2], c[:, 2]], axis=1).ravel()
    eq.add_many(r, cols, vals, np.zeros(n_el))
    cols = np.stack([base + 2, base + 1, base + 5, base + 4, base + 8, base + 7], axis=1).ravel()
    eq.add_many(r, cols, vals, 2.0 * A * gam)
    # boundary edges
    be = boundary_edges(mesh, xy)
    cen = [np.zeros(2) if ft.centre is None else np.asarray(ft.centre) / sc.L for ft in site.footings]
    prescribed = {}  # flat index of a vertex on a free edge: (nx, nz, stress zero, p_dead, p_ref)
    # a cohesionless triangle vertex at a point of a traction-free edge: its traction on some plane is zero
    # (on the free edge, or on an interior edge shared with a vertex that has it), and a Mohr circle through
    # the origin inside the Coulomb wedge is a point: the only admissible stress is zero. Stated as such,
    # the certified field sits exactly on the apex there instead of 1e-10 outside it
    free_nodes = set()
    for j in range(len(be.p)):
        bnd = site.segments[be.seg[j]][2]
        if bnd.traction_free:
            free_nodes.update((int(be.p[j]), int(be.q[j])))
    cohesionless = np.array([m.c == 0.0 and not m.rigid for m in site.materials])[mesh.material]
    zero = set()
    for e, v in zip(*np.nonzero(np.isin(mesh.tri, list(free_nodes)) & cohesionless[:, None])):
        zero.add(int(9 * e + 3 * v))
        for cc in range(3):
            eq.add([9 * e + 3 * v + cc], [1.0], 0.0)
    # footing: cols, x-vals, z-vals of the resultant, moment-vals about its centre
    F = {i: [[], [], [], []] for i in range(len(site.footings))}
    for j in range(len(be.p)):
        bnd = site.segments[be.seg[j]][2]
        nx, nz = be.n[j]
        for end, loc in enumerate((be.lp[j], be.lq[j])):
            s0 = 9 * be.el[j] + 3 * loc
            tx = ([s0, s0 + 2], [nx, nz])
            tz = ([s0 + 2, s0 + 1], [nx, nz])
            if bnd.kind == "free":
                g = be.p[j] if end == 0 else be.q[j]  # this end's node: a linear dead pressure's value here
                pd, pr = bnd.dead_at(*mesh.xy[g]) / sc.S, bnd.pressure_ref / sc.S
                first = prescribed.get(s0)
                if first is not None:
                    # a corner of the boundary inside one triangle (a trench wall's top, a kink of the
                    # ground): the first edge's rows fix sigma n1; of this edge's two rows only the one
                    # along its own normal is new (the other is their consistency, implied when the two
                    # tractions agree and dependent rows are kept out)
                    if s0 not in zero and abs(first[0] - nx) + abs(first[1] - nz) > 1e-9:
                        sn_cols = [s0, s0 + 2, s0 + 1, imu]
                        eq.add(sn_cols, [nx * nx, 2.0 * nx * nz, nz * nz, pr / sc.k], -pd)
                    continue
                prescribed[s0] = (nx, nz, s0 in zero, pd, pr)
                if s0 in zero:
                    continue
                eq.add(tx[0] + [imu], tx[1] + [pr * nx / sc.k], -pd * nx)
                eq.add(tz[0] + [imu], tz[1] + [pr * nz / sc.k], -pd * nz)
            elif bnd.kind == "symmetry":  # t . s = -nz t_x + nx t_z = 0
                eq.add([s0, s0 + 2, s0 + 2, s0 + 1], [-nz * nx, -nz * nz, nx * nx, nx * nz], 0.0)
            elif bnd.kind == "footing":
                f = F[bnd.footing]
                f[0] += [s0, s0 + 2, s0 + 1]
                h = 0.5 * be.length[j]
                f[1] += [h * nx, h * nz, 0.0]
                f[2] += [0.0, h * nx, h * nz]
                ft = site.footings[bnd.footing]
                if ft.rotates:
                    # int (r_x t_z - r_z t_x) ds of linear r and t: this end's traction times
                    # L/6 (2 r_here + r_other), r the lever arm from the centre
                    here, other = (be.p[j], be.q[j]) if end == 0 else (be.q[j], be.p[j])
                    lj = be.length[j]
                    cx, cz = (2.0 * xy[here] + xy[other]) * lj / 6.0 - 0.5 * lj * cen[bnd.footing]
                    f[3] += [-cz * nx, cx * nx - cz * nz, cx * nz]
                else:
                    f[3] += [0.0, 0.0, 0.0]
                itf = site.interface_of(bnd)
                # sigma_n = nx t_x + nz t_z ; tau = -nz t_x + nx t_z
                sn = ([s0, s0 + 2, s0 + 1], [nx * nx, 2 * nx * nz, nz * nz])
                ta = ([s0, s0 + 2, s0 + 1], [-nz * nx, nx * nx - nz * nz, nx * nz])
                if itf.kind == "smooth":
                    eq.add(ta[0], ta[1], 0.0)
                elif itf.kind == "coulomb":
                    ci, tphi = itf.strength
                    for sgn in (1.0, -1.0):
                        vals = [tphi * v for v in sn[1]] + [sgn * v for v in ta[1]]
                        ineq.add(sn[0] + ta[0], vals, ci / sc.S)
                    if itf.tension is not None:  # the cut-off sigma_n <= t_i
                        ineq.add(sn[0], sn[1], itf.tension / sc.S)
    # traction continuity on interior edges, at both ends. Where both triangles have their traction
    # prescribed on the same free boundary line at that end, the component along the boundary normal is
    # implied (n_b . (sig1 - sig2) n = n . (sig1 - sig2) n_b = 0): only the tangential row is kept, and no
    # row where both stresses are zero -- the rows stay linearly independent
    e1, k1, e2, k2, _ = interior_edges(mesh)
    t1, t2 = mesh.tri[e1], mesh.tri[e2]
    ia, ib = (k1 + 1) % 3, (k1 + 2) % 3
    ga, gb = t1[np.arange(len(e1)), ia], t1[np.arange(len(e1)), ib]
    d = xy[gb] - xy[ga]
    nrm = np.stack([d[:, 1], -d[:, 0]], axis=1) / np.hypot(d[:, 0], d[:, 1])[:, None]
    for g, i1 in ((ga, ia), (gb, ib)):
        i2 = np.argmax(t2 == g[:, None], axis=1)
        s1, s2 = 9 * e1 + 3 * i1, 9 * e2 + 3 * i2
        for r in range(len(e1)):
            nx, nz = nrm[r]
            a, b_ = int(s1[r]), int(s2[r])
            # t_x = nx sx + nz tau ; t_z = nx tau + nz sz
            tx = ([a, a + 2, b_, b_ + 2], [nx, nz, -nx, -nz])
            tz = ([a + 2, a + 1, b_ + 2, b_ + 1], [nx, nz, -nx, -nz])
            if a in zero and b_ in zero:
                continue
            pa, pb = prescribed.get(a), prescribed.get(b_)
            same = pa is not None and pb is not None and abs(pa[0] - pb[0]) + abs(pa[1] - pb[1]) < 1e-9
            # implied only where both prescribed tractions are the same: at a jump of the surface load (the
            # edge of a flexible footing) the normal row is kept, a real condition on the field
            if same and pa[3:] == pb[3:]:
                if pa[2] and pb[2]:
                    continue
                sx_, sz_ = -pa[1], pa[0]  # boundary tangent
                eq.add(tx[0] + tz[0], [sx_ * v for v in tx[1]] + [sz_ * v for v in tz[1]], 0.0)
                continue
            eq.add(*tx, 0.0)
            eq.add(*tz, 0.0)
    for i, ft in enumerate(site.footings):
        cols, vx, vz, vm = F[i]
        for d_, vals in (("x", vx), ("z", vz)):
            ax = 0 if d_ == "x" else 1
            if d_ in ft.moves:
                fr = ft.load_ref[ax] / (sc.S * sc.L)
                fd = ft.load_dead[ax] / (sc.S * sc.L)
                eq.add(cols + [imu], vals + [-fr / sc.k], fd)
        if ft.rotates:  # the moment of the base tractions about the centre balances the applied moment
            mr = ft.moment_ref / (sc.S * sc.L**2)
            md = ft.moment_dead / (sc.S * sc.L**2)
            eq.add(cols + [imu], vm + [-mr / sc.k], md)
    # a bending footing: (N, M) within its polygon at the Bernstein points of every element (shrunk by the
    # margin in the solve, checked against the true capacity in the certification)
    n_itf = len(ineq.rhs)
    beams = {}
    for f, ft in enumerate(site.footings):
        if ft.beam is None:
            continue
        lay = beam_layout(site, f, be, xy, sc.L)
        st = lower_bound_statics(site, f, lay, be, n, imu, sc.S, sc.L, sc.k)
        for a_n, a_m, b_ in st.facets:  # a_N N + a_M M <= b (1 - margin) at every control point
            G = (a_n * st.BN + a_m * st.B).tocoo() if a_n != 0.0 else (a_m * st.B).tocoo()
            ineq.add_many(G.row, G.col, G.data, (1.0 - margin) * b_ - a_n * st.bN0 - a_m * st.b0)
        beams[f] = st
    # yield cones at every vertex: s = (f (2c cos - (sx+sz) sin), sx - sz, 2 tau) in SOC_3, s = b - A x; none
    # in a rigid material (it never yields), so the cones are those of the yielding vertices, in order
    mats = site.materials
    two_c, sphi, _ = (np.array(v) for v in zip(*(strength(m, sc.S) for m in mats)))
    f = 1.0 - margin
    yielding = _yielding_vertices(site, mesh)
    nv = len(yielding)
    s0 = 3 * yielding  # flat index of sig_x of each vertex
    m_v = np.repeat(mesh.material, 3)[yielding]
    rr = np.arange(nv) * 3
    soc.add_many(
        np.concatenate([rr, rr, rr + 1, rr + 1, rr + 2]),
        np.concatenate([s0, s0 + 1, s0, s0 + 1, s0 + 2]),
        np.concatenate([f * sphi[m_v], f * sphi[m_v], -np.ones(nv), np.ones(nv), -2 * np.ones(nv)]),
        np.stack([f * two_c[m_v], np.zeros(nv), np.zeros(nv)], axis=1).ravel(),
    )
    cut = [m.tension_cutoff for m in mats]
    if any(t is not None for t in cut):
        for v in yielding:
            t = cut[np.repeat(mesh.material, 3)[v]]
            if t is None:
                continue
            # the cut-off lowered to T (1 - margin): shifted, not scaled, which would also shrink the room
            # left of sig_1 = T. A zero cut-off leaves no room on a traction-free surface (sig_1 = sig_z = 0
            # there): such a field is certified only if the solver's point happens to be inside
            soc.add([3 * v, 3 * v + 1], [1.0, 1.0], 2 * t * f / sc.S)
            soc.add([3 * v, 3 * v + 1], [-1.0, 1.0], 0.0)
            soc.add([3 * v + 2], [-2.0], 0.0)
    q = np.zeros(n)
    q[imu] = -1.0
    eq = _independent_local_rows(eq, 9 * n_el)
    if site.scale_all:
        if beams:
            raise NotImplementedError("scale_all with a bending footing (Beam): its M-N rows hold dead parts")
        eq = _scale_all_rows(eq, imu, sc.k)
    return sc, eq, ineq, soc, q, n, n_itf, beams


def _yielding_vertices(site: Site, mesh: TriMesh) -> np.ndarray:
    """The flat vertex indices 3 e + k of the elements whose material yields (not rigid), in order."""
    rigid = np.array([m.rigid for m in site.materials], bool)[mesh.material]
    return np.flatnonzero(np.repeat(~rigid, 3))


def _scale_all_rows(eq: Rows, imu: int, k: float) -> Rows:
    """Every equality row A sig + a mu = b (b: the dead loads and the weight) as A sig + (a - b / k) mu = 0:
    lambda = mu / k then multiplies the dead loads and the weight as well as the reference loads
    (:attr:`ssi.limit.geometry.Site.scale_all`). Only equality rows carry loads; the inequality and cone
    rows' right-hand sides are strengths and stay."""
    rhs = np.asarray(eq.rhs, float)
    r = np.flatnonzero(rhs != 0.0)
    out = Rows(list(eq.rows), list(eq.cols), list(eq.vals), [0.0] * len(rhs))
    out.rows.extend(r.tolist())
    out.cols.extend([imu] * len(r))
    out.vals.extend((-rhs[r] / k).tolist())
    return out


def _independent_local_rows(eq: Rows, n_sig: int) -> Rows:
    """``eq`` without the rows that repeat other rows on the same vertex: where two boundary conditions
    meet at a domain corner (a free top and a symmetry roller: the roller's tau = 0 is already in t = 0),
    the rows acting on that vertex's three stresses alone are reduced to an independent set (greedy, in
    order, by the rank of the small dense block)."""
    vals = np.asarray(eq.vals, float)
    nz = vals != 0.0  # a stored zero (the load factor's coefficient on an unloaded edge) couples nothing
    rows = np.asarray(eq.rows)[nz]
    cols = np.asarray(eq.cols)[nz]
    vals = vals[nz]
    n_rows = len(eq.rhs)
    lo = np.full(n_rows, np.iinfo(np.int64).max)
    hi = np.full(n_rows, -1)
    np.minimum.at(lo, rows, cols)
    np.maximum.at(hi, rows, cols)
    local = (hi < n_sig) & (lo // 3 == hi // 3) & (hi >= 0)
    groups: dict[int, list[int]] = {}
    for r in np.flatnonzero(local):
        groups.setdefault(int(lo[r] // 3), []).append(int(r))
    drop = np.zeros(n_rows, bool)
    entries = {}
    for r, c, v in zip(
        rows[np.isin(rows, np.flatnonzero(local))],
        cols[np.isin(rows, np.flatnonzero(local))],
        vals[np.isin(rows, np.flatnonzero(local))],
    ):
        entries.setdefault(int(r), np.zeros(3))[int(c) % 3] += v
    for g in groups.values():
        if len(g) < 2:
            continue
        kept = []
        for r in g:
            block = np.array([entries[k] for k in kept + [r]])
            if np.linalg.matrix_rank(block, tol=1e-10 * np.abs(block).max()) > len(kept):
                kept.append(r)
            else:
                drop[r] = True
    if not drop.any():
        return eq
    out = Rows()
    keep_rows = np.flatnonzero(~drop)
    new_index = -np.ones(n_rows, np.int64)
    new_index[keep_rows] = np.arange(len(keep_rows))
    m = ~drop[rows]
    out.add_many(new_index[rows[m]], cols[m], vals[m], np.asarray(eq.rhs)[keep_rows])
    return out


def _project(A: sp.csr_matrix, b: np.ndarray, x0: np.ndarray, steps: int = 4) -> np.ndarray:
    """x closest to x0 with A x = b: the KKT system [[I, A^T], [A, -eps I]] (eps regularises rows that are
    linearly dependent), with iterative refinement on the unregularised residual."""
    m, n = A.shape
    eps = 1e-12
    K = sp.bmat([[sp.identity(n), A.T], [A, -eps * sp.identity(m)]], format="csc")
    lu = spla.splu(K)
    x = x0.copy()
    for _ in range(steps):
        r = b - A @ x
        if np.max(np.abs(r)) < 1e-15:
            break
        sol = lu.solve(np.concatenate([np.zeros(n), r]))
        x += sol[:n]
    return x


def lower_bound(
    site: Site, mesh: TriMesh, margin: float = 1e-4, tol: float = 1e-9, stress: tuple | None = None
) -> LowerBound:
    """The certified lower bound of the load factor lambda of ``site`` on ``mesh`` (module docstring).
    ``margin``: relative shrink of the yield cones in the solve (dimensionless); ``tol``: Clarabel's
    tolerances. ``stress``: (sig (n_el, 3, 3) [Pa], lam) a field to certify instead of solving (e.g. a
    coarser mesh's field carried to a nested finer mesh)."""
    if not 0.0 <= margin < 0.1:
        raise ValueError(f"margin must be in [0, 0.1), got {margin!r}")
    sc, eq, ineq, soc, q, n, n_itf, beams = _assemble(site, mesh, margin)
    if stress is None:
        sol = solve_conic(q, eq, ineq, soc, n, tol=tol, refine=needs_refinement(site.materials))
    else:
        x_in = np.concatenate([np.asarray(stress[0], float).ravel() / sc.S, [stress[1] * sc.k]])
        sol = ConicSolution(x_in, "given", 0, 0.0, len(soc.rhs) // 3)
    lam_solver = sol.x[-1] / sc.k
    Ae, be = eq.matrix(n)
    rs = 1.0 / np.maximum(abs(Ae).max(axis=1).toarray().ravel(), 1e-300)
    Ae, be = sp.diags(rs) @ Ae, rs * be
    x = _project(Ae.tocsr(), be, sol.x)
    res = float(np.max(np.abs(Ae @ x - be))) if len(be) else 0.0
    sig = x[:-1].reshape(mesh.n_el, 3, 3)
    # true cones
    two_c, sphi, _ = (np.array(v) for v in zip(*(strength(m, sc.S) for m in site.materials)))
    mv = mesh.material
    cohesionless_el = np.array([m.c == 0.0 and not m.rigid for m in site.materials])[mv]
    rigid_el = np.array([m.rigid for m in site.materials], bool)[mv]
    sx, sz, tau = sig[..., 0], sig[..., 1], sig[..., 2]
    rad = np.hypot(sx - sz, 2 * tau)
    top = two_c[mv][:, None] - (sx + sz) * sphi[mv][:, None]
    top[rigid_el] = np.inf  # no yield condition in a rigid material: every stress is inside
    marg = top - rad
    cuts = [np.inf if m.tension_cutoff is None else 2 * m.tension_cutoff / sc.S for m in site.materials]
    cuts = np.array(cuts)
    cut_marg = cuts[mv][:, None] - (sx + sz) - rad
    apex = (np.abs(top) <= APEX_TOL) & (rad <= APEX_TOL)
    # on the cut-off to round-off (CUT_TOL S): a free surface under a zero cut-off, where sig_1 = sig_z = 0
    on_cut = np.abs(cut_marg) <= CUT_TOL
    slack = (marg <= 0.0) & ~apex & cohesionless_el[:, None] & (marg >= -APEX_SLACK)
    bad = ((marg <= 0.0) & ~apex & ~slack) | ((cut_marg <= 0.0) & ~on_cut)
    marg = np.minimum(marg, np.where(on_cut, np.inf, cut_marg))
    Ai, bi = ineq.matrix(n)
    itf_viol = Ai[:n_itf] @ x - bi[:n_itf] if n_itf else np.zeros(0)
    itf_apex = bi[:n_itf] == 0.0 if n_itf else np.zeros(0, bool)
    itf_slack = itf_apex & (itf_viol > ITF_TOL) & (itf_viol <= APEX_SLACK)
    ineq_bad = int(np.sum((itf_viol > ITF_TOL) & ~itf_slack))
    beam_out, beam_bad = {}, 0
    for f, st in beams.items():
        over = st.facet_values(x)  # a_N N + a_M M - b at the control points, <= 0 inside the polygon
        beam_bad += int(np.sum(over > 0.0))
        unit = sc.S * sc.L**2
        beam_out[f] = dict(
            M_left=(st.M_left[0] @ x + st.M_left[1]) * unit,
            M_right=(st.M_right[0] @ x + st.M_right[1]) * unit,
            N_left=(st.N_left[0] @ x + st.N_left[1]) * sc.S * sc.L,
            N_right=(st.N_right[0] @ x + st.N_right[1]) * sc.S * sc.L,
            utilisation=float(np.max(1.0 + over / st.facets[:, 2:3])),
        )
    reasons = []
    if not np.all(np.isfinite(x)):
        reasons.append("the solver returned no finite point")
    if res > 1e-10:
        reasons.append(f"equality residual {res:.2e} S after projection")
    if bad.any():
        nb = int(bad.sum())
        reasons.append(f"{nb} vertices outside or on the yield surface (min margin {marg.min():.2e} S)")
    if ineq_bad:
        reasons.append(f"{ineq_bad} interface rows violated")
    if beam_bad:
        reasons.append(f"{beam_bad} beam moments beyond M_p")
    certified = not reasons
    # the lower bound's own refinement indicator: at each vertex cone the product of the first components of
    # the dual point z (the plastic multiplier of the program's dual mechanism) and the slack s (the cone's
    # radius there), equal at the optimum to the stress power of that mechanism's strain rate (z . s = 0 in
    # the cone): where the yield condition binds and limits lambda, cohesionless soil included (lambda
    # units, summed per element)
    yield_work = None
    if sol.z is not None and sol.s is not None and np.all(np.isfinite(sol.z)) and np.all(np.isfinite(sol.s)):
        yielding = _yielding_vertices(site, mesh)
        nv = len(yielding)
        r0 = len(sol.z) - 3 * sol.n_soc  # the first cone row
        w = np.zeros(3 * mesh.n_el)
        w[yielding] = sol.s[r0 : r0 + 3 * nv : 3] * sol.z[r0 : r0 + 3 * nv : 3]
        yield_work = np.maximum(w, 0.0).reshape(mesh.n_el, 3).sum(axis=1) / sc.k
    apex_gap = max(float(-marg[slack].min(initial=0.0)), float(itf_viol[itf_slack].max(initial=0.0)))
    lam = x[-1] / sc.k
    return LowerBound(
        lam=float(lam) if certified else math.nan,
        lam_solver=float(lam_solver),
        lam_projected=float(lam),
        certified=certified,
        reason="; ".join(reasons)
        if reasons
        else f"certified ({int(apex.sum())} vertices at the apex, {int(on_cut.sum())} on the cut-off"
        + (
            f", {int(slack.sum()) + int(itf_slack.sum())} cohesionless vertices or joint rows within "
            f"{apex_gap:.1e} S of the apex: rigorous with at most {apex_gap * sc.S:.2g} Pa of cohesion added)"
            if slack.any() or itf_slack.any()
            else ")"
        ),
        stress=sig * sc.S,
        beam=beam_out,
        min_margin=float(np.min(np.where(apex, np.inf, marg), initial=np.inf)) * sc.S,
        n_apex=int(apex.sum()),
        eq_residual=res * sc.S,
        time=sol.time,
        iterations=sol.iterations,
        status=sol.status,
        n_cones=sol.n_soc,
        n_rows=Ae.shape[0] + Ai.shape[0] + 3 * sol.n_soc,
        yield_work=yield_work,
    )
