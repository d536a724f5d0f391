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
# # 8. A reinforced-concrete beam: the nonlinear layered strip (Figs. 11–12)
#
# Paper §9.2 (Test 2, Monnier's beam), with the laws of §5 (chapter 03) in the layered strip of §4
# (chapter 02), solved by the incremental–iterative scheme of §8.
#
# In this chapter you will
#
# * build the beam the paper describes — layered strip, 11 layers, smeared bar layers — and redraw Fig. 11
#   from the model actually run;
# * check the strip against the exact Timoshenko deflection in the linear range;
# * build an independent reference for the cracked beam: a strain-compatibility section analysis with the
#   same laws, integrated along the span (curvature integral), and watch the FE converge to it;
# * compare with a measured beam (the substitute for Monnier's, which is unavailable), without tuning;
# * measure the mesh sensitivity with and without tying the crack band to the element, and the trade of
#   layers × elements × load steps against error and wall time.
#
# ## What is compared with what
#
# Monnier's geometry, materials and measurements are not available (reference-data.md, trust D): the slot
# `reference_data/monnier1970_fig12.csv` is kept empty and documented, and is plotted as soon as someone
# adds the points. The model actually run is the beam of **Janney, Hognestad & McHenry (1956)** (trust C):
# simply supported, four-point bending, $b\times h$ = 152.4 × 304.8 mm, span 2.7432 m, loads at the third
# points, $A_s$ = 600 mm² at $d$ = 210.8 mm, $f_c$ = 36.2 MPa, $f_y$ = 333 MPa (non-hardening).
#
# **Designer values only** (no fitting to the curve): from $f_c$ the *fib* Model Code 2010 gives
# $E_0$, $f_r$, $G_f$ (`ssi.materials.rc.designer_concrete`); $\varepsilon_c = 2f_c/E_0$ (the smallest peak
# strain for which (5.1) stays below its initial tangent), $\varepsilon_{cu}$ = 0.0035; bars $E_s$ = 200 GPa,
# $f_y$ = 333 MPa, $E_H$ = 0 as reported; the open defaults of paper-notes §3 ($\alpha_{ts}$ = 0.5,
# $\beta_0$ = 0.25, $\nu$ = 0.2, $\kappa_s$ = 5/6). Self-weight is left out (the measured moment starts at 0).
#
# **The beam's width.** The strip works per unit width. The bar layer gets the equivalent thickness
# $A_s/b$; forces and moments per beam are $b$ times the strip's values (exact for a prismatic beam).
#
# **Crack band.** Eq. (5.4) needs a band width $l_s$. The paper takes the element size; for a strip
# integration point the natural reading is the length the point represents, $w_p L_e/2$
# (`PlateStrip(crack_band="point")`). A reinforced beam, however, does not crack in one band: the bars
# force a crack every $s_{rm}$ along the span, and below yield the section's $M(\kappa)$ keeps rising, so
# nothing localises. Then the energy a band dissipates per unit length should be $G_f/s_{rm}$, not $G_f/L_e$.
# We measure both rules below; the model used for the comparisons takes the designer's mean crack spacing
# (EC2 eq. 7.11, `ssi.rc_beam.janney_crack_spacing`) as $l_s$.
#
# **Curvature-integral reference.** For a statically determinate beam, virtual work gives the mid-span
# deflection without any element:
# $\delta=\int\kappa(M(x))\,\bar m(x)\,dx+\int\gamma(x)\,\bar v(x)\,dx$, with $\kappa(M)$ from the section
# analysis (plane sections, $N$ = 0, the same layers and laws, histories committed step by step) and
# $\gamma=V/S$ with the section's cracked shear stiffness $S$. It holds while $M(\kappa)$ rises, i.e. until
# the bars yield (with $E_H$ = 0 the section's moment then stalls and deformation can localise).
#
# | paper / text | code | meaning |
# |---|---|---|
# | $b$, $h$, $L$, $a$ | `JANNEY["b"]`, `["h"]`, `["span"]`, `["a"]` | width, depth, span, shear span |
# | $A_s$, $d$ | `JANNEY["As"]`, `["d"]` | bar area, effective depth |
# | $l_s$ | `ls`, `crack_band` | crack band width (eq. 5.4) |
# | $\kappa$, $M$ | `mc.kap`, `mc.M` | section curvature and moment (per unit width) |
# | $P$, $\delta$ | `out["P"]`, `out["delta"]` | load per load point, mid-span deflection |

