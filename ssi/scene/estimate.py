"""Error estimates of a scene's answers: re-solve on systematically refined copies, Richardson extrapolation.

    from ssi.scene.estimate import estimate
    est = estimate(scene)                 # mesh h/2, h/4; steps x2, x4; plate layers x2, x4
    print(est)                            # value, estimated error, observed order and cost per quantity

The quantity the user asked for leads: of a push-over (a scene driven by a prescribed ``Settlement``) the
capacity (:meth:`SceneResult.capacity`: the footing load at the peak or plateau of the path; the prescribed
settlement is an input, not an answer, and is left out), of a load-controlled scene the largest settlement.
``solve_with_error`` and ``solve_to_target`` attach the capacity's estimate to the result they return
(``out.capacity_error``), and a capacity whose estimated error exceeds 5 % carries a warning there
(``out.capacity()["warning"]``, printed in the summary).

A discretisation parameter ``h`` (element size, load increment, plate layer thickness) is halved twice, giving
three answers q0 (the scene as given), q1 (h/2), q2 (h/4) of every headline quantity. If the error behaves as
``C h^p`` (the asymptotic range), the differences d1 = q1 - q0 and d2 = q2 - q1 shrink by 2^p, so

    p = log2(d1 / d2)                                  (observed order)
    q0 - q_exact ~ d1 * 2^p / (2^p - 1)                (error of the scene as given)
    q2 - q_exact ~ d2 / (2^p - 1)                      (error of the finest copy)

The three refinements are estimated one at a time from the same base solve and their error estimates are
added (a bound when the contributions do not cancel). Where d1 and d2 differ in sign, or p lies outside
[``ORDER_MIN``, ``ORDER_MAX``], the sequence is not in the asymptotic range and the estimate is flagged, never
silently used. A refinement that changes nothing (the load steps of a linear scene, the layers of an elastic
homogeneous strip) contributes zero error.

:func:`solve_to_target` fits each refinement's error C h^p from that estimate, picks the cheapest number of
halvings per refinement predicted to bring the asked quantities below ``target_error``, solves it and returns
it with the predicted error; it stops with a message when an observed order is not asymptotic. Solves are
cached by refinement level, so a level already solved for the estimate is not solved again. It lives in
:mod:`ssi.scene.estimate_target`; the Richardson analysis of three answers (:func:`richardson`) in
:mod:`ssi.scene.richardson`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..elements.section import Section, layered
from ..solver import Settings
from .richardson import NOISE, ROUND_OFF, richardson
from .view_load_path import capacity_error_warning

REFINEMENTS = ("mesh", "steps", "layers")
QUANTITIES = (
    "capacity",
    "max_settlement",
    "differential_settlement",
    "max_contact_pressure",
    "max_moment",
    "limit_load_factor",
)
UNITS = {
    "capacity": "N/m",
    "max_settlement": "m",
    "differential_settlement": "m",
    "max_contact_pressure": "Pa",
    "max_moment": "N m/m",
    "limit_load_factor": "-",
}


# the Richardson analysis itself (pure arithmetic on three answers) is richardson.py's
# ---- refined copies of a scene ---------------------------------------------------------------------------
def split_section(section: Section, factor: int = 2) -> Section:
    """The ``section`` with every layer split into ``factor`` equal layers (same faces, kinds, parameters)."""
    if int(factor) != factor or factor < 1:
        raise ValueError(f"factor must be an integer >= 1, got {factor}")
    f = int(factor)
    order = np.argsort(section.z_mid)
    rep = np.repeat(order, f)
    labels = tuple(section.labels[i] for i in rep) if section.labels else ()
    return layered(
        section.h[rep] / f,
        section.kind[rep],
        list(section.params[rep]),
        carries_shear=section.carries_shear[rep],
        z_ref=-section.z_bottom,
        labels=labels,
    )


def refined_scene(scene, mesh: int = 0, layers: int = 0):
    """A copy of ``scene`` with the element sizes halved ``mesh`` times (h_fine and h_coarse) and every plate
    layer split in 2^``layers``; the scene itself is not changed."""
    if mesh < 0 or layers < 0:
        raise ValueError(f"refinement levels must be >= 0, got mesh={mesh}, layers={layers}")
    out = replace(
        scene,
        mesh=replace(scene.mesh, h_fine=scene.mesh.h_fine / 2**mesh, h_coarse=scene.mesh.h_coarse / 2**mesh),
    )
    if layers:  # every plate strip's layers split (a scene or site without one: unchanged)
        out = out.with_sections(lambda section: split_section(section, 2**layers))
    return out


def refined_steps(n_steps: int | None, settings: Settings | None, level: int):
    """(n_steps, settings) with the load increments halved ``level`` times: 2^level times the equal load
    levels, and the automatic stepping's first, largest and smallest increments divided by 2^level."""
    s = settings or Settings()
    f = 2**level
    n = None if n_steps is None else int(n_steps) * f
    return n, replace(s, first_step=s.first_step / f, max_step=s.max_step / f, min_step=s.min_step / f)


