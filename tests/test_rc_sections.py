"""Issue 33, item 1: every ordinary section builds with the Foundation defaults and cracks under load.

The regularised band is checked against the two properties that define it (the fracture energy under the
softening line and the distance from the snap-back limit), both closed-form, to round-off (1e-12). The grid's
representative sections are driven past cracking as beams (``ssi.lab.rc_sections``); the whole grid runs in
chapter 18's full mode (row ``rc_sections_grid``)."""

import warnings

import numpy as np
import pytest

from ssi.elements.section import PlainConcreteWarning
from ssi.lab.rc_sections import design_section, grid_case, issue_section, rho_min_ec2, section_grid
from ssi.materials.concrete import P_ALPHA_TS, P_E0, P_FR, P_GF, P_LS
from ssi.materials.layer_laws import CONCRETE, STEEL
from ssi.materials.rc import (
    SNAP_BACK_MARGIN,
    CrackBandWarning,
    designer_concrete,
    regularised_tensile_strength,
    snap_back_limit,
)
from ssi.scene import Foundation


def test_regularised_strength_keeps_fracture_energy_and_softens():
    E0, Gf, fr = 33.5e9, 140.5, 2.9e6
    limit = snap_back_limit(E0, Gf, fr)
    assert regularised_tensile_strength(E0, Gf, fr, 0.5 * limit) == fr  # narrow band: untouched
    for ls in (0.9 * limit, limit, 3.0 * limit):
        fr2 = regularised_tensile_strength(E0, Gf, fr, ls)
        eps_u = 2.0 * Gf / (fr2 * ls)  # end of the softening line of eq. (5.4)
        assert fr2 < fr
        assert 0.5 * fr2 * eps_u * ls == pytest.approx(Gf, rel=1e-12)  # energy per crack kept
        assert ls / snap_back_limit(E0, Gf, fr2) == pytest.approx(SNAP_BACK_MARGIN, rel=1e-12)
        assert eps_u > fr2 / E0  # softens, no snap-back
    with pytest.raises(ValueError, match="ls must be a positive"):
        regularised_tensile_strength(E0, Gf, fr, 0.0)


def test_issue_footing_builds_with_a_warning():
    found = Foundation(x0=-1.2, x1=1.2, section=issue_section(), bar_diameter=0.016)
    with pytest.warns(CrackBandWarning, match=r"top face.*tensile strength is lowered") as rec:
        strip = found.strip_section()
    assert len(rec) == 1  # once per face, not per layer
    conc = np.flatnonzero(strip.kind == CONCRETE)
    top = conc[strip.z_mid[conc] > 0.0]
    bottom = conc[strip.z_mid[conc] < 0.0]
    p_top, p_bot = strip.params[top[0]], strip.params[bottom[0]]
    fr = designer_concrete(38e6)["fr"]
    assert p_bot[P_FR] == fr  # the bottom face's band is below the margin: untouched
    assert p_top[P_FR] < fr
    assert p_top[P_LS] / snap_back_limit(p_top[P_E0], p_top[P_GF], p_top[P_FR]) == pytest.approx(
        SNAP_BACK_MARGIN, rel=1e-12
    )


@pytest.mark.parametrize("case", section_grid(full=False), ids=lambda g: g.label())
def test_representative_sections_crack_and_solve(case):
    out = grid_case(case)
    assert out["completed"], out
    assert out["cracked"], out
    assert out["M_end"] > out["M_cr"]  # carried more than its cracking moment
    assert 0.0 < out["sig_s_max"] < 500e6


def test_plain_concrete_strip_builds_cracks_and_says_brittle():
    sec = issue_section(bars=[])
    assert not np.any(sec.kind == STEEL)
    found = Foundation(x0=-1.2, x1=1.2, section=sec)
    with pytest.warns(PlainConcreteWarning, match="brittle"):
        strip = found.strip_section()
    conc = strip.kind == CONCRETE
    assert np.all(strip.params[conc, P_ALPHA_TS] == 0.0)  # nothing to stiffen a plain crack
    assert np.allclose(strip.params[conc, P_LS], 0.3)  # h / 2
    from ssi.lab.rc_sections import crack_section

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlainConcreteWarning)
        out = crack_section(sec, 0.016, overdrive=1.5)
    assert out["cracked"] and out["completed"]
    assert out["sig_s_max"] == 0.0


@pytest.mark.parametrize(
    ("bars", "match"),
    [
        ([[0.05]], r"bars\[0\] must be a pair"),
        ([(0.05, 1e-3), (0.5, 1e-3, 2)], r"bars\[1\] must be a pair"),
        ([("low", 1e-3)], r"bars\[0\] must hold two numbers"),
        ([(float("nan"), 1e-3)], r"bars\[0\] must hold finite"),
        ("0.05 1e-3", "bars must be a list"),
        (0.05, "bars must be a list"),
    ],
)
def test_malformed_bars_are_named(bars, match):
    with pytest.raises(ValueError, match=match):
        issue_section(bars=bars)


def test_rho_min_and_design_section():
    # EN 1992-1-1 eq. (9.1N): C30/37, fctm = 2.9 MPa: 0.26 * 2.896 / 500 = 0.001506 > 0.0013
    assert rho_min_ec2(30e6) == pytest.approx(0.26 * 0.30 * 30 ** (2 / 3) / 500, rel=1e-12)
    assert rho_min_ec2(12e6) == 0.0013
    sec = design_section(0.6, 30e6, 0.016, 0.05, 0.005, 0.0)
    steel = np.flatnonzero(sec.kind == STEEL)
    assert steel.size == 1
    assert sec.h[steel[0]] == pytest.approx(0.005 * (0.6 - 0.058), rel=1e-12)
