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
# # 11 — A foundation engineer's scene: an RC foundation beam on layered subsoil
#
# *Beyond the paper.* Chapters 02–10 verified each element and the solver against closed forms and
# measurements. This chapter uses them the way a user would: one scene, described by its components, solved,
# and read off — settlements, contact pressures, stick/slip/open zones, cracks and steel stresses.
#
# In this chapter you will
# - describe a scene with `ssi.scene` (soil layers, a foundation section, a contact law, column loads) and see
#   that only the element groups the scene needs are built;
# - solve it with the paper's modified Newton–Raphson and with the default controlled path, and measure the
#   trade;
# - read the results and store them in HDF5;
# - check them where a check can fail: the steel stress against an independent, layer-free section calculation
#   at the same curvature and axial force, and the settlement and the moment against mesh refinement, with the
#   order of convergence fitted over three meshes;
# - measure what accuracy costs in wall time.
#
# ## The scene
#
# The scene is built by `ssi.lab.examples.chapter11_foundation(h_fine)` (its section: `chapter11_section()`),
# so that chapters 13 and 14 and the sweep benchmark vary the very scene studied here.
#
# | component | choice | code |
# |---|---|---|
# | soil block | 30 m × 10 m, bottom fixed, sides on rollers (Fig. 1) | `Scene(width, depth)` |
# | layer 1 | 2 m soft clay: E = 10 MPa, ν = 0.3, γ = 18 kN/m³, c = 20 kPa, φ = 20°, ψ = 0 | `SoilLayer` |
# | layer 2 | 8 m sand: E = 80 MPa, ν = 0.3, γ = 20 kN/m³, c = 1 kPa, φ = 35°, ψ = 5° | `SoilLayer` |
# | foundation | 6 m long, 0.4 m deep RC strip, fc = 38 MPa, fy = 500 MPa | `Foundation`, `rc_section` |
# | reinforcement | As = 1.5·10⁻³ m²/m (15 cm²/m) top and bottom at 5 cm cover | `rc_section` |
# | contact | kn = 4·10⁹ Pa/m, kt = 4·10⁸ Pa/m, φ_i = 25°, c_i = 0, no tension (it may lift off) | `Contact` |
# | loads | two columns at x = ±2.5 m, N = 400 kN/m each; self-weight of beam and soil | `ColumnLoad` |
#
# The soil starts from its geostatic stress (K0 = 1 − sin φ) in equilibrium with its weight, so the
# displacements are those caused by the foundation. The concrete parameters E0, fr, Gf, εc come from fc by the
# designer formulas of chapter 03 (`designer_concrete`). The strip takes the `Foundation` defaults, which
# chapters 02 and 08 chose from evidence: each layer's own bending term from the stresses at its faces
# (`self_bending="chord"`), and a crack band equal to the *fib* Model Code 2010 crack spacing s_r,max of the
# nearest bars (`crack_band="spacing"`, `bar_diameter` = 16 mm here), which makes the cracked response
# independent of the element size (chapter 08: 0.55 % spread over four meshes, against 21.5 % for the paper's
# per-point band); the concrete layers are plane strain like the elastic ones (`plane_strain=True`, eq. 4.4).
# The band width 0.1 m given to `concrete_params` in the section is therefore replaced.
#
# The column load is 400 kN/m. (With the former defaults — initial-modulus self-bending and a 0.1 m band — the
# chapter used 450 kN/m; the corrected strip is softer, and at 450 kN/m its top bars reach 497 of 500 MPa,
# where the finer meshes of the refinement study stop converging. The chapter studies the cracked, elastic
# service state; the yield of this beam is a different study.)

# %%
import time
from dataclasses import replace

import matplotlib.pyplot as plt
import numpy as np

from ssi.elements import section_analysis as sa
from ssi.elements.section import homogeneous
from ssi.io.results import read_result, write_result
from ssi.lab import paths
from ssi.lab.digitize import read_reference
from ssi.lab.examples import CHAPTER11_COLUMN_LOAD, chapter11_foundation, chapter11_section
from ssi.lab.report import record, save_figure
from ssi.lab.verify import convergence_rate
from ssi.materials.layer_laws import CONCRETE, N_LAYER_HIST, STEEL, layer_update
from ssi.materials.rc import designer_concrete
from ssi.scene import Contact
from ssi.solver import Settings

