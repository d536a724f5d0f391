"""Unstructured 8-node serendipity meshes of a :class:`~ssi.core.geometry.Geometry` by gmsh.

Each cell of the geometry is one plane surface; the surfaces share their edges, so the mesh conforms to every
layer boundary and every point of the geometry (foundation ends, load points, boreholes). gmsh triangulates
(frontal-Delaunay for quadrilaterals), recombines the triangles into quadrilaterals (Blossom), and raises the
order to an incomplete second order: 8-node quadrilaterals, whose node order (corners counter-clockwise, then
the mid-side nodes of edges 0-1, 1-2, 2-3, 3-0) is that of :func:`ssi.core.shapes.serendipity8`. A size field
refines the mesh towards the ``refine_points`` (the foundations' edges): size ``h_fine`` there, growing by
``growth - 1`` per metre of distance up to ``h_coarse``.

gmsh is driven from plain Python (never from numba), single-threaded and with fixed options, so the same
geometry gives the same mesh. Every element is checked (:func:`check_quality`): a Jacobian that is not
positive at a Gauss point or a corner angle outside [``min_angle``, ``MAX_ANGLE_DEG``] raises
:class:`MeshQualityError`; ``min_angle`` is ``MIN_ANGLE_DEG``, or half the geometry's sharpest cell corner
where a pinch-out or thin wedge is sharper than that (no mesh of such a cell can do better at its tip), and
the largest angle accepted is max(``MAX_ANGLE_DEG``, 180 - ``min_angle``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import Geometry

MIN_ANGLE_DEG = 15.0  # corner angles of a quadrilateral below this are slivers (stiffness ill-conditioned)
MAX_ANGLE_DEG = 165.0  # above this the element is nearly a triangle (Jacobian near zero at that corner)

__all__ = ["MeshQualityError", "UnstructuredMesh", "check_quality", "mesh_geometry", "q8_jacobians"]


class MeshQualityError(ValueError):
    """An element of a generated mesh is inverted or distorted beyond the angle limits."""


@dataclass
class UnstructuredMesh:
    """A Q8 mesh: ``xy`` (n_nodes, 2) [m], ``conn`` (n_el, 8), ``el_layer`` (n_el,) region of each element,
    ``el_cell`` (n_el,) geometry cell of each element, ``geometry`` the description it meshes."""

    xy: np.ndarray
    conn: np.ndarray
    el_layer: np.ndarray
    el_cell: np.ndarray
    geometry: Geometry
    quality: dict | None = None

    def nodes_on_segments(self, tag: str, tol: float = 1e-7) -> np.ndarray:
        """Ids of the nodes on the geometry's segments tagged ``tag`` (within ``tol`` [m] relative to the
        site's size), ordered by x then z."""
        g = self.geometry
        scale = max(1.0, float(np.ptp(g.points, axis=0).max()))
        on = np.zeros(len(self.xy), bool)
        for a, b in g.segments_tagged(tag):
            on |= _distance_to_segment(self.xy, g.points[a], g.points[b]) < tol * scale
        ids = np.flatnonzero(on)
        return ids[np.lexsort((self.xy[ids, 1], self.xy[ids, 0]))]


def _distance_to_segment(p, a, b):
    ab = b - a
    t = np.clip(((p - a) @ ab) / (ab @ ab), 0.0, 1.0)
    return np.hypot(*(p - (a + t[:, None] * ab)).T)


