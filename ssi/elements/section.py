"""Cross-sections of the layered plate strip: from a description (depth, cover, bars) to layers.

A section is a stack of layers through the thickness of the strip (paper §4, Fig. 4). Each layer ``n`` has

=================  ==========  =================================================================
array              shape       meaning
=================  ==========  =================================================================
``z_mid``          (n_layer,)  mid-depth of the layer, measured upwards from the reference surface
                               (the surface the element's nodes lie on; default: mid-depth)
``h``              (n_layer,)  thickness [m]; a steel layer's thickness is its bar area per unit
                               width As/b [m^2/m], its *mechanically equivalent* thickness
``kind``           (n_layer,)  law kind of ``ssi.materials.layer_laws`` (ELASTIC, concrete, steel...)
``params``         (n_layer,   law parameters, padded with zeros to a common length
                   n_par)
``carries_shear``  (n_layer,)  False for steel layers: bars carry only axial stress (paper §5.4)
=================  ==========  =================================================================

Layers are stacked from the bottom face upwards; bar layers *replace* the concrete they occupy, so the
layer thicknesses add up to the section depth. With the paper's beam (§9.2): 9 concrete layers and two
steel layers give 11 layers, steel in layers 2 and 10 (counted from the bottom), see :func:`rc_section`.
"""

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numba import njit
from numpy.typing import ArrayLike

from ..core.protocol import K0_MATRIX
from ..core.quadrature import layer_rule
from ..core.validate import check_array, check_int, check_real
from ..materials.concrete import N_CONCRETE_PARAMS
from ..materials.layer_laws import (
    CONCRETE,
    ELASTIC,
    N_LAYER_CONSTANTS,
    N_LAYER_HIST,
    STEEL,
    layer_constants,
    layer_update_with,
)
from ..materials.steel import N_STEEL_PARAMS

__all__ = ["Section", "homogeneous", "layered", "paper_rc_section", "rc_section", "with_crack_spacing_band"]

LAYER_KINDS = (ELASTIC, CONCRETE, STEEL)


# The layers' initial moduli through the plate kernel's own call of layer_update_with (constants as an array
# row), compiled without reference counting as the plate's loop is: numba compiles a function once per
# signature, with the setting of its first caller, and the loop then calls that copy. Called from Python
# instead, layer_update_with was compiled with the counts and the plate loop ran at 245-290 ns per layer point
# instead of 53-58 (bench_kernels.py's strip); through layer_update (a tuple of constants) a second copy of
# the concrete law compiled on a fresh install (~10 % of the first run).
@njit(cache=True, _nrt=False)
def _initial_moduli(kind, params, const, hist0, hist1, tangent, e0, g0):
    for n in range(kind.shape[0]):
        layer_constants(kind[n], params[n], const)
        e_t, g_t = layer_update_with(kind[n], params[n], const, 0.0, 0.0, hist0, hist1, tangent)[2:]
        e0[n] = e_t
        g0[n] = g_t


