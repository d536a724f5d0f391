"""The command line: ``ssi run scene.toml``, ``ssi limit scene.toml``, ``ssi show result.h5``, ``ssi schema``.

``ssi run scene.toml`` solves the scene file (see :mod:`ssi.scene.scene_file`) and writes, next to it unless
told otherwise: ``<name>.h5`` (the result, :func:`ssi.io.results.write_result`), ``<name>.pvd`` +
``<name>_steps/*.vtu`` (ParaView, every step), ``<name>_plots/*.png`` (:func:`ssi.io.plot.standard_figures`),
``<name>_summary.json`` and ``<name>_report.html`` (:mod:`ssi.io.report`: the summary with units, the
capacity, per-phase tables, warnings and the figures, one page that works offline); it prints the summary
(the foundation load and capacity, settlement, contact pressure -- mean, peak away from the edges, the edge
value marked as a singularity --, bending moment, per-phase maxima, the status, wall time). Nothing is
overwritten without ``--overwrite``. ``ssi run scene.toml --estimate`` also solves the scene at h/2 and h/4
(:func:`ssi.scene.estimate.estimate_solved`) and prints, stores and reports the estimated discretisation
error of its answer: of a push-over the capacity (a capacity whose estimated error exceeds 5 % says so),
else the settlement.
A run whose controlled path peaks is a complete answer (status "limit load reached", with the load factor
the scene carries; exit status 0). A run the solver stops before the end of its load path (a
:class:`ssi.solver.NonConvergence`) still writes everything, marked incomplete, and the command exits with
status 3. A site file (:mod:`ssi.scene.scene_file` reads both) goes the same way: its summary is per
foundation (settlement, tilt, differential settlement; of a plate strip its contact resultant, bending moment
and RC design), its status the solver's, and the same files are written. ``ssi show result.h5`` prints the
summary of a result file (a scene's or a site's) and redraws its plots and report into a new folder
(``<result>_plots_2``, ... when the run's exists; ``--overwrite``: into the run's).
``ssi limit scene.toml`` brackets the scene's capacity by finite-element limit analysis
(:meth:`ssi.scene.Scene.limit_analysis`): one line of progress per refinement, then the summary; it writes
``<name>_limit.json`` (the numbers), ``<name>_limit.h5`` (the result file: bounds, Davis bounds, gaps, the
mesh, the mechanism's velocity, the dissipation and the stress field; ``ssi show`` reads it back),
``<name>_limit.vtu`` (ParaView) and ``<name>_limit.png`` (the mechanism and the dissipation). ``--strip``
chooses how a plate strip enters (rigid, a beam with plastic hinges), ``--side-soil`` how an embedded
strip's side soil does (its overburden, or modelled with its trench walls: ``ssi limit --help``).
"""

import argparse
import functools
import json
import sys
import time
import warnings
from pathlib import Path

EXIT_INCOMPLETE = 3


def _column_loads_exist(scene) -> bool:
    loads = list(scene.loads) + [ld for ph in scene.phases for ld in ph.loads]
    return any(ld.columns() for ld in loads)


def summary(result, wall_time=None, complete=True, stop=None) -> dict:
    """The numbers ``ssi run`` prints, from a SceneResult or a SiteResult (``kind`` "scene" or "site"; a
    site's per foundation: :func:`_site_summary`): SI units (m, Pa, N/m, N m/m, s).

    ``status``: "completed" (the whole load path), "limit load reached" (the controlled path peaked: the
    path up to the limit is the answer, ``limit_load_factor`` the fraction of the loads -- of a phased scene,
    of the last phase's loads -- that the scene carries) or "stopped" (the solver failed before either;
    ``stop_reason``; ``stop_ill_posed``: the yielding soils with psi < phi whose rate problem has lost
    ellipticity there, or None). ``phase``: of a phased scene, the name of the last phase reached;
    ``phase_load_factor`` the load factor reached in it.

    Loads: ``column_load`` [N/m] the column forces applied at the end (None: the scene has no column);
    ``foundation_load`` [N/m] the load the foundation carries at the end (of a push-over the soil's
    reaction); ``capacity``: :meth:`SceneResult.capacity` (the largest load carried over rate-independent
    equilibrium states, whether it is a limit and how it was found).

    Values at the end (``max_settlement``, ``contact_resultant``, the pressures, ``max_abs_moment``) and
    over all phases: ``phases`` (:meth:`SceneResult.phase_table`, one row per phase) and ``envelope`` (the
    largest of each quantity over the phases, with the phase it occurs in). Contact pressure:
    ``mean_contact_pressure``, ``peak_contact_pressure`` (edge-excluded, with its x) and
    ``max_contact_pressure`` (the largest anywhere: the corner singularity of a stiff strip, not a bearing
    pressure).

    ``error_estimate``: :meth:`ssi.scene.estimate.ErrorEstimate.to_dict` of the result (``ssi run
    --estimate``; the capacity's part is also ``capacity["estimate"]``), ``{"failed": reason}`` when a
    refined copy could not be solved, None when not asked."""
    v = getattr(result, "verdict", None)
    if v is not None:  # a run's verdict (ssi run), first; stored in the result file for ssi show
        result.verdict = None
        try:
            return {"verdict": v, **summary(result, wall_time, complete, stop)}
        finally:
            result.verdict = v
    if result.kind == "site":
        return _site_summary(result, wall_time, complete, stop)
    x_s, s_max = result.max_settlement()
    out = {
        "kind": "scene",
        "complete": bool(complete),
        "steps": result.n_steps,
        "load_factor": float(result.load_factor[-1]),
        "max_settlement": s_max,
        "x_max_settlement": x_s,
    }
    if result.built.plate is not None:
        cp = result.contact_pressure()
        out["mean_contact_pressure"] = cp["mean"]
        out["peak_contact_pressure"] = cp["peak"]
        out["x_peak_contact_pressure"] = cp["x_peak"]
        out["max_contact_pressure"] = cp["edge"]
        out["x_max_contact_pressure"] = cp["x_edge"]
        out["contact_resultant"] = result.contact_resultant()["N"]
        forces = result.strip_forces()
        m = forces["M"]
        j = int(abs(m).argmax())
        out["max_abs_moment"] = float(abs(m).ravel()[j])
        out["x_max_abs_moment"] = float(forces["x_ax"].ravel()[j])
    last = result.phases[-1] if result.phases else None
    out["phase"] = None if last is None else last["name"]
    out["phase_load_factor"] = out["load_factor"] if last is None else float(last["result"].load_factor[-1])
    has_columns = _column_loads_exist(result.built.scene)
    out["column_load"] = float(result.column_load()[-1]) if has_columns else None
    out["foundation_load"] = float(result.foundation_load()[-1])
    out["push_over"] = result.is_push_over
    out["capacity"] = result.capacity()
    out["phases"] = result.phase_table()
    out["status"] = result.status if complete else "stopped"
    out["limit_load_factor"] = result.limit_load_factor if complete else None
    if complete and result.status == "limit load reached":
        out.update(_limit_checks(result))
    out["stopped_at_column_load"] = None if complete else out["column_load"]
    out["stop_reason"] = None if stop is None else stop.get("reason")
    out["stop_message"] = _stop_message(stop, "scene")
    # a soil whose rate problem is ill-posed at the stop (psi < phi yielding): why, and what is well posed
    out["stop_ill_posed"] = None if stop is None else stop.get("ill_posed")
    if result.built.plate is not None:  # an RC strip: crack widths, utilisations (None for an elastic one)
        out["design"] = result.design_summary()
        by_phase = (out["design"] or {}).get("phases", {})
        for row in out["phases"]:  # EN 1992 crack width w_k [m] of each phase, from the design summary
            if row["name"] in by_phase:
                row["max_crack_width"] = 1e-3 * by_phase[row["name"]]["w_k_max_mm"]
    out["envelope"] = _envelope(out["phases"])
    # the discretisation error of the headline quantities (ssi run --estimate, solve_with_error): None when
    # not estimated, {"failed": why} when a refined copy could not be solved
    out["error_estimate"] = result.error_estimate
    out["wall_time_s"] = wall_time  # ssi run: build + solve (with any first-time compilation)
    return out