# %%
import itertools
import time

import matplotlib.pyplot as plt
import numpy as np

from ssi import paths, report
from ssi import rc_beam as rb
from ssi import section_analysis as sa
from ssi.materials.layer_laws import STEEL
from ssi.solver import Settings

t_start = time.perf_counter()
FAST = paths.FAST
G = rb.JANNEY
B, SPAN, A = G["b"], G["span"], G["a"]
KNM = B / 1e3                 # per-width N m/m  ->  kN m per beam
S_RM = rb.janney_crack_spacing()
_, _, DES = rb.janney_materials()
print({k: f"{v:.4g}" for k, v in DES.items()}, f"s_rm = {S_RM:.3f} m")

ref_notes, _, JAN = rb.read_reference_csv("janney1956_beam.csv")
mon_notes, _, MON = rb.read_reference_csv("monnier1970_fig12.csv")

# discretisations (fast mode: coarse, for CI)
N_LAYERS = 41                                  # main model; the trade study below justifies it
SELF = "tangent"                               # PlateStrip self-bending option of the main model (see trade)
N_EL = 2 if FAST else 4                        # elements per region (shear span, half middle third)
N_STEPS = 40 if FAST else 100
W_LOAD = 0.036                                 # load-point travel [m]: mid-span deflection passes 42 mm
SETTINGS = Settings(max_iter=3000)             # modified Newton (paper): slow but sure past yield

# %% [markdown]
# ## The model actually run (Fig. 11)

# %%
section = rb.janney_section(N_LAYERS, ls=S_RM)
beam = rb.build_four_point(section, SPAN, A, N_EL, N_EL, crack_band=None, self_bending=SELF)
print(f"{section.n_layer} layers (steel layer(s) {list(np.flatnonzero(section.kind == STEEL) + 1)} "
      f"from the bottom), {beam.group.n_el} elements in the half beam, {beam.model.n_dof} DOFs")

fig, ax = plt.subplots(1, 3, figsize=(15, 3.6), gridspec_kw={"width_ratios": [2.2, 2.2, 1]})
a0 = ax[0]
a0.add_patch(plt.Rectangle((0, 0), SPAN, G["h"], fc="0.9", ec="k"))
a0.plot([0, SPAN], [G["h"] - G["d"]] * 2, "r-", lw=2, label=r"3 No. 5 bars, $A_s$ = 600 mm$^2$")
for x in (0, SPAN):
    a0.plot([x - 0.05, x, x + 0.05, x - 0.05], [-0.08, 0, -0.08, -0.08], "k-")
for x in (A, SPAN - A):
    a0.annotate("", (x, G["h"]), (x, G["h"] + 0.25), arrowprops={"arrowstyle": "->", "lw": 2})
    a0.text(x, G["h"] + 0.27, "P", ha="center")
a0.set(xlim=(-0.2, SPAN + 0.2), ylim=(-0.2, 0.7), aspect="equal", xlabel="x [m]", ylabel="z [m]",
       title="(A) geometry: span 2.743 m, loads at the third points")
a0.legend(loc="lower center", fontsize=8, bbox_to_anchor=(0.5, -0.02))
a1 = ax[1]
xe = beam.x_ends
a1.plot(beam.model.coords[:, 0], np.zeros(beam.model.n_nodes), "o", ms=3, c="C0", label="nodes")
a1.vlines(xe, -0.05, 0.05, colors="k", lw=1)
a1.plot([0], [0], "k^", ms=10, label="support: w = 0")
a1.plot([SPAN / 2], [0], "ks", ms=8, mfc="none", label=r"symmetry: u = $\alpha$ = 0")
a1.annotate("", (A, 0.02), (A, 0.3), arrowprops={"arrowstyle": "->", "lw": 2, "color": "C3"})
a1.text(A, 0.32, "prescribed w (displacement control)", ha="center", color="C3", fontsize=8)
a1.set(xlim=(-0.1, SPAN / 2 + 0.1), ylim=(-0.3, 0.45), xlabel="x [m]", yticks=[],
       title=f"(B) half model: {beam.group.n_el} three-node strip elements")
