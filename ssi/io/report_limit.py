"""The report of a limit analysis (``ssi limit``): one self-contained HTML page a person opens.

    write_limit_report(cap, "footing_limit_report.html", title="footing.toml")

The page holds both brackets with their gaps (associated: a ceiling for any psi <= phi; Davis: the
conventional value for psi < phi) and what the adaptive runs did -- each run's meshes, triangles, time and
why it stopped (gap target met, refinement cap, a stalled bound: :attr:`ssi.limit.AdaptiveResult.reason`),
a table per mesh -- the forces on each foundation at the bracket's factors (``foundation_forces``), and
the mechanism figure (:func:`ssi.io.plot.limit_mechanism`) embedded as a PNG (``data:`` URI), so the page is
one file that can be mailed. The numbers are those of ``cap.to_dict()``, the same as the JSON file's, so a
limit analysis read back from its file (:class:`ssi.io.results_limit.StoredLimit`) gives the same page.
Written like the run report (:mod:`ssi.io.report`): atomically, an existing file kept unless ``overwrite``.
"""

from __future__ import annotations

import base64
import html
import io
from pathlib import Path

from .report import _page_head
from .results import atomic_path

__all__ = ["limit_report_html", "mechanism_png", "write_limit_report"]


def mechanism_png(cap, dpi: int = 110) -> bytes:
    """The mechanism figure (:func:`ssi.io.plot.limit_mechanism`) of ``cap`` as PNG bytes."""
    import matplotlib.pyplot as plt

    from .plot import limit_mechanism

    fig = limit_mechanism(cap)
    buf = io.BytesIO()
    fig.savefig(buf, dpi=dpi, format="png")
    plt.close(fig)
    return buf.getvalue()


def _num(v, k: float = 1.0, fmt: str = "{:.4g}") -> str:
    return "–" if v is None else fmt.format(k * v)


def _stop_words(reason: str | None, gap_target: float | None) -> str:
    """Why an adaptive run stopped, in words a reader checks: target met, or which cap and which bound."""
    if not reason:
        return "–"
    if reason == "gap reached":
        return "gap target met" + ("" if gap_target is None else f" ({100 * gap_target:g} %)")
    asked = "" if gap_target is None else f" of {100 * gap_target:g} %"
    return f"gap target{asked} NOT met: {reason}"


def _forces_table(rows: list[dict]) -> list[str]:
    """The forces on each foundation at the bracket's factors (``foundation_forces_N_per_m`` of
    :meth:`ssi.capacity.CapacityResult.to_dict`: per footing ``x0``, ``x1`` [m], ``reference`` [N/m] its
    loads at lambda = 1, ``associated`` and ``davis`` (lb, ub) [N/m]) as a table in kN/m."""

    def pair(v):
        return "–" if not v else f"[{_num(v[0], 1e-3)}, {_num(v[1], 1e-3)}]"

    out = [
        '<div class="scroll"><table><tr><th>#</th><th>x0 [m]</th><th>x1 [m]</th><th>its loads at lambda = 1 '
        "[kN/m]</th><th>associated [kN/m]</th><th>Davis [kN/m]</th></tr>"
    ]
    for i, r in enumerate(rows):
        out.append(
            f'<tr><td>{i}</td><td class="num">{_num(r.get("x0"), 1.0, "{:g}")}</td>'
            f'<td class="num">{_num(r.get("x1"), 1.0, "{:g}")}</td>'
            f'<td class="num">{_num(r.get("reference"), 1e-3)}</td>'
            f'<td class="num">{pair(r.get("associated"))}</td>'
            f'<td class="num">{pair(r.get("davis"))}</td></tr>'
        )
    out.append("</table></div>")
    if len(rows) > 1:
        out.append(
            "<p>The foundations share one lambda: these sum to the total, but the mechanism that sets lambda "
            "may be one foundation's (see the figure).</p>"
        )
    return out


