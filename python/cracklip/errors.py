"""Typed errors: every bad input names what is wrong and how to fix it."""


class CracklipError(Exception):
    """Base class of all cracklip errors."""


class InputError(CracklipError, ValueError):
    """A scene input is invalid (material, mesh, crack, boundary condition)."""


class MaterialError(InputError):
    """Material parameters out of range."""


class MeshError(InputError):
    """The mesh is not a 2D triangle mesh cracklip can use."""


class CrackGeometryError(InputError):
    """A crack is malformed or does not meet the mesh."""


class BoundaryConditionError(InputError):
    """Boundary conditions are missing, inconsistent or do not fix rigid motion."""


class SolverError(CracklipError, RuntimeError):
    """The linear solve failed (singular matrix, factorisation error, large residual)."""


class ModelSizeError(MeshError):
    """The model asked for would not fit in the machine's memory (estimated before meshing)."""