@dataclass(frozen=True)
class Section:
    """Layers of a plate-strip section (arrays described in the module docstring).

    ``z_bottom``/``z_top`` are the faces relative to the reference surface (``z_bottom < 0 < z_top`` when the
    reference is inside the section). The interface element attaches to the bottom face: its upper nodes move
    with ``u_g = u_b - z_bottom * alpha_b`` (paper eq. 6.1 with ``-z_bottom = h/2`` for a mid-depth
    reference).
    """

    z_mid: np.ndarray
    h: np.ndarray
    kind: np.ndarray
    params: np.ndarray
    carries_shear: np.ndarray
    z_bottom: float
    z_top: float
    labels: tuple = ()

    def __post_init__(self):
        """Check the arrays against each other (the layers must stack from z_bottom to z_top without gaps) and
        store them as contiguous float64 / int64 / bool arrays."""
        h = check_array("Section.h", self.h, ndim=1, lo=0.0, lo_open=True, min_size=1)
        n = h.size
        z_mid = check_array("Section.z_mid", self.z_mid, shape=(n,))
        kind = check_array("Section.kind", self.kind, shape=(n,), dtype=np.int64)
        if not np.all(np.isin(kind, LAYER_KINDS)):
            bad = kind[~np.isin(kind, LAYER_KINDS)][0]
            raise ValueError(
                f"Section.kind must hold layer law kinds {LAYER_KINDS} (ELASTIC, CONCRETE, STEEL), got {bad}"
            )
        params = check_array("Section.params", self.params, ndim=2)
        if params.shape[0] != n or params.shape[1] < 2:
            raise ValueError(
                f"Section.params must have shape ({n}, n_par >= 2), one row per layer, got {params.shape}"
            )
        # a CONCRETE or STEEL layer reads its law's whole parameter row (ssi.materials.rc.concrete_params,
        # steel_params): a shorter row (an elastic [E, nu] row given a concrete kind) is refused here, by
        # name, not met as an index error inside the crack band or the kernels
        for law, name, n_par, maker in (
            (CONCRETE, "CONCRETE", N_CONCRETE_PARAMS, "concrete_params"),
            (STEEL, "STEEL", N_STEEL_PARAMS, "steel_params"),
        ):
            if np.any(kind == law) and params.shape[1] < n_par:
                layer = int(np.flatnonzero(kind == law)[0])
                raise ValueError(
                    f"Section.params has {params.shape[1]} columns, but layer {layer} is {name}, whose law "
                    f"needs {n_par} (build its row with ssi.materials.rc.{maker})"
                )
        if not params[:, 0].min() > 0.0:
            raise ValueError(
                f"Section.params[:, 0] (each layer's initial modulus) must be > 0, got {params[:, 0].min()!r}"
            )
        elastic = kind == ELASTIC
        if np.any(elastic & ~((params[:, 1] > -1.0) & (params[:, 1] < 0.5))):
            bad = params[elastic, 1][~((params[elastic, 1] > -1.0) & (params[elastic, 1] < 0.5))][0]
            raise ValueError(
                f"Section.params[:, 1] (nu of an ELASTIC layer) must lie in (-1, 0.5), got {bad!r}"
            )
        shear = self.carries_shear
        if isinstance(shear, str) or np.asarray(shear).dtype != bool:
            raise TypeError(f"Section.carries_shear must be a boolean array of shape ({n},), got {shear!r}")
        shear = np.ascontiguousarray(shear, bool)
        if shear.shape != (n,):
            raise ValueError(f"Section.carries_shear must have shape ({n},), got {shear.shape}")
        if not shear.any():
            raise ValueError("Section.carries_shear is all False: at least one layer must carry shear")
        z_bottom = check_real("Section.z_bottom", self.z_bottom, unit="m")
        z_top = check_real("Section.z_top", self.z_top, unit="m")
        if not z_bottom < z_top:
            raise ValueError(
                f"Section.z_bottom must be < z_top, got z_bottom={self.z_bottom!r}, z_top={self.z_top!r}"
            )
        tol = 1e-9 * (z_top - z_bottom)
        if abs(h.sum() - (z_top - z_bottom)) > tol:
            raise ValueError(
                f"Section.h must add up to the depth z_top - z_bottom = {z_top - z_bottom:g} m "
                f"(stacked layers), got sum(h) = {h.sum():g}"
            )
        stacked = z_bottom + np.cumsum(h) - 0.5 * h
        if np.max(np.abs(z_mid - stacked)) > tol:
            raise ValueError(
                f"Section.z_mid must be the mid-depths of the layers stacked upwards from z_bottom "
                f"({stacked.tolist()}), got {z_mid.tolist()}"
            )
        labels = self.labels
        if (
            not isinstance(labels, tuple | list)
            or not all(isinstance(t, str) for t in labels)
            or len(labels) not in (0, n)
        ):
            raise TypeError(f"Section.labels must be a tuple of {n} strings (or empty), got {labels!r}")
        for name, value in (
            ("z_mid", z_mid),
            ("h", h),
            ("kind", kind),
            ("params", params),
            ("carries_shear", shear),
            ("labels", tuple(labels)),
        ):
            object.__setattr__(self, name, value)

    @property
    def n_layer(self) -> int:
        return len(self.h)

    @property
    def thickness(self) -> float:
        return self.z_top - self.z_bottom

    def initial_moduli(self) -> tuple[np.ndarray, np.ndarray]:
        """Initial moduli ``(e0, g0)`` (n_layer,) of every layer's law at zero strain and zero history:
        ``e0 = d sig/d eps`` (D1 of eq. 4.4), ``g0 = d tau/d gam`` (D2, before the shear factor kappa)."""
        e0 = np.empty(self.n_layer)
        g0 = np.empty(self.n_layer)
        const = np.zeros(N_LAYER_CONSTANTS)
        hist0 = np.zeros(N_LAYER_HIST)
        hist1 = np.zeros(N_LAYER_HIST)
        _initial_moduli(self.kind, self.params, const, hist0, hist1, K0_MATRIX, e0, g0)
        return e0, g0

    def elastic_resultant_stiffness(self, kappa: float = 5.0 / 6.0) -> dict:
        """Section stiffnesses of the undamaged section about the reference surface, eq. (4.7b) integrated
        through the thickness with the rectangular rule and its exact h_n^2/12 term:

        A = sum e0 h (axial), B = -sum e0 h z (coupling), D = sum e0 h (z^2 + h^2/12) (bending),
        S = kappa sum_{shear layers} g0 h (shear); also the elastic neutral axis z_na = -B/A and
        D_na = D - B^2/A (bending stiffness about it)."""
        e0, g0 = self.initial_moduli()
        A = float(np.sum(e0 * self.h))
        B = float(-np.sum(e0 * self.h * self.z_mid))
        D = float(np.sum(e0 * self.h * (self.z_mid**2 + self.h**2 / 12.0)))
        S = float(kappa * np.sum(np.where(self.carries_shear, g0 * self.h, 0.0)))
        return {"A": A, "B": B, "D": D, "S": S, "z_na": -B / A, "D_na": D - B * B / A}

    def describe(self) -> dict:
        return {
            "n_layer": self.n_layer,
            "thickness": self.thickness,
            "z_bottom": self.z_bottom,
            "z_mid": self.z_mid.tolist(),
            "h": self.h.tolist(),
            "kind": self.kind.tolist(),
            "params": self.params.tolist(),
            "carries_shear": self.carries_shear.tolist(),
            "labels": list(self.labels),
        }


