"""The phantom-node (Hansbo) basis of the Heaviside pairs.

Per Heaviside pseudo-node k (base node i, side s = H(x_i)) and component d,
the standard dof u and the enriched dof a become p = u (the node's own-side
copy) and q = u - 2 s a (the other-side copy): u = p, a = s (p - q) / 2. T
maps the new dofs to the old ones (u = T y); the solved system is
T^T A T y = T^T b, and with contact the constraints become B T. In this
basis every Heaviside basis function is N_i times the indicator of one side
of the crack, so the stiffness looks like two standard meshes glued along
the uncut part: an ordinary elasticity operator that smoothed aggregation
can coarsen.
"""
from __future__ import annotations

import dataclasses
import logging
import typing

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from .checked import scipy_from_petsc
if typing.TYPE_CHECKING:
    from ..model.model import XfemModel


logger = logging.getLogger(__name__)


#: The in-place transform's result must be symmetric (A is): x^T A z and
#: z^T A x of two random vectors may differ by at most this times
#: ||A||_F ||x|| ||z||. Round-off gave 5e-21 .. 3e-19 (penny, Westergaard;
#: 1 and 2 processes); one wrong entry of a typical size gives about
#: 1 / (sqrt(nnz) n) (5e-10 at 1e6 dofs), a row left untransformed more
#: (the block under pressure on 2 processes when the distributed transform
#: still took its rows from the crack band: 6.4e-7).
SYMMETRY_TOL = 1e-12


@dataclasses.dataclass
class PhantomBasis:
    """The phantom-node transform of a model's Heaviside pairs.

    Attributes:
        T: (n, n) new -> old dofs, u = T y (n = model.num_dofs).
        T_inv: (n, n) old -> new dofs, y = T_inv u.
        heaviside: (num_heaviside,) the Heaviside pseudo-nodes.
        touched: sorted dofs where T is not the identity (both dofs of
            every Heaviside node and of its Heaviside pseudo-nodes).
    """
    T: sp.csr_matrix
    T_inv: sp.csr_matrix
    heaviside: np.ndarray
    touched: np.ndarray

    #: The block size (the space dimension: 2 or 3).
    bs: int = 2

    def petsc(self) -> PETSc.Mat:
        """T as a PETSc AIJ matrix with the model's block size (so that
        T^T A T keeps the block size GAMG needs)."""
        T = self.T
        return PETSc.Mat().createAIJ(T.shape, bsize=self.bs, comm=PETSc.COMM_SELF,
                                     csr=(T.indptr.astype(PETSc.IntType), T.indices.astype(PETSc.IntType), T.data))


def phantom_basis(model: "XfemModel") -> PhantomBasis:
    """T and T^-1 of the phantom-node basis (module docstring); identity on
    standard dofs of plain nodes and on tip dofs."""
    lay = model.layout
    n = model.num_dofs
    nstd = lay.num_std_nodes
    kind = np.asarray(lay.kind)
    heav = np.flatnonzero(kind == 0)
    base = np.asarray(lay.node, dtype=np.int64)[heav]
    side = np.asarray(lay.node_side, dtype=np.float64)[heav]  # H(x_i): +1 on the crack itself
    d = model.gdim
    e = (d * (nstd + heav)[:, None] + np.arange(d)).ravel()
    s = (d * base[:, None] + np.arange(d)).ravel()
    sgn = np.repeat(side, d)
    eye = np.ones(n)
    eye[e] = 0.0
    diag = np.arange(n)
    # T: a = s/2 p - s/2 q; u = p.
    T = sp.csr_matrix((np.concatenate([eye[eye > 0], 0.5 * sgn, -0.5 * sgn]),
                       (np.concatenate([diag[eye > 0], e, e]), np.concatenate([diag[eye > 0], s, e]))), shape=(n, n))
    # T^-1: q = u - 2 s a; p = u.
    T_inv = sp.csr_matrix((np.concatenate([eye[eye > 0], np.ones(e.size), -2.0 * sgn]),
                           (np.concatenate([diag[eye > 0], e, e]), np.concatenate([diag[eye > 0], s, e]))),
                          shape=(n, n))
    T.sort_indices()
    T_inv.sort_indices()
    return PhantomBasis(T, T_inv, heav, np.union1d(s, e).astype(np.int64), d)


def transform_system(basis: PhantomBasis, A: PETSc.Mat, b: PETSc.Vec) -> tuple[PETSc.Mat, PETSc.Vec]:
    """(T^T A T, T^T b): transform_matrix and the load (A is consumed as
    there)."""
    b_t = A.createVecRight()
    b_t.array[:] = basis.T.T @ b.array
    return transform_matrix(basis, A), b_t


