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
# # 13 — Accuracy you ask for: error estimates, and the speed/accuracy trade
#
# *Beyond the paper.* Every chapter so far measured its discretisation error once, by hand, against a
# reference it happened to have. A user's scene has no reference. This chapter turns the refinement studies
# into a tool: `ssi.estimate` re-solves a scene on systematically refined copies and estimates the error of
# each headline answer from how the answers change.
#
# In this chapter you will
# - derive the Richardson estimate with the *observed* order of convergence from three refinement levels;
# - check on three closed forms (a strip load on the half-plane, Prandtl's bearing capacity, Hetényi's beam
#   on a Winkler bed) that the estimate brackets the true error: the **efficiency index** estimated/true;
# - ask for an accuracy (`solve_to_target`) on the chapter-11 foundation and check what was delivered;
# - map the trade between error and wall time (a Pareto front) over mesh × steps × plate layers × solver
#   for the chapter-11 scene and the Mohr–Coulomb footing, and read off the cheapest setting for 10/5/2/1 %.
#
# ## Theory: Richardson with the observed order
#
# Let $q(h)$ be an answer computed with a discretisation parameter $h$ — the element size, the load increment
# or a plate layer's thickness — and suppose that, for small enough $h$ (the *asymptotic range*),
# $q(h) = q^\* + C h^p$. Three answers $q_0, q_1, q_2$ at $h, h/2, h/4$ give the differences
# $d_1 = q_1 - q_0$ and $d_2 = q_2 - q_1$, whose ratio is $2^p$:
#
# $$p = \log_2 \frac{d_1}{d_2}, \qquad q_0 - q^\* \approx \frac{2^p}{2^p - 1}\, d_1 \cdot (-1), \qquad
#   q_2 - q^\* \approx -\frac{d_2}{2^p - 1}.$$
#
# The estimate is only as good as the power law. When $d_1$ and $d_2$ differ in sign, or $p$ lies outside
# [0.5, 5], the answers are not in the asymptotic range and `ssi.estimate` flags the estimate instead of
# using it. Differences smaller than the nonlinear solver's iteration error (10⁻³ relative; chapter 11
# measured 10⁻⁴ between two solvers at the same tolerance) carry no order: the error is then bounded by the
# differences themselves. The three refinements (mesh, steps, layers) are estimated one at a time from one
# base solve and their errors are added.
#
# | symbol | meaning | code |
# |---|---|---|
# | $q_0, q_1, q_2$ | answers at h, h/2, h/4 | `Richardson.values` |
# | $p$ | observed order | `Richardson.order` |
# | $q_0 - q^\*$ | estimated error of the scene as given | `Richardson.error_base` |
# | $q_2 - q^\*$ | estimated error of the finest copy | `Richardson.error_fine` |
# | $I = \hat e / e$ | efficiency index (estimated / true error) | — |

# %%
import itertools
import math
import time

import matplotlib.pyplot as plt
import numpy as np

from ssi import paths
from ssi.analytical import hetenyi_deflection
from ssi.analytical_soil import strip_centreline_compression, strip_load_stresses
from ssi.bearing_capacity import prandtl, push_footing, rigid_footing
from ssi.elements.interface import add_interface
from ssi.elements.plate import add_plate_strip
from ssi.elements.soil_q8 import SoilQ8
from ssi.estimate import RefinedSolver, estimate, richardson, solve_to_target
from ssi.materials.interface_law import interface_params
from ssi.materials.layer_laws import CONCRETE, STEEL
from ssi.materials.rc import concrete_params, designer_concrete, steel_params
from ssi.materials.soil_laws import ELASTIC, elastic_params
from ssi.mesh import structured_q8
from ssi.model import Model
from ssi.report import record, save_figure
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer
from ssi.section import homogeneous, rc_section
from ssi.solver import NonConvergence, Settings
from ssi.supports import edge_forces

FAST = paths.FAST
print("fast mode" if FAST else "full mode")

