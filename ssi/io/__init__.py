"""What leaves the computation: result files (``results``: HDF5, written atomically), ParaView export
(``export``), the standard figures (``plot``) and the command line (``cli``: ``ssi run scene.toml``)."""

from .results import read_result, write_result

__all__ = ["read_result", "write_result"]
