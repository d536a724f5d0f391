# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 17 — Limit analysis: the capacity as a certified bracket (beyond the paper)
#
# The paper finds a footing's capacity the way an incremental elasto-plastic analysis does: push until the
# solver stops making progress. That number depends on the mesh, the iteration scheme and, for ψ < φ, on the
# path (chapter 10). Limit analysis answers the question the engineer asked — the collapse load of the
# rigid-plastic body — with two numbers that enclose it: a **lower bound** from a stress field that is in
# equilibrium and nowhere above yield, and an **upper bound** from a collapse mechanism whose dissipation
# pays for the work of the loads. Each bound is one second-order cone program (Makrodimopoulos & Martin
# 2006, 2007; Sloan 2013), solved here by Clarabel on meshes from Triangle.
#
# **In this chapter you will**
# - state the static and kinematic theorems and write Mohr–Coulomb and its flow rule as 3-D cones;
# - build both bounds on the same triangles (`ssi.limit`), certify the lower bound after the solve and
#   recompute the upper bound from the velocities;
# - split the gap between the bounds by element and refine where it lives (nested bisection, so the bounds
#   can only improve) until (UB − LB)/(UB + LB) ≤ 2 % (1 % on request);
# - check the brackets against Prandtl (N_c), Prandtl–Reissner (N_q), Martin's exact N_γ, a sliding footing
#   and Smith & Griffiths' program 6.1, bracket the Davis material for ψ < φ and a factor of safety.

# %% [markdown]
# ## Theory
#
# **The theorems** (associated perfect plasticity, small strain). The collapse multiplier λ* of the
# reference loads, with the dead loads (weight, surcharge) held, is unique and independent of E, ν and the
# loading history. *Static theorem*: a stress field in equilibrium with the dead loads plus λ × the
# reference loads, meeting the traction boundary conditions and nowhere outside the yield surface, has
# λ ≤ λ*. *Kinematic theorem*: a velocity field meeting the velocity boundary conditions and the flow rule,
# with unit power of the reference loads, has λ = D − P_dead ≥ λ* (D the plastic dissipation, P_dead the
# power of the dead loads). For ψ < φ neither theorem holds; Radenković's theorem keeps the associated upper
# bound as a ceiling, and Davis' associated material (c* = βc, tan φ* = β tan φ,
# β = cos ψ cos φ / (1 − sin ψ sin φ)) gives the usual engineering value.
#
# **Mohr–Coulomb as a cone** (plane strain, tension positive):
#
# $$\|(\sigma_x-\sigma_z,\ 2\tau_{xz})\| \le 2c\cos\varphi - (\sigma_x+\sigma_z)\sin\varphi ,$$
#
# the vector $(2c\cos\varphi-(\sigma_x+\sigma_z)\sin\varphi,\ \sigma_x-\sigma_z,\ 2\tau_{xz})$ lies in
# the 3-D second-order cone; φ = 0 is Tresca. Its associated flow rule: with
# $e \ge \|(\dot\varepsilon_x-\dot\varepsilon_z,\ \dot\gamma_{xz})\|$,
# $\dot\varepsilon_x+\dot\varepsilon_z = e\sin\varphi$, and the dissipation per unit volume is
# $c\cos\varphi\,e$.
# On a Coulomb joint (c_i, φ_i) with slip $d_t$ and opening $d_n$: $d_n = |d_t|\tan\varphi_i$, dissipation
# $c_i|d_t|$ per unit length.
#
# **Elements.** Lower bound: 3-node triangles with linear stress, nodes unique to each triangle, so every
# edge may carry a stress discontinuity with continuous tractions; equilibrium in each triangle (constant
# divergence, the weight γ along −z); the cone at the three vertices holds the whole linear field inside.
# Upper bound: 6-node triangles with quadratic velocity, so the strain rate is linear and the flow rule at
# the vertices holds everywhere; the dissipation is integrated with the vertex rule, exact for φ > 0 (it is
# then $c\cot\varphi$ times the linear volumetric rate) and above the true integral for φ = 0 (a convex
# function of a linear field lies below the interpolant of its vertex values), so the bound stays rigorous.
# A rigid footing is a translating body: rough — the soil under it moves with it; smooth or Coulomb — the
# jump d = U − u is quadratic along an edge and its Bernstein control points, which hold the whole curve in
# their convex hull, carry the joint's cone and its dissipation.
#
# **Certification.** The solver's status is not trusted (Clarabel reports `AlmostSolved` or even
# `NumericalError` on good lower bounds). The lower bound is solved with the yield cones shrunk by 10⁻⁴,
# projected exactly (sparse least squares) onto the equalities, checked vertex by vertex against the true
# cone, and λ is recomputed from the projected field. The upper bound is recomputed from the velocities:
# strain rates, the least e, the flow-rule residual, dissipation and powers.
#
# **The gap by element.** With the lower-bound stress σ and the upper-bound velocity u on the same
# triangles, virtual work gives
#
# $$\lambda_{UB}-\lambda_{LB} = \sum_e\Big[D_e(u)-\int_e \sigma:\dot\varepsilon(u)\,dA\Big]
#   + \sum_{\text{joint}}\int \big[D_i(d) - t\cdot d\big]\,ds ,$$
#
# every term ≥ 0 (σ is admissible and D is the support function of the yield set). Each element's term is
# its share; the largest shares are refined by longest-edge bisection. A bisected mesh contains the old
# one, so the old fields stay admissible: the lower bound cannot fall and the upper bound cannot rise.
#
# | symbol | code | meaning |
# |---|---|---|
# | λ | `lam` | load factor of the reference loads |
# | c, φ, γ | `Material(c, phi_deg, gamma)` | cohesion [Pa], friction angle [°], unit weight [N/m³] |
# | c_i, φ_i | `Interface("coulomb", c, phi_deg)` | footing joint |
# | β | `davis_beta(phi, psi)` | Davis' reduction factor |
# | e | `e` variables of `ssi.limit.upper` | plastic multiplier at a vertex |
# | share_e | `Bracket.shares` | element's share of UB − LB |

# %%
import math
import time
from dataclasses import replace

import matplotlib.pyplot as plt
import numpy as np

from ssi.capacity import strip_beam_capacity, strip_beam_interaction
from ssi.lab import paths, report
from ssi.lab.examples import chapter11_section
from ssi.limit import (
    Beam,
    Boundary,
    Footing,
    Interface,
    Material,
    Site,
    adaptive,
    bracket,
    check_limit,
    davis_beta,
    safety_factor,
    strip_site,
    triangulate,
)

FAST = paths.FAST
# the requested relative gaps (UB-LB)/(UB+LB): the 2 %, 1 % on request and 3 % for N_gamma in full
# mode; fast mode (make test) exercises the same code on a few small meshes
GAP = 0.10 if FAST else 0.02
GAP_FINE = 0.07 if FAST else 0.01
GAP_NGAMMA = 0.20 if FAST else 0.03
GAP_ROT = 0.10 if FAST else 0.06  # the rotating footing's checks are inequalities, not a gap claim
C = 10e3  # cohesion [Pa] of chapter 10's footing
B = 2.0  # footing width [m]
print("fast mode" if FAST else "full mode", "gap", GAP)


def prandtl(c, phi_deg, q=0.0):
    """Prandtl-Reissner q_u = c N_c + q N_q of a weightless soil [Pa] (closed form, independent of ssi)."""
    if phi_deg == 0.0:
        return c * (2.0 + math.pi) + q
    t = math.tan(math.radians(phi_deg))
    nq = math.exp(math.pi * t) * math.tan(math.radians(45.0 + phi_deg / 2.0)) ** 2
    return c * (nq - 1.0) / t + q * nq


def graded(x0, h_min, growth):
    """Element size [m] growing from h_min at the footing edge (x0, 0)."""
    return lambda p: h_min + growth * np.hypot(p[:, 0] - x0, p[:, 1])


def outside(lb, ub, exact):
    """How far ``exact`` lies outside [lb, ub], relative (<= 0: inside)."""
    return max(lb / exact - 1.0, 1.0 - ub / exact)


