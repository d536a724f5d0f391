"""Triangle meshes of a :class:`ssi.limit.geometry.Site`: the initial quality mesh from Shewchuk's Triangle
(the ``triangle`` wheel) and nested refinement by longest-edge bisection (Rivara) for adaptivity.

Layout (written once here): ``xy`` (n_nodes, 2) float [m]; ``tri`` (n_el, 3) int, counter-clockwise;
``material`` (n_el,) int, the site's material index of each element; ``bnd`` (n_b, 2) int, boundary edges
oriented with the domain on their left; ``bnd_seg`` (n_b,) int, the index in ``site.segments`` of the
segment each boundary edge lies on.

Why our own refinement: Triangle's refinement of a mesh (switch ``r`` with area constraints) re-triangulates
with Delaunay flips, so a refined mesh need not be a subdivision of the old one, and the bounds need not
improve. Bisection of marked triangles (and of their neighbours to keep the mesh conforming) splits every
old triangle into new ones: an old lower-bound stress field and an old upper-bound velocity field stay
admissible on the new mesh, so the lower bound cannot fall and the upper bound cannot rise.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import triangle

from ..core.validate import check_real
from .geometry import Site

__all__ = ["TriMesh", "bisect", "fans_at", "triangulate"]


@dataclass
class TriMesh:
    """A conforming triangle mesh of a site (layout in the module docstring)."""

    xy: np.ndarray
    tri: np.ndarray
    material: np.ndarray
    bnd: np.ndarray
    bnd_seg: np.ndarray
    parent: np.ndarray | None = None  # (n_el,) after bisect: the element of the coarser mesh containing each

    @property
    def n_el(self) -> int:
        return len(self.tri)

    def areas(self) -> np.ndarray:
        """Element areas (n_el,) [m^2]."""
        p = self.xy[self.tri]
        d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        return 0.5 * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])

    def edges(self) -> tuple[np.ndarray, np.ndarray]:
        """Unique edges and the edge of each element side: (edges (n_e, 2) sorted node pairs, el_edge
        (n_el, 3) with side k opposite local vertex k, i.e. joining vertices k+1 and k+2)."""
        t = self.tri
        sides = np.stack([t[:, [1, 2]], t[:, [2, 0]], t[:, [0, 1]]], axis=1).reshape(-1, 2)
        key = np.sort(sides, axis=1)
        edges, inv = np.unique(key, axis=0, return_inverse=True)
        return edges, inv.reshape(-1, 3)

    def permuted(self, seed: int) -> TriMesh:
        """The same mesh with nodes, elements and each element's vertex order shuffled (``seed``): a test that
        the bounds do not depend on numbering."""
        rng = np.random.default_rng(seed)
        pn = rng.permutation(len(self.xy))
        inv = np.empty_like(pn)
        inv[pn] = np.arange(len(pn))
        pe = rng.permutation(self.n_el)
        roll = rng.integers(0, 3, self.n_el)
        tri = inv[self.tri[pe]]
        tri = np.array([np.roll(t, r) for t, r in zip(tri, roll[pe])])
        pb = rng.permutation(len(self.bnd))
        return TriMesh(self.xy[pn], tri, self.material[pe], inv[self.bnd[pb]], self.bnd_seg[pb])


# a fan's rays at a footing's or a load's end (fans_at): odd, so that none runs straight down (a site's cut
# lines often do); issue 46's two-strip site, first mesh: lower bound 1.750 with five rays of 2 h_min against
# 1.042 without, gap 11.2 % against 37.3 %
FAN_RAYS = 5


def fans_at(site: Site, points, radius: float, n: int = FAN_RAYS) -> tuple:
    """The ``fans`` of :func:`triangulate` at those of ``points`` [(x, z) m] that are points of the site on
    a horizontal stretch of its boundary (both boundary segments there horizontal, the domain below: a
    footing's or a surface load's end on level ground), ``n`` rays of ``radius`` [m] each; other points
    (a trench's corner, a sloping ground) get none."""
    radius = check_real("radius", radius, lo=0.0, lo_open=True, unit="m")
    pts = site.points
    out = []
    for x, z in points:
        d = np.hypot(pts[:, 0] - x, pts[:, 1] - z)
        c = int(np.argmin(d))
        if d[c] > 1e-9:
            continue
        ends = [(i, j) for i, j, b in site.segments if b is not None and c in (i, j)]
        flat = all(
            abs(pts[j, 1] - pts[i, 1]) <= 1e-9 * max(abs(pts[j, 0] - pts[i, 0]), 1e-300) for i, j in ends
        )
        # the boundary runs counter-clockwise with the domain on its left: leftwards along the top
        leftward = all((pts[j, 0] - pts[i, 0]) < 0.0 for i, j in ends)
        if len(ends) == 2 and flat and leftward:
            out.append((float(pts[c, 0]), float(pts[c, 1]), radius, n))
    return tuple(out)


def triangulate(
    site: Site,
    h: float,
    size: Callable[[np.ndarray], np.ndarray] | None = None,
    min_angle: float = 28.0,
    fans: tuple = (),
) -> TriMesh:
    """A quality mesh of ``site`` (Triangle: constrained conforming Delaunay, smallest angle ``min_angle``
    [deg]) whose triangles are no larger than an equilateral triangle of side ``h`` [m], or of side
    ``size(centroids)`` [m] where that is smaller (``size`` maps (n, 2) points to (n,) lengths).

    ``fans``: (x, z, radius [m], n) for points of a site's point list on a horizontal ground surface (the
    edge of a flexible load): n + 1 rays of length ``radius`` into the ground, equally spaced over the half
    plane below, are meshed as interior segments. A lower-bound stress field turns through a fan of
    sectors at such a point; bisection keeps the number of sectors there bounded, so the fan is made here.
    A ray is checked against the site's segments and the rays before it (:func:`_free_length`): one along
    a segment from the point (a vertical cut line below a strip's end) is dropped, one that meets a segment
    is shortened."""
    h = check_real("h", h, lo=0.0, lo_open=True, unit="m")
    min_angle = check_real("min_angle", min_angle, lo=10.0, hi=33.0, unit="deg")
    seg = np.array([(i, j) for i, j, _ in site.segments], dtype=np.int32)
    markers = np.arange(len(seg), dtype=np.int32) + 2  # 0 and 1 are Triangle's own markers
    pts = site.points
    for x, z, radius, n in fans:
        c = int(np.argmin(np.hypot(pts[:, 0] - x, pts[:, 1] - z)))
        if np.hypot(pts[c, 0] - x, pts[c, 1] - z) > 1e-9:
            raise ValueError(f"fans: ({x}, {z}) is not a point of the site")
        ang = -np.pi * np.arange(1, n) / n  # strictly inside the half plane below (the surface rays exist)
        new = []
        for a in ang:
            length = _free_length(pts, seg, c, np.array([np.cos(a), np.sin(a)]), radius)
            if length > 0.0:
                new.append((x + length * np.cos(a), z + length * np.sin(a)))
                pts = np.vstack([pts, new[-1]])
                seg = np.vstack([seg, np.array([(c, len(pts) - 1)], np.int32)])  # later rays see this one
                markers = np.concatenate([markers, np.ones(1, np.int32)])  # interior: marker 1
    area = np.sqrt(3.0) / 4.0 * h * h
    regions = [[x, z, m, area] for x, z, m in site.regions]
    data = dict(vertices=pts, segments=seg, segment_markers=markers[:, None], regions=regions)
    out = triangle.triangulate(data, f"pq{min_angle:g}Aa")
    for _ in range(12):
        if size is None:
            break
        p = out["vertices"][out["triangles"]]
        cen = p.mean(axis=1)
        target = np.sqrt(3.0) / 4.0 * np.minimum(np.asarray(size(cen), float), h) ** 2
        d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        a = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
        if np.all(a <= 1.5 * target):
            break
        out["triangle_max_area"] = target
        out = triangle.triangulate(out, f"rpq{min_angle:g}Aa")
    return _from_triangle(site, out)


# a fan's ray that meets a segment of the site (or an earlier ray) is cut at FAN_CUT of the distance to it,
# and dropped if that leaves less than FAN_MIN of its radius: Triangle then never gets a ray lying along a
# segment (a ray down a site's vertical cut line sent it out of memory, issue 46) nor a vertex next to one
FAN_CUT, FAN_MIN = 0.5, 0.2


def _free_length(pts: np.ndarray, seg: np.ndarray, c: int, d: np.ndarray, radius: float) -> float:
    """How long a ray from point ``c`` along unit ``d`` may be, at most ``radius`` [m], without meeting a
    segment of ``seg`` other than at ``c`` (0: dropped; :data:`FAN_CUT`, :data:`FAN_MIN`)."""
    o = pts[c]
    a, b = pts[seg[:, 0]], pts[seg[:, 1]]
    at_c = (seg[:, 0] == c) | (seg[:, 1] == c)
    # a segment from c along the ray's direction: the ray would lie on it
    far = np.where((seg[:, 0] == c)[:, None], b, a) - o
    along = far @ d
    cross = far[:, 0] * d[1] - far[:, 1] * d[0]
    if np.any(at_c & (along > 0.0) & (np.abs(cross) <= 1e-9 * np.maximum(np.abs(along), 1e-300))):
        return 0.0
    # other segments: the ray's parameter t at the crossing (t in (0, radius], s in [0, 1] along the segment),
    # and the distance along the ray to any segment end lying within a hair of it
    e = b - a
    den = d[0] * e[:, 1] - d[1] * e[:, 0]
    w = a - o
    ok = ~at_c & (np.abs(den) > 1e-12 * np.hypot(e[:, 0], e[:, 1]))
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0]) / den
        s = (w[:, 0] * d[1] - w[:, 1] * d[0]) / den
    hit = ok & (t > 0.0) & (s >= 0.0) & (s <= 1.0)
    t_hit = float(np.min(t[hit], initial=np.inf))
    for p in (a[~at_c], b[~at_c]):  # ends (and collinear segments) close to the ray
        v = p - o
        tp = v @ d
        near = (tp > 0.0) & (np.abs(v[:, 0] * d[1] - v[:, 1] * d[0]) <= 1e-6 * radius)
        t_hit = min(t_hit, float(np.min(tp[near], initial=np.inf)))
    if t_hit > radius:
        return radius
    length = FAN_CUT * t_hit
    return length if length >= FAN_MIN * radius else 0.0


