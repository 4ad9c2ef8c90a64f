"""The fatigue life of a growing crack under a load spectrum: K at every load
state per growth step, without a solve per cycle.

Per growth step (one crack geometry) the scene is assembled once
(load_path.LevelSolver) and solved

1. linearly for each load group at factor 1 (the superposition basis; an
   initial stress gets a basis case of its own, the residual-stress K of the
   beta table): K and the lip opening at any load state are then the sums
   of the basis values times the state's factors, exact wherever the lips
   stay open;
2. with contact (closure "contact" only) at the load states where that
   opening would be negative somewhere (the lips would pass through each
   other): at most spectrum.contact_levels of them. One load group: the
   lowest closed level and levels evenly spaced up to the closure level
   lambda_cl (where the linear opening first touches zero, K there is the
   linear value, exactly); K at the other closed levels is interpolated
   piecewise linearly between these. Several groups: each closed state
   takes K of the solved closed state nearest to it in factor space (the
   closed states with the largest interpenetration are solved first) --
   an approximation, reported in results.json (closed_states,
   contact_solved).

So the solves grow with growth steps x load levels, never with cycles.
Cycles are counted once per run on the load factor (one group: the order of
K follows the factor) or per tip and step on K itself (several groups),
see cracklip.fracture.rainflow. Each counted cycle's K_max and K_min are
K at its two states; the law (cracklip.fracture.life.LifeLaw) gives da/dN
with the closure chosen.

Between two growth steps the cycles of the increment are integrated with K
interpolated: for each tip K / sqrt(a) is linear in the increment's fraction
t (exact for K proportional to sqrt(a)), a the tip's crack length (the
length in the part over its number of tips). Without retardation a pass
grows the crack by the sum over its cycles (equal cycles merged) and the
passes of the increment are the integral of da / (growth per pass),
composite Simpson in t; with retardation every tip is grown cycle by cycle
in closing order by the compiled kernel (fracture.life_kernels, each cycle
at its own crack length) and keeps its own overload state. The increments
themselves are as in constant amplitude: the fastest tip advances da, the
others da times their growth per pass over the fastest one's.

Failure: K_max of a counted cycle reaching K_c (the smaller of the
material's K_c(t), else K_Ic, and the law's own K_crit), or the mean stress normal to the
crack over the ligament ahead of a tip (tip to boundary) reaching the yield
stress (net-section yield; for a centre crack in a plate of width W this
mean is S W / (W - 2a) exactly), found inside the increment by bisection on
the interpolated values. The residual strength of each step is the largest
multiple of the spectrum's varying loads at its maximum state that the
cracked part carries (steady loads held).
"""
from __future__ import annotations

import dataclasses
import logging
import math
import time
import typing

import numpy as np

from ..errors import InputError
from ..fracture.kink import equivalent_k, kink_angle
from ..fracture.laws import (Forman, GrowthLaw, HartmanSchijve, Nasgro, NasgroConstants, Paris, RateTable, Tabular,
                             Walker)
from ..fracture.life import CycleTable, LifeLaw, pass_growth
from ..fracture.life_kernels import KTable, integrate_cycles, new_run
from ..fracture.rainflow import count_cycles
from ..fracture.retardation import OverloadState, Retardation, constraint_beta
from ..scene.fatigue import FatigueMaterial
from ..scene.growth import Growth, load_cycle
from ..scene.processes import reduced
from ..scene.scene import Scene, load_groups
from ..scene.spectrum import Spectrum, SpectrumBlock
from .tips import no_growth_status


logger = logging.getLogger(__name__)

#: The load group an initial stress is moved to, so that its K is a basis case of its own.
RESIDUAL_GROUP = "initial stress (residual)"


#: An R this far outside a da/dN table's span is said (closure by contact
#: leaves K_min a rounding below 0: R = -2e-4 on the R = 0 curve is no news).
R_OUTSIDE_TABLE = 0.01


def rate_table_messages(reach: dict[str, float], fm: FatigueMaterial, units, whose: str) -> list[str]:
    """The warnings of a tabular da/dN read outside its data
    (fracture.laws.rate_table_reach's `reach` of the cycles `whose`, e.g.
    "the life's cycles"): Delta K above a curve's last row (its last log-log
    segment extended: a table in other units than the scene's K lands
    there) and R outside the table's span (the nearest curve). units: the
    scene's (cracklip.scene.units.Units) or None."""
    where = "material.fatigue.table" + (f" ({fm.source})" if fm.source else "")
    K_unit = f" {units.name('K')}" if units is not None else ""
    out = []
    if reach["ratio"] > 1.0:
        out.append(f"{where}: {whose} reach Delta K = {reach['delta_K']:.4g}{K_unit} at R = {reach['R']:.3g}, "
                   f"{reach['ratio']:.3g} times the table's largest Delta K there ({reach['last']:.4g}): the rates "
                   "above it extend the last log-log segment. Extend the table, or if it is in other units than "
                   "the scene's K give material.fatigue.units")
    if reach["R_min"] < reach["R_lo"] - R_OUTSIDE_TABLE or reach["R_max"] > reach["R_hi"] + R_OUTSIDE_TABLE:
        out.append(f"{where}: {whose} have R from {reach['R_min']:.3g} to {reach['R_max']:.3g}, outside the "
                   f"table's R from {reach['R_lo']:.3g} to {reach['R_hi']:.3g}: they take the rates of the nearest "
                   "curve")
    return out


def create_law(fm: FatigueMaterial) -> LifeLaw:
    """The LifeLaw of a fatigue material already in the scene's units."""
    c = fm.constants
    K_c = fm.toughness()
    if fm.law == "paris":
        law: GrowthLaw = Paris(c["C"], c["m"])
    elif fm.law == "walker":
        law = Walker(c["C"], c["m"], c["gamma"])
    elif fm.law == "forman":
        law = Forman(c["C"], c["n"], c["K_f"])
    elif fm.law == "nasgro":
        law = Nasgro(NasgroConstants(c["C"], c["n"], c["p"], c["q"], c["dK1"], c["C_th_plus"], c["C_th_minus"],
                                     c["alpha"], c["smax_over_flow"], c["a0"],
                                     K_c if K_c is not None else math.inf), fm.closure == "newman")
    elif fm.law == "hartman_schijve":
        law = HartmanSchijve(c["D"], c["dK_thr"], c["A"], c["exponent"])
    else:
        law = Tabular(RateTable(tuple(fm.table_R), tuple(r[0] for r in fm.table), tuple(tuple(r[1:]) for r in fm.table)))
    return LifeLaw(law, fm.closure, c.get("alpha", 2.0), c.get("smax_over_flow", 0.3), fm.threshold)


