"""Parameter studies: many scenes on a dask.distributed cluster, one result file each, one table.

    from ssi.studies.sweep import sweep, grid
    table = sweep(make_scene, grid(E=[10e6, 20e6], c=[10e3, 20e3]), out_dir="results/my_sweep")

``make_scene(**params)`` returns a :class:`~ssi.scene.Scene`; every parameter set becomes one task that builds
and solves it and writes ``scenes/<key>.h5`` (the full result, :func:`ssi.io.results.write_result`) and
``scenes/<key>.json`` (its table row), both atomically, where ``<key>`` is a hash of the parameters. The
sweep then gathers every row into ``sweep.csv``. A scene that raises is recorded with status "failed" and its
error, never fatal; a re-run skips the scenes whose row says "completed" or "collapsed" (resumable after a
crash or an interrupted run) and retries the failed ones.

``client=None`` starts a ``LocalCluster`` (processes, one thread each: a solve is single-threaded and the
GIL is held in numba kernels) and closes it at the end; a scheduler address ("tcp://host:8786") or a
``distributed.Client`` runs on that cluster, whose workers must see ``out_dir`` and have ``ssi`` installed.
``client="serial"`` runs in this process without dask (what the sweep falls back to, with a warning, when
dask is not installed).

Numba: the workers of a LocalCluster inherit this process's environment, so they load the compiled kernels
from the same ``NUMBA_CACHE_DIR`` (importing ``ssi`` sets it: see ``ssi.numba_cache_key``); on a real cluster,
set ``NUMBA_CACHE_DIR`` to one shared folder in the workers' environment.
"""

from __future__ import annotations

import contextlib
import csv
import hashlib
import itertools
import json
import math
import os
import sys
import time
import traceback
import warnings
from pathlib import Path

from ..io.results import atomic_path, write_result

STATUSES = ("completed", "collapsed", "failed")
DONE = ("completed", "collapsed")


def grid(**axes) -> list[dict]:
    """Every combination of the given parameter values: ``grid(E=[1, 2], c=[3])`` ->
    ``[{"E": 1, "c": 3}, {"E": 2, "c": 3}]``."""
    for name, values in axes.items():
        if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
            raise TypeError(f"grid: {name} must be a list of values, got {values!r}")
    names = list(axes)
    return [dict(zip(names, combo)) for combo in itertools.product(*(list(axes[n]) for n in names))]


def scene_key(params: dict) -> str:
    """A stable 16-hex-digit name for a parameter set (JSON with sorted keys, SHA-1)."""
    text = json.dumps(params, sort_keys=True, default=repr)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


def _write_json(path: Path, row: dict) -> None:
    with atomic_path(path, overwrite=True) as tmp:
        Path(tmp).write_text(json.dumps(row, indent=1, default=repr))


def run_scene(
    scene_factory, params: dict, out_dir: str, n_steps=None, settings=None, keep_files: bool = True
) -> dict:
    """Build and solve ``scene_factory(**params)``; write its result file and row; return the row.

    The row: ``key``, ``params``, ``status`` ("completed", "collapsed": a limit load was reached, "failed":
    the factory, build or solve raised), headline quantities (:func:`ssi.scene.estimate.headline`),
    ``n_dof``, ``wall_time`` [s] (build + solve), ``error`` (the exception of a failed scene), ``worker``
    (pid)."""
    from ..scene.estimate import headline

    key = scene_key(params)
    folder = Path(out_dir) / "scenes"
    folder.mkdir(parents=True, exist_ok=True)
    row = {"key": key, "params": params, "worker": os.getpid()}
    t0 = time.perf_counter()
    try:
        built = scene_factory(**params).build()
        out = built.solve(n_steps=n_steps, settings=settings)
        row.update(
            status="completed" if out.status == "completed" else "collapsed",
            n_dof=built.model.n_dof,
            limit_load_factor=out.limit_load_factor,
            **headline(out),
        )
        if keep_files:
            write_result(folder / f"{key}.h5", out, settings, overwrite=True)
    except Exception as err:  # noqa: BLE001 -- a failed scene is a result of the sweep, not its end
        row.update(
            status="failed", error=f"{type(err).__name__}: {err}", traceback=traceback.format_exc(limit=5)
        )
    row["wall_time"] = time.perf_counter() - t0
    _write_json(folder / f"{key}.json", row)
    return row


def _read_row(path: Path):
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


@contextlib.contextmanager
def _main_not_reimported():
    """Start worker processes without re-running the main script: multiprocessing's "spawn" imports
    ``__main__`` from its file in each child, which would run a chapter or script (and its sweep) again.
    The scene factory reaches the workers pickled by value (cloudpickle does so for ``__main__``), so the
    children do not need the script."""
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if path is None or getattr(main, "__spec__", None) is not None:
        yield
        return
    del main.__file__
    try:
        yield
    finally:
        main.__file__ = path


def _client(client, n_workers):
    """(client, owned): a distributed Client for ``client`` (None: a new LocalCluster), owned if made here."""
    from distributed import Client, LocalCluster

    if client is None:
        for var in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
            os.environ.setdefault(var, "1")
        with _main_not_reimported():
            cluster = LocalCluster(
                n_workers=n_workers, threads_per_worker=1, processes=True, dashboard_address=":0"
            )
        return Client(cluster), True
    if isinstance(client, str):
        return Client(client), True
    return client, False


