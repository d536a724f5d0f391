"""The capacity of a :class:`~ssi.scene.Scene` or a :class:`~ssi.scene.site.Site` as a certified bracket:
the input turned into a limit-analysis problem (:mod:`ssi.limit`, :mod:`ssi.capacity.problem`) and solved
for both bounds, associated and Davis.

    cap = scene.limit_analysis(gap=0.02)       # or ssi.capacity.limit_analysis(scene, ...)
    print(cap.summary())
    cap.lb, cap.ub                             # associated bracket of the load factor lambda
    cap.lb_davis, cap.ub_davis                 # Davis bracket (the conventional value for psi < phi)

An :class:`ssi.scene.site.Site` (any layering and ground, several strips) maps the same way through its own
:meth:`Site.geometry` (see :mod:`ssi.capacity.problem`): ``site.limit_analysis(gap=0.02)``.

What lambda scales. The loads of one phase (``phase``: a name of ``Scene.phases``, or "loads" for
``Scene.loads``; None: the last phase) are the reference loads, multiplied by lambda; the loads of the
phases before it act at the factors they have at that phase's end (dead loads), and so do the surcharge and
the soil's weight. A phase that pushes a rigid footing down (a :class:`Settlement` of a
:class:`RigidFooting`, or of a whole plate strip) has no force to scale: lambda is then the footing's
vertical force [N/m] (of a symmetric scene, the whole footing's, like :meth:`BuiltScene.contact_force`).

The mapping (what lambda scales, what is held, what is refused) is :mod:`ssi.capacity.problem`'s. Of a site
with several strips lambda scales every strip's loads at once; each foundation's own force at the bracket's
factors is :meth:`CapacityResult.foundation_forces`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from ..core.validate import check_int, check_optional_real, check_real
from ..limit import Interface, Material, triangulate
from ..limit.analysis import AdaptiveResult, adaptive_pair
from ..limit.mesh import TriMesh, fans_at
from .action import LimitInput
from .problem import LimitProblem, limit_problem

__all__ = ["CapacityResult", "capacity_bracket", "initial_mesh", "limit_analysis"]


def initial_mesh(problem: LimitProblem, h: float | None, h_min: float | None) -> TriMesh:
    pts = problem.site.points
    size = float(np.max(pts.max(axis=0) - pts.min(axis=0)))
    h = size / 6.0 if h is None else check_real("h", h, lo=0.0, lo_open=True, unit="m")
    if h_min is None:
        h_min = max(problem.footing_width, size / 10.0) / 8.0
    h_min = check_real("h_min", h_min, lo=0.0, lo_open=True, unit="m")
    sing = np.array(problem.singular, float).reshape(-1, 2)
    if not len(sing):
        return triangulate(problem.site, h)

    def graded(p):
        d = np.min(np.hypot(p[:, None, 0] - sing[None, :, 0], p[:, None, 1] - sing[None, :, 1]), axis=1)
        return h_min + 0.3 * d

    return triangulate(problem.site, h, size=graded, fans=fans_at(problem.site, sing, 2.0 * h_min))


@dataclass
class CapacityResult:
    """Both brackets of a scene's collapse load factor lambda (see :mod:`ssi.capacity.bracket`).

    ``lb``, ``ub``: the **associated** bracket (psi = phi everywhere): rigorous bounds of the associated
    material's collapse load, and ``ub`` a rigorous ceiling of the scene's for the user's psi <= phi
    (Radenkovic); ``lb_davis``, ``ub_davis``: the **Davis** bracket (c* = beta c, tan phi* = beta tan phi,
    soil and contact), the conventional engineering value for psi < phi (equal to the associated one when
    everything is associated). lambda in ``problem.lam_unit`` ("N/m": the footing's vertical force; "": a
    factor of ``problem.reference``). ``associated``/``davis``: the adaptive runs (:class:`ssi.limit.
    AdaptiveResult`; ``davis`` None when the scene is associated); ``time`` [s] wall time of both."""

    problem: LimitProblem
    associated: AdaptiveResult
    davis: AdaptiveResult | None
    time: float
    gap_target: float | None = None  # the relative gap asked for (None: not recorded)

    @property
    def lb(self) -> float:
        return self.associated.lb

    @property
    def ub(self) -> float:
        return self.associated.ub

    @property
    def gap(self) -> float:
        """(ub - lb) / (ub + lb) of the associated bracket."""
        return self.associated.gap

    @property
    def _d(self) -> AdaptiveResult:
        return self.associated if self.davis is None else self.davis

    @property
    def lb_davis(self) -> float:
        return self._d.lb

    @property
    def ub_davis(self) -> float:
        return self._d.ub

    @property
    def gap_davis(self) -> float:
        return self._d.gap

    @property
    def mesh(self) -> TriMesh:
        """The last (finest) mesh of the associated run."""
        return self.associated.final.mesh

    @property
    def n_triangles(self) -> int:
        return self.mesh.n_el

    @property
    def n_cones(self) -> tuple[int, int]:
        """(lower, upper) bound cones on the last associated mesh."""
        last = self.associated.history[-1]
        return last["cones_lb"], last["cones_ub"]

    @property
    def iterations(self) -> tuple[int, int]:
        """(lower, upper) Clarabel iterations, summed over the associated run's meshes."""
        h = self.associated.history
        return sum(r["it_lb"] for r in h), sum(r["it_ub"] for r in h)

    @property
    def velocity(self) -> np.ndarray:
        """The collapse mechanism (upper bound), (n_nodes + n_edges, 2) [m/s at unit reference power]: the
        velocities of the mesh's corner nodes then of its edges' midside nodes."""
        return self.associated.final.upper.velocity

    @property
    def dissipation(self) -> np.ndarray:
        """Each triangle's plastic dissipation (n_el,) [in lambda units: their sum less the dead loads'
        power is the upper bound]."""
        return self.associated.final.upper.dissipation

    @property
    def stress(self) -> np.ndarray:
        """The certified lower-bound stress field (n_el, 3 vertices, 3: sig_x, sig_z, tau) [Pa]."""
        return self.associated.final.lower.stress

    def foundation_forces(self) -> list[dict]:
        """Each foundation's downward force at the bracket's factors, lambda times its own loads [N/m]: one
        dict per footing (the order of ``problem.site.footings``, a site's strips) with ``x0``, ``x1`` [m],
        ``reference`` [N/m] its loads at lambda = 1, ``associated`` and ``davis`` (lb F, ub F) [N/m]. A
        site's strips share one lambda, so these sum to the total, but the mechanism that sets lambda may be
        one strip's. Empty for a push (lambda is then itself the footing's force)."""
        p = self.problem
        if p.lam_unit:
            return []
        return [
            {
                "x0": float(x0),
                "x1": float(x1),
                "reference": float(f),
                "associated": (self.lb * f, self.ub * f),
                "davis": (self.lb_davis * f, self.ub_davis * f),
            }
            for (x0, x1), f in zip(p.footing_spans, p.ref_forces)
        ]

    def contains(self, value: float) -> bool:
        """Whether ``value`` (lambda units) lies in the associated bracket."""
        return bool(self.lb <= value <= self.ub)

    def to_dict(self) -> dict:
        """The numbers as plain data (JSON): both brackets in lambda units, what lambda scales, the mesh
        and solver counts, the time [s] and each run's history (one row per mesh)."""

        def rows(run):
            return None if run is None else [{k: _plain(v) for k, v in r.items()} for r in run.history]

        p = self.problem
        return {
            "phase": p.phase,
            "lambda_unit": p.lam_unit or "factor of the phase's loads",
            "reference": p.reference,
            "reference_footing_force_N_per_m": p.ref_force or None,
            "lb": _plain(self.lb),
            "ub": _plain(self.ub),
            "gap": _plain(self.gap),
            "lb_davis": _plain(self.lb_davis),
            "ub_davis": _plain(self.ub_davis),
            "gap_davis": _plain(self.gap_davis),
            "associated": self.davis is None,
            "triangles": self.n_triangles,
            "cones_lb_ub": list(self.n_cones),
            "iterations_lb_ub": list(self.iterations),
            "time_s": self.time,
            "history_associated": rows(self.associated),
            "history_davis": rows(self.davis),
            "gap_target": self.gap_target,
            "reason_associated": self.associated.reason,
            "reason_davis": None if self.davis is None else self.davis.reason,
            "strip": self.strip,
            "strip_mp_sag_hog_N_m_per_m": self.strip_mp,
            "foundation_forces_N_per_m": [
                {k: [_plain(v) for v in val] if isinstance(val, tuple) else val for k, val in row.items()}
                for row in self.foundation_forces()
            ],
        }

    @property
    def strip(self) -> str | None:
        """How the foundation enters the limit analysis: "beam" (plastic hinges), "rigid" or None (none)."""
        fts = self.problem.site.footings
        if not fts:
            return None
        return "beam" if any(ft.beam is not None for ft in fts) else "rigid"

    @property
    def strip_mp(self) -> list | None:
        """[M_p sagging, M_p hogging] [N m/m] of a beam strip's hinges (None: no beam)."""
        beams = [ft.beam for ft in self.problem.site.footings if ft.beam is not None]
        return [beams[0].mp_sag, beams[0].mp_hog] if beams else None

    def summary(self) -> str:
        """A few lines an engineer reads: both brackets in kN/m (a Settlement push) or as factors of the
        loads they scale (with the footing force they mean), the gaps, the mesh and the time."""
        p = self.problem
        d = self.davis is not None
        if p.lam_unit == "N/m":
            head = "capacity: the footing's vertical force V (Settlement push), kN/m"
            k, unit = 1e-3, " kN/m"
        else:
            head = f"capacity: load factor lambda of {p.reference}"
            k, unit = 1.0, ""
        lines = [
            head,
            f"  associated [{k * self.lb:.4g}, {k * self.ub:.4g}]{unit}  gap {100 * self.gap:.2f} %  "
            "(rigorous for psi = phi; a ceiling for any psi <= phi)",
            f"  Davis      [{k * self.lb_davis:.4g}, {k * self.ub_davis:.4g}]{unit}  gap "
            f"{100 * self.gap_davis:.2f} %  "
            + ("(psi < phi: the conventional engineering value)" if d else "(= associated: psi = phi)"),
        ]
        if self.strip_mp is not None:
            ms, mh = (m / 1e3 for m in self.strip_mp)
            mn = any(ft.beam is not None and ft.beam.axial for ft in p.site.footings)
            lines.append(
                f"  strip: a beam with plastic hinges, M_p {ms:.4g} kN m/m sagging, {mh:.4g} hogging (its RC "
                + ("section at N = 0, and its M-N polygon" if mn else "section at N = 0")
                + "; strip='rigid' ignores its bending)"
            )
        if p.lam_unit == "N/m" and p.footing_width:
            b = p.footing_width * (2.0 if p.symmetric else 1.0)
            lines.append(
                f"  mean pressure over B = {b:g} m: associated [{self.lb / b / 1e3:.4g}, "
                f"{self.ub / b / 1e3:.4g}] kPa, Davis [{self.lb_davis / b / 1e3:.4g}, "
                f"{self.ub_davis / b / 1e3:.4g}] kPa"
            )
        elif len(p.ref_forces) > 1:  # one lambda for every strip: each foundation's force at it
            for i, row in enumerate(self.foundation_forces()):
                (al, au), (dl, du) = ((v / 1e3 for v in row[k]) for k in ("associated", "davis"))
                lines.append(
                    f"  foundation {i} (x = [{row['x0']:g}, {row['x1']:g}] m, its loads "
                    f"{row['reference'] / 1e3:.4g} kN/m): force on top of the held loads associated "
                    f"[{al:.4g}, {au:.4g}] kN/m, Davis [{dl:.4g}, {du:.4g}] kN/m"
                )
        elif p.ref_force:
            f = p.ref_force / 1e3
            lines.append(
                f"  footing force on top of the held loads: associated [{self.lb * f:.4g}, "
                f"{self.ub * f:.4g}] kN/m, Davis [{self.lb_davis * f:.4g}, {self.ub_davis * f:.4g}] kN/m"
            )
        for name, run in (("associated", self.associated), ("Davis", self.davis)):
            if run is not None and not np.isfinite(run.ub):
                up = run.final.upper
                lines.append(
                    f"  no {name} upper bound: the velocity field of the last mesh is not a mechanism "
                    f"(solver status {up.status}, flow-rule residual {up.flow_residual:.2g}); none may exist "
                    "(e.g. a footing confined across the whole block under a centred load): the capacity is "
                    "then unbounded, and the lower bound is only what was proven"
                )
        for name, run in (("associated", self.associated), ("Davis", self.davis)):
            if run is not None and not run.converged and run.reason:
                asked = "" if self.gap_target is None else f" of {100 * self.gap_target:.3g} %"
                lines.append(
                    f"  {name} gap target{asked} NOT reached: {run.reason} (raise --max-elements, or read "
                    "the bracket as it stands: both bounds are certified)"
                )
        cl, cu = self.n_cones
        il, iu = self.iterations
        lines.append(
            f"  {self.n_triangles} triangles ({len(self.associated.history)} meshes), cones LB {cl} UB {cu}, "
            f"solver iterations LB {il} UB {iu}, {self.time:.1f} s"
        )
        return "\n".join(lines)


