"""Figures of a solved site (:class:`ssi.scene.SiteResult`): each one call that returns the matplotlib Figure,
the site's geometry -- ground, layer boundaries, water table, foundations -- drawn under every one.

    fig = ssi.io.plot_site.site_stress(result)     # at the last step; k= selects another step

Lengths in m, settlements in mm, stresses in kPa, forces in kN/m (as :mod:`ssi.io.plot`).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure

from .plot import _OUTLINE, _axes, _step, save_figures

if TYPE_CHECKING:  # annotations only
    from ..scene import SiteResult

__all__ = [
    "draw_site",
    "ground_line",
    "save_site_figures",
    "site_deformed_mesh",
    "site_figures",
    "site_load_settlement",
    "site_settlement",
    "site_stress",
]


def ground_line(site) -> tuple[np.ndarray, np.ndarray]:
    """(x, z) [m] of the soil's top surface: the ground polyline with every embedded strip's trench cut in
    (down its left wall, along the base level, up its right wall), x non-decreasing (a wall: two points at
    the same x)."""
    xs = np.unique(np.concatenate([np.linspace(site.x_left, site.x_right, 401), site.breaks()]))
    pts = [(x, float(site.ground_z(x))) for x in xs]
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
    from ..scene import ColumnLoad

    height = 0.04 * site.width
    for i, s in enumerate(site.strips):
        x0, x1 = (s.foundation.x0, s.foundation.x1) if hasattr(s, "foundation") else (s.x0, s.x1)
        z = site.base_z(i)  # the ground under it, or its level if embedded
        ax.plot([x0, x1], [z, z], "-", color="C1", lw=4, solid_capstyle="butt", zorder=5,
                label="foundation" if i == 0 else None)  # fmt: skip
        ax.annotate(f"#{i}", (0.5 * (x0 + x1), z + 0.3 * height), ha="center", fontsize=8, zorder=6)
    for ld in site.loads:
        if isinstance(ld, ColumnLoad):
            z = float(site.ground_z(ld.x)) + height
            ax.annotate("", (ld.x, z - 0.6 * height), (ld.x, z + height),
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
        x0, x1 = (s.foundation.x0, s.foundation.x1) if hasattr(s, "foundation") else (s.x0, s.x1)
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


def site_figures(result: SiteResult) -> dict[str, Figure]:
    """Every figure that applies to the site: name -> Figure."""
    figs = {
        "geometry_and_deformed_mesh": site_deformed_mesh(result),
        "settlement": site_settlement(result),
        "stress": site_stress(result),
    }
    if any(st.get("rigid") for st in result.built.strips) and len(result.load_factor) > 2:
        figs["load_settlement"] = site_load_settlement(result)
    return figs


def save_site_figures(result: SiteResult, folder: str | Path, overwrite: bool = False) -> list[Path]:
    """Write :func:`site_figures` as PNGs into ``folder`` (atomically, never replacing a file unless
    ``overwrite``); return the paths."""
    return save_figures(site_figures(result), folder, overwrite)
