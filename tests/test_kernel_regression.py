"""The allocation-free soil kernels (issue 16) give the same numbers as the kernels they replaced.

``tests/data/soil_kernel_v0.npz`` holds the forces, element matrices and new states that the kernels of main
08e0f11 (before the rewrite: shape functions per point, temporary arrays per point) computed for the fixed
case of ``tests/kernel_regression_case.py``: every soil law, both Gauss rules, all three tangent flags, points
in every return branch. The rewrite changes where intermediate values live, not the arithmetic, so the outputs
must agree bit for bit; the comparison allows 1e-14 relative in case a compiler reorders a sum.

``tests/data/plate_kernel_v0.npz`` does the same for the plate strip (``tests/plate_regression_case.py``,
stored at main 510b7d3): its concrete law now takes constants computed once per layer, by the same
expressions, instead of at every layer point.
"""

import os
import textwrap
from pathlib import Path

import numpy as np
import plate_regression_case
import pytest
from kernel_regression_case import DATA, outputs

TOL = 1e-14


@pytest.fixture(scope="module")
def stored():
    return dict(np.load(DATA))


@pytest.fixture(scope="module")
def current():
    return outputs()


def test_same_outputs_as_the_stored_kernel(stored, current):
    assert set(stored) == set(current)
    for key, ref in stored.items():
        new = current[key]
        scale = np.abs(ref).max()
        assert scale > 0.0, key
        assert np.max(np.abs(new - ref)) <= TOL * scale, key


def test_plate_kernel_gives_the_stored_outputs():
    stored = dict(np.load(plate_regression_case.DATA))
    current = plate_regression_case.outputs()
    assert set(stored) == set(current)
    for key, ref in stored.items():
        scale = np.abs(ref).max()
        assert scale > 0.0, key
        assert np.max(np.abs(current[key] - ref)) <= TOL * scale, key


def test_plate_case_reaches_every_branch_of_the_layer_laws():
    from ssi.materials.concrete import P_E0, P_EPS_CU, P_FR
    from ssi.materials.layer_laws import CONCRETE, STEEL

    stored = dict(np.load(plate_regression_case.DATA))
    for tag, plane_strain, gc in (("a", False, None), ("b", True, 0.0)):
        s = plate_regression_case.section(plane_strain, gc)
        prm = s.params[s.kind == CONCRETE][0]
        state = stored[f"state_{tag}_committed_consistent"]
        x_max, e_max = state[..., s.kind == CONCRETE, 0], state[..., s.kind == CONCRETE, 1]
        assert (x_max == 0.0).any() and (x_max > 0.0).any() and (x_max >= prm[P_EPS_CU]).any(), tag
        assert (e_max <= prm[P_FR] / prm[P_E0]).any() and (e_max > prm[P_FR] / prm[P_E0]).any(), tag
        yielded = state[..., s.kind == STEEL, 0] != 0.0
        assert yielded.any() and not yielded.all(), tag


def test_case_covers_every_return_branch(stored):
    # hist[1] of the new states: 0 elastic, 1 plane, 2 and 3 edges, 4 apex -- all reached
    branches = set(np.unique(stored["state_g2_t2"][:, :, 5]).astype(int))
    assert {0, 1, 2, 3, 4} <= branches


