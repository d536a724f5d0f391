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
# # 15 — Results a user can read, see and keep: scene files, the command line, result files, ParaView
#
# *Beyond the paper.* The earlier chapters solve scenes from Python. An engineer also wants to describe a
# scene in a file, run it with one command, keep the result, reopen it months later without the script that
# made it, look at it in ParaView, and read off the numbers a design needs: settlement, contact pressure,
# bending moment, steel stress, where the soil yields.
#
# In this chapter you will
# - write a scene as a TOML file whose tables are the `ssi.scene` dataclasses, key for key;
# - run it with `ssi run scene.toml` and check that the command line gives the numbers the Python API gives;
# - write the result to HDF5, read it back, and check that *every* quantity a `SceneResult` answers comes back
#   bit for bit;
# - export every load step to ParaView (VTU + a `.pvd` time series) and read it back with meshio;
# - draw the standard figures, each one call of `ssi.io.plot`, from the file alone.
#
# ## What a result file holds
#
# - attributes: the scene (every layer, load, section layer), the solver settings, `complete`, `stop` — to
#   rebuild the scene and know whether the run finished;
# - `/mesh`: node coordinates, each group's connectivity and DOF table, interface point positions and
#   weights — to plot and integrate without rebuilding;
# - `/steps`: load factor, displacements and committed integration-point states of every step — every
#   quantity at every step;
# - `/solver`: internal forces, iterations, residual histories, cuts, wall time — how the answer was
#   obtained.
#
# Reading a file rebuilds the scene from its description and checks that the rebuilt mesh equals the stored
# coordinates, so a file written by an incompatible version is refused rather than misread. Files are
# written atomically: a temporary file in the same folder, flushed to disk, then renamed over the target, so
# a crash never leaves half a file; an existing file is replaced only when asked.

# %%
import json
import subprocess
import sys
import time

import matplotlib.pyplot as plt
import numpy as np

from ssi.io import plot
from ssi.io.cli import summary
from ssi.io.export import read_series, time_value
from ssi.io.results import max_difference, read_info, read_result, write_result
from ssi.lab import paths
from ssi.lab.report import record, save_figure
from ssi.scene.scene_file import read_scene_file

FAST = paths.FAST
EXAMPLES = paths.ROOT / "examples"
OUT = paths.RESULTS / "ch15"
OUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## A scene file
#
# Chapter 11's RC foundation beam on a coarse mesh. Units are SI and written next to each key;
# `ssi schema` prints every table with its keys and units. A misspelt key (`phi` for `phi_deg`) is refused
# with its name — a scene file never silently ignores what the user wrote.

# %%
scene_path = EXAMPLES / "rc_strip.toml"
print(scene_path.read_text())

# %% [markdown]
# Everything chapter 12 adds to a scene is in the file too, one table per dataclass: a load table names its
# class with `type` (a table without it is a `ColumnLoad`, so the files above need none), phases are
# `[[phases]]` tables with their own `[[phases.loads]]` and `factors` rescaling earlier phases, and
# `embedment`, `water_table`, undrained layers (`drainage = "undrained_A"`) and contact segments
# (`[[contact]]` with `x0`, `x1` and a `contact` table) are keys like any other. Leaving `n_steps` out of
# `[solve]` lets the solver choose its increments (automatic stepping, the default of `Settings`). This
# example is an embedded strip below a water table, loaded in three phases:

# %%
phased_path = EXAMPLES / "phased_embedded.toml"
print(phased_path.read_text())

# %% [markdown]
# ## One command: `ssi run`
#
# Each example file is run through the command line in a fresh process (`python -m ssi.io.cli run`, what the
# installed `ssi` script calls), which writes the result file, the ParaView series, the figures and a
# summary. The same file is then solved in this notebook through the Python API (`read_scene_file`,
# `Scene.build`, `BuiltScene.solve`) and the summaries are compared. They are the same computation, so they
# must agree exactly (tolerance 0): any difference would mean the command line solves something else than
# the file says. The summary's status tells three endings apart: "completed", "limit load reached" (the
# solver detected a collapse; the path up to it is the answer and the load factor the scene carries is
# printed; exit status 0) and "stopped" (the solver failed before either; the file is marked incomplete and
# the command exits with status 3).

