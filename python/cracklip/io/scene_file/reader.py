"""Reading a scene document: the whole schema (SCHEMA: the sections' keys in
the order of the reference), the check of its keys (an unknown key names
the nearest valid one), ``parse_settings`` (every key that applies, given
or default, checked), ``KEY=VALUE`` overrides and the reference table."""
from __future__ import annotations

import difflib
import pathlib
import re
import tomllib
import typing

from ...errors import BoundaryConditionError, InputError
from ...scene.scene import rigid_motion_hint
from . import conditions, cracks, growth, life, material, mesh, options
from .cracks import CRACK_KINDS
from .dimension import check_dimension, scene_dimension
from .mesh import MESH_KINDS
from .schema import REQUIRED, UNSET, Key, p_choice, p_str


SCHEMA: tuple[Key, ...] = tuple(
    [Key("title", "string", "", "name shown in outputs (default: the file name)", p_str)]
    + mesh.KEYS + material.KEYS + growth._fatigue_keys() + cracks.KEYS + conditions.DIRICHLET_KEYS + conditions.SYMMETRY_KEYS
    + conditions.LOAD_KEYS + options.OPTION_KEYS + growth._growth_keys() + growth._spectrum_keys()
    + life.KEYS + growth._fatigue_file_keys() + options.OUTPUT_KEYS)


KEYS: dict[str, Key] = {k.path: k for k in SCHEMA}


def _tables() -> set[str]:
    """Paths of all (arrays of) tables: parents of keys and their ancestors."""
    out = {""}
    for k in SCHEMA:
        p = k.parent
        while p:
            out.add(p)
            p = p.rpartition(".")[0]
    return out


TABLES = _tables()


def _children(table: str) -> dict[str, str]:
    """Valid names in a table (path with [] for arrays): name -> 'key' | 'table' | 'array'."""
    out = {}
    for k in SCHEMA:
        if k.parent == table:
            out[k.name] = "key"
    for t in TABLES:
        if t and t.rpartition(".")[0] == table:
            name = t.rpartition(".")[2]
            out[name.removesuffix("[]")] = "array" if name.endswith("[]") else "table"
    return out


def _display(path: str) -> str:
    return path.replace("[]", "")


def _unknown_key(where: str, table: str, name: str) -> InputError:
    """'unknown key ...; did you mean ...': a close key of the same table, else
    the place where a key of that name belongs, else the table's nearest key."""
    children = list(_children(table))
    full = f"{where}.{name}" if where else name
    close = difflib.get_close_matches(name, children, n=1, cutoff=0.6)
    elsewhere = sorted(_display(k.path) for k in SCHEMA if k.name == name)
    if not close and elsewhere:
        place = f"[{where}]" if where else "the top level"
        return InputError(f"unknown key {full}; did you mean {elsewhere[0]}? ({name} is not a key of {place})")
    near = close or difflib.get_close_matches(name, children, n=1, cutoff=0.0) or children[:1]
    return InputError(f"unknown key {full}; did you mean {where + '.' if where else ''}{near[0]}?")


def check_keys(doc: dict, table: str = "", where: str = "") -> None:
    """Raise InputError for the first key of doc that the schema does not have
    (or a table where a value is expected and vice versa)."""
    children = _children(table)
    for name, value in doc.items():
        path = f"{where}.{name}" if where else name
        kind = children.get(name)
        if kind is None:
            raise _unknown_key(where, table, name)
        sub = f"{table}.{name}" if table else name
        if kind == "table":
            if not isinstance(value, dict):
                raise InputError(f"{path} must be a table ([{path}] or {name} = {{ ... }}), got {value!r}")
            check_keys(value, sub, path)
        elif kind == "array":
            if isinstance(value, dict):
                value = [value]
            if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
                raise InputError(f"{path} must be an array of tables ([[{path}]]), got {value!r}")
            for i, item in enumerate(value):
                check_keys(item, sub + "[]", f"{path}[{i}]")
        elif isinstance(value, dict) and not KEYS[f"{table}.{name}" if table else name].type.startswith("table"):
            raise InputError(f"{path} must be a value, not a table")


def _section(doc: dict, table: str, where: str, kind: str | None = None) -> dict:
    """Parsed values of one table: every key of the schema at that table,
    given or default; REQUIRED keys that apply must be given."""
    out = {}
    for k in SCHEMA:
        if k.parent != table:
            continue
        path = f"{where}.{k.name}" if where else k.name
        applies = not k.kinds or kind is None or kind in k.kinds
        if k.name in doc:
            if not applies:
                raise InputError(f"{path} applies to mesh kind {' or '.join(repr(x) for x in k.kinds)} "
                                 f"only; this mesh is {kind!r}")
            out[k.name] = k.parse(doc[k.name], path)
        elif k.default is REQUIRED:
            if applies:
                extra = f" for mesh kind {kind!r}" if k.kinds else ""
                raise InputError(f"{path} is required{extra}: {k.meaning}")
        elif k.default is not UNSET and applies:
            out[k.name] = k.default
    return out