def critical_k(fm: FatigueMaterial, law: LifeLaw) -> float | None:
    """K_max at which the part fails: the smaller of the toughness (K_c(t),
    else K_Ic) and the law's own critical K (Forman's K_f, Hartman-Schijve's
    A), where its rate diverges; None if neither is given. (The toughness
    alone, when given, let a life run past the law's divergence: with K_Ic
    above Forman's K_f the crack grew from K_f's size to the table's end in
    zero passes.)"""
    ks = [k for k in (fm.toughness(), law.K_crit) if k is not None and math.isfinite(k)]
    return min(ks) if ks else None


def constant_amplitude_spectrum(scene: Scene, growth: Growth) -> Spectrum:
    """The cycle of growth.cycle_max / cycle_min / R as a one-block spectrum."""
    groups = sorted(load_groups(scene)) or ["default"]
    high, low, warning = load_cycle(growth, groups,
                                    scene.initial_stress_group if scene.initial_stress is not None else None)
    if warning is not None:
        logger.warning(warning)
    names = sorted(set(high) | set(low))
    pts = np.array([[high.get(g, 0.0) for g in names], [low.get(g, 0.0) for g in names]])
    steady = {g: 0.0 for g in groups if g not in names}
    return Spectrum([SpectrumBlock(pts, 1, "cycle")], tuple(names), steady=steady, block_name="cycle")


@dataclasses.dataclass
class TipLevels:
    """One tip (a growth point of a 3D front) at one geometry: K at every
    load state of the spectrum.

    Attributes:
        key: (crack, end); 3D: (crack, point).
        a: the tip's crack length (length in the part / tips of the crack);
            3D: the point's distance from the crack's origin
            (front_growth.SurfaceFronts).
        K_lin: K_eq (along theta) of the linear solution per state.
        K_con: K_eq with contact (= K_lin where the lips are open).
        K_I, K_II: per state, as used (contact where closed); K_III too in 3D.
        theta: the kink (radians) at the reference state; twist: 3D only.
        ref, low: the states of the largest and smallest K.
        basis: K_I, K_II (3D: and K_III) of each load group at factor 1 (linear).
        sigma_net: the mean normal stress on the ligament per state (None
            without a yield stress); sigma_basis: the same per load group at
            factor 1.
        cycles: the counted cycles (state indices).
        x, y: the tip; z: 3D only.
        closed: per state, whether the lips touch there (K from contact).
    """
    key: tuple[int, int]
    a: float
    K_lin: np.ndarray
    K_con: np.ndarray
    K_I: np.ndarray
    K_II: np.ndarray
    theta: float
    ref: int
    low: int
    basis: dict[str, tuple[float, float]]
    sigma_net: np.ndarray | None
    cycles: CycleTable
    x: float
    y: float
    sigma_basis: np.ndarray | None = None
    closed: np.ndarray | None = None
    K_III: np.ndarray | None = None
    z: float | None = None
    twist: float = 0.0


class TipPoints:
    """Where a life is measured, 2D: the tips of polylines, one per SIF row
    (a 2D tip is a front of one point). front_growth.FrontPoints is the 3D
    counterpart (growth points along the fronts, K interpolated there from
    the front's SIF points); LifeRun asks its points for where they are, the
    kink, K_eq along it, the net-section stress and a record.

    locate(model, rows, cracks) returns the points of one geometry (self,
    with the model and the rows): keys, values(sifs, name) (a SIF column per
    point, (solutions, points)), lengths (per crack), size(j) (the a of
    point j), position(j), basis(j, ...), net_stresses(basis, wanted),
    record(...); the functions kink, k_eq, k_eq_one, magnitude take K_III
    (0 here) for the 3D points' sake."""

    def locate(self, model, rows: list[dict], cracks) -> "TipPoints":
        from .tips import part_length
        out = TipPoints()
        out.model, out.rows = model, rows
        out.keys = []
        for r in rows:
            g = model.geometries[r["crack"]]
            end = 1 if int(np.asarray(g.tip_orientation)[r["tip"]]) == 1 else 0
            out.keys.append((r["crack"], end))
        out.lengths = [part_length(model, ci) for ci in range(len(cracks))]
        out.ntips = {}
        for ci, _ in out.keys:
            out.ntips[ci] = out.ntips.get(ci, 0) + 1
        return out

    @staticmethod
    def values(sifs: list[list[dict]], name: str) -> np.ndarray | None:
        """One SIF column, (solutions, points); None for K_III (2D)."""
        if name == "K_III":
            return None
        return np.array([[r[name] for r in s] for s in sifs])

    def size(self, j: int) -> float:
        ci = self.keys[j][0]
        return self.lengths[ci] / max(self.ntips[ci], 1)

    def position(self, j: int) -> tuple[float, float, None]:
        r = self.rows[j]
        return float(r["x"]), float(r["y"]), None

    def basis(self, j: int, groups, KI, KII, KIII) -> dict[str, tuple[float, ...]]:
        return {g: (float(KI[i, j]), float(KII[i, j])) for i, g in enumerate(groups)}

    @staticmethod
    def magnitude(KI: np.ndarray, KII: np.ndarray, KIII) -> np.ndarray:
        return np.hypot(np.maximum(KI, 0.0), KII)

    @staticmethod
    def kink(KI: float, KII: float, KIII: float, criterion: str) -> tuple[float, float]:
        return kink_angle(KI, KII, criterion), 0.0

    @staticmethod
    def k_eq(KI: np.ndarray, KII: np.ndarray, KIII, theta: float) -> np.ndarray:
        """K_eq along the kink at every state (linear: not clamped)."""
        return np.array([equivalent_k(a, b, theta, clamp=False) for a, b in zip(KI, KII)])

    @staticmethod
    def k_eq_one(KI: float, KII: float, KIII: float, theta: float, clamp: bool = False) -> float:
        """K_eq of one state (clamp: a negative K_I counts as 0)."""
        return equivalent_k(KI, KII, theta, clamp=clamp)

    @staticmethod
    def near(x: float, y: float, *z: float) -> str:
        return f"the tip near ({x:.6g}, {y:.6g})"

    def net_stresses(self, basis, wanted: bool):
        """s(j, theta): the mean stress normal to the kink on the ligament
        ahead of tip j for each basis solution (G,), or None."""
        if not wanted:
            return None
        from ..model.boundary import boundary_segments
        bnd = boundary_segments(self.model.scene.mesh)

        def at(j: int, theta: float) -> np.ndarray:
            r0 = self.rows[j]
            return np.array([_ligament_stress(b, np.array([r0["x"], r0["y"]]), r0, theta, bnd) for b in basis])
        return at

    def record(self, k: int, j: int, lv: "TipLevels", spread_I: float, spread_II: float, keq: float, closed: float,
               N: float):
        from .tips import TipRecord
        r0 = self.rows[j]
        ci, end = lv.key
        return TipRecord(k, ci, end, r0["x"], r0["y"], self.lengths[ci], float(lv.K_I[lv.ref]), float(lv.K_II[lv.ref]),
                         spread_I, spread_II, math.degrees(lv.theta), keq, closed, N=N, sif_radius=float(r0["radius"]))

    @staticmethod
    def carry(prev: dict, now: dict) -> dict:
        """The levels of this geometry keyed by the previous geometry's points
        (2D: the same tips)."""
        return now