# %%
KEYS = (
    "max_settlement",
    "max_contact_pressure",
    "max_abs_moment",
    "contact_resultant",
    "complete",
    "steps",
    "status",
    "phase",
    "phase_load_factor",
    "limit_load_factor",
    "foundation_load",
    "capacity",
)
# the verdict's capacity bracket (limit analysis, chapter 17) costs 5-20 s an example: fast mode skips it
# here, where the files are the subject; full mode prints each example's verdict
VERDICT = ["--no-capacity"] if FAST else []
cli_ok = {}
for example in sorted(EXAMPLES.glob("*.toml")):
    work = OUT / example.name
    work.write_text(example.read_text())
    t0 = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, "-m", "ssi.io.cli", "run", str(work), "--overwrite", *VERDICT],
        capture_output=True,
        text=True,
        check=False,
    )
    wall = time.perf_counter() - t0
    stored = json.loads(work.with_name(work.stem + "_summary.json").read_text())
    scene, n_steps, settings = read_scene_file(example)
    direct = summary(scene.build().solve(n_steps=n_steps, settings=settings))
    # .get: a RigidFooting push-over (pushover_footing.toml) has no contact pressure or moment to compare
    cli_ok[example.name] = proc.returncode == 0 and all(stored.get(k) == direct.get(k) for k in KEYS)
    print(f"--- ssi run {example.name}  (exit {proc.returncode}, {wall:.1f} s with start-up)")
    print(proc.stdout.split("wrote")[0])
    print("matches the Python API:", cli_ok[example.name])

# %% [markdown]
# ## Back from the file: every number
#
# `read_result` gives back a `SceneResult`. `ssi.io.results.max_difference` walks every quantity a
# `SceneResult` answers — displacements, states of every group at every step, settlements, contact stresses,
# zones, weights and resultant, strip forces, layer strains and stresses, steel stress and yield, crack map,
# soil stress, plastic points and strain, the load–settlement path, the status and limit load, and every
# field of the solver's record (internal forces, iterations, residual histories, current stiffness, cuts,
# wall time) — of a phased result for every phase, with its name and step range — and returns the largest
# absolute difference. HDF5 stores float64 bit for bit and the scene description is JSON, whose floats
# round-trip exactly, so the tolerance is 0.
#
# The test case is the phased, embedded strip below the water table. Its geostatic phase takes several
# automatic increments of which the scene result keeps only the first and last state; the file stores those
# intermediate steps with the phase's record (the other rows of a phase are the scene result's own and are
# stored once), so they come back too.

# %%
phased_back = read_result((OUT / "phased_embedded").with_suffix(".h5"))
scene, n_steps, settings = read_scene_file(phased_path)
live = scene.build().solve(n_steps=n_steps, settings=settings)
# two runs of the same file: everything equal but the time each took
roundtrip_live, where = max_difference(live, phased_back, skip=("wall_time",))
print(f"file written by `ssi run` vs a fresh solve: max difference {roundtrip_live:.3g} ({where or 'none'})")

path = write_result(OUT / "phased_embedded_api.h5", live, settings, overwrite=True)
back_api = read_result(path)
roundtrip, where = max_difference(live, back_api)
print(f"write -> read: max difference {roundtrip:.3g} over every SceneResult quantity ({where or 'none'})")
print("phases:", [(r["name"], r["first"], r["last"], r["result"].n_steps) for r in back_api.phases])
print("file info:", {k: v for k, v in read_info(path).items() if k in ("kind", "complete", "ssi_version")})

RESULT_ROUNDTRIP_TOL = 0.0
assert back_api.phases is not None and len(back_api.phases) == 4
assert back_api.built.scene.embedment == 1.0 and back_api.built.scene.water_table == 2.0
assert roundtrip <= RESULT_ROUNDTRIP_TOL
assert roundtrip_live <= RESULT_ROUNDTRIP_TOL  # the solve is deterministic: the CLI's file equals it too
record(
    "result_roundtrip",
    "max |difference| of every SceneResult quantity after write -> read (phased, "
    "embedded scene with a water table)",
    roundtrip,
    RESULT_ROUNDTRIP_TOL,
    roundtrip <= RESULT_ROUNDTRIP_TOL,
)

# the RC strip of the ParaView section below, from the file `ssi run` wrote
stem = OUT / "rc_strip"
back = read_result(stem.with_suffix(".h5"))

# %% [markdown]
# ## ParaView: every step, read back
#
# The soil is exported as quadratic quads (`quad8`, whose node order is ssi's), the strip and the contact as
# quadratic lines (`line3`); point data are the displacement (for *Warp By Vector*) and the plate rotation,
# cell data the element-mean soil stress, the share of yielding points, the plastic strain, the strip forces
# and the contact pressure and shear. Reading the series back with meshio, the numbers must equal the
# result's to the precision of the VTU's binary float64 (tolerance 1e-12 relative to each field's largest
# magnitude; in practice they are equal).

