"""Handbook geometry factors of cracks under remote tension S:
beta = K / (S sqrt(pi a)), the K a life needs without a mesh.

Through cracks (a the crack length at the tip: half the length of a centre
crack, the length from the edge or the hole's edge otherwise):

    centre crack, plate W wide      Feddersen (1966): sqrt(sec(pi a / W));
                                    Tada (1973): (1 - 0.025 x^2 + 0.06 x^4)
                                    sqrt(sec(pi x / 2)), x = 2a / W, 0.1 %
                                    for any x (Tada, Paris, Irwin, p. 2.2)
    edge crack, strip W wide        Tada (1973): sqrt(2 / (pi x) tan(pi x / 2))
                                    (0.752 + 2.02 x + 0.37 (1 - sin(pi x /
                                    2))^3) / cos(pi x / 2), x = a / W, 0.5 %
                                    for any x, ends free to rotate
    crack(s) at a hole of radius R  Bowie (1956) in an infinite plate, as
                                    fitted by Paul and Lombardo (DSTO CRKGRW
                                    manual, 1988): one crack 0.6762 + 0.8734 /
                                    (0.3246 + a / R), two symmetric cracks
                                    0.9439 + 0.6865 / (0.2772 + a / R)
                                    (both read in easigrow's beta.rs,
                                    `ssht-bowie56` and `dsht-bowie56`)

Surface and corner cracks: Newman and Raju (NASA TM-85793, 1984), a handbook
fit to finite-element results stated accurate to +-5 %: depth a, half
length c (corner: length c), plate thickness t and width 2b (corner: b),

    K = S sqrt(pi a / Q) F(a/c, a/t, c/b, phi),
    Q = 1 + 1.464 (a/c)^1.65 (a/c <= 1; (c/a)^1.65 for a/c > 1),
    f_phi = ((a/c)^2 cos^2 phi + sin^2 phi)^(1/4)    (a/c <= 1;
            ((c/a)^2 sin^2 phi + cos^2 phi)^(1/4) for a/c > 1),
    F = (M1 + M2 (a/t)^2 + M3 (a/t)^4) g f_phi f_w,

phi the parametric angle from the free surface (pi/2: the deepest point,
which grows a; 0: the surface point, which grows c; for the corner crack
phi = 0 is the end on the surface of width b, pi/2 the end on the surface
of thickness t), with the coefficients below (as in the report and in
easigrow's beta.rs, which the project's notes checked). Range: 0 < a/c <= 2
(corner: <= 1), a/t < 0.8, c/b < 0.5.

A surface crack under bending too (the same report): with S_b the bending
stress at the cracked face (the stress across the plate varying linearly
from S + S_b there to S - S_b on the back face),

    K = (S + H S_b) sqrt(pi a / Q) F,  H = H1 + (H2 - H1) sin^p phi,
    a/c <= 1: p = 0.2 + a/c + 0.6 a/t, H1 = 1 - 0.34 a/t - 0.11 (a/c)(a/t),
              H2 = 1 + G1 a/t + G2 (a/t)^2, G1 = -1.22 - 0.12 a/c,
              G2 = 0.55 - 1.05 (a/c)^0.75 + 0.47 (a/c)^1.5;
    a/c > 1:  p = 0.2 + c/a + 0.6 a/t, H1 = 1 - (0.04 + 0.41 c/a) a/t
              + (0.55 - 1.93 (c/a)^0.75 + 1.38 (c/a)^1.5) (a/t)^2,
              G1 = -2.11 + 0.77 c/a, G2 = 0.55 - 0.72 (c/a)^0.75 + 0.14 (c/a)^1.5

(checked 2026-11-29 against four independent implementations of the
report's equations; the corner crack's bending is not implemented).

Everything is vectorised over numpy arrays.
"""
from __future__ import annotations

import math

import numpy as np


#: The handbook solutions a life can use, with their source (docs/life.md).
SOURCES = {
    "centre_crack": "centre crack in a plate of width W: Feddersen's sqrt(sec(pi a / W)) (1966), or Tada's "
                    "(1 - 0.025 x^2 + 0.06 x^4) sqrt(sec(pi x / 2)), x = 2a / W (Tada, Paris, Irwin, 1973; 0.1 %)",
    "edge_crack": "single edge crack in a strip of width W, ends free to rotate: Tada (1973; Tada, Paris, Irwin "
                  "p. 2.11; 0.5 % for any a / W)",
    "hole_crack": "one or two symmetric through cracks at a circular hole of radius R in an infinite plate: "
                  "Bowie (1956) as fitted by Paul and Lombardo (DSTO CRKGRW manual, 1988)",
    "surface_crack": "semi-elliptical surface crack in a plate (thickness t, width 2b) under tension (and "
                     "bending): Newman and Raju, NASA TM-85793 (1984), +-5 %",
    "corner_crack": "quarter-elliptical corner crack in a plate (thickness t, width b) under tension: Newman and "
                    "Raju, NASA TM-85793 (1984), +-5 %, a/c <= 1",
}


