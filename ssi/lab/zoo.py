"""A zoo of ordinary scenes: what a new user writes first, solved with the default settings or given ones.

Each entry is a :class:`~ssi.scene.Scene` a foundation engineer would plausibly write -- a strip footing or
foundation beam on one or two layers under column loads -- spread over the ranges where solvers get into
trouble: Poisson's ratio from 0 to 0.49, cohesionless sand, slipping and opening contact (associated and not),
horizontal forces and moments, a 10^4 stiffness contrast between layers, fine meshes, RC sections, a
foundation that reaches the block's side, and loads above the bearing capacity. :func:`solve_zoo` solves
each and classifies the outcome: ``"completed"`` (lambda = 1), ``"limit load reached"`` (a detected collapse),
or ``"failed"`` (:class:`~ssi.solver.NonConvergence`, or any other exception, with its message).

``ordinary_scenes()`` is the fixed list of the tests (cheap meshes); ``random_scenes(n, seed)`` draws scenes
uniformly within the same ranges. Chapter 06 reads the 100 random scenes of seed 1 on the controlled path
from their stored outcomes (``tools/zoo_controlled.py --store``), re-solves the first 20 as a staleness check
and solves the ordinary scenes (rows ``zoo_solved``, ``zoo_solved_controlled``).
"""

import time
from dataclasses import dataclass, replace

import numpy as np

from ..elements.section import homogeneous, rc_section
from ..limit import flag_suspect
from ..materials.layer_laws import CONCRETE, STEEL
from ..materials.rc import concrete_params, designer_concrete, steel_params
from ..scene import (
    ColumnLoad,
    Contact,
    Excavation,
    Foundation,
    MeshSize,
    Phase,
    Scene,
    SoilLayer,
    StripWeight,
    SurfacePressure,
)
from ..solver import LIMIT_LOAD, NonConvergence, Settings


def rc_strip(depth: float = 0.5, fc: float = 30e6, fy: float = 500e6, area: float = 1.0e-3):
    """An RC strip section: bars of ``area`` [m^2/m] top and bottom at 5 cm cover (chapter 03 concrete)."""
    d = designer_concrete(fc)
    concrete = (CONCRETE, concrete_params(fc, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, fy / 200e9))
    return rc_section(
        depth, [(0.05, area), (depth - 0.05, area)], concrete, (STEEL, steel_params(fy, 200e9)), n_concrete=7
    )


def _base(**changes) -> Scene:
    """A 2 m footing on 1.5 m of clay over sand, 250 kN/m at its centre (about 40 % of its capacity)."""
    scene = Scene(
        width=12.0,
        depth=6.0,
        layers=[
            SoilLayer(1.5, E=15e6, nu=0.3, unit_weight=18e3, c=10e3, phi_deg=25.0, psi_deg=0.0),
            SoilLayer(4.5, E=60e6, nu=0.3, unit_weight=19e3, c=1e3, phi_deg=35.0, psi_deg=5.0),
        ],
        foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0),
        loads=[ColumnLoad(x=0.0, N=250e3)],
        mesh=MeshSize(h_fine=0.5, h_coarse=2.0),
    )
    return replace(scene, **changes)


def _layer(scene, i, **changes):
    layers = list(scene.layers)
    layers[i] = replace(layers[i], **changes)
    return layers


