"""The parts of a scene besides its soil layers and loads: the foundation (a layered strip or a rigid
footing), the contact under it, the mesh size, and the phases of construction with the excavations they dig.
"""

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..core.mesh import MAX_END_GRADING
from ..core.validate import (
    check_bool,
    check_choice,
    check_instance,
    check_int,
    check_optional_real,
    check_real,
)
from ..elements.plate import INTEGRATIONS
from ..elements.section import Section
from ..materials.interface_law import interface_params
from ..materials.layer_laws import CONCRETE
from ..materials.soil_laws import (
    DRAINAGE,
)
from .loads import LOAD_TYPES


@dataclass(frozen=True)
class Foundation:
    """The strip from x0 to x1 (both become soil mesh lines) with its layered ``section``.

    Section options (passed to :class:`ssi.elements.plate.PlateStrip`; defaults from chapters 02 and 08):
    ``kappa`` shear factor (5/6); ``integration`` along the element ("selective", the paper's);
    ``self_bending`` = "chord" (each layer's own bending from the stresses at its faces: within about 1 % of
    the layer-free moment with 11 layers up to 0.06 1/m, where "initial" is +17 %, and continuous, unlike
    "tangent"; chapter 02, row ``section_selfbending``); ``crack_band`` = "spacing" (every concrete layer's
    band width ls = the crack spacing s_r,max of fib Model Code 2010 from the nearest bars, ``bar_diameter``
    [m] and the cover:
    one band per crack, so the response does not depend on the element size; chapter 08, row
    ``fig12_mesh_spread``), "point" (the paper's rule: ls = the length each sampling point represents,
    mesh-dependent for a reinforced strip) or None (the ls already in the section's parameters);
    ``plane_strain`` = True: the concrete layers use E0 / (1 - nu^2) like the elastic layers (eq. 4.4), so the
    strip is consistently plane strain (False: keep the section's own setting, e.g. a plane-stress beam);
    ``tension_stiffening`` (with ``crack_band="spacing"``): "all" cracked concrete layers (chapter 03's rule)
    or only the "effective_area" h_c,ef around the bars (chapters 03 and 08 score both).
    """

    rigid: ClassVar[bool] = False  # a plate strip on an interface (RigidFooting: True)

    x0: float
    x1: float
    section: Section
    kappa: float = 5.0 / 6.0
    integration: str = "selective"
    self_weight: float = 0.0  # [N/m^2] of the strip's plan area, a dead load
    self_bending: str = "chord"
    crack_band: str | None = "spacing"
    bar_diameter: float = 0.016
    plane_strain: bool = True
    tension_stiffening: str = "all"

    def strip_section(self) -> Section:
        """The section the strip is built with (concrete bands set to the crack spacing for "spacing")."""
        if self.crack_band not in ("spacing", "point", None):
            raise ValueError(f"crack_band must be 'spacing', 'point' or None, got {self.crack_band!r}")
        from dataclasses import replace

        from ..elements.section import with_crack_spacing_band
        from ..materials.rc import with_plane_strain

        sec = self.section
        if not np.any(sec.kind == CONCRETE):
            return sec
        if self.crack_band == "spacing":
            sec = with_crack_spacing_band(sec, self.bar_diameter, self.tension_stiffening)[0]
        if self.plane_strain:
            params = sec.params.copy()
            for n in np.flatnonzero(sec.kind == CONCRETE):
                params[n] = with_plane_strain(params[n])
            sec = replace(sec, params=params)
        return sec

    def strip_options(self) -> dict:
        """Keyword arguments of :class:`ssi.elements.plate.PlateStrip` for this foundation."""
        return {
            "kappa": self.kappa,
            "integration": self.integration,
            "self_weight": self.self_weight,
            "self_bending": self.self_bending,
            "crack_band": "point" if self.crack_band == "point" else None,
        }

    def __post_init__(self):
        x0 = check_real("Foundation.x0", self.x0, unit="m")
        x1 = check_real("Foundation.x1", self.x1, unit="m")
        if not x0 < x1:
            raise ValueError(f"Foundation.x0 must be < x1, got x0={self.x0!r}, x1={self.x1!r}")
        check_instance("Foundation.section", self.section, Section)
        check_real("Foundation.kappa", self.kappa, lo=0.0, hi=1.0, lo_open=True)
        _check_integration("Foundation.integration", self.integration)
        check_real("Foundation.self_weight", self.self_weight, lo=0.0, unit="N/m^2")


