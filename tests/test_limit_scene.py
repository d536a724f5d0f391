"""A whole scene's capacity by limit analysis (ssi.capacity, ``ssi limit``) and the check of an
incremental limit against its bracket (ssi.limit.check), on small meshes.

Exact references, from closed forms, not from the code under test:
- Prandtl, weightless rough strip of width B: V = c N_c B, N_q = e^{pi tan phi} tan^2(45 + phi/2),
  N_c = (N_q - 1) cot phi (N_c = 2 + pi for phi = 0); of the Davis material the same with c* = beta c,
  tan phi* = beta tan phi, beta = cos psi cos phi / (1 - sin psi sin phi);
- strength reduction of a weightless Tresca footing: its capacity (2 + pi) c B is proportional to c, so
  loaded at half of it the factor of safety is exactly 2.
Each bound is rigorous for its mesh, so "exact inside [LB, UB]" needs no tolerance beyond the solver's
relative accuracy REL (1e-6: Clarabel's tolerances are 1e-9 and the lower bound is certified).
"""

import contextlib
import io
import json
import math
import pathlib
import re
import shutil
import warnings
from dataclasses import replace

import numpy as np
import pytest

from ssi.capacity import limit_problem
from ssi.elements.section import homogeneous
from ssi.io.cli import main
from ssi.limit import Interface, bracket, check_limit
from ssi.limit.upper import FLOW_TOL
from ssi.scene import (
    ColumnLoad,
    Contact,
    ContactSegment,
    Excavation,
    Foundation,
    Phase,
    RigidFooting,
    Scene,
    Settlement,
    SoilLayer,
    StripLoad,
    SurfacePressure,
)

ROOT = pathlib.Path(__file__).resolve().parent.parent
REL = 1e-6


def prandtl_nc(phi_deg):
    if phi_deg == 0.0:
        return 2.0 + math.pi
    t = math.tan(math.radians(phi_deg))
    nq = math.exp(math.pi * t) * math.tan(math.radians(45.0 + phi_deg / 2.0)) ** 2
    return (nq - 1.0) / t


def davis(c, phi_deg, psi_deg):
    phi, psi = math.radians(phi_deg), math.radians(psi_deg)
    beta = math.cos(psi) * math.cos(phi) / (1.0 - math.sin(psi) * math.sin(phi))
    return beta * c, math.degrees(math.atan(beta * math.tan(phi)))


def footing(symmetric=True, psi_deg=0.0, **kw):
    """Chapter 10's footing: B = 2 m rough, c = 10 kPa, phi = 20 deg, weightless, pushed (lambda = V)."""
    layer = SoilLayer(5.0, E=20e6, nu=0.3, c=10e3, phi_deg=20.0, psi_deg=psi_deg)
    return Scene(
        width=12.0,
        depth=5.0,
        symmetric=symmetric,
        layers=[layer],
        foundation=RigidFooting(-1.0, 1.0),
        loads=[Settlement(0.05)],
        **kw,
    )


def test_readme_capacity_block_prints_what_the_readme_shows():
    """The README's capacity block, executed as written: its printed brackets are the README's (every line
    but the last, mesh and time), and they contain Prandtl's V = c N_c B (associated) and that of the Davis
    material (Davis bracket), the Davis bracket lying below the associated one."""
    readme = (ROOT / "README.md").read_text()
    code = next(b for b in re.findall(r"```python\n(.*?)```", readme, re.S) if "limit_analysis" in b)
    shown = re.search(r"cap = scene.limit_analysis.*?```text\n(.*?)```", readme, re.S).group(1)
    shown = shown.strip().splitlines()
    env = {}
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README.md", "exec"), env)
    printed = out.getvalue().strip().splitlines()
    assert printed[: len(shown)] == shown
    cap = env["cap"]
    assert cap.lb <= 10e3 * prandtl_nc(20.0) * 2.0 * (1 + REL)
    assert cap.ub >= 10e3 * prandtl_nc(20.0) * 2.0 * (1 - REL)
    c_d, phi_d = davis(10e3, 20.0, 0.0)
    v_d = c_d * prandtl_nc(phi_d) * 2.0
    assert cap.lb_davis * (1 - REL) <= v_d <= cap.ub_davis * (1 + REL)
    assert cap.ub_davis < cap.lb and cap.lb_davis < cap.lb
    assert cap.n_triangles == cap.mesh.n_el > 0 and min(cap.n_cones) > 0 and min(cap.iterations) > 0
    assert cap.stress.shape == (cap.n_triangles, 3, 3)
    assert cap.velocity.shape[1] == 2 and cap.dissipation.shape == (cap.n_triangles,)


def test_whole_model_brackets_the_same_force_as_the_half():
    """The whole footing (no symmetry, lambda = V of the whole footing) on its initial mesh (the bounds are
    rigorous on any mesh): Prandtl inside ([0.861, 1.205] V on 233 triangles)."""
    cap = footing(symmetric=False, psi_deg=None).limit_analysis(gap=0.08, max_steps=0)
    v = 10e3 * prandtl_nc(20.0) * 2.0
    assert cap.davis is None and cap.lb_davis == cap.lb
    assert cap.lb * (1 - REL) <= v <= cap.ub * (1 + REL)
    problem = limit_problem(footing(symmetric=False))
    assert problem.lam_unit == "N/m" and problem.site.footings[0].load_ref == (0.0, -1.0)


