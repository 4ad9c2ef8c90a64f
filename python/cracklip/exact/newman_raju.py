"""Newman and Raju's stress intensity factors of surface and corner cracks
under remote tension (NASA TM-85793, 1984): a handbook fit to finite
element results, stated accurate to +-5 %, not an exact solution.

Semi-elliptical surface crack of depth a and half-length c in a plate of
thickness t and width 2b (c/b < 0.5, a/t < 0.8, 0 < a/c <= 2), and a
quarter-elliptical corner crack (a/c <= 1 here); phi is the parametric angle
measured from the free surface (pi/2: the deepest point; for the corner
crack phi = 0 is the end on the surface of width b, pi/2 the end on the
surface of thickness t):

    K = S sqrt(pi a / Q) F(a/c, a/t, c/b, phi),
    Q = 1 + 1.464 (a/c)^1.65 (a/c <= 1; (c/a)^1.65 for a/c > 1),
    f_phi = ((a/c)^2 cos^2 phi + sin^2 phi)^(1/4)    (a/c <= 1;
            ((c/a)^2 sin^2 phi + cos^2 phi)^(1/4) for a/c > 1),
    F = (M1 + M2 (a/t)^2 + M3 (a/t)^4) g f_phi f_w,

with the coefficients in the functions below (as written in the report and
in the open Easigrow code's beta.rs, which the project's notes checked).
"""
from __future__ import annotations

import math

import numpy as np


def _Q(ac: float) -> float:
    return 1.0 + 1.464 * (ac if ac <= 1.0 else 1.0 / ac) ** 1.65


def _check(a: float, c: float, t: float, b: float, corner: bool) -> None:
    if not (a > 0.0 and c > 0.0 and t > 0.0 and b > 0.0):
        raise ValueError(f"Newman-Raju: a, c, t, b must be positive, got {a}, {c}, {t}, {b}")
    ac = a / c
    if corner and ac > 1.0:
        raise ValueError(f"Newman-Raju corner crack implemented for a/c <= 1, got {ac:g}")
    if not (0.0 < ac <= 2.0 and a / t < 0.8 and c / b < 0.5):
        raise ValueError(f"Newman-Raju: outside the fit's range (0 < a/c <= 2, a/t < 0.8, c/b < 0.5): a/c = {ac:g}, "
                         f"a/t = {a / t:g}, c/b = {c / b:g}")


def surface_crack_F(a: float, c: float, t: float, b: float, phi: np.ndarray) -> np.ndarray:
    """F of a semi-elliptical surface crack under tension (see the module)."""
    _check(a, c, t, b, corner=False)
    phi = np.asarray(phi, dtype=float)
    ac, at = a / c, a / t
    if ac <= 1.0:
        M1 = 1.13 - 0.09 * ac
        M2 = -0.54 + 0.89 / (0.2 + ac)
        M3 = 0.5 - 1.0 / (0.65 + ac) + 14.0 * (1.0 - ac) ** 24
        g = 1.0 + (0.1 + 0.35 * at ** 2) * (1.0 - np.sin(phi)) ** 2
        f_phi = (ac ** 2 * np.cos(phi) ** 2 + np.sin(phi) ** 2) ** 0.25
    else:
        ca = 1.0 / ac
        M1 = math.sqrt(ca) * (1.0 + 0.04 * ca)
        M2 = 0.2 * ca ** 4
        M3 = -0.11 * ca ** 4
        g = 1.0 + (0.1 + 0.35 * ca * at ** 2) * (1.0 - np.sin(phi)) ** 2
        f_phi = (ca ** 2 * np.sin(phi) ** 2 + np.cos(phi) ** 2) ** 0.25
    f_w = 1.0 / math.sqrt(math.cos(math.pi * c / (2.0 * b) * math.sqrt(at)))
    return (M1 + M2 * at ** 2 + M3 * at ** 4) * g * f_phi * f_w


def corner_crack_F(a: float, c: float, t: float, b: float, phi: np.ndarray) -> np.ndarray:
    """F of a quarter-elliptical corner crack under tension, a/c <= 1."""
    _check(a, c, t, b, corner=True)
    phi = np.asarray(phi, dtype=float)
    ac, at = a / c, a / t
    M1 = 1.08 - 0.03 * ac
    M2 = -0.44 + 1.06 / (0.3 + ac)
    M3 = -0.5 + 0.25 * ac + 14.8 * (1.0 - ac) ** 15
    g1 = 1.0 + (0.08 + 0.4 * at ** 2) * (1.0 - np.sin(phi)) ** 3
    g2 = 1.0 + (0.08 + 0.15 * at ** 2) * (1.0 - np.cos(phi)) ** 3
    f_phi = (ac ** 2 * np.cos(phi) ** 2 + np.sin(phi) ** 2) ** 0.25
    lam = c / b * math.sqrt(at)
    f_w = 1.0 - 0.2 * lam + 9.4 * lam ** 2 - 19.4 * lam ** 3 + 27.1 * lam ** 4
    return (M1 + M2 * at ** 2 + M3 * at ** 4) * g1 * g2 * f_phi * f_w


def surface_crack_k(S: float, a: float, c: float, t: float, b: float, phi: np.ndarray,
                    corner: bool = False) -> np.ndarray:
    """K (n,) along a surface (or corner) crack under remote tension S."""
    F = corner_crack_F(a, c, t, b, phi) if corner else surface_crack_F(a, c, t, b, phi)
    return S * np.sqrt(math.pi * a / _Q(a / c)) * F


__all__ = ["surface_crack_F", "corner_crack_F", "surface_crack_k"]
