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
# # 02d — The layer rule of the plate strip (paper §4)
#
# The strip integrates its section by layers: one law call at each layer's mid-depth plus the exact h²/12
# self-bending term. For linear layers that rule must be exact for any layering, and an asymmetric composite
# must reproduce the transformed section.
#
# Chapter 02 is the plate strip in five parts, each with its own verification: **02a** the element (theory,
# properties, internal force), **02b** the Timoshenko closed forms, **02c** the locking study, **02d** the
# layer rule, **02e** the trade between error, elements, layers and wall time.
#
# **In this chapter you will**
# - see that the rectangular layer rule with its h²/12 term is exact for any layering, and that a composite
#   section reproduces the transformed-section EI and neutral-axis shift;
# - see the layers the section builder makes for the paper's reinforced beam.

# %%
import matplotlib.pyplot as plt
import numpy as np

from ssi.elements.plate import PlateStrip
from ssi.elements.section import homogeneous, layered, paper_rc_section
from ssi.elements.supports import cantilever_strip
from ssi.lab import paths, report
from ssi.lab.examples import CHAPTER02_STRIP
from ssi.materials import rc
from ssi.materials.layer_laws import CONCRETE, ELASTIC, STEEL

FAST = paths.FAST
E, NU, H = CHAPTER02_STRIP.E, CHAPTER02_STRIP.nu, CHAPTER02_STRIP.h  # 30 GPa, 0.2, 1 m (span/depth = span)
BACKEND = "superlu"  # many tiny systems: SuperLU's set-up is the cheapest
print(f"fast mode: {FAST}")

# %%
# the paper's reinforced section (§9.2), drawn in Fig. 2.4
conc = rc.concrete_params(fc=30e6, E0=30e9, eps_c=0.002, fr=3e6, Gf=100.0, ls=0.1, eps_y=2.5e-3)
steel = rc.steel_params(fy=500e6, Es=200e9, EH=2e9)
rc_sec = paper_rc_section(0.5, 0.05, 1.5e-3, 0.8e-3, (CONCRETE, conc), (STEEL, steel))

# %% [markdown]
# ## The layer rule
#
# (a) A homogeneous section split into 1, 2, 11 and 50 layers must give the *same* linear stiffness — the
# h²/12 term makes the rectangular rule exact for the quadratic z² integrand. (b) An asymmetric composite —
# 0.4 m of concrete on a 10 mm steel plate, nodes at mid-depth — must reproduce the transformed section:
# neutral axis
# z_na = Σ Eₙhₙzₙ / Σ Eₙhₙ and EI about it, EI = Σ Eₙ(hₙ³/12 + hₙ(zₙ − z_na)²). With the nodes on the
# mid-depth and no axial force, a cantilever with a tip load must deflect by PL³/(3EI) + PL/(κGA) and its
# reference surface must stretch by u = z_na·α — the neutral-axis shift seen in the kinematics.

# %%
# the element of chapter 02a (off-centre middle node) with the section split into 1, 2, 11 and 50 layers
xy_d = np.array([[[0.0, 0.0], [1.1, 0.0], [2.0, 0.0]]])
k_by_layers = {
    n: PlateStrip(xy_d, np.arange(9)[None], homogeneous(H, E, NU, n)).elastic_stiffness()[0]
    for n in (1, 2, 11, 50)
}
k1 = k_by_layers[1]
layer_diff = max(np.abs(k_by_layers[n] - k1).max() / np.abs(k1).max() for n in (2, 11, 50))
print(f"max |K(n layers) - K(1 layer)| / max|K| over n = 2, 11, 50: {layer_diff:.1e}")

hc, hs, Ec, Es = 0.4, 0.01, 30e9, 200e9
composite = layered([hs, hc], ELASTIC, [[Es, 0.0], [Ec, 0.0]], carries_shear=[False, True])
zc, zs = composite.z_mid[1], composite.z_mid[0]  # relative to the mid-depth
z_na = (Ec * hc * zc + Es * hs * zs) / (Ec * hc + Es * hs)
ei_tr = Ec * (hc**3 / 12 + hc * (zc - z_na) ** 2) + Es * (hs**3 / 12 + hs * (zs - z_na) ** 2)
props = composite.elastic_resultant_stiffness()
span_c, P_c = 3.0, -1.0e4
m, g, ids, r = cantilever_strip(6, span_c, composite, P_c, backend=BACKEND)
w_tip = r.displacement(ids[-1], "w")[-1, 0]
w_tip_exact = P_c * span_c**3 / (3 * ei_tr) + P_c * span_c / props["S"]
u_tip, a_tip = r.displacement(ids[-1], "u")[-1, 0], r.displacement(ids[-1], "alpha")[-1, 0]
composite_err = {
    "neutral axis": abs(props["z_na"] - z_na) / (hc + hs),
    "EI about the neutral axis": abs(props["D_na"] - ei_tr) / ei_tr,
    "tip deflection": abs(w_tip / w_tip_exact - 1),
    "u = z_na alpha at the tip": abs(u_tip - z_na * a_tip) / abs(z_na * a_tip),
}
print(f"neutral axis {z_na * 1e3:.2f} mm below mid-depth; EI = {ei_tr:.4e} N m^2/m")
for name, err in composite_err.items():
    print(f"  {name:28s} relative error {err:.1e}")

