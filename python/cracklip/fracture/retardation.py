"""Load interaction: Wheeler and generalized Willenborg retardation.

An overload leaves a plastic zone ahead of the tip, r_y = (K_max /
sigma_ys)^2 / (beta pi), beta = 2 in plane stress, 6 in plane strain
(Irwin's zone; beta chosen by the thickness when "auto": plane strain when
t >= 2.5 (K_Ic / sigma_ys)^2). While the current cycle's zone lies inside
the overload's (a + r_y < a_OL + r_y,OL) growth is retarded:

- Wheeler (1972): da/dN = C_p (da/dN)_CA, C_p = [r_y / (a_OL + r_y,OL -
  a)]^gamma.
- generalized Willenborg (Gallagher): a residual K_R = phi [K_max,OL sqrt(1
  - (a - a_OL) / r_y,OL) - K_max] (>= 0), phi = (1 - Delta K_th / Delta K) /
  (SOLR - 1) with SOLR the shut-off overload ratio (a material constant:
  an overload SOLR times the cycle's K_max arrests growth); K_max,eff =
  K_max - K_R, K_min,eff = max(K_min - K_R, 0): the law sees Delta K_eff =
  K_max,eff - K_min,eff and R_eff = K_min,eff / K_max,eff; no growth once
  K_max,eff <= 0.

A cycle whose zone reaches beyond the current overload zone becomes the new
overload (no retardation for it). Sources: the notes (gap 3), read in the
MATLAB scripts of andrelrosam/CRACK-GROWTH-RETARDATION-MODELS-UNDER-LOAD-
INTERACTION; SOLR as a material constant as in NASGRO's manual (the script
puts the applied overload ratio there; not copied).

The functions take a sequence of cycles at one crack length a (the caller
keeps a chunk of cycles short against the plastic zone, cracklip.fracture.
life) and the state left by the cycles before; they return each cycle's
rate and the new state. Everything is vectorised over the cycles (running
maxima), so a flight of 1e5 cycles costs a few numpy passes.
"""
from __future__ import annotations

import dataclasses
import math
import typing

import numpy as np


MODELS = ("none", "wheeler", "willenborg")


def plastic_zone(K_max: np.ndarray | float, sigma_ys: float, beta: float) -> np.ndarray:
    """Irwin's plastic zone size (K_max / sigma_ys)^2 / (beta pi); 0 for K_max <= 0."""
    k = np.maximum(np.asarray(K_max, dtype=float), 0.0)
    return (k / sigma_ys) ** 2 / (beta * math.pi)


def constraint_beta(constraint: str, thickness: float | None = None, K_Ic: float | None = None,
                    sigma_ys: float | None = None) -> float:
    """beta of the plastic zone: 2 (plane stress), 6 (plane strain); "auto":
    plane strain when t >= 2.5 (K_Ic / sigma_ys)^2."""
    if constraint == "plane_stress":
        return 2.0
    if constraint == "plane_strain":
        return 6.0
    if thickness is None or K_Ic is None or sigma_ys is None:
        return 2.0
    return 6.0 if thickness >= 2.5 * (K_Ic / sigma_ys) ** 2 else 2.0


@dataclasses.dataclass
class OverloadState:
    """The governing overload: the crack length a_OL at it, its plastic zone
    r_OL and its K_max (zone end a_OL + r_OL; none yet: zone end -inf)."""
    a_OL: float = -math.inf
    r_OL: float = 0.0
    K_OL: float = 0.0

    @property
    def zone_end(self) -> float:
        return self.a_OL + self.r_OL


