"""The CSR sparsity pattern and scatter maps of ``SparsePattern`` against an independent construction: scipy's
COO -> CSR conversion of every element coupling between free DOFs (duplicates summed, indices sorted). The
comparison is exact (integer index arrays), on meshes small enough to run in well under a second."""

import numpy as np
import pytest
import scipy.sparse as sp

from ssi.core.assembly import SparsePattern
from ssi.core.mesh import structured_q8
from ssi.core.protocol import ElementGroup


def reference_pattern(edofs_list, free):
    """(indptr, indices) of the union of element couplings over the free DOFs, built by scipy."""
    free_of = np.full(free.size, -1)
    free_of[free] = np.arange(np.count_nonzero(free))
    rows, cols = [], []
    for edofs in edofs_list:
        f = free_of[edofs]
        r = np.repeat(f, f.shape[1], axis=1).ravel()
        c = np.tile(f, (1, f.shape[1])).ravel()
        keep = (r >= 0) & (c >= 0)
        rows.append(r[keep])
        cols.append(c[keep])
    n = np.count_nonzero(free)
    m = sp.coo_matrix(
        (np.ones(sum(r.size for r in rows)), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)
    ).tocsr()
    m.sum_duplicates()
    m.sort_indices()
    return m.indptr, m.indices, free_of


def assert_matches_reference(edofs_list, free):
    pattern = SparsePattern(edofs_list, free)
    indptr, indices, free_of = reference_pattern(edofs_list, free)
    np.testing.assert_array_equal(pattern.indptr, indptr)
    np.testing.assert_array_equal(pattern.indices, indices)
    assert pattern.nnz == indices.size
    for edofs, smap in zip(edofs_list, pattern.scatter_maps):
        n_edof = edofs.shape[1]
        assert smap.shape == (edofs.shape[0], n_edof**2)
        row = np.repeat(free_of[edofs], n_edof, axis=1)  # entry (a, b) of element e -> (row, col)
        col = np.tile(free_of[edofs], (1, n_edof))
        coupled = (row >= 0) & (col >= 0)
        assert np.all(smap[~coupled] == -1)
        pos = smap[coupled]
        # each position lies in its row's slice of the CSR arrays and holds its column
        assert np.all((indptr[row[coupled]] <= pos) & (pos < indptr[row[coupled] + 1]))
        np.testing.assert_array_equal(indices[pos], col[coupled])
    return pattern


def q8_edofs(nx, nz, order=None):
    mesh = structured_q8(np.linspace(0.0, 2.0, nx + 1), np.linspace(-1.0, 0.0, nz + 1))
    n_nodes = mesh.xy.shape[0]
    relabel = np.arange(n_nodes) if order is None else order(n_nodes)
    conn = relabel[mesh.conn]
    edofs = np.stack([2 * conn, 2 * conn + 1], axis=-1).reshape(conn.shape[0], -1)
    return mesh, edofs, 2 * n_nodes


def test_one_group_with_supports():
    mesh, edofs, n_dof = q8_edofs(5, 3)
    free = np.ones(n_dof, bool)
    free[2 * mesh.bottom] = free[2 * mesh.bottom + 1] = False
    free[2 * mesh.left] = False
    assert_matches_reference([edofs], free)


def test_shuffled_numbering_and_a_dof_in_no_element():
    rng = np.random.default_rng(3)
    _, edofs, n_dof = q8_edofs(4, 3, order=rng.permutation)
    n_dof += 3  # three extra DOFs, one of them free and in no element (an empty row)
    free = np.ones(n_dof, bool)
    free[rng.choice(n_dof - 3, size=7, replace=False)] = False
    free[-2:] = False
    assert_matches_reference([edofs], free)


