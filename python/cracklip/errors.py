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


class KeywordError(InputError, TypeError):
    """A keyword argument the function or class does not take (a misspelling, most often): the
    message names the nearest keywords it does take. A TypeError too, as Python's own is."""


def checked_keywords(obj):
    """Decorator of a class (its __init__, e.g. a dataclass's) or a function: a keyword argument it
    does not take is a KeywordError naming the nearest ones it does ("Options() takes no keyword
    'contcat'; did you mean 'contact'?") instead of Python's bare TypeError. Positional arguments,
    the signature (help, inspect) and the behaviour are unchanged."""
    import difflib
    import functools
    import inspect

    target = obj.__init__ if isinstance(obj, type) else obj
    params = inspect.signature(target).parameters
    if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params.values()):
        return obj
    known = {n for n, p in params.items() if n != "self" and p.kind is not inspect.Parameter.POSITIONAL_ONLY}
    names = [n for n in params if n in known and not n.startswith("_")]  # the ones to suggest
    label = obj.__qualname__ + "()"

    @functools.wraps(target)
    def wrapper(*args, **kwargs):
        for key in kwargs:
            if key not in known:
                near = difflib.get_close_matches(key, names, n=3, cutoff=0.6)
                hint = (f"did you mean {' or '.join(repr(n) for n in near)}?" if near
                        else f"it takes {', '.join(names)}")
                raise KeywordError(f"{label} takes no keyword {key!r}; {hint}")
        return target(*args, **kwargs)

    if isinstance(obj, type):
        obj.__init__ = wrapper
        return obj
    return wrapper
