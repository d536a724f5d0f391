"""Python side of the reinforced-concrete laws: validated parameter vectors and designer defaults.

The numba kernels (``concrete``, ``steel``) trust their input; everything a user can get wrong is
checked here and reported as a ``ValueError`` naming the parameter and its allowed range.

Designer values from the compressive strength alone (:func:`designer_concrete`), all from one source,
the *fib* Model Code 2010 (§5.1), with fc read as the mean cylinder strength fcm [Pa]:

* E0 = Eci = 21.5 GPa (fcm / 10 MPa)^(1/3)                         (MC2010 eq. 5.1-21, alpha_E = 1)
* fr = fctm = 0.30 (fcm - 8 MPa)^(2/3) MPa  (fck = fcm - 8 MPa <= 50 MPa)  (MC2010 eq. 5.1-3a)
* Gf = 73 fcm^0.18 N/m                                              (MC2010 eq. 5.1-9)
* eps_c = 2 fc / E0: the peak strain that makes eq. (5.1) the curve whose secant at the peak is E0/2
  (a = E0 eps_c / fc = 2); smaller eps_c would bend the curve above its initial tangent (a < 2).
* eps_cu = 0.0035 (MC2010/EC2 ultimate strain in bending).
* Gc = 8.8 sqrt(fcm / MPa) N/mm: compressive fracture energy of Nakamura & Higai (2001), "Compressive fracture
  energy and fracture zone length of concrete", JSCE/ASCE seminar on post-peak behavior of RC structures
  (MC2010 gives none); it regularises crushing beyond eps_cu (``ssi.materials.concrete``).
"""

import math

import numpy as np

from .concrete import N_CONCRETE_PARAMS
from .layer_laws import CONCRETE, ELASTIC, STEEL
from .steel import N_STEEL_PARAMS

MPA = 1.0e6


def _positive(name, value):
    value = float(value)
    if not (value > 0.0 and math.isfinite(value)):
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    return value


def snap_back_limit(E0: float, Gf: float, fr: float) -> float:
    """Largest crack band width 2 E0 Gf / fr^2 for which eq. (5.4) gives a softening (negative) modulus."""
    return 2.0 * E0 * Gf / (fr * fr)


def check_crack_band(ls, E0: float, Gf: float, fr: float) -> None:
    """Raise ValueError unless every crack band width in ``ls`` satisfies 0 < ls < 2 E0 Gf / fr^2."""
    ls = np.atleast_1d(np.asarray(ls, dtype=np.float64))
    limit = snap_back_limit(E0, Gf, fr)
    if np.any(~np.isfinite(ls)) or np.any(ls <= 0.0):
        raise ValueError(f"crack band width ls must be positive, got min ls = {ls.min()!r} m")
    if np.any(ls >= limit):
        raise ValueError(
            f"crack band width ls = {ls.max():.6g} m is too large: eq. (5.4) snaps back unless "
            f"ls < 2*E0*Gf/fr**2 = {limit:.6g} m (E0 = {E0:.6g} Pa, Gf = {Gf:.6g} N/m, fr = {fr:.6g} Pa); "
            "refine the mesh or raise Gf"
        )


# Largest ls / (2 E0 Gf / fr^2) a band keeps before its tensile strength is lowered (regularise_band): the
# softening modulus of eq. (5.4) is then at most 1 / (1/0.8 - 1) = 4 times E0 in magnitude.
SNAP_BACK_MARGIN = 0.8


class CrackBandWarning(UserWarning):
    """A concrete band's tensile strength was lowered so that eq. (5.4) keeps Gf without snapping back."""


def regularised_tensile_strength(
    E0: float, Gf: float, fr: float, ls: float, margin: float = SNAP_BACK_MARGIN
):
    """Tensile strength [Pa] of a crack band of width ``ls`` [m] that keeps the fracture energy ``Gf`` [N/m]
    with a softening line (eq. 5.4) no steeper than the ``margin`` allows (Bazant & Oh 1983, "Crack band
    theory for fracture of concrete", Materiaux et Constructions 16: for bands too wide to soften, lower the
    strength, not the energy).

    The triangle under the softening line of eq. (5.4) has the area fr eps_u / 2 = Gf / ls whatever fr is, so
    a band dissipates Gf per unit area with any strength; the line snaps back (eps_u < fr / E0) once
    ls >= 2 E0 Gf / fr^2. Returns min(fr, sqrt(margin 2 E0 Gf / ls)): fr itself while ls <= margin times the
    snap-back limit, else the strength at which ls is exactly that fraction of the limit."""
    for name, v in (("E0", E0), ("Gf", Gf), ("fr", fr), ("ls", ls)):
        _positive(name, v)
    if not 0.0 < margin < 1.0:
        raise ValueError(f"margin must be in (0, 1), got {margin!r}")
    return min(float(fr), math.sqrt(margin * 2.0 * E0 * Gf / ls))


