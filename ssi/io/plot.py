"""Standard figures of a :class:`ssi.scene.SceneResult`: each one call that returns the matplotlib Figure.

    fig = ssi.io.plot.contact(result)            # at the last step; k= selects another step
    fig.savefig("contact.png")

Every function takes the result (live or read back with :func:`ssi.io.results.read_result`), the step ``k``
(default the last converged one) and an optional ``ax`` to draw into (then the figure of that axes is
returned). Lengths are plotted in m, settlements in mm, stresses in kPa or MPa, forces in kN/m.
"""

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import PolyCollection

ZONE_COLOURS = {"stick": "C0", "slip": "C1", "open": "C3"}
_OUTLINE = [0, 4, 1, 5, 2, 6, 3, 7]  # Q8 nodes in order around the element (corner, mid-side, ...)


def _axes(ax, n=1, figsize=(8, 3.5)):
    if ax is not None:
        return ax.figure, ax
    fig, axes = plt.subplots(n, 1, figsize=figsize, sharex=True, squeeze=True, layout="constrained")
    return fig, axes


def _foundation_window(result, margin=2.0):
    f = result.built.scene.foundation
    if f is None:
        return None
    return (f.x0 - margin * (f.x1 - f.x0), f.x1 + margin * (f.x1 - f.x0))


def deformed_mesh(result, k=-1, scale=None, ax=None, window=None):
    """The soil mesh (grey) and its deformed shape (blue) with displacements times ``scale`` (default: the
    largest displacement drawn as 5 % of the block width); the strip as a thick line."""
    fig, ax = _axes(ax, figsize=(9, 4))
    built = result.built
    xy = built.model.coords
    u = np.asarray(result.u[k])
    dofs = built.model.node_dofs(np.arange(built.mesh.xy.shape[0]))
    disp = np.zeros_like(xy)
    disp[: len(dofs)] = u[dofs]
    if built.plate_nodes is not None:
        disp[built.plate_nodes] = u[built.model.node_dofs(built.plate_nodes)][:, :2]
    umax = np.abs(disp).max()
    if scale is None:
        scale = 0.05 * built.scene.width / umax if umax > 0 else 1.0
    outline = built.mesh.conn[:, _OUTLINE]
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
    ax.set_title(f"deformed mesh, displacements x {scale:.3g} (step {_step(result, k)})")
    return fig


def plastic_points(result, k=-1, ax=None, window=None):
    """Soil integration points yielding at step ``k`` (red) on the mesh outline: where the soil has reached
    its Mohr--Coulomb strength in that step."""
    fig, ax = _axes(ax, figsize=(9, 4))
    built = result.built
    xy = built.model.coords
    ax.add_collection(
        PolyCollection(xy[built.mesh.conn[:, _OUTLINE]], facecolors="none", edgecolors="0.8", linewidths=0.4)
    )
    pts = result.soil_points()
    mask = result.plastic_points(k)
    ax.plot(pts[mask][:, 0], pts[mask][:, 1], "r.", ms=3, label=f"plastic ({mask.sum()} points)")
    if built.plate_nodes is not None:
        ax.plot(xy[built.plate_nodes, 0], xy[built.plate_nodes, 1], "k-", lw=3)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlim(*(window or _foundation_window(result, 3.0) or ax.get_xlim()))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.legend(loc="lower right")
    ax.set_title(f"plastic points (step {_step(result, k)})")
    return fig


def contact(result, k=-1, ax=None):
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


def settlement(result, k=-1, ax=None):
    """Settlement [mm] of the soil surface and of the foundation (positive down, plotted downwards)."""
    fig, ax = _axes(ax)
    xs, ss = result.surface(k)
    window = _foundation_window(result, 2.0)
    near = np.ones_like(xs, bool) if window is None else (xs >= window[0]) & (xs <= window[1])
    ax.plot(xs[near], 1e3 * ss[near], "k-", lw=1, label="soil surface")
    if result.built.plate is not None:
        xp, sp = result.settlement(k)
        ax.plot(xp, 1e3 * sp, "C0o-", ms=3, label="foundation")
    ax.invert_yaxis()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("settlement [mm]")
    ax.legend()
    ax.set_title(f"settlement (step {_step(result, k)})")
    return fig


