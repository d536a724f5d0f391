"""The input of a limit analysis: a domain polygon split into regions, each with a rigid-plastic material, and
named boundary segments (fixed, symmetry roller, free or loaded, footing).

Units: metres, pascals, newtons per metre run (plane strain); tension positive; coordinates (x, z) with z
up, gravity along -z. Nothing here knows about elasticity: E and nu do not enter a limit analysis, which is
why a :class:`Site` has no place for them.

A :class:`Site` is what :func:`ssi.limit.mesh.triangulate` meshes and what the bound solvers read; a scene
(or a chapter) builds one with :func:`strip_site` or by listing points, segments and regions itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..core.geometry import Geometry
from ..core.validate import check_choice, check_int, check_real
from ..materials.soil_laws import davis_beta

__all__ = [
    "Beam",
    "Boundary",
    "Footing",
    "Interface",
    "Material",
    "Site",
    "davis_beta",
    "site_from_geometry",
    "strip_site",
]

BOUNDARY_KINDS = ("fixed", "symmetry", "free", "footing")


@dataclass(frozen=True)
class Material:
    """A rigid-plastic Mohr-Coulomb material: cohesion ``c`` [Pa], friction angle ``phi_deg`` [deg] (0: Tresca
    with c the undrained strength), unit weight ``gamma`` [N/m^3] (effective, buoyant below water), dilation
    angle ``psi_deg`` [deg] (None: associated, psi = phi; used only by :meth:`davis`), optional
    ``tension_cutoff`` [Pa]: the largest principal stress allowed (lower bound only; None: no cut-off).

    ``rigid``: a material that never yields (:meth:`rigid_body`; an elastic layer's own assumption, as a
    linear-elastic cluster in PLAXIS): the lower bound imposes no yield condition in it, the upper bound
    lets it move only as a rigid body (no strain rate, no dissipation, no velocity jump on its boundary,
    which the continuous velocity field has nowhere); its c and phi_deg are 0 and unused."""

    c: float
    phi_deg: float
    gamma: float = 0.0
    psi_deg: float | None = None
    tension_cutoff: float | None = None
    rigid: bool = False

    @classmethod
    def rigid_body(cls, gamma: float = 0.0) -> Material:
        """A material that never yields, of unit weight ``gamma`` [N/m^3] (class docstring)."""
        return cls(0.0, 0.0, gamma=gamma, rigid=True)

    def __post_init__(self):
        if self.rigid:
            if self.c != 0.0 or self.phi_deg != 0.0 or self.psi_deg is not None or self.tension_cutoff:
                raise ValueError(
                    "a rigid Material has no strength: give c=0, phi_deg=0, no psi_deg or tension_cutoff "
                    f"(got c={self.c!r}, phi_deg={self.phi_deg!r}, psi_deg={self.psi_deg!r}, "
                    f"tension_cutoff={self.tension_cutoff!r}); use Material.rigid_body(gamma)"
                )
            object.__setattr__(self, "gamma", check_real("gamma", self.gamma, lo=0.0, unit="N/m^3"))
            return
        object.__setattr__(self, "c", check_real("c", self.c, lo=0.0, unit="Pa"))
        object.__setattr__(self, "phi_deg", check_real("phi_deg", self.phi_deg, lo=0.0, hi=60.0, unit="deg"))
        object.__setattr__(self, "gamma", check_real("gamma", self.gamma, lo=0.0, unit="N/m^3"))
        if self.psi_deg is not None:
            psi = check_real("psi_deg", self.psi_deg, lo=0.0, hi=self.phi_deg, unit="deg")
            object.__setattr__(self, "psi_deg", psi)
        if self.tension_cutoff is not None:
            t = check_real("tension_cutoff", self.tension_cutoff, lo=0.0, unit="Pa")
            object.__setattr__(self, "tension_cutoff", t)
        if self.c == 0.0 and self.phi_deg == 0.0:
            raise ValueError("a Material needs c > 0 or phi_deg > 0 (got c = 0 and phi_deg = 0: no strength)")

    @property
    def associated(self) -> bool:
        return self.psi_deg is None or self.psi_deg == self.phi_deg

    def davis(self) -> Material:
        """The associated material of Davis (1968): c* = beta c, tan phi* = beta tan phi (psi* = phi*)."""
        if self.associated or self.rigid:
            return replace(self, psi_deg=None)
        b = davis_beta(self.phi_deg, self.psi_deg)
        phi = math.degrees(math.atan(b * math.tan(math.radians(self.phi_deg))))
        return replace(self, c=b * self.c, phi_deg=phi, psi_deg=None)

    def reduced(self, factor: float) -> Material:
        """The strength-reduced material c / F, tan phi / F (F = ``factor`` > 0); a rigid one stays rigid (it
        has no strength to reduce, as an elastic cluster in PLAXIS's safety calculation)."""
        factor = check_real("factor", factor, lo=0.0, lo_open=True)
        if self.rigid:
            return self
        phi = math.degrees(math.atan(math.tan(math.radians(self.phi_deg)) / factor))
        return replace(self, c=self.c / factor, phi_deg=phi)


@dataclass(frozen=True)
class Interface:
    """The contact between a rigid footing and the soil. ``kind``: "rough" (bonded: no velocity jump, the
    soil's own strength governs), "smooth" (no shear, no separation) or "coulomb" (|tau| <= c - sigma_n tan
    phi with cohesion ``c`` [Pa] and friction angle ``phi_deg`` [deg], associated: a slip opens the joint by
    |slip| tan phi). ``psi_deg`` [deg] (coulomb only, None = associated) enters only :meth:`davis`.
    ``tension`` [Pa] (coulomb only): the tension cut-off t_i, sigma_n <= t_i beside the Coulomb cone (0: no
    tension, the paper's contact; None: none, the joint takes tension up to its apex c / tan phi); a
    cut-off above the apex changes nothing. Its flow rule (the support function of the truncated cone):
    an opening d_n >= tan phi |d_t| dissipates t_i d_n + (c - t_i tan phi) |d_t|."""

    kind: str = "rough"
    c: float = 0.0
    phi_deg: float = 0.0
    psi_deg: float | None = None
    tension: float | None = None

    def __post_init__(self):
        check_choice("kind", self.kind, ("rough", "smooth", "coulomb"))
        object.__setattr__(self, "c", check_real("c", self.c, lo=0.0, unit="Pa"))
        object.__setattr__(self, "phi_deg", check_real("phi_deg", self.phi_deg, lo=0.0, hi=60.0, unit="deg"))
        if self.psi_deg is not None:
            psi = check_real("psi_deg", self.psi_deg, lo=0.0, hi=self.phi_deg, unit="deg")
            object.__setattr__(self, "psi_deg", psi)
        if self.kind != "coulomb" and (self.c != 0.0 or self.phi_deg != 0.0):
            raise ValueError(f"c and phi_deg of an Interface need kind 'coulomb', got kind={self.kind!r}")
        if self.tension is not None:
            if self.kind != "coulomb":
                raise ValueError(f"tension of an Interface needs kind 'coulomb', got kind={self.kind!r}")
            t = float(check_real("tension", self.tension, lo=0.0, unit="Pa"))
            if self.phi_deg > 0.0:
                t = min(t, self.c / math.tan(math.radians(self.phi_deg)))  # above the apex: inactive
            object.__setattr__(self, "tension", t)

    @property
    def strength(self) -> tuple[float, float]:
        """(c [Pa], tan phi) of the joint; smooth: (0, 0). Meaningless for rough."""
        return self.c, math.tan(math.radians(self.phi_deg))

    def davis(self) -> Interface:
        if self.kind != "coulomb" or self.psi_deg is None or self.psi_deg == self.phi_deg:
            return replace(self, psi_deg=None)
        b = davis_beta(self.phi_deg, self.psi_deg)
        phi = math.degrees(math.atan(b * math.tan(math.radians(self.phi_deg))))
        return replace(self, c=b * self.c, phi_deg=phi, psi_deg=None)

    def reduced(self, factor: float) -> Interface:
        """c / F, tan phi / F and the tension cut-off / F (all the joint's strengths reduced alike)."""
        if self.kind != "coulomb":
            return self
        phi = math.degrees(math.atan(math.tan(math.radians(self.phi_deg)) / factor))
        t = None if self.tension is None else self.tension / factor
        return replace(self, c=self.c / factor, phi_deg=phi, tension=t)


@dataclass(frozen=True)
class Beam:
    """A footing that bends: a rigid-plastic beam along its base, x0..x1 [m] on a straight horizontal base,
    one element per base edge of the triangle mesh (each element rigid, inextensible), a hinge at each end
    of every element, i.e. on both sides of every base node (with no couple at a node the two act as one).
    A hinge rotating in sagging (tension at the bottom, the rotation rising along +x) dissipates ``mp_sag``
    [N m/m] times its rotation, in hogging ``mp_hog`` [N m/m]; the beam's axis is the base (a load's
    horizontal force above the base is given here as the force at the base and its couple).

    ``interaction``: the hinges' M-N interaction, points ((N [N/m] tension positive, M_sag(N), M_hog(N)
    [N m/m], both >= 0), ...) of the section's resistance with the moment about the base, one of them at
    N = 0 (that one's moments are mp_sag and mp_hog). The capacity is then the polygon P (:meth:`facets`):
    N within the points' range, M below the upper concave hull of the (N, M_sag) points and above the lower
    convex hull of the (N, -M_hog) points; a hinge's rotation theta and axial extension delta obey the
    associated flow rule (normal to P) and dissipate P's support function max over P of (N delta + M
    theta). Empty (default): M_p independent of N (the strip -mp_hog <= M <= mp_sag for every N, no axial
    extension). P is the convex hull of points on the true resistance's boundary, so it lies inside a
    convex resistance: the bracket is that of a beam no stronger than the section (safe), for a ductile
    section only (a brittle one, below minimum reinforcement, forms no hinge).

    ``loads_ref`` / ``loads_dead``: point loads ((x [m], Fx [N/m], Fz [N/m], C [N m/m]), ...) at base
    nodes (the site needs a point at each x), C counter-clockwise; ``pressure_ref`` / ``pressure_dead``
    [Pa]: a uniform downward pressure on the whole beam (self weight, a uniform strip load)."""

    x0: float
    x1: float
    mp_sag: float
    mp_hog: float
    loads_ref: tuple = ()
    loads_dead: tuple = ()
    pressure_ref: float = 0.0
    pressure_dead: float = 0.0
    interaction: tuple = ()

    def __post_init__(self):
        x0 = check_real("x0", self.x0, unit="m")
        check_real("x1", self.x1, lo=x0, lo_open=True, unit="m")
        check_real("mp_sag", self.mp_sag, lo=0.0, lo_open=True, unit="N m/m")
        check_real("mp_hog", self.mp_hog, lo=0.0, lo_open=True, unit="N m/m")
        for name in ("loads_ref", "loads_dead"):
            out = []
            for i, ld in enumerate(getattr(self, name)):
                if len(ld) != 4:
                    raise ValueError(f"{name}[{i}] must be (x, Fx, Fz, C), got {ld!r}")
                v = tuple(float(check_real(f"{name}[{i}][{k}]", a)) for k, a in enumerate(ld))
                if not (self.x0 - 1e-9 <= v[0] <= self.x1 + 1e-9):
                    raise ValueError(
                        f"{name}[{i}]: x={v[0]!r} m lies outside the beam [{self.x0}, {self.x1}] m"
                    )
                out.append(v)
            object.__setattr__(self, name, tuple(out))
        for name in ("pressure_ref", "pressure_dead"):
            object.__setattr__(self, name, float(check_real(name, getattr(self, name), unit="Pa")))
        pts = []
        for i, p in enumerate(self.interaction):
            if len(p) != 3:
                raise ValueError(f"interaction[{i}] must be (N, M_sag, M_hog), got {p!r}")
            n_ = float(check_real(f"interaction[{i}][0]", p[0], unit="N/m"))
            ms = float(check_real(f"interaction[{i}][1]", p[1], lo=0.0, unit="N m/m"))
            mh = float(check_real(f"interaction[{i}][2]", p[2], lo=0.0, unit="N m/m"))
            pts.append((n_, ms, mh))
        if pts:
            zero = [p for p in pts if p[0] == 0.0]
            if (
                len(zero) != 1
                or abs(zero[0][1] - self.mp_sag) > 1e-9 * self.mp_sag
                or abs(zero[0][2] - self.mp_hog) > 1e-9 * self.mp_hog
            ):
                raise ValueError(
                    f"interaction needs exactly one point at N = 0 with M_sag = mp_sag = {self.mp_sag!r} and "
                    f"M_hog = mp_hog = {self.mp_hog!r} N m/m, got {[p for p in pts if p[0] == 0.0]!r}"
                )
            if len({p[0] for p in pts}) != len(pts):
                raise ValueError("interaction: two points at the same N")
        object.__setattr__(self, "interaction", tuple(sorted(pts)))

    @property
    def axial(self) -> bool:
        """Whether the capacity depends on N (an interaction polygon with more than its N = 0 point)."""
        return len(self.interaction) > 1

    def facets(self) -> np.ndarray:
        """The capacity polygon P as rows (a_N [1/m], a_M, b [N m/m]): a_N N + a_M M <= b for every row
        (class docstring); without an interaction, the two rows M <= mp_sag, -M <= mp_hog."""
        if not self.axial:
            return np.array([[0.0, 1.0, self.mp_sag], [0.0, -1.0, self.mp_hog]])
        pts = np.array(self.interaction)
        rows = []
        # sagging: M <= m1 + s (N - n1) on each segment of the upper hull of (N, M_sag); hogging: -M <= h1 +
        # s (N - n1) on each segment of the upper hull of (N, M_hog)
        for col, a_m in ((1, 1.0), (2, -1.0)):
            hull = _upper_hull(pts[:, 0], pts[:, col])
            for (n1, m1), (n2, m2) in zip(hull[:-1], hull[1:]):
                s = (m2 - m1) / (n2 - n1)
                rows.append((-s, a_m, m1 - s * n1))
        rows.append((1.0, 0.0, float(pts[-1, 0])))
        rows.append((-1.0, 0.0, float(-pts[0, 0])))
        return np.array(rows, float)

    def vertices(self) -> np.ndarray:
        """The corners (N [N/m], M [N m/m]) of the bounded polygon P (``axial`` only)."""
        pts = np.array(self.interaction)
        sag = _upper_hull(pts[:, 0], pts[:, 1])
        hog = [(n_, -m) for n_, m in _upper_hull(pts[:, 0], pts[:, 2])]
        return np.array(sag + hog, float)

    def resultant(self, which: str, xc: float) -> tuple[float, float, float]:
        """(Fx, Fz [N/m], moment about x = ``xc`` [N m/m]) of the ``which`` ("ref" or "dead") loads."""
        loads, p = (
            (self.loads_ref, self.pressure_ref) if which == "ref" else (self.loads_dead, self.pressure_dead)
        )
        fx = sum(ld[1] for ld in loads)
        fz = sum(ld[2] for ld in loads) - p * (self.x1 - self.x0)
        m = sum(ld[3] + (ld[0] - xc) * ld[2] for ld in loads) - p * (self.x1 - self.x0) * (
            0.5 * (self.x0 + self.x1) - xc
        )
        return fx, fz, m


def _upper_hull(x: np.ndarray, y: np.ndarray) -> list:
    """The upper concave hull of points (x, y) sorted by x: [(x, y), ...] left to right (monotone chain)."""
    hull: list = []
    for p in zip(x.tolist(), y.tolist()):
        while len(hull) >= 2:
            (x1, y1), (x2, y2) = hull[-2], hull[-1]
            if (x2 - x1) * (p[1] - y1) - (y2 - y1) * (p[0] - x1) >= 0.0:  # hull[-1] not above the chord
                hull.pop()
            else:
                break
        hull.append(p)
    return hull


@dataclass(frozen=True)
class Footing:
    """A rigid footing on the ``footing`` segments of a site: a rigid body with velocity (U, W) of its
    reference point ``centre`` (x_c, z_c) [m] and, if "r" is among its ``moves``, the rotation rate theta
    (counter-clockwise, x right and z up): a point (x, z) of it moves with (U - theta (z - z_c), W + theta
    (x - x_c)).

    With a :class:`Beam` ``beam`` it bends as well: the beam's loads then replace ``load_*`` and ``moment_*``
    (set to their resultants here).

    ``load_ref`` (Fx, Fz) [N/m] and ``moment_ref`` [N m/m] (counter-clockwise about ``centre``) are the
    reference load that the load factor lambda scales, ``load_dead`` and ``moment_dead`` the load held
    fixed (e.g. a column's vertical load while lambda scales a horizontal push). ``moves``: the free
    motions, "x", "z" (translations) and "r" (rotation; needs ``centre``); a held one is a support whose
    reaction needs no equilibrium (the symmetry axis of a half model holds "x" and "r")."""

    interface: Interface = field(default_factory=Interface)
    load_ref: tuple[float, float] = (0.0, -1.0)
    load_dead: tuple[float, float] = (0.0, 0.0)
    moves: tuple[str, ...] = ("x", "z")
    centre: tuple[float, float] | None = None
    moment_ref: float = 0.0
    moment_dead: float = 0.0
    beam: Beam | None = None

    def __post_init__(self):
        for m in self.moves:
            check_choice("moves", m, ("x", "z", "r"))
        if self.beam is not None:
            if not isinstance(self.beam, Beam):
                raise TypeError(f"beam must be an ssi.limit.Beam, got {type(self.beam).__name__}")
            if self.centre is None or "z" not in self.moves or "r" not in self.moves:
                raise ValueError(
                    f"a beam Footing needs 'z' and 'r' in moves and its centre (the beam bends and tilts), "
                    f"got moves={self.moves!r}, centre={self.centre!r}"
                )
            # the loads are the beam's: the footing's resultants are theirs about the centre
            for which in ("ref", "dead"):
                fx, fz, m = self.beam.resultant(which, float(self.centre[0]))
                object.__setattr__(self, f"load_{which}", (fx, fz))
                object.__setattr__(self, f"moment_{which}", m)
        for name in ("load_ref", "load_dead"):
            given = getattr(self, name)
            v = tuple(float(check_real(f"{name}[{i}]", x, unit="N/m")) for i, x in enumerate(given))
            if len(v) != 2:
                raise ValueError(f"{name} must be (Fx, Fz), got {getattr(self, name)!r}")
            object.__setattr__(self, name, v)
        for name in ("moment_ref", "moment_dead"):
            object.__setattr__(self, name, float(check_real(name, getattr(self, name), unit="N m/m")))
        for i, d in enumerate("xz"):
            if d not in self.moves and (self.load_ref[i] != 0.0 or self.load_dead[i] != 0.0):
                raise ValueError(f"Footing load along {d} needs '{d}' in moves, got moves={self.moves!r}")
        if "r" not in self.moves and (self.moment_ref != 0.0 or self.moment_dead != 0.0):
            raise ValueError(f"a Footing moment needs 'r' in moves (rotation free), got moves={self.moves!r}")
        if self.centre is not None:
            c = tuple(float(check_real(f"centre[{i}]", x, unit="m")) for i, x in enumerate(self.centre))
            if len(c) != 2:
                raise ValueError(f"centre must be (x_c, z_c) [m], got {self.centre!r}")
            object.__setattr__(self, "centre", c)
        elif "r" in self.moves:
            raise ValueError("a rotating Footing ('r' in moves) needs its reference point centre=(x_c, z_c)")

    @property
    def rotates(self) -> bool:
        return "r" in self.moves

    def velocity_at(self, motion: np.ndarray, xy: np.ndarray) -> np.ndarray:
        """The rigid-body velocity (n, 2) at points ``xy`` (n, 2) [m] of the motion (U, W, theta) (3,)."""
        xc, zc = self.centre if self.centre is not None else (0.0, 0.0)
        out = np.empty((len(xy), 2))
        out[:, 0] = motion[0] - motion[2] * (xy[:, 1] - zc)
        out[:, 1] = motion[1] + motion[2] * (xy[:, 0] - xc)
        return out


@dataclass(frozen=True)
class Boundary:
    """The condition on one boundary segment. ``kind``: "fixed" (velocity zero), "symmetry" (roller: normal
    velocity and shear traction zero), "free" (traction = -(p_dead(x, z) + lambda pressure_ref) n, n the
    outward normal: a surcharge or a flexible load; both zero: a free surface) or "footing" (in contact with
    ``footing``, an index into :attr:`Site.footings`; ``interface`` the contact on this segment, None: the
    footing's own, e.g. the trench walls of an embedded footing with a side contact unlike its base's).
    Pressures in Pa, compression positive. The dead
    pressure may vary linearly along the segment (a wall's geostatic horizontal stress):
    p_dead(x, z) = ``pressure_dead`` + ``pressure_dead_grad`` . (x, z), the gradient in Pa/m (default zero:
    uniform). Linear is what both bounds take exactly: the lower bound's linear stresses meet it at every
    vertex, the upper bound's Simpson rule integrates it times a quadratic velocity exactly."""

    kind: str
    pressure_dead: float = 0.0
    pressure_ref: float = 0.0
    footing: int = 0
    pressure_dead_grad: tuple[float, float] = (0.0, 0.0)
    interface: Interface | None = None

    def __post_init__(self):
        check_choice("kind", self.kind, BOUNDARY_KINDS)
        if self.interface is not None:
            if not isinstance(self.interface, Interface):
                raise TypeError(
                    f"interface must be an ssi.limit.Interface, got {type(self.interface).__name__}"
                )
            if self.kind != "footing":
                raise ValueError(f"interface applies to kind 'footing' only, got kind={self.kind!r}")
        object.__setattr__(self, "pressure_dead", check_real("pressure_dead", self.pressure_dead, unit="Pa"))
        object.__setattr__(self, "pressure_ref", check_real("pressure_ref", self.pressure_ref, unit="Pa"))
        object.__setattr__(self, "footing", check_int("footing", self.footing, lo=0))
        grad = tuple(self.pressure_dead_grad)
        if len(grad) != 2:
            raise ValueError(f"pressure_dead_grad must be (d/dx, d/dz) [Pa/m], got {grad!r}")
        grad = tuple(
            float(check_real(f"pressure_dead_grad[{i}]", v, unit="Pa/m")) for i, v in enumerate(grad)
        )
        object.__setattr__(self, "pressure_dead_grad", grad)
        if self.kind != "free" and (self.pressure_dead != 0.0 or self.pressure_ref != 0.0 or any(grad)):
            raise ValueError(f"pressures apply to kind 'free' only, got kind={self.kind!r}")

    @property
    def traction_free(self) -> bool:
        """A free surface: kind "free" with no pressure at all."""
        return (
            self.kind == "free"
            and self.pressure_dead == 0.0
            and self.pressure_ref == 0.0
            and not any(self.pressure_dead_grad)
        )

    def dead_at(self, x: float, z: float) -> float:
        """The dead pressure p_dead [Pa] at the point (x, z) [m] of the segment."""
        gx, gz = self.pressure_dead_grad
        return self.pressure_dead + gx * x + gz * z


@dataclass(frozen=True)
class Site:
    """A meshable limit-analysis problem.

    ``points`` (n_p, 2) [m]; ``segments``: (i, j, Boundary) for every segment of the outer boundary, listed
    so that the domain lies on the left of i -> j (counter-clockwise), or (i, j, None) for an interior
    polyline that splits regions; ``regions``: (x, z, material index) seed points, one inside each region;
    ``materials`` and ``footings`` are indexed by regions and boundaries. ``max_area`` [m^2] per region
    material (None: the global ``h`` of the mesher).

    ``scale_all``: lambda multiplies every load together -- the soil's weight, the dead loads and the
    reference loads at factor 1 -- instead of the reference loads alone (:meth:`all_loads`). Both bound
    programs are then bounded whatever the dead loads (the dissipation is >= 0), and lambda >= 1 says
    exactly that the site carries its loads: the test of a strength-reduction factor of safety, also for a
    site loaded by its weight alone (a slope)."""

    points: np.ndarray
    segments: tuple
    regions: tuple
    materials: tuple
    footings: tuple = ()
    scale_all: bool = False

    def __post_init__(self):
        pts = np.ascontiguousarray(self.points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or not np.all(np.isfinite(pts)):
            raise ValueError(f"points must be a finite (n, 2) array, got shape {pts.shape}")
        object.__setattr__(self, "points", pts)
        n = len(pts)
        for s in self.segments:
            i, j, b = s
            if not (0 <= i < n and 0 <= j < n) or i == j:
                raise ValueError(f"segment ({i}, {j}) must join two distinct points of 0..{n - 1}")
            if b is not None and b.kind == "footing" and b.footing >= len(self.footings):
                nf = len(self.footings)
                raise ValueError(f"segment ({i}, {j}) names footing {b.footing}, only {nf} given")
        for r in self.regions:
            if not (0 <= r[2] < len(self.materials)):
                raise ValueError(f"region seed {r} names material {r[2]}, only {len(self.materials)} given")

    def map_materials(self, fn) -> Site:
        """A copy with every material replaced by ``fn(material)`` (Davis, strength reduction)."""
        return replace(self, materials=tuple(fn(m) for m in self.materials))

    def map_interfaces(self, fn) -> Site:
        """A copy with every interface replaced by ``fn(interface)``: the footings' and the segments' own."""
        segs = tuple(
            (i, j, replace(b, interface=fn(b.interface)) if b is not None and b.interface is not None else b)
            for i, j, b in self.segments
        )
        footings = tuple(replace(f, interface=fn(f.interface)) for f in self.footings)
        return replace(self, segments=segs, footings=footings)

    def interface_of(self, boundary: Boundary) -> Interface:
        """The contact on a "footing" segment's ``boundary``: its own, else its footing's."""
        if boundary.interface is not None:
            return boundary.interface
        return self.footings[boundary.footing].interface

    @property
    def interfaces(self) -> tuple:
        """Every interface of the site: each footing's, then each segment's own."""
        own = tuple(b.interface for _, _, b in self.segments if b is not None and b.interface is not None)
        return tuple(f.interface for f in self.footings) + own

    def davis(self, interface: bool = True) -> Site:
        """The Davis-reduced site (soil and, if ``interface``, the footing interfaces)."""
        out = self.map_materials(Material.davis)
        return out.map_interfaces(Interface.davis) if interface else out

    def reduced(self, factor: float, interface: bool = True) -> Site:
        """The site with c / F and tan phi / F (soil and, if ``interface``, the footing interfaces)."""
        out = self.map_materials(lambda m: m.reduced(factor))
        return out.map_interfaces(lambda i: i.reduced(factor)) if interface else out

    def all_loads(self) -> Site:
        """A copy whose lambda multiplies every load together (``scale_all``; class docstring)."""
        return replace(self, scale_all=True)

    @property
    def length_scale(self) -> float:
        """The larger side of the bounding box [m]."""
        return float(np.max(self.points.max(axis=0) - self.points.min(axis=0)))


def strip_site(
    B: float,
    material: Material,
    interface: Interface | None = None,
    half_width: float = 6.0,
    depth: float = 5.0,
    symmetric: bool = True,
    surcharge: float = 0.0,
    load_ref: tuple[float, float] | None = None,
    load_dead: tuple[float, float] = (0.0, 0.0),
    flexible: bool = False,
    side: str = "symmetry",
    base_points: tuple = (),
) -> Site:
    """A strip footing of width ``B`` [m] on the surface z = 0 of a block ``half_width`` [m] either side of
    the axis and ``depth`` [m] deep (base fixed, far sides ``side``: "symmetry" rollers or "fixed").

    ``symmetric``: only x >= 0 modelled, the axis a symmetry roller, the footing moving along z alone.
    ``flexible``: a uniform reference pressure of 1 Pa on the footing's width instead of a rigid footing
    (Smith & Griffiths' program 6.1): lambda is then the pressure [Pa]. Rigid: lambda multiplies
    ``load_ref`` [N/m] (default (0, -B_model): lambda is the mean footing pressure [Pa], B_model the modelled
    width), with ``load_dead`` held. ``surcharge`` [Pa] acts on the free surface beside the footing.
    ``base_points``: x [m] of extra points on the footing's base (where a beam's point loads act; whole
    model only)."""
    B = check_real("B", B, lo=0.0, lo_open=True, unit="m")
    half_width = check_real("half_width", half_width, lo=B / 2, lo_open=True, unit="m")
    depth = check_real("depth", depth, lo=0.0, lo_open=True, unit="m")
    surcharge = check_real("surcharge", surcharge, lo=0.0, unit="Pa")
    check_choice("side", side, ("symmetry", "fixed"))
    interface = Interface() if interface is None else interface
    x0 = 0.0 if symmetric else -half_width
    xf = 0.0 if symmetric else -B / 2
    b_model = B / 2 if symmetric else B
    top_rest = Boundary("free", pressure_dead=surcharge)
    if flexible:
        under = Boundary("free", pressure_ref=1.0)
        footings = ()
    else:
        under = Boundary("footing", footing=0)
        ref = (0.0, -b_model) if load_ref is None else load_ref
        moves = ("z",) if symmetric else ("x", "z")
        footings = (Footing(interface, ref, load_dead, moves),)
    far = Boundary(side)
    if symmetric:
        pts = [(0, -depth), (half_width, -depth), (half_width, 0), (B / 2, 0), (0, 0)]
        segs = [(0, 1, Boundary("fixed")), (1, 2, far), (2, 3, top_rest), (3, 4, under)]
        segs.append((4, 0, Boundary("symmetry")))
    else:
        inner = sorted((float(x) for x in base_points if -B / 2 < x < B / 2), reverse=True)
        top = [(B / 2, 0)] + [(x, 0) for x in inner] + [(xf, 0)]
        pts = [(x0, -depth), (half_width, -depth), (half_width, 0)] + top + [(x0, 0)]
        segs = [(0, 1, Boundary("fixed")), (1, 2, far), (2, 3, top_rest)]
        segs += [(3 + i, 4 + i, under) for i in range(len(top) - 1)]
        n_top = 3 + len(top) - 1
        segs += [(n_top, n_top + 1, top_rest), (n_top + 1, 0, far)]
    seed = ((0.5 * (x0 + B / 2), -0.5 * depth, 0),)
    return Site(np.array(pts, float), tuple(segs), seed, (material,), footings)


def site_from_geometry(
    geometry: Geometry,
    materials: tuple,
    boundary,
    footings: tuple = (),
) -> Site:
    """The limit-analysis :class:`Site` of a site's one geometry description (:class:`ssi.core.geometry.
    Geometry`, the graph the soil mesher meshes too): every cell's region indexes ``materials``; every
    segment tagged "interior" stays an interior polyline (the triangles conform to it); every outer segment
    gets ``boundary(tag, pa, pb)`` -> :class:`Boundary`, with pa, pb its end points (2,) [m] oriented so the
    domain lies on the left of pa -> pb (counter-clockwise, the orientation :class:`Site` needs)."""
    if not isinstance(geometry, Geometry):
        raise TypeError(f"geometry must be an ssi.core.geometry.Geometry, got {type(geometry).__name__}")
    n_reg = int(np.max(geometry.cell_region)) + 1 if len(geometry.cells) else 0
    if len(materials) < n_reg:
        raise ValueError(f"materials: the geometry has {n_reg} regions, {len(materials)} materials given")
    # the orientation of each cell edge in its (counter-clockwise) cell: an outer edge has exactly one
    oriented = {}
    for cell in geometry.cells:
        for a, b in zip(cell, cell[1:] + cell[:1]):
            oriented[(min(a, b), max(a, b))] = (a, b)
    pts = geometry.points
    segments = []
    for (a, b), tag in zip(geometry.segments, geometry.segment_tags):
        a, b = int(a), int(b)
        if tag == "interior":
            segments.append((a, b, None))
            continue
        i, j = oriented[(min(a, b), max(a, b))]
        bnd = boundary(tag, pts[i], pts[j])
        if not isinstance(bnd, Boundary):
            raise TypeError(f"boundary({tag!r}, ...) must return a Boundary, got {type(bnd).__name__}")
        segments.append((i, j, bnd))
    seeds = tuple(
        (*pts[list(c)].mean(axis=0).tolist(), int(r)) for c, r in zip(geometry.cells, geometry.cell_region)
    )
    return Site(pts, tuple(segments), seeds, tuple(materials), tuple(footings))
