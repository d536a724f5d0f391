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
# # 07 — Sadowsky's punch: Gauss vs Newton–Cotes interface integration (paper §9.1, Fig. 10)
#
# The paper's first test presses a rigid flat punch into an elastic half-plane and compares the contact
# pressure under it with the exact solution: fully Gauss-integrated interface elements make the pressure
# oscillate, the reduced Newton–Cotes rule does not. The paper shows this in Fig. 10 without numbers; here
# the claim is measured, and the interface bed is also checked against Hetényi's beam on a Winkler
# foundation.
#
# **In this chapter you will**
# - build the punch from the library's parts: a very stiff plate strip, a row of interface elements and a
#   large elastic soil block, and compare its contact pressure with p(x) = P/(π√(a² − x²));
# - measure the pressure error of the Newton–Cotes rule and its convergence under mesh refinement;
# - define an oscillation measure and show that Gauss integration rings far more than Newton–Cotes;
# - sweep the interface penalty k_n·a/E from 1 to 10⁸: too soft lets the punch sink into the interface,
#   very stiff must not break the solve;
# - check that a plate strip on an interface bed over a rigid base *is* a beam on a Winkler foundation.

# %% [markdown]
# ## Theory
#
# **Sadowsky's problem (1928).** A rigid, smooth punch of half-width a is pressed by a force P (per unit
# length) into an elastic half-plane. The contact pressure (compression positive) is
# $$p(x) = \frac{P}{\pi\sqrt{a^2 - x^2}},\qquad |x| < a,\qquad \frac{p}{p_m} = \frac{2}{\pi\sqrt{1-\xi^2}},
#   \ \ \xi = x/a,\ \ p_m = \frac{P}{2a}.$$
# It is singular at the edges (the stress concentration that tests the interface) and independent of E and ν.
# The settlement of a half-plane is undefined (logarithmic), so only the pressure *shape* is compared.
#
# **Model.** A block 20a wide and 10a deep (bottom fixed, sides on vertical rollers) stands for the
# half-plane. The punch is a plate strip 0.5a thick with E_p = 10⁵ E: its bending stiffness is ~10³·E·a³, so
# it stays flat to within 10⁻³ of its settlement. It rests on interface elements with k_t = 0 (a smooth punch,
# as in Sadowsky's solution) and k_n·a/E = 10⁶ (a bonded, nearly rigid contact), and is loaded by P at its
# middle node. The interface stays in compression everywhere, so the linear solve is exact for this law.
#
# **Measures.** *Pressure error*: max |p_FE/p − 1| over the integration points with |x| ≤ 0.8a (beyond that
# the singularity dominates every mesh). *Oscillation*: the total variation of the relative deviation
# d = p_FE/p − 1 along all integration points inside the contact, TV = Σ|d_{i+1} − d_i|. A smooth error
# has a small TV even when it is not small; a zig-zag has a large one. We report TV_Gauss / TV_NC.
#
# **Winkler check.** A plate strip on interface elements whose lower nodes are fixed, with k_t = 0 and
# k_n = k, is exactly a beam on a Winkler bed of modulus k: the interface traction is σn = k·w at every
# Newton–Cotes sample. Hetényi's infinite beam under a point load P,
# $$w(x) = \frac{P\lambda}{2k}e^{-\lambda|x|}(\cos\lambda x + \sin\lambda|x|),\qquad
#   \lambda = \Big(\frac{k}{4EI}\Big)^{1/4},\qquad EI = \frac{E h^3}{12(1-\nu^2)}\ \text{(plate strip)},$$
# is the reference. The strip is a Mindlin element, so its shear flexibility adds a relative deflection of
# order EIλ²/(κGh); we keep it ~10⁻³ by taking a thin strip.
#
# | symbol | code | value |
# |---|---|---|
# | a, P | `A`, `P` | 1 m, 100 kN/m |
# | E, ν (soil) | `E_SOIL`, `NU_SOIL` | 10 MPa, 0.3 |
# | block width, depth | `WIDTH`, `DEPTH` | 20a, 10a |
# | plate h, E_p | `H_PLATE`, `E_PLATE` | 0.5a, 10⁵E |
# | k_n, k_t | `interface_params(0, kn, c=inf)` | k_n a/E = 10⁶ (swept 1…10⁸), k_t = 0 |
# | elements under the punch | `n_under` | 8, 16, 32 (named mesh), 64 (full mode) |

