"""RC design view of a solved scene: crack widths, utilisations, envelopes over phases, a design summary.

The checks themselves (EN 1992-1-1 §7.3.4 crack width, M_Rd(N), V_Rd,c, the brittle flag) live in
``ssi.elements.rc_design``; this module feeds them the coupled analysis's action effects at every sampling
point of the strip and every row (load step) of a solved strip (``out``: a
:class:`~ssi.scene.foundation_result.FoundationResult`, a site's strip or a scene's, or a
:class:`~ssi.scene.view.SceneResult`, whose accessors are its strip's):

* :func:`crack_width` -- w_k at the axial points of row ``k`` (0 where the tension face has not cracked in the
  analysis), with the bar stress at the crack;
* :func:`utilisation` -- |M_Ed| / M_Rd(N_Ed) at the axial points and |V_Ed| / V_Rd,c at the shear points;
* :func:`envelopes` -- max / min over the rows of each phase of M, N, V, w_k, steel stress, contact pressure;
* :func:`design_summary` -- the maxima an engineer reports, per phase and overall.

Units: SI (m, N/m, N m/m, Pa); crack widths [m]. Sign conventions are the strip's
(``SceneResult.strip_forces``).
"""

import math

import numpy as np

from ..elements.rc_design import RCDesign
from ..materials.layer_laws import CONCRETE, STEEL

__all__ = ["crack_width", "design_of", "design_summary", "envelopes", "utilisation"]


def design_of(out, **options) -> RCDesign | None:
    """The :class:`RCDesign` of the scene's foundation section (the user's section, before the crack band's
    regularisation), with the Foundation's ``bar_diameter``; None if the strip has no concrete layer (an
    elastic or rigid foundation). ``options`` go to :class:`RCDesign` (gamma_c, gamma_s, kt, fck...)."""
    found = out.foundation
    sec = getattr(found, "section", None)
    if sec is None or not np.any(sec.kind == CONCRETE):
        return None
    options.setdefault("bar_diameter", found.bar_diameter)
    return RCDesign(sec, **options)


def _tension_face_cracked(out, k, M):
    """(n_el, n_ax) bool: the concrete layer nearest the face that M puts in tension has cracked at row k."""
    layers = out.plate_layers(k)
    sec = out.plate.section
    conc = np.flatnonzero(sec.kind == CONCRETE)
    low, high = conc[np.argmin(sec.z_mid[conc])], conc[np.argmax(sec.z_mid[conc])]
    cracked = layers["cracked"]
    return np.where(M >= 0.0, cracked[..., low], cracked[..., high])


def crack_width(out, k: int = -1, design: RCDesign | None = None) -> dict:
    """Crack width at the strip's axial points at row ``k``: dict of ``x`` (n_el, n_ax) [m], ``w_k`` (n_el,
    n_ax) [m] (EN 1992-1-1 §7.3.4 from the point's N and M; 0 where the analysis has not cracked the tension
    face or the face has no bars), ``sig_s`` (n_el, n_ax) [Pa] bar stress at the crack (nan where uncracked),
    ``face`` (n_el, n_ax) "bottom"/"top"."""
    design = design or design_of(out)
    f = out.strip_forces(k)
    N, M = f["N"], f["M"]
    cracked = _tension_face_cracked(out, k, M)
    w = np.zeros(M.shape)
    sig = np.full(M.shape, np.nan)
    face = np.where(M >= 0.0, "bottom", "top")
    if design is not None:
        for i in zip(*np.nonzero(cracked), strict=True):
            c = design.crack_width(float(N[i]), float(M[i]))
            w[i], sig[i] = c["w_k"], c["sig_s"]
    return {"x": f["x_ax"], "w_k": w, "sig_s": sig, "face": face}


def _mrd_table(design: RCDesign, N_values: np.ndarray) -> dict:
    """M_Rd(N) sagging and hogging on a grid of N spanning ``N_values`` (9 values; linear between them)."""
    lo, hi = float(np.min(N_values)), float(np.max(N_values))
    grid = np.linspace(lo, hi, 9) if hi > lo else np.array([lo])
    return {
        "N": grid,
        "sag": np.array([design.M_Rd(n, 1) for n in grid]),
        "hog": np.array([design.M_Rd(n, -1) for n in grid]),
    }


def _mrd_at(table: dict, N: np.ndarray, M: np.ndarray) -> np.ndarray:
    if table["N"].size == 1:
        sag, hog = np.full(N.shape, table["sag"][0]), np.full(N.shape, table["hog"][0])
    else:
        sag, hog = np.interp(N, table["N"], table["sag"]), np.interp(N, table["N"], table["hog"])
    return np.where(M >= 0.0, sag, -hog)


