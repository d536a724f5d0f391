"""The pieces of a :class:`~ssi.scene.site.Site` that an engineer lists: boreholes, layers whose stiffness and
strength grow with depth, foundation strips and rigid strips (the site itself, its geometry and its mesh are
in :mod:`.site`; the built model in :mod:`.site_built`)."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from ..core.geometry import GeometryError
from ..core.validate import check_instance, check_optional_real, check_real
from ..materials.soil_laws import SoilLayer
from .parts import Contact, Foundation

__all__ = ["Borehole", "DepthVarying", "Lens", "RigidStrip", "Strip"]


@dataclass(frozen=True)
class Borehole:
    """A borehole at ``x`` [m]: ``boundaries`` the elevations z [m] of the layer boundaries met from the top
    down (one fewer than the site's layers; non-increasing, equal values: a layer absent there)."""

    x: float
    boundaries: tuple = ()

    def __post_init__(self):
        check_real("Borehole.x", self.x, unit="m")
        z = tuple(
            float(check_real(f"Borehole.boundaries[{i}]", v, unit="m")) for i, v in enumerate(self.boundaries)
        )
        for i in range(1, len(z)):
            if z[i] > z[i - 1]:
                raise GeometryError(
                    f"Borehole at x={self.x}: boundaries[{i}]={z[i]} lies above boundaries[{i - 1}]="
                    f"{z[i - 1]}; "
                    "list them from the top down (equal values: a layer pinched out)"
                )
        object.__setattr__(self, "boundaries", z)


@dataclass(frozen=True)
class Lens:
    """A closed region of another soil in a site (a lens, a pocket, a wedge): ``points`` [(x, z), ...] [m]
    its outline (a polygon, either orientation, not closed by repeating the first point), ``layer`` its
    SoilLayer or DepthVarying (``thickness`` not used). The outline must be x-monotone -- every vertical
    line meets it at most twice, so it is the region between a lower and an upper chain -- which is what a
    lens drawn from boreholes is; an outline that folds back is refused by name."""

    points: tuple
    layer: object

    def __post_init__(self):
        check_instance("Lens.layer", self.layer, (SoilLayer, DepthVarying))
        try:
            pts = tuple((float(x), float(z)) for x, z in self.points)
        except (TypeError, ValueError) as err:
            raise GeometryError(
                f"Lens.points must be a list of (x, z) points [m], got {self.points!r}"
            ) from err
        for i, (x, z) in enumerate(pts):
            check_real(f"Lens.points[{i}].x", x, unit="m")
            check_real(f"Lens.points[{i}].z", z, unit="m")
        if len(pts) < 3:
            raise GeometryError(f"Lens.points: an outline needs at least 3 points, got {len(pts)}")
        object.__setattr__(self, "points", pts)
        self.chains()  # refuses an outline that is not x-monotone or has no area

    def chains(self):
        """((xs, zs) of the lower chain, (xs, zs) of the upper chain), each with x strictly increasing from
        the outline's leftmost to its rightmost x (a vertical end edge: the lowest point starts the lower
        chain, the highest the upper)."""
        pts = list(self.points)
        area2 = sum(x0 * z1 - x1 * z0 for (x0, z0), (x1, z1) in zip(pts, pts[1:] + pts[:1]))
        if abs(area2) <= 1e-12 * max(1.0, max(abs(v) for p in pts for v in p)) ** 2:
            raise GeometryError(f"Lens.points {pts}: the outline has no area")
        if area2 < 0:  # counter-clockwise: along the bottom to the right, back along the top
            pts = pts[::-1]
        n, xs = len(pts), [p[0] for p in pts]
        lo_x, hi_x = min(xs), max(xs)
        start = min((i for i in range(n) if xs[i] == lo_x), key=lambda i: pts[i][1])
        end = min((i for i in range(n) if xs[i] == hi_x), key=lambda i: pts[i][1])
        top_r = max((i for i in range(n) if xs[i] == hi_x), key=lambda i: pts[i][1])
        top_l = max((i for i in range(n) if xs[i] == lo_x), key=lambda i: pts[i][1])

        def walk(a, b):  # the points from a to b, counter-clockwise
            out = [pts[a]]
            while a != b:
                a = (a + 1) % n
                out.append(pts[a])
            return out

        lower, upper = walk(start, end), walk(top_r, top_l)[::-1]
        for name, chain in (("lower", lower), ("upper", upper)):
            cx = [p[0] for p in chain]
            if any(b <= a for a, b in zip(cx, cx[1:])) or len(lower) + len(upper) < n:
                raise GeometryError(
                    f"Lens.points {list(self.points)}: the outline is not x-monotone (its {name} side turns "
                    "back in x): a vertical line must meet it at most twice; split it into such lenses"
                )
        as_arrays = [tuple(np.array(v, np.float64) for v in zip(*c)) for c in (lower, upper)]
        return as_arrays[0], as_arrays[1]


@dataclass(frozen=True)
class DepthVarying:
    """``layer`` whose E and c grow with depth: E = layer.E + E_inc * max(z_ref - z, 0), c = layer.c + c_inc *
    max(z_ref - z, 0); ``E_inc`` [Pa/m], ``c_inc`` [Pa/m], ``z_ref`` [m] reference elevation (None: the
    ground surface above the point)."""

    layer: SoilLayer
    E_inc: float = 0.0
    c_inc: float = 0.0
    z_ref: float | None = None

    def __post_init__(self):
        check_instance("DepthVarying.layer", self.layer, SoilLayer)
        check_real("DepthVarying.E_inc", self.E_inc, lo=0.0, unit="Pa/m")
        check_real("DepthVarying.c_inc", self.c_inc, lo=0.0, unit="Pa/m")
        check_optional_real("DepthVarying.z_ref", self.z_ref, unit="m")
        if self.c_inc and self.layer.c is None:
            raise ValueError(f"DepthVarying.c_inc={self.c_inc}: the layer is elastic (c=None), give it a c")

    def at(self, depth: float) -> SoilLayer:
        """The layer's material at ``depth`` [m] below the reference level."""
        d = max(float(depth), 0.0)
        c = None if self.layer.c is None else self.layer.c + self.c_inc * d
        return replace(self.layer, E=self.layer.E + self.E_inc * d, c=c)


@dataclass(frozen=True)
class Strip:
    """A foundation strip of a site resting on the ground through its own ``contact``. ``level`` [m]: the
    elevation of its base (None: the ground under it; the ground must be level there). A level below the
    ground embeds the strip: the site gets a trench from the ground down to ``level`` between the strip's
    ends (its soil removed), the soil beside it is the backfill, and ``side_contact`` (a :class:`Contact`,
    its own Coulomb parameters; None: none) puts interfaces between the trench walls and the strip's
    vertical sides, which move rigidly with the strip's end nodes (:mod:`ssi.elements.side_interface`)."""

    rigid: ClassVar[bool] = False  # a plate strip on an interface (RigidStrip: True)

    foundation: Foundation
    contact: Contact
    level: float | None = None
    side_contact: Contact | None = None

    @property
    def ends(self) -> tuple[float, float]:
        """(x0, x1) [m] of the strip."""
        return self.foundation.x0, self.foundation.x1

    def __post_init__(self):
        check_instance("Strip.foundation", self.foundation, Foundation)
        check_instance("Strip.contact", self.contact, Contact)
        check_optional_real("Strip.level", self.level, unit="m")
        check_instance("Strip.side_contact", self.side_contact, Contact, optional=True)
        if self.side_contact is not None and self.level is None:
            raise GeometryError(
                "Strip.side_contact needs an embedded strip: give Strip.level, the elevation of its base "
                "below the ground [m]"
            )


@dataclass(frozen=True)
class RigidStrip:
    """A rigid strip footing from ``x0`` to ``x1`` [m] on level ground, without plate or interface: the
    ground nodes under it are its base, pushed down by ``settle`` [m] times the load factor (displacement
    control: the reaction is the load, :meth:`SiteResult.rigid_pressure`); ``rough``: their u held too.
    ``level`` [m] and ``side_contact`` as for :class:`Strip`: a level below the ground embeds it in a trench
    (its base the trench bottom), and ``side_contact`` puts interfaces on the trench walls whose structure
    side is one rigid body moving with the base: settling by ``settle`` times the load factor, not
    rotating, its horizontal motion held (or prescribed by a :class:`~ssi.scene.loads.Push`)."""

    rigid: ClassVar[bool] = True  # no plate, no interface: its base nodes are pushed down

    x0: float
    x1: float
    settle: float
    rough: bool = True
    level: float | None = None
    side_contact: Contact | None = None

    @property
    def ends(self) -> tuple[float, float]:
        """(x0, x1) [m] of the strip."""
        return self.x0, self.x1

    def __post_init__(self):
        check_real("RigidStrip.x0", self.x0, unit="m")
        check_real("RigidStrip.x1", self.x1, lo=self.x0, lo_open=True, unit="m (> x0)")
        check_real("RigidStrip.settle", self.settle, lo=0.0, lo_open=True, unit="m")
        check_optional_real("RigidStrip.level", self.level, unit="m")
        check_instance("RigidStrip.side_contact", self.side_contact, Contact, optional=True)
        if self.side_contact is not None and self.level is None:
            raise GeometryError(
                "RigidStrip.side_contact needs an embedded strip: give RigidStrip.level, the elevation of "
                "its base below the ground [m]"
            )
