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
# # 02a — The layered plate strip: a locking-free 3-node Mindlin element (paper §4, §10)
#
# The foundation in every scene is a plate strip bent to a cylindrical surface: a strip of unit width that
# stretches, bends and shears in the (x, z) plane. The paper discretises it with 3-node quadratic elements of
# Mindlin (Timoshenko) type, layered through the thickness so that concrete and smeared reinforcement can each
# have their own law (eqs. 4.1–4.7b), and integrates it selectively along the element (§10). This part derives
# the element and checks its properties, with linear-elastic layers; the cracking concrete and yielding steel
# of §5 plug into the same kernel later (chapter 03).
#
# Chapter 02 is the plate strip in five parts, each with its own verification: **02a** the element (theory,
# properties, internal force), **02b** the Timoshenko closed forms, **02c** the locking study, **02d** the
# layer rule, **02e** the trade between error, elements, layers and wall time.
#
# **In this chapter you will**
# - derive the strip's kinematics, strains, section forces and the stiffness block of eq. (4.7b), and see why
#   the internal-force vector computed from layer stresses equals K₀u for elastic layers;
# - check the element's properties: zero force at zero displacement, a symmetric stiffness, exactly three
#   rigid-body modes — and what the spurious modes of under-integration look like.

# %% [markdown]
# ## Theory
#
# **Kinematics (eqs. 4.1–4.3).** z points upwards from the *reference surface*, on which the nodes lie (the
# mid-depth unless stated). A normal to it stays straight but not necessarily normal (Mindlin's hypothesis):
#
# $$u(x,z) = \bar u(x) - z\,\alpha(x),\qquad w(x,z) = \bar w(x),\qquad \gamma = \bar w' - \alpha .$$
#
# α is the rotation of the normal; it equals the slope w̄′ when the transverse shear strain γ vanishes.
# A positive α′ (sagging, concave up) stretches the bottom fibres (z < 0) — tension is positive.
#
# **Strains and stresses (eqs. 4.4–4.5).** With ε₀ = ū′ and the curvature k = α′,
#
# $$\varepsilon_x(z) = \varepsilon_0 - z\,k,\qquad
#   \sigma_x = D_1\varepsilon_x,\ D_1 = \frac{E}{1-\nu^2},\qquad
#   \tau_{xz} = \kappa D_2\gamma,\ D_2 = \frac{E}{2(1+\nu)} .$$
#
# D₁ is the plane-strain (cylindrical bending) modulus. κ is the shear correction factor: the paper writes
# eq. (4.4) with κ = 1; a uniform shear strain through the depth over-estimates the shear stiffness of a
# rectangle, whose parabolic τ gives κ = 5/6 by energy. The code makes κ a named parameter, default 5/6
# (its effect is measured in chapter 02c).
#
# **Section forces** per unit width — with M positive in sagging:
#
# $$N = \int\sigma_x\,dz,\qquad M = -\int z\,\sigma_x\,dz,\qquad
#   Q = \int_{\text{shear layers}}\tau_{xz}\,dz .$$
#
# The internal virtual work of the strip is then δW = ∫ (δε₀ N + δk M + δγ Q) dx.
#
# **Discretisation (eq. 4.6).** Each node carries (u, w, α); all three are interpolated with the quadratic
# Lagrange functions on ξ = −1, 0, +1 (nodes left, middle, right), and x = Σ Nᵢ xᵢ. So ε₀ = Σ Nᵢ′uᵢ,
# k = Σ Nᵢ′αᵢ, γ = Σ (Nᵢ′wᵢ − Nᵢαᵢ), and the element internal force vector is
#
# $$f_i = \int_{L_e}\Big(\frac{\partial\varepsilon_0}{\partial a_i}N + \frac{\partial k}{\partial a_i}M
#   + \frac{\partial\gamma}{\partial a_i}Q\Big)\,dx .$$
#
# Differentiating once more with N, M, Q linear in the strains gives the stiffness block of eq. (4.7a); the
# membrane–bending coupling −Nᵢ′ z D₁ Nⱼ′ vanishes only if the section is symmetric about the reference
# surface.
#
# **Layers (eq. 4.7b).** The section is a stack of layers n with mid-depth zₙ and thickness hₙ, each with its
# own law: concrete, or steel smeared into a layer of *mechanically equivalent thickness* — the bar area per
# unit width — which carries axial stress only. Integrating z² exactly over one layer gives
# ∫z² dz = hₙ(zₙ² + hₙ²/12): the rectangular rule plus the layer's own bending term. That is eq. (4.7b).
#
# **Internal force from layer stresses.** The nonlinear laws of §5 are *total*: the stress follows from the
# total strain (and a history). The kernel calls each layer's law once, at its mid-depth zₙ, and takes the
# stress as linear within the layer with a modulus eₙ — option `self_bending`: the chord through the stresses
# the law gives at the layer's two faces (default, `"chord"`:
# $M_{self}=\frac{h_n^2}{12}(\sigma_{bot}-\sigma_{top})$), the layer's tangent modulus (`"tangent"`), or its
# initial modulus e₀ₙ (its D₁, `"initial"`):
#
# $$N = \sum_n h_n\sigma_n,\qquad M = -\sum_n h_n z_n\sigma_n + \sum_n e_{n}\frac{h_n^3}{12}k .$$
#
# For a linear law the stress *is* linear within the layer, so this is the exact integral and f = K₀u with
# K₀ of eq. (4.7b) — for any number of layers (asserted below). For a nonlinear law the last term is an
# O(hₙ²) correction that vanishes as the layers get thinner. With e₀ₙ it keeps f continuous when a layer
# cracks or yields and the consistent tangent exact, but a cracked or crushed layer keeps its elastic bending
# stiffness; with the tangent modulus it follows the layer's state, but f jumps by O(hₙ³) when a layer changes
# branch; the chord follows the state *and* keeps f continuous, with an exact (non-symmetric) tangent. The
# trade study of chapter 02e measures both and picks the default from the evidence (Fig. 2.6).
#
# **Integration along the element (§10).** Three rules are options of the element:
#
# | option | membrane + bending | shear | note |
# |---|---|---|---|
# | `"selective"` (paper, default) | 3-point Gauss | 2-point Gauss | locking-free |
# | `"full"` | 3-point | 3-point | shear locking |
# | `"reduced"` | 2-point | 2-point | uniform reduction |
#
# Why full integration locks: for a thin strip the shear stiffness κGh ≫ EI/L², so the discrete solution
# approaches γ = 0 at every point where shear is sampled. With 3 points and γ = w′ − α quadratic, that forces
# α″ = 0 in every element — curvature piecewise constant — a constraint the true solution does not satisfy.
# With 2 points only the "consistent" part of γ is constrained, and the Kirchhoff limit is reached without
# spurious stiffening. Note that for a *straight* element with a centred mid node, 2-point Gauss already
# integrates the bending term (Nᵢ′Nⱼ′, a quadratic) exactly, so `"reduced"` and `"selective"` give the same
# linear stiffness there; they differ on distorted elements and when a nonlinear law makes the section
# stiffness vary along the element (2 vs 3 sampling points of cracking).
#
# | paper | code | meaning |
# |---|---|---|
# | ū, w̄, α | node DOFs `u, w, alpha` (comp 0, 1, 2) | mid-surface displacements, rotation |
# | ε₀, α′, γ | `eps0, kap, gam` in `ssi.elements.plate._section` | membrane strain, curvature, shear strain |
# | D₁, D₂ | `e0, g0 = section.initial_moduli()` | initial layer moduli |
# | κ | `PlateStrip(..., kappa=5/6)` | shear correction factor |
# | zₙ, hₙ, lw | `section.z_mid, section.h, section.n_layer` | layer mid-depth, thickness, count |
# | N, M, Q | `group.resultants(u_el)` | section forces per unit width (M sagging +) |
# | eq. (4.7b) | `group.elastic_stiffness()` | element K₀ (n_el, 9, 9) |

