"""Where K is computed along a 3D front (cracklip.fracture.front_sampling):
the front points' spacing, the minimum number per piece and what limits
it, positions asked for, the mirror images at symmetry planes and the
free-surface end value, on plain arrays (no mesh)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from cracklip.exact.embedded_cracks import inclined_penny_k
from cracklip.fracture import front_sampling as fs
from cracklip.fracture.sif_3d import hat_deconvolve
from cracklip.scene.crack_surface import EllipticalCrack


def test_minimum_points_and_the_floor():
    """A piece of length 2.76 whose hats want 0.6: 16 points (the minimum,
    15 equal steps) where hats of 0.1 fit, 7 points when the floor is 0.4
    (a step may not fall below it: the mesh limits them), both ends kept;
    a loop gets 16 equal steps."""
    s = np.linspace(0.0, 2.76, 30)
    st, flags, between = fs.piece_stations(s, np.full(30, 0.6), 2.76, False, 0.1, 16)
    assert len(st) == 16 and st[0] == 0.0 and st[-1] == 2.76
    assert np.ptp(np.diff(st)) < 1e-12 and not flags.any() and not between.size
    st, _, _ = fs.piece_stations(s, np.full(30, 0.6), 2.76, False, 0.4, 16)
    assert len(st) == 7 and np.diff(st).min() >= 0.4 * (1 - fs.FLOOR_SLACK)
    loop = np.linspace(0.0, 2 * np.pi, 101)[:-1]
    st, _, _ = fs.piece_stations(loop, np.full(100, 1.0), 2 * np.pi, True, 0.1, 16)
    assert len(st) == 16 and np.ptp(np.diff(np.append(st, 2 * np.pi))) < 1e-9
    # the hats wanted where they are smaller than the minimum asks
    st, _, _ = fs.piece_stations(loop, np.full(100, 0.2), 2 * np.pi, True, 0.1, 16)
    assert len(st) == round(2 * np.pi / 0.2)


def test_requested_positions():
    """Asked positions spaced at least the local step apart become front
    points (flagged), denser ones are interpolated and never thin the
    points; an asked position near an end is that end."""
    s = np.linspace(0.0, 2.76, 30)
    st, flags, between = fs.piece_stations(s, np.full(30, 0.28), 2.76, False, 0.19, 16,
                                           np.array([0.01, 1.0, 2.76]))
    assert set(np.round(st[flags], 6)) == {0.0, 1.0, 2.76} and not between.size
    assert np.diff(st).max() <= 0.2 + 1e-9
    dense = np.linspace(0.0, 2.76, 19)                 # every 0.153 < the step 0.184
    st, flags, between = fs.piece_stations(s, np.full(30, 0.28), 2.76, False, 0.19, 16, dense)
    assert len(st) == 15 and flags[0] and flags[-1]
    assert len(between) + flags.sum() == len(dense)
    assert np.all(np.abs(st[flags][:, None] - dense[None]).min(axis=1) < 1e-9)


def test_angle_positions_on_an_ellipse():
    """Parametric angles on a quarter ellipse's front (a = 2 along x, b =
    1.5, the corner crack's): every 30 degrees gives the arc lengths of
    those points; 90.2 degrees, a tenth of an element beyond the end, is
    the end."""
    class Opts:
        sif_angles, sif_angle_step, sif_arc_lengths = [90.2], 30.0, None
    crack = EllipticalCrack((4.0, 0.0, 5.0), (0.0, 1.0, 0.0), 2.0, b=1.5, axis=(1.0, 0.0, 0.0))
    t = np.linspace(0.0, math.pi / 2, 200)
    x = crack.point(t)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(x, axis=0), axis=1))])
    pos, notes = fs.requested_positions(Opts, crack, x, s, float(s[-1]), False, 0.05)
    want = np.interp(np.radians([0, 30, 60, 90]), t, s)
    assert not notes and len(pos) == 4 and np.allclose(pos, want, atol=1e-6)

    class Other:
        sif_angles, sif_angle_step, sif_arc_lengths = [10.0], 0.0, [0.5, 9.0]
    class Polygon:
        name = "polygon"
    pos, notes = fs.requested_positions(Other, Polygon(), x, s, float(s[-1]), False, 0.05)
    assert notes and "elliptical" in notes[0] and np.allclose(pos, [0.5])


def test_mirror_signs_of_the_inclined_penny():
    """The mirror signs (K_I, K_II keep, K_III flips) on the closed form: an
    inclined penny (beta = 45 degrees) is symmetric about the plane of its
    normal and the load, which maps the front point at omega from the shear
    direction to -omega: K(-omega) = MIRROR_SIGNS K(omega), K_III = 0 and
    K_II largest on the plane (omega = 0, pi)."""
    omega = np.linspace(0.0, math.pi, 13)
    K = np.column_stack(inclined_penny_k(1.0, math.radians(45.0), 1.0, 0.3, omega))
    Km = np.column_stack(inclined_penny_k(1.0, math.radians(45.0), 1.0, 0.3, -omega))
    assert np.allclose(Km, K * fs.MIRROR_SIGNS, atol=1e-14)
    assert abs(K[0, 2]) < 1e-14 and abs(K[-1, 2]) < 1e-14 and abs(K[0, 1]) == pytest.approx(np.abs(K[:, 1]).max())


def test_mirrored_sequence_and_the_hat_correction():
    """The hat correction of a piece between two symmetry planes (a quarter
    of a loop) sees the mirror images: with K = cos(2 s) (even about both
    ends, s in [0, pi/2]) its averages are deconvolved as on the whole
    loop; K_III-like odd data vanish at the planes."""
    idx, mirrored, loop = fs.mirrored_sequence(5, True, True)
    assert loop and list(idx) == [0, 1, 2, 3, 4, 3, 2, 1] and mirrored.sum() == 3
    idx, mirrored, loop = fs.mirrored_sequence(4, True, False)
    assert not loop and list(idx) == [3, 2, 1, 0, 1, 2, 3] and list(mirrored) == [True] * 3 + [False] * 4
    idx, mirrored, loop = fs.mirrored_sequence(4, False, True)
    assert list(idx) == [0, 1, 2, 3, 2, 1, 0] and list(mirrored) == [False] * 4 + [True] * 3
    # averages of cos(2 s) over hats l on the quarter, deconvolved on the mirrored loop
    n, l = 7, (math.pi / 2) / 6
    st = np.arange(n) * l
    avg = np.cos(2 * st) * (2 * (1 - np.cos(2 * l)) / (2 * l) ** 2)      # the hat average of cos(2 s)
    idx, mirrored, loop = fs.mirrored_sequence(n, True, True)
    K = hat_deconvolve(avg[idx], np.full(len(idx), l), np.full(len(idx), l), loop)[~mirrored]
    assert np.abs(K - np.cos(2 * st)).max() < np.abs(avg - np.cos(2 * st)).max() / 20


def _nr_front(ac: float, corner: bool, points: int):
    """Newman-Raju's K (a = 1, t = 5, width 20 c) at `points` equally spaced
    front points of a semi- or quarter-elliptical front (arc length s), the
    ends left out, with the ends' values and the front's curvature there."""
    from cracklip.exact.newman_raju import surface_crack_k
    a, c = 1.0, 1.0 / ac
    th = np.linspace(0.0, math.pi / 2 if corner else math.pi, 20001)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(c * np.cos(th)), np.diff(a * np.sin(th))))])
    K = surface_crack_k(1.0, a, c, 5.0, 20.0 * c, np.minimum(th, math.pi - th), corner=corner)
    st = np.linspace(0.0, s[-1], points)[1:-1]
    return st, np.interp(st, s, K), s[-1], (K[0], K[-1]), (c / a ** 2, a / c ** 2)


def test_end_value_rule():
    """The end value: the least-squares quadratic through the interior
    points within the window (half the piece, at most a radius of
    curvature; at least END_POINTS points), evaluated at the end: exact for
    a quadratic; on Newman-Raju's own distributions (arc-length sampling)
    it finds their phi = 0 and 90 degree values: semicircular surface crack
    with 16 points -0.2 %, quarter-circular corner crack -0.4 % and -0.3 %,
    corner a/c = 0.5 with 32 points -1.0 % and -0.2 %, surface a/c = 0.2
    (the end's radius of curvature a^2 / c = 0.2 a) with 32 points -1.1 %
    (half the piece as the window: +17 %)."""
    d = np.array([0.3, 0.6, 0.9, 1.2, 2.0])
    val, used = fs.end_value(d, 1.0 + 2.0 * d - 3.0 * d ** 2, 0.0, 1.0)
    assert val == pytest.approx(1.0, abs=1e-12) and len(used) == fs.END_POINTS
    val, _ = fs.end_value(d, np.column_stack([1 + d, 2 - d ** 2]), 0.0, 1.0)
    assert np.allclose(val, [1.0, 2.0])
    assert fs.end_window(3.0, [0.0, 0.1]) == pytest.approx(min(fs.END_WINDOW * 3.0, fs.END_CURVATURE / 0.1))
    assert fs.end_window(3.0, [0.0]) == fs.END_WINDOW * 3.0
    for ac, corner, points, bound in ((1.0, False, 16, 0.004), (1.0, True, 16, 0.006), (0.5, True, 32, 0.015),
                                      (0.2, False, 32, 0.015)):
        st, K, L, ref, kappa = _nr_front(ac, corner, points)
        for e, (end, k_end, kap) in enumerate(((0.0, ref[0], kappa[0]), (L, ref[1], kappa[1]))):
            if e == 1 and not corner:
                continue
            val, _ = fs.end_value(st, K, end, fs.end_window(L, [kap]))
            assert abs(val / k_end - 1.0) < bound, (ac, corner, e, val / k_end - 1.0)
    st, K, L, ref, kappa = _nr_front(0.2, False, 32)
    assert fs.end_value(st, K, 0.0, fs.END_WINDOW * L)[0] / ref[0] - 1.0 > 0.1


def _ellipse_front(a: float, c: float, spacing: float):
    """A semi-elliptical front x = c cos phi, y = a sin phi, phi from 0 to
    pi: arc lengths of equally spaced front points about `spacing` apart
    (ends left out), their parametric angles, the curvature there and at
    the ends, and the piece's length."""
    th = np.linspace(0.0, math.pi, 40001)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(c * np.cos(th)), np.diff(a * np.sin(th))))])
    st = np.linspace(0.0, s[-1], int(round(s[-1] / spacing)) + 1)[1:-1]
    phi = np.interp(st, s, th)

    def kappa(f):
        return a * c / (c ** 2 * np.sin(f) ** 2 + a ** 2 * np.cos(f) ** 2) ** 1.5
    return st, phi, kappa(phi), float(kappa(0.0)), float(s[-1])


