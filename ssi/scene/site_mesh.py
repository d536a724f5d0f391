"""A :class:`~ssi.scene.site.Site`'s geometry and its two meshes (a mixin the Site inherits): the site cut
into cells at its breaks (``geometry``, the one description gmsh and a triangle mesher read); the graded
structured block of :func:`ssi.core.mesh.soil_block` where it serves (level ground and boundaries, one
strip), else gmsh's Q8 mesh of the geometry, refined along the strips, their trench walls and the loaded
ground."""

from __future__ import annotations

import numpy as np

from ..core.geometry import Geometry, from_cells
from ..core.gmsh_mesh import UnstructuredMesh, mesh_geometry
from ..core.mesh import soil_block
from .site_checks import TOL


class SiteMesh:
    """``breaks`` and ``geometry`` (the site cut into cells), ``_structured_mesh`` and ``_gmsh_mesh``
    (``Site.build`` picks one)."""

    def _cut_lines(self, xs, side: str | None = None) -> list[np.ndarray]:
        """Elevations [m] at ``xs`` of the lines every layer is cut along (mesh lines): the water table and
        the base level of every embedded strip (so the trench walls end at a mesh node)."""
        cuts = [self.water_z(xs, side)] if self.has_water else []
        return cuts + [np.full(np.shape(xs), lv) for _, _, _, lv in self.embedded()]

    def breaks(self) -> np.ndarray:
        """x [m] of the vertical cuts of the geometry (see the module docstring), sorted, unique."""
        xs = [self.x_left, self.x_right, *self._ground[0]]
        for bx, _ in self._raw:
            xs += list(bx)
        for a, b in self._strip_ends():
            xs += [a, b]
        xs += self._load_points()
        xs = np.unique(np.clip(np.array(xs, np.float64), self.x_left, self.x_right))
        if self._water[0] == "polyline":
            xs = np.unique(np.clip(np.concatenate([xs, self._water[1][0]]), self.x_left, self.x_right))
        for lens in self.lenses:  # its vertices
            (lx, _), (ux, _) = lens.chains()
            xs = np.unique(np.clip(np.concatenate([xs, lx, ux]), self.x_left, self.x_right))
        # where the ground crosses a boundary (the cut boundary has a kink there) and where a cut line (the
        # water table, an embedded strip's base level) crosses the ground, a boundary or another cut line
        # each line as (its values just right of xs, just left of them): they differ at a step of the ground
        # only, and a crossing within (xs[i], xs[i + 1]) is a change of sign from the right of xs[i] to the
        # left of xs[i + 1]
        lines = [(b, b) for b in (np.interp(xs, *r) for r in self._raw)]
        ground = (self.ground_z(xs, "right"), self.ground_z(xs, "left"))
        pairs = [(ground, b) for b in lines]
        cuts = list(zip(self._cut_lines(xs, "right"), self._cut_lines(xs, "left")))
        for k, c in enumerate(cuts):
            pairs += [(c, ground)] + [(c, b) for b in lines] + [(c, d) for d in cuts[k + 1 :]]
        extra = _crossings(xs, pairs)
        # where a lens's outline crosses the ground, a boundary, a cut line or another lens, within its span
        lens_lines = [(self._lens_span(j), c) for j in range(len(self.lenses)) for c in self._lens_at(j, xs)]
        others = [ground, *lines, *cuts]
        for k, (span, c) in enumerate(lens_lines):
            pairs = [(c, o) for o in others] + [(c, d) for _, d in lens_lines[k + 1 :]]
            extra += [x for x in _crossings(xs, pairs) if span[0] < x < span[1]]
        return _unique(np.concatenate([xs, extra]), self.width)

    def _lens_span(self, j: int) -> tuple[float, float]:
        """(x0, x1) [m] of lens ``j``."""
        (lx, _), _ = self.lenses[j].chains()
        return float(lx[0]), float(lx[-1])

    def _lens_at(self, j: int, xs) -> list[tuple[np.ndarray, np.ndarray]]:
        """Lens ``j``'s lower and upper outline at ``xs`` [m], each as (right, left) values (the outline is
        continuous: both the same), level beyond its span."""
        lower, upper = self.lenses[j].chains()
        return [(np.interp(xs, *c),) * 2 for c in (lower, upper)]

    def _lens_of(self, x: float, z: float) -> int | None:
        """Index of the lens that holds the point (x, z), None if none does."""
        for j, lens in enumerate(self.lenses):
            x0, x1 = self._lens_span(j)
            lower, upper = lens.chains()
            if x0 < x < x1 and np.interp(x, *lower) < z < np.interp(x, *upper):
                return j
        return None

    def geometry(self) -> Geometry:
        """The site cut into cells (columns between breaks, layers within each, each layer cut by the water
        table and the lenses' outlines where they pass), region = layer index (a lens's cells: the number of
        layers plus the lens's index, :meth:`Site.soils`)."""
        xs = self.breaks()
        polys, regions = [], []
        n = len(self.layers)
        trenches = self.embedded()
        eps = TOL * self.width
        for xa, xb in zip(xs[:-1], xs[1:]):

            def at_ends(values_a, values_b):  # a column's left end sees the right of xa, its right end...
                return [np.array([a, b], np.float64) for a, b in zip(values_a, values_b)]

            (top,) = at_ends([self.ground_z(xa, "right")], [self.ground_z(xb, "left")])
            for _, x0, x1, lv in trenches:  # inside a trench the soil ends at the strip's base level
                if xa >= x0 - eps and xb <= x1 + eps:
                    top = np.minimum(top, lv)
            bounds = at_ends(
                [self.boundary_z(k, xa, "right") for k in range(n - 1)],
                [self.boundary_z(k, xb, "left") for k in range(n - 1)],
            )
            tops = [top] + [np.minimum(b, top) for b in bounds]
            tops.append(np.array([self.z_bottom, self.z_bottom]))
            cuts = at_ends(self._cut_lines(xa, "right"), self._cut_lines(xb, "left"))
            for j in range(len(self.lenses)):  # a lens's outline over the column is two more cut lines
                x0, x1 = self._lens_span(j)
                if xa >= x0 - eps and xb <= x1 + eps:
                    cuts += [np.array([c[0][0], c[0][1]]) for c in self._lens_at(j, np.array([xa, xb]))]
            for k in range(n):
                t, b = tops[k], tops[k + 1]
                # the cut lines within the layer (on its top or bottom if outside), bottom up
                inner = sorted((np.clip(c, b, t) for c in cuts), key=lambda c: float(c.sum()))
                for lo, hi in zip([b, *inner], [*inner, t]):  # a cell of zero area is dropped by from_cells
                    polys.append([(xa, lo[0]), (xb, lo[1]), (xb, hi[1]), (xa, hi[0])])
                    mid = (0.5 * (xa + xb), 0.25 * float(lo.sum() + hi.sum()))
                    lens = self._lens_of(*mid) if self.lenses else None
                    regions.append(k if lens is None else n + lens)  # a lens's soil: region n + its index
        # a step's face, a lens's end: the cells beside it get their neighbours' vertices (conforming; else
        # the column beside a lens's tip has a hanging vertex there, which a triangle mesher takes as a
        # boundary running through the soil)
        if self._steps or self.lenses:
            polys, regions = conforming_cells(polys, regions, TOL * max(1.0, self.width))
        return from_cells(polys, regions, tol=TOL)

    def _structured_mesh(self):
        m = self.mesh
        if self.strips:
            foot = self.strips[0].ends
        else:
            pressures = [ld.ground_span() for ld in self.all_loads() if ld.ground_span() is not None]
            foot = (
                (min(a for a, _ in pressures), max(b for _, b in pressures))
                if pressures
                else (-0.25 * self.width, 0.25 * self.width)
            )
        breaks = self._load_points()
        # the layers split at the water table (a mesh line there, as the layered scene does): each element
        # wholly above or below it; and at an embedded strip's base (the trench's bottom, as soil_block needs)
        d_w = -float(self.water_z(0.0)) if self.has_water else np.inf
        trench = self.embedded()
        d_base = -trench[0][3] if trench else 0.0
        thick, owner, top = [], [], 0.0
        for k, t in enumerate(self.layer_thicknesses()):
            inner = sorted({d for d in (d_w, d_base) if 1e-9 * t < d - top < t * (1 - 1e-9)})
            for a, b in zip([top, *inner], [*inner, top + t]):
                thick.append(b - a)
                owner.append(k)
            top += t
        mesh = soil_block(
            self.width, self.depth, thick, foot, m.h_fine, m.h_coarse, m.growth,
            breaks=breaks, embedment=d_base, end_grading=m.end_grading,
        )  # fmt: skip
        mesh.el_layer = np.array(owner, np.int64)[mesh.el_layer]
        return mesh

    def _gmsh_mesh(self) -> UnstructuredMesh:
        m = self.mesh
        ref = []
        for i, s in enumerate(self.strips):
            x0, x1 = s.ends
            n = max(1, round((x1 - x0) / m.h_fine))
            xs = np.linspace(x0, x1, n + 1)
            ref += [(x, self.base_z(i)) for x in xs]
            top = float(self.ground_z(x0))
            if top - self.base_z(i) > TOL * self.width:  # the trench walls of an embedded strip
                n_w = max(1, round((top - self.base_z(i)) / m.h_fine))
                ref += [(x, z) for x in (x0, x1) for z in np.linspace(self.base_z(i), top, n_w + 1)]
        for span in (ld.ground_span() for ld in self.all_loads()):
            if span is not None:
                n = max(1, round((span[1] - span[0]) / m.h_fine))
                ref += [(x, float(self.ground_z(x))) for x in np.linspace(*span, n + 1)]
        return mesh_geometry(self.geometry(), m.h_fine, m.h_coarse, m.growth, np.array(ref) if ref else None)


