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
# $\beta_0$ = 0.25, $\nu$ = 0.2, $\kappa_s$ = 5/6). Self-weight is left out of the main model (the measured
# moment starts at 0; its effect is measured below).
#
# **The beam's width.** The strip works per unit width. The bar layer gets the equivalent thickness
# $A_s/b$; forces and moments per beam are $b$ times the strip's values (exact for a prismatic beam).
#
# **Crack band.** Eq. (5.4) needs a band width $l_s$. The paper takes the element size; for a strip
# integration point the natural reading is the length the point represents, $w_p L_e/2$
# (`PlateStrip(crack_band="point")`). A reinforced beam, however, does not crack in one band: the bars
# force a crack every $s_{rm}$ along the span, and below yield the section's $M(\kappa)$ keeps rising, so
# nothing localises. Then the energy a band dissipates per unit length should be $G_f/s_r$, not $G_f/L_e$.
# We measure both rules below; the model used for the comparisons — and the default of every scene's
# `Foundation` — takes the maximum crack spacing of stabilised cracking of the *fib* Model Code 2010
# (§7.6.4.4, eq. 7.6-4 with $k$ = 1 and $\tau_{bms}$ = 1.8 $f_{ctm}$ for short-term loading) as $l_s$:
#
# $$s_{r,max}=2\Bigl(c+\frac{\phi}{7.2\,\rho_{s,ef}}\Bigr),\qquad \rho_{s,ef}=\frac{A_s}{b\,h_{c,ef}},\qquad
#   h_{c,ef}=\min\bigl(2.5(h-d),\ (h-x)/3,\ h/2\bigr),$$
#
# $c$ the clear cover, $\phi$ the bar diameter, $x$ the cracked elastic neutral-axis depth
# (`ssi.materials.rc.crack_spacing_mc2010`, `ssi.elements.section.with_crack_spacing_band`). The same band
# width regularises crushing (compressive fracture energy $G_c$, chapter 03). For this beam $h_{c,ef}$ = 75 mm
# ($(h-x)/3$ governs) and $s_{r,max}$ = 0.256 m.
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

from ssi.elements import section_analysis as sa
from ssi.lab import paths, report
from ssi.lab import rc_beam as rb
from ssi.lab.digitize import read_reference
from ssi.lab.verify import convergence_rate
from ssi.materials.layer_laws import STEEL
from ssi.solver import Settings

t_start = time.perf_counter()
FAST = paths.FAST
G = rb.JANNEY
B, SPAN, A = G["b"], G["span"], G["a"]
KNM = B / 1e3  # per-width N m/m  ->  kN m per beam
S_RM = rb.janney_crack_spacing()  # MC2010 s_r,max, the scene default band
_, _, DES = rb.janney_materials()
print({k: f"{v:.4g}" for k, v in DES.items()}, f"s_rm = {S_RM:.3f} m")

# the reference tables as (n, 4) arrays in their column order: delta, M or F, and the two uncertainties
JAN = np.column_stack(list(read_reference("janney1956_beam.csv")[1].values()))
MON = np.column_stack(list(read_reference("monnier1970_fig12.csv")[1].values()))

# discretisations (fast mode: coarse, for CI)
N_LAYERS = 41  # main model; the trade study below justifies it
SELF = "chord"  # the strip's default self-bending (chapter 02, Fig. 2.6)
N_EL = 2 if FAST else 4  # elements per region (shear span, half middle third)
N_STEPS = 40 if FAST else 100
W_LOAD = 0.036  # load-point travel [m]: mid-span deflection passes 42 mm
# displacement control in the given steps, past the peak of the load: load control (prescribed
# displacement; the default controlled path ends where the reaction peaks), BFGS on K0, a large iteration cap
SETTINGS = Settings(control="load", max_iter=3000)

# %% [markdown]
# ## The model actually run (Fig. 11)

# %%
section = rb.janney_band_section(N_LAYERS)
beam = rb.build_four_point(section, SPAN, A, N_EL, N_EL, crack_band=None, self_bending=SELF)
print(
    f"{section.n_layer} layers (steel layer(s) {list(np.flatnonzero(section.kind == STEEL) + 1)} "
    f"from the bottom), {beam.group.n_el} elements in the half beam, {beam.model.n_dof} DOFs"
)

fig, ax = plt.subplots(1, 3, figsize=(15, 3.6), gridspec_kw={"width_ratios": [2.2, 2.2, 1]})
a0 = ax[0]
a0.add_patch(plt.Rectangle((0, 0), SPAN, G["h"], fc="0.9", ec="k"))
a0.plot([0, SPAN], [G["h"] - G["d"]] * 2, "r-", lw=2, label=r"3 No. 5 bars, $A_s$ = 600 mm$^2$")
for x in (0, SPAN):
    a0.plot([x - 0.05, x, x + 0.05, x - 0.05], [-0.08, 0, -0.08, -0.08], "k-")
for x in (A, SPAN - A):
    a0.annotate("", (x, G["h"]), (x, G["h"] + 0.25), arrowprops={"arrowstyle": "->", "lw": 2})
    a0.text(x, G["h"] + 0.27, "P", ha="center")
