"""The zoo's incremental limits against their limit-analysis brackets (issues 30 and 31).

Each zoo scene (:mod:`ssi.lab.zoo`) has a certified bracket of its collapse load factor lambda (lambda scales
the column load; the soil's weight is held): the associated bracket [LB, UB] and the Davis one [LB_D, UB_D]
(:meth:`ssi.scene.Scene.limit_analysis`). ``tools/zoo_brackets.py`` computes them once and stores them in
``reference_data/zoo_brackets_random.csv`` and ``zoo_brackets_ordinary.csv`` (:func:`zoo_bracket`
computes one row, :func:`read_zoo_brackets` reads the tables); chapter 06 reads them and checks every
incremental outcome against its bracket
(:func:`bracket_verdict`, the band [0.97 LB_Davis, 1.03 UB_assoc] of :func:`ssi.limit.check_limit`): the
100 random scenes' stored outcomes on the controlled path (``reference_data/zoo_controlled_random.csv``,
rows ``fela_zoo`` and ``zoo_limits_certified``), where a run stopped in NonConvergence below the floor is
listed as a stop, not a limit.

For the round-off check of the zoo's limits (row ``roundoff_limits``) the same scene is re-solved with the
soil's Young's moduli scaled by 1 + 1e-13 (:func:`perturb_soil_modulus`) and with the soil's nodes -- and
so the degrees of freedom -- renumbered by a seeded permutation (:func:`renumbered_nodes`), the numbers of
the problem otherwise unchanged.
"""

from __future__ import annotations

import math
import time
from contextlib import contextmanager
from dataclasses import replace

import numpy as np

from ..core.mesh import SoilMesh
from ..core.validate import check_real
from ..limit import LimitCheck, check_limit
from ..scene import MeshSize
from ..solver import LIMIT_LOAD
from . import paths
from .digitize import read_reference
from .zoo import ordinary_scenes, random_scenes

__all__ = [
    "BAND",
    "BRACKETS_FILES",
    "bracket_check",
    "bracket_scenes",
    "bracket_verdict",
    "perturb_soil_modulus",
    "limit_check",
    "limit_key",
    "permute_nodes",
    "read_zoo_brackets",
    "renumbered_nodes",
    "zoo_bracket",
]

# one file per part of the zoo, each with its own provenance (computed by separate runs of the tool)
BRACKETS_FILES = {
    "random": paths.REFERENCE_DATA / "zoo_brackets_random.csv",
    "ordinary": paths.REFERENCE_DATA / "zoo_brackets_ordinary.csv",
}
BAND = (0.03, 0.03)  # check_limit's margins below LB_Davis and above UB_assoc (issue 30, item 6)
COLUMNS = ("lb", "ub", "lb_davis", "ub_davis", "gap", "gap_davis", "triangles", "seconds")


def bracket_scenes() -> list[tuple[str, object]]:
    """The scenes the table covers, in its order: the 100 random scenes of seed 1 (chapter 06, section 6)
    then the fixed ordinary scenes (tests/test_zoo.py)."""
    return random_scenes(100, seed=1) + ordinary_scenes()


def limit_key(scene) -> str:
    """A key equal for scenes that are the same limit problem: the scene with what limit analysis does not
    read -- the soil's stiffness (E, nu, nu_u, K0), its integration scheme, the contact's stiffnesses and
    the incremental mesh -- set to fixed values (the zoo's nu and h_fine variants of one scene share a
    bracket)."""
    layers = [
        replace(lay, E=1e7, nu=0.3, K0=None, nu_u=0.495, scheme="implicit", n_sub=1, drift=False)
        for lay in scene.layers
    ]
    contact = scene.contact
    if contact is not None and hasattr(contact, "kn"):
        contact = replace(contact, kn=1e10, kt=1e9)
    return repr(replace(scene, layers=layers, contact=contact, mesh=MeshSize()))


def zoo_bracket(scene, gap: float, **options) -> dict:
    """One row of the table: the scene's associated and Davis brackets of lambda (the last phase's loads)
    refined to the relative ``gap``, their achieved gaps, the final mesh's triangles and the wall time [s].
    Raises ValueError (from :func:`ssi.capacity.limit_problem`) for a scene the limit problem
    cannot represent; ``options`` go to :meth:`Scene.limit_analysis`."""
    t0 = time.perf_counter()
    cap = scene.limit_analysis(gap=gap, **options)
    return {
        "lb": cap.lb,
        "ub": cap.ub,
        "lb_davis": cap.lb_davis,
        "ub_davis": cap.ub_davis,
        "gap": cap.gap,
        "gap_davis": cap.gap_davis,
        "triangles": cap.n_triangles,
        "seconds": time.perf_counter() - t0,
    }


