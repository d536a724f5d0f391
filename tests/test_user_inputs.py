"""Input a user gave that ssi mishandled (held-out fuzzing, issue 44): valid input accepted, bad input refused
by name -- never a traceback from inside ssi."""

import numpy as np
import pytest

from ssi.core.geometry import GeometryError
from ssi.scene import MeshSize, SoilLayer
from ssi.scene.site import Borehole, Site

COARSE = MeshSize(h_fine=0.5, h_coarse=3.0)


@pytest.mark.parametrize("nu", [0.495, 0.499])
def test_a_drained_layer_takes_any_nu_below_one_half(nu):
    """The undrained default nu_u = 0.495 is not checked against nu where the layer is drained: the layer is
    accepted and its law carries the nu given."""
    layer = SoilLayer(1.0, E=10e6, nu=nu)
    assert layer.drainage == "drained" and layer.law()[1][1] == nu
    with pytest.raises(ValueError, match="SoilLayer.nu_u"):  # undrained: nu_u must exceed nu
        SoilLayer(1.0, E=10e6, nu=nu, drainage="undrained_A")
    assert SoilLayer(1.0, E=10e6, nu=0.3, nu_u=0.499, drainage="undrained_A").undrained_k_water() > 0.0


def test_a_layer_boundary_beyond_the_site_is_refused_by_name():
    layers = [SoilLayer(1.0, E=10e6, nu=0.3), SoilLayer(1.0, E=40e6, nu=0.3)]
    with pytest.raises(GeometryError, match="layer boundary 0 .* beyond the block"):
        Site(10.0, 5.0, layers, boundaries=[[(20.0, -2.0), (30.0, -2.0)]])  # right of the 10 m block
    with pytest.raises(GeometryError, match="layer boundary 0 lies at or above the ground everywhere"):
        Site(10.0, 5.0, layers, boreholes=[Borehole(0.0, [1.0])])  # 1 m above the level ground at z = 0
    with pytest.raises(GeometryError, match="below the block bottom"):
        Site(10.0, 5.0, layers, boreholes=[Borehole(0.0, [-6.0])])
    Site(10.0, 5.0, layers, boundaries=[[(-20.0, -2.0), (20.0, -3.0)]])  # wider than the block: fine


def test_gravity_plastic_on_a_slope_that_cannot_stand_is_refused_by_name():
    """A cohesionless slope of 56 deg (3 m over 2 m) with phi = 30 deg cannot carry its own weight: the
    plastic gravity phase fails, and the user reads why, naming the input -- not a solver traceback."""
    soil = [SoilLayer(1.0, E=20e6, nu=0.3, unit_weight=18e3, c=0.0, phi_deg=30.0)]
    ground = [(-10.0, 3.0), (-1.0, 3.0), (1.0, 0.0), (10.0, 0.0)]
    site = Site(20.0, 6.0, soil, ground=ground, initial_stress="gravity_plastic", mesh=COARSE)
    with pytest.raises(ValueError, match='initial_stress = "gravity_plastic": the soil does not carry'):
        site.build()


def test_a_hand_built_concrete_section_with_a_short_row_is_refused_by_name():
    """Concrete layers given an elastic [E, nu] row: the Section names the layer and the row it needs (it
    ended in an IndexError inside the crack band)."""
    from ssi.elements.section import Section
    from ssi.materials.concrete import N_CONCRETE_PARAMS
    from ssi.materials.layer_laws import CONCRETE

    with pytest.raises(ValueError, match=f"layer 0 is CONCRETE, whose law needs {N_CONCRETE_PARAMS}"):
        Section(
            z_mid=np.array([-0.1, 0.1]), h=np.array([0.2, 0.2]), kind=np.array([CONCRETE, CONCRETE]),
            params=np.array([[30e9, 0.2], [30e9, 0.2]]), carries_shear=np.array([True, True]),
            z_bottom=-0.2, z_top=0.2,
        )  # fmt: skip
    from ssi.materials.rc import concrete_params, designer_concrete

    d = designer_concrete(30e6)
    row = concrete_params(30e6, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, 500e6 / 200e9)
    whole = Section(
        z_mid=np.array([-0.1, 0.1]), h=np.array([0.2, 0.2]), kind=np.array([CONCRETE, CONCRETE]),
        params=np.array([row, row]), carries_shear=np.array([True, True]), z_bottom=-0.2, z_top=0.2,
    )  # fmt: skip
    assert whole.params.shape == (2, N_CONCRETE_PARAMS)  # the whole row: accepted
