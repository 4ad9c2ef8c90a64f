"""Nodal block rescaling of the X-FEM stiffness (Options.rescale = "nodal").

Every node that carries enriched dofs forms one group with its standard
dofs; the group's diagonal block K_gg = L L^T is replaced by the identity
through T_g = L^-T (C++ kernel nodal_block_transform), all other dofs are
Jacobi-scaled. The solved system is (T^T K T) y = T^T f, u = T y; with
contact the constraint rows become B T. The span of the discretisation is
untouched: the answer is the same, only the conditioning of the matrix
changes (and what MUMPS sees). Work is proportional to the enriched nodes:
only the rows of grouped dofs are extracted from the matrix.
"""
from __future__ import annotations

import time
import typing

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from .. import _cracklip
from ..errors import SolverError
from ..model.model import XfemModel
from .checked import petsc_from_scipy


def nodal_groups(model: XfemModel) -> tuple[np.ndarray, np.ndarray]:
    """(group_offsets, group_dofs): per enriched mesh node, its standard
    dofs followed by the dofs of each of its enriched pseudo-nodes (block
    size = the space dimension)."""
    lay = model.layout
    nstd = lay.num_std_nodes
    base = np.asarray(lay.node, dtype=np.int64)
    if base.size == 0:
        return np.zeros(1, dtype=np.int32), np.zeros(0, dtype=np.int32)
    order = np.argsort(base, kind="stable")
    nodes, start, counts = np.unique(base[order], return_index=True, return_counts=True)
    d = model.gdim
    sizes = d + d * counts
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    dofs = np.empty(offsets[-1], dtype=np.int64)
    for c in range(d):
        dofs[offsets[:-1] + c] = d * nodes + c
    group = np.repeat(np.arange(nodes.size), counts)
    rank = np.arange(order.size) - start[group]
    pos = offsets[group] + d + d * rank
    for c in range(d):
        dofs[pos + c] = d * (nstd + order) + c
    return offsets.astype(np.int32), dofs.astype(np.int32)


def nodal_transform(model: XfemModel, A: PETSc.Mat) -> sp.csr_matrix:
    """The block-diagonal T (num_dofs x num_dofs) of the nodal rescaling of A."""
    n = A.getSize()[0]
    offsets, dofs = nodal_groups(model)
    grouped = np.unique(dofs)
    diag = np.abs(A.getDiagonal().array)
    scale = np.where(diag > 0.0, 1.0 / np.sqrt(np.where(diag > 0.0, diag, 1.0)), 1.0)
    rows = [np.setdiff1d(np.arange(n), grouped)]
    cols = [rows[0]]
    vals = [scale[rows[0]]]
    if grouped.size:
        iset = PETSc.IS().createGeneral(grouped.astype(PETSc.IntType), comm=PETSc.COMM_SELF)
        S = A.createSubMatrix(iset, iset)
        indptr, indices, data = S.getValuesCSR()
        S.destroy()
        iset.destroy()
        local = np.searchsorted(grouped, dofs).astype(np.int32)
        try:
            r, c, v = _cracklip.nodal_block_transform(indptr.astype(np.int32), indices.astype(np.int32),
                                                      data, offsets, local)
        except RuntimeError as e:
            raise SolverError(f"{e}; use rescale='none'") from None
        rows.append(grouped[r])
        cols.append(grouped[c])
        vals.append(v)
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))


def rescale_matrix(A: PETSc.Mat, T: sp.csr_matrix) -> PETSc.Mat:
    """T^T A T as a new PETSc matrix."""
    Tp = petsc_from_scipy(T)
    As = A.PtAP(Tp)
    Tp.destroy()
    return As


def rescale_system(A: PETSc.Mat, b: PETSc.Vec, T: sp.csr_matrix) -> tuple[PETSc.Mat, PETSc.Vec]:
    """(T^T A T, T^T b) as new PETSc objects."""
    bs = b.duplicate()
    bs.array[:] = T.T @ b.array
    return rescale_matrix(A, T), bs


