"""Standard figures of a :class:`ssi.scene.SceneResult` or a :class:`ssi.scene.SiteResult`: each one call
that returns the matplotlib Figure; a site's (``site_*``) with its geometry -- ground, layer boundaries,
water table, foundations -- drawn under each.

    fig = ssi.io.plot.contact(result)            # at the last step; k= selects another step
    fig.savefig("contact.png")

Every function takes the result (live or read back with :func:`ssi.io.results.read_result`), the step ``k``
(default the last converged one) and an optional ``ax`` to draw into (then the figure of that axes is
returned). Lengths are plotted in m, settlements in mm, stresses in kPa or MPa, forces in kN/m.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure

if TYPE_CHECKING:  # annotations only: ssi.scene imports nothing of ssi.io
    from ..scene import SceneResult, SiteResult

ZONE_COLOURS = {"stick": "C0", "slip": "C1", "open": "C3"}
_OUTLINE = [0, 4, 1, 5, 2, 6, 3, 7]  # Q8 nodes in order around the element (corner, mid-side, ...)


def _axes(ax, n=1, figsize=(8, 3.5)) -> tuple[Figure, Axes]:
    if ax is not None:
        return ax.figure, ax
    fig, axes = plt.subplots(n, 1, figsize=figsize, sharex=True, squeeze=True, layout="constrained")
    return fig, axes


def _foundation_window(result, margin=2.0):
    f = result.built.scene.foundation
    if f is None:
        return None
    return (f.x0 - margin * (f.x1 - f.x0), f.x1 + margin * (f.x1 - f.x0))


def _present(result: SceneResult, k: int) -> np.ndarray:
    """(n_el,) bool: the soil elements present at step ``k`` (excavated ones are left out of the plots)."""
    if result.phases and any(ph.excavate for ph in result.built.scene.phases):
        return result.active_elements(k)
    return np.ones(result.built.mesh.conn.shape[0], bool)


def _column_xs(loads) -> list[float]:
    """The x [m] of every column of ``loads``, sorted, each once."""
    return sorted({x for ld in loads for x, _ in ld.columns()})


def _draw_context(ax: Axes, result: SceneResult) -> None:
    """Layer boundaries (dashed), the water table (blue) and the column loads (arrows) of the scene."""
    scene = result.built.scene
    x0, x1 = float(result.built.model.coords[:, 0].min()), float(result.built.model.coords[:, 0].max())
    z = -np.cumsum([lay.thickness for lay in scene.layers])[:-1]
    for zi in z:
        ax.plot([x0, x1], [zi, zi], "--", color="0.45", lw=0.7, zorder=3)
    if z.size:
        ax.plot([], [], "--", color="0.45", lw=0.7, label="layer boundary")
    if scene.water_table is not None:
        zw = -float(scene.water_table)
        ax.plot([x0, x1], [zw, zw], "-", color="C9", lw=1.2, zorder=3, label="water table")
    loads = list(scene.loads) + [ld for ph in scene.phases for ld in ph.loads]
    columns = _column_xs(loads)
    if columns and result.built.plate_nodes is not None:
        top = float(result.built.model.coords[result.built.plate_nodes, 1].max())
        height = 0.08 * (x1 - x0)
        for xc in columns:
            ax.annotate(
                "", (xc, top), (xc, top + height), arrowprops={"arrowstyle": "-|>", "color": "C3", "lw": 1.5}
            )
        ax.plot([], [], "-", color="C3", label="column")
        ax.set_ylim(top=max(ax.get_ylim()[1], top + 1.2 * height))


def deformed_mesh(
    result: SceneResult,
    k: int = -1,
    scale: float | None = None,
    ax: Axes | None = None,
    window: tuple[float, float] | None = None,
) -> Figure:
    """The soil mesh (grey) and its deformed shape (blue) with displacements times ``scale`` (default: the
    largest displacement drawn as 5 % of the block width); the strip as a thick line. Soil excavated by step
    ``k`` is left out (the pit shows as a gap)."""
    fig, ax = _axes(ax, figsize=(9, 4))
    built = result.built
    xy = built.model.coords
    u = np.asarray(result.u[k])
    dofs = built.model.node_dofs(np.arange(built.mesh.xy.shape[0]))
    disp = np.zeros_like(xy)
    disp[: len(dofs)] = u[dofs]
    if built.plate_nodes is not None:
        disp[built.plate_nodes] = u[built.model.node_dofs(built.plate_nodes)][:, :2]
    present = _present(result, k)
    umax = np.abs(disp[np.unique(built.mesh.conn[present])]).max()
    if scale is None:
        scale = 0.05 * built.scene.width / umax if umax > 0 else 1.0
    outline = built.mesh.conn[present][:, _OUTLINE]
    ax.add_collection(PolyCollection(xy[outline], facecolors="none", edgecolors="0.8", linewidths=0.4))
    moved = xy + scale * disp
    ax.add_collection(PolyCollection(moved[outline], facecolors="none", edgecolors="C0", linewidths=0.5))
    if built.plate_nodes is not None:
        p = built.plate_nodes
        ax.plot(xy[p, 0], xy[p, 1], color="0.5", lw=3)
        ax.plot(moved[p, 0], moved[p, 1], color="k", lw=3)
    ax.set_aspect("equal")
    ax.autoscale_view()
    if window is not None:
        ax.set_xlim(*window)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    _draw_context(ax, result)
    handles, _ = ax.get_legend_handles_labels()
    if handles:
        ax.legend(loc="lower right", fontsize=8)
    ax.set_title(f"deformed mesh, displacements x {scale:.3g} (step {_step(result, k)})")
    return fig


def plastic_points(
    result: SceneResult, k: int = -1, ax: Axes | None = None, window: tuple[float, float] | None = None
) -> Figure:
    """Soil integration points yielding at step ``k`` (red): where the soil is at its strength in that step,
    over the elements shaded by their accumulated plastic strain (largest over their points) up to step
    ``k``; layer boundaries, the water table and the columns drawn (excavated soil left out)."""
    fig, ax = _axes(ax, figsize=(9, 4))
    built = result.built
    xy = built.model.coords
    present = _present(result, k)
    # the accumulated plastic strain shades the elements: the mechanism of a collapse shows even when the
    # last step (a relaxation or unloading step) has few points yielding in it
    strain = result.plastic_strain(k).max(axis=1)[present]
    shade = PolyCollection(
        xy[built.mesh.conn[present][:, _OUTLINE]], cmap="Oranges", edgecolors="0.8", linewidths=0.4
    )
    shade.set_array(strain)
    shade.set_clim(0.0, max(float(strain.max()), 1e-12))
    ax.add_collection(shade)
    fig.colorbar(shade, ax=ax, label="accumulated plastic strain [-]", shrink=0.8)
    pts = result.soil_points()
    mask = result.plastic_points(k) & present[:, None]
    ax.plot(pts[mask][:, 0], pts[mask][:, 1], "r.", ms=3, label=f"plastic ({mask.sum()} points)")
    _finish_soil_axes(ax, result, xy, window)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title(f"plastic strain and points yielding in step {_step(result, k)}")
    return fig


def _finish_soil_axes(ax: Axes, result: SceneResult, xy: np.ndarray, window) -> None:
    """The common frame of a plot over the soil: the strip drawn, equal scales, the foundation's window
    (``window`` (x0, x1) or 3 widths around it), axis labels and the context (layers, water, columns)."""
    built = result.built
    if built.plate_nodes is not None:
        ax.plot(xy[built.plate_nodes, 0], xy[built.plate_nodes, 1], "k-", lw=3)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlim(*(window or _foundation_window(result, 3.0) or ax.get_xlim()))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    _draw_context(ax, result)


def mechanism(
    result: SceneResult,
    k: int = -1,
    last: int = 3,
    ax: Axes | None = None,
    window: tuple[float, float] | None = None,
) -> Figure:
    """The mechanism: the soil's incremental displacement over the ``last`` steps up to step ``k`` (arrows
    at the element corners, coloured by magnitude [mm]) -- of a collapse, the failure mechanism the
    plateau's last steps move (the total displacement also holds the elastic part). Excavated soil is left
    out; layer boundaries, the water table and the columns are drawn."""
    fig, ax = _axes(ax, figsize=(9, 4))
    built = result.built
    xy = built.model.coords
    k = _step(result, k)
    k0 = max(k - int(last), 0)
    present = _present(result, k)
    corners = np.unique(built.mesh.conn[present][:, :4])
    du = np.asarray(result.u[k]) - np.asarray(result.u[k0])
    d = np.column_stack([du[built.model.dof(corners, "u")], du[built.model.dof(corners, "w")]])
    size = np.hypot(d[:, 0], d[:, 1])
    ax.add_collection(
        PolyCollection(
            xy[built.mesh.conn[present][:, _OUTLINE]], facecolors="none", edgecolors="0.85", linewidths=0.4
        )
    )
    arrows = ax.quiver(
        xy[corners, 0],
        xy[corners, 1],
        d[:, 0],
        d[:, 1],
        1e3 * size,
        cmap="viridis",
        angles="xy",
        scale_units="xy",
        # the longest arrow drawn 4 % of the block width long: the pattern, not the size, is the message
        scale=max(float(size.max()), 1e-300) / (0.04 * built.scene.width),
        width=0.003,
    )
    fig.colorbar(arrows, ax=ax, label=f"displacement, steps {k0}-{k} [mm]", shrink=0.8)
    _finish_soil_axes(ax, result, xy, window)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="lower right", fontsize=8)
    ax.set_title(f"mechanism: incremental displacement of steps {k0}-{k}")
    return fig


def contact(result: SceneResult, k: int = -1, ax: Axes | None = None) -> Figure:
    """Contact pressure and shear stress under the foundation [kPa], points coloured by zone (stick, slip,
    open). ``ax``: two axes (pressure, shear) or None."""
    fig, axes = _axes(ax, 2, figsize=(8, 5)) if ax is None else (ax[0].figure, ax)
    c = result.contact(k)
    x, zone = c["x"].ravel(), c["zone"].ravel()
    for name, colour in ZONE_COLOURS.items():
        m = zone == name
        if m.any():
            axes[0].plot(x[m], -c["sig_n"].ravel()[m] / 1e3, "o", ms=4, color=colour, label=name)
            axes[1].plot(x[m], c["tau"].ravel()[m] / 1e3, "o", ms=4, color=colour, label=name)
    order = np.argsort(x)
    axes[0].plot(x[order], -c["sig_n"].ravel()[order] / 1e3, "-", color="0.6", lw=0.8)
    axes[1].plot(x[order], c["tau"].ravel()[order] / 1e3, "-", color="0.6", lw=0.8)
    axes[0].set_ylabel("contact pressure [kPa]")
    axes[1].set_ylabel("contact shear [kPa]")
    axes[1].set_xlabel("x [m]")
    axes[0].legend()
    axes[0].set_title(f"contact (step {_step(result, k)})")
    return fig


def settlement(result: SceneResult, k: int = -1, ax: Axes | None = None) -> Figure:
    """Settlement [mm] of the soil surface and of the foundation (positive down, plotted downwards)."""
    fig, ax = _axes(ax)
    xs, ss = result.surface(k)
    window = _foundation_window(result, 2.0)
    near = np.ones_like(xs, bool) if window is None else (xs >= window[0]) & (xs <= window[1])
    ax.plot(xs[near], 1e3 * ss[near], "k-", lw=1, label="soil surface")
    if result.built.plate is not None or result.built.footing_nodes is not None:
        xp, sp = result.settlement(k)
        ax.plot(xp, 1e3 * sp, "C0o-", ms=3, label="foundation")
    ax.invert_yaxis()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("settlement [mm]")
    ax.legend()
    ax.set_title(f"settlement (step {_step(result, k)})")
    return fig


MOMENT_CONVENTION = "M > 0 sagging (tension at the bottom), drawn downwards: on the tension side"


def strip_forces(result: SceneResult, k: int = -1, ax: Axes | None = None) -> Figure:
    """Bending moment M [kN m/m] (sagging positive, drawn on the tension side: downwards -- the convention
    is written on the figure), shear force Q [kN/m] and normal force N [kN/m] (tension positive) along the
    strip, at the sampling points; N also as each element's mean (grey steps); of an RC strip the crack width
    w_k [mm] (:meth:`SceneResult.crack_width`) on a second axis of the moment panel. ``ax``: three axes or
    None.

    Why the mean: in the element a crack front passes through, N at the points oscillates (in
    examples/rc_strip.toml +110 and -43 kN/m at x = +-1.75 m, where the element's points have 2, 5 and 6
    cracked layers), most likely because a 3-node element's axial strain is linear along it and cannot
    follow the jump of the section's stiffness, so the point values balance one another. The element's
    weighted mean -- what its equilibrium fixes -- stays between its neighbours' (27 kN/m there, against 18
    and 36; checked in tests/test_results.py)."""
    fig, axes = _axes(ax, 3, figsize=(8, 7)) if ax is None else (ax[0].figure, ax)
    f = result.strip_forces(k)
    plate = result.built.plate
    w = plate.wt[plate.ax.astype(bool)]
    n_mean = f["N"] @ w / w.sum()
    ends = result.built.model.coords[result.built.plate_nodes[::2], 0]
    axes[2].hlines(n_mean / 1e3, ends[:-1], ends[1:], color="0.4", lw=2.0, label="element mean", zorder=1)
    for a, (xkey, key, label) in zip(
        axes, (("x_ax", "M", "M [kN m/m]"), ("x_sh", "Q", "Q [kN/m]"), ("x_ax", "N", "N [kN/m]"))
    ):
        a.plot(f[xkey].ravel(), f[key].ravel() / 1e3, ".-", label="at the points")
        a.axhline(0.0, color="0.5", lw=0.6)
        a.set_ylabel(label)
    axes[0].invert_yaxis()  # moments on the tension side
    from ..scene.design import design_of  # lazily, as ssi.io's other scene imports

    if design_of(result) is not None:  # an RC strip: its EN 1992 crack width on a second axis of the M panel
        cw = result.crack_width(k)
        tw = axes[0].twinx()
        tw.plot(cw["x"].ravel(), 1e3 * cw["w_k"].ravel(), "C3.:", ms=3, label="crack width $w_k$")
        tw.set_ylabel("$w_k$ [mm] (EN 1992 7.3.4)", color="C3")
        tw.set_ylim(bottom=0.0)
        tw.legend(fontsize=7, loc="lower right")
    axes[2].legend(fontsize=7, loc="lower right")
    axes[-1].set_xlabel("x [m]")
    # the conventions in the title, where no curve can hide them
    axes[0].set_title(
        f"strip forces (step {_step(result, k)})\n{MOMENT_CONVENTION}; N > 0 tension", fontsize=9
    )
    return fig


def cracks_and_steel(result: SceneResult, k: int = -1, ax: Axes | None = None) -> Figure:
    """Cracked concrete layer points (red ticks at their height) and the steel layers' stress [MPa] with
    yielded points marked (x). ``ax``: two axes or None."""
    fig, axes = _axes(ax, 2, figsize=(8, 5)) if ax is None else (ax[0].figure, ax)
    cm = result.crack_map(k)
    xs = cm["x"].ravel()
    for j, z in enumerate(cm["z"]):
        m = cm["cracked"][:, :, j].ravel()
        axes[0].plot(xs[m], np.full(m.sum(), z), "r|", ms=8)
    sec = result.built.plate.section
    axes[0].set_ylim(sec.z_bottom, sec.z_top)
    axes[0].set_ylabel("z of cracked layer [m]")
    st = result.steel_stress(k)
    for j, z in enumerate(st["z"]):
        axes[1].plot(xs, st["sig"][:, :, j].ravel() / 1e6, ".-", label=f"bars at z = {z:.3f} m")
        y = st["yielded"][:, :, j].ravel()
        axes[1].plot(xs[y], st["sig"][:, :, j].ravel()[y] / 1e6, "kx")
    axes[1].set_ylabel("steel stress [MPa]")
    axes[1].set_xlabel("x [m]")
    if len(st["z"]):
        axes[1].legend()
    axes[0].set_title(f"cracks and steel (step {_step(result, k)})")
    return fig


def load_settlement(result: SceneResult, ax: Axes | None = None) -> Figure:
    """The load the foundation carries [kN/m] (:meth:`SceneResult.foundation_load`: the column load, or of
    a push-over the soil's reaction) against the largest settlement [mm] at every converged step, with the
    capacity (:meth:`SceneResult.capacity`) marked and how it was found (and, when its error was estimated,
    the extrapolated capacity as a dashed line). Rows that are not rate-independent
    equilibria (a viscous fallback's) are drawn hollow and never marked as the capacity. Of a phased result
    each phase's stretch is coloured and named."""
    fig, ax = _axes(ax, figsize=(6, 4.5))
    path = result.load_settlement()
    s_mm, load = 1e3 * path["settlement"], path["load"] / 1e3
    ax.plot(s_mm, load, "-", color="0.6", lw=0.8, zorder=1)
    spans = (
        [(r["name"], max(r["first"] - 1, 0), r["last"]) for r in result.phases[1:]]
        if result.phases
        else [(None, 0, len(load) - 1)]
    )
    ok = path["equilibrium"]
    for i, (name, first, last) in enumerate(spans):
        rows = np.arange(first, last + 1)
        good, bad = rows[ok[rows]], rows[~ok[rows]]
        ax.plot(s_mm[good], load[good], "o", ms=3.5, color=f"C{i}", label=name, zorder=2)
        if bad.size:
            ax.plot(s_mm[bad], load[bad], "o", ms=4, mfc="none", color=f"C{i}", zorder=2)
    if (~ok).any():
        ax.plot([], [], "o", mfc="none", color="0.3", label="viscous state (not an equilibrium)")
    cap = result.capacity()
    word = "capacity" if cap["is_limit"] else "largest load carried"
    ax.plot(1e3 * cap["settlement"], cap["load"] / 1e3, "k*", ms=11, zorder=3,
            label=f"{word} {cap['load'] / 1e3:.1f} kN/m")  # fmt: skip
    est = cap.get("estimate")
    if est:  # ssi run --estimate, solve_with_error: where the capacity goes as the mesh is refined
        ax.axhline(est["extrapolated"] / 1e3, ls="--", color="0.3", lw=0.9,
                   label=f"extrapolated {est['extrapolated'] / 1e3:.1f} kN/m "
                   f"(estimated error {100 * est['relative']:.1f} %)")  # fmt: skip
    ax.annotate(cap["how"], (0.02, 0.02), xycoords="axes fraction", fontsize=7, va="bottom", wrap=True)
    ax.set_xlabel("largest settlement [mm]")
    ax.set_ylabel(("footing load (soil reaction)" if result.is_push_over else "column load") + " [kN/m]")
    ax.legend(fontsize=8, loc="center right")  # clear of the sentence at the bottom
    ax.set_title("load-settlement path" + (" over the phases" if result.phases else ""))
    return fig


# ---- a site's figures: its geometry under each -----------------------------------------------------------
def ground_line(site) -> tuple[np.ndarray, np.ndarray]:
    """(x, z) [m] of the soil's top surface: the ground polyline with every embedded strip's trench cut in
    (down its left wall, along the base level, up its right wall), x non-decreasing (a wall: two points at
    the same x)."""
    xs = np.unique(np.concatenate([np.linspace(site.x_left, site.x_right, 401), site.breaks()]))
    # a vertical step of the ground (a cut's face): both its ends at one x, the left one first
    pts = []
    for x in xs:
        z_left, z_right = float(site.ground_z(x, "left")), float(site.ground_z(x, "right"))
        pts += [(x, z_left)] + ([(x, z_right)] if z_right != z_left else [])
    for _, x0, x1, lv in site.embedded():
        left = [p for p in pts if p[0] < x0]  # the ground over the trench (x0 to x1) is gone
        right = [p for p in pts if p[0] > x1]
        walls = [(x0, float(site.ground_z(x0))), (x0, lv), (x1, lv), (x1, float(site.ground_z(x1)))]
        pts = left + walls + right
    a = np.array(pts)
    return a[:, 0], a[:, 1]


def draw_site(ax: Axes, site, result: SiteResult | None = None, k: int = -1) -> None:
    """The site's geometry on ``ax``: the ground (black, with every embedded strip's trench cut in), every
    layer boundary (dashed grey, cut by the ground and the trenches), the water table (blue), the side
    contact on the trench walls (green) and the foundations (thick, at their base level: a plate strip at
    its reference surface, a rigid strip), the column loads as arrows, each foundation numbered as in the
    summary."""
    xs, top = ground_line(site)
    ax.plot(xs, top, "k-", lw=1.0, zorder=4, label="ground")
    for b in range(len(site.layers) - 1):
        ax.plot(xs, np.minimum(site.boundary_z(b, xs), top), "--", color="0.4", lw=0.8, zorder=4,
                label="layer boundary" if b == 0 else None)  # fmt: skip
    first = True
    for i, x0, x1, lv in site.embedded():
        if site.strips[i].side_contact is not None:
            for x in (x0, x1):
                ax.plot([x, x], [float(site.ground_z(x)), lv], "-", color="C2", lw=2.5, zorder=5,
                        label="side contact" if first else None)  # fmt: skip
                first = False
    zw = site.water_z(xs)
    if np.isfinite(zw).any():
        wet = zw <= top + 1e-9  # the water table where it lies in the ground
        ax.plot(np.where(wet, xs, np.nan), zw, "-", color="C9", lw=1.3, zorder=4, label="water table")
    height = 0.04 * site.width
    for i, s in enumerate(site.strips):
        x0, x1 = s.ends
        z = site.base_z(i)  # the ground under it, or its level if embedded
        ax.plot([x0, x1], [z, z], "-", color="C1", lw=4, solid_capstyle="butt", zorder=5,
                label="foundation" if i == 0 else None)  # fmt: skip
        ax.annotate(f"#{i}", (0.5 * (x0 + x1), z + 0.3 * height), ha="center", fontsize=8, zorder=6)
    for x in _column_xs(site.loads):
        z = float(site.ground_z(x)) + height
        ax.annotate("", (x, z - 0.6 * height), (x, z + height),
                    arrowprops={"arrowstyle": "-|>", "color": "C3", "lw": 1.5})  # fmt: skip


def _soil_frame(ax: Axes, site) -> None:
    ax.set_aspect("equal")
    ax.set_xlim(site.x_left, site.x_right)
    top = float(np.max(site.ground_z(np.linspace(site.x_left, site.x_right, 201))))
    ax.set_ylim(site.z_bottom, top + 0.1 * site.width)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.legend(loc="lower right", fontsize=7)


def site_deformed_mesh(result: SiteResult, k: int = -1, scale: float | None = None, ax: Axes | None = None):
    """The soil mesh shaded by layer (each element's material id), its deformed outline (blue, displacements
    times ``scale``; default: the largest drawn as 5 % of the block width) and the site's geometry."""
    fig, ax = _axes(ax, figsize=(10, 4.5))
    built = result.built
    xy = built.mesh.xy
    u = np.asarray(result.u[k])
    n = len(xy)
    disp = np.column_stack([u[built.model.dof(np.arange(n), "u")], u[built.model.dof(np.arange(n), "w")]])
    umax = float(np.abs(disp).max())
    if scale is None:
        scale = 0.05 * built.site.width / umax if umax > 0 else 1.0
    outline = built.mesh.conn[:, _OUTLINE]
    layers = PolyCollection(xy[outline], cmap="Pastel1", edgecolors="0.75", linewidths=0.3)
    layers.set_array(np.asarray(built.element_layer, np.float64))
    layers.set_clim(0, max(8, len(built.site.layers)))
    ax.add_collection(layers)
    moved = PolyCollection((xy + scale * disp)[outline], facecolors="none", edgecolors="C0", linewidths=0.4)
    ax.add_collection(moved)
    draw_site(ax, built.site)
    _soil_frame(ax, built.site)
    ax.set_title(f"layers (shaded by material id) and deformed mesh x {scale:.3g} (step {_step(result, k)})")
    return fig


def site_stress(result: SiteResult, k: int = -1, ax: Axes | None = None) -> Figure:
    """Vertical effective stress szz [kPa] (compression negative), the element means at step ``k``, with the
    site's geometry; yielding points in red where the soil is plastic."""
    fig, ax = _axes(ax, figsize=(10, 4.5))
    built = result.built
    xy = built.mesh.xy
    szz = result.soil_stress(k)[..., 1].mean(axis=1) / 1e3
    pc = PolyCollection(xy[built.mesh.conn[:, _OUTLINE]], cmap="viridis", edgecolors="face", linewidths=0.2)
    pc.set_array(szz)
    ax.add_collection(pc)
    fig.colorbar(pc, ax=ax, label="vertical effective stress szz [kPa]", shrink=0.8)
    mask = result.plastic_points(k)
    if mask.any():
        pts = built.soil.integration_points()
        ax.plot(pts[mask][:, 0], pts[mask][:, 1], "r.", ms=2, label=f"plastic ({mask.sum()} points)")
    draw_site(ax, built.site)
    _soil_frame(ax, built.site)
    ax.set_title(f"vertical effective stress (step {_step(result, k)})")
    return fig


def site_settlement(result: SiteResult, k: int = -1, ax: Axes | None = None) -> Figure:
    """Settlement [mm] (positive down, plotted downwards) of the ground and of every foundation at step
    ``k``, the foundations numbered as in the summary and their extents shaded."""
    fig, ax = _axes(ax, figsize=(9, 3.8))
    built = result.built
    for s in built.site.strips:  # where the foundations stand, shaded under the curves
        x0, x1 = s.ends
        ax.axvspan(x0, x1, color="C1", alpha=0.12, lw=0)
    xs, ws = result.ground_settlement(k=k)
    ax.plot(xs, 1e3 * ws, "k-", lw=1, label="ground")
    for i, st in enumerate(built.strips):
        if st.get("rigid"):
            ids = st["soil_nodes"]
            x = built.mesh.xy[ids, 0]
            w = -np.asarray(result.u[k])[built.model.dof(ids, "w")]
        else:
            x, w = result.strip_settlement(i, k)
        ax.plot(x, 1e3 * w, "o-", ms=3, color=f"C{i % 10}", label=f"#{i}")
    ax.invert_yaxis()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("settlement [mm]")
    ax.legend(fontsize=8)
    ax.set_title(f"settlement of the ground and the foundations (step {_step(result, k)})")
    return fig


def site_load_settlement(result: SiteResult, ax: Axes | None = None) -> Figure:
    """Of a site with rigid strips (pushed down): each one's mean pressure [kPa] against its settlement
    [mm] over the steps."""
    fig, ax = _axes(ax, figsize=(6, 4.5))
    for i, st in enumerate(result.built.strips):
        if st.get("rigid"):
            s, q = result.rigid_pressure(i)
            ax.plot(1e3 * s, q / 1e3, "o-", ms=3, color=f"C{i % 10}", label=f"#{i} rigid strip")
    ax.set_xlabel("settlement [mm]")
    ax.set_ylabel("mean base pressure [kPa]")
    ax.legend(fontsize=8)
    ax.set_title("pressure-settlement of the rigid strips")
    return fig


def _site_figures(result: SiteResult) -> dict[str, Figure]:
    """Every figure that applies to the site: name -> Figure."""
    figs = {
        "geometry_and_deformed_mesh": site_deformed_mesh(result),
        "settlement": site_settlement(result),
        "stress": site_stress(result),
    }
    if any(st.get("rigid") for st in result.built.strips) and len(result.load_factor) > 2:
        figs["load_settlement"] = site_load_settlement(result)
    return figs


def standard_figures(result: SceneResult | SiteResult) -> dict[str, Figure]:
    """Every figure that applies to the result's scene or site: name -> Figure."""
    if result.kind == "site":
        return _site_figures(result)
    figs = {
        "settlement": settlement(result),
        "deformed_mesh": deformed_mesh(result),
        "load_settlement": load_settlement(result),
    }
    if any(lay.c is not None for lay in result.built.scene.layers):
        figs["plastic_points"] = plastic_points(result)
        collapse = result.capacity()["is_limit"] or result.status == "limit load reached"
        if collapse and result.n_steps >= 2:  # a push-over's plateau or peak, a detected limit: its mechanism
            figs["mechanism"] = mechanism(result)
    if result.built.plate is not None:
        figs["contact"] = contact(result)
        figs["strip_forces"] = strip_forces(result)
        if result.built.plate.section.kind.any():  # concrete or steel layers
            figs["cracks_and_steel"] = cracks_and_steel(result)
    return figs


def save_standard_figures(
    result: SceneResult | SiteResult, folder: str | Path, overwrite: bool = False
) -> list[Path]:
    """Write :func:`standard_figures` as PNGs into ``folder`` (atomically, never replacing a file unless
    ``overwrite``); return the paths."""
    return save_figures(standard_figures(result), folder, overwrite)


def save_figures(figs: dict[str, Figure], folder: str | Path, overwrite: bool = False) -> list[Path]:
    """Write each figure of ``figs`` as ``folder/<name>.png`` (atomically, never replacing a file unless
    ``overwrite``), close it, and return the paths."""
    from .results import atomic_path

    folder = Path(folder)
    paths = []
    for name, fig in figs.items():
        target = folder / f"{name}.png"
        with atomic_path(target, overwrite) as tmp:
            fig.savefig(tmp, dpi=110, format="png")
        plt.close(fig)
        paths.append(target)
    return paths


def _step(result, k):
    return range(len(result.load_factor))[k]


def limit_mechanism(capacity, axes=None, window=None):
    """The collapse mechanism of a limit analysis (:class:`ssi.capacity.CapacityResult`, its upper
    bound on the last associated mesh): the speed with the velocity arrows (left) and where the plastic
    dissipation happens, log10 of each triangle's dissipation density over the largest (right).
    ``axes``: two axes to draw into; ``window`` (x0, x1, z0, z1) [m] (default: the whole block). The
    velocities are those of unit reference power: only their pattern and ratios mean anything."""
    mesh = capacity.mesh
    xy, tri = mesh.xy, mesh.tri
    if axes is None:
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), layout="constrained")
    fig = axes[0].figure
    vel = capacity.velocity[: len(xy)]
    speed = np.hypot(vel[:, 0], vel[:, 1])
    tp = axes[0].tripcolor(xy[:, 0], xy[:, 1], tri, speed, shading="gouraud", cmap="viridis")
    axes[0].triplot(xy[:, 0], xy[:, 1], tri, lw=0.1, color="w")
    step = max(1, len(xy) // 400)  # at most ~400 arrows
    axes[0].quiver(xy[::step, 0], xy[::step, 1], vel[::step, 0], vel[::step, 1], color="w", width=0.002)
    fig.colorbar(tp, ax=axes[0], label="|velocity| (unit reference power)")
    dens = np.maximum(capacity.dissipation, 1e-300) / mesh.areas()
    tp = axes[1].tripcolor(
        xy[:, 0], xy[:, 1], tri, facecolors=np.log10(dens / dens.max() + 1e-12), cmap="magma"
    )
    tp.set_clim(-4, 0)
    fig.colorbar(tp, ax=axes[1], label="log10 dissipation density / max")
    if window is None:
        window = (xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(), xy[:, 1].max())
    x0, x1, z0, z1 = window
    for ax, title in zip(axes, ("mechanism (upper bound)", "plastic dissipation")):
        ax.set_aspect("equal")
        ax.set_xlim(x0, x1)
        ax.set_ylim(z0, z1)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("z [m]")
        ax.set_title(title)
    return fig
