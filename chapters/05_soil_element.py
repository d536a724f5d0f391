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
# # 05 — The soil element: 8-node serendipity quad in plane strain (paper §7, §10)
#
# The subsoil of every scene is meshed with 8-node serendipity quadrilaterals in plane strain, integrated
# with the reduced 2×2 Gauss rule (paper §7 and §10, after Zienkiewicz & Taylor). This chapter checks the
# linear element on its own before any plasticity or contact enters.
#
# **In this chapter you will**
# - see the shape functions, the strain–displacement matrix and the plane-strain elastic matrix that make the
#   element stiffness, and how the two integration rules (2×2 reduced, 3×3 full) differ;
# - count zero-energy modes: the one spurious (hourglass) mode a single 2×2 element has, and why it vanishes
#   in a mesh;
# - pass the patch test on a distorted mesh to round-off;
# - converge to the closed-form stresses under an elastic strip load, with a fitted rate;
# - watch full integration lock as ν → 0.5 while the reduced rule does not;
# - measure what each rule costs: error against DOFs and wall time.

# %% [markdown]
# ## Theory
#
# **Geometry and displacement.** On the reference square (ξ, η) ∈ [−1, 1]² the eight serendipity functions
# are, for the corners (ξₐ, ηₐ = ±1) and the mid-sides,
#
# $$N_a = \tfrac14(1+\xi_a\xi)(1+\eta_a\eta)(\xi_a\xi+\eta_a\eta-1),\qquad
#   N_a = \tfrac12(1-\xi^2)(1+\eta_a\eta)\ \ (\xi_a = 0),\qquad
#   N_a = \tfrac12(1+\xi_a\xi)(1-\eta^2)\ \ (\eta_a=0).$$
#
# They interpolate both the coordinates and the displacements (isoparametric): x = Σ Nₐ xₐ, u = Σ Nₐ uₐ. They
# reproduce every complete quadratic in ξ, η plus ξ²η and ξη² — so a linear displacement field in x, z is
# represented exactly on any straight-sided mesh, which is what the patch test asks.
#
# **Strain and stress.** With z upwards and engineering shear, ε = [εxx, εzz, γxz] = B uₑ where node a
# contributes the columns
# $$B_a = \begin{bmatrix} \partial_x N_a & 0\\ 0 & \partial_z N_a\\
#   \partial_z N_a & \partial_x N_a\end{bmatrix},$$
# the physical derivatives coming from the Jacobian J = ∂(x, z)/∂(ξ, η). In plane strain εyy = 0 and the
# out-of-plane stress σyy = ν(σxx + σzz) is kept in the state (the plastic laws need it). The elastic matrix
# in the code's order [xx, zz, xz, yy] is λ on the normal–normal entries, λ + 2μ on their diagonal and μ for
# shear, λ = Eν/((1+ν)(1−2ν)), μ = E/(2(1+ν)).
#
# **Stiffness** — the first term of the virtual-work equation (3.1) restricted to one element:
# $$K_e = \int_{\Omega_e} B^T D B\, d\Omega \approx \sum_{q} w_q\, \det J(\xi_q,\eta_q)\, B_q^T D B_q .$$
#
# **Two rules.** 3×3 Gauss integrates Kₑ of an undistorted element exactly. 2×2 (the paper's choice) samples
# strain at 4 points only, which is one constraint too few: a single element gets one *spurious* zero-energy
# mode besides the 3 rigid-body modes. That mode is not compatible between neighbours, so a mesh of two or
# more elements has only the 3 rigid modes. The reward is that 2×2 samples the volumetric strain at few enough
# points that a nearly incompressible material (ν → 0.5, undrained soil) does not lock; 3×3 enforces
# div u ≈ 0 at 9 points per element and the mesh stiffens spuriously (volumetric locking). The 2×2 points are
# also the optimal (Barlow) stress-sampling points of the quadratic element.
#
# | paper | code | meaning |
# |---|---|---|
# | N, ∂N/∂ξ | `ssi.core.shapes.serendipity8` | shape functions and reference derivatives |
# | B | built inside `ssi.elements.soil_q8.q8_kernel` | strain–displacement matrix |
# | D | `ssi.materials.soil_laws.elastic_matrix` | plane-strain elastic matrix, order [xx, zz, xz, yy] |
# | σx, σz, τxz, σy | `state[..., 0:4]` = `sxx, szz, txz, syy` | stress at the integration points, tension + |
# | E, ν | `params = elastic_params(E, nu)` | validated elastic parameters |
# | 2×2 / 3×3 | `SoilQ8(..., n_gauss=2 / 3)` | reduced / full Gauss integration |

# %%
import inspect
import itertools
import math
import time

import matplotlib.pyplot as plt
import numpy as np

