"""Least-squares fits of a quantity sampled at the points of one crack front
piece (K along a 3D front): a Fourier series in the arc length on a loop,
Legendre polynomials on an open piece, as many terms as leave-one-out
cross-validation chooses (Allen's PRESS), and a check against a second,
similar mesh that the fit does not miss K's own variation.

K from the interaction integral scatters from front point to front point by
about 0.1 % of the K scale (hats on an unstructured mesh), as much as its
discretisation error at a front size of a/14-a/20; the scatter differs from
mesh to mesh, the shape of K along the front does not. A fit too stiff for
that shape leaves it in the residual on both meshes alike: with r and r'
the residuals of the two meshes' K at the same points, |r + r'| is about
|r - r'| when they are scatter and much larger when they are shape
(SHAPE_RATIO). code_aster smooths G and K along a front by default in the
same spirit (CALC_G's LISSAGE: LISSAGE_G = LEGENDRE, polynomials up to a
fixed DEGRE = 5, on an open front; on a closed front Legendre is refused and
LAGRANGE, piecewise linear between the front's nodes, is asked for);
cracklip chooses the size of the fit per quantity and checks it on the
second mesh, and fits nothing where no size passes (the ellipse b/a = 0.5 at
b/8: K_I varies within one point spacing at the ends of the major axis).
"""
from __future__ import annotations

import math
import typing

import numpy as np

#: A fit passes the second mesh's check when the two meshes' residuals
#: about it are this much larger summed than subtracted at most. For
#: independent scatter of equal size the two are independent and the ratio's
#: square is F-distributed with about n - k degrees of freedom each way
#: (above 2 on 20 points: about 0.1 %; above 1.5: 4 %); measured on the
#: penny and inclined penny at a/14 (22 points): 0.9-1.6; K_I of the ellipse
#: b/a = 0.5 at b/8 with up to 5 terms, a shape missed: 16-63.
SHAPE_RATIO = 2.0


def piece_basis(s: np.ndarray, closed: bool, length: float, terms: int) -> tuple[np.ndarray, list[int]]:
    """The basis (n, k) at arc lengths s of a piece and the fit sizes to try:
    on a loop 1, cos, sin of the first (terms - 1) // 2 harmonics of
    2 pi s / length (whole harmonics: sizes 1, 3, 5, ...), on an open piece
    Legendre polynomials of degree < terms in s mapped to [-1, 1]."""
    s = np.asarray(s, dtype=float)
    if closed:
        t = 2.0 * math.pi * s / length
        M = max(1, (terms - 1) // 2)
        basis = np.column_stack([np.ones_like(t)] + [f(k * t) for k in range(1, M + 1) for f in (np.cos, np.sin)])
        return basis, list(range(1, basis.shape[1] + 1, 2))
    t = 2.0 * (s - s.min()) / max(float(np.ptp(s)), 1e-300) - 1.0
    basis = np.polynomial.legendre.legvander(t, max(terms, 1) - 1)
    return basis, list(range(1, basis.shape[1] + 1))


def _projector(B: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Q (orthonormal columns of B) and the leverages h, or None when a point
    would be fitted exactly (h = 1)."""
    q, _ = np.linalg.qr(B)
    h = np.einsum("ij,ij->i", q, q)
    return None if h.max() > 1.0 - 1e-9 else (q, h)


def loo_fit(basis: np.ndarray, use: np.ndarray, values: np.ndarray, sizes: typing.Iterable[int],
            other: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """values (n, m) fitted by least squares on the first k columns of
    `basis` (n, K) over the points `use`, k chosen per column of values by
    leave-one-out cross-validation (the smallest sum of squared residuals
    of each point left out, r_i / (1 - h_ii) for a linear fit; Allen's
    PRESS) among `sizes`. With `other` (n, m: the same quantity from a
    second, similar mesh at the same points) only sizes whose residuals pass
    the check against it (SHAPE_RATIO) are taken, and a column no size passes
    is not fitted (its values returned as they are, k = 0). Returns (the fit
    at every point, k per column)."""
    use = np.asarray(use, dtype=bool)
    B, V = basis[use], values[use]
    best = np.full(values.shape[1], np.inf)
    chosen = np.zeros(values.shape[1], dtype=int)
    if other is None:  # the mean at least, as before
        out = np.repeat(values[use].mean(axis=0, keepdims=True), len(values), axis=0)
    else:
        out = np.array(values, dtype=float)
    for k in sizes:
        if k > len(B) - 1:
            break
        qh = _projector(B[:, :k])
        if qh is None:
            break
        q, h = qh
        r = V - q @ (q.T @ V)
        press = np.sum((r / (1.0 - h)[:, None]) ** 2, axis=0)
        better = press < best * (1.0 - 1e-12)
        if other is not None:
            O = other[use]
            ro = O - q @ (q.T @ O)
            better &= np.linalg.norm(r + ro, axis=0) <= SHAPE_RATIO * np.linalg.norm(r - ro, axis=0)
        if np.any(better):
            coef = np.linalg.lstsq(B[:, :k], V[:, better], rcond=None)[0]
            out[:, better] = basis[:, :k] @ coef
            best[better] = press[better]
            chosen[better] = k
    return out, chosen


def fit_spread(basis: np.ndarray, use: np.ndarray, values: np.ndarray, chosen: np.ndarray) -> np.ndarray:
    """The standard deviation (n, m) of the fit of values (loo_fit's k per
    column; 0: not fitted, NaN) due to the scatter about it: sqrt(h_ii) times
    the residuals' RMS over n - k, h the leverage of point i in the k-term
    fit (at the points not used, the basis' own leverage)."""
    use = np.asarray(use, dtype=bool)
    out = np.full(values.shape, np.nan)
    for k in sorted(set(int(c) for c in chosen if c > 0)):
        cols = np.flatnonzero(chosen == k)
        B = basis[use, :k]
        pinv = np.linalg.pinv(B)
        r = values[use][:, cols] - B @ (pinv @ values[use][:, cols])
        sigma = np.sqrt(np.sum(r ** 2, axis=0) / max(int(use.sum()) - k, 1))
        h = np.einsum("ij,jk,ik->i", basis[:, :k], pinv @ pinv.T, basis[:, :k])
        out[:, cols] = np.sqrt(np.maximum(h, 0.0))[:, None] * sigma[None, :]
    return out


__all__ = ["piece_basis", "loo_fit", "fit_spread", "SHAPE_RATIO"]
