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
# # 02c — Shear locking of the plate strip: full, selective and reduced integration (paper §10)
#
# Why the paper integrates the strip selectively: a COMET-style locking study of the quadratic element, the
# thin-limit deficit of full integration derived by hand, and the shear correction factor κ.
#
# Chapter 02 is the plate strip in five parts, each with its own verification: **02a** the element (theory,
# properties, internal force), **02b** the Timoshenko closed forms, **02c** the locking study, **02d** the
# layer rule, **02e** the trade between error, elements, layers and wall time.
#
# **In this chapter you will**
# - run a COMET-style locking study from span/depth 10 to 10⁴ for full, selective and reduced integration;
# - derive the thin-limit deflection deficit 4/(5n²) of full integration and see the shear force oscillate;
# - measure what κ = 5/6 against the paper's κ = 1 changes.

# %%
import matplotlib.pyplot as plt
import numpy as np

from ssi.elements.supports import simply_supported_strip
from ssi.lab import paths, report
from ssi.lab.analytical import timoshenko_simply_supported_uniform
from ssi.lab.examples import CHAPTER02_STRIP
from ssi.lab.verify import convergence_rate

FAST = paths.FAST
STRIP = CHAPTER02_STRIP  # chapter 02b's elastic strip: 30 GPa, nu = 0.2, kappa = 5/6
H, G = STRIP.h, STRIP.G  # depth 1 m (span/depth is the span in metres), shear modulus D2 [Pa]
EI, KGA, SECTION = STRIP.EI, STRIP.kGA, STRIP.section()  # bending, shear stiffness (kappa G h)
BACKEND = "superlu"  # many tiny systems: SuperLU's set-up is the cheapest
print(f"fast mode: {FAST};  EI = {EI:.4e} N m^2/m,  kappa G h = {KGA:.4e} N/m")

# %% [markdown]
# ## Locking study (COMET-style)
#
# Simply supported strip, uniform load, mid-span deflection divided by the Timoshenko value, span/depth from
# 10 to 10⁴, the three integration rules, 1 to 64 elements.