@dataclass(frozen=True)
class RigidFooting:
    """A rigid strip footing from ``x0`` to ``x1`` [m] on the ground, without a plate or an interface: the
    soil nodes under it are its base, held at rest (w = 0) until a :class:`Settlement` (``x=None``) moves
    them all by the same w -- a displacement-controlled push, whose reaction is the footing's load
    (:meth:`BuiltScene.contact_force`). ``rough=True``: the base also holds the soil horizontally (u = 0,
    the full adhesion of a rough base); ``rough=False``: smooth, u free (no shear on the base). The
    footing carries a ``Scene.surcharge`` over its own width through that reaction; it takes no other load
    (a column, a strip load or the strip's weight needs a plate :class:`Foundation`) and no ``embedment``.
    """

    rigid: ClassVar[bool] = True  # no plate, no interface: its base nodes are pushed down

    x0: float
    x1: float
    rough: bool = True

    def __post_init__(self):
        x0 = check_real("RigidFooting.x0", self.x0, unit="m")
        x1 = check_real("RigidFooting.x1", self.x1, unit="m")
        if not x0 < x1:
            raise ValueError(f"RigidFooting.x0 must be < x1, got x0={self.x0!r}, x1={self.x1!r}")
        check_bool("RigidFooting.rough", self.rough)


@dataclass(frozen=True)
class Contact:
    """Foundation--soil interface (Coulomb). ``phi_deg=None``: bonded and elastic (never slips or opens).

    Fields: ``kn``, ``kt`` normal and tangential stiffness [Pa/m]; ``phi_deg`` interface friction angle [deg];
    ``c`` adhesion [Pa]; ``psi_deg`` dilation angle [deg] -- the default 0 (slip without dilation) is the
    usual engineering choice for a concrete--soil contact, ``None`` gives the paper's associated rule (psi =
    phi); ``sig_t`` tension cut-off [Pa]; ``rule`` "newton_cotes" or "gauss". ``kt = 0`` on the whole strip
    (frictionless): nothing holds the strip horizontally, so the built scene fixes u of its middle plate node
    (``BuiltScene.slide_support``, zero reaction under vertical loads) and refuses a ``ColumnLoad`` with H.
    """

    kn: float
    kt: float
    phi_deg: float | None = None
    c: float = 0.0
    psi_deg: float | None = 0.0
    sig_t: float | None = None
    rule: str = "newton_cotes"

    def __post_init__(self):
        check_real("Contact.kn", self.kn, lo=0.0, lo_open=True, unit="Pa/m")
        check_real("Contact.kt", self.kt, lo=0.0, unit="Pa/m")
        check_optional_real("Contact.phi_deg", self.phi_deg, lo=0.0, hi=90.0, hi_open=True, unit="degrees")
        check_real("Contact.c", self.c, lo=0.0, allow_inf=True, unit="Pa")
        psi_max = 90.0 if self.phi_deg is None else self.phi_deg
        check_optional_real(
            "Contact.psi_deg",
            self.psi_deg,
            lo=0.0,
            hi=psi_max,
            hi_open=self.phi_deg is None,
            unit="degrees (<= phi_deg)",
        )
        check_optional_real("Contact.sig_t", self.sig_t, lo=0.0, unit="Pa")
        check_choice("Contact.rule", self.rule, ("newton_cotes", "gauss"))
        self.params()  # the interface law's own checks of the combination (sig_t below the apex)

    def params(self) -> np.ndarray:
        if self.phi_deg is None:
            return interface_params(kt=self.kt, kn=self.kn, phi_deg=0.0, c=np.inf, psi_deg=None, sig_t=np.inf)
        return interface_params(
            kt=self.kt, kn=self.kn, phi_deg=self.phi_deg, c=self.c, psi_deg=self.psi_deg, sig_t=self.sig_t
        )


@dataclass(frozen=True)
class ContactSegment:
    """The contact law ``contact`` on the part x0 <= x <= x1 [m] of the strip; segments tile the strip."""

    x0: float
    x1: float
    contact: Contact


@dataclass(frozen=True)
class Excavation:
    """Soil removed in the phase that lists it: every element whose centre lies in ``x0`` < x < ``x1`` [m]
    and ``top`` < depth below the ground < ``bottom`` [m]. The mesh puts element edges on all four sides
    (x0 and x1 become element lines, top and bottom split the layers there). x0 = -width/2 and
    x1 = width/2 remove a whole layer part over the full width. The removed soil's stress and weight (and a
    surcharge on its ground) are released over the phase; below the water table the pit stays flooded to
    the table (the effective-stress formulation: the water in it balances the pore pressure on its faces).
    It may not remove soil under the strip or beside an embedded strip's trench walls."""

    x0: float
    x1: float
    bottom: float
    top: float = 0.0

    def __post_init__(self):
        x0 = check_real("Excavation.x0", self.x0, unit="m")
        if not x0 < check_real("Excavation.x1", self.x1, unit="m"):
            raise ValueError(f"Excavation.x0 must be < x1, got x0={self.x0!r}, x1={self.x1!r}")
        top = check_real("Excavation.top", self.top, lo=0.0, unit="m (depth below the ground)")
        check_real("Excavation.bottom", self.bottom, lo=top, lo_open=True, unit="m (depth, > top)")


