"""The strength-reduction factor of safety (ssi.limit.strength_reduction, issue 46): a slope's own factor
under its weight alone, a vertical cut, and every conic status read for what it means.

References (not produced by the code under test):
- a 2:1 slope (26.57 deg) of height H on a rough rigid base at its toe level (depth factor D = 1), phi = 20
  deg, c / (gamma H) = 0.05, dry: Bishop & Morgenstern's charts (limit equilibrium, 1960) F = 1.380;
  Griffiths & Lane (1999, Geotechnique 49(3), their first example, elasto-plastic strength reduction with
  psi = 0) F = 1.40. Neither is a bound of the associated collapse factor: Bishop's circles and the
  elasto-plastic non-convergence criterion each differ from it by about 1 %. The assertion is that the
  certified bracket overlaps [1.38, 1.40] (F_L <= 1.40 and F_U >= 1.38) at a gap (F_U - F_L) / (F_U +
  F_L) <= 4 % here (a coarse mesh keeps `make test` short; chapter 17's `fos_slope_2to1` asks 1 % in full
  mode): a bracket that missed the range would contradict both references by more than their own spread.
- a vertical cut of height H in Tresca soil (c = s_u) over a deep stratum: the stability number gamma H /
  c at collapse lies in [3.772, 3.776] (Pastor, Thai & Francescato 2003, Int. J. Numer. Anal. Meth.
  Geomech. 27: rigorous lower and upper bounds). For phi = 0 strength reduction divides c alone, so F* =
  N_s c / (gamma H) exactly; any rigorous bracket contains F*, so F_L <= 3.776 c / (gamma H) and F_U >=
  3.772 c / (gamma H) must hold with no tolerance beyond the solver's (REL).
"""

import math

import numpy as np
import pytest

from ssi.limit import Boundary, Material, Site, lower_bound, strength_reduction, triangulate, upper_bound

REL = 1e-6


def slope_site(H=10.0, c_ratio=0.05, phi=20.0, gamma=20e3, n=2.0, back=3.0, crest_load=0.0):
    """A 1:n slope on a rough rigid base at the toe's level (D = 1): the toe at (0, 0), the crest at (n H,
    H), the ground behind it to x = (n + back) H (a vertical roller there). ``crest_load`` [Pa]: a
    reference pressure on the ground behind the crest (its first H)."""
    L = (n + back) * H
    top = Boundary("free")
    if crest_load:
        pts = [(0.0, 0.0), (L, 0.0), (L, H), ((n + 1) * H, H), (n * H, H)]
        segs = [(0, 1, Boundary("fixed")), (1, 2, Boundary("symmetry")), (2, 3, top)]
        segs += [(3, 4, Boundary("free", pressure_ref=crest_load)), (4, 0, top)]
    else:
        pts = [(0.0, 0.0), (L, 0.0), (L, H), (n * H, H)]
        segs = [(0, 1, Boundary("fixed")), (1, 2, Boundary("symmetry")), (2, 3, top), (3, 0, top)]
    mat = Material(c_ratio * gamma * H, phi, gamma)
    return Site(np.array(pts, float), tuple(segs), ((L - 1.0, 0.5 * H, 0),), (mat,))


def cut_site(H=5.0, c=40e3, gamma=20e3):
    """A vertical cut of height H: the face at x = 0 from z = 0 to H, the soil behind it to x = 2.5 H and
    below the toe to z = -H, in front of it to x = -1.5 H (rollers at the far sides, a rough base)."""
    W, L, D = 1.5 * H, 2.5 * H, 1.0 * H
    pts = [(-W, -D), (L, -D), (L, H), (0.0, H), (0.0, 0.0), (-W, 0.0)]
    free = Boundary("free")
    segs = [(0, 1, Boundary("fixed")), (1, 2, Boundary("symmetry")), (2, 3, free), (3, 4, free)]
    segs += [(4, 5, free), (5, 0, Boundary("symmetry"))]
    return Site(np.array(pts, float), tuple(segs), ((L - 0.5, 0.0, 0),), (Material(c, 0.0, gamma),))


def graded(points, h_min, slope=0.3):
    pts = np.asarray(points, float)

    def size(p):
        d = np.min(np.hypot(p[:, None, 0] - pts[None, :, 0], p[:, None, 1] - pts[None, :, 1]), axis=1)
        return h_min + slope * d

    return size


def test_slope_2to1_own_factor_of_safety():
    """fos_slope_2to1: the slope under its weight alone (no load to scale: lambda multiplies the weight)."""
    site = slope_site()
    mesh = triangulate(site, 2.5, size=graded([(0.0, 0.0), (20.0, 10.0)], 1.0))
    res = strength_reduction(site, mesh, gap=0.04)
    assert res.converged, res.summary()
    assert res.f_lower <= 1.40 and res.f_upper >= 1.38, res.summary()
    assert res.gap <= 0.04
    # every proven trial sits on its side of the bracket: safe ones at or below F_L, unsafe at or above F_U
    for t in res.trials:
        if t["proven"] and t["bound"] == "lb":
            assert t["F"] <= res.f_lower * (1 + REL)
        if t["proven"] and t["bound"] == "ub":
            assert t["F"] >= res.f_upper * (1 - REL)


