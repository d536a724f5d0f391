"""A fixed soil-kernel case (distorted Q8 elements, every soil law, stress states around yield) shared by the
regression test and the script that stored the kernels' output before the allocation-free rewrite.

``python tests/kernel_regression_case.py`` rewrites ``tests/data/soil_kernel_v0.npz`` -- run it only on the
kernel version whose output is the reference (it was run on main 08e0f11, before issue 16's rewrite).
"""

from pathlib import Path

import numpy as np

from ssi.core.protocol import CONSISTENT, FORCES_ONLY, K0_MATRIX
from ssi.elements.soil_q8 import SoilQ8
from ssi.materials.soil_laws import elastic_params, material_table, mohr_coulomb_params, von_mises_params

DATA = Path(__file__).parent / "data" / "soil_kernel_v0.npz"
N_EL = 120


def case(n_gauss):
    """(group, du_el, state_old) with seeded random geometry, increments and initial stresses."""
    rng = np.random.default_rng(16 + n_gauss)
    ref = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], float)
    corners = ref[:4] + rng.uniform(-0.25, 0.25, (N_EL, 4, 2))
    mids = 0.5 * (corners + np.roll(corners, -1, axis=1))
    coords = np.concatenate([corners, mids], axis=1) * rng.uniform(0.2, 2.0, (N_EL, 1, 1))
    materials = [
        (0, elastic_params(20e6, 0.3)),
        mohr_coulomb_params(20e6, 0.3, 10e3, 20.0),  # associated
        mohr_coulomb_params(20e6, 0.3, 10e3, 30.0, psi_deg=0.0),  # non-associated
        mohr_coulomb_params(20e6, 0.25, 5e3, 25.0, 5.0, scheme="explicit", n_sub=3, drift=True),
        mohr_coulomb_params(20e6, 0.3, 8e3, 20.0, scheme="explicit"),
        von_mises_params(20e6, 0.45, 30e3),
    ]
    kinds, params = material_table(materials)
    el_mat = np.arange(N_EL) % len(kinds)
    edofs = np.arange(N_EL * 16).reshape(N_EL, 16)
    group = SoilQ8(coords, edofs, el_mat, kinds, params, n_gauss=n_gauss)
    du_el = rng.normal(0.0, 1e-3, (N_EL, 16)) * rng.choice([0.1, 1.0, 4.0], (N_EL, 1))
    state = group.initial_state()
    n_ip = state.shape[1]
    p = rng.uniform(-200e3, 5e3, (N_EL, n_ip))  # mean stress, some points near the apex (tension)
    state[:, :, 0] = p + rng.normal(0, 30e3, (N_EL, n_ip))
    state[:, :, 1] = p + rng.normal(0, 30e3, (N_EL, n_ip))
    state[:, :, 2] = rng.normal(0, 20e3, (N_EL, n_ip))
    state[:, :, 3] = p
    return group, du_el, state


def outputs():
    """{name: array} of forces, tangents (-1 forces only, 0 elastic D, 1 consistent) and new states."""
    out = {}
    for n_gauss in (2, 3):
        group, du_el, state = case(n_gauss)
        for tangent in (FORCES_ONLY, K0_MATRIX, CONSISTENT):  # tags t0, t1, t2 (flag + 1)
            f, k, new = group.evaluate(du_el, du_el, state, tangent)
            tag = f"g{n_gauss}_t{tangent + 1}"
            out[f"f_{tag}"] = f
            out[f"state_{tag}"] = new
            if k is not None:
                out[f"k_{tag}"] = k
    return out


if __name__ == "__main__":
    np.savez_compressed(DATA, **outputs())
    print(f"wrote {DATA}")
