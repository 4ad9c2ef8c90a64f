"""Crack growth through the fixed mesh, and fatigue life.

The growth loop: solve the scene (with contact and friction if it has them)
-> K_I, K_II at every tip (three domains, their spread) -> the kink angle by
the maximum hoop stress criterion (or maximum energy release rate) -> extend
each growing tip's polyline by its increment -> rebuild the level sets,
enrichment and multipliers on the same mesh -> repeat. The standard
stiffness block is assembled once (MeshData's cache) and reused; per step
the enriched work stays proportional to the cracks.

Increments: a fixed da for every growing tip, or fatigue: the load cycle
between a maximum and a minimum load (Growth.cycle_max / cycle_min: factors
per load group) is solved at both ends with contact (closure: where the lips
touch at the minimum, K_min is what contact gives, not the linear value),
Delta K_eff = K_eq(max) - K_eq(min) along the kink direction, the Paris law
da/dN = C (Delta K_eff)^m (Walker's R-ratio form with gamma != 1, none below
the threshold), the fastest tip advancing da and the others da (rate_i /
rate_max), the cycles integrated by the trapezoidal rule between steps.

Conventions (docs/sifs.md, "Conventions"): angles in the tip frame (e1 out of the
crack, e2 = e1 turned by +90 degrees), positive toward e2: K_II > 0 kinks
the crack toward -e2 (pure mode II: -70.53 degrees). A closed crack (K_I <=
0 with contact) grows by its K_II like any other.

Stops, each reported: a tip reaching the boundary (or a hole: the crack
becomes an edge or a through crack, its end on the boundary), a tip
reaching another crack (it stops there), K_eq above K_Ic (final failure),
a kink that turns by more than max_kink_change between steps (instability),
the step count, a crack length, and in fatigue a tip below the threshold.
"""
from __future__ import annotations

import dataclasses
import logging
import math
import time
import typing

import numpy as np

from ..errors import BoundaryConditionError, InputError
from ..fracture.kink import equivalent_k, kink_angle
from ..scene.conditions import LoadStep
from ..scene.crack import Crack
from ..scene.growth import Growth
from ..scene.scene import Scene


logger = logging.getLogger(__name__)


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

    def row(self) -> dict[str, typing.Any]:
        return dataclasses.asdict(self)


@dataclasses.dataclass
class GrowthResult:
    """What grow returns: the tip records of every step (records[k] at step
    k, the last one at the final geometry), the final cracks, why it stopped,
    the warnings met, each step's Solution if kept, seconds per step, the
    cycles, the solves per step (1 + the corrector's), the model warning
    codes of each step."""
    records: list[list[TipRecord]]
    cracks: list[Crack]
    stop_reason: str
    stops: list[str]
    warnings: list[str]
    solutions: list
    step_times: list[float]
    cycles: float = 0.0
    step_solves: list[int] = dataclasses.field(default_factory=list)
    step_warnings: list[list[str]] = dataclasses.field(default_factory=list)

    @property
    def rows(self) -> list[dict[str, typing.Any]]:
        return [r.row() for step in self.records for r in step]


def _segment_hit(p: np.ndarray, q: np.ndarray, a: np.ndarray, b: np.ndarray) -> float | None:
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


def _distance_to_segments(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    d = b - a
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / dd, 0.0, 1.0)
    return float(np.linalg.norm(a + t[:, None] * d - p, axis=1).min()) if len(a) else math.inf


def crack_length(points: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())


def part_length(model, crack: int) -> float:
    """The length of a crack inside the part (its polyline may run beyond the boundary)."""
    from ..model.tip_regions import lip_points
    return float(lip_points(model, crack)["weight"].sum())


def _cycle_scene(scene: Scene, growth: Growth) -> tuple[Scene, bool]:
    """The scene solved at each step: its own loads, or (fatigue) the load
    cycle as a two-step path [max, min]."""
    if not growth.fatigue:
        return scene, False
    from ..scene.scene import load_groups
    groups = sorted(load_groups(scene) | {"default"})
    high = dict(growth.cycle_max) if growth.cycle_max is not None else {g: 1.0 for g in groups}
    low = dict(growth.cycle_min) if growth.cycle_min is not None else {g: growth.R * f for g, f in high.items()}
    low = {g: low.get(g, 0.0) for g in set(high) | set(low)}
    path = [LoadStep(high, "maximum load"), LoadStep(low, "minimum load")]
    return dataclasses.replace(scene, load_path=path), True


