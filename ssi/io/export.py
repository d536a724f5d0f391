"""ParaView files of a :class:`ssi.scene.SceneResult` through meshio: a VTU per step and a .pvd time series.

Cells: the soil as quadratic quads (``quad8``; ssi's Q8 node order is VTK's), the foundation strip as
quadratic lines (``line3``, VTK order: ends then middle) on its reference surface, the contact as ``line3``
on the soil side of the interface. Points are all model nodes in model order at (x, z, 0) -- ParaView's
y axis is the scene's z.

Point data: ``displacement`` (n_nodes, 3) = (u, w, 0) [m] (Warp By Vector shows the deformed shape),
``rotation`` (n_nodes,) [rad] (plate nodes; 0 elsewhere). Cell data (NaN on blocks it does not apply to):
``sxx``, ``szz``, ``txz``, ``syy`` (soil stress [Pa], tension positive, the mean over each element's
integration points),
``plastic_fraction`` (share of yielding points), ``plastic_strain`` (largest accumulated norm),
``pore_pressure`` (hydrostatic below the water table plus the excess of undrained_A layers [Pa], compression
positive, the element mean; the stresses are effective), ``N``, ``M``,
``Q`` (strip forces, means over the element's points [N/m, N m/m]), ``contact_pressure``, ``contact_shear``
(means over the interface element's points [Pa]) and ``contact_open`` (share of open points); of an RC
strip ``steel_stress`` (largest |stress| of its bars over the element's points [Pa]), ``cracked_fraction``
(share of its concrete layer points beyond the cracking strain) and ``crack_width`` (the largest EN 1992-1-1
§7.3.4 crack width w_k over the element's axial points [m], :meth:`SceneResult.crack_width`); ``active``
(1: the soil element is present at that step, 0: excavated by an earlier phase -- its stress, strain and
pore pressure are then NaN, so ParaView's Threshold on ``active`` >= 1 shows the ground as it is);
``material_id`` (the soil element's layer: its index in ``scene.layers`` or ``site.layers``).

A :class:`ssi.scene.SiteResult` is written the same way: the soil, then each plate strip and its contact
(rigid strips are ground nodes and have no cells of their own); its pore pressure is the hydrostatic one
below the site's water table.

Units: every field's unit is in :data:`FIELD_UNITS`, and each VTU carries it as field data: a VTK string
array per field, ``unit_<name>`` (e.g. ``unit_sxx`` = "Pa"; ParaView lists them under Information, Data
Arrays), and ``time`` (the load factor or the step number, the .pvd entry's value). meshio neither writes
field data to a VTU nor reads string arrays, so :func:`export_vtu` adds them to the XML it wrote and
:func:`read_vtu` takes them out before meshio reads the rest.
"""

from __future__ import annotations

import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import TYPE_CHECKING

import meshio
import numpy as np

from ..materials.layer_laws import CONCRETE
from .results import OutputExistsError, atomic_path

if TYPE_CHECKING:  # annotations only
    from ..scene import SceneResult

STRESS_NAMES = ("sxx", "szz", "txz", "syy")
CELL_FIELDS = (
    *STRESS_NAMES,
    "plastic_fraction",
    "plastic_strain",
    "pore_pressure",
    "N",
    "M",
    "Q",
    "contact_pressure",
    "contact_shear",
    "contact_open",
    "active",
    "steel_stress",
    "cracked_fraction",
    "crack_width",
    "material_id",
)
FIELD_UNITS = {
    "displacement": "m",
    "rotation": "rad",
    "sxx": "Pa",
    "szz": "Pa",
    "txz": "Pa",
    "syy": "Pa",
    "plastic_fraction": "-",
    "plastic_strain": "-",
    "pore_pressure": "Pa",
    "N": "N/m",
    "M": "N m/m",
    "Q": "N/m",
    "contact_pressure": "Pa",
    "contact_shear": "Pa",
    "contact_open": "-",
    "active": "-",
    "steel_stress": "Pa",
    "cracked_fraction": "-",
    "crack_width": "m",
    "material_id": "-",
}


def _is_site(result) -> bool:
    return result.kind == "site"


def _plate_strips(result) -> list[dict]:
    """The plate strips of a site's result ({"plate", "interface", "plate_nodes"}; rigid strips have none)."""
    return [st for st in result.built.strips if not st.get("rigid")]


