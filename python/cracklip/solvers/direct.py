"""The solver-path interface, and the direct path: MUMPS LDL^T with every check."""
from __future__ import annotations

import typing

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from .checked import scipy_from_petsc, solve_checked
from .saddle import assembled_bordered, saddle_matrix


class LinearSolver:
    """A checked solver path for a model's systems.

    transform(A) gives the matrix of the system the path solves and the T
    of its basis (or None; see to_solver_basis); solve(A, b) solves a system in that basis: the
    stiffness, or a saddle-point system [K B^T; B D] whose first num_dofs
    unknowns are the stiffness's."""
    name = "direct"

    def transform(self, A: PETSc.Mat) -> tuple[PETSc.Mat, sp.csr_matrix | None]:
        return A, None

    def solve(self, A: PETSc.Mat, b: PETSc.Vec, residual_tol: float, what: str,
              x0: np.ndarray | None = None, symmetric: bool = True,
              contact_points: int | None = None, rtol: float | None = None) -> PETSc.Vec:
        """symmetric = False for an unsymmetric system (frictional contact:
        the slip rows): LU instead of LDL^T, GMRES instead of CG.
        contact_points: the number of contact points the multipliers belong
        to (default: one multiplier per point, frictionless; friction has
        two), which sizes the iterative path's crack band. rtol: an inexact
        solve (an inner step of the friction iteration, never its answer):
        the iterative path stops its Krylov iteration at this relative
        residual instead of KRYLOV_RTOL and checks the residual against it;
        a direct path solves exactly anyway."""
        raise NotImplementedError

    def stiffness(self, A: PETSc.Mat) -> typing.Any:
        """The stiffness as saddle_matrix() takes it (the direct path: a
        scipy CSR copy, converted once per contact solve)."""
        return scipy_from_petsc(A)

    def saddle_matrix(self, K: typing.Any, B: sp.csr_matrix, active: np.ndarray,
                      S: sp.csr_matrix | None = None) -> PETSc.Mat:
        """The frictionless saddle point [K B_a^T; B_a D] (solvers.saddle.
        saddle_matrix; S the multipliers' stabilization or None) on K from
        stiffness()."""
        return saddle_matrix(K, B, active, S)

    def bordered_matrix(self, K: typing.Any, C: sp.csr_matrix, rows: sp.csr_matrix,
                        constraints: sp.csr_matrix) -> PETSc.Mat:
        """Frictional contact's unsymmetric saddle point [K C^T; rows] on K
        from stiffness() (assembled; constraints, the rows of C that hold
        as constraints, serve the iterative path)."""
        return assembled_bordered(K, C, rows)

    def destroy(self) -> None:
        pass


class DirectSolver(LinearSolver):
    """MUMPS LDL^T with every check of checked.solve_checked."""
    name = "direct"

    def solve(self, A: PETSc.Mat, b: PETSc.Vec, residual_tol: float, what: str,
              x0: np.ndarray | None = None, symmetric: bool = True,
              contact_points: int | None = None, rtol: float | None = None) -> PETSc.Vec:
        return solve_checked(A, b, residual_tol, what=what, symmetric=symmetric)