a1.legend(loc="lower center", fontsize=7, ncol=3)
a2 = ax[2]
zb = section.z_bottom
bottoms = np.concatenate([[0.0], np.cumsum(section.h)[:-1]])
for n in range(section.n_layer):
    steel = section.kind[n] == STEEL
    a2.add_patch(plt.Rectangle((0, bottoms[n]), B, section.h[n], fc="C3" if steel else "0.85", ec="k",
                               lw=0.6))
    if steel or section.n_layer <= 15 or (n + 1) % 5 == 0 or n == 0:
        a2.text(B * 1.05, bottoms[n] + section.h[n] / 2, f"{n + 1}" + (" (steel)" if steel else ""),
                va="center", fontsize=7, color="C3" if steel else "k")
a2.set(xlim=(-0.02, 0.3), ylim=(-0.01, G["h"] + 0.01), aspect="equal", xlabel="width [m]",
       ylabel="height above the bottom face [m]", title="(C) layers (bars smeared, As/b)")
fig.tight_layout()
report.save_figure(fig, "fig11_rc_beam_model")
plt.show()

# %% [markdown]
# **Figure 8.1** (the paper's Fig. 11, redrawn for the beam actually run). (A) Geometry and loading of the
# substitute beam. (B) The discretisation: half beam by symmetry, a node at the load point, which is driven
# downwards (displacement control). (C) The layered section: concrete layers spread over the depth in
# proportion to the gaps, the bars as one smeared layer of thickness $A_s/b$ (the paper's beam had bars top
# and bottom, in layers 2 and 10 of 11; this beam has bottom bars only).
#
# ## Linear range: the exact Timoshenko deflection

# %%
lin_sec = rb.janney_section(N_LAYERS, elastic=True)
k_el = lin_sec.elastic_resultant_stiffness()
lin_beam = rb.build_four_point(lin_sec, SPAN, A, N_EL, N_EL, crack_band=None)
c_fe = rb.linear_compliance(lin_beam)
c_exact = sa.four_point_deflection_elastic(1.0, SPAN, A, k_el["D_na"], k_el["S"])
err_linear = abs(c_fe / c_exact - 1)
# the K0 model of the nonlinear section is the same linear beam (initial moduli E0, G; Es, no bar shear)
c_k0 = rb.linear_compliance(rb.build_four_point(rb.janney_section(N_LAYERS, ls=S_RM), SPAN, A, N_EL, N_EL,
                                                crack_band=None))
print(f"linear FE {c_fe:.9e} m per N/m, Timoshenko {c_exact:.9e}, relative error {err_linear:.1e}")

# %% [markdown]
# ## The independent reference: section analysis and curvature integral

# %%
# the convergence study uses the paper's 11 layers and the strip's default self-bending; the section
# analysis mirrors both (it is the same discrete section, integrated exactly along the span)
conv_section = rb.janney_section(11, ls=S_RM)
mc = sa.moment_curvature(conv_section, 0.02, 1000 if FAST else 3000, self_bending="initial")
M_Y = mc.M[mc.first_yield - 1]
print(f"section analysis: cracking M = {mc.M[np.argmax(np.diff(mc.S) < 0)] * KNM:.2f} kN m, "
      f"first yield M_y = {M_Y * KNM:.2f} kN m per beam")