# %%
import math
import time

import matplotlib.pyplot as plt
import numpy as np

from ssi.core.mesh import foundation_contact, soil_block
from ssi.core.model import Model
from ssi.elements.interface import add_interface
from ssi.elements.plate import add_plate_strip
from ssi.elements.section import homogeneous
from ssi.elements.supports import fix_block, soil_group
from ssi.lab import paths, report
from ssi.lab.analytical import hetenyi_deflection, sadowsky_pressure
from ssi.lab.examples import winkler_strip
from ssi.lab.verify import convergence_rate
from ssi.materials.interface_law import interface_params
from ssi.materials.soil_laws import ELASTIC, elastic_params

t_chapter = time.perf_counter()
A, P = 1.0, 100e3
E_SOIL, NU_SOIL = 10e6, 0.3
WIDTH, DEPTH = 20 * A, 10 * A
H_PLATE, E_PLATE = 0.5 * A, 1e5 * E_SOIL
KN_RATIO = 1e6
NAMED_MESH = 32  # elements under the punch (h = a/16) at which the 5 % claim is made
MESHES = [8, 16, 32] if paths.FAST else [8, 16, 32, 64]
SWEEP = [1.0, 1e1, 1e2, 1e3, 1e4, 1e6, 1e8]
SWEEP_MESH = 16 if paths.FAST else NAMED_MESH