# %% [markdown]
# Figure 2.4 shows the layers the section builder makes for the paper's beam (§9.2): 9 concrete layers and
# the two smeared bar layers as layers 2 and 10, stacked so that the thicknesses add up to the depth; the
# bar layers are drawn to scale (1.5 mm and 0.8 mm equivalent thickness).

# %%
fig, axes = plt.subplots(1, 2, figsize=(10, 4), gridspec_kw={"width_ratios": [1, 1.4]})
ax = axes[0]
for n in range(rc_sec.n_layer):
    bottom = rc_sec.z_mid[n] - rc_sec.h[n] / 2
    if rc_sec.kind[n] == STEEL:
        ax.barh(bottom, 1.0, height=rc_sec.h[n], align="edge", color="C3", edgecolor="C3", lw=1.5)
        ax.text(
            1.03,
            rc_sec.z_mid[n],
            f"{n + 1}: steel, {rc_sec.h[n] * 1e3:.1f} mm",
            va="center",
            fontsize=7,
            color="C3",
        )
    else:
        ax.barh(bottom, 1.0, height=rc_sec.h[n], align="edge", color="0.85", edgecolor="k", lw=0.5)
        ax.text(
            1.03,
            rc_sec.z_mid[n] + (0.006 if n in (0, rc_sec.n_layer - 1) else 0.0),
            f"{n + 1}",
            va="center",
            fontsize=7,
        )
ax.set_xlim(0, 1.6)
ax.set_xticks([])
ax.set_ylabel("z [m] (reference surface at 0)")
ax.set_title("(a) paper section: 11 layers, steel 2 and 10")
ax = axes[1]
eps_a, gam_a = g.layer_strains(r.u[-1][g.edofs])
e0c, _ = composite.initial_moduli()
x_pt = g.resultants(r.u[-1][g.edofs])["x_ax"][0, 0]
zz = np.linspace(composite.z_bottom, composite.z_top, 200)
kap0 = (eps_a[0, 0, 1] - eps_a[0, 0, 0]) / (composite.z_mid[0] - composite.z_mid[1])
eps_line = eps_a[0, 0, 0] - (zz - composite.z_mid[0]) * kap0
ax.plot(eps_line * 1e6, zz, "k-", lw=1, label="strain (linear)")
ax.plot(eps_a[0, 0] * 1e6, composite.z_mid, "C0o", label="layer mid-depth strains")
ax.axhline(z_na, color="C3", ls="--", label="transformed-section neutral axis")
ax.axhline(composite.z_bottom + hs, color="0.6", lw=0.8)
ax.set_xlabel("εx [µstrain]")
ax.set_ylabel("z [m]")
ax.legend(fontsize=8)
ax.set_title(f"(b) composite cantilever, x = {x_pt:.2f} m: zero strain at z_na")
fig.suptitle("Fig. 2.4 — Layered sections")
fig.tight_layout()
report.save_figure(fig, "fig02_layers")

# %% [markdown]
# ## Verification
#
# Tolerances: `ROUND` is for results that are exact in exact arithmetic (a few hundred ulps of the
# conditioning of these small systems).

# %%
ROUND = 1e-9
report.check(
    "layer_rule",
    "max relative stiffness difference, 1 vs 2/11/50 layers",
    layer_diff,
    ROUND,
    layer_diff < ROUND,
)
assert max(composite_err.values()) < ROUND, composite_err
print("all chapter 02d checks passed")

# %% [markdown]
# ## Summary
#
# - The layer rule with the exact h²/12 self-bending term gives the same linear stiffness for any layering
#   (`layer_rule`), and the asymmetric composite reproduces the transformed-section EI and neutral-axis
#   shift.
#
# References: W. Szajna, §4, §10; D. R. J. Owen and J. A. Figueiras (layered RC plates); G. Prathap, *The
# Finite Element Method in Structural Mechanics* (field consistency, locking of the quadratic beam element);
# J. Bleyer, COMET numerical tours (the Reissner–Mindlin locking table chapter 02c follows).
