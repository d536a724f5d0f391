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
# # 19 — Sites: boreholes, sloping ground, several foundations, stiffness growing with depth
#
# *Beyond the paper.* The paper's foundation rests on "an arbitrary system of geological layers" (§1, §2
# Fig. 1, §11); the scene of chapters 11–12 writes only a stack of level slabs. A site is what an engineer
# draws: layer boundaries measured in boreholes and interpolated between them, layers that pinch out, a
# ground surface that slopes, two foundations side by side, a clay whose stiffness grows with depth.
#
# In this chapter you will
# - describe a site by boreholes, a ground polyline and strips (`ssi.scene.site.Site`) and see the one
#   geometry description (`ssi.core.geometry.Geometry`) that both the soil mesh and a triangle mesher read;
# - mesh it with gmsh into 8-node serendipity quadrilaterals conforming to every boundary and refined
#   towards the foundations (`ssi.core.gmsh_mesh`), quality-checked;
# - check that a level borehole site on the structured path gives the layered scene's numbers;
# - compute the initial stress by gravity loading and check it against the K0 state on level ground;
# - check a strip load on Gibson's soil (G = m z, ν → ½) against Gibson's exact settlement;
# - put two strips on a four-layer borehole site and check elastic superposition on one mesh;
# - push a smooth rigid strip at the crest of a 30° slope and compare its capacity with the exact
#   slip-line value N_c = π + 2 − 2β;
# - re-check the 1-D column estimate of a beam over a dipping boundary, and check it where it applies;
# - push an embedded strip sideways with and without side contact (`Scene.side_contact`).
#
# ## Theory
#
# **Geometry.** The block x ∈ [−W/2, W/2], z ∈ [−D, z_g(x)] is cut by vertical lines at every *break*
# (ground vertices, boreholes, polyline vertices, foundation ends, load points, and the points where the
# ground crosses a layer boundary). Between two breaks every boundary is a straight segment, so each layer
# occupies a trapezoid (a triangle where it pinches out, nothing where it is absent). These cells tile the
# site; they share their edges, so any mesher that meshes each cell conforms to every boundary. A boundary
# between boreholes at x_a < x_b is interpolated linearly, z_k(x) = z_k(x_a) + (x − x_a)/(x_b − x_a)
# (z_k(x_b) − z_k(x_a)), level beyond the outermost boreholes, and cut by the ground: min(z_k, z_g).
#
# **Mesh.** gmsh meshes each cell (frontal-Delaunay for quadrilaterals), recombines the triangles into
# quadrilaterals (Blossom), subdivides what is left so that every element is a quadrilateral, and adds the
# mid-side nodes (incomplete second order): the Q8 of chapter 05. A threshold size field sets the size to
# h_fine at the foundations and lets it grow by (growth − 1) per metre up to h_coarse.
#
# **Initial stress.** On level ground over level boundaries the vertical stress is the weight of the column
# above, σ_v = Σ γ_i t_i, and σ_h = K0 σ_v (chapter 12). Elsewhere the state must be computed: *gravity
# loading* solves K u_g = f_γ (the soil's weight on the soil alone, elastic) and keeps σ_0 = D B u_g, which
# is in discrete equilibrium with the weight, discarding u_g. On level ground with rollers on the sides,
# ε_xx = 0 gives σ_h/σ_v = ν/(1 − ν) exactly — the check below.
#
# **Gibson soil.** For G(z) = m z (z depth) and ν = ½, Gibson (1967) showed that a surface pressure q
# settles the half-space by w = q/(2m) under the load and not at all outside it: the soil acts as a
# Winkler foundation of modulus 2m. In a closed block of incompressible soil the volume pushed down under
# the load heaves the far ground uniformly, so the check compares the settlement *relative to the far
# ground*.
#
# | paper / text | code |
# |---|---|
# | layer boundaries from boreholes | `Borehole(x, boundaries)` |
# | ground surface z_g(x) | `Site.ground`, `Site.ground_z` |
# | E = E_ref + E_inc · depth | `DepthVarying(layer, E_inc, c_inc, z_ref)` |
# | gravity loading σ_0 = D B u_g | `Site(initial_stress="gravity")` |
# | Gibson's w = q/(2m) | `ssi.scene.site.gibson_settlement` |

# %%
import time

import matplotlib.pyplot as plt
import numpy as np

from ssi.elements.section import homogeneous
from ssi.lab import paths
from ssi.lab.bearing_capacity import footing_settings
from ssi.lab.report import check, save_figure
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Push, Scene, SoilLayer, SurfacePressure
from ssi.scene.site import Borehole, DepthVarying, RigidStrip, Site, Strip, gibson_settlement

FAST = paths.FAST
H_FINE = 0.25 if FAST else 0.125
MESH = MeshSize(h_fine=H_FINE, h_coarse=2.0)
SECTION = homogeneous(0.5, 30e9, 0.2)
CONTACT = Contact(kn=1e10, kt=1e9)
TWO = [
    SoilLayer(3.0, E=20e6, nu=0.3, unit_weight=18e3),
    SoilLayer(7.0, E=60e6, nu=0.25, unit_weight=20e3),
]

# %% [markdown]
# ## 1. A level borehole site is the layered scene
#
# Two boreholes find the boundary at 3 m both; the site's structured path builds the same graded block as the
# scene, so the numbers must agree to round-off (1e-10 relative: the same arithmetic in another order would
# differ by a few ulp). The same site on the gmsh mesh differs by the discretisation error; we show it next to
# the change of the gmsh result under halving h_fine, its own error indicator.

# %%
loads = [ColumnLoad(0.0, N=400e3)]
scene = Scene(width=20.0, depth=10.0, layers=TWO, foundation=Foundation(-1.0, 1.0, SECTION), contact=CONTACT,
              loads=loads, mesh=MESH)  # fmt: skip


def level_site(mesher, mesh=MESH):
    return Site(20.0, 10.0, TWO, boreholes=[Borehole(-5.0, [-3.0]), Borehole(5.0, [-3.0])],
                strips=[Strip(Foundation(-1.0, 1.0, SECTION), CONTACT)], loads=loads, mesh=mesh,
                mesher=mesher)  # fmt: skip


x_ref, w_ref = scene.build().solve().settlement()
built_s = level_site("auto").build()
x_s, w_s = built_s.solve().strip_settlement(0)
equal_err = float(np.abs(w_s - w_ref).max() / np.abs(w_ref).max())
w_gmsh = {}
for h in (2 * H_FINE, H_FINE):
    m = MeshSize(h_fine=h, h_coarse=2.0)
    w_gmsh[h] = level_site("gmsh", m).build().solve().strip_settlement(0)[1].max()
w_struct_max = w_ref.max()
gmsh_diff = abs(w_gmsh[H_FINE] - w_struct_max) / w_struct_max
gmsh_change = abs(w_gmsh[H_FINE] - w_gmsh[2 * H_FINE]) / w_struct_max
print(f"structured path: {built_s.mesher}, {built_s.initial_stress_method}; max |dw|/w = {equal_err:.2e}")
print(f"max settlement: layered scene {1e3 * w_struct_max:.3f} mm, gmsh h={2 * H_FINE}: "
      f"{1e3 * w_gmsh[2 * H_FINE]:.3f} mm, h={H_FINE}: {1e3 * w_gmsh[H_FINE]:.3f} mm")  # fmt: skip
print(f"gmsh vs structured {gmsh_diff:.2%}; gmsh change under refinement {gmsh_change:.2%}")