from ssi.core.mesh import structured_q8
from ssi.core.model import Model
from ssi.core.shapes import Q8_NODES, serendipity8
from ssi.elements.soil_q8 import SoilQ8
from ssi.elements.supports import edge_forces
from ssi.lab import paths, report
from ssi.lab.analytical_soil import lame_cylinder_displacement, strip_load_stresses
from ssi.lab.verify import (
    convergence_rate,
    dense_stiffness,
    distorted_q8_mesh,
    fd_jacobian,
    zero_energy_modes,
)
from ssi.materials.mc_surface import B_APEX, B_EDGE12, B_EDGE23, B_PLANE, mc_yield
from ssi.materials.soil_laws import ELASTIC, drive, elastic_matrix, elastic_params, mohr_coulomb_params

FAST = paths.FAST
# Every system in this chapter is small (< 1e5 DOFs): SciPy's SuperLU factorises them in milliseconds, while
# a new PARDISO solver object costs ~0.5 s of start-up (pypardiso searches the file system for MKL) -- so the
# chapter asks for SuperLU explicitly.
BACKEND = "superlu"
print("fast mode" if FAST else "full mode")
print(inspect.getsource(getattr(serendipity8, "py_func", serendipity8)))

# %% [markdown]
# ## 1. Zero-energy modes
#
# The eigenvalues of an unsupported stiffness matrix that are zero (to round-off) count its zero-energy
# modes. We count them for one element under both rules and for an unsupported 3×3-element mesh under 2×2.

# %%
E, NU = 30e6, 0.3


def q8_model(xy, conn, n_gauss, nu=NU):
    """A model with the nodes ``xy`` and one Q8 group on ``conn``; returns (model, group)."""
    model = Model()
    model.add_nodes(xy, 2)
    group = model.add_group(
        SoilQ8(xy[conn], model.element_dofs(conn), 0, [ELASTIC], [elastic_params(E, nu)], n_gauss=n_gauss)
    )
    return model, group


def q8_stiffness(xy, conn, n_gauss):
    """The dense unsupported K0 of one Q8 group on ``conn`` (:func:`ssi.lab.verify.dense_stiffness`)."""
    model, group = q8_model(xy, conn, n_gauss)
    return dense_stiffness(model.n_dof, [group])


one_xy = Q8_NODES * [1.0, 0.75]
one_conn = np.arange(8)[None]
zero_single = {}
for ng in (2, 3):
    zero_single[ng] = zero_energy_modes(q8_stiffness(one_xy, one_conn, ng))
    print(f"one element, {ng}x{ng}: {zero_single[ng]} zero-energy modes")

mesh3, xy3 = distorted_q8_mesh(3)
zero_mesh = zero_energy_modes(q8_stiffness(xy3, mesh3.conn, 2))
print(f"unsupported distorted 3x3 mesh, 2x2: {zero_mesh} zero-energy modes")

# the spurious mode of one element: the zero-energy space minus the rigid-body modes
K_one = q8_stiffness(one_xy, one_conn, 2)
ev, vec = np.linalg.eigh(K_one)
null = vec[:, ev < 1e-10 * ev.max()]
rigid = np.zeros((16, 3))
rigid[0::2, 0] = 1.0
rigid[1::2, 1] = 1.0
rigid[0::2, 2] = -one_xy[:, 1]
rigid[1::2, 2] = one_xy[:, 0]
q_rigid, _ = np.linalg.qr(rigid)
spurious = null - q_rigid @ (q_rigid.T @ null)
spurious = spurious[:, np.argmax(np.linalg.norm(spurious, axis=0))]
spurious /= np.abs(spurious).max()
energy_spurious = spurious @ K_one @ spurious
print("spurious mode (u, w per node):", np.round(spurious.reshape(8, 2), 3).tolist())


# %% [markdown]
# ## 2. Patch test on a distorted mesh
#
# Every boundary node of the distorted 3×3 mesh gets the displacement of one linear field
# u = a₀ + a₁x + a₂z, w = a₃ + a₄x + a₅z; the interior is solved for. A consistent element must return the
# same linear field at every interior node and the constant stress D ε everywhere — exactly, up to round-off.

# %%
a_lin = np.array([1e-3, 2e-3, -1.5e-3, 0.5e-3, 3e-3, -1e-3])


def linear_field(p):
    return np.column_stack(
        [
            a_lin[0] + a_lin[1] * p[:, 0] + a_lin[2] * p[:, 1],
            a_lin[3] + a_lin[4] * p[:, 0] + a_lin[5] * p[:, 1],
        ]
    )


