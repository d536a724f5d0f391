"""Global assembly into a CSR matrix whose sparsity pattern is computed once per mesh.

Dirichlet conditions are applied by *elimination*: the pattern is built over the free DOFs only and every
element entry that touches a constrained DOF is skipped by the scatter map (index -1). The matrix therefore is
K_ff itself, and its factorisation stays valid for every iteration of modified Newton--Raphson; prescribed
displacements enter through the residual, r_f = F_ext,f - F_int,f(u), with u already holding the prescribed
values.

Layout: ``scatter`` is (n_el, n_edof * n_edof) int32/int64, row-major over the element matrix, holding the
position of each entry in the CSR ``data`` array (or -1).
"""

import numpy as np
import scipy.sparse as sp
from numba import njit


@njit(cache=True)
def _incidence(dofs, el_ptr, free_of, n_free):
    """CSR incidence free DOF -> elements holding it: for each, the element ``e`` and the position ``k`` of
    the DOF in the flat element-DOF list (its local index is ``k - el_ptr[e]``)."""
    count = np.zeros(n_free + 1, np.int64)
    for k in range(dofs.size):
        f = free_of[dofs[k]]
        if f >= 0:
            count[f + 1] += 1
    for i in range(n_free):
        count[i + 1] += count[i]
    inc_el = np.empty(count[n_free], np.int64)
    inc_entry = np.empty(count[n_free], np.int64)
    fill = count[:-1].copy()
    for e in range(el_ptr.size - 1):
        for k in range(el_ptr[e], el_ptr[e + 1]):
            f = free_of[dofs[k]]
            if f >= 0:
                inc_el[fill[f]] = e
                inc_entry[fill[f]] = k
                fill[f] += 1
    return count, inc_el, inc_entry


@njit(cache=True)
def _same_elements(inc_ptr, inc_el, row):
    """Whether free DOF ``row`` lies in the same elements as ``row - 1`` (the DOFs of one node do): then both
    rows have the same columns."""
    if row == 0 or inc_ptr[row + 1] - inc_ptr[row] != inc_ptr[row] - inc_ptr[row - 1]:
        return False
    shift = inc_ptr[row] - inc_ptr[row - 1]
    for k in range(inc_ptr[row], inc_ptr[row + 1]):
        if inc_el[k] != inc_el[k - shift]:
            return False
    return True


@njit(cache=True)
def _pattern(dofs, el_ptr, free_of, n_free, inc_ptr, inc_el):
    """Row pointers and sorted column indices of the union of element couplings over the free DOFs.

    Two passes over each row's elements and no sort: the first counts the row's distinct columns, the second
    appends the row to the list of each of its columns. The couplings are symmetric (row i holds column j iff
    row j holds column i), so visiting the rows in increasing order fills every list in increasing order. A
    row in the same elements as the row before it reuses that row's columns instead of visiting them."""
    marker = np.full(n_free, -1, np.int64)
    indptr = np.zeros(n_free + 1, np.int64)
    for row in range(n_free):
        if _same_elements(inc_ptr, inc_el, row):
            indptr[row + 1] = 2 * indptr[row] - indptr[row - 1]
            continue
        n = 0
        for k in range(inc_ptr[row], inc_ptr[row + 1]):
            e = inc_el[k]
            for b in range(el_ptr[e], el_ptr[e + 1]):
                col = free_of[dofs[b]]
                if col >= 0 and marker[col] != row:
                    marker[col] = row
                    n += 1
        indptr[row + 1] = indptr[row] + n
    indices = np.empty(indptr[n_free], np.int32)
    fill = indptr[:-1].copy()
    marker[:] = -1
    cols = np.empty(max_row_length(indptr), np.int64)  # the columns of the last row visited
    n = 0
    for row in range(n_free):
        if not _same_elements(inc_ptr, inc_el, row):
            n = 0
            for k in range(inc_ptr[row], inc_ptr[row + 1]):
                e = inc_el[k]
                for b in range(el_ptr[e], el_ptr[e + 1]):
                    col = free_of[dofs[b]]
                    if col >= 0 and marker[col] != row:
                        marker[col] = row
                        cols[n] = col
                        n += 1
        for j in range(n):
            col = cols[j]
            indices[fill[col]] = row
            fill[col] += 1
    return indptr, indices


@njit(cache=True)
def max_row_length(indptr):
    longest = 0
    for row in range(indptr.size - 1):
        longest = max(longest, indptr[row + 1] - indptr[row])
    return longest


@njit(cache=True)
def _scatter_map(dofs, el_ptr, smap_ptr, free_of, indptr, indices, inc_ptr, inc_el, inc_entry, smap):
    """Fill the flat scatter map ``smap`` (element e's n_e x n_e block, row-major, at ``smap_ptr[e]``) with
    CSR data positions, -1 where the row or the column is constrained. Row by row: the row's columns are
    spread into a position table once, then every element holding the row reads its block row from it; a row
    with the same columns as the row before it shifts that row's block rows instead."""
    for e in range(el_ptr.size - 1):  # rows of constrained DOFs are not in the incidence
        n_e = el_ptr[e + 1] - el_ptr[e]
        for a in range(n_e):
            if free_of[dofs[el_ptr[e] + a]] < 0:
                smap[smap_ptr[e] + a * n_e : smap_ptr[e] + (a + 1) * n_e] = -1
    position = np.empty(free_of.size, np.int64)  # free_of.size >= n_free: any free column fits
    for row in range(indptr.size - 1):
        if _same_elements(inc_ptr, inc_el, row):
            shift = indptr[row] - indptr[row - 1]
            back = inc_ptr[row] - inc_ptr[row - 1]
            for k in range(inc_ptr[row], inc_ptr[row + 1]):
                e = inc_el[k]
                lo = el_ptr[e]
                n_e = el_ptr[e + 1] - lo
                out = smap_ptr[e] + (inc_entry[k] - lo) * n_e
                prev = smap_ptr[e] + (inc_entry[k - back] - lo) * n_e
                for b in range(n_e):
                    p = smap[prev + b]
                    smap[out + b] = p + shift if p >= 0 else -1
            continue
        for p in range(indptr[row], indptr[row + 1]):
            position[indices[p]] = p
        for k in range(inc_ptr[row], inc_ptr[row + 1]):
            e = inc_el[k]
            lo = el_ptr[e]
            n_e = el_ptr[e + 1] - lo
            out = smap_ptr[e] + (inc_entry[k] - lo) * n_e
            for b in range(n_e):
                col = free_of[dofs[lo + b]]
                smap[out + b] = position[col] if col >= 0 else -1