@dataclass(frozen=True)
class Phase:
    """One stage of the analysis: ``loads`` added (at full value at the end of the phase), ``factors``
    {name of an earlier phase: factor} rescaling that phase's loads (0 removes them, 1 restores them;
    a Settlement's factor scales its settlement), ``n_steps`` equal increments (None: the ``n_steps`` given to
    ``solve``).

    ``excavate``: :class:`Excavation` regions whose soil this phase removes (the forces the removed soil
    exerted on the rest -- its stress and weight -- fall to zero during the phase). ``drainage``: {index of a
    layer in ``Scene.layers`` (0 = top): "drained" | "undrained_A"} from this phase on (a layer switched to
    undrained starts its excess pore pressure at zero from the phase's first state; switched back to
    drained, its excess pore pressure is released during the phase: full consolidation)."""

    name: str
    loads: tuple = ()
    factors: dict = field(default_factory=dict)
    n_steps: int | None = None
    excavate: tuple = ()
    drainage: dict = field(default_factory=dict)

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise TypeError(f"Phase.name must be a non-empty string, got {self.name!r}")
        _check_list(f"Phase({self.name!r}).loads", list(self.loads), tuple(LOAD_TYPES.values()))
        if not isinstance(self.factors, dict):
            raise TypeError(
                f"Phase({self.name!r}).factors must be a dict {{phase name: factor}}, got "
                f"{type(self.factors).__name__}"
            )
        for key, value in self.factors.items():
            check_real(f"Phase({self.name!r}).factors[{key!r}]", value)
        if self.n_steps is not None:
            check_int(f"Phase({self.name!r}).n_steps", self.n_steps, lo=1)
        _check_list(f"Phase({self.name!r}).excavate", list(self.excavate), Excavation)
        if not isinstance(self.drainage, dict):
            raise TypeError(
                f"Phase({self.name!r}).drainage must be a dict {{layer index: 'drained' | 'undrained_A'}}, "
                f"got {type(self.drainage).__name__}"
            )
        for key, value in self.drainage.items():
            check_int(f"Phase({self.name!r}).drainage key (layer index)", key, lo=0)
            check_choice(f"Phase({self.name!r}).drainage[{key!r}]", value, DRAINAGE)


@dataclass(frozen=True)
class MeshSize:
    """Element size ``h_fine`` [m] under the foundation, ``h_coarse`` [m] far from it, ``growth`` [-] ratio of
    neighbouring sizes, ``n_gauss`` 2 (reduced) or 3 (full) Gauss points per direction, ``end_grading``
    [-] exponent (1 to ``ssi.core.mesh.MAX_END_GRADING``) grading the elements under the foundation towards
    its ends (1: even; see ``ssi.core.mesh.foundation_lines``)."""

    h_fine: float = 0.25
    h_coarse: float = 2.0
    growth: float = 1.25
    n_gauss: int = 2
    end_grading: float = 1.0

    def __post_init__(self):
        h_fine = check_real("MeshSize.h_fine", self.h_fine, lo=0.0, lo_open=True, unit="m")
        if check_real("MeshSize.h_coarse", self.h_coarse, lo=0.0, lo_open=True, unit="m") < h_fine:
            raise ValueError(f"MeshSize.h_coarse must be >= h_fine = {self.h_fine!r}, got {self.h_coarse!r}")
        check_real("MeshSize.growth", self.growth, lo=1.0)
        check_choice("MeshSize.n_gauss", self.n_gauss, (2, 3))
        check_real("MeshSize.end_grading", self.end_grading, lo=1.0, hi=MAX_END_GRADING, unit="-")


CONTACT_SEGMENT_TYPES = (ContactSegment,)


def _check_list(name, value, cls, min_len=0):
    """A list or tuple of ``cls`` objects (a class or a tuple of classes), at least ``min_len`` of them."""
    kinds = " or ".join(c.__name__ for c in (cls if isinstance(cls, tuple) else (cls,)))
    if not isinstance(value, list | tuple):
        raise TypeError(f"{name} must be a list of {kinds}, got {value!r} ({type(value).__name__})")
    if len(value) < min_len:
        raise ValueError(f"{name} must hold at least {min_len} {kinds}, got {value!r}")
    for i, item in enumerate(value):
        check_instance(f"{name}[{i}]", item, cls)


def _check_integration(name, value):
    """A named rule of the plate strip or a pair (n_axial, n_shear) of point counts in 1..3."""
    if isinstance(value, str):
        check_choice(name, value, tuple(INTEGRATIONS))
        return
    if not (isinstance(value, list | tuple) and len(value) == 2):
        raise TypeError(
            f"{name} must be one of {tuple(INTEGRATIONS)} or a pair (n_axial, n_shear), got {value!r}"
        )
    for v in value:
        check_int(f"{name} point count", v, lo=1, hi=3)
