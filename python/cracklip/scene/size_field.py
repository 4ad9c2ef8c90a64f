"""Element-size fields: what size a mesh should have where.

One description serves every way cracklip makes or refines a mesh: gmsh
meshes of the built-in shapes and of a user's geometry (.geo, STEP, BREP)
get it as a background field (``size_expression``), and a user's .msh is
refined by DOLFINx until its cells meet it (``cracklip.scene.refine``,
which evaluates ``size_at``).

- ``refine`` items, (x, y, h_near, radius) or (x, y, h_near, radius, x1,
  y1): the size is h_near within PLATEAU h_near of the point (or of the
  segment (x, y)-(x1, y1): a band along a crack's expected path) and grows
  linearly back to h beyond it, by (h - h_near) / radius per unit length
  but never faster than MAX_GROWTH (refinement_size).
- ``levels`` items, (x, y, x1, y1, D, L): the size the field has without
  them is divided by 2^L within distance D of the point (x1, y1 = x, y) or
  of the segment, and grows back to it by MAX_GROWTH per unit length beyond
  D. One level halves every element size there: the meshes of an error
  estimate and of an accuracy target (cracklip.analysis.accuracy).

The size at x is the smallest that any item asks for, never above h.
"""
from __future__ import annotations

import math
import typing

import numpy as np

from ..errors import MeshError


#: Largest growth rate of the element size away from a refinement point
#: (size increase per unit distance). A steeper size field cannot be
#: realised by the mesher: with the size growing from 0.005 to 0.2 over 0.1
#: gmsh left a 0.11 element at the point. At 0.25 the size at the point is
#: reached to a few per cent (measured over 20 random points and 5 size
#: ratios up to 200).
MAX_GROWTH = 0.25


#: The size is h_near within PLATEAU * h_near of a refinement point, so that
#: the cells around it (a crack tip's cell and its neighbours) all have it.
PLATEAU = 4.0


Refinement = typing.Sequence[float]   # (x, y, h_near, radius[, x1, y1])
Level = typing.Sequence[float]        # (x, y, x1, y1, D, L)


def refinement_size(h: float, h_near: float, radius: float) -> tuple[float, float]:
    """The (plateau, growth) of a refinement's size field: the size is
    h_near up to `plateau` from the point and then grows linearly by
    `growth` per unit distance until it reaches h. The growth is
    (h - h_near) / radius, at most MAX_GROWTH: a radius too short for the
    mesher to honour is lengthened (to (h - h_near) / MAX_GROWTH)."""
    plateau = PLATEAU * h_near
    growth = (h - h_near) / radius if radius > 0.0 else MAX_GROWTH
    return plateau, min(growth, MAX_GROWTH)


def check_refinement(item: Refinement) -> tuple[float, float, float, float, float, float]:
    """(x, y, h_near, radius, x1, y1) of a refine item, checked."""
    x, y, h_near, radius = (float(v) for v in item[:4])
    x1, y1 = (float(item[4]), float(item[5])) if len(item) >= 6 else (x, y)
    if not (h_near > 0.0 and radius >= 0.0 and all(map(math.isfinite, (x, y, x1, y1, h_near, radius)))):
        raise MeshError(f"refinement at ({x:g}, {y:g}): need a size > 0 and a radius >= 0, got "
                        f"size {h_near!r}, radius {radius!r}")
    return x, y, h_near, radius, x1, y1


def check_level(item: Level) -> tuple[float, float, float, float, float, int]:
    """(x, y, x1, y1, D, L) of a level item, checked."""
    x, y, x1, y1, D = (float(v) for v in item[:5])
    L = int(item[5])
    if not (D >= 0.0 and L >= 0 and all(map(math.isfinite, (x, y, x1, y1, D)))):
        raise MeshError(f"refinement level around ({x:g}, {y:g}): need a radius >= 0 and a level >= 0, got "
                        f"{D!r}, {item[5]!r}")
    return x, y, x1, y1, D, L


def _num(v: float) -> str:
    # Every number in parentheses: "x--0.5" (a negative centre) makes gmsh's
    # expression parser abort the process.
    return f"({float(v)!r})"


