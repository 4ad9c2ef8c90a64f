"""A crack as the user gives it: a polyline in the plane, with an optional lip pressure."""
from __future__ import annotations

import dataclasses
import math
import numbers
import typing

import numpy as np

from ..errors import CrackGeometryError, checked_keywords
from .conditions import Value


@checked_keywords
@dataclasses.dataclass
class Crack:
    """A crack as a polyline.

    An end point inside the domain is a crack tip; an end point on or outside
    the boundary makes an edge crack (the polyline must then cross the
    boundary). Tips are found by the model from the mesh.

    Attributes:
        points: (k, 2) polyline vertices, k >= 2.
        name: label used in messages and outputs.
        pressure: pressure on both lips (> 0 pushes them apart: a pressurised
            crack), a number or a callable p(x) of points (n, 2) returning
            (n,); 0 for traction-free lips. With contact the lips carry it
            besides the contact pressure.
        pressure_group: load group whose factor (Scene.load_path) scales
            the pressure.
    """
    points: np.ndarray
    name: str = ""
    pressure: Value = 0.0
    pressure_group: str = "default"

    def __post_init__(self):
        label = self.name or "crack"
        try:
            pts = np.asarray(self.points, dtype=np.float64)
        except (TypeError, ValueError):
            raise CrackGeometryError(f"{label}: points must be numbers, an array of shape (k, 2) (k >= 2: the "
                                     f"polyline's vertices), got {self.points!r:.80}") from None
        if not callable(self.pressure) and not (isinstance(self.pressure, numbers.Real)
                                                and math.isfinite(self.pressure)):
            raise CrackGeometryError(f"{label}: the lip pressure must be a finite number or a callable "
                                     f"p(x), got {self.pressure!r}")
        if pts.ndim != 2 or pts.shape[1] != 2 or pts.shape[0] < 2:
            raise CrackGeometryError(f"{label}: points must be an array of shape (k, 2), k >= 2; "
                                     f"got shape {pts.shape}")
        if not np.all(np.isfinite(pts)):
            k = int(np.flatnonzero(~np.all(np.isfinite(pts), axis=1))[0])
            raise CrackGeometryError(f"{label}: point {k} is {pts[k].tolist()}; crack points must be "
                                     "finite numbers (no NaN or infinity)")
        lengths = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        scale = max(np.ptp(pts, axis=0).max(), 1e-300)
        bad = np.flatnonzero(lengths <= 1e-12 * scale)
        if bad.size:
            k = int(bad[0])
            raise CrackGeometryError(f"{label}: segment {k} from {pts[k].tolist()} to "
                                     f"{pts[k + 1].tolist()} has zero length; remove the repeated point")
        hit = self_intersection(pts)
        if hit is not None:
            i, j, q = hit
            how = "folds back onto" if j == i + 1 else "meets"
            raise CrackGeometryError(
                f"{label}: segment {i} ({pts[i].tolist()} to {pts[i + 1].tolist()}) {how} segment {j} "
                f"({pts[j].tolist()} to {pts[j + 1].tolist()}) at {np.round(q, 12).tolist()}; a crack must "
                "be a simple polyline (no self-intersection, no point visited twice)")
        self.points = pts


