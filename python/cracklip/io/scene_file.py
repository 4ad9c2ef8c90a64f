"""Scene files: a TOML description of a cracked part, read into a ``cracklip.Scene``.

One table, ``SCHEMA``, lists every key with its type, default and meaning;
the parser accepts exactly these keys and the README's scene reference is
generated from it (``reference_markdown()``, or ``python3 -m cracklip
reference``). An unknown key is an ``InputError`` naming the nearest valid
key. Typical use::

    from cracklip.io.scene_file import load_scene_file
    sf = load_scene_file("demos/scenes/block_uniform_pressure.toml", overrides=["mesh.h=0.1"])
    solution = cracklip.solve(sf.scene)

Paths in the schema: ``mesh.h`` is key ``h`` of table ``[mesh]``;
``cracks[].points`` is key ``points`` of every ``[[cracks]]`` entry;
``loads.tractions[].kirsch.remote_stress`` is a key of the inline table
``kirsch = {...}`` of a ``[[loads.tractions]]`` entry.
"""
from __future__ import annotations

import dataclasses
import difflib
import math
import pathlib
import re
import time
import tomllib
import typing

import numpy as np

from ..errors import BoundaryConditionError, InputError, MeshError
from ..scene.conditions import Dirichlet, LoadStep, PointForce, Traction
from ..scene.crack import Crack
from ..scene.material import Material
from ..scene.mesh import MeshData, create_half_annulus, create_plate_with_holes, create_rectangle, read_msh
from ..scene.options import ENRICHMENTS, Options, SOLVERS, TIP_QUADRATURES
from ..scene.scene import Scene
from ..scene.stress_field import LinearStress
from ..scene.units import FORCES, LENGTHS, STRESSES, Units
from .scene_file_3d import CRACK_KINDS, check_dimension, scene_dimension


MESH_KINDS = ("rectangle", "plate_with_hole", "plate_with_holes", "half_annulus", "box", "cylinder", "geometry",
              "file")


GENERATED = ("rectangle", "plate_with_hole", "plate_with_holes", "half_annulus")


#: Generated 3D parts (tetrahedra).
SOLIDS = ("box", "cylinder")


#: Kinds that cracklip meshes with gmsh (mesh.h applies).
MESHED = GENERATED + SOLIDS + ("geometry",)


#: Kinds whose mesh can be 3D (crack surfaces, front refinement).
KINDS_3D = SOLIDS + ("geometry", "file")


PLATES = ("rectangle", "plate_with_hole", "plate_with_holes")


STRESS_COMPONENTS = ("xx", "yy", "xy", "von_mises")


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
            close = difflib.get_close_matches(str(value), choices, n=1, cutoff=0.0)
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


p_point = p_numbers(2, "a point [x, y]")


p_vector = p_numbers(2, "a vector [x, y]")


p_stress = p_numbers(3, "a stress [sigma_xx, sigma_yy, sigma_xy]")


p_point3 = p_numbers(3, "a point [x, y, z]")


p_vector3 = p_numbers(3, "a vector [x, y, z]")


def p_coords(what: str, counts: tuple[int, ...] = (2, 3)):
    """A list of 2 or 3 numbers (a 2D or 3D point or vector; the scene's
    dimension is checked once it is known: scene_file_3d.check_dimension)."""
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
    """[[d sxx/dx, d syy/dx, d sxy/dx], [d sxx/dy, d syy/dy, d sxy/dy]]."""
    what = "a stress gradient [[dsxx/dx, dsyy/dx, dsxy/dx], [dsxx/dy, dsyy/dy, dsxy/dy]]"
    if not isinstance(value, list) or len(value) != 2:
        raise _type_error(path, what, value)
    return [p_numbers(3, what)(v, f"{path}[{i}]") for i, v in enumerate(value)]


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


_OPTION_MEANINGS = {
    "enrichment": "crack-tip enrichment: `vector` (the two Williams fields, 2 dofs per node), "
                  "`scalar` (4 branch functions, 8 dofs per node) or `none` (Heaviside only)",
    "radius": "geometric enrichment radius: nodes within it of a tip get tip dofs; 0 enriches "
              "the tip cell's nodes only",
    "blending": "`corrected` (Fries' corrected X-FEM, optimal rate) or `standard` blending",
    "quadrature": "rule where tip functions live: `collapsed` (quasi-polar fan from the tip) "
                  "or `gauss` (the paper's plain rule)",
    "quadrature_degree": "degree p of the `gauss` tip rule ((p + 3) / 2)^2 points per sub-triangle",
    "tip_radial": "`collapsed` rule: points along each ray of a fan triangle",
    "tip_angular": "`collapsed` rule: points across each fan triangle",
    "tip_max_angle": "`collapsed` rule: largest apex angle of a fan triangle (radians)",
    "degree": "Gauss degree in enriched cells without tip functions (1 is exact for P1 x Heaviside)",
    "contact": "crack-lip contact: `none` (traction-free lips), `bilateral` (lips held together, "
               "free to slide) or `unilateral` (gap >= 0, pressure >= 0; active set)",
    "multipliers": "multiplier space: `stable` (P1-, P0 in the tip cell) or `naive` (P1 on every "
                   "node of the cut cells; violates inf-sup)",
    "contact_points": "Gauss points per crack segment for the contact terms",
    "active_set_start": "initial active set of unilateral contact: `closed` or `open`",
    "max_active_set_iterations": "active-set iterations before giving up (a set that comes back stops at once as a cycle)",
    "snap_tol": "a node closer to a crack than snap_tol times its shortest edge is moved onto it",
    "facet_degree": "quadrature degree of boundary tractions",
    "residual_tol": "largest accepted relative residual of a linear solve",
    "rescale": "`none`, or `nodal`: each enriched node's block of standard and enriched dofs "
               "orthonormalised (Cholesky), others Jacobi-scaled; same answer, better conditioned matrix",
    "friction": "Coulomb friction coefficient mu of the lips (0: frictionless); needs contact `bilateral` or "
                "`unilateral`; each multiplier open, stick or slip",
    "load_steps": "increments per step of the load path (friction is path-dependent: more increments "
                  "follow the slip history closely)",
    "sif_radius": "radius of the largest SIF domain at every tip (K also on 1/2 and 3/4 of it; their "
                  "spread is reported); 0: 6 element sizes at that tip; clipped to stay inside the part "
                  "and away from other tips, cracks, kinks and holes (with a warning)",
    "sif_ring": "K on one ring as another code defines it: q = 1 within r_in, 0 beyond r_out, linear between "
                "(code_aster's R_INF / R_SUP, MOOSE's rings; r_in = r_out: the plateau of that radius); NOT clipped: "
                "a ring reaching a hole, kink, tip or the boundary warns and its K is marked unreliable; no spread; "
                "overrides sif_radius (a ring through a hole: docs/growth.md)",
    "accuracy": "target of the estimated discretisation error of every K, relative to the K scale (0.01: 1 %); "
                "0: off. Refines around every tip (sizes halved within twice the crack's length, one level per "
                "solve) until the estimate is below it; reports the levels, the estimate and the extrapolated K; "
                "warns if not reached (docs/guide.md)",
    "accuracy_levels": "at most this many refinement levels for options.accuracy (each about 4 times the cells "
                       "in the refined region)",
    "solver": "linear solver: `direct` (MUMPS LDL^T), `iterative` (AMG in a phantom-node basis with a "
              "direct solve of the crack band; same checked accuracy) or `auto` (iterative from 5e4 "
              "dofs when 1-5 % of them are enriched and from 2e6 dofs always, else direct: the faster one as "
              "measured)",
}