# %%
slender = [10.0, 100.0, 1e3, 1e4] if FAST else [10.0, 30.0, 100.0, 300.0, 1e3, 3e3, 1e4]
n_lock = [1, 2, 4, 8, 16, 32, 64]
rules = ("full", "selective", "reduced")
ratio = {}
for rule in rules:
    for sd in slender:
        span = sd * H
        for n in n_lock:
            m, g, ids, r = simply_supported_strip(n, span, SECTION, ("uniform", -1.0), rule, backend=BACKEND)
            ratio[rule, sd, n] = r.displacement(ids[len(ids) // 2], "w")[
                -1, 0
            ] / timoshenko_simply_supported_uniform(span / 2, span, -1.0, EI, KGA)

for rule in rules:
    print(f"\n{rule} integration: w(L/2) / w_Timoshenko")
    print("span/depth " + "".join(f"{n:>9d}" for n in n_lock) + "  (elements)")
    for sd in slender:
        print(f"{sd:10.0f} " + "".join(f"{ratio[rule, sd, n]:9.5f}" for n in n_lock))

# selective: worst deviation over the whole slenderness range, meshes of 2 or more elements (with one element
# the mid-span point is the middle node, which is not nodally exact: 0.8 at every slenderness, for every rule)
locking_worst = max(abs(ratio["selective", sd, n] - 1) for sd in slender for n in n_lock if n >= 2)
full_thin = np.array([1 - ratio["full", slender[-1], n] for n in n_lock if n >= 2])
rate_full = convergence_rate([n for n in n_lock if n >= 2], full_thin)
print(f"\nselective: worst |ratio - 1| = {locking_worst:.2e};  full, thin limit: error ~ n^{rate_full:.2f}")

# %% [markdown]
# The table shows the character of shear locking in the *quadratic* element. Full integration does not
# freeze the strip completely as the linear element would: in the thin limit the constraint γ = 0 at three
# points forces α = w′ with α″ = 0, so the strip can only bend with a curvature that is constant in each
# element. That limit can be worked out by hand. For a statically determinate strip every admissible
# piecewise-constant curvature is reachable, so minimising the energy makes κₕ the element mean of the exact
# curvature κ = M/EI. The unit-load theorem gives the mid-span deflection as ∫κ m̄ dx with m̄ the moment of a
# unit load at mid-span (linear in each element when n is even), hence the deficit
#
# $$\delta - \delta_h = \int (\kappa - \bar\kappa_e)(\bar m - \bar{\bar m}_e)\,dx
#   = \sum_e \kappa'\,\bar m'\,\frac{l_e^3}{12} = \frac{l_e^2}{12}\int_0^L \kappa'\bar m'\,dx
#   = \frac{l_e^2}{12}\,\frac{qL^2}{8EI},\qquad
#   \frac{\delta - \delta_h}{\delta} = \frac{qL^4/(96EIn^2)}{5qL^4/(384EI)} = \frac{4}{5n^2}$$
#
# (κ′ is linear, so the element midpoint sum is exact). The table matches it — 0.80, 0.95, 0.9875, … for
# n = 2, 4, 8 — independent of slenderness once span/depth ≳ 100: second-order convergence where the
# selective element is exact, and a shear force that oscillates violently (Fig. 2.3). Selective (and, on
# straight elements, 2/2 reduced) integration is exact at the element end nodes at every slenderness from
# 10 to 10⁴.

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
ax = axes[0]
for n, c in zip((2, 4, 8), ("C0", "C1", "C2")):
    ax.semilogx(slender, [ratio["full", sd, n] for sd in slender], c + "--o", ms=4, label=f"full, {n} el")
    ax.semilogx(
        slender, [ratio["selective", sd, n] for sd in slender], c + "-s", ms=4, label=f"selective, {n} el"
    )
ax.set_xlabel("span / depth")
ax.set_ylabel("w(L/2) / w_Timoshenko")
ax.legend(fontsize=8, ncol=2)
ax.set_title("(a) mid-span deflection ratio")
ax = axes[1]
nn = np.array([n for n in n_lock if n >= 2])
ax.loglog(nn, full_thin, "C3o-", label=f"full, span/depth {slender[-1]:.0e}: slope {rate_full:.2f}")
ax.loglog(nn, 0.8 / nn**2, "k:", label="thin-limit theory 4/(5 n²)")
sel_err = np.array([abs(ratio["selective", slender[-1], n] - 1) for n in nn]) + 1e-17
ax.loglog(nn, sel_err, "C0s-", label="selective (round-off)")
ax.set_xticks(nn, [str(n) for n in nn])
ax.minorticks_off()
ax.set_xlabel("number of elements")
ax.set_ylabel("|w / w_Timoshenko − 1|")
ax.legend(fontsize=8)
ax.set_title("(b) thin-limit error against mesh")
fig.suptitle("Fig. 2.2 — Locking study: simply supported strip, uniform load")
fig.tight_layout()
report.save_figure(fig, "fig02_locking")

# %%
span_q, n_q = 100.0, 8
fig, ax = plt.subplots(figsize=(7, 3.5))
xs = np.linspace(0, span_q, 200)
ax.plot(xs, -1.0 * (span_q / 2 - xs), "k-", lw=1, label="exact Q = q (L/2 − x)")
q_osc = {}
for rule, style in (("full", "C3o"), ("selective", "C0s")):
    m, g, ids, r = simply_supported_strip(n_q, span_q, SECTION, ("uniform", -1.0), rule, backend=BACKEND)
    res = g.resultants(r.u[-1][g.edofs])
    ax.plot(res["x_sh"].ravel(), res["Q"].ravel(), style, ms=4, label=f"{rule} (shear points)")
    q_osc[rule] = np.abs(res["Q"] - (-1.0) * (span_q / 2 - res["x_sh"])).max() / (span_q / 2)
ax.set_xlabel("x [m]")
ax.set_ylabel("Q [N/m per N/m² of load]")
ax.legend(fontsize=8)
ax.set_title("Fig. 2.3 — Shear force along a strip of span/depth 100, 8 elements")
report.save_figure(fig, "fig02_shear_force")
print("max shear-force error / (qL/2):", {k: f"{v:.1e}" for k, v in q_osc.items()})

# %% [markdown]
# ### κ = 1 (the paper's literal eq. 4.4) against κ = 5/6
#
# κ scales only the shear part of the deflection. For the simply supported strip under uniform load, shear
# is 2.4/(span/depth)² of the bending deflection here (ν = 0.2), so κ = 1 instead of 5/6 makes a thick strip
# stiffer by up to a few per cent and is invisible for a slender foundation plate:

# %%
kappa_effect = {}
for sd in (2.0, 5.0, 10.0, 100.0):
    span = sd * H
    w56 = simply_supported_strip(4, span, SECTION, ("uniform", -1.0), kappa=5 / 6, backend=BACKEND)[3]
    w1 = simply_supported_strip(4, span, SECTION, ("uniform", -1.0), kappa=1.0, backend=BACKEND)[3]
    ids_mid = 4  # node at mid-span of 4 elements
    ratio_fe = w1.displacement(ids_mid, "w")[-1, 0] / w56.displacement(ids_mid, "w")[-1, 0]
    ratio_exact = timoshenko_simply_supported_uniform(
        span / 2, span, -1.0, EI, G * H
    ) / timoshenko_simply_supported_uniform(span / 2, span, -1.0, EI, KGA)
    kappa_effect[sd] = (ratio_fe, ratio_exact)
    print(f"span/depth {sd:5.0f}: w(kappa=1) / w(kappa=5/6) = {ratio_fe:.5f} (closed form {ratio_exact:.5f})")

# %% [markdown]
# ## Verification
#
# Tolerances: `ROUND` is for results that are exact in exact arithmetic; the thin strips of the locking
# study amplify round-off by up to (span/depth)² = 10⁸, hence the separate `LOCK_TOL` of the issue, 1 %.
# Fitted rates are asserted within ±0.15 of their theoretical values.

# %%
ROUND = 1e-9
LOCK_TOL = 0.01
RATE_TOL = 0.15
report.check(
    "locking_selective",
    "worst |w/w_exact - 1|, selective, span/depth 10..1e4, 2-64 elements",
    locking_worst,
    LOCK_TOL,
    locking_worst < LOCK_TOL,
)
assert all(abs(ratio["selective", sd, n] - 0.8) < 0.01 for sd in slender for n in (1,))  # 1 el: middle node
assert ratio["full", slender[-1], 4] < 0.96 and ratio["full", slender[-1], 8] < 0.99, "full integration locks"
assert abs(rate_full + 2.0) < RATE_TOL, rate_full
# the hand-derived thin limit 1 - 4/(5 n^2); at span/depth 1e4 the finite shear penalty leaves O((h/l_e)^2)
# <= 4e-7 and round-off is what the selective rule shows on the same meshes (<= 1e-5): tolerance 2e-5
THIN_TOL = 2e-5
thin_dev = max(abs(full_thin[i] - 0.8 / n**2) for i, n in enumerate(nn))
print(f"full integration vs the thin-limit theory 4/(5n^2): max deviation {thin_dev:.1e}")
assert thin_dev < THIN_TOL, thin_dev
assert q_osc["selective"] < 1e-6 and q_osc["full"] > 1.0
# same stiffness on straight elements; the solutions differ only by round-off, which the thin strips amplify
# by up to (span/depth)^2 ~ 1e8 (the selective ratio itself deviates 9e-6 at 1e4 with 64 elements)
assert max(abs(ratio["reduced", sd, n] - ratio["selective", sd, n]) for sd in slender for n in n_lock) < 1e-4
# kappa: FE ratio equals the closed-form ratio
assert all(abs(fe / ex - 1) < ROUND for fe, ex in kappa_effect.values())
print("all chapter 02c checks passed")

# %% [markdown]
# ## Summary
#
# - **Full integration locks**: in the quadratic element the lock is partial — curvature becomes piecewise
#   constant, the thin-limit deflection is short by 4/(5n²) whatever the slenderness, and the shear force
#   oscillates. Selective integration stays exact from span/depth 10 to 10⁴ (`locking_selective`).
# - κ = 5/6 against the paper's literal κ = 1 changes only the shear part of the deflection: a few per cent
#   for span/depth 2–5, nothing that matters for slender foundation strips.
#
# References: W. Szajna, §4, §10; D. R. J. Owen and J. A. Figueiras (layered RC plates); G. Prathap, *The
# Finite Element Method in Structural Mechanics* (field consistency, locking of the quadratic beam element);
# J. Bleyer, COMET numerical tours (the Reissner–Mindlin locking table chapter 02c follows).