def limit_report_html(
    cap, title: str = "ssi limit", png: bytes | None = None, run_warnings: list[str] | None = None
) -> str:
    """The page as a string: ``cap`` a :class:`ssi.scene.capacity.CapacityResult` (or a StoredLimit),
    ``png`` the mechanism figure's bytes (None: no figure, as ``--no-plots``), ``run_warnings`` the
    analysis's warnings as an engineer reads them (:func:`ssi.io.cli.warning_text`)."""
    esc = html.escape
    d = cap.to_dict()
    force = d.get("lambda_unit") == "N/m"
    k, unit = (1e-3, "kN/m") if force else (1.0, "-")
    what = (
        "the footing's vertical force V of the Settlement push"
        if force
        else f"the load factor lambda of {d.get('reference')}"
    )
    davis = not d.get("associated", True)
    parts = _page_head(title)
    target = d.get("gap_target")
    met = [d.get("reason_associated"), d.get("reason_davis") if davis else "gap reached"]
    ok = all(r in (None, "gap reached") for r in met)
    parts.append(f'<div class="verdict{" ok" if ok else ""}"><h2>Capacity bracket</h2>')
    parts.append(f"<p>Bracketed: {esc(what)} [{esc(unit)}].</p>")
    parts.append(
        "<table><tr><th>bracket</th><th>lower bound</th><th>upper bound</th><th>unit</th><th>gap [%]</th>"
        "<th>reads as</th></tr>"
    )
    brackets = [
        ("associated", d.get("lb"), d.get("ub"), d.get("gap"),
         "rigorous for psi = phi; a ceiling for any psi <= phi"),
        ("Davis", d.get("lb_davis"), d.get("ub_davis"), d.get("gap_davis"),
         "the conventional engineering value for psi < phi" if davis else "= associated (psi = phi)"),
    ]  # fmt: skip
    for name, lo, hi, gap, reads in brackets:
        parts.append(
            f'<tr><td>{name}</td><td class="num">{_num(lo, k)}</td><td class="num">{_num(hi, k)}</td>'
            f'<td>{esc(unit)}</td><td class="num">{_num(gap, 100.0, "{:.2f}")}</td><td>{esc(reads)}</td></tr>'
        )
    parts.append("</table>")
    ref = d.get("reference_footing_force_N_per_m")
    if ref and not force:
        f = ref / 1e3
        parts.append(
            f"<p>As the footing force on top of the held loads: associated [{_num(d.get('lb'), f)}, "
            f"{_num(d.get('ub'), f)}] kN/m, Davis [{_num(d.get('lb_davis'), f)}, "
            f"{_num(d.get('ub_davis'), f)}] kN/m.</p>"
        )
    for name, reason in (("associated", d.get("reason_associated")), ("Davis", d.get("reason_davis"))):
        if reason is not None:
            words = _stop_words(reason, target)
            cls = "" if reason == "gap reached" else ' class="warn"'
            parts.append(f"<p{cls}>{name} run: {esc(words)}.</p>")
    parts.append("</div>")
    if run_warnings:
        parts.append("<h2>Warnings</h2>")
        parts += [f'<div class="warn">{esc(w)}</div>' for w in run_warnings]
    forces = d.get("foundation_forces_N_per_m")  # a push has none: lambda is itself the footing's force
    if forces:
        parts.append("<h2>Forces on the foundations at collapse</h2>")
        parts += _forces_table(forces)
    parts.append("<h2>What the adaptive runs did</h2>")
    parts.append(
        f"<p>{d.get('triangles')} triangles on the last mesh; {_num(d.get('time_s'), 1.0, '{:.1f}')} s in "
        "all. Each mesh refines the last where the bracket's gap is (nested meshes: the lower bound cannot "
        "fall nor the upper bound rise).</p>"
    )
    for name, rows in (("associated", d.get("history_associated")), ("Davis", d.get("history_davis"))):
        if not rows:
            continue
        parts.append(f"<h3>{name} ({len(rows)} mesh{'es' if len(rows) > 1 else ''})</h3>")
        parts.append(
            '<div class="scroll"><table><tr><th>mesh</th><th>triangles</th><th>LB</th><th>UB</th>'
            f"<th>best LB [{esc(unit)}]</th><th>best UB [{esc(unit)}]</th><th>gap [%]</th><th>time [s]</th>"
            "</tr>"
        )
        for r in rows:
            best_lb, best_ub = r.get("best_lb", r.get("lb")), r.get("best_ub", r.get("ub"))
            gap = None
            if best_lb is not None and best_ub is not None and best_lb + best_ub > 0:
                gap = (best_ub - best_lb) / (best_ub + best_lb)
            t = sum(r.get(key) or 0.0 for key in ("t_lb", "t_ub"))
            parts.append(
                f'<tr><td class="num">{r.get("step")}</td><td class="num">{r.get("n_el")}</td>'
                f'<td class="num">{_num(r.get("lb"), k)}</td><td class="num">{_num(r.get("ub"), k)}</td>'
                f'<td class="num">{_num(best_lb, k)}</td><td class="num">{_num(best_ub, k)}</td>'
                f'<td class="num">{_num(gap, 100.0, "{:.2f}")}</td><td class="num">{t:.1f}</td></tr>'
            )
        parts.append("</table></div>")
    if png is not None:
        data = base64.b64encode(png).decode("ascii")
        parts.append("<h2>Mechanism</h2>")
        parts.append(
            f'<figure><img src="data:image/png;base64,{data}" alt="collapse mechanism">'
            "<figcaption>The upper bound's mechanism on the last associated mesh: the speed and the velocity "
            "(unit reference power: only the pattern means anything) and where the soil dissipates (over "
            "the mesh); the foundations in black.</figcaption></figure>"
        )
    parts.append(f"<h2>As printed</h2><pre>{esc(cap.summary())}</pre>")
    parts.append(
        "<p><small>SI units in the JSON and HDF5 files; this page shows kN/m. Written by ssi.</small></p>"
    )
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def write_limit_report(
    cap, path: str | Path, title: str | None = None, figure: bool = True, overwrite: bool = False,
    run_warnings: list[str] | None = None,
) -> Path:  # fmt: skip
    """Write :func:`limit_report_html` to ``path`` (atomically, the user's umask; an existing file is kept
    unless ``overwrite``), the mechanism figure embedded unless ``figure`` is False. Returns the path."""
    path = Path(path)
    png = mechanism_png(cap) if figure else None
    text = limit_report_html(cap, title or path.stem, png, run_warnings)
    with atomic_path(path, overwrite) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path
