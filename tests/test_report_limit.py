"""`ssi limit`'s HTML report (ssi.io.report_limit) and its mechanism plot (ssi.io.plot.mechanism_fields,
limit_mechanism), issue 46 item 6.

The physical checks are independent of the code: plastic dissipation is non-negative in every triangle of
a kinematically admissible field (the flow rule makes the stress power of a plastic strain rate >= 0); and
Prandtl's mechanism of a rough strip on Tresca clay (B = 2 m) fans about the footing's edge, where the
strain rate is singular, and reaches the ground B beyond the edge (its passive wedge's face, B/sqrt(2)
times sqrt(2)): x = B/2 + B = 3 m from the axis, well inside the 6 m half block.
"""

import json
import re
import shutil
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from ssi.io.cli import main  # noqa: E402
from ssi.io.plot import limit_mechanism, mechanism_fields  # noqa: E402
from ssi.io.report_limit import limit_report_html  # noqa: E402
from ssi.scene import RigidFooting, Scene, Settlement, SoilLayer  # noqa: E402

B = 2.0
ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def prandtl():
    scene = Scene(
        width=12.0, depth=5.0, symmetric=True,
        layers=[SoilLayer(5.0, E=20e6, nu=0.3, c=10e3, phi_deg=0.0, psi_deg=0.0)],
        foundation=RigidFooting(-0.5 * B, 0.5 * B), loads=[Settlement(0.05)],
    )  # fmt: skip
    return scene.limit_analysis(gap=0.1)


def test_mechanism_dissipates_at_the_footing_edge_and_is_cropped_to_it(prandtl):
    f = mechanism_fields(prandtl)
    assert np.all(f["dissipation"] >= 0.0) and f["dissipation"].max() > 0.0
    # the densest dissipation at the footing's edge (x = B/2, z = 0): the fan's centre
    x, z = f["centroid"][np.argmax(f["density"])]
    assert np.hypot(x - 0.5 * B, z) < 0.25 * B, (x, z)
    # the window holds the mechanism to Prandtl's exit point and is cropped below the 6 m x 5 m block
    x0, x1, z0, z1 = f["window"]
    assert x0 == 0.0 and 1.5 * B <= x1 < 6.0 and -5.0 < z0 <= -0.5 * B and z1 >= 0.0
    # the foundation drawn where it is: the base line of the modelled half, x in [0, B/2] at z = 0
    (seg,) = f["footings"]
    assert sorted(seg[:, 0].tolist()) == [0.0, 0.5 * B] and np.all(seg[:, 1] == 0.0)
    fig = limit_mechanism(prandtl)
    for ax in fig.axes[:1]:
        assert ax.get_xlim() == (x0, x1) and ax.get_aspect() == 1.0
    matplotlib.pyplot.close(fig)


def test_report_shows_the_forces_on_the_foundation():
    """A 2 m strip bonded to Tresca clay (s_u = 20 kPa) under a 100 kN/m column: the forces row's brackets
    in kN/m contain Prandtl's (2 + pi) s_u B = 205.7 kN/m (the hand value), the reference is the column."""
    from ssi.elements.section import homogeneous
    from ssi.scene import ColumnLoad, Contact, Foundation

    scene = Scene(
        width=12.0, depth=5.0, layers=[SoilLayer(5.0, E=30e6, nu=0.3, c=20e3, phi_deg=0.0, psi_deg=0.0)],
        foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)), contact=Contact(kn=1e10, kt=1e9),
        loads=[ColumnLoad(0.0, N=100e3)],
    )  # fmt: skip
    cap = scene.limit_analysis(gap=0.1)
    text = limit_report_html(cap, "t")
    assert "<img" not in text  # no figure asked
    (row,) = cap.to_dict()["foundation_forces_N_per_m"]
    lo, hi = row["associated"]
    assert lo <= (2.0 + np.pi) * 20e3 * 2.0 <= hi and row["reference"] == 100e3
    assert "Forces on the foundations at collapse" in text
    assert f"[{lo / 1e3:.4g}, {hi / 1e3:.4g}]" in text and ">100<" in text


def test_ssi_limit_writes_its_report_with_the_bracket_and_the_mechanism(tmp_path, capsys):
    scene = tmp_path / "push.toml"
    shutil.copy(ROOT / "examples" / "pushover_footing.toml", scene)
    assert main(["limit", str(scene), "--gap", "0.1", "--max-elements", "1500"]) == 0
    out = capsys.readouterr().out
    report = tmp_path / "push_limit_report.html"
    assert f"wrote {report}" in out
    text = report.read_text()
    d = json.loads((tmp_path / "push_limit.json").read_text())
    for key in ("lb", "ub", "lb_davis", "ub_davis"):  # the bracket as in the JSON, in kN/m
        assert f">{d[key] / 1e3:.4g}<" in text, key
    assert re.search(r'<img src="data:image/png;base64,[A-Za-z0-9+/]{1000,}', text)  # embedded, one file
    assert "gap target met (10 %)" in text or "gap target of 10 % NOT met" in text
    rows = d["history_associated"]
    assert f"<h3>associated ({len(rows)} mesh" in text
    # ssi show of the result file redraws the same page from the stored numbers (no geometry: no footing)
    assert main(["show", str(tmp_path / "push_limit.h5")]) == 0
    shown = (tmp_path / "push_limit_plots" / "report.html").read_text()
    for key in ("lb", "ub"):
        assert f">{d[key] / 1e3:.4g}<" in shown, key
    assert "data:image/png;base64," in shown
    capsys.readouterr()
    # a second run keeps the user's report: refused before anything is solved, the file unchanged
    before = report.stat().st_mtime_ns
    (tmp_path / "push_limit.json").unlink()
    (tmp_path / "push_limit.h5").unlink()
    (tmp_path / "push_limit.vtu").unlink()
    (tmp_path / "push_limit.png").unlink()
    assert main(["limit", str(scene), "--gap", "0.1"]) == 2
    assert "push_limit_report.html exists; pass --overwrite" in capsys.readouterr().err
    assert report.stat().st_mtime_ns == before


def test_limit_help_shows_every_options_default(capsys):
    with pytest.raises(SystemExit):
        main(["limit", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for option in ("--phase", "--gap", "--h", "--h-min", "--max-elements", "--strip", "--side-soil", "--out",
                   "--plot", "--report"):  # fmt: skip
        help_text = text.split(f"{option} ", 2)[-1].split(" --")[0]
        assert "default" in help_text, option