def centre_crack(a, W: float, form: str = "feddersen") -> np.ndarray:
    """beta of a centre crack of half length a in a plate of width W."""
    x = 2.0 * np.asarray(a, dtype=float) / W
    sec = np.sqrt(1.0 / np.cos(np.pi * x / 2.0))
    if form == "feddersen":
        return sec
    if form == "tada":
        return (1.0 - 0.025 * x ** 2 + 0.06 * x ** 4) * sec
    raise ValueError(f"centre crack: form must be 'feddersen' or 'tada', got {form!r}")


def edge_crack(a, W: float) -> np.ndarray:
    """beta of a single edge crack of length a in a strip of width W (Tada)."""
    x = np.asarray(a, dtype=float) / W
    t = np.pi * x / 2.0
    return np.sqrt(2.0 / (np.pi * x) * np.tan(t)) * (0.752 + 2.02 * x + 0.37 * (1.0 - np.sin(t)) ** 3) / np.cos(t)


def hole_crack(a, R: float, cracks: int = 1) -> np.ndarray:
    """beta of one (cracks = 1) or two symmetric (2) through cracks of length
    a at a hole of radius R in an infinite plate (Bowie, CRKGRW fit)."""
    s = np.asarray(a, dtype=float) / R
    if cracks == 1:
        return 0.6762 + 0.8734 / (0.3246 + s)
    if cracks == 2:
        return 0.9439 + 0.6865 / (0.2772 + s)
    raise ValueError(f"hole crack: 1 or 2 cracks, got {cracks!r}")


# -- Newman-Raju ----------------------------------------------------------------------------------------------

def _Q(ac):
    ac = np.asarray(ac, dtype=float)
    return 1.0 + 1.464 * np.where(ac <= 1.0, ac, 1.0 / ac) ** 1.65


def newman_raju_range(a, c, t: float, b: float, corner: bool = False) -> np.ndarray:
    """Whether (a, c) lies in the fit's range (module doc)."""
    a, c = np.asarray(a, dtype=float), np.asarray(c, dtype=float)
    ac = a / c
    return (a > 0) & (c > 0) & (ac > 0) & (ac <= (1.0 if corner else 2.0)) & (a / t < 0.8) & (c / b < 0.5)


def _check(a: float, c: float, t: float, b: float, corner: bool) -> None:
    if not (a > 0.0 and c > 0.0 and t > 0.0 and b > 0.0):
        raise ValueError(f"Newman-Raju: a, c, t, b must be positive, got {a}, {c}, {t}, {b}")
    ac = a / c
    if corner and ac > 1.0:
        raise ValueError(f"Newman-Raju corner crack implemented for a/c <= 1, got {ac:g}")
    if not (0.0 < ac <= 2.0 and a / t < 0.8 and c / b < 0.5):
        raise ValueError(f"Newman-Raju: outside the fit's range (0 < a/c <= 2, a/t < 0.8, c/b < 0.5): a/c = {ac:g}, "
                         f"a/t = {a / t:g}, c/b = {c / b:g}")


def surface_F(a, c, t: float, b: float, phi) -> np.ndarray:
    """F of a semi-elliptical surface crack, broadcast over a, c and phi
    (no range check: newman_raju_range says where it holds)."""
    a, c, phi = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (a, c, phi)))
    ac, at = a / c, a / t
    ca = 1.0 / ac
    low = ac <= 1.0
    M1 = np.where(low, 1.13 - 0.09 * ac, np.sqrt(ca) * (1.0 + 0.04 * ca))
    M2 = np.where(low, -0.54 + 0.89 / (0.2 + ac), 0.2 * ca ** 4)
    M3 = np.where(low, 0.5 - 1.0 / (0.65 + ac) + 14.0 * np.abs(1.0 - ac) ** 24 * low, -0.11 * ca ** 4)
    g = 1.0 + (0.1 + 0.35 * np.where(low, 1.0, ca) * at ** 2) * (1.0 - np.sin(phi)) ** 2
    f_phi = np.where(low, (ac ** 2 * np.cos(phi) ** 2 + np.sin(phi) ** 2) ** 0.25,
                     (ca ** 2 * np.sin(phi) ** 2 + np.cos(phi) ** 2) ** 0.25)
    f_w = 1.0 / np.sqrt(np.cos(np.pi * c / (2.0 * b) * np.sqrt(at)))
    return (M1 + M2 * at ** 2 + M3 * at ** 4) * g * f_phi * f_w


