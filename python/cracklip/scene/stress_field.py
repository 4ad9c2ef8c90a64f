"""Stress fields given as input: uniform, linear, or any callable sigma(x).

A stress field is used three ways: as the traction sigma n on a boundary
(``Traction(where, stress=...)``), as an initial (residual) stress of the
part (``Scene(initial_stress=...)``), and, through its divergence, as the
equivalent body force of that initial stress. ``evaluate_stress`` evaluates
every accepted form at points x (n, d) -> sigma (n, d, d).
"""
from __future__ import annotations

import dataclasses
import typing

import numpy as np

from ..errors import InputError, checked_keywords


StressLike = typing.Union["LinearStress", typing.Sequence[float], typing.Callable[[np.ndarray], np.ndarray]]


@checked_keywords
@dataclasses.dataclass(frozen=True)
class LinearStress:
    """sigma(x) = value + (x - x_0) gradient[0] + (y - y_0) gradient[1], in
    Voigt order (xx, yy, xy).

    Attributes:
        value: (sxx, syy, sxy) at the origin.
        gradient: ((d sxx/dx, d syy/dx, d sxy/dx), (d sxx/dy, d syy/dy, d sxy/dy)).
        origin: (x_0, y_0).

    Example: pure bending of a beam along x with its neutral axis at y = 0,
    sigma_xx = M y / I: LinearStress((0, 0, 0), gradient=((0, 0, 0), (M / I, 0, 0))).
    """
    value: tuple[float, float, float] = (0.0, 0.0, 0.0)
    gradient: tuple[tuple[float, float, float], tuple[float, float, float]] = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    origin: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self):
        v = np.asarray(self.value, dtype=float)
        g = np.asarray(self.gradient, dtype=float)
        o = np.asarray(self.origin, dtype=float)
        if v.shape != (3,) or g.shape != (2, 3) or o.shape != (2,):
            raise InputError(f"a linear stress needs value (sxx, syy, sxy), gradient ((3 numbers d/dx), "
                             f"(3 numbers d/dy)) and origin (x, y); got shapes {v.shape}, {g.shape}, {o.shape}")
        if not (np.all(np.isfinite(v)) and np.all(np.isfinite(g)) and np.all(np.isfinite(o))):
            raise InputError("a linear stress must be made of finite numbers")
        object.__setattr__(self, "value", tuple(v.tolist()))
        object.__setattr__(self, "gradient", tuple(map(tuple, g.tolist())))
        object.__setattr__(self, "origin", tuple(o.tolist()))

    def voigt(self, x: np.ndarray) -> np.ndarray:
        """(n, 3) xx, yy, xy at points (n, 2)."""
        d = np.asarray(x, dtype=float).reshape(-1, 2) - np.asarray(self.origin)
        return np.asarray(self.value)[None] + d @ np.asarray(self.gradient)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        return voigt_to_tensor(self.voigt(x))

    def divergence(self, x: np.ndarray) -> np.ndarray:
        """div sigma (n, 2): constant."""
        g = np.asarray(self.gradient)
        div = np.array([g[0, 0] + g[1, 2], g[0, 2] + g[1, 1]])
        return np.broadcast_to(div, (len(np.asarray(x).reshape(-1, 2)), 2)).copy()

    @property
    def is_uniform(self) -> bool:
        return not np.any(np.asarray(self.gradient))


@dataclasses.dataclass(frozen=True)
class UniformStress3D:
    """A uniform stress in 3D as a callable sigma(x): points (n, 3) ->
    (n, 3, 3); value (sxx, syy, szz, syz, sxz, sxy). A traction
    Traction(tag, stress=UniformStress3D(...)) loads a face with sigma n, a
    pressure p is UniformStress3D.pressure(p) (sigma = -p I)."""
    value: tuple[float, float, float, float, float, float]

    def __post_init__(self):
        v = np.asarray(self.value, dtype=float)
        if v.shape != (6,) or not np.all(np.isfinite(v)):
            raise InputError(f"a 3D stress needs 6 finite components (sxx, syy, szz, syz, sxz, sxy), got {self.value!r}")
        object.__setattr__(self, "value", tuple(float(c) for c in v))

    @classmethod
    def pressure(cls, p: float) -> "UniformStress3D":
        return cls((-p, -p, -p, 0.0, 0.0, 0.0))

    @property
    def tensor(self) -> np.ndarray:
        sxx, syy, szz, syz, sxz, sxy = self.value
        return np.array([[sxx, sxy, sxz], [sxy, syy, syz], [sxz, syz, szz]])

    def __call__(self, x: np.ndarray) -> np.ndarray:
        n = len(np.asarray(x).reshape(-1, 3))
        return np.broadcast_to(self.tensor, (n, 3, 3)).copy()


