"""A scene built into a model (``BuiltScene``): its groups and nodes, the effect of each load, the water and
pore-pressure fields, and the staged analysis that solves it (the geostatic phase, then each phase in turn,
with excavation and drainage switches).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..core.assembly import scatter_vector
from ..core.mesh import surface_pressure_forces
from ..core.model import Model, System
from ..core.validate import (
    check_instance,
    check_int,
)
from ..elements.interface import V_SIG, Interface6
from ..elements.plate import PlateStrip
from ..elements.soil_q8 import SoilQ8
from ..materials.layer_laws import ELASTIC as LAYER_ELASTIC
from ..materials.soil_laws import (
    pore_pressure,
)
from ..solver import NonConvergence, Settings
from .checks import _segments
from .loads import LOAD_TYPES, ColumnLoad, Push, Settlement, StripLoad, StripWeight, SurfacePressure
from .stages import (
    PhaseLoads,
    _held,
    _hold,
    _load_levels,
    _phase_failure,
    _run_phase,
    join_phases,
)
from .view import SceneResult

if TYPE_CHECKING:  # for annotations only: these modules import this one
    from .scene import Scene


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
    side_interfaces: list | None = None  # SideInterface groups of the left and right walls (side_contact)

    def plate_node_at(self, x: float, tol: float = 1e-6) -> np.integer:
        xs = self.model.coords[self.plate_nodes, 0]
        i = int(np.argmin(np.abs(xs - x)))
        if abs(xs[i] - x) > tol * max(1.0, abs(x)):
            raise ValueError(
                f"x={x}: column loads must act on the strip; nearest plate node is x={xs[i]:.6g}"
            )
        return self.plate_nodes[i]

    def push_held(self, push: Push) -> dict[int, float]:
        """{dof: prescribed increment [m]} of a :class:`~ssi.scene.loads.Push` (its ``effect``): a rigid
        footing's base u; the plate nodes' u with their rotations held."""
        model, held, u = self.model, {}, push.u
        if self.footing_nodes is not None:  # a RigidFooting's base
            if not self.scene.foundation.rough:
                raise ValueError(
                    f"Push(u={u:g}) on a smooth RigidFooting (rough=False): its base nodes slide "
                    "freely, nothing carries the push; give RigidFooting(rough=True) or a plate Foundation"
                )
            held.update({int(d): float(u) for d in model.dof(self.footing_nodes, "u")})
            return held
        if self.plate_nodes is None:
            raise ValueError(f"Push(u={u:g}): the scene has no foundation to push")
        f = self.scene.foundation
        if push.x is not None and not (f.x0 - 1e-9 <= push.x <= f.x1 + 1e-9):
            raise ValueError(f"Push.x={push.x:g} m lies off the strip ({f.x0:g}, {f.x1:g}) m")
        if self.slide_support is not None:
            raise ValueError(
                f"Push(u={u:g}) on a frictionless contact (every Contact.kt = 0): the strip's middle "
                "node is held against sliding; give Contact.kt > 0"
            )
        held.update({int(d): float(u) for d in model.dof(self.plate_nodes, "u")})
        held.update({int(d): 0.0 for d in model.dof(self.plate_nodes, "alpha")})
        return held

    def slides_freely_at(self, x: float) -> bool:
        """True if the strip under ``x`` [m] has no shear stiffness (every Contact.kt = 0: its middle node's
        u held)."""
        return self.slide_support is not None

    def foundation_spans(self) -> list[tuple[float, float]]:
        """(x0, x1) [m] of the foundation (none without one): a ground pressure must stay clear of it."""
        f = self.scene.foundation
        return [] if f is None else [(f.x0, f.x1)]

    def ground_weights(self, x0: float, x1: float) -> tuple[np.ndarray, np.ndarray]:
        """(surface node ids, their share [m] of the length from ``x0`` to ``x1``): a unit ground pressure's
        consistent nodal forces."""
        return surface_pressure_forces(self.mesh, x0, x1)

    @property
    def is_linear(self) -> bool:
        soil_linear = all(lay.c is None for lay in self.scene.layers)
        plate_linear = self.plate is None or bool(np.all(self.plate.section.kind == LAYER_ELASTIC))
        contact_linear = self.scene.contact is None or all(
            seg.contact.phi_deg is None for seg in _segments(self.scene)
        )
        contact_linear &= self.scene.side_contact is None or self.scene.side_contact.phi_deg is None
        return soil_linear and plate_linear and contact_linear

    # ---- loads -----------------------------------------------------------------------------------------
    def load_effect(
        self, load: SurfacePressure | ColumnLoad | StripLoad | StripWeight | Settlement | Push
    ) -> tuple[np.ndarray, dict[int, float]]:
        """(force vector (n_dof,) [N/m], {dof: prescribed displacement increment [m]}) of one load: its own
        ``effect`` on this built scene (``ssi.scene.loads``)."""
        if not isinstance(load, tuple(LOAD_TYPES.values())):
            raise TypeError(f"loads: {load!r} is not a load type of a scene ({', '.join(LOAD_TYPES)})")
        return load.effect(self)

    def submerged_depth(self) -> float:
        """Thickness [m] of the strip below the water level: the water pressure on its base exceeds that on
        its top by gamma_w times it (the strip's buoyancy, netted in :class:`StripWeight`)."""
        if self.scene.water_table is None:
            return 0.0
        t = self.plate.section.thickness
        return float(np.clip(-self.scene.water_table + self.scene.embedment, 0.0, t))

    def _register(self, load):
        """Add one load of the single-phase scene to the model (reference load, or prescribed settlement)."""
        f_vec, held = self.load_effect(load)
        nz = np.flatnonzero(f_vec)
        if nz.size:
            self.model.add_element_load(nz[None], f_vec[nz][None])
        self.model.prescribe_dofs(np.array(list(held), np.int64), list(held.values()))

    def pore_pressure(self) -> np.ndarray:
        """Hydrostatic pore pressure [Pa] (compression positive) at the soil's integration points (n_el,
        n_ip); the total stress is the state's effective stress minus it on the normal components."""
        z = self.soil.integration_points()[..., 1]
        return pore_pressure(z, self.scene.water_table, gamma_w=self.scene.gamma_w)

    def excess_pore_pressure(self, out: SceneResult, k: int = -1) -> np.ndarray:
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

    def total_stress(self, out: SceneResult, k: int = -1) -> np.ndarray:
        """(n_el, n_ip, 4) total stress [sxx, szz, txz, syy] [Pa] (tension positive) at step ``k`` of ``out``:
        the effective stress of the state minus the pore pressure (hydrostatic from the water level, ponding
        included, plus the excess of undrained layers) on the normal components."""
        p = self.pore_pressure() + self.excess_pore_pressure(out, k)
        sig = out.soil_stress(k)
        return sig - p[..., None] * np.array([1.0, 1.0, 0.0, 1.0])

    def contact_force(self, out: SceneResult) -> np.ndarray:
        """Vertical force [N/m] the strip presses on the soil (> 0 compression) at every step of ``out``:
        -integral of sig_n along the contact. Of a push-over it is the load. Of a :class:`RigidFooting`: the
        reaction of its base nodes (of a symmetric scene: twice the modelled half's, the whole footing's)."""
        if self.footing_nodes is not None:
            return self._footing_reaction(out)
        k = self.model.groups.index(self.interface)
        w = self.interface.ip_weights()
        return np.array([-np.sum(st[k][..., V_SIG] * w) for st in out.states])

    def pushed_nodes(self) -> np.ndarray:
        """Node ids a :class:`Push` moves: a RigidFooting's base, else the plate nodes."""
        return self.footing_nodes if self.footing_nodes is not None else self.plate_nodes

    def push_force(self, out: SceneResult) -> np.ndarray:
        """Horizontal force [N/m] (> 0 in +x) the pushed foundation carries at every row of ``out`` (a
        :class:`Push`): the support reactions at the pushed u DOFs, summed (of a phased solve: each phase's
        own record, zero in the geostatic phase)."""
        nodes = self.pushed_nodes()
        if not out.phases:
            return np.asarray(out.solver_result.support_reaction(nodes, "u"), np.float64)
        force = np.zeros(len(out.load_factor))
        for record in out.phases:
            reaction = record["result"].support_reaction(nodes, "u")
            first = max(record["first"] - 1, 0) if record is not out.phases[0] else 0
            force[first : first + len(reaction)] = reaction
        return force

    def _footing_reaction(self, out: SceneResult) -> np.ndarray:
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
    def result_view(self, solver_result) -> SceneResult:
        """The view of a solver result of this scene (a NonConvergence's converged steps, a stored result)."""
        return SceneResult(self, solver_result)

    def solve(
        self,
        n_steps: int | None = None,
        settings: Settings | None = None,
    ) -> SceneResult:
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
        :func:`ssi.scene.estimate.estimate`, :func:`ssi.scene.estimate_target.solve_to_target`."""
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
        n = model.n_dof
        body = np.zeros(n)
        for g in model.groups:
            if g is not self.plate and g.body_force() is not None:
                scatter_vector(g.edofs, g.body_force(), body)
        plate_weight = np.zeros(n)
        if self.plate is not None and self.plate.body_force() is not None:
            scatter_vector(self.plate.edofs, self.plate.body_force(), plate_weight)
        f_geo = body + self.geostatic_load
        saved = model.constraint_state()
        # the single-phase registration is not used here: phases set every load and constraint themselves
        model.fix_prescribed()
        try:
            res = _run_phase(model, [1.0], settings, loads=(np.zeros(n), f_geo))
            records = [{"name": "geostatic", "first": 0, "last": 1, "result": res}]
            book = PhaseLoads(n)
            config = self._initial_soil()
            for i, ph in enumerate(scene.load_phases()):
                parts = [self.load_effect(ld) for ld in ph.loads]
                f_ph = sum((p[0] for p in parts), np.zeros(n)) + (plate_weight if i == 0 else 0.0)
                f_end, dofs, goal = book.begin(ph, f_ph, _held(parts), res.u[-1])
                f_prev = book.f_prev
                now = res.u[-1][dofs]
                soil_before = config
                config = self._phase_soil(config, ph, res.u[-1])
                if config is not soil_before:  # soil removed or drainage switched
                    self.soil.configure(config["active"], config["k_water"], config["reference"])
                    self._fix_removed_nodes(config, res.u[-1])
                    f_geo = self._body_force() + self.geostatic_load - self._removed_ground_load(config)
                _hold(model, dofs, now, goal - now)
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
                if book.end(model, dofs, goal, f_end, records, ph.name, res):
                    break
        finally:
            model.restore_constraints(saved)
            self.soil.configure()
        return SceneResult(self, join_phases(model, records), phases=records)

    # ---- phases that change the soil: excavation, drainage switch ---------------------------------------
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

    def soil_configuration(self, out: SceneResult, k: int = -1) -> dict[str, np.ndarray]:
        """The soil configuration at step ``k`` of ``out``: ``active`` (n_el,) elements present (False:
        excavated), ``k_water`` (n_el,) K_w/n [Pa] (0: drained), ``reference`` (n_el, 16) displacement [m]
        from which each undrained element's pore water counts. Replayed from the phases of ``out``."""
        config = self._initial_soil()
        k = k % len(out.u)
        for phase, record in zip(self.scene.load_phases(), (out.phases or [])[1:]):
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
        dofs = np.concatenate(
            [self.model.dof(np.flatnonzero(~used), "u"), self.model.dof(np.flatnonzero(~used), "w")]
        )
        self.model.fix_dofs(dofs, u_start[dofs])

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