def run(site, size, gap, h=1.0, label="", fans=(), **kw):
    mesh = triangulate(site, h, size=size, fans=fans)
    t0 = time.perf_counter()
    res = adaptive(site, mesh, gap=gap, **kw)
    res.wall = time.perf_counter() - t0
    last = res.history[-1]
    print(
        f"{label:28s} {len(res.history):2d} meshes, {last['n_el']:5d} triangles: LB {res.lb / 1e3:9.3f} "
        f"UB {res.ub / 1e3:9.3f} kPa, gap {100 * res.gap:5.2f} %, {res.wall:6.1f} s, "
        f"solver setbacks {res.solver_setbacks}"
    )
    return res


# %% [markdown]
# ## Prandtl: rough and smooth rigid strip, φ = 0 and 20°, c = 10 kPa, weightless
#
# The half model of chapter 10 (6 m × 5 m, footing 0 ≤ x ≤ 1 m, symmetry roller on x = 0, rollers on
# x = 6 m, base fixed); λ is the mean footing pressure [Pa].

# %%
prandtl_runs = {}
for phi in (0.0, 20.0):
    for kind in ("rough", "smooth"):
        site = strip_site(B, Material(C, phi), Interface(kind))
        gap = GAP_FINE if (phi, kind) == (20.0, "rough") else GAP
        prandtl_runs[phi, kind] = run(site, graded(1.0, 0.2, 0.3), gap, label=f"phi={phi:g} {kind}")

# %%
ok_prandtl, worst_gap = True, 0.0
for (phi, kind), res in prandtl_runs.items():
    exact = prandtl(C, phi)
    inside_every_mesh = all(r["best_lb"] <= exact <= r["best_ub"] for r in res.history)
    inside_every_mesh &= all(r["lb"] <= exact * (1 + 1e-9) for r in res.history if r["certified"])
    inside_every_mesh &= all(r["ub"] >= exact * (1 - 1e-9) for r in res.history)
    want = GAP_FINE if (phi, kind) == (20.0, "rough") else GAP
    ok_prandtl &= inside_every_mesh and res.gap <= want
    worst_gap = max(worst_gap, res.gap)
    print(
        f"phi={phi:4.0f} {kind:6s} LB/exact {res.lb / exact:.4f}  UB/exact {res.ub / exact:.4f}  "
        f"gap {100 * res.gap:.2f} % (asked {100 * want:g} %)  inside on every mesh: {inside_every_mesh}"
    )
report.check(
    "fela_prandtl",
    f"largest gap (UB-LB)/(UB+LB) of 4 adaptive Prandtl brackets; each contains c Nc on every mesh "
    f"and rough phi=20 reaches {100 * GAP_FINE:g} %",
    worst_gap,
    GAP,
    passed=ok_prandtl,
)

# %% [markdown]
# ### Time against triangles
#
# The rough φ = 20° footing refined to the fine gap: each row of the adaptive history is one lower and one
# upper bound (Clarabel with its QDLDL factorisation on one thread -- its "auto" choice, faer on every core,
# was 2.4x slower on the lower bound -- on the 2-core machine shared with the rest of the test suite, so
# the times are upper estimates; both bounds are solved to 1e-9: lower bounds solved to 1e-7 failed their
# certification on the N_gamma meshes of cohesionless sand from 4 700 triangles on, measured).

# %%
hist = prandtl_runs[20.0, "rough"].history
print(" triangles   LB/exact   UB/exact   gap %   t_LB [s]  t_UB [s]  it_LB it_UB  cones")
ex20 = prandtl(C, 20.0)
for r in hist:
    print(
        f"{r['n_el']:10d}  {r['best_lb'] / ex20:9.4f}  {r['best_ub'] / ex20:9.4f}  {100 * r['gap']:6.2f}  "
        f"{r['t_lb']:8.2f}  {r['t_ub']:8.2f}  {r['it_lb']:5d} {r['it_ub']:5d}  {r['cones_lb']:6d}"
    )

# %% [markdown]
# ## Davis: the same footing with φ = 20°, ψ = 0
#
# No rigorous lower bound exists for ψ < φ. The associated bracket (above) is a ceiling (Radenković); the
# Davis material c* = βc, tan φ* = β tan φ (β = cos φ for ψ = 0) is associated, so its bracket is rigorous
# for it and must contain its own Prandtl value. Chapter 10's former incremental ψ = 0 limits (viscously
# relaxed pushes of the load-controlled solver before issue 31, measured there: 1.039, 0.995 and 0.969 ×
# Prandtl(φ = 20°) on h = 0.25, 0.125 and 0.0625 m) are set beside both brackets.

# %%
soil_na = Material(C, 20.0, psi_deg=0.0)
site_na = strip_site(B, soil_na, Interface("rough"))
davis = run(site_na.davis(), graded(1.0, 0.2, 0.3), GAP, label="Davis phi=20 psi=0")
m_d = soil_na.davis()
exact_d = prandtl(m_d.c, m_d.phi_deg)
beta = davis_beta(20.0, 0.0)
print(f"beta = {beta:.4f}: c* = {m_d.c / 1e3:.3f} kPa, phi* = {m_d.phi_deg:.3f} deg")
print(f"Davis bracket / Prandtl(c*, phi*): [{davis.lb / exact_d:.4f}, {davis.ub / exact_d:.4f}]")
assoc = prandtl_runs[20.0, "rough"]
print(f"in units of Prandtl(phi=20): Davis [{davis.lb / ex20:.3f}, {davis.ub / ex20:.3f}], "
      f"associated [{assoc.lb / ex20:.3f}, {assoc.ub / ex20:.3f}]")  # fmt: skip
# each incremental limit also checked as a solver checks it (ssi.limit.check_limit: inside the band
# [0.97 LB_Davis, 1.03 UB_assoc], a false collapse below it, a mesh overestimate above it)
for h, v in ((0.25, 1.039), (0.125, 0.995), (0.0625, 0.969)):
    where = "above the associated upper bound" if v * ex20 > assoc.ub else "inside [LB_Davis, UB_assoc]"
    verdict = check_limit(v * ex20, (davis.lb, assoc.ub)).verdict
    print(f"chapter 10, psi = 0, h = {h:6.4f} m: {v:.3f} x Prandtl -> {where}; check_limit: {verdict}")
report.check(
    "fela_davis",
    "how far Prandtl(c*, phi*) of the Davis material (phi=20, psi=0) lies outside its bracket (<= 0: inside)",
    outside(davis.lb, davis.ub, exact_d),
    0.0,
    passed=outside(davis.lb, davis.ub, exact_d) <= 0.0,
)

# %% [markdown]
# ## N_γ: rough strip on sand, c = 0, φ = 30°, γ = 20 kN/m³
#
# The exact value from the method of characteristics: **N_γ = 14.75** for a rough base, φ = 30° (Martin,
# C.M. 2005, *Exact bearing capacity calculations using the method of characteristics*, Proc. 11th
# IACMAG, Turin, vol. 4, 441–450: his ABC program's table; the rough value carries its four printed digits,
# ±0.005). q_u = ½ γ B N_γ. The mechanism reaches ≈ 9 m from the axis for B = 2 m: the block is 10 m × 5 m.

# %%
GAMMA = 20e3
N_GAMMA_MARTIN = 14.75
site_ng = strip_site(B, Material(0.0, 30.0, gamma=GAMMA), Interface("rough"), half_width=10.0, depth=5.0)
# full mode starts from a finer graded mesh (0.05 m at the footing edge, growing by 0.18 per metre, at most
# 1 m) with a fan of 8 sectors (radius 0.5 m) at the footing's edge, where the lower bound's stress field
# turns round the singular point, and marks half of the gap per step: 4 381 triangles in 8 meshes and 41 s
# CPU to a 2.87 % gap, against 5 219 triangles in 9 meshes and 60 s CPU still at 3.28 % without the fan
# (measured side by side, 2026-12-04, loaded machine; without it the gap of 3 % took 7 159 triangles in 10
# meshes and ~92 s CPU). The bracket is rigorous on any mesh: the fan changes the cost, not the claim
if FAST:
    size_ng, h_ng, theta_ng, fans_ng = graded(1.0, 0.08, 0.25), 1.5, 0.6, ()
else:
    size_ng, h_ng, theta_ng, fans_ng = graded(1.0, 0.05, 0.18), 1.0, 0.5, ((1.0, 0.0, 0.5, 8),)
