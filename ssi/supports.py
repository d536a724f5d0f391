"""Supports and loads of a hand-built soil-block model: the glue every chapter and test that builds a
:class:`ssi.model.Model` by hand used to write again.

* :func:`soil_group` -- the Q8 soil group of a mesh, added to the model (materials as ``(kind, params)``).
* :func:`fix_block` -- the soil block's standard supports: bottom fixed (u = w = 0), sides on vertical
  rollers (u = 0).
* :func:`surface_pressure` -- a uniform pressure on a stretch of a horizontal mesh line, as consistent
  nodal forces (:func:`ssi.mesh.surface_pressure_forces`, the L/6, 4L/6, L/6 rule of a quadratic edge).
* :func:`edge_forces` -- consistent nodal forces of any traction on curved quadratic edges (Gauss).

:class:`ssi.scene.Scene` builds its models with the same supports; these helpers are for the models that a
chapter or a test builds itself.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from .elements.soil_q8 import SoilQ8
from .materials.soil_laws import material_table
from .mesh import SoilMesh, surface_pressure_forces
from .quadrature import gauss_legendre
from .shapes import lagrange3

__all__ = ["edge_forces", "fix_block", "soil_group", "surface_pressure"]


def soil_group(model, mesh: SoilMesh, materials: Sequence, ids=None, el_mat=0, xy=None, **options) -> SoilQ8:
    """Add the Q8 soil group of ``mesh`` to ``model`` and return it.

    ``materials``: ``[(kind, params), ...]`` (e.g. ``[(ELASTIC, elastic_params(E, nu))]``), stacked by
    :func:`ssi.materials.soil_laws.material_table`; ``el_mat``: each element's material index (an int for
    one material, or ``mesh.el_layer``); ``ids``: the model node ids of the mesh nodes (default: the mesh
    nodes are the model's first nodes, ``model.add_nodes(mesh.xy, 2)`` on an empty model); ``xy``: the
    nodal coordinates if not ``mesh.xy`` (a distorted copy, :func:`ssi.verify.distorted_q8_mesh`).
    ``options`` go to :class:`ssi.elements.soil_q8.SoilQ8` (``n_gauss``, ``unit_weight``, ``initial_stress``,
    ...)."""
    kinds, params = material_table(materials)
    conn = mesh.conn if ids is None else np.asarray(ids)[mesh.conn]
    coords = (mesh.xy if xy is None else np.asarray(xy))[mesh.conn]
    return model.add_group(SoilQ8(coords, model.element_dofs(conn), el_mat, kinds, params, **options))


def fix_block(model, mesh: SoilMesh, ids=None, sides: bool = True) -> None:
    """The soil block's supports: bottom nodes fixed in u and w; with ``sides`` the left and right faces on
    vertical rollers (u = 0). ``ids``: the model node ids of the mesh nodes (default: the same numbers)."""
    node = (lambda n: n) if ids is None else (lambda n: np.asarray(ids)[n])
    model.fix(node(mesh.bottom), "u")
    model.fix(node(mesh.bottom), "w")
    if sides:
        model.fix(node(mesh.left), "u")
        model.fix(node(mesh.right), "u")


def surface_pressure(
    model, mesh: SoilMesh, x0: float, x1: float, p: float, z: float = 0.0, ids=None, dead: bool = False
):
    """Load the mesh line z from x0 to x1 with a uniform pressure ``p`` [Pa] (positive down): the
    consistent nodal forces of :func:`ssi.mesh.surface_pressure_forces`, as a reference load (scaled by the
    load factor) or, with ``dead``, a dead load. ``ids``: the model node ids of the mesh nodes. Returns
    ``(model node ids, nodal force per unit pressure [m])``."""
    nodes, f = surface_pressure_forces(mesh, x0, x1, z)
    nodes = nodes if ids is None else np.asarray(ids)[nodes]
    if dead:
        model.add_dead_load(nodes, "w", -p * f)
    else:
        model.add_load(nodes, "w", -p * f)
    return nodes, f


def edge_forces(edge_xy, traction: Callable, n_gauss: int = 4) -> np.ndarray:
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
