"""ssi.limit: a beam's M-N interaction (its hinges' capacity as a polygon in (N, M)) and a Coulomb interface's
tension cut-off, each against a hand value computed here, not by the code under test.

References:
- a strip bridging a trench (chapter 17's `fela_beam_mechanism`: span l = 4 m, columns at x = +-a = +-1 m,
  near-rigid Tresca soil s_u = 20 MPa beyond the trench) on a frictionless no-tension contact (c_i = 0,
  phi_i = 0, t_i = 0: the contact carries no shear, so the beam's axial force is exactly the applied end
  force -P), under two columns lambda N_ref: the four-point-bending mechanism (Heyman, Plastic design of
  frames, 1971) with sagging hinges under the columns that rotate and extend normal to the M-N polygon
  gives N_beam = M_p(-P) / (l/2 - a) (the virtual work of P on the hinges' extension is what turns the
  support function into M_p at N = -P); the soil beside each trench edge carries the reaction over a
  width delta = N / (2 s_u), so the exact load lies in [N_beam / (1 + eps), N_beam], eps = delta / (2 (l/2
  - a)) (chapter 17);
- M_p(N) of chapter 11's section (0.4 m, 15 cm^2/m bars top and bottom at 5 cm, f_ck 30 MPa, f_y 500 MPa)
  by the rectangular stress block of EN 1992-1-1 §3.1.7 (3) (depth 0.8 x at f_ck, eps_cu = 3.5e-3, bars
  elastic-perfectly plastic, E_s = 200 GPa), the moment about the base: M_base = M_mid + P h / 2;
- pull-out of a rigid footing (B = 2 m) bonded by a Coulomb joint with cut-off t_i over far stronger soil,
  held down by N: T = N + t_i B (the joint opens uniformly; without a cut-off its apex c_i / tan phi_i is
  the tension limit);
- overturning of the same footing under N about its edge with the soil far stronger: the compression
  N + t_i B concentrates at the edge (width delta = (N + t_i B) / ((2 + pi) s_u), a Prandtl strip at the
  edge) and the cut-off's tension t_i acts on the whole base: M = (N + t_i B) (B - delta) / 2, bracketed
  by [(N + t_i B) (B - delta) / 2, (N + t_i B) B / 2].
Each bound is rigorous for its mesh, so LB <= exact <= UB holds to the solver's relative accuracy REL
(1e-6, Clarabel's tolerances 1e-9).
"""

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from ssi.capacity import strip_beam_interaction
from ssi.lab.examples import chapter11_section
from ssi.limit import Beam, Boundary, Footing, Interface, Material, Site, bracket, strip_site, triangulate

REL = 1e-6
HALF_L, A_COL, X_S, S_U, N_REF = 2.0, 1.0, 3.0, 20e6, 100e3


@pytest.fixture(scope="module")
def interaction():
    return strip_beam_interaction(chapter11_section())


def block_mp(P: float) -> float:
    """M_p sagging [N m/m] about the base of chapter 11's section under an axial compression P [N/m] by the
    rectangular stress block (module docstring)."""
    fck, fy, es, a_s, ecu = 30e6, 500e6, 200e9, 1.5e-3, 3.5e-3

    def parts(x):
        s_top = max(min(es * ecu * (x - 0.05) / x, fy), -fy)
        s_bot = min(es * ecu * (0.35 - x) / x, fy)
        return 0.8 * x * fck, s_top, s_bot

    x = brentq(lambda x: parts(x)[0] + a_s * (parts(x)[1] - parts(x)[2]) - P, 0.01, 0.4)
    c, s_top, s_bot = parts(x)
    return c * (0.2 - 0.4 * x) + a_s * (s_top + s_bot) * 0.15 + P * 0.2


def test_the_sections_interaction_is_the_rectangular_blocks(interaction):
    """ssi's M_Rd(N) (parabola-rectangle, layered) about the base against the rectangular block: within
    1 % (measured 0.3 %: the two stress blocks' difference) at N = 0 and the sampled compressions; the
    polygon contains N = 0 and the hogging side mirrors the sagging one (a symmetric section) with the
    base's lever arm: M_sag(N) - M_hog(N) = -2 N h / 2."""
    pts = np.array(interaction)
    assert 0.0 in pts[:, 0] and pts[0, 0] < -0.9e6 and pts[-1, 0] > 0.5e6
    for n, ms, mh in pts[pts[:, 0] <= 0.0]:
        assert ms == pytest.approx(block_mp(-n), rel=0.01)
        assert ms - mh == pytest.approx(-2.0 * n * 0.2, rel=1e-6, abs=1e-6 * ms)