# ---- headline quantities ---------------------------------------------------------------------------------
def asked_quantity(result) -> str:
    """The quantity a scene is solved for: ``"capacity"`` of a push-over (:attr:`SceneResult.is_push_over`),
    ``"max_settlement"`` of a load-controlled scene."""
    return "capacity" if result.is_push_over else "max_settlement"


def headline(result) -> dict:
    """The headline quantities of a :class:`~ssi.scene.SceneResult` at its last step: of a push-over
    ``capacity`` [N/m] (:meth:`SceneResult.capacity`'s load) in place of ``max_settlement`` (its prescribed
    settlement: an input); else ``max_settlement`` [m]; with a plate strip ``differential_settlement`` [m]
    (largest minus smallest settlement along the strip), ``max_contact_pressure`` [Pa], ``max_moment``
    [N m/m] (largest |M| in the strip) and
    ``limit_load_factor`` [-] (only when a limit load was reached). A scene without foundation has only
    the surface's ``max_settlement``. Of a site (:class:`~ssi.scene.SiteResult`) the same quantities over
    its plate strips: the largest settlement, differential settlement (between strips, and along each),
    contact pressure and |moment|."""
    if result.kind == "site":
        return _site_headline(result)
    if result.is_push_over:
        out = {"capacity": result.capacity()["load"]}
    else:
        out = {"max_settlement": result.max_settlement()[1]}
    if result.built.plate is not None:
        s = result.settlement()[1]
        out["differential_settlement"] = float(s.max() - s.min())
        out["max_contact_pressure"] = float(np.nanmax(-result.contact()["sig_n"]))
        out["max_moment"] = float(np.max(np.abs(result.strip_forces()["M"])))
    if result.limit_load_factor is not None:
        out["limit_load_factor"] = float(result.limit_load_factor)
    return out


def _site_headline(result) -> dict:
    """:func:`headline` of a site of plate strips, loaded (a RigidStrip's settlement or a Push is an input,
    not an answer: refused by name)."""
    if result.is_push_over:
        raise ValueError(
            "the error estimate of a site driven by a RigidStrip's settlement or a Push is not available "
            "(its settlement is an input); estimate a site of loaded plate strips"
        )
    views = [result.foundation_result(i) for i in range(len(result.built.strips))]
    means = [v.settlement_summary()["mean"] for v in views]
    along = [float(np.ptp(v.settlement()[1])) for v in views]
    out = {
        "max_settlement": max(v.settlement_summary()["max"] for v in views),
        "differential_settlement": max(along + [max(means) - min(means)]),
        "max_contact_pressure": max(float(np.nanmax(-v.contact()["sig_n"])) for v in views),
        "max_moment": max(v.max_abs_moment()[1] for v in views),
    }
    if result.limit_load_factor is not None:
        out["limit_load_factor"] = float(result.limit_load_factor)
    return out


# ---- the estimate ----------------------------------------------------------------------------------------
@dataclass
class Level:
    """One solve: refinement ``key`` (mesh, steps, layers halvings), ``values`` headline quantities,
    ``wall_time`` [s], ``n_dof``, ``status``, and the SceneResult ``result``."""

    key: tuple
    values: dict
    wall_time: float
    n_dof: int
    status: str
    result: object = field(repr=False, default=None)


