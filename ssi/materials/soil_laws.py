"""Soil constitutive laws at one integration point (plane strain).

Vectors: strain ``eps = [exx, ezz, gxz, eyy]`` (engineering shear, eyy the out-of-plane strain, zero in
plane strain), stress ``sig = [sxx, szz, txz, syy]``, tension positive. ``D`` is (4, 4) in that order.

Law kinds (``kind``) and their parameter vectors ``params`` (one row per material; rows of different
kinds are padded to ``N_SOIL_PARAMS`` by :func:`material_table`):

* ``ELASTIC`` (0): [E, nu].
* ``MOHR_COULOMB`` (1): implicit return mapping in principal stresses (plane, edges, apex) with its
  consistent tangent — ``[E, nu, c, phi, psi, n_sub, drift, 0]`` from :func:`mohr_coulomb_params`.
* ``MOHR_COULOMB_EXPLICIT`` (2): the paper's tangent scheme Δσ = D_ep Δε (eq. 6.9), optional sub-stepping
  (n_sub) and drift correction (drift = 1); same parameter vector.
* ``VON_MISES`` (3): [E, nu, cu], f = sqrt(J2) - cu (the law of Smith & Griffiths' Program 6.1).

History (``N_SOIL_HIST`` = 2): [accumulated plastic strain norm, branch of the last update
(0 elastic, 1 plane, 2 edge s1 = s2, 3 edge s2 = s3, 4 apex)].

:class:`SoilLayer` (re-exported by ``ssi.scene``) is the one description of a horizontal soil layer -- its
law, weight and at-rest state -- that the scene, the rigid footing and :func:`geostatic_stress` all take.

Numba's on-disk cache keys a kernel on its own file only, but the element kernels inline these laws;
``import ssi`` therefore keys the whole cache on a hash of all package sources (``ssi/__init__.py``), so an
edit of this file recompiles ``q8_kernel`` too and nothing stale runs.
"""

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..core.protocol import CONSISTENT
from ..core.validate import (
    check_bool,
    check_choice,
    check_instance,
    check_int,
    check_optional_real,
    check_real,
)
from .mc_explicit_scheme import mc_explicit
from .mc_implicit_scheme import N_MC_WORK_ROWS, mc_implicit
from .mc_surface import N_MC_CONSTANTS, mc_material_constants
from .principal import elastic_fill, lame
from .von_mises import vm_implicit

ELASTIC = 0
MOHR_COULOMB = 1
MOHR_COULOMB_EXPLICIT = 2
VON_MISES = 3
N_SOIL_HIST = 2  # history variables per integration point (laws may use fewer)
# the history slots the laws write, by name: accumulated plastic strain norm sum |d eps_p| [-], and the
# branch of the last stress update (0 elastic, 1 plane, 2 edge s1 = s2, 3 edge s2 = s3, 4 apex)
H_PLASTIC_STRAIN, H_BRANCH = 0, 1
SOIL_HIST_NAMES = ("plastic_strain", "branch")
N_SOIL_PARAMS = 8  # width of a padded parameter row
KIND_NAMES = {
    ELASTIC: "elastic",
    MOHR_COULOMB: "mohr_coulomb",
    MOHR_COULOMB_EXPLICIT: "mohr_coulomb_explicit",
    VON_MISES: "von_mises",
}


def davis_beta(phi_deg: float, psi_deg: float) -> float:
    """Davis' (1968) factor beta = cos psi cos phi / (1 - sin psi sin phi) (dimensionless; 1 for psi = phi):
    the associated material with c* = beta c, tan phi* = beta tan phi bounds the capacity of the
    non-associated one (phi, psi in degrees). The one definition in the package: the limit analysis
    (``ssi.limit``) and the solver's Davis mode (``Settings(flow="davis")``) both use it."""
    phi, psi = math.radians(phi_deg), math.radians(psi_deg)
    return math.cos(psi) * math.cos(phi) / (1.0 - math.sin(psi) * math.sin(phi))


def davis_soil_row(row: np.ndarray) -> np.ndarray:
    """A Mohr-Coulomb parameter row [E, nu, c, phi, psi, ...] (angles in rad) made associated with Davis'
    reduced c*, phi* (psi* = phi*); a new array, ``row`` is not touched."""
    out = row.copy()
    beta = davis_beta(math.degrees(row[3]), math.degrees(row[4]))
    out[2] = beta * row[2]
    out[3] = out[4] = math.atan(beta * math.tan(row[3]))
    return out


