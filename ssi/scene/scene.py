"""A user's scene, described by its components: a strip foundation on layered subsoil under column loads.

    scene = Scene(width=20.0, depth=10.0,
                  layers=[SoilLayer(3.0, E=20e6, nu=0.3, unit_weight=18e3, c=5e3, phi_deg=30.0, psi_deg=0.0),
                          SoilLayer(7.0, E=60e6, nu=0.3, unit_weight=19e3)],
                  foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
                  contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0),
                  loads=[ColumnLoad(x=0.0, N=400e3)])
    built = scene.build()
    out = built.solve(n_steps=10)          # one factorisation and one solve if the scene is linear

Only what the scene contains is built: no plate or interface group without a foundation, no plasticity state
in a layer given without strength (``c=None``), no Newton loop for a linear scene. Layers are listed from the
surface down; a layer with ``unit_weight > 0`` starts from geostatic stress (K0 = 1 - sin(phi) unless given),
equilibrated with its self-weight so the structural loads produce the displacements. The block's bottom is
fixed and its sides are on vertical rollers (the separated block of the paper's Fig. 1).

Signs: z upwards; a column force ``N > 0`` pushes down, ``H > 0`` pushes in +x, ``M > 0`` is counter-clockwise
(the direction of a positive rotation alpha). Settlements are reported positive downwards. Units: SI
throughout (m, N, Pa, N/m^3); forces of the plane-strain scene are per metre of the strip's length.

What a foundation engineer adds to that (see ``chapters/12_engineering_scenes.py``):

* **Loads** (``Scene.loads`` and ``Phase.loads``): :class:`SurfacePressure` on the ground, with or without a
  foundation; :class:`StripLoad` along the strip (uniform or linear); :class:`ColumnLoad` anywhere on the
  strip (the mesh gets a node there); :class:`StripWeight` from the section depth; :class:`Settlement` of the
  strip (push-over: rigid or at the columns, the contact force is the load).
* **The geostatic state** is in equilibrium with everything that acts before the structural loads: the soil's
  weight, the ``surcharge`` on the ground (a dead surface load, so nothing moves before the loads), the
  overburden of an embedded strip (the strip starts carrying the geostatic vertical stress of its base level,
  the trench walls the horizontal one) and the buoyant weight below a ``water_table``.
* **Phases** (``Scene.phases``): geostatic first (zero displacement), then each phase adds loads and rescales
  those of earlier phases (``factors``, 0 removes them); the state at the end of one phase is the start of
  the next, so unloading and reloading paths follow the materials' history.
* **Groundwater**: hydrostatic pore pressure below ``water_table``; the soil state is the effective stress
  (the strength acts on it), the body force is the buoyant weight gamma_sat - gamma_w; an undrained clay in
  total stress is ``SoilLayer.undrained`` (phi = 0, c = s_u, nu_u close to 0.5); in effective stress it is
  ``SoilLayer(..., drainage="undrained_A")`` (drained parameters plus a pore-water bulk modulus; give
  psi_deg = 0, since a dilating soil sucks ever more negative pore pressure and never fails undrained).
* **Embedment**: ``embedment`` D puts the strip's base D below the ground in a trench; the soil beside it is
  the layer(s) above depth D (the backfill).
* **Contact along the strip**: ``contact`` is one :class:`Contact` or a list of :class:`ContactSegment`.
* **A rigid footing and the half model**: ``foundation`` may be a :class:`RigidFooting` (no plate, no
  interface: the soil nodes under it pushed by a ``Settlement``, rough or smooth), and ``symmetric=True``
  models only the half x >= 0 of a scene symmetric about x = 0 (u = 0 on the axis) -- the bearing-capacity
  scenes of ``ssi.lab.bearing_capacity`` are such scenes.
* **Phases that change the soil**: ``Phase.excavate`` removes :class:`Excavation` regions (the forces the
  removed soil exerted fall to zero over the phase), ``Phase.drainage`` switches a layer between drained and
  undrained_A; ``water_table < 0`` is free water above the ground (pore pressure, not effective stress). A
  phase that does not converge raises :class:`PhaseNonConvergence` with every completed phase.
"""

import math
import warnings
from dataclasses import dataclass, field
from itertools import pairwise

import numpy as np

from ..core.assembly import scatter_vector
from ..core.mesh import MAX_END_GRADING, foundation_contact, soil_block, surface_pressure_forces
from ..core.model import Model, System
from ..core.shapes import lagrange3
from ..core.solution import Result
from ..core.validate import (
    check_bool,
    check_choice,
    check_instance,
    check_int,
    check_optional_real,
    check_real,
)
from ..elements.interface import V_SIG, V_TAU, Interface6, add_interface
from ..elements.plate import INTEGRATIONS, PlateStrip
from ..elements.section import Section
from ..elements.soil_q8 import SoilQ8
from ..elements.supports import fix_block
from ..materials.concrete import P_E0, P_FR
from ..materials.interface_law import interface_params
from ..materials.layer_laws import CONCRETE, STEEL
from ..materials.layer_laws import ELASTIC as LAYER_ELASTIC
from ..materials.soil_laws import (
    DRAINAGE,
    GAMMA_W,
    SoilLayer,
    geostatic_stress,
    material_table,
    pore_pressure,
)
from ..solver import NonConvergence, Settings, run


@dataclass(frozen=True)
class Foundation:
    """The strip from x0 to x1 (both become soil mesh lines) with its layered ``section``.

    Section options (passed to :class:`ssi.elements.plate.PlateStrip`; defaults from chapters 02 and 08):
    ``kappa`` shear factor (5/6); ``integration`` along the element ("selective", the paper's);
    ``self_bending`` = "chord" (each layer's own bending from the stresses at its faces: within about 1 % of
    the layer-free moment with 11 layers up to 0.06 1/m, where "initial" is +17 %, and continuous, unlike
    "tangent"; chapter 02, row ``section_selfbending``); ``crack_band`` = "spacing" (every concrete layer's
    band width ls = the crack spacing s_r,max of fib Model Code 2010 from the nearest bars, ``bar_diameter``
    [m] and the cover:
    one band per crack, so the response does not depend on the element size; chapter 08, row
    ``fig12_mesh_spread``), "point" (the paper's rule: ls = the length each sampling point represents,
    mesh-dependent for a reinforced strip) or None (the ls already in the section's parameters);
    ``plane_strain`` = True: the concrete layers use E0 / (1 - nu^2) like the elastic layers (eq. 4.4), so the
    strip is consistently plane strain (False: keep the section's own setting, e.g. a plane-stress beam);
    ``tension_stiffening`` (with ``crack_band="spacing"``): "all" cracked concrete layers (chapter 03's rule)
    or only the "effective_area" h_c,ef around the bars (chapters 03 and 08 score both).
    """

    x0: float
    x1: float
    section: Section
    kappa: float = 5.0 / 6.0
    integration: str = "selective"
    self_weight: float = 0.0  # [N/m^2] of the strip's plan area, a dead load
    self_bending: str = "chord"
    crack_band: str | None = "spacing"
    bar_diameter: float = 0.016
    plane_strain: bool = True
    tension_stiffening: str = "all"

    def strip_section(self) -> Section:
        """The section the strip is built with (concrete bands set to the crack spacing for "spacing")."""
        if self.crack_band not in ("spacing", "point", None):
            raise ValueError(f"crack_band must be 'spacing', 'point' or None, got {self.crack_band!r}")
        from dataclasses import replace

        from ..elements.section import with_crack_spacing_band
        from ..materials.rc import with_plane_strain

        sec = self.section
        if not np.any(sec.kind == CONCRETE):
            return sec
        if self.crack_band == "spacing":
            sec = with_crack_spacing_band(sec, self.bar_diameter, self.tension_stiffening)[0]
        if self.plane_strain:
            params = sec.params.copy()
            for n in np.flatnonzero(sec.kind == CONCRETE):
                params[n] = with_plane_strain(params[n])
            sec = replace(sec, params=params)
        return sec

    def strip_options(self) -> dict:
        """Keyword arguments of :class:`ssi.elements.plate.PlateStrip` for this foundation."""
        return {
            "kappa": self.kappa,
            "integration": self.integration,
            "self_weight": self.self_weight,
            "self_bending": self.self_bending,
            "crack_band": "point" if self.crack_band == "point" else None,
        }

    def __post_init__(self):
        x0 = check_real("Foundation.x0", self.x0, unit="m")
        x1 = check_real("Foundation.x1", self.x1, unit="m")
        if not x0 < x1:
            raise ValueError(f"Foundation.x0 must be < x1, got x0={self.x0!r}, x1={self.x1!r}")
        check_instance("Foundation.section", self.section, Section)
        check_real("Foundation.kappa", self.kappa, lo=0.0, hi=1.0, lo_open=True)
        _check_integration("Foundation.integration", self.integration)
        check_real("Foundation.self_weight", self.self_weight, lo=0.0, unit="N/m^2")


@dataclass(frozen=True)
class RigidFooting:
    """A rigid strip footing from ``x0`` to ``x1`` [m] on the ground, without a plate or an interface: the
    soil nodes under it are its base, held at rest (w = 0) until a :class:`Settlement` (``x=None``) moves
    them all by the same w -- a displacement-controlled push, whose reaction is the footing's load
    (:meth:`BuiltScene.contact_force`). ``rough=True``: the base also holds the soil horizontally (u = 0,
    the full adhesion of a rough base); ``rough=False``: smooth, u free (no shear on the base). The
    footing carries a ``Scene.surcharge`` over its own width through that reaction; it takes no other load
    (a column, a strip load or the strip's weight needs a plate :class:`Foundation`) and no ``embedment``.
    """

    x0: float
    x1: float
    rough: bool = True

    def __post_init__(self):
        x0 = check_real("RigidFooting.x0", self.x0, unit="m")
        x1 = check_real("RigidFooting.x1", self.x1, unit="m")
        if not x0 < x1:
            raise ValueError(f"RigidFooting.x0 must be < x1, got x0={self.x0!r}, x1={self.x1!r}")
        check_bool("RigidFooting.rough", self.rough)


