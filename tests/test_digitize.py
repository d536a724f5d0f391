"""The digitiser-export converter: calibration, multi-curve parsing, the reference format, the empty slot.

Reference: synthetic exports made here from known data values through a known pixel map, so the converter
must return those values to round-off (the calibration is an exact affine / log-affine map).
"""

import numpy as np
import pytest

from ssi.lab import paths
from ssi.lab.digitize import (
    REQUIRED_META,
    AxisCalibration,
    convert,
    main,
    read_digitizer_csv,
    read_reference,
    write_reference,
)

META = {
    "source": "synthetic",
    "figure": "none",
    "units": "kPa, mm",
    "trust": "C (test)",
    "uncertainty": "0",
    "how_obtained": "made in tests/test_digitize.py",
}


def test_linear_and_log_calibration_are_exact():
    cal = AxisCalibration(100.0, 0.0, 500.0, 40.0)  # 10 px per unit, origin at px 100
    np.testing.assert_allclose(cal([100.0, 300.0, 550.0]), [0.0, 20.0, 45.0], rtol=0, atol=1e-12)
    inverted = AxisCalibration(400.0, 0.0, 50.0, 7.0)  # image y grows downwards
    np.testing.assert_allclose(inverted([400.0, 225.0, 50.0]), [0.0, 3.5, 7.0], atol=1e-12)
    logc = AxisCalibration(0.0, 1.0, 300.0, 1000.0, log=True)
    np.testing.assert_allclose(logc([0.0, 100.0, 200.0, 300.0]), [1.0, 10.0, 100.0, 1000.0], rtol=1e-13)
    assert AxisCalibration.parse("0,1,300,1000,log") == logc


@pytest.mark.parametrize(
    "args, word",
    [((1, 0, 1, 5), "px1 and px2"), ((1, 2, 3, 2), "val1 and val2"), ((0, 0, 1, 10, True), "logarithmic")],
)
def test_bad_calibration(args, word):
    with pytest.raises(ValueError, match=word):
        AxisCalibration(*args)


def test_multi_curve_export_with_pixels(tmp_path):
    """A WebPlotDigitizer-style 'all datasets' export in pixels -> reference rows in data units."""
    tau = {"point6": np.array([0.0, 10.0, 20.0, 30.0]), "edge": np.array([0.0, 15.0, 30.0])}
    disp = {"point6": np.array([0.0, 0.5, 1.5, 3.0]), "edge": np.array([0.0, 1.0, 4.0])}
    xcal = AxisCalibration(80.0, 0.0, 680.0, 6.0)  # figure's x axis = displacement [mm]
    ycal = AxisCalibration(420.0, 0.0, 20.0, 40.0)  # figure's y axis = tau_bar [kPa]
    px = {k: (80.0 + disp[k] * 100.0, 420.0 - tau[k] * 10.0) for k in tau}
    lines = ["point6,,edge,", "X,Y,X,Y"]
    for i in range(4):
        cells = []
        for k in ("point6", "edge"):
            cells += [f"{px[k][0][i]:.10g}", f"{px[k][1][i]:.10g}"] if i < len(tau[k]) else ["", ""]
        lines.append(",".join(cells))
    src = tmp_path / "export.csv"
    src.write_text("\n".join(lines) + "\n")
    curves = read_digitizer_csv(src)
    assert list(curves) == ["point6", "edge"] and curves["edge"].shape == (3, 2)
    dst = tmp_path / "ref.csv"
    convert(src, dst, META, ("curve", "tau_bar_kPa", "displacement_mm"), xcal, ycal, swap=True)
    meta, cols = read_reference(dst)
    assert meta == META
    for k, tau_k in tau.items():
        sel = cols["curve"] == k
        np.testing.assert_allclose(cols["tau_bar_kPa"][sel], tau_k, atol=1e-5)  # written with 6 digits
        np.testing.assert_allclose(cols["displacement_mm"][sel], disp[k], atol=1e-6)


def test_single_curve_in_data_units_and_rename(tmp_path):
    dst = tmp_path / "r.csv"
    convert("x,y\n3,30\n1,10\n2,20\n", dst, META, ("curve", "a", "b"), rename={"curve": "c1"})
    _, cols = read_reference(dst)
    assert list(cols["curve"]) == ["c1"] * 3
    np.testing.assert_array_equal(cols["a"], [1.0, 2.0, 3.0])  # sorted by the first value
    np.testing.assert_array_equal(cols["b"], [10.0, 20.0, 30.0])


def test_reference_format_requires_provenance(tmp_path):
    for k in REQUIRED_META:
        bad = {**META, k: ""}
        with pytest.raises(ValueError, match=k):
            write_reference(tmp_path / "x.csv", bad, {"a": [1.0]})
    with pytest.raises(ValueError, match="trust"):
        write_reference(tmp_path / "x.csv", {**META, "trust": "Z"}, {"a": [1.0]})
    with pytest.raises(ValueError, match="same length"):
        write_reference(tmp_path / "x.csv", META, {"a": [1.0], "b": []})
    with pytest.raises(ValueError, match="one coordinate"):
        read_digitizer_csv("a,,b,\nX,Y,X,Y\n1,2,3,\n")


def test_empty_fig13a_slot_is_documented_and_empty():
    meta, cols = read_reference(paths.REFERENCE_DATA / "zongze1995_fig13a.csv")
    assert set(REQUIRED_META) <= set(meta)
    assert list(cols) == ["curve", "tau_bar_kPa", "displacement_mm"]
    assert all(len(v) == 0 for v in cols.values())


def test_command_line_fills_a_copy_of_the_slot(tmp_path, capsys):
    slot = paths.REFERENCE_DATA / "zongze1995_fig13a.csv"
    src = tmp_path / "e.csv"
    src.write_text("edge,\nX,Y\n0,0\n2,25\n")
    out = tmp_path / "filled.csv"
    assert (
        main(
            [
                str(src),
                str(out),
                "--columns",
                "curve,tau_bar_kPa,displacement_mm",
                "--swap",
                "--meta-from",
                str(slot),
            ]
        )
        == 0
    )
    meta, cols = read_reference(out)
    assert meta["trust"].startswith("C") and meta["source"] == read_reference(slot)[0]["source"]
    np.testing.assert_array_equal(cols["tau_bar_kPa"], [0.0, 25.0])
    np.testing.assert_array_equal(cols["displacement_mm"], [0.0, 2.0])
    assert "2 points of 1 curves" in capsys.readouterr().out
