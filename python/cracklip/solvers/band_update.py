"""The crack band's factorisation kept across the solves of a contact or
friction state iteration, and updated where the band changed in few rows.

Between two solves of an active-set or friction iteration the stiffness
is the same; what changes are the rows of the multipliers whose state
(open, stick, slip) or slip direction changed, and, for a symmetric saddle
point, their columns. The band block A (the Schwarz sweep's exact block,
cracklip.solvers.schwarz) then differs from a matrix A0 already factored
by E = A - A0 = U V of small rank k, and Sherman-Morrison-Woodbury solves
with A exactly from A0's factorisation F:

    A^-1 r = F^-1 r - G S^-1 V F^-1 r,   G = F^-1 U,   S = I + V G,

G by one solve of k right-hand sides at once (MUMPS solves a block of
right-hand sides about ten times faster per column than one at a time:
0.003 s against 0.028 s a column on a 3.4e4-row band with 3e7 factor
entries, whose factorisation takes 1.3-1.5 s), S a dense k x k LU. U V
takes the changed multiplier rows as they are (U = their unit columns,
V = E's rows) and the other changed entries by their columns (U = E's
columns there, V = unit rows): for friction the rows alone (the bordered
matrix's columns C^T do not change), for a symmetric saddle point the
changed multipliers' rows and columns. A band that changed in more than
MAX_RANK_FRACTION of its rows, or whose S is ill-conditioned, is factored
again and becomes the new A0, unless it is unsymmetric (friction, solved
by GMRES, which needs no exact block) and changed only in its multiplier
rows by at most STALE_CHANGE of each row's largest entry: A0's
factorisation then preconditions it as it is (stale; the friction
iteration's last Newton turns of the slip directions, where every slipping
multiplier's rows change a little). Serial only: under mpirun every band is
factored afresh (the band is distributed there).

Measured on the corner crack of demos/scenes/corner_crack_closure.toml at
half its element sizes (1.6e5 dofs, a 3.6e4-row band, 10 friction
iterations): see docs/contact.md."""
from __future__ import annotations

import logging
import typing

import numpy as np
import scipy.linalg
import scipy.sparse as sp
from petsc4py import PETSc

#: Update (not factor again) while the rank k of the change is at most this
#: fraction of the band's rows: k columns solved at once cost about
#: 0.003 k s against 1.3-1.5 s for the factorisation of a 3.4e4-row band,
#: so 0.005 (k <= 170 there) keeps an update below about 40 % of a
#: factorisation.
MAX_RANK_FRACTION = 0.005
#: ... and at least this many (small bands).
MIN_RANK = 16
#: S's condition number above which the band is factored again (the
#: update's rounding grows with it).
MAX_CONDITION = 1e8
#: An unsymmetric band (friction; solved inside GMRES, which needs no exact
#: block) whose multiplier rows changed by at most this fraction of each
#: row's largest entry, and nothing else, is not factored again: the kept
#: factorisation of the earlier band preconditions it as it is (stale).
#: The closed penny's last Newton turns of the slip directions: see
#: docs/contact.md.
STALE_CHANGE = 0.01

logger = logging.getLogger(__name__)


def _csr(A: PETSc.Mat) -> sp.csr_matrix:
    ai, aj, av = A.getValuesCSR()
    n, m = A.getSize()
    return sp.csr_matrix((av, aj, ai), shape=(n, m))  # (getValuesCSR gives copies)


def low_rank_change(E: sp.csr_matrix, rows: np.ndarray) -> tuple[np.ndarray, sp.csr_matrix, np.ndarray,
                                                                  sp.csc_matrix]:
    """E = P_R^T E[R, :] + E'[:, C] P_C with R the nonzero rows of E among
    `rows` (the multipliers') and C the nonzero columns of E' (E without
    those rows): (R, E[R, :], C, E'[:, C]). k = len(R) + len(C)."""
    E = E.tocsr()
    nz_rows = np.flatnonzero(np.diff(E.indptr) > 0)
    R = np.intersect1d(nz_rows, rows)
    keep = np.ones(E.shape[0], dtype=bool)
    keep[R] = False
    rest = sp.diags(keep.astype(float)) @ E
    rest.eliminate_zeros()
    rest = rest.tocsc()
    C = np.flatnonzero(np.diff(rest.indptr) > 0)
    return R, E[R, :], C, rest[:, C]


