"""The scene file's schema machinery: what a key is (``Key``: its path, type,
default, meaning and parser), the parsers of values (``p_*``: numbers,
choices, points, boxes, ...; each checks a value and names the key when it
is wrong), and the markers of keys without a default (REQUIRED, UNSET).
The keys themselves are listed section by section in the modules beside
this one (mesh, material, cracks, conditions, options, growth)."""
from __future__ import annotations

import dataclasses
import difflib
import math
import re
import typing

from ...errors import InputError


class _Required:
    """Marker of a key without a default (it must be given where it applies)."""

    def __repr__(self) -> str:
        return "required"


class _Unset:
    """Marker of an optional key without a default (one of several alternatives)."""

    def __repr__(self) -> str:
        return "unset"


REQUIRED = _Required()


UNSET = _Unset()


def _type_error(path: str, expected: str, value) -> InputError:
    return InputError(f"{path} must be {expected}, got {value!r}")


def _number(value, path: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _type_error(path, "a number", value)
    v = float(value)
    if not math.isfinite(v):
        raise _type_error(path, "a finite number", value)
    return v


def p_float(minimum: float | None = None, positive: bool = False):
    def parse(value, path):
        v = _number(value, path)
        if positive and not v > 0.0:
            raise _type_error(path, "a positive number", value)
        if minimum is not None and v < minimum:
            raise _type_error(path, f"a number >= {minimum:g}", value)
        return v
    return parse


def p_int(minimum: int = 1):
    def parse(value, path):
        if isinstance(value, bool) or not isinstance(value, int):
            raise _type_error(path, "an integer", value)
        if value < minimum:
            raise _type_error(path, f"an integer >= {minimum}", value)
        return int(value)
    return parse


def p_bool(value, path):
    if not isinstance(value, bool):
        raise _type_error(path, "true or false", value)
    return value


def p_str(value, path):
    if not isinstance(value, str):
        raise _type_error(path, "a string", value)
    return value


def p_choice(*choices: str):
    def parse(value, path):
        if value not in choices:
            same = [c for c in choices if c.lower() == str(value).strip().lower()]   # 'Y' means 'y'
            close = same or difflib.get_close_matches(str(value), choices, n=1, cutoff=0.0)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise InputError(f"{path} must be one of {', '.join(repr(c) for c in choices)}, "
                             f"got {value!r}{hint}")
        return value
    return parse


def p_numbers(n: int, what: str):
    def parse(value, path):
        if not isinstance(value, list) or len(value) != n:
            raise _type_error(path, what, value)
        return [_number(v, f"{path}[{i}]") for i, v in enumerate(value)]
    return parse


def p_number_list(value, path):
    """A list of numbers of any length."""
    if not isinstance(value, list):
        raise _type_error(path, "a list of numbers [v, ...]", value)
    return [_number(v, f"{path}[{i}]") for i, v in enumerate(value)]


p_point = p_numbers(2, "a point [x, y]")


p_vector = p_numbers(2, "a vector [x, y]")


p_point3 = p_numbers(3, "a point [x, y, z]")


p_vector3 = p_numbers(3, "a vector [x, y, z]")


def p_coords(what: str, counts: tuple[int, ...] = (2, 3)):
    """A list of 2 or 3 numbers (a 2D or 3D point or vector; the scene's
    dimension is checked once it is known: dimension.check_dimension)."""
    def parse(value, path):
        if not isinstance(value, list) or len(value) not in counts:
            raise _type_error(path, what, value)
        return [_number(v, f"{path}[{i}]") for i, v in enumerate(value)]
    return parse


p_point_any = p_coords("a point [x, y] (3D: [x, y, z])")


p_vector_any = p_coords("a vector [x, y] (3D: [x, y, z])")


p_stress_any = p_coords("a stress [sxx, syy, sxy] (3D: [sxx, syy, szz, syz, sxz, sxy])", (3, 6))


def p_solid_box(value, path):
    x0, y0, z0, x1, y1, z1 = p_numbers(6, "a box [x0, y0, z0, x1, y1, z1]")(value, path)
    if not (x1 > x0 and y1 > y0 and z1 > z0):
        raise InputError(f"{path} = {value} is empty: need x0 < x1, y0 < y1 and z0 < z1")
    return [x0, y0, z0, x1, y1, z1]


def p_polygon(value, path):
    if not isinstance(value, list) or len(value) < 3:
        raise _type_error(path, "a list of at least three points [[x, y, z], ...]", value)
    return [p_point3(v, f"{path}[{i}]") for i, v in enumerate(value)]


p_angles = p_numbers(2, "two angles [start, end] in degrees")


def p_gradient(value, path):
    """A linear stress field's gradient, one row per coordinate: 2D
    [[d sxx/dx, d syy/dx, d sxy/dx], [d sxx/dy, d syy/dy, d sxy/dy]], 3D
    three rows (d/dx, d/dy, d/dz) of the six components (sxx, syy, szz,
    syz, sxz, sxy) (the scene's dimension is checked once it is known:
    dimension.check_dimension)."""
    what = ("a stress gradient [[dsxx/dx, dsyy/dx, dsxy/dx], [dsxx/dy, dsyy/dy, dsxy/dy]] (3D: three rows d/dx, "
            "d/dy, d/dz of [sxx, syy, szz, syz, sxz, sxy])")
    if not isinstance(value, list) or len(value) not in (2, 3):
        raise _type_error(path, what, value)
    return [p_numbers(3 if len(value) == 2 else 6, what)(v, f"{path}[{i}]") for i, v in enumerate(value)]


def p_box(value, path):
    x0, y0, x1, y1 = p_numbers(4, "a box [x0, y0, x1, y1]")(value, path)
    if not (x1 > x0 and y1 > y0):
        raise InputError(f"{path} = {value} is empty: need x0 < x1 and y0 < y1")
    return [x0, y0, x1, y1]


def p_holes(value, path):
    """[[x, y, r], ...]: at least one hole, radii > 0."""
    if not isinstance(value, list) or not value:
        raise _type_error(path, "a list of holes [[x, y, r], ...]", value)
    holes = [p_numbers(3, "a hole [x, y, r]")(v, f"{path}[{i}]") for i, v in enumerate(value)]
    for i, (_, _, r) in enumerate(holes):
        if not r > 0.0:
            raise InputError(f"{path}[{i}]: the radius must be > 0, got {r}")
    return holes


def p_region(value, path):
    """A box that may be flat (x0 = x1 or y0 = y1: the nodes on a line; in
    3D [x0, y0, z0, x1, y1, z1], flat: the nodes on a plane or a line)."""
    if isinstance(value, list) and len(value) == 6:
        v = p_numbers(6, "a box [x0, y0, z0, x1, y1, z1]")(value, path)
        if not all(v[3 + d] >= v[d] for d in range(3)):
            raise InputError(f"{path} = {value}: need x0 <= x1, y0 <= y1 and z0 <= z1")
        return v
    x0, y0, x1, y1 = p_numbers(4, "a box [x0, y0, x1, y1] (3D: [x0, y0, z0, x1, y1, z1])")(value, path)
    if not (x1 >= x0 and y1 >= y0):
        raise InputError(f"{path} = {value}: need x0 <= x1 and y0 <= y1")
    return [x0, y0, x1, y1]


def p_polyline(value, path):
    if not isinstance(value, list) or len(value) < 2:
        raise _type_error(path, "a list of at least two points [[x, y], ...]", value)
    return [p_point(v, f"{path}[{i}]") for i, v in enumerate(value)]


def p_tag(value, path):
    if isinstance(value, bool) or not isinstance(value, (str, int)):
        raise _type_error(path, "a boundary tag name (string) or number (integer)", value)
    return value


def p_segment(value, path):
    what = "a segment [[x0, y0], [x1, y1]] (3D: [[x0, y0, z0], [x1, y1, z1]])"
    if not isinstance(value, list) or len(value) != 2:
        raise _type_error(path, what, value)
    pts = [p_point_any(v, f"{path}[{i}]") for i, v in enumerate(value)]
    if len(pts[0]) != len(pts[1]):
        raise _type_error(path, what, value)
    return pts


def p_group(value, path):
    if not isinstance(value, str) or not value:
        raise _type_error(path, "a load group name (a non-empty string)", value)
    return value


def p_factors(value, path):
    if not isinstance(value, dict) or not value:
        raise _type_error(path, "a table of load group = factor, e.g. { clamp = 1.0, shear = 0.5 }", value)
    return {str(k): _number(v, f"{path}.{k}") for k, v in value.items()}


def p_value(value, path):
    if isinstance(value, list):
        return p_vector_any(value, path)
    return _number(value, path)


@dataclasses.dataclass(frozen=True)
class Key:
    """One scene-file key.

    Attributes:
        path: dotted path; ``[]`` marks an array of tables (``cracks[].points``).
        type: the type as documented.
        default: the value when absent; REQUIRED (must be given where it
            applies) or UNSET (optional, no value: one of alternatives).
        meaning: what it does (README's scene reference).
        parse: converts and checks a value: (value, path) -> value.
        kinds: for mesh keys, the mesh kinds the key applies to (empty: all).
    """
    path: str
    type: str
    default: typing.Any
    meaning: str
    parse: typing.Callable[[typing.Any, str], typing.Any]
    kinds: tuple[str, ...] = ()

    @property
    def parent(self) -> str:
        return self.path.rpartition(".")[0]

    @property
    def name(self) -> str:
        return self.path.rpartition(".")[2]



def docstring_attributes(cls) -> dict[str, str]:
    """'name: text' entries of the Attributes section of a class docstring."""
    out: dict[str, str] = {}
    doc = (cls.__doc__ or "").split("Attributes:", 1)[-1]
    name = None
    for line in doc.splitlines():
        m = re.match(r"^\s{8}([A-Za-z_][A-Za-z0-9_, ]*): (.*)$", line)
        if m:
            name = m.group(1)
            out[name] = m.group(2).strip()
        elif name and line.strip():
            out[name] += " " + line.strip()
    for names in [n for n in out if "," in n]:  # "a, b, c: text" documents three fields
        for n in names.split(","):
            out.setdefault(n.strip(), out[names])
    return out


