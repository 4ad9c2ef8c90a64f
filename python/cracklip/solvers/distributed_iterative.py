"""The iterative path on several processes (mpirun; issue 40 step 2).

The same solver as the serial one (solvers/iterative.py: CG preconditioned
by the symmetric Schwarz sweep {crack band by MUMPS | one GAMG V-cycle |
band} in the phantom-node basis), on a distributed model
(model/distributed.py): only what the numbering gives changes, and this
class supplies it in the global numbering, each process its owned rows:

* the phantom-node transform T (per Heaviside pseudo-node: u = p,
  a = s (p - q) / 2) as a distributed matrix. A pseudo-node belongs to the
  owner of its base node, so every row of T couples dofs of one process
  (no communication in T y, T^T r); T^T A T is PETSc's parallel PtAP;
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
path's _ConstrainedCoarse is a serial LU of the coarse operator): on the
test scenes 2 processes took 0 to 3 CG iterations more than serial (the
block under pressure 22 / 19, the crack at a hole 22 / 21, the cantilever
26 / 25 at its first active set).
"""
from __future__ import annotations

import typing

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from .iterative import IterativeSolver, crack_band, rigid_mode_nodes, rigid_motions, tip_dofs
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
        """T^T A T (a new matrix; A is left as it is)."""
        A_t = A.PtAP(self.basis.T)
        A_t.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        self._K = A_t
        return A_t, self.basis

    def _grow_band(self, K: PETSc.Mat, rings: int) -> np.ndarray:
        """The owned band rows grown by `rings` rings through K's graph
        (symmetric): each ring marks the columns of the band's owned rows
        on their owners (summed marks, as _crack_band)."""
        lo = K.getOwnershipRange()[0]
        indptr, indices, _ = K.getValuesCSR()  # (the owned rows, global columns)
        band = self._band_k
        mark = K.createVecRight()
        for _ in range(rings):
            mark.set(0.0)
            rows = band - lo
            start, count = indptr[rows], indptr[rows + 1] - indptr[rows]
            cols = indices[np.repeat(start - np.cumsum(count) + count, count) + np.arange(count.sum())]
            mark.setValues(cols.astype(PETSc.IntType), np.ones(cols.size), addv=PETSc.InsertMode.ADD_VALUES)
            mark.assemble()
            band = np.union1d(band, np.flatnonzero(mark.array > 0) + lo).astype(np.int64)
        mark.destroy()
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