# %% [markdown]
# ## 2. Gravity loading against K0 on level ground
#
# The elastic gravity phase on the structured block: σ_v against the weight of the column above (1e-6
# relative: the exact state is quadratic in z, in the Q8 space, so only round-off remains) and σ_h/σ_v against
# ν/(1 − ν) (1e-6 absolute). On a gmsh mesh of general quadrilaterals the quadratic field is not reproduced
# exactly; its error is shown, not asserted.


# %%
def gravity_error(mesher):
    site = Site(12.0, 10.0, TWO, boreholes=[Borehole(0.0, [-3.0])], initial_stress="gravity", mesher=mesher,
                mesh=MESH)  # fmt: skip
    built = site.build()
    sig, z = built.soil.initial_stress, built.soil.integration_points()[..., 1]
    sv = np.where(z > -3.0, 18e3 * z, -54e3 + 20e3 * (z + 3.0))
    nu = np.where(z > -3.0, 0.3, 0.25)
    return (
        built.initial_stress_method,
        float(np.abs(sig[..., 1] - sv).max() / np.abs(sv).max()),
        float(np.abs(sig[..., 0] / sig[..., 1] - nu / (1 - nu)).max()),
    )


grav = {mesher: gravity_error(mesher) for mesher in ("structured", "gmsh")}
for mesher, (method, e_v, e_k) in grav.items():
    print(f"{mesher:10s} {method}: sigma_v rel. error {e_v:.2e}, sigma_h/sigma_v - nu/(1-nu) {e_k:.2e}")

# %% [markdown]
# ## 3. Gibson's soil
#
# G = m z with m = 1 MPa/m, ν = 0.499 (E_inc = 2(1 + ν) m, E_ref ≈ 0), a flexible strip of half-width
# b = 1 m under q = 100 kPa, block 40 m × 20 m. The modulus is evaluated at each Gauss point of the soil
# elements (`Site.depth_varying="gauss"`, the default: a material row per point); the same site sampled
# once per element at its centroid (`"centroid"`, a piecewise-constant modulus) is shown beside it. The
# centroid version errs most near the surface, where G = m z changes fastest relative to itself: the top
# element's centroid modulus stands for a field that runs from zero to twice it.

# %%
nu_g, m_g, q_g, b_g = 0.499, 1e6, 100e3, 1.0
gibson_layer = DepthVarying(SoilLayer(1.0, E=1e-3 * m_g, nu=nu_g, nu_u=nu_g), E_inc=2.0 * (1.0 + nu_g) * m_g)
w_exact = gibson_settlement(q_g, m_g)


def gibson(sampling):
    """(x, settlement relative to the far ground / Gibson's, max error under |x| <= b/2, max outside 2b)."""
    site = Site(40.0, 20.0, [gibson_layer], loads=[SurfacePressure(-b_g, b_g, q_g)],
                mesh=MeshSize(h_fine=H_FINE, h_coarse=4.0), depth_varying=sampling)  # fmt: skip
    x, w = site.build().solve().ground_settlement()
    rel = (w - w[0]) / w_exact  # relative to the far ground at the block's side
    under = float(np.abs(rel[np.abs(x) <= 0.5 * b_g] - 1.0).max())
    return x, w, under, float(np.abs(rel[np.abs(x) >= 2.0 * b_g]).max())


x_g, w_g, gibson_under, gibson_outside = gibson("gauss")
_, _, gibson_under_centroid, gibson_outside_centroid = gibson("centroid")
print(f"Gibson w = q/2m = {1e3 * w_exact:.1f} mm; far-ground heave {-1e3 * w_g[0]:.2f} mm")
for name, under, outside in (("Gauss points", gibson_under, gibson_outside),
                             ("centroids", gibson_under_centroid, gibson_outside_centroid)):  # fmt: skip
    print(f"E at the {name}: under |x| <= b/2: max |w_rel/w - 1| = {under:.2%}; outside |x| >= 2b: "
          f"max |w_rel|/w = {outside:.2%}")  # fmt: skip

# %% [markdown]
# Gibson's check mixes the sampling error with that of ν = 0.499 and of the closed block. An exact check of
# the sampling alone: a column confined sideways (the pressure over the whole width, rollers on the sides)
# with E = E0 + k·depth settles q c ln(1 + kH/E0)/k, c = (1 + ν)(1 − 2ν)/(1 − ν). Sampled at the Gauss
# points the error falls with h² (a linear E integrated by the element's own rule); at the centroids it is
# a piecewise-constant E, first order and several times larger (asserted below).


# %%
def column_error(h, sampling, e0=1e6, k=4e6, nu=0.3, q=100e3, depth=10.0):
    lay = DepthVarying(SoilLayer(1.0, E=e0, nu=nu), E_inc=k)
    site = Site(4.0, depth, [lay], loads=[SurfacePressure(-2.0, 2.0, q)],
                mesh=MeshSize(h_fine=h, h_coarse=h, growth=1.0), depth_varying=sampling)  # fmt: skip
    _, w = site.build().solve().ground_settlement()
    return float(w.mean() / (q * (1 + nu) * (1 - 2 * nu) / (1 - nu) * np.log(1 + k * depth / e0) / k) - 1.0)


column = {s: [column_error(h, s) for h in (1.0, 0.5)] for s in ("gauss", "centroid")}
for s, errs in column.items():
    e1, e2 = 100 * errs[0], 100 * errs[1]
    print(f"confined column, E at the {s}: error {e1:+.2f} % (h = 1 m), {e2:+.2f} % (h = 0.5 m)")

# %% [markdown]
# ## 4. Two strips on a four-layer borehole site
#
# Three boreholes; the second layer pinches out at x = 0. Strip A (x ∈ [−6, −4]) carries 300 kN/m, strip B
# (x ∈ [3, 5]) 200 kN/m. The soil and the bonded contact are elastic, so the two-strip solution is the sum of
# the single ones on the same mesh (1e-10: round-off of a linear solve); the gmsh mesh is the same for the
# three sites because the load points are the same and gmsh runs deterministically (asserted).

# %%
FOUR = [
    SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3),
    SoilLayer(1.0, E=30e6, nu=0.3, unit_weight=19e3),
    SoilLayer(1.0, E=50e6, nu=0.3, unit_weight=19e3),
    SoilLayer(1.0, E=80e6, nu=0.3, unit_weight=20e3),
]
BOREHOLES = [Borehole(-10.0, [-2.0, -4.0, -7.0]), Borehole(0.0, [-2.5, -2.5, -6.0]),
             Borehole(10.0, [-3.5, -5.0, -8.0])]  # fmt: skip


def two_strips(n_a, n_b):
    return Site(30.0, 12.0, FOUR, boreholes=BOREHOLES, mesh=MESH,
                strips=[Strip(Foundation(-6.0, -4.0, SECTION), CONTACT),
                        Strip(Foundation(3.0, 5.0, SECTION), CONTACT)],
                loads=[ColumnLoad(-5.0, N=n_a), ColumnLoad(4.0, N=n_b)])  # fmt: skip


