"""Parameter sweeps (ssi.studies.sweep): one row and one file per scene, failures recorded, re-runs resumed,
and the dask cluster giving the same answers as the serial run."""

import json
import sys

import pytest

from ssi.elements.section import homogeneous
from ssi.io.results import read_result
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Scene, SoilLayer
from ssi.studies.sweep import grid, read_table, scene_key, sweep

CALLS = []


def strip_on_soil(E, N):
    """A linear 2 m strip on one elastic layer; E < 0 makes the build fail (a failing scene)."""
    CALLS.append((E, N))
    return Scene(
        width=12.0,
        depth=6.0,
        layers=[SoilLayer(6.0, E=E, nu=0.3)],
        foundation=Foundation(x0=-1.0, x1=1.0, section=homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9),
        loads=[ColumnLoad(x=0.0, N=N)],
        mesh=MeshSize(h_fine=1.0, h_coarse=4.0, growth=1.5),
    )


def test_grid_is_the_product_of_the_axes():
    assert grid(E=[1, 2], N=[3]) == [{"E": 1, "N": 3}, {"E": 2, "N": 3}]
    with pytest.raises(TypeError, match="E"):
        grid(E=5.0)


def test_serial_sweep_records_failures_and_resumes(tmp_path):
    params = [{"E": 20e6, "N": 100e3}, {"E": 20e6, "N": 200e3}, {"E": -1.0, "N": 100e3}]
    CALLS.clear()
    rows = sweep(strip_on_soil, params, client="serial", out_dir=tmp_path)
    assert [r["status"] for r in rows] == ["completed", "completed", "failed"]
    assert rows[2]["error"].startswith("ValueError") and "E" in rows[2]["error"]
    # a linear scene: twice the load, twice the settlement (an independent check of the rows)
    assert rows[1]["max_settlement"] == pytest.approx(2.0 * rows[0]["max_settlement"], rel=1e-9)
    table = read_table(tmp_path / "sweep.csv")
    assert [t["status"] for t in table] == ["completed", "completed", "failed"]
    assert table[0]["p.E"] == 20e6
    stored = read_result(tmp_path / "scenes" / f"{scene_key(params[0])}.h5")
    assert stored.max_settlement()[1] == pytest.approx(rows[0]["max_settlement"], rel=1e-12)
    CALLS.clear()
    again = sweep(strip_on_soil, params, client="serial", out_dir=tmp_path)
    assert CALLS == [(-1.0, 100e3)]  # only the failed scene is tried again
    assert again[0]["max_settlement"] == rows[0]["max_settlement"]
    row = json.loads((tmp_path / "scenes" / f"{scene_key(params[1])}.json").read_text())
    assert row["status"] == "completed"


def test_sweep_rejects_bad_input(tmp_path):
    with pytest.raises(ValueError, match="parameters"):
        sweep(strip_on_soil, [], client="serial", out_dir=tmp_path)
    with pytest.raises(ValueError, match="equal"):
        sweep(strip_on_soil, [{"E": 1e7, "N": 1.0}] * 2, client="serial", out_dir=tmp_path)
    with pytest.raises(ValueError, match="n_workers"):
        sweep(strip_on_soil, [{"E": 1e7, "N": 1.0}], out_dir=tmp_path, n_workers=0)


def test_dask_sweep_matches_the_serial_one(tmp_path):
    pytest.importorskip("distributed", reason="dask.distributed (the test and sweep extras) is not installed")
    import cloudpickle

    cloudpickle.register_pickle_by_value(sys.modules[__name__])  # workers do not import the tests
    params = grid(E=[20e6, 30e6], N=[100e3, 200e3])
    serial = sweep(strip_on_soil, params, client="serial", out_dir=tmp_path / "serial", keep_files=False)
    dist = sweep(strip_on_soil, params, out_dir=tmp_path / "dask", n_workers=2, keep_files=False)
    assert [r["status"] for r in dist] == ["completed"] * 4
    for a, b in zip(serial, dist):
        assert b["max_settlement"] == pytest.approx(a["max_settlement"], rel=1e-12)
    assert len({r["worker"] for r in dist} | {r["worker"] for r in serial}) >= 2  # ran in other processes
