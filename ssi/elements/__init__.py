"""Element groups: flat arrays and numba kernels, one group per kind of element.

* ``soil_q8`` -- eight-node plane-strain soil elements (``q8_elastic``: their elastic kernels);
* ``plate`` -- the layered plate strip, with its cross-section in ``section`` and the section's
  moment-curvature and M(N) analyses in ``section_analysis``;
* ``interface`` -- six-node contact elements between the strip and the soil;
* ``spring`` -- nodal springs;
* ``supports`` -- builders of hand-made models: soil groups on a mesh, fixed block sides, surface pressures,
  strips on supports.

The array layout they share is written once in ``ssi.core.protocol``.
"""

from .interface import Interface6, add_interface
from .plate import PlateStrip, add_plate_strip
from .section import Section
from .soil_q8 import SoilQ8
from .spring import Spring

__all__ = ["Interface6", "PlateStrip", "Section", "SoilQ8", "Spring", "add_interface", "add_plate_strip"]
