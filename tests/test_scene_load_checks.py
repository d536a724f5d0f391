"""A scene's cross-field checks ask each load (its ``drives``, ``ground_span``, ``on_rigid_footing`` and
``magnitudes``), not its class: what a RigidFooting carries, what a symmetric half refuses, what an
excavation may not remove, and which values look like kN or kPa."""

import warnings

import pytest

from ssi.elements.section import homogeneous
from ssi.scene import (
    ColumnLoad,
    Contact,
    Excavation,
    Foundation,
    MeshSize,
    Phase,
    Push,
    RigidFooting,
    Scene,
    Settlement,
    SoilLayer,
    StripLoad,
    StripWeight,
    SurfacePressure,
)

SOIL = [SoilLayer(6.0, E=20e6, nu=0.3, unit_weight=18e3)]
COARSE = MeshSize(h_fine=0.5, h_coarse=2.0)


def _footing(loads, **kw):
    return Scene(12.0, 6.0, SOIL, foundation=RigidFooting(-1.0, 1.0), loads=loads, mesh=COARSE, **kw)


def _strip(loads=(), **kw):
    f = Foundation(-1.0, 1.0, homogeneous(0.5, 30e9, 0.2))
    contact = Contact(kn=1e10, kt=1e9)
    return Scene(12.0, 6.0, SOIL, foundation=f, contact=contact, loads=list(loads), mesh=COARSE, **kw)


def test_what_a_rigid_footing_carries():
    # its whole settlement, a push and a ground pressure beside it: built
    _footing([Settlement(0.01), SurfacePressure(2.0, 4.0, 10e3)]).build()
    _footing([Push(0.01)]).build()
    # a force on a plate, a column's settlement, a strip load, a strip weight: refused by name
    for load in (ColumnLoad(0.0, N=100e3), Settlement(0.01, x=(0.0,)), StripLoad(10e3), StripWeight()):
        with pytest.raises(ValueError, match="a RigidFooting takes only Settlement"):
            _footing([load]).build()


def test_a_symmetric_half_refuses_a_push():
    with pytest.raises(ValueError, match="pushes the footing sideways"):
        _footing([Push(0.01)], symmetric=True)


def test_an_excavation_may_not_remove_the_ground_under_a_pressure():
    with pytest.raises(ValueError, match=r"removes the ground under SurfacePressure\(3.0, 5.0\)"):
        _strip(
            [SurfacePressure(3.0, 5.0, 10e3)],
            phases=[Phase("dig", excavate=(Excavation(2.5, 4.0, 1.0),))],
        ).build()


@pytest.mark.parametrize(
    ("load", "label"),
    [
        (ColumnLoad(0.0, N=300.0), "ColumnLoad.N = 300 N/m"),
        (SurfacePressure(2.0, 4.0, 20.0), "SurfacePressure.q = 20 Pa"),
        (StripLoad(20.0), "StripLoad.q = 20 Pa"),
        (StripWeight(25.0), "StripWeight.unit_weight = 25 N/m"),
    ],
)
def test_a_load_in_kilo_units_is_warned_about_by_its_own_label(load, label):
    with pytest.warns(UserWarning, match=label.replace(".", r"\.").replace("^", r"\^")):
        _strip([load]).build()
    with warnings.catch_warnings():  # the same load in SI: no warning
        warnings.simplefilter("error")
        si = {k: v * 1e3 for k, v in _magnitude(load).items()}
        _strip([type(load)(**{**vars(load), **si})]).build()


def _magnitude(load):
    return {f: getattr(load, f) for f in ("N", "q", "unit_weight") if hasattr(load, f)}