FAST = paths.FAST
fy = 500e6
section = chapter11_section()  # fc = 38 MPa, fy = 500 MPa, 15 cm^2/m top and bottom, 9 concrete layers
N_COLUMN = CHAPTER11_COLUMN_LOAD  # [N/m] per column: 400 kN/m


def foundation_scene(h_fine, N=N_COLUMN, H=0.0):
    return chapter11_foundation(h_fine, column_load=N, horizontal_load=H)


H_FINE = 0.5 if FAST else 0.25
built = foundation_scene(H_FINE).build()
print(
    "groups:",
    [g.name for g in built.model.groups],
    "| DOFs:",
    built.model.n_dof,
    "| linear scene:",
    built.is_linear,
)
print(
    "crack band of the concrete layers (MC2010 s_r,max, bottom / top bars):",
    sorted({f"{v:.3f} m" for v in built.plate.section.params[built.plate.section.kind == CONCRETE, 7]}),
    "| self-bending:",
    built.plate.self_bending,
)

# %% [markdown]
# ## Solving: the paper's modified Newton–Raphson and the controlled path
#
# Modified Newton–Raphson factorises K0 once and pays with many cheap iterations in load steps; the default
# controlled path (`Settings()`, chapter 06) follows the work of the load with a lagged consistent tangent,
# L-BFGS updates and a line search, and needs fewer. Both stop at the same tolerance, so their answers
# may differ only by that tolerance; which is faster depends on how nonlinear the step is. (Full Newton in
# load steps, without the L-BFGS retry it once had, stops here at lambda = 0.66 in a `NonConvergence`: an
# increment on the cracking strip that does not converge in 30 tangent iterations, while the path is
# still as stiff as at its start -- not a limit.)

# %%
runs = {}
for method, settings in (("modified", Settings(method="modified", max_iter=500)), ("controlled", Settings())):
    scene_built = foundation_scene(H_FINE).build()
    t0 = time.perf_counter()
    out = scene_built.solve(n_steps=10, settings=settings)
    runs[method] = (out, time.perf_counter() - t0)
    res = out.solver_result
    print(
        f"{method:10s}: {sum(res.iterations):5d} iterations, {res.factorizations:4d} factorisations, "
        f"{res.cuts} step cuts, {runs[method][1]:6.2f} s, max settlement "
        f"{1e3 * out.settlement()[1].max():.2f} mm"
    )
out = runs["controlled"][0]

# %% [markdown]
# ## What the engineer reads off

# %%
x_plate, settle = out.settlement()
x_soil, settle_soil = out.surface()
contact = out.contact()
layers = out.plate_layers()
steel_sig = layers["sig"][..., layers["steel"]]
zone_codes = {"stick": 0, "slip": 1, "open": 2}

fig, ax = plt.subplots(4, 1, figsize=(8, 11), sharex=True)
near = np.abs(x_soil) < 8.0
ax[0].plot(x_soil[near], 1e3 * settle_soil[near], "k-", lw=1, label="soil surface")
ax[0].plot(x_plate, 1e3 * settle, "C0o-", ms=3, label="foundation")
ax[0].invert_yaxis()
ax[0].set_ylabel("settlement [mm]")
ax[0].legend()
xc, sn = contact["x"].ravel(), contact["sig_n"].ravel()
for name in zone_codes:
    m = contact["zone"].ravel() == name
    ax[1].plot(xc[m], -sn[m] / 1e3, "o", ms=4, label=name)
ax[1].set_ylabel("contact pressure [kPa]")
ax[1].legend()
xs = layers["x"].ravel()
for j, z in enumerate(layers["z"]):
    m = layers["cracked"][:, :, j].ravel()
    ax[2].plot(xs[m], np.full(m.sum(), z), "r|", ms=8)