def _pad_params(params_list) -> np.ndarray:
    rows = [np.atleast_1d(np.asarray(p, np.float64)) for p in params_list]
    if any(r.ndim != 1 or r.size == 0 for r in rows):
        raise ValueError("params must give a non-empty 1-D parameter vector per layer")
    out = np.zeros((len(rows), max(r.size for r in rows)))
    for i, r in enumerate(rows):
        out[i, : r.size] = r
    return out


def layered(
    thicknesses: ArrayLike,
    kinds: ArrayLike,
    params: ArrayLike | Sequence[ArrayLike],
    carries_shear: ArrayLike | None = None,
    z_ref: float | None = None,
    labels: tuple = (),
) -> Section:
    """A section from layer thicknesses listed from the bottom face upwards.

    Parameters
    ----------
    thicknesses : (n_layer,) positive thicknesses [m], bottom to top
    kinds : int or (n_layer,) law kinds
    params : (n_par,) for all layers, or a list of per-layer parameter vectors
    carries_shear : None (all layers carry shear) or (n_layer,) bool
    z_ref : height of the reference surface (the nodes) above the bottom face; default mid-depth
    """
    h_in = np.asarray(thicknesses, np.float64)
    if h_in.ndim != 1 or h_in.size == 0 or np.any(~(h_in > 0.0)):
        raise ValueError("thicknesses must be a non-empty 1-D list of positive numbers")
    n = h_in.size
    total = float(h_in.sum())
    if z_ref is None:
        z_ref = 0.5 * total
    if not 0.0 <= z_ref <= total:
        raise ValueError(f"z_ref must lie within the section, 0 <= z_ref <= {total}, got {z_ref}")
    z_mid, h = layer_rule(h_in, -float(z_ref))
    kind = np.ascontiguousarray(np.broadcast_to(np.asarray(kinds, np.int64), (n,)))
    if all(np.isscalar(x) for x in params):
        plist = [np.asarray(params, np.float64)] * n  # one parameter vector for every layer
    else:
        plist = list(params)
    if len(plist) != n:
        raise ValueError(f"params must be one vector or {n} vectors (one per layer), got {len(plist)}")
    cs = np.ones(n, bool) if carries_shear is None else np.asarray(carries_shear, bool)
    if cs.shape != (n,):
        raise ValueError(f"carries_shear must have shape ({n},), got {cs.shape}")
    if not cs.any():
        raise ValueError("at least one layer must carry shear (carries_shear all False)")
    return Section(
        z_mid=np.ascontiguousarray(z_mid),
        h=np.ascontiguousarray(h),
        kind=kind,
        params=_pad_params(plist),
        carries_shear=np.ascontiguousarray(cs),
        z_bottom=-float(z_ref),
        z_top=total - float(z_ref),
        labels=tuple(labels),
    )


