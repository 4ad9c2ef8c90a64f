"""Where K is computed along a 3D crack front, and what K is at its ends
(cracklip.fracture.sif_3d computes the domain integrals at these points).

Front points. Along every front piece the points are spaced by the hat
half-width l(s) each wants (sif_3d: HAT_ELEMENTS front elements, shorter
where the front curves, but never closer than MIN_HAT_ELEMENTS element
sizes: a hat narrower than two elements scatters), capped so that the piece
gets at least Options.sif_points points (MIN_POINTS = 16; a loop's length
/ n, an open piece's length / (n - 1)) where that leaves hats of
COUNT_HAT_ELEMENTS (3) element sizes (front_points: two-element hats run
low). So a front shorter than (n - 1) x 3 element sizes gets fewer points:
the mesh along the front limits them (refine with mesh.tip_h). An open piece keeps
both ends.

Positions asked for. Options.sif_angles / sif_angle_step (parametric
angles of an elliptical crack, degrees: the ellipse center + a cos t
e_a + b sin t e_b, e_b = normal x e_a) and sif_arc_lengths (from the start
of each piece, front.csv's s) name positions where K is wanted. A position
within SNAP_END floors of an open piece's end is that end; one whose
neighbours (asked positions, ends) are at least the local spacing away
becomes a front point, the others placed in the gaps as above; where the
asked positions are denser than the spacing K is interpolated between the
front points (a cubic spline in s through their K, periodic on a loop),
so that asking for many positions never thins the front points; those
rows say so (K_source "interpolation"). Every row at an asked position has
``requested`` true.

Ends on a symmetry plane (cracklip.scene.symmetry). The crack continues in
its mirror image, so the end is an interior point of the whole front: its
q is symmetric about the plane and the domain integral over the part's half
plus its mirror image is I_half (1 + s_m) per mode, with the normalisation
int q ds twice the half's. The signs s_m of the mirror (MIRROR_SIGNS):
with the front meeting the plane at right angles (e3 = the plane's normal,
e1 and e2 in the plane) the mirror M = I - 2 n n^T maps the frame (e1, e2,
e3) at x to (e1, e2, -e3) at M x, so in local coordinates the mirrored
field is (u1, u2, -u3)(x1, x2, -x3): the opening u2 and the sliding u1 are
even, the tearing u3 odd. K_I and K_II keep their values in the mirror
(s = +1), K_III changes sign (s = -1) and vanishes on the plane. The hat
correction sees the mirror images of the neighbours (K_-1 = s K_1).

Ends on a free surface. There the singularity is no longer the square
root (the corner singularity of a front meeting a surface: K of the
square-root field tends to 0 or infinity within a boundary layer), and the
end's own domain integral (half a hat, q not vanishing on the surface)
depends on the mesh: the corner crack at a hole gave 374, 380, 381 MPa
sqrt(mm) at the bore against 420 at 82 degrees. What an engineer needs at
phi -> 0 and 90 degrees is the value of the front's K distribution there,
as Newman and Raju's fits give it: their phi = 0 value continues the
interior distribution (it is a fit over the front; the boundary layer, a
small fraction of the crack size for nu = 0.3, is left out) [from memory:
Newman and Raju, NASA TM-85793]; NASGRO's corner and surface crack tables
take it from them, FRANC3D users commonly drop or extrapolate the end
points and code_aster reports the end nodes as they are [from memory, not
checked]. The rule here (END_*): K at a free-surface end is the
least-squares quadratic in the arc length through K kappa^(1/6) at the
interior points within END_WINDOW of the piece's length from the end (at
least the END_POINTS points nearest it; the end's own value left out),
evaluated at the end and divided by the end's kappa^(1/6) (a piece with
one interior point: that point's K kappa^(1/6) over the end's, with a
warning); K_source "end_extrapolation", the end's own domain value kept
as K_domain. kappa is the front's curvature at the end and at the
points (END_SHAPE: at least 1 / the piece's length), of the conic
least-squares fitted through all the piece's points (conic_curvatures),
where the front curves outward, that conic is an ellipse and its weights
flatten K along the interior points (end_curvatures; else K itself, as on
a straight front).
The whole piece, because Irwin's relation holds for the ellipse, not for
a local bend: a conic through the end's nearest points followed the
grown front's own lag at the ends (surface crack a/c0 = 0.2, steps 5-6:
the ends' K 0.82-0.84 of Newman and Raju's against 0.885-0.904 with the
whole piece's conic), and the polyline's own curvature at the end jumped
from 5 to 23 between steps of the a/c0 = 1 growth (the interior 7-9).
Why the weight: along an elliptical crack (semi-axes a
<= c) under uniform tension K = sigma sqrt(pi a) / E(k) (sin^2 phi +
(a/c)^2 cos^2 phi)^(1/4) (Irwin 1962, exact); with p the distance from
the ellipse's centre to the tangent at the point, (sin^2 phi + (a/c)^2
cos^2 phi) = a^2 / p^2 and the curvature is kappa = p^3 / (a^2 c^2), so
K is proportional to kappa^(-1/6): K kappa^(1/6) is constant along the
front (a circle: kappa constant, the weight changes nothing). Near the end
of a slender front's major axis K itself varies on the length of the
front's radius of curvature there (a^2 / c: from phi = 0 to 20 degrees
Newman and Raju's K rises by 7 % at a/c = 0.41), which front points a
few elements apart cannot follow: a quadratic through them misses the
end value whatever the K (Newman and Raju's own values at the points of
a surface crack a/c = 0.41, a/t = 0.21 on a mesh of a/8 (hats of 3
elements): -7.5 %). K kappa^(1/6) varies only with what the ellipse
alone does not give (the free face, finite width, bending; Newman and
Raju's g, f_w, M), slowly: Newman and Raju's own K at points 3 elements
of a/8, a/12, a/16 apart gives -2.3, -0.9, -0.4 % at a/c = 0.41 (-2.4,
-1.4, -0.8 % at 0.2) where the plain quadratic gives -8.0, -6.6, -4.9 %
(+0.7, -5.2, -7.2 %) (docs/growth.md). On a penny-like end (kappa constant)
and on a straight front (kappa under 1 / the length) it is the plain
quadratic. On the surface crack a/c = 1, a/t = 0.2 at a/12 it gives
1.3204 against Newman-Raju's 1.3198 at phi = 0 (the end's own domain
value: 1.011).
"""
from __future__ import annotations