@dataclass(frozen=True)
class Contact:
    """Foundation--soil interface (Coulomb). ``phi_deg=None``: bonded and elastic (never slips or opens).

    Fields: ``kn``, ``kt`` normal and tangential stiffness [Pa/m]; ``phi_deg`` interface friction angle [deg];
    ``c`` adhesion [Pa]; ``psi_deg`` dilation angle [deg] -- the default 0 (slip without dilation) is the
    usual engineering choice for a concrete--soil contact, ``None`` gives the paper's associated rule (psi =
    phi); ``sig_t`` tension cut-off [Pa]; ``rule`` "newton_cotes" or "gauss". ``kt = 0`` on the whole strip
    (frictionless): nothing holds the strip horizontally, so the built scene fixes u of its middle plate node
    (``BuiltScene.slide_support``, zero reaction under vertical loads) and refuses a ``ColumnLoad`` with H.
    """

    kn: float
    kt: float
    phi_deg: float | None = None
    c: float = 0.0
    psi_deg: float | None = 0.0
    sig_t: float | None = None
    rule: str = "newton_cotes"

    def __post_init__(self):
        check_real("Contact.kn", self.kn, lo=0.0, lo_open=True, unit="Pa/m")
        check_real("Contact.kt", self.kt, lo=0.0, unit="Pa/m")
        check_optional_real("Contact.phi_deg", self.phi_deg, lo=0.0, hi=90.0, hi_open=True, unit="degrees")
        check_real("Contact.c", self.c, lo=0.0, allow_inf=True, unit="Pa")
        psi_max = 90.0 if self.phi_deg is None else self.phi_deg
        check_optional_real(
            "Contact.psi_deg",
            self.psi_deg,
            lo=0.0,
            hi=psi_max,
            hi_open=self.phi_deg is None,
            unit="degrees (<= phi_deg)",
        )
        check_optional_real("Contact.sig_t", self.sig_t, lo=0.0, unit="Pa")
        check_choice("Contact.rule", self.rule, ("newton_cotes", "gauss"))
        self.params()  # the interface law's own checks of the combination (sig_t below the apex)

    def params(self) -> np.ndarray:
        if self.phi_deg is None:
            return interface_params(kt=self.kt, kn=self.kn, phi_deg=0.0, c=np.inf, psi_deg=None, sig_t=np.inf)
        return interface_params(
            kt=self.kt, kn=self.kn, phi_deg=self.phi_deg, c=self.c, psi_deg=self.psi_deg, sig_t=self.sig_t
        )


@dataclass(frozen=True)
class ContactSegment:
    """The contact law ``contact`` on the part x0 <= x <= x1 [m] of the strip; segments tile the strip."""

    x0: float
    x1: float
    contact: Contact


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


@dataclass(frozen=True)
class Excavation:
    """Soil removed in the phase that lists it: every element whose centre lies in ``x0`` < x < ``x1`` [m]
    and ``top`` < depth below the ground < ``bottom`` [m]. The mesh puts element edges on all four sides
    (x0 and x1 become element lines, top and bottom split the layers there). x0 = -width/2 and
    x1 = width/2 remove a whole layer part over the full width. The removed soil's stress and weight (and a
    surcharge on its ground) are released over the phase; below the water table the pit stays flooded to
    the table (the effective-stress formulation: the water in it balances the pore pressure on its faces).
    It may not remove soil under the strip or beside an embedded strip's trench walls."""

    x0: float
    x1: float
    bottom: float
    top: float = 0.0

    def __post_init__(self):
        x0 = check_real("Excavation.x0", self.x0, unit="m")
        if not x0 < check_real("Excavation.x1", self.x1, unit="m"):
            raise ValueError(f"Excavation.x0 must be < x1, got x0={self.x0!r}, x1={self.x1!r}")
        top = check_real("Excavation.top", self.top, lo=0.0, unit="m (depth below the ground)")
        check_real("Excavation.bottom", self.bottom, lo=top, lo_open=True, unit="m (depth, > top)")


@dataclass(frozen=True)
class Phase:
    """One stage of the analysis: ``loads`` added (at full value at the end of the phase), ``factors``
    {name of an earlier phase: factor} rescaling that phase's loads (0 removes them, 1 restores them;
    a Settlement's factor scales its settlement), ``n_steps`` equal increments (None: the ``n_steps`` given to
    ``solve``).

    ``excavate``: :class:`Excavation` regions whose soil this phase removes (the forces the removed soil
    exerted on the rest -- its stress and weight -- fall to zero during the phase). ``drainage``: {index of a
    layer in ``Scene.layers`` (0 = top): "drained" | "undrained_A"} from this phase on (a layer switched to
    undrained starts its excess pore pressure at zero from the phase's first state; switched back to
    drained, its excess pore pressure is released during the phase: full consolidation)."""

    name: str
    loads: tuple = ()
    factors: dict = field(default_factory=dict)
    n_steps: int | None = None
    excavate: tuple = ()
    drainage: dict = field(default_factory=dict)

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise TypeError(f"Phase.name must be a non-empty string, got {self.name!r}")
        _check_list(f"Phase({self.name!r}).loads", list(self.loads), LOAD_TYPES)
        if not isinstance(self.factors, dict):
            raise TypeError(
                f"Phase({self.name!r}).factors must be a dict {{phase name: factor}}, got "
                f"{type(self.factors).__name__}"
            )
        for key, value in self.factors.items():
            check_real(f"Phase({self.name!r}).factors[{key!r}]", value)
        if self.n_steps is not None:
            check_int(f"Phase({self.name!r}).n_steps", self.n_steps, lo=1)
        _check_list(f"Phase({self.name!r}).excavate", list(self.excavate), Excavation)
        if not isinstance(self.drainage, dict):
            raise TypeError(
                f"Phase({self.name!r}).drainage must be a dict {{layer index: 'drained' | 'undrained_A'}}, "
                f"got {type(self.drainage).__name__}"
            )
        for key, value in self.drainage.items():
            check_int(f"Phase({self.name!r}).drainage key (layer index)", key, lo=0)
            check_choice(f"Phase({self.name!r}).drainage[{key!r}]", value, DRAINAGE)


@dataclass(frozen=True)
class MeshSize:
    """Element size ``h_fine`` [m] under the foundation, ``h_coarse`` [m] far from it, ``growth`` [-] ratio of
    neighbouring sizes, ``n_gauss`` 2 (reduced) or 3 (full) Gauss points per direction, ``end_grading``
    [-] exponent (1 to ``ssi.core.mesh.MAX_END_GRADING``) grading the elements under the foundation towards
    its ends (1: even; see ``ssi.core.mesh.foundation_lines``)."""

    h_fine: float = 0.25
    h_coarse: float = 2.0
    growth: float = 1.25
    n_gauss: int = 2
    end_grading: float = 1.0

    def __post_init__(self):
        h_fine = check_real("MeshSize.h_fine", self.h_fine, lo=0.0, lo_open=True, unit="m")
        if check_real("MeshSize.h_coarse", self.h_coarse, lo=0.0, lo_open=True, unit="m") < h_fine:
            raise ValueError(f"MeshSize.h_coarse must be >= h_fine = {self.h_fine!r}, got {self.h_coarse!r}")
        check_real("MeshSize.growth", self.growth, lo=1.0)
        check_choice("MeshSize.n_gauss", self.n_gauss, (2, 3))
        check_real("MeshSize.end_grading", self.end_grading, lo=1.0, hi=MAX_END_GRADING, unit="-")


