"""Design checks of a reinforced-concrete strip section from the action effects of the coupled analysis.

What a designer reads off a foundation beam, per unit width (b = 1 m), at the strip's sampling points:

* **Crack width**, EN 1992-1-1 §7.3.4: w_k = s_r,max (eps_sm - eps_cm), with

  - eps_sm - eps_cm = [sig_s - k_t f_ct,eff / rho_p,eff (1 + alpha_e rho_p,eff)] / E_s >= 0.6 sig_s / E_s
    (eq. 7.9; k_t = 0.4 long-term loading by default, 0.6 short-term);
  - s_r,max = k3 c + k1 k2 k4 phi / rho_p,eff (eq. 7.11; k1 = 0.8 ribbed bars, k2 = 0.5 bending, k3 = 3.4,
    k4 = 0.425, c the clear cover), or 1.3 (h - x) where the bar spacing exceeds 5 (c + phi/2) (eq. 7.14);
  - rho_p,eff = A_s / A_c,eff, h_c,ef = min(2.5 (h - d), (h - x)/3, h/2) (§7.3.2 (3));
  - sig_s the stress of the tension bars *at the crack* and x the neutral-axis depth, both from the cracked
    elastic section (concrete linear in compression, no tension; bars elastic) under the point's N and M --
    the section state EN 1992 §7.1 (2) prescribes for crack control. The analysis supplies N, M and whether
    the tension face has cracked: an uncracked point has w_k = 0.

* **Bending resistance** M_Rd(N) from ssi's own layer-free section analysis
  (``ssi.elements.section_analysis.layer_free_state``): the moment at which the extreme compressed fibre
  reaches eps_cu (EN 1992 §6.1 (3)), with the concrete's strength replaced by alpha_cc f_ck / gamma_c (f_ck
  = f_cm - 8 MPa, EN 1992 Table 3.1, unless given), the bars' by f_yk / gamma_s, no tension stiffening;
  characteristic values by default (gamma_c = gamma_s = 1).

* **Shear resistance without shear reinforcement**, EN 1992 §6.2.2 eq. (6.2): V_Rd,c = [C_Rd,c k (100 rho_l
  f_ck)^(1/3) + k1 sigma_cp] b d >= (v_min + k1 sigma_cp) b d, C_Rd,c = 0.18 / gamma_c, k = 1 + sqrt(200/d)
  <= 2 (d in mm), rho_l <= 0.02, v_min = 0.035 k^1.5 f_ck^0.5, k1 = 0.15, sigma_cp = N_Ed / A_c < 0.2 f_cd
  (compression positive) [MPa, mm].

* **Brittle flag**: a face whose cracking moment M_cr = f_ctm I / y (uncracked elastic section) exceeds its
  yield moment M_y (cracked elastic section with the tension bars at f_yk) cracks and yields at once -- below
  minimum reinforcement; a plain section (no bars on the tension face) is always brittle.

Sign conventions are the strip's: N > 0 tension [N/m], M > 0 sagging (tension at the bottom) [N m/m], V [N/m].
Stresses [Pa], lengths [m], crack widths [m].
"""

import math
from dataclasses import dataclass, field

import numpy as np

from ..materials.concrete import P_ALPHA_TS, P_E0, P_EPS_C, P_FC, P_FR
from ..materials.layer_laws import CONCRETE, STEEL
from ..materials.steel import S_FY
from .section import Section

__all__ = ["FaceBars", "RCDesign", "cracked_section", "vrdc_ec2"]

MPA = 1.0e6


CAPACITY_SPLIT = 8  # sublayers per concrete layer of the capacity section's layered analysis


def split_layers(section: Section, factor: int) -> Section:
    """``section`` with every concrete layer split into ``factor`` equal layers (bars kept), same laws."""
    from .section import layered

    th, kinds, params, shear, labels = [], [], [], [], []
    for n in range(section.n_layer):
        k = factor if section.kind[n] == CONCRETE else 1
        for _ in range(k):
            th.append(section.h[n] / k)
            kinds.append(section.kind[n])
            params.append(section.params[n])
            shear.append(bool(section.carries_shear[n]))
            labels.append(section.labels[n] if section.labels else "")
    return layered(th, kinds, params, carries_shear=shear, z_ref=-section.z_bottom, labels=tuple(labels))