def voigt_to_tensor(s: np.ndarray) -> np.ndarray:
    """(n, 3) xx, yy, xy -> (n, 2, 2)."""
    out = np.empty((len(s), 2, 2))
    out[:, 0, 0], out[:, 1, 1] = s[:, 0], s[:, 1]
    out[:, 0, 1] = out[:, 1, 0] = s[:, 2]
    return out


def tensor_to_voigt(s: np.ndarray) -> np.ndarray:
    """(n, 2, 2) -> (n, 3) xx, yy, xy."""
    return np.stack([s[:, 0, 0], s[:, 1, 1], 0.5 * (s[:, 0, 1] + s[:, 1, 0])], axis=1)


def as_stress_field(value: StressLike, what: str) -> typing.Union[LinearStress, typing.Callable]:
    """A LinearStress for a constant (sxx, syy, sxy) or a LinearStress; a
    callable is kept (it must return (n, 2, 2) or (n, 3) for points (n, 2))."""
    if isinstance(value, LinearStress):
        return value
    if callable(value):
        return value
    v = np.asarray(value, dtype=float)
    if v.shape == (2, 2):
        if abs(v[0, 1] - v[1, 0]) > 1e-12 * max(np.abs(v).max(), 1e-300):
            raise InputError(f"{what}: the stress tensor must be symmetric, got {v.tolist()}")
        v = np.array([v[0, 0], v[1, 1], v[0, 1]])
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise InputError(f"{what}: a stress must be (sxx, syy, sxy), a LinearStress or a callable "
                         f"sigma(x); got {value!r}")
    return LinearStress(tuple(v))


def evaluate_stress(field, x: np.ndarray, what: str) -> np.ndarray:
    """sigma (n, d, d) of a stress field at points (n, d), checked; the
    field may return Voigt components instead: (n, 3) xx, yy, xy in 2D,
    (n, 6) xx, yy, zz, yz, xz, xy in 3D."""
    x = np.asarray(x, dtype=float)
    d = 3 if x.ndim == 2 and x.shape[1] == 3 else 2
    x = x.reshape(-1, d)
    s = np.asarray(field(x), dtype=float)
    voigt = 3 if d == 2 else 6
    if s.shape == (len(x), voigt):
        s = voigt_to_tensor(s) if d == 2 else voigt6_to_tensor(s)
    if s.shape != (len(x), d, d):
        names = "xx, yy, xy" if d == 2 else "xx, yy, zz, yz, xz, xy"
        raise InputError(f"{what}: the stress function returned shape {s.shape} for points of shape "
                         f"{x.shape}; it must return ({len(x)}, {d}, {d}) or ({len(x)}, {voigt}) ({names})")
    if not np.all(np.isfinite(s)):
        raise InputError(f"{what}: the stress evaluates to NaN or infinity")
    return s


def voigt6_to_tensor(s: np.ndarray) -> np.ndarray:
    """(n, 6) xx, yy, zz, yz, xz, xy -> (n, 3, 3)."""
    out = np.empty((len(s), 3, 3))
    for k, (i, j) in enumerate(((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))):
        out[:, i, j] = out[:, j, i] = s[:, k]
    return out


def divergence(field, x: np.ndarray, scale: float, what: str) -> np.ndarray:
    """div sigma (n, 2) at points: exact for a LinearStress, else by central
    differences with a step of 1e-5 of `scale` (the part's size)."""
    x = np.asarray(x, dtype=float).reshape(-1, 2)
    if isinstance(field, LinearStress):
        return field.divergence(x)
    h = 1e-5 * scale
    ex, ey = np.array([h, 0.0]), np.array([0.0, h])
    dsx = (evaluate_stress(field, x + ex, what) - evaluate_stress(field, x - ex, what)) / (2 * h)
    dsy = (evaluate_stress(field, x + ey, what) - evaluate_stress(field, x - ey, what)) / (2 * h)
    return np.stack([dsx[:, 0, 0] + dsy[:, 0, 1], dsx[:, 1, 0] + dsy[:, 1, 1]], axis=1)