lam_, mu_ = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
exx, ezz, gxz = a_lin[1], a_lin[5], a_lin[2] + a_lin[4]
sig_exact = np.array(
    [lam_ * (exx + ezz) + 2 * mu_ * exx, lam_ * (exx + ezz) + 2 * mu_ * ezz, mu_ * gxz, lam_ * (exx + ezz)]
)
patch = {}
for ng in (2, 3):
    model, group = q8_model(xy3, mesh3.conn, ng)
    boundary = np.unique(np.concatenate([mesh3.left, mesh3.right, mesh3.bottom, mesh3.surface]))
    ub = linear_field(xy3[boundary])
    for k, node in enumerate(boundary):
        model.fix([node], "u", ub[k, 0])
        model.fix([node], "w", ub[k, 1])
    res = model.solve_linear(backend=BACKEND)
    ids = np.arange(model.n_nodes)
    u = np.column_stack([res.displacement(ids, "u")[-1], res.displacement(ids, "w")[-1]])
    node_err = np.abs(u - linear_field(xy3)).max() / np.abs(linear_field(xy3)).max()
    stress_err = np.abs(group.stress(res.final_state[0]) - sig_exact).max() / np.abs(sig_exact).max()
    patch[ng] = (node_err, stress_err)
    print(
        f"{ng}x{ng}: max nodal error / max |u| = {node_err:.2e}, "
        f"max stress error / max |sig| = {stress_err:.2e}"
    )

# %% [markdown]
# ## 3. Elastic strip load against the closed form
#
# A uniform pressure q on −b ≤ x ≤ b of an elastic half-plane has closed-form stresses
# (`ssi.lab.analytical_soil.strip_load_stresses`; checked in the tests against Flamant's line-load solution
# integrated over the strip). To measure the *discretisation* error alone we cut a finite window out of the
# half-plane — the half 0 ≤ x ≤ 4b, −4b ≤ z ≤ 0 (symmetry: u = 0 on x = 0) — and load its cut faces with the
# exact tractions σ·n of the half-plane solution, integrated consistently on each quadratic edge. One vertical
# support removes the last rigid mode; its reaction is the quadrature error of the applied tractions
# (~1e-10 q b). There is then no truncation error from a finite block, and the FE stresses must converge to
# the closed form as the mesh is refined (h = b/n, n = 1, 2, 4, ...).
#
# **Where we compare.** At the integration points with 0.5b ≤ depth ≤ 2.5b and 0 ≤ x ≤ 2b. The edge of the
# load (x = b, z = 0) carries a jump of the surface traction; the stresses there are bounded but discontinuous
# and their gradients grow like 1/r, so pointwise errors next to the edge measure only that singularity and
# converge slowly. The window is ≥ 0.5b from the edge and ≥ 1.5b from the cut faces (where the applied
# traction is only as accurate as its edge integration). The error measure is
# max |σ_FE − σ_exact| / q over the four stress components and all those points.

# %%
Q, B_HALF, WINDOW = 100e3, 1.0, 4.0


def strip_window(n, n_gauss, nu=NU, backend=BACKEND):
    """Solve the half window with exact boundary tractions; return (n_dof, error, wall time, points,
    stress)."""
    t0 = time.perf_counter()
    lines = np.linspace(0.0, WINDOW * B_HALF, int(WINDOW * n) + 1)
    m = structured_q8(lines, lines - WINDOW * B_HALF)
    model, group = q8_model(m.xy, m.conn, n_gauss, nu)
    model.fix(m.left, "u")
    model.fix(m.bottom[:1], "w")

    def load_edges(line, traction):
        edges = np.stack([line[0:-2:2], line[1:-1:2], line[2::2]], axis=1)
        model.add_element_load(model.element_dofs(edges), edge_forces(m.xy[edges], traction))

    surf = m.surface
    load_edges(surf[m.xy[surf, 0] <= B_HALF + 1e-9], lambda x, z: (0.0 * x, -Q + 0.0 * x))

    def right(x, z):
        sxx, _, txz = strip_load_stresses(x, z, Q, B_HALF)
        return sxx, txz  # sigma . (1, 0)

    def bottom(x, z):
        _, szz, txz = strip_load_stresses(x, z, Q, B_HALF)
        return -txz, -szz  # sigma . (0, -1)

    load_edges(m.right, right)
    load_edges(m.bottom, bottom)
    # SuperLU up to ~2e4 DOFs; beyond, the library's default (PARDISO when installed) is the faster one
    res = model.solve_linear(backend=backend if model.n_dof < 20000 else "auto")
    wall = time.perf_counter() - t0
    pts = group.integration_points()
    sig = group.stress(res.final_state[0])
    depth, x = -pts[..., 1], pts[..., 0]
    sel = (depth >= 0.5 * B_HALF) & (depth <= 2.5 * B_HALF) & (x <= 2.0 * B_HALF)
    exact = np.stack(strip_load_stresses(x[sel], pts[..., 1][sel], Q, B_HALF, nu), axis=-1)
    err = np.abs(sig[sel] - exact).max() / Q
    return model.n_dof, err, wall, pts, sig, res