def ordinary_scenes() -> list[tuple[str, Scene]]:
    """The fixed zoo of the tests: (name, scene) pairs."""
    base = _base()
    out = []
    for nu in (0.0, 0.1, 0.3, 0.45, 0.49):
        out.append((f"nu={nu}", _base(layers=[replace(lay, nu=nu) for lay in base.layers])))
    sand = [
        SoilLayer(6.0, E=40e6, nu=0.3, unit_weight=18e3, c=0.0, phi_deg=phi, psi_deg=0.0)
        for phi in (30.0, 35.0)
    ]
    for lay in sand:
        out.append((f"sand c=0 phi={lay.phi_deg:g} surcharge", _base(layers=[lay], surcharge=10e3)))
    for phi_i in (10.0, 20.0, 35.0):
        for psi_i in (0.0, phi_i):
            out.append(
                (
                    f"contact phi_i={phi_i:g} psi_i={psi_i:g} c_i=0",
                    _base(
                        contact=Contact(kn=1e10, kt=1e9, phi_deg=phi_i, psi_deg=psi_i),
                        loads=[ColumnLoad(x=0.0, N=200e3, H=30e3)],
                    ),
                )
            )
    out.append(("horizontal force", _base(loads=[ColumnLoad(x=0.0, N=250e3, H=50e3)])))
    out.append(("moment", _base(loads=[ColumnLoad(x=0.0, N=250e3, M=60e3)])))
    out.append(
        (
            "force and moment, two columns",
            _base(
                foundation=Foundation(x0=-2.0, x1=2.0, section=homogeneous(0.5, 30e9, 0.2)),
                loads=[ColumnLoad(x=-1.5, N=200e3, H=20e3), ColumnLoad(x=1.5, N=150e3, M=-40e3)],
            ),
        )
    )
    soft, stiff = 2e6, 2e10
    out.append(
        (
            "contrast 1e4 soft over stiff",
            _base(
                layers=[
                    replace(base.layers[0], E=soft, c=20e3, phi_deg=0.0),
                    replace(base.layers[1], E=stiff),
                ],
                loads=[ColumnLoad(x=0.0, N=150e3)],
            ),
        )
    )
    out.append(
        (
            "contrast 1e4 stiff over soft",
            _base(layers=[replace(base.layers[0], E=stiff, c=None), replace(base.layers[1], E=soft)]),
        )
    )
    for h in (0.25, 0.125):
        out.append((f"h_fine={h}", _base(mesh=MeshSize(h_fine=h, h_coarse=2.0))))
    out.append(("RC section", _base(foundation=Foundation(x0=-1.0, x1=1.0, section=rc_strip()))))
    out.append(
        (
            "RC beam, two columns",
            _base(
                width=16.0,
                foundation=Foundation(x0=-3.0, x1=3.0, section=rc_strip(0.4)),
                loads=[ColumnLoad(x=-2.5, N=250e3), ColumnLoad(x=2.5, N=250e3)],
            ),
        )
    )
    out.append(
        (
            "foundation at the block's side",
            _base(
                foundation=Foundation(x0=4.0, x1=6.0, section=homogeneous(0.5, 30e9, 0.2)),
                loads=[ColumnLoad(x=5.0, N=150e3)],
            ),
        )
    )
    out.append(
        (
            "foundation across the block",
            _base(
                width=4.0,
                foundation=Foundation(x0=-2.0, x1=2.0, section=homogeneous(0.5, 30e9, 0.2)),
                loads=[ColumnLoad(x=0.0, N=200e3)],
            ),
        )
    )
    out.append(("bonded contact", _base(contact=Contact(kn=1e10, kt=1e9))))
    out.append(
        (
            "weightless soil",
            _base(
                layers=[replace(lay, unit_weight=0.0) for lay in base.layers],
                loads=[ColumnLoad(x=0.0, N=150e3)],
            ),
        )
    )
    out.append(("associated soil", _base(layers=[replace(lay, psi_deg=lay.phi_deg) for lay in base.layers])))
    out.extend(phased_scenes())
    out.append(("above capacity, clay", _base(loads=[ColumnLoad(x=0.0, N=2.0e6)])))
    out.append(("above capacity, sand", _base(layers=[sand[0]], loads=[ColumnLoad(x=0.0, N=3.0e6)])))
    return out


def phased_scenes() -> list[tuple[str, Scene]]:
    """Phased scenes of the zoo (chapter 12's capabilities): an embedded strip below a water table loaded in
    phases and half unloaded, and a pit excavated beside a loaded strip."""
    base = _base()
    sand = SoilLayer(
        4.5, E=50e6, nu=0.3, unit_weight=19e3, unit_weight_sat=20e3, c=2e3, phi_deg=32.0, psi_deg=0.0
    )
    embedded = _base(
        layers=[SoilLayer(1.5, E=10e6, nu=0.3, unit_weight=18e3), sand],
        embedment=1.5,
        water_table=2.0,
        loads=[],
        phases=[
            Phase("weight", loads=(StripWeight(unit_weight=25e3),)),
            Phase(
                "building",
                loads=(ColumnLoad(x=0.0, N=250e3, H=20e3), SurfacePressure(x0=3.0, x1=5.0, q=20e3)),
            ),
            Phase("half unload", factors={"building": 0.5}),
        ],
    )
    pit = _base(
        water_table=1.0,
        loads=[],
        phases=[
            Phase("building", loads=(ColumnLoad(x=0.0, N=250e3),)),
            Phase("pit", excavate=(Excavation(x0=3.0, x1=5.0, bottom=1.0),)),
        ],
        layers=list(base.layers),
    )
    return [("phased, embedded, water table", embedded), ("excavation beside a strip", pit)]


def light_footing_on_deep_block() -> Scene:
    """A 10 kN/m strip (H = 1 kN/m) on 60 m of soft, heavy sand: the geostatic forces dwarf the structural
    load -- the scene on which the old convergence measure (``convergence_reference="total"``) accepts an
    unconverged state (chapter 06, tests/test_solver.py)."""
    return Scene(
        width=120.0,
        depth=60.0,
        layers=[SoilLayer(60.0, E=2e6, nu=0.3, unit_weight=20e3, c=0.0, phi_deg=30.0, psi_deg=0.0)],
        foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0),
        loads=[ColumnLoad(x=0.0, N=10e3, H=1e3)],
        mesh=MeshSize(h_fine=0.5, h_coarse=7.5),
    )


