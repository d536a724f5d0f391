"""Result files (HDF5, h5py): write any result, read it back as an object that answers and replots.

``write_result(path, result)`` takes a :class:`ssi.scene.SceneResult` (linear or not, complete or stopped), a
:class:`ssi.scene.SiteResult` or a :class:`ssi.core.solution.Result` (of ``ssi.solver.run`` or
``Model.solve_linear``). ``read_result(path)`` gives back a ``SceneResult`` (the scene is rebuilt from its
stored description, so every ``SceneResult`` method and every ``ssi.io.plot`` function works without the
original script), a ``SiteResult`` (the site rebuilt likewise) or, for a bare model, a
:class:`StoredResult`.

Layout::

    /attrs  format, ssi_version, kind ('scene' | 'site' | 'model'), complete (bool), stop (JSON: why a run
            stopped), scene (JSON, ssi.scene.scene_file.scene_to_dict: every layer, load, section layer) or
            site (JSON, ssi.scene.scene_file.scene_to_dict), model (JSON,
            Model.describe), settings (JSON), extra (JSON: further scalar fields of the result object)
    /mesh/coords                    (n_nodes, 2) node coordinates [m]
    /mesh/node_ndof                 (n_nodes,)
    /mesh/element_layer             (n_soil_el,) a site's soil elements' layer index (site files only)
    /mesh/<group>/conn              (n_el, n_nodes_el) node ids of each element (soil Q8, plate, interface)
    /mesh/<group>/edofs             (n_el, n_edof)
    /mesh/<group>/ip_xy             (n_el, n_ip, 2) integration points (soil, interface) [m]
    /mesh/<group>/ip_weights        (n_el, n_ip) interface point weights times Jacobian [m]
    /steps/load_factor              (n_steps + 1,)
    /steps/u                        (n_steps + 1, n_dof) [m, rad]
    /steps/state/<group>            (n_kept, ...) committed integration-point states
    /steps/state_step               (n_kept,) the step each kept state belongs to
    /solver/f_int, iterations, residuals + residual_counts, energies + energy_counts, stiffness,
            step_viscosity, load_factor, u_origin, f_int_origin, f_ref and f_dead (the loads it was solved
            with); attrs cuts, wall_time, factorizations, status, limit_load_factor, limit_evidence,
            limit_uncertainty, limit_suspect, limit_mechanism, limit_stored_share; relaxation_steps,
            relaxation_iterations, relaxation_note where the controlled path relaxed (files written before
            issue 31 also hold limit_load_upper, relaxed_steps and viscous_from of the removed viscous
            fallback: not read)
                                    (the result's; of a SceneResult its solver_result, except of a phased one)
    /solver/u_rows, state_rows      the solver result's rows of u / states: the index of the /steps row (of
                                    /steps/state) they are, or -1 for a row of its own in u_own / state_own
    /phases/<i>                     a phased SceneResult's phase i: attrs name, first, last (step indices);
                                    its solver result laid out as /solver. The SceneResult's own result is
                                    the phases' joined (ssi.scene.join_phases), rebuilt on reading.

Files of earlier versions read too: without f_ref/f_dead (a scene's result then gets the rebuilt scene's
loads), a linear scene's without /solver (its Result is rebuilt from /steps, f_int evaluated from each row),
a bare linear model's with /solver/reactions only (read as a StoredResult without f_int), a phased scene's
with the attribute solver_phase (ignored: the phases are joined as for a new file).

Writes are atomic (:func:`atomic_path`: a temporary file in the target's folder, flushed and fsynced, given
the mode a newly created file gets under the user's umask, then moved over the target), and an existing
file is never replaced unless ``overwrite=True``. A run that stopped
mid-path is written with ``complete=False``, its last converged step and the solver's report (``stop``).
"""

import contextlib
import dataclasses
import json
import os
import tempfile
from collections.abc import Iterator
from dataclasses import asdict, dataclass, field, is_dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import h5py
import numpy as np

from .. import __version__

if TYPE_CHECKING:  # for annotations only: the functions import ssi.scene and ssi.solver lazily
    from ..core.model import Model
    from ..core.solution import Result
    from ..scene import SceneResult, SiteResult
    from ..solver import Settings