ngamma = run(
    site_ng,
    size_ng,
    GAP_NGAMMA,
    h=h_ng,
    label="N_gamma phi=30 rough",
    fans=fans_ng,
    theta=theta_ng,
    max_steps=20,
)
q_ng = 0.5 * GAMMA * B * N_GAMMA_MARTIN
n_lb, n_ub = ngamma.lb / (0.5 * GAMMA * B), ngamma.ub / (0.5 * GAMMA * B)
print(f"N_gamma bracket [{n_lb:.3f}, {n_ub:.3f}] against Martin's {N_GAMMA_MARTIN}")
report.check(
    "fela_ngamma",
    f"gap of the N_gamma bracket [{n_lb:.3f}, {n_ub:.3f}] (rough, phi=30), which must contain Martin's 14.75",
    ngamma.gap,
    GAP_NGAMMA,
    passed=ngamma.lb <= q_ng <= ngamma.ub and ngamma.gap <= GAP_NGAMMA,
)

# %% [markdown]
# ## Surcharge: c = 0, φ = 30°, weightless, q = 10 kPa — Prandtl–Reissner q N_q

# %%
Q = 10e3
site_q = strip_site(B, Material(0.0, 30.0), Interface("rough"), half_width=10.0, depth=5.0, surcharge=Q)
surch = run(site_q, graded(1.0, 0.1, 0.25), GAP, h=1.5, label="surcharge phi=30")
exact_q = prandtl(0.0, 30.0, Q)
print(f"bracket / (q Nq): [{surch.lb / exact_q:.4f}, {surch.ub / exact_q:.4f}]")
report.check(
    "fela_surcharge",
    "how far q Nq (c=0, phi=30, q=10 kPa) lies outside the bracket (<= 0: inside)",
    outside(surch.lb, surch.ub, exact_q),
    0.0,
    passed=outside(surch.lb, surch.ub, exact_q) <= 0.0,
)

# %% [markdown]
# ## Embedment: the side soil as its overburden, or modelled
#
# Chapter 12's trench: the strip's base D = 1 m below the ground, 1 m of backfill (γ = 18 kN/m³) beside it,
# weightless c = 0, φ = 30° sand below (here a rigid rough strip, B = 2 m, half model; λ = its force V).
# `scene.limit_analysis()` replaces the side soil by its **overburden**: the geostatic vertical stress of
# the base level, q = γD, as a dead pressure on the ground beside the strip at the base level, the model
# being the block below the base. That is Terzaghi's assumption (the backfill has weight but no strength),
# and for it the collapse pressure on weightless sand is exactly q N_q (Prandtl–Reissner, rough or smooth).
# Chapter 12's soft elastic backfill is such a backfill; its strength is not used, so the scene is taken as
# it is. The bracket is also a rigorous floor for a backfill with strength: a statically admissible field of
# the surcharge model extends above the base by the geostatic state (σ_zz = σ_v, σ_xx = K0 σ_v, admissible
# for K0 between the active and passive values; K0 = 1 here), so the side soil's strength can only add.
#
# `side_soil="soil"` models the backfill (here sand, c = 0, φ = 30°, K0 = 1): the trench is cut out of the
# cells, its walls touch nothing and keep their geostatic horizontal stress K0 γ |z| as a dead pressure
# that is linear along the wall (exact in both bounds: linear stresses meet it at every vertex, Simpson's
# rule integrates it against quadratic velocities). By the argument above its capacity is at least the
# surcharge model's: its upper bound must lie above the surcharge model's lower bound. (Both backfills
# weigh 18 kN/m³, so their surcharge models are one problem; for the sand backfill `side_soil="surcharge"`
# warns that its upper bound is not a ceiling of that scene.) With a `side_contact` the walls do touch: they
# are segments of the strip's footing on that contact (c_i, φ_i and the tension cut-off, in both bounds),
# so a smooth, a frictional and a bonded wall order the bounds as the theorems require
# (`tests/test_limit_scene.py`).
# A `Site`'s embedded strip always stands in its modelled trench, its walls free or on its side contact.

# %%
from ssi.scene import RigidFooting, Scene, Settlement, SoilLayer  # noqa: E402

D_EMB, GAMMA_BACK = 1.0, 18e3
GAP_EMB = 0.10 if FAST else 0.07


def embedded(backfill):
    sand = SoilLayer(5.0, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, K0=1.0)
    return Scene(
        width=12.0,
        depth=5.0 + D_EMB,
        symmetric=True,
        layers=[backfill, sand],
        embedment=D_EMB,
        foundation=RigidFooting(-1.0, 1.0),
        loads=[Settlement(0.05)],
    )


soft_backfill = SoilLayer(D_EMB, E=1e3, nu=0.3, unit_weight=GAMMA_BACK)  # chapter 12's: weight, no strength
sand_backfill = SoilLayer(D_EMB, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, unit_weight=GAMMA_BACK, K0=1.0)
q_nq_emb = prandtl(0.0, 30.0, GAMMA_BACK * D_EMB)
emb_q = embedded(soft_backfill).limit_analysis(gap=GAP_EMB)
emb_s = embedded(sand_backfill).limit_analysis(gap=GAP_EMB, side_soil="soil")
for name, r in (("overburden (surcharge)", emb_q), ("side soil modelled", emb_s)):
    print(
        f"{name:24s} V/B in [{r.lb / B / 1e3:7.1f}, {r.ub / B / 1e3:7.1f}] kPa = [{r.lb / B / q_nq_emb:.4f}, "
        f"{r.ub / B / q_nq_emb:.4f}] gamma D Nq, gap {100 * r.gap:4.1f} %, {r.n_triangles} triangles, "
        f"{r.time:4.1f} s"
    )
emb_out = outside(emb_q.lb / B, emb_q.ub / B, q_nq_emb)
report.check(
    "fela_embedded",
    "how far gamma D Nq (D = 1 m, c=0, phi=30, weightless below the base) lies outside the bracket of the "
    "embedded strip with its side soil as overburden (<= 0: inside)",
    emb_out,
    0.0,
    passed=emb_out <= 0.0,
)
emb_side = emb_s.ub / emb_q.lb - 1.0
report.check(
    "fela_embedded_side_soil",
    "UB with the side soil modelled / LB with it as overburden - 1 (>= 0: the stronger scene's ceiling is "
    "above the weaker one's floor)",
    emb_side,
    0.0,
    passed=emb_side >= 0.0,
)
print(f"modelled side soil: LB {emb_s.lb / emb_q.lb - 1:+.2%} against the overburden-only LB")

# %% [markdown]
# ## Sliding: a rigid footing on a Coulomb joint over much stronger soil
#
# Whole model (no symmetry), N = 100 kN/m held, the horizontal force λ × 1 N/m scaled; joint φ_i = 25°,
# c_i = 0 and 5 kPa; soil Tresca with c = 1 MPa. The footing translates (its rotation is held), so the
# exact capacity is H = c_i B + N tan φ_i: the mechanism is the footing sliding and lifting by tan φ_i.

# %%
N_SLIDE = 100e3
slide = {}
for c_i in (0.0, 5e3):
    itf = Interface("coulomb", c=c_i, phi_deg=25.0)
    site_s = strip_site(
        B, Material(1e6, 0.0), itf, half_width=4.0, depth=3.0, symmetric=False,
        load_ref=(1.0, 0.0), load_dead=(0.0, -N_SLIDE),
    )  # fmt: skip
    br = bracket(site_s, triangulate(site_s, 1.0, size=graded(1.0, 0.3, 0.3)))
    exact_s = c_i * B + N_SLIDE * math.tan(math.radians(25.0))
    slide[c_i] = (br, exact_s)
    print(
        f"c_i = {c_i / 1e3:3.0f} kPa: [{br.lb / exact_s:.6f}, {br.ub / exact_s:.6f}] x exact, "
        f"gap {br.gap:.1e}"
    )
ok_slide = all(b.lb <= e <= b.ub * (1 + 1e-9) and b.gap <= 0.01 for b, e in slide.values())
report.check(
    "fela_sliding",
    "largest gap of the sliding brackets (c_i = 0, 5 kPa); each contains c_i B + N tan phi_i",
    max(b.gap for b, _ in slide.values()),
    0.01,
    passed=ok_slide,
)