def test_facets_are_the_hull_of_the_points():
    """A polygon from five points: the facets hold at every point with equality on the hull, a point
    above the hull violates one; with its N = 0 point only it is the strip -mp_hog <= M <= mp_sag."""
    pts = ((-1000.0, 50.0, 40.0), (-500.0, 150.0, 100.0), (0.0, 100.0, 80.0), (300.0, 90.0, 30.0),
           (600.0, 0.0, 0.0))  # fmt: skip
    b = Beam(0.0, 1.0, 100.0, 80.0, interaction=pts)
    f = b.facets()
    for n, ms, mh in pts:
        for m in (ms, -mh):
            assert np.all(f[:, 0] * n + f[:, 1] * m <= f[:, 2] * (1 + 1e-12))
    # (0, 100) lies below the chord from (-500, 150) to (300, 90): the hull passes above it at 112.5
    assert np.max(f[:, 0] * 0.0 + f[:, 1] * 112.5 - f[:, 2]) == pytest.approx(0.0, abs=1e-9)
    assert np.max(f[:, 0] * 0.0 + f[:, 1] * 113.0 - f[:, 2]) > 0.0
    strip = Beam(0.0, 1.0, 100.0, 80.0, interaction=((0.0, 100.0, 80.0),))
    assert not strip.axial and np.array_equal(strip.facets(), [[0.0, 1.0, 100.0], [0.0, -1.0, 80.0]])
    with pytest.raises(ValueError, match=r"interaction needs exactly one point at N = 0"):
        Beam(0.0, 1.0, 100.0, 80.0, interaction=((1.0, 100.0, 80.0),))


def test_the_n0_point_alone_reproduces_the_old_beam():
    """A beam on Tresca soil (chapter 17's rough test strip) with M_p at N = 0 given as its interaction's
    only point: both bounds bit-identical to the beam without an interaction."""
    itf = Interface("rough")
    site = strip_site(2.0, Material(10e3, 0.0), itf, half_width=4.0, depth=3.0, symmetric=False,
                      base_points=(-0.5, 0.5))  # fmt: skip
    loads = ((-0.5, 0.0, -0.5, 0.0), (0.5, 0.0, -0.5, 0.0))
    mesh = None
    out = []
    for inter in ((), ((0.0, 1e3, 1e3),)):
        beam = Beam(-1.0, 1.0, 1e3, 1e3, loads_ref=loads, interaction=inter)
        s = replace(site, footings=(Footing(itf, moves=("x", "z", "r"), centre=(0.0, 0.0), beam=beam),))
        mesh = mesh or triangulate(s, 1.0, size=lambda p: 0.5 + 0.3 * np.abs(np.abs(p[:, 0]) - 1.0))
        out.append(bracket(s, mesh))
    assert out[0].lb == out[1].lb and out[0].ub == out[1].ub


def trench_site(P: float, inter: tuple) -> Site:
    pts = [(-6.0, -4.0), (6.0, -4.0), (6.0, 0.0), (X_S, 0.0), (HALF_L, 0.0), (HALF_L, -1.0), (-HALF_L, -1.0),
           (-HALF_L, 0.0), (-X_S, 0.0), (-6.0, 0.0)]  # fmt: skip
    free, foot = Boundary("free"), Boundary("footing", footing=0)
    segs = ((0, 1, Boundary("fixed")), (1, 2, Boundary("symmetry")), (2, 3, free), (3, 4, foot), (4, 5, free),
            (5, 6, free), (6, 7, free), (7, 8, foot), (8, 9, free), (9, 0, Boundary("symmetry")))  # fmt: skip
    itf = Interface("coulomb", c=0.0, phi_deg=0.0, tension=0.0)  # frictionless, no tension
    mp0 = next(p for p in inter if p[0] == 0.0)
    beam = Beam(-X_S, X_S, mp0[1], mp0[2], interaction=inter,
                loads_ref=((-A_COL, 0.0, -N_REF, 0.0), (A_COL, 0.0, -N_REF, 0.0)),
                loads_dead=((-X_S, P, 0.0, 0.0), (X_S, -P, 0.0, 0.0)))  # fmt: skip
    return Site(np.array(pts), segs, ((0.0, -3.0, 0),), (Material(S_U, 0.0),),
                (Footing(itf, moves=("x", "z", "r"), centre=(0.0, 0.0), beam=beam),))  # fmt: skip


def test_an_axial_force_moves_the_beam_mechanisms_bracket(interaction):
    """The trench beam (module docstring) under an axial compression P = 500 kN/m and a tension 300 kN/m
    applied at its ends: each bracket meets the hand interval [N_beam / (1 + eps), N_beam] with N_beam =
    M_p(-P) / (l/2 - a), M_p(-P) the polygon's (within 1 % of the rectangular block's at P = 500 kN/m:
    a fact of the section, tested above), and the compression raises both bounds above the unloaded
    beam's bracket, the tension lowers both below it (M_p(N = 0) = 257 kN m/m, M_p(-500 kN/m) = 435, M_p(300
    kN/m) = 150). The UB is the hand mechanism's load (measured within 5e-6); the LB on this coarse mesh
    (244 triangles) 0.92 of it (the soil's reaction beside the trench edge is not resolved)."""
    pts = np.array(interaction)

    def size(p):
        d = np.min([np.hypot(p[:, 0] - x, p[:, 1]) for x in (-HALF_L, HALF_L, -X_S, X_S)], axis=0)
        return 0.2 + 0.4 * d

    mesh, out = None, {}
    for P in (0.0, 500e3, -300e3):
        site = trench_site(P, interaction)
        mesh = mesh or triangulate(site, 1.0, size=size)
        br = bracket(site, mesh)
        assert br.lower.certified and br.upper.certified, br.lower.reason
        n_beam = np.interp(-P, pts[:, 0], pts[:, 1]) / (HALF_L - A_COL)
        eps = n_beam / (2 * S_U) / (2 * (HALF_L - A_COL))
        lb, ub = br.lb * N_REF, br.ub * N_REF
        assert lb <= n_beam * (1 + REL) and ub >= n_beam / (1 + eps) * (1 - REL)
        assert ub <= n_beam * 1.001  # the mechanism is found (measured 1 + 4e-6)
        out[P] = (lb, ub)
    assert np.interp(-500e3, pts[:, 0], pts[:, 1]) == pytest.approx(block_mp(500e3), rel=0.01)
    assert out[500e3][0] > out[0.0][1] and out[-300e3][1] < out[0.0][0]


