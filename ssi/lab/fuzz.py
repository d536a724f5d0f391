"""Property-based study of the public API's handling of bad input (hypothesis strategies and the driver).

Two populations of inputs, drawn by ``hypothesis`` (a test dependency: ``pip install -e '.[test]'``):

* **invalid cases** (:func:`invalid_cases`): a small valid base call of one public entry point (a scene built
  and solved, a ``Section`` used in a scene, ``Settings``, the footing builders, ``prandtl``, the analytical
  references) with *one* argument replaced by a value outside its allowed set -- a wrong type (string,
  ``None`` where a number is required, list, complex), NaN or infinity, a number outside its range, an
  unknown option -- or one of a list of relational faults (psi > phi, a foundation outside the block, layers
  that do not tile the depth, inconsistent section arrays...). The allowed sets are written down once, in
  the ``*_SPEC`` tables below, next to the base call they perturb.
* **valid scenes** (:func:`valid_scenes`): small random scenes (one or two elastic or Mohr--Coulomb layers,
  a homogeneous foundation, bonded or Coulomb contact, a column load, one to three load steps).

:func:`classify_invalid` runs one invalid case and names the outcome: ``"named"`` (a ``ValueError`` or
``TypeError`` whose message names the parameter and the value given), ``"unnamed"`` (one that does not),
``"returned"`` (a result came back), ``"other"`` (any other exception, including ``NonConvergence``) or
``"timeout"``. :func:`classify_valid` runs one valid scene: ``"solved"`` (finite settlements),
``"nonconvergence"`` (the solver's named stop) or anything else, which is a failure. :func:`study` draws a
bounded, seeded number of examples of both and tallies them; ``tests/test_fuzz.py`` runs the same
strategies under ``@given`` (with shrinking) and ``chapters/16_bad_input.py`` reports the tallies.
"""

import contextlib
import math
import signal
import time
from dataclasses import dataclass, field

import numpy as np
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

__all__ = ["InvalidCase", "classify_invalid", "classify_valid", "invalid_cases", "study", "valid_scenes"]

CASE_TIMEOUT = 30.0  # [s] one case; an input that makes the code loop (width = inf) must not stall the study


# ---- allowed sets ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Real:
    """A real number in [lo, hi] (ends open on request); ``optional``: None allowed; ``allow_inf``: +-inf
    allowed within the bounds."""

    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    optional: bool = False
    allow_inf: bool = False


@dataclass(frozen=True)
class Integer:
    lo: int | None = None
    hi: int | None = None
    optional: bool = False


@dataclass(frozen=True)
class Choice:
    choices: tuple
    optional: bool = False  # None is valid too (it means a default rule, e.g. Settings.method)


@dataclass(frozen=True)
class Flag:
    """True or False."""


@dataclass(frozen=True)
class Instance:
    """An object of a given class; the invalid values are other objects."""

    optional: bool = False


POSITIVE = Real(lo=0.0, lo_open=True)
NON_NEGATIVE = Real(lo=0.0)
ANY_REAL = Real()
ANGLE = Real(lo=0.0, hi=90.0, hi_open=True)
POISSON = Real(lo=-1.0, hi=0.5, lo_open=True, hi_open=True)

