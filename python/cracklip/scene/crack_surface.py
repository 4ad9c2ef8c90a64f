"""Cracks in 3D parts as the user gives them: crack surfaces.

- ``EllipticalCrack``: a planar crack bounded by an ellipse (a circle when
  b = a): centre, unit normal, the direction of the first semi-axis, the
  semi-axes a and b. A surface crack is an ellipse centred on a face of the
  part, a corner crack one centred on an edge: the part's boundary cuts the
  crack, and only what lies inside the part is a crack.
- ``PolygonCrack``: a planar crack bounded by a polygon (vertices in order).
- ``SurfaceCrack``: a triangulated surface (vertices, consistently oriented
  triangles) for non-planar cracks, read from STL or a gmsh file
  (``read_crack_surface``).

Every crack has a + side (the side its normal points to; for a triangulated
surface, the side of the triangles' right-handed normals) and a front: the
boundary of the surface inside the part. ``front_points(spacing)`` samples
the front (before meshing: the mesh is refined around it),
``surface_points(spacing)`` covers the whole surface (a refinement over the
crack), ``plane()`` gives in-plane coordinates (pictures of the opening).
"""
from __future__ import annotations

import dataclasses
import math
import numbers
import pathlib
import typing

import numpy as np

from ..errors import CrackGeometryError

Value = typing.Union[float, typing.Callable[[np.ndarray], np.ndarray]]


def _unit(v, what: str, label: str) -> np.ndarray:
    a = np.asarray(v, dtype=float).reshape(-1)
    if a.shape != (3,) or not np.all(np.isfinite(a)) or np.linalg.norm(a) == 0.0:
        raise CrackGeometryError(f"{label}: {what} must be three finite numbers, not all zero; got {v!r}")
    return a / np.linalg.norm(a)


def _check_pressure(pressure, label: str) -> None:
    if not callable(pressure) and not (isinstance(pressure, numbers.Real) and math.isfinite(pressure)):
        raise CrackGeometryError(f"{label}: the lip pressure must be a finite number or a callable p(x), "
                                 f"got {pressure!r}")


