"""Exact fields of a straight (Griffith) crack in an infinite plate, for tests, demos and loads.

A crack of half length a, centre c, at angle beta from the x axis, under a
remote uniform stress (given in the crack frame: x along the crack, y normal
to it) and uniform tractions on its lips (a pressure p pushing the lips
apart, a shear q). With Westergaard's functions (crack frame, z = x + i y,
branch sqrt(z - a) sqrt(z + a), cut on the crack)

    Z_I = s z / sqrt(z^2 - a^2):  remote sigma_xx = sigma_yy = s, traction-free lips;
    Z_II = t z / sqrt(z^2 - a^2): remote sigma_xy = t, traction-free lips,

every such field is a superposition of them and uniform fields:

    remote (sxx, syy, sxy), lip pressure p, lip shear q  =
        W_I(syy + p) + W_II(sxy + q) + uniform (sxx - syy - p, -p, -q).

Displacements (kappa = 3 - 4 nu plane strain, (3 - nu)/(1 + nu) plane
stress): 2 mu u_x = (kappa - 1)/2 Re Zh - y Im Z, 2 mu u_y = (kappa + 1)/2 Im Zh
- y Re Z for mode I; 2 mu u_x = (kappa + 1)/2 Im Zh + y Re Z, 2 mu u_y =
-(kappa - 1)/2 Re Zh - y Im Z for mode II (Zh' = Z). Stress intensity factors
at both tips: K_I = (syy + p) sqrt(pi a), K_II = (sxy + q) sqrt(pi a) (the
shear of the tip frame, e1 out of the crack, e2 = e1 turned by +90 degrees,
is the same at both tips). Opening [[u_y]] = (kappa + 1)/(2 mu) (syy + p)
sqrt(a^2 - x^2) (Sneddon), slip [[u_x]] = (kappa + 1)/(2 mu) (sxy + q)
sqrt(a^2 - x^2), [[.]] = upper (y > 0) lip minus lower.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..scene.material import Material


@dataclasses.dataclass
class GriffithField:
    """Exact field of a Griffith crack (see the module doc).

    Attributes:
        material: elastic constants (plane strain or stress).
        a: half length; center: (2,); angle: degrees from the x axis.
        remote: remote stress (sxx, syy, sxy) in the crack frame.
        pressure, shear: uniform tractions on the lips, in the crack frame:
            the upper lip (y > 0) carries the traction (q, p) and the lower
            one (-q, -p) (sigma_xy = -q, sigma_yy = -p on the crack); a
            pressure p > 0 pushes the lips apart.
    """
    material: Material
    a: float = 1.0
    center: tuple[float, float] = (0.0, 0.0)
    angle: float = 0.0
    remote: tuple[float, float, float] = (0.0, 0.0, 0.0)
    pressure: float = 0.0
    shear: float = 0.0

    @property
    def rotation(self) -> np.ndarray:
        b = math.radians(self.angle)
        return np.array([[math.cos(b), -math.sin(b)], [math.sin(b), math.cos(b)]])

    @property
    def K_I(self) -> float:
        return (self.remote[1] + self.pressure) * math.sqrt(math.pi * self.a)

    @property
    def K_II(self) -> float:
        return (self.remote[2] + self.shear) * math.sqrt(math.pi * self.a)

    @property
    def tips(self) -> np.ndarray:
        """(2, 2): the tips at -a and +a along the crack."""
        R = self.rotation
        return np.asarray(self.center) + np.array([[-self.a, 0.0], [self.a, 0.0]]) @ R.T

    def _local(self, X: np.ndarray, side) -> tuple[np.ndarray, np.ndarray]:
        """z = x + i y in the crack frame; points on the crack line (|y|
        below 1e-14 a) take the lip of `side` (+1 upper, -1 lower, 0: upper)."""
        X = np.asarray(X, dtype=float).reshape(-1, 2)
        loc = (X - np.asarray(self.center)) @ self.rotation
        s = np.zeros(len(X)) if side is None else np.broadcast_to(np.asarray(side, dtype=float), (len(X),))
        z = np.empty(len(X), dtype=complex)
        z.real = loc[:, 0]
        # (built part by part: x + 1j * y would drop the sign of a zero y)
        z.imag = np.where(np.abs(loc[:, 1]) <= 1e-14 * self.a, np.where(s < 0, -0.0, 0.0), loc[:, 1])
        return z, loc

    def _potentials(self, z: np.ndarray):
        """sqrt(z^2 - a^2) on the branch cut along the crack, Z / s, Z' / s."""
        a = self.a
        root = np.sqrt(z - a) * np.sqrt(z + a)
        with np.errstate(divide="ignore", invalid="ignore"):
            Z = z / root
            dZ = -a * a / root ** 3
        return root, Z, dZ

    def _uniform(self) -> np.ndarray:
        """The uniform stress (crack frame, 2x2) added to the two Westergaard fields."""
        sxx, syy, sxy = self.remote
        p, q = self.pressure, self.shear
        return np.array([[sxx - syy - p, -q], [-q, -p]])

    def _local_gradient(self, X, side) -> tuple[np.ndarray, np.ndarray]:
        """Displacement (n, 2) and gradient (n, 2, 2) in the crack frame."""
        mat = self.material
        z, loc = self._local(X, side)
        y = z.imag
        root, Z, dZ = self._potentials(z)
        k, mu2 = mat.kappa, 2.0 * mat.mu
        sI = self.remote[1] + self.pressure
        sII = self.remote[2] + self.shear
        u = np.zeros((len(y), 2))
        g = np.zeros((len(y), 2, 2))
        # mode I
        u[:, 0] += sI * ((k - 1) / 2 * root.real - y * Z.imag) / mu2
        u[:, 1] += sI * ((k + 1) / 2 * root.imag - y * Z.real) / mu2
        g[:, 0, 0] += sI * ((k - 1) / 2 * Z.real - y * dZ.imag) / mu2
        g[:, 0, 1] += sI * (-(k + 1) / 2 * Z.imag - y * dZ.real) / mu2
        g[:, 1, 0] += sI * ((k + 1) / 2 * Z.imag - y * dZ.real) / mu2
        g[:, 1, 1] += sI * ((k - 1) / 2 * Z.real + y * dZ.imag) / mu2
        # mode II
        u[:, 0] += sII * ((k + 1) / 2 * root.imag + y * Z.real) / mu2
        u[:, 1] += sII * (-(k - 1) / 2 * root.real - y * Z.imag) / mu2
        g[:, 0, 0] += sII * ((k + 1) / 2 * Z.imag + y * dZ.real) / mu2
        g[:, 0, 1] += sII * ((k + 3) / 2 * Z.real - y * dZ.imag) / mu2
        g[:, 1, 0] += sII * (-(k - 1) / 2 * Z.real - y * dZ.imag) / mu2
        g[:, 1, 1] += sII * ((k - 3) / 2 * Z.imag - y * dZ.real) / mu2
        # uniform part: u = eps x (no rotation)
        eps = _compliance(mat, self._uniform())
        u += loc @ eps.T
        g += eps[None]
        return u, g

    def displacement(self, X: np.ndarray, side=None) -> np.ndarray:
        """(n, 2) global displacement; side (n,) picks the lip for points on the crack."""
        u, _ = self._local_gradient(X, side)
        return u @ self.rotation.T

    def gradient(self, X: np.ndarray, side=None) -> np.ndarray:
        """(n, 2, 2) global displacement gradient, [p, i, j] = d u_i / d x_j."""
        _, g = self._local_gradient(X, side)
        R = self.rotation
        return np.einsum("ik,nkl,jl->nij", R, g, R)

    def stress(self, X: np.ndarray, side=None) -> np.ndarray:
        """(n, 2, 2) global stress."""
        from ..scene.material import strain, stress
        return stress(strain(self.gradient(X, side)), self.material)

    def traction(self, normal):
        """A traction callable t(X) = sigma(X) n for a fixed outward normal (2,)."""
        n = np.asarray(normal, dtype=float)
        return lambda X: np.einsum("nij,j->ni", self.stress(X), n)

    def jump(self, x_local: np.ndarray) -> np.ndarray:
        """Exact (opening, slip) (n, 2) = [[u_y]], [[u_x]] in the crack frame at
        crack coordinates x (|x| < a), upper minus lower lip."""
        x = np.asarray(x_local, dtype=float)
        c = (self.material.kappa + 1) / (2 * self.material.mu) * np.sqrt(np.maximum(self.a ** 2 - x ** 2, 0.0))
        return np.stack([c * (self.remote[1] + self.pressure), c * (self.remote[2] + self.shear)], axis=1)


def _compliance(material: Material, sigma: np.ndarray) -> np.ndarray:
    """In-plane strain (2, 2) of a uniform stress (2, 2)."""
    E, nu = material.E_strain, material.nu_strain  # plane strain: eps_zz = 0
    tr = sigma[0, 0] + sigma[1, 1]
    return (1 + nu) * (sigma - nu * tr * np.eye(2)) / E


def remote_in_crack_frame(stress_xy: tuple[float, float, float], angle: float) -> tuple[float, float, float]:
    """A global uniform stress (sxx, syy, sxy) in the frame of a crack at
    `angle` degrees: (s_tt, s_nn, s_tn) (t along the crack, n normal)."""
    sxx, syy, sxy = stress_xy
    S = np.array([[sxx, sxy], [sxy, syy]])
    b = math.radians(angle)
    R = np.array([[math.cos(b), -math.sin(b)], [math.sin(b), math.cos(b)]])
    L = R.T @ S @ R
    return float(L[0, 0]), float(L[1, 1]), float(L[0, 1])