@dataclasses.dataclass(frozen=True)
class Retardation:
    """Retardation settings: model (MODELS), sigma_ys, beta (plastic zone),
    gamma (Wheeler's exponent), shutoff (Willenborg's SOLR)."""
    model: str
    sigma_ys: float
    beta: float = 2.0
    gamma: float = 1.0
    shutoff: float = 3.0

    def governing(self, a: np.ndarray | float, K_max: np.ndarray, state: OverloadState
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, OverloadState]:
        """For each cycle (crack length a: one value or one per cycle): its
        zone r, the overload governing it (a_OL, r_OL, K_OL: the largest zone
        end a + r among the state and the cycles before it), whether it is
        itself a new overload (its zone reaches the governing one's end), and
        the state after the sequence."""
        km = np.maximum(np.asarray(K_max, dtype=float), 0.0)
        n = km.size
        aa = np.broadcast_to(np.asarray(a, dtype=float), km.shape)
        r = plastic_zone(km, self.sigma_ys, self.beta)
        if n == 0:
            return r, r, r, r, np.zeros(0, dtype=bool), state
        z = aa + r
        cm = np.maximum.accumulate(z)
        record = np.r_[True, z[1:] > cm[:-1]]
        arg = np.maximum.accumulate(np.where(record, np.arange(n), 0))
        prev_arg = np.r_[0, arg[:-1]]
        prev_end = np.r_[-np.inf, cm[:-1]]
        inner = prev_end > state.zone_end
        a_ol = np.where(inner, aa[prev_arg], state.a_OL)
        r_ol = np.where(inner, r[prev_arg], state.r_OL)
        k_ol = np.where(inner, km[prev_arg], state.K_OL)
        new = z >= np.maximum(prev_end, state.zone_end)
        j = int(arg[-1])
        if z[j] >= state.zone_end:
            state = OverloadState(float(aa[j]), float(r[j]), float(km[j]))
        return r, a_ol, r_ol, k_ol, new, state


def wheeler_factor(a: np.ndarray | float, r: np.ndarray, a_ol: np.ndarray, r_ol: np.ndarray, new: np.ndarray,
                   gamma: float) -> np.ndarray:
    """C_p = [r / (a_OL + r_OL - a)]^gamma inside the overload zone, 1 otherwise."""
    room = np.maximum(a_ol + r_ol - a, 1e-300)
    return np.where(new, 1.0, np.clip(r / room, 0.0, 1.0) ** gamma)


def willenborg_k(a: np.ndarray | float, K_max: np.ndarray, K_min: np.ndarray, a_ol: np.ndarray, r_ol: np.ndarray,
                 k_ol: np.ndarray, new: np.ndarray, shutoff: float,
                 threshold: np.ndarray | float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """K_max,eff and K_min,eff of the generalized Willenborg model (module doc)."""
    km, kn = np.asarray(K_max, dtype=float), np.asarray(K_min, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        depth = np.clip(1.0 - (a - a_ol) / np.where(r_ol > 0, r_ol, 1.0), 0.0, 1.0)
        kw = np.maximum(k_ol * np.sqrt(depth) - km, 0.0)
        dk = km - kn
        phi = np.clip(1.0 - np.asarray(threshold, dtype=float) / np.where(dk > 0, dk, np.inf), 0.0, 1.0) \
            / (shutoff - 1.0)
    kr = np.where(new | (r_ol <= 0.0), 0.0, phi * kw)
    return km - kr, np.maximum(kn - kr, 0.0)


def retarded_rates(a: np.ndarray | float, K_max: np.ndarray, K_min: np.ndarray, state: OverloadState, ret: Retardation,
                   rate: typing.Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray],
                   threshold: np.ndarray | float = 0.0) -> tuple[np.ndarray, OverloadState]:
    """Each cycle's da/dN with retardation (a: the crack length, one value or
    one per cycle), and the state after the sequence. rate(K_max, K_min) ->
    da/dN without retardation."""
    r, a_ol, r_ol, k_ol, new, after = ret.governing(a, K_max, state)
    if ret.model == "wheeler":
        return rate(K_max, K_min) * wheeler_factor(a, r, a_ol, r_ol, new, ret.gamma), after
    kx, kn = willenborg_k(a, K_max, K_min, a_ol, r_ol, k_ol, new, ret.shutoff, threshold)
    out = np.where(kx > 0.0, rate(np.where(kx > 0.0, kx, 1.0), np.where(kx > 0.0, kn, 0.0)), 0.0)
    return out, after


__all__ = ["MODELS", "plastic_zone", "constraint_beta", "OverloadState", "Retardation", "wheeler_factor",
           "willenborg_k", "retarded_rates"]
