"""The closed penny crack's closed form (cracklip.exact.closed_penny): its
pieces checked against each other and against independent computations
(the stress transformation, the near-front slip, the energy balance,
the published unit case)."""
import math

import numpy as np
import pytest

from cracklip.exact.closed_penny import closed_penny, closed_penny_inclined, inclined_compression
from cracklip.exact.embedded_cracks import inclined_penny_k

E, NU, A = 2.0, 0.3, 1.3


def test_inclined_compression_is_the_traction_on_the_plane():
    """p and |tau| from sigma = -s e_L e_L resolved on the plane of normal n:
    the traction sigma n, its normal part -p, its tangential part of
    length |tau| along t (the direction the closed form's K use)."""
    rng = np.random.default_rng(3)
    for _ in range(5):
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        beta = rng.uniform(0.05, 1.5)
        # e_L at angle beta to n.
        w = np.cross(n, rng.normal(size=3))
        w /= np.linalg.norm(w)
        eL = math.cos(beta) * n + math.sin(beta) * w
        s = 2.7
        traction = (-s * np.outer(eL, eL)) @ n
        p, tau = inclined_compression(s, beta)
        assert -traction @ n == pytest.approx(p, rel=1e-13)
        assert np.linalg.norm(traction - (traction @ n) * n) == pytest.approx(tau, rel=1e-13)


def test_k_from_the_slip_near_the_front():
    """K_II and K_III are the near-front limits of the slip profile: with
    the jump of each mode 8 (1 - nu^2) K_II sqrt(d / 2 pi) / E along e1 and
    8 (1 + nu) K_III sqrt(d / 2 pi) / E along e3 (d = a - r), and the slip
    t s(r), t = cos(omega) e1 + sin(omega) e3."""
    cp = closed_penny(p=1.0, tau=0.7, mu=0.25, a=A, nu=NU)
    assert cp.state == "slip" and cp.tau_eff == pytest.approx(0.45)
    omega = np.linspace(0.0, 2 * math.pi, 9)
    KI, KII, KIII = cp.k(omega)
    assert np.all(KI == 0.0)
    d = 1e-7 * A  # s / sqrt(d) reaches its limit to d / 4a; a^2 - r^2 loses 1e-9
    s = cp.slip(np.array([A - d]), E)[0]
    root = math.sqrt(d / (2 * math.pi))
    assert np.allclose(KII, s * np.cos(omega) * E / (8 * (1 - NU ** 2) * root), rtol=1e-7, atol=1e-14)
    assert np.allclose(KIII, s * np.sin(omega) * E / (8 * (1 + NU) * root), rtol=1e-7, atol=1e-14)


def test_energy_balance():
    """The energy released along the front, int G a d(omega) with
    G = (1 - nu^2) K_II^2 / E + (1 + nu) K_III^2 / E, equals d/da of the
    work (1/2) int tau_eff s dA of the relieved shear (numerical integral of
    the slip and a central difference in a)."""
    def work(a):
        cp = closed_penny(1.0, 0.7, 0.25, a, NU)
        r = np.linspace(0.0, a, 20001)
        f = 0.5 * cp.tau_eff * cp.slip(r, E) * 2 * math.pi * r
        return np.trapz(f, r)
    da = 1e-4 * A
    released = (work(A + da) - work(A - da)) / (2 * da)
    cp = closed_penny(1.0, 0.7, 0.25, A, NU)
    om = np.linspace(0.0, 2 * math.pi, 2001)
    _, KII, KIII = cp.k(om)
    G = ((1 - NU ** 2) * KII ** 2 + (1 + NU) * KIII ** 2) / E
    assert np.trapz(G * A, om) == pytest.approx(released, rel=1e-6)
    # and the closed form 8 (1 - nu) tau_eff^2 a^2 / ((2 - nu) mu)
    mu_s = E / (2 * (1 + NU))
    assert released == pytest.approx(8 * (1 - NU) * 0.45 ** 2 * A ** 2 / ((2 - NU) * mu_s), rel=1e-6)


def test_stick_slip_and_frictionless_limit():
    """Friction lowers the shear to tau - mu p; at mu p >= tau the crack
    sticks (no K, no slip); frictionless, K_II and K_III are the shear part
    of the inclined penny (Tada P.24.22) at the same angle to the plane."""
    om = np.array([0.0, math.pi / 2, 1.1])
    for beta in (math.radians(30), math.radians(45), math.radians(60)):
        free = closed_penny_inclined(1.0, beta, 0.0, A, NU)
        _, KII, KIII = free.k(om)
        _, tII, tIII = inclined_penny_k(1.0, math.pi / 2 - beta, A, NU, om)
        assert np.allclose(KII, tII, rtol=1e-14) and np.allclose(KIII, tIII, rtol=1e-14)
        # Slip iff tan(beta) > mu: just below and just above.
        for mu, state in ((0.999 * math.tan(beta), "slip"), (1.001 * math.tan(beta), "stick")):
            cp = closed_penny_inclined(1.0, beta, mu, A, NU)
            assert cp.state == state
            assert cp.p == pytest.approx(math.cos(beta) ** 2)
            if state == "stick":
                assert all(np.all(k == 0.0) for k in cp.k(om)) and np.all(cp.slip(np.array([0.0]), E) == 0.0)
            else:
                assert cp.tau_eff == pytest.approx(math.cos(beta) * (math.sin(beta) - mu * math.cos(beta)))
    # A negative shear slips the other way.
    assert closed_penny(1.0, -0.7, 0.25, A, NU).tau_eff == pytest.approx(-0.45)


def test_unit_cases_of_the_notes():
    """a = 1, sigma = 1, nu = 0.3 (the table of the project's notes, §1.5):
    K_II(0) and K_III(90 deg)."""
    table = {(30, 0.0): (0.57483, 0.40238), (30, 0.3): (0.27614, 0.19330), (45, 0.0): (0.66375, 0.46463),
             (45, 0.3): (0.46463, 0.32524), (60, 0.3): (0.47526, 0.33268)}
    for (beta, mu), (kii, kiii) in table.items():
        _, KII, KIII = closed_penny_inclined(1.0, math.radians(beta), mu, 1.0, 0.3).k(np.array([0.0, math.pi / 2]))
        assert KII[0] == pytest.approx(kii, abs=1e-5) and KIII[1] == pytest.approx(kiii, abs=1e-5)
    assert closed_penny_inclined(1.0, math.radians(30), 0.6, 1.0, 0.3).state == "stick"


def test_bad_input():
    with pytest.raises(ValueError, match="pressure"):
        closed_penny(-1.0, 0.5, 0.3, 1.0, 0.3)
    with pytest.raises(ValueError, match="beta"):
        closed_penny_inclined(1.0, math.pi / 2, 0.3, 1.0, 0.3)
