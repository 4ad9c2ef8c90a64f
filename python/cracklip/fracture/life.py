"""Fatigue life from counted cycles: each cycle's K_max, K_min and Delta K_eff
from K at the load states of a pass, the growth per pass, and the pass count
between two crack lengths, with or without retardation.

Pure functions of arrays: K per load state (one number per distinct state
of the spectrum, from a solve per state or from superposition, see
cracklip.analysis.life) and cycles as pairs of state indices (from
cracklip.fracture.rainflow). Nothing here solves.

Closure, one of CLOSURES, never two at once:

- "contact": K at each state is what the solve with crack-lip contact
  gives (a closed tip has K_I ~ 0, not the negative linear value); the
  law sees Delta K = K_max - K_min and R = K_min / K_max of those K, with
  NASGRO's f = R (its closure is not added again). Contact closure is
  elastic lip contact: closure by compression, residual stress or the
  part's own geometry, no plastic wake.
- "newman": K is the linear value at every state (lips free to pass
  through each other), and closure is Newman's opening function f(R):
  NASGRO's own, or U = (1 - f) / (1 - R) times Delta K for the Paris and
  Hartman-Schijve laws (their constants must then be effective-range ones).
- "none": linear K, full range, no closure.
"""
from __future__ import annotations

import dataclasses
import math
import typing

import numpy as np

from ..errors import InputError
from .laws import GrowthLaw, Nasgro, newman_f
from .retardation import OverloadState, Retardation, plastic_zone, retarded_rates


CLOSURES = ("contact", "newman", "none")