def test_groups_of_different_sizes_are_merged():
    """Soil Q8 (16 DOFs), beam-like elements on the surface (2 nodes x 3 DOFs) and interface-like elements
    (4 nodes x 2 DOFs) joining surface nodes to the beam nodes: the union of all couplings."""
    mesh, soil, n_soil = q8_edofs(6, 2)
    surface = mesh.surface
    beam_nodes = n_soil + 3 * np.arange(surface.size)  # 3 DOFs per beam node after the soil DOFs
    beam = np.array([np.r_[beam_nodes[i] + np.arange(3), beam_nodes[i + 1] + np.arange(3)] for i in range(4)])
    interface = np.array(
        [
            [2 * surface[i], 2 * surface[i] + 1, 2 * surface[i + 1], 2 * surface[i + 1] + 1]
            + [beam_nodes[i], beam_nodes[i] + 1, beam_nodes[i + 1], beam_nodes[i + 1] + 1]
            for i in range(4)
        ]
    )
    n_dof = n_soil + 3 * surface.size
    free = np.ones(n_dof, bool)
    free[2 * mesh.bottom] = free[2 * mesh.bottom + 1] = False
    free[beam_nodes[0] + 2] = False  # a rotation fixed at the beam end
    pattern = assert_matches_reference([soil, beam, interface], free)
    assert pattern.indptr.dtype == np.int32 and all(m.dtype == np.int32 for m in pattern.scatter_maps)


@pytest.mark.parametrize("split", [1, 4])
def test_assembly_through_the_maps_matches_dense(split):
    """Random element matrices scattered through the maps give the dense K_ff (sums of at most 4 terms of
    size <= 1: exact up to a few ulps)."""
    mesh, edofs, n_dof = q8_edofs(3, 2)
    free = np.ones(n_dof, bool)
    free[2 * mesh.bottom + 1] = False
    groups = [edofs[:split], edofs[split:]]  # two groups of one element type
    pattern = SparsePattern(groups, free)
    rng = np.random.default_rng(5)
    k_el = [rng.uniform(-1.0, 1.0, (g.shape[0], 16, 16)) for g in groups]
    dense = np.zeros((n_dof, n_dof))
    for g, k in zip(groups, k_el):
        for ed, ke in zip(g, k):
            dense[np.ix_(ed, ed)] += ke
    kff = pattern.matrix(pattern.assemble(k_el)).toarray()
    assert np.abs(kff - dense[np.ix_(free, free)]).max() <= 1e-15 * 8


class _StoredMatrices(ElementGroup):
    """An element group that only offers its stored K0 (as the plate and interface groups do): the base
    class's default ``assemble_elastic_stiffness`` scatters it."""

    def __init__(self, k_el):
        self.k_el = k_el

    def elastic_stiffness(self):
        return self.k_el


@pytest.mark.parametrize("n_gauss", [2, 3])
def test_elastic_assembly_without_element_matrices_is_the_stored_one(n_gauss):
    """K0 assembled element by element straight into the CSR values (``assemble_elastic``) is bit for bit the
    scatter of the stored element matrices: the same per-element arithmetic and the same sums in the same
    order. A group without the direct path is scattered from its stored matrices."""
    from ssi.elements.soil_q8 import SoilQ8
    from ssi.materials.soil_laws import elastic_params

    mesh, edofs, n_dof = q8_edofs(5, 3)
    rng = np.random.default_rng(7)
    coords = mesh.xy[mesh.conn] + rng.uniform(-0.03, 0.03, (mesh.conn.shape[0], 8, 2))
    params = [elastic_params(20e6, 0.3), elastic_params(80e6, 0.25)]
    group = SoilQ8(coords, edofs, np.arange(edofs.shape[0]) % 2, [0, 0], params, n_gauss=n_gauss)
    other = _StoredMatrices(rng.uniform(-1.0, 1.0, (3, 16, 16)))
    free = np.ones(n_dof, bool)
    free[2 * mesh.bottom] = free[2 * mesh.bottom + 1] = False
    pattern = SparsePattern([edofs, edofs[:3]], free)
    stored = pattern.assemble([group.elastic_stiffness(), other.k_el])
    direct = pattern.assemble_elastic([group, other])
    assert np.array_equal(direct, stored)
    assert np.array_equal(pattern.assemble_elastic([group, other], direct), stored)  # reused: zeroed first
