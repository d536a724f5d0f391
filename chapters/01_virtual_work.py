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
# # 01 — Virtual work of two bodies in contact (paper §3, eq. 3.1)
#
# Every element of the paper comes out of one equation: the principle of virtual work for bodies that touch
# along a contact surface. This chapter takes the smallest scene that has every term of it — two elastic
# blocks joined by an interface, carrying their own weight and a surface load — and shows how each term
# becomes a stiffness matrix or a load vector, and that assembling them through `ssi` gives exactly the
# answer worked out by hand.
#
# **In this chapter you will**
# - read eq. (3.1) term by term and see which `ssi` object each term becomes;
# - build two blocks (8-node soil elements) joined by a zero-thickness interface, with self-weight and a
#   surface load, once pressed and once sheared;
# - solve the same scene by hand (a one-dimensional column: closed form);
# - check that the FE nodal displacements equal the hand solution to round-off, and that the internal virtual
#   work splits into a volume part and an interface part exactly as the hand calculation says.

# %% [markdown]
# ## Theory
#
# For bodies of volume V with outer surface S, joined along the contact surface S_c, equilibrium in weak form
# reads: for every admissible virtual displacement δu,
#
# $$\underbrace{\int_V \delta\varepsilon^T \sigma\, dV}_{\text{(a) bodies}}
#  + \underbrace{\int_{S_c} \delta\Delta u^T t_c\, dS_c}_{\text{(b) contact}}
#  = \underbrace{\int_V \delta u^T b\, dV}_{\text{(c) body force}}
#  + \underbrace{\int_S \delta u^T p\, dS}_{\text{(d) surface load}} \qquad (3.1)$$
#
# where Δu is the jump of displacement across S_c (upper body minus lower body) and t_c the contact traction
# that the jump produces. With displacements interpolated from nodal values, u = N d, ε = B d, Δu = B_c d,
# and linear laws σ = D ε, t_c = D_c Δu (D_c = diag(k_t, k_n), eq. 6.2), the equation must hold for every
# δd, so
#
# $$\Big(\underbrace{\textstyle\sum_e \int B^T D B\, dV}_{K_V}
#       + \underbrace{\textstyle\sum_c \int B_c^T D_c B_c\, dS}_{K_c}\Big)\, d
#   = \underbrace{\textstyle\sum_e \int N^T b\, dV}_{F_b}
#     + \underbrace{\textstyle\sum_s \int N^T p\, dS}_{F_p}.$$
#
# Term (a) gives the soil (and later plate) element stiffnesses, term (b) the interface stiffness, (c) and
# (d) the load vectors. Taking δd = d itself turns (3.1) into an energy balance: dᵀK_V d + dᵀK_c d = dᵀ(F_b +
#     F_p),
# the work done inside the bodies plus in the interface equals the work of the loads.
#
# | paper | code | meaning |
# |---|---|---|
# | ∫ δεᵀσ dV | `SoilQ8(...).elastic_stiffness()` (K_V per element) | term (a): bodies |
# | ∫ δΔuᵀ t_c dS_c | `add_interface(...)` → `Interface6`, its `k_el` (K_c) | term (b): contact |
# | ∫ δuᵀ b dV | `SoilQ8(..., unit_weight=γ).body_force()` | term (c): self-weight, b = (0, −γ) |
# | ∫ δuᵀ p dS | `edge_forces(...)` → `Model.add_element_load` | term (d): surface tractions |
# | k_t, k_n | `interface_params(kt, kn, ...)` | interface stiffness (eq. 6.2) |
# | d | `Result.u[-1]` (of `Model.solve_linear`) | nodal displacements |

# %%
import matplotlib.pyplot as plt
import numpy as np

from ssi.core.mesh import structured_q8
from ssi.core.model import Model
from ssi.elements.interface import add_interface
from ssi.elements.supports import edge_forces, fix_block, soil_group
from ssi.lab import report
from ssi.lab.verify import zero_energy_modes
from ssi.materials.interface_law import interface_params
from ssi.materials.soil_laws import ELASTIC, elastic_params

# %% [markdown]
# ## The scene
#
# A lower block (height H₁ = 2 m) on a fixed base and an upper block (H₂ = 1 m) on top of it, both 1 m wide,
# joined by a zero-thickness interface along z = H₁. The blocks have different stiffness and weight. Two
# load cases:
#
# - **A, pressed**: pressure p on the top and both self-weights; the sides are on vertical rollers (u = 0),
#   so every horizontal section is in the same state — a one-dimensional (oedometric) column. Terms (a),
#   (b: normal part k_n), (c) and (d) are all active.
# - **B, sheared**: a horizontal traction τ on the top, the complementary shear tractions ±τ on the sides
#   (so that the exact state is uniform simple shear), no weight, base fixed. Exercises the tangential part
#   k_t of term (b).
#
# The interface is integrated with the paper's Newton–Cotes rule (Simpson on the node pairs).

