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
# # 10 — Bearing capacity: Mohr–Coulomb soil against Prandtl and a peer code (paper §7, §8)
#
# The paper models the subsoil with Mohr–Coulomb plasticity (cohesion c, friction angle φ) and a
# non-associated flow rule whose potential has the dilation angle ψ in place of φ (§7, eq. 6.9), integrated
# by increments Δσ = D_ep Δε and solved by modified Newton–Raphson (§8). It shows no bearing-capacity test.
# This chapter verifies the soil law inside the Q8 element against the strongest references that exist: the
# exact Prandtl collapse pressure of a strip footing on weightless soil and the recorded load–settlement
# curve of Smith & Griffiths' Program 6.1 — and then measures what the paper's choices cost.
#
# **In this chapter you will**
# - recall the two integration schemes of the soil law (the paper's explicit D_ep scheme and the implicit
#   return mapping in principal stresses) and the displacement-controlled footing test;
# - push rigid smooth and rough footings into weightless soil with φ = 0 and φ = 20° and compare the limit
#   pressure with Prandtl's q_u = c·N_c on three meshes (the error must shrink; ≤ 3 % on the named mesh);
# - reproduce the Smith & Griffiths flexible-footing curve within 3 % up to 500 kPa, and see why the yield
#   function (von Mises vs Tresca) matters before collapse;
# - follow the associated, the Davis-mode and the user's ψ = 0 footing on the controlled path, and report
#   the ψ = 0 value as what it is: a path estimate with its spread, between the Davis value and the
#   associated ceiling;
# - plot the trade: explicit vs implicit integration, full vs modified Newton, step size — error vs wall time.

# %% [markdown]
# ## Theory
#
# **Yield function and potential.** With principal stresses ordered σ₁ ≥ σ₂ ≥ σ₃ (tension positive),
#
# $$f = k\,\sigma_1 - \sigma_3 - 2c\sqrt{k},\quad k = \frac{1+\sin\varphi}{1-\sin\varphi};\qquad
#   g = m\,\sigma_1 - \sigma_3,\quad m = \frac{1+\sin\psi}{1-\sin\psi}.$$
#
# In principal-stress space f = 0 is a six-sided pyramid with its apex at the hydrostatic tension c·cot φ
# (φ > 0); φ = 0 gives Tresca's prism. The out-of-plane stress σ_yy is carried, so each of the three principal
# stresses can be the largest or the smallest.
#
# **Explicit tangent scheme (the paper).** Split off the elastic part of the increment up to f = 0, then
# Δσ = D_ep Δε with D_ep = D − D b aᵀ D / (aᵀ D b), a = ∂f/∂σ, b = ∂g/∂σ at the current stress (eq. 6.9),
# optionally in n_sub sub-steps and with a drift correction back to f = 0. Without the correction the stress
# leaves the surface wherever the principal axes rotate.
#
# **Implicit return mapping.** The trial stress σ_B = σ_n + D Δε is returned along D b to the closest
# admissible feature of the pyramid in principal space — a face, one of the two edges next to it, or the
# apex — by one linear solve each (the faces are planes and isotropic elasticity keeps the principal axes).
# Its consistent tangent adds the rotation of the principal axes and is unsymmetric when ψ ≠ φ. Both schemes
# live in `ssi/materials/mc_implicit_scheme.py` and `mc_explicit_scheme.py` (one surface,
# `mc_surface.py`); their material-point checks (every branch, finite-difference
# tangents, symmetry only for ψ = φ) are in `tests/test_mohr_coulomb.py` and chapter 05.
#
# **Prandtl's collapse pressure** of a strip footing on weightless soil (smooth or rough base — for γ = 0 both
# give the same value):
#
# $$N_q = e^{\pi\tan\varphi}\tan^2(45^\circ+\varphi/2),\qquad N_c = (N_q-1)\cot\varphi
#   \ (=2+\pi\ \text{for}\ \varphi=0),
#   \qquad q_u = c\,N_c + q\,N_q .$$
#
# It is exact for associated flow (ψ = φ). With ψ < φ no exact value exists; displacement-based FE gives
# lower limit loads (de Borst & Vermeer 1984; Loukidis & Salgado 2009).
#
# **The footing test.** By symmetry, half of the footing (0 ≤ x ≤ B/2) on a block x ∈ [0, 6 m], z ∈ [−5 m, 0]
# (u = 0 on x = 0 and x = 6 m, base fixed): for φ ≤ 20° the Prandtl mechanism stays within ≈ 3.5 m of the axis
# and ≈ 2 m deep. The footing nodes get a prescribed settlement (displacement control); a rough base also
# holds u = 0 there. The pressure is q = 2R/B from the reaction R. Elements are h wide under the footing and
# grow by 1.25 up to 1 m. The Prandtl pushes follow the controlled path (`Settings(control="work")`,
# chapter 06; with a prescribed settlement and no force load its control is the settlement itself) in steps
# of at most 1/30 of the push, ending where the pressure stays on a plateau or at the full settlement. The
# trade study below also uses full Newton with the consistent tangent and a backtracking line search on
# fixed settlement increments (`Settings(method="full", line_search=True)`:
# `ssi.lab.bearing_capacity.footing_settings()`; `push_footing`'s default is the controlled path): plain
# Newton steps near the footing corner overshoot into a far plastic state and diverge.
#
# | paper / text | code | meaning |
# |---|---|---|
# | c, φ, ψ | `c`, `phi_deg`, `psi_deg` | cohesion [Pa], friction and dilation angles [°] |
# | k, m | `k`, `m` in `mc_constants` | slopes of f and g in principal space |
# | D_ep (eq. 6.9) | `_continuum_dep` | continuum elasto-plastic matrix (explicit scheme) |
# | σ_B, Δλ | `sB`, `dl` in `mc_return_principal` | trial stress, plastic multiplier |
# | B, q_u | `B`, `q_u` | footing width, limit (collapse) pressure |
# | h | `h_fine` | element size under the footing |