def _items(doc: dict, name: str) -> list[dict]:
    v = doc.get(name, [])
    return [v] if isinstance(v, dict) else v


def fatigue_settings(fd: dict) -> dict:
    """The parsed [material.fatigue] table (with its [material.fatigue.units])."""
    out = _section(fd, "material.fatigue", "material.fatigue")
    if "units" in fd:
        out["units"] = _section(fd["units"], "material.fatigue.units", "material.fatigue.units")
    return out


def spectrum_settings(sd: dict) -> dict:
    """The parsed [spectrum] table with its blocks (each of points or file)."""
    out = _section(sd, "spectrum", "spectrum")
    out["blocks"] = [_section(b, "spectrum.blocks[]", f"spectrum.blocks[{i}]")
                     for i, b in enumerate(_items(sd, "blocks"))]
    for i, b in enumerate(out["blocks"]):
        if ("points" in b) == ("file" in b):
            raise InputError(f"spectrum.blocks[{i}] needs exactly one of points or file")
    return out


def parse_settings(doc: dict) -> dict:
    """Validate a scene document (from tomllib) and fill in defaults.

    Returns a nested dict with the same layout as the file: every key of the
    schema that applies, with its parsed value. Raises InputError naming
    the first bad key.
    """
    check_keys(doc)
    s: dict[str, typing.Any] = _section(doc, "", "")
    mesh_doc = doc.get("mesh", {})
    kind = p_choice(*MESH_KINDS)(mesh_doc.get("kind", "rectangle"), "mesh.kind")
    s["mesh"] = _section(mesh_doc, "mesh", "mesh", kind)
    refine = _items(mesh_doc, "refine")
    s["mesh"]["refine"] = [_section(r, "mesh.refine[]", f"mesh.refine[{i}]", kind) for i, r in enumerate(refine)]
    for i, r in enumerate(s["mesh"]["refine"]):
        if sum(k in r for k in ("point", "segment", "box")) != 1:
            raise InputError(f"mesh.refine[{i}] needs exactly one of point, segment or box (3D)")
    if "units" in doc:
        s["units"] = _section(doc["units"], "units", "units")
    if "material" not in doc:
        raise InputError("the scene has no [material] table: give material.E and material.nu")
    s["material"] = _section(doc["material"], "material", "material")
    if "fatigue" in doc["material"]:
        s["material"]["fatigue"] = fatigue_settings(doc["material"]["fatigue"])
    s["cracks"] = []
    for i, c in enumerate(_items(doc, "cracks")):
        where = f"cracks[{i}]"
        crack = _section(c, "cracks[]", where)
        given = [k for k in CRACK_KINDS[2] + CRACK_KINDS[3] if k in c]
        if len(given) != 1:
            raise InputError(f"{where} needs exactly one of points (a polyline) or arc (a circular arc) in 2D, or "
                             f"ellipse, polygon or surface (a crack surface) in 3D; got "
                             f"{', '.join(given) if given else 'none'}")
        for sub in ("arc", "ellipse"):
            if sub in c:
                crack[sub] = _section(c[sub], f"cracks[].{sub}", f"{where}.{sub}")
        s["cracks"].append(crack)
    s["dirichlet"] = []
    for i, d in enumerate(_items(doc, "dirichlet")):
        where = f"dirichlet[{i}]"
        bc = _section(d, "dirichlet[]", where)
        given = [k for k in ("tag", "box", "point") if k in d]
        if len(given) != 1:
            raise InputError(f"{where} needs exactly one of tag, box or point, got "
                             f"{', '.join(given) if given else 'none'}")
        if "williams" in d:
            if "value" in d:
                raise InputError(f"{where}: give value or williams, not both")
            bc["williams"] = _section(d["williams"], "dirichlet[].williams", f"{where}.williams")
        elif isinstance(bc["value"], list) and bc["component"] not in ("both", "all"):
            raise InputError(f"{where}.value is a vector but component is {bc['component']!r}: "
                             "give one number for one component")
        s["dirichlet"].append(bc)
    s["symmetry"] = [_section(d, "symmetry[]", f"symmetry[{i}]") for i, d in enumerate(_items(doc, "symmetry"))]
    if not s["dirichlet"] and not s["symmetry"]:
        dim, _ = scene_dimension(s)
        raise BoundaryConditionError("the scene has no [[dirichlet]] condition: rigid body motion is free; "
                                     + rigid_motion_hint(dim or 2))
    loads_doc = doc.get("loads", {})
    s["loads"] = _section(loads_doc, "loads", "loads")
    s["loads"]["tractions"] = []
    for i, t in enumerate(_items(loads_doc, "tractions")):
        where = f"loads.tractions[{i}]"
        tr = _section(t, "loads.tractions[]", where)
        given = [k for k in ("value", "stress", "williams", "kirsch") if k in t]
        if len(given) != 1:
            raise InputError(f"{where} needs exactly one of value, stress, williams or kirsch, got "
                             f"{', '.join(given) if given else 'none'}")
        for sub in ("williams", "kirsch"):
            if sub in t:
                tr[sub] = _section(t[sub], f"loads.tractions[].{sub}", f"{where}.{sub}")
        s["loads"]["tractions"].append(tr)
        if "stress_gradient" in t and "stress" not in t:
            raise InputError(f"{where}.stress_gradient needs {where}.stress (the stress at origin)")
    s["loads"]["pressures"] = [_section(p, "loads.pressures[]", f"loads.pressures[{i}]")
                               for i, p in enumerate(_items(loads_doc, "pressures"))]
    s["loads"]["point_forces"] = [_section(p, "loads.point_forces[]", f"loads.point_forces[{i}]")
                                  for i, p in enumerate(_items(loads_doc, "point_forces"))]
    if "initial_stress" in loads_doc:
        s["loads"]["initial_stress"] = _section(loads_doc["initial_stress"], "loads.initial_stress",
                                                "loads.initial_stress")
    s["load_path"] = [_section(st, "load_path[]", f"load_path[{i}]") for i, st in enumerate(_items(doc, "load_path"))]
    if "growth" in doc:
        s["growth"] = _section(doc["growth"], "growth", "growth")
    if "spectrum" in doc:
        s["spectrum"] = spectrum_settings(doc["spectrum"])
    s["options"] = _section(doc.get("options", {}), "options", "options")
    s["outputs"] = _section(doc.get("outputs", {}), "outputs", "outputs")
    dim, why = scene_dimension(s)
    if dim is not None:
        check_dimension(doc, s, dim, why)
    return s


