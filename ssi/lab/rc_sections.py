"""Ordinary RC strip sections as a designer writes them, and a quick structural solve of each (issue 33).

:func:`design_section` builds a section from design quantities (depth, EC2 concrete class, bar
diameter, reinforcement ratio per face, clear cover); :func:`section_grid` lists the grid of chapter 18
(depth 0.3-1.5 m, rho from the EC2 minimum to 2 % per face with one light face, bars 10-32 mm,
C20/25-C50/60, covers 30-75 mm); :func:`crack_section` builds a strip of that section with the
``Foundation`` defaults (crack band from the crack spacing, plane strain, tension stiffening everywhere,
chord self-bending) and drives it as a simply supported beam in four-point bending (span 10 h, loads at the
third points) to several times its cracking deflection.

Units: SI (m, Pa, N/m, N m/m); reinforcement ratios are As / (b d) per face.
"""

import itertools
import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..core.validate import check_real
from ..elements.section import Section, rc_section
from ..materials.concrete import H_EMAX, P_E0, P_FR
from ..materials.layer_laws import CONCRETE, STEEL
from ..materials.rc import concrete_params, designer_concrete, steel_params

__all__ = ["GridSection", "crack_section", "design_section", "issue_section", "rho_min_ec2", "section_grid"]

FCK_CLASSES = {"C20/25": 20e6, "C30/37": 30e6, "C40/50": 40e6, "C50/60": 50e6}
MPA = 1.0e6


def rho_min_ec2(fck: float, fyk: float = 500e6) -> float:
    """EN 1992-1-1 eq. (9.1N): As,min / (b d) = max(0.26 fctm / fyk, 0.0013), fctm = 0.30 fck^(2/3) [MPa]."""
    fctm = 0.30 * (fck / MPA) ** (2.0 / 3.0)
    return max(0.26 * fctm / (fyk / MPA), 0.0013)


def issue_section(bars=None) -> Section:
    """The footing of issue 33: 0.6 m deep, C30/37 (fcm 38 MPa), B500, phi16@150 bottom, phi12@200 top, covers
    50 mm (to the bar surface)."""
    d = designer_concrete(38e6)
    conc = (CONCRETE, concrete_params(38e6, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, 500e6 / 200e9))
    if bars is None:
        bars = [(0.058, math.pi * 0.016**2 / 4 / 0.15), (0.6 - 0.056, math.pi * 0.012**2 / 4 / 0.2)]
    return rc_section(0.6, bars, conc, (STEEL, steel_params(500e6)))


@dataclass(frozen=True)
class GridSection:
    """One section of the grid: ``depth`` [m], ``fck`` [Pa], ``phi`` bar diameter [m], ``cover`` clear cover
    [m], ``rho_bottom`` / ``rho_top`` As / (b d) per face (0: no bars on that face)."""

    depth: float
    fck: float
    phi: float
    cover: float
    rho_bottom: float
    rho_top: float

    def label(self) -> str:
        return (
            f"h={self.depth:g} C{self.fck / MPA:g} phi{1e3 * self.phi:g} c{1e3 * self.cover:g} "
            f"rho={100 * self.rho_bottom:.3g}/{100 * self.rho_top:.3g}%"
        )


def design_section(
    depth: float,
    fck: float,
    phi: float,
    cover: float,
    rho_bottom: float,
    rho_top: float,
    fyk: float = 500e6,
    Es: float = 200e9,
    n_concrete: int = 9,
) -> Section:
    """The layered section of a strip from design quantities: concrete of characteristic strength ``fck``
    [Pa] with the MC2010 designer values at fcm = fck + 8 MPa (``designer_concrete``), B500 bars of diameter
    ``phi`` [m] at clear ``cover`` [m] from each face, As = rho d per unit width on each face whose ratio is
    > 0, d = depth - cover - phi/2."""
    depth = check_real("depth", depth, lo=0.0, lo_open=True, unit="m")
    check_real("fck", fck, lo=12e6, hi=50e6, unit="Pa (EC2 classes C12/15-C50/60)")
    check_real("phi", phi, lo=0.0, lo_open=True, unit="m")
    check_real("cover", cover, lo=0.0, lo_open=True, unit="m")
    fcm = fck + 8.0 * MPA
    des = designer_concrete(fcm)
    conc = concrete_params(
        fcm, des["E0"], des["eps_c"], des["fr"], des["Gf"], 0.1, fyk / Es, eps_cu=des["eps_cu"]
    )
    z = cover + 0.5 * phi
    d = depth - z
    bars = [(zb, rho * d) for zb, rho in ((z, rho_bottom), (depth - z, rho_top)) if rho > 0.0]
    return rc_section(depth, bars, (CONCRETE, conc), (STEEL, steel_params(fyk, Es)), n_concrete=n_concrete)