def punch(n_under, rule="newton_cotes", kn_ratio=KN_RATIO):
    """Solve the punch; return the contact points, pressures and the settlement of the punch."""
    mesh = soil_block(WIDTH, DEPTH, foundation=(-A, A), h_fine=2 * A / n_under, h_coarse=2.0 * A, growth=1.3)
    m = Model()
    soil_ids = m.add_nodes(mesh.xy, 2)
    soil_group(m, mesh, [(ELASTIC, elastic_params(E_SOIL, NU_SOIL))], ids=soil_ids)
    contact = foundation_contact(mesh, -A, A, H_PLATE)
    plate, pids, pconn = add_plate_strip(
        m, contact.plate_xy[0::2, 0], homogeneous(H_PLATE, E_PLATE, 0.2), z=H_PLATE / 2
    )
    itf = add_interface(
        m,
        pconn,
        soil_ids[contact.soil_conn],
        interface_params(0.0, kn_ratio * E_SOIL / A, c=math.inf),
        offset=plate.bottom_offset,
        rule=rule,
    )
    fix_block(m, mesh, soil_ids)
    mid = pids[len(pids) // 2]
    m.fix([mid], "u")  # k_t = 0: nothing else holds the punch sideways
    m.add_load([mid], "w", -P)
    t0 = time.perf_counter()
    res = m.solve_linear(backend="superlu")
    wall = time.perf_counter() - t0
    st = res.final_state[m.groups.index(itf)]
    xq = itf.ip_coords()[..., 0].ravel()
    p = -st[..., 1].ravel()
    o = np.argsort(xq, kind="stable")
    gap = st[..., 4].ravel()[o]  # normal gap g_n (< 0: the punch has entered the interface)
    return {
        "x": xq[o],
        "p": p[o],
        "gap": gap,
        "w_punch": -res.displacement([mid], "w")[-1, 0],
        "n_dof": m.n_dof,
        "wall": wall,
        "force": float((itf.ip_weights().ravel() * p).sum()),
    }


def measures(r):
    """Max relative pressure error for |x| <= 0.8a and the total variation of the relative deviation."""
    inside = np.abs(r["x"]) < A * (1 - 1e-9)
    d = r["p"][inside] / sadowsky_pressure(r["x"][inside], A, P) - 1.0
    near = np.abs(r["x"][inside]) <= 0.8 * A + 1e-9
    return float(np.abs(d[near]).max()), float(np.abs(np.diff(d)).sum())


# %% [markdown]
# ## Mesh refinement, both rules

# %%
rows = []
runs = {}
for n in MESHES:
    for rule in ("newton_cotes", "gauss"):
        r = punch(n, rule)
        runs[(n, rule)] = r
        err, tv = measures(r)
        rows.append((n, rule, r["n_dof"], err, tv, r["wall"], r["force"] / P))
print(
    f"{'n_under':>7s} {'rule':>13s} {'DOF':>6s} {'max err |x|<=0.8a':>18s} {'TV':>7s} {'solve [s]':>9s} "
    f"{'sum p ds / P':>12s}"
)
for n, rule, ndof, err, tv, wall, fr in rows:
    print(f"{n:7d} {rule:>13s} {ndof:6d} {err:18.4f} {tv:7.3f} {wall:9.2f} {fr:12.9f}")

# %% [markdown]
# ## Penalty sweep k_n·a/E = 1 … 10⁸
#
# A soft interface is a compliant layer: the punch settles into it by p/k_n, the soil sees a smeared load and
# the pressure flattens. A very stiff one makes the system stiffness span many decades; the direct solver
# must cope, and the answer must stop changing.

# %%
sweep = {}
for kr in SWEEP:
    for rule in ("newton_cotes", "gauss"):
        r = punch(SWEEP_MESH, rule, kr)
        err, tv = measures(r)
        penetration = float(-r["gap"][np.abs(r["x"]) <= 0.5 * A].mean()) / r["w_punch"]
        sweep[(kr, rule)] = (err, tv, penetration, r["w_punch"])
print(f"mesh n_under = {SWEEP_MESH}")
print(
    f"{'kn a/E':>8s} {'rule':>13s} {'max err':>8s} {'TV':>7s} "
    f"{'gap/settlement':>15s} {'settlement [mm]':>16s}"
)
for (kr, rule), (err, tv, pen, w) in sweep.items():
    print(f"{kr:8.0e} {rule:>13s} {err:8.4f} {tv:7.3f} {pen:15.2e} {w * 1e3:16.4f}")

# %% [markdown]
# ## Winkler check: the plate strip on an interface bed (Hetényi)

# %%
H_B, E_B, NU_B, K_BED, P_B = 0.05, 30e9, 0.2, 5e6, 10e3
EI_B = E_B * H_B**3 / (12 * (1 - NU_B**2))
LAM_B = (K_BED / (4 * EI_B)) ** 0.25
L_B = 2 * 3 * math.pi / LAM_B  # e^(-lam L/2) = 8e-5: the ends do not matter
N_B = 100  # named mesh: 100 elements, 16 per wavelength 2 pi / lam


def winkler_beam(n_el, h=H_B):
    """The strip of depth h on the bed (`ssi.lab.examples.winkler_strip`) against Hetenyi: x, w, w_exact, max
    relative error, lambda, EI."""
    ei = E_B * h**3 / (12 * (1 - NU_B**2))
    lam = (K_BED / (4 * ei)) ** 0.25
    x, w = winkler_strip(n_el, h, E_B, NU_B, K_BED, P_B)
    w_ex = hetenyi_deflection(x, P_B, K_BED, ei)
    return x, w, w_ex, float(np.abs(w - w_ex).max() / w_ex.max()), lam, ei


x_b, w_b, w_b_ex, het_err, _, _ = winkler_beam(N_B)
het_conv = [(n, winkler_beam(n)[3]) for n in (25, 50, 100, 200)]
het_thin = []
for h_try in (0.2, 0.05, 0.02):
    *_, e_try, lam_try, ei_try = winkler_beam(200, h_try)
    het_thin.append((h_try, e_try, ei_try * lam_try**2 / (5 / 6 * E_B / (2 * (1 + NU_B)) * h_try)))
print(f"lambda = {LAM_B:.3f} 1/m, beam length {L_B:.1f} m, {N_B} elements")
print("max |w - w_H| / w_H(0) vs elements:", [(n, round(e, 5)) for n, e in het_conv])
print(
    "with 200 elements vs strip depth h: (h, error, shear estimate EI lam^2/(kappa G h))",
    [(h, round(e, 5), round(s, 5)) for h, e, s in het_thin],
)

# %% [markdown]
# ## Verification

# %%
PRESSURE_TOL = 0.05  # the issue's claim: within 5 % of exact for |x| <= 0.8a at the named mesh
OSC_MARGIN = 3.0  # "larger by a clear margin": Gauss TV at least 3x Newton-Cotes (measured ~10x)
RATE_MIN = 1.0  # fitted convergence rate of the NC pressure error in h (measured ~1.3-1.5)
HETENYI_TOL = 0.005  # shear flexibility ~1.2e-3 (estimate above) + discretisation < 1e-4 at 100 elements
EQUILIBRIUM_TOL = 1e-6  # sum of interface tractions = P (linear solve; round-off of a stiff system)

err_nc = {n: measures(runs[(n, "newton_cotes")])[0] for n in MESHES}
tv_nc = measures(runs[(NAMED_MESH, "newton_cotes")])[1]
tv_g = measures(runs[(NAMED_MESH, "gauss")])[1]
osc_ratio = tv_g / tv_nc
h = np.array([2 * A / n for n in MESHES])
rate = convergence_rate(h, [err_nc[n] for n in MESHES])
print(f"Newton-Cotes max error at n_under = {NAMED_MESH}: {err_nc[NAMED_MESH]:.4f} (tol {PRESSURE_TOL})")
print(f"fitted rate of the NC error in h: {rate:.2f}")
print(f"oscillation TV: Gauss {tv_g:.3f}, Newton-Cotes {tv_nc:.3f}, ratio {osc_ratio:.1f} (>= {OSC_MARGIN})")
print(f"Hetenyi max relative deflection error ({N_B} elements): {het_err:.2e} (tol {HETENYI_TOL})")
for key, r in runs.items():
    assert abs(r["force"] / P - 1) < EQUILIBRIUM_TOL, key
assert err_nc[NAMED_MESH] <= PRESSURE_TOL
assert all(np.diff([err_nc[n] for n in MESHES]) < 0)  # monotone convergence
assert rate >= RATE_MIN
assert osc_ratio >= OSC_MARGIN
for n in MESHES:  # at every mesh, not just one
    assert measures(runs[(n, "gauss")])[1] > OSC_MARGIN * measures(runs[(n, "newton_cotes")])[1]
# penalty: soft interfaces let the punch sink in (gap a large part of the settlement), stiff ones converge
assert sweep[(1.0, "newton_cotes")][2] > 0.2
assert sweep[(1e8, "newton_cotes")][2] < 1e-6
assert abs(sweep[(1e8, "newton_cotes")][0] - sweep[(1e6, "newton_cotes")][0]) < 1e-3
assert het_err <= HETENYI_TOL
report.record(
    "fig10_newton_cotes",
    f"max |p/p_exact-1| for |x|<=0.8a, Newton-Cotes, {NAMED_MESH} elements under the punch, kn a/E=1e6",
    err_nc[NAMED_MESH],
    PRESSURE_TOL,
    err_nc[NAMED_MESH] <= PRESSURE_TOL,
)
report.record(
    "fig10_gauss_oscillation",
    f"TV(p/p_exact-1) Gauss / Newton-Cotes, {NAMED_MESH} elements (pass if >= tolerance)",
    osc_ratio,
    OSC_MARGIN,
    osc_ratio >= OSC_MARGIN,
)
report.record(
    "hetenyi",
    f"max |w-w_Hetenyi|/w_Hetenyi(0), plate strip on interface bed, {N_B} elements",
    het_err,
    HETENYI_TOL,
    het_err <= HETENYI_TOL,
)
print("all checks passed")

# %% [markdown]
# ## Figures

# %%
fig, ax = plt.subplots(1, 2, figsize=(13, 4.6))
xx = np.linspace(-0.995, 0.995, 500) * A
pm = P / (2 * A)
for k, (n, lims) in enumerate(((NAMED_MESH, (0, 3)), (8, (0, 3)))):
    ax[k].plot(xx / A, sadowsky_pressure(xx, A, P) / pm, "k-", lw=1.2, label="exact (Sadowsky)")
    for rule, mk in (("gauss", "o-"), ("newton_cotes", "s-")):
        r = runs[(n, rule)]
        inside = np.abs(r["x"]) < A * (1 - 1e-9)
        ax[k].plot(
            r["x"][inside] / A,
            r["p"][inside] / pm,
            mk,
            ms=3,
            lw=0.8,
            label=f"{'full Gauss' if rule == 'gauss' else 'Newton–Cotes'} (TV = {measures(r)[1]:.2f})",
        )
    ax[k].set(ylim=lims, xlabel="x / a", ylabel="p / p_m", title=f"({'ab'[k]}) {n} elements under the punch")
    ax[k].axvspan(-0.8, 0.8, color="0.93", zorder=0)
    ax[k].legend(fontsize=8, loc="upper center")
fig.tight_layout()
report.save_figure(fig, "fig10_sadowsky")

# %% [markdown]
# *Figure 10 — Contact pressure under a rigid punch on an elastic block (20a × 10a), k_n·a/E = 10⁶, against
# Sadowsky's exact p/p_m = 2/(π√(1 − ξ²)). (a) The named mesh (32 elements under the punch): Newton–Cotes
# follows the exact curve (max error in the shaded |x| ≤ 0.8a given in the verification cell); full Gauss
# oscillates near the edges. (b) A coarse mesh (8 elements): the Gauss oscillation spreads over the whole
# contact.*

# %%
fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
ax[0].loglog(h / A, [err_nc[n] for n in MESHES], "s-", label="Newton–Cotes")
ax[0].loglog(h / A, [measures(runs[(n, "gauss")])[0] for n in MESHES], "o-", label="full Gauss")
ax[0].axhline(PRESSURE_TOL, color="k", ls=":", lw=0.8)
ax[0].set(
    xlabel="element length / a",
    ylabel="max |p/p_exact − 1|, |x| ≤ 0.8a",
    title=f"(a) convergence (NC rate {rate:.2f})",
)
ax[0].legend(fontsize=8)
krs = np.array(SWEEP)
for rule, mk, col in (("newton_cotes", "s-", "tab:blue"), ("gauss", "o-", "tab:orange")):
    ax[1].loglog(
        krs, [sweep[(k, rule)][0] for k in SWEEP], mk, color=col, label=f"{rule.replace('_', '–')}: max error"
    )
    ax[1].loglog(
        krs,
        [sweep[(k, rule)][1] for k in SWEEP],
        mk[0] + "--",
        mfc="none",
        color=col,
        label=f"{rule.replace('_', '–')}: TV",
    )
ax[1].loglog(krs, [sweep[(k, "newton_cotes")][2] for k in SWEEP], "k^-", ms=4, label="gap / settlement")
ax[1].set(xlabel="k_n a / E", title=f"(b) penalty sweep ({SWEEP_MESH} elements)")
ax[1].legend(fontsize=7)
ax[2].plot(x_b, w_b_ex * 1e3, "k-", lw=1.2, label="Hetényi (exact)")
ax[2].plot(x_b[::4], w_b[::4] * 1e3, "o", ms=3, label=f"plate strip on interface bed ({N_B} el.)")
ax[2].set(xlabel="x [m]", ylabel="settlement [mm]", title="(c) beam on Winkler bed")
ax[2].legend(fontsize=8)
fig.tight_layout()
report.save_figure(fig, "fig10_sadowsky_errors")

# %% [markdown]
# *Figure 10.1 — (a) Max pressure error in |x| ≤ 0.8a against element size: Newton–Cotes converges at the
# fitted rate; full Gauss has similar errors inside 0.8a on fine meshes because its ringing stays in the
# last elements near the singular edge, but it never goes away (see the TV ratio). (b) Penalty sweep: below
# k_n·a/E ≈ 10² the punch sinks into the interface (gap/settlement, triangles) and the pressure flattens; from
# 10³ on, the answer is converged, and 10⁸ still solves cleanly. (c) The strip on an interface bed over a
# rigid base against Hetényi's infinite beam on a Winkler foundation.*

# %% [markdown]
# ## Summary
#
# - With the paper's Newton–Cotes interface integration the punch pressure is within 5 % of Sadowsky's
#   solution over |x| ≤ 0.8a with 32 elements under the punch, and the error converges at a rate ≥ 1.
# - Full Gauss integration rings: the total variation of its pressure deviation is an order of magnitude
#   larger than Newton–Cotes at every mesh. On coarse meshes the ringing covers the whole contact (Fig. 10b);
#   on fine meshes it stays next to the edges — it is the L²-projection of a singular traction (chapter 04).
# - The penalty only needs k_n·a/E ≳ 10³; 10⁸ is harmless to the direct solver.
# - The interface bed under the plate strip reproduces Hetényi's beam on a Winkler foundation; the remaining
#   difference (~10⁻³) is the strip's shear flexibility, shrinking with its depth like √h.

# %%
print(f"chapter 07 ran in {time.perf_counter() - t_chapter:.1f} s")
