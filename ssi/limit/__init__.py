"""Finite-element limit analysis: the collapse load factor of a site as a certified bracket.

- :mod:`.geometry`: the input (:class:`Site`: a polygon split into regions with rigid-plastic materials,
  named boundary segments, rigid footings with their interfaces); Davis and strength reduction of a site;
- :mod:`.mesh`: Triangle quality meshes and nested longest-edge bisection;
- :mod:`.lower`: the lower bound (linear-stress triangles, SOCP, certified by projection);
- :mod:`.upper`: the upper bound (6-node quadratic-velocity triangles, SOCP, recomputed from velocities);
- :mod:`.analysis`: brackets, the gap split by element, adaptivity (the gap shares and the lower bound's own
  indicator), the factor of safety by strength reduction as a certified bracket (:func:`strength_reduction`:
  with or without loads, a slope under its weight alone; every conic status read for what it proves);
- :mod:`.check`: an incremental analysis's limit load against a bracket (inside, false collapse, mesh
  overestimate).

Imports numpy, scipy, clarabel, triangle and :mod:`ssi.core.validate` only, so a scene can wrap it thinly:
a scene's block is the :class:`Site` polygon, each soil layer a region below an interior polyline (its c,
phi, effective unit weight; an undrained layer phi = 0), a rigid footing a :class:`Footing` on the
``footing`` segments (its interface rough / smooth / Coulomb), a surcharge the ``pressure_dead`` of the free
surface (linear along a segment with ``pressure_dead_grad``: a trench wall's geostatic stress), the loads
that scale with lambda ``load_ref`` / ``pressure_ref`` (a ``Settlement`` push: the
footing's vertical force, so lambda is its mean pressure), a symmetric scene the axis as a "symmetry"
segment and the footing moving along z only; a footing with "r" in its ``moves`` also rotates about its
``centre`` (its ``moment_ref`` / ``moment_dead`` balanced by the base tractions' moment). Not covered yet:
pore pressures as loads (only effective unit weights). A footing with a :class:`Beam` bends: a beam along
its base with plastic hinges (M_p sagging and hogging) at every base node, or with an M-N interaction
polygon (``Beam.interaction``: the lower bound bounds (N, M) along the beam, the upper bound's hinges
rotate and extend normal to it). A Coulomb :class:`Interface` takes a tension cut-off ``tension`` (0: no
tension) in both bounds. A footing segment may carry its own interface (:class:`Boundary` ``interface``:
an embedded footing's trench walls on a side contact unlike its base). Both bounds of a bracket are solved
on two threads (``SSI_LIMIT_THREADS=1``: one).
"""

from .analysis import (
    AdaptiveResult,
    Bracket,
    SafetyFactor,
    adaptive,
    adaptive_pair,
    bracket,
    gap_shares,
    refine_marks,
    safety_factor,
    strength_reduction,
)
from .check import LimitCheck, check_limit, flag_suspect
from .geometry import (
    Beam,
    Boundary,
    Footing,
    Interface,
    Material,
    Site,
    davis_beta,
    site_from_geometry,
    strip_site,
)
from .lower import LowerBound, lower_bound
from .mesh import TriMesh, bisect, fans_at, triangulate
from .upper import UpperBound, upper_bound

__all__ = [
    "AdaptiveResult",
    "Beam",
    "Boundary",
    "Bracket",
    "Footing",
    "Interface",
    "LimitCheck",
    "LowerBound",
    "Material",
    "SafetyFactor",
    "Site",
    "TriMesh",
    "UpperBound",
    "adaptive",
    "adaptive_pair",
    "bisect",
    "bracket",
    "check_limit",
    "flag_suspect",
    "davis_beta",
    "fans_at",
    "gap_shares",
    "lower_bound",
    "refine_marks",
    "safety_factor",
    "site_from_geometry",
    "strength_reduction",
    "strip_site",
    "triangulate",
    "upper_bound",
]
