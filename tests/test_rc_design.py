"""Issue 33, items 2-4: crack width (EN 1992-1-1 7.3.4), M_Rd(N), V_Rd,c (6.2.2), brittle flag, and the design
view of a solved scene.

Each reference is worked by hand here from the code's equations as printed in EN 1992-1-1, not from
``ssi.elements.rc_design``: the cracked elastic section in closed form (N = 0: the neutral axis of the
transformed section, sigma_s = alpha M (d - x) / I_cr), eq. (7.8)-(7.11), eq. (6.2a/b) and the rectangular
stress block (lambda = 0.8, eta = 1, eps_cu3 = 0.0035) with strain compatibility of the compression bars.
Tolerances: round-off (1e-9) where the same formula is evaluated by both; 2 % for the rectangular block
against the Sargin curve of eq. (5.1) integrated by the layered analysis (a different stress block: the
issue's tolerance)."""

import math
import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

from ssi.elements.rc_design import RCDesign, cracked_section, vrdc_ec2
from ssi.elements.section import PlainConcreteWarning
from ssi.lab.rc_sections import issue_section

AS1 = math.pi * 0.016**2 / 4 / 0.15  # phi16@150 bottom [m^2/m]
AS2 = math.pi * 0.012**2 / 4 / 0.20  # phi12@200 top
H, D1, D2 = 0.6, 0.6 - 0.058, 0.056  # depth, effective depth, top bars from the top face [m]


@pytest.fixture(scope="module")
def design():
    return RCDesign(issue_section(), (0.016, 0.012))


def test_crack_width_by_hand(design):
    M = 250e3  # [N m/m], N = 0
    ec, es = design.Ec, 200e9
    a = es / ec
    # neutral axis of the cracked transformed section: Ec x^2/2 = Es [As1 (d1 - x) + As2 (d2 - x)]
    x = brentq(lambda x: 0.5 * x * x - a * (AS1 * (D1 - x) + AS2 * (D2 - x)), 1e-6, H)
    i_cr = x**3 / 3 + a * (AS1 * (D1 - x) ** 2 + AS2 * (D2 - x) ** 2)  # per Ec
    sig_s = a * M * (D1 - x) / i_cr
    h_c_ef = min(2.5 * (H - D1), (H - x) / 3, H / 2)
    rho = AS1 / h_c_ef
    fct = design.fctm
    eps = max((sig_s - 0.4 * fct / rho * (1 + a * rho)) / es, 0.6 * sig_s / es)  # eq. (7.9)
    s_r = 3.4 * 0.050 + 0.8 * 0.5 * 0.425 * 0.016 / rho  # eq. (7.11), spacing 150 < 5 (c + phi/2)
    w = s_r * eps
    got = design.crack_width(0.0, M)
    assert got["x"] == pytest.approx(x, rel=1e-9)
    assert got["sig_s"] == pytest.approx(sig_s, rel=1e-9)
    assert got["w_k"] == pytest.approx(w, rel=1e-9)
    assert 0.2e-3 < w < 0.6e-3  # a plausible service crack width for ~ 330 MPa in the bars
    # hogging: the top face's phi12 at 200 mm < 5 (50 + 6) mm: eq. (7.11) with the top bars
    top = design.crack_width(0.0, -100e3)
    assert top["face"] == "top"
    h_top = min(2.5 * 0.056, (H - top["x"]) / 3, H / 2)
    assert top["s_r_max"] == pytest.approx(3.4 * 0.050 + 0.17 * 0.012 * h_top / AS2, rel=1e-12)
    # bars wider apart than 5 (c + phi/2): eq. (7.14) s_r = 1.3 (h - x)
    wide = RCDesign(issue_section(), (0.016, 0.032)).crack_width(0.0, -100e3)
    assert wide["s_r_max"] == pytest.approx(1.3 * (H - wide["x"]), rel=1e-12)


def test_cracked_section_with_axial_force_is_in_equilibrium():
    bars = [(D1, AS1), (D2, AS2)]
    ec, es = 33e9, 200e9
    for N in (-300e3, 0.0, 50e3):
        x, kap, sig = cracked_section(H, ec, es, bars, N, 200e3)
        conc = 0.5 * ec * kap * x * x  # compression resultant [N/m]
        n = AS1 * sig[0] + AS2 * sig[1] - conc
        m = AS1 * sig[0] * (D1 - H / 2) + AS2 * sig[1] * (D2 - H / 2) + conc * (H / 2 - x / 3)
        assert n == pytest.approx(N, abs=1e-6 * 200e3)
        assert m == pytest.approx(200e3, rel=1e-9)


