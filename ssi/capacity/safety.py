"""The factor of safety of a :class:`~ssi.scene.Scene` or a :class:`~ssi.scene.site.Site` by strength
reduction (c / F and tan phi / F of the soil and the contact) as a certified bracket
(:func:`ssi.limit.strength_reduction`) on the input's limit problem (:mod:`ssi.capacity.problem`).

    sf = scene.safety_factor(gap=0.02)         # or site.safety_factor(), ssi.capacity.safety_factor(...)
    sf.f_lb, sf.f_ub
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..core.validate import check_int, check_real
from ..limit import bisect
from ..limit.analysis import SafetyFactor, relative_gap, strength_reduction
from ..limit.mesh import TriMesh
from .action import LimitInput
from .bracket import _associated, _plain, initial_mesh
from .problem import LimitProblem, limit_problem

__all__ = ["SafetyFactorResult", "safety_factor"]


@dataclass
class SafetyFactorResult:
    """The strength-reduction factor of safety of a scene or a site as a certified bracket F* in [``f_lb``,
    ``f_ub``] (:func:`ssi.limit.strength_reduction`: c / F and tan phi / F of the soil and the contact):
    under the soil's weight, the dead loads and 1 x the scaled loads (a site with no loads: its weight
    alone, e.g. a slope's own factor). ``f_lb`` a factor whose reduced problem has a certified lower bound
    carrying them, ``f_ub`` one with a kinematically admissible mechanism; ``davis``: the Davis materials
    were reduced (else the associated ones); ``mesh`` the last mesh; ``trials`` the (bound, F, lambda)
    solves; ``result`` the :class:`ssi.limit.SafetyFactor` (history per mesh, ``converged``, ``reason``);
    ``time`` [s]."""

    f_lb: float
    f_ub: float
    davis: bool
    mesh: TriMesh
    trials: list
    time: float
    problem: LimitProblem
    result: SafetyFactor | None = None

    @property
    def n_triangles(self) -> int:
        return self.mesh.n_el

    @property
    def gap(self) -> float:
        return relative_gap(self.f_lb, self.f_ub)

    @property
    def converged(self) -> bool:
        return bool(self.result is not None and self.result.converged)

    @property
    def reason(self) -> str:
        return "" if self.result is None else self.result.reason

    def contains(self, value: float) -> bool:
        return bool(self.f_lb <= value <= self.f_ub)

    def to_dict(self) -> dict:
        return {
            "kind": "safety_factor",
            "f_lower": _plain(float(self.f_lb)),
            "f_upper": _plain(float(self.f_ub)),
            "gap": _plain(float(self.gap)),
            "converged": self.converged,
            "reason": self.reason,
            "davis": self.davis,
            "loads": self.problem.reference,
            "n_triangles": int(self.n_triangles),
            "meshes": []
            if self.result is None
            else [{k: _plain(v) for k, v in r.items()} for r in self.result.history],
            "bound_solves": len(self.trials),
            "time_s": float(self.time),
        }

    def summary(self) -> str:
        kind = "Davis materials" if self.davis else "associated materials"
        if self.result is None or self.converged:
            state = "gap reached"
        else:
            state = f"gap NOT reached: {self.reason}"
        meshes = 1 if self.result is None else len(self.result.history)
        return (
            f"factor of safety (strength reduction, {kind}) F in [{self.f_lb:.3f}, {self.f_ub:.3f}], gap "
            f"{100 * self.gap:.2f} % ({state})\n  under {self.problem.reference} at load factor 1\n  "
            f"{self.n_triangles} triangles ({meshes} meshes), {len(self.trials)} bound solves, "
            f"{self.time:.1f} s"
        )


def safety_factor(
    scene: LimitInput,
    phase: str | None = None,
    h: float | None = None,
    h_min: float | None = None,
    refine: int = 0,
    rel_tol: float | None = None,
    gap: float = 0.02,
    max_steps: int = 8,
    max_elements: int = 20000,
    davis: bool = True,
    strip: str | None = None,
    side_soil: str | None = None,
    progress=None,
) -> SafetyFactorResult:
    """The factor of safety of a scene or a site by strength reduction, a certified bracket
    (:func:`ssi.limit.strength_reduction`, every load scaled together: the programs stay bounded): the
    loads are the soil's weight, the dead loads and the scaled phase's loads at factor 1; a Site without
    loads is asked for its own factor under its weight (a slope). Of a Settlement push there is no load to
    carry: refused. From the initial mesh of :func:`limit_analysis` (bisected uniformly ``refine`` times)
    the mesh is refined adaptively until the relative gap (F_U - F_L)/(F_U + F_L) <= ``gap`` or
    ``max_steps`` / ``max_elements``; ``rel_tol`` given: one mesh only, each bound searched to that relative
    width in F (the former one-mesh form). ``davis``: reduce the Davis materials (the conventional value for
    psi < phi); else the associated ones. ``strip``, ``side_soil``: as in :func:`limit_analysis` (the
    beam's M_p is not reduced). ``progress(row)``: once per mesh."""
    problem = limit_problem(scene, phase, strip, side_soil, unloaded=True)
    if problem.lam_unit:
        raise ValueError(
            f"phase {problem.phase!r} is a Settlement push: it has no load to carry at factor 1, so no "
            "factor of safety; give the phase force loads (ColumnLoad, StripLoad, SurfacePressure)"
        )
    refine = check_int("refine", refine, lo=0, hi=6)
    if rel_tol is not None:
        rel_tol = check_real("rel_tol", rel_tol, lo=0.0, lo_open=True, hi=0.5)
        gap, max_steps = 5.0 * rel_tol, 0
    gap = check_real("gap", gap, lo=0.0, lo_open=True, hi=1.0)
    max_steps = check_int("max_steps", max_steps, lo=0)
    t0 = time.perf_counter()
    mesh = initial_mesh(problem, h, h_min)
    for _ in range(refine):
        mesh = bisect(mesh, np.ones(mesh.n_el, bool))
    site = problem.site.davis() if davis else problem.site.map_materials(_associated)
    res = strength_reduction(
        site, mesh, gap=gap, max_steps=max_steps, max_elements=max_elements, progress=progress
    )
    trials = [(t["bound"], t["F"], t["lam"]) for t in res.trials]
    return SafetyFactorResult(
        res.f_lower, res.f_upper, davis, res.mesh, trials, time.perf_counter() - t0, problem, res
    )