@dataclasses.dataclass
class _StateK:
    """K of one growth step's geometry at the growth points, each a tuple
    (K_I, K_II, K_III), K_III None in 2D: basis per load group (G, points),
    lin per load state by superposition (states, points), use per load state
    with the closed states' contact K filled in; spread_I, spread_II the
    basis's domain spreads (G, points)."""
    basis: tuple
    lin: tuple
    use: tuple
    spread_I: np.ndarray
    spread_II: np.ndarray


@dataclasses.dataclass
class _Closure:
    """A growth step's closed load states (module doc, step 2): the smallest
    linear lip opening per state over the largest (gap_min), the states
    where it is negative (states), those solved with contact (solved) and
    their solutions by state (solutions)."""
    gap_min: np.ndarray
    states: list[int] = dataclasses.field(default_factory=list)
    solved: list[int] = dataclasses.field(default_factory=list)
    solutions: dict[int, typing.Any] = dataclasses.field(default_factory=dict)


#: The status of the records of a geometry the crack reaches only after the
#: failure found inside the increment to it (their N is the failure's).
PAST_FAILURE = "past failure"

#: The status of the records of a geometry past growth.max_length, which the
#: crack reached inside the increment to it (their N is the life to it).
PAST_MAX_LENGTH = "past max_length"

#: The status of the records of a geometry past spectrum.max_passes, which
#: the life reached inside the increment to it (their N is the life then).
PAST_MAX_PASSES = "past max_passes"

#: The statuses whose records are no (a, N) point of the life.
PAST_STOP = (PAST_FAILURE, PAST_MAX_LENGTH, PAST_MAX_PASSES)


