"""Strain-compatibility section analysis and the curvature-integral deflection of a determinate beam.

Two section analyses live here. :func:`moment_curvature` is the *discrete* section of the layered strip: the
same layer laws (``ssi.materials.layer_laws.layer_update``), the same layers
(``ssi.elements.section.Section``) and the same self-bending term, but none of the element code -- it checks
the element along the span. :func:`layer_free_moment_curvature` forgets the layers: it integrates the
continuous stress profile through the depth by adaptive quadrature, so it also sees the error of the layer
rule (chapter 02, row ``section_selfbending``; chapter 08, ``fig12_curvature_integral``). For the discrete
one: Plane sections remain plane,

    eps(z) = eps0 - z kap,      N = sum h_n sig_n = 0 (no axial force in a simply supported beam),
    M = -sum h_n z_n sig_n + sum e_n h_n^3/12 kap      (sagging positive, per unit width),

the second term being the within-layer bending with the layer's initial (e_n = e0_n) or tangent modulus,
the same discrete section model as the plate strip's ``self_bending`` option (see ``ssi.elements.plate``).
The curvature is raised monotonically in small steps; at each step eps0 solves N = 0 (Newton on A = dN/deps0,
bisection if Newton stalls) and the layer histories are committed, so the section follows the same loading
path as a section of the beam whose moment grows monotonically. The shear stiffness of the section in that
state is S = kappa_s sum_{shear layers} g_t,n h_n (cracked layers with their shear retention beta).

For a statically determinate beam the deflection follows from virtual work without any element:

    delta = int kap(M(x)) mbar(x) dx + int gam(x) vbar(x) dx,   gam = V / S(M(x)),

with (mbar, vbar) the moment and shear of a unit load at the point where delta is wanted. This is only
valid while kap(M) is single-valued, i.e. while the section's M(kap) rises monotonically: once it
softens, deformation localises in one section and the integral no longer describes the beam.

Shapes: kap, M, eps0, S are (n_steps + 1,) arrays, row 0 the unloaded section.
"""

from dataclasses import dataclass

import numpy as np
from numba import njit

from ..core.protocol import CONSISTENT
from ..materials.concrete import H_EMAX, H_XMAX, P_LS
from ..materials.layer_laws import CONCRETE, N_LAYER_HIST, layer_update
from .section import Section

__all__ = [
    "MomentCurvature",
    "four_point_deflection",
    "four_point_deflection_elastic",
    "layer_free_moment_curvature",
    "layer_free_resultants",
    "layer_free_state",
    "moment_curvature",
    "section_state",
]


def _params(section: Section, ls):
    prm = np.array(section.params, dtype=np.float64)
    if ls is not None:
        prm[section.kind == CONCRETE, P_LS] = float(ls)
    return prm


_SELF_BENDING = {"none": 0, "initial": 1, "tangent": 2, "chord": 3}


def section_state(section: Section, params, eps0, kap, hist_old, kappa_s=5.0 / 6.0, self_bending="chord"):
    """Resultants of the section at (eps0, kap) from the committed layer histories ``hist_old``.

    ``self_bending``: each layer's own bending term, as the plate strip's option -- "chord" (h^2/12 times the
    difference of the stresses at the layer's faces, the strip's default), "tangent" (e_t h^3/12 kap),
    "initial" (e0 h^3/12 kap) or "none" (pure midpoint rule).
    Returns ``(N, M, A, S, hist_new)``: axial force, moment, dN/deps0, shear stiffness (per unit width),
    and the new histories (n_layer, N_LAYER_HIST)."""
    if self_bending not in _SELF_BENDING:
        raise ValueError(f"self_bending must be one of {sorted(_SELF_BENDING)}, got {self_bending!r}")
    return _section_state(_Layers.of(section), params, eps0, kap, hist_old, kappa_s, self_bending)


@dataclass(frozen=True)
class _Layers:
    """The arrays of a section that :func:`_section_resultants` reads, with the initial moduli (computed once
    per analysis, not at each of its thousands of section states)."""

    z_mid: np.ndarray
    h: np.ndarray
    h_cubed: np.ndarray
    kind: np.ndarray
    carries_shear: np.ndarray
    e0: np.ndarray

    @classmethod
    def of(cls, section: Section) -> "_Layers":
        h = np.ascontiguousarray(section.h, np.float64)
        return cls(
            np.ascontiguousarray(section.z_mid, np.float64),
            h,
            h**3,
            np.ascontiguousarray(section.kind, np.int64),
            np.ascontiguousarray(section.carries_shear, np.bool_),
            section.initial_moduli()[0],
        )