conv_meshes = (1, 2, 4) if FAST else (1, 2, 4, 8, 16)
conv = {}
for n in conv_meshes:
    b_n = rb.build_four_point(conv_section, SPAN, A, n, n, crack_band=None, self_bending="initial")
    out = rb.load_path(b_n, 0.009, 30 if FAST else 80, SETTINGS)
    ok = (out["M"] < M_Y) & (out["P"] > 0)
    ref = sa.four_point_deflection(mc, out["P"][ok], SPAN, A)
    conv[n] = {"delta": out["delta"][ok], "err": np.abs(out["delta"][ok] / ref - 1), "M": out["M"][ok]}
    print(f"{2 * n:3d} elements: max relative deflection error before yield {conv[n]['err'].max():.2e}")
err_ci = [conv[n]["err"].max() for n in conv_meshes]
rate = np.polyfit(np.log(conv_meshes), np.log(err_ci), 1)[0]
print(f"observed convergence rate in the element count: {-rate:.2f}")

# %% [markdown]
# ## The nonlinear beam against the measurements

# %%
main = rb.load_path(beam, W_LOAD, N_STEPS, SETTINGS)
d_fe, m_fe = main["delta"] * 1e3, main["M"] * KNM
print(f"main run: {N_STEPS} steps, {main['iterations'].sum()} iterations, {main['wall_time']:.1f} s")

# the paper's rule: band = the length each point represents, on the same mesh
paper_rule = rb.load_path(rb.build_four_point(rb.janney_section(N_LAYERS, ls=S_RM), SPAN, A, N_EL, N_EL,
                                              crack_band="point", self_bending=SELF), W_LOAD, N_STEPS,
                          Settings(max_iter=3000, max_cuts=2), allow_partial=True)


def moment_at(d_mm, delta_mm, m_knm):
    return np.interp(d_mm, delta_mm, m_knm)


def reading_tolerance(i):
    """Relative moment tolerance of data row i: +-1 kN m plus +-0.5 mm times the steeper adjacent slope."""
    slopes = [abs((JAN[j + 1, 1] - JAN[j, 1]) / (JAN[j + 1, 0] - JAN[j, 0])) for j in (i - 1, i)
              if 0 <= j < len(JAN) - 1]
    return (JAN[i, 3] + JAN[i, 2] * max(slopes)) / JAN[i, 1]


i_y = int(np.flatnonzero(JAN[:, 0] == 11.5)[0])
i_last = len(JAN) - 1
err_y = abs(moment_at(JAN[i_y, 0], d_fe, m_fe) / JAN[i_y, 1] - 1)
err_last = abs(moment_at(JAN[i_last, 0], d_fe, m_fe) / JAN[i_last, 1] - 1)
tol_y, tol_last = reading_tolerance(i_y), reading_tolerance(i_last)
print(f"yield (11.5 mm): FE {moment_at(11.5, d_fe, m_fe):.2f} vs {JAN[i_y, 1]} kN m, error {err_y:.1%} "
      f"(tolerance {tol_y:.1%}); last (42 mm): FE {moment_at(42, d_fe, m_fe):.2f} vs {JAN[i_last, 1]}, "
      f"error {err_last:.1%} (tolerance {tol_last:.1%})")
d_pr, m_pr = paper_rule["delta"] * 1e3, paper_rule["M"] * KNM
print(f"paper's band rule on the same mesh: {moment_at(11.5, d_pr, m_pr):.2f} kN m at 11.5 mm; run reached "
      f"{d_pr[-1]:.1f} mm" + ("" if paper_rule["failure"] is None else
                              f" and stopped ({paper_rule['failure']['reason']})"))

# %% [markdown]
# ## Mesh sensitivity: the band tied to the element, or to the crack spacing

# %%
MESHES = (2, 3, 4, 6) if FAST else (2, 4, 8, 16)
N_MESH_LAYERS = 11         # the layer error (~1 %, trade study) is common to all meshes; the spread is not
mesh_runs = {}
for rule in ("point", "spacing"):
    for n in MESHES:
        b_n = rb.build_four_point(rb.janney_section(N_MESH_LAYERS, ls=S_RM), SPAN, A, n, n,
                                  crack_band="point" if rule == "point" else None, self_bending=SELF)
        out = rb.load_path(b_n, W_LOAD, 30 if FAST else 60, Settings(max_iter=3000, max_cuts=2), allow_partial=True)
        mesh_runs[rule, n] = (out["delta"] * 1e3, out["M"] * KNM, out["wall_time"])
        if out["failure"] is not None:
            print(f"band = {rule}, {2 * n} elements: stopped at delta = {out['delta'][-1] * 1e3:.1f} mm "
                  f"({out['failure']['reason']})")