def test_safety_factor_of_a_footing_loaded_at_half_its_capacity():
    """A plate strip bonded (rough) to weightless Tresca clay under a central column of half Prandtl's
    (2 + pi) c B: the capacity is proportional to c, so F* = 2 exactly (module docstring); both
    strength-reduction bounds on one coarse mesh (139 triangles: [1.785, 2.580]) bracket it, and are that
    mesh's bracket of the load."""
    c, B = 20e3, 2.0
    scene = Scene(
        width=12.0,
        depth=5.0,
        layers=[SoilLayer.undrained(5.0, E_u=30e6, s_u=c)],
        foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9),
        loads=[ColumnLoad(0.0, N=0.5 * (2.0 + math.pi) * c * B)],
    )
    tol = 1e-2
    sf = scene.safety_factor(rel_tol=tol, h=4.0, h_min=0.5)
    assert sf.f_lb <= 2.0 * (1 + REL) and sf.f_ub >= 2.0 * (1 - REL)
    # the capacity is proportional to c, so on this mesh F_LB and F_UB are the bracket of the unreduced
    # scene (lambda in units of the applied load) to within the bisection's relative tolerance
    br = bracket(limit_problem(scene).site, sf.mesh)
    assert br.lb / (1 + tol) * (1 - REL) <= sf.f_lb <= br.lb * (1 + REL)
    assert br.ub * (1 - REL) <= sf.f_ub <= br.ub * (1 + tol) * (1 + REL)
    assert "factor of safety" in sf.summary()


def test_cli_limit_runs_the_example(tmp_path, capsys):
    """``ssi limit examples/capacity.toml``: one progress line per mesh, the summary, a JSON and a PNG."""
    scene = tmp_path / "capacity.toml"
    shutil.copy(ROOT / "examples" / "capacity.toml", scene)
    assert main(["limit", str(scene), "--gap", "0.25", "--max-elements", "400"]) == 0
    out = capsys.readouterr().out
    data = json.loads((tmp_path / "capacity_limit.json").read_text())
    n_meshes = len(data["history_associated"]) + len(data["history_davis"] or [])
    assert len(re.findall(r"^(associated|Davis) +mesh", out, re.M)) == n_meshes
    assert "Davis" in out and "kN/m" in out
    assert 0.0 < data["lb"] <= data["ub"] and 0.0 < data["lb_davis"] <= data["ub_davis"] < data["ub"]
    assert (tmp_path / "capacity_limit.png").stat().st_size > 0
    assert main(["limit", str(scene)]) == 2  # the outputs exist: refused without --overwrite
    # --strip reaches the limit problem: the example's elastic strip cannot be a beam (no plastic moment)
    assert main(["limit", str(scene), "--strip", "beam", "--overwrite"]) == 2
    assert "strip='beam': the Foundation's section is not reinforced concrete" in capsys.readouterr().err


def _layer(thickness):
    return SoilLayer(thickness, E=2e7, nu=0.3, c=1e4, phi_deg=20.0)


def _scene(**kw):
    base = dict(
        width=12.0,
        depth=5.0,
        layers=[SoilLayer(5.0, E=20e6, nu=0.3, c=10e3, phi_deg=20.0)],
        foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0),
        loads=[ColumnLoad(0.0, N=100e3)],
    )
    return Scene(**(base | kw))


@pytest.mark.parametrize(
    "kw, message",
    [
        (dict(layers=[SoilLayer(5.0, E=20e6, nu=0.3)]), r"every layer of the scene is elastic \(c=None\)"),
        (
            dict(layers=[SoilLayer(5.0, E=20e6, nu=0.3, c=1e3, phi_deg=30.0, drainage="undrained_A")]),
            r"layers\[0\]\.drainage='undrained_A'",
        ),
        (
            dict(loads=[ColumnLoad(0.5, N=100e3)], phases=[Phase("push", loads=(Settlement(0.01),))]),
            r"moment -50000 N m/m about the centre of its base x = 0 m, but its rotation is held",
        ),
        (dict(foundation=RigidFooting(-1.0, 1.0), contact=None), r"a ColumnLoad on a RigidFooting"),
        (
            dict(embedment=1.0, layers=[_layer(1.0), _layer(4.0)], water_table=0.5),
            r"Scene.water_table=0.5 m lies above the embedded strip's base \(embedment=1.0 m\)",
        ),
        (
            dict(embedment=1.0, layers=[_layer(1.0), _layer(4.0)], loads=[SurfacePressure(2.0, 5.0, 1e3)]),
            r"Scene.loads\[0\]: a SurfacePressure on the ground of an embedded scene with "
            r"side_soil='surcharge'",
        ),
        (
            dict(
                contact=[
                    ContactSegment(-1.0, 0.0, Contact(kn=1e10, kt=1e9, phi_deg=25.0)),
                    ContactSegment(0.0, 1.0, Contact(kn=1e10, kt=1e9, phi_deg=30.0)),
                ]
            ),
            r"contact segments with different laws",
        ),  # fmt: skip
        (
            dict(phases=[Phase("dig", excavate=(Excavation(3.0, 5.0, 1.0),))]),
            r"Phase\('dig'\)\.excavate",
        ),
        (
            dict(loads=[Settlement(0.01)], phases=[Phase("more", loads=(ColumnLoad(0.0, N=1e3),))]),
            r"a Settlement among the held loads",
        ),
    ],
)
def test_what_limit_analysis_cannot_represent_is_refused_by_name(kw, message):
    with pytest.raises(ValueError, match=message):
        limit_problem(_scene(**kw))


def test_bad_arguments_are_refused_by_name():
    scene = _scene()
    with pytest.raises(
        ValueError, match=r"phase='nope' is not a phase of the scene; its phases are \['loads'\]"
    ):
        scene.limit_analysis(phase="nope")
    with pytest.raises(ValueError, match=r"gap must be a finite number in \(0, 1\]"):
        scene.limit_analysis(gap=0.0)
    with pytest.raises(ValueError, match=r"h_min must be a finite number in \(0, inf\)"):
        scene.limit_analysis(h_min=-1.0)
    with pytest.raises(ValueError, match=r"Settlement push: it has no load to carry"):
        footing().safety_factor()


