"""The RC beam of chapter 08: section analysis against closed forms, the curvature integral against the
Timoshenko formula, the layered FE against both, and the reference-data files.

Tolerances: closed forms of linear problems hold to round-off (1e-9 after a sparse solve); the plastic
rectangle's midpoint rule over 400 layers errs by O(1/n^2) ~ 1e-5 (asserted 1e-4); the FE against the
curvature integral is a discretisation error measured in chapter 08 at 2.8e-3 (2 + 2 elements, 40
steps), asserted 4e-3 here, and it must shrink on refinement.
"""

import numpy as np
import pytest

from ssi.elements import section_analysis as sa
from ssi.elements.section import layered
from ssi.lab import rc_beam as rb
from ssi.lab.digitize import read_reference
from ssi.materials import rc
from ssi.materials.concrete import P_FR
from ssi.materials.layer_laws import CONCRETE, ELASTIC, STEEL
from ssi.solver import Settings

G = rb.JANNEY


def test_moment_curvature_elastic_plastic_rectangle():
    fy, Es, H, n = 300e6, 200e9, 0.2, 400
    sec = layered(np.full(n, H / n), STEEL, rc.steel_params(fy, Es, 0.0))
    kap_y = 2 * fy / (Es * H)
    mc = sa.moment_curvature(sec, 5 * kap_y, 500)
    m_p = fy * H**2 / 4
    k = mc.kap[mc.kap > kap_y * 1.01]
    exact = m_p * (1 - (kap_y / k) ** 2 / 3)
    assert np.max(np.abs(mc.M[mc.kap > kap_y * 1.01] - exact)) <= 1e-4 * m_p
    el = mc.kap < 0.99 * kap_y
    assert np.max(np.abs(mc.M[el] - Es * H**3 / 12 * mc.kap[el])) <= 1e-9 * m_p


def test_section_state_resultants_of_an_elastic_section_and_its_option_check():
    """N = E A eps0 and M = E I kap for an elastic section about its mid-plane, with every self-bending term
    exact for linear layers; an unknown option is refused by name."""
    E, H, n = 30e9, 0.4, 8
    sec = layered(np.full(n, H / n), ELASTIC, np.array([E, 0.0]))
    for mode in ("chord", "initial", "tangent"):
        N, M, A, S, _ = sa.section_state(sec, sec.params, 1e-4, 2e-3, np.zeros((n, 4)), self_bending=mode)
        assert N == pytest.approx(E * H * 1e-4, rel=1e-12)
        assert M == pytest.approx(E * H**3 / 12 * 2e-3, rel=1e-12)
        assert A == pytest.approx(E * H, rel=1e-12)
    with pytest.raises(ValueError, match="self_bending.*'mid'"):
        sa.section_state(sec, sec.params, 0.0, 0.0, np.zeros((n, 4)), self_bending="mid")


def test_curvature_integral_matches_timoshenko_for_elastic_section():
    sec = rb.janney_section(11, elastic=True)
    k = sec.elastic_resultant_stiffness()
    mc = sa.moment_curvature(sec, 1e-3, 200)
    assert np.allclose(mc.M, k["D_na"] * mc.kap, rtol=1e-9, atol=1e-9 * k["D_na"] * 1e-3)
    P = 0.8 * mc.M[-1] / G["a"]
    ref = sa.four_point_deflection_elastic(P, G["span"], G["a"], k["D_na"], k["S"])
    assert sa.four_point_deflection(mc, P, G["span"], G["a"])[0] == pytest.approx(ref, rel=1e-6)


@pytest.mark.parametrize("n", [1, 3])
def test_fe_linear_is_exact_timoshenko(n):
    sec = rb.janney_section(11, elastic=True)
    beam = rb.build_four_point(sec, G["span"], G["a"], n, n, crack_band=None)
    k = sec.elastic_resultant_stiffness()
    ref = sa.four_point_deflection_elastic(1.0, G["span"], G["a"], k["D_na"], k["S"])
    assert rb.linear_compliance(beam) == pytest.approx(ref, rel=1e-9)


def test_fe_converges_to_curvature_integral_before_yield():
    ls = 0.05
    sec = rb.janney_section(11, ls=ls)
    # the discrete section with the initial-modulus self-bending: its M(kap) rises monotonically (the
    # tangent option drops a layer's own bending term when it cracks, so kap(M) is not single-valued)
    mc = sa.moment_curvature(sec, 0.016, 2000, ls=ls, self_bending="initial")
    m_y = mc.M[mc.first_yield - 1]
    errors = []
    for n in (2, 4):
        beam = rb.build_four_point(sec, G["span"], G["a"], n, n, crack_band=None, self_bending="initial")
        out = rb.load_path(beam, 0.008, 40, Settings(max_iter=2000))
        ok = (out["M"] < m_y) & (out["P"] > 0)
        ref = sa.four_point_deflection(mc, out["P"][ok], G["span"], G["a"])
        errors.append(np.max(np.abs(out["delta"][ok] / ref - 1)))
    assert errors[0] <= 4e-3 and errors[1] < errors[0], errors