two_strips(300e3, 200e3).build()  # warm-up (first gmsh call, plate and interface kernels)
t0 = time.perf_counter()
both = two_strips(300e3, 200e3).build()
mesh_s = time.perf_counter() - t0
only_a, only_b = two_strips(300e3, 0.0).build(), two_strips(0.0, 200e3).build()
same_mesh = np.array_equal(both.mesh.xy, only_a.mesh.xy) and np.array_equal(both.mesh.conn, only_b.mesh.conn)
out_both = both.solve()
u, ua, ub = out_both.u[-1], only_a.solve().u[-1], only_b.solve().u[-1]
superposition = float(np.abs(u - ua - ub).max() / np.abs(u).max())
sa, sb = out_both.strip_summary(0), out_both.strip_summary(1)
print(f"{both.mesher} mesh: {len(both.mesh.conn)} Q8, {both.model.n_dof} DOFs, quality {both.quality}; "
      f"initial stress: {both.initial_stress_method}; meshed and built in {mesh_s:.3f} s")  # fmt: skip
print(f"strip A: mean {1e3 * sa['mean']:.2f} mm, tilt {1e3 * sa['tilt']:.3f} mm/m; strip B: mean "
      f"{1e3 * sb['mean']:.2f} mm, tilt {1e3 * sb['tilt']:.3f} mm/m; differential A - B "
      f"{1e3 * out_both.differential_settlement(0, 1):.2f} mm; superposition error "
      f"{superposition:.1e}")  # fmt: skip

# %% [markdown]
# ### Plastic soil: the interaction against distance
#
# On a Mohr–Coulomb soil (c = 10 kPa, φ = 30°, ψ = 0) superposition no longer holds. Strip A (x ∈ [−2, 0])
# carries 250 kN/m alone and then with strip B, equally loaded, at a clear distance s to its right; the extra
# mean settlement of A caused by B is the interaction. It must fall monotonically with s (the plastic zones
# and the elastic stress bulbs separate) towards zero. Each strip carries its own weight (0.5 m of concrete,
# 25 kN/m³ × 0.5 m × 2 m = 25 kN/m, as a column load at its middle): an unloaded, weightless strip on a
# cohesionless contact floats -- its contact may open anywhere at no cost, so its position is not
# determined, and the controlled path stops in `NonConvergence` at λ = 0 on that strip's contact rather than
# pick one of those positions.

# %%
MC = [SoilLayer(1.0, E=20e6, nu=0.3, unit_weight=18e3, c=10e3, phi_deg=30.0, psi_deg=0.0)]
FRICTION = Contact(kn=1e10, kt=1e9, phi_deg=25.0)
WEIGHT = 25e3 * 0.5 * 2.0  # [N/m] each strip's own weight


def strip_a_settlement(gap, n_b):
    site = Site(40.0, 15.0, MC, mesher="gmsh", mesh=MeshSize(h_fine=0.25, h_coarse=3.0),
                strips=[Strip(Foundation(-2.0, 0.0, SECTION), FRICTION),
                        Strip(Foundation(gap, gap + 2.0, SECTION), FRICTION)],
                loads=[ColumnLoad(-1.0, N=250e3 + WEIGHT),
                       ColumnLoad(gap + 1.0, N=n_b + WEIGHT)])  # fmt: skip
    out = site.build().solve()
    assert out.result.status == "completed"
    return out.strip_summary(0)["mean"]


gaps = [1.0, 4.0] if FAST else [0.5, 1.0, 2.0, 4.0, 8.0]
interaction = []
for gap in gaps:
    alone, together = strip_a_settlement(gap, 0.0), strip_a_settlement(gap, 250e3)
    interaction.append((together - alone) / alone)
    print(f"clear distance {gap:4.1f} m: strip A {1e3 * alone:.2f} mm alone, {1e3 * together:.2f} mm with B "
          f"(+{interaction[-1]:.1%})")  # fmt: skip

# %% [markdown]
# ## 5. A beam over a dipping boundary
#
# A foundation beam (L = 10 m, 0.5 m concrete) under eleven equal columns (50 kN/m each, 1 m apart) rests on
# soft soil (E = 5 MPa) over stiff soil (E = 50 MPa) whose boundary dips 10° to the right: the soft layer is
# 2 m thick under the left end and 3.76 m under the right one, the block 8 m deep. The beam must tilt towards
# the soft side. A 1-D column estimate under each end, s = q Σ t_i / E_oed,i with q the mean pressure and
# E_oed = E (1 − ν) / ((1 + ν)(1 − 2ν)), gives a differential settlement to compare with. The 20 % is
# recorded, not asserted: the FE result, converged under refinement, is what it is.
#
# *Is the estimate a correct one?* Re-checked term by term: E_oed (not E) is the modulus of a column that
# cannot strain sideways, which is the 1-D assumption; the column runs from the ground to the block's fixed
# base at 8 m, the depth the FE soil has; the soft thicknesses under the ends (2.00 and 3.76 m) follow from
# the 10° dip. Within the 1-D model the beam's stiffness changes nothing: the column compliance
# Σ t_i / E_oed,i varies linearly along the beam (the boundary is straight), so the settlement q Σ t_i/E_oed,i
# is itself a straight line and a beam of any stiffness follows it under a uniform reaction, without bending.
# So the estimate is a correct 1-D estimate; what it leaves out is two-dimensional. The beam is 10 m long on
# 8 m of soil (L/H = 1.25), far from the wide-load limit where a column is confined: near the ends the load
# spreads sideways into unloaded soil, and the stiff beam draws pressure towards its ends. Replacing q by the
# elastic vertical stress under the end of a flexible strip load (Flamant's solution for a homogeneous
# half-space, σ_z = (q/π)(α + sin α cos(α + 2δ)), ≈ q/2 at an edge) goes too far the other way: it halves the
# estimate, while the beam's ends, carried by the stiff beam, settle with its middle. The FE differential lies
# between the two simple estimates (asserted below), within 20 % of neither: the FE is converged and the 1-D
# estimate is too crude for this geometry. This case stays as a study of where 1-D fails; the row is taken
# on the geometry below, chosen (before it was run) where a 1-D column is the right reference.

# %%
E_SOFT, E_STIFF, NU_D = 5e6, 50e6, 0.3
TAN10 = np.tan(np.radians(10.0))


def z_dip(x):
    return -2.0 - (x + 5.0) * TAN10  # the boundary: 2 m deep at the beam's left end, dipping to the right


def e_oed(e):
    return e * (1 - NU_D) / ((1 + NU_D) * (1 - 2 * NU_D))


def dipping(h):
    site = Site(40.0, 8.0, [SoilLayer(1.0, E=E_SOFT, nu=NU_D), SoilLayer(1.0, E=E_STIFF, nu=NU_D)],
                boundaries=[[(-20.0, z_dip(-20.0)), (20.0, z_dip(20.0))]],
                strips=[Strip(Foundation(-5.0, 5.0, SECTION), CONTACT)],
                loads=[ColumnLoad(x, N=50e3) for x in np.linspace(-5.0, 5.0, 11)],
                mesh=MeshSize(h_fine=h, h_coarse=2.0))  # fmt: skip
    x, w = site.build().solve().strip_settlement(0)
    return w[0], w[-1]


q_dip = 11 * 50e3 / 10.0
s_1d = {xe: q_dip * (-z_dip(xe) / e_oed(E_SOFT) + (8.0 + z_dip(xe)) / e_oed(E_STIFF)) for xe in (-5.0, 5.0)}
dip_h = [0.5, 0.25] if FAST else [0.5, 0.25, 0.125]
dip = {h: dipping(h) for h in dip_h}
for h, (wl, wr) in dip.items():
    print(f"h={h}: ends {1e3 * wl:.2f} / {1e3 * wr:.2f} mm, differential {1e3 * (wr - wl):.2f} mm; 1-D "
          f"{1e3 * s_1d[-5.0]:.2f} / {1e3 * s_1d[5.0]:.2f} mm, differential "
          f"{1e3 * (s_1d[5.0] - s_1d[-5.0]):.2f} mm")  # fmt: skip