def test_irwin_shape_is_constant_with_the_curvature_weight():
    """Along an elliptical crack under uniform tension K is proportional to
    (sin^2 phi + (a/c)^2 cos^2 phi)^(1/4) (Irwin), and that is kappa^(-1/6)
    (front_sampling's doc: p^3 = a^2 c^2 kappa, p the centre's distance to
    the tangent): K kappa^(1/6) is constant along the front. The end value
    through K kappa^(1/6) then finds the phi = 0 value exactly from points
    three elements of a/8 apart (a/c = 0.2 and 0.41), where the plain
    quadratic misses it by +1.7 % and -7.0 % (as the first point falls
    within the end's radius of curvature a^2 / c or not); on a circle and
    on a straight front (curvature under 1 / the length) the weight changes
    nothing."""
    plain_errors = []
    for a, c in ((0.2, 1.0), (0.2148, 0.522)):
        st, phi, kap, kap_end, L = _ellipse_front(a, c, 3 * a / 8)
        K = (np.sin(phi) ** 2 + (a / c) ** 2 * np.cos(phi) ** 2) ** 0.25
        assert np.ptp(K * kap ** fs.END_SHAPE) < 1e-12 * K.max()
        K_end = math.sqrt(a / c)
        win = fs.end_window(L, [kap_end])
        plain, _ = fs.end_value(st, K, 0.0, win)
        weighted, used = fs.end_value(st, K, 0.0, win, kap, kap_end, L)
        assert weighted == pytest.approx(K_end, rel=1e-10) and len(used) == fs.END_POINTS
        plain_errors.append(plain / K_end - 1.0)
    assert plain_errors[1] < -0.06 and plain_errors[0] > 0.01, plain_errors
    d = np.array([0.3, 0.6, 0.9, 1.2, 2.0])
    K = 1.0 + 2.0 * d - 3.0 * d ** 2
    for kap, kap_end in ((np.full(5, 0.5), 0.5), (np.array([1e-3, -1e-3, 0.0, 2e-3, 1e-4]), 0.0)):
        assert fs.end_value(d, K, 0.0, 1.0, kap, kap_end, 10.0)[0] == pytest.approx(1.0, abs=1e-12)
    assert np.allclose(fs.shape_weights([-2.0, 0.0, 0.05, 1.0], 10.0), [0.1 ** fs.END_SHAPE] * 3 + [1.0], rtol=1e-14)


