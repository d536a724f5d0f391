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
# # 3. Concrete and steel: the layer laws of the reinforced-concrete strip
#
# Paper §5, equations (5.1)–(5.4), Figs. 5 and 6 (paper-notes §3).
#
# In this chapter you will
#
# * drive one concrete point and one steel point alone along strain paths, before they enter a structure;
# * check the closed-form features of the compression curve (5.1) and show that the two forms of the
#   irreversible strain (5.3) agree;
# * verify that crack-band softening (5.4) dissipates exactly $G_f/l_s$ per unit volume, and see the
#   clear error for an element so large that the law would snap back;
# * see tension stiffening and the cracked shear modulus vanish at steel yield (Figs. 5–6 redrawn);
# * check every branch's tangent against finite differences.
#
# ## Theory, in brief
#
# **Compression (5.1).** With magnitudes $x=-\varepsilon\ge 0$ and $r=x/\varepsilon_c$, the envelope is
# $f(x)=E_0x/\bigl(1+(E_0\varepsilon_c/f_c-2)r+r^2\bigr)$. It starts with slope $E_0$, peaks at
# $f_c$ when $x=\varepsilon_c$ (slope zero there) and descends after. At $\varepsilon_{cu}$ it still carries
# $f_{cu}=f(\varepsilon_{cu})$ (about $0.9f_c$ for $a=2$); what happens beyond is open in the paper. Dropping
# to zero there is a stress cliff that a structure cannot follow (the softening of a crushing zone then
# depends on the element size, like an unregularised crack). We regularise it like cracking: the stress
# falls linearly from $f_{cu}$ to zero at $\varepsilon_{cd}=\varepsilon_{cu}+2G_c/(f_{cu}l_s)$, so the band
# dissipates the compressive fracture energy $G_c$ per unit area beyond $\varepsilon_{cu}$
# (`crushing_envelope`; designer value $G_c=8.8\sqrt{f_c/\text{MPa}}$ N/mm, Nakamura & Higai 2001;
# `Gc=0` restores the cliff). A crushed point unloads with $E_0$ and carries no tension.
# We require $a=E_0\varepsilon_c/f_c\ge 2$: for smaller $a$
# the curve would bend *above* its own initial tangent and the irreversible strain below would be negative.
#
# **Irreversible strain (5.2–5.3).** The strain splits into an elastic part $\sigma/E_0$ (unloading runs
# parallel to the initial slope) and a permanent part. From the largest compression reached,
# $\varepsilon_p=x_{max}-f(x_{max})/E_0$. Equivalently, from the stress alone: (5.1) is a quadratic in $r$,
# $\sigma r^2+(\sigma(a-2)-E_0\varepsilon_c)r+\sigma=0$, whose smaller root lies on the rising branch and the
# larger on the falling one; then $\varepsilon_p=\varepsilon_c r-\sigma/E_0$. Both forms are coded and
# must agree.
#
# **Tension (5.4).** Linear up to $f_r$ at $\varepsilon_r=f_r/E_0$, then linear softening to zero at
# $\varepsilon_u=2G_f/(f_r l_s)$, i.e. slope $E_s=-E_0/(2E_0G_f/(l_sf_r^2)-1)$. The area under the curve is
# $\tfrac12 f_r\varepsilon_u=G_f/l_s$: a crack band of width $l_s$ dissipates $G_f$ per unit crack area,
# whatever the element size (Bažant–Oh). The slope stays negative only while $l_s<2E_0G_f/f_r^2$; a larger
# band is refused with a message naming $l_s, G_f, f_r, E_0$. A cracked point unloads along the secant to
# the origin (open choice) and recloses without resistance.
#
# **Tension stiffening (Fig. 5, dotted).** Between cracks the bars drag the concrete along; open default:
# a second branch $\alpha_{ts}f_r(\varepsilon_y-\varepsilon)/(\varepsilon_y-\varepsilon_r)$ that vanishes at
# the yield strain $\varepsilon_y$ of the reinforcement; the concrete carries the larger of the two. The paper
# speaks of a "superposition" of softening and stiffening. Read as a sum, a point just past cracking would
# carry $f_r(1+\alpha_{ts})$ — more than its strength — so we read it as the envelope of the two (the max),
# which is continuous at $f_r$ only in the limit and never exceeds $f_r$. Where it acts is a modelling
# choice the paper leaves open: on every cracked layer (`tension_stiffening="all"`, the default) or only in
# the effective tension area around the bars, $h_{c,ef}=\min(2.5(h-d),(h-x)/3,h/2)$ (MC2010, EC2 7.3.2;
# `ssi.elements.section.with_crack_spacing_band(..., tension_stiffening="effective_area")`), outside which the
# concrete softens as plain concrete. Chapter 08 scores both against every measured point of a beam.
#
# **Cracked shear (Fig. 6).** $G_c=\beta G$, $\beta=\beta_0(1-\varepsilon_{max}/\varepsilon_y)$ after
# cracking, never below a floor $\beta_{floor}$ that keeps the matrix regular. $\beta$ is taken from the crack
# state committed at the start of the increment (see `ssi/materials/concrete.py` for why).
#
# **Steel (§5.4).** Bilinear: $E_s$ to $f_y$, then hardening $E_H$; unloading with $E_s$ (linear kinematic
# hardening with plastic modulus $H=E_sE_H/(E_s-E_H)$ produces exactly this curve).
#
# | paper | code (`params` of `ssi.materials.rc.concrete_params`) | meaning |
# |---|---|---|
# | $E_0$ | `E0` | initial modulus |
# | $f_c$, $\varepsilon_c$ | `fc`, `eps_c` | compressive strength and its strain (magnitudes) |
# | $\varepsilon_{cu}$ | `eps_cu` | crushing strain (open, 0.0035) |
# | $G_c$ | `Gc` | compressive fracture energy beyond $\varepsilon_{cu}$ (regularised crushing) |
# | $f_r$, $G_f$, $l_s$ | `fr`, `Gf`, `ls` | tensile strength, fracture energy, crack band width |
# | $\alpha_{ts}$ | `alpha_ts` | tension stiffening factor (open, 0.5) |
# | $\varepsilon_y$ | `eps_y` | yield strain of the bars crossing the crack |
# | $\beta_0$, floor | `beta0`, `beta_floor` | shear retention (open, 0.25 and 1e-4) |
# | $E_s$, $f_y$, $E_H$ | `Es`, `fy`, `EH` (`steel_params`) | steel |