@njit(cache=True)
def elastic_matrix(E, nu, D):
    """Fill ``D`` (4, 4) with the isotropic linear-elastic matrix in the [xx, zz, xz, yy] order."""
    lam, mu = lame(E, nu)
    elastic_fill(lam, mu, D)


@njit(cache=True)
def law_constants_of(kind, params, out):
    """Fill ``out`` (N_MC_CONSTANTS,) with the constants a law of ``kind`` shares over all points of one
    material (left alone for a law that has none)."""
    if kind == MOHR_COULOMB:
        mc_material_constants(params, out)


@njit(cache=True)
def law_constants(kinds, params):
    """(n_mat, N_MC_CONSTANTS): :func:`law_constants_of` per material (the ``constants`` row of
    :func:`soil_update_among`; zeros for a law that has none)."""
    out = np.zeros((kinds.shape[0], N_MC_CONSTANTS))
    for i in range(kinds.shape[0]):
        law_constants_of(kinds[i], params[i], out[i])
    return out


@njit(cache=True, inline="always")
def soil_update_among(
    has_mc,
    has_mc_explicit,
    has_vm,
    kind,
    params,
    constants,
    deps,
    sig_old,
    hist_old,
    sig_new,
    hist_new,
    D,
    tangent,
    work,
    iwork,
):
    """:func:`soil_update` restricted to the laws flagged ``has_*`` (a kind not flagged is taken as ELASTIC);
    ``constants`` is the material's row of :func:`law_constants`, ``work`` (N_MC_WORK_ROWS, 4) float and
    ``iwork`` (3,) int the caller's scratch.

    Inlined into its caller: where the flags are compile-time constants (the law-specialised kernels of
    ``ssi.elements.soil_q8.q8_kernel_for``), numba drops the branches of the laws not flagged before typing
    them, so a scene compiles only the laws its materials use."""
    if has_mc and kind == MOHR_COULOMB:
        return mc_implicit(constants, deps, sig_old, hist_old, sig_new, hist_new, D, tangent, work, iwork)
    if has_mc_explicit and kind == MOHR_COULOMB_EXPLICIT:
        return mc_explicit(params, deps, sig_old, hist_old, sig_new, hist_new, D, tangent)
    if has_vm and kind == VON_MISES:
        return vm_implicit(params, deps, sig_old, hist_old, sig_new, hist_new, D, tangent, work)
    elastic_matrix(params[0], params[1], D)
    for i in range(4):
        s = sig_old[i]
        for j in range(4):
            s += D[i, j] * deps[j]
        sig_new[i] = s
    for i in range(hist_old.size):  # a loop, not hist_new[:] = hist_old (see layer_update)
        hist_new[i] = hist_old[i]
    return 0


@njit(cache=True)
def soil_update(kind, params, deps, sig_old, hist_old, sig_new, hist_new, D, tangent):
    """Update the stress of one point for the strain increment ``deps``; return a status code.

    Writes ``sig_new`` (4,), ``hist_new`` (N_SOIL_HIST,) and ``D`` (4, 4): the elastic matrix when
    ``tangent == K0_MATRIX`` (0, :mod:`ssi.core.protocol`), else the consistent tangent. Status 0 = elastic, 1
    = plastic, < 0 = failure.
    """
    constants = np.zeros(N_MC_CONSTANTS)
    law_constants_of(kind, params, constants)
    work, iwork = np.empty((N_MC_WORK_ROWS, 4)), np.empty(3, np.int64)
    return soil_update_among(
        True,
        True,
        True,
        kind,
        params,
        constants,
        deps,
        sig_old,
        hist_old,
        sig_new,
        hist_new,
        D,
        tangent,
        work,
        iwork,
    )


def laws_used(kinds) -> tuple[bool, bool, bool]:
    """The ``has_*`` flags of :func:`soil_update_among` for a material table's ``kinds``."""
    present = {int(k) for k in np.atleast_1d(kinds)}
    return MOHR_COULOMB in present, MOHR_COULOMB_EXPLICIT in present, VON_MISES in present