def homogeneous(
    thickness: float, E: float, nu: float, n_layers: int = 1, z_ref: float | None = None
) -> Section:
    """A linear-elastic homogeneous section split into ``n_layers`` equal layers."""
    thickness = check_real("thickness", thickness, lo=0.0, lo_open=True, unit="m")
    check_real("E", E, lo=0.0, lo_open=True, unit="Pa")
    check_real("nu", nu, lo=-1.0, hi=0.5, lo_open=True, hi_open=True)
    n = check_int("n_layers", n_layers, lo=1)
    return layered(np.full(n, thickness / n), ELASTIC, [E, nu], z_ref=z_ref, labels=("concrete",) * n)


def _allocate(n_total: int, gaps: np.ndarray) -> np.ndarray:
    """Split ``n_total`` layers over gaps in proportion to their thickness, at least one per gap
    (largest-remainder rounding)."""
    k = len(gaps)
    if n_total < k:
        raise ValueError(f"n_concrete must be >= {k} (one layer per concrete gap), got {n_total}")
    share = gaps / gaps.sum() * (n_total - k)
    n = 1 + np.floor(share).astype(int)
    rest = n_total - n.sum()
    order = sorted(range(k), key=lambda i: -(share[i] - np.floor(share[i])))
    for i in order[:rest]:
        n[i] += 1
    return n


def _bar_entries(bars) -> list[tuple[float, float]]:
    """``bars`` as a list of (z_bar [m], As [m^2/m]) float pairs, or a ValueError naming the bad entry."""
    if isinstance(bars, str | bytes) or not isinstance(bars, Sequence | np.ndarray):
        raise ValueError(f"bars must be a list of [z_bar, As] pairs (m, m^2/m), got {bars!r}")
    out = []
    for i, entry in enumerate(bars):
        if isinstance(entry, str | bytes) or np.ndim(entry) != 1 or len(entry) != 2:
            raise ValueError(
                f"bars[{i}] must be a pair [z_bar, As] (height of the bar centroid above the bottom face "
                f"[m], bar area per unit width [m^2/m]), got {entry!r}"
            )
        try:
            z, a = float(entry[0]), float(entry[1])
        except (TypeError, ValueError):
            raise ValueError(f"bars[{i}] must hold two numbers [z_bar, As], got {entry!r}") from None
        if not (np.isfinite(z) and np.isfinite(a)):
            raise ValueError(f"bars[{i}] must hold finite numbers [z_bar, As], got {entry!r}")
        out.append((z, a))
    return out


