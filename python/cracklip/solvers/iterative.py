"""The iterative (AMG) path: Krylov in the phantom-node basis, preconditioned
by an overlapping Schwarz sweep (IterativeSolver).

Its parts, one file each:

* the phantom-node (Hansbo) basis of the Heaviside pairs (solvers/
  phantom.py): every Heaviside basis function becomes N_i times the
  indicator of one side of the crack, so the stiffness looks like two
  standard meshes glued along the uncut part, an ordinary elasticity
  operator that smoothed aggregation can coarsen (GAMG_OPTIONS: a strength
  threshold that drops the rounding-level couplings across the crack);
* GAMG's near-nullspace, the rigid motions on the standard and phantom
  dofs (solvers/near_nullspace.py);
* which dofs each block of the sweep holds: GAMG's block 0, the crack band
  (the enriched nodes, in 2D their first ring of neighbours, every tip dof
  and every multiplier; wider with contact), the outer torus of a large 3D
  front enrichment radius (solvers/sweep_blocks.py);
* the sweep {band by MUMPS LDL^T | one GAMG V-cycle | band again}, with
  {band | outer | GAMG | outer | band} where the outer torus has a block of
  its own (solvers/schwarz.py); the band's factorisation kept and updated
  across a contact iteration's solves (solvers/band_update.py); GAMG's
  coarsest solve keeping the coarse space's main crack-opening modes
  closed during a contact solve (solvers/coarse_space.py);
* the saddle points of contact applied block by block around the stiffness
  (solvers/saddle.py), and distributed under mpirun
  (solvers/distributed_iterative.py).

IterativeSolver runs CG (also for the frictionless saddle point, with
GMRES(30) as the fallback) and GMRES(30) for friction's unsymmetric saddle
point. The Krylov iteration starts where the band's equations hold, so they
hold at every iterate and the sweep's first band solve is skipped. The GAMG
hierarchy depends on the stiffness only, so it is built once and reused by
every active-set iteration; the friction iteration's early solves stop at a
loose Krylov tolerance (contact/friction.py INEXACT_RTOL). Every solve path
takes it: solve.solve, the load path and friction (load_path.solve_path),
hence growth. Which path runs: solvers/choice.py.

Every iterative solve is checked like the direct one (checked.
solve_checked): the relative residual of the original (untransformed)
system must be at most Options.residual_tol, else SolverError names the
likely cause. The Krylov tolerance is much tighter (KRYLOV_RTOL) so that
SIFs, pressures and energies equal the direct path's.
"""
from __future__ import annotations

import logging
import time
import typing
import weakref

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from ..errors import SolverError
from ..scene.processes import on_all
from .band_update import KeptBand
from .checked import record_solve, solve_checked
from .coarse_space import ConstrainedCoarse
from .direct import LinearSolver
from .pc_setup import set_up_pc
from .phantom import phantom_basis, transform_matrix
from .near_nullspace import rigid_modes
from .saddle import BorderedOperator, SaddleOperator
from .schwarz import Schwarz, factor_band
from .sweep_blocks import (BAND_RINGS, TIP_DOFS_OUT_OF_GAMG, band_rings, block0_dofs, crack_band, grow_band,
                           outer_block, tip_dofs)
if typing.TYPE_CHECKING:
    from ..model.model import XfemModel


logger = logging.getLogger(__name__)


#: Relative (unpreconditioned) residual at which the Krylov iteration stops.
#: At 1e-10 the SIFs, pressures and energies equal the direct path's to
#: 1e-8 relative on the test scenes (tests/test_solvers.py; the errors there
#: are 1e-10 .. 1e-12). The last decade is the expensive one: at 1e6 dofs the
#: bilateral-contact solve needs 52 iterations to 1e-10 and 71 to 1e-11.
KRYLOV_RTOL = 1e-10


#: GMRES restart, when GMRES takes over from CG on a saddle point (see
#: IterativeSolver._solve): at 1e6 dofs (bilateral, 1-ring band) GMRES(30)
#: was faster than full GMRES (13.7 s vs 15.5 s): orthogonalising against up
#: to 54 vectors of 1e6 entries costs more than 20 extra V-cycles.
GMRES_RESTART = 30