a0.set(
    xlim=(-0.2, SPAN + 0.2),
    ylim=(-0.2, 0.7),
    aspect="equal",
    xlabel="x [m]",
    ylabel="z [m]",
    title="(A) geometry: span 2.743 m, loads at the third points",
)
a0.legend(loc="lower center", fontsize=8, bbox_to_anchor=(0.5, -0.02))
a1 = ax[1]
xe = beam.x_ends
a1.plot(beam.model.coords[:, 0], np.zeros(beam.model.n_nodes), "o", ms=3, c="C0", label="nodes")
a1.vlines(xe, -0.05, 0.05, colors="k", lw=1)
a1.plot([0], [0], "k^", ms=10, label="support: w = 0")
a1.plot([SPAN / 2], [0], "ks", ms=8, mfc="none", label=r"symmetry: u = $\alpha$ = 0")
a1.annotate("", (A, 0.02), (A, 0.3), arrowprops={"arrowstyle": "->", "lw": 2, "color": "C3"})
a1.text(A, 0.32, "prescribed w (displacement control)", ha="center", color="C3", fontsize=8)
a1.set(
    xlim=(-0.1, SPAN / 2 + 0.1),
    ylim=(-0.3, 0.45),
    xlabel="x [m]",
    yticks=[],
    title=f"(B) half model: {beam.group.n_el} three-node strip elements",
)
a1.legend(loc="lower center", fontsize=7, ncol=3)
a2 = ax[2]
zb = section.z_bottom
bottoms = np.concatenate([[0.0], np.cumsum(section.h)[:-1]])
for n in range(section.n_layer):
    steel = section.kind[n] == STEEL
    a2.add_patch(
        plt.Rectangle((0, bottoms[n]), B, section.h[n], fc="C3" if steel else "0.85", ec="k", lw=0.6)
    )
    if steel or section.n_layer <= 15 or (n + 1) % 5 == 0 or n == 0:
        a2.text(
            B * 1.05,
            bottoms[n] + section.h[n] / 2,
            f"{n + 1}" + (" (steel)" if steel else ""),
            va="center",
            fontsize=7,
            color="C3" if steel else "k",
        )
a2.set(
    xlim=(-0.02, 0.3),
    ylim=(-0.01, G["h"] + 0.01),
    aspect="equal",
    xlabel="width [m]",
    ylabel="height above the bottom face [m]",
    title="(C) layers (bars smeared, As/b)",
)
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
c_k0 = rb.linear_compliance(
    rb.build_four_point(rb.janney_band_section(N_LAYERS), SPAN, A, N_EL, N_EL, crack_band=None)
)
print(f"linear FE {c_fe:.9e} m per N/m, Timoshenko {c_exact:.9e}, relative error {err_linear:.1e}")

# %% [markdown]
# ## The independent reference: section analysis and curvature integral

# %%
# (i) element convergence: the FE against the curvature integral of the *same discrete section* (21 layers,
# initial-modulus self-bending: its M(kap) rises monotonically up to yield, which the integral needs; with the
# paper's 11 layers the cracking of the 28 mm cover layer makes M dip at 0.0014 1/m and kap(M) is not
# single-valued)
conv_section = rb.janney_band_section(21)
mc = sa.moment_curvature(conv_section, 0.02, 1000 if FAST else 3000, self_bending="initial")
M_Y = mc.M[mc.first_yield - 1]
print(
    f"section analysis: cracking M = {mc.M[np.argmax(np.diff(mc.S) < 0)] * KNM:.2f} kN m, "
    f"first yield M_y = {M_Y * KNM:.2f} kN m per beam"
)

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
rate = convergence_rate(conv_meshes, err_ci)
print(f"observed convergence rate in the element count: {-rate:.2f}")

# (ii) the layer-free reference: kap(M) from adaptive quadrature of the continuous stress profile (no layers,
# no self-bending term; chapter 02), integrated along the span, against the main model's discretisation
# (N_LAYERS layers, default self-bending) on the finest convergence mesh
LF_KAPS = np.concatenate([[0.0], np.geomspace(2e-5, 0.016, 70 if FAST else 200)])
mc_free = sa.layer_free_moment_curvature(section, LF_KAPS)
M_Y_FREE = mc_free.M[mc_free.first_yield - 1]
assert mc_free.monotone == len(LF_KAPS), "the layer-free M(kap) must rise up to 0.016 1/m"
b_free = rb.build_four_point(section, SPAN, A, conv_meshes[-1], conv_meshes[-1], crack_band=None)
out_free = rb.load_path(b_free, 0.009, 30 if FAST else 80, SETTINGS)
ok = (out_free["M"] < M_Y_FREE) & (out_free["P"] > 0)
err_free = np.abs(out_free["delta"][ok] / sa.four_point_deflection(mc_free, out_free["P"][ok], SPAN, A) - 1)
print(
    f"{N_LAYERS} layers, {2 * conv_meshes[-1]} elements vs the layer-free curvature integral: max relative "
    f"deflection error before yield {err_free.max():.2e}"
)

# (iii) the layer count: M of the discrete section (default self-bending) against the layer-free M, from
# cracking to four times the yield curvature
LC_KAPS = np.geomspace(1e-3, 0.06, 12)
lc_ref = sa.layer_free_moment_curvature(section, np.concatenate([[0.0], LC_KAPS])).M[1:]
layer_count_err = {}
for n_lay in (11, 21, 41):
    mc_n = sa.moment_curvature(rb.janney_band_section(n_lay), 0.06, 2000)
    layer_count_err[n_lay] = float(np.max(np.abs(np.interp(LC_KAPS, mc_n.kap, mc_n.M) / lc_ref - 1)))
print("max |M/M_ref - 1| for kap 1e-3..0.06 by layers:", {k: f"{v:.2e}" for k, v in layer_count_err.items()})

# %% [markdown]
# ## The nonlinear beam against the measurements

# %%
main = rb.load_path(beam, W_LOAD, N_STEPS, SETTINGS)
d_fe, m_fe = main["delta"] * 1e3, main["M"] * KNM
print(f"main run: {N_STEPS} steps, {main['iterations'].sum()} iterations, {main['wall_time']:.1f} s")

# the paper's rule: band = the length each point represents, on the same mesh
paper_rule = rb.load_path(
    rb.build_four_point(rb.janney_band_section(N_LAYERS), SPAN, A, N_EL, N_EL, crack_band="point"),
    W_LOAD,
    N_STEPS,
    SETTINGS,
    allow_partial=True,
)
# tension stiffening only in the effective tension area around the bars (chapter 03), same model otherwise
ts_area = rb.load_path(
    rb.build_four_point(
        rb.janney_band_section(N_LAYERS, "effective_area"), SPAN, A, N_EL, N_EL, crack_band=None
    ),
    W_LOAD,
    N_STEPS,
    SETTINGS,
)