# %% [markdown]
# ## A footing that rotates: an eccentric load and a moment
#
# The footing is a rigid body with velocity (U, W) of its reference point (x_c, z_c) (the centre of its
# base) and rotation rate θ: a point of it moves with (U − θ(z − z_c), W + θ(x − x_c)). The upper bound adds
# θ to its unknowns (a rough base's nodes tied to the rigid motion, the moment's power M θ); the lower bound
# adds one equation, the moment of the base tractions about (x_c, z_c) equal to the applied moment. Two
# independent references on a weightless Tresca strip (B = 2 m, s_u = 10 kPa, whole model):
#
# - **Eccentric vertical load** V at e = B/8. Meyerhof's effective width, V_M = (2 + π) s_u (B − 2e), is a
#   rigorous *lower* bound of the exact load for any interface that can carry zero shear: Prandtl's field,
#   which extends statically admissibly into the whole half-space for Tresca, under the width B − 2e centred
#   on the load and zero traction on the rest of the base (the footing is then in equilibrium, moment
#   included). So the upper bound must lie above V_M (asserted). Meyerhof's V_M is otherwise only an
#   approximation of the exact load; how close it is, the brackets below show (for a no-tension Coulomb
#   joint, c_i = 0, and for a bonded base, which can also pull).
# - **Moment alone, bonded base.** The circular "scoop" (the footing and a circular block of soil under it
#   rotating about a point on the axis, slip at s_u on the arc through the footing's edges) is a rigorous
#   upper bound M = (B²/2) s_u α / sin²α, least at tan α = 2α (α = 1.1656): **M = 0.690 s_u B²**. The lower
#   bound must lie below it; the bracket then pins the exact moment capacity between the two.


# %%
def rotating_site(kind, V, M):
    """The whole-model Tresca strip of this section, lambda scaling (0, -V) [N/m] and M [N m/m]."""
    itf = Interface(kind) if kind != "coulomb" else Interface("coulomb", c=0.0, phi_deg=45.0)
    st = strip_site(B, Material(C, 0.0), itf, half_width=4.0, depth=3.0, symmetric=False)
    ft = Footing(itf, (0.0, -V), (0.0, 0.0), ("x", "z", "r"), centre=(0.0, 0.0), moment_ref=M)
    return replace(st, footings=(ft,))


def two_edges(h_min):
    """Element size [m] graded from h_min at both footing edges (x = -1, 1 m)."""
    return lambda p: h_min + 0.3 * np.minimum(np.hypot(p[:, 0] - 1, p[:, 1]), np.hypot(p[:, 0] + 1, p[:, 1]))


alpha = 1.1655611852072114  # tan(alpha) = 2 alpha (solved below to 1e-12)
assert abs(math.tan(alpha) - 2 * alpha) < 1e-9
scoop = 0.5 * B**2 * C * alpha / math.sin(alpha) ** 2
E_ECC = B / 8
v_m = (2.0 + math.pi) * C * (B - 2 * E_ECC)
rot = {}
for name, kind, V, M, ref in (
    ("eccentric, bonded", "rough", 1.0, -E_ECC, v_m),
    ("eccentric, no tension", "coulomb", 1.0, -E_ECC, v_m),
    ("moment, bonded", "rough", 0.0, 1.0, scoop),
):
    r = run(rotating_site(kind, V, M), two_edges(0.15), GAP_ROT, label=name, max_elements=4000)
    rot[name] = r
    print(f"    bracket / reference = [{r.lb / ref:.4f}, {r.ub / ref:.4f}]  (reference {ref / 1e3:.3f})")
assert all(rot[k].ub >= v_m * (1 - 1e-6) for k in ("eccentric, bonded", "eccentric, no tension"))
assert rot["moment, bonded"].lb <= scoop * (1 + 1e-6)
print(f"moment capacity of the bonded strip in [{rot['moment, bonded'].lb / (C * B**2):.4f}, "
      f"{min(rot['moment, bonded'].ub, scoop) / (C * B**2):.4f}] s_u B^2")  # fmt: skip

# %% [markdown]
# The bonded strip's moment capacity is pinned between the certified lower bound and the scoop (full mode:
# [0.6835, 0.6900] s_u B²). Both eccentric brackets contain Meyerhof's V_M at these gaps (full mode: no
# tension [0.985, 1.083] V_M, bonded [0.979, 1.100] V_M): here V_M is close to the exact load, and the
# bonded base (which can also pull, so carries at least as much) is not resolved from the no-tension one
# at a 6 % gap.
#
# ## The strip as a beam with plastic hinges: `fela_beam_mechanism`
#
# A footing with a `Beam` bends: one rigid, inextensible beam element per base edge of the triangle mesh,
# hinges at both ends of every element dissipating M_p |rotation| (M_p sagging or hogging); the lower bound
# bounds the beam's moment — from the base tractions and the columns — at the four Bernstein points of each
# element's cubic M(x), so |M| ≤ M_p along the whole beam, not only at the nodes. M_p comes from ssi's own
# section analysis of the RC section (`RCDesign.M_Rd(N = 0)`, `ssi.capacity.strip_beam_capacity`;
# a brittle section, below minimum reinforcement, is refused: it forms no hinge).
#
# **Why a trench.** On uniformly strong soil a beam mechanism never governs: the soil can take each column's
# load right under it and the strip need not bend at all (its collapse load grows without bound with the
# soil's strength). The beam governs when the soil cannot support the strip where the columns are: here
# chapter 11's strip (6 m, 0.4 m deep, 15 cm²/m top and bottom) bridges a trench 4 m wide and 1 m deep,
# columns N at x = ±a = ±1 m over the trench, on very strong Tresca soil (s_u = 20 MPa) with a no-tension
# Coulomb contact (c_i = 0, φ_i = 30°).
#
# **Hand calculation.** Upper bound: the two halves of the span rotate by θ about the trench edges
# (x = ±l/2, l = 4 m), the outer overhangs lifting off the soil (a no-tension joint opens freely), hinges in
# sagging under both columns. Work 2 N θ (l/2 − a) = dissipation M_p (θ + θ) gives
# **N_beam = M_p / (l/2 − a)**: the simply supported four-point-bending mechanism (Heyman, *Plastic design of
# frames*, 1971; any hinge position between the columns gives the same load). Lower bound: the soil can carry
# the reaction N of each side over a width δ beside the trench edge at the uniaxial strength 2 s_u (a vertical
# band of uniaxial compression, free on the trench face — statically admissible for Tresca), which moves the
# support out by δ/2: N ≥ M_p / (l/2 − a + δ/2), δ = N / (2 s_u). The exact load therefore lies in
# [N_beam / (1 + ε), N_beam] with ε = δ / (2 (l/2 − a)) = 0.3 %. **PASS** when the certified bracket meets
# that interval (LB ≤ N_beam and UB ≥ N_beam / (1 + ε), solver accuracy 1e-6 relative) with a gap ≤ 2 %.

# %%
MP_SAG, MP_HOG = strip_beam_capacity(chapter11_section())
HALF_L, A_COL, X_S, S_U, N_REF = 2.0, 1.0, 3.0, 20e6, 100e3
# the rectangular stress block of EN 1992 (0.8 x at f_ck = 30 MPa) for As = 1.5e-3 m^2/m, f_y = 500 MPa,
# d = 0.35 m, as an independent check of M_p: As f_y (d - 0.4 x), x = As f_y / (0.8 f_ck)
x_blk = 1.5e-3 * 500e6 / (0.8 * 30e6)
mp_hand = 1.5e-3 * 500e6 * (0.35 - 0.4 * x_blk)
print(f"M_p = {MP_SAG / 1e3:.1f} kN m/m (sagging), {MP_HOG / 1e3:.1f} (hogging); rectangular block "
      f"{mp_hand / 1e3:.1f} kN m/m")  # fmt: skip
assert abs(MP_SAG / mp_hand - 1.0) < 0.03  # the parabola-rectangle and the compression bars: +1.7 %
pts_t = [(-6.0, -4.0), (6.0, -4.0), (6.0, 0.0), (X_S, 0.0), (HALF_L, 0.0), (HALF_L, -1.0), (-HALF_L, -1.0),
         (-HALF_L, 0.0), (-X_S, 0.0), (-6.0, 0.0)]  # fmt: skip