# base values of every perturbed call (a small linear scene: one factorisation, one solve)
BASE_LAYER = dict(
    thickness=4.0,
    E=20e6,
    nu=0.3,
    unit_weight=18e3,
    c=None,
    phi_deg=30.0,
    psi_deg=None,
    K0=None,
    scheme="implicit",
)
BASE_FOUNDATION = dict(x0=-1.0, x1=1.0, kappa=5.0 / 6.0, integration="selective", self_weight=0.0)
BASE_CONTACT = dict(kn=1e10, kt=1e9, phi_deg=None, c=0.0, psi_deg=None, sig_t=None, rule="newton_cotes")
BASE_LOAD = dict(x=0.0, N=200e3, H=0.0, M=0.0)
BASE_MESH = dict(h_fine=0.5, h_coarse=2.0, growth=1.5, n_gauss=2)
BASE_SCENE = dict(width=8.0, depth=4.0, surcharge=0.0)
BASE_SOLVE = dict(n_steps=1)
BASE_SECTION = dict(thickness=0.5, E=30e9, nu=0.2, n_layers=2)
BASE_RIGID = dict(
    B=1.0,
    c=20e3,
    phi_deg=0.0,
    E=20e6,
    nu=0.3,
    half_width=3.0,
    depth=2.0,
    h_fine=0.5,
    h_coarse=1.0,
    settle=1e-4,
    surcharge=0.0,
    n_gauss=2,
    scheme="implicit",
    rough=True,
)
BASE_PUSH = dict(n_steps=1, grading=1.0)  # solver options: Settings, fuzzed as its own target
BASE_PRANDTL = dict(c=10e3, phi_deg=20.0, q=0.0)
BASE_SADOWSKY = dict(a=1.0, P=1e5)
BASE_HETENYI = dict(P=1e5, k=1e7, EI=1e8)
BASE_SHEAR_LAG = dict(tau_bar=50e3, EA=1e9, kt=1e9, L=1.0, tau_f=100e3)

LAYER_SPEC = dict(
    thickness=POSITIVE,
    E=POSITIVE,
    nu=POISSON,
    unit_weight=NON_NEGATIVE,
    c=Real(lo=0.0, optional=True),
    phi_deg=ANGLE,
    psi_deg=Real(lo=0.0, hi=30.0, optional=True),
    K0=Real(lo=0.0, hi=10.0, hi_open=True, optional=True),
    scheme=Choice(("implicit", "explicit")),
)
FOUNDATION_SPEC = dict(
    x0=ANY_REAL,
    x1=ANY_REAL,
    kappa=Real(lo=0.0, hi=1.0, lo_open=True),
    integration=Choice(("selective", "full", "reduced")),
    self_weight=NON_NEGATIVE,
    section=Instance(),
)
CONTACT_SPEC = dict(
    kn=POSITIVE,
    kt=NON_NEGATIVE,
    phi_deg=Real(lo=0.0, hi=90.0, hi_open=True, optional=True),
    c=Real(lo=0.0, allow_inf=True),
    psi_deg=Real(lo=0.0, hi=90.0, hi_open=True, optional=True),
    sig_t=Real(lo=0.0, optional=True),
    rule=Choice(("newton_cotes", "gauss")),
)
LOAD_SPEC = dict(x=ANY_REAL, N=ANY_REAL, H=ANY_REAL, M=ANY_REAL)
MESH_SPEC = dict(h_fine=POSITIVE, h_coarse=POSITIVE, growth=Real(lo=1.0), n_gauss=Choice((2, 3)))
SCENE_SPEC = dict(
    width=POSITIVE,
    depth=POSITIVE,
    surcharge=NON_NEGATIVE,
    layers=Instance(),
    foundation=Instance(optional=True),
    contact=Instance(optional=True),
    loads=Instance(),
    mesh=Instance(),
)
SOLVE_SPEC = dict(n_steps=Integer(lo=1, optional=True), settings=Instance(optional=True))
SETTINGS_SPEC = dict(
    method=Choice(("bfgs", "modified", "full"), optional=True),
    stepping=Choice(("auto", "fixed")),
    convergence_reference=Choice(("structural", "total")),
    force_tol=Real(0.0, 1.0, True, True),
    energy_tol=Real(0.0, 1.0, True, True),
    max_iter=Integer(lo=1, optional=True),
    max_cuts=Integer(lo=0),
    divergence_ratio=Real(lo=1.0, lo_open=True),
    backend=Choice(("auto", "superlu", "pardiso")),
    symmetric_tangent=Flag(),
    verbose=Flag(),
    keep_states=Flag(),
    line_search_min=Real(0.0, 1.0, lo_open=True),
    desired_iterations=Integer(lo=1, optional=True),
    bfgs_memory=Integer(lo=0),
)
HOMOGENEOUS_SPEC = dict(thickness=POSITIVE, E=POSITIVE, nu=POISSON, n_layers=Integer(lo=1))
RIGID_SPEC = dict(
    B=POSITIVE,
    c=NON_NEGATIVE,
    phi_deg=ANGLE,
    E=POSITIVE,
    nu=POISSON,
    half_width=POSITIVE,
    depth=POSITIVE,
    h_fine=POSITIVE,
    h_coarse=POSITIVE,
    settle=POSITIVE,
    surcharge=NON_NEGATIVE,
    n_gauss=Choice((2, 3)),
    scheme=Choice(("implicit", "explicit")),
    rough=Flag(),
)
PUSH_SPEC = dict(n_steps=Integer(lo=1), grading=POSITIVE)
PRANDTL_SPEC = dict(c=NON_NEGATIVE, phi_deg=ANGLE, q=NON_NEGATIVE)
SADOWSKY_SPEC = dict(a=POSITIVE, P=ANY_REAL)
HETENYI_SPEC = dict(P=ANY_REAL, k=POSITIVE, EI=POSITIVE)
SHEAR_LAG_SPEC = dict(tau_bar=Real(lo=0.0, hi=100e3), EA=POSITIVE, kt=POSITIVE, L=POSITIVE, tau_f=POSITIVE)


