"""The engineer's verdict of a run (issue 46): does the scene or site carry its loads, with what margin,
how much does it settle, is the RC adequate.

:func:`verdict` takes the run's summary (:func:`ssi.io.cli.summary`) and the scene or site it solved, and
brackets the capacity of the run's loads by limit analysis (:meth:`ssi.scene.Scene.limit_analysis`: the
associated ceiling and the Davis estimate, each with its gap, to a cheap ``gap``). The margin is the Davis
bracket of the load factor lambda (the conventional value for psi < phi; the associated one when psi =
phi): lambda_LB >= 1 carries the loads, lambda_UB < 1 does not, a bracket containing 1 is undecided (the
bracket is refined by ``ssi limit`` with a smaller gap). The margin's second number is the factor of
safety on strength (:meth:`ssi.scene.Scene.safety_factor`: the F that brings c / F and tan phi / F to
collapse under the loads at factor 1, a certified bracket of the Davis materials at ``fos_gap``): lambda
says how far the loads may grow, F how far the soil's strength may fall. What the limit analysis cannot
represent (an elastic layer, an excavation, a horizontal push ...) is named as the reason the capacity was
not computed.

Beside it, per foundation: settlement, tilt, differential settlement and the RC utilisations (M_Ed/M_Rd,
V_Ed/V_Rd,c, the crack width w_k against ``w_k_limit``), each above 1 flagged; and the incremental run's
own limit against the bracket: above 1.03 x the associated upper bound (a ceiling for any psi <= phi) or
outside the Davis bracket is flagged with its excess and what to do.
"""

from __future__ import annotations

import math
import time

from ..capacity import capacity_bracket  # the bracket of the loads as plain data (ssi.capacity)

W_K_LIMIT_MM = 0.3  # EN 1992-1-1 Table 7.1N, exposure XC2-XC4 (quasi-permanent): the default crack limit
UB_EXCESS = 1.03  # an incremental limit above 1.03 x the associated upper bound is flagged


def _finite(v) -> float | None:
    return None if v is None or not math.isfinite(float(v)) else float(v)


def fos_bracket(scene, gap: float = 0.05, max_elements: int = 6000) -> dict:
    """The factor of safety on strength of the scene's (or site's) loads as plain data (:meth:`ssi.scene.
    Scene.safety_factor`, Davis materials, a certified bracket refined to the relative ``gap``), or
    ``{"not_computed": why}`` when the strength reduction refuses the problem (the refusal's own message)."""
    t0 = time.perf_counter()
    try:
        sf = scene.safety_factor(gap=gap, max_elements=max_elements)
    except (ValueError, NotImplementedError, TypeError) as err:
        return {"not_computed": str(err)}
    return {
        "lb": _finite(sf.f_lb),
        "ub": _finite(sf.f_ub),
        "gap": _finite(sf.gap),
        "gap_target": gap,
        "davis": bool(sf.davis),
        "converged": bool(sf.converged),
        "reason": sf.reason or "gap reached",
        "n_triangles": int(sf.n_triangles),
        "time_s": time.perf_counter() - t0,
    }


def _word_line(b: dict, push: bool) -> tuple[str, bool | None]:
    """The verdict in words and whether the loads are carried (None: undecided or not asked)."""
    if "not_computed" in b:
        return f"capacity not computed: {b['not_computed']}", None
    lo, hi = b["lb_davis"], b["ub_davis"]
    hi_t = "inf" if hi is None else f"{hi:#.3g}"  # '#': trailing zeros kept, so both ends read alike
    kind = "Davis" if b["davis"] else "associated"
    if push:  # a Settlement push has no loads to carry: its capacity is the footing's force
        return (
            f"a push-over (no loads to carry): capacity V in [{(lo or 0) / 1e3:.4g}, "
            f"{'inf' if hi is None else f'{hi / 1e3:.4g}'}] kN/m ({kind})",
            None,
        )
    if b.get("no_mechanism"):
        return (
            f"carries its loads: no collapse mechanism exists ({kind} lower bound unbounded: every mechanism "
            "would cross soil taken as never yielding)",
            True,
        )
    if lo is not None and lo >= 1.0:
        return f"carries its loads with margin lambda in [{lo:#.3g}, {hi_t}] ({kind} bracket)", True
    if hi is not None and hi < 1.0:
        return f"does not carry its loads ({kind} lambda in [{lo or 0:#.3g}, {hi_t}] < 1)", False
    return (
        f"undecided: the {kind} bracket lambda in [{lo or 0:.3g}, {hi_t}] contains 1 (refine it: "
        "`ssi limit --gap 0.01`)",
        None,
    )


