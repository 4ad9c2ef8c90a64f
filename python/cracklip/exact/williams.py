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


@dataclasses.dataclass
class WilliamsField3D:
    """Exact field of a straight crack front in a solid: the plane-strain
    Williams field (K_I, K_II) in the plane normal to the front plus the
    anti-plane mode III field u3 = 4 K_III sqrt(r) sin(theta / 2) / (2 mu
    sqrt(2 pi)), exact in 3D for any position along the front.

    Attributes:
        material: elastic constants.
        K_I, K_II, K_III: stress intensity factors (K_II > 0: the + lip
            moves along +e1 relative to the - lip; K_III > 0: along +e3).
        point: a point of the front (3,).
        e1: propagation direction (3,), e2: the crack's normal toward its
            + lip (3,), orthogonal to e1; e3 = e1 x e2 runs along the front.
            The crack is the half plane (x - point).e2 = 0, (x - point).e1 < 0.
    """
    material: Material
    K_I: float = 1.0
    K_II: float = 0.0
    K_III: float = 0.0
    point: tuple[float, float, float] = (0.0, 0.0, 0.0)
    e1: tuple[float, float, float] = (1.0, 0.0, 0.0)
    e2: tuple[float, float, float] = (0.0, 1.0, 0.0)

    @property
    def frame(self) -> np.ndarray:
        """(3, 3) columns e1, e2, e3."""
        e1, e2 = np.asarray(self.e1, float), np.asarray(self.e2, float)
        return np.column_stack([e1, e2, np.cross(e1, e2)])

    def _local(self, x: np.ndarray, side):
        Q = self.frame
        y = (np.asarray(x, dtype=float).reshape(-1, 3) - np.asarray(self.point, float)) @ Q
        s = np.zeros(len(y), dtype=np.int8) if side is None else np.asarray(side, dtype=np.int8).reshape(-1)
        if s.size == 1 and len(y) != 1:
            s = np.full(len(y), s[0], dtype=np.int8)
        return Q, y, s

    def _anti_plane(self, y: np.ndarray, s: np.ndarray):
        r = np.hypot(y[:, 0], y[:, 1])
        th = np.arctan2(y[:, 1], y[:, 0])
        behind = (y[:, 0] < 0.0) & (s != 0)
        th = np.where(behind, np.where(s > 0, np.abs(th), -np.abs(th)), th)
        c = self.K_III / (2.0 * self.material.mu * np.sqrt(2.0 * np.pi))
        u3 = 4.0 * c * np.sqrt(r) * np.sin(th / 2.0)
        rs = np.sqrt(np.maximum(r, 1e-300))
        return u3, np.stack([-2.0 * c * np.sin(th / 2.0) / rs, 2.0 * c * np.cos(th / 2.0) / rs], axis=1)

    def displacement(self, x: np.ndarray, side=None) -> np.ndarray:
        """(n, 3); side (n,) picks the lip behind the front (+1 / -1), 0 = the point's own side."""
        Q, y, s = self._local(x, side)
        plane = WilliamsField(self.material, self.K_I, self.K_II)
        u = np.zeros((len(y), 3))
        u[:, :2] = plane.displacement(y[:, :2], s)
        u[:, 2] = self._anti_plane(y, s)[0]
        return u @ Q.T

    def gradient(self, x: np.ndarray, side=None) -> np.ndarray:
        """(n, 3, 3) displacement gradient, [p, i, j] = d u_i / d x_j."""
        Q, y, s = self._local(x, side)
        plane = WilliamsField(self.material, self.K_I, self.K_II)
        G = np.zeros((len(y), 3, 3))
        G[:, :2, :2] = plane.gradient(y[:, :2], s)
        G[:, 2, :2] = self._anti_plane(y, s)[1]
        return np.einsum("ij,njk,lk->nil", Q, G, Q)