def section_grid(full: bool = True) -> list[GridSection]:
    """The grid of ordinary sections. Every combination of depth (0.3, 0.6, 1.0, 1.5 m), concrete class
    (C20/25, C30/37, C50/60) and bottom ratio (the EC2 minimum, 0.5 %, 1 %, 2 %) with the top face at the EC2
    minimum (the light face), plus the same with the two faces swapped at 2 % (a hogging design); bar
    diameters (10, 12, 16, 20, 25, 32 mm) and covers (30, 40, 50, 75 mm) are cycled through the list so each
    appears with every depth. ``full=False``: four representative sections (shallow and light, the issue's
    footing, deep and heavy, one more hogging)."""
    depths = (0.3, 0.6, 1.0, 1.5)
    classes = (20e6, 30e6, 50e6)
    phis = (0.010, 0.012, 0.016, 0.020, 0.025, 0.032)
    covers = (0.030, 0.040, 0.050, 0.075)
    out = []
    for i, (h, fck, rho) in enumerate(itertools.product(depths, classes, ("min", 0.005, 0.01, 0.02))):
        r_min = rho_min_ec2(fck)
        rb = r_min if rho == "min" else rho
        out.append(GridSection(h, fck, phis[i % len(phis)], covers[(i // 3) % len(covers)], rb, r_min))
    for i, (h, fck) in enumerate(itertools.product(depths, classes)):
        out.append(
            GridSection(h, fck, phis[(i + 2) % len(phis)], covers[i % len(covers)], rho_min_ec2(fck), 0.02)
        )
    if full:
        return out
    return [
        GridSection(0.3, 20e6, 0.010, 0.030, rho_min_ec2(20e6), rho_min_ec2(20e6)),
        GridSection(0.6, 30e6, 0.016, 0.050, 0.0023, 0.00095),
        GridSection(1.5, 50e6, 0.032, 0.075, 0.02, rho_min_ec2(50e6)),
        GridSection(1.0, 30e6, 0.025, 0.040, rho_min_ec2(30e6), 0.02),
    ]


def crack_section(section: Section, bar_diameter: float, n_steps: int = 12, overdrive: float = 4.0) -> dict:
    """Build a strip of ``section`` with the ``Foundation`` defaults and drive it as a simply supported beam
    (span 10 h, loads at the third points, half model, 8 elements) in displacement control to ``overdrive``
    times the load-point deflection at which the linear model reaches the cracking moment of the sagging
    face (M_cr = fr I / y of the uncracked section, with the section's own fr). Hogging-reinforced sections
    are turned upside down first, so the heavier face is in tension.

    Returns a dict: ``completed`` (all steps converged), ``cracked`` (a concrete layer at the tension face
    passed its cracking strain), ``M_cr`` [N m/m], ``M_end`` the mid-span moment at the end [N m/m],
    ``sig_s_max`` the largest steel stress [Pa] (0 without bars), ``warnings`` (the messages of the build)."""
    from ..elements.plate import add_plate_strip  # noqa: F401  (build_four_point adds the strip)
    from ..scene import Foundation
    from ..solver import NonConvergence
    from .rc_beam import build_four_point, linear_compliance, load_path

    h = section.thickness
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        found = Foundation(x0=0.0, x1=1.0, section=section, bar_diameter=bar_diameter)
        strip = found.strip_section()
    opts = found.strip_options()
    span = 10.0 * h
    a = span / 3.0

    def beam():
        return build_four_point(
            strip,
            span,
            a,
            3,
            2,
            crack_band=opts["crack_band"],
            integration=opts["integration"],
            kappa=opts["kappa"],
            self_bending=opts["self_bending"],
        )

    stiff = strip.elastic_resultant_stiffness()
    conc = np.flatnonzero(strip.kind == CONCRETE)
    bottom = conc[np.argmin(strip.z_mid[conc])]
    E_ax = strip.initial_moduli()[0][bottom]
    fr = strip.params[bottom, P_FR]
    M_cr = fr / E_ax * stiff["D_na"] / (stiff["z_na"] - strip.z_bottom)
    # linear load-point deflection at P = M_cr / a (per width): compliance at mid-span scaled to the load
    # point by the elastic ratio of the two deflections of a third-point loaded beam, 20/23 (Euler-Bernoulli)
    delta_cr = (M_cr / a) * linear_compliance(beam()) * 20.0 / 23.0
    b = beam()
    completed = True
    try:
        path = load_path(b, overdrive * delta_cr, n_steps)
    except NonConvergence:
        completed = False
        path = load_path(b := beam(), overdrive * delta_cr, n_steps, allow_partial=True)
    res = path["result"]
    state = res.states[-1][b.model.groups.index(b.group)]
    eps_r = strip.params[bottom, P_FR] / strip.params[bottom, P_E0]
    cracked = bool(np.any(state[..., bottom, H_EMAX] > eps_r))
    steel = strip.kind == STEEL
    sig, _ = b.group.layer_stresses(res.u[-1][b.group.edofs], state)
    return {
        "completed": completed and path["failure"] is None,
        "cracked": cracked,
        "M_cr": float(M_cr),
        "M_end": float(path["M"][-1]),
        "sig_s_max": float(sig[..., steel].max()) if steel.any() else 0.0,
        "warnings": [str(w.message) for w in caught],
    }


def upside_down(g: GridSection) -> GridSection:
    """The section turned over: its heavier face at the bottom (the sagging beam test puts that face in
    tension)."""
    if g.rho_top > g.rho_bottom:
        return GridSection(g.depth, g.fck, g.phi, g.cover, g.rho_top, g.rho_bottom)
    return g


def grid_case(g: GridSection, n_steps: int = 12) -> dict:
    """Build :func:`design_section` of ``g`` (turned so that its heavier face is in tension) and
    :func:`crack_section` it."""
    g = upside_down(g)
    sec = design_section(g.depth, g.fck, g.phi, g.cover, g.rho_bottom, g.rho_top)
    out = crack_section(sec, g.phi, n_steps=n_steps)
    out["label"] = g.label()
    out["ok"] = out["completed"] and out["cracked"] and math.isfinite(out["M_end"]) and out["M_end"] > 0.0
    return out
