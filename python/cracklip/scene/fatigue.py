"""Fatigue material constants as the user gives them ([material.fatigue]):
the growth law and its constants, their units, toughness and yield stress
for the failure criteria, closure and retardation.

Constants may be given in other units than the scene's (a NASGRO set in
in/cycle and ksi sqrt(in) for a part meshed in mm and MPa): ``units`` names
their length and stress unit, and ``converted(scene_units)`` returns them in
the scene's (cracklip.scene.units; the scene needs a [units] table then).
How each constant converts (L a length, S a stress, K = S sqrt(L)):

    rate coefficient of da/dN = C K^e   C (L_c / L) (K / K_c)^e, e = m, n
                                        (Paris, Walker, NASGRO), n - 1
                                        (Forman), alpha (Hartman-Schijve)
    K values                            dK1, K_Ic, K_f, dK_thr, A, threshold
    lengths                             a0, thickness; tabular rates per cycle
    stresses                            yield_stress
    the rest                            dimensionless

Example sets (``example = "..."``, EXAMPLES): each with its source; the
NASGRO ones come from an anonymous file quoting the NASGRO database whose
provenance is unknown (read in the notes, gap 2: treat as unaudited), the
Forman and Hartman-Schijve ones from easigrow's material library (DST
Group), which cites Schwarmann (1986) and Jones et al. (2012/2013).
"""
from __future__ import annotations

import dataclasses
import math
import typing

from ..errors import InputError, checked_keywords
from .units import Units


LAWS = ("paris", "walker", "forman", "nasgro", "hartman_schijve", "tabular")
CLOSURES = ("contact", "newman", "none")
RETARDATIONS = ("none", "wheeler", "willenborg")
CONSTRAINTS = ("auto", "plane_stress", "plane_strain")

#: The constants each law needs (required) and may take (optional, with defaults).
LAW_CONSTANTS: dict[str, tuple[tuple[str, ...], dict[str, float]]] = {
    "paris": (("C", "m"), {}),
    "walker": (("C", "m", "gamma"), {}),
    "forman": (("C", "n", "K_f"), {}),
    "nasgro": (("C", "n", "p", "q", "dK1", "C_th_plus", "C_th_minus"),
               {"alpha": 2.0, "smax_over_flow": 0.3, "a0": 0.0}),
    "hartman_schijve": (("D", "dK_thr", "A", "exponent"), {}),
    "tabular": ((), {}),
}

#: How a constant converts (module doc): "rate" (with its exponent's name), "K", "length", "stress".
KINDS = {"dK1": "K", "K_Ic": "K", "K_f": "K", "dK_thr": "K", "A": "K", "threshold": "K", "a0": "length",
         "thickness": "length", "yield_stress": "stress"}

#: Named constant sets: law, constants, units, source.
EXAMPLES: dict[str, dict[str, typing.Any]] = {
    "nasgro_7075_T6_LT": {
        "law": "nasgro", "units": ("in", "ksi"),
        "constants": {"C": 7.0e-8, "n": 2.40, "p": 1.0, "q": 1.0, "dK1": 0.90, "C_th_plus": 1.5,
                      "C_th_minus": 0.1, "alpha": 2.0, "smax_over_flow": 0.3, "a0": 0.0015,
                      "K_Ic": 25.0, "A_k": 1.0, "B_k": 1.5, "yield_stress": 75.0},
        "source": "7075-T6 plate and sheet, L-T, lab air: NASGRO constants as listed in an anonymous "
                  "materials.js ('30 aluminium + steel + titanium alloys from NASGRO database'; provenance "
                  "unknown, unaudited)"},
    "nasgro_2024_T3_LT": {
        "law": "nasgro", "units": ("in", "ksi"),
        "constants": {"C": 8.0e-9, "n": 3.20, "p": 0.25, "q": 1.0, "dK1": 1.22, "C_th_plus": 1.21,
                      "C_th_minus": 0.1, "alpha": 2.0, "smax_over_flow": 0.3, "a0": 0.0015,
                      "K_Ic": 30.0, "A_k": 1.0, "B_k": 1.5, "yield_stress": 53.0},
        "source": "2024-T3 clad and bare, L-T: same anonymous NASGRO listing as nasgro_7075_T6_LT (unaudited)"},
    "nasgro_Ti6Al4V_MA_LT": {
        "law": "nasgro", "units": ("in", "ksi"),
        "constants": {"C": 2.5e-9, "n": 3.00, "p": 0.5, "q": 0.75, "dK1": 2.10, "C_th_plus": 0.0,
                      "C_th_minus": 0.1, "alpha": 2.5, "smax_over_flow": 0.3, "a0": 0.0015,
                      "K_Ic": 50.0, "A_k": 1.0, "B_k": 1.0, "yield_stress": 138.0},
        "source": "Ti-6Al-4V mill annealed plate, L-T: same anonymous NASGRO listing (unaudited)"},
    "forman_7075_T6_sheet": {
        "law": "forman", "units": ("m", "MPa"),
        "constants": {"C": 1.37e-8, "n": 3.02, "K_f": 63.9},
        "source": "7075-T6 sheet, Forman constants of Schwarmann (1986) as in easigrow's material library "
                  "(doc/list.md: 'converted from mm/cycle to m/cycle'; SI: m/cycle, MPa sqrt(m))"},
    "hartman_schijve_7050_T7451": {
        "law": "hartman_schijve", "units": ("m", "MPa"),
        "constants": {"D": 7.0e-10, "dK_thr": 0.1, "A": 47.0, "exponent": 2.0},
        "source": "AA7050-T7451, Hartman-Schijve (Jones-Molent) constants 'jones13' as in easigrow's material "
                  "library (doc/list.md; SI: m/cycle, MPa sqrt(m))"},
}


