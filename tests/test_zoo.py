"""The zoo of ordinary scenes (``ssi.zoo``), each solved with the default ``Settings()``: every one must
reach its full load or end as a detected collapse -- never stop with NonConvergence.

The checks on each outcome can fail for a wrong answer, not only for a stopped run: a completed scene's
contact must carry the column loads (vertical equilibrium of the strip, to the convergence tolerance), and
the scenes loaded above their capacity must end as "limit load reached" below their load.
"""

import numpy as np
import pytest

from ssi.solver import LIMIT_LOAD, Settings
from ssi.zoo import ordinary_scenes

SCENES = dict(ordinary_scenes())


@pytest.mark.parametrize("name", list(SCENES))
def test_zoo_scene_reaches_its_load_or_a_detected_collapse(name):
    scene = SCENES[name]
    built = scene.build()
    out = built.solve(settings=Settings())
    if name.startswith("above capacity"):
        assert out.status == LIMIT_LOAD and out.limit_load_factor < 1.0
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
