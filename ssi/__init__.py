"""ssi: 2D soil-structure interaction of reinforced concrete shallow foundations (after W. Szajna).

Element groups (``ssi.elements``) hold flat arrays and numba kernels; ``ssi.model.Model`` collects a scene;
``ssi.solver.run`` follows a load path with (modified) Newton--Raphson; ``ssi.results`` writes HDF5.
"""

import hashlib
import os
from pathlib import Path

__version__ = "0.1.0"


def _keyed_numba_cache():
    """Point numba's on-disk cache at a folder named after a hash of this package's sources.

    numba checks a cached kernel against its own file only: a kernel that calls a kernel from another module
    (the Q8 element calling the soil law) would silently keep the old callee after that module changes.
    Keying the whole cache on all sources makes any edit recompile everything once, and never run stale
    code. Must run before numba is imported (importing ssi first guarantees it).
    """
    here = Path(__file__).resolve().parent
    digest = hashlib.sha1()
    for path in sorted(here.rglob("*.py")):
        digest.update(path.relative_to(here).as_posix().encode())
        digest.update(path.read_bytes())
    key = digest.hexdigest()[:16]
    base = Path(os.environ.get("NUMBA_CACHE_DIR") or here.parent / ".numba_cache")
    if base.name != key:
        os.environ["NUMBA_CACHE_DIR"] = str(base / key)


_keyed_numba_cache()
