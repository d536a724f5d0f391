"""Model problems shared by several chapters, benchmarks and tests (one home for each).

* :func:`chapter11_foundation` -- the RC foundation beam on soft clay over sand under two columns of chapter
  11, as a :class:`~ssi.scene.Scene`; chapters 13 and 14 and ``benchmarks/bench_sweep.py`` vary it.
* :func:`chapter11_section` -- that beam's RC section.
* :func:`winkler_strip` -- a plate strip on an interface bed over a rigid base under a point load: the finite
  element model of Hetenyi's beam on a Winkler foundation (chapters 07 and 13 compare it with
  :func:`ssi.lab.analytical.hetenyi_deflection`).
* :class:`ElasticStrip` / ``CHAPTER02_STRIP`` -- the elastic plate strip of chapter 02's closed-form studies
  (02a to 02d) with its stiffnesses.
* :func:`excavated_column` and :func:`excavated_column_errors` -- chapter 12's one-dimensional excavation
  check (the top layer removed over the full width) against its hand calculation; also
  ``tests/test_scene_phases.py``.
* :func:`pit_beside_strip` and :func:`pit_reaction_drop` -- chapter 12's pit dug beside a loaded strip and its
  equilibrium check (the bottom reaction falls by the removed weight); also ``tests/test_scene_phases.py``.
* :func:`drainage_switch_scene`, :func:`drainage_switch_errors` and :func:`switched_layer_pore_pressure` --
  chapter 12's layer switched drained -> undrained -> drained and its closed forms; also
  ``tests/test_scene_phases.py``.
* :func:`surcharge_heave` -- chapter 12's surcharge that must not move the ground; also
  ``tests/test_scene.py``.
* :func:`ponding_scene`, :func:`ponding_errors` and :func:`submerged_strip_error` -- chapter 12's free water
  above the ground and its hand calculations; also ``tests/test_scene_phases.py``.
"""

import math
from dataclasses import dataclass

import numpy as np

from ..core.mesh import foundation_contact, soil_block
from ..core.model import Model
from ..core.validate import check_int, check_real
from ..elements.interface import add_interface
from ..elements.plate import add_plate_strip
from ..elements.section import Section, homogeneous, rc_section
from ..elements.supports import fix_block, soil_group
from ..materials.interface_law import interface_params
from ..materials.layer_laws import CONCRETE, STEEL
from ..materials.rc import concrete_params, designer_concrete, steel_params
from ..materials.soil_laws import ELASTIC, GAMMA_W, elastic_params
from ..scene import (
    BuiltScene,
    ColumnLoad,
    Contact,
    Excavation,
    Foundation,
    MeshSize,
    Phase,
    Scene,
    SceneResult,
    SoilLayer,
    StripWeight,
    SurfacePressure,
)

__all__ = [
    "CHAPTER02_STRIP",
    "ElasticStrip",
    "chapter11_foundation",
    "chapter11_section",
    "drainage_switch_errors",
    "drainage_switch_scene",
    "excavated_column",
    "excavated_column_errors",
    "pit_beside_strip",
    "pit_reaction_drop",
    "ponding_errors",
    "ponding_scene",
    "submerged_strip_error",
    "surcharge_heave",
    "switched_layer_pore_pressure",
    "winkler_strip",
]


@dataclass(frozen=True)
class ElasticStrip:
    """A homogeneous elastic plate strip: Young's modulus ``E`` [Pa], Poisson's ratio ``nu`` [-], depth ``h``
    [m], shear correction factor ``kappa`` [-]; per metre of width (plane strain across it)."""

    E: float = 30.0e9
    nu: float = 0.2
    h: float = 1.0
    kappa: float = 5.0 / 6.0

    @property
    def E1(self) -> float:
        """D1 = E / (1 - nu^2) [Pa], the plane-strain modulus of the fibre (chapter 02a)."""
        return self.E / (1.0 - self.nu**2)

    @property
    def G(self) -> float:
        """D2 = E / (2 (1 + nu)) [Pa], the shear modulus."""
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def EI(self) -> float:
        """Bending stiffness D1 h^3 / 12 [N m^2/m]."""
        return self.E1 * self.h**3 / 12.0

    @property
    def kGA(self) -> float:
        """Shear stiffness kappa G h [N/m]."""
        return self.kappa * self.G * self.h

    def section(self) -> Section:
        """The strip's :class:`~ssi.elements.section.Section` (:func:`ssi.elements.section.homogeneous`, its
        default layers)."""
        return homogeneous(self.h, self.E, self.nu)


