"""The 8-node serendipity plane-strain soil element (paper §7, §10).

Reduced 2x2 Gauss integration is the paper's default (it removes volumetric locking as nu -> 0.5 and the
spurious mode it admits in a single element does not propagate in a mesh); 3x3 is the full-rule option.

State per integration point: ``[sxx, szz, txz, syy, hist...]`` (stress, tension positive, then the law's
history), shape (n_el, n_ip, 4 + N_SOIL_HIST). The law is applied incrementally: the stress increment comes
from the strain increment ``B du_el`` since the last converged state (paper §8, incremental formulation).
"""

import functools

import numpy as np
from numba import njit

from ..core.assembly import scatter_matrix
from ..core.protocol import FORCES_ONLY, K0_MATRIX, TANGENT_FLAGS, ElementGroup
from ..core.quadrature import gauss_2d
from ..core.shapes import serendipity8
from ..materials.mc_implicit_scheme import N_MC_WORK_ROWS
from ..materials.soil_laws import (
    MOHR_COULOMB,
    MOHR_COULOMB_EXPLICIT,
    N_SOIL_HIST,
    SOIL_HIST_NAMES,
    davis_soil_row,
    elastic_matrix,
    law_constants,
    laws_used,
    soil_update_among,
)
from .q8_elastic import q8_elastic_assemble, q8_elastic_stiffness

N_STRESS = 4
N_SOIL_STATE = N_STRESS + N_SOIL_HIST
STRESS_NAMES = ("sxx", "szz", "txz", "syy")
# the state's slots by name: the stress, then the law's history (names from ssi.materials.soil_laws)
SOIL_STATE_FIELDS = {name: i for i, name in enumerate(STRESS_NAMES + SOIL_HIST_NAMES)}


@njit(cache=True)
def _reference_derivatives(gp):
    """dN/d(xi, eta) (n_ip, 8, 2) at the points ``gp`` (n_ip, 2): computed once per call, not per element."""
    dn_ref = np.empty((gp.shape[0], 8, 2))
    for q in range(gp.shape[0]):
        _, dn = serendipity8(gp[q, 0], gp[q, 1])
        for a in range(8):  # loops, not dn_ref[q] = dn: no array-to-slice copy to compile
            dn_ref[q, a, 0] = dn[a, 0]
            dn_ref[q, a, 1] = dn[a, 1]
    return dn_ref


@njit(cache=True)
def _physical_gradients(xy, dn, dndx):
    """Fill dndx (8, 2) with physical shape-function gradients from the reference ones ``dn`` (8, 2);
    return det J."""
    j00 = j01 = j10 = j11 = 0.0
    for a in range(8):
        j00 += dn[a, 0] * xy[a, 0]
        j01 += dn[a, 0] * xy[a, 1]
        j10 += dn[a, 1] * xy[a, 0]
        j11 += dn[a, 1] * xy[a, 1]
    det = j00 * j11 - j01 * j10
    # one division, not sixteen; a degenerate element (det = 0) raises ZeroDivisionError here, as it did
    inv = 1.0 / det
    for a in range(8):
        dndx[a, 0] = (j11 * dn[a, 0] - j01 * dn[a, 1]) * inv
        dndx[a, 1] = (-j10 * dn[a, 0] + j00 * dn[a, 1]) * inv
    return det


@njit(cache=True)
def _shape_gradients(xy, xi, eta, dndx):
    """Fill dndx (8, 2) with physical shape-function gradients at (xi, eta); return N (8,) and det J."""
    n, dn = serendipity8(xi, eta)
    return n, _physical_gradients(xy, dn, dndx)


