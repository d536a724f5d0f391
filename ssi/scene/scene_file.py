"""Scene and site files: a TOML description that maps one-to-one onto the :mod:`ssi.scene` dataclasses.

One reader for both (:func:`read_scene_file`, :func:`model_from_dict`): a file with a ``[foundation]`` table
or none of a site's keys (:data:`SITE_ONLY_KEYS`) is a :class:`Scene`, else a :class:`~ssi.scene.site.Site`;
their loads come from the one registry :data:`~ssi.scene.loads.LOAD_TYPES`. ``ssi schema`` lists every key
(:mod:`ssi.scene.file_schema`).

Every table is one dataclass and every key one of its fields, with the same name; a key the dataclass does
not have is refused with its name and where it was found. SI units throughout
(:data:`ssi.scene.file_schema.UNITS`). A scene::

    width = 12.0                       # [m]  Scene.width
    depth = 6.0                        # [m]  Scene.depth

    [[layers]]                         # SoilLayer, listed from the surface down
    thickness = 2.0                    # [m]
    E = 20e6                           # [Pa]
    nu = 0.3                           # [-]
    unit_weight = 18e3                 # [N/m^3]
    c = 10e3                           # [Pa]  (leave out: linear elastic)
    phi_deg = 30.0                     # [deg]

    [foundation]                       # Foundation
    x0 = -1.0                          # [m]
    x1 = 1.0                           # [m]
    section = { homogeneous = { thickness = 0.5, E = 30e9, nu = 0.2 } }

    [contact]                          # Contact
    kn = 1e10                          # [Pa/m]
    kt = 1e9                           # [Pa/m]

    [[loads]]                          # ColumnLoad (type = "ColumnLoad" is the default)
    x = 0.0                            # [m]
    N = 300e3                          # [N/m]

    [[loads]]
    type = "SurfacePressure"           # any load class of ssi.scene, by its name
    x0 = 2.0                           # [m]
    x1 = 4.0                           # [m]
    q = 20e3                           # [Pa]

    [mesh]                             # MeshSize
    h_fine = 0.5                       # [m]

    [solve]                            # not part of the Scene: n_steps and ssi.solver.Settings fields
    n_steps = 4                        # leave out: automatic load stepping
    method = "full"

A load table names its class with ``type`` (:data:`LOAD_TYPES`: ``ColumnLoad`` -- the default, so a table
without ``type`` is a column --, ``SurfacePressure``, ``StripLoad``, ``StripWeight``, ``Settlement``,
``Push``); its other keys are that class's fields. Phases are ``[[phases]]`` tables (``name``,
``factors = {earlier = 0.0}``, ``n_steps``, ``drainage = {1 = "undrained_A"}`` by layer index) with their
loads in ``[[phases.loads]]`` and
their excavations in ``[[phases.excavate]]`` (``x0``, ``x1``, ``bottom``, ``top`` [m]); ``embedment``,
``water_table``, ``gamma_w`` and ``symmetric`` are top-level keys; a ``[foundation]`` table with
``type = "RigidFooting"`` is a :class:`ssi.scene.RigidFooting` (``x0``, ``x1``, ``rough``); ``contact`` is
one table (:class:`ssi.scene.Contact`) or a list ``[[contact]]`` of :class:`ssi.scene.ContactSegment` tables
(``x0``, ``x1`` and a ``[contact.contact]`` table)::

    [[contact]]
    x0 = -1.0
    x1 = 0.0
    contact = { kn = 1e10, kt = 0.0 }

An embedded strip's side contact is a ``[side_contact]`` table (:class:`ssi.scene.Contact`, with
``embedment`` > 0): ``side_contact = { kn = 1e10, kt = 0.0, phi_deg = 0.0 }`` is a smooth side.

A site (:class:`~ssi.scene.site.Site`: boreholes or boundary polylines, a ground polyline, several strips;
``water_table`` is a DEPTH [m] below the ground in both, as in a scene; a site's ``water_level`` is an
ELEVATION [m] or a polyline of elevations, PLAXIS's phreatic level -- one of the two)::

    width = 30.0                          # [m]  Site.width
    depth = 12.0                          # [m]  Site.depth
    ground = [[-15.0, 1.0], [-4.0, 1.0], [4.0, 0.0], [15.0, 0.0]]   # [m] (x, z) polyline
    water_level = -3.0                    # [m] elevation, or a polyline; or water_table = 3.0 (depth)
    initial_stress = "auto"               # "auto" | "K0" | "gravity" | "gravity_plastic"
    mesher = "auto"                       # "auto" | "structured" | "gmsh"

    [[layers]]                            # SoilLayer fields (thickness: not needed, the boundaries decide)
    E = 10e6                              # [Pa]
    nu = 0.3
    E_inc = 1e6                           # [Pa/m] optional: a DepthVarying layer (also c_inc, z_ref)

    [[boreholes]]                         # Borehole: x [m], boundaries: elevations [m] from the top down
    x = -10.0
    boundaries = [-2.0]

    [[strips]]                            # Strip: a foundation and its contact (level [m], side_contact)
    foundation = { x0 = -6.0, x1 = -4.0, section = { homogeneous = { thickness = 0.5, E = 30e9, nu = 0.2 } } }
    contact = { kn = 1e10, kt = 1e9 }

    [[loads]]                             # ColumnLoad (default); type = "SurfacePressure", "Push"
    x = -5.0
    N = 300e3

``boundaries = [[[x, z], ...], ...]`` (one polyline per boundary) may replace the boreholes, or mix with
them: an empty polyline ``[]`` (None in Python) takes that boundary from the boreholes, which then list only
those; a strip table with ``type = "RigidStrip"`` holds a :class:`~ssi.scene.site.RigidStrip`'s fields. A
lens (:class:`~ssi.scene.site.Lens`) is a ``[[lenses]]`` table: ``points = [[x, z], ...]`` its outline and a
``layer`` table of SoilLayer keys (E_inc, c_inc, z_ref: a DepthVarying one).

The foundation's ``section`` is one of ``{homogeneous = {...}}`` (arguments of
:func:`ssi.elements.section.homogeneous`), ``{rc = {...}}`` (:func:`ssi.elements.section.rc_section` with
``bars = [[z, As], ...]`` and ``concrete``/``steel`` given as ``{fc = ..., ...}``/``{fy = ..., Es = ...}``,
see :func:`rc_section_from`) or ``{layers = {...}}``: the :class:`ssi.elements.section.Section` fields
themselves (z_mid, h, kind, params, carries_shear, z_bottom, z_top, labels) -- the exact form result files
store.
"""

