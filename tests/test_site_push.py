"""The horizontal push-over load ``Push`` (issue 32 item 5): on a Scene and on a Site, its reaction as the
push-over's load, against the base's Tresca sliding resistance, and its named errors."""

import numpy as np
import pytest

from ssi.core.geometry import GeometryError
from ssi.elements.section import homogeneous
from ssi.scene import Contact, Foundation, MeshSize, Push, RigidFooting, Scene, SoilLayer
from ssi.scene.scene_file import scene_to_dict, site_from_dict
from ssi.scene.site import RigidStrip, Site, Strip

SEC = homogeneous(0.5, 30e9, 0.2)
C_I = 10e3  # base adhesion [Pa], phi_i = 0: the base slides at C_I * B whatever the normal force
TRESCA_BASE = Contact(kn=1e10, kt=1e9, phi_deg=0.0, c=C_I)
CLAY = SoilLayer(6.0, E=10e6, nu=0.3, unit_weight=18e3)
MESH = MeshSize(h_fine=0.5, h_coarse=2.0)


def _scene(loads, embedment=0.0, **kw):
    layers = [
        SoilLayer(1.0, E=10e6, nu=0.3, unit_weight=18e3),
        SoilLayer(5.0, E=10e6, nu=0.3, unit_weight=18e3),
    ]
    kw = {"foundation": Foundation(-1.0, 1.0, SEC), "contact": TRESCA_BASE} | kw
    return Scene(width=12.0, depth=6.0, layers=layers, embedment=embedment, mesh=MESH, loads=loads, **kw)


@pytest.mark.parametrize("embedment", [0.0, 1.0])
def test_push_slides_the_strip_at_the_base_adhesion(embedment):
    """An elastic soil, a Tresca base: pushed 3 cm (far beyond the elastic slip C_I / kt = 10 um) the strip
    slides at C_I B = 20 kN/m (1e-6 relative: the interface law's return mapping and the solver's force
    tolerance); capacity() reports that horizontal force as a plateau, its displacement the push."""
    out = _scene([Push(0.03)], embedment).build().solve(n_steps=6)
    assert out.is_push_over and out.is_horizontal_push
    load = out.foundation_load()
    assert load[-1] == pytest.approx(C_I * 2.0, rel=1e-6)
    assert out.load_settlement()["settlement"][-1] == pytest.approx(0.03, rel=1e-12)
    cap = out.capacity()
    assert cap["is_limit"] and cap["load"] == pytest.approx(C_I * 2.0, rel=1e-6)


def test_push_equals_the_displacement_prescribed_on_the_model():
    """The Push load prescribes what chapter 19 used to prescribe by hand (the plate nodes' u, rotations
    held): the same reaction history to round-off (1e-9 of the force)."""
    built = _scene([], 1.0).build()
    built.model.prescribe(built.plate_nodes, "u", -0.02)
    built.model.fix(built.plate_nodes, "alpha")
    by_hand = built.solve(n_steps=4).solver_result.support_reaction(built.plate_nodes, "u")
    out = _scene([Push(-0.02)], 1.0).build().solve(n_steps=4)
    assert np.allclose(out.built.push_force(out), by_hand, rtol=0.0, atol=1e-9 * C_I * 2.0)
    # a push in -x reports the force resisting it as positive
    assert out.foundation_load()[-1] == pytest.approx(C_I * 2.0, rel=1e-6)


def test_push_of_a_rough_rigid_footing_moves_its_base():
    out = _scene([Push(0.01)], contact=None, foundation=RigidFooting(-1.0, 1.0)).build().solve()
    dofs = out.built.model.dof(out.built.footing_nodes, "u")
    assert np.allclose(out.u[-1][dofs], 0.01, rtol=1e-12)
    assert out.foundation_load()[-1] > 0.0  # elastic soil resists the push