# %%
import time

import matplotlib.pyplot as plt
import numpy as np

from ssi.lab import paths, report
from ssi.lab.bearing_capacity import (
    CHAPTER10_FOOTING,
    chapter10_footing,
    footing_pressure,
    footing_settings,
    prandtl,
    push_footing,
    sg61_scene,
)
from ssi.lab.digitize import read_reference
from ssi.lab.verify import convergence_rate
from ssi.solver import NonConvergence, Settings, run

FAST = paths.FAST
# the footing test above, `ssi.lab.bearing_capacity.chapter10_footing`: B = 2 m, c = 10 kPa, phi = 20° unless
# varied, E = 20 MPa and nu = 0.3 (the limit load does not depend on them), the 6 m x 5 m half block
C = CHAPTER10_FOOTING["c"]  # cohesion [Pa]
MESHES = [0.5, 0.25] if FAST else [0.25, 0.125, 0.0625]  # element size under the footing [m]
H_NAMED = 0.0625  # the mesh on which the 3 % claim is made (16 elements under the half footing)
TOL_PRANDTL = 0.03  # issue 4: within 3 % of the exact value on the named mesh
SETTLE = {0.0: 0.04, 20.0: 0.06}  # settlement [m] at the end of the push (the curve has levelled off)
N_STEPS = 30
# the Prandtl pushes on the controlled path, steps of at most 1/N_STEPS of the push (so that "levelled off"
# below compares steps as far apart as 30 equal increments would). Measured on this machine (CPU, full mode,
# 2026-12-04): the 12 pushes 6.4 s against 35 s with full Newton in 30 increments, the same errors to
# 0.06 percentage points (the controlled path stops on the plateau, at 2.9-5 cm on h = 0.0625 m, where the
# pressure of these meshes still creeps up by < 0.2 %)
PRANDTL_SETTINGS = Settings(
    control="work", symmetric_tangent=True, backend="superlu", first_step=1 / N_STEPS, max_step=1 / N_STEPS
)
CASES = [(0.0, False), (0.0, True), (20.0, False), (20.0, True)]
print("fast mode" if FAST else "full mode", "meshes h =", MESHES)

# %% [markdown]
# ## Prandtl: smooth and rough rigid footings, φ = 0 and φ = 20°

# %%
prandtl_runs = {}
t_all = time.perf_counter()
for phi, rough in CASES:
    q_exact = prandtl(C, phi)[0]
    for h in MESHES:
        # psi = phi on purpose: Prandtl's value is exact for associated flow only (a SoilLayer's default
        # is psi = 0)
        scene = chapter10_footing(phi_deg=phi, psi_deg=phi, rough=rough, h_fine=h, settle=SETTLE[phi])
        out = push_footing(scene, n_steps=1, settings=PRANDTL_SETTINGS)
        if out["failure"]:
            raise RuntimeError(f"phi={phi} rough={rough} h={h}: {out['failure']}")
        out["err"] = out["q_u"] / q_exact - 1.0
        out["n_dof"] = scene.info["n_dof"]
        prandtl_runs[phi, rough, h] = out
        print(
            f"phi={phi:4.0f}  {'rough ' if rough else 'smooth'}  h={h:6.4f}  DOFs={out['n_dof']:5d}  "
            f"q_u={out['q_u'] / 1e3:7.2f} kPa  exact={q_exact / 1e3:7.2f}  error={100 * out['err']:+6.2f} %  "
            f"iterations={out['n_iterations']:4d}  time={out['wall_time']:5.1f} s"
        )
print(f"all Prandtl runs: {time.perf_counter() - t_all:.1f} s")

# %%
for phi, rough in CASES:
    errs = [prandtl_runs[phi, rough, h]["err"] for h in MESHES]
    rid = f"prandtl_phi{int(phi)}_{'rough' if rough else 'smooth'}"
    if not FAST:
        report.record(
            rid,
            f"q_u,FE/q_u,exact - 1 (h={H_NAMED} m, {prandtl_runs[phi, rough, H_NAMED]['n_dof']} "
            "DOFs, half model)",
            errs[-1],
            TOL_PRANDTL,
            abs(errs[-1]) <= TOL_PRANDTL and all(abs(a) > abs(b) for a, b in zip(errs, errs[1:])),
        )
    slope = convergence_rate(MESHES, np.abs(errs))
    print(f"{rid:22s} errors {', '.join(f'{100 * e:+.2f} %' for e in errs)}   fitted order {slope:.2f}")

# %% [markdown]
# ## Smith & Griffiths, Program 6.1: a flexible footing on undrained clay
#
# The peer's yield function is √J₂ = c_u (von Mises matched in plane strain), so this regression runs the
# von Mises law of `ssi.materials.soil_laws` (`VON_MISES`) on the peer's 8 × 4 mesh and pressures. The same
# mesh with Tresca (Mohr–Coulomb, φ = 0) is shown beside it: both collapse at the same pressure, but before
# collapse the out-of-plane stress is not the mean of the in-plane ones, so the two laws yield at different
# points and their settlements differ by several per cent.