# ---------------------------------------------------------------------------------------------------------
# validating parameter builders (plain Python)
# ---------------------------------------------------------------------------------------------------------
def _check_elastic(E, nu):
    if not (np.isfinite(E) and E > 0.0):
        raise ValueError(f"E must be > 0 (Young's modulus, Pa), got {E}")
    if not (-1.0 < nu < 0.5):
        raise ValueError(f"nu must lie in (-1, 0.5) (Poisson's ratio), got {nu}")


def elastic_params(E, nu):
    """Parameter row of the ELASTIC law, padded to N_SOIL_PARAMS."""
    _check_elastic(E, nu)
    row = np.zeros(N_SOIL_PARAMS)
    row[:2] = E, nu
    return row


def mohr_coulomb_params(E, nu, c, phi_deg, psi_deg=None, scheme="implicit", n_sub=1, drift=False):
    """Return ``(kind, params)`` of a Mohr–Coulomb soil.

    Parameters
    ----------
    E, nu : Young's modulus [Pa] (> 0) and Poisson's ratio (-1 < nu < 0.5)
    c : cohesion [Pa] (>= 0)
    phi_deg : friction angle [deg], 0 <= phi < 90; c and phi may not both be zero
    psi_deg : dilation angle [deg], 0 <= psi <= phi (None: psi = phi, associated flow -- this law-level
        default serves the material-point checks; a :class:`SoilLayer` left without psi_deg has psi = 0)
    scheme : "implicit" (return mapping, default of this code) or "explicit" (the paper's Δσ = D_ep Δε)
    n_sub : sub-steps of the explicit scheme (>= 1; paper: 1)
    drift : drift correction of the explicit scheme (paper: False)
    """
    _check_elastic(E, nu)
    if not (np.isfinite(c) and c >= 0.0):
        raise ValueError(f"c must be >= 0 (cohesion, Pa), got {c}")
    if not (0.0 <= phi_deg < 90.0):
        raise ValueError(f"phi_deg must lie in [0, 90) (friction angle, degrees), got {phi_deg}")
    psi_deg = phi_deg if psi_deg is None else psi_deg
    if not (0.0 <= psi_deg <= phi_deg):
        raise ValueError(
            f"psi_deg must lie in [0, phi_deg] = [0, {phi_deg}] (dilation angle, degrees), got {psi_deg}"
        )
    if c == 0.0 and phi_deg == 0.0:
        raise ValueError(
            "c and phi_deg are both zero: the soil would have no strength (need c > 0 or phi > 0)"
        )
    if scheme not in ("implicit", "explicit"):
        raise ValueError(f"scheme must be 'implicit' or 'explicit', got {scheme!r}")
    if int(n_sub) != n_sub or n_sub < 1:
        raise ValueError(f"n_sub must be an integer >= 1 (explicit sub-steps), got {n_sub}")
    row = np.zeros(N_SOIL_PARAMS)
    row[:7] = E, nu, c, math.radians(phi_deg), math.radians(psi_deg), n_sub, 1.0 if drift else 0.0
    return (MOHR_COULOMB if scheme == "implicit" else MOHR_COULOMB_EXPLICIT), row


def von_mises_params(E, nu, cu):
    """Return ``(VON_MISES, params)``: f = sqrt(J2) - cu (cu > 0, the undrained shear strength)."""
    _check_elastic(E, nu)
    if not (np.isfinite(cu) and cu > 0.0):
        raise ValueError(f"cu must be > 0 (undrained shear strength, Pa), got {cu}")
    row = np.zeros(N_SOIL_PARAMS)
    row[:3] = E, nu, cu
    return VON_MISES, row


def material_table(materials):
    """Stack ``[(kind, params), ...]`` into ``(kinds (n_mat,), params (n_mat, N_SOIL_PARAMS))`` for SoilQ8."""
    kinds = np.array([int(k) for k, _ in materials], np.int64)
    table = np.zeros((len(materials), N_SOIL_PARAMS))
    for i, (_, p) in enumerate(materials):
        p = np.asarray(p, np.float64)
        table[i, : len(p)] = p
    return kinds, table


# ---------------------------------------------------------------------------------------------------------
# a soil layer: the material of a horizontal layer, its weight and its at-rest state
# ---------------------------------------------------------------------------------------------------------
DRAINAGE = ("drained", "undrained_A")


