"""A 3D crack surface that grows: a triangulated surface whose boundary loop
is its front, extended step by step by a strip of triangles (the crack
grown on a fixed mesh; the model recomputes its level sets geometrically
from the surface, cpp/geometry/crack_surface_3d, no Hamilton-Jacobi solve).

A growing surface starts from the user's crack (``GrowingSurface.from_crack``):
an ellipse or a planar polygon is triangulated in rings scaled from its
boundary, sampled every `spacing`; a triangulated surface is taken as it is.
Its boundary loop runs counter-clockwise seen from the + side (the
surface's interior on the left).

Where the crack meets the part's boundary (a surface or corner crack) part
of the loop lies outside the part: the front is where the surface crosses
the part, and the part clips it. A growth step (``extend``) works on
chains of the loop (``chains``): each run of loop vertices inside the part
with the loop vertices outside it up to `margin` of arc length beyond the
boundary on both sides (a closed front, all inside: the whole loop). The
caller advances every chain vertex (``outward`` gives the in-surface
direction normal to the loop and the surface's normal there), the new
polyline is re-sampled (``resample``), its ends carried `margin` beyond
the part's boundary along its end tangents (``extend_ends``), and a strip
of triangles joins the old chain to the new one (``stitch``, the shorter
diagonal first): the surface keeps covering the part behind the front with
a margin, so that mesh nodes on the part's boundary behind the front lie
inside the crack surface (their psi < 0) and no false front appears there.
The loop then runs ..., old chain start, new chain, old chain end, ...
(the chain's inner old vertices leave the loop).

Nothing here needs the mesh: the caller says which points are inside the
part (``inside``: a function of points (n, 3) returning bools).
"""
from __future__ import annotations

import dataclasses
import math
import typing

import numpy as np

from ..errors import CrackGeometryError
from .crack_surface import EllipticalCrack, PolygonCrack, SurfaceCrack

Inside = typing.Callable[[np.ndarray], np.ndarray]


class StripTurnedOver(CrackGeometryError):
    """A grown strip's triangles face the other way (``extend``): the
    increment is too large for the front's curvature; the caller may retry
    with a smaller one (the surface is left unchanged)."""


@dataclasses.dataclass
class Chain:
    """Loop positions (indices into GrowingSurface.loop, in loop order) of a
    part of the front that grows: closed (the whole loop) or open (its first
    and last vertices outside the part, `margin` beyond the boundary)."""
    positions: np.ndarray
    closed: bool
    inside: np.ndarray  # (len(positions),) bool: the vertex is inside the part