free, foot = Boundary("free"), Boundary("footing", footing=0)
segs_t = ((0, 1, Boundary("fixed")), (1, 2, Boundary("symmetry")), (2, 3, free), (3, 4, foot), (4, 5, free),
          (5, 6, free), (6, 7, free), (7, 8, foot), (8, 9, free), (9, 0, Boundary("symmetry")))  # fmt: skip
itf_t = Interface("coulomb", c=0.0, phi_deg=30.0)
beam_t = Beam(-X_S, X_S, MP_SAG, MP_HOG, loads_ref=((-A_COL, 0.0, -N_REF, 0.0), (A_COL, 0.0, -N_REF, 0.0)))
site_t = Site(np.array(pts_t), segs_t, ((0.0, -3.0, 0),), (Material(S_U, 0.0),),
              (Footing(itf_t, moves=("x", "z", "r"), centre=(0.0, 0.0), beam=beam_t),))  # fmt: skip
n_beam = MP_SAG / (HALF_L - A_COL)
eps = n_beam / (2 * S_U) / (2 * (HALF_L - A_COL))


def near_edges(p):
    """Element size [m] graded from 0.1 m at the trench edges and the strip's ends."""
    d = np.min([np.hypot(p[:, 0] - x, p[:, 1]) for x in (-HALF_L, HALF_L, -X_S, X_S)], axis=0)
    return 0.1 + 0.4 * d


beam_run = run(site_t, near_edges, GAP, label="beam over a trench", max_elements=6000)
lb_n, ub_n = beam_run.lb * N_REF, beam_run.ub * N_REF
print(f"N_beam = {n_beam / 1e3:.2f} kN/m per column, exact in [{n_beam / (1 + eps) / 1e3:.2f}, "
      f"{n_beam / 1e3:.2f}]; bracket [{lb_n / 1e3:.2f}, {ub_n / 1e3:.2f}] kN/m")  # fmt: skip
ok_beam = lb_n <= n_beam * (1 + 1e-6) and ub_n >= n_beam / (1 + eps) * (1 - 1e-6) and beam_run.gap <= GAP
report.check(
    "fela_beam_mechanism",
    "gap of the bracket of an RC strip bridging a trench under two columns; it meets the hand beam "
    "mechanism's interval [M_p/(l/2-a)/(1+eps), M_p/(l/2-a)]",
    beam_run.gap,
    GAP,
    passed=ok_beam,
)
fb = beam_run.final
bm = fb.upper.beam[0]
node_rot = np.zeros(len(bm["x"]))  # each node's hinge rotation: the right end of one element + the left
node_rot[1:] += bm["hinge"][:, 1]  # end of the next
node_rot[:-1] += bm["hinge"][:, 0]
hinged = np.abs(node_rot) > 1e-6 * np.abs(node_rot).max()
print(
    "upper bound: hinges at x =",
    bm["x"][hinged],
    "m, rotations / largest",
    (node_rot / abs(node_rot).max())[hinged].round(4),
)
print(f"lower bound: max |M| / M_p = {fb.lower.beam[0]['utilisation']:.6f}")

# %%
fig, axes = plt.subplots(1, 2, figsize=(12, 3.8))
axes[0].plot(bm["x"], bm["w"] / np.abs(bm["w"]).max(), "r-o", ms=3, label="beam: upper-bound w / max |w|")
axes[0].plot(
    bm["x"][hinged], (bm["w"] / np.abs(bm["w"]).max())[hinged], "ks", ms=7, mfc="none", label="hinges"
)
axes[0].axvspan(-HALF_L, HALF_L, color="0.85", label="trench")
axes[0].set_xlabel("x [m]")
axes[0].set_ylabel("vertical velocity (normalised)")
axes[0].legend(fontsize=8)
m_lb = fb.lower.beam[0]
xb = bm["x"]
axes[1].plot(xb, m_lb["M_left"] / 1e3, "-o", ms=3, color="C0", label="lower bound: M at the beam's nodes")
# the hand diagram at collapse: knife-edge supports at the trench edges, N_beam at each column
xh = np.array([-X_S, -HALF_L, -A_COL, A_COL, HALF_L, X_S])
axes[1].plot(xh, [0, 0, MP_SAG / 1e3, MP_SAG / 1e3, 0, 0], "k--", label="hand: four-point bending at N_beam")
axes[1].axhline(MP_SAG / 1e3, color="r", lw=0.8, label="M_p")
axes[1].set_xlabel("x [m]")
axes[1].set_ylabel("M [kN m/m], sagging > 0")
axes[1].legend(fontsize=8)
report.save_figure(fig, "fig17_3_beam_mechanism")
plt.show()

# %% [markdown]
# *Figure 17.3 — The RC strip bridging a trench. Left: the upper-bound mechanism on the last mesh (the
# beam's vertical velocity: the span between the trench edges sags about hinges under the columns, the
# overhangs lift off the no-tension joint, the soil does not move). Right: the lower bound's bending
# moment at the beam's nodes against the hand calculation's diagram (knife-edge supports at the trench
# edges): the certified field reaches M_p between the columns with the reactions spread a few millimetres
# beyond the edges.*

# %% [markdown]
# ### The hinges' M–N interaction and a joint's tension cut-off
#
# A hinge's capacity depends on the beam's axial force N. `Beam(interaction=...)` takes points (N, M_sag(N),
# M_hog(N)) of the section's resistance with the moment about the base (the beam's axis here), and
# `strip_beam_interaction` samples them from ssi's own section analysis (`RCDesign.M_Rd(N)`), from N = 0 out
# to where M_Rd's search for a strain plane stops (for this section about −1 MN/m: a tenth of the squash
# load, below the balance point). The capacity is then the polygon P of their convex hull: the lower bound
# walks N along the beam (from the base shear and the point loads' horizontal forces) beside M and keeps
# (N, M) inside P at the same four Bernstein points per element (a facet a_N N + a_M M ≤ b is a cubic along
# the element whose control points are a_N N_k + a_M M_k); in the upper bound each hinge rotates θ and
# extends δ along an outward normal of P (the associated flow rule: (δ, θ) = Σ λ_i (a_N, a_M)_i, λ ≥ 0),
# each element of the beam with its own horizontal velocity, and dissipates P's support function Σ λ_i b_i.
# With only the N = 0 point, P is the strip −M_hog ≤ M ≤ M_sag for every N and the beam above is reproduced
# bit for bit (`tests/test_limit_mn.py`). P lies inside the section's convex resistance, so the bracket is
# that of a beam no stronger than the section; as for M_p at N = 0, a brittle section (below minimum
# reinforcement) forms no hinge and is refused. (On a rough base the hinges cannot extend — the soil's
# nodes are tied to the beam — and dissipate P's support function at zero extension: rigorous but loose
# where N matters.)
#
# **The check.** The trench beam on a frictionless contact without tension (a Coulomb joint with c_i = 0,
# φ_i = 0 and the cut-off t_i = 0: no base shear, so N is exactly the end force −P), with P = 500 kN/m of
# compression and 300 kN/m of tension applied at the strip's ends. The hand load is N_beam = M_p(−P) /
# (l/2 − a), M_p(−P) from the rectangular stress block of EN 1992-1-1 §3.1.7 (3) (0.8 x at f_ck, both bar
# layers, moment about the base: M_mid + P h/2): the compression raises M_p (the section is below its
# balance point, and the end force acts below the section's centre), the tension lowers it.
#
# **A tension cut-off.** `Interface("coulomb", c, phi_deg, tension=t_i)` adds σ_n ≤ t_i beside the Coulomb
# rows in the lower bound and, in the upper bound, the support function of the truncated cone: an opening
# d_n ≥ tan φ_i |d_t| dissipates t_i d_n + (c_i − t_i tan φ_i)|d_t| (a Contact's `sig_t` reaches it). Check:
# the pull-out of a rigid footing held down by N over far stronger soil, T = N + t_i B exactly (the joint
# opens uniformly; without a cut-off the apex c_i / tan φ_i is the limit).