def _stop_message(stop, kind: str) -> str | None:
    """A solver stop's report as one engineering sentence (:func:`ssi.scene.verdict.stop_sentence`); a
    report read back from a file as text is given as it is."""
    if stop is None:
        return None
    if not isinstance(stop, dict):
        return str(stop)
    from ..scene.verdict import stop_sentence

    return stop_sentence(stop, kind)


def _column_force_on(loads, x0: float, x1: float) -> float:
    """The column forces N [N/m] of ``loads`` standing on a strip from ``x0`` to ``x1`` [m], summed."""
    return sum(n for ld in loads for x, n in ld.columns() if x0 - 1e-9 <= x <= x1 + 1e-9)


def _site_summary(result, wall_time: float | None = None, complete: bool = True, stop=None) -> dict:
    """The per-foundation summary of a solved site (:class:`ssi.scene.site_view.SiteResult`), SI units in
    the key names: settlement [m] positive down, tilt [rad] (> 0: the right end settles more), pressure
    [Pa], forces [N/m], moments [N m/m].

    ``status`` is the solver's, as for a scene (:func:`summary`): "completed" (load factor 1
    reached), "limit load reached" (the controlled path peaked at ``limit_load_factor`` of the site's loads,
    with the limit's checks ``limit_evidence``, ``limit_uncertainty``, ``limit_mechanism`` and
    ``limit_suspect``) or "stopped" (the solver failed before either, ``stop``). ``complete`` as for a
    scene: False only when the solver stopped (a limit load is an answer). A plate strip's row also holds
    its contact resultant (``contact_N_N_per_m``, ``contact_H_N_per_m``, ``contact_M_Nm_per_m`` about
    x = 0), the column load applied on it at the end (``applied_N_N_per_m``), its largest bending moment and
    its EN 1992 design (``design``: :func:`ssi.scene.design.design_summary`, None without concrete)."""
    built = result.built
    foundations, plates = [], []
    lam = float(result.load_factor[-1])
    status = result.status if complete else "stopped"
    for i, (part, st) in enumerate(zip(built.site.strips, built.strips)):
        if st.get("rigid"):
            s, q = result.rigid_pressure(i)
            foundations.append({
                "index": i, "type": "rigid strip", "x0_m": part.x0, "x1_m": part.x1,
                "settlement_m": float(s[-1]), "pressure_Pa": float(q[-1]), "max_pressure_Pa": float(q.max()),
            })  # fmt: skip
            continue
        view = result.foundation_result(i)
        d = view.settlement_summary()
        c = view.contact_resultant()
        x_m, m_max = view.max_abs_moment()
        foundations.append({
            "index": i, "type": "strip", "x0_m": part.foundation.x0, "x1_m": part.foundation.x1,
            "mean_settlement_m": d["mean"], "max_settlement_m": d["max"], "tilt_rad": d["tilt"],
            "applied_N_N_per_m": lam * _column_force_on(built.site.loads, *part.ends),
            "contact_N_N_per_m": c["N"], "contact_H_N_per_m": c["H"], "contact_M_Nm_per_m": c["M"],
            "max_abs_moment_Nm_per_m": m_max, "x_max_abs_moment_m": x_m,
            "design": view.design_summary(),
        })  # fmt: skip
        plates.append(i)
    differential = [
        {"i": i, "j": j, "mean_settlement_i_minus_j_m": float(result.differential_settlement(i, j))}
        for k, i in enumerate(plates)
        for j in plates[k + 1 :]
    ]
    out = {
        "kind": "site",
        "complete": bool(complete),
        "status": status,
        "load_factor": lam,
        "limit_load_factor": (
            result.solver_result.limit_load_factor if status == "limit load reached" else None
        ),
        "stop": None if stop is None else str(stop),
        "stop_message": _stop_message(stop, "site"),
        "mesher": built.mesher,
        "initial_stress": built.initial_stress_method,
        "n_elements": int(len(built.mesh.conn)),
        "n_dof": int(built.model.n_dof),
        "wall_time_s": None if wall_time is None else float(wall_time),
        "foundations": foundations,
        "differential_settlement": differential,
        # the discretisation error of the headline quantities (ssi run --estimate), as a scene's summary
        "error_estimate": result.error_estimate,
    }
    if status == "limit load reached":  # how the controlled path found its limit, as a scene's summary has it
        out.update(_limit_checks(result))
    return out