def rc_section(
    depth: float,
    bars: Sequence[tuple[float, float]],
    concrete: tuple[int, ArrayLike],
    steel: tuple[int, ArrayLike] | Sequence[tuple[int, ArrayLike]],
    n_concrete: int | Sequence[int] = 9,
    z_ref: float | None = None,
) -> Section:
    """A reinforced-concrete section: concrete layers with smeared bar layers between them.

    Parameters
    ----------
    depth : section depth [m]
    bars : list of ``(z_bar, As)``: height of the bar centroid above the bottom face [m] and bar area per
        unit width [m^2/m]; the bar layer has thickness ``As`` centred on ``z_bar`` (equivalent thickness)
    concrete : ``(kind, params)`` of the concrete layers
    steel : ``(kind, params)`` of all bar layers, or a list with one ``(kind, params)`` per bar (unused
        without bars: ``bars=[]`` is a plain concrete section)
    n_concrete : total number of concrete layers (int, spread over the gaps between faces and bars in
        proportion to the gap thickness, at least one each) or a list with one count per gap, bottom up
    z_ref : reference surface height above the bottom face (default depth/2)

    Steel layers carry no shear. The concrete a bar layer occupies is not counted twice (layers are
    stacked), so the thicknesses add up to ``depth``.
    """
    if not depth > 0.0:
        raise ValueError(f"depth must be > 0, got {depth}")
    bars = sorted(_bar_entries(bars))
    if len(steel) == 2 and np.isscalar(steel[0]):  # one (kind, params) for all bars
        steel = [steel] * len(bars)
    if len(steel) != len(bars):
        raise ValueError(f"steel must be one (kind, params) or one per bar ({len(bars)}), got {len(steel)}")
    edges = [0.0]
    for z, a in bars:
        if not a > 0.0:
            raise ValueError(f"bar area per width As must be > 0, got {a}")
        lo, hi = z - 0.5 * a, z + 0.5 * a
        if lo <= edges[-1] or hi >= depth:
            raise ValueError(
                f"bar layer at z_bar={z} (thickness {a}) overlaps a face or another bar; "
                f"need 0 < z_bar - As/2 and z_bar + As/2 < depth={depth}"
            )
        edges += [lo, hi]
    edges.append(depth)
    gaps = np.array([edges[2 * i + 1] - edges[2 * i] for i in range(len(bars) + 1)])
    if np.isscalar(n_concrete):
        counts = _allocate(int(n_concrete), gaps)
    else:
        counts = np.asarray(n_concrete, int)
        if counts.shape != gaps.shape or np.any(counts < 1):
            raise ValueError(f"n_concrete per gap must be {len(gaps)} counts >= 1, got {n_concrete}")
    th, kinds, params, shear, labels = [], [], [], [], []
    for i, gap in enumerate(gaps):
        for _ in range(counts[i]):
            th.append(gap / counts[i])
            kinds.append(concrete[0])
            params.append(concrete[1])
            shear.append(True)
            labels.append("concrete")
        if i < len(bars):
            th.append(bars[i][1])
            kinds.append(steel[i][0])
            params.append(steel[i][1])
            shear.append(False)
            labels.append("steel")
    return layered(th, kinds, params, carries_shear=shear, z_ref=z_ref, labels=labels)


def paper_rc_section(
    depth: float,
    cover: float,
    as_bottom: float,
    as_top: float,
    concrete: tuple[int, ArrayLike],
    steel: tuple[int, ArrayLike] | Sequence[tuple[int, ArrayLike]],
    n_concrete: int = 9,
) -> Section:
    """The paper's doubly reinforced section (§9.2): bars at ``cover`` (to the bar centroid) from each face;
    with the default 9 concrete layers (1 + 7 + 1) there are 11 layers, steel in layers 2 and 10."""
    return rc_section(
        depth,
        [(cover, as_bottom), (depth - cover, as_top)],
        concrete,
        steel,
        n_concrete=[1, n_concrete - 2, 1] if n_concrete >= 3 else n_concrete,
    )


