"""The run report: one self-contained HTML page per scene or site that a person opens (``ssi run`` writes it).

    write_report(summary_dict, "strip_report.html", figures=[...png paths...], title="strip.toml")

The page holds the summary as a table with units, the capacity and how it was found, one row per phase
and the envelope over the phases, the RC design lines, the warnings of the run, and every figure, linked
by a path relative to the page (the figures stay beside it; nothing is fetched from the network: the style
is inline, there is no script). Values come from :func:`ssi.io.cli.summary` (SI units), shown in kN, kPa,
mm, MPa. A site's page (:func:`site_report_html`, from :func:`ssi.io.cli.summary`) holds one row
per foundation and the differential settlements.
"""

from __future__ import annotations

import html
import os
from pathlib import Path

from .results import atomic_path

# (summary key, label, scale from SI, unit, format): the rows of the summary table, in reading order
SUMMARY_ROWS = (
    ("foundation_load", "load on the foundation at the end", 1e-3, "kN/m", "{:.2f}"),
    ("column_load", "column load at the end", 1e-3, "kN/m", "{:.2f}"),
    ("max_settlement", "largest settlement at the end", 1e3, "mm", "{:.3f}"),
    ("x_max_settlement", "  at x", 1.0, "m", "{:.3f}"),
    ("mean_contact_pressure", "contact pressure, mean", 1e-3, "kPa", "{:.2f}"),
    ("peak_contact_pressure", "contact pressure, peak (edges excluded)", 1e-3, "kPa", "{:.2f}"),
    ("x_peak_contact_pressure", "  at x", 1.0, "m", "{:.3f}"),
    ("max_contact_pressure", "edge pressure (corner singularity, not a bearing pressure)", 1e-3, "kPa",
     "{:.2f}"),
    ("contact_resultant", "contact resultant", 1e-3, "kN/m", "{:.2f}"),
    ("max_abs_moment", "largest |bending moment| at the end", 1e-3, "kN m/m", "{:.2f}"),
    ("x_max_abs_moment", "  at x", 1.0, "m", "{:.3f}"),
    ("load_factor", "load factor reached (of a phased scene: phase time)", 1.0, "-", "{:.4g}"),
    ("steps", "converged steps", 1.0, "-", "{:d}"),
    ("wall_time_s", "wall time", 1.0, "s", "{:.2f}"),
)  # fmt: skip
PHASE_COLUMNS = (
    ("end_load_factor", "load factor at the end", 1.0, "-", "{:.4g}"),
    ("column_load", "column load at the end", 1e-3, "kN/m", "{:.2f}"),
    ("foundation_load", "foundation load at the end", 1e-3, "kN/m", "{:.2f}"),
    ("max_settlement", "max settlement", 1e3, "mm", "{:.3f}"),
    ("max_abs_moment", "max |M|", 1e-3, "kN m/m", "{:.2f}"),
    ("mean_pressure", "mean pressure at the end", 1e-3, "kPa", "{:.2f}"),
    ("peak_pressure", "max peak pressure (edges excluded)", 1e-3, "kPa", "{:.2f}"),
    ("max_steel_stress", "max |steel stress|", 1e-6, "MPa", "{:.1f}"),
    ("max_crack_width", "max crack width w_k (EN 1992)", 1e3, "mm", "{:.3f}"),
)
ENVELOPE_UNITS = {
    "max_settlement": ("largest settlement", 1e3, "mm", "{:.3f}"),
    "max_abs_moment": ("largest |M|", 1e-3, "kN m/m", "{:.2f}"),
    "peak_pressure": ("largest peak contact pressure (edges excluded)", 1e-3, "kPa", "{:.2f}"),
    "max_steel_stress": ("largest |steel stress|", 1e-6, "MPa", "{:.1f}"),
    "max_crack_width": ("largest crack width w_k (EN 1992)", 1e3, "mm", "{:.3f}"),
    "foundation_load": ("largest load at a phase end", 1e-3, "kN/m", "{:.2f}"),
}
# (scale from SI, unit shown) of each estimated quantity (ssi.scene.estimate.QUANTITIES)
ESTIMATE_UNITS = {
    "capacity": (1e-3, "kN/m"),
    "max_settlement": (1e3, "mm"),
    "differential_settlement": (1e3, "mm"),
    "max_contact_pressure": (1e-3, "kPa"),
    "max_moment": (1e-3, "kN m/m"),
    "limit_load_factor": (1.0, "-"),
}