def _site_summary_text(s: dict) -> str:
    """The printed form of :func:`_site_summary` (mm, mm/m, kPa)."""
    from .report import site_status_line

    lines = [
        f"site: {s['n_elements']} elements ({s['mesher']} mesh), {s['n_dof']} DOFs, initial stress "
        f"{s['initial_stress']}; status: {site_status_line(s)}"
    ]
    if s["stop"]:
        lines.append(f"  stopped: {s.get('stop_message') or s['stop']}")
    for f in s["foundations"]:
        where = f"#{f['index']} {f['type']} [{f['x0_m']:g}, {f['x1_m']:g}] m"
        if f["type"] == "rigid strip":
            lines.append(f"  {where}: settlement {1e3 * f['settlement_m']:.2f} mm, pressure "
                         f"{f['pressure_Pa'] / 1e3:.1f} kPa (largest "
                         f"{f['max_pressure_Pa'] / 1e3:.1f} kPa)")  # fmt: skip
        else:
            lines.append(f"  {where}: settlement mean {1e3 * f['mean_settlement_m']:.2f} mm, max "
                         f"{1e3 * f['max_settlement_m']:.2f} mm, "
                         f"tilt {1e3 * f['tilt_rad']:.3f} mm/m")  # fmt: skip
            if "contact_N_N_per_m" in f:  # a summary written before the strips' forces were part of it
                lines.append(f"    contact resultant {f['contact_N_N_per_m'] / 1e3:.2f} kN/m (column load "
                             f"{f['applied_N_N_per_m'] / 1e3:.2f} kN/m), max |moment| "
                             f"{f['max_abs_moment_Nm_per_m'] / 1e3:.2f} kN m/m at x = "
                             f"{f['x_max_abs_moment_m']:.3f} m")  # fmt: skip
            if f.get("design"):
                from ..scene.design import summary_text as design_text

                lines += ["    " + line for line in design_text(f["design"]).splitlines()]
    for d in s["differential_settlement"]:
        lines.append(f"  differential settlement #{d['i']} - #{d['j']}: "
                     f"{1e3 * d['mean_settlement_i_minus_j_m']:.2f} mm (mean settlements)")  # fmt: skip
    lines += _estimate_lines(s)
    if s["wall_time_s"] is not None:
        lines.append(f"  wall time {s['wall_time_s']:.2f} s")
    if s.get("estimate_wall_time_s") is not None:
        lines.append(f"  {s['estimate_wall_time_s']:.2f} s (the error estimate's refined solves)")
    return "\n".join(lines)


def _limit_checks(result) -> dict:
    """How the controlled path found its limit and the limit's checks (ssi/solver/path.py):
    ``limit_evidence`` (peak or plateau, where), ``limit_uncertainty`` (relative change of the peak when the
    steps around it are redone at half size), ``limit_mechanism`` (the mechanism certificate lambda_k /
    lambda_peak, associated and Davis-mode laws only, else None) and ``limit_suspect`` (why the limit is not
    to be read as a capacity, "" when every check passed). Of a phased solve, the last phase's."""
    last = result.phases[-1]["result"] if result.phases else result.solver_result
    return {
        "limit_evidence": last.limit_evidence,
        "limit_uncertainty": last.limit_uncertainty,
        "limit_mechanism": last.limit_mechanism,
        "limit_suspect": last.limit_suspect,
    }


ENVELOPE_KEYS = (
    "max_settlement",
    "max_abs_moment",
    "peak_pressure",
    "max_steel_stress",
    "max_crack_width",
    "foundation_load",
)


def _envelope(table: list[dict]) -> dict:
    """The largest of each of ``ENVELOPE_KEYS`` over the phase rows: {key: {"value", "phase"}} (keys no
    phase has are left out)."""
    out = {}
    for key in ENVELOPE_KEYS:
        rows = [r for r in table if r.get(key) is not None]
        if rows:
            best = max(rows, key=lambda r: r[key])
            out[key] = {"value": best[key], "phase": best["name"]}
    return out


def _capacity_line(s: dict) -> str | None:
    cap = s.get("capacity")
    if not cap:
        return None
    if s.get("push_over"):
        word = "capacity" if cap["is_limit"] else "largest load"
        line = (
            f"{word:<17}{cap['load'] / 1e3:.2f} kN/m at {1e3 * cap['settlement']:.2f} mm settlement "
            f"({cap['how']})"
        )
    elif cap["is_limit"]:
        line = f"capacity         {cap['load'] / 1e3:.2f} kN/m of column load ({cap['how']})"
    else:
        return None
    if cap.get("viscous_rows"):
        line += f"; {cap['viscous_rows']} viscous (not equilibrium) rows left out"
    est = cap.get("estimate")
    if not est and cap["is_limit"] and not s.get("error_estimate"):
        # a displacement-based mesh is too stiff at collapse: its capacity lies above the true one (a Tresca
        # footing on the default mesh by ~10 %); the reader is told how to check it, not left to trust it
        line += (
            "\ncapacity error   not estimated (a finite-element mesh overstates a capacity): "
            "`ssi run --estimate` estimates its mesh error, `ssi limit` brackets it"
        )
    if not est and (s.get("error_estimate") or {}).get("failed"):
        line += f"\ncapacity error   not estimated: {s['error_estimate']['failed']}"
    if est:  # attached by ssi.scene.estimate (solve_with_error, solve_to_target, ssi run --estimate)
        meshes = ""
        if est.get("values"):
            meshes = (
                "mesh h, h/2, h/4: "
                + ", ".join(f"{v / 1e3:.2f}" for v in est["values"])
                + f" kN/m, observed order {est['order']:.2f}; "
            )
        line += (
            f"\ncapacity error   {est['relative']:.1%} estimated ({meshes}extrapolated "
            f"{est['extrapolated'] / 1e3:.2f} kN/m)"
        )
    if cap.get("warning"):
        line += f"\nWARNING          {cap['warning']}"
    return line