class LifeRun:
    """The spectrum life of one growth run: set up once, then per step
    measure() (the load levels), count() (the cycles of the increment just
    taken), advanced() (the increments given) and at the end summary()."""

    def __init__(self, scene: Scene, growth: Growth, points: "TipPoints | None" = None):
        self.locator = points if points is not None else TipPoints()
        self.scene0 = scene
        self.growth = growth
        fm = growth.fatigue_material.converted(scene.units)
        self.material = fm
        self.law = create_law(fm)
        self.spectrum = growth.spectrum if growth.spectrum is not None else constant_amplitude_spectrum(scene, growth)
        sp = self.spectrum
        groups = sorted(load_groups(scene)) or ["default"]  # (a group without loads has K = 0: not solved)
        unknown = sorted(set(sp.groups) - set(groups))
        if unknown:
            raise InputError(f"spectrum.groups names load group(s) {unknown} that no load belongs to; the scene's "
                             f"groups: {groups}")
        unknown = sorted(set(sp.steady) - set(groups))
        if unknown:
            raise InputError(f"spectrum.steady names load group(s) {unknown} that no load belongs to; the scene's "
                             f"groups: {groups}")
        if scene.options.friction > 0.0:
            raise InputError("the fatigue life solves each load level on its own: options.friction must be 0 "
                             "(friction makes K depend on the load path)")
        if fm.closure == "contact" and scene.options.contact == "none":
            raise InputError("material.fatigue.closure = 'contact' takes K_min from crack-lip contact, but "
                             "options.contact is 'none': set options.contact = 'unilateral', or closure = 'newman' "
                             "or 'none'")
        # The initial stress in a basis case of its own (its K is the beta table's residual column).
        self.residual_of = None
        if scene.initial_stress is not None:
            self.residual_of = scene.initial_stress_group
            scene = dataclasses.replace(scene, initial_stress_group=RESIDUAL_GROUP)
        self.scene = scene
        self.groups = groups + ([RESIDUAL_GROUP] if self.residual_of is not None else [])
        self.spec_groups = list(sp.groups)
        pts, owner = sp.pass_points()
        self.states, self.point_state = np.unique(pts, axis=0, return_inverse=True)
        self.point_state = self.point_state.ravel()
        self.point_block = owner
        self.points = pts
        self.blocks_per_pass = sp.blocks_per_pass
        # Factor of every solver group at each state: spectrum columns, steady groups (default 1).
        F = np.zeros((len(self.states), len(self.groups)))
        for j, g in enumerate(self.groups):
            src = self.residual_of if g == RESIDUAL_GROUP else g
            if src in self.spec_groups:
                F[:, j] = self.states[:, self.spec_groups.index(src)]
            else:
                F[:, j] = sp.steady.get(src, 1.0)
        self.F = F
        self.steady = F[0].copy()
        for j, g in enumerate(self.groups):
            src = self.residual_of if g == RESIDUAL_GROUP else g
            if src in self.spec_groups:
                self.steady[j] = 0.0
        self.single = len(self.spec_groups) == 1
        self.cycles = None
        if self.single:
            ct = count_cycles(pts[:, 0], sp.counting, repeated=sp.residue == "close")
            self.cycles = CycleTable(self.point_state[ct.lo], self.point_state[ct.hi], ct.count, owner[ct.hi])
            self.cycles_per_pass = self.cycles.cycles
        else:
            self.cycles_per_pass = None
        self.contact_closure = fm.closure == "contact" and scene.options.contact != "none"
        if scene.options.contact != "none" and fm.closure != "contact":
            # Said once: the contact the scene asks for does not enter K here (Newman's f or the full range
            # on the linear K); closure = 'contact' would use it.
            logger.warning("options.contact = '%s' but material.fatigue.closure = '%s': the life takes the linear "
                           "K at every load state (%s); set closure = 'contact' to take K_min from crack-lip "
                           "contact", scene.options.contact, fm.closure,
                           "Newman's opening function accounts for closure" if fm.closure == "newman" else
                           "the full range, the lips free to pass through each other")
        self.K_crit = self._critical_k()
        self.yield_stress = fm.yield_stress
        self.retardation = None
        if fm.retardation != "none":
            beta = constraint_beta(fm.constraint, fm.thickness, fm.K_Ic, fm.yield_stress)
            self.retardation = Retardation(fm.retardation, fm.yield_stress, beta, fm.wheeler_exponent or 1.0,
                                           fm.shutoff_ratio or 3.0)
        self.ret_state: dict[tuple[int, int], OverloadState] = {}
        self.reference_stress = dict(growth.reference_stress or {})
        self.max_passes = sp.max_passes
        # Run state.
        self.prev: dict[tuple[int, int], TipLevels] | None = None
        self.increments: dict[tuple[int, int], float] = {}
        self.passes = 0.0
        self.N = 0.0
        self.failure: str | None = None
        self.failure_criterion: str | None = None
        self.failure_point: dict[str, typing.Any] | None = None
        self.passes_fraction: float | None = None   # where spectrum.max_passes was reached inside the last increment
        self.steps: list[dict[str, typing.Any]] = []
        self.level_solves = 0
        self.load_levels: list[int] = []
        self.step_seconds: list[float] = []
        self.closure_notes: list[str] = []

    # -- set-up ------------------------------------------------------------------------------------------
    def _critical_k(self) -> float | None:
        return critical_k(self.material, self.law)

    def factors(self, row: np.ndarray) -> dict[str, float]:
        return {g: float(f) for g, f in zip(self.groups, row)}

    # -- measure -----------------------------------------------------------------------------------------
    def measure(self, cracks, k: int, N: float, stopped: set[tuple[int, int]]):
        """Solve the load levels of the current geometry (module doc) and
        record every tip (2D) or growth point of a front (3D, the points of
        self.locator); returns tips.Measured with .levels per point."""
        from .tips import Measured
        from .load_path import LevelSolver
        t0 = time.perf_counter()
        scene = dataclasses.replace(self.scene, cracks=[dataclasses.replace(c) for c in cracks])
        solver = LevelSolver(scene)
        try:
            basis, where, K = self._basis_solves(solver, scene, cracks)
            closure = self._closure(solver, scene, basis, where, K)
            self.level_solves += solver.solves
            self.load_levels.append(solver.solves)
            n_solves = solver.solves
            sol_ref = self._reference_solution(scene, basis, K, closure)
            records, rates, levels = self._tip_records(k, N, stopped, basis, where, K, closure)
            self.closure_notes.append(f"step {k}: {len(closure.states)} of {len(self.states)} load states close the "
                                      "lips" + (f"; contact solved at {len(closure.solved)}" if closure.states else ""))
        finally:
            solver.close()
        self.step_seconds.append(time.perf_counter() - t0)
        m = Measured(records, rates, where.lengths, sol_ref, basis[0].model, solves=n_solves, levels=levels)
        m.where = where
        if k == 0:
            self._check_initial_failure(levels)
        return m

    def _basis_solves(self, solver, scene: Scene, cracks) -> tuple[list, "TipPoints", "_StateK"]:
        """Step 1 (module doc): the linear solve of each load group at
        factor 1, the growth points located on it, and K per load state by
        superposition."""
        unit = [{g: (1.0 if i == j else 0.0) for j, g in enumerate(self.groups)} for i in range(len(self.groups))]
        basis = solver.solve(unit, contact=scene.options.contact == "bilateral",
                             names=[f"unit {g}" for g in self.groups])
        sifs = [b.stress_intensity_factors(None) for b in basis]
        where = self.locator.locate(basis[0].model, sifs[0], cracks)
        Kb = tuple(where.values(sifs, name) for name in ("K_I", "K_II", "K_III"))  # (G, pts) each (K_III: 3D)
        lin = tuple(None if Kg is None else self.F @ Kg for Kg in Kb)  # (states, pts)
        return basis, where, _StateK(Kb, lin, tuple(None if Kl is None else Kl.copy() for Kl in lin),
                                     where.values(sifs, "K_I_spread"), where.values(sifs, "K_II_spread"))

    def _closure(self, solver, scene: Scene, basis: list, where: "TipPoints", K: "_StateK") -> "_Closure":
        """Step 2 (module doc): the load states whose linear lips would pass
        through each other, the contact solves at some of them and K at
        every closed state (K.use filled)."""
        model = basis[0].model
        closure = _Closure(gap_min=np.zeros(len(self.states)))
        if not model.cracks:
            return closure
        gaps = np.array([np.concatenate([b.lip_samples(ci, 2)["gap"] for ci in range(len(model.cracks))])
                         for b in basis])                     # (G, points)
        gstate = self.F @ gaps
        # (under mpirun each process samples the lips of its cells: the extremes over all of them)
        comm = model.V.mesh.comm
        scale = np.maximum(reduced(np.abs(gstate).max(axis=1, initial=0.0), "MAX", comm), 1e-300)
        closure.gap_min = reduced(gstate.min(axis=1, initial=np.inf), "MIN", comm) / scale
        if not self.contact_closure or scene.options.contact == "bilateral":
            return closure
        closure.states = [int(s) for s in np.flatnonzero(closure.gap_min < -1e-6)]
        if not closure.states:
            return closure
        closure.solved, lam_cl = self._contact_levels(closure.states, gaps, closure.gap_min)
        sols = solver.solve([self.factors(self.F[s]) for s in closure.solved], contact=True,
                            names=[f"closed state {s}" for s in closure.solved])
        closure.solutions = dict(zip(closure.solved, sols))
        cs = [sol.stress_intensity_factors(None) for sol in sols]
        for c, name in enumerate(("K_I", "K_II", "K_III")):
            Kc = where.values(cs, name)
            if Kc is not None:
                self._fill_closed(closure.states, closure.solved, Kc, K.use[c], lam_cl, K.basis[c])
        return closure

    def _reference_solution(self, scene: Scene, basis: list, K: "_StateK", closure: "_Closure"):
        """The solution at the reference (largest) state, for the ParaView
        series and the warnings; without contact, the lowest state's joins
        its path where its lips pass through each other (post.checks warns)."""
        from ..post.solution import create_solution
        model = basis[0].model
        KI_use = K.use[0]
        ref_state = int(np.argmax(KI_use.max(axis=1))) if KI_use.size else 0
        if ref_state in closure.solutions:
            sol_ref = closure.solutions[ref_state]
        else:
            u = sum(f * b.u for f, b in zip(self.F[ref_state], basis))
            sol_ref = create_solution(model, u, dict(basis[0].timings), factors=self.factors(self.F[ref_state]),
                                      combination=[(float(f), b) for f, b in zip(self.F[ref_state], basis)])
        gap_min = closure.gap_min
        if scene.options.contact == "none" and gap_min.size and gap_min.min() < -1e-6:
            low_state = int(np.argmin(gap_min))
            u = sum(f * b.u for f, b in zip(self.F[low_state], basis))
            sol_low = create_solution(model, u, dict(basis[0].timings), factors=self.factors(self.F[low_state]))
            sol_low.step = {"index": low_state, "name": "the spectrum's load state " + ", ".join(
                f"{g} x {f:.4g}" for g, f in self.factors(self.F[low_state]).items())}
            sol_ref.path = [sol_ref, sol_low]
        return sol_ref

    def _tip_records(self, k: int, N: float, stopped: set, basis: list, where: "TipPoints", K: "_StateK",
                     closure: "_Closure") -> tuple[list, dict, dict]:
        """Per growth point: its load levels (TipLevels: K per state, the
        kink, the cycles), its record for the step and its growth per pass
        (rates of the growing ones)."""
        from .tips import closed_fraction
        (KI_lin, KII_lin, KIII_lin), (KI_use, KII_use, KIII_use) = K.lin, K.use
        nstate = len(self.states)
        records, rates, levels = [], {}, {}
        nets = where.net_stresses(basis, self.yield_stress is not None)
        zero = np.zeros(nstate)
        for j, key in enumerate(where.keys):
            k3_lin = zero if KIII_lin is None else KIII_lin[:, j]      # K_III per state (0 in 2D)
            k3_use = zero if KIII_use is None else KIII_use[:, j]
            mag = where.magnitude(KI_use[:, j], KII_use[:, j], k3_use)
            ref = int(np.argmax(mag))
            theta, twist = where.kink(KI_use[ref, j], KII_use[ref, j], k3_use[ref], self.growth.criterion)
            K_lin = where.k_eq(KI_lin[:, j], KII_lin[:, j], k3_lin, theta)
            K_con = where.k_eq(KI_use[:, j], KII_use[:, j], k3_use, theta)
            low = int(np.argmin(K_con if self.contact_closure else K_lin))
            a_tip = where.size(j)
            K_cyc = K_con if self.contact_closure else K_lin
            cycles = self.cycles if self.single else self._count_tip(K_cyc)
            sigma_net = s_basis = None
            if nets is not None:
                s_basis = nets(j, theta)
                sigma_net = self.F @ s_basis
            x, y, z = where.position(j)
            lv = TipLevels(key, a_tip, K_lin, K_con, KI_use[:, j], KII_use[:, j], theta, ref, low,
                           where.basis(j, self.groups, *K.basis), sigma_net, cycles, x, y, s_basis,
                           np.isin(np.arange(nstate), closure.states),
                           K_III=None if KIII_use is None else KIII_use[:, j], z=z, twist=twist)
            levels[key] = lv
            spread_I = float(np.abs(self.F[ref]) @ K.spread_I[:, j])
            spread_II = float(np.abs(self.F[ref]) @ K.spread_II[:, j])
            keq = where.k_eq_one(KI_use[ref, j], KII_use[ref, j], k3_use[ref], theta, clamp=True)
            closed = closed_fraction(closure.solutions[ref], key[0]) if ref in closure.solutions else 0.0
            rec = where.record(k, j, lv, spread_I, spread_II, keq, closed, N)
            rec.K_I_min, rec.K_II_min = float(KI_use[low, j]), float(KII_use[low, j])
            rec.a = a_tip
            self._cycle_summary(rec, lv)
            if key in stopped:
                rec.status = "stopped"
            growth_per_pass = pass_growth(K_cyc, cycles.unique(), self.law, a_tip)
            # At K_max >= K_c the law's rate is infinite: no rate to report (the failure is found by
            # the increment's integration, count); results.json holds no inf.
            rec.da_per_pass = growth_per_pass if math.isfinite(growth_per_pass) else None
            rec.residual_strength = self._residual_strength(lv)
            if rec.status == "growing":
                if not growth_per_pass > 0.0:
                    rec.status = no_growth_status(float(np.max(KI_use[:, j])))
                else:
                    rates[key] = growth_per_pass
            records.append(rec)
        return records, rates, levels

    def _count_tip(self, K_states: np.ndarray) -> CycleTable:
        """Several load groups: count the pass on this tip's K."""
        sp = self.spectrum
        values = np.asarray(K_states)[self.point_state]
        if np.ptp(values) <= 0.0:
            return CycleTable(np.zeros(0, int), np.zeros(0, int), np.zeros(0))
        ct = count_cycles(values, sp.counting, repeated=sp.residue == "close")
        out = CycleTable(self.point_state[ct.lo], self.point_state[ct.hi], ct.count, self.point_block[ct.hi])
        if self.cycles_per_pass is None:
            self.cycles_per_pass = out.cycles
        return out

    def _contact_levels(self, closed: list[int], gaps: np.ndarray, gap_min: np.ndarray
                        ) -> tuple[list[int], float | None]:
        """The closed states to solve with contact, and (one group) the closure level."""
        n = self.spectrum.contact_levels
        if not self.single:
            order = sorted(closed, key=lambda s: gap_min[s])  # the deepest interpenetration first
            return sorted(order[:n]), None
        col = self.groups.index(self.spec_groups[0]) if self.spec_groups[0] in self.groups else None
        lam = self.states[:, 0]
        g0 = self.steady @ gaps
        g1 = gaps[col]
        pos = g1 > 1e-12 * max(np.abs(g1).max(), 1e-300)
        lam_cl = float(np.max(-g0[pos] / g1[pos])) if np.any(pos) else None
        below = [s for s in closed if lam_cl is None or lam[s] < lam_cl]
        above = [s for s in closed if s not in below]
        chosen: list[int] = []
        if below:
            lo = min(below, key=lambda s: lam[s])
            chosen.append(lo)
            top = lam_cl if lam_cl is not None else max(lam[s] for s in below)
            for target in np.linspace(lam[lo], top, n + 1)[1:-1]:
                s = min(below, key=lambda s: abs(lam[s] - target))
                if s not in chosen:
                    chosen.append(s)
        chosen += [s for s in sorted(above, key=lambda s: lam[s])][:max(n - len(chosen), 0)]
        if not chosen:
            chosen = [closed[0]]
        return sorted(chosen), lam_cl

    def _fill_closed(self, closed, solved, K_c: np.ndarray, K_use: np.ndarray, lam_cl, basis: np.ndarray) -> None:
        """One component of K (K_I, K_II or K_III) at every closed state from
        the solved ones (module doc): K_c (solved, pts) the contact values,
        K_use (states, pts) filled in place, basis (groups, pts) the unit
        values (the linear K at the closure level)."""
        for i, s in enumerate(solved):
            K_use[s] = K_c[i]
        rest = [s for s in closed if s not in solved]
        if not rest:
            return
        if self.single:
            lam = self.states[:, 0]
            xs = [lam[s] for s in solved]
            ys = [K_c[i] for i in range(len(solved))]
            if lam_cl is not None:
                # The closure level: the lips just touch, K is the linear value there.
                col = [i for i, g in enumerate(self.groups) if (self.residual_of if g == RESIDUAL_GROUP else g)
                       in self.spec_groups]
                row = self.steady.copy()
                row[col] = lam_cl
                xs.append(lam_cl)
                ys.append(row @ basis)
            order = np.argsort(xs)
            xs = np.asarray(xs)[order]
            Y = np.asarray(ys)[order]
            for s in rest:
                for j in range(K_use.shape[1]):
                    K_use[s, j] = np.interp(lam[s], xs, Y[:, j])
        else:
            P = self.F[solved]
            for s in rest:
                i = int(np.argmin(np.linalg.norm(P - self.F[s], axis=1)))
                K_use[s] = K_c[i]

    def _cycle_summary(self, rec, lv: TipLevels) -> None:
        """The largest counted cycle of the tip: K_max, K_min, Delta K_eff, R."""
        K = lv.K_con if self.contact_closure else lv.K_lin
        ct = lv.cycles
        if len(ct.lo) == 0:
            rec.K_max = rec.K_min = rec.delta_K_eff = rec.R = None
            return
        km, kn = K[ct.hi], K[ct.lo]
        i = int(np.argmax(km - kn))
        dk, R = self.law.effective(km[i:i + 1], kn[i:i + 1])
        rec.K_max, rec.K_min = float(km[i]), float(kn[i])
        rec.delta_K_eff, rec.R = float(dk[0]), float(R[0])
        rec.delta_K = rec.delta_K_eff

    def _residual_strength(self, lv: TipLevels) -> float | None:
        """The multiple of the varying loads at the reference state the
        cracked part carries (module doc): min of the K and net-section ones."""
        out = []
        ref = lv.ref
        K_steady = float(np.sum(self.steady * self._keq_basis(lv)))
        K_var = float(lv.K_lin[ref]) - K_steady
        if self.K_crit is not None and K_var > 0:
            out.append((self.K_crit - K_steady) / K_var)
        if lv.sigma_net is not None and self.yield_stress is not None:
            s_steady = float(self.steady @ self._sigma_basis(lv))
            s_var = float(lv.sigma_net[ref]) - s_steady
            if s_var > 0:
                out.append((self.yield_stress - s_steady) / s_var)
        return min(out) if out else None

    def _keq_basis(self, lv: TipLevels) -> np.ndarray:
        return np.array([self.locator.k_eq_one(b[0], b[1], b[2] if len(b) > 2 else 0.0, lv.theta)
                         for b in (lv.basis[g] for g in self.groups)])

    def _sigma_basis(self, lv: TipLevels) -> np.ndarray:
        return lv.sigma_basis

    def _check_initial_failure(self, levels: dict) -> None:
        for key, lv in levels.items():
            reason = self._fails(lv.K_con if self.contact_closure else lv.K_lin, lv.sigma_net)
            if reason:
                self._fail(reason, 0.0, lv, key)
                return

    def _fails(self, K: np.ndarray, sigma: np.ndarray | None) -> str | None:
        if self.K_crit is not None and float(np.max(K)) >= self.K_crit:
            return "K_max >= K_c"
        if sigma is not None and self.yield_stress is not None and float(np.max(sigma)) >= self.yield_stress:
            return "net-section yield"
        return None

    def _fail(self, criterion: str, t: float, lv: TipLevels, key, a: float | None = None,
              at: tuple[float, ...] | None = None) -> None:
        u = self.scene.units
        unit = (lambda q: f" {u.name(q)}" if u is not None else "")  # noqa: E731 (the scene's units, as converted)
        what = (f"K_max reached K_c = {self.K_crit:.6g}{unit('K')}" if criterion == "K_max >= K_c" else
                f"the mean stress on the ligament reached the yield stress {self.yield_stress:.6g}{unit('stress')}")
        cyc = self.N
        self.failure_criterion = criterion
        x, y, *z = at if at is not None else (lv.x, lv.y) + (() if lv.z is None else (lv.z,))
        cracks = self.scene0.cracks
        name = repr(cracks[key[0]].name) if key[0] < len(cracks) and cracks[key[0]].name else str(key[0])
        when = f"inside the increment to step {len(self.steps)}" if t > 0.0 else f"at step {len(self.steps)}"
        self.failure = (f"final failure: {what} at {self.locator.near(x, y, *z)} of crack {name} ({when}), a = "
                        f"{a if a is not None else lv.a:.6g}, after {cyc:.6g} cycles = {self.passes:.6g} passes = "
                        f"{self.passes * self.blocks_per_pass:.6g} {self.spectrum.block_name}s (criterion: {criterion})")
        self.failure_point = {"criterion": criterion, "a": a if a is not None else lv.a, "cycles": cyc,
                              "passes": self.passes, "blocks": self.passes * self.blocks_per_pass, "crack": key[0],
                              "end": key[1], "x": x, "y": y, **({"z": z[0]} if z else {})}

    # -- count -------------------------------------------------------------------------------------------
    def count(self, m, k: int, t_stop: float | None = None) -> float:
        """Integrate the increment from the last geometry to this one (module
        doc); set the records' N, passes, blocks; return the cycles so far.
        t_stop: the fraction of the increment at which the run stops inside
        it (growth.max_length reached there): the cycles up to it only, and
        this geometry's records marked past it."""
        now = m.levels
        failed_inside = past_stop = False
        self.passes_fraction = None
        if k > 0 and self.prev is not None and self.increments and self.failure is None:
            self._integrate(self.prev, self.locator.carry(self.prev, now), t_stop)
            failed_inside = self.failure is not None
            past_stop = not failed_inside and t_stop is not None and t_stop < 1.0
        dN = self.N - (self.steps[-1]["cycles"] if self.steps else 0.0)
        for rec in m.records:
            rec.N, rec.dN = self.N, dN
            rec.passes = self.passes
            rec.blocks = self.passes * self.blocks_per_pass
            if failed_inside:  # this geometry lies beyond the failure found inside the increment: no (a, N) point
                rec.status = PAST_FAILURE
            elif self.passes_fraction is not None:  # beyond spectrum.max_passes, reached inside the increment
                rec.status = PAST_MAX_PASSES
            elif past_stop:  # and beyond growth.max_length, reached inside the increment
                rec.status = PAST_MAX_LENGTH
        self.steps.append({"step": k, "cycles": self.N, "passes": self.passes,
                           "blocks": self.passes * self.blocks_per_pass,
                           "tips": [{"crack": r.crack, "end": r.end, "a": now[(r.crack, r.end)].a if (r.crack, r.end)
                                     in now else None, "K_max": r.K_max, "K_min": r.K_min,
                                     "delta_K_eff": r.delta_K_eff, "R": r.R, "da_per_pass": r.da_per_pass,
                                     "residual_strength": r.residual_strength} for r in m.records]})
        self.prev = now
        return self.N

    def advanced(self, m, increments: dict[tuple[int, int], float]) -> None:
        """The increments the tips were just given."""
        self.increments = dict(increments)

    def _interp(self, a: TipLevels, b: TipLevels, t: float, which: str) -> tuple[np.ndarray, float]:
        A, B = getattr(a, which), getattr(b, which)
        aa = a.a + t * (b.a - a.a)
        return math.sqrt(aa) * ((1.0 - t) * A / math.sqrt(a.a) + t * B / math.sqrt(b.a)), aa

    def _integrate(self, prev: dict, now: dict, t_stop: float | None = None) -> None:
        """The passes of the increment from prev to now (up to the fraction
        t_stop of it if given, and up to a failure found inside it)."""
        which = "K_con" if self.contact_closure else "K_lin"
        keys = [key for key in self.increments if key in prev and key in now]
        if not keys:
            return
        fast = max(keys, key=lambda key: self.increments[key])
        p, q = prev[fast], now[fast]
        ds = self.increments[fast]
        cyc_u = p.cycles.unique()

        def growth_at(t: float) -> float:
            K, aa = self._interp(p, q, t, which)
            return pass_growth(K, cyc_u, self.law, aa)

        def excess(t: float) -> tuple[str | None, float, typing.Any]:
            worst = (None, -math.inf, None)
            for key in keys:
                K, _ = self._interp(prev[key], now[key], t, which)
                if self.K_crit is not None:
                    v = float(np.max(K)) / self.K_crit - 1.0
                    if v > worst[1]:
                        worst = ("K_max >= K_c", v, key)
                if self.yield_stress is not None and prev[key].sigma_net is not None:
                    s = (1 - t) * prev[key].sigma_net + t * now[key].sigma_net
                    v = float(np.max(s)) / self.yield_stress - 1.0
                    if v > worst[1]:
                        worst = ("net-section yield", v, key)
            return worst
        t_end = 1.0 if t_stop is None else t_stop
        crit, v1, fkey = excess(t_end)
        if crit is not None and v1 >= 0.0:
            lo, hi = 0.0, t_end
            for _ in range(50):
                mid = 0.5 * (lo + hi)
                if excess(mid)[1] >= 0.0:
                    hi = mid
                else:
                    lo = mid
            t_end = hi
        def passes_to(t: float) -> float:
            """The passes from the increment's start to its fraction t (Simpson, 16 intervals)."""
            n = 16
            ts = np.linspace(0.0, t, n + 1)
            g = np.array([growth_at(x) for x in ts])
            if np.any(g <= 0.0):
                return math.inf
            w = np.ones(n + 1)
            w[1:-1:2], w[2:-1:2] = 4.0, 2.0
            return float(ds * (ts[1] - ts[0]) / 3.0 * np.sum(w / g))
        if self.retardation is None:
            passes = passes_to(t_end)
            want = self.max_passes - self.passes
            if math.isfinite(passes) and passes > want:
                # spectrum.max_passes inside the increment: the life ends where the passes reach it (as `cracklip
                # life`'s does), before a failure found further on.
                lo, hi = 0.0, t_end
                for _ in range(50):
                    mid = 0.5 * (lo + hi)
                    if passes_to(mid) >= want:
                        hi = mid
                    else:
                        lo = mid
                t_end, passes, crit = hi, want, None
                self.passes_fraction = hi
        else:
            passes = self._retarded_passes(prev, now, keys, fast, ds, t_end, which)
        if not math.isfinite(passes):
            # The growth per pass vanishes inside the increment (K falls below the threshold): arrest.
            self.failure_criterion = "arrest"
            self.failure = (f"growth arrested: the growth per pass of the fastest tip (crack {fast[0]} end "
                            f"{fast[1]}) falls to 0 within the increment from a = {p.a:.6g} to {q.a:.6g} (below the "
                            f"threshold), after {self.N:.6g} cycles = {self.passes:.6g} passes")
            self.failure_point = {"criterion": "arrest", "a": p.a, "cycles": self.N, "passes": self.passes,
                                  "blocks": self.passes * self.blocks_per_pass, "crack": fast[0], "end": fast[1],
                                  "x": p.x, "y": p.y}
            return
        self.passes += passes
        self.N = self.passes * (self.cycles_per_pass or 0.0)
        if crit is not None and v1 >= 0.0:
            aa = p.a + t_end * (q.a - p.a)
            lv, lp = now[fkey], prev[fkey]
            self._fail(crit, t_end, lv, fkey, a=lp.a + t_end * (lv.a - lp.a),
                       at=(lp.x + t_end * (lv.x - lp.x), lp.y + t_end * (lv.y - lp.y))
                       + (() if lv.z is None else (lp.z + t_end * (lv.z - lp.z),)))
            if fkey == fast:
                self.failure_point["a"] = aa

    def _retarded_passes(self, prev, now, keys, fast, ds, t_end, which) -> float:
        """Every tip grown cycle by cycle over the increment by the compiled
        kernel (fracture.life_kernels): K of each load state from the
        increment's two level tables (K / sqrt(a) linear in a, as _interp),
        each tip with its own overload state; the passes of the fastest tip."""
        out = None
        for key in keys:
            p, q = prev[key], now[key]
            span = q.a - p.a
            if span <= 0.0:
                continue
            K = np.stack([getattr(p, which), getattr(q, which)])  # (2 sizes, states): one case per state
            table = KTable(1, np.array([p.a, q.a]), K, tuple(str(s) for s in range(K.shape[1])))
            st = self.ret_state.get(key) or OverloadState()
            run = new_run([p.a])
            run["state"] = ((st.a_OL, st.r_OL, st.K_OL), run["state"][1])
            run = integrate_cycles(table, np.eye(K.shape[1]), p.cycles, self.law, self.retardation, run,
                                   [p.a + t_end * span], max_passes=10 ** 7)
            self.ret_state[key] = OverloadState(*run["state"][0])
            if key == fast:
                out = (run["cycles"] / max(self.cycles_per_pass or 1.0, 1e-300) if run["stop"] == "reached"
                       else math.inf)
        return out if out is not None else 0.0

    def passes_exceeded(self) -> bool:
        """The life reached spectrum.max_passes (exactly, when found inside
        an increment; a retarded life by the step past it)."""
        return self.passes >= self.max_passes * (1.0 - 1e-12)

    # -- the summary -------------------------------------------------------------------------------------
    def summary(self, records) -> dict[str, typing.Any]:
        fm = self.material
        curve = []
        for st, recs in zip(self.steps, records):
            for r in recs:
                if r.residual_strength is not None:
                    curve.append({"step": st["step"], "crack": r.crack, "end": r.end, "a": r.a,
                                  "multiple": r.residual_strength,
                                  "stress": self._strength_stress(r.residual_strength)})
        return {
            "law": self.law.law.describe(),
            "closure": self.law.closure,
            "closure_note": ("elastic crack-lip contact at every load state (no plastic wake)"
                             if self.law.closure == "contact" else
                             "Newman's opening function f(R) on the linear K (contact not used for K)"
                             if self.law.closure == "newman" else "none: linear K, full range"),
            "retardation": fm.retardation,
            "material_source": fm.source,
            "K_crit": self.K_crit,
            "yield_stress": self.yield_stress,
            "counting": self.spectrum.counting,
            "residue": self.spectrum.residue,
            "load_states": int(len(self.states)),
            "cycles_per_pass": self.cycles_per_pass,
            "blocks_per_pass": self.blocks_per_pass,
            "block_name": self.spectrum.block_name,
            "cycles": self.N,
            "passes": self.passes,
            "blocks": self.passes * self.blocks_per_pass,
            "failure": self.failure_point,
            "level_solves": self.level_solves,
            "load_levels_per_step": self.load_levels,
            "measure_seconds": self.step_seconds,
            "closure_per_step": self.closure_notes,
            "residual_strength": curve,
            "steps": self.steps,
        }

    def _strength_stress(self, multiple: float) -> float | None:
        """The residual strength as a stress: the multiple times the spectrum's
        maximum factor times the reference stress (one varying group only)."""
        if not self.single:
            return None
        g = self.spec_groups[0]
        S = self.reference_stress.get(g, 1.0)
        return float(multiple * np.max(self.states[:, 0]) * S)


