"""The boundary of the part: its facets as segments, and outward normals on a tag."""
from __future__ import annotations

import typing

import numpy as np

import dolfinx.cpp.mesh
import dolfinx.fem
import dolfinx.mesh

from ..errors import InputError
from ..scene.mesh import MeshData


def boundary_segments(mesh) -> tuple[np.ndarray, np.ndarray]:
    """End points (n, 2), (n, 2) of the boundary facets (holes included) of a MeshData."""
    msh = mesh.mesh
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    facets = dolfinx.mesh.exterior_facet_indices(msh.topology)
    verts = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)
    return msh.geometry.x[verts[:, 0], :2], msh.geometry.x[verts[:, 1], :2]


def boundary_normals(mesh: MeshData, where: str | int) -> typing.Callable[[np.ndarray], np.ndarray]:
    """Outward unit normal of a tagged boundary as a function of points (n, 2) -> (n, 2).

    Each point takes the normal of the nearest facet of the tag: exact on a
    polygonal boundary, the facet normal on a meshed curve.
    """
    facets = mesh.facets(where)
    if facets.size == 0:
        raise InputError(f"boundary {where!r} has no facets")
    msh = mesh.mesh
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    msh.topology.create_connectivity(tdim, 0)
    verts = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)
    x = msh.geometry.x[:, :2]
    a, b = x[verts[:, 0]], x[verts[:, 1]]
    # The cell of each boundary facet; its third vertex lies inside.
    f2c = msh.topology.connectivity(tdim - 1, tdim)
    cells = f2c.array[f2c.offsets[facets]]
    cell_geo = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim, cells.astype(np.int32), False)
    centroid = x[cell_geo].mean(axis=1)
    d = b - a
    n = np.stack([d[:, 1], -d[:, 0]], axis=1)
    n /= np.linalg.norm(n, axis=1)[:, None]
    flip = np.einsum("ij,ij->i", centroid - a, n) > 0.0
    n[flip] *= -1.0
    dd = np.einsum("ij,ij->i", d, d)

    def normals(points: np.ndarray) -> np.ndarray:
        p = np.asarray(points, dtype=float).reshape(-1, 2)
        out = np.empty_like(p)
        # In chunks, so that memory stays bounded for long boundaries.
        step = max(1, 2_000_000 // max(len(a), 1))
        for s in range(0, len(p), step):
            q = p[s:s + step, None, :]
            t = np.clip(np.einsum("pfi,fi->pf", q - a[None], d) / dd[None], 0.0, 1.0)
            dist = np.linalg.norm(a[None] + t[..., None] * d[None] - q, axis=2)
            out[s:s + step] = n[np.argmin(dist, axis=1)]
        return out
    return normals