import math
import typing

import numpy as np

#: Default of Options.sif_points: the fewest front points per piece.
MIN_POINTS = 16

#: Mirror signs of (K_I, K_II, K_III) across a symmetry plane that the
#: front meets at right angles (module doc).
MIRROR_SIGNS = np.array([1.0, 1.0, -1.0])

#: Steps may fall this fraction of a step below the floor (two steps in a
#: gap of 1.97 floors rather than one).
FLOOR_SLACK = 0.1

#: A requested position within SNAP_END floors of an open piece's end is
#: that end (the P1 front ends within about an element of the exact one),
#: within SNAP floors of another front point that point.
SNAP_END = 0.25
SNAP = 1e-3

#: Free-surface end value (module doc): the window (END_WINDOW of the
#: piece's length, at most END_CURVATURE radii of curvature of the front
#: there), the fewest interior points, the polynomial degree.
END_WINDOW = 0.5
END_CURVATURE = 1.0
END_POINTS = 4
END_DEGREE = 2
#: The end value extrapolates K kappa^END_SHAPE (module doc: constant
#: along an elliptical crack under uniform tension), kappa the front's
#: curvature, at least 1 / the piece's length.
END_SHAPE = 1.0 / 6.0
#: ... where the weighted K varies along the interior points no more than
#: this (relative range) above K itself (end_curvatures).
END_ROUGHER = 0.02

#: Where a row's K comes from (the rows' K_source).
SOURCES = {"domain": "the point's domain integral (hat along the front)",
           "mirrored_domain": "an end on a symmetry plane: its domain and the domain's mirror image",
           "end_extrapolation": ("a free-surface end: the interior points' K kappa^(1/6) extrapolated to the end, "
                                 "over the end's kappa^(1/6)"),
           "interpolation": "an asked position between front points: K interpolated between them"}