def test_held_and_scaled_phases():
    """Phase 'loads' held at its factor in the later phase, the later phase's loads scaled; the surcharge
    on the ground beside the strip and on the strip's own width is a dead load; the first phase's
    loads scaled when it is named."""
    scene = _scene(
        surcharge=5e3,
        phases=[Phase("more", loads=(ColumnLoad(0.0, N=50e3),), factors={"loads": 0.5})],
    )
    p = limit_problem(scene)
    (ft,) = p.site.footings
    assert p.phase == "more" and ft.load_ref == (0.0, -50e3)
    assert ft.load_dead == pytest.approx((0.0, -0.5 * 100e3 - 5e3 * 2.0))
    free = [b for _, _, b in p.site.segments if b is not None and b.kind == "free"]
    assert free and all(b.pressure_dead == 5e3 and b.pressure_ref == 0.0 for b in free)
    p0 = limit_problem(scene, phase="loads")
    assert p0.site.footings[0].load_ref == (0.0, -100e3) and p0.site.footings[0].load_dead == (0.0, -1e4)


def test_water_table_gives_the_buoyant_unit_weight_below_it():
    layer = SoilLayer(5.0, E=2e7, nu=0.3, unit_weight=18e3, unit_weight_sat=20e3, c=1e4, phi_deg=25.0)
    p = limit_problem(_scene(layers=[layer], water_table=2.0))
    assert sorted(m.gamma for m in p.site.materials) == pytest.approx([20e3 - 9.81e3, 18e3], rel=1e-3)


@pytest.mark.parametrize(
    "limit, verdict, size",
    [
        (100.0, "inside", 0.0),
        (90.0, "false collapse", 1 - 90 / 97),
        (130.0, "mesh overestimate", 130 / 123.6 - 1),
    ],
)
def test_check_limit_classifies_an_incremental_limit(limit, verdict, size):
    """Band [0.97 LB_Davis, 1.03 UB_assoc] = [97, 123.6] for the pair (100, 120): the size is computed here
    by hand from the band's ends."""
    res = check_limit(limit, (100.0, 120.0))
    assert res.verdict == verdict and res.size == pytest.approx(size, rel=1e-12)
    assert (res.low, res.high) == pytest.approx((97.0, 123.6))
    assert res.ok == (verdict == "inside") and verdict.split()[0].upper() in str(res).upper()


def test_check_limit_bad_input():
    with pytest.raises(ValueError, match=r"limit_load must be a finite number in \[0, inf\)"):
        check_limit(float("nan"), (1.0, 2.0))
    with pytest.raises(ValueError, match="LB_Davis = 3 must not exceed UB_assoc = 2"):
        check_limit(1.0, (3.0, 2.0))
    with pytest.raises(TypeError, match="bracket must be a CapacityResult or a pair"):
        check_limit(1.0, 5.0)


def test_a_site_brackets_prandtl_and_refuses_what_it_cannot_represent():
    """An ssi.scene.site.Site (its one geometry, Site.geometry()): a plate strip bonded to weightless Tresca
    clay under a central column N: lambda* = (2 + pi) c B / N exactly (Prandtl) inside the bracket; a
    DepthVarying layer is refused by name."""
    from ssi.scene.site import DepthVarying, Site, Strip

    c, N = 20e3, 100e3
    strip = Strip(Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)), Contact(kn=1e10, kt=1e9))
    site = Site(
        width=12.0,
        depth=5.0,
        layers=[SoilLayer.undrained(5.0, E_u=30e6, s_u=c)],
        strips=[strip],
        loads=[ColumnLoad(0.0, N=N)],
    )
    cap = site.limit_analysis(max_steps=0)  # the initial mesh: the bounds are rigorous on any
    exact = (2.0 + math.pi) * c * 2.0 / N
    assert cap.lb * (1 - REL) <= exact <= cap.ub * (1 + REL)
    varying = Site(
        width=12.0,
        depth=5.0,
        layers=[DepthVarying(SoilLayer(5.0, E=3e7, nu=0.3, c=c), c_inc=1e3)],
        strips=[strip],
        loads=[ColumnLoad(0.0, N=N)],
    )
    with pytest.raises(ValueError, match=r"Site.layers\[0\] is a DepthVarying"):
        limit_problem(varying)
    # an eccentric column: the strip rotates about the centre of its base, moment -N e
    clay = [SoilLayer.undrained(5.0, E_u=30e6, s_u=c)]
    eccentric = Site(width=12.0, depth=5.0, layers=clay, strips=[strip], loads=[ColumnLoad(0.25, N=N)])
    (ft,) = limit_problem(eccentric).site.footings
    assert (
        "r" in ft.moves and ft.centre == (0.0, 0.0) and ft.moment_ref == pytest.approx(-0.25 * N, rel=1e-12)
    )


