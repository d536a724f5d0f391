"""Bearing-capacity scenes: a rigid strip footing pushed into a Mohr–Coulomb block under displacement control,
and Smith & Griffiths' flexible footing (Program 6.1) under load control.

Used by ``chapters/10_bearing_capacity.py``, ``tests/test_bearing_capacity.py`` and
``benchmarks/bench_footing.py``. Plain Python orchestration; all numerics are the library's kernels.

Geometry of the rigid footing: by symmetry only the half x >= 0 is modelled (u = 0 on x = 0): a block
``half_width`` wide and ``depth`` deep, the footing on 0 <= x <= B/2. The footing nodes get a prescribed
settlement (w = -lambda * settle) and, for a rough base, u = 0; smooth: u free. The footing pressure is
q = 2 R / B with R the vertical reaction of the half footing. The model is a :class:`ssi.scene.Scene`
(:func:`footing_scene`: ``symmetric=True``, a :class:`ssi.scene.RigidFooting`, a ``Settlement``), so the
scene builder is the only place a soil block is set up.
"""

import inspect
import math
import time
from dataclasses import dataclass, replace

import numpy as np

from ..core.mesh import structured_q8
from ..core.model import Model
from ..core.validate import (
    check_bool,
    check_choice,
    check_instance,
    check_int,
    check_optional_real,
    check_real,
)
from ..elements.soil_q8 import SoilQ8
from ..elements.supports import fix_block, soil_group, surface_pressure
from ..materials.soil_laws import mohr_coulomb_params, von_mises_params
from ..scene import BuiltScene, MeshSize, RigidFooting, Scene, Settlement, SoilLayer
from ..solver import NonConvergence, Settings, run


def prandtl(c, phi_deg, q=0.0):
    """Prandtl–Reissner bearing capacity of a weightless soil: returns (q_u, Nc, Nq).

    Nq = exp(π tan φ) tan²(45° + φ/2), Nc = (Nq - 1) cot φ (Nc = 2 + π for φ = 0), q_u = c Nc + q Nq.
    """
    c = check_real("c", c, lo=0.0, unit="Pa")
    phi_deg = check_real("phi_deg", phi_deg, lo=0.0, hi=90.0, hi_open=True, unit="degrees")
    q = check_real("q", q, lo=0.0, unit="Pa")
    if phi_deg == 0.0:
        nq, nc = 1.0, 2.0 + math.pi
    else:
        t = math.tan(math.radians(phi_deg))
        nq = math.exp(math.pi * t) * math.tan(math.radians(45.0 + 0.5 * phi_deg)) ** 2
        nc = (nq - 1.0) / t
    return c * nc + q * nq, nc, nq


@dataclass
class FootingScene:
    """A built footing model and what :func:`push_footing` reads off it: ``footing`` the node ids under the
    (half) footing, ``B`` the footing width [m], ``info`` its parameters; ``built`` the
    :class:`ssi.scene.BuiltScene` it came from (None for :func:`sg61_scene`, built by hand)."""

    model: Model
    soil: SoilQ8
    footing: np.ndarray  # node ids under the (half) footing
    B: float
    mesh: object
    info: dict
    built: BuiltScene | None = None


def rigid_footing(**options: object) -> FootingScene:
    """Half model of a rigid strip footing of width ``B`` [m] on a weightless Mohr–Coulomb block: the scene of
    :func:`footing_scene` (same keyword arguments ``options``, same defaults), built.

    ``settle`` is the footing settlement at load factor 1 [m]. ``surcharge`` [Pa] acts on the ground surface
    beside the footing and, as an isotropic initial stress (K0 = 1), everywhere (weightless soil in
    equilibrium). ``layers``: optional list of :class:`ssi.scene.SoilLayer` from the surface down
    (Mohr--Coulomb: ``c`` set; weightless: ``unit_weight`` 0), overriding the single material (for the
    stiffness-contrast extreme); their thickness, E, nu, c, phi_deg and psi_deg are used (psi_deg None:
    associated, psi = phi), with this function's ``scheme``, ``n_sub``, ``drift`` and K0 = 1.
    """
    args = inspect.signature(footing_scene).bind(**options)
    args.apply_defaults()
    p = args.arguments
    built = footing_scene(**p).build()
    info = {k: p[k] for k in _INFO_KEYS} | {"psi_deg": p["phi_deg"] if p["psi_deg"] is None else p["psi_deg"]}
    info |= {"n_el": len(built.mesh.conn), "n_dof": built.model.n_dof}
    return FootingScene(built.model, built.soil, built.footing_nodes, p["B"], built.mesh, info, built)


