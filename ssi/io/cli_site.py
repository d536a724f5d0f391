"""``ssi run site.toml``: solve a site file (:mod:`ssi.scene.site_file`) and summarise it per foundation.

A site file is told from a scene file by its keys (:func:`is_site_file`). The run prints, for each strip, its
mean and largest settlement and its tilt, the differential settlement of every pair of strips, and for a
rigid strip its settlement and pressure; the same numbers go to ``<name>_summary.json`` (atomically, with the
user's umask), and as for a scene the result file, the ParaView series, the figures (the site's geometry
under each) and the HTML report are written (:func:`run_site_file`); ``ssi show`` reads the result file
back."""

from __future__ import annotations

import json
import time
import tomllib
import warnings
from pathlib import Path

__all__ = [
    "SITE_ONLY_KEYS", "is_site_file", "run_site_file", "site_summary", "site_summary_text",
]  # fmt: skip

# top-level keys a site file may have and a scene file may not (a scene file has a ``foundation``)
SITE_ONLY_KEYS = frozenset({"strips", "boreholes", "boundaries", "ground", "mesher", "initial_stress"})


def is_site_file(path) -> bool:
    """True if the TOML file at ``path`` describes a site: it has a key only a site file has and no
    ``foundation`` (a scene's). A file that is not valid TOML is left to the scene reader's error."""
    try:
        with open(path, "rb") as fh:
            data = tomllib.load(fh)
    except tomllib.TOMLDecodeError:
        return False
    return "foundation" not in data and bool(SITE_ONLY_KEYS & data.keys())


def site_summary(result, wall_time: float | None = None, complete: bool = True, stop=None) -> dict:
    """The per-foundation summary of a solved site (:class:`ssi.scene.site_view.SiteResult`), SI units in
    the key names: settlement [m] positive down, tilt [rad] (> 0: the right end settles more), pressure
    [Pa], forces [N/m], moments [N m/m].

    ``status`` is the solver's, as for a scene (:func:`ssi.io.cli.summary`): "completed" (load factor 1
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
            "applied_N_N_per_m": lam * sum(ld.column_force_on(part.foundation.x0, part.foundation.x1)
                                           for ld in built.site.loads),
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
        "mesher": built.mesher,
        "initial_stress": built.initial_stress_method,
        "n_elements": int(len(built.mesh.conn)),
        "n_dof": int(built.model.n_dof),
        "wall_time_s": None if wall_time is None else float(wall_time),
        "foundations": foundations,
        "differential_settlement": differential,
    }
    if status == "limit load reached":  # how the controlled path found its limit, as a scene's summary has it
        res = result.solver_result
        out |= {"limit_evidence": res.limit_evidence, "limit_uncertainty": res.limit_uncertainty,
                "limit_mechanism": res.limit_mechanism, "limit_suspect": res.limit_suspect}  # fmt: skip
    return out


def site_summary_text(s: dict) -> str:
    """The printed form of :func:`site_summary` (mm, mm/m, kPa)."""
    from .report import site_status_line

    lines = [
        f"site: {s['n_elements']} elements ({s['mesher']} mesh), {s['n_dof']} DOFs, initial stress "
        f"{s['initial_stress']}; status: {site_status_line(s)}"
    ]
    if s["stop"]:
        lines.append(f"  stopped: {s['stop']}")
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
    if s["wall_time_s"] is not None:
        lines.append(f"  wall time {s['wall_time_s']:.2f} s")
    return "\n".join(lines)


def run_site_file(site_path, overwrite: bool = False, out=None, plots=None, paraview=None, figures=True):
    """What ``ssi run`` does with a site file; returns (result, summary dict, written paths): the result
    file ``<name>.h5`` (:func:`ssi.io.results.write_result`; ``ssi show`` reads it back), the ParaView
    series ``<name>.pvd`` (a material id per soil element), the figures ``<name>_plots/*.png``
    (:mod:`ssi.io.plot_site`: the geometry under each), ``<name>_summary.json`` and ``<name>_report.html``.
    Nothing is overwritten without ``overwrite``; a run the solver stops is written marked incomplete."""
    from ..scene.site_file import read_site_file
    from ..scene.site_view import SiteResult
    from ..solver import NonConvergence
    from ..solver.progress import announce_compilation
    from .export import export_series
    from .plot_site import save_site_figures
    from .report import write_report
    from .results import atomic_path, run_output_paths, write_result

    site_path = Path(site_path)
    site, n_steps, settings = read_site_file(site_path)
    paths = run_output_paths(site_path, out, paraview, plots, overwrite)
    out, paraview, plots, summary_path, report_path = paths
    announce_compilation()
    t0 = time.perf_counter()
    stop = None
    with warnings.catch_warnings(record=True) as caught:  # shown as usual below, and kept for the report
        warnings.simplefilter("default")
        built = site.build()
        try:
            result = built.solve(n_steps=n_steps, settings=settings)
        except NonConvergence as err:  # the converged steps before the failure
            result, stop = SiteResult(built, err.result), err.report
    for w in caught:
        warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    run_warnings = [f"{w.category.__name__}: {w.message}" for w in caught]
    s = site_summary(result, time.perf_counter() - t0, stop is None, stop)
    written = [write_result(out, result, settings, overwrite=overwrite, complete=stop is None, stop=stop)]
    written.append(export_series(result, paraview, overwrite=overwrite))
    with atomic_path(summary_path, overwrite) as tmp:
        tmp.write_text(json.dumps(s, indent=1))
    written.append(summary_path)
    figs = save_site_figures(result, plots, overwrite=overwrite) if figures else []
    written += figs
    written.append(
        write_report(s, report_path, figs, site_path.name, run_warnings=run_warnings, overwrite=overwrite)
    )
    return result, s, written