diffs = [wr - wl for wl, wr in dip.values()]
dip_ratio = diffs[-1] / (s_1d[5.0] - s_1d[-5.0])
dip_change = abs(diffs[-1] - diffs[-2]) / abs(diffs[-1])


def flamant_sigma_z(x, z, q, x0, x1):
    """Vertical stress [Pa] at (x, depth z > 0) under a uniform strip load q [Pa] on [x0, x1] of a homogeneous
    elastic half-space (Flamant's line load integrated over the strip; Poulos & Davis 1974)."""
    t1, t2 = np.arctan((x - x0) / z), np.arctan((x - x1) / z)
    alpha = t1 - t2
    return q / np.pi * (alpha + np.sin(alpha) * np.cos(alpha + 2.0 * t2))


depth_d = np.linspace(1e-6, 8.0, 8001)  # column depth [m]: trapezoidal rule, converged to < 1e-6 relative
s_spread = {}
for xe in (-5.0, 5.0):
    eo = np.where(-depth_d > z_dip(xe), e_oed(E_SOFT), e_oed(E_STIFF))
    s_spread[xe] = float(np.trapezoid(flamant_sigma_z(xe, depth_d, q_dip, -5.0, 5.0) / eo, depth_d))
diff_1d, diff_spread = s_1d[5.0] - s_1d[-5.0], s_spread[5.0] - s_spread[-5.0]
print(f"differential: FE {1e3 * diffs[-1]:.2f} mm; 1-D columns under q {1e3 * diff_1d:.2f} mm "
      f"(FE/1-D {diffs[-1] / diff_1d:.3f}); 1-D columns under Flamant's edge stress "
      f"{1e3 * diff_spread:.2f} mm (FE/that {diffs[-1] / diff_spread:.3f})")  # fmt: skip

# %% [markdown]
# ### The row: a long, stiff beam over a thin compressible block
#
# A 1-D column is the right reference where (a) the loaded length is long against the soil's depth, so the
# soil under most of the beam is confined sideways, and (b) the beam's ends do not dip on their own: a
# flexible beam's end settles like the edge of a strip load, about half the 1-D value whatever L/H, while
# a stiff beam's ends follow its straight line (the pressure gathers under them instead) and the error
# falls with H/L. So the geometry is fixed as: L = 25 m on a block H = 5 m deep (L/H = 5), a 2 m concrete
# section (EI/(E_soft L³) ≈ 0.5: stiff), 26 columns of 50 kN/m 1 m apart (q = 52 kPa), the same soils, the
# boundary dipping 10° over the beam's length (0.3 m deep under its left end, 4.71 m under its right one,
# level beyond the ends), the block 60 m wide. The thin layers at the ends need a fine mesh everywhere
# (h_coarse = 0.5 m; with 2 m gmsh's elements there fail the quality check). The 1-D estimate is the same
# formula as above with the block's 5 m; the row asserts the 20 % on the differential settlement
# of the ends, converged under refinement (1 %).

# %%
L_LONG, H_LONG, Z_LEFT = 25.0, 5.0, 0.3


def z_long(x):
    return -Z_LEFT - (np.clip(x, -L_LONG / 2, L_LONG / 2) + L_LONG / 2) * TAN10


def long_beam(h):
    xs = [-30.0, -L_LONG / 2, L_LONG / 2, 30.0]
    site = Site(60.0, H_LONG, [SoilLayer(1.0, E=E_SOFT, nu=NU_D), SoilLayer(1.0, E=E_STIFF, nu=NU_D)],
                boundaries=[[(x, z_long(x)) for x in xs]],
                strips=[Strip(Foundation(-L_LONG / 2, L_LONG / 2, homogeneous(2.0, 30e9, 0.2)), CONTACT)],
                loads=[ColumnLoad(x, N=50e3) for x in np.linspace(-L_LONG / 2, L_LONG / 2, 26)],
                mesh=MeshSize(h_fine=h, h_coarse=0.5))  # fmt: skip
    x, w = site.build().solve().strip_settlement(0)
    return w[-1] - w[0]


q_long = 26 * 50e3 / L_LONG
s_long = {
    xe: q_long * (-z_long(xe) / e_oed(E_SOFT) + (H_LONG + z_long(xe)) / e_oed(E_STIFF))
    for xe in (-L_LONG / 2, L_LONG / 2)
}
diff_long_1d = s_long[L_LONG / 2] - s_long[-L_LONG / 2]
long_h = [0.5, 0.25] if FAST else [0.5, 0.25, 0.15]  # at h = 0.125 gmsh makes an element of 165.9 deg
diff_long = [long_beam(h) for h in long_h]
for h, d in zip(long_h, diff_long):
    print(f"long beam, h={h}: differential {1e3 * d:.2f} mm; 1-D {1e3 * diff_long_1d:.2f} mm "
          f"(FE/1-D {d / diff_long_1d:.3f})")  # fmt: skip
long_ratio = diff_long[-1] / diff_long_1d
long_change = abs(diff_long[-1] - diff_long[-2]) / abs(diff_long[-1])

# %% [markdown]
# ## 6. A strip footing at the crest of a slope: push-over capacity
#
# A smooth rigid strip (B = 1 m) on weightless undrained clay (Tresca: Mohr–Coulomb with φ = ψ = 0,
# c_u = 20 kPa), its right edge at the crest (λ = b/B = 0) of a β = 30° slope 2 m high, is pushed down
# (`RigidStrip`, displacement control) until the pressure levels off.
#
# **Reference.** For weightless soil the slip-line field is Prandtl's with its fan shrunk from π/2 to π/2 − β:
# the passive triangle now lies under the slope face, whose major principal stress runs along the face. Along
# the fan the mean stress grows by 2 c_u per radian, so q_u = c_u (1 + 2(π/2 − β) + 1), i.e.
# N_c = π + 2 − 2β = 4.094 for β = 30°. Its stress field is statically admissible (a lower bound) and its
# mechanism, the rigid triangle under the footing sliding along the smooth base, kinematically admissible (an
# upper bound): for a smooth base the value is exact. It is also the φ = 0 ground-inclination factor of
# Vesić (1975), N_c = 5.14 − 2β. The issue asks for a table value of Georgiadis (2010) or of Shiau,
# Merifield, Lyamin & Sloan (2011), whose undrained slope charts address this problem; their tables could not
# be obtained here (only abstracts), so none is quoted, and the closed form is the limit-analysis value this
# row checks. A *rough* base forbids the triangle's sliding, so for it π + 2 − 2β is only a lower bound (the
# rough base is printed below in full mode on the coarser mesh, h = B/8: 4.75 c_u, 16 % above π + 2 − 2β
# (14 % at h = B/16, and 4.58 c_u, 12 % above, at h = B/32 while this section was written, still falling
# slowly; the rough B/16 push cost 8.5 s CPU against 2.7 s at B/8, in every full run, for a remark); the
# smooth base is the case with an exact value.
#
# The slope is 2B high: the mechanism's passive triangle has its hypotenuse, of length B, on the face, so it
# reaches 0.5 m below the crest, well above the toe. Displacement FE over-estimates a limit load on
# coarse meshes; the error must shrink under refinement and be within 5 % on the finest mesh (full mode).