def test_conic_curvature():
    """The curvature from a conic fitted to front points: exact on an
    ellipse (any plane, any 7 points of it, at the end of its major axis
    where it is largest: c / a^2) and on a circle, about 0 on a straight
    line."""
    rng = np.random.default_rng(3)
    R, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    for a, c in ((0.2, 1.0), (0.2148, 0.522), (1.0, 1.0)):
        ph = np.concatenate([[0.0], np.sort(rng.uniform(0.1, 1.2, 6))])
        P = np.column_stack([c * np.cos(ph), a * np.sin(ph), np.zeros(7)]) @ R.T + [1.0, -2.0, 0.5]
        k = fs.conic_curvatures(P, P)
        assert k == pytest.approx(a * c / (c ** 2 * np.sin(ph) ** 2 + a ** 2 * np.cos(ph) ** 2) ** 1.5, rel=1e-6)
    line = np.outer(np.linspace(0.0, 1.0, 7), [1.0, 2.0, -0.5])
    assert np.abs(fs.conic_curvatures(line, line)).max() < 1e-6


def test_end_weights_need_an_ellipse_that_flattens_k():
    """The conic through exactly five points is the one through them (the
    null vector of the 5 x 6 system; the economy SVD's last row was another
    conic, a hyperbola through none of them): five points of a quarter
    ellipse a/c = 0.5 give its exact curvatures, and the end value's
    weights (end_curvatures) are kept there with Irwin's K. They are
    dropped where the weights would roughen K (K constant along that
    ellipse: Irwin's variation added) and where the conic is a hyperbola.
    The five points of a corner crack grown on a coarse mesh
    (demos/scenes/corner_crack_growth.toml, step 3; with the wrong conic
    its end values were 815 and 1098 against 289-337 inside, and the part
    failed by K_c two steps later): a conic of curvature 0.78-0.83 (the
    front is about a quarter circle of radius 1.25), end values within 15 %
    of their nearest interior K."""
    a, c = 1.0, 2.0
    phi = np.radians([0.0, 20.0, 45.0, 70.0, 90.0])
    P = np.column_stack([c * np.cos(phi), a * np.sin(phi), np.zeros(5)])
    exact = a * c / (c ** 2 * np.sin(phi) ** 2 + a ** 2 * np.cos(phi) ** 2) ** 1.5
    assert fs.conic_curvatures(P, P) == pytest.approx(exact, rel=1e-9)
    K_irwin = (np.sin(phi) ** 2 + (a / c) ** 2 * np.cos(phi) ** 2) ** 0.25
    at = P[[0, 1, 2, 3]]
    k = fs.end_curvatures(P, at, K_irwin[1:4, None])
    assert k is not None and k == pytest.approx(exact[:4], rel=1e-9)
    assert fs.end_curvatures(P, at, np.ones((3, 1))) is None
    t = np.linspace(0.2, 1.4, 6)
    hyperbola = np.column_stack([np.cosh(t), np.sinh(t), np.zeros(6)])
    assert fs.end_curvatures(hyperbola, hyperbola[:5], np.ones((4, 1))) is None
    grown = np.array([[3.99944, 7.4e-05, 3.67304], [4.36983, 6.1e-05, 3.76554], [4.74881, 5.6e-05, 4.00981],
                      [5.05978, 4.2e-05, 4.46008], [5.14781, 3.9e-05, 5.0]])
    K = np.array([[336.913, -1.083, -0.221], [303.020, -0.141, -0.210], [288.815, 0.042, -0.082]])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(grown, axis=0), axis=1))])
    for end in (0, 4):
        k = fs.end_curvatures(grown, grown[[end, 1, 2, 3]], K)
        assert k is not None and np.all((k > 0.7) & (k < 0.9)), k
        K_end, _ = fs.end_value(s[1:4], K, s[end], fs.end_window(s[-1], [k[0]]), k[1:], k[0], s[-1])
        nearest = K[0 if end == 0 else 2, 0]
        assert abs(K_end[0] / nearest - 1.0) < 0.15, (end, K_end)