@dataclass
class ErrorEstimate:
    """Error estimate of a scene's headline quantities.

    ``value`` {quantity: value of the scene as given}; ``parts`` {refinement: {quantity: Richardson}};
    ``error`` {quantity: summed |estimated error| of the scene as given}; ``relative`` {quantity: error /
    |value|}; ``cost`` {refinement: wall time [s] of its two refined solves}; ``levels`` every solve;
    ``asymptotic`` {quantity: every refinement asymptotic}; ``quantity`` the quantity asked for
    (:func:`asked_quantity`: the capacity of a push-over, else the largest settlement)."""

    value: dict
    parts: dict
    levels: dict
    base_key: tuple = (0, 0, 0)
    quantity: str = "max_settlement"

    @property
    def extrapolated(self) -> dict:
        """{quantity: value of the scene as given minus every refinement's estimated error}: the
        Richardson estimate of the converged value (units of the quantity)."""
        return {
            q: v - sum(p[q].error_base for p in self.parts.values() if q in p) for q, v in self.value.items()
        }

    def capacity_error(self) -> dict | None:
        """The capacity's estimate as a result carries it (``SceneResult.capacity_error``), None if the
        scene answers no capacity: ``relative`` estimated relative error of the scene as given, ``error``
        [N/m], ``extrapolated`` [N/m], ``values`` [N/m] of the mesh refinement's levels h, h/2, h/4 (None
        when the mesh was not refined), ``order`` its observed order, ``asymptotic``, ``refinements``."""
        q = "capacity"
        if q not in self.value:
            return None
        mesh = self.parts.get("mesh", {}).get(q)
        return {
            "relative": float(self.relative[q]),
            "error": float(self.error[q]),
            "extrapolated": float(self.extrapolated[q]),
            "values": None if mesh is None else [float(v) for v in mesh.values],
            "order": None if mesh is None else float(mesh.order),
            "asymptotic": bool(self.asymptotic[q]),
            "refinements": list(self.parts),
            "how": "Richardson extrapolation over halvings of h (ssi.scene.estimate)",
        }

    def to_dict(self) -> dict:
        """The estimate as plain numbers (what a result file, the JSON summary and the report keep):
        ``asked`` the quantity asked for, ``refinements``, ``quantities`` {quantity: {``unit``, ``value``
        (the scene as given), ``error`` (summed |estimated error|), ``relative``, ``extrapolated``,
        ``asymptotic``, ``orders`` {refinement: observed order (nan: changed nothing or resolved to the
        noise)}, ``values`` {refinement: [h, h/2, h/4]}}}, ``cost_s`` {refinement: wall time of its two
        refined solves [s]}."""
        return {
            "asked": self.quantity,
            "refinements": list(self.parts),
            "quantities": {
                q: {
                    "unit": UNITS.get(q, ""),
                    "value": float(v),
                    "error": float(self.error[q]),
                    "relative": float(self.relative[q]),
                    "extrapolated": float(self.extrapolated[q]),
                    "asymptotic": bool(self.asymptotic[q]),
                    "orders": {r: float(p[q].order) for r, p in self.parts.items() if q in p},
                    "values": {r: [float(x) for x in p[q].values] for r, p in self.parts.items() if q in p},
                }
                for q, v in self.value.items()
            },
            "cost_s": {r: float(c) for r, c in self.cost.items()},
            "how": "Richardson extrapolation over halvings of h, h/2, h/4 (ssi.scene.estimate)",
        }

    @property
    def error(self) -> dict:
        return {q: sum(abs(p[q].error_base) for p in self.parts.values() if q in p) for q in self.value}

    @property
    def relative(self) -> dict:
        return {q: self.error[q] / abs(v) if v else math.inf for q, v in self.value.items()}

    @property
    def asymptotic(self) -> dict:
        return {q: all(p[q].asymptotic for p in self.parts.values() if q in p) for q in self.value}

    @property
    def cost(self) -> dict:
        return {
            name: sum(self.levels[k].wall_time for k in _keys(self.base_key, name)[1:]) for name in self.parts
        }

    @property
    def base_wall_time(self) -> float:
        return self.levels[self.base_key].wall_time

    def worst_refinement(self, quantities) -> str:
        """The refinement whose estimated error (relative, summed over ``quantities``) is largest."""
        return max(
            self.parts,
            key=lambda r: sum(
                abs(self.parts[r][q].error_base) / abs(self.value[q])
                for q in quantities
                if q in self.parts[r] and self.value[q]
            ),
        )

    def __str__(self) -> str:
        lines = [
            f"{'quantity':24s} {'value':>12s} {'error':>10s} {'rel':>8s}  "
            + "  ".join(f"{r + ' (p)':>14s}" for r in self.parts)
        ]
        for q, v in self.value.items():
            orders = "  ".join(
                f"{self.parts[r][q].order:14.2f}" if q in self.parts[r] else f"{'-':>14s}" for r in self.parts
            )
            flag = "" if self.asymptotic[q] else "  (not asymptotic)"
            lines.append(f"{q:24s} {v:12.5g} {self.error[q]:10.3g} {self.relative[q]:8.2%}  {orders}{flag}")
        q = self.quantity
        if q in self.value:
            unit = UNITS.get(q, "")
            for r, part in self.parts.items():
                if q in part:
                    lines.append(
                        f"{q} over {r} halvings (h, h/2, h/4): "
                        + ", ".join(f"{v:.6g}" for v in part[q].values)
                        + f" {unit}; extrapolated {part[q].extrapolated:.6g} {unit}; observed order "
                        f"{part[q].order:.2f}"
                    )
            lines.append(
                f"{q}: {self.value[q]:.6g} {unit} as given, {self.extrapolated[q]:.6g} {unit} extrapolated, "
                f"estimated error {self.relative[q]:.2%}"
            )
            warning = capacity_error_warning(self.capacity_error()) if q == "capacity" else None
            if warning:
                lines.append("WARNING: " + warning)
        lines.append(
            f"cost [s]: base {self.base_wall_time:.2f}, "
            + ", ".join(f"{r} {c:.2f}" for r, c in self.cost.items())
        )
        return "\n".join(lines)