def test_vrdc_by_hand(design):
    k = 1 + math.sqrt(200 / 542)
    rho = AS1 / D1
    v = max(0.18 * k * (100 * rho * 30) ** (1 / 3), 0.035 * k**1.5 * math.sqrt(30))  # [MPa]
    assert design.V_Rd_c(1.0) == pytest.approx(v * 542 * 1000, rel=1e-12)
    # axial compression adds k1 sigma_cp (0.15 * 1 MPa for 600 kN/m over 0.6 m); gamma_c = 1.5 divides C_Rd,c
    v_n = v + 0.15 * 1.0
    assert vrdc_ec2(30e6, D1, rho, -600e3, H) == pytest.approx(v_n * 542e3, rel=1e-12)
    v_d = max(0.12 * k * (100 * rho * 30) ** (1 / 3), 0.035 * k**1.5 * math.sqrt(30))
    assert vrdc_ec2(30e6, D1, rho, gamma_c=1.5) == pytest.approx(v_d * 542e3, rel=1e-12)


def _rect_block(fck, fy, es=200e9, as1=AS1, as2=AS2, d1=D1, d2=D2, h=H):
    def bars2(x):
        s2 = max(min(es * 0.0035 * (x - d2) / x, fy), -fy)
        return s2 - (fck if 0.8 * x > d2 else 0.0)  # the bar displaces concrete of the block

    x = brentq(lambda x: 0.8 * x * fck + as2 * bars2(x) - as1 * fy, 1e-5, h)
    return 0.8 * x * fck * (h / 2 - 0.4 * x) + as2 * bars2(x) * (h / 2 - d2) + as1 * fy * (d1 - h / 2)


def test_mrd_against_rectangular_block(design):
    assert design.M_Rd(0.0) == pytest.approx(_rect_block(30e6, 500e6), rel=0.02)
    # design values: gamma_c = 1.5, gamma_s = 1.15
    dd = RCDesign(issue_section(), (0.016, 0.012), gamma_c=1.5, gamma_s=1.15)
    assert dd.M_Rd(0.0) == pytest.approx(_rect_block(20e6, 500e6 / 1.15), rel=0.02)
    # hogging, the faces swapped
    hog = _rect_block(30e6, 500e6, as1=AS2, as2=AS1, d1=H - 0.056, d2=0.058)
    assert -design.M_Rd(0.0, -1) == pytest.approx(hog, rel=0.02)
    # moderate compression raises M_Rd of an under-reinforced section
    assert design.M_Rd(-500e3) > design.M_Rd(0.0)


def test_brittle_flags(design):
    b = design.brittle()
    assert not b["bottom"]["brittle"]  # 0.25 % bottom: M_y well above M_cr
    assert b["top"]["brittle"]  # 0.10 % top: below the EC2 minimum of 0.15 %
    assert b["bottom"]["M_cr"] == pytest.approx(design.fctm * 1.0 * H**2 / 6, rel=0.05)  # bars add ~3 %
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlainConcreteWarning)
        plain = RCDesign(issue_section(bars=[]))
    pb = plain.brittle()
    assert pb["bottom"]["brittle"] and pb["top"]["brittle"]
    assert plain.M_Rd(0.0) == pytest.approx(pb["bottom"]["M_cr"], rel=1e-12)
    assert plain.crack_width(0.0, 100e3)["w_k"] == 0.0


def test_bad_design_options():
    with pytest.raises(ValueError, match="gamma_c must be in"):
        RCDesign(issue_section(), gamma_c=0.0)
    with pytest.raises(ValueError, match="kt must be 0.4"):
        RCDesign(issue_section(), kt=0.5)