def _rc_flags(where: str, design: dict | None, w_k_limit_mm: float) -> tuple[dict, list[str]]:
    """The RC utilisations of one strip's design summary and the flags of those above 1."""
    if not design:
        return {}, []
    u = {
        "M_Ed/M_Rd": design.get("util_M_max"),
        "V_Ed/V_Rd,c": design.get("util_V_max"),
        "w_k/w_lim": None if design.get("w_k_max_mm") is None else design["w_k_max_mm"] / w_k_limit_mm,
    }
    flags = []
    what = {
        "M_Ed/M_Rd": "bending exceeds the section's resistance: more or larger bars, or a deeper strip",
        "V_Ed/V_Rd,c": "shear exceeds the resistance without shear links: a deeper strip or shear links",
        "w_k/w_lim": f"the crack width exceeds {w_k_limit_mm:g} mm: more, smaller bars closer to the face",
    }
    for k, v in u.items():
        if v is not None and math.isfinite(v) and v > 1.0:
            flags.append(f"{where}: {k} = {v:.2f} > 1: {what[k]}")
    return u, flags


def _limit_flag(s: dict, b: dict) -> dict | None:
    """The incremental run's limit against the bracket: {"value", "ub_assoc", "davis", "excess", "flag"} or
    None (no limit, or no bracket). ``excess`` relative to the bound it passes."""
    if "not_computed" in b:
        return None
    if s.get("push_over"):
        cap = s.get("capacity") or {}
        if not cap.get("is_limit"):
            return None
        value = float(cap["load"])
    elif s.get("status") == "limit load reached" and s.get("limit_load_factor") is not None:
        value = float(s["limit_load_factor"])
    else:
        return None
    ub, lo_d, hi_d = b["ub"], b["lb_davis"], b["ub_davis"]
    out = {"value": value, "ub_assoc": ub, "lb_davis": lo_d, "ub_davis": hi_d, "excess": 0.0, "flag": ""}
    unit = " kN/m" if b["unit"] == "N/m" else ""
    k = 1e-3 if b["unit"] == "N/m" else 1.0
    if ub is not None and value > UB_EXCESS * ub:
        out["excess"] = value / ub - 1.0
        out["flag"] = (
            f"the incremental limit {k * value:.4g}{unit} lies {100 * out['excess']:.1f} % above the "
            f"associated upper bound {k * ub:.4g}{unit}, a ceiling for any psi <= phi: a mesh "
            "overestimate, not a capacity. Refine the mesh (`ssi run --estimate`) or read the bracket"
        )
    elif hi_d is not None and value > hi_d:
        out["excess"] = value / hi_d - 1.0
        out["flag"] = (
            f"the incremental limit {k * value:.4g}{unit} lies {100 * out['excess']:.1f} % above the Davis "
            f"bracket [{k * (lo_d or 0):.4g}, {k * hi_d:.4g}]{unit}: a mesh overestimate of the conventional "
            "capacity. Refine the mesh (`ssi run --estimate`) or read the bracket"
        )
    elif lo_d is not None and value < lo_d:
        out["excess"] = value / lo_d - 1.0
        out["flag"] = (
            f"the incremental limit {k * value:.4g}{unit} lies {-100 * out['excess']:.1f} % below the Davis "
            f"bracket [{k * lo_d:.4g}, {k * (hi_d or math.inf):.4g}]{unit}: the non-associated path "
            "(psi < phi) peaked or stalled below the conventional capacity. Read the bracket, and check the "
            'path\'s limit on a finer mesh or in Davis mode ([solve] flow = "davis")'
        )
    return out


