"""A 3D crack's front as a curve, and the mesh around it.

The front is the P1 polyline of the crack's level sets
(CrackGeometry3D.front), in pieces: closed loops, or open polylines between
two points of the part's boundary. crack_front gives it as arrays (Front):
its vertices, arc lengths, frames (e1 propagation, e2 normal, e3 tangent)
and the curvatures of the front and of the crack's surface; a
triangulated crack's frames and curvatures come from a smooth fit around
each vertex (FIT_ELEMENTS, FIT_CURVATURE; not kept where the surface is
kinked: FIT_TURN). project gives, for any points near the front, their
nearest front position, frame and curvatures: what the interaction
integral's auxiliary fields follow (fracture/sif_3d.py).

The mesh helpers (each node's cells, the boundary's nodes, the lips'
quadrature points) are cached on the model. Under MPI every process holds
the whole front; a segment is integrated by the process owning its cell
(owned_segments), and all_points gathers every process's points.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import scipy.spatial

from .. import _cracklip
from ..scene.cell_size import cell_sizes
from ..scene.crack_surface import SurfaceCrack
from ..scene.processes import reduced


def model_cache(model) -> dict:
    return model.__dict__.setdefault("_sif3d_cache", {})


def node_tree(model) -> scipy.spatial.cKDTree:
    c = model_cache(model)
    if "tree" not in c:
        c["tree"] = scipy.spatial.cKDTree(model.x)
    return c["tree"]


def node_cells(model) -> tuple[np.ndarray, np.ndarray]:
    """(offsets, cells): the cells around each node, CSR."""
    c = model_cache(model)
    if "node_cells" not in c:
        flat = model.cells.ravel()
        order = np.argsort(flat, kind="stable")
        counts = np.bincount(flat, minlength=model.x.shape[0])
        c["node_cells"] = (np.concatenate([[0], np.cumsum(counts)]), (order // 4).astype(np.int32))
    return c["node_cells"]


def cells_of_nodes(model, nodes: np.ndarray) -> np.ndarray:
    off, cl = node_cells(model)
    nodes = np.asarray(nodes, dtype=np.int64)
    if nodes.size == 0:
        return np.zeros(0, dtype=np.int32)
    counts = off[nodes + 1] - off[nodes]
    idx = np.repeat(off[nodes] - np.concatenate([[0], np.cumsum(counts)[:-1]]), counts) + np.arange(counts.sum())
    return np.unique(cl[idx])


def boundary_nodes(model) -> np.ndarray:
    """Nodes on the part's boundary (faces held by one tetrahedron). Under
    MPI this process's part of them: the faces of its owned cells (whose
    neighbours it holds), not the faces where its ghost cells end."""
    c = model_cache(model)
    if "boundary_nodes" not in c:
        cells = model.cells
        faces = np.sort(np.concatenate([cells[:, [1, 2, 3]], cells[:, [0, 2, 3]], cells[:, [0, 1, 3]],
                                        cells[:, [0, 1, 2]]]), axis=1)
        _, idx, counts = np.unique(faces, axis=0, return_index=True, return_counts=True)
        one = idx[counts == 1]
        one = one[model.owned_cells_only(one % len(cells))]  # (faces are stacked face-type by face-type)
        c["boundary_nodes"] = np.unique(faces[one])
    return c["boundary_nodes"]


def model_comm(model):
    """The model's communicator under MPI, else None."""
    return model.comm


def all_points(model, points: np.ndarray) -> np.ndarray:
    """Every process's points (n, 3), without repeats, in one order (the
    points themselves in serial)."""
    comm = model_comm(model)
    if comm is None:
        return points
    allp = np.concatenate(comm.allgather(np.asarray(points, dtype=float).reshape(-1, 3)))
    return np.unique(allp, axis=0) if len(allp) else allp


def owned_segments(model, segment_cell: np.ndarray) -> np.ndarray:
    """Which front segments (by their cells, -1: none) this process
    integrates: those of its owned cells (each segment's cell is owned by
    one process; all in serial)."""
    cell = np.asarray(segment_cell)
    return (cell >= 0) & model.owned_cells_only(cell)


#: Gauss points per lip facet direction for the lip terms.
LIP_POINTS = 6


def lip_points(model, crack: int) -> dict:
    """The crack's lip points of the lip terms (LIP_POINTS per facet direction), computed once."""
    return model.cracks[crack].lip_points(model, LIP_POINTS)


def owned_lip_points(model, crack: int) -> np.ndarray:
    """The lip points (n, 3) in this process's owned cells (all in serial)."""
    lp = lip_points(model, crack)
    return lp["x"][model.owned_cells_only(lp["cell"])]


#: A triangulated crack's surface and front are fitted (frames,
#: curvatures) over this many front element sizes around each front vertex
#: (and at least three facet edges: SurfaceCrack.front_geometry; five let a
#: coarse triangulation's fit reach 0.6 of the front's radius and run 8 % low).
FIT_ELEMENTS = 4.0