# chapter 02's strip: depth 1 m, so that span/depth is the span in metres
CHAPTER02_STRIP = ElasticStrip()

CHAPTER11_COLUMN_LOAD = 400e3  # [N/m] per column (chapter 11: the cracked, elastic service state)


def chapter11_section(fc: float = 38e6, fy: float = 500e6, area: float = 1.5e-3) -> Section:
    """The 0.4 m deep RC strip of chapter 11: bars of ``area`` [m^2/m] top and bottom at 5 cm cover, concrete
    of strength ``fc`` [Pa] with the designer parameters of chapter 03, steel of yield stress ``fy`` [Pa]
    (Es = 200 GPa), 9 concrete layers."""
    es = 200e9
    d = designer_concrete(fc)
    concrete = (CONCRETE, concrete_params(fc, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, fy / es))
    return rc_section(
        0.4, [(0.05, area), (0.35, area)], concrete, (STEEL, steel_params(fy, es)), n_concrete=9
    )


def chapter11_foundation(
    h_fine: float = 1.0,
    *,
    column_load: float = CHAPTER11_COLUMN_LOAD,
    horizontal_load: float = 0.0,
    clay_E: float = 10e6,
    clay_c: float = 20e3,
    clay_phi_deg: float = 20.0,
    h_coarse: float = 2.0,
    growth: float = 1.3,
    section: Section | None = None,
    end_grading: float = 1.0,
) -> Scene:
    """The scene of chapter 11: a 6 m long RC beam (:func:`chapter11_section`) on 2 m of soft clay over 8 m of
    sand, a 30 m x 10 m block, two columns at x = +-2.5 m carrying ``column_load`` [N/m] each (the left one
    also ``horizontal_load`` [N/m]), the beam's self-weight 25 kN/m^3 x 0.4 m.

    ``h_fine`` / ``h_coarse`` [m]: element size under the beam / far from it, ``growth`` [-] their ratio per
    element, ``end_grading`` [-] the grading of the elements under the beam towards its ends (1: even;
    :class:`~ssi.scene.MeshSize`); ``clay_E`` [Pa], ``clay_c`` [Pa], ``clay_phi_deg`` [deg]: the clay's
    modulus and strength (the variables of chapter 14); ``section``: another strip section (default
    chapter 11's)."""
    check_real("column_load", column_load, unit="N/m")
    return Scene(
        width=30.0,
        depth=10.0,
        layers=[
            SoilLayer(2.0, E=clay_E, nu=0.3, unit_weight=18e3, c=clay_c, phi_deg=clay_phi_deg, psi_deg=0.0),
            SoilLayer(8.0, E=80e6, nu=0.3, unit_weight=20e3, c=1e3, phi_deg=35.0, psi_deg=5.0),
        ],
        foundation=Foundation(
            x0=-3.0,
            x1=3.0,
            section=chapter11_section() if section is None else section,
            self_weight=25e3 * 0.4,
            bar_diameter=0.016,
        ),
        contact=Contact(kn=4e9, kt=4e8, phi_deg=25.0),
        loads=[ColumnLoad(x=-2.5, N=column_load, H=horizontal_load), ColumnLoad(x=2.5, N=column_load)],
        mesh=MeshSize(h_fine=h_fine, h_coarse=h_coarse, growth=growth, end_grading=end_grading),
    )


