"""The soil block's mesh lines: the grading under the foundation towards its ends (``end_grading``).

Expected node positions are hand calculations of the power map in ``ssi.core.mesh.foundation_lines``; the
default is compared with the even spacing the block was built with before the option existed (reconstructed
here from ``np.linspace`` and ``graded_lines``, the pieces it was made of)."""

import numpy as np
import pytest

from ssi.core.mesh import MAX_END_GRADING, foundation_lines, graded_lines, soil_block
from ssi.lab.examples import chapter11_foundation, punch_settlement
from ssi.scene import MeshSize


def test_even_lines_are_the_default():
    assert np.array_equal(foundation_lines(-3.0, 3.0, 0.5), np.linspace(-3.0, 3.0, 13))
    assert np.array_equal(foundation_lines(-3.0, 3.0, 0.5, 1.0), np.linspace(-3.0, 3.0, 13))


def test_default_block_is_the_even_block_of_before():
    """x lines: even under the foundation, growing from that size beside it; z lines from that size too."""
    x0, x1, h, hc, g = -1.0, 1.0, 0.25, 1.0, 1.3
    mesh = soil_block(10.0, 5.0, [1.0, 4.0], (x0, x1), h, hc, g)
    h0 = (x1 - x0) / 8
    left = graded_lines(x0, -5.0, h0, hc, g)[::-1]
    right = graded_lines(x1, 5.0, h0, hc, g)
    old_x = np.unique(np.concatenate([left, np.linspace(x0, x1, 9), right]))
    assert np.array_equal(mesh.x_lines, old_x)
    explicit = soil_block(10.0, 5.0, [1.0, 4.0], (x0, x1), h, hc, g, end_grading=1.0)
    assert np.array_equal(mesh.x_lines, explicit.x_lines)
    assert np.array_equal(mesh.z_lines, explicit.z_lines)
    z_top = graded_lines(0.0, -1.0, h0, hc, g)
    assert np.array_equal(mesh.z_lines[::-1][: len(z_top)], z_top)


def test_scene_default_mesh_is_unchanged():
    assert MeshSize().end_grading == 1.0
    scene = chapter11_foundation(0.5, h_coarse=2.0)
    mesh = scene.build().mesh
    under = mesh.x_lines[(mesh.x_lines >= -3.0) & (mesh.x_lines <= 3.0)]
    assert np.array_equal(under, np.linspace(-3.0, 3.0, 13))


@pytest.mark.parametrize(
    ("n_el", "expected"),
    [
        (4, [0.0, 1.0, 4.0, 7.0, 8.0]),  # s(1/4) = (1/2)^2 / 2 = 1/8 of 8 m
        (3, [0.0, 8.0 / 9.0 * 3 / 2, 6.0 - 8.0 / 9.0 * 3 / 2, 6.0]),  # on 6 m: s(1/3) = (2/3)^2 / 2 = 2/9
    ],
)
def test_graded_lines_hand_calculation(n_el, expected):
    width = 8.0 if n_el == 4 else 6.0
    got = foundation_lines(0.0, width, width / n_el, 2.0)
    assert np.allclose(got, expected, rtol=0, atol=1e-12)


def test_grading_is_symmetric_and_shrinks_the_end_element_by_two_to_the_gamma():
    gamma = 1.75
    for n in (6, 7):
        lines = foundation_lines(-3.0, 3.0, 6.0 / n, gamma)
        assert len(lines) == n + 1 and np.all(np.diff(lines) > 0)
        assert np.allclose(lines, -lines[::-1], rtol=0, atol=1e-12)
    ends = [np.diff(foundation_lines(-3.0, 3.0, 6.0 / n, gamma))[0] for n in (6, 12, 24)]
    assert np.allclose(np.array(ends[:-1]) / ends[1:], 2.0**gamma, rtol=1e-12)
    assert np.isclose(ends[0], 3.0 * (2.0 / 6.0) ** gamma, rtol=1e-12)  # (x1 - x0)/2 * (2/n)^gamma


def test_block_grows_beside_the_foundation_from_the_end_element():
    mesh = soil_block(
        20.0, 10.0, foundation=(-2.0, 2.0), h_fine=0.5, h_coarse=2.0, growth=1.25, end_grading=2.0
    )
    under = foundation_lines(-2.0, 2.0, 0.5, 2.0)
    inside = mesh.x_lines[(mesh.x_lines >= -2.0 - 1e-12) & (mesh.x_lines <= 2.0 + 1e-12)]
    assert np.allclose(inside, under, rtol=0, atol=1e-12)
    h_end = under[1] - under[0]
    right = mesh.x_lines[mesh.x_lines >= 2.0 - 1e-12]
    assert np.allclose(right, graded_lines(2.0, 10.0, h_end, 2.0, 1.25), rtol=0, atol=1e-12)
    beside = np.diff(right)  # h_end, 1.25 h_end, ... times the common scale that fits the block, <= h_coarse
    assert np.allclose(beside[1:4] / beside[:3], 1.25, rtol=1e-12)
    assert abs(h_end - 2.0 * (2.0 / 8.0) ** 2) < 1e-12  # half-width * (2/n)^gamma, n = 8
    assert beside[0] < 0.5 * 0.5  # beside the end: a quarter of the even size 0.5 m, not the even size
    assert np.all(beside <= 2.0 * (1 + 1e-9))


@pytest.mark.parametrize("bad", [0.5, 0.999, MAX_END_GRADING + 0.1, float("nan")])
def test_bad_end_grading_is_named(bad):
    with pytest.raises(ValueError, match="end_grading"):
        foundation_lines(0.0, 1.0, 0.25, bad)
    with pytest.raises(ValueError, match="end_grading"):
        soil_block(10.0, 5.0, foundation=(-1.0, 1.0), end_grading=bad)
    with pytest.raises(ValueError, match=r"MeshSize\.end_grading"):
        MeshSize(end_grading=bad)
    with pytest.raises(TypeError, match=r"MeshSize\.end_grading"):
        MeshSize(end_grading="2")


@pytest.mark.parametrize(("end_grading", "order"), [(1.0, 1.0), (2.0, 2.0)])
def test_graded_punch_converges_at_the_graded_order(end_grading, order):
    """The punch's settlement P w / 2 is its strain energy: with the contact pressure singular like
    r^(-1/2) at the edges (u ~ r^(1/2)), its error falls like h^1 on even meshes and like h^min(gamma, 4)
    on meshes graded with exponent gamma (Babuska's radical grading; Q8 elements, 2p = 4). Observed order
    from n = 4, 8, 16 elements under the punch; the band +-0.25 covers what the pre-asymptotic meshes show
    (0.97 and 1.86 here, 0.98 and 2.02 from n = 16, 32, 64)."""
    w = [punch_settlement(n, end_grading) for n in (4, 8, 16)]
    observed = np.log2((w[1] - w[0]) / (w[2] - w[1]))
    assert w[0] < w[1] < w[2]
    assert abs(observed - order) < 0.25, observed