import dataclasses
import tomllib
from pathlib import Path

import numpy as np

from ..elements import section as section_mod
from ..elements.section import Section
from ..materials.soil_laws import SoilLayer
from ..solver import Settings
from .loads import LOAD_TYPES, ColumnLoad, Push, Settlement, StripLoad, StripWeight, SurfacePressure  # noqa: F401
from .parts import Contact, ContactSegment, Excavation, Foundation, MeshSize, Phase, RigidFooting
from .scene import Scene
from .site import Site
from .site_parts import Borehole, DepthVarying, Lens, RigidStrip, Strip

# top-level keys a site file may have and a scene file may not (a scene file has a ``foundation``)
SITE_ONLY_KEYS = frozenset(
    {"strips", "boreholes", "boundaries", "ground", "mesher", "initial_stress", "water_level"}
)
DEPTH_KEYS = ("E_inc", "c_inc", "z_ref")  # a site's layer with these is a DepthVarying layer

_LOAD = "load"  # marks a field holding load tables
# fields holding other dataclasses: (class, field) -> (element class, container: "one" | "list" | "tuple")
_NESTED = {
    (Scene, "layers"): (SoilLayer, "list"),
    (Scene, "foundation"): (Foundation, "one"),
    (Scene, "loads"): (_LOAD, "list"),
    (Scene, "mesh"): (MeshSize, "one"),
    (Scene, "phases"): (Phase, "list"),
    (Phase, "loads"): (_LOAD, "tuple"),
    (Phase, "excavate"): (Excavation, "tuple"),
    (ContactSegment, "contact"): (Contact, "one"),
    (Scene, "side_contact"): (Contact, "one"),
    (Site, "loads"): (_LOAD, "list"),
    (Site, "phases"): (Phase, "list"),
    (Site, "lenses"): (Lens, "list"),
    (Site, "mesh"): (MeshSize, "one"),
    (Site, "boreholes"): (Borehole, "list"),
    (Strip, "foundation"): (Foundation, "one"),
    (Strip, "contact"): (Contact, "one"),
    (Strip, "side_contact"): (Contact, "one"),
    (RigidStrip, "side_contact"): (Contact, "one"),
}
# plain lists that the dataclass holds as tuples
_TUPLES = {(Settlement, "x")}
_SECTION_FIELDS = [f.name for f in dataclasses.fields(Section)]


