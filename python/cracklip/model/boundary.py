"""The boundary of the part: its facets as segments (2D), the facets of a tag
with their outward normals (2D and 3D), and outward normals on a tag at any
point (2D)."""
from __future__ import annotations

import typing

import numpy as np

import dolfinx.cpp.mesh
import dolfinx.fem
import dolfinx.mesh

from ..errors import BoundaryConditionError
from ..scene.mesh import MeshData
from ..scene.processes import reduced, total


def boundary_segments(mesh) -> tuple[np.ndarray, np.ndarray]:
    """End points (n, 2), (n, 2) of the boundary facets (holes included) of a
    MeshData; computed once per mesh (under mpirun the first call is
    collective: every process's facets gathered on all, in rank order)."""
    cache = mesh.__dict__.setdefault("_boundary_segments", [])
    if not cache:
        cache.append(_segments(mesh))
    return cache[0]


def _segments(mesh) -> tuple[np.ndarray, np.ndarray]:
    msh = mesh.mesh
    tdim = msh.topology.dim
    facets = _boundary_facets(msh)
    verts = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)
    a, b = msh.geometry.x[verts[:, 0], :2], msh.geometry.x[verts[:, 1], :2]
    if msh.comm.size > 1:
        a, b = (np.concatenate(msh.comm.allgather(v)) for v in (a, b))
    return a, b


def _boundary_facets(msh) -> np.ndarray:
    """The part's boundary facets on this process: all in serial; under
    mpirun the facets of owned cells with one cell (every process holds the
    cells across its owned cells' facets: vertex-patch ghosts), so that each
    boundary facet is on one process."""
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    if msh.comm.size == 1:
        return dolfinx.mesh.exterior_facet_indices(msh.topology)
    f2c = msh.topology.connectivity(tdim - 1, tdim)
    one = np.flatnonzero(np.diff(f2c.offsets) == 1)
    owned = msh.topology.index_map(tdim).size_local
    return one[f2c.array[f2c.offsets[one]] < owned].astype(np.int32)


def owned_boundary_facets(mesh: MeshData) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The part's boundary facets this process counts (all in serial; under
    mpirun those of its owned cells, each facet on one process): facet
    indices (n,) and, as tag_facets, vertices (n, d, d), lengths or areas
    (n,), outward unit normals (n, d)."""
    facets = _boundary_facets(mesh.mesh)
    return (facets, *_facet_geometry(mesh, facets))


def boundary_normals(mesh: MeshData, where: str | int) -> typing.Callable[[np.ndarray], np.ndarray]:
    """Outward unit normal of a tagged boundary of a planar part as a
    function of points (n, 2) -> (n, 2).

    Each point takes the normal of the nearest facet of the tag: exact on a
    polygonal boundary, the facet normal on a meshed curve.
    """
    verts, _, n = _tag_facets(mesh, where)
    a, b = verts[:, 0], verts[:, 1]
    d = b - a
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


def tag_facets(mesh: MeshData, where: str | int, owned: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The facets of a tag (segments in 2D, triangles in 3D): centroids (n,
    d), lengths or areas (n,), outward unit normals (n, d). owned: under
    mpirun only those of the process's owned cells (MeshData.owned_facets)."""
    verts, size, n = _tag_facets(mesh, where) if not owned else _facet_geometry(mesh, mesh.owned_facets(where))
    return verts.mean(axis=1), size, n