@dataclass(frozen=True)
class SoilLayer:
    """One horizontal soil layer. ``c=None``: linear elastic; else Mohr--Coulomb with c, phi, psi.

    Fields: ``thickness`` [m]; ``E`` Young's modulus [Pa] (drained, or undrained E_u); ``nu`` Poisson's ratio
    [-]; ``unit_weight`` [N/m^3] (bulk, above the water table); ``c`` cohesion [Pa] (s_u for undrained clay)
    or None (elastic); ``phi_deg`` friction angle [deg]; ``psi_deg`` dilation angle [deg], 0 <= psi <= phi,
    **default 0** (flow without volume change, PLAXIS's default too): a real soil dilates far less than
    associated flow says, and psi = phi overstates a footing's capacity (a user's push-over came out 18 %
    higher than with psi = 0, issue 31) -- so leaving it out errs on the safe side; ``None`` means associated
    flow psi = phi (what a comparison with an exact associated solution such as Prandtl's needs, though
    ``psi_deg=phi_deg`` says it plainer); ``K0`` ratio [-] of the
    horizontal to the vertical initial effective stress (default 1 - sin phi, Jaky's at-rest value of a soil
    consolidated under its own weight; a weightless layer under a surcharge is in equilibrium with any
    uniform stress, and K0 = 1 makes it isotropic); ``scheme`` "implicit" or "explicit" stress update, with
    ``n_sub`` sub-steps [-] and ``drift`` correction for "explicit" (see :func:`mohr_coulomb_params`);
    ``unit_weight_sat`` [N/m^3] below the water table (default ``unit_weight``); ``drainage`` "drained" or
    "undrained_A" (effective-stress undrained: E, nu, c, phi are the drained parameters and the pore water
    adds a bulk modulus K_w/n = K_u - K' chosen so that the undrained Poisson's ratio is ``nu_u`` [-]; the
    excess pore pressure is ``BuiltScene.excess_pore_pressure``).
    """

    thickness: float
    E: float
    nu: float
    unit_weight: float = 0.0
    c: float | None = None
    phi_deg: float = 0.0
    psi_deg: float | None = 0.0  # psi = 0 unless given (not phi: see the docstring); None: associated
    K0: float | None = None
    scheme: str = "implicit"
    unit_weight_sat: float | None = None
    drainage: str = "drained"
    nu_u: float = 0.495
    n_sub: int = 1
    drift: bool = False

    def k_water(self) -> float:
        """K_w/n [Pa] of the pore water: 0 if drained; else :meth:`undrained_k_water`."""
        if self.drainage == "drained":
            return 0.0
        if self.drainage != "undrained_A":
            raise ValueError(f"drainage must be 'drained' or 'undrained_A', got {self.drainage!r}")
        return self.undrained_k_water()

    def undrained_k_water(self) -> float:
        """K_w/n [Pa] of the layer when undrained: K_u - K' with K_u the bulk modulus of the skeleton's shear
        modulus G at the undrained Poisson's ratio nu_u, K_u = 2G(1 + nu_u) / (3(1 - 2 nu_u))."""
        if not (self.nu < self.nu_u < 0.5):
            raise ValueError(
                f"SoilLayer.nu_u must lie in (nu, 0.5) = ({self.nu}, 0.5) for an undrained layer, got "
                f"{self.nu_u}"
            )
        shear = self.E / (2.0 * (1.0 + self.nu))
        k_skeleton = self.E / (3.0 * (1.0 - 2.0 * self.nu))
        return 2.0 * shear * (1.0 + self.nu_u) / (3.0 * (1.0 - 2.0 * self.nu_u)) - k_skeleton

    @classmethod
    def undrained(
        cls,
        thickness: float,
        E_u: float,
        s_u: float,
        unit_weight: float = 0.0,
        nu_u: float = 0.495,
        K0: float | None = None,
        unit_weight_sat: float | None = None,
    ) -> "SoilLayer":
        """Total-stress undrained clay (Tresca: phi = 0, c = s_u [Pa]) with the undrained modulus E_u [Pa] and
        nu_u close to 0.5 (nearly incompressible). phi = 0 makes the strength independent of the mean stress,
        so the hydrostatic pore pressure the scene separates does not change it. ``thickness`` [m], unit
        weights [N/m^3] as in :class:`SoilLayer`."""
        return cls(
            thickness,
            E=E_u,
            nu=nu_u,
            unit_weight=unit_weight,
            c=s_u,
            phi_deg=0.0,
            K0=K0,
            unit_weight_sat=unit_weight_sat,
        )

    def __post_init__(self):
        check_real("SoilLayer.thickness", self.thickness, lo=0.0, lo_open=True, unit="m")
        check_real("SoilLayer.E", self.E, lo=0.0, lo_open=True, unit="Pa")
        check_real("SoilLayer.nu", self.nu, lo=-1.0, hi=0.5, lo_open=True, hi_open=True)
        check_real("SoilLayer.unit_weight", self.unit_weight, lo=0.0, unit="N/m^3")
        check_optional_real("SoilLayer.c", self.c, lo=0.0, unit="Pa")
        check_real("SoilLayer.phi_deg", self.phi_deg, lo=0.0, hi=90.0, hi_open=True, unit="degrees")
        check_optional_real(
            "SoilLayer.psi_deg", self.psi_deg, lo=0.0, hi=self.phi_deg, unit="degrees (<= phi_deg)"
        )
        check_optional_real("SoilLayer.K0", self.K0, lo=0.0, hi=10.0, hi_open=True)
        check_choice("SoilLayer.scheme", self.scheme, ("implicit", "explicit"))
        check_int("SoilLayer.n_sub", self.n_sub, lo=1)
        check_bool("SoilLayer.drift", self.drift)
        check_optional_real("SoilLayer.unit_weight_sat", self.unit_weight_sat, lo=0.0, unit="N/m^3")
        check_choice("SoilLayer.drainage", self.drainage, DRAINAGE)
        # nu_u matters only where the layer is undrained: a drained layer (nu up to 0.5) keeps the default
        # nu_u unchecked against nu; a phase that makes it undrained meets undrained_k_water's check
        check_real("SoilLayer.nu_u", self.nu_u, lo=-1.0, hi=0.5, lo_open=True, hi_open=True)
        if self.drainage == "undrained_A":
            check_real(
                "SoilLayer.nu_u", self.nu_u, lo=self.nu, hi=0.5, lo_open=True, hi_open=True,
                unit="(nu < nu_u < 0.5)",
            )  # fmt: skip
        if self.c == 0.0 and self.phi_deg == 0.0:
            raise ValueError(
                "SoilLayer: c=0 and phi_deg=0 give a soil without strength; need c > 0 or "
                "phi_deg > 0 (or c=None for an elastic layer)"
            )

    def law(self) -> tuple[int, np.ndarray]:
        if self.c is None:
            return ELASTIC, elastic_params(self.E, self.nu)
        return mohr_coulomb_params(
            self.E,
            self.nu,
            self.c,
            self.phi_deg,
            self.psi_deg,
            scheme=self.scheme,
            n_sub=self.n_sub,
            drift=self.drift,
        )