@dataclass
class Scene:
    """A strip foundation on layered subsoil: ``width``, ``depth`` [m] of the soil block; ``layers`` from the
    ground surface down (thicknesses tile ``depth``); ``foundation`` and its ``contact`` (one
    :class:`Contact` or a list of :class:`ContactSegment`); ``loads`` of the first phase after the geostatic
    one; ``mesh``; ``surcharge`` [Pa] on the ground (a dead load of the geostatic state, beside the strip; the
    strip carries it over its own width); ``phases`` after ``loads``; ``embedment`` D [m] of the strip's base
    below the ground (a layer boundary); ``water_table`` [m] depth of the water table below the ground (None:
    dry; negative: free water stands -water_table above the ground, ponding); ``gamma_w`` [N/m^3] unit weight
    of water; ``symmetric``: model only the half x >= 0 (see below).

    ``foundation`` is a plate :class:`Foundation` (resting on the soil through ``contact``) or a
    :class:`RigidFooting` (its base is the soil's surface nodes, pushed by a :class:`Settlement`; no contact).

    ``symmetric=True``: the scene is symmetric about x = 0 and only its half x >= 0 is modelled, the block
    [0, width/2] with the axis x = 0 on vertical rollers (u = 0 and no shear across it: the conditions of a
    displacement field symmetric about the axis), like the block's far side. ``width`` and the foundation's
    x0, x1 describe the whole scene; the foundation must be centred on the axis (x0 = -x1) and be a
    RigidFooting (a plate strip's half would need its rotation held on the axis: not built) or absent;
    loads and excavations are given on the modelled half (their mirror images act on the other). The model's
    forces are those of the half; :meth:`BuiltScene.contact_force` reports the whole footing's.

    Initial stress of weightless soil: a layer with ``unit_weight`` 0 under a ``surcharge`` q starts from the
    uniform stress szz = -q, sxx = syy = K0 szz, txz = 0. Without body forces every uniform stress is in
    equilibrium with a uniform pressure on the ground, so the horizontal stress is the modeller's choice,
    made through the layer's ``K0`` (default Jaky's 1 - sin phi, the ratio of a soil consolidated under its
    own weight): ``K0=1`` starts the soil isotropic, on the hydrostatic axis and as far from the
    Mohr--Coulomb surface as that mean stress allows (the start of the rigid-footing bearing-capacity scenes,
    :func:`ssi.lab.bearing_capacity.rigid_footing`).
    """

    width: float
    depth: float
    layers: list
    foundation: "Foundation | RigidFooting | None" = None
    contact: Contact | list | None = None
    loads: list = field(default_factory=list)
    mesh: MeshSize = field(default_factory=MeshSize)
    surcharge: float = 0.0  # uniform pressure on the ground surface in the geostatic state [Pa]
    phases: list = field(default_factory=list)
    embedment: float = 0.0
    water_table: float | None = None
    gamma_w: float = GAMMA_W
    symmetric: bool = False

    def __post_init__(self):
        width = check_real("Scene.width", self.width, lo=0.0, lo_open=True, unit="m")
        depth = check_real("Scene.depth", self.depth, lo=0.0, lo_open=True, unit="m")
        check_real("Scene.surcharge", self.surcharge, lo=0.0, unit="Pa")
        _check_list("Scene.layers", self.layers, SoilLayer, min_len=1)
        _check_list("Scene.loads", self.loads, LOAD_TYPES)
        check_instance("Scene.foundation", self.foundation, (Foundation, RigidFooting), optional=True)
        check_bool("Scene.symmetric", self.symmetric)
        if isinstance(self.contact, list | tuple) and CONTACT_SEGMENT_TYPES:
            _check_list("Scene.contact", self.contact, CONTACT_SEGMENT_TYPES, min_len=1)
        else:
            check_instance("Scene.contact", self.contact, Contact, optional=True)
        check_instance("Scene.mesh", self.mesh, MeshSize)
        _check_list("Scene.phases", self.phases, Phase)
        check_real("Scene.embedment", self.embedment, lo=0.0, hi=depth, hi_open=True, unit="m")
        check_optional_real(
            "Scene.water_table", self.water_table, unit="m (depth below the ground; < 0: water above it)"
        )
        check_real("Scene.gamma_w", self.gamma_w, lo=0.0, lo_open=True, unit="N/m^3")
        total = sum(lay.thickness for lay in self.layers)
        if abs(total - depth) > 1e-9 * depth:
            raise ValueError(
                f"Scene.depth={self.depth!r}: the layer thicknesses "
                f"{[lay.thickness for lay in self.layers]} must tile the depth (their sum is {total:g})"
            )
        f = self.foundation
        x0, x1 = (f.x0, f.x1) if f else (-0.25 * width, 0.25 * width)
        if f is not None and not (-0.5 * width <= x0 and x1 <= 0.5 * width):
            raise ValueError(
                f"Scene.foundation (x0={f.x0!r}, x1={f.x1!r}) must lie within the block "
                f"[-width/2, width/2] = [{-0.5 * width:g}, {0.5 * width:g}] (Scene.width={self.width!r})"
            )
        if self.symmetric:
            _check_symmetric(self)
        a, b = self._footprint()
        if self.mesh.h_fine > b - a:
            raise ValueError(
                f"MeshSize.h_fine={self.mesh.h_fine!r} must be <= the foundation width x1 - x0 = "
                f"{b - a:g} m{' of the modelled half' if self.symmetric else ''} (at least one element under "
                "the foundation)"
            )
        for i, load in enumerate(self.loads):
            if isinstance(load, ColumnLoad) and f is not None and not x0 <= load.x <= x1:
                raise ValueError(
                    f"loads[{i}].x={load.x!r} must lie on the foundation [x0, x1] = [{x0:g}, {x1:g}]"
                )

    def build(self) -> "BuiltScene":
        """Mesh the block, add only the groups the scene needs, supports, the geostatic state and loads."""
        if not self.layers:
            raise ValueError("layers: the scene needs at least one soil layer")
        if isinstance(self.foundation, Foundation) and self.contact is None:
            raise ValueError("contact: a foundation needs a Contact (interface) to rest on the soil")
        if isinstance(self.foundation, RigidFooting):
            _check_rigid_footing(self)
        strip_loads = [ld for ld in self._all_loads() if not isinstance(ld, SurfacePressure)]
        if self.foundation is None and strip_loads:
            raise ValueError(
                f"loads: {type(strip_loads[0]).__name__} needs a foundation to act on (a pressure on "
                "the ground without a foundation is a SurfacePressure)"
            )
        if self.embedment and self.foundation is None:
            raise ValueError(f"embedment={self.embedment}: an embedded scene needs a foundation")
        _check_phases(self)
        _warn_implausible_units(self)
        f = self.foundation
        mesh_layers = self._mesh_layers()
        mesh = soil_block(
            0.5 * self.width if self.symmetric else self.width,
            self.depth,
            [t for t, _, _ in mesh_layers],
            self._footprint(),
            self.mesh.h_fine,
            self.mesh.h_coarse,
            self.mesh.growth,
            x_left=self._block()[0],
            breaks=self._breaks(),
            embedment=self.embedment,
            edges=sorted({v for ph in self.phases for ex in ph.excavate for v in (ex.x0, ex.x1)}),
            end_grading=self.mesh.end_grading,
        )
        model = Model()
        model.info["scene"] = _describe(self)
        soil_ids = model.add_nodes(mesh.xy, ndof=2)
        kinds, params = material_table([lay.law() for _, lay, _ in mesh_layers])
        weights = np.array([gamma for _, _, gamma in mesh_layers])
        k_water = np.array([lay.k_water() for _, lay, _ in mesh_layers])
        soil = SoilQ8(
            mesh.xy[mesh.conn],
            model.element_dofs(soil_ids[mesh.conn]),
            mesh.el_layer,
            kinds,
            params,
            n_gauss=self.mesh.n_gauss,
            unit_weight=weights if weights.any() else None,
            k_water=k_water if k_water.any() else None,
        )
        if weights.any() or self.surcharge:
            soil.initial_stress = self._geostatic(soil.integration_points()[..., 1])
        model.add_group(soil)
        fix_block(model, mesh, soil_ids)
        built = BuiltScene(self, model, mesh, soil)
        owner = [next(i for i, lay in enumerate(self.layers) if lay is own) for _, own, _ in mesh_layers]
        built.element_layer = np.array(owner, np.int64)[mesh.el_layer]
        built.geostatic_load = self._ground_loads(built)
        if isinstance(f, Foundation):
            self._add_foundation(built)
        elif isinstance(f, RigidFooting):
            self._add_rigid_footing(built, soil_ids)
        model.add_element_load(np.arange(model.n_dof)[None], built.geostatic_load[None], dead=True)
        _check_excavations(built)
        for load in self.loads:
            built._register(load)
        return built

    def _block(self) -> tuple[float, float]:
        """(x_left, x_right) [m] of the modelled block: the whole width centred on x = 0, or its half x >= 0
        of a symmetric scene."""
        return (0.0 if self.symmetric else -0.5 * self.width), 0.5 * self.width

    def _footprint(self) -> tuple[float, float]:
        """(x0, x1) [m] of the foundation in the modelled block (of a symmetric scene: its half x >= 0);
        without a foundation the middle half of the ground, where the mesh is finest."""
        f = self.foundation
        x0, x1 = (f.x0, f.x1) if f else (-0.25 * self.width, 0.25 * self.width)
        return (max(x0, 0.0) if self.symmetric else x0), x1

    def _all_loads(self):
        return list(self.loads) + [ld for ph in self.phases for ld in ph.loads]

    def _breaks(self):
        """x [m] that must be surface nodes: load ends, columns, settled columns, contact segment ends."""
        out = []
        f = self.foundation
        for load in self._all_loads():
            if isinstance(load, SurfacePressure):
                out += [load.x0, load.x1]
            elif isinstance(load, ColumnLoad):
                out.append(load.x)
            elif isinstance(load, StripLoad):
                out += [v for v in (load.x0, load.x1) if v is not None]
            elif isinstance(load, Settlement) and load.x is not None:
                out += list(load.x)
        lo, hi = self._block()
        bad = [x for x in out if not (lo <= x <= hi)]
        if bad:
            half = " (the modelled half of a symmetric scene)" if self.symmetric else ""
            raise ValueError(f"loads: x={bad[0]} lies outside the block [{lo}, {hi}] m{half}")
        if isinstance(f, Foundation):
            out += [v for seg in _segments(self) for v in (seg.x0, seg.x1)]
        return out

    def _mesh_layers(self):
        """[(thickness, layer, body-force unit weight)] with the layer that holds the water table split there:
        gamma above the table, the buoyant gamma_sat - gamma_w below it (the soil state is effective
        stress)."""
        d_w = math.inf if self.water_table is None else float(self.water_table)
        if self.water_table is not None and not np.isfinite(d_w):
            raise ValueError(f"water_table must be a finite depth below the ground [m] or None, got {d_w}")
        # depths where a layer is split: the water table and the top and bottom of every excavation
        cuts = [d_w] + [d for ph in self.phases for ex in ph.excavate for d in (ex.top, ex.bottom)]
        out, top = [], 0.0
        for lay in self.layers:
            sat = lay.unit_weight if lay.unit_weight_sat is None else lay.unit_weight_sat
            wet = max(sat - self.gamma_w, 0.0) if self.water_table is not None else sat
            bottom = top + lay.thickness
            inner = sorted({d for d in cuts if min(d - top, bottom - d) > 1e-9 * lay.thickness})
            for a, b in pairwise([top, *inner, bottom]):
                out.append((b - a, lay, lay.unit_weight if b <= d_w + 1e-12 else wet))
            top = bottom
        return out

    def _geostatic(self, z):
        """Effective geostatic stress (n, ..., 4) at the points z [m] (see ``geostatic_stress``)."""
        return geostatic_stress(
            z, self.layers, self.surcharge, water_table=self.water_table, gamma_w=self.gamma_w
        )

    def _ground_loads(self, built):
        """Dead loads that hold the geostatic state in place (without the soil's own weight, a body force of
        the soil group): the surcharge on the ground beside the strip and the horizontal geostatic stress on
        the walls of an embedded strip's trench."""
        mesh, model = built.mesh, built.model
        f_vec = np.zeros(model.n_dof)
        lo, hi = self._block()
        if self.surcharge:
            a, b = self._footprint()
            ranges = [(lo, hi)] if self.foundation is None else [(lo, a), (b, hi)]
            for a, b in ranges:
                if b - a > 1e-12:
                    nodes, f = surface_pressure_forces(mesh, a, b)
                    np.add.at(f_vec, model.dof(nodes, "w"), -self.surcharge * f)
        if self.embedment:
            for x_wall, normal in ((self.foundation.x0, 1.0), (self.foundation.x1, -1.0)):
                nodes, f = self._wall_forces(mesh, x_wall, normal)
                np.add.at(f_vec, model.dof(nodes, "u"), f)
        return f_vec

    def _wall_forces(self, mesh, x_wall, normal):
        """Nodal forces [N/m] of the traction sig_xx0 * n_x on a trench wall (3-point Gauss per edge)."""
        on = np.flatnonzero(
            (np.abs(mesh.xy[:, 0] - x_wall) < 1e-9) & (mesh.xy[:, 1] >= -self.embedment - 1e-9)
        )
        nodes = on[np.argsort(mesh.xy[on, 1])]
        z = mesh.xy[nodes, 1]
        f = np.zeros(len(nodes))
        xi = np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])
        wt = np.array([5.0, 8.0, 5.0]) / 9.0
        for i in range(0, len(nodes) - 2, 2):
            za = z[i : i + 3]
            for s, w in zip(xi, wt):
                n = lagrange3(s)[0]
                sxx = self._geostatic(np.array([n @ za]))[0, 0]
                f[i : i + 3] += n * sxx * normal * w * 0.5 * (za[2] - za[0])
        return nodes, f

    def _add_foundation(self, built):
        f, model, mesh = self.foundation, built.model, built.mesh
        z_base = -float(self.embedment)
        contact = foundation_contact(mesh, f.x0, f.x1, f.section.thickness, z=z_base)
        offset = -f.section.z_bottom  # plate nodes sit on the reference surface, this far above the base
        plate_xy = np.column_stack([contact.plate_xy[:, 0], np.full(len(contact.plate_xy), z_base + offset)])
        ids = model.add_nodes(plate_xy, ndof=3)
        built.geostatic_load = np.concatenate([built.geostatic_load, np.zeros(3 * len(ids))])
        conn = ids[contact.plate_conn]
        plate = PlateStrip(
            plate_xy[contact.plate_conn], model.element_dofs(conn), f.strip_section(), **f.strip_options()
        )
        model.add_group(plate)
        segments = _segments(self)
        x_mid = plate_xy[contact.plate_conn[:, 1], 0]
        params = np.array([_segment_at(segments, x).contact.params() for x in x_mid])
        # the strip starts carrying the geostatic vertical stress of its base level (surcharge, overburden):
        # contact traction and an equal dead load on the strip, so the initial state is in equilibrium
        p0 = -float(self._geostatic(np.array([z_base]))[0, 1]) if self._has_geostatic_stress() else 0.0
        iface = add_interface(
            model,
            conn,
            contact.soil_conn,
            params,
            offset=plate.bottom_offset,
            rule=segments[0].contact.rule,
            initial_traction=np.array([0.0, -p0]) if p0 else None,
        )
        built.plate, built.interface, built.plate_nodes = plate, iface, ids
        built.base_pressure = p0
        if all(seg.contact.kt == 0.0 for seg in segments):
            # frictionless contact everywhere: nothing resists a horizontal translation of the strip, so K0
            # is singular (strict pivoting used to factorise it on a round-off pivot). Hold u at the plate
            # node nearest the middle: the contact tractions are normal to the horizontal base, so the
            # support's reaction is zero while the strip carries no horizontal load (load_effect refuses one)
            built.slide_support = int(ids[np.argmin(np.abs(plate_xy[:, 0] - 0.5 * (f.x0 + f.x1)))])
            model.fix([built.slide_support], "u")
        if p0:
            scatter_vector(plate.edofs, plate.distributed_load(-p0, comp="w"), built.geostatic_load)

    def _add_rigid_footing(self, built, soil_ids):
        """The soil nodes under a :class:`RigidFooting` are its base: held at rest (w = 0; rough: u = 0 too)
        until a Settlement prescribes their w (:meth:`BuiltScene.load_effect`)."""
        nodes = soil_ids[built.mesh.nodes_between(*self._footprint())]
        if self.foundation.rough:
            built.model.fix(nodes, "u")
        built.model.fix(nodes, "w")
        built.footing_nodes = nodes

    def _has_geostatic_stress(self):
        return bool(self.surcharge) or any(lay.unit_weight or lay.unit_weight_sat for lay in self.layers)