def distance_expression(x: float, y: float, x1: float, y1: float) -> str:
    """gmsh MathEval expression of the distance to the point (x, y), or to
    the segment (x, y)-(x1, y1)."""
    dx, dy = float(x1) - float(x), float(y1) - float(y)
    if dx == 0.0 and dy == 0.0:
        return f"Sqrt((x - {_num(x)})^2 + (y - {_num(y)})^2)"
    t = (f"Max(0, Min(1, ((x - {_num(x)}) * {_num(dx)} + (y - {_num(y)}) * {_num(dy)}) / "
         f"{_num(dx * dx + dy * dy)}))")
    return f"Sqrt((x - {_num(x)} - {t} * {_num(dx)})^2 + (y - {_num(y)} - {t} * {_num(dy)})^2)"


def refinement_expression(h: float, item: Refinement) -> str:
    """The size of one refine item as a gmsh MathEval expression."""
    x, y, h_near, radius, x1, y1 = check_refinement(item)
    plateau, growth = refinement_size(h, h_near, radius)
    return (f"Min({_num(h)}, {_num(h_near)} + {_num(growth)} * Max(0, {distance_expression(x, y, x1, y1)} - "
            f"{_num(plateau)}))")


def size_expression(h: float, refine: typing.Sequence[Refinement] = (),
                    levels: typing.Sequence[Level] = ()) -> str:
    """The whole size field as one gmsh MathEval expression (gmsh hangs when
    a MathEval field refers to another field, so the base field is written
    out inside every level term)."""
    base = _nested_min([_num(h)] + [refinement_expression(h, r) for r in refine])
    terms = [base]
    for item in levels:
        x, y, x1, y1, D, L = check_level(item)
        if L == 0:
            continue
        terms.append(f"{_num(2.0 ** -L)} * {base} + {_num(MAX_GROWTH)} * Max(0, "
                     f"{distance_expression(x, y, x1, y1)} - {_num(D)})")
    return _nested_min(terms)


def _nested_min(terms: list[str]) -> str:
    out = terms[0]
    for t in terms[1:]:
        out = f"Min({out}, {t})"
    return out


def segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance of points p (n, 2) to the segment a-b (2,), (2,)."""
    d = b - a
    dd = float(d @ d)
    if dd == 0.0:
        return np.linalg.norm(p - a, axis=1)
    t = np.clip((p - a) @ d / dd, 0.0, 1.0)
    return np.linalg.norm(a + t[:, None] * d - p, axis=1)


def size_at(points: np.ndarray, h: float | np.ndarray, refine: typing.Sequence[Refinement] = (),
            levels: typing.Sequence[Level] = ()) -> np.ndarray:
    """The size field at points (n, 2), as size_expression writes it for
    gmsh. h: the size without refinement, a number or one value per point
    (the cells' own sizes when a given mesh is refined)."""
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    hh = np.broadcast_to(np.asarray(h, dtype=float), (len(p),))
    base = hh.copy()
    for item in refine:
        x, y, h_near, radius, x1, y1 = check_refinement(item)
        d = segment_distance(p, np.array([x, y]), np.array([x1, y1]))
        plateau = PLATEAU * h_near
        growth = np.minimum(np.where(radius > 0.0, (hh - h_near) / max(radius, 1e-300), MAX_GROWTH), MAX_GROWTH)
        base = np.minimum(base, h_near + growth * np.maximum(0.0, d - plateau))
    out = base.copy()
    for item in levels:
        x, y, x1, y1, D, L = check_level(item)
        if L == 0:
            continue
        d = segment_distance(p, np.array([x, y]), np.array([x1, y1]))
        out = np.minimum(out, 2.0 ** -L * base + MAX_GROWTH * np.maximum(0.0, d - D))
    return out


def smallest_size(h: float, refine: typing.Sequence[Refinement] = (), levels: typing.Sequence[Level] = ()) -> float:
    """A lower bound of the size field (gmsh's Mesh.MeshSizeMin)."""
    smallest = min([float(h)] + [check_refinement(r)[2] for r in refine])
    top = max([0] + [check_level(v)[5] for v in levels])
    return smallest * 2.0 ** -top