ax[2].set_ylabel("z of cracked layer [m]")
ax[2].set_ylim(section.z_bottom, section.z_top)
for k, label in enumerate(("bottom bars", "top bars")):
    ax[3].plot(xs, steel_sig[:, :, k].ravel() / 1e6, ".-", label=label)
ax[3].axhline(fy / 1e6, color="grey", ls="--", lw=0.8)
ax[3].set_ylabel("steel stress [MPa]")
ax[3].set_xlabel("x [m]")
ax[3].legend()
fig.suptitle("Fig. 11.1 — RC foundation beam on layered subsoil: settlement, contact, cracks, steel")
save_figure(fig, "ch11_foundation_scene")

# %% [markdown]
# ## Checks
# - **Modified Newton vs the controlled path** agree to the solver tolerance (two different iterations, one
#   answer).
# - **Steel against an independent section calculation.** At the point where the bars are most stressed, the
#   strip's curvature κ and axial force N are read off; the layer-free section analysis of chapter 02
#   (`ssi.elements.section_analysis.layer_free_state`: adaptive quadrature of the continuous stress profile,
#   no layers, Brent's method for the strain plane carrying N at κ) gives the bar strain and stress there. The
#   difference is the strip's layer rule (11 layers; about 1 % in M in chapter 02) and the history of the
#   fibres; the tolerance is 3 % of the stress.
# - **Cracks**: the soil pushes the beam up between the columns, so the hogging moment is largest near
#   mid-span and the top face cracks there.
# - **Equilibrium of the contact resultant with the loads is not a test of convergence**, and the check
#   that is. The same scene is solved once more with the same ten load steps but every increment accepted as
#   soon as the residual is below 5 % of the load (`Settings(method="modified", stepping="fixed",
#   force_tol=0.05)`: modified Newton–Raphson stopped early, an un-converged iterate). Its contact resultant
#   and even the load taken by the block's fixed base still match the applied loads to round-off: the
#   residual such an iterate leaves is the stress correction of the yielding soil and the cracked strip,
#   a self-equilibrated set of nodal forces (zero resultant) wherever the nonlinearity is away from the
#   supports, so every *global* resultant holds for any iterate. The row `scene_equilibrium` is therefore a
#   consistency figure only. What does see the stopped iterate is the settlement: against the converged
#   answer of the controlled path it differs by far more than the 1e-3 within which the two converged
#   methods must agree — the method check above fails on it.

# %%
applied = 2 * N_COLUMN + 25e3 * 0.4 * 6.0


def contact_resultant(o):
    """Vertical resultant [N/m] of the contact pressure of a solved scene (compression positive)."""
    return -np.sum(o.contact()["sig_n"] * o.built.interface.ip_weights())


equilibrium_error = abs(contact_resultant(out) - applied) / applied
LOOSE_TOL = 0.05  # [-] force tolerance of the stopped-early iterates (the solver's default is 1e-5)
loose = (
    foundation_scene(H_FINE)
    .build()
    .solve(
        n_steps=10,
        settings=Settings(
            method="modified", stepping="fixed", force_tol=LOOSE_TOL, energy_tol=0.5, max_iter=500
        ),
    )
)


def base_load(o):
    """Vertical force [N/m] the block's fixed base takes on beyond the geostatic state."""
    r = o.solver_result.reaction(o.built.mesh.bottom, "w")
    return float(r[-1] - r[0])


loose_resultant_error = abs(contact_resultant(loose) - applied) / applied
loose_base_error = abs(base_load(loose) - applied) / applied
loose_gap = np.max(np.abs(loose.settlement()[1] - settle)) / settle.max()
method_gap = np.max(np.abs(runs["modified"][0].settlement()[1] - settle)) / settle.max()
print(
    f"stopped-early iterate (force_tol {LOOSE_TOL}, {sum(loose.solver_result.iterations)} iterations against "
    f"{sum(runs['modified'][0].solver_result.iterations)} converged): contact resultant error "
    f"{loose_resultant_error:.1e}, base load error {loose_base_error:.1e} (converged: "
    f"{equilibrium_error:.1e}, {abs(base_load(out) - applied) / applied:.1e}); settlement vs the "
    "controlled path "
    f"{loose_gap:.2e} (converged modified Newton: {method_gap:.2e})"
)
mid = np.argmin(np.abs(layers["x"].ravel()))
top_concrete = int(np.flatnonzero(~layers["steel"])[-1])
print(
    f"contact resultant {contact_resultant(out) / 1e3:.2f} kN/m vs applied {applied / 1e3:.2f} kN/m "
    f"(relative error {equilibrium_error:.2e}); modified Newton vs controlled path {method_gap:.2e}"
)