@checked_keywords
@dataclasses.dataclass
class FatigueMaterial:
    """The fatigue constants of the material.

    Attributes:
        law: one of LAWS.
        constants: the law's constants (LAW_CONSTANTS) by name.
        units: (length, stress) unit names the constants are given in (None:
            the scene's own units).
        table_R, table: tabular law: the R of each curve and rows [da/dN,
            Delta K at R_1, Delta K at R_2, ...] (easigrow's layout).
        threshold: Delta K below which a cycle does not grow (any law; 0: none).
        K_Ic, A_k, B_k, thickness, yield_stress: toughness K_c(t) = K_Ic [1 +
            B_k exp(-(A_k t / t0)^2)], t0 = 2.5 (K_Ic / yield_stress)^2 (B_k
            unset: K_c = K_Ic); the yield stress also gives net-section yield
            and the plastic zone of retardation.
        closure: "contact", "newman" or "none" (cracklip.fracture.life).
        retardation: "none", "wheeler" or "willenborg".
        wheeler_exponent: Wheeler's gamma.
        shutoff_ratio: Willenborg's shut-off overload ratio SOLR (> 1).
        constraint: plastic zone of retardation: "plane_stress" (beta 2),
            "plane_strain" (6) or "auto" (by the thickness).
        example: the name of the EXAMPLES set this started from, if any.
        source: where the constants come from (an example's source).
    """
    law: str
    constants: dict[str, float] = dataclasses.field(default_factory=dict)
    units: tuple[str, str] | None = None
    table_R: list[float] | None = None
    table: list[list[float]] | None = None
    threshold: float = 0.0
    K_Ic: float | None = None
    A_k: float | None = None
    B_k: float | None = None
    thickness: float | None = None
    yield_stress: float | None = None
    closure: str = "contact"
    retardation: str = "none"
    wheeler_exponent: float | None = None
    shutoff_ratio: float | None = None
    constraint: str = "auto"
    example: str | None = None
    source: str = ""

    def __post_init__(self):
        where = "material.fatigue"
        if self.law not in LAWS:
            raise InputError(f"{where}.law must be one of {LAWS}, got {self.law!r}")
        if self.closure not in CLOSURES:
            raise InputError(f"{where}.closure must be one of {CLOSURES}, got {self.closure!r}")
        if self.retardation not in RETARDATIONS:
            raise InputError(f"{where}.retardation must be one of {RETARDATIONS}, got {self.retardation!r}")
        if self.constraint not in CONSTRAINTS:
            raise InputError(f"{where}.constraint must be one of {CONSTRAINTS}, got {self.constraint!r}")
        required, optional = LAW_CONSTANTS[self.law]
        missing = [k for k in required if k not in self.constants]
        if missing:
            raise InputError(f"{where}: the {self.law} law needs {', '.join(f'{where}.{k}' for k in missing)}")
        allowed = set(required) | set(optional)
        extra = sorted(set(self.constants) - allowed)
        if extra:
            raise InputError(f"{where}.{extra[0]} is not a constant of the {self.law} law (its constants: "
                             f"{', '.join(sorted(allowed)) or 'the table'})")
        for k, v in self.constants.items():
            _finite(v, f"{where}.{k}")
        for k, v in optional.items():
            self.constants.setdefault(k, v)
        self._check_ranges(where)
        for name in ("threshold", "K_Ic", "A_k", "B_k", "thickness", "yield_stress", "wheeler_exponent",
                     "shutoff_ratio"):
            v = getattr(self, name)
            if v is not None:
                _finite(v, f"{where}.{name}")
                if v < 0 or (v == 0 and name not in ("threshold", "A_k", "B_k")):
                    raise InputError(f"{where}.{name} must be {'>= 0' if name == 'threshold' else 'positive'}, "
                                     f"got {v!r}")
        if self.law == "tabular":
            if self.table_R is None or self.table is None:
                raise InputError(f"{where}: the tabular law needs {where}.table_R (the R of each curve) and "
                                 f"{where}.table (rows [da/dN, Delta K at each R])")
            for i, row in enumerate(self.table):
                if len(row) != len(self.table_R) + 1:
                    raise InputError(f"{where}.table[{i}] has {len(row)} numbers; it needs da/dN and one Delta K per "
                                     f"R of {where}.table_R ({len(self.table_R)})")
                for j, v in enumerate(row):
                    _finite(v, f"{where}.table[{i}][{j}]")
            self._check_table(where)
        elif self.table is not None or self.table_R is not None:
            raise InputError(f"{where}.table and table_R belong to the tabular law (law = 'tabular'), not {self.law!r}")
        if self.retardation != "none":
            if self.yield_stress is None:
                raise InputError(f"{where}.retardation = {self.retardation!r} needs {where}.yield_stress (the plastic "
                                 "zone r_y = (K_max / yield_stress)^2 / (beta pi))")
            if self.retardation == "wheeler" and self.wheeler_exponent is None:
                raise InputError(f"{where}.retardation = 'wheeler' needs {where}.wheeler_exponent (gamma of "
                                 "C_p = (r_y / (a_OL + r_OL - a))^gamma)")
            if self.retardation == "willenborg" and (self.shutoff_ratio is None or not self.shutoff_ratio > 1.0):
                raise InputError(f"{where}.retardation = 'willenborg' needs {where}.shutoff_ratio > 1 (the overload "
                                 f"ratio that arrests growth), got {self.shutoff_ratio!r}")
        if self.B_k is not None and (self.K_Ic is None or self.thickness is None or self.yield_stress is None):
            raise InputError(f"{where}.B_k (toughness K_c(t)) needs {where}.K_Ic, {where}.thickness and "
                             f"{where}.yield_stress")
        if self.closure == "newman" and self.law in ("walker", "forman", "tabular"):
            raise InputError(f"{where}.closure = 'newman' with the {self.law} law would count the R effect twice "
                             "(the law has its own): use closure 'contact' or 'none'")

    def _check_ranges(self, where: str) -> None:
        c = self.constants
        positive = {"C", "m", "n", "D", "exponent", "K_f", "A", "dK1"}
        for k in positive & set(c):
            if not c[k] > 0.0:
                raise InputError(f"{where}.{k} must be positive, got {c[k]!r}")
        if self.law == "nasgro":
            for k in ("p", "q"):
                if not 0.0 <= c[k] <= 10.0:
                    raise InputError(f"{where}.{k} = {c[k]!r} is out of range: NASGRO exponents p, q lie in [0, 10]")
            if not 1.0 <= c["alpha"] <= 3.0:
                raise InputError(f"{where}.alpha = {c['alpha']!r} is out of range: Newman's constraint factor lies in "
                                 "[1, 3] (1 plane stress, 3 plane strain)")
            if not 0.0 < c["smax_over_flow"] < 1.0:
                raise InputError(f"{where}.smax_over_flow = {c['smax_over_flow']!r} is out of range: S_max / sigma_0 "
                                 "lies in (0, 1)")
            if not c["a0"] >= 0.0:
                raise InputError(f"{where}.a0 must be >= 0, got {c['a0']!r}")
            for k in ("C_th_plus", "C_th_minus"):
                if not -5.0 <= c[k] <= 10.0:
                    raise InputError(f"{where}.{k} = {c[k]!r} is out of range [-5, 10] (the threshold's R exponent)")
            if not c["n"] <= 20.0:
                raise InputError(f"{where}.n = {c['n']!r} is out of range: NASGRO's n lies in (0, 20]")
        if self.law == "walker" and not 0.0 <= c["gamma"] <= 1.0:
            raise InputError(f"{where}.gamma = {c['gamma']!r} is out of range: Walker's gamma lies in [0, 1]")
        if self.law == "hartman_schijve" and c["dK_thr"] < 0.0:
            raise InputError(f"{where}.dK_thr must be >= 0, got {c['dK_thr']!r}")

    def _check_table(self, where: str) -> None:
        """The tabular law's R rise, its rates and every Delta K column are
        positive and rise down the table (the interpolation needs it)."""
        R, rows = self.table_R, self.table
        for j in range(1, len(R)):
            if not R[j] > R[j - 1]:
                raise InputError(f"{where}.table_R[{j}] = {R[j]!r} does not rise above {R[j - 1]!r}: the R values must "
                                 "be ascending")
        if len(rows) < 2:
            raise InputError(f"{where}.table needs at least two rows (rates)")
        for i, row in enumerate(rows):
            for j, v in enumerate(row):
                if not v > 0:
                    raise InputError(f"{where}.table[{i}][{j}] must be positive, got {v!r}")
            if i == 0:
                continue
            if not row[0] > rows[i - 1][0]:
                raise InputError(f"{where}.table[{i}][0]: the rates must rise down the table, {row[0]!r} follows "
                                 f"{rows[i - 1][0]!r}")
            for j in range(1, len(row)):
                if not row[j] > rows[i - 1][j]:
                    raise InputError(f"{where}.table[{i}][{j}]: the Delta K at R = {R[j - 1]:g} must rise down the "
                                     f"table (a non-ascending Delta K column), {row[j]!r} follows {rows[i - 1][j]!r}")

    @property
    def fixed_units(self) -> Units | None:
        return None if self.units is None else Units(self.units[0], stress=self.units[1])

    def converted(self, scene_units: Units | None) -> "FatigueMaterial":
        """This material with every dimensional value in the scene's units (module doc)."""
        if self.units is None:
            return self
        if scene_units is None:
            raise InputError(f"material.fatigue.units = {list(self.units)} needs the scene's own units to convert "
                             "into: give a [units] table (length and stress or force)")
        src = self.fixed_units
        L = src.length_si / scene_units.length_si           # one source length in scene lengths
        S = src.stress_si / scene_units.stress_si           # one source stress in scene stresses
        K = src.si_factor("K") / scene_units.si_factor("K")  # one source K in scene K

        def conv(name: str, v):
            if v is None:
                return None
            kind = KINDS.get(name)
            return v * {"K": K, "length": L, "stress": S}[kind] if kind else v
        c = dict(self.constants)
        exponent = {"paris": "m", "walker": "m", "nasgro": "n", "forman": "n", "hartman_schijve": "exponent"}
        if self.law in exponent:
            key = "D" if self.law == "hartman_schijve" else "C"
            e = c[exponent[self.law]] - (1.0 if self.law == "forman" else 0.0)
            c[key] = c[key] * L / K ** e
        for k in list(c):
            if k in KINDS:
                c[k] = conv(k, c[k])
        table = None if self.table is None else [[row[0] * L] + [v * K for v in row[1:]] for row in self.table]
        return dataclasses.replace(self, constants=c, units=None, table=table, threshold=self.threshold * K,
                                   K_Ic=conv("K_Ic", self.K_Ic), thickness=conv("thickness", self.thickness),
                                   yield_stress=conv("yield_stress", self.yield_stress))

    def toughness(self) -> float | None:
        """K_c(t) (module doc), K_Ic without B_k, None without K_Ic."""
        if self.K_Ic is None:
            return None
        if self.B_k is None:
            return self.K_Ic
        t0 = 2.5 * (self.K_Ic / self.yield_stress) ** 2
        return self.K_Ic * (1.0 + self.B_k * math.exp(-((self.A_k or 1.0) * self.thickness / t0) ** 2))

    def describe(self) -> str:
        c = ", ".join(f"{k} = {v:g}" for k, v in self.constants.items())
        u = f" [{self.units[0]}, {self.units[1]}]" if self.units else ""
        return (f"{self.law}{' (' + self.example + ')' if self.example else ''}: {c}{u}; closure {self.closure}"
                + (f"; retardation {self.retardation}" if self.retardation != "none" else ""))


def from_example(name: str, **overrides) -> FatigueMaterial:
    """A FatigueMaterial from a named example set, with keys overridden (e.g. thickness)."""
    if name not in EXAMPLES:
        raise InputError(f"material.fatigue.example must be one of {sorted(EXAMPLES)}, got {name!r}")
    ex = EXAMPLES[name]
    fields = {f.name for f in dataclasses.fields(FatigueMaterial)}
    consts = {k: v for k, v in ex["constants"].items() if k not in fields}
    top = {k: v for k, v in ex["constants"].items() if k in fields}
    law = overrides.pop("law", ex["law"])
    consts.update(overrides.pop("constants", {}) or {})
    kwargs = {"law": law, "constants": consts, "units": ex["units"], "example": name, "source": ex["source"], **top}
    kwargs.update(overrides)
    return FatigueMaterial(**kwargs)


def _finite(v, path: str) -> None:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise InputError(f"{path} must be a finite number, got {v!r}")


__all__ = ["LAWS", "CLOSURES", "RETARDATIONS", "CONSTRAINTS", "LAW_CONSTANTS", "EXAMPLES", "FatigueMaterial",
           "from_example"]
