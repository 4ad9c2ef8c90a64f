"""A 3D crack's front joined alike on every process (issue 40): the front
polyline, its points, frames and boundary ends do not depend on how the mesh
is split, nor on DOLFINx's local cell order.

Each front cell holds one straight front segment (cpp/geometry/
crack_front_3d.h); the C++ joins them into ordered pieces, and the order it
meets them in decides where a closed loop starts and which of two coincident
points is kept. The segments of a process's own part (owned cells and the
ghost cells around them) would give a front cut at the partition, with
false ends. So every process gathers every process's segments of its owned
front cells (a few per front element: the front is a line, a few kB), sorts
them by the cells' input index (the mesh file's or gmsh's cell order, the
same on any number of processes) and joins them with the same C++. Serial
runs take the same path, so one process and N give the same front points.

The faces of the front cells held by one front cell of the whole mesh (the
candidates for the part's boundary, where an open piece ends) are counted
over all processes by their nodes' input indices. A segment's cell is the
process's local index of that cell, or -1 where the cell is not on the
process (a part of the front another process integrates).
"""
from __future__ import annotations

import numpy as np

from ...scene.processes import gathered, reduced

#: cpp/geometry/crack_geometry_3d.h CellClass3D::front.
FRONT = 3

#: The faces of a tetrahedron (local vertices), as the C++ lists them.
FACES = np.array([[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]])


def join_front(geometry, surface, msh, x: np.ndarray, cells: np.ndarray, node_input: np.ndarray) -> None:
    """Collective: replace geometry's front (computed on this process's
    cells x, cells: extract_node_mesh's, owned cells first; node_input:
    their nodes' input indices) by the front joined from every process's
    owned front cells in input-cell order, with frames from surface (module
    doc)."""
    comm = msh.comm
    tdim = msh.topology.dim
    num_owned = msh.topology.index_map(tdim).size_local
    original = np.asarray(msh.topology.original_cell_index, dtype=np.int64)
    fs = geometry.front_segments
    mine = fs["cell"] < num_owned
    key = original[fs["cell"][mine]]
    rows = np.column_stack([fs["p"][mine], fs["q"][mine], fs["grad_phi"][mine], fs["grad_psi"][mine]])
    # The faces of the owned front cells, by their nodes' input indices.
    front_cells = np.flatnonzero(np.asarray(geometry.cell_class)[:num_owned] == FRONT)
    tri = cells[front_cells][:, FACES].reshape(-1, 3)                      # (4 f, 3) local nodes
    face_key = np.sort(node_input[tri], axis=1)
    face_x = x[tri].reshape(-1, 9)
    key, rows, face_key, face_x = gathered(comm, [key, rows, face_key.reshape(-1, 3), face_x])
    order = np.argsort(key, kind="stable")
    key, rows = key[order], rows[order]
    # Faces held by one front cell of the whole mesh, in input-node order.
    boundary = np.zeros((0, 9))
    if len(face_key):  # (np.unique's rows: sorted by key)
        _, first, count = np.unique(face_key, axis=0, return_index=True, return_counts=True)
        boundary = face_x[first[count == 1]]
    # The segments' cells on this process (-1: another process's part).
    by_input = np.argsort(original, kind="stable")
    at = np.clip(np.searchsorted(original[by_input], key), 0, len(original) - 1)
    local = np.where(original[by_input][at] == key, by_input[at], -1).astype(np.int32)
    h_front = float(reduced(float(fs["cell_size"]), "MIN", comm))
    geometry.set_front(np.ascontiguousarray(rows[:, 0:3]), np.ascontiguousarray(rows[:, 3:6]), local,
                       np.ascontiguousarray(rows[:, 6:9]), np.ascontiguousarray(rows[:, 9:12]),
                       np.ascontiguousarray(boundary.reshape(-1, 3, 3)), h_front if len(key) else 1.0, surface)


__all__ = ["join_front"]