def designer_concrete(fc: float) -> dict:
    """Designer values of E0, fr, Gf, eps_c, eps_cu from the mean compressive strength ``fc`` [Pa]
    (fib Model Code 2010; see the module docstring)."""
    fc = _positive("fc", fc)
    fcm = fc / MPA
    if not 8.0 < fcm <= 58.0:
        raise ValueError(f"fc must be within (8, 58] MPa for the MC2010 designer formulas, got {fcm} MPa")
    E0 = 21.5e3 * (fcm / 10.0) ** (1.0 / 3.0) * MPA
    return {
        "E0": E0,
        "fr": 0.30 * (fcm - 8.0) ** (2.0 / 3.0) * MPA,
        "Gf": 73.0 * fcm**0.18,
        "eps_c": 2.0 * fc / E0,
        "eps_cu": 0.0035,
        "Gc": 8.8e3 * math.sqrt(fcm),
    }


def concrete_params(
    fc,
    E0,
    eps_c,
    fr,
    Gf,
    ls,
    eps_y,
    *,
    eps_cu=0.0035,
    nu=0.2,
    alpha_ts=0.5,
    beta0=0.25,
    beta_floor=1e-4,
    Gc=None,
    plane_strain=False,
) -> np.ndarray:
    """Validated CONCRETE parameter vector (N_CONCRETE_PARAMS,), SI units (Pa, m, N/m).

    ``ls`` is the crack band width of eq. (5.4) (the length the integration point represents);
    ``eps_y`` the yield strain fy/Es of the reinforcement crossing the crack (tension stiffening and
    shear retention vanish there). ``alpha_ts`` = 0 turns tension stiffening off. ``Gc``: compressive fracture
    energy beyond eps_cu [N/m] (None: the designer value 8.8 sqrt(fc / MPa) N/mm of Nakamura & Higai; 0: the
    stress cliff at eps_cu). ``plane_strain``: the axial law uses E0 / (1 - nu^2) (a layer of a plane-strain
    strip, eq. 4.4); False: uniaxial (a beam). Scenes set it for their foundation
    (``Foundation.plane_strain``).
    """
    fc = _positive("fc", fc)
    E0 = _positive("E0", E0)
    eps_c = _positive("eps_c", eps_c)
    fr = _positive("fr", fr)
    Gf = _positive("Gf", Gf)
    eps_cu = _positive("eps_cu", eps_cu)
    eps_y = _positive("eps_y", eps_y)
    a = E0 * eps_c / fc
    if a < 2.0 - 1e-12:
        raise ValueError(
            f"E0*eps_c/fc must be >= 2 (eq. 5.1 would rise above its initial tangent and the "
            f"irreversible strain turn negative), got E0*eps_c/fc = {a:.6g}; raise eps_c to "
            f">= 2*fc/E0 = {2 * fc / E0:.6g}"
        )
    if eps_cu <= eps_c:
        raise ValueError(f"eps_cu must exceed eps_c = {eps_c:.6g}, got {eps_cu:.6g}")
    if fr >= fc:
        raise ValueError(f"fr must be below fc = {fc:.6g} Pa, got {fr:.6g} Pa")
    check_crack_band(ls, E0, Gf, fr)
    if eps_y <= fr / E0:
        raise ValueError(f"eps_y must exceed the cracking strain fr/E0 = {fr / E0:.6g}, got {eps_y:.6g}")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu must be in (-1, 0.5), got {nu!r}")
    if not 0.0 <= alpha_ts <= 1.0:
        raise ValueError(f"alpha_ts must be in [0, 1], got {alpha_ts!r}")
    if not 0.0 < beta0 <= 1.0:
        raise ValueError(f"beta0 must be in (0, 1], got {beta0!r}")
    if not 0.0 < beta_floor <= beta0:
        raise ValueError(f"beta_floor must be in (0, beta0 = {beta0}], got {beta_floor!r}")
    Gc = 8.8e3 * math.sqrt(fc / MPA) if Gc is None else float(Gc)
    if not (Gc >= 0.0 and math.isfinite(Gc)):
        raise ValueError(f"Gc must be a finite number >= 0 N/m (0: no crushing energy), got {Gc!r}")
    p = np.array(
        [
            E0,
            nu,
            fc,
            eps_c,
            eps_cu,
            fr,
            Gf,
            float(ls),
            alpha_ts,
            eps_y,
            beta0,
            beta_floor,
            Gc,
            1.0 if plane_strain else 0.0,
        ]
    )
    assert p.size == N_CONCRETE_PARAMS
    return p