# %%
L, H1, H2 = 1.0, 2.0, 1.0
E1, NU1, G1_W = 40e6, 0.3, 20e3  # lower block: E [Pa], nu, unit weight [N/m^3]
E2, NU2, G2_W = 10e6, 0.25, 18e3  # upper block
KN, KT = 2e8, 5e7  # interface normal / tangential stiffness [Pa/m]
P_TOP, TAU_TOP = 50e3, 20e3  # surface pressure and shear traction [Pa]
NX, NZ1, NZ2 = 2, 2, 2  # elements across, in the lower and in the upper block


def constrained_modulus(E, nu):
    return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))


def shear_modulus(E, nu):
    return E / (2 * (1 + nu))


def build(case):
    """The two-block scene for load case 'A' (pressed, weight) or 'B' (sheared); returns what the checks
    need: model, groups, block meshes and node ids."""
    model = Model()
    low = structured_q8(np.linspace(0, L, NX + 1), np.linspace(0, H1, NZ1 + 1))
    up = structured_q8(np.linspace(0, L, NX + 1), np.linspace(H1, H1 + H2, NZ2 + 1))
    low_ids = model.add_nodes(low.xy, 2)
    up_ids = model.add_nodes(up.xy, 2)
    weight = case == "A"
    soil_low = soil_group(
        model, low, [(ELASTIC, elastic_params(E1, NU1))], ids=low_ids, unit_weight=[G1_W] if weight else None
    )
    soil_up = soil_group(
        model, up, [(ELASTIC, elastic_params(E2, NU2))], ids=up_ids, unit_weight=[G2_W] if weight else None
    )
    # term (b): the interface joins the upper block's bottom nodes to the lower block's top nodes
    bottom_of_up, top_of_low = up_ids[up.bottom], low_ids[low.surface]
    pairs = np.arange(0, len(top_of_low) - 2, 2)
    conn_lower = np.column_stack([top_of_low[pairs], top_of_low[pairs + 1], top_of_low[pairs + 2]])
    conn_upper = np.column_stack([bottom_of_up[pairs], bottom_of_up[pairs + 1], bottom_of_up[pairs + 2]])
    bonded = interface_params(KT, KN, 0.0, np.inf, None, np.inf)  # elastic: never slips, never opens
    contact = add_interface(model, conn_upper, conn_lower, bonded)

    def traction_on(node_line, traction):  # term (d) on the quadratic edges of a line of nodes
        edges = np.column_stack([node_line[0:-2:2], node_line[1:-1:2], node_line[2::2]])
        model.add_element_load(model.element_dofs(edges), edge_forces(model.coords[edges], traction))

    top = up_ids[up.surface]
    fix_block(model, low, low_ids, sides=False)
    if case == "A":
        traction_on(top, lambda x, z: (0.0 * x, -P_TOP + 0.0 * x))
        model.fix(
            np.concatenate([low_ids[low.left], low_ids[low.right], up_ids[up.left], up_ids[up.right]]), "u"
        )
    else:
        traction_on(top, lambda x, z: (TAU_TOP + 0.0 * x, 0.0 * x))
        for ids_left, ids_right in (
            (low_ids[low.left], low_ids[low.right]),
            (up_ids[up.left], up_ids[up.right]),
        ):
            traction_on(ids_right, lambda x, z: (0.0 * x, TAU_TOP + 0.0 * x))  # sigma . (+1, 0)
            traction_on(ids_left[::-1], lambda x, z: (0.0 * x, -TAU_TOP + 0.0 * x))  # sigma . (-1, 0)
    return model, (soil_low, soil_up, contact), low_ids, up_ids


# %% [markdown]
# ## Each term as a matrix
#
# One soil element's K_V block and one interface element's K_c: with Newton–Cotes integration an interface
# element couples each upper node only with the lower node under it, with the tributary lengths
# (1/6, 4/6, 1/6) × element length times k_n (normal) or k_t (tangential).

# %%
model_a, (soil_low, soil_up, contact), low_ids, up_ids = build("A")
k_if = contact.elastic_stiffness()[0]
le = L / NX
print("interface element: 12 DOFs = 3 upper nodes (u, w) then 3 lower nodes (u, w)")
print(
    "diagonal of K_c / (k * element length):",
    np.round(np.diag(k_if) / (le * np.tile([KT, KN], 6)), 4).tolist(),
)
coupling = k_if[:6, 6:]
print("upper-lower coupling block / (k * length):")
print(np.round(coupling / (le * np.array([KT, KN] * 3)[None, :]), 4))
k_soil = soil_low.elastic_stiffness()[0]
print(
    f"soil element K_V: 16 x 16, max asymmetry / max entry "
    f"{np.abs(k_soil - k_soil.T).max() / np.abs(k_soil).max():.1e}, "
    f"zero-energy modes: {zero_energy_modes(k_soil)}"
)
f_body = soil_up.body_force()
print(
    f"body force of one upper element: sum of vertical nodal forces = {f_body[0, 1::2].sum():.1f} N "
    f"(= -gamma * area = {-G2_W * (L / NX) * (H2 / NZ2):.1f} N)"
)

