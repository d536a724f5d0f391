"""A scene as the solver sees it: nodes with their DOFs, element groups, supports and loads.

Nodes carry 2 DOFs (soil: u, w) or 3 DOFs (plate strip: u, w, alpha); one numbering holds both kinds.
Node ``n``'s DOFs are ``dof_start[n] + (0, 1[, 2])``, in the order nodes were added, so a structured mesh
keeps its locality in the global matrix.

Only what the scene contains is instantiated: element groups are added one by one, and a scene without
nonlinear laws is solved by :meth:`Model.solve_linear` -- one factorisation, one solve.
"""

import time

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from .assembly import SparsePattern, gather_vector, scatter_vector
from .linsolve import Factorization, SingularMatrix
from .protocol import CONSISTENT, FORCES_ONLY, K0_MATRIX, SECANT_SOFTENING, ElementGroup
from .solution import Result
from .validate import check_array, check_real

COMPONENTS = {"u": 0, "w": 1, "alpha": 2}


def _component(comp):
    c = COMPONENTS.get(comp, comp)
    if c not in (0, 1, 2):
        raise ValueError(f"comp must be one of 'u', 'w', 'alpha' or 0, 1, 2; got {comp!r}")
    return c


def _free_rigid_motion(coords, start, nodes, dofs):
    """Description of a rigid motion of ``nodes`` that moves none of the constrained ``dofs``, or None."""
    centre = coords[nodes].mean(axis=0)
    size = float(np.ptp(coords[nodes], axis=0).max())
    point_like = size == 0.0  # nodes at one point: no rotation to hold (an alpha DOF is a DOF of its own)
    size = size or 1.0
    if dofs.size == 0:
        return "a translation in x (unsupported DOFs: every node's u and w)"
    dof_node = np.searchsorted(start, dofs, side="right") - 1
    comp = dofs - start[dof_node]
    x, z = ((coords[dof_node] - centre) / size).T
    m = np.zeros((len(dofs), 3))
    m[comp == 0, 0] = 1.0
    m[comp == 1, 1] = 1.0
    m[:, 2] = np.where(comp == 0, -z, np.where(comp == 1, x, 1.0 / size))
    if point_like:
        m = m[:, :2]
    # the full V^T (3 x 3) is needed only when there are fewer rows than modes; the full U (n x n) never is
    # (at 1e6 DOFs it made this check cost 0.9 s)
    _, sv, vt = np.linalg.svd(m, full_matrices=m.shape[0] < m.shape[1])
    sv = np.concatenate([sv, np.zeros(m.shape[1] - len(sv))])
    if sv[-1] > 1e-10 * sv[0]:
        return None
    a, b, c = np.append(vt[-1], 0.0)[:3]
    if abs(c) < 1e-9:
        if abs(b) < 1e-9:
            return "a translation in x (unsupported DOFs: every node's u)"
        if abs(a) < 1e-9:
            return "a translation in z (unsupported DOFs: every node's w)"
        return f"a translation along ({a:.3g}, {b:.3g}) (unsupported DOFs: u and w of every node)"
    px, pz = centre + size * np.array([-b / c, a / c])  # where a - c z = 0 and b + c x = 0
    return f"a rotation about the point ({px:.4g}, {pz:.4g}) (unsupported DOFs: u and w of every node off it)"


def _nodal_values(name, value, shape):
    """A finite scalar or array broadcast to ``shape``."""
    arr = check_array(name, value)
    try:
        return np.broadcast_to(arr, shape).copy()
    except ValueError as err:
        raise ValueError(f"{name} must be a scalar or have shape {shape}, got shape {arr.shape}") from err


