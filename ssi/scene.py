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
(the direction of a positive rotation alpha). Settlements are reported positive downwards.
"""

from dataclasses import asdict, dataclass, field

import numpy as np

from .elements.interface import V_SIG, V_TAU, Interface6, add_interface
from .elements.plate import INTEGRATIONS, PlateStrip
from .elements.soil_q8 import SoilQ8
from .materials.concrete import P_E0, P_FR
from .materials.interface_law import interface_params
from .materials.layer_laws import CONCRETE, P_LS, STEEL, layer_update
from .materials.layer_laws import ELASTIC as LAYER_ELASTIC
from .materials.soil_laws import elastic_params, geostatic_stress, material_table, mohr_coulomb_params
from .mesh import foundation_contact, soil_block
from .model import Model
from .section import Section
from .solver import Settings, run
from .validate import check_choice, check_instance, check_int, check_optional_real, check_real


@dataclass(frozen=True)
class SoilLayer:
    """One horizontal soil layer. ``c=None``: linear elastic; else Mohr--Coulomb with c, phi, psi."""

    thickness: float
    E: float
    nu: float
    unit_weight: float = 0.0
    c: float | None = None
    phi_deg: float = 0.0
    psi_deg: float | None = None
    K0: float | None = None
    scheme: str = "implicit"

    def __post_init__(self):
        check_real("SoilLayer.thickness", self.thickness, lo=0.0, lo_open=True, unit="m")
        check_real("SoilLayer.E", self.E, lo=0.0, lo_open=True, unit="Pa")
        check_real("SoilLayer.nu", self.nu, lo=-1.0, hi=0.5, lo_open=True, hi_open=True)
        check_real("SoilLayer.unit_weight", self.unit_weight, lo=0.0, unit="N/m^3")
        check_optional_real("SoilLayer.c", self.c, lo=0.0, unit="Pa")
        check_real("SoilLayer.phi_deg", self.phi_deg, lo=0.0, hi=90.0, hi_open=True, unit="degrees")
        check_optional_real("SoilLayer.psi_deg", self.psi_deg, lo=0.0, hi=self.phi_deg, unit="degrees (<= phi_deg)")
        check_optional_real("SoilLayer.K0", self.K0, lo=0.0, hi=10.0, hi_open=True)
        check_choice("SoilLayer.scheme", self.scheme, ("implicit", "explicit"))
        if self.c == 0.0 and self.phi_deg == 0.0:
            raise ValueError("SoilLayer: c=0 and phi_deg=0 give a soil without strength; need c > 0 or "
                             "phi_deg > 0 (or c=None for an elastic layer)")

    def law(self):
        if self.c is None:
            return 0, elastic_params(self.E, self.nu)
        return mohr_coulomb_params(self.E, self.nu, self.c, self.phi_deg, self.psi_deg, scheme=self.scheme)


@dataclass(frozen=True)
class Foundation:
    """The strip from x0 to x1 (both become soil mesh lines) with its layered ``section``."""

    x0: float
    x1: float
    section: Section
    kappa: float = 5.0 / 6.0
    integration: str = "selective"
    self_weight: float = 0.0  # [N/m^2] of the strip's plan area, a dead load

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
class Contact:
    """Foundation--soil interface (Coulomb). ``phi_deg=None``: bonded and elastic (never slips or opens)."""

    kn: float
    kt: float
    phi_deg: float | None = None
    c: float = 0.0
    psi_deg: float | None = None
    sig_t: float | None = None
    rule: str = "newton_cotes"

    def __post_init__(self):
        check_real("Contact.kn", self.kn, lo=0.0, lo_open=True, unit="Pa/m")
        check_real("Contact.kt", self.kt, lo=0.0, unit="Pa/m")
        check_optional_real("Contact.phi_deg", self.phi_deg, lo=0.0, hi=90.0, hi_open=True, unit="degrees")
        check_real("Contact.c", self.c, lo=0.0, allow_inf=True, unit="Pa")
        psi_max = 90.0 if self.phi_deg is None else self.phi_deg
        check_optional_real("Contact.psi_deg", self.psi_deg, lo=0.0, hi=psi_max, hi_open=self.phi_deg is None,
                            unit="degrees (<= phi_deg)")
        check_optional_real("Contact.sig_t", self.sig_t, lo=0.0, unit="Pa")
        check_choice("Contact.rule", self.rule, ("newton_cotes", "gauss"))
        self.params()  # the interface law's own checks of the combination (sig_t below the apex)

    def params(self):
        if self.phi_deg is None:
            return interface_params(self.kt, self.kn, 0.0, np.inf, None, np.inf)
        return interface_params(self.kt, self.kn, self.phi_deg, self.c, self.psi_deg, self.sig_t)


@dataclass(frozen=True)
class ColumnLoad:
    """Column forces per unit length of the strip at a plate node (x must be a node of the strip)."""

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
class MeshSize:
    h_fine: float = 0.25
    h_coarse: float = 2.0
    growth: float = 1.25
    n_gauss: int = 2

    def __post_init__(self):
        h_fine = check_real("MeshSize.h_fine", self.h_fine, lo=0.0, lo_open=True, unit="m")
        if check_real("MeshSize.h_coarse", self.h_coarse, lo=0.0, lo_open=True, unit="m") < h_fine:
            raise ValueError(f"MeshSize.h_coarse must be >= h_fine = {self.h_fine!r}, got {self.h_coarse!r}")
        check_real("MeshSize.growth", self.growth, lo=1.0)
        check_choice("MeshSize.n_gauss", self.n_gauss, (2, 3))


@dataclass
class Scene:
    width: float
    depth: float
    layers: list
    foundation: Foundation | None = None
    contact: Contact | None = None
    loads: list = field(default_factory=list)
    mesh: MeshSize = field(default_factory=MeshSize)
    surcharge: float = 0.0  # uniform pressure on the ground surface in the geostatic state [Pa]

    def __post_init__(self):
        width = check_real("Scene.width", self.width, lo=0.0, lo_open=True, unit="m")
        depth = check_real("Scene.depth", self.depth, lo=0.0, lo_open=True, unit="m")
        check_real("Scene.surcharge", self.surcharge, lo=0.0, unit="Pa")
        _check_list("Scene.layers", self.layers, SoilLayer, min_len=1)
        _check_list("Scene.loads", self.loads, LOAD_TYPES)
        check_instance("Scene.foundation", self.foundation, Foundation, optional=True)
        if isinstance(self.contact, list | tuple) and CONTACT_SEGMENT_TYPES:
            _check_list("Scene.contact", self.contact, CONTACT_SEGMENT_TYPES, min_len=1)
        else:
            check_instance("Scene.contact", self.contact, Contact, optional=True)
        check_instance("Scene.mesh", self.mesh, MeshSize)
        total = sum(lay.thickness for lay in self.layers)
        if abs(total - depth) > 1e-9 * depth:
            raise ValueError(f"Scene.depth={self.depth!r}: the layer thicknesses "
                             f"{[lay.thickness for lay in self.layers]} must tile the depth (their sum is {total:g})")
        f = self.foundation
        x0, x1 = (f.x0, f.x1) if f else (-0.25 * width, 0.25 * width)
        if f is not None and not (-0.5 * width <= x0 and x1 <= 0.5 * width):
            raise ValueError(f"Scene.foundation (x0={f.x0!r}, x1={f.x1!r}) must lie within the block "
                             f"[-width/2, width/2] = [{-0.5 * width:g}, {0.5 * width:g}] (Scene.width={self.width!r})")
        if self.mesh.h_fine > x1 - x0:
            raise ValueError(f"MeshSize.h_fine={self.mesh.h_fine!r} must be <= the foundation width x1 - x0 = "
                             f"{x1 - x0:g} m (at least one element under the foundation)")
        for i, load in enumerate(self.loads):
            if isinstance(load, ColumnLoad) and f is not None and not x0 <= load.x <= x1:
                raise ValueError(f"loads[{i}].x={load.x!r} must lie on the foundation [x0, x1] = [{x0:g}, {x1:g}]")

    def build(self) -> "BuiltScene":
        """Mesh the block, add only the groups the scene needs, supports and loads."""
        if not self.layers:
            raise ValueError("layers: the scene needs at least one soil layer")
        if self.foundation is not None and self.contact is None:
            raise ValueError("contact: a foundation needs a Contact (interface) to rest on the soil")
        if self.foundation is None and self.loads:
            raise ValueError("loads: column loads need a foundation to act on")
        f = self.foundation
        x0, x1 = (f.x0, f.x1) if f else (-0.25 * self.width, 0.25 * self.width)
        mesh = soil_block(self.width, self.depth, [lay.thickness for lay in self.layers], (x0, x1),
                          self.mesh.h_fine, self.mesh.h_coarse, self.mesh.growth)
        model = Model()
        model.info["scene"] = _describe(self)
        soil_ids = model.add_nodes(mesh.xy, ndof=2)
        kinds, params = material_table([lay.law() for lay in self.layers])
        weights = np.array([lay.unit_weight for lay in self.layers])
        soil = SoilQ8(mesh.xy[mesh.conn], model.element_dofs(soil_ids[mesh.conn]), mesh.el_layer, kinds, params,
                      n_gauss=self.mesh.n_gauss, unit_weight=weights if weights.any() else None)
        if weights.any() or self.surcharge:
            soil.initial_stress = self._geostatic(soil)
        model.add_group(soil)
        model.fix(mesh.bottom, "u")
        model.fix(mesh.bottom, "w")
        model.fix(mesh.left, "u")
        model.fix(mesh.right, "u")
        built = BuiltScene(self, model, mesh, soil)
        if f is not None:
            self._add_foundation(built)
        return built

    def _geostatic(self, soil):
        layers = [{"thickness": lay.thickness, "gamma": lay.unit_weight,
                   **({"K0": lay.K0} if lay.K0 is not None else {"phi_deg": lay.phi_deg})} for lay in self.layers]
        return geostatic_stress(soil.integration_points()[..., 1], layers, self.surcharge)

    def _add_foundation(self, built):
        f, model, mesh = self.foundation, built.model, built.mesh
        contact = foundation_contact(mesh, f.x0, f.x1, f.section.thickness)
        offset = -f.section.z_bottom  # plate nodes sit on the reference surface, this far above the soil
        plate_xy = np.column_stack([contact.plate_xy[:, 0], np.full(len(contact.plate_xy), offset)])
        ids = model.add_nodes(plate_xy, ndof=3)
        conn = ids[contact.plate_conn]
        plate = PlateStrip(plate_xy[contact.plate_conn], model.element_dofs(conn), f.section, kappa=f.kappa,
                           integration=f.integration, self_weight=f.self_weight)
        model.add_group(plate)
        iface = add_interface(model, conn, contact.soil_conn, self.contact.params(), offset=plate.bottom_offset,
                              rule=self.contact.rule)
        built.plate, built.interface, built.plate_nodes = plate, iface, ids
        for load in self.loads:
            node = built.plate_node_at(load.x)
            if load.N:
                model.add_load(node, "w", -load.N)
            if load.H:
                model.add_load(node, "u", load.H)
            if load.M:
                model.add_load(node, "alpha", load.M)


# what Scene.loads may hold, and the per-segment contact type allowed as a list in Scene.contact (none yet)
LOAD_TYPES = (ColumnLoad,)
CONTACT_SEGMENT_TYPES = ()


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
        raise TypeError(f"{name} must be one of {tuple(INTEGRATIONS)} or a pair (n_axial, n_shear), got {value!r}")
    for v in value:
        check_int(f"{name} point count", v, lo=1, hi=3)


def _describe(scene):
    d = asdict(scene)
    if scene.foundation is not None:
        s = scene.foundation.section
        d["foundation"]["section"] = {"z_mid": s.z_mid.tolist(), "h": s.h.tolist(), "kind": s.kind.tolist(),
                                      "params": s.params.tolist(), "carries_shear": s.carries_shear.tolist()}
    return d


@dataclass
class BuiltScene:
    scene: Scene
    model: Model
    mesh: object
    soil: SoilQ8
    plate: PlateStrip | None = None
    interface: Interface6 | None = None
    plate_nodes: np.ndarray | None = None

    def plate_node_at(self, x, tol=1e-6):
        xs = self.model.coords[self.plate_nodes, 0]
        i = int(np.argmin(np.abs(xs - x)))
        if abs(xs[i] - x) > tol * max(1.0, abs(x)):
            raise ValueError(f"x={x}: column loads must act at a plate node; nearest is x={xs[i]:.6g} "
                             "(refine or align the mesh)")
        return self.plate_nodes[i]

    @property
    def is_linear(self) -> bool:
        soil_linear = all(lay.c is None for lay in self.scene.layers)
        plate_linear = self.plate is None or bool(np.all(self.plate.section.kind == LAYER_ELASTIC))
        contact_linear = self.scene.contact is None or self.scene.contact.phi_deg is None
        return soil_linear and plate_linear and contact_linear

    def solve(self, n_steps=10, settings: Settings | None = None):
        """Apply the loads in ``n_steps`` equal increments (one linear solve if the scene is linear)."""
        n_steps = check_int("n_steps", n_steps, lo=1)
        check_instance("settings", settings, Settings, optional=True)
        if self.is_linear:
            lin = self.model.solve_linear(backend=(settings or Settings()).backend)
            return SceneResult(self, [0.0, 1.0], [np.zeros_like(lin.u), lin.u], [lin.states, lin.states], None)
        if int(n_steps) < 1:
            raise ValueError(f"n_steps must be >= 1, got {n_steps}")
        res = run(self.model, np.linspace(0.0, 1.0, int(n_steps) + 1)[1:], settings)
        return SceneResult(self, res.load_factor, res.u, res.states, res)


@dataclass
class SceneResult:
    """What a foundation engineer reads off a scene, at step ``k`` (default: the last)."""

    built: BuiltScene
    load_factor: list
    u: list
    states: list
    solver_result: object

    def _group_state(self, group, k):
        return self.states[k][self.built.model.groups.index(group)]

    def settlement(self, k=-1):
        """(x, settlement) along the foundation's nodes, settlement positive downwards."""
        ids = self.built.plate_nodes
        return self.built.model.coords[ids, 0], -self.u[k][self.built.model.dof(ids, "w")]

    def contact(self, k=-1):
        """Interface points: dict of x, normal stress sig_n (< 0 compression), shear tau and the zone name
        ('stick', 'slip', 'open') at each integration point."""
        iface = self.built.interface
        st = self._group_state(iface, k)
        names = np.array(["stick", "slip", "open"])[Interface6.status(st)]
        return {"x": iface.ip_coords()[..., 0], "sig_n": st[..., V_SIG], "tau": st[..., V_TAU], "zone": names}

    def surface(self, k=-1):
        """(x, settlement) of the soil surface, positive downwards."""
        ids = self.built.mesh.surface
        return self.built.model.coords[ids, 0], -self.u[k][self.built.model.dof(ids, "w")]

    def plate_layers(self, k=-1):
        """Layer strains and stresses of the foundation at its axial sampling points.

        Returns a dict: ``x`` (n_el, n_ip), ``z`` (n_layer,) layer mid-depths above the reference surface,
        ``eps``/``sig`` (n_el, n_ip, n_layer), ``cracked`` (n_el, n_ip, n_layer) bool for concrete layers whose
        largest tensile strain passed the cracking strain fr/E0, and ``steel`` (n_layer,) bool.
        """
        plate = self.built.plate
        sec = plate.section
        u_el = self.u[k][plate.edofs]
        state = self._group_state(plate, k)
        eps, gam = plate.layer_strains(u_el)
        length = plate._x[:, 2] - plate._x[:, 0]
        sig = np.zeros_like(eps)
        cracked = np.zeros(eps.shape, bool)
        h_new = np.zeros(state.shape[-1])
        for e in range(plate.n_el):
            for q in range(plate.n_ip):
                for n in range(sec.n_layer):
                    prm = sec.params[n].copy()
                    if plate.band[n]:
                        prm[P_LS] = 0.5 * plate.wt[q] * length[e]
                    hist = state[e, q, n]
                    sig[e, q, n] = layer_update(sec.kind[n], prm, eps[e, q, n], gam[e, q], hist, h_new, 0)[0]
                    if sec.kind[n] == CONCRETE:
                        cracked[e, q, n] = hist[1] > prm[P_FR] / prm[P_E0]
        x_pts = np.array([[np.dot(_lagrange_row(xi), plate._x[e]) for xi in plate.xi] for e in range(plate.n_el)])
        axial = plate.ax.astype(bool)
        return {"x": x_pts[:, axial], "z": sec.z_mid, "eps": eps[:, axial], "sig": sig[:, axial],
                "cracked": cracked[:, axial], "steel": sec.kind == STEEL}


def _lagrange_row(xi):
    return np.array([0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)])