def summary_text(s: dict) -> str:
    """The summary as the lines ``ssi run`` and ``ssi show`` print (kN, kPa, mm); a site's per foundation
    (:func:`_site_summary_text`)."""
    from ..scene.verdict import verdict_lines

    head = verdict_lines(s.get("verdict"))
    if s.get("kind") == "site":
        return "\n".join([*head, _site_summary_text(s)])
    state = {
        "completed": ")",
        "limit load reached": ", the limit load)",
        "stopped": ", INCOMPLETE: the run stopped before the end of its load path)",
    }[s["status"]]
    lines = [*head, f"steps            {s['steps']} (load factor {s['load_factor']:.4g}{state}"]
    if s.get("phase") is not None:
        lines.append(
            f"last phase       {s['phase']!r} at load factor {s['phase_load_factor']:.4g} of its loads"
        )
    if s.get("push_over"):
        lines.append(
            f"footing load     {s['foundation_load'] / 1e3:.2f} kN/m at the end (the soil's reaction)"
        )
    cap = _capacity_line(s)
    if cap:
        lines.append(cap)
    env = s.get("envelope", {})
    lines.append(f"max settlement   {1e3 * s['max_settlement']:.3f} mm at x = {s['x_max_settlement']:.3f} m")
    if len(s.get("phases") or []) > 1 and "max_settlement" in env:
        lines[-1] += " at the end"
        lines.append(
            f"                 {1e3 * env['max_settlement']['value']:.3f} mm largest over the phases "
            f"(phase {env['max_settlement']['phase']!r})"
        )
    if "max_contact_pressure" in s:
        lines += [
            (
                f"contact pressure {s['mean_contact_pressure'] / 1e3:.2f} kPa mean, "
                f"{s['peak_contact_pressure'] / 1e3:.2f} kPa peak at x = "
                f"{s['x_peak_contact_pressure']:.3f} m (edges excluded; contact resultant "
                f"{s['contact_resultant'] / 1e3:.2f} kN/m)"
            ),
            (
                f"edge pressure    {s['max_contact_pressure'] / 1e3:.2f} kPa at x = "
                f"{s['x_max_contact_pressure']:.3f} m (a corner singularity: mesh dependent, not a "
                "bearing pressure)"
            ),
            f"max |moment|     {s['max_abs_moment'] / 1e3:.2f} kN m/m at x = {s['x_max_abs_moment']:.3f} m",
        ]
    lines += _estimate_lines(s)
    if len(s.get("phases") or []) > 1:
        lines.append("per phase        " + _phase_header(s["phases"]))
        lines += ["  " + _phase_line(row, s["phases"]) for row in s["phases"]]
    load = "" if s.get("column_load") is None else f", {s['column_load'] / 1e3:.2f} kN/m of column load"
    if s["status"] == "limit load reached":
        from .report import limit_meaning

        where = "" if s.get("phase") is None else f" of phase {s['phase']!r}"
        lines.append(
            f"limit load       reached at load factor {s['limit_load_factor']:.4g}{where}{load}: "
            f"{limit_meaning(s)} (the path up to the limit is the answer)"
        )
        lines += _limit_check_lines(s)
    elif s["status"] == "stopped":
        where = "" if s.get("phase") is None else f" in phase {s['phase']!r}"
        lines.append(
            f"stopped          at load factor {s['load_factor']:.4g}{where}{load} "
            f"(solver failure, not a detected limit load: {s['stop_reason']})"
        )
        if s.get("stop_message"):
            lines.append(f"                 {s['stop_message']}")
        if s.get("stop_ill_posed"):
            lines.append(f"ill-posed soil   {s['stop_ill_posed']}")
    if s.get("design"):
        from ..scene.design import summary_text as design_text

        lines.append(design_text(s["design"]))
    if s.get("wall_time_s") is not None:
        lines.append(
            f"wall time        {s['wall_time_s']:.2f} s ({s.get('wall_time_of', 'build and solve')})"
        )
    if s.get("estimate_wall_time_s") is not None:
        lines.append(
            f"                 {s['estimate_wall_time_s']:.2f} s (the error estimate's refined solves)"
        )
    return "\n".join(lines)


def _limit_check_lines(s: dict) -> list[str]:
    """The limit's checks under the ``limit load`` line; a failed check as its own SUSPECT line, so that an
    engineer does not read such a limit as a capacity."""
    if "limit_evidence" not in s:  # a summary written before the checks were part of it
        return []
    unc = s.get("limit_uncertainty")  # (the evidence itself is on the capacity line)
    text = "                 relative uncertainty " + (
        "not measured" if unc is None else f"{unc:.1e} (the steps around the peak redone at half size)"
    )
    if s.get("limit_mechanism") is not None:
        text += f"; mechanism certificate {s['limit_mechanism']:.4f} (1 at a collapse)"
    lines = [text]
    if s.get("limit_suspect"):
        lines.append(f"SUSPECT          {s['limit_suspect']}")
    return lines