# %%
series = read_series(stem.with_suffix(".pvd"))
built = back.built
soil = np.arange(built.mesh.xy.shape[0])
n_plate = built.plate.n_el
vtk_error = 0.0
# the .pvd's time: the load factor to 12 digits, or the step number where the load factors do not strictly
# increase (ParaView shows one data set per time; the controlled path's first step balances the strip's own
# weight at lambda = 0, a second row there)
lams = np.asarray(back.load_factor)
pvd_times = lams if np.all(np.diff(lams) > 0.0) else np.arange(len(lams), dtype=np.float64)
for k, (lam, mesh) in enumerate(series):
    assert lam == time_value(pvd_times[k])
    u = back.u[k]
    disp = mesh.point_data["displacement"]
    checks = [
        (disp[soil, 0], u[built.model.dof(soil, "u")]),
        (disp[soil, 1], u[built.model.dof(soil, "w")]),
        (mesh.cell_data["szz"][0], back.soil_stress(k)[..., 1].mean(axis=1)),
        (mesh.cell_data["plastic_fraction"][0], back.plastic_points(k).mean(axis=1)),
        (mesh.cell_data["M"][1][:n_plate], back.strip_forces(k)["M"].mean(axis=1)),
        (mesh.cell_data["contact_pressure"][1][n_plate:], -back.contact(k)["sig_n"].mean(axis=1)),
    ]
    for got, want in checks:
        scale = max(np.abs(want).max(), 1e-300)
        vtk_error = max(vtk_error, float(np.abs(got - want).max() / scale))
print(f"{len(series)} steps read back; largest relative difference {vtk_error:.3g}")
VTK_TOL = 1e-12
assert vtk_error <= VTK_TOL
record(
    "vtk_roundtrip",
    "max relative difference of the meshio read-back of the ParaView export",
    vtk_error,
    VTK_TOL,
    vtk_error <= VTK_TOL,
)

# %% [markdown]
# ## The standard figures, from the file alone
#
# Each panel below is one `ssi.io.plot` call on the result read back from disk (`ax=` draws into a given
# axes).

# %%
fig, ax = plt.subplots(3, 2, figsize=(13, 11), layout="constrained")
plot.settlement(back, ax=ax[0, 0])
plot.contact(back, ax=[ax[1, 0], ax[2, 0]])
plot.deformed_mesh(back, ax=ax[0, 1], window=(-8.0, 8.0))
plot.plastic_points(back, ax=ax[1, 1], window=(-8.0, 8.0))
plot.load_settlement(back, ax=ax[2, 1])
fig.suptitle("Fig. 15.1 — the RC strip of examples/rc_strip.toml, redrawn from its result file")
save_figure(fig, "ch15_scene_figures")

fig2, ax2 = plt.subplots(5, 1, figsize=(8, 12), sharex=True, layout="constrained")
plot.strip_forces(back, ax=ax2[:3])
plot.cracks_and_steel(back, ax=ax2[3:])
fig2.suptitle("Fig. 15.2 — bending moment, shear and normal force; cracks and steel stress")
save_figure(fig2, "ch15_strip_figures")

fig3, ax3 = plt.subplots(1, 2, figsize=(12, 4), layout="constrained")
plot.load_settlement(phased_back, ax=ax3[0])
plot.settlement(phased_back, ax=ax3[1])
fig3.suptitle(
    "Fig. 15.3 — examples/phased_embedded.toml from its result file: settlement through the phases "
    "(phase time: phase i runs from i - 1 to i) and the strip's settlement at the end"
)
save_figure(fig3, "ch15_phased_figures")

# %% [markdown]
# ## A site and a capacity bracket, through the same files
#
# A site (chapter 19: layers from boreholes, several strips, a gmsh mesh) goes through the same outputs:
# `ssi run site.toml` prints each foundation's settlement and tilt and writes the result file, the ParaView
# series (with each soil element's layer as `material_id`), the figures -- the site's ground, layer
# boundaries, water table and foundations drawn under each -- and the report. The file gives back a
# `SiteResult`: the site is rebuilt from its stored description and its mesh compared with the stored one,
# so the displacements must equal a direct solve of the same file to round-off.
#
# `ssi limit scene.toml` brackets a capacity (chapter 17) and writes its result file beside the JSON: both
# brackets, the finest mesh, the mechanism's velocity field, each triangle's dissipation and the
# lower-bound stress field, and the mechanism for ParaView as 6-node triangles. Read back, the stored
# fields still satisfy the upper-bound identity: the triangles' dissipation sums to the upper bound (the
# push-over example's soil is weightless, so no dead load does work). Its exact capacity, Prandtl's
# (2 + π) s_u B = 514.2 kN/m, lies in the stored bracket.