def _from_triangle(site: Site, out: dict) -> TriMesh:
    xy = np.ascontiguousarray(out["vertices"], float)
    tri = np.ascontiguousarray(out["triangles"], np.int64)
    material = np.rint(out["triangle_attributes"][:, 0]).astype(np.int64)
    mesh = TriMesh(xy, tri, material, np.zeros((0, 2), np.int64), np.zeros(0, np.int64))
    a = mesh.areas()
    if np.any(a <= 0.0):  # Triangle returns counter-clockwise triangles; keep the layout's promise checked
        raise RuntimeError("triangle returned a clockwise or degenerate triangle")
    seg_of = {}
    for (i, j), m in zip(out["segments"], out["segment_markers"].ravel()):
        if m >= 2:
            seg_of[(min(i, j), max(i, j))] = m - 2
    bnd, bseg = [], []
    t = tri
    for k in range(3):
        a_, b_ = t[:, (k + 1) % 3], t[:, (k + 2) % 3]
        for p, q in zip(a_, b_):
            s = seg_of.get((min(p, q), max(p, q)))
            if s is not None and site.segments[s][2] is not None:
                bnd.append((p, q))  # element side p -> q: the element (domain) is on its left
                bseg.append(s)
    order = np.lexsort(np.array(bnd).T[::-1]) if bnd else np.zeros(0, int)
    mesh.bnd = np.array(bnd, np.int64)[order]
    mesh.bnd_seg = np.array(bseg, np.int64)[order]
    _check_boundary_closed(site, mesh)
    return mesh


