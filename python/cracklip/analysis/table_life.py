"""The fatigue life of a crack from K against crack size, without a mesh
(`cracklip life`): a table of K or beta from a file (one a cracklip grow
wrote, or a handbook's, or another code's) or a handbook solution, the
same growth laws, closure, retardation, spectra and stops as `cracklip
grow`, integrated by the compiled kernels (cracklip.fracture.life_kernels).

1. K per unit load of each load case against crack size: the table's
   columns (beta columns times the case's reference stress S and sqrt(pi
   a)), or the handbook's beta (cracklip.fracture.handbook) tabulated
   finely between a0 and the geometry's end (its K / sqrt(a) is then
   linear between close sizes: the tabulation error is reported);
   K at a load state is the sum over the cases of factor x K.
2. Cycles: one pass of the spectrum (its blocks, repeated) counted once
   on K at the initial size (rainflow, range-pair or valley-to-peak; the
   residue closed or counted in halves), as grow counts it on the load
   factor of a one-group spectrum.
3. Closure: "contact" -- without a mesh no lip contact is solved, so a
   state whose K would be negative has its lips closed at the tip and K_min
   is taken as 0 (exact for lips pressed together up to the tip; a table
   cracklip grow wrote with contact gives K > 0 wherever the lips are open);
   "newman" and "none" as in grow (linear K).
4. Stops, each found before the integration where it can be: the critical
   size (K_max of the spectrum's largest state reaching K_c, else the law's
   critical K; net-section yield for a handbook plate with a width and a
   yield stress: the gross stress at the largest state over the net section
   W / (W - 2a) of a centre crack, W / (W - a) of an edge crack, W / (W - 2R
   - n a) of n cracks at a hole, W t / (W t - area) of a surface or corner
   crack; two sizes: checked along the path, where the spectrum's largest
   load may not have come yet when the crack leaves the handbook's range),
   life.a_final, the end of the table or of the handbook's range
   (Newman-Raju: a/t < 0.8, c/b < 0.5, a/c <= 2, corner <= 1; a crack at a
   central hole: the plate's edge, (W - 2R) / 2, for one crack or two),
   arrest (a pass without growth), spectrum.max_passes.
5. Integration: cycle by cycle in the order the cycles close, pass after
   pass (retardation needs it: each point keeps its overload), or in
   blocks (no sequence effects): one size by Gauss-Legendre quadrature of
   da / (growth per pass) in ln a between the table's sizes, two sizes by
   Runge-Kutta in the passes.
6. Outputs: a-N in cycles, passes and blocks; the critical size and its
   criterion; the inspection threshold (half the life from a0 to failure)
   and interval (half the life from life.detectable_size to failure, a
   second life from that size when it is below a0).
"""
from __future__ import annotations

import dataclasses
import logging
import math
import os
import time
import typing

import numpy as np

from ..errors import InputError
from ..fracture import handbook
from ..fracture.life import CycleTable, LifeLaw
from ..fracture.laws import rate_table_reach
from ..fracture.life_kernels import (KTable, grow_blocks, growth_per_pass, integrate_cycles, new_run, passes_to,
                                     state_k_max)
from ..fracture.rainflow import count_cycles
from ..fracture.retardation import Retardation, constraint_beta
from ..scene.fatigue import FatigueMaterial
from ..scene.input_files import DEFAULT_CASE, KTableData
from ..scene.life import LifeSettings
from ..scene.spectrum import Spectrum
from ..scene.units import Units
from .life import create_law, critical_k, rate_table_messages

logger = logging.getLogger(__name__)

#: Sizes of a handbook solution's table (one size; two sizes: per direction).
HANDBOOK_POINTS, HANDBOOK_GRID = 16000, 321
#: Cycles per call of the cycle-by-cycle kernel between progress lines.
CHUNK = 20_000_000


@dataclasses.dataclass
class LoadCases:
    """The load of a life: the factor of each case at each load state.

    Attributes:
        cases: the load cases (the table's columns).
        F: (states, cases) factors.
        states: (states, groups) the spectrum's distinct factor rows.
        point_state: the state of each turning point of a pass.
        block_of_point: the block of each turning point.
    """
    cases: tuple[str, ...]
    F: np.ndarray
    states: np.ndarray
    point_state: np.ndarray
    block_of_point: np.ndarray


def load_cases(spectrum: Spectrum, cases: typing.Sequence[str], steady_cases: typing.Sequence[str] = ()) -> LoadCases:
    """F of each case: a spectrum group's column, a steady group's factor
    (spectrum.steady, default 1), a steady table case (residual K) at 1."""
    pts, owner = spectrum.pass_points()
    states, inverse = np.unique(pts, axis=0, return_inverse=True)
    F = np.zeros((len(states), len(cases)))
    groups = list(spectrum.groups)
    for j, g in enumerate(cases):
        if g in groups:
            F[:, j] = states[:, groups.index(g)]
        elif g in steady_cases:
            F[:, j] = 1.0
        else:
            F[:, j] = spectrum.steady.get(g, 1.0)
    return LoadCases(tuple(cases), F, states, inverse.ravel(), owner)