# the arguments of footing_scene that FootingScene.info repeats (with psi_deg resolved, n_el and n_dof)
_INFO_KEYS = ("B", "c", "phi_deg", "psi_deg", "E", "nu", "rough", "half_width", "depth", "h_fine", "scheme")
_INFO_KEYS += ("n_sub", "drift", "surcharge")


def footing_scene(
    B=2.0,
    c=10e3,
    phi_deg=20.0,
    psi_deg=None,
    E=20e6,
    nu=0.3,
    rough=True,
    half_width=10.0,
    depth=10.0,
    h_fine=0.25,
    h_coarse=2.0,
    growth=1.25,
    scheme="implicit",
    n_sub=1,
    drift=False,
    surcharge=0.0,
    settle=0.1,
    n_gauss=2,
    layers=None,
) -> Scene:
    """The :class:`ssi.scene.Scene` of :func:`rigid_footing` (same arguments, same units): a symmetric scene
    (only the half x >= 0 modelled) ``2 half_width`` wide and ``depth`` deep, a :class:`RigidFooting` from
    -B/2 to B/2 (``rough``) pushed by ``Settlement(settle)``, weightless layers with K0 = 1 (isotropic
    initial stress under the ``surcharge``), the mesh ``MeshSize(h_fine, h_coarse, growth, n_gauss)``."""
    B = check_real("B", B, lo=0.0, lo_open=True, unit="m")
    half_width = check_real("half_width", half_width, lo=0.0, lo_open=True, unit="m")
    depth = check_real("depth", depth, lo=0.0, lo_open=True, unit="m")
    if half_width <= B / 2:
        raise ValueError(
            f"half_width must be > B/2 = {B / 2:g} m (the block must extend beyond the footing), "
            f"got half_width={half_width!r}"
        )
    check_real("settle", settle, lo=0.0, lo_open=True, unit="m (footing settlement at load factor 1)")
    check_real("surcharge", surcharge, lo=0.0, unit="Pa")
    for name, value in (("c", c), ("E", E), ("nu", nu), ("phi_deg", phi_deg)):
        check_real(name, value)  # types and finiteness; the law's parameter check gives the ranges
    check_optional_real("psi_deg", psi_deg)
    check_bool("rough", rough)
    check_bool("drift", drift)
    check_choice("n_gauss", n_gauss, (2, 3))
    if layers is None:
        mohr_coulomb_params(E, nu, c, phi_deg, psi_deg, scheme=scheme, n_sub=n_sub, drift=drift)  # its checks
        layers = [SoilLayer(depth, E=E, nu=nu, c=c, phi_deg=phi_deg, psi_deg=psi_deg)]
    for i, lay in enumerate(layers):
        check_instance(f"layers[{i}]", lay, SoilLayer)
        if lay.c is None or lay.unit_weight != 0.0:
            raise ValueError(
                f"layers[{i}] must be a weightless Mohr-Coulomb layer (c set, unit_weight 0) for the "
                f"rigid footing, got c={lay.c!r}, unit_weight={lay.unit_weight!r}"
            )
    layers = [replace(lay, K0=1.0, scheme=scheme, n_sub=n_sub, drift=drift) for lay in layers]
    return Scene(
        width=2.0 * half_width,
        depth=depth,
        layers=layers,
        foundation=RigidFooting(-0.5 * B, 0.5 * B, rough=rough),
        loads=[Settlement(settle)],
        mesh=MeshSize(h_fine=h_fine, h_coarse=h_coarse, growth=growth, n_gauss=n_gauss),
        surcharge=surcharge,
        symmetric=True,
    )