def moment_at(d_mm, delta_mm, m_knm):
    return np.interp(d_mm, delta_mm, m_knm)


def reading_tolerance(i):
    """Relative moment tolerance of data row i: +-1 kN m plus +-0.5 mm times the steeper adjacent slope."""
    slopes = [
        abs((JAN[j + 1, 1] - JAN[j, 1]) / (JAN[j + 1, 0] - JAN[j, 0]))
        for j in (i - 1, i)
        if 0 <= j < len(JAN) - 1
    ]
    return (JAN[i, 3] + JAN[i, 2] * max(slopes)) / JAN[i, 1]


POINTS = np.arange(1, len(JAN))  # the ten measured points (row 0 is the origin)
TOL_POINTS = np.array([reading_tolerance(i) for i in POINTS])


def point_errors(out):
    """Signed relative moment error M_FE / M_measured - 1 at each measured deflection (NaN beyond the run)."""
    d, m = out["delta"] * 1e3, out["M"] * KNM
    return np.where(JAN[POINTS, 0] <= d[-1], moment_at(JAN[POINTS, 0], d, m) / JAN[POINTS, 1] - 1, np.nan)


err_all = point_errors(main)
err_area = point_errors(ts_area)
print(" delta [mm]   measured   tolerance   error (TS all layers)   error (TS effective area)")
for k, i in enumerate(POINTS):
    print(
        f"{JAN[i, 0]:8.1f} {JAN[i, 1]:10.1f} {TOL_POINTS[k]:10.1%} {err_all[k]:+16.1%} {err_area[k]:+22.1%}"
    )
worst_k = int(np.nanargmax(np.abs(err_all) / TOL_POINTS))
worst_area_k = int(np.nanargmax(np.abs(err_area) / TOL_POINTS))
d_pr, m_pr = paper_rule["delta"] * 1e3, paper_rule["M"] * KNM
post = d_pr > 11.5
print(
    f"paper's band rule on the same mesh: {moment_at(11.5, d_pr, m_pr):.2f} kN m at 11.5 mm; run reached "
    f"{d_pr[-1]:.1f} mm"
    + ("" if paper_rule["failure"] is None else f" and stopped ({paper_rule['failure']['reason']})")
    + f"; smallest moment after yield {m_pr[post].min():.2f} kN m"
    if post.any()
    else ""
)

# %% [markdown]
# **Every measured point, and what the model lacks.** The table scores all ten points (full mode, 41 layers,
# 8 elements, 100 steps; the printout above is the current mode's run). Tension stiffening on every cracked
# layer: +75, +31, +13, +6.2, +6.6, +1.8, +0.3, −1.7, −4.7, −7.5 % at 1, 2.5, 5, 7.5, 10, 11.5, 15, 20, 30 and
# 42 mm (before this chapter's defaults changed: +77, +32, +13, +6, +7, +1.8, +0.3, −1.7, −4.8, −7.6 %). Four
# points fall outside their reading tolerance, in two groups with two different causes:
#
# * *Cracking, 1–2.5 mm* (+75 % against 67 %, +31 % against 24 %). At 1 mm the measured beam carries 6 kN m,
#   40 % of what the uncracked beam would (15 kN m); it is already cracked at a moment well below the model's
#   cracking moment (7.8 kN m, from the MC2010 $f_{ctm}$ = 2.78 MPa). What the model lacks here is whatever
#   lowered the tensile capacity of the real beam before and during the test — shrinkage restraint by the bars
#   and drying microcracks — and the bond slip that lets the bars pull out of the concrete between cracks.
#   Limiting tension stiffening to the effective tension area around the bars (chapter 03) is the
#   one change the codes support: it brings 2.5 mm from +31 to +26 % and 5 mm from +13 to +7 %, but not
#   within 24 % at 2.5 mm; it is shown beside the default and not adopted (both are scored in the row's text).
# * *After yield, 30–42 mm* (−4.7 % against 2.7 %, −7.5 % against 2.5 %). With $E_H$ = 0 (the data's summary
#   calls the bars non-hardening) the model's moment rises only by the growing lever arm, 37.7 → 38.3 kN m
#   (+2 %) from 11.5 to 42 mm, while the measurement rises 37 → 41.5 kN m (+12 %). The missing mechanism is
#   strain hardening of the bars past their yield plateau (and any confinement of the crushing zone); we do
#   not invent a hardening modulus to close it.
#
# **The paper's band rule.** With the band equal to the length each point represents (≈ 0.11 m on the full
# mesh), a point cracks with about twice the energy per unit volume of the spacing band, so the cracked
# branch is stiffer still (+64 % at 2.5 mm). Its collapse after 17 mm in the former version (from ≈ 40 to
# ≈ 5 kN m) came from crushing: at $\varepsilon_{cu}$ the top layers dropped from 0.9 $f_c$ to zero at once,
# the compression zone of the one element at mid-span lost its resultant, and deformation localised there.
# With crushing regularised (chapter 03) the curve stays on the plateau (smallest moment after yield
# 38.5 kN m, full mode); it stops at 41 mm when modified Newton exhausts its 3000 iterations in one step,
# which the figure shows as the end of the curve.