def test_eccentric_column_and_strip_loads_become_the_footing_moment():
    """A plate strip's loads about the centre of its base (x_c = 0, z = 0), counter-clockwise positive: a
    column N at x = 0.5 m with H and M gives M - N x - H e (e = 0.25 m, the homogeneous 0.5 m section's
    mid-plane above the base); a trapezoidal strip load q = 10 -> 20 kPa over [-1, 1] m has the resultant
    30 kN/m at x = 1/9 m (the centroid of the trapezoid), moment -30e3/9; the rotation is free."""
    col = ColumnLoad(0.5, N=100e3, H=5e3, M=7e3)
    p = limit_problem(_scene(loads=[col]))
    (ft,) = p.site.footings
    assert ft.moves == ("x", "z", "r") and ft.centre == (0.0, 0.0)
    assert ft.moment_ref == pytest.approx(7e3 - 100e3 * 0.5 - 5e3 * 0.25, rel=1e-12)
    assert ft.load_ref == pytest.approx((5e3, -100e3), rel=1e-12)
    p = limit_problem(_scene(loads=[StripLoad(1e4, q_end=2e4)]))
    assert p.site.footings[0].moment_ref == pytest.approx(-30e3 / 9.0, rel=1e-12)
    # a problem that is its own mirror image about the strip's centre holds the rotation (the same exact
    # load, a tighter bracket); a pressure on one side breaks the symmetry and frees it
    assert limit_problem(_scene()).site.footings[0].moves == ("x", "z")
    one_side = _scene(loads=[ColumnLoad(0.0, N=100e3), SurfacePressure(2.0, 4.0, 10e3)])
    assert limit_problem(one_side).site.footings[0].moves == ("x", "z", "r")


def test_an_rc_strip_is_a_beam_with_the_sections_plastic_moment():
    """Chapter 11's RC section (As = 1.5e-3 m^2/m top and bottom, d = 0.35 m, f_ck = 30 MPa, f_y = 500
    MPa): by default the strip is a beam whose M_p is within 3 % of the rectangular stress block's
    As f_y (d - 0.4 x), x = As f_y / (0.8 f_ck) (253.1 kN m/m; the section analysis' parabola-rectangle and
    compression bars add ~2 %); its columns are point loads at base points; strip='rigid' drops the beam;
    an elastic section or a Settlement push cannot be a beam."""
    from ssi.lab.examples import chapter11_section

    rc = Foundation(-1.0, 1.0, chapter11_section())
    loads = [ColumnLoad(-0.5, N=100e3), ColumnLoad(0.5, N=100e3, H=2e3)]
    p = limit_problem(_scene(foundation=rc, loads=loads))
    (ft,) = p.site.footings
    x_blk = 1.5e-3 * 500e6 / (0.8 * 30e6)
    mp_hand = 1.5e-3 * 500e6 * (0.35 - 0.4 * x_blk)
    assert (
        ft.beam is not None
        and abs(ft.beam.mp_sag / mp_hand - 1) < 0.03
        and abs(ft.beam.mp_hog / mp_hand - 1) < 0.03
    )
    # the H of a column at the plate's mid-plane (0.2 m above the base) is a force at the base and a couple
    assert ft.beam.loads_ref == ((-0.5, 0.0, -100e3, 0.0), (0.5, 2e3, -100e3, -2e3 * 0.2))
    xs = {round(float(x), 9) for x, z in p.site.points if z == 0.0}
    assert {-0.5, 0.5} <= xs
    assert limit_problem(_scene(foundation=rc, loads=loads), strip="rigid").site.footings[0].beam is None
    with pytest.raises(
        ValueError, match=r"strip='beam': the Foundation's section is not reinforced concrete"
    ):
        limit_problem(_scene(), strip="beam")
    trapezoid = _scene(foundation=rc, loads=[StripLoad(1e4, q_end=2e4)])
    with pytest.raises(ValueError, match=r"a StripLoad not uniform over the whole strip"):
        limit_problem(trapezoid, strip="beam")
    with pytest.warns(UserWarning, match=r"the strip is taken rigid"):
        assert limit_problem(trapezoid).site.footings[0].beam is None
    push = _scene(foundation=rc, loads=[Settlement(0.01)])
    assert limit_problem(push).site.footings[0].beam is None
    with pytest.raises(ValueError, match=r"strip='beam' with a Settlement push"):
        limit_problem(push, strip="beam")
    # strip='beam_mn': the same beam with the section's M-N polygon, its N = 0 point the beam's M_p
    mn = limit_problem(_scene(foundation=rc, loads=loads), strip="beam_mn").site.footings[0].beam
    assert mn.axial and (0.0, ft.beam.mp_sag, ft.beam.mp_hog) in mn.interaction
    assert mn.loads_ref == ft.beam.loads_ref
    with pytest.raises(ValueError, match=r"strip must be 'rigid', 'beam', 'beam_mn' or None"):
        limit_problem(_scene(foundation=rc, loads=loads), strip="mn")


def test_a_brittle_strip_forms_no_hinge():
    """0.5 cm^2/m of bars in a 0.4 m section (far below minimum reinforcement: the cracking moment exceeds
    the yield moment): strip='beam' is refused by name; by default the strip is taken rigid with a
    warning saying why."""
    from ssi.lab.examples import chapter11_section

    weak = Foundation(-1.0, 1.0, chapter11_section(area=0.5e-4))
    scene = _scene(foundation=weak)
    with pytest.raises(ValueError, match=r"brittle on its bottom face .* below minimum reinforcement"):
        limit_problem(scene, strip="beam")
    with pytest.warns(UserWarning, match=r"brittle .* the strip is taken rigid"):
        assert limit_problem(scene).site.footings[0].beam is None


def test_a_footing_confined_across_the_block_has_no_upper_bound():
    """A footing over the whole top of a block on rollers with a fixed base, centred load, associated soil
    (phi > 0 dilates under any plastic flow): no kinematically admissible mechanism does work against the
    load (the block cannot lose volume), so the capacity is unbounded. The upper-bound program is then
    infeasible and its returned field violates the flow rule by O(1): no upper bound may come of it (it once
    gave 0.20 against a certified lower bound of 2.57). A footing that can collapse keeps a certified one."""
    confined = _scene(
        width=4.0,
        foundation=Foundation(-2.0, 2.0, homogeneous(0.5, 30e9, 0.2)),
        loads=[ColumnLoad(0.0, N=200e3)],
    )
    cap = confined.limit_analysis(gap=0.05, max_elements=400, davis=False)
    up = cap.associated.final.upper
    assert not up.certified and up.flow_residual > 1e3 * FLOW_TOL
    assert cap.ub == np.inf and cap.gap == 1.0 and cap.lb > 0.0
    assert "no associated upper bound" in cap.summary() and cap.to_dict()["ub"] is None
    free = _scene().limit_analysis(gap=0.2, max_elements=400, davis=False)
    assert free.associated.final.upper.certified and np.isfinite(free.ub) and free.lb <= free.ub