def _segments(scene):
    """The contact as a list of ContactSegment tiling the strip (checked)."""
    f, c = scene.foundation, scene.contact
    if isinstance(c, Contact):
        return [ContactSegment(f.x0, f.x1, c)]
    segs = sorted(c, key=lambda s: s.x0)
    if not segs or not all(isinstance(s, ContactSegment) for s in segs):
        raise TypeError("contact must be a Contact or a non-empty list of ContactSegment")
    tol = 1e-9 * max(1.0, f.x1 - f.x0)
    ends = [f.x0] + [v for s in segs for v in (s.x0, s.x1)] + [f.x1]
    gaps = [abs(a - b) for a, b in zip(ends[0::2], ends[1::2])]
    if max(gaps) > tol or any(s.x1 <= s.x0 for s in segs):
        raise ValueError(
            f"contact segments {[(s.x0, s.x1) for s in segs]} must tile the strip [{f.x0}, {f.x1}] "
            "without gaps or overlaps"
        )
    if len({s.contact.rule for s in segs}) != 1:
        raise ValueError("contact segments must share one integration rule")
    return segs


def _segment_at(segments, x):
    for seg in segments:
        if seg.x0 <= x <= seg.x1:
            return seg
    raise ValueError(f"x={x}: no contact segment covers this point of the strip")


def _check_symmetric(scene):
    """A symmetric scene: a RigidFooting (or no foundation) centred on the axis x = 0."""
    f = scene.foundation
    if isinstance(f, Foundation):
        raise ValueError(
            "Scene.symmetric=True models the half x >= 0 of a rigid footing or of bare ground; a plate "
            "Foundation's half model (its rotation held on the axis) is not built: use symmetric=False"
        )
    if f is not None and abs(f.x0 + f.x1) > 1e-9 * max(1.0, f.x1 - f.x0):
        raise ValueError(
            f"Scene.symmetric=True needs the foundation centred on the axis x = 0 (x0 = -x1), got "
            f"x0={f.x0!r}, x1={f.x1!r}"
        )


def _check_rigid_footing(scene):
    """A RigidFooting rests on the ground without an interface and takes only its settlement."""
    if scene.contact is not None:
        raise ValueError(
            "contact: a RigidFooting has no interface (its base is the soil's surface nodes); leave contact "
            "None, or use a plate Foundation"
        )
    if scene.embedment:
        raise ValueError(f"embedment={scene.embedment}: a RigidFooting sits on the ground (embedment 0)")
    for load in scene._all_loads():
        if isinstance(load, SurfacePressure) or (isinstance(load, Settlement) and load.x is None):
            continue
        raise ValueError(
            f"loads: a RigidFooting takes only Settlement(w) (x=None: it settles as a whole) and the ground "
            f"SurfacePressure; {load!r} needs a plate Foundation"
        )


def _check_phases(scene):
    names = (["loads"] if scene.loads else []) + [ph.name for ph in scene.phases]
    if len(set(names)) != len(names) or "geostatic" in names:
        raise ValueError(f"phase names {names} must be unique and not 'geostatic' (the first phase's name)")
    for k, ph in enumerate(scene.phases):
        earlier = names[: names.index(ph.name)]
        unknown = [n for n in ph.factors if n not in earlier]
        if unknown:
            raise ValueError(
                f"phases[{k}] ({ph.name!r}): factors name {unknown}, which are not earlier phases ({earlier})"
            )
        if ph.n_steps is not None and int(ph.n_steps) < 1:
            raise ValueError(f"phases[{k}] ({ph.name!r}): n_steps must be >= 1, got {ph.n_steps}")
        _check_phase_soil(scene, k, ph)


def _check_excavations(built):
    """No excavation removes soil under the strip or beside an embedded strip's trench walls (an element with
    an edge on the contact or on a wall)."""
    scene, mesh = built.scene, built.mesh
    f = scene.foundation
    if f is None or not any(ph.excavate for ph in scene.phases):
        return
    xy = mesh.xy
    on_base = (
        (np.abs(xy[:, 1] + scene.embedment) < 1e-9) & (xy[:, 0] > f.x0 - 1e-9) & (xy[:, 0] < f.x1 + 1e-9)
    )
    on_wall = (
        (np.minimum(np.abs(xy[:, 0] - f.x0), np.abs(xy[:, 0] - f.x1)) < 1e-9)
        & (xy[:, 1] > -scene.embedment - 1e-9)
        & (scene.embedment > 0.0)
    )
    touching = (on_base | on_wall)[mesh.conn].sum(axis=1) >= 2
    for k, ph in enumerate(scene.phases):
        if (built._excavated(ph) & touching).any():
            raise ValueError(
                f"phases[{k}] ({ph.name!r}): an excavation removes soil under the strip or beside its trench "
                f"walls (strip x0={f.x0}, x1={f.x1}, embedment {scene.embedment} m); keep it clear of them"
            )