@dataclass(frozen=True)
class FaceBars:
    """The bars of one face: ``As`` [m^2/m], ``depth_d`` effective depth from the opposite face [m],
    ``cover`` clear cover to the bar surface [m], ``phi`` bar diameter [m] (As = 0: no bars)."""

    As: float
    depth_d: float
    cover: float
    phi: float

    @property
    def spacing(self) -> float:
        """Bar spacing [m] of bars of diameter phi giving As per metre (inf without bars)."""
        return math.pi * self.phi**2 / 4.0 / self.As if self.As > 0.0 else math.inf


def cracked_section(h: float, Ec: float, Es: float, bars: list[tuple[float, float]], N: float, M: float):
    """Cracked elastic section of depth ``h`` [m], per unit width, compressed at the top: concrete linear
    (modulus ``Ec`` [Pa]) in compression only, bars ``(y, As)`` at depth y from the compressed face [m] with
    area As [m^2/m] elastic (``Es`` [Pa]). Actions ``N`` [N/m] (tension positive) and ``M`` [N m/m] > 0 about
    mid-depth, tensioning the bottom. Returns ``(x, kap, sig_bars)``: neutral-axis depth [m], curvature [1/m]
    and the bar stresses [Pa] (tension positive); x = nan if no neutral axis lies within the section (all
    compressed: no crack; all in tension: the bars alone carry N and M)."""
    ys = np.array([b[0] for b in bars], np.float64)
    As = np.array([b[1] for b in bars], np.float64)
    if M <= 0.0:
        raise ValueError(f"M must be > 0 (tension at the bottom), got {M!r}")

    def forces(x):  # per unit curvature
        n = Es * np.sum(As * (ys - x)) - 0.5 * Ec * x * x
        m = Es * np.sum(As * (ys - x) * (ys - 0.5 * h)) + 0.5 * Ec * x * x * (0.5 * h - x / 3.0)
        return n, m

    def f(x):
        n, m = forces(x)
        return n * M - m * N

    from scipy.optimize import brentq

    lo, hi = 1e-9 * h, h
    if f(lo) * f(hi) > 0.0:
        return math.nan, math.nan, np.full(ys.size, math.nan)
    x = brentq(f, lo, hi, xtol=1e-14 * h, rtol=1e-14)
    kap = M / forces(x)[1]
    return x, kap, Es * kap * (ys - x)


def vrdc_ec2(
    fck: float, d: float, rho_l: float, N: float = 0.0, h: float | None = None, gamma_c: float = 1.0
):
    """EN 1992-1-1 eq. (6.2) per metre width [N/m]: ``fck`` [Pa], effective depth ``d`` [m], ``rho_l`` =
    A_sl / (b d) of the tension bars (capped at 0.02), ``N`` [N/m] (tension positive, so sigma_cp = -N / A_c),
    ``h`` [m] the depth giving A_c (default d), ``gamma_c`` (1: characteristic)."""
    fck_mpa = fck / MPA
    d_mm = d * 1e3
    k = min(1.0 + math.sqrt(200.0 / d_mm), 2.0)
    rho = min(max(rho_l, 0.0), 0.02)
    fcd = fck_mpa / gamma_c
    sig_cp = min(-N / (h or d) / MPA, 0.2 * fcd)  # [MPa]: -N [N/m] / A_c [m^2 per m]
    c_rd = 0.18 / gamma_c
    v_min = 0.035 * k**1.5 * math.sqrt(fck_mpa)
    v = max(c_rd * k * (100.0 * rho * fck_mpa) ** (1.0 / 3.0) + 0.15 * sig_cp, v_min + 0.15 * sig_cp)
    return v * 1000.0 * d_mm  # N per 1000 mm of width


