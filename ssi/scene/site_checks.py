"""The checks of a :class:`~ssi.scene.site.Site`'s geometry that need the whole site (ground, boundaries,
strips, trenches, loads): a mixin the Site inherits, each failure a GeometryError naming the part and
where."""

from __future__ import annotations

import numpy as np

from ..core.geometry import GeometryError
from ..core.validate import check_real

TOL = 1e-9  # relative to the site's size: coordinates closer than this are one point


def _polyline(name, pts, steps=False):
    """(x, z) arrays of a polyline [(x, z), ...] with x strictly increasing; ``steps``: two consecutive points
    may share an x (a vertical step, e.g. the face of a cut), never three."""
    a = np.asarray(pts, np.float64)
    if a.ndim != 2 or a.shape[1] != 2 or len(a) < 1 or not np.all(np.isfinite(a)):
        raise GeometryError(f"{name} must be a list of (x, z) points [m], got {pts!r}")
    dx = np.diff(a[:, 0])
    if np.any(dx < 0) or (not steps and np.any(dx == 0)):
        rule = "must increase strictly"
        if steps:
            rule = "must not decrease (a vertical step: two points at one x)"
        raise GeometryError(f"{name}: the x of its points {rule}, got {a[:, 0].tolist()}")
    if steps and np.any((dx[:-1] == 0) & (dx[1:] == 0)):
        raise GeometryError(f"{name}: three points at one x (a step has two), got {a[:, 0].tolist()}")
    return a[:, 0], a[:, 1]


# what the two water fields mean, for the messages that name the other one
_LEVEL = "Site.water_level is the water table's ELEVATION [m] (z up, as the ground polyline)"
_DEPTH = "Site.water_table is the water table's DEPTH [m] below the ground (as a Scene's)"


