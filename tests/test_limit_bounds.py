"""Finite-element limit analysis (ssi.limit): the bounds against exact collapse loads, the certification,
nested refinement, numbering independence, Davis, the factor of safety and bad input.

Exact references (all associated, rigid-perfectly plastic, plane strain), computed here from their closed
forms, not by the code under test:
- Prandtl-Reissner, weightless, rough or smooth strip: q_u = c N_c + q N_q, N_q = e^{pi tan phi}
  tan^2(45 + phi/2), N_c = (N_q - 1) cot phi, N_c = 2 + pi for phi = 0;
- sliding of a rigid footing held against rotation on a Coulomb joint over far stronger soil:
  H = c_i B + N tan phi_i;
- strength reduction of a Tresca footing: the capacity is proportional to c, so F* = q_u / q_applied;
- a rotating rigid strip on Tresca soil (c = s_u) under a vertical load V at eccentricity e: Meyerhof's
  effective width, V_M = (2 + pi) s_u (B - 2e), is a rigorous lower bound of the exact load for any
  interface that can carry zero shear (Prandtl's statically admissible field, which extends into the whole
  half-space for Tresca, under the width B - 2e centred on the load and zero traction on the rest of the
  base: the footing is in equilibrium, moment included), so UB >= V_M;
- its moment capacity under zero vertical load, bonded base: the circular "scoop" mechanism (the footing
  and a circular block of soil below it rotating about a point on the footing's axis, slip on the arc
  through the footing's edges at s_u) is a rigorous upper bound M = (B^2 / 2) s_u alpha / sin^2 alpha,
  least at tan alpha = 2 alpha (alpha = 1.1656): M = 0.6900 s_u B^2, so LB <= 0.6900 s_u B^2;
- on one mesh, freeing a footing's rotation (one more unknown in the upper bound, one more equation in the
  lower bound) can only lower both bounds; so can letting it bend (a beam with plastic hinges: more
  mechanisms, more constraints on the stress field), and a beam too strong to yield is the rigid footing.
Each bound is rigorous for its mesh, so the assertions LB <= exact <= UB have no tolerance beyond the
solver's relative accuracy REL (1e-6: Clarabel's tolerances are 1e-9 and the lower bound is certified).
"""

import functools
import math
from dataclasses import replace

import numpy as np
import pytest

from ssi.limit import (
    Beam,
    Boundary,
    Footing,
    Interface,
    Material,
    Site,
    adaptive,
    bisect,
    bracket,
    lower_bound,
    safety_factor,
    strip_site,
    triangulate,
    upper_bound,
)
from ssi.limit import lower as lower_module

REL = 1e-6


def prandtl_q(c, phi_deg, q=0.0):
    if phi_deg == 0.0:
        return c * (2.0 + math.pi) + q
    t = math.tan(math.radians(phi_deg))
    nq = math.exp(math.pi * t) * math.tan(math.radians(45.0 + phi_deg / 2.0)) ** 2
    return c * (nq - 1.0) / t + q * nq


def graded(x0, h_min, growth):
    return lambda p: h_min + growth * np.hypot(p[:, 0] - x0, p[:, 1])


def footing(phi, kind, c=10e3, surcharge=0.0, **kw):
    site = strip_site(2.0, Material(c, phi), Interface(kind), surcharge=surcharge, **kw)
    return site, triangulate(site, 1.0, size=graded(1.0, 0.2, 0.3))


@functools.cache
def solved(phi, kind):
    """(site, mesh, bracket) of ``footing(phi, kind)``, solved once and shared by the tests that read it
    (read-only: a test that needs a fresh solve makes its own)."""
    site, mesh = footing(phi, kind)
    return site, mesh, bracket(site, mesh)


@pytest.mark.parametrize("phi", [0.0, 20.0])
@pytest.mark.parametrize("kind", ["rough", "smooth"])
def test_prandtl_inside_bracket(phi, kind):
    _, _, br = solved(phi, kind)
    exact = prandtl_q(10e3, phi)
    assert br.lower.certified, br.lower.reason
    assert br.lb <= exact * (1 + REL) and exact <= br.ub * (1 + REL), (br.lb / exact, br.ub / exact)
    # the bracket says something on this ~200-element mesh (measured: 0.81-1.22 x exact; a broken
    # assembly gives 0 or unbounded)
    assert br.lb > 0.7 * exact and br.ub < 1.3 * exact
    # the gap identity: the element shares sum to UB - LB (virtual work of the two fields), round-off only
    assert br.identity_error < 1e-6
    assert br.upper.flow_residual < 1e-6