@njit(cache=True)
def _blend_with_trial(params, tau, deps, sig_old, sig, D, d_elastic, with_tangent):
    """Duvaut--Lions at one point: the stress ``sig`` and tangent ``D`` of the inviscid return become
    (elastic trial + tau inviscid) / (1 + tau), in place; the history stays the inviscid return's. Every
    soil law's params start with (E, nu). Done per point in the kernel: a second, elastic pass over all
    elements cost ~11 % of a viscous path (measured on the zoo's limit scenes)."""
    elastic_matrix(params[0], params[1], d_elastic)
    w = 1.0 / (1.0 + tau)
    for i in range(N_STRESS):
        trial = sig_old[i]
        for j in range(N_STRESS):
            trial += d_elastic[i, j] * deps[j]
        sig[i] = (trial + tau * sig[i]) * w
    if with_tangent:
        for i in range(N_STRESS):
            for j in range(N_STRESS):
                D[i, j] = (d_elastic[i, j] + tau * D[i, j]) * w


@functools.cache
def q8_kernel_for(has_mc=True, has_mc_explicit=True, has_vm=True):
    """The Q8 kernel compiled for the soil laws flagged (see ``soil_update_among``; ELASTIC always): a scene
    compiles only the laws its materials use -- all four laws take ~11 s to compile, an elastic-only
    kernel a fraction of that. Each specialisation is a closure over its flags, which numba caches on disk
    under a key that includes them."""

    # The loop over elements and points. Without the explicit Mohr-Coulomb law it is compiled without
    # numba's reference counting: the elastic, implicit Mohr-Coulomb and von Mises updates allocate nothing
    # (the scratch comes from ``kernel``), and the counts numba kept for the array arguments of the inlined
    # law update (an atomic increment and decrement each, per point) were half of the Mohr-Coulomb kernel's
    # time (measured: 225 -> 98 ns per point, forces only). The explicit law (the paper's scheme, an option)
    # allocates per point, which needs the runtime; numba compiles the functions a loop calls with the loop's
    # own setting, so a law that allocates must never be reached from a loop without it.
    @njit(cache=True, _nrt=has_mc_explicit)
    def points(
        coords, du_el, el_mat, kinds, params, gp, gw, state_old, state_new, f_el, k_el, tangent, tau,
        dndx, deps, sig, hist, D, sig_old, hist_old, xy, d_elastic, db, dn_ref, constants, work, iwork,
    ):  # fmt: skip
        n_el = coords.shape[0]
        n_ip = gp.shape[0]
        failures = 0
        for e in range(n_el):
            for i in range(16):
                f_el[e, i] = 0.0
            if tangent != FORCES_ONLY:
                k_el[e, :, :] = 0.0
            m = el_mat[e]
            for a in range(8):
                xy[a, 0] = coords[e, a, 0]
                xy[a, 1] = coords[e, a, 1]
            for q in range(n_ip):
                det = _physical_gradients(xy, dn_ref[q], dndx)
                if det <= 0.0:
                    failures += 1
                    continue
                wdet = gw[q] * det
                exx = ezz = gxz = 0.0
                for a in range(8):
                    du = du_el[e, 2 * a]
                    dw = du_el[e, 2 * a + 1]
                    exx += dndx[a, 0] * du
                    ezz += dndx[a, 1] * dw
                    gxz += dndx[a, 1] * du + dndx[a, 0] * dw
                deps[0] = exx
                deps[1] = ezz
                deps[2] = gxz
                for i in range(N_STRESS):
                    sig_old[i] = state_old[e, q, i]
                for i in range(N_SOIL_HIST):
                    hist_old[i] = state_old[e, q, N_STRESS + i]
                status = soil_update_among(
                    has_mc,
                    has_mc_explicit,
                    has_vm,
                    kinds[m],
                    params[m],
                    constants[m],
                    deps,
                    sig_old,
                    hist_old,
                    sig,
                    hist,
                    D,
                    K0_MATRIX if tangent == FORCES_ONLY else tangent,
                    work,
                    iwork,
                )
                if status < 0:
                    failures += 1
                if tau > 0.0:
                    _blend_with_trial(
                        params[m], tau, deps, sig_old, sig, D, d_elastic, tangent != FORCES_ONLY
                    )
                for i in range(N_STRESS):
                    state_new[e, q, i] = sig[i]
                for i in range(N_SOIL_HIST):
                    state_new[e, q, N_STRESS + i] = hist[i]
                for a in range(8):
                    bx = dndx[a, 0]
                    bz = dndx[a, 1]
                    # B_a^T sigma for rows (exx, ezz, gxz): u-row (bx, 0, bz), w-row (0, bz, bx)
                    f_el[e, 2 * a] += (bx * sig[0] + bz * sig[2]) * wdet
                    f_el[e, 2 * a + 1] += (bz * sig[1] + bx * sig[2]) * wdet
                if tangent == FORCES_ONLY:  # modified Newton: the matrix is K0, kept factorised
                    continue
                # D B_b for both columns of each node b, once per point (not once per node pair a, b):
                # columns u_b -> strain (cx, 0, cz); w_b -> strain (0, cz, cx)
                for b in range(8):
                    cx = dndx[b, 0]
                    cz = dndx[b, 1]
                    db[b, 0] = D[0, 0] * cx + D[0, 2] * cz
                    db[b, 1] = D[1, 0] * cx + D[1, 2] * cz
                    db[b, 2] = D[2, 0] * cx + D[2, 2] * cz
                    db[b, 3] = D[0, 1] * cz + D[0, 2] * cx
                    db[b, 4] = D[1, 1] * cz + D[1, 2] * cx
                    db[b, 5] = D[2, 1] * cz + D[2, 2] * cx
                # then B_a^T (D B_b)
                for a in range(8):
                    bx = dndx[a, 0]
                    bz = dndx[a, 1]
                    for b in range(8):
                        du0, du1, du2 = db[b, 0], db[b, 1], db[b, 2]
                        dw0, dw1, dw2 = db[b, 3], db[b, 4], db[b, 5]
                        k_el[e, 2 * a, 2 * b] += (bx * du0 + bz * du2) * wdet
                        k_el[e, 2 * a, 2 * b + 1] += (bx * dw0 + bz * dw2) * wdet
                        k_el[e, 2 * a + 1, 2 * b] += (bz * du1 + bx * du2) * wdet
                        k_el[e, 2 * a + 1, 2 * b + 1] += (bz * dw1 + bx * dw2) * wdet
        return failures

    def kernel(coords, du_el, el_mat, kinds, params, gp, gw, state_old, state_new, f_el, k_el, tangent, tau):
        """Internal forces and stiffness of all Q8 elements; returns the number of points that failed.

        coords (n_el, 8, 2); du_el (n_el, 16); el_mat (n_el,) material index into kinds (n_mat,), params
        (n_mat, n_par); gp (n_ip, 2), gw (n_ip,); state_old/state_new (n_el, n_ip, N_SOIL_STATE);
        f_el (n_el, 16), k_el (n_el, 16, 16) are overwritten (k_el is left alone when tangent is
        FORCES_ONLY); tau >= 0 the Duvaut--Lions viscosity (see :class:`SoilQ8`; 0: rate independent).

        Plain Python around the compiled loop: it allocates the loop's scratch (fresh per call, so that
        threads may share a kernel). A compiled wrapper calling ``points`` would hold that closure as a
        constant, which numba's cache cannot key: it was compiled again in every process (0.5 s of the
        README scene's 1.7 s) and added an entry to the cache at each run.
        """
        return points(
            coords, du_el, el_mat, kinds, params, gp, gw, state_old, state_new, f_el, k_el, tangent, tau,
            np.empty((8, 2)),  # dndx
            np.zeros(4),  # deps
            np.empty(4),  # sig
            np.empty(N_SOIL_HIST),  # hist
            np.empty((4, 4)),  # D
            np.empty(4),  # sig_old: the point's committed state, copied (no views built per point)
            np.empty(N_SOIL_HIST),  # hist_old
            np.empty((8, 2)),  # xy
            np.empty((4, 4)),  # d_elastic
            np.empty((8, 6)),  # db: D B_b of each node b at the current point
            _reference_derivatives(gp),  # dn_ref
            law_constants(kinds, params),  # constants
            np.empty((N_MC_WORK_ROWS, 4)),  # work
            np.empty(3, np.int64),  # iwork
        )  # fmt: skip

    return kernel


