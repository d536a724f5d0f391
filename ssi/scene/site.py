"""Any site an engineer draws: layers from boreholes or boundary polylines, a ground-surface polyline, a
water table, several foundations, and stiffness and strength growing with depth within a layer.

    site = Site(width=30.0, depth=12.0,
                layers=[SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3),
                        SoilLayer(1.0, E=40e6, nu=0.3, unit_weight=19e3)],
                boreholes=[Borehole(-10.0, [-2.0]), Borehole(10.0, [-5.0])],   # the boundary dips
                ground=[(-15.0, 0.0), (15.0, 0.0)],
                strips=[Strip(Foundation(-6.0, -4.0, section), Contact(kn=1e10, kt=1e9)),
                        Strip(Foundation(4.0, 6.0, section), Contact(kn=1e10, kt=1e9))],
                loads=[ColumnLoad(-5.0, N=300e3), ColumnLoad(5.0, N=300e3)])
    built = site.build()          # the mesh: structured where it can serve, else gmsh Q8
    out = built.solve()
    out.strip_settlement(0), out.differential_settlement(0, 1)

Geometry. The block spans x in [-width/2, width/2] down to z = -depth (z upwards, m). The ground is the
polyline ``ground`` (x increasing; extended level beyond its ends; default z = 0); two consecutive points at
one x are a vertical step, the face of a cut (the cells beside it made conforming, meshed by gmsh; a
SurfacePressure may end at its crest, not cross it). Layers are listed from the
top down; the boundary between layer k and k + 1 is given either by ``boreholes`` (each lists the boundary
elevations at its x, from the top down; between boreholes the boundaries are interpolated linearly, beyond
the outermost ones they are level) or by ``boundaries`` (one polyline per boundary), or both mixed (a None
-- in a file an empty ``[]`` -- in ``boundaries`` takes that boundary from the boreholes, which list only
those). A :class:`Lens` is a closed region of another soil (an x-monotone outline: its lower and upper sides
are cut lines of the columns it spans, its cells region ``len(layers) + j``; the K0 state, the structured
mesh and the limit analysis are refused with one). Equal elevations make a layer pinch out; a boundary
above the ground is cut by it (the layer is eroded there). A layer's
``SoilLayer.thickness`` is not used by a site (the boundaries decide), except on the structured path, where it
is set from the boundaries.

The geometry is a :class:`ssi.core.geometry.Geometry`: the block cut by vertical lines at every break (ground
vertices, boreholes, polyline vertices, foundation ends, load points, and where the ground crosses a
boundary) into columns, each column cut by the layer boundaries into cells. The soil mesh meshes every cell,
and a triangle mesher (limit analysis) can take the same description (:meth:`Geometry.as_pslg`).

Embedded strips. A :class:`Strip` or :class:`RigidStrip` whose ``level`` lies below the ground is
embedded: the site gets a trench between its ends from the ground down to that level (the soil there is
removed; the base level is a mesh line across the site, so the trench walls end at a node), the soil
beside it is the backfill, and the strip's ``side_contact`` puts interfaces on both walls. The ground over
the strip must be level; refused
with a named error: a trench against the block's side, another foundation touching or overlapping the
trench, a water table above the base level in the trench (a flooded trench), a level in the air or at the
block bottom. A layer boundary may pass through the backfill or the trench (the trench removes what lies
above the level). The initial stress is gravity loading with the trench open (the walls are free faces,
not K0 ground: ``initial_stress="K0"`` is refused), so the side interfaces start without traction.

Mesh. ``mesher="structured"`` uses the graded block of :func:`ssi.core.mesh.soil_block` (level ground at
z = 0 and level boundaries only; the fast path); ``"gmsh"`` the unstructured Q8 mesh of
:func:`ssi.core.gmsh_mesh.mesh_geometry`; ``"auto"`` (default) the structured one wherever it can serve (level
ground and boundaries, at most one strip, embedded or not: the block's trench of
:func:`ssi.core.mesh.soil_block`).

Initial stress. ``initial_stress="K0"``: the geostatic K0 state (:func:`ssi.materials.soil_laws.
geostatic_stress`), valid for level ground over level layer boundaries only (refused otherwise);
``"gravity"``: the soil's weight switched on in a first, elastic phase (a linear solve on the same mesh, the
strips absent); the stress of that solve, in equilibrium with the weight, is the initial stress and its
displacement is discarded; ``"gravity_plastic"``: the same with the soil's own (plastic) laws, the weight
ramped up in automatic increments (the stress is kept, the plastic history of that phase is not). The
elastic state may lie outside a soil's strength (a steep slope); the first loaded step then carries that
out-of-balance, which "gravity_plastic" avoids.
``"auto"``: K0 where it applies (level and no embedded strip), else gravity.
``BuiltSite.initial_stress_method`` says which was used.

Stiffness and strength growing with depth: :class:`DepthVarying` (PLAXIS's E_inc, c_inc): E = E_ref + E_inc
(z_ref - z) below the reference elevation z_ref (above it E_ref), the same for c; ``depth_varying="gauss"``
(default) evaluates them at each Gauss point of the soil elements (a material row per point,
:class:`ssi.elements.soil_q8_points.SoilQ8Points`), ``"centroid"`` once per element at its centroid (a
piecewise-constant field, whose error falls only with the element size). A site without DepthVarying
layers builds the element-wise group either way.

Water. ``water_level`` is the water table's ELEVATION [m] (a level or a polyline of (x, z) points, as the
ground: PLAXIS's phreatic level); ``water_table`` its DEPTH [m] below the ground, the word's meaning in a
:class:`~ssi.scene.scene.Scene` too (on sloping ground the table then follows the ground). One or neither.
A value that reads as the other convention is refused by name: a level above the ground everywhere, a
negative depth (ponding, which a site does not build), a polyline given as a depth, either at or below the
block bottom everywhere (for a dry site leave both out).

Supports: the bottom fixed, the sides on vertical rollers (the separated block of the paper's Fig. 1).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np

from ..capacity import CapacityResult, SafetyFactorResult, limit_analysis, safety_factor
from ..core.geometry import GeometryError
from ..core.gmsh_mesh import check_quality
from ..core.validate import check_choice, check_instance, check_real
from ..materials.soil_laws import GAMMA_W, SoilLayer
from ..solver.progress import announce_compilation
from .loads import LOAD_TYPES, Push
from .parts import MeshSize
from .site_built import BuiltSite
from .site_checks import TOL, SiteChecks, _polyline
from .site_mesh import SiteMesh
from .site_parts import Borehole, DepthVarying, Lens, RigidStrip, Strip
from .site_view import SiteResult, gibson_settlement

# the public names of a site, importable from here (the README and chapter 19 do)
__all__ = [
    "Borehole",
    "BuiltSite",
    "DepthVarying",
    "Lens",
    "RigidStrip",
    "Site",
    "SiteResult",
    "Strip",
    "gibson_settlement",
]


@dataclass
class Site(SiteChecks, SiteMesh):
    """A site: see the module docstring. ``layers`` (SoilLayer or DepthVarying) from the top down;
    ``boreholes`` or ``boundaries`` (len(layers) - 1 boundaries); ``ground`` polyline [(x, z)] [m];
    ``water_level``: the water table's ELEVATION [m] (z up, as ``ground``: PLAXIS's phreatic level) or a
    polyline [(x, z)], or ``water_table``: its DEPTH [m] below the ground, as a :class:`Scene`'s (on sloping
    ground it follows the ground); one of them or neither (dry); the weight below it is the buoyant one;
    ``strips``; ``loads`` (ColumnLoad on a strip, SurfacePressure on the ground, Push of a strip sideways:
    its ``x`` picks the strip, None: the only one); ``mesh`` sizes;
    ``mesher`` "auto" | "structured" | "gmsh"; ``initial_stress`` "auto" | "K0" | "gravity" |
    "gravity_plastic"; ``depth_varying`` "gauss" | "centroid" (where a DepthVarying layer is sampled);
    ``lenses``: :class:`Lens` es, closed regions of another soil;
    ``phases``: :class:`~ssi.scene.parts.Phase` s solved in turn after ``loads`` (their loads and factors,
    as a scene's; excavations and drainage switches are a scene's only, refused by name)."""

    kind: ClassVar[str] = "site"  # the input's kind (a Scene's: "scene"), as result files name it

    width: float
    depth: float
    layers: list
    boreholes: list | None = None
    boundaries: list | None = None
    ground: list | None = None
    water_table: float | None = None
    strips: list = field(default_factory=list)
    loads: list = field(default_factory=list)
    mesh: MeshSize = field(default_factory=MeshSize)
    mesher: str = "auto"
    initial_stress: str = "auto"
    gamma_w: float = GAMMA_W
    depth_varying: str = "gauss"
    water_level: float | list | None = None
    phases: list = field(default_factory=list)
    lenses: list = field(default_factory=list)

    def __post_init__(self):
        self.width = check_real("Site.width", self.width, lo=0.0, lo_open=True, unit="m")
        self.depth = check_real("Site.depth", self.depth, lo=0.0, lo_open=True, unit="m")
        check_choice("Site.mesher", self.mesher, ("auto", "structured", "gmsh"))
        check_choice("Site.initial_stress", self.initial_stress, ("auto", "K0", "gravity", "gravity_plastic"))
        check_instance("Site.mesh", self.mesh, MeshSize)
        check_choice("Site.depth_varying", self.depth_varying, ("gauss", "centroid"))
        if not self.layers:
            raise ValueError("Site.layers: a site needs at least one soil layer")
        for i, lay in enumerate(self.layers):
            check_instance(f"Site.layers[{i}]", lay, (SoilLayer, DepthVarying))
        for i, s in enumerate(self.strips):
            check_instance(f"Site.strips[{i}]", s, (Strip, RigidStrip))
        for i, ld in enumerate(self.loads):
            if type(ld) not in LOAD_TYPES.values():
                raise TypeError(f"Site.loads[{i}] must be a load of {sorted(LOAD_TYPES)}, got {ld!r}")
            if not ld.on_site:
                site_loads = sorted(n for n, c in LOAD_TYPES.items() if c.on_site)
                raise ValueError(
                    f"Site.loads[{i}]: {type(ld).__name__} is not one a site takes: {site_loads}"
                )
        self._check_phases()
        n_b = len(self.layers) - 1
        self.x_left, self.x_right = -0.5 * self.width, 0.5 * self.width
        self.z_bottom = -self.depth
        gx, gz = (
            (np.array([0.0]), np.array([0.0]))
            if self.ground is None
            else _polyline("Site.ground", self.ground, steps=True)
        )
        self._ground = (gx, gz)
        # the vertical steps of the ground (i: points i and i + 1 share their x): the ground has two
        # elevations there, the one left of the step and the one right of it
        self._steps = [int(i) for i in np.flatnonzero(np.diff(gx) == 0.0)]
        for i in self._steps:
            if not (self.x_left < gx[i] < self.x_right):
                raise GeometryError(
                    f"Site.ground: the vertical step at x={gx[i]:g} m must lie inside the block "
                    f"({self.x_left:g}, {self.x_right:g}) m"
                )
        self._raw = self._boundary_lines(n_b)  # (x, z) of each boundary
        for i, lens in enumerate(self.lenses):
            check_instance(f"Site.lenses[{i}]", lens, Lens)
        self._water = self._water_line()
        self._check_geometry()

    def soils(self) -> list:
        """The soil of each region of the geometry: ``layers``, then each lens's layer (region = index)."""
        return list(self.layers) + [lens.layer for lens in self.lenses]

    def all_loads(self) -> list:
        """``loads`` and every phase's loads, in that order (what the mesh and the checks must serve)."""
        return list(self.loads) + [ld for ph in self.phases for ld in ph.loads]

    def sections(self) -> list:
        """The sections of the plate strips, in the order of ``strips`` (a RigidStrip has none)."""
        return [s.foundation.section for s in self.strips if not s.rigid]

    def with_sections(self, fn) -> Site:
        """A copy whose every plate strip's section is ``fn(section)``."""
        strips = [
            s if s.rigid else replace(s, foundation=replace(s.foundation, section=fn(s.foundation.section)))
            for s in self.strips
        ]
        return replace(self, strips=strips)

    # ---- geometry -----------------------------------------------------------------------------------------
    def ground_z(self, x, side: str | None = None) -> np.ndarray:
        """Elevation [m] of the ground at ``x``; at a vertical step the top of its face, or with ``side``
        "left" / "right" the ground just left / right of it (what a column of the geometry ending / starting
        there has)."""
        gx, gz = self._ground
        z = np.interp(x, gx, gz)
        for i in self._steps:
            at = np.abs(np.asarray(x, np.float64) - gx[i]) <= TOL * max(1.0, self.width)
            pick = {None: max(gz[i], gz[i + 1]), "left": gz[i], "right": gz[i + 1]}[side]
            z = np.where(at, pick, z)
        return z

    def boundary_z(self, k: int, x, side: str | None = None) -> np.ndarray:
        """Elevation [m] of the boundary below layer ``k`` at ``x``, cut by the ground (min of both)."""
        return np.minimum(np.interp(x, *self._raw[k]), self.ground_z(x, side))

    def water_z(self, x, side: str | None = None) -> np.ndarray:
        """Elevation [m] of the water table at ``x`` (-inf: dry), whichever field gave it (``side``: at a step
        of the ground, as :meth:`ground_z`)."""
        kind, value = self._water
        if kind == "dry":
            return np.full(np.shape(x), -np.inf)
        if kind == "depth":
            return self.ground_z(x, side) - value
        if kind == "level":
            return np.full(np.shape(x), value)
        return np.interp(x, *value)

    @property
    def has_water(self) -> bool:
        """True if the site has a water table (``water_level`` or ``water_table`` given)."""
        return self._water[0] != "dry"

    def _strip_ends(self):
        return sorted(s.ends for s in self.strips)

    def embedded(self) -> list[tuple[int, float, float, float]]:
        """(index, x0 [m], x1 [m], base level [m]) of every embedded strip (a Strip whose ``level`` lies below
        the ground at its left end; a Strip or a RigidStrip): the site has a trench there, its soil removed
        down to the level."""
        out = []
        for i, s in enumerate(self.strips):
            if s.level is not None:
                x0, x1 = s.ends
                if s.level < float(self.ground_z(x0, "right")) - TOL * self.width:
                    out.append((i, x0, x1, float(s.level)))
        return out

    def base_z(self, i: int) -> float:
        """Elevation [m] of the base of strip ``i``: its level if embedded, else the ground under it."""
        s = self.strips[i]
        x0, _ = s.ends
        return float(self.ground_z(x0, "right")) if s.level is None else float(s.level)

    def _strip_at(self, x):
        for i, s in enumerate(self.strips):
            x0, x1 = s.ends
            if not s.rigid and x0 - 1e-9 <= x <= x1 + 1e-9:
                return i
        return None

    def limit_analysis(self, gap: float = 0.02, **options) -> CapacityResult:
        """The site's capacity as a certified bracket by finite-element limit analysis: lambda scales the
        site's loads (a lone RigidStrip: lambda is its vertical force [N/m]), the soil's weight held; every
        strip a rigid body on its contact, a RigidStrip translating, a Strip also rotating (see
        :mod:`ssi.capacity`; ``options`` of :func:`ssi.capacity.limit_analysis`). A
        :class:`Push` is refused: a horizontal push is not built in the limit analysis. An embedded strip
        stands in its trench, the side soil modelled, the walls free or on its ``side_contact``
        (:mod:`ssi.capacity`). A site has no phases: ``phase`` is refused by name."""
        if options.get("phase") is not None and not self.phases:
            raise ValueError(
                f"phase={options['phase']!r}: a site has no phases (its loads are the ones scaled)"
            )
        if self.phases:
            raise ValueError(
                f"Site.phases={[ph.name for ph in self.phases]}: the limit analysis of a phased site is not "
                "built (a site's limit analysis scales its loads); give the loads to scale as Site.loads of "
                "a site without phases"
            )
        options.pop("phase", None)
        if self.lenses:
            raise ValueError(
                f"Site.limit_analysis: Site.lenses ({len(self.lenses)}): a lens's soil is not built in the "
                "limit analysis (it would take the layer around it); solve the site, or give the lens as a "
                "layer between boundaries"
            )
        pushes = [ld for ld in self.loads if ld.drives == "horizontal"]
        if pushes:
            raise ValueError(
                f"Site.limit_analysis: {pushes[0]!r} in Site.loads: a horizontal push is not built in the "
                "limit analysis; give the horizontal force as ColumnLoad.H, or read the push-over's "
                "SiteResult.push_force"
            )
        return limit_analysis(self, gap=gap, **options)

    def safety_factor(self, gap: float = 0.02, **options) -> SafetyFactorResult:
        """The site's factor of safety by strength reduction (c / F, tan phi / F of the soil and the
        contacts) as a certified bracket [F_LB, F_UB] refined to the relative ``gap``: under its weight and
        its loads at factor 1, or, without loads, its weight alone (a slope's own factor). A lone
        RigidStrip (a push, no load to carry) and a horizontal :class:`Push` are refused
        (:func:`ssi.capacity.safety_factor` for ``options``)."""
        if options.get("phase") is not None:
            raise ValueError(
                f"phase={options['phase']!r}: a site has no phases (its loads are the ones held)"
            )
        options.pop("phase", None)
        pushes = [ld for ld in self.loads if ld.drives == "horizontal"]
        if pushes:
            raise ValueError(
                f"Site.safety_factor: {pushes[0]!r} in Site.loads: a horizontal push has no load to carry; "
                "give the horizontal force as ColumnLoad.H"
            )
        return safety_factor(self, gap=gap, **options)

    def is_level(self) -> bool:
        """Level ground at z = 0, level layer boundaries and a level water table (or none): the K0 state and
        the structured mesh apply."""
        xs = self.breaks()
        flat = np.all(np.abs(self.ground_z(xs)) <= TOL * self.width)
        water = not self.has_water or np.ptp(self.water_z(xs)) <= TOL * self.width
        level = all(np.ptp(np.interp(xs, *r)) <= TOL * self.width for r in self._raw)
        return bool(flat and water and level and not self.lenses)

    def layer_thicknesses(self) -> list[float]:
        """Thicknesses [m] of the layers of a level site (:meth:`is_level`), top down."""
        tops = [0.0] + [float(np.interp(0.0, *r)) for r in self._raw] + [self.z_bottom]
        return [a - b for a, b in zip(tops, tops[1:])]

    def _structured_ok(self) -> str | None:
        """None if the structured block can serve, else why not."""
        if not self.is_level():
            return "the ground or a layer boundary is not level"
        if len(self.strips) > 1:
            return "the block is graded for one foundation"
        if any(t <= TOL * self.depth for t in self.layer_thicknesses()):
            return "a layer is pinched out everywhere"
        return None

    # ---- build ---------------------------------------------------------------------------------------------
    def build(self) -> BuiltSite:
        """Mesh the site, add the soil, the strips and their contacts, the supports, the initial stress and
        the loads. On a fresh install (numba's cache empty) one line on stderr says the kernels compile
        now."""
        announce_compilation()
        why = self._structured_ok()
        if self.mesher == "structured" and why:
            raise GeometryError(f"Site.mesher='structured' cannot serve: {why}")
        use_structured = self.mesher == "structured" or (self.mesher == "auto" and why is None)
        level = self.is_level()
        method = self.initial_stress
        if method == "K0" and not level:
            raise ValueError(
                "Site.initial_stress='K0' is wrong here: the ground or a layer boundary is not level, so the "
                "vertical stress is not the weight of the column above; use 'gravity' (or 'auto')"
            )
        if method == "K0" and self.embedded():
            raise ValueError(
                "Site.initial_stress='K0' is wrong here: an embedded strip's trench walls are free faces, "
                "not K0 ground (the horizontal stress beside them is not K0 times the vertical); use "
                "'gravity' (or 'auto')"
            )
        if method == "auto":
            method = "K0" if level and not self.embedded() else "gravity"
        mesh = self._structured_mesh() if use_structured else self._gmsh_mesh()
        quality = mesh.quality if not use_structured else check_quality(mesh.xy, mesh.conn)
        return BuiltSite.assemble(self, mesh, method, "structured" if use_structured else "gmsh", quality)

    def _load_points(self) -> list[float]:
        out = []
        for ld in self.all_loads():
            out += ld.mesh_lines()  # a column's x, a pressure's ends (a Push: none)
        return out

    def pushed_strip(self, push: Push) -> int:
        """Index of the strip a :class:`Push` moves: the strip under ``push.x`` (None: the only strip)."""
        if push.x is None:
            if len(self.strips) != 1:
                raise GeometryError(
                    f"{push!r}: the site has {len(self.strips)} strips; give Push.x, a point on the pushed "
                    "one"
                )
            return 0
        for i, s in enumerate(self.strips):
            x0, x1 = s.ends
            if x0 - TOL * self.width <= push.x <= x1 + TOL * self.width:
                return i
        raise GeometryError(f"{push!r}: Push.x={push.x:g} m lies on no strip {self._strip_ends()}")
