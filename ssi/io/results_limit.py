"""A limit analysis's result (:class:`ssi.capacity.CapacityResult`, ``scene.limit_analysis(...)``) in
a result file and in ParaView.

    write_limit_result("strip_limit.h5", cap)          # ssi limit strip.toml writes it
    stored = read_limit_result("strip_limit.h5")        # StoredLimit: bounds, mesh, mechanism, stress
    export_limit_vtu(cap, "strip_limit.vtu")            # triangles: velocity, dissipation, stress

File layout (HDF5, the format of :mod:`ssi.io.results` with kind "limit")::

    /attrs  format, ssi_version, kind = 'limit', limit (JSON: CapacityResult.to_dict -- both brackets in
            lambda units, what lambda scales, triangles, cones, iterations, time, each run's history),
            summary (the printed lines), scene (JSON, scene_to_dict; when the problem came from a Scene)
    /associated, /davis (a non-associated scene's Davis run)   the run's last (finest) mesh and fields:
        attrs lb, ub, gap (the run's bracket), lb_certified, lb_reason
        mesh_xy (n_nodes, 2) [m], mesh_tri (n_el, 3) counter-clockwise, mesh_material (n_el,)
        velocity (n_nodes + n_edges, 2) [m/s at unit reference power]: the upper bound's mechanism, the
                 corner nodes then one midside node per edge of TriMesh.edges()
        footing_velocity  the rigid footings' translations, same scaling
        dissipation (n_el,) each triangle's plastic dissipation [lambda units: their sum less the dead
                 loads' power is the upper bound]
        stress (n_el, 3, 3) [Pa] the certified lower-bound stress field (sig_x, sig_z, tau; tension
                 positive) at each triangle's vertices (discontinuous between triangles)

A file is read back by :func:`read_limit_result` (:func:`ssi.io.results.read_result` names it for a limit
file); the mechanism plot (:func:`ssi.io.plot.limit_mechanism`) draws from either object.

ParaView (:func:`export_limit_vtu`): the upper-bound mesh as 6-node triangles (``triangle6``: corners, then
the midside nodes of edges 0-1, 1-2, 2-0 -- the velocity field's own nodes); point data ``velocity``
(u, w, 0); cell data ``dissipation``, ``dissipation_density`` (per m^2), ``sig_x``, ``sig_z``, ``tau``
(the lower bound's vertex stresses averaged over the triangle) and ``material_id``; units as field data
(``unit_<name>``, as :mod:`ssi.io.export`).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import meshio
import numpy as np

from .. import __version__
from .export import _add_units
from .results import FORMAT, OutputExistsError, atomic_path

__all__ = ["LIMIT_UNITS", "StoredLimit", "export_limit_vtu", "read_limit_result", "write_limit_result"]

LIMIT_UNITS = {
    "velocity": "m/s at unit reference power (the pattern, not the size, is the result)",
    "dissipation": "lambda units (the upper bound's share of each triangle)",
    "dissipation_density": "lambda units per m^2",
    "sig_x": "Pa",
    "sig_z": "Pa",
    "tau": "Pa",
    "material_id": "-",
}


@dataclass
class LimitRun:
    """One adaptive run as stored: its bracket and its last mesh's fields (layout in the module docstring)."""

    lb: float
    ub: float
    gap: float
    mesh: object  # ssi.limit.mesh.TriMesh (boundary edges not stored: empty)
    velocity: np.ndarray
    footing_velocity: np.ndarray
    dissipation: np.ndarray
    stress: np.ndarray
    lb_certified: bool = True
    lb_reason: str = ""


