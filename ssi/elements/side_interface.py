"""Zero-thickness interface between a rigid body's face and the soil: the side contact of an embedded strip.

An embedded strip touches the backfill along the vertical walls of its trench as well as along its base. Each
side element joins three soil nodes on a wall to the **rigid body** of the structure: the face's points move
with one reference node (u_b, w_b, alpha_b) at (x_r, z_r), a plane section through the strip's end,

    u(x, z) = u_b - (z - z_r) alpha_b,    w(x, z) = w_b + (x - x_r) alpha_b

(alpha counter-clockwise positive, the plate's convention: u(z) = u_b - z alpha, ``ssi.elements.plate``).
The element is the soil--soil :class:`~ssi.elements.interface.Interface6` (solid upper nodes, zero
thickness, the same Coulomb law with separation, the same integration rules) whose three upper nodes are
those points of the face: with T (12, 9) the map from the element's DOFs [u_b, w_b, alpha_b, soil 3 x (u, w)]
to the six-node element's [face 3 x (u, w), soil 3 x (u, w)],

    du_6 = T du,    f = T^T f_6,    k = T^T k_6 T,

exact (the rigid-body constraint eliminated, no penalty). Why not new face nodes tied by constraints: the
model has no multi-point constraints, and a penalty tie would add a stiffness to choose; the transformation
adds no node and no parameter. Why rigid: the strip's end section stays plane in the plate theory, and
above the plate's top the face is the footing block's (a stem or the footing's own depth), taken as rigid.

Node order: as for Interface6, the upper body (the structure) lies on the left when walking from the first
to the third soil node: on a wall with the soil on its left (x < wall) walk down, on a wall with the soil on
its right walk up; the normal then points into the structure and g_n > 0 opens the contact.

Layout: coords (n_el, 6, 2) [face 0-2 = soil 3-5]; edofs (n_el, 9); state as Interface6's.
"""

import numpy as np

from .interface import Interface6

__all__ = ["SideInterface", "add_side_interface"]


class SideInterface(Interface6):
    """Interface elements between the soil nodes ``soil_xy`` (n_el, 3, 2) [m] and the face of a rigid body
    whose reference node sits at ``ref_xy`` (n_el, 2) or (2,) [m]. ``edofs`` (n_el, 9): the reference node's
    (u, w, alpha) then the three soil nodes' (u, w). ``params``, ``rule``, ``n_gauss``, ``name``,
    ``initial_traction`` ([tau, sig_n] [Pa], sig_n < 0 compression) as for :class:`Interface6`."""

    def __init__(
        self,
        soil_xy,
        edofs,
        ref_xy,
        params,
        rule="newton_cotes",
        n_gauss=3,
        name="side_interface",
        initial_traction=None,
    ):
        soil_xy = np.ascontiguousarray(soil_xy, np.float64)
        edofs = np.ascontiguousarray(edofs, np.int64)
        if soil_xy.ndim != 3 or soil_xy.shape[1:] != (3, 2):
            raise ValueError(f"soil_xy must have shape (n_el, 3, 2), got {soil_xy.shape}")
        n_el = soil_xy.shape[0]
        if edofs.shape != (n_el, 9):
            raise ValueError(f"edofs must have shape (n_el, 9) = ({n_el}, 9), got {edofs.shape}")
        ref = np.broadcast_to(np.asarray(ref_xy, np.float64), (n_el, 2))
        if not np.all(np.isfinite(ref)):
            raise ValueError("ref_xy must be finite [m]")
        coords = np.concatenate([soil_xy, soil_xy], axis=1)  # zero thickness: the face on the soil nodes
        super().__init__(
            coords, np.zeros((n_el, 12), np.int64), params, rule=rule, n_gauss=n_gauss, name=name,
            initial_traction=initial_traction,
        )  # fmt: skip
        self.edofs = edofs
        self.upper = "rigid body"
        self.ref_xy = np.ascontiguousarray(ref)
        t = np.zeros((n_el, 12, 9))
        for a in range(3):
            t[:, 2 * a, 0] = 1.0
            t[:, 2 * a, 2] = -(soil_xy[:, a, 1] - ref[:, 1])
            t[:, 2 * a + 1, 1] = 1.0
            t[:, 2 * a + 1, 2] = soil_xy[:, a, 0] - ref[:, 0]
        for k in range(6):
            t[:, 6 + k, 3 + k] = 1.0
        self.transform = t

    def evaluate(self, u_el, du_el, state_old, tangent):
        du_el = np.ascontiguousarray(du_el, np.float64)
        if du_el.shape != self.edofs.shape:
            raise ValueError(f"du_el must have shape {self.edofs.shape}, got {du_el.shape}")
        t = self.transform
        du6 = np.einsum("eij,ej->ei", t, du_el)
        f6 = np.empty((self.n_el, 12))
        k6 = np.empty((self.n_el, 12, 12))
        state_new = np.empty_like(state_old)
        state_old = np.ascontiguousarray(state_old)
        self._kernel(self.params, du6, state_old, int(tangent), f6, k6, state_new)
        if self.viscosity > 0.0:
            self._blend_with_trial(du6, state_old, tangent, f6, k6, state_new)
        f_el = np.einsum("eji,ej->ei", t, f6)
        k_el = np.einsum("eji,ejk,ekl->eil", t, k6, t)
        return f_el, k_el, state_new

    def describe(self) -> dict:
        out = super().describe()
        out["type"] = "SideInterface"
        return out


def add_side_interface(model, body_node, soil_conn, params, rule="newton_cotes", name="side_interface",
                       initial_traction=None) -> SideInterface:  # fmt: skip
    """Build a :class:`SideInterface` between the rigid body of the model node ``body_node`` (3 DOFs: u, w,
    alpha) and the soil nodes ``soil_conn`` (n_el, 3) (ordered as the module docstring says), add it to
    ``model`` and return it."""
    soil_conn = np.atleast_2d(np.asarray(soil_conn, np.int64))
    if soil_conn.shape[1:] != (3,):
        raise ValueError(f"soil_conn must be (n_el, 3), got {soil_conn.shape}")
    body = int(body_node)
    body_dofs = [int(model.dof([body], c)[0]) for c in ("u", "w", "alpha")]
    edofs = np.hstack([np.tile(body_dofs, (len(soil_conn), 1)), model.element_dofs(soil_conn)])
    group = SideInterface(
        model.coords[soil_conn], edofs, model.coords[body], params, rule=rule, name=name,
        initial_traction=initial_traction,
    )  # fmt: skip
    model.add_group(group)
    return group
