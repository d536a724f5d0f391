"""Six-node zero-thickness interface element (paper §6.1, eqs. 6.1-6.6; integration §9.1, §10).

An element joins three upper nodes to three lower (soil) nodes along a quadratic line. The upper nodes are
either **plate-strip nodes** (DOFs u, w, alpha at the plate's mid-surface) or **solid nodes** (u, w):

* plate, eq. (6.1a): the contact face is the plate's bottom face, u_g = u_b + e alpha_b, w_g = w_b, with the
  lever arm ``offset`` e from the plate nodes down to the bottom face (e = h/2 for nodes on the mid-surface;
  ``PlateStrip.bottom_offset`` in general), from the plate kinematics u(z) = u_b - z alpha at z = -e;
* solid, eq. (6.1b): u_g = u, w_g = w, the same as the lower side u_d = u_s, w_d = w_s.

The gap Delta u = u_g - u_d (eq. 6.5) is taken into the local frame of the contact line, built from the
lower nodes' geometry at every integration point: tangent t = (dx/dxi, dz/dxi)/|.|, normal n = (-t_z, t_x).
Order the lower nodes so that the upper body lies on the left when walking from node 0 to node 2 (for a
horizontal contact under a plate: left to right, then n points up and g_n > 0 opens the contact).
Tractions [tau, sig_n] follow from :func:`ssi.materials.interface_law.interface_update`, and

    f_el = sum_ip w_ip |J| B^T t,    k_el = sum_ip w_ip |J| B^T D B    (eq. 6.6),

with B (2, n_edof) the map from element DOFs to [g_t, g_n]. Two integration rules:

* ``rule="newton_cotes"`` (default, the paper's): Simpson on the three node pairs (weights 1/3, 4/3, 1/3 on
  [-1, 1]). Each integration point sees one node pair only, so the stiffness couples a node to its partner
  and nothing else ("diagonal" in node pairs, Hohberg).
* ``rule="gauss"``: ``n_gauss``-point Gauss--Legendre (3 = full integration of N^T D N). Every point sees all
  three pairs, which couples neighbouring pairs and lets stiff interfaces oscillate (Fig. 10).

Layout (see ``base``): coords (n_el, 6, 2) [upper 0-2, lower 3-5]; edofs (n_el, 15) for plate upper nodes
(3 x (u, w, alpha) then 3 x (u, w)) or (n_el, 12) for solid upper nodes; state (n_el, n_ip, N_VAR) with
[tau, sig_n, status, g_t, g_n, slip_t, slip_n, open_gap, broken] per point (status 0 stick, 1 slip, 2 open).
"""

import numpy as np
from numba import njit

from ..core.protocol import CONSISTENT, K0_MATRIX, ElementGroup
from ..core.quadrature import gauss_legendre, newton_cotes
from ..core.shapes import lagrange3, lagrange3_into
from ..materials.interface_law import (
    N_HIST,
    N_PARAMS,
    STATE_NAMES,
    STICK,
    davis_interface_row,
    interface_update,
)

__all__ = ["N_VAR", "V_GN", "V_GT", "V_SIG", "V_STATUS", "V_TAU", "Interface6", "add_interface"]

_lagrange3_py = getattr(
    lagrange3, "py_func", lagrange3
)  # plain Python version (also under NUMBA_DISABLE_JIT)

N_VAR = 2 + N_HIST
V_TAU, V_SIG, V_STATUS, V_GT, V_GN, V_SLIPT, V_SLIPN, V_OPEN, V_BROKEN = range(N_VAR)
# the state's slots by name (the order of the V_* indices)
_STATE_NAMES = ("tau", "sig_n", "status", "g_t", "g_n", "slip_t", "slip_n", "open_gap", "broken")
INTERFACE_STATE_FIELDS = {name: i for i, name in enumerate(_STATE_NAMES)}


