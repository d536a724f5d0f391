"""The result view: what a foundation engineer reads off a solved scene (``SceneResult``)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from ..core.solution import Result
from .foundation_result import FoundationResult, NotInThisScene
from .view_load_path import LoadPathView

if TYPE_CHECKING:  # for annotations only: these modules import this one
    from .built import BuiltScene


@dataclass
class SceneResult(LoadPathView):
    """What a foundation engineer reads off a scene, at step ``k`` (default: the last): a view of one
    :class:`~ssi.core.solution.Result`, ``solver_result``, whose rows (load_factor, u, f_int, states) it
    reads.

    Of a linear scene that result is :meth:`Model.solve_linear`'s (rows [unloaded, solved]); of a phased
    solve it is its phases' rows joined on the phase time (:func:`join_phases`), and ``phases`` lists each
    phase's name, first and last row and its own result."""

    kind: ClassVar[str] = "scene"  # what the outputs (summary, figures, result file) read it as

    built: BuiltScene
    solver_result: Result
    phases: list | None = None  # phased solve: [{"name", "first", "last" (step indices), "result"}]
    # the estimated discretisation error of capacity()["load"], attached by ssi.scene.estimate
    # (solve_with_error, solve_to_target): {"relative", "error" [N/m], "extrapolated" [N/m], "values" [N/m]
    # on h, h/2, h/4, "order", "asymptotic", "refinements", "how"}; None: not estimated
    capacity_error: dict | None = None
    # the estimate of every headline quantity (ssi.scene.estimate.ErrorEstimate.to_dict: the asked one, each
    # quantity's value, error, relative error, extrapolated value, orders), attached with capacity_error by
    # solve_with_error and estimate_solved (ssi run --estimate); kept by the result file. None: not estimated
    error_estimate: dict | None = None
    # the run's verdict (ssi.scene.verdict.verdict, `ssi run`): the capacity bracket of its loads, the
    # margin, settlements and RC utilisations; kept by the result file. None: not asked
    verdict: dict | None = None

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

    def _needs_plate(self, what: str) -> None:
        """Raise :class:`NotInThisScene` for ``what`` (an accessor's name) unless the scene has a plate strip
        on an interface."""
        if self.built.plate is not None and self.built.interface is not None:
            return
        f = self.built.scene.foundation
        if f is None:
            raise NotInThisScene(
                f"{what}: the scene has no foundation (read the soil: surface(), soil_stress())"
            )
        raise NotInThisScene(
            f"{what}: a {type(f).__name__} has no plate strip and no contact interface (its base nodes are "
            "held and pushed): its load is foundation_load() and capacity(), its settlement settlement()"
        )

    @property
    def foundation(self):
        """The scene's foundation part (a Foundation, a RigidFooting, or None)."""
        return self.built.scene.foundation

    @property
    def plate(self):
        """The foundation's PlateStrip group (None: the scene has no plate strip)."""
        return self.built.plate

    def foundation_result(self, what: str = "foundation_result()") -> FoundationResult:
        """The view of the scene's plate strip (the same one a site's strips have); :class:`NotInThisScene`
        naming ``what`` when the scene has no plate strip on an interface."""
        self._needs_plate(what)
        b = self.built
        f = b.scene.foundation
        return FoundationResult(self, b.model, f, b.plate, b.interface, b.plate_nodes, self.phases)

    def settlement(self, k: int = -1) -> tuple[np.ndarray, np.ndarray]:
        """(x, settlement) along the foundation's nodes (a RigidFooting's: its base), settlement positive
        downwards."""
        ids = self.built.plate_nodes if self.built.footing_nodes is None else self.built.footing_nodes
        return self.built.model.coords[ids, 0], -self.u[k][self.built.model.dof(ids, "w")]

    def contact(self, k: int = -1) -> dict[str, np.ndarray]:
        """Interface points: dict of x, normal stress sig_n (< 0 compression), shear tau and the zone name
        ('stick', 'slip', 'open') at each integration point (:meth:`FoundationResult.contact`)."""
        return self.foundation_result("contact()").contact(k)

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
        """Layer strains and stresses of the foundation at its axial sampling points
        (:meth:`FoundationResult.plate_layers`)."""
        return self.foundation_result("plate_layers()").plate_layers(k)

    # ---- what the engineer asks (issue 13); units in each docstring -------------------------------------
    @property
    def n_steps(self) -> int:
        """Number of converged load steps after the initial state (row 0 is lambda = 0)."""
        return len(self.load_factor) - 1

    def max_settlement(self, k: int = -1) -> tuple[float, float]:
        """(x [m], settlement [m]) of the foundation node that settles most at step ``k`` (positive down);
        the soil surface's if the scene has no foundation."""
        has_foundation = self.built.plate is not None or self.built.footing_nodes is not None
        x, s = self.settlement(k) if has_foundation else self.surface(k)
        i = int(np.argmax(s))
        return float(x[i]), float(s[i])

    def contact_weights(self) -> np.ndarray:
        """(n_el, n_ip) contact length [m] each contact point represents (their sum is the foundation
        width)."""
        return self.foundation_result("contact_weights()").contact_weights()

    def contact_resultant(self, k: int = -1) -> dict[str, float]:
        """Resultant of the contact tractions at step ``k``: ``N``, ``H`` [N/m], ``M`` [N m/m] about x = 0 and
        the ``eccentricity`` [m] (:meth:`FoundationResult.contact_resultant`)."""
        return self.foundation_result("contact_resultant()").contact_resultant(k)

    def strip_forces(self, k: int = -1) -> dict[str, np.ndarray]:
        """Stress resultants of the foundation strip per unit width at step ``k``: ``x_ax``, ``N`` [N/m],
        ``M`` [N m/m] (sagging positive), ``x_sh``, ``Q`` [N/m] (:meth:`FoundationResult.strip_forces`)."""
        return self.foundation_result("strip_forces()").strip_forces(k)

    def steel_stress(self, k: int = -1) -> dict[str, np.ndarray]:
        """Stress [Pa] in every steel layer at the strip's axial points
        (:meth:`FoundationResult.steel_stress`)."""
        return self.foundation_result("steel_stress()").steel_stress(k)

    def crack_map(self, k: int = -1) -> dict[str, np.ndarray]:
        """Cracked concrete layer points at step ``k`` (:meth:`FoundationResult.crack_map`)."""
        return self.foundation_result("crack_map()").crack_map(k)

    def crack_width(self, k: int = -1) -> dict[str, np.ndarray]:
        """Crack width w_k [m] (EN 1992-1-1 7.3.4) at the strip's axial points at step ``k``: see
        :func:`ssi.scene.design.crack_width`."""
        return self.foundation_result("crack_width()").crack_width(k)

    def design_summary(self, **options) -> dict | None:
        """Crack widths, utilisations and envelopes of an RC strip per phase: see
        :func:`ssi.scene.design.design_summary` (``options``: gamma_c, gamma_s, kt, fck)."""
        if self.built.plate is None:  # a scene without a strip has nothing to design
            return None
        return self.foundation_result("design_summary()").design_summary(**options)

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
        surface (the history field ``branch`` non-zero), i.e. the points yielding in that step."""
        soil = self.built.soil
        return soil.history(self._group_state(soil, k), "branch") > 0.0

    def plastic_strain(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip) accumulated plastic strain norm sum |d eps_p| [-] of the soil points up to step ``k``
        (the history field ``plastic_strain``; zero for elastic layers)."""
        soil = self.built.soil
        return soil.history(self._group_state(soil, k), "plastic_strain").copy()

    def contact_pressure(self, k: int = -1) -> dict[str, float]:
        """The contact pressure at step ``k`` as an engineer reports it [Pa, m]: ``mean`` (contact resultant N
        over the contact length), ``peak`` and ``x_peak`` the largest pressure at points farther than
        ``edge_exclusion`` = 10 % of the foundation width from its edges, and ``edge`` and ``x_edge`` the
        largest pressure anywhere -- at a stiff foundation's edge the singularity of an elastic corner,
        which grows as the mesh is refined (up to the soil's strength where it yields): not a bearing
        pressure."""
        self._needs_plate("contact_pressure()")
        c = self.contact(k)
        x, p = c["x"].ravel(), -c["sig_n"].ravel()
        f = self.built.scene.foundation
        exclusion = 0.1 * (f.x1 - f.x0)
        inner = np.minimum(np.abs(x - f.x0), np.abs(f.x1 - x)) > exclusion
        if self.built.scene.symmetric:  # the modelled half ends at the axis x = 0, not at an edge
            inner = np.abs(f.x1 - x) > exclusion
        if not inner.any():
            inner[:] = True
        i = int(np.argmax(np.where(inner, p, -np.inf)))
        j = int(np.argmax(p))
        length = float(self.contact_weights().sum())
        return {
            "mean": self.contact_resultant(k)["N"] / length,  # both of the modelled part (half if symmetric)
            "peak": float(p[i]),
            "x_peak": float(x[i]),
            "edge": float(p[j]),
            "x_edge": float(x[j]),
            "edge_exclusion": float(exclusion),
        }

    def phase_table(self) -> list[dict]:
        """Per phase (a single-phase scene: one, named "loading"), its extremes over its rate-independent
        equilibrium rows that hold states, SI units: ``name``, ``first``/``last`` rows, ``end_load_factor``
        [-], ``column_load`` and ``foundation_load`` at its end [N/m], ``max_settlement`` [m] with ``x`` and
        ``row``; with a plate strip ``max_abs_moment`` [N m/m] (and x), ``mean_pressure`` at its end and
        ``peak_pressure`` (edge-excluded, :meth:`contact_pressure`) [Pa], ``max_steel_stress`` |sigma_s| [Pa]
        (None without steel). The geostatic phase is left out (no load on the foundation yet)."""
        if self.phases:
            spans = [(r["name"], r["first"], r["last"]) for r in self.phases[1:]]
        else:
            spans = [("loading", 0, len(self.load_factor) - 1)]
        n_rows = len(self.load_factor)
        with_state = n_rows - len(self.states)
        ok = self.equilibrium_rows()
        col, load = self.column_load(), self.foundation_load()
        table = []
        for name, first, last in spans:
            rows = [k for k in range(first, last + 1) if ok[k]] or [last]
            settle = [self.max_settlement(k) for k in rows]
            i = int(np.argmax([s for _, s in settle]))
            row = {
                "name": name,
                "first": first,
                "last": last,
                "end_load_factor": float(self.phases[[r["name"] for r in self.phases].index(name)]["result"]
                                         .load_factor[-1]) if self.phases else float(self.load_factor[-1]),
                "column_load": float(col[last]),
                "foundation_load": float(load[last]),
                "max_settlement": settle[i][1],
                "x_max_settlement": settle[i][0],
                "row_max_settlement": rows[i],
            }  # fmt: skip
            if self.built.plate is not None:
                stated = [k for k in rows if k >= with_state] or [n_rows - 1]
                m_best, x_m, p_best, x_p, s_best = 0.0, float("nan"), 0.0, float("nan"), None
                for k in stated:
                    f = self.strip_forces(k)
                    j = int(np.abs(f["M"]).argmax())
                    if abs(f["M"].ravel()[j]) >= m_best:
                        m_best, x_m = float(abs(f["M"].ravel()[j])), float(f["x_ax"].ravel()[j])
                    cp = self.contact_pressure(k)
                    if cp["peak"] >= p_best:
                        p_best, x_p = cp["peak"], cp["x_peak"]
                    sig = self.steel_stress(k)["sig"]
                    if sig.size:
                        s_best = max(s_best or 0.0, float(np.abs(sig).max()))
                row |= {
                    "max_abs_moment": m_best,
                    "x_max_abs_moment": x_m,
                    "mean_pressure": self.contact_pressure(stated[-1])["mean"],
                    "peak_pressure": p_best,
                    "x_peak_pressure": x_p,
                    "max_steel_stress": s_best,
                }
            table.append(row)
        return table