# ---- Scene or Site -> plain dict (what result files store) -----------------------------------------------
def scene_to_dict(scene: Scene | Site) -> dict:
    """Every field of the scene (or site) as plain Python values (lists, floats, None); the section in its
    exact ``{"layers": {...}}`` form, so :func:`model_from_dict` rebuilds an identical scene."""
    return _to_plain(scene)


# classes whose table names its class with ``type``: a load, a RigidFooting, a RigidStrip
_TAGGED = frozenset(LOAD_TYPES.values()) | {RigidFooting, RigidStrip}


def _to_plain(obj):
    if isinstance(obj, Section):
        return {"layers": {name: _to_plain(getattr(obj, name)) for name in _SECTION_FIELDS}}
    if isinstance(obj, DepthVarying):  # a site's layer table: the SoilLayer's keys and the growth rates
        return {**_to_plain(obj.layer), **{k: getattr(obj, k) for k in DEPTH_KEYS}}
    if dataclasses.is_dataclass(obj):
        plain = {f.name: _to_plain(getattr(obj, f.name)) for f in dataclasses.fields(obj)}
        return {"type": type(obj).__name__, **plain} if type(obj) in _TAGGED else plain
    if isinstance(obj, dict):
        return {str(k): _to_plain(v) for k, v in obj.items()}
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, list | tuple):
        return [_to_plain(v) for v in obj]
    return obj


# ---- plain dict -> Scene or Site ------------------------------------------------------------------------
def is_site_data(data: dict) -> bool:
    """True if the plain dict describes a site: it has a key only a site has and no ``foundation``."""
    return "foundation" not in data and bool(SITE_ONLY_KEYS & data.keys())


def model_from_dict(data: dict, where: str = "scene") -> Scene | Site:
    """The :class:`Scene` or :class:`~ssi.scene.site.Site` a dict (from TOML or a result file) describes
    (:func:`is_site_data`); unknown keys raise ValueError naming them."""
    _check_table(data, where)
    return _build(Site if is_site_data(data) else Scene, data, where)


def scene_from_dict(data: dict) -> Scene:
    """The :class:`Scene` a dict (from TOML or a result file) describes; unknown keys raise ValueError."""
    return _build(Scene, data, "scene")


def site_from_dict(data: dict, where: str = "site") -> Site:
    """The :class:`~ssi.scene.site.Site` a dict describes (the same reader as a scene's, :func:`_build`)."""
    return _build(Site, data, where)


def _build(cls, data, where):
    if not isinstance(data, dict):
        raise TypeError(f"{where}: expected a table of {cls.__name__} fields, got {type(data).__name__}")
    names = {f.name for f in dataclasses.fields(cls)}
    unknown = sorted(set(data) - names)
    if unknown:
        raise ValueError(f"{where}: unknown key {unknown[0]!r} for {cls.__name__}; allowed: {sorted(names)}")
    kwargs = {}
    for key, value in data.items():
        nested = _NESTED.get((cls, key))
        if cls is Scene and key == "foundation" and isinstance(value, dict) and "type" in value:
            kwargs[key] = _foundation(value, f"{where}.foundation")
        elif cls is Site and key in ("layers", "strips"):
            kwargs[key] = _site_items(key, value, f"{where}.{key}")
        elif cls is Lens and key == "layer":  # a site's layer table (thickness optional, E_inc...)
            kwargs[key] = _site_items("layers", [value], f"{where}.layer")[0]
        elif cls is Foundation and key == "section":
            kwargs[key] = section_from_dict(value, f"{where}.section")
        elif cls is Scene and key == "contact" and value is not None:
            kwargs[key] = _contact(value, f"{where}.contact")
        elif nested is not None and value is not None:
            sub, container = nested
            if container == "one":
                kwargs[key] = _build(sub, value, f"{where}.{key}")
                continue
            name = "load" if sub is _LOAD else sub.__name__
            if not isinstance(value, list | tuple):
                raise TypeError(
                    f"{where}.{key}: expected a list of {name} tables, got {type(value).__name__}"
                )
            items = [
                _load(v, f"{where}.{key}[{i}]") if sub is _LOAD else _build(sub, v, f"{where}.{key}[{i}]")
                for i, v in enumerate(value)
            ]
            kwargs[key] = tuple(items) if container == "tuple" else items
        elif (cls, key) in _TUPLES and isinstance(value, list | tuple):
            kwargs[key] = tuple(value)
        elif cls is Phase and key == "factors":
            _check_table(value, f"{where}.factors")
            kwargs[key] = dict(value)
        elif cls is Phase and key == "drainage":
            kwargs[key] = _layer_keys(value, f"{where}.drainage")
        else:
            kwargs[key] = value
    try:
        return cls(**kwargs)
    except TypeError as err:  # a required field missing
        raise ValueError(f"{where}: {err}") from err