# %%
from ssi.io.plot import site_deformed_mesh, site_settlement  # noqa: E402
from ssi.io.results_limit import read_limit_result  # noqa: E402
from ssi.scene.scene_file import read_scene_file  # noqa: E402

site_work = OUT / "boreholes.toml"
site_work.write_text((EXAMPLES / "sites" / "boreholes.toml").read_text())
proc = subprocess.run(
    # --no-plots: drawn below
    [sys.executable, "-m", "ssi.io.cli", "run", str(site_work), "--overwrite", "--no-plots", *VERDICT],
    capture_output=True, text=True, check=False,
)  # fmt: skip
print(proc.stdout.split("wrote")[0])
site_back = read_result(site_work.with_suffix(".h5"))
site, site_steps, site_settings = read_scene_file(site_work)
site_direct = site.build().solve(n_steps=site_steps, settings=site_settings)
site_du = np.abs(np.asarray(site_back.u[-1]) - np.asarray(site_direct.u[-1])).max()
site_ok = proc.returncode == 0 and site_du <= 1e-12 * np.abs(np.asarray(site_direct.u[-1])).max()
print(f"site result file read back: largest displacement difference to a direct solve {site_du:.1e} m")
assert site_ok

limit_work = OUT / "pushover_footing.toml"
limit_work.write_text((EXAMPLES / "pushover_footing.toml").read_text())
proc = subprocess.run(
    [sys.executable, "-m", "ssi.io.cli", "limit", str(limit_work), "--gap", "0.1", "--max-elements", "600",
     "--overwrite", "--no-plots"],
    capture_output=True, text=True, check=False,
)  # fmt: skip
print(proc.stdout.split("wrote")[0])
bracket = read_limit_result(OUT / "pushover_footing_limit.h5")
prandtl = (2.0 + np.pi) * 50e3 * 2.0  # [N/m] s_u = 50 kPa, B = 2 m
identity = abs(bracket.dissipation.sum() - bracket.ub) / bracket.ub
print(
    f"stored bracket [{bracket.lb / 1e3:.1f}, {bracket.ub / 1e3:.1f}] kN/m on {bracket.mesh.n_el} triangles; "
    f"Prandtl {prandtl / 1e3:.1f} kN/m; sum of the stored dissipation against the upper bound: {identity:.1e}"
)
assert proc.returncode == 0 and bracket.lb <= prandtl <= bracket.ub and identity <= 1e-9

fig4, ax4 = plt.subplots(2, 1, figsize=(10, 8), layout="constrained")
site_deformed_mesh(site_back, ax=ax4[0])
site_settlement(site_back, ax=ax4[1])
fig4.suptitle("Fig. 15.4 — examples/sites/boreholes.toml redrawn from its result file")
save_figure(fig4, "ch15_site_figures")
fig5 = plot.limit_mechanism(bracket, window=(0.0, 5.0, -3.0, 0.0))  # the modelled half, x >= 0
fig5.suptitle("Fig. 15.5 — the push-over's collapse mechanism, redrawn from its limit-analysis file")
save_figure(fig5, "ch15_limit_figures")

# %% [markdown]
# ## The command line's verdict

# %%
print(cli_ok)
assert all(cli_ok.values())
record(
    "cli_example",
    "every example scene file runs through `ssi run` and its summary equals the Python API",
    float(all(cli_ok.values())),
    1.0,
    all(cli_ok.values()),
)

# %% [markdown]
# ## Summary
#
# - A TOML scene file maps key for key onto the `Scene` dataclasses — loads of every type, phases, contact
#   segments, water table, embedment, undrained layers; unknown keys and load types are refused by name.
# - `ssi run scene.toml` writes the result, a ParaView series, the figures and a summary; its numbers equal
#   the Python API's for every example (`cli_example`).
# - `read_result` gives back a `SceneResult` whose every quantity equals the original exactly, phases and
#   their solver records included (`result_roundtrip`, tolerance 0), so figures can be redrawn without the
#   script.
# - The ParaView export reads back with meshio to the last bit of its float64 data (`vtk_roundtrip`).
# - A site's run writes the same files (a `material_id` per element in ParaView, the geometry under every
#   figure) and reads back as a `SiteResult`; a limit analysis's result file keeps both brackets, the mesh,
#   the mechanism, the dissipation and the stress field.
#
# Not shown here (`tests/test_results.py`): a run that ends at a detected limit load is written as a complete
# result with its status and limit load factor, and `ssi show` reports the limit load; a run the solver
# stops before the end of its load path is written too, marked `complete = False` with its last converged
# step and the solver's report, and `ssi run` exits with status 3.