# ---- the perturbed calls -----------------------------------------------------------------------------------
def _section(**kw):
    from ..elements.section import homogeneous

    return homogeneous(**{**BASE_SECTION, **kw})


def run_scene(
    layer=None,
    foundation=None,
    contact=None,
    load=None,
    mesh=None,
    scene=None,
    solve=None,
    section=None,
    settings_kw=None,
):
    """Build and solve the base scene with the given overrides of each component; returns the result."""
    from ..scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer
    from ..solver import Settings

    parts = dict(
        layers=[SoilLayer(**{**BASE_LAYER, **(layer or {})})],
        foundation=Foundation(
            **{**BASE_FOUNDATION, "section": _section() if section is None else section, **(foundation or {})}
        ),
        contact=Contact(**{**BASE_CONTACT, **(contact or {})}),
        loads=[ColumnLoad(**{**BASE_LOAD, **(load or {})})],
        mesh=MeshSize(**{**BASE_MESH, **(mesh or {})}),
    )
    parts.update(scene or {})
    scene_obj = Scene(**{**BASE_SCENE, **parts})
    solve_kw = {**BASE_SOLVE, **(solve or {})}
    if settings_kw is not None:
        solve_kw["settings"] = Settings(**settings_kw)
    return scene_obj.build().solve(**solve_kw)


def _run_section(**fields):
    from ..elements.section import Section

    base = _section()
    arrays = {
        k: getattr(base, k) for k in ("z_mid", "h", "kind", "params", "carries_shear", "z_bottom", "z_top")
    }
    return run_scene(section=Section(**{**arrays, **fields}))


def _run_push(**kw):
    from .bearing_capacity import push_footing, rigid_footing

    rigid = {k: kw.pop(k) for k in list(kw) if k in RIGID_SPEC}
    return push_footing(rigid_footing(**{**BASE_RIGID, **rigid}), **{**BASE_PUSH, **kw})


def _run_prandtl(**kw):
    from .bearing_capacity import prandtl

    return prandtl(**{**BASE_PRANDTL, **kw})


def _run_sadowsky(**kw):
    from .analytical import sadowsky_pressure

    return sadowsky_pressure(np.array([0.0, 0.5]), **{**BASE_SADOWSKY, **kw})


def _run_hetenyi(**kw):
    from .analytical import hetenyi_deflection

    return hetenyi_deflection(np.array([0.0, 1.0]), **{**BASE_HETENYI, **kw})


def _run_shear_lag(**kw):
    from .analytical import shear_lag_state

    return shear_lag_state(**{**BASE_SHEAR_LAG, **kw})


def _run_homogeneous(**kw):
    return run_scene(section=_section(**kw))


