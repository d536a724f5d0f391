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
(means over the interface element's points [Pa]) and ``contact_open`` (share of open points).
"""

from pathlib import Path

import meshio
import numpy as np

from .results import atomic_path

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
)


def mesh_cells(result) -> list:
    """meshio cell blocks [(type, conn)]: soil quad8, then the strip's and the contact's line3."""
    built = result.built
    cells = [("quad8", built.mesh.conn)]
    if built.plate is not None:
        p = built.plate_nodes
        conn = np.column_stack([p[0:-2:2], p[1:-1:2], p[2::2]])
        cells.append(("line3", conn[:, [0, 2, 1]]))
        lower = _interface_lower_nodes(built)
        cells.append(("line3", lower[:, [0, 2, 1]]))
    return cells


def _interface_lower_nodes(built):
    from .results import element_nodes

    return element_nodes(built.model, built.interface.edofs)[:, 3:]


def point_data(result, k=-1) -> dict:
    built = result.built
    model = built.model
    u = np.asarray(result.u[k])
    disp = np.zeros((model.n_nodes, 3))
    rot = np.zeros(model.n_nodes)
    soil = np.arange(built.mesh.xy.shape[0])
    disp[soil, 0] = u[model.dof(soil, "u")]
    disp[soil, 1] = u[model.dof(soil, "w")]
    if built.plate_nodes is not None:
        p = built.plate_nodes
        disp[p, 0] = u[model.dof(p, "u")]
        disp[p, 1] = u[model.dof(p, "w")]
        rot[p] = u[model.dof(p, "alpha")]
    return {"displacement": disp, "rotation": rot}


def cell_data(result, k=-1) -> dict:
    """Per-block cell data (lists in the order of :func:`mesh_cells`)."""
    built = result.built
    n_soil = built.mesh.conn.shape[0]
    n_plate = 0 if built.plate is None else built.plate.n_el
    blocks = [n_soil] + ([n_plate, built.interface.n_el] if n_plate else [])
    data = {name: [np.full(n, np.nan) for n in blocks] for name in CELL_FIELDS}
    sig = result.soil_stress(k).mean(axis=1)
    for i, name in enumerate(STRESS_NAMES):
        data[name][0] = sig[:, i]
    data["plastic_fraction"][0] = result.plastic_points(k).mean(axis=1)
    data["plastic_strain"][0] = result.plastic_strain(k).max(axis=1)
    data["pore_pressure"][0] = (built.pore_pressure() + built.excess_pore_pressure(result, k)).mean(axis=1)
    if n_plate:
        f = result.strip_forces(k)
        data["N"][1], data["M"][1], data["Q"][1] = f["N"].mean(1), f["M"].mean(1), f["Q"].mean(1)
        c = result.contact(k)
        data["contact_pressure"][2] = -c["sig_n"].mean(axis=1)
        data["contact_shear"][2] = c["tau"].mean(axis=1)
        data["contact_open"][2] = (c["zone"] == "open").mean(axis=1)
    return data


def _points(result):
    xy = result.built.model.coords
    return np.column_stack([xy, np.zeros(len(xy))])


def export_vtu(result, path, k=-1, overwrite=False) -> Path:
    """One step as a VTU file (atomic write; an existing file is kept unless ``overwrite``)."""
    path = Path(path)
    if path.suffix != ".vtu":
        raise ValueError(f"path must end in .vtu, got {path.name!r}")
    mesh = meshio.Mesh(
        _points(result), mesh_cells(result), point_data=point_data(result, k), cell_data=cell_data(result, k)
    )
    with atomic_path(path, overwrite) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
    return path


def export_series(result, path, overwrite=False) -> Path:
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
        raise FileExistsError(f"{path} exists; pass overwrite=True to replace it")
    folder = path.parent / f"{path.stem}_steps"
    entries = []
    times = np.asarray(result.load_factor, np.float64)
    if np.any(np.diff(times) <= 0.0):
        times = np.arange(len(times), dtype=np.float64)
    for k, lam in enumerate(times):
        step_file = folder / f"{path.stem}_{k:04d}.vtu"
        export_vtu(result, step_file, k=k, overwrite=overwrite)
        entries.append(
            f'    <DataSet timestep="{float(lam)!r}" part="0" file="{folder.name}/{step_file.name}"/>'
        )
    text = (
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
        + "\n".join(entries)
        + "\n  </Collection>\n</VTKFile>\n"
    )
    with atomic_path(path, overwrite) as tmp:
        tmp.write_text(text)
    return path


def read_series(path) -> list:
    """[(time: load factor or step number, meshio.Mesh)] of a .pvd series written by :func:`export_series`."""
    import xml.etree.ElementTree as ET

    path = Path(path)
    root = ET.parse(path).getroot()
    return [
        (float(d.get("timestep")), meshio.read(path.parent / d.get("file"))) for d in root.iter("DataSet")
    ]


def export(result, path, overwrite=False) -> Path:
    """Export to ``path``: ``.pvd`` (every step) or ``.vtu`` (the last step)."""
    suffix = Path(path).suffix
    if suffix == ".pvd":
        return export_series(result, path, overwrite)
    if suffix == ".vtu":
        return export_vtu(result, path, overwrite=overwrite)
    raise ValueError(f"path must end in .pvd or .vtu, got {Path(path).name!r}")
