"""ParaView files of a solution (VTU: cracklip.io.vtu), planar or solid.

- ``subcell_mesh``: the sub-cell mesh (Solution.subcell_fields): the cells
  a crack splits cut into sub-triangles or sub-tetrahedra whose vertices
  carry their own side's displacement (Warp By Vector with
  ``displacement`` opens the crack), whole cells elsewhere; point data
  displacement (3 components); cell data the stress components
  (``stress_xx`` ...), ``stress_von_mises``, side (+1 / -1 on the
  sub-cells, 0 on whole cells), parent cell, and in 3D the crack splitting
  each sub-cell (-1 on whole cells).
- the crack: ``crack_lips_mesh`` (2D): both lips of every crack as
  polylines through the crack samples, with the lip's displacement, contact
  pressure, shear, gap, slip and state; ``crack_surface_mesh`` (3D): both
  lips of every crack as triangles (each lip facet twice), with the lip's
  displacement, the opening [[u]] (``jump``), its normal part ``gap``, its
  tangential part ``slip`` (a vector), and with contact the ``pressure``,
  the friction ``shear`` on the + lip (a vector) and the ``state`` (0
  open, 1 stick, 2 slip).
- the fronts (3D): ``front_mesh``, every crack's front as polylines with
  the arc length ``s``, the frame ``e1``, ``e2``, ``e3`` and ``on_boundary``;
  ``front_sif_mesh``, the SIF points along them carrying K.
"""
from __future__ import annotations

import math
import pathlib
import typing

import numpy as np

from ..errors import InputError, checked_keywords
from ..post.solution import Solution
from .files import atomic_path
from .vtu import VtuMesh, write_vtu as _write_vtu_file

#: The VTK cell of a sub-cell mesh of each dimension.
CELL_TYPES = {2: "triangle", 3: "tetra"}


def _in_3d(a: np.ndarray) -> np.ndarray:
    """Points or vectors (n, d) as (n, 3) (ParaView's vectors have 3 components)."""
    a = np.asarray(a, dtype=float)
    if a.shape[1] == 3:
        return a
    out = np.zeros((len(a), 3))
    out[:, :a.shape[1]] = a
    return out


def subcell_mesh(solution: Solution, fields: dict | None = None) -> VtuMesh:
    """The solution on the sub-cell mesh (module doc). fields:
    solution.subcell_fields() if the caller has it already."""
    f = solution.subcell_fields() if fields is None else fields
    s = f["stress"]
    cell_data = {f"stress_{c}": s[:, k] for k, c in enumerate(solution.model.crack_type.VOIGT)}
    cell_data.update({"stress_von_mises": f["von_mises"], "side": f["side"].astype(np.int32),
                      "parent_cell": f["parent"]})
    if "crack" in f:
        cell_data["crack"] = f["crack"]
    return VtuMesh(_in_3d(f["points"]), CELL_TYPES[solution.model.gdim], f["cells"],
                   point_data={"displacement": _in_3d(f["displacement"])}, cell_data=cell_data)


