"""The iterative path's preconditioner: a symmetric multiplicative Schwarz
sweep {crack band | GAMG | band} (Schwarz), with in 3D an inexact block
for the outer torus of a large front enrichment radius (InexactBlock), and
the band's exact factorisation by MUMPS (factor_band). Which dofs each
block holds: solvers/sweep_blocks.py; the band kept and updated across a
contact iteration: solvers/band_update.py; GAMG's coarsest solve with
contact: solvers/coarse_space.py."""
from __future__ import annotations

import typing

import numpy as np
from petsc4py import PETSc

from ..errors import SolverError
from .band_update import BandSolve
from .checked import factor_call, factor_relaxed, out_of_memory
from .pc_setup import set_up_pc


#: The Schwarz sweep skips its first band solve when the residual's band
#: part is below this fraction of the residual: so it is (1e-14 .. 1e-12)
#: in every CG iteration started by Schwarz.start, whose band equations
#: hold. One MUMPS band solve per iteration instead of two (4.5 ms each at
#: 1e6 dofs with contact), and the start itself saves iterations (2e5 dofs:
#: open crack 39 -> 36, contact 44 -> 41).
BAND_RESIDUAL_SKIP = 1e-10


#: The outer block's inexact solve: a fixed symmetric operator (CG);
#: ICC(1) took as many iterations (29 at 5.3e5 dofs) for a larger factor.
OUTER_PC = {"pc_type": "icc", "pc_factor_levels": 0, "pc_factor_shift_type": "positive_definite"}


