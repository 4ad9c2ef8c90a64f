"""Least-squares fits along a front piece (cracklip.fracture.front_fit):
leave-one-out choice of the size, the second mesh's check that a fit does
not miss K's own shape, the fit's spread from the scatter."""
import math

import numpy as np
import pytest

from cracklip.fracture.front_fit import SHAPE_RATIO, fit_spread, loo_fit, piece_basis


def _noise(n: int, seed: int, size: float) -> np.ndarray:
    return size * np.random.default_rng(seed).standard_normal(n)


def test_piece_basis_loop_and_open():
    s = np.linspace(0.0, 2.0, 9)
    B, sizes = piece_basis(s, True, 4.0, 5)
    assert B.shape == (9, 5) and sizes == [1, 3, 5]
    assert np.allclose(B[:, 1], np.cos(2 * math.pi * s / 4.0)) and np.allclose(B[:, 4], np.sin(4 * math.pi * s / 4.0))
    B, sizes = piece_basis(s, False, 4.0, 3)
    assert B.shape == (9, 3) and sizes == [1, 2, 3]
    assert np.allclose(B[:, 1], np.linspace(-1.0, 1.0, 9)) and np.allclose(B[:, 2], 1.5 * B[:, 1] ** 2 - 0.5)


def test_fit_removes_scatter_and_keeps_the_shape():
    """K = 1 + 0.2 cos t on 24 points of a loop, scatter 1e-3 (different on
    the two meshes): the fit (first harmonic, by leave-one-out, passing the
    check) is within 6e-4 of the shape everywhere, where K itself scatters
    by up to 2.5e-3."""
    n = 24
    s = 2 * math.pi * np.arange(n) / n
    shape = 1.0 + 0.2 * np.cos(s)
    K = (shape + _noise(n, 1, 1e-3))[:, None]
    other = (shape - 0.004 + _noise(n, 2, 1e-3))[:, None]   # the other mesh: its own error and scatter
    B, sizes = piece_basis(s, True, 2 * math.pi, n // 4)
    fit, k = loo_fit(B, np.ones(n, bool), K, sizes, other=other)
    assert k.tolist() == [3]
    assert np.abs(fit[:, 0] - shape).max() < 6e-4 < np.abs(K[:, 0] - shape).max()
    # the fit's spread: sqrt(h) sigma, h = 3 / n on an even loop
    sd = fit_spread(B, np.ones(n, bool), K, k)
    r = K[:, 0] - fit[:, 0]
    assert sd[:, 0] == pytest.approx(np.sqrt(3 / n) * np.sqrt(np.sum(r ** 2) / (n - 3)), rel=1e-9)


def test_a_fit_that_misses_the_shape_is_refused():
    """K with a third harmonic of 5 % on 20 points, fits of at most 5 terms
    (harmonics 0-2): leave-one-out alone takes one and misses the shape by
    up to 5 % (a wrong K reported), the second mesh's residuals share that
    shape (sum / difference far above SHAPE_RATIO), so no fit is taken and
    K is returned as it is."""
    n = 20
    s = 2 * math.pi * np.arange(n) / n
    shape = 1.0 + 0.05 * np.cos(3 * s)
    K = (shape + _noise(n, 3, 5e-4))[:, None]
    other = (shape + _noise(n, 4, 5e-4))[:, None]
    B, sizes = piece_basis(s, True, 2 * math.pi, n // 4)
    blind, _ = loo_fit(B, np.ones(n, bool), K, sizes)
    assert np.abs(blind[:, 0] - shape).max() > 0.04
    fit, k = loo_fit(B, np.ones(n, bool), K, sizes, other=other)
    assert k.tolist() == [0] and np.array_equal(fit, K)
    r, ro = K[:, 0] - blind[:, 0], other[:, 0] - blind[:, 0]
    assert np.linalg.norm(r + ro) > 10 * SHAPE_RATIO * np.linalg.norm(r - ro)
    assert np.all(np.isnan(fit_spread(B, np.ones(n, bool), K, k)))


def test_open_piece_fit_leaves_out_free_surface_points():
    """A Legendre fit on an open piece over its inner points: a quadratic
    K with scatter is recovered at the inner points; the end points (on a
    free surface, off the trend) do not pull the fit."""
    n = 21
    s = np.linspace(0.0, 3.0, n)
    t = 2 * s / 3.0 - 1.0
    shape = 1.0 - 0.1 * t ** 2
    K = shape + _noise(n, 5, 3e-4)
    K[0] += 0.2
    K[-1] -= 0.3
    use = np.ones(n, bool)
    use[[0, -1]] = False
    other = shape + 0.002 + _noise(n, 6, 3e-4)
    B, sizes = piece_basis(s, False, 3.0, n // 4)
    fit, k = loo_fit(B, use, K[:, None], sizes, other=other[:, None])
    assert k[0] >= 3
    assert np.abs(fit[use, 0] - shape[use]).max() < 4e-4