def test_a_tension_cut_off_bounds_the_pull_out():
    """Pull-out of a footing held down by N = 10 kN/m on a Coulomb joint (c_i = 5 kPa, phi_i = 25 deg) over
    far stronger soil (s_u = 1 MPa): bracket contains N + t_i B for t_i = 0, 2 kPa and no cut-off (the apex
    c_i / tan phi_i = 10.7 kPa), each within 1e-3 (measured 2e-5 on 113 triangles: the mechanism is the
    joint's opening, exact on any mesh; the lower bound's margin 1e-4 bounds the gap)."""
    N = 10e3
    for t in (0.0, 2e3, None):
        itf = Interface("coulomb", c=5e3, phi_deg=25.0, tension=t)
        site = strip_site(2.0, Material(1e6, 0.0), itf, half_width=4.0, depth=3.0, symmetric=False)
        site = replace(site, footings=(Footing(itf, (0.0, 1.0), (0.0, -N), ("x", "z")),))
        br = bracket(site, triangulate(site, 2.0, size=lambda p: 0.6 + 0.3 * np.abs(np.abs(p[:, 0]) - 1.0)))
        exact = N + (5e3 / math.tan(math.radians(25.0)) if t is None else t) * 2.0
        assert br.lower.certified and br.upper.certified, br.lower.reason
        assert br.lb <= exact * (1 + REL) and br.ub >= exact * (1 - REL)
        assert br.ub / br.lb - 1.0 < 1e-3


def test_a_tension_cut_off_bounds_the_overturning_moment():
    """The footing under N = 10 kN/m overturned by lambda (clockwise moment 1 N m/m) on s_u = 1 MPa soil:
    brackets contain the hand interval (module docstring) for t_i = 0 and 2 kPa, and they are apart:
    the cut-off governs the moment (M = 10 and 14 kN m/m)."""
    N, B = 10e3, 2.0
    out = {}
    for t in (0.0, 2e3):
        itf = Interface("coulomb", c=5e3, phi_deg=25.0, tension=t)
        site = strip_site(B, Material(1e6, 0.0), itf, half_width=4.0, depth=3.0, symmetric=False)
        ft = Footing(itf, (0.0, 0.0), (0.0, -N), ("x", "z", "r"), centre=(0.0, 0.0), moment_ref=-1.0)
        site = replace(site, footings=(ft,))
        br = bracket(site, triangulate(site, 1.0, size=lambda p: 0.3 + 0.3 * np.abs(np.abs(p[:, 0]) - 1.0)))
        c = N + t * B
        delta = c / ((2.0 + math.pi) * 1e6)
        assert br.lower.certified and br.upper.certified, br.lower.reason
        assert br.lb <= c * B / 2 * (1 + REL) and br.ub >= c * (B - delta) / 2 * (1 - REL)
        out[t] = br
    assert out[0.0].ub < out[2e3].lb


def test_bounds_solved_side_by_side_are_the_serial_ones():
    """bracket(threads=2) solves the two programs at once: the same numbers, bit for bit, as one after the
    other (each program is solved alone); bad input is named."""
    itf = Interface("coulomb", c=5e3, phi_deg=25.0, tension=1e3)
    site = strip_site(2.0, Material(10e3, 20.0), itf, half_width=4.0, depth=3.0, symmetric=False)
    mesh = triangulate(site, 1.0, size=lambda p: 0.4 + 0.3 * np.abs(np.abs(p[:, 0]) - 1.0))
    one, two = bracket(site, mesh, threads=1), bracket(site, mesh, threads=2)
    assert one.lb == two.lb and one.ub == two.ub
    with pytest.raises(ValueError, match=r"threads"):
        bracket(site, mesh, threads=3)
    with pytest.raises(ValueError, match=r"tension of an Interface needs kind 'coulomb', got kind='rough'"):
        Interface("rough", tension=0.0)
    with pytest.raises(ValueError, match=r"tension"):
        Interface("coulomb", c=1e3, phi_deg=20.0, tension=-1.0)
    # a cut-off above the joint's apex c / tan phi changes nothing: clipped to the apex
    assert Interface("coulomb", c=1e3, phi_deg=45.0, tension=5e3).tension == pytest.approx(1e3)