# target name -> (call taking the overridden keyword arguments, allowed sets)
TARGETS = {
    "SoilLayer": (lambda **kw: run_scene(layer=kw), LAYER_SPEC),
    "Foundation": (lambda **kw: run_scene(foundation=kw), FOUNDATION_SPEC),
    "Contact": (lambda **kw: run_scene(contact=kw), CONTACT_SPEC),
    "ColumnLoad": (lambda **kw: run_scene(load=kw), LOAD_SPEC),
    "MeshSize": (lambda **kw: run_scene(mesh=kw), MESH_SPEC),
    "Scene": (lambda **kw: run_scene(scene=kw), SCENE_SPEC),
    "solve": (lambda **kw: run_scene(solve=kw), SOLVE_SPEC),
    "Settings": (lambda **kw: run_scene(settings_kw=kw), SETTINGS_SPEC),
    "homogeneous": (_run_homogeneous, HOMOGENEOUS_SPEC),
    "rigid_footing/push_footing": (_run_push, {**RIGID_SPEC, **PUSH_SPEC}),
    "prandtl": (_run_prandtl, PRANDTL_SPEC),
    "sadowsky_pressure": (_run_sadowsky, SADOWSKY_SPEC),
    "hetenyi_deflection": (_run_hetenyi, HETENYI_SPEC),
    "shear_lag_state": (_run_shear_lag, SHEAR_LAG_SPEC),
    "Section": (_run_section, {}),
}


@dataclass(frozen=True)
class InvalidCase:
    """One public call with one invalid argument: ``target`` (a key of TARGETS), the keyword ``overrides``,
    and the parameter name (and value text, if any) the error message must contain."""

    target: str
    overrides: dict = field(hash=False)
    param: str = ""
    value_text: tuple = ()  # the message must contain one of these (empty: the name suffices)

    def __repr__(self):
        return f"InvalidCase({self.target}: {self.overrides!r}, expect {self.param!r})"


def _texts(value) -> tuple:
    if isinstance(value, str | float | int | complex | type(None)) and not isinstance(value, bool):
        return (repr(value), str(value))
    return ()


_BAD_OBJECTS = ("abc", [1.0], 1 + 2j)


def _invalid_values(spec):
    """Strategy of values outside the allowed set ``spec``."""
    if isinstance(spec, Real):
        bad = list(_BAD_OBJECTS) + ([] if spec.optional else [None]) + [math.nan]
        if not spec.allow_inf or spec.hi is not None:
            bad.append(math.inf)
        if not spec.allow_inf or spec.lo is not None:
            bad.append(-math.inf)
        parts = [st.sampled_from(bad)]
        if spec.lo is not None:
            parts.append(
                st.floats(
                    max_value=spec.lo, exclude_max=not spec.lo_open, allow_nan=False, allow_infinity=False
                )
            )
        if spec.hi is not None:
            parts.append(
                st.floats(
                    min_value=spec.hi, exclude_min=not spec.hi_open, allow_nan=False, allow_infinity=False
                )
            )
        return st.one_of(parts)
    if isinstance(spec, Integer):
        bad = ["abc", 2.7, math.nan, [1]] + ([] if spec.optional else [None])
        parts = [st.sampled_from(bad)]
        if spec.lo is not None:
            parts.append(st.integers(max_value=spec.lo - 1, min_value=spec.lo - 10**6))
        if spec.hi is not None:
            parts.append(st.integers(min_value=spec.hi + 1))
        return st.one_of(parts)
    if isinstance(spec, Choice):
        return st.sampled_from(["no_such_option", 7, 2.5] + ([] if spec.optional else [None]))
    if isinstance(spec, Flag):
        return st.sampled_from(["no", None, 0.5])
    return st.sampled_from(["abc", 1.0, [1.0]] + ([] if spec.optional else [None]))


def _field_cases():
    pairs = [(target, name, spec) for target, (_, table) in TARGETS.items() for name, spec in table.items()]

    def case(triple):
        target, name, spec = triple
        return _invalid_values(spec).map(lambda v: InvalidCase(target, {name: v}, name, _texts(v)))

    return st.sampled_from(pairs).flatmap(case)