def test_push_named_errors():
    with pytest.raises(ValueError, match="Push.u"):
        Push(float("nan"))
    with pytest.raises(ValueError, match="Push.x"):
        _scene([Push(0.01, x=3.0)]).build()
    with pytest.raises(ValueError, match="symmetric"):
        _scene([Push(0.01)], contact=None, foundation=RigidFooting(-1.0, 1.0), symmetric=True)
    with pytest.raises(ValueError, match="smooth RigidFooting"):
        _scene([Push(0.01)], contact=None, foundation=RigidFooting(-1.0, 1.0, rough=False)).build()
    with pytest.raises(ValueError, match="frictionless"):
        _scene([Push(0.01)], contact=Contact(kn=1e10, kt=0.0)).build()
    with pytest.raises(ValueError, match="horizontal push is not built in the limit analysis"):
        _scene([Push(0.01)]).limit_analysis()


def _site(loads, strips=None):
    strips = strips or [Strip(Foundation(-1.0, 1.0, SEC), TRESCA_BASE)]
    return Site(width=12.0, depth=6.0, layers=[CLAY], strips=strips, loads=loads, mesh=MESH)


@pytest.mark.parametrize("mesher", ["structured", "gmsh"])
def test_site_push_slides_at_the_base_adhesion(mesher):
    """The same Tresca base on a Site, both meshes: C_I B to 1e-6 relative."""
    site = _site([Push(0.03)])
    site.mesher = mesher
    out = site.build().solve(load_factors=np.arange(1, 7) / 6)
    u, h = out.push_force(0)
    assert u[-1] == pytest.approx(0.03, rel=1e-12)
    assert h[-1] == pytest.approx(C_I * 2.0, rel=1e-6)


def test_site_push_picks_its_strip_and_names_errors():
    two = [Strip(Foundation(-4.0, -2.0, SEC), TRESCA_BASE), Strip(Foundation(2.0, 4.0, SEC), TRESCA_BASE)]
    with pytest.raises(GeometryError, match="give Push.x"):
        _site([Push(0.01)], two)
    with pytest.raises(GeometryError, match="lies on no strip"):
        _site([Push(0.01, x=0.0)], two)
    with pytest.raises(GeometryError, match="smooth RigidStrip"):
        _site([Push(0.01)], [RigidStrip(-1.0, 1.0, settle=0.01, rough=False)])
    with pytest.raises(ValueError, match="horizontal push is not built in the limit analysis"):
        _site([Push(0.01)]).limit_analysis()
    out = _site([Push(0.03, x=3.0)], two).build().solve(load_factors=np.arange(1, 7) / 6)
    assert out.push_force(1)[1][-1] == pytest.approx(C_I * 2.0, rel=1e-6)
    x, _ = out.strip_settlement(0)
    assert np.allclose(
        out.u[-1][out.built.model.dof(out.built.strips[0]["plate_nodes"], "u")], 0.0, atol=1e-3
    )


def test_push_in_a_site_file_dict():
    site = _site([Push(0.02)])
    data = scene_to_dict(site)
    assert site_from_dict(data).loads == [Push(0.02)]


def test_push_in_a_scene_file_dict():
    """A scene file's load table ``type = "Push"`` (the one load registry) round-trips."""
    from ssi.scene.scene_file import scene_from_dict, scene_to_dict

    data = scene_to_dict(_scene([Push(0.02, x=0.5)]))
    assert data["loads"] == [{"type": "Push", "u": 0.02, "x": 0.5}]
    assert scene_from_dict(data).loads == [Push(0.02, x=0.5)]


def test_push_in_a_later_phase():
    """A column load first, then the push (a phase of its own): the horizontal reaction is read from each
    phase's record, zero before the push and C_I B (1e-6) at its end; the displacement is the push."""
    from ssi.scene import ColumnLoad, Phase

    phases = [Phase("load", (ColumnLoad(0.0, N=100e3),), n_steps=2), Phase("push", (Push(0.03),), n_steps=6)]
    out = _scene([], phases=phases).build().solve()
    load, u = out.foundation_load(), out.load_settlement()["settlement"]
    last_load = out.phases[1]["last"]
    assert np.abs(load[: last_load + 1]).max() < 1e-6 * C_I * 2.0  # no horizontal load before the push
    assert load[-1] == pytest.approx(C_I * 2.0, rel=1e-6) and u[-1] == pytest.approx(0.03, rel=1e-12)
    cap = out.capacity()  # the plateau of the push, its stiffness measured from the push's first increment
    assert cap["is_limit"] and "plateau" in cap["how"], cap