def self_intersection(pts: np.ndarray) -> typing.Optional[tuple[int, int, np.ndarray]]:
    """First pair of segments (i < j) of a polyline that meet other than at
    the point shared by consecutive segments (or that overlap there: the
    polyline folds back), with a point they share; None for a simple polyline."""
    a, b = pts[:-1], pts[1:]
    d = b - a
    m = len(a)
    scale = max(float(np.ptp(pts, axis=0).max()), 1e-300)
    tol = 1e-12 * scale * scale

    def cross(u, v):
        return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
    # Consecutive segments: only a fold back (collinear, opposite directions).
    if m >= 2:
        fold = (np.abs(cross(d[:-1], d[1:])) <= tol) & (np.einsum("ij,ij->i", d[:-1], d[1:]) < 0.0)
        if fold.any():
            i = int(np.flatnonzero(fold)[0])
            return i, i + 1, b[i]
    for i0 in range(0, max(m - 2, 0), 512):
        i = np.arange(i0, min(i0 + 512, m - 2))[:, None]
        j = np.arange(m)[None, :]
        ai, di, aj, dj = a[i], d[i], a[j], d[j]
        o1, o2 = cross(di, aj - ai), cross(di, aj + dj - ai)
        o3, o4 = cross(dj, ai - aj), cross(dj, ai + di - aj)
        o1, o2, o3, o4 = (np.where(np.abs(o) <= tol, 0.0, o) for o in (o1, o2, o3, o4))
        meet = (o1 * o2 <= 0.0) & (o3 * o4 <= 0.0) & (j >= i + 2)
        collinear = (o1 == 0.0) & (o2 == 0.0)
        # Collinear pairs meet only if their projections on segment i overlap.
        dd = np.einsum("...k,...k->...", di, di)
        s0 = np.einsum("...k,...k->...", aj - ai, di) / dd
        s1 = np.einsum("...k,...k->...", aj + dj - ai, di) / dd
        overlap = (np.maximum(s0, s1) >= -1e-12) & (np.minimum(s0, s1) <= 1.0 + 1e-12)
        meet &= ~collinear | overlap
        if meet.any():
            r, c = np.argwhere(meet)[0]
            ii, jj = int(i[r, 0]), int(c)
            den = cross(d[ii], d[jj])
            if abs(den) > tol:
                t = cross(a[jj] - a[ii], d[jj]) / den
                q = a[ii] + np.clip(t, 0.0, 1.0) * d[ii]
            else:
                q = a[jj] if 0.0 <= s0[r, c] <= 1.0 else a[ii]
            return ii, jj, q
    return None


def arc_polyline(center, radius: float, start: float, end: float, segments: int) -> np.ndarray:
    """The polyline of a circular-arc crack (angles in radians): `segments`
    segments, each along the arc's tangent at a point of the arc, the two at
    the ends along the tangents at the tips.

    K depends on the crack's direction at the tip to first order. A polyline
    inscribed in the arc (its vertices on the arc) ends along a chord, turned
    by half a segment's angle from the tangent: its K_II was 4.1 % and K_I
    1.8 % off the arc's closed form with 24 segments over 90 degrees (2.2 % and
    0.8 % with 48), whatever the mesh. Here the vertices are where the
    tangents at points of the arc meet (outside it by at most R (sec(d / 2) -
    1), d the angle between those points); the end points are 2 d from
    their neighbours on the arc so that the tip segments are about as long as the
    others (a SIF domain stays on the straight run at the tip). One segment:
    the chord.
    """
    c = np.asarray(center, dtype=float)
    if segments == 1:
        t = np.array([start, end])
        return c + radius * np.stack([np.cos(t), np.sin(t)], axis=1)
    d = (end - start) / (segments + 1)
    if abs(d) * (3 if segments == 2 else 2) >= math.pi:   # two tangents turning by 180 degrees never meet
        raise CrackGeometryError(f"an arc of {math.degrees(abs(end - start)):g} degrees needs more than "
                                 f"{segments} segments (each at most 90 degrees of it)")
    t = np.concatenate([[start], start + 2 * d + d * np.arange(segments - 2), [end]])   # tangent points
    mid = 0.5 * (t[:-1] + t[1:])
    half = 0.5 * (t[1:] - t[:-1])
    corners = c + (radius / np.cos(half))[:, None] * np.stack([np.cos(mid), np.sin(mid)], axis=1)
    ends = c + radius * np.array([[math.cos(start), math.sin(start)], [math.cos(end), math.sin(end)]])
    return np.concatenate([ends[:1], corners, ends[1:]])