# %%
import inspect

import matplotlib.pyplot as plt
import numpy as np

from ssi.core.protocol import CONSISTENT
from ssi.core.shapes import lagrange3
from ssi.elements import plate as plate_module
from ssi.elements.plate import PlateStrip
from ssi.elements.section import homogeneous, paper_rc_section
from ssi.elements.supports import plate_strip_model
from ssi.lab import paths, report
from ssi.lab.examples import CHAPTER02_STRIP
from ssi.lab.verify import dense_stiffness, zero_energy_modes
from ssi.materials import rc
from ssi.materials.layer_laws import CONCRETE, STEEL

FAST = paths.FAST
E, NU, H = CHAPTER02_STRIP.E, CHAPTER02_STRIP.nu, CHAPTER02_STRIP.h  # 30 GPa, 0.2, 1 m (span/depth = span)
print(f"fast mode: {FAST}")

# %% [markdown]
# The whole section response of one sampling point — the loop over layers, the law call at mid-depth, the
# h²/12 self-bending term and the section tangent — is this kernel (printed from the library, not retyped):

# %%
print(inspect.getsource(plate_module._section.py_func))


# %% [markdown]
# ## Building blocks
#
# A strip on supports is a few lines with `ssi.core.model.Model`: `add_plate_strip` adds the nodes (3 DOFs
# each) and the element group; supports act on u, w, α; nodal forces with `add_load`, distributed loads
# through the element's equivalent nodal forces (`distributed_load`, exact for loads up to cubic). The strips
# of this chapter's parts are built by `ssi.elements.supports.plate_strip_model`, `simply_supported_strip` and
# `cantilever_strip`, and compared with the Timoshenko closed forms of `ssi.lab.analytical`.