_OPTION_CHOICES = {
    "enrichment": ENRICHMENTS, "blending": ("corrected", "standard"), "quadrature": TIP_QUADRATURES,
    "contact": ("none", "bilateral", "unilateral"), "multipliers": ("stable", "naive"),
    "active_set_start": ("closed", "open"), "rescale": ("none", "nodal"),
    "solver": SOLVERS,
}


def _docstring_attributes(cls) -> dict[str, str]:
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


def _option_keys() -> list[Key]:
    """The [options] keys: every field of cracklip.Options (defaults from the
    dataclass itself; the meaning from _OPTION_MEANINGS, else from Options'
    docstring)."""
    keys = []
    documented = _docstring_attributes(Options)
    for f in dataclasses.fields(Options):
        default = f.default
        meaning = _OPTION_MEANINGS.get(f.name) or documented.get(f.name, f.name.replace("_", " "))
        if f.name in _OPTION_CHOICES:
            keys.append(Key(f"options.{f.name}", "string", default, meaning, p_choice(*_OPTION_CHOICES[f.name])))
        elif f.name == "sif_ring":
            keys.append(Key(f"options.{f.name}", "[r_in, r_out]", UNSET, meaning,
                            p_numbers(2, "two radii [r_in, r_out]")))
        elif isinstance(default, bool):
            keys.append(Key(f"options.{f.name}", "boolean", default, meaning, p_bool))
        elif isinstance(default, int):
            keys.append(Key(f"options.{f.name}", "integer", default, meaning, p_int(1)))
        elif isinstance(default, str):
            keys.append(Key(f"options.{f.name}", "string", default, meaning, p_str))
        else:
            keys.append(Key(f"options.{f.name}", "float", default, meaning, p_float(0.0)))
    return keys


def _growth_keys() -> list[Key]:
    """The [growth] keys: every field of cracklip.scene.growth.Growth, with the
    meanings of its docstring (cycle_max / cycle_min are tables of load group
    = factor; the optional numbers have no default)."""
    from ..scene.growth import CRITERIA, Growth
    documented = _docstring_attributes(Growth)
    keys = []
    for f in dataclasses.fields(Growth):
        meaning = documented.get(f.name, f.name.replace("_", " "))
        path = f"growth.{f.name}"
        if f.name == "criterion":
            keys.append(Key(path, "string", f.default, meaning, p_choice(*CRITERIA)))
        elif f.name in ("fatigue_material", "spectrum"):
            continue  # the [material.fatigue] and [spectrum] tables
        elif f.name in ("cycle_max", "cycle_min"):
            keys.append(Key(path, "table of group = factor", UNSET, meaning, p_factors))
        elif f.name == "reference_stress":
            keys.append(Key(path, "table of group = stress", UNSET, meaning, p_factors))
        elif f.name == "steps":
            keys.append(Key(path, "integer", f.default, meaning, p_int(1)))
        elif f.name == "corrections":
            keys.append(Key(path, "integer", f.default, meaning, p_int(0)))
        elif f.default is None:
            keys.append(Key(path, "float", UNSET, meaning, p_float()))
        else:
            keys.append(Key(path, "float", f.default, meaning, p_float()))
    return keys


def p_numbers_any(value, path):
    """A list of numbers (one load group) or of rows of numbers (several)."""
    if not isinstance(value, list) or not value:
        raise _type_error(path, "a list of factors, or of rows of factors (one per group)", value)
    if all(isinstance(v, list) for v in value):
        return [[_number(x, f"{path}[{i}][{j}]") for j, x in enumerate(v)] for i, v in enumerate(value)]
    return [_number(v, f"{path}[{i}]") for i, v in enumerate(value)]


def p_rows(value, path):
    """Rows of numbers (a tabular da/dN)."""
    if not isinstance(value, list) or not value or not all(isinstance(v, list) for v in value):
        raise _type_error(path, "rows of numbers [[da/dN, Delta K at R_1, ...], ...]", value)
    return [[_number(x, f"{path}[{i}][{j}]") for j, x in enumerate(v)] for i, v in enumerate(value)]


def p_list(value, path):
    if not isinstance(value, list) or not value:
        raise _type_error(path, "a list of numbers", value)
    return [_number(v, f"{path}[{i}]") for i, v in enumerate(value)]


def p_names(value, path):
    if not isinstance(value, list) or not value or not all(isinstance(v, str) and v for v in value):
        raise _type_error(path, "a list of load group names", value)
    return list(value)


def _fatigue_keys() -> list[Key]:
    """[material.fatigue]: the growth law, its constants and their units,
    toughness, closure, retardation (cracklip.scene.fatigue)."""
    from ..scene.fatigue import CLOSURES, CONSTRAINTS, EXAMPLES, LAWS, RETARDATIONS
    t = "material.fatigue"
    const = [
        ("C", "rate coefficient (paris, walker, forman, nasgro)"), ("m", "exponent (paris, walker)"),
        ("n", "exponent (forman, nasgro)"), ("gamma", "Walker's exponent of (1 - R), 0..1 (walker)"),
        ("K_f", "Forman's critical K (forman)"), ("p", "threshold exponent (nasgro)"),
        ("q", "toughness exponent (nasgro)"), ("dK1", "long-crack threshold at R = 0 (nasgro)"),
        ("C_th_plus", "threshold R exponent for R >= 0 (nasgro)"),
        ("C_th_minus", "threshold R exponent for R < 0 (nasgro)"),
        ("alpha", "Newman's constraint factor 1..3 (nasgro; closure newman); default 2"),
        ("smax_over_flow", "S_max / sigma_0 of Newman's f (nasgro; closure newman); default 0.3"),
        ("a0", "intrinsic crack length of the threshold's small-crack term (nasgro); default 0: none"),
        ("D", "rate coefficient (hartman_schijve)"), ("dK_thr", "threshold (hartman_schijve)"),
        ("A", "apparent cyclic toughness (hartman_schijve)"), ("exponent", "exponent (hartman_schijve)"),
    ]
    keys = [
        Key(f"{t}.law", "string", UNSET, "growth law of the fatigue life: " + ", ".join(f"`{x}`" for x in LAWS)
            + " (docs/life.md); with [spectrum] or growth.cycle_min / R instead of growth.paris_C", p_choice(*LAWS)),
        Key(f"{t}.example", "string", UNSET, "start from a documented constant set (keys given here override): "
            + ", ".join(f"`{x}`" for x in EXAMPLES), p_choice(*EXAMPLES)),
    ] + [Key(f"{t}.{name}", "float", UNSET, meaning, p_float()) for name, meaning in const] + [
        Key(f"{t}.table_R", "[R, ...]", UNSET, "tabular law: the R of each da/dN curve (ascending)", p_list),
        Key(f"{t}.table", "[[da/dN, dK_R1, ...], ...]", UNSET, "tabular law: rows of a rate and the Delta K giving "
            "it at each R (easigrow's layout)", p_rows),
        Key(f"{t}.threshold", "float", 0.0, "Delta K below which a cycle does not grow (any law)", p_float(0.0)),
        Key(f"{t}.K_Ic", "float", UNSET, "plane-strain toughness: failure at K_max >= K_c (K_c(t) with B_k)",
            p_float(positive=True)),
        Key(f"{t}.A_k", "float", UNSET, "K_c(t) = K_Ic [1 + B_k exp(-(A_k t / t0)^2)], t0 = 2.5 (K_Ic / "
            "yield_stress)^2; default 1", p_float(0.0)),
        Key(f"{t}.B_k", "float", UNSET, "see A_k; unset: K_c = K_Ic", p_float(0.0)),
        Key(f"{t}.thickness", "float", UNSET, "thickness t of K_c(t) and of the plastic zone's constraint",
            p_float(positive=True)),
        Key(f"{t}.yield_stress", "float", UNSET, "yield stress: net-section yield (failure) and the plastic "
            "zone of retardation", p_float(positive=True)),
        Key(f"{t}.closure", "string", "contact", "`contact` (K from crack-lip contact at every load state; "
            "elastic, no plastic wake), `newman` (Newman's f on the linear K) or `none`; never both",
            p_choice(*CLOSURES)),
        Key(f"{t}.retardation", "string", "none", "load interaction: `none`, `wheeler` or `willenborg` "
            "(generalized)", p_choice(*RETARDATIONS)),
        Key(f"{t}.wheeler_exponent", "float", UNSET, "Wheeler's gamma", p_float(positive=True)),
        Key(f"{t}.shutoff_ratio", "float", UNSET, "Willenborg's shut-off overload ratio (> 1)", p_float(positive=True)),
        Key(f"{t}.constraint", "string", "auto", "plastic zone (K / yield_stress)^2 / (beta pi): `plane_stress` "
            "(beta 2), `plane_strain` (6) or `auto` (by thickness)", p_choice(*CONSTRAINTS)),
        Key(f"{t}.units.length", "string", UNSET, "length unit of the constants (da per cycle, a0, "
            "thickness); with units.stress they are converted into the scene's [units]", p_choice(*LENGTHS)),
        Key(f"{t}.units.stress", "string", UNSET, "stress unit of the constants (K in stress sqrt(length))",
            p_choice(*STRESSES)),
    ]
    return keys


