"""The capacity bridge: a :class:`~ssi.scene.Scene` or a :class:`~ssi.scene.site.Site` turned into a
limit-analysis problem (:mod:`ssi.limit`) and its collapse load and factor of safety as certified brackets.
It ranks between ``limit`` and ``scene``: it reads a scene or a site through the fields and methods its
README.md lists (its functions take a :class:`LimitInput`) and each load through its ``limit_action``
(:mod:`ssi.capacity.action`), and never imports ``ssi.scene``; ``Scene.limit_analysis``,
``Scene.safety_factor``, ``Site.limit_analysis`` and ``Site.safety_factor`` call into it.
"""

from .action import FootingFrame, LimitAction, LimitInput
from .bracket import CapacityResult, capacity_bracket, initial_mesh, limit_analysis
from .common import SIDE_SOIL, LimitProblem, NotOnBeam
from .problem import limit_problem
from .safety import SafetyFactorResult, safety_factor
from .strip import strip_beam_capacity, strip_beam_interaction

__all__ = [
    "SIDE_SOIL",
    "CapacityResult",
    "FootingFrame",
    "LimitAction",
    "LimitInput",
    "LimitProblem",
    "NotOnBeam",
    "SafetyFactorResult",
    "capacity_bracket",
    "initial_mesh",
    "limit_analysis",
    "limit_problem",
    "safety_factor",
    "strip_beam_capacity",
    "strip_beam_interaction",
]
