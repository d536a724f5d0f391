"""Structured meshes: the separated soil block of the paper's Fig. 1, the foundation strip on top of it and
the interface node pairs between them.

The soil block spans x in [x_left, x_right], z in [-depth, 0] (surface at z = 0, z upwards). Mesh lines are
graded: element size ``h_fine`` under the foundation, growing geometrically (ratio ``growth``) up to
``h_coarse`` away from it, sideways and downwards; optionally (``end_grading``) the elements under the
foundation are graded towards its two ends, where a stiff strip's contact pressure is singular, and the
growth starts from the end elements' size. Every layer boundary is a mesh line, so each element lies
in one layer. Nodes are numbered column by column (z fastest), which keeps neighbours close in memory.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from .validate import check_array, check_real

MAX_LINES = 100_000  # mesh lines per direction: more is a unit slip (mm for m), not a mesh
MAX_END_GRADING = 4.0  # beyond, the end element of a coarse mesh is (2/n)^4 of the half-width: slivers


def graded_lines(start: float, stop: float, h_start: float, h_max: float, growth: float = 1.2) -> np.ndarray:
    """Mesh-line positions from ``start`` to ``stop`` with sizes growing from ``h_start`` by ``growth`` up to
    ``h_max``; the sizes are scaled slightly so the last line falls exactly on ``stop``."""
    start = check_real("start", start, unit="m")
    stop = check_real("stop", stop, unit="m")
    h_start = check_real("h_start", h_start, lo=0.0, lo_open=True, unit="m")
    h_max = check_real("h_max", h_max, lo=h_start, unit="m (>= h_start)")
    growth = check_real("growth", growth, lo=1.0)
    length = abs(stop - start)
    if length == 0.0:
        return np.array([start])
    if length / h_max > MAX_LINES:
        raise ValueError(
            f"h_max={h_max!r} gives more than {MAX_LINES} mesh lines over the length {length:g} m"
        )
    sizes = []
    h = h_start
    while sum(sizes) < length - 1e-9 * length:
        sizes.append(min(h, h_max))
        h *= growth
    sizes = np.array(sizes)
    if len(sizes) > 1 and sizes.sum() - length > 0.5 * sizes[-1]:
        sizes = sizes[:-1]
    sizes *= length / sizes.sum()
    return start + np.sign(stop - start) * np.concatenate([[0.0], np.cumsum(sizes)])


@dataclass
class SoilMesh:
    """A structured Q8 mesh. ``conn`` (n_el, 8) in the node order of ``ssi.core.shapes.serendipity8``."""

    xy: np.ndarray
    conn: np.ndarray
    el_layer: np.ndarray
    x_lines: np.ndarray
    z_lines: np.ndarray
    grid: np.ndarray = field(repr=False)  # (2*nx+1, 2*nz+1) node id at each grid position, -1 at centres

    @property
    def surface(self) -> np.ndarray:
        """Node ids of the ground surface ordered by x: the top node of every grid column (z = 0, and the
        trench bottom z = -embedment where the elements above were removed)."""
        top = [col[col >= 0][-1] for col in self.grid]
        return np.array(top, np.int64)

    @property
    def bottom(self) -> np.ndarray:
        return self.grid[:, 0].copy()

    @property
    def left(self) -> np.ndarray:
        return self.grid[0, :].copy()

    @property
    def right(self) -> np.ndarray:
        return self.grid[-1, :].copy()

    def nodes_between(self, x0: float, x1: float, z: float = 0.0, tol: float = 1e-9) -> np.ndarray:
        """Ids of the nodes on the line z (must be a mesh line) with x0 <= x <= x1, ordered by x."""
        ids = np.flatnonzero(
            (np.abs(self.xy[:, 1] - z) < tol) & (self.xy[:, 0] >= x0 - tol) & (self.xy[:, 0] <= x1 + tol)
        )
        return ids[np.argsort(self.xy[ids, 0])]


def structured_q8(
    x_lines: ArrayLike, z_lines: ArrayLike, z_layer_tops: Sequence[float] | None = None
) -> SoilMesh:
    """Q8 mesh on the tensor grid of element edges ``x_lines`` (nx+1,) and ``z_lines`` (nz+1,), both
    increasing. ``z_layer_tops`` (descending tops of layers 2, 3, ...) assigns ``el_layer``."""
    x_lines = check_array("x_lines", x_lines, ndim=1, min_size=2)
    z_lines = check_array("z_lines", z_lines, ndim=1, min_size=2)
    if np.any(np.diff(x_lines) <= 0) or np.any(np.diff(z_lines) <= 0):
        raise ValueError("x_lines and z_lines must be strictly increasing")
    nx, nz = len(x_lines) - 1, len(z_lines) - 1
    xs = np.empty(2 * nx + 1)
    xs[0::2] = x_lines
    xs[1::2] = 0.5 * (x_lines[:-1] + x_lines[1:])
    zs = np.empty(2 * nz + 1)
    zs[0::2] = z_lines
    zs[1::2] = 0.5 * (z_lines[:-1] + z_lines[1:])
    i, j = np.meshgrid(np.arange(2 * nx + 1), np.arange(2 * nz + 1), indexing="ij")
    keep = ~((i % 2 == 1) & (j % 2 == 1))  # serendipity: no centre node
    grid = np.full(i.shape, -1, np.int64)
    grid[keep] = np.arange(np.count_nonzero(keep))  # C order over (i, j): z fastest
    xy = np.column_stack([xs[i[keep]], zs[j[keep]]])
    ei, ej = np.meshgrid(np.arange(nx), np.arange(nz), indexing="ij")
    ei, ej = 2 * ei.ravel(), 2 * ej.ravel()
    conn = np.column_stack(
        [
            grid[ei, ej],
            grid[ei + 2, ej],
            grid[ei + 2, ej + 2],
            grid[ei, ej + 2],
            grid[ei + 1, ej],
            grid[ei + 2, ej + 1],
            grid[ei + 1, ej + 2],
            grid[ei, ej + 1],
        ]
    )
    z_mid = 0.5 * (z_lines[:-1] + z_lines[1:])[ej // 2]
    el_layer = np.zeros(len(conn), np.int64)
    for top in z_layer_tops if z_layer_tops is not None else []:
        el_layer += z_mid < top
    return SoilMesh(xy, conn, el_layer, x_lines, z_lines, grid)


def soil_block(
    width: float,
    depth: float,
    layer_thicknesses: Sequence[float] | None = None,
    foundation: tuple[float, float] = (-0.5, 0.5),
    h_fine: float = 0.25,
    h_coarse: float = 2.0,
    growth: float = 1.25,
    x_left: float | None = None,
    breaks: Sequence[float] = (),
    embedment: float = 0.0,
    edges: Sequence[float] = (),
    end_grading: float = 1.0,
) -> SoilMesh:
    """The graded soil block of Fig. 1.

    Parameters
    ----------
    width, depth : block size [m]; the block spans x_left .. x_left + width (default centred on x = 0)
    layer_thicknesses : thicknesses of the horizontal layers from the surface down; must sum to ``depth``
        (default: one layer)
    foundation : (x0, x1) of the foundation; mesh lines fall on both ends, spacing ``h_fine`` between them
    h_fine, h_coarse, growth : element size under the foundation, the largest size, the growth ratio
    breaks : x positions [m] that must be nodes of the surface (load ends, column positions, contact segment
        ends): the nearest mesh line is moved there if that keeps every element at least half its size,
        otherwise a line is added; a position that already is a node (a mid-side node) is left alone
    embedment : depth D [m] of the foundation base below the ground (>= 0; must be a layer boundary): the
        elements above it between the foundation ends are removed (the trench the strip sits in)
    edges : x positions [m] that must be element edges (vertical mesh lines through corner nodes, e.g. the
        sides of an excavation), placed before ``breaks`` as they are
    end_grading : exponent gamma >= 1 of the grading of the lines under the foundation towards its ends
        (:func:`foundation_lines`); 1 (default) spaces them evenly. The lines beside the foundation and
        those below the surface grow (ratio ``growth``) from the end element's size, so the elements at the
        foundation's corners are about square: the mesh is graded towards both corner points
    """
    width = check_real("width", width, lo=0.0, lo_open=True, unit="m")
    depth = check_real("depth", depth, lo=0.0, lo_open=True, unit="m")
    x_left = -0.5 * width if x_left is None else check_real("x_left", x_left, unit="m")
    x_right = x_left + width
    if len(foundation) != 2:
        raise ValueError(f"foundation must be a pair (x0, x1), got {foundation!r}")
    x0 = check_real("foundation x0", foundation[0], unit="m")
    x1 = check_real("foundation x1", foundation[1], unit="m")
    if not (x_left <= x0 < x1 <= x_right):
        raise ValueError(
            f"foundation (x0, x1) = {foundation} must lie within the block [{x_left}, {x_right}] "
            "and have x0 < x1"
        )
    layers = [depth] if layer_thicknesses is None else list(layer_thicknesses)
    for i, t in enumerate(layers):
        check_real(f"layer_thicknesses[{i}]", t, lo=0.0, lo_open=True, unit="m")
    if abs(sum(layers) - depth) > 1e-9 * depth:
        raise ValueError(
            f"layer_thicknesses {layers} must tile the depth {depth} (their sum is {sum(layers):g})"
        )
    h_fine = check_real("h_fine", h_fine, lo=0.0, lo_open=True, unit="m")
    if h_fine > x1 - x0:
        raise ValueError(
            f"h_fine={h_fine!r} must be <= the foundation width x1 - x0 = {x1 - x0:g} m (at least one "
            "element under the foundation)"
        )
    h_coarse = check_real("h_coarse", h_coarse, lo=h_fine, unit="m (>= h_fine)")
    check_real("growth", growth, lo=1.0)
    if (x1 - x0) / h_fine > MAX_LINES or max(width, depth) / h_coarse > MAX_LINES:
        raise ValueError(
            f"h_fine={h_fine!r}, h_coarse={h_coarse!r} give more than {MAX_LINES} mesh lines "
            f"in one direction (block {width:g} m x {depth:g} m): check the units"
        )
    under = foundation_lines(x0, x1, h_fine, end_grading)
    # the lines beside the foundation and below the surface grow from the end element's size (even: exactly
    # the size used before the grading existed)
    h_end = (x1 - x0) / (len(under) - 1) if end_grading == 1.0 else under[1] - under[0]
    left = graded_lines(x0, x_left, h_end, h_coarse, growth)[::-1]
    right = graded_lines(x1, x_right, h_end, h_coarse, growth)
    protected = (x_left, x0, x1, x_right)
    x_lines = _insert_breaks(np.unique(np.concatenate([left, under, right])), edges, protected, as_edges=True)
    x_lines = _insert_breaks(x_lines, breaks, protected + tuple(float(v) for v in edges))
    z_parts = [np.array([0.0])]
    top, h = 0.0, h_end  # graded: the ends' corner elements are about square, not slivers
    for t in layers:
        part = graded_lines(top, top - t, h, h_coarse, growth)
        z_parts.append(part[1:])
        h = min(abs(part[-1] - part[-2]) * growth, h_coarse)
        top -= t
    z_lines = np.concatenate(z_parts)[::-1]
    tops = -np.cumsum(layers)[:-1]
    mesh = structured_q8(x_lines, z_lines, tops)
    if embedment:
        if not (0.0 < embedment < depth) or np.min(np.abs(tops - (-embedment)), initial=np.inf) > 1e-9:
            raise ValueError(
                f"embedment={embedment} m must be a layer boundary inside the block (layer tops "
                f"at depths {(-tops).tolist()} m): give the soil beside the strip as its own layer"
            )
        centre = mesh.xy[mesh.conn].mean(axis=1)
        trench = (centre[:, 0] > x0) & (centre[:, 0] < x1) & (centre[:, 1] > -embedment)
        mesh = remove_elements(mesh, ~trench)
    return mesh


def foundation_lines(x0: float, x1: float, h_fine: float, end_grading: float = 1.0) -> np.ndarray:
    """Mesh-line positions [m] under a foundation from ``x0`` to ``x1``: n = round((x1 - x0) / h_fine)
    elements (at least one), spaced evenly for ``end_grading`` = 1, else graded towards both ends by the
    symmetric power map

        x(t) = x0 + (x1 - x0) s(t),  s(t) = (2t)^gamma / 2 for t <= 1/2,  1 - (2(1 - t))^gamma / 2 beyond,

    of the even parameters t = i/n (Babuska's radical grading, mirrored). The end element is then about
    (x1 - x0) / 2 * (2/n)^gamma, so halving ``h_fine`` shrinks it by 2^gamma: a family of such meshes resolves
    the singular contact pressure at the ends of a stiff strip faster than the even one, with the same number
    of elements (those in the middle grow to about gamma * h_fine)."""
    h_fine = check_real("h_fine", h_fine, lo=0.0, lo_open=True, unit="m")
    end_grading = check_real("end_grading", end_grading, lo=1.0, hi=MAX_END_GRADING, unit="-")
    n = max(1, round((x1 - x0) / h_fine))
    if end_grading == 1.0:
        return np.linspace(x0, x1, n + 1)
    t = np.arange(n + 1) / n
    s = np.where(t <= 0.5, 0.5 * (2.0 * t) ** end_grading, 1.0 - 0.5 * (2.0 * (1.0 - t)) ** end_grading)
    return x0 + (x1 - x0) * s


def _insert_breaks(
    lines: ArrayLike, breaks: Sequence[float], protected: Sequence[float], as_edges: bool = False
) -> np.ndarray:
    """Make every x in ``breaks`` a node of the surface: move the nearest unprotected line there when both
    neighbouring elements stay at least half their size, else insert a line. ``as_edges``: every x must be
    a line itself (an element edge), a mid-side node is not enough."""
    lines = np.array(lines, np.float64)
    fixed = list(protected)
    for b in sorted(float(v) for v in breaks):
        if not (lines[0] <= b <= lines[-1]):
            raise ValueError(f"break x={b} lies outside the block [{lines[0]}, {lines[-1]}]")
        mids = 0.5 * (lines[:-1] + lines[1:])
        scale = max(1.0, abs(b)) * 1e-9
        if np.min(np.abs(lines - b)) < scale or (not as_edges and np.min(np.abs(mids - b)) < scale):
            fixed.append(b)
            continue
        i = int(np.argmin(np.abs(lines - b)))
        movable = 0 < i < len(lines) - 1 and min(abs(lines[i] - f) for f in fixed) > scale
        if movable:
            left, right = lines[i] - lines[i - 1], lines[i + 1] - lines[i]
            new_left, new_right = b - lines[i - 1], lines[i + 1] - b
            movable = new_left >= 0.5 * left and new_right >= 0.5 * right
        if movable:
            lines[i] = b
        else:
            lines = np.sort(np.append(lines, b))
        fixed.append(b)
    return lines


def remove_elements(mesh: SoilMesh, keep: ArrayLike) -> SoilMesh:
    """The mesh without the elements where ``keep`` (n_el,) is False; nodes no kept element uses are dropped
    and the rest renumbered in their order (``grid`` holds -1 where a node was dropped)."""
    keep = np.asarray(keep, bool)
    conn = mesh.conn[keep]
    used = np.zeros(len(mesh.xy), bool)
    used[conn.ravel()] = True
    new_id = np.full(len(mesh.xy), -1, np.int64)
    new_id[used] = np.arange(np.count_nonzero(used))
    grid = np.where(mesh.grid >= 0, new_id[np.maximum(mesh.grid, 0)], -1)
    return SoilMesh(mesh.xy[used], new_id[conn], mesh.el_layer[keep], mesh.x_lines, mesh.z_lines, grid)


def surface_pressure_forces(
    mesh: SoilMesh, x0: float, x1: float, z: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """(node ids, nodal force per unit pressure [m]) of a uniform pressure on the surface line z from x0 to
    x1 (both mesh lines): the consistent forces L/6, 4L/6, L/6 of every quadratic edge in the range."""
    nodes = mesh.nodes_between(x0, x1, z)
    if len(nodes) < 3 or len(nodes) % 2 == 0:
        raise ValueError(f"the pressure range ({x0}, {x1}) at z={z} must start and end on element edges")
    xs = mesh.xy[nodes, 0]
    f = np.zeros(len(nodes))
    for i in range(0, len(nodes) - 2, 2):
        L = xs[i + 2] - xs[i]
        f[i : i + 3] += np.array([1.0, 4.0, 1.0]) * L / 6.0
    return nodes, f


@dataclass
class Contact:
    """The foundation strip on the block's surface and the interface node pairs under it."""

    plate_xy: np.ndarray  # (n, 2) plate mid-surface nodes, z = thickness / 2
    soil_nodes: np.ndarray  # (n,) soil surface node ids under them, ordered by x
    plate_conn: np.ndarray  # (n_el, 3) local plate-node indices of each 3-node plate/interface element
    soil_conn: np.ndarray  # (n_el, 3) soil node ids of each interface element's lower side


def foundation_contact(mesh: SoilMesh, x0: float, x1: float, thickness: float, z: float = 0.0) -> Contact:
    """Plate-strip nodes above the soil nodes on the line z (the foundation base) between x0 and x1 (which
    must be mesh lines)."""
    soil = mesh.nodes_between(x0, x1, z)
    if len(soil) < 3 or len(soil) % 2 == 0:
        raise ValueError(f"the foundation ({x0}, {x1}) must start and end on soil element edges")
    if abs(mesh.xy[soil[0], 0] - x0) > 1e-9 or abs(mesh.xy[soil[-1], 0] - x1) > 1e-9:
        raise ValueError(f"the foundation ends x0={x0}, x1={x1} must be mesh lines of the soil block")
    plate_xy = np.column_stack([mesh.xy[soil, 0], np.full(len(soil), z + 0.5 * thickness)])
    local = np.arange(0, len(soil) - 2, 2)
    plate_conn = np.column_stack([local, local + 1, local + 2])
    return Contact(plate_xy, soil, plate_conn, soil[plate_conn])