def verdict(
    s: dict, scene, gap: float = 0.05, max_elements: int = 6000, w_k_limit_mm: float = W_K_LIMIT_MM,
    bracket: dict | None = None, fos_gap: float | None = 0.05, fos: dict | None = None,
) -> dict:  # fmt: skip
    """The verdict of a run whose summary is ``s`` (a scene's or a site's) on ``scene`` (the Scene or Site
    it solved): ``line`` (one sentence), ``carries`` (True / False / None: undecided or not computed),
    ``capacity`` (:func:`capacity_bracket`, or ``bracket`` when given), ``margin`` the Davis lambda bracket
    [lb, ub] (None without one), ``fos`` the factor of safety on strength (:func:`fos_bracket` at the
    relative gap ``fos_gap``, or ``fos`` when given; ``{"skipped": why}`` without a capacity bracket or for
    a push-over; None: ``fos_gap`` None, not asked), ``fos_margin`` its [F_LB, F_UB] (None without one),
    ``foundations`` (per foundation: settlement [m], tilt [rad], the RC
    utilisations), ``differential_settlement`` [m], ``incremental_limit`` (:func:`_limit_flag`) and
    ``flags`` (sentences for an engineer: what, where, what to do)."""
    b = capacity_bracket(scene, gap, max_elements) if bracket is None else bracket
    push = bool(s.get("push_over")) or b.get("unit") == "N/m"
    line, carries = _word_line(b, push)
    flags = []
    if "not_computed" not in b and not push and b.get("reason") and b["reason"] != "gap reached":
        flags.append(
            f"the capacity bracket stopped short of its {100 * gap:g} % gap ({b['reason']}): the bounds are "
            "certified but wide; `ssi limit` refines it"
        )
    if carries is False:
        flags.append(
            "the loads exceed the conventional (Davis) capacity: reduce the loads, widen or deepen the "
            "foundation, or improve the soil"
        )
    fnds = []
    at_limit = s.get("status") == "limit load reached"
    if s.get("kind") == "site":
        for f in s["foundations"]:
            where = f"foundation #{f['index']} ({f['type']} [{f['x0_m']:g}, {f['x1_m']:g}] m)"
            row = {"where": where}
            if f["type"] == "rigid strip":
                row["settlement_m"] = f["settlement_m"]
            else:
                row.update(settlement_m=f["max_settlement_m"], mean_settlement_m=f["mean_settlement_m"],
                           tilt_rad=f["tilt_rad"])  # fmt: skip
                u, fl = _rc_flags(where, f.get("design"), w_k_limit_mm)
                row["utilisation"] = u
                flags += fl
            fnds.append(row)
        diff = [
            {"i": d["i"], "j": d["j"], "m": d["mean_settlement_i_minus_j_m"]}
            for d in s.get("differential_settlement", [])
        ]
    else:
        row = {"where": "the foundation", "settlement_m": s.get("max_settlement")}
        u, fl = _rc_flags("the strip", s.get("design"), w_k_limit_mm)
        row["utilisation"] = u
        flags += fl
        fnds.append(row)
        diff = []
    over = [
        f"{k} {val:.2f}"
        for f in fnds
        for k, val in (f.get("utilisation") or {}).items()
        if val is not None and math.isfinite(val) and val > 1.0
    ]
    rc_ok = not over
    if over:  # the soil may carry the loads while the strip does not: said in the same sentence
        line += "; but the RC strip is over-utilised (" + ", ".join(over) + " > 1)"
    lim = _limit_flag(s, b)
    if lim and lim["flag"]:
        flags.append(lim["flag"])
        if carries and lim["value"] < 1.0:  # the two answers disagree: said in the sentence, not hidden
            line += f"; but the incremental run peaked at lambda = {lim['value']:.3g} < 1 (see the warning)"
    margin = None
    if "not_computed" not in b and not push:
        margin = [b["lb_davis"], b["ub_davis"]]
    if fos is None and fos_gap is not None:  # skipped (not printed) where the line above says why already
        if "not_computed" in b:
            fos = {"skipped": "no capacity bracket"}
        elif push:
            fos = {"skipped": "a push-over has no loads to carry at factor 1"}
        else:
            fos = fos_bracket(scene, fos_gap, max_elements)
    fos_margin = None if not fos or "lb" not in fos else [fos["lb"], fos["ub"]]
    if carries and fos_margin is not None:  # the margin in both senses, in the one sentence
        hi = "inf" if fos["ub"] is None else f"{fos['ub']:#.3g}"
        head, sep, tail = line.partition(" bracket)")
        line = f"{head}{sep} and factor of safety on strength F in [{fos['lb'] or 0:#.3g}, {hi}]{tail}"
    return {
        "line": line,
        "carries": carries,
        "margin": margin,
        "fos": fos,
        "fos_margin": fos_margin,
        "capacity": b,
        "foundations": fnds,
        "differential_settlement": diff,
        "incremental_limit": lim,
        "w_k_limit_mm": w_k_limit_mm,
        "flags": flags,
        "at_limit": at_limit,
        "rc_ok": rc_ok,
    }


