"""The discretisation error of K, and refinement to a target accuracy.

K from a displacement-based solve converges as the mesh is refined (from
below on the handbook cases, the C(T) and the crack at a hole: a P1 part is
too stiff). Its error is estimated from solves on refinement levels of the
same part (cracklip.scene.size_field, levels; cracklip.scene.refine):

- level L has every element size halved L times within D of each tip,
  D = TIP_REGION x the crack's length in the part (the region whose mesh
  sets K: measured on the handbook cases, a region of one crack length
  left up to a third of the difference to a uniform refinement, two crack
  lengths within 10 % of it), and around every hole within D of a tip
  (HOLE_REGION x its radius), graded back beyond;
- with two levels the error of the finer K is |K_1 - K_0| / (2^p - 1) at
  the rate p = ASSUMED_RATE = 1 (and 2 |K_1 - K_0| for K_0): the rate of
  K lies between 1 (enrichment in the tip cell only, point loads: 1.3 on
  the C(T)) and 2 (geometric enrichment, smooth loads: 1.8-2.7 on the
  handbook cases), so the slowest one bounds the error from above;
- with three levels or more the rate is observed (the smallest over every
  three consecutive levels, clipped to [RATE_MIN, RATE_MAX]; when the
  differences change sign or do not shrink it is not observed and the
  assumed rate stands), the error of
  the finest K is SAFETY |K_L - K_{L-1}| / (2^p - 1), and K extrapolated
  (Richardson) is K_L + (K_L - K_{L-1}) / (2^p - 1). This is Roache's grid
  convergence index (Roache 1994, J. Fluids Eng. 116: safety factor 1.25
  with an observed rate; with two grids he takes 3 at the theoretical rate
  2, which is the 1 / (2^1 - 1) = 3 / (2^2 - 1) above). Measured: the
  handbook cases converge at 1.8-2.7, the C(T) at 1.3, the crack at a hole
  at 1.3-1.8 over the levels, pre-asymptotic (without the safety factor its
  level-2 estimate was 0.9 of the true error).

Cost: one solve per level; a level has about 4^L times the cells of the
refined region (the whole part when the crack is not small in it).

``estimate_error`` adds one solve (level 1) to a solution and gives each of
its K an estimate; ``solve_to_accuracy`` refines level by level until the
largest estimate is below Options.accuracy (relative to the K scale), and
returns the finest level's solution. Neither imports the solve itself (it
is passed in), so cracklip.analysis.solve can call them.
"""
from __future__ import annotations

import dataclasses
import logging
import math
import time
import typing

import numpy as np

from ..scene.refine import with_levels
from ..scene.scene import Scene


logger = logging.getLogger(__name__)


#: Refined region around a tip: this many times the crack's length in the part.
TIP_REGION = 2.0


#: Refined region around a hole near a tip: this many times the hole's radius from its centre.
HOLE_REGION = 4.0


#: The rate of K assumed while it cannot be observed (two levels): the
#: slowest of the cases measured, so that the estimate bounds the error.
ASSUMED_RATE = 1.0


#: Safety factor on the error estimated with an observed rate (Roache's 1.25).
SAFETY = 1.25


#: An observed rate is clipped to this range (2: K with geometric
#: enrichment; 0.5: K without tip enrichment).
RATE_MIN, RATE_MAX = 0.5, 2.0


Solver = typing.Callable[[Scene], typing.Any]