# %%
_, ref = read_reference("smith_griffiths_p61.csv")
q_ref, d_ref = ref["q_kPa"], ref["delta_m"]
path = [
    50.0,
    100.0,
    150.0,
    200.0,
    250.0,
    300.0,
    350.0,
    400.0,
    425.0,
    450.0,
    465.0,
    480.0,
    490.0,
    500.0,
    505.0,
    510.0,
    515.0,
    519.0,
]
sg = {}
for law in ("von_mises", "tresca"):
    scene = sg61_scene(law)
    t0 = time.perf_counter()
    try:
        res = run(scene.model, path, Settings(method="full", backend="superlu", max_iter=100))
        stop = None
    except NonConvergence as err:
        res, stop = err.result, err.report
    lf = np.array(res.load_factor)
    w = res.displacement(scene.footing, "w")[:, 0]
    sg[law] = dict(q=lf, w=w, time=time.perf_counter() - t0, iterations=res.iterations, stop=stop)
    print(f"{law}: {time.perf_counter() - t0:.2f} s, iterations per step {res.iterations[1:]}, stop: {stop}")
print(" q [kPa]   peer [mm]   von Mises [mm]  error    Tresca [mm]  difference")
sg_err = []
for q, d in zip(q_ref, d_ref):
    row = [f"{q:7.0f}  {1e3 * d:10.3f}"]
    for law in ("von_mises", "tresca"):
        i = np.flatnonzero(np.isclose(sg[law]["q"], q))
        wv = sg[law]["w"][i[0]] if len(i) else np.nan
        row.append(f"{1e3 * wv:12.3f}  {100 * (wv / d - 1):+6.2f} %")
        if law == "von_mises" and q <= 500.0:
            sg_err.append(abs(wv / d - 1))
    print("   ".join(row))
SG_TOL = 0.03  # issue 4: within 3 % at every pressure up to 500 kPa
sg_max = max(sg_err)
report.record(
    "sg61",
    "max |settlement/peer - 1| for q <= 500 kPa (von Mises, peer mesh)",
    sg_max,
    SG_TOL,
    sg_max <= SG_TOL,
)
print(f"largest relative settlement error up to 500 kPa: {100 * sg_max:.2f} %")

# %% [markdown]
# ## Non-associated flow: no unique limit, so three answers
#
# With ψ < φ the plastic flow is not normal to the yield surface: Drucker's stability postulate fails, the
# bound theorems of limit analysis no longer hold, and the rate-independent increment can lose uniqueness
# before any peak (de Borst & Vermeer 1984; Loukidis & Salgado 2009). The ψ = 0 footing shows it: near the
# footing's edge single points flip between elastic and plastic from one iterate to the next, the residual
# stagnates for every Newton variant, and what a push reports depends on its steps, its mesh and round-off.
# Earlier versions of this chapter pushed it viscoplastically (Duvaut–Lions), relaxed the end of the path and
# asked for a ψ = 0 plateau independent of the step count on every mesh (rows `psi0_limit_h0125` and
# `psi0_step_independence`). That request was ill-posed (issue 31): a non-associated "limit" belongs to the
# path, not to the material, and a regularisation tuned until it looks unique measures the regularisation.
# This chapter therefore computes, side by side on one controlled path (next section):
#
# - the **associated** footing (ψ = φ): a unique limit, checked against Prandtl and the limit-analysis
#   bracket; its upper bound UB_assoc is a rigorous ceiling for every ψ ≤ φ (the flow rule cannot make the
#   material stronger than its associated twin, Radenković's first theorem);
# - the **Davis** footing (`Settings(flow="davis")`): associated flow with Davis' reduced strength, the
#   conventional capacity of the non-associated soil (row `footing_davis_peak`);
# - the **user's ψ = 0** as a *path estimate*: the largest pressure of its controlled path, reported with its
#   spread under the perturbations issue 31 names — step budget 20, 40 and 80, E × (1 + 1e-13), and the
#   mesh — and checked to lie between 0.97 × the Davis value and 1.03 × UB_assoc. The rows
#   `psi0_limit_h0125` and `psi0_step_independence` keep their ids and now hold this estimate and its spread:
#   they are the replacement of the viscous rows.