# %% [markdown]
# ## Where the over-stiffness of the cracked branch comes from: one measurement per source
#
# The model is +75, +31 and +13 % too stiff at 1, 2.5 and 5 mm (full mode). Each candidate source is switched
# alone around the main model (41 layers, band = crack spacing, tension stiffening on every cracked layer) on
# a short path to 5.5 mm at the load point, and the change of the moment at the three measured points of the
# cracked branch is measured (1, 2.5 and 5 mm: the data's own points, so 2.5 rather than 3 mm). Nothing is
# fitted to the beam; where a source needs an input the data do not report, the input is a stated assumption.
#
# * **(a) Shear stiffness kept after cracking.** The Mindlin strip keeps $\beta_0 G$ = 0.25 $G$ in a cracked
#   layer (Fig. 6). Run with $\beta_0$ = 0.001 (the floor): the largest effect this source can have.
# * **(b) Tension stiffening.** Run with $\alpha_{ts}$ = 0 (off), and with stiffening only in the effective
#   tension area $h_{c,ef}$ (the code rule of chapter 03).
# * **(c) Pre-cracking by shrinkage.** Bonded bars restrain the concrete's shrinkage, which puts the
#   concrete around them in tension before the test. $\varepsilon_{cs}$ by EN 1992-1-1 §3.1.4 / Annex B.2
#   (`rc_beam.shrinkage_strain_en1992`) with **assumed** conditions (not reported): cement class N, curing
#   7 days, test at 28 days, RH 50 %; the restraint stress from the uncracked transformed section
#   (`rc_beam.shrinkage_restraint_stress`, short-term $\alpha_e$ = $E_s/E_0$, the same section as the
#   shrinkage curvature $1/r_{cs}=\varepsilon_{cs}\alpha_e S/I$ of EN 1992-1-1 §7.4.3), and the concrete
#   layers then crack at $f_r-\sigma_{cs}(z)$ (`rc_beam.with_shrinkage_restraint`; the bars' small
#   pre-compression is not carried over). The shrinkage curvature itself happened before the gauges were
#   zeroed and is not part of the measured deflection.
# * **(c') Self-weight.** The measured moment starts at 0 after the beam carries its own weight
#   (25 kN/m³, EN 1991-1-1 Table A.1: 1.16 kN/m, 1.09 kN m at mid-span), so the real beam cracked at a smaller
#   *applied* moment. The strip carries the weight first, then its load point is driven from there and
#   load and deflection are counted from that state (`rc_beam.load_path(..., self_weight=q)`); checked with
#   the curvature integral from the self-weight state (`rc_beam.four_point_deflection_after_self_weight`).
# * **(d) Bond slip.** Not modelled: the bars are perfectly bonded to their layer; the smeared tension
#   stiffening law (b) is the model's only stand-in for the slip between cracks. Slip lowers the stress the
#   bond carries into the concrete between cracks, so its largest possible effect is that of no bond
#   transfer at all — tension stiffening switched off, (b) — which bounds it without a bond-slip law.

# %%
D_SRC = np.array([1.0, 2.5, 5.0])  # the measured points of the cracked branch [mm]
N_EL_SRC = 2 if FAST else 4
SRC_STEPS = 22 if FAST else 44
UNIT_WEIGHT_RC = 25e3  # N/m^3, EN 1991-1-1 Table A.1, reinforced normal-weight concrete
SHRINK_ASSUMED = {"t_days": 28.0, "ts_days": 7.0, "rh": 0.5, "cement": "N"}  # not reported: assumed
H0 = 2 * B * G["h"] / (2 * (B + G["h"]))  # notional size 2 Ac / u of the beam [m]
shrink = rb.shrinkage_strain_en1992(G["fc"], H0, **SHRINK_ASSUMED)
sig_cs, kap_cs = rb.shrinkage_restraint_stress(section, shrink["eps_cs"])


def source_moments(sec, q=0.0):
    """Mid-span moment [kN m] at D_SRC of the strip (N_EL_SRC + N_EL_SRC elements) with section ``sec``,
    driven from the state under the self-weight ``q`` [N/m per unit width] when q > 0."""
    b_s = rb.build_four_point(sec, SPAN, A, N_EL_SRC, N_EL_SRC, crack_band=None, self_bending=SELF)
    out = rb.load_path(b_s, 0.0055, SRC_STEPS, SETTINGS, self_weight=q)
    assert out["delta"][-1] * 1e3 >= D_SRC[-1], "the short path must pass the last point"
    return moment_at(D_SRC, out["delta"] * 1e3, out["M"] * KNM)


Q_SW = UNIT_WEIGHT_RC * G["h"]  # self-weight per unit length and unit width [N/m per m]
m_src0 = source_moments(section)
sources = {
    "(a) shear retention beta0 0.25 -> 0.001": source_moments(rb.janney_band_section(N_LAYERS, beta0=1e-3)),
    "(b) tension stiffening off": source_moments(rb.janney_band_section(N_LAYERS, alpha_ts=0.0)),
    "(b) tension stiffening in h_c,ef only": source_moments(
        rb.janney_band_section(N_LAYERS, "effective_area")
    ),
    "(c) shrinkage restraint (EN 1992)": source_moments(
        rb.with_shrinkage_restraint(section, shrink["eps_cs"])[0]
    ),
    "(c') self-weight (strip, from its state)": source_moments(section, Q_SW),
}
change = {k: m / m_src0 - 1 for k, m in sources.items()}
m_all = source_moments(
    rb.with_shrinkage_restraint(rb.janney_band_section(N_LAYERS, "effective_area"), shrink["eps_cs"])[0], Q_SW
)
change["(b h_c,ef) + (c) + (c') together (strip)"] = m_all / m_src0 - 1

# (c') checked by the independent curvature integral (21 layers): moments at D_SRC from P(delta)
P_GRID = np.linspace(1e-3, 0.95 * M_Y / A, 300)


def integral_moments(mc_s, q):
    d_mm = rb.four_point_deflection_after_self_weight(mc_s, P_GRID, q, SPAN, A) * 1e3
    ok = np.isfinite(d_mm)  # NaN once P a + the self-weight moment leaves the monotone branch
    assert d_mm[ok][-1] > D_SRC[-1]
    return moment_at(D_SRC, d_mm[ok], P_GRID[ok] * A * KNM)