STYLE = """
body { font-family: sans-serif; max-width: 60em; margin: 1em auto; padding: 0 1em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.5em; }
table { border-collapse: collapse; margin: 0.5em 0; }
td, th { border: 1px solid #bbb; padding: 0.2em 0.6em; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.scroll { overflow-x: auto; }
.warn { background: #fff4e0; border-left: 4px solid #e69500; padding: 0.3em 0.8em; margin: 0.3em 0; }
.status { font-weight: bold; }
.verdict { border: 2px solid #444; padding: 0.4em 1em; margin: 0.5em 0 1em 0; }
.verdict p.line { font-size: 1.2em; font-weight: bold; margin: 0.3em 0; }
.verdict.ok { border-color: #2a7a2a; } .verdict.fail { border-color: #b00020; background: #fff0f0; }
figure { margin: 1em 0; } figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
pre { background: #f6f6f6; padding: 0.5em; overflow-x: auto; }
"""


def _page_head(title: str) -> list[str]:
    """The opening lines of a report page (doctype, the bundled style, the title as heading)."""
    esc = html.escape
    return [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{esc(title)}</title>",
        f"<style>{STYLE}</style></head><body>",
        f"<h1>{esc(title)}</h1>",
    ]


def _verdict_section(s: dict) -> list[str]:
    """The verdict (:mod:`ssi.scene.verdict`) as the report's first screen: the sentence, the capacity
    bracket, per foundation the settlement, tilt and RC utilisations (above 1 flagged), the warnings."""
    v = s.get("verdict")
    if not v:
        return []
    esc = html.escape
    if v.get("skipped"):
        return [f'<div class="verdict"><p class="line">Verdict not asked ({esc(v["skipped"])})</p></div>']
    from ..scene.verdict import verdict_lines

    cls = {True: " ok", False: " fail"}.get(v.get("carries"), "")
    if v.get("rc_ok") is False:
        cls = " fail"
    lines = verdict_lines(v)
    rest = [ln.strip() for ln in lines[1:] if not ln.strip().startswith("WARNING")]
    out = [f'<div class="verdict{cls}"><h2>Verdict</h2><p class="line">{esc(v["line"])}</p>']
    out += [f"<p>{esc(ln)}</p>" for ln in rest]
    out += [f'<div class="warn">{esc(fl)}</div>' for fl in v.get("flags", [])]
    out.append("</div>")
    return out


def _fmt(value, scale, fmt) -> str:
    if value is None:
        return "–"
    if fmt == "{:d}":
        return str(int(value))
    return fmt.format(value * scale)


def limit_meaning(s: dict) -> str:
    """What a limit of the summary ``s`` means to the reader: a push-over has no loads to carry."""
    if s.get("push_over"):
        return "the push reached the footing's limit, where its load peaked or levelled off"
    return "the scene cannot carry its full loads"


