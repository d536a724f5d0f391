"""The keys of a scene or site file (:mod:`ssi.scene.scene_file`), their units and meaning: ``ssi schema``
prints them (:func:`schema_text`). One table per dataclass, one row per field."""

from .loads import LOAD_TYPES

__all__ = ["UNITS", "schema_text"]

UNITS = {
    "Scene": {
        "width": "m",
        "depth": "m",
        "layers": "list of SoilLayer tables, from the surface down",
        "foundation": "Foundation table, or a RigidFooting table (type = 'RigidFooting'); leave out: none",
        "contact": "Contact table, or a list of ContactSegment tables tiling the strip",
        "loads": "list of load tables (type = ...) of the first phase",
        "mesh": "MeshSize table",
        "surcharge": "Pa",
        "phases": "list of Phase tables",
        "embedment": "m (depth of the strip's base)",
        "water_table": "m (depth below the ground; < 0: free water above it, ponding; leave out: dry)",
        "gamma_w": "N/m^3",
        "symmetric": "bool (true: model the half x >= 0 of a scene symmetric about x = 0)",
        "side_contact": "Contact table on the sides of an embedded strip (leave out: none)",
    },
    "Site": {
        "width": "m",
        "depth": "m",
        "layers": "list of SoilLayer tables from the top down (thickness: not needed, the boundaries "
        "decide), or DepthVarying ones",
        "boreholes": "list of Borehole tables (or boundaries; the layer boundaries)",
        "boundaries": "[[[x m, z m], ...], ...] one polyline per layer boundary, from the top down; with "
        "boreholes, [] takes that boundary from them (they list only those)",
        "ground": "[[x m, z m], ...] ground polyline, x increasing; two points at one x: a vertical step "
        "(a cut's face) (leave out: level at z = 0)",
        "water_table": "m DEPTH of the water table below the ground, as a Scene's (on sloping ground it "
        "follows the ground; >= 0: a site builds no ponding); or give water_level; leave both out: dry",
        "strips": "list of Strip tables (type = 'RigidStrip': a RigidStrip table)",
        "loads": "list of load tables (type = 'ColumnLoad' | 'SurfacePressure' | 'Push')",
        "mesh": "MeshSize table",
        "mesher": "'auto' | 'structured' | 'gmsh'",
        "initial_stress": "'auto' | 'K0' | 'gravity' | 'gravity_plastic'",
        "gamma_w": "N/m^3",
        "depth_varying": "'gauss' | 'centroid' (where a DepthVarying layer is sampled)",
        "lenses": "list of Lens tables (closed regions of another soil)",
        "phases": "list of Phase tables (loads and factors; excavate and drainage: a Scene's only)",
        "water_level": "m ELEVATION of the water table (z up, as ground: PLAXIS's phreatic level), or "
        "[[x m, z m], ...] a polyline of elevations; or give water_table (a depth); leave both out: dry",
    },
    "DepthVarying": {
        "layer": "- (not a key: the SoilLayer keys stand in the same [[layers]] table)",
        "E_inc": "Pa/m (E grows with the depth below z_ref)",
        "c_inc": "Pa/m (c grows with the depth below z_ref)",
        "z_ref": "m (reference elevation; leave out: the ground above the point)",
    },
    "Lens": {
        "points": "[[x m, z m], ...] the outline (x-monotone: a vertical line meets it at most twice)",
        "layer": "a SoilLayer table (thickness not needed; E_inc, c_inc, z_ref: a DepthVarying one)",
    },
    "Borehole": {"x": "m", "boundaries": "[z m, ...] elevations of the layer boundaries from the top down"},
    "Strip": {
        "foundation": "Foundation table",
        "contact": "Contact table",
        "level": "m elevation of the base (leave out: the ground under it)",
        "side_contact": "Contact table on the trench walls of an embedded strip (leave out: none)",
    },
    "RigidStrip": {
        "x0": "m",
        "x1": "m",
        "settle": "m (down positive) at load factor 1",
        "rough": "bool (true: u = 0 under the base)",
        "level": "m elevation of the base (leave out: the ground under it)",
        "side_contact": "Contact table on the trench walls (leave out: none)",
    },
    "SoilLayer": {
        "thickness": "m",
        "E": "Pa",
        "nu": "-",
        "unit_weight": "N/m^3",
        "c": "Pa",
        "phi_deg": "deg",
        "psi_deg": "deg, 0 <= psi <= phi (leave out: 0, no dilation, as PLAXIS; psi = phi_deg: associated)",
        "K0": "-",
        "scheme": "'implicit' | 'explicit'",
        "unit_weight_sat": "N/m^3",
        "drainage": "'drained' | 'undrained_A'",
        "nu_u": "-",
        "n_sub": "- (sub-steps of the explicit scheme)",
        "drift": "bool (drift correction of the explicit scheme)",
    },
    "Foundation": {
        "x0": "m",
        "x1": "m",
        "section": "{homogeneous | rc | layers} table",
        "kappa": "-",
        "integration": "'selective' | 'full' | 'reduced'",
        "self_weight": "N/m^2",
        "self_bending": "'chord' | 'tangent' | 'initial' | 'none'",
        "crack_band": "'spacing' | 'point' | none",
        "bar_diameter": "m",
        "plane_strain": "bool",
        "tension_stiffening": "'all' | 'effective_area'",
    },
    "RigidFooting": {"x0": "m", "x1": "m", "rough": "bool (true: u = 0 under the base; false: smooth)"},
    "Contact": {
        "kn": "Pa/m",
        "kt": "Pa/m",
        "phi_deg": "deg",
        "c": "Pa",
        "psi_deg": "deg (leave out: 0, no dilation)",
        "sig_t": "Pa",
        "rule": "'newton_cotes' | 'gauss'",
    },
    "ContactSegment": {"x0": "m", "x1": "m", "contact": "Contact table"},
    "ColumnLoad": {"x": "m", "N": "N/m (down positive)", "H": "N/m (+x)", "M": "N m/m (counter-clockwise)"},
    "SurfacePressure": {"x0": "m", "x1": "m", "q": "Pa (down positive)"},
    "StripLoad": {
        "q": "Pa (down positive) at x0",
        "q_end": "Pa at x1 (leave out: uniform)",
        "x0": "m (leave out: the strip's x0)",
        "x1": "m (leave out: the strip's x1)",
    },
    "StripWeight": {"unit_weight": "N/m^3"},
    "Settlement": {"w": "m (down positive)", "x": "[m, ...] settled columns (leave out: the rigid strip)"},
    "Push": {"u": "m (+x positive)", "x": "m, a point on the pushed strip (leave out: the only strip)"},
    "Phase": {
        "name": "text",
        "loads": "list of load tables (type = ...)",
        "factors": "{earlier phase name = factor -}",
        "n_steps": "- (leave out: [solve] n_steps)",
        "excavate": "list of Excavation tables removed in this phase",
        "drainage": "{layer index = 'drained' | 'undrained_A'} from this phase on",
    },
    "Excavation": {
        "x0": "m",
        "x1": "m",
        "bottom": "m (depth below the ground)",
        "top": "m (depth below the ground; leave out: 0)",
    },
    "MeshSize": {
        "h_fine": "m",
        "h_coarse": "m",
        "growth": "-",
        "n_gauss": "2 | 3",
        "end_grading": "- (1: even; ends graded up to 4)",
    },
    "homogeneous": {"thickness": "m", "E": "Pa", "nu": "-", "n_layers": "-"},
    "rc": {
        "depth": "m",
        "bars": "[[z_bar m, As m^2/m], ...]",
        "n_concrete": "-",
        "concrete": "{fc Pa, E0 Pa, eps_c, fr Pa, Gf N/m, ls m}",
        "steel": "{fy Pa, Es Pa, EH Pa}",
    },
}


def schema_text() -> str:
    """The tables of a scene or site file, their keys and units, as text (``ssi schema``)."""
    lines = []
    for table, units in UNITS.items():
        lines.append(
            f"[{table}]" + ('  (a load table: type = "' + table + '")' if table in LOAD_TYPES else "")
        )
        lines += [f"  {key:16s} {unit}" for key, unit in units.items()]
    lines.append("[solve]  n_steps (leave out: automatic stepping) and any ssi.solver.Settings field")
    return "\n".join(lines)