#: Krylov iterations before the iterative path gives up.
MAX_ITERATIONS = 1000


#: GAMG on the standard + phantom dofs (pinned: PETSc's defaults change
#: between versions). The strength threshold must be > 0: T^T A T leaves
#: rounding-level couplings across the crack, and with threshold 0 the
#: aggregates straddle the crack (78-140 iterations instead of ~40). 0.002
#: rather than 0.01: the same CG / GMRES iterations (3D penny 28, 3D
#: contact 30, 3D friction 15+7+21+9 against 15+7+22+8; 2D open crack 37
#: against 36) for a set-up 17-30 % cheaper (the coarse levels sparser:
#: 3D penny at 2e5 dofs 7.05 -> 5.90 s, plain P1 at 5e5 18.6 -> 12.8 s,
#: alternated in one process; docs/speed.md).
GAMG_OPTIONS = {
    "pc_type": "gamg",
    "pc_gamg_type": "agg",
    "pc_gamg_threshold": 0.002,
    "pc_gamg_coarse_eq_limit": 1000,
    "mg_levels_ksp_type": "chebyshev",
    "mg_levels_pc_type": "jacobi",
    "mg_levels_esteig_ksp_type": "cg",
    "mg_levels_ksp_chebyshev_esteig_steps": 20,
    # The prolongator smoother's eigenvalue estimate by CG, as GAMG does by
    # itself for a matrix flagged SPD (plain DOLFINx): K' is SPD, but the flag
    # would also make a MUMPS fallback factor it without pivoting. GMRES
    # (the default otherwise) cost 0.26 s more at 1e6 dofs.
    "pc_gamg_esteig_ksp_type": "cg",
}