# chapter 10's footing: B = 2 m, c = 10 kPa, phi = 20 deg, E = 20 MPa, nu = 0.3, rough, 6 m x 5 m half block
CHAPTER10_FOOTING = dict(
    B=2.0,
    c=10e3,
    phi_deg=20.0,
    E=20e6,
    nu=0.3,
    rough=True,
    half_width=6.0,
    depth=5.0,
    h_coarse=1.0,
    growth=1.25,
    settle=0.06,
)


def chapter10_footing(**overrides: object) -> FootingScene:
    """Chapter 10's rigid rough strip footing, B = 2 m on weightless Mohr--Coulomb soil (c = 10 kPa,
    phi = 20 deg, associated unless ``psi_deg`` is given; E = 20 MPa, nu = 0.3 -- the limit load does not
    depend on them): the half model on a block 6 m wide and 5 m deep, elements ``h_fine`` (default 0.25 m)
    under the footing growing by 1.25 up to 1 m, pushed to 6 cm. ``overrides``: any other
    :func:`rigid_footing` arguments (chapters 06 and 12, the benchmarks and the tests vary it)."""
    return rigid_footing(**(CHAPTER10_FOOTING | overrides))


def footing_pressure(scene: FootingScene, result):
    """(settlement [m, positive down], pressure q [Pa]) histories of a rigid-footing run.

    The pressure is the footing's reaction: the soil's internal force at the footing nodes minus the external
    force on them. A surcharge beside the footing puts its consistent share q L/6 on the footing's edge node
    (L the next element); counting it as footing pressure overstated q by 874 Pa at h = 0.25 m and 1707 Pa at
    0.5 m under chapter 12's 20 kPa (measured), an error that only vanished with the mesh."""
    w = result.displacement(scene.footing[:1], "w")[:, 0]
    q = -result.support_reaction(scene.footing, "w") / (0.5 * scene.B)
    return -w, q


def footing_settings(**overrides: object) -> Settings:
    """Full Newton on load control, the footing setting the studies of the Newton variant and the step size
    name (chapter 10's trade study, chapter 13's solver comparison, chapter 19's slope; not
    :func:`push_footing`'s default, which is :func:`footing_path_settings`): the consistent tangent with a
    backtracking line search, each prescribed settlement increment taken as one increment (the increments
    are the study's variable), halved up to 8 times on failure. Plain Newton steps near the footing corner
    overshoot into a far plastic state and diverge; the line search stops that. Without load control's
    former L-BFGS retry (issue 31) a failed increment is only halved: on the bench footing with psi = 0
    (``benchmarks/bench_nonlinear.py``) it then took 16.7 s CPU against 4.0 s, 61 failed attempts.

    SuperLU is the backend: at a few thousand DOFs PARDISO's set-up costs 0.3-0.5 s per factorisation
    against SuperLU's 0.01-0.03 s. ``overrides`` are further :class:`ssi.solver.Settings` fields."""
    return Settings(
        **{"method": "full", "line_search": True, "stepping": "fixed", "control": "load", "max_cuts": 8}
        | {"backend": "superlu"}
        | overrides
    )


def footing_path_settings(**overrides: object) -> Settings:
    """:func:`push_footing`'s default: the controlled path (``control="work"``, :mod:`ssi.solver.path`; with
    the prescribed settlement and no force load its control is the settlement itself) with its own step
    rule, on SuperLU (see :func:`footing_settings` for why). The push's settlement targets bound the steps
    (the path lands on each target and never steps past one), so no step is longer than one increment; where
    the pressure peaks or stays on a plateau the path ends there as a limit, before the full settlement.

    Why the path's own first and largest step (0.1 and 0.25 of the push) and not the increments as the step
    budget (first_step = max_step = 1/n_steps): measured on the bench footing (``bench_nonlinear.py``: psi =
    0, h = 0.125 m, 12 targets), at main f6cc289 the defaults completed with q_u / Prandtl 0.99516 in 6.7 s
    (full Newton in 12 fixed increments: 0.99539 in 16.1 s, same run) and the 1/12 budget ended in
    NonConvergence at 76.1 of 80 mm (q_u / Prandtl 0.9785); on the path of main cd8ff2a the defaults 0.99427
    in 4.8 s CPU, the budget 0.98924 in 6.6 s. The chapters' pushes need no budget: the targets are one.
    ``overrides`` are further :class:`ssi.solver.Settings` fields."""
    return Settings(**({"control": "work", "backend": "superlu"} | overrides))