@dataclasses.dataclass
class _Measured:
    """One solve of a geometry: the tip records, the fatigue rates, the
    solution at the maximum load and its model."""
    records: list[TipRecord]
    rates: dict[tuple[int, int], float]
    lengths: list[float]
    sol: typing.Any
    model: typing.Any


def _measure(scene: Scene, cracks: list[Crack], growth: Growth, k: int, N: float,
             stopped: set[tuple[int, int]]) -> _Measured:
    """Solve the scene with the given cracks (the load cycle in fatigue) and
    record every tip: K, kink, K_eq, closed fraction, Delta K and the Paris
    rate (growing tips only)."""
    from .solve import solve
    current = dataclasses.replace(scene, cracks=[dataclasses.replace(c) for c in cracks])
    solved_scene, fatigue = _cycle_scene(current, growth)
    sol = solve(solved_scene)
    sol_max, sol_min = (sol.steps[0], sol.steps[1]) if fatigue else (sol, None)
    model = sol_max.model
    sifs_max = sol_max.stress_intensity_factors(None)
    sifs_min = {(r["crack"], r["tip"]): r for r in sol_min.stress_intensity_factors(None)} if fatigue else {}
    step: list[TipRecord] = []
    rates: dict[tuple[int, int], float] = {}
    lengths = [part_length(model, ci) for ci in range(len(cracks))]
    closed = [_closed_fraction(sol_max, ci) for ci in range(len(cracks))]
    for r in sifs_max:
        ci = r["crack"]
        g = model.geometries[ci]
        end = 1 if int(np.asarray(g.tip_orientation)[r["tip"]]) == 1 else 0
        key = (ci, end)
        theta = kink_angle(r["K_I"], r["K_II"], growth.criterion)
        keq = equivalent_k(r["K_I"], r["K_II"], theta)
        rec = TipRecord(k, ci, end, r["x"], r["y"], lengths[ci], r["K_I"], r["K_II"],
                        r["K_I_spread"], r["K_II_spread"], math.degrees(theta), keq, closed[ci], N=N,
                        sif_radius=float(r["radius"]))
        if key in stopped:
            rec.status = "stopped"
        if fatigue:
            rm = sifs_min[(ci, r["tip"])]
            rec.K_I_min, rec.K_II_min = rm["K_I"], rm["K_II"]
            # The linear K_eq at both ends: with contact K_min is what the closed lips give
            # (about 0), without it the value of lips passing through each other.
            keq_max = equivalent_k(r["K_I"], r["K_II"], theta, clamp=False)
            keq_min = equivalent_k(rm["K_I"], rm["K_II"], theta, clamp=False)
            rec.delta_K = max(keq_max - keq_min, 0.0)
            ratio = keq_min / keq_max if keq_max > 0 else 0.0
            dk = rec.delta_K / (1.0 - ratio) ** (1.0 - growth.walker_gamma) if ratio < 1 else rec.delta_K
            if rec.status == "growing":
                if rec.delta_K <= growth.threshold:
                    rec.status = "below threshold"
                else:
                    rates[key] = growth.paris_C * dk ** growth.paris_m
        elif rec.status == "growing" and keq < growth.threshold:
            rec.status = "below threshold"
        step.append(rec)
    return _Measured(step, rates, lengths, sol_max, model)


def _rotate_last_segment(crack: Crack, end: int, delta: float) -> None:
    """Turn the segment at the given end of a polyline about its inner point by delta (radians)."""
    pts = crack.points.copy()
    i, j = (-1, -2) if end == 1 else (0, 1)
    v = pts[i] - pts[j]
    c, s = math.cos(delta), math.sin(delta)
    pts[i] = pts[j] + np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])
    crack.points = pts