@pytest.mark.parametrize("laws", [(0,), (0, 1), (0, 3), (0, 1, 3), (0, 2)])
def test_law_specialised_kernels_give_the_stored_outputs(stored, laws):
    """A group whose table holds only some laws runs a kernel compiled for those laws alone
    (``q8_kernel_for``): on the elements of those laws it must reproduce the stored outputs bit for bit.
    Without the explicit law (2) the point loop is compiled without reference counting: those cases check
    that this changes no number either."""
    from kernel_regression_case import case

    from ssi.elements.soil_q8 import SoilQ8, q8_kernel, q8_kernel_for
    from ssi.materials.soil_laws import laws_used

    for n_gauss in (2, 3):
        full, du_el, state = case(n_gauss)
        mats = np.flatnonzero(np.isin(full.kinds, laws))
        sel = np.flatnonzero(np.isin(full.el_mat, mats))
        el_mat = np.searchsorted(mats, full.el_mat[sel])
        group = SoilQ8(
            full.coords[sel], full.edofs[sel], el_mat, full.kinds[mats], full.params[mats], n_gauss
        )
        assert group.kernel is q8_kernel_for(*laws_used(laws)) and group.kernel is not q8_kernel
        for tangent in (-1, 0, 1):
            f, k, new = group.evaluate(du_el[sel], du_el[sel], state[sel], tangent)
            tag = f"g{n_gauss}_t{tangent + 1}"
            for name, value in (("f", f), ("state", new), ("k", k)):
                if value is None:
                    continue
                ref = stored[f"{name}_{tag}"][sel]
                assert np.max(np.abs(value - ref)) <= TOL * np.abs(ref).max(), (laws, name, tag)


def test_loops_without_reference_counting_compile_first_in_a_fresh_process(tmp_path):
    """The soil (elastic, Mohr-Coulomb, von Mises), plate and interface loops are compiled without numba's
    runtime, and numba compiles the functions they call with that same setting: a callee that allocates fails
    to compile there, but only when no earlier call in the process compiled it with the runtime. A process
    with an empty cache that calls those kernels first is the order where such a callee would show. A second
    process on the same cache must then compile nothing (a compiled function holding another as a closure
    constant is not found in the cache: it was compiled again in every process)."""
    import subprocess
    import sys

    code = textwrap.dedent("""
        import numpy as np
        import ssi
        from kernel_regression_case import case
        from ssi.elements.plate import PlateStrip
        from ssi.materials import rc
        from ssi.materials.layer_laws import CONCRETE, STEEL
        from ssi.elements.section import paper_rc_section
        for laws in ((0,), (0, 1), (0, 3), (0, 1, 3)):
            full, du, state = case(2)
            sel = np.flatnonzero(np.isin(full.kinds[full.el_mat], laws))
            mats = np.flatnonzero(np.isin(full.kinds, laws))
            group = type(full)(full.coords[sel], full.edofs[sel], np.searchsorted(mats, full.el_mat[sel]),
                               full.kinds[mats], full.params[mats])
            for tangent in (-1, 0, 1):
                group.evaluate(du[sel], du[sel], state[sel], tangent)
        conc = rc.concrete_params(fc=30e6, E0=30e9, eps_c=0.002, fr=3e6, Gf=100.0, ls=0.1, eps_y=2.5e-3)
        steel = rc.steel_params(fy=500e6, Es=200e9, EH=2e9)
        section = paper_rc_section(0.5, 0.05, 1.5e-3, 0.8e-3, (CONCRETE, conc), (STEEL, steel))
        xy = np.array([[[0.0, 0.0], [0.25, 0.0], [0.5, 0.0]]])
        strip = PlateStrip(xy, np.arange(9)[None], section)
        u = np.linspace(0.0, 1e-3, 9)[None]
        for tangent in (-1, 0, 1):
            strip.evaluate(u, u, strip.initial_state(), tangent)
        from ssi.elements.interface import Interface6
        from ssi.materials.interface_law import interface_params
        line = np.array([[0.0, 0.0], [0.25, 0.0], [0.5, 0.0]])
        contact = Interface6(np.concatenate([line, line])[None], np.arange(12)[None],
                             interface_params(1e8, 1e9, c=0.0, phi_deg=30.0))
        du = np.array([[1e-3, -1e-4] * 3 + [0.0, 0.0] * 3])
        for tangent in (0, 1):
            contact.evaluate(du, du, contact.initial_state(), tangent)
        print("compiled")
    """)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), PYTHONPATH=str(Path(__file__).parent))
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert run.returncode == 0 and "compiled" in run.stdout, run.stderr[-3000:]
    env["NUMBA_DEBUG_CACHE"] = "1"
    again = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert again.returncode == 0, again.stderr[-3000:]
    saved = [line for line in again.stdout.splitlines() if "data saved" in line]
    assert "data loaded" in again.stdout and not saved, saved
