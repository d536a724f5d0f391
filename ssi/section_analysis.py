"""Strain-compatibility section analysis and the curvature-integral deflection of a determinate beam.

This is the *independent* reference for the nonlinear layered strip (chapter 08, Fig. 12): it uses the
same layer laws (``ssi.materials.layer_laws.layer_update``) and the same layers (``ssi.section.Section``)
but none of the element code. Plane sections remain plane,

    eps(z) = eps0 - z kap,      N = sum h_n sig_n = 0 (no axial force in a simply supported beam),
    M = -sum h_n z_n sig_n + sum e_n h_n^3/12 kap      (sagging positive, per unit width),

the second term being the within-layer bending with the layer's initial (e_n = e0_n) or tangent modulus,
the same discrete section model as the plate strip's ``self_bending`` option (see ``ssi.elements.plate``).
The curvature is raised monotonically in small steps; at each step eps0 solves N = 0 (Newton on A = dN/deps0, bisection if Newton stalls) and
the layer histories are committed, so the section follows the same loading path as a section of the
beam whose moment grows monotonically. The shear stiffness of the section in that state is
S = kappa_s sum_{shear layers} g_t,n h_n (cracked layers with their shear retention beta).

For a statically determinate beam the deflection follows from virtual work without any element:

    delta = int kap(M(x)) mbar(x) dx + int gam(x) vbar(x) dx,   gam = V / S(M(x)),

with (mbar, vbar) the moment and shear of a unit load at the point where delta is wanted. This is only
valid while kap(M) is single-valued, i.e. while the section's M(kap) rises monotonically: once it
softens, deformation localises in one section and the integral no longer describes the beam.

Shapes: kap, M, eps0, S are (n_steps + 1,) arrays, row 0 the unloaded section.
"""

from dataclasses import dataclass

import numpy as np

from .materials.concrete import P_LS
from .materials.layer_laws import CONCRETE, N_LAYER_HIST, layer_update
from .section import Section

__all__ = [
    "MomentCurvature",
    "four_point_deflection",
    "four_point_deflection_elastic",
    "moment_curvature",
    "section_state",
]


def _params(section: Section, ls):
    prm = np.array(section.params, dtype=np.float64)
    if ls is not None:
        prm[section.kind == CONCRETE, P_LS] = float(ls)
    return prm


def section_state(section: Section, params, eps0, kap, hist_old, kappa_s=5.0 / 6.0, self_bending="initial"):
    """Resultants of the section at (eps0, kap) from the committed layer histories ``hist_old``.

    ``self_bending``: modulus of each layer's own bending term h^3/12 kap -- "initial" (e0, the plate
    strip's default), "tangent" (the law's tangent, the strip's other option) or "none" (pure midpoint rule).
    Returns ``(N, M, A, S, hist_new)``: axial force, moment, dN/deps0, shear stiffness (per unit width),
    and the new histories (n_layer, N_LAYER_HIST)."""
    e0, _ = section.initial_moduli()
    hist_new = np.empty_like(hist_old)
    N = M = A = S = 0.0
    for n in range(section.n_layer):
        z, h = section.z_mid[n], section.h[n]
        sig, _, e_t, g_t = layer_update(section.kind[n], params[n], eps0 - z * kap, 0.0, hist_old[n],
                                        hist_new[n], 1)
        e_self = e0[n] if self_bending == "initial" else (e_t if self_bending == "tangent" else 0.0)
        N += h * sig
        M += -h * z * sig + e_self * h**3 / 12.0 * kap
        A += h * e_t
        if section.carries_shear[n]:
            S += kappa_s * h * g_t
    return N, M, A, S, hist_new


def _solve_eps0(section, params, kap, hist, guess, n_scale, kappa_s, sb):
    """eps0 with N(eps0, kap) = 0 for the committed ``hist``: Newton, then bisection as a fallback."""
    tol = 1e-11 * n_scale
    x = guess
    for _ in range(60):
        N, M, A, S, hn = section_state(section, params, x, kap, hist, kappa_s, sb)
        if abs(N) <= tol:
            return x, M, S, hn
        if A <= 0.0:
            break
        x = x - N / A
    # bracket and bisect (N rises with eps0 wherever the section still has stiffness)
    lo, hi = guess - 1e-3, guess + 1e-3
    while section_state(section, params, lo, kap, hist, kappa_s, sb)[0] > 0.0:
        lo -= 2.0 * (hi - lo)
    while section_state(section, params, hi, kap, hist, kappa_s, sb)[0] < 0.0:
        hi += 2.0 * (hi - lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        N, M, A, S, hn = section_state(section, params, mid, kap, hist, kappa_s, sb)
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


def moment_curvature(section: Section, kap_max: float, n_steps: int = 2000, ls=None, kappa_s=5.0 / 6.0,
                     self_bending="initial"):
    """Trace M(kap) of ``section`` for kap = 0 .. kap_max in ``n_steps`` equal steps (N = 0).

    ``ls``: crack band width given to every CONCRETE layer (None: as in the section's params);
    ``self_bending``: as in :func:`section_state` (match the strip's option)."""
    if self_bending not in ("initial", "tangent", "none"):
        raise ValueError(f"self_bending must be 'initial', 'tangent' or 'none', got {self_bending!r}")
    if not kap_max > 0.0 or int(n_steps) < 2:
        raise ValueError(f"need kap_max > 0 and n_steps >= 2, got {kap_max}, {n_steps}")
    params = _params(section, ls)
    from .materials.layer_laws import STEEL
    steel = np.flatnonzero(section.kind == STEEL)
    e0, _ = section.initial_moduli()
    n_scale = float(np.sum(e0 * section.h)) * 1e-3
    kaps = np.linspace(0.0, kap_max, int(n_steps) + 1)
    hist = np.zeros((section.n_layer, N_LAYER_HIST))
    M = np.zeros_like(kaps)
    eps0 = np.zeros_like(kaps)
    S = np.zeros_like(kaps)
    _, M[0], _, S[0], _ = section_state(section, params, 0.0, 0.0, hist, kappa_s, self_bending)
    first_yield = None
    for i in range(1, kaps.size):
        eps0[i], M[i], S[i], hist = _solve_eps0(section, params, kaps[i], hist, eps0[i - 1], n_scale, kappa_s,
                                               self_bending)
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
