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

The counting itself is compiled (cpp/life/rainflow.cpp: one pass with a
stack, O(n)); this module checks the history and names the cycles.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from .. import _cracklip
from ..errors import InputError


METHODS = ("rainflow", "range_pair", "valley_to_peak")


@dataclasses.dataclass
class Cycles:
    """Counted cycles of a reversal sequence.

    Attributes:
        lo: index into the counted history (the values given to
            count_cycles, not its reversals) of each cycle's minimum.
        hi: index of each cycle's maximum, likewise.
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


def _history(values) -> np.ndarray:
    """The history as a flat float array; InputError for a non-finite value
    or a history with no reversal (fewer than two distinct values)."""
    try:
        v = np.ascontiguousarray(values, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"the load history must be numbers (a sequence of load values), got {values!r:.80}") from None
    if v.size and not np.all(np.isfinite(v)):
        bad = int(np.flatnonzero(~np.isfinite(v))[0])
        raise InputError(f"the load history has a non-finite value {v[bad]} at point {bad}")
    if v.size < 2 or not np.any(v != v[0]):
        raise InputError("the load history has no reversal: it needs at least two different values")
    return v


def reversal_indices(values: np.ndarray) -> np.ndarray:
    """Indices of the turning points of a history: the first and last point
    and every point where the slope changes sign (of a plateau its first
    point). Raises InputError for a history with no reversal (fewer than two
    distinct values) or a non-finite value."""
    return np.asarray(_cracklip.reversal_indices(_history(values)), dtype=int)


def count_cycles(values, method: str = "rainflow", repeated: bool = True) -> Cycles:
    """Count the cycles of a history (module doc). values: the history (a
    sequence of load values, any units); method: one of METHODS,
    "rainflow" (ASTM E1049), "range_pair" or "valley_to_peak"; repeated: the history repeats (its residue is closed: full cycles only)
    or is counted once (ASTM: residue as half cycles; valley_to_peak has no
    residue). Indices in the result refer to the given values."""
    if method not in METHODS:
        raise InputError(f"cycle counting must be one of {METHODS}, got {method!r}")
    lo, hi, count = _cracklip.count_cycles(_history(values), method, repeated)
    return Cycles(np.asarray(lo, dtype=int), np.asarray(hi, dtype=int), np.asarray(count))


def rainflow(values) -> list[tuple[float, float]]:
    """ASTM E1049 rainflow of a history counted once: (range, count) per distinct range."""
    return count_cycles(values, "rainflow", repeated=False).table(values)


def rainflow_repeated(values) -> list[tuple[float, float]]:
    """Rainflow of a history repeated without end (residue closed): (range, count)."""
    return count_cycles(values, "rainflow", repeated=True).table(values)


__all__ = ["METHODS", "Cycles", "reversal_indices", "count_cycles", "rainflow", "rainflow_repeated"]
