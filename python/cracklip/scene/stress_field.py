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
    """sigma(x) = value + (x - origin) . gradient, in Voigt order: in 2D
    (xx, yy, xy), in 3D (xx, yy, zz, yz, xz, xy); the dimension is the
    value's (3 or 6 components).

    Attributes:
        value: sigma at the origin, (sxx, syy, sxy) or (sxx, syy, szz, syz, sxz, sxy).
        gradient: one row per coordinate, the derivative of value's components
            along it: 2D ((d/dx), (d/dy)) of 3 each, 3D ((d/dx), (d/dy), (d/dz))
            of 6 each (None: uniform).
        origin: (x_0, y_0) or (x_0, y_0, z_0) (None: 0).

    Example: pure bending of a beam along x with its neutral axis at y = 0,
    sigma_xx = M y / I: LinearStress((0, 0, 0), gradient=((0, 0, 0), (M / I, 0, 0))); in 3D
    LinearStress((0,) * 6, gradient=((0,) * 6, (M / I, 0, 0, 0, 0, 0), (0,) * 6)).
    """
    value: tuple = (0.0, 0.0, 0.0)
    gradient: typing.Optional[tuple] = None
    origin: typing.Optional[tuple] = None

    def __post_init__(self):
        v = np.asarray(self.value, dtype=float)
        if v.shape not in ((3,), (6,)):
            raise InputError(f"a linear stress's value is (sxx, syy, sxy) in 2D or (sxx, syy, szz, syz, sxz, sxy) "
                             f"in 3D; got shape {v.shape}")
        d = 2 if v.size == 3 else 3
        g = np.zeros((d, v.size)) if self.gradient is None else np.asarray(self.gradient, dtype=float)
        o = np.zeros(d) if self.origin is None else np.asarray(self.origin, dtype=float)
        if g.shape != (d, v.size) or o.shape != (d,):
            rows = "((3 numbers d/dx), (3 numbers d/dy))" if d == 2 else "(d/dx, d/dy, d/dz: 6 numbers each)"
            raise InputError(f"a {d}D linear stress (value of {v.size} components) needs gradient {rows} and origin "
                             f"of {d} coordinates; got shapes {g.shape}, {o.shape}")
        if not (np.all(np.isfinite(v)) and np.all(np.isfinite(g)) and np.all(np.isfinite(o))):
            raise InputError("a linear stress must be made of finite numbers")
        object.__setattr__(self, "value", tuple(v.tolist()))
        object.__setattr__(self, "gradient", tuple(map(tuple, g.tolist())))
        object.__setattr__(self, "origin", tuple(o.tolist()))

    @property
    def dim(self) -> int:
        return len(self.origin)

    def voigt(self, x: np.ndarray) -> np.ndarray:
        """(n, 3) or (n, 6) Voigt components at points (n, dim)."""
        d = np.asarray(x, dtype=float).reshape(-1, self.dim) - np.asarray(self.origin)
        return np.asarray(self.value)[None] + d @ np.asarray(self.gradient)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        return voigt_to_tensor(self.voigt(x))

    def divergence(self, x: np.ndarray) -> np.ndarray:
        """div sigma (n, dim): constant, (div sigma)_i = sum_j d sigma_ij / d x_j."""
        g = np.asarray(self.gradient)
        pairs = VOIGT_PAIRS[self.dim]
        div = np.zeros(self.dim)
        for k, (i, j) in enumerate(pairs):
            div[i] += g[j, k]
            if i != j:
                div[j] += g[i, k]
        return np.broadcast_to(div, (len(np.asarray(x).reshape(-1, self.dim)), self.dim)).copy()

    @property
    def is_uniform(self) -> bool:
        return not np.any(np.asarray(self.gradient))


#: The (i, j) of each Voigt component: 2D xx, yy, xy; 3D xx, yy, zz, yz, xz, xy.
VOIGT_PAIRS = {2: ((0, 0), (1, 1), (0, 1)), 3: ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))}