# %%
B_SL, H_SL, CU_SL, BETA_SL = 1.0, 2.0, 20e3, np.radians(30.0)
NC_SLOPE = np.pi + 2.0 - 2.0 * BETA_SL  # exact for a smooth strip at the crest of a weightless Tresca slope
X_TOE = H_SL / np.tan(BETA_SL)
SLOPE_MESHES = [0.25] if FAST else [0.125, 0.0625]  # element size at the footing and the crest [m]


def slope_capacity(h, rough=False):
    """q_u / c_u of the rigid strip [-B, 0] at the crest x = 0 (smooth unless ``rough``), element size h [m]
    there."""
    site = Site(2.0 * (2.0 + X_TOE), 4.0,
                [SoilLayer(1.0, E=20e6, nu=0.3, unit_weight=0.0, c=CU_SL, phi_deg=0.0, psi_deg=0.0)],
                ground=[(-4.0, 0.0), (0.0, 0.0), (X_TOE, -H_SL), (2.0 + X_TOE, -H_SL)],
                strips=[RigidStrip(-B_SL, 0.0, settle=0.03, rough=rough)], mesher="gmsh",
                mesh=MeshSize(h_fine=h, h_coarse=max(0.25, 2 * h), growth=1.1))  # fmt: skip
    n_push = 8 if FAST else 15  # settlement increments to 3 cm = 0.03 B: the pressure has levelled off
    out = site.build().solve(load_factors=np.arange(1, n_push + 1) / n_push, settings=footing_settings())
    assert out.result.status == "completed"
    return float(out.rigid_pressure(0)[1].max() / CU_SL)


nc_fe = {h: slope_capacity(h) for h in SLOPE_MESHES}
for h, nc in nc_fe.items():
    print(f"h = {h:6.4f} m: N_c,FE = q_u/c_u = {nc:.3f}; pi + 2 - 2 beta = {NC_SLOPE:.3f}; "
          f"error {nc / NC_SLOPE - 1:+.2%}")  # fmt: skip
slope_err = nc_fe[SLOPE_MESHES[-1]] / NC_SLOPE - 1.0
if not FAST:  # the rough base on the coarser mesh, for the text's remark (not a check of the row)
    nc_rough = slope_capacity(SLOPE_MESHES[0], rough=True)
    print(f"rough base, h = {SLOPE_MESHES[0]} m: N_c,FE = {nc_rough:.3f} ({nc_rough / NC_SLOPE - 1:+.1%})")
    # holding u too only adds constraints to the same mesh: its limit load cannot be lower
    assert nc_rough >= nc_fe[SLOPE_MESHES[0]], (nc_rough, nc_fe)

# %% [markdown]
# **The limit-analysis bracket** (`Site.limit_analysis`, finite-element limit analysis on triangles of the
# same geometry, refined until the relative gap (UB − LB)/(UB + LB) is 2 %, 5 % in fast mode) bounds the
# smooth strip's capacity from both sides, rigorously for the discretised problem: the exact π + 2 − 2β must
# lie inside it (asserted). The displacement push-over lies above the exact value by its discretisation
# error, so it need not lie below the bracket's upper bound; where it stands is printed.

# %%
la_slope = Site(2.0 * (2.0 + X_TOE), 4.0,
                [SoilLayer(1.0, E=20e6, nu=0.3, unit_weight=0.0, c=CU_SL, phi_deg=0.0, psi_deg=0.0)],
                ground=[(-4.0, 0.0), (0.0, 0.0), (X_TOE, -H_SL), (2.0 + X_TOE, -H_SL)],
                strips=[RigidStrip(-B_SL, 0.0, settle=0.03, rough=False)])  # fmt: skip
la_slope = la_slope.limit_analysis(gap=0.05 if FAST else 0.02)
nc_lb, nc_ub = la_slope.lb / (CU_SL * B_SL), la_slope.ub / (CU_SL * B_SL)  # lambda: the footing's force [N/m]
nc_push = nc_fe[SLOPE_MESHES[-1]]
where = "inside" if nc_lb <= nc_push <= nc_ub else ("above" if nc_push > nc_ub else "below")
print(f"limit analysis: N_c in [{nc_lb:.3f}, {nc_ub:.3f}] (gap {la_slope.gap:.1%}); exact {NC_SLOPE:.3f}; "
      f"push-over {nc_push:.3f} ({where} the bracket)")  # fmt: skip

# %% [markdown]
# ## 7. Solve time per DOF: gmsh mesh against the structured block
#
# The level site of section 1 on both meshes (linear: one factorisation and one solve each), best of three.
# A wall time on a shared machine is a benchmark, not a reproduced number: `make bench`
# (benchmarks/bench_site.py) measures this ratio and the meshing time against their goals; shown here only.


# %%
def solve_per_dof(mesher):
    built = level_site(mesher).build()
    best = min(_timed(built) for _ in range(3))
    return best / built.model.n_dof


def _timed(built):
    t = time.perf_counter()
    built.solve()
    return time.perf_counter() - t


per_dof_ratio = solve_per_dof("gmsh") / solve_per_dof("structured")
print(f"solve time per DOF, gmsh / structured: {per_dof_ratio:.2f}")

# %% [markdown]
# ## 8. Side contact of an embedded strip under a horizontal push
#
# A rigid strip (B = 2 m) sits in a trench D = 1 m deep in a Tresca clay (s_u = 20 kPa, γ = 18 kN/m³,
# E = 10 MPa, ν = 0.3) on a base contact of adhesion c_i = 10 kPa (φ_i = 0, so the base slides at c_i B
# whatever the normal force). Pushed horizontally without side contact it slides at c_i B = 20 kN/m. With
# `Scene.side_contact` its vertical sides touch the backfill through zero-thickness interfaces; here
# smooth (δ = 0) and free to open. The hand value (chosen before running): the front side is a smooth
# vertical wall translating into level Tresca ground, for which Rankine's passive state is exact,
# P_p = ½ γ D² + 2 s_u D = 49 kN/m (the 45° wedge mechanism gives the same upper bound); the back side
# opens (Rankine's active stress γz − 2 s_u is tensile down to 2 s_u/γ = 2.2 m > D, and the soil's vertical
# face stands, its critical height ≈ 3.8 s_u/γ = 4.3 m), P_a = 0. So H = c_i B + P_p = 69 kN/m: the base
# sliding block with the front wedge is a kinematically admissible mechanism, an upper bound of the exact
# capacity. Capacity here: the push resistance at 5 cm (5 % of D), where it has levelled off.
#
# The push is a load of the scene, `Push(u)`: every plate node's horizontal displacement prescribed (the
# rotations held, w free), so the strip translates; the push-over's `foundation_load()` (and `capacity()`)
# is then the horizontal reaction. (Before `Push` existed this section prescribed u on the model by hand;
# the push resistance is bit for bit the same: 85957.19560779599 N/m at h = 0.25 m both ways, and the
# base alone 20000.0 N/m.)
#
# The passive wedge is only 1 m deep, so the mesh is refined through it: the backfill is split into n
# equal sublayers (mesh lines) as h_fine halves, n = 1/h · 1 m. A displacement-based mesh overstates a
# capacity, most at the wall's toe (the corner where the wedge leaves the base), so the row takes the
# Richardson extrapolation of three meshes, with the observed order, against the hand value within the
# issue's 5 % (full mode; fast mode runs the coarsest mesh only and asserts the ordering).

# %%
S_U, GAMMA_B, C_I, B_S, D_S = 20e3, 18e3, 10e3, 2.0, 1.0
SMOOTH_SIDE = Contact(kn=1e10, kt=0.0, phi_deg=0.0, c=0.0)