def reached(rule):
    """The largest deflection [mm] every mesh of this band rule reached (at most 42 mm, the data's last)."""
    return min(42.0, min(mesh_runs[rule, n][0][-1] for n in MESHES))


def spread(rule):
    # after cracking (the cracking moment is reached below 1 mm), up to the last point every mesh reached
    d_end = reached(rule)
    d_grid = np.linspace(2.0, d_end, 81)
    curves = np.array([moment_at(d_grid, *mesh_runs[rule, n][:2]) for n in MESHES])
    return float(np.max((curves.max(0) - curves.min(0)) / curves.mean(0)))


spread_spacing, spread_point = spread("spacing"), spread("point")
SPREAD_BOUND = 1.0 / 37.0      # the data's reading uncertainty (1 kN m at the yield moment)
print(f"spread of M over {len(MESHES)} meshes: band = crack spacing {spread_spacing:.2%} (delta 2-"
      f"{reached('spacing'):.1f} mm), band = point length {spread_point:.2%} "
      f"(delta 2-{reached('point'):.1f} mm); bound {SPREAD_BOUND:.1%}")

# %% [markdown]
# ## The trade: layers × elements × load steps against error and wall time

# %%
# one factor at a time around a base: layers with the base mesh and steps; elements and steps with the
# reference's 41 layers (so that the layer error does not hide theirs)
base = {"layers": 11, "n_el": 2 if FAST else 4, "steps": 30 if FAST else 60, "self": "tangent"}
ref_cfg = {"layers": 41, "n_el": 4 if FAST else 8, "steps": 60 if FAST else 120, "self": "tangent"}
LAYER_SET = (11, 41) if FAST else (5, 11, 21, 41)
variants = ([("layers", v) for v in LAYER_SET]
            + [("layers, self-bending e0", v) for v in LAYER_SET]
            + [("n_el", v) for v in ((1,) if FAST else (1, 2, 4))]
            + [("steps", v) for v in ((15,) if FAST else (30, 60, 120))])


def run_cfg(cfg):
    b_n = rb.build_four_point(rb.janney_section(cfg["layers"], ls=S_RM), SPAN, A, cfg["n_el"], cfg["n_el"],
                              crack_band=None, self_bending=cfg["self"])
    out = rb.load_path(b_n, W_LOAD, cfg["steps"], SETTINGS)
    return moment_at(np.array([11.5, 42.0]), out["delta"] * 1e3, out["M"] * KNM), out["wall_time"]


m_ref, t_ref = run_cfg(ref_cfg)
trade = []
for key, value in variants:
    if key.startswith("layers"):
        cfg = dict(base, layers=value, self="initial" if key.startswith("layers,") else "tangent")
    else:
        cfg = dict(base, layers=41, **{key: value})
    m_v, t_v = run_cfg(cfg)
    trade.append((key, value, float(np.max(np.abs(m_v / m_ref - 1))), t_v))
    print(f"{key:24s} = {value:3d}: error vs reference {trade[-1][2]:.2e}, wall time {t_v:.2f} s")
print(f"reference (41 layers, {2 * ref_cfg['n_el']} elements, {ref_cfg['steps']} steps): {t_ref:.2f} s")

# %% [markdown]
# **What the trade shows.** Through-thickness layering dominates the error, and how each layer's own bending
# term $e\,h_n^3/12\,\kappa$ is evaluated matters more than anything else: with the strip's default (the layer's
# *initial* modulus, exact for elastic layers) a cracked or crushed layer keeps its full elastic bending
# stiffness, an error that grows with the curvature — about 20 % of the moment at 42 mm with the paper's 11
# layers, still about 1 % with 41. With the layer's *tangent* modulus (`self_bending="tangent"`) 11 layers
# are within about 1 % and 41 within 0.02 %. Elements and load steps matter far less once a node sits at the
# load point (the moment is piecewise linear and the strip integrates it well). Hence the main model:
# 41 layers, tangent self-bending.
#
# ## Verification