# the strip's section state at the most stressed bar point
plate = out.built.plate
sec_p = plate.section
st_plate = out.states[-1][out.built.model.groups.index(plate)]
u_plate = out.u[-1][plate.edofs]
eps_l, _ = plate.layer_strains(u_plate)
axial = plate.ax.astype(bool)
eps_ax = eps_l[:, axial]
kap_pts = (eps_ax[..., 0] - eps_ax[..., -1]) / (sec_p.z_mid[-1] - sec_p.z_mid[0])
N_pts = plate.resultants(u_plate, st_plate)["N"]
e_s, q_s, j_s = np.unravel_index(np.argmax(np.abs(steel_sig)), steel_sig.shape)
bar = int(np.flatnonzero(layers["steel"])[j_s])
eps0_free, m_free, _ = sa.layer_free_state(sec_p, kap_pts[e_s, q_s], N_pts[e_s, q_s])
h0, h1 = np.zeros(N_LAYER_HIST), np.zeros(N_LAYER_HIST)
sig_free = layer_update(
    STEEL, sec_p.params[bar], eps0_free - sec_p.z_mid[bar] * kap_pts[e_s, q_s], 0.0, h0, h1, 1
)[0]
steel_gap = abs(steel_sig[e_s, q_s, j_s] / sig_free - 1)
print(
    f"most stressed bar point x = {layers['x'][e_s, q_s]:.3f} m: kap = {kap_pts[e_s, q_s]:.3e} 1/m, "
    f"N = {N_pts[e_s, q_s] / 1e3:.1f} kN/m; steel stress strip {steel_sig[e_s, q_s, j_s] / 1e6:.1f} MPa, "
    f"layer-free section {sig_free / 1e6:.1f} MPa (relative difference {steel_gap:.1e})"
)
print(
    f"cracked points {layers['cracked'].sum()}, max steel stress {np.abs(steel_sig).max() / 1e6:.1f} MPa "
    f"(fy = {fy / 1e6:.0f} MPa)"
)

METHOD_TOL = 1e-3  # both methods converge to 1e-5 in force; settlements agree to ~1e-4
STEEL_TOL = 0.03  # the 11-layer rule against the layer-free section (chapter 02: ~1 % in M)
assert method_gap < METHOD_TOL
assert steel_gap < STEEL_TOL, steel_gap
assert layers["cracked"].any()
assert layers["cracked"][:, :, top_concrete].ravel()[mid]  # the top face is cracked at mid-span
EQUILIBRIUM_TOL = 1e-4  # the row's tolerance: 10x the solver's force tolerance
assert method_gap < METHOD_TOL
assert loose_gap > METHOD_TOL  # the method check fails on the stopped-early iterate: it tests convergence
record(
    "scene_equilibrium",
    "relative error of the contact resultant vs applied loads (consistency only: an iterate stopped at "
    f"force_tol {LOOSE_TOL} meets it too, to {loose_resultant_error:.0e})",
    equilibrium_error,
    EQUILIBRIUM_TOL,
    equilibrium_error < EQUILIBRIUM_TOL,
)

# %% [markdown]
# ## Results are kept: HDF5
# The result file holds the mesh, every step's displacements and integration-point states, and the scene
# description, so a figure can be redrawn later without solving again.

# %%
path = paths.RESULTS / "ch11_foundation_scene.h5"
write_result(path, out.solver_result, Settings(), overwrite=True)
back = read_result(path)
assert back["model"]["scene"]["foundation"]["x1"] == 3.0
assert np.array_equal(back["u"][-1], out.u[-1])
print("stored:", path.name, "| groups:", list(back["state"]), "| steps:", len(back["load_factor"]) - 1)