def random_scenes(n: int, seed: int = 0) -> list[tuple[str, Scene]]:
    """``n`` scenes drawn uniformly within the zoo's ranges (seeded)."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        nu = rng.uniform(0.0, 0.49)
        c1 = rng.choice([0.0, rng.uniform(1e3, 30e3)])
        phi1 = rng.uniform(20.0, 38.0) if c1 == 0.0 else rng.uniform(0.0, 35.0)
        E1 = 10 ** rng.uniform(6.5, 8.0)
        E2 = E1 * 10 ** rng.uniform(-2.0, 2.0)
        phi_i = rng.uniform(10.0, 35.0)
        half = rng.uniform(0.5, 2.0)
        layers = [
            SoilLayer(1.5, E=E1, nu=nu, unit_weight=18e3, c=c1, phi_deg=phi1, psi_deg=0.0),
            SoilLayer(4.5, E=E2, nu=nu, unit_weight=19e3, c=1e3, phi_deg=35.0, psi_deg=5.0),
        ]
        load = rng.uniform(50e3, 600e3) * half
        scene = _base(
            layers=layers,
            foundation=Foundation(x0=-half, x1=half, section=homogeneous(0.5, 30e9, 0.2)),
            contact=Contact(kn=1e10, kt=1e9, phi_deg=phi_i, psi_deg=float(rng.choice([0.0, phi_i]))),
            loads=[
                ColumnLoad(
                    x=0.0, N=load, H=rng.uniform(-0.15, 0.15) * load, M=rng.uniform(-0.1, 0.1) * load * half
                )
            ],
            mesh=MeshSize(h_fine=float(rng.choice([0.5, 0.25])), h_coarse=2.0),
        )
        out.append((f"random {i}", scene))
    return out


@dataclass
class ZooOutcome:
    name: str
    status: str  # "completed", "limit load reached" or "failed"
    load_factor: float  # last converged lambda
    wall_time: float  # [s]
    message: str = ""
    limit_load: float | None = None  # the reported limit load factor (a controlled path's peak, which its
    # last converged lambda, past the peak, is below); None unless status is "limit load reached"
    limit_uncertainty: float | None = None  # controlled path: the peak's relative numerical uncertainty
    limit_suspect: str = (
        ""  # the result's reasons not to read the limit as a capacity, the bracket's included
    )
    limit_mechanism: float | None = None  # the limit's mechanism certificate lambda_k / lambda_peak
    # (ssi.solver.mechanism; None where it certifies nothing: non-associated flow)
    settlement: float | None = None  # [m] the largest settlement under the foundation at the last converged
    # step (SceneResult.max_settlement; at lambda = 1 when completed); None when the run failed

    @property
    def solved(self) -> bool:
        return self.status != "failed"

    @property
    def carried(self) -> float:
        """The load factor the outcome claims: the limit when one was reported, else the last converged
        lambda (1 when completed)."""
        return self.load_factor if self.limit_load is None else self.limit_load


def solve_zoo(scenes, settings: Settings | None = None, check=None) -> list[ZooOutcome]:
    """Solve each (name, scene) with ``settings`` (default: ``Settings()``) and classify the outcome.

    ``check(name, limit)``: the :class:`ssi.limit.LimitCheck` of a scene's limit load factor against its
    limit-analysis bracket, or None when there is nothing to check (:func:`ssi.lab.zoo_limits.
    bracket_check`); a failed check is recorded on the result by :func:`ssi.limit.flag_suspect`, so
    ``limit_suspect`` carries a false collapse or a mesh overestimate with its size, as a user's would."""
    outcomes = []
    for name, scene in scenes:
        t0 = time.perf_counter()
        limit, uncertainty, suspect, mechanism, settlement = None, None, "", None, None
        try:
            out = scene.build().solve(settings=settings)
            status, lam, message = out.status, out.load_factor[-1], out.solver_result.message
            res = out.solver_result
            settlement = out.max_settlement()[1]
            if status == LIMIT_LOAD:
                limit = float(lam if res.limit_load_factor is None else res.limit_load_factor)
                uncertainty = res.limit_uncertainty
                verdict = None if check is None else check(name, limit)
                if verdict is not None:
                    flag_suspect(res, verdict)
                suspect, mechanism = res.limit_suspect, res.limit_mechanism
        except NonConvergence as err:
            status, lam, message = "failed", err.result.load_factor[-1], str(err)
        outcomes.append(
            ZooOutcome(
                name,
                status,
                float(lam),
                time.perf_counter() - t0,
                message,
                limit,
                uncertainty,
                suspect,
                mechanism,
                settlement,
            )
        )
    return outcomes
