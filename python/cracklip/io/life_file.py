"""The scene-file side of a fatigue life: the [life] table's keys (in the
scene reference with every other key), a life scene read and checked
without any mesh (`cracklip life`, `cracklip check`), and the input files
of [material.fatigue] and [spectrum] read before anything is meshed (also
for `cracklip grow` and `check` on a scene with a mesh).

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


def life_keys() -> list:
    """The [life] keys and the input-file keys of [material.fatigue] (the
    scene reference lists them with the others)."""
    from ..scene.input_files import RATE_LAYOUTS, UNSUPPORTED_RATE_LAYOUTS
    from ..scene.life import CENTRE_FORMS, GEOMETRIES, INTEGRATIONS
    from .scene_file import REQUIRED, UNSET, Key, p_choice, p_factors, p_float, p_int, p_numbers, p_str
    t = "life"
    return [
        Key(f"{t}.geometry", "string", REQUIRED, "the crack's geometry factor for `cracklip life` (a life without a "
            "mesh): " + ", ".join(f"`{g}`" for g in GEOMETRIES) + " (docs/life.md)", p_choice(*GEOMETRIES)),
        Key(f"{t}.a0", "float", REQUIRED, "initial crack size a (half length of a centre crack; length from the edge "
            "or the hole's edge; depth of a surface or corner crack)", p_float(positive=True)),
        Key(f"{t}.c0", "float", UNSET, "initial second size c of a surface crack (half length) or corner crack "
            "(length), or of a two-size beta table", p_float(positive=True)),
        Key(f"{t}.a_final", "float", UNSET, "stop when a reaches this (unset: at failure or the end of the table "
            "or handbook range)", p_float(positive=True)),
        Key(f"{t}.detectable_size", "float", UNSET, "crack size a an inspection finds: the inspection interval is "
            "half the life from it to failure (the threshold half the life from a0)", p_float(positive=True)),
        Key(f"{t}.width", "float", UNSET, "plate width W (centre and edge crack; surface crack 2b, corner crack b; "
            "hole crack: net-section yield only)", p_float(positive=True)),
        Key(f"{t}.thickness", "float", UNSET, "plate thickness t (surface and corner cracks)", p_float(positive=True)),
        Key(f"{t}.hole_radius", "float", UNSET, "radius R of the hole (hole_crack)", p_float(positive=True)),
        Key(f"{t}.cracks", "integer", 1, "cracks at the hole: 1 or 2 symmetric ones (hole_crack)", p_int(1)),
        Key(f"{t}.form", "string", "feddersen", "centre crack: `feddersen` (sqrt(sec(pi a / W))) or `tada` "
            "(0.1 %)", p_choice(*CENTRE_FORMS)),
        Key(f"{t}.table", "string", UNSET, "beta_table: a file of K or beta against crack size (a, beta[_group] / "
            "K[_group]; a, c, beta_a, beta_c; a beta; or the beta.csv of `cracklip grow --beta-table`), relative "
            "to the scene file", p_str),
        Key(f"{t}.table_scale", "float", 1.0, "factor on the table's crack sizes (an a/d table: d)",
            p_float(positive=True)),
        Key(f"{t}.tip", "[crack, end]", UNSET, "the tip of a beta.csv `cracklip grow` wrote for several tips",
            p_numbers(2, "a tip [crack, end]")),
        Key(f"{t}.reference_stress", "table of group = stress", UNSET, "remote stress S of factor 1 of each load "
            "group: K = factor x S x beta x sqrt(pi a) (handbook solutions and beta columns; default 1)", p_factors),
        Key(f"{t}.integration", "string", "auto", "`cycles` (cycle by cycle, sequence effects), `blocks` (growth "
            "per pass summed) or `auto` (cycles with retardation, else blocks)", p_choice(*INTEGRATIONS)),
        Key(f"{t}.points", "integer", 200, "rows of the a-N table", p_int(2)),
        Key("material.fatigue.table_file", "string", UNSET, "tabular law: a da/dN table file instead of table_R / "
            "table, relative to the scene file (layouts: table_layout)", p_str),
        Key("material.fatigue.table_layout", "string", "auto", "layout of table_file: " + ", ".join(
            f"`{x}`" for x in RATE_LAYOUTS) + f" (not supported, undocumented publicly: "
            f"{', '.join(UNSUPPORTED_RATE_LAYOUTS)}; docs/life.md)", p_str),
    ]


def resolve_rate_table(fatigue: dict, base_dir: pathlib.Path) -> dict:
    """The [material.fatigue] values with table_file read into table_R and
    table (the file's errors name its line and column)."""
    from ..scene.input_files import read_rate_table
    f = dict(fatigue)
    layout = f.pop("table_layout", "auto")
    name = f.pop("table_file", None)
    if name is None:
        return f
    if "table" in f or "table_R" in f:
        raise InputError("material.fatigue: give table_file or table_R / table, not both")
    path = pathlib.Path(name)
    f["table_R"], f["table"] = read_rate_table(path if path.is_absolute() else base_dir / path,
                                               "material.fatigue.table_file", layout)
    return f


def build_growth(doc: dict, s: dict, units, base_dir: pathlib.Path):
    """The [growth] settings of a scene with a mesh, with its fatigue material
    and spectrum and their files, checked before the mesh is made; None
    without [growth]."""
    from ..scene.growth import Growth
    from .scene_file import _fatigue_material, _spectrum
    if "growth" not in s:
        if "life" not in doc and ("spectrum" in s or "fatigue" in s["material"]):
            raise InputError(f"[{'spectrum' if 'spectrum' in s else 'material.fatigue'}] is read by `cracklip grow` "
                             "(add a [growth] table: growth.da, growth.steps) or `cracklip life` (a [life] table)")
        return None
    fatigue = (_fatigue_material(resolve_rate_table(s["material"]["fatigue"], base_dir))
               if "fatigue" in s["material"] else None)
    spectrum = _spectrum(s["spectrum"], base_dir) if "spectrum" in s else None
    if fatigue is not None:
        fatigue.converted(units)  # units given without the scene's [units]: an error now, not at the solve
    try:
        return Growth(**s["growth"], fatigue_material=fatigue, spectrum=spectrum)
    except InputError as e:
        raise InputError(f"growth: {e}") from None


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
    from ..scene.input_files import read_k_table
    from ..scene.life import life_settings
    from ..scene.units import Units
    from .scene_file import _fatigue_material, _items, _section, _spectrum, check_keys
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
    units = None
    if "units" in doc:
        u = _section(doc["units"], "units", "units")
        units = Units(u.get("length"), u.get("force"), u.get("stress"))
    fd = doc["material"]["fatigue"]
    fs = _section(fd, "material.fatigue", "material.fatigue")
    if "units" in fd:
        fs["units"] = _section(fd["units"], "material.fatigue.units", "material.fatigue.units")
    fatigue = _fatigue_material(resolve_rate_table(fs, base_dir))
    fatigue.converted(units)
    sp = _section(doc["spectrum"], "spectrum", "spectrum")
    sp["blocks"] = [_section(b, "spectrum.blocks[]", f"spectrum.blocks[{i}]")
                    for i, b in enumerate(_items(doc["spectrum"], "blocks"))]
    for i, b in enumerate(sp["blocks"]):
        if ("points" in b) == ("file" in b):
            raise InputError(f"spectrum.blocks[{i}] needs exactly one of points or file")
    spectrum = _spectrum(sp, base_dir)
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


__all__ = ["LIFE_TABLES", "life_keys", "resolve_rate_table", "build_growth", "LifeFile", "is_life_scene", "build_life",
           "load_life_file"]