# %% [markdown]
# ## 1. Closed forms: does the estimate bracket the true error?
#
# **Strip load.** A uniform pressure q on the half-plane over |x| ≤ b; the closed form (chapter 05) gives the
# compression of the centreline between the surface and depth 2b, $w(0,0) - w(0,-2b)$. As in chapter 05 we
# solve a finite window 0 ≤ x ≤ 4b, −4b ≤ z ≤ 0 whose cut faces carry the exact tractions, so the only error
# left is the discretisation's; the mesh has n elements per b (n = 1, 2, 4, 8).

# %%
Q, B_HALF, E_SOIL, NU = 100e3, 1.0, 30e6, 0.3


def strip_compression(n):
    """w(0,0) - w(0,-2b) [m] of the window with exact boundary tractions and n Q8 elements per b."""
    lines = np.linspace(0.0, 4.0 * B_HALF, 4 * n + 1)
    m = structured_q8(lines, lines - 4.0 * B_HALF)
    model = Model()
    model.add_nodes(m.xy, 2)
    model.add_group(
        SoilQ8(
            m.xy[m.conn], model.element_dofs(m.conn), 0, [ELASTIC], [elastic_params(E_SOIL, NU)], n_gauss=2
        )
    )
    model.fix(m.left, "u")
    model.fix(m.bottom[:1], "w")

    def load(line, traction):
        edges = np.stack([line[0:-2:2], line[1:-1:2], line[2::2]], axis=1)
        model.add_element_load(model.element_dofs(edges), edge_forces(m.xy[edges], traction))

    def right(x, z):
        sxx, _, txz = strip_load_stresses(x, z, Q, B_HALF)
        return sxx, txz

    def bottom(x, z):
        _, szz, txz = strip_load_stresses(x, z, Q, B_HALF)
        return -txz, -szz

    load(m.surface[m.xy[m.surface, 0] <= B_HALF + 1e-9], lambda x, z: (0.0 * x, -Q + 0.0 * x))
    load(m.right, right)
    load(m.bottom, bottom)
    res = model.solve_linear(backend="superlu")
    on_axis = np.abs(m.xy[:, 0]) < 1e-9
    top = np.flatnonzero(on_axis & (np.abs(m.xy[:, 1]) < 1e-9))
    low = np.flatnonzero(on_axis & (np.abs(m.xy[:, 1] + 2.0 * B_HALF) < 1e-9))
    return float(res.at(top, "w")[0] - res.at(low, "w")[0])


# %% [markdown]
# **Hetényi.** A thin plate strip (h = 1 cm) on an interface bed of modulus k under a point load P; the
# closed form is Euler–Bernoulli's, the strip is a Mindlin plate, whose shear flexibility adds about
# EIλ²/(κGh) ≈ 6·10⁻⁴ to the deflection (chapter 07): a model error, not a discretisation error. The levels
# (16, 32, 64, 128 elements over 6π/λ) start where the discretisation error is several times that. Coarser
# meshes (4 and 8 elements) converge with alternating sign — not yet asymptotic, which the estimate flags.
#
# **Prandtl.** The smooth rigid footing of chapter 10 (φ = 0, c = 10 kPa, half model) pushed to 4 cm in 30
# steps; the limit pressure converges from above with the element size under the footing (h = 0.5, 0.25,
# 0.125 m; full mode adds 0.0625 m). Its other errors (the block's size, the finite settlement) are below
# 0.5 % (chapter 10).

# %%
H_PLATE, E_PLATE, K_BED, P_LOAD = 0.01, 30e9, 5e6, 10e3
EI_PLATE = E_PLATE * H_PLATE**3 / (12 * (1 - 0.2**2))
LAM = (K_BED / (4 * EI_PLATE)) ** 0.25