# %% [markdown]
# ## What accuracy costs: mesh refinement, fitted order and wall time
# The element size under the foundation is halved three times. Two quantities an engineer designs with are
# followed: the settlement under a column (x = 2.5 m, a node on every mesh) and the hogging moment at
# mid-span (x = 0, an element end on every mesh; the strip's Gauss-point moments of the two elements there
# are extrapolated to it with their quadratic and averaged). With successive changes d_i = |q_i − q_{i+1}|
# the order p is the slope of log d against log h (Richardson); it must be positive, i.e. the changes must
# shrink, for the finest answer to mean anything, and d_last / (2^p − 1) estimates the finest mesh's error.
# What order to expect: the strip's edges on the soil are the corners of a stiff punch, where the elastic
# contact pressure is singular like r^(−1/2); that limits the convergence of energy-type quantities to
# about h^(1/2), whatever the elements' degree (Strang & Fix, ch. 8). The row's tolerance is that 0.5.
# The wall time is measured beside it.

# %%
# the default solver (the controlled path; until issue 31 load control with BFGS on K0 and a viscous
# fallback, 0.5 / 0.9 / 4.9 / 41 s on h = 1 / 0.5 / 0.25 / 0.125 m, measured on a loaded machine); fast mode
# stops at three meshes, the least a fitted order needs
sizes = [1.0, 0.5, 0.25] if FAST else [1.0, 0.5, 0.25, 0.125]


def midspan_moment(o):
    """Hogging moment at x = 0 [N m/m]: the quadratic through each adjacent element's three Gauss-point
    moments, evaluated at the shared end, averaged over the two elements."""
    p = o.built.plate
    r = p.resultants(o.u[-1][p.edofs], o.states[-1][o.built.model.groups.index(p)])
    ends = p._x[:, [0, 2]]
    vals = []
    for e in (
        int(np.flatnonzero(np.isclose(ends[:, 1], 0.0))[0]),
        int(np.flatnonzero(np.isclose(ends[:, 0], 0.0))[0]),
    ):
        vals.append(np.polyval(np.polyfit(r["x_ax"][e], r["M"][e], 2), 0.0))
    return float(np.mean(vals))


study = []
for h in sizes:
    b = foundation_scene(h).build()
    t0 = time.perf_counter()
    o = b.solve()
    wall = time.perf_counter() - t0
    x_pl, s_pl = o.settlement()
    study.append(
        (h, b.model.n_dof, 1e3 * float(s_pl[np.argmin(np.abs(x_pl - 2.5))]), midspan_moment(o) / 1e3, wall)
    )
    print(
        f"h = {h:5.3f} m: {b.model.n_dof:6d} DOFs, settlement at the column {study[-1][2]:.4f} mm, "
        f"mid-span moment {study[-1][3]:.3f} kN m/m, {wall:.2f} s"
    )
study = np.array(study)


def fitted_order(q):
    d = np.abs(np.diff(q))
    return convergence_rate(study[:-1, 0], d)