class SiteChecks:
    """``_check_geometry`` (run by ``Site.__post_init__``), ``_check_trench`` of an embedded strip and the
    water table's two fields (``_water_line``, ``_check_water``)."""

    def _boundary_lines(self, n_b):
        """(x, z) of each of the ``n_b`` layer boundaries, from ``boreholes`` (interpolated between them),
        ``boundaries`` (polylines), or both mixed: then ``boundaries[k]`` is a polyline or None, None taking
        boundary k from the boreholes, which list exactly those boundaries, from the top down."""
        bh, lines = self.boreholes, self.boundaries
        if n_b and bh is None and lines is None:
            raise GeometryError(
                f"Site: {len(self.layers)} layers need boreholes or boundaries ({n_b} boundaries)"
            )
        if lines is not None and len(lines) != n_b:
            raise GeometryError(f"Site.boundaries: {len(lines)} given, {len(self.layers)} layers need {n_b}")
        # an empty polyline is None (a file's form: TOML has no null)
        lines = [None] * n_b if lines is None else [None if p is None or len(p) == 0 else p for p in lines]
        from_bh = [k for k, p in enumerate(lines) if p is None]
        if bh is not None and n_b and not from_bh:
            raise GeometryError(
                "Site: boreholes and boundaries are both given, but every boundary is a polyline: mark the "
                "boundaries the boreholes give with None in Site.boundaries, or leave the boreholes out"
            )
        if from_bh and bh is None:
            raise GeometryError(
                f"Site.boundaries{from_bh}: None takes a boundary from the boreholes, and none are given"
            )
        raw = [None if p is None else _polyline(f"Site.boundaries[{k}]", p) for k, p in enumerate(lines)]
        if bh is None:
            return raw
        if not bh:
            raise GeometryError("Site.boreholes: give at least one borehole")
        bh = sorted(bh, key=lambda b: b.x)
        for b in bh:
            if not (self.x_left <= b.x <= self.x_right):
                raise GeometryError(
                    f"Borehole at x={b.x} lies outside the block [{self.x_left:g}, {self.x_right:g}] m"
                )
            if len(b.boundaries) != len(from_bh):
                given = "" if len(from_bh) == n_b else f" (boundaries {from_bh}: the others are polylines)"
                raise GeometryError(
                    f"Borehole at x={b.x} lists {len(b.boundaries)} boundaries, the {len(self.layers)} "
                    f"layers need {len(from_bh)}{given}"
                )
        if len({b.x for b in bh}) != len(bh):
            raise GeometryError(f"Site.boreholes: two boreholes at the same x ({[b.x for b in bh]})")
        xs = np.array([b.x for b in bh])
        for j, k in enumerate(from_bh):
            raw[k] = (xs, np.array([b.boundaries[j] for b in bh]))
        return raw

    def _check_phases(self):
        """Each phase a Phase whose loads a site takes, its factors naming earlier phases, no excavation or
        drainage switch (a scene's: not built on a site's mesh), names unique; a RigidStrip's ``settle`` is
        a single-phase site's (a phased one would hold it at zero)."""
        from .loads import LOAD_TYPES
        from .parts import Phase

        names = ["loads"] if self.loads else []
        for i, ph in enumerate(self.phases):
            if not isinstance(ph, Phase):
                raise TypeError(f"Site.phases[{i}] must be a Phase, got {ph!r}")
            where = f"Site.phases[{i}] ({ph.name!r})"
            if ph.name in names or ph.name == "geostatic":
                raise ValueError(f"{where}: the name is taken (earlier phases: {['geostatic', *names]})")
            for j, ld in enumerate(ph.loads):
                if not ld.on_site:
                    site_loads = sorted(n for n, c in LOAD_TYPES.items() if c.on_site)
                    raise ValueError(
                        f"{where}.loads[{j}]: {type(ld).__name__} is not one a site takes: {site_loads}"
                    )
            for key in ph.factors:
                if key not in names:
                    raise ValueError(
                        f"{where}.factors[{key!r}]: no earlier phase of that name (earlier: {names})"
                    )
            if ph.excavate or ph.drainage:
                raise ValueError(
                    f"{where}: excavate={ph.excavate!r}, drainage={ph.drainage!r}: excavations and "
                    "drainage switches are built on a Scene only; a site's phases carry loads and factors"
                )
            names.append(ph.name)
        for i, s in enumerate(self.strips):
            if self.phases and s.rigid and s.settle != 0.0:
                raise ValueError(
                    f"Site.strips[{i}]: RigidStrip.settle={s.settle!r} m in a phased site is not built (the "
                    "phases set every prescribed motion); give settle=0 or solve the site without phases"
                )

    def _water_line(self):
        """("dry", None) | ("depth", d) | ("level", z) | ("polyline", (xs, zs)) from ``water_table`` (a depth
        below the ground) or ``water_level`` (an elevation or a polyline of elevations): one field, one
        meaning. A polyline given as a depth is refused by name (a polyline is (x, z) points: elevations)."""
        if self.water_table is not None and self.water_level is not None:
            raise ValueError(
                f"Site: give the water table by water_level={self.water_level!r} (an ELEVATION [m]) or by "
                f"water_table={self.water_table!r} (a DEPTH [m] below the ground), not both"
            )
        if self.water_table is not None:
            if np.ndim(self.water_table) != 0:
                raise ValueError(
                    f"{_DEPTH}: one number, got {self.water_table!r}; a polyline [(x, z), ...] of elevations "
                    "is Site.water_level"
                )
            d = check_real("Site.water_table", self.water_table, unit="m (depth below the ground)")
            if d < 0.0:
                raise ValueError(
                    f"{_DEPTH}; water_table={d:g} m puts free water {-d:g} m above the ground (ponding), "
                    f"which a site does not build; if {d:g} m is the water table's elevation, give "
                    f"water_level={d:g}"
                )
            return "depth", d
        if self.water_level is None:
            return "dry", None
        if np.ndim(self.water_level) == 0:
            return "level", check_real("Site.water_level", self.water_level, unit="m (elevation)")
        return "polyline", _polyline("Site.water_level", self.water_level)

    def _check_water(self, xs, g):
        """A water table that reads as the other field's convention, refused by name: an elevation above the
        ground everywhere (a depth given as an elevation: ``water_level=2.0`` for 2 m down), or either field
        at or below the block bottom everywhere (no soil wet: a dry site is None)."""
        kind, value = self._water
        if kind == "dry":
            return
        w = self.water_z(xs)
        if kind != "depth" and np.all(w > g + TOL * self.width):
            raise ValueError(
                f"{_LEVEL}; water_level={self.water_level!r} lies above the ground everywhere (ground z from "
                f"{g.min():g} to {g.max():g} m, water from {w.min():g} to {w.max():g} m): the whole site "
                f"under free water, which a site does not build. If it is a depth below the ground, give "
                f"water_table={self.water_level!r}; for a submerged site give the ground's level (the free "
                "water above changes no effective stress)"
            )
        if np.all(w <= self.z_bottom + TOL * self.width):
            name, conv, other = (
                ("water_table", _DEPTH, _LEVEL) if kind == "depth" else ("water_level", _LEVEL, _DEPTH)
            )
            raise ValueError(
                f"{conv}; {name}={getattr(self, name)!r} lies at or below the block bottom "
                f"z={self.z_bottom:g} m everywhere (water z up to {float(w.max()):g} m), so no soil is wet: "
                f"for a dry site leave it out (None); the other convention is the other field ({other})"
            )

    def _check_geometry(self):
        xs = self.breaks()
        g = self.ground_z(xs)
        self._check_water(xs, g)
        self._check_lenses(xs)
        low = np.minimum(self.ground_z(xs, "left"), self.ground_z(xs, "right"))  # the foot of a step
        if np.any(low <= self.z_bottom):
            x = xs[np.argmax(low <= self.z_bottom)]
            raise GeometryError(
                f"Site.ground at x={x:g} m lies at or below the block bottom z={self.z_bottom:g} m"
            )
        for k in range(len(self._raw)):
            bx = self._raw[k][0]
            if bx.max() < self.x_left or bx.min() > self.x_right:  # no point of it over the block
                raise GeometryError(
                    f"layer boundary {k} (x from {bx.min():g} to {bx.max():g} m) lies beyond the block "
                    f"[{self.x_left:g}, {self.x_right:g}] m: give its points over the site"
                )
            b = np.interp(xs, *self._raw[k])
            if np.all(b >= g - TOL * self.width):  # above the ground everywhere: the layers above it empty
                raise GeometryError(
                    f"layer boundary {k} lies at or above the ground everywhere (z from {b.min():g} to "
                    f"{b.max():g} m, ground from {g.min():g} to {g.max():g} m): layer {k} has no soil in the "
                    "site; give boundaries below the ground, or leave the layer out"
                )
            if np.any(b < self.z_bottom - TOL * self.width):
                x = xs[np.argmax(b < self.z_bottom)]
                raise GeometryError(
                    f"layer boundary {k} at x={x:g} m lies below the block bottom z={self.z_bottom:g} m "
                    f"(z={np.interp(x, *self._raw[k]):g} m): deepen the block"
                )
            if k and np.any(b > np.interp(xs, *self._raw[k - 1]) + TOL * self.width):
                x = xs[np.argmax(b > np.interp(xs, *self._raw[k - 1]) + TOL * self.width)]
                raise GeometryError(
                    f"layer boundaries {k - 1} and {k} cross near x={x:g} m: boundary {k} must not rise "
                    "above "
                    f"boundary {k - 1} (equal: layer {k} pinched out)"
                )
        ends = self._strip_ends()
        for (a0, a1), (b0, b1) in zip(ends, ends[1:]):
            if b0 < a1 - TOL * self.width:
                raise GeometryError(f"strips ({a0:g}, {a1:g}) and ({b0:g}, {b1:g}) m overlap")
        for i, s in enumerate(self.strips):
            x0, x1 = s.ends
            if not (self.x_left <= x0 < x1 <= self.x_right):
                raise GeometryError(
                    f"strips[{i}] ({x0:g}, {x1:g}) m must lie within the block "
                    f"[{self.x_left:g}, {self.x_right:g}]"
                )
            inside = xs[(xs > x0) & (xs < x1)]
            # the ground just right of x0, on both sides of every break within, just left of x1
            gz = np.concatenate([
                [self.ground_z(x0, "right")], self.ground_z(inside, "left"), self.ground_z(inside, "right"),
                [self.ground_z(x1, "left")],
            ])  # fmt: skip
            if np.ptp(gz) > TOL * self.width:
                raise GeometryError(
                    f"strips[{i}] ({x0:g}, {x1:g}) m: the ground under it is not level "
                    f"(z from {gz.min():g} "
                    f"to {gz.max():g} m); level the ground under the strip (a berm)"
                )
            if s.level is not None and s.level > gz[0] + TOL * self.width:
                raise GeometryError(
                    f"strips[{i}].level={s.level:g} m lies above the ground (z={gz[0]:g} m there): a "
                    "foundation in the air"
                )
        for i, x0, x1, lv in self.embedded():
            self._check_trench(i, x0, x1, lv, xs)
        for i, ld in enumerate(self.all_loads()):  # i: of loads, then of each phase's
            if ld.drives == "horizontal":  # a Push
                s = self.strips[self.pushed_strip(ld)]
                if s.rigid and not s.rough:
                    raise GeometryError(
                        f"loads[{i}]: {ld!r} pushes a smooth RigidStrip (rough=False), whose base nodes "
                        "slide freely: nothing carries the push; give rough=True"
                    )
            for x, _ in ld.columns():
                if self._strip_at(x) is None:
                    raise GeometryError(f"loads[{i}]: ColumnLoad at x={x:g} m lies on no strip {ends}")
            if ld.ground_span() is not None:
                x0, x1 = ld.ground_span()
                if not (self.x_left <= x0 < x1 <= self.x_right):
                    raise GeometryError(f"loads[{i}]: SurfacePressure ({x0:g}, {x1:g}) m outside the block")
                gx, gz, eps = *self._ground, TOL * self.width
                # a pressure may end at the crest of a step (its nodes there are the ground's), not at its
                # foot nor across it
                steps = [
                    gx[j] for j in self._steps
                    if x0 + eps < gx[j] < x1 - eps
                    or (abs(gx[j] - x1) <= eps and gz[j] < gz[j + 1])
                    or (abs(gx[j] - x0) <= eps and gz[j + 1] < gz[j])
                ]  # fmt: skip
                if steps:
                    raise GeometryError(
                        f"loads[{i}]: SurfacePressure ({x0:g}, {x1:g}) m reaches the vertical step of the "
                        f"ground at x={steps[0]:g} m: give a pressure on each side of it, clear of the step"
                    )
                for a, b in ends:
                    if min(x1, b) - max(x0, a) > TOL * self.width:
                        raise GeometryError(
                            f"loads[{i}]: SurfacePressure ({x0:g}, {x1:g}) m overlaps the strip "
                            f"({a:g}, {b:g})"
                        )

    def _check_lenses(self, xs):
        """Each lens inside the block and below the ground, and no two overlapping."""
        for j in range(len(self.lenses)):
            x0, x1 = self._lens_span(j)
            if x0 < self.x_left - TOL * self.width or x1 > self.x_right + TOL * self.width:
                raise GeometryError(
                    f"Site.lenses[{j}] (x from {x0:g} to {x1:g} m) reaches beyond the block "
                    f"[{self.x_left:g}, {self.x_right:g}] m"
                )
            at = xs[(xs >= x0) & (xs <= x1)]
            lower, upper = (c[0] for c in self._lens_at(j, at))
            ground = np.minimum(self.ground_z(at, "left"), self.ground_z(at, "right"))
            if np.any(upper > ground + TOL * self.width):
                x = at[np.argmax(upper > ground + TOL * self.width)]
                raise GeometryError(
                    f"Site.lenses[{j}] at x={x:g} m rises above the ground (z={float(self.ground_z(x)):g} "
                    "m): a lens is a region of soil below the ground"
                )
            if np.any(lower < self.z_bottom - TOL * self.width):
                raise GeometryError(
                    f"Site.lenses[{j}] reaches below the block bottom z={self.z_bottom:g} m: deepen the block"
                )
            for i in range(j):  # the outlines are linear between breaks: an overlap shows at one
                a0, a1 = self._lens_span(i)
                both = at[(at >= a0) & (at <= a1)]
                lo_j, up_j = (c[0] for c in self._lens_at(j, both))
                lo_i, up_i = (c[0] for c in self._lens_at(i, both))
                if len(both) and np.any(np.minimum(up_j, up_i) - np.maximum(lo_j, lo_i) > TOL * self.width):
                    raise GeometryError(f"Site.lenses[{i}] and [{j}] overlap: give each soil one region")

    def _check_trench(self, i, x0, x1, level, xs):
        """An embedded strip's trench: inside the block, clear of every other foundation (a wall of backfill
        between them) and dry (a flooded trench is not built)."""
        if level <= self.z_bottom + TOL * self.width:
            raise GeometryError(
                f"strips[{i}].level={level:g} m lies at or below the block bottom z={self.z_bottom:g} m"
            )
        if x0 <= self.x_left + TOL * self.width or x1 >= self.x_right - TOL * self.width:
            raise GeometryError(
                f"strips[{i}] ({x0:g}, {x1:g}) m is embedded (level {level:g} m) against the block's side: "
                "its trench needs backfill on both sides; widen the block"
            )
        for j, other in enumerate(self.strips):
            a, b = other.ends
            if j != i and b >= x0 - TOL * self.width and a <= x1 + TOL * self.width:
                raise GeometryError(
                    f"strips[{j}] ({a:g}, {b:g}) m touches or overlaps the trench of the embedded "
                    f"strips[{i}] ({x0:g}, {x1:g}) m, level {level:g} m: leave backfill between them"
                )
        inside = xs[(xs >= x0) & (xs <= x1)]
        if self.has_water and np.any(self.water_z(inside) > level + TOL * self.width):
            raise GeometryError(
                f"strips[{i}]: the water table (z up to {float(self.water_z(inside).max()):g} m) lies above "
                f"its base level {level:g} m: a flooded trench is not built; lower the water table or "
                "raise the strip"
            )