def side_push(h, side, push=0.05, n_steps=20):
    """(displacement [m], push resistance [N/m]) of the embedded rigid strip pushed to ``push`` [m] in
    ``n_steps`` equal steps by a `Push` load: every plate node's u prescribed (rotations held, w free), the
    horizontal reaction summed (the push-over's `foundation_load()`)."""
    n_sub = round(D_S / h)  # sublayers of the backfill: mesh lines through the passive wedge

    def clay(t):
        return SoilLayer(t, E=10e6, nu=0.3, unit_weight=GAMMA_B, c=S_U, phi_deg=0.0, psi_deg=0.0)

    scene = Scene(width=16.0, depth=8.0, layers=[clay(D_S / n_sub) for _ in range(n_sub)] + [clay(7.0)],
                  foundation=Foundation(-B_S / 2, B_S / 2, SECTION),
                  contact=Contact(kn=1e10, kt=1e9, phi_deg=0.0, c=C_I), embedment=D_S,
                  mesh=MeshSize(h_fine=h, h_coarse=2.0), side_contact=side, loads=[Push(push)])  # fmt: skip
    out = scene.build().solve(n_steps=n_steps)
    return out.load_settlement()["settlement"], out.foundation_load()


curve_base = side_push(0.25, None)
h_base_only = float(curve_base[1][-1])
H_HAND = C_I * B_S + 0.5 * GAMMA_B * D_S**2 + 2 * S_U * D_S
SIDE_MESHES = [0.25] if FAST else [0.25, 0.125, 0.0625]
curves_side = {h: side_push(h, SMOOTH_SIDE) for h in SIDE_MESHES}
h_side = {h: float(c[1][-1]) for h, c in curves_side.items()}
for h, v in h_side.items():
    print(f"h={h} m, {round(D_S / h)} sublayers: H = {v / 1e3:.2f} kN/m (hand {H_HAND / 1e3:.1f})")
print(f"base only: {h_base_only / 1e3:.3f} kN/m (c_i B = {C_I * B_S / 1e3:.1f})")
if not FAST:
    f1, f2, f3 = h_side.values()
    side_order = np.log2((f1 - f2) / (f2 - f3))
    h_side_extrap = f3 - (f2 - f3) / (2.0**side_order - 1.0)
    side_err = h_side_extrap / H_HAND - 1.0
    print(f"observed order {side_order:.2f}; extrapolated H = {h_side_extrap / 1e3:.2f} kN/m, "
          f"{100 * side_err:+.1f} % against the hand value")  # fmt: skip

# %% [markdown]
# ## 9. An embedded strip on a site
#
# A site strip whose `Strip.level` lies below the ground is embedded: the site geometry loses the trench
# between its ends down to that level (the level is a mesh line across the site, so the walls end at a
# node), the soil beside it is the backfill, and `Strip.side_contact` puts the same side interfaces on the
# walls as the layered scene's `side_contact`. The initial stress is gravity loading with the trench open
# (the walls are free faces, not K0 ground), so the side interfaces start without traction, where the
# layered scene holds its walls at the K0 stress.
#
# First the elastic check: the strip of section 8 in a two-layer elastic soil (the backfill the top layer),
# linear base and side contact, a column's N = 200 kN/m and H = 20 kN/m. A linear increment does not depend
# on the state it starts from, so the site on the structured path (the same block) must give the layered
# scene's displacements to round-off, and on the gmsh mesh within its discretisation error. Then the push
# of section 8 on a site: the same soil, the base on its Tresca contact, smooth sides, pushed by `Push` on
# the gmsh mesh refined through the wedge (h_fine at the walls and the base).

# %%
EMB_TOP = SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3)
EMB_LOW = SoilLayer(7.0, E=30e6, nu=0.3, unit_weight=19e3)
EMB_SIDE = Contact(kn=1e9, kt=1e8)  # linear: no friction limit, so the comparison is elastic
EMB_LOADS = [ColumnLoad(0.0, N=200e3, H=20e3)]


def embedded_site(mesher, h):
    """(x, w, u) [m] of the plate nodes of the embedded strip of an elastic two-layer site."""
    site = Site(width=16.0, depth=8.0, layers=[EMB_TOP, EMB_LOW], boreholes=[Borehole(0.0, [-1.0])],
                strips=[Strip(Foundation(-B_S / 2, B_S / 2, SECTION), Contact(kn=1e10, kt=1e9), level=-D_S,
                              side_contact=EMB_SIDE)],
                loads=EMB_LOADS, mesh=MeshSize(h_fine=h, h_coarse=2.0), mesher=mesher)  # fmt: skip
    b = site.build()
    out, ids = b.solve(), b.strips[0]["plate_nodes"]
    assert b.initial_stress_method == "gravity" and b.mesher == mesher
    return b.model.coords[ids, 0], out.u[-1][b.model.dof(ids, "w")], out.u[-1][b.model.dof(ids, "u")]


emb_scene = Scene(width=16.0, depth=8.0, layers=[EMB_TOP, EMB_LOW], foundation=Foundation(-B_S / 2, B_S / 2,
                  SECTION), contact=Contact(kn=1e10, kt=1e9), embedment=D_S, side_contact=EMB_SIDE,
                  loads=EMB_LOADS, mesh=MeshSize(h_fine=0.25, h_coarse=2.0)).build()  # fmt: skip
emb_out = emb_scene.solve()
w_scene = emb_out.u[-1][emb_scene.model.dof(emb_scene.plate_nodes, "w")]
u_scene = emb_out.u[-1][emb_scene.model.dof(emb_scene.plate_nodes, "u")]
_, w_str, u_str = embedded_site("structured", 0.25)
emb_equal = max(np.abs(w_str - w_scene).max(), np.abs(u_str - u_scene).max()) / np.abs(w_scene).max()
emb_gmsh = {h: embedded_site("gmsh", h) for h in (0.5, 0.25)}
emb_mean = {h: float(np.mean(v[1])) for h, v in emb_gmsh.items()}
emb_change = abs(emb_mean[0.25] / emb_mean[0.5] - 1.0)
emb_diff = abs(emb_mean[0.25] / np.mean(w_scene) - 1.0)
print(f"embedded strip, structured site vs layered scene: max |du| / max |w| = {emb_equal:.1e}")
print(f"gmsh site: mean settlement {-1e3 * emb_mean[0.25]:.3f} mm vs the scene's "
      f"{-1e3 * np.mean(w_scene):.3f} mm ({100 * emb_diff:.2f} %; the gmsh mean changes "
      f"{100 * emb_change:.2f} % from h = 0.5 to 0.25 m)")  # fmt: skip


def site_side_push(h, side, push=0.05, n_steps=20):
    """Push resistance [N/m] history of section 8's strip on a site (gmsh), pushed to ``push`` [m]."""
    clay = SoilLayer(8.0, E=10e6, nu=0.3, unit_weight=GAMMA_B, c=S_U, phi_deg=0.0, psi_deg=0.0)
    site = Site(width=16.0, depth=8.0, layers=[clay],
                strips=[Strip(Foundation(-B_S / 2, B_S / 2, SECTION),
                              Contact(kn=1e10, kt=1e9, phi_deg=0.0, c=C_I), level=-D_S, side_contact=side)],
                loads=[Push(push)], mesh=MeshSize(h_fine=h, h_coarse=2.0), mesher="gmsh")  # fmt: skip
    out = site.build().solve(load_factors=np.arange(1, n_steps + 1) / n_steps)
    return out.push_force(0)