def _check_phase_soil(scene, k, ph):
    """A phase's excavations lie in the block and leave the strip and its loads alone; its drainage names
    existing layers that can be undrained."""
    where = f"phases[{k}] ({ph.name!r})"
    for key, value in ph.drainage.items():
        if key >= len(scene.layers):
            raise ValueError(
                f"{where}: drainage names layer {key}; the scene has layers 0..{len(scene.layers) - 1}"
            )
        if value == "undrained_A":
            try:
                scene.layers[key].undrained_k_water()
            except ValueError as err:
                raise ValueError(f"{where}: drainage[{key}] = 'undrained_A': {err}") from err
    lo, hi = scene._block()
    pressures = [ld for p in scene.phases for ld in p.loads if isinstance(ld, SurfacePressure)]
    pressures += [ld for ld in scene.loads if isinstance(ld, SurfacePressure)]
    for j, ex in enumerate(ph.excavate):
        name = f"{where}.excavate[{j}]"
        if ex.x0 < lo - 1e-9 or ex.x1 > hi + 1e-9:
            raise ValueError(f"{name}: x0={ex.x0}, x1={ex.x1} must lie in the block [{lo:g}, {hi:g}] m")
        if ex.bottom >= scene.depth:
            raise ValueError(f"{name}: bottom={ex.bottom} m must be < the block depth {scene.depth:g} m")
        for ld in pressures:
            if ex.top == 0.0 and min(ex.x1, ld.x1) - max(ex.x0, ld.x0) > 1e-9:
                raise ValueError(
                    f"{name}: ({ex.x0}, {ex.x1}) removes the ground under SurfacePressure({ld.x0}, {ld.x1})"
                )


# values below these in SI look like they were given in kN, kPa or kN/m^3
_PLAUSIBLE_MIN = {"E": 1e5, "unit_weight": 100.0, "c": 100.0, "pressure": 100.0, "force": 1e3, "kn": 1e5}


def _warn_implausible_units(scene):
    """Warn (never refuse) where a value looks like kN, kPa or kN/m^3 instead of N, Pa, N/m^3."""

    def warn(what, value, unit, key):
        size = abs(value) if key in ("force", "pressure") else value  # a negative modulus is the validator's
        if 0.0 < size < _PLAUSIBLE_MIN[key]:
            warnings.warn(
                f"{what} = {value:g} {unit} looks small for SI units (was it given in k{unit}?); "
                "the scene uses N, Pa, N/m^3",
                UserWarning,
                stacklevel=3,
            )

    for i, lay in enumerate(scene.layers):
        warn(f"layers[{i}].E", lay.E, "Pa", "E")
        warn(f"layers[{i}].unit_weight", lay.unit_weight, "N/m^3", "unit_weight")
        if lay.c is not None:
            warn(f"layers[{i}].c", lay.c, "Pa", "c")
    warn("surcharge", scene.surcharge, "Pa", "pressure")
    for c in (
        [scene.contact] if isinstance(scene.contact, Contact) else [s.contact for s in scene.contact or []]
    ):
        warn("contact.kn", c.kn, "Pa/m", "kn")
    for load in scene._all_loads():
        if isinstance(load, ColumnLoad):
            warn("ColumnLoad.N", load.N, "N/m", "force")
        elif isinstance(load, (SurfacePressure, StripLoad)):
            warn(f"{type(load).__name__}.q", load.q, "Pa", "pressure")
        elif isinstance(load, StripWeight):
            warn("StripWeight.unit_weight", load.unit_weight, "N/m^3", "unit_weight")


# what Scene.loads (and a Phase's loads) may hold, and the per-segment contact type of a list Scene.contact
LOAD_TYPES = (ColumnLoad, SurfacePressure, StripLoad, StripWeight, Settlement)
CONTACT_SEGMENT_TYPES = (ContactSegment,)


def _check_list(name, value, cls, min_len=0):
    """A list or tuple of ``cls`` objects (a class or a tuple of classes), at least ``min_len`` of them."""
    kinds = " or ".join(c.__name__ for c in (cls if isinstance(cls, tuple) else (cls,)))
    if not isinstance(value, list | tuple):
        raise TypeError(f"{name} must be a list of {kinds}, got {value!r} ({type(value).__name__})")
    if len(value) < min_len:
        raise ValueError(f"{name} must hold at least {min_len} {kinds}, got {value!r}")
    for i, item in enumerate(value):
        check_instance(f"{name}[{i}]", item, cls)


def _check_integration(name, value):
    """A named rule of the plate strip or a pair (n_axial, n_shear) of point counts in 1..3."""
    if isinstance(value, str):
        check_choice(name, value, tuple(INTEGRATIONS))
        return
    if not (isinstance(value, list | tuple) and len(value) == 2):
        raise TypeError(
            f"{name} must be one of {tuple(INTEGRATIONS)} or a pair (n_axial, n_shear), got {value!r}"
        )
    for v in value:
        check_int(f"{name} point count", v, lo=1, hi=3)


def _describe(scene):
    """The scene record of ``model.info["scene"]``: :func:`ssi.scene.scene_file.scene_to_dict` (one home for
    the plain form of a scene; every load tagged with its class name under ``type``)."""
    from .scene_file import scene_to_dict

    return scene_to_dict(scene)


def _load_levels(n_steps):
    """Target load factors of one phase: [1] (automatic increments) for None, else n equal levels."""
    if n_steps is None:
        return [1.0]
    if isinstance(n_steps, (int, np.integer)) and not isinstance(n_steps, bool) and n_steps >= 1:
        return np.linspace(0.0, 1.0, int(n_steps) + 1)[1:]
    raise ValueError(f"n_steps must be None (automatic) or an integer >= 1, got {n_steps!r}")


def _run_phase(model, load_factors, settings, start=None, loads=None):
    """The one place a phase is stepped: ``ssi.solver.run`` along ``load_factors`` from ``start`` (the last
    converged state of the previous phase) with F_ext = lambda f_ref + f_dead (``loads``)."""
    return run(model, load_factors, settings, start=start, loads=loads)


class PhaseNonConvergence(NonConvergence):
    """A phase of a phased solve did not converge. ``scene_result`` is a :class:`SceneResult` of every
    completed phase plus the failing phase's converged steps (its record's ``result`` has status "stopped";
    ``ssi.io.results.write_result`` writes it with ``stop=report``); ``result`` is the failing phase's partial
    solver result (as for any :class:`~ssi.solver.NonConvergence`); ``report`` is the solver's report with
    ``phase`` (the failing phase's name) and ``completed_phases`` ("name (steps first-last)") added."""

    def __init__(self, report: dict, result: Result, scene_result: "SceneResult") -> None:
        super().__init__(report, result)
        self.scene_result = scene_result
        solver = ", ".join(f"{k}={v}" for k, v in report.items() if k not in ("phase", "completed_phases"))
        done = ", ".join(report["completed_phases"]) or "none"
        text = f"phase {report['phase']!r} did not converge: {solver}; completed phases: {done}"
        self.args = (text + " (all in .scene_result)",)


def _phase_failure(built, err, name, records):
    """The PhaseNonConvergence of phase ``name`` from the solver's NonConvergence ``err``, with the completed
    phases' ``records``."""
    partial = err.result
    records = records + [_phase_record(name, records, partial)]
    done = [f"{r['name']} (steps {r['first']}-{r['last']})" for r in records[:-1]]
    report = {"phase": name, "completed_phases": done, **err.report}
    scene_result = SceneResult(built, join_phases(built.model, records), phases=records)
    return PhaseNonConvergence(report, partial, scene_result)


def _phase_record(name, records, result):
    """The record of a phase solved after ``records``: its rows follow theirs (its row 0 is their last)."""
    first = records[-1]["last"] + 1
    return {"name": name, "first": first, "last": first + result.n_steps - 1, "result": result}


def join_phases(model: Model, records: list[dict]) -> Result:
    """The one :class:`~ssi.core.solution.Result` of a phased solve from its phases' ``records`` (``name``,
    ``first``, ``last``, ``result``; the geostatic phase first): on the phase time (the geostatic phase's
    first and last rows at 0, phase i's rows at i - 1 + its load factor), each phase's rows after its first
    (its first is the previous phase's last); the per-row records come along, the counts and times are
    summed, the status and limit (shifted onto the phase time) are the last phase's. Its ``f_ref`` and
    ``f_dead`` are None: each phase has its own loads (``records[i]["result"]``)."""
    geo = records[0]["result"]
    rows = {
        "load_factor": [0.0, 0.0],
        **{key: [getattr(geo, key)[0], getattr(geo, key)[-1]] for key in Result.ROWS if key != "load_factor"},
    }
    for i, record in enumerate(records[1:]):
        res = record["result"]
        rows["load_factor"] += [i + v for v in res.load_factor[1:]]
        for key in Result.ROWS[1:]:  # states: every step's, or the last only, as the phases kept them
            rows[key] += getattr(res, key)[1:]
    last, i_last = records[-1]["result"], len(records) - 2

    def phase_time(value):  # a load factor of the last phase on the phase time
        return None if value is None else i_last + value

    return Result(
        model=model,
        **rows,
        cuts=sum(r["result"].cuts for r in records),
        wall_time=sum(r["result"].wall_time for r in records),
        factorizations=sum(r["result"].factorizations for r in records),
        status=last.status,
        limit_load_factor=phase_time(last.limit_load_factor),
        limit_load_upper=phase_time(last.limit_load_upper),
        limit_evidence=last.limit_evidence,
        relaxed_steps=last.relaxed_steps,
        viscous_from=None if last.viscous_from is None else records[-1]["first"] + last.viscous_from - 1,
        u_origin=geo.u_origin,
        f_int_origin=geo.f_int_origin,
    )


def _hold(model, dofs, start, increment):
    """Constrain ``dofs`` to start + lambda * increment during a phase (the model stores a DOF's fixed value
    and its prescribed reference apart; both are set here)."""
    for d, a, b in zip(dofs, start, increment):
        model._fixed[int(d)] = float(a)
        model._prescribed[int(d)] = float(b)