def with_crack_spacing_band(
    section: Section, bar_diameter: float, tension_stiffening: str = "all"
) -> tuple[Section, list]:
    """Copy of an RC ``section`` whose concrete layers get the crack band width ls = s_r,max of *fib* Model
    Code 2010 (``ssi.materials.rc.crack_spacing_mc2010``): one band per crack, so that a band dissipates Gf
    per crack whatever the element size (chapter 08).

    The bars nearest each face set that face's spacing: concrete layers below mid-depth take the spacing of
    the lowest bar layer, layers above that of the topmost one; a face with no bar layer in its half of the
    depth takes the other face's spacing. Per face: c = clear cover to the bar surface, d = depth to the bar
    centroid from the opposite face, As = the bar layer's equivalent thickness (per unit width), alpha_e = Es
    / E0. ``tension_stiffening``: "all" keeps every concrete layer's alpha_ts (the rule of chapter 03: every
    cracked layer stiffened); "effective_area" keeps it only in the layers whose mid-depth lies within the
    effective tension depth h_c,ef (the same MC2010 / EC2 7.3.2 value, min(2.5 (h - d), (h - x)/3, h/2)) of a
    face that has its own bars, where bond transfers stress from the bars into the concrete between cracks;
    the other concrete layers soften to zero as plain concrete (alpha_ts = 0). Returns ``(section, spacings)``
    with one ``crack_spacing_mc2010`` dict per face used (bottom, top)."""
    from ..materials.concrete import P_E0
    from ..materials.layer_laws import CONCRETE, STEEL
    from ..materials.rc import _positive, crack_spacing_mc2010, with_crack_band

    phi = _positive("bar_diameter", bar_diameter)
    bars = np.flatnonzero(section.kind == STEEL)
    conc = np.flatnonzero(section.kind == CONCRETE)
    if conc.size == 0:
        raise ValueError("with_crack_spacing_band: the section has no CONCRETE layer to give a crack band")
    if tension_stiffening not in ("all", "effective_area"):
        raise ValueError(f"tension_stiffening must be 'all' or 'effective_area', got {tension_stiffening!r}")
    _WARNED.clear()  # each build warns once per face
    if bars.size == 0:
        return _plain_concrete_band(section, conc)
    h = section.thickness
    z_mid_sec = 0.5 * (section.z_bottom + section.z_top)

    def bar_layer(side):
        """The bar layer of one half of the depth: the steel layers stacked next to the one nearest that face
        (a bar layer split into thinner layers, e.g. by a layer-count refinement, counts as one), as
        (area per width As [m], centroid height)."""
        order = bars if side == "bottom" else bars[::-1]
        group = [order[0]]
        for b in order[1:]:
            if (
                abs(section.z_mid[b] - section.z_mid[group[-1]])
                > 0.5 * (section.h[b] + section.h[group[-1]]) + 1e-12
            ):
                break
            group.append(b)
        area = float(section.h[group].sum())
        return area, float(np.dot(section.h[group], section.z_mid[group]) / area), group[0]

    def spacing(side):
        area, z_bar, bar = bar_layer(side)
        cover = (z_bar - section.z_bottom) if side == "bottom" else (section.z_top - z_bar)
        alpha_e = section.params[bar, 0] / section.params[conc[0], P_E0]
        return crack_spacing_mc2010(cover - 0.5 * phi, phi, area, 1.0, h, h - cover, alpha_e)

    bottom = spacing("bottom") if section.z_mid[bars[0]] < z_mid_sec else None
    top = spacing("top") if section.z_mid[bars[-1]] >= z_mid_sec else None
    faces = [bottom or top, top or bottom]
    from ..materials.concrete import P_ALPHA_TS

    params = section.params.copy()
    for n in conc:
        face = faces[0] if section.z_mid[n] < z_mid_sec else faces[1]
        prm = _regularised(section.params[n], face["s_r_max"], "bottom" if face is faces[0] else "top")
        params[n, : len(section.params[n])] = with_crack_band(prm, face["s_r_max"])
        if tension_stiffening == "effective_area":
            near_bottom = bottom is not None and section.z_mid[n] - section.z_bottom <= bottom["h_c_ef"]
            near_top = top is not None and section.z_top - section.z_mid[n] <= top["h_c_ef"]
            if not (near_bottom or near_top):
                params[n, P_ALPHA_TS] = 0.0
    from dataclasses import replace

    return replace(section, params=params), faces