def mesh_geometry(
    geometry: Geometry,
    h_fine: float,
    h_coarse: float,
    growth: float = 1.25,
    refine_points: np.ndarray | None = None,
    min_angle: float | None = None,
) -> UnstructuredMesh:
    """Mesh ``geometry`` into Q8 elements with gmsh (see the module docstring). ``h_fine``, ``h_coarse``
    [m]: element sizes at the ``refine_points`` (k, 2) [m] and far from them (everywhere ``h_coarse`` without
    refine points); ``growth`` [-]: the size grows by (growth - 1) per metre of distance from them;
    ``min_angle`` [deg] the smallest corner angle accepted (None: see the module docstring)."""
    import gmsh  # imported here: only generated meshes need it

    if not (h_fine > 0.0 and h_coarse >= h_fine and growth > 1.0):
        raise ValueError(
            f"mesh sizes need 0 < h_fine <= h_coarse and growth > 1, got h_fine={h_fine!r}, "
            f"h_coarse={h_coarse!r}, growth={growth!r}"
        )
    pts = geometry.points
    was_initialized = gmsh.isInitialized()
    if not was_initialized:
        gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("ssi_site")
        geo = gmsh.model.geo
        ptag = [geo.addPoint(float(x), float(z), 0.0, 2.0 * h_coarse) for x, z in pts]
        line_of: dict = {}
        for a, b in geometry.segments:
            line_of[(int(a), int(b))] = geo.addLine(ptag[a], ptag[b])
        surfaces = []
        for cell in geometry.cells:
            loop = []
            for a, b in zip(cell, cell[1:] + cell[:1]):
                tag = line_of.get((a, b))
                loop.append(tag if tag is not None else -line_of[(b, a)])
            surfaces.append(geo.addPlaneSurface([geo.addCurveLoop(loop)]))
        geo.synchronize()
        field = gmsh.model.mesh.field
        if refine_points is not None and len(refine_points):
            rp = np.asarray(refine_points, np.float64).reshape(-1, 2)
            targets = [geo.addPoint(float(x), float(z), 0.0, h_fine) for x, z in rp]
            geo.synchronize()
            dist = field.add("Distance")
            field.setNumbers(dist, "PointsList", targets)
            thr = field.add("Threshold")
            field.setNumber(thr, "InField", dist)
            field.setNumber(thr, "SizeMin", 2.0 * h_fine)
            field.setNumber(thr, "SizeMax", 2.0 * h_coarse)
            field.setNumber(thr, "DistMin", 0.5 * h_fine)
            field.setNumber(thr, "DistMax", 0.5 * h_fine + (h_coarse - h_fine) / (growth - 1.0))
            field.setAsBackgroundMesh(thr)
        else:
            const = field.add("MathEval")
            field.setString(const, "F", repr(2.0 * float(h_coarse)))
            field.setAsBackgroundMesh(const)
        for name, value in (
            ("Mesh.MeshSizeFromPoints", 0),
            ("Mesh.MeshSizeFromCurvature", 0),
            ("Mesh.MeshSizeExtendFromBoundary", 0),
            ("Mesh.Algorithm", 8),  # frontal-Delaunay for quadrilaterals
            ("Mesh.RecombinationAlgorithm", 1),  # Blossom
            ("Mesh.SubdivisionAlgorithm", 1),  # split what is left into quadrilaterals: all quads
            ("Mesh.RecombineAll", 1),
            ("Mesh.ElementOrder", 2),
            ("Mesh.SecondOrderIncomplete", 1),  # 8-node serendipity, no centre node
            ("Mesh.RandomFactor", 1e-9),
        ):
            gmsh.option.setNumber(name, value)
        gmsh.model.mesh.generate(2)  # (sizes doubled above: the subdivision halves every element)
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        index = np.full(int(node_tags.max()) + 1, -1, np.int64)
        index[node_tags.astype(np.int64)] = np.arange(len(node_tags))
        xy_all = coords.reshape(-1, 3)[:, :2]
        conn, el_cell = [], []
        for k, s in enumerate(surfaces):
            types, _, nodes = gmsh.model.mesh.getElements(2, s)
            for t, n in zip(types, nodes):
                if t != 16:  # 16: the 8-node second-order quadrilateral
                    raise MeshQualityError(
                        f"gmsh left elements of type {int(t)} (not 8-node quadrilaterals) in cell {k}: "
                        "the recombination failed; change h_fine/h_coarse"
                    )
                c = index[n.astype(np.int64)].reshape(-1, 8)
                conn.append(c)
                el_cell.append(np.full(len(c), k, np.int64))
        gmsh.model.remove()
    finally:
        if not was_initialized:
            gmsh.finalize()
    conn = np.vstack(conn)
    el_cell = np.concatenate(el_cell)
    used = np.unique(conn)  # drop the refine points and any node no element uses; keep gmsh's order
    new = np.full(len(xy_all), -1, np.int64)
    new[used] = np.arange(len(used))
    xy = np.ascontiguousarray(xy_all[used])
    conn = new[conn]
    conn = _counter_clockwise(xy, conn)
    mesh = UnstructuredMesh(xy, conn, geometry.cell_region[el_cell], el_cell, geometry)
    if min_angle is None:
        min_angle = min(MIN_ANGLE_DEG, 0.5 * geometry.min_corner_angle())
    mesh.quality = check_quality(mesh.xy, mesh.conn, min_angle)
    return mesh


