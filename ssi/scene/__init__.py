"""A foundation described by its parts: soil layers, the foundation and its contact, loads, the mesh size and
the phases of construction (``Scene``); built into a model (``BuiltScene``), solved in stages, and viewed as
engineering quantities (``SceneResult``).

* ``loads`` -- the loads; ``parts`` -- foundation, contact, mesh size, phases, excavations;
* ``checks`` -- checks across the fields of a scene; ``scene`` -- ``Scene`` and its builder;
* ``built`` -- ``BuiltScene``: load effects, water fields, the staged analysis; ``stages`` -- its pieces;
* ``view`` -- ``SceneResult``; ``foundation_result`` -- one plate strip's view (a scene's or a site's);
* ``scene_file`` -- scenes and sites as TOML and plain dicts (one reader), ``file_schema`` -- their keys;
* sites of any layering: ``site`` -- ``Site`` (geometry, mesh); ``site_parts`` -- ``Borehole``,
  ``DepthVarying``, ``Lens``, ``Strip``, ``RigidStrip``; ``site_built`` -- ``BuiltSite``; ``site_view`` --
  ``SiteResult``.
"""

from ..materials.soil_laws import SoilLayer
from .built import BuiltScene
from .loads import ColumnLoad, Push, Settlement, StripLoad, StripWeight, SurfacePressure
from .parts import Contact, ContactSegment, Excavation, Foundation, MeshSize, Phase, RigidFooting
from .scene import Scene
from .site import BuiltSite, Site, SiteResult
from .site_parts import Borehole, DepthVarying, Lens, RigidStrip, Strip
from .stages import PhaseNonConvergence, join_phases
from .view import SceneResult

__all__ = [
    "Borehole",
    "BuiltScene",
    "BuiltSite",
    "ColumnLoad",
    "Contact",
    "ContactSegment",
    "DepthVarying",
    "Lens",
    "Excavation",
    "Foundation",
    "MeshSize",
    "Phase",
    "PhaseNonConvergence",
    "Push",
    "RigidFooting",
    "RigidStrip",
    "Scene",
    "SceneResult",
    "Settlement",
    "Site",
    "SiteResult",
    "SoilLayer",
    "Strip",
    "StripLoad",
    "StripWeight",
    "SurfacePressure",
    "join_phases",
]