@dataclass
class RCDesign:
    """Design data of an RC strip ``section`` (the user's, before crack-band regularisation) with bars of
    ``bar_diameter`` [m] (one per face, or a pair (bottom, top)).

    Options: ``fck`` [Pa] (default f_cm - 8 MPa from the concrete layers' fc, EN 1992 Table 3.1), ``gamma_c``,
    ``gamma_s`` (1: characteristic resistances), ``alpha_cc`` (1), ``kt`` (0.4 long-term, 0.6 short-term),
    ``eps_cu`` (0.0035)."""

    section: Section
    bar_diameter: float | tuple[float, float] = 0.016
    fck: float | None = None
    gamma_c: float = 1.0
    gamma_s: float = 1.0
    alpha_cc: float = 1.0
    kt: float = 0.4
    eps_cu: float = 0.0035
    faces: dict = field(init=False)

    def __post_init__(self):
        sec = self.section
        conc = np.flatnonzero(sec.kind == CONCRETE)
        if conc.size == 0:
            raise ValueError("RCDesign: the section has no CONCRETE layer")
        for name in ("gamma_c", "gamma_s", "alpha_cc"):
            v = getattr(self, name)
            if not (math.isfinite(v) and 0.5 <= v <= 2.0):
                raise ValueError(f"{name} must be in [0.5, 2], got {v!r}")
        if self.kt not in (0.4, 0.6):
            raise ValueError(f"kt must be 0.4 (long-term) or 0.6 (short-term loading), got {self.kt!r}")
        p = sec.params[conc[0]]
        self.fcm = float(p[P_FC])
        if self.fck is None:
            self.fck = self.fcm - 8.0 * MPA
        if not 12e6 <= self.fck <= 90e6:
            raise ValueError(f"fck must be in [12, 90] MPa, got {self.fck / MPA!r} MPa")
        self.Ec = float(p[P_E0])
        self.fctm = float(p[P_FR])
        steel = np.flatnonzero(sec.kind == STEEL)
        self.Es = float(sec.params[steel[0], 0]) if steel.size else 200e9
        self.fyk = float(sec.params[steel[0], S_FY]) if steel.size else 500e6
        phis = self.bar_diameter if isinstance(self.bar_diameter, tuple | list) else (self.bar_diameter,) * 2
        h = sec.thickness
        mid = 0.5 * (sec.z_bottom + sec.z_top)
        self.h = h
        self.faces = {}
        for face, phi in zip(("bottom", "top"), phis, strict=True):
            sel = steel[(sec.z_mid[steel] < mid) if face == "bottom" else (sec.z_mid[steel] >= mid)]
            if sel.size == 0:
                self.faces[face] = FaceBars(0.0, 0.5 * h, 0.5 * h, float(phi))
                continue
            As = float(sec.h[sel].sum())
            z = float(np.dot(sec.h[sel], sec.z_mid[sel]) / As)
            dist = (z - sec.z_bottom) if face == "bottom" else (sec.z_top - z)
            self.faces[face] = FaceBars(As, h - dist, dist - 0.5 * phi, float(phi))
        self._mrd_cache: dict = {}
        self._split: dict = {}
        self._capacity = None

    # ---- bars seen from the compressed face ----------------------------------------------------------
    def _bars_from_top(self, tension_face: str) -> list[tuple[float, float]]:
        """(depth from the compressed face, As) of every bar layer, for tension at ``tension_face``."""
        sec = self.section
        steel = np.flatnonzero(sec.kind == STEEL)
        if tension_face == "bottom":
            return [(sec.z_top - sec.z_mid[n], sec.h[n]) for n in steel]
        return [(sec.z_mid[n] - sec.z_bottom, sec.h[n]) for n in steel]

    def steel_stress_at_crack(self, N: float, M: float) -> tuple[float, float, str]:
        """``(sig_s, x, face)``: stress [Pa] of the tension face's bars at a crack and the neutral-axis depth
        [m] from the cracked elastic section under N [N/m] and M [N m/m] about mid-depth (the strip's
        reference: M is shifted to mid-depth if the reference surface lies elsewhere); face = the tension
        face. sig_s = nan where the section has no bars on that face or no neutral axis."""
        sec = self.section
        M_mid = M + N * (0.5 * (sec.z_bottom + sec.z_top))  # moment about mid-depth (z_mid of the section)
        face = "bottom" if M_mid >= 0.0 else "top"
        fb = self.faces[face]
        if fb.As == 0.0 or M_mid == 0.0:
            return math.nan, math.nan, face
        bars = self._bars_from_top(face)
        x, _, sig = cracked_section(self.h, self.Ec, self.Es, bars, N, abs(M_mid))
        d = fb.depth_d
        i = int(np.argmin([abs(y - d) for y, _ in bars]))
        return float(sig[i]), x, face

    def crack_width(self, N: float, M: float) -> dict:
        """EN 1992-1-1 §7.3.4 at a cracked section under N [N/m] and M [N m/m]: dict of ``w_k`` [m],
        ``s_r_max`` [m], ``eps_diff`` (eps_sm - eps_cm), ``sig_s`` [Pa], ``x`` [m], ``rho_p_eff``, ``h_c_ef``
        [m], ``face``. w_k = 0 where the tension face has no bars' stress (all compressed) or is plain."""
        sig_s, x, face = self.steel_stress_at_crack(N, M)
        fb = self.faces[face]
        if not math.isfinite(sig_s) or sig_s <= 0.0:
            return {"w_k": 0.0, "s_r_max": math.nan, "eps_diff": 0.0, "sig_s": sig_s, "x": x,
                    "rho_p_eff": math.nan, "h_c_ef": math.nan, "face": face}  # fmt: skip
        h, d = self.h, fb.depth_d
        h_c_ef = min(2.5 * (h - d), (h - x) / 3.0, 0.5 * h)
        rho = fb.As / h_c_ef
        alpha_e = self.Es / self.Ec
        eps_diff = max(
            (sig_s - self.kt * self.fctm / rho * (1.0 + alpha_e * rho)) / self.Es, 0.6 * sig_s / self.Es
        )
        if fb.spacing > 5.0 * (fb.cover + 0.5 * fb.phi):  # eq. (7.14)
            s_r = 1.3 * (h - x)
        else:  # eq. (7.11)
            s_r = 3.4 * fb.cover + 0.8 * 0.5 * 0.425 * fb.phi / rho
        return {"w_k": s_r * eps_diff, "s_r_max": s_r, "eps_diff": eps_diff, "sig_s": sig_s, "x": x,
                "rho_p_eff": rho, "h_c_ef": h_c_ef, "face": face}  # fmt: skip

    # ---- resistances ---------------------------------------------------------------------------------
    def capacity_section(self) -> Section:
        """The section with design strengths: concrete alpha_cc f_ck / gamma_c (eps_c kept, or raised to
        2 fc/E0 so that eq. 5.1 stays below its initial tangent), no tension stiffening; bars f_yk /
        gamma_s."""
        from dataclasses import replace

        params = self.section.params.copy()
        fcd = self.alpha_cc * self.fck / self.gamma_c
        for n in np.flatnonzero(self.section.kind == CONCRETE):
            params[n, P_FC] = fcd
            params[n, P_EPS_C] = max(params[n, P_EPS_C], 2.0 * fcd / params[n, P_E0])
            params[n, P_ALPHA_TS] = 0.0
            params[n, P_FR] = min(params[n, P_FR], 0.99 * fcd)
        for n in np.flatnonzero(self.section.kind == STEEL):
            params[n, S_FY] = self.fyk / self.gamma_s
        return replace(self.section, params=params)

    def M_Rd(self, N: float = 0.0, sign: int = 1, layer_free: bool = False) -> float:
        """Bending resistance [N m/m] under the axial force ``N`` [N/m] (tension positive), sagging (``sign``
        = 1) or hogging (-1, returned negative); a face without bars: its cracking moment M_cr. Otherwise
        the section at the curvature where the extreme compressed
        fibre reaches eps_cu, every fibre loaded monotonically (see the module docstring). The layered
        section analysis (``section_analysis.section_state``) of the capacity section with each concrete
        layer split in ``CAPACITY_SPLIT`` (the layer rule's error in M then below 1e-4, measured against
        ``layer_free=True``, the adaptive-quadrature analysis, in chapter 18; that one takes seconds)."""
        from scipy.optimize import brentq

        from .section_analysis import layer_free_state

        key = (round(float(N), 6), int(sign), bool(layer_free))
        if key in self._mrd_cache:
            return self._mrd_cache[key]
        face = "bottom" if sign > 0 else "top"
        if self.faces[face].As == 0.0:  # no bars in tension: the plain section's peak is its cracking moment
            return sign * self.brittle()[face]["M_cr"]
        if self._capacity is None:
            self._capacity = self.capacity_section()
        sec = self._capacity
        z_c = sec.z_top if sign > 0 else sec.z_bottom  # compressed face
        state = layer_free_state if layer_free else self._layered_state

        def excess(kap):
            eps0, _, _ = state(sec, kap, N)
            return -(eps0 - z_c * kap) - self.eps_cu

        kap_hi = sign * 50.0 * self.eps_cu / self.h
        kap_lo = sign * 0.05 * self.eps_cu / self.h
        kap = brentq(excess, kap_lo, kap_hi, xtol=1e-10 * abs(kap_hi), rtol=1e-10)
        M = float(state(sec, kap, N)[1])
        self._mrd_cache[key] = M
        return M

    def _layered_state(self, sec: Section, kap: float, N: float):
        """(eps0, M, S) of the split capacity section at curvature ``kap`` carrying ``N``, virgin history
        (every fibre loaded monotonically): Brent's method on N(eps0) between the all-compressed and the
        all-tensile planes."""
        from scipy.optimize import brentq

        from ..materials.layer_laws import N_LAYER_HIST
        from .section_analysis import _Layers, _section_state

        if id(sec) not in self._split:
            fine = split_layers(sec, CAPACITY_SPLIT)
            self._split[id(sec)] = (fine, _Layers.of(fine))
        fine, layers = self._split[id(sec)]
        hist = np.zeros((fine.n_layer, N_LAYER_HIST))

        def axial(eps0):
            return _section_state(layers, fine.params, eps0, kap, hist, 5.0 / 6.0, "chord")[0] - N

        ends = (kap * fine.z_bottom, kap * fine.z_top)
        lo, hi = min(ends) - 1e-7, max(ends) + 1e-7
        if axial(lo) > 0.0 or axial(hi) < 0.0:
            raise ValueError(f"N = {N!r} N/m is outside what the section carries at kap = {kap!r} 1/m")
        eps0 = brentq(axial, lo, hi, xtol=1e-15 + 1e-13 * (hi - lo), rtol=1e-12, maxiter=200)
        _, M, _, S, _ = _section_state(layers, fine.params, eps0, kap, hist, 5.0 / 6.0, "chord")
        return eps0, M, S

    def V_Rd_c(self, M_sign: float, N: float = 0.0) -> float:
        """Shear resistance without shear reinforcement [N/m] (EN 1992 eq. 6.2) with the tension bars of the
        face that ``M_sign`` (the moment's sign at the point) puts in tension."""
        fb = self.faces["bottom" if M_sign >= 0.0 else "top"]
        d = fb.depth_d
        return vrdc_ec2(self.fck, d, fb.As / d, N, self.h, self.gamma_c)

    def brittle(self) -> dict:
        """Per face: ``M_cr`` [N m/m] (uncracked elastic section at f_ctm), ``M_y`` [N m/m] (cracked elastic
        section, tension bars at f_yk, N = 0; 0 without bars) and ``brittle`` (M_cr > M_y)."""
        sec = self.section
        e0, _ = sec.initial_moduli()
        stiff = sec.elastic_resultant_stiffness()
        conc = sec.kind == CONCRETE
        e_c = float(e0[conc][0])
        out = {}
        for face, sign in (("bottom", 1.0), ("top", -1.0)):
            y = (stiff["z_na"] - sec.z_bottom) if sign > 0 else (sec.z_top - stiff["z_na"])
            M_cr = self.fctm / e_c * stiff["D_na"] / y
            fb = self.faces[face]
            M_y = 0.0
            if fb.As > 0.0:
                sig = self.steel_stress_at_crack(0.0, sign * 1.0)[0]  # per unit moment (linear)
                M_y = self.fyk / sig if sig > 0.0 else math.inf
            out[face] = {"M_cr": float(M_cr), "M_y": float(M_y), "brittle": bool(M_cr > M_y)}
        return out