def test_end_value_on_newman_raju_with_growth_spacing():
    """Newman and Raju's own K (a/t = 0.2, a/c = 0.41 and 0.2) at front
    points three elements of a/8 apart, as the surface-crack growth samples
    it: the plain quadratic misses the phi = 0 value by -8.0 % at a/c =
    0.41 (+0.7 % at 0.2: the front's steep rise within a^2 / c of the end
    falls between the points or not), K kappa^(1/6) finds it within -2.3
    and -2.4 % (what remains varies with the free face's g, not with the
    ellipse)."""
    from cracklip.exact.newman_raju import surface_crack_k
    out = {}
    for ac in (0.41, 0.2):
        a, c = 1.0, 1.0 / ac
        st, phi, kap, kap_end, L = _ellipse_front(a, c, 3 * a / 8)
        K = surface_crack_k(1.0, a, c, 5.0, 20.0 * c, np.minimum(phi, math.pi - phi))
        K_end = float(surface_crack_k(1.0, a, c, 5.0, 20.0 * c, np.array([0.0]))[0])
        win = fs.end_window(L, [kap_end])
        out[ac] = (fs.end_value(st, K, 0.0, win)[0] / K_end - 1.0,
                   fs.end_value(st, K, 0.0, win, kap, kap_end, L)[0] / K_end - 1.0)
    assert out[0.41][0] < -0.07 and all(-0.03 < out[ac][1] < 0.0 for ac in out), out