def _relational_cases() -> list:
    """Faults that no single allowed set catches: each value is fine alone, not together."""
    lay, sec = "SoilLayer", "Section"
    base = _section_arrays()
    n = len(base["h"])
    return [
        InvalidCase(lay, dict(c=10e3, phi_deg=20.0, psi_deg=25.0), "psi_deg", ("25.0",)),
        InvalidCase(lay, dict(c=0.0, phi_deg=0.0), "phi_deg"),
        InvalidCase("Contact", dict(phi_deg=20.0, psi_deg=30.0), "psi_deg", ("30.0",)),
        InvalidCase("Contact", dict(phi_deg=30.0, c=1e3, sig_t=1e6), "sig_t"),
        InvalidCase("Foundation", dict(x0=1.0, x1=-1.0), "x0"),
        InvalidCase("Foundation", dict(x0=-1.0, x1=-1.0), "x0"),
        InvalidCase("Foundation", dict(x0=-9.0, x1=1.0), "x0", ("-9.0",)),
        InvalidCase("Foundation", dict(x0=-1.0, x1=5.0), "x1", ("5.0",)),
        InvalidCase("ColumnLoad", dict(x=3.0), "x", ("3.0",)),
        InvalidCase("ColumnLoad", dict(x=-1.5), "x", ("-1.5",)),
        InvalidCase("MeshSize", dict(h_fine=1.0, h_coarse=0.5), "h_coarse"),
        InvalidCase("MeshSize", dict(h_fine=100.0, h_coarse=200.0), "h_fine", ("100.0",)),
        InvalidCase("MeshSize", dict(h_fine=3.0, h_coarse=3.0), "h_fine", ("3.0",)),
        InvalidCase("Scene", dict(depth=5.0), "depth", ("5.0",)),
        InvalidCase("Scene", dict(width=1.0), "width"),
        InvalidCase("Scene", dict(layers=[]), "layers"),
        InvalidCase("Scene", dict(layers=["clay"]), "layers"),
        InvalidCase("Scene", dict(loads=[(0.0, 1e5)]), "loads"),
        InvalidCase("Scene", dict(foundation=None), "loads"),
        InvalidCase("Scene", dict(contact=None), "contact"),
        InvalidCase("Settings", dict(method="full", max_iter=0), "max_iter"),
        InvalidCase("rigid_footing/push_footing", dict(B=8.0), "half_width"),
        InvalidCase("rigid_footing/push_footing", dict(h_fine=0.5, h_coarse=0.25), "h_coarse"),
        InvalidCase("shear_lag_state", dict(tau_bar=150e3), "tau_bar", ("150000.0",)),
        # Section: inconsistent or impossible arrays (each field alone has the right type)
        InvalidCase(sec, dict(kind=np.array([0, 9])), "kind", ("9",)),
        InvalidCase(sec, dict(kind=np.array([0, -1])), "kind", ("-1",)),
        InvalidCase(sec, dict(kind=np.array([0.0, 0.5])), "kind"),
        InvalidCase(sec, dict(kind=np.zeros(n + 1, np.int64)), "kind"),
        InvalidCase(sec, dict(h=-base["h"]), "h"),
        InvalidCase(sec, dict(h=np.zeros(n)), "h"),
        InvalidCase(sec, dict(h=np.array([np.nan] * n)), "h"),
        InvalidCase(sec, dict(h=np.array([np.inf] * n)), "h"),
        InvalidCase(sec, dict(h=base["h"][:1]), "h"),
        InvalidCase(sec, dict(h=2.0 * base["h"]), "h"),
        InvalidCase(sec, dict(z_mid=np.array([np.nan] * n)), "z_mid"),
        InvalidCase(sec, dict(z_mid=base["z_mid"][:1]), "z_mid"),
        InvalidCase(sec, dict(z_mid=base["z_mid"] + 1.0), "z_mid"),
        InvalidCase(sec, dict(z_mid="abc"), "z_mid"),
        InvalidCase(sec, dict(params=np.full_like(base["params"], np.nan)), "params"),
        InvalidCase(sec, dict(params=base["params"][0]), "params"),
        InvalidCase(sec, dict(params=base["params"][:1]), "params"),
        InvalidCase(sec, dict(params=np.array([[-30e9, 0.2]] * n)), "params"),
        InvalidCase(sec, dict(params=np.array([[30e9, 0.7]] * n)), "params"),
        InvalidCase(sec, dict(params=np.array([[np.inf, 0.2]] * n)), "params"),
        InvalidCase(sec, dict(carries_shear=np.zeros(n, bool)), "carries_shear"),
        InvalidCase(sec, dict(carries_shear=np.ones(n + 1, bool)), "carries_shear"),
        InvalidCase(sec, dict(carries_shear="yes"), "carries_shear"),
        InvalidCase(sec, dict(z_bottom=math.nan), "z_bottom"),
        InvalidCase(sec, dict(z_bottom="abc"), "z_bottom"),
        InvalidCase(sec, dict(z_bottom=None), "z_bottom"),
        InvalidCase(sec, dict(z_bottom=0.5), "z_bottom"),
        InvalidCase(sec, dict(z_top=math.inf), "z_top"),
        InvalidCase(sec, dict(z_top=-1.0), "z_top"),
        InvalidCase(sec, dict(labels=5), "labels"),
    ]


