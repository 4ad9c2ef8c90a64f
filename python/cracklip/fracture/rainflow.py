"""Cycle counting of a load history: ASTM E1049 rainflow, range-pair and
valley-to-peak, with the residue of a repeated history closed.

A history is a sequence of values (a load factor, a stress or a K). Every
counter works on its reversals (turning points: the points where the
slope changes sign; plateaus collapse to one point) and returns the
counted cycles as ``Cycles``: for each cycle the index of its minimum and
of its maximum in the reversal sequence (so a caller can look up any
quantity of those turning points, e.g. K of both load states), the count
(1 or 0.5) and the order in which the cycles close (for sequence effects:
retardation).

- ``rainflow``: ASTM E1049-85 section 5.4.4 (three-point rule with the
  starting point): ranges containing the starting point are half cycles,
  the ranges left at the end half cycles. The E1049 example -2, 1, -3, 5,
  -1, 3, -4, 4, -2 gives (range, count) (3, 0.5), (4, 1.5), (6, 0.5),
  (8, 1.0), (9, 0.5).
- ``rainflow_repeated``: the history repeated without end, each pass
  counted alike: the history is started at its largest absolute value
  and closed on it (E1049 section 5.4.5), so every cycle is a full one
  and nothing is left over. The example gives full cycles of 3, 4, 7, 9.
- ``range_pair``: the three-point rule without the starting-point rule
  (every closed range a full cycle); the residue as in rainflow (half
  cycles), or closed like rainflow_repeated.
- ``valley_to_peak``: every rise from a valley to the next peak is one
  cycle (the "tension part" of each excursion; easigrow's "tension").
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..errors import InputError


METHODS = ("rainflow", "range_pair", "valley_to_peak")


@dataclasses.dataclass
class Cycles:
    """Counted cycles of a reversal sequence.

    Attributes:
        lo: index (into the reversals) of each cycle's minimum.
        hi: index of each cycle's maximum.
        count: 1.0 (full) or 0.5 (half) per cycle.
    The cycles are stored in the order they close (the residue's half
    cycles last).
    """
    lo: np.ndarray
    hi: np.ndarray
    count: np.ndarray

    def __len__(self) -> int:
        return int(self.lo.size)

    def ranges(self, values: np.ndarray) -> np.ndarray:
        v = np.asarray(values, dtype=float)
        return v[self.hi] - v[self.lo]

    def table(self, values: np.ndarray, decimals: int = 12) -> list[tuple[float, float]]:
        """(range, total count) for each distinct range, ascending."""
        r = np.round(self.ranges(values), decimals)
        out: dict[float, float] = {}
        for x, c in zip(r.tolist(), self.count.tolist()):
            out[x] = out.get(x, 0.0) + c
        return sorted(out.items())


def reversal_indices(values: np.ndarray) -> np.ndarray:
    """Indices of the turning points of a history: the first and last point
    and every point where the slope changes sign (of a plateau its first
    point). Raises InputError for a history with no reversal (fewer than two
    distinct values) or a non-finite value."""
    v = np.asarray(values, dtype=float).ravel()
    if v.size and not np.all(np.isfinite(v)):
        bad = int(np.flatnonzero(~np.isfinite(v))[0])
        raise InputError(f"the load history has a non-finite value {v[bad]} at point {bad}")
    keep = np.flatnonzero(np.r_[True, np.diff(v) != 0.0])  # first point of every plateau
    w = v[keep]
    if w.size < 2:
        raise InputError("the load history has no reversal: it needs at least two different values")
    d = np.sign(np.diff(w))
    turn = np.flatnonzero(d[1:] != d[:-1]) + 1
    return keep[np.r_[0, turn, w.size - 1]]


def _count(v: np.ndarray, start_rule: bool) -> tuple[list[tuple[int, int, float]], list[int]]:
    """The three-point rule on a reversal sequence v: (i, j, count) of the
    counted ranges (indices into v) and the residue (indices left)."""
    stack: list[int] = []
    out: list[tuple[int, int, float]] = []
    for k in range(v.size):
        stack.append(k)
        while len(stack) >= 3:
            x = abs(v[stack[-1]] - v[stack[-2]])
            y = abs(v[stack[-2]] - v[stack[-3]])
            if x < y:
                break
            if start_rule and len(stack) == 3:
                # Y holds the starting point: half a cycle, the start moves on.
                out.append((stack[0], stack[1], 0.5))
                stack.pop(0)
            else:
                out.append((stack[-3], stack[-2], 1.0))
                del stack[-3:-1]
    return out, stack


def _as_cycles(v: np.ndarray, ranges: list[tuple[int, int, float]], index: np.ndarray) -> Cycles:
    i = np.array([r[0] for r in ranges], dtype=int)
    j = np.array([r[1] for r in ranges], dtype=int)
    c = np.array([r[2] for r in ranges], dtype=float)
    low = np.where(v[i] <= v[j], i, j)
    high = np.where(v[i] <= v[j], j, i)
    return Cycles(index[low], index[high], c)


def count_cycles(values, method: str = "rainflow", repeated: bool = True) -> Cycles:
    """Count the cycles of a history (module doc). values: the history;
    repeated: the history repeats (its residue is closed: full cycles only)
    or is counted once (ASTM: residue as half cycles; valley_to_peak has no
    residue). Indices in the result refer to the given values."""
    if method not in METHODS:
        raise InputError(f"cycle counting must be one of {METHODS}, got {method!r}")
    rev = reversal_indices(values)
    v = np.asarray(values, dtype=float).ravel()[rev]
    if repeated:
        # Start at the largest absolute value, close the loop on it (E1049 5.4.5); the joint (the
        # last point, then the first) may not be a reversal: such points drop out.
        k = int(np.argmax(np.abs(v)))
        order = np.r_[np.arange(k, v.size), np.arange(0, k), k]
        keep = reversal_indices(v[order])
        order = order[keep]
        vv = v[order]
        if method == "valley_to_peak":
            up = np.flatnonzero(vv[1:] > vv[:-1])
            return Cycles(rev[order[up]], rev[order[up + 1]], np.ones(up.size))
        ranges, _ = _count(vv, start_rule=False)
        return _as_cycles(vv, ranges, rev[order])
    if method == "valley_to_peak":
        up = np.flatnonzero(v[1:] > v[:-1])
        return Cycles(rev[up], rev[up + 1], np.ones(up.size))
    ranges, residue = _count(v, start_rule=(method == "rainflow"))
    ranges += [(residue[i], residue[i + 1], 0.5) for i in range(len(residue) - 1)]
    return _as_cycles(v, ranges, rev)


def rainflow(values) -> list[tuple[float, float]]:
    """ASTM E1049 rainflow of a history counted once: (range, count) per distinct range."""
    return count_cycles(values, "rainflow", repeated=False).table(values)


def rainflow_repeated(values) -> list[tuple[float, float]]:
    """Rainflow of a history repeated without end (residue closed): (range, count)."""
    return count_cycles(values, "rainflow", repeated=True).table(values)


__all__ = ["METHODS", "Cycles", "reversal_indices", "count_cycles", "rainflow", "rainflow_repeated"]