def _estimate_lines(s: dict) -> list[str]:
    """The error estimate's lines (the capacity's is on the capacity line): the quantity asked for first,
    then the others, each with its estimated error, extrapolated value and a flag when not asymptotic."""
    from .report import ESTIMATE_UNITS, SINGULAR_ESTIMATES

    est = s.get("error_estimate")
    if not est:
        return []
    if est.get("failed"):
        return [] if s.get("push_over") else [f"error estimate   not available: {est['failed']}"]
    qs = est["quantities"]
    order = [est["asked"]] + [q for q in qs if q != est["asked"]]
    lines = []
    for q in order:
        if q not in qs or q == "capacity":
            continue
        e = qs[q]
        scale, unit = ESTIMATE_UNITS.get(q, (1.0, e["unit"]))
        if q in SINGULAR_ESTIMATES:
            lines.append(f"  {q:<31}{e['value'] * scale:.4g} {unit}: {SINGULAR_ESTIMATES[q]}")
            continue
        flag = "" if e["asymptotic"] else ", NOT asymptotic: the estimate is a rough bound"
        asked = " (asked for)" if q == est["asked"] else ""
        lines.append(
            f"  {q + asked:<31}{e['value'] * scale:.4g} {unit}, error {e['relative']:.1%} "
            f"(extrapolated {e['extrapolated'] * scale:.4g} {unit}{flag})"
        )
    if not lines:  # the capacity alone: on its own line
        return []
    head = f"error estimate   over {', '.join(est['refinements'])} halvings (h, h/2, h/4; Richardson)"
    return [head, *lines]


PHASE_COLUMNS = (  # (key, header with unit, scale from SI, format)
    ("foundation_load", "load [kN/m]", 1e-3, "{:9.2f}"),
    ("max_settlement", "settl. [mm]", 1e3, "{:9.3f}"),
    ("max_abs_moment", "|M| [kNm/m]", 1e-3, "{:9.2f}"),
    ("peak_pressure", "p peak [kPa]", 1e-3, "{:9.2f}"),
    ("max_steel_stress", "steel [MPa]", 1e-6, "{:9.1f}"),
    ("max_crack_width", "w_k [mm]", 1e3, "{:9.3f}"),
)


def _phase_columns(table):
    """The PHASE_COLUMNS some phase has a value of (the same for the header and every line)."""
    return [c for c in PHASE_COLUMNS if any(r.get(c[0]) is not None for r in table)]


def _phase_header(table):
    return "max over each phase: " + ", ".join(h for _, h, _, _ in _phase_columns(table))


def _phase_line(row, table):
    cells = [
        "        -" if row.get(key) is None else fmt.format(row[key] * scale)
        for key, _, scale, fmt in _phase_columns(table)
    ]
    return f"{row['name']:<14} " + " ".join(cells)


def run_scene_file(
    scene_path, out=None, plots=None, paraview=None, overwrite=False, figures=True, estimate=None, echo=None,
    capacity=True, capacity_gap=0.05,
):  # fmt: skip
    """What ``ssi run`` does; returns (result, summary dict, written paths).

    ``estimate``: None (default) or the refinements whose discretisation error is estimated (a subset of
    ``("mesh", "steps", "layers")``, :func:`ssi.scene.estimate.estimate_solved`): the scene as solved is the
    base level, its copies at h/2 and h/4 are solved in addition (about 4 and 16 times the base solve for
    the mesh) and the estimate goes to the summary, the result file and the report. A refined copy that
    the solver cannot finish leaves the estimate ``{"failed": why}``. ``echo``: gets a line before the
    refined solves start (the command line prints it). ``capacity``: the verdict (:func:`ssi.scene.verdict.
    verdict`: the capacity bracket of the run's loads to the relative gap ``capacity_gap``, the margin,
    settlements and RC utilisations) first in the summary; False: skipped."""
    from ..scene.scene_file import read_scene_file
    from ..solver import NonConvergence
    from ..solver.progress import announce_compilation
    from .plot import save_standard_figures
    from .report import write_report
    from .results import atomic_path, run_output_paths, write_result

    scene_path = Path(scene_path)
    scene, n_steps, settings = read_scene_file(scene_path)  # a scene or a site: the same path from here
    paths = run_output_paths(scene_path, out, paraview, plots, overwrite)
    out, paraview, plots, summary_path, report_path = paths
    announce_compilation()
    t0 = time.perf_counter()
    stop = None
    with warnings.catch_warnings(record=True) as caught:  # shown as usual below, and kept for the report
        warnings.simplefilter("default")
        built = scene.build()
        try:
            result = built.solve(n_steps=n_steps, settings=settings)
        except NonConvergence as err:
            # the converged steps before the failure; of a phased scene every completed phase and the
            # failing phase's steps (PhaseNonConvergence.scene_result)
            result = getattr(err, "scene_result", None) or built.result_view(err.result)
            stop = err.report
        wall = time.perf_counter() - t0
        if estimate and stop is None:
            estimate_wall = _estimate_run(result, n_steps, settings, estimate, wall, echo)
        elif estimate:  # a stopped run has no answer whose error could be estimated
            result.error_estimate = {"failed": "the run stopped before the end of its load path"}
    # for an engineer: what, where, what to do (the warnings' own texts), not a Python source path
    run_warnings = list(dict.fromkeys(str(w.message) for w in caught))
    for text in run_warnings:
        print(f"WARNING: {text}", file=sys.stderr)
    complete = stop is None
    s = summary(result, wall, complete, stop)
    if estimate and stop is None:
        s["estimate_wall_time_s"] = estimate_wall
    if capacity:
        from ..scene.verdict import verdict

        if echo is not None:
            echo(
                "verdict: bracketing the capacity of the run's loads by limit analysis (gap "
                f"{100 * capacity_gap:g} %)"
            )
        with warnings.catch_warnings(record=True) as caught_v:  # as the run's: for the engineer, no path
            warnings.simplefilter("default")
            result.verdict = verdict(s, scene, gap=capacity_gap)
        for text in dict.fromkeys(f"capacity bracket: {w.message}" for w in caught_v):
            print(f"WARNING: {text}", file=sys.stderr)
            run_warnings.append(text)
    else:
        result.verdict = {"skipped": "--no-capacity"}
    s = {"verdict": result.verdict, **s}
    written = [write_result(out, result, settings, overwrite=overwrite, complete=complete, stop=stop)]
    from .export import export_series

    written.append(export_series(result, paraview, overwrite=overwrite))
    with atomic_path(summary_path, overwrite) as tmp:
        tmp.write_text(json.dumps(s, indent=1))
    written.append(summary_path)
    figs = save_standard_figures(result, plots, overwrite=overwrite) if figures else []
    written += figs
    written.append(
        write_report(s, report_path, figs, scene_path.name, run_warnings=run_warnings, overwrite=overwrite)
    )
    return result, s, written