def _section_arrays():
    s = _section()
    return {k: getattr(s, k) for k in ("z_mid", "h", "kind", "params", "carries_shear")}


def invalid_cases():
    """Strategy of :class:`InvalidCase`: one perturbed argument (drawn from the allowed-set tables) or one
    relational fault."""
    return st.one_of(_field_cases(), st.sampled_from(_relational_cases()))


# ---- running a case ----------------------------------------------------------------------------------------
class CaseTimeout(Exception):
    pass


@contextlib.contextmanager
def _time_limit(seconds):
    """Raise CaseTimeout after ``seconds`` (SIGALRM; a no-op where alarms are unavailable)."""
    if not hasattr(signal, "SIGALRM"):
        yield
        return

    def handler(signum, frame):
        raise CaseTimeout(f"no answer within {seconds} s")

    try:
        old = signal.signal(signal.SIGALRM, handler)
    except ValueError:  # not the main thread
        yield
        return
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, old)


def classify_invalid(case: InvalidCase, timeout: float = CASE_TIMEOUT) -> tuple[str, str]:
    """(outcome, detail) of one invalid case; outcome in named / unnamed / returned / other / timeout."""
    call = TARGETS[case.target][0]
    try:
        with np.errstate(all="ignore"), _time_limit(timeout):
            call(**case.overrides)
    except (ValueError, TypeError) as err:
        msg = str(err)
        named = case.param in msg and (not case.value_text or any(t in msg for t in case.value_text))
        return ("named" if named else "unnamed"), f"{type(err).__name__}: {msg}"
    except CaseTimeout as err:
        return "timeout", str(err)
    except Exception as err:  # noqa: BLE001 -- the study's point is to see what escapes
        return "other", f"{type(err).__name__}: {err}"
    return "returned", "a result was returned"


# ---- valid scenes ------------------------------------------------------------------------------------------
@st.composite
def valid_scenes(draw):
    """Strategy of small valid scenes: (Scene, n_steps, Settings)."""
    from ..elements.section import homogeneous
    from ..scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer
    from ..solver import Settings

    h_fine = draw(st.sampled_from([0.5, 1.0]))
    half_b = h_fine * draw(st.integers(1, 2))
    width = draw(st.sampled_from([8.0, 10.0]))
    depth = draw(st.sampled_from([3.0, 4.0, 5.0]))
    n_layers = draw(st.integers(1, 2))
    tops = [depth] if n_layers == 1 else [1.0, depth - 1.0]
    layers = []
    for t in tops:
        phi = draw(st.floats(0.0, 40.0))
        plastic = draw(st.booleans())
        c = draw(st.floats(5e3, 50e3)) if plastic else None
        layers.append(
            SoilLayer(
                t,
                E=draw(st.floats(1e4, 1e8)),
                nu=draw(st.floats(0.0, 0.45)),
                unit_weight=draw(st.sampled_from([0.0, 18e3])),
                c=c,
                phi_deg=phi,
                psi_deg=draw(st.floats(0.0, phi)) if plastic else None,
            )
        )
    section = homogeneous(draw(st.floats(0.3, 1.0)), draw(st.floats(20e9, 40e9)), 0.2)
    x_c = draw(st.sampled_from([0.0, -h_fine, h_fine]))
    foundation = Foundation(x_c - half_b, x_c + half_b, section)
    coulomb = draw(st.booleans())
    contact = Contact(kn=1e10, kt=1e9, phi_deg=draw(st.floats(15.0, 35.0)) if coulomb else None)
    load = ColumnLoad(
        x=x_c, N=draw(st.floats(0.0, 300e3)), H=draw(st.floats(-20e3, 20e3)), M=draw(st.floats(-20e3, 20e3))
    )
    scene = Scene(
        width=width,
        depth=depth,
        layers=layers,
        foundation=foundation,
        contact=contact,
        loads=[load],
        mesh=MeshSize(h_fine=h_fine, h_coarse=2.0, growth=1.5),
    )
    method = draw(st.sampled_from(["modified", "full"]))
    solver = Settings(
        method=method,
        line_search=method == "full",
        max_iter=60 if method == "modified" else 20,
        max_cuts=2,
        backend="superlu",
    )
    return scene, draw(st.integers(1, 3)), solver


