"""What the growth loop records per tip and step, and the geometric helpers
it shares with the fatigue life (cracklip.analysis.life)."""
from __future__ import annotations

import dataclasses
import math
import typing

import numpy as np


#: The status of a tip whose growth rate is 0 this step: below the law's
#: threshold, or shut at every load of the cycle or pass (K_I <= 0 at its
#: largest: a crack pressed closed, where "below threshold" hid the cause).
BELOW_THRESHOLD = "below threshold"
SHUT = "shut at every load (K_I <= 0)"


def no_growth_status(K_I_max: float) -> str:
    """BELOW_THRESHOLD, or SHUT where the largest K_I of the cycle is <= 0."""
    return SHUT if K_I_max <= 0.0 else BELOW_THRESHOLD


@dataclasses.dataclass
class TipRecord:
    """One tip at one step: where it is, its K (at the maximum load in
    fatigue), the kink it takes, and the cycles."""
    step: int
    crack: int
    end: int  # 0: the polyline's first point, 1: its last
    x: float
    y: float
    length: float
    K_I: float
    K_II: float
    K_I_spread: float
    K_II_spread: float
    kink_deg: float
    K_eq: float
    closed_fraction: float
    da: float = 0.0
    K_I_min: float | None = None
    K_II_min: float | None = None
    delta_K: float | None = None
    dN: float = 0.0
    N: float = 0.0
    status: str = "growing"
    sif_radius: float = 0.0
    # A spectrum life (analysis.life): the tip's crack length a, its largest counted cycle (K_max,
    # K_min, the Delta K the law sees, R), its growth per pass, the residual strength (multiple of the
    # varying loads at their maximum), passes and blocks (flights) so far.
    a: float | None = None
    K_max: float | None = None
    K_min: float | None = None
    delta_K_eff: float | None = None
    R: float | None = None
    da_per_pass: float | None = None
    residual_strength: float | None = None
    passes: float | None = None
    blocks: float | None = None

    def row(self) -> dict[str, typing.Any]:
        return dataclasses.asdict(self)


@dataclasses.dataclass
class FrontRecord(TipRecord):
    """One growth point of a 3D front at one step: a TipRecord whose `end`
    is the point's index along its crack's front and `length` its crack
    size a (the distance from the crack's origin), with z, K_III and its
    spread, the twist (degrees), whether the point is where the front meets
    the part's boundary, and the element size there."""
    z: float = 0.0
    K_III: float = 0.0
    K_III_spread: float = 0.0
    twist_deg: float = 0.0
    free_surface: bool = False
    element_size: float = 0.0


@dataclasses.dataclass
class Measured:
    """One measurement of a geometry: the tip records, the fatigue rates (da
    per cycle, or per pass of a spectrum), the solution at the maximum load
    and its model, the solves it took (one per load level), and in a
    spectrum life each tip's K at every load state (analysis.life)."""
    records: list[TipRecord]
    rates: dict[tuple[int, int], float]
    lengths: list[float]
    sol: typing.Any
    model: typing.Any
    solves: int = 1
    levels: typing.Any = None


def segment_hit(p: np.ndarray, q: np.ndarray, a: np.ndarray, b: np.ndarray) -> float | None:
    """The smallest t in (0, 1] with p + t (q - p) on one of the segments a-b, or None."""
    d = q - p
    e = b - a
    den = d[0] * e[:, 1] - d[1] * e[:, 0]
    ok = np.abs(den) > 1e-300
    w = a - p
    t = np.where(ok, (w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0]) / np.where(ok, den, 1.0), np.inf)
    s = np.where(ok, (w[:, 0] * d[1] - w[:, 1] * d[0]) / np.where(ok, den, 1.0), np.inf)
    hit = ok & (t > 1e-12) & (t <= 1.0) & (s >= 0.0) & (s <= 1.0)
    return float(t[hit].min()) if np.any(hit) else None


def distance_to_segments(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    d = b - a
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / dd, 0.0, 1.0)
    return float(np.linalg.norm(a + t[:, None] * d - p, axis=1).min()) if len(a) else math.inf


def crack_length(points: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())


def part_length(model, crack: int) -> float:
    """The length of a crack inside the part (its polyline may run beyond the boundary)."""
    from ..model.tip_regions import length_in_part
    return length_in_part(model, crack)


def closed_fraction(sol, crack: int) -> float:
    if not sol.contact:
        return 0.0
    smp = sol.lip_samples(crack, 2)
    w = smp["weight"]
    closed = smp["state"] != "open"
    return float(w[closed].sum() / w.sum()) if w.sum() > 0 else 0.0