# warm the JIT cache of both rules so the wall times below are run times only
strip_window(1, 2)
strip_window(1, 3)
levels = [1, 2, 4, 8] if FAST else [1, 2, 4, 8, 16, 32]
conv = {2: [], 3: []}
for ng in (2, 3):
    for n in levels:
        n_dof, err, wall, *_ = strip_window(n, ng)
        conv[ng].append((n, n_dof, err, wall))
for ng in (2, 3):
    print(f"{ng}x{ng} Gauss:")
    print("   n     DOFs   max|dsig|/q   wall [s]")
    for n, n_dof, err, wall in conv[ng]:
        print(f"{n:4d} {n_dof:8d}   {err:10.3e}   {wall:8.3f}")

# fitted rate of the error against h = b/n over the meshes from n = 2 on (n = 1 is pre-asymptotic)
rates = {}
for ng in (2, 3):
    arr = np.array(conv[ng])
    fit = arr[arr[:, 0] >= 2]
    rates[ng] = convergence_rate(1.0 / fit[:, 0], fit[:, 2])
    print(f"{ng}x{ng}: fitted rate of the stress error in h: {rates[ng]:.2f}")
finest_err = conv[2][-1][2]

# %% [markdown]
# ## 4. Nearly incompressible material: locking
#
# Undrained clay behaves with ν → 0.5. The standard probe is Lamé's thick cylinder in plane strain (inner
# radius a = 1, outer b = 2, internal pressure p), whose radial displacement
# u_r = (1+ν) p a² / (E (b² − a²)) · [(1−2ν) r + b²/r] stays finite as ν → 0.5. A quarter of the ring is
# meshed (symmetry supports on both straight edges), with curved element edges from the polar map, on a coarse
# 2 × 4 mesh and a finer 4 × 8 one. The strip-load window of §3 is run too, at ν = 0.4999.

# %%
A_IN, B_OUT, P_IN = 1.0, 2.0, 1e6
NUS = [0.3, 0.45, 0.49, 0.499, 0.4999]


def thick_cylinder(nr, nt, nu, n_gauss):
    """u_r(a) of the FE quarter ring divided by Lamé's exact value."""
    m = structured_q8(np.linspace(A_IN, B_OUT, nr + 1), np.linspace(0.0, 0.5 * np.pi, nt + 1))
    r, t = m.xy[:, 0], m.xy[:, 1]
    xy = np.column_stack([r * np.cos(t), r * np.sin(t)])
    model, _ = q8_model(xy, m.conn, n_gauss, nu)
    model.fix(m.grid[:, 0][m.grid[:, 0] >= 0], "w")  # theta = 0 edge: on the x axis, w = 0
    model.fix(m.grid[:, -1][m.grid[:, -1] >= 0], "u")  # theta = 90 deg edge: on the z axis, u = 0
    inner = m.grid[0, :]
    edges = np.stack([inner[0:-2:2], inner[1:-1:2], inner[2::2]], axis=1)
    f = edge_forces(xy[edges], lambda x, z: (P_IN * x / np.hypot(x, z), P_IN * z / np.hypot(x, z)))
    model.add_element_load(model.element_dofs(edges), f)
    res = model.solve_linear(backend=BACKEND)
    return res.displacement(inner[0], "u")[-1, 0] / float(
        lame_cylinder_displacement(A_IN, A_IN, B_OUT, P_IN, E, nu)
    )


locking = {
    (ng, mesh): [thick_cylinder(*mesh, nu, ng) for nu in NUS] for ng in (2, 3) for mesh in ((2, 4), (4, 8))
}
print("u_r(a) FE / exact")
print("nu        " + "".join(f"{ng}x{ng} {mr}x{mt}   " for (ng, (mr, mt)) in locking))
for i, nu in enumerate(NUS):
    print(f"{nu:<8}  " + "".join(f"{v[i]:10.4f}   " for v in locking.values()))


def pressure_deviator_errors(pts, sig, nu):
    """Max errors / q of the mean stress (sxx + szz + syy)/3 and of the deviatoric part, in the window."""
    depth, x = -pts[..., 1], pts[..., 0]
    sel = (depth >= 0.5 * B_HALF) & (depth <= 2.5 * B_HALF) & (x <= 2.0 * B_HALF)
    d = (sig[sel] - np.stack(strip_load_stresses(x[sel], pts[..., 1][sel], Q, B_HALF, nu), axis=-1)) / Q
    p = d[:, [0, 1, 3]].mean(axis=1)
    dev = d.copy()
    dev[:, [0, 1, 3]] -= p[:, None]
    return np.abs(p).max(), np.abs(dev).max()