def _correct(scene: Scene, cracks: list[Crack], growth: Growth, k: int, N: float, stopped, grown,
             measured: _Measured) -> tuple[_Measured, dict[tuple[int, int], float], int]:
    """The corrector: turn each tip's last increment about its start until
    the kink wanted at its end vanishes (local symmetry at the end of the
    increment, K_II = 0 there, not only at its start): secant iterations on
    the turn, at most growth.corrections solves, stopping when every kink is
    below growth.corrector_tolerance degrees. Returns the measurement of the
    best geometry met (least sum of |kink|), the turn it gives each tip
    (radians) and the number of solves."""
    tol = math.radians(growth.corrector_tolerance)
    turn: dict[tuple[int, int], float] = {}
    hist: dict[tuple[int, int], list[tuple[float, float]]] = {}
    best = measured
    best_err = {(r.crack, r.end): abs(math.radians(r.kink_deg)) for r in measured.records}
    best_turn: dict[tuple[int, int], float] = {}
    cur = measured
    solves = 0
    for _ in range(growth.corrections):
        todo = {(r.crack, r.end): math.radians(r.kink_deg) for r in cur.records
                if (r.crack, r.end) in grown and r.status == "growing" and abs(math.radians(r.kink_deg)) > tol}
        if not todo:
            break
        for key, th in todo.items():
            d0 = turn.get(key, 0.0)
            h = hist.setdefault(key, [])
            h.append((d0, th))
            if len(h) >= 2 and abs(h[-1][1] - h[-2][1]) > 1e-9:
                (da_, ta), (db, tb) = h[-2], h[-1]
                d1 = db - tb * (db - da_) / (tb - ta)
            else:
                d1 = d0 + 0.5 * th  # the first trial: half the kink wanted (a full one overshoots when T < 0)
            d1 = max(-math.radians(60.0), min(math.radians(60.0), d1))
            _rotate_last_segment(cracks[key[0]], key[1], d1 - d0)
            turn[key] = d1
        cur = _measure(scene, cracks, growth, k, N, stopped)
        solves += 1
        errs = {(r.crack, r.end): abs(math.radians(r.kink_deg)) for r in cur.records}
        if sum(errs.get(key, 0.0) for key in grown) < sum(best_err.get(key, 0.0) for key in grown):
            best, best_err, best_turn = cur, errs, dict(turn)
    # Back to the geometry of the best measurement met.
    for key in turn:
        _rotate_last_segment(cracks[key[0]], key[1], best_turn.get(key, 0.0) - turn[key])
    return best, best_turn, solves


