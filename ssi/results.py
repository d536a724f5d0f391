"""Results to and from HDF5 (h5py).

Layout of a result file::

    /attrs                  model description (JSON in attribute ``model``), solver settings, ssi version
    /mesh/coords            (n_nodes, 2)
    /mesh/node_ndof         (n_nodes,)
    /mesh/<group>/edofs     (n_el, n_edof) for each element group
    /steps/load_factor      (n_steps + 1,)
    /steps/u                (n_steps + 1, n_dof)
    /steps/f_int            (n_steps + 1, n_dof)
    /steps/iterations       (n_steps + 1,)
    /steps/state/<group>    (n_kept, ...) committed integration-point states (stresses and history)

A file is never overwritten unless ``overwrite=True`` is passed.
"""

import json
from dataclasses import asdict, is_dataclass
from pathlib import Path

import h5py
import numpy as np

from . import __version__


def _group_names(model):
    names = []
    for g in model.groups:
        base, k = g.name, 1
        while (name := base if k == 1 else f"{base}_{k}") in names:
            k += 1
        names.append(name)
    return names


def write_result(path, result, settings=None, overwrite=False):
    """Write a :class:`ssi.solver.Result` (or a linear result) to ``path``."""
    path = Path(path)
    if path.exists() and not overwrite:
        raise FileExistsError(f"{path} exists; pass overwrite=True to replace it")
    path.parent.mkdir(parents=True, exist_ok=True)
    model = result.model
    names = _group_names(model)
    with h5py.File(path, "w") as h5:
        h5.attrs["ssi_version"] = __version__
        h5.attrs["model"] = json.dumps(model.describe(), default=_jsonable)
        if settings is not None:
            h5.attrs["settings"] = json.dumps(asdict(settings) if is_dataclass(settings) else settings)
        mesh = h5.create_group("mesh")
        mesh["coords"] = model.coords
        mesh["node_ndof"] = model.node_ndof
        for name, g in zip(names, model.groups):
            mesh.create_group(name)["edofs"] = g.edofs
        steps = h5.create_group("steps")
        if hasattr(result, "load_factor"):
            steps["load_factor"] = np.asarray(result.load_factor)
            steps["u"] = np.asarray(result.u)
            steps["f_int"] = np.asarray(result.f_int)
            steps["iterations"] = np.asarray(result.iterations)
            states = result.states
        else:  # linear result: one step at load factor 1
            steps["load_factor"] = np.array([1.0])
            steps["u"] = result.u[None]
            steps["f_int"] = (result.reactions)[None]
            steps["iterations"] = np.array([1])
            states = [result.states]
        st = steps.create_group("state")
        for i, name in enumerate(names):
            st[name] = np.stack([s[i] for s in states])
    return path


def read_result(path) -> dict:
    """Read a result file back into plain arrays: {'model': dict, 'coords', 'u', 'load_factor', 'state': {...}}."""
    with h5py.File(path, "r") as h5:
        out = {"model": json.loads(h5.attrs["model"]), "ssi_version": h5.attrs["ssi_version"]}
        if "settings" in h5.attrs:
            out["settings"] = json.loads(h5.attrs["settings"])
        out["coords"] = h5["mesh/coords"][...]
        out["node_ndof"] = h5["mesh/node_ndof"][...]
        out["edofs"] = {k: h5[f"mesh/{k}/edofs"][...] for k in h5["mesh"] if isinstance(h5[f"mesh/{k}"], h5py.Group)}
        for key in ("load_factor", "u", "f_int", "iterations"):
            out[key] = h5[f"steps/{key}"][...]
        out["state"] = {k: h5[f"steps/state/{k}"][...] for k in h5["steps/state"]}
    return out


def _jsonable(obj):
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    return str(obj)