strip_nu = {}
for ng in (2, 3):
    for nu in (0.3, 0.4999):
        _, _, _, pts_nu, sig_nu, _ = strip_window(4, ng, nu=nu)
        strip_nu[ng, nu] = pressure_deviator_errors(pts_nu, sig_nu, nu)
print("strip window n = 4: max error / q of the mean stress | of the deviator")
for (ng, nu), (ep, ed) in strip_nu.items():
    print(f"  {ng}x{ng}, nu = {nu:<6}: {ep:.2e} | {ed:.2e}")

# %% [markdown]
# ## 5. Mohr–Coulomb at a material point
#
# The plastic soil law (paper §7; the surface in `ssi.materials.mc_surface`, the schemes in
# `ssi.materials.mc_implicit_scheme` and `mc_explicit_scheme`, unit-tested with their own FD checks in
# `tests/test_mohr_coulomb.py`) is driven here alone, one integration point along prescribed
# plane-strain strain paths, with the library's driver `ssi.materials.soil_laws.drive` — before it enters a
# mesh (chapter 10). With principal stresses s1 ≥ s2 ≥ s3 (tension positive) the yield function and the
# plastic potential are
#
# $$f = k\,s_1 - s_3 - 2c\sqrt{k},\quad k = \frac{1+\sin\varphi}{1-\sin\varphi};\qquad
#   g = m\,s_1 - s_3,\quad m = \frac{1+\sin\psi}{1-\sin\psi}.$$
#
# The plastic strain increment is parallel to ∂g/∂σ: in principal axes (m, 0, −1)·Δλ on the main plane, so
# the plastic dilatancy ratio Δε_v^p / Δγ_max^p = (m − 1)/(m + 1) = sin ψ. Where two principal stresses are
# equal the return goes to an *edge*, and under enough volumetric extension to the *apex*
# s1 = s2 = s3 = c cot φ. Four paths from an isotropic 100 kPa compression (E = 20 MPa, ν = 0.3, c = 10 kPa,
# φ = 30°) reach the four branches: in-plane shear (plane), vertical extension (edge s2 = s3), equal biaxial
# extension (edge s1 = s2, then apex). Each is run for ψ = 0, 10° and 30° (= φ, associated).

# %%
MC_E, MC_NU, MC_C, MC_PHI = 20e6, 0.3, 10e3, 30.0
SIG0 = np.array([-100e3, -100e3, 0.0, -100e3])
PATHS = {
    "in-plane shear": [1.0, -1.0, 0.0, 0.0],
    "vertical extension": [0.0, 1.0, 0.0, 0.0],
    "biaxial extension": [1.0, 1.0, 0.0, 0.0],
}
BRANCH_NAMES = {B_PLANE: "plane", B_EDGE12: "edge s1=s2", B_EDGE23: "edge s2=s3", B_APEX: "apex"}
D_el = np.empty((4, 4))
elastic_matrix(MC_E, MC_NU, D_el)
C_el = np.linalg.inv(D_el)


def fd_tangent(kind, prm, deps, sig_old, h=1e-9):
    """Central differences of the updated stress with respect to the strain increment (4 x 4)."""
    return fd_jacobian(lambda d: drive(kind, prm, [d], sig_old)[0][1], deps, h)


mc_rows = []
mc_paths = {}
for psi in (0.0, 10.0, 30.0):
    kind, prm = mohr_coulomb_params(MC_E, MC_NU, MC_C, MC_PHI, psi)
    for name, direction in PATHS.items():
        deps = 2e-4 * np.array(direction)
        sig, hist, status, D_alg = drive(kind, prm, np.tile(deps, (30, 1)), SIG0)
        mc_paths[psi, name] = sig
        plastic = np.flatnonzero(status > 0)
        f_max = max(abs(mc_yield(sig[i + 1], MC_C, math.radians(MC_PHI))) for i in plastic) / MC_C
        for branch in sorted(set(hist[plastic + 1, 1].astype(int))):
            i = plastic[hist[plastic + 1, 1] == branch][-1]  # the last step returned to this branch
            D_fd = fd_tangent(kind, prm, deps, sig[i])
            fd_err = np.abs(D_alg[i] - D_fd).max() / np.abs(D_el).max()
            asym = np.abs(D_alg[i] - D_alg[i].T).max() / np.abs(D_el).max()
            deps_p = deps - C_el @ (sig[i + 1] - sig[i])  # plastic strain of that step
            gamma_p = math.hypot(deps_p[0] - deps_p[1], deps_p[2])
            ratio = (deps_p[0] + deps_p[1] + deps_p[3]) / gamma_p if gamma_p > 0 else float("nan")
            mc_rows.append(
                {
                    "psi": psi,
                    "path": name,
                    "branch": int(branch),
                    "f_max": f_max,
                    "fd_err": fd_err,
                    "asym": asym,
                    "dilatancy": ratio,
                    "eyy_p": deps_p[3],
                    "sig": sig[i + 1],
                }
            )
