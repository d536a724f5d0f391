"""Compile every numba kernel once, right after installing (``make`` runs this), so that a user's first
scene, the tests and the chapters load cached machine code instead of compiling it (15–80 s otherwise).

Runs small versions of the paths users take: the README scene (soil, plate, interface kernels, the default
solver), a Mohr–Coulomb footing pushed to failure (full Newton with the consistent tangent), a linear solve
of an elastic block (the K0 kernel, assembly), an RC section's moment-curvature (both section analyses).
Prints the wall time as ``warm_cache_s: N``.
"""

import re
import time
from pathlib import Path

t0 = time.perf_counter()
import ssi  # noqa: E402, F401  (first: keys numba's cache on the package sources)

ROOT = Path(__file__).resolve().parent.parent


def main():
    from ssi.lab.bearing_capacity import chapter10_footing, push_footing
    from ssi.solver.progress import announce_compilation

    announce_compilation()
    code = re.search(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.DOTALL).group(1)
    code = code.replace("print(", "(")  # quiet
    exec(compile(code, "README.md", "exec"), {"__name__": "warm"})  # noqa: S102
    scene = chapter10_footing(  # coarse: it only compiles the kernels
        psi_deg=0.0, half_width=5.0, h_fine=1.0, h_coarse=2.0, growth=1.5, settle=0.02
    )
    push_footing(scene, n_steps=2)
    import numpy as np

    from ssi.core.mesh import structured_q8
    from ssi.core.model import Model
    from ssi.elements.supports import fix_block, soil_group
    from ssi.materials.soil_laws import ELASTIC, elastic_params

    mesh = structured_q8(np.linspace(0.0, 2.0, 3), np.linspace(-1.0, 0.0, 2))
    m = Model()
    m.add_nodes(mesh.xy, 2)
    soil_group(m, mesh, [(ELASTIC, elastic_params(1e7, 0.3))])
    fix_block(m, mesh, sides=False)
    m.add_load(mesh.surface, "w", -1.0)
    m.solve_linear()
    from ssi.elements.section_analysis import layer_free_moment_curvature, moment_curvature
    from ssi.lab.examples import chapter11_section

    moment_curvature(chapter11_section(), 0.01, 4)
    layer_free_moment_curvature(chapter11_section(), np.array([0.0, 1e-3]))
    warm_soil_law_kernels()
    warm_pardiso_kernels(m)
    print(f"warm_cache_s: {time.perf_counter() - t0:.1f}")


def warm_pardiso_kernels(model):
    """The kernels that hand a pattern to PARDISO (the scenes above are small enough for SuperLU)."""
    from ssi.core.linsolve import Factorization, pardiso_available
    from ssi.core.model import System

    if not pardiso_available():
        return
    system = System(model)
    k0 = system.pattern.matrix(system.pattern.assemble_elastic(model.groups))
    for spd, symmetric in ((True, True), (False, False)):
        Factorization(k0, symmetric, "pardiso", spd=spd)


def warm_soil_law_kernels():
    """The soil kernel is compiled per set of laws a group uses (``q8_kernel_for``): besides the sets the
    scenes above use (elastic; Mohr-Coulomb with elastic layers), the chapters and tests use von Mises, the
    explicit Mohr-Coulomb scheme and tables of every law -- compile those here too."""
    import numpy as np

    from ssi.elements.soil_q8 import SoilQ8
    from ssi.materials.soil_laws import (
        elastic_params,
        material_table,
        mohr_coulomb_params,
        von_mises_params,
    )

    elastic = (0, elastic_params(1e7, 0.3))
    tables = [
        [von_mises_params(1e7, 0.3, 1e4)],
        [mohr_coulomb_params(1e7, 0.3, 1e4, 20.0, scheme="explicit")],
        [elastic, mohr_coulomb_params(1e7, 0.3, 1e4, 20.0), von_mises_params(1e7, 0.3, 1e4)]
        + [mohr_coulomb_params(1e7, 0.3, 1e4, 20.0, scheme="explicit")],
    ]
    ref = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], float)
    for materials in tables:
        kinds, params = material_table(materials)
        group = SoilQ8(ref[None], np.arange(16).reshape(1, 16), 0, kinds, params)
        zero = np.zeros((1, 16))
        group.evaluate(zero, zero, group.initial_state(), 1)


if __name__ == "__main__":
    main()