def classify_valid(case, timeout: float = 4 * CASE_TIMEOUT) -> tuple[str, str]:
    """(outcome, detail) of one valid scene: solved / nonconvergence / not_finite / other / timeout."""
    from ..solver import NonConvergence

    scene, n_steps, solver = case
    try:
        with _time_limit(timeout):
            out = scene.build().solve(n_steps=n_steps, settings=solver)
    except NonConvergence as err:
        return "nonconvergence", str(err)[:200]
    except CaseTimeout as err:
        return "timeout", str(err)
    except Exception as err:  # noqa: BLE001
        return "other", f"{type(err).__name__}: {err}"
    x, w = out.settlement()
    if not (np.all(np.isfinite(w)) and np.all(np.isfinite(x))):
        return "not_finite", "settlements are not finite"
    return "solved", f"max settlement {w.max():.4g} m"


# ---- the study ---------------------------------------------------------------------------------------------
def _collect(strategy, classify, n_examples, seed_value):
    rows = []

    @seed(seed_value)
    @settings(
        max_examples=n_examples,
        database=None,
        deadline=None,
        phases=[Phase.generate],
        suppress_health_check=list(HealthCheck),
    )
    @given(strategy)
    def draw(case):
        rows.append((case, *classify(case)))

    draw()
    return rows


def study(n_invalid: int = 200, n_valid: int = 10, seed_value: int = 20261201) -> dict:
    """Draw ``n_invalid`` invalid cases and ``n_valid`` valid scenes (seeded) and tally the outcomes.

    Returns a dict: ``invalid`` (list of (case, outcome, detail)), ``valid`` (list of (case, outcome,
    detail)), ``named_fraction`` (named / invalid cases), ``escapes`` (invalid cases with any other outcome),
    ``counts_invalid``, ``counts_valid`` (outcome -> count), ``wall_time`` [s] (after one warm-up run of the
    base scene that compiles the kernels).
    """
    run_scene()  # compile the kernels first (numba's first call), so that no case's time limit counts it
    t0 = time.perf_counter()
    invalid = _collect(invalid_cases(), classify_invalid, n_invalid, seed_value)
    valid = _collect(valid_scenes(), classify_valid, n_valid, seed_value + 1) if n_valid else []
    counts_invalid: dict = {}
    for _, outcome, _ in invalid:
        counts_invalid[outcome] = counts_invalid.get(outcome, 0) + 1
    counts_valid: dict = {}
    for _, outcome, _ in valid:
        counts_valid[outcome] = counts_valid.get(outcome, 0) + 1
    named = counts_invalid.get("named", 0)
    return {
        "invalid": invalid,
        "valid": valid,
        "named_fraction": named / max(len(invalid), 1),
        "escapes": len(invalid) - named,
        "counts_invalid": counts_invalid,
        "counts_valid": counts_valid,
        "wall_time": time.perf_counter() - t0,
    }
