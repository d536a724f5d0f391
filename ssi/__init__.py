"""ssi: 2D soil-structure interaction of reinforced concrete shallow foundations (after W. Szajna).

Element groups (``ssi.elements``) hold flat arrays and numba kernels; ``ssi.model.Model`` collects a scene;
``ssi.solver.run`` follows a load path with (modified) Newton--Raphson; ``ssi.results`` writes HDF5.
"""

__version__ = "0.1.0"