q8_kernel = q8_kernel_for()  # every law (any material table)


@njit(cache=True)
def q8_pore_water(coords, u_el, el_mat, k_water, gp, gw, f_el, k_el, with_matrix):
    """Add the pore water of an undrained ("undrained A") layer: excess pore pressure p = -K_w/n eps_v(u)
    (compression positive) from the total volumetric strain since the start, so the total stress is
    sig' - p m. ``f_el`` (n_el, 16) += int B^T m (K_w/n) eps_v, ``k_el`` (n_el, 16, 16) += int B^T m m^T B
    (K_w/n) when ``with_matrix``; ``k_water`` (n_mat,) is K_w/n [Pa] (0: drained, nothing added)."""
    dndx = np.empty((8, 2))
    dn_ref = _reference_derivatives(gp)
    for e in range(coords.shape[0]):
        kw = k_water[el_mat[e]]
        if kw == 0.0:
            continue
        for q in range(gp.shape[0]):
            det = _physical_gradients(coords[e], dn_ref[q], dndx)
            wdet = gw[q] * det * kw
            ev = 0.0
            for a in range(8):
                ev += dndx[a, 0] * u_el[e, 2 * a] + dndx[a, 1] * u_el[e, 2 * a + 1]
            for a in range(8):
                f_el[e, 2 * a] += dndx[a, 0] * ev * wdet
                f_el[e, 2 * a + 1] += dndx[a, 1] * ev * wdet
                if with_matrix:
                    for b in range(8):
                        for i in range(2):
                            for j in range(2):
                                k_el[e, 2 * a + i, 2 * b + j] += dndx[a, i] * dndx[b, j] * wdet