@dataclass
class StoredLimit:
    """A limit analysis read from its file: ``info`` (CapacityResult.to_dict), ``associated`` and ``davis``
    (:class:`LimitRun`; ``davis`` None for an associated scene) and the same accessors as a
    :class:`~ssi.capacity.CapacityResult` (``lb``, ``ub``, ``gap``, ``lb_davis``, ``ub_davis``,
    ``gap_davis``, ``mesh``, ``velocity``, ``dissipation``, ``stress``, ``to_dict``, ``summary``)."""

    info: dict
    associated: LimitRun
    davis: LimitRun | None = None
    summary_text: str = ""
    file_info: dict = field(default_factory=dict)

    lb = property(lambda self: self.associated.lb)
    ub = property(lambda self: self.associated.ub)
    gap = property(lambda self: self.associated.gap)
    lb_davis = property(lambda self: (self.davis or self.associated).lb)
    ub_davis = property(lambda self: (self.davis or self.associated).ub)
    gap_davis = property(lambda self: (self.davis or self.associated).gap)
    mesh = property(lambda self: self.associated.mesh)
    velocity = property(lambda self: self.associated.velocity)
    dissipation = property(lambda self: self.associated.dissipation)
    stress = property(lambda self: self.associated.stress)

    def to_dict(self) -> dict:
        return self.info

    def summary(self) -> str:
        return self.summary_text


def _runs(cap) -> dict:
    """{"associated": AdaptiveResult, "davis": AdaptiveResult} of a CapacityResult or a StoredLimit."""
    return {
        name: run for name, run in (("associated", cap.associated), ("davis", cap.davis)) if run is not None
    }


def _fields(run) -> dict:
    """The arrays and bracket of one run: an AdaptiveResult (its ``final`` Bracket) or a stored LimitRun."""
    if isinstance(run, LimitRun):
        return vars(run)
    final = run.final
    return {
        "lb": run.lb, "ub": run.ub, "gap": run.gap, "mesh": final.mesh,
        "velocity": final.upper.velocity, "footing_velocity": final.upper.footing_velocity,
        "dissipation": final.upper.dissipation, "stress": final.lower.stress,
        "lb_certified": bool(final.lower.certified), "lb_reason": str(final.lower.reason),
    }  # fmt: skip


def write_limit_result(path: str | os.PathLike, cap, overwrite: bool = False) -> Path:
    """Write a limit analysis (``CapacityResult``, or a ``StoredLimit`` read back) to the HDF5 file ``path``,
    atomically with the user's umask; an existing file is kept unless ``overwrite``. Returns the path."""
    from ..scene.scene_file import scene_to_dict

    path = Path(path)
    scene = getattr(getattr(cap, "problem", None), "scene", None)
    with atomic_path(path, overwrite) as tmp, h5py.File(tmp, "w") as h5:
        h5.attrs["format"] = FORMAT
        h5.attrs["ssi_version"] = __version__
        h5.attrs["kind"] = "limit"
        h5.attrs["limit"] = json.dumps(cap.to_dict(), default=_plain)
        h5.attrs["summary"] = cap.summary()
        if scene is not None:  # the input, a scene's or a site's plain form (one writer): "scene" or "site"
            h5.attrs[scene.kind] = json.dumps(scene_to_dict(scene), default=_plain)
        for name, run in _runs(cap).items():
            f = _fields(run)
            grp = h5.create_group(name)
            for key in ("lb", "ub", "gap"):
                grp.attrs[key] = float(f[key])
            grp.attrs["lb_certified"] = bool(f["lb_certified"])
            grp.attrs["lb_reason"] = str(f["lb_reason"])
            grp["mesh_xy"] = np.asarray(f["mesh"].xy, np.float64)
            grp["mesh_tri"] = np.asarray(f["mesh"].tri, np.int64)
            grp["mesh_material"] = np.asarray(f["mesh"].material, np.int64)
            for key in ("velocity", "footing_velocity", "dissipation", "stress"):
                grp[key] = np.asarray(f[key], np.float64)
    return path