def grow(scene: Scene, growth: Growth, keep_solutions: bool = False,
         on_step: typing.Callable[[int, list[TipRecord], typing.Any], None] | None = None) -> GrowthResult:
    """Grow the scene's cracks (module doc). on_step(k, records, solution) is
    called after every step's solve (progress, a ParaView file per step; in
    fatigue the solution at the maximum load); keep_solutions keeps each
    step's Solution in the result."""
    from ..model.boundary import boundary_segments
    from ..model.tip_regions import tip_element_size
    scene.mesh.cache_standard_block = True
    cracks = [dataclasses.replace(c, points=np.array(c.points, dtype=float)) for c in scene.cracks]
    if not cracks:
        raise InputError("growth needs at least one crack")
    a_bnd, b_bnd = boundary_segments(scene.mesh)
    records: list[list[TipRecord]] = []
    stops: list[str] = []
    warnings: list[str] = []
    solutions = []
    step_times: list[float] = []
    solves: list[int] = []
    stopped: set[tuple[int, int]] = set()      # (crack, end) that no longer grow
    grown: set[tuple[int, int]] = set()        # (crack, end) advanced by the last step
    warned: set[str] = set()                   # increment warnings given (once each)
    warning_counts: dict[str, int] = {}        # model warnings by code, over all steps
    step_warnings: list[list[str]] = []
    last_kink: dict[tuple[int, int], float] = {}
    N = 0.0
    prev_rate: float | None = None
    prev_da = 0.0
    da = growth.da
    fatigue = growth.fatigue
    stop_reason = f"{growth.steps} steps done"
    for k in range(growth.steps + 1):
        t0 = time.perf_counter()
        try:
            m = _measure(scene, cracks, growth, k, N, stopped)
        except BoundaryConditionError as e:
            if k == 0 or "cut the part into" not in str(e):
                raise
            stop_reason = f"final separation: after step {k - 1} the cracks cut the part apart ({e})"
            stops.append(stop_reason)
            break
        n_solves = 1
        if growth.corrections and k > 0 and grown:
            m, turns, extra = _correct(scene, cracks, growth, k, N, stopped, grown, m)
            n_solves += extra
            for r in records[-1]:  # the kink the last increment actually took
                if (r.crack, r.end) in turns:
                    r.kink_deg += math.degrees(turns[r.crack, r.end])
                    last_kink[r.crack, r.end] = r.kink_deg
        step, rates, lengths, sol_max, model = m.records, m.rates, m.lengths, m.sol, m.model
        solves.append(n_solves)
        # The model's warnings of every step (a kinked path can clip a SIF domain): the first of
        # each code in full, the later ones counted.
        step_warnings.append(sorted({w.code for w in sol_max.warnings}))
        for w in sol_max.warnings:
            if w.code not in warning_counts:
                warnings.append(w.message if k == 0 else f"step {k}: {w.message}")
            warning_counts[w.code] = warning_counts.get(w.code, 0) + 1
        # The cycles of the increment just taken (trapezoid between its two ends).
        if fatigue and k > 0 and prev_rate is not None:
            rate_now = max(rates.values()) if rates else prev_rate
            dN = prev_da * 0.5 * (1.0 / prev_rate + 1.0 / rate_now)
            N += dN
            for rec in step:  # the cycles spent to reach this geometry
                rec.dN, rec.N = dN, N
        records.append(step)
        if on_step is not None:
            on_step(k, step, sol_max)
        if keep_solutions:
            solutions.append(sol_max)
        # Stops that end the run.
        if growth.K_Ic is not None:
            failing = [r for r in step if r.K_eq >= growth.K_Ic]
            if failing:
                r = failing[0]
                stop_reason = (f"final failure: K_eq = {r.K_eq:.6g} >= K_Ic = {growth.K_Ic:g} at the tip "
                               f"({r.x:.6g}, {r.y:.6g}) of crack {cracks[r.crack].name!r} (step {k})")
                stops.append(stop_reason)
                step_times.append(time.perf_counter() - t0)
                break
        if growth.max_length is not None and any(v >= growth.max_length * (1.0 - 1e-9) for v in lengths):
            stop_reason = f"a crack reached the length {growth.max_length:g} (step {k})"
            stops.append(stop_reason)
            step_times.append(time.perf_counter() - t0)
            break
        if k == growth.steps:
            step_times.append(time.perf_counter() - t0)
            break
        growing = [r for r in step if r.status == "growing"]
        if not step:
            stop_reason = f"no crack tip is left in the part (step {k}): the cracks run through it"
            stops.append(stop_reason)
            step_times.append(time.perf_counter() - t0)
            break
        if not growing:
            stop_reason = f"no tip grows any more (step {k}: " + "; ".join(
                f"crack {cracks[r.crack].name!r} end {r.end}: {r.status}" for r in step) + ")"
            stops.append(stop_reason)
            step_times.append(time.perf_counter() - t0)
            break
        if da <= 0.0:
            r0 = growing[0]
            da = 3.0 * tip_element_size(model, np.array([r0.x, r0.y]))
            growth = dataclasses.replace(growth, da=da)
        unstable = [r for r in growing if (r.crack, r.end) in last_kink
                    and abs(r.kink_deg - last_kink[r.crack, r.end]) > growth.max_kink_change]
        if unstable:
            r = unstable[0]
            stop_reason = (f"unstable growth: the kink at ({r.x:.6g}, {r.y:.6g}) turned from "
                           f"{last_kink[r.crack, r.end]:.2f} to {r.kink_deg:.2f} degrees between steps "
                           f"(more than growth.max_kink_change = {growth.max_kink_change:g})")
            stops.append(stop_reason)
            step_times.append(time.perf_counter() - t0)
            break
        rate_max = max(rates.values()) if rates else None
        # Advance every growing tip.
        grown = set()
        for r in growing:
            key = (r.crack, r.end)
            if k > 0:  # the first kink leaves the initial crack, any angle: not a reference
                last_kink[key] = r.kink_deg
            inc = da if not fatigue else da * rates[key] / rate_max
            r.da = inc
            h_tip = tip_element_size(model, np.array([r.x, r.y]))
            if inc < h_tip and "small" not in warned:
                warned.add("small")
                warnings.append(f"step {k}: the increment {inc:.3g} at ({r.x:.6g}, {r.y:.6g}) is below the element "
                                f"size there ({h_tip:.3g}): the path follows the mesh; use a larger da or a finer mesh "
                                "(said once)")
            if inc > r.sif_radius and not growth.corrections and "large" not in warned:
                warned.add("large")  # (the corrector checks the kink at the increment's end)
                warnings.append(f"step {k}: the increment {inc:.3g} at ({r.x:.6g}, {r.y:.6g}) is larger than the SIF "
                                f"domain there (radius {r.sif_radius:.3g}): the kink comes from the field within "
                                "that radius and is extrapolated beyond it; use a smaller da or growth.corrections (said once)")
            note = _advance(cracks, r, inc, model, a_bnd, b_bnd, h_tip)
            if note:
                stops.append(f"step {k}: {note}")
                stopped.add(key)
                r.status = note.split(":")[0]
            else:
                grown.add(key)
        if fatigue:
            prev_rate, prev_da = rate_max, da
        step_times.append(time.perf_counter() - t0)
        logger.debug("growth step %d: %s", k, "; ".join(
            f"crack {cracks[r.crack].name!r} end {r.end}: a = {r.length:.4g}, K_I = {r.K_I:.4g}, K_II = {r.K_II:.4g}, "
            f"kink {r.kink_deg:.1f} deg" + (f", N = {r.N:.4g}" if fatigue else "") for r in step))
    warnings += [f"the model warning '{c}' came {n} times in all (at the steps listed in results.json per_step)"
                 for c, n in warning_counts.items() if n > 1]
    return GrowthResult(records, cracks, stop_reason, stops, list(dict.fromkeys(warnings)), solutions, step_times, N,
                        solves, step_warnings)