@dataclasses.dataclass
class EllipticalCrack:
    """A planar crack bounded by an ellipse.

    Attributes:
        center: (3,) centre of the ellipse.
        normal: (3,) normal of the crack's plane (points to the + side).
        axis: (3,) direction of the first semi-axis (projected onto the
            plane; need not be exactly in it).
        a: the semi-axis along `axis` (> 0).
        b: the other semi-axis, along normal x axis (> 0; None: a circle,
            b = a).
        name: label in messages and outputs.
        pressure: pressure on both lips (> 0 pushes them apart), a number
            or a callable p(x) of points (n, 3) returning (n,).
        pressure_group: load group whose factor scales the pressure.
    """
    center: typing.Sequence[float]
    normal: typing.Sequence[float]
    a: float
    b: float | None = None
    axis: typing.Sequence[float] | None = None
    name: str = ""
    pressure: Value = 0.0
    pressure_group: str = "default"

    def __post_init__(self):
        label = self.name or "crack"
        c = np.asarray(self.center, dtype=float).reshape(-1)
        if c.shape != (3,) or not np.all(np.isfinite(c)):
            raise CrackGeometryError(f"{label}: center must be three finite numbers, got {self.center!r}")
        n = _unit(self.normal, "normal", label)
        b = self.a if self.b is None else self.b
        for key, v in (("a", self.a), ("b", b)):
            if not (isinstance(v, numbers.Real) and math.isfinite(v) and v > 0.0):
                raise CrackGeometryError(f"{label}: semi-axis {key} must be a positive number, got {v!r}")
        if self.axis is None:  # any direction in the plane
            trial = np.eye(3)[int(np.argmin(np.abs(n)))]
            ax = trial - np.dot(trial, n) * n
        else:
            ax = _unit(self.axis, "axis", label)
            ax = ax - np.dot(ax, n) * n
            if np.linalg.norm(ax) < 1e-9:
                raise CrackGeometryError(f"{label}: axis {list(self.axis)} is along the normal; give a direction "
                                         "in the crack's plane for the semi-axis a")
        self.center, self.normal, self.axis = c, n, ax / np.linalg.norm(ax)
        self.b = float(b)
        self.a = float(self.a)
        _check_pressure(self.pressure, label)

    @property
    def axis2(self) -> np.ndarray:
        """Direction of the semi-axis b: normal x axis."""
        return np.cross(self.normal, self.axis)

    def point(self, phi: np.ndarray) -> np.ndarray:
        """Points (n, 3) of the front at parametric angles phi (n,)."""
        phi = np.asarray(phi, dtype=float).reshape(-1)
        return (self.center[None] + self.a * np.cos(phi)[:, None] * self.axis[None]
                + self.b * np.sin(phi)[:, None] * self.axis2[None])

    def parametric_angle(self, x: np.ndarray) -> np.ndarray:
        """The parametric angle (n,) of points (n, 3) near the front."""
        d = np.asarray(x, dtype=float).reshape(-1, 3) - self.center
        return np.arctan2(d @ self.axis2 / self.b, d @ self.axis / self.a)

    def front_points(self, spacing: float) -> np.ndarray:
        """Points (m, 3) along the whole ellipse at most `spacing` apart (equal
        steps in the parametric angle: the fastest part of the ellipse moves
        max(a, b) per radian)."""
        m = max(16, int(math.ceil(2 * math.pi * max(self.a, self.b) / spacing)))
        return self.point(np.linspace(0.0, 2 * math.pi, m, endpoint=False))

    def surface_points(self, spacing: float) -> np.ndarray:
        """Points (m, 3) covering the crack's surface on a grid `spacing`
        apart (for refining a mesh over it)."""
        u = np.arange(-self.a, self.a + 0.5 * spacing, spacing)
        v = np.arange(-self.b, self.b + 0.5 * spacing, spacing)
        U, V = (w.ravel() for w in np.meshgrid(u, v))
        inside = (U / self.a) ** 2 + (V / self.b) ** 2 <= 1.0
        return (self.center[None] + U[inside, None] * self.axis[None] + V[inside, None] * self.axis2[None])

    @property
    def area(self) -> float:
        return math.pi * self.a * self.b

    @property
    def perimeter(self) -> float:
        """The ellipse's length (Ramanujan's second formula: 1e-9 relative
        at b / a = 0.5, 1.2e-5 at 0.1)."""
        t = ((self.a - self.b) / (self.a + self.b)) ** 2
        return math.pi * (self.a + self.b) * (1.0 + 3.0 * t / (10.0 + math.sqrt(4.0 - 3.0 * t)))

    def plane(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(origin, e1, e2): the centre and the directions of the semi-axes
        a and b (pictures of the crack are drawn in these coordinates)."""
        return self.center, self.axis, self.axis2


@dataclasses.dataclass
class PolygonCrack:
    """A planar crack bounded by a polygon.

    Attributes:
        points: (k, 3) vertices in order around the crack, k >= 3, in one
            plane; the normal (the + side) follows the right-hand rule.
        name, pressure, pressure_group: as EllipticalCrack.
    """
    points: np.ndarray
    name: str = ""
    pressure: Value = 0.0
    pressure_group: str = "default"

    def __post_init__(self):
        label = self.name or "crack"
        p = np.asarray(self.points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3 or p.shape[0] < 3 or not np.all(np.isfinite(p)):
            raise CrackGeometryError(f"{label}: a polygon needs k >= 3 finite vertices (k, 3), got shape "
                                     f"{np.shape(self.points)}")
        c = p.mean(axis=0)
        # Newell's normal: robust for any simple polygon.
        nrm = np.zeros(3)
        for i in range(len(p)):
            q, r = p[i] - c, p[(i + 1) % len(p)] - c
            nrm += np.cross(q, r)
        area2 = np.linalg.norm(nrm)
        scale = float(np.ptp(p, axis=0).max())
        if area2 <= 1e-12 * scale * scale:
            raise CrackGeometryError(f"{label}: the polygon has no area (its vertices are collinear or repeated)")
        n = nrm / area2
        off = np.abs((p - c) @ n)
        if off.max() > 1e-9 * scale:
            k = int(np.argmax(off))
            raise CrackGeometryError(f"{label}: vertex {k} {p[k].tolist()} lies {off[k]:.3g} off the polygon's plane; "
                                     "a polygon crack must be planar (give a curved crack as a triangulated "
                                     "surface: cracks[].surface)")
        self.points = p
        self.normal = n
        _check_pressure(self.pressure, label)

    def front_points(self, spacing: float) -> np.ndarray:
        out = []
        for i in range(len(self.points)):
            a, b = self.points[i], self.points[(i + 1) % len(self.points)]
            m = max(1, int(math.ceil(np.linalg.norm(b - a) / spacing)))
            t = np.arange(m) / m
            out.append(a[None] + t[:, None] * (b - a)[None])
        return np.concatenate(out)

    def surface_points(self, spacing: float) -> np.ndarray:
        """Points (m, 3) covering the polygon on a grid `spacing` apart in
        its plane (even-odd rule), and its vertices."""
        t1 = self.points[1] - self.points[0]
        t1 /= np.linalg.norm(t1)
        t2 = np.cross(self.normal, t1)
        q = (self.points - self.points[0]) @ np.column_stack([t1, t2])
        lo, hi = q.min(axis=0), q.max(axis=0)
        u = np.arange(lo[0], hi[0] + 0.5 * spacing, spacing)
        v = np.arange(lo[1], hi[1] + 0.5 * spacing, spacing)
        U, V = (w.ravel() for w in np.meshgrid(u, v))
        inside = np.zeros(len(U), dtype=bool)
        for i in range(len(q)):
            (x0, y0), (x1, y1) = q[i], q[(i + 1) % len(q)]
            crosses = (y0 > V) != (y1 > V)
            with np.errstate(divide="ignore", invalid="ignore"):
                xc = x0 + (V - y0) * (x1 - x0) / (y1 - y0)
            inside ^= crosses & (U < xc)
        grid = self.points[0][None] + U[inside, None] * t1[None] + V[inside, None] * t2[None]
        return np.concatenate([grid, self.points])

    @property
    def area(self) -> float:
        c = self.points.mean(axis=0)
        return 0.5 * float(sum(np.dot(np.cross(self.points[i] - c, self.points[(i + 1) % len(self.points)] - c),
                                      self.normal) for i in range(len(self.points))))

    @property
    def perimeter(self) -> float:
        return float(np.linalg.norm(np.roll(self.points, -1, axis=0) - self.points, axis=1).sum())

    def plane(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(origin, e1, e2): the vertices' centroid, the direction of the first
        edge and normal x e1 (a right-handed frame with the normal)."""
        e1 = self.points[1] - self.points[0]
        e1 = e1 - np.dot(e1, self.normal) * self.normal
        e1 /= np.linalg.norm(e1)
        return self.points.mean(axis=0), e1, np.cross(self.normal, e1)


#: SurfaceCrack.front_geometry: a front bent by more than this (|x1''|
#: reach) takes its curvature from a fitted circle.
FRONT_CIRCLE_BEND = 0.05


@dataclasses.dataclass
class SurfaceCrack:
    """A crack given as a triangulated surface.

    Attributes:
        vertices: (nv, 3) points.
        triangles: (nt, 3) vertex indices, consistently oriented (the +
            side is that of their right-handed normals).
        name, pressure, pressure_group: as EllipticalCrack.
        source: where it came from, for messages (a scene file's
            "cracks[i].surface = 'file.stl'"; "" for none).
    The surface's boundary edges are its front where they lie inside the
    part. Checks here: shapes, finite values, indices in range, no
    degenerate triangle; manifoldness and orientation are checked with the
    level sets (C++), which name the edge at fault.
    """
    vertices: np.ndarray
    triangles: np.ndarray
    name: str = ""
    pressure: Value = 0.0
    pressure_group: str = "default"
    source: str = ""

    def __post_init__(self):
        label = self.name or "crack"
        v = np.asarray(self.vertices, dtype=float)
        t = np.asarray(self.triangles)
        if v.ndim != 2 or v.shape[1] != 3 or not np.all(np.isfinite(v)):
            raise CrackGeometryError(f"{label}: vertices must be finite (nv, 3), got shape {np.shape(self.vertices)}")
        if t.ndim != 2 or t.shape[1] != 3 or len(t) == 0 or not np.issubdtype(t.dtype, np.integer):
            raise CrackGeometryError(f"{label}: triangles must be integer vertex indices (nt, 3), nt >= 1, got "
                                     f"shape {np.shape(self.triangles)}")
        if t.min() < 0 or t.max() >= len(v):
            raise CrackGeometryError(f"{label}: triangle vertex index out of range [0, {len(v)})")
        e = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
        scale = float(np.ptp(v, axis=0).max())
        bad = np.flatnonzero(np.linalg.norm(e, axis=1) <= 1e-12 * scale * scale)
        if bad.size:
            k = int(bad[0])
            raise CrackGeometryError(f"{label}: triangle {k} (vertices {t[k].tolist()}) has no area; remove "
                                     f"degenerate triangles ({bad.size} of them)")
        self.vertices, self.triangles = v, t.astype(np.int32)
        _check_pressure(self.pressure, label)

    def boundary_edges(self) -> np.ndarray:
        """(m, 2) vertex pairs of the edges that belong to one triangle only."""
        edges = np.sort(self.triangles[:, [[0, 1], [1, 2], [2, 0]]].reshape(-1, 2), axis=1)
        uniq, count = np.unique(edges, axis=0, return_counts=True)
        return uniq[count == 1]

    def front_points(self, spacing: float) -> np.ndarray:
        out = []
        for a, b in self.boundary_edges():
            pa, pb = self.vertices[a], self.vertices[b]
            m = max(1, int(math.ceil(np.linalg.norm(pb - pa) / spacing)))
            out.append(pa[None] + (np.arange(m + 1) / m)[:, None] * (pb - pa)[None])
        return np.concatenate(out) if out else np.zeros((0, 3))

    def surface_points(self, spacing: float) -> np.ndarray:
        """Points (m, 3) covering the triangles: each subdivided into a
        barycentric grid of step at most `spacing`."""
        v, t = self.vertices, self.triangles
        out = [v]
        for tri in t:
            P = v[tri]
            m = int(math.ceil(max(np.linalg.norm(P[1] - P[0]), np.linalg.norm(P[2] - P[1]),
                                  np.linalg.norm(P[0] - P[2])) / spacing))
            if m < 2:
                continue
            i, j = np.meshgrid(np.arange(m + 1), np.arange(m + 1))
            keep = (i + j <= m).ravel()
            b1, b2 = i.ravel()[keep] / m, j.ravel()[keep] / m
            out.append(P[0][None] + b1[:, None] * (P[1] - P[0])[None] + b2[:, None] * (P[2] - P[0])[None])
        return np.unique(np.concatenate(out), axis=0)

    @property
    def area(self) -> float:
        v, t = self.vertices, self.triangles
        return 0.5 * float(np.linalg.norm(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1).sum())

    def front_geometry(self, points: np.ndarray, frames: np.ndarray, radius: float) -> dict[str, np.ndarray]:
        """The smooth surface and front through the triangulation near front
        points (n, 3) whose frames (n, 3, 3) (rows e1 out of the crack, e2
        the normal to the + side, e3 = e1 x e2: the facets') are a first
        guess, so that quantities the facets only give piecewise (the
        normal, the front's direction) and not at all (curvatures) follow
        the surface the triangulation samples: per point, least squares in
        the point's frame (x1, x2, x3), weighted by (1 - (d / radius)^2)^2
        (radius: one for all points or one per point),

        - of the vertices within `radius` (at least 3 edges): the surface
          x2 = c + a1 x1 + a3 x3 + (k11 x1^2 + 2 k13 x1 x3 + k33 x3^2) / 2 +
          cubic and quartic terms (where 30 and 45 vertices allow): its
          normal at the point, its normal curvatures across (kappa_11) and
          along (kappa_33) the front and its geodesic torsion tau = k13 (the
          turning of the normal along the front, d e2 / ds . e1 = -tau);
        - of the boundary vertices (the front's) within `radius`: x1 and x2
          as polynomials of x3 (up to degree 4 with 12 vertices): the
          front's tangent and kappa_f = -x1''(0) (> 0 where the front bends
          around the crack);

        twice, the second time in the frame of the first fit (e2 its normal,
        e3 the front's tangent made normal to it, e1 = e2 x e3). Returns
        frame (n, 3, 3) and curvatures (n, 4): kappa_f, kappa_11, kappa_33,
        tau (interaction_integral_3d.h), 0 where they are below 1e-9 of the
        inverse size (a planar triangulation). Raises CrackGeometryError
        where too few vertices lie within reach."""
        import scipy.spatial
        v, label = self.vertices, self.name or "crack"
        pts = np.asarray(points, dtype=float).reshape(-1, 3)
        frames = np.array(frames, dtype=float).reshape(-1, 3, 3)
        edges = np.linalg.norm(v[self.triangles] - v[np.roll(self.triangles, 1, axis=1)], axis=2)
        least = 3.0 * float(np.median(edges))
        radii = np.broadcast_to(np.asarray(radius, dtype=float), (len(pts),))
        size = float(np.ptp(v, axis=0).max())
        front = np.unique(self.boundary_edges())
        tree, ftree = scipy.spatial.cKDTree(v), scipy.spatial.cKDTree(v[front])
        out_frame = np.empty_like(frames)
        out_k = np.zeros((len(pts), 4))
        for i, (x0, fr) in enumerate(zip(pts, frames)):
            e1, e2, e3 = fr
            reach = max(float(radii[i]), least)
            for _ in range(2):
                X = self._nearby(tree, v, x0, reach, 10, label)
                Y = self._nearby(ftree, v[front], x0, reach, 5, label)
                c = self._quadric(X, x0, e1, e2, e3, reach)
                n = e2 - c[1] * e1 - c[2] * e3
                n /= np.linalg.norm(n)
                b = self._front_curve(Y, x0, e1, e2, e3, reach)
                t = e3 + b[0] * e1 + b[1] * e2
                t -= np.dot(t, n) * n
                t /= np.linalg.norm(t)
                e1, e2, e3 = np.cross(n, t), n, t
            c = self._quadric(X, x0, e1, e2, e3, reach)
            b = self._front_curve(Y, x0, e1, e2, e3, reach)
            k = np.array([-b[2], c[3], c[5], c[4]])
            k[np.abs(k) * size < 1e-9] = 0.0
            out_frame[i] = (e1, e2, e3)
            out_k[i] = k
        return {"frame": out_frame, "curvatures": out_k}

    @staticmethod
    def _nearby(tree, v: np.ndarray, x0: np.ndarray, reach: float, least: int, label: str) -> np.ndarray:
        idx = tree.query_ball_point(x0, reach)
        if len(idx) < least:
            _, idx = tree.query(x0, k=min(least, len(v)))
            idx = np.atleast_1d(idx)
        if len(idx) < least:
            raise CrackGeometryError(f"{label}: fewer than {least} vertices of the triangulated surface near the "
                                     f"front point {x0.tolist()}: too few to fit its curvature; give a finer "
                                     "triangulation")
        return v[np.asarray(idx)]

    @staticmethod
    def _weights(d: np.ndarray, reach: float) -> np.ndarray:
        r = np.minimum(d / (1.5 * reach), 1.0)
        return (1.0 - r * r) ** 2 + 1e-3

    @classmethod
    def _quadric(cls, X, x0, e1, e2, e3, reach) -> np.ndarray:
        """(c, a1, a3, k11, k13, k33) of x2 = c + a1 x1 + a3 x3 + (k11 x1^2 +
        2 k13 x1 x3 + k33 x3^2) / 2 + cubic terms (least squares)."""
        d = X - x0
        y1, y2, y3 = d @ e1, d @ e2, d @ e3
        cols = [np.ones_like(y1), y1, y3, 0.5 * y1 * y1, y1 * y3, 0.5 * y3 * y3]
        if len(X) >= 30:
            cols += [y1 ** 3, y1 * y1 * y3, y1 * y3 * y3, y3 ** 3]
        if len(X) >= 45:
            cols += [y1 ** 4, y1 ** 3 * y3, y1 * y1 * y3 * y3, y1 * y3 ** 3, y3 ** 4]
        A = np.column_stack(cols)
        w = np.sqrt(cls._weights(np.linalg.norm(d, axis=1), reach))
        return np.linalg.lstsq(A * w[:, None], y2 * w, rcond=None)[0][:6]

    @classmethod
    def _front_curve(cls, Y, x0, e1, e2, e3, reach) -> np.ndarray:
        """(x1'(0), x2'(0), x1''(0)) of the front through the boundary
        vertices Y as x1(x3), x2(x3) (least squares)."""
        d = Y - x0
        y1, y2, y3 = d @ e1, d @ e2, d @ e3
        cols = [np.ones_like(y3), y3, 0.5 * y3 * y3]
        if len(Y) >= 8:
            cols.append(y3 ** 3)
        if len(Y) >= 12:
            cols.append(y3 ** 4)
        A = np.column_stack(cols)
        w = np.sqrt(cls._weights(np.linalg.norm(d, axis=1), reach))
        c1 = np.linalg.lstsq(A * w[:, None], y1 * w, rcond=None)[0]
        c2 = np.linalg.lstsq(A * w[:, None], y2 * w, rcond=None)[0]
        x1pp = c1[2]
        if abs(x1pp) * reach > FRONT_CIRCLE_BEND and 4 <= len(Y) < 12:
            # A bent front with too few vertices for the quartic: a circle
            # through the vertices (x3, x1) instead of a lower polynomial:
            # a quadratic over +-3 vertices of a circle takes the x3^4 term
            # into x1'' (7 % high on a penny sampled at 1/8 of its radius).
            B = np.column_stack([y3, y1, np.ones_like(y3)])
            D, E, F = np.linalg.lstsq(B * w[:, None], -(y3 * y3 + y1 * y1) * w, rcond=None)[0]
            R2 = 0.25 * (D * D + E * E) - F
            if R2 > 0.0:
                x1pp = -math.copysign(1.0 / math.sqrt(R2), E)   # centre at x1 = -E/2 < 0: the front bends around the crack
        return np.array([c1[1], c2[1], x1pp])

    @property
    def perimeter(self) -> float:
        """The length of its boundary edges."""
        e = self.boundary_edges()
        return float(np.linalg.norm(self.vertices[e[:, 1]] - self.vertices[e[:, 0]], axis=1).sum())

    def plane(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(origin, e1, e2): the best-fitting plane of the vertices (their
        centroid and the two leading principal directions, e1 x e2 along the
        triangles' mean normal), onto which pictures project the surface."""
        v, t = self.vertices, self.triangles
        origin = v.mean(axis=0)
        _, _, vt = np.linalg.svd(v - origin, full_matrices=False)
        e1, e2 = vt[0], vt[1]
        mean_normal = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]).sum(axis=0)
        if np.dot(np.cross(e1, e2), mean_normal) < 0.0:
            e2 = -e2
        return origin, e1, e2


def read_crack_surface(path: str | pathlib.Path, name: str = "") -> SurfaceCrack:
    """A SurfaceCrack from an STL file (ASCII or binary) or a gmsh .msh file
    (its 3-node triangles)."""
    path = pathlib.Path(path)
    if not path.is_file():
        raise CrackGeometryError(f"crack surface file {path} does not exist")
    from .mesh import _gmsh
    gmsh = _gmsh()
    gmsh.model.add("crack_surface")
    try:
        gmsh.merge(str(path))
    except Exception as e:  # gmsh raises a bare Exception for an unreadable file
        gmsh.model.remove()
        raise CrackGeometryError(f"{path}: gmsh cannot read this file ({e}); give an STL or a gmsh .msh file "
                                 "with triangles") from None
    try:
        tags, coords, _ = gmsh.model.mesh.getNodes()
        types, _, nodes = gmsh.model.mesh.getElements(2)
    finally:
        gmsh.model.remove()
    tri = [np.asarray(n) for t, n in zip(types, nodes) if t == 2]
    if not tri:
        raise CrackGeometryError(f"{path}: no 3-node triangles in the file")
    order = np.argsort(tags)
    pos = np.searchsorted(tags[order], np.concatenate(tri))
    triangles = order[pos].reshape(-1, 3)
    vertices = coords.reshape(-1, 3)
    # STL repeats vertices per triangle: merge coincident ones.
    scale = float(np.ptp(vertices, axis=0).max()) or 1.0
    key = np.round(vertices / (1e-9 * scale)).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return SurfaceCrack(vertices[first], inverse.reshape(-1)[triangles], name=name or path.stem)


CrackSurface = typing.Union[EllipticalCrack, PolygonCrack, SurfaceCrack]

__all__ = ["EllipticalCrack", "PolygonCrack", "SurfaceCrack", "CrackSurface", "read_crack_surface"]