# %% [markdown]
# ## The controlled path: associated, Davis and ψ = 0 footings
#
# `Settings(control="work")` follows the path on a control that keeps rising through a limit point (here,
# with the settlement prescribed, the settlement itself; with force loads the work of the reference load,
# `ssi/solver/path.py`), with one corrector (Newton on a lagged factorisation of the consistent tangent,
# L-BFGS on that factor, a line search) and a step that grows or shrinks with the iteration count. It
# declares a limit only where the pressure passes a maximum and falls, or stays on a plateau (rising less
# than 0.2 % over at least 10 steps and half the settlement reached there) — never where an increment
# fails: that is a `NonConvergence`. The peak is reported with its numerical uncertainty: the steps
# around it redone at half size. `Settings(flow="davis")` solves the same footing associated with Davis'
# reduced strength
# c* = βc, tan φ* = β tan φ, β = cos ψ cos φ / (1 − sin ψ sin φ) (= cos φ for ψ = 0): a convex problem per
# increment whose limit is the conventional capacity of the non-associated soil.
#
# Checks: the associated peak on the named mesh within 3 % of Prandtl and inside the limit-analysis bracket
# (`ssi.limit`, chapter 17) of the same footing, and step-independent (at most 20, 40 or 80 steps to the
# full settlement agree to 0.5 %); the Davis peaks on three meshes converge towards Prandtl's value of the
# reduced material. The user's ψ = 0 is run on each mesh with a 20-step budget; on h = 0.25 and 0.125 m
# (fast mode: 0.5 m) also with 40 and 80 steps and with E × (1 + 1e-13) (the round-off perturbation of the
# zoo's `roundoff_limits`). A run that ends in a `NonConvergence` gives no estimate: its largest pressure is
# only where the path stopped. The claims (full mode): on h = 0.125 m every perturbed run gives an estimate,
# each inside [0.97 × the Davis-mode peak of the same mesh, 1.03 × UB_assoc] (row `psi0_limit_h0125`); the
# spread of the estimates on each of the two meshes is at most 2 %, issue 31's bound for a ψ < φ limit under
# round-off (row `psi0_step_independence`). Neither tolerance is fitted to these runs: the band is issue 31's
# [0.97 LB_Davis, 1.03 UB_assoc] for every incremental limit with the Davis-mode peak of the same mesh in
# place of LB_Davis (it carries the same discretisation error as the estimate and lies above LB_Davis, so
# the band is the narrower one), and the 2 % is issue 31's bound for non-associated limits.

# %%
from ssi.limit import Interface as LimitInterface  # noqa: E402
from ssi.limit import Material as LimitMaterial  # noqa: E402
from ssi.limit import adaptive, strip_site, triangulate  # noqa: E402
from ssi.materials.soil_laws import davis_beta  # noqa: E402

CTRL_MESHES = [0.5, 0.25] if FAST else [0.25, 0.125, 0.0625]  # element size under the footing [m]
CTRL_H = CTRL_MESHES[-1]  # the named mesh of footing_assoc_peak (h = 0.0625 m in full mode)
CTRL_STEPS = [20, 40] if FAST else [20, 40, 80]  # the step budgets: the largest step is 1/n of the push
STEP_AGREE = 0.005  # issue 31: the peaks of 20, 40 and 80 steps agree to 0.5 %
PSI0_SPREAD_TOL = 0.02  # issue 31 (roundoff_limits): a user psi < phi limit moves by at most 2 %
BRACKET_GAP = 0.03  # requested (UB-LB)/(UB+LB) of the limit-analysis bracket (full mode)
q_p20 = prandtl(C, 20.0)[0]  # Prandtl's q_u of the phi = 20 deg footing [Pa]
beta = davis_beta(20.0, 0.0)
phi_star = float(np.degrees(np.arctan(beta * np.tan(np.radians(20.0)))))
q_davis = prandtl(beta * C, phi_star)[0]  # Prandtl's value of the reduced (Davis) material [Pa]
print(f"Davis: beta = {beta:.4f}, c* = {beta * C / 1e3:.3f} kPa, phi* = {phi_star:.3f} deg, "
      f"Prandtl(c*, phi*) = {q_davis / 1e3:.2f} kPa = {q_davis / q_p20:.4f} x Prandtl(c, phi)")  # fmt: skip


def controlled_push(h, n_steps=20, psi_deg=None, flow="user", E=CHAPTER10_FOOTING["E"]):
    """Chapter 10's rough phi = 20 deg footing pushed to 6 cm on the controlled path, the largest step 1/n of
    the push; ``psi_deg`` None: associated; ``E`` [Pa] the soil's modulus (perturbed by round-off below).
    Returns the push's dict (settlement [m], q [Pa], peak q_u [Pa], the solver result, failure)."""
    scene = chapter10_footing(
        phi_deg=20.0, psi_deg=20.0 if psi_deg is None else psi_deg, h_fine=h, settle=SETTLE[20.0], E=E
    )
    symmetric = psi_deg is None or flow == "davis"  # associated (or Davis) soil: symmetric tangent
    settings = Settings(
        control="work", flow=flow, backend="superlu", symmetric_tangent=symmetric,
        first_step=min(0.1, 1.0 / n_steps), max_step=min(0.25, 1.0 / n_steps),
    )  # fmt: skip
    t0 = time.perf_counter()
    failure = None
    try:
        res = run(scene.model, [1.0], settings)
    except NonConvergence as err:
        res, failure = err.result, err.report
    s, q = footing_pressure(scene, res)
    return dict(
        settlement=s, q=q, q_u=float(q.max()), result=res, failure=failure, n_dof=scene.info["n_dof"],
        wall_time=time.perf_counter() - t0,
    )  # fmt: skip


ctrl = {}
for n in CTRL_STEPS:
    ctrl["assoc", CTRL_H, n] = controlled_push(CTRL_H, n)
for h in CTRL_MESHES:
    ctrl["davis", h, 20] = controlled_push(h, 20, psi_deg=0.0, flow="davis")
# the user's psi = 0: every mesh with the 20-step budget; the perturbed runs on the meshes of PSI0_SPREAD
PSI0_SPREAD = CTRL_MESHES[:1] if FAST else CTRL_MESHES[:2]  # h = 0.5 m (fast), 0.25 and 0.125 m (full)
E_ROUNDOFF = CHAPTER10_FOOTING["E"] * (1.0 + 1e-13)  # issue 31's round-off perturbation of E [Pa]
for h in CTRL_MESHES:
    for n in CTRL_STEPS if h in PSI0_SPREAD else CTRL_STEPS[:1]:
        ctrl["psi0", h, n] = controlled_push(h, n, psi_deg=0.0)
    if h in PSI0_SPREAD:
        ctrl["psi0_E", h, CTRL_STEPS[0]] = controlled_push(h, CTRL_STEPS[0], psi_deg=0.0, E=E_ROUNDOFF)
