"""What is read off a solved site (``SiteResult``): strip settlements, tilt and differential settlement, the
ground's settlement, the soil stress, a rigid strip's pressure; and Gibson's settlement to check it by."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # for annotations only: the built site imports this module
    from .site_built import BuiltSite

__all__ = ["SiteResult", "gibson_settlement"]


@dataclass
class SiteResult:
    """The solution of a :class:`BuiltSite`: ``result`` the solver's :class:`~ssi.core.solution.Result`."""

    built: BuiltSite
    result: object

    @property
    def u(self) -> list:
        return self.result.u

    def rigid_pressure(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """(settlement [m], mean pressure [Pa]) histories of the RigidStrip ``i``: the pressure is the
        vertical support reaction of its base nodes over its width."""
        st, res = self.built.strips[i], self.result
        w = res.displacement(st["soil_nodes"][:1], "w")[:, 0]
        return -w, -res.support_reaction(st["soil_nodes"], "w") / st["width"]

    def strip_settlement(self, i: int, k: int = -1) -> tuple[np.ndarray, np.ndarray]:
        """(x [m], settlement [m], positive down) of the plate nodes of strip ``i`` at step ``k``."""
        ids = self.built.strips[i]["plate_nodes"]
        model = self.built.model
        return model.coords[ids, 0], -self.u[k][model.dof(ids, "w")]

    def strip_summary(self, i: int, k: int = -1) -> dict:
        """Strip ``i``: ``mean`` settlement [m] (average over its width), ``max`` [m], ``tilt`` [rad] (the
        slope of the least-squares line through its settlements; > 0: the right end settles more)."""
        x, w = self.strip_settlement(i, k)
        slope = np.polyfit(x, w, 1)[0] if len(x) > 1 else 0.0
        mean = float(np.sum(0.5 * (w[1:] + w[:-1]) * np.diff(x)) / (x[-1] - x[0]))
        return {"mean": mean, "max": float(w.max()), "tilt": float(slope)}

    def differential_settlement(self, i: int, j: int, k: int = -1) -> float:
        """Mean settlement of strip ``i`` minus that of strip ``j`` [m]."""
        return self.strip_summary(i, k)["mean"] - self.strip_summary(j, k)["mean"]

    def ground_settlement(self, x0: float | None = None, x1: float | None = None, k: int = -1):
        """(x [m], settlement [m], positive down) of the ground nodes between x0 and x1 (default: all)."""
        site = self.built.site
        ids = self.built.ground_nodes(site.x_left if x0 is None else x0, site.x_right if x1 is None else x1)
        return self.built.mesh.xy[ids, 0], -self.u[k][self.built.model.dof(ids, "w")]

    def soil_stress(self, k: int = -1) -> np.ndarray:
        """(n_el, n_ip, 4) effective stress [sxx, szz, txz, syy] [Pa] at step ``k``."""
        soil = self.built.soil
        return soil.stress(self.result.states[k][self.built.model.groups.index(soil)])


def gibson_settlement(q: float, m: float) -> float:
    """Settlement [m] under a uniform strip pressure ``q`` [Pa] on Gibson's incompressible half-space whose
    shear modulus grows from zero at the surface as G = m z (``m`` [Pa/m]): w = q / (2 m), uniform under the
    load and zero outside it (Gibson 1967, Geotechnique 17(1), 58-67; the 'Gibson soil' behaves as a Winkler
    foundation of modulus 2m)."""
    return float(q) / (2.0 * float(m))