def voigt_to_tensor(s: np.ndarray) -> np.ndarray:
    """(n, 3) xx, yy, xy -> (n, 2, 2); (n, 6) xx, yy, zz, yz, xz, xy -> (n, 3, 3)."""
    s = np.asarray(s)
    d = 2 if s.shape[1] == 3 else 3
    out = np.empty((len(s), d, d))
    for k, (i, j) in enumerate(VOIGT_PAIRS[d]):
        out[:, i, j] = out[:, j, i] = s[:, k]
    return out


def tensor_to_voigt(s: np.ndarray) -> np.ndarray:
    """(n, 2, 2) -> (n, 3) xx, yy, xy; (n, 3, 3) -> (n, 6) xx, yy, zz, yz, xz, xy
    (the shear components symmetrised)."""
    s = np.asarray(s)
    return np.stack([0.5 * (s[:, i, j] + s[:, j, i]) for i, j in VOIGT_PAIRS[s.shape[1]]], axis=1)


def as_stress_field(value: StressLike, what: str, dim: int | None = None
                    ) -> typing.Union[LinearStress, typing.Callable]:
    """A LinearStress for a constant stress (2D: (sxx, syy, sxy) or a 2 x 2
    tensor; 3D: (sxx, syy, szz, syz, sxz, sxy) or a 3 x 3 tensor) or a
    LinearStress; a callable is kept (it must return (n, d, d) or Voigt
    components for points (n, d)). dim: the part's dimension, which a
    constant or linear stress must have (None: the value's own)."""
    if dim is None and (isinstance(value, LinearStress) or not callable(value)):
        dim = value.dim if isinstance(value, LinearStress) else 3 if np.shape(value) in ((6,), (3, 3)) else 2
    names = "(sxx, syy, sxy)" if dim == 2 else "(sxx, syy, szz, syz, sxz, sxy)"
    if isinstance(value, LinearStress):
        if value.dim != dim:
            raise InputError(f"{what}: a {value.dim}D linear stress on a {dim}D part: give its value as {names}")
        return value
    if callable(value):
        return value
    v = np.asarray(value, dtype=float)
    if v.shape == (dim, dim):
        if np.abs(v - v.T).max() > 1e-12 * max(np.abs(v).max(), 1e-300):
            raise InputError(f"{what}: the stress tensor must be symmetric, got {v.tolist()}")
        v = tensor_to_voigt(v[None])[0]
    if v.shape != (3 * dim - 3,) or not np.all(np.isfinite(v)):
        raise InputError(f"{what}: a stress on a {dim}D part must be {names}, a LinearStress or a callable "
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
        s = voigt_to_tensor(s)
    if s.shape != (len(x), d, d):
        names = "xx, yy, xy" if d == 2 else "xx, yy, zz, yz, xz, xy"
        raise InputError(f"{what}: the stress function returned shape {s.shape} for points of shape "
                         f"{x.shape}; it must return ({len(x)}, {d}, {d}) or ({len(x)}, {voigt}) ({names})")
    if not np.all(np.isfinite(s)):
        raise InputError(f"{what}: the stress evaluates to NaN or infinity")
    return s


def divergence(field, x: np.ndarray, scale: float, what: str) -> np.ndarray:
    """div sigma (n, d) at points (n, d): exact for a LinearStress, else by
    central differences with a step of 1e-5 of `scale` (the part's size)."""
    x = np.asarray(x, dtype=float)
    d = x.shape[1] if x.ndim == 2 else 2
    x = x.reshape(-1, d)
    if isinstance(field, LinearStress):
        return field.divergence(x)
    h = 1e-5 * scale
    out = np.zeros((len(x), d))
    for j in range(d):  # d sigma_ij / d x_j
        e = np.zeros(d)
        e[j] = h
        ds = (evaluate_stress(field, x + e, what) - evaluate_stress(field, x - e, what)) / (2 * h)
        out += ds[:, :, j]
    return out