def _life_keys() -> list[Key]:
    """The [life] keys and the input-file keys of [material.fatigue] (the
    scene reference lists them with the others)."""
    from ..scene.input_files import RATE_LAYOUTS, UNSUPPORTED_RATE_LAYOUTS
    from ..scene.life import CENTRE_FORMS, GEOMETRIES, INTEGRATIONS
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


def _spectrum_keys() -> list[Key]:
    from ..scene.spectrum import COUNTING, RESIDUE
    return [
        Key("spectrum.groups", "[group, ...]", ["default"], "the load groups whose factors the spectrum's "
            "points give (columns); other groups stay at their steady factor", p_names),
        Key("spectrum.counting", "string", "rainflow", "cycle counting: " + ", ".join(f"`{c}`" for c in COUNTING),
            p_choice(*COUNTING)),
        Key("spectrum.residue", "string", "close", "`close` (the pass repeats: full cycles only, E1049's "
            "repeated history) or `half` (each pass counted alone, residue as half cycles)", p_choice(*RESIDUE)),
        Key("spectrum.steady", "table of group = factor", UNSET, "factors of the groups not in the spectrum "
            "(unset ones: 1, e.g. a residual stress)", p_factors),
        Key("spectrum.block_name", "string", "flight", "what a block is called in outputs", p_str),
        Key("spectrum.contact_levels", "integer", 2, "contact solves per growth step at the load states "
            "where the lips touch (K interpolated between them and the closure level)", p_int(1)),
        Key("spectrum.max_passes", "float", 1e9, "stop after this many passes", p_float(positive=True)),
        Key("spectrum.blocks[].points", "[factor, ...] or [[factors], ...]", UNSET, "turning points of the "
            "block: one factor per point (one group) or one row per point (one factor per group); one of "
            "points, file", p_numbers_any),
        Key("spectrum.blocks[].file", "string", UNSET, "a file of turning points, relative to the scene file: one "
            "value per line, or a header naming the group of each column, or a block-load table (header max, min, "
            "cycles); docs/life.md", p_str),
        Key("spectrum.blocks[].repeat", "integer", 1, "times the block comes in a pass", p_int(1)),
        Key("spectrum.blocks[].name", "string", "", "label of the block (e.g. a flight type)", p_str),
    ]


_WILLIAMS = [
    ("K_I", "float", 0.0, "mode I stress intensity factor of the exact Williams field", p_float()),
    ("K_II", "float", 0.0, "mode II stress intensity factor of the exact Williams field", p_float()),
    ("tip", "[x, y]", REQUIRED, "crack tip of the Williams field (an end of one of the cracks)", p_point),
    ("angle", "float", 0.0, "crack direction at the tip, degrees from the x axis", p_float()),
]