print(" psi  path                 branch        max|f|/c   |D - D_FD|   asymmetry   dev_p/gam_p  (sin psi)")
for r in mc_rows:
    print(
        f"{r['psi']:4.0f}  {r['path']:20s} {BRANCH_NAMES[r['branch']]:12s} "
        f"{r['f_max']:9.1e}   {r['fd_err']:9.1e}"
        f"   {r['asym']:9.1e}   "
        + (
            f"{r['dilatancy']:8.4f}    ({math.sin(math.radians(r['psi'])):.4f})"
            if r["branch"] == B_PLANE
            else "   (plane branch only)"
        )
    )
apex = MC_C / math.tan(math.radians(MC_PHI))
apex_rows = [r for r in mc_rows if r["branch"] == B_APEX]
print(
    f"apex c cot(phi) = {apex / 1e3:.3f} kPa; apex stresses reached:",
    [np.round(r["sig"] / 1e3, 3).tolist() for r in apex_rows],
)

# %% [markdown]
# ## Verification
#
# Tolerances and why:
# - `TOL_PATCH = 1e-10`: the patch test is exact in exact arithmetic; 1e-10 is the bound, far above
#   the ~1e-14 round-off of these small solves.
# - rates: a quadratic element's stresses converge like h² at general points; at the 2×2 Gauss (Barlow)
#   points the reduced rule gains about one order. We require ≥ 1.5 for both rules (h² less a margin for the
#   pre-asymptotic coarse meshes) and ≥ 2.5 for the reduced rule's superconvergent sampling.
# - `TOL_STRIP = 1e-3`: the finest-mesh stress error must be below 0.1 % of q, well inside what any soil
#   parameter is known to.
# - locking: reduced integration within 0.1 % of Lamé at every ν on the 4 × 8 mesh (the ν = 0.3 error sets
#   the discretisation level, 3e-5); full integration more than 20 % too stiff at ν = 0.4999 on the coarse
#   mesh. Strip window at ν = 0.4999: the full rule's mean-stress error at least 3× the reduced rule's; the
#   reduced rule's deviatoric stress within 1 % of q (its ν = 0.3 level is 0.15 %), the full rule's not.
# - Mohr–Coulomb point: after every plastic step |f| ≤ 1e-9 c (the return is exact up to round-off);
#   consistent tangent = central differences within 1e-6 of the elastic modulus scale (h = 1e-9 on strains of
#   2e-4: truncation ~1e-10, round-off ~1e-7 relative); asymmetric (> 1e-3) for ψ < φ and symmetric (< 1e-9)
#   for ψ = φ on the main plane; plastic dilatancy ratio = sin ψ to 1e-9 and no out-of-plane plastic strain on
#   the plane; the apex is the hydrostatic stress c cot φ to 1e-9.

# %%
TOL_PATCH = 1e-10
TOL_STRIP = 1e-3
patch_err = max(p[0] for p in patch.values())
assert zero_single[3] == 3, zero_single
assert zero_single[2] == 4, zero_single  # 3 rigid + 1 spurious mode
assert zero_mesh == 3, zero_mesh  # the spurious mode does not survive in a mesh
assert abs(energy_spurious) < 1e-10 * E  # it really costs no energy
assert patch_err < TOL_PATCH, patch
assert max(p[1] for p in patch.values()) < TOL_PATCH, patch
errs2 = [c[2] for c in conv[2]]
assert all(e1 < e0 for e0, e1 in itertools.pairwise(errs2)), errs2  # monotone decrease under refinement
assert rates[2] >= 2.5 and rates[3] >= 1.5, rates
assert conv[2][-1][2] < conv[3][-1][2]  # at equal DOFs the reduced rule is more accurate here
assert finest_err < TOL_STRIP, finest_err
assert all(abs(v - 1.0) < 1e-3 for v in locking[(2, (4, 8))]), locking[(2, (4, 8))]
assert locking[(3, (2, 4))][-1] < 0.8, locking[(3, (2, 4))]  # full integration locks
assert strip_nu[3, 0.4999][0] > 3 * strip_nu[2, 0.4999][0], strip_nu  # full: pressure locked
assert strip_nu[2, 0.4999][1] < 1e-2 < strip_nu[3, 0.4999][1], strip_nu  # deviator: reduced fine, full not
branches_seen = {r["branch"] for r in mc_rows}
assert branches_seen == {B_PLANE, B_EDGE12, B_EDGE23, B_APEX}, branches_seen
for r in mc_rows:
    assert r["f_max"] < 1e-9, r
    assert r["fd_err"] < 1e-6, r
    if r["branch"] == B_PLANE:
        assert abs(r["dilatancy"] - math.sin(math.radians(r["psi"]))) < 1e-9, r
        assert abs(r["eyy_p"]) < 1e-12, r
        assert (r["asym"] < 1e-9) if r["psi"] == MC_PHI else (r["asym"] > 1e-3), r
