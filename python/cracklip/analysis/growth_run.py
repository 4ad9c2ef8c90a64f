"""The growth loop's state and its named steps, shared by 2D and 3D
(GrowthRun), and what a run returns (GrowthResult). The geometry's own
steps are in the subclasses: analysis.growth.CurveGrowth (2D tips) and
analysis.front_growth.SurfaceGrowth (3D fronts); analysis.growth.grow
picks one by the part's dimension."""
from __future__ import annotations

import dataclasses
import logging
import math
import time
import typing

import numpy as np

from ..errors import BoundaryConditionError, CracklipError, InputError
from ..fracture.laws import rate_table_reach
from ..model.checks import CODE_MEANINGS, CodedText
from ..scene.growth import Growth
from ..scene.processes import mark_collective
from ..scene.scene import Scene
from .life import PAST_FAILURE, PAST_MAX_LENGTH, rate_table_messages
from .tips import Measured, TipRecord

logger = logging.getLogger("cracklip.analysis.growth")


def increment_cycles(da: float, rate0: float, rate1: float, m: float) -> float:
    """The cycles of an increment da between rates rate0 and rate1 of the law
    da/dN = C D^m (D: Delta K, or Walker's Delta K / (1 - R)^(1 - gamma)),
    with D linear along the increment: da / rate0 (1 - q^(1 - m)) / ((m - 1)
    (q - 1)), q = (rate1 / rate0)^(1 / m) (m = 1: ln q / (q - 1)).

    The trapezoidal rule of 1/rate it replaces is biased high, by about
    m (m + 2) (da / a)^2 / 48 on a crack whose K grows as sqrt(a): a centre
    crack grown by 0.3 a per step got a life 1.3-1.7 % too long against the
    integral of its own K (non-conservative); K linear along the step leaves
    only K's curvature (-0.4 .. -0.1 % there). A rate of 0 at an end (below a
    threshold) keeps the trapezoid's infinite / finite reading."""
    if not (rate0 > 0.0 and rate1 > 0.0 and m > 0.0) or not math.isfinite(rate0 + rate1):
        return da * 0.5 * (1.0 / rate0 + 1.0 / rate1)
    q = (rate1 / rate0) ** (1.0 / m)
    if abs(q - 1.0) < 1e-9:
        return da * 0.5 * (1.0 / rate0 + 1.0 / rate1)
    if abs(m - 1.0) < 1e-12:
        return da / rate0 * math.log(q) / (q - 1.0)
    return da / rate0 * (1.0 - q ** (1.0 - m)) / ((m - 1.0) * (q - 1.0))


@dataclasses.dataclass(repr=False)
class GrowthResult:
    """What grow returns: the tip records of every step (records[k] at step
    k, the last one at the final geometry), the final cracks, why it stopped,
    the warnings met, each step's Solution if kept, seconds per step, the
    cycles, the solves per step (load levels solved, with the corrector's),
    the model warning codes of each step, the criterion of the stop, in
    a spectrum life its summary (analysis.life.LifeRun.summary), and the
    beta table's rows (grow(beta_table=True); analysis.life.beta_rows);
    3D: fronts, what the fronts did (front_growth.SurfaceGrowth.result:
    per step the crack surfaces and each crack's shape, the growth
    spacing, margin, front element size)."""
    records: list[list[TipRecord]]
    cracks: list  # the final cracks: scene.crack.Crack (2D), scene.crack_surface.SurfaceCrack (3D)
    stop_reason: str
    stops: list[str]
    warnings: list[str]
    solutions: list
    step_times: list[float]
    cycles: float = 0.0
    step_solves: list[int] = dataclasses.field(default_factory=list)
    step_warnings: list[list[str]] = dataclasses.field(default_factory=list)
    stop_criterion: str | None = None
    life: dict[str, typing.Any] | None = None
    beta: list[dict[str, typing.Any]] = dataclasses.field(default_factory=list)
    fronts: dict[str, typing.Any] | None = None
    #: results.json's warnings: the first of each code as an object (the
    #: run's keys code, message, crack, tip, with the step it came at and
    #: its count over the run); `warnings` are the lines printed.
    warning_rows: list[dict[str, typing.Any]] = dataclasses.field(default_factory=list)

    @property
    def rows(self) -> list[dict[str, typing.Any]]:
        """One dict per tip and step (path.csv's rows)."""
        return [r.row() for step in self.records for r in step]

    def __repr__(self) -> str:
        """What the growth did, on one line (the dataclass's repr printed every tip record)."""
        parts = [f"{max(len(self.records) - 1, 0)} steps", f"{len(self.cracks)} cracks",
                 f"stopped: {self.stop_reason!r}"]
        if self.cycles:
            parts.append(f"{self.cycles:.6g} cycles")
        if self.life is not None:
            failure = self.life.get("failure")
            parts.append(f"life {self.life.get('blocks', 0):.6g} {self.life.get('block_name', 'block')}s, failure "
                         + (f"by {failure['criterion']} at a = {failure['a']:.6g}" if failure else "not reached"))
        parts.append(f"{len(self.warnings)} warnings")
        return (f"GrowthResult({'; '.join(parts)}; per step and tip: .records, .rows"
                f"{', .life' if self.life is not None else ''}{', .beta' if self.beta else ''})")


