"""The compiled life kernels (cpp/life) from Python: a LifeLaw and a
Retardation as their C++ counterparts (made once per law: a tabular law's
table is converted once and kept), tables of K against crack size, and the
integrations -- cycle by cycle (with Wheeler or Willenborg) and in blocks
(the growth per pass of the distinct cycles, no sequence effects).

Load: K of point p (one for a through crack; the deepest and the surface
point of a surface crack) at load state s is sum_g F[s, g] K_pg(sizes), F
the factor of each load case g at each state. Cycles are pairs of states
(lo, hi) with a count (0.5, 1, or n cycles in a row), in the order they
close (cracklip.fracture.life.CycleTable). clamp_min: K_min = max(K_min, 0)
(a tip whose lips close carries no negative K: the contact closure of a
life on a table of linear K).
"""
from __future__ import annotations

import dataclasses
import functools
import math
import typing

import numpy as np

from .. import _cracklip
from ..errors import InputError
from .life import CycleTable, LifeLaw
from .retardation import Retardation

#: Why a cycle-by-cycle run or a block run stopped (the kernels' codes).
STOPS = ("reached", "failure", "arrest", "max_passes", "paused")


@functools.lru_cache(maxsize=64)
def compiled_law(law: LifeLaw) -> "_cracklip.GrowthLaw":
    """The C++ GrowthLaw of a LifeLaw (the same formulas; kept per law)."""
    g = law.law
    k: dict[str, float] = {"threshold": float(law.threshold), "alpha": float(law.alpha),
                           "smax_over_flow": float(law.smax_over_flow)}
    table: tuple[list, list, list] = ([], [], [])
    if g.name == "paris":
        k.update(C=g.C, m=g.m)
    elif g.name == "walker":
        k.update(C=g.C, m=g.m, gamma=g.gamma)
    elif g.name == "forman":
        k.update(C=g.C, n=g.n, K_f=g.K_f)
    elif g.name == "nasgro":
        c = g.constants
        k.update(C=c.C, n=c.n, p=c.p, q=c.q, dK1=c.dK1, C_th_plus=c.C_th_plus, C_th_minus=c.C_th_minus,
                 alpha=c.alpha, smax_over_flow=c.smax_over_flow, a0=c.a0, K_crit=c.K_crit)
    elif g.name == "hartman_schijve":
        k.update(D=g.D, dK_thr=g.dK_thr, A=g.A, exponent=g.alpha)
    elif g.name == "tabular":
        t = g.table
        table = (list(t.R), list(t.dadn), list(np.asarray(t.delta_K, dtype=float).ravel()))
    else:  # pragma: no cover - every law of cracklip.fracture.laws is listed
        raise InputError(f"no compiled form of the {g.name} law")
    return _cracklip.GrowthLaw(g.name, law.closure, {a: float(b) for a, b in k.items()}, *table)


def compiled_retardation(ret: Retardation | None) -> "_cracklip.Retardation":
    if ret is None or ret.model == "none":
        return _cracklip.Retardation("none")
    return _cracklip.Retardation(ret.model, ret.sigma_ys, ret.beta, ret.gamma, ret.shutoff)


@dataclasses.dataclass
class KTable:
    """K per unit load against crack size(s), compiled.

    Attributes:
        sizes: 1 (a) or 2 (a, c).
        a, c: the table's sizes (ascending).
        K: one size (n, cases); two sizes (na, nc, 2, cases) (point 0 the
            deepest, grows a; point 1 the surface, grows c).
        cases: the load case of each column.
        native: the C++ table.
    """
    sizes: int
    a: np.ndarray
    K: np.ndarray
    cases: tuple[str, ...]
    c: np.ndarray | None = None
    native: typing.Any = None

    def __post_init__(self):
        self.a = np.ascontiguousarray(self.a, dtype=float)
        self.K = np.ascontiguousarray(self.K, dtype=float)
        if self.sizes == 1:
            self.native = _cracklip.KTable1(self.a.tolist(), self.K)
        else:
            self.c = np.ascontiguousarray(self.c, dtype=float)
            self.native = _cracklip.KTable2(self.a.tolist(), self.c.tolist(), self.K)

    def evaluate(self, a, c=None) -> np.ndarray:
        """K at the sizes: one size (n, cases); two sizes (n, 2, cases)."""
        a = np.atleast_1d(np.asarray(a, dtype=float))
        if self.sizes == 1:
            return self.native.evaluate(a)
        return self.native.evaluate(a, np.atleast_1d(np.asarray(c, dtype=float)))