# Hinge width of a plain concrete beam's flexural crack, as a fraction of the depth: Ulfkjaer, Krenk &
# Brincker (1995), "Analytical model for fictitious crack propagation in concrete beams", J. Eng. Mech.
# 121(1), s = h/2.
PLAIN_HINGE_FRACTION = 0.5


class PlainConcreteWarning(UserWarning):
    """A concrete section without reinforcement: its cracking is brittle (the cracking moment is its peak)."""


_WARNED: list = []


def _warn_once(message: str, category: type) -> None:
    """Warn ``message`` unless it was just warned for another layer of the same section build."""
    import warnings

    if message not in _WARNED:
        warnings.warn(message, category, stacklevel=5)
    _WARNED.append(message)


def _regularised(params: np.ndarray, ls: float, where: str) -> np.ndarray:
    """Copy of a CONCRETE vector whose tensile strength is lowered (``ssi.materials.rc.
    regularised_tensile_strength``) if the band ``ls`` [m] would snap back or soften steeper than the margin
    allows; warns (``CrackBandWarning``) saying what was done and why."""

    from ..materials.concrete import P_E0, P_FR, P_GF
    from ..materials.rc import (
        SNAP_BACK_MARGIN,
        CrackBandWarning,
        regularised_tensile_strength,
        snap_back_limit,
    )

    p = np.array(params, dtype=np.float64)
    E0, Gf, fr = p[P_E0], p[P_GF], p[P_FR]
    fr_band = regularised_tensile_strength(E0, Gf, fr, ls)
    if fr_band < fr:
        limit = snap_back_limit(E0, Gf, fr)
        _warn_once(
            f"crack band of the {where} face: ls = {ls:.4g} m (the crack spacing s_r,max) is "
            f"{ls / limit:.3g} times the snap-back limit 2*E0*Gf/fr**2 = {limit:.4g} m of eq. (5.4) "
            f"(allowed: {SNAP_BACK_MARGIN}); the band's tensile strength is lowered from "
            f"fr = {fr / 1e6:.4g} to {fr_band / 1e6:.4g} MPa so that its softening still dissipates "
            f"Gf = {Gf:.4g} N/m without "
            "snapping back (crack band regularisation of Bazant & Oh); the strip cracks at a moment lower "
            f"by about {100 * (1 - fr_band / fr):.0f} %",
            CrackBandWarning,
        )
        p[P_FR] = fr_band
    return p


def _plain_concrete_band(section: Section, conc: np.ndarray) -> tuple[Section, list]:
    """The crack band of a section without bars: one flexural crack, whose fracture zone spans a hinge of
    width h/2 (``PLAIN_HINGE_FRACTION``), no tension stiffening (nothing bonds to the concrete); the band
    regularised like a reinforced one if that width would snap back. Warns that the cracking is brittle."""
    import warnings
    from dataclasses import replace

    from ..materials.concrete import P_ALPHA_TS
    from ..materials.rc import with_crack_band

    ls = PLAIN_HINGE_FRACTION * section.thickness
    params = section.params.copy()
    for n in conc:
        prm = _regularised(section.params[n], ls, "plain")
        prm[P_ALPHA_TS] = 0.0
        params[n, : len(section.params[n])] = with_crack_band(prm, ls)
    warnings.warn(
        "plain concrete section (no bars): its cracking is brittle -- the cracking moment is its peak "
        f"moment and the crack opens with no reinforcement to hold it; crack band ls = h/2 = {ls:.4g} m (the "
        "flexural hinge width of Ulfkjaer, Krenk & Brincker 1995), no tension stiffening",
        PlainConcreteWarning,
        stacklevel=3,
    )
    return replace(section, params=params), [{"s_r_max": ls, "plain": True}]