def _estimate_run(result, n_steps, settings, refine, wall, echo) -> float:
    """Estimate ``result``'s error over ``refine`` (:func:`ssi.scene.estimate.estimate_solved`), attached
    to it; a refined copy the solver cannot finish leaves ``result.error_estimate = {"failed": why}``.
    Returns the wall time of the refined solves [s]."""
    from ..scene.estimate import estimate_solved
    from ..solver import NonConvergence

    if echo is not None:
        echo(
            f"estimating the discretisation error: solving the scene again at h/2 and h/4 over "
            f"{', '.join(refine)} (the mesh's copies cost about 4 and 16 times the {wall:.1f} s of the run, "
            "the steps' and layers' about 2 and 4 times)"
        )
    t0 = time.perf_counter()
    try:
        estimate_solved(result, n_steps, settings, refine, wall_time=wall)
    except NonConvergence as err:
        result.error_estimate = {"failed": f"a refined copy did not finish its load path ({err})"}
    return time.perf_counter() - t0


def _free_folder(folder: Path) -> Path:
    """``folder`` if it does not exist, else the first of ``folder_2``, ``folder_3``, ... that does not."""
    k = 2
    candidate = folder
    while candidate.exists():
        candidate = folder.with_name(f"{folder.name}_{k}")
        k += 1
    return candidate


def show_result_file(path, plots=None, overwrite=False, figures=True):
    """What ``ssi show`` does; returns (result, summary dict, written paths).

    The figures go to ``plots`` (default ``<result>_plots``, the folder ``ssi run`` drew into); if that
    default folder exists and ``overwrite`` is False they go to a new folder beside it (``<result>_plots_2``,
    ...), so showing a result right after its run never fails. A folder given explicitly is used as given:
    an existing figure in it is replaced only with ``overwrite``. The figures' folder also gets the HTML
    report (``report.html``, :mod:`ssi.io.report`)."""
    from .plot import save_standard_figures
    from .report import write_report
    from .results import read_info, read_result

    path = Path(path)
    info = read_info(path)
    if info.get("kind") == "limit":
        return _show_limit_file(path, plots, overwrite, figures)
    result = read_result(path)
    wall = result.solver_result.wall_time  # of a phased solve: its phases' summed
    s = summary(result, wall, info["complete"], info["stop"])
    s["wall_time_of"] = "the solver, as stored in the file"
    written = []
    if figures:
        folder = Path(plots) if plots else path.parent / (path.stem + "_plots")
        if plots is None and not overwrite:
            folder = _free_folder(folder)
        written = save_standard_figures(result, folder, overwrite=overwrite)
        written.append(write_report(s, folder / "report.html", written, path.name, overwrite=overwrite))
    return result, s, written


def _show_limit_file(path: Path, plots, overwrite: bool, figures: bool):
    """``ssi show`` of a limit analysis's file: (StoredLimit, its numbers with ``kind`` "limit" and
    ``summary_text``, the mechanism figure redrawn into ``plots`` -- default ``<file>_plots``, or a new
    folder beside it)."""
    from .results_limit import read_limit_result

    stored = read_limit_result(path)
    s = {"kind": "limit", "complete": True, **stored.to_dict(), "summary_text": stored.summary()}
    written = []
    if figures:
        folder = Path(plots) if plots else path.parent / (path.stem + "_plots")
        if plots is None and not overwrite:
            folder = _free_folder(folder)
        written.append(_save_limit_figure(stored, folder / "mechanism.png", overwrite))
    return stored, s, written


def limit_scene_file(
    scene_path, phase=None, gap=0.02, h=None, h_min=None, max_elements=20000, out=None, plot=None,
    overwrite=False, figures=True, echo=print, strip=None, side_soil=None,
):  # fmt: skip
    """What ``ssi limit`` does with a scene or a site file (:meth:`ssi.scene.Site.limit_analysis`: its loads
    scaled, no ``phase``); returns (CapacityResult, written paths): ``<name>_limit.json`` (the numbers,
    ``out``), ``<name>_limit.h5`` (the result file: bounds, meshes, mechanism, dissipation, stress field;
    :mod:`ssi.io.results_limit`), ``<name>_limit.vtu`` (ParaView: the mechanism's triangles with velocity,
    dissipation and stress) and ``<name>_limit.png`` (the mechanism and the dissipation, ``plot``). ``echo``
    gets one line of progress per mesh of the adaptive runs. ``strip``: a plate strip "rigid", a "beam"
    with plastic hinges of M_p at N = 0 or "beam_mn" (hinges on the section's M-N polygon; None: the scene's
    default, :func:`ssi.capacity.limit_problem`). ``side_soil``: an embedded strip's side soil
    "surcharge" (its overburden at the base level) or "soil" (modelled with its strength; None: the scene's
    default, "surcharge" for a scene, "soil" for a site: ``ssi/capacity/README.md``, *Embedment*)."""
    from ..scene.scene_file import read_scene_file
    from .results import atomic_path
    from .results_limit import export_limit_vtu, write_limit_result

    scene_path = Path(scene_path)
    stem = scene_path.with_suffix("")
    out = Path(out) if out else stem.parent / (stem.name + "_limit.json")
    plot = Path(plot) if plot else stem.parent / (stem.name + "_limit.png")
    h5_path = stem.parent / (stem.name + "_limit.h5")
    vtu_path = stem.parent / (stem.name + "_limit.vtu")
    for target in (out, h5_path, vtu_path, plot) if figures else (out, h5_path, vtu_path):
        if target.exists() and not overwrite:
            raise FileExistsError(f"{target} exists; pass --overwrite to replace it")
    scene, _, _ = read_scene_file(scene_path)  # a scene or a site (which refuses a phase by name)
    options = {} if phase is None else {"phase": phase}
    if strip is not None:
        options["strip"] = strip
    if side_soil is not None:
        options["side_soil"] = side_soil

    def progress(label, r):
        echo(
            f"{label:10s} mesh {r['step']:2d}: {r['n_el']:6d} triangles  LB {r['best_lb']:.5g}  "
            f"UB {r['best_ub']:.5g}  gap {100 * r['gap']:6.2f} %  ({r['t_lb'] + r['t_ub']:.1f} s)"
        )

    cap = scene.limit_analysis(
        gap=gap, h=h, h_min=h_min, max_elements=max_elements, progress=progress, **options
    )
    with atomic_path(out, overwrite) as tmp:
        tmp.write_text(json.dumps(cap.to_dict(), indent=1))
    written = [out, write_limit_result(h5_path, cap, overwrite), export_limit_vtu(cap, vtu_path, overwrite)]
    if figures:
        written.append(_save_limit_figure(cap, plot, overwrite))
    return cap, written


