"""Output files: ParaView VTU on the sub-cell mesh (crack opening visible)."""
from __future__ import annotations

import pathlib

import meshio
import numpy as np

from .post import Solution


def write_vtu(solution: Solution, path: str | pathlib.Path) -> pathlib.Path:
    """Write displacement (point data, 3 components for ParaView's Warp By
    Vector) and stress, side, parent cell (cell data) on the sub-cell mesh,
    whose vertices are not shared across the crack."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    f = solution.subcell_fields()
    npts = f["points"].shape[0]
    points = np.zeros((npts, 3))
    points[:, :2] = f["points"]
    disp = np.zeros((npts, 3))
    disp[:, :2] = f["displacement"]
    conn = np.arange(npts, dtype=np.int64).reshape(-1, 3)
    s = f["stress"]
    mesh = meshio.Mesh(
        points, [("triangle", conn)],
        point_data={"displacement": disp},
        cell_data={"stress_xx": [s[:, 0]], "stress_yy": [s[:, 1]], "stress_xy": [s[:, 2]],
                   "side": [f["side"].astype(np.int32)], "parent_cell": [f["parent"]]})
    mesh.write(path)
    return path