SCHEMA: tuple[Key, ...] = tuple([
    Key("title", "string", "", "name shown in outputs (default: the file name)", p_str),
    # mesh
    Key("mesh.kind", "string", "rectangle",
        "`rectangle`, `plate_with_hole`, `plate_with_holes` (a drilled plate), `half_annulus` (r between hole_radius and outer_radius, "
        "y >= 0, centre at the origin), 3D: `box`, `cylinder` (tetrahedra, refined along the crack fronts), "
        "`geometry` (your part as a gmsh .geo, STEP or BREP file, meshed by cracklip "
        "with h, tip_h and refine; a solid is meshed in tetrahedra) or `file` (a gmsh .msh mesh, refined locally "
        "by cracklip for tip_h and refine; 3D: tetrahedra, used as they are)",
        p_choice(*MESH_KINDS)),
    Key("mesh.h", "float", REQUIRED, "element size", p_float(positive=True), MESHED),
    Key("mesh.box", "[x0, y0, z0, x1, y1, z1]", REQUIRED,
        "the box (3D); tags `xmin`, `xmax`, `ymin`, `ymax`, `zmin`, `zmax`", p_solid_box, ("box",)),
    Key("mesh.center", "[x, y, z]", REQUIRED, "centre of the cylinder's bottom face (tag `bottom`)", p_point3,
        ("cylinder",)),
    Key("mesh.axis", "[x, y, z]", [0.0, 0.0, 1.0], "direction from the cylinder's bottom face to its top face "
        "(tag `top`; the curved face is `side`)", p_vector3, ("cylinder",)),
    Key("mesh.radius", "float", REQUIRED, "radius of the cylinder", p_float(positive=True), ("cylinder",)),
    Key("mesh.length", "float", REQUIRED, "length of the cylinder along its axis", p_float(positive=True),
        ("cylinder",)),
    Key("mesh.domain", "[x0, y0, x1, y1]", [-1.0, -1.0, 1.0, 1.0],
        "the rectangle; tags `left`, `right`, `bottom`, `top`", p_box, PLATES),
    Key("mesh.hole_center", "[x, y]", [0.0, 0.0], "centre of the hole (tag `hole`)", p_point,
        ("plate_with_hole",)),
    Key("mesh.hole_radius", "float", REQUIRED, "radius of the hole (tag `hole`)", p_float(positive=True),
        ("plate_with_hole", "half_annulus")),
    Key("mesh.holes", "[[x, y, r], ...]", REQUIRED, "the holes' centres and radii (tag `hole`: every hole's edge)",
        p_holes, ("plate_with_holes",)),
    Key("mesh.outer_radius", "float", REQUIRED,
        "outer radius of the half annulus (tag `outer`; `symmetry` on y = 0)", p_float(positive=True),
        ("half_annulus",)),
    Key("mesh.path", "string", REQUIRED,
        "the file, relative to the scene file: a gmsh .geo script, STEP or BREP file (kind geometry; named "
        "physical curves are the boundary tags, without any every boundary curve N is tag `curve N`; a solid: "
        "named physical surfaces, else `surface N`) or a gmsh "
        ".msh mesh (kind file; named physical curves as boundary tags, a Physical Surface for the triangles; 3D: "
        "named physical surfaces as boundary tags, a Physical Volume for the tetrahedra)",
        p_str, ("file", "geometry")),
    Key("mesh.tip_h", "float", 0.0,
        "element size at crack tips inside the part (3D: along the crack fronts); 0: no tip refinement (kind "
        "file: the file's mesh is refined around the tips until its cells are that small; not for 3D files)",
        p_float(0.0)),
    Key("mesh.tip_radius", "float", 0.0,
        "distance over which the size grows from tip_h to h beyond a plateau of 4 tip_h around the tip (3D: "
        "the front); never faster than 0.25 per unit length (a shorter radius is lengthened); 0: that fastest "
        "growth (kind file: up to the file's own element size)",
        p_float(0.0)),
    Key("mesh.crack_h", "float", 0.0,
        "3D: element size over the crack surfaces (within 4 crack_h of them), growing back to h as from the "
        "front; 0: no refinement beyond the front's", p_float(0.0), SOLIDS + ("geometry",)),
    Key("mesh.refine[].point", "[x, y] or [x, y, z]", UNSET, "centre of a local refinement (one of point, "
        "segment)", p_point_any),
    Key("mesh.refine[].segment", "[[x0, y0], [x1, y1]]", UNSET, "a segment refined along its length (a band "
        "along a crack's expected path; one of point, segment; 3D: [[x0, y0, z0], [x1, y1, z1]])", p_segment),
    Key("mesh.refine[].h", "float", REQUIRED, "element size at the point (and within 4 times that size of it)",
        p_float(positive=True)),
    Key("mesh.refine[].radius", "float", 0.0, "distance over which the size grows back to h beyond that "
        "plateau, never faster than 0.25 per unit length; 0: that fastest growth", p_float(0.0)),
    # material
    # units (optional: labels and conversions, the solve needs only consistent units)
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
] + _fatigue_keys() + [
    # cracks
    Key("cracks[].name", "string", "", "label in messages and outputs (default: crack i)", p_str),
    Key("cracks[].points", "[[x, y], ...]", UNSET,
        "2D: polyline; an end inside the part is a tip, an end on or outside the boundary makes an "
        "edge crack", p_polyline),
    Key("cracks[].arc.center", "[x, y]", REQUIRED, "circular-arc crack: centre", p_point),
    Key("cracks[].arc.radius", "float", REQUIRED, "circular-arc crack: radius", p_float(positive=True)),
    Key("cracks[].arc.angles", "[start, end]", REQUIRED,
        "circular-arc crack: polar angles of its ends, degrees (counter-clockwise if end > start)",
        p_angles),
    Key("cracks[].arc.segments", "integer", 24, "circular-arc crack: polyline segments", p_int(1)),
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
    # Dirichlet conditions
    Key("dirichlet[].tag", "string or integer", UNSET,
        "boundary tag the displacement is prescribed on (one of tag, box, point)", p_tag),
    Key("dirichlet[].box", "[x0, y0, x1, y1]", UNSET,
        "every mesh node inside the box, edges included; it may be flat (x0 = x1: the nodes on a "
        "line); standard dofs only, like a point (3D: [x0, y0, z0, x1, y1, z1])", p_region),
    Key("dirichlet[].point", "[x, y] or [x, y, z]", UNSET,
        "the mesh node nearest to the point (within one mean edge length); a generated rectangle, "
        "plate or box has a node at its corners", p_point_any),
    Key("dirichlet[].component", "string", "all", "`x`, `y`, `z` (3D) or `all` (`both` in 2D means all)",
        p_choice("x", "y", "z", "all", "both")),
    Key("dirichlet[].value", "float or [x, y]", 0.0,
        "prescribed displacement ([x, y], 3D [x, y, z], with component = all)", p_value),
    Key("dirichlet[].group", "string", "default", "load group of the prescribed value (see load_path); the "
        "values of conditions of different groups on one node add up", p_group),
] + [Key(f"dirichlet[].williams.{n}", t, d, m + " (displacement prescribed; replaces value)", p)
     for n, t, d, m, p in _WILLIAMS] + [
    # loads
    Key("loads.body_force", "[x, y] or [x, y, z]", [0.0, 0.0], "constant body force, force per unit area "
        "(3D: per unit volume)", p_vector_any),
    Key("loads.body_force_group", "string", "default", "load group of the body force (see load_path)", p_group),
    Key("loads.tractions[].tag", "string or integer", REQUIRED, "boundary tag loaded", p_tag),
    Key("loads.tractions[].group", "string", "default", "load group (see load_path)", p_group),
    Key("loads.tractions[].value", "[x, y] or [x, y, z]", UNSET, "constant traction, force per unit length "
        "(3D: per unit area) (one of value, stress, williams, kirsch)", p_vector_any),
    Key("loads.tractions[].stress", "[sxx, syy, sxy]", UNSET,
        "stress at `origin`: the traction is sigma n on the tag (n the outward facet normal); 3D: a uniform "
        "[sxx, syy, szz, syz, sxz, sxy]", p_stress_any),
    Key("loads.tractions[].stress_gradient", "[[3 numbers], [3 numbers]]", UNSET,
        "with stress: d(sxx, syy, sxy)/dx and d(sxx, syy, sxy)/dy of a linear stress field "
        "sigma(x) = stress + (x - origin) gradient (bending: sxx varying with y)", p_gradient),
    Key("loads.tractions[].origin", "[x, y]", [0.0, 0.0], "with stress_gradient: where sigma = stress",
        p_point),
] + [Key(f"loads.tractions[].williams.{n}", t, d, m + " (traction sigma n)", p) for n, t, d, m, p in _WILLIAMS] + [
    Key("loads.tractions[].kirsch.remote_stress", "float", REQUIRED,
        "Kirsch field of a hole under remote stress along x (< 0: compression); traction sigma n",
        p_float()),
    Key("loads.tractions[].kirsch.hole_radius", "float", REQUIRED, "Kirsch field: hole radius",
        p_float(positive=True)),
    Key("loads.tractions[].kirsch.center", "[x, y]", [0.0, 0.0], "Kirsch field: hole centre", p_point),
    Key("loads.pressures[].tag", "string or integer", REQUIRED, "boundary tag under pressure", p_tag),
    Key("loads.pressures[].group", "string", "default", "load group (see load_path)", p_group),
    Key("loads.pressures[].value", "float", REQUIRED,
        "pressure (> 0 pushes on the part): traction -p n", p_float()),
    Key("loads.point_forces[].point", "[x, y] or [x, y, z]", REQUIRED,
        "a concentrated force at the mesh node nearest to the point (within one element); a generated "
        "rectangle or plate has a node there", p_point_any),
    Key("loads.point_forces[].value", "[x, y] or [x, y, z]", REQUIRED, "the force (per unit thickness in 2D)",
        p_vector_any),
    Key("loads.point_forces[].group", "string", "default", "load group (see load_path)", p_group),
    Key("loads.initial_stress.value", "[sxx, syy, sxy]", REQUIRED,
        "initial (residual) stress sigma_0 at `origin`: the stress is C eps(u) + sigma_0, its "
        "equivalent loads open or close the cracks", p_stress),
    Key("loads.initial_stress.gradient", "[[3 numbers], [3 numbers]]", [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        "d sigma_0 / dx and d sigma_0 / dy of a linear initial stress", p_gradient),
    Key("loads.initial_stress.origin", "[x, y]", [0.0, 0.0], "where sigma_0 = value", p_point),
    Key("loads.initial_stress.group", "string", "default", "load group of the initial stress (see load_path)",
        p_group),
    Key("load_path[].name", "string", "", "label of the step in outputs (default: step k)", p_str),
    Key("load_path[].factors", "table of group = factor", REQUIRED,
        "the factor of each named load group at the end of the step (a group not named keeps its factor "
        "from the step before; all are 0 before the first step); without load_path one step takes every "
        "group to 1", p_factors),
] + _option_keys() + _growth_keys() + _spectrum_keys() + _life_keys() + [
    # outputs
    Key("outputs.vtu", "boolean", True, "write ParaView files solution.vtu and crack_lips.vtu (3D: "
        "solution.vtu, crack_surface.vtu and crack_front.vtu)", p_bool),
    Key("outputs.png", "boolean", True, "write deformed.png, crack_pressure.png and stress.png (3D: "
        "crack_opening.png)", p_bool),
    Key("outputs.magnification", "float", 0.0,
        "displacement scale of deformed.png; 0: largest displacement = 5 % of the part", p_float(0.0)),
    Key("outputs.stress_component", "string", "yy", "stress shown in stress.png: `xx`, `yy`, `xy` "
        "or `von_mises`", p_choice(*STRESS_COMPONENTS)),
    Key("outputs.error_estimate", "boolean", True,
        "estimate the discretisation error of every K with one more solve on a mesh whose element sizes are "
        "halved within two crack lengths of each tip (about 2-4 times the dofs; results.json, sif.csv, a warning "
        "above 1 % of the K scale); options.accuracy makes its own", p_bool),
    Key("outputs.condition_number", "boolean", False,
        "estimate the 1-norm condition number of the stiffness (results.json)", p_bool),
    Key("outputs.crack_points", "integer", 3, "sample points per crack segment in crack.csv (3D: per "
        "direction of each lip facet, for the statistics of results.json)", p_int(1)),
])


KEYS: dict[str, Key] = {k.path: k for k in SCHEMA}


# Demo flags named differently from their Options field (the issues' names).
_FLAGS = {"quadrature_degree": "degree"}


def add_option_arguments(parser, choices: dict[str, tuple[str, ...]] | None = None, **defaults) -> None:
    """Add one command-line flag per given Options field to an argparse
    parser, with the scene file's choices and meaning and the caller's
    default: add_option_arguments(ap, enrichment="vector", radius=0.2).
    choices narrows a field's choices (e.g. contact without `none`).
    quadrature_degree is the flag --degree (args.degree)."""
    for name, default in defaults.items():
        key = KEYS[f"options.{name}"]
        kw: dict[str, typing.Any] = {"default": default,
                                     "help": f"{key.meaning} (default {default})".replace("%", "%%")}
        if name in _OPTION_CHOICES:
            kw["choices"] = (choices or {}).get(name, _OPTION_CHOICES[name])
        else:
            kw["type"] = type(key.default)
        parser.add_argument("--" + _FLAGS.get(name, name).replace("_", "-"), **kw)


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
        if ("point" in r) == ("segment" in r):
            raise InputError(f"mesh.refine[{i}] needs exactly one of point or segment")
    if "units" in doc:
        s["units"] = _section(doc["units"], "units", "units")
    if "material" not in doc:
        raise InputError("the scene has no [material] table: give material.E and material.nu")
    s["material"] = _section(doc["material"], "material", "material")
    if "fatigue" in doc["material"]:
        fd = doc["material"]["fatigue"]
        s["material"]["fatigue"] = _section(fd, "material.fatigue", "material.fatigue")
        if "units" in fd:
            s["material"]["fatigue"]["units"] = _section(fd["units"], "material.fatigue.units", "material.fatigue.units")
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
    if not s["dirichlet"]:
        raise BoundaryConditionError("the scene has no [[dirichlet]] condition: rigid body motion is free; "
                                     "fix at least u_x and u_y somewhere and one more component elsewhere")
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
        s["spectrum"] = _section(doc["spectrum"], "spectrum", "spectrum")
        s["spectrum"]["blocks"] = [_section(b, "spectrum.blocks[]", f"spectrum.blocks[{i}]")
                                   for i, b in enumerate(_items(doc["spectrum"], "blocks"))]
        for i, b in enumerate(s["spectrum"]["blocks"]):
            if ("points" in b) == ("file" in b):
                raise InputError(f"spectrum.blocks[{i}] needs exactly one of points or file")
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


@dataclasses.dataclass
class SceneFile:
    """A scene file read and built.

    Attributes:
        path: the file (None for a document given directly).
        title: the title (or the file's stem).
        settings: every key with its value (parse_settings).
        scene: the cracklip Scene.
        growth: the [growth] settings (cracklip.scene.growth.Growth), or None.
        outputs: the [outputs] settings.
        notes: one line per boundary condition and load, saying what it became.
        timings: seconds spent meshing ("mesh").
    """
    path: pathlib.Path | None
    title: str
    settings: dict
    scene: Scene
    outputs: dict
    notes: list[str]
    timings: dict[str, float]
    growth: typing.Any = None


def load_scene_file(path: str | pathlib.Path, overrides: typing.Sequence[str] = ()) -> SceneFile:
    """Read, validate and build a scene file; overrides are ``KEY=VALUE`` strings."""
    path = pathlib.Path(path)
    doc = read_document(path)
    for o in overrides:
        apply_override(doc, o)
    return build_scene(doc, base_dir=path.parent, path=path)


def build_scene(doc: dict, base_dir: str | pathlib.Path = ".", path: pathlib.Path | None = None) -> SceneFile:
    """Validate a scene document and build its mesh and Scene."""
    s = parse_settings(doc)
    units = None
    if "units" in s:
        u = s["units"]
        units = Units(u.get("length"), u.get("force"), u.get("stress"))
    try:
        material = Material(s["material"]["E"], s["material"]["nu"], s["material"]["plane"])
    except InputError as e:
        raise type(e)(f"material: {e}") from None
    dim, why = scene_dimension(s)
    base_dir = pathlib.Path(base_dir)
    growth = None  # [growth] with the fatigue inputs and their files: checked before meshing
    if "growth" not in s and "life" not in doc and ("spectrum" in s or "fatigue" in s["material"]):
        raise InputError(f"[{'spectrum' if 'spectrum' in s else 'material.fatigue'}] is read by `cracklip grow` (add "
                         "a [growth] table: growth.da, growth.steps) or `cracklip life` (a [life] table)")
    if "growth" in s:
        from ..scene.growth import Growth
        from ..scene.input_files import resolve_rate_table
        fatigue = (_fatigue_material(resolve_rate_table(s["material"]["fatigue"], base_dir))
                   if "fatigue" in s["material"] else None)
        spectrum = _spectrum(s["spectrum"], base_dir) if "spectrum" in s else None
        if fatigue is not None:
            fatigue.converted(units)  # units given without the scene's [units]: an error now, not at the solve
        try:
            growth = Growth(**s["growth"], fatigue_material=fatigue, spectrum=spectrum)
        except InputError as e:
            raise InputError(f"growth: {e}") from None
    if dim == 3:
        from .scene_file_3d import crack_surface
        cracks = [crack_surface(c, i, base_dir) for i, c in enumerate(s["cracks"])]
    else:
        cracks = [_crack(c, i) for i, c in enumerate(s["cracks"])]
    t0 = time.perf_counter()
    points = [bc["point"] for bc in s["dirichlet"] if "point" in bc] + \
        [pf["point"] for pf in s["loads"]["point_forces"]]
    mesh = _mesh(s["mesh"], cracks, base_dir, points, dim)
    t_mesh = time.perf_counter() - t0
    gdim = mesh.gdim
    if dim is None:
        check_dimension(doc, s, gdim, f"mesh.path {s['mesh']['path']!r} holds a {'solid' if gdim == 3 else 'planar part'}")
    elif gdim != dim:
        raise MeshError(f"mesh.path {s['mesh']['path']!r} holds a {gdim}D part ({'tetrahedra' if gdim == 3 else 'triangles'}) "
                        f"but {why}: the scene is {dim}D; give "
                        + ("crack surfaces (ellipse, polygon, surface)" if gdim == 3 else "2D cracks (points, arc)")
                        + " or the matching part")
    notes: list[str] = []
    if gdim == 3:
        from .scene_file_3d import describe_crack
        notes += [f"cracks[{i}] {describe_crack(c)}" for i, c in enumerate(cracks)]
    dirichlet = []
    for i, bc in enumerate(s["dirichlet"]):
        dirichlet += _dirichlet(bc, i, mesh, material, cracks, notes)
    tractions = []
    for i, tr in enumerate(s["loads"]["tractions"]):
        if gdim == 3:
            from .scene_file_3d import traction_3d
            _check_tag(mesh, tr["tag"], f"loads.tractions[{i}]")
            tractions.append(traction_3d(tr, i, mesh, notes))
        else:
            tractions.append(_traction(tr, i, mesh, material, cracks, notes))
    for i, p in enumerate(s["loads"]["pressures"]):
        if gdim == 3:
            from .scene_file_3d import pressure_3d
            _check_tag(mesh, p["tag"], f"loads.pressures[{i}]")
            tractions.append(pressure_3d(p, i, mesh, notes))
        else:
            tractions.append(_pressure(p, i, mesh, notes))
    body_force = s["loads"]["body_force"]
    if any(body_force):
        notes.append(f"loads.body_force: {body_force} per unit {'volume' if gdim == 3 else 'area'}")
    else:
        body_force = None
    point_forces = []
    for i, pf in enumerate(s["loads"]["point_forces"]):
        point_forces.append(_point_force(pf, i, mesh, notes))
    initial_stress = None
    if "initial_stress" in s["loads"]:
        st = s["loads"]["initial_stress"]
        initial_stress = LinearStress(tuple(st["value"]), tuple(map(tuple, st["gradient"])), tuple(st["origin"]))
        notes.append(f"loads.initial_stress: sigma_0 = {st['value']} at {st['origin']}"
                     + (f", gradient {st['gradient']}" if not initial_stress.is_uniform else " (uniform)"))
    for c, cs in zip(cracks, s["cracks"]):
        if cs["pressure"] != 0.0:
            notes.append(f"{c.name}: lip pressure {cs['pressure']:g}")
    try:
        options = Options(**s["options"])
    except InputError as e:
        raise InputError(f"options: {e}") from None
    load_path = None
    if s["load_path"]:
        load_path = [LoadStep(st["factors"], st["name"] or f"step {k + 1}") for k, st in enumerate(s["load_path"])]
        notes.append("load path: " + "; ".join(f"{st.name}: " + ", ".join(f"{g} = {f:g}" for g, f in st.factors.items())
                                               for st in load_path)
                     + f" ({options.load_steps} increment(s) per step)")
    scene = Scene(mesh, material, cracks=cracks, dirichlet=dirichlet, tractions=tractions,
                  options=options, body_force=body_force, point_forces=point_forces,
                  initial_stress=initial_stress, body_force_group=s["loads"]["body_force_group"],
                  initial_stress_group=s["loads"].get("initial_stress", {}).get("group", "default"),
                  load_path=load_path, units=units)
    if load_path is not None:
        from ..scene.load_path import steps
        steps(scene)  # unknown groups are an InputError now, not at the solve
    title = s["title"] or (path.stem if path is not None else "scene")
    if growth is not None:
        if scene.load_path is not None:
            raise InputError("a scene with [growth] solves its loads (or its load cycle) at every step: give "
                             "growth.cycle_max / cycle_min instead of [[load_path]]")
        from ..scene.scene import load_groups
        groups = load_groups(scene) | {"default"}
        for name in ("cycle_max", "cycle_min"):
            unknown = sorted(set(getattr(growth, name) or {}) - groups)
            if unknown:
                raise InputError(f"growth.{name} names load group(s) {unknown} that no load belongs to; the "
                                 f"scene's groups: {sorted(groups)}")
        checks = [("growth.reference_stress", set(growth.reference_stress or {}))]
        if growth.spectrum is not None:
            checks += [("spectrum.groups", set(growth.spectrum.groups)), ("spectrum.steady", set(growth.spectrum.steady))]
        for name, named in checks:
            unknown = sorted(named - groups)
            if unknown:
                raise InputError(f"{name} names load group(s) {unknown} that no load belongs to; the scene's "
                                 f"groups: {sorted(groups)}")
        notes.append("growth: " + describe_growth(growth))
    return SceneFile(path, title, s, scene, s["outputs"], notes, {"mesh": t_mesh}, growth)


def _fatigue_material(f: dict):
    """The FatigueMaterial of the [material.fatigue] settings."""
    from ..scene.fatigue import FatigueMaterial, from_example
    f = dict(f)
    units = f.pop("units", None)
    if units is not None:
        if set(units) != {"length", "stress"}:
            raise InputError("material.fatigue.units needs both length and stress (e.g. length = \"in\", "
                             "stress = \"ksi\")")
        units = (units["length"], units["stress"])
    example = f.pop("example", None)
    fields = {fl.name for fl in dataclasses.fields(FatigueMaterial)}
    top = {k: v for k, v in f.items() if k in fields}
    constants = {k: v for k, v in f.items() if k not in fields}
    if units is not None:
        top["units"] = units
    if example is not None:
        return from_example(example, constants=constants, **top)
    if "law" not in top:
        raise InputError("material.fatigue needs law (paris, walker, forman, nasgro, hartman_schijve, tabular) or "
                         "example (a documented constant set)")
    return FatigueMaterial(constants=constants, **top)


def _spectrum(sp: dict, base_dir: pathlib.Path):
    """The Spectrum of the [spectrum] settings (blocks inline or from CSV files)."""
    from ..scene.spectrum import Spectrum, SpectrumBlock, read_spectrum_csv
    groups = list(sp["groups"])
    blocks = []
    for i, b in enumerate(sp["blocks"]):
        where = f"spectrum.blocks[{i}]"
        if "file" in b:
            f = pathlib.Path(b["file"])
            cols, pts = read_spectrum_csv(f if f.is_absolute() else base_dir / f, f"{where}.file", groups)
            missing = [g for g in groups if g not in cols]
            if missing:
                raise InputError(f"{where}.file {b['file']}: no column for load group(s) {missing} of spectrum.groups "
                                 f"(its columns: {cols})")
            pts = pts[:, [cols.index(g) for g in groups]]
        else:
            pts = b["points"]
        blocks.append(SpectrumBlock(pts, b["repeat"], b["name"]))
    return Spectrum(blocks, tuple(groups), sp["counting"], sp["residue"], dict(sp.get("steady", {})),
                    sp["block_name"], sp["contact_levels"], sp["max_passes"])


def describe_growth(g) -> str:
    """One line of the growth settings (check and the progress)."""
    if g.life:
        sp = g.spectrum
        load = (f"spectrum of {sp.blocks_per_pass} {sp.block_name}(s) per pass, groups {list(sp.groups)}, "
                f"{sp.counting} counting, residue {sp.residue}" if sp is not None else
                f"cycle max {g.cycle_max or 'every group at 1'}, min "
                f"{g.cycle_min if g.cycle_min is not None else f'R = {g.R:g} x max'}")
        how = f"fatigue life: {g.fatigue_material.describe()}; {load}; fastest tip da = " + \
            (f"{g.da:g}" if g.da else "3 tip elements")
    elif g.fatigue:
        cycle = (f"cycle max {g.cycle_max or 'every group at 1'}, min "
                 f"{g.cycle_min if g.cycle_min is not None else f'R = {g.R:g} x max'}")
        how = (f"fatigue: Paris C = {g.paris_C:g}, m = {g.paris_m:g}"
               + (f", Walker gamma = {g.walker_gamma:g}" if g.walker_gamma != 1.0 else "")
               + (f", threshold {g.threshold:g}" if g.threshold else "") + f"; {cycle}; fastest tip da = "
               + (f"{g.da:g}" if g.da else "3 tip elements"))
    else:
        how = "fixed increments da = " + (f"{g.da:g}" if g.da else "3 tip elements") + \
            (f", K_eq threshold {g.threshold:g}" if g.threshold else "")
    stops = [f"{g.steps} steps"] + ([f"K_Ic = {g.K_Ic:g}"] if g.K_Ic is not None else []) + \
        ([f"length {g.max_length:g}"] if g.max_length is not None else []) + [f"kink change > {g.max_kink_change:g} deg"]
    return f"{g.criterion.replace('_', ' ')} criterion, {how}; stops: {', '.join(stops)}"


def _crack(c: dict, i: int) -> Crack:
    name = c["name"] or f"crack {i}"
    if "arc" in c:
        a = c["arc"]
        t0, t1 = np.radians(a["angles"])
        if abs(t1 - t0) < 1e-12:
            raise InputError(f"cracks[{i}].arc.angles: the start and end angles are equal")
        t = np.linspace(t0, t1, a["segments"] + 1)
        pts = np.asarray(a["center"]) + a["radius"] * np.stack([np.cos(t), np.sin(t)], axis=1)
        return Crack(pts, name=name, pressure=c["pressure"], pressure_group=c["pressure_group"])
    return Crack(np.asarray(c["points"], dtype=float), name=name, pressure=c["pressure"],
                 pressure_group=c["pressure_group"])


def _inside(m: dict, p: np.ndarray) -> bool:
    """Whether p lies strictly inside a generated mesh's domain."""
    kind = m["kind"]
    if kind in PLATES:
        x0, y0, x1, y1 = m["domain"]
        inside = x0 < p[0] < x1 and y0 < p[1] < y1
        for cx, cy, r in _holes(m):
            inside = inside and np.hypot(p[0] - cx, p[1] - cy) > r
        return bool(inside)
    r = float(np.hypot(*p))
    return bool(m["hole_radius"] < r < m["outer_radius"] and p[1] > 0.0)


def _holes(m: dict) -> list[tuple[float, float, float]]:
    """The holes (x, y, r) of a generated plate."""
    if m["kind"] == "plate_with_hole":
        return [(m["hole_center"][0], m["hole_center"][1], m["hole_radius"])]
    if m["kind"] == "plate_with_holes":
        return [tuple(h) for h in m["holes"]]
    return []


def _mesh(m: dict, cracks: list, base_dir: pathlib.Path, points=(), dim: int | None = 2) -> MeshData:
    """The mesh of the [mesh] settings; `points` (point supports and forces)
    inside or on a generated rectangle or plate become mesh nodes. dim: the
    scene's dimension if known (3: scene_file_3d.mesh_3d; None: a geometry
    or .msh file without cracks, whose own dimension decides)."""
    kind = m["kind"]
    if dim is None and kind == "file":
        from .scene_file_3d import mesh_file_dimension
        f = pathlib.Path(m["path"])
        dim = mesh_file_dimension(f if f.is_absolute() else base_dir / f)
    if dim == 3:
        from .scene_file_3d import mesh_3d
        return mesh_3d(m, cracks, base_dir)
    refine = [(r["point"][0], r["point"][1], r["h"], r["radius"]) if "point" in r else
              (r["segment"][0][0], r["segment"][0][1], r["h"], r["radius"], r["segment"][1][0], r["segment"][1][1])
              for r in m["refine"]]
    ends = [tuple(float(v) for v in p) for c in cracks for p in c.points[[0, -1]]]
    if kind in ("file", "geometry"):
        f = pathlib.Path(m["path"])
        f = f if f.is_absolute() else base_dir / f
        if kind == "geometry":
            from ..scene.geometry_file import create_from_geometry
            return create_from_geometry(f, m["h"], refine=refine, embed_points=points,
                                        tips=ends if m["tip_h"] > 0.0 else (), tip_h=m["tip_h"],
                                        tip_radius=m["tip_radius"])
        if f.suffix.lower() in (".geo", ".step", ".stp", ".brep", ".brp"):
            raise MeshError(f"mesh.path {m['path']!r} is a geometry, not a mesh: use mesh.kind = \"geometry\" with "
                            "mesh.h (cracklip meshes it, with tip_h and refine)")
        from ..scene.refine import inside_mesh, refine_file_mesh
        md = read_msh(f)
        if m["tip_h"] > 0.0:
            refine += [(p[0], p[1], m["tip_h"], m["tip_radius"]) for p, inside in zip(ends, inside_mesh(md, ends))
                       if inside]
        return refine_file_mesh(md, refine, (), f"mesh file {f}")
    h = m["h"]
    if m["tip_h"] > 0.0:
        radius = m["tip_radius"]
        for c in cracks:
            for p in c.points[[0, -1]]:
                if _inside(m, p):
                    refine.append((float(p[0]), float(p[1]), m["tip_h"], radius))
    if kind in PLATES:
        x0, y0, x1, y1 = m["domain"]
        tol = 1e-12 * max(x1 - x0, y1 - y0)
        embed = [tuple(p) for p in points if x0 - tol <= p[0] <= x1 + tol and y0 - tol <= p[1] <= y1 + tol]
        holes = _holes(m)
        embed = [p for p in embed if all(np.hypot(p[0] - cx, p[1] - cy) > r * (1 + 1e-9) for cx, cy, r in holes)]
        if holes:
            return create_plate_with_holes(*m["domain"], h, holes, refine=refine, embed_points=embed)
        return create_rectangle(*m["domain"], h, refine=refine, embed_points=embed)
    if not m["hole_radius"] < m["outer_radius"]:
        raise MeshError(f"mesh.hole_radius ({m['hole_radius']}) must be smaller than mesh.outer_radius "
                        f"({m['outer_radius']})")
    return create_half_annulus(h, m["hole_radius"], m["outer_radius"], refine=refine)


def _check_tag(mesh: MeshData, tag, where: str) -> None:
    try:
        facets = mesh.facets(tag)
    except MeshError as e:
        raise MeshError(f"{where}: {e}") from None
    if facets.size == 0:
        raise MeshError(f"{where}: boundary tag {tag!r} has no facets")


def _williams(w: dict, material: Material, cracks: list[Crack], where: str):
    from ..exact.williams import WilliamsField
    tip = np.asarray(w["tip"], dtype=float)
    a = math.radians(w["angle"])
    # Orientation: theta -> +pi on the crack's + side (left of the polyline's
    # direction) when the tip is the polyline's last point, else on its - side.
    orientation, best = 1, math.inf
    for c in cracks:
        for end, sign in ((c.points[-1], 1), (c.points[0], -1)):
            d = float(np.linalg.norm(end - tip))
            if d < best:
                best, orientation = d, sign
    scale = max((float(np.ptp(c.points, axis=0).max()) for c in cracks), default=1.0)
    if best > 1e-6 * scale:
        raise InputError(f"{where}.tip {tip.tolist()} is not an end point of any crack")
    return WilliamsField(material, K_I=w["K_I"], K_II=w["K_II"], tip=tuple(tip),
                         e1=(math.cos(a), math.sin(a)), orientation=orientation)


_COMPONENT = {"x": 0, "y": 1, "z": 2, "both": None, "all": None}


def _dirichlet(bc: dict, i: int, mesh: MeshData, material: Material, cracks: list[Crack],
               notes: list[str]) -> list[Dirichlet]:
    where = f"dirichlet[{i}]"
    comp = _COMPONENT[bc["component"]]
    if "williams" in bc:
        field = _williams(bc["williams"], material, cracks, f"{where}.williams")

        def value(p, side):
            u = field.displacement(p, side)
            return u if comp is None else u[:, comp]
        entries = [(comp, value)]
        what = f"Williams field K_I = {field.K_I:g}, K_II = {field.K_II:g}"
    elif isinstance(bc["value"], list):
        entries = list(enumerate(bc["value"]))
        what = f"u = {bc['value']}"
    else:
        entries = [(comp, bc["value"])]
        what = f"u_{bc['component']} = {bc['value']:g}" if comp is not None else f"u = {bc['value']:g}"
    gdim = mesh.gdim
    x = mesh.mesh.geometry.x[:, :gdim]
    out: list[Dirichlet] = []
    if "tag" in bc:
        _check_tag(mesh, bc["tag"], where)
        targets = [bc["tag"]]
        notes.append(f"{where}: tag {bc['tag']!r} ({mesh.facets(bc['tag']).size} facets), {what}")
    elif "point" in bc:
        node = _nearest_node(mesh, bc["point"], f"{where}.point")
        targets = [node]
        notes.append(f"{where}: point {bc['point']} -> node ({', '.join(f'{v:.6g}' for v in node)}), {what}")
    else:
        lo, hi = np.asarray(bc["box"][:gdim]), np.asarray(bc["box"][gdim:])
        tol = 1e-9 * float(np.ptp(x, axis=0).max())
        inside = np.flatnonzero(np.all((x >= lo - tol) & (x <= hi + tol), axis=1))
        if inside.size == 0:
            raise BoundaryConditionError(f"{where}.box {bc['box']} holds no mesh node")
        targets = [tuple(float(v) for v in x[n]) for n in inside]
        notes.append(f"{where}: box {bc['box']} ({inside.size} nodes), {what}")
    label = f"{where}: " + (f"tag {bc['tag']!r}" if "tag" in bc else f"point {bc['point']}" if "point" in bc
                            else f"box {bc['box']}")
    for target in targets:
        out += [Dirichlet(target, c, v, group=bc["group"], label=label) for c, v in entries]
    return out


def _mean_edge(mesh: MeshData) -> float:
    msh = mesh.mesh
    if mesh.gdim == 3:  # the six edges of every tetrahedron, a chunk of cells at a time
        x = msh.geometry.x
        cells = msh.geometry.dofmap.array.reshape(-1, 4)
        a, b = [0, 0, 0, 1, 1, 2], [1, 2, 3, 2, 3, 3]
        total = sum(float(np.linalg.norm(x[c[:, b]] - x[c[:, a]], axis=2).sum())
                    for c in np.array_split(cells, max(1, len(cells) // 200_000)))
        return total / (6 * len(cells))
    x = msh.geometry.x[:, :2]
    cells = msh.geometry.dofmap.array.reshape(-1, 3)
    e = x[cells[:, [1, 2, 0]]] - x[cells]
    return float(np.linalg.norm(e, axis=2).mean())


def _traction(tr: dict, i: int, mesh: MeshData, material: Material, cracks: list[Crack],
              notes: list[str]) -> Traction:
    from ..model.boundary import boundary_normals
    where = f"loads.tractions[{i}]"
    _check_tag(mesh, tr["tag"], where)
    tag = tr["tag"]
    nf = mesh.facets(tag).size
    if "value" in tr:
        notes.append(f"{where}: tag {tag!r} ({nf} facets), traction {tr['value']}")
        return Traction(tag, tuple(tr["value"]), group=tr["group"])
    if "stress" in tr:
        field = LinearStress(tuple(tr["stress"]), tuple(map(tuple, tr.get("stress_gradient", [[0.0] * 3] * 2))),
                             tuple(tr["origin"]))
        what = (f"sigma = {tr['stress']}" if field.is_uniform else
                f"linear sigma = {tr['stress']} at {tr['origin']}, gradient {tr['stress_gradient']}")
        notes.append(f"{where}: tag {tag!r} ({nf} facets), traction sigma n, {what}")
        return Traction(tag, stress=field, group=tr["group"])
    normals = boundary_normals(mesh, tag)
    if "williams" in tr:
        field = _williams(tr["williams"], material, cracks, f"{where}.williams")
        notes.append(f"{where}: tag {tag!r} ({nf} facets), traction of the Williams field "
                     f"K_I = {field.K_I:g}, K_II = {field.K_II:g}")
        return Traction(tag, lambda p: np.einsum("nij,nj->ni", field.stress(p), normals(p)), group=tr["group"])
    from ..exact.kirsch import kirsch_stress
    k = tr["kirsch"]
    center = np.asarray(k["center"], dtype=float)
    notes.append(f"{where}: tag {tag!r} ({nf} facets), traction of the Kirsch field, remote stress "
                 f"{k['remote_stress']:g}, hole radius {k['hole_radius']:g}")
    def kirsch_traction(p):
        return np.einsum("nij,nj->ni", kirsch_stress(p - center, k["remote_stress"], k["hole_radius"]), normals(p))
    return Traction(tag, kirsch_traction, group=tr["group"])


def _nearest_node(mesh: MeshData, point, where: str) -> tuple[float, ...]:
    """The mesh node nearest to a point given in a scene file; an error
    naming the key if it is more than a mean edge length away."""
    x = mesh.mesh.geometry.x[:, :mesh.gdim]
    p = np.asarray(point)
    d = np.linalg.norm(x - p, axis=1)
    node = int(np.argmin(d))
    edge = _mean_edge(mesh)
    if d[node] > edge:
        raise BoundaryConditionError(
            f"{where} {p.tolist()}: the nearest mesh node {x[node].tolist()} is {d[node]:.3g} away, more than "
            f"the mean edge length {edge:.3g}; put the point on the part")
    return tuple(float(v) for v in x[node])


def _point_force(pf: dict, i: int, mesh: MeshData, notes: list[str]) -> PointForce:
    where = f"loads.point_forces[{i}]"
    node = _nearest_node(mesh, pf["point"], f"{where}.point")
    notes.append(f"{where}: force {pf['value']} at node ({', '.join(f'{v:.6g}' for v in node)})")
    return PointForce(node, tuple(pf["value"]), group=pf["group"])


def _pressure(pr: dict, i: int, mesh: MeshData, notes: list[str]) -> Traction:
    from ..model.boundary import boundary_normals
    where = f"loads.pressures[{i}]"
    _check_tag(mesh, pr["tag"], where)
    normals = boundary_normals(mesh, pr["tag"])
    p = pr["value"]
    notes.append(f"{where}: tag {pr['tag']!r} ({mesh.facets(pr['tag']).size} facets), pressure {p:g}")
    return Traction(pr["tag"], lambda x: -p * normals(x), group=pr["group"])


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