@njit(cache=True)
def scatter_matrix(smap, k_el, data):
    """Add element matrices ``k_el`` (n_el, n_edof, n_edof) into CSR ``data`` through ``smap``."""
    n_el, n_edof = k_el.shape[0], k_el.shape[1]
    for e in range(n_el):
        for a in range(n_edof):
            for b in range(n_edof):
                p = smap[e, a * n_edof + b]
                if p >= 0:
                    data[p] += k_el[e, a, b]


@njit(cache=True)
def scatter_vector(edofs, f_el, out):
    """Add element vectors ``f_el`` (n_el, n_edof) into the global vector ``out``."""
    n_el, n_edof = edofs.shape
    for e in range(n_el):
        for a in range(n_edof):
            out[edofs[e, a]] += f_el[e, a]


@njit(cache=True)
def gather_vector(edofs, u, out):
    """Gather the global vector ``u`` into element vectors ``out`` (n_el, n_edof)."""
    n_el, n_edof = edofs.shape
    for e in range(n_el):
        for a in range(n_edof):
            out[e, a] = u[edofs[e, a]]


class SparsePattern:
    """CSR pattern of K_ff over the free DOFs of several element groups, with one scatter map per group.

    Parameters
    ----------
    edofs_list : list of (n_el, n_edof) int arrays, one per element group
    free : (n_dof,) bool mask of free DOFs
    """

    def __init__(self, edofs_list, free):
        free = np.asarray(free, dtype=bool)
        self.n_dof = free.size
        self.free_dofs = np.flatnonzero(free)
        self.n_free = self.free_dofs.size
        self.free_of = np.full(self.n_dof, -1, np.int64)
        self.free_of[self.free_dofs] = np.arange(self.n_free)
        # every group's element-DOF lists in one flat array: one pass over all groups builds the union
        edofs_list = [np.ascontiguousarray(ed, np.int64) for ed in edofs_list]
        if len(edofs_list) == 1:
            dofs = edofs_list[0].ravel()  # a view: one group needs no copy
        else:
            dofs = np.concatenate([ed.ravel() for ed in edofs_list] + [np.zeros(0, np.int64)])
        sizes = [np.full(ed.shape[0], ed.shape[1], np.int64) for ed in edofs_list]
        n_per_el = np.concatenate(sizes) if sizes else np.zeros(0, np.int64)
        el_ptr = np.zeros(n_per_el.size + 1, np.int64)
        np.cumsum(n_per_el, out=el_ptr[1:])
        smap_ptr = np.zeros(n_per_el.size + 1, np.int64)
        np.cumsum(n_per_el**2, out=smap_ptr[1:])
        inc_ptr, inc_el, inc_entry = _incidence(dofs, el_ptr, self.free_of, self.n_free)
        indptr, self.indices = _pattern(dofs, el_ptr, self.free_of, self.n_free, inc_ptr, inc_el)
        self.nnz = int(indptr[-1])
        # int32 row pointers and scatter maps where the entries fit (half the memory of int64; the CSR
        # matrices built on this pattern then share its index arrays instead of casting a copy each time)
        index_dtype = np.int32 if self.nnz < np.iinfo(np.int32).max else np.int64
        self.indptr = indptr.astype(index_dtype)
        if index_dtype == np.int64:
            self.indices = self.indices.astype(np.int64)
        smap = np.empty(smap_ptr[-1], index_dtype)
        _scatter_map(
            dofs, el_ptr, smap_ptr, self.free_of, indptr, self.indices, inc_ptr, inc_el, inc_entry, smap
        )
        # one (n_el, n_edof * n_edof) view per group into the flat map
        self.scatter_maps, start = [], 0
        for ed in edofs_list:
            size = ed.shape[0] * ed.shape[1] ** 2
            self.scatter_maps.append(smap[start : start + size].reshape(ed.shape[0], ed.shape[1] ** 2))
            start += size

    def new_data(self):
        return np.zeros(self.nnz)

    def matrix(self, data):
        """scipy CSR matrix K_ff sharing ``data`` and this pattern's index arrays (no copies: a solver can
        recognise the pattern by their identity and keep its symbolic analysis)."""
        if data.shape != (self.nnz,) or data.dtype != np.float64:
            raise ValueError(f"data must be float64 of shape ({self.nnz},), got {data.dtype} {data.shape}")
        m = sp.csr_matrix((self.n_free, self.n_free))  # scipy's constructor would copy the index arrays
        m.data, m.indices, m.indptr = data, self.indices, self.indptr
        m.has_sorted_indices = True  # sorted by construction
        return m

    def assemble(self, k_el_list, data=None):
        """Assemble the element matrices of every group into ``data`` (reused if given)."""
        if data is None:
            data = self.new_data()
        else:
            data[:] = 0.0
        for smap, k_el in zip(self.scatter_maps, k_el_list):
            scatter_matrix(smap, k_el, data)
        return data