def push_footing(
    scene: FootingScene, n_steps: int = 20, grading: float = 1.0, settings: Settings | None = None
) -> dict:
    """Push the footing to the settlement ``settle`` through ``n_steps`` targets (``grading`` > 1 makes the
    first steps smaller: lambda_i = (i/n)^grading) with ``ssi.solver.run`` and ``settings`` (default
    :func:`footing_path_settings`: the controlled path, which may end at a limit before the last target;
    :func:`footing_settings` is full Newton on the same targets as fixed increments). Returns a dict with
    settlement [m], q [Pa], q_u [Pa] (the largest pressure reached by a state of the rate-independent law,
    see ``Result.rate_independent_steps``), iterations per step, wall time [s], and the failure report if
    the solver stopped.
    """
    check_instance("scene", scene, FootingScene)
    n_steps = check_int("n_steps", n_steps, lo=1)
    grading = check_real("grading", grading, lo=0.0, lo_open=True)
    check_instance("settings", settings, Settings, optional=True)
    if settings is None:
        settings = footing_path_settings()
    lam = (np.arange(1, n_steps + 1) / n_steps) ** grading
    t0 = time.perf_counter()
    failure = None
    try:
        res = run(scene.model, lam, settings)
    except NonConvergence as err:
        res = err.result
        failure = err.report
    wall = time.perf_counter() - t0
    s, q = footing_pressure(scene, res)
    return dict(
        settlement=s,
        q=q,
        q_u=float(q[res.rate_independent_steps()].max()),  # a viscous state's overstress is not capacity
        iterations=list(res.iterations[1:]),
        n_iterations=int(sum(res.iterations[1:])),
        wall_time=wall,
        result=res,
        failure=failure,
        cuts=res.cuts,
        factorizations=res.factorizations,
    )


# ---------------------------------------------------------------------------------------------------------
# Smith & Griffiths, Program 6.1
# ---------------------------------------------------------------------------------------------------------
SG61_X = (0.0, 1.0, 2.0, 3.0, 4.0, 5.5, 7.0, 9.0, 12.0)
SG61_Z = (-5.0, -3.75, -2.5, -1.25, 0.0)


def sg61_scene(law="von_mises", E=1e5 * 1e3, nu=0.3, cu=100e3, n_gauss=2, refine=1):
    """The flexible strip footing of Smith & Griffiths' Program 6.1 (half model, 8 × 4 Q8 elements, footing
    half width 2 m): x = 0 and x = 12 m on rollers (u = 0), base fixed. ``law``: "von_mises" (the peer's
    sqrt(J2) = cu) or "tresca" (Mohr–Coulomb with φ = 0). Load factor = footing pressure in kPa.
    ``refine`` splits every element into refine × refine."""
    check_choice("law", law, ("von_mises", "tresca"))
    refine = check_int("refine", refine, lo=1, hi=64)
    check_real("E", E)
    check_real("nu", nu)
    check_real("cu", cu)
    x = _refine_lines(SG61_X, refine)
    z = _refine_lines(SG61_Z, refine)
    mesh = structured_q8(x, z)
    model = Model()
    ids = model.add_nodes(mesh.xy, ndof=2)
    if law == "von_mises":
        mat = von_mises_params(E, nu, cu)
    elif law == "tresca":
        mat = mohr_coulomb_params(E, nu, cu, 0.0)
    else:
        raise ValueError(f"law must be 'von_mises' or 'tresca', got {law!r}")
    soil = soil_group(model, mesh, [mat], ids=ids, n_gauss=n_gauss)
    fix_block(model, mesh, ids)
    surface_pressure(model, mesh, 0.0, 2.0, 1e3, ids=ids)  # 1 kPa per unit load factor
    centre = mesh.nodes_between(0.0, 0.0)
    return FootingScene(model, soil, centre, 4.0, mesh, dict(law=law, refine=refine))


def _refine_lines(lines, r):
    lines = np.asarray(lines, float)
    if r == 1:
        return lines
    out = [lines[0]]
    for a, b in zip(lines[:-1], lines[1:]):
        out.extend(a + (b - a) * np.arange(1, r + 1) / r)
    return np.array(out)
