"""An embedded RigidStrip on a Site (issue 32 items 4 and 5): its trench, its side contact moving with its
rigid base, against an embedded very stiff plate Strip, under a push, its named errors and its file form; on
small meshes."""

import numpy as np
import pytest

from ssi.core.geometry import GeometryError
from ssi.elements.section import homogeneous
from ssi.scene import ColumnLoad, Contact, Foundation, MeshSize, Push, SoilLayer
from ssi.scene.scene_file import scene_to_dict, site_from_dict
from ssi.scene.site import Borehole, RigidStrip, Site, Strip

TOP = SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3)
LOW = SoilLayer(7.0, E=30e6, nu=0.3, unit_weight=19e3)
SIDE = Contact(kn=1e9, kt=1e8)  # linear: the elastic comparison is one linear solve each
SETTLE = 0.01  # [m]


def _site(strip, loads=(), mesher="auto"):
    return Site(
        width=16.0, depth=8.0, layers=[TOP, LOW], boreholes=[Borehole(0.0, [-1.0])], strips=[strip],
        loads=list(loads), mesh=MeshSize(h_fine=0.5, h_coarse=2.0), mesher=mesher,
    )  # fmt: skip


def _rigid(**kw):
    return RigidStrip(-1.0, 1.0, settle=SETTLE, level=-1.0, side_contact=SIDE, **kw)


@pytest.mark.parametrize("mesher", ["structured", "gmsh"])
def test_embedded_rigid_strip_settles_as_a_very_stiff_plate(mesher):
    """Elastic two-layer soil, the strip 1 m deep with linear side contact. The RigidStrip settles 1 cm
    (rough base): its reaction V (base and walls). The same-width plate Strip, 2 m thick with E = 3e12 Pa,
    on a contact of kn = kt = 1e12 Pa/m with the same side contact, under a column V at its middle settles
    1 cm as well, to 1e-4 relative: what separates them is the plate's contact compliance, V / (B kn) = 1.4e-7
    m (1.4e-5 relative), its bending (smaller still) and the plate's base not held horizontally (kt large,
    not infinite); measured 2e-5 to 3e-5 on both meshes."""
    built = _site(_rigid(), mesher=mesher).build()
    assert built.mesher == mesher and built.initial_stress_method == "gravity"
    settle, pressure = built.solve().rigid_pressure(0)
    assert settle[-1] == pytest.approx(SETTLE, rel=1e-12)
    force = pressure[-1] * 2.0
    assert force > 0.0
    stiff = homogeneous(2.0, 3e12, 0.2)
    plate = Strip(Foundation(-1.0, 1.0, stiff), Contact(kn=1e12, kt=1e12), level=-1.0, side_contact=SIDE)
    summary = _site(plate, [ColumnLoad(0.0, N=force)], mesher).build().solve().strip_summary(0)
    assert summary["mean"] == pytest.approx(SETTLE, rel=1e-4)
    assert summary["max"] == pytest.approx(SETTLE, rel=1e-3)  # the plate does not bend visibly


def test_embedded_rigid_strip_walls_carry_friction():
    """The side interfaces' structure side is one rigid body at the base's middle: both walls' elements
    reference it, its settlement is the strip's, and the walls' shear (kt > 0) adds to the vertical force:
    the rigid strip with side contact carries more than without (the walls' friction holds the backfill)."""
    built = _site(_rigid()).build()
    st = built.strips[0]
    left, right = st["side_interfaces"]
    assert np.array_equal(left.ref_xy[0], [0.0, -1.0]) and np.array_equal(right.ref_xy[0], [0.0, -1.0])
    out = built.solve()
    assert out.u[-1][built.model.dof([st["body"]], "w")[0]] == pytest.approx(-SETTLE, rel=1e-12)
    bare = _site(RigidStrip(-1.0, 1.0, settle=SETTLE, level=-1.0)).build().solve()
    assert out.rigid_pressure(0)[1][-1] > bare.rigid_pressure(0)[1][-1]


def test_embedded_rigid_strip_push_mobilises_the_smooth_walls():
    """Tresca clay (s_u = 20 kPa), the rigid strip 1 m deep with a rough base, pushed 5 cm: with smooth side
    contact (kt = 0, phi = 0, no tension) the push force exceeds the base-only one. Coarse, ordering only:
    at 5 cm neither has reached its capacity (the leading wall adds 28 kN/m here, against Rankine's passive
    0.5 gamma D^2 + 2 s_u D = 49 kN/m on a smooth wall, the trailing wall separating)."""
    clay = SoilLayer(6.0, E=10e6, nu=0.45, unit_weight=18e3, c=20e3, phi_deg=0.0)
    smooth = Contact(kn=1e9, kt=0.0, phi_deg=0.0)
    force = {}
    for name, side in (("base", None), ("side", smooth)):
        site = Site(
            width=12.0, depth=6.0, layers=[clay], loads=[Push(0.05)], mesh=MeshSize(h_fine=0.5, h_coarse=2.0),
            strips=[RigidStrip(-1.0, 1.0, settle=1e-4, level=-1.0, side_contact=side)],
        )  # fmt: skip
        out = site.build().solve(load_factors=np.arange(1, 11) / 10)
        u, h = out.push_force(0)
        assert out.status == "completed" and u[-1] == pytest.approx(0.05, rel=1e-12)
        force[name] = h[-1]
    assert force["side"] > force["base"] > 0.0


def test_embedded_rigid_strip_named_errors_and_file():
    with pytest.raises(GeometryError, match="RigidStrip.side_contact needs an embedded strip"):
        RigidStrip(-1.0, 1.0, settle=0.01, side_contact=SIDE)
    with pytest.raises(ValueError, match="RigidStrip.level"):
        RigidStrip(-1.0, 1.0, settle=0.01, level=float("nan"))
    with pytest.raises(GeometryError, match="in the air"):
        _site(RigidStrip(-1.0, 1.0, settle=0.01, level=0.5))
    with pytest.raises(GeometryError, match="against the block's side"):
        _site(RigidStrip(6.0, 8.0, settle=0.01, level=-1.0))
    with pytest.raises(ValueError, match="K0"):
        site = _site(_rigid())
        site.initial_stress = "K0"
        site.build()
    # an embedded RigidStrip is represented by the limit analysis now (its trench modelled); this site is
    # refused for what has no collapse load, every layer elastic, by name
    with pytest.raises(ValueError, match=r"every layer of the site is elastic"):
        _site(_rigid()).limit_analysis()
    back = site_from_dict(scene_to_dict(_site(_rigid())))
    assert back.strips == [_rigid()]
