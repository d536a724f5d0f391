"""Factorisations kept across solves and refactorisations (issue 16): the CSR matrices of one pattern share
its index arrays, and a PARDISO handle reused for a refactorisation (numeric phase only) solves as a fresh
SuperLU factorisation does. The reference is SuperLU, an independent code; 1e-10 relative leaves a factor
~1e3 over the round-off of these well-conditioned 1e3-DOF systems (condition ~1e4)."""

import numpy as np
import pytest
import scipy.sparse as sp

from ssi.core.assembly import SparsePattern
from ssi.core.linsolve import SUPERLU_PIVOT_THRESHOLD, Factorization, pardiso_available
from ssi.core.mesh import structured_q8
from ssi.core.model import Model
from ssi.elements.supports import fix_block, soil_group
from ssi.materials.soil_laws import ELASTIC, elastic_params

TOL = 1e-10


def block_system():
    mesh = structured_q8(np.linspace(0, 4, 13), np.linspace(-2, 0, 7))
    model = Model()
    model.add_nodes(mesh.xy, 2)
    g = soil_group(model, mesh, [(ELASTIC, elastic_params(30e6, 0.3))])
    fix_block(model, mesh, sides=False)
    free = model.free_mask()
    return SparsePattern([g.edofs], free), g


def test_matrices_share_the_pattern_index_arrays():
    pattern, g = block_system()
    a = pattern.matrix(pattern.assemble([g.elastic_stiffness()]))
    b = pattern.matrix(pattern.assemble([2.0 * g.elastic_stiffness()]))
    assert a.indices is pattern.indices is b.indices and a.indptr is pattern.indptr is b.indptr
    assert pattern.scatter_maps[0].dtype == np.int32 and pattern.indptr.dtype == np.int32
    x = np.random.default_rng(0).normal(size=pattern.n_free)
    dense = np.zeros((pattern.n_free, pattern.n_free))
    np.add.at(dense, (np.repeat(np.arange(pattern.n_free), np.diff(a.indptr)), a.indices), a.data)
    ref = 2.0 * dense @ x  # K x sums ~18 terms of size |K| |x|: round-off ~1e-15 of max |K| |x|
    assert np.max(np.abs(b @ x - ref)) <= 1e-13 * np.abs(2.0 * dense).max() * np.abs(x).max()


def test_matrix_rejects_data_of_another_pattern():
    pattern, _ = block_system()
    with pytest.raises(ValueError, match="data must be float64"):
        pattern.matrix(np.zeros(pattern.nnz + 1))


@pytest.mark.skipif(not pardiso_available(), reason="pypardiso (MKL) not installed")
@pytest.mark.parametrize("spd, symmetric", [(True, True), (False, True), (False, False)])
def test_pardiso_refactorisation_reuses_the_analysis(spd, symmetric):
    from ssi.core import linsolve

    pattern, g = block_system()
    rhs = np.random.default_rng(1).normal(size=(pattern.n_free, 2))
    first_handle = None
    for scale in (1.0, 3.0, 0.5):  # one pattern, three matrices: analysed once, refactorised twice
        k = pattern.matrix(pattern.assemble([scale * g.elastic_stiffness()]))
        fac = Factorization(k, symmetric, "pardiso", spd=spd)
        handle = fac._solve.__self__
        if scale != 1.0:
            assert handle is first_handle  # the idle analysed handle came back
        first_handle = handle
        ref = Factorization(k, True, "superlu").solve(rhs)
        assert np.max(np.abs(fac.solve(rhs) - ref)) <= TOL * np.max(np.abs(ref))
        del fac
    assert any(h is first_handle for _, h in linsolve._IDLE_HANDLES)


