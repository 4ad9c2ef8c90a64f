"""K of one mesh at the front points of another: the same crack front solved
on two meshes of a part (an error estimate's, cracklip.analysis.accuracy)
has its front points at other places, so the other mesh's K is carried to
this mesh's points along the front.

Each point is projected onto the other mesh's front polyline through its
K points (the piece of that crack nearest to it); its coordinate is the arc
length of the projection along that polyline, and the other K there is the
cubic spline through the other points' K in arc length (periodic on a
closed piece; not-a-knot on an open one, the ends included). A cubic keeps
the interpolation error far below K's discretisation error: K_II of the
inclined penny (cos omega) on points 3 elements apart at a/10 errs by 1e-5
of its amplitude, linear interpolation by 1 %.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from scipy.interpolate import CubicSpline


@dataclasses.dataclass
class FrontPiece:
    """One piece of a crack's front on one mesh: its K points in order
    along it (x (n, 3)), the K there (n, m) and whether it is a loop."""
    x: np.ndarray
    K: np.ndarray
    closed: bool

    def arc_lengths(self) -> tuple[np.ndarray, float]:
        """Arc length of every point along the polyline through them, and
        the polyline's length (a loop: back to the first point)."""
        seg = np.linalg.norm(np.diff(self.x, axis=0), axis=1)
        s = np.concatenate([[0.0], np.cumsum(seg)])
        total = s[-1] + (float(np.linalg.norm(self.x[0] - self.x[-1])) if self.closed else 0.0)
        return s, total

    def project(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(arc length, distance) of the projection of points (k, 3) onto the
        polyline."""
        p = np.asarray(points, dtype=float).reshape(-1, 3)
        if len(self.x) == 1:
            return np.zeros(len(p)), np.linalg.norm(p - self.x[0], axis=1)
        a, b = (self.x, np.roll(self.x, -1, axis=0)) if self.closed else (self.x[:-1], self.x[1:])
        s, _ = self.arc_lengths()
        d = b - a
        dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
        t = np.clip(np.einsum("kij,ij->ki", p[:, None, :] - a[None], d) / dd[None], 0.0, 1.0)   # (k, segs)
        q = a[None] + t[:, :, None] * d[None]
        dist = np.linalg.norm(q - p[:, None, :], axis=2)
        j = np.argmin(dist, axis=1)
        seg_len = np.sqrt(dd)
        return s[j] + t[np.arange(len(p)), j] * seg_len[j], dist[np.arange(len(p)), j]

    def values_at(self, u: np.ndarray) -> np.ndarray:
        """K (k, m) at arc lengths u (k,) along the polyline (cubic spline)."""
        s, total = self.arc_lengths()
        K = np.asarray(self.K, dtype=float)
        n = len(s)
        if n == 1:
            return np.repeat(K[:1], len(u), axis=0)
        if self.closed:
            if n < 3:
                return np.repeat(K.mean(axis=0, keepdims=True), len(u), axis=0)
            spline = CubicSpline(np.append(s, total), np.vstack([K, K[:1]]), axis=0, bc_type="periodic")
            return spline(np.mod(u, total))
        if n == 2:
            w = np.clip(u / max(total, 1e-300), 0.0, 1.0)[:, None]
            return (1.0 - w) * K[:1] + w * K[1:]
        return CubicSpline(s, K, axis=0, bc_type="not-a-knot")(np.clip(u, 0.0, total))


def carry_over(points: np.ndarray, pieces: list[FrontPiece]) -> np.ndarray:
    """The other mesh's K (k, m) at points (k, 3) of this mesh's front:
    each point on the piece it lies nearest to."""
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    best = np.full(len(p), np.inf)
    out = np.zeros((len(p), pieces[0].K.shape[1]))
    for piece in pieces:
        u, dist = piece.project(p)
        take = dist < best
        if np.any(take):
            out[take] = piece.values_at(u[take])
            best[take] = dist[take]
    return out


__all__ = ["FrontPiece", "carry_over"]