def test_vertical_cut_stability_number():
    """fos_vertical_cut: a vertical face; F* = N_s c / (gamma H) with N_s in [3.772, 3.776]."""
    H, c, gamma = 5.0, 40e3, 20e3
    r = c / (gamma * H)  # 0.4: F* = 1.509 .. 1.510
    site = cut_site(H, c, gamma)
    mesh = triangulate(site, H / 2.0, size=graded([(0.0, 0.0), (0.0, H)], H / 12.0))
    res = strength_reduction(site, mesh, gap=0.05)
    assert res.f_lower <= 3.776 * r * (1 + REL) and res.f_upper >= 3.772 * r * (1 - REL), res.summary()
    assert res.converged and res.gap <= 0.05, res.summary()
    # as a stability number: gamma H / c at collapse in [F_L, F_U] / r
    assert res.f_lower / r <= 3.776 and res.f_upper / r >= 3.772


def test_statuses_read_for_what_they_mean():
    """Dead loads held (loads="ref"), the weight alone collapsing the reduced slope: the upper-bound program
    is unbounded (its status DualInfeasible) and its ray is a mechanism proving collapse; the lower-bound
    program has no admissible field (infeasible), which proves nothing and certifies nothing. Neither is
    read as "nothing fails"; both modes then give overlapping brackets."""
    site = slope_site(crest_load=1e3)
    mesh = triangulate(site, 2.5, size=graded([(0.0, 0.0), (20.0, 10.0)], 0.8))
    weak = site.reduced(3.0)  # F = 3, about twice the slope's factor
    up = upper_bound(weak, mesh)
    assert "DualInfeasible" in up.status
    assert not up.certified and up.collapse_proven(1.0)
    lo = lower_bound(weak, mesh)
    assert not lo.certified and math.isnan(lo.lam)
    ref = strength_reduction(site, mesh, gap=0.08, loads="ref", max_steps=0)
    allm = strength_reduction(site, mesh, gap=0.08, loads="all", max_steps=0)
    assert np.isfinite(ref.f_upper) and ref.f_lower > 1.0
    assert max(ref.f_lower, allm.f_lower) <= min(ref.f_upper, allm.f_upper) * (1 + REL)
    # the crest load is small: both near the slope's own factor
    assert 1.2 < ref.f_lower and ref.f_upper < 1.7


def test_gravity_alone_needs_the_all_loads_mode():
    site = slope_site()
    mesh = triangulate(site, 5.0)
    with pytest.raises(ValueError, match="no reference load"):
        strength_reduction(site, mesh, loads="ref", max_steps=0)
    res = strength_reduction(site, mesh, gap=0.1, max_steps=0)
    assert 0.0 < res.f_lower <= res.f_upper < np.inf


def test_weightless_unloaded_site_is_refused():
    site = slope_site(gamma=0.0, c_ratio=0.0)
    with pytest.raises(ValueError):
        strength_reduction(site, triangulate(site, 5.0), max_steps=0)


def test_adaptive_says_why_it_stopped():
    """ssi limit's diagnostics at the limit level: a missed gap names the cap and the bound that stalled."""
    from ssi.limit import Interface, adaptive, strip_site

    site = strip_site(2.0, Material(10e3, 0.0), Interface("rough"))
    mesh = triangulate(site, 1.5)
    res = adaptive(site, mesh, gap=1e-4, max_steps=1)
    assert not res.converged and res.reason.startswith("refinement cap (max_steps = 1) at gap")
    res = adaptive(site, mesh, gap=0.5)
    assert res.converged and res.reason == "gap reached"
    assert res.stalled() == {"lb": False, "ub": False}  # too few meshes to say


def prandtl_weightless(c, phi_deg, q):
    """Prandtl's bearing pressure of a strip on weightless soil with surcharge q: c N_c + q N_q [Pa]
    (N_q = e^(pi tan phi) tan^2(45 + phi/2), N_c = (N_q - 1) cot phi; exact, rough or smooth)."""
    t = math.tan(math.radians(phi_deg))
    nq = math.exp(math.pi * t) * math.tan(math.radians(45.0 + phi_deg / 2.0)) ** 2
    return c * (nq - 1.0) / t + q * nq


def test_surcharge_that_outgrows_the_load_is_read_as_safe():
    """Every load scaled together, a surcharge whose q N_q (426 kPa) exceeds twice the footing pressure
    (200 kPa) makes lambda_all unbounded at F = 1 (the lower-bound program's status DualInfeasible): that
    is safe, not "no proof" (which sent the search down to F < 0.5, where tan(phi) / F passes 60 deg:
    make demo's scene). The factor is the F* where the reduced Prandtl pressure (c / F) N_c + q N_q of
    tan(phi) / F equals the load, found here by bisection of the closed form."""
    from ssi.limit import strip_site

    c, phi, q, p = 5e3, 25.0, 40e3, 200e3
    lo, hi = 1.0, 3.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        phi_f = math.degrees(math.atan(math.tan(math.radians(phi)) / mid))
        lo, hi = (mid, hi) if prandtl_weightless(c / mid, phi_f, q) > p else (lo, mid)
    f_star = 0.5 * (lo + hi)
    site = strip_site(2.0, Material(c, phi), half_width=8.0, depth=5.0, surcharge=q, load_ref=(0.0, -p))
    mesh = triangulate(site, 2.0, size=graded([(1.0, 0.0)], 0.15))
    first = lower_bound(site.all_loads(), mesh)
    assert "DualInfeasible" in first.status  # the case this test is about
    res = strength_reduction(site, mesh, gap=0.08)
    assert res.converged, res.summary()
    assert res.f_lower <= f_star * (1 + REL) and res.f_upper >= f_star * (1 - REL), (f_star, res.summary())