order_w, order_m = fitted_order(study[:, 2]), fitted_order(study[:, 3])
est_w = abs(study[-1, 2] - study[-2, 2]) / (2**order_w - 1) / abs(study[-1, 2])
est_m = abs(study[-1, 3] - study[-2, 3]) / (2**order_m - 1) / abs(study[-1, 3])
print(
    f"fitted order: settlement {order_w:.2f}, mid-span moment {order_m:.2f}; Richardson "
    f"estimate of the finest mesh's relative error: settlement {est_w:.1%}, moment {est_m:.1%}"
)
fig, ax = plt.subplots(1, 3, figsize=(13, 3.5))
ax[0].plot(study[:, 1], study[:, 2], "o-")
ax[0].set(xscale="log", xlabel="DOFs", ylabel="settlement at the column [mm]")
ax[1].loglog(
    study[:-1, 0],
    np.abs(np.diff(study[:, 2])) / abs(study[-1, 2]),
    "o-",
    label=f"settlement (p = {order_w:.2f})",
)
ax[1].loglog(
    study[:-1, 0], np.abs(np.diff(study[:, 3])) / abs(study[-1, 3]), "s-", label=f"moment (p = {order_m:.2f})"
)
ax[1].set(xlabel="h of the coarser mesh [m]", ylabel="relative change on halving h")
ax[1].legend(fontsize=8)
ax[2].loglog(study[:, 1], study[:, 4], "o-")
ax[2].set(xlabel="DOFs", ylabel="wall time [s]")
fig.suptitle("Fig. 11.2 — accuracy vs cost under mesh refinement")
fig.tight_layout()
save_figure(fig, "ch11_mesh_trade")
ORDER_MIN = 0.5  # the punch-edge singularity's h^(1/2) (see above)
order_min = min(order_w, order_m)
record(
    "ch11_mesh_order",
    f"fitted order of convergence over {len(sizes)} meshes h = {sizes} m: settlement at the "
    f"column {order_w:.2f}, mid-span moment {order_m:.2f} (value: the smaller; pass: >= {ORDER_MIN}); "
    f"Richardson error of the finest mesh: settlement {est_w:.3f}, moment {est_m:.3f}",
    order_min,
    ORDER_MIN,
    order_min >= ORDER_MIN,
)
assert order_min > 0.0, (order_w, order_m)  # the changes shrink: the sequence converges

# %% [markdown]
# **Why four meshes: the edge singularity, the nonlinearity, or coarse meshes?** With the three coarse
# meshes alone (fast mode) the moment's fitted order was 0.36–0.40, below the singularity's 1/2. The same
# scene made linear — elastic soil (`c=None`), a homogeneous
# elastic strip with the concrete's E0, a bonded linear contact — solves in about a second per mesh, so its
# order can be read over four meshes, one more halving. Successive orders p_i = log2(d_i / d_(i+1)) of the
# column settlement show whether the three coarse meshes are in the asymptotic range at all.

# %%
E0 = designer_concrete(38e6)["E0"]


def linear_variant(h):
    sc = foundation_scene(h)
    return replace(
        sc,
        layers=[replace(lay, c=None) for lay in sc.layers],
        foundation=replace(sc.foundation, section=homogeneous(0.4, E0, 0.2)),
        contact=Contact(kn=sc.contact.kn, kt=sc.contact.kt),
    )


linear_sizes = [1.0, 0.5, 0.25, 0.125]
linear_study = []
for h in linear_sizes:
    b = linear_variant(h).build()
    assert b.is_linear
    o = b.solve(n_steps=1)
    x_pl, s_pl = o.settlement()
    linear_study.append((1e3 * float(s_pl[np.argmin(np.abs(x_pl - 2.5))]), midspan_moment(o) / 1e3))
linear_study = np.array(linear_study)
d_lin = np.abs(np.diff(linear_study, axis=0))
successive = np.log2(d_lin[:-1] / d_lin[1:])
print(
    "linear variant, column settlement [mm]:",
    np.round(linear_study[:, 0], 4).tolist(),
    "| successive orders:",
    np.round(successive[:, 0], 2).tolist(),
)
print(
    "linear variant, mid-span moment [kN m/m]:",
    np.round(linear_study[:, 1], 3).tolist(),
    "| successive orders:",
    np.round(successive[:, 1], 2).tolist(),
)
# the linear scene's settlement order rises with the finest halving: the row's meshes are pre-asymptotic
assert successive[-1, 0] > successive[0, 0]

# %% [markdown]
# ## The h/16 copy on the controlled path (row `ch11_h16`)
#
# The graded h/16 copy of this foundation (chapter 13's family, 70 989 DOFs) once ended "limit load reached at
# λ = 0.606" on the load-controlled path with its viscous fallback, although coarser copies carry 1.5 times
# the service load: a false collapse. One solve takes minutes, so it is run once per solver change on the
# controlled path (`tools/chapter11_h16.py`, `Settings(control="work")`) and its outcome is stored with the
# commit (`reference_data/chapter11_h16_controlled.csv`). The row accepts exactly two outcomes: completed at
# λ = 1, or an honest `NonConvergence` (a failure, reported as one); a limit is accepted only at or above the
# foundation's certified lower bound (its limit analysis with the strip as a beam with plastic hinges, at a
# coarse 10 % gap: a lower bound needs no fine mesh to be one). Full mode only (the bracket costs seconds).