def utilisation(out, k: int = -1, design: RCDesign | None = None, table: dict | None = None) -> dict:
    """Utilisations at row ``k``: ``x_ax``, ``M`` (|M_Ed| / M_Rd(N_Ed), n_el x n_ax), ``M_Rd`` [N m/m] (its
    magnitude at each point), ``x_sh``, ``V`` (|V_Ed| / V_Rd,c, n_el x n_sh), ``V_Rd_c`` [N/m]; the tension
    face of a shear point is the one its interpolated moment puts in tension."""
    design = design or design_of(out)
    f = out.strip_forces(k)
    table = table or _mrd_table(design, np.append(f["N"].ravel(), 0.0))
    m_rd = _mrd_at(table, f["N"], f["M"])
    x_ax, x_sh = f["x_ax"].ravel(), f["x_sh"].ravel()
    order = np.argsort(x_ax)
    M_sh = np.interp(x_sh, x_ax[order], f["M"].ravel()[order])
    N_sh = np.interp(x_sh, x_ax[order], f["N"].ravel()[order])
    v_rd = np.array([design.V_Rd_c(m, n) for m, n in zip(M_sh, N_sh, strict=True)]).reshape(f["Q"].shape)
    return {
        "x_ax": f["x_ax"],
        "M": np.abs(f["M"]) / m_rd,
        "M_Rd": m_rd,
        "x_sh": f["x_sh"],
        "V": np.abs(f["Q"]) / v_rd,
        "V_Rd_c": v_rd,
    }


def _phase_rows(out) -> list[tuple[str, range]]:
    if out.phases:
        return [(ph["name"], range(ph["first"], ph["last"] + 1)) for ph in out.phases]
    return [("loading", range(len(out.load_factor)))]


def envelopes(out, design: RCDesign | None = None) -> dict:
    """Per phase (name -> dict), the max and min over its rows of ``M`` [N m/m], ``N`` [N/m], ``V`` [N/m],
    ``w_k`` [m], ``sig_s`` (steel layer stress of the analysis, [Pa]) and ``p`` (contact pressure,
    compression positive, [Pa]), each as (max, min) at every point: arrays of the point layout of
    ``strip_forces`` / ``contact``."""
    design = design or design_of(out)
    res = {}
    for name, rows in _phase_rows(out):
        acc: dict = {}
        for k in rows:
            f = out.strip_forces(k)
            st = out.steel_stress(k)["sig"]
            fields = {
                "M": f["M"],
                "N": f["N"],
                "V": f["Q"],
                "w_k": crack_width(out, k, design)["w_k"],
                "sig_s": st.max(axis=-1) if st.shape[-1] else np.zeros(f["M"].shape),
                "p": -out.contact(k)["sig_n"],
            }
            for key, v in fields.items():
                if key in acc:
                    acc[key] = (np.maximum(acc[key][0], v), np.minimum(acc[key][1], v))
                else:
                    acc[key] = (np.array(v, float), np.array(v, float))
        res[name] = acc
    return res