def corner_F(a, c, t: float, b: float, phi) -> np.ndarray:
    """F of a quarter-elliptical corner crack (a/c <= 1), broadcast over a, c
    and phi (no range check)."""
    a, c, phi = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (a, c, phi)))
    ac, at = a / c, a / t
    M1 = 1.08 - 0.03 * ac
    M2 = -0.44 + 1.06 / (0.3 + ac)
    M3 = -0.5 + 0.25 * ac + 14.8 * (1.0 - ac) ** 15
    g1 = 1.0 + (0.08 + 0.4 * at ** 2) * (1.0 - np.sin(phi)) ** 3
    g2 = 1.0 + (0.08 + 0.15 * at ** 2) * (1.0 - np.cos(phi)) ** 3
    f_phi = (ac ** 2 * np.cos(phi) ** 2 + np.sin(phi) ** 2) ** 0.25
    lam = c / b * np.sqrt(at)
    f_w = 1.0 - 0.2 * lam + 9.4 * lam ** 2 - 19.4 * lam ** 3 + 27.1 * lam ** 4
    return (M1 + M2 * at ** 2 + M3 * at ** 4) * g1 * g2 * f_phi * f_w


def surface_H(a, c, t: float, phi) -> np.ndarray:
    """Newman and Raju's bending multiplier H of a semi-elliptical surface
    crack (module doc), broadcast over a, c and phi (no range check)."""
    a, c, phi = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (a, c, phi)))
    ac, at = a / c, a / t
    ca = 1.0 / ac
    low = ac <= 1.0
    p = 0.2 + np.where(low, ac, ca) + 0.6 * at
    H1 = np.where(low, 1.0 - 0.34 * at - 0.11 * ac * at,
                  1.0 - (0.04 + 0.41 * ca) * at + (0.55 - 1.93 * ca ** 0.75 + 1.38 * ca ** 1.5) * at ** 2)
    G1 = np.where(low, -1.22 - 0.12 * ac, -2.11 + 0.77 * ca)
    G2 = np.where(low, 0.55 - 1.05 * ac ** 0.75 + 0.47 * ac ** 1.5, 0.55 - 0.72 * ca ** 0.75 + 0.14 * ca ** 1.5)
    H2 = 1.0 + G1 * at + G2 * at ** 2
    return H1 + (H2 - H1) * np.abs(np.sin(phi)) ** p


def surface_crack_F(a: float, c: float, t: float, b: float, phi: np.ndarray) -> np.ndarray:
    """F of a semi-elliptical surface crack under tension (ValueError outside the fit's range)."""
    _check(a, c, t, b, corner=False)
    return surface_F(a, c, t, b, np.asarray(phi, dtype=float))


def corner_crack_F(a: float, c: float, t: float, b: float, phi: np.ndarray) -> np.ndarray:
    """F of a quarter-elliptical corner crack under tension, a/c <= 1."""
    _check(a, c, t, b, corner=True)
    return corner_F(a, c, t, b, np.asarray(phi, dtype=float))


def surface_crack_k(S: float, a: float, c: float, t: float, b: float, phi: np.ndarray,
                    corner: bool = False, bending: float = 0.0) -> np.ndarray:
    """K (n,) along a surface (or corner) crack under remote tension S and,
    for a surface crack, the bending stress `bending` at its face (module
    doc)."""
    if corner and bending:
        raise ValueError("Newman-Raju: the corner crack's bending is not implemented")
    F = corner_crack_F(a, c, t, b, phi) if corner else surface_crack_F(a, c, t, b, phi)
    H = surface_H(a, c, t, phi) if bending else 0.0
    return (S + H * bending) * np.sqrt(math.pi * a / _Q(a / c)) * F


def surface_crack_beta(a, c, t: float, b: float, corner: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """beta = K / (S sqrt(pi a)) at the deepest point (phi = pi/2, grows a) and
    at the surface point (phi = 0, grows c), broadcast over a and c (no range
    check)."""
    F = corner_F if corner else surface_F
    q = np.sqrt(_Q(np.asarray(a, dtype=float) / np.asarray(c, dtype=float)))
    return F(a, c, t, b, math.pi / 2) / q, F(a, c, t, b, 0.0) / q


__all__ = ["SOURCES", "centre_crack", "edge_crack", "hole_crack", "newman_raju_range", "surface_F", "surface_H",
           "corner_F", "surface_crack_F", "corner_crack_F", "surface_crack_k", "surface_crack_beta"]