def nodal_transform_distributed(model: XfemModel, A: PETSc.Mat) -> PETSc.Mat:
    """nodal_transform on one process's part of a distributed model
    (model.distributed; collective): T as a distributed matrix laid out as A.
    A group (an enriched node's standard and pseudo-node dofs) is built by
    the process owning its node, which owns all its dofs (a pseudo-node
    belongs to its base node's owner), from the owned diagonal block of A
    on the groups' dofs; the other owned dofs are Jacobi-scaled."""
    from ..scene.processes import agree
    dm = model.dofs
    d = model.gdim
    offsets, dofs = nodal_groups(model)
    sizes = np.diff(offsets)
    mine = dofs[offsets[:-1]] // d < model.V.dofmap.index_map.size_local  # (a group's first dof: its node's x)
    g = dm.global_dofs(dofs[np.repeat(mine, sizes)])
    offsets = np.concatenate([[0], np.cumsum(sizes[mine])]).astype(np.int32)
    lo, hi = A.getOwnershipRange()
    if np.any((g < lo) | (g >= hi)):
        raise RuntimeError("a nodal group has dofs owned by another process")  # (the numbering's invariant)
    grouped = np.unique(g)
    diag = np.abs(A.getDiagonal().array)
    scale = np.where(diag > 0.0, 1.0 / np.sqrt(np.where(diag > 0.0, diag, 1.0)), 1.0)
    rest = np.setdiff1d(np.arange(lo, hi), grouped)
    rows, cols, vals = [rest], [rest], [scale[rest - lo]]
    iset = PETSc.IS().createGeneral(grouped.astype(PETSc.IntType), comm=A.getComm())
    S = A.createSubMatrix(iset, iset)
    D = S.getDiagonalBlock()  # the owned groups' rows and columns, in grouped's order
    indptr, indices, data = D.getValuesCSR()
    for o in (S, iset):
        o.destroy()
    error = None
    if grouped.size:
        try:
            r, c, v = _cracklip.nodal_block_transform(indptr.astype(np.int32), indices.astype(np.int32), data,
                                                      offsets, np.searchsorted(grouped, g).astype(np.int32))
        except RuntimeError as e:
            error = SolverError(f"{e}; use rescale='none'")
        else:
            rows.append(grouped[r])
            cols.append(grouped[c])
            vals.append(v)
    agree(error, A.getComm().tompi4py())
    n, N = A.getSizes()[0]
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows) - lo, np.concatenate(cols))), shape=(n, N))
    T.sort_indices()
    return PETSc.Mat().createAIJ(((n, N), (n, N)), csr=(T.indptr.astype(PETSc.IntType),
                                                        T.indices.astype(PETSc.IntType), T.data), comm=A.getComm())


def rescale_distributed(model: XfemModel, A: PETSc.Mat, rhs: list[np.ndarray]
                        ) -> tuple[PETSc.Mat, list[np.ndarray], PETSc.Mat | None, dict[str, float]]:
    """choice.to_solver_basis on a distributed model's direct path: with
    Options.rescale = "nodal" (T^T A T, [T^T b for b in rhs], T, timings),
    the right-hand sides as this process's owned entries; else (A, rhs,
    None, {}). A is consumed."""
    if model.scene.options.rescale != "nodal":
        return A, rhs, None, {}
    t0 = time.perf_counter()
    T = nodal_transform_distributed(model, A)
    A_t = A.PtAP(T)
    A.destroy()
    return A_t, transposed_products(T, rhs), T, {"rescale": time.perf_counter() - t0}


def transposed_products(T: PETSc.Mat, rhs: typing.Sequence[np.ndarray]) -> list[np.ndarray]:
    """Collective: T^T b for each b of rhs (this process's owned entries of
    T's rows; the results its owned entries of T's columns)."""
    out = []
    b, bt = T.createVecLeft(), T.createVecRight()
    for v in rhs:
        b.array[:] = v
        T.multTranspose(b, bt)
        out.append(bt.array.copy())
    for o in (b, bt):
        o.destroy()
    return out


def from_basis(T: PETSc.Mat | None, x: PETSc.Vec) -> PETSc.Vec:
    """The dofs u = T y of a solution y in rescale_distributed's basis (x
    itself without T; a new vector with it, x destroyed)."""
    if T is None:
        return x
    u = T.createVecLeft()
    T.mult(x, u)
    x.destroy()
    return u


def times_basis(C: sp.csr_matrix, T: "PETSc.Mat | sp.spmatrix") -> sp.csr_matrix:
    """C T: constraint rows C acting on u = T y (the contact couplings B,
    B_t in a solver path's basis). Serial T (scipy): C @ T. A distributed T
    (PETSc, this process's rows; C whole on every process, its columns T's
    global rows; collective): each process's columns of C times its rows
    of T, summed over the processes; whole on every process."""
    if not isinstance(T, PETSc.Mat):
        return (C @ T).tocsr()
    from ..scene.processes import gathered
    lo, hi = T.getOwnershipRange()
    indptr, indices, data = T.getValuesCSR()
    rows = sp.csr_matrix((data, indices, indptr), shape=(hi - lo, T.getSize()[1]))
    part = (C[:, lo:hi] @ rows).tocoo()
    r, c, v = gathered(T.getComm().tompi4py(), [part.row, part.col, part.data])
    out = sp.csr_matrix((v, (r, c)), shape=(C.shape[0], T.getSize()[1]))
    out.sort_indices()
    return out