# %% [markdown]
# ## Solving through `ssi` and by hand
#
# **By hand, case A.** Every horizontal section carries the same vertical stress; with M =
# E(1−ν)/((1+ν)(1−2ν)) the constrained modulus of a laterally confined layer and z measured up from the base,
#
# - upper block: σ_z(z) = −[p + γ₂(H₁ + H₂ − z)];  lower block: σ_z(z) = −[p + γ₂H₂ + γ₁(H₁ − z)];
# - lower block: w(z) = ∫₀ᶻ σ_z/M₁ dz = −[(p + γ₂H₂ + γ₁H₁) z − γ₁z²/2] / M₁;
# - interface: the contact traction σ_n = −(p + γ₂H₂) opens a (negative) normal jump Δu_n = σ_n / k_n;
# - upper block: w(z) = w₁(H₁) + σ_n/k_n − [(p + γ₂(H₁ + H₂))(z − H₁) − γ₂(z² − H₁²)/2] / M₂, and u = 0.
#
# **By hand, case B.** Uniform shear τ everywhere: u = τz/G₁ below the interface, a slip τ/k_t across it,
# and u = τH₁/G₁ + τ/k_t + τ(z − H₁)/G₂ above, w = 0.
#
# Both fields are at most quadratic in z, which the 8-node elements contain exactly: the FE nodal values must
# equal the hand values to round-off.

# %%
M1, M2 = constrained_modulus(E1, NU1), constrained_modulus(E2, NU2)
G1, G2 = shear_modulus(E1, NU1), shear_modulus(E2, NU2)


def hand_case_a(z, upper):
    s1 = P_TOP + G2_W * H2 + G1_W * H1

    def w_low(zz):
        return -(s1 * zz - 0.5 * G1_W * zz**2) / M1

    if not upper:
        return w_low(z)
    sig_n = -(P_TOP + G2_W * H2)
    top = P_TOP + G2_W * (H1 + H2)
    return w_low(H1) + sig_n / KN - (top * (z - H1) - 0.5 * G2_W * (z**2 - H1**2)) / M2


def hand_case_b(z, upper):
    return TAU_TOP * (H1 / G1 + 1.0 / KT + (z - H1) / G2) if upper else TAU_TOP * z / G1


results = {}
for case in ("A", "B"):
    model, groups, lids, uids = build(case)
    res = model.solve_linear()
    z_low, z_up = model.coords[lids, 1], model.coords[uids, 1]
    if case == "A":
        fe = np.concatenate([res.displacement(lids, "w")[-1], res.displacement(uids, "w")[-1]])
        other = np.concatenate([res.displacement(lids, "u")[-1], res.displacement(uids, "u")[-1]])
        hand = np.concatenate([hand_case_a(z_low, False), hand_case_a(z_up, True)])
    else:
        fe = np.concatenate([res.displacement(lids, "u")[-1], res.displacement(uids, "u")[-1]])
        other = np.concatenate([res.displacement(lids, "w")[-1], res.displacement(uids, "w")[-1]])
        hand = np.concatenate([hand_case_b(z_low, False), hand_case_b(z_up, True)])
    # the terms of (3.1) with delta d = d: work inside the blocks, in the interface, and of the loads
    d = res.u[-1]
    work = {}
    for name, g in zip(("blocks", "interface"), (groups[:2], groups[2:])):
        w = 0.0
        for grp in g:
            de = d[grp.edofs]
            w += np.einsum("ei,eij,ej->", de, grp.elastic_stiffness(), de)
        work[name] = w
    f_ref, f_dead = model.load_vectors()
    work["loads"] = d @ (f_ref + f_dead)
    results[case] = {
        "fe": fe,
        "hand": hand,
        "other": other,
        "work": work,
        "z": np.concatenate([z_low, z_up]),
        "n_low": len(lids),
        "res": res,
        "model": model,
    }
    err = np.abs(fe - hand).max() / np.abs(hand).max()
    print(
        f"case {case}: max |FE - hand| / max|hand| = {err:.2e}; work: blocks {work['blocks']:.6e}, "
        f"interface {work['interface']:.6e}, loads {work['loads']:.6e} [J/m]"
    )