@dataclasses.dataclass
class GrowingSurface:
    """A growing crack surface (module doc).

    Attributes:
        vertices: (nv, 3); triangles: (nt, 3) consistently oriented (normals
            to the + side).
        loop: (m,) the boundary loop's vertex indices, counter-clockwise
            seen from the + side.
        origin: (3,) the crack's origin (an ellipse's centre, else the
            centroid of the initial surface): a front point's crack size a
            is its distance from it.
        name, pressure, pressure_group: as the crack it started from.
    """
    vertices: np.ndarray
    triangles: np.ndarray
    loop: np.ndarray
    origin: np.ndarray
    name: str = ""
    pressure: typing.Any = 0.0
    pressure_group: str = "default"

    # -- construction --------------------------------------------------------------------------------------
    @classmethod
    def from_crack(cls, crack, spacing: float) -> "GrowingSurface":
        """The growing surface of a user's crack (module doc); `spacing`: the
        largest distance between boundary vertices of an ellipse or polygon."""
        if not spacing > 0.0:
            raise CrackGeometryError(f"{crack.name}: the front spacing must be positive, got {spacing!r}")
        kw = {"name": crack.name, "pressure": crack.pressure, "pressure_group": crack.pressure_group}
        if isinstance(crack, EllipticalCrack):
            # Equal arc length along the ellipse (a fine parametric sampling re-sampled).
            fine = crack.point(np.linspace(0.0, 2 * math.pi, 64 * max(16, int(
                math.ceil(2 * math.pi * max(crack.a, crack.b) / spacing))), endpoint=False))
            boundary = resample(fine, spacing, closed=True)
            return cls._rings(boundary, crack.center, **kw)
        if isinstance(crack, PolygonCrack):
            boundary = crack.front_points(spacing)  # every edge subdivided: the corners stay
            c = crack.points.mean(axis=0)
            return cls._rings(boundary, c, **kw)
        if isinstance(crack, SurfaceCrack):
            v, t = crack.vertices.copy(), crack.triangles.copy()
            return cls(v, t, boundary_loop(t), v.mean(axis=0), **kw)
        raise CrackGeometryError(f"{getattr(crack, 'name', 'crack')}: a growing 3D crack starts from an ellipse, a "
                                 f"polygon or a triangulated surface, got {type(crack).__name__}")

    @classmethod
    def _rings(cls, boundary: np.ndarray, center: np.ndarray, **kw) -> "GrowingSurface":
        """A star-shaped planar boundary (m, 3) triangulated in rings scaled
        toward its centre (about as many rings as the boundary's radius in
        spacings, m points each; a fan at the centre)."""
        m = len(boundary)
        radius = float(np.linalg.norm(boundary - center, axis=1).max())
        step = float(np.linalg.norm(np.diff(np.vstack([boundary, boundary[:1]]), axis=0), axis=1).mean())
        nr = max(2, int(math.ceil(radius / max(step, 1e-300) / 2.0)))
        verts = [center[None]]
        for k in range(1, nr + 1):
            verts.append(center + (k / nr) * (boundary - center))
        v = np.concatenate(verts)
        tris = []
        ring = lambda k: 1 + (k - 1) * m + np.arange(m)  # noqa: E731
        r1 = ring(1)
        tris.append(np.column_stack([np.zeros(m, dtype=np.int64), r1, np.roll(r1, -1)]))
        for k in range(1, nr):
            a, b = ring(k), ring(k + 1)
            tris.append(np.column_stack([a, b, np.roll(b, -1)]))
            tris.append(np.column_stack([a, np.roll(b, -1), np.roll(a, -1)]))
        t = np.concatenate(tris).astype(np.int32)
        # Right-handed with the crack's normal: the boundary's orientation decides.
        return cls(v, t, ring(nr).astype(np.int64), np.asarray(center, dtype=float), **kw)

    @property
    def crack(self) -> SurfaceCrack:
        """The surface as a crack description (the model's)."""
        return SurfaceCrack(self.vertices, self.triangles, name=self.name, pressure=self.pressure,
                            pressure_group=self.pressure_group)

    @property
    def loop_points(self) -> np.ndarray:
        return self.vertices[self.loop]

    # -- the loop's geometry ---------------------------------------------------------------------------------
    def outward(self) -> tuple[np.ndarray, np.ndarray]:
        """At every loop vertex (m, 3) each: the unit in-surface direction
        normal to the loop pointing away from the surface (the propagation
        direction e1 of a planar front) and the unit surface normal (e2), both
        averaged over the vertex's two boundary edges and their triangles."""
        v, t, loop = self.vertices, self.triangles, self.loop
        m = len(loop)
        a, b = loop, np.roll(loop, -1)
        # The triangle of each boundary edge a -> b.
        tri_of = _edge_triangles(t)
        ti = np.array([tri_of[(int(p), int(q))] for p, q in zip(a, b)])
        P = v[t[ti]]
        n = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0])
        n /= np.linalg.norm(n, axis=1)[:, None]
        tang = v[b] - v[a]
        o = np.cross(tang, n)
        o /= np.maximum(np.linalg.norm(o, axis=1), 1e-300)[:, None]
        # Vertex i sits between edge i - 1 and edge i.
        ov = o + np.roll(o, 1, axis=0)
        nv = n + np.roll(n, 1, axis=0)
        nv /= np.maximum(np.linalg.norm(nv, axis=1), 1e-300)[:, None]
        ov -= np.einsum("ij,ij->i", ov, nv)[:, None] * nv
        ov /= np.maximum(np.linalg.norm(ov, axis=1), 1e-300)[:, None]
        assert len(ov) == m
        return ov, nv

    def chains(self, inside: Inside, margin: float) -> list[Chain]:
        """The parts of the front that grow (module doc): every run of loop
        vertices inside the part with `margin` of arc length of outside
        vertices on both sides; the whole loop when it is inside."""
        pts = self.loop_points
        m = len(pts)
        ins = np.asarray(inside(pts), dtype=bool)
        if ins.all():
            return [Chain(np.arange(m), True, ins)]
        if not ins.any():
            return []
        seg = np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1)  # seg[i]: i -> i + 1
        out = []
        start = int(np.flatnonzero(~ins)[0])  # walk from an outside vertex
        i = 0
        while i < m:
            p = (start + i) % m
            if ins[p] and not ins[(p - 1) % m]:
                # A run starts at p: its end.
                q = p
                while ins[(q + 1) % m]:
                    q = (q + 1) % m
                lo, acc = p, 0.0
                while True:  # outside vertices before the run, up to `margin`
                    prev = (lo - 1) % m
                    acc += seg[prev]
                    lo = prev
                    if acc >= margin or ins[(lo - 1) % m] or (lo - 1) % m == q:
                        break
                hi, acc = q, 0.0
                while True:
                    acc += seg[hi]
                    hi = (hi + 1) % m
                    if acc >= margin or ins[(hi + 1) % m] or (hi + 1) % m == lo:
                        break
                n = (hi - lo) % m + 1
                pos = (lo + np.arange(n)) % m
                out.append(Chain(pos, False, ins[pos]))
                i += (q - p) % m + 1
            else:
                i += 1
        return out

    # -- growth ------------------------------------------------------------------------------------------
    def extend(self, chains: list[Chain], new: list[np.ndarray]) -> None:
        """Join each chain to its new polyline (module doc) by a strip of
        triangles and put the new polyline into the loop. Open chains: the
        new polyline's ends are the strip's side edges' far ends (outside
        the part); closed: a loop."""
        v = [self.vertices]
        tris = [self.triangles]
        nv = len(self.vertices)
        loop = self.loop
        replaced: list[tuple[np.ndarray, np.ndarray, bool]] = []
        for ch, B in zip(chains, new):
            B = np.asarray(B, dtype=float)
            A_ids = loop[ch.positions]
            B_ids = nv + np.arange(len(B))
            nv += len(B)
            v.append(B)
            A = self.vertices[A_ids]
            if ch.closed:
                shift = int(np.argmin(np.linalg.norm(B - A[0], axis=1)))
                B_ids = np.roll(B_ids, -shift)
                Bx = np.roll(B, -shift, axis=0)
                pairs = stitch(np.vstack([A, A[:1]]), np.vstack([Bx, Bx[:1]]))
                ai = np.append(A_ids, A_ids[0])
                bi = np.append(B_ids, B_ids[0])
            else:
                pairs = stitch(A, B)
                ai, bi = A_ids, B_ids
            tri = np.array([[ai[i], bi[j], ai[i + 1]] if kind == 0 else [ai[i], bi[j], bi[j + 1]]
                            for kind, i, j in pairs], dtype=np.int64)
            tris.append(tri)
            replaced.append((ch.positions, B_ids, ch.closed))
        verts = np.concatenate(v)
        new_tris = np.concatenate(tris[1:]) if len(tris) > 1 else np.zeros((0, 3), np.int64)
        # Orientation: the strip's normals agree with the old boundary triangles'.
        if len(new_tris):
            old_n = _mean_normal(verts, self.triangles[[i for i in _boundary_triangles(self.triangles, loop)]])
            nn = np.cross(verts[new_tris[:, 1]] - verts[new_tris[:, 0]], verts[new_tris[:, 2]] - verts[new_tris[:, 0]])
            if float(np.einsum("ij,j->i", nn, old_n).sum()) < 0.0:
                raise StripTurnedOver(f"{self.name}: the grown strip turned over (its triangles face the other "
                                         "way): the increment is too large for the front's curvature")
        self.vertices = verts
        self.triangles = np.concatenate([self.triangles, new_tris]).astype(np.int32)
        # The new loop: each open chain's inner vertices replaced by its new polyline.
        m = len(loop)
        keep = np.ones(m, dtype=bool)
        insert: dict[int, np.ndarray] = {}
        for pos, B_ids, closed in replaced:
            if closed:
                self.loop = B_ids.astype(np.int64)
                return
            keep[pos[1:-1]] = False
            insert[int(pos[0])] = B_ids
        out = []
        for i in range(m):
            if keep[i]:
                out.append([loop[i]])
            if i in insert:
                out.append(insert[i])
        self.loop = np.concatenate(out).astype(np.int64)


