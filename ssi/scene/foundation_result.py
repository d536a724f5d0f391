"""What is read off one plate strip of a solved scene or site (``FoundationResult``): its settlement and tilt,
the contact under it, its stress resultants, its layers (steel stress, cracks) and its RC design.

One implementation for both fronts: ``SceneResult.foundation_result()`` (a scene's one strip) and
``SiteResult.foundation_result(i)`` (strip ``i`` of a site) return this view, and their own accessors
(``contact``, ``strip_forces``, ``design_summary`` ...) delegate to it, so a site's strip gets the same
contact pressure, bending moments and EN 1992 design lines as a scene's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.model import Model
from ..elements.interface import V_SIG, V_TAU, Interface6
from ..elements.plate import PlateStrip
from ..materials.concrete import P_E0, P_FR
from ..materials.layer_laws import CONCRETE, STEEL
from .parts import Foundation

__all__ = ["FoundationResult", "NotInThisScene"]


class NotInThisScene(ValueError):
    """A result asked of a scene that has no such part (the contact stresses, strip forces, steel or cracks of
    a :class:`~ssi.scene.RigidFooting`, which has no plate and no interface): the message says what the scene
    has instead."""


@dataclass
class FoundationResult:
    """One plate strip on its contact interface in a solved model, at row ``k`` of every accessor (default:
    the last). ``rows``: the result view whose ``u``, ``states`` and ``load_factor`` it reads (a
    ``SceneResult`` or a ``SiteResult``); ``phases``: the phased solve's rows (None: one loading phase)."""

    rows: object
    model: Model
    foundation: Foundation
    plate: PlateStrip
    interface: Interface6
    plate_nodes: np.ndarray
    phases: list | None = None

    @property
    def load_factor(self) -> list:
        return self.rows.load_factor

    def _state(self, group, k: int):
        return self.rows.states[k][self.model.groups.index(group)]

    def settlement(self, k: int = -1) -> tuple[np.ndarray, np.ndarray]:
        """(x [m], settlement [m], positive down) of the strip's nodes at row ``k``."""
        ids = self.plate_nodes
        return self.model.coords[ids, 0], -self.rows.u[k][self.model.dof(ids, "w")]

    def settlement_summary(self, k: int = -1) -> dict[str, float]:
        """``mean`` settlement [m] (average over the strip's width), ``max`` [m] and ``tilt`` [rad] (the slope
        of the least-squares line through its settlements; > 0: the right end settles more)."""
        x, w = self.settlement(k)
        slope = np.polyfit(x, w, 1)[0] if len(x) > 1 else 0.0
        mean = float(np.sum(0.5 * (w[1:] + w[:-1]) * np.diff(x)) / (x[-1] - x[0]))
        return {"mean": mean, "max": float(w.max()), "tilt": float(slope)}

    def contact(self, k: int = -1) -> dict[str, np.ndarray]:
        """Interface points at row ``k``: ``x`` [m], ``sig_n`` [Pa] (< 0 compression), ``tau`` [Pa] and the
        ``zone`` ("stick", "slip", "open") at each integration point, (n_el, n_ip) each."""
        st = self._state(self.interface, k)
        zone = np.array(["stick", "slip", "open"])[Interface6.status(st)]
        return {"x": self.interface.ip_coords()[..., 0], "sig_n": st[..., V_SIG], "tau": st[..., V_TAU],
                "zone": zone}  # fmt: skip

    def contact_weights(self) -> np.ndarray:
        """(n_el, n_ip) integration weight of every contact point times the line Jacobian [m]: the contact
        length each point represents (their sum is the strip's width)."""
        return self.interface.ip_weights()

    def contact_resultant(self, k: int = -1) -> dict[str, float]:
        """Resultant of the contact tractions at row ``k`` per unit length: ``N`` [N/m] (compression positive,
        the vertical load the soil carries), ``H`` [N/m] (shear, +x), ``M`` [N m/m] (moment of the pressure
        about x = 0, counter-clockwise positive) and ``eccentricity`` M/N [m] of the pressure about x = 0."""
        c = self.contact(k)
        w = self.contact_weights()
        pressure = -c["sig_n"]
        N = float(np.sum(pressure * w))
        H = float(np.sum(c["tau"] * w))
        M = float(np.sum(pressure * w * c["x"]))
        return {"N": N, "H": H, "M": M, "eccentricity": M / N if N else float("nan")}

    def strip_forces(self, k: int = -1) -> dict[str, np.ndarray]:
        """Stress resultants per unit width at row ``k`` (``PlateStrip.resultants``): ``x_ax`` (n_el, n_ax)
        [m] with normal force ``N`` [N/m] and bending moment ``M`` [N m/m] (sagging positive: tension at the
        bottom), ``x_sh`` (n_el, n_sh) [m] with shear force ``Q`` [N/m]."""
        return self.plate.resultants(self.rows.u[k][self.plate.edofs], self._state(self.plate, k))

    def max_abs_moment(self, k: int = -1) -> tuple[float, float]:
        """(x [m], |M| [N m/m]) of the largest bending moment at row ``k``."""
        f = self.strip_forces(k)
        j = int(np.abs(f["M"]).argmax())
        return float(f["x_ax"].ravel()[j]), float(abs(f["M"].ravel()[j]))

    def plate_layers(self, k: int = -1) -> dict[str, np.ndarray]:
        """Layer strains and stresses at the axial sampling points at row ``k``: ``x`` (n_el, n_ip), ``z``
        (n_layer,) layer mid-depths above the reference surface, ``eps``/``sig`` (n_el, n_ip, n_layer),
        ``cracked`` (n_el, n_ip, n_layer) bool for concrete layers whose largest tensile strain passed the
        cracking strain fr/E0, and ``steel`` (n_layer,) bool."""
        plate = self.plate
        sec = plate.section
        u_el = self.rows.u[k][plate.edofs]
        state = self._state(plate, k)
        eps, _ = plate.layer_strains(u_el)
        sig, _ = plate.layer_stresses(u_el, state)
        cracked = np.zeros(eps.shape, bool)
        e_max = plate.history(state, "e_max")  # concrete's largest tensile strain
        for n in np.flatnonzero(sec.kind == CONCRETE):
            cracked[..., n] = e_max[..., n] > sec.params[n, P_FR] / sec.params[n, P_E0]
        axial = plate.ax.astype(bool)
        return {
            "x": plate.point_x()[:, axial],
            "z": sec.z_mid,
            "eps": eps[:, axial],
            "sig": sig[:, axial],
            "cracked": cracked[:, axial],
            "steel": sec.kind == STEEL,
        }

    def steel_stress(self, k: int = -1) -> dict[str, np.ndarray]:
        """Stress [Pa] in every steel layer at the axial points at row ``k``: ``x`` (n_el, n_ax) [m], ``z``
        (n_steel,) [m] layer heights above the reference surface, ``sig`` (n_el, n_ax, n_steel) [Pa],
        ``yielded`` (n_el, n_ax, n_steel) bool where |sig| reached the layer's fy."""
        from ..materials.steel import S_FY

        layers = self.plate_layers(k)
        steel = layers["steel"]
        sig = layers["sig"][..., steel]
        fy = self.plate.section.params[steel, S_FY] if steel.any() else np.zeros(0)
        yielded = np.abs(sig) >= fy * (1.0 - 1e-9)
        return {"x": layers["x"], "z": layers["z"][steel], "sig": sig, "yielded": yielded}

    def crack_map(self, k: int = -1) -> dict[str, np.ndarray]:
        """Cracked concrete layer points at row ``k``: ``x`` (n_el, n_ax) [m], ``z`` (n_layer,) [m],
        ``cracked`` (n_el, n_ax, n_layer) bool (see :meth:`plate_layers`)."""
        layers = self.plate_layers(k)
        return {"x": layers["x"], "z": layers["z"], "cracked": layers["cracked"]}

    def crack_width(self, k: int = -1) -> dict[str, np.ndarray]:
        """Crack width w_k [m] (EN 1992-1-1 7.3.4) at the axial points at row ``k``: see
        :func:`ssi.scene.design.crack_width`."""
        from .design import crack_width

        return crack_width(self, k)

    def design_summary(self, **options) -> dict | None:
        """Crack widths, M_Ed/M_Rd and V_Ed/V_Rd,c per phase and overall (None without a concrete layer): see
        :func:`ssi.scene.design.design_summary` (``options``: gamma_c, gamma_s, kt, fck)."""
        from .design import design_summary

        return design_summary(self, **options)