def tip_regions(solution) -> list[tuple[int, int, float, float, float]]:
    """The regions refined per level: (crack, tip, x, y, D) of every tip, D
    = TIP_REGION x the crack's length in the part, and (-1, k, x, y, D) of
    every hole that comes within D of a tip: its centre, D = HOLE_REGION x
    its radius (the hole's stress concentration sets K of a crack beside
    it: for a 4 mm crack at a 10 mm hole, demos/scenes/hole_fatigue.toml,
    the tip's region alone gave an estimate of 1.1 for an error of 17.2;
    with the hole's region of 2 radii 13.6, of 4 radii 20.7, of the whole
    plate 23.8)."""
    from ..model.boundary import boundary_loops
    from ..model.tip_regions import lip_points, model_boundary, segment_distance
    m = solution.model
    out = []
    for ci, cm in enumerate(m.cracks):
        tips = np.asarray(cm.geometry.tips).reshape(-1, 2)
        if not len(tips):
            continue
        length = float(lip_points(m, ci)["weight"].sum())
        for j, p in enumerate(tips):
            out.append((ci, j, float(p[0]), float(p[1]), TIP_REGION * length))
    if not out:
        return out
    a, b = model_boundary(m)
    labels, outer = boundary_loops(a, b)
    tips = list(out)
    for k, lab in enumerate(sorted(set(labels.tolist()) - {outer})):
        la, lb = a[labels == lab], b[labels == lab]
        w = np.linalg.norm(lb - la, axis=1)
        centre = (0.5 * (la + lb) * w[:, None]).sum(axis=0) / w.sum()
        radius = float(np.linalg.norm(np.concatenate([la, lb]) - centre, axis=1).max())
        if any(segment_distance(np.array([x, y]), la, lb).min() < D for (_, _, x, y, D) in tips):
            out.append((-1, k, float(centre[0]), float(centre[1]), HOLE_REGION * radius))
    return out


def level_items(regions, level: int) -> list[tuple[float, float, float, float, float, int]]:
    """The size-field levels (x, y, x, y, D, level) of the regions."""
    return [(x, y, x, y, D, level) for (_, _, x, y, D) in regions]


def scene_on(scene: Scene, mesh) -> Scene:
    """The scene on another mesh of the same part: point conditions go to the
    new mesh's node at (or nearest to) their point."""
    dirichlet = []
    for bc in scene.dirichlet:
        if isinstance(bc.where, (tuple, list, np.ndarray)) and not isinstance(bc.where, str):
            bc = dataclasses.replace(bc, where=mesh.nearest_node(bc.where))
        dirichlet.append(bc)
    return dataclasses.replace(scene, mesh=mesh, dirichlet=dirichlet)


@dataclasses.dataclass
class Level:
    """One solve of the sequence: its level, dofs, seconds and K per (state
    of the load path, crack, tip)."""
    level: int
    dofs: int
    seconds: float
    K: dict[tuple[int, int, int], tuple[float, float]]


def _states(solution) -> list:
    return solution.path or [solution]


def _levels_K(solution) -> dict[tuple[int, int, int], tuple[float, float]]:
    return {(s, r["crack"], r["tip"]): (r["K_I"], r["K_II"])
            for s, st in enumerate(_states(solution)) for r in st.stress_intensity_factors(None)}


def _rate(values: list[float]) -> float | None:
    """The observed rate: the smallest over every three consecutive values
    (a rate still rising toward its asymptote is not trusted: the C(T)'s
    1.3 then 1.8), None if any three do not converge monotonically."""
    if len(values) < 3:
        return None
    rates = []
    for k in range(len(values) - 2):
        d1, d2 = values[k + 1] - values[k], values[k + 2] - values[k + 1]
        if d1 == 0.0 or d2 == 0.0 or d1 * d2 < 0.0 or abs(d2) >= abs(d1):
            return None
        rates.append(math.log2(abs(d1) / abs(d2)))
    return float(min(max(min(rates), RATE_MIN), RATE_MAX))


def estimate(levels: list[Level], of: int = -1) -> dict[tuple[int, int, int], dict[str, typing.Any]]:
    """Per (state, crack, tip): the estimated error of K_I, K_II at level
    `of` (the last by default, or 0: the first, as estimate_error gives it),
    the rates used (None: not observed, ASSUMED_RATE used), K per level and
    K extrapolated (when the rate is observed)."""
    out = {}
    for key in levels[-1].K:
        row: dict[str, typing.Any] = {}
        for m, mode in enumerate(("K_I", "K_II")):
            values = [lv.K[key][m] for lv in levels if key in lv.K]
            if len(values) < 2:
                continue
            observed = _rate(values)
            p = ASSUMED_RATE if observed is None else observed
            diff = values[-1] - values[-2]
            factor = 1.0 / (2.0 ** p - 1.0)
            safety = 1.0 if observed is None else SAFETY
            row[f"{mode}_error"] = safety * abs(diff) * (factor if of == -1 else 1.0 + factor)
            row[f"{mode}_rate"] = observed
            row[f"{mode}_levels"] = values
            row[f"{mode}_extrapolated"] = values[-1] + diff * factor if observed is not None else None
        if row:
            out[key] = row
    return out