for r in apex_rows:
    assert np.abs(r["sig"] - apex * np.array([1.0, 1.0, 0.0, 1.0])).max() < 1e-9 * apex, r
report.record(
    "patch_test",
    "max nodal error / max |u|, distorted 3x3 Q8 mesh, 2x2 and 3x3 Gauss",
    patch_err,
    TOL_PATCH,
    patch_err < TOL_PATCH,
)
report.record(
    "strip_load",
    f"max |sig_FE - sig_exact| / q at Gauss points 0.5b<=depth<=2.5b, x<=2b, 2x2 Gauss, "
    f"h = b/{levels[-1]} (fitted rate {rates[2]:.2f})",
    finest_err,
    TOL_STRIP,
    finest_err < TOL_STRIP,
)
print("all checks passed")

# %% [markdown]
# ## Figures


# %%
def draw_q8(ax, xy8, **kw):
    """Draw a Q8 element's four quadratic edges."""
    s = np.linspace(-1, 1, 21)
    for xi, eta in (
        (s, -np.ones_like(s)),
        (np.ones_like(s), s),
        (-s, np.ones_like(s)),
        (-np.ones_like(s), -s),
    ):
        pts = np.array([serendipity8(a, b)[0] @ xy8 for a, b in zip(xi, eta)])
        ax.plot(pts[:, 0], pts[:, 1], **kw)


fig, axes = plt.subplots(1, 2, figsize=(10, 4))
draw_q8(axes[0], one_xy, color="0.6", ls="--")
draw_q8(axes[0], one_xy + 0.25 * spurious.reshape(8, 2), color="C3")
axes[0].plot(*(one_xy + 0.25 * spurious.reshape(8, 2)).T, "o", color="C3")
axes[0].set_aspect("equal")
axes[0].set_title("spurious zero-energy mode, one element, 2×2")
n_show = 12
axes[1].semilogy(
    np.arange(1, n_show + 1),
    np.abs(np.linalg.eigvalsh(q8_stiffness(one_xy, one_conn, 2)))[:n_show] + 1e-3,
    "o-",
    label="one element, 2×2",
)
axes[1].semilogy(
    np.arange(1, n_show + 1),
    np.abs(np.linalg.eigvalsh(q8_stiffness(one_xy, one_conn, 3)))[:n_show] + 1e-3,
    "s-",
    label="one element, 3×3",
)
axes[1].semilogy(
    np.arange(1, n_show + 1),
    np.abs(np.linalg.eigvalsh(q8_stiffness(xy3, mesh3.conn, 2)))[:n_show] + 1e-3,
    "^-",
    label="3×3 mesh, 2×2",
)
axes[1].set_xlabel("eigenvalue index")
axes[1].set_ylabel("|eigenvalue| + 1e-3 [N/m]")
axes[1].legend()
fig.suptitle("Figure 5.1 — zero-energy modes: 4 for one 2×2 element (3 rigid + 1 spurious), 3 otherwise")
report.save_figure(fig, "ch05_zero_energy_modes")

# %%
n_fine = levels[-1]
_, _, _, pts, sig, _ = strip_window(n_fine, 2)
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
on_axis = pts[..., 0] < 0.5 / n_fine
zc = pts[..., 1][on_axis]
order = np.argsort(zc)
zz = np.linspace(-WINDOW * B_HALF, -1e-3, 200)
ex = strip_load_stresses(0.0 * zz, zz, Q, B_HALF)
axes[0].plot(-ex[1] / Q, -zz, "k-", label="σz exact")
axes[0].plot(-ex[0] / Q, -zz, "k--", label="σx exact")
axes[0].plot(-sig[..., 1][on_axis][order] / Q, -zc[order], "C0o", ms=3, label="σz FE (2×2 points)")
axes[0].plot(-sig[..., 0][on_axis][order] / Q, -zc[order], "C1s", ms=3, label="σx FE")
axes[0].invert_yaxis()
axes[0].set_xlabel("compression / q")
axes[0].set_ylabel("depth / b (near the axis x ≈ 0)")
axes[0].legend()
for ng, mk in ((2, "o"), (3, "s")):
    arr = np.array(conv[ng])
    axes[1].loglog(1.0 / arr[:, 0], arr[:, 2], mk + "-", label=f"{ng}×{ng}: rate {rates[ng]:.2f}")