def boundary_loop(triangles: np.ndarray) -> np.ndarray:
    """The boundary of a consistently oriented triangulation as one loop of
    vertex indices, in the direction its edges run in their triangles."""
    t = np.asarray(triangles)
    directed = t[:, [[0, 1], [1, 2], [2, 0]]].reshape(-1, 2)
    key = np.sort(directed, axis=1)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    bd = directed[cnt[inv.ravel()] == 1]
    if len(bd) == 0:
        raise CrackGeometryError("the crack surface is closed: it has no front")
    nxt = {int(a): int(b) for a, b in bd}
    if len(nxt) != len(bd):
        raise CrackGeometryError("the crack surface's boundary touches itself (a vertex with more than two boundary "
                                 "edges): give a surface with one boundary loop")
    start = int(bd[0, 0])
    loop = [start]
    while True:
        nx = nxt[loop[-1]]
        if nx == start:
            break
        loop.append(nx)
        if len(loop) > len(bd):
            break
    if len(loop) != len(bd):
        raise CrackGeometryError(f"the crack surface's boundary has several loops ({len(bd)} boundary edges, one loop "
                                 f"of {len(loop)}): a growing crack needs a surface with one front loop")
    return np.array(loop, dtype=np.int64)


def resample(points: np.ndarray, spacing: float, closed: bool) -> np.ndarray:
    """A polyline (n, 3) re-sampled at equal arc-length steps of at most
    `spacing` (open: both ends kept; closed: a loop, starting at the first
    point), along the cubic spline through its vertices (chord length
    parameter; periodic when closed): new points on a curved front stay on
    the curve, not on the chords between the old ones."""
    from scipy.interpolate import CubicSpline
    P = np.asarray(points, dtype=float)
    Q = np.vstack([P, P[:1]]) if closed else P
    seg = np.linalg.norm(np.diff(Q, axis=0), axis=1)
    keep = np.concatenate([[True], seg > 1e-12 * max(float(seg.max(initial=0.0)), 1e-300)])
    Q = Q[keep]
    s = np.concatenate([[0.0], np.cumsum(seg[keep[1:]])])
    L = float(s[-1])
    if L <= 0.0 or len(Q) < 2:
        return P[:1].copy()
    n = max(3 if closed else 1, int(math.ceil(L / spacing)))
    if len(Q) < (4 if closed else 3):
        t = np.linspace(0.0, L, n + 1)
        out = np.column_stack([np.interp(t, s, Q[:, k]) for k in range(3)])
    else:
        spline = CubicSpline(s, Q, axis=0, bc_type="periodic" if closed else "not-a-knot")
        # Equal arc length on the spline (its own length, from a fine sampling).
        fine = np.linspace(0.0, L, 8 * n + 1)
        F = spline(fine)
        sf = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(F, axis=0), axis=1))])
        target = np.linspace(0.0, sf[-1], n + 1)
        out = spline(np.interp(target, sf, fine))
        out[0] = Q[0]
        out[-1] = Q[-1]
    return out[:-1] if closed else out


