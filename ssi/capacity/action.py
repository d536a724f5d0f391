"""What one load does in the limit problem, as data the bridge reads: the extension point of ``ssi.capacity``.

A load class (``ssi/scene/loads.py``) answers ``limit_action(frame)`` with a :class:`LimitAction`; the
bridge (:mod:`ssi.capacity.problem`) sums the actions of a phase's loads into the footing's forces, the
ground pressures and a beam strip's loads, and refuses by name what an action says it cannot represent. The
bridge never asks a load's class. ``frame`` (:class:`FootingFrame`) is what a load needs of the footing it
acts on (None: the problem has no footing; a load then gives only what does not need one).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Protocol, runtime_checkable

import numpy as np

__all__ = ["FootingFrame", "LimitAction", "LimitInput", "SceneInput", "SiteInput"]


@dataclass(frozen=True)
class FootingFrame:
    """The footing a load acts on, as a load's ``limit_action`` reads it: ``x0``, ``x1`` [m] of the strip
    (its moments are taken about the centre of its base, x_c = (x0 + x1) / 2), ``lever`` [m] the height of
    the plate's nodes above the base (``-section.z_bottom``; 0 without a plate), ``thickness`` [m] of the
    plate's section (0 without a plate) and ``buoyancy`` [Pa] gamma_w times the plate's submerged
    thickness (free water above the ground)."""

    x0: float
    x1: float
    lever: float = 0.0
    thickness: float = 0.0
    buoyancy: float = 0.0

    @property
    def xc(self) -> float:
        """x [m] of the centre of the base."""
        return 0.5 * (self.x0 + self.x1)


@dataclass(frozen=True)
class LimitAction:
    """One load's part in the limit problem at load factor 1 (every field's default: no part).

    ``ground``: (x0 [m], x1 [m], q [Pa]) a pressure on the ground beside the footing; ``force``: (Fx, Fz
    [N/m], M [N m/m]) on the rigid footing, Fz > 0 up and M counter-clockwise about the centre of its base;
    ``beam_points``: a beam strip's point loads ((x [m], Fx, Fz [N/m], C [N m/m]), ...) at its base;
    ``beam_pressure`` [Pa]: its uniform downward pressure on a beam strip; ``not_on_beam``: why a beam strip
    cannot carry it (the strip is then rigid, or refused with strip="beam"); ``settles``: a prescribed
    settlement of the whole footing (lambda is then the footing's vertical force); ``refused``: why the
    limit problem cannot represent it at all (a ValueError names the load); ``drives``: the load's own
    ``drives`` (a prescribed displacement is not held among dead loads); ``on_rigid``: a RigidFooting
    carries it; ``text``: what it is at factor 1 in kN/m or kPa (the reference the bracket's lambda
    multiplies; empty: nothing to say)."""

    ground: tuple[float, float, float] | None = None
    force: tuple[float, float, float] = (0.0, 0.0, 0.0)
    beam_points: tuple = ()
    beam_pressure: float = 0.0
    not_on_beam: str | None = None
    settles: bool = False
    refused: str | None = None
    drives: str | None = None
    on_rigid: bool = False
    text: str = ""


@runtime_checkable
class LimitInput(Protocol):
    """What the bridge takes: a Scene or a Site, named by the fields every input answers (``kind``: "scene"
    or "site", which geometry applies: :class:`SceneInput` or :class:`SiteInput`). A protocol, not the
    classes: ``ssi.scene`` ranks above this package, which never imports it."""

    kind: ClassVar[str]
    loads: list
    layers: list
    gamma_w: float

    def soils(self) -> list:
        """The soil of each region: the layers from the top down, then a site's lenses' (their ``c`` None:
        elastic, never yielding)."""


@runtime_checkable
class SceneInput(LimitInput, Protocol):
    """What :func:`ssi.capacity.scene_problem.scene_parts` reads of a Scene (``kind == "scene"``) besides the
    loads (their ``limit_action``) and the layers: its foundation and contacts, its water, and its block."""

    foundation: object
    side_contact: object
    embedment: float  # [m] the strip's base below the ground
    water_table: float | None  # [m] depth below the ground (None: dry)
    surcharge: float  # [Pa] on the ground in the geostatic state
    symmetric: bool
    depth: float  # [m]
    phases: list

    def load_phases(self) -> list:
        """The phases after the geostatic one (``name``, ``loads``, ``factors``, ``excavate``,
        ``drainage``): ``loads`` as a first phase "loads" (if any), then ``phases``."""

    def contact_laws(self) -> list:
        """The distinct Contact laws under the plate strip."""

    def block(self) -> tuple[float, float]:
        """(x_left, x_right) [m] of the modelled block."""

    def footprint(self) -> tuple[float, float]:
        """(x0, x1) [m] of the foundation in the modelled block."""

    def mesh_layers(self) -> list:
        """[(thickness [m], layer, body-force unit weight [N/m^3])] from the ground down."""

    def geostatic(self, z: np.ndarray) -> np.ndarray:
        """Effective geostatic stress [Pa], shape ``z.shape + (4,)``, at the elevations ``z`` [m]."""

    def has_geostatic_stress(self) -> bool:
        """True if the block starts from a geostatic stress (weight or surcharge)."""


@runtime_checkable
class SiteInput(LimitInput, Protocol):
    """What :func:`ssi.capacity.site_problem.site_parts` reads of a Site (``kind == "site"``) besides the
    loads and the layers: its strips and its geometry."""

    strips: list

    def geometry(self) -> object:
        """The site's :class:`ssi.core.geometry.Geometry` (cells cut at the water table)."""

    def embedded(self) -> list:
        """(index, x0 [m], x1 [m], base level [m]) of every embedded strip."""

    def base_z(self, i: int) -> float:
        """Elevation [m] of the base of strip ``i``."""

    def ground_z(self, x: np.ndarray) -> np.ndarray:
        """Elevation [m] of the ground at ``x`` [m]."""

    def water_z(self, x: np.ndarray) -> np.ndarray:
        """Elevation [m] of the water table at ``x`` [m] (-inf: dry)."""