def _keys(base, name):
    i = REFINEMENTS.index(name)
    return [tuple(b + (j if n == i else 0) for n, b in enumerate(base)) for j in range(3)]


class RefinedSolver:
    """Solves refined copies of one scene, cached by ``key`` = (mesh, steps, layers) halvings:
    ``solver(key)`` returns the :class:`Level`; ``solver.cache`` holds every level solved."""

    def __init__(self, scene, n_steps, settings):
        self.scene, self.n_steps, self.settings = scene, n_steps, settings
        self.cache: dict[tuple, Level] = {}
        self.linear = True  # every solve so far was a linear one: differences carry no iteration error

    def __call__(self, key) -> Level:
        if key not in self.cache:
            m, s, lay = key
            n, settings = refined_steps(self.n_steps, self.settings, s)
            built = refined_scene(self.scene, mesh=m, layers=lay).build()
            self.linear &= bool(built.is_linear and not self.scene.phases)
            t0 = time.perf_counter()
            out = built.solve(n_steps=n, settings=settings)
            self.cache[key] = Level(
                key, headline(out), time.perf_counter() - t0, built.model.n_dof, out.status, out
            )
        return self.cache[key]


def _check_refine(refine, scene):
    refine = tuple(refine)
    bad = [r for r in refine if r not in REFINEMENTS]
    if bad or not refine:
        raise ValueError(f"refine must be a non-empty subset of {REFINEMENTS}, got {refine}")
    if not scene.sections():  # no plate strip: no layers to split
        refine = tuple(r for r in refine if r != "layers")
    return refine


def _estimate(solver, base, refine) -> ErrorEstimate:
    base_level = solver(base)
    parts = {}
    for name in refine:
        levels = [solver(k) for k in _keys(base, name)]
        common = [q for q in base_level.values if all(q in lv.values for lv in levels)]
        noise = ROUND_OFF if solver.linear else NOISE
        parts[name] = {q: richardson(*(lv.values[q] for lv in levels), noise=noise) for q in common}
    value = {q: v for q, v in base_level.values.items() if all(q in p for p in parts.values())}
    asked = "capacity" if "capacity" in base_level.values else "max_settlement"  # see asked_quantity
    return ErrorEstimate(value, parts, dict(solver.cache), base, asked)


def estimate(
    scene, n_steps: int | None = None, settings: Settings | None = None, refine=REFINEMENTS
) -> ErrorEstimate:
    """Estimate the discretisation error of ``scene``'s headline quantities (see the module docstring).

    ``refine``: the refinements to estimate, a subset of ("mesh", "steps", "layers"); each costs two more
    solves (h/2 and h/4: the mesh ones cost about 4 and 16 times the base solve in 2D). ``n_steps`` and
    ``settings`` are those of ``BuiltScene.solve``. A quantity reached at some levels only (a limit load
    found on one mesh but not another) is left out."""
    return _estimate(RefinedSolver(scene, n_steps, settings), (0, 0, 0), _check_refine(refine, scene))


def solve_with_error(scene, n_steps: int | None = None, settings: Settings | None = None, refine=REFINEMENTS):
    """(SceneResult of the scene as given, its ErrorEstimate): the scene's own solution with
    the estimate of its error. Of a push-over the result carries its capacity's estimate
    (``out.capacity_error``; ``out.capacity()["warning"]`` when it exceeds 5 %)."""
    est = estimate(scene, n_steps, settings, refine)
    out = est.levels[est.base_key].result
    out.capacity_error = est.capacity_error()
    out.error_estimate = est.to_dict()
    return out, est


def estimate_solved(
    result, n_steps: int | None = None, settings: Settings | None = None, refine=("mesh",),
    wall_time: float = float("nan"),
) -> ErrorEstimate:  # fmt: skip
    """The :class:`ErrorEstimate` of a scene already solved (``result``, a SceneResult of
    ``result.built.scene`` solved with ``n_steps`` and ``settings``), which is the base level and is not
    solved again; only the refined copies are (h/2 and h/4 for each of ``refine``: by default the mesh, the
    error that dominates a capacity). Of a push-over the capacity's estimate is attached to ``result``
    (``result.capacity_error``). ``wall_time`` [s]: what the given solve cost (for the estimate's cost
    table; nan if unknown). What ``ssi run --estimate`` calls."""
    scene = result.built.scene  # a scene or a site
    solver = RefinedSolver(scene, n_steps, settings)
    solver.linear = bool(result.built.is_linear and not scene.phases)
    base = (0, 0, 0)
    solver.cache[base] = Level(
        base, headline(result), float(wall_time), result.built.model.n_dof, result.status, result
    )
    est = _estimate(solver, base, _check_refine(refine, scene))
    result.capacity_error = est.capacity_error()
    result.error_estimate = est.to_dict()
    return est