@dataclass
class BuiltScene:
    scene: Scene
    model: Model
    mesh: object
    soil: SoilQ8
    plate: PlateStrip | None = None
    interface: Interface6 | None = None
    plate_nodes: np.ndarray | None = None
    geostatic_load: np.ndarray | None = None  # (n_dof,) dead loads [N/m] holding the geostatic state
    base_pressure: float = 0.0  # geostatic vertical stress [Pa] the strip's base starts with
    element_layer: np.ndarray | None = None  # (n_el,) index in scene.layers of every soil element
    footing_nodes: np.ndarray | None = None  # soil node ids under a RigidFooting (its base), ordered by x
    slide_support: int | None = None  # plate node whose u is held because every Contact.kt = 0 (frictionless)

    def plate_node_at(self, x: float, tol: float = 1e-6) -> np.integer:
        xs = self.model.coords[self.plate_nodes, 0]
        i = int(np.argmin(np.abs(xs - x)))
        if abs(xs[i] - x) > tol * max(1.0, abs(x)):
            raise ValueError(
                f"x={x}: column loads must act on the strip; nearest plate node is x={xs[i]:.6g}"
            )
        return self.plate_nodes[i]

    @property
    def is_linear(self) -> bool:
        soil_linear = all(lay.c is None for lay in self.scene.layers)
        plate_linear = self.plate is None or bool(np.all(self.plate.section.kind == LAYER_ELASTIC))
        contact_linear = self.scene.contact is None or all(
            seg.contact.phi_deg is None for seg in _segments(self.scene)
        )
        return soil_linear and plate_linear and contact_linear

    # ---- loads -----------------------------------------------------------------------------------------
    def load_effect(
        self, load: "SurfacePressure | ColumnLoad | StripLoad | StripWeight | Settlement"
    ) -> tuple[np.ndarray, dict[int, float]]:
        """(force vector (n_dof,) [N/m], {dof: prescribed displacement increment [m]}) of one load."""
        model, f_vec, held = self.model, np.zeros(self.model.n_dof), {}
        if isinstance(load, SurfacePressure):
            f = self.scene.foundation
            if f is not None and min(load.x1, f.x1) - max(load.x0, f.x0) > 1e-9:
                raise ValueError(
                    f"SurfacePressure ({load.x0}, {load.x1}) overlaps the strip ({f.x0}, {f.x1}): "
                    "a load on the strip is a StripLoad"
                )
            nodes, w = surface_pressure_forces(self.mesh, load.x0, load.x1)
            np.add.at(f_vec, model.dof(nodes, "w"), -load.q * w)
        elif isinstance(load, ColumnLoad):
            if load.H != 0.0 and self.slide_support is not None:
                raise ValueError(
                    f"ColumnLoad.H = {load.H:g} N/m at x = {load.x:g} m on a frictionless contact (every "
                    "Contact.kt = 0): nothing resists a horizontal load on the strip; give Contact.kt > 0"
                )
            node = self.plate_node_at(load.x)
            for comp, value in (("w", -load.N), ("u", load.H), ("alpha", load.M)):
                f_vec[model.dof(node, comp)] += value
        elif isinstance(load, StripLoad):
            scatter_vector(
                self.plate.edofs, self.plate.distributed_load(self._strip_profile(load), comp="w"), f_vec
            )
        elif isinstance(load, StripWeight):
            q = load.unit_weight * self.plate.section.thickness - self.scene.gamma_w * self._submerged_depth()
            scatter_vector(self.plate.edofs, self.plate.distributed_load(-q, comp="w"), f_vec)
        elif isinstance(load, Settlement) and self.footing_nodes is not None:  # a RigidFooting's base
            held.update({int(d): -float(load.w) for d in model.dof(self.footing_nodes, "w")})
        elif isinstance(load, Settlement):
            ids = self.plate_nodes if load.x is None else np.array([self.plate_node_at(x) for x in load.x])
            held.update({int(d): -float(load.w) for d in model.dof(ids, "w")})
            if load.x is None:  # rigid strip: rotations held
                held.update({int(d): 0.0 for d in model.dof(ids, "alpha")})
        else:
            raise TypeError(
                f"loads: {load!r} is not a SurfacePressure, StripLoad, StripWeight, ColumnLoad or Settlement"
            )
        return f_vec, held

    def _submerged_depth(self) -> float:
        """Thickness [m] of the strip below the water level: the water pressure on its base exceeds that on
        its top by gamma_w times it (the strip's buoyancy, netted in :class:`StripWeight`)."""
        if self.scene.water_table is None:
            return 0.0
        t = self.plate.section.thickness
        return float(np.clip(-self.scene.water_table + self.scene.embedment, 0.0, t))

    def _strip_profile(self, load):
        a = self.scene.foundation.x0 if load.x0 is None else load.x0
        b = self.scene.foundation.x1 if load.x1 is None else load.x1
        if not (self.scene.foundation.x0 - 1e-9 <= a < b <= self.scene.foundation.x1 + 1e-9):
            raise ValueError(
                f"StripLoad x0={a}, x1={b} must satisfy foundation.x0 <= x0 < x1 <= foundation.x1"
            )
        q_end = load.q if load.q_end is None else load.q_end

        def q(x):
            inside = (x >= a - 1e-12) & (x <= b + 1e-12)
            return np.where(inside, -(load.q + (q_end - load.q) * (x - a) / (b - a)), 0.0)

        return q

    def _register(self, load):
        """Add one load of the single-phase scene to the model (reference load, or prescribed settlement)."""
        f_vec, held = self.load_effect(load)
        nz = np.flatnonzero(f_vec)
        if nz.size:
            self.model.add_element_load(nz[None], f_vec[nz][None])
        for d, v in held.items():
            self.model._prescribed[d] = v
            self.model._fixed.pop(d, None)

    def pore_pressure(self) -> np.ndarray:
        """Hydrostatic pore pressure [Pa] (compression positive) at the soil's integration points (n_el,
        n_ip); the total stress is the state's effective stress minus it on the normal components."""
        z = self.soil.integration_points()[..., 1]
        return pore_pressure(z, self.scene.water_table, gamma_w=self.scene.gamma_w)

    def excess_pore_pressure(self, out: "SceneResult", k: int = -1) -> np.ndarray:
        """Excess pore pressure [Pa] (compression positive) of the undrained_A layers at the soil's
        integration points (n_el, n_ip) at step ``k`` of ``out``; zero in drained layers (and in a layer's
        drained phases, see ``Phase.drainage``) and in excavated elements."""
        config = self.soil_configuration(out, k) if out.phases else None
        try:
            if config is not None:
                self.soil.configure(config["active"], config["k_water"], config["reference"])
            return self.soil.excess_pore_pressure(out.u[k][self.soil.edofs])
        finally:
            self.soil.configure()

    def total_stress(self, out: "SceneResult", k: int = -1) -> np.ndarray:
        """(n_el, n_ip, 4) total stress [sxx, szz, txz, syy] [Pa] (tension positive) at step ``k`` of ``out``:
        the effective stress of the state minus the pore pressure (hydrostatic from the water level, ponding
        included, plus the excess of undrained layers) on the normal components."""
        p = self.pore_pressure() + self.excess_pore_pressure(out, k)
        sig = out.soil_stress(k)
        return sig - p[..., None] * np.array([1.0, 1.0, 0.0, 1.0])

    def contact_force(self, out: "SceneResult") -> np.ndarray:
        """Vertical force [N/m] the strip presses on the soil (> 0 compression) at every step of ``out``:
        -integral of sig_n along the contact. Of a push-over it is the load. Of a :class:`RigidFooting`: the
        reaction of its base nodes (of a symmetric scene: twice the modelled half's, the whole footing's)."""
        if self.footing_nodes is not None:
            return self._footing_reaction(out)
        k = self.model.groups.index(self.interface)
        w = self.interface.ip_weights()
        return np.array([-np.sum(st[k][..., V_SIG] * w) for st in out.states])

    def _footing_reaction(self, out: "SceneResult") -> np.ndarray:
        """Downward reaction [N/m] of a RigidFooting's base at every step of a single-phase solve: the
        support reactions (internal force minus the ground loads that share the footing's edge node) at the
        base's w DOFs, summed, doubled for a symmetric scene."""
        if out.phases:
            raise ValueError(
                "contact_force: the reaction of a RigidFooting is read from a single-phase solve (its "
                "Settlement in Scene.loads); of a phased solve it is not built"
            )
        whole = 2.0 if self.scene.symmetric else 1.0
        return -whole * out.solver_result.support_reaction(self.footing_nodes, "w")

    # ---- solution --------------------------------------------------------------------------------------
    def solve(
        self,
        n_steps: int | None = None,
        settings: Settings | None = None,
    ) -> "SceneResult":
        """Apply the loads up to their full value (load factor 1); one linear solve if the scene is linear and
        has no phases.

        ``n_steps=None`` (default): automatic increments (``settings.stepping``, see :class:`Settings`);
        an integer: the path passes through n equal load levels (each may be subdivided by automatic
        stepping; ``Settings.paper()`` takes each as one increment). The result's ``status`` says
        ``"completed"`` or ``"limit load reached"`` (the loads exceed what the scene can carry: the path up
        to the limit is returned); a failure before either raises :class:`~ssi.solver.NonConvergence`.

        With ``scene.phases``: the geostatic phase, then each phase in turn (``scene.loads``, if any, as the
        first, named "loads"); a phase that reaches a limit load ends the analysis. Of a phased solve,
        ``out.load_factor`` is the phase time (phase i runs from i - 1 to i; the geostatic phase is at 0),
        ``out.phases`` lists each phase's name, first and last step index and solver result, and
        ``out.solver_result`` joins their rows (:func:`join_phases`).

        An error estimate, or a refinement to a target error, is a study above the scene:
        :func:`ssi.studies.estimate.estimate`, :func:`ssi.studies.estimate.solve_to_target`."""
        if n_steps is not None:
            check_int("n_steps", n_steps, lo=1)
        check_instance("settings", settings, Settings, optional=True)
        if self.scene.phases:
            return self._solve_phases(n_steps, settings)
        if self.is_linear:
            return SceneResult(self, self.model.solve_linear(backend=(settings or Settings()).backend))
        return SceneResult(self, _run_phase(self.model, _load_levels(n_steps), settings))

    def _solve_phases(self, n_steps, settings):
        scene, model = self.scene, self.model
        phases = ([Phase("loads", tuple(scene.loads))] if scene.loads else []) + list(scene.phases)
        n = model.n_dof
        body = np.zeros(n)
        for g in model.groups:
            if g is not self.plate and g.body_force() is not None:
                scatter_vector(g.edofs, g.body_force(), body)
        plate_weight = np.zeros(n)
        if self.plate is not None and self.plate.body_force() is not None:
            scatter_vector(self.plate.edofs, self.plate.body_force(), plate_weight)
        f_geo = body + self.geostatic_load
        saved = dict(model._fixed), dict(model._prescribed)
        # the single-phase registration is not used here: phases set every load and constraint themselves
        for d in list(model._prescribed):
            model._fixed[d] = 0.0
            model._prescribed.pop(d)
        try:
            res = _run_phase(model, [1.0], settings, loads=(np.zeros(n), f_geo))
            records = [{"name": "geostatic", "first": 0, "last": 1, "result": res}]
            effects, factors, held_from = {}, {}, {}
            f_prev = np.zeros(n)
            config = self._initial_soil()
            for i, ph in enumerate(phases):
                parts = [self.load_effect(ld) for ld in ph.loads]
                f_ph = sum((p[0] for p in parts), np.zeros(n)) + (plate_weight if i == 0 else 0.0)
                held = {}
                for p in parts:
                    for d, v in p[1].items():
                        held[d] = held.get(d, 0.0) + v
                effects[ph.name] = (f_ph, held)
                factors[ph.name] = 1.0
                factors.update(ph.factors)
                for d in held:
                    held_from.setdefault(ph.name, {})[d] = float(res.u[-1][d])
                f_end = sum((factors[k] * effects[k][0] for k in effects), np.zeros(n))
                target = {}
                for k, start in held_from.items():
                    for d, u0 in start.items():
                        target[d] = target.get(d, u0) + factors[k] * effects[k][1][d]
                dofs = np.array(sorted(target), np.int64)
                now = res.u[-1][dofs]
                soil_before = config
                config = self._phase_soil(config, ph, res.u[-1])
                if config is not soil_before:  # soil removed or drainage switched
                    self.soil.configure(config["active"], config["k_water"], config["reference"])
                    self._fix_removed_nodes(config, res.u[-1])
                    f_geo = self._body_force() + self.geostatic_load - self._removed_ground_load(config)
                _hold(model, dofs, now, np.array([target[d] for d in dofs]) - now)
                # a changed soil releases the forces it no longer carries: the out-of-balance force g of the
                # phase's first state (removed elements' stress and weight, the released pore water) is
                # applied at the start and falls to zero over the phase
                g = self._release_force(res, f_geo + f_prev) if config is not soil_before else 0.0
                try:
                    res = _run_phase(
                        model,
                        _load_levels(ph.n_steps or n_steps),
                        settings,
                        start=res,
                        loads=(f_end - f_prev - g, f_geo + f_prev + g),
                    )
                except NonConvergence as err:
                    raise _phase_failure(self, err, ph.name, records) from err
                _hold(model, dofs, np.array([target[d] for d in dofs]), np.zeros(len(dofs)))
                f_prev = f_end
                records.append(_phase_record(ph.name, records, res))
                if res.collapsed:
                    break
        finally:
            model._fixed.clear()
            model._fixed.update(saved[0])
            model._prescribed.clear()
            model._prescribed.update(saved[1])
            self.soil.configure()
        return SceneResult(self, join_phases(model, records), phases=records)

    # ---- phases that change the soil: excavation, drainage switch ---------------------------------------
    def _phase_list(self):
        """The phases after the geostatic one: ``scene.loads`` (if any) as the first, named "loads"."""
        scene = self.scene
        return ([Phase("loads", tuple(scene.loads))] if scene.loads else []) + list(scene.phases)

    def _initial_soil(self):
        """The soil configuration as built: every element present, each layer's own drainage."""
        n_el = self.soil.n_el
        kw = np.array([lay.k_water() for lay in self.scene.layers])[self.element_layer]
        return {"active": np.ones(n_el, bool), "k_water": kw, "reference": np.zeros((n_el, 16))}

    def _phase_soil(self, config, phase, u_start):
        """The soil configuration of ``phase`` from that of the phase before (returned itself if unchanged):
        its excavations removed, its drainage switches made (an undrained layer's pore water counts the
        volume change from ``u_start``, the phase's first state)."""
        removed = self._excavated(phase)
        switch = {
            k: v
            for k, v in phase.drainage.items()
            if (config["k_water"][self.element_layer == k] > 0).any() != (v == "undrained_A")
        }
        if not (removed & config["active"]).any() and not switch:
            return config
        active = config["active"] & ~removed
        kw, ref = config["k_water"].copy(), config["reference"].copy()
        for k, value in switch.items():
            els = self.element_layer == k
            kw[els] = self.scene.layers[k].undrained_k_water() if value == "undrained_A" else 0.0
            ref[els] = u_start[self.soil.edofs[els]]
        return {"active": active, "k_water": kw, "reference": ref}

    def _excavated(self, phase):
        """(n_el,) bool: the soil elements inside the phase's excavation regions."""
        xc = self.soil.coords.mean(axis=1)
        out = np.zeros(self.soil.n_el, bool)
        for ex in phase.excavate:
            depth = -xc[:, 1]
            out |= (xc[:, 0] > ex.x0) & (xc[:, 0] < ex.x1) & (depth > ex.top) & (depth < ex.bottom)
        return out

    def soil_configuration(self, out: "SceneResult", k: int = -1) -> dict[str, np.ndarray]:
        """The soil configuration at step ``k`` of ``out``: ``active`` (n_el,) elements present (False:
        excavated), ``k_water`` (n_el,) K_w/n [Pa] (0: drained), ``reference`` (n_el, 16) displacement [m]
        from which each undrained element's pore water counts. Replayed from the phases of ``out``."""
        config = self._initial_soil()
        k = k % len(out.u)
        for phase, record in zip(self._phase_list(), (out.phases or [])[1:]):
            if record["first"] > k:
                break
            config = self._phase_soil(config, phase, out.u[record["first"] - 1])
        return config

    def _body_force(self):
        """(n_dof,) body forces [N/m] of the soil as currently configured (the plate's weight is a load)."""
        f = np.zeros(self.model.n_dof)
        for g in self.model.groups:
            if g is not self.plate and g.body_force() is not None:
                scatter_vector(g.edofs, g.body_force(), f)
        return f

    def _removed_ground_load(self, config):
        """(n_dof,) the part of the geostatic ground load (the surcharge) that acted on the top edges of
        excavated elements: it is removed with them."""
        f = np.zeros(self.model.n_dof)
        q, fdn = self.scene.surcharge, self.scene.foundation
        if not q:
            return f
        for e in np.flatnonzero(~config["active"]):
            top = self.mesh.conn[e][[3, 6, 2]]  # serendipity order: top edge left, middle, right
            x, z = self.mesh.xy[top, 0], self.mesh.xy[top, 1]
            under_strip = fdn is not None and fdn.x0 - 1e-9 <= x[1] <= fdn.x1 + 1e-9
            if np.all(np.abs(z) < 1e-9) and not under_strip:
                np.add.at(f, self.model.dof(top, "w"), -q * np.array([1.0, 4.0, 1.0]) * (x[2] - x[0]) / 6.0)
        return f

    def _fix_removed_nodes(self, config, u_start):
        """Hold the soil nodes that no present element uses at their displacement (they leave the system)."""
        used = np.zeros(len(self.mesh.xy), bool)
        used[self.mesh.conn[config["active"]].ravel()] = True
        for d in (
            self.model.dof(np.flatnonzero(~used), "u").tolist()
            + self.model.dof(np.flatnonzero(~used), "w").tolist()
        ):
            self.model._fixed[int(d)] = float(u_start[d])
            self.model._prescribed.pop(int(d), None)

    def _release_force(self, res, f_ext):
        """g (n_dof,) [N/m]: internal force of the changed model at the phase's first state minus the external
        force ``f_ext`` it keeps, on the free DOFs -- the excavation forces (the removed soil's stress and
        weight acting on what remains) and the pore water force a drained layer releases."""
        system = System(self.model)
        u0 = res.u[-1]
        f_int, _, _ = system.evaluate(u0, np.zeros_like(u0), res.final_state, None)
        g = np.zeros(self.model.n_dof)
        g[system.free] = (f_int - f_ext)[system.free]
        return g