@njit(cache=True)
def _b_matrix(xl, zl, hoff, n_up_dof, xi, B, n, dn):
    """Fill B (2, n_edof) at ``xi``; return |dx/dxi| (the line Jacobian). xl, zl: lower-node coordinates;
    n, dn (3,): scratch for the shape functions and their derivatives."""
    lagrange3_into(xi, n, dn)
    dx = 0.0
    dz = 0.0
    for a in range(3):
        dx += dn[a] * xl[a]
        dz += dn[a] * zl[a]
    jac = np.sqrt(dx * dx + dz * dz)
    tx = dx / jac
    tz = dz / jac
    nx = -tz
    nz = tx
    for j in range(B.shape[1]):
        B[0, j] = 0.0
        B[1, j] = 0.0
    step = n_up_dof // 3
    for a in range(3):
        # upper node a: +N_a (u + hoff alpha, w); eq. (6.3)
        k = a * step
        B[0, k] = n[a] * tx
        B[1, k] = n[a] * nx
        B[0, k + 1] = n[a] * tz
        B[1, k + 1] = n[a] * nz
        if step == 3:
            B[0, k + 2] = n[a] * hoff * tx
            B[1, k + 2] = n[a] * hoff * nx
        # lower node a: -N_a (u, w); eq. (6.4)
        k = n_up_dof + 2 * a
        B[0, k] = -n[a] * tx
        B[1, k] = -n[a] * nx
        B[0, k + 1] = -n[a] * tz
        B[1, k + 1] = -n[a] * nz
    return jac


def _evaluate(coords, hoff, n_up_dof, xis, wts, params, du_el, state_old, tangent, f_el, k_el, state_new):
    """The compiled loop with its scratch. Plain Python (as the soil's kernel): a compiled wrapper
    re-optimises and re-emits the whole loop with the law it inlines on a fresh install (~20 % of the
    interface's compilation) for ten allocations that cost microseconds here; the loop runs as fast (20 000
    elements: 212-268 ns per point, 223-310 with the compiled wrapper). Not so the plate strip: inlined in
    its compiled wrapper, its loop ran at 53 ns per layer point, 80 ns alone (bench_kernels.py's strip)."""
    n_edof = du_el.shape[1]
    _points(
        coords, hoff, n_up_dof, xis, wts, params, du_el, state_old, tangent, f_el, k_el, state_new,
        np.empty((2, n_edof)),  # B
        np.empty(3),  # xl
        np.empty(3),  # zl
        np.empty(2),  # dgap
        np.empty(2),  # t_new
        np.empty(N_HIST),  # h_new
        np.empty((2, 2)),  # D
        np.empty((2, n_edof)),  # DB
        np.empty(3),  # n
        np.empty(3),  # dn
    )  # fmt: skip


# The loop over elements and points, compiled without numba's reference counting (the scratch comes from
# _evaluate; nothing below allocates): the law update's array arguments and views cost an atomic increment
# and decrement each per point. Numba compiles the functions a loop calls with the loop's own setting, so
# nothing that allocates may be reached from here.
@njit(cache=True, _nrt=False)
def _points(
    coords, hoff, n_up_dof, xis, wts, params, du_el, state_old, tangent, f_el, k_el, state_new,
    B, xl, zl, dgap, t_new, h_new, D, DB, n, dn,
):  # fmt: skip
    n_el, n_edof = du_el.shape
    n_ip = xis.shape[0]
    for e in range(n_el):
        for a in range(3):
            xl[a] = coords[e, 3 + a, 0]
            zl[a] = coords[e, 3 + a, 1]
        for i in range(n_edof):
            f_el[e, i] = 0.0
            for j in range(n_edof):
                k_el[e, i, j] = 0.0
        for q in range(n_ip):
            jac = _b_matrix(xl, zl, hoff[e], n_up_dof, xis[q], B, n, dn)
            dv = wts[q] * jac
            for r in range(2):
                s = 0.0
                for j in range(n_edof):
                    s += B[r, j] * du_el[e, j]
                dgap[r] = s
            interface_update(
                params[e], dgap, state_old[e, q, 0:2], state_old[e, q, 2:], t_new, h_new, D, tangent
            )
            state_new[e, q, 0] = t_new[0]
            state_new[e, q, 1] = t_new[1]
            for k in range(N_HIST):
                state_new[e, q, 2 + k] = h_new[k]
            for j in range(n_edof):
                DB[0, j] = D[0, 0] * B[0, j] + D[0, 1] * B[1, j]
                DB[1, j] = D[1, 0] * B[0, j] + D[1, 1] * B[1, j]
            for i in range(n_edof):
                b0 = B[0, i] * dv
                b1 = B[1, i] * dv
                if b0 == 0.0 and b1 == 0.0:
                    continue
                f_el[e, i] += b0 * t_new[0] + b1 * t_new[1]
                for j in range(n_edof):
                    k_el[e, i, j] += b0 * DB[0, j] + b1 * DB[1, j]