def safety_scene_file(
    scene_path, phase=None, gap=0.02, h=None, h_min=None, max_elements=20000, out=None, overwrite=False,
    echo=print, strip=None, side_soil=None,
):  # fmt: skip
    """What ``ssi limit --fos`` does: the factor of safety of a scene or a site file by strength reduction
    (:meth:`ssi.scene.Scene.safety_factor`, :meth:`ssi.scene.Site.safety_factor`), a certified bracket
    refined to ``gap``; writes ``<name>_fos.json`` (``out``). Returns (SafetyFactorResult, written)."""
    from ..scene.scene_file import read_scene_file
    from .results import atomic_path

    scene_path = Path(scene_path)
    stem = scene_path.with_suffix("")
    out = Path(out) if out else stem.parent / (stem.name + "_fos.json")
    if out.exists() and not overwrite:
        raise FileExistsError(f"{out} exists; pass --overwrite to replace it")
    scene, _, _ = read_scene_file(scene_path)
    options = {"gap": gap, "h": h, "h_min": h_min, "max_elements": max_elements}
    if phase is not None:
        options["phase"] = phase
    if strip is not None:
        options["strip"] = strip
    if side_soil is not None:
        options["side_soil"] = side_soil

    def progress(r):
        echo(
            f"F search   mesh {r['step']:2d}: {r['n_el']:6d} triangles  F_LB {r['f_lower']:.5g}  "
            f"F_UB {r['f_upper']:.5g}  gap {100 * r['gap']:6.2f} %  ({r['solves']} solves, {r['time']:.1f} s)"
        )

    sf = scene.safety_factor(progress=progress, **options)
    with atomic_path(out, overwrite) as tmp:
        tmp.write_text(json.dumps(sf.to_dict(), indent=1))
    return sf, [out]


def _save_limit_figure(cap, path: Path, overwrite: bool) -> Path:
    import matplotlib.pyplot as plt

    from .plot import limit_mechanism
    from .results import atomic_path

    fig = limit_mechanism(cap)
    with atomic_path(path, overwrite) as tmp:
        fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    return path


def _refinements(text: str | None) -> tuple | None:
    """``--estimate-over``'s comma list as a tuple of refinements (None: no estimate); an unknown name is a
    ValueError naming the flag, the value and the allowed names."""
    if text is None:
        return None
    from ..scene.estimate import REFINEMENTS

    names = tuple(n.strip() for n in text.split(",") if n.strip())
    bad = [n for n in names if n not in REFINEMENTS]
    if bad or not names:
        raise ValueError(f"--estimate-over must be a comma list of {', '.join(REFINEMENTS)}, got {text!r}")
    return names