def test_superlu_threshold_pivoting_still_pivots_where_the_diagonal_is_weak():
    """SuperLU keeps diagonal pivots down to SUPERLU_PIVOT_THRESHOLD of a column's largest entry: rows whose
    diagonal is zero or tiny (a saddle-point block, a nearly singular non-associated tangent) must still be
    pivoted off the diagonal and solved to round-off. (Without pivoting -- threshold 0 -- the 1e-13 pivots
    below wreck the solution: checked when this test was written.)"""
    rng = np.random.default_rng(3)
    n = 400
    a = sp.random(n, n, density=0.02, random_state=rng, format="lil") + sp.eye(n) * 2.0
    a = (a + a.T).tolil()  # a symmetric pattern, as the assembled matrices have
    tiny = 1e-13
    assert tiny < 1e-6 * SUPERLU_PIVOT_THRESHOLD  # far below the threshold: these must be pivoted away
    for i in rng.choice(n, 60, replace=False):
        a[i, i] = 0.0 if i % 2 else tiny
        a[i, (i + 1) % n] = 3.0  # a strong off-diagonal partner, nonsymmetric
    a = a.tocsc()
    x_true = rng.standard_normal(n)
    b = a @ x_true
    x = Factorization(a, symmetric=False, backend="superlu").solve(b)
    assert np.linalg.norm(a @ x - b) <= 1e-10 * np.linalg.norm(b)
    cond = np.linalg.cond(a.toarray())
    assert np.linalg.norm(x - x_true) <= 1e-14 * cond * np.linalg.norm(x_true)


def test_superlu_keeps_a_refactorised_patterns_ordering():
    """A tangent refactorised on one pattern is factorised in the ordering of the pattern's first
    factorisation (permuted, natural order): every solve, of one or several right-hand sides, agrees with an
    independent dense solve to round-off, and the kept ordering goes when the pattern does."""
    import gc

    from ssi.core import linsolve

    pattern, g = block_system()
    rng = np.random.default_rng(4)
    k_el = g.elastic_stiffness()
    rhs = rng.normal(size=(pattern.n_free, 2))
    for scale in (1.0, 3.0, 0.5):  # the first factorisation orders the pattern, the next two reuse it
        data = pattern.assemble([scale * k_el])
        data *= 1.0 + 0.01 * rng.uniform(-1.0, 1.0, data.size)  # nonsymmetric values, as non-associated flow
        k = pattern.matrix(data)
        fac = Factorization(k, symmetric=False, backend="superlu")
        ref = np.linalg.solve(k.toarray(), rhs)
        assert np.max(np.abs(fac.solve(rhs) - ref)) <= TOL * np.max(np.abs(ref))
        assert np.max(np.abs(fac.solve(rhs[:, 0]) - ref[:, 0])) <= TOL * np.max(np.abs(ref))
    key = linsolve._pattern_key(k)
    assert linsolve._ORDERINGS[key].source is not None  # the later factorisations took the kept ordering
    del fac, k, pattern, g
    gc.collect()
    assert key not in linsolve._ORDERINGS


def test_lagged_tangent_takes_superlu_and_traps_only_its_first_solve(monkeypatch):
    """A lagged tangent (the controlled path's, kept for many solves) is factorised by SuperLU under "auto"
    even where PARDISO would be taken for a tangent refactorised at every iteration (its solves measured 3.5x
    SuperLU's at 6 k DOFs: linsolve's docstring); only its first solve goes through the C-output trap, and
    every solve agrees with an independent dense solve to round-off (TOL, see the module docstring)."""
    from ssi.core import linsolve

    pattern, g = block_system()
    data = pattern.assemble([g.elastic_stiffness()])
    data *= 1.0 + 0.01 * np.random.default_rng(5).uniform(-1.0, 1.0, data.size)
    k = pattern.matrix(data)
    monkeypatch.setattr(linsolve, "pardiso_available", lambda: True)  # as if the fast extra were installed
    monkeypatch.setattr(linsolve, "AUTO_PARDISO_MIN_DOFS_REFACTORISED", 1)
    assert Factorization(k, symmetric=False, lagged=True).backend == "superlu"
    trapped = []
    trap = linsolve._trap_c_output
    monkeypatch.setattr(linsolve, "_trap_c_output", lambda fn, *a, **kw: trapped.append(fn) or trap(fn, *a))
    fac = Factorization(k, symmetric=False, lagged=True)
    ref = np.linalg.solve(k.toarray(), np.ones(pattern.n_free))
    for _ in range(3):
        assert np.max(np.abs(fac.solve(np.ones(pattern.n_free)) - ref)) <= TOL * np.max(np.abs(ref))
    assert len(trapped) == 2  # the factorisation and the first solve