@dataclasses.dataclass
class CycleTable:
    """Cycles of one pass as load-state indices, in the order they close.

    Attributes:
        lo: state index of each cycle's minimum.
        hi: state index of each cycle's maximum.
        count: 1 (full) or 0.5 (half) per cycle.
        block: the block (flight) of the pass each cycle closes in.
    """
    lo: np.ndarray
    hi: np.ndarray
    count: np.ndarray
    block: np.ndarray | None = None

    def __post_init__(self):
        self.lo = np.asarray(self.lo, dtype=int)
        self.hi = np.asarray(self.hi, dtype=int)
        self.count = np.asarray(self.count, dtype=float)
        if self.block is not None:
            self.block = np.asarray(self.block, dtype=int)

    @property
    def cycles(self) -> float:
        return float(self.count.sum())

    def unique(self) -> "CycleTable":
        """The same cycles with equal (lo, hi) pairs merged (counts added;
        order lost): the growth per pass without sequence effects. Kept
        after the first call (a table is not changed in place)."""
        cached = getattr(self, "_unique", None)
        if cached is not None:
            return cached
        if self.lo.size == 0:
            self._unique = self
            return self
        n = int(max(self.lo.max(), self.hi.max())) + 1
        keys, inv = np.unique(self.lo.astype(np.int64) * n + self.hi, return_inverse=True)
        counts = np.bincount(inv.ravel(), weights=self.count, minlength=len(keys))
        self._unique = CycleTable(keys // n, keys % n, counts)
        self._unique._unique = self._unique
        return self._unique

    def slice(self, i0: int, i1: int) -> "CycleTable":
        return CycleTable(self.lo[i0:i1], self.hi[i0:i1], self.count[i0:i1],
                          None if self.block is None else self.block[i0:i1])


@dataclasses.dataclass(frozen=True)
class LifeLaw:
    """A growth law with its closure (CLOSURES): rates of cycles from their K.

    Attributes:
        law: the growth law (cracklip.fracture.laws).
        closure: "contact", "newman" or "none" (module doc).
        alpha, smax_over_flow: Newman's f for closure "newman" with a law
            that has no f of its own (Paris, Hartman-Schijve).
        threshold: Delta K below which a cycle does not grow (besides the
            law's own threshold; 0: none).
    """
    law: GrowthLaw
    closure: str = "contact"
    alpha: float = 2.0
    smax_over_flow: float = 0.3
    threshold: float = 0.0

    def __post_init__(self):
        if self.closure not in CLOSURES:
            raise InputError(f"closure must be one of {CLOSURES}, got {self.closure!r}")
        if self.closure == "newman" and self.law.name not in ("nasgro", "paris", "hartman_schijve"):
            raise InputError(f"material.fatigue.closure = 'newman' applies Newman's f to Delta K; the "
                             f"{self.law.name} law carries its own R dependence (that would count closure "
                             "twice): use closure 'contact' or 'none', or the nasgro, paris or "
                             "hartman_schijve law")
        if isinstance(self.law, Nasgro) and self.law.newman != (self.closure == "newman"):
            object.__setattr__(self, "law", dataclasses.replace(self.law, newman=self.closure == "newman"))

    @property
    def K_crit(self) -> float | None:
        return self.law.K_crit

    def effective(self, K_max: np.ndarray, K_min: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(Delta K as the law sees it, R) of cycles from K_max, K_min: the
        range, times U = (1 - f) / (1 - R) for Newman closure on a law
        without its own f; R = K_min / K_max (0 where K_max <= 0)."""
        km = np.asarray(K_max, dtype=float)
        kn = np.asarray(K_min, dtype=float)
        pos = km > 0.0
        R = np.where(pos, kn / np.where(pos, km, 1.0), 0.0)
        dk = np.where(pos, km - kn, 0.0)
        if self.closure == "newman" and self.law.name in ("paris", "hartman_schijve"):
            f = newman_f(R, self.alpha, self.smax_over_flow)
            dk = dk * np.where(R < 1.0, (1.0 - f) / np.where(R < 1.0, 1.0 - R, 1.0), 1.0)
        return dk, R

    def rates(self, K_max: np.ndarray, K_min: np.ndarray, a: float | np.ndarray) -> np.ndarray:
        """da/dN of each cycle (0 where K_max <= 0 or below threshold; +inf at
        the law's critical K)."""
        km = np.asarray(K_max, dtype=float)
        dk, R = self.effective(km, K_min)
        with np.errstate(invalid="ignore", divide="ignore"):
            out = self.law.rate(dk, R, km, a)
        out = np.where((km > 0.0) & (dk > self.threshold), out, 0.0)
        return out

    def law_threshold(self, K_max: np.ndarray, K_min: np.ndarray, a: float) -> np.ndarray | float:
        """The threshold Delta K of each cycle (Willenborg's phi)."""
        if isinstance(self.law, Nasgro):
            _, R = self.effective(K_max, K_min)
            return self.law.threshold(np.minimum(R, 0.99), a)
        return self.threshold


def cycle_k(K_states: np.ndarray, cycles: CycleTable) -> tuple[np.ndarray, np.ndarray]:
    """K_max and K_min of each cycle from K at the load states."""
    K = np.asarray(K_states, dtype=float)
    return K[cycles.hi], K[cycles.lo]


def pass_growth(K_states: np.ndarray, cycles: CycleTable, law: LifeLaw, a: float) -> float:
    """Growth over one pass without sequence effects: sum of count x da/dN
    (pass cycles.unique() for speed; +inf when a cycle reaches K_crit)."""
    km, kn = cycle_k(K_states, cycles)
    return float(np.sum(cycles.count * law.rates(km, kn, a)))


def passes_between(growth: typing.Callable[[float], float], a0: float, a1: float, panels: int = 400) -> float:
    """Passes to grow from a0 to a1 when one pass grows the crack by
    growth(a): the integral of da / growth(a), composite Simpson on ln a
    (exact to ~1e-10 relative for power-law rates with 400 panels). inf if
    growth vanishes (below threshold) somewhere."""
    if not a1 > a0 > 0.0:
        raise InputError(f"passes_between needs 0 < a0 < a1, got a0 = {a0}, a1 = {a1}")
    n = panels + panels % 2
    s = np.linspace(math.log(a0), math.log(a1), n + 1)
    a = np.exp(s)
    g = np.array([growth(float(x)) for x in a])
    if np.any(g <= 0.0):
        return math.inf
    f = a / g
    w = np.ones(n + 1)
    w[1:-1:2], w[2:-1:2] = 4.0, 2.0
    return float((s[1] - s[0]) / 3.0 * np.sum(w * f))


@dataclasses.dataclass
class RetardedRun:
    """Where a run with retardation got to: a, cycles, passes (fractional),
    the overload state, and whether it reached the target length."""
    a: float
    cycles: float
    passes: float
    state: OverloadState
    reached: bool


def grow_with_retardation(K_of_a: typing.Callable[[float], np.ndarray], passes: typing.Callable[[int], CycleTable],
                          law: LifeLaw, ret: Retardation, a0: float, a_end: float, state: OverloadState | None = None,
                          max_passes: int = 10 ** 7, chunk_tol: float = 0.05) -> RetardedRun:
    """Grow cycle by cycle in the order they close, pass after pass, with
    retardation: passes(i) gives pass i's cycles (as state indices),
    K_of_a(a) K at every state for crack length a. A pass is taken in
    chunks over which the crack grows at most chunk_tol times the largest
    plastic zone in play (ret_zone), each chunk twice: a predictor at its start
    length gives every cycle's crack length (the growth of the cycles
    before it), the corrector takes the overload zones at those lengths and
    K at the chunk's middle (second order in the chunk's growth). Stops at
    the cycle where a reaches a_end (cycle resolution). K may be any
    function of a here; grow and `cracklip life` use the compiled kernel
    (fracture.life_kernels.integrate_cycles: each cycle at its own length,
    K from a table), which this vectorised form approximates to 5e-5 on the
    notes' Wheeler check (tests/test_table_life.py)."""
    st = state if state is not None else OverloadState()
    a = a0
    cycles = 0.0
    size = None  # the last accepted chunk's length: the next one tries twice that first
    for i in range(max_passes):
        ct = passes(i)
        n = len(ct.lo)
        i0 = 0
        while i0 < n:
            i1 = n if size is None else min(n, i0 + 2 * size)
            while True:
                chunk = ct.slice(i0, i1)
                K0 = K_of_a(a)
                da1, _ = _chunk_rates(K0, chunk, law, ret, a, st)
                total = float(np.sum(da1))
                r = ret_zone(K0, chunk, ret, st)
                if not math.isfinite(total) or total <= chunk_tol * r or i1 - i0 <= 1:
                    break
                i1 = i0 + max(1, int((i1 - i0) * chunk_tol * r / total))
            if not math.isfinite(total):
                return RetardedRun(a, cycles, i + i0 / max(n, 1), st, False)
            a_cycle = a + np.r_[0.0, np.cumsum(da1)[:-1]]
            da, st_new = _chunk_rates(K_of_a(a + 0.5 * total), chunk, law, ret, a_cycle, st)
            cum = np.cumsum(da)
            if a + cum[-1] >= a_end or not np.all(np.isfinite(cum)):
                k = min(int(np.searchsorted(cum, a_end - a)), len(cum) - 1)
                reached = bool(np.isfinite(cum[k]))
                return RetardedRun(a_end if reached else a, cycles + float(np.sum(chunk.count[:k + 1])),
                                   i + (i0 + k + 1) / max(n, 1), st_new, reached)
            a += float(cum[-1])
            cycles += chunk.cycles
            st = st_new
            size = i1 - i0
            i0 = i1
    return RetardedRun(a, cycles, float(max_passes), st, False)


def ret_zone(K_states: np.ndarray, chunk: CycleTable, ret: Retardation, state: OverloadState | None = None) -> float:
    """The length a chunk's growth must stay small against: the largest
    plastic zone among its cycles and the governing overload's (the zones
    that set the retardation; each cycle's own crack length comes from the
    predictor, so only this scale bounds the error)."""
    km = np.asarray(K_states, dtype=float)[chunk.hi]
    r = plastic_zone(km, ret.sigma_ys, ret.beta)
    big = max(float(r.max()) if r.size else 0.0, state.r_OL if state is not None else 0.0)
    return big if big > 0 else math.inf


def _chunk_rates(K: np.ndarray, chunk: CycleTable, law: LifeLaw, ret: Retardation, a: np.ndarray | float,
                 state: OverloadState) -> tuple[np.ndarray, OverloadState]:
    km, kn = cycle_k(K, chunk)
    a_mean = float(np.mean(a))
    rates, after = retarded_rates(a, km, kn, state, ret, lambda x, y: law.rates(x, y, a_mean),
                                  law.law_threshold(km, kn, a_mean))
    return chunk.count * rates, after


__all__ = ["CLOSURES", "CycleTable", "LifeLaw", "cycle_k", "pass_growth", "passes_between", "RetardedRun",
           "grow_with_retardation"]