def transform_matrix(basis: PhantomBasis, A: PETSc.Mat) -> PETSc.Mat:
    """T^T A T (block size 2). A's storage is reused when it can be (then
    the returned matrix is A itself, changed): do not use A after.

    T differs from the identity only on the Heaviside nodes' dofs J, so
    T^T A T differs from A only in the rows and columns R that couple to J
    (J and its neighbours): (T^T A T)[r, :] = (A T)[r, :] for r not in J and
    T_JJ^T (A T)[J, :] on J. Only those rows are computed (scipy, |R| rows)
    and added into A, whose pattern already holds them (a node's standard
    and Heaviside dofs couple to the same dofs): at 1e6 dofs 0.05 s instead
    of PtAP's 0.9 s (and no copy of A). Falls back to PtAP (a new matrix,
    A untouched) if A's pattern lacks an entry or the result is not
    symmetric (changed_symmetric)."""
    T = basis.T
    J = basis.touched
    if J.size == 0:
        return A
    n = A.getSize()[0]
    all_cols = PETSc.IS().createStride(n, 0, 1, comm=PETSc.COMM_SELF)

    def rows(idx: np.ndarray) -> sp.csr_matrix:
        iset = PETSc.IS().createGeneral(idx.astype(PETSc.IntType), comm=PETSc.COMM_SELF)
        sub = A.createSubMatrix(iset, all_cols)
        out = scipy_from_petsc(sub)
        sub.destroy()
        iset.destroy()
        return out
    R = np.union1d(np.unique(rows(J).indices), J)  # every row with a column in J (A is symmetric)
    S = rows(R)
    all_cols.destroy()
    ST = (S @ T).tocsr()
    delta, order, fits = phantom_change(S, ST, R, J, T[J][:, J])
    del S, ST
    if fits and changed_symmetric(A, delta, order):
        return A
    Tp = basis.petsc()  # a coupling outside A's pattern, or a wrong change (taken back): the general way
    A_t = A.PtAP(Tp)
    Tp.destroy()
    return A_t


def phantom_change(S: sp.csr_matrix, ST: sp.csr_matrix, R: np.ndarray, J: np.ndarray,
                   T_JJ: sp.csr_matrix) -> tuple[sp.csr_matrix, np.ndarray, bool]:
    """The change T^T A T - A on the rows it touches, for the in-place
    transforms (transform_matrix; distributed_iterative.transform_in_place).

    S: A's rows R (sorted); ST: (A T) on the same rows, in the same columns;
    J (sorted, within R): the rows where T is not the identity, T_JJ: T's
    block on them. Off J a row of T^T A T is (A T)'s, on J it is
    T_JJ^T (A T)[J, :]. Returns (delta, rows, fits): delta's row k goes to
    A's row rows[k] (R off J first, then J), and fits says whether every
    nonzero of delta lies in A's pattern (else the caller falls back to a
    product)."""
    posJ = np.searchsorted(R, J)
    keep = np.ones(R.size, dtype=bool)
    keep[posJ] = False
    new = sp.vstack([ST[keep], (T_JJ.T.tocsr() @ ST[posJ]).tocsr()], format="csr")  # (all CSR: the fast stack)
    old = sp.vstack([S[keep], S[posJ]], format="csr")
    delta = (new - old).tocsr()
    delta.eliminate_zeros()

    def pattern(M: sp.csr_matrix) -> sp.csr_matrix:
        return sp.csr_matrix((np.ones(M.nnz), M.indices, M.indptr), shape=M.shape)
    fits = pattern(delta).multiply(pattern(old)).nnz == delta.nnz
    return delta, np.concatenate([R[keep], J]), fits


def add_change(A: PETSc.Mat, delta: sp.csr_matrix, rows: np.ndarray, columns: np.ndarray | None = None) -> None:
    """A[rows[k], columns[j]] += delta[k, j] (columns: the identity if None)
    in one call with the CSR rows of delta (no padding to the longest row:
    in 3D that dense block took 0.15 GB at 8e4 dofs), then assembled."""
    cols = delta.indices if columns is None else columns[delta.indices]
    A.setValuesIJV(delta.indptr.astype(PETSc.IntType), cols.astype(PETSc.IntType), delta.data,
                   addv=PETSc.InsertMode.ADD_VALUES, rowmap=rows.astype(PETSc.IntType))
    A.assemble()


def changed_symmetric(A: PETSc.Mat, delta: sp.csr_matrix, rows: np.ndarray,
                      columns: np.ndarray | None = None) -> bool:
    """add_change, then a check that A stayed symmetric (collective): two
    random vectors, |x^T A z - z^T A x| <= SYMMETRY_TOL ||A||_F ||x|| ||z||
    (two products with A). If not, the change is taken back (A as it was)
    and False returned, so that the caller computes T^T A T by PtAP: a
    wrong in-place transform (a row it should have changed and did not)
    is never solved, whose answer the residual check, made on the same
    matrix, would pass."""
    add_change(A, delta, rows, columns)
    rand = PETSc.Random().create(A.getComm())
    rand.setSeed(20261127)
    x, z = A.createVecs()
    x.setRandom(rand)
    z.setRandom(rand)
    Ax, Az = A.createVecs()
    A.mult(x, Ax)
    A.mult(z, Az)
    defect = abs(x.dot(Az) - z.dot(Ax))
    scale = A.norm(PETSc.NormType.FROBENIUS) * x.norm() * z.norm()
    for v in (x, z, Ax, Az, rand):
        v.destroy()
    if defect <= SYMMETRY_TOL * scale:
        return True
    logger.warning("the phantom-node transform in place is not symmetric (defect %.2g of the scale): "
                   "recomputed by a matrix product instead", defect / scale)
    add_change(A, -delta, rows, columns)
    return False