def _attach(solution, levels: list[Level], est, target: float | None, of: int) -> dict[str, typing.Any]:
    """Put the estimate on every state of the solution's load path
    (Solution.error_estimate, its own tips each) and return the summary of
    the whole: the largest error relative to the largest K scale."""
    from ..fracture.sif import k_scale
    states = _states(solution)
    scales = [k_scale(st, [v for (s, _, _), v in levels[of].K.items() if s == i]) for i, st in enumerate(states)]
    scale = max(scales)
    worst = max([max(r.get("K_I_error", 0.0), r.get("K_II_error", 0.0)) for r in est.values()] + [0.0])
    summary = {"method": f"refinement levels: element sizes halved within {TIP_REGION:g} crack lengths of each "
                         "tip per level; the rate of K observed (the smallest over three consecutive levels) where it "
                         f"converges monotonically (times a safety factor {SAFETY:g}), else assumed {ASSUMED_RATE:g} (an "
                         "upper bound of the error)",
               "levels": [lv.level for lv in levels], "dofs": [lv.dofs for lv in levels],
               "seconds": [lv.seconds for lv in levels], "of_level": levels[of].level,
               "K_scale": scale, "largest_error": worst, "largest_relative_error": worst / scale if scale > 0 else 0.0,
               "target": target, "reached": None if target is None else bool(worst <= target * scale)}
    for i, st in enumerate(states):
        st.error_estimate = {**summary, "tips": {f"{c}:{t}": v for (s, c, t), v in est.items() if s == i}}
    return summary


def estimate_error(scene: Scene, solution, solve_once: Solver) -> dict[str, typing.Any] | None:
    """One more solve on level 1 (sizes halved around every tip): the error
    estimate of every K of `solution` (level 0), attached to it (and every
    state of its load path: Solution.error_estimate) and returned (the
    summary). None without a tip."""
    regions = tip_regions(solution)
    if not regions:
        return None
    t0 = time.perf_counter()
    fine = solve_once(scene_on(scene, with_levels(scene.mesh, level_items(regions, 1))))
    levels = [Level(0, solution.model.num_dofs, float(solution.timings.get("total", 0.0)), _levels_K(solution)),
              Level(1, fine.model.num_dofs, time.perf_counter() - t0, _levels_K(fine))]
    summary = _attach(solution, levels, estimate(levels, of=0), None, 0)
    logger.info("error estimate: level 1 has %d dofs (%.2f s); largest estimated error %.3g %% of the K scale",
                fine.model.num_dofs, levels[1].seconds, 100 * summary["largest_relative_error"])
    return summary


def solve_to_accuracy(scene: Scene, accuracy: float, max_levels: int, solve_once: Solver):
    """Solve level 0, 1, ... (sizes halved around every tip per level)
    until the largest estimated error of K is below `accuracy` times the K
    scale or max_levels is reached; the finest solution, with
    Solution.error_estimate on every state of its load path."""
    t0 = time.perf_counter()
    sol = solve_once(scene)
    levels = [Level(0, sol.model.num_dofs, time.perf_counter() - t0, _levels_K(sol))]
    regions = tip_regions(sol)
    if not regions:
        logger.info("accuracy: no crack tip in the part, nothing to refine")
        return sol
    for level in range(1, max_levels + 1):
        t0 = time.perf_counter()
        sol = solve_once(scene_on(scene, with_levels(scene.mesh, level_items(regions, level))))
        levels.append(Level(level, sol.model.num_dofs, time.perf_counter() - t0, _levels_K(sol)))
        summary = _attach(sol, levels, estimate(levels), accuracy, -1)
        logger.info("accuracy: level %d, %d dofs (%.2f s), largest estimated error %.3g %% (target %.3g %%)",
                    level, sol.model.num_dofs, levels[-1].seconds, 100 * summary["largest_relative_error"],
                    100 * accuracy)
        if summary["reached"]:
            break
    return sol


__all__ = ["estimate_error", "solve_to_accuracy", "estimate", "tip_regions", "scene_on", "TIP_REGION",
           "ASSUMED_RATE"]
