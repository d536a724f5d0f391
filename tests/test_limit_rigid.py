"""Limit analysis with a material that never yields (``Material.rigid_body``: an elastic layer's own
assumption), fans at strip ends checked against the site's segments, and lazy adaptive refinement.

References, none computed by the code under test:
- a rough strip of width B = 2 b on a Tresca layer (c) of thickness H over a base that never yields: the
  base only removes mechanisms, so the collapse load is at least Prandtl's (2 + pi) c B; Prandtl's
  mechanism (a wedge under the strip and a circular fan of radius b sqrt(2) about each edge) reaches the
  depth b sqrt(2), so for H >= b sqrt(2) it is still admissible and the collapse load is exactly
  (2 + pi) c B (Mandel & Salencon's factor is 1 for B/H <= sqrt(2)); a thinner layer squeezed out between
  two rough bodies carries more (their factor grows with B/H), so the certified lower bound of a thin
  layer must rise above (2 + pi) c B;
- on one mesh, a rigid base is a far strong base with the yield condition removed: the lower bound's
  admissible set grows (lb_rigid >= lb_strong) and the upper bound's kinematic set shrinks to rigid
  motions there (ub_rigid >= ub_strong).
Bounds are rigorous per mesh, so the assertions have no tolerance beyond the solver's REL.
"""

import math

import numpy as np
import pytest

from ssi.limit import (
    Boundary,
    Footing,
    Interface,
    Material,
    Site,
    adaptive,
    bisect,
    bracket,
    triangulate,
)
from ssi.limit.mesh import fans_at

REL = 1e-6
SOLVER = 1e-4  # relative accuracy of one program's optimum (not of a certified bound: that is rigorous)
C = 10e3  # [Pa]
PRANDTL_HALF = (2.0 + math.pi) * C * 1.0  # the half model's footing force [N/m]: b = 1 m


def layer_site(H, bottom, depth=3.0):
    """Half of a rough strip (b = 1 m) on a Tresca layer of thickness ``H`` [m] over ``bottom``."""
    pts = np.array([(0, -depth), (6, -depth), (6, -H), (6, 0), (1, 0), (0, 0), (0, -H)], float)
    sym, fixed = Boundary("symmetry"), Boundary("fixed")
    segs = (
        (0, 1, fixed), (1, 2, sym), (2, 3, sym), (3, 4, Boundary("free")),
        (4, 5, Boundary("footing", footing=0)), (5, 6, sym), (6, 0, sym), (6, 2, None),
    )  # fmt: skip
    regions = ((3.0, -H / 2, 0), (3.0, -(H + depth) / 2, 1))
    footing = Footing(Interface("rough"), load_ref=(0.0, -1.0), moves=("z",))
    return Site(pts, segs, regions, (Material(C, 0.0), bottom), (footing,))


def test_deep_layer_on_a_rigid_base_is_prandtl():
    site = layer_site(2.0, Material.rigid_body(gamma=20e3))  # H = 2 m >= sqrt(2) b
    size = lambda p: 0.08 + 0.3 * np.hypot(p[:, 0] - 1.0, p[:, 1])  # noqa: E731
    mesh = triangulate(site, 0.5, size=size, fans=fans_at(site, [(1.0, 0.0)], 0.3, n=7))
    br = bracket(site, mesh)
    assert br.lower.certified, br.lower.reason
    assert br.upper.certified
    assert br.lb <= PRANDTL_HALF * (1 + REL) and br.ub >= PRANDTL_HALF * (1 - REL)
    assert br.gap < 0.05  # a bracket, not two far numbers around it
    # no yield condition in the base: its stresses may leave every cone, none of it dissipates
    rigid = mesh.material == 1
    assert np.all(br.upper.dissipation[rigid] == 0.0)


def test_thin_layer_on_a_rigid_base_carries_more_than_prandtl():
    site = layer_site(0.25, Material.rigid_body())  # B/H = 8
    mesh = triangulate(site, 0.25, size=lambda p: 0.05 + 0.15 * np.hypot(p[:, 0] - 1.0, p[:, 1]))
    br = bracket(site, mesh)
    assert br.lower.certified, br.lower.reason
    assert br.lb > 1.3 * PRANDTL_HALF  # squeezed between two rigid bodies: well above (2 + pi) c B
    if br.upper.certified:
        assert br.ub >= br.lb


def test_rigid_base_against_a_strong_base_on_one_mesh():
    rigid, strong = layer_site(1.0, Material.rigid_body()), layer_site(1.0, Material(1000 * C, 0.0))
    mesh = triangulate(rigid, 0.5, size=lambda p: 0.1 + 0.3 * np.hypot(p[:, 0] - 1.0, p[:, 1]))
    br_r, br_s = bracket(rigid, mesh), bracket(strong, mesh)
    assert br_r.lower.certified and br_s.lower.certified
    # two programs' optima compared, each to the solver's accuracy: without Clarabel's iterative refinement
    # (cohesive soils, ssi.limit.conic) an upper bound's optimum was measured 1.3e-5 above the refined one
    assert br_r.lb >= br_s.lb * (1 - SOLVER)
    assert br_r.ub >= br_s.ub * (1 - SOLVER)


