"""The material: linear elastic and isotropic, plane strain or plane stress, and its
stress-strain law on displacement gradients."""
from __future__ import annotations

import dataclasses
import math
import numbers

import numpy as np

from ..errors import MaterialError, checked_keywords


PLANES = ("strain", "stress")


@checked_keywords
@dataclasses.dataclass(frozen=True)
class Material:
    """Linear elastic, isotropic; a planar part in plane strain (default) or
    plane stress, a 3D part plain 3D elasticity (plane stays "strain").

    Attributes:
        E: Young's modulus (> 0).
        nu: Poisson's ratio (-1 < nu < 0.5 in plane strain and in 3D, <= 0.5 in
            plane stress).
        plane: "strain" (thick parts: eps_zz = 0) or "stress" (thin plates:
            sigma_zz = 0).

    Plane stress with (E, nu) has the in-plane response of plane strain with
    (E_strain, nu_strain) = (E (1 + 2 nu) / (1 + nu)^2, nu / (1 + nu)): the
    kernels, the Williams fields (kappa = (3 - nu) / (1 + nu)) and K = sqrt(E* G)
    (E* = E) all follow from that pair, exactly.
    """
    E: float
    nu: float
    plane: str = "strain"

    def __post_init__(self):
        if self.plane not in PLANES:
            raise MaterialError(f"plane must be 'strain' or 'stress', got {self.plane!r}")
        for name in ("E", "nu"):
            value = getattr(self, name)
            if not isinstance(value, numbers.Real) or isinstance(value, bool):
                raise MaterialError(f"Material.{name} must be a number, got {value!r} ({type(value).__name__})")
        if not (math.isfinite(self.E) and self.E > 0.0):
            raise MaterialError(f"Young's modulus E must be positive, got {self.E}")
        ok = isinstance(self.nu, numbers.Real) and math.isfinite(self.nu) and -1.0 < self.nu <= 0.5
        if not ok or (self.plane == "strain" and self.nu == 0.5):
            raise MaterialError(
                f"Poisson's ratio nu must lie in (-1, 0.5) (plane strain, or a 3D part), got {self.nu} (nu = 0.5 is "
                "incompressible: not supported)" if self.plane == "strain" else
                f"Poisson's ratio nu must lie in (-1, 0.5] for plane stress, got {self.nu}")

    @property
    def E_strain(self) -> float:
        """Young's modulus of the plane-strain material with the same in-plane response."""
        return self.E if self.plane == "strain" else self.E * (1.0 + 2.0 * self.nu) / (1.0 + self.nu) ** 2

    @property
    def nu_strain(self) -> float:
        """Poisson's ratio of the plane-strain material with the same in-plane response."""
        return self.nu if self.plane == "strain" else self.nu / (1.0 + self.nu)

    @property
    def mu(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def kappa(self) -> float:
        """Kolosov's constant: 3 - 4 nu (plane strain), (3 - nu) / (1 + nu) (plane stress)."""
        return 3.0 - 4.0 * self.nu_strain

    @property
    def E_star(self) -> float:
        """E' of G = K^2 / E': E / (1 - nu^2) (plane strain), E (plane stress)."""
        return self.E_strain / (1.0 - self.nu_strain ** 2)

    @property
    def sigma_zz_ratio(self) -> float:
        """sigma_zz / (sigma_xx + sigma_yy): nu (plane strain), 0 (plane stress)."""
        return self.nu if self.plane == "strain" else 0.0

    def scaled(self, E: float) -> "Material":
        """The same material with Young's modulus E."""
        return Material(E, self.nu, self.plane)


def strain(grad: np.ndarray) -> np.ndarray:
    """Symmetric part of gradients (n, d, d)."""
    return 0.5 * (grad + np.swapaxes(grad, 1, 2))


def stress(eps: np.ndarray, material) -> np.ndarray:
    """Stress (n, d, d) of strains (n, d, d): in-plane (plane strain or
    stress) for d = 2, plain elasticity for d = 3 (plane is "strain" there)."""
    E, nu = material.E_strain, material.nu_strain
    lmbda = E * nu / ((1 + nu) * (1 - 2 * nu))
    d = eps.shape[1]
    tr = np.trace(eps, axis1=1, axis2=2)
    return 2 * material.mu * eps + lmbda * tr[:, None, None] * np.eye(d)[None]