SITE_SIDE_MESHES = [0.25] if FAST else [0.25, 0.125, 0.0625]
site_base_only = float(site_side_push(0.25, None)[1][-1])
site_side = {h: float(site_side_push(h, SMOOTH_SIDE)[1][-1]) for h in SITE_SIDE_MESHES}
for h, v in site_side.items():
    print(f"site (gmsh), h={h} m: H = {v / 1e3:.2f} kN/m (hand {H_HAND / 1e3:.1f}, the scene at h=0.25: "
          f"{h_side[0.25] / 1e3:.2f})")  # fmt: skip
print(f"site, base only: {site_base_only / 1e3:.3f} kN/m")
if not FAST:
    g1, g2, g3 = site_side.values()
    site_order = np.log2((g1 - g2) / (g2 - g3))
    site_extrap = g3 - (g2 - g3) / (2.0**site_order - 1.0)
    print(f"site: observed order {site_order:.2f}; extrapolated H = {site_extrap / 1e3:.2f} kN/m, "
          f"{100 * (site_extrap / H_HAND - 1.0):+.1f} % against the hand value")  # fmt: skip

# %% [markdown]
# ## Verification

# %%
check("site_horizontal_equal", "max |w_site - w_scene| / max w, structured path", equal_err, 1e-10)
assert built_s.mesher == "structured" and built_s.initial_stress_method == "K0"
# the gmsh result lies within a few times its own change under refinement of the structured one (the two
# meshes err differently; 3x the indicator and at least 1 %: the indicator itself is an estimate)
assert gmsh_diff <= max(3.0 * gmsh_change, 0.01), (gmsh_diff, gmsh_change)
_, e_v, e_k = grav["structured"]
check("site_gravity_k0", "max rel. error of sigma_v from gravity loading (level ground)", e_v, 1e-6)
assert e_k <= 1e-6, e_k
assert grav["gmsh"][0] == "gravity"
check("site_gibson", "max |w/w_Gibson - 1| under the load (relative to the far ground)", gibson_under, 0.03)
# the sampling alone (the confined column): Gauss points second order, centroids several times worse
assert abs(column["gauss"][1]) * 3.0 <= abs(column["gauss"][0]), column
assert all(abs(g) * 5.0 < abs(c) for g, c in zip(column["gauss"], column["centroid"])), column
assert gibson_outside <= 0.03, gibson_outside
assert same_mesh
check("site_two_footings", "max |u_AB - u_A - u_B| / max |u_AB| on one mesh (elastic)", superposition, 1e-10)
assert sa["mean"] > sb["mean"] > 0.0  # the heavier strip over the softer left side settles more
# plastic interaction: positive, falling monotonically with the distance
assert all(i > 0.0 for i in interaction) and all(a > b for a, b in zip(interaction, interaction[1:])), (
    interaction
)
assert all(d > 0.0 for d in diffs)  # the right (soft) end settles more: the beam tilts towards the soft side
assert dip_change <= 0.01, dip_change  # converged: the finest two meshes agree within 1 %
assert diff_spread < diffs[-1] < diff_1d  # the FE lies between the spread and the unspread column estimates
print(f"the short beam (L/H = 1.25, a study): FE / 1-D differential {dip_ratio:.3f}")
assert all(d > 0.0 for d in diff_long)  # the long beam tilts towards the soft side too
assert long_change <= 0.01, long_change  # converged: the finest two meshes agree within 1 %
check("site_dipping_layer", "FE / 1-D column differential settlement - 1, beam L/H = 5 (section 5)",
      long_ratio - 1.0, 0.2)  # fmt: skip
# the FE limit load lies above the exact one and falls under refinement (displacement FE over-estimates);
# 5 % (the issue's) on the finest mesh: a claim of full mode only (fast mode's coarse mesh is not reported)
assert all(nc > NC_SLOPE for nc in nc_fe.values()), nc_fe
assert all(a > b for a, b in zip(nc_fe.values(), list(nc_fe.values())[1:])), nc_fe
assert nc_lb <= NC_SLOPE <= nc_ub, (nc_lb, NC_SLOPE, nc_ub)  # the exact value inside the certified bracket
if not FAST:
    metric = f"N_c,FE/(pi+2-2beta) - 1, smooth strip at a 30 deg crest, h={SLOPE_MESHES[-1]} m"
    check("site_slope_capacity", metric, slope_err, 0.05)
assert abs(h_base_only / (C_I * B_S) - 1.0) <= 1e-6, h_base_only  # the base alone: its Tresca law, c_i B
# side contact adds the passive resistance; every mesh overstates it, falling under refinement
assert all(v > H_HAND for v in h_side.values()), h_side
assert all(a > b for a, b in zip(h_side.values(), list(h_side.values())[1:])), h_side
if not FAST:
    metric = "H_FE (Richardson, 3 meshes) / (c_i B + Rankine P_p) - 1, smooth sides, embedded rigid strip"
    check("site_side_contact", metric, side_err, 0.05)
# the embedded site: the structured path is the scene's block (round-off); the gmsh mesh within 3x its own
# change under halving h and at least 1 % (as for the level site above)
assert emb_equal <= 1e-10, emb_equal
assert emb_diff <= max(3.0 * emb_change, 0.01), (emb_diff, emb_change)
# the site's push: the base alone slides at c_i B; side contact adds the passive resistance, overstated by
# every mesh (a displacement-based capacity) and falling under refinement
assert abs(site_base_only / (C_I * B_S) - 1.0) <= 1e-6, site_base_only
assert all(v > H_HAND for v in site_side.values()), site_side
assert all(a > b for a, b in zip(site_side.values(), list(site_side.values())[1:])), site_side
if not FAST:  # extrapolated from three gmsh meshes: the hand value within the 5 % (as the row's)
    assert abs(site_extrap / H_HAND - 1.0) <= 0.05, site_extrap
# wall times on a shared machine are benchmarks, not reproduced numbers: the keys site_mesh_s (goal 2 s)
# and site_solve_per_dof_vs_structured (goal 1.3) are measured by benchmarks/bench_site.py; shown here only
print(f"this run: gmsh mesh + build {mesh_s:.2f} s; solve time per DOF, gmsh / structured "
      f"{per_dof_ratio:.2f} (make bench measures both against their goals)")  # fmt: skip

# %% [markdown]
# ## Figure

# %%
fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(18, 4.5))
xy, conn = both.mesh.xy, both.mesh.conn
colors = plt.cm.YlOrBr(np.linspace(0.2, 0.8, len(FOUR)))
for e, c in enumerate(conn):
    poly = xy[c[[0, 4, 1, 5, 2, 6, 3, 7]]]
    ax0.fill(poly[:, 0], poly[:, 1], color=colors[both.element_layer[e]], ec="0.4", lw=0.2)
for s in both.site.strips:
    ax0.plot([s.foundation.x0, s.foundation.x1], [0.25, 0.25], "k", lw=5)
for bh in BOREHOLES:
    ax0.plot([bh.x, bh.x], [0.0, -12.0], "b--", lw=0.8)
    ax0.plot([bh.x] * len(bh.boundaries), bh.boundaries, "bo", ms=3)