change["(c') self-weight (curvature integral)"] = integral_moments(mc, Q_SW) / integral_moments(mc, 0.0) - 1
m_measured = np.interp(D_SRC, JAN[:, 0], JAN[:, 1])  # D_SRC are measured points: no interpolation
err_src0 = m_src0 / m_measured - 1
print(
    f"eps_cs = {shrink['eps_cs']:.3e} (drying {shrink['eps_cd']:.3e}, autogenous {shrink['eps_ca']:.3e}); "
    f"restraint stress at the bottom layer {sig_cs[0] / 1e6:.2f} MPa of fr = {DES['fr'] / 1e6:.2f} MPa; "
    f"1/r_cs = {kap_cs:.2e} 1/m; self-weight moment {Q_SW * SPAN**2 / 8 * KNM:.2f} kN m"
)
print(f"{'source':46s}" + "".join(f"{d:>9.1f} mm" for d in D_SRC))
print(f"{'main model: error vs measured':46s}" + "".join(f"{e:+12.1%}" for e in err_src0))
for k, c in change.items():
    print(f"{k:46s}" + "".join(f"{v:+12.1%}" for v in c))
remaining = m_all / m_measured - 1
LEFT = "error left with (b h_c,ef) + (c) + (c')"
print(f"{LEFT:46s}" + "".join(f"{e:+12.1%}" for e in remaining))
inside = np.abs(remaining) <= TOL_POINTS[: len(D_SRC)]  # D_SRC are the first three measured points
print("inside the reading tolerance with the three estimated sources:", dict(zip(D_SRC, inside, strict=True)))
# the claims of the table below: the shear source is negligible (< 1 %), shrinkage and self-weight each
# lower the cracked branch at every point, and with all three the model is still stiffer at 1 mm
assert np.all(np.abs(change["(a) shear retention beta0 0.25 -> 0.001"]) < 0.01)
assert np.all(change["(c) shrinkage restraint (EN 1992)"] < 0)
assert np.all(change["(c') self-weight (strip, from its state)"] < 0)
# the strip and the curvature integral agree on the self-weight's effect within 1.5 % of the moment (the
# integral's 21-layer section, initial self-bending and no element error; measured 0.9 % at 1 mm)
assert np.allclose(
    change["(c') self-weight (strip, from its state)"],
    change["(c') self-weight (curvature integral)"],
    atol=0.015,
)
assert 0 < remaining[0] < err_src0[0]

# %% [markdown]
# **What each source is worth** (full mode; the printout above is the current mode's run). Change of the
# mid-span moment at a given deflection, each source alone against the main model:
#
# | source | how measured | 1 mm | 2.5 mm | 5 mm |
# |---|---|---|---|---|
# | main model against the measurement | strip, 8 elements, 41 layers | +76.7 % | +30.9 % | +13.2 % |
# | (a) shear stiffness kept after cracking | strip with $\beta_0$ 0.25 → 0.001 | −0.0 % | −0.1 % | −0.1 % |
# | (b) tension stiffening switched off | strip with $\alpha_{ts}$ = 0 | +0.0 % | −17.6 % | −11.7 % |
# | (b) tension stiffening in $h_{c,ef}$ only | strip, code rule of chapter 03 | +0.0 % | −4.0 % | −5.3 % |
# | (c) shrinkage restraint, 196 µε | strip cracking at $f_r-\sigma_{cs}$ | −12.0 % | −7.9 % | −3.8 % |
# | (c') self-weight, 1.09 kN m | strip driven from its self-weight state | −9.0 % | −5.9 % | −4.0 % |
# | (c') the same, checked | curvature integral from the self-weight state | −9.0 % | −5.9 % | −4.0 % |
# | (d) bond slip | bounded by (b) off: no bond transfer between cracks | ≥ +0.0 % | ≥ −17.6 % | ≥ −11.7 % |
# | (b, $h_{c,ef}$) + (c) + (c') together | strip with all three | −19.8 % | −14.8 % | −11.4 % |
# | error left with the three together | the same strip against the measurement | +41.7 % | +11.4 % | +0.3 % |
#
# The reading tolerances at these points are 67, 24 and 11 %.
#
# * **Shear (a) is not a source.** Cutting the shear stiffness a cracked layer retains by a factor 250
#   changes the moment by at most 0.1 %: the Mindlin strip's shear stiffness after cracking does not make
#   this beam stiff.
# * **At 1 mm, tension stiffening (b) is not a source either**: the model is barely cracked there (its
#   cracking moment 7.8 kN m is above the measured 6 kN m at 1 mm). Its +77 % is a cracking-onset error: the
#   real beam cracked earlier. Shrinkage restraint (c) and self-weight (c') are the two measured causes of
#   that, −12 % and −9 % each.
# * **At 2.5–5 mm**, where the beam is cracked, tension stiffening is the largest lever; the code's
#   effective-area rule takes 4–5 % off, switching it off altogether 12–18 %.
# * **Together** the three standard models leave +42, +11 and +0.3 %, inside the reading tolerance of each
#   point. This
#   is not adopted as the model's default and the row below still scores the main model: the shrinkage
#   estimate rests on curing, age and humidity that the data do not report (assumed: 7 days, 28 days,
#   RH 50 %); with RH 80 % $\varepsilon_{cs}$ would be 123 instead of 196 µε. In a scene, self-weight is the
#   user's `StripWeight` load (a load, not a model); shrinkage is not modelled in the product.
# * **The effective-area rule** is a standard model with no fitted parameter (the same $h_{c,ef}$ the default
#   crack spacing is derived from), and on this beam it is better in the cracked range and equal after yield
#   (full mode, all ten points: +75, +26, +7.2, +2.4, +4.3, −0.1, −0.7, −2.2, −4.9, −7.6 %). It was tried as
#   the scene default (`Foundation(tension_stiffening="effective_area")`) and measured on the other chapters
#   once (fast mode, after commit fa58c0b): chapter 11's foundation beam then stopped in `NonConvergence` at
#   λ = 0.50 on the default solver (the concrete outside $h_{c,ef}$ softens to zero over a band near the
#   snap-back limit, and the load-controlled path cannot follow the strip's snap-through), and two light
#   sections of chapter 18's grid carried less than their cracking moment at four times the cracking
#   deflection (0.91 and 0.93 $M_{cr}$; more than $M_{cr}$ at eight times). A default that stops an ordinary
#   scene is worse than 4–6 % of over-stiffness, so the rule stays one setting away until the controlled path
#   (chapter 06) carries such scenes.
# * **What is left** at 1 mm (+42 %, inside the tolerance only because that tolerance is wide) is not bond
#   slip (d): at 1 mm the model is still uncracked and slip, bounded by (b) off, changes nothing there. It
#   is the spread of the concrete's real tensile strength about the MC2010 mean (the beam cracked below the
#   model's 7.8 kN m), which this test does not report and so cannot be measured here.

