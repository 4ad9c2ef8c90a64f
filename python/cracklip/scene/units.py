"""Units of a scene: what its numbers mean, for labels and conversions.

cracklip computes in whatever consistent units the user's numbers are in;
an optional ``[units]`` table (``Units``) names them, so that every axis and
every K can carry a label and constants given in other units (a Paris C
from a handbook in m/cycle and MPa sqrt(m)) are converted. Give the length
unit and either the force or the stress unit; the other follows
(stress = force / length^2). Derived units:

    displacement  length
    stress        stress (= force / length^2)
    K             stress sqrt(length)            e.g. MPa sqrt(mm)
    G             force / length (energy per area)
    line force    force / length (a 2D traction or point force per unit thickness)

Nothing here converts the scene itself: the solve needs consistent units,
not SI.
"""
from __future__ import annotations

import dataclasses
import math
import re

from ..errors import InputError, checked_keywords

#: Lengths in metres.
LENGTHS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "in": 0.0254, "ft": 0.3048}
#: Forces in newtons.
FORCES = {"N": 1.0, "kN": 1e3, "MN": 1e6, "lbf": 4.4482216152605, "kip": 4448.2216152605}
#: Stresses in pascals.
STRESSES = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "psi": 6894.757293168361,
            "ksi": 6894757.293168361}
#: The stress each (force, length) pair makes, where it has a name.
_STRESS_OF = {("N", "m"): "Pa", ("N", "mm"): "MPa", ("kN", "mm"): "GPa", ("lbf", "in"): "psi",
              ("kip", "in"): "ksi", ("kN", "m"): "kPa", ("MN", "m"): "MPa"}

QUANTITIES = ("length", "displacement", "stress", "force", "line_force", "K", "G")


def _check(name: str, value, table: dict[str, float]) -> None:
    if value is not None and value not in table:
        raise InputError(f"units.{name} must be one of {sorted(table)}, got {value!r}")


@checked_keywords
@dataclasses.dataclass(frozen=True)
class Units:
    """The units a scene's numbers are in.

    Attributes:
        length: a key of LENGTHS (e.g. "mm").
        force: a key of FORCES (e.g. "N"); with length, fixes the stress.
        stress: a key of STRESSES (e.g. "MPa"); with length, fixes the force.
    Give length and one of force, stress (or both, if consistent).
    """
    length: str
    force: str | None = None
    stress: str | None = None

    def __post_init__(self):
        if self.length is None:
            raise InputError("units.length is required (one of "
                             f"{sorted(LENGTHS)}) with units.force or units.stress")
        _check("length", self.length, LENGTHS)
        _check("force", self.force, FORCES)
        _check("stress", self.stress, STRESSES)
        if self.force is None and self.stress is None:
            raise InputError("units: give units.force or units.stress besides units.length "
                             "(e.g. length = \"mm\", stress = \"MPa\")")
        if self.force is not None and self.stress is not None:
            implied = FORCES[self.force] / LENGTHS[self.length] ** 2
            if not math.isclose(implied, STRESSES[self.stress], rel_tol=1e-9):
                raise InputError(f"units: force {self.force!r} per {self.length!r}^2 is {implied:g} Pa, not "
                                 f"{self.stress!r} ({STRESSES[self.stress]:g} Pa); give only one of force, stress")

    # -- factors to SI ----------------------------------------------------
    @property
    def stress_si(self) -> float:
        """Pascals per stress unit."""
        if self.stress is not None:
            return STRESSES[self.stress]
        return FORCES[self.force] / LENGTHS[self.length] ** 2

    @property
    def length_si(self) -> float:
        return LENGTHS[self.length]

    def si_factor(self, quantity: str) -> float:
        """SI value of one unit of a quantity (QUANTITIES)."""
        L, S = self.length_si, self.stress_si
        factors = {"length": L, "displacement": L, "stress": S, "force": S * L * L, "line_force": S * L,
                   "G": S * L, "K": S * math.sqrt(L)}
        if quantity not in factors:
            raise ValueError(f"unknown quantity {quantity!r}; one of {QUANTITIES}")
        return factors[quantity]

    # -- labels -----------------------------------------------------------
    @property
    def stress_name(self) -> str:
        if self.stress is not None:
            return self.stress
        return _STRESS_OF.get((self.force, self.length), f"{self.force}/{self.length}^2")

    @property
    def force_name(self) -> str:
        if self.force is not None:
            return self.force
        for (f, length), s in _STRESS_OF.items():
            if s == self.stress and length == self.length:
                return f
        return f"{self.stress} {self.length}^2"

    def name(self, quantity: str) -> str:
        """The unit of a quantity as text, e.g. name("K") = "MPa sqrt(mm)"."""
        names = {"length": self.length, "displacement": self.length, "stress": self.stress_name,
                 "force": self.force_name, "line_force": f"{self.force_name}/{self.length}",
                 "G": f"{self.force_name}/{self.length}", "K": f"{self.stress_name} sqrt({self.length})"}
        if quantity not in names:
            raise ValueError(f"unknown quantity {quantity!r}; one of {QUANTITIES}")
        return names[quantity]


