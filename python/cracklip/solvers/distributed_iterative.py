"""The iterative path on several processes (mpirun; issue 40 step 2).

The same solver as the serial one (solvers/iterative.py: CG preconditioned
by the symmetric Schwarz sweep {crack band by MUMPS | one GAMG V-cycle |
band} in the phantom-node basis), on a distributed model
(model/distributed.py): only what the numbering gives changes, and this
class supplies it in the global numbering, each process its owned rows:

* the phantom-node transform T (per Heaviside pseudo-node: u = p,
  a = s (p - q) / 2) as a distributed matrix. A pseudo-node belongs to the
  owner of its base node, so every row of T couples dofs of one process
  (no communication in T y, T^T r). T^T A T is computed in A's storage on
  the rows it changes, as the serial path does (transform_in_place): each
  process its owned rows, the T rows of their columns gathered from the
  owners; PETSc's parallel PtAP only if a coupling lies outside A's
  pattern;
* the rigid-body near-nullspace on the owned standard and Heaviside rows
  (about the mean of all processes' nodes), orthonormalised over the
  processes;
* the crack band: the owned rows of the enriched nodes, of their rings of
  neighbours and every enriched dof. A process marks the band on its cells
  (owned and ghost) and the marks are summed over the processes, so a
  neighbour owned by another process is in that process's band too;
* the tip dofs GAMG leaves out in 3D, and the residual of the original
  system (T^-T r) for the accuracy check.

The band's MUMPS factorisation and GAMG are PETSc's parallel ones. GAMG
aggregates each process's rows apart, so the iteration count may differ
from the serial one by a few; K agrees with the serial solve to the Krylov
tolerance (KRYLOV_RTOL).

Contact and friction: the saddle point is one distributed AIJ bordering
T^T A T (solvers/saddle.py bordered_matrix: the multiplier rows on the
last process; contact.frictionless.solve_bordered), the constraints in
the phantom basis (B T: solvers/rescaling.py times_basis). The sweep is
the serial one with every owned multiplier row in the band (the band's
parallel MUMPS factorisation holds them all), the contact band grown
through the distributed graph of T^T A T, CG (GMRES for friction's
unsymmetric rows), the residual checked on the original system. GAMG's
coarsest solve is left unconstrained (constrained_coarse: the serial
path's ConstrainedCoarse is a serial LU of the coarse operator): on the
test scenes 2 processes took 0 to 3 CG iterations more than serial (the
block under pressure 22 / 19, the crack at a hole 22 / 21, the cantilever
26 / 25 at its first active set).
"""
from __future__ import annotations

import typing

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from ..scene.processes import on_all
from .phantom import changed_symmetric, phantom_change
from .iterative import IterativeSolver
from .pc_setup import product_data_cleared
from .near_nullspace import rigid_mode_nodes, rigid_motions
from .sweep_blocks import crack_band, tip_dofs
if typing.TYPE_CHECKING:
    from ..model.model import XfemModel


class DistributedPhantomBasis:
    """T and T^-1 of the phantom-node basis (solvers/phantom.py) as
    distributed PETSc matrices over the global numbering (module doc)."""

    def __init__(self, model: "XfemModel"):
        dm = model.dofs
        d = model.gdim
        lay = model.layout
        nstd = lay.num_std_nodes
        heav = np.flatnonzero(np.asarray(lay.kind) == 0)
        base = np.asarray(lay.node, dtype=np.int64)[heav]
        side = np.asarray(lay.node_side, dtype=np.float64)[heav]
        e = dm.global_dofs((d * (nstd + heav)[:, None] + np.arange(d)).ravel())
        s = dm.global_dofs((d * base[:, None] + np.arange(d)).ravel())
        sgn = np.repeat(side, d)
        mine = (e >= 0) & dm.owned(e)
        e, s, sgn = e[mine], s[mine], sgn[mine]
        self.e, self.s, self.sgn = e, s, sgn
        self.comm = dm.comm
        self.lo = dm.start * d
        self.n_local, self.n_global, self.bs = dm.num_owned * d, dm.num_global * d, d
        self.T = self._matrix(e, s, 0.5 * sgn, -0.5 * sgn)       # a = s/2 p - s/2 q; u = p
        self.T_inv = self._matrix(e, s, np.ones_like(sgn), -2.0 * sgn)  # q = u - 2 s a; p = u

    def _matrix(self, e: np.ndarray, s: np.ndarray, at_s: np.ndarray, at_e: np.ndarray) -> PETSc.Mat:
        """The identity on the owned rows but rows e: at_s in column s, at_e in column e."""
        n, lo = self.n_local, self.lo
        rows = np.arange(n)
        plain = np.ones(n, dtype=bool)
        plain[e - lo] = False
        r = np.concatenate([rows[plain], e - lo, e - lo])
        c = np.concatenate([rows[plain] + lo, s, e])
        v = np.concatenate([np.ones(int(plain.sum())), at_s, at_e])
        M = sp.csr_matrix((v, (r, c)), shape=(n, self.n_global))
        M.sort_indices()
        A = PETSc.Mat().createAIJ(((n, self.n_global), (n, self.n_global)), bsize=self.bs, comm=self.comm,
                                  csr=(M.indptr.astype(PETSc.IntType), M.indices.astype(PETSc.IntType), M.data))
        return A

    def destroy(self) -> None:
        self.T.destroy()
        self.T_inv.destroy()


