"""[units] and [material]: the units of the scene's numbers (labels and
conversions only: the solve needs consistent units) and the elastic
material (its fatigue constants, [material.fatigue], are growth.py's)."""
from __future__ import annotations

from ...errors import InputError
from ...scene.material import Material
from ...scene.units import FORCES, LENGTHS, STRESSES, Units
from .schema import REQUIRED, UNSET, Key, p_choice, p_float


KEYS: list[Key] = [
    Key("units.length", "string", UNSET, "length unit of every coordinate and size: " + ", ".join(
        f"`{u}`" for u in LENGTHS) + "; with units.force or units.stress it labels every axis and K "
        "(K in stress sqrt(length)) and converts constants given in other units", p_choice(*LENGTHS)),
    Key("units.force", "string", UNSET, "force unit: " + ", ".join(f"`{u}`" for u in FORCES)
        + " (stress = force / length^2)", p_choice(*FORCES)),
    Key("units.stress", "string", UNSET, "stress unit (of E, tractions, pressures): " + ", ".join(
        f"`{u}`" for u in STRESSES) + "; give it or units.force", p_choice(*STRESSES)),
    Key("material.E", "float", REQUIRED, "Young's modulus", p_float(positive=True)),
    Key("material.nu", "float", REQUIRED, "Poisson's ratio, -1 < nu < 0.5 (plane stress: <= 0.5)", p_float()),
    Key("material.plane", "string", "strain", "`strain` (thick part, eps_zz = 0) or `stress` (thin plate, "
        "sigma_zz = 0; K from G with E' = E); 2D only", p_choice("strain", "stress")),
]


def build_units(s: dict) -> Units | None:
    """The Units of the [units] settings, or None without them."""
    if "units" not in s:
        return None
    u = s["units"]
    return Units(u.get("length"), u.get("force"), u.get("stress"))


def build_material(s: dict) -> Material:
    """The Material of the [material] settings (its errors name the table)."""
    try:
        return Material(s["material"]["E"], s["material"]["nu"], s["material"]["plane"])
    except InputError as e:
        raise type(e)(f"material: {e}") from None