def requested_positions(options, crack, x: np.ndarray, s: np.ndarray, length: float, closed: bool,
                        tol: float) -> tuple[np.ndarray, list[str]]:
    """Arc lengths along a front piece (vertices x (n, 3) at arc lengths s)
    where K is asked for (Options.sif_angles, sif_angle_step on an
    elliptical crack, sif_arc_lengths), sorted and unique, and notes on
    positions that cannot be used. tol: a distance (about half an element)
    within which an angle just beyond an open piece's end is that end."""
    out: list[float] = []
    notes: list[str] = []
    angles = list(options.sif_angles or [])
    step = float(options.sif_angle_step or 0.0)
    if step > 0.0:
        angles += list(np.arange(0.0, 360.0 - 1e-9, step))
    if angles:
        if hasattr(crack, "parametric_angle"):
            out += _angle_positions(crack, np.radians(angles), x, s, length, closed, tol)
        else:
            notes.append(f"crack {crack.name!r}: options.sif_angles / sif_angle_step need an elliptical crack "
                         "(a parametric angle); give options.sif_arc_lengths")
    for v in options.sif_arc_lengths or []:
        if closed:
            out.append(v % length)
        elif v <= length + tol:
            out.append(min(v, length))
    if not out:
        return np.zeros(0), notes
    v = np.sort(np.asarray(out, dtype=float))
    keep = np.concatenate([[True], np.diff(v) > 1e-9 * max(length, 1e-300)])
    v = v[keep]
    if closed and len(v) > 1 and length - v[-1] + v[0] <= 1e-9 * length:
        v = v[:-1]
    return v, notes


def unmatched_positions(options, crack, pieces: list[tuple[np.ndarray, np.ndarray, float, bool, float]]
                        ) -> list[str]:
    """Notes on the positions asked for by value that fall on no piece of a
    crack's front (pieces: (x, s, length, closed, tol) as requested_positions
    takes them): an explicit options.sif_angles angle the front does not
    reach (sif_angle_step's sweep of the whole turn is not named), an
    options.sif_arc_lengths value beyond every open piece's end. Such a
    position gave no row and no word (a corner crack of radius 2, front
    3.14 long, asked for s = 5: nothing)."""
    notes = []
    angles = [float(a) for a in (options.sif_angles or [])]
    if angles and hasattr(crack, "parametric_angle"):
        missed = [a for a in angles
                  if not any(_angle_positions(crack, np.radians([a]), x, s_, L, closed, tol)
                             for x, s_, L, closed, tol in pieces)]
        if missed:
            notes.append(f"crack {crack.name!r}: options.sif_angles {missed} (degrees) are on no piece of its front "
                         "inside the part: no K there (front.csv's parametric_angle_deg has the angles the front "
                         "covers)")
    lengths = [float(v) for v in (options.sif_arc_lengths or [])]
    if lengths and not any(closed for _, _, _, closed, _ in pieces):
        longest = max((L + tol for _, _, L, _, tol in pieces), default=0.0)
        missed = [v for v in lengths if v > longest]
        if missed:
            notes.append(f"crack {crack.name!r}: options.sif_arc_lengths {missed} are beyond the end of every piece "
                         f"of its front (the longest is {max(L for _, _, L, _, _ in pieces):.4g} long; arc lengths "
                         "run from 0 at each piece's start, front.csv's s): no K there")
    return notes


def _angle_positions(crack, theta: np.ndarray, x: np.ndarray, s: np.ndarray, length: float, closed: bool,
                     tol: float) -> list[float]:
    """Arc lengths where the piece's parametric angle (unwrapped along its
    vertices) equals theta (mod 2 pi)."""
    t = np.unwrap(crack.parametric_angle(x))
    sv = np.asarray(s, dtype=float)
    if closed:
        t = np.append(t, t[0] + 2.0 * math.pi * np.sign(t[-1] - t[0] or 1.0))
        sv = np.append(sv, length)
    out = []
    lo, hi = min(t[0], t[-1]), max(t[0], t[-1])
    for th in np.asarray(theta, dtype=float):
        ks = np.arange(math.floor((lo - th) / (2 * math.pi)) - 1, math.ceil((hi - th) / (2 * math.pi)) + 2)
        for k in ks:
            target = th + 2.0 * math.pi * k
            i = np.flatnonzero((t[:-1] - target) * (t[1:] - target) <= 0.0)
            for j in i:
                dt = t[j + 1] - t[j]
                f = 0.0 if dt == 0.0 else (target - t[j]) / dt
                out.append(float(sv[j] + f * (sv[j + 1] - sv[j])))
            if not closed and not len(i):  # just beyond an end (within tol): that end
                for j0, j1, at in ((0, 1, 0.0), (-1, -2, length)):
                    rate = abs((sv[j1] - sv[j0]) / ((t[j1] - t[j0]) or 1e-300))
                    if abs(target - t[j0]) * rate <= tol:
                        out.append(at)
    return [v % length if closed else min(max(v, 0.0), length) for v in out]


