"""ParaView files of a solution: the sub-cell mesh (crack opening visible) and the
crack lips as a line mesh."""
from __future__ import annotations

import pathlib
import typing

import numpy as np

from ..post.solution import Solution
from .files import atomic_path
from .vtu import VtuMesh, write_vtu as _write_vtu_file


def von_mises(stress: np.ndarray, zz_ratio: float) -> np.ndarray:
    """von Mises stress of (n, 3) xx, yy, xy stresses with sigma_zz = zz_ratio
    (xx + yy) (Material.sigma_zz_ratio: nu in plane strain, 0 in plane stress)."""
    sxx, syy, sxy = stress[:, 0], stress[:, 1], stress[:, 2]
    szz = zz_ratio * (sxx + syy)
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxy ** 2)


def subcell_mesh(solution: Solution, fields: dict | None = None) -> VtuMesh:
    """The solution on the sub-cell mesh (vertices not shared across a crack):
    displacement (point data, 3 components for ParaView's Warp By Vector),
    stress components, von Mises stress, crack side and parent cell (cell data).
    fields: solution.subcell_fields() if the caller has it already."""
    f = solution.subcell_fields() if fields is None else fields
    npts = f["points"].shape[0]
    points = np.zeros((npts, 3))
    points[:, :2] = f["points"]
    disp = np.zeros((npts, 3))
    disp[:, :2] = f["displacement"]
    conn = np.arange(npts, dtype=np.int64).reshape(-1, 3)
    s = f["stress"]
    return VtuMesh(
        points, "triangle", conn,
        point_data={"displacement": disp},
        cell_data={"stress_xx": s[:, 0], "stress_yy": s[:, 1], "stress_xy": s[:, 2],
                   "stress_von_mises": von_mises(s, solution.model.scene.material.sigma_zz_ratio),
                   "side": f["side"].astype(np.int32), "parent_cell": f["parent"]})


def crack_lips_mesh(samples: typing.Sequence[dict]) -> VtuMesh:
    """The lips of every crack as two polylines (+ and - lip) through the
    crack sample points (see outputs.crack_samples), each point carrying
    the displacement of its lip, pressure, shear (friction), normal gap,
    tangential slip, state (0 open, 1 stick, 2 slip); cell data: crack index
    and lip (+1 / -1)."""
    pts, disp, conn, crack_id, lip = [], [], [], [], []
    data = {"pressure": [], "shear": [], "gap": [], "slip": [], "s": [], "state": []}
    offset = 0
    for c, smp in enumerate(samples):
        n = len(smp["s"])
        if n < 2:
            continue
        for sign, key in ((1, "u_plus"), (-1, "u_minus")):
            pts.append(smp["x"])
            disp.append(smp[key])
            for name in data:
                v = smp[name]
                if name == "state":  # 0 open, 1 stick, 2 slip
                    v = np.select([v == "stick", v == "slip"], [1, 2], 0).astype(np.int32)
                data[name].append(v)
            idx = offset + np.arange(n)
            conn.append(np.stack([idx[:-1], idx[1:]], axis=1))
            crack_id.append(np.full(n - 1, c, dtype=np.int32))
            lip.append(np.full(n - 1, sign, dtype=np.int32))
            offset += n
    if not pts:
        return VtuMesh(np.zeros((0, 3)), "line", np.zeros((0, 2), dtype=np.int64))
    x = np.concatenate(pts)
    points = np.zeros((len(x), 3))
    points[:, :2] = x
    u = np.zeros((len(x), 3))
    u[:, :2] = np.concatenate(disp)
    point_data = {"displacement": u, **{k: np.concatenate(v) for k, v in data.items()}}
    return VtuMesh(points, "line", np.concatenate(conn).astype(np.int64), point_data=point_data,
                   cell_data={"crack": np.concatenate(crack_id), "lip": np.concatenate(lip)})


def write_mesh(mesh: VtuMesh, path: str | pathlib.Path) -> pathlib.Path:
    """Write a mesh as VTU (cracklip.io.vtu: raw appended binary) through a
    temporary file."""
    path = pathlib.Path(path)
    with atomic_path(path) as tmp:
        _write_vtu_file(tmp, mesh)
    return path


def write_vtu(solution: Solution, path: str | pathlib.Path) -> pathlib.Path:
    """Write the sub-cell mesh with displacement and stress (see subcell_mesh)."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return write_mesh(subcell_mesh(solution), path)