def _section_state(layers: _Layers, params, eps0, kap, hist_old, kappa_s, self_bending):
    hist_new = np.empty_like(hist_old)
    N, M, A, S = _section_resultants(
        layers.z_mid, layers.h, layers.h_cubed, layers.kind, layers.carries_shear, layers.e0,
        np.ascontiguousarray(params, np.float64), float(eps0), float(kap), hist_old, hist_new,
        float(kappa_s), _SELF_BENDING[self_bending],
    )  # fmt: skip
    return N, M, A, S, hist_new


@njit(cache=True)
def _section_resultants(z_mid, h_all, h_cubed, kind, carries_shear, e0, params, eps0, kap, hist_old, hist_new,
                        kappa_s, self_bending):  # fmt: skip
    """The loop of :func:`section_state` (``self_bending`` 0 none, 1 initial, 2 tangent, 3 chord)."""
    scratch = np.empty(hist_old.shape[1])
    N = M = A = S = 0.0
    for n in range(z_mid.shape[0]):
        z, h = z_mid[n], h_all[n]
        sig, _, e_t, g_t = layer_update(kind[n], params[n], eps0 - z * kap, 0.0, hist_old[n], hist_new[n], 1)
        N += h * sig
        M += -h * z * sig
        if self_bending == 3:
            s_b = layer_update(kind[n], params[n], eps0 - (z - h / 2) * kap, 0.0, hist_old[n], scratch, 1)[0]
            s_t = layer_update(kind[n], params[n], eps0 - (z + h / 2) * kap, 0.0, hist_old[n], scratch, 1)[0]
            M += h * h / 12.0 * (s_b - s_t)
        else:
            e_self = e0[n] if self_bending == 1 else (e_t if self_bending == 2 else 0.0)
            M += e_self * h_cubed[n] / 12.0 * kap
        A += h * e_t
        if carries_shear[n]:
            S += kappa_s * h * g_t
    return N, M, A, S