def _check_boundary_closed(site: Site, mesh: TriMesh) -> None:
    """Every element side that belongs to one element only must lie on a labelled boundary segment."""
    edges, el_edge = mesh.edges()
    count = np.bincount(el_edge.ravel(), minlength=len(edges))
    outer = {tuple(e) for e in edges[count == 1]}
    labelled = {tuple(sorted(e)) for e in mesh.bnd}
    missing = outer - labelled
    if missing:
        nm = len(missing)
        raise ValueError(f"{nm} boundary edges lie on no labelled segment of the site, e.g. {min(missing)}")


def bisect(mesh: TriMesh, marked: np.ndarray) -> TriMesh:
    """Refine by longest-edge bisection (Rivara): every marked element (boolean (n_el,) or indices) is split
    across its longest edge, after its neighbour across that edge has been split until it shares that edge
    as its own longest (so the mesh stays conforming). The result is nested: each old triangle is a union of
    new ones (``parent`` names it). Ties between equal edges are broken by node numbers, so the result is
    deterministic."""
    xy = [tuple(p) for p in mesh.xy]
    tris = [list(map(int, t)) for t in mesh.tri]
    mat = list(map(int, mesh.material))
    origin = list(range(len(tris)))
    alive = [True] * len(tris)
    edge_tris: dict[tuple[int, int], list[int]] = {}
    for e, t in enumerate(tris):
        for k in range(3):
            edge_tris.setdefault(_key(t[k], t[(k + 1) % 3]), []).append(e)
    bnd = {_key(p, q): (int(p), int(q), int(s)) for (p, q), s in zip(mesh.bnd, mesh.bnd_seg)}
    mid: dict[tuple[int, int], int] = {}

    def longest(e):
        t = tris[e]
        best = None
        for k in range(3):
            a, b = t[k], t[(k + 1) % 3]
            d = (xy[a][0] - xy[b][0]) ** 2 + (xy[a][1] - xy[b][1]) ** 2
            cand = (d, -min(a, b), -max(a, b))
            if best is None or cand > best[0]:
                best = (cand, _key(a, b))
        return best[1]

    def split(e, edge):
        a, b = edge
        m = mid.get(edge)
        if m is None:
            m = len(xy)
            xy.append((0.5 * (xy[a][0] + xy[b][0]), 0.5 * (xy[a][1] + xy[b][1])))
            mid[edge] = m
            if edge in bnd:
                p, q, s = bnd.pop(edge)
                bnd[_key(p, m)] = (p, m, s)
                bnd[_key(m, q)] = (m, q, s)
        t = tris[e]
        k = next(k for k in range(3) if {t[k], t[(k + 1) % 3]} == {a, b})
        p, q, r = t[k], t[(k + 1) % 3], t[(k + 2) % 3]  # edge p-q split at m, r opposite
        alive[e] = False
        new = [[p, m, r], [m, q, r]]
        for nt in new:
            tris.append(nt)
            mat.append(mat[e])
            origin.append(origin[e])
            alive.append(True)
        n1, n2 = len(tris) - 2, len(tris) - 1
        for kk in range(3):
            ek = _key(t[kk], t[(kk + 1) % 3])
            edge_tris[ek] = [x for x in edge_tris[ek] if x != e]
        for idx in (n1, n2):
            nt = tris[idx]
            for kk in range(3):
                edge_tris.setdefault(_key(nt[kk], nt[(kk + 1) % 3]), []).append(idx)
        return n1, n2

    def refine(e):
        while alive[e]:
            edge = longest(e)
            nb = [x for x in edge_tris[edge] if x != e]
            if nb and longest(nb[0]) != edge:
                refine_one_step(nb[0])
                continue
            split(e, edge)
            if nb:
                split(nb[0], edge)

    def refine_one_step(e):
        # split e across its longest edge (recursively making that edge conforming first)
        edge = longest(e)
        nb = [x for x in edge_tris[edge] if x != e]
        if nb and longest(nb[0]) != edge:
            refine_one_step(nb[0])
            return
        split(e, edge)
        if nb:
            split(nb[0], edge)

    idx = np.flatnonzero(marked) if np.asarray(marked).dtype == bool else np.asarray(marked, int)
    for e in sorted(set(int(i) for i in idx)):
        refine(e)
    keep = [i for i, a in enumerate(alive) if a]
    bnd_items = sorted(bnd.values())
    out = TriMesh(
        np.array(xy, float),
        np.array([tris[i] for i in keep], np.int64),
        np.array([mat[i] for i in keep], np.int64),
        np.array([(p, q) for p, q, _ in bnd_items], np.int64).reshape(-1, 2),
        np.array([s for _, _, s in bnd_items], np.int64),
        np.array([origin[i] for i in keep], np.int64),
    )
    if np.any(out.areas() <= 0.0):
        raise RuntimeError("bisection produced a clockwise or degenerate triangle")
    return out


def _key(a: int, b: int) -> tuple[int, int]:
    return (a, b) if a < b else (b, a)
