"""A foundation described by its parts: soil layers, the foundation and its contact, loads, the mesh size and
the phases of construction (``Scene``); built into a model (``BuiltScene``), solved in stages, and viewed as
engineering quantities (``SceneResult``). ``scene_file`` reads and writes scenes as TOML."""

from .scene import (
    BuiltScene,
    ColumnLoad,
    Contact,
    ContactSegment,
    Excavation,
    Foundation,
    MeshSize,
    Phase,
    PhaseNonConvergence,
    RigidFooting,
    Scene,
    SceneResult,
    Settlement,
    SoilLayer,
    StripLoad,
    StripWeight,
    SurfacePressure,
    join_phases,
)

__all__ = [
    "BuiltScene",
    "ColumnLoad",
    "Contact",
    "ContactSegment",
    "Excavation",
    "Foundation",
    "MeshSize",
    "Phase",
    "PhaseNonConvergence",
    "RigidFooting",
    "Scene",
    "SceneResult",
    "Settlement",
    "SoilLayer",
    "StripLoad",
    "StripWeight",
    "SurfacePressure",
    "join_phases",
]