def test_surcharge_inside_bracket():
    q = 10e3
    site, mesh = footing(30.0, "rough", c=0.0, surcharge=q, half_width=12.0, depth=6.0)
    br = bracket(site, mesh)
    exact = prandtl_q(0.0, 30.0, q)
    assert br.lower.certified, br.lower.reason
    assert br.lb <= exact * (1 + REL) <= br.ub * (1 + 2 * REL)


@pytest.mark.parametrize("c_i", [0.0, 5e3])
def test_sliding_on_coulomb_joint(c_i):
    N, B, phi_i = 100e3, 2.0, 25.0
    itf = Interface("coulomb", c=c_i, phi_deg=phi_i)
    site = strip_site(
        B, Material(1e6, 0.0), itf, half_width=4.0, depth=3.0, symmetric=False,
        load_ref=(1.0, 0.0), load_dead=(0.0, -N),
    )  # fmt: skip
    mesh = triangulate(site, 1.0, size=graded(1.0, 0.3, 0.3))
    br = bracket(site, mesh)
    exact = c_i * B + N * math.tan(math.radians(phi_i))
    assert br.lower.certified, br.lower.reason
    assert br.lb <= exact * (1 + REL) and exact <= br.ub * (1 + REL)
    assert br.gap <= 0.01  # the sliding check: a translational mechanism is exact on any mesh


def test_certification_rejects_a_field_outside_the_cones(monkeypatch):
    """The certificate is computed from the returned point alone: a solver answer scaled 1.5x (still in
    equilibrium with 1.5 lambda) leaves the yield cones and must come back uncertified, lam NaN."""
    site, mesh = footing(0.0, "rough")
    real = lower_module.solve_conic

    def inflated(*args, **kwargs):
        sol = real(*args, **kwargs)
        sol.x = 1.5 * sol.x
        return sol

    monkeypatch.setattr(lower_module, "solve_conic", inflated)
    lb = lower_bound(site, mesh)
    assert not lb.certified and math.isnan(lb.lam)
    assert "outside" in lb.reason