def mesh_cells(result: SceneResult) -> list[tuple[str, np.ndarray]]:
    """meshio cell blocks [(type, conn)]: soil quad8, then the strip's and the contact's line3 (of a site:
    each plate strip's and its contact's, strip by strip)."""
    built = result.built
    cells = [("quad8", built.mesh.conn)]
    if _is_site(result):
        from .results import element_nodes

        for st in _plate_strips(result):
            p = st["plate_nodes"]
            conn = np.column_stack([p[0:-2:2], p[1:-1:2], p[2::2]])
            cells.append(("line3", conn[:, [0, 2, 1]]))
            lower = element_nodes(built.model, st["interface"].edofs)[:, 3:]
            cells.append(("line3", lower[:, [0, 2, 1]]))
        return cells
    if built.plate is not None:
        p = built.plate_nodes
        conn = np.column_stack([p[0:-2:2], p[1:-1:2], p[2::2]])
        cells.append(("line3", conn[:, [0, 2, 1]]))
        lower = _interface_lower_nodes(built)
        cells.append(("line3", lower[:, [0, 2, 1]]))
    return cells


def _interface_lower_nodes(built) -> np.ndarray:
    from .results import element_nodes

    return element_nodes(built.model, built.interface.edofs)[:, 3:]


def point_data(result: SceneResult, k: int = -1) -> dict[str, np.ndarray]:
    """``displacement`` (n_nodes, 3) [m] and ``rotation`` (n_nodes,) [rad] at step ``k``."""
    built = result.built
    model = built.model
    u = np.asarray(result.u[k])
    disp = np.zeros((model.n_nodes, 3))
    rot = np.zeros(model.n_nodes)
    soil = np.arange(built.mesh.xy.shape[0])
    disp[soil, 0] = u[model.dof(soil, "u")]
    disp[soil, 1] = u[model.dof(soil, "w")]
    plates = (
        [st["plate_nodes"] for st in _plate_strips(result)]
        if _is_site(result)
        else [built.plate_nodes]
        if built.plate_nodes is not None
        else []
    )
    for p in plates:
        disp[p, 0] = u[model.dof(p, "u")]
        disp[p, 1] = u[model.dof(p, "w")]
        rot[p] = u[model.dof(p, "alpha")]
    return {"displacement": disp, "rotation": rot}


def cell_data(result: SceneResult, k: int = -1) -> dict[str, list[np.ndarray]]:
    """Per-block cell data (lists in the order of :func:`mesh_cells`); soil fields NaN in excavated
    elements (``active`` = 0); ``material_id`` the soil element's layer index (in ``scene.layers`` or
    ``site.layers``)."""
    if _is_site(result):
        return _site_cell_data(result, k)
    built = result.built
    n_soil = built.mesh.conn.shape[0]
    n_plate = 0 if built.plate is None else built.plate.n_el
    blocks = [n_soil] + ([n_plate, built.interface.n_el] if n_plate else [])
    data = {name: [np.full(n, np.nan) for n in blocks] for name in CELL_FIELDS}
    _soil_state(data, result, k)
    data["pore_pressure"][0] = (built.pore_pressure() + built.excess_pore_pressure(result, k)).mean(axis=1)
    active = result.active_elements(k) if result.phases else np.ones(n_soil, bool)
    data["active"][0] = active.astype(np.float64)
    data["material_id"][0] = np.asarray(built.element_layer, np.float64)
    for name in (*STRESS_NAMES, "plastic_fraction", "plastic_strain", "pore_pressure"):
        data[name][0][~active] = np.nan  # removed soil carries nothing: not a zero stress to be read
    if n_plate:
        f = result.strip_forces(k)
        data["N"][1], data["M"][1], data["Q"][1] = f["N"].mean(1), f["M"].mean(1), f["Q"].mean(1)
        c = result.contact(k)
        data["contact_pressure"][2] = -c["sig_n"].mean(axis=1)
        data["contact_shear"][2] = c["tau"].mean(axis=1)
        data["contact_open"][2] = (c["zone"] == "open").mean(axis=1)
        layers = result.plate_layers(k)
        steel = layers["steel"]
        if steel.any():  # the largest |stress| of the element's bars, at any of its axial points
            data["steel_stress"][1] = np.abs(layers["sig"][..., steel]).max(axis=(1, 2))
        concrete = result.built.plate.section.kind == CONCRETE
        if concrete.any():  # share of the element's concrete layer points beyond the cracking strain
            data["cracked_fraction"][1] = layers["cracked"][..., concrete].mean(axis=(1, 2))
        from ..scene.design import design_of  # lazily, as the other io modules import the scene

        if design_of(result) is not None:  # an RC strip: the widest crack at the element's axial points
            data["crack_width"][1] = result.crack_width(k)["w_k"].max(axis=1)
    return data


