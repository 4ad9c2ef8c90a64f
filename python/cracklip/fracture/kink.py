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


def kink_twist_3d(K_I: float, K_II: float, K_III: float, nu: float) -> tuple[float, float]:
    """The kink beta and twist gamma (radians) of a 3D front point with K_I,
    K_II, K_III.

    beta: code_aster's SITT_MAX_DEVER kink (maximum hoop stress generalised
    with mode III), as read in code_aster's source
    (code_aster/MacroCommands/post_rupture_ops.py: puissance,
    terme_general, racine, trigo):

        k_i = K_i / (K_I + |K_II| + |K_III|),  p = (sqrt(pi) - 5 nu) / 4,
        X = (1 + k_I - (1 - k_III)^p) / k_II,
        beta = 2 atan[(X - sign(K_II) sqrt(X^2 + 8)) / 4]   (0 when K_II = 0).

    With K_III = 0, X = K_I / K_II and beta is the 2D maximum hoop stress
    kink (kink_angle). Two deliberate differences from the source: the
    mode-III term uses |K_III| (code_aster's (1 - k_III)^p with a signed
    k_III gives different kinks to K_III and -K_III, which mirror images
    cannot have), and a negative K_I counts as 0 as in 2D.

    gamma: the twist of the kinked facet about the propagation direction
    that makes it normal to the largest principal stress of the plane
    normal to the kinked direction (Schoellmann et al. 2002's form),
    gamma = 1/2 atan[2 tau_tz / (sigma_tt - sigma_zz)] with the asymptotic
    plane-strain fields at theta = beta (times sqrt(2 pi r)):

        4 (sigma_tt - sigma_zz) = K_I ((3 - 8 nu) cos(b/2) + cos(3b/2))
                                  + K_II ((8 nu - 3) sin(b/2) - 3 sin(3b/2)),
        tau_tz = K_III cos(b/2).

    code_aster's membre_1..3 and division compute 1/2 atan(tau_tz / [4
    (sigma_tt - sigma_zz)]) with K_II's term written (8 nu - 1) sin(b/2) +
    (3 nu - 4) sin(3b/2): at beta = 0 its argument is 8 times smaller than
    the principal direction's (K_I = K_III, nu = 0.3: 16.0 degrees against
    39.3); cracklip uses the form derived here. The twist is reported, not
    applied to the surface (a continuous crack surface cannot twist along
    its front; twisted growth breaks into facets, a 'factory roof').
    Conventions as kink_angle: beta in the frame (e1, e2), positive toward
    e2 (K_II > 0 kinks toward -e2)."""
    kI = max(K_I, 0.0)
    if K_II == 0.0:
        beta = 0.0
    else:
        den = kI + abs(K_II) + abs(K_III)
        k1, k2, k3 = kI / den, K_II / den, abs(K_III) / den
        p = (math.sqrt(math.pi) - 5.0 * nu) / 4.0
        X = (1.0 + k1 - (1.0 - k3) ** p) / k2
        beta = 2.0 * math.atan((X - math.copysign(math.sqrt(X * X + 8.0), K_II)) / 4.0)
    c1, c3 = math.cos(beta / 2), math.cos(3 * beta / 2)
    s1, s3 = math.sin(beta / 2), math.sin(3 * beta / 2)
    diff = 0.25 * (kI * ((3 - 8 * nu) * c1 + c3) + K_II * ((8 * nu - 3) * s1 - 3 * s3))
    gamma = 0.5 * math.atan2(2.0 * K_III * c1, diff) if K_III != 0.0 else 0.0
    return beta, gamma


def equivalent_k_3d(K_I, K_II, K_III, theta: float, nu: float, clamp: bool = True):
    """K_eq of a 3D front point along the kink theta: the hoop-stress K of
    equivalent_k (K_I, K_II) and mode III's share of the energy release
    rate, K_eq = sqrt(K_tt^2 + K_III^2 / (1 - nu)) (G E' = K_I^2 + K_II^2
    + K_III^2 / (1 - nu)), added only where K_tt > 0 (an open kink). With
    K_III = 0 it is equivalent_k exactly. Arrays of states work too."""
    c = np.cos(theta / 2)
    kI = np.maximum(K_I, 0.0) if clamp else np.asarray(K_I, dtype=float)
    ktt = c * (kI * c * c - 1.5 * np.asarray(K_II, dtype=float) * np.sin(theta))
    k3 = np.asarray(K_III, dtype=float)
    out = np.where(ktt > 0.0, np.sqrt(ktt * ktt + k3 * k3 / (1.0 - nu)), ktt)
    return float(out) if np.ndim(out) == 0 else out


#: The share of the criterion's kink a 3D front point takes per step
#: (front_kinks). The explicit kink annuls K_II at the new front only to
#: first order in a field K_II measures exactly; on the surface crack a/c0 =
#: 1 (increments below the element size at a free-surface end) the K_II it
#: left behind was 2-3 times the one it removed, of the other sign: a
#: zig-zag growing by that factor each step. A half kink (as 2D's corrector
#: tries first, analysis.growth._correct) turns a response gain G (K_II
#: removed over K_II the kink aims to remove) into a factor 1 - G/2 per
#: step: stable up to G = 4, and a mixed-mode front still turns (K_II falls
#: by half a step where G = 1).
FRONT_KINK_SHARE = 0.5


def front_kinks(theta, free, X, share: float = FRONT_KINK_SHARE) -> np.ndarray:
    """The kinks (radians) a crack's front points take in one step, from the
    criterion's kinks theta (n,) at points X (n, 3), free (n,) marking the
    points where the front meets the part's boundary: a free-surface point
    takes the kink of its nearest point off the free surface (its K_II is
    not measured there but extrapolated from the interior,
    fracture.sif_3d, and the kink it gave led a zig-zag: a/c0 = 1, K_II /
    K_I -0.10, +0.20, -0.21 at steps 9-11), then every point `share` of it
    (FRONT_KINK_SHARE). A front without interior points keeps its own
    kinks (times share)."""
    th = np.asarray(theta, dtype=float).reshape(-1).copy()
    fr = np.asarray(free, dtype=bool).reshape(-1)
    P = np.asarray(X, dtype=float).reshape(len(th), -1)
    inner = np.flatnonzero(~fr)
    if inner.size:
        for j in np.flatnonzero(fr):
            th[j] = th[inner[np.argmin(np.linalg.norm(P[inner] - P[j], axis=1))]]
    return share * th