def k_table_from_file(data: KTableData, life: LifeSettings, spectrum: Spectrum) -> tuple[KTable, tuple[str, ...]]:
    """The compiled table of a file's K (beta columns times S sqrt(pi a))
    with its cases named after the spectrum's groups; the steady cases."""
    groups = list(spectrum.groups)
    names = dict()
    for case in data.values:
        if case == DEFAULT_CASE:
            if len(groups) != 1:
                raise InputError(f"life.table {data.source} has one column of K (or beta) for all loads, but "
                                 f"spectrum.groups has {len(groups)} groups {groups}: name the columns K_<group> "
                                 "(or beta_<group>)")
            names[case] = groups[0]
        else:
            names[case] = case
    missing = [g for g in groups if g not in names.values()]
    if missing:
        raise InputError(f"life.table {data.source} has no column for load group(s) {missing} of spectrum.groups; "
                         f"its columns: {sorted(names.values())}")
    used = [c for c in data.values if names[c] in groups or names[c] in spectrum.steady or c in data.steady]
    cases = tuple(names[c] for c in used)
    if data.kind == "beta" and data.reference_stress:
        # A table cracklip grow wrote says over which S its beta is: life.reference_stress must give the same
        # (left unset it was S = 1: K 100 times too small for S = 100, a life of 1e9 cycles or an arrest at a0).
        for c in used:
            S_file = data.reference_stress.get(c, next(iter(data.reference_stress.values()))
                                               if c == DEFAULT_CASE and len(data.reference_stress) == 1 else None)
            S = life.stress(names[c])
            if S_file is not None and not math.isclose(S, S_file, rel_tol=1e-9):
                raise InputError(f"life.table {data.source}: its beta of load group {names[c]!r} is K / (S sqrt(pi "
                                 f"a)) with S = {S_file:g} (the file's '# reference_stress' line: growth."
                                 f"reference_stress of the run that wrote it), but life.reference_stress gives S = "
                                 f"{S:g}" + (" (unset: 1)" if names[c] not in (life.reference_stress or {}) else "")
                                 + f": set life.reference_stress = {{ {names[c]} = {S_file:g} }} (the load factors "
                                 "of the spectrum scale it)")
    if data.sizes == 1:
        K = np.stack([_as_k(data.values[c], data.a, data.kind, life.stress(names[c])) for c in used], axis=1)
        return KTable(1, data.a, K, cases), tuple(data.steady)
    K = np.stack([data.values[c] * (math.sqrt(math.pi) * life.stress(names[c]) * np.sqrt(data.a)[:, None, None]
                                    if data.kind == "beta" else 1.0) for c in used], axis=-1)
    return KTable(2, data.a, K, cases, c=data.c), tuple(data.steady)


def _as_k(values: np.ndarray, a: np.ndarray, kind: str, S: float) -> np.ndarray:
    return values * S * np.sqrt(math.pi * a) if kind == "beta" else values


def handbook_end(life: LifeSettings) -> tuple[float, str]:
    """The largest size of the handbook table and why (the geometry's end)."""
    g = life.geometry
    if g == "centre_crack":
        return life.width / 2 * (1 - 1e-9), "the ligament (a = W / 2)"
    if g == "edge_crack":
        return life.width * (1 - 1e-9), "the ligament (a = W)"
    if g == "hole_crack":
        if life.width is not None:
            # The hole central: each crack (one or two) reaches its own edge of the plate at (W - 2R) / 2.
            return ((life.width - 2 * life.hole_radius) / 2 * (1 - 1e-9),
                    "the crack reaches the plate's edge: the ligament (W - 2R) / 2 beside the central hole")
        return max(100.0 * (life.a0 + life.hole_radius), life.a_final or 0.0), "100 (a0 + R): the table's end"
    return 0.8 * life.thickness * (1 - 1e-12), "Newman-Raju's range a/t < 0.8"


