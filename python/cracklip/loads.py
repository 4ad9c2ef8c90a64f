"""Loads beyond constant tractions: boundary normals (pressure, t = sigma n) and body forces.

- ``boundary_normals(mesh, where)`` gives the outward unit normal of a tagged
  boundary at any point on it (the normal of the nearest boundary facet), so
  that a pressure p becomes the traction -p n and a stress field sigma(x)
  the traction sigma(x) n.
- ``assemble_body_force(model, force)`` integrates a constant body force
  (force per unit area) against every basis function, standard and
  enriched, with the stiffness's quadrature in the enriched cells.
"""
from __future__ import annotations

import typing

import numpy as np

import dolfinx.cpp.mesh

from . import _cracklip
from .errors import InputError
from .mesh import MeshData


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


def _greedy_colours(layout) -> np.ndarray:
    """Colour the pseudo-nodes so that no two of one colour share an enriched cell."""
    offsets = np.asarray(layout.cell_offsets)
    members = np.asarray(layout.cell_enr)
    n = layout.num_enriched
    neighbours: list[set[int]] = [set() for _ in range(n)]
    for i in range(len(offsets) - 1):
        group = members[offsets[i]:offsets[i + 1]].tolist()
        for k in group:
            neighbours[k].update(group)
    colour = np.full(n, -1, dtype=np.int64)
    for k in range(n):
        used = {colour[j] for j in neighbours[k] if j != k}
        c = 0
        while c in used:
            c += 1
        colour[k] = c
    return colour


def assemble_body_force(model, force: typing.Sequence[float]) -> np.ndarray:
    """Load vector (num_dofs,) of a constant body force f: int f . phi_j dx for every dof j.

    Standard dofs: each node gets f times a third of the area of its cells
    (exact for P1). Enriched dofs: the stiffness's quadrature of the enriched
    cells (sub-triangles, tip rules); the enriched basis functions are
    evaluated by colours of pseudo-nodes that share no cell, two
    evaluations per colour.
    """
    f = np.asarray(force, dtype=float).reshape(2)
    if not np.all(np.isfinite(f)):
        raise InputError(f"body force {f.tolist()} contains NaN or infinity")
    b = np.zeros(model.num_dofs)
    if not np.any(f):
        return b
    xv = model.x[model.cells]
    e1, e2 = xv[:, 1] - xv[:, 0], xv[:, 2] - xv[:, 0]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    for d in (0, 1):
        np.add.at(b, 2 * model.cells.ravel() + d, np.repeat(f[d] * area / 3.0, 3))
    layout = model.layout
    if layout.num_enriched == 0:
        return b
    opts = model.scene.options
    geometries = model.geometries
    fp = _cracklip.compute_field_points(model.x, model.cells, layout, geometries, np.zeros(model.num_dofs),
                                        np.asarray(layout.cells, dtype=np.int32), opts.quadrature_options())
    pcell = fp["cell"]
    xc = model.x[model.cells[pcell]]
    J = np.stack([xc[:, 1] - xc[:, 0], xc[:, 2] - xc[:, 0]], axis=2)
    ref = np.linalg.solve(J, (fp["x"] - xc[:, 0])[:, :, None])[:, :, 0]
    side = fp["side"].astype(np.int8)
    weight = fp["weight"]
    colour = _greedy_colours(layout)
    offsets = np.asarray(layout.cell_offsets)
    members = np.asarray(layout.cell_enr)
    enr_cells = np.asarray(layout.cells)
    cell_of_member = np.repeat(enr_cells, np.diff(offsets))
    nstd = layout.num_std_nodes
    for c in range(int(colour.max()) + 1):
        owner = np.full(model.cells.shape[0], -1, dtype=np.int64)
        pick = colour[members] == c
        owner[cell_of_member[pick]] = members[pick]
        at = np.flatnonzero(owner[pcell] >= 0)
        if at.size == 0:
            continue
        k = owner[pcell[at]]
        for d in (0, 1):
            u = np.zeros(model.num_dofs)
            u[2 * (nstd + np.flatnonzero(colour == c)) + d] = 1.0
            val, _ = _cracklip.evaluate_displacement(model.x, model.cells, layout, geometries, u,
                                                     pcell[at], ref[at], side[at])
            np.add.at(b, 2 * (nstd + k) + d, weight[at] * (val @ f))
    return b
