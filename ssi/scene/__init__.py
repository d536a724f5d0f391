"""A foundation described by its parts: soil layers, the foundation and its contact, loads, the mesh size and
the phases of construction (``Scene``); built into a model (``BuiltScene``), solved in stages, and viewed as
engineering quantities (``SceneResult``).

* ``loads`` -- the loads; ``parts`` -- foundation, contact, mesh size, phases, excavations;
* ``checks`` -- checks across the fields of a scene; ``scene`` -- ``Scene`` and its builder;
* ``built`` -- ``BuiltScene``: load effects, water fields, the staged analysis; ``stages`` -- its pieces;
* ``view`` -- ``SceneResult``; ``scene_file`` -- scenes as TOML and plain dicts.
"""

from ..materials.soil_laws import SoilLayer
from .built import BuiltScene
from .loads import ColumnLoad, Settlement, StripLoad, StripWeight, SurfacePressure
from .parts import Contact, ContactSegment, Excavation, Foundation, MeshSize, Phase, RigidFooting
from .scene import Scene
from .stages import PhaseNonConvergence, join_phases
from .view import SceneResult

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