def cycle_arrays(cycles: CycleTable) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return (np.ascontiguousarray(cycles.lo, dtype=np.int64), np.ascontiguousarray(cycles.hi, dtype=np.int64),
            np.ascontiguousarray(cycles.count, dtype=float))


def new_run(sizes: typing.Sequence[float]) -> dict[str, typing.Any]:
    """The start of a cycle-by-cycle run at the given sizes (no overload yet)."""
    s = (float(sizes[0]), float(sizes[1]) if len(sizes) > 1 else 0.0)
    none = (-math.inf, 0.0, 0.0)
    return {"size": s, "cycles": 0.0, "pass": 0, "entry": 0, "done": 0, "state": (none, none), "pass_start": s}


def integrate_cycles(table: KTable, F: np.ndarray, cycles: CycleTable, law: LifeLaw, ret: Retardation | None,
                     run: dict, size_end: typing.Sequence[float], K_crit: float | None = None,
                     max_passes: float = math.inf, max_cycles: float = math.inf, clamp_min: bool = False) -> dict:
    """Cycle by cycle from `run` (new_run) until a size reaches size_end (one
    per size), K_max reaches K_crit, arrest, max_passes or max_cycles (then
    resume with the returned run); run["stop"] names why (STOPS)."""
    lo, hi, n = cycle_arrays(cycles)
    limits = {"size_end": tuple(float(x) for x in size_end) + (math.inf,) * (2 - len(size_end)),
              "K_crit": math.inf if K_crit is None else float(K_crit), "max_passes": float(max_passes),
              "max_cycles": float(max_cycles)}
    out = _cracklip.integrate_cycles(table.native, np.ascontiguousarray(F, dtype=float), lo, hi, n, compiled_law(law),
                                     compiled_retardation(ret), run, limits, clamp_min)
    out["stop"] = STOPS[out["stop"]]
    return out


def growth_per_pass(table: KTable, F: np.ndarray, cycles: CycleTable, law: LifeLaw, sizes,
                    clamp_min: bool = False) -> np.ndarray:
    """The growth of each point over one pass at the sizes (no sequence effects)."""
    lo, hi, n = cycle_arrays(cycles)
    return np.asarray(_cracklip.growth_per_pass(table.native, np.ascontiguousarray(F, dtype=float), lo, hi, n,
                                                compiled_law(law), [float(x) for x in np.atleast_1d(sizes)],
                                                clamp_min))


def state_k_max(table: KTable, F: np.ndarray, sizes) -> np.ndarray:
    """K_max over the load states of each point at the sizes."""
    return np.asarray(_cracklip.state_k_max(table.native, np.ascontiguousarray(F, dtype=float),
                                            [float(x) for x in np.atleast_1d(sizes)]))


def passes_to(table: KTable, F: np.ndarray, cycles: CycleTable, law: LifeLaw, a, clamp_min: bool = False
              ) -> np.ndarray:
    """Passes from a[0] to each a[k] (one size, no sequence effects):
    Gauss-Legendre in ln a between the table's sizes; inf past an arrest."""
    lo, hi, n = cycle_arrays(cycles)
    return np.asarray(_cracklip.passes_to(table.native, np.ascontiguousarray(F, dtype=float), lo, hi, n,
                                          compiled_law(law), np.ascontiguousarray(a, dtype=float),
                                          clamp_min=clamp_min))


def grow_blocks(table: KTable, F: np.ndarray, cycles: CycleTable, law: LifeLaw, a0: float, c0: float,
                size_end: typing.Sequence[float], K_crit: float | None = None, max_passes: float = math.inf,
                fraction: float = 2e-3, clamp_min: bool = False) -> dict:
    """Two sizes in blocks: {"passes", "a", "c" (per step), "stop", "point"}."""
    lo, hi, n = cycle_arrays(cycles)
    limits = {"size_end": (float(size_end[0]), float(size_end[1])),
              "K_crit": math.inf if K_crit is None else float(K_crit), "max_passes": float(max_passes),
              "max_cycles": math.inf}
    out = _cracklip.grow_blocks(table.native, np.ascontiguousarray(F, dtype=float), lo, hi, n, compiled_law(law),
                                float(a0), float(c0), limits, fraction, clamp_min)
    out["stop"] = STOPS[out["stop"]]
    return out


__all__ = ["STOPS", "compiled_law", "compiled_retardation", "KTable", "cycle_arrays", "new_run", "integrate_cycles",
           "growth_per_pass", "state_k_max", "passes_to", "grow_blocks"]