def test_interpolation():
    """K between front points by a cubic spline: periodic on a loop, with
    the end values on an open piece."""
    s = np.linspace(0.0, 2 * np.pi, 17)[:-1]
    K = np.column_stack([np.cos(s), np.sin(2 * s)])
    at = np.array([0.1, 3.0, 6.2])
    out = fs.interpolate(s, K, at, 2 * np.pi, True)
    assert np.abs(out - np.column_stack([np.cos(at), np.sin(2 * at)])).max() < 3e-3
    s = np.linspace(0.0, 1.0, 6)
    out = fs.interpolate(s, s ** 3, np.array([0.05, 0.55]), 1.0, False)
    assert np.allclose(out, [0.05 ** 3, 0.55 ** 3], atol=2e-3)


def test_positions_on_no_piece_are_named():
    """A corner crack's quarter front (parametric angles 0..90 degrees,
    length pi/2 for a = 1): an explicit angle of 180 degrees and an arc
    length of 5 fall on no piece, which gave no row and no word; they are
    now named (the sweep of sif_angle_step over the whole turn is not, nor
    are positions that fall on the front)."""
    from types import SimpleNamespace
    crack = EllipticalCrack((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 1.0, axis=(1.0, 0.0, 0.0), name="corner")
    t = np.linspace(0.0, math.pi / 2, 40)
    x = np.column_stack([np.cos(t), np.sin(t), np.zeros_like(t)])
    pieces = [(x, t.copy(), math.pi / 2, False, 0.02)]
    opts = SimpleNamespace(sif_angles=[0.0, 45.0, 180.0], sif_angle_step=5.0, sif_arc_lengths=[1.0, 5.0])
    notes = fs.unmatched_positions(opts, crack, pieces)
    assert len(notes) == 2
    assert "options.sif_angles [180.0] (degrees) are on no piece" in notes[0]
    assert "options.sif_arc_lengths [5.0] are beyond the end of every piece" in notes[1] and "1.571 long" in notes[1]
    fine = SimpleNamespace(sif_angles=[0.0, 90.0], sif_angle_step=5.0, sif_arc_lengths=[1.5])
    assert fs.unmatched_positions(fine, crack, pieces) == []
