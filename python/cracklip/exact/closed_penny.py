"""The closed penny crack: a penny crack of radius a in an infinite body
under a uniform remote stress that presses it shut (normal traction -p on
its plane, p > 0) and shears it (shear traction tau along a unit vector t
in its plane), with Coulomb friction mu on its lips.

Solution (derived here; the pieces are classical):

1. The uncracked uniform stress closes the crack: across the plane it
   transmits the pressure p with no jump, which the contact condition
   accepts (gap 0, pressure p >= 0). Hence the contact pressure is p
   everywhere and K_I = 0 along the whole front.
2. Stick: if |tau| <= mu p the uncracked field also satisfies the friction
   law (no slip, shear |tau| within the cone mu p): it is the solution,
   K_II = K_III = 0.
3. Slip: if |tau| > mu p, assume the whole crack slips along t, the
   friction traction mu p opposing the slip. The crack field is then the
   uncracked field plus the penny whose faces are relieved of the
   uniform shear tau_eff = tau - mu p sign(tau) (superposition). That
   penny's slip is parallel to t at every point, with the elliptical
   profile s(r) = 8 (1 - nu) tau_eff sqrt(a^2 - r^2) / (pi (2 - nu) mu_s),
   mu_s = E / (2 (1 + nu)) (Eshelby 1957; Segall, Earthquake and Volcano
   Deformation (2010) eq. 4.74 gives one face's half). The slip has the
   sign of tau_eff everywhere, so the friction opposes it everywhere with
   the magnitude mu p of a slipping point: the assumption holds, and no
   partial-slip zone exists (the loads are uniform).
4. K along the front from the slip near it: at a front point at angle
   omega from t, with e1 radial (outward), e2 = n, e3 = e1 x e2, the slip
   t s(r) has components s cos(omega) along e1 and s sin(omega) along e3
   (t = cos(omega) e1 + sin(omega) e3). At a distance d = a - r from the
   front s ~ 8 (1 - nu) tau_eff sqrt(2 a d) / (pi (2 - nu) mu_s), and the
   jumps of the modes are [[u_1]] = 8 (1 - nu^2) K_II sqrt(d / 2 pi) / E,
   [[u_3]] = 8 (1 + nu) K_III sqrt(d / 2 pi) / E. Hence

       K_II(omega)  = 4 tau_eff sqrt(a / pi) cos(omega) / (2 - nu),
       K_III(omega) = 4 (1 - nu) tau_eff sqrt(a / pi) sin(omega) / (2 - nu),

   Tada, Paris and Irwin's P.24.22 (the shear part of the inclined penny,
   embedded_cracks.inclined_penny_k; code_aster V6.04.159 quotes it) with
   tau replaced by tau_eff. The energy balance closes it: the front
   integral of G = (1 - nu^2)(K_II^2) / E + (1 + nu) K_III^2 / E equals
   d/da of (1/2) int tau_eff s dA = 8 (1 - nu) tau_eff^2 a^2 / ((2 - nu) mu_s)
   (tests/test_exact_closed_penny.py checks both numerically).
5. Inclined uniaxial compression sigma > 0 along a unit vector e_L at
   angle beta to the crack normal n: the stress -sigma e_L e_L gives the
   traction -sigma cos(beta) e_L on the + face, so

       p = sigma cos^2(beta),   |tau| = sigma sin(beta) cos(beta),

   t along minus the in-plane part of e_L, and the crack slips iff
   tan(beta) > mu.

The tests: K_I = 0, the pressure p everywhere, K_II and K_III above,
slip or stick, in one closed form (the 3D analogue of 2D's closed sliding
crack).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from .embedded_cracks import penny_shear_k, penny_slip


@dataclasses.dataclass(frozen=True)
class ClosedPenny:
    """The closed penny crack's solution (module doc).

    Attributes:
        a: radius; nu: Poisson's ratio.
        p: contact pressure (> 0), uniform over the crack.
        tau: remote shear traction on the crack's plane along t.
        mu: Coulomb friction coefficient.
        tau_eff: the shear the slipping faces carry beyond friction,
            tau - mu p sign(tau); 0 when the crack sticks.
        state: "slip" or "stick".
    """
    a: float
    nu: float
    p: float
    tau: float
    mu: float
    tau_eff: float
    state: str

    def k(self, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """K_I, K_II, K_III (each (n,)) at front angles omega (n,) from t."""
        K_II, K_III = penny_shear_k(self.tau_eff, self.a, self.nu, omega)
        return np.zeros(np.shape(K_II)), K_II, K_III

    def slip(self, r: np.ndarray, E: float) -> np.ndarray:
        """The slip along t (+ face minus - face) at distances r (n,) from the centre."""
        return penny_slip(r, self.tau_eff, self.a, E, self.nu)


def closed_penny(p: float, tau: float, mu: float, a: float, nu: float) -> ClosedPenny:
    """The closed penny crack under pressure p > 0 and shear tau with friction mu >= 0."""
    if not (math.isfinite(p) and p > 0.0):
        raise ValueError(f"closed_penny: the pressure must be > 0 (a crack in tension opens), got p = {p}")
    if not (math.isfinite(mu) and mu >= 0.0) or not math.isfinite(tau):
        raise ValueError(f"closed_penny: need mu >= 0 and a finite tau, got mu = {mu}, tau = {tau}")
    if not (a > 0.0 and -1.0 < nu < 0.5):
        raise ValueError(f"closed_penny: need a > 0 and -1 < nu < 0.5, got a = {a}, nu = {nu}")
    stick = abs(tau) <= mu * p
    tau_eff = 0.0 if stick else tau - mu * p * math.copysign(1.0, tau)
    return ClosedPenny(a, nu, p, tau, mu, tau_eff, "stick" if stick else "slip")


def inclined_compression(sigma: float, beta: float) -> tuple[float, float]:
    """(p, tau) on a crack plane whose normal makes the angle beta (radians)
    with a uniaxial compression of magnitude sigma > 0: sigma cos^2(beta),
    sigma sin(beta) cos(beta) (module doc, 5.)."""
    return sigma * math.cos(beta) ** 2, sigma * math.sin(beta) * math.cos(beta)


def closed_penny_inclined(sigma: float, beta: float, mu: float, a: float, nu: float) -> ClosedPenny:
    """The closed penny under uniaxial compression sigma > 0 at angle beta
    (radians, 0 <= beta < pi / 2) between the load and the crack normal."""
    if not 0.0 <= beta < 0.5 * math.pi:
        raise ValueError(f"closed_penny_inclined: beta must lie in [0, pi/2) (at pi/2 nothing presses the crack), "
                         f"got {beta}")
    p, tau = inclined_compression(sigma, beta)
    return closed_penny(p, tau, mu, a, nu)


__all__ = ["ClosedPenny", "closed_penny", "inclined_compression", "closed_penny_inclined"]