def limit_analysis(
    scene: LimitInput,
    phase: str | None = None,
    gap: float = 0.02,
    h: float | None = None,
    h_min: float | None = None,
    max_elements: int = 20000,
    max_steps: int = 12,
    davis: bool = True,
    progress=None,
    strip: str | None = None,
    side_soil: str | None = None,
) -> CapacityResult:
    """The scene's capacity as a certified bracket (module docstring): the associated bracket refined until
    its relative gap (ub - lb)/(ub + lb) <= ``gap`` (or ``max_elements`` triangles / ``max_steps``
    refinements), then, for a non-associated scene and ``davis``, the Davis bracket likewise. ``h`` [m]
    the largest initial triangle (default: the block's size / 6), ``h_min`` [m] at the footing's and loads'
    ends (default: max(footing width, size / 10) / 8). ``progress(label, row)`` is called once per mesh
    (label "associated" or "Davis", row of :attr:`ssi.limit.AdaptiveResult.history`). ``strip``: a plate
    strip "rigid", a "beam" with plastic hinges of M_p at N = 0 or "beam_mn" with its section's M-N
    polygon (None: a beam for a ductile RC section; :func:`ssi.capacity.problem.limit_problem`).
    ``side_soil``: an embedded strip's side soil as its overburden on the base level ("surcharge": the
    bracket of a strengthless backfill, Terzaghi's assumption, whose lower bound is a lower bound of the
    scene) or modelled with its strength ("soil"; this package's README.md, *Embedment*); None:
    "surcharge" for a Scene, "soil" for a Site."""
    gap = check_real("gap", gap, lo=0.0, lo_open=True, hi=1.0)
    check_optional_real("h", h, lo=0.0, lo_open=True, unit="m")
    check_optional_real("h_min", h_min, lo=0.0, lo_open=True, unit="m")
    max_elements = check_int("max_elements", max_elements, lo=1)
    max_steps = check_int("max_steps", max_steps, lo=0)
    problem = limit_problem(scene, phase, strip, side_soil)
    t0 = time.perf_counter()
    mesh = initial_mesh(problem, h, h_min)

    kw = dict(gap=gap, max_elements=max_elements, max_steps=max_steps, lazy=True)
    assoc_site = problem.site.map_materials(lambda m: _associated(m))
    assoc_site = assoc_site.map_interfaces(_associated_interface)
    non_assoc = any(not m.associated for m in problem.site.materials) or any(
        itf.kind == "coulomb" and itf.psi_deg not in (None, itf.phi_deg) for itf in problem.site.interfaces
    )
    # the Davis run from the associated run's last mesh (ssi.limit.adaptive_pair)
    dav_site = problem.site.davis() if davis and non_assoc else None
    res, dav = adaptive_pair(assoc_site, dav_site, mesh, progress=progress, **kw)
    return CapacityResult(problem, res, dav, time.perf_counter() - t0, gap)