@njit(cache=True)
def q8_volumetric_strain(coords, u_el, gp, out):
    """Volumetric strain eps_v = exx + ezz (n_el, n_ip) at the integration points from total u_el."""
    dndx = np.empty((8, 2))
    dn_ref = _reference_derivatives(gp)
    for e in range(coords.shape[0]):
        for q in range(gp.shape[0]):
            _physical_gradients(coords[e], dn_ref[q], dndx)
            ev = 0.0
            for a in range(8):
                ev += dndx[a, 0] * u_el[e, 2 * a] + dndx[a, 1] * u_el[e, 2 * a + 1]
            out[e, q] = ev


@njit(cache=True)
def q8_body_force(coords, el_mat, unit_weight, gp, gw, f_el):
    """Equivalent nodal forces of the self-weight (unit weight per material, acting in -z)."""
    dndx = np.empty((8, 2))
    for e in range(coords.shape[0]):
        f_el[e, :] = 0.0
        for q in range(gp.shape[0]):
            n, det = _shape_gradients(coords[e], gp[q, 0], gp[q, 1], dndx)
            for a in range(8):
                f_el[e, 2 * a + 1] -= n[a] * unit_weight[el_mat[e]] * gw[q] * det


@njit(cache=True)
def q8_points(coords, gp, out):
    """Physical (x, z) of the integration points, out (n_el, n_ip, 2)."""
    for e in range(coords.shape[0]):
        for q in range(gp.shape[0]):
            n, _ = serendipity8(gp[q, 0], gp[q, 1])
            out[e, q, 0] = 0.0
            out[e, q, 1] = 0.0
            for a in range(8):
                out[e, q, 0] += n[a] * coords[e, a, 0]
                out[e, q, 1] += n[a] * coords[e, a, 1]


