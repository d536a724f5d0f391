"""ssi.lab.examples: the shared model problems are what their docstrings say."""

import math

import numpy as np
import pytest

from ssi.lab.analytical import hetenyi_deflection
from ssi.lab.examples import CHAPTER11_COLUMN_LOAD, chapter11_foundation, chapter11_section, winkler_strip


def test_winkler_strip_is_hetenyi_beam():
    # thin strip: the Mindlin shear flexibility EI lam^2/(kappa G h) is ~1e-3 (chapter 07), 100 elements
    # resolve the wavelength to < 1e-4; the tolerance 5e-3 is chapter 07's
    depth, E, nu, k, P = 0.05, 30e9, 0.2, 5e6, 10e3
    x, w = winkler_strip(100, depth, E, nu, k, P)
    ei = E * depth**3 / (12 * (1 - nu**2))
    exact = hetenyi_deflection(x, P, k, ei)
    assert np.abs(w - exact).max() / exact.max() < 5e-3
    lam = (k / (4 * ei)) ** 0.25
    assert x[-1] - x[0] == pytest.approx(6 * math.pi / lam)


def test_winkler_strip_rejects_bad_input():
    with pytest.raises(ValueError, match="n_el"):
        winkler_strip(1, 0.05, 30e9, 0.2, 5e6, 10e3)
    with pytest.raises(ValueError, match="k"):
        winkler_strip(10, 0.05, 30e9, 0.2, -1.0, 10e3)


def test_chapter11_foundation_describes_chapter11():
    scene = chapter11_foundation(0.5, clay_E=12e6, h_coarse=4.0)
    assert [ld.N for ld in scene.loads] == [CHAPTER11_COLUMN_LOAD] * 2 == [400e3, 400e3]
    assert scene.layers[0].E == 12e6 and scene.layers[1].E == 80e6
    assert (scene.mesh.h_fine, scene.mesh.h_coarse) == (0.5, 4.0)
    assert np.array_equal(scene.foundation.section.h, chapter11_section().h)
    assert scene.foundation.section.h.sum() == pytest.approx(0.4)