def basis_levels(scene: Scene, cracks) -> dict[tuple[int, int], dict[str, typing.Any]]:
    """K_I, K_II of every load group at factor 1 (linear: lips free) at every
    tip of the given cracks, an initial stress as its own case
    (RESIDUAL_GROUP): {(crack, end): {"x", "y", "a", "basis": {group: (K_I,
    K_II)}}}. One solve per group on one assembly (the beta table of a run
    without a spectrum)."""
    from .load_path import LevelSolver
    from .tips import part_length
    if scene.initial_stress is not None:
        scene = dataclasses.replace(scene, initial_stress_group=RESIDUAL_GROUP)
    groups = sorted(load_groups(scene) - {RESIDUAL_GROUP}) + ([RESIDUAL_GROUP] if scene.initial_stress is not None
                                                              else [])
    groups = groups or ["default"]
    scene = dataclasses.replace(scene, cracks=[dataclasses.replace(c) for c in cracks],
                                options=dataclasses.replace(scene.options, friction=0.0))
    solver = LevelSolver(scene)
    try:
        unit = [{g: (1.0 if g == h else 0.0) for g in groups} for h in groups]
        sols = solver.solve(unit, contact=scene.options.contact == "bilateral")
        model = sols[0].model
        sifs = [x.stress_intensity_factors(None) for x in sols]
        lengths = [part_length(model, ci) for ci in range(len(cracks))]
        ntips: dict[int, int] = {}
        for r in sifs[0]:
            ntips[r["crack"]] = ntips.get(r["crack"], 0) + 1
        out = {}
        for j, r in enumerate(sifs[0]):
            ci = r["crack"]
            end = 1 if int(np.asarray(model.geometries[ci].tip_orientation)[r["tip"]]) == 1 else 0
            out[(ci, end)] = {"x": float(r["x"]), "y": float(r["y"]), "a": lengths[ci] / ntips[ci],
                              "basis": {g: (float(sifs[i][j]["K_I"]), float(sifs[i][j]["K_II"]))
                                        for i, g in enumerate(groups)}}
        return out
    finally:
        solver.close()


