"""Typed errors: every bad input names what is wrong and how to fix it."""
from __future__ import annotations


class CracklipError(Exception):
    """Base class of all cracklip errors."""


class InputError(CracklipError, ValueError):
    """A scene input is invalid (material, mesh, crack, boundary condition)."""


class MaterialError(InputError):
    """Material parameters out of range, or not numbers."""


class MeshError(InputError):
    """The mesh is not a 2D triangle mesh cracklip can use."""


class CrackGeometryError(InputError):
    """A crack is malformed or does not meet the mesh."""


class BoundaryConditionError(InputError):
    """Boundary conditions are missing, inconsistent or do not fix rigid motion."""


class SolverError(CracklipError, RuntimeError):
    """The linear solve failed (singular matrix, factorisation error, large residual)."""


class InputFileError(InputError):
    """An input file (a table of turning points, of da/dN, of beta) is
    unreadable or holds a bad value; the message names the file, the line
    and the column. Attributes: path, line (1-based, None: the whole file),
    column (1-based, None: the whole line)."""

    def __init__(self, message: str, path=None, line: int | None = None, column: int | None = None):
        super().__init__(message)
        self.path, self.line, self.column = path, line, column


class ModelSizeError(MeshError):
    """The model asked for would not fit in the machine's memory (estimated before meshing)."""