class Schwarz:
    """PCSHELL context: a symmetric multiplicative sweep over two
    overlapping blocks, the crack band (exact, MUMPS) before and after one
    GAMG V-cycle on block 0 (the leading n0 dofs, the stiffness, or the
    given part of them: IterativeSolver._block0):

        z  = R1^T A11^-1 R1 r
        z += R0^T GAMG(R0 (r - A z))
        z += R1^T A11^-1 R1 (r - A z)

    i.e. I - M A = (I - B1 A)(I - B0 A)(I - B1 A): symmetric, and positive
    definite for a positive definite A (CG). Only the band's rows and
    columns of A are needed for the residual updates (small matrices).
    When R1 r = 0 the first line gives z = 0 and is skipped: one band solve
    per iteration. So it is in a Krylov iteration started by start(): the
    sweep ends with the band's exact solve, so R1 A M r = R1 r for every r;
    CG's residuals then keep R1 r = 0, and so do the basis vectors of
    GMRES preconditioned on the right (Arnoldi's v_j+1 combines A M v_j and
    the v_i; rounding grows as the iteration converges, and the sweep then
    does its first band solve). 3D friction at 4.9e5 dofs (56 GMRES
    iterations, one process, alternated twice): the sweeps 9.1 and 9.7 s
    started, 10.3 and 12.2 s not."""

    def __init__(self, A: PETSc.Mat, amg: PETSc.PC, n0: int, band_dofs: np.ndarray, symmetric: bool = True,
                 outer_dofs: np.ndarray | None = None, block0: np.ndarray | None = None,
                 band_factor: typing.Callable[[np.ndarray, PETSc.Mat, bool], BandSolve] | None = None):
        # Under MPI (a distributed A) band_dofs are this process's owned band
        # rows (global numbers) and block 0 its owned rows below n0, or of
        # block0 (sorted: a part of them, GAMG's operator's rows) if given.
        comm = A.getComm()
        size = A.getSize()[0]
        lo, hi = A.getOwnershipRange()
        self.amg = amg
        band = np.sort(band_dofs).astype(PETSc.IntType)
        self.is1 = PETSc.IS().createGeneral(band, comm=comm)
        if block0 is None:
            self.is0 = PETSc.IS().createStride(max(0, min(hi, n0) - lo), lo, 1, comm=comm)
        else:
            self.is0 = PETSc.IS().createGeneral(block0.astype(PETSc.IntType), comm=comm)
            n0 = comm.tompi4py().allreduce(block0.size)
        if A.getType() == PETSc.Mat.Type.PYTHON:  # IterativeSolver.saddle_matrix's (serial)
            self.A1, self.A01, A11 = A.getPythonContext().band_blocks(band)
            if block0 is not None:  # (A01: every stiffness row; block 0's)
                cols = PETSc.IS().createStride(self.A01.getSize()[1], 0, 1, comm=comm)
                A01 = self.A01.createSubMatrix(self.is0, cols)
                cols.destroy()
                self.A01.destroy()
                self.A01 = A01
        else:
            all_cols = PETSc.IS().createStride(hi - lo, lo, 1, comm=comm)  # (the owned columns)
            self.A1 = A.createSubMatrix(self.is1, all_cols)  # band rows, all columns
            all_cols.destroy()
            # Block 0's rows and the band's columns: for a symmetric A the
            # transpose of A1's (no copy: 0.06 GB at 8e4 dofs in 3D).
            self.A01 = None if symmetric else A.createSubMatrix(self.is0, self.is1)
            A11 = A.createSubMatrix(self.is1, self.is1)
        # The band's exact solve: factored, or a kept factorisation updated
        # (band_factor: KeptBand.factor, which takes A11 over;
        # solvers/band_update.py).
        if band_factor is None:
            self.band = BandSolve(factor_band(A11, symmetric), owned=True)
            A11.destroy()
        else:
            self.band = band_factor(band, A11, symmetric)
        self.r0 = PETSc.Vec().create(comm)
        self.r0.setSizes((self.is0.getLocalSize(), n0))
        self.r0.setUp()
        self.z0, self.t0 = self.r0.duplicate(), self.r0.duplicate()
        self.r1, self.z1, self.t1 = (self.A1.createVecLeft() for _ in range(3))
        self.full = self.A1.createVecRight() if self.A01 is None else None  # A1^T z1
        r = PETSc.Vec().create(comm)
        r.setSizes((hi - lo, size))
        r.setUp()
        # Block 0 by a scatter made once (VecGetSubVector of a general
        # index set makes one per call: 10 ms a sweep at 1e5 dofs).
        self.s0 = PETSc.Scatter().create(r, self.is0, self.r0, None)
        self.s1 = PETSc.Scatter().create(r, self.is1, self.r1, None)
        r.destroy()
        #: The outer torus's inexact block (serial, symmetric A), or None.
        self.outer = None if outer_dofs is None or outer_dofs.size == 0 else InexactBlock(A, outer_dofs)
        #: The CG KSP this sweep preconditions (set by IterativeSolver._krylov
        #: for the solve), whose residual norm apply() reads.
        self.cg: PETSc.KSP | None = None

    def apply(self, pc: PETSc.PC, r: PETSc.Vec, z: PETSc.Vec) -> None:
        fwd, rev = PETSc.ScatterMode.FORWARD, PETSc.ScatterMode.REVERSE
        ins, add = PETSc.InsertMode.INSERT_VALUES, PETSc.InsertMode.ADD_VALUES
        self.s1.scatter(r, self.r1, ins, fwd)
        # ||r||: CG has just computed it (unpreconditioned norm) before
        # calling the preconditioner.
        rnorm = self.cg.getResidualNorm() if self.cg is not None else r.norm()
        # r vanishes on the band (CG started by start(): every residual does,
        # up to rounding): the first band solve would give 0, and the V-cycle
        # acts on r itself. Else band first, and the V-cycle on r - A z (z the
        # band correction so far).
        band_first = self.r1.norm() > BAND_RESIDUAL_SKIP * rnorm
        self.s0.scatter(r, self.r0, ins, fwd)
        if band_first:
            self.band.solve(self.r1, self.z1)
            self.z1.scale(-1.0)
            if self.A01 is None:  # A01 = (A1's block-0 columns)^T
                self.A1.multTranspose(self.z1, self.full)
                self.s0.scatter(self.full, self.r0, add, fwd)  # r0 - A01 z1
            else:
                self.A01.multAdd(self.z1, self.r0, self.r0)  # r0 - A01 z1
            self.z1.scale(-1.0)
        z.set(0.0)
        if self.outer is not None:
            # The outer torus on r - A z, and block 0's residual updated by its
            # correction (z is the band's so far; serial and symmetric A).
            if band_first:
                self.s1.scatter(self.z1, z, add, rev)
            self.s0.scatter(self.outer.correct(r, z, z_zero=not band_first), self.t0, ins, fwd)
            self.r0.axpy(-1.0, self.t0)
        self.amg.apply(self.r0, self.z0)
        self.s0.scatter(self.z0, z, add, rev)
        if self.outer is not None:
            self.outer.correct(r, z, product=False)  # (no product: the band's A1 z follows)
        elif band_first:
            self.s1.scatter(self.z1, z, add, rev)
        # Band again on r - A z.
        self.A1.mult(z, self.t1)
        self.t1.aypx(-1.0, self.r1)
        self.band.solve(self.t1, self.z1)
        self.s1.scatter(self.z1, z, add, rev)

    def start(self, A: PETSc.Mat, b: PETSc.Vec, y: PETSc.Vec) -> None:
        """y += R1^T A11^-1 R1 (b - A y): the band's equations hold at y,
        and then at every CG iterate (R1 A z = R1 r for each preconditioned
        residual z, so R1 r stays 0), which lets apply() skip its first
        band solve."""
        r = b.duplicate()
        A.mult(y, r)
        r.aypx(-1.0, b)
        self.s1.scatter(r, self.r1, PETSc.InsertMode.INSERT_VALUES, PETSc.ScatterMode.FORWARD)
        r.destroy()
        self.band.solve(self.r1, self.z1)
        self.s1.scatter(self.z1, y, PETSc.InsertMode.ADD_VALUES, PETSc.ScatterMode.REVERSE)

    def destroy(self, pc: PETSc.PC) -> None:
        """Called by PETSc when a PC using this context is destroyed: the
        context outlives it (several Krylov attempts share it); free() frees."""

    def free(self) -> None:
        """Free the PETSc objects (idempotent)."""
        for obj in (self.is0, self.is1, self.A1, self.A01, self.band, self.r0, self.z0, self.t0, self.r1, self.z1,
                    self.t1, self.s0, self.s1, self.full):
            if obj is not None:
                obj.destroy()
        if self.outer is not None:
            self.outer.free()
        self.amg = self.cg = None


