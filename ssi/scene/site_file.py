"""Site files: a TOML description of a :class:`ssi.scene.site.Site`, its keys the dataclasses' fields (as in
:mod:`ssi.scene.scene_file`, whose tables for a foundation, a contact, a soil layer, a load and the mesh it
reuses). SI units::

    width = 30.0                          # [m]  Site.width
    depth = 12.0                          # [m]  Site.depth
    ground = [[-15.0, 1.0], [-4.0, 1.0], [4.0, 0.0], [15.0, 0.0]]   # [m] (x, z) polyline
    water_table = -3.0                    # [m] elevation, or a polyline; leave out: dry
    initial_stress = "auto"               # "auto" | "K0" | "gravity"
    mesher = "auto"                       # "auto" | "structured" | "gmsh"

    [[layers]]                            # SoilLayer fields (thickness: not needed, the boundaries decide)
    E = 10e6                              # [Pa]
    nu = 0.3
    unit_weight = 18e3                    # [N/m^3]
    E_inc = 1e6                           # [Pa/m] optional: a DepthVarying layer (also c_inc, z_ref)

    [[boreholes]]                         # Borehole: x [m], boundaries: elevations [m] from the top down
    x = -10.0
    boundaries = [-2.0]

    [[strips]]                            # Strip: a foundation and its contact (and level [m])
    foundation = { x0 = -6.0, x1 = -4.0, section = { homogeneous = { thickness = 0.5, E = 30e9, nu = 0.2 } } }
    contact = { kn = 1e10, kt = 1e9 }

    [[loads]]                             # ColumnLoad (default); type = "SurfacePressure", "Push"
    x = -5.0
    N = 300e3

``boundaries = [[[x, z], ...], ...]`` (one polyline per boundary) may replace the boreholes. A strip table
with ``level`` below the ground is embedded (a trench); its optional ``side_contact`` is a Contact table on
the trench walls, e.g. ``side_contact = { kn = 1e10, kt = 0.0, phi_deg = 0.0 }`` (smooth). A strip table
with ``type = "RigidStrip"`` holds a :class:`RigidStrip`'s fields (``x0``, ``x1``, ``settle``, ``rough``,
``level``, ``side_contact``).
The optional ``[solve]`` table holds ``n_steps`` and :class:`ssi.solver.Settings` fields, as in a scene file.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from ..solver import Settings
from .loads import ColumnLoad, Push, SurfacePressure
from .parts import Contact, Foundation, MeshSize
from .scene_file import _build, _check_keys, _check_table, read_toml_and_solve
from .site import Borehole, DepthVarying, Site, Strip
from .site_parts import RigidStrip

__all__ = ["read_site_file", "site_from_dict", "site_to_dict"]

SITE_KEYS = {
    "width", "depth", "layers", "boreholes", "boundaries", "ground", "water_table", "strips", "loads", "mesh",
    "mesher", "initial_stress", "gamma_w", "depth_varying",
}  # fmt: skip
DEPTH_KEYS = ("E_inc", "c_inc", "z_ref")


def site_from_dict(data: dict, where: str = "site") -> Site:
    """The :class:`Site` a plain dict (from TOML) describes; unknown keys raise ValueError naming them."""
    from ..materials.soil_laws import SoilLayer

    _check_table(data, where)
    _check_keys(data, SITE_KEYS, where)
    kw = {k: v for k, v in data.items() if k not in ("layers", "boreholes", "strips", "loads", "mesh")}
    layers = []
    for i, lay in enumerate(data.get("layers", [])):
        _check_table(lay, f"{where}.layers[{i}]")
        fields = {"thickness": 1.0, **{k: v for k, v in lay.items() if k not in DEPTH_KEYS}}
        layer = _build(SoilLayer, fields, f"{where}.layers[{i}]")
        extra = {k: lay[k] for k in DEPTH_KEYS if k in lay}
        layers.append(DepthVarying(layer, **extra) if extra else layer)
    kw["layers"] = layers
    if "boreholes" in data:
        kw["boreholes"] = [
            _build(Borehole, b, f"{where}.boreholes[{i}]") for i, b in enumerate(data["boreholes"])
        ]
    strips = []
    for i, s in enumerate(data.get("strips", [])):
        _check_table(s, f"{where}.strips[{i}]")
        if s.get("type") == "RigidStrip":  # a rigid strip footing: its fields (x0, x1, settle, rough, level)
            fields = {k: v for k, v in s.items() if k != "type"}
            if fields.get("side_contact") is not None:
                where_side = f"{where}.strips[{i}].side_contact"
                fields["side_contact"] = _build(Contact, fields["side_contact"], where_side)
            strips.append(_build(RigidStrip, fields, f"{where}.strips[{i}]"))
            continue
        _check_keys(s, {"foundation", "contact", "level", "side_contact"}, f"{where}.strips[{i}]")
        side = s.get("side_contact")
        strips.append(
            Strip(
                _build(Foundation, s["foundation"], f"{where}.strips[{i}].foundation"),
                _build(Contact, s["contact"], f"{where}.strips[{i}].contact"),
                s.get("level"),
                None if side is None else _build(Contact, side, f"{where}.strips[{i}].side_contact"),
            )
        )
    kw["strips"] = strips
    loads = []
    kinds = {"ColumnLoad": ColumnLoad, "SurfacePressure": SurfacePressure, "Push": Push}
    for i, ld in enumerate(data.get("loads", [])):
        _check_table(ld, f"{where}.loads[{i}]")
        fields = dict(ld)
        kind = fields.pop("type", "ColumnLoad")
        if kind not in kinds:
            raise ValueError(
                f"{where}.loads[{i}]: load type {kind!r} is not one a site takes: {sorted(kinds)}"
            )
        loads.append(_build(kinds[kind], fields, f"{where}.loads[{i}]"))
    kw["loads"] = loads
    if "mesh" in data:
        kw["mesh"] = _build(MeshSize, data["mesh"], f"{where}.mesh")
    return Site(**kw)


def read_site_file(path) -> tuple[Site, int | None, Settings]:
    """``(site, n_steps, settings)`` from a TOML site file (see the module docstring; the ``[solve]`` table
    as in a scene file: :func:`ssi.scene.scene_file.read_toml_and_solve`)."""
    data, n_steps, solve = read_toml_and_solve(path)
    return site_from_dict(data, Path(path).name), n_steps, Settings(**solve)


def site_to_dict(site: Site) -> dict:
    """Every field of ``site`` as plain values in the form :func:`site_from_dict` reads (what a site's result
    file stores to rebuild it): a DepthVarying layer as its SoilLayer's keys with ``E_inc``, ``c_inc``,
    ``z_ref``; a RigidStrip as a strip table with ``type = "RigidStrip"``; loads tagged by ``type``."""
    from .scene_file import _to_plain

    out = {}
    for f in dataclasses.fields(site):
        value = getattr(site, f.name)
        if f.name == "layers":
            value = [
                {**_to_plain(lay.layer), **{k: getattr(lay, k) for k in DEPTH_KEYS}}
                if isinstance(lay, DepthVarying)
                else _to_plain(lay)
                for lay in value
            ]
        elif f.name == "strips":  # a field left at None is left out: the reader's default restores it
            value = [
                {"type": "RigidStrip", **{k: v for k, v in _to_plain(s).items() if v is not None}}
                if isinstance(s, RigidStrip)
                else {k: v for k, v in _to_plain(s).items() if v is not None}
                for s in value
            ]
        else:
            value = _to_plain(value)
        if value is not None:
            out[f.name] = value
    return out