# hand values of the two internal-work terms of case A: integral of sigma^2 / M over each block, and
# sigma_n^2 / k_n over the contact (times the width L)
zz1 = np.linspace(0, H1, 2001)
zz2 = np.linspace(H1, H1 + H2, 2001)
sig1 = -(P_TOP + G2_W * H2 + G1_W * (H1 - zz1))
sig2 = -(P_TOP + G2_W * (H1 + H2 - zz2))
work_blocks_hand = L * (np.trapezoid(sig1**2, zz1) / M1 + np.trapezoid(sig2**2, zz2) / M2)
work_if_hand = L * (P_TOP + G2_W * H2) ** 2 / KN
print(f"case A by hand: blocks {work_blocks_hand:.6e}, interface {work_if_hand:.6e} [J/m]")

# %% [markdown]
# ## Verification
#
# - `TOL_EXACT = 1e-10`: the hand fields lie in the element space, so FE = hand up to the round-off of a
#   ~100-DOF solve (~1e-14); 1e-10 leaves a wide margin and still catches any wrong term (a wrong k_n, a
#   missing body force or a mis-integrated surface load changes the answer by percents).
# - Energy balance (3.1) with δd = d: blocks + interface = loads to 1e-10 relative.
# - The hand work integrals use the trapezoid rule on 2000 panels of a quadratic integrand: relative error
#   ~1e-7, hence `TOL_WORK = 1e-6`.

# %%
TOL_EXACT, TOL_WORK = 1e-10, 1e-6
for case, r in results.items():
    assert np.abs(r["fe"] - r["hand"]).max() < TOL_EXACT * np.abs(r["hand"]).max(), case
    assert np.abs(r["other"]).max() < TOL_EXACT * np.abs(r["hand"]).max(), case  # u = 0 (A), w = 0 (B)
    w = r["work"]
    assert abs(w["blocks"] + w["interface"] - w["loads"]) < TOL_EXACT * w["loads"], case
assert abs(results["A"]["work"]["blocks"] - work_blocks_hand) < TOL_WORK * work_blocks_hand
assert abs(results["A"]["work"]["interface"] - work_if_hand) < TOL_WORK * work_if_hand
# Newton-Cotes: the interface couples node pairs only, with Simpson weights (1/6, 4/6, 1/6) x length
nc = np.diag(k_if)[:6] / (le * np.tile([KT, KN], 3))
assert np.allclose(nc, [1 / 6, 1 / 6, 4 / 6, 4 / 6, 1 / 6, 1 / 6], rtol=1e-12)
assert np.count_nonzero(np.abs(k_if) > 1e-9 * np.abs(k_if).max()) == 12 + 12  # diagonal + pair couplings
print("all checks passed")

# %% [markdown]
# ## Figure

# %%
fig, axes = plt.subplots(1, 2, figsize=(10, 4.5), sharey=True)
for ax, case, label in ((axes[0], "A", "w [mm] (pressed, with weight)"), (axes[1], "B", "u [mm] (sheared)")):
    r = results[case]
    n = r["n_low"]
    for part, sl, color in (("lower block", slice(0, n), "C0"), ("upper block", slice(n, None), "C1")):
        zs = np.linspace(0, H1, 100) if part == "lower block" else np.linspace(H1, H1 + H2, 100)
        hand_fn = hand_case_a if case == "A" else hand_case_b
        ax.plot(1e3 * hand_fn(zs, part == "upper block"), zs, "-", color=color, label=f"hand, {part}")
        ax.plot(1e3 * r["fe"][sl], r["z"][sl], "o", mfc="none", color=color, label=f"FE nodes, {part}")
    ax.axhline(H1, color="k", lw=0.8, ls=":")
    ax.annotate("interface: jump Δu = t_c / k", (ax.get_xlim()[0], H1 + 0.05), fontsize=8)
    ax.set_xlabel(label)
axes[0].set_ylabel("z [m]")
axes[0].legend(fontsize=8)
fig.suptitle(
    "Figure 1.1 — two blocks joined by an interface: every term of eq. (3.1) assembled by ssi "
    "equals the hand solution"
)
report.save_figure(fig, "ch01_two_blocks")

# %% [markdown]
# ## Summary
#
# - Term (a) of eq. (3.1) is the soil element stiffness ∫BᵀDB dV, term (b) the interface stiffness
#   ∫B_cᵀD_cB_c dS (node-to-node with the paper's Newton–Cotes rule), terms (c) and (d) the consistent nodal
#   forces of self-weight and surface tractions.
# - Assembled by `ssi`, they reproduce the hand solution of a pressed and of a sheared two-block column at
#   every node to round-off, including the displacement jump across the interface.
# - With δd = d, eq. (3.1) is an energy balance: the work in the blocks plus the work in the interface
#   equals the work of the loads, and each part equals its hand integral.
#
# Reference: W. T. Koiter, as cited by the paper for eq. (3.1); O. C. Zienkiewicz, R. L. Taylor,
# *The Finite Element Method*, vol. 1, ch. 2 (virtual work → stiffness).
