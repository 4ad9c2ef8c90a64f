"""Local refinement of a given mesh (a user's .msh), its boundary tags kept.

A mesh read from a file has no geometry to re-mesh, so it is refined in
place: DOLFINx's Plaza refinement (``dolfinx.mesh.refine`` with the marked
cells' edges; conforming, every marked triangle split in four, its
neighbours bisected) is repeated until every cell is at most
SIZE_TOLERANCE times the size the field asks for at its centroid
(cracklip.scene.size_field: tip_h, refine points and segments, levels).
New nodes lie on the old edges: a curved boundary keeps the chords of the
file's mesh (re-mesh a geometry, mesh.kind = "geometry", to refine a curve
itself).

DOLFINx 0.5.2 does not carry facet tags through a local refinement, so
they are carried here by geometry: a refined boundary facet is either an
old facet or one of its halves (an old facet's midpoint is one of its
ends), which is matched exactly (to 1e-9 of the part's size) with a k-d tree.

``with_levels(md, levels)`` is the refined copy any MeshData can give: a
gmsh mesh of a known geometry is made again with the levels in its size
field (MeshData.recipe), a file's mesh is refined here.
"""
from __future__ import annotations

import dataclasses
import logging
import typing

import numpy as np

from ..errors import MeshError
from .cell_size import cell_sizes
from .mesh import MeshData, check_mesh
from .size_field import size_at


logger = logging.getLogger(__name__)


#: A cell is refined while its size (mean edge) exceeds the size field at
#: its centroid by this factor (a halving leaves 0.5-1.25 of the target).
SIZE_TOLERANCE = 1.25


#: At most this many refinement passes (each halves the marked cells: 2^-20
#: of the file's element size is beyond any use).
MAX_PASSES = 20


def _arrays(msh) -> tuple[np.ndarray, np.ndarray]:
    return msh.geometry.x[:, :2], msh.geometry.dofmap.array.reshape(-1, 3)


def _locate(msh, points: np.ndarray) -> np.ndarray:
    """The cell of msh holding each point (n,) (points inside the mesh)."""
    import dolfinx.geometry
    tree = dolfinx.geometry.BoundingBoxTree(msh, msh.topology.dim)
    p3 = np.zeros((len(points), 3))
    p3[:, :2] = points
    coll = dolfinx.geometry.compute_colliding_cells(msh, dolfinx.geometry.compute_collisions(tree, p3), p3)
    offsets = coll.offsets
    out = coll.array[offsets[:-1]]
    if np.any(np.diff(offsets) == 0):
        raise MeshError("a refined cell lies outside the mesh it refines (internal error)")
    return out


def inside_mesh(md: MeshData, points: typing.Sequence[typing.Sequence[float]]) -> list[bool]:
    """Whether each point lies in a cell of the mesh (on its boundary counts)."""
    if not len(points):
        return []
    import dolfinx.geometry
    msh = md.mesh
    tree = dolfinx.geometry.BoundingBoxTree(msh, msh.topology.dim)
    p3 = np.zeros((len(points), 3))
    p3[:, :2] = np.asarray(points, dtype=float).reshape(-1, 2)
    coll = dolfinx.geometry.compute_colliding_cells(msh, dolfinx.geometry.compute_collisions(tree, p3), p3)
    return [bool(n) for n in np.diff(coll.offsets)]


