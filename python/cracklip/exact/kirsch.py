"""Kirsch's exact field around a circular hole under a remote uniaxial stress.

Remote stress S along x (S < 0 compression), hole radius R, polar (r, t):
  s_rr = S/2 (1 - R^2/r^2) + S/2 (1 - 4 R^2/r^2 + 3 R^4/r^4) cos 2t
  s_tt = S/2 (1 + R^2/r^2) - S/2 (1 + 3 R^4/r^4) cos 2t
  s_rt = -S/2 (1 + 2 R^2/r^2 - 3 R^4/r^4) sin 2t
On the line x = 0 the shear vanishes and s_xx = s_tt = S (1 + R^2/(2y^2) +
3 R^4/(2y^4)): under compression a crack along that line stays closed with the
contact pressure -s_xx (paper section 5.2).
"""
from __future__ import annotations

import numpy as np

from ..scene.material import Material


def kirsch_stress(x: np.ndarray, S: float, R: float = 1.0) -> np.ndarray:
    """Cartesian stress (n, 2, 2) at points (n, 2)."""
    x = np.asarray(x, dtype=float).reshape(-1, 2)
    r = np.linalg.norm(x, axis=1)
    t = np.arctan2(x[:, 1], x[:, 0])
    a2, a4 = (R / r) ** 2, (R / r) ** 4
    c2, s2 = np.cos(2 * t), np.sin(2 * t)
    srr = S / 2 * (1 - a2) + S / 2 * (1 - 4 * a2 + 3 * a4) * c2
    stt = S / 2 * (1 + a2) - S / 2 * (1 + 3 * a4) * c2
    srt = -S / 2 * (1 + 2 * a2 - 3 * a4) * s2
    c, s = np.cos(t), np.sin(t)
    out = np.empty((len(x), 2, 2))
    out[:, 0, 0] = srr * c * c + stt * s * s - 2 * srt * s * c
    out[:, 1, 1] = srr * s * s + stt * c * c + 2 * srt * s * c
    out[:, 0, 1] = out[:, 1, 0] = (srr - stt) * s * c + srt * (c * c - s * s)
    return out


def kirsch_strain(x: np.ndarray, S: float, R: float, material: Material) -> np.ndarray:
    """In-plane strain (n, 2, 2) of the Kirsch stress (plane strain or stress)."""
    sig = kirsch_stress(x, S, R)
    E, nu = material.E_strain, material.nu_strain
    tr = sig[:, 0, 0] + sig[:, 1, 1]
    return (1 + nu) / E * (sig - nu * tr[:, None, None] * np.eye(2)[None])


def crack_pressure(y: np.ndarray, sigma_inf: float, R: float = 1.0) -> np.ndarray:
    """Exact contact pressure on the crack x = 0 under remote compression sigma_inf > 0."""
    y = np.asarray(y, dtype=float)
    return sigma_inf * (1 + R ** 2 / (2 * y ** 2) + 3 * R ** 4 / (2 * y ** 4))