# %%
MN_POINTS = strip_beam_interaction(chapter11_section())
mn_n = np.array([p[0] for p in MN_POINTS])
mn_s = np.array([p[1] for p in MN_POINTS])


def block_mp(P):
    """Hand M_p [N m/m] about the base under compression P [N/m]: rectangular block, both bar layers."""
    fck, fy, es, a_s, ecu = 30e6, 500e6, 200e9, 1.5e-3, 3.5e-3

    def forces(x):
        s_top = max(min(es * ecu * (x - 0.05) / x, fy), -fy)
        s_bot = min(es * ecu * (0.35 - x) / x, fy)
        return 0.8 * x * fck, s_top, s_bot

    lo, hi = 0.01, 0.4  # bisection on the neutral axis depth x for the axial balance
    for _ in range(100):
        x = 0.5 * (lo + hi)
        c, st, sb = forces(x)
        lo, hi = (x, hi) if c + 1.5e-3 * (st - sb) < P else (lo, x)
    c, st, sb = forces(x)
    return c * (0.2 - 0.4 * x) + a_s * (st + sb) * 0.15 + P * 0.2


itf_mn = Interface("coulomb", c=0.0, phi_deg=0.0, tension=0.0)
MN_GAP = 0.05  # one fixed mesh in both modes (cheap): the direction and the interval are the claims
mn_rows, mn_ok = [], True
for P in (0.0, 500e3, -300e3):
    beam_p = Beam(-X_S, X_S, MP_SAG, MP_HOG, interaction=MN_POINTS,
                  loads_ref=((-A_COL, 0.0, -N_REF, 0.0), (A_COL, 0.0, -N_REF, 0.0)),
                  loads_dead=((-X_S, P, 0.0, 0.0), (X_S, -P, 0.0, 0.0)))  # fmt: skip
    site_p = replace(
        site_t, footings=(Footing(itf_mn, moves=("x", "z", "r"), centre=(0.0, 0.0), beam=beam_p),)
    )
    res_p = bracket(site_p, triangulate(site_p, 1.0, size=near_edges))  # one mesh: 374 triangles
    mp_p = float(np.interp(-P, mn_n, mn_s))
    nb_p = mp_p / (HALF_L - A_COL)
    eps_p = nb_p / (2 * S_U) / (2 * (HALF_L - A_COL))
    lb_p, ub_p = res_p.lb * N_REF, res_p.ub * N_REF
    ok_p = lb_p <= nb_p * (1 + 1e-6) and ub_p >= nb_p / (1 + eps_p) * (1 - 1e-6) and res_p.gap <= MN_GAP
    hand = block_mp(P) if P >= 0 else None  # (the tension side: no hand value claimed)
    mn_rows.append((P, mp_p, hand, nb_p, lb_p, ub_p))
    mn_ok &= ok_p
    blk = "" if hand is None else f" (block {hand / 1e3:.1f})"
    print(f"  P = {P / 1e3:6.0f} kN/m: M_p(-P) = {mp_p / 1e3:6.1f} kN m/m{blk}, N_beam "
          f"{nb_p / 1e3:6.2f}, bracket [{lb_p / 1e3:6.2f}, {ub_p / 1e3:6.2f}] kN/m: {ok_p}")  # fmt: skip
# the direction: compression above, tension below the unloaded beam's bracket
mn_ok &= mn_rows[1][4] > mn_rows[0][5] and mn_rows[2][5] < mn_rows[0][4]
mn_ok &= abs(mn_rows[1][1] / mn_rows[1][2] - 1.0) < 0.01  # ssi's M_p(N) against the block (0.3 % measured)
report.check(
    "fela_beam_mn",
    "the trench beam with the hinges' M-N polygon under end compression 500 and tension 300 kN/m: each "
    "bracket meets [N_beam/(1+eps), N_beam], N_beam = M_p(-P)/(l/2-a), and moves the right way; largest gap "
    "on one mesh of 374 triangles",
    max((r[5] - r[4]) / (r[5] + r[4]) for r in mn_rows),
    MN_GAP,
    passed=mn_ok,
)

# %%
N_HOLD = 10e3
cut_rows, cut_ok = [], True
for t_i in (0.0, 2e3, None):
    itf_c = Interface("coulomb", c=5e3, phi_deg=25.0, tension=t_i)
    site_c = strip_site(2.0, Material(1e6, 0.0), itf_c, half_width=4.0, depth=3.0, symmetric=False)
    site_c = replace(site_c, footings=(Footing(itf_c, (0.0, 1.0), (0.0, -N_HOLD), ("x", "z")),))
    br_c = bracket(site_c, triangulate(site_c, 1.0, size=lambda p: 0.3 + 0.3 * np.abs(np.abs(p[:, 0]) - 1.0)))
    t_eff = 5e3 / math.tan(math.radians(25.0)) if t_i is None else t_i
    exact_c = N_HOLD + t_eff * 2.0
    ok_c = (
        br_c.lb <= exact_c * (1 + 1e-6) and br_c.ub >= exact_c * (1 - 1e-6) and br_c.ub / br_c.lb - 1 < 1e-3
    )
    cut_ok &= ok_c
    cut_rows.append(br_c.ub / br_c.lb - 1)
    print(f"  pull-out, t_i = {t_eff / 1e3:5.2f} kPa: bracket / (N + t_i B) = [{br_c.lb / exact_c:.6f}, "
          f"{br_c.ub / exact_c:.6f}]: {ok_c}")  # fmt: skip
report.check(
    "fela_cutoff",
    "pull-out of a footing held by N on a Coulomb joint with tension cut-off t_i = 0, 2 kPa and none (apex): "
    "bracket contains N + t_i B with a relative width below 1e-3; largest width",
    max(cut_rows),
    1e-3,
    passed=cut_ok,
)

# %% [markdown]
# ## Smith & Griffiths, program 6.1: a flexible footing on undrained clay
#
# The scene of chapter 10 (`ssi.bearing_capacity.sg61_scene`): half width 2 m of uniform pressure on a
# 12 m × 5 m half block, c_u = 100 kPa (Tresca), x = 0 and x = 12 m on rollers, base fixed. Its limit is
# Prandtl's (2 + π) c_u = 514.16 kPa (the peer's table; chapter 10's reference data).

# %%
site_sg = strip_site(4.0, Material(100e3, 0.0), half_width=12.0, depth=5.0, flexible=True)
# the edge of the flexible load (x = 2 m) is a point where the surface traction jumps: a lower-bound field
# turns through a fan of sectors there, and bisection keeps the number of sectors bounded (without the fan
# the lower bound stalls at 471.3 kPa, 0.917 x, on every mesh from 630 to 12 400 triangles, measured)
sg = run(site_sg, graded(2.0, 0.15, 0.3), GAP, label="S&G 6.1 flexible", fans=((2.0, 0.0, 0.6, 18),))
q_sg = (2.0 + math.pi) * 100e3
print(f"bracket [{sg.lb / 1e3:.1f}, {sg.ub / 1e3:.1f}] kPa against {q_sg / 1e3:.2f} kPa")
report.check(
    "fela_sg61",
    "how far (2+pi) cu = 514.16 kPa lies outside the bracket of S&G 6.1's footing (<= 0: inside)",
    outside(sg.lb, sg.ub, q_sg),
    0.0,
    passed=outside(sg.lb, sg.ub, q_sg) <= 0.0,
)

# %% [markdown]
# ## Monotone, reproducible, free of E and ν
#
# Along every adaptive sequence above the reported lower bound must not fall and the upper bound must not
# rise. Each reported bound is the better of the solver's field and the previous mesh's field carried over
# (still admissible on the nested mesh); the count of steps where the solver's own optimum was worse than
# the previous mesh's is printed — in exact arithmetic there would be none. A rerun gives bit-identical
# bounds. E and ν appear nowhere in the input of `ssi.limit`, so the bounds cannot depend on them.