# %%
TOL_LINEAR = 1e-6         # the strip is exact for this load case; only round-off of the solve remains
TOL_CI = 5e-3 if FAST else 2e-3   # discretisation error of the finest mesh (8 / 32 elements), rate ~2 measured

assert err_linear <= TOL_LINEAR, err_linear
assert abs(c_k0 / c_exact - 1) < 0.05          # the K0 model is the same beam up to the concrete's nu = 0.2 in G
report.record("fig12_linear", "relative error of the linear FE mid-span deflection vs Timoshenko",
              err_linear, TOL_LINEAR, err_linear <= TOL_LINEAR)

assert all(e2 < e1 for e1, e2 in itertools.pairwise(err_ci)), err_ci
assert -rate > 1.5, rate
assert err_ci[-1] <= TOL_CI, err_ci
report.record("fig12_curvature_integral",
              f"max relative deflection error of the FE ({2 * conv_meshes[-1]} elements) vs the curvature "
              "integral, up to first yield", err_ci[-1], TOL_CI, err_ci[-1] <= TOL_CI)

passed_sub = err_y <= tol_y and err_last <= tol_last
worst = max((err_y, tol_y), (err_last, tol_last), key=lambda p: p[0] / p[1])
report.record("fig12_substitute_beam",
              f"relative moment error vs Janney et al. 1956 (C): at yield {err_y:.4f} (tol {tol_y:.4f}), "
              f"at the last point {err_last:.4f} (tol {tol_last:.4f}); value/tolerance = the worse of the two",
              worst[0], worst[1], passed_sub)

report.record("fig12_mesh_spread",
              f"max relative spread of M over meshes {MESHES} elements per region, band = crack spacing, "
              f"delta 2-{reached('spacing'):.1f} mm (every mesh reached it; band = point length: "
              f"{spread_point:.4f} up to {reached('point'):.1f} mm)", spread_spacing, SPREAD_BOUND,
              spread_spacing <= SPREAD_BOUND)
assert spread_spacing <= SPREAD_BOUND

if len(MON):
    report.record_empty("fig12_monnier", f"{len(MON)} measured points present; Monnier's geometry and materials "
                        "still missing from the chapter, so no comparison yet")
else:
    report.record_empty("fig12_monnier", "Monnier (1970) measurements: empty slot reference_data/monnier1970_fig12.csv")
print("linear", err_linear, "| curvature integral", err_ci, "| substitute", err_y, err_last, "| spread",
      spread_spacing, spread_point)

# %% [markdown]
# ## Fig. 12 and its error figures

# %%
fig, ax = plt.subplots(figsize=(7.5, 5))
ax.errorbar(JAN[:, 0], JAN[:, 1], xerr=JAN[:, 2], yerr=JAN[:, 3], fmt="ko", ms=4, capsize=2,
            label="measured, Janney et al. 1956 (C)")
d_lin = np.array([0.0, 12.0])
ax.plot(d_lin, d_lin / 1e3 / (c_k0 * 1.0) * A * KNM, "k:", label="linear FE (K0)")
ax.plot(d_fe, m_fe, "C0-", lw=2, label=f"nonlinear FE, band = crack spacing {S_RM:.2f} m")
ax.plot(d_pr, m_pr, "C1--", label="nonlinear FE, band = point length (paper's rule)")
p_ref = np.linspace(0, M_Y * 0.999, 60) / A
ax.plot(sa.four_point_deflection(mc, p_ref, SPAN, A) * 1e3, p_ref * A * KNM, "C2-.", lw=1.5,
        label="curvature integral (to first yield)")
if len(MON):
    ax.plot(MON[:, 0], MON[:, 1], "rs", label="Monnier 1970 (load in kN)")
