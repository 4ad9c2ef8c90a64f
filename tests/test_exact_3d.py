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


def test_newman_raju_bending():
    """The bending multiplier H (module doc of cracklip.fracture.handbook),
    by hand at a/c = 0.6, a/t = 0.3 (the plate of
    demos/scenes/residual_stress_3d.toml): H1 = 1 - 0.34 (0.3) - 0.11 (0.6)
    (0.3) = 0.8782 at the surface, G1 = -1.292, G2 = 0.55 - 1.05 (0.68173) +
    0.47 (0.46476) = 0.052618, H2 = 1 - 0.3876 + 0.0047356 = 0.61714 at the
    deepest point. A shallow crack (a/t -> 0) sees the face's bending stress
    as a tension: H = 1. The two branches meet at a/c = 1 (H1 = 1 - 0.45
    a/t, G1 = -1.34, G2 = -0.03 from either side). K = (S + H S_b) ..."""
    from cracklip.exact.newman_raju import surface_H
    assert surface_H(3.0, 5.0, 10.0, 0.0) == pytest.approx(0.8782, abs=1e-12)
    assert surface_H(3.0, 5.0, 10.0, math.pi / 2) == pytest.approx(0.6171356, abs=1e-7)
    assert np.allclose(surface_H(1e-6, 1e-5, 1.0, np.linspace(0, math.pi / 2, 5)), 1.0, atol=1e-5)
    for at in (0.1, 0.3, 0.6):
        for phi in (0.0, 0.7, math.pi / 2):
            assert surface_H(at, at * (1 - 1e-12), 1.0, phi) == pytest.approx(surface_H(at, at * (1 + 1e-12), 1.0, phi),
                                                                              abs=1e-9)
    phi = np.array([0.0, 0.6, math.pi / 2])
    k = surface_crack_k(100.0, 3.0, 5.0, 10.0, 20.0, phi, bending=-150.0)
    kt = surface_crack_k(100.0, 3.0, 5.0, 10.0, 20.0, phi)
    assert np.allclose(k, kt * (1.0 - 1.5 * surface_H(3.0, 5.0, 10.0, phi)), rtol=1e-14)
    with pytest.raises(ValueError, match="corner crack's bending"):
        surface_crack_k(1.0, 1.0, 2.0, 5.0, 20.0, phi, corner=True, bending=1.0)