class DistributedIterativeSolver(IterativeSolver):
    """IterativeSolver on one process's part of a distributed model: the
    global, owned counterparts of the serial solver's numbering (module
    doc). transform(A) gives T^T A T and the basis, whose distributed T
    carries the loads (T^T b) and the solution (u = T y) between the bases
    (solvers.choice.to_distributed_solver_basis, rescaling.from_basis)."""

    constrained_coarse = False  # (a serial LU of GAMG's coarse operator: not distributed)

    def _phantom_basis(self) -> DistributedPhantomBasis:
        return DistributedPhantomBasis(self.model)

    def _num_dofs(self) -> int:
        return self.model.dofs.num_global * self.model.gdim

    def _owned_rows(self, local: np.ndarray) -> np.ndarray:
        """The owned global rows of local dofs (sorted, unique)."""
        g = self.model.dofs.global_dofs(local)
        return np.unique(g[(g >= 0) & self.model.dofs.owned(g)])

    def _crack_band(self, rings: int) -> np.ndarray:
        """The owned band rows: every process's marks (crack_band on its own
        cells) summed, so that each owner sees the rings another process
        found around its enriched nodes."""
        dm = self.model.dofs
        mark = PETSc.Vec().createMPI((dm.num_owned * dm.d, dm.num_global * dm.d), bsize=dm.d, comm=dm.comm)
        mark.set(0.0)
        g = dm.global_dofs(crack_band(self.model, rings))
        g = g[g >= 0]
        mark.setValues(g.astype(PETSc.IntType), np.ones(g.size), addv=PETSc.InsertMode.ADD_VALUES)
        mark.assemble()
        band = np.flatnonzero(mark.array > 0) + dm.start * dm.d
        mark.destroy()
        return band.astype(np.int64)

    def _tip_dofs(self) -> np.ndarray:
        return self._owned_rows(tip_dofs(self.model))

    def _outer_torus(self) -> tuple[np.ndarray, np.ndarray]:
        """None split off: under MPI the whole band is solved exactly."""
        none = np.zeros(0, dtype=np.int64)
        return none, none

    def _rigid_modes(self) -> np.ndarray:
        """(owned rows, 3 or 6): the rigid motions on the owned standard and
        Heaviside rows (about the mean of all owned nodes), orthonormal
        over the processes."""
        model, dm = self.model, self.model.dofs
        local, xy = rigid_mode_nodes(model)
        block = dm.block[local]
        mine = (block >= dm.start) & (block < dm.start + dm.num_owned)
        comm = dm.comm
        n_own = model.V.dofmap.index_map.size_local
        sums = comm.allreduce(np.concatenate([model.x[:n_own].sum(axis=0), [n_own]]))
        centre = sums[:-1] / max(sums[-1], 1.0)
        return rigid_motions(xy[mine] - centre, block[mine] - dm.start, dm.num_owned * dm.d, comm)

    def transform(self, A: PETSc.Mat) -> tuple[PETSc.Mat, DistributedPhantomBasis]:
        """T^T A T: A itself, changed in place where its pattern allows
        (transform_in_place), else a new matrix by PETSc's PtAP (A left as
        it is): use A only through the returned matrix."""
        A_t = transform_in_place(self.basis, A)
        if A_t is None:
            with product_data_cleared():
                A_t = A.PtAP(self.basis.T)
        A_t.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        self._K = A_t
        return A_t, self.basis

    def _grow_band(self, K: PETSc.Mat, rings: int) -> np.ndarray:
        """The owned band rows grown by `rings` rings through K's graph
        (symmetric): each ring marks the columns of the band's owned rows
        on their owners (summed marks, as _crack_band)."""
        band = self._band_k
        for _ in range(rings):
            band = np.union1d(band, reached_rows(K, band)).astype(np.int64)
        return band

    def _multiplier_rows(self, A: PETSc.Mat) -> np.ndarray:
        """The owned multiplier rows (contact.frictionless.solve_bordered's
        saddle points: on the last process)."""
        lo, hi = A.getOwnershipRange()
        return np.arange(max(self.n, lo), hi, dtype=np.int64)

    def _original_residual(self, A: PETSc.Mat, y: PETSc.Vec, b: PETSc.Vec) -> float:
        """||A_orig u - b_orig|| / ||b_orig|| over all processes: T^-T on
        the stiffness rows, the multiplier rows (owned by the last process)
        as they are."""
        r = b.duplicate()
        A.mult(y, r)
        r.axpy(-1.0, b)
        k = self.basis.n_local  # (this process's stiffness rows come first)
        comm = self.model.dofs.comm
        norms = []
        for v in (r, b):
            s, so = self.basis.T_inv.createVecs()
            s.array[:] = v.array_r[:k]
            self.basis.T_inv.multTranspose(s, so)
            tail = float(np.dot(v.array_r[k:], v.array_r[k:]))
            norms.append(float(np.sqrt(so.norm() ** 2 + comm.allreduce(tail))))
            for o in (s, so):
                o.destroy()
        r.destroy()
        rn, bn = norms
        return rn / bn if bn > 0 else rn

    def destroy(self) -> None:
        super().destroy()
        self.basis.destroy()