def label(units: Units | None, quantity: str, text: str) -> str:
    """An axis label: "text [unit]" with units, the bare text without."""
    return text if units is None else f"{text} [{units.name(quantity)}]"


_K_UNIT = re.compile(r"^\s*([A-Za-z]+)\s*(?:\*\s*)?(?:sqrt\(\s*([A-Za-z]+)\s*\)|√\s*([A-Za-z]+)|"
                     r"([A-Za-z]+)\s*\^\s*(?:0\.5|\(1/2\)))\s*$")


def parse_k_unit(text: str) -> float:
    """SI value (Pa sqrt(m)) of a K unit written "MPa sqrt(m)", "MPa*sqrt(m)",
    "MPa √m", "ksi sqrt(in)" or "MPa m^0.5"."""
    m = _K_UNIT.match(text) if isinstance(text, str) else None
    if not m or m.group(1) not in STRESSES or (m.group(2) or m.group(3) or m.group(4)) not in LENGTHS:
        raise InputError(f"a K unit must read '<stress> sqrt(<length>)' with a stress in {sorted(STRESSES)} and a "
                         f"length in {sorted(LENGTHS)}, e.g. 'MPa sqrt(m)' or 'ksi sqrt(in)'; got {text!r}")
    return STRESSES[m.group(1)] * math.sqrt(LENGTHS[m.group(2) or m.group(3) or m.group(4)])


def parse_length_unit(text: str) -> float:
    if text not in LENGTHS:
        raise InputError(f"a length unit must be one of {sorted(LENGTHS)}, got {text!r}")
    return LENGTHS[text]


def convert_paris_C(C: float, m: float, da_unit: str, K_unit: str, units: Units) -> float:
    """C of da/dN = C (Delta K)^m given with da in da_unit per cycle and K in
    K_unit, in the scene's units: C' = C (da_unit / L) (K / K_unit)^m, where
    L and K are the scene's length and K units."""
    if not (isinstance(C, (int, float)) and math.isfinite(C) and C > 0.0):
        raise InputError(f"paris C must be a positive number, got {C!r}")
    if not (isinstance(m, (int, float)) and math.isfinite(m) and m > 0.0):
        raise InputError(f"paris m must be a positive number, got {m!r}")
    length_ratio = parse_length_unit(da_unit) / units.length_si
    k_ratio = units.si_factor("K") / parse_k_unit(K_unit)
    return C * length_ratio * k_ratio ** m


def convert(value: float, quantity: str, from_units: Units, to_units: Units) -> float:
    """A value of a quantity in from_units, expressed in to_units."""
    return value * from_units.si_factor(quantity) / to_units.si_factor(quantity)


__all__ = ["Units", "label", "parse_k_unit", "convert_paris_C", "convert", "LENGTHS", "FORCES", "STRESSES",
           "QUANTITIES"]