def test_rigid_material_is_not_reduced_nor_davis_and_has_no_strength():
    m = Material.rigid_body(gamma=18e3)
    assert m.rigid and m.reduced(2.0) == m and m.davis() == m and m.associated
    with pytest.raises(ValueError, match="rigid Material has no strength"):
        Material(5e3, 0.0, rigid=True)


def test_fan_rays_along_a_site_segment_are_dropped():
    """A vertical interior segment below a strip's end (a site's cut line): a fan of n = 6 has a ray
    straight down along it, which sent Triangle out of memory (issue 46); it is dropped, the others kept
    (and cut short where they meet the layer line)."""
    pts = np.array([(0, -3), (6, -3), (6, -1), (6, 0), (1, 0), (0, 0), (0, -1), (1, -1)], float)
    sym, fixed = Boundary("symmetry"), Boundary("fixed")
    segs = (
        (0, 1, fixed), (1, 2, sym), (2, 3, sym), (3, 4, Boundary("free")),
        (4, 5, Boundary("footing", footing=0)), (5, 6, sym), (6, 0, sym), (6, 7, None), (7, 2, None),
        (7, 4, None),
    )  # fmt: skip
    site = Site(
        pts, segs, ((3.0, -0.5, 0), (0.5, -0.5, 0), (3.0, -2.0, 1)), (Material(C, 0.0), Material(C, 0.0)),
        (Footing(Interface("rough"), load_ref=(0.0, -1.0), moves=("z",)),),
    )  # fmt: skip
    fans = fans_at(site, [(1.0, 0.0), (0.0, 0.0)], 0.6, n=6)
    assert fans == ((1.0, 0.0, 0.6, 6),)  # the axis point is not on a horizontal stretch of boundary
    mesh = triangulate(site, 1.0, fans=fans)
    new = mesh.xy[len(pts) :]
    ends = new[np.isclose(np.hypot(new[:, 0] - 1.0, new[:, 1]), 0.6)]
    assert len(ends) == 4  # 5 rays, the vertical one dropped
    assert not np.any(np.isclose(ends[:, 0], 1.0))  # none of them straight down


def test_lazy_refinement_keeps_the_bracket_certified():
    site = layer_site(2.0, Material(C, 0.0))  # homogeneous Tresca: Prandtl exactly
    mesh = triangulate(site, 1.0, size=lambda p: 0.2 + 0.3 * np.hypot(p[:, 0] - 1.0, p[:, 1]))
    br = bracket(site, mesh)
    fine = bisect(mesh, np.ones(mesh.n_el, bool))
    only_lb = bracket(site, fine, previous=br, solve=("lb",))
    assert only_lb.upper.certified and only_lb.upper.iterations == 0  # the carried field, not a solve
    assert only_lb.ub <= br.ub * (1 + REL)
    assert only_lb.lb <= PRANDTL_HALF * (1 + REL) <= only_lb.ub * (1 + 2 * REL)
    with pytest.raises(ValueError, match="nested mesh"):
        bracket(site, mesh, solve=("ub",))
    res = adaptive(site, mesh, gap=0.02, lazy=True)
    assert res.lb <= PRANDTL_HALF * (1 + REL) <= res.ub * (1 + REL)
    assert res.converged


def test_a_free_rigid_inclusion_moves_as_a_rigid_body():
    """A rigid block inside the Tresca soil beside the strip, touching no boundary: the upper bound lets it
    translate and rotate (three rigid-body unknowns) but not deform; against the same block of soil on the
    same mesh both bounds can only rise (the lower bound's admissible set grows, the upper bound's
    kinematic set shrinks)."""
    pts = np.array(
        [(0, -3), (6, -3), (6, 0), (1, 0), (0, 0), (1.5, -0.8), (2.5, -0.8), (2.5, -0.4), (1.5, -0.4)], float
    )
    segs = (
        (0, 1, Boundary("fixed")), (1, 2, Boundary("symmetry")), (2, 3, Boundary("free")),
        (3, 4, Boundary("footing", footing=0)), (4, 0, Boundary("symmetry")),
        (5, 6, None), (6, 7, None), (7, 8, None), (8, 5, None),
    )  # fmt: skip
    footing = (Footing(Interface("rough"), load_ref=(0.0, -1.0), moves=("z",)),)
    regions = ((4.0, -2.0, 0), (2.0, -0.6, 1))
    block = Site(pts, segs, regions, (Material(C, 0.0), Material.rigid_body()), footing)
    soil = Site(pts, segs, regions, (Material(C, 0.0), Material(C, 0.0)), footing)
    mesh = triangulate(block, 0.5, size=lambda p: 0.1 + 0.3 * np.hypot(p[:, 0] - 1.0, p[:, 1]))
    br_b, br_s = bracket(block, mesh), bracket(soil, mesh)
    assert br_b.lower.certified and br_b.upper.certified
    assert br_b.lb >= br_s.lb * (1 - SOLVER) and br_b.ub >= br_s.ub * (1 - SOLVER)
    strain = np.abs(br_b.upper.strain)
    inside = mesh.material == 1
    assert strain[inside].max() <= 1e-9 * strain.max()  # a rigid motion: no strain rate
    v = br_b.upper.velocity[: len(mesh.xy)]
    moving = np.unique(mesh.tri[inside])
    assert np.abs(v[moving]).max() > 1e-3 * np.abs(v).max()  # and it does move with the soil around it