def _load(data, where):
    """One load table: its ``type`` names the class (default ColumnLoad), the other keys are its fields."""
    _check_table(data, where)
    fields = dict(data)
    kind = fields.pop("type", "ColumnLoad")
    if kind not in LOAD_TYPES:
        raise ValueError(f"{where}: unknown load type {kind!r}; allowed: {sorted(LOAD_TYPES)}")
    return _build(LOAD_TYPES[kind], fields, where)


def _site_items(key, value, where):
    """A site's ``layers`` (SoilLayer tables, thickness optional; with E_inc, c_inc or z_ref a DepthVarying
    layer) or ``strips`` (Strip tables; ``type = "RigidStrip"``: a RigidStrip's)."""
    if not isinstance(value, list | tuple):
        raise TypeError(f"{where}: expected a list of tables, got {type(value).__name__}")
    out = []
    for i, item in enumerate(value):
        here = f"{where}[{i}]"
        _check_table(item, here)
        if key == "layers":
            fields = {"thickness": 1.0, **{k: v for k, v in item.items() if k not in DEPTH_KEYS}}
            layer = _build(SoilLayer, fields, here)
            extra = {k: item[k] for k in DEPTH_KEYS if k in item}
            out.append(DepthVarying(layer, **extra) if extra else layer)
            continue
        fields = dict(item)
        kinds = {"Strip": Strip, "RigidStrip": RigidStrip}
        kind = fields.pop("type", "Strip")
        if kind not in kinds:
            raise ValueError(f"{here}: unknown strip type {kind!r}; allowed: {sorted(kinds)}")
        out.append(_build(kinds[kind], fields, here))
    return out


def _foundation(data, where):
    """A foundation table that names its class with ``type``: "Foundation" (the default) or "RigidFooting"."""
    fields = dict(data)
    kind = fields.pop("type")
    kinds = {"Foundation": Foundation, "RigidFooting": RigidFooting}
    if kind not in kinds:
        raise ValueError(f"{where}: unknown foundation type {kind!r}; allowed: {sorted(kinds)}")
    return _build(kinds[kind], fields, where)


def _contact(value, where):
    """``contact``: one Contact table, or a list of ContactSegment tables."""
    if isinstance(value, list | tuple):
        if not value:
            raise ValueError(f"{where}: a list of contact segments must not be empty")
        return [_build(ContactSegment, v, f"{where}[{i}]") for i, v in enumerate(value)]
    return _build(Contact, value, where)


def _layer_keys(value, where):
    """``{layer index: value}`` from a table whose keys are layer indices written as text (TOML keys and
    JSON object keys are strings: ``drainage = { 1 = "undrained_A" }``)."""
    _check_table(value, where)
    out = {}
    for key, item in value.items():
        text = str(key)
        if not text.isdigit():
            raise ValueError(f"{where}: key {key!r} must be a layer index 0, 1, ... (0 = the top layer)")
        out[int(text)] = item
    return out


def _check_table(data, where):
    if not isinstance(data, dict):
        raise TypeError(f"{where}: expected a table, got {type(data).__name__}")


def section_from_dict(data: dict, where: str = "section") -> Section:
    """A :class:`Section` from ``{"homogeneous": {...}}``, ``{"rc": {...}}`` or ``{"layers": {...}}``."""
    if not isinstance(data, dict) or len(data) != 1:
        raise ValueError(f"{where}: give exactly one of 'homogeneous', 'rc', 'layers', got {data!r}")
    ((kind, args),) = data.items()
    if kind == "homogeneous":
        _check_keys(args, {"thickness", "E", "nu", "n_layers", "z_ref"}, f"{where}.homogeneous")
        return section_mod.homogeneous(**args)
    if kind == "rc":
        return rc_section_from(args, f"{where}.rc")
    if kind == "layers":
        _check_keys(args, set(_SECTION_FIELDS), f"{where}.layers")
        arrays = {
            "z_mid": np.float64,
            "h": np.float64,
            "kind": np.int64,
            "params": np.float64,
            "carries_shear": bool,
        }
        kw = {
            k: (np.ascontiguousarray(np.asarray(v, arrays[k])) if k in arrays else v) for k, v in args.items()
        }
        kw["labels"] = tuple(kw.get("labels", ()))
        return Section(**kw)
    raise ValueError(f"{where}: unknown key {kind!r}; allowed: 'homogeneous', 'rc', 'layers'")


