"""Exact solutions of planar cracks embedded in an infinite 3D body.

- Penny-shaped crack of radius a under remote tension sigma normal to it
  (Sneddon 1946): K_I = 2 sigma sqrt(a / pi) along the front; the opening of
  the two lips together (the jump) is 8 (1 - nu^2) sigma sqrt(a^2 - r^2) / (pi E).
- Inclined penny crack under remote uniaxial stress sigma at angle beta to
  the crack's plane (Tada, Paris, Irwin, The Stress Analysis of Cracks
  Handbook; the formulas of code_aster's benchmark V6.04.159 and of the
  issue): with sigma_n = sigma sin^2 beta and tau = sigma sin beta cos beta
  the crack-plane normal and shear tractions,
      K_I   = 2 sigma_n sqrt(a / pi),
      K_II  = 4 tau sqrt(a / pi) cos(omega) / (2 - nu),
      K_III = 4 (1 - nu) tau sqrt(a / pi) sin(omega) / (2 - nu),
  omega the angle along the front measured from the shear direction; the
  shear part alone (penny_shear_k) is the penny whose faces carry a uniform
  shear tau, whose slip is 8 (1 - nu) tau sqrt(a^2 - r^2) / (pi (2 - nu) mu)
  along the shear everywhere (penny_slip).
- Embedded elliptical crack (Irwin 1962) with semi-axes a >= b under remote
  tension sigma normal to it: K_I(phi) = sigma sqrt(pi b) / E(k) (sin^2 phi +
  (b / a)^2 cos^2 phi)^(1/4), k^2 = 1 - b^2 / a^2, E the complete elliptic
  integral of the second kind, phi the parametric angle (x = a cos phi,
  y = b sin phi).

Conventions (cracklip's front frame): at a front point e1 points out of the
crack (propagation), e2 along the crack normal n (the + side), e3 = e1 x e2.
K_II > 0 when the + side moves along +e1 relative to the - side, K_III > 0
when it moves along +e3. For a crack in the plane normal to n with the shear
traction tau along a unit vector t in the plane (the + side pulled along +t
by the remote stress), omega is measured from t about n, so that e1 = cos
omega t + sin omega (n x t) and the signs above hold as written.
"""
from __future__ import annotations

import math

import numpy as np
import scipy.special


def penny_k(sigma: float, a: float) -> float:
    """K_I of a penny crack of radius a under remote tension sigma."""
    return 2.0 * sigma * math.sqrt(a / math.pi)


def penny_opening(r: np.ndarray, sigma: float, a: float, E: float, nu: float) -> np.ndarray:
    """Crack opening (the jump of the normal displacement) at distance r (n,)
    from the centre: 8 (1 - nu^2) sigma sqrt(a^2 - r^2) / (pi E), 0 outside."""
    r = np.asarray(r, dtype=float)
    return 8.0 * (1.0 - nu * nu) * sigma * np.sqrt(np.maximum(a * a - r * r, 0.0)) / (math.pi * E)


def inclined_penny_k(sigma: float, beta: float, a: float, nu: float, omega: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """K_I, K_II, K_III (each (n,)) along the front of a penny crack of radius
    a under remote uniaxial stress sigma at angle beta (radians) to the
    crack's plane, at angles omega (n,) from the shear direction."""
    omega = np.asarray(omega, dtype=float)
    sn = sigma * math.sin(beta) ** 2
    tau = sigma * math.sin(beta) * math.cos(beta)
    K_I = np.full(omega.shape, 2.0 * sn * math.sqrt(a / math.pi))
    K_II, K_III = penny_shear_k(tau, a, nu, omega)
    return K_I, K_II, K_III


def penny_shear_k(tau: float, a: float, nu: float, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """K_II, K_III (each (n,)) along the front of a penny crack of radius a
    whose faces carry a uniform shear traction tau (the + face pulled along
    t, omega (n,) from t): 4 tau sqrt(a / pi) cos(omega) / (2 - nu) and
    4 (1 - nu) tau sqrt(a / pi) sin(omega) / (2 - nu) (Tada P.24.22)."""
    omega = np.asarray(omega, dtype=float)
    root = math.sqrt(a / math.pi)
    return (4.0 * tau * root * np.cos(omega) / (2.0 - nu),
            4.0 * (1.0 - nu) * tau * root * np.sin(omega) / (2.0 - nu))


def penny_slip(r: np.ndarray, tau: float, a: float, E: float, nu: float) -> np.ndarray:
    """The slip (the jump of the tangential displacement, along t) at
    distance r (n,) from the centre of a penny crack of radius a under a
    uniform face shear tau: 8 (1 - nu) tau sqrt(a^2 - r^2) / (pi (2 - nu) mu),
    mu = E / (2 (1 + nu)); 0 outside (Eshelby 1957; Segall, Earthquake and
    Volcano Deformation, eq. 4.74 gives one face's half)."""
    r = np.asarray(r, dtype=float)
    mu = E / (2.0 * (1.0 + nu))
    return 8.0 * (1.0 - nu) * tau * np.sqrt(np.maximum(a * a - r * r, 0.0)) / (math.pi * (2.0 - nu) * mu)


def elliptic_e(k2: float) -> float:
    """The complete elliptic integral of the second kind E(k), k^2 = k2 (the
    parameter m of scipy.special.ellipe)."""
    if not 0.0 <= k2 <= 1.0:
        raise ValueError(f"elliptic_e: k^2 must lie in [0, 1], got {k2}")
    return float(scipy.special.ellipe(k2))


def irwin_k(sigma: float, a: float, b: float, phi: np.ndarray) -> np.ndarray:
    """K_I (n,) along an embedded elliptical crack with semi-axes a >= b under
    remote tension sigma, at parametric angles phi (n,) (0 at the end of the
    major axis, where K is least)."""
    if not a >= b > 0.0:
        raise ValueError(f"irwin_k: semi-axes must satisfy a >= b > 0, got a = {a}, b = {b}")
    phi = np.asarray(phi, dtype=float)
    Ek = elliptic_e(1.0 - (b / a) ** 2)
    return sigma * math.sqrt(math.pi * b) / Ek * (np.sin(phi) ** 2 + (b / a) ** 2 * np.cos(phi) ** 2) ** 0.25


def parametric_angle(x: np.ndarray, a: float, b: float) -> np.ndarray:
    """The parametric angle phi of points (n, 2) in the ellipse's axes (x along
    the semi-axis a): atan2(y / b, x / a)."""
    x = np.asarray(x, dtype=float).reshape(-1, 2)
    return np.arctan2(x[:, 1] / b, x[:, 0] / a)


__all__ = ["penny_k", "penny_opening", "inclined_penny_k", "penny_shear_k", "penny_slip", "elliptic_e", "irwin_k",
           "parametric_angle"]
