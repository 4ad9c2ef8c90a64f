"""Where a crack tip goes: the kink angle (maximum hoop stress or maximum energy
release rate), the local stress intensity factors of a kink, and the
equivalent K along it.

Conventions (docs/sifs.md, "Conventions"): angles in the tip frame (e1 out of the
crack, e2 = e1 turned by +90 degrees), positive toward e2: K_II > 0 kinks
the crack toward -e2 (pure mode II: -70.53 degrees).
"""
from __future__ import annotations

import math

import numpy as np


def kink_angle(K_I: float, K_II: float, criterion: str = "max_hoop") -> float:
    """The kink angle (radians, in the tip frame, positive toward e2) of a tip
    with K_I, K_II. A negative K_I (lips pressed: with contact it is ~0)
    counts as 0."""
    kI = max(K_I, 0.0)
    if criterion == "max_hoop":
        # d sigma_theta_theta / d theta = 0: K_I sin(theta) + K_II (3 cos(theta) - 1) = 0, the root
        # with the larger hoop stress. (Written with sign(K_II) in front of the root, as in some
        # texts, it is only right for K_II > 0: that form belongs to the ratio K_I / K_II.)
        if K_II == 0.0:
            return 0.0
        return 2.0 * math.atan((kI - math.sqrt(kI * kI + 8.0 * K_II * K_II)) / (4.0 * K_II))
    # Maximum energy release rate: maximise k1^2 + k2^2 of the local fields.
    th = np.linspace(-math.radians(85.0), math.radians(85.0), 3401)
    k1, k2 = local_sifs(kI, K_II, th)
    t0 = float(th[np.argmax(k1 * k1 + k2 * k2 - 1e9 * np.minimum(k1, 0.0) ** 2)])
    lo, hi = t0 - 1e-3, t0 + 1e-3
    for _ in range(60):  # golden-section refinement
        a, b = hi - 0.618 * (hi - lo), lo + 0.618 * (hi - lo)
        ga, gb = (np.hypot(*local_sifs(kI, K_II, np.array([v]))) for v in (a, b))
        lo, hi = (lo, b) if ga > gb else (a, hi)
    return 0.5 * (lo + hi)


def local_sifs(K_I: float, K_II: float, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The first-order stress intensity factors of a kink at theta:
    sigma_theta_theta and sigma_r_theta of the tip field times sqrt(2 pi r)."""
    c1, c3 = np.cos(theta / 2), np.cos(3 * theta / 2)
    s1, s3 = np.sin(theta / 2), np.sin(3 * theta / 2)
    k1 = 0.25 * (3 * c1 + c3) * K_I - 0.75 * (s1 + s3) * K_II
    k2 = 0.25 * (s1 + s3) * K_I + 0.25 * (c1 + 3 * c3) * K_II
    return k1, k2


def equivalent_k(K_I: float, K_II: float, theta: float, clamp: bool = True) -> float:
    """K_eq = sigma_theta_theta sqrt(2 pi r) along the kink: cos(theta/2)
    (K_I cos^2(theta/2) - 3/2 K_II sin(theta)) (pure mode II: 1.1547 K_II).
    clamp: a negative K_I (pressed lips) counts as 0; without it K_eq is the
    linear value (Delta K of a cycle whose lips would pass through each
    other, contact off)."""
    c = math.cos(theta / 2)
    return c * ((max(K_I, 0.0) if clamp else K_I) * c * c - 1.5 * K_II * math.sin(theta))