def test_bisection_is_nested_and_bounds_monotone():
    site, mesh, br0 = solved(20.0, "rough")
    marked = np.argsort(-br0.shares)[: mesh.n_el // 4]
    fine = bisect(mesh, marked)
    assert fine.n_el > mesh.n_el
    # nested: every new triangle lies in exactly one old triangle (its centroid and its vertices), and the
    # areas are preserved
    cen = fine.xy[fine.tri].mean(axis=1)
    p = mesh.xy[mesh.tri]
    owners = np.zeros(len(cen), int)
    for e in range(mesh.n_el):
        a, b, c = p[e]
        m = np.array([[b[0] - a[0], c[0] - a[0]], [b[1] - a[1], c[1] - a[1]]])
        lam = np.linalg.solve(m, (cen - a).T)
        inside = (lam[0] > -1e-12) & (lam[1] > -1e-12) & (lam.sum(axis=0) < 1 + 1e-12)
        owners += inside
    assert np.all(owners == 1)
    assert abs(fine.areas().sum() - mesh.areas().sum()) < 1e-12 * mesh.areas().sum()
    br1 = bracket(site, fine)
    assert br1.lb >= br0.lb * (1 - REL) and br1.ub <= br0.ub * (1 + REL)


def test_numbering_independent_and_rerun_identical():
    site, mesh, a = solved(20.0, "smooth")
    b = bracket(site, mesh)
    assert (a.lb, a.ub) == (b.lb, b.ub)  # bit-identical rerun
    c = bracket(site, mesh.permuted(seed=3))
    # another numbering is another factorisation order: equal to the solver's accuracy
    assert abs(c.lb / a.lb - 1) < 1e-5 and abs(c.ub / a.ub - 1) < 1e-5


def test_adaptive_reaches_requested_gap():
    site, mesh = footing(0.0, "rough")
    res = adaptive(site, mesh, gap=0.05, max_elements=3000)
    exact = prandtl_q(10e3, 0.0)
    assert res.converged and res.gap <= 0.05
    assert res.lb <= exact <= res.ub
    assert res.monotone


def test_safety_factor_of_tresca_footing():
    q_applied = 20e3  # Pa: F* = (2 + pi) c / q exactly (capacity proportional to c for phi = 0)
    site = strip_site(2.0, Material(10e3, 0.0), Interface("rough"), load_ref=(0.0, -q_applied * 1.0))
    mesh = triangulate(site, 1.0, size=graded(1.0, 0.25, 0.35))
    f_lb, f_ub, trials = safety_factor(site, mesh, rel_tol=2e-2)
    exact = prandtl_q(10e3, 0.0) / q_applied
    assert f_lb <= exact <= f_ub
    assert f_ub / f_lb < 1.4
    assert all(np.isfinite(v) for _, _, v in trials)


def test_davis_material():
    m = Material(10e3, 20.0, psi_deg=0.0)
    d = m.davis()
    beta = math.cos(math.radians(20.0))  # psi = 0: beta = cos phi
    assert d.c == pytest.approx(beta * 10e3, rel=1e-14)
    assert math.tan(math.radians(d.phi_deg)) == pytest.approx(beta * math.tan(math.radians(20.0)), rel=1e-14)
    assert Material(10e3, 20.0).davis() == Material(10e3, 20.0)


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: Material(-1.0, 20.0), "c must be"),
        (lambda: Material(10e3, 75.0), "phi_deg must be"),
        (lambda: Material(10e3, 20.0, psi_deg=25.0), "psi_deg must be"),
        (lambda: Material(0.0, 0.0), "no strength"),
        (lambda: Interface("smooth", c=5e3), "coulomb"),
        (lambda: Interface("glued"), "kind"),
        (lambda: strip_site(2.0, Material(1e4, 0.0), half_width=0.5), "half_width"),
    ],
)
def test_bad_input_names_the_parameter(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_fields_carried_to_a_nested_mesh_keep_their_bounds():
    """On a bisected mesh the coarse stress field is still statically admissible and the coarse velocity
    field still kinematically admissible: re-certified and re-evaluated there, they give the coarse bounds
    back (to round-off), which is what makes nested refinement monotone."""
    from ssi.limit.analysis import carry_stress, carry_velocity

    site, mesh, br0 = solved(20.0, "smooth")
    fine = bisect(mesh, np.argsort(-br0.shares)[: mesh.n_el // 3])
    sig = carry_stress(mesh, fine, br0.lower.stress)
    lb = lower_bound(site, fine, stress=(sig, br0.lower.lam_projected))
    assert lb.certified, lb.reason
    assert abs(lb.lam / br0.lb - 1) < 1e-9
    vel = carry_velocity(mesh, fine, br0.upper.velocity)
    ub = upper_bound(site, fine, velocity=(vel, br0.upper.footing_velocity))
    assert abs(ub.lam / br0.ub - 1) < 1e-9


def two_layer_site(top, bottom):
    """Chapter 10's half block split at z = -1 m by an interior polyline: ``top`` over ``bottom``."""
    from ssi.limit import Boundary, Footing, Site

    pts = np.array([(0, -5), (6, -5), (6, -1), (6, 0), (1, 0), (0, 0), (0, -1)], float)
    sym, fixed = Boundary("symmetry"), Boundary("fixed")
    segs = (
        (0, 1, fixed), (1, 2, sym), (2, 3, sym), (3, 4, Boundary("free")),
        (4, 5, Boundary("footing", footing=0)), (5, 6, sym), (6, 0, sym), (6, 2, None),
    )  # fmt: skip
    regions = ((3.0, -0.5, 0), (3.0, -3.0, 1))
    footing = Footing(Interface("rough"), load_ref=(0.0, -1.0), moves=("z",))
    return Site(pts, segs, regions, (top, bottom), (footing,))


def test_layered_site_regions_and_bracket():
    soil = Material(10e3, 0.0)
    site = two_layer_site(soil, Material(10e3, 0.0, gamma=0.0))
    mesh = triangulate(site, 1.0, size=graded(1.0, 0.2, 0.3))
    cz = mesh.xy[mesh.tri][:, :, 1].mean(axis=1)
    assert np.all(mesh.material[cz > -1.0] == 0) and np.all(mesh.material[cz < -1.0] == 1)
    br = bracket(site, mesh)
    exact = prandtl_q(10e3, 0.0)  # the two layers are the same soil: Prandtl again
    assert br.lower.certified
    assert br.lb <= exact <= br.ub
    # a far stronger lower layer cannot lower the capacity: both bounds stay above the homogeneous LB
    strong = bracket(two_layer_site(soil, Material(100e3, 0.0)), mesh)
    assert strong.lb >= br.lb * (1 - REL) and strong.ub >= br.lb


def test_tension_cutoff_lower_bound():
    site, mesh = footing(20.0, "rough")
    T = 1e3  # Pa
    cut = strip_site(2.0, Material(10e3, 20.0, tension_cutoff=T), Interface("rough"))
    lb0 = lower_bound(site, mesh)
    lb1 = lower_bound(cut, mesh)
    assert lb1.certified, lb1.reason
    assert lb1.lam <= lb0.lam * (1 + REL)  # a smaller admissible set: never a larger lower bound
    sx, sz, tau = lb1.stress[..., 0], lb1.stress[..., 1], lb1.stress[..., 2]
    sig1 = 0.5 * (sx + sz) + np.hypot(0.5 * (sx - sz), tau)
    assert sig1.max() <= T  # certified: no principal stress above the cut-off anywhere
    # a zero cut-off is met with equality on the free surface: reported, not certified by tolerance
    zero = lower_bound(strip_site(2.0, Material(10e3, 20.0, tension_cutoff=0.0), Interface("rough")), mesh)
    assert zero.certified == math.isfinite(zero.lam)


def test_flexible_load_with_a_fan_brackets_sg61():
    """Smith & Griffiths' program 6.1 footing (uniform pressure on a half width of 2 m, Tresca c_u = 100 kPa):
    (2 + pi) c_u inside the bracket, with the rays of a fan meshed at the edge of the load."""
    site = strip_site(4.0, Material(100e3, 0.0), half_width=12.0, depth=5.0, flexible=True)
    mesh = triangulate(site, 1.5, size=graded(2.0, 0.3, 0.4), fans=((2.0, 0.0, 0.6, 12),))
    br = bracket(site, mesh)
    assert br.lower.certified, br.lower.reason
    assert br.lb <= (2 + math.pi) * 100e3 <= br.ub
    with pytest.raises(ValueError, match="fans"):
        triangulate(site, 1.5, fans=((2.5, 0.0, 0.6, 12),))


def scoop_moment(B, su):
    """The least circular-scoop upper bound of a bonded strip's moment capacity [N m/m] (module docstring)."""
    from scipy.optimize import brentq

    alpha = brentq(lambda a: math.tan(a) - 2 * a, 0.8, 1.5)
    return 0.5 * B**2 * su * alpha / math.sin(alpha) ** 2


def two_edge_size(p):
    """Element size [m] graded towards both edges (x = -1, 1 m) of a 2 m footing."""
    return 0.15 + 0.3 * np.minimum(np.hypot(p[:, 0] - 1, p[:, 1]), np.hypot(p[:, 0] + 1, p[:, 1]))


def rotating_strip(kind="rough", V=1.0, M=0.0, moves=("x", "z", "r")):
    """A weightless Tresca strip B = 2 m, s_u = 10 kPa, whole model, the footing free to rotate about the
    centre of its base; lambda scales (0, -V) and the moment M [N m/m]."""
    itf = Interface(kind) if kind != "coulomb" else Interface("coulomb", c=0.0, phi_deg=45.0)
    site = strip_site(2.0, Material(10e3, 0.0), itf, half_width=4.0, depth=3.0, symmetric=False)
    centre = (0.0, 0.0) if "r" in moves else None
    ft = Footing(itf, (0.0, -V), (0.0, 0.0), moves, centre=centre, moment_ref=M)
    site = replace(site, footings=(ft,))
    return site, triangulate(site, 1.0, size=two_edge_size)


@pytest.mark.parametrize("kind", ["coulomb"])  # rough rotating bases: the moment and free-rotation tests
def test_eccentric_load_on_a_rotating_footing(kind):
    """V at e = B/8 (moment -V e about the centre): certified, UB above Meyerhof's rigorous lower bound, the
    virtual-work identity of the two fields exact (it checks the moment row of the lower bound against the
    rotation's power in the upper bound), and the footing turning towards the load."""
    e = 0.25
    site, mesh = rotating_strip(kind, M=-e)
    br = bracket(site, mesh)
    v_m = (2.0 + math.pi) * 10e3 * (2.0 - 2 * e)
    assert br.lower.certified, br.lower.reason
    assert br.ub >= v_m * (1 - REL), br.ub / v_m
    assert br.identity_error < 1e-9
    assert br.upper.footing_rotation[0] < 0.0  # clockwise: the loaded right side goes down
    # the bracket says something on this ~260-element mesh (measured [0.948, 1.162] x V_M)
    assert 0.85 * v_m < br.lb and br.ub < 1.3 * v_m


def test_moment_capacity_of_a_bonded_strip_below_the_scoop():
    site, mesh = rotating_strip("rough", V=0.0, M=1.0)
    br = bracket(site, mesh)
    scoop = scoop_moment(2.0, 10e3)
    assert abs(scoop / (10e3 * 4.0) - 0.6900) < 5e-5  # the classical 0.69 s_u B^2
    assert br.lower.certified, br.lower.reason
    assert br.lb <= scoop * (1 + REL) and br.lb > 0.9 * scoop, br.lb / scoop  # measured 0.97
    assert br.ub >= br.lb and br.identity_error < 1e-9


def test_a_free_rotation_lowers_both_bounds_on_one_mesh():
    """Centred load: the exact load is Prandtl's with the rotation free or held (the mirror image of a
    tilting mechanism costs the same, and their average does not tilt); on one mesh the freer problem's
    bounds can only be lower, and both brackets contain Prandtl."""
    held_site, mesh = rotating_strip("rough", moves=("x", "z"))
    free_site, _ = rotating_strip("rough")
    held, free = bracket(held_site, mesh), bracket(free_site, mesh)
    exact = prandtl_q(10e3, 0.0) * 2.0
    for br in (held, free):
        assert br.lower.certified and br.lb <= exact * (1 + REL) and exact <= br.ub * (1 + REL)
    assert free.lb <= held.lb * (1 + REL) and free.ub <= held.ub * (1 + REL)


def beam_strip(mp, kind="rough"):
    """rotating_strip's footing as a beam with M_p = ``mp`` [N m/m] (sagging and hogging) under two columns
    of lambda x 0.5 N/m at x = -0.5 and 0.5 m."""
    itf = Interface(kind) if kind != "coulomb" else Interface("coulomb", c=0.0, phi_deg=45.0)
    site = strip_site(2.0, Material(10e3, 0.0), itf, half_width=4.0, depth=3.0, symmetric=False,
                      base_points=(-0.5, 0.5))  # fmt: skip
    beam = Beam(-1.0, 1.0, mp, mp, loads_ref=((-0.5, 0.0, -0.5, 0.0), (0.5, 0.0, -0.5, 0.0)))
    site = replace(site, footings=(Footing(itf, moves=("x", "z", "r"), centre=(0.0, 0.0), beam=beam),))
    return site


@pytest.mark.parametrize("kind", ["rough"])  # a beam on a Coulomb joint: chapter 17's fela_beam_mechanism
def test_a_beam_footing_between_rigid_and_weak(kind):
    """Same mesh: a beam whose M_p (1e9 N m/m) no load on this soil reaches gives the rigid rotating
    footing's bounds; a weak one (1 kN m/m) gives both bounds lower, certified, its moment within M_p and
    the virtual-work identity exact with the hinges' term."""
    rigid_site = beam_strip(1.0, kind)
    rigid_site = replace(
        rigid_site, footings=(replace(rigid_site.footings[0], beam=None, load_ref=(0.0, -1.0)),)
    )
    mesh = triangulate(rigid_site, 1.0, size=two_edge_size)
    rigid = bracket(rigid_site, mesh)
    strong = bracket(beam_strip(1e9, kind), mesh)
    weak = bracket(beam_strip(1e3, kind), mesh)
    assert strong.lb == pytest.approx(rigid.lb, rel=REL) and strong.ub == pytest.approx(rigid.ub, rel=REL)
    assert weak.lower.certified, weak.lower.reason
    assert weak.lb <= rigid.lb * (1 + REL) and weak.ub <= rigid.ub * (1 + REL)
    assert weak.ub < 0.8 * rigid.ub  # the beam's mechanism governs (measured 0.52)
    assert weak.lower.beam[0]["utilisation"] <= 1.0
    assert weak.identity_error < 1e-9 and strong.identity_error < 1e-9


def _trench_site(wall: Interface, c: float, depth_d: float = 1.0) -> Site:
    """A rigid block standing in a trench (base 1 m wide, ``depth_d`` deep) in a 6 m x 2 m block of weightless
    Tresca soil c, pushed along x alone by lambda [N/m] on a smooth base: only the walls, on the contact
    ``wall``, resist it."""
    b, w, h = 0.5, 3.0, 2.0
    pts = [(-w, -h), (w, -h), (w, 0), (b, 0), (b, -depth_d), (-b, -depth_d), (-b, 0), (-w, 0)]
    walls = Boundary("footing", footing=0, interface=wall)
    segs = (
        (0, 1, Boundary("fixed")),
        (1, 2, Boundary("symmetry")),
        (2, 3, Boundary("free")),
        (3, 4, walls),
        (4, 5, Boundary("footing", footing=0)),
        (5, 6, walls),
        (6, 7, Boundary("free")),
        (7, 0, Boundary("symmetry")),
    )
    push = Footing(Interface("smooth"), (1.0, 0.0), (0.0, 0.0), ("x",))
    return Site(np.array(pts, float), segs, ((0.0, -1.5, 0),), (Material(c, 0.0),), (push,))


def test_a_walls_contact_sets_the_passive_resistance_of_a_pushed_trench_block():
    """A segment's own interface (``Boundary.interface``: a trench wall's side contact, unlike the base's):
    a block in a trench pushed horizontally on a smooth base, weightless Tresca soil c, walls D deep with no
    tension (cut-off 0: the back wall opens). Hand values (slip-line theory): a smooth wall (c_i = 0,
    phi_i = 0) meets Rankine's passive pressure 2c on its whole height, H = 2 c D exactly; a wall with full
    adhesion c_i = c turns the stress through a fan of pi/4 at its top (Hencky: p rises by 2 c pi/4), so
    sigma_n = (1 + pi/2) c and H = (1 + pi/2) c D. Both inside their brackets (to the solvers' REL), and the
    rough wall's certified floor above the smooth wall's exact value: the contact carries what it should.
    Measured on 247 triangles: smooth [0.9999, 1.25] x 2cD (the Rankine field is linear: exact but for the
    solve's 1e-4 cone margin), rough [0.974, 1.18] x (1 + pi/2) cD, its floor 1.25 x 2cD; refined to a 2 %
    gap, [0.9999, 1.038] x 2cD on 442 triangles and [0.992, 1.027] x (1 + pi/2) cD on 638."""
    c, d = 10e3, 1.0
    sing = np.array([(0.5, 0.0), (0.5, -d)])  # the front wall's ends

    def size(p):
        return 0.1 + 0.3 * np.min(np.hypot(p[:, None, 0] - sing[:, 0], p[:, None, 1] - sing[:, 1]), axis=1)

    smooth = _trench_site(Interface("coulomb", 0.0, 0.0, tension=0.0), c)
    rough = _trench_site(Interface("coulomb", c, 0.0, tension=0.0), c)
    mesh = triangulate(smooth, 1.0, size=size)
    assert np.array_equal(mesh.xy, triangulate(rough, 1.0, size=size).xy)
    b_s, b_r = bracket(smooth, mesh), bracket(rough, mesh)
    assert b_s.lower.certified and b_r.lower.certified and b_s.upper.certified and b_r.upper.certified
    h_smooth, h_rough = 2.0 * c * d, (1.0 + math.pi / 2.0) * c * d
    assert b_s.lb * (1 - REL) <= h_smooth <= b_s.ub * (1 + REL)
    assert b_r.lb * (1 - REL) <= h_rough <= b_r.ub * (1 + REL)
    assert b_s.lb >= 0.999 * h_smooth  # the exact Rankine field, less the solve's margin 1e-4
    assert b_r.lb > 1.2 * h_smooth
    # without the cut-off the back wall pulls: weightless Tresca's active state mirrors the passive one
    # (sigma_h = -2c), so smooth walls carry 4 c D (measured [0.9999, 1.45] x 4cD here: the back wall's
    # ends are not refined)
    b_t = bracket(_trench_site(Interface("coulomb", 0.0, 0.0), c), mesh)
    assert b_t.lb * (1 - REL) <= 2.0 * h_smooth <= b_t.ub * (1 + REL) and b_t.lb >= 0.999 * 2.0 * h_smooth
    # the segment's interface follows strength reduction and Davis, the footing's own as before
    red = rough.reduced(2.0)
    walls = [b.interface for _, _, b in red.segments if b.interface is not None]
    assert len(walls) == 2 and all(w.c == c / 2.0 for w in walls)
    assert red.interfaces == (Interface("smooth"), walls[0], walls[1])
    with pytest.raises(ValueError, match="interface applies to kind 'footing' only, got kind='free'"):
        Boundary("free", interface=Interface())