def steel_params(fy, Es=200.0e9, EH=0.0) -> np.ndarray:
    """Validated STEEL parameter vector [Es, 0, fy, EH]; 0 <= EH < Es (EH = 0: no hardening)."""
    fy = _positive("fy", fy)
    Es = _positive("Es", Es)
    EH = float(EH)
    if not (0.0 <= EH < Es):
        raise ValueError(
            f"EH must be in [0, Es = {Es:.6g}) Pa, got {EH!r} (a negative hardening modulus "
            "would soften the bars)"
        )
    p = np.array([Es, 0.0, fy, EH])
    assert p.size == N_STEEL_PARAMS
    return p


def elastic_params(E, nu) -> np.ndarray:
    """Validated ELASTIC parameter vector [E, nu]."""
    E = _positive("E", E)
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu must be in (-1, 0.5), got {nu!r}")
    return np.array([E, float(nu)])


def with_plane_strain(params, plane_strain: bool = True) -> np.ndarray:
    """Copy of a CONCRETE vector with the plane-strain flag set (True) or cleared (False)."""
    from .concrete import P_PLANE

    p = np.array(params, dtype=np.float64)
    p[P_PLANE] = 1.0 if plane_strain else 0.0
    return p


def with_crack_band(params, ls) -> np.ndarray:
    """Copy of a CONCRETE vector with the crack band width replaced by ``ls`` (validated)."""
    from .concrete import P_E0, P_FR, P_GF, P_LS

    p = np.array(params, dtype=np.float64)
    check_crack_band(ls, p[P_E0], p[P_GF], p[P_FR])
    p[P_LS] = float(ls)
    return p


KINDS = {"elastic": ELASTIC, "concrete": CONCRETE, "steel": STEEL}


def drive(kind: int, params, eps_path, gam_path=None, tangent: int = 1):
    """Drive one layer point along a strain path, committing the history after every step.

    Returns ``(sig, tau, e_t, g_t, hist)`` with shapes (n,), (n,), (n,), (n,), (n, N_LAYER_HIST).
    """
    from .layer_laws import N_LAYER_HIST, layer_update

    eps_path = np.asarray(eps_path, dtype=np.float64)
    gam_path = np.zeros_like(eps_path) if gam_path is None else np.asarray(gam_path, dtype=np.float64)
    params = np.asarray(params, dtype=np.float64)
    n = eps_path.size
    out = np.zeros((4, n))
    hist = np.zeros((n, N_LAYER_HIST))
    h_old = np.zeros(N_LAYER_HIST)
    h_new = np.zeros(N_LAYER_HIST)
    for i in range(n):
        out[:, i] = layer_update(kind, params, eps_path[i], gam_path[i], h_old, h_new, tangent)
        h_old[:] = h_new
        hist[i] = h_new
    return out[0], out[1], out[2], out[3], hist


def crack_spacing_mc2010(
    c: float, phi: float, As: float, b: float, h: float, d: float, alpha_e: float
) -> dict:
    """Maximum crack spacing of stabilised cracking, *fib* Model Code 2010 §7.6.4.4, eq. (7.6-4):

        s_r,max = 2 l_s,max,   l_s,max = k c + (1/4) (f_ctm / tau_bms) phi / rho_s,ef,

    with k = 1 and the mean bond stress tau_bms = 1.8 f_ctm (short-term loading, Table 7.6-2), so
    l_s,max = c + phi / (7.2 rho_s,ef). rho_s,ef = As / (b h_c,ef), h_c,ef = min(2.5 (h - d), (h - x)/3, h/2)
    (MC2010 Fig. 7.6-4), x the neutral-axis depth of the cracked elastic section in pure bending,
    x = d alpha_e rho (sqrt(1 + 2 / (alpha_e rho)) - 1), rho = As / (b d), alpha_e = Es / E0.

    c: clear cover to the bar surface, phi: bar diameter, As: bar area over the width b, h: depth, d:
    effective depth [m]. Returns a dict with ``s_r_max``, ``l_s_max``, ``h_c_ef``, ``rho_s_ef``, ``x``. Used
    as the crack band width of a reinforced strip (one band per crack; chapter 08)."""
    for name, v in (("c", c), ("phi", phi), ("As", As), ("b", b), ("h", h), ("d", d), ("alpha_e", alpha_e)):
        _positive(name, v)
    if not d < h:
        raise ValueError(f"d must be below h = {h}, got {d}")
    rho = As / (b * d)
    ar = alpha_e * rho
    x = d * ar * (math.sqrt(1.0 + 2.0 / ar) - 1.0)
    h_c_ef = min(2.5 * (h - d), (h - x) / 3.0, 0.5 * h)
    rho_ef = As / (b * h_c_ef)
    l_s_max = c + phi / (7.2 * rho_ef)
    return {"s_r_max": 2.0 * l_s_max, "l_s_max": l_s_max, "h_c_ef": h_c_ef, "rho_s_ef": rho_ef, "x": x}