# %%
h16_meta, h16 = read_reference("chapter11_h16_controlled.csv")
h16_status, h16_lam = str(h16["status"][0]), float(h16["load_factor"][0])
print(f"h/16 copy ({int(h16['n_dof'][0])} DOFs) on the controlled path: {h16_status} at lambda = "
      f"{h16_lam:.4g}, {h16['wall_s'][0]:.0f} s ({h16_meta['how_obtained']})")  # fmt: skip
if not FAST:
    cap11 = chapter11_foundation(0.0625, h_coarse=0.25, end_grading=1.75).limit_analysis(gap=0.1, davis=False)
    print(cap11.summary())
    honest = h16_status == "completed" and h16_lam == 1.0 or h16_status == "NonConvergence"
    above_floor = h16_status == "limit load reached" and h16_lam >= cap11.lb
    record("ch11_h16", f"outcome of the h/16 graded copy on the controlled path: {h16_status} at lambda = "
           f"{h16_lam:.4g} (certified LB of the foundation {cap11.lb:.3f}; a limit below it is a false "
           "collapse); value 1 when completed or an honest NonConvergence, or a limit above the LB",
           float(honest or above_floor), 1.0, bool(honest or above_floor))  # fmt: skip

# %% [markdown]
# Measured (commit 46f05b4, stored): the controlled path stops in `NonConvergence` at λ = 0.156 after 147 s —
# a work-control step whose load-factor correction blows up (−2·10¹³) at the strip's end node, where the strip
# cracks and the contact opens. It is a failure and says so, which is what the row asks; it is not yet a
# solver that carries this copy to its service load (the certified floor of the foundation is 1.68 times it,
# so whatever stops below that is the solver's, not the foundation's).

# %% [markdown]
# ## Summary
# A scene is a handful of components; `build()` makes only the groups it needs, `solve()` returns settlements,
# contact pressures and zones, cracks and steel stresses; the steel stress is checked against an independent
# layer-free section calculation (0.9 %). Settlement and moment converge under mesh refinement, but slowly.
# Over the four meshes h = 1 … 0.125 m (full mode; the default solver, 41 s for the finest on a loaded
# machine) the successive orders of the column settlement are 0.70 and 0.67 and those of the mid-span moment
# 0.39 and 0.69; the fitted orders are 0.68 and 0.54, so the row `ch11_mesh_order` passes its h^(1/2) bound,
# and the Richardson estimate of the finest mesh's error is about 4 % (settlement) and 4.5 % (moment). The
# three coarse meshes of fast mode alone give a moment order below 1/2: they are pre-asymptotic, as the linear
# variant shows without any yield or cracking — its settlement's successive order rises from 0.55
# (h = 1 → 0.25 m) to 1.16 (0.5 → 0.125 m), and its mid-span moment's changes first grow (order −1.08) before
# they shrink at order 0.95. Yielding under the strip's edges and the contact's slip and opening may slow the
# convergence further; that is not isolated here. A design moment to a few per cent needs h = 0.125 m or a
# Richardson extrapolation (chapter 13). An iterate stopped at 5 % residual still balances the loads in its
# contact resultant and its base reaction to round-off (its residual is self-equilibrated), so that row is
# consistency only; its settlement misses the converged one by 4.6·10⁻³, caught by the method check (10⁻³).
# The controlled path and the paper's modified Newton–Raphson give the same answer; the measured iteration
# counts and wall times above are the trade between them. Beyond steel yield this particular beam forms a
# plastic hinge at mid-span; load control then stops with a `NonConvergence` report naming the node — the
# controlled path (the default) or `run_arc_length` (chapter 06) follows the path further.
