"""A fatigue life without a mesh, as the user describes it (the [life] table,
`cracklip life`): the crack's geometry factor -- a table of K (or beta)
against crack size from a file, or a handbook solution with its
dimensions --, the initial crack, where to stop, and the detectable size
of the inspections. The growth law, closure and retardation are
[material.fatigue]'s, the load history [spectrum]'s, as for `cracklip
grow` (cracklip.analysis.table_life integrates it).

Geometries (GEOMETRIES; the handbook formulas and their sources are in
cracklip.fracture.handbook):

    beta_table     a table file (life.table): one crack size a, or two (a,
                   c) for a surface or corner crack
    centre_crack   a through crack of half length a in a plate of width W
                   (life.width; life.form: feddersen or tada)
    edge_crack     a through crack of length a from the edge of a strip of
                   width W (life.width)
    hole_crack     one or two (life.cracks) through cracks of length a from
                   a hole of radius R (life.hole_radius), infinite plate
                   (life.width, the hole central: net-section yield, and
                   the plate's edge at a = (W - 2R) / 2 ends the table)
    surface_crack  a semi-elliptical crack of depth a, half length c
                   (life.c0) in a plate of thickness t (life.thickness) and
                   width 2b (life.width)
    corner_crack   a quarter-elliptical crack of depth a and length c at the
                   corner of a plate of thickness t and width b

Sizes: a is the crack length at the tip (half the length of a centre
crack, the length from the edge or from the hole's edge), in the scene's
length unit.
"""
from __future__ import annotations

import dataclasses
import math
import typing

from ..errors import InputError


GEOMETRIES = ("beta_table", "centre_crack", "edge_crack", "hole_crack", "surface_crack", "corner_crack")
CENTRE_FORMS = ("feddersen", "tada")
INTEGRATIONS = ("auto", "cycles", "blocks")

#: The dimensions each handbook geometry needs.
NEEDS = {"centre_crack": ("width",), "edge_crack": ("width",), "hole_crack": ("hole_radius",),
         "surface_crack": ("thickness", "width", "c0"), "corner_crack": ("thickness", "width", "c0")}


