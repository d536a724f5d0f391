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
def _dof_to_elements(edofs, free_of, n_free):
    """CSR incidence (free DOF -> elements touching it)."""
    n_el, n_edof = edofs.shape
    count = np.zeros(n_free + 1, np.int64)
    for e in range(n_el):
        for a in range(n_edof):
            f = free_of[edofs[e, a]]
            if f >= 0:
                count[f + 1] += 1
    for i in range(n_free):
        count[i + 1] += count[i]
    elems = np.empty(count[n_free], np.int64)
    fill = count[:-1].copy()
    for e in range(n_el):
        for a in range(n_edof):
            f = free_of[edofs[e, a]]
            if f >= 0:
                elems[fill[f]] = e
                fill[f] += 1
    return count, elems


@njit(cache=True)
def _insertion_sort(a, lo, hi):
    for i in range(lo + 1, hi):
        key = a[i]
        j = i - 1
        while j >= lo and a[j] > key:
            a[j + 1] = a[j]
            j -= 1
        a[j + 1] = key


@njit(cache=True)
def _pattern(edofs, free_of, n_free, inc_ptr, inc_el):
    """Row pointers and sorted column indices of the union of element couplings over free DOFs."""
    n_edof = edofs.shape[1]
    marker = np.full(n_free, -1, np.int64)
    indptr = np.zeros(n_free + 1, np.int64)
    for row in range(n_free):
        n = 0
        for k in range(inc_ptr[row], inc_ptr[row + 1]):
            e = inc_el[k]
            for b in range(n_edof):
                col = free_of[edofs[e, b]]
                if col >= 0 and marker[col] != row:
                    marker[col] = row
                    n += 1
        indptr[row + 1] = indptr[row] + n
    indices = np.empty(indptr[n_free], np.int32)
    marker[:] = -1
    for row in range(n_free):
        pos = indptr[row]
        for k in range(inc_ptr[row], inc_ptr[row + 1]):
            e = inc_el[k]
            for b in range(n_edof):
                col = free_of[edofs[e, b]]
                if col >= 0 and marker[col] != row:
                    marker[col] = row
                    indices[pos] = col
                    pos += 1
        _insertion_sort(indices, indptr[row], indptr[row + 1])
    return indptr, indices


@njit(cache=True)
def _scatter_map(edofs, free_of, indptr, indices, smap):
    """Fill ``smap`` (n_el, n_edof * n_edof), int32 or int64, with CSR data positions (-1: constrained)."""
    n_el, n_edof = edofs.shape
    smap[:, :] = -1
    for e in range(n_el):
        for a in range(n_edof):
            row = free_of[edofs[e, a]]
            if row < 0:
                continue
            for b in range(n_edof):
                col = free_of[edofs[e, b]]
                if col < 0:
                    continue
                lo = indptr[row]
                hi = indptr[row + 1] - 1
                while lo < hi:  # binary search for col in the sorted row
                    mid = (lo + hi) // 2
                    if indices[mid] < col:
                        lo = mid + 1
                    else:
                        hi = mid
                smap[e, a * n_edof + b] = lo


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
        # all groups' couplings are merged by concatenating padded edofs per group
        ptrs, cols = [], []
        for edofs in edofs_list:
            ptr, col = self._group_pattern(np.ascontiguousarray(edofs, np.int64))
            ptrs.append(ptr)
            cols.append(col)
        indptr, self.indices = self._merge(ptrs, cols)
        self.nnz = int(indptr[-1])
        # int32 row pointers and scatter maps where the entries fit (half the memory of int64; the CSR
        # matrices built on this pattern then share its index arrays instead of casting a copy each time)
        index_dtype = np.int32 if self.nnz < np.iinfo(np.int32).max else np.int64
        self.indptr = indptr.astype(index_dtype)
        if index_dtype == np.int64:
            self.indices = self.indices.astype(np.int64)
        self.scatter_maps = []
        for ed in edofs_list:
            ed = np.ascontiguousarray(ed, np.int64)
            smap = np.empty((ed.shape[0], ed.shape[1] ** 2), index_dtype)
            _scatter_map(ed, self.free_of, indptr, self.indices, smap)
            self.scatter_maps.append(smap)

    def _group_pattern(self, edofs):
        inc_ptr, inc_el = _dof_to_elements(edofs, self.free_of, self.n_free)
        return _pattern(edofs, self.free_of, self.n_free, inc_ptr, inc_el)

    def _merge(self, ptrs, cols):
        if len(ptrs) == 1:
            return ptrs[0], cols[0]
        mats = [
            sp.csr_matrix((np.ones(c.size), c, p), shape=(self.n_free, self.n_free))
            for p, c in zip(ptrs, cols)
        ]
        union = sum(mats[1:], mats[0]).tocsr()
        union.sort_indices()
        return union.indptr.astype(np.int64), union.indices.astype(np.int32)

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