def conforming_cells(polys, regions, tol):
    """The column cells [(xa, lo0), (xb, lo1), (xb, hi1), (xa, hi0)] made conforming where a column's end
    has vertices its neighbour's has not (beside a vertical step of the ground the taller column's edge
    carries the lower column's vertices): each such cell split, up its two vertical edges, into quads and
    triangles through every vertex that lies on them. Returns (cells, regions)."""
    at_x: dict = {}
    for p in polys:
        for x, z in p:
            at_x.setdefault(round(x / tol), []).append(z)

    def on_edge(x, lo, hi):
        zs = sorted({z for z in at_x[round(x / tol)] if lo + tol < z < hi - tol})
        return [lo, *zs, hi]

    out, out_regions = [], []
    for p, r in zip(polys, regions):
        (xa, lo0), (xb, lo1), (_, hi1), (_, hi0) = p
        left, right = on_edge(xa, lo0, hi0), on_edge(xb, lo1, hi1)
        i = j = 0
        while i < len(left) - 1 or j < len(right) - 1:  # a ladder up both edges: quads, then triangles
            if i < len(left) - 1 and j < len(right) - 1:
                out.append([(xa, left[i]), (xb, right[j]), (xb, right[j + 1]), (xa, left[i + 1])])
                i, j = i + 1, j + 1
            elif i < len(left) - 1:
                out.append([(xa, left[i]), (xb, right[j]), (xa, left[i + 1])])
                i += 1
            else:
                out.append([(xa, left[i]), (xb, right[j]), (xb, right[j + 1])])
                j += 1
            out_regions.append(r)
    return out, out_regions


def _crossings(xs, pairs) -> list[float]:
    """x [m] where the lines of each pair ((right, left) values at ``xs``) cross between two of ``xs``."""
    extra = []
    for (f_r, f_l), (g_r, g_l) in pairs:
        d_r, d_l = f_r - g_r, f_l - g_l
        for i in np.flatnonzero(d_r[:-1] * d_l[1:] < 0.0):
            extra.append(xs[i] + (xs[i + 1] - xs[i]) * d_r[i] / (d_r[i] - d_l[i + 1]))
    return extra


def _unique(xs, scale):
    xs = np.sort(np.asarray(xs, np.float64))
    keep = np.concatenate([[True], np.diff(xs) > TOL * max(scale, 1.0)])
    return xs[keep]