# %%
import inspect
import time

import matplotlib.pyplot as plt
import numpy as np

from ssi.core.protocol import CONSISTENT
from ssi.lab import report
from ssi.lab.verify import fd_jacobian
from ssi.materials import concrete, rc
from ssi.materials.layer_laws import CONCRETE, N_LAYER_HIST, STEEL, layer_update

t_start = time.perf_counter()
FC, FY = 36.2e6, 333.0e6  # the substitute beam of chapter 08
des = rc.designer_concrete(FC)  # fib MC2010 designer values from fc alone
EPS_Y = FY / 200e9
LS = 0.15  # a crack band width of a coarse strip mesh [m]
p_c = rc.concrete_params(FC, des["E0"], des["eps_c"], des["fr"], des["Gf"], LS, EPS_Y)
p_plain = rc.concrete_params(FC, des["E0"], des["eps_c"], des["fr"], des["Gf"], LS, EPS_Y, alpha_ts=0.0)
p_s = rc.steel_params(FY, 200e9, 2e9)
E0, FR, GF = des["E0"], des["fr"], des["Gf"]
print({k: f"{v:.4g}" for k, v in des.items()})
print(f"snap-back limit 2 E0 Gf / fr^2 = {rc.snap_back_limit(E0, GF, FR):.3f} m")

# %% [markdown]
# The kernel, printed from the library (the chapter never retypes it). Its constants -- the functions of the
# parameters alone -- are computed apart, so that the plate strip computes them once per layer rather than at
# each of its layer points:

# %%
print(inspect.getsource(concrete.concrete_constants.py_func))
print(inspect.getsource(concrete.concrete_update_with.py_func))

# %% [markdown]
# ## Driving the points along strain paths

# %%
ec, ecu = des["eps_c"], des["eps_cu"]
path_c = np.concatenate(
    [
        np.linspace(0, -0.6 * ec, 40),
        np.linspace(-0.6 * ec, -0.1 * ec, 20),
        np.linspace(-0.1 * ec, -1.3 * ec, 60),
        np.linspace(-1.3 * ec, 0.0, 40),
        np.linspace(0.0, -1.5 * ecu, 80),
    ]
)
sig_c = rc.drive(CONCRETE, p_c, path_c)[0]

eps_r = FR / E0
eps_u = 2 * GF / (FR * LS)
path_t = np.unique(np.concatenate([np.linspace(0.0, 1.2 * EPS_Y, 1500), [eps_r, eps_u, EPS_Y]]))
sig_soft = rc.drive(CONCRETE, p_plain, path_t)[0]
sig_ts = rc.drive(CONCRETE, p_c, path_t)[0]
cyc = np.concatenate(
    [np.linspace(0, 3 * eps_r, 30), np.linspace(3 * eps_r, 0, 20), np.linspace(0, 6 * eps_r, 40)]
)
sig_cyc = rc.drive(CONCRETE, p_c, cyc)[0]

# shear retention from the committed crack strain: drive eps, then read g_t for the next increment
beta = np.empty_like(path_t)
h_old = np.zeros(N_LAYER_HIST)
h_new = np.zeros(N_LAYER_HIST)
for i, e in enumerate(path_t):
    layer_update(CONCRETE, p_c, e, 0.0, h_old, h_new, CONSISTENT)
    h_old[:] = h_new
    beta[i] = layer_update(CONCRETE, p_c, e, 1e-6, h_old, h_new, CONSISTENT)[3] / (E0 / (2 * 1.2))

ey_s = FY / 200e9
path_s = np.concatenate(
    [
        np.linspace(0, 5 * ey_s, 50),
        np.linspace(5 * ey_s, -4 * ey_s, 90),
        np.linspace(-4 * ey_s, 6 * ey_s, 100),
    ]
)
sig_s = rc.drive(STEEL, p_s, path_s)[0]

# %% [markdown]
# ## Verification

# %%
TOL_EXACT = 1e-12  # identities of rational / piecewise-linear functions: round-off only
TOL_ROOT = 1e-9  # the quadratic-root form of (5.3) loses digits near the peak (double root)
TOL_FD = 1e-6  # central differences, h = 1e-9: truncation and round-off both below 1e-6 of the tangent

f, df0 = concrete.compression_envelope(0.0, E0, FC, ec, ecu)
assert abs(df0 - E0) <= TOL_EXACT * E0
f, dfc = concrete.compression_envelope(ec, E0, FC, ec, ecu)
assert abs(f - FC) <= TOL_EXACT * FC and abs(dfc) <= TOL_EXACT * E0

worst_53 = 0.0
for x in np.linspace(0.05, 1.55, 31) * ec:
    s, _ = concrete.compression_envelope(x, E0, FC, ec, ecu)
    a = concrete.irreversible_strain(x, E0, FC, ec, ecu)
    b = concrete.irreversible_strain_from_stress(s, x > ec, E0, FC, ec)
    worst_53 = max(worst_53, abs(a - b) / ec)
assert worst_53 <= TOL_ROOT, worst_53

# unloading along E0: on the unloading branch the slope is E0
i_unl = 40 + 20 + 60 + 5
assert abs((sig_c[i_unl + 1] - sig_c[i_unl]) / (path_c[i_unl + 1] - path_c[i_unl]) - E0) <= 1e-9 * E0