def _counter_clockwise(xy, conn):
    """Reverse the elements listed clockwise (corners and mid-side nodes together)."""
    c = xy[conn[:, :4]]
    area = 0.5 * np.sum(c[:, :, 0] * np.roll(c[:, :, 1], -1, 1) - np.roll(c[:, :, 0], -1, 1) * c[:, :, 1], 1)
    conn = conn.copy()
    flip = area < 0.0
    conn[flip] = conn[flip][:, [0, 3, 2, 1, 7, 6, 5, 4]]
    return conn


def q8_jacobians(xy: np.ndarray, conn: np.ndarray, n_gauss: int = 3) -> np.ndarray:
    """det J (n_el, n_gauss^2) of the Q8 elements at the Gauss points (plain numpy: a check, not a kernel)."""
    g, _ = np.polynomial.legendre.leggauss(n_gauss)
    xi, eta = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    xc = np.array([-1, 1, 1, -1, 0, 1, 0, -1], float)
    ec = np.array([-1, -1, 1, 1, -1, 0, 1, 0], float)
    dxi = np.empty((len(xi), 8))
    deta = np.empty((len(xi), 8))
    for a in range(8):
        if a < 4:
            dxi[:, a] = 0.25 * xc[a] * (1 + eta * ec[a]) * (2 * xi * xc[a] + eta * ec[a])
            deta[:, a] = 0.25 * ec[a] * (1 + xi * xc[a]) * (xi * xc[a] + 2 * eta * ec[a])
        elif xc[a] == 0:
            dxi[:, a] = -xi * (1 + eta * ec[a])
            deta[:, a] = 0.5 * ec[a] * (1 - xi**2)
        else:
            dxi[:, a] = 0.5 * xc[a] * (1 - eta**2)
            deta[:, a] = -eta * (1 + xi * xc[a])
    ex = xy[conn]  # (n_el, 8, 2)
    j00 = np.einsum("qa,ea->eq", dxi, ex[:, :, 0])
    j01 = np.einsum("qa,ea->eq", dxi, ex[:, :, 1])
    j10 = np.einsum("qa,ea->eq", deta, ex[:, :, 0])
    j11 = np.einsum("qa,ea->eq", deta, ex[:, :, 1])
    return j00 * j11 - j01 * j10


def corner_angles(xy: np.ndarray, conn: np.ndarray) -> np.ndarray:
    """Interior corner angles [deg] (n_el, 4) of the quadrilaterals' corners."""
    c = xy[conn[:, :4]]
    prev = np.roll(c, 1, axis=1) - c
    nxt = np.roll(c, -1, axis=1) - c
    cos = np.sum(prev * nxt, axis=2) / (np.linalg.norm(prev, axis=2) * np.linalg.norm(nxt, axis=2))
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


def check_quality(xy: np.ndarray, conn: np.ndarray, min_angle: float = MIN_ANGLE_DEG) -> dict:
    """Raise :class:`MeshQualityError` naming the worst element if a Jacobian at a 3x3 Gauss point is not
    positive or a corner angle lies outside [``min_angle``, max(MAX_ANGLE_DEG, 180 - ``min_angle``)] [deg];
    return the extremes
    (``min_det_ratio``: min over elements of min det J / max det J, ``min_angle``, ``max_angle`` [deg])."""
    det = q8_jacobians(xy, conn)
    ratio = det.min(axis=1) / np.abs(det).max(axis=1)
    ang = corner_angles(xy, conn)
    e = int(np.argmin(ratio))
    if ratio[e] <= 0.0:
        raise MeshQualityError(
            f"element {e} (centre {xy[conn[e]].mean(axis=0).round(4).tolist()} m) is inverted: det J ratio "
            f"{ratio[e]:.3g} <= 0"
        )
    lo, hi = ang.min(axis=1), ang.max(axis=1)
    max_angle = max(MAX_ANGLE_DEG, 180.0 - min_angle)
    e = int(np.argmin(np.minimum(lo - min_angle, max_angle - hi)))
    if lo[e] < min_angle or hi[e] > max_angle:
        raise MeshQualityError(
            f"element {e} (centre {xy[conn[e]].mean(axis=0).round(4).tolist()} m) has corner angles "
            f"{lo[e]:.1f}..{hi[e]:.1f} deg outside the allowed [{min_angle:.3g}, {max_angle:.3g}] deg"
        )
    return {"min_det_ratio": float(ratio.min()), "min_angle": float(ang.min()), "max_angle": float(ang.max())}