def smooth(vectors: np.ndarray, passes: int, closed: bool) -> np.ndarray:
    """`passes` sweeps of the (1, 2, 1) / 4 filter along a polyline's values
    (n, d) (open: the ends kept): removes vertex-to-vertex zig-zag, leaves a
    linear profile unchanged."""
    V = np.asarray(vectors, dtype=float).copy()
    for _ in range(passes):
        if closed:
            V = 0.25 * np.roll(V, 1, axis=0) + 0.5 * V + 0.25 * np.roll(V, -1, axis=0)
        elif len(V) > 2:
            V[1:-1] = 0.25 * V[:-2] + 0.5 * V[1:-1] + 0.25 * V[2:]
    return V


def extend_ends(B: np.ndarray, inside: Inside, margin: float) -> np.ndarray:
    """An open polyline (n, 3) whose ends must lie outside the part: each
    end carried along the polyline's end tangent until it is `margin`
    beyond the part's boundary (crossing found by bisection)."""
    B = np.asarray(B, dtype=float).copy()
    for end, nb in ((0, 1), (-1, -2)):
        d = B[end] - B[nb]
        nd = np.linalg.norm(d)
        if nd == 0.0:
            continue
        d /= nd
        if not bool(inside(B[end][None])[0]):
            continue
        # March out until outside, then bisect the crossing.
        step, t = max(margin, 1e-12), 0.0
        for _ in range(200):
            t += step
            if not bool(inside((B[end] + t * d)[None])[0]):
                break
            step *= 1.5
        lo, hi = 0.0, t
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if bool(inside((B[end] + mid * d)[None])[0]):
                lo = mid
            else:
                hi = mid
        B[end] = B[end] + (hi + margin) * d
    return B