energy = np.sum(0.5 * (sig_soft[1:] + sig_soft[:-1]) * np.diff(path_t))
crack_band_energy = abs(energy - GF / LS) / (GF / LS)
assert crack_band_energy <= 1e-10, crack_band_energy
report.record(
    "crack_band_energy",
    "relative error of the dissipated energy vs Gf/ls (material point)",
    crack_band_energy,
    1e-10,
    crack_band_energy <= 1e-10,
)

# crushing: no cliff at eps_cu, and Gc / ls dissipated beyond it (the path is piecewise linear there; the one
# step straddling eps_cd limits the trapezoid sum to ~1/n_steps)
f_cu, eps_cd = concrete.crushing_end(E0, FC, ec, ecu, p_c[concrete.P_GC], LS)
path_cr = -np.linspace(ecu, 1.05 * eps_cd, 20001)
sig_cr = rc.drive(CONCRETE, p_c, path_cr)[0]
crush_energy = abs(np.trapezoid(-sig_cr, -path_cr) / (p_c[concrete.P_GC] / LS) - 1)
print(
    f"crushing: f(eps_cu) = {f_cu / FC:.3f} fc, stress reaches zero at {eps_cd:.4f}; "
    f"energy error {crush_energy:.1e}"
)
assert abs(sig_cr[0] + f_cu) <= 1e-6 * FC and crush_energy <= 1e-3, crush_energy

try:
    rc.concrete_params(FC, E0, ec, FR, GF, 1.01 * rc.snap_back_limit(E0, GF, FR), EPS_Y)
    raise AssertionError("snap-back crack band accepted")
except ValueError as err:
    message = str(err)
    assert all(w in message for w in ("ls", "Gf", "fr", "E0")), message
    print("refused:", message)

# tension stiffening and shear retention vanish at steel yield (only plain softening is left beyond eps_y)
assert np.all(sig_ts[path_t >= EPS_Y] == sig_soft[path_t >= EPS_Y])
assert np.all(np.abs(beta[path_t >= EPS_Y] - 1e-4) <= 1e-12)

# steel: plateau slope EH, unloading slope Es, no shear
assert abs((sig_s[40] - sig_s[30]) / (path_s[40] - path_s[30]) - 2e9) <= 1e-6 * 2e9
assert abs((sig_s[55] - sig_s[52]) / (path_s[55] - path_s[52]) - 200e9) <= 1e-9 * 200e9


def fd_error(kind, params, eps, hist):
    h0 = np.zeros(N_LAYER_HIST)
    h0[: len(hist)] = hist
    h1 = np.zeros(N_LAYER_HIST)
    _s, _t, e_t, g_t = layer_update(kind, params, eps, 1e-4, h0, h1, CONSISTENT)
    # d sig / d eps and d tau / d gam by central differences (step 1e-9) at (eps, gam = 1e-4)
    jac = fd_jacobian(
        lambda x: layer_update(kind, params, x[0], x[1], h0, h1, CONSISTENT)[:2], [eps, 1e-4], 1e-9
    )
    e_fd, g_fd = jac[0, 0], jac[1, 1]
    return max(abs(e_fd - e_t) / max(abs(e_t), 1e-3 * E0), abs(g_fd - g_t) / max(abs(g_t), 1e-6 * E0))


branches = {
    "elastic tension": (CONCRETE, p_c, 0.5 * eps_r, ()),
    "ascending (5.1)": (CONCRETE, p_c, -0.5 * ec, ()),
    "descending (5.1)": (CONCRETE, p_c, -1.3 * ec, (1.2 * ec,)),
    "unloading along E0": (CONCRETE, p_c, -0.8 * ec, (1.2 * ec,)),
    "softening (5.4)": (CONCRETE, p_plain, 0.5 * (eps_r + eps_u), (0.0, 1.5 * eps_r)),
    "tension stiffening": (CONCRETE, p_c, 0.6 * EPS_Y, (0.0, 0.5 * EPS_Y)),
    "secant unloading": (CONCRETE, p_c, 0.3 * EPS_Y, (0.0, 0.5 * EPS_Y)),
    "crushed": (CONCRETE, p_c, -0.5 * ec, (1.1 * ecu,)),
    "steel elastic": (STEEL, p_s, 0.5 * ey_s, ()),
    "steel hardening": (STEEL, p_s, 3 * ey_s, ()),
    "steel unloading": (STEEL, p_s, 2 * ey_s, (2 * ey_s,)),
}
fd = {name: fd_error(*args) for name, args in branches.items()}
for name, err in fd.items():
    print(f"FD tangent check {name:22s} {err:.1e}")
    assert err <= TOL_FD, (name, err)