def report_warnings(s: dict, run_warnings: list[str] | None = None) -> list[str]:
    """What the reader must not miss: the run's own warnings (``run_warnings``: bad-looking input, solver
    notes), an incomplete run, a limit load and a failed check of it, viscous rows left out, no limit found
    on a push-over, the corner singularity of the contact pressure."""
    out = list(run_warnings or [])
    if s["status"] == "stopped":
        out.append(
            f"The run stopped before the end of its load path (solver failure, not a detected limit load): "
            f"{s.get('stop_reason')}. The values are those of the last converged step."
        )
        if s.get("stop_message"):
            out.append(s["stop_message"])
        if s.get("stop_ill_posed"):
            out.append(f"Where it stopped, the soil's rate problem is ill-posed: {s['stop_ill_posed']}.")
    elif s["status"] == "limit load reached":
        out.append(
            f"Limit load reached at load factor {s['limit_load_factor']:.4g}: {limit_meaning(s)}; the path "
            "up to the limit is the answer."
        )
        if s.get("limit_suspect"):  # a failed check of the limit (ssi/solver/path.py): not a capacity as read
            out.append(f"The limit is suspect: {s['limit_suspect']}.")
    cap = s.get("capacity") or {}
    if cap.get("viscous_rows"):
        out.append(
            f"{cap['viscous_rows']} rows are viscous states (groups with their own Duvaut-Lions viscosity: "
            "overstress, not equilibria): left out of the capacity and of the maxima."
        )
    if s.get("push_over") and cap and not cap.get("is_limit"):
        out.append(
            "The push-over did not reach a limit: its largest load is a lower bound of the capacity "
            "(push further)."
        )
    if cap.get("warning"):  # the capacity's error estimate (ssi.scene.estimate): above 5 % or not asymptotic
        out.append(str(cap["warning"]))
    if "max_contact_pressure" in s:
        out.append(
            "The edge pressure is a singularity of the stiff foundation's corner: it grows as the mesh is "
            "refined and is not a bearing pressure (read the mean and the peak away from the edges)."
        )
    return out


# estimated quantities that are singular: the largest contact pressure sits at a stiff strip's corner, where
# the elastic pressure is infinite and grows under every refinement -- no discretisation error exists to be
# estimated (its "extrapolation" can even be negative), so its row says so instead of giving numbers
SINGULAR_ESTIMATES = {
    "max_contact_pressure": "the corner singularity: grows under refinement, no error to estimate"
}


def _capacity_estimate_rows(est: dict | None) -> str:
    """The capacity table's rows of its estimated discretisation error (``capacity["estimate"]``)."""
    if not est:
        return ""
    rows = [
        ("estimated discretisation error", f"{100 * est['relative']:.1f}", "%"),
        ("extrapolated capacity (Richardson)", f"{est['extrapolated'] / 1e3:.2f}", "kN/m"),
    ]
    if est.get("values"):
        rows.append(("capacity on meshes h, h/2, h/4", ", ".join(f"{v / 1e3:.2f}" for v in est["values"]),
                     "kN/m"))  # fmt: skip
        rows.append(("observed order of convergence", f"{est['order']:.2f}", "-"))
    return "".join(
        f'<tr><td>{html.escape(a)}</td><td class="num">{b}</td><td>{c}</td></tr>' for a, b, c in rows
    )


def _estimate_section(s: dict) -> list[str]:
    """The error estimate's table (``s["error_estimate"]``): each headline quantity's value, estimated
    error, extrapolated value and whether the refinements were in the asymptotic range."""
    est = s.get("error_estimate")
    if not est:
        return []
    esc = html.escape
    if est.get("failed"):
        return [
            "<h2>Discretisation error</h2>",
            f'<div class="warn">not estimated: {esc(est["failed"])}</div>',
        ]
    out = [
        "<h2>Discretisation error</h2>",
        f"<p>Richardson extrapolation over halvings of {esc(', '.join(est['refinements']))} (the scene as "
        "given, h/2 and h/4); the quantity asked for first.</p>",
        '<div class="scroll"><table><tr><th>quantity</th><th>value</th><th>extrapolated</th><th>unit</th>'
        "<th>estimated error [%]</th><th>observed order</th><th>asymptotic</th></tr>",
    ]
    qs = est["quantities"]
    for q in [est["asked"]] + [q for q in qs if q != est["asked"]]:
        if q not in qs:
            continue
        e = qs[q]
        scale, unit = ESTIMATE_UNITS.get(q, (1.0, e["unit"]))
        if q in SINGULAR_ESTIMATES:
            out.append(
                f'<tr><td>{esc(q)}</td><td class="num">{e["value"] * scale:.4g}</td><td>–</td>'
                f'<td>{esc(unit)}</td><td colspan="3">{esc(SINGULAR_ESTIMATES[q])}</td></tr>'
            )
            continue
        orders = ", ".join(f"{r} {p:.2f}" for r, p in e["orders"].items())
        out.append(
            f'<tr><td>{esc(q)}</td><td class="num">{e["value"] * scale:.4g}</td>'
            f'<td class="num">{e["extrapolated"] * scale:.4g}</td><td>{esc(unit)}</td>'
            f'<td class="num">{100 * e["relative"]:.2f}</td><td>{esc(orders)}</td>'
            f"<td>{'yes' if e['asymptotic'] else 'NO (a rough bound)'}</td></tr>"
        )
    out.append("</table></div>")
    return out