def test_reference_files():
    meta, cols = read_reference("janney1956_beam.csv")  # a bare name: the file in reference_data/
    assert meta["trust"].startswith("C") and all(k in meta for k in ("uncertainty", "units", "source"))
    assert list(cols)[:2] == ["delta_mm", "M_kNm"] and len(cols) == 4
    assert all(c.dtype == np.float64 and c.shape == (11,) for c in cols.values())
    meta, cols = read_reference("monnier1970_fig12.csv")  # header only: four empty float columns
    assert len(cols) == 4 and all(c.size == 0 for c in cols.values()) and meta["trust"].startswith("D")


def test_beam_input_validation():
    sec = rb.janney_section(11, elastic=True)
    with pytest.raises(ValueError, match="a must be"):
        rb.build_four_point(sec, 2.0, 1.5, 2, 2)
    with pytest.raises(ValueError, match="n_shear"):
        rb.build_four_point(sec, 2.0, 0.5, 0, 2)
    assert sec.kind[0] == ELASTIC


def test_layer_free_reference_closed_forms():
    """The layer-free section reference against closed forms: an elastic-plastic steel rectangle (no layers
    in the closed form either) to quadrature accuracy, and a linear composite section's EI about its
    neutral axis; the layering of the input section does not enter (1 vs 50 identical layers)."""
    fy, Es, H = 300e6, 200e9, 0.2
    kap_y = 2 * fy / (Es * H)
    kaps = np.array([0.0, 0.5, 1.5, 3.0, 5.0]) * kap_y
    m_p = fy * H**2 / 4
    exact = np.where(
        kaps <= kap_y, Es * H**3 / 12 * kaps, m_p * (1 - (kap_y / np.maximum(kaps, 1e-30)) ** 2 / 3)
    )
    for n in (1, 50):
        sec = layered(np.full(n, H / n), STEEL, rc.steel_params(fy, Es, 0.0))
        ref = sa.layer_free_moment_curvature(sec, kaps)
        assert np.max(np.abs(ref.M - exact)) <= 1e-8 * m_p
        assert ref.first_yield == 2
    sec = rb.janney_section(11, elastic=True)
    k = sec.elastic_resultant_stiffness()
    ref = sa.layer_free_moment_curvature(sec, np.array([0.0, 1e-4, 1e-3]))
    assert np.allclose(ref.M[1:], k["D_na"] * ref.kap[1:], rtol=1e-9)
    assert np.allclose(ref.S, k["S"], rtol=1e-12)
    with pytest.raises(ValueError, match="kaps"):
        sa.layer_free_moment_curvature(sec, [0.0, -1.0])


def test_layered_section_converges_to_layer_free_reference():
    """The discrete (history-following) section with many thin layers and no self-bending term approaches
    the layer-free reference in the cracked and the yielded state (midpoint rule O(1/n^2); the reference's
    monotonic-fibre assumption measured at 4e-4 in chapter 02)."""
    sec11 = rb.janney_section(11, ls=0.1)
    kaps = np.array([0.0, 0.004, 0.03])
    ref = sa.layer_free_moment_curvature(sec11, kaps)
    errs = []
    for n in (21, 81):
        mc = sa.moment_curvature(rb.janney_section(n, ls=0.1), 0.03, 600, self_bending="none")
        errs.append(np.max(np.abs(np.interp(kaps[1:], mc.kap, mc.M) / ref.M[1:] - 1)))
    assert errs[1] < errs[0] and errs[1] < 2e-3, errs


# ---- the over-stiffness sources of chapter 08: shrinkage restraint and self-weight
@pytest.mark.parametrize(
    ("fck", "rh", "table"),
    # EN 1992-1-1 Table 3.2 (cement class N), nominal drying shrinkage eps_cd,0 in per mille, printed to two
    # digits: the tolerance is half the last printed digit, 0.005 per mille
    [(20e6, 0.4, 0.58), (40e6, 0.6, 0.38), (60e6, 0.8, 0.19), (20e6, 0.9, 0.17)],
)
def test_shrinkage_strain_matches_en1992_table_3_2(fck, rh, table):
    # h0 = 100 mm (k_h = 1) and drying for 1e9 days (beta_ds = 1): eps_cd is eps_cd,0 of the table
    out = rb.shrinkage_strain_en1992(fck + 8e6, 0.1, 1e9, 0.0, rh=rh, cement="N")
    assert out["eps_cd"] * 1e3 == pytest.approx(table, abs=0.005)