def _plain(v):
    """A JSON value: numpy scalars as Python ones, a non-finite number (no certified bound) as None."""
    if isinstance(v, np.generic):
        v = v.item()
    if isinstance(v, float) and not np.isfinite(v):
        return None
    return v


def _associated(m: Material) -> Material:
    return replace(m, psi_deg=None)


def _associated_interface(i: Interface) -> Interface:
    return replace(i, psi_deg=None)


def _finite(v) -> float | None:
    return None if v is None or not math.isfinite(float(v)) else float(v)


def capacity_bracket(scene: LimitInput, gap: float = 0.05, max_elements: int = 6000) -> dict:
    """The capacity bracket of the scene's (or site's) loads as plain data, or ``{"not_computed": why}``
    when the limit analysis refuses the problem (the refusal's own message: it names the part)."""
    t0 = time.perf_counter()
    try:
        cap = scene.limit_analysis(gap=gap, max_elements=max_elements)
    except (ValueError, NotImplementedError, TypeError) as err:
        return {"not_computed": str(err)}
    p = cap.problem
    return {
        "unit": p.lam_unit or "",
        "reference": p.reference,
        "lb": _finite(cap.lb),
        "ub": _finite(cap.ub),
        "gap": _finite(cap.gap),
        "lb_davis": _finite(cap.lb_davis),
        "ub_davis": _finite(cap.ub_davis),
        "gap_davis": _finite(cap.gap_davis),
        "davis": cap.davis is not None,
        "gap_target": gap,
        "reason": cap.associated.reason if cap.davis is None else cap.davis.reason,
        "n_triangles": int(cap.n_triangles),
        "time_s": time.perf_counter() - t0,
        "never_yield": elastic_parts(scene),
        # the lower-bound program unbounded: every load factor has a statically admissible field, so no
        # mechanism exists (each would cross soil that never yields): the capacity is infinite, certified
        "no_mechanism": bool(math.isinf(float(cap.lb_davis if cap.davis is not None else cap.lb))),
    }


def elastic_parts(scene: LimitInput) -> list[str]:
    """The names of the scene's (or site's) elastic soils (``c=None``), which the bracket takes as never
    yielding, as the incremental model does: a user who means them to fail must give their strength."""
    owner, n_layers = type(scene).__name__, len(scene.layers)
    return [
        f"{owner}.layers[{i}]" if i < n_layers else f"{owner}.lenses[{i - n_layers}]"
        for i, soil in enumerate(scene.soils())
        if soil.c is None
    ]