def rc_section_from(args: dict, where: str = "rc") -> Section:
    """:func:`ssi.elements.section.rc_section` from plain values: ``depth``, ``bars``, ``n_concrete``,
    ``concrete = {fc, E0?, eps_c?, fr?, Gf?, ls}`` (missing ones from
    :func:`ssi.materials.rc.designer_concrete`) and
    ``steel = {fy, Es?, EH?}``; the concrete's yield strain for shear retention is fy/Es."""
    from ..materials.layer_laws import CONCRETE, STEEL
    from ..materials.rc import concrete_params, designer_concrete, steel_params

    _check_keys(args, {"depth", "bars", "concrete", "steel", "n_concrete", "z_ref"}, where)
    conc = dict(args["concrete"])
    steel = dict(args["steel"])
    _check_keys(conc, {"fc", "E0", "eps_c", "fr", "Gf", "ls"}, f"{where}.concrete")
    _check_keys(steel, {"fy", "Es", "EH"}, f"{where}.steel")
    d = {**designer_concrete(conc["fc"]), **conc}
    es = steel.get("Es", 200e9)
    concrete = (
        CONCRETE,
        concrete_params(d["fc"], d["E0"], d["eps_c"], d["fr"], d["Gf"], d.get("ls", 0.1), steel["fy"] / es),
    )
    return section_mod.rc_section(
        args["depth"],
        [tuple(b) for b in args["bars"]],
        concrete,
        (STEEL, steel_params(steel["fy"], es, steel.get("EH", 0.0))),
        n_concrete=args.get("n_concrete", 9),
        z_ref=args.get("z_ref"),
    )


def _check_keys(args, allowed, where):
    if not isinstance(args, dict):
        raise TypeError(f"{where}: expected a table, got {type(args).__name__}")
    unknown = sorted(set(args) - allowed)
    if unknown:
        raise ValueError(f"{where}: unknown key {unknown[0]!r}; allowed: {sorted(allowed)}")


# ---- files ---------------------------------------------------------------------------------------------
def read_toml_and_solve(path) -> tuple[dict, int | None, dict]:
    """``(data, n_steps, solve)`` of a TOML scene or site file: its tables, and its optional ``[solve]``
    table split into ``n_steps`` (an integer >= 1: that many equal load levels; left out: None, automatic
    stepping) and the :class:`ssi.solver.Settings` fields (checked by name)."""
    path = Path(path)
    with open(path, "rb") as fh:
        try:
            data = tomllib.load(fh)
        except tomllib.TOMLDecodeError as err:
            raise ValueError(f"{path}: not valid TOML: {err}") from err
    solve = dict(data.pop("solve", {}))
    n_steps = solve.pop("n_steps", None)
    if n_steps is not None and (isinstance(n_steps, bool) or not isinstance(n_steps, int) or n_steps < 1):
        raise ValueError(
            f"{path.name}: solve: 'n_steps' must be an integer >= 1 (leave it out for automatic "
            f"stepping), got {n_steps!r}"
        )
    _check_keys(solve, {f.name for f in dataclasses.fields(Settings)}, f"{path.name}: solve")
    return data, n_steps, solve


def read_scene_file(path) -> tuple[Scene | Site, int | None, Settings]:
    """``(scene or site, n_steps, settings)`` from a TOML scene or site file (:func:`model_from_dict`); the
    optional ``[solve]`` table holds ``n_steps`` and any :class:`ssi.solver.Settings` field
    (:func:`read_toml_and_solve`)."""
    data, n_steps, solve = read_toml_and_solve(path)
    return model_from_dict(data, Path(path).name), n_steps, Settings(**solve)


def is_site_file(path) -> bool:
    """True if the TOML file at ``path`` describes a site (:func:`is_site_data`); a file that is not valid
    TOML is left to the reader's error."""
    try:
        with open(path, "rb") as fh:
            return is_site_data(tomllib.load(fh))
    except tomllib.TOMLDecodeError:
        return False
