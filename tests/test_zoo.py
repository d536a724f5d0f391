"""The zoo of ordinary scenes (``ssi.lab.zoo``), each solved with the default ``Settings()``: every one must
reach its full load or end as a detected collapse -- never stop with NonConvergence.

The checks on each outcome can fail for a wrong answer, not only for a stopped run: a completed scene's
contact must carry the column loads (vertical equilibrium of the strip, to the convergence tolerance), and
the scenes loaded above their capacity must end as "limit load reached" below their load.
"""

import numpy as np
import pytest

from ssi.lab.zoo import ordinary_scenes
from ssi.solver import LIMIT_LOAD, Settings

SCENES = dict(ordinary_scenes())


@pytest.mark.parametrize("name", list(SCENES))
def test_zoo_scene_reaches_its_load_or_a_detected_collapse(name):
    scene = SCENES[name]
    built = scene.build()
    out = built.solve(settings=Settings())
    if name.startswith("above capacity"):
        assert out.status == LIMIT_LOAD and out.limit_load_factor < 1.0
        return
    if scene.phases:  # every phase to its end (their physics is verified in chapter 12)
        assert [p["result"].status for p in out.phases] == ["completed"] * (len(scene.phases) + 1)
        assert out.load_factor[-1] == len(scene.phases)
        return
    assert out.status == "completed" and out.load_factor[-1] == 1.0
    contact = out.contact()
    weights = built.interface.ip_weights()
    carried = -np.sum(contact["sig_n"] * weights)  # [N/m], compression positive
    width = scene.foundation.x1 - scene.foundation.x0
    # the strip also carries its own weight and the surcharge it displaces (the geostatic stress at its base)
    applied = sum(load.N for load in scene.loads) + (scene.foundation.self_weight + scene.surcharge) * width
    # tolerance: the convergence tolerance (force_tol 1e-5 of the structural load) with ample room
    assert carried == pytest.approx(applied, rel=1e-3), (carried, applied)


def test_a_viscous_path_past_the_limit_load_ends_as_a_bracketed_limit():
    """With viscosity, load control passes the rate-independent capacity (the overstress carries the excess),
    so the held load cannot relax. The solver then finds the largest load factor that does relax and ends as
    "limit load reached" there, with the smallest factor where the held load kept flowing as the upper end.
    The reference is independent of that machinery: the same scene (associated soil, where the
    rate-independent path converges) solved without viscosity stops rising at its limit. The bracket must
    contain it; its width is at most 2**-4 of the last viscous step (BRACKET_REFINEMENTS) -- here <= 4 %."""
    from dataclasses import replace

    from ssi.lab.zoo import _base
    from ssi.scene import ColumnLoad

    base = _base()
    scene = _base(
        layers=[replace(lay, psi_deg=lay.phi_deg) for lay in base.layers], loads=[ColumnLoad(x=0.0, N=2.0e6)]
    )
    inviscid = scene.build().solve(settings=Settings()).solver_result
    viscous = scene.build().solve(settings=Settings(viscosity=1.0)).solver_result
    assert inviscid.status == LIMIT_LOAD and inviscid.limit_load_upper is None
    assert viscous.status == LIMIT_LOAD and viscous.limit_load_upper is not None
    lo, hi = viscous.limit_load_factor, viscous.limit_load_upper
    # the inviscid limit is where its steps got stuck: within min_step (1e-4) below the true one
    assert lo <= inviscid.limit_load_factor + 1e-4 and inviscid.limit_load_factor <= hi, (lo, hi, inviscid)
    assert hi - lo <= 0.04 * hi
    assert viscous.load_factor[-1] == lo and "kept flowing" in viscous.message