def front_exit(B: np.ndarray, closed: bool, inside: Inside) -> tuple[str | None, int | None, np.ndarray]:
    """How a new front B (n, 3) meets the part's boundary where it should
    not: ("surface", i) a closed (embedded) front with vertex i outside the
    part; ("split", i) an open front with vertex i outside between inside
    vertices (it broke through into two pieces); ("gone", None) no vertex
    inside; else (None, None). Also the inside mask (n,)."""
    ins = np.asarray(inside(B), dtype=bool)
    if closed:
        out = np.flatnonzero(~ins)
        return ("surface", int(out[0])) if out.size else (None, None), ins
    idx = np.flatnonzero(ins)
    if idx.size == 0:
        return ("gone", None), ins
    inner = np.arange(idx[0], idx[-1] + 1)
    gap = inner[~ins[inner]]
    return (("split", int(gap[0])) if gap.size else (None, None)), ins


def stitch(A: np.ndarray, B: np.ndarray) -> list[tuple[int, int, int]]:
    """Triangles joining two polylines A (m, 3) and B (n, 3) running the same
    way: (0, i, j) is the triangle (A_i, B_j, A_i+1), (1, i, j) is (A_i, B_j,
    B_j+1); at each step the shorter new diagonal."""
    m, n = len(A) - 1, len(B) - 1
    i = j = 0
    out = []
    while i < m or j < n:
        if i == m:
            adv_a = False
        elif j == n:
            adv_a = True
        else:
            adv_a = np.linalg.norm(A[i + 1] - B[j]) <= np.linalg.norm(B[j + 1] - A[i])
        if adv_a:
            out.append((0, i, j))
            i += 1
        else:
            out.append((1, i, j))
            j += 1
    return out


def _edge_triangles(t: np.ndarray) -> dict[tuple[int, int], int]:
    out = {}
    for k, (a, b, c) in enumerate(np.asarray(t)):
        out[(int(a), int(b))] = k
        out[(int(b), int(c))] = k
        out[(int(c), int(a))] = k
    return out


def _boundary_triangles(t: np.ndarray, loop: np.ndarray) -> list[int]:
    e = _edge_triangles(t)
    return [e[(int(a), int(b))] for a, b in zip(loop, np.roll(loop, -1))]


def _mean_normal(v: np.ndarray, tris: np.ndarray) -> np.ndarray:
    n = np.cross(v[tris[:, 1]] - v[tris[:, 0]], v[tris[:, 2]] - v[tris[:, 0]]).sum(axis=0)
    return n / max(np.linalg.norm(n), 1e-300)


__all__ = ["GrowingSurface", "Chain", "boundary_loop", "resample", "smooth", "extend_ends", "stitch",
           "front_exit"]