def _closed_fraction(sol, crack: int) -> float:
    if not sol.contact:
        return 0.0
    smp = sol.lip_samples(crack, 2)
    w = smp["weight"]
    closed = smp["state"] != "open"
    return float(w[closed].sum() / w.sum()) if w.sum() > 0 else 0.0


def _advance(cracks: list[Crack], r: TipRecord, inc: float, model, a_bnd, b_bnd, h_tip: float) -> str | None:
    """Extend the polyline of crack r.crack at end r.end by inc along the
    kink; returns a stop note when the tip reached the boundary (the end is
    put beyond it) or another crack (the tip stays)."""
    crack = cracks[r.crack]
    pts = crack.points
    tip = pts[-1] if r.end == 1 else pts[0]
    prev = pts[-2] if r.end == 1 else pts[1]
    e1 = (tip - prev) / np.linalg.norm(tip - prev)
    e2 = np.array([-e1[1], e1[0]])
    th = math.radians(r.kink_deg)
    d = math.cos(th) * e1 + math.sin(th) * e2
    new = tip + inc * d
    note = None
    # Another crack ahead: stop the tip short of it.
    for j, other in enumerate(cracks):
        if j == r.crack:
            continue
        o = other.points
        t = _segment_hit(tip, tip + (inc + 1.5 * h_tip) * d, o[:-1], o[1:])
        if t is not None or _distance_to_segments(new, o[:-1], o[1:]) < 1.5 * h_tip:
            return f"reached crack {other.name!r}: the tip at ({tip[0]:.6g}, {tip[1]:.6g}) stops"
    # The boundary (or a hole) ahead: the crack runs to it and beyond.
    t = _segment_hit(tip, tip + (inc + h_tip) * d, a_bnd, b_bnd)
    if t is not None:
        reach = t * (inc + h_tip)
        new = tip + (reach + 0.5 * h_tip) * d
        hit = tip + reach * d
        note = f"reached the boundary: at ({hit[0]:.6g}, {hit[1]:.6g})"
    crack.points = np.vstack([pts, new]) if r.end == 1 else np.vstack([new, pts])
    return note