def reached_rows(A: PETSc.Mat, rows: np.ndarray) -> np.ndarray:
    """Collective: the sorted owned rows of A (square, symmetric pattern)
    that any process's `rows` (its owned rows, global numbers) reach: the
    columns of those rows, marked on their owners and summed over the
    processes. Work in proportion to the rows given."""
    comm = A.getComm()
    lo, hi = A.getOwnershipRange()
    isrow = PETSc.IS().createGeneral(np.asarray(rows).astype(PETSc.IntType), comm=comm)
    iscol = PETSc.IS().createStride(hi - lo, lo, 1, comm=comm)  # (each process its own: every column)
    sub = A.createSubMatrix(isrow, iscol)
    _, cols, _ = sub.getValuesCSR()  # (global columns)
    for o in (sub, isrow, iscol):
        o.destroy()
    mark = A.createVecRight()
    mark.set(0.0)
    mark.setValues(cols.astype(PETSc.IntType), np.ones(cols.size), addv=PETSc.InsertMode.ADD_VALUES)
    mark.assemble()
    out = (np.flatnonzero(mark.array > 0) + lo).astype(np.int64)
    mark.destroy()
    return out


def transform_in_place(basis: DistributedPhantomBasis, A: PETSc.Mat) -> PETSc.Mat | None:
    """T^T A T in A's storage (A returned, changed), or None (A untouched)
    if a changed entry lies outside A's pattern on any process or the
    result fails the symmetry check (phantom.changed_symmetric).

    As the serial solvers.phantom.transform_matrix: T differs from the
    identity only on the Heaviside nodes' dofs J, so T^T A T differs from A
    only in the rows coupled to J: (A T)[r, :] off J, T_JJ^T (A T)[J, :] on
    J. Each process takes its owned rows coupled to any process's J, read
    from A's pattern as the serial transform does (the columns of the J
    rows, marked on their owners: reached_rows), their columns' rows of T
    from the columns' owners (one scatter of the base dof and side of every
    Heaviside dof), and adds the change into its rows. (Not from the
    model's crack band: a process may hold an enriched node of another as
    a ghost without the cut cells that enrich it, and then missed a row of
    its own coupled to that node's Heaviside dofs through a cell of the
    other process; T^T A T came out unsymmetric there and the contact
    solve of the block under pressure wrong on some partitions.) The
    rows of J it owns need only rows of T it owns (a pseudo-node belongs to
    its base node's owner). Work and memory in proportion to the band;
    no copy of A (PtAP: the matrix again and the product A T)."""
    comm = basis.comm
    lo, hi = A.getOwnershipRange()
    J = np.union1d(basis.s, basis.e).astype(np.int64)  # the owned touched dofs
    R = np.union1d(reached_rows(A, J), J)
    isrow = PETSc.IS().createGeneral(R.astype(PETSc.IntType), comm=comm)
    iscol = PETSc.IS().createStride(hi - lo, lo, 1, comm=comm)
    sub = A.createSubMatrix(isrow, iscol)  # (its columns are A's: each process gave its own range)
    indptr, indices, data = sub.getValuesCSR()
    sub.destroy()
    isrow.destroy()
    iscol.destroy()
    cols = np.unique(indices)
    side, base = _heaviside_columns(basis, cols)
    # Every column the rows reach, and the base dofs of the Heaviside ones.
    heav = side != 0.0
    U = np.union1d(cols, base[heav])
    ci = np.searchsorted(U, cols)
    S = sp.csr_matrix((data, np.searchsorted(U, indices), indptr), shape=(R.size, U.size))
    # T's rows for the columns (in U): a = s/2 p - s/2 q on a Heaviside dof, else the identity.
    hc = np.flatnonzero(heav)
    tr = np.concatenate([np.flatnonzero(~heav), hc, hc])
    tc = np.concatenate([ci[~heav], np.searchsorted(U, base[hc]), ci[hc]])
    tv = np.concatenate([np.ones(int((~heav).sum())), 0.5 * side[hc], -0.5 * side[hc]])
    T_cols = sp.csr_matrix((tv, (tr, tc)), shape=(cols.size, U.size))
    on_cols = sp.csr_matrix((np.ones(cols.size), (ci, np.arange(cols.size))), shape=(U.size, cols.size))
    ST = (S @ on_cols @ T_cols).tocsr()  # (A T) on the rows R, columns in U
    # T_JJ (owned J): rows s: the identity; rows e: s/2 at s, -s/2 at e.
    pe, ps = np.searchsorted(J, basis.e), np.searchsorted(J, basis.s)
    std = np.setdiff1d(np.arange(J.size), pe)
    T_JJ = sp.csr_matrix((np.concatenate([np.ones(std.size), 0.5 * basis.sgn, -0.5 * basis.sgn]),
                          (np.concatenate([std, pe, pe]), np.concatenate([std, ps, pe]))), shape=(J.size, J.size))
    delta, order, fits = phantom_change(S, ST, R, J, T_JJ)
    if not on_all(fits, comm):
        return None
    return A if changed_symmetric(A, delta, order, U) else None


def _heaviside_columns(basis: DistributedPhantomBasis, cols: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For global dofs `cols` (sorted), the side s of each that is a
    Heaviside dof (0 elsewhere) and its base dof, from their owners."""
    comm = basis.comm
    lo = basis.lo
    side = PETSc.Vec().createMPI((basis.n_local, basis.n_global), comm=comm)
    base = side.duplicate()
    side.set(0.0)
    base.set(-1.0)
    side.array[basis.e - lo] = basis.sgn
    base.array[basis.e - lo] = basis.s  # (exact in doubles below 2^53)
    out = []
    for v in (side, base):
        w = PETSc.Vec().createSeq(cols.size, comm=PETSc.COMM_SELF)
        src = PETSc.IS().createGeneral(cols.astype(PETSc.IntType), comm=PETSc.COMM_SELF)
        sc = PETSc.Scatter().create(v, src, w, None)
        sc.scatter(v, w, addv=PETSc.InsertMode.INSERT_VALUES, mode=PETSc.ScatterMode.FORWARD)
        out.append(w.array.copy())
        for o in (w, src, sc, v):
            o.destroy()
    return out[0], np.rint(out[1]).astype(np.int64)