class Interface6(ElementGroup):
    """A group of 6-node zero-thickness interface elements (see the module docstring).

    Parameters
    ----------
    coords : array (n_el, 6, 2)
        Node coordinates: upper nodes 0-2 (plate mid-surface nodes, or solid nodes), lower nodes 3-5.
    edofs : int array (n_el, 15) or (n_el, 12)
        Global DOFs, upper nodes first; 15 columns = plate upper nodes, 12 = solid upper nodes.
    params : array (N_PARAMS,) or (n_el, N_PARAMS)
        Interface law parameters from :func:`ssi.materials.interface_law.interface_params`.
    offset : float or array (n_el,), optional
        Plate variant only: lever arm e [m] from the plate nodes down to the bottom face, u_g = u_b + e
        alpha_b (h/2 for mid-surface nodes; use ``PlateStrip.bottom_offset``). The plate nodes must lie e
        straight above their lower nodes.
    rule : {"newton_cotes", "gauss"}
        Integration along the element (default the paper's Newton--Cotes / Simpson on the node pairs).
    n_gauss : int
        Number of Gauss points for ``rule="gauss"`` (1..5; 3 integrates N^T D N exactly).
    name : str
        Group name used in result files.
    initial_traction : array broadcastable to (n_el, n_ip, 2), optional
        Tractions [tau, sig_n] of the committed state before the first step (e.g. the contact pressure of a
        geostatic or pre-loaded state that the loads already equilibrate; sig_n < 0 compression). Default 0.
    viscosity : float
        Duvaut--Lions regularisation tau = dt / eta per increment (dimensionless; 0: rate independent).
    """

    viscous = True
    history_fields = INTERFACE_STATE_FIELDS
    point_code_names = tuple(STATE_NAMES[k] for k in sorted(STATE_NAMES))

    def __init__(
        self,
        coords,
        edofs,
        params,
        offset=None,
        rule="newton_cotes",
        n_gauss=3,
        name="interface",
        initial_traction=None,
        viscosity=0.0,
    ):
        coords = np.ascontiguousarray(coords, dtype=np.float64)
        edofs = np.ascontiguousarray(edofs, dtype=np.int64)
        if coords.ndim != 3 or coords.shape[1:] != (6, 2):
            raise ValueError(f"coords must have shape (n_el, 6, 2), got {coords.shape}")
        n_el = coords.shape[0]
        if edofs.ndim != 2 or edofs.shape[0] != n_el or edofs.shape[1] not in (12, 15):
            raise ValueError(
                f"edofs must have shape (n_el, 15) (plate upper nodes) or (n_el, 12) "
                f"(solid upper nodes) with n_el = {n_el}, got {edofs.shape}"
            )
        self.upper = "plate" if edofs.shape[1] == 15 else "solid"
        n_up_dof = 9 if self.upper == "plate" else 6
        params = np.asarray(params, dtype=np.float64)
        if params.shape == (N_PARAMS,):
            params = np.tile(params, (n_el, 1))
        if params.shape != (n_el, N_PARAMS):
            raise ValueError(
                f"params must have shape ({N_PARAMS},) or ({n_el}, {N_PARAMS}); "
                "build it with interface_params()"
            )
        lower = coords[:, 3:, :]
        chord = np.hypot(*(lower[:, 2] - lower[:, 0]).T)
        if np.any(chord <= 0.0):
            raise ValueError("coords: lower nodes 3 and 5 of an element coincide (zero-length element)")
        mid = 0.5 * (lower[:, 0] + lower[:, 2])
        if np.any(np.hypot(*(lower[:, 1] - mid).T) > 0.25 * chord):
            raise ValueError(
                "coords: the middle lower node must lie near the middle of the element "
                "(within a quarter of its length)"
            )
        if self.upper == "plate":
            if offset is None:
                raise ValueError(
                    "offset (plate nodes to bottom face, >= 0 [m]; h/2 for mid-surface nodes) is "
                    "required when the upper nodes are plate nodes"
                )
            e_off = np.broadcast_to(np.asarray(offset, dtype=np.float64), (n_el,)).copy()
            if np.any(~(e_off >= 0.0)):
                raise ValueError("offset must be >= 0 [m]")
            # the plate strip runs along x; its nodes sit e above the contact face
            off = coords[:, :3, :] - lower
            tol = 1e-6 * chord[:, None]
            if np.any(np.abs(off[:, :, 0]) > tol) or np.any(np.abs(off[:, :, 1] - e_off[:, None]) > tol):
                raise ValueError(
                    "coords: plate nodes must lie offset (e.g. h/2) straight above their lower "
                    "(soil) nodes (plate reference surface over its bottom face, eq. 6.1a)"
                )
            hoff = e_off
        else:
            if offset is not None:
                raise ValueError("offset applies only to plate upper nodes (edofs with 15 columns)")
            if np.any(np.abs(coords[:, :3, :] - lower) > 1e-6 * chord[:, None, None]):
                raise ValueError(
                    "coords: solid upper nodes must coincide with their lower nodes "
                    "(zero-thickness interface)"
                )
            hoff = np.zeros(n_el)
        if rule == "newton_cotes":
            xis, wts = newton_cotes(3)
        elif rule == "gauss":
            if not 1 <= int(n_gauss) <= 5:
                raise ValueError(f"n_gauss must be in 1..5, got {n_gauss}")
            xis, wts = gauss_legendre(int(n_gauss))
        else:
            raise ValueError(f"rule must be 'newton_cotes' or 'gauss', got {rule!r}")
        self.name = name
        self.rule = rule
        self.coords = coords
        self.edofs = edofs
        self.params = np.ascontiguousarray(params)
        self.hoff = np.ascontiguousarray(hoff)
        self.n_up_dof = n_up_dof
        self.xi = np.ascontiguousarray(xis)
        self.w = np.ascontiguousarray(wts)
        self.n_el = n_el
        self.n_ip = len(xis)
        if not (np.isfinite(viscosity) and viscosity >= 0.0):
            raise ValueError(
                f"viscosity must be finite and >= 0 (tau = dt/eta per increment), got {viscosity}"
            )
        self.viscosity = float(viscosity)
        self.initial_traction = None
        if initial_traction is not None:
            try:
                t0 = np.broadcast_to(np.asarray(initial_traction, np.float64), (n_el, self.n_ip, 2)).copy()
            except ValueError as err:
                raise ValueError(
                    f"initial_traction must broadcast to (n_el, n_ip, 2) = ({n_el}, {self.n_ip}, 2)"
                ) from err
            if not np.all(np.isfinite(t0)):
                raise ValueError("initial_traction must be finite")
            self.initial_traction = t0

    # ---- protocol -------------------------------------------------------------------------------------
    def initial_state(self) -> np.ndarray:
        state = np.zeros((self.n_el, self.n_ip, N_VAR))
        if self.initial_traction is not None:
            state[..., V_TAU : V_SIG + 1] = self.initial_traction
        return state

    def evaluate(self, u_el, du_el, state_old, tangent):
        if tangent not in (K0_MATRIX, CONSISTENT):
            raise ValueError(f"tangent must be K0_MATRIX (0) or CONSISTENT (1), got {tangent}")
        du_el = np.ascontiguousarray(du_el, dtype=np.float64)
        if du_el.shape != self.edofs.shape:
            raise ValueError(f"du_el must have shape {self.edofs.shape}, got {du_el.shape}")
        f_el = np.empty(self.edofs.shape)
        k_el = np.empty((self.n_el, self.edofs.shape[1], self.edofs.shape[1]))
        state_new = np.empty_like(state_old)
        state_old = np.ascontiguousarray(state_old)
        self._kernel(self.params, du_el, state_old, tangent, f_el, k_el, state_new)
        if self.viscosity > 0.0:
            self._blend_with_trial(du_el, state_old, tangent, f_el, k_el, state_new)
        return f_el, k_el, state_new

    def _kernel(self, params, du_el, state_old, tangent, f_el, k_el, state_new):
        _evaluate(
            self.coords,
            self.hoff,
            self.n_up_dof,
            self.xi,
            self.w,
            params,
            du_el,
            state_old,
            int(tangent),
            f_el,
            k_el,
            state_new,
        )

    def _blend_with_trial(self, du_el, state_old, tangent, f_el, k_el, state_new):
        """Duvaut--Lions, as for the soil (``SoilQ8``): forces, tangent and tractions become
        (trial + tau inviscid) / (1 + tau), the trial being the elastic springs' response t_old + De dgap
        (no slip, no opening); the history (status, slips, opening) stays the inviscid law's. It regularises
        the non-associated friction of the contact the way the viscous soil regularises its flow."""
        elastic = self.params.copy()
        elastic[:, 2] = np.inf  # cohesion: the Coulomb condition is never met
        elastic[:, 5] = np.inf  # tensile strength: never opens
        closed = state_old.copy()
        closed[..., V_STATUS] = STICK
        closed[..., V_BROKEN] = 0.0
        f_tr, k_tr, st_tr = np.empty_like(f_el), np.empty_like(k_el), np.empty_like(state_new)
        self._kernel(elastic, du_el, closed, tangent, f_tr, k_tr, st_tr)
        tau = self.viscosity
        f_el[...] = (f_tr + tau * f_el) / (1.0 + tau)
        k_el[...] = (k_tr + tau * k_el) / (1.0 + tau)
        state_new[..., V_TAU : V_SIG + 1] = (
            st_tr[..., V_TAU : V_SIG + 1] + tau * state_new[..., V_TAU : V_SIG + 1]
        ) / (1.0 + tau)

    def elastic_stiffness(self) -> np.ndarray:
        z = np.zeros(self.edofs.shape)
        return self.evaluate(z, z, self.initial_state(), K0_MATRIX)[1]

    def body_force(self):
        return None

    def describe(self) -> dict:
        return {
            "type": "Interface6",
            "name": self.name,
            "n_el": self.n_el,
            "upper": self.upper,
            "rule": self.rule,
            "n_ip": self.n_ip,
            "params": "[kt, kn, c, tan_phi, tan_psi, sig_t]",
            "params_first": self.params[0].tolist(),
        }

    # ---- what the solver asks (ssi.core.protocol.ElementGroup) -------------------------------------------
    def associated_flow(self, tol: float = 0.0) -> bool:
        """True unless a row has |tan psi - tan phi| > ``tol`` (columns 4 and 3 of ``params``)."""
        return not np.any(np.abs(self.params[:, 4] - self.params[:, 3]) > tol)

    def symmetric_tangent(self) -> bool:
        """Associated Coulomb contact (tan psi = tan phi exactly) has a symmetric consistent tangent (a point
        that re-closes within a step excepted: its chained tangent is not, interface_law step 1)."""
        return self.associated_flow()

    def davis_params(self) -> np.ndarray:
        """(n_el, N_PARAMS) a new array of Davis' associated rows
        (:func:`ssi.materials.interface_law.davis_interface_row`)."""
        return np.ascontiguousarray(np.array([davis_interface_row(p) for p in self.params], np.float64))

    def stored_energy(self, u_el, du_el, state_old, state_new, work) -> float:
        """sum t_n+1 . K^-1 d_t w |J| with K = diag(kt, kn) of each element [J/m]."""
        t_new = self.tractions(state_new)
        dt = t_new - self.tractions(state_old)
        kt, kn = self.params[:, 0][:, None], self.params[:, 1][:, None]
        # kt = 0 (allowed: a contact without tangential stiffness) carries no shear traction: no shear term
        shear = np.divide(t_new[..., 0] * dt[..., 0], kt, out=np.zeros_like(dt[..., 0]), where=kt > 0.0)
        density = shear + t_new[..., 1] * dt[..., 1] / kn
        return float(np.sum(density * self.ip_weights()))

    def point_codes(self, state) -> np.ndarray:
        """(n_el, n_ip) 0 stick, 1 slip, 2 open (see :meth:`status`)."""
        return self.status(state)

    def integration_points(self) -> np.ndarray:
        """(n_el, n_ip, 2) coordinates (x, z) of the integration points (:meth:`ip_coords`)."""
        return self.ip_coords()

    # ---- reporting ------------------------------------------------------------------------------------
    def ip_coords(self) -> np.ndarray:
        """(n_el, n_ip, 2) coordinates (x, z) of the integration points on the contact line."""
        out = np.empty((self.n_el, self.n_ip, 2))
        for q, xi in enumerate(self.xi):
            n, _ = _lagrange3_py(float(xi))
            out[:, q, :] = np.einsum("a,eak->ek", n, self.coords[:, 3:, :])
        return out

    def ip_weights(self) -> np.ndarray:
        """(n_el, n_ip) integration weights times the line Jacobian (sum = contact length)."""
        out = np.empty((self.n_el, self.n_ip))
        for q, xi in enumerate(self.xi):
            _, dn = _lagrange3_py(float(xi))
            d = np.einsum("a,eak->ek", dn, self.coords[:, 3:, :])
            out[:, q] = self.w[q] * np.hypot(d[:, 0], d[:, 1])
        return out

    @staticmethod
    def tractions(state) -> np.ndarray:
        """(n_el, n_ip, 2) tractions [tau, sig_n] from a state array."""
        return state[..., V_TAU : V_SIG + 1]

    @staticmethod
    def status(state) -> np.ndarray:
        """(n_el, n_ip) int state codes: 0 stick, 1 slip, 2 open."""
        return np.rint(state[..., V_STATUS]).astype(np.int64)

    @staticmethod
    def status_counts(state) -> dict:
        """Number of integration points in each state, e.g. {'stick': 10, 'slip': 4, 'open': 0}."""
        codes = Interface6.status(state).ravel()
        return {name: int(np.count_nonzero(codes == k)) for k, name in STATE_NAMES.items()}