def report_html(
    s: dict, figures: list[Path] | None = None, base: Path | None = None, title: str = "ssi run",
    run_warnings: list[str] | None = None,
) -> str:  # fmt: skip
    """The report page as a string: summary dict ``s`` (:func:`ssi.io.cli.summary`), ``figures`` (PNG
    paths, linked relative to the folder ``base`` the page is written into), ``title`` (the scene's name),
    ``run_warnings`` (texts)."""
    esc = html.escape
    parts = _page_head(title) + _verdict_section(s)
    status = {"completed": "completed", "limit load reached": "limit load reached", "stopped": "INCOMPLETE"}
    parts.append(
        f'<p class="status">status: {esc(status.get(s["status"], s["status"]))}'
        + (f", last phase {esc(repr(s['phase']))}" if s.get("phase") else "")
        + "</p>"
    )
    warn = report_warnings(s, run_warnings)
    if warn:
        parts.append("<h2>Warnings</h2>")
        parts += [f'<div class="warn">{esc(w)}</div>' for w in warn]
    cap = s.get("capacity")
    if cap and (s.get("push_over") or cap["is_limit"]):  # a load-controlled run carried its loads
        word = "Capacity" if cap["is_limit"] else "Largest load carried (no limit found)"
        parts.append(f"<h2>{word}</h2>")
        parts.append(
            "<table><tr><th>quantity</th><th>value</th><th>unit</th></tr>"
            f"<tr><td>{'footing load (soil reaction)' if s.get('push_over') else 'load'}</td>"
            f'<td class="num">{cap["load"] / 1e3:.2f}</td><td>kN/m</td></tr>'
            f'<tr><td>at settlement</td><td class="num">{1e3 * cap["settlement"]:.2f}</td><td>mm</td></tr>'
            + _capacity_estimate_rows(cap.get("estimate"))
            + f"</table><p>How it was found: {esc(cap['how'])}.</p>"
        )
    parts += _estimate_section(s)
    parts.append("<h2>Summary</h2>")
    parts.append('<div class="scroll"><table><tr><th>quantity</th><th>value</th><th>unit</th></tr>')
    for key, label, scale, unit, fmt in SUMMARY_ROWS:
        if key in s and s[key] is not None:
            parts.append(
                f'<tr><td>{esc(label)}</td><td class="num">{_fmt(s[key], scale, fmt)}</td>'
                f"<td>{esc(unit)}</td></tr>"
            )
    parts.append("</table></div>")
    table = s.get("phases") or []
    if table:
        parts.append("<h2>Per phase</h2>" if len(table) > 1 else "<h2>Over the load path</h2>")
        cols = [c for c in PHASE_COLUMNS if any(r.get(c[0]) is not None for r in table)]
        parts.append('<div class="scroll"><table><tr><th>phase</th><th>steps</th>')
        parts += [f"<th>{esc(label)} [{esc(unit)}]</th>" for _, label, _, unit, _ in cols]
        parts.append("</tr>")
        for row in table:
            cells = "".join(
                f'<td class="num">{_fmt(row.get(key), scale, fmt)}</td>' for key, _, scale, _, fmt in cols
            )
            parts.append(f"<tr><td>{esc(row['name'])}</td><td>{row['first']}–{row['last']}</td>{cells}</tr>")
        parts.append("</table></div>")
        env = s.get("envelope") or {}
        if len(table) > 1 and env:
            parts.append("<h3>Envelope over the phases</h3>")
            parts.append("<table><tr><th>quantity</th><th>value</th><th>unit</th><th>phase</th></tr>")
            for key, (label, scale, unit, fmt) in ENVELOPE_UNITS.items():
                if key in env:
                    parts.append(
                        f'<tr><td>{esc(label)}</td><td class="num">{_fmt(env[key]["value"], scale, fmt)}'
                        f"</td><td>{esc(unit)}</td><td>{esc(env[key]['phase'])}</td></tr>"
                    )
            parts.append("</table>")
    if s.get("design"):
        from ..scene.design import summary_text as design_text

        parts.append("<h2>RC design</h2>")
        parts.append(f"<pre>{esc(design_text(s['design']))}</pre>")
    parts += _figures(figures, base)
    parts.append(
        "<p><small>SI units in the result file and the JSON summary; this page shows kN, kPa, mm, MPa. "
        "Written by ssi.</small></p></body></html>"
    )
    return "\n".join(parts) + "\n"


