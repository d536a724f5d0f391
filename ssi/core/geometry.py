"""One geometry description of a 2D site, shared by every mesher: a planar straight-line graph of points,
tagged segments and convex cells (triangles or quadrilaterals) that tile the domain, each cell in one
region (a soil layer).

The soil mesh (:func:`ssi.core.gmsh_mesh.mesh_geometry`, 8-node quadrilaterals) meshes every cell as one
gmsh surface; a triangle mesher (the limit-analysis meshes) takes the same graph through
:meth:`Geometry.as_pslg`: the points, the segments (every cell edge, so the triangles conform to every layer
boundary and every foundation end) and one seed point per cell with its region.

Units: metres; coordinates (x, z), z upwards. Shapes: ``points`` (n_p, 2); ``segments`` (n_s, 2) point
indices with ``segment_tags`` (n_s,) strings; ``cells`` a tuple of point-index tuples listed
counter-clockwise, with ``cell_region`` (n_c,) region indices.

Segment tags: ``ground`` (the free ground surface), ``bottom``, ``left``, ``right`` (the block's sides),
``interior`` (a layer boundary or a cut between cells).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Geometry", "GeometryError", "from_cells"]

SEGMENT_TAGS = ("ground", "bottom", "left", "right", "interior")


class GeometryError(ValueError):
    """A site geometry that cannot be meshed: crossing layer boundaries, a borehole outside the block, a
    foundation in the air, overlapping foundations, a degenerate cell. The message names the part and
    where."""


@dataclass(frozen=True)
class Geometry:
    """A tiling of the site into convex cells (see the module docstring for the fields and their shapes)."""

    points: np.ndarray
    segments: np.ndarray
    segment_tags: tuple
    cells: tuple
    cell_region: np.ndarray

    def __post_init__(self):
        pts = np.ascontiguousarray(self.points, np.float64)
        if pts.ndim != 2 or pts.shape[1] != 2 or not np.all(np.isfinite(pts)):
            raise GeometryError(f"points must be a finite (n, 2) array, got shape {pts.shape}")
        object.__setattr__(self, "points", pts)
        for k, cell in enumerate(self.cells):
            if len(cell) not in (3, 4):
                raise GeometryError(
                    f"cell {k} has {len(cell)} vertices: cells are triangles or quadrilaterals"
                )
            area = _signed_area(pts[list(cell)])
            if area <= 0.0:
                raise GeometryError(f"cell {k} (points {cell}) is degenerate or clockwise: area {area:g} m^2")
        for tag in self.segment_tags:
            if tag not in SEGMENT_TAGS:
                raise GeometryError(f"segment tag {tag!r} is not one of {SEGMENT_TAGS}")

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """(x_min, x_max, z_min, z_max) [m]."""
        return (*self.points.min(axis=0), *self.points.max(axis=0))

    def segments_tagged(self, tag: str) -> np.ndarray:
        """(k, 2) point indices of the segments with ``tag``."""
        return self.segments[[t == tag for t in self.segment_tags]]

    def area(self) -> float:
        """Area of the site [m^2] (the sum of the cells')."""
        return float(sum(_signed_area(self.points[list(c)]) for c in self.cells))

    def min_corner_angle(self) -> float:
        """The smallest interior corner angle [deg] of any cell (a pinch-out or a thin wedge makes it small,
        and the mesh of that cell cannot have larger angles at that corner)."""
        out = 180.0
        for cell in self.cells:
            c = self.points[list(cell)]
            prev = np.roll(c, 1, axis=0) - c
            nxt = np.roll(c, -1, axis=0) - c
            cos = np.sum(prev * nxt, 1) / (np.linalg.norm(prev, axis=1) * np.linalg.norm(nxt, axis=1))
            out = min(out, float(np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))).min()))
        return out

    def as_pslg(self) -> dict:
        """The planar straight-line graph a triangle mesher takes: ``vertices`` (n_p, 2), ``segments``
        (n_s, 2), ``segment_tags``, ``regions`` (n_c, 4) rows (x, z, region index, area limit [m^2]; 0: none)
        of one seed point (the centroid) inside each cell, the row layout of Triangle's regions.
        ``triangle.triangulate(pslg, "pA")`` meshes it conforming to every edge, each triangle carrying its
        cell's region in ``triangle_attributes``."""
        seeds = np.array(
            [
                [*self.points[list(c)].mean(axis=0), float(r), 0.0]
                for c, r in zip(self.cells, self.cell_region)
            ]
        )
        return {
            "vertices": self.points.copy(),
            "segments": self.segments.copy(),
            "segment_tags": tuple(self.segment_tags),
            "regions": seeds,
        }


def _signed_area(poly: np.ndarray) -> float:
    x, z = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.sum(x * np.roll(z, -1) - np.roll(x, -1) * z))


def from_cells(polygons: list, regions: list, tol: float = 1e-9) -> Geometry:
    """A :class:`Geometry` from cells given by their vertex coordinates (each an (m, 2) sequence,
    counter-clockwise; m = 3 or 4 after coincident vertices are merged; cells of zero area are dropped) and
    their region indices. Points closer than ``tol`` [m] (relative to the site's size) are one point, so the
    cells share their common edges. Segments are tagged by position: on the block's bottom, left or right
    side, else ``ground`` if only one cell has the edge, else ``interior``."""
    allpts = np.vstack([np.asarray(p, np.float64) for p in polygons])
    scale = max(1.0, float(np.ptp(allpts, axis=0).max()))
    key_of = {}
    points = []

    def pid(p):
        key = (round(p[0] / (tol * scale)), round(p[1] / (tol * scale)))
        if key not in key_of:
            key_of[key] = len(points)
            points.append((float(p[0]), float(p[1])))
        return key_of[key]

    cells, cell_region = [], []
    for poly, region in zip(polygons, regions):
        ids = [pid(p) for p in np.asarray(poly, np.float64)]
        uniq = [i for k, i in enumerate(ids) if i != ids[k - 1]]  # merge coincident neighbours (cyclic)
        if len(uniq) < 3:
            continue
        pts = np.array([points[i] for i in uniq])
        if _signed_area(pts) <= (tol * scale) ** 2:
            continue
        cells.append(tuple(uniq))
        cell_region.append(int(region))
    pts = np.array(points)
    x_min, x_max, z_min = pts[:, 0].min(), pts[:, 0].max(), pts[:, 1].min()
    count: dict = {}
    for cell in cells:
        for a, b in zip(cell, cell[1:] + cell[:1]):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    segments, tags = [], []
    eps = tol * scale
    for (a, b), n in sorted(count.items()):
        pa, pb = pts[a], pts[b]
        if abs(pa[1] - z_min) < eps and abs(pb[1] - z_min) < eps:
            tag = "bottom"
        elif abs(pa[0] - x_min) < eps and abs(pb[0] - x_min) < eps:
            tag = "left"
        elif abs(pa[0] - x_max) < eps and abs(pb[0] - x_max) < eps:
            tag = "right"
        else:
            tag = "ground" if n == 1 else "interior"
        segments.append((a, b))
        tags.append(tag)
    return Geometry(
        pts, np.array(segments, np.int64), tuple(tags), tuple(cells), np.array(cell_region, np.int64)
    )