def _tagged_segments(md: MeshData) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(a (m, 2), b (m, 2), value (m,)) of the tagged facets."""
    msh = md.mesh
    if md.facet_tags is None or len(md.facet_tags.indices) == 0:
        return np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0, dtype=np.int32)
    import dolfinx.cpp.mesh
    geo = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, 1, np.asarray(md.facet_tags.indices, dtype=np.int32), False)
    x = msh.geometry.x[:, :2]
    return x[geo[:, 0]], x[geo[:, 1]], np.asarray(md.facet_tags.values, dtype=np.int32)


def _transfer_tags(old: MeshData, new_msh) -> typing.Any:
    """Facet tags of new_msh (a one-pass refinement of old.mesh): every new
    facet that is an old tagged facet or one of its halves takes its value."""
    import dolfinx.cpp.mesh
    import dolfinx.mesh
    from scipy.spatial import cKDTree
    a, b, values = _tagged_segments(old)
    tdim = new_msh.topology.dim
    new_msh.topology.create_entities(1)
    if len(values) == 0:
        return dolfinx.mesh.meshtags(new_msh, tdim - 1, np.zeros(0, dtype=np.int32), np.zeros(0, dtype=np.int32))
    x = new_msh.geometry.x[:, :2]
    scale = float(np.ptp(x, axis=0).max())
    tol = 1e-9 * scale
    num = new_msh.topology.index_map(1).size_local
    geo = dolfinx.cpp.mesh.entities_to_geometry(new_msh._mesh, 1, np.arange(num, dtype=np.int32), False)
    p, q = x[geo[:, 0]], x[geo[:, 1]]
    mid_old = 0.5 * (a + b)
    tree = cKDTree(mid_old)
    hit = np.full(num, -1, dtype=np.int64)
    # An old facet kept whole: same midpoint, and its ends on the old ends.
    d, k = tree.query(0.5 * (p + q))
    whole = (d <= tol) & (np.minimum(np.linalg.norm(p - a[k], axis=1), np.linalg.norm(p - b[k], axis=1)) <= tol)
    hit[whole] = k[whole]
    # A half: one end at the old midpoint, the other at an old end.
    for end, other in ((p, q), (q, p)):
        d, k = tree.query(end)
        half = (hit < 0) & (d <= tol) & (np.minimum(np.linalg.norm(other - a[k], axis=1),
                                                     np.linalg.norm(other - b[k], axis=1)) <= tol)
        hit[half] = k[half]
    facets = np.flatnonzero(hit >= 0).astype(np.int32)
    return dolfinx.mesh.meshtags(new_msh, tdim - 1, facets, values[hit[facets]])


def refine_once(md: MeshData, cells: np.ndarray) -> MeshData:
    """md with the given cells refined (Plaza, their edges marked), tags kept."""
    import dolfinx.cpp.mesh
    import dolfinx.mesh
    msh = md.mesh
    msh.topology.create_entities(1)
    msh.topology.create_connectivity(2, 1)
    c2e = msh.topology.connectivity(2, 1)
    edges = np.unique(c2e.array.reshape(-1, 3)[np.asarray(cells, dtype=np.int32)]).astype(np.int32)
    new = dolfinx.mesh.refine(msh, edges, redistribute=False)
    tags = _transfer_tags(md, new)
    out = dataclasses.replace(md, mesh=new, facet_tags=tags, standard_blocks={})
    return out


def refine_to(md: MeshData, target: typing.Callable[[np.ndarray], np.ndarray], what: str) -> tuple[MeshData, int]:
    """Refine md until every cell is at most SIZE_TOLERANCE x target(centroid)
    (target: sizes (n,) at points (n, 2)); returns (mesh, passes)."""
    out = md
    for k in range(MAX_PASSES + 1):
        x, cells = _arrays(out.mesh)
        size = cell_sizes(x, cells)
        centroid = x[cells].mean(axis=1)
        marked = np.flatnonzero(size > SIZE_TOLERANCE * target(centroid))
        if marked.size == 0:
            return out, k
        if k == MAX_PASSES:
            break
        out = refine_once(out, marked)
    raise MeshError(f"{what}: {MAX_PASSES} refinement passes did not reach the sizes asked for (a size below "
                    f"2^-{MAX_PASSES} of the file's elements?)")


def refine_file_mesh(md: MeshData, refine: typing.Sequence[typing.Sequence[float]] = (),
                     levels: typing.Sequence[typing.Sequence[float]] = (), what: str = "the mesh") -> MeshData:
    """A mesh read from a file refined locally: refine items (tip_h around
    tips, refine points and segments) and levels (each halving the size of
    this mesh's own cells within its radius), as cracklip.scene.size_field
    describes them; tags kept. A mesh already as fine is returned as it is."""
    if not refine and not any(int(v[5]) > 0 for v in levels):
        return md
    base = md.mesh
    bx, bcells = _arrays(base)
    base_size = cell_sizes(bx, bcells)

    def target(points: np.ndarray) -> np.ndarray:
        h0 = base_size[_locate(base, points)]  # the file mesh's own size there
        return size_at(points, h0, refine, levels)
    out, passes = refine_to(md, target, what)
    check_mesh(out.mesh)
    out.refine = list(md.refine) + [tuple(float(v) for v in r) for r in refine]
    out.refinements = list(md.refinements) + [(float(r[0]), float(r[1]), float(r[2])) for r in refine]
    out.levels = list(md.levels) + [tuple(v) for v in levels]
    out.recipe = None
    logger.info("%s refined in %d pass(es): %d -> %d cells", what, passes, len(bcells),
                out.mesh.topology.index_map(2).size_local)
    return out


def with_levels(md: MeshData, levels: typing.Sequence[typing.Sequence[float]]) -> MeshData:
    """The same mesh with refinement levels (x, y, x1, y1, D, L) added:
    made again by its recipe (gmsh, the geometry known), or refined here
    (a file's mesh)."""
    if md.recipe is not None:
        return md.recipe(levels=list(md.levels) + [tuple(v) for v in levels])
    return refine_file_mesh(md, (), levels, "the mesh")