class IterativeSolver(LinearSolver):
    """Krylov + overlapping symmetric multiplicative Schwarz in the
    phantom-node basis (module docstring): CG for the stiffness and for the
    frictionless saddle point (the sweep ends with the band's exact solve,
    so CG works on the constrained problem; GMRES(30) if CG breaks down),
    GMRES(30) for friction's unsymmetric saddle point.

    Block 0 is in 2D the whole transformed stiffness K', tip dofs included
    (no copy, no scatter: the stiffness's dofs come first in every system;
    the tip dofs' rows have no rigid modes, and the band solves them
    exactly): Westergaard at 2e5 dofs, radius 0.2, takes 23 iterations so
    and 62 with K' without its tip dofs as block 0 (a hole in the AMG's
    operator). In 3D it is K' without the tip dofs (TIP_DOFS_OUT_OF_GAMG),
    which the band and the outer block hold. Its
    GAMG hierarchy is built on the first solve and reused by every later
    one (the active-set iterations of contact only change multiplier rows);
    with contact its coarsest solve is constrained by the active
    multipliers (ConstrainedCoarse), set anew for every solve.
    """
    name = "iterative"

    def __init__(self, model: "XfemModel", fallback: bool = False):
        self.model = model
        self.fallback = fallback
        self.basis = self._phantom_basis()
        self.n = self._num_dofs()
        self._band_k = self._crack_band(BAND_RINGS[self.model.gdim])
        self._outer, beyond = self._outer_torus()
        # The exact band of a solve without contact when the outer torus
        # has its own block: without the outer torus beyond its overlap.
        self._band_inner = np.setdiff1d(self._band_k, beyond) if self._outer.size else self._band_k
        self._bands: dict[int, np.ndarray] = {}
        self._T_inv_t: sp.csr_matrix | None = None
        self._K: PETSc.Mat | None = None
        self._amg: PETSc.PC | None = None
        self._K_amg: PETSc.Mat | None = None
        #: Block 0's owned rows (GAMG's), or None: the whole stiffness.
        self._block0: np.ndarray | None = None
        self._n_amg = self.n  # (GAMG's operator's size, over the processes)
        self._coarse: ConstrainedCoarse | None = None
        # The hierarchy holds a Python PC (its coarse solve), which PETSc must
        # not destroy after the interpreter's shutdown (a segfault at exit):
        # destroy() frees it, and so does this finalizer, at the latest when
        # the interpreter exits.
        self._owned: list[typing.Any] = []
        self._release = weakref.finalize(self, _release, self._owned)
        #: The last crack band factored, updated where the next one changed
        #: in few rows (a contact or friction state iteration's solves).
        self._kept_band = KeptBand(factor_band, self.n)
        self._owned.append(self._kept_band)

    #: Whether GAMG's coarsest solve is replaced by ConstrainedCoarse (the
    #: contact solves' constrained coarse space; a serial LU of the coarse
    #: operator).
    constrained_coarse = True

    # What the model's numbering gives (serial: the kernels' local dofs;
    # solvers.distributed_iterative overrides them with the global, owned ones).
    def _phantom_basis(self):
        return phantom_basis(self.model)

    def _num_dofs(self) -> int:
        return self.model.num_dofs

    def _crack_band(self, rings: int) -> np.ndarray:
        return crack_band(self.model, rings)

    def _rigid_modes(self) -> np.ndarray:
        return rigid_modes(self.model)

    def _outer_torus(self) -> tuple[np.ndarray, np.ndarray]:
        """(the outer block's dofs, those the exact band leaves to it): outer_block."""
        return outer_block(self.model, self._band_k.size)

    def _tip_dofs(self) -> np.ndarray:
        return tip_dofs(self.model)

    # The system in the phantom basis.
    def transform(self, A: PETSc.Mat) -> tuple[PETSc.Mat, sp.csr_matrix]:
        A_t = transform_matrix(self.basis, A)
        A_t.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        self._K = A_t
        return A_t, self.basis.T

    def stiffness(self, A: PETSc.Mat) -> PETSc.Mat:
        """The stiffness itself: saddle_matrix() does not copy it."""
        return A

    def saddle_matrix(self, K: PETSc.Mat, B: sp.csr_matrix, active: np.ndarray,
                      S: sp.csr_matrix | None = None) -> PETSc.Mat:
        """[K B_a^T; B_a D] as a Python PETSc matrix applied blockwise around
        K (SaddleOperator; no copy of the stiffness: at 1e6 dofs the
        assembled saddle point cost 0.1-0.25 s and the scipy copy of K it
        needs another 0.25-0.3 s)."""
        op = SaddleOperator(K, B, active, S)
        size = op.n + op.m
        A = PETSc.Mat().createPython([size, size], context=op, comm=PETSc.COMM_SELF)
        A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        A.setUp()
        return A

    def bordered_matrix(self, K: PETSc.Mat, C: sp.csr_matrix, rows: sp.csr_matrix,
                        constraints: sp.csr_matrix) -> PETSc.Mat:
        """Friction's [K C^T; rows] as a Python PETSc matrix applied
        blockwise around K (BorderedOperator: no copy of the stiffness);
        constraints (rows of C) keep GAMG's coarse space closed as B_a does
        for the frictionless saddle point."""
        op = BorderedOperator(K, C, rows, constraints)
        size = op.n + op.m
        A = PETSc.Mat().createPython([size, size], context=op, comm=PETSc.COMM_SELF)
        A.setUp()
        return A

    def destroy(self) -> None:
        self._release()
        self._amg = self._coarse = None

    def _contact_band(self, m: int) -> np.ndarray:
        """The stiffness dofs of the band with m multipliers (band_rings
        rings, grown through the stiffness's graph), kept for later solves."""
        rings = band_rings(self.model.gdim, m)
        if rings not in self._bands:
            K = self._K
            self._bands[rings] = self._band_k if rings == 1 or K is None else self._grow_band(K, rings - 1)
        return self._bands[rings]

    def _grow_band(self, K: PETSc.Mat, rings: int) -> np.ndarray:
        """The band dofs grown by `rings` rings through K's graph."""
        return grow_band(K, self._band_k, rings)

    def _multiplier_rows(self, A: PETSc.Mat) -> np.ndarray:
        """The rows of A beyond the stiffness's (the multipliers') that
        belong to the band: all of them (under MPI the owned ones)."""
        return np.arange(self.n, A.getSize()[0])

    def _block0_pc(self, A: PETSc.Mat) -> tuple[PETSc.PC, bool]:
        """The GAMG PC of block 0, built once ((pc, reused)): on the
        stiffness given to transform(), or on its rows and columns
        self._block0 when GAMG leaves the tip dofs out (TIP_DOFS_OUT_OF_GAMG)."""
        if self._amg is not None:
            return self._amg, True
        if self._K is None:
            raise SolverError("IterativeSolver.solve needs the system from IterativeSolver.transform")
        K = self._K
        modes = self._rigid_modes()
        tip = self._tip_dofs()
        if TIP_DOFS_OUT_OF_GAMG[self.model.gdim] and K.getComm().tompi4py().allreduce(tip.size):
            lo, hi = K.getOwnershipRange()
            self._block0 = block0_dofs(self.n, lo, hi, tip)
            iset = PETSc.IS().createGeneral(self._block0.astype(PETSc.IntType), comm=K.getComm())
            iset.setBlockSize(K.getBlockSize())  # (whole nodes: GAMG aggregates nodes)
            K = self._K_amg = self._K.createSubMatrix(iset, iset)
            iset.destroy()
            self._n_amg = K.getSize()[0]
            self._owned.append(K)
            modes = modes[self._block0 - lo]  # (0 on the tip rows: still orthonormal)
        self._amg = self._gamg(K, modes)
        self._owned.append(self._amg)
        if self.constrained_coarse:
            self._coarse = ConstrainedCoarse(self._amg, self._block0)
            self._owned.append(self._coarse)
        return self._amg, False

    def _gamg(self, A: PETSc.Mat, modes: np.ndarray) -> PETSc.PC:
        """A set-up GAMG PC on A with the rigid modes (orthonormal columns,
        rows of A: rigid_modes) as near-nullspace."""
        vecs = []
        for j in range(modes.shape[1]):
            v = A.createVecRight()
            v.array[:] = modes[:, j]
            vecs.append(v)
        A.setNearNullSpace(PETSc.NullSpace().create(vectors=vecs, comm=A.getComm()))
        return set_up_pc(A, "amg", GAMG_OPTIONS)

    def solve(self, A: PETSc.Mat, b: PETSc.Vec, residual_tol: float, what: str,
              x0: np.ndarray | None = None, symmetric: bool = True,
              contact_points: int | None = None, rtol: float | None = None) -> PETSc.Vec:
        """Solve A y = b (A in the phantom basis: the stiffness given to
        transform(), or a saddle-point system extending it, unsymmetric
        with friction); check the residual of the original system. With
        fallback (solver = "auto") a failed iterative solve is repeated by
        MUMPS (LDL^T, or LU if not symmetric), which either solves the
        system or names what is singular. rtol: an inexact solve
        (LinearSolver.solve): the Krylov iteration stops at this relative
        residual, and the check takes 10 rtol as residual_tol (the original
        basis's residual is not the phantom basis's)."""
        if rtol is not None:
            residual_tol = max(residual_tol, 10.0 * rtol)
        try:
            return self._solve(A, b, residual_tol, what, x0, symmetric, contact_points, rtol)
        except SolverError as e:
            if not self.fallback:
                raise
            logger.warning("%s: the iterative solver failed (%s); solving with MUMPS instead", what, e)
            if A.getType() == PETSc.Mat.Type.PYTHON:  # saddle_matrix's: MUMPS needs it assembled
                A_aij = A.getPythonContext().assembled()
                try:
                    return solve_checked(A_aij, b, residual_tol, what=what, symmetric=symmetric)
                finally:
                    A_aij.destroy()
            return solve_checked(A, b, residual_tol, what=what, symmetric=symmetric)

    def _solve(self, A: PETSc.Mat, b: PETSc.Vec, residual_tol: float, what: str,
               x0: np.ndarray | None, symmetric: bool = True, contact_points: int | None = None,
               rtol: float | None = None) -> PETSc.Vec:
        size = A.getSize()[0]
        m = size - self.n
        t0 = time.perf_counter()
        if x0 is not None:
            y = self._started(A, b, x0, KRYLOV_RTOL if rtol is None else rtol, residual_tol)
            if y is not None:  # (the friction iteration's last check, most often)
                record_solve({"what": what, "size": size, "relative_residual": self._original_residual(A, y, b),
                              "solver": "iterative", "method": _method("cg" if symmetric else "gmres"),
                              "iterations": 0, "amg_dofs": self._n_amg, "setup_reused": True,
                              "rtol": KRYLOV_RTOL if rtol is None else rtol, "t_setup": 0.0,
                              "t_total": time.perf_counter() - t0})
                return y
        shell = None
        try:
            pc0, reused = self._block0_pc(A)
            t_amg = time.perf_counter() - t0
            # The band's width follows the contact points (friction has two
            # multipliers per point: normal, tangential).
            # Without contact the outer torus (if any) is a block of its own.
            split = m == 0 and symmetric and self._outer.size > 0
            band_dofs = self._band_inner if split else np.concatenate([
                self._contact_band(m if contact_points is None else contact_points), self._multiplier_rows(A)])
            shell = Schwarz(A, pc0, self.n, band_dofs, symmetric, self._outer if split else None, self._block0,
                             self._kept_band.factor)
            t_band = time.perf_counter() - t0 - t_amg
            if A.getType() == PETSc.Mat.Type.PYTHON and m > 0 and self._coarse is not None:
                self._coarse.constrain(A.getPythonContext().Ba_petsc)
            t_setup = time.perf_counter() - t0
            # CG also for the saddle point: the sweep ends with an exact solve
            # of the band, which holds every multiplier and every dof they
            # touch, so the preconditioned residual always satisfies the
            # constraints and CG works on the constrained (positive definite)
            # problem, as with a constraint preconditioner. If it breaks down
            # anyway, GMRES (which needs no definiteness) takes over.
            # An unsymmetric system (friction) goes to GMRES at once.
            attempts = ["gmres"] if not symmetric else ["cg"] if m == 0 else ["cg", "gmres"]
            for krylov in attempts:
                y, its, reason = self._krylov(A, b, shell, krylov, x0, what, rtol)
                rel = self._original_residual(A, y, b)
                ok = on_all(bool(np.all(np.isfinite(y.array))), y.getComm().tompi4py()) and rel <= residual_tol
                if ok or krylov == attempts[-1]:
                    break
                logger.info("%s: CG stopped at relative residual %.3g after %d iterations (reason %s); "
                            "GMRES(%d) instead", what, rel, its, reason, GMRES_RESTART)
                y.destroy()
        finally:
            if shell is not None:
                shell.free()
            if self._coarse is not None:
                self._coarse.clear()
        method = _method(krylov)
        record_solve({"what": what, "size": size, "relative_residual": rel, "solver": "iterative",
                      "method": method, "iterations": int(its),
                      "band": int(A.getComm().tompi4py().allreduce(band_dofs.size)),  # (over the processes)
                      "outer": int(shell.outer.size if shell is not None and shell.outer is not None else 0),
                      # (the band solved from the kept factorisation of an earlier one: band_update.py)
                      "band_updated": bool(shell is not None and shell.band.updated),
                      "band_update_rank": int(shell.band.rank if shell is not None else 0),
                      "band_stale": bool(shell is not None and shell.band.stale),
                      "amg_dofs": self._n_amg, "setup_reused": reused, "rtol": KRYLOV_RTOL if rtol is None else rtol,
                      "t_setup": t_setup, "t_amg_setup": t_amg, "t_band_setup": t_band,
                      "t_total": time.perf_counter() - t0})
        logger.info("%s: %d iterations (%s), relative residual %.3g", what, its, method, rel)
        if not ok:
            cause = ("it stopped after the iteration limit" if reason == PETSc.KSP.ConvergedReason.DIVERGED_MAX_IT
                     else f"PETSc reason {reason}")
            y.destroy()
            raise SolverError(
                f"the iterative solve of the {what} is inaccurate: relative residual {rel:.3g} > "
                f"{residual_tol:g} after {its} iterations ({cause}); the matrix is singular (a piece of the "
                "domain cut free by a crack, a multiplier without a jump) or too ill-conditioned for the "
                "AMG preconditioner (slivers cut by the crack, a large tip enrichment radius): use "
                "solver = 'direct'")
        return y

    def _started(self, A: PETSc.Mat, b: PETSc.Vec, x0: np.ndarray, rtol: float,
                 residual_tol: float) -> PETSc.Vec | None:
        """x0 as a vector if it already solves A y = b to the Krylov
        tolerance and passes the check (no preconditioner set up: a band
        factorisation saved), else None."""
        y = A.createVecRight()
        y.array[:] = x0
        r = b.duplicate()
        A.mult(y, r)
        r.axpy(-1.0, b)
        done = r.norm() <= rtol * b.norm()
        r.destroy()
        if done and self._original_residual(A, y, b) <= residual_tol:
            return y
        y.destroy()
        return None

    def _krylov(self, A: PETSc.Mat, b: PETSc.Vec, shell: "Schwarz", krylov: str, x0: np.ndarray | None,
                what: str, rtol: float | None = None) -> tuple[PETSc.Vec, int, int]:
        """One Krylov solve of A y = b preconditioned by the Schwarz sweep: (y, iterations, reason)."""
        ksp = PETSc.KSP().create(A.getComm())
        try:
            ksp.setOperators(A)
            ksp.setType(krylov)
            if krylov == "gmres":
                ksp.setGMRESRestart(GMRES_RESTART)
                ksp.setPCSide(PETSc.PC.Side.RIGHT)  # (the unpreconditioned norm; Schwarz.start)
            ksp.setTolerances(rtol=KRYLOV_RTOL if rtol is None else rtol, atol=0.0, max_it=MAX_ITERATIONS)
            ksp.setNormType(PETSc.KSP.NormType.UNPRECONDITIONED)
            pc = ksp.getPC()
            pc.setType("python")
            pc.setPythonContext(shell)
            # No wrapper of the PC may outlive ksp.destroy(): PETSc then keeps
            # the PC, and the PC the matrix (K' leaked, 0.2 GB per solve at
            # 1e6 dofs).
            del pc
            y = b.duplicate()
            y.set(0.0)
            if x0 is not None:
                y.array[:] = x0
            shell.start(A, b, y)  # (CG, and GMRES on the right: Schwarz's doc)
            ksp.setInitialGuessNonzero(True)
            shell.cg = ksp if krylov == "cg" else None
            try:
                ksp.solve(b, y)
            except PETSc.Error as e:
                raise SolverError(f"the iterative solve of the {what} failed in PETSc ({e}); the crack band "
                                  "block is probably singular: check that every piece of the domain has "
                                  "Dirichlet conditions fixing its rigid motion, or use solver = 'direct'") from None
            return y, ksp.getIterationNumber(), ksp.getConvergedReason()
        finally:
            shell.cg = None
            ksp.destroy()

    def _original_residual(self, A: PETSc.Mat, y: PETSc.Vec, b: PETSc.Vec) -> float:
        """||A_orig u - b_orig|| / ||b_orig|| from the transformed system:
        r_orig = T^-T r (T^T r_orig = r), on the stiffness rows; multiplier
        rows are the same in both bases."""
        r = b.duplicate()
        A.mult(y, r)
        r.axpy(-1.0, b)
        ra, ba = r.array.copy(), b.array.copy()
        r.destroy()
        if self._T_inv_t is None:
            self._T_inv_t = self.basis.T_inv.T.tocsr()
        Ti = self._T_inv_t
        ra[:self.n] = Ti @ ra[:self.n]
        ba[:self.n] = Ti @ ba[:self.n]
        bn = float(np.linalg.norm(ba))
        rn = float(np.linalg.norm(ra))
        return rn / bn if bn > 0 else rn


def _method(krylov: str) -> str:
    """The iterative path's method as solve records name it."""
    return (f"{'CG' if krylov == 'cg' else f'GMRES({GMRES_RESTART})'} + "
            "Schwarz {MUMPS crack band | GAMG | band} (phantom basis)")


def _release(owned: list[typing.Any]) -> None:
    """Free an IterativeSolver's PETSc objects (last made, first freed)."""
    while owned:
        obj = owned.pop()
        (obj.free if isinstance(obj, ConstrainedCoarse) else obj.destroy)()