def sweep(
    scene_factory,
    parameters,
    client=None,
    out_dir=None,
    n_steps=None,
    settings=None,
    n_workers: int = 2,
    keep_files: bool = True,
    retry_failed: bool = True,
) -> list[dict]:
    """Solve ``scene_factory(**p)`` for every ``p`` in ``parameters`` (a list of dicts, e.g. :func:`grid`).

    ``client``: None (a LocalCluster of ``n_workers`` processes), a scheduler address, a
    ``distributed.Client``, or "serial" (this process, no dask). ``out_dir`` (default
    ``results/sweep`` under the current folder): where ``scenes/`` and ``sweep.csv`` go. ``n_steps``,
    ``settings``: those of ``BuiltScene.solve``. ``keep_files``: write each scene's HDF5 result (False: only
    its row).
    Returns the rows in the order of ``parameters``; ``sweep.csv`` holds them with one column per parameter
    and quantity. A scene already done (its row says completed or collapsed) is not solved again; a failed
    one is retried if ``retry_failed``."""
    parameters = [dict(p) for p in parameters]
    if not parameters:
        raise ValueError("parameters: the sweep needs at least one parameter set")
    if int(n_workers) != n_workers or n_workers < 1:
        raise ValueError(f"n_workers must be an integer >= 1, got {n_workers}")
    out = Path(out_dir) if out_dir is not None else Path("results") / "sweep"
    (out / "scenes").mkdir(parents=True, exist_ok=True)
    keys = [scene_key(p) for p in parameters]
    if len(set(keys)) != len(keys):
        raise ValueError("parameters: two parameter sets are equal (each scene must be distinct)")
    rows = {}
    for key in keys:
        row = _read_row(out / "scenes" / f"{key}.json")
        if row and (row.get("status") in DONE or (row.get("status") == "failed" and not retry_failed)):
            rows[key] = row
    todo = [(k, p) for k, p in zip(keys, parameters) if k not in rows]
    if todo:
        rows.update(_run(scene_factory, todo, client, str(out), n_steps, settings, n_workers, keep_files))
    ordered = [rows[k] for k in keys]
    write_table(out / "sweep.csv", ordered)
    return ordered


def _run(scene_factory, todo, client, out_dir, n_steps, settings, n_workers, keep_files):
    if client != "serial":
        try:
            import distributed  # noqa: F401
        except ImportError:
            warnings.warn(
                "dask.distributed is not installed (pip install 'ssi[sweep]'): the sweep runs "
                "serially in this process",
                RuntimeWarning,
                stacklevel=3,
            )
            client = "serial"
    if client == "serial":
        return {k: run_scene(scene_factory, p, out_dir, n_steps, settings, keep_files) for k, p in todo}
    from distributed import as_completed

    cl, owned = _client(client, n_workers)
    try:
        futures = {
            cl.submit(
                run_scene,
                scene_factory,
                p,
                out_dir,
                n_steps,
                settings,
                keep_files,
                key=f"ssi-scene-{k}",
                pure=False,
            ): k
            for k, p in todo
        }
        done = {}
        for fut in as_completed(futures):
            k = futures[fut]
            try:
                done[k] = fut.result()
            except Exception as err:  # noqa: BLE001 -- a lost worker: recorded like a failed scene
                p = dict(todo)[k]
                done[k] = {
                    "key": k,
                    "params": p,
                    "status": "failed",
                    "wall_time": math.nan,
                    "error": f"{type(err).__name__}: {err} (worker lost)",
                }
                _write_json(Path(out_dir) / "scenes" / f"{k}.json", done[k])
        return done
    finally:
        if owned:
            cluster = getattr(cl, "cluster", None)
            cl.close()
            if cluster is not None:
                cluster.close()


TABLE_FIRST = ("key", "status", "wall_time", "n_dof")


def write_table(path, rows) -> Path:
    """Write the sweep's rows to the CSV file ``path`` atomically: key, status, wall time, DOFs, one column
    per parameter (``p.<name>``), every quantity, the error of a failed scene."""
    params = sorted({n for r in rows for n in r.get("params", {})})
    skip = set(TABLE_FIRST) | {"params", "traceback", "error", "worker"}
    quantities = sorted({n for r in rows for n in r if n not in skip})
    header = list(TABLE_FIRST) + [f"p.{n}" for n in params] + quantities + ["error"]
    path = Path(path)
    with atomic_path(path, overwrite=True) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for r in rows:
            w.writerow(
                [r.get(c, "") for c in TABLE_FIRST]
                + [r.get("params", {}).get(n, "") for n in params]
                + [r.get(q, "") for q in quantities]
                + [r.get("error", "")]
            )
    return path


def read_table(path) -> list[dict]:
    """The rows of a ``sweep.csv`` as dicts of strings converted to float where they are numbers."""

    def conv(v):
        try:
            return float(v)
        except ValueError:
            return v

    with open(path, newline="") as fh:
        return [{k: conv(v) for k, v in r.items()} for r in csv.DictReader(fh)]