# ---------------------------------------------------------------------------------------------------------
# geostatic initial stress
# ---------------------------------------------------------------------------------------------------------
def k0_jaky(phi_deg):
    """Jáky's at-rest coefficient K0 = 1 - sin φ (the default of paper-notes §7)."""
    return 1.0 - math.sin(math.radians(phi_deg))


GAMMA_W = 9.81e3  # unit weight of water [N/m^3]


def geostatic_stress(
    z,
    layers: list[SoilLayer],
    surcharge: float = 0.0,
    z_surface: float = 0.0,
    water_table: float | None = None,
    gamma_w: float = GAMMA_W,
) -> np.ndarray:
    """Geostatic (effective) stress [sxx, szz, txz, syy] (tension positive) at ``z`` (any shape, z upwards).

    Parameters
    ----------
    z : array of z coordinates of the points (e.g. ``SoilQ8.integration_points()[..., 1]``), <= z_surface
    layers : list of :class:`SoilLayer` from the surface down; used are ``thickness`` [m], ``unit_weight``
        [N/m^3], ``unit_weight_sat`` [N/m^3] (below the water table; None: ``unit_weight``) and ``K0`` (None:
        1 - sin φ from ``phi_deg``); the last layer extends downwards without limit
    surcharge : uniform vertical pressure on the surface [Pa] (>= 0, compression)
    z_surface : z of the ground surface [m]
    water_table : depth of the water table below the surface [m], or None (dry); negative: free water
        stands above the surface (ponding; it changes the pore pressure, not the effective stress)
    gamma_w : unit weight of water [N/m^3]

    Returns an array of shape ``z.shape + (4,)``: szz = -(surcharge + ∫ γ' dz) above the point with the
    effective unit weight γ' = γ above the table and γ_sat - γ_w below it, sxx = syy = K0 szz of the point's
    layer (K0 acts on effective stress), txz = 0. With hydrostatic pore pressure p = γ_w (depth - d_w) (see
    :func:`pore_pressure`) the total stress is sig - p [1, 1, 0, 1]. Equilibrium with the body force γ'
    holds exactly for piecewise-constant γ'.
    """
    z = np.asarray(z, np.float64)
    if surcharge < 0.0:
        raise ValueError(f"surcharge must be >= 0 (a compressive pressure, Pa), got {surcharge}")
    if not layers:
        raise ValueError("layers must list at least one layer")
    if np.any(z > z_surface + 1e-9):
        raise ValueError(f"all points must lie at or below the surface z = {z_surface}")
    if water_table is not None and not np.isfinite(water_table):
        raise ValueError(
            f"water_table must be a finite depth below the surface [m] or None, got {water_table}"
        )
    d_w = math.inf if water_table is None else float(water_table)
    depth = z_surface - z
    szz = np.full(z.shape, -float(surcharge))
    k0 = np.zeros(z.shape)
    top = 0.0
    for i, lay in enumerate(layers):
        # a SoilLayer has checked its own ranges (unit weights >= 0, thickness > 0, 0 <= K0 < 10)
        check_instance(f"layers[{i}]", lay, SoilLayer)
        gamma = float(lay.unit_weight)
        gamma_sat = float(gamma if lay.unit_weight_sat is None else lay.unit_weight_sat)
        if water_table is not None and gamma_sat < gamma_w:
            raise ValueError(
                f"layers[{i}].unit_weight_sat = {gamma_sat} N/m^3 is below the unit weight of water "
                f"{gamma_w}: the buoyant weight would be negative"
            )
        K0 = k0_jaky(lay.phi_deg) if lay.K0 is None else lay.K0
        last = i == len(layers) - 1
        t = math.inf if last else float(lay.thickness)
        inside = (depth >= top - 1e-12) & ((depth <= top + t) if last else (depth < top + t))
        # dry part of the layer above the table, buoyant part below it
        dry = np.clip(np.minimum(depth, d_w) - top, 0.0, t)
        wet = np.clip(depth - top, 0.0, t) - dry
        szz -= gamma * dry + (gamma_sat - gamma_w) * wet
        k0 = np.where(inside, K0, k0)
        top += t
    out = np.zeros(z.shape + (4,))
    out[..., 1] = szz
    out[..., 0] = k0 * szz
    out[..., 3] = k0 * szz
    return out


