"""The loads a scene can carry: column loads and strip loads on the foundation, its self-weight, pressures on
the ground, a prescribed settlement of a rigid footing and a prescribed horizontal push of the strip.

Each load class knows what it does to a built scene and to its mesh: ``effect(built)`` gives its force vector
(n_dof,) [N/m] and the DOFs it prescribes {dof: displacement increment [m]}; ``mesh_lines()`` the x [m] that
must be surface nodes of the mesh; ``limit_action(frame)`` what it is in the limit problem
(:class:`ssi.capacity.LimitAction`: a ground pressure, a force and moment on the footing, a beam strip's
loads, a push, or why it is refused). ``LOAD_TYPES`` (class name -> class) is the one registry of load types:
the scene's checks and the scene file read it. A new load is a class here with those methods and its row in
``LOAD_TYPES``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from ..capacity.action import FootingFrame, LimitAction
from ..core.assembly import scatter_vector
from ..core.validate import check_real

if TYPE_CHECKING:  # for annotations only: the built scene and site import this module
    from .built import BuiltScene
    from .site_built import BuiltSite


class Load:
    """What every load answers besides its ``effect`` and ``mesh_lines`` (the defaults of a force on the
    foundation that a site does not take); each load class overrides what differs. The result views, the
    checks and the summaries ask these, never the load's class."""

    drives: ClassVar[str | None] = None  # None: a force (the load given, the displacement the answer);
    # "vertical" / "horizontal": a prescribed displacement whose reaction is the load
    on_site: ClassVar[bool] = False  # whether a Site applies it (a Scene applies every load)

    def columns(self) -> list[tuple[float, float]]:
        """(x [m], N [N/m] > 0 down) of each column force this load applies: none by default."""
        return []

    def ground_span(self) -> tuple[float, float] | None:
        """(x0, x1) [m] of the ground a pressure loads; None: not a pressure on the ground."""
        return None

    def on_rigid_footing(self) -> bool:
        """Whether a scene with a RigidFooting (no plate, no interface: its base nodes settle together) can
        carry it: a ground pressure, a push and a settlement of the whole footing can; a force on a plate
        cannot."""
        return self.ground_span() is not None or self.drives == "horizontal"

    def magnitudes(self) -> list[tuple[str, float, str, str]]:
        """(label, value, unit, kind) of each value the plausible-units warning reads (kind: "force",
        "pressure" or "unit_weight"): none by default."""
        return []

    def limit_action(self, frame: FootingFrame | None = None) -> LimitAction:
        """What this load is in the limit problem at load factor 1, on the footing ``frame`` (None: without
        one): by default refused by name, so that a load the limit analysis does not represent is never
        silently dropped."""
        return LimitAction(refused=f"a {type(self).__name__} is not represented by ssi.limit")


@dataclass(frozen=True)
class ColumnLoad(Load):
    """Column forces at ``x`` [m] on the strip (the plate mesh gets a node there): ``N`` [N/m] downwards,
    ``H`` [N/m] in +x, ``M`` [N m/m] counter-clockwise, all per metre of the strip's length."""

    x: float
    N: float = 0.0
    H: float = 0.0
    M: float = 0.0

    def __post_init__(self):
        check_real("ColumnLoad.x", self.x, unit="m")
        check_real("ColumnLoad.N", self.N, unit="N/m")
        check_real("ColumnLoad.H", self.H, unit="N/m")
        check_real("ColumnLoad.M", self.M, unit="N m/m")

    on_site: ClassVar[bool] = True  # a site applies it

    def magnitudes(self) -> list[tuple[str, float, str, str]]:
        return [("ColumnLoad.N", self.N, "N/m", "force")]

    def columns(self) -> list[tuple[float, float]]:
        """(x [m], N [N/m] > 0 down) of each column force this load applies: this column."""
        return [(self.x, self.N)]

    def limit_action(self, frame: FootingFrame | None = None) -> LimitAction:
        """N, H, M on the footing (H at the plate's nodes, ``frame.lever`` above the base: its moment about
        the centre of the base is M - N (x - x_c) - H e); on a beam strip a point load at the base with the
        couple -H e."""
        text = f"column N={self.N / 1e3:g} kN/m" + (f" H={self.H / 1e3:g} kN/m" if self.H else "")
        text += f" at x={self.x:g} m"
        if frame is None:
            return LimitAction(text=text)
        lever = frame.lever
        m = self.M - self.N * (self.x - frame.xc) - self.H * lever
        point = (float(self.x), float(self.H), -float(self.N), float(self.M) - float(self.H) * lever)
        return LimitAction(force=(self.H, -self.N, m), beam_points=(point,), text=text)

    def mesh_lines(self) -> list[float]:
        """The column's x [m]: a plate (and surface) node."""
        return [self.x]

    def effect(self, built: BuiltScene | BuiltSite) -> tuple[np.ndarray, dict[int, float]]:
        """N, H, M at the plate node at x (of a site: of the strip under x)."""
        model, f_vec = built.model, np.zeros(built.model.n_dof)
        if self.H != 0.0 and built.slides_freely_at(self.x):
            raise ValueError(
                f"ColumnLoad.H = {self.H:g} N/m at x = {self.x:g} m on a frictionless contact (every "
                "Contact.kt = 0): nothing resists a horizontal load on the strip; give Contact.kt > 0"
            )
        node = built.plate_node_at(self.x)
        for comp, value in (("w", -self.N), ("u", self.H), ("alpha", self.M)):
            f_vec[model.dof(node, comp)] += value
        return f_vec, {}


