"""The controlled path's predictor for a step to a prescribed load factor without a previous step to scale
(``path._Follower._prescribed_predictor``, issue 31, stall9): the committed state's linear response to the
change of load and of the prescribed displacements, not the prescribed DOFs moved alone.

Measured on the bench footing (psi = 0, h = 0.125 m, 8 cm in 12 targets, 6.2 s per run: not repeated here):
the first step moved the rigid footing 6.7 mm beside unmoved soil, 968 soil points on the Mohr-Coulomb apex,
four failed attempts; with the predictor 24 failed steps instead of 29 over the push and 361 factorisations
instead of 450."""

import numpy as np

from ssi.lab.bearing_capacity import chapter10_footing, footing_path_settings
from ssi.solver import run


def test_an_elastic_prescribed_step_converges_at_its_first_iteration():
    # 0.6 mm of chapter 10's rigid footing: the soil stays elastic (plasticity starts near 1 mm), so the
    # linear response is the solution and the first iterate is already balanced; with the footing nodes
    # moved alone (main 9119491) this first step took 2 iterations, and on the bench footing at h = 0.25 m
    # (0.67 mm) 13
    scene = chapter10_footing(psi_deg=0.0, h_fine=0.25, settle=6e-4)
    res = run(scene.model, np.array([1.0]), footing_path_settings())
    assert res.status == "completed"
    assert np.all(np.asarray(res.iterations[1:]) == 1), res.iterations
    assert res.cuts == 0
