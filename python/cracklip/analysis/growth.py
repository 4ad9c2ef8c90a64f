"""Crack growth through the fixed mesh, and fatigue life: grow() and the
2D steps (CurveGrowth); the loop's state and named steps shared with 3D
are analysis.growth_run.GrowthRun, the 3D fronts' steps
analysis.front_growth.SurfaceGrowth (grow picks by the part's dimension).

The 2D growth loop: solve the scene (with contact and friction if it has them)
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
rate_max), the cycles of each step from the rates at its ends with Delta K
linear along it (growth_run.increment_cycles).

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
import typing

import numpy as np

from ..errors import InputError, checked_keywords
from ..fracture.kink import equivalent_k, kink_angle
from ..fracture.laws import walker_rate
from ..scene.conditions import LoadStep
from ..scene.crack import Crack
from ..scene.growth import Growth, load_cycle
from ..scene.scene import Scene, require_scene
from .growth_run import GrowthResult, GrowthRun  # noqa: F401 (GrowthResult: the result of grow)
from .tips import (Measured, TipRecord, closed_fraction, crack_length, distance_to_segments,  # noqa: F401
                   no_growth_status, part_length, segment_hit)  # noqa: F401


logger = logging.getLogger(__name__)


def _cycle_scene(scene: Scene, growth: Growth) -> tuple[Scene, bool]:
    """The scene solved at each step: its own loads, or (fatigue) the load
    cycle as a two-step path [max, min]."""
    if not growth.fatigue:
        return scene, False
    from ..scene.scene import load_groups
    groups = load_groups(scene) or {"default"}
    high, low, warning = load_cycle(growth, groups,
                                    scene.initial_stress_group if scene.initial_stress is not None else None)
    if warning is not None:
        logger.warning(warning)
    if growth.cycle_max is None and "default" not in high:  # (as before: every group and "default" at 1)
        high["default"] = 1.0
        if growth.cycle_min is None:
            low["default"] = growth.R
    low = {g: low.get(g, 0.0) for g in set(high) | set(low)}
    path = [LoadStep(high, "maximum load"), LoadStep(low, "minimum load")]
    return dataclasses.replace(scene, load_path=path), True


def _measure(scene: Scene, cracks: list[Crack], growth: Growth, k: int, N: float,
             stopped: set[tuple[int, int]]) -> Measured:
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
    closed = [closed_fraction(sol_max, ci) for ci in range(len(cracks))]
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
            if rec.status == "growing":
                if rec.delta_K <= growth.threshold:
                    rec.status = no_growth_status(max(r["K_I"], rm["K_I"]))
                else:  # Walker's form (gamma = 1: Paris), cracklip.fracture.laws
                    rates[key] = float(walker_rate(rec.delta_K, ratio, growth.paris_C, growth.paris_m,
                                                   growth.walker_gamma))
        elif rec.status == "growing" and keq < growth.threshold:
            rec.status = no_growth_status(r["K_I"])
        step.append(rec)
    return Measured(step, rates, lengths, sol_max, model)


def _rotate_last_segment(crack: Crack, end: int, delta: float) -> None:
    """Turn the segment at the given end of a polyline about its inner point by delta (radians)."""
    pts = crack.points.copy()
    i, j = (-1, -2) if end == 1 else (0, 1)
    v = pts[i] - pts[j]
    c, s = math.cos(delta), math.sin(delta)
    pts[i] = pts[j] + np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])
    crack.points = pts


def _correct(scene: Scene, cracks: list[Crack], growth: Growth, k: int, N: float, stopped, grown,
             measured: Measured, measure: typing.Callable[[], Measured] | None = None
             ) -> tuple[Measured, dict[tuple[int, int], float], int]:
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
        cur = measure() if measure is not None else _measure(scene, cracks, growth, k, N, stopped)
        solves += cur.solves
        errs = {(r.crack, r.end): abs(math.radians(r.kink_deg)) for r in cur.records}
        if sum(errs.get(key, 0.0) for key in grown) < sum(best_err.get(key, 0.0) for key in grown):
            best, best_err, best_turn = cur, errs, dict(turn)
    # Back to the geometry of the best measurement met.
    for key in turn:
        _rotate_last_segment(cracks[key[0]], key[1], best_turn.get(key, 0.0) - turn[key])
    return best, best_turn, solves


class CurveGrowth(GrowthRun):
    """2D: polylines grown at their tips (module doc)."""

    def __init__(self, scene: Scene, growth: Growth, keep_solutions: bool,
                 on_step: typing.Callable[[int, list[TipRecord], typing.Any], None] | None, beta_table: bool = False):
        from ..model.boundary import boundary_segments
        if growth.da_fraction:
            raise InputError("growth.da_fraction sizes the steps of 3D fronts; a 2D tip advances growth.da")
        super().__init__(scene, growth, keep_solutions, on_step, beta_table)
        self.a_bnd, self.b_bnd = boundary_segments(scene.mesh)

    def initial_cracks(self, scene: Scene) -> list[Crack]:
        return [dataclasses.replace(c, points=np.array(c.points, dtype=float)) for c in scene.cracks]

    def create_life(self):
        if not self.growth.life:
            return None
        from .life import LifeRun
        return LifeRun(self.scene, self.growth)

    # -- the named steps of a polyline ---------------------------------------------------------------------
    def measure(self) -> Measured:
        """Solve the current geometry and record every tip."""
        if self.life is not None:
            return self.life.measure(self.cracks, self.k, self.N, self.stopped)
        return _measure(self.scene, self.cracks, self.growth, self.k, self.N, self.stopped)

    def correct(self, m: Measured) -> tuple[Measured, int]:
        """The corrector on the increment just taken (growth.corrections):
        the measurement of the geometry kept and the extra solves."""
        if not (self.growth.corrections and self.k > 0 and self.grown):
            return m, 0
        m, turns, extra = _correct(self.scene, self.cracks, self.growth, self.k, self.N, self.stopped, self.grown, m,
                                   measure=lambda: self.measure())
        for r in self.records[-1]:  # the kink the last increment actually took
            if (r.crack, r.end) in turns:
                r.kink_deg += math.degrees(turns[r.crack, r.end])
                if self.k > 1:  # (the first kink leaves the initial crack: no reference, as in advance)
                    self.last_kink[r.crack, r.end] = r.kink_deg
        return m, extra

    def record_beta(self, m: Measured) -> int:
        """The beta table's rows of this geometry (grow(beta_table=True)): K of
        each load group at factor 1 (a spectrum life has them from its
        levels; else one linear solve per group); returns the extra solves."""
        if not self.beta_table:
            return 0
        from .life import basis_levels, beta_rows
        ref = dict(self.growth.reference_stress or {})
        if self.life is not None:
            tips = {key: {"x": lv.x, "y": lv.y, "a": lv.a, "basis": lv.basis} for key, lv in m.levels.items()}
            self.beta += beta_rows(self.k, tips, ref, m.levels, self.life)
            return 0
        tips = basis_levels(self.scene, self.cracks)
        self.beta += beta_rows(self.k, tips, ref)
        return len(next(iter(tips.values()))["basis"]) if tips else 0

    def advance(self, m: Measured) -> None:
        """Extend every growing tip: the fastest by da, the others (fatigue)
        by da times their rate over the fastest one's."""
        from ..model.tip_regions import tip_element_size
        k, model, rates = self.k, m.model, m.rates
        growing = [r for r in m.records if r.status == "growing"]
        if self.da <= 0.0:
            r0 = growing[0]
            self.da = 3.0 * tip_element_size(model, np.array([r0.x, r0.y]))
            self.growth = dataclasses.replace(self.growth, da=self.da)
        rate_max = max(rates.values()) if rates else None
        self.grown = set()
        for r in growing:
            key = (r.crack, r.end)
            if k > 0:  # the first kink leaves the initial crack, any angle: not a reference
                self.last_kink[key] = r.kink_deg
            inc = self.da if not self.fatigue else self.da * rates[key] / rate_max
            r.da = inc
            h_tip = tip_element_size(model, np.array([r.x, r.y]))
            if inc < h_tip and "small" not in self.warned:
                self.warned.add("small")
                self.warn("growth_increment", f"the increment {inc:.3g} at ({r.x:.6g}, {r.y:.6g}) is below the "
                          f"element size there ({h_tip:.3g}): the path follows the mesh; use a larger da or a finer "
                          "mesh (said once)", r.crack, r.end)
            if inc > r.sif_radius and not self.growth.corrections and "large" not in self.warned:
                self.warned.add("large")  # (the corrector checks the kink at the increment's end)
                self.warn("growth_increment", f"the increment {inc:.3g} at ({r.x:.6g}, {r.y:.6g}) is larger than "
                          f"the SIF domain there (radius {r.sif_radius:.3g}): the kink comes from the field within "
                          "that radius and is extrapolated beyond it; use a smaller da or growth.corrections (said "
                          "once)", r.crack, r.end)
            note = _advance(self.cracks, r, inc, model, self.a_bnd, self.b_bnd, h_tip)
            if note:
                self.stops.append(f"step {k}: {note}")
                self.stopped.add(key)
                r.status = note.split(":")[0]
            else:
                self.grown.add(key)
        if self.fatigue:
            self.prev_rate, self.prev_da = rate_max, self.da
        if self.life is not None:
            self.life.advanced(m, {(r.crack, r.end): r.da for r in growing if (r.crack, r.end) in self.grown})