def test_a_sand_footing_lower_bound_certifies_at_the_apex():
    """Zoo scene random 2 (c = 0 sand beside a rough-ish footing): the projected field has four vertices
    1e-10 .. 1e-8 S outside the cohesionless cone next to the footing's edge (round-off: the cone has no
    inside at its apex) and interface rows violated by ~1e-20 S; both were refused before, leaving 41 of the
    100 zoo scenes without a certified floor. Within the apex slack the bound certifies and says with how
    much cohesion it is rigorous; a vertex further out than the slack still refuses it."""
    from ssi.lab.zoo import random_scenes
    from ssi.limit import lower as lower_module
    from ssi.limit import lower_bound, triangulate

    scene = dict(random_scenes(3, seed=1))["random 2"]
    site = limit_problem(scene, strip="rigid").site
    mesh = triangulate(site, h=1.0)
    lb = lower_bound(site, mesh)
    assert (
        lb.certified
        and "cohesionless vertices or joint rows within" in lb.reason
        and lb.lam == lb.lam_projected
    )
    tight = lower_module.APEX_SLACK
    try:
        lower_module.APEX_SLACK = 1e-12
        assert not lower_bound(site, mesh).certified
    finally:
        lower_module.APEX_SLACK = tight


def test_a_contacts_tension_cut_off_reaches_the_interface():
    """The Contact's sig_t is the limit interface's tension cut-off (one above the joint's apex c / tan
    phi is inactive, clipped to it); without sig_t the joint has none."""
    itf = limit_problem(_scene(contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0, c=1e3, sig_t=200.0)))
    assert itf.site.footings[0].interface.tension == 200.0
    assert limit_problem(_scene()).site.footings[0].interface.tension is None


def test_a_bonded_contact_without_shear_stiffness_is_smooth():
    """Contact(kn, kt=0) bonded (chapter 12's): no shear traction ever, no opening: the smooth interface."""
    push = [Settlement(0.01)]
    p = limit_problem(_scene(contact=Contact(kn=1e11, kt=0.0), loads=push), strip="rigid")
    assert p.site.footings[0].interface.kind == "smooth" and p.site.footings[0].moves == ("z",)
    assert limit_problem(_scene(contact=Contact(kn=1e11, kt=1e9))).site.footings[0].interface.kind == "rough"


# ---- an embedded strip (issue 30 item 2): the side soil as its overburden, or modelled

D_EMB, GAMMA_BACKFILL = 1.0, 18e3  # chapter 12's trench: base 1 m deep, backfill 18 kN/m^3


def _embedded(backfill, width=12.0, depth=5.0 + D_EMB, **kw):
    """Chapter 12's embedded strip as a rigid rough footing (B = 2 m, half model): weightless c = 0,
    phi = 30 deg sand below the base, ``backfill`` the 1 m beside it; lambda = the footing's force V."""
    sand = SoilLayer(depth - D_EMB, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, K0=1.0)
    return Scene(
        width=width,
        depth=depth,
        symmetric=True,
        layers=[backfill, sand],
        embedment=D_EMB,
        foundation=RigidFooting(-1.0, 1.0),
        loads=[Settlement(0.05)],
        **kw,
    )


def test_an_embedded_strip_with_its_overburden_brackets_prandtl_reissner():
    """Side soil replaced by its overburden q = gamma D on the ground at the base level (Terzaghi): on
    weightless sand the exact collapse pressure is q N_q, rough or smooth (Prandtl-Reissner; N_q from the
    closed form, not from ssi), so the bracket of V / B must contain it (to the solver's REL). Chapter 12's
    backfill is elastic: its strength is not used, so it is accepted; its weight is the overburden."""
    soft = SoilLayer(D_EMB, E=1e3, nu=0.3, unit_weight=GAMMA_BACKFILL)
    scene = _embedded(soft)
    p = limit_problem(scene)
    assert len(p.site.materials) == 1 and p.site.materials[0].phi_deg == 30.0  # only the sand below
    assert p.site.footings[0].centre == (0.0, -D_EMB)
    assert "side soil as its overburden 18 kPa at the base level" in p.reference
    ground = [b for _, _, b in p.site.segments if b is not None and b.kind == "free"]
    assert ground and all(b.pressure_dead == pytest.approx(GAMMA_BACKFILL * D_EMB) for b in ground)
    assert p.site.points[:, 1].max() == pytest.approx(-D_EMB)  # nothing above the base level
    q_nq = (
        GAMMA_BACKFILL
        * D_EMB
        * math.exp(math.pi * math.tan(math.radians(30.0)))
        * math.tan(math.radians(60.0)) ** 2
    )
    cap = scene.limit_analysis(gap=0.08)  # [0.929, 1.067] q N_q on 497 triangles, 2 s
    b = 2.0
    assert cap.lb / b <= q_nq * (1 + REL) and q_nq <= cap.ub / b * (1 + REL)
    assert cap.gap <= 0.08