class Model:
    """Nodes, element groups, supports and loads of one scene."""

    def __init__(self):
        self._coords: list[np.ndarray] = []
        self._ndof: list[np.ndarray] = []
        self.groups: list = []
        self._fixed: dict[int, float] = {}
        self._prescribed: dict[int, float] = {}
        self._loads: list[tuple[np.ndarray, np.ndarray]] = []
        self._dead_loads: list[tuple[np.ndarray, np.ndarray]] = []
        self.info: dict = {}

    # ---- nodes and DOFs -------------------------------------------------------------------------------
    def add_nodes(self, xy, ndof: int) -> np.ndarray:
        """Add nodes at ``xy`` (n, 2) with ``ndof`` DOFs each (2 or 3); return their ids."""
        xy = np.atleast_2d(np.asarray(xy, dtype=np.float64))
        if xy.ndim != 2 or xy.shape[1] != 2:
            raise ValueError(f"xy must have shape (n, 2), got {xy.shape}")
        if ndof not in (2, 3):
            raise ValueError(f"ndof must be 2 (soil) or 3 (plate strip), got {ndof}")
        start = self.n_nodes
        self._coords.append(xy)
        self._ndof.append(np.full(len(xy), ndof, np.int64))
        self._invalidate()
        return np.arange(start, start + len(xy))

    def _invalidate(self):
        self.__dict__.pop("_cache", None)

    @property
    def _arrays(self):
        if "_cache" not in self.__dict__:
            coords = np.concatenate(self._coords) if self._coords else np.zeros((0, 2))
            ndof = np.concatenate(self._ndof) if self._ndof else np.zeros(0, np.int64)
            start = np.concatenate([[0], np.cumsum(ndof)])
            self.__dict__["_cache"] = (coords, ndof, start)
        return self.__dict__["_cache"]

    @property
    def coords(self) -> np.ndarray:
        return self._arrays[0]

    @property
    def n_nodes(self) -> int:
        return sum(len(c) for c in self._coords)

    @property
    def n_dof(self) -> int:
        return int(self._arrays[2][-1])

    @property
    def node_ndof(self) -> np.ndarray:
        return self._arrays[1]

    def node_dofs(self, ids) -> np.ndarray:
        """Global DOFs (n, ndof) of nodes that all have the same number of DOFs."""
        ids = np.atleast_1d(np.asarray(ids, dtype=np.int64))
        _, ndof, start = self._arrays
        k = np.unique(ndof[ids])
        if k.size != 1:
            raise ValueError("node_dofs needs nodes of one kind (all 2-DOF or all 3-DOF)")
        return start[ids][:, None] + np.arange(k[0])

    def dof(self, ids, comp) -> np.ndarray:
        """Global DOF of component ``comp`` ('u', 'w', 'alpha' or 0, 1, 2) of nodes ``ids``."""
        ids = np.atleast_1d(np.asarray(ids, dtype=np.int64))
        c = _component(comp)
        _, ndof, start = self._arrays
        if np.any(ndof[ids] <= c):
            raise ValueError("comp 'alpha' exists only on plate-strip nodes (3 DOFs)")
        return start[ids] + c

    def element_dofs(self, conn) -> np.ndarray:
        """Element DOF table (n_el, n_edof): each node's DOFs in turn, in the order of ``conn``."""
        conn = np.atleast_2d(np.asarray(conn, dtype=np.int64))
        _, ndof, start = self._arrays
        per_col = [start[conn[:, j]][:, None] + np.arange(ndof[conn[0, j]]) for j in range(conn.shape[1])]
        for j in range(conn.shape[1]):
            if np.any(ndof[conn[:, j]] != ndof[conn[0, j]]):
                raise ValueError("each column of conn must hold nodes of one kind")
        return np.ascontiguousarray(np.hstack(per_col))

    # ---- groups, supports, loads ----------------------------------------------------------------------
    def add_group(self, group: ElementGroup) -> ElementGroup:
        """Add an element group (a subclass of :class:`~ssi.core.protocol.ElementGroup`, or an object that
        forwards its attributes, as a recorder wrapping one does) and return it."""
        if group.edofs.size and group.edofs.max() >= self.n_dof:
            raise ValueError(f"group {group.name!r} refers to DOFs that the model does not have")
        self.groups.append(group)
        return group

    def fix(self, ids, comp: str | int, value: float = 0.0) -> None:
        """Hold component ``comp`` of nodes ``ids`` at ``value`` (not scaled by the load factor)."""
        value = check_real("fix value", value, unit="m or rad")
        for d in self.dof(ids, comp):
            self._fixed[int(d)] = value
            self._prescribed.pop(int(d), None)

    def prescribe(self, ids, comp: str | int, value) -> None:
        """Prescribe displacement ``value`` of ``comp`` at ``ids``, scaled by the load factor
        (displacement control: the reaction there is the load measure)."""
        value = check_real("prescribed value", value, unit="m or rad")
        for d in self.dof(ids, comp):
            self._prescribed[int(d)] = value
            self._fixed.pop(int(d), None)

    # ---- constraints by DOF number, for a staged analysis ----------------------------------------------
    def _dof_numbers(self, name: str, dofs) -> list[int]:
        dofs = np.atleast_1d(np.asarray(dofs))
        if dofs.size and (dofs.dtype.kind not in "iu" or dofs.min() < 0 or dofs.max() >= self.n_dof):
            raise ValueError(f"{name}: DOF numbers must be integers in [0, {self.n_dof}), got {dofs!r}")
        return [int(d) for d in dofs.ravel()]

    def fix_dofs(self, dofs, values) -> None:
        """Hold each DOF of ``dofs`` (model DOF numbers) at its entry of ``values`` [m or rad], not scaled by
        the load factor; a DOF prescribed before stops being prescribed."""
        dofs = self._dof_numbers("fix_dofs dofs", dofs)
        for d, v in zip(dofs, np.broadcast_to(np.asarray(values, float), (len(dofs),))):
            self._fixed[d] = float(v)
            self._prescribed.pop(d, None)

    def prescribe_dofs(self, dofs, values) -> None:
        """Prescribe each DOF of ``dofs`` at its entry of ``values`` [m or rad] times the load factor; a DOF
        fixed before stops being fixed."""
        dofs = self._dof_numbers("prescribe_dofs dofs", dofs)
        for d, v in zip(dofs, np.broadcast_to(np.asarray(values, float), (len(dofs),))):
            self._prescribed[d] = float(v)
            self._fixed.pop(d, None)

    def hold_dofs(self, dofs, start, increment) -> None:
        """Constrain each DOF of ``dofs`` to u = start + lambda * increment [m or rad] (the phase engine's
        hold: the fixed value and the prescribed reference of one DOF, both set)."""
        dofs = self._dof_numbers("hold_dofs dofs", dofs)
        for d, a, b in zip(dofs, start, increment):
            self._fixed[d] = float(a)
            self._prescribed[d] = float(b)

    def fix_prescribed(self) -> None:
        """Turn every prescribed DOF into one fixed at zero (a phase sets its own prescribed motions)."""
        for d in list(self._prescribed):
            self._fixed[d] = 0.0
            self._prescribed.pop(d)

    def constraint_state(self) -> tuple[dict[int, float], dict[int, float]]:
        """A copy of the constraints, (fixed values, prescribed references) by DOF, for
        :meth:`restore_constraints`."""
        return dict(self._fixed), dict(self._prescribed)

    def restore_constraints(self, state: tuple[dict[int, float], dict[int, float]]) -> None:
        """Put back the constraints a :meth:`constraint_state` recorded."""
        fixed, prescribed = state
        self._fixed.clear()
        self._fixed.update(fixed)
        self._prescribed.clear()
        self._prescribed.update(prescribed)

    def add_load(self, ids, comp: str | int, value) -> None:
        """Nodal force (or moment for 'alpha') per node, scaled by the load factor."""
        d = self.dof(ids, comp)
        self._loads.append((d, _nodal_values("load value", value, d.shape)))

    def add_dead_load(self, ids, comp: str | int, value) -> None:
        """Nodal force applied in full at every step (e.g. weight already carried by the initial stress)."""
        d = self.dof(ids, comp)
        self._dead_loads.append((d, _nodal_values("dead load value", value, d.shape)))

    def add_element_load(self, edofs: np.ndarray, f_el: np.ndarray, dead: bool = False) -> None:
        """Equivalent nodal forces of distributed loads, given per element (n_el, n_edof)."""
        target = self._dead_loads if dead else self._loads
        edofs = np.asarray(edofs).ravel()
        f_el = check_array("element load f_el", f_el).ravel()
        if f_el.shape != edofs.shape:
            raise ValueError(
                f"element load f_el must have the shape of edofs {np.shape(edofs)}, got {f_el.shape}"
            )
        target.append((edofs, f_el))

    # ---- what the solver needs ------------------------------------------------------------------------
    def constrained(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(dofs, fixed values, prescribed reference values) of all constrained DOFs."""
        dofs = np.array(sorted(set(self._fixed) | set(self._prescribed)), np.int64)
        fixed = np.array([self._fixed.get(int(d), 0.0) for d in dofs])
        ref = np.array([self._prescribed.get(int(d), 0.0) for d in dofs])
        return dofs, fixed, ref

    def free_mask(self) -> np.ndarray:
        free = np.ones(self.n_dof, bool)
        free[self.constrained()[0]] = False
        return free

    def load_vectors(self) -> tuple[np.ndarray, np.ndarray]:
        """(reference load F_ref, dead load F_dead) as global vectors; body forces of groups are dead."""
        f_ref = np.zeros(self.n_dof)
        f_dead = np.zeros(self.n_dof)
        for d, v in self._loads:
            np.add.at(f_ref, d, v)
        for d, v in self._dead_loads:
            np.add.at(f_dead, d, v)
        for g in self.groups:
            body = g.body_force()
            if body is not None:
                if not np.all(np.isfinite(body)):
                    raise ValueError(
                        f"group {g.name!r}: its body force (unit weight or self weight) is not "
                        "finite; give finite unit weights [N/m^3]"
                    )
                scatter_vector(g.edofs, body, f_dead)
        return f_ref, f_dead

    def check(self) -> None:
        """Raise ValueError for a scene that cannot be solved."""
        if not self.groups:
            raise ValueError("the scene is empty: add at least one element group")
        if not (self._fixed or self._prescribed):
            raise ValueError("the scene has no supports: fix or prescribe at least the rigid-body modes")
        used = np.zeros(self.n_dof, bool)
        for g in self.groups:
            used[g.edofs.ravel()] = True
        unconnected = ~used & self.free_mask()
        if unconnected.any():
            raise ValueError(
                f"{np.count_nonzero(unconnected)} free DOFs belong to no element (unconnected "
                "nodes): connect them or fix them"
            )
        self._check_rigid_body_modes()

    def _check_rigid_body_modes(self):
        """Every connected part of the model (nodes joined by elements) must have its rigid-body motions held
        (the elements are taken to be plane ones, which resist no rigid motion of the plane).

        A motion of the plane combines translations in x and z and a rotation (u = -z theta, w = x theta,
        alpha = theta). On a part's constrained DOFs these three modes span the columns of M (n, 3); a
        combination that moves none of them (M of rank < 3) is a zero-energy motion: K0 is singular. Exact up
        to round-off, with no pivot threshold (an ill-conditioned but supported model, a very slender strip,
        passes). Mechanisms inside one connected part (a hinge of elements) are not detected here."""
        coords, ndof, start = self._arrays
        n_nodes = self.n_nodes
        el_nodes = [np.searchsorted(start, g.edofs, side="right") - 1 for g in self.groups if g.edofs.size]
        rows = np.concatenate([np.repeat(e[:, :1], e.shape[1] - 1, axis=1).ravel() for e in el_nodes])
        cols = np.concatenate([e[:, 1:].ravel() for e in el_nodes])
        graph = sp.coo_matrix((np.ones(rows.size), (rows, cols)), shape=(n_nodes, n_nodes))
        n_parts, node_part = connected_components(graph, directed=False)
        constrained = np.array(sorted(set(self._fixed) | set(self._prescribed)), np.int64)
        constrained_part = node_part[np.searchsorted(start, constrained, side="right") - 1]
        for part in range(n_parts):
            nodes_here = np.flatnonzero(node_part == part)
            dofs = constrained[constrained_part == part]
            free = _free_rigid_motion(coords, start, nodes_here, dofs)
            if free is not None:
                where = (
                    ""
                    if n_parts == 1
                    else (
                        f" of the part with nodes {nodes_here[:4].tolist()}"
                        f"{'...' if nodes_here.size > 4 else ''}"
                    )
                )
                raise ValueError(
                    f"supports: the stiffness matrix is singular: {free}{where} moves no fixed or "
                    "prescribed DOF; fix or prescribe a DOF that this motion moves"
                )

    def describe(self) -> dict:
        return {
            "n_nodes": self.n_nodes,
            "n_dof": self.n_dof,
            "groups": [g.describe() for g in self.groups],
            **self.info,
        }

    # ---- linear solution ------------------------------------------------------------------------------
    def solve_linear(self, backend: str = "auto") -> Result:
        """Solve the linear-elastic scene at load factor 1: one factorisation, one solve.

        Returns a :class:`ssi.core.solution.Result` (:meth:`~ssi.core.solution.Result.of_linear_solve`) with
        two rows, the initial state (load factor 0) and the solution (load factor 1), each with its internal
        force; ``reactions()`` gives the support reactions."""
        t_start = time.perf_counter()
        self.check()
        system = System(self)
        u0, states0 = system.start(0.0)
        f_ref, f_dead = self.load_vectors()
        if u0.any() or any(state.any() for state in states0):
            f_int0, _, _ = system.evaluate(u0, u0, states0, None)
        else:  # nothing displaced, nothing stressed: no internal force (spares a pass over every element)
            f_int0 = np.zeros(self.n_dof)
        u = system.apply_constraints(u0.copy(), 1.0)
        f_int = f_int0 if np.array_equal(u, u0) else system.evaluate(u, u, states0, None)[0]
        residual = (f_ref + f_dead - f_int)[system.free]
        try:
            u[system.free] += system.factorize_k0(backend).solve(residual)
        except SingularMatrix as err:
            raise ValueError(
                f"supports: the stiffness matrix is singular (a rigid-body mode is not held); "
                f"{system.describe_dofs(err.rows)}"
            ) from err
        f_int, _, states = system.evaluate(u, u, states0, None)
        return Result.of_linear_solve(
            self, [u0, u], [f_int0, f_int], [states0, states], f_ref, f_dead, time.perf_counter() - t_start
        )


class System:
    """Assembly machinery of a model: free-DOF pattern, gather/scatter, evaluation of all groups."""

    def start(self, load_factor: float = 0.0) -> tuple[np.ndarray, list]:
        """The state an analysis starts from: displacement zero except the constrained DOFs at
        ``load_factor``, and every group's initial (committed) state."""
        u = self.apply_constraints(np.zeros(self.model.n_dof), load_factor)
        return u, [g.initial_state() for g in self.model.groups]

    def factorize_k0(self, backend: str = "auto") -> "Factorization":
        """The one factorisation of the initial elastic stiffness K0 over the free DOFs (SPD)."""
        k0 = self.pattern.assemble_elastic(self.model.groups)  # no element matrices kept (343 MB at 1e6 DOFs)
        return Factorization(self.pattern.matrix(k0), symmetric=True, backend=backend, spd=True)

    def __init__(self, model: Model):
        self.model = model
        self.free = model.free_mask()
        self.free_dofs = np.flatnonzero(self.free)
        self.cons_dofs, self.cons_fixed, self.cons_ref = model.constrained()
        self.pattern = SparsePattern([g.edofs for g in model.groups], self.free)

    def describe_dofs(self, rows, limit=8) -> str:
        """Name the free DOFs at matrix rows ``rows`` (indices into the free DOFs): node, component, x, z."""
        dofs = self.free_dofs[np.asarray(rows, np.int64)[:limit]]
        _, _, start = self.model._arrays
        nodes = np.searchsorted(start, dofs, side="right") - 1
        names = [
            f"node {n} ({('u', 'w', 'alpha')[d - start[n]]}) at ({self.model.coords[n, 0]:.4g}, "
            f"{self.model.coords[n, 1]:.4g})"
            for n, d in zip(nodes, dofs)
        ]
        more = f" and {len(rows) - limit} more" if len(rows) > limit else ""
        return "unsupported DOFs: " + ", ".join(names) + more

    def apply_constraints(self, u, load_factor):
        """Write the fixed and prescribed values (at ``load_factor``) into ``u`` (in place)."""
        u[self.cons_dofs] = self.cons_fixed + load_factor * self.cons_ref
        return u

    def evaluate(self, u, du, states, tangent):
        """Global internal force and element matrices (None if ``tangent`` is None) of all groups."""
        f_int = np.zeros(self.model.n_dof)
        k_list, new_states = [], []
        for g, state in zip(self.model.groups, states):
            u_el = np.empty(g.edofs.shape)
            du_el = np.empty(g.edofs.shape)
            gather_vector(g.edofs, u, u_el)
            gather_vector(g.edofs, du, du_el)
            if tangent is None:
                flag = FORCES_ONLY if g.forces_only else K0_MATRIX
            elif tangent == SECANT_SOFTENING and not g.secant_softening:
                flag = CONSISTENT
            else:
                flag = tangent
            f_el, k_el, state_new = g.evaluate(u_el, du_el, state, flag)
            scatter_vector(g.edofs, f_el, f_int)
            k_list.append(k_el)
            new_states.append(state_new)
        return f_int, (None if tangent is None else k_list), new_states