# %%
runs = list(prandtl_runs.values()) + [davis, ngamma, surch, sg]
mono = all(r.monotone for r in runs)
setbacks = sum(r.solver_setbacks for r in runs)
steps = sum(len(r.history) - 1 for r in runs)
site0 = strip_site(B, Material(C, 20.0), Interface("smooth"))
mesh0 = triangulate(site0, 1.0, size=graded(1.0, 0.25, 0.3))
a, b = bracket(site0, mesh0), bracket(site0, mesh0)
identical = (a.lb, a.ub) == (b.lb, b.ub)
print(f"monotone on all {len(runs)} sequences ({steps} refinements): {mono}; solver setbacks: {setbacks}")
print(f"rerun bit-identical: {identical}")
report.check(
    "fela_monotone",
    f"refinement steps with a falling LB or rising UB over {len(runs)} adaptive sequences "
    f"(and reruns bit-identical: {identical})",
    0 if mono else 1,
    0,
    passed=mono and identical,
)

# %% [markdown]
# ## A factor of safety by strength reduction
#
# Chapter 10's footing (c = 10 kPa, φ = 20°) under a mean pressure of 100 kPa: the largest F for which
# c/F, tan φ/F still carry it, bracketed by bisection on each bound (a coarse mesh: the bracket is as wide
# as that mesh's bounds).

# %%
site_f = strip_site(B, Material(C, 20.0), Interface("rough"), load_ref=(0.0, -100e3 * B / 2))
mesh_f = triangulate(site_f, 1.0, size=graded(1.0, 0.25 if FAST else 0.12, 0.3))
t0 = time.perf_counter()
f_lb, f_ub, trials = safety_factor(site_f, mesh_f, rel_tol=3e-2 if FAST else 3e-3)
print(f"F in [{f_lb:.3f}, {f_ub:.3f}] ({len(trials)} bound solves, {time.perf_counter() - t0:.1f} s)")
assert f_lb < f_ub

# %% [markdown]
# ### A slope's own factor of safety, and a vertical cut
#
# `strength_reduction` scales every load together (the weight included) when it tests a factor F: F is
# safe exactly when the reduced site carries λ_all ≥ 1, both conic programs stay bounded, and a slope under
# its weight alone needs no load to scale. Each bound is read by what it proves: a certified λ_LB ≥ 1
# proves F safe, a kinematically admissible field whose loads out-work its dissipation (the optimum, or the
# ray of an unbounded program) proves F unsafe; anything else (an infeasible program) proves nothing.
#
# - A 2:1 slope on a rough base at its toe (D = 1), φ = 20°, c/(γH) = 0.05, dry: Bishop & Morgenstern's
#   charts give F = 1.380, Griffiths & Lane's elastic-plastic strength reduction (ψ = 0) F = 1.40. Neither
#   is a bound of the associated collapse factor (each method differs from it by about 1 %), so the claim
#   is that the certified bracket overlaps [1.38, 1.40] (`fos_slope_2to1`, value ≤ 0: the relative distance
#   of the range from the bracket). A tight bracket must exclude 1.40: at a 0.5 % gap F_U = 1.392.
# - A vertical cut in Tresca soil: γH/c at collapse lies in [3.772, 3.776] (Pastor, Thai & Francescato
#   2003, rigorous bounds); for φ = 0, F* = N_s c/(γH) exactly, so any rigorous bracket meets that range
#   with no tolerance (`fos_vertical_cut`).

# %%
from ssi.limit import strength_reduction  # noqa: E402


def slope_site(H=10.0, c_ratio=0.05, phi=20.0, gamma=20e3, n=2.0, back=3.0):
    """A 1:n slope of height H on a rough rigid base at the toe's level, the ground behind the crest to
    (n + back) H (a vertical roller there)."""
    L = (n + back) * H
    pts = [(0.0, 0.0), (L, 0.0), (L, H), (n * H, H)]
    top = Boundary("free")
    segs = ((0, 1, Boundary("fixed")), (1, 2, Boundary("symmetry")), (2, 3, top), (3, 0, top))
    return Site(
        np.array(pts, float), segs, ((L - 1.0, 0.5 * H, 0),), (Material(c_ratio * gamma * H, phi, gamma),)
    )


def cut_site(H=5.0, c=40e3, gamma=20e3):
    """A vertical cut of height H in Tresca soil, the soil below the toe to depth H (a rough base)."""
    W, L, D = 1.5 * H, 2.5 * H, 1.0 * H
    pts = [(-W, -D), (L, -D), (L, H), (0.0, H), (0.0, 0.0), (-W, 0.0)]
    free = Boundary("free")
    segs = ((0, 1, Boundary("fixed")), (1, 2, Boundary("symmetry")), (2, 3, free), (3, 4, free))
    segs += ((4, 5, free), (5, 0, Boundary("symmetry")))
    return Site(np.array(pts, float), segs, ((L - 0.5, 0.0, 0),), (Material(c, 0.0, gamma),))


def graded_to(points, h_min, slope=0.3):
    pts = np.asarray(points, float)
    return lambda p: (
        h_min
        + slope * np.min(np.hypot(p[:, None, 0] - pts[None, :, 0], p[:, None, 1] - pts[None, :, 1]), axis=1)
    )


GAP_FOS = 0.05 if FAST else 0.01  # fast mode: a wider bracket, still certified
t0 = time.perf_counter()
site_s = slope_site()
mesh_s = triangulate(site_s, 2.5, size=graded_to([(0.0, 0.0), (20.0, 10.0)], 1.0 if FAST else 0.6))
fos_s = strength_reduction(site_s, mesh_s, gap=GAP_FOS)
print("2:1 slope:", fos_s.summary(), f"({time.perf_counter() - t0:.1f} s)")
report.check(
    "fos_slope_2to1",
    "relative distance of Bishop-Morgenstern/Griffiths-Lane F = 1.38..1.40 from the certified strength-"
    "reduction bracket of a 2:1 slope, phi = 20, c/(gamma H) = 0.05 (<= 0: they overlap)",
    max(fos_s.f_lower / 1.40 - 1.0, 1.0 - fos_s.f_upper / 1.38),
    0.0,
    passed=fos_s.f_lower <= 1.40 and fos_s.f_upper >= 1.38 and fos_s.converged,
)
H_CUT, C_CUT, G_CUT = 5.0, 40e3, 20e3
r_cut = C_CUT / (G_CUT * H_CUT)
t0 = time.perf_counter()
site_c = cut_site(H_CUT, C_CUT, G_CUT)
h_cut = H_CUT / (12.0 if FAST else 25.0)
mesh_c = triangulate(site_c, H_CUT / 2.0, size=graded_to([(0.0, 0.0), (0.0, H_CUT)], h_cut))
fos_c = strength_reduction(site_c, mesh_c, gap=0.08 if FAST else 0.01)
ns = (fos_c.f_lower / r_cut, fos_c.f_upper / r_cut)
print(
    f"vertical cut: gamma H / c in [{ns[0]:.4f}, {ns[1]:.4f}]",
    fos_c.summary(),
    f"({time.perf_counter() - t0:.1f} s)",
)
report.check(
    "fos_vertical_cut",
    "relative distance of Pastor et al.'s stability number gamma H/c = 3.772..3.776 from the certified "
    "strength-reduction bracket of a vertical Tresca cut (<= 0: contained or overlapping)",
    max(ns[0] / 3.776 - 1.0, 1.0 - ns[1] / 3.772),
    0.0,
    passed=ns[0] <= 3.776 * (1 + 1e-6) and ns[1] >= 3.772 * (1 - 1e-6) and fos_c.converged,
)

# %% [markdown]
# ### The verdict of a run
#
# `ssi run` ends with a verdict (`ssi.scene.verdict`): the capacity bracket of the run's own loads, the
# margin λ as the Davis bracket, and one sentence. A 2 m strip bonded to Tresca clay (s_u = 20 kPa) under a
# 400 kN/m column: Prandtl's (2 + π) s_u B = 205.7 kN/m (hand value) is about half the load, λ* = 0.514, so
# the scene must say "does not carry its loads" with a bracket containing 0.514 (`verdict_overloaded`).
# Its incremental run on the default mesh peaks above the associated upper bound (a displacement mesh is
# too stiff at collapse): the verdict flags a limit above 1.03 × UB_assoc with its excess
# (`limit_vs_bracket_flagged`).

# %%
from ssi.elements.section import homogeneous  # noqa: E402
from ssi.io.cli import summary as run_summary  # noqa: E402
from ssi.scene import ColumnLoad, Contact, Foundation, SoilLayer  # noqa: E402
from ssi.scene.verdict import verdict, verdict_lines  # noqa: E402

