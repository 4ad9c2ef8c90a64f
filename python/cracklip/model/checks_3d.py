"""Model checks of a tetrahedral part (the 3D counterpart of checks.py),
shared by ``cracklip check`` and ``run``, before solving.

Errors (the model cannot be right):
- ``check_front_ends``: a front piece that is neither closed (an embedded
  crack) nor ends on the part's boundary (a surface or corner crack): the
  front leaves the part without crossing its boundary, which happens where
  the P1 front touches itself (branch points) or breaks in degenerate
  cells;
- ``check_enrichment_radius``: options.radius > 0 that reaches no node of
  a front (a radius in the wrong units or far below the element size).

Warnings (ModelWarning, as in 2D): a front whose elements are coarse for
the crack's size (front_resolution), a radius below the element size at
the front (enrichment_radius), front cells where the P1 front is not a
line (degenerate_front), no front enrichment (front_enrichment).

``front_element_sizes`` is the element size reached along a front (what
``check`` reports): the mean edge length of each front cell.
"""
from __future__ import annotations

import numpy as np

from .. import _cracklip
from ..errors import CrackGeometryError, InputError
from .checks import ModelWarning


#: Cell class of the cells holding the front (CellClass3D::front).
FRONT_CLASS = 3


#: A front whose elements exceed this fraction of the crack's size is warned
#: about (the penny crack at a / h = 8 opens 2.3 % off Sneddon's; at a / h =
#: 4 the front cells span a quarter of the radius).
FRONT_RESOLUTION = 0.2


_EDGES = ([0, 0, 0, 1, 1, 2], [1, 2, 3, 2, 3, 3])


def cell_sizes(x: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Mean edge length of each tetrahedron (cells (m, 4))."""
    a, b = _EDGES
    return np.linalg.norm(x[cells[:, b]] - x[cells[:, a]], axis=2).mean(axis=1)


def front_cells(geometry) -> np.ndarray:
    """The cells holding a crack's front."""
    return np.flatnonzero(np.asarray(geometry.cell_class) == FRONT_CLASS).astype(np.int32)


def front_element_sizes(model, crack: int) -> np.ndarray:
    """The element size (mean edge length) of every cell holding a crack's front (empty without a front)."""
    fc = front_cells(model.geometries[crack])
    return cell_sizes(model.x, model.cells[fc])


def crack_size(crack) -> float:
    """A crack's size: its smaller semi-axis for an ellipse, else twice its
    area over the length of its whole boundary (the radius of a circle)."""
    if hasattr(crack, "b") and hasattr(crack, "a"):
        return float(min(crack.a, crack.b))
    if hasattr(crack, "boundary_edges"):
        e = crack.boundary_edges()
        length = float(np.linalg.norm(crack.vertices[e[:, 1]] - crack.vertices[e[:, 0]], axis=1).sum())
    else:
        p = crack.points
        length = float(np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1).sum())
    return 2.0 * crack.area / length if length > 0 else 0.0


def check_front_ends(name: str, front: dict) -> None:
    """Raise CrackGeometryError if an open piece of the front (dict of
    CrackGeometry3D.front) has an end that is not on the part's boundary."""
    offsets = np.asarray(front["piece_offsets"])
    on = np.asarray(front["on_boundary"])
    x = np.asarray(front["x"]).reshape(-1, 3)
    for k, closed in enumerate(np.asarray(front["closed"])):
        if closed:
            continue
        for end in (int(offsets[k]), int(offsets[k + 1]) - 1):
            if not on[end]:
                branch = int(front["num_branch_points"])
                why = (f" (the P1 front meets itself at {branch} point(s) there: the crack surface touches itself "
                       "or runs along mesh faces)" if branch else "")
                raise CrackGeometryError(
                    f"{name}: the front (piece {k} of {len(offsets) - 1}) ends at "
                    f"({', '.join(f'{v:.6g}' for v in x[end])}) inside the part, off its boundary{why}: a front must "
                    "be closed (an embedded crack) or end on the part's boundary (a surface or corner crack). Check "
                    "that the crack does not fold onto itself, move it off the mesh nodes by a fraction of the "
                    "element size, or refine the mesh along its front (mesh.tip_h)")


def check_enrichment_radius(model) -> None:
    """Raise InputError when options.radius > 0 reaches no node of a crack's front."""
    opts = model.scene.options
    if opts.radius <= 0.0 or opts.enrichment == "none":
        return
    r = opts.radius
    for cm in model.cracks:
        g = cm.geometry
        if not len(g.front["x"]):
            continue
        phi, psi = np.asarray(g.phi), np.asarray(g.psi)
        cand = np.flatnonzero((np.abs(phi) <= r) & (np.abs(psi) <= r))
        if cand.size:
            d = _cracklip.compute_front_projection_3d(g, np.ascontiguousarray(model.x[cand]))["distance"]
            if np.any(d <= r):
                continue
        nodes = np.unique(model.cells[front_cells(g)])
        nearest = float(_cracklip.compute_front_projection_3d(g, np.ascontiguousarray(model.x[nodes]))["distance"].min())
        h = float(front_element_sizes(model, model.cracks.index(cm)).mean())
        raise InputError(
            f"{cm.crack.name}: the enrichment radius options.radius = {r:.3g} reaches no node (the nearest node is "
            f"{nearest:.3g} from the front, where the elements are {h:.3g}): only the front cells' own nodes would "
            f"get front functions; give a radius of 2 to 3 elements there (e.g. {2.5 * h:.3g}), or 0 for the front "
            "cells' nodes only")


def check_model_3d(model) -> list[ModelWarning]:
    """Raise on a broken front or a radius that reaches no node; return the
    warnings (module doc)."""
    out: list[ModelWarning] = []
    opts = model.scene.options
    for ci, cm in enumerate(model.cracks):
        g = cm.geometry
        front = g.front
        name = cm.crack.name
        check_front_ends(name, front)
        if not len(front["x"]):
            continue
        h = front_element_sizes(model, ci)
        size = crack_size(cm.crack)
        hm = float(h.mean())
        if size > 0.0 and hm > FRONT_RESOLUTION * size:
            out.append(ModelWarning(
                "front_resolution", f"crack {name!r}: the elements along its front ({hm:.3g} on average) are coarser "
                f"than {FRONT_RESOLUTION:g} times the crack's size ({size:.3g}): the opening near the front is not "
                f"resolved; refine along the front (mesh.tip_h <= {0.1 * size:.3g})", ci))
        if opts.enrichment == "none":
            out.append(ModelWarning(
                "front_enrichment", f"crack {name!r}: without front enrichment (options.enrichment = 'none') the "
                "crack ends at the faces of the front cells and the sqrt(r) field is not represented", ci))
        elif 0.0 < opts.radius < hm:
            out.append(ModelWarning(
                "enrichment_radius", f"crack {name!r}: the enrichment radius {opts.radius:.3g} is smaller than the "
                f"elements along the front ({hm:.3g}): few nodes beyond the front cells' get front functions; use a "
                "radius of 2 to 3 elements", ci))
        if g.num_degenerate_front_cells:
            out.append(ModelWarning(
                "degenerate_front", f"crack {name!r}: {g.num_degenerate_front_cells} front cell(s) where the P1 front "
                "is not a line (a corner of the crack on a mesh node, or its edge along mesh edges); move the crack "
                "off the nodes by a fraction of the element size", ci))
    check_enrichment_radius(model)
    return out


__all__ = ["check_model_3d", "check_front_ends", "check_enrichment_radius", "front_element_sizes", "cell_sizes",
           "crack_size", "front_cells"]
