"""Checked direct solves with MUMPS.

MUMPS can meet a singular saddle-point or stiffness matrix (a piece of the
domain cut free by a crack, a constraint missing) and return an arbitrary
solution with only a warning. Every solve here reads the factorisation status,
the number of null pivots and the relative residual, and raises SolverError
naming the likely cause.
"""
from __future__ import annotations

import numpy as np
from petsc4py import PETSc

from .errors import SolverError


def create_lu_solver(A: PETSc.Mat, detect_null_pivots: bool = True) -> PETSc.KSP:
    """KSP preonly + LU (MUMPS) on A."""
    ksp = PETSc.KSP().create(PETSc.COMM_SELF)
    ksp.setOperators(A)
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType("lu")
    pc.setFactorSolverType("mumps")
    pc.setFactorSetUpSolverType()
    F = pc.getFactorMatrix()
    if detect_null_pivots:
        F.setMumpsIcntl(24, 1)  # null pivot detection
    F.setMumpsIcntl(4, 0)  # silent
    return ksp


def solve_checked(A: PETSc.Mat, b: PETSc.Vec, residual_tol: float = 1e-8,
                  what: str = "system") -> PETSc.Vec:
    """Solve A x = b by MUMPS LU; raise SolverError on any sign of failure."""
    ksp = create_lu_solver(A)
    x = b.duplicate()
    try:
        ksp.setUp()
    except PETSc.Error as e:
        raise SolverError(f"MUMPS factorisation of the {what} failed ({e}); the matrix is "
                          "probably singular: check that every piece of the domain (a crack may "
                          "cut it in two) has Dirichlet conditions fixing its rigid motion") from None
    F = ksp.getPC().getFactorMatrix()
    info = F.getMumpsInfog(1)
    if info < 0:
        raise SolverError(f"MUMPS failed on the {what}: INFOG(1) = {info}, INFOG(2) = "
                          f"{F.getMumpsInfog(2)}")
    null_pivots = F.getMumpsInfog(28)
    if null_pivots > 0:
        raise SolverError(
            f"the {what} is singular: MUMPS found {null_pivots} null pivot(s). Likely cause: a "
            "piece of the domain separated by a crack has no Dirichlet condition fixing its rigid "
            "motion, or an enriched dof sees no stiffness")
    ksp.solve(b, x)
    r = b.duplicate()
    A.mult(x, r)
    r.axpy(-1.0, b)
    bnorm = b.norm()
    rel = r.norm() / bnorm if bnorm > 0 else r.norm()
    if not np.all(np.isfinite(x.array)) or not rel <= residual_tol:
        raise SolverError(f"the solve of the {what} is inaccurate: relative residual {rel:.3g} "
                          f"> {residual_tol:g}; the matrix is singular or very ill-conditioned")
    ksp.destroy()
    return x