def _tag_facets(mesh: MeshData, where: str | int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The facets of a tag: vertices (n, d, d), lengths or areas (n,),
    outward unit normals (n, d) (pointing away from the facet's cell)."""
    facets = mesh.facets(where)
    if total(facets.size, mesh.mesh.comm) == 0:  # (under mpirun a process may hold none of them)
        raise BoundaryConditionError(f"boundary {where!r} has no facets")
    return _facet_geometry(mesh, facets)


def exterior_facets(mesh: MeshData) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every facet of the part's boundary (holes included), as tag_facets:
    vertices (n, d, d), lengths or areas (n,), outward unit normals (n, d);
    computed once per mesh."""
    return _exterior(mesh)[0]


def exterior_facet_tags(mesh: MeshData) -> list[str | None]:
    """The boundary tag name of each facet of exterior_facets (None where
    the facet has no named tag)."""
    return _exterior(mesh)[1]


def _exterior(mesh: MeshData) -> tuple:
    """(exterior_facets, exterior_facet_tags), computed once per mesh
    (collective under mpirun: every process's boundary facets gathered on
    all, in rank order)."""
    cache = mesh.__dict__.setdefault("_exterior_facets", [])
    if not cache:
        msh = mesh.mesh
        facets = _boundary_facets(msh)
        names = {v: k for k, v in mesh.tags.items()}
        tag_of: dict[int, str] = {}
        if mesh.facet_tags is not None:
            for f, v in zip(np.asarray(mesh.facet_tags.indices), np.asarray(mesh.facet_tags.values)):
                if int(v) in names:
                    tag_of[int(f)] = names[int(v)]
        geometry, tags = _facet_geometry(mesh, facets), [tag_of.get(int(f)) for f in facets]
        if msh.comm.size > 1:
            parts = msh.comm.allgather((geometry, tags))
            geometry = tuple(np.concatenate([p[0][k] for p in parts]) for k in range(3))
            tags = [t for p in parts for t in p[1]]
        cache.append((geometry, tags))
    return cache[0]


def points_inside(mesh: MeshData, points: np.ndarray) -> np.ndarray:
    """Whether each point (n, d) lies in a cell of the mesh (on the boundary
    counts), any dimension; the cells' bounding-box tree is built once per
    mesh. Collective under mpirun (in a cell of any process: every process
    asks with the same points)."""
    import dolfinx.geometry
    msh = mesh.mesh
    pts = np.asarray(points, dtype=float).reshape(-1, msh.geometry.dim)
    if not len(pts):
        return np.zeros(0, dtype=bool)
    cache = mesh.__dict__.setdefault("_cell_tree", [])
    if not cache:
        cache.append(dolfinx.geometry.BoundingBoxTree(msh, msh.topology.dim))
    p3 = np.zeros((len(pts), 3))
    p3[:, :pts.shape[1]] = pts
    coll = dolfinx.geometry.compute_colliding_cells(msh, dolfinx.geometry.compute_collisions(cache[0], p3), p3)
    inside = np.diff(coll.offsets) > 0
    return reduced(inside.astype(np.uint8), "MAX", msh.comm) > 0 if msh.comm.size > 1 else inside


def _facet_geometry(mesh: MeshData, facets: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    msh = mesh.mesh
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    x = msh.geometry.x[:, :tdim]
    verts = x[dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)]   # (n, d, d)
    edges = verts[:, 1:] - verts[:, :1]
    if tdim == 2:  # a segment's normal: its direction turned by -90 degrees
        n = np.stack([edges[:, 0, 1], -edges[:, 0, 0]], axis=1)
        size = np.linalg.norm(edges[:, 0], axis=1)
    else:  # a triangle's: the cross product of two edges
        n = np.cross(edges[:, 0], edges[:, 1])
        size = 0.5 * np.linalg.norm(n, axis=1)
    n /= np.linalg.norm(n, axis=1)[:, None]
    # The cell of each boundary facet: its other vertices lie inside.
    f2c = msh.topology.connectivity(tdim - 1, tdim)
    cells = f2c.array[f2c.offsets[facets]]
    centroid = x[dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim, cells.astype(np.int32), False)].mean(axis=1)
    flip = np.einsum("ij,ij->i", centroid - verts[:, 0], n) > 0.0
    n[flip] *= -1.0
    return verts, size, n


def boundary_loops(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, int]:
    """The closed loop each boundary segment belongs to (labels (n,), by
    shared end points) and the label of the outer loop (the one with the
    largest bounding box; the others bound holes)."""
    import scipy.sparse
    import scipy.sparse.csgraph
    pts = np.concatenate([a, b])
    scale = float(np.ptp(pts, axis=0).max()) or 1.0
    key = np.round(pts / (1e-9 * scale)).astype(np.int64)
    _, ids = np.unique(key, axis=0, return_inverse=True)
    ids = ids.reshape(-1)
    n = len(a)
    graph = scipy.sparse.coo_matrix((np.ones(n), (ids[:n], ids[n:])), shape=(ids.max() + 1,) * 2)
    _, comp = scipy.sparse.csgraph.connected_components(graph, directed=False)
    labels = comp[ids[:n]]
    sizes = {int(lab): float(np.ptp(np.concatenate([a[labels == lab], b[labels == lab]]), axis=0).prod())
             for lab in np.unique(labels)}
    return labels, max(sizes, key=sizes.get)


def inside_segments(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> bool:
    """Even-odd ray casting of point p (2,) against segments a-b."""
    straddle = (a[:, 1] > p[1]) != (b[:, 1] > p[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[:, 0] + (p[1] - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return bool(np.count_nonzero(straddle & (xc > p[0])) % 2 == 1)


def nearest_boundary_point(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, float, int]:
    """(the boundary point nearest to p, its distance, its segment)."""
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
    q = a + t[:, None] * d
    dist = np.linalg.norm(q - p, axis=1)
    k = int(np.argmin(dist))
    return q[k], float(dist[k]), k


#: A boundary vertex turning by less than this (radians) is a point of a
#: discretised curve (a hole's circle at about 8 facets and more); a larger
#: turn is a corner of the part, whose facets are the geometry itself.
CURVE_TURN = 0.8


def boundary_tolerance(p: np.ndarray, a: np.ndarray, b: np.ndarray, scale: float) -> float:
    """How far from the boundary facets a point p (2,) may lie and still be
    on the boundary: the facets of a curved boundary (a hole) are chords,
    and a point of the true curve lies up to the sagitta beyond the nearest
    chord, inside the part. For a chord of length L between vertices whose
    facets turn by delta (a circle of radius L / (2 sin(delta / 2))) the
    sagitta is about L delta / 8; the tolerance is twice that, at least
    1e-9 of the part's size (straight boundaries, corners)."""
    q, dist, k = nearest_boundary_point(p, a, b)
    L = float(np.linalg.norm(b[k] - a[k]))
    if L <= 0.0:
        return 1e-9 * scale
    d = (b[k] - a[k]) / L
    turn = 0.0
    for v in (a[k], b[k]):  # the facets sharing each end vertex of segment k
        for other in np.flatnonzero((np.linalg.norm(a - v, axis=1) <= 1e-9 * scale)
                                    | (np.linalg.norm(b - v, axis=1) <= 1e-9 * scale)):
            if other == k:
                continue
            e = b[other] - a[other]
            n = float(np.linalg.norm(e))
            if n > 0.0:
                t = float(np.arccos(np.clip(abs(float(np.dot(d, e))) / n, -1.0, 1.0)))
                if t < CURVE_TURN:
                    turn = max(turn, t)
    return max(1e-9 * scale, 0.25 * L * turn)


def on_boundary(p: np.ndarray, a: np.ndarray, b: np.ndarray, scale: float) -> bool:
    """Whether p lies on the boundary: within boundary_tolerance of it."""
    return nearest_boundary_point(p, a, b)[1] <= boundary_tolerance(p, a, b, scale)


def where_outside(p, a: np.ndarray, b: np.ndarray) -> str | None:
    """None if the point lies in the part (or on its boundary), else "in a
    hole of the part" (inside the outer boundary, outside the part) or
    "outside the part"."""
    p = np.asarray(p, dtype=float)
    scale = float(np.ptp(np.concatenate([a, b]), axis=0).max()) or 1.0
    if inside_segments(p, a, b) or nearest_boundary_point(p, a, b)[1] <= 1e-9 * scale:
        return None
    labels, outer = boundary_loops(a, b)
    keep = labels == outer
    return "in a hole of the part" if inside_segments(p, a[keep], b[keep]) else "outside the part"


def polyline_pieces(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> list[dict]:
    """The parts of a polyline inside the part, in order: each with its
    start and end (2,), length, and whether each end lies on the boundary
    (start_on_boundary, end_on_boundary)."""
    pts = np.asarray(points, dtype=float)
    scale = float(np.ptp(np.concatenate([a, b, pts]), axis=0).max()) or 1.0
    cuts: list[np.ndarray] = []
    for p, q in zip(pts[:-1], pts[1:]):
        d, e = q - p, b - a
        den = d[0] * e[:, 1] - d[1] * e[:, 0]
        ok = np.abs(den) > 1e-300
        w = a - p
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0]) / den
            s = (w[:, 0] * d[1] - w[:, 1] * d[0]) / den
        hit = ok & (t >= 0.0) & (t <= 1.0) & (s >= 0.0) & (s <= 1.0)
        cuts.append(p)
        cuts += [p + tt * d for tt in np.sort(t[hit])]
    cuts.append(pts[-1])
    pieces: list[dict] = []
    for p, q in zip(cuts[:-1], cuts[1:]):
        length = float(np.linalg.norm(q - p))
        if length <= 1e-9 * scale or where_outside(0.5 * (p + q), a, b) is not None:
            continue
        if pieces and np.linalg.norm(pieces[-1]["end"] - p) <= 1e-9 * scale and not pieces[-1]["end_on_boundary"]:
            pieces[-1]["end"], pieces[-1]["length"] = q, pieces[-1]["length"] + length
        else:
            pieces.append({"start": p, "end": q, "length": length})
        for key, x in (("start_on_boundary", pieces[-1]["start"]), ("end_on_boundary", pieces[-1]["end"])):
            pieces[-1][key] = on_boundary(x, a, b, scale)
    return pieces