for (kind, h, n), out in ctrl.items():
    r = out["result"]
    unc = "-" if r.limit_uncertainty is None else f"{r.limit_uncertainty:.1e}"
    print(
        f"{kind:6s} h={h:6.4f} ({out['n_dof']:4d} DOFs) <= {n:2d}-step budget: {r.n_steps:3d} steps, "
        f"{r.factorizations:3d} factorisations, {r.cuts:2d} halvings, {out['wall_time']:5.1f} s; "
        f"q_u = {out['q_u'] / q_p20:.4f} x Prandtl; {r.status}"
        + (f" (uncertainty {unc}; suspect: {r.limit_suspect or 'no'})" if r.collapsed else "")
        + (f"; NonConvergence: {out['failure']['reason']}" if out["failure"] else "")
    )  # fmt: skip

# %%
# the limit-analysis bracket of the same footing (chapter 17's tool): associated, and Davis' material; full
# mode only (4 s even at a 10 % gap: fast mode's budget)
t0 = time.perf_counter()
brackets = {}
for name, soil in (("assoc", LimitMaterial(C, 20.0)), ("davis", LimitMaterial(C, 20.0, psi_deg=0.0).davis())):
    if FAST:
        continue
    site = strip_site(2.0, soil, LimitInterface("rough"))
    brackets[name] = adaptive(site, triangulate(site, 1.0), gap=BRACKET_GAP)
    print(f"{name}: bracket [{brackets[name].lb / q_p20:.4f}, {brackets[name].ub / q_p20:.4f}] x Prandtl")
print(f"brackets: {time.perf_counter() - t0:.1f} s")

# %%
peaks = [ctrl["assoc", CTRL_H, n]["q_u"] for n in CTRL_STEPS]
assoc_err = peaks[0] / q_p20 - 1.0
step_spread = max(peaks) / min(peaks) - 1.0
lb_davis, ub_assoc = (brackets["davis"].lb, brackets["assoc"].ub) if brackets else (np.nan, np.nan)
in_bracket = all(0.97 * lb_davis <= p <= 1.03 * ub_assoc for p in peaks)  # False without a bracket
davis_err = [ctrl["davis", h, 20]["q_u"] / q_davis - 1.0 for h in CTRL_MESHES]


def psi0_estimate(out):
    """q_u / Prandtl(c, phi) of a user's psi = 0 run, or None where it ended in a NonConvergence (a stopped
    path has no estimate: its largest pressure is only where it stopped)."""
    return None if out["failure"] else out["q_u"] / q_p20


psi0_est = {h: {k: psi0_estimate(o) for k, o in ctrl.items() if k[0].startswith("psi0") and k[1] == h}
            for h in CTRL_MESHES}  # fmt: skip
psi0_spread = {}  # max/min - 1 of the estimates of one mesh; inf if a perturbed run gave none
for h in PSI0_SPREAD:
    est = list(psi0_est[h].values())
    psi0_spread[h] = np.inf if None in est else max(est) / min(est) - 1.0
# the band of issue 31 for the estimate: [0.97 x the Davis-mode peak of the same mesh, 1.03 x UB_assoc]
psi0_band = {h: (0.97 * ctrl["davis", h, 20]["q_u"] / q_p20, 1.03 * ub_assoc / q_p20) for h in CTRL_MESHES}
print(f"associated, h = {CTRL_H} m: peak - Prandtl {100 * assoc_err:+.2f} %, spread over {CTRL_STEPS} steps "
      f"{100 * step_spread:.3f} %, inside [0.97 LB_Davis, 1.03 UB_assoc]: "
      f"{'(no bracket in fast mode)' if FAST else in_bracket}")  # fmt: skip
print("Davis peak / Prandtl(c*, phi*) - 1 on h =", CTRL_MESHES, ":", [f"{100 * e:+.2f} %" for e in davis_err])


def psi0_text(key, est):
    """One run's estimate, or where its path stopped."""
    if est is not None:
        return f"{key[0]} {key[2]}: {est:.4f}"
    out = ctrl[key]
    where = f"{100 * out['settlement'][-1]:.2f} cm, q {out['q_u'] / q_p20:.4f}"
    return f"{key[0]} {key[2]}: none (stopped at {where})"


for h in CTRL_MESHES:
    runs = ", ".join(psi0_text(k, e) for k, e in psi0_est[h].items())
    spread = f"; spread {100 * psi0_spread[h]:.2f} %" if h in psi0_spread else ""
    print(f"psi = 0 path estimate / Prandtl, h = {h} m: {runs}{spread}; band [0.97 Davis, 1.03 UB_assoc] = "
          f"[{psi0_band[h][0]:.4f}, {psi0_band[h][1]:.4f}]")  # fmt: skip