@dataclass(frozen=True)
class SurfacePressure(Load):
    """A pressure ``q`` [Pa] (> 0 downwards) on the ground surface from ``x0`` to ``x1`` [m] (both become mesh
    lines); beside the foundation, not under it (a load on the strip is a :class:`StripLoad`)."""

    x0: float
    x1: float
    q: float

    on_site: ClassVar[bool] = True  # a site applies it

    def ground_span(self) -> tuple[float, float] | None:
        """(x0, x1) [m] of the ground this pressure loads."""
        return self.x0, self.x1

    def limit_action(self, frame: FootingFrame | None = None) -> LimitAction:
        """A pressure on the ground beside the footing."""
        text = f"pressure q={self.q / 1e3:g} kPa on x=[{self.x0:g}, {self.x1:g}] m"
        return LimitAction(ground=(self.x0, self.x1, self.q), text=text)

    def magnitudes(self) -> list[tuple[str, float, str, str]]:
        return [("SurfacePressure.q", self.q, "Pa", "pressure")]

    def mesh_lines(self) -> list[float]:
        """Both ends [m]."""
        return [self.x0, self.x1]

    def effect(self, built: BuiltScene | BuiltSite) -> tuple[np.ndarray, dict[int, float]]:
        """The consistent nodal forces of the pressure on the ground surface (``built.ground_weights``: the
        ground nodes from x0 to x1 and their share of the loaded length [m])."""
        model, f_vec = built.model, np.zeros(built.model.n_dof)
        for a, b in built.foundation_spans():
            if min(self.x1, b) - max(self.x0, a) > 1e-9:
                raise ValueError(
                    f"SurfacePressure ({self.x0}, {self.x1}) overlaps the strip ({a}, {b}): "
                    "a load on the strip is a StripLoad"
                )
        nodes, w = built.ground_weights(self.x0, self.x1)
        np.add.at(f_vec, model.dof(nodes, "w"), -self.q * w)
        return f_vec, {}


