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
def _incidence(dofs, el_ptr, free_of, inc_ptr, inc_el, inc_entry, fill):
    """Fill the CSR incidence free DOF -> elements holding it (``inc_ptr`` zeros of n_free + 1; ``inc_el`` and
    ``inc_entry`` of at least ``dofs.size``): for each, the element ``e`` and the position ``k`` of the DOF in
    the flat element-DOF list (its local index is ``k - el_ptr[e]``). The arrays come from the caller: numpy
    backs large ones with huge pages, a kernel's own allocation does not (6x the page faults); ``fill`` (>=
    n_free) is scratch. No kernel here allocates: each allocation would compile one more numpy overload into
    a cold first run."""
    n_free = inc_ptr.size - 1
    for k in range(dofs.size):
        f = free_of[dofs[k]]
        if f >= 0:
            inc_ptr[f + 1] += 1
    for i in range(n_free):
        inc_ptr[i + 1] += inc_ptr[i]
    for i in range(n_free):
        fill[i] = inc_ptr[i]
    for e in range(el_ptr.size - 1):
        for k in range(el_ptr[e], el_ptr[e + 1]):
            f = free_of[dofs[k]]
            if f >= 0:
                inc_el[fill[f]] = e
                inc_entry[fill[f]] = k
                fill[f] += 1


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
def _run_length(inc_ptr, inc_el, row):
    """How many rows from ``row`` on lie in the same elements as ``row`` (the free DOFs of one node do)."""
    run = 1
    while row + run < inc_ptr.size - 1 and _same_elements(inc_ptr, inc_el, row + run):
        run += 1
    return run


@njit(cache=True)
def _row_pointers(dofs, el_ptr, free_of, inc_ptr, inc_el, indptr, marker):
    """Fill ``indptr`` (zeros of n_free + 1) with the row pointers of the union of element couplings over the
    free DOFs: each row's distinct columns counted with a marker. Consecutive rows in the same elements (one
    node's DOFs) have the same columns and are counted once. ``marker`` (>= n_free) is scratch."""
    n_free = inc_ptr.size - 1
    for i in range(n_free):
        marker[i] = -1
    row = np.int64(0)  # not the literal 0: numba would compile a second _run_length for a literal argument
    while row < n_free:
        run = _run_length(inc_ptr, inc_el, row)
        n = 0
        for k in range(inc_ptr[row], inc_ptr[row + 1]):
            e = inc_el[k]
            for b in range(el_ptr[e], el_ptr[e + 1]):
                col = free_of[dofs[b]]
                if col >= 0 and marker[col] != row:
                    marker[col] = row
                    n += 1
        for t in range(run):
            indptr[row + t + 1] = indptr[row + t] + n
        row += run


@njit(cache=True)
def _column_indices(dofs, el_ptr, free_of, inc_ptr, inc_el, indptr, indices, marker, fill):
    """Fill ``indices`` (nnz) with the sorted column indices of every row, without a sort: each row is
    appended to the list of each of its columns. The couplings are symmetric (row i holds column j iff row j
    holds column i), so visiting the rows in increasing order fills every list in increasing order.
    ``marker`` and ``fill`` (>= n_free) are scratch."""
    n_free = inc_ptr.size - 1
    for i in range(n_free):
        marker[i] = -1
        fill[i] = indptr[i]
    row = np.int64(0)  # see _row_pointers
    while row < n_free:
        run = _run_length(inc_ptr, inc_el, row)
        for k in range(inc_ptr[row], inc_ptr[row + 1]):
            e = inc_el[k]
            for b in range(el_ptr[e], el_ptr[e + 1]):
                col = free_of[dofs[b]]
                if col >= 0 and marker[col] != row:
                    marker[col] = row
                    start = fill[col]
                    for t in range(run):  # the run's rows, in order, side by side in column col's list
                        indices[start + t] = row + t
                    fill[col] = start + run
        row += run