class BandSolve:
    """x = A^-1 b for the band block A, by a factorisation of A or of an
    earlier band A0 with the Woodbury correction (module doc). solve(b, x)
    on PETSc vectors, as a KSP's. updated: from a kept factorisation (no
    factorisation of this band); rank: the update's k."""

    def __init__(self, ksp: PETSc.KSP, owned: bool, G: np.ndarray | None = None,
                 S: tuple | None = None, V: sp.csr_matrix | None = None, updated: bool = False,
                 stale: bool = False):
        self.ksp = ksp
        self.owned = owned
        self.updated = updated
        self.stale = stale
        self.G, self.S, self.V = G, S, V
        self.rank = 0 if G is None else G.shape[1]

    def solve(self, b: PETSc.Vec, x: PETSc.Vec) -> None:
        self.ksp.solve(b, x)
        if self.G is not None:
            with x as xa:  # (the vector's state increased: no stale cached norm)
                xa -= self.G @ scipy.linalg.lu_solve(self.S, self.V @ xa)

    def destroy(self) -> None:
        if self.owned and self.ksp is not None:
            self.ksp.destroy()
        self.ksp = self.G = self.S = self.V = None


class KeptBand:
    """The last band factored (its dofs, its matrix, its factorisation),
    kept by an IterativeSolver across its solves; factor() gives the
    BandSolve of a new band: the kept factorisation updated (same dofs, a
    change of small rank), or a new one that is kept instead. factor() takes
    the band's matrix over (keeps or destroys it); a band solved only once,
    as without contact, is read into scipy only if a next one comes.
    first_multiplier: the first multiplier's global dof (the stiffness's
    size); rows at or beyond it are multiplier rows."""

    def __init__(self, factor: typing.Callable[[PETSc.Mat, bool], PETSc.KSP], first_multiplier: int):
        self._factor = factor
        self.first_multiplier = first_multiplier
        self.dofs: np.ndarray | None = None
        # (the factorisation's own operator, so kept at no cost; scipy once an
        # update has read it)
        self._A0: PETSc.Mat | sp.csr_matrix | None = None
        self.ksp: PETSc.KSP | None = None
        self.symmetric: bool | None = None
        #: Updates and factorisations so far.
        self.updates = self.factorisations = 0

    def factor(self, dofs: np.ndarray, A11: PETSc.Mat, symmetric: bool) -> BandSolve:
        if A11.getComm().getSize() > 1:  # (distributed band: no update)
            self.factorisations += 1
            try:
                return BandSolve(self._factor(A11, symmetric), owned=True)
            finally:
                A11.destroy()
        if self.ksp is not None and self.symmetric == symmetric and np.array_equal(self.dofs, dofs):
            A = _csr(A11)
            update = self._update(A, dofs)
            if update is not None:
                A11.destroy()
                return update
        self.free()
        self.ksp = self._factor(A11, symmetric)
        self.dofs, self._A0, self.symmetric = np.array(dofs, copy=True), A11, symmetric
        self.factorisations += 1
        return BandSolve(self.ksp, owned=False)

    def _A0_csr(self) -> sp.csr_matrix:
        if isinstance(self._A0, PETSc.Mat):
            A0 = _csr(self._A0)
            self._A0.destroy()
            self._A0 = A0
        return self._A0

    def _update(self, A: sp.csr_matrix, dofs: np.ndarray) -> BandSolve | None:
        limit = max(MIN_RANK, MAX_RANK_FRACTION * A.shape[0])
        multipliers = np.flatnonzero(np.sort(dofs) >= self.first_multiplier)
        # The multiplier rows first (a few thousand rows: cheap), which rule
        # out most large changes (a new state everywhere) before E is formed:
        # k is their number, twice that for a symmetric saddle point (their
        # columns changed too).
        A0 = self._A0_csr()
        Em = (A[multipliers] - A0[multipliers]).tocsr()
        Em.eliminate_zeros()
        k_rows = np.count_nonzero(np.diff(Em.indptr))
        if k_rows * (2 if self.symmetric else 1) > limit:
            if not self.symmetric and self._close(A, A0, multipliers, Em):
                logger.debug("band: %d multiplier rows changed by at most %g of their size: the kept "
                             "factorisation preconditions it", k_rows, STALE_CHANGE)
                self.updates += 1
                return BandSolve(self.ksp, owned=False, updated=True, stale=True)
            logger.debug("band: %d multiplier rows changed (limit %d): factored again", k_rows, limit)
            return None
        E = (A - A0).tocsr()
        E.eliminate_zeros()
        if E.nnz == 0:
            self.updates += 1
            return BandSolve(self.ksp, owned=False, updated=True)
        R, ER, C, EC = low_rank_change(E, multipliers)
        k = len(R) + len(C)
        if k > limit:
            logger.debug("band: a change of rank %d (%d rows, %d columns; limit %d): factored again", k, len(R),
                         len(C), limit)
            return None
        n = A.shape[0]
        U = np.zeros((n, k))
        U[R, np.arange(len(R))] = 1.0
        if len(C):
            U[:, len(R):] = EC.toarray()
        V = sp.vstack([ER, sp.csr_matrix((np.ones(len(C)), (np.arange(len(C)), C)), shape=(len(C), n))],
                      format="csr")
        G = self._solve_block(U)
        S = np.eye(k) + V @ G
        cond = np.linalg.cond(S)
        if cond > MAX_CONDITION:
            logger.debug("band: the update's capacitance matrix has condition number %.2g: factored again", cond)
            return None
        self.updates += 1
        return BandSolve(self.ksp, owned=False, G=G, S=scipy.linalg.lu_factor(S), V=V, updated=True)

    @staticmethod
    def _close(A: sp.csr_matrix, A0: sp.csr_matrix, multipliers: np.ndarray, Em: sp.csr_matrix) -> bool:
        """Whether A has A0's entries, the same everywhere but in the
        multiplier rows (Em: A - A0 there), and there no entry changed by
        more than STALE_CHANGE of its row's largest in A0 (the slip
        directions turned a little: the friction iteration's last solves)."""
        if not (np.array_equal(A.indptr, A0.indptr) and np.array_equal(A.indices, A0.indices)):
            return False
        in_multiplier_row = np.zeros(A.shape[0], dtype=bool)
        in_multiplier_row[multipliers] = True
        elsewhere = ~np.repeat(in_multiplier_row, np.diff(A.indptr))
        if not np.array_equal(A.data[elsewhere], A0.data[elsewhere]):
            return False
        change = abs(Em).max(axis=1).toarray().ravel()
        size = abs(A0[multipliers]).max(axis=1).toarray().ravel()
        return bool(np.all(change <= STALE_CHANGE * size))

    def _solve_block(self, U: np.ndarray) -> np.ndarray:
        """F^-1 U, all columns in one solve."""
        n, k = U.shape
        F = self.ksp.getPC().getFactorMatrix()
        B = PETSc.Mat().createDense([n, k], array=np.asfortranarray(U), comm=PETSc.COMM_SELF)
        X = PETSc.Mat().createDense([n, k], comm=PETSc.COMM_SELF)
        X.setUp()
        try:
            F.matSolve(B, X)
            return np.array(X.getDenseArray(), copy=True)
        finally:
            B.destroy()
            X.destroy()

    def free(self) -> None:
        if self.ksp is not None:
            self.ksp.destroy()
        if isinstance(self._A0, PETSc.Mat):
            self._A0.destroy()
        self.ksp = self._A0 = self.dofs = None

    destroy = free  # (IterativeSolver's release calls destroy)