def crack_lips_mesh(samples: typing.Sequence[dict]) -> VtuMesh:
    """The lips of every 2D crack as two polylines (+ and - lip) through the
    crack sample points (Solution.lip_samples), each point carrying the
    displacement of its lip, pressure, shear (friction), normal gap,
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
                    v = _state_codes(v)
                data[name].append(v)
            idx = offset + np.arange(n)
            conn.append(np.stack([idx[:-1], idx[1:]], axis=1))
            crack_id.append(np.full(n - 1, c, dtype=np.int32))
            lip.append(np.full(n - 1, sign, dtype=np.int32))
            offset += n
    if not pts:
        return VtuMesh(np.zeros((0, 3)), "line", np.zeros((0, 2), dtype=np.int64))
    point_data = {"displacement": _in_3d(np.concatenate(disp)), **{k: np.concatenate(v) for k, v in data.items()}}
    return VtuMesh(_in_3d(np.concatenate(pts)), "line", np.concatenate(conn).astype(np.int64), point_data=point_data,
                   cell_data={"crack": np.concatenate(crack_id), "lip": np.concatenate(lip)})


def crack_surface_mesh(facets: typing.Sequence[dict]) -> VtuMesh:
    """Both lips of every 3D crack (SurfaceCrackModel.lip_facets per crack;
    with contact, io.outputs.facet_contact's pressure, shear and state at
    the vertices)."""
    keys = ("u_plus", "jump", "gap", "slip_vector", "pressure", "shear", "state")
    data: dict[str, list] = {k: [] for k in keys}
    crack, lip, normal = [], [], []
    contact = all("pressure" in f for f in facets)
    for c, f in enumerate(facets):
        nf = len(f["cell"])
        if nf == 0:
            continue
        for sign, key in ((1, "u_plus"), (-1, "u_minus")):
            data["u_plus"].append(f[key].reshape(-1, 3))
            data["jump"].append(f["jump"].reshape(-1, 3))
            data["gap"].append(f["gap"].reshape(-1))
            data["slip_vector"].append(f["slip_vector"].reshape(-1, 3))
            if contact:
                data["pressure"].append(f["pressure"].reshape(-1))
                data["shear"].append(f["shear"].reshape(-1, 3))
                data["state"].append(_state_codes(f["state"].reshape(-1)))
            crack.append(np.full(nf, c, dtype=np.int32))
            lip.append(np.full(nf, sign, dtype=np.int32))
            normal.append(f["normal"])
    if not crack:
        return VtuMesh(np.zeros((0, 3)), "triangle", np.zeros((0, 3), dtype=np.int64))
    x = np.concatenate([f["x"].reshape(-1, 3) for f in facets for _ in (1, -1) if len(f["cell"])])
    names = {"u_plus": "displacement", "slip_vector": "slip"}
    point_data = {names.get(k, k): np.concatenate(v) for k, v in data.items() if v}
    return VtuMesh(x, "triangle", np.arange(len(x), dtype=np.int64).reshape(-1, 3), point_data=point_data,
                   cell_data={"crack": np.concatenate(crack), "lip": np.concatenate(lip),
                              "normal": np.concatenate(normal)})


def _state_codes(state: np.ndarray) -> np.ndarray:
    """Contact states as codes: 0 open, 1 stick, 2 slip."""
    return np.select([state == "stick", state == "slip"], [1, 2], 0).astype(np.int32)


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


def _pieces(rows: typing.Sequence[dict]) -> dict[tuple[int, int], list[int]]:
    groups: dict[tuple[int, int], list[int]] = {}
    for i, r in enumerate(rows):
        groups.setdefault((int(r["crack"]), int(r["piece"])), []).append(i)
    for idx in groups.values():
        idx.sort(key=lambda i: rows[i]["s"])
    return groups


def front_sif_mesh(rows: typing.Sequence[dict], closed: typing.Callable[[int, int], bool] | None = None) -> VtuMesh:
    """The SIF points of 3D fronts (results.json's "sifs") as polylines per
    front piece (a closed loop closes; closed(crack, piece): whether the
    piece is a loop, default: a piece without free-surface points), carrying
    K_I, K_II, K_III, their estimated errors (NaN without an estimate), the
    spreads, G, the mode mix, the domain radius, the free-surface flag and
    the local frame, to colour the front in ParaView."""
    if not rows:
        return VtuMesh(np.zeros((0, 3)), "line", np.zeros((0, 2), dtype=np.int64))
    x = np.array([[r["x"], r["y"], r["z"]] for r in rows], dtype=float)
    conn = []
    for (c, p), idx in _pieces(rows).items():
        conn += [(a, b) for a, b in zip(idx[:-1], idx[1:])]
        loop = closed(c, p) if closed is not None else not any(rows[i]["free_surface"] for i in idx)
        if loop and len(idx) > 2:
            conn.append((idx[-1], idx[0]))
    data = {k: np.array([float(r[k]) if r[k] is not None else math.nan for r in rows])
            for k in ("s", "K_I", "K_II", "K_III", "K_I_error", "K_II_error", "K_III_error", "K_I_spread",
                      "K_II_spread", "K_III_spread", "G", "mode_mix_deg", "radius", "element_size")}
    data["mode_mix_deg"] = np.nan_to_num(data["mode_mix_deg"], nan=0.0)
    data["free_surface"] = np.array([int(r["free_surface"]) for r in rows], dtype=np.int32)
    data["crack"] = np.array([int(r["crack"]) for r in rows], dtype=np.int32)
    data["e1"] = np.array([r["direction"] for r in rows], dtype=float)
    data["e2"] = np.array([r["normal"] for r in rows], dtype=float)
    return VtuMesh(x, "line", np.array(conn, dtype=np.int64).reshape(-1, 2), point_data=data)


def write_mesh(mesh: VtuMesh, path: str | pathlib.Path) -> pathlib.Path:
    """Write a mesh as VTU (cracklip.io.vtu: raw appended binary) through a
    temporary file."""
    path = pathlib.Path(path)
    with atomic_path(path) as tmp:
        _write_vtu_file(tmp, mesh)
    return path


@checked_keywords
def write_vtu(solution: Solution, path: str | pathlib.Path) -> pathlib.Path:
    """Write the sub-cell mesh with displacement and stress (see subcell_mesh) to path (a .vtu
    file, its folder made); returns the path. solution: what cl.solve returned."""
    if not isinstance(solution, Solution):
        raise InputError(f"write_vtu() takes the Solution cl.solve returned, got {type(solution).__name__}"
                         + (": solve it first, write_vtu(cl.solve(scene), path)"
                            if type(solution).__name__ == "Scene" else ""))
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return write_mesh(subcell_mesh(solution), path)


__all__ = ["subcell_mesh", "crack_lips_mesh", "crack_surface_mesh", "front_mesh", "front_sif_mesh", "write_mesh",
           "write_vtu", "CELL_TYPES"]