@njit(cache=True)
def _scatter_map(
    dofs, el_ptr, smap_ptr, free_of, indptr, indices, inc_ptr, inc_el, inc_entry, smap, position
):
    """Fill the flat scatter map ``smap`` (element e's n_e x n_e block, row-major, at ``smap_ptr[e]``) with
    CSR data positions, -1 where the row or the column is constrained. Row by row: the row's columns are
    spread into a position table once, then every element holding the row reads its block row from it; a row
    with the same columns as the row before it shifts that row's block rows instead. ``position`` (>= n_free)
    is scratch."""
    for e in range(el_ptr.size - 1):  # rows of constrained DOFs are not in the incidence
        n_e = el_ptr[e + 1] - el_ptr[e]
        for a in range(n_e):
            if free_of[dofs[el_ptr[e] + a]] < 0:
                for b in range(n_e):
                    smap[smap_ptr[e] + a * n_e + b] = -1
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


def _flat_elements(edofs_list):
    """Every group's element-DOF lists in one flat array, so that one pass over all groups builds the union
    of their couplings: (dofs, el_ptr, smap_ptr), element e's DOFs ``dofs[el_ptr[e]:el_ptr[e + 1]]`` and its
    n_e x n_e scatter-map block at ``smap_ptr[e]``."""
    if len(edofs_list) == 1:
        dofs = edofs_list[0].ravel()  # a view: one group needs no copy
    else:
        dofs = np.concatenate([ed.ravel() for ed in edofs_list] + [np.zeros(0, np.int64)])
    n_per_el = np.concatenate(
        [np.full(ed.shape[0], ed.shape[1], np.int64) for ed in edofs_list] + [np.zeros(0, np.int64)]
    )
    el_ptr = np.zeros(n_per_el.size + 1, np.int64)
    np.cumsum(n_per_el, out=el_ptr[1:])
    smap_ptr = np.zeros(n_per_el.size + 1, np.int64)
    np.cumsum(n_per_el**2, out=smap_ptr[1:])
    return dofs, el_ptr, smap_ptr


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
        edofs_list = [np.ascontiguousarray(ed, np.int64) for ed in edofs_list]
        dofs, el_ptr, smap_ptr = _flat_elements(edofs_list)
        inc_ptr = np.zeros(self.n_free + 1, np.int64)
        inc_el, inc_entry = np.empty(dofs.size, np.int64), np.empty(dofs.size, np.int64)
        scratch = np.empty((2, self.n_free + 1), np.int64)
        _incidence(dofs, el_ptr, self.free_of, inc_ptr, inc_el, inc_entry, scratch[0])
        indptr = np.zeros(self.n_free + 1, np.int64)
        _row_pointers(dofs, el_ptr, self.free_of, inc_ptr, inc_el, indptr, scratch[0])
        self.nnz = int(indptr[-1])
        self.indices = np.empty(self.nnz, np.int32)
        _column_indices(dofs, el_ptr, self.free_of, inc_ptr, inc_el, indptr, self.indices, *scratch)
        # int32 row pointers and scatter maps where the entries fit (half the memory of int64; the CSR
        # matrices built on this pattern then share its index arrays instead of casting a copy each time)
        index_dtype = np.int32 if self.nnz < np.iinfo(np.int32).max else np.int64
        self.indptr = indptr.astype(index_dtype)
        if index_dtype == np.int64:
            self.indices = self.indices.astype(np.int64)
        smap = np.empty(smap_ptr[-1], index_dtype)
        _scatter_map(
            dofs,
            el_ptr,
            smap_ptr,
            self.free_of,
            indptr,
            self.indices,
            inc_ptr,
            inc_el,
            inc_entry,
            smap,
            scratch[0],
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

    def assemble_elastic(self, groups, data=None):
        """Assemble K0 of the element ``groups`` (in the order of this pattern's ``edofs_list``) into ``data``
        (reused if given), through each group's ``assemble_elastic_stiffness(smap, data)``: by default it
        scatters the group's ``elastic_stiffness()``; the soil group assembles without keeping element
        matrices (at 1e6 DOFs their 343 MB cost more to touch than to compute)."""
        if data is None:
            data = self.new_data()
        else:
            data[:] = 0.0
        for smap, group in zip(self.scatter_maps, groups):
            group.assemble_elastic_stiffness(smap, data)
        return data

    def assemble(self, k_el_list, data=None):
        """Assemble the element matrices of every group into ``data`` (reused if given)."""
        if data is None:
            data = self.new_data()
        else:
            data[:] = 0.0
        for smap, k_el in zip(self.scatter_maps, k_el_list):
            scatter_matrix(smap, k_el, data)
        return data
