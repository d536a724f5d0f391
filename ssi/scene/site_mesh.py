"""A :class:`~ssi.scene.site.Site`'s two meshes (a mixin the Site inherits): the graded structured block
of :func:`ssi.core.mesh.soil_block` where it serves (level ground and boundaries, one strip) and gmsh's Q8
mesh of the site's geometry otherwise, refined along the strips, their trench walls and the loaded
ground."""

from __future__ import annotations

import numpy as np

from ..core.gmsh_mesh import UnstructuredMesh, mesh_geometry
from ..core.mesh import soil_block
from .site_checks import TOL


class SiteMesh:
    """``_structured_mesh`` and ``_gmsh_mesh`` (``Site.build`` picks one)."""

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