def add_interface(
    model,
    upper_conn,
    lower_conn,
    params,
    offset=None,
    rule="newton_cotes",
    n_gauss=3,
    name="interface",
    initial_traction=None,
):
    """Build an :class:`Interface6` group from node ids and add it to ``model``.

    ``upper_conn`` (n_el, 3): plate-strip nodes (3 DOFs; then ``offset`` is required, e.g. the plate group's
    ``bottom_offset``) or solid nodes (2 DOFs); ``lower_conn`` (n_el, 3): soil nodes, ordered so that the
    upper body lies on the left when walking from the first to the third node. Returns the group.
    """
    upper_conn = np.atleast_2d(np.asarray(upper_conn, np.int64))
    lower_conn = np.atleast_2d(np.asarray(lower_conn, np.int64))
    if upper_conn.shape != lower_conn.shape or upper_conn.shape[1:] != (3,):
        raise ValueError(
            f"upper_conn and lower_conn must both be (n_el, 3), got {upper_conn.shape} and {lower_conn.shape}"
        )
    conn = np.hstack([upper_conn, lower_conn])
    group = Interface6(
        model.coords[conn],
        model.element_dofs(conn),
        params,
        offset=offset,
        rule=rule,
        n_gauss=n_gauss,
        name=name,
        initial_traction=initial_traction,
    )
    model.add_group(group)
    return group