@checked_keywords
def grow(scene: Scene, growth: Growth, keep_solutions: bool = False,
         on_step: typing.Callable[[int, list[TipRecord], typing.Any], None] | None = None,
         beta_table: bool = False) -> GrowthResult:
    """Grow the scene's cracks through its fixed mesh (cracklip.analysis.growth's module doc): a
    solve and K at every tip per step, the kink, the increment; in fatigue (growth.paris_C/m or
    growth.fatigue_material with a spectrum or a cycle) the cycles of each increment, the life.

    scene: a cl.Scene (a scene file's is cl.load_scene_file(path).scene, its growth .growth);
    growth: a cl.Growth (help(cl.Growth): criterion, da, steps, the law, the cycle, the stops).
    on_step(k, records, solution) is called after every step's solve (progress, a ParaView file
    per step; in fatigue the solution at the maximum load); keep_solutions keeps each step's
    Solution in the result; beta_table records K / (S sqrt(pi a)) of every load group at every
    step (GrowthResult.beta).

    Returns a GrowthResult: .records[k] the TipRecords (x, y, length, K_I, K_II, kink_deg, da, N) of step
    k, .rows the same as path.csv's rows, .stop_reason, .warnings, .cycles, and with a fatigue
    material .life (blocks and cycles to failure, its criterion, the residual strength)."""
    require_scene(scene, "grow")
    if not isinstance(growth, Growth):
        raise InputError(f"grow() takes its settings as a cl.Growth(...) (keywords: help(cl.Growth)), got "
                         f"{type(growth).__name__}" + (": write cl.Growth(**settings)" if isinstance(growth, dict)
                                                        else ""))
    if scene.mesh.gdim == 3:
        from .front_growth import SurfaceGrowth
        return SurfaceGrowth(scene, growth, keep_solutions, on_step, beta_table).run()
    return CurveGrowth(scene, growth, keep_solutions, on_step, beta_table).run()


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
        t = segment_hit(tip, tip + (inc + 1.5 * h_tip) * d, o[:-1], o[1:])
        if t is not None or distance_to_segments(new, o[:-1], o[1:]) < 1.5 * h_tip:
            return f"reached crack {other.name!r}: the tip at ({tip[0]:.6g}, {tip[1]:.6g}) stops"
    # The boundary (or a hole) ahead: the crack runs to it and beyond.
    t = segment_hit(tip, tip + (inc + h_tip) * d, a_bnd, b_bnd)
    if t is not None:
        reach = t * (inc + h_tip)
        new = tip + (reach + 0.5 * h_tip) * d
        hit = tip + reach * d
        note = f"reached the boundary: at ({hit[0]:.6g}, {hit[1]:.6g})"
    crack.points = np.vstack([pts, new]) if r.end == 1 else np.vstack([new, pts])
    return note