print(f"both forms of (5.3) agree to {worst_53:.1e} eps_c; energy error {crack_band_energy:.1e}")

# %% [markdown]
# ## Figures

# %%
fig, ax = plt.subplots(1, 3, figsize=(14, 4))
ax[0].plot(-path_c * 1e3, -sig_c / 1e6, "k-")
ax[0].axhline(FC / 1e6, ls=":", c="grey")
ax[0].set(
    xlabel="compressive strain [‰]",
    ylabel="compressive stress [MPa]",
    title="compression (5.1), unloading along $E_0$",
)
ax[1].plot(path_t * 1e3, sig_soft / 1e6, label=f"crack band, $l_s$ = {LS} m")
ax[1].plot(path_t * 1e3, sig_ts / 1e6, "--", label=r"with tension stiffening $\alpha_{ts}$ = 0.5")
ax[1].plot(cyc * 1e3, sig_cyc / 1e6, ":", c="k", lw=1, label="unloading: secant")
ax[1].axvline(EPS_Y * 1e3, c="grey", lw=0.8)
ax[1].text(EPS_Y * 1e3, 0.9 * FR / 1e6, r" $\varepsilon_y$")
ax[1].set(xlabel="tensile strain [‰]", ylabel="stress [MPa]", title="tension (Fig. 5)")
ax[1].legend(fontsize=8)
ax[2].plot(path_s * 1e3, sig_s / 1e6, "k-")
ax[2].set(xlabel="strain [‰]", ylabel="stress [MPa]", title="steel, bilinear ($E_H$ = 2 GPa)")
fig.tight_layout()
report.save_figure(fig, "fig05_concrete_steel_laws")
plt.show()

# %% [markdown]
# **Figure 3.1** (the paper's Fig. 5 redrawn, with the steel law). Left: eq. (5.1) driven through an
# unload–reload cycle — unloading is parallel to $E_0$, leaving the irreversible strain (5.3); the last leg
# crushes at $\varepsilon_{cu}$. Middle: tension, linear to $f_r$, crack-band softening (5.4) and the
# tension-stiffening branch that ends at the bars' yield strain; the dotted cycle unloads along the secant.
# Right: bilinear steel with hardening, unloading with $E_s$.

# %%
fig, ax = plt.subplots(figsize=(5, 3.5))
ax.plot(path_t * 1e3, beta, "k-")
ax.set(
    xlabel="largest tensile strain [‰]",
    ylabel=r"$\beta = G_c/G$",
    yscale="log",
    title="cracked shear modulus (Fig. 6)",
)
ax.axvline(EPS_Y * 1e3, c="grey", lw=0.8)
report.save_figure(fig, "fig06_shear_retention")
plt.show()

# %% [markdown]
# **Figure 3.2** (the paper's Fig. 6 redrawn). Shear retention after cracking: $\beta_0=0.25$ falling
# linearly to the floor $10^{-4}$ at the steel yield strain (log scale to show the floor).
#
# ## Summary
#
# * Eq. (5.1) has peak $f_c$ at $\varepsilon_c$, initial slope $E_0$ and zero slope at the peak (to
#   round-off); both forms of (5.3) agree; unloading runs along $E_0$.
# * The crack band dissipates $G_f/l_s$ per unit volume (report row `crack_band_energy`); a band at or
#   beyond $2E_0G_f/f_r^2$ is refused.
# * Every branch of both laws has an exact tangent (FD checks above).

# %%
print(f"chapter 03 ran in {time.perf_counter() - t_start:.1f} s")
