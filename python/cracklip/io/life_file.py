"""A life scene read and checked without any mesh (`cracklip life`,
`cracklip check`): the [life] table (its keys are in the scene reference,
cracklip.io.scene_file), [material.fatigue] with its da/dN table file,
[spectrum] with its turning-point files, [units].

A life scene needs [life], [material.fatigue] and [spectrum] (and [units]
when the constants are given in other units); any other table (a mesh,
cracks, loads: the scene `cracklip grow` ran) is left to the commands that
mesh, and named in the notes. docs/life.md explains the keys and files.
"""
from __future__ import annotations

import dataclasses
import pathlib
import typing

from ..errors import InputError

#: The tables `cracklip life` reads; the others are left alone.
LIFE_TABLES = ("title", "units", "material", "spectrum", "life")


@dataclasses.dataclass
class LifeFile:
    """A life scene read and checked.

    Attributes:
        path: the file (None for a document given directly).
        title: the title (or the file's stem).
        life: the [life] settings (cracklip.scene.life.LifeSettings).
        material: the fatigue material ([material.fatigue]).
        spectrum: the load spectrum ([spectrum]).
        units: the scene's [units] (None: none given).
        table: the beta table's data (geometry beta_table), else None.
        notes: what was read, and the tables left to other commands.
    """
    path: pathlib.Path | None
    title: str
    life: typing.Any
    material: typing.Any
    spectrum: typing.Any
    units: typing.Any
    table: typing.Any
    notes: list[str]


def is_life_scene(doc: dict) -> bool:
    """A scene for `cracklip life` alone: a [life] table and no mesh."""
    return "life" in doc and "mesh" not in doc


def build_life(doc: dict, base_dir: str | pathlib.Path = ".", path: pathlib.Path | None = None) -> LifeFile:
    """Check a life scene's tables and files (nothing is meshed)."""
    from ..scene.input_files import read_k_table, resolve_rate_table
    from ..scene.life import life_settings
    from .scene_file.growth import _fatigue_material, _spectrum
    from .scene_file.material import build_units
    from .scene_file.reader import _section, check_keys, fatigue_settings, spectrum_settings
    base_dir = pathlib.Path(base_dir)
    if "life" not in doc:
        raise InputError("the scene has no [life] table: give life.geometry and life.a0 (docs/life.md)")
    for name in ("life", "units", "spectrum"):
        if name in doc:
            if not isinstance(doc[name], dict):
                raise InputError(f"{name} must be a table ([{name}]), got {doc[name]!r}")
            check_keys(doc[name], name, name)
    material = doc.get("material", {})
    if not isinstance(material, dict) or "fatigue" not in material:
        raise InputError("a life needs [material.fatigue]: the growth law and its constants (docs/life.md)")
    check_keys(material["fatigue"], "material.fatigue", "material.fatigue")
    if "spectrum" not in doc:
        raise InputError("a life needs a [spectrum]: blocks of turning points (a constant-amplitude cycle is one "
                         "block of two points, e.g. points = [0.1, 1.0])")
    title = doc.get("title") or (path.stem if path is not None else "life")
    units = build_units({"units": _section(doc["units"], "units", "units")} if "units" in doc else {})
    fatigue = _fatigue_material(resolve_rate_table(fatigue_settings(doc["material"]["fatigue"]), base_dir))
    fatigue.converted(units)
    spectrum = _spectrum(spectrum_settings(doc["spectrum"]), base_dir)
    life = life_settings(_section(doc["life"], "life", "life"))
    table = None
    if life.table is not None:
        f = pathlib.Path(life.table)
        table = read_k_table(f if f.is_absolute() else base_dir / f, "life.table", life.tip, life.table_scale)
    left = sorted(k for k in doc if k not in LIFE_TABLES)
    notes = [f"life: {life.describe()}", f"material.fatigue: {fatigue.describe()}",
             f"spectrum: {spectrum.blocks_per_pass} {spectrum.block_name}(s) per pass, groups {list(spectrum.groups)}, "
             f"{spectrum.counting} counting, residue {spectrum.residue}"]
    if left:
        notes.append(f"not read by `cracklip life` (the part's model, for `cracklip run` and `grow`): "
                     f"{', '.join(f'[{k}]' for k in left)}")
    return LifeFile(path, str(title), life, fatigue, spectrum, units, table, notes)


def load_life_file(path: str | pathlib.Path, overrides: typing.Sequence[str] = ()) -> LifeFile:
    """Read and check a life scene; overrides are ``KEY=VALUE`` strings."""
    from .scene_file import apply_override, read_document
    path = pathlib.Path(path)
    doc = read_document(path)
    for o in overrides:
        apply_override(doc, o)
    return build_life(doc, path.parent, path)


__all__ = ["LIFE_TABLES", "LifeFile", "is_life_scene", "build_life", "load_life_file"]