def test_an_embedded_plate_strip_carries_its_base_levels_overburden():
    """A plate strip starts carrying the geostatic vertical stress of its base level (the incremental
    scene's initial state): surcharge plus overburden, a dead load gamma D B + q B on the footing."""
    back = SoilLayer(D_EMB, E=1e3, nu=0.3, unit_weight=GAMMA_BACKFILL)
    scene = _scene(
        layers=[back, SoilLayer(5.0, E=20e6, nu=0.3, c=10e3, phi_deg=20.0)],
        depth=5.0 + D_EMB,
        embedment=D_EMB,
        surcharge=2e3,
    )
    (ft,) = limit_problem(scene, strip="rigid").site.footings
    assert ft.load_dead == pytest.approx((0.0, -(GAMMA_BACKFILL * D_EMB + 2e3) * 2.0))
    assert ft.load_ref == (0.0, -100e3) and ft.centre == (0.0, -D_EMB)


def test_the_modelled_side_soil_carries_at_least_its_overburden():
    """With the side soil modelled (its strength and weight; the trench walls under their geostatic
    horizontal stress -sigma_xx0 = K0 gamma |z| as a linear dead pressure, touching nothing, as in the
    incremental scene) the scene is stronger than with the overburden alone: the surcharge-only lower
    bound's stress field extends into the side soil by the geostatic state (admissible: K0 = 1), so the
    true capacity with the side soil is at least the surcharge-only one. Asserted on the initial meshes (208
    and 286 triangles; the theorem holds on any): the modelled upper bound is above the surcharge-only
    lower bound (that theorem) and, measured, so is its lower bound (0.881 against 0.864 q N_q there; 0.942
    against 0.929 at an 8 % gap, 0.972 against 0.953 at 5 %)."""
    sand_back = SoilLayer(D_EMB, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, unit_weight=GAMMA_BACKFILL, K0=1.0)
    scene = _embedded(sand_back)
    p = limit_problem(scene, side_soil="soil")
    walls = [b for _, _, b in p.site.segments if b is not None and any(b.pressure_dead_grad)]
    assert len(walls) == 1  # the half model's one wall, at x = B/2, under K0 gamma |z|
    assert walls[0].dead_at(1.0, -0.4) == pytest.approx(0.4 * GAMMA_BACKFILL)
    with pytest.warns(UserWarning, match=r"side_soil='surcharge' ignores"):
        surcharge_only = scene.limit_analysis(max_steps=0)
    modelled = scene.limit_analysis(max_steps=0, side_soil="soil")
    assert modelled.ub >= surcharge_only.lb
    assert modelled.lb >= surcharge_only.lb


def test_embedded_options_refused_by_name():
    from ssi.lab.examples import chapter11_section

    back = SoilLayer(D_EMB, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, unit_weight=GAMMA_BACKFILL)
    with pytest.raises(
        ValueError, match=r"side_soil must be one of \('surcharge', 'soil'\) or None, got 'air'"
    ):
        limit_problem(_embedded(back), side_soil="air")
    # an elastic side soil never yields (as in the incremental run): a region of the rigid material
    soft = SoilLayer(D_EMB, E=1e3, nu=0.3, unit_weight=GAMMA_BACKFILL)
    mats = limit_problem(_embedded(soft), side_soil="soil").site.materials
    assert mats[0].rigid and mats[0].gamma == GAMMA_BACKFILL and not mats[1].rigid
    scene = _scene(
        layers=[back, SoilLayer(5.0, E=20e6, nu=0.3, c=10e3, phi_deg=20.0)],
        depth=5.0 + D_EMB,
        embedment=D_EMB,
        side_contact=Contact(kn=1e10, kt=1e9, phi_deg=20.0),
        foundation=Foundation(-1.0, 1.0, chapter11_section()),
    )
    # a beam strip's walls would move with its end sections, which the hinged beam does not represent
    with pytest.raises(ValueError, match=r"Scene.side_contact with side_soil='soil' on a beam strip"):
        limit_problem(scene, side_soil="soil", strip="beam")
    with pytest.warns(UserWarning, match=r"on a beam strip.*the strip is taken rigid"):
        assert limit_problem(scene, side_soil="soil").site.footings[0].beam is None
    with pytest.raises(ValueError, match=r"Scene.side_contact.phi_deg=70.0: ssi.limit takes 0 <= phi_deg"):
        limit_problem(replace(scene, side_contact=Contact(kn=1e10, kt=1e9, phi_deg=70.0)), side_soil="soil")
    # the surcharge model ignores the side contact and, with a warning, the backfill's strength (a floor)
    with pytest.warns(UserWarning, match=r"Scene.layers\[0\] above the embedded base have strength"):
        assert limit_problem(scene, strip="rigid").site.footings


def test_a_walls_linear_pressure_enters_both_bounds_exactly():
    """A metamorphic identity that holds mesh by mesh: on Tresca soil (pressure-independent strength) the
    hydrostatic field sigma = gamma z I (K0 = 1) is admissible and balances the weight gamma, the trench
    walls' linear pressure gamma |z| and gamma D on the footing's base; subtracting it maps the
    heavy scene's fields one to one onto the weightless scene's (the field is linear: exact on linear
    stress triangles; an associated Tresca flow is isochoric, so its power against the field is zero).
    So on one mesh both bounds of the heavy trench scene are the weightless one's plus gamma D B, the force
    of the base level's overburden on the footing; a wrong wall pressure (sign, gradient, quadrature)
    breaks it. Tolerance 1e-6 relative: the solvers' 1e-9 tolerances on differently scaled problems."""
    from ssi.limit import lower_bound, triangulate, upper_bound

    def trench(gamma):
        tresca = dict(E=20e6, nu=0.3, c=20e3, phi_deg=0.0, unit_weight=gamma, K0=1.0)
        lay = [SoilLayer(t, **tresca) for t in (1.0, 4.0)]
        scene = Scene(
            width=8.0,
            depth=5.0,
            symmetric=True,
            layers=lay,
            embedment=1.0,
            foundation=RigidFooting(-1.0, 1.0),
            loads=[Settlement(0.05)],
        )
        return limit_problem(scene, side_soil="soil").site

    heavy, light = trench(18e3), trench(0.0)
    assert any(any(b.pressure_dead_grad) for _, _, b in heavy.segments if b is not None)
    mesh = triangulate(heavy, 0.6)
    assert np.array_equal(mesh.xy, triangulate(light, 0.6).xy)  # the same geometry, the same mesh
    shift = 18e3 * 1.0 * 2.0  # gamma D B [N/m]
    lb_h, lb_l = lower_bound(heavy, mesh), lower_bound(light, mesh)
    ub_h, ub_l = upper_bound(heavy, mesh), upper_bound(light, mesh)
    assert lb_h.lam_solver == pytest.approx(lb_l.lam_solver + shift, rel=1e-6)
    assert ub_h.lam == pytest.approx(ub_l.lam + shift, rel=1e-6)