def site_status_line(s: dict) -> str:
    """The status as a sentence: the solver's, with the load factor reached and a SUSPECT limit named."""
    if s["status"] == "limit load reached":
        text = (
            f"limit load reached at load factor {s['limit_load_factor']:.4g} of "
            + (f"phase '{s['phase']}' (phase time)" if s.get("phase") else "the site's loads")
            + " (the path up to the limit is the answer)"
        )
        if s.get("limit_suspect"):
            text += f"; SUSPECT: {s['limit_suspect']}"
        return text
    if s["status"] == "stopped":
        return (
            f"INCOMPLETE: stopped at load factor {s.get('load_factor', float('nan')):.4g} (solver failure, "
            "not a detected limit load)"
        )
    return s["status"]


def site_report_html(
    s: dict, figures: list[Path] | None = None, base: Path | None = None, title: str = "ssi run",
    run_warnings: list[str] | None = None,
) -> str:  # fmt: skip
    """The report page of a site (``s`` from :func:`ssi.io.cli.summary`): the mesh and the initial
    stress, one row per foundation (settlement, tilt, pressure), the differential settlements, the
    warnings and the figures."""
    esc = html.escape
    parts = (
        _page_head(title)
        + _verdict_section(s)
        + [
            f'<p class="status">status: {esc(site_status_line(s))}</p>',
            f"<p>{s['n_elements']} soil elements ({esc(s['mesher'])} mesh), {s['n_dof']} DOFs; initial "
            f"stress {esc(s['initial_stress'])}.</p>",
        ]
    )
    stopped = s.get("stop_message") or s.get("stop")
    warn = list(run_warnings or []) + ([f"The run stopped: {stopped}"] if stopped else [])
    if warn:
        parts.append("<h2>Warnings</h2>")
        parts += [f'<div class="warn">{esc(w)}</div>' for w in warn]
    parts += _estimate_section(s)
    parts.append("<h2>Foundations</h2>")
    parts.append(
        '<div class="scroll"><table><tr><th>#</th><th>type</th><th>x0 [m]</th><th>x1 [m]</th>'
        "<th>mean settlement [mm]</th><th>max settlement [mm]</th><th>tilt [mm/m]</th>"
        "<th>mean pressure [kPa]</th><th>contact resultant [kN/m]</th><th>column load [kN/m]</th>"
        "<th>max |M| [kN m/m]</th></tr>"
    )
    for f in s["foundations"]:
        rigid = f["type"] == "rigid strip"
        cells = [
            _fmt(f["settlement_m"] if rigid else f["mean_settlement_m"], 1e3, "{:.3f}"),
            _fmt(None if rigid else f["max_settlement_m"], 1e3, "{:.3f}"),
            _fmt(None if rigid else f["tilt_rad"], 1e3, "{:.3f}"),
            _fmt(f.get("pressure_Pa"), 1e-3, "{:.2f}"),
            _fmt(f.get("contact_N_N_per_m"), 1e-3, "{:.2f}"),
            _fmt(f.get("applied_N_N_per_m"), 1e-3, "{:.2f}"),
            _fmt(f.get("max_abs_moment_Nm_per_m"), 1e-3, "{:.2f}"),
        ]
        parts.append(
            f"<tr><td>{f['index']}</td><td>{esc(f['type'])}</td>"
            f'<td class="num">{f["x0_m"]:g}</td><td class="num">{f["x1_m"]:g}</td>'
            + "".join(f'<td class="num">{c}</td>' for c in cells)
            + "</tr>"
        )
    parts.append("</table></div>")
    parts += _site_phase_rows(s)
    if s["differential_settlement"]:
        parts.append("<h2>Differential settlement</h2>")
        parts.append("<table><tr><th>strips</th><th>mean settlement difference [mm]</th></tr>")
        for d in s["differential_settlement"]:
            parts.append(
                f"<tr><td>#{d['i']} - #{d['j']}</td>"
                f'<td class="num">{1e3 * d["mean_settlement_i_minus_j_m"]:.3f}</td></tr>'
            )
        parts.append("</table>")
    designed = [f for f in s["foundations"] if f.get("design")]
    if designed:
        from ..scene.design import summary_text as design_text

        parts.append("<h2>RC design</h2>")
        parts += [f"<h3>strip #{f['index']}</h3><pre>{esc(design_text(f['design']))}</pre>" for f in designed]
    parts += _figures(figures, base)
    parts.append(
        "<p><small>SI units in the result file and the JSON summary; this page shows kN, kPa, mm. "
        "Written by ssi.</small></p></body></html>"
    )
    return "\n".join(parts) + "\n"


