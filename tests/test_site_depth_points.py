"""Properties varying with depth sampled at the Gauss points (issue 32 item 6): the per-point soil group
against the element-wise one, and the confined column with E growing linearly with depth against its exact
settlement."""

import numpy as np
import pytest

from ssi.core.model import Model
from ssi.core.protocol import CONSISTENT
from ssi.elements.soil_q8 import SoilQ8
from ssi.elements.soil_q8_points import SoilQ8Points
from ssi.materials.soil_laws import SoilLayer, material_table
from ssi.scene import MeshSize, SurfacePressure
from ssi.scene.site import DepthVarying, Site


def test_points_group_with_one_row_per_element_is_the_elementwise_group():
    """point_mat repeating each element's row: forces, tangent, state and body force equal SoilQ8's (1e-12
    relative: the same point sums, added in another order)."""
    model = Model()
    xy = np.array([[0, 0], [2, 0], [2, 1], [0, 1], [1, 0], [2, 0.5], [1, 1], [0, 0.5]], float)
    xy2 = xy + [2.0, 0.0]
    ids = model.add_nodes(np.vstack([xy, xy2]), ndof=2)
    conn = np.array([ids[:8], ids[8:]])
    kinds, params = material_table(
        [
            SoilLayer(1.0, E=2e7, nu=0.3, c=5e3, phi_deg=25.0, psi_deg=5.0).law(),
            SoilLayer(1.0, E=5e7, nu=0.2).law(),
        ]
    )
    args = (model.coords[conn], model.element_dofs(conn))
    el_mat = np.array([0, 1])
    a = SoilQ8(*args, el_mat, kinds, params, unit_weight=np.array([18e3, 20e3]))
    b = SoilQ8Points(
        *args, np.repeat(el_mat[:, None], 4, axis=1), kinds, params, unit_weight=np.array([18e3, 20e3])
    )
    rng = np.random.default_rng(3)
    du = 1e-3 * rng.standard_normal((2, 16))
    fa, ka, sa = a.evaluate(du, du, a.initial_state(), CONSISTENT)
    fb, kb, sb = b.evaluate(du, du, b.initial_state(), CONSISTENT)
    assert np.allclose(fb, fa, rtol=1e-12, atol=1e-12 * np.abs(fa).max())
    assert np.allclose(kb, ka, rtol=1e-12, atol=1e-12 * np.abs(ka).max())
    assert np.allclose(sb, sa, rtol=1e-12, atol=1e-12 * np.abs(sa).max())
    assert np.allclose(b.body_force(), a.body_force(), rtol=1e-12)
    assert np.allclose(
        b.elastic_stiffness(), a.elastic_stiffness(), rtol=1e-10, atol=1e-10 * np.abs(ka).max()
    )


def _column_error(h, sampling):
    """Relative error of the settlement of a laterally confined column (a uniform pressure over the whole
    width, rollers on the sides) whose E grows linearly with depth, against q c ln(1 + k H / E0) / k,
    c = (1 + nu)(1 - 2 nu)/(1 - nu) (the oedometric compliance integrated over the depth)."""
    e0, k, nu, q, depth = 1e6, 4e6, 0.3, 100e3, 10.0
    lay = DepthVarying(SoilLayer(1.0, E=e0, nu=nu), E_inc=k)
    site = Site(4.0, depth, [lay], loads=[SurfacePressure(-2.0, 2.0, q)],
                mesh=MeshSize(h_fine=h, h_coarse=h, growth=1.0), depth_varying=sampling)  # fmt: skip
    _, w = site.build().solve().ground_settlement()
    exact = q * (1 + nu) * (1 - 2 * nu) / (1 - nu) * np.log(1 + k * depth / e0) / k
    assert np.ptp(w) < 1e-12 * exact  # a 1-D state: the ground settles uniformly
    return w.mean() / exact - 1.0


def test_gauss_point_sampling_converges_faster_than_the_centroid_one():
    """E sampled at the Gauss points: second-order convergence of the column's settlement (the error falls
    by at least 3x when h halves, 4x for O(h^2)); at the centroid the error is several times larger on
    every mesh (a piecewise-constant E: first order)."""
    gauss = [_column_error(h, "gauss") for h in (1.0, 0.5)]
    centroid = [_column_error(h, "centroid") for h in (1.0, 0.5)]
    assert abs(gauss[1]) * 3.0 <= abs(gauss[0])
    assert all(abs(g) * 5.0 < abs(c) for g, c in zip(gauss, centroid)), (gauss, centroid)


def test_depth_varying_sampling_is_checked():
    with pytest.raises(ValueError, match="depth_varying"):
        Site(4.0, 4.0, [SoilLayer(1.0, E=1e6, nu=0.3)], depth_varying="nodes")


def test_gravity_loading_with_stiffness_growing_with_depth():
    """Gravity loading on level ground through the per-point group (E sampled at the Gauss points): the
    vertical stress is the weight above whatever the stiffness (1-D equilibrium with rollers on the sides;
    1e-6 relative, as for a uniform layer) and sigma_h/sigma_v = nu/(1 - nu)."""
    lay = DepthVarying(SoilLayer(1.0, E=2e6, nu=0.3, unit_weight=18e3), E_inc=3e6)
    site = Site(12.0, 8.0, [lay], initial_stress="gravity", mesher="structured",
                mesh=MeshSize(h_fine=0.5, h_coarse=2.0))  # fmt: skip
    built = site.build()
    assert isinstance(built.soil, SoilQ8Points) and built.initial_stress_method == "gravity"
    sig = built.soil.initial_stress
    sv = 18e3 * built.soil.integration_points()[..., 1]
    assert np.abs(sig[..., 1] - sv).max() <= 1e-6 * np.abs(sv).max()
    assert np.abs(sig[..., 0] / sig[..., 1] - 0.3 / 0.7).max() <= 1e-6