def test_scene_design_view():
    from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scene = Scene(
            width=8.0,
            depth=3.0,
            layers=[SoilLayer(3.0, E=10e6, nu=0.3)],
            foundation=Foundation(x0=-1.2, x1=1.2, section=issue_section(), bar_diameter=0.016),
            contact=Contact(kn=4e9, kt=4e8),
            loads=[ColumnLoad(x=0.0, N=900e3)],
            mesh=MeshSize(h_fine=0.6, h_coarse=2.0),
        )
        out = scene.build().solve(n_steps=2)
    cw = out.crack_width()
    cracked = out.crack_map()["cracked"]
    sec = out.built.plate.section
    low = int(np.argmin(np.where(sec.kind == 1, sec.z_mid, np.inf)))
    f = out.strip_forces()
    sag = f["M"] > 0
    assert np.all(cw["w_k"][sag & ~cracked[..., low]] == 0.0)  # no width where the analysis has no crack
    assert cw["w_k"].max() > 0.0
    s = out.design_summary()
    envelope = max(out.crack_width(k)["w_k"].max() for k in range(len(out.load_factor)))  # over every step
    assert s["w_k_max_mm"] == pytest.approx(1e3 * envelope, rel=1e-12)
    from ssi.scene.design import utilisation

    u = utilisation(out)
    assert np.allclose(u["M"] * u["M_Rd"], np.abs(f["M"]), rtol=1e-12)
    assert s["util_M_max"] >= u["M"].max() - 1e-12  # the maximum over every step includes the last
    assert 0.3 * s["M_Rd_sag_kNm"] < 1e-3 * u["M_Rd"].max() < 2.0 * s["M_Rd_sag_kNm"]
    assert s["brittle"] == {"bottom": False, "top": True}
    from ssi.scene.design import envelopes

    env = envelopes(out)["loading"]
    for key in ("M", "N", "V", "w_k", "sig_s", "p"):
        assert np.all(env[key][0] >= env[key][1])
    assert 1e3 * env["w_k"][0].max() == pytest.approx(s["w_k_max_mm"], rel=1e-12)
    rows = range(out.n_steps + 1)
    assert np.array_equal(env["M"][0], np.max([out.strip_forces(k)["M"] for k in rows], axis=0))
    assert 1e-3 * env["p"][0].max() == pytest.approx(s["phases"]["loading"]["p_max_kPa"], rel=1e-12)
    # the crack width as a field: the ParaView cell data (the widest crack at each element's axial points),
    # the compared quantities of a result file, and the strip-forces plot (a second axis of the M panel)
    from ssi.io.export import FIELD_UNITS, cell_data
    from ssi.io.plot import strip_forces
    from ssi.io.results import scene_quantities

    n_plate = out.built.plate.n_el
    assert (
        np.array_equal(cell_data(out)["crack_width"][1], cw["w_k"].max(axis=1))
        and FIELD_UNITS["crack_width"] == "m"
    )
    assert np.all(np.isnan(cell_data(out)["crack_width"][0]))  # soil cells carry no crack width
    last = len(out.load_factor) - 1
    assert np.array_equal(scene_quantities(out)[f"crack_width[{last}].w_k"], cw["w_k"])
    fig = strip_forces(out)
    lines = [ln for a in fig.axes for ln in a.get_lines() if ln.get_label() == "crack width $w_k$"]
    assert len(lines) == 1 and np.array_equal(lines[0].get_ydata(), 1e3 * cw["w_k"].ravel())
    assert n_plate == cw["w_k"].shape[0]
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_readme_rc_design_lines_are_what_ssi_run_prints():
    """The README's RC design block is the summary `ssi run examples/rc_strip.toml` prints, line for line:
    the numbers a designer reads there (w_k, utilisations, M_Rd) are the run's, not a hand copy gone stale."""
    import os
    import pathlib
    import re

    from ssi.io.cli import summary, summary_text
    from ssi.scene.scene_file import read_scene_file

    root = pathlib.Path(__file__).resolve().parent.parent
    readme = (root / "README.md").read_text()
    block = re.search(r"```text\n(RC design \(EN 1992.*?)```", readme, re.S)
    assert block, "README: the RC design block is missing"
    scene, n_steps, settings = read_scene_file(os.path.join(root, "examples", "rc_strip.toml"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = scene.build().solve(n_steps=n_steps, settings=settings)
    printed = summary_text(summary(out)).splitlines()
    for line in block.group(1).strip().splitlines():
        assert line in printed, f"README line not printed by ssi run: {line!r}"
