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
  strip (push-over: rigid or at the columns, the contact force is the load); :class:`Push` of the strip
  sideways (horizontal push-over: the horizontal reaction is the load).
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
* **Side contact** of an embedded strip: ``side_contact`` (a :class:`Contact`, its own Coulomb parameters)
  puts interfaces between the trench walls and the strip's vertical sides, which move as the strip's end
  sections (:mod:`ssi.elements.side_interface`), so a horizontal load mobilises the passive resistance and
  the friction of the backfill. They start carrying the walls' geostatic horizontal stress. None (default):
  the walls keep that stress as a dead load and touch nothing.
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
from dataclasses import dataclass, field, replace
from itertools import pairwise
from typing import ClassVar

import numpy as np

from ..capacity import CapacityResult, SafetyFactorResult, limit_analysis, safety_factor
from ..core.mesh import soil_block
from ..core.model import Model
from ..core.validate import (
    check_bool,
    check_instance,
    check_optional_real,
    check_real,
)
from ..elements.soil_q8 import SoilQ8
from ..elements.supports import fix_block
from ..materials.soil_laws import (
    GAMMA_W,
    SoilLayer,
    geostatic_stress,
    material_table,
)
from ..solver.progress import announce_compilation
from .built import BuiltScene
from .checks import (
    _check_excavations,
    _check_phases,
    _check_rigid_footing,
    _check_symmetric,
    _segments,
    _warn_implausible_units,
)
from .loads import LOAD_TYPES
from .parts import (
    CONTACT_SEGMENT_TYPES,
    Contact,
    Foundation,
    MeshSize,
    Phase,
    RigidFooting,
    _check_list,
    load_phases,
)
from .scene_parts import SceneParts


