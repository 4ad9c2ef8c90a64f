"""Boundary conditions and loads a user describes: prescribed displacements,
tractions, point forces, and the steps of a load path (factors per load group)."""
from __future__ import annotations

import dataclasses
import math
import numbers
import typing

import numpy as np

from ..errors import BoundaryConditionError, InputError, checked_keywords
from .stress_field import as_stress_field


Value = typing.Union[float, typing.Callable[[np.ndarray], np.ndarray]]


VectorValue = typing.Union[typing.Sequence[float], typing.Callable[[np.ndarray], np.ndarray]]


@checked_keywords
@dataclasses.dataclass
class Dirichlet:
    """Prescribed displacement.

    Attributes:
        where: a boundary tag name or number, or a point (x, y) (in 3D
            (x, y, z)) that is a mesh node (in 2D not on a crack's line:
            its node would be one lip's or the other's by the mesh).
        component: 0 (x), 1 (y), 2 (z, in 3D) or None (every component).
        value: a number, or a callable f(x) with x of shape (n, d) (d the
            space dimension) returning (n,) for one component or (n, d) for
            all; a callable f(x, side)
            also receives the crack side (n,) of each point (+1 / -1) and may
            jump across a crack (an exact crack field on a cut boundary).
        group: load group whose factor (Scene.load_path) scales the value.
        label: the name of the condition in results.json's reactions (a scene
            file's "dirichlet[i]"; the conditions of one label are summed);
            default: its index and where it acts.
    """
    where: typing.Union[str, int, tuple[float, float]]
    component: typing.Optional[int] = None
    value: Value = 0.0
    group: str = "default"
    label: str = ""

    def __post_init__(self):
        _check_group(self.group, f"Dirichlet condition on {self.where!r}")
        if self.component not in (None, 0, 1, 2):
            raise BoundaryConditionError(f"Dirichlet component must be 0 (x), 1 (y), 2 (z, in 3D) or None (all), "
                                         f"got {self.component!r}")
        v = self.value
        if not callable(v) and (isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(v)):
            # (a string was read as its number at the solve, a vector failed
            # there with a TypeError from float())
            raise InputError(f"Dirichlet condition on {self.where!r}: value must be a finite number or a callable "
                             f"f(x), got {v!r}" + (f" (a string: write the number itself, value={_number(v)})"
                                                   if isinstance(v, str) and _number(v) is not None else
                                                   "; for a vector give one Dirichlet per component (component = "
                                                   "0, 1, 2), or a callable returning (n, d) with component None"
                                                   if np.ndim(v) == 1 else ""))


@checked_keywords
@dataclasses.dataclass
class Traction:
    """Surface traction (force per length) on a tagged boundary.

    Attributes:
        where: boundary tag name or number.
        value: (t_x, t_y), or a callable f(x) with x (n, 2) returning (n, 2).
        stress: instead of value, a stress field whose traction sigma n (n
            the outward normal) loads the boundary: (sxx, syy, sxy), a
            stress_field.LinearStress (e.g. bending), or a callable sigma(x)
            returning (n, 2, 2).
        group: load group whose factor (Scene.load_path) scales it.
    """
    where: typing.Union[str, int]
    value: typing.Optional[VectorValue] = None
    stress: typing.Any = None
    group: str = "default"

    def __post_init__(self):
        _check_group(self.group, f"traction on {self.where!r}")
        if (self.value is None) == (self.stress is None):
            raise InputError(f"traction on {self.where!r}: give exactly one of value (a traction) or stress "
                             "(a stress field whose sigma n is applied)")
        if self.stress is not None:
            self.stress = as_stress_field(self.stress, f"traction on {self.where!r}")
        elif not callable(self.value):
            v = np.asarray(self.value, dtype=float)
            if v.shape not in ((2,), (3,)) or not np.all(np.isfinite(v)):
                raise InputError(f"traction on {self.where!r}: a constant value must be finite numbers (t_x, t_y), "
                                 f"or (t_x, t_y, t_z) in 3D, got {self.value!r}")


@checked_keywords
@dataclasses.dataclass
class PointForce:
    """A concentrated force (force, in 2D per unit thickness) at the mesh node
    nearest to a point (which must lie within one element of a node).

    Attributes:
        point: (x, y).
        value: (F_x, F_y).
        group: load group whose factor (Scene.load_path) scales it.
    """
    point: tuple[float, float]
    value: tuple[float, float]
    group: str = "default"

    def __post_init__(self):
        _check_group(self.group, f"point force at {self.point!r}")
        p = np.asarray(self.point, dtype=float)
        v = np.asarray(self.value, dtype=float)
        if p.shape not in ((2,), (3,)) or v.shape != p.shape or not (np.all(np.isfinite(p))
                                                                        and np.all(np.isfinite(v))):
            raise InputError(f"a point force needs a point (x, y) and a value (F_x, F_y) of finite numbers (in 3D "
                             f"(x, y, z) and (F_x, F_y, F_z)), got point {self.point!r}, value {self.value!r}")
        self.point, self.value = tuple(p.tolist()), tuple(v.tolist())


def _number(text: str) -> float | None:
    """The number a string spells, or None."""
    try:
        return float(text)
    except ValueError:
        return None


def _check_group(group, what: str) -> None:
    if not isinstance(group, str) or not group:
        raise InputError(f"{what}: a load group must be a non-empty name, got {group!r}")


@checked_keywords
@dataclasses.dataclass
class LoadStep:
    """One step of a load path: the factor of each named load group at the
    end of the step. A group not named keeps its factor from the step before
    (0 before the first step: the path starts unloaded).

    Attributes:
        factors: group name -> factor.
        name: label in outputs (default "step k").
    """
    factors: dict[str, float]
    name: str = ""

    def __post_init__(self):
        if not isinstance(self.factors, dict) or not self.factors:
            raise InputError(f"load step {self.name!r}: factors must be a non-empty mapping group -> factor, "
                             f"got {self.factors!r}")
        for g, f in self.factors.items():
            _check_group(g, f"load step {self.name!r}")
            if isinstance(f, bool) or not isinstance(f, numbers.Real) or not math.isfinite(f):
                raise InputError(f"load step {self.name!r}: the factor of group {g!r} must be a finite number, "
                                 f"got {f!r}")