def test_shrinkage_strain_of_the_janney_beam_by_hand():
    """Hand calculation (EN 1992-1-1 3.1.4, B.2; fcm 36.2 MPa, h0 = 101.6 mm, drying 7 -> 28 d, RH 50 %,
    class N): eps_cd,0 = 0.85 * 660 * exp(-0.4344) * 1.55 * 0.875 = 492.8e-6, k_h = 0.9976,
    beta_ds = 21 / (21 + 40.96) = 0.3389, eps_cd = 166.6e-6; eps_ca = (1 - exp(-0.2 sqrt 28)) 2.5 (28.2 - 10)
    = 0.6530 * 45.5e-6 = 29.71e-6. Tolerance 0.1 %: the hand values' four digits."""
    b, h = G["b"], G["h"]
    out = rb.shrinkage_strain_en1992(G["fc"], b * h / (b + h), 28.0, 7.0, rh=0.5, cement="N")
    assert out["eps_cd"] == pytest.approx(166.6e-6, rel=1e-3)
    assert out["eps_ca"] == pytest.approx(29.71e-6, rel=1e-3)
    assert out["eps_cs"] == pytest.approx(out["eps_cd"] + out["eps_ca"], rel=1e-12)
    with pytest.raises(ValueError, match="rh must be"):
        rb.shrinkage_strain_en1992(G["fc"], 0.1, 28.0, 7.0, rh=0.2)
    with pytest.raises(ValueError, match="ts_days"):
        rb.shrinkage_strain_en1992(G["fc"], 0.1, 7.0, 28.0)
    with pytest.raises(ValueError, match="cement must be"):
        rb.shrinkage_strain_en1992(G["fc"], 0.1, 28.0, 7.0, cement="X")


def test_shrinkage_restraint_of_the_janney_section_by_hand():
    """Transformed uncracked section by hand (per beam, mm): alpha_e = 200 / 33.01 = 6.06, A_t = 46452 +
    5.06 * 600 = 49488 mm^2, centroid 156.0 mm from the top, e = 54.8 mm to the bars, I_t = 369.3e6 mm^4;
    F = eps_cs Es As = 1.9631e-4 * 200e3 * 600 = 23.56 kN; bottom face (y = 148.8 mm): sigma = F / A_t +
    F e y / I_t = 0.476 + 0.520 = 0.996 MPa; 1/r_cs = F e / (E0 I_t) = 1.059e-4 1/m. Tolerance 0.5 %: the
    hand calculation's rounding (three to four digits)."""
    sec = rb.janney_band_section(41)
    sigma, kap = rb.shrinkage_restraint_stress(sec, 1.9631e-4)
    conc = sec.kind == CONCRETE
    line = np.polyfit(sec.z_mid[conc], sigma[conc], 1)  # the stress is linear in z over the concrete
    assert np.polyval(line, sec.z_bottom) / 1e6 == pytest.approx(0.996, rel=5e-3)
    assert kap == pytest.approx(1.059e-4, rel=5e-3)
    shr, _ = rb.with_shrinkage_restraint(sec, 1.9631e-4)
    fr = sec.params[conc, P_FR]
    assert np.allclose(shr.params[conc, P_FR], fr - np.maximum(sigma[conc], 0.0), rtol=1e-12)
    with pytest.raises(ValueError, match="eps_cs must be"):
        rb.shrinkage_restraint_stress(sec, -1e-4)
    with pytest.raises(ValueError, match="cracked by shrinkage alone"):
        rb.with_shrinkage_restraint(sec, 1.5e-3)


def test_deflection_after_self_weight_is_superposition_for_an_elastic_section():
    """Linear section: the deflection measured from the self-weight state is the Timoshenko deflection of the
    point loads alone, whatever q (superposition); q = 0 is the plain curvature integral."""
    sec = rb.janney_section(11, elastic=True)
    k = sec.elastic_resultant_stiffness()
    mc = sa.moment_curvature(sec, 1e-3, 200)
    P = np.array([0.0, 0.3, 0.6]) * mc.M[-1] / G["a"]
    ref = sa.four_point_deflection_elastic(P, G["span"], G["a"], k["D_na"], k["S"])
    q = 0.2 * mc.M[-1] * 8 / G["span"] ** 2  # a self-weight moment of a fifth of the table's range
    for qq in (0.0, q):
        got = rb.four_point_deflection_after_self_weight(mc, P, qq, G["span"], G["a"])
        assert np.allclose(got, ref, rtol=1e-6, atol=1e-12)
    assert np.isnan(
        rb.four_point_deflection_after_self_weight(mc, [mc.M[-1] / G["a"]], q, G["span"], G["a"])
    )[0]


def test_load_path_after_self_weight_is_superposition_for_an_elastic_beam():
    """Linear beam: driven from the self-weight state, the load-deflection path is the path without it (the
    weight's own share at the load node is not counted as load: P = 0 at the start); a negative weight is
    refused by name."""
    sec = rb.janney_section(11, elastic=True)
    runs = []
    for q in (0.0, 7.6e3):
        beam = rb.build_four_point(sec, G["span"], G["a"], 2, 2, crack_band=None)
        runs.append(rb.load_path(beam, 0.004, 4, Settings(), self_weight=q))
    (a, b) = runs
    assert b["P"][0] == pytest.approx(0.0, abs=1e-9 * a["P"][-1])
    assert np.allclose(b["P"], a["P"], rtol=1e-9) and np.allclose(b["delta"], a["delta"], rtol=1e-9)
    with pytest.raises(ValueError, match="self_weight must be"):
        rb.load_path(rb.build_four_point(sec, G["span"], G["a"], 2, 2), 0.004, 2, self_weight=-1.0)