class InexactBlock:
    """A block of the Schwarz sweep solved inexactly by a fixed symmetric
    operator B, OUTER_PC's factor of its diagonal block (serial, symmetric
    A): correct(r, z) does z += R^T B R (r - A z) and returns A R^T (that
    correction) (the length of A), for the next block's residual."""

    def __init__(self, A: PETSc.Mat, dofs: np.ndarray):
        comm = A.getComm()
        self.size = int(dofs.size)
        self.idx = dofs
        iset = PETSc.IS().createGeneral(dofs.astype(PETSc.IntType), comm=comm)
        all_cols = PETSc.IS().createStride(A.getSize()[0], 0, 1, comm=comm)
        self.A2 = A.createSubMatrix(iset, all_cols)  # its rows, all columns
        all_cols.destroy()
        A22 = A.createSubMatrix(iset, iset)
        iset.destroy()
        A22.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        pc = set_up_pc(A22, "outer", OUTER_PC)
        # Only the factor is kept (what the PC applies), not A22 (0.2-0.3 GB
        # at 1e6 dofs).
        self.factor = pc.getFactorMatrix()
        pc.destroy()
        A22.destroy()
        self.r2, self.z2 = self.A2.createVecLeft(), self.A2.createVecLeft()
        self.full = self.A2.createVecRight()

    def correct(self, r: PETSc.Vec, z: PETSc.Vec, z_zero: bool = False, product: bool = True) -> PETSc.Vec | None:
        """z_zero: z is 0 (its product skipped); product: whether the
        caller needs A R^T (the correction) (else None)."""
        if z_zero:
            self.r2.array[:] = r.array[self.idx]
        else:
            self.A2.mult(z, self.r2)
            self.r2.array[:] = r.array[self.idx] - self.r2.array
        self.factor.solve(self.r2, self.z2)
        z.array[self.idx] += self.z2.array
        if not product:
            return None
        self.A2.multTranspose(self.z2, self.full)
        return self.full

    def free(self) -> None:
        for obj in (self.A2, self.factor, self.r2, self.z2, self.full):
            obj.destroy()


def factor_band(A11: PETSc.Mat, symmetric: bool = True) -> PETSc.KSP:
    """MUMPS LDL^T of the crack band (symmetric indefinite with multipliers;
    LU if not symmetric: friction's slip rows),
    with solve_checked's checks: a factorisation that runs out of workspace
    (INFOG(1) = -8, -9: delayed pivots of the ill-conditioned tip dofs) is
    retried with more (ICNTL(14)); an error or a null pivot raises."""
    ksp, error, info = factor_relaxed(A11, symmetric)
    oom = out_of_memory(ksp, error, "crack band block of the iterative solver", A11.getSize()[0])
    if oom is not None and info not in (-8, -9):
        ksp.destroy()
        raise oom
    null = factor_call(ksp, "getMumpsInfog", 28)
    if error is not None or info < 0 or null > 0:
        ksp.destroy()
        what = (f"MUMPS INFOG(1) = {info} (out of workspace even with ICNTL(14) = 400)" if info in (-8, -9) else
                f"MUMPS INFOG(1) = {info}, {null} null pivot(s)")
        cause = ("the band is too large or too ill-conditioned for the workspace" if info in (-8, -9) else
                 "a piece of the domain next to the crack has no Dirichlet condition, or a contact multiplier "
                 "sees no jump")
        verdict = "could not be factored" if info in (-8, -9) else "is singular"
        raise SolverError(f"the crack band block {verdict} ({what}): {cause}; use solver = 'direct'")
    return ksp