@dataclasses.dataclass
class LifeSettings:
    """The [life] table.

    Attributes:
        geometry: one of GEOMETRIES (module doc).
        a0: the initial crack size a (> 0).
        c0: the initial second size c of a surface or corner crack.
        a_final: stop when a reaches this (unset: at failure, the end of the
            table or of the handbook's range).
        detectable_size: the crack size a inspections find (NDI): the
            inspection interval is half the life from it to failure.
        width: plate width W (centre, edge crack; surface crack: 2b; corner
            crack: b; hole crack: for net-section yield only).
        thickness: plate thickness t (surface and corner cracks).
        hole_radius: R of the hole (hole_crack).
        cracks: 1 or 2 cracks at the hole (hole_crack).
        form: the centre crack's handbook form: "feddersen" or "tada".
        table: the table file (beta_table), relative to the scene file.
        table_scale: factor on the table's crack sizes (an a/d table: d).
        tip: [crack, end] of a beta table cracklip grow wrote for several tips.
        reference_stress: the remote stress S of factor 1 of each load group:
            K = factor x S x beta x sqrt(pi a) (handbook and beta columns;
            unset: 1; K columns are per unit factor already).
        integration: "cycles" (cycle by cycle in closing order), "blocks"
            (the growth per pass summed, no sequence effects) or "auto"
            (cycles with retardation, else blocks).
        points: rows of the a-N table between a0 and the end.
    """
    geometry: str
    a0: float
    c0: float | None = None
    a_final: float | None = None
    detectable_size: float | None = None
    width: float | None = None
    thickness: float | None = None
    hole_radius: float | None = None
    cracks: int = 1
    form: str = "feddersen"
    table: str | None = None
    table_scale: float = 1.0
    tip: tuple[int, int] | None = None
    reference_stress: dict[str, float] | None = None
    integration: str = "auto"
    points: int = 200

    def __post_init__(self):
        w = "life"
        if self.geometry not in GEOMETRIES:
            raise InputError(f"{w}.geometry must be one of {GEOMETRIES}, got {self.geometry!r}")
        for name in ("a0", "c0", "a_final", "detectable_size", "width", "thickness", "hole_radius", "table_scale"):
            v = getattr(self, name)
            if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v)
                                  or v <= 0):
                raise InputError(f"{w}.{name} must be a positive number, got {v!r}")
        missing = [k for k in NEEDS.get(self.geometry, ()) if getattr(self, k) is None]
        if missing:
            raise InputError(f"{w}.geometry = {self.geometry!r} needs " + ", ".join(f"{w}.{k}" for k in missing))
        if self.geometry == "beta_table" and self.table is None:
            raise InputError(f"{w}.geometry = 'beta_table' needs {w}.table (the file of K or beta against crack size)")
        if self.geometry != "beta_table" and self.table is not None:
            raise InputError(f"{w}.table belongs to geometry 'beta_table', not {self.geometry!r}")
        if self.cracks not in (1, 2):
            raise InputError(f"{w}.cracks (at the hole) must be 1 or 2, got {self.cracks!r}")
        if self.form not in CENTRE_FORMS:
            raise InputError(f"{w}.form must be one of {CENTRE_FORMS}, got {self.form!r}")
        if self.integration not in INTEGRATIONS:
            raise InputError(f"{w}.integration must be one of {INTEGRATIONS}, got {self.integration!r}")
        if self.a_final is not None and not self.a_final > self.a0:
            raise InputError(f"{w}.a_final ({self.a_final:g}) must be larger than {w}.a0 ({self.a0:g})")
        if self.geometry in ("centre_crack", "edge_crack"):
            limit = self.width / 2 if self.geometry == "centre_crack" else self.width
            if not self.a0 < limit:
                raise InputError(f"{w}.a0 = {self.a0:g} leaves no ligament in a plate {w}.width = {self.width:g} wide")
        if self.geometry in ("surface_crack", "corner_crack") and not self.a0 < 0.8 * self.thickness:
            raise InputError(f"{w}.a0 = {self.a0:g} is beyond Newman-Raju's range a/t < 0.8 ({w}.thickness = "
                             f"{self.thickness:g})")
        if self.c0 is not None and self.geometry not in ("surface_crack", "corner_crack", "beta_table"):
            raise InputError(f"{w}.c0 belongs to surface and corner cracks (or a two-size beta table), not "
                             f"{self.geometry!r}")
        if self.reference_stress is not None and not all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0
                for v in self.reference_stress.values()):
            raise InputError(f"{w}.reference_stress must be a table of load group = positive stress, got "
                             f"{self.reference_stress!r}")
        if isinstance(self.points, bool) or not isinstance(self.points, int) or self.points < 2:
            raise InputError(f"{w}.points must be an integer >= 2, got {self.points!r}")

    @property
    def two_sizes(self) -> bool:
        return self.geometry in ("surface_crack", "corner_crack") or self.c0 is not None

    def stress(self, group: str) -> float:
        return (self.reference_stress or {}).get(group, 1.0)

    def describe(self) -> str:
        dims = {"width": "W", "thickness": "t", "hole_radius": "R", "c0": "c0"}
        parts = [f"{dims[k]} = {getattr(self, k):g}" for k in dims if getattr(self, k) is not None]
        what = {"beta_table": f"table {self.table}", "centre_crack": f"centre crack ({self.form})",
                "edge_crack": "edge crack (Tada)", "hole_crack": f"{self.cracks} crack(s) at a hole (Bowie)",
                "surface_crack": "surface crack (Newman-Raju)", "corner_crack": "corner crack (Newman-Raju)"}
        return (f"{what[self.geometry]}, a0 = {self.a0:g}" + (", " + ", ".join(parts) if parts else "")
                + (f", to a = {self.a_final:g}" if self.a_final else ""))


def life_settings(values: dict[str, typing.Any]) -> LifeSettings:
    """LifeSettings from the parsed [life] values (tip as a pair)."""
    v = dict(values)
    if "tip" in v:
        tip = v["tip"]
        v["tip"] = (int(tip[0]), int(tip[1]))
    return LifeSettings(**v)


__all__ = ["GEOMETRIES", "CENTRE_FORMS", "INTEGRATIONS", "NEEDS", "LifeSettings", "life_settings"]
