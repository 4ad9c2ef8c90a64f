"""Exact Williams (Westergaard) crack-tip fields, for tests, demos and loads.

u = (K_I U_I + K_II U_II) / (2 mu sqrt(2 pi)) with the vector functions of
the C++ kernels (cpp/enrichment/tip_functions_2d.h), whose traction-free lips and
divergence-free stress are unit-tested.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from .. import _cracklip
from ..scene.material import Material, strain, stress


@dataclasses.dataclass
class WilliamsField:
    """Exact plane-strain crack-tip field with SIFs K_I, K_II.

    Attributes:
        material: elastic constants.
        K_I, K_II: stress intensity factors.
        tip: tip position (2,); e1: unit crack direction at the tip (2,).
        orientation: the crack side (sign of phi) on which theta -> +pi.
    """
    material: Material
    K_I: float = 1.0
    K_II: float = 0.0
    tip: tuple[float, float] = (0.0, 0.0)
    e1: tuple[float, float] = (1.0, 0.0)
    orientation: int = 1

    def _eval(self, x: np.ndarray, side=None):
        x = np.asarray(x, dtype=float).reshape(-1, 2)
        s = np.zeros(len(x), dtype=np.int8) if side is None else np.asarray(side, dtype=np.int8)
        U, dU = _cracklip.williams_displacement(np.asarray(self.tip, float), np.asarray(self.e1, float),
                                                self.material.kappa, x, s, self.orientation)
        c = 1.0 / (2.0 * self.material.mu * np.sqrt(2.0 * np.pi))
        return c * (self.K_I * U[:, 0] + self.K_II * U[:, 1]), c * (self.K_I * dU[:, 0] + self.K_II * dU[:, 1])

    def displacement(self, x: np.ndarray, side=None) -> np.ndarray:
        """(n, 2); side (n,) picks the lip behind the tip (+1 / -1), 0 = atan2."""
        return self._eval(x, side)[0]

    def gradient(self, x: np.ndarray, side=None) -> np.ndarray:
        """(n, 2, 2) displacement gradient."""
        return self._eval(x, side)[1]

    def stress(self, x: np.ndarray, side=None) -> np.ndarray:
        """(n, 2, 2) stress."""
        return stress(strain(self.gradient(x, side)), self.material)

    def traction(self, normal: np.ndarray):
        """A traction callable t(x) = sigma(x) n for a fixed outward normal."""
        n = np.asarray(normal, dtype=float)
        return lambda x: np.einsum("nij,j->ni", self.stress(x), n)
