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

import itertools
import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..core.model import Model
from ..elements.plate import add_plate_strip
from ..elements.section import Section, rc_section, with_crack_spacing_band
from ..materials import rc
from ..materials.concrete import P_E0, P_FR
from ..materials.layer_laws import CONCRETE, ELASTIC, STEEL
from ..materials.steel import S_ES
from ..solver import NonConvergence, Settings, run

__all__ = [
    "JANNEY",
    "FourPointBeam",
    "build_four_point",
    "four_point_deflection_after_self_weight",
    "janney_band_section",
    "janney_crack_spacing",
    "janney_materials",
    "janney_section",
    "load_path",
    "shrinkage_restraint_stress",
    "shrinkage_strain_en1992",
    "with_shrinkage_restraint",
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
    beam: FourPointBeam,
    w_load_max,
    n_steps,
    settings: Settings | None = None,
    allow_partial=False,
    self_weight: float = 0.0,
):
    """Drive the load point down to ``w_load_max`` (> 0, a deflection) in ``n_steps`` equal steps.

    ``self_weight`` [N/m per unit width, >= 0]: a distributed weight carried first (one load step, consistent
    nodal forces 1/6, 2/3, 1/6 of q L_e per element) and held while the load point is driven from where the
    weight left it; ``P``, ``M`` and the deflections are then those of the test, measured from that state (the
    gauges zeroed under the beam's own weight).

    Returns a dict of arrays (n_steps + 1,): ``P`` (load per unit width at the load point, positive
    down), ``M`` (mid-span moment per unit width), ``delta`` (mid-span deflection, positive down),
    ``delta_load``; plus ``wall_time``, ``iterations``, ``result`` and ``failure`` (None, or the solver's
    report when ``allow_partial`` kept the converged steps of a run that stopped early)."""
    if not (math.isfinite(self_weight) and self_weight >= 0.0):
        raise ValueError(f"self_weight must be >= 0 N/m per unit width, got {self_weight!r}")
    m = beam.model
    settings = settings or Settings()
    load_w, mid_w = int(m.dof([beam.load], "w")[0]), int(m.dof([beam.mid], "w")[0])
    t0 = time.perf_counter()
    weight = np.zeros(m.n_dof)
    start, u0 = None, np.zeros(m.n_dof)
    if self_weight > 0.0:
        x, w_dofs = m.coords[:, 0], m.dof(np.arange(m.n_nodes), "w")
        for x0, x1 in itertools.pairwise(beam.x_ends):
            for xn, share in ((x0, 1.0 / 6.0), (0.5 * (x0 + x1), 2.0 / 3.0), (x1, 1.0 / 6.0)):
                weight[w_dofs[int(np.argmin(np.abs(x - xn)))]] -= self_weight * (x1 - x0) * share
        start = run(m, [1.0], settings, loads=(weight, np.zeros(m.n_dof)))
        u0 = np.asarray(start.u[-1])
    factors = np.linspace(0.0, 1.0, int(n_steps) + 1)[1:]
    failure = None
    try:
        if start is None:
            m.prescribe([beam.load], "w", -float(w_load_max))
            res = run(m, factors, settings)
        else:  # the load point held where the weight left it, then driven; the weight stays as dead load
            m.hold_dofs([load_w], [u0[load_w]], [-float(w_load_max)])
            res = run(m, factors, settings, start=start, loads=(np.zeros(m.n_dof), weight))
    except NonConvergence as err:
        if not allow_partial:
            raise
        res, failure = err.result, err.report
    wall = time.perf_counter() - t0
    # the reaction at the held load point is its internal force: the weight's own nodal share is not load
    P = -res.reaction([beam.load], "w") + weight[load_w]
    u = np.asarray(res.u)
    return {
        "P": P,
        "M": P * beam.a,
        "delta": -(u[:, mid_w] - u0[mid_w]),
        "delta_load": -(u[:, load_w] - u0[load_w]),
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


# ---- sources of the cracked branch's over-stiffness (chapter 08): shrinkage restraint and self-weight
_CEMENT_CLASS = {
    "S": (3.0, 0.13),
    "N": (4.0, 0.12),
    "R": (6.0, 0.11),
}  # EN 1992-1-1 B.2: alpha_ds1, alpha_ds2


def shrinkage_strain_en1992(fcm, h0, t_days, ts_days, rh=0.5, cement="N") -> dict:
    """Total shrinkage strain eps_cs = eps_cd + eps_ca of EN 1992-1-1 §3.1.4 and Annex B.2 at age ``t_days``
    for drying from ``ts_days`` (end of curing), mean cylinder strength ``fcm`` [Pa], notional size
    ``h0`` = 2 Ac / u [m], relative humidity ``rh`` (fraction, 0.4-1.0) and cement class "S", "N" or "R".

    eps_cd = beta_ds k_h eps_cd,0 with eps_cd,0 = 0.85 (220 + 110 alpha_ds1) exp(-alpha_ds2 fcm/10 MPa) 1e-6
    beta_RH, beta_RH = 1.55 (1 - rh^3), beta_ds = (t - ts) / (t - ts + 0.04 sqrt(h0^3)) (h0 in mm), k_h from
    Table 3.3 (linear between 100, 200, 300, 500 mm, constant outside); eps_ca = (1 - exp(-0.2 sqrt(t)))
    2.5 (fck - 10 MPa) 1e-6 with fck = fcm - 8 MPa. Returns a dict with ``eps_cs``, ``eps_cd``, ``eps_ca``
    (shrinkage positive)."""
    if not (math.isfinite(fcm) and 18e6 <= fcm <= 120e6):
        raise ValueError(f"fcm must be in [18e6, 120e6] Pa (fck >= 10 MPa), got {fcm!r}")
    if not (math.isfinite(h0) and h0 > 0.0):
        raise ValueError(f"h0 must be a positive notional size 2 Ac / u [m], got {h0!r}")
    if not (math.isfinite(ts_days) and ts_days >= 0.0 and math.isfinite(t_days) and t_days > ts_days):
        raise ValueError(
            f"ages must satisfy 0 <= ts_days < t_days, got ts_days={ts_days!r}, t_days={t_days!r}"
        )
    if not (math.isfinite(rh) and 0.4 <= rh <= 1.0):
        raise ValueError(f"rh must be a relative humidity in [0.4, 1.0] (fraction), got {rh!r}")
    if cement not in _CEMENT_CLASS:
        raise ValueError(f"cement must be one of {sorted(_CEMENT_CLASS)}, got {cement!r}")
    a1, a2 = _CEMENT_CLASS[cement]
    eps_cd0 = 0.85 * (220.0 + 110.0 * a1) * math.exp(-a2 * fcm / 10e6) * 1e-6 * 1.55 * (1.0 - rh**3)
    h0_mm = h0 * 1e3
    k_h = float(np.interp(h0_mm, [100.0, 200.0, 300.0, 500.0], [1.0, 0.85, 0.75, 0.70]))
    beta_ds = (t_days - ts_days) / (t_days - ts_days + 0.04 * math.sqrt(h0_mm**3))
    eps_cd = beta_ds * k_h * eps_cd0
    eps_ca = (1.0 - math.exp(-0.2 * math.sqrt(t_days))) * 2.5 * (fcm / 1e6 - 8.0 - 10.0) * 1e-6
    return {"eps_cs": eps_cd + eps_ca, "eps_cd": eps_cd, "eps_ca": eps_ca}


def shrinkage_restraint_stress(section: Section, eps_cs: float) -> tuple[np.ndarray, float]:
    """Concrete stress [Pa] (tension positive) at each layer's mid-depth of an uncracked RC ``section`` whose
    bars restrain a free shrinkage ``eps_cs`` (> 0), and the shrinkage curvature [1/m] of EN 1992-1-1 §7.4.3
    (1/r_cs = eps_cs alpha_e S / I).

    The classical transformed-section estimate: bonded bars that do not shrink act on the composite section
    as tensile forces F_i = eps_cs Es A_i at their levels; concrete layers count with their E0 (short-term
    alpha_e = Es / E0: no creep relaxation, so an upper estimate of the stress). Per unit width."""
    if not (math.isfinite(eps_cs) and 0.0 < eps_cs < 2e-3):
        raise ValueError(f"eps_cs must be a shrinkage strain in (0, 2e-3), got {eps_cs!r}")
    conc = section.kind == CONCRETE
    bars = section.kind == STEEL
    if not conc.any() or not bars.any():
        raise ValueError("shrinkage_restraint_stress: the section needs CONCRETE and STEEL layers")
    e_ref = float(section.params[np.flatnonzero(conc)[0], P_E0])
    modulus = np.where(conc, section.params[:, P_E0], 0.0) + np.where(bars, section.params[:, S_ES], 0.0)
    n = modulus / e_ref  # modular ratio of each layer
    a_t = float(np.sum(n * section.h))
    z_c = float(np.sum(n * section.h * section.z_mid)) / a_t
    i_t = float(np.sum(n * (section.h**3 / 12.0 + section.h * (section.z_mid - z_c) ** 2)))
    force = eps_cs * modulus[bars] * section.h[bars]  # per unit width
    n_f = float(force.sum())
    m_f = float(np.sum(force * (section.z_mid[bars] - z_c)))
    sigma = n_f / a_t + m_f * (section.z_mid - z_c) / i_t
    # bars below the centroid (m_f < 0) pull the bottom face longer: sagging, reported positive
    sagging = -m_f / (e_ref * i_t)
    return np.where(conc, sigma, 0.0), sagging


def with_shrinkage_restraint(section: Section, eps_cs: float) -> tuple[Section, np.ndarray]:
    """Copy of ``section`` whose concrete layers crack at fr - sigma_cs, sigma_cs the restraint stress of
    :func:`shrinkage_restraint_stress` where it is tensile (the compressive side keeps fr). A first-order
    model of pre-cracking by shrinkage: the bars' small pre-compression is not carried over. Returns
    ``(section, sigma_cs)``."""
    sigma, _ = shrinkage_restraint_stress(section, eps_cs)
    conc = section.kind == CONCRETE
    params = section.params.copy()
    fr_new = params[conc, P_FR] - np.maximum(sigma[conc], 0.0)
    if np.any(fr_new <= 0.0):
        raise ValueError(
            f"eps_cs = {eps_cs!r}: the restraint stress {sigma[conc].max():.4g} Pa reaches the tensile "
            "strength (the section is cracked by shrinkage alone)"
        )
    params[conc, P_FR] = fr_new
    return replace(section, params=params), sigma


def four_point_deflection_after_self_weight(mc, P, q: float, span: float, a: float, n_int: int = 4001):
    """Mid-span deflection [m] (positive down) under two loads ``P`` (per unit width) at distance ``a`` from
    the supports, measured from the state under the self-weight ``q`` [N/m per unit width], as a test that
    zeroes its gauges after placing the beam measures it: delta(P, q) - delta(0, q), each by the curvature
    integral int kap(M) x dx + int V / S dx over the half span (``mc`` a monotone moment-curvature table, the
    load applied monotonically after the self-weight). NaN beyond the table's monotone branch."""
    # the shear span and the middle part integrated apart: M has a kink and V a jump at the load point, and
    # the trapezoid rule is then O(h^2) on each part
    n_a = max(2, int(n_int * a / (0.5 * span)))
    parts = (
        (np.linspace(0.0, a, n_a), 1.0),
        (np.linspace(a, 0.5 * span, max(2, int(n_int) - n_a + 1)), 0.0),
    )

    def delta(p):
        total = 0.0
        for x, in_shear_span in parts:
            m = (p * x if in_shear_span else p * a) + 0.5 * q * x * (span - x)
            v = in_shear_span * p + q * (0.5 * span - x)
            if m.max() > mc.M_limit():
                return np.nan
            total += np.trapezoid(mc.curvature(m) * x, x) + np.trapezoid(v / mc.shear_stiffness(m), x)
        return float(total)

    d0 = delta(0.0)
    return np.array([delta(float(p)) - d0 for p in np.atleast_1d(P)])