def read_zoo_brackets() -> tuple[dict, dict[str, dict]]:
    """``(meta, rows)`` of the stored tables (:data:`BRACKETS_FILES`; a part not computed yet is absent):
    ``rows[scene name]`` a dict of :data:`COLUMNS` (floats); ``meta[part]`` the part's provenance. Scenes
    the limit problem refused are not rows; ``meta[part]["refused"]`` lists them with the reason."""
    meta, rows = {}, {}
    for part, path in BRACKETS_FILES.items():
        if not path.exists():
            continue
        meta[part], cols = read_reference(path)
        for i, name in enumerate(str(s) for s in cols["scene"]):
            rows[name] = {k: float(cols[k][i]) for k in COLUMNS}
    return meta, rows


def limit_check(row: dict | None, limit: float) -> LimitCheck | None:
    """The check of an incremental ``limit`` load factor against a bracket ``row`` (None: no bracket, None
    returned): :func:`ssi.limit.check_limit` in the band [0.97 LB_Davis, 1.03 UB_assoc]. A row whose Davis
    lower bound did not certify (NaN) has no floor: only a limit above the ceiling is a verdict then (a
    mesh overestimate), otherwise None."""
    if row is None:
        return None
    low, high = BAND
    if np.isfinite(row["lb_davis"]):
        return check_limit(limit, (row["lb_davis"], row["ub"]), low=low, high=high)
    ceiling = (1.0 + high) * row["ub"]
    if limit > ceiling:
        return LimitCheck("mesh overestimate", limit, math.nan, ceiling, limit / ceiling - 1.0)
    return None


def bracket_check(rows: dict[str, dict]):
    """``check(name, limit)`` for :func:`ssi.lab.zoo.solve_zoo`: :func:`limit_check` of the scene's row."""
    return lambda name, limit: limit_check(rows.get(name), limit)


def bracket_verdict(status: str, load_factor: float, row: dict | None) -> tuple[str, float]:
    """(verdict, size) of one incremental outcome against its bracket ``row`` (None: no bracket).

    A limit (``status`` "limit load reached", ``load_factor`` the limit) is checked by :func:`limit_check`:
    "inside", "false collapse" (below 0.97 LB_Davis) or "mesh overestimate" (above 1.03 UB_assoc), ``size``
    how far outside (relative); "no floor" when the Davis lower bound did not certify and the limit is below
    the ceiling. Any other outcome claims no capacity, only that ``load_factor`` was carried (1 when
    completed, the last converged lambda when stopped): "mesh overestimate" when that is above the ceiling
    (the incremental mesh carried what no mechanism allows), else "carried" (completed) or "stopped"
    (NonConvergence, no claim to check) -- a carried load below LB_Davis is not a collapse."""
    if row is None:
        return "no bracket", 0.0
    load_factor = check_real("load_factor", load_factor, lo=0.0)
    if status == LIMIT_LOAD:
        chk = limit_check(row, load_factor)
        return ("no floor", 0.0) if chk is None else (chk.verdict, chk.size)
    ceiling = (1.0 + BAND[1]) * row["ub"]
    if load_factor > ceiling:
        return "mesh overestimate", load_factor / ceiling - 1.0
    return ("carried" if status == "completed" else "stopped"), 0.0


def perturb_soil_modulus(scene, factor: float = 1.0 + 1e-13):
    """``scene`` with every soil layer's Young's modulus E multiplied by ``factor`` (a round-off-level change
    of the soil kernel's numbers; nothing else changes)."""
    return replace(scene, layers=[replace(lay, E=lay.E * factor) for lay in scene.layers])


def permute_nodes(mesh: SoilMesh, seed: int) -> SoilMesh:
    """The same mesh with its nodes renumbered by a seeded random permutation: new node i is old node
    order[i]; coordinates, elements (the same nodes in the same local order), layers and the grid map
    follow, so the problem is unchanged but for the order of its unknowns."""
    order = np.random.default_rng(seed).permutation(len(mesh.xy))
    new_id = np.empty_like(order)
    new_id[order] = np.arange(len(order))
    grid = np.where(mesh.grid >= 0, new_id[np.maximum(mesh.grid, 0)], -1)
    return SoilMesh(mesh.xy[order], new_id[mesh.conn], mesh.el_layer, mesh.x_lines, mesh.z_lines, grid)


@contextmanager
def renumbered_nodes(seed: int = 1):
    """Within the block, :meth:`Scene.build` numbers the soil's nodes (and so the model's DOFs) by the
    seeded permutation of :func:`permute_nodes` instead of the mesh generator's order. ssi.core has no DOF
    permutation hook; this swaps the scene module's mesh generator for the block's duration (a verification
    tool: not thread-safe, and restored on exit)."""
    from ..scene import scene as scene_module

    original = scene_module.soil_block

    def permuted(*args, **kwargs):
        return permute_nodes(original(*args, **kwargs), seed)

    scene_module.soil_block = permuted
    try:
        yield
    finally:
        scene_module.soil_block = original
