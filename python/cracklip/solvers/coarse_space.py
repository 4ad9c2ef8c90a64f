"""GAMG's coarsest solve during a contact solve: the coarse space's
strongest crack-opening modes kept closed (ConstrainedCoarse)."""
from __future__ import annotations

import hashlib

import numpy as np
from petsc4py import PETSc

from .checked import scipy_from_petsc


#: ConstrainedCoarse keeps closed the jump modes of GAMG's coarsest space
#: whose singular values (in B_a P) are at least this fraction of the
#: largest. At 1e6 dofs (bilateral, coarsest level 3483 dofs): 0.1 and 0.01
#: (17 and 50 modes) 43 -> 36 CG iterations; 1e-3 (87 modes) 44: modes the
#: coarse space represents poorly lock it.
COARSE_CONSTRAINT_SV = 0.05


class ConstrainedCoarse:
    """Python PC of the coarsest solve of the GAMG hierarchy: the LU solve
    of the coarse operator A_c and, while a contact solve runs, the solve
    constrained to keep the coarse space's strongest crack-opening modes
    closed:

        y = A_c^-1 r - W S^-1 W^T r,   W = A_c^-1 C^T,  S = C W,

    C (k x n_c, orthonormal rows) = the right singular vectors of B_a P
    (P: coarse space -> stiffness dofs, the product of GAMG's
    interpolations) whose singular values are at least COARSE_CONSTRAINT_SV
    times the largest: the jumps the multipliers see best. Without it the
    V-cycle's coarse correction opens the crack over its whole length, and
    the band, a few cells wide, closes it again only locally. Symmetric
    positive semidefinite, so the V-cycle stays symmetric (CG)."""

    def __init__(self, amg: PETSc.PC, block0: np.ndarray | None = None):
        """block0: the stiffness dofs GAMG's operator holds (None: all of
        them, in order)."""
        ksp = amg.getMGCoarseSolve()
        self.Ac = ksp.getOperators()[0]
        self.lu = PETSc.PC().create(PETSc.COMM_SELF)
        self.lu.setOperators(self.Ac)
        self.lu.setType(PETSc.PC.Type.LU)
        # As GAMG's own coarse solve: a coarse operator may be singular
        # (rigid modes of a small hierarchy).
        self.lu.setFactorShift(PETSc.Mat.FactorShiftType.INBLOCKS)
        self.lu.setUp()
        ksp.setType(PETSc.KSP.Type.PREONLY)
        pc = ksp.getPC()
        pc.setType(PETSc.PC.Type.PYTHON)
        pc.setPythonContext(self)
        levels = amg.getMGLevels()
        self.interpolations = [amg.getMGInterpolation(level) for level in range(levels - 1, 0, -1)]  # finest first
        self.block0 = block0
        self.C: np.ndarray | None = None
        self.G: np.ndarray | None = None
        # The last constraint's (key, (C, G)): the friction iteration's
        # solves keep the same closed rows (bilateral: all of them), and the
        # dense SVD on the coarse space is then done once.
        self._last: tuple[bytes, tuple] | None = None

    @property
    def rank(self) -> int:
        """The number of constrained coarse modes (0: the plain LU solve)."""
        return 0 if self.C is None else self.C.shape[0]

    def constrain(self, B: PETSc.Mat) -> None:
        """Constrain the coarse solve by the multipliers' rows B (m x n,
        stiffness columns in the solver's basis; the same B as the last
        time: its C and G again)."""
        indptr, indices, data = B.getValuesCSR()
        key = hashlib.sha1(b"".join(np.ascontiguousarray(a).tobytes() for a in (indptr, indices, data))).digest()
        if self._last is not None and self._last[0] == key:
            self.C, self.G = self._last[1]
            return
        self._constrain(B)
        self._last = (key, (self.C, self.G))

    def _constrain(self, B: PETSc.Mat) -> None:
        Bc = B
        if self.block0 is not None:  # (B's columns of GAMG's rows; freed as the products are)
            rows = PETSc.IS().createStride(B.getSize()[0], 0, 1, comm=B.getComm())
            cols = PETSc.IS().createGeneral(self.block0.astype(PETSc.IntType), comm=B.getComm())
            Bc = B.createSubMatrix(rows, cols)
            rows.destroy()
            cols.destroy()
        for P in self.interpolations:
            nxt = Bc.matMult(P)
            if Bc is not B:
                Bc.destroy()
            Bc = nxt
        dense = scipy_from_petsc(Bc).toarray()
        if Bc is not B:
            Bc.destroy()
        _, sv, Vt = np.linalg.svd(dense, full_matrices=False)
        k = int((sv >= COARSE_CONSTRAINT_SV * sv[0]).sum()) if sv.size and sv[0] > 0 else 0
        self.clear()
        if k == 0:
            return
        C = Vt[:k]
        W = np.empty((C.shape[1], k))
        x, y = self.Ac.createVecs()
        for j in range(k):
            x.array[:] = C[j]
            self.lu.apply(x, y)
            W[:, j] = y.array
        x.destroy()
        y.destroy()
        S = C @ W
        # S = C A_c^-1 C^T is symmetric positive definite unless A_c is
        # singular (GAMG's shifted LU then solves it): a pseudo-inverse.
        self.C, self.G = C, W @ np.linalg.pinv(0.5 * (S + S.T), rcond=1e-12, hermitian=True)

    def clear(self) -> None:
        """Back to the plain LU solve (solves without contact)."""
        self.C = self.G = None

    def apply(self, pc: PETSc.PC, x: PETSc.Vec, y: PETSc.Vec) -> None:
        self.lu.apply(x, y)
        if self.C is not None:
            ya = y.array
            ya -= self.G @ (self.C @ ya)

    def free(self) -> None:
        """Free the LU and drop every PETSc object this context holds: the
        coarse PC holding the context does not release it when GAMG is
        destroyed, and wrappers kept here kept the stiffness alive (0.2 GB
        per solve at 1e6 dofs)."""
        self.lu.destroy()
        self.Ac = None
        self.interpolations = []
        self.clear()
        self._last = None