def pore_pressure(z, water_table=None, z_surface=0.0, gamma_w=GAMMA_W):
    """Hydrostatic pore pressure [Pa] (compression positive) at ``z``: γ_w (depth - d_w) below the water table
    at depth ``water_table`` [m] below ``z_surface`` (negative: the free water level above it), zero above it
    (and everywhere if None)."""
    z = np.asarray(z, np.float64)
    if water_table is None:
        return np.zeros(z.shape)
    return gamma_w * np.maximum(z_surface - water_table - z, 0.0)


# ---------------------------------------------------------------------------------------------------------
# material-point driver (plain Python; for tests and chapters)
# ---------------------------------------------------------------------------------------------------------
def drive(kind, params, deps_path, sig0=None, tangent=CONSISTENT):
    """Drive one point along strain increments ``deps_path`` (n, 4); return (sig (n+1, 4), hist (n+1, 2),
    status (n,), D (n, 4, 4)). Each increment is committed before the next (as the solver does)."""
    deps_path = np.atleast_2d(np.asarray(deps_path, np.float64))
    params = np.asarray(params, np.float64)
    n = len(deps_path)
    sig = np.zeros((n + 1, 4))
    if sig0 is not None:
        sig[0] = sig0
    hist = np.zeros((n + 1, N_SOIL_HIST))
    status = np.zeros(n, np.int64)
    Ds = np.zeros((n, 4, 4))
    for i in range(n):
        status[i] = soil_update(
            int(kind), params, deps_path[i], sig[i], hist[i], sig[i + 1], hist[i + 1], Ds[i], tangent
        )
    return sig, hist, status, Ds