def piece_stations(s: np.ndarray, l: np.ndarray, length: float, closed: bool, floor: float, minimum: int,
                   requested: np.ndarray | None = None, count_floor: float = 0.0
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Front points along a piece whose vertices at arc lengths s (from 0,
    increasing) want hat half-widths l (module doc): their arc lengths, a
    flag per point for the requested positions that are front points, and
    the requested positions that are not (interpolated). The minimum count
    shortens the hats down to count_floor at most (the front's curvature
    and an explicit spacing down to floor)."""
    s, l = np.asarray(s, dtype=float), np.asarray(l, dtype=float)
    cap = max(length / max(minimum if closed else minimum - 1, 1), count_floor)
    l = np.maximum(np.minimum(l, cap), floor)
    if closed:   # the loop unrolled twice, so that a gap may pass s = length
        s = np.concatenate([s, s + length, [2.0 * length]])
        l = np.concatenate([l, l, l[:1]])
    elif s[-1] < length:
        s, l = np.append(s, length), np.append(l, l[-1])
    dens = 1.0 / l
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (dens[1:] + dens[:-1]) * np.diff(s))])
    req = np.zeros(0) if requested is None else np.asarray(requested, dtype=float)
    # The anchors: the ends of an open piece, and the requested positions
    # at least the local spacing from the others (denser ones would thin
    # the points: they are interpolated); one within SNAP_END floors of an end
    # is that end.
    anchors = [] if closed else [0.0, length]
    is_req = [] if closed else [False, False]
    between = []
    for i, r in enumerate(req):
        others = np.delete(req, i)
        if not closed:
            others = np.concatenate([others, [0.0, length]])
        d = np.abs(others - r)
        if closed:
            d = np.minimum(d, length - d)
        step = (1.0 - FLOOR_SLACK) * max(float(np.interp(r, s, l)), floor)
        if not closed and min(r, length - r) <= SNAP_END * floor:
            is_req[0 if r <= length - r else 1] = True
        elif not d.size or d.min() >= step:
            anchors.append(float(r))
            is_req.append(True)
        else:
            between.append(float(r))
    if closed and not anchors:
        n = max(1, int(round(cum[len(cum) // 2])))  # cum at s = length
        n = min(n, max(1, int(length / floor + FLOOR_SLACK)))
        targets = np.arange(n) * (cum[len(cum) // 2] / n)
        return _snap(np.interp(targets, cum, s), np.zeros(n, dtype=bool), between, length, closed, floor)
    order = np.argsort(anchors)
    anchors, is_req = [anchors[i] for i in order], [is_req[i] for i in order]
    out, flags = [], []
    gaps = list(zip(anchors[:-1], anchors[1:]))
    if closed:
        gaps.append((anchors[-1], anchors[0] + length))
    for k, (a, b) in enumerate(gaps):
        out.append(a)
        flags.append(is_req[k])
        ca, cb = np.interp([a, b], s, cum)
        n = max(1, int(round(cb - ca)))
        n = min(n, max(1, int((b - a) / floor + FLOOR_SLACK)))
        for j in range(1, n):
            out.append(float(np.interp(ca + j * (cb - ca) / n, cum, s)))
            flags.append(False)
    if not closed:
        out.append(anchors[-1])
        flags.append(is_req[-1])
    out = np.asarray(out)
    if closed:
        out = out % length
        o = np.argsort(out)
        out, flags = out[o], np.asarray(flags)[o]
    return _snap(out, np.asarray(flags, dtype=bool), between, length, closed, floor)


def _snap(st: np.ndarray, flags: np.ndarray, between: list[float], length: float, closed: bool, floor: float
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Requested positions within SNAP floors of a front point are that point."""
    rest = []
    for r in between:
        d = np.abs(st - r)
        if closed:
            d = np.minimum(d, length - d)
        k = int(np.argmin(d))
        if d[k] <= SNAP * floor:
            flags[k] = True
        else:
            rest.append(r)
    return st, flags, np.asarray(rest, dtype=float)


def mirrored_sequence(n: int, mirror_start: bool, mirror_end: bool) -> tuple[np.ndarray, np.ndarray, bool]:
    """The points of an open piece of n points with their mirror images at
    the ends on symmetry planes, as one sequence (the hat correction along
    the whole front): indices into the piece, a flag per entry for mirror
    images and whether the sequence is a loop (both ends mirrored). Mirrored at the start: n - 1, ..., 1
    (mirrored), 0, ..., n - 1; at the end: 0, ..., n - 1, n - 2, ..., 0
    (mirrored); at both: the loop 0, ..., n - 1, n - 2, ..., 1."""
    own = np.arange(n)
    if mirror_start and mirror_end and n >= 2:
        back = np.arange(n - 2, 0, -1)
        return np.concatenate([own, back]), np.concatenate([np.zeros(n, bool), np.ones(len(back), bool)]), True
    idx, flag = own, np.zeros(n, dtype=bool)
    if mirror_start and n >= 2:
        idx = np.concatenate([own[:0:-1], idx])
        flag = np.concatenate([np.ones(n - 1, bool), flag])
    if mirror_end and n >= 2:
        idx = np.concatenate([idx, own[-2::-1]])
        flag = np.concatenate([flag, np.ones(n - 1, bool)])
    return idx, flag, False


def end_window(length: float, curvature: np.ndarray) -> float:
    """The window of an end value: END_WINDOW x the piece's length, at most
    END_CURVATURE / the largest |curvature| of the front there."""
    kappa = float(np.abs(np.asarray(curvature, dtype=float)).max(initial=0.0))
    return min(END_WINDOW * length, END_CURVATURE / kappa if kappa > 0.0 else math.inf)


def shape_weights(curvature, length: float) -> np.ndarray:
    """kappa^END_SHAPE of the front's curvatures, kappa at least 1 / the
    piece's length (a straight or inward-curving front: 1 / length, the
    weights equal)."""
    floor = 1.0 / max(float(length), 1e-300)
    return np.maximum(np.asarray(curvature, dtype=float), floor) ** END_SHAPE


def _conic(points: np.ndarray) -> tuple[np.ndarray, float, np.ndarray, np.ndarray]:
    """The conic a x^2 + b x y + c y^2 + d x + e y + f = 0 least-squares
    fitted to `points` (n >= 5, 3) in their best plane: (origin, scale, the
    plane's axes (2, 3), (a, b, c, d, e, f)) in coordinates (x - origin) /
    scale along those axes."""
    P = np.asarray(points, dtype=float)
    o = P.mean(axis=0)
    scale = max(float(np.abs(P - o).max()), 1e-300)
    _, _, vt = np.linalg.svd((P - o) / scale, full_matrices=False)
    uv = (P - o) / scale @ vt[:2].T
    x, y = uv[:, 0], uv[:, 1]
    # full_matrices: with five points the conic is V's sixth row (the null vector), which the economy
    # SVD of the 5 x 6 matrix leaves out (its last row, the fifth, is another conic)
    _, _, ct = np.linalg.svd(np.column_stack([x * x, x * y, y * y, x, y, np.ones_like(x)]), full_matrices=True)
    return o, scale, vt[:2], ct[-1]


def conic_curvatures(points: np.ndarray, at: np.ndarray) -> np.ndarray:
    """The curvature at `at` (m, 3) of the conic (a x^2 + b x y + c y^2 + d
    x + e y + f = 0) least-squares fitted to `points` (n >= 5, 3) in their
    best plane: the curvature of the ellipse (or circle, or line: about 0)
    a front's points follow, for the end value's weights (module doc)."""
    return _curvatures(_conic(points), at)


def _curvatures(fit, at: np.ndarray) -> np.ndarray:
    """The curvature at `at` (m, 3) of a conic fitted by _conic."""
    o, scale, axes, (a, b, c, d, e, _) = fit
    q = (np.asarray(at, dtype=float) - o) / scale @ axes.T
    fx = 2 * a * q[:, 0] + b * q[:, 1] + d
    fy = b * q[:, 0] + 2 * c * q[:, 1] + e
    num = np.abs(fy * fy * 2 * a - 2 * fx * fy * b + fx * fx * 2 * c)
    return num / np.maximum(np.hypot(fx, fy) ** 3, 1e-300) / scale


def end_curvatures(points: np.ndarray, at: np.ndarray, K: np.ndarray) -> np.ndarray | None:
    """The front's curvatures at `at` (the end, then the interior points
    whose K (n, ...) is given) for the end value's weights (module doc): of
    the conic through the whole piece's `points` (conic_curvatures), where
    that conic is an ellipse and the weights flatten K rather than roughen
    it (the relative range of |K| kappa^END_SHAPE over the interior points at
    most END_ROUGHER above that of |K|; Irwin's relation makes it constant).
    None elsewhere: the end value is then the quadratic through K itself.
    Why: the weights multiply the end's K by (kappa_i / kappa_end)^(1/6)
    of the conic, so a conic that is not the front's ellipse (a hyperbola,
    or a slender ellipse through the scatter of a grown front's few points)
    moves the end value by as much: on the corner crack of
    demos/scenes/corner_crack_growth.toml (5 front points, while the conic
    through five points was computed wrong: the economy SVD's last row,
    not its null vector) the conics were hyperbolas of curvature 0.02-0.05
    at the ends and 0.5-21 inside, against about 0.8 for the front, and
    the end values came out 3-5 times the interior K (1098-1707 against
    289-379 MPa sqrt(mm)), enough to fail the part by K_c.
    """
    fit = _conic(points)
    a, b, c = fit[3][:3]
    if b * b - 4.0 * a * c >= 0.0:  # a parabola or hyperbola: no ellipse through the points
        return None
    kappa = _curvatures(fit, at)
    mag = np.linalg.norm(np.asarray(K, dtype=float).reshape(len(kappa) - 1, -1), axis=1)
    if len(mag) < 2 or not mag.mean() > 0.0:
        return None
    weighted = mag * np.maximum(kappa[1:], 1e-300) ** END_SHAPE
    if np.ptp(weighted) / weighted.mean() > np.ptp(mag) / mag.mean() + END_ROUGHER:
        return None
    return kappa


def end_value(s: np.ndarray, K: np.ndarray, end: float, window: float, curvature: np.ndarray | None = None,
              end_curvature: float | None = None, length: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """K (...) at a free-surface end at arc length `end` from the interior
    points' K (n, ...) at arc lengths s (the end itself left out by the
    caller): the END_DEGREE least-squares polynomial in the distance from
    the end through the points within `window` of it (end_window; at least
    the END_POINTS nearest), evaluated at the end. With the front's
    curvature at the points and at the end (and the piece's length) the
    polynomial goes through K shape_weights and its end value is divided by
    the end's weight (module doc); without them through K. Returns the
    value and the indices of the points used."""
    d = np.abs(np.asarray(s, dtype=float) - end)
    order = np.argsort(d)
    use = order[d[order] <= window]
    if len(use) < END_POINTS:
        use = order[:END_POINTS]
    deg = min(END_DEGREE, len(use) - 1)
    flat = np.asarray(K, dtype=float).reshape(len(d), -1)[use]
    w_end = 1.0
    if curvature is not None:
        flat = flat * shape_weights(np.asarray(curvature, dtype=float)[use], length)[:, None]
        w_end = float(shape_weights(end_curvature, length))
    V = np.vander(d[use], deg + 1)                     # columns d^deg .. d^0
    coef, *_ = np.linalg.lstsq(V, flat, rcond=None)
    return (coef[-1] / w_end).reshape(np.shape(K)[1:]), use


def interpolate(s: np.ndarray, K: np.ndarray, at: np.ndarray, length: float, closed: bool) -> np.ndarray:
    """K (m, ...) at arc lengths `at` by a cubic spline in s through K (n,
    ...) at the front points s (periodic on a loop; linear through fewer
    than 4 points)."""
    import scipy.interpolate
    s = np.asarray(s, dtype=float)
    flat = np.asarray(K, dtype=float).reshape(len(s), -1)
    at = np.asarray(at, dtype=float)
    if closed:
        ss, ff = np.append(s, s[0] + length), np.vstack([flat, flat[:1]])
        x = (at - s[0]) % length + s[0]
        if len(s) >= 3:
            out = scipy.interpolate.CubicSpline(ss, ff, bc_type="periodic", axis=0)(x)
        else:
            out = np.stack([np.interp(x, ss, ff[:, j]) for j in range(ff.shape[1])], axis=1)
    elif len(s) >= 4:
        out = scipy.interpolate.CubicSpline(s, flat, axis=0)(at)
    else:
        out = np.stack([np.interp(at, s, flat[:, j]) for j in range(flat.shape[1])], axis=1)
    return out.reshape((len(at),) + np.shape(K)[1:])


__all__ = ["MIN_POINTS", "MIRROR_SIGNS", "END_WINDOW", "END_CURVATURE", "END_POINTS", "END_DEGREE", "END_SHAPE",
           "SOURCES", "requested_positions", "unmatched_positions", "piece_stations", "mirrored_sequence",
           "end_window", "shape_weights", "conic_curvatures", "end_curvatures", "END_ROUGHER", "end_value",
           "interpolate"]