S_U, B_V, N_V = 20e3, 2.0, 400e3
lam_prandtl = (2.0 + math.pi) * S_U * B_V / N_V
over = Scene(
    width=12.0,
    depth=5.0,
    layers=[SoilLayer(5.0, E=30e6, nu=0.3, c=S_U, phi_deg=0.0, psi_deg=0.0)],
    foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)),
    contact=Contact(kn=1e10, kt=1e9),
    loads=[ColumnLoad(0.0, N=N_V)],
)
t0 = time.perf_counter()
res_over = over.build().solve(n_steps=8)
v_over = verdict(run_summary(res_over, None), over, gap=0.05)
print("\n".join(verdict_lines(v_over)), f"\n({time.perf_counter() - t0:.1f} s)")
b_over = v_over["capacity"]
report.check(
    "verdict_overloaded",
    "Davis upper bound of the load factor of a strip loaded at 1.95 x Prandtl's (2+pi) s_u B; the verdict "
    "must read 'does not carry its loads' and its bracket contain the hand value 0.514 (passes when < 1)",
    b_over["ub_davis"],
    1.0,
    passed=v_over["carries"] is False
    and v_over["line"].startswith("does not carry its loads")
    and b_over["lb_davis"] * (1 - 1e-6) <= lam_prandtl <= b_over["ub_davis"] * (1 + 1e-6),
)
lim = v_over["incremental_limit"]
report.check(
    "limit_vs_bracket_flagged",
    "excess of the overloaded strip's incremental limit load factor over its associated upper bound (a "
    "ceiling for any psi <= phi), flagged in the verdict when above 3 %",
    lim["excess"],
    0.03,
    passed=(lim["value"] > 1.03 * lim["ub_assoc"]) == bool(lim["flag"])
    and bool(lim["flag"])
    and any("above the associated upper bound" in f for f in v_over["flags"]),
)

# %% [markdown]
# ## Verification
#
# The report rows above assert their conditions; here the lower bounds' certificates and the upper bounds'
# flow-rule residuals of the last meshes, and the gap identity (the element shares sum to UB − LB).

# %%
for name, r in [("prandtl rough 20", assoc), ("davis", davis), ("N_gamma", ngamma), ("S&G", sg)]:
    f = r.final
    print(
        f"{name:18s} LB certified: {f.lower.certified} ({f.lower.reason}); UB flow residual "
        f"{f.upper.flow_residual:.1e}; identity error {f.identity_error:.1e}"
    )
    assert f.lower.certified
    assert f.upper.flow_residual < 1e-6  # relative to the velocity scale: solver tolerance 1e-9
    assert f.identity_error < 1e-6  # round-off of two fields that each satisfy their constraints

# %% [markdown]
# ## Figures

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for (phi, kind), res in prandtl_runs.items():
    n = [r["n_el"] for r in res.history]
    ex = prandtl(C, phi)
    (line,) = axes[0].semilogx(
        n, [r["best_ub"] / ex for r in res.history], "-o", ms=3, label=f"φ={phi:g} {kind}"
    )
    axes[0].semilogx(n, [r["best_lb"] / ex for r in res.history], "--o", ms=3, color=line.get_color())
axes[0].axhline(1.0, color="k", lw=0.8)
axes[0].set_xlabel("triangles")
axes[0].set_ylabel("bound / Prandtl")
axes[0].legend(fontsize=8)
axes[1].loglog([r["n_el"] for r in hist], [r["t_lb"] for r in hist], "-o", label="lower bound")
axes[1].loglog([r["n_el"] for r in hist], [r["t_ub"] for r in hist], "-s", label="upper bound")
axes[1].set_xlabel("triangles")
axes[1].set_ylabel("solve time [s]")
axes[1].legend()
report.save_figure(fig, "fig17_1_bounds_and_time")
plt.show()

# %% [markdown]
# *Figure 17.1 — Left: upper (solid) and lower (dashed) bounds over Prandtl's exact pressure along the
# adaptive sequences. Right: solve time of each bound against the number of triangles (rough φ = 20°).*

# %%
fin = assoc.final
m = fin.mesh
fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
speed = np.hypot(*fin.upper.velocity[: len(m.xy)].T)
tp = axes[0].tripcolor(m.xy[:, 0], m.xy[:, 1], m.tri, speed, shading="gouraud", cmap="viridis")
axes[0].triplot(m.xy[:, 0], m.xy[:, 1], m.tri, lw=0.1, color="w")
fig.colorbar(tp, ax=axes[0], label="|velocity| (unit reference power)")
dens = np.maximum(fin.upper.dissipation, 1e-30) / m.areas()
tp = axes[1].tripcolor(
    m.xy[:, 0], m.xy[:, 1], m.tri, facecolors=np.log10(dens / dens.max() + 1e-12), cmap="magma"
)
tp.set_clim(-4, 0)
fig.colorbar(tp, ax=axes[1], label="log10 dissipation density / max")
for ax in axes:
    ax.set_aspect("equal")
    ax.set_xlim(0, 6)
    ax.set_ylim(-5, 0)
report.save_figure(fig, "fig17_2_mechanism")
plt.show()

# %% [markdown]
# *Figure 17.2 — The upper-bound mechanism of the rough φ = 20° footing on its last adaptive mesh: speed
# (left) and where the dissipation happens (right); the refinement follows the fan and the wedge edges.*
#
# ## Summary
#
# - Both bounds are one conic program each on the same Triangle mesh; the lower bound is certified from
#   its projected field (never from the solver's status), the upper bound recomputed from its velocities.
# - Prandtl (rough/smooth, φ = 0 and 20°), Prandtl–Reissner, Martin's N_γ, sliding and program 6.1 each lie
#   inside their bracket on every mesh; adaptivity on each element's share of the gap reaches 2 % (1 % on
#   request, N_γ 3 %), with the numbers printed above.
# - Nested bisection makes the sequence monotone; the carried fields make it so even where the interior-point
#   solver reports success short of the optimum.
# - A footing rotates (the upper bound's rigid motion (U, W, θ), the lower bound's moment equation): an
#   eccentric load's bracket lies above Meyerhof's rigorous V_M, the bonded strip's moment capacity is
#   pinned between the certified lower bound and the 0.690 s_u B² scoop.
# - A footing bends (a `Beam`: rigid elements, hinges of M_p at every base node, the moment bounded at the
#   Bernstein points): chapter 11's RC strip bridging a trench brackets the hand four-point-bending
#   mechanism load M_p/(l/2 − a) (`fela_beam_mechanism`). With the hinges' M–N polygon from the section
#   analysis, an end compression raises and a tension lowers the bracket, each meeting M_p(−P)/(l/2 − a)
#   (`fela_beam_mn`); a Coulomb joint's tension cut-off brackets a pull-out N + t_i B (`fela_cutoff`).
# - An embedded strip: its side soil as the overburden γD at the base level (Terzaghi's strengthless
#   backfill, chapter 12's) brackets γD N_q (`fela_embedded`), a rigorous floor for any backfill; modelled
#   with its strength, the trench walls under their geostatic stress, it carries at least that
#   (`fela_embedded_side_soil`).
# - For ψ < φ the associated bracket is a ceiling and the Davis bracket the conventional value; chapter 10's
#   ψ = 0 incremental limit on its coarsest mesh lies above every associated upper bound here: a mesh
#   overestimate, not a capacity.
#
# References: Sloan (2013) Géotechnique 63(7); Makrodimopoulos & Martin (2006) IJNME 66, (2007) IJNAMG 31;
# Lyamin & Sloan (2002); Krabbenhøft et al. (2012); Davis (1968); Drescher & Detournay (1993); Martin (2005);
# Radenković (1961); Meyerhof (1953) on the effective width; Bransby & Randolph (1998) on the scoop mechanism
# (its least value 0.690 s_u B² derived above); Heyman (1971) on beam mechanisms; EN 1992-1-1 §3.1.7 (3) (the
# rectangular stress block); Rivara (1984) on longest-edge bisection; Goulart & Chen (2024) Clarabel; Shewchuk
# (1996) Triangle.
