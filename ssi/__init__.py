"""ssi: 2D soil-structure interaction of reinforced concrete shallow foundations (after W. Szajna).

The package is layered by role; each subpackage imports only those before it in this list:

* ``ssi.core`` -- the engine that knows no scene: ``Model``, ``System``, assembly, linear solvers, quadrature,
  shapes, meshes, ``Result``, input validation and the element-group protocol;
* ``ssi.materials`` -- constitutive laws as numba point kernels and their parameter builders;
* ``ssi.elements`` -- the element groups (soil Q8, plate strip with its layered section, interface, spring);
* ``ssi.solver`` -- ``Settings`` and ``run``: the incremental-iterative solution of a model;
* ``ssi.limit`` -- finite-element limit analysis: certified bounds of a collapse load;
* ``ssi.capacity`` -- a scene or a site as a limit-analysis problem: its capacity's and its factor of
  safety's brackets (read through the scene's protocol, never importing ``ssi.scene``);
* ``ssi.scene`` -- a foundation described by its parts (``Scene``, ``Site``), built and solved in stages,
  and the discretisation error of its answer (``estimate``);
* ``ssi.io`` -- result files (HDF5), ParaView export, plots, the command line;
* ``ssi.studies`` -- parameter sweeps over many scenes;
* ``ssi.lab`` -- verification and research tools, never imported by the rest of the package.
"""

import hashlib
import os
from pathlib import Path

__version__ = "0.1.0"

# the subpackages that hold numba kernels (``@njit``): the on-disk cache is keyed on their sources alone
KERNEL_PACKAGES = ("core", "materials", "elements", "solver")


def numba_cache_key(package_dir: Path) -> str:
    """A 16-hex-digit hash of the sources of the kernel subpackages under ``package_dir`` (the folder of this
    file): their relative paths and bytes, in sorted order. A file outside ``KERNEL_PACKAGES`` (a scene, a
    plot, a lab tool) does not enter it, so editing one leaves the compiled kernels valid."""
    digest = hashlib.sha1()
    for name in KERNEL_PACKAGES:
        for path in sorted((package_dir / name).rglob("*.py")):
            digest.update(path.relative_to(package_dir).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _keyed_numba_cache() -> None:
    """Point numba's on-disk cache at a folder named after :func:`numba_cache_key`.

    numba checks a cached kernel against its own file only: a kernel that calls a kernel from another module
    (the Q8 element calling the soil law) would silently keep the old callee after that module changes.
    Keying the whole cache on every kernel source makes any edit of one recompile everything once, and never
    run stale code. Must run before numba is imported (importing ssi first guarantees it).
    """
    here = Path(__file__).resolve().parent
    key = numba_cache_key(here)
    base = Path(os.environ.get("NUMBA_CACHE_DIR") or here.parent / ".numba_cache")
    if base.name != key:
        os.environ["NUMBA_CACHE_DIR"] = str(base / key)


_keyed_numba_cache()