#: ... and over at most this fraction of the front's smallest radius of
#: curvature (from the mesh's front polyline).
FIT_CURVATURE = 0.5


#: The fit assumes a smooth surface. Where a grown surface is kinked within
#: the fit's reach (a strip that kinked by 30 degrees next to a free-surface
#: end, the next one back in plane) the quadric cannot follow it: on the
#: surface crack a/c0 = 1 grown to a/t = 0.24 on a mesh of a/8 it turned the
#: normal by 90-127 degrees from the mesh's (kappa_11 up to 9e3 against an
#: element size of 0.035), e1 pointed into the crack, int q (e1 . d) ds came
#: out negative and the run broke off. Where the fitted normal departs from
#: the mesh's (the level sets' gradient in the front's cell) by more than
#: FIT_TURN degrees, the vertex keeps the mesh's frame and the polyline's
#: kappa_f (the surface's curvatures 0), as an elliptical crack's front does,
#: with a warning. On that front the fit's turn was below 10 degrees at the
#: 78 smooth vertices, 23-127 at the 24 in the kinked part.
FIT_TURN = 15.0


#: Keep the terms of the front's curvature (module doc); False drops them
#: (straight-front auxiliary fields in each point's frame), for measuring
#: their effect.
CURVATURE_TERMS = True


@dataclasses.dataclass
class Front:
    """A crack's front polyline as arrays: vertices x (n, 3), s (n,), frame
    (n, 3, 3), piece (n,), segments (m, 2), segment_cell (m,), per piece:
    offsets, closed, length; curvature (n,) the front's (kappa_f) at the
    vertices, curvatures (n, 4) kappa_f, kappa_11, kappa_33, tau (the
    crack surface's too: interaction_integral_3d.h; 0 but kappa_f on a
    planar crack), segment sizes (m,) (mean edge of the segment's cell);
    fitted: the frames and curvatures come from the smooth fit of a
    triangulated surface (SurfaceCrack.front_geometry), not from the
    geometry's frames; unfitted, fit_turn: where the fit was not kept
    (FIT_TURN)."""
    x: np.ndarray
    s: np.ndarray
    frame: np.ndarray
    piece: np.ndarray
    offsets: np.ndarray
    closed: np.ndarray
    length: np.ndarray
    segments: np.ndarray
    segment_cell: np.ndarray
    segment_size: np.ndarray
    curvature: np.ndarray
    on_boundary: np.ndarray
    curvatures: np.ndarray | None = None
    fitted: bool = False
    #: (n,) bool: a fitted front's vertices where the fit was not kept (FIT_TURN), and (n,) the fit's turn
    #: of the normal from the mesh's in degrees (None unfitted)
    unfitted: np.ndarray | None = None
    fit_turn: np.ndarray | None = None

    def __post_init__(self):
        if self.curvatures is None:
            self.curvatures = np.zeros((len(self.s), 4))
            self.curvatures[:, 0] = self.curvature


