"""Each foundation's force at the capacity bracket's factors (issue 46, item 6), and the capacity bridge's
refusal of a load it does not represent (issue 44: each load answers ``limit_action``; the bridge never asks
its class).

On a site with several strips lambda scales every strip's loads at once: each foundation's force at the
bracket's factors is lambda times its own loads, and the foundations' forces sum to the total. The site is
issue 46's two-strip shape (``benchmarks/data/two_strip_site.toml``: columns N = 400 kN/m at x = -7 m on
the strip [-8, -6] m and N = 300 kN/m at x = -1 m on the strip [-2, 0] m, no self weight), bracketed on one
coarse mesh: the identities hold on any mesh.
"""

import pathlib

import pytest

from ssi.capacity import LimitInput, limit_problem
from ssi.elements.section import homogeneous
from ssi.scene import ColumnLoad, Contact, Foundation, Phase, Push, Scene, SoilLayer
from ssi.scene.scene_file import read_scene_file

SITE = pathlib.Path(__file__).resolve().parent.parent / "benchmarks" / "data" / "two_strip_site.toml"
COLUMNS = (400e3, 300e3)  # [N/m] each strip's column, from the file
SPANS = ((-8.0, -6.0), (-2.0, 0.0))  # [m] each strip's ends, from the file


@pytest.fixture(scope="module")
def site():
    site, _, _ = read_scene_file(SITE)
    return site


def test_each_strip_carries_its_own_column_in_the_limit_problem(site):
    assert isinstance(site, LimitInput)  # what the bridge takes (it never imports ssi.scene)
    p = limit_problem(site)
    assert p.ref_forces == COLUMNS
    assert p.footing_spans == SPANS
    assert p.ref_force == sum(COLUMNS)
    # each rigid footing's scaled load is its own column (downward), not the sum of both
    assert [ft.load_ref for ft in p.site.footings] == [(0.0, -n) for n in COLUMNS]


@pytest.fixture(scope="module")
def cap(site):
    # one coarse mesh: the identities below do not depend on the bracket's gap
    return site.limit_analysis(gap=0.9, h=3.0, h_min=1.0, max_steps=0, max_elements=2000)


def test_each_foundation_force_is_lambda_times_its_own_loads(cap):
    rows = cap.foundation_forces()
    assert len(rows) == 2
    for row, n, (x0, x1) in zip(rows, COLUMNS, SPANS):
        assert (row["x0"], row["x1"], row["reference"]) == (x0, x1, n)
        assert row["associated"] == pytest.approx((cap.lb * n, cap.ub * n), rel=1e-15)
        assert row["davis"] == pytest.approx((cap.lb_davis * n, cap.ub_davis * n), rel=1e-15)
    total_lb = sum(row["davis"][0] for row in rows)
    assert total_lb == pytest.approx(cap.lb_davis * sum(COLUMNS), rel=1e-12)
    assert cap.to_dict()["foundation_forces_N_per_m"][1]["davis"] == pytest.approx(list(rows[1]["davis"]))


def test_ssi_limit_text_gives_each_foundation_force_not_the_sum(cap):
    text = cap.summary()  # what `ssi limit` prints
    for i, ((x0, x1), n) in enumerate(zip(SPANS, COLUMNS)):
        lb, ub = cap.lb_davis * n / 1e3, cap.ub_davis * n / 1e3
        line = next(ln for ln in text.splitlines() if ln.strip().startswith(f"foundation {i} "))
        assert f"x = [{x0:g}, {x1:g}] m, its loads {n / 1e3:.4g} kN/m" in line
        assert f"Davis [{lb:.4g}, {ub:.4g}] kN/m" in line
    assert "footing force on top of the held loads" not in text  # the one summed line of a single footing


def test_a_load_the_limit_problem_does_not_represent_is_refused_by_name():
    """A horizontal Push (any load whose ``limit_action`` is the default) is refused with its place, never
    silently dropped beside the columns it would otherwise go with."""
    scene = Scene(
        width=12.0,
        depth=5.0,
        layers=[SoilLayer(5.0, E=20e6, nu=0.3, c=10e3, phi_deg=20.0)],
        foundation=Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)),
        contact=Contact(kn=1e10, kt=1e9, phi_deg=25.0),
        loads=[ColumnLoad(0.0, N=100e3)],
        phases=[Phase("push", (ColumnLoad(0.0, N=50e3), Push(0.01)))],
    )
    with pytest.raises(ValueError, match=r"Phase\('push'\)\.loads\[1\]: a horizontal Push is not built"):
        limit_problem(scene)