def winkler_strip(n_el: int, depth: float, E: float, nu: float, k: float, P: float):
    """A plate strip (``depth`` [m], ``E`` [Pa], ``nu`` [-]) on interface elements of normal stiffness ``k``
    [Pa/m] (k_t = 0, no strength limit) whose lower nodes are fixed, ``n_el`` elements over a length
    6 pi / lambda, lambda = (k / 4EI)^(1/4), EI = E depth^3 / (12 (1 - nu^2)) (the ends then carry
    exp(-3 pi) = 8e-5 of the centre's deflection), a point load ``P`` [N/m] at the middle node; solved
    linearly. Returns (x [m], w [m], settlement positive) of the strip's nodes."""
    n_el = check_int("n_el", n_el, lo=2)
    for name, v in (("depth", depth), ("E", E), ("k", k)):
        check_real(name, v, lo=0.0, lo_open=True)
    check_real("nu", nu, lo=0.0, hi=0.5, hi_open=True)
    ei = E * depth**3 / (12 * (1 - nu**2))
    lam = (k / (4 * ei)) ** 0.25
    length = 2 * 3 * math.pi / lam
    m = Model()
    plate, pids, pconn = add_plate_strip(
        m, np.linspace(-length / 2, length / 2, n_el + 1), homogeneous(depth, E, nu), z=depth / 2
    )
    low = m.add_nodes(m.coords[pids] - [0.0, depth / 2], 2)
    add_interface(
        m, pconn, low[pconn - pids[0]], interface_params(0.0, k, c=math.inf), offset=plate.bottom_offset
    )
    m.fix(low, "u")
    m.fix(low, "w")
    mid = pids[len(pids) // 2]
    m.fix([mid], "u")
    m.add_load([mid], "w", -P)
    res = m.solve_linear(backend="superlu")
    return m.coords[pids, 0], -res.displacement(pids, "w")[-1]


def punch_settlement(n_under: int, end_grading: float = 1.0) -> float:
    """Settlement [m] of a rigid, smooth strip punch (chapter 07's Sadowsky problem: half-width 1 m, plate
    E = 1e12 Pa, interface k_n = 1e13 Pa/m, k_t = 0) pressed by 100 kN/m into an elastic block (E = 10 MPa,
    nu = 0.3) 20 m wide and 10 m deep, with ``n_under`` elements under the punch graded by ``end_grading``
    (:class:`~ssi.scene.MeshSize`), 4 times that size far from it; solved linearly. P w / 2 is the strain
    energy, so its convergence order measures how a mesh family resolves the punch's edge singularity."""
    n_under = check_int("n_under", n_under, lo=1)
    h = 2.0 / n_under
    mesh = soil_block(20.0, 10.0, foundation=(-1.0, 1.0), h_fine=h, h_coarse=4 * h, end_grading=end_grading)
    m = Model()
    ids = m.add_nodes(mesh.xy, 2)
    soil_group(m, mesh, [(ELASTIC, elastic_params(10e6, 0.3))], ids=ids)
    contact = foundation_contact(mesh, -1.0, 1.0, 0.5)
    plate, pids, pconn = add_plate_strip(m, contact.plate_xy[0::2, 0], homogeneous(0.5, 1e12, 0.2), z=0.25)
    add_interface(
        m, pconn, ids[contact.soil_conn], interface_params(0.0, 1e13, c=math.inf), offset=plate.bottom_offset
    )
    fix_block(m, mesh, ids)
    mid = pids[len(pids) // 2]
    m.fix([mid], "u")
    m.add_load([mid], "w", -100e3)
    return float(-m.solve_linear(backend="superlu").displacement([mid], "w")[-1, 0])


def excavated_column(
    t: float = 2.0,
    depth: float = 6.0,
    E: float = 20e6,
    nu: float = 0.3,
    unit_weight: float = 18e3,
    K0: float = 0.5,
) -> Scene:
    """Chapter 12's one-dimensional excavation: an elastic block 4 m wide and ``depth`` [m] deep (bottom
    fixed, sides on rollers) of modulus ``E`` [Pa], Poisson's ratio ``nu``, ``unit_weight`` [N/m^3] and
    at-rest coefficient ``K0``, whose top ``t`` [m] is excavated over the full width in one phase of one
    step."""
    return Scene(
        width=4.0,
        depth=depth,
        layers=[SoilLayer(depth, E=E, nu=nu, unit_weight=unit_weight, K0=K0)],
        mesh=MeshSize(h_fine=0.5, h_coarse=1.0, growth=1.2),
        phases=[Phase("dig", excavate=(Excavation(-2.0, 2.0, bottom=t),), n_steps=1)],
    )


def excavated_column_errors(scene: Scene) -> dict:
    """Solve an :func:`excavated_column` scene and compare it with the hand calculation of chapter 12:
    removing the top layer (thickness t) unloads the remaining column uniformly and laterally confined, so
    the new surface heaves gamma t (H - t) / M with M = E (1 - nu) / ((1 + nu)(1 - 2 nu)), sigma_v rises by
    gamma t and sigma_h by nu / (1 - nu) gamma t (tension positive).

    Returns the largest relative errors ``heave``, ``sigma_v``, ``sigma_h`` [-], the FE heave of the new
    surface's nodes ``heave_nodes`` [m] and the hand value ``heave_hand`` [m], ``kept`` (the elements that
    remain, (n_el,) bool), the integration points' ``z`` [m] and ``stress`` [Pa] after the phase, and the
    ``built`` scene and its result ``out``."""
    layer, dig = scene.layers[0], scene.phases[0].excavate[0]
    t, depth, gamma, k0 = dig.bottom, scene.depth, layer.unit_weight, layer.K0
    m_oed = layer.E * (1 - layer.nu) / ((1 + layer.nu) * (1 - 2 * layer.nu))
    built = scene.build()
    out = built.solve()
    new_surface = np.flatnonzero(np.abs(built.mesh.xy[:, 1] + t) < 1e-9)
    heave = out.u[-1][built.model.dof(new_surface, "w")]
    heave_hand = gamma * t * (depth - t) / m_oed
    kept = out.active_elements()
    z = built.soil.integration_points()[..., 1]
    sig = out.soil_stress()
    d_sv = sig[kept][..., 1] - gamma * z[kept]
    d_sh = sig[kept][..., 0] - k0 * gamma * z[kept]
    return dict(
        heave=np.abs(heave / heave_hand - 1).max(),
        sigma_v=np.abs(d_sv / (gamma * t) - 1).max(),
        sigma_h=np.abs(d_sh / (layer.nu / (1 - layer.nu) * gamma * t) - 1).max(),
        heave_nodes=heave,
        heave_hand=heave_hand,
        kept=kept,
        z=z,
        stress=sig,
        built=built,
        out=out,
    )


PIT_STRIP_LOAD = 300e3  # [N/m] the column on the strip beside the pit


def pit_beside_strip(section: Section | None = None) -> Scene:
    """Chapter 12's pit beside a loaded strip, default solver settings: a Mohr--Coulomb top layer (3 m) over
    an elastic one (5 m), water table at 1 m, a 10 kPa surcharge, a strip at x = -5..-3 m (``section``,
    default a stiff 0.5 m homogeneous one) carrying 300 kN/m in phase "building", then phase "pit" digs a
    5 m wide, 1.5 m deep pit from x = -1.3 m (neither end on the regular mesh) on a 20 m x 8 m block."""
    return Scene(
        width=20.0,
        depth=8.0,
        layers=[
            SoilLayer(
                3.0, E=20e6, nu=0.3, unit_weight=18e3, unit_weight_sat=20e3, c=10e3, phi_deg=30.0, psi_deg=0.0
            ),
            SoilLayer(5.0, E=60e6, nu=0.3, unit_weight=19e3, unit_weight_sat=21e3),
        ],
        water_table=1.0,
        surcharge=10e3,
        foundation=Foundation(
            x0=-5.0, x1=-3.0, section=homogeneous(0.5, 30e9, 0.2) if section is None else section
        ),
        contact=Contact(kn=1e10, kt=1e9),
        mesh=MeshSize(h_fine=0.5, h_coarse=2.0, growth=1.3),
        phases=[
            Phase("building", loads=(ColumnLoad(-4.0, N=PIT_STRIP_LOAD),)),
            Phase("pit", excavate=(Excavation(-1.3, 3.7, bottom=1.5),)),
        ],
    )


def pit_reaction_drop(built: BuiltScene, out: SceneResult) -> tuple[list[float], float]:
    """(bottom reaction [N/m] at the end of each phase of a solved :func:`pit_beside_strip`, the load the pit
    removes [N/m]). Equilibrium: from the building phase to the pit phase the reaction falls by the removed
    buoyant weight plus the surcharge that stood on the pit, 5 (18 kN/m^3 x 1 m + (20 - 9.81) kN/m^3 x 0.5 m)
    + 10 kPa x 5 m = 165.5 kN/m; the building phase raises it by the strip's load."""
    bottom_w = built.model.dof(built.mesh.bottom, "w")
    reaction = [np.array(r["result"].f_int)[-1][bottom_w].sum() for r in out.phases]
    removed = 5.0 * (18e3 * 1.0 + (20e3 - GAMMA_W) * 0.5) + 10e3 * 5.0
    return reaction, removed


def drainage_switch_scene(layer: SoilLayer, section: Section | None = None, **changes: object) -> Scene:
    """Chapter 12's drainage-switch block: ``layer`` (its thickness is the block's depth) 12 m wide, water
    table at 1 m, a strip at x = -1..1 m (``section``, default a stiff 0.5 m homogeneous one) on a contact
    kn = 1e10 Pa/m, kt = 1e9 Pa/m; ``changes``: other :class:`~ssi.scene.Scene` fields (loads, phases,
    foundation=None...)."""
    fields = {
        "width": 12.0,
        "depth": layer.thickness,
        "layers": [layer],
        "foundation": Foundation(
            x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2) if section is None else section
        ),
        "contact": Contact(kn=1e10, kt=1e9),
        "mesh": MeshSize(h_fine=0.5, h_coarse=2.0, growth=1.5),
        "water_table": 1.0,
    }
    return Scene(**(fields | changes))


def drainage_switch_errors(
    E: float = 20e6, nu: float = 0.3, nu_u: float = 0.495, depth: float = 6.0, section: Section | None = None
) -> dict:
    """Chapter 12's drained -> undrained -> drained check on :func:`drainage_switch_scene` (elastic skeleton
    ``E`` [Pa], ``nu``; undrained Poisson's ratio ``nu_u``; ``depth`` [m]): a column of 200 kN/m at x = 0
    drained ("construction"), a second one (150 kN/m, 20 kN/m horizontal, x = 0.3 m) undrained_A ("rapid"),
    then drained again ("consolidation"). Closed forms: the undrained increment is that of an elastic soil
    with the skeleton's G and nu_u under the second column; the consolidated state is the drained response
    to both columns (an elastic skeleton does not remember the path).

    Returns the relative errors ``increment`` and ``consolidated`` [-] (max |difference| / max |reference|),
    the phased ``built`` scene, its result ``out`` and ``step`` {phase name: last step}."""
    layer = SoilLayer(depth, E=E, nu=nu, unit_weight=18e3, unit_weight_sat=20e3, nu_u=nu_u)
    first_load, second_load = ColumnLoad(0.0, N=200e3), ColumnLoad(0.3, N=150e3, H=20e3)
    switch = drainage_switch_scene(
        layer,
        section,
        phases=[
            Phase("construction", loads=(first_load,)),
            Phase("rapid", loads=(second_load,), drainage={0: "undrained_A"}),
            Phase("consolidation", drainage={0: "drained"}),
        ],
    )
    built = switch.build()
    out = built.solve(n_steps=1)
    step = {r["name"]: r["last"] for r in out.phases}
    shear = E / (2 * (1 + nu))
    undrained_layer = SoilLayer(
        depth, E=2 * shear * (1 + nu_u), nu=nu_u, unit_weight=18e3, unit_weight_sat=20e3
    )
    u_nu_u = drainage_switch_scene(undrained_layer, section, loads=[second_load]).build().solve().u[-1]
    u_drained = drainage_switch_scene(layer, section, loads=[first_load, second_load]).build().solve().u[-1]
    increment = (
        np.abs(out.u[step["rapid"]] - out.u[step["construction"]] - u_nu_u).max() / np.abs(u_nu_u).max()
    )
    consolidated = np.abs(out.u[step["consolidation"]] - u_drained).max() / np.abs(u_drained).max()
    return dict(increment=increment, consolidated=consolidated, built=built, out=out, step=step)


def switched_layer_pore_pressure(
    E: float = 20e6, nu: float = 0.3, nu_u: float = 0.495, depth: float = 6.0, dq: float = 10e3
) -> dict:
    """Chapter 12's one-dimensional drainage switch: a drained fill of 20 kPa over the whole width of
    :func:`drainage_switch_scene` (no strip), then ``dq`` [Pa] with the layer undrained_A. Closed form
    (eps_x = 0): the excess pore pressure is dq (K_w/n) / (K_w/n + M') with M' = K' + 4G/3 and
    K_w/n = K_u - K', K_u = 2G (1 + nu_u) / (3 (1 - 2 nu_u)), from zero at the switch.

    Returns the largest relative ``error`` [-], the excess pore pressure ``p`` [Pa] at the integration points
    after the undrained phase, the closed form ``p_hand`` [Pa], ``built``, ``out`` and ``step``."""
    layer = SoilLayer(depth, E=E, nu=nu, unit_weight=18e3, unit_weight_sat=20e3, nu_u=nu_u)
    shear = E / (2 * (1 + nu))
    k_water = 2 * shear * (1 + nu_u) / (3 * (1 - 2 * nu_u)) - E / (3 * (1 - 2 * nu))
    m_skeleton = E / (3 * (1 - 2 * nu)) + 4 * shear / 3
    scene = drainage_switch_scene(
        layer,
        foundation=None,
        contact=None,
        phases=[
            Phase("fill", loads=(SurfacePressure(-6.0, 6.0, 20e3),)),
            Phase("rapid", loads=(SurfacePressure(-6.0, 6.0, dq),), drainage={0: "undrained_A"}),
        ],
    )
    built = scene.build()
    out = built.solve(n_steps=1)
    step = {r["name"]: r["last"] for r in out.phases}
    p = built.excess_pore_pressure(out, step["rapid"])
    p_hand = dq * k_water / (k_water + m_skeleton)
    return dict(error=np.abs(p / p_hand - 1).max(), p=p, p_hand=p_hand, built=built, out=out, step=step)


def ponding_scene(h_pond: float, depth: float = 6.0, E: float = 20e6, nu: float = 0.3) -> Scene:
    """Chapter 12's ponding scene: an elastic layer (``E`` [Pa], ``nu``, 18/20 kN/m^3 above/below the table,
    K0 = 0.5) ``depth`` [m] deep and 12 m wide under free water ``h_pond`` [m] above the ground
    (``water_table = -h_pond``), loaded by 50 kPa on x = -1..1 m in one phase."""
    layer = SoilLayer(depth, E=E, nu=nu, unit_weight=18e3, unit_weight_sat=20e3, K0=0.5)
    return drainage_switch_scene(
        layer,
        foundation=None,
        contact=None,
        water_table=-h_pond,
        phases=[Phase("load", loads=(SurfacePressure(-1.0, 1.0, 50e3),))],
    )


def ponding_errors(
    h_ponds: tuple = (0.0, 1.0, 3.0), depth: float = 6.0, E: float = 20e6, nu: float = 0.3
) -> dict:
    """Solve :func:`ponding_scene` for every pond depth in ``h_ponds`` [m] (the first is the reference, 0: the
    table at the ground) and compare with chapter 12's closed forms: the effective stress and the
    displacements do not depend on the pond (the skeleton does not see it), the pore pressure is
    gamma_w (h + d) and the total vertical stress -(gamma_w h + gamma_sat d) at depth d.

    Returns {h: {"stress", "u", "pore_pressure", "total_stress": largest relative errors [-], "built",
    "out"}}."""
    runs = {}
    for h_pond in h_ponds:
        built = ponding_scene(h_pond, depth, E, nu).build()
        runs[h_pond] = (built, built.solve(n_steps=1))
    ref_built, ref_out = runs[h_ponds[0]]
    d = -ref_built.soil.integration_points()[..., 1]
    errors = {}
    for h_pond, (built, out) in runs.items():
        errors[h_pond] = dict(
            stress=np.abs(out.soil_stress() - ref_out.soil_stress()).max()
            / np.abs(ref_out.soil_stress()).max(),
            u=np.abs(out.u[-1] - ref_out.u[-1]).max() / np.abs(ref_out.u[-1]).max(),
            pore_pressure=np.abs(out.pore_pressure(1) / (GAMMA_W * (h_pond + d)) - 1).max(),
            total_stress=np.abs(out.total_stress(1)[..., 1] / -(GAMMA_W * h_pond + 20e3 * d) - 1).max(),
            built=built,
            out=out,
        )
    return errors


def submerged_strip_error(depth: float = 6.0, E: float = 20e6, nu: float = 0.3) -> tuple[float, float]:
    """Chapter 12's 0.5 m strip, 2 m wide, under 2 m of free water on :func:`ponding_scene`'s layer, loaded by
    its ``StripWeight`` of 25 kN/m^3: the contact force is the buoyant weight (25e3 - gamma_w) x 0.5 m x 2 m
    (hand calculation). Returns (relative error [-], contact force [N/m])."""
    layer = SoilLayer(depth, E=E, nu=nu, unit_weight=18e3, unit_weight_sat=20e3, K0=0.5)
    scene = drainage_switch_scene(
        layer, water_table=-2.0, phases=[Phase("weight", loads=(StripWeight(25e3),))]
    )
    built = scene.build()
    force = built.contact_force(built.solve(n_steps=1))[-1]
    return abs(force / ((25e3 - GAMMA_W) * 0.5 * 2.0) - 1), force


def surcharge_heave(
    with_strip: bool, q: float = 10e3, depth: float = 6.0, E: float = 20e6, nu: float = 0.3
) -> tuple[float, BuiltScene, SceneResult]:
    """Chapter 12's surcharge check: only the surcharge ``q`` [Pa] on an elastic layer (``E`` [Pa], ``nu``,
    18 kN/m^3) ``depth`` [m] deep and 12 m wide, with or without the stiff 0.5 m strip at x = -1..1 m, in one
    phase. The geostatic state carries the surcharge, so nothing may move; the measure is the largest
    surface displacement over the heave q H / M that a block out of equilibrium by q would show (M the
    constrained modulus). Returns (that ratio [-], the built scene, its result)."""
    scene = Scene(
        width=12.0,
        depth=depth,
        layers=[SoilLayer(depth, E=E, nu=nu, unit_weight=18e3)],
        surcharge=q,
        mesh=MeshSize(h_fine=0.5, h_coarse=2.0, growth=1.5),
        foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)) if with_strip else None,
        contact=Contact(kn=1e10, kt=1e9) if with_strip else None,
        phases=[Phase("surcharge only")],
    )
    m_oed = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
    built = scene.build()
    out = built.solve(n_steps=1)
    return np.abs(out.surface()[1]).max() / (q * depth / m_oed), built, out
