"""The stored brackets of the zoo's scenes (reference_data/zoo_brackets_*.csv, written by
tools/zoo_brackets.py) and the helpers of chapter 06's checks against them (ssi.lab.zoo_limits).

The tables must not go stale silently: one stored scene (of both tables, the one with the fewest triangles,
so the test stays within a few seconds) is recomputed with the stored requested gap and compared with its
row.
"""

import numpy as np
import pytest

from ssi.core.mesh import soil_block
from ssi.lab.zoo import _base
from ssi.lab.zoo_limits import (
    bracket_scenes,
    bracket_verdict,
    permute_nodes,
    read_zoo_brackets,
    renumbered_nodes,
    zoo_bracket,
)
from ssi.scene import ColumnLoad


def test_a_stored_bracket_is_recomputed_to_the_solver_tolerance():
    metas, rows = read_zoo_brackets()
    if not rows:
        pytest.skip("no zoo bracket table written yet (tools/zoo_brackets.py random|ordinary)")
    certified = [n for n in rows if np.isfinite(rows[n]["lb"]) and np.isfinite(rows[n]["lb_davis"])]
    assert certified, "the tables hold no certified bracket"
    # one scene of both tables (they come from the same code): the one with the fewest triangles
    name = min(certified, key=lambda n: (rows[n]["triangles"], n))
    meta = metas["random" if name.startswith("random ") else "ordinary"]
    scene = dict(bracket_scenes())[name]
    row = zoo_bracket(scene, float(meta["gap_requested"]), max_elements=int(meta["max_elements"]))
    stored = rows[name]
    # the same adaptive sequence: the same final mesh
    assert row["triangles"] == stored["triangles"], (name, row, stored)
    # each bound to 1e-6 relative: the conic solves stop at Clarabel's tolerances (1e-9) and the certified
    # bounds are recomputed from their fields, so another BLAS may move the last digits; a change of the
    # code or of the scenes moves them by far more
    for k in ("lb", "ub", "lb_davis", "ub_davis"):
        assert row[k] == pytest.approx(stored[k], rel=1e-6), (name, k, row[k], stored[k])
    # each bracket is one, and the Davis material (weaker: c* <= c, phi* <= phi) collapses below the
    # associated ceiling: LB_Davis <= Davis collapse load <= associated collapse load <= UB
    assert stored["lb"] <= stored["ub"] and stored["lb_davis"] <= stored["ub_davis"]
    assert stored["lb_davis"] <= stored["ub"]


def test_the_verdicts_of_limits_and_of_carried_loads():
    b = {"lb_davis": 2.0, "ub": 2.5}
    assert bracket_verdict("limit load reached", 1.5, b)[0] == "false collapse"  # below 0.97 * 2.0 = 1.94
    assert bracket_verdict("limit load reached", 1.95, b) == ("inside", 0.0)
    verdict, size = bracket_verdict("limit load reached", 2.7, b)  # above 1.03 * 2.5 = 2.575
    assert verdict == "mesh overestimate" and size == pytest.approx(2.7 / 2.575 - 1.0)
    # a completed run carried lambda = 1: well below the floor, and no collapse claimed
    assert bracket_verdict("completed", 1.0, b) == ("carried", 0.0)
    assert bracket_verdict("failed", 0.4, b) == ("stopped", 0.0)
    # carrying more than the associated ceiling allows is the incremental mesh's overestimate
    assert bracket_verdict("completed", 1.0, {"lb_davis": 0.5, "ub": 0.8})[0] == "mesh overestimate"
    assert bracket_verdict("completed", 1.0, None) == ("no bracket", 0.0)


def test_renumbered_nodes_change_the_order_of_the_unknowns_only():
    mesh = soil_block(6.0, 3.0, None, (-0.5, 0.5), 0.5, 1.0)
    perm = permute_nodes(mesh, seed=1)
    assert not np.array_equal(perm.xy, mesh.xy)
    np.testing.assert_array_equal(perm.xy[perm.conn], mesh.xy[mesh.conn])  # each element's nodes, in order
    np.testing.assert_array_equal(perm.xy[perm.surface], mesh.xy[mesh.surface])
    # an elastic scene: the same settlement whatever the numbering (to round-off: the factorisation's
    # operations come in another order)
    scene = _base(loads=[ColumnLoad(x=0.0, N=50e3)])
    plain = scene.build()
    with renumbered_nodes(seed=1):
        renumbered = scene.build()
    assert not np.array_equal(plain.model.coords, renumbered.model.coords)
    s0 = plain.solve().max_settlement()[1]
    s1 = renumbered.solve().max_settlement()[1]
    assert s1 == pytest.approx(s0, rel=1e-9)