def _soil_state(data: dict, result, k: int) -> None:
    """The soil block's element means of stress and plastic share, and its largest plastic strain, at
    state ``k`` into ``data`` (block 0) -- the same for a scene and a site."""
    sig = result.soil_stress(k).mean(axis=1)
    for i, name in enumerate(STRESS_NAMES):
        data[name][0] = sig[:, i]
    data["plastic_fraction"][0] = result.plastic_points(k).mean(axis=1)
    data["plastic_strain"][0] = result.plastic_strain(k).max(axis=1)


def _site_cell_data(result, k: int) -> dict[str, list[np.ndarray]]:
    """:func:`cell_data` of a :class:`ssi.scene.SiteResult`: the soil block, then per plate strip its plate
    (N, M, Q) and its contact (pressure, shear, open share); pore pressure hydrostatic below the water
    table."""
    built = result.built
    strips = _plate_strips(result)
    blocks = [built.mesh.conn.shape[0]] + [
        n for st in strips for n in (st["plate"].n_el, st["interface"].n_el)
    ]
    data = {name: [np.full(n, np.nan) for n in blocks] for name in CELL_FIELDS}
    _soil_state(data, result, k)
    data["pore_pressure"][0] = result.pore_pressure().mean(axis=1)
    data["active"][0] = np.ones(blocks[0])
    data["material_id"][0] = np.asarray(built.element_layer, np.float64)
    plate_index = [i for i, st in enumerate(built.strips) if not st.get("rigid")]
    for j, i in enumerate(plate_index):
        f = result.strip_forces(i, k)
        b = 1 + 2 * j
        data["N"][b], data["M"][b], data["Q"][b] = f["N"].mean(1), f["M"].mean(1), f["Q"].mean(1)
        c = result.contact(i, k)
        data["contact_pressure"][b + 1] = -c["sig_n"].mean(axis=1)
        data["contact_shear"][b + 1] = c["tau"].mean(axis=1)
        data["contact_open"][b + 1] = (c["zone"] == "open").mean(axis=1)
    return data


def _points(result) -> np.ndarray:
    xy = result.built.model.coords
    return np.column_stack([xy, np.zeros(len(xy))])


def time_value(value: float) -> float:
    """A load factor as a time value without binary noise (0.30000000000000004 -> 0.3): rounded to 12
    significant digits, far finer than any load step."""
    return float(f"{float(value):.12g}")


def _add_field_data(path: Path, time: float) -> None:
    """Put the units of :data:`FIELD_UNITS` and the time into the VTU at ``path`` (:func:`_add_units`)."""
    _add_units(path, FIELD_UNITS, time)


def _add_units(path: Path, units: dict[str, str], time: float | None) -> None:
    """Put ``units`` {field: unit} (VTK string arrays ``unit_<field>``: each string's character codes,
    0-terminated, ascii) and the ``time`` (None: none) into the VTU at ``path`` as the grid's FieldData."""
    tree = ET.parse(path)
    grid = tree.getroot().find("UnstructuredGrid")
    fd = ET.Element("FieldData")
    for name, unit in units.items():
        arr = ET.SubElement(
            fd, "DataArray", type="String", Name=f"unit_{name}", NumberOfTuples="1", format="ascii"
        )
        arr.text = " ".join(str(b) for b in [*unit.encode(), 0])
    if time is not None:
        arr = ET.SubElement(fd, "DataArray", type="Float64", Name="time", NumberOfTuples="1", format="ascii")
        arr.text = repr(time_value(time))
    grid.insert(0, fd)
    tree.write(path, xml_declaration=True, encoding="utf-8")


