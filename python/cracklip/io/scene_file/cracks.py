"""[[cracks]]: the keys (KEYS) and the crack each entry builds: a polyline
or a circular arc on a planar part (``build_crack``), an ellipse, a planar
polygon or a triangulated surface in a solid (``crack_surface``); the
one-line description of a crack surface in the scene's notes."""
from __future__ import annotations

import pathlib

import numpy as np

from ...errors import CrackGeometryError, InputError
from ...scene.crack import Crack, arc_polyline
from ...scene.crack_surface import EllipticalCrack, PolygonCrack, SurfaceCrack, read_crack_surface
from .schema import (REQUIRED, UNSET, Key, p_angles, p_float, p_group, p_int, p_point, p_point3, p_polygon,
                     p_polyline, p_str, p_vector3)


#: Crack keys of each dimension (one of them per [[cracks]] entry).
CRACK_KINDS = {2: ("points", "arc"), 3: ("ellipse", "polygon", "surface")}



KEYS: list[Key] = [
    Key("cracks[].name", "string", "", "label in messages and outputs (default: crack i)", p_str),
    Key("cracks[].points", "[[x, y], ...]", UNSET,
        "2D: polyline; an end inside the part is a tip, an end on or outside the boundary makes an "
        "edge crack (on a hole: on its circle, which the mesh's facets approximate by chords)", p_polyline),
    Key("cracks[].arc.center", "[x, y]", REQUIRED, "circular-arc crack: centre", p_point),
    Key("cracks[].arc.radius", "float", REQUIRED, "circular-arc crack: radius", p_float(positive=True)),
    Key("cracks[].arc.angles", "[start, end]", REQUIRED,
        "circular-arc crack: polar angles of its ends, degrees (counter-clockwise if end > start)",
        p_angles),
    Key("cracks[].arc.segments", "integer", 24, "circular-arc crack: polyline segments, each along a tangent of the arc (the end ones along the tips' "
        "tangents, so K sees the arc's direction there)", p_int(1)),
    Key("cracks[].ellipse.center", "[x, y, z]", REQUIRED, "3D elliptical (or circular) planar crack: centre; "
        "on a face of the part it is a surface crack, on an edge a corner crack (the part's boundary cuts it)",
        p_point3),
    Key("cracks[].ellipse.normal", "[x, y, z]", REQUIRED, "elliptical crack: normal of its plane (points to the "
        "+ lip)", p_vector3),
    Key("cracks[].ellipse.a", "float", REQUIRED, "elliptical crack: semi-axis along `a_direction`", p_float(positive=True)),
    Key("cracks[].ellipse.b", "float", UNSET, "elliptical crack: the other semi-axis, along normal x a_direction "
        "(unset: b = a, a circle)", p_float(positive=True)),
    Key("cracks[].ellipse.a_direction", "[x, y, z]", UNSET, "elliptical crack: direction of the semi-axis a (projected "
        "onto the plane; unset: any direction in it, fine for a circle)", p_vector3),
    Key("cracks[].polygon", "[[x, y, z], ...]", UNSET, "3D planar crack bounded by a polygon (vertices in order; "
        "its normal by the right-hand rule)", p_polygon),
    Key("cracks[].surface", "string", UNSET, "3D crack given as a triangulated surface: an STL or gmsh .msh "
        "file of consistently oriented triangles, relative to the scene file (its boundary inside the part "
        "is the front)", p_str),
    Key("cracks[].pressure", "float", 0.0, "pressure on both lips (> 0 pushes them apart: a pressurised "
        "crack); with contact it acts besides the contact pressure", p_float()),
    Key("cracks[].pressure_group", "string", "default", "load group of the lip pressure (see load_path)", p_group),
]


def build_crack(c: dict, i: int) -> Crack:
    name = c["name"] or f"crack {i}"
    if "arc" in c:
        a = c["arc"]
        t0, t1 = np.radians(a["angles"])
        if abs(t1 - t0) < 1e-12:
            raise InputError(f"cracks[{i}].arc.angles: the start and end angles are equal")
        pts = arc_polyline(a["center"], a["radius"], t0, t1, a["segments"])
        return Crack(pts, name=name, pressure=c["pressure"], pressure_group=c["pressure_group"])
    return Crack(np.asarray(c["points"], dtype=float), name=name, pressure=c["pressure"],
                 pressure_group=c["pressure_group"])



def crack_surface(c: dict, i: int, base_dir: pathlib.Path):
    """The crack surface of a parsed [[cracks]] entry (ellipse, polygon or surface)."""
    name = c["name"] or f"crack {i}"
    kw = {"name": name, "pressure": c["pressure"], "pressure_group": c["pressure_group"]}
    where = f"cracks[{i}]"
    try:
        if "ellipse" in c:
            e = c["ellipse"]
            return EllipticalCrack(e["center"], e["normal"], e["a"], e.get("b"), e.get("a_direction"), **kw)
        if "polygon" in c:
            return PolygonCrack(np.asarray(c["polygon"], dtype=float), **kw)
        f = pathlib.Path(c["surface"])
        f = f if f.is_absolute() else base_dir / f
        sc = read_crack_surface(f, name=name)
        return SurfaceCrack(sc.vertices, sc.triangles, source=f"{where}.surface = {c['surface']!r}", **kw)
    except CrackGeometryError as e:
        raise CrackGeometryError(f"{where}: {e}") from None


def describe_crack(crack) -> str:
    """One line of a crack surface (the notes of a scene)."""
    def v(a) -> str:
        return "[" + ", ".join(f"{x:.6g}" for x in np.asarray(a, dtype=float)) + "]"
    if isinstance(crack, EllipticalCrack):
        shape = (f"circle, radius {crack.a:.6g}" if crack.a == crack.b else
                 f"ellipse, semi-axes a = {crack.a:.6g} along {v(crack.axis)}, b = {crack.b:.6g}")
        return f"{crack.name}: {shape}, centre {v(crack.center)}, normal {v(crack.normal)}"
    if isinstance(crack, PolygonCrack):
        return f"{crack.name}: polygon of {len(crack.points)} vertices, normal {v(crack.normal)}, area {crack.area:.6g}"
    return (f"{crack.name}: triangulated surface, {len(crack.vertices)} vertices, {len(crack.triangles)} triangles, "
            f"area {crack.area:.6g}")