_INDEX = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?$")


def apply_override(doc: dict, text: str) -> None:
    """Apply one ``KEY=VALUE`` override to a scene document in place.

    KEY is a dotted path with indices for arrays of tables
    (``mesh.h``, ``options.radius``, ``cracks[0].points``); VALUE is a TOML
    value (``0.1``, ``[1, 2]``, ``"x"``; a bare word is taken as a string).
    """
    key, sep, raw = text.partition("=")
    key, raw = key.strip(), raw.strip()
    if not sep or not key:
        raise InputError(f"override {text!r} must look like KEY=VALUE, e.g. mesh.h=0.1")
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw
    parts = key.split(".")
    node = doc
    for j, part in enumerate(parts):
        m = _INDEX.match(part)
        if not m:
            raise InputError(f"override key {key!r}: bad part {part!r} (use names and [i] indices)")
        name, index = m.group(1), m.group(2)
        last = j == len(parts) - 1
        if index is not None:
            items = node.get(name)
            if isinstance(items, dict):
                items = node[name] = [items]
            if not isinstance(items, list) or int(index) >= len(items):
                n = len(items) if isinstance(items, list) else 0
                raise InputError(f"override key {key!r}: {name} has {n} entries, no [{index}]")
            if last:
                items[int(index)] = value
            else:
                node = items[int(index)]
        elif last:
            node[name] = value
        else:
            node = node.setdefault(name, {})
            if isinstance(node, list) and parts[j + 1].isdigit():  # cracks.0.points for cracks[0].points
                rest = ".".join(parts[j + 2:])
                raise InputError(f"override key {key!r}: {name} is an array of tables; index it with "
                                 f"brackets: {name}[{parts[j + 1]}]" + (f".{rest}" if rest else ""))
            if not isinstance(node, dict):
                raise InputError(f"override key {key!r}: {name} is not a table")


def read_document(path: str | pathlib.Path) -> dict:
    """The TOML document of a scene file (InputError on bad TOML, OSError if unreadable)."""
    path = pathlib.Path(path)
    try:
        with path.open("rb") as f:
            return tomllib.load(f)
    except tomllib.TOMLDecodeError as e:
        raise InputError(f"{path}: not valid TOML: {e}") from None



def _default_text(k: Key) -> str:
    if k.default is REQUIRED:
        return "required"
    if k.default is UNSET:
        return "—"
    if isinstance(k.default, bool):
        return "`true`" if k.default else "`false`"
    if isinstance(k.default, str):
        return f'`"{k.default}"`'
    if isinstance(k.default, list):
        return "`[" + ", ".join(f"{v:g}" if isinstance(v, float) else str(v) for v in k.default) + "]`"
    if isinstance(k.default, float):
        return f"`{k.default:g}`" if k.default != 0.0 else "`0.0`"
    return f"`{k.default}`"


def reference_rows() -> list[tuple[str, str, str, str]]:
    """(key, type, default, meaning) of every key, in schema order."""
    rows = []
    for k in SCHEMA:
        meaning = k.meaning
        if k.kinds and len(k.kinds) < len(MESH_KINDS):
            meaning += f" (mesh kind {', '.join(k.kinds)})"
        rows.append((k.path, k.type, _default_text(k), meaning))
    return rows


def reference_markdown() -> str:
    """The scene reference as a Markdown table (the README's)."""
    lines = ["| key | type | default | meaning |", "|---|---|---|---|"]
    for key, typ, default, meaning in reference_rows():
        lines.append(f"| `{key}` | {typ} | {default} | {meaning.replace('|', '/')} |")
    return "\n".join(lines) + "\n"