axes[1].set_xlabel("h / b")
axes[1].set_ylabel("max |σ_FE − σ_exact| / q (window)")
axes[1].legend()
fig.suptitle("Figure 5.2 — elastic strip load: stresses under the centre, and the error under refinement")
report.save_figure(fig, "ch05_strip_load")

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
x_nu = 1.0 - 2.0 * np.array(NUS)
for (ng, mesh), vals in locking.items():
    axes[0].semilogx(
        x_nu, vals, ("o-" if ng == 2 else "s--"), label=f"{ng}×{ng}, {mesh[0]}×{mesh[1]} elements"
    )
axes[0].invert_xaxis()
axes[0].set_xlabel("1 − 2ν")
axes[0].set_ylabel("u_r(a) FE / Lamé")
axes[0].legend()
axes[0].set_title("thick cylinder: full integration locks")
for ng, mk in ((2, "o"), (3, "s")):
    arr = np.array(conv[ng])
    axes[1].loglog(arr[:, 3], arr[:, 2], mk + "-", label=f"{ng}×{ng}")
    for _n, n_dof, err, wall in conv[ng]:
        axes[1].annotate(f"{n_dof}", (wall, err), fontsize=7, textcoords="offset points", xytext=(3, 3))
axes[1].set_xlabel("wall time: mesh + assembly + factorisation + solve [s]")
axes[1].set_ylabel("max |σ_FE − σ_exact| / q")
axes[1].legend(title="labels: DOFs")
axes[1].set_title("the trade: error vs DOFs vs wall time")
fig.suptitle("Figure 5.3 — locking as ν → 0.5, and what each integration rule buys per second")
report.save_figure(fig, "ch05_locking_and_trade")

# %%
fig, ax = plt.subplots(figsize=(7, 4.5))
pp = np.linspace(-200e3, apex, 50)
ax.plot(
    -pp / 1e3,
    (MC_C * math.cos(math.radians(MC_PHI)) - pp * math.sin(math.radians(MC_PHI))) / 1e3,
    "k-",
    lw=2,
    label="Mohr–Coulomb: t = c cos φ − s sin φ",
)
for (psi, name), sig in mc_paths.items():
    if psi not in (0.0, 30.0):
        continue
    pr = np.array([sorted([*np.linalg.eigvalsh([[x[0], x[2]], [x[2], x[1]]]), x[3]]) for x in sig])
    s_mid, t_rad = 0.5 * (pr[:, 2] + pr[:, 0]), 0.5 * (pr[:, 2] - pr[:, 0])
    ax.plot(-s_mid / 1e3, t_rad / 1e3, "o-" if psi == 0 else "x--", ms=3, label=f"{name}, ψ = {psi:g}°")
ax.set_xlabel("mean of the extreme principal stresses, compression (−s) [kPa]")
ax.set_ylabel("radius t = (s1 − s3)/2 [kPa]")
ax.legend(fontsize=7)
ax.set_title("Figure 5.4 — Mohr–Coulomb material-point paths end on the yield line (apex at t = 0)")
report.save_figure(fig, "ch05_mohr_coulomb_point")

# %% [markdown]
# ## Summary
#
# - One 2×2 element has exactly one spurious zero-energy mode (the hourglass shape of Fig. 5.1); a mesh of
#   2×2 elements has only the 3 rigid-body modes, so the paper's reduced rule is safe in a mesh.
# - The distorted-mesh patch test is passed to round-off by both rules (row `patch_test`).
# - Under the strip load the stresses converge to the closed form; the reduced rule's Gauss points sample
#   the stress about one order better (rate ≈ 3 against ≈ 2 for 3×3) and at every mesh it is more accurate
#   for the same DOFs, and cheaper (4 points instead of 9) — the trade of Fig. 5.3 favours 2×2 outright.
# - As ν → 0.5 the 3×3 rule locks (the coarse ring is 2× too stiff at ν = 0.4999, and its mean stress is
#   wrong by about q), the 2×2 rule does not: the reason the paper chose it for soil that may flow
#   plastically at constant volume. Honest caveat: 2×2 is not free of trouble there either — its
#   displacements and deviatoric stresses stay accurate, but the mean stress at the Gauss points picks up
#   noise of ~0.2 q at ν = 0.4999 on the n = 4 window (it shrinks slowly with h). Mixed (u–p) elements
#   would cure it; the paper does not use them and neither do we.
# - The Mohr–Coulomb law, driven alone, returns exactly onto the surface on the plane, both edges and the
#   apex, flows along ∂g/∂σ (dilatancy ratio sin ψ), and its consistent tangent matches finite differences in
#   every branch — symmetric only for associated flow, as the paper's choice of modified Newton presumes.
#
# References: O. C. Zienkiewicz, R. L. Taylor, *The Finite Element Method*, vol. 1 (reduced integration,
# patch test); H. G. Poulos, E. H. Davis, *Elastic Solutions for Soil and Rock Mechanics* (strip load);
# J. Barlow, *Optimal stress locations in finite element models*, IJNME 10 (1976).