def test_chapter_12s_embedded_scene_brackets_gamma_d_nq():
    """Chapter 12's embedded scene as it is written there (a stiff plate strip on a frictionless bonded
    contact, whole model, a soft elastic backfill, associated weightless sand below, a Settlement push):
    the strip starts carrying p_0 = gamma D (a dead load), lambda is the force added to it, and
    lambda / B + p_0 is bracketed around gamma D N_q (exact for a strengthless backfill, smooth or rough),
    on the initial mesh (the bounds are rigorous on any mesh): [0.733, 1.139] gamma D N_q on 233 triangles
    (at an 8 % gap: [0.906, 1.046] on 583 triangles, 7 times the cost)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # the soft backfill's small E, as in chapter 12
        back = SoilLayer(D_EMB, E=1e3, nu=0.3, unit_weight=GAMMA_BACKFILL)
        sand = SoilLayer(5.0, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, psi_deg=30.0, K0=1.0)
        scene = Scene(
            width=12.0,
            depth=5.0 + D_EMB,
            layers=[back, sand],
            embedment=D_EMB,
            foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
            contact=Contact(kn=1e11, kt=0.0),
            phases=[Phase("push", loads=(Settlement(w=0.15),))],
        )
    p0 = GAMMA_BACKFILL * D_EMB
    nq = math.exp(math.pi * math.tan(math.radians(30.0))) * math.tan(math.radians(60.0)) ** 2
    cap = scene.limit_analysis(max_steps=0)
    assert cap.problem.site.footings[0].interface.kind == "smooth"
    assert (cap.lb / 2.0 + p0) <= p0 * nq * (1 + REL) and p0 * nq <= (cap.ub / 2.0 + p0) * (1 + REL)


def test_the_lower_bound_meets_both_tractions_at_a_trench_corner():
    """The trench wall's top corner (ground under the surcharge q, wall under K0 q + K0 gamma |z|) lies in
    one triangle of the mesh with both edges: its certified stress there must carry both tractions,
    sigma_z = -q on the ground and sigma_x = -K0 q on the wall, tau = 0 (K0 = 1: sigma = -q I; the wall's
    row was skipped before, and this test failed). Tolerance 1e-6 q: the projection's equality residual."""
    from ssi.capacity import initial_mesh
    from ssi.limit import lower_bound

    q = 10e3
    back = SoilLayer(D_EMB, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, unit_weight=GAMMA_BACKFILL, K0=1.0)
    problem = limit_problem(_embedded(back, surcharge=q), side_soil="soil")
    mesh = initial_mesh(problem, None, None)
    corner = int(np.argmin(np.hypot(mesh.xy[:, 0] - 1.0, mesh.xy[:, 1])))  # (B/2, 0)
    assert np.hypot(*(mesh.xy[corner] - (1.0, 0.0))) < 1e-12
    lb = lower_bound(problem.site, mesh)
    assert lb.certified
    els, verts = np.nonzero(mesh.tri == corner)
    assert len(els) >= 1
    for e, v in zip(els, verts):
        sx, sz, tau = lb.stress[e, v]
        assert sx == pytest.approx(-q, abs=1e-6 * q) and sz == pytest.approx(-q, abs=1e-6 * q)
        assert tau == pytest.approx(0.0, abs=1e-6 * q)


def _side_contact_scene(side):
    """Chapter 12's embedded strip (B = 2 m, D = 1 m, whole model) as a stiff elastic plate (rigid in the
    limit problem) bonded on its base, c = 0, phi = 30 deg sand beside it (K0 = 1) and weightless below,
    pushed by a Settlement (lambda = V); ``side`` the trench walls' contact."""
    back = SoilLayer(D_EMB, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, unit_weight=GAMMA_BACKFILL, K0=1.0)
    sand = SoilLayer(5.0, E=20e6, nu=0.3, c=0.0, phi_deg=30.0, K0=1.0)
    return Scene(
        width=12.0,
        depth=5.0 + D_EMB,
        layers=[back, sand],
        embedment=D_EMB,
        foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9),
        loads=[Settlement(0.05)],
        side_contact=side,
    )


