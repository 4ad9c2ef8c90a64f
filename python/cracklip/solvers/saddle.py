"""The contact saddle points: the frictionless [K B_a^T; B_a D] assembled (direct path)
or applied block by block around the stiffness (iterative path); under mpirun
any multiplier border [K C^T; rows] around the distributed stiffness
(frictionless and frictional)."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from .. import _cracklip
from .checked import petsc_from_scipy, scipy_from_petsc


def multiplier_block(active: np.ndarray, S: sp.spmatrix | None = None) -> sp.csr_matrix:
    """D of [K B_a^T; B_a D]: 1 on the diagonal of inactive multipliers (held
    at 0), -S on the active rows and columns (the multipliers'
    stabilization, contact/stabilization.py; 0 without S)."""
    a = np.asarray(active, dtype=bool)
    D = sp.diags((~a).astype(float), format="csr")
    if S is not None:
        Pa = sp.diags(a.astype(float))
        D = (D - Pa @ S @ Pa).tocsr()
        D.eliminate_zeros()
    return D


def saddle_matrix(K: sp.csr_matrix, B: sp.csr_matrix, active: np.ndarray,
                  S: sp.csr_matrix | None = None) -> PETSc.Mat:
    """The PETSc AIJ matrix [K B_a^T; B_a D] (symmetric): B_a = B with the
    rows of inactive multipliers emptied, D = multiplier_block(active, S)
    (1 on inactive multipliers, which are held at 0, -S on the active ones).

    The CSR arrays come from the C++ kernel (cpp/solvers/saddle_matrix.h: B_a^T's
    entries at the ends of K's rows, then B_a's rows and D) and go to PETSc
    without a copy: at 1e6 dofs 0.06 s, against 0.58 s for the same merge
    in numpy and ~3.6 s for a scipy block product and a second conversion."""
    n, m = K.shape[0], B.shape[0]
    idx = PETSc.IntType
    if not K.has_sorted_indices:
        K = K.sorted_indices()
    if not B.has_sorted_indices:
        B = B.sorted_indices()
    indptr, indices, data = _cracklip.saddle_csr(
        K.indptr.astype(idx, copy=False), K.indices.astype(idx, copy=False), K.data,
        B.indptr.astype(idx, copy=False), B.indices.astype(idx, copy=False), B.data,
        np.asarray(active, dtype=np.int8),
        *((S.indptr.astype(idx, copy=False), S.indices.astype(idx, copy=False), S.data) if S is not None
          else (np.zeros(0, dtype=idx), np.zeros(0, dtype=idx), np.zeros(0))))
    A = PETSc.Mat().createAIJWithArrays((n + m, n + m), (indptr, indices, data), comm=PETSc.COMM_SELF)
    A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
    return A


def distributed_saddle_matrix(K: PETSc.Mat, B: sp.csr_matrix, active: np.ndarray,
                              S: sp.csr_matrix | None = None) -> PETSc.Mat:
    """[K B_a^T; B_a D] (saddle_matrix) on K's processes (mpirun): K
    distributed over its processes, B (m, N) whole on every process (columns
    K's global dofs); bordered_matrix with C = B_a and the rows [B_a D]."""
    Ba = (sp.diags(np.asarray(active, dtype=float)) @ B).tocsr()
    D = multiplier_block(active, S)
    return bordered_matrix(K, Ba, sp.hstack([Ba, D], format="csr"), symmetric=True)


def bordered_matrix(K: PETSc.Mat, C: sp.csr_matrix, rows: sp.csr_matrix, symmetric: bool) -> PETSc.Mat:
    """[K C^T; rows] on K's processes (mpirun): K (N, N) distributed over its
    processes; C (m, N) and rows (m, N + m), the multipliers' columns and
    rows, whole on every process (columns K's global dofs, then the m
    multipliers). Each process holds its rows of K with C^T's entries at
    the columns N + k; the multiplier rows (few) go to the last process,
    after K's last rows. The frictionless saddle point (symmetric: rows =
    [C D]) and the frictional one (unsymmetric: the normal and tangential
    multipliers' rows, contact/friction.py)."""
    comm = K.getComm()
    N, m = K.getSize()[0], C.shape[0]
    lo, hi = K.getOwnershipRange()
    indptr, indices, data = K.getValuesCSR()
    rows_own = sp.hstack([sp.csr_matrix((data, indices, indptr), shape=(hi - lo, N)), C[:, lo:hi].T], format="csr")
    if comm.getRank() == comm.getSize() - 1:
        rows_own = sp.vstack([rows_own, rows], format="csr")
    rows_own.sort_indices()
    idx = PETSc.IntType
    n = rows_own.shape[0]
    A = PETSc.Mat().createAIJWithArrays(((n, N + m), (n, N + m)), (rows_own.indptr.astype(idx),
                                                                  rows_own.indices.astype(idx), rows_own.data),
                                        comm=comm)
    A.setOption(PETSc.Mat.Option.SYMMETRIC, symmetric)
    return A


class SaddleOperator:
    """Python-matrix context of IterativeSolver.saddle_matrix: the
    frictionless saddle point [K B_a^T; B_a D] (B_a = B with the rows of
    inactive multipliers emptied, D = 1 on inactive multipliers, 0 on active
    ones) applied block by block on ordinary (n + m) vectors, K in place
    (K.mult on a view: a MatNest zeroes y and calls multAdd, 1.5 ms more per
    product at 1e6 dofs)."""

    def __init__(self, K: PETSc.Mat, B: sp.csr_matrix, active: np.ndarray, S: sp.csr_matrix | None = None):
        comm = PETSc.COMM_SELF
        self.K = K
        self.active = np.asarray(active, dtype=bool)
        self.B = B
        self.Ba = (sp.diags(self.active.astype(float)) @ B).tocsr()
        self.Ba.sort_indices()
        self.n, self.m = K.getSize()[0], B.shape[0]
        self.S = S
        self.D = multiplier_block(self.active, S)
        self._D = petsc_from_scipy(self.D)
        self.Ba_petsc = petsc_from_scipy(self.Ba)
        self._BaT = petsc_from_scipy(self.Ba.T)
        self._is_u = PETSc.IS().createStride(self.n, 0, 1, comm=comm)
        self._is_l = PETSc.IS().createStride(self.m, self.n, 1, comm=comm)

    def mult(self, mat: PETSc.Mat, x: PETSc.Vec, y: PETSc.Vec) -> None:
        xu, yu = x.getSubVector(self._is_u), y.getSubVector(self._is_u)
        self.K.mult(xu, yu)
        if self.m:
            xl, yl = x.getSubVector(self._is_l), y.getSubVector(self._is_l)
            self._BaT.multAdd(xl, yu, yu)
            self.Ba_petsc.mult(xu, yl)
            self._D.multAdd(xl, yl, yl)
            x.restoreSubVector(self._is_l, xl)
            y.restoreSubVector(self._is_l, yl)
        x.restoreSubVector(self._is_u, xu)
        y.restoreSubVector(self._is_u, yu)

    def multTranspose(self, mat: PETSc.Mat, x: PETSc.Vec, y: PETSc.Vec) -> None:
        self.mult(mat, x, y)

    def assembled(self) -> PETSc.Mat:
        """The same matrix assembled (PETSc AIJ, for MUMPS)."""
        return saddle_matrix(scipy_from_petsc(self.K), self.B, self.active, self.S)

    def band_blocks(self, band: np.ndarray) -> tuple[PETSc.Mat, PETSc.Mat, PETSc.Mat]:
        """(A1, A01, A11) of Schwarz for the sorted band dofs, from K's band
        rows and the small blocks: A1 = the band's rows, A01 = the
        stiffness rows at the band's columns (A1's transpose, the matrix
        being symmetric), A11 = the band's rows and columns."""
        comm = PETSc.COMM_SELF
        n = self.n
        kb = band[band < n]
        rows = PETSc.IS().createGeneral(kb.astype(PETSc.IntType), comm=comm)
        K1 = self.K.createSubMatrix(rows, self._is_u)
        rows.destroy()
        top = sp.hstack([scipy_from_petsc(K1), self.Ba.T.tocsr()[kb]], format="csr")
        K1.destroy()
        A1 = sp.vstack([top, sp.hstack([self.Ba, self.D], format="csr")], format="csr")
        return petsc_from_scipy(A1), petsc_from_scipy(A1[:, :n].T), petsc_from_scipy(A1[:, band])

    def destroy(self, mat: PETSc.Mat) -> None:
        for obj in (self.Ba_petsc, self._BaT, self._D, self._is_u, self._is_l):
            obj.destroy()


def assembled_bordered(K: sp.csr_matrix, C: sp.csr_matrix, rows: sp.csr_matrix) -> PETSc.Mat:
    """The PETSc AIJ matrix [K C^T; rows] (serial, unsymmetric in general):
    K the scipy stiffness, C (m, n) the multipliers' columns, rows (m, n + m)
    their rows (frictional contact's saddle point on the direct path)."""
    return petsc_from_scipy(sp.vstack([sp.hstack([K, C.T]), rows], format="csr"))


class BorderedOperator:
    """Python-matrix context of IterativeSolver.bordered_matrix: [K C^T;
    rows] (serial) applied block by block around the PETSc stiffness K,
    with no copy of it: friction's unsymmetric saddle point (C = [B; B_t]
    whole, rows the normal and tangential multipliers' rows of the current
    states). Assembled, the 1e6-dof system cost a scipy copy of K and a
    block merge of its ~4e7 entries per semi-smooth iteration.
    Ba_petsc: the rows of C that hold as constraints in these states (the
    closed normal rows, the sticking tangential ones), which keep
    IterativeSolver's coarse space closed (ConstrainedCoarse)."""

    def __init__(self, K: PETSc.Mat, C: sp.csr_matrix, rows: sp.csr_matrix, constraints: sp.csr_matrix):
        comm = PETSc.COMM_SELF
        self.K = K
        self.n, self.m = K.getSize()[0], C.shape[0]
        n = self.n
        self.C = C.tocsr()
        self.C.sort_indices()
        rows = rows.tocsr()
        self.rows = rows
        self.Ru = rows[:, :n].tocsr()
        self.Rl = rows[:, n:].tocsr()
        self._CT = petsc_from_scipy(self.C.T)
        self._Ru = petsc_from_scipy(self.Ru)
        self.Ba_petsc = petsc_from_scipy(constraints)
        self._is_u = PETSc.IS().createStride(n, 0, 1, comm=comm)
        self._is_l = PETSc.IS().createStride(self.m, n, 1, comm=comm)

    def mult(self, mat: PETSc.Mat, x: PETSc.Vec, y: PETSc.Vec) -> None:
        xu, yu = x.getSubVector(self._is_u), y.getSubVector(self._is_u)
        self.K.mult(xu, yu)
        if self.m:
            xl, yl = x.getSubVector(self._is_l), y.getSubVector(self._is_l)
            self._CT.multAdd(xl, yu, yu)
            self._Ru.mult(xu, yl)
            yl.array[:] += self.Rl @ xl.array_r
            x.restoreSubVector(self._is_l, xl)
            y.restoreSubVector(self._is_l, yl)
        x.restoreSubVector(self._is_u, xu)
        y.restoreSubVector(self._is_u, yu)

    def multTranspose(self, mat: PETSc.Mat, x: PETSc.Vec, y: PETSc.Vec) -> None:
        xu, yu = x.getSubVector(self._is_u), y.getSubVector(self._is_u)
        self.K.mult(xu, yu)  # (K symmetric)
        if self.m:
            xl, yl = x.getSubVector(self._is_l), y.getSubVector(self._is_l)
            self._Ru.multTransposeAdd(xl, yu, yu)
            yl.array[:] = self.C @ xu.array_r + self.Rl.T @ xl.array_r
            x.restoreSubVector(self._is_l, xl)
            y.restoreSubVector(self._is_l, yl)
        x.restoreSubVector(self._is_u, xu)
        y.restoreSubVector(self._is_u, yu)

    def assembled(self) -> PETSc.Mat:
        """The same matrix assembled (PETSc AIJ, for MUMPS)."""
        return assembled_bordered(scipy_from_petsc(self.K), self.C, self.rows)

    def band_blocks(self, band: np.ndarray) -> tuple[PETSc.Mat, PETSc.Mat, PETSc.Mat]:
        """(A1, A01, A11) of Schwarz for the sorted band dofs (every
        multiplier among them): A1 = the band's rows, A01 = the stiffness
        rows at the band's columns ([K C^T]'s: K's band rows transposed, K
        being symmetric, and C^T), A11 = the band's rows and columns."""
        comm = PETSc.COMM_SELF
        n = self.n
        kb = band[band < n]
        lb = band[band >= n] - n
        idx = PETSc.IS().createGeneral(kb.astype(PETSc.IntType), comm=comm)
        K1 = self.K.createSubMatrix(idx, self._is_u)
        idx.destroy()
        K1s = scipy_from_petsc(K1)
        K1.destroy()
        CT = self.C.T.tocsr()
        A1 = sp.vstack([sp.hstack([K1s, CT[kb]], format="csr"), self.rows[lb]], format="csr")
        A01 = sp.hstack([K1s.T, CT[:, lb]], format="csr")
        return petsc_from_scipy(A1), petsc_from_scipy(A01), petsc_from_scipy(A1[:, band])

    def destroy(self, mat: PETSc.Mat) -> None:
        for obj in (self._CT, self._Ru, self.Ba_petsc, self._is_u, self._is_l):
            obj.destroy()