else:
    ax.text(20, 8, "Monnier (1970) measurements: empty slot\nreference_data/monnier1970_fig12.csv",
            fontsize=8, color="0.4")
ax.set(xlabel="mid-span deflection [mm]", ylabel="mid-span moment per beam [kN m]", xlim=(0, 45), ylim=(0, 55))
ax.legend(fontsize=8, loc="upper left")
report.save_figure(fig, "fig12_rc_beam")
plt.show()

# %% [markdown]
# **Figure 8.2** (the paper's Fig. 12 for the substitute beam). Mid-span moment against deflection: the
# measured points with their reading uncertainty, the linear FE, the nonlinear layered strip with the two
# crack-band rules, and the independent curvature-integral reference up to first yield.

# %%
fig, ax = plt.subplots(1, 3, figsize=(15, 4))
for n in conv_meshes:
    ax[0].semilogy(conv[n]["delta"][1:] * 1e3, conv[n]["err"][1:], label=f"{2 * n} elements")
ax[0].set(xlabel="mid-span deflection [mm]", ylabel="|FE / curvature integral - 1|",
          title="(a) FE vs curvature integral, before yield")
ax[0].legend(fontsize=8)
for n in MESHES:
    ax[1].plot(*mesh_runs["spacing", n][:2], "-", label=f"{2 * n} el., band = spacing")
    ax[1].plot(*mesh_runs["point", n][:2], "--", label=f"{2 * n} el., band = point length")
ax[1].errorbar(JAN[:, 0], JAN[:, 1], yerr=JAN[:, 3], fmt="ko", ms=3)
ax[1].set(xlabel="mid-span deflection [mm]", ylabel="M per beam [kN m]", xlim=(0, 45),
          title="(b) mesh sensitivity")
ax[1].legend(fontsize=6, ncol=2)
for key, mk in (("layers", "o"), ("layers, self-bending e0", "x"), ("n_el", "s"), ("steps", "^")):
    rows = [r for r in trade if r[0] == key]
    ax[2].loglog([r[3] for r in rows], [max(r[2], 1e-6) for r in rows], mk + "-", label=key)
    for r in rows:
        ax[2].annotate(str(r[1]), (r[3], max(r[2], 1e-6)), fontsize=7)
ax[2].set(xlabel="wall time [s]", ylabel="max relative error of M at 11.5 and 42 mm",
          title="(c) trade vs 41 layers, fine mesh, fine steps")
ax[2].legend(fontsize=8)
fig.tight_layout()
report.save_figure(fig, "fig12_rc_beam_errors")
plt.show()

# %% [markdown]
# **Figure 8.3** Error figures of Fig. 12. (a) Relative deflection error of the layered strip against the
# curvature integral up to first yield, for increasing meshes. (b) Load–deflection over four meshes with
# the band tied to the crack spacing (solid) and to the length each point represents (dashed). (c) Error
# against wall time when one of layers / elements per region / load steps is varied around the base model
# (labels: the varied value).
#
# ## Summary
#
# * Linear range: the layered strip reproduces the Timoshenko deflection to round-off (row `fig12_linear`).
# * Before yield the strip converges to the independent curvature integral (row `fig12_curvature_integral`).
# * Against the substitute beam (designer values only) see row `fig12_substitute_beam`: the strip is a
#   little stiffer than the measurement in the cracked range, meets the moment at yield within the reading
#   uncertainty, but stays flat after yield ($E_H$ = 0, as the data's summary reports the bars) while the
#   measured moment keeps rising to 41.5 kN m at 42 mm — a gap (about 8 %) the model cannot close without
#   inventing a hardening modulus, which we do not do.
# * A band tied to the element makes the *reinforced* beam mesh-dependent (distributed cracking does not
#   localise before yield); a band equal to the crack spacing removes that (row `fig12_mesh_spread`).
# * Monnier's measurements remain an empty slot (row `fig12_monnier`).

# %%
print(f"chapter 08 ran in {time.perf_counter() - t_start:.1f} s")