@dataclass
class SceneResult:
    """What a foundation engineer reads off a scene, at step ``k`` (default: the last): a view of one
    :class:`~ssi.core.solution.Result`, ``solver_result``, whose rows (load_factor, u, f_int, states) it
    reads.

    Of a linear scene that result is :meth:`Model.solve_linear`'s (rows [unloaded, solved]); of a phased
    solve it is its phases' rows joined on the phase time (:func:`join_phases`), and ``phases`` lists each
    phase's name, first and last row and its own result."""

    built: BuiltScene
    solver_result: Result
    phases: list | None = None  # phased solve: [{"name", "first", "last" (step indices), "result"}]

    @property
    def load_factor(self) -> list:
        """Load factor of every row (of a phased solve: the phase time)."""
        return self.solver_result.load_factor

    @property
    def u(self) -> list:
        """(n_dof,) displacement [m, rad] of every row."""
        return self.solver_result.u

    @property
    def f_int(self) -> list:
        """(n_dof,) internal force [N/m] of every row."""
        return self.solver_result.f_int

    @property
    def states(self) -> list:
        """Committed states of every row (or of the last only, ``Settings.keep_states=False``)."""
        return self.solver_result.states

    @property
    def status(self) -> str:
        """ "completed" (load factor 1 reached) or "limit load reached" (collapse detected before it)."""
        return self.solver_result.status

    @property
    def limit_load_factor(self) -> float | None:
        """Load factor of the detected collapse (fraction of the scene's loads; of a phased solve, of the
        last phase's), None if completed."""
        last = self.phases[-1]["result"] if self.phases else self.solver_result
        return last.limit_load_factor

    def _group_state(self, group, k):
        return self.states[k][self.built.model.groups.index(group)]

    def settlement(self, k: int = -1) -> tuple[np.ndarray, np.ndarray]:
        """(x, settlement) along the foundation's nodes (a RigidFooting's: its base), settlement positive
        downwards."""
        ids = self.built.plate_nodes if self.built.footing_nodes is None else self.built.footing_nodes
        return self.built.model.coords[ids, 0], -self.u[k][self.built.model.dof(ids, "w")]

    def contact(self, k: int = -1) -> dict[str, np.ndarray]:
        """Interface points: dict of x, normal stress sig_n (< 0 compression), shear tau and the zone name
        ('stick', 'slip', 'open') at each integration point."""
        iface = self.built.interface
        st = self._group_state(iface, k)
        names = np.array(["stick", "slip", "open"])[Interface6.status(st)]
        return {"x": iface.ip_coords()[..., 0], "sig_n": st[..., V_SIG], "tau": st[..., V_TAU], "zone": names}

    def surface(self, k: int = -1) -> tuple[np.ndarray, np.ndarray]:
        """(x, settlement) of the soil surface, positive downwards; after an excavation the ground as it is at
        step ``k`` (the pit's bottom and walls' tops)."""
        ids = self.built.mesh.surface
        if any(ph.excavate for ph in self.built.scene.phases) and self.phases:
            mesh = self.built.mesh
            used = np.zeros(len(mesh.xy), bool)
            used[mesh.conn[self.active_elements(k)].ravel()] = True
            ids = np.array([col[(col >= 0) & used[np.maximum(col, 0)]][-1] for col in mesh.grid], np.int64)
        return self.built.model.coords[ids, 0], -self.u[k][self.built.model.dof(ids, "w")]

    def plate_layers(self, k: int = -1) -> dict[str, np.ndarray]:
        """Layer strains and stresses of the foundation at its axial sampling points.

        Returns a dict: ``x`` (n_el, n_ip), ``z`` (n_layer,) layer mid-depths above the reference surface,
        ``eps``/``sig`` (n_el, n_ip, n_layer), ``cracked`` (n_el, n_ip, n_layer) bool for concrete layers
        whose largest tensile strain passed the cracking strain fr/E0, and ``steel`` (n_layer,) bool.
        """
        plate = self.built.plate
        sec = plate.section
        u_el = self.u[k][plate.edofs]
        state = self._group_state(plate, k)
        eps, _ = plate.layer_strains(u_el)
        sig, _ = plate.layer_stresses(u_el, state)
        cracked = np.zeros(eps.shape, bool)
        for n in np.flatnonzero(sec.kind == CONCRETE):  # history slot 1: the largest tensile strain
            cracked[..., n] = state[..., n, 1] > sec.params[n, P_FR] / sec.params[n, P_E0]
        x_pts = plate.point_x()
        axial = plate.ax.astype(bool)
        return {
            "x": x_pts[:, axial],
            "z": sec.z_mid,
            "eps": eps[:, axial],
            "sig": sig[:, axial],
            "cracked": cracked[:, axial],
            "steel": sec.kind == STEEL,
        }

    # ---- what the engineer asks (issue 13); units in each docstring -------------------------------------
    @property
    def n_steps(self) -> int:
        """Number of converged load steps after the initial state (row 0 is lambda = 0)."""
        return len(self.load_factor) - 1

    def max_settlement(self, k: int = -1) -> tuple[float, float]:
        """(x [m], settlement [m]) of the foundation node that settles most at step ``k`` (positive down);
        the soil surface's if the scene has no foundation."""
        x, s = self.settlement(k) if self.built.plate is not None else self.surface(k)
        i = int(np.argmax(s))
        return float(x[i]), float(s[i])

    def contact_weights(self) -> np.ndarray:
        """(n_el, n_ip) integration weight of every contact point times the line Jacobian [m]: the contact
        length each point represents (their sum is the foundation width)."""
        return self.built.interface.ip_weights()

    def contact_resultant(self, k: int = -1) -> dict[str, float]:
        """Resultant of the contact tractions at step ``k`` per unit length of the strip: ``N`` [N/m]
        (compression positive, = the vertical load the soil carries), ``H`` [N/m] (shear, +x), ``M``
        [N m/m] (moment of the tractions about x = 0, counter-clockwise positive) and the foundation's
        ``eccentricity`` M_p/N [m] of the pressure about x = 0."""
        c = self.contact(k)
        w = self.contact_weights()
        pressure = -c["sig_n"]
        N = float(np.sum(pressure * w))
        H = float(np.sum(c["tau"] * w))
        M = float(np.sum(pressure * w * c["x"]))
        return {"N": N, "H": H, "M": M, "eccentricity": M / N if N else float("nan")}

    def strip_forces(self, k: int = -1) -> dict[str, np.ndarray]:
        """Stress resultants of the foundation strip per unit width at step ``k``, from
        ``PlateStrip.resultants``: ``x_ax`` (n_el, n_ax) [m] with normal force ``N`` [N/m] and bending moment
        ``M`` [N m/m] (positive sagging: tension at the bottom), ``x_sh`` (n_el, n_sh) [m] with shear force
        ``Q`` [N/m]."""
        plate = self.built.plate
        return plate.resultants(self.u[k][plate.edofs], self._group_state(plate, k))

    def steel_stress(self, k: int = -1) -> dict[str, np.ndarray]:
        """Stress [Pa] in every steel layer at the strip's axial points at step ``k``: ``x`` (n_el, n_ax) [m],
        ``z`` (n_steel,) [m] layer heights above the reference surface, ``sig`` (n_el, n_ax, n_steel) [Pa],
        ``yielded`` (n_el, n_ax, n_steel) bool where |sig| reached the layer's fy."""
        from ..materials.steel import S_FY

        layers = self.plate_layers(k)
        steel = layers["steel"]
        sig = layers["sig"][..., steel]
        params = self.built.plate.section.params
        fy = params[steel, S_FY] if steel.any() else np.zeros(0)
        return {
            "x": layers["x"],
            "z": layers["z"][steel],
            "sig": sig,
            "yielded": np.abs(sig) >= fy * (1.0 - 1e-9),
        }

    def crack_map(self, k: int = -1) -> dict[str, np.ndarray]:
        """Cracked concrete layer points at step ``k``: ``x`` (n_el, n_ax) [m], ``z`` (n_layer,) [m],
        ``cracked`` (n_el, n_ax, n_layer) bool (largest tensile strain beyond fr/E0; see ``plate_layers``)."""
        layers = self.plate_layers(k)
        return {"x": layers["x"], "z": layers["z"], "cracked": layers["cracked"]}

    def crack_width(self, k: int = -1) -> dict[str, np.ndarray]:
        """Crack width w_k [m] (EN 1992-1-1 7.3.4) at the strip's axial points at step ``k``: see
        :func:`ssi.scene.design.crack_width`."""
        from .design import crack_width

        return crack_width(self, k)

    def design_summary(self, **options) -> dict | None:
        """Crack widths, utilisations and envelopes of an RC strip per phase: see
        :func:`ssi.scene.design.design_summary` (``options``: gamma_c, gamma_s, kt, fck)."""
        from .design import design_summary

        return design_summary(self, **options)

    def soil_points(self) -> np.ndarray:
        """(n_el, n_ip, 2) coordinates (x, z) [m] of the soil integration points."""
        return self.built.soil.integration_points()

    def soil_stress(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip, 4) soil stress [sxx, szz, txz, syy] [Pa] (tension positive; geostatic included)."""
        return self.built.soil.stress(self._group_state(self.built.soil, k)).copy()

    def total_stress(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip, 4) total soil stress [sxx, szz, txz, syy] [Pa] (tension positive) at step ``k``: see
        :meth:`BuiltScene.total_stress`."""
        return self.built.total_stress(self, k)

    def pore_pressure(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip) pore pressure [Pa] (compression positive) at step ``k``: hydrostatic from the water
        level (ponding included) plus the excess pore pressure of undrained layers."""
        return self.built.pore_pressure() + self.built.excess_pore_pressure(self, k)

    def active_elements(self, k: int = -1) -> np.ndarray:
        """(n_el,) bool: the soil elements present at step ``k`` (False: excavated in an earlier phase)."""
        return self.built.soil_configuration(self, k)["active"]

    def plastic_points(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip) bool: soil points whose last stress update at step ``k`` returned to the yield
        surface (history slot 1, the return branch, non-zero), i.e. the points yielding in that step."""
        from ..elements.soil_q8 import N_STRESS

        return self._group_state(self.built.soil, k)[..., N_STRESS + 1] > 0.0

    def plastic_strain(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip) accumulated plastic strain norm sum |d eps_p| [-] of the soil points up to step ``k``
        (history slot 0; zero for elastic layers)."""
        from ..elements.soil_q8 import N_STRESS

        return self._group_state(self.built.soil, k)[..., N_STRESS].copy()

    def load_settlement(self) -> dict[str, np.ndarray]:
        """The load--settlement path over every converged step (also of a stopped run): ``load_factor``
        (n_steps + 1,) [-], ``column_load`` (n_steps + 1,) [N/m] = lambda * sum of the column forces N,
        ``settlement`` (n_steps + 1,) [m] the largest settlement at each step (positive down)."""
        lam = np.asarray(self.load_factor, np.float64)
        total_n = sum(load.N for load in self.built.scene.loads if isinstance(load, ColumnLoad))
        settle = np.array([self.max_settlement(k)[1] for k in range(len(lam))])
        return {"load_factor": lam, "column_load": lam * total_n, "settlement": settle}