def verdict_lines(v: dict | None) -> list[str]:
    """The printed verdict (first in ``ssi run``'s summary)."""
    if not v:
        return []
    if v.get("skipped"):
        return [f"VERDICT          not asked ({v['skipped']})"]
    lines = [f"VERDICT          {v['line']}"]
    b = v["capacity"]
    if "not_computed" not in b:
        k, unit = (1e-3, " kN/m") if b["unit"] == "N/m" else (1.0, "")

        def fmt(x):
            return "inf" if x is None else f"{k * x:.4g}"

        lines.append(
            f"  capacity of {b['reference']}: associated ceiling [{fmt(b['lb'])}, {fmt(b['ub'])}]{unit} gap "
            f"{100 * (b['gap'] or 0):.1f} %; Davis estimate [{fmt(b['lb_davis'])}, "
            f"{fmt(b['ub_davis'])}]{unit} gap {100 * (b['gap_davis'] or 0):.1f} % ({b['n_triangles']} "
            f"triangles, {b['time_s']:.1f} s)"
        )
        if b.get("never_yield"):
            lines.append(
                f"  taken as never yielding (elastic, as in the run): {', '.join(b['never_yield'])}; give c "
                "and phi_deg where the soil may fail"
            )
    fos = v.get("fos")
    if not fos or "skipped" in fos:
        pass
    elif "not_computed" in fos:
        lines.append(f"  factor of safety on strength: not computed ({fos['not_computed']})")
    elif fos:
        state = (
            ""
            if fos["converged"]
            else f", gap target {100 * fos['gap_target']:g} % NOT reached: {fos['reason']}"
        )
        hi = "inf" if fos["ub"] is None else f"{fos['ub']:.4g}"
        # the Davis materials reduced, which are the associated ones when the scene is associated
        kind = "Davis" if fos["davis"] and b.get("davis") else "associated"
        lines.append(
            f"  factor of safety on strength (c/F, tan(phi)/F, {kind}): "
            f"F in [{fos['lb'] or 0:.4g}, {hi}] gap {100 * (fos['gap'] or 0):.1f} %{state} "
            f"({fos['n_triangles']} triangles, {fos['time_s']:.1f} s)"
        )
    for f in v["foundations"]:
        parts = []
        if f.get("settlement_m") is not None:
            parts.append(f"settlement {1e3 * f['settlement_m']:.2f} mm")
            if v.get("at_limit"):
                parts[-1] += " at the limit load (a mechanism's, not a service settlement)"
        if f.get("tilt_rad") is not None:
            parts.append(f"tilt {1e3 * f['tilt_rad']:.2f} mm/m")
        for key, val in (f.get("utilisation") or {}).items():
            if val is not None and math.isfinite(val):
                parts.append(f"{key} {val:.2f}" + (" > 1 !" if val > 1.0 else ""))
        lines.append(f"  {f['where']}: " + ", ".join(parts))
    for d in v["differential_settlement"]:
        lines.append(f"  differential settlement #{d['i']} - #{d['j']}: {1e3 * d['m']:.2f} mm")
    for fl in v["flags"]:
        lines.append(f"  WARNING: {fl}")
    return lines


def stop_sentence(report: dict | None, kind: str = "scene") -> str:
    """A solver stop (:class:`ssi.solver.NonConvergence`'s ``report``) as one sentence an engineer reads:
    where (the load factor, the worst point), which material (the ill-posed soil, or the groups active
    there) and what to do. The full report stays in the result file and the JSON summary."""
    if not report:
        return ""
    lam = report.get("load_factor_from")
    where = f"at load factor {lam:.4g}" if isinstance(lam, (int, float)) else "during the run"
    if report.get("phase"):
        where += f" of phase {report['phase']!r}"
    xy = report.get("node_xy")
    if xy:
        where += f", worst near x = {xy[0]:.2f} m, z = {xy[1]:.2f} m"
    reason = str(report.get("reason", "unknown"))
    if report.get("ill_posed"):
        which = str(report["ill_posed"]).split(":")[0]  # "<n> plastic points of <group> material <i> (phi.."
        what = (
            f"{which}): non-associated soil yielding there has lost ellipticity, so the path need not "
            "continue on this mesh"
        )
        todo = (
            'read the capacity from the verdict\'s bracket, or solve in Davis mode ([solve] flow = "davis"); '
            "the path up to the stop is valid"
        )
    elif report.get("soft_mode"):
        what = f"{reason}; the structure softens ({report['soft_mode']})"
        todo = "the loads are near the capacity: compare them with the verdict's bracket"
    else:
        groups = report.get("worst_groups")
        what = reason + (f" (active there: {str(groups)[:160]})" if groups else "")
        todo = (
            "try more load steps ([solve] n_steps), a finer mesh near that point, or check the loads "
            "against the verdict's capacity bracket"
        )
    return f"The {kind}'s solver stopped {where}: {what}. What to do: {todo}. Details in the result file."
