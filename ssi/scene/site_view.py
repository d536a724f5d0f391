"""What is read off a solved site (``SiteResult``): strip settlements, tilt and differential settlement, the
ground's settlement, the soil stress, a rigid strip's pressure; and Gibson's settlement to check it by."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from .foundation_result import FoundationResult, NotInThisScene
from .parts import load_history

if TYPE_CHECKING:  # for annotations only: the built site imports this module
    from .site_built import BuiltSite

__all__ = ["SiteResult", "gibson_settlement"]


@dataclass
class SiteResult:
    """The solution of a :class:`BuiltSite`: ``result`` the solver's :class:`~ssi.core.solution.Result`."""

    kind: ClassVar[str] = "site"  # what the outputs (summary, figures, result file) read it as

    built: BuiltSite
    result: object
    # the estimated discretisation error of the headline quantities (ssi.scene.estimate.estimate_solved, `ssi
    # run --estimate`): ErrorEstimate.to_dict(), or {"failed": why}; None: not estimated
    error_estimate: dict | None = None
    capacity_error: dict | None = None  # a site answers no capacity (kept for the estimate's interface)
    verdict: dict | None = None  # the run's verdict (ssi.scene.verdict, `ssi run`); kept by the result file
    # a phased solve (Site.phases): [{"name", "first", "last" (row indices), "result"}], the geostatic phase
    # first; None: one loading phase
    phases: list | None = None

    @property
    def solver_result(self):
        """The solver's :class:`~ssi.core.solution.Result` (as a SceneResult names it)."""
        return self.result

    @property
    def u(self) -> list:
        return self.result.u

    def rigid_pressure(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """(settlement [m], mean pressure [Pa]) histories of the RigidStrip ``i``: the pressure is the
        vertical support reaction of its base nodes (and of an embedded strip's side contact body, the
        friction on its walls) over its width."""
        st, res = self.built.strips[i], self.result
        w = res.displacement(st["soil_nodes"][:1], "w")[:, 0]
        return -w, -res.support_reaction(pushed_nodes(st), "w") / st["width"]

    def push_force(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """(horizontal displacement [m], horizontal force [N/m]) histories of strip ``i`` pushed by a
        :class:`~ssi.scene.loads.Push`, both > 0 in +x: the displacement of its first pushed node and the
        summed support reaction at its pushed u DOFs (a plate's nodes, a RigidStrip's base)."""
        st, res = self.built.strips[i], self.result
        nodes = pushed_nodes(st)
        return res.displacement(nodes[:1], "u")[:, 0], res.support_reaction(nodes, "u")

    def strip_settlement(self, i: int, k: int = -1) -> tuple[np.ndarray, np.ndarray]:
        """(x [m], settlement [m], positive down) of the plate nodes of strip ``i`` at step ``k``."""
        return self.foundation_result(i).settlement(k)

    def strip_summary(self, i: int, k: int = -1) -> dict:
        """Strip ``i``: ``mean`` settlement [m] (average over its width), ``max`` [m], ``tilt`` [rad] (the
        slope of the least-squares line through its settlements; > 0: the right end settles more)."""
        return self.foundation_result(i).settlement_summary(k)

    def differential_settlement(self, i: int, j: int, k: int = -1) -> float:
        """Mean settlement of strip ``i`` minus that of strip ``j`` [m]."""
        return self.strip_summary(i, k)["mean"] - self.strip_summary(j, k)["mean"]

    def ground_settlement(self, x0: float | None = None, x1: float | None = None, k: int = -1):
        """(x [m], settlement [m], positive down) of the ground nodes between x0 and x1 (default: all); of an
        embedded strip the ground beside its trench (its base is :meth:`strip_settlement`)."""
        site = self.built.site
        ids = self.built.ground_nodes(
            site.x_left if x0 is None else x0, site.x_right if x1 is None else x1, chain=False
        )
        return self.built.mesh.xy[ids, 0], -self.u[k][self.built.model.dof(ids, "w")]

    def soil_stress(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip, 4) effective stress [sxx, szz, txz, syy] [Pa] at step ``k``."""
        soil = self.built.soil
        return soil.stress(self.result.states[k][self.built.model.groups.index(soil)])

    # ---- the fields the outputs read (result file, ParaView, plots) -------------------------------------
    @property
    def load_factor(self) -> list:
        """Load factor of every row (0 the initial state, 1 the full loads)."""
        return self.result.load_factor

    @property
    def states(self) -> list:
        """Committed states of every kept row, one array per element group."""
        return self.result.states

    @property
    def status(self) -> str:
        """The solver result's status ("completed" or "limit load reached")."""
        return self.result.status

    def _state(self, group, k):
        return self.result.states[k][self.built.model.groups.index(group)]

    def plastic_points(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip) bool: soil points yielding in step ``k`` (history ``branch`` non-zero)."""
        return self.built.soil.history(self._state(self.built.soil, k), "branch") > 0.0

    def plastic_strain(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip) accumulated plastic strain norm [-] of the soil points up to step ``k``."""
        return self.built.soil.history(self._state(self.built.soil, k), "plastic_strain").copy()

    def pore_pressure(self) -> np.ndarray:
        """(n_el, n_ip) hydrostatic pore pressure [Pa] (compression positive) below the site's water table:
        gamma_w times the depth of each soil point below it (the soil stresses are effective)."""
        xy = self.built.soil.integration_points()
        head = self.built.site.water_z(xy[..., 0]) - xy[..., 1]
        return self.built.site.gamma_w * np.where(np.isfinite(head), np.maximum(head, 0.0), 0.0)

    @property
    def is_push_over(self) -> bool:
        """True if a strip is driven by a prescribed displacement (a RigidStrip's settlement, a Push)."""
        site = self.built.site
        loads = list(site.loads) + [ld for ph in site.phases for ld in ph.loads]
        return any(st.get("rigid") for st in self.built.strips) or any(ld.drives for ld in loads)

    @property
    def limit_load_factor(self) -> float | None:
        """Load factor of the detected collapse (fraction of the site's loads), None if completed."""
        return self.result.limit_load_factor

    def column_load(self, i: int) -> np.ndarray:
        """(n_rows,) column force [N/m] standing on strip ``i`` at every row (the sum of the ColumnLoad N on
        it): the loads times the load factor of a single-phase solve; of a phased solve every phase's columns
        at their factors, the running phase's ramped by its load factor (:func:`ssi.scene.parts.load_history`,
        zero in the geostatic phase)."""
        x0, x1 = self.built.site.strips[i].ends

        def on_strip(loads):
            return float(sum(n for ld in loads for x, n in ld.columns() if x0 - 1e-9 <= x <= x1 + 1e-9))

        lam = np.asarray(self.load_factor, np.float64)
        if not self.phases:
            return lam * on_strip(self.built.site.loads)
        return load_history(self.built.site.load_phases(), self.phases, len(lam), on_strip)

    def phase_table(self) -> list[dict]:
        """Per phase (a single-phase solve: one, named "loading"; the geostatic phase left out), its end
        state, SI units: ``name``, ``first`` / ``last`` rows, ``end_load_factor`` [-] reached in it,
        ``max_settlement`` [m] the largest of its foundations' settlements, and ``foundations``, one row per
        strip: ``index``, a plate strip's ``mean_settlement_m``, ``max_settlement_m`` [m] (positive down),
        ``tilt_rad`` and the ``column_N_N_per_m`` standing on it; a RigidStrip's ``settlement_m``."""
        if self.phases:
            spans = [(r["name"], r["first"], r["last"], r["result"].load_factor[-1]) for r in self.phases[1:]]
        else:
            spans = [("loading", 0, len(self.load_factor) - 1, self.load_factor[-1])]
        strips = self.built.strips
        columns = {i: self.column_load(i) for i, st in enumerate(strips) if not st.get("rigid")}
        table = []
        for name, first, last, lam in spans:
            rows = []
            for i, st in enumerate(strips):
                if st.get("rigid"):
                    rows.append({"index": i, "settlement_m": float(self.rigid_pressure(i)[0][last])})
                    continue
                d = self.strip_summary(i, last)
                rows.append({
                    "index": i, "mean_settlement_m": d["mean"], "max_settlement_m": d["max"],
                    "tilt_rad": d["tilt"], "column_N_N_per_m": float(columns[i][last]),
                })  # fmt: skip
            settle = [r.get("max_settlement_m", r.get("settlement_m")) for r in rows]
            table.append({
                "name": name, "first": first, "last": last, "end_load_factor": float(lam),
                "max_settlement": max(settle) if settle else None, "foundations": rows,
            })  # fmt: skip
        return table

    def foundation_result(self, i: int) -> FoundationResult:
        """The view of plate strip ``i`` (the one a scene's strip has): settlement, contact, strip forces, RC
        design. A RigidStrip has none: :class:`NotInThisScene` naming it."""
        st = self.built.strips[i]
        if st.get("rigid"):
            raise NotInThisScene(
                f"strip {i} is a RigidStrip: it has no plate or interface (read rigid_pressure({i}))"
            )
        part = self.built.site.strips[i]
        return FoundationResult(
            self, self.built.model, part.foundation, st["plate"], st["interface"], st["plate_nodes"],
            self.phases,
        )  # fmt: skip

    def strip_forces(self, i: int, k: int = -1) -> dict[str, np.ndarray]:
        """Stress resultants of the plate strip ``i`` at step ``k`` (:meth:`FoundationResult.strip_forces`):
        ``x_ax`` (n_el, n_ax) [m], ``N`` [N/m], ``M`` [N m/m] (sagging positive), ``x_sh``, ``Q`` [N/m]."""
        return self.foundation_result(i).strip_forces(k)

    def contact(self, i: int, k: int = -1) -> dict[str, np.ndarray]:
        """The interface under plate strip ``i`` at step ``k``: ``x`` [m], ``sig_n`` [Pa] (< 0 compression),
        ``tau`` [Pa] and ``zone`` ("stick", "slip", "open") at each integration point."""
        return self.foundation_result(i).contact(k)

    def contact_resultant(self, i: int, k: int = -1) -> dict[str, float]:
        """Resultant of the contact tractions under plate strip ``i`` at step ``k``: ``N``, ``H`` [N/m], ``M``
        [N m/m] about x = 0, ``eccentricity`` [m] (:meth:`FoundationResult.contact_resultant`)."""
        return self.foundation_result(i).contact_resultant(k)

    def design_summary(self, i: int, **options) -> dict | None:
        """EN 1992 design of plate strip ``i`` (crack width, M_Ed/M_Rd, V_Ed/V_Rd,c; None without concrete):
        :func:`ssi.scene.design.design_summary`."""
        return self.foundation_result(i).design_summary(**options)


def gibson_settlement(q: float, m: float) -> float:
    """Settlement [m] under a uniform strip pressure ``q`` [Pa] on Gibson's incompressible half-space whose
    shear modulus grows from zero at the surface as G = m z (``m`` [Pa/m]): w = q / (2 m), uniform under the
    load and zero outside it (Gibson 1967, Geotechnique 17(1), 58-67; the 'Gibson soil' behaves as a Winkler
    foundation of modulus 2m)."""
    return float(q) / (2.0 * float(m))


def pushed_nodes(st: dict) -> np.ndarray:
    """Model ids of the nodes a Push moves of the built strip ``st``: a plate's nodes; a RigidStrip's base
    nodes and its side contact's rigid body node (if any)."""
    if not st.get("rigid"):
        return st["plate_nodes"]
    body = [] if st.get("body") is None else [st["body"]]
    return np.concatenate([st["soil_nodes"], np.array(body, np.int64)])
