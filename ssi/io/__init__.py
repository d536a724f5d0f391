"""What leaves the computation: result files (``results``: HDF5, written atomically, of a scene, a site or a
bare model; ``results_limit``: of a limit analysis), ParaView export (``export``), the standard figures
(``plot``, a scene's or a site's), the HTML run report (``report``) and the command line (``cli``:
``ssi run | show | limit`` of a scene or a site file)."""

from .results import read_result, write_result

__all__ = ["read_result", "write_result"]