@dataclass(frozen=True)
class StripLoad(Load):
    """A distributed load on the strip [N/m^2 = Pa], > 0 downwards: ``q`` at ``x0`` varying linearly to
    ``q_end`` at ``x1`` (default: uniform ``q`` over the whole strip). x0, x1 [m] become plate nodes."""

    q: float
    q_end: float | None = None
    x0: float | None = None
    x1: float | None = None

    def magnitudes(self) -> list[tuple[str, float, str, str]]:
        return [("StripLoad.q", self.q, "Pa", "pressure")]

    def mesh_lines(self) -> list[float]:
        """The ends [m] that are given."""
        return [v for v in (self.x0, self.x1) if v is not None]

    def limit_action(self, frame: FootingFrame | None = None) -> LimitAction:
        """Its resultant on the footing at the centroid of the trapezoid; on a beam strip a uniform pressure
        if it is uniform over the whole strip (else the beam does not represent it)."""
        q0, q1 = self.q, self.q if self.q_end is None else self.q_end
        text = f"strip load q={q0 / 1e3:g}..{q1 / 1e3:g} kPa"
        if frame is None:
            return LimitAction(text=text)
        a = frame.x0 if self.x0 is None else self.x0
        b = frame.x1 if self.x1 is None else self.x1
        r = 0.5 * (q0 + q1) * (b - a)
        xr = a + (b - a) * (q0 + 2 * q1) / (3 * (q0 + q1)) if q0 + q1 != 0.0 else 0.5 * (a + b)
        full = (self.x0 is None or self.x0 <= frame.x0) and (self.x1 is None or self.x1 >= frame.x1)
        uniform = full and (self.q_end is None or self.q_end == self.q)
        why = (
            None
            if uniform
            else "a StripLoad not uniform over the whole strip is not represented on a beam strip by "
            "ssi.limit; give strip='rigid'"
        )
        force = (0.0, -r, -(r * (xr - frame.xc)))
        return LimitAction(force=force, beam_pressure=self.q if uniform else 0.0, not_on_beam=why, text=text)

    def profile(self, foundation):
        """q(x) [Pa], > 0 upwards as the plate's distributed load takes it, on ``foundation``'s strip."""
        a = foundation.x0 if self.x0 is None else self.x0
        b = foundation.x1 if self.x1 is None else self.x1
        if not (foundation.x0 - 1e-9 <= a < b <= foundation.x1 + 1e-9):
            raise ValueError(
                f"StripLoad x0={a}, x1={b} must satisfy foundation.x0 <= x0 < x1 <= foundation.x1"
            )
        q_end = self.q if self.q_end is None else self.q_end

        def q(x):
            inside = (x >= a - 1e-12) & (x <= b + 1e-12)
            return np.where(inside, -(self.q + (q_end - self.q) * (x - a) / (b - a)), 0.0)

        return q

    def effect(self, built: BuiltScene) -> tuple[np.ndarray, dict[int, float]]:
        """The plate's equivalent nodal forces of the distributed load."""
        f_vec = np.zeros(built.model.n_dof)
        scatter_vector(
            built.plate.edofs,
            built.plate.distributed_load(self.profile(built.scene.foundation), comp="w"),
            f_vec,
        )
        return f_vec, {}


@dataclass(frozen=True)
class StripWeight(Load):
    """Self-weight of the strip from its section: ``unit_weight`` [N/m^3] times the section depth [m], a
    uniform downward load [Pa] applied in the phase that lists it (reinforced concrete: 25e3). Below the
    water level the strip's buoyancy gamma_w [N/m^3] times its submerged thickness [m] is netted from it (the
    water pressure on its base exceeds that on its top by that much)."""

    unit_weight: float = 25e3

    def magnitudes(self) -> list[tuple[str, float, str, str]]:
        return [("StripWeight.unit_weight", self.unit_weight, "N/m^3", "unit_weight")]

    def mesh_lines(self) -> list[float]:
        """None: the weight acts on the whole strip."""
        return []

    def limit_action(self, frame: FootingFrame | None = None) -> LimitAction:
        """The strip's weight less its buoyancy, a uniform pressure over the whole footing."""
        text = f"strip weight {self.unit_weight / 1e3:g} kN/m^3"
        if frame is None:
            return LimitAction(text=text)
        q = self.unit_weight * frame.thickness - frame.buoyancy
        return LimitAction(force=(0.0, -(q * (frame.x1 - frame.x0)), 0.0), beam_pressure=q, text=text)

    def effect(self, built: BuiltScene) -> tuple[np.ndarray, dict[int, float]]:
        """The strip's weight less its buoyancy, as the plate's equivalent nodal forces."""
        f_vec = np.zeros(built.model.n_dof)
        q = self.unit_weight * built.plate.section.thickness - built.scene.gamma_w * built.submerged_depth()
        scatter_vector(built.plate.edofs, built.plate.distributed_load(-q, comp="w"), f_vec)
        return f_vec, {}