def crack_front(model, crack: int) -> Front:
    c = model_cache(model).setdefault("fronts", {})
    if crack in c:
        return c[crack]
    f = model.geometries[crack].front
    x, s, frame = np.asarray(f["x"]), np.asarray(f["s"]), np.asarray(f["frame"])
    off = np.asarray(f["piece_offsets"])
    closed = np.asarray(f["closed"]).astype(bool)
    piece = np.repeat(np.arange(len(closed)), np.diff(off))
    length = np.array([s[off[k + 1] - 1] + (np.linalg.norm(x[off[k + 1] - 1] - x[off[k]]) if closed[k] else 0.0)
                       for k in range(len(closed))])
    segs = np.asarray(f["segments"]).reshape(-1, 2)
    scell = np.asarray(f["segment_cell"])
    ssize = np.zeros(len(scell))
    if len(scell):  # (under MPI each segment's size from the process owning its cell)
        own = owned_segments(model, scell)
        ssize[own] = cell_sizes(model.x, model.cells[scell[own]])
        if model_comm(model) is not None:
            ssize = reduced(ssize, "SUM", model_comm(model))
    h = float(np.median(ssize)) if len(ssize) else 0.0
    curv = np.zeros(len(s))
    for k in range(len(closed)):
        idx = np.arange(off[k], off[k + 1])
        if len(idx) < 3:
            continue
        sp, e1, e3 = s[idx], frame[idx, 0], frame[idx, 2]
        if closed[k]:  # unroll the loop once on each side
            L = length[k]
            sp = np.concatenate([sp - L, sp, sp + L])
            e1, e3 = np.concatenate([e1] * 3), np.concatenate([e3] * 3)
            mid = np.arange(len(idx), 2 * len(idx))
        else:
            mid = np.arange(len(idx))
        w = max(h, 1e-12)
        ahead = np.clip(np.searchsorted(sp, sp[mid] + w, side="right") - 1, mid + 1, len(sp) - 1)
        behind = np.clip(np.searchsorted(sp, sp[mid] - w, side="left"), 0, np.maximum(mid - 1, 0))
        ahead = np.where(ahead <= mid, np.minimum(mid + 1, len(sp) - 1), ahead)
        behind = np.where(behind >= mid, np.maximum(mid - 1, 0), behind)
        ds = sp[ahead] - sp[behind]
        de3 = e3[ahead] - e3[behind]
        curv[idx] = np.where(ds > 0, -np.einsum("ij,ij->i", de3, e1[mid]) / np.maximum(ds, 1e-300), 0.0)
    on_boundary = np.asarray(f["on_boundary"]).astype(bool)
    surface = model.cracks[crack].crack
    if isinstance(surface, SurfaceCrack) and len(x):
        # A triangulated surface: frames and curvatures of the smooth
        # surface and front through its vertices, fitted over the domains'
        # reach (the facets' normals jump from facet to facet).
        # (over at most FIT_CURVATURE of the front's radius of curvature: a
        # quartic in x3 cannot follow a front that turns through a right
        # angle within the reach; a penny at a/3 fitted over 1.35 a took
        # kappa_f = 0.61 / a and K 5.5 % low)
        # Per vertex, by the front's curvature within its own reach: a global largest curvature (the
        # ends of a shallow surface crack, radius a^2/c) shrank every point's reach to little more than
        # one grown strip behind the front, where kappa_11 (across the front) is undetermined: on the
        # surface crack a/c = 0.32 grown on a mesh of a/8 the fit turned the normal by 80 degrees at the
        # deepest points (kappa_11 ~ 5e3) and K_I came out -0.44 there.
        reach = np.full(len(x), FIT_ELEMENTS * h)
        kabs = np.abs(curv)
        for i, near in enumerate(scipy.spatial.cKDTree(x).query_ball_point(x, FIT_ELEMENTS * h)):
            kmax = float(kabs[near].max()) if near else 0.0
            if kmax > 0.0:
                reach[i] = min(reach[i], FIT_CURVATURE / kmax)
        fit = surface.front_geometry(x, frame, reach)
        fframe, k = fit["frame"], fit["curvatures"]
        turn = np.degrees(np.arccos(np.clip(np.einsum("ni,ni->n", fframe[:, 1], frame[:, 1]), -1.0, 1.0)))
        kinked = turn > FIT_TURN
        if np.any(kinked):
            fframe, k = fframe.copy(), k.copy()
            fframe[kinked] = frame[kinked]
            k[kinked] = 0.0
            k[kinked, 0] = curv[kinked]
        out = Front(x, s, fframe, piece, off, closed, length, segs, scell, ssize, k[:, 0].copy(), on_boundary,
                    k, True, kinked, turn)
    else:
        out = Front(x, s, frame, piece, off, closed, length, segs, scell, ssize, curv, on_boundary)
    c[crack] = out
    return out


def wrap(ds: np.ndarray, length: float, closed: bool) -> np.ndarray:
    return (ds + 0.5 * length) % length - 0.5 * length if closed else ds


def project(model, crack: int, points: np.ndarray) -> dict[str, np.ndarray]:
    """Nearest front point of points (n, 3): s, piece, distance, x (n, 3),
    frame (n, 3, 3), curvatures (n, 4) (kappa_f, kappa_11, kappa_33, tau
    interpolated along the segment), curvature (n,) (kappa_f)."""
    fr = crack_front(model, crack)
    pts = np.ascontiguousarray(points, dtype=float)
    # (a triangulated surface: its fitted frames, interpolated as the geometry's are)
    p = _cracklip.compute_front_projection_3d(model.geometries[crack], pts,
                                              np.ascontiguousarray(fr.frame) if fr.fitted else None)
    seg = fr.segments[p["segment"]]
    t = p["t"]
    k = (1.0 - t)[:, None] * fr.curvatures[seg[:, 0]] + t[:, None] * fr.curvatures[seg[:, 1]]
    if not CURVATURE_TERMS:
        k[:] = 0.0
    # A point beyond its front point's centre of curvature (a domain too large
    # for the curvature; the domains are clipped to avoid it) gets the
    # curvatures scaled so that it lies a tenth of the way: the kernel needs
    # h = 1 + kappa_f x1 - kappa_33 x2 > 0.
    d = pts - p["x"]
    lin = k[:, 0] * np.einsum("ni,ni->n", d, p["frame"][:, 0])
    if np.any(k[:, 2]):
        lin -= k[:, 2] * np.einsum("ni,ni->n", d, p["frame"][:, 1])
    bad = 1.0 + lin < 0.1
    k[bad] *= (-0.9 / lin[bad])[:, None]
    p["curvatures"] = k
    p["curvature"] = k[:, 0].copy()
    p["curvature_clamped"] = bad
    return p


__all__ = ["Front", "crack_front", "project", "wrap", "node_tree", "node_cells", "cells_of_nodes", "boundary_nodes",
           "lip_points", "owned_lip_points", "owned_segments", "all_points", "model_cache", "model_comm", "FIT_TURN"]