def read_vtu(path: str | Path) -> meshio.Mesh:
    """A VTU written by :func:`export_vtu` as a meshio Mesh, its field data included: ``time`` (1,) and
    ``unit_<name>`` (1,) str arrays (meshio alone cannot read VTK string arrays)."""
    tree = ET.parse(path)
    grid = tree.getroot().find("UnstructuredGrid")
    fields = {}
    for fd in grid.findall("FieldData"):
        for arr in fd:
            if arr.get("type") == "String":
                codes = [int(c) for c in arr.text.split()]
                fields[arr.get("Name")] = np.array([bytes(codes[: codes.index(0)]).decode()])
            else:
                fields[arr.get("Name")] = np.array([float(v) for v in arr.text.split()])
        grid.remove(fd)
    with tempfile.TemporaryDirectory() as tmp:  # meshio reads VTU from a path only
        plain = Path(tmp) / "plain.vtu"
        tree.write(plain, xml_declaration=True, encoding="utf-8")
        mesh = meshio.read(plain, file_format="vtu")
    mesh.field_data.update(fields)
    return mesh


def export_vtu(
    result: SceneResult, path: str | Path, k: int = -1, overwrite: bool = False, time: float | None = None
) -> Path:
    """One step as a VTU file (atomic write; an existing file is kept unless ``overwrite``); ``time``: the
    value written as field data (default: the step's load factor)."""
    path = Path(path)
    if path.suffix != ".vtu":
        raise ValueError(f"path must end in .vtu, got {path.name!r}")
    mesh = meshio.Mesh(
        _points(result),
        mesh_cells(result),
        point_data=point_data(result, k),
        cell_data=cell_data(result, k),
    )
    with atomic_path(path, overwrite) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
        _add_field_data(tmp, result.load_factor[k] if time is None else time)
    return path


def export_series(result: SceneResult, path: str | Path, overwrite: bool = False) -> Path:
    """Every converged step as a ParaView time series: ``path`` (.pvd, the collection, load factor as
    time) and one VTU per step in the folder ``<stem>_steps`` beside it. Each file is written atomically,
    the .pvd last, so a reader never sees a collection pointing at missing steps. ParaView shows one data
    set per time value, so where the load factors do not strictly increase (a phased result: its initial
    and geostatic states are both at phase time 0) the step number is the time instead.

    (XDMF + HDF5 through meshio was tried first: meshio writes the mixed quad8/line3 grid as an XDMF
    "Mixed" topology that its own reader cannot read back, so the export could not be checked.)"""
    path = Path(path)
    if path.suffix != ".pvd":
        raise ValueError(f"path must end in .pvd, got {path.name!r}")
    if path.exists() and not overwrite:
        raise OutputExistsError(path)
    folder = path.parent / f"{path.stem}_steps"
    entries = []
    times = np.asarray(result.load_factor, np.float64)
    if np.any(np.diff(times) <= 0.0):
        times = np.arange(len(times), dtype=np.float64)
    for k, lam in enumerate(times):
        step_file = folder / f"{path.stem}_{k:04d}.vtu"
        export_vtu(result, step_file, k=k, overwrite=overwrite, time=lam)
        entries.append(
            f'    <DataSet timestep="{time_value(lam)!r}" part="0" file="{folder.name}/{step_file.name}"/>'
        )
    text = (
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
        + "\n".join(entries)
        + "\n  </Collection>\n</VTKFile>\n"
    )
    with atomic_path(path, overwrite) as tmp:
        tmp.write_text(text)
    return path


def read_series(path: str | Path) -> list[tuple[float, meshio.Mesh]]:
    """[(time: load factor or step number, meshio.Mesh with its field data)] of a .pvd series written by
    :func:`export_series`."""
    path = Path(path)
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), read_vtu(path.parent / d.get("file"))) for d in root.iter("DataSet")]


def export(result: SceneResult, path: str | Path, overwrite: bool = False) -> Path:
    """Export to ``path``: ``.pvd`` (every step) or ``.vtu`` (the last step)."""
    suffix = Path(path).suffix
    if suffix == ".pvd":
        return export_series(result, path, overwrite)
    if suffix == ".vtu":
        return export_vtu(result, path, overwrite=overwrite)
    raise ValueError(f"path must end in .pvd or .vtu, got {Path(path).name!r}")