def beta_rows(step: int, tips: dict[tuple[int, int], dict[str, typing.Any]], reference_stress: dict[str, float],
              levels: dict[tuple[int, int], TipLevels] | None = None, run: "LifeRun | None" = None
              ) -> list[dict[str, typing.Any]]:
    """One row per tip of the beta table: beta_<group> = K_I / (S sqrt(pi a))
    of each load group at factor 1 (S its reference stress, default 1),
    K_residual (the initial stress's K_I alone, linear), and with contact in a
    one-group spectrum beta at every load level solved with contact,
    beta_<group>_at_<factor> = K_I(level) / (factor S sqrt(pi a))."""
    rows = []
    for key, t in sorted(tips.items()):
        a = t["a"]
        row: dict[str, typing.Any] = {"step": step, "crack": key[0], "end": key[1], "x": t["x"], "y": t["y"], "a": a}
        for g, (kI, kII) in t["basis"].items():
            if g == RESIDUAL_GROUP:
                row["K_residual"] = kI
                continue
            S = reference_stress.get(g, 1.0)
            row[f"beta_{g}"] = kI / (S * math.sqrt(math.pi * a)) if a > 0 else None
            row[f"K_I_{g}"] = kI
            row[f"K_II_{g}"] = kII
        if levels is not None and run is not None and run.single and key in levels:
            lv = levels[key]
            g = run.spec_groups[0]
            S = reference_stress.get(g, 1.0)
            for s in np.flatnonzero(lv.closed):
                lam = float(run.states[s, 0])
                if lam != 0.0:
                    row[f"beta_{g}_at_{lam:g}"] = float(lv.K_I[s]) / (lam * S * math.sqrt(math.pi * a))
        rows.append(row)
    return rows