def _solve_eps0(layers, params, kap, hist, guess, n_scale, kappa_s, sb):
    """eps0 with N(eps0, kap) = 0 for the committed ``hist``: Newton, then bisection as a fallback."""
    tol = 1e-11 * n_scale
    x = guess
    for _ in range(60):
        N, M, A, S, hn = _section_state(layers, params, x, kap, hist, kappa_s, sb)
        if abs(N) <= tol:
            return x, M, S, hn
        if A <= 0.0:
            break
        x = x - N / A
    # bracket and bisect (N rises with eps0 wherever the section still has stiffness)
    lo, hi = guess - 1e-3, guess + 1e-3
    while _section_state(layers, params, lo, kap, hist, kappa_s, sb)[0] > 0.0:
        lo -= 2.0 * (hi - lo)
    while _section_state(layers, params, hi, kap, hist, kappa_s, sb)[0] < 0.0:
        hi += 2.0 * (hi - lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        N, M, A, S, hn = _section_state(layers, params, mid, kap, hist, kappa_s, sb)
        if abs(N) <= tol or hi - lo < 1e-16:
            return mid, M, S, hn
        if N > 0.0:
            hi = mid
        else:
            lo = mid
    raise RuntimeError(f"section analysis: no eps0 with N = 0 at kap = {kap}")


@dataclass
class MomentCurvature:
    """Result of :func:`moment_curvature` (per unit width). ``monotone`` is the number of leading rows on
    which M rises strictly (kap(M) single-valued); ``first_yield`` the row where a steel layer first
    yields (or None)."""

    kap: np.ndarray
    M: np.ndarray
    eps0: np.ndarray
    S: np.ndarray
    monotone: int
    first_yield: int | None

    def M_limit(self):
        """Largest moment of the monotone (pre-softening) branch."""
        return float(self.M[self.monotone - 1])

    def curvature(self, M):
        """kap(M) on the monotone branch (linear interpolation); NaN beyond it."""
        m = self.M[: self.monotone]
        return np.interp(M, m, self.kap[: self.monotone], right=np.nan)

    def shear_stiffness(self, M):
        m = self.M[: self.monotone]
        return np.interp(M, m, self.S[: self.monotone], right=np.nan)


def moment_curvature(
    section: Section, kap_max: float, n_steps: int = 2000, ls=None, kappa_s=5.0 / 6.0, self_bending="chord"
):
    """Trace M(kap) of ``section`` for kap = 0 .. kap_max in ``n_steps`` equal steps (N = 0).

    ``ls``: crack band width given to every CONCRETE layer (None: as in the section's params);
    ``self_bending``: as in :func:`section_state` (match the strip's option)."""
    if self_bending not in ("initial", "tangent", "chord", "none"):
        raise ValueError(
            f"self_bending must be 'initial', 'tangent', 'chord' or 'none', got {self_bending!r}"
        )
    if not kap_max > 0.0 or int(n_steps) < 2:
        raise ValueError(f"need kap_max > 0 and n_steps >= 2, got {kap_max}, {n_steps}")
    params = _params(section, ls)
    from ..materials.layer_laws import STEEL

    steel = np.flatnonzero(section.kind == STEEL)
    e0, _ = section.initial_moduli()
    n_scale = float(np.sum(e0 * section.h)) * 1e-3
    kaps = np.linspace(0.0, kap_max, int(n_steps) + 1)
    hist = np.zeros((section.n_layer, N_LAYER_HIST))
    M = np.zeros_like(kaps)
    eps0 = np.zeros_like(kaps)
    S = np.zeros_like(kaps)
    layers = _Layers.of(section)
    _, M[0], _, S[0], _ = _section_state(layers, params, 0.0, 0.0, hist, kappa_s, self_bending)
    first_yield = None
    for i in range(1, kaps.size):
        eps0[i], M[i], S[i], hist = _solve_eps0(
            layers, params, kaps[i], hist, eps0[i - 1], n_scale, kappa_s, self_bending
        )
        if first_yield is None and steel.size and np.any(hist[steel, 0] != 0.0):
            first_yield = i
    rising = np.diff(M) > 0.0
    monotone = int(np.argmin(rising)) + 1 if not rising.all() else kaps.size
    return MomentCurvature(kap=kaps, M=M, eps0=eps0, S=S, monotone=monotone, first_yield=first_yield)


def four_point_deflection(mc: MomentCurvature, P, span: float, a: float, n_int: int = 4001):
    """Mid-span deflection (positive down) of a simply supported beam of ``span`` with two loads ``P``
    (per unit width) at distance ``a`` from the supports, by the curvature integral:

        delta = int_0^{L/2} kap(M(x)) x dx + int_0^a P / S(M(x)) dx,  M = P x (x < a), P a (a <= x <= L/2).

    Substituting m = P x in the shear span: int_0^a kap x dx = P^-2 int_0^{Pa} kap(m) m dm and
    int_0^a P/S dx = int_0^{Pa} dm / S(m). NaN where P a exceeds the monotone branch."""
    P = np.atleast_1d(np.asarray(P, np.float64))
    out = np.empty_like(P)
    for k, p in enumerate(P):
        if p == 0.0:
            out[k] = 0.0
            continue
        m_max = p * a
        if m_max > mc.M_limit():
            out[k] = np.nan
            continue
        # integrate on the table's own moments (kinks of kap(M) sit on table rows) plus a fine grid
        m_tab = mc.M[: mc.monotone]
        m = np.union1d(np.linspace(0.0, m_max, n_int), m_tab[m_tab < m_max])
        kap = mc.curvature(m)
        s = mc.shear_stiffness(m)
        bend_shear_span = np.trapezoid(kap * m, m) / p**2
        bend_middle = mc.curvature(m_max) * 0.5 * (0.25 * span**2 - a**2)
        shear = np.trapezoid(1.0 / s, m)
        out[k] = bend_shear_span + bend_middle + shear
    return out


def four_point_deflection_elastic(P, span, a, D, S):
    """Closed form (Timoshenko beam): delta = P a (3 L^2 - 4 a^2) / (24 D) + P a / S."""
    return P * a * (3.0 * span**2 - 4.0 * a**2) / (24.0 * D) + P * a / S


# ---- layer-free reference: the continuous stress profile integrated adaptively through the depth -----------
def _material_intervals(section: Section, params):
    """Merge neighbouring layers that share a law and its parameters into one continuous interval.

    Returns a list of ``(z_lo, z_hi, kind, params, carries_shear)``; the layering itself is forgotten."""
    out = []
    lo = section.z_mid - 0.5 * section.h
    hi = section.z_mid + 0.5 * section.h
    for n in range(section.n_layer):
        kind, prm, shear = int(section.kind[n]), np.array(params[n]), bool(section.carries_shear[n])
        if out and out[-1][2] == kind and out[-1][4] == shear and np.array_equal(out[-1][3], prm):
            out[-1] = (out[-1][0], float(hi[n]), kind, prm, shear)
        else:
            out.append((float(lo[n]), float(hi[n]), kind, prm, shear))
    return out


def _kink_strains(kind, prm):
    """Strains at which a law's monotonic envelope has a kink or a jump (breakpoints for quadrature)."""
    from ..materials.concrete import C_EPS_CD, C_EPS_R, C_EPS_U, P_EPS_CU, P_EPS_Y, concrete_constants
    from ..materials.layer_laws import STEEL

    if kind == CONCRETE:
        const = concrete_constants(prm)
        eps_r, eps_u = const[C_EPS_R], const[C_EPS_U]
        kinks = [eps_r, eps_u, prm[P_EPS_Y], -prm[P_EPS_CU], -const[C_EPS_CD]]
        return kinks + _softening_meets_stiffening(prm, eps_r, eps_u)
    if kind == STEEL:
        return [prm[2] / prm[0], -prm[2] / prm[0]]
    return []


def _softening_meets_stiffening(prm, eps_r, eps_u):
    """Strain where the softening line (eq. 5.4) meets the tension-stiffening line (the kink of their max)."""
    from ..materials.concrete import P_ALPHA_TS, P_EPS_Y

    eps_y, alpha = prm[P_EPS_Y], prm[P_ALPHA_TS]
    # fr (eps_u - e)/(eps_u - eps_r) = alpha fr (eps_y - e)/(eps_y - eps_r)
    a1, a2 = 1.0 / (eps_u - eps_r), alpha / (eps_y - eps_r)
    if abs(a1 - a2) < 1e-300:
        return []
    return [(eps_u * a1 - eps_y * a2) / (a1 - a2)]


@njit(cache=True)
def _envelope(kind, prm, eps):
    """Stress and shear modulus of a fibre loaded monotonically to ``eps`` (the law from a virgin history;
    the shear modulus with the crack or crushing state that strain leaves). Compiled: the adaptive
    quadrature of the layer-free section calls it some 10^5 times per moment-curvature trace."""
    h0 = np.zeros(N_LAYER_HIST)
    h1 = np.zeros(N_LAYER_HIST)
    sig = layer_update(kind, prm, eps, 0.0, h0, h1, CONSISTENT)[0]
    if kind == CONCRETE:
        h0[H_XMAX], h0[H_EMAX] = max(-eps, 0.0), max(eps, 0.0)
    g_t = layer_update(kind, prm, eps, 1.0, h0, h1, CONSISTENT)[3]
    return sig, g_t


def _fibre_stress(z, kind, prm, eps0, kap):
    return _envelope(kind, prm, eps0 - z * kap)[0]


def _fibre_moment(z, kind, prm, eps0, kap):
    return -z * _envelope(kind, prm, eps0 - z * kap)[0]


def _fibre_shear_modulus(z, kind, prm, eps0, kap):
    return _envelope(kind, prm, eps0 - z * kap)[1]


def _axial_force(eps0, section, kap, ls, kappa_s, N_target):
    return layer_free_resultants(section, eps0, kap, ls, kappa_s, 1e-9)[0] - N_target


def layer_free_state(section: Section, kap: float, N: float = 0.0, ls=None, kappa_s=5.0 / 6.0):
    """The layer-free section at curvature ``kap`` (either sign) carrying the axial force ``N`` (per unit
    width): Brent's method on N(eps0) between the all-compressed and the all-tensile strain planes, then
    :func:`layer_free_resultants`. Returns ``(eps0, M, S)``; raises ValueError if the section cannot carry
    N."""
    from scipy.optimize import brentq

    if kap == 0.0:
        raise ValueError("kap must be non-zero for layer_free_state (at kap = 0 the strain plane is uniform)")
    ends = (kap * section.z_bottom, kap * section.z_top)
    lo, hi = min(ends) - 1e-7, max(ends) + 1e-7
    f_lo = _axial_force(lo, section, kap, ls, kappa_s, N)
    f_hi = _axial_force(hi, section, kap, ls, kappa_s, N)
    if f_lo > 0.0 or f_hi < 0.0:
        raise ValueError(
            f"N = {N!r} N/m is outside what the section carries at kap = {kap!r} 1/m "
            f"([{f_lo + N:.6g}, {f_hi + N:.6g}] between the all-compressed and all-tensile planes)"
        )
    eps0 = brentq(
        _axial_force,
        lo,
        hi,
        args=(section, kap, ls, kappa_s, N),
        xtol=1e-15 + 1e-13 * (hi - lo),
        rtol=1e-12,
        maxiter=200,
    )
    _, M, S = layer_free_resultants(section, eps0, kap, ls, kappa_s)
    return eps0, M, S


def layer_free_resultants(
    section: Section, eps0: float, kap: float, ls=None, kappa_s=5.0 / 6.0, epsrel: float = 1e-10
):
    """N, M, S of the section at (eps0, kap) with every fibre loaded monotonically to its strain, by
    adaptive quadrature (``scipy.integrate.quad``) of the continuous stress profile sig(eps0 - z kap) over
    each material interval, with breakpoints where the strain crosses a kink of the law (cracking, end of
    softening and of tension stiffening, crushing, steel yield). No layers and no self-bending term: the
    reference the layered rule converges to. Returns ``(N, M, S)`` per unit width."""
    from scipy.integrate import quad

    params = _params(section, ls)
    N = M = S = 0.0
    for z_lo, z_hi, kind, prm, shear in _material_intervals(section, params):
        pts = []
        if kap != 0.0:
            pts = sorted(z for z in ((eps0 - e) / kap for e in _kink_strains(kind, prm)) if z_lo < z < z_hi)
        # absolute tolerance from the integrand's scale (a resultant near zero, e.g. N at the root, cannot be
        # met in relative terms)
        z_s = [z_lo, z_hi, *pts]
        scale = max(max(abs(_envelope(kind, prm, eps0 - z * kap)[0]) for z in z_s), 1.0) * (z_hi - z_lo)
        zmax = max(abs(z_lo), abs(z_hi))
        args = (kind, prm, eps0, kap)
        opts = {"points": pts or None, "limit": 400, "epsrel": epsrel, "args": args}
        N += quad(_fibre_stress, z_lo, z_hi, epsabs=epsrel * scale, **opts)[0]
        M += quad(_fibre_moment, z_lo, z_hi, epsabs=epsrel * scale * zmax, **opts)[0]
        if shear:
            g_scale = max(_envelope(kind, prm, 0.0)[1], 1.0) * (z_hi - z_lo)
            S += kappa_s * quad(_fibre_shear_modulus, z_lo, z_hi, epsabs=epsrel * g_scale, **opts)[0]
    return N, M, S


def layer_free_moment_curvature(section: Section, kaps, ls=None, kappa_s=5.0 / 6.0) -> MomentCurvature:
    """M(kap) with N = 0 from :func:`layer_free_resultants` at each curvature of ``kaps`` (increasing, >= 0).

    Each curvature is solved on its own (Brent's method on N(eps0) = 0 between the all-compressed and the
    all-tensile strain planes), so neither load steps nor layers enter. The monotonic-fibre assumption is
    exact for fibres whose strain grows in magnitude as kap grows; near the rising neutral axis a few fibres
    unload slightly from small compression, which the history-following analysis (:func:`moment_curvature`)
    keeps and this one does not (measured in chapter 02: below 1e-3 of M). ``first_yield``: first row with a
    steel fibre past fy/Es."""
    from ..materials.layer_laws import STEEL

    kaps = np.asarray(kaps, np.float64)
    if kaps.ndim != 1 or kaps.size < 2 or np.any(np.diff(kaps) <= 0.0) or kaps[0] < 0.0:
        raise ValueError("kaps must be an increasing 1-D array of curvatures >= 0 with at least 2 values")
    M = np.zeros_like(kaps)
    eps0 = np.zeros_like(kaps)
    S = np.zeros_like(kaps)
    steel = section.kind == STEEL
    faces = np.concatenate(
        [section.z_mid[steel] - 0.5 * section.h[steel], section.z_mid[steel] + 0.5 * section.h[steel]]
    )
    eps_y = section.params[steel, 2] / section.params[steel, 0] if steel.any() else np.zeros(0)
    first_yield = None
    for i, k in enumerate(kaps):
        if k == 0.0:
            M[i], S[i] = 0.0, layer_free_resultants(section, 0.0, 0.0, ls, kappa_s)[2]
            continue
        eps0[i], M[i], S[i] = layer_free_state(section, k, 0.0, ls, kappa_s)
        if first_yield is None and steel.any() and np.any(np.abs(eps0[i] - faces * k) >= np.tile(eps_y, 2)):
            first_yield = i
    rising = np.diff(M) > 0.0
    monotone = int(np.argmin(rising)) + 1 if not rising.all() else kaps.size
    return MomentCurvature(kap=kaps, M=M, eps0=eps0, S=S, monotone=monotone, first_yield=first_yield)
