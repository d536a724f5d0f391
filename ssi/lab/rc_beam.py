"""The reinforced-concrete beam of chapter 08 (paper §9.2, Figs. 11-12): section, model and load path.

Monnier's beam (the paper's test) is not available (reference-data.md, trust D), so the model actually run
is the substitute experiment of Janney, Hognestad & McHenry (1956), trust C: a simply supported beam in
four-point bending, b x h = 152.4 x 304.8 mm, span 2.7432 m, loads at the third points, 3 No. 5 bars
(As = 600 mm^2) at d = 210.8 mm, fc = 36.2 MPa, fy = 333 MPa (non-hardening).

The plate strip works per unit width; the beam's width b enters explicitly: the bar layer has the
equivalent thickness As/b (m^2 per m of width), and forces/moments per beam are b times the strip's
per-width values (exact for a prismatic beam).

Half model by symmetry: x = 0 (support: w = 0) to x = L/2 (symmetry: u = alpha = 0); the load point x = a
is driven by a prescribed deflection (displacement control, ``Model.prescribe``) whose reaction is the
load P per unit width; mid-span moment M = P a (per width).
"""

import time
from dataclasses import dataclass, field

import numpy as np

from ..core.model import Model
from ..elements.plate import add_plate_strip
from ..elements.section import rc_section, with_crack_spacing_band
from ..materials import rc
from ..materials.layer_laws import CONCRETE, ELASTIC, STEEL
from ..solver import NonConvergence, Settings, run

__all__ = [
    "JANNEY",
    "FourPointBeam",
    "build_four_point",
    "janney_band_section",
    "janney_crack_spacing",
    "janney_materials",
    "janney_section",
    "load_path",
]

JANNEY = {
    "b": 0.1524,
    "h": 0.3048,
    "span": 2.7432,
    "a": 0.9144,
    "As": 600.0e-6,
    "d": 0.2108,
    "fc": 36.2e6,
    "fy": 333.0e6,
}
ES_DESIGN = 200.0e9  # designer value of the bar modulus (not reported in the substitute's summary)


def janney_materials(ls=0.05, alpha_ts=0.5, beta0=0.25, Es=ES_DESIGN, EH=0.0):
    """(concrete params, steel params, designer dict) from fc and fy only (see ``ssi.materials.rc``)."""
    g = JANNEY
    des = rc.designer_concrete(g["fc"])
    eps_y = g["fy"] / Es
    pc = rc.concrete_params(
        g["fc"],
        des["E0"],
        des["eps_c"],
        des["fr"],
        des["Gf"],
        ls,
        eps_y,
        eps_cu=des["eps_cu"],
        alpha_ts=alpha_ts,
        beta0=beta0,
    )
    ps = rc.steel_params(g["fy"], Es, EH)
    return pc, ps, des


def janney_section(n_layers=11, ls=0.05, alpha_ts=0.5, elastic=False, **kw):
    """Layered section per unit width: one bar layer (As/b thick at d) and n_layers - 1 concrete layers
    spread over the two gaps in proportion to their depth. ``elastic``: ELASTIC layers with the concrete's
    E0 and nu = 0 (uniaxial) and the bars' Es -- the linear model of Fig. 12."""
    g = JANNEY
    pc, ps, _ = janney_materials(ls=ls, alpha_ts=alpha_ts, **kw)
    if elastic:
        conc = (ELASTIC, rc.elastic_params(pc[0], 0.0))
        steel = (ELASTIC, rc.elastic_params(ps[0], 0.0))
    else:
        conc = (CONCRETE, pc)
        steel = (STEEL, ps)
    return rc_section(g["h"], [(g["h"] - g["d"], g["As"] / g["b"])], conc, steel, n_concrete=n_layers - 1)


@dataclass
class FourPointBeam:
    """A half beam in four-point bending: the model, its strip group and the node ids that matter."""

    model: Model
    group: object
    support: int
    load: int
    mid: int
    span: float
    a: float
    x_ends: np.ndarray
    info: dict = field(default_factory=dict)