# %% [markdown]
# ## Mesh sensitivity: the band tied to the element, or to the crack spacing

# %%
MESHES = (2, 3, 4, 6) if FAST else (2, 4, 8, 16)
N_MESH_LAYERS = 11  # the layer error (~1 %, trade study) is common to all meshes; the spread is not
# the solver is given explicitly (the paper's modified Newton with a high iteration cap and the default step
# cuts), so the study does not depend on the solver's defaults
MESH_SETTINGS = SETTINGS
mesh_runs = {}
for rule in ("point", "spacing"):
    for n in MESHES:
        # the scene defaults: Foundation(crack_band="spacing", self_bending="chord"), 11 layers
        b_n = rb.build_four_point(
            rb.janney_band_section(N_MESH_LAYERS),
            SPAN,
            A,
            n,
            n,
            crack_band="point" if rule == "point" else None,
        )
        out = rb.load_path(b_n, W_LOAD, 30 if FAST else 60, MESH_SETTINGS, allow_partial=True)
        mesh_runs[rule, n] = (out["delta"] * 1e3, out["M"] * KNM, out["wall_time"])
        if out["failure"] is not None:
            print(
                f"band = {rule}, {2 * n} elements: stopped at delta = {out['delta'][-1] * 1e3:.1f} mm "
                f"({out['failure']['reason']})"
            )


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
SPREAD_BOUND = 0.03  # the bar, about the data's reading uncertainty (1 kN m at 37 kN m)
print(
    f"spread of M over {len(MESHES)} meshes: band = crack spacing {spread_spacing:.2%} (delta 2-"
    f"{reached('spacing'):.1f} mm), band = point length {spread_point:.2%} "
    f"(delta 2-{reached('point'):.1f} mm); bound {SPREAD_BOUND:.1%}"
)

# %% [markdown]
# ## The trade: layers × elements × load steps against error and wall time

# %%
# one factor at a time around a base: layers with the base mesh and steps; elements and steps with the
# reference's 41 layers (so that the layer error does not hide theirs)
base = {"layers": 11, "n_el": 2 if FAST else 4, "steps": 30 if FAST else 60, "self": SELF}
ref_cfg = {"layers": 41, "n_el": 4 if FAST else 8, "steps": 60 if FAST else 120, "self": SELF}
LAYER_SET = (11, 41) if FAST else (5, 11, 21, 41)
variants = (
    [("layers", v) for v in LAYER_SET]
    + [("layers, self-bending e0", v) for v in LAYER_SET]
    + [("n_el", v) for v in ((1,) if FAST else (1, 2, 4))]
    + [("steps", v) for v in ((15,) if FAST else (30, 60, 120))]
)


def run_cfg(cfg):
    b_n = rb.build_four_point(
        rb.janney_band_section(cfg["layers"]),
        SPAN,
        A,
        cfg["n_el"],
        cfg["n_el"],
        crack_band=None,
        self_bending=cfg["self"],
    )
    out = rb.load_path(b_n, W_LOAD, cfg["steps"], MESH_SETTINGS)
    return moment_at(np.array([11.5, 42.0]), out["delta"] * 1e3, out["M"] * KNM), out["wall_time"]


m_ref, t_ref = run_cfg(ref_cfg)
trade = []
for key, value in variants:
    if key.startswith("layers"):
        cfg = dict(base, layers=value, self="initial" if key.startswith("layers,") else SELF)
    else:
        cfg = dict(base, layers=41, **{key: value})
    m_v, t_v = run_cfg(cfg)
    trade.append((key, value, float(np.max(np.abs(m_v / m_ref - 1))), t_v))
    print(f"{key:24s} = {value:3d}: error vs reference {trade[-1][2]:.2e}, wall time {t_v:.2f} s")
print(f"reference (41 layers, {2 * ref_cfg['n_el']} elements, {ref_cfg['steps']} steps): {t_ref:.2f} s")

# %% [markdown]
# **What the trade shows.** Through-thickness layering dominates the error, and how each layer's own bending
# term $e\,h_n^3/12\,\kappa$ is evaluated matters more than anything else: with the strip's former default
# (the layer's *initial* modulus, exact for elastic layers) a cracked or crushed layer keeps its full elastic
# bending stiffness, an error that grows with the curvature — about 20 % of the moment at 42 mm with the
# paper's 11 layers, still about 1 % with 41. With the chord through the stresses at each layer's faces (the
# default `self_bending="chord"`, chapter 02) 11 layers are within about 1 % and 41 within 0.1 % of the
# layer-free section (row `fig12_layer_count`). Elements and load steps matter far less once a node sits at
# the load point (the moment is piecewise linear and the strip integrates it well). Hence the main model:
# 41 layers, chord self-bending.
#
# ## Verification

# %%
TOL_LINEAR = 1e-6  # the strip is exact for this load case; only round-off of the solve remains
TOL_CI = 5e-3 if FAST else 2e-3  # discretisation error of the finest mesh (8 / 32 elements), rate ~2 measured

assert abs(c_k0 / c_exact - 1) < 0.05  # the K0 model is the same beam up to the concrete's nu = 0.2 in G
report.check(
    "fig12_linear",
    "relative error of the linear FE mid-span deflection vs Timoshenko",
    err_linear,
    TOL_LINEAR,
    err_linear <= TOL_LINEAR,
)