def test_a_side_contact_puts_the_trench_walls_on_the_strip():
    """side_soil='soil' with a side_contact: the trench walls become segments of the strip's footing on
    that contact (Coulomb c_i, phi_i and its tension cut-off; bonded: rough), instead of free faces under
    their geostatic stress. Theorems that hold mesh by mesh, so on one mesh: the free walls' geostatic
    traction (normal, compressive, equal and opposite on the two walls: no net force or moment on the
    strip) is admissible for any no-tension contact, and a contact only removes mechanisms; a stronger
    contact (a wider Coulomb cone, bonded the strongest) does both again. So both bounds rise along free <=
    smooth (c_i = 0, phi_i = 0, no tension) <= phi_i = 20 deg <= bonded (to the solvers' REL). Measured on
    this coarse mesh (182 triangles): LB 0.478, 0.487, 0.525, 0.527 MN/m, UB 0.961, 0.980, 1.027, 1.088
    (on the default initial mesh, 302 triangles: LB 0.537, 0.539, 0.586, 0.595, UB 0.771 .. 0.845)."""
    from ssi.capacity import initial_mesh

    sides = (
        None,
        Contact(kn=1e10, kt=1e9, phi_deg=0.0, sig_t=0.0),
        Contact(kn=1e10, kt=1e9, phi_deg=20.0, sig_t=0.0),
        Contact(kn=1e10, kt=1e9),
    )
    problems = [limit_problem(_side_contact_scene(side), side_soil="soil") for side in sides]
    free_walls = [b for _, _, b in problems[0].site.segments if b is not None and any(b.pressure_dead_grad)]
    assert len(free_walls) == 2 and all(b.kind == "free" for b in free_walls)
    for p, kind in zip(problems[1:], ("coulomb", "coulomb", "rough")):
        walls = [b for _, _, b in p.site.segments if b is not None and b.interface is not None]
        assert len(walls) == 2 and all(b.kind == "footing" and b.interface.kind == kind for b in walls)
    assert problems[2].site.interfaces[1] == Interface("coulomb", phi_deg=20.0, psi_deg=0.0, tension=0.0)
    # the walls' psi_i = 0 enters the Davis bracket: tan phi* = beta tan phi_i (beta = cos 20 deg)
    tan_star = math.tan(math.radians(problems[2].site.davis().interfaces[1].phi_deg))
    assert tan_star == pytest.approx(math.cos(math.radians(20.0)) * math.tan(math.radians(20.0)), rel=1e-12)
    mesh = initial_mesh(problems[0], 3.0, 0.4)
    brackets = [bracket(p.site, mesh) for p in problems]
    assert all(b.lower.certified and b.upper.certified for b in brackets)
    for weak, strong in zip(brackets[:-1], brackets[1:]):
        assert strong.lb >= weak.lb * (1 - REL) and strong.ub >= weak.ub * (1 - REL)


def test_a_sites_embedded_strip_stands_in_its_trench():
    """A Site's embedded Strip (``level`` -1 m, B = 2 m, a central column N, weightless Tresca clay c): the
    site's own geometry with its trench, the walls free faces (the incremental site's trench is open while
    gravity loads it) or, with ``side_contact``, footing segments on that contact; the strip rotates about
    the centre of its base. Prandtl's field below the base level with zero stress above it is admissible,
    so the true capacity is at least (2 + pi) c B (the surface strip's, exact): the upper bound is above it
    (a theorem), and so, measured, is the certified lower bound (the side soil carries: 5.54 c B on the
    default mesh, 5.61 .. 6.11 c B at a 5 % gap); bonded walls raise both bounds on one mesh (theorem).
    A RigidStrip in a trench (Settlement push) is taken too; side_soil='surcharge' has no meaning here."""
    from ssi.capacity import initial_mesh
    from ssi.scene.site import RigidStrip, Site, Strip

    c, n_col = 20e3, 100e3
    clay = [SoilLayer.undrained(6.0, E_u=30e6, s_u=c)]

    def site(side):
        strip = Strip(
            Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)), Contact(kn=1e10, kt=1e9), -1.0, side
        )
        return Site(width=12.0, depth=6.0, layers=clay, strips=[strip], loads=[ColumnLoad(0.0, N=n_col)])

    free, bonded = limit_problem(site(None)), limit_problem(site(Contact(kn=1e10, kt=1e9)))
    (ft,) = free.site.footings
    assert ft.centre == (0.0, -1.0) and ft.moves == ("x", "z", "r")
    walls = [b for i, j, b in free.site.segments if b is not None and _vertical_at_strip_end(free.site, i, j)]
    assert len(walls) == 2 and all(b.traction_free for b in walls)
    walls = [
        b for i, j, b in bonded.site.segments if b is not None and _vertical_at_strip_end(bonded.site, i, j)
    ]
    assert len(walls) == 2 and all(b.kind == "footing" and b.interface.kind == "rough" for b in walls)
    assert {(1.0, 0.0), (-1.0, 0.0), (1.0, -1.0), (-1.0, -1.0)} <= set(free.singular)
    mesh = initial_mesh(free, 3.0, 0.4)
    b_free, b_bonded = bracket(free.site, mesh), bracket(bonded.site, mesh)
    prandtl = (2.0 + math.pi) * c * 2.0 / n_col
    assert b_free.lower.certified and b_free.ub * (1 + REL) >= prandtl
    assert b_free.lb > prandtl
    assert b_bonded.lb >= b_free.lb * (1 - REL) and b_bonded.ub >= b_free.ub * (1 - REL)
    rigid = Site(width=12.0, depth=6.0, layers=clay, strips=[RigidStrip(-1.0, 1.0, 0.05, level=-1.0)])
    p = limit_problem(rigid)
    assert p.lam_unit == "N/m" and p.site.footings[0].moves == ("z",)
    with pytest.raises(
        ValueError, match=r"side_soil='surcharge': a Site's embedded strip stands in its trench"
    ):
        limit_problem(rigid, side_soil="surcharge")


def _vertical_at_strip_end(site, i, j) -> bool:
    """Whether segment i-j of a limit site is vertical at x = +-1 m (a trench wall of the strip above)."""
    (xa, za), (xb, zb) = site.points[i], site.points[j]
    return abs(xa - xb) < 1e-12 and abs(abs(xa) - 1.0) < 1e-12 and min(za, zb) >= -1.0 - 1e-12