ax0.set(xlabel="x [m]", ylabel="z [m]", title="Fig. 19.1a — four layers from three boreholes, two strips")
ax0.set_aspect("equal")
ax1.plot(x_g, 1e3 * (w_g - w_g[0]), "o-", ms=3, label="FE, relative to the far ground")
ax1.plot([-b_g, -b_g, b_g, b_g], [0, 1e3 * w_exact, 1e3 * w_exact, 0], "k--", label="Gibson (1967): q/2m")
ax1.set(
    xlim=(-6, 6), xlabel="x [m]", ylabel="settlement [mm]", title="Fig. 19.1b — strip load on Gibson soil"
)
ax1.invert_yaxis()
ax1.legend()
ax2.plot(gaps, 100 * np.array(interaction), "o-")
ax2.set(xlabel="clear distance between the strips [m]", ylabel="extra settlement of strip A [%]",
        title="Fig. 19.1c — plastic interaction of two strips")  # fmt: skip
save_figure(fig, "19_sites")

fig, ax = plt.subplots(figsize=(6.5, 4.5))
ax.plot(1e3 * curve_base[0], curve_base[1] / 1e3, "k-", label="base only (no side contact)")
for h, (u_c, f_c) in curves_side.items():
    ax.plot(1e3 * u_c, f_c / 1e3, "o-", ms=3, label=f"smooth side contact, h = {h} m")
ax.axhline(H_HAND / 1e3, color="r", ls="--", label="c_i B + Rankine passive P_p (hand)")
ax.axhline(C_I * B_S / 1e3, color="0.5", ls=":", label="c_i B")
if not FAST:
    ax.axhline(h_side_extrap / 1e3, color="b", ls="-.", lw=0.8, label="Richardson, 3 meshes")
ax.set(xlabel="horizontal displacement of the strip [mm]", ylabel="push resistance H [kN/m]",
       title="Fig. 19.2 — embedded rigid strip pushed sideways")  # fmt: skip
ax.legend(fontsize=8)
save_figure(fig, "19_sites_side_contact")

# %% [markdown]
# *Fig. 19.1* (a) The gmsh Q8 mesh of the two-strip site: it conforms to the interpolated boundaries and
# to the pinch-out of the second layer at x = 0, and is finest at the strips. (b) Settlement of the ground
# under a strip load on Gibson's soil against the exact uniform value. (c) Extra mean settlement of strip A
# caused by an equally loaded strip B on Mohr–Coulomb soil, against their clear distance.
#
# *Fig. 19.2* The embedded rigid strip of section 8 pushed sideways: without side contact it slides at its
# base's c_i B; with smooth side contact the backfill's passive resistance adds to it. Each mesh levels off
# above the hand value c_i B + P_p and the level falls under refinement through the passive wedge; the
# extrapolation of the three meshes (full mode) lands on the hand value.
#
# ## Summary
#
# A site is described once (boreholes or polylines, a ground polyline, strips); the description is cut into
# cells that a quadrilateral mesher (gmsh) and a triangle mesher can both mesh. Where the ground and the
# boundaries are level, the structured block and the K0 state serve and give the layered scene's numbers;
# elsewhere the gmsh mesh and gravity loading do. Gibson's exact settlement and elastic superposition of two
# strips check the new pieces. Stiffness growing with depth is sampled at the Gauss points: on a confined
# column with E linear in depth (exact 1-D settlement) its error falls as h², several times below that of
# the per-element (centroid) sampling; on Gibson's soil both are within the row's 3 % on the chapter's
# mesh (the Gibson case's own error, ν = 0.499 in a closed block, is of the same size as the sampling's
# there, so the centroid version, by a cancellation, is the closer one on the finer meshes: 0.68 % against
# 1.45 % at h = 0.25 m, 0.23 % against 0.97 % at 0.125 m; at 0.5 m the Gauss version is, 2.6 % against 4.6 %).
#
# A beam over the dipping boundary tilts towards the soft side, converged under refinement. On a geometry
# where a 1-D column is the right reference (a stiff beam five times as long as the soil is deep) its
# differential settlement is within the 20 % of the 1-D estimate (about 0.91 of it); the short
# beam of the first study (L/H = 1.25) is about 0.72 of it, between the 1-D estimate and the version with
# Flamant's stress spreading: there the 1-D model, not the FE, is wrong.
#
# With side contact an embedded strip pushed sideways carries the backfill's passive resistance on top of
# its base's sliding resistance; extrapolated from three meshes refined through the passive wedge, the
# push resistance is within about 1 % of the base's c_i B plus Rankine's passive force (full mode).
#
# The smooth strip at the crest of the 30° slope reaches the exact slip-line capacity π + 2 − 2β within the
# issue's 5 % on the finest mesh of full mode, from above and falling under refinement; no table value of the
# published slope charts (Georgiadis 2010; Shiau et al. 2011) could be obtained, so none is quoted. The
# limit-analysis bracket of the same site (2 % gap, full mode: [4.047, 4.205] while this was written)
# contains the exact value; the push-over on the finest mesh (4.207) lies just above its upper bound, by
# its own discretisation error (+2.8 % over the exact value): not inside the bracket, as the issue asks.
#
# An embedded strip on a site (section 9) meshes a trench into the site geometry: on the structured path it
# reproduces the layered scene's embedded strip with side contact to round-off (1.3e-14, elastic), on the
# gmsh mesh within its discretisation error (0.25 % against a 0.43 % change under halving h). Pushed by
# `Push` with smooth sides its resistance on the gmsh meshes falls towards the hand value from above (83.1,
# 76.7, 73.2 kN/m at h = 0.25, 0.125, 0.0625 m while this was written; extrapolated with the observed order
# about 69.1 against 69.0), although its trench walls start free (gravity loading) where the layered scene
# holds them at K0: the limit does not depend on the initial stress.
#
# **Not yet here** (issue 32): slope capacity against a published *table* value (and a push-over inside the
# limit-analysis bracket), the result file, result plots and ParaView export of sites (`ssi run` on a site
# file prints and writes only the per-foundation summary; the site plots do not draw the trench), side
# contact in scene files' examples and in the limit analysis (a `Push` is refused there), several embedded
# strips on the structured path (the gmsh mesh serves them), a flooded trench.
#
# ## References
#
# - R. E. Gibson (1967), Some results concerning displacements and stresses in a non-homogeneous elastic
#   half-space, *Géotechnique* 17(1), 58–67.
# - C. Geuzaine, J.-F. Remacle (2009), Gmsh: a 3-D finite element mesh generator with built-in pre- and
#   post-processing facilities, *Int. J. Numer. Meth. Eng.* 79(11), 1309–1331.
# - L. Prandtl (1920), Über die Härte plastischer Körper, *Nachr. Ges. Wiss. Göttingen*, 74–85.
# - A. S. Vesić (1975), Bearing capacity of shallow foundations, in *Foundation Engineering Handbook*
#   (Winterkorn & Fang, eds.), ch. 3.
# - K. Georgiadis (2010), Undrained bearing capacity of strip footings on slopes, *J. Geotech. Geoenviron.
#   Eng.* 136(5), 677–685 (its tables were not consulted; see section 6).
# - J. S. Shiau, R. S. Merifield, A. V. Lyamin, S. W. Sloan (2011), Undrained stability of footings on
#   slopes, *Int. J. Geomech.* 11(5), 381–390 (its tables were not consulted; see section 6).
# - H. G. Poulos, E. H. Davis (1974), *Elastic Solutions for Soil and Rock Mechanics*, Wiley.
# - W. Szajna, *A set of finite elements for 2D analysis of reinforced concrete foundations on deformable
#   subsoil* (§1, §2 Fig. 1, §11: arbitrary layered subsoil).