def handbook_table(life: LifeSettings, spectrum: Spectrum, a_lo: float) -> tuple[KTable, dict[str, typing.Any]]:
    """The handbook's K per unit factor of every load case, tabulated finely
    from a_lo to the geometry's end; info["check"]: sizes a halfway between
    the table's and the relative difference of the table's beta from the
    formula there (tabulation_error reports it over the sizes a life uses)."""
    cases = tuple(spectrum.groups) + tuple(g for g in spectrum.steady)
    S = np.array([life.stress(g) for g in cases])
    end, _ = handbook_end(life)
    if life.two_sizes:
        t, W = life.thickness, life.width
        corner = life.geometry == "corner_crack"
        b = W if corner else W / 2
        a = np.unique(np.r_[np.geomspace(a_lo, end, HANDBOOK_GRID), end - np.geomspace(end - a_lo, end * 1e-6,
                                                                                           40)])
        a = a[(a >= a_lo) & (a <= end)]
        c_end = 0.5 * b * (1 - 1e-12)
        c_lo = min(life.c0, a_lo) * 0.5
        c = np.unique(np.r_[np.geomspace(c_lo, c_end, HANDBOOK_GRID), life.c0])
        A, C = np.meshgrid(a, c, indexing="ij")
        ba, bc = handbook.surface_crack_beta(A, C, t, b, corner)
        root = np.sqrt(math.pi * A)
        K = np.stack([ba * root, bc * root], axis=2)[..., None] * S
        table = KTable(2, a, K, cases, c=c)
        am, cm = np.sqrt(a[1:] * a[:-1]), np.sqrt(c[1:] * c[:-1])
        Am, Cm = np.meshgrid(am, cm, indexing="ij")
        exact = handbook.surface_crack_beta(Am, Cm, t, b, corner)
        got = table.evaluate(Am.ravel(), Cm.ravel())[:, :, 0] / (S[0] * np.sqrt(math.pi * Am.ravel()))[:, None]
        inside = handbook.newman_raju_range(Am, Cm, t, b, corner).ravel()
        err = np.max(np.abs(got / np.stack([e.ravel() for e in exact], axis=1) - 1.0), axis=1)
        return table, {"points": [int(a.size), int(c.size)], "check": (Am.ravel(), np.where(inside, err, 0.0))}
    a = np.unique(np.r_[np.geomspace(a_lo, end, HANDBOOK_POINTS // 2),
                        end - np.geomspace(end - a_lo, max(end * 1e-7, 1e-300), HANDBOOK_POINTS // 2)])
    a = a[(a >= a_lo) & (a <= end)]
    beta = handbook_beta(life, a)
    K = (beta * np.sqrt(math.pi * a))[:, None] * S
    table = KTable(1, a, K, cases)
    mid = np.sqrt(a[1:] * a[:-1])
    got = table.evaluate(mid)[:, 0] / (S[0] * np.sqrt(math.pi * mid))
    err = np.abs(got / handbook_beta(life, mid) - 1.0)
    return table, {"points": int(a.size), "check": (mid, err)}


def tabulation_error(info: dict[str, typing.Any], a_end: float) -> float | None:
    """The largest relative difference of a handbook table from its formula
    up to the size a_end (None for a table from a file)."""
    if "check" not in info:
        return None
    a, err = info["check"]
    use = a <= a_end
    return float(np.max(err[use])) if np.any(use) else 0.0


def handbook_beta(life: LifeSettings, a: np.ndarray) -> np.ndarray:
    g = life.geometry
    if g == "centre_crack":
        return handbook.centre_crack(a, life.width, life.form)
    if g == "edge_crack":
        return handbook.edge_crack(a, life.width)
    return handbook.hole_crack(a, life.hole_radius, life.cracks)


def net_section_factor(life: LifeSettings, a, c=None):
    """Net-section stress over gross remote stress (module doc); None where
    the geometry has no width."""
    g, W = life.geometry, life.width
    if W is None or g == "beta_table":
        return None
    a = np.asarray(a, dtype=float)
    if g == "centre_crack":
        net = W - 2 * a
    elif g == "edge_crack":
        net = W - a
    elif g == "hole_crack":
        net = W - 2 * life.hole_radius - life.cracks * a
    else:
        area = math.pi * a * np.asarray(c, dtype=float) / (4.0 if g == "corner_crack" else 2.0)
        return W * life.thickness / np.maximum(W * life.thickness - area, 1e-300)
    return W / np.maximum(net, 1e-300)


@dataclasses.dataclass
class TableLife:
    """A life without a mesh, set up (inputs checked, K tabulated, cycles
    counted); run() integrates it."""
    life: LifeSettings
    material: FatigueMaterial
    spectrum: Spectrum
    law: LifeLaw
    table: KTable
    load: LoadCases
    cycles: CycleTable
    retardation: Retardation | None
    K_crit: float | None
    yield_stress: float | None
    table_info: dict[str, typing.Any]
    source: str
    clamp_min: bool
    units: Units | None = None

    @property
    def cycles_per_pass(self) -> float:
        return self.cycles.cycles

    @property
    def blocks_per_pass(self) -> int:
        return self.spectrum.blocks_per_pass

    @property
    def method(self) -> str:
        if self.life.integration != "auto":
            return self.life.integration
        return "cycles" if self.retardation is not None else "blocks"


def create_table_life(life: LifeSettings, material: FatigueMaterial, spectrum: Spectrum, units: Units | None = None,
                      table_data: KTableData | None = None) -> TableLife:
    """Set up a life (module doc, 1-3): every input checked, nothing integrated."""
    fm = material.converted(units)
    law = create_law(fm)
    if life.geometry == "beta_table":
        if table_data is None:
            raise InputError("life.geometry = 'beta_table' needs the table's data (life.table)")
        if table_data.sizes == 2 and life.c0 is None:
            raise InputError(f"life.table {table_data.source} is a table of two sizes (a, c): give life.c0")
        if table_data.sizes == 1 and life.c0 is not None:
            raise InputError(f"life.c0 is given but life.table {table_data.source} has one crack size")
        if table_data.units is not None and units is not None:
            mine = {"length": units.length, "stress": units.name("stress")}
            if mine != table_data.units:
                raise InputError(f"life.table {table_data.source} is in {table_data.units['length']} and "
                                 f"{table_data.units['stress']} (its '# units' line: the [units] of the run that wrote "
                                 f"it), but this scene's [units] are {mine['length']} and {mine['stress']}: its crack "
                                 "sizes and K would be read in the wrong units; give the scene the table's [units] "
                                 "(material.fatigue.units converts the law's constants)")
        table, steady = k_table_from_file(table_data, life, spectrum)
        info: dict[str, typing.Any] = {"points": int(table.a.size) if table.sizes == 1 else [int(table.a.size),
                                                                                             int(table.c.size)]}
        source = table_data.source
        if life.a0 < table.a[0] or life.a0 >= table.a[-1]:
            raise InputError(f"life.a0 = {life.a0:g} is outside the table's crack sizes [{table.a[0]:g}, "
                             f"{table.a[-1]:g}] ({source})")
        if table.sizes == 2 and not table.c[0] <= life.c0 < table.c[-1]:
            raise InputError(f"life.c0 = {life.c0:g} is outside the table's sizes c [{table.c[0]:g}, "
                             f"{table.c[-1]:g}] ({source})")
        if life.detectable_size is not None and life.detectable_size < table.a[0]:
            raise InputError(f"life.detectable_size = {life.detectable_size:g} is below the table's smallest crack "
                             f"size {table.a[0]:g} ({source})")
    else:
        a_lo = min(life.a0, life.detectable_size or life.a0)
        table, info = handbook_table(life, spectrum, a_lo)
        steady = ()
        source = handbook.SOURCES[life.geometry]
        if life.two_sizes and not handbook.newman_raju_range(life.a0, life.c0, life.thickness,
                                                             life.width if life.geometry == "corner_crack"
                                                             else life.width / 2, life.geometry == "corner_crack"):
            raise InputError(f"life.a0 = {life.a0:g}, life.c0 = {life.c0:g} is outside Newman-Raju's range "
                             "(0 < a/c <= 2, corner <= 1; a/t < 0.8; c/b < 0.5)")
    _check_reference_stress(life, spectrum, table_data if life.geometry == "beta_table" else None)
    load = load_cases(spectrum, table.cases, steady)
    # Count one pass on K at the initial size (point 0).
    K0 = table.evaluate(life.a0) if table.sizes == 1 else table.evaluate(life.a0, life.c0)[:, 0]
    K_states = load.F @ K0[0]
    values = K_states[load.point_state]
    if np.ptp(values) <= 0.0:
        raise InputError("the spectrum gives the same K at every turning point: no cycle to count")
    ct = count_cycles(values, spectrum.counting, repeated=spectrum.residue == "close")
    cycles = CycleTable(load.point_state[ct.lo], load.point_state[ct.hi], ct.count, load.block_of_point[ct.hi])
    K_c = critical_k(fm, law)
    if fm.retardation != "none" and life.integration == "blocks":
        raise InputError(f"life.integration = 'blocks' sums the growth of a pass without sequence effects, but "
                         f"material.fatigue.retardation = {fm.retardation!r} needs them: use 'cycles' or 'auto'")
    ret = None
    if fm.retardation != "none":
        beta = constraint_beta(fm.constraint, fm.thickness, fm.K_Ic, fm.yield_stress)
        ret = Retardation(fm.retardation, fm.yield_stress, beta, fm.wheeler_exponent or 1.0, fm.shutoff_ratio or 3.0)
    return TableLife(life, fm, spectrum, law, table, load, cycles, ret, K_c, fm.yield_stress, info, source,
                     law.closure == "contact", units)


def _check_reference_stress(life: LifeSettings, spectrum: Spectrum, data: KTableData | None) -> None:
    """life.reference_stress must name load groups of the life (a group it
    does not name has S = 1, so a misspelt or renamed group would silently
    scale K by 1 / S) and must scale something (a table of K per unit
    factor takes no S)."""
    named = sorted(life.reference_stress or {})
    if not named:
        return
    if data is not None and data.kind == "K":
        raise InputError(f"life.reference_stress {life.reference_stress} scales beta columns and handbook "
                         f"solutions, but life.table {data.source} gives K per unit load factor (K columns): "
                         "remove life.reference_stress, or give the table as beta columns")
    groups = list(spectrum.groups) + [g for g in spectrum.steady if g not in spectrum.groups]
    unknown = [g for g in named if g not in groups]
    if unknown:
        import difflib
        near = difflib.get_close_matches(unknown[0], groups, n=1, cutoff=0.0)
        raise InputError(f"life.reference_stress names load group(s) {unknown} that the life has no load for (a "
                         f"group left out has S = 1); its load groups (spectrum.groups, spectrum.steady): {groups}"
                         + (f"; did you mean {near[0]!r}?" if near else ""))


@dataclasses.dataclass
class LifeResult:
    """What a life without a mesh gives.

    Attributes:
        rows: the a-N table: a (and c), cycles, passes, blocks, K_max of the
            largest load state at the deepest point (and at the surface).
        stop, stop_reason: the criterion that ended the life and a sentence.
        critical: the critical size: {"a", "c", "criterion"} (None: not
            reached before the end of the table or of the handbook's range).
        inspection: threshold and interval (module doc) or None.
        method: "cycles" or "blocks"; seconds; cycles_per_second (cycles).
        warnings: what makes the life doubtful (a tabular da/dN read
            outside its data), one sentence each.
    """
    rows: list[dict[str, typing.Any]]
    stop: str
    stop_reason: str
    critical: dict[str, typing.Any] | None
    inspection: dict[str, typing.Any] | None
    method: str
    seconds: float
    cycles_per_second: float | None = None
    warnings: list[str] = dataclasses.field(default_factory=list)

    @property
    def cycles(self) -> float:
        return self.rows[-1]["cycles"]

    @property
    def passes(self) -> float:
        return self.rows[-1]["passes"]

    @property
    def blocks(self) -> float:
        return self.rows[-1]["blocks"]


def critical_size(tl: TableLife) -> tuple[float | None, str | None]:
    """One size: the smallest a >= a0 where K_max of the largest state
    reaches K_crit or the net section yields (bisection between the table's
    sizes); (None, None) if neither happens within the table."""
    life, table = tl.life, tl.table
    a = table.a[table.a >= life.a0]
    a = np.r_[life.a0, a[a > life.a0]]
    best: tuple[float | None, str | None] = (None, None)
    tests = []
    if tl.K_crit is not None and math.isfinite(tl.K_crit):
        tests.append(("K_max >= K_c", lambda x: float(state_k_max(table, tl.load.F, [x])[0]) / tl.K_crit - 1.0))
    factor = net_section_factor(life, a)
    if factor is not None and tl.yield_stress is not None:
        S_max = float(np.max(tl.load.F @ np.array([life.stress(g) for g in tl.load.cases])))
        tests.append(("net-section yield",
                      lambda x: S_max * float(net_section_factor(life, x)) / tl.yield_stress - 1.0))
    for name, f in tests:
        vals = np.array([f(x) for x in a])
        hit = np.flatnonzero(vals >= 0.0)
        if not hit.size:
            continue
        i = int(hit[0])
        if i == 0:
            x = float(a[0])
        else:
            lo, hi = float(a[i - 1]), float(a[i])
            for _ in range(100):
                mid = 0.5 * (lo + hi)
                if f(mid) >= 0.0:
                    hi = mid
                else:
                    lo = mid
                if hi - lo <= 1e-14 * hi:
                    break
            x = hi
        if best[0] is None or x < best[0]:
            best = (x, name)
    return best


def run_life(tl: TableLife, progress: typing.Callable[[str], None] | None = None,
             a0: float | None = None) -> LifeResult:
    """Integrate a life set up by create_table_life (module doc, 4-6)."""
    t0 = time.perf_counter()
    if tl.table.sizes == 2:
        out = _run_two(tl, progress)
    else:
        out = _run_one(tl, progress, tl.life.a0 if a0 is None else a0)
    out.seconds = time.perf_counter() - t0
    if a0 is None:
        out.inspection = _inspection(tl, out, progress)
        out.warnings = rate_table_warnings(tl, out)
    return out


def rate_table_warnings(tl: TableLife, out: LifeResult) -> list[str]:
    """A tabular da/dN read outside its data by the life's cycles (at the
    sizes of the a-N table): Delta K above a curve's last row (its last
    log-log segment extended: a table in other units than the scene's K
    lands there) and R outside the table's span (the nearest curve)."""
    law = tl.law.law
    if law.name != "tabular":
        return []
    cyc = tl.cycles.unique()
    dks, Rs = [], []
    for row in out.rows:
        if tl.table.sizes == 1:
            K = tl.table.evaluate(row["a"])[0][None]
        else:
            K = tl.table.evaluate(row["a"], row["c"])[0]
        for Kp in K:  # each point of the crack
            Ks = tl.load.F @ Kp
            km, kn = Ks[cyc.hi], Ks[cyc.lo]
            if tl.clamp_min:
                kn = np.maximum(kn, 0.0)
            dk, R = tl.law.effective(km, kn)
            grow = (km > 0.0) & (dk > tl.law.threshold)
            dks.append(dk[grow])
            Rs.append(R[grow])
    return rate_table_messages(rate_table_reach(law.table, np.concatenate(dks), np.concatenate(Rs)), tl.material,
                               tl.units, "the life's cycles")


def _stop_of_end(tl: TableLife, a_crit, crit, end_table) -> tuple[float, str, str]:
    """Where a one-size life ends before integrating, and why."""
    life = tl.life
    ends = []  # failure first, then a_final, then the table's end: the first of equal sizes names the stop
    if a_crit is not None:
        ends.append((a_crit, crit, "final failure: " + ("K_max reached K_c = " + f"{tl.K_crit:.6g}"
                                                           if crit == "K_max >= K_c" else
                                                           f"the net section reached the yield stress "
                                                           f"{tl.yield_stress:.6g}") + f" at a = {a_crit:.6g}"))
    if life.a_final is not None:
        ends.append((life.a_final, "a_final", f"life.a_final = {life.a_final:g} reached"))
    ends.append((end_table[0], "end of the table", end_table[1]))
    a_end, stop, reason = min(ends, key=lambda e: e[0])
    if stop == "end of the table":
        reason += short_of_a_final(life, a_end)
    return a_end, stop, reason


def short_of_a_final(life: LifeSettings, a_end: float) -> str:
    """What a life that ends at a_end (the end of its table or of the
    handbook's range) adds to its stop when life.a_final was asked for
    (else nothing): a_final not reached."""
    if life.a_final is None:
        return ""
    shown = f"{a_end:.6g}"
    if float(shown) >= life.a_final:
        # (a table cracklip grow wrote ends at 25.4999998 for 16 steps of 1.5 mm: "the life is to a = 25.5, not
        # reached" read as a contradiction)
        shown = f"{a_end:.10g}, {life.a_final - a_end:.2g} short of it"
    return f", before life.a_final = {life.a_final:g} (not reached: the life is to a = {shown})"


def _row(tl: TableLife, a: float, cycles: float, passes: float, c: float | None = None) -> dict[str, typing.Any]:
    row = {"a": a}
    if c is not None:
        row["c"] = c
    K = state_k_max(tl.table, tl.load.F, [a] if c is None else [a, c])
    row.update({"cycles": cycles, "passes": passes, "blocks": passes * tl.blocks_per_pass, "K_max": float(K[0])})
    if c is not None:
        row["K_max_c"] = float(K[1])
    return row


def _run_one(tl: TableLife, progress, a0: float) -> LifeResult:
    life, table = tl.life, tl.table
    a_crit, crit = critical_size(tl)
    if table.sizes == 1 and life.geometry != "beta_table":
        end_table = (table.a[-1], "the handbook table ends at a = " + f"{table.a[-1]:.6g} "
                     f"({handbook_end(life)[1]})")
    else:
        end_table = (table.a[-1], f"the table ends at a = {table.a[-1]:.6g}")
    a_end, stop, reason = _stop_of_end(tl, a_crit, crit, end_table)
    critical = {"a": a_crit, "criterion": crit} if a_crit is not None else None
    if a_crit is not None and a_crit <= a0:
        # Critical at the start: the first largest load breaks the part. Say by how much (a K_Ic in MPa sqrt(m)
        # read by a scene in mm is 31.6 times too small), and that the critical size is a0 or below.
        rows = [_row(tl, a0, 0.0, 0.0)]
        critical["at_initial_size"] = True
        unit = f" {tl.units.name('K')}" if tl.units is not None else ""
        if crit == "K_max >= K_c":
            what = (f"K_max = {rows[0]['K_max']:.6g}{unit} of the spectrum's largest load state reaches K_c = "
                    f"{tl.K_crit:.6g}{unit} (material.fatigue.K_Ic, K_c(t) or the law's critical K: check its "
                    "value and units)")
        else:
            S_max = float(np.max(tl.load.F @ np.array([life.stress(g) for g in tl.load.cases])))
            what = (f"the net-section stress {S_max * float(net_section_factor(life, a0)):.6g} of the spectrum's "
                    f"largest load state reaches the yield stress {tl.yield_stress:.6g}")
        return LifeResult(rows, stop, f"no life: the initial crack a0 = {a0:g} is already critical: {what}",
                          critical, None, tl.method, 0.0)
    if not a_end > a0:
        rows = [_row(tl, a0, 0.0, 0.0)]
        return LifeResult(rows, stop, reason + f" (at or below the initial size {a0:g}: no life)", critical, None,
                          tl.method, 0.0)
    grid = np.geomspace(a0, a_end, life.points)
    if life.detectable_size is not None and a0 < life.detectable_size < a_end:
        grid = np.unique(np.r_[grid, life.detectable_size])
    grid[-1] = a_end
    max_passes = tl.spectrum.max_passes
    if tl.method == "blocks":
        P = passes_to(table, tl.load.F, tl.cycles.unique(), tl.law, grid, tl.clamp_min)
        ok = np.isfinite(P) & (P <= max_passes)
        if not ok.all():
            k = int(np.flatnonzero(~ok)[0])
            if not np.isfinite(P[k]):
                # The a-N table ends where the crack stops: at the arrest size, after the passes to it (the last
                # grid size before it understated them: 11510 of 11848 cycles in tests/test_table_life.py).
                a_grow, a_arr = _arrest_size(tl, grid[k - 1], grid[k])
                P_arr = float(P[k - 1]) + float(passes_to(table, tl.load.F, tl.cycles.unique(), tl.law,
                                                          np.array([grid[k - 1], a_grow]), tl.clamp_min)[1])
                if P_arr <= max_passes:
                    rows = [_row(tl, float(x), float(p) * tl.cycles_per_pass, float(p))
                            for x, p in zip(grid[:k], P[:k])]
                    if a_grow > grid[k - 1]:
                        rows.append(_row(tl, a_grow, P_arr * tl.cycles_per_pass, P_arr))
                    return LifeResult(rows, "arrest", f"growth arrested: the growth per pass falls to 0 at a = "
                                      f"{a_arr:.6g} (below the threshold)", critical, None, "blocks", 0.0)
                P = np.r_[P[:k], P_arr]
                grid = np.r_[grid[:k], a_grow]
            # The crack size where the passes reach max_passes, inside (grid[k - 1], grid[k]): the life is
            # max_passes there (the last grid size before it would understate both).
            a_mp = _size_at_passes(tl, grid[k - 1], float(P[k - 1]), grid[k], max_passes)
            rows = [_row(tl, float(x), float(p) * tl.cycles_per_pass, float(p)) for x, p in zip(grid[:k], P[:k])]
            rows.append(_row(tl, a_mp, max_passes * tl.cycles_per_pass, max_passes))
            return LifeResult(rows, "max_passes", f"spectrum.max_passes = {max_passes:g} reached at a = "
                              f"{a_mp:.6g}", critical, None, "blocks", 0.0)
        rows = [_row(tl, float(x), float(p) * tl.cycles_per_pass, float(p)) for x, p in zip(grid, P)]
        return LifeResult(rows, stop, reason, critical, None, "blocks", 0.0)
    run = new_run([a0])
    rows = [_row(tl, a0, 0.0, 0.0)]
    n = len(tl.cycles.lo)
    t_start = time.perf_counter()
    last = t_start
    for target in grid[1:]:
        while True:
            run = integrate_cycles(table, tl.load.F, tl.cycles, tl.law, tl.retardation, run, [target], tl.K_crit,
                                   max_passes, CHUNK, tl.clamp_min)
            now = time.perf_counter()
            if progress is not None and now - last >= 1.0:
                last = now
                progress(f"a = {run['size'][0]:.6g}, N = {run['cycles']:.6g} cycles = "
                         f"{_passes(run, n) * tl.blocks_per_pass:.6g} {tl.spectrum.block_name}s, "
                         f"{run['cycles'] / max(now - t_start, 1e-9):.3g} cycles/s")
            if run["stop"] != "paused":
                break
        passes = _passes(run, n)
        if run["stop"] == "reached":
            rows.append(_row(tl, float(run["size"][0]), run["cycles"], passes))
            continue
        rows.append(_row(tl, float(run["size"][0]), run["cycles"], passes))
        speed = run["cycles"] / max(time.perf_counter() - t_start, 1e-9)
        if run["stop"] == "failure":
            return LifeResult(rows, "K_max >= K_c", f"final failure: a cycle's K_max = {run['K_max']:.6g} reached "
                              f"K_c at a = {run['size'][0]:.6g}", critical, None, "cycles", 0.0, speed)
        if run["stop"] == "arrest":
            return LifeResult(rows, "arrest", f"growth arrested at a = {run['size'][0]:.6g}: a whole pass without "
                              "growth (below the threshold, or retarded to a standstill)", critical, None, "cycles",
                              0.0, speed)
        return LifeResult(rows, "max_passes", f"spectrum.max_passes = {max_passes:g} reached at a = "
                          f"{run['size'][0]:.6g}", critical, None, "cycles", 0.0, speed)
    speed = run["cycles"] / max(time.perf_counter() - t_start, 1e-9)
    return LifeResult(rows, stop, reason, critical, None, "cycles", 0.0, speed)


def _passes(run: dict, n: int) -> float:
    return run["pass"] + run["entry"] / max(n, 1)


def _size_at_passes(tl: TableLife, a_lo: float, P_lo: float, a_hi: float, target: float) -> float:
    """The size between a_lo (P_lo passes from the start) and a_hi (more than
    target passes) at which the blocks integration reaches target passes
    (bisection in ln a)."""
    cyc = tl.cycles.unique()
    lo, hi = a_lo, a_hi
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        if not lo < mid < hi:
            break
        P = P_lo + float(passes_to(tl.table, tl.load.F, cyc, tl.law, np.array([a_lo, mid]), tl.clamp_min)[1])
        if P <= target:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-14 * hi:
            break
    return lo


def _arrest_size(tl: TableLife, lo: float, hi: float) -> tuple[float, float]:
    """(the last size that grows, the first that does not) between lo and hi
    (bisection to the last bit)."""
    cyc = tl.cycles.unique()
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        if growth_per_pass(tl.table, tl.load.F, cyc, tl.law, [mid], tl.clamp_min)[0] > 0.0:
            lo = mid
        else:
            hi = mid
    return lo, hi


def _run_two(tl: TableLife, progress) -> LifeResult:
    """Two sizes (a, c): blocks by RK4 or cycle by cycle; the handbook's
    range, net-section yield and life.a_final checked along the path."""
    life, table = tl.life, tl.table
    corner = life.geometry == "corner_crack"
    a_end = min(table.a[-1], life.a_final or math.inf)
    c_end = table.c[-1]
    n = len(tl.cycles.lo)
    if tl.method == "blocks":
        path = grow_blocks(table, tl.load.F, tl.cycles.unique(), tl.law, life.a0, life.c0, (a_end, c_end),
                           tl.K_crit, tl.spectrum.max_passes, clamp_min=tl.clamp_min)
        P, A, C, stop, speed = path["passes"], path["a"], path["c"], path["stop"], None
        cycles = P * tl.cycles_per_pass
    else:
        run = new_run([life.a0, life.c0])
        P, A, C, cyc = [0.0], [life.a0], [life.c0], [0.0]
        t_start = last = time.perf_counter()
        steps = np.geomspace(life.a0, a_end, life.points)[1:]
        k = 0
        while True:
            target = steps[min(k, len(steps) - 1)]
            run = integrate_cycles(table, tl.load.F, tl.cycles, tl.law, tl.retardation, run, [target, c_end],
                                   tl.K_crit, tl.spectrum.max_passes, min(CHUNK, 1e6), tl.clamp_min)
            P.append(_passes(run, n))
            A.append(run["size"][0])
            C.append(run["size"][1])
            cyc.append(run["cycles"])
            now = time.perf_counter()
            if progress is not None and now - last >= 1.0:
                last = now
                progress(f"a = {A[-1]:.6g}, c = {C[-1]:.6g}, N = {cyc[-1]:.6g} cycles")
            if run["stop"] == "reached" and run["point"] == 0 and A[-1] < a_end:
                k += 1
                continue
            if run["stop"] == "paused" and not _outside(life, A[-1], C[-1], corner):
                continue
            break
        stop = {"reached": "reached", "paused": "reached"}.get(run["stop"], run["stop"])
        P, A, C, cycles = np.asarray(P), np.asarray(A), np.asarray(C), np.asarray(cyc)
        speed = cycles[-1] / max(time.perf_counter() - t_start, 1e-9)
    # Along the path: the handbook's range, K_c under the spectrum's largest load, net-section yield.
    k_cut, why, crit = len(A), None, None
    P, A, C, cycles = (np.array(v, dtype=float) for v in (P, A, C, cycles))
    for i in range(1, len(A)):
        if life.geometry != "beta_table" and _outside(life, A[i], C[i], corner):
            k_cut, why = i, "the handbook's range"
            break
        t = _critical_between(tl, (A[i - 1], C[i - 1]), (A[i], C[i]))
        if t is not None:
            # The largest load of the spectrum would fail the part here (as a one-size life's critical_size);
            # cycle by cycle that load may not have come yet when the crack leaves the handbook's range.
            for v in (P, A, C, cycles):
                v[i] = v[i - 1] + t * (v[i] - v[i - 1])
            k_cut, why, crit = i, "K_max >= K_c", "K_max >= K_c"
            break
        f = net_section_factor(life, A[i], C[i])
        if f is not None and tl.yield_stress is not None:
            S_max = float(np.max(tl.load.F @ np.array([life.stress(g) for g in tl.load.cases])))
            if S_max * float(f) >= tl.yield_stress:
                k_cut, why, crit = i, "net-section yield", "net-section yield"
                break
    rows = [_row(tl, float(A[i]), float(cycles[i]), float(P[i]), float(C[i])) for i in range(min(k_cut + 1, len(A)))]
    critical = None
    if why == "K_max >= K_c":
        stop_name = "K_max >= K_c"
        reason = (f"final failure: K_max under the spectrum's largest load reached K_c = {tl.K_crit:.6g} at a = "
                  f"{A[k_cut]:.6g}, c = {C[k_cut]:.6g}")
        critical = {"a": float(A[k_cut]), "c": float(C[k_cut]), "criterion": crit}
    elif why == "net-section yield":
        stop_name, reason = "net-section yield", (f"final failure: the net section reached the yield stress "
                                                  f"{tl.yield_stress:.6g} at a = {A[k_cut]:.6g}, c = {C[k_cut]:.6g}")
        critical = {"a": float(A[k_cut]), "c": float(C[k_cut]), "criterion": crit}
    elif why is not None:
        stop_name, reason = "handbook range", (f"the crack left Newman-Raju's range (a/c <= {1 if corner else 2}, "
                                               f"a/t < 0.8, c/b < 0.5) at a = {A[k_cut]:.6g}, c = {C[k_cut]:.6g}"
                                               + short_of_a_final(life, float(A[k_cut])))
    elif stop == "failure":
        stop_name = "K_max >= K_c"
        reason = f"final failure: K_max reached K_c = {tl.K_crit:.6g} at a = {A[-1]:.6g}, c = {C[-1]:.6g}"
        critical = {"a": float(A[-1]), "c": float(C[-1]), "criterion": stop_name}
    elif stop == "reached":
        if life.a_final is not None and A[-1] >= life.a_final * (1 - 1e-12):
            stop_name, reason = "a_final", f"life.a_final = {life.a_final:g} reached"
        else:
            stop_name, reason = "end of the table", (f"the table ends at a = {table.a[-1]:.6g}, c = "
                                                     f"{table.c[-1]:.6g}" + short_of_a_final(life, float(A[-1])))
    elif stop == "arrest":
        stop_name, reason = "arrest", f"growth arrested at a = {A[-1]:.6g}, c = {C[-1]:.6g}"
    else:
        stop_name, reason = "max_passes", f"spectrum.max_passes = {tl.spectrum.max_passes:g} reached"
    return LifeResult(rows, stop_name, reason, critical, None, tl.method, 0.0, speed)


def _critical_between(tl: TableLife, s0: tuple[float, float], s1: tuple[float, float]) -> float | None:
    """Where between two sizes (a, c) of a path K_max of the spectrum's
    largest load state first reaches K_crit at either point, as the fraction
    t of the step (linear in the larger ratio K / K_crit; 0 if already at
    s0); None if it does not by s1."""
    if tl.K_crit is None or not math.isfinite(tl.K_crit):
        return None
    r1 = float(np.max(state_k_max(tl.table, tl.load.F, list(s1)))) / tl.K_crit - 1.0
    if r1 < 0.0:
        return None
    r0 = float(np.max(state_k_max(tl.table, tl.load.F, list(s0)))) / tl.K_crit - 1.0
    return 0.0 if r0 >= 0.0 else r0 / (r0 - r1)


def _outside(life: LifeSettings, a: float, c: float, corner: bool) -> bool:
    if life.geometry == "beta_table":
        return False
    b = life.width if corner else life.width / 2
    return not bool(handbook.newman_raju_range(a, c, life.thickness, b, corner))


FAILURES = ("K_max >= K_c", "net-section yield")


def _inspection(tl: TableLife, out: LifeResult, progress) -> dict[str, typing.Any] | None:
    """Threshold (half the life from a0) and interval (half the life from the
    detectable size) to the end of the life; None without a detectable size
    or when the life did not end in failure."""
    life = tl.life
    if life.detectable_size is None:
        return None
    a_det = life.detectable_size
    end = out.rows[-1]
    info = {"detectable_size": a_det, "end": out.stop, "failure": out.stop in FAILURES,
            "threshold_cycles": 0.5 * end["cycles"], "threshold_blocks": 0.5 * end["blocks"]}
    if a_det >= end["a"]:
        info.update({"interval_cycles": None, "interval_blocks": None,
                     "note": f"the detectable size {a_det:g} is not below the end of the life a = {end['a']:.6g}"})
        return info
    if a_det >= life.a0:
        a = np.array([r["a"] for r in out.rows])
        N = np.array([r["cycles"] for r in out.rows])
        B = np.array([r["blocks"] for r in out.rows])
        N_det, B_det = float(np.interp(a_det, a, N)), float(np.interp(a_det, a, B))
        rest_N, rest_B = end["cycles"] - N_det, end["blocks"] - B_det
    else:
        second = run_life(tl, progress, a0=a_det)
        rest_N, rest_B = second.cycles, second.blocks
    info.update({"interval_cycles": 0.5 * rest_N, "interval_blocks": 0.5 * rest_B,
                 "life_from_detectable_cycles": rest_N, "life_from_detectable_blocks": rest_B})
    if not info["failure"]:
        info["note"] = (f"the life ended by {out.stop}, not by failure: the threshold and interval are half the "
                        "lives to that end")
    return info


def summary(tl: TableLife, out: LifeResult) -> dict[str, typing.Any]:
    """The life's summary for results.json."""
    fm = tl.material
    return {
        "geometry": tl.life.geometry, "geometry_description": tl.life.describe(), "K_source": tl.source,
        "K_table": {"points": tl.table_info["points"],
                    "tabulation_error": tabulation_error(tl.table_info, out.rows[-1]["a"])},
        "law": tl.law.law.describe(), "closure": tl.law.closure,
        "closure_note": ("no contact is solved without a mesh: K_min = max(K_min, 0) (lips closed at the tip)"
                         if tl.clamp_min else "linear K" + (", Newman's f(R)" if tl.law.closure == "newman" else "")),
        "retardation": fm.retardation, "material_source": fm.source, "K_crit": tl.K_crit,
        "yield_stress": tl.yield_stress, "counting": tl.spectrum.counting, "residue": tl.spectrum.residue,
        "load_states": int(len(tl.load.states)), "load_cases": list(tl.load.cases),
        "cycles_per_pass": tl.cycles_per_pass, "blocks_per_pass": tl.blocks_per_pass,
        "block_name": tl.spectrum.block_name, "integration": out.method,
        "cycles": out.cycles, "passes": out.passes, "blocks": out.blocks, "a_end": out.rows[-1]["a"],
        "stop": out.stop, "stop_reason": out.stop_reason, "critical": out.critical, "inspection": out.inspection,
        "seconds": out.seconds, "cycles_per_second": out.cycles_per_second, "warnings": list(out.warnings),
    }


def life_of(life_file, progress: typing.Callable[[str], None] | None = None
            ) -> tuple[TableLife, LifeResult, dict[str, typing.Any]]:
    """Set up and integrate the life of a life scene read by
    cl.load_life_file (its life, material, spectrum, units and table):
    (the set-up, the result, its summary); `cracklip life` and cl.life."""
    setup = create_table_life(life_file.life, life_file.material, life_file.spectrum, life_file.units,
                              life_file.table)
    logger.info("life: %s; K from %s; %.6g cycles and %d %ss per pass, %d load states; integration %s",
                life_file.life.describe(), setup.source, setup.cycles_per_pass, setup.blocks_per_pass,
                setup.spectrum.block_name, len(setup.load.states), setup.method)
    result = run_life(setup, progress=progress)
    return setup, result, summary(setup, result)


def life(life_file, progress: typing.Callable[[str], None] | None = None) -> dict[str, typing.Any]:
    """The fatigue life of a life scene without a mesh, as `cracklip life`
    integrates it (docs/life.md): life_file is cl.load_life_file(path,
    overrides)'s; progress, if given, receives a line of text now and then
    on a long cycle-by-cycle life. Returns what results.json holds under
    "life": cycles, passes, blocks, a_end, stop, stop_reason, critical,
    inspection, warnings, the law, closure and K source, ... and "rows",
    the a-N history (a, and c for a two-size crack, cycles, passes, blocks,
    K_max)."""
    if not all(hasattr(life_file, k) for k in ("life", "material", "spectrum", "units", "table")):
        raise InputError(f"life() takes a life scene read by cl.load_life_file(path), got {life_file!r}"
                         + (": life(cl.load_life_file(path))" if isinstance(life_file, (str, os.PathLike)) else ""))
    _, result, out = life_of(life_file, progress)
    out["rows"] = [dict(r) for r in result.rows]
    return out


__all__ = ["LoadCases", "load_cases", "TableLife", "create_table_life", "LifeResult", "critical_size", "run_life",
           "rate_table_warnings", "summary", "net_section_factor", "handbook_table", "tabulation_error", "life_of",
           "life"]