# %%
# no run of the associated or Davis footing may end in a NonConvergence; every limit it reports is backed by
# a peak or a plateau of the pressure (the solver's own rule), never a failure
assert all(ctrl[k]["failure"] is None for k in ctrl if not k[0].startswith("psi0"))
assert step_spread < STEP_AGREE, step_spread
assert all(abs(a) > abs(b) for a, b in zip(davis_err, davis_err[1:]))  # converging towards Prandtl(c*, phi*)
assert all(e > 0.0 for e in davis_err)  # from above, as the displacement method's first-order corner error
if not FAST:
    assert in_bracket
    assert abs(assoc_err) < TOL_PRANDTL
    report.check(
        "footing_assoc_peak",
        f"associated rough footing phi=20, h={CTRL_H} m, controlled path: peak/Prandtl - 1 (20-step budget); "
        f"spread over {CTRL_STEPS} steps {100 * step_spread:.3f} % (<= 0.5 %); inside [0.97 LB_Davis, "
        f"1.03 UB_assoc] = [{0.97 * lb_davis / q_p20:.4f}, {1.03 * ub_assoc / q_p20:.4f}] x Prandtl",
        assoc_err,
        TOL_PRANDTL,
        abs(assoc_err) < TOL_PRANDTL and step_spread < STEP_AGREE and in_bracket,
    )
    report.check(
        "footing_davis_peak",
        f"psi=0 footing in Davis mode: peak / Prandtl(c*={beta * C / 1e3:.3f} kPa, phi*={phi_star:.3f} deg) "
        f"- 1 on h={CTRL_MESHES[-1]} m; on h={CTRL_MESHES} m: "
        f"{', '.join(f'{100 * e:+.2f} %' for e in davis_err)} "
        "(PASS: falling with h, within 3 % on the finest)",
        davis_err[-1],
        TOL_PRANDTL,
        all(abs(a) > abs(b) for a, b in zip(davis_err, davis_err[1:])) and abs(davis_err[-1]) < TOL_PRANDTL,
    )
    est_h0125 = list(psi0_est[0.125].values())
    statuses = sorted({ctrl[k]["result"].status for k in psi0_est[0.125]})
    low, high = psi0_band[0.125]
    finest = ctrl["psi0", CTRL_MESHES[-1], CTRL_STEPS[0]]
    finest_txt = psi0_text(("psi0", CTRL_MESHES[-1], CTRL_STEPS[0]), psi0_estimate(finest))
    report.check(
        "psi0_limit_h0125",
        "replacement of the viscous row: psi=0 rough footing phi=20, h=0.125 m, controlled path (20-step "
        "budget): path estimate q_u/Prandtl; with 40, 80 steps and E x (1+1e-13): "
        f"{', '.join('none' if e is None else f'{e:.4f}' for e in est_h0125)} (spread "
        f"{100 * psi0_spread[0.125]:.2f} %; solver status {statuses}: the estimate is the largest pressure "
        "of the path to 6 cm); PASS: every run an estimate inside [0.97 Davis-mode peak, 1.03 "
        f"UB_assoc] = [{low:.4f}, {high:.4f}] (Davis-mode peak {low / 0.97:.4f})",
        psi0_est[0.125]["psi0", 0.125, CTRL_STEPS[0]] or np.nan,
        0.03,
        None not in est_h0125 and all(low <= e <= high for e in est_h0125),
    )
    report.check(
        "psi0_step_independence",
        "replacement of the viscous row: largest spread (max/min - 1) of the psi=0 path estimates under "
        f"{CTRL_STEPS} steps and E x (1+1e-13) on h = {PSI0_SPREAD} m: "
        + ", ".join(f"{100 * psi0_spread[h]:.2f} %" for h in PSI0_SPREAD)
        + f" (PASS: <= 2 %, issue 31's bound for psi < phi); h = {CTRL_MESHES[-1]} m: {finest_txt}",
        max(psi0_spread.values()),
        PSI0_SPREAD_TOL,
    )

# %%
fig, ax = plt.subplots(figsize=(7, 4.2))
for (kind, h, n), out in ctrl.items():
    if n != CTRL_STEPS[0] or kind == "psi0_E":
        continue
    style = {"assoc": "-", "davis": "--", "psi0": ":"}[kind]
    label = {"assoc": "ψ = φ", "davis": "Davis (ψ = 0)", "psi0": "ψ = 0 (user)"}[kind]
    ax.plot(100 * out["settlement"], out["q"] / q_p20, style, label=f"{label}, h = {h} m")
ax.axhline(1.0, color="k", lw=0.8)
ax.axhline(q_davis / q_p20, color="gray", lw=0.8)
ax.set_xlabel("settlement [cm]")
ax.set_ylabel("q / Prandtl(c, φ)")
ax.legend(fontsize=7)
ax.set_title("controlled path, rough footing φ = 20°")
report.save_figure(fig, "fig10_4_controlled_path")
plt.show()

# %% [markdown]
# *Figure 10.4 — The rough φ = 20° footing on the controlled path: associated (ψ = φ), Davis mode and the
# user's ψ = 0; horizontal lines: Prandtl's value of the material (black) and of Davis' reduced material
# (grey). Each curve ends where the target settlement, a detected limit or an honest NonConvergence ends it.*

# %% [markdown]
# ## The trade: integration scheme, Newton variant, step size
#
# The rough footing with φ = ψ = 20° on the coarse mesh, pushed with 10, 20 or 40 steps. The error is the
# difference from the same mesh's converged implicit result with the finest steps (so it measures the
# integration and solution error, not the discretisation error), relative to Prandtl's value.