FORMAT = "ssi-result-1"
_SCENE_RESULT_FIELDS = ("built", "solver_result", "phases")


# ---- atomic files ----------------------------------------------------------------------------------------
class OutputExistsError(FileExistsError):
    """An output file exists and ``overwrite`` was not given: ``path`` is the file. The command line names
    its own flag (``--overwrite``), the Python API its keyword."""

    def __init__(self, path: Path, appeared: bool = False) -> None:
        self.path = Path(path)
        when = "appeared while writing" if appeared else "exists"
        super().__init__(f"{self.path} {when}; pass overwrite=True to replace it")


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, overwrite: bool = False) -> Iterator[Path]:
    """Yield a temporary path in ``path``'s folder; on success it is fsynced and moved to ``path``.

    ``overwrite=False`` refuses an existing target (FileExistsError) before and, atomically (a hard link
    that fails if the target appeared meanwhile), after writing. On an exception the temporary file is
    removed and the target is untouched."""
    path = Path(path)
    if path.exists() and not overwrite:
        raise OutputExistsError(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    try:
        yield Path(tmp)
        with open(tmp, "rb+") as fh:
            fh.flush()
            os.fsync(fh.fileno())
        # mkstemp creates the file 0600; the result is the user's file, as open() would have made it
        os.chmod(tmp, 0o666 & ~current_umask())
        if overwrite:
            os.replace(tmp, path)
        else:
            try:
                os.link(tmp, path)
            except FileExistsError:
                raise OutputExistsError(path, appeared=True) from None
            except OSError:  # a file system without hard links: check, then rename
                if path.exists():
                    raise OutputExistsError(path, appeared=True) from None
                os.replace(tmp, path)
            if os.path.exists(tmp):
                os.unlink(tmp)
        _fsync_dir(path.parent)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def current_umask() -> int:
    """The process's file-creation mask (e.g. 0o022), read without changing it where the system says it
    (Linux: /proc/self/status), else by setting and restoring it."""
    with contextlib.suppress(OSError, ValueError):
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("Umask:"):
                return int(line.split()[1], 8)
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _fsync_dir(folder):
    with contextlib.suppress(OSError):
        fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


# ---- writing ---------------------------------------------------------------------------------------------
def group_names(model: "Model") -> list[str]:
    """Unique name of every element group of ``model`` (a repeated name gets a suffix _2, _3, ...)."""
    names = []
    for g in model.groups:
        base, k = g.name, 1
        while (name := base if k == 1 else f"{base}_{k}") in names:
            k += 1
        names.append(name)
    return names


def element_nodes(model: "Model", edofs: np.ndarray) -> np.ndarray:
    """(n_el, n_nodes_el) node ids of elements from their DOF table: each node's first DOF marks it."""
    start = np.concatenate([[0], np.cumsum(model.node_ndof)])
    node_of_dof = np.repeat(np.arange(model.n_nodes), model.node_ndof)
    nodes = node_of_dof[edofs]
    first = edofs[0] == start[nodes[0]]
    return np.ascontiguousarray(nodes[:, first])


def write_result(
    path: str | os.PathLike,
    result: "SceneResult | Result",
    settings: "Settings | dict | None" = None,
    overwrite: bool = False,
    complete: bool | None = None,
    stop: dict | None = None,
) -> Path:
    """Write ``result`` (SceneResult or Result) to the HDF5 file ``path``, atomically.

    ``complete``: whether the run reached the end of its load path; default: False if ``stop`` (the
    solver's failure report, e.g. ``NonConvergence.report``) is given or the result's ``status`` field says
    otherwise, else True. ``settings``: the solver Settings (or a JSON-able dict) to record. Returns the
    path."""
    path = Path(path)
    if complete is None:
        # a run that ended at a detected limit load is complete: the collapse is its answer, and its status
        # ("limit load reached") is stored with the solver's record
        complete = stop is None
    with atomic_path(path, overwrite) as tmp, h5py.File(tmp, "w") as h5:
        h5.attrs["format"] = FORMAT
        h5.attrs["ssi_version"] = __version__
        h5.attrs["complete"] = bool(complete)
        h5.attrs["stop"] = json.dumps(stop, default=_jsonable)
        if settings is not None:
            h5.attrs["settings"] = json.dumps(asdict(settings) if is_dataclass(settings) else settings)
        from ..core.solution import Result

        if isinstance(result, Result):  # a model's bare solver result, not a scene's or a site's view
            _write_model_result(h5, result)
        elif result.kind == "site":
            _write_site_result(h5, result)
        else:
            _write_scene_result(h5, result)
    return path


def _write_scene_result(h5, result):
    from ..scene.scene_file import scene_to_dict

    built = result.built
    h5.attrs["kind"] = "scene"
    h5.attrs["scene"] = json.dumps(scene_to_dict(built.scene))
    extra = {
        f.name: getattr(result, f.name)
        for f in dataclasses.fields(result)
        if f.name not in _SCENE_RESULT_FIELDS
    }
    h5.attrs["extra"] = json.dumps(extra, default=_jsonable)
    _write_mesh(h5, built.model)
    _write_steps(h5, built.model, result.load_factor, result.u, result.states)
    _write_phases(h5, result, result.solver_result, group_names(built.model))


def _write_site_result(h5, result):
    """A :class:`ssi.scene.SiteResult`: the site's description (rebuilt on reading, its mesh compared with
    the stored one), the mesh with each soil element's layer index, the steps and the solver's record."""
    from ..scene.scene_file import scene_to_dict

    built, res = result.built, result.result
    h5.attrs["kind"] = "site"
    h5.attrs["site"] = json.dumps(scene_to_dict(built.site), default=_jsonable)
    h5.attrs["extra"] = json.dumps(
        {
            "mesher": built.mesher,
            "initial_stress_method": built.initial_stress_method,
            "error_estimate": result.error_estimate,
            "verdict": result.verdict,
        },
        default=_jsonable,
    )
    _write_mesh(h5, built.model)
    h5["mesh"].create_dataset("element_layer", data=np.asarray(built.element_layer, np.int64))
    _write_steps(h5, built.model, res.load_factor, res.u, res.states)
    _write_phases(h5, result, res, group_names(built.model))


def _write_phases(h5, result, joined, names):
    """Each phase's record and solver result (``phases/<i>``) of a phased SceneResult or SiteResult, else
    the one solver result (``solver``): a phased result's own is its phases' joined, rebuilt on reading."""
    for i, record in enumerate(result.phases or []):
        grp = h5.create_group(f"phases/{i}")
        for key, value in record.items():
            if key != "result":
                grp.attrs[key] = json.dumps(value, default=_jsonable)
        _write_solver(grp, record["result"], result.u, result.states, names)
    if not result.phases:
        _write_solver(h5.create_group("solver"), joined, result.u, result.states, names)


def _write_model_result(h5, result):
    model = result.model
    h5.attrs["kind"] = "model"
    _write_mesh(h5, model)
    _write_steps(h5, model, result.load_factor, result.u, result.states)
    _write_solver(h5.create_group("solver"), result, result.u, result.states, group_names(model))


def _write_mesh(h5, model):
    h5.attrs["model"] = json.dumps(model.describe(), default=_jsonable)
    mesh = h5.create_group("mesh")
    mesh["coords"] = model.coords
    mesh["node_ndof"] = model.node_ndof
    for name, g in zip(group_names(model), model.groups):
        grp = mesh.create_group(name)
        grp["edofs"] = g.edofs
        grp["conn"] = element_nodes(model, g.edofs)
        ip_xy, ip_weights = g.integration_points(), g.ip_weights()
        if ip_xy is not None:
            grp["ip_xy"] = ip_xy
        if ip_weights is not None:
            grp["ip_weights"] = ip_weights


def _write_steps(h5, model, load_factor, u, states):
    steps = h5.create_group("steps")
    steps["load_factor"] = np.asarray(load_factor, np.float64)
    steps["u"] = np.asarray(u, np.float64)
    n_rows = len(load_factor)
    steps["state_step"] = np.arange(n_rows - len(states), n_rows)  # keep_states=False keeps the last only
    st = steps.create_group("state")
    for i, name in enumerate(group_names(model)):
        st[name] = np.stack([s[i] for s in states])


def _write_solver(grp, res, u, states, names):
    """The solver Result ``res`` in ``grp``: its rows of u and states by reference to the rows ``u`` and
    ``states`` written in /steps where they are the same arrays (a phase's rows are the scene result's),
    stored in ``u_own``/``state_own`` where not (the first row of a phase, a phase's intermediate steps)."""
    grp["load_factor"] = np.asarray(res.load_factor, np.float64)
    grp["f_int"] = np.asarray(res.f_int, np.float64)
    grp["iterations"] = np.asarray(res.iterations, np.int64)
    for key in ("residuals", "energies"):
        rows = getattr(res, key)
        grp[key] = np.array([v for row in rows for v in row], np.float64)
        grp[f"{key}_counts"] = np.array([len(row) for row in rows], np.int64)
    for key in ("cuts", "wall_time", "factorizations"):
        grp.attrs[key] = getattr(res, key)
    if res.relaxed_steps or res.relaxed_iterations:  # written only where the path relaxed: the files of
        for key in ("steps", "iterations", "note"):  # every other run unchanged (not "relaxed_steps": an
            grp.attrs[f"relaxation_{key}"] = getattr(res, f"relaxed_{key}")  # old file's, see above)
    grp["stiffness"] = np.asarray(res.stiffness, np.float64)
    grp["step_viscosity"] = np.asarray(res.step_viscosity, np.float64)
    grp.attrs["status"] = res.status
    grp.attrs["limit_load_factor"] = np.nan if res.limit_load_factor is None else res.limit_load_factor
    grp.attrs["limit_evidence"] = res.limit_evidence
    # the controlled path's limit: its numerical uncertainty (nan: not measured) and why it is suspect
    grp.attrs["limit_uncertainty"] = np.nan if res.limit_uncertainty is None else res.limit_uncertainty
    grp.attrs["limit_suspect"] = res.limit_suspect
    # its mechanism certificate (ssi.solver.mechanism; nan: none given)
    for key in ("limit_mechanism", "limit_stored_share"):
        grp.attrs[key] = np.nan if getattr(res, key) is None else getattr(res, key)
    for key in ("u_origin", "f_int_origin", "f_ref", "f_dead"):
        if getattr(res, key, None) is not None:
            grp[key] = np.asarray(getattr(res, key), np.float64)
    u_at = {id(row): r for r, row in enumerate(u)}
    u_rows = np.array([u_at.get(id(row), -1) for row in res.u], np.int64)
    grp["u_rows"] = u_rows
    if (u_rows < 0).any():
        grp["u_own"] = np.asarray([row for row, r in zip(res.u, u_rows) if r < 0], np.float64)
    state_at = {id(row): r for r, row in enumerate(states)}
    state_rows = np.array([state_at.get(id(row), -1) for row in res.states], np.int64)
    grp["state_rows"] = state_rows
    own = [row for row, r in zip(res.states, state_rows) if r < 0]
    for i, name in enumerate(names if own else []):
        grp[f"state_own/{name}"] = np.stack([row[i] for row in own])


# ---- reading ---------------------------------------------------------------------------------------------
@dataclass
class StoredResult:
    """A result file of a bare model (no scene to rebuild): the arrays as stored, per step."""

    coords: np.ndarray
    node_ndof: np.ndarray
    conn: dict
    edofs: dict
    load_factor: np.ndarray
    u: np.ndarray
    states: list  # per kept step: one array per group, in group order
    model: dict  # Model.describe()
    f_int: np.ndarray | None = None
    iterations: np.ndarray | None = None
    info: dict = field(default_factory=dict)
    group_names: list = field(default_factory=list)

    def __getitem__(self, key):
        """Mapping access with the keys of the earlier dict reader (``model``, ``u``, ``load_factor``,
        ``coords``, ``node_ndof``, ``f_int``, ``iterations``, ``settings``, ``state``: {group: (n_kept,
        ...)}), so scripts written against it keep working."""
        if key == "state":
            return {name: np.stack([s[i] for s in self.states]) for i, name in enumerate(self.group_names)}
        if key == "settings":
            return self.info["settings"]
        if key in ("model", "u", "load_factor", "coords", "node_ndof", "f_int", "iterations"):
            return getattr(self, key)
        raise KeyError(key)


def read_info(path: str | os.PathLike) -> dict:
    """The file's description: format, ssi_version, kind, complete, stop, settings, scene, model, extra."""
    with h5py.File(path, "r") as h5:
        return _info(h5)


def _info(h5):
    out = {}
    for key, value in h5.attrs.items():
        value = value.decode() if isinstance(value, bytes) else value
        if key in ("stop", "settings", "scene", "site", "model", "extra"):
            value = json.loads(value)
        elif isinstance(value, np.bool_ | np.generic):
            value = value.item()
        out[key] = value
    return out


def read_result(path: str | os.PathLike) -> "SceneResult | SiteResult | StoredResult":
    """Read a result file: a :class:`ssi.scene.SceneResult` (scene rebuilt from its description; its
    ``solver_result`` a :class:`ssi.solver.Result` when one was written), a :class:`ssi.scene.SiteResult`
    (the site rebuilt likewise) or a :class:`StoredResult`. A limit analysis's file is read by
    :func:`ssi.io.results_limit.read_limit_result`."""
    with h5py.File(path, "r") as h5:
        info = _info(h5)
        if info.get("format") != FORMAT:
            raise ValueError(
                f"{path}: not an ssi result file of format {FORMAT} (found {info.get('format')})"
            )
        if info.get("kind") == "limit":
            raise ValueError(
                f"{path}: a limit-analysis file; read it with ssi.io.results_limit.read_limit_result"
            )
        lam = h5["steps/load_factor"][...]
        u = h5["steps/u"][...]
        names = list(h5["steps/state"])
        order = json.loads(h5.attrs["model"])["groups"]
        stored = {k: h5[f"steps/state/{k}"][...] for k in names}
        kept = len(h5["steps/state_step"])
        solver = _read_solver(h5["solver"]) if "solver/f_int" in h5 else None
        phases = (
            [
                (
                    _read_solver(h5[f"phases/{i}"]),
                    {
                        k: json.loads(v)
                        for k, v in h5[f"phases/{i}"].attrs.items()
                        if k in ("name", "first", "last")
                    },
                )
                for i in range(len(h5["phases"]))
            ]
            if "phases" in h5
            else []
        )
        mesh = {
            k: (h5[f"mesh/{k}/conn"][...], h5[f"mesh/{k}/edofs"][...])
            for k in h5["mesh"]
            if isinstance(h5[f"mesh/{k}"], h5py.Group)
        }
        coords, node_ndof = h5["mesh/coords"][...], h5["mesh/node_ndof"][...]
    group_order = _stored_group_order(order, names)
    states = [[stored[name][i] for name in group_order] for i in range(kept)]
    for record, _ in phases:
        if "state_own" in record:
            record["state_own"] = [
                [record["state_own"][name][i] for name in group_order]
                for i in range(len(record["state_own"][group_order[0]]))
            ]
    if solver is not None and "state_own" in solver:
        solver["state_own"] = [
            [solver["state_own"][name][i] for name in group_order]
            for i in range(len(solver["state_own"][group_order[0]]))
        ]
    if info["kind"] == "site":
        return _site_result(info, lam, u, states, solver, phases, coords)
    if info["kind"] != "scene":
        return StoredResult(
            coords=coords,
            node_ndof=node_ndof,
            conn={k: v[0] for k, v in mesh.items()},
            edofs={k: v[1] for k, v in mesh.items()},
            load_factor=lam,
            u=u,
            states=states,
            model=info["model"],
            f_int=None if solver is None else solver["f_int"],
            iterations=None if solver is None else solver["iterations"],
            info=info,
            group_names=group_order,
        )
    return _scene_result(info, lam, u, states, solver, phases, coords)


def _stored_group_order(described, names):
    """Group names in the model's group order (h5py lists them alphabetically)."""
    base = [g.get("name", "") for g in described]
    ordered = []
    for b in base:
        k = 1
        while (name := b if k == 1 else f"{b}_{k}") in ordered:
            k += 1
        ordered.append(name)
    if sorted(ordered) != sorted(names):
        raise ValueError(f"state groups {names} do not match the model's groups {ordered}")
    return ordered


def _read_solver(grp):
    out = {k: grp[k][...] for k in grp if isinstance(grp[k], h5py.Dataset)}
    if "state_own" in grp:
        out["state_own"] = {k: grp[f"state_own/{k}"][...] for k in grp["state_own"]}
    out.update({k: v.item() if isinstance(v, np.generic) else v for k, v in grp.attrs.items()})
    return out


def _optional_float(value):
    return None if value is None or not np.isfinite(value) else float(value)


def _scene_result(info, lam, u, states, solver, phases, coords):
    from ..scene import SceneResult, join_phases
    from ..scene.scene_file import scene_from_dict

    built = scene_from_dict(info["scene"]).build()
    if built.model.coords.shape != coords.shape or not np.array_equal(built.model.coords, coords):
        raise ValueError(
            "the rebuilt scene's mesh differs from the stored one (file written by another "
            f"ssi version? this is {__version__}, the file {info.get('ssi_version')})"
        )
    u_rows = list(u)
    records = [
        {**meta, "result": _solver_result(built.model, rec, lam, u_rows, states)} for rec, meta in phases
    ]
    if records:
        solver_result = join_phases(built.model, records)
    elif solver is not None:
        solver_result = _solver_result(built.model, solver, lam, u_rows, states)
        if solver_result.f_ref is None:  # a file written before the loads were kept: the scene's own
            solver_result.f_ref, solver_result.f_dead = built.model.load_vectors()
    else:  # a linear scene's file written before its solve was a Result: its rows, f_int re-evaluated
        solver_result = _linear_result(built.model, u_rows, states)
    extra = {
        k: v
        for k, v in info.get("extra", {}).items()
        if k in {f.name for f in dataclasses.fields(SceneResult)}
    }
    return SceneResult(built, solver_result, phases=records or None, **extra)


def _site_result(info, lam, u, states, solver, phases, coords):
    """A :class:`ssi.scene.SiteResult` from a file: the site rebuilt from its description (its mesh must
    be the stored one), its solver result from the stored record (a phased site's: its phases' joined)."""
    from ..scene import join_phases
    from ..scene.scene_file import site_from_dict
    from ..scene.site_view import SiteResult

    built = site_from_dict(info["site"], "the result file's site").build()
    if built.model.coords.shape != coords.shape or not np.array_equal(built.model.coords, coords):
        raise ValueError(
            "the rebuilt site's mesh differs from the stored one (file written by another ssi or gmsh "
            f"version? this is ssi {__version__}, the file {info.get('ssi_version')})"
        )
    estimate = info.get("extra", {}).get("error_estimate")
    records = [
        {**meta, "result": _solver_result(built.model, rec, lam, list(u), states)} for rec, meta in phases
    ]
    joined = (
        join_phases(built.model, records)
        if records
        else _solver_result(built.model, solver, lam, list(u), states)
    )
    return SiteResult(
        built, joined, error_estimate=estimate, phases=records or None,
        verdict=info.get("extra", {}).get("verdict"),
    )  # fmt: skip


def _linear_result(model, u, states):
    """The Result of a linear solve from its two stored rows ``u`` and ``states`` (files of linear scenes
    written before Model.solve_linear returned one: the solved state stored on both rows), its internal
    force evaluated from each row; the solve's wall time was not stored (nan)."""
    from ..core.model import System
    from ..core.solution import Result

    system = System(model)
    f_int = [system.evaluate(row, np.zeros_like(row), st, None)[0] for row, st in zip(u, states)]
    return Result.of_linear_solve(model, u, f_int, states, *model.load_vectors(), wall_time=float("nan"))


def _solver_result(model, rec, lam, u, states):
    """A :class:`ssi.solver.Result` from its stored record; its u and state rows are the scene result's
    where the file says so (files without the row tables: the scene result's rows themselves)."""
    from ..core.solution import Result

    u_rows = rec.get("u_rows", np.arange(len(lam)))
    state_rows = rec.get("state_rows", np.arange(len(states)))
    own_u = iter(rec.get("u_own", ()))
    own_states = iter(rec.get("state_own", ()))
    return Result(
        model=model,
        load_factor=list(rec.get("load_factor", lam)),
        u=[u[r] if r >= 0 else next(own_u) for r in u_rows],
        f_int=list(rec["f_int"]),
        states=[states[r] if r >= 0 else next(own_states) for r in state_rows],
        iterations=rec["iterations"].tolist(),
        residuals=_split(rec["residuals"], rec["residuals_counts"]),
        energies=_split(rec["energies"], rec["energies_counts"]),
        stiffness=list(rec.get("stiffness", [])),
        # a file written before the field existed: its steps read as rate independent, as they were then
        step_viscosity=list(rec.get("step_viscosity", np.zeros(len(rec["iterations"])))),
        cuts=int(rec["cuts"]),
        relaxed_steps=int(rec.get("relaxation_steps", 0)),
        relaxed_iterations=int(rec.get("relaxation_iterations", 0)),
        relaxed_note=str(rec.get("relaxation_note", "")),
        wall_time=float(rec["wall_time"]),
        factorizations=int(rec["factorizations"]),
        status=str(rec.get("status", "completed")),
        limit_load_factor=_optional_float(rec.get("limit_load_factor")),
        limit_evidence=str(rec.get("limit_evidence", "")),
        limit_uncertainty=_optional_float(rec.get("limit_uncertainty")),
        limit_suspect=str(rec.get("limit_suspect", "")),
        limit_mechanism=_optional_float(rec.get("limit_mechanism")),
        limit_stored_share=_optional_float(rec.get("limit_stored_share")),
        u_origin=rec.get("u_origin"),
        f_int_origin=rec.get("f_int_origin"),
        f_ref=rec.get("f_ref"),  # files written before the loads were kept: None
        f_dead=rec.get("f_dead"),
    )


def _split(flat, counts):
    ends = np.cumsum(counts)
    return [flat[e - c : e].tolist() for e, c in zip(ends, counts)]


def _jsonable(obj):
    from ..scene import Scene
    from ..scene.scene_file import scene_to_dict

    if isinstance(obj, Scene):  # the scene a model was built from (Model.info["scene"]): its plain form
        return scene_to_dict(obj)
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    return str(obj)


# ---- comparing results -----------------------------------------------------------------------------------
def scene_quantities(result: "SceneResult") -> dict[str, np.ndarray]:
    """Every number a :class:`ssi.scene.SceneResult` answers, at every step it holds states for, as flat
    arrays keyed by name: what a file must give back unchanged (``max_difference``). With the status and
    limit load, the solver result (``solver.*``) and of a phased result every phase's name, step range and
    solver result (``phases[i].*``)."""
    out = {
        "load_factor": np.asarray(result.load_factor, np.float64),
        "u": np.asarray(result.u, np.float64),
        "coords": result.built.model.coords,
        "status": np.asarray(result.status),
        "limit_load_factor": _number(result.limit_load_factor),
        "n_phases": np.asarray(-1 if result.phases is None else len(result.phases)),
    }
    out.update(solver_quantities(result.solver_result, "solver."))
    for i, record in enumerate(result.phases or []):
        for key, value in record.items():
            if key == "result":
                out.update(solver_quantities(value, f"phases[{i}].solver."))
            else:
                out[f"phases[{i}].{key}"] = np.asarray(value)
    for key, value in result.load_settlement().items():
        out[f"load_settlement.{key}"] = value
    n_rows = len(result.load_factor)
    for k in range(n_rows - len(result.states), n_rows):
        for i, state in enumerate(result.states[k - n_rows]):
            out[f"state[{k}][{i}]"] = state
        q = {
            "settlement": result.surface(k),
            "soil_stress": result.soil_stress(k),
            "plastic_points": result.plastic_points(k),
            "plastic_strain": result.plastic_strain(k),
            "max_settlement": result.max_settlement(k),
        }
        if result.built.plate is not None:
            q.update(
                plate_settlement=result.settlement(k),
                contact=result.contact(k),
                contact_resultant=result.contact_resultant(k),
                strip_forces=result.strip_forces(k),
                plate_layers=result.plate_layers(k),
                steel_stress=result.steel_stress(k),
                crack_map=result.crack_map(k),
            )
            from ..scene.design import design_of  # lazily, as ssi.io's other scene imports

            if design_of(result) is not None:  # an RC strip: EN 1992 crack width w_k [m] at the axial points
                cw = result.crack_width(k)
                q["crack_width"] = {"x": cw["x"], "w_k": cw["w_k"], "sig_s": cw["sig_s"]}
        for name, value in q.items():
            if isinstance(value, dict):
                items = value.items()
            else:
                items = enumerate(value) if isinstance(value, tuple) else [("", value)]
            for sub, arr in items:
                out[f"{name}[{k}].{sub}"] = np.asarray(arr)
    return out


def solver_quantities(res: "Result", prefix: str = "") -> dict[str, np.ndarray]:
    """Every field of a :class:`ssi.solver.Result` as arrays keyed ``prefix + name`` (rows of ragged
    histories concatenated, with their lengths); None as NaN."""
    out = {}
    for f in dataclasses.fields(res):
        value = getattr(res, f.name)
        if f.name == "model":
            continue
        if f.name == "states":
            for k, row in enumerate(value):
                for i, state in enumerate(row):
                    out[f"{prefix}states[{k}][{i}]"] = np.asarray(state)
        elif f.name in ("residuals", "energies"):
            out[f"{prefix}{f.name}"] = np.array([v for row in value for v in row], np.float64)
            out[f"{prefix}{f.name}_counts"] = np.array([len(row) for row in value], np.int64)
        else:
            out[prefix + f.name] = _number(value) if value is None else np.asarray(value)
    return out


def _number(value):
    return np.asarray(np.nan if value is None else value, np.float64)


def max_difference(a: "SceneResult", b: "SceneResult", skip: tuple = ()) -> tuple[float, str]:
    """(largest absolute difference, the quantity where it occurs) between two SceneResults over
    :func:`scene_quantities`; inf for a quantity missing on one side, of another shape, or a differing
    non-numeric array (zones, flags). NaN equals NaN (points that do not carry a quantity). ``skip``: parts
    of names to leave out (``("wall_time",)`` to compare two runs of the same scene)."""
    qa, qb = scene_quantities(a), scene_quantities(b)
    worst, where = 0.0, ""
    for name in sorted(set(qa) | set(qb)):
        if any(part in name for part in skip):
            continue
        x, y = qa.get(name), qb.get(name)
        if x is None or y is None or np.shape(x) != np.shape(y):
            return float("inf"), name
        if x.dtype.kind in "fc" and y.dtype.kind in "fc":
            both_nan = np.isnan(x) & np.isnan(y)
            diff = np.where(both_nan, 0.0, np.abs(x - y))
            d = float(np.max(diff, initial=0.0)) if not np.any(np.isnan(diff)) else float("inf")
        else:
            d = 0.0 if np.array_equal(x, y) else float("inf")
        if d > worst:
            worst, where = d, name
    return worst, where


def run_output_paths(input_path, out=None, paraview=None, plots=None, overwrite: bool = False) -> tuple:
    """The files ``ssi run`` writes for a scene or site file ``input_path``: (result file, ParaView series,
    plots folder, JSON summary, HTML report), defaults beside the input (``<name>.h5``, ``<name>.pvd``,
    ``<name>_plots``, ``<name>_summary.json``, ``<name>_report.html``); raises OutputExistsError for one that
    exists unless ``overwrite`` (checked before anything is solved)."""
    stem = Path(input_path).with_suffix("")
    out = Path(out) if out else stem.with_suffix(".h5")
    paraview = Path(paraview) if paraview else stem.parent / (stem.name + ".pvd")
    plots = Path(plots) if plots else stem.parent / (stem.name + "_plots")
    summary_path = stem.parent / (stem.name + "_summary.json")
    report_path = stem.parent / (stem.name + "_report.html")
    for target in (out, paraview, summary_path, report_path):
        if target.exists() and not overwrite:
            raise OutputExistsError(target)
    return out, paraview, plots, summary_path, report_path