@dataclass
class Scene(SceneParts):
    """A strip foundation on layered subsoil: ``width``, ``depth`` [m] of the soil block; ``layers`` from the
    ground surface down (thicknesses tile ``depth``); ``foundation`` and its ``contact`` (one
    :class:`Contact` or a list of :class:`ContactSegment`); ``loads`` of the first phase after the geostatic
    one; ``mesh``; ``surcharge`` [Pa] on the ground (a dead load of the geostatic state, beside the strip; the
    strip carries it over its own width); ``phases`` after ``loads``; ``embedment`` D [m] of the strip's base
    below the ground (a layer boundary); ``water_table`` [m] depth of the water table below the ground (None:
    dry; negative: free water stands -water_table above the ground, ponding); ``gamma_w`` [N/m^3] unit weight
    of water; ``symmetric``: model only the half x >= 0 (see below); ``side_contact`` a :class:`Contact` on
    the vertical sides of an embedded strip (None: none; see the module docstring).

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
    side_contact: Contact | None = None

    kind: ClassVar[str] = "scene"  # the input's kind (a Site's: "site"), as result files name it

    def __post_init__(self):
        width = check_real("Scene.width", self.width, lo=0.0, lo_open=True, unit="m")
        depth = check_real("Scene.depth", self.depth, lo=0.0, lo_open=True, unit="m")
        check_real("Scene.surcharge", self.surcharge, lo=0.0, unit="Pa")
        _check_list("Scene.layers", self.layers, SoilLayer, min_len=1)
        _check_list("Scene.loads", self.loads, tuple(LOAD_TYPES.values()))
        check_instance("Scene.foundation", self.foundation, (Foundation, RigidFooting), optional=True)
        check_bool("Scene.symmetric", self.symmetric)
        if isinstance(self.contact, list | tuple) and CONTACT_SEGMENT_TYPES:
            _check_list("Scene.contact", self.contact, CONTACT_SEGMENT_TYPES, min_len=1)
        else:
            check_instance("Scene.contact", self.contact, Contact, optional=True)
        check_instance("Scene.mesh", self.mesh, MeshSize)
        check_instance("Scene.side_contact", self.side_contact, Contact, optional=True)
        if self.side_contact is not None and not (
            self.embedment > 0.0 and isinstance(self.foundation, Foundation)
        ):
            raise ValueError(
                f"Scene.side_contact={self.side_contact!r}: side contact needs an embedded plate Foundation "
                f"(embedment > 0, got {self.embedment!r}; foundation {type(self.foundation).__name__})"
            )
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
        a, b = self.footprint()
        if self.mesh.h_fine > b - a:
            raise ValueError(
                f"MeshSize.h_fine={self.mesh.h_fine!r} must be <= the foundation width x1 - x0 = "
                f"{b - a:g} m{' of the modelled half' if self.symmetric else ''} (at least one element under "
                "the foundation)"
            )
        for i, load in enumerate(self.loads):
            for x, _ in load.columns():
                if f is not None and not x0 <= x <= x1:
                    raise ValueError(
                        f"loads[{i}].x={x!r} must lie on the foundation [x0, x1] = [{x0:g}, {x1:g}]"
                    )

    def build(self) -> "BuiltScene":
        """Mesh the block, add only the groups the scene needs, supports, the geostatic state and loads.

        On a fresh install (numba's cache empty) one line on stderr says the kernels compile now, once."""
        if not self.layers:
            raise ValueError("layers: the scene needs at least one soil layer")
        if isinstance(self.foundation, Foundation) and self.contact is None:
            raise ValueError("contact: a foundation needs a Contact (interface) to rest on the soil")
        if self.foundation is not None and self.foundation.rigid:
            _check_rigid_footing(self)
        strip_loads = [ld for ld in self._all_loads() if ld.ground_span() is None]
        if self.foundation is None and strip_loads:
            raise ValueError(
                f"loads: {type(strip_loads[0]).__name__} needs a foundation to act on (a pressure on "
                "the ground without a foundation is a SurfacePressure)"
            )
        if self.embedment and self.foundation is None:
            raise ValueError(f"embedment={self.embedment}: an embedded scene needs a foundation")
        # the first kernels run while building (geostatic state, a linear solve): say why it takes ~1 min
        announce_compilation()
        _check_phases(self)
        _warn_implausible_units(self)
        f = self.foundation
        mesh_layers = self.mesh_layers()
        mesh = soil_block(
            0.5 * self.width if self.symmetric else self.width,
            self.depth,
            [t for t, _, _ in mesh_layers],
            self.footprint(),
            self.mesh.h_fine,
            self.mesh.h_coarse,
            self.mesh.growth,
            x_left=self.block()[0],
            breaks=self._breaks(),
            embedment=self.embedment,
            edges=sorted({v for ph in self.phases for ex in ph.excavate for v in (ex.x0, ex.x1)}),
            end_grading=self.mesh.end_grading,
        )
        model = Model()
        model.info["scene"] = self  # the scene itself; a result file stores its plain form (ssi.io.results)
        if self.symmetric:  # the half x >= 0 of a scene mirrored about x = 0: what the solver's small-strain
            model.info["mirror_x"] = 0.0  # check of a limit needs to measure the whole loaded width
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
            soil.initial_stress = self.geostatic(soil.integration_points()[..., 1])
        model.add_group(soil)
        fix_block(model, mesh, soil_ids)
        built = BuiltScene(self, model, mesh, soil)
        owner = [next(i for i, lay in enumerate(self.layers) if lay is own) for _, own, _ in mesh_layers]
        built.element_layer = np.array(owner, np.int64)[mesh.el_layer]
        built.geostatic_load = self._ground_loads(built)
        if f is not None and f.rigid:
            self._add_rigid_footing(built, soil_ids)
        elif f is not None:
            self._add_foundation(built)
        model.add_element_load(np.arange(model.n_dof)[None], built.geostatic_load[None], dead=True)
        _check_excavations(built)
        for load in self.loads:
            built._register(load)
        return built

    def limit_analysis(self, phase: str | None = None, gap: float = 0.02, **options) -> CapacityResult:
        """The scene's capacity as a certified bracket by finite-element limit analysis: lambda scales the
        loads of ``phase`` (None: the last phase; a Settlement push: lambda is the footing's vertical force
        [N/m]) with the earlier phases' loads, the surcharge and the soil's weight held; refined until the
        relative gap (UB - LB)/(UB + LB) <= ``gap``. Returns the associated and the Davis brackets, the
        mesh, the mechanism and the stress field (:class:`ssi.capacity.CapacityResult`; ``options``:
        see :func:`ssi.capacity.limit_analysis`). Raises ValueError naming any part of the scene that
        the limit analysis cannot represent (a horizontal :class:`Push` among them)."""
        self._refuse_push("limit_analysis")
        return limit_analysis(self, phase=phase, gap=gap, **options)

    def safety_factor(self, phase: str | None = None, **options) -> SafetyFactorResult:
        """The factor of safety by strength reduction (c / F, tan phi / F of the soil and the contact) under
        the soil's weight, the dead loads and the loads of ``phase`` at factor 1, a certified bracket
        [F_LB, F_UB] refined adaptively to ``gap`` (default 2 %; :func:`ssi.capacity.safety_factor`
        for ``options``)."""
        self._refuse_push("safety_factor")
        return safety_factor(self, phase=phase, **options)

    def soils(self) -> list:
        """The soil of each region: the ``layers`` from the top down (a :class:`Site`'s adds its lenses')."""
        return list(self.layers)

    def load_phases(self) -> list[Phase]:
        """The phases after the geostatic one: ``loads`` as a first Phase "loads" (if any), then ``phases``
        (what the limit problem scales and holds)."""
        return load_phases(self.loads, self.phases)

    def contact_laws(self) -> list:
        """The distinct Contact laws under the plate strip: the one ``contact``, or its segments' laws in
        order (none without a contact)."""
        if self.contact is None or isinstance(self.contact, Contact):
            return [] if self.contact is None else [self.contact]
        laws = []
        for seg in self.contact:
            if seg.contact not in laws:
                laws.append(seg.contact)
        return laws

    def sections(self) -> list:
        """The sections of the plate strips (the one strip's; none without a plate strip)."""
        return [self.foundation.section] if isinstance(self.foundation, Foundation) else []

    def with_sections(self, fn) -> "Scene":
        """A copy whose plate strip's section is ``fn(section)`` (a scene without a plate strip: itself)."""
        if not self.sections():
            return self
        return replace(self, foundation=replace(self.foundation, section=fn(self.foundation.section)))

    def _refuse_push(self, what: str) -> None:
        """A horizontal Push is not represented by the limit analysis (ssi.limit pushes vertically)."""
        pushes = [ld for ld in self._all_loads() if ld.drives == "horizontal"]
        if pushes:
            raise ValueError(
                f"{what}: {pushes[0]!r} in the scene's loads: a horizontal push is not built in the limit "
                "analysis; give the horizontal force as ColumnLoad.H, or read the push-over's capacity()"
            )

    # ---- the block, as the capacity bridge reads it (ssi.capacity.LimitInput) --------------------------
    def block(self) -> tuple[float, float]:
        """(x_left, x_right) [m] of the modelled block: the whole width centred on x = 0, or its half x >= 0
        of a symmetric scene."""
        return (0.0 if self.symmetric else -0.5 * self.width), 0.5 * self.width

    def footprint(self) -> tuple[float, float]:
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
            out += load.mesh_lines()
        lo, hi = self.block()
        bad = [x for x in out if not (lo <= x <= hi)]
        if bad:
            half = " (the modelled half of a symmetric scene)" if self.symmetric else ""
            raise ValueError(f"loads: x={bad[0]} lies outside the block [{lo}, {hi}] m{half}")
        if isinstance(f, Foundation):
            out += [v for seg in _segments(self) for v in (seg.x0, seg.x1)]
        return out

    def mesh_layers(self) -> list[tuple[float, SoilLayer, float]]:
        """The block's horizontal bands from the ground down: [(thickness [m], layer, body-force unit weight
        [N/m^3])], each layer split at the water table and at the top and bottom of every excavation; the
        unit weight is gamma above the water table and the buoyant gamma_sat - gamma_w below it (the soil
        state is effective stress). The thicknesses tile ``depth``."""
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

    def geostatic(self, z: np.ndarray) -> np.ndarray:
        """Effective geostatic stress [Pa] (tension positive), shape ``z.shape + (4,)`` in the order
        [sxx, szz, txz, syy], at the elevations ``z`` [m] (z = 0 the ground, negative below): the weight of
        the layers above (buoyant below the water table) plus the ``surcharge``, the horizontal components
        K0 times the vertical (:func:`ssi.materials.soil_laws.geostatic_stress`)."""
        return geostatic_stress(
            z, self.layers, self.surcharge, water_table=self.water_table, gamma_w=self.gamma_w
        )

    def has_geostatic_stress(self) -> bool:
        """True if the block starts from a geostatic stress: a ``surcharge`` or a layer with weight."""
        return bool(self.surcharge) or any(lay.unit_weight or lay.unit_weight_sat for lay in self.layers)
