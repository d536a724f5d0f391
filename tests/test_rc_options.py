"""Crack-spacing band (fib Model Code 2010) and the section options a scene's Foundation passes to its strip.

The MC2010 numbers are worked by hand from eq. (7.6-4) (k = 1, tau_bms = 1.8 fctm) and Fig. 7.6-4; round-off
only (1e-12)."""

import math

import numpy as np
import pytest

from ssi.elements.section import rc_section, with_crack_spacing_band
from ssi.materials.concrete import P_ALPHA_TS, P_LS, P_PLANE
from ssi.materials.layer_laws import CONCRETE, STEEL
from ssi.materials.rc import concrete_params, crack_spacing_mc2010, designer_concrete, steel_params
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer


def test_crack_spacing_mc2010_by_hand():
    # rho = 1e-3/0.45; alpha_e rho = 6 rho; x = d alpha_e rho (sqrt(1 + 2/(alpha_e rho)) - 1) = 0.0677 m;
    # h_c,ef = min(2.5 * 0.05, (0.5 - x)/3, 0.25) = 0.125; rho_ef = 0.008; l = 0.03 + 0.02/(7.2*0.008)
    out = crack_spacing_mc2010(0.03, 0.02, 1e-3, 1.0, 0.5, 0.45, 6.0)
    ar = 6.0 * 1e-3 / 0.45
    assert out["x"] == pytest.approx(0.45 * ar * (math.sqrt(1 + 2 / ar) - 1), rel=1e-12)
    assert out["h_c_ef"] == pytest.approx(0.125, rel=1e-12)
    assert out["s_r_max"] == pytest.approx(2 * (0.03 + 0.02 / (7.2 * 0.008)), rel=1e-12)
    # (h - x)/3 governs for a shallow bar layer in a deep section of high ratio
    assert crack_spacing_mc2010(0.03, 0.02, 5e-3, 1.0, 0.3, 0.25, 6.0)["h_c_ef"] < 0.125
    with pytest.raises(ValueError, match="phi"):
        crack_spacing_mc2010(0.03, -0.02, 1e-3, 1.0, 0.5, 0.45, 6.0)
    with pytest.raises(ValueError, match="d must be below"):
        crack_spacing_mc2010(0.03, 0.02, 1e-3, 1.0, 0.5, 0.55, 6.0)


def _rc(cover_top=0.05):
    d = designer_concrete(38e6)
    conc = (CONCRETE, concrete_params(38e6, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, 500e6 / 200e9))
    return rc_section(0.4, [(0.05, 1.5e-3), (0.4 - cover_top, 0.8e-3)], conc, (STEEL, steel_params(500e6)))


def test_crack_spacing_band_per_face():
    sec, faces = with_crack_spacing_band(_rc(), 0.016)
    conc = np.flatnonzero(sec.kind == CONCRETE)
    low = conc[sec.z_mid[conc] < 0.0]
    high = conc[sec.z_mid[conc] >= 0.0]
    assert np.all(sec.params[low, P_LS] == faces[0]["s_r_max"])
    assert np.all(sec.params[high, P_LS] == faces[1]["s_r_max"])
    assert faces[1]["s_r_max"] > faces[0]["s_r_max"]  # fewer top bars: wider spacing
    alpha_e = 200e9 / designer_concrete(38e6)["E0"]
    by_hand = crack_spacing_mc2010(0.05 - 0.008, 0.016, 1.5e-3, 1.0, 0.4, 0.35, alpha_e)
    assert faces[0]["s_r_max"] == pytest.approx(by_hand["s_r_max"], rel=1e-12)
    with pytest.raises(ValueError, match="bar_diameter"):
        with_crack_spacing_band(_rc(), 0.0)


def _scene(**options):
    return Scene(
        width=12.0,
        depth=4.0,
        layers=[SoilLayer(4.0, E=20e6, nu=0.3)],
        foundation=Foundation(x0=-1.0, x1=1.0, section=_rc(), **options),
        contact=Contact(kn=4e9, kt=4e8),
        loads=[ColumnLoad(x=0.0, N=100e3)],
        mesh=MeshSize(h_fine=0.5, h_coarse=2.0),
    )


def test_foundation_options_reach_the_strip():
    plate = _scene().build().plate
    assert plate.self_bending == "chord" and plate.crack_band is None
    ls = plate.section.params[plate.section.kind == CONCRETE, P_LS]
    expected = with_crack_spacing_band(_rc(), 0.016)[0].params[plate.section.kind == CONCRETE, P_LS]
    assert np.array_equal(ls, expected) and not np.any(ls == 0.1)
    paper = _scene(crack_band="point", self_bending="initial", kappa=1.0, integration="full").build().plate
    assert paper.crack_band == "point" and paper.self_bending == "initial"
    assert paper.kappa == 1.0 and paper.integration == "full"
    own = _scene(crack_band=None).build().plate
    assert np.all(own.section.params[own.section.kind == CONCRETE, P_LS] == 0.1)
    # plane strain by default (eq. 4.4, like the elastic layers); plane_strain=False keeps the section's own
    conc = plate.section.kind == CONCRETE
    assert np.all(plate.section.params[conc, P_PLANE] == 1.0)
    stress = _scene(plane_strain=False).build().plate
    assert np.all(stress.section.params[conc, P_PLANE] == 0.0)
    # tension stiffening only within h_c,ef of a face with bars
    area = _scene(tension_stiffening="effective_area").build().plate.section
    expected = with_crack_spacing_band(_rc(), 0.016, "effective_area")[0]
    assert np.array_equal(area.params[conc, P_ALPHA_TS], expected.params[conc, P_ALPHA_TS])
    assert np.any(area.params[conc, P_ALPHA_TS] == 0.0) and np.any(area.params[conc, P_ALPHA_TS] == 0.5)
    with pytest.raises(ValueError, match="crack_band"):
        _scene(crack_band="element").build()


def test_crack_spacing_does_not_depend_on_how_a_bar_layer_is_split():
    """A layer-count refinement (ssi.scene.estimate.split_section) splits each bar layer into thinner steel
    layers; the MC2010 spacing must still see one bar layer of the same area and centroid (before, each
    half-layer counted as a bar of half the area, and the band grew past the snap-back limit)."""
    from ssi.elements.section import rc_section, with_crack_spacing_band
    from ssi.materials.layer_laws import CONCRETE, STEEL
    from ssi.materials.rc import concrete_params, designer_concrete, steel_params
    from ssi.scene.estimate import split_section

    d = designer_concrete(38e6)
    concrete = (CONCRETE, concrete_params(38e6, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, 500e6 / 200e9))
    sec = rc_section(
        0.4, [(0.05, 1.5e-3), (0.35, 1.5e-3)], concrete, (STEEL, steel_params(500e6, 200e9)), n_concrete=9
    )
    base = [f["s_r_max"] for f in with_crack_spacing_band(sec, 0.016)[1]]
    for factor in (2, 4):
        split = [f["s_r_max"] for f in with_crack_spacing_band(split_section(sec, factor), 0.016)[1]]
        assert split == pytest.approx(base, rel=1e-12)