class _DefaultsFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """``--help`` with every option's default (argparse's ArgumentDefaultsHelpFormatter), except where the
    help already says it or there is none to show (a flag, an option whose default is computed)."""

    def _get_help_string(self, action):
        text = action.help or ""
        if "default" in text or action.default in (None, False) or action.default is argparse.SUPPRESS:
            return text
        return super()._get_help_string(action)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        prog="ssi",
        description="2D soil-structure interaction of strip "
        "foundations: solve a scene file, show a result file.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    run_p = sub.add_parser(
        "run",
        help="solve a TOML scene or site file; write result, ParaView file, plots, summary, verdict",
        formatter_class=_DefaultsFormatter,
    )
    run_p.add_argument("scene", type=Path)
    run_p.add_argument("-o", "--out", type=Path, help="result file (default: <scene>.h5)")
    run_p.add_argument("--plots", type=Path, help="folder for the figures (default: <scene>_plots)")
    run_p.add_argument(
        "--paraview", type=Path, help="ParaView series (default: <scene>.pvd, steps in <scene>_steps/)"
    )
    run_p.add_argument("--no-plots", action="store_true", help="skip the figures")
    run_p.add_argument("--overwrite", action="store_true", help="replace existing output files")
    run_p.add_argument("--json", action="store_true", help="print the summary as JSON")
    run_p.add_argument(
        "--no-capacity",
        action="store_true",
        help="skip the verdict's capacity bracket (limit analysis of the run's loads)",
    )
    run_p.add_argument(
        "--capacity-gap",
        type=float,
        default=0.05,
        help="relative gap (UB-LB)/(UB+LB) of the verdict's capacity bracket",
    )
    # a flag, and the refinements under their own option: an optional value on --estimate would swallow
    # the scene's path in `ssi run --estimate scene.toml`
    run_p.add_argument(
        "--estimate",
        action="store_true",
        help="estimate the discretisation error by re-solving at h/2 and h/4 (Richardson): the capacity of "
        "a push-over, the settlement otherwise; over the mesh unless --estimate-over says otherwise. Costs "
        "about 20 times the run per refinement",
    )
    run_p.add_argument(
        "--estimate-over",
        metavar="REFINEMENTS",
        help="the refinements of --estimate (implies it): a comma list of mesh, steps, layers",
    )
    show_p = sub.add_parser("show", help="print the summary of a result file and write its plots")
    show_p.add_argument("result", type=Path)
    show_p.add_argument(
        "--plots",
        type=Path,
        help="folder for the figures (default: <result>_plots, or <result>_plots_2, ... if it exists)",
    )
    show_p.add_argument("--no-plots", action="store_true", help="skip the figures")
    show_p.add_argument("--overwrite", action="store_true", help="redraw into <result>_plots, replacing it")
    show_p.add_argument("--json", action="store_true", help="print the summary as JSON")
    sub.add_parser("schema", help="print the scene file's tables, keys and units")
    lim_p = sub.add_parser(
        "limit",
        help="bracket the capacity of a TOML scene or site by limit analysis (--fos: its factor of safety)",
        formatter_class=_DefaultsFormatter,
    )
    lim_p.add_argument("scene", type=Path)
    lim_p.add_argument("--phase", help="the phase whose loads are scaled (default: the last)")
    lim_p.add_argument("--gap", type=float, default=0.02, help="relative gap (UB-LB)/(UB+LB) to reach")
    lim_p.add_argument("--h", type=float, help="largest initial triangle [m]")
    lim_p.add_argument("--h-min", type=float, help="initial triangle at the footing's ends [m]")
    lim_p.add_argument("--max-elements", type=int, default=20000, help="stop refining at this many")
    lim_p.add_argument(
        "--strip",
        choices=("rigid", "beam", "beam_mn"),
        help="a plate strip as a rigid body, a beam with plastic hinges of M_p at N = 0, or 'beam_mn' whose "
        "hinges follow the section's M-N interaction (default: a beam for a ductile RC section, rigid "
        "otherwise)",
    )
    lim_p.add_argument(
        "--side-soil",
        choices=("surcharge", "soil"),
        help="an embedded strip's side soil: 'surcharge' replaces it by its overburden on the ground at "
        "the base level (the bracket of a strengthless backfill: its lower bound is a floor of the scene), "
        "'soil' models it with its strength and weight, the trench walls under their geostatic stress or "
        "in contact with the strip through side_contact (default: 'surcharge' for a scene, 'soil' for a "
        "site)",
    )
    lim_p.add_argument("-o", "--out", type=Path, help="numbers as JSON (default: <scene>_limit.json)")
    lim_p.add_argument("--plot", type=Path, help="mechanism figure (default: <scene>_limit.png)")
    lim_p.add_argument("--no-plots", action="store_true", help="skip the figure")
    lim_p.add_argument("--overwrite", action="store_true", help="replace existing output files")
    lim_p.add_argument("--json", action="store_true", help="print the numbers as JSON")
    lim_p.add_argument(
        "--fos",
        action="store_true",
        help="the factor of safety by strength reduction (c/F, tan(phi)/F) instead of the capacity: a "
        "certified bracket [F_LB, F_UB] under the weight, the dead loads and 1 x the loads (a site without "
        "loads: its weight alone, e.g. a slope); written to <scene>_fos.json",
    )
    args = parser.parse_args(argv)
    from .results import OutputExistsError

    if args.command == "limit":
        # the bracket of the capacity, or with --fos of the factor of safety: one call, one way to report it
        echo = functools.partial(print, flush=True)
        try:
            if args.fos:
                answer, written = safety_scene_file(
                    args.scene, args.phase, args.gap, args.h, args.h_min, args.max_elements, args.out,
                    args.overwrite, echo=echo, strip=args.strip, side_soil=args.side_soil,
                )  # fmt: skip
            else:
                answer, written = limit_scene_file(
                    args.scene, args.phase, args.gap, args.h, args.h_min, args.max_elements, args.out,
                    args.plot, args.overwrite, not args.no_plots, echo=echo, strip=args.strip,
                    side_soil=args.side_soil,
                )  # fmt: skip
        except (FileExistsError, FileNotFoundError, ValueError, TypeError) as err:
            print(f"ssi: error: {err}", file=sys.stderr)
            return 2
        print(json.dumps(answer.to_dict(), indent=1) if args.json else answer.summary())
        for p in written:
            print(f"wrote {p}")
        return 0
    if args.command == "schema":
        from ..scene.file_schema import schema_text

        print(schema_text())
        return 0
    try:
        estimate = None  # the refinements of --estimate / --estimate-over
        if args.command == "run" and (args.estimate or args.estimate_over is not None):
            estimate = "mesh" if args.estimate_over is None else args.estimate_over
        if args.command == "run":
            _, s, written = run_scene_file(
                args.scene, args.out, args.plots, args.paraview, args.overwrite, not args.no_plots,
                _refinements(estimate), echo=lambda line: print(line, file=sys.stderr, flush=True),
                capacity=not args.no_capacity, capacity_gap=args.capacity_gap,
            )  # fmt: skip
        else:
            _, s, written = show_result_file(args.result, args.plots, args.overwrite, not args.no_plots)
    except OutputExistsError as err:  # the flag, not the Python keyword
        print(f"ssi: error: {err.path} exists; pass --overwrite to replace it", file=sys.stderr)
        return 2
    except (FileExistsError, FileNotFoundError, ValueError, TypeError) as err:
        print(f"ssi: error: {err}", file=sys.stderr)
        return 2
    text = {"limit": lambda d: d["summary_text"]}.get(s.get("kind"), summary_text)
    print(json.dumps(s, indent=1) if args.json else text(s))
    for p in written:
        print(f"wrote {p}")
    return 0 if s["complete"] else EXIT_INCOMPLETE


if __name__ == "__main__":
    sys.exit(main())