def build_four_point(
    section,
    span,
    a,
    n_shear,
    n_middle,
    crack_band="point",
    integration="selective",
    kappa=5.0 / 6.0,
    **strip_options,
):
    """Half beam: ``n_shear`` equal elements on [0, a], ``n_middle`` on [a, L/2]. Extra keywords go to
    :class:`ssi.elements.plate.PlateStrip` (e.g. ``self_bending``)."""
    if not 0.0 < a < 0.5 * span:
        raise ValueError(f"a must be in (0, span/2 = {0.5 * span}), got {a}")
    if int(n_shear) < 1 or int(n_middle) < 1:
        raise ValueError(f"n_shear and n_middle must be >= 1, got {n_shear}, {n_middle}")
    x_ends = np.concatenate(
        [np.linspace(0.0, a, int(n_shear) + 1), np.linspace(a, 0.5 * span, int(n_middle) + 1)[1:]]
    )
    model = Model()
    group, ids, _ = add_plate_strip(
        model,
        x_ends,
        section,
        crack_band=crack_band,
        integration=integration,
        kappa=kappa,
        name="beam",
        **strip_options,
    )
    support, load, mid = int(ids[0]), int(ids[2 * int(n_shear)]), int(ids[-1])
    model.fix([support], "w")
    model.fix([mid], "u")
    model.fix([mid], "alpha")
    return FourPointBeam(
        model,
        group,
        support,
        load,
        mid,
        float(span),
        float(a),
        x_ends,
        {"n_shear": int(n_shear), "n_middle": int(n_middle)},
    )


def load_path(
    beam: FourPointBeam, w_load_max, n_steps, settings: Settings | None = None, allow_partial=False
):
    """Drive the load point down to ``w_load_max`` (> 0, a deflection) in ``n_steps`` equal steps.

    Returns a dict of arrays (n_steps + 1,): ``P`` (load per unit width at the load point, positive
    down), ``M`` (mid-span moment per unit width), ``delta`` (mid-span deflection, positive down),
    ``delta_load``; plus ``wall_time``, ``iterations``, ``result`` and ``failure`` (None, or the solver's
    report when ``allow_partial`` kept the converged steps of a run that stopped early)."""
    m = beam.model
    m.prescribe([beam.load], "w", -float(w_load_max))
    t0 = time.perf_counter()
    failure = None
    try:
        res = run(m, np.linspace(0.0, 1.0, int(n_steps) + 1)[1:], settings or Settings())
    except NonConvergence as err:
        if not allow_partial:
            raise
        res, failure = err.result, err.report
    wall = time.perf_counter() - t0
    P = -res.reaction([beam.load], "w")
    return {
        "P": P,
        "M": P * beam.a,
        "delta": -res.displacement([beam.mid], "w")[:, 0],
        "delta_load": -res.displacement([beam.load], "w")[:, 0],
        "wall_time": wall,
        "iterations": np.array(res.iterations),
        "result": res,
        "failure": failure,
    }


def linear_compliance(beam: FourPointBeam):
    """Mid-span deflection per unit load per unit width of the K0 (initial elastic) model."""
    m = beam.model
    m.add_load([beam.load], "w", -1.0)
    lin = m.solve_linear()
    return -float(lin.displacement([beam.mid], "w")[-1, 0])


JANNEY_BAR_DIAMETER = 0.0159  # No. 5 bar [m]


def janney_band_section(n_layers=11, tension_stiffening="all", **kw):
    """The Janney section with the scene's crack band (MC2010 s_r,max, ``with_crack_spacing_band``) and the
    chosen tension-stiffening rule ("all" concrete layers or the "effective_area" around the bars)."""
    return with_crack_spacing_band(janney_section(n_layers, **kw), JANNEY_BAR_DIAMETER, tension_stiffening)[0]


def janney_crack_spacing():
    """Crack band width of the substitute beam: s_r,max of *fib* Model Code 2010 for its bars (the scene
    default, ``ssi.elements.section.with_crack_spacing_band``; the No. 5 bars' diameter)."""
    return float(with_crack_spacing_band(janney_section(11), JANNEY_BAR_DIAMETER)[1][0]["s_r_max"])
