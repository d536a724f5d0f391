"""A site's water table has one meaning per field: ``water_table`` a DEPTH below the ground (as a Scene's),
``water_level`` an ELEVATION (or a polyline of elevations); a value that reads as the other convention is
refused by a ValueError naming the field and the convention."""

import numpy as np
import pytest

from ssi.scene import MeshSize, Scene, SoilLayer
from ssi.scene.site import Borehole, Site

COARSE = MeshSize(h_fine=1.0, h_coarse=3.0)
WET = [
    SoilLayer(3.0, E=20e6, nu=0.3, unit_weight=18e3, unit_weight_sat=20e3),
    SoilLayer(7.0, E=60e6, nu=0.25, unit_weight=19e3, unit_weight_sat=21e3),
]
SLOPE = [(-10.0, 2.0), (-2.0, 2.0), (4.0, 0.0), (10.0, 0.0)]


def _site(**kw):
    return Site(20.0, 10.0, WET, boreholes=[Borehole(0.0, [-3.0])], mesh=COARSE, **kw)


def test_a_depth_and_the_same_elevation_build_the_same_site():
    """water_table=2.0 (2 m below the level ground at z = 0, a Scene's meaning) and water_level=-2.0 give the
    same K0 state bit for bit, and it is the hand one: sigma_v' = 18 kN/m3 * 2 m + (20 - 9.81) kN/m3 below."""
    by_depth = _site(water_table=2.0, initial_stress="K0").build()
    by_level = _site(water_level=-2.0, initial_stress="K0").build()
    np.testing.assert_array_equal(by_depth.soil.initial_stress, by_level.soil.initial_stress)
    z = by_depth.soil.integration_points()[..., 1]
    top = (z > -3.0) & (z < -2.0)
    hand = -36e3 + (20e3 - 9.81e3) * (z[top] + 2.0)
    np.testing.assert_allclose(by_depth.soil.initial_stress[..., 1][top], hand, rtol=1e-9)
    # the same word means the same in a Scene: its water table 2 m below its ground
    assert Scene(20.0, 10.0, WET, water_table=2.0).water_table == by_depth.site.water_table


def test_a_depth_follows_sloping_ground():
    """On sloping ground a depth is measured from the ground above each point: z_w(x) = ground(x) - d."""
    site = _site(ground=SLOPE, water_table=1.5)
    xs = np.array([-10.0, -2.0, 1.0, 4.0, 10.0])
    np.testing.assert_allclose(site.water_z(xs), np.interp(xs, *np.array(SLOPE).T) - 1.5, rtol=0, atol=1e-12)


def test_the_other_convention_is_refused_by_name():
    # an elevation field given a depth: 2 m "down" is 2 m above the level ground, everywhere
    with pytest.raises(ValueError, match=r"water_level is the water table's ELEVATION.*water_table=2\.0"):
        _site(water_level=2.0)
    # a depth field given an elevation: -2 m "deep" is free water above the ground
    with pytest.raises(ValueError, match=r"water_table is the water table's DEPTH.*water_level=-2"):
        _site(water_table=-2.0)
    # a polyline is (x, z) points: elevations, not depths
    with pytest.raises(ValueError, match=r"DEPTH.*polyline.*water_level"):
        _site(water_table=[(-10.0, -1.0), (10.0, -2.0)])
    # below the block bottom everywhere: no soil wet, either field
    with pytest.raises(ValueError, match=r"DEPTH.*block bottom z=-10"):
        _site(water_table=12.0)
    with pytest.raises(ValueError, match=r"ELEVATION.*block bottom z=-10"):
        _site(water_level=-10.0)
    with pytest.raises(ValueError, match="not both"):
        _site(water_level=-2.0, water_table=2.0)


def test_partial_flooding_of_sloping_ground_is_accepted():
    """An elevation above the toe of a slope but below its crest (a river at the toe) is a valid level: only
    a level above the ground everywhere reads as a depth."""
    site = _site(ground=SLOPE, water_level=1.0)
    assert site.has_water and float(site.water_z(0.0)) == 1.0