def design_summary(out, **options) -> dict | None:
    """What a designer reports of an RC strip, per phase and overall (None without a concrete strip):
    ``w_k_max`` [mm] and where, ``sig_s_max`` [MPa] (bars at the crack, EN 1992 7.3.4), ``M_max`` /
    ``M_min`` [kN m/m], ``V_max`` [kN/m], ``N`` range [kN/m], ``p_max`` contact pressure [kPa],
    ``util_M_max`` and ``util_V_max`` (|M_Ed| / M_Rd(N), |V_Ed| / V_Rd,c) with their x [m]; the section's
    ``M_Rd`` (N = 0, sagging / hogging) [kN m/m], the ``brittle`` flag per face and the design options.
    ``options`` go to :class:`~ssi.elements.rc_design.RCDesign` (characteristic by default)."""
    design = design_of(out, **options)
    if design is None:
        return None
    all_N = np.concatenate([out.strip_forces(k)["N"].ravel() for k in range(len(out.load_factor))] + [[0.0]])
    table = _mrd_table(design, all_N)
    phases = {}
    for name, rows in _phase_rows(out):
        best = {"w_k_max": (0.0, math.nan), "util_M_max": (0.0, math.nan), "util_V_max": (0.0, math.nan),
                "sig_s_max": 0.0, "M_max": -math.inf, "M_min": math.inf, "V_max": 0.0, "N_min": math.inf,
                "N_max": -math.inf, "p_max": 0.0}  # fmt: skip
        for k in rows:
            cw = crack_width(out, k, design)
            u = utilisation(out, k, design, table)
            f = out.strip_forces(k)
            i = np.unravel_index(np.argmax(cw["w_k"]), cw["w_k"].shape)
            if cw["w_k"][i] > best["w_k_max"][0]:
                best["w_k_max"] = (float(cw["w_k"][i]), float(cw["x"][i]))
            for key, arr, x in (("util_M_max", u["M"], u["x_ax"]), ("util_V_max", u["V"], u["x_sh"])):
                j = np.unravel_index(np.argmax(arr), arr.shape)
                if arr[j] > best[key][0]:
                    best[key] = (float(arr[j]), float(x[j]))
            if np.any(np.isfinite(cw["sig_s"])):
                best["sig_s_max"] = max(best["sig_s_max"], float(np.nanmax(cw["sig_s"])))
            best["M_max"] = max(best["M_max"], float(f["M"].max()))
            best["M_min"] = min(best["M_min"], float(f["M"].min()))
            best["V_max"] = max(best["V_max"], float(np.abs(f["Q"]).max()))
            best["N_min"] = min(best["N_min"], float(f["N"].min()))
            best["N_max"] = max(best["N_max"], float(f["N"].max()))
            best["p_max"] = max(best["p_max"], float((-out.contact(k)["sig_n"]).max()))
        phases[name] = {
            "w_k_max_mm": 1e3 * best["w_k_max"][0],
            "w_k_x_m": best["w_k_max"][1],
            "sig_s_crack_max_MPa": best["sig_s_max"] / 1e6,
            "M_max_kNm": best["M_max"] / 1e3,
            "M_min_kNm": best["M_min"] / 1e3,
            "V_max_kN": best["V_max"] / 1e3,
            "N_min_kN": best["N_min"] / 1e3,
            "N_max_kN": best["N_max"] / 1e3,
            "p_max_kPa": best["p_max"] / 1e3,
            "util_M_max": best["util_M_max"][0],
            "util_M_x_m": best["util_M_max"][1],
            "util_V_max": best["util_V_max"][0],
            "util_V_x_m": best["util_V_max"][1],
        }
    brittle = design.brittle()
    plain = not np.any(design.section.kind == STEEL)
    return {
        "phases": phases,
        "w_k_max_mm": max(p["w_k_max_mm"] for p in phases.values()),
        "util_M_max": max(p["util_M_max"] for p in phases.values()),
        "util_V_max": max(p["util_V_max"] for p in phases.values()),
        "M_Rd_sag_kNm": design.M_Rd(0.0, 1) / 1e3,
        "M_Rd_hog_kNm": design.M_Rd(0.0, -1) / 1e3,
        "brittle": {face: b["brittle"] for face, b in brittle.items()},
        "plain_concrete": plain,
        "options": {
            "fck_MPa": design.fck / 1e6,
            "fyk_MPa": design.fyk / 1e6,
            "gamma_c": design.gamma_c,
            "gamma_s": design.gamma_s,
            "kt": design.kt,
        },  # fmt: skip
    }


def summary_text(s: dict | None) -> str:
    """The design summary as lines for ``ssi run`` (mm, MPa, kN)."""
    if s is None:
        return ""
    lines = ["RC design (EN 1992-1-1, characteristic unless gamma_c/gamma_s given):"]
    for name, p in s["phases"].items():
        lines.append(
            f"  {name}: w_k max {p['w_k_max_mm']:.3f} mm at x = {p['w_k_x_m']:.2f} m, sig_s at crack max "
            f"{p['sig_s_crack_max_MPa']:.0f} MPa, M_Ed/M_Rd {p['util_M_max']:.2f}, V_Ed/V_Rd,c "
            f"{p['util_V_max']:.2f}, M {p['M_min_kNm']:.1f} .. {p['M_max_kNm']:.1f} kNm/m"
        )
        if p["sig_s_crack_max_MPa"] > s["options"]["fyk_MPa"]:
            lines.append(
                "    the cracked elastic section puts the bars beyond f_yk at a crack: the section has "
                "yielded "
                "and the crack width of 7.3.4 (a service check) does not apply there"
            )
    lines.append(
        f"  M_Rd (N = 0): sagging {s['M_Rd_sag_kNm']:.1f}, hogging {s['M_Rd_hog_kNm']:.1f} kNm/m; brittle "
        f"faces: {', '.join(f for f, b in s['brittle'].items() if b) or 'none'}"
        + ("; plain concrete: cracking is brittle" if s["plain_concrete"] else "")
    )
    return "\n".join(lines)
