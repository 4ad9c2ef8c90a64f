"""A load spectrum as the user describes it: turning points of the load
factors per load group, in blocks (flights), repeated (the [spectrum] table).

One pass of the spectrum is its blocks in order, each repeated ``repeat``
times; the life repeats passes until failure. A block's points are the
factors of the spectrum's load groups (one column per group) at its turning
points; every other load group of the scene stays at its ``steady`` factor
(default 1: residual stress, a pressure that does not cycle). Counting
(cracklip.fracture.rainflow): "rainflow" (ASTM E1049), "range_pair" or
"valley_to_peak"; residue "close" (the pass repeats: every cycle full, as
E1049's repeated-history rule) or "half" (each pass counted on its own,
left-over ranges as half cycles).
"""
from __future__ import annotations

import dataclasses
import math
import pathlib
import typing

import numpy as np

from ..errors import InputError, checked_keywords


COUNTING = ("rainflow", "range_pair", "valley_to_peak")
RESIDUE = ("close", "half")


@checked_keywords
@dataclasses.dataclass
class SpectrumBlock:
    """One block (flight) of turning points.

    Attributes:
        points: (n, groups) load factors at the turning points (a list of
            numbers for one group).
        repeat: times the block comes in a pass, one after the other.
        name: a label (e.g. the flight type).
        source: where the points come from (e.g. "file flight_A.csv"), for messages.
    """
    points: np.ndarray
    repeat: int = 1
    name: str = ""
    source: str = ""


@checked_keywords
@dataclasses.dataclass
class Spectrum:
    """A load spectrum (module doc).

    Attributes:
        blocks: the blocks of one pass, in order.
        groups: the load groups the columns of the points are.
        counting: "rainflow", "range_pair" or "valley_to_peak".
        residue: "close" (repeated history) or "half" (each pass alone).
        steady: factors of the scene's other load groups (unset ones: 1).
        block_name: what a block is called in outputs ("flight", "block").
        contact_levels: contact solves per growth step for the load states
            where the lips touch (one group: the lowest closed level and
            evenly spaced ones up to the closure level, K interpolated between
            them; several groups: the closed states nearest to these).
        max_passes: stop after this many passes (a bound on the life).
    """
    blocks: list[SpectrumBlock]
    groups: tuple[str, ...] = ("default",)
    counting: str = "rainflow"
    residue: str = "close"
    steady: dict[str, float] = dataclasses.field(default_factory=dict)
    block_name: str = "flight"
    contact_levels: int = 2
    max_passes: float = 1e9

    def __post_init__(self):
        self.groups = tuple(self.groups)
        if not self.groups or len(set(self.groups)) != len(self.groups):
            raise InputError(f"spectrum.groups must name distinct load groups, got {list(self.groups)}")
        if self.counting not in COUNTING:
            raise InputError(f"spectrum.counting must be one of {COUNTING}, got {self.counting!r}")
        if self.residue not in RESIDUE:
            raise InputError(f"spectrum.residue must be one of {RESIDUE}, got {self.residue!r}")
        if not self.blocks:
            raise InputError("spectrum.blocks is empty: give at least one block of turning points")
        G = len(self.groups)
        for i, b in enumerate(self.blocks):
            where = f"spectrum.blocks[{i}]"
            if not isinstance(b, SpectrumBlock):
                raise InputError(f"{where} must be a cl.SpectrumBlock(points=[...], repeat=n), got "
                                 f"{type(b).__name__}")
            try:
                pts = np.asarray(b.points, dtype=float)
            except (TypeError, ValueError):
                raise InputError(f"{where}.points must be load factors (numbers), got {b.points!r:.80}") from None
            if pts.ndim == 1 and G == 1:
                pts = pts[:, None]
            if pts.ndim != 2 or pts.shape[1] != G or pts.shape[0] < 1:
                raise InputError(f"{where}.points must be {'a list of numbers' if G == 1 else f'rows of {G} factors'}"
                                 f" (one per group of spectrum.groups {list(self.groups)}), got shape "
                                 f"{tuple(pts.shape)}")
            bad = np.argwhere(~np.isfinite(pts))
            if bad.size:
                raise InputError(f"{where}.points[{bad[0][0]}]: a factor is not a finite number ({pts[tuple(bad[0])]})")
            if isinstance(b.repeat, bool) or not isinstance(b.repeat, (int, np.integer)) or b.repeat < 1:
                raise InputError(f"{where}.repeat must be an integer >= 1, got {b.repeat!r}")
            b.points = pts
            b.name = b.name or f"{self.block_name} {i + 1}"
        for g, f in self.steady.items():
            if isinstance(f, bool) or not isinstance(f, (int, float)) or not math.isfinite(f):
                raise InputError(f"spectrum.steady.{g} must be a finite number, got {f!r}")
            if g in self.groups:
                raise InputError(f"spectrum.steady.{g}: group {g!r} is a column of the spectrum; it cannot be steady too")
        if isinstance(self.contact_levels, bool) or not isinstance(self.contact_levels, int) or self.contact_levels < 1:
            raise InputError(f"spectrum.contact_levels must be an integer >= 1, got {self.contact_levels!r}")
        if not (self.max_passes > 0):
            raise InputError(f"spectrum.max_passes must be positive, got {self.max_passes!r}")
        pts, _ = self.pass_points()
        spread = np.ptp(pts, axis=0)
        if not np.any(spread > 0.0):
            where = "; ".join(f"spectrum.blocks[{i}]" + (f" ({b.source})" if b.source else "")
                              + f": {len(b.points)} point(s)" for i, b in enumerate(self.blocks))
            raise InputError(f"the spectrum has no reversal: every turning point has the same factors "
                             f"{[float(f) for f in pts[0]]} ({where}); a fatigue cycle needs at least two "
                             "different load levels")

    @property
    def blocks_per_pass(self) -> int:
        return int(sum(b.repeat for b in self.blocks))

    def pass_points(self) -> tuple[np.ndarray, np.ndarray]:
        """The turning points of one pass, (n, groups), and the block (0 ..
        blocks_per_pass - 1) each point belongs to."""
        rows, owner = [], []
        k = 0
        for b in self.blocks:
            for _ in range(b.repeat):
                rows.append(b.points)
                owner.append(np.full(len(b.points), k))
                k += 1
        return np.vstack(rows), np.concatenate(owner)


def read_spectrum_csv(path: str | pathlib.Path, where: str = "spectrum",
                      groups: typing.Sequence[str] = ("default",)) -> tuple[list[str], np.ndarray]:
    """The turning points of a block file for the spectrum's load groups:
    (groups, points (n, groups)). The file is a plain list of values (one
    group), named columns (a header with the group of each column; comment
    lines start with #) or a block-load table (header max, min, cycles);
    cracklip.scene.input_files has the layouts and checks them line by line."""
    from .input_files import read_turning_points
    return list(groups), read_turning_points(path, where, tuple(groups))


__all__ = ["COUNTING", "RESIDUE", "SpectrumBlock", "Spectrum", "read_spectrum_csv"]