def _site_phase_rows(s: dict) -> list[str]:
    """A phased site's table: one row per phase and foundation, its end state (the summary's ``phases``)."""
    table = s.get("phases") or []
    if len(table) < 2:
        return []
    esc = html.escape
    out = [
        "<h2>Per phase</h2>",
        '<div class="scroll"><table><tr><th>phase</th><th>steps</th><th>#</th><th>mean settlement [mm]</th>'
        "<th>max settlement [mm]</th><th>tilt [mm/m]</th><th>column load [kN/m]</th></tr>",
    ]
    for row in table:
        for f in row["foundations"]:
            mean = f.get("mean_settlement_m", f.get("settlement_m"))
            cells = [
                _fmt(mean, 1e3, "{:.3f}"),
                _fmt(f.get("max_settlement_m"), 1e3, "{:.3f}"),
                _fmt(f.get("tilt_rad"), 1e3, "{:.3f}"),
                _fmt(f.get("column_N_N_per_m"), 1e-3, "{:.2f}"),
            ]
            out.append(
                f"<tr><td>{esc(row['name'])}</td><td>{row['first']}–{row['last']}</td><td>{f['index']}</td>"
                + "".join(f'<td class="num">{c}</td>' for c in cells)
                + "</tr>"
            )
    out.append("</table></div>")
    return out


def _figures(figures, base) -> list[str]:
    if not figures:
        return []
    esc = html.escape
    out = ["<h2>Figures</h2>"]
    for fig in figures:
        rel = Path(os.path.relpath(Path(fig), base) if base is not None else str(fig)).as_posix()
        out.append(
            f'<figure><img src="{esc(rel)}" alt="{esc(Path(fig).stem)}">'
            f"<figcaption>{esc(Path(fig).stem.replace('_', ' '))}</figcaption></figure>"
        )
    return out


def write_report(
    s: dict, path: str | Path, figures: list[Path] | None = None, title: str | None = None,
    run_warnings: list[str] | None = None, overwrite: bool = False,
) -> Path:  # fmt: skip
    """Write :func:`report_html` to ``path`` (atomically, the user's umask; an existing file is kept unless
    ``overwrite``), the figures linked relative to its folder. Returns the path."""
    path = Path(path)
    page = site_report_html if s.get("kind") == "site" else report_html
    text = page(s, figures, path.parent.resolve(), title or path.stem, run_warnings)
    with atomic_path(path, overwrite) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path
