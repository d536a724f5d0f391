"""Q8 soil elements whose material may change from one integration point to the next: properties that vary
within an element (stiffness and strength growing with depth, ``ssi.scene.site_parts.DepthVarying``) sampled
at the Gauss points instead of once per element.

:class:`SoilQ8Points` is a :class:`~ssi.elements.soil_q8.SoilQ8` with a material row per point,
``point_mat`` (n_el, n_ip). It runs the same compiled kernel once per Gauss point q, each run a one-point
rule (the point's coordinates and weight) over all elements with that point's material index, and sums the
elements' forces and stiffness over the points: the same sums the kernel forms over its own point loop, so
a ``point_mat`` that repeats each element's row gives the element-wise group's result (to the order of the
additions). No kernel is changed or compiled anew, and a group whose material is constant per element
(``SoilQ8``) runs exactly as before. The elastic stiffness comes from the same kernel with the K0 flag
(the dedicated elastic kernel takes one E, nu per element).

Not supported here (refused by name): pore water (``k_water``) and phase configurations (excavation,
drainage switches), which the scenes that use them build with ``SoilQ8``.
"""

import numpy as np

from ..core.assembly import scatter_matrix
from ..core.protocol import FORCES_ONLY, K0_MATRIX, TANGENT_FLAGS
from .soil_q8 import SoilQ8, q8_body_force

__all__ = ["SoilQ8Points"]


class SoilQ8Points(SoilQ8):
    """Q8 soil group with one material index per integration point: ``point_mat`` (n_el, n_ip) into
    ``kinds``/``params``/``unit_weight`` (n_ip = n_gauss**2, the points in the order of
    :func:`ssi.core.quadrature.gauss_2d`, as :meth:`integration_points` lists them). Other parameters as
    :class:`SoilQ8` (``el_mat`` is each element's first point's row, kept for code that reads one row per
    element); ``k_water`` is not accepted."""

    name = "soil_q8"

    def __init__(self, coords, edofs, point_mat, kinds, params, n_gauss=2, unit_weight=None,
                 initial_stress=None, viscosity=0.0):  # fmt: skip
        point_mat = np.asarray(point_mat, np.int64)
        super().__init__(
            coords, edofs, point_mat[:, 0] if point_mat.ndim == 2 else point_mat, kinds, params,
            n_gauss=n_gauss, unit_weight=unit_weight, initial_stress=initial_stress, viscosity=viscosity,
        )  # fmt: skip
        n_ip = len(self.gw)
        if point_mat.shape != (self.n_el, n_ip):
            raise ValueError(
                f"point_mat must have shape (n_el, n_ip) = ({self.n_el}, {n_ip}), got {point_mat.shape}"
            )
        if point_mat.min() < 0 or point_mat.max() >= len(self.kinds):
            raise ValueError(f"point_mat must index kinds/params (0..{len(self.kinds) - 1})")
        # one contiguous column per point: the kernel's arrays keep the layout it was compiled for
        self.point_mat = [np.ascontiguousarray(point_mat[:, q]) for q in range(n_ip)]
        self._rules = [(np.ascontiguousarray(self.gp[q : q + 1]), np.ascontiguousarray(self.gw[q : q + 1]))
                       for q in range(n_ip)]  # fmt: skip

    def point_materials(self) -> np.ndarray:
        """(n_el, n_ip) the material row of each integration point (``point_mat``)."""
        return np.stack(self.point_mat, axis=1)

    def configure(self, active=None, k_water_el=None, water_reference=None):
        if active is None and k_water_el is None and water_reference is None:
            return
        raise ValueError("SoilQ8Points: phase configurations (excavation, drainage) are not supported")

    def evaluate(self, u_el, du_el, state_old, tangent):
        if tangent not in TANGENT_FLAGS:
            raise ValueError(
                f"tangent must be K0_MATRIX (0), CONSISTENT (1) or FORCES_ONLY (-1), got {tangent}"
            )
        du_el = np.ascontiguousarray(du_el, np.float64)
        f_el = np.zeros((self.n_el, 16))
        k_el = np.zeros((self.n_el, 16, 16)) if tangent != FORCES_ONLY else None
        state_new = np.empty_like(state_old)
        f_q = np.empty((self.n_el, 16))
        k_q = np.empty((self.n_el, 16, 16) if tangent != FORCES_ONLY else (1, 16, 16))
        failures = 0
        for q, (gp, gw) in enumerate(self._rules):
            old = np.ascontiguousarray(state_old[:, q : q + 1])
            new = np.empty_like(old)
            failures += self.kernel(
                self.coords, du_el, self.point_mat[q], self.kinds, self.params, gp, gw, old, new, f_q, k_q,
                tangent, self.viscosity,
            )  # fmt: skip
            state_new[:, q] = new[:, 0]
            f_el += f_q
            if k_el is not None:
                k_el += k_q
        if failures:
            raise FloatingPointError(
                f"soil_q8: {failures} integration points failed (distorted element "
                "or a stress update that did not converge)"
            )
        return f_el, k_el, state_new

    def elastic_stiffness(self):
        """K0 per element (n_el, 16, 16): the kernel's K0-flag matrix at the initial state (every law
        returns its elastic matrix for that flag)."""
        z = np.zeros((self.n_el, 16))
        return self.evaluate(z, z, self.initial_state(), K0_MATRIX)[1]

    def assemble_elastic_stiffness(self, smap, data):
        scatter_matrix(smap, self.elastic_stiffness(), data)
        return data

    def body_force(self):
        if self.unit_weight is None:
            return None
        f_el = np.zeros((self.n_el, 16))
        f_q = np.empty((self.n_el, 16))
        for q, (gp, gw) in enumerate(self._rules):
            q8_body_force(self.coords, self.point_mat[q], self.unit_weight, gp, gw, f_q)
            f_el += f_q
        return f_el