# %%
H_TRADE = MESHES[0]
q_p20 = prandtl(C, 20.0)[0]
variants = [
    ("implicit, full Newton", dict(scheme="implicit"), "line_search"),
    ("explicit (paper), full Newton", dict(scheme="explicit"), "line_search"),
    ("explicit, 8 sub-steps + drift corr.", dict(scheme="explicit", n_sub=8, drift=True), "line_search"),
    ("implicit, modified Newton (paper)", dict(scheme="implicit"), "modified"),
]
step_counts = [10, 20] if FAST else [10, 20, 40]
trade = {}
for name, kw, method in variants:
    for n in step_counts:
        if (method == "modified" or "sub-steps" in name) and n != step_counts[-1]:
            continue
        scene = chapter10_footing(h_fine=H_TRADE, settle=SETTLE[20.0], **kw)
        if method == "modified":
            # the paper's algorithm: modified Newton on K0 in the given increments, one halving (with
            # automatic steps and the former viscous fallback: ~3000 increments to the limit, 110 s)
            out = push_footing(
                scene, n_steps=n, settings=Settings.paper(backend="superlu", max_iter=400, max_cuts=1)
            )
        else:
            out = push_footing(scene, n_steps=n, settings=footing_settings())  # full Newton, line search
        trade[name, n] = out
ref_scene = chapter10_footing(h_fine=H_TRADE, settle=SETTLE[20.0])
q_ref_trade = push_footing(ref_scene, n_steps=4 * step_counts[-1], settings=footing_settings())["q_u"]
for (name, n), out in trade.items():
    out["trade_err"] = abs(out["q_u"] - q_ref_trade) / q_p20
    stop = (
        f"  STOPPED: {out['failure']['reason']} at settlement {out['settlement'][-1] * 1e3:.1f} mm"
        if out["failure"]
        else ""
    )
    print(
        f"{name:38s} steps={n:3d}  q_u/Prandtl={out['q_u'] / q_p20:.4f}  error={out['trade_err']:.2e}  "
        f"iterations={out['n_iterations']:5d}  time={out['wall_time']:6.2f} s{stop}"
    )

# %% [markdown]
# ## Verification

# %%
# Prandtl: the error shrinks under refinement in every case; the 3 % claim is made on the named mesh (full
# mode)
for phi, rough in CASES:
    errs = [abs(prandtl_runs[phi, rough, h]["err"]) for h in MESHES]
    assert all(a > b for a, b in zip(errs, errs[1:])), (phi, rough, errs)
    if not FAST:
        assert errs[-1] <= TOL_PRANDTL, (phi, rough, errs)
# each push levelled off: the last two steps differ by < 0.1 % of the pressure (a limit, not a hardening
# curve)
LEVEL_TOL = 1e-3
for key, out in prandtl_runs.items():
    assert abs(out["q"][-1] - out["q"][-2]) <= LEVEL_TOL * out["q"][-1], key
# Smith & Griffiths: within 3 % up to 500 kPa (the peer's own iteration tolerance is 1e-3)
assert sg_max <= SG_TOL, sg_max
# non-associated flow cannot raise the limit load of an associated material (ψ < φ is a weaker material):
# each ψ = 0 estimate lies below the associated push's limit on the same mesh (the Prandtl runs, φ = 20°
# rough, the same footing and settlement)
for h in PSI0_SPREAD:
    for key, est in psi0_est[h].items():
        assert est is not None and est <= prandtl_runs[20.0, True, h]["q_u"] / q_p20 * (1 + LEVEL_TOL), key
assert max(psi0_spread.values()) <= PSI0_SPREAD_TOL, psi0_spread
print("all checks passed")

# %% [markdown]
# ## Figures

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
h_show = MESHES[-1]
for phi, rough in CASES:
    out = prandtl_runs[phi, rough, h_show]
    axes[0].plot(
        1e3 * out["settlement"],
        out["q"] / prandtl(C, phi)[0],
        label=f"φ = {phi:.0f}°, {'rough' if rough else 'smooth'}",
    )
    errs = [abs(prandtl_runs[phi, rough, h]["err"]) for h in MESHES]
    axes[1].loglog(
        MESHES, 100 * np.array(errs), "o-", label=f"φ = {phi:.0f}°, {'rough' if rough else 'smooth'}"
    )
axes[0].axhline(1.0, color="k", lw=0.8)
axes[0].set_xlabel("settlement [mm]")
axes[0].set_ylabel("q / q_u,Prandtl")
axes[0].set_title(f"rigid footing, h = {h_show} m")
axes[0].legend()
axes[1].axhline(100 * TOL_PRANDTL, color="k", ls="--", lw=0.8, label="3 %")
axes[1].set_xlabel("element size under the footing h [m]")
axes[1].set_ylabel("|q_u,FE / q_u,exact − 1| [%]")
axes[1].legend()
report.save_figure(fig, "fig10_1_prandtl")
plt.show()

# %% [markdown]
# *Figure 10.1 — Left: footing pressure over Prandtl's collapse pressure vs settlement on the finest mesh.
# Right: the error of the limit pressure against the element size under the footing.*

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
axes[0].plot(-1e3 * d_ref, q_ref, "ko", label="Smith & Griffiths P6.1 (peer)")
for law, style in (("von_mises", "-"), ("tresca", "--")):
    axes[0].plot(-1e3 * sg[law]["w"], sg[law]["q"], style, label=f"ssi, {law.replace('_', ' ')}")
