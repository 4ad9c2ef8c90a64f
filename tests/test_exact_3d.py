"""The closed forms the 3D crack checks measure against (cracklip.exact):
limits that tie them together, and published numbers."""
import math

import numpy as np
import pytest

from cracklip.exact.embedded_cracks import (elliptic_e, inclined_penny_k, irwin_k, parametric_angle, penny_k,
                                            penny_opening)
from cracklip.exact.newman_raju import surface_crack_F, surface_crack_k


def test_penny_crack():
    # K_I = 2 sigma sqrt(a / pi); code_aster V3.04.156 quotes 1.5957 MPa sqrt(m)
    # for a = 2 m, sigma = 1 MPa.
    assert penny_k(1.0, 2.0) == pytest.approx(1.5957, abs=1e-4)  # quoted to 4 decimals
    # The opening is largest at the centre, 8 (1 - nu^2) sigma a / (pi E), and 0 at the front.
    assert penny_opening(np.array([0.0, 1.0]), 1.0, 1.0, 1.0, 0.3).tolist() == pytest.approx(
        [8 * 0.91 / math.pi, 0.0])


def test_inclined_penny_limits_and_unit_case():
    om = np.linspace(0.0, 2 * math.pi, 13)
    KI, KII, KIII = inclined_penny_k(1.0, math.pi / 2, 1.0, 0.3, om)  # load normal to the crack
    assert np.allclose(KI, penny_k(1.0, 1.0)) and np.allclose(KII, 0.0) and np.allclose(KIII, 0.0)
    KI, KII, KIII = inclined_penny_k(1.0, math.pi / 4, 1.0, 0.3, np.array([0.0, math.pi / 2]))
    # Unit case of the project's notes (a = 1, sigma = 1, 45 degrees, nu = 0.3), recomputed from
    # the handbook form (2/pi) sigma sin^2 sqrt(pi a), 4/(pi (2 - nu)) sigma sin cos sqrt(pi a), ...
    assert KI[0] == pytest.approx(2 / math.pi * 0.5 * math.sqrt(math.pi), rel=1e-14)
    assert KI[0] == pytest.approx(0.56419, abs=1e-5)
    assert KII[0] == pytest.approx(0.66375, abs=1e-5) and abs(KII[1]) < 1e-15
    assert KIII[1] == pytest.approx(0.46463, abs=1e-5) and KIII[0] == 0.0


def test_irwin_ellipse():
    phi = np.linspace(0.0, math.pi, 7)
    # A circle is the penny crack.
    assert np.allclose(irwin_k(1.0, 1.0, 1.0, phi), penny_k(1.0, 1.0), rtol=1e-14)
    # code_aster SSLV110 (a = 25, b = 6, sigma = 1): references 4.068 (phi = 90) and 1.9929 (phi = 0).
    assert elliptic_e(1 - (6 / 25) ** 2) == pytest.approx(1.067740, abs=1e-6)
    k = irwin_k(1.0, 25.0, 6.0, np.array([math.pi / 2, 0.0]))
    assert k[0] == pytest.approx(4.068, rel=5e-4) and k[1] == pytest.approx(1.9929, rel=5e-4)
    assert parametric_angle(np.array([[0.0, 6.0], [25.0, 0.0]]), 25.0, 6.0).tolist() == [math.pi / 2, 0.0]
    with pytest.raises(ValueError):
        irwin_k(1.0, 1.0, 2.0, phi)


def test_newman_raju():
    # The notes' sample values, K / (S sqrt(pi a)), c/b = 0.1: semi-circular a/t = 0.2 and
    # semi-elliptical a/c = 0.5, a/t = 0.5 (deepest point, surface point).
    def beta(a, c, t, phi):
        return surface_crack_k(1.0, a, c, t, c / 0.1, np.array([phi]))[0] / math.sqrt(math.pi * a)
    assert beta(0.2, 0.2, 1.0, math.pi / 2) == pytest.approx(0.6684, abs=1e-4)
    assert beta(0.2, 0.2, 1.0, 0.0) == pytest.approx(0.7446, abs=1e-4)
    assert beta(0.5, 1.0, 1.0, math.pi / 2) == pytest.approx(1.0311, abs=1e-4)
    assert beta(0.5, 1.0, 1.0, 0.0) == pytest.approx(0.8658, abs=1e-4)
    # A long shallow crack (a/c -> 0, a/t -> 0, narrow c/b) tends to the edge crack in a half
    # plane at its deepest point: F = M1 = 1.13 (the edge-crack factor 1.12 to the fit's accuracy).
    assert surface_crack_F(1e-4, 1e2, 1.0, 1e4, np.array([math.pi / 2]))[0] == pytest.approx(1.13, abs=2e-3)
    with pytest.raises(ValueError, match="range"):
        surface_crack_F(0.9, 1.0, 1.0, 10.0, np.array([0.0]))
