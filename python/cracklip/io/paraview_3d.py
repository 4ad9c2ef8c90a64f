"""ParaView files of a solved tetrahedral part (the 3D counterpart of
paraview.py), each a VTU (cracklip.io.vtu):

- ``solution_mesh``: the sub-tetrahedral mesh (post.subcells_3d): the cells
  the crack touches split into sub-tetrahedra whose vertices carry their own
  side's displacement (Warp By Vector with ``displacement`` opens the
  crack), whole cells elsewhere; point data displacement; cell data stress
  (``stress_xx`` ... ``stress_xy``, ``stress_von_mises``), side (+1 / -1 on
  the sub-tetrahedra, 0 on whole cells), parent cell, crack (-1 on whole
  cells).
- ``crack_surface_mesh``: both lips of every crack as triangles (each lip
  facet twice, once per lip), point data the lip's displacement, the
  opening [[u]] (``jump``), its normal part ``gap`` (> 0 open) and the size
  of its tangential part ``slip``; cell data crack, lip (+1 / -1), normal.
- ``front_mesh``: every crack's front as polylines (its pieces), point
  data the arc length ``s`` from the start of the piece, the local frame
  ``e1`` (propagation), ``e2`` (normal), ``e3`` (tangent), ``on_boundary``
  (1 at the ends of a piece that leaves the part), crack, piece.
"""
from __future__ import annotations

import typing

import numpy as np

from ..post.subcells_3d import VOIGT
from .vtu import VtuMesh


def solution_mesh(fields: dict[str, typing.Any]) -> VtuMesh:
    """The sub-tetrahedral mesh of post.subcells_3d.subcell_fields_3d."""
    s = fields["stress"]
    cell_data = {f"stress_{c}": s[:, k] for k, c in enumerate(VOIGT)}
    cell_data.update({"stress_von_mises": fields["von_mises"], "side": fields["side"].astype(np.int32),
                      "parent_cell": fields["parent"], "crack": fields["crack"]})
    return VtuMesh(fields["points"], "tetra", fields["cells"], point_data={"displacement": fields["displacement"]},
                   cell_data=cell_data)


def crack_surface_mesh(facets: typing.Sequence[dict]) -> VtuMesh:
    """Both lips of every crack (post.subcells_3d.lip_facets_3d per crack)."""
    pts, disp, jump, gap, slip, crack, lip, normal = [], [], [], [], [], [], [], []
    for c, f in enumerate(facets):
        nf = len(f["cell"])
        if nf == 0:
            continue
        for sign, key in ((1, "u_plus"), (-1, "u_minus")):
            pts.append(f["x"].reshape(-1, 3))
            disp.append(f[key].reshape(-1, 3))
            jump.append(f["jump"].reshape(-1, 3))
            gap.append(f["gap"].reshape(-1))
            slip.append(f["slip"].reshape(-1))
            crack.append(np.full(nf, c, dtype=np.int32))
            lip.append(np.full(nf, sign, dtype=np.int32))
            normal.append(f["normal"])
    if not pts:
        return VtuMesh(np.zeros((0, 3)), "triangle", np.zeros((0, 3), dtype=np.int64))
    x = np.concatenate(pts)
    return VtuMesh(x, "triangle", np.arange(len(x), dtype=np.int64).reshape(-1, 3),
                   point_data={"displacement": np.concatenate(disp), "jump": np.concatenate(jump),
                               "gap": np.concatenate(gap), "slip": np.concatenate(slip)},
                   cell_data={"crack": np.concatenate(crack), "lip": np.concatenate(lip),
                              "normal": np.concatenate(normal)})


def front_mesh(fronts: typing.Sequence[dict]) -> VtuMesh:
    """The fronts (CrackGeometry3D.front of each crack) as polylines."""
    pts, conn, data = [], [], {"s": [], "e1": [], "e2": [], "e3": [], "on_boundary": [], "crack": [], "piece": []}
    offset = 0
    for c, fr in enumerate(fronts):
        x = np.asarray(fr["x"]).reshape(-1, 3)
        if not len(x):
            continue
        frame = np.asarray(fr["frame"]).reshape(-1, 3, 3)
        offsets = np.asarray(fr["piece_offsets"])
        pts.append(x)
        conn.append(offset + np.asarray(fr["segments"], dtype=np.int64).reshape(-1, 2))
        data["s"].append(np.asarray(fr["s"]))
        for k in range(3):
            data[f"e{k + 1}"].append(frame[:, k])
        data["on_boundary"].append(np.asarray(fr["on_boundary"], dtype=np.int32))
        data["crack"].append(np.full(len(x), c, dtype=np.int32))
        data["piece"].append(np.repeat(np.arange(len(offsets) - 1, dtype=np.int32), np.diff(offsets)))
        offset += len(x)
    if not pts:
        return VtuMesh(np.zeros((0, 3)), "line", np.zeros((0, 2), dtype=np.int64))
    return VtuMesh(np.concatenate(pts), "line", np.concatenate(conn),
                   point_data={k: np.concatenate(v) for k, v in data.items()})


__all__ = ["solution_mesh", "crack_surface_mesh", "front_mesh"]