assert all(e2 < e1 for e1, e2 in itertools.pairwise(err_ci)), err_ci
assert -rate > 1.5, rate
assert err_ci[-1] <= TOL_CI, err_ci
# against the layer-free reference the FE error is the mesh error above plus the layer rule's (41 layers,
# chord self-bending: <= 1.8e-3 of M, row fig12_layer_count) plus the linear interpolation of kap(M) between
# the reference's curvatures: budget 5e-3 in both modes (measured in full mode: 2.8e-3 with 8 + 8 elements,
# 2.6e-3 with 16 + 16, the plateau being the layer and table error)
TOL_LF = 5e-3
err_lf = float(err_free.max())
report.check(
    "fig12_curvature_integral",
    f"max relative deflection error of the FE ({N_LAYERS} layers, {2 * conv_meshes[-1]} elements) vs the "
    f"layer-free curvature integral, up to first yield (vs the same discrete section, 21 layers: "
    f"{err_ci[-1]:.2e}, fitted rate {-rate:.2f})",
    err_lf,
    TOL_LF,
    err_lf <= TOL_LF,
)
TOL_LAYERS = 5e-3  # an order below the data's reading uncertainty (2.7 % at the yield moment)
report.check(
    "fig12_layer_count",
    f"max |M/M_ref - 1| of the {N_LAYERS}-layer section (chord self-bending) vs "
    f"the layer-free reference, kap 1e-3..0.06 1/m (11 layers: {layer_count_err[11]:.4f}, 21: "
    f"{layer_count_err[21]:.4f})",
    layer_count_err[N_LAYERS],
    TOL_LAYERS,
    layer_count_err[N_LAYERS] <= TOL_LAYERS,
)
assert layer_count_err[N_LAYERS] < layer_count_err[11]  # more layers, closer to the layer-free section

# every measured point with its reading tolerance; the row carries the point with the largest error/tolerance
passed_sub = bool(np.all(np.abs(err_all) <= TOL_POINTS))
report.record(
    "fig12_substitute_beam",
    "relative moment error vs Janney et al. 1956 (C) at all ten points, worst by error/tolerance at "
    f"{JAN[POINTS[worst_k], 0]:g} mm; errors "
    + " ".join(f"{e:+.3f}" for e in err_all)
    + f"; tension stiffening in the effective area only: worst {err_area[worst_area_k]:+.3f} at "
    f"{JAN[POINTS[worst_area_k], 0]:g} mm; sources at 1/2.5/5 mm: shear retention "
    + "/".join(f"{v:+.3f}" for v in change["(a) shear retention beta0 0.25 -> 0.001"])
    + ", shrinkage restraint (EN 1992, assumed 28 d, RH 50 %) "
    + "/".join(f"{v:+.3f}" for v in change["(c) shrinkage restraint (EN 1992)"])
    + ", self-weight "
    + "/".join(f"{v:+.3f}" for v in change["(c') self-weight (strip, from its state)"])
    + ", bond slip (bounded by tension stiffening off) "
    + "/".join(f"{v:+.3f}" for v in change["(b) tension stiffening off"])
    + "; left with TS in h_c,ef + shrinkage + self-weight "
    + "/".join(f"{v:+.3f}" for v in remaining),
    abs(err_all[worst_k]),
    TOL_POINTS[worst_k],
    passed_sub,
)
assert np.all(np.isfinite(err_all)), "the main run must reach the last measured point"

report.check(
    "fig12_mesh_spread",
    f"max relative spread of M over meshes {MESHES} elements per region, band = crack spacing, "
    f"delta 2-{reached('spacing'):.1f} mm (every mesh reached it; band = point length: "
    f"{spread_point:.4f} up to {reached('point'):.1f} mm)",
    spread_spacing,
    SPREAD_BOUND,
    spread_spacing <= SPREAD_BOUND,
)

if len(MON):
    report.record_empty(
        "fig12_monnier",
        f"{len(MON)} measured points present; Monnier's geometry and materials "
        "still missing from the chapter, so no comparison yet",
    )
else:
    report.record_empty(
        "fig12_monnier", "Monnier (1970) measurements: empty slot reference_data/monnier1970_fig12.csv"
    )
print(
    "linear",
    err_linear,
    "| curvature integral",
    err_ci,
    err_lf,
    "| substitute",
    err_all,
    "| spread",
    spread_spacing,
    spread_point,
)

# %% [markdown]
# ## Fig. 12 and its error figures

# %%
fig, ax = plt.subplots(figsize=(7.5, 5))
ax.errorbar(
    JAN[:, 0],
    JAN[:, 1],
    xerr=JAN[:, 2],
    yerr=JAN[:, 3],
    fmt="ko",
    ms=4,
    capsize=2,
    label="measured, Janney et al. 1956 (C)",
)
d_lin = np.array([0.0, 12.0])
ax.plot(d_lin, d_lin / 1e3 / (c_k0 * 1.0) * A * KNM, "k:", label="linear FE (K0)")
ax.plot(d_fe, m_fe, "C0-", lw=2, label=f"nonlinear FE, band = crack spacing {S_RM:.2f} m")
ax.plot(d_pr, m_pr, "C1--", label="nonlinear FE, band = point length (paper's rule)")
ax.plot(
    ts_area["delta"] * 1e3,
    ts_area["M"] * KNM,
    "C4-",
    lw=1,
    label="nonlinear FE, tension stiffening in "
    r"$h_{c,ef}$ only",
)
p_free = np.linspace(0, M_Y_FREE * 0.999, 60) / A
ax.plot(
    sa.four_point_deflection(mc_free, p_free, SPAN, A) * 1e3,
    p_free * A * KNM,
    "C2-.",
    lw=1.5,
    label="layer-free curvature integral (to first yield)",
)
if len(MON):
    ax.plot(MON[:, 0], MON[:, 1], "rs", label="Monnier 1970 (load in kN)")
else:
    ax.text(
        20,
        8,
        "Monnier (1970) measurements: empty slot\nreference_data/monnier1970_fig12.csv",
        fontsize=8,
        color="0.4",
    )