def read_limit_result(path: str | os.PathLike) -> StoredLimit:
    """A limit-analysis file written by :func:`write_limit_result`, as a :class:`StoredLimit`."""
    from ..limit.mesh import TriMesh

    with h5py.File(path, "r") as h5:
        if h5.attrs.get("format") != FORMAT or h5.attrs.get("kind") != "limit":
            raise ValueError(
                f"{path}: not an ssi limit-analysis file (format {h5.attrs.get('format')!r}, kind "
                f"{h5.attrs.get('kind')!r}; expected {FORMAT!r}, 'limit')"
            )
        runs = {}
        for name in ("associated", "davis"):
            if name not in h5:
                continue
            g = h5[name]
            mesh = TriMesh(
                g["mesh_xy"][...], g["mesh_tri"][...], g["mesh_material"][...],
                np.zeros((0, 2), np.int64), np.zeros(0, np.int64),
            )  # fmt: skip
            runs[name] = LimitRun(
                float(g.attrs["lb"]), float(g.attrs["ub"]), float(g.attrs["gap"]), mesh,
                g["velocity"][...], g["footing_velocity"][...], g["dissipation"][...], g["stress"][...],
                bool(g.attrs["lb_certified"]), str(g.attrs["lb_reason"]),
            )  # fmt: skip
        file_info = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in h5.attrs.items()}
    return StoredLimit(
        json.loads(file_info["limit"]),
        runs["associated"],
        runs.get("davis"),
        str(file_info["summary"]),
        file_info,
    )


def limit_mesh_data(cap) -> meshio.Mesh:
    """The upper-bound mesh of the associated run as a meshio Mesh (6-node triangles) with its fields (see
    the module docstring)."""
    mesh = cap.mesh
    xy, tri = np.asarray(mesh.xy), np.asarray(mesh.tri)
    edges, el_edge = mesh.edges()
    n = len(xy)
    points = np.vstack([xy, 0.5 * (xy[edges[:, 0]] + xy[edges[:, 1]])])
    # triangle6: corners 0, 1, 2, then the midsides of 0-1, 1-2, 2-0 (side k of TriMesh.edges joins the
    # vertices other than k: 0-1 is side 2, 1-2 side 0, 2-0 side 1)
    conn = np.column_stack([tri, n + el_edge[:, 2], n + el_edge[:, 0], n + el_edge[:, 1]])
    vel = np.asarray(cap.velocity, np.float64)
    if vel.shape != (len(points), 2):
        raise ValueError(
            f"velocity has shape {vel.shape}, the mesh's nodes and midsides need {(len(points), 2)}"
        )
    stress = np.asarray(cap.stress, np.float64).mean(axis=1)
    dissipation = np.asarray(cap.dissipation, np.float64)
    cell = {
        "dissipation": dissipation,
        "dissipation_density": dissipation / mesh.areas(),
        "sig_x": stress[:, 0],
        "sig_z": stress[:, 1],
        "tau": stress[:, 2],
        "material_id": np.asarray(mesh.material, np.float64),
    }
    return meshio.Mesh(
        np.column_stack([points, np.zeros(len(points))]),
        [("triangle6", conn)],
        point_data={"velocity": np.column_stack([vel, np.zeros(len(vel))])},
        cell_data={k: [v] for k, v in cell.items()},
    )


def export_limit_vtu(cap, path: str | os.PathLike, overwrite: bool = False) -> Path:
    """The collapse mechanism and the stress field of a limit analysis (``CapacityResult`` or
    ``StoredLimit``) as one VTU (atomic; an existing file is kept unless ``overwrite``). Returns the path."""
    path = Path(path)
    if path.suffix != ".vtu":
        raise ValueError(f"path must end in .vtu, got {path.name!r}")
    if path.exists() and not overwrite:
        raise OutputExistsError(path)
    mesh = limit_mesh_data(cap)
    with atomic_path(path, overwrite) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
        _add_units(tmp, LIMIT_UNITS, time=None)
    return path


def _plain(v):
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, np.generic):
        return v.item()
    return str(v)
