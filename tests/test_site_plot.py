"""The site figures (ssi.io.plot) draw the geometry under every plot, an embedded strip's trench with
it: the ground goes down the trench walls and along the base level, the strip lies at its level, and the
walls with side contact are drawn; on a small mesh."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402

from ssi.elements.section import homogeneous  # noqa: E402
from ssi.io.plot import ground_line  # noqa: E402
from ssi.io.plot import standard_figures as site_figures  # noqa: E402
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, SoilLayer  # noqa: E402
from ssi.scene.site import Borehole, RigidStrip, Site, Strip  # noqa: E402

TOP = SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3)
LOW = SoilLayer(7.0, E=30e6, nu=0.3, unit_weight=19e3)
SIDE = Contact(kn=1e9, kt=1e8)


def _segments(ax, color=None):
    """Every straight segment ((x_a, z_a), (x_b, z_b)) of the lines drawn on ``ax`` (in ``color`` if given),
    with its line's label."""
    out = []
    for line in ax.get_lines():
        if color is not None and to_rgba(line.get_color()) != to_rgba(color):
            continue
        x, z = (np.asarray(v, np.float64) for v in line.get_data())
        out += [((x[i], z[i]), (x[i + 1], z[i + 1]), line.get_label()) for i in range(len(x) - 1)]
    return out


def _has(segs, a, b, label=None):
    for p, q, lab in segs:
        if label is not None and lab != label:
            continue
        for u, v in ((p, q), (q, p)):
            if np.allclose(u, a, atol=1e-9) and np.allclose(v, b, atol=1e-9):
                return True
    return False


def test_ground_line_cuts_the_trench():
    """The soil's top surface of a 1 m deep trench from x = -1 to 1: down at x = -1, along z = -1, up at
    x = 1; no point of it above the trench (exact: the points are the geometry's own)."""
    site = Site(
        width=16.0, depth=8.0, layers=[TOP, LOW], boreholes=[Borehole(0.0, [-2.0])],
        strips=[RigidStrip(-1.0, 1.0, settle=0.01, level=-1.0)],
    )  # fmt: skip
    x, z = ground_line(site)
    pts = list(zip(x, z))
    i = pts.index((-1.0, 0.0))
    assert pts[i : i + 4] == [(-1.0, 0.0), (-1.0, -1.0), (1.0, -1.0), (1.0, 0.0)]
    assert not np.any((np.abs(x) < 1.0) & (z > -1.0))
    assert np.all(np.diff(x) >= 0.0)


@pytest.mark.parametrize("rigid", [False, True])
def test_every_site_plot_draws_the_trench_and_the_strip_at_its_level(rigid):
    """Each geometry figure of a solved embedded site (deformed mesh, stress) holds the ground's wall
    segments (-1, 0)-(-1, -1) and (1, 0)-(1, -1) and its bottom (-1, -1)-(1, -1), the side contact on both
    walls, and the foundation at z = -1."""
    strip = (
        RigidStrip(-1.0, 1.0, settle=0.01, level=-1.0, side_contact=SIDE)
        if rigid
        else Strip(Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2)), Contact(kn=1e10, kt=1e9), level=-1.0,
                   side_contact=SIDE)
    )  # fmt: skip
    site = Site(
        width=16.0, depth=8.0, layers=[TOP, LOW], boreholes=[Borehole(0.0, [-1.0])], strips=[strip],
        loads=[] if rigid else [ColumnLoad(0.0, N=200e3)], mesh=MeshSize(h_fine=0.5, h_coarse=2.0),
    )  # fmt: skip
    figs = site_figures(site.build().solve())
    try:
        for name in ("geometry_and_deformed_mesh", "stress"):
            ax = figs[name].axes[0]
            segs = _segments(ax)
            for x in (-1.0, 1.0):
                assert _has(segs, (x, 0.0), (x, -1.0), "ground"), name
                assert _has(_segments(ax, "C2"), (x, 0.0), (x, -1.0)), name  # the side contact
            assert _has(segs, (-1.0, -1.0), (1.0, -1.0), "ground"), name
            assert _has(segs, (-1.0, -1.0), (1.0, -1.0), "foundation"), name
            assert not _has(segs, (-1.0, 0.0), (1.0, 0.0)), name  # no ground drawn over the trench
    finally:
        for fig in figs.values():
            plt.close(fig)