@dataclass(frozen=True)
class Settlement(Load):
    """Push-over: a prescribed further settlement ``w`` [m] (> 0 downwards) during the phase that lists it.
    ``x=None``: the rigid strip (every plate node settles by w, rotations held); else the plate nodes at the
    positions ``x`` [m] (columns) settle by w. The reaction is the load: read it with
    :meth:`BuiltScene.contact_force`. The settled nodes stay held in later phases."""

    w: float
    x: tuple | None = None

    drives: ClassVar[str | None] = "vertical"  # a prescribed settlement: the load is the soil's reaction

    def on_rigid_footing(self) -> bool:
        """The whole footing's settlement (``x`` None) only: a RigidFooting has no columns."""
        return self.x is None

    def mesh_lines(self) -> list[float]:
        """The settled columns' x [m] (none for the whole strip)."""
        return [] if self.x is None else list(self.x)

    def limit_action(self, frame: FootingFrame | None = None) -> LimitAction:
        """The whole footing pushed down (lambda is then its vertical force); settled columns are refused:
        the limit problem's footing is a rigid body."""
        if self.x is not None:
            return LimitAction(
                refused=f"Settlement at the columns x={self.x!r} pushes a flexible strip; ssi.limit pushes "
                "the footing as a rigid body: give Settlement(w) with x=None"
            )
        return LimitAction(settles=True)

    def effect(self, built: BuiltScene) -> tuple[np.ndarray, dict[int, float]]:
        """No force: the settled DOFs prescribed (a rigid footing's base, the whole strip with its rotations
        held, or the plate nodes at x)."""
        model, held = built.model, {}
        if built.footing_nodes is not None:  # a RigidFooting's base
            held.update({int(d): -float(self.w) for d in model.dof(built.footing_nodes, "w")})
        else:
            ids = built.plate_nodes if self.x is None else np.array([built.plate_node_at(x) for x in self.x])
            held.update({int(d): -float(self.w) for d in model.dof(ids, "w")})
            if self.x is None:  # rigid strip: rotations held
                held.update({int(d): 0.0 for d in model.dof(ids, "alpha")})
        return np.zeros(model.n_dof), held


@dataclass(frozen=True)
class Push(Load):
    """Horizontal push-over: a prescribed further horizontal displacement ``u`` [m] (> 0 in +x) of the whole
    foundation during the phase that lists it: every plate node's u by ``u``, their rotations held, their
    w free (the strip translates as a rigid body and may rise or settle); of a RigidFooting its base nodes'
    u (their w stays held). The reaction is the load: read it with :meth:`BuiltScene.push_force` (the
    push-over's ``foundation_load()`` and ``capacity()`` then report this horizontal force). ``x`` [m]: a
    point on the pushed strip, which picks the strip of a :class:`~ssi.scene.site.Site` with several (None:
    the only one). The pushed nodes stay held in later phases."""

    u: float
    x: float | None = None

    def __post_init__(self):
        check_real("Push.u", self.u, unit="m")
        if self.x is not None:
            check_real("Push.x", self.x, unit="m")

    drives: ClassVar[str | None] = "horizontal"  # a prescribed displacement: the load is the reaction
    on_site: ClassVar[bool] = True  # a site applies it

    def mesh_lines(self) -> list[float]:
        """None: the push moves the whole strip."""
        return []

    def limit_action(self, frame: FootingFrame | None = None) -> LimitAction:
        """Refused: ssi.limit pushes vertically only."""
        return LimitAction(
            refused="a horizontal Push is not built in the limit analysis; give the horizontal force as "
            "ColumnLoad.H"
        )

    def effect(self, built: BuiltScene | BuiltSite) -> tuple[np.ndarray, dict[int, float]]:
        """No force: the pushed DOFs prescribed (``built.push_held``: a rigid footing's base u; the plate
        nodes' u with their rotations held)."""
        return np.zeros(built.model.n_dof), built.push_held(self)


# the one registry of load types (class name -> class): what Scene.loads and a Phase's loads may hold, and
# the names a scene file's load tables take under ``type``
LOAD_TYPES = {
    cls.__name__: cls for cls in (ColumnLoad, SurfacePressure, StripLoad, StripWeight, Settlement, Push)
}