axes[0].axhline(prandtl(100.0, 0.0)[0], color="k", lw=0.8)
axes[0].set_xlim(0, 80)
axes[0].set_xlabel("centre settlement [mm]")
axes[0].set_ylabel("footing pressure [kPa]")
axes[0].legend()
for h in CTRL_MESHES:
    out = ctrl["psi0", h, CTRL_STEPS[0]]
    (line,) = axes[1].plot(
        1e3 * out["settlement"],
        out["q"] / q_p20,
        label=f"ψ = 0, h = {h} m" + (" (stopped)" if out["failure"] else ""),
    )
    if (20.0, True, h) in prandtl_runs:  # the associated push on the same mesh, dashed
        assoc = prandtl_runs[20.0, True, h]
        axes[1].plot(1e3 * assoc["settlement"], assoc["q"] / q_p20, "--", color=line.get_color(), lw=0.8)
axes[1].axhline(1.0, color="k", lw=0.8)
axes[1].axhline(q_davis / q_p20, color="gray", lw=0.8)
axes[1].set_xlabel("settlement [mm]")
axes[1].set_ylabel("q / q_u,Prandtl(φ = 20°)")
axes[1].set_title("rough footing, φ = 20°: ψ = 0 on the controlled path (dashed: ψ = φ)")
axes[1].legend(fontsize=8)
report.save_figure(fig, "fig10_2_sg61_nonassociated")
plt.show()

# %% [markdown]
# *Figure 10.2 — Left: the flexible footing of Smith & Griffiths' Program 6.1 (8 × 4 Q8, c_u = 100 kPa);
# von Mises reproduces the peer, Tresca settles less before the common collapse pressure 514 kPa.
# Right: the rough φ = 20° footing with ψ = 0 on the controlled path (20-step budget) on each mesh, the
# associated push of the same mesh dashed; grey: Prandtl's value of Davis' reduced material. "stopped": the
# path ended in a NonConvergence there (no estimate).*

# %%
fig, ax = plt.subplots(figsize=(7, 4.5))
markers = {variants[0][0]: "o-", variants[1][0]: "s-", variants[2][0]: "^-", variants[3][0]: "x"}
for name, _, _ in variants:
    pts = [
        (out["wall_time"], max(out["trade_err"], 1e-6), n, out["failure"])
        for (nm, n), out in trade.items()
        if nm == name
    ]
    if not pts:  # a variant fast mode does not run
        continue
    ax.loglog([p[0] for p in pts], [p[1] for p in pts], markers[name], label=name)
    for t, e, n, fail in pts:
        ax.annotate(f"{n}" + (" (stopped)" if fail else ""), (t, e), fontsize=7)
ax.set_xlabel("wall time [s]")
ax.set_ylabel("|q_u − q_u,ref| / q_u,Prandtl")
ax.set_title(f"rough footing φ = ψ = 20°, h = {H_TRADE} m (labels: number of steps)")
ax.legend(fontsize=8)
report.save_figure(fig, "fig10_3_trade")
plt.show()

# %% [markdown]
# *Figure 10.3 — Error of the limit pressure against wall time for the integration schemes and Newton
# variants; labels give the number of displacement steps. "stopped" marks runs that the solver ended with a
# NonConvergence report (their point is the largest pressure reached).*
#
# ## Summary
#
# - The implicit Mohr–Coulomb return mapping inside the reduced-integrated Q8 element converges to Prandtl's
#   collapse pressure for smooth and rough footings, φ = 0 and 20°, with the error shrinking under refinement
#   (about first order in h, the footing corner being singular); on the named mesh (h = 0.0625 m) all four
#   cases are within 3 % (values in the table above and in `figures/report.csv`).
# - The flexible-footing curve of Smith & Griffiths is reproduced to well within 3 % up to 500 kPa when the
#   peer's yield function is used; Tresca with the same c_u differs by ≈ 8 % before collapse.
# - On the controlled path the associated footing peaks within 3 % of Prandtl on h = 0.0625 m, inside the
#   limit-analysis bracket, whatever the step budget (`footing_assoc_peak`); Davis mode converges from above
#   towards Prandtl's value of the reduced material (`footing_davis_peak`).
# - The user's ψ = 0 has no unique limit. Its path estimate (values in the table above and in
#   `figures/report.csv`) lies between the Davis value and the associated ceiling, below the associated
#   push of the same mesh, and moves little under the step budget and round-off on h = 0.25 and 0.125 m
#   (`psi0_limit_h0125`, `psi0_step_independence`); on the finest mesh the user's ψ = 0 path may end in a
#   `NonConvergence` (printed above), which is reported as such and never read as a limit. For a capacity
#   of non-associated soil use Davis mode; keep the user's ψ for deformations under service loads.
# - The paper's explicit scheme and modified Newton cost more wall time per digit of accuracy than the
#   implicit return mapping with full Newton; the paper's modified Newton with K₀ in the given increments
#   (`Settings.paper()`, 400 iterations, one halving) stops before the limit: at 24 mm (1.02 × Prandtl) on
#   h = 0.5 m in 20 increments, at 8 mm (0.47 ×) on h = 0.25 m in 40 (measured), where 400 iterations no
#   longer reach the tolerance.
#
# References: Prandtl (1920), Reissner (1924); Smith, Griffiths & Margetts, *Programming the Finite Element
# Method*, Program 6.1; Clausen, Damkilde & Andersen (2006, 2007) on principal-space return mapping;
# de Borst & Vermeer (1984); Loukidis & Salgado (2009); Sloan & Randolph (1982).