# %% [markdown]
# ## 1. Element properties
#
# Zero force at zero displacement, symmetric stiffness, and the zero-energy modes of a free strip. The
# properties are checked on the paper's reinforced section (11 layers, steel in layers 2 and 10, laws of
# chapter 03) with an off-centre middle node, so that the Jacobian varies along the element.

# %%
conc = rc.concrete_params(fc=30e6, E0=30e9, eps_c=0.002, fr=3e6, Gf=100.0, ls=0.1, eps_y=2.5e-3)
steel = rc.steel_params(fy=500e6, Es=200e9, EH=2e9)
rc_sec = paper_rc_section(0.5, 0.05, 1.5e-3, 0.8e-3, (CONCRETE, conc), (STEEL, steel))
print(
    "paper section: layers",
    rc_sec.n_layer,
    " steel layers (1-based):",
    (np.flatnonzero(rc_sec.kind == STEEL) + 1).tolist(),
)

xy1 = np.array([[0.0, 0.0], [0.22, 0.0], [0.5, 0.0]])
one = PlateStrip(xy1[None], np.arange(9)[None], rc_sec)
zero = np.zeros((1, 9))
f0, k0, s0 = one.evaluate(zero, zero, one.initial_state(), CONSISTENT)
zero_force = np.abs(f0).max()
asym = np.abs(k0 - k0.transpose(0, 2, 1)).max() / np.abs(k0).max()
print(f"|f(0)| = {zero_force:.1e} N,  max |K - K^T| / max |K| = {asym:.1e}")


def free_strip_stiffness(n_el, integration, section):
    """The unsupported dense stiffness of a free strip of ``n_el`` elements, 2 m each."""
    model, group, _ = plate_strip_model(n_el, 2.0 * n_el, section, integration)
    return dense_stiffness(model.n_dof, [group])


hom2 = homogeneous(H, E, NU, 2)
modes = {}
for rule in ("selective", "full", "reduced", (1, 1), (2, 1)):
    modes[str(rule)] = [zero_energy_modes(free_strip_stiffness(n, rule, hom2)) for n in (1, 2, 4)]
print("zero-energy modes of a free strip of 1, 2, 4 elements:")
for rule, counts in modes.items():
    print(f"  {rule:>10s}: {counts}")

# reduced (2/2) and selective (3/2) coincide for straight elements with a centred mid node...
k_sel = PlateStrip(np.array([[[0, 0], [1, 0], [2, 0]]], float), np.arange(9)[None], hom2).elastic_stiffness()
k_red = PlateStrip(
    np.array([[[0, 0], [1, 0], [2, 0]]], float), np.arange(9)[None], hom2, integration="reduced"
).elastic_stiffness()
same_straight = np.abs(k_sel - k_red).max() / np.abs(k_sel).max()
# ... but not on a distorted one
k_sel_d = PlateStrip(
    np.array([[[0, 0], [0.8, 0], [2, 0]]], float), np.arange(9)[None], hom2
).elastic_stiffness()
k_red_d = PlateStrip(
    np.array([[[0, 0], [0.8, 0], [2, 0]]], float), np.arange(9)[None], hom2, integration="reduced"
).elastic_stiffness()
diff_distorted = np.abs(k_sel_d - k_red_d).max() / np.abs(k_sel_d).max()
print(
    f"selective vs reduced stiffness: straight {same_straight:.1e}, off-centre mid node {diff_distorted:.2e}"
)

# %% [markdown]
# Every rule the paper discusses — selective, full, and uniformly reduced 2/2 — leaves exactly the three
# rigid-body modes (u translation, w translation, rigid rotation w = θx, α = θ). Uniform 2-point reduction
# of this *quadratic* element has no spurious mode at all, because 2 points still integrate its bending term
# exactly. Spurious modes appear one step further down: with one point for everything, a single element has
# three extra zero-energy modes (6 in total), and a one-point shear rule (2, 1) leaves one. Figure 2.1 shows
# the three spurious modes of the one-point element — displacement patterns that strain the element but are
# invisible at its only sampling point. In a mesh they propagate (the counts do not drop to 3), which is why
# such a rule is unusable.