def strip_forces(result, k=-1, ax=None):
    """Bending moment M [kN m/m] (sagging positive, drawn on the tension side: downwards), shear force
    Q [kN/m] and normal force N [kN/m] along the strip. ``ax``: three axes or None."""
    fig, axes = _axes(ax, 3, figsize=(8, 7)) if ax is None else (ax[0].figure, ax)
    f = result.strip_forces(k)
    for a, (xkey, key, label) in zip(
        axes, (("x_ax", "M", "M [kN m/m]"), ("x_sh", "Q", "Q [kN/m]"), ("x_ax", "N", "N [kN/m]"))
    ):
        a.plot(f[xkey].ravel(), f[key].ravel() / 1e3, ".-")
        a.axhline(0.0, color="0.5", lw=0.6)
        a.set_ylabel(label)
    axes[0].invert_yaxis()  # moments on the tension side
    axes[-1].set_xlabel("x [m]")
    axes[0].set_title(f"strip forces (step {_step(result, k)})")
    return fig


def cracks_and_steel(result, k=-1, ax=None):
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


def load_settlement(result, ax=None):
    """Total column load [kN/m] against the largest settlement [mm], every converged step; of a phased
    result the phase time (phase i runs from i - 1 to i) against the settlement, each phase named."""
    fig, ax = _axes(ax, figsize=(5, 4))
    path = result.load_settlement()
    if result.phases:
        ax.plot(1e3 * path["settlement"], path["load_factor"], "o-", ms=3)
        for i, record in enumerate(result.phases):
            ax.axhline(i, color="0.8", lw=0.8, zorder=0)
            ax.annotate(
                record["name"],
                (0.02, i - 0.5 if i else 0.0),
                xycoords=("axes fraction", "data"),
                fontsize=8,
                va="center",
            )
        ax.set_ylabel("phase time [-]")
    else:
        ax.plot(1e3 * path["settlement"], path["column_load"] / 1e3, "o-")
        ax.set_ylabel("column load [kN/m]")
    ax.set_xlabel("largest settlement [mm]")
    ax.set_title("load-settlement path")
    return fig


def standard_figures(result) -> dict:
    """Every figure that applies to the result's scene: name -> Figure."""
    figs = {
        "settlement": settlement(result),
        "deformed_mesh": deformed_mesh(result),
        "load_settlement": load_settlement(result),
    }
    if any(lay.c is not None for lay in result.built.scene.layers):
        figs["plastic_points"] = plastic_points(result)
    if result.built.plate is not None:
        figs["contact"] = contact(result)
        figs["strip_forces"] = strip_forces(result)
        if result.built.plate.section.kind.any():  # concrete or steel layers
            figs["cracks_and_steel"] = cracks_and_steel(result)
    return figs


def save_standard_figures(result, folder, overwrite=False) -> list[Path]:
    """Write :func:`standard_figures` as PNGs into ``folder`` (atomically, never replacing a file unless
    ``overwrite``); return the paths."""
    from .results import atomic_path

    folder = Path(folder)
    paths = []
    for name, fig in standard_figures(result).items():
        target = folder / f"{name}.png"
        with atomic_path(target, overwrite) as tmp:
            fig.savefig(tmp, dpi=110, format="png")
        plt.close(fig)
        paths.append(target)
    return paths


def _step(result, k):
    return range(len(result.load_factor))[k]


def limit_mechanism(capacity, axes=None, window=None):
    """The collapse mechanism of a limit analysis (:class:`ssi.scene.capacity.CapacityResult`, its upper
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
