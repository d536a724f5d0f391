"""The loads a scene can carry: column loads and strip loads on the foundation, its self-weight, pressures on
the ground, and a prescribed settlement of a rigid footing.
"""

from dataclasses import dataclass

from ..core.validate import (
    check_real,
)


@dataclass(frozen=True)
class ColumnLoad:
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


@dataclass(frozen=True)
class SurfacePressure:
    """A pressure ``q`` [Pa] (> 0 downwards) on the ground surface from ``x0`` to ``x1`` [m] (both become mesh
    lines); beside the foundation, not under it (a load on the strip is a :class:`StripLoad`)."""

    x0: float
    x1: float
    q: float


@dataclass(frozen=True)
class StripLoad:
    """A distributed load on the strip [N/m^2 = Pa], > 0 downwards: ``q`` at ``x0`` varying linearly to
    ``q_end`` at ``x1`` (default: uniform ``q`` over the whole strip). x0, x1 [m] become plate nodes."""

    q: float
    q_end: float | None = None
    x0: float | None = None
    x1: float | None = None


@dataclass(frozen=True)
class StripWeight:
    """Self-weight of the strip from its section: ``unit_weight`` [N/m^3] times the section depth [m], a
    uniform downward load [Pa] applied in the phase that lists it (reinforced concrete: 25e3). Below the
    water level the strip's buoyancy gamma_w [N/m^3] times its submerged thickness [m] is netted from it (the
    water pressure on its base exceeds that on its top by that much)."""

    unit_weight: float = 25e3


@dataclass(frozen=True)
class Settlement:
    """Push-over: a prescribed further settlement ``w`` [m] (> 0 downwards) during the phase that lists it.
    ``x=None``: the rigid strip (every plate node settles by w, rotations held); else the plate nodes at the
    positions ``x`` [m] (columns) settle by w. The reaction is the load: read it with
    :meth:`BuiltScene.contact_force`. The settled nodes stay held in later phases."""

    w: float
    x: tuple | None = None


# what Scene.loads (and a Phase's loads) may hold, and the per-segment contact type of a list Scene.contact
LOAD_TYPES = (ColumnLoad, SurfacePressure, StripLoad, StripWeight, Settlement)