class SoilQ8(ElementGroup):
    """A group of 8-node plane-strain soil elements.

    Parameters
    ----------
    coords : (n_el, 8, 2) nodal coordinates, node order of ``ssi.core.shapes.serendipity8``
    edofs : (n_el, 16) global DOFs (u, w per node)
    el_mat : (n_el,) material index of each element
    kinds : (n_mat,) law kinds of ``ssi.materials.soil_laws``
    params : (n_mat, n_par) law parameters
    n_gauss : 2 (reduced, paper default) or 3 (full)
    unit_weight : (n_mat,) unit weight gamma [N/m^3] for the self-weight body force, or None
    initial_stress : (n_el, n_ip, 4) initial (e.g. geostatic) stress, or None for a stress-free start
    k_water : (n_mat,) K_w/n [Pa] of undrained ("undrained A") materials, 0 for drained ones, or None: the
        state holds the effective stress, the pore water adds p = -K_w/n eps_v (see :func:`q8_pore_water`)
    viscosity : Duvaut--Lions regularisation tau = dt / eta per increment (dimensionless; 0: rate
        independent). The stress of an increment is (sigma_trial + tau sigma_inviscid) / (1 + tau), and so
        are the forces and the tangent: the overstress of the elastic trial over the rate-independent return
        decays by 1 / (1 + tau) per increment, so repeating an increment at fixed load (relaxation) recovers
        the rate-independent state where one exists. It restores a solution to increments that have none
        nearby without it (non-associated flow, psi < phi), at the price of a rate-dependent path.
    """

    name = "soil_q8"
    forces_only = True  # accepts the FORCES_ONLY flag
    viscous = True
    history_fields = SOIL_STATE_FIELDS
    point_code_names = ("elastic", "plastic")

    def __init__(
        self,
        coords,
        edofs,
        el_mat,
        kinds,
        params,
        n_gauss=2,
        unit_weight=None,
        initial_stress=None,
        k_water=None,
        viscosity=0.0,
    ):
        self.coords = np.ascontiguousarray(coords, np.float64)
        self.edofs = np.ascontiguousarray(edofs, np.int64)
        n_el = self.coords.shape[0]
        if self.coords.shape != (n_el, 8, 2) or self.edofs.shape != (n_el, 16):
            raise ValueError("coords must be (n_el, 8, 2) and edofs (n_el, 16)")
        if n_gauss not in (2, 3):
            raise ValueError(f"n_gauss must be 2 (reduced) or 3 (full), got {n_gauss}")
        self.el_mat = np.ascontiguousarray(np.broadcast_to(el_mat, (n_el,)), np.int64)
        self.kinds = np.ascontiguousarray(np.atleast_1d(kinds), np.int64)
        self.params = np.ascontiguousarray(np.atleast_2d(params), np.float64)
        if self.el_mat.max(initial=0) >= len(self.kinds) or len(self.kinds) != len(self.params):
            raise ValueError("el_mat must index kinds/params, which need one row per material")
        self.n_gauss = n_gauss
        self.gp, self.gw = gauss_2d(n_gauss)
        self.unit_weight = None if unit_weight is None else np.asarray(unit_weight, np.float64)
        self.initial_stress = initial_stress
        self.k_water = None
        if k_water is not None:
            kw = np.ascontiguousarray(np.broadcast_to(np.asarray(k_water, np.float64), (len(self.kinds),)))
            if np.any(~(kw >= 0.0)) or not np.all(np.isfinite(kw)):
                raise ValueError(f"k_water must be finite and >= 0 (K_w/n, Pa), got {kw}")
            self.k_water = kw if kw.any() else None
        if not (np.isfinite(viscosity) and viscosity >= 0.0):
            raise ValueError(
                f"viscosity must be finite and >= 0 (tau = dt/eta per increment), got {viscosity}"
            )
        self.viscosity = float(viscosity)
        self._phase = None  # see configure()

    @property
    def n_el(self):
        return self.coords.shape[0]

    @property
    def kernel(self):
        """The Q8 kernel specialised to this group's soil laws (compiled, or loaded, on first use)."""
        return q8_kernel_for(*laws_used(self.kinds))

    def initial_state(self):
        state = np.zeros((self.n_el, len(self.gw), N_SOIL_STATE))
        if self.initial_stress is not None:
            state[:, :, :N_STRESS] = self.initial_stress
        return state

    # ---- phases (ssi.scene): excavated elements and the pore water of a drainage switch -------------------
    def configure(self, active=None, k_water_el=None, water_reference=None):
        """Set the phase's configuration; all None restores the group as built.

        ``active`` (n_el,) bool: the elements present (False: excavated -- no force, no stiffness, no
        weight, zero stress). ``k_water_el`` (n_el,) K_w/n [Pa] of every element (replaces the material's
        ``k_water``: a layer switched between drained and undrained). ``water_reference`` (n_el, 16): the
        displacement [m] from which the pore water's volumetric strain counts (the state where the layer
        became undrained: its excess pore pressure starts at zero there)."""
        if active is None and k_water_el is None and water_reference is None:
            self._phase = None
            return
        active = np.ones(self.n_el, bool) if active is None else np.asarray(active, bool)
        kw = self.k_water_of_elements() if k_water_el is None else np.asarray(k_water_el, np.float64)
        ref = (
            np.zeros((self.n_el, 16)) if water_reference is None else np.asarray(water_reference, np.float64)
        )
        if active.shape != (self.n_el,) or kw.shape != (self.n_el,) or ref.shape != (self.n_el, 16):
            raise ValueError(
                "configure: active and k_water_el need shape (n_el,), water_reference (n_el, 16)"
            )
        idx = np.flatnonzero(active)
        mat = self.el_mat[idx]
        # the active elements as a group of their own, one material row per element (each its own K_w/n)
        sub = SoilQ8(
            self.coords[idx],
            self.edofs[idx],
            np.arange(len(idx)),
            self.kinds[mat],
            self.params[mat],
            n_gauss=self.n_gauss,
            k_water=kw[idx] if kw[idx].any() else None,
        )
        self._phase = {"active": active, "index": idx, "k_water": kw, "reference": ref, "group": sub}

    def k_water_of_elements(self) -> np.ndarray:
        """(n_el,) K_w/n [Pa] of every element in the current configuration (0: drained)."""
        phase = self._phase
        if phase is not None:
            return phase["k_water"].copy()
        return np.zeros(self.n_el) if self.k_water is None else self.k_water[self.el_mat]

    @property
    def active(self) -> np.ndarray:
        """(n_el,) bool: the elements present in the current configuration."""
        phase = self._phase
        return np.ones(self.n_el, bool) if phase is None else phase["active"].copy()

    def _scatter(self, values, fill_shape):
        out = np.zeros((self.n_el,) + fill_shape)
        out[self._phase["index"]] = values
        return out

    def _evaluate_phase(self, u_el, du_el, state_old, tangent):
        phase = self._phase
        idx, sub = phase["index"], phase["group"]
        sub.viscosity = self.viscosity
        u_water = np.asarray(u_el)[idx] - phase["reference"][idx]
        f_s, k_s, st_s = sub.evaluate(u_water, np.asarray(du_el)[idx], state_old[idx], tangent)
        state_new = np.zeros_like(state_old)
        state_new[idx] = st_s
        k_el = None if k_s is None else self._scatter(k_s, (16, 16))
        return self._scatter(f_s, (16,)), k_el, state_new

    def evaluate(self, u_el, du_el, state_old, tangent):
        if tangent not in TANGENT_FLAGS:
            raise ValueError(
                f"tangent must be K0_MATRIX (0), CONSISTENT (1) or FORCES_ONLY (-1), got {tangent}"
            )
        if self._phase is not None:
            return self._evaluate_phase(u_el, du_el, state_old, tangent)
        f_el = np.empty((self.n_el, 16))
        k_el = np.empty((self.n_el, 16, 16) if tangent != FORCES_ONLY else (1, 16, 16))
        state_new = np.empty_like(state_old)
        failures = self.kernel(
            self.coords,
            np.ascontiguousarray(du_el),
            self.el_mat,
            self.kinds,
            self.params,
            self.gp,
            self.gw,
            state_old,
            state_new,
            f_el,
            k_el,
            tangent,
            self.viscosity,
        )
        if failures:
            raise FloatingPointError(
                f"soil_q8: {failures} integration points failed (distorted element "
                "or a stress update that did not converge)"
            )
        if self.k_water is not None:
            q8_pore_water(
                self.coords,
                np.ascontiguousarray(u_el),
                self.el_mat,
                self.k_water,
                self.gp,
                self.gw,
                f_el,
                k_el,
                tangent != FORCES_ONLY,
            )
        return f_el, (k_el if tangent != FORCES_ONLY else None), state_new

    def elastic_stiffness(self):
        """K0 per element (n_el, 16, 16), from the dedicated elastic kernel (every soil law's params start
        with E, nu). Computed afresh on each call and not kept: the solver assembles K0 once per run, and
        keeping it would hold 2 kB per element (343 MB at 1e6 DOFs) for the whole analysis."""
        if self._phase is not None:
            return self._scatter(self._phase["group"].elastic_stiffness(), (16, 16))
        E = self.params[self.el_mat, 0]
        nu = self.params[self.el_mat, 1]
        k0 = q8_elastic_stiffness(self.coords, E, nu, self.n_gauss)
        if self.k_water is not None:
            zero = np.zeros((self.n_el, 16))
            q8_pore_water(
                self.coords, zero, self.el_mat, self.k_water, self.gp, self.gw, zero.copy(), k0, True
            )
        return k0

    def assemble_elastic_stiffness(self, smap, data):
        """Add K0 into CSR values ``data`` through this group's scatter map ``smap`` without keeping the
        element matrices (the same sums as scattering :meth:`elastic_stiffness`); undrained groups (pore-water
        term) and a group configured for a phase (excavated elements, a drainage switch) scatter the
        matrices of :meth:`elastic_stiffness`, which knows that configuration."""
        if self.k_water is not None or self._phase is not None:
            scatter_matrix(smap, self.elastic_stiffness(), data)
            return data
        E = self.params[self.el_mat, 0]
        nu = self.params[self.el_mat, 1]
        return q8_elastic_assemble(self.coords, E, nu, self.n_gauss, smap, data)

    def excess_pore_pressure(self, u_el) -> np.ndarray:
        """Excess pore pressure [Pa] (compression positive) at the integration points (n_el, n_ip) of the
        undrained materials, -K_w/n eps_v from the total displacement ``u_el`` (n_el, 16); 0 where drained."""
        ev = np.empty((self.n_el, len(self.gw)))
        phase = self._phase
        u_water = np.asarray(u_el, np.float64) - (0.0 if phase is None else phase["reference"])
        q8_volumetric_strain(self.coords, np.ascontiguousarray(u_water), self.gp, ev)
        kw = self.k_water_of_elements() * self.active
        return -kw[:, None] * ev

    def body_force(self):
        if self.unit_weight is None:
            return None
        f_el = np.empty((self.n_el, 16))
        q8_body_force(self.coords, self.el_mat, self.unit_weight, self.gp, self.gw, f_el)
        return f_el * self.active[:, None]

    def integration_points(self):
        """(n_el, n_ip, 2) physical coordinates of the integration points."""
        out = np.empty((self.n_el, len(self.gw), 2))
        q8_points(self.coords, self.gp, out)
        return out

    def stress(self, state):
        """Stress [sxx, szz, txz, syy] at the integration points, (n_el, n_ip, 4)."""
        return state[:, :, :N_STRESS]

    def point_materials(self) -> np.ndarray:
        """(n_el, n_ip) the row of ``kinds``/``params`` of each integration point (here its element's)."""
        return np.repeat(self.el_mat[:, None], len(self.gw), axis=1)

    def point_codes(self, state):
        """(n_el, n_ip) 1 where the last stress update returned to the yield surface (plastic), else 0."""
        return (self.history(state, "branch") > 0).astype(int)

    # ---- what the solver asks (ssi.core.protocol.ElementGroup) -------------------------------------------
    def _mohr_coulomb(self) -> np.ndarray:
        """(n_mat,) True for the Mohr-Coulomb rows of ``kinds`` (the rows with a friction and a dilatancy
        angle, columns 3 and 4 of ``params``)."""
        return np.isin(self.kinds, (MOHR_COULOMB, MOHR_COULOMB_EXPLICIT))

    def associated_flow(self, tol: float = 0.0) -> bool:
        """True unless a Mohr-Coulomb row has |psi - phi| > ``tol`` [rad] (elastic and von Mises rows are
        associated)."""
        mc = self._mohr_coulomb()
        return not np.any(np.abs(self.params[mc, 4] - self.params[mc, 3]) > tol)

    def symmetric_tangent(self) -> bool:
        """Associated flow (psi = phi exactly) has a symmetric consistent tangent."""
        return self.associated_flow()

    def davis_params(self) -> np.ndarray:
        """(n_mat, n_par) a new array: Davis' associated row of each Mohr-Coulomb row
        (:func:`ssi.materials.soil_laws.davis_soil_row`), the other rows copied."""
        rows = [davis_soil_row(p) if m else p.copy() for p, m in zip(self.params, self._mohr_coulomb())]
        return np.ascontiguousarray(np.array(rows, np.float64))

    def stored_energy(self, u_el, du_el, state_old, state_new, work) -> float:
        """sum sigma_n+1 : C^-1 d_sigma w |J| (+ the undrained pore water's elastic work) [J/m]."""
        mat = self.point_materials()
        e_mod, nu = self.params[mat, 0], self.params[mat, 1]
        sig = self.stress(state_new)
        dsig = sig - self.stress(state_old)
        normal = [0, 1, 3]  # sxx, szz, syy
        sn, dn = sig[..., normal], dsig[..., normal]
        dot = np.einsum("eqi,eqi->eq", sn, dn)
        cross = sn.sum(-1) * dn.sum(-1) - dot  # sum over i != j of s_i ds_j
        shear = sig[..., 2] * dsig[..., 2]
        density = (dot - nu * cross + 2.0 * (1.0 + nu) * shear) / e_mod
        weights = self._point_weights()
        total = float(np.sum(density * weights))
        if np.any(self.k_water_of_elements()):  # undrained: the pore water's volumetric spring is elastic
            dev = np.empty(weights.shape)
            gp, _ = gauss_2d(self.n_gauss)
            q8_volumetric_strain(self.coords, np.ascontiguousarray(du_el), gp, dev)
            total += float(np.sum(-self.excess_pore_pressure(u_el) * dev * weights))
        return total

    def _point_weights(self) -> np.ndarray:
        """(n_el, n_ip) Gauss weight times det J of the group's points [m^2 per m of strip]."""
        gp, gw = gauss_2d(self.n_gauss)
        dn = np.array([serendipity8(float(x), float(y))[1] for x, y in gp])  # (n_ip, 8, 2)
        jac = np.einsum("qai,eaj->eqij", dn, self.coords)
        det = jac[..., 0, 0] * jac[..., 1, 1] - jac[..., 0, 1] * jac[..., 1, 0]
        return det * gw[None, :]

    def nonassociated_yielding(self, state, tol):
        """(row, plastic points, nu, phi, psi) of each Mohr-Coulomb row with phi - psi > ``tol`` [rad] that
        has plastic points in ``state``."""
        plastic = np.asarray(self.point_codes(state)) > 0
        rows, counts = np.unique(self.point_materials()[plastic], return_counts=True)
        out = []
        for row, count in zip(rows, counts):
            nu, phi, psi = self.params[row, 1], self.params[row, 3], self.params[row, 4]
            is_mc = self.kinds[row] in (MOHR_COULOMB, MOHR_COULOMB_EXPLICIT)
            if is_mc and phi - psi > tol:
                out.append((row, count, nu, phi, psi))
        return out

    def describe(self):
        return {
            "name": self.name,
            "n_el": self.n_el,
            "n_gauss": self.n_gauss,
            "kinds": self.kinds.tolist(),
            "params": self.params.tolist(),
        }