def _ligament_stress(sol, tip: np.ndarray, r0: dict, theta: float, bnd) -> float:
    """The mean stress normal to the growth direction over the ligament ahead
    of a tip (tip to the boundary along the kink direction), by Gauss-Legendre
    in u with s = L u^2 (the 1/sqrt(s) of the tip field becomes smooth)."""
    from .tips import segment_hit
    from ..scene.material import strain, stress
    from ..scene.stress_field import evaluate_stress
    d0 = np.asarray(r0.get("direction", (1.0, 0.0)), dtype=float)
    d0 = d0 / max(np.linalg.norm(d0), 1e-300)
    c, s = math.cos(theta), math.sin(theta)
    d = np.array([c * d0[0] - s * d0[1], s * d0[0] + c * d0[1]])
    a, b = bnd
    span = float(np.ptp(np.vstack([a, b]), axis=0).max()) * 4.0
    t = segment_hit(tip, tip + span * d, a, b)
    if t is None:
        return 0.0
    L = t * span
    u, w = np.polynomial.legendre.leggauss(24)
    u, w = 0.5 * (u + 1.0), 0.5 * w
    pts = tip + (L * u ** 2)[:, None] * d
    grad = sol.gradient_anywhere(pts)  # (under mpirun from the processes holding the points)
    sig = stress(strain(grad), sol.model.scene.material)
    scene = sol.model.scene
    if scene.initial_stress is not None and sol.factor(scene.initial_stress_group) != 0.0:
        sig = sig + sol.factor(scene.initial_stress_group) * evaluate_stress(scene.initial_stress, pts, "initial stress")
    n = np.array([-d[1], d[0]])
    snn = np.einsum("i,nij,j->n", n, sig, n)
    return float(np.sum(w * snn * 2.0 * u))


__all__ = ["RESIDUAL_GROUP", "PAST_FAILURE", "PAST_MAX_LENGTH", "PAST_MAX_PASSES", "PAST_STOP", "create_law", "critical_k",
           "constant_amplitude_spectrum", "TipLevels", "LifeRun"]