class GrowthRun:
    """The growth loop's state and its named steps, shared by 2D and 3D:
    measure the geometry (solve, K per tip or front point), correct the
    increment just taken (optional, 2D), collect the model's warnings,
    count the cycles of the increment (fatigue), record the beta table,
    check the stops, advance the cracks. run() repeats them until a stop.

    What differs with the geometry (a polyline's tips against a surface's
    front) lives in the subclasses: CurveGrowth here (2D) and
    front_growth.SurfaceGrowth (3D) give measure, advance and record_beta
    (and 2D the corrector)."""

    def __init__(self, scene: Scene, growth: Growth, keep_solutions: bool,
                 on_step: typing.Callable[[int, list[TipRecord], typing.Any], None] | None, beta_table: bool = False):
        scene.mesh.cache_standard_block = True
        self.scene = scene
        self.growth = growth
        self.keep_solutions = keep_solutions
        self.on_step = on_step
        self.cracks = self.initial_cracks(scene)
        if not self.cracks:
            raise InputError("growth needs at least one crack")
        self.records: list[list[TipRecord]] = []
        self.stops: list[str] = []
        self.warnings: list[tuple[CodedText, int | None]] = []  # each with its step (None: of the whole run)
        self.solutions: list = []
        self.step_times: list[float] = []
        self.solves: list[int] = []
        self.stopped: set[tuple[int, int]] = set()      # (crack, end) that no longer grow
        self.grown: set[tuple[int, int]] = set()        # (crack, end) advanced by the last step
        self.warned: set[str] = set()                   # increment warnings given (once each)
        self.warning_counts: dict[str, int] = {}        # model warnings by code, over all steps
        self.step_warnings: list[list[str]] = []
        self.last_kink: dict[tuple[int, int], float] = {}
        self.N = 0.0
        self.prev_rate: float | None = None             # constant amplitude: the trapezoid's last rate
        self.prev_da = 0.0
        self.prev_lengths: list[float] | None = None    # the cracks' sizes at the last geometry (growth.max_length)
        self.stop_fraction: float | None = None         # where growth.max_length (or 2D growth.K_Ic) was reached
        self.stop_cause: str | None = None              # which of the two: "max_length" or "K_Ic"
        self.stop_sizes: list[float] | None = None      # the cracks' sizes where spectrum.max_passes was reached
        self.da = growth.da
        self.fatigue = growth.fatigue
        self.stop_reason = f"{growth.steps} steps done"
        self.stop_criterion: str | None = None
        self.k = 0
        self.t0 = 0.0
        self.beta_table = beta_table
        self.beta: list[dict[str, typing.Any]] = []
        self.pending: tuple[str, str] | None = None     # a stop found by advance: (reason, criterion)
        self.life = self.create_life()

    # -- what the geometry gives (subclasses) ---------------------------------------------------------------
    def initial_cracks(self, scene: Scene) -> list:
        """The cracks the run grows (copies of the scene's)."""
        raise NotImplementedError

    def create_life(self):
        """The fatigue life of the run (analysis.life.LifeRun), or None."""
        return None

    def measure(self) -> Measured:
        """Solve the current geometry and record every tip or front point."""
        raise NotImplementedError

    def correct(self, m: Measured) -> tuple[Measured, int]:
        """The corrector on the increment just taken: the measurement of the
        geometry kept and the extra solves (none by default)."""
        return m, 0

    def record_beta(self, m: Measured) -> int:
        """The beta table's rows of this geometry; returns the extra solves."""
        return 0

    def advance(self, m: Measured) -> None:
        """Advance the growing cracks by the step's increments."""
        raise NotImplementedError

    # -- the shared steps ---------------------------------------------------------------------------------
    def collect_warnings(self, m: Measured) -> None:
        """The model's warnings of every step (a kinked path can clip a SIF
        domain): the first of each code in full, the later ones counted."""
        self.step_warnings.append(sorted({w.code for w in m.sol.warnings}))
        for w in m.sol.warnings:
            if w.code not in self.warning_counts:
                self.warn(w.code, w.message, w.crack, w.tip)
            self.warning_counts[w.code] = self.warning_counts.get(w.code, 0) + 1

    def warn(self, code: str, message: str, crack: int | None = None, tip: int | None = None,
             of_step: bool = True) -> None:
        """A warning of this step: a model's (collect_warnings) or the
        growth's own (growth_increment, growth_strip, growth_resolution,
        rate_table; docs/sifs.md), prefixed with the step after the first
        (of_step False: of the whole run, no step)."""
        prefix = f"step {self.k}: " if of_step and self.k else ""
        self.warnings.append((CodedText(prefix + message, code, crack, tip), self.k if of_step else None))

    def check_rate_table(self) -> None:
        """A tabular da/dN read outside its data by the largest counted
        cycle of any tip at any step (a spectrum life; fracture.laws.
        rate_table_reach): a warning of the run (rate_table)."""
        if self.life is None or self.life.law.law.name != "tabular":
            return
        cycles = [(r.delta_K_eff, r.R) for step in self.records for r in step
                  if r.delta_K_eff is not None and r.R is not None]
        if not cycles:
            return
        dk, R = np.array(cycles).T
        reach = rate_table_reach(self.life.law.law.table, dk, R)
        for text in rate_table_messages(reach, self.life.material, self.scene.units, "the tips' largest cycles"):
            self.warn("rate_table", text, of_step=False)

    def count_cycles(self, m: Measured) -> None:
        """The cycles of the increment just taken: constant amplitude with
        Delta K linear along it (increment_cycles); a spectrum pass by pass
        with K interpolated between its ends (cracklip.analysis.life). Where
        a crack passes growth.max_length inside the increment, only up to
        there (the size taken linear over the increment): the life to that
        size, not to the geometry beyond it (which check_stops then stops
        at); likewise at constant amplitude where K_eq reaches growth.K_Ic
        (K_eq linear over the increment)."""
        t = self.max_length_fraction(m)
        self.stop_cause = None if t is None else "max_length"
        t_kc = self.toughness_fraction(m) if self.life is None and self.fatigue else None  # (a life to stop)
        if t_kc is not None and (t is None or t_kc < t):
            t, self.stop_cause = t_kc, "K_Ic"
        self.stop_fraction = t
        prev, self.prev_lengths = self.prev_lengths, list(m.lengths)
        if self.life is not None:
            self.N = self.life.count(m, self.k, t)
            f = self.life.passes_fraction  # spectrum.max_passes reached inside the increment: the sizes there
            self.stop_sizes = None if f is None or prev is None else [p + f * (n - p) for p, n in zip(prev, m.lengths)]
            return
        if self.fatigue and self.k > 0 and self.prev_rate is not None:
            rate_now = max(m.rates.values()) if m.rates else self.prev_rate
            m_ = float(self.growth.paris_m)
            f = 1.0 if t is None else t
            rate_f = rate_now
            if f < 1.0:  # (Delta K linear along the increment, as increment_cycles: the rate at its fraction f)
                if self.prev_rate > 0.0 and rate_now > 0.0:
                    rate_f = self.prev_rate * (1.0 + ((rate_now / self.prev_rate) ** (1.0 / m_) - 1.0) * f) ** m_
                else:
                    rate_f = self.prev_rate + f * (rate_now - self.prev_rate)
            dN = increment_cycles(f * self.prev_da, self.prev_rate, rate_f, m_)
            self.N += dN
            for rec in m.records:  # the cycles spent to reach this geometry
                rec.dN, rec.N = dN, self.N
                if t is not None and t < 1.0:
                    rec.status = PAST_FAILURE if self.stop_cause == "K_Ic" else PAST_MAX_LENGTH

    def max_length_fraction(self, m: Measured) -> float | None:
        """The fraction of the increment just taken at which a crack's size
        reached growth.max_length (linear between the two geometries' sizes),
        or None (not reached in it, or the first geometry)."""
        L = self.growth.max_length
        if L is None or self.k == 0 or self.prev_lengths is None:
            return None
        lim = L * (1.0 - 1e-9)
        fr = [(L - p) / (n - p) for p, n in zip(self.prev_lengths, m.lengths) if p < lim <= n]
        return min(1.0, max(0.0, min(fr))) if fr else None

    def toughness_fraction(self, m: Measured) -> float | None:
        """The fraction of the increment just taken at which a tip's K_eq
        reached growth.K_Ic (K_eq linear between the two geometries, as
        increment_cycles takes Delta K), or None (not reached in it, or the
        first geometry)."""
        K_c = self.growth.K_Ic
        if K_c is None or self.k == 0 or not self.records:
            return None
        before = {(r.crack, r.end): r.K_eq for r in self.records[-1]}
        fr = [(K_c - before[r.crack, r.end]) / (r.K_eq - before[r.crack, r.end]) for r in m.records
              if (r.crack, r.end) in before and before[r.crack, r.end] < K_c <= r.K_eq]
        return min(1.0, max(0.0, min(fr))) if fr else None

    def _stop(self, reason: str, criterion: str | None = None) -> bool:
        self.stop_reason = reason
        self.stop_criterion = criterion
        self.stops.append(reason)
        self.step_times.append(time.perf_counter() - self.t0)
        return True

    def check_stops(self, m: Measured) -> bool:
        """The stops that end the run (module doc); True to stop."""
        growth, k, step = self.growth, self.k, m.records
        if self.life is not None and self.life.failure is not None:
            return self._stop(self.life.failure, self.life.failure_criterion)
        if self.life is not None and self.life.passes_exceeded():
            lf, t = self.life, self.life.passes_fraction
            if t is None:
                return self._stop(f"the life passed spectrum.max_passes = {lf.max_passes:g} passes (step {k})",
                                  "spectrum.max_passes")
            sizes = ", ".join(f"{v:.6g}" for v in self.stop_sizes or [])
            return self._stop(f"the life reached spectrum.max_passes = {lf.max_passes:g} passes inside the increment "
                              f"to step {k} ({t:.3g} of it): {self.N:.6g} cycles = "
                              f"{lf.passes * lf.blocks_per_pass:.6g} {lf.spectrum.block_name}s; the {self.SIZE_NAME} "
                              f"there {sizes} (linear over the increment); step {k}'s geometry lies beyond it",
                              "spectrum.max_passes")
        t, cause = self.stop_fraction, self.stop_cause
        if growth.K_Ic is not None and cause != "max_length":
            failing = [r for r in step if r.K_eq >= growth.K_Ic]
            if failing:
                r = failing[0]
                where = f"{self.where(r)} of crack {self.cracks[r.crack].name!r}"
                if cause == "K_Ic" and t < 1.0:
                    return self._stop(f"final failure: K_eq reaches K_Ic = {growth.K_Ic:g} at {where} inside the "
                                      f"increment to step {k} ({t:.3g} of it, K_eq linear over it): the life to it "
                                      f"{self.N:.6g} cycles; step {k}'s geometry lies beyond it (K_eq = "
                                      f"{r.K_eq:.6g} there)", "K_eq >= growth.K_Ic")
                return self._stop(f"final failure: K_eq = {r.K_eq:.6g} >= K_Ic = {growth.K_Ic:g} at {where} "
                                  f"(step {k})", "K_eq >= growth.K_Ic")
        if growth.max_length is not None and k == 0 and any(v >= growth.max_length * (1.0 - 1e-9)
                                                            for v in m.lengths):
            return self._stop(f"the {self.SIZE_NAME} at the start, {max(m.lengths):.6g}, is already at or beyond "
                              f"growth.max_length = {growth.max_length:g}: nothing to grow (step 0)",
                              "growth.max_length")
        if growth.max_length is not None and any(v >= growth.max_length * (1.0 - 1e-9) for v in m.lengths):
            blocks = (f" = {self.life.passes * self.life.blocks_per_pass:.6g} {self.life.spectrum.block_name}s"
                      if self.life is not None and self.life.spectrum.block_name != "cycle" else "")
            inside = (f" inside the increment to step {k} ({t:.3g} of it, the size linear over it): the life to it "
                      f"{self.N:.6g} cycles{blocks}; step {k}'s geometry lies beyond it (largest size "
                      f"{max(m.lengths):.6g})" if t is not None and t < 1.0 else f" (step {k})")
            return self._stop(f"a crack reached the {self.SIZE_NAME} {growth.max_length:g}" + inside,
                              "growth.max_length")
        if k == growth.steps:
            self.step_times.append(time.perf_counter() - self.t0)
            self.stop_criterion = "growth.steps"
            return True
        growing = [r for r in step if r.status == "growing"]
        if not step:
            return self._stop(f"no crack tip is left in the part (step {k}): the cracks run through it",
                              "no tip in the part")
        if not growing:
            return self._stop(f"no tip grows any more (step {k}: " + "; ".join(
                f"crack {self.cracks[r.crack].name!r} {self.END} {r.end}: {r.status}" for r in step) + ")",
                "no growing tip")
        unstable = [r for r in growing if (r.crack, r.end) in self.last_kink
                    and abs(r.kink_deg - self.last_kink[r.crack, r.end]) > growth.max_kink_change]
        if unstable:
            r = unstable[0]
            return self._stop(f"unstable growth: the kink at {self.where(r, 'at')} turned from "
                              f"{self.last_kink[r.crack, r.end]:.2f} to {r.kink_deg:.2f} degrees between steps "
                              f"(more than growth.max_kink_change = {growth.max_kink_change:g})",
                              "growth.max_kink_change")
        return self.check_geometry_stops(m)

    def check_geometry_stops(self, m: Measured) -> bool:
        """Stops of the geometry (3D: breakthrough); True to stop."""
        return False

    #: What a crack's size is called in messages (growth.max_length).
    SIZE_NAME = "length"
    #: What a record's `end` is called in messages.
    END = "end"

    def where(self, r: TipRecord, how: str = "tip") -> str:
        """A record's point for messages."""
        if how == "at":
            return f"({r.x:.6g}, {r.y:.6g})"
        return f"the tip ({r.x:.6g}, {r.y:.6g})"

    def describe_step(self, records: list[TipRecord]) -> str:
        return "; ".join(
            f"crack {self.cracks[r.crack].name!r} end {r.end}: a = {r.length:.4g}, K_I = {r.K_I:.4g}, "
            f"K_II = {r.K_II:.4g}, kink {r.kink_deg:.1f} deg" + (f", N = {r.N:.4g}" if self.fatigue else "")
            for r in records)

    def final_stop(self, k: int, error: BoundaryConditionError) -> bool:
        """A solve that failed after some growth: True when it ends the run
        (the cracks cut the part apart), False to raise the error."""
        if k == 0 or "cut the part into" not in str(error):
            return False
        self.stop_reason = f"final separation: after step {k - 1} the cracks cut the part apart ({error})"
        self.stop_criterion = "final separation"
        self.stops.append(self.stop_reason)
        return True

    # -- the loop ---------------------------------------------------------------------------------------
    def run(self) -> GrowthResult:
        for k in range(self.growth.steps + 1):
            self.k = k
            self.t0 = time.perf_counter()
            try:
                m = self.measure()
            except BoundaryConditionError as e:
                if not self.final_stop(k, e):
                    raise
                break
            m, extra = self.correct(m)
            extra += self.record_beta(m)
            self.solves.append(m.solves + extra)
            self.collect_warnings(m)
            self.count_cycles(m)
            self.records.append(m.records)
            if self.on_step is not None:
                self.on_step(k, m.records, m.sol)
            if self.keep_solutions:
                self.solutions.append(m.sol)
            if self.check_stops(m):
                break
            try:
                self.advance(m)
            except CracklipError as e:  # (from the geometry every process holds alike: raised on every one)
                raise mark_collective(e)
            if self.pending is not None:  # a stop the advance found (3D: breakthrough)
                self._stop(*self.pending)
                break
            self.step_times.append(time.perf_counter() - self.t0)
            logger.debug("growth step %d: %s", k, self.describe_step(m.records))
        return self.result()

    def result(self) -> GrowthResult:
        self.check_rate_table()
        warnings = [w for w, _ in self.warnings] + [
            f"the model warning '{c}'" + (f" ({CODE_MEANINGS[c]})" if c in CODE_MEANINGS else "")
            + f" came {n} times in all (at the steps listed in results.json per_step)"
            for c, n in self.warning_counts.items() if n > 1]
        rows = [{"code": w.code, "message": str(w), "crack": w.crack, "tip": w.tip, "step": k,
                 "count": self.warning_counts.get(w.code, 1)} for w, k in self.warnings]
        return GrowthResult(self.records, self.cracks, self.stop_reason, self.stops, list(dict.fromkeys(warnings)),
                            self.solutions, self.step_times, self.N, self.solves, self.step_warnings,
                            stop_criterion=self.stop_criterion,
                            life=self.life.summary(self.records) if self.life is not None else None, beta=self.beta,
                            warning_rows=rows)


__all__ = ["GrowthResult", "GrowthRun"]