ax.set(
    xlabel="mid-span deflection [mm]", ylabel="mid-span moment per beam [kN m]", xlim=(0, 45), ylim=(0, 55)
)
ax.legend(fontsize=8, loc="upper left")
report.save_figure(fig, "fig12_rc_beam")
plt.show()

# %% [markdown]
# **Figure 8.2** (the paper's Fig. 12 for the substitute beam). Mid-span moment against deflection: the
# measured points with their reading uncertainty, the linear FE, the nonlinear layered strip with the two
# crack-band rules, and the independent curvature-integral reference up to first yield.

# %%
fig, ax = plt.subplots(1, 4, figsize=(20, 4))
for n in conv_meshes:
    ax[0].semilogy(conv[n]["delta"][1:] * 1e3, conv[n]["err"][1:], label=f"{2 * n} elements")
ax[0].set(
    xlabel="mid-span deflection [mm]",
    ylabel="|FE / curvature integral - 1|",
    title="(a) FE vs curvature integral, before yield",
)
ax[0].legend(fontsize=8)
for n in MESHES:
    ax[1].plot(*mesh_runs["spacing", n][:2], "-", label=f"{2 * n} el., band = spacing")
    ax[1].plot(*mesh_runs["point", n][:2], "--", label=f"{2 * n} el., band = point length")
ax[1].errorbar(JAN[:, 0], JAN[:, 1], yerr=JAN[:, 3], fmt="ko", ms=3)
ax[1].set(
    xlabel="mid-span deflection [mm]", ylabel="M per beam [kN m]", xlim=(0, 45), title="(b) mesh sensitivity"
)
ax[1].legend(fontsize=6, ncol=2)
for key, mk in (("layers", "o"), ("layers, self-bending e0", "x"), ("n_el", "s"), ("steps", "^")):
    rows = [r for r in trade if r[0] == key]
    ax[2].loglog([r[3] for r in rows], [max(r[2], 1e-6) for r in rows], mk + "-", label=key)
    for r in rows:
        ax[2].annotate(str(r[1]), (r[3], max(r[2], 1e-6)), fontsize=7)
ax[2].set(
    xlabel="wall time [s]",
    ylabel="max relative error of M at 11.5 and 42 mm",
    title="(c) trade vs 41 layers, fine mesh, fine steps",
)
ax[2].legend(fontsize=8)
ax[3].fill_between(
    JAN[POINTS, 0], -100 * TOL_POINTS, 100 * TOL_POINTS, color="0.85", label="reading tolerance"
)
ax[3].plot(JAN[POINTS, 0], 100 * err_all, "C0o-", label="tension stiffening, all layers")
ax[3].plot(JAN[POINTS, 0], 100 * err_area, "C4s-", label=r"tension stiffening in $h_{c,ef}$ only")
ax[3].axhline(0, color="k", lw=0.5)
ax[3].set(
    xlabel="mid-span deflection [mm]",
    ylabel="M_FE / M_measured − 1 [%]",
    ylim=(-30, 90),
    title="(d) error at every measured point",
)
ax[3].legend(fontsize=8)
fig.tight_layout()
report.save_figure(fig, "fig12_rc_beam_errors")
plt.show()

# %% [markdown]
# **Figure 8.3** Error figures of Fig. 12. (a) Relative deflection error of the layered strip against the
# curvature integral up to first yield, for increasing meshes. (b) Load–deflection over four meshes with
# the band tied to the crack spacing (solid) and to the length each point represents (dashed). (c) Error
# against wall time when one of layers / elements per region / load steps is varied around the base model
# (labels: the varied value). (d) Relative moment error of the main model at each of the ten measured points,
# with the two tension-stiffening rules, against the reading tolerance of each point (±1 kN m plus ±0.5 mm
# times the local slope).
#
# ## Summary
#
# * Linear range: the layered strip reproduces the Timoshenko deflection to round-off (row `fig12_linear`).
# * Before yield the strip converges to the curvature integral of its own discrete section (fitted rate ≈ 2)
#   and, with 41 layers, to the layer-free curvature integral (row `fig12_curvature_integral`); the layer
#   count is set by the layer-free section error (row `fig12_layer_count`: 41 layers 0.1 %, 11 layers 1.2 %).
# * Against the substitute beam (designer values only) every measured point is scored (row
#   `fig12_substitute_beam`, Fig. 8.3d). The row fails: the cracked branch is too stiff at 1–2.5 mm (+75 %,
#   +31 %), the moment at yield is met (+1.8 %), and after
#   yield the model stays flat while the bars of the real beam harden (−4.7 % at 30 mm, −7.5 % at 42 mm).
#   Tension stiffening only in the effective tension area helps in the cracked range (+26 % at 2.5 mm) and
#   changes nothing after yield; no parameter was fitted to the beam.
# * The cracked-branch over-stiffness, source by source (table above): the shear stiffness kept after
#   cracking −0.1 % at most (not a source); shrinkage restraint by EN 1992 (assumed curing and humidity)
#   −12/−8/−4 % and self-weight −9/−6/−4 % at 1/2.5/5 mm, the two causes of the early cracking at 1 mm;
#   tension stiffening −4/−5 % with the effective-area rule at 2.5/5 mm; bond slip, not modelled, at most
#   what switching tension stiffening off does (0/−18/−12 %). With the
#   three estimated sources together +42/+11/+0.3 % would remain, inside the reading tolerances; they are
#   not the default (shrinkage needs unreported inputs; the effective-area rule stopped chapter 11's scene on
#   the default solver), so the row still scores the main model and fails.
# * A band tied to the element makes the *reinforced* beam mesh-dependent (distributed cracking does not
#   localise before yield); a band equal to the MC2010 crack spacing — the scene default — removes that
#   (row `fig12_mesh_spread`: 0.55 % over 2–32 elements per half beam from 2 to 42 mm in full mode, 0.5 % in
#   fast mode, against 21.5 % with the point band, up to the 37 mm every mesh reached).
# * Monnier's measurements remain an empty slot (row `fig12_monnier`).

# %%
print(f"chapter 08 ran in {time.perf_counter() - t_start:.1f} s")