def winkler_deflection(n_el):
    """Deflection [m] under the load of the plate strip on the interface bed with n_el elements."""
    length = 6.0 * math.pi / LAM
    m = Model()
    plate, pids, pconn = add_plate_strip(
        m, np.linspace(-length / 2, length / 2, n_el + 1), homogeneous(H_PLATE, E_PLATE, 0.2), z=H_PLATE / 2
    )
    low = m.add_nodes(m.coords[pids] - [0.0, H_PLATE / 2], 2)
    add_interface(
        m, pconn, low[pconn - pids[0]], interface_params(0.0, K_BED, c=math.inf), offset=plate.bottom_offset
    )
    m.fix(low, "u")
    m.fix(low, "w")
    mid = pids[len(pids) // 2]
    m.fix([mid], "u")
    m.add_load([mid], "w", -P_LOAD)
    return float(-m.solve_linear(backend="superlu").at([mid], "w")[0])


C_MC = 10e3
FOOTING = {
    "B": 2.0,
    "c": C_MC,
    "phi_deg": 0.0,
    "E": 20e6,
    "nu": 0.3,
    "rough": False,
    "settle": 0.04,
    "half_width": 6.0,
    "depth": 5.0,
    "h_coarse": 1.0,
    "growth": 1.25,
}


def footing_capacity(h, n_steps=30, method="line_search"):
    """(limit pressure q_u [Pa], wall time [s]) of the smooth rigid footing with element size h [m]."""
    out = push_footing(rigid_footing(h_fine=h, **FOOTING), n_steps=n_steps, method=method)
    if out["failure"]:
        raise RuntimeError(f"footing h={h}, {n_steps} steps, {method}: {out['failure']}")
    return out["q_u"], out["wall_time"]


# relative error of each closed form as a model of the discrete problem (not a discretisation error): the
# strip's window has exact tractions (quadrature error ~1e-10); the Mindlin strip's shear flexibility
# EI lambda^2 / (kappa G h) (chapter 07); Prandtl's block size and finite settlement (< 0.5 %, chapter 10)
SHEAR_FLEXIBILITY = EI_PLATE * LAM**2 / (5.0 / 6.0 * E_PLATE / (2 * 1.2) * H_PLATE)
MODEL_ERROR = {"strip load w(0,0)-w(0,-2b)": 1e-10, "Hetenyi w(0)": SHEAR_FLEXIBILITY, "Prandtl q_u": 0.005}
t0 = time.perf_counter()
cases = {
    "strip load w(0,0)-w(0,-2b)": (
        [1, 2, 4] if FAST else [1, 2, 4, 8],
        strip_compression,
        strip_centreline_compression(2 * B_HALF, Q, B_HALF, E_SOIL, NU),
    ),
    "Hetenyi w(0)": (
        [16, 32, 64] if FAST else [16, 32, 64, 128],
        winkler_deflection,
        float(hetenyi_deflection(np.array([0.0]), P_LOAD, K_BED, EI_PLATE)[0]),
    ),
    "Prandtl q_u": (
        [0.5, 0.25, 0.125] if FAST else [0.5, 0.25, 0.125, 0.0625],
        lambda h: footing_capacity(h)[0],
        prandtl(C_MC, 0.0)[0],
    ),
}
efficiency = []
for name, (levels, solve, exact) in cases.items():
    values = [solve(lv) for lv in levels]
    for i in range(len(levels) - 2):
        r = richardson(*values[i : i + 3], noise=0.0)  # linear solves / the footing's converged plateau
        true_base, true_fine = values[i] - exact, values[i + 2] - exact
        # a true error within 3x the closed form's model error measures the model, not the discretisation
        judged = abs(true_base / exact) >= 3.0 * MODEL_ERROR[name]
        efficiency.append(
            {
                "case": name,
                "level": levels[i],
                "order": r.order,
                "est": r.error_base / exact,
                "true": true_base / exact,
                "index": r.error_base / true_base,
                "index_fine": r.error_fine / true_fine,
                "asymptotic": r.asymptotic,
                "judged": judged,
            }
        )
print(
    f"closed-form studies: {time.perf_counter() - t0:.1f} s; "
    f"Mindlin shear flexibility {SHEAR_FLEXIBILITY:.1e}"
)
print(
    f"{'case':28s} {'level':>7s} {'p':>6s} {'est. err':>10s} {'true err':>10s} {'index':>7s} "
    f"{'index (finest)':>15s}"
)
for row in efficiency:
    print(
        f"{row['case']:28s} {row['level']:7g} {row['order']:6.2f} {row['est']:10.2e} {row['true']:10.2e} "
        f"{row['index']:7.3f} {row['index_fine']:15.3f}"
        + ("" if row["asymptotic"] else "  (order outside [0.5, 5]: flagged)")
        + ("" if row["judged"] else "  (true error within 3x the model error: not judged)")
    )

# %% [markdown]
# The index of the scene *as given* (the coarsest of each triple: what a user solving that mesh is told) is
# the claim, for every triple whose true error is at least three times the closed form's own model error
# (the finest Hetényi triple of full mode is below it: there the reference measures the Mindlin strip's shear
# flexibility, not the mesh); the finest level's index is printed too — it is less reliable, since there the
# power law is extrapolated furthest and the other error sources (the Hetényi model error, the solver's
# tolerance) are relatively largest.

# %%
EFFICIENCY_RANGE = (0.5, 2.0)  # the band: an estimate within a factor 2 of the true error
indices = np.array([row["index"] for row in efficiency if row["judged"]])
print(f"efficiency indices of the scene as given: {np.round(indices, 3).tolist()}")
assert np.all(indices > 0.0)  # the estimate has the sign of the true error: it brackets q*
efficiency_ok = bool(np.all((indices >= EFFICIENCY_RANGE[0]) & (indices <= EFFICIENCY_RANGE[1])))
record(
    "error_estimate_efficiency",
    "efficiency index est./true error of the scene as given, min over strip "
    f"load, Prandtl, Hetenyi (max {indices.max():.3g}; PASS when all in [0.5, 2])",
    indices.min(),
    EFFICIENCY_RANGE[0],
    efficiency_ok,
)
assert efficiency_ok, f"efficiency indices {indices} outside {EFFICIENCY_RANGE}"

# %% [markdown]
# ## 2. The chapter-11 foundation, with its error
#
# The scene of chapter 11 — an RC beam on soft clay over sand under two columns — solved as given (coarse:
# h = 1 m under the foundation) with `estimate`: every headline quantity, the error estimate of each
# refinement with its observed order, and what each refinement cost.

# %%
fc, fy, Es = 38e6, 500e6, 200e9
d = designer_concrete(fc)
concrete = (CONCRETE, concrete_params(fc, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, fy / Es))
steel = (STEEL, steel_params(fy, Es))
SECTION = rc_section(0.4, [(0.05, 1.5e-3), (0.35, 1.5e-3)], concrete, steel, n_concrete=9)
H_COARSE = 4.0  # both modes: the full-mode 2.0 made the refined references run for > 25 min here


def foundation_scene(h_fine=1.0):
    return Scene(
        width=30.0,
        depth=10.0,
        layers=[
            SoilLayer(2.0, E=10e6, nu=0.3, unit_weight=18e3, c=20e3, phi_deg=20.0, psi_deg=0.0),
            SoilLayer(8.0, E=80e6, nu=0.3, unit_weight=20e3, c=1e3, phi_deg=35.0, psi_deg=5.0),
        ],
        foundation=Foundation(x0=-3.0, x1=3.0, section=SECTION, self_weight=25e3 * 0.4),
        contact=Contact(kn=4e9, kt=4e8, phi_deg=25.0),
        loads=[ColumnLoad(x=-2.5, N=400e3), ColumnLoad(x=2.5, N=400e3)],
        mesh=MeshSize(h_fine=h_fine, h_coarse=H_COARSE, growth=1.3),
    )


scene11 = foundation_scene()
# full Newton, as in chapter 11: the default BFGS on K0 stalls near 97 % of the load on some refined copies
# (h/4 with twice the steps or layers), where the beam's cracking spreads
NEWTON = Settings(method="full")
t0 = time.perf_counter()
est11 = estimate(scene11, settings=NEWTON)
print(est11)
print(f"estimate: {time.perf_counter() - t0:.1f} s")

# %% [markdown]
# ## Accuracy on demand: `solve_to_target`
#
# From the estimate, each refinement's error is extrapolated with its fitted power law; the cheapest number of
# halvings predicted to reach the target is solved. Fast mode asks for 10 %, full mode for the 2 %.
# The delivered settlement is then compared with a reference one halving finer than it in every refinement
# — an independent solve the driver never saw. If no setting within three halvings per refinement
# is predicted to reach the target, the driver says so, the row records a FAIL of the claim, and the driver
# is checked on 10 % instead.

# %%
TARGET = 0.10 if FAST else 0.02


def solve_and_check(target_error):
    """(TargetResult, true relative error of its settlement or None, reference Level or None)."""
    t0 = time.perf_counter()
    res = solve_to_target(scene11, target_error=target_error, quantities=("max_settlement",), settings=NEWTON)
    print(f"target {target_error:.0%}: {res.status} | {res.message} | {time.perf_counter() - t0:.1f} s")
    if not res.met:
        return res, None, None
    ref_key = tuple(k + 1 for k in res.key)
    ref = RefinedSolver(scene11, None, NEWTON)(ref_key)
    got, want = res.result.max_settlement()[1], ref.values["max_settlement"]
    err = abs(got - want) / abs(want)
    print(
        f"  delivered at halvings {res.key}: {1e3 * got:.3f} mm; reference at {ref_key} ({ref.n_dof} DOFs, "
        f"{ref.wall_time:.1f} s): {1e3 * want:.3f} mm; true error {err:.2%} (predicted "
        f"{res.predicted['max_settlement']:.2%})"
    )
    return res, err, ref


target, true_target_error, reference = solve_and_check(TARGET)
if target.met:
    record(
        "target_error_met",
        f"|s_max - s_ref|/s_ref of the chapter-11 scene solved to target_error={TARGET} "
        f"(reference: one more halving of mesh, steps and layers, {reference.n_dof} DOFs)",
        true_target_error,
        TARGET,
        true_target_error <= TARGET,
    )
    assert true_target_error <= TARGET
else:
    # an honest refusal is the driver's answer, recorded as a FAIL of the claim (not hidden, not a crash);
    # the driver is then shown on the loosest target it can reach here
    record(
        "target_error_met",
        f"chapter-11 scene, target_error={TARGET}: {target.status} (value: estimated "
        "error of the scene as given)",
        target.predicted["max_settlement"],
        TARGET,
        False,
    )
    assert not FAST, "fast mode's 10 % must be reachable"
    looser, looser_error, reference = solve_and_check(0.10)
    assert looser.met and looser_error <= 0.10
s_ref = reference.values["max_settlement"]

# %% [markdown]
# ## 3. The speed/accuracy trade: Pareto fronts
#
# Every combination of mesh (h, h/2[, h/4]), load steps (automatic, and twice as fine), plate layers (9 + 2
# bars, and each split in two) and solver (BFGS on K0, the default, and full Newton) is one setting; its error
# is measured against the finest solve of the study (for the chapter-11 scene: the reference above), its cost
# is the solve's wall time. A setting is on the Pareto front when no other is both faster and more accurate.

# %%
mesh_levels = [0, 1]  # both modes (h/4 copies of this scene take tens of minutes on this machine)
solvers = {
    "bfgs": RefinedSolver(scene11, None, Settings(method="bfgs")),
    "full": RefinedSolver(scene11, None, NEWTON),
}
solvers["full"].cache.update(est11.levels)  # the estimate's solves used full Newton
trade11 = []
for method, solver in solvers.items():
    for m in mesh_levels:
        for s in (0, 1):
            for lay in (0, 1):
                try:
                    lv = solver((m, s, lay))
                except NonConvergence as err:  # a setting that fails is not on any front: say so
                    print(
                        f"h/{2**m} steps x{2**s} layers x{2**lay} {method}: failed ({err.report['reason']})"
                    )
                    continue
                trade11.append(
                    {
                        "setting": f"h/{2**m} steps x{2**s} layers x{2**lay} {method}",
                        "error": abs(lv.values["max_settlement"] - s_ref) / abs(s_ref),
                        "wall": lv.wall_time,
                        "n_dof": lv.n_dof,
                    }
                )


def footing_trade():
    h_levels = [0.5, 0.25] if FAST else [0.5, 0.25, 0.125]
    q_exact = prandtl(C_MC, 0.0)[0]
    rows = []
    for method in ("line_search", "bfgs"):
        for h in h_levels:
            for n_steps in (15, 30):
                q_u, wall = footing_capacity(h, n_steps, method)
                rows.append(
                    {
                        "setting": f"h={h} {n_steps} steps {method}",
                        "error": abs(q_u / q_exact - 1),
                        "wall": wall,
                    }
                )
    return rows


trade_mc = footing_trade()


def pareto(rows):
    """The rows no other row beats in both error and wall time, fastest first."""

    def dominates(o, r):
        return (
            o["wall"] <= r["wall"]
            and o["error"] <= r["error"]
            and (o["wall"] < r["wall"] or o["error"] < r["error"])
        )

    front = [r for r in rows if not any(dominates(o, r) for o in rows)]
    return sorted(front, key=lambda r: r["wall"])


def cheapest(rows, levels=(0.10, 0.05, 0.02, 0.01)):
    out = {}
    for tol in levels:
        ok = [r for r in rows if r["error"] <= tol]
        out[tol] = min(ok, key=lambda r: r["wall"]) if ok else None
    return out


fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for ax, (title, rows) in zip(
    axes, (("chapter-11 foundation, max settlement", trade11), ("MC footing (Prandtl), q_u", trade_mc))
):
    ax.loglog([r["wall"] for r in rows], [max(r["error"], 1e-5) for r in rows], "o", color="0.6", ms=4)
    front = pareto(rows)
    ax.loglog(
        [r["wall"] for r in front], [max(r["error"], 1e-5) for r in front], "C0o-", label="Pareto front"
    )
    for tol in (0.10, 0.05, 0.02, 0.01):
        ax.axhline(tol, color="k", lw=0.5, ls=":")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("relative error")
    ax.set_title(title)
    ax.legend()
fig.suptitle("Fig. 13.1 — error against wall time over mesh × steps × layers × solver")
save_figure(fig, "ch13_pareto")

for title, rows in (("chapter-11 foundation", trade11), ("MC footing", trade_mc)):
    print(f"\n{title}: Pareto front")
    for r in pareto(rows):
        print(f"  {r['setting']:36s} error {r['error']:8.3%}  {r['wall']:7.2f} s")
    print(f"{title}: cheapest setting reaching")
    for tol, r in cheapest(rows).items():
        print(
            f"  {tol:4.0%}: "
            + (
                "not reached in this study"
                if r is None
                else f"{r['setting']:36s} error {r['error']:7.3%}  {r['wall']:6.2f} s"
            )
        )

# %% [markdown]
# ## Checks
# - every Pareto front is a front: along it, the error falls as the wall time grows;
# - the finest mesh is more accurate than the coarsest for both scenes (the refinement is not wasted);
# - the chapter-11 scene's estimated error is compared with its error against the reference (printed: the
#   reference is itself only one halving finer than the delivered answer, so this is not a second index).

# %%
for rows in (trade11, trade_mc):
    front = pareto(rows)
    assert all(a["error"] > b["error"] for a, b in itertools.pairwise(front))
coarse = next(r for r in trade11 if r["setting"] == "h/1 steps x1 layers x1 full")
finest = next(r for r in trade11 if r["setting"] == f"h/{2 ** mesh_levels[-1]} steps x1 layers x1 full")
assert finest["error"] < coarse["error"]
true_base = abs(est11.value["max_settlement"] - s_ref) / abs(s_ref)
est_base = est11.relative["max_settlement"]
print(
    f"chapter-11 scene as given: estimated error {est_base:.2%}, error against the "
    f"reference {true_base:.2%}, "
    f"index {est_base / true_base:.2f} (the reference carries its own error: printed, not asserted)"
)
assert est_base > 0.0 and true_base > 0.0

# %% [markdown]
# ## Summary
# `ssi.estimate.estimate(scene)` answers "how wrong is this?" for the headline quantities from three
# refinement levels of the mesh, the steps and the plate layers, with the observed order of each; on three
# closed forms its efficiency index lies in the table above. `solve_to_target(scene, 0.02)` turns it round:
# it extrapolates each refinement's error and solves the cheapest setting predicted to meet the target, and it
# refuses (with a message naming the refinement and its order) when the refinements are not in the
# asymptotic range. The Pareto fronts show where the time goes: for the chapter-11 scene the mesh dominates
# the error and the cost; the number of load steps hardly matters at the solver's tolerance.
#
# References: L. F. Richardson (1911), *Phil. Trans. R. Soc. A* 210, 307–357; P. J. Roache (1998),
# *Verification and Validation in Computational Science and Engineering*, Hermosa (the grid convergence index
# and the observed order).