# %%
g11 = PlateStrip(np.array([[[0, 0], [1, 0], [2, 0]]], float), np.arange(9)[None], hom2, integration=(1, 1))
ev, vec = np.linalg.eigh(g11.elastic_stiffness()[0])
null = vec[:, ev < 1e-10 * ev.max()]
x_nodes = np.array([0.0, 1.0, 2.0])
rigid = np.zeros((9, 3))
rigid[0::3, 0] = 1.0  # u translation
rigid[1::3, 1] = 1.0  # w translation
rigid[1::3, 2] = x_nodes  # rigid rotation: w = theta x, alpha = theta
rigid[2::3, 2] = 1.0
qr, _ = np.linalg.qr(rigid)
spurious = null - qr @ (qr.T @ null)  # remove the rigid part of the null space
u_s, s_s, _ = np.linalg.svd(spurious)
spurious = u_s[:, : int(np.sum(s_s > 1e-8))]
n_spurious = spurious.shape[1]
xi = np.linspace(-1, 1, 101)
shape = np.array([lagrange3(s)[0] for s in xi]).T  # (3, 101) quadratic Lagrange N_i(xi)
fig, axes = plt.subplots(1, n_spurious, figsize=(3.6 * n_spurious, 3.0), sharey=True)
for j, ax in enumerate(np.atleast_1d(axes)):
    v = spurious[:, j] / np.abs(spurious[:, j]).max()
    for c, (name, style) in enumerate((("u", "C0-"), ("w", "C1--"), ("alpha", "C2:"))):
        ax.plot(1 + xi, v[c::3] @ shape, style, label=name)
        ax.plot(x_nodes, v[c::3], style[:2] + "o", ms=4)
    ax.axvline(1.0, color="0.7", lw=0.8)
    ax.set_title(f"spurious mode {j + 1}")
    ax.set_xlabel("x [m] (sampling point at x = 1)")
axes[0].legend()
fig.suptitle("Fig. 2.1 — Zero-energy modes of a one-point (1, 1) element beyond the 3 rigid-body modes")
fig.tight_layout()
report.save_figure(fig, "fig02_spurious_modes")

# %% [markdown]
# ## 2. Internal force from layer stresses equals K₀u
#
# The same section split into 1, 2, 11 and 50 layers, a random displacement of an element with an off-centre
# middle node: the force computed from layer stresses (one law call per layer at mid-depth, plus the exact
# h²/12 term) against the stiffness of eq. (4.7b) times u.

# %%
rng = np.random.default_rng(2)
xy_d = np.array([[[0.0, 0.0], [1.1, 0.0], [2.0, 0.0]]])
fk_err = {}
k_by_layers = {}
for n_layers in (1, 2, 11, 50):
    g = PlateStrip(xy_d, np.arange(9)[None], homogeneous(H, E, NU, n_layers))
    u = rng.standard_normal((1, 9)) * 1e-3
    f, _, _ = g.evaluate(u, u, g.initial_state(), CONSISTENT)
    fk_err[n_layers] = np.abs(f[0] - g.elastic_stiffness()[0] @ u[0]).max() / np.abs(f).max()
    k_by_layers[n_layers] = g.elastic_stiffness()[0]
print("max |f - K0 u| / max |f| by number of layers:", {k: f"{v:.1e}" for k, v in fk_err.items()})

# %% [markdown]
# ## Verification
#
# Tolerances: `ROUND` is for results that are exact in exact arithmetic (a few hundred ulps of the
# conditioning of these small systems).

# %%
ROUND = 1e-9
assert zero_force == 0.0, "internal force at zero displacement must vanish"
assert asym < ROUND, "stiffness must be symmetric"
assert modes["selective"] == [3, 3, 3], "selective: exactly the 3 rigid-body modes"
assert modes["full"] == [3, 3, 3] and modes["reduced"] == [3, 3, 3]
assert modes["(1, 1)"][0] == 6 and n_spurious == 3, "one-point rule: 3 spurious modes in one element"
assert modes["(1, 1)"][2] > 3 and modes["(2, 1)"][0] == 4, "spurious modes of under-integration propagate"
assert same_straight < ROUND and diff_distorted > 1e-3
# layer stresses reproduce eq. (4.7b)
assert max(fk_err.values()) < ROUND, "f_int must equal K0 u for elastic layers"
print("all chapter 02a checks passed")

# %% [markdown]
# ## Summary
#
# - The 3-node layered strip with **selective integration** (3-point bending, 2-point shear) has exactly the
#   three rigid-body modes, a symmetric stiffness and zero force at zero displacement. Uniform 2/2 reduction
#   equals selective on straight elements and has no spurious mode; a one-point rule would have three, and
#   they propagate through a mesh.
# - The internal force comes from **layer stresses** sampled at mid-depth with the exact h²/12 self-bending
#   term: identical to K₀u of eq. (4.7b) for elastic layers.
#
# References: W. Szajna, §4, §10; D. R. J. Owen and J. A. Figueiras (layered RC plates); G. Prathap, *The
# Finite Element Method in Structural Mechanics* (field consistency, locking of the quadratic beam element);
# J. Bleyer, COMET numerical tours (the Reissner–Mindlin locking table chapter 02c follows).
