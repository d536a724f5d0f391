"""A fixed plate-strip case (two RC sections, both crack-band modes, committed histories in every branch of
the concrete and steel laws) shared by the regression test and the script that stored the kernel's output.

``python tests/plate_regression_case.py`` rewrites ``tests/data/plate_kernel_v0.npz`` -- run it only on the
kernel version whose output is the reference (it was run on main 510b7d3, before the concrete law's constants
were computed once per layer instead of at every layer point).
"""

from pathlib import Path

import numpy as np

from ssi.core.protocol import CONSISTENT, K0_MATRIX
from ssi.elements.plate import PlateStrip
from ssi.elements.section import rc_section
from ssi.materials.layer_laws import CONCRETE, STEEL
from ssi.materials.rc import concrete_params, designer_concrete, steel_params

DATA = Path(__file__).parent / "data" / "plate_kernel_v0.npz"
N_EL = 40
FY, ES = 500e6, 200e9


def section(plane_strain, Gc):
    """A 0.4 m RC strip, 9 concrete layers, bars top and bottom; ``Gc`` None: the designer crushing energy."""
    d = designer_concrete(38e6)
    concrete = concrete_params(
        38e6, d["E0"], d["eps_c"], d["fr"], d["Gf"], 0.1, FY / ES, Gc=Gc, plane_strain=plane_strain
    )
    bars = [(0.05, 1.5e-3), (0.35, 1.5e-3)]
    return rc_section(0.4, bars, (CONCRETE, concrete), (STEEL, steel_params(FY, ES, 2e9)), n_concrete=9)


def strip(plane_strain, Gc, crack_band):
    """(group, u_el) -- elements of random length, displacements that bend them from +-1e-4 to +-0.05 1/m."""
    rng = np.random.default_rng(8 + plane_strain)
    length = rng.uniform(0.1, 0.5, N_EL)
    x0 = np.concatenate([[0.0], np.cumsum(length)[:-1]])
    coords = np.zeros((N_EL, 3, 2))
    coords[:, :, 0] = x0[:, None] + length[:, None] * np.array([0.0, 0.5, 1.0])
    edofs = np.arange(N_EL * 9).reshape(N_EL, 9)
    group = PlateStrip(coords, edofs, section(plane_strain, Gc), crack_band=crack_band)
    kap = rng.choice([1e-4, 1e-3, 1e-2, 5e-2], N_EL) * rng.choice([-1.0, 1.0], N_EL)
    eps0 = rng.uniform(-2e-3, 1e-3, N_EL)
    xs = coords[:, :, 0] - coords[:, :1, 0]
    u_el = np.zeros((N_EL, 9))
    u_el[:, 0::3] = eps0[:, None] * xs  # axial strain
    u_el[:, 2::3] = kap[:, None] * xs  # rotation: curvature kap
    u_el[:, 1::3] = 0.5 * kap[:, None] * xs**2 + rng.normal(0.0, 1e-4, (N_EL, 3))  # w: shear strains
    return group, u_el


def committed(group, u_el):
    """A history from a larger state: the current one then unloads, reloads or goes on."""
    state0 = group.initial_state()
    _, _, state = group.evaluate(1.5 * u_el[::-1], None, state0, CONSISTENT)
    return state


def outputs():
    """{name: array} for K0 and consistent tangents, from the virgin and a committed history."""
    out = {}
    for tag, plane_strain, Gc, band in (("a", False, None, "point"), ("b", True, 0.0, None)):
        group, u_el = strip(plane_strain, Gc, band)
        for hist, state in (("virgin", group.initial_state()), ("committed", committed(group, u_el))):
            for flag, t in ((K0_MATRIX, "k0"), (CONSISTENT, "consistent")):
                f, k, new = group.evaluate(u_el, None, state, flag)
                key = f"{tag}_{hist}_{t}"
                out[f"f_{key}"], out[f"k_{key}"], out[f"state_{key}"] = f, k, new
    return out


if __name__ == "__main__":
    DATA.parent.mkdir(exist_ok=True)
    np.savez_compressed(DATA, **outputs())
    print(f"wrote {DATA}")
