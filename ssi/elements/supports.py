"""Supports and loads of a hand-built soil-block model: the glue every chapter and test that builds a
:class:`ssi.core.model.Model` by hand used to write again.

* :func:`soil_group` -- the Q8 soil group of a mesh, added to the model (materials as ``(kind, params)``).
* :func:`fix_block` -- the soil block's standard supports: bottom fixed (u = w = 0), sides on vertical
  rollers (u = 0).
* :func:`surface_pressure` -- a uniform pressure on a stretch of a horizontal mesh line, as consistent
  nodal forces (:func:`ssi.core.mesh.surface_pressure_forces`, the L/6, 4L/6, L/6 rule of a quadratic edge).
* :func:`edge_forces` -- consistent nodal forces of any traction on curved quadratic edges (Gauss).
* :func:`plate_strip_model`, :func:`simply_supported_strip`, :func:`cantilever_strip` -- a plate strip
  alone on its supports (the element checks of chapter 02).
* :func:`spring_chain` -- nonlinear springs in series (the solver's closed-form checks, chapter 06); it lives
  here, not beside the spring element, because it builds a :class:`ssi.core.model.Model` (elements sit below
  the model and do not import it).

:class:`ssi.scene.Scene` builds its models with the same supports; these helpers are for the models that a
chapter or a test builds itself.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..core.mesh import SoilMesh, surface_pressure_forces
from ..core.model import Model
from ..core.quadrature import gauss_legendre
from ..core.shapes import lagrange3
from ..core.solution import Result
from ..materials.soil_laws import material_table
from .plate import PlateStrip, add_plate_strip
from .section import Section
from .soil_q8 import SoilQ8
from .spring import LINEAR, Spring

__all__ = [
    "cantilever_strip",
    "edge_forces",
    "fix_block",
    "plate_strip_model",
    "simply_supported_strip",
    "soil_group",
    "spring_chain",
    "surface_pressure",
]


def soil_group(
    model: Model,
    mesh: SoilMesh,
    materials: Sequence,
    ids: ArrayLike | None = None,
    el_mat: int | ArrayLike = 0,
    xy: ArrayLike | None = None,
    **options,
) -> SoilQ8:
    """Add the Q8 soil group of ``mesh`` to ``model`` and return it.

    ``materials``: ``[(kind, params), ...]`` (e.g. ``[(ELASTIC, elastic_params(E, nu))]``), stacked by
    :func:`ssi.materials.soil_laws.material_table`; ``el_mat``: each element's material index (an int for
    one material, or ``mesh.el_layer``); ``ids``: the model node ids of the mesh nodes (default: the mesh
    nodes are the model's first nodes, ``model.add_nodes(mesh.xy, 2)`` on an empty model); ``xy``: the
    nodal coordinates if not ``mesh.xy`` (a distorted copy, :func:`ssi.lab.verify.distorted_q8_mesh`).
    ``options`` go to :class:`ssi.elements.soil_q8.SoilQ8` (``n_gauss``, ``unit_weight``, ``initial_stress``,
    ...)."""
    kinds, params = material_table(materials)
    conn = mesh.conn if ids is None else np.asarray(ids)[mesh.conn]
    coords = (mesh.xy if xy is None else np.asarray(xy))[mesh.conn]
    return model.add_group(SoilQ8(coords, model.element_dofs(conn), el_mat, kinds, params, **options))


def fix_block(model: Model, mesh: SoilMesh, ids: ArrayLike | None = None, sides: bool = True) -> None:
    """The soil block's supports: bottom nodes fixed in u and w; with ``sides`` the left and right faces on
    vertical rollers (u = 0). ``ids``: the model node ids of the mesh nodes (default: the same numbers)."""
    node = (lambda n: n) if ids is None else (lambda n: np.asarray(ids)[n])
    model.fix(node(mesh.bottom), "u")
    model.fix(node(mesh.bottom), "w")
    if sides:
        model.fix(node(mesh.left), "u")
        model.fix(node(mesh.right), "u")


def surface_pressure(
    model: Model,
    mesh: SoilMesh,
    x0: float,
    x1: float,
    p: float,
    z: float = 0.0,
    ids: ArrayLike | None = None,
    dead: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """Load the mesh line z from x0 to x1 with a uniform pressure ``p`` [Pa] (positive down): the
    consistent nodal forces of :func:`ssi.core.mesh.surface_pressure_forces`, as a reference load (scaled by
    the load factor) or, with ``dead``, a dead load. ``ids``: the model node ids of the mesh nodes. Returns
    ``(model node ids, nodal force per unit pressure [m])``."""
    nodes, f = surface_pressure_forces(mesh, x0, x1, z)
    nodes = nodes if ids is None else np.asarray(ids)[nodes]
    if dead:
        model.add_dead_load(nodes, "w", -p * f)
    else:
        model.add_load(nodes, "w", -p * f)
    return nodes, f


def edge_forces(edge_xy: ArrayLike, traction: Callable, n_gauss: int = 4) -> np.ndarray:
    """Consistent nodal forces of a traction on quadratic (3-node) edges.

    Parameters
    ----------
    edge_xy : (n_edge, 3, 2) node coordinates of each edge (end, middle, end)
    traction : callable (x, z) -> (tx, tz), vectorised over arrays of points
    n_gauss : Gauss points along each edge (4 integrates a quadratic traction on a straight edge exactly)

    Returns
    -------
    (n_edge, 6) forces [fx0, fz0, fx1, fz1, fx2, fz2] per edge
    """
    edge_xy = np.asarray(edge_xy, dtype=np.float64)
    pts, wts = gauss_legendre(n_gauss)
    out = np.zeros((edge_xy.shape[0], 6))
    for xi, wq in zip(pts, wts):
        n, dn = getattr(lagrange3, "py_func", lagrange3)(float(xi))
        p = np.einsum("a,eak->ek", n, edge_xy)
        t = np.einsum("a,eak->ek", dn, edge_xy)
        jac = np.hypot(t[:, 0], t[:, 1])
        tx, tz = traction(p[:, 0], p[:, 1])
        tx = np.broadcast_to(tx, jac.shape)
        tz = np.broadcast_to(tz, jac.shape)
        for a in range(3):
            out[:, 2 * a] += wq * jac * n[a] * tx
            out[:, 2 * a + 1] += wq * jac * n[a] * tz
    return out


def plate_strip_model(
    n_el: int, span: float, section: Section, integration: str | tuple = "selective", kappa: float = 5.0 / 6.0
) -> tuple[Model, PlateStrip, np.ndarray]:
    """``(model, group, node ids)``: a new model holding one plate strip of ``n_el`` equal elements from
    x = 0 to ``span`` [m] (:func:`ssi.elements.plate.add_plate_strip`), no supports, no loads."""
    model = Model()
    group, ids, _ = add_plate_strip(
        model, np.linspace(0.0, span, n_el + 1), section, integration=integration, kappa=kappa
    )
    return model, group, ids


def simply_supported_strip(
    n_el: int,
    span: float,
    section: Section,
    load: tuple[str, float],
    integration: str | tuple = "selective",
    kappa: float = 5.0 / 6.0,
    backend: str = "auto",
) -> tuple[Model, PlateStrip, np.ndarray, Result]:
    """A strip pinned at x = 0 (u, w) and on a roller at x = ``span`` (w), solved linearly.

    ``load``: ``("uniform", q)`` [N/m per m, positive up] on every element (consistent nodal forces) or
    ``("point", P)`` [N/m, positive up] at the middle node. Returns ``(model, group, ids, Result)``."""
    model, group, ids = plate_strip_model(n_el, span, section, integration, kappa)
    model.fix(ids[0], "u")
    model.fix(ids[0], "w")
    model.fix(ids[-1], "w")
    kind, value = load
    if kind == "uniform":
        model.add_element_load(group.edofs, group.distributed_load(value))
    elif kind == "point":
        model.add_load(ids[len(ids) // 2], "w", value)
    else:
        raise ValueError(f"load must be ('uniform', q) or ('point', P), got {load!r}")
    return model, group, ids, model.solve_linear(backend=backend)


def cantilever_strip(
    n_el: int,
    span: float,
    section: Section,
    P: float,
    integration: str | tuple = "selective",
    backend: str = "auto",
) -> tuple[Model, PlateStrip, np.ndarray, Result]:
    """A strip clamped at x = 0 (u, w, alpha) with a tip load ``P`` [N/m, positive up] at x = ``span``,
    solved linearly. Returns ``(model, group, ids, Result)``."""
    model, group, ids = plate_strip_model(n_el, span, section, integration)
    for comp in ("u", "w", "alpha"):
        model.fix(ids[0], comp)
    model.add_load(ids[-1], "w", P)
    return model, group, ids, model.solve_linear(backend=backend)


def spring_chain(
    kinds: int | ArrayLike, params: ArrayLike, name: str = "spring"
) -> tuple[Model, Spring, np.ndarray]:
    """A model of springs in series along x: node 0 (fixed) -- spring 0 -- node 1 -- ... -- node n.

    Spring e acts between the u DOFs of nodes e and e + 1. Model nodes carry (u, w); every w is fixed, and the
    w DOFs are joined by stiff linear springs only so that every DOF belongs to an element (they carry no
    force). Load the chain with ``model.add_load(nodes[-1], "u", F)`` or ``model.prescribe(...)``.

    Returns ``(model, group, nodes)``; ``group`` is the :class:`Spring` group (first n springs: the chain).
    """
    kinds = np.atleast_1d(np.asarray(kinds, np.int64))
    n = kinds.size
    params = np.broadcast_to(np.asarray(params, np.float64), (n, 3))
    model = Model()
    nodes = model.add_nodes(np.column_stack([np.arange(n + 1.0), np.zeros(n + 1)]), 2)
    u = model.dof(nodes, "u")
    w = model.dof(nodes, "w")
    edofs = np.vstack([np.column_stack([u[:-1], u[1:]]), np.column_stack([w[:-1], w[1:]])])
    all_kinds = np.concatenate([kinds, np.full(n, LINEAR)])
    all_params = np.vstack([params, np.tile([params[:, 0].max(), 0.0, 0.0], (n, 1))])
    group = model.add_group(Spring(edofs, all_kinds, all_params, name=name))
    model.fix(nodes, "w")
    model.fix(nodes[:1], "u")
    return model, group, nodes
