"""Stress intensity factors K_I, K_II, K_III along 3D crack fronts: front
points, domains chosen per point, the domain interaction integral on three
domains per point, and their spread (sif.py does the tips of 2D cracks: the
geometry differs, hats along a curved front against a disc around one
point; both give rows of one schema, sif.SIF_KEYS).

Front points. Each piece of a crack's front (a closed loop, or an open
polyline between two points of the part's boundary) carries front points at
arc-length steps of about HAT_ELEMENTS element sizes, shortened to the
front's radius of curvature where that is smaller (HAT_CURVATURE; a loop: n
steps round it; an open piece: both ends included). The front is the P1 polyline of
the crack's level sets (CrackGeometry3D.front); a point's frame (e1
propagation, e2 normal, e3 tangent) is interpolated along it.

The virtual crack extension of front point k is q_k(x) d_k, d_k = e1 of the
point, with q_k = q_s(s) q_r(r) at the mesh nodes (s, r the arc length of
the node's nearest front point and its distance to the front) interpolated
by P1 (so that its gradient is constant on a cell and the integrals below
are the quadrature's of cell-wise smooth integrands):

- q_s the hat along the front between the neighbouring front points
  (1 at point k, 0 at k - 1 and k + 1; asymmetric where the steps differ);
- q_r = 1 for r <= R_IN_FRACTION R, linear to 0 at the domain radius R.

The auxiliary fields of a quadrature point follow the front (the unit-K
Williams fields in the frame of its nearest front point) with their true
gradient, and the integral keeps the terms of the front's curvature in the
crack's plane (cpp/fracture/interaction_integral_3d.h): the hoop part of the
gradient, the divergence of the auxiliary stress and its traction on the
lips. Not kept: the rate of change of the curvature along the front and the
curvature of the crack surface (a non-planar crack). Then

    I_m int q_s (e1 . d) ds = int_V (grad q . T_m d + q D_m . d) dV
                              - int_lips (t . [grad u_aux d] + t_aux . grad u d) q dA,

T, D from the C++ kernel (interaction_integrand_3d, body force included), t
the lip traction (the lip pressure's, the contact pressure and friction
shear: fracture/lip_tractions.py), and K_I = E' I_I / 2, K_II = E' I_II / 2,
K_III = mu I_III, E' = E / (1 - nu^2). The normalisation is the integral of
the P1 q along the front polyline.

Domains. The radius of the largest domain is sif_radius, else
DEFAULT_ELEMENTS element sizes at the point (the mean edge of the front's
cells within the hat), clipped so that the domain stays clear of the part's
boundary (except, at a point where the front meets the boundary, the free
surface it meets: K there is reported and flagged free_surface, since the
singularity is no longer the square root of the Williams fields), of other
cracks and of the front itself where it comes back (a thin crack), and
within half the front's radius of curvature. K is computed on
DOMAIN_FRACTIONS of that radius; the largest gives K, the three their
spread, and a spread above SPREAD_WARNING of the K scale is warned about.

Conventions (cracklip.exact.embedded_cracks): K_I > 0 opens the crack,
K_II > 0 when the + side moves along +e1 relative to the - side, K_III > 0
when it moves along +e3 (e3 = e1 x e2).
"""
from __future__ import annotations

import copy
import dataclasses
import logging
import math
import typing

import numpy as np
import scipy.spatial

from .. import _cracklip
from ..errors import InputError
from ..model.cracks.surface import split_enriched
from ..scene.cell_size import cell_sizes
from ..scene.crack_surface import EllipticalCrack, SurfaceCrack
from ..scene.processes import reduced
from ..scene.symmetry import SymmetryCondition
from . import front_sampling
from .lip_tractions import has_lip_traction, lip_traction
from .sif import complete_rows

logger = logging.getLogger(__name__)

#: Default radius of the largest domain, in element sizes at the front point.
DEFAULT_ELEMENTS = 4.0

#: The domains' radii as fractions of the largest.
DOMAIN_FRACTIONS = (0.5, 0.75, 1.0)

#: q_r is 1 up to this fraction of the domain radius, then linear to 0
#: (0: linear from the front; on a penny crack at a/h = 20 it halved the
#: scatter of K_II against 0.5).
R_IN_FRACTION = 0.0

#: Distance between neighbouring front points (the hat's half-width), in
#: element sizes at the front (mean edges of the front's cells). Penny crack
#: at a/h = 20: scatter of K_I along the front +-0.6 % with 1, +-0.2 % with
#: 2, +-0.08 % with 3; K_II, K_III 4.8e-3, 1.2e-3, 8.6e-4 of K.
HAT_ELEMENTS = 3.0

#: K on the hat is the hat's average of K along the front: with half-widths
#: l- behind and l+ ahead, K + K' (l+ - l-) / 3 + K'' (l+^2 - l+ l- + l-^2)
#: / 12 (equal l: K + K'' l^2 / 12); K' and K'' from the neighbours'
#: averages (non-uniform differences) remove those terms (equal l: K_k -
#: (K_k+1 - 2 K_k + K_k-1) / 12) where both neighbours exist and are not
#: free-surface points.
HAT_CORRECTION = True

#: Where the front curves strongly the hat's half-width also stays below
#: HAT_CURVATURE radii of curvature rho of the front (rho from the largest
#: |kappa| within the element-size hat of the point), but not below
#: MIN_HAT_ELEMENTS element sizes: the front points are spaced by the local
#: half-width l(s) = clip(HAT_CURVATURE rho, MIN_HAT_ELEMENTS h,
#: HAT_ELEMENTS h) (equal steps of the integral of ds / l), so that K does
#: not vary much more across a hat than the hat correction can remove.
#: Irwin ellipse b/a = 0.25 (rho = b^2/a at the ends of the major axis: 1.75,
#: 2.5, 3.5 elements at h = b/7, b/10, b/14; there the fixed hat spans 40
#: degrees of parametric angle where K falls by a quarter), max error with
#: fixed hats -> with these: 2.54 -> 2.99 % at b/7, 1.75 -> 1.27 % at b/10,
#: 0.91 -> 0.76 % at b/14 (both with the hat correction below); a fraction
#: 0.75 gave 1.20 % / 0.87 %. Fronts with rho >= HAT_ELEMENTS h everywhere
#: (the penny at a/10 and finer) keep equal steps.
HAT_CURVATURE = 1.0
#: Hats narrower than 2 elements scatter (penny, HAT_ELEMENTS above: +-0.6 %
#: at 1 element); Irwin b/a = 0.25 at b/7: max 3.36 % with a floor of 1, 2.99
#: % with 2 (K_II, K_III noise 1.3 % -> 1.0 %).
MIN_HAT_ELEMENTS = 2.0

#: Options.sif_points shortens the hats to this many element sizes at most:
#: on a coarse front 16 points would make two-element hats, whose K runs
#: low (penny at a/4, 12 points of 2.1 elements: K_I 4.5 % low at every
#: point; 8 points of 3.1 elements: -0.8 .. +0.4 %).
COUNT_HAT_ELEMENTS = HAT_ELEMENTS

#: A domain's radius stays below this fraction of the smallest radius of
#: curvature of the front and of the crack's surface (1 / max(|kappa_f|,
#: |kappa_11|, |kappa_33|): the curvature terms hold for h = 1 + kappa_f x1
#: - kappa_33 x2 > 0, the surface-following coordinates while the quadric
#: describes the surface; the change of the curvatures along the front is
#: not kept).
CURVATURE_FRACTION = 0.75

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

#: Spread above this fraction of the K scale is warned about.
SPREAD_WARNING = 0.01

#: Gauss degree of the integrand in cells without enriched nodes, by the
#: distance of the cell's nearest node to the front in cell diameters
#: (below 1, below 2, beyond): the auxiliary fields vary on the scale of
#: that distance.
PLAIN_DEGREES = (6, 4, 3)

#: Gauss degree in enriched cells away from the front (the stiffness's rule
#: is raised to it; front cells keep their collapsed rules).
ENRICHED_DEGREE = 4

#: Gauss degree of the pieces of enriched cells within a diameter of the
#: front that do not touch it (QuadratureOptions3D.far_degree; graded down
#: with the distance). The near-front rule (signed cones from the cell's
#: front line, near_factor) is not used: on a straight front it halved the
#: quadrature error of an exact field, on a penny crack (a/h = 8) it made K
#: scatter by 15 % (cones from cells' front lines that are not the front).
FAR_DEGREE = 6

#: Gauss points per lip facet direction for the lip terms.
LIP_POINTS = 6

#: Keep the terms of the front's curvature (module doc); False drops them
#: (straight-front auxiliary fields in each point's frame), for measuring
#: their effect.
CURVATURE_TERMS = True

#: Quadrature points per chunk of front points (bounds the memory).
CHUNK_POINTS = 400_000


@dataclasses.dataclass
class FrontPoint:
    """A point of a crack's front where K is computed, with its domains.

    Attributes:
        crack, index: crack index, index of the point along the crack's front
            (piece after piece).
        piece: the front piece (CrackGeometry3D.front piece_offsets).
        closed: whether the piece is a loop.
        s: arc length from the start of the piece; length: the piece's length.
        x: (3,) the point, on the front polyline.
        frame: (3, 3) rows e1 (propagation), e2 (normal), e3 (tangent).
        hat: the larger distance to the neighbouring front points (the hat's
            half-width); hat_before, hat_after: the distances to the previous
            and the next one (the hat is 1 at the point, 0 at both).
        curvature: the front's curvature there (1/a on a penny of radius a).
        element_size: mean edge of the front's cells within the hat.
        free_surface: the point is an end of an open piece on the part's
            boundary (a surface crack meeting a free face), not on a
            symmetry plane.
        clearance, obstacle: distance to what the domain must avoid and what.
        radius, radii: the largest domain's radius, all radii (increasing).
        requested: the radius asked for (None: the default).
        clear: False when no domain of one element fits.
        warnings: messages about this point's domains.
        symmetry: the label of the symmetry plane the point (an end) lies
            on, else None (front_sampling: its domain is mirrored).
        requested_position: the point is at a position asked for
            (Options.sif_angles, sif_angle_step, sif_arc_lengths).
        source: where its K comes from (front_sampling.SOURCES).
        K_domain: a free-surface end's own domain K (domains, 3) when its K
            is the end value (front_sampling), else None.
    """
    crack: int
    index: int
    piece: int
    closed: bool
    s: float
    length: float
    x: np.ndarray
    frame: np.ndarray
    hat: float
    curvature: float
    element_size: float
    free_surface: bool
    clearance: float
    obstacle: str
    radius: float
    radii: tuple[float, ...]
    requested: float | None
    clear: bool
    warnings: list[str] = dataclasses.field(default_factory=list)
    hat_before: float = 0.0
    hat_after: float = 0.0
    symmetry: str | None = None
    requested_position: bool = False
    source: str = "domain"
    K_domain: np.ndarray | None = None

    def __post_init__(self):
        self.hat_before = self.hat_before or self.hat
        self.hat_after = self.hat_after or self.hat

    @property
    def limited(self) -> bool:
        wanted = self.requested if self.requested else DEFAULT_ELEMENTS * self.element_size
        return self.radius < wanted * (1.0 - 1e-12)


# -- mesh helpers (cached on the model) -------------------------------------
def _cache(model) -> dict:
    return model.__dict__.setdefault("_sif3d_cache", {})


def node_tree(model) -> scipy.spatial.cKDTree:
    c = _cache(model)
    if "tree" not in c:
        c["tree"] = scipy.spatial.cKDTree(model.x)
    return c["tree"]


def node_cells(model) -> tuple[np.ndarray, np.ndarray]:
    """(offsets, cells): the cells around each node, CSR."""
    c = _cache(model)
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
    c = _cache(model)
    if "boundary_nodes" not in c:
        cells = model.cells
        faces = np.sort(np.concatenate([cells[:, [1, 2, 3]], cells[:, [0, 2, 3]], cells[:, [0, 1, 3]],
                                        cells[:, [0, 1, 2]]]), axis=1)
        _, idx, counts = np.unique(faces, axis=0, return_index=True, return_counts=True)
        one = idx[counts == 1]
        one = one[model.owned_cells_only(one % len(cells))]  # (faces are stacked face-type by face-type)
        c["boundary_nodes"] = np.unique(faces[one])
    return c["boundary_nodes"]


def _comm(model):
    """The model's communicator under MPI, else None."""
    return model.comm


def _all_points(model, points: np.ndarray) -> np.ndarray:
    """Every process's points (n, 3), without repeats, in one order (the
    points themselves in serial)."""
    comm = _comm(model)
    if comm is None:
        return points
    allp = np.concatenate(comm.allgather(np.asarray(points, dtype=float).reshape(-1, 3)))
    return np.unique(allp, axis=0) if len(allp) else allp


def _owned_segments(model, segment_cell: np.ndarray) -> np.ndarray:
    """Which front segments (by their cells, -1: none) this process
    integrates: those of its owned cells (each segment's cell is owned by
    one process; all in serial)."""
    cell = np.asarray(segment_cell)
    return (cell >= 0) & model.owned_cells_only(cell)


def lip_points(model, crack: int) -> dict:
    """The crack's lip points of the lip terms (LIP_POINTS per facet direction), computed once."""
    return model.cracks[crack].lip_points(model, LIP_POINTS)


def _owned_lip_points(model, crack: int) -> np.ndarray:
    """The lip points (n, 3) in this process's owned cells (all in serial)."""
    lp = lip_points(model, crack)
    return lp["x"][model.owned_cells_only(lp["cell"])]


# -- the front --------------------------------------------------------------
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
    c = _cache(model).setdefault("fronts", {})
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
        own = _owned_segments(model, scell)
        ssize[own] = cell_sizes(model.x, model.cells[scell[own]])
        if _comm(model) is not None:
            ssize = reduced(ssize, "SUM", _comm(model))
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


def _wrap(ds: np.ndarray, length: float, closed: bool) -> np.ndarray:
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


def hat_lengths(curvature: np.ndarray, h: float) -> np.ndarray:
    """The hat's half-width wanted where the front has these curvatures
    (element size h): HAT_CURVATURE / |kappa| clipped to [MIN_HAT_ELEMENTS h,
    HAT_ELEMENTS h]."""
    kap = np.abs(np.asarray(curvature, dtype=float))
    rho = np.where(kap > 0.0, HAT_CURVATURE / np.maximum(kap, 1e-300), np.inf)
    return np.clip(rho, MIN_HAT_ELEMENTS * h, HAT_ELEMENTS * h)


def wanted_hats(s: np.ndarray, curvature: np.ndarray, h: float, length: float, closed: bool) -> np.ndarray:
    """hat_lengths at vertices s of a piece from the largest |curvature|
    within HAT_ELEMENTS h of each (the hat a point there would span)."""
    s, kv = np.asarray(s, dtype=float), np.abs(np.asarray(curvature, dtype=float))
    ds = np.abs(s[:, None] - s[None, :])
    if closed:
        ds = np.minimum(ds, length - ds)
    kmax = np.where(ds <= HAT_ELEMENTS * h, kv[None, :], 0.0).max(axis=1)
    return hat_lengths(kmax, h)


def station_positions(s: np.ndarray, l: np.ndarray, length: float, closed: bool, minimum: int = 1) -> np.ndarray:
    """Arc lengths of front points along a piece whose vertices at s (from
    0, increasing) want half-widths l: equal steps of int ds / l (a loop
    from s = 0 round to length, an open piece with both ends)."""
    s, l = np.asarray(s, dtype=float), np.asarray(l, dtype=float)
    if closed:
        s, l = np.append(s, length), np.append(l, l[0])
    dens = 1.0 / l
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (dens[1:] + dens[:-1]) * np.diff(s))])
    if not closed and s[-1] < length:  # the last vertex short of the end
        cum = np.append(cum, cum[-1] + dens[-1] * (length - s[-1]))
        s = np.append(s, length)
    n = max(minimum, int(round(cum[-1])))
    targets = np.arange(n) * (cum[-1] / n) if closed else np.linspace(0.0, cum[-1], n + 1)
    out = np.interp(targets, cum, s)
    if not closed:
        out[0], out[-1] = 0.0, length
    return out


def symmetry_planes(model) -> list:
    """The scene's symmetry planes (cracklip.scene.symmetry.SymmetryCondition)."""
    return [bc for bc in model.scene.dirichlet if isinstance(bc, SymmetryCondition)]


def _end_plane(model, x: np.ndarray, h: float):
    """The symmetry plane a front end at x lies on (within half an element), or None."""
    for bc in symmetry_planes(model):
        if abs(float((x - np.asarray(bc.origin)) @ np.asarray(bc.normal))) <= 0.5 * h:
            return bc
    return None


def _stations(model, crack: int, spacing: float | None) -> tuple[list[dict], list[dict], list[str]]:
    """Front points along every piece (front_sampling.piece_stations): piece,
    s, closed, length, hat, hat_before, hat_after, end, end_on_boundary,
    symmetry (the label of the plane an end lies on, else None), requested;
    the requested positions between front points (piece, s, closed,
    length); notes on positions that could not be used."""
    fr = crack_front(model, crack)
    h = float(np.median(fr.segment_size)) if len(fr.segment_size) else 0.0
    opts = model.scene.options
    floor = MIN_HAT_ELEMENTS * h if not spacing else min(MIN_HAT_ELEMENTS * h, spacing)
    crk = model.cracks[crack].crack
    out, between_all, notes_all = [], [], []
    for k in range(len(fr.closed)):
        L = float(fr.length[k])
        if L <= 0.0:
            continue
        closed = bool(fr.closed[k])
        idx = np.arange(fr.offsets[k], fr.offsets[k + 1])
        sv = fr.s[idx]
        if spacing or HAT_CURVATURE <= 0.0 or len(idx) < 3:
            wanted = np.full(len(idx), spacing if spacing else HAT_ELEMENTS * h)
        else:
            wanted = wanted_hats(sv, fr.curvature[idx], h, L, closed)
        asked, notes = front_sampling.requested_positions(opts, crk, fr.x[idx], sv, L, closed, 0.5 * h)
        notes_all += [n_ for n_ in notes if n_ not in notes_all]
        svals, requested, between = front_sampling.piece_stations(sv, wanted, L, closed, floor, opts.sif_points,
                                                                  asked, 0.0 if spacing else COUNT_HAT_ELEMENTS * h)
        n = len(svals)
        if closed:
            before = (svals - np.roll(svals, 1)) % L
            after = (np.roll(svals, -1) - svals) % L
            if n == 1:
                before = after = np.array([L])
        else:
            gaps = np.diff(svals)
            before = np.concatenate([gaps[:1], gaps])
            after = np.concatenate([gaps, gaps[-1:]])
        planes = [None, None]
        if not closed:
            for e, v in enumerate((fr.offsets[k], fr.offsets[k + 1] - 1)):
                if fr.on_boundary[v]:
                    planes[e] = _end_plane(model, fr.x[v], h)
        for j, sv_ in enumerate(svals):
            end = (not closed) and (j == 0 or j == n - 1)
            on_boundary = end and bool(fr.on_boundary[fr.offsets[k] if j == 0 else fr.offsets[k + 1] - 1])
            plane = planes[0 if j == 0 else 1] if on_boundary else None
            out.append({"piece": k, "s": float(sv_), "closed": closed, "length": L,
                        "hat": float(max(before[j], after[j])), "hat_before": float(before[j]),
                        "hat_after": float(after[j]), "end": end, "end_on_boundary": on_boundary,
                        "symmetry": None if plane is None else plane.label, "requested": bool(requested[j])})
        between_all += [{"piece": k, "s": float(b), "closed": closed, "length": L} for b in between]
    return out, between_all, notes_all


def _point_at(fr: Front, piece: int, s: float) -> np.ndarray:
    idx = np.arange(fr.offsets[piece], fr.offsets[piece + 1])
    xs, ss = fr.x[idx], fr.s[idx]
    if fr.closed[piece]:
        xs = np.vstack([xs, xs[:1]])
        ss = np.concatenate([ss, [fr.length[piece]]])
    return np.array([np.interp(s, ss, xs[:, i]) for i in range(3)])


def front_points(model, crack: int, requested: float | None = None, spacing: float | None = None
                 ) -> list[FrontPoint]:
    """The front points of a crack and their SIF domains (module doc).
    requested: the largest domain's radius (None or 0: Options.sif_radius,
    else DEFAULT_ELEMENTS element sizes at each point); spacing: distance
    between front points (default HAT_ELEMENTS element sizes)."""
    if requested is not None and not (isinstance(requested, (int, float, np.floating))
                                      and math.isfinite(requested) and requested > 0.0):
        raise InputError(f"the SIF domain radius must be a finite number > 0, got {requested!r}")
    if requested is None:
        requested = model.scene.options.sif_radius or None
    fr = crack_front(model, crack)
    if fr.segments.size == 0:
        return []
    name = model.cracks[crack].crack.name
    st, _, notes = _stations(model, crack, spacing)
    if fr.unfitted is not None and np.any(fr.unfitted):
        bad = np.flatnonzero(fr.unfitted)
        notes = notes + [
            f"crack {name!r}: the triangulated surface is kinked near {len(bad)} front vertices (arc lengths "
            f"{fr.s[bad].min():.4g} .. {fr.s[bad].max():.4g}): a smooth fit through it turned the normal by up to "
            f"{fr.fit_turn[bad].max():.0f} degrees from the mesh's there (more than {FIT_TURN:g}); those vertices "
            "keep the mesh's frame and the front's own curvature, the surface's curvatures taken as 0"]
    xs = np.array([_point_at(fr, d["piece"], d["s"]) for d in st])
    pr = project(model, crack, xs)
    # The front's own segments within each hat: element size and curvature.
    seg_mid_s = 0.5 * (fr.s[fr.segments[:, 0]] + fr.s[fr.segments[:, 1]])
    seg_len = np.linalg.norm(fr.x[fr.segments[:, 1]] - fr.x[fr.segments[:, 0]], axis=1)
    # closing segment of a loop: its middle arc length
    for k in np.flatnonzero(fr.closed):
        last = fr.offsets[k + 1] - 1
        closing = np.flatnonzero((fr.segments[:, 0] == last) & (fr.segments[:, 1] == fr.offsets[k]))
        seg_mid_s[closing] = fr.s[last] + 0.5 * seg_len[closing]
    seg_piece = fr.piece[fr.segments[:, 0]]
    # Obstacles: boundary nodes near the front, other cracks' lip points.
    wanted_max = max(requested or 0.0, DEFAULT_ELEMENTS * float(fr.segment_size.max()))
    reach = wanted_max + 2.0 * max(d["hat"] for d in st) + float(fr.segment_size.max())
    bnodes = boundary_nodes(model)
    near_b = np.unique(np.concatenate([np.asarray(i, dtype=np.int64) for i in
                                       scipy.spatial.cKDTree(model.x[bnodes]).query_ball_point(fr.x, reach)]
                                      + [np.zeros(0, np.int64)])) if bnodes.size else np.zeros(0, np.int64)
    bx = _all_points(model, model.x[bnodes[near_b]])  # (every process's under MPI)
    bpr = project(model, crack, bx) if len(bx) else None
    # A symmetry plane that a piece ends on is no obstacle of that piece's
    # domains: they continue in the mirror image.
    lo, hi = model.x.min(axis=0), model.x.max(axis=0)
    if _comm(model) is not None:
        lo, hi = reduced(lo, "MIN", _comm(model)), reduced(hi, "MAX", _comm(model))
    size = float((hi - lo).max())
    mirror_of = {}
    for bc in symmetry_planes(model):
        on = np.abs((bx - np.asarray(bc.origin)) @ np.asarray(bc.normal)) <= 1e-9 * size
        pieces = {d["piece"] for d in st if d["symmetry"] == bc.label}
        mirror_of[bc.label] = (on, pieces)
    others = [ci for ci in range(len(model.cracks)) if ci != crack]
    other_pts = [(ci, np.vstack([_all_points(model, _owned_lip_points(model, ci)),
                                 np.asarray(model.geometries[ci].front["x"])])) for ci in others]
    out = []
    for k, d in enumerate(st):
        piece, s0, hat, L = d["piece"], d["s"], d["hat"], d["length"]
        xk = pr["x"][k]
        where = f"front point {k} of crack {name!r} at ({xk[0]:.6g}, {xk[1]:.6g}, {xk[2]:.6g})"
        in_hat = (seg_piece == piece) & (np.abs(_wrap(seg_mid_s - s0, L, d["closed"])) <= hat + 0.5 * seg_len)
        if not np.any(in_hat):
            in_hat = seg_piece == piece
        h = float(np.mean(fr.segment_size[in_hat]))
        wanted = float(requested) if requested else DEFAULT_ELEMENTS * h
        # The curvature of the front wherever the domain's points may project:
        # the front within its reach (the hat, the radius, an element).
        near = fr.piece == piece
        near &= np.linalg.norm(fr.x - xk, axis=1) <= hat + wanted + 2.0 * h
        kap = float(np.abs(fr.curvatures[near, :3]).max()) if np.any(near) else 0.0
        # (clearance: the largest radius clear of it, what, its distance)
        obstacles = []
        if kap > 0:
            room = min(CURVATURE_FRACTION / kap, 0.95 / kap - h)
            obstacles.append((room, f"{CURVATURE_FRACTION:g} of the smallest radius of curvature of the front and "
                                    f"the crack's surface ({1 / kap:.3g})", room))
        if bpr is not None:
            same = bpr["piece"] == piece
            ds = _wrap(bpr["s"] - s0, L, d["closed"])
            weight = np.clip(1.0 - np.abs(ds) / hat, 0.0, 1.0)
            hit = same & (weight >= 0.05)
            if d["end_on_boundary"]:  # the free surface the front meets is not an obstacle
                end_s = 0.0 if s0 == 0.0 else L
                hit &= np.abs(bpr["s"] - end_s) > h
            for on, pieces in mirror_of.values():
                if piece in pieces:
                    hit &= ~on
            if np.any(hit):
                dist = float(bpr["distance"][hit].min())
                obstacles.append((dist - h, "the boundary of the part", dist))
        for ci, pts in other_pts:
            dist = float(np.linalg.norm(pts - xk, axis=1).min())
            obstacles.append((dist - hat - h, f"crack {model.cracks[ci].crack.name!r}", dist))
        # The own front where it comes back (a thin crack): front vertices
        # off the hat whose distance is less than their arc-length distance.
        own = fr.piece == piece
        dso = np.abs(_wrap(fr.s[own] - s0, L, d["closed"]))
        dxo = np.linalg.norm(fr.x[own] - xk, axis=1)
        back = dso > hat + 2.0 * dxo
        if np.any(back):
            dist = float(dxo[back].min())
            obstacles.append((0.5 * (dist - hat), f"the opposite part of the front of crack {name!r}", dist))
        clearance, obstacle, distance = min(obstacles, key=lambda o: o[0]) if obstacles else (math.inf, "", math.inf)
        least = 2.0 * h  # the smallest domain (half the largest) spans an element
        warnings: list[str] = []
        clear = clearance >= least
        if not clear:
            radius = least
            warnings.append(f"{where}: no SIF domain of at least one element ({h:.3g}) fits between the front and "
                            f"{obstacle} ({distance:.3g} away: room for a domain of radius {max(clearance, 0.0):.3g}, "
                            f"{least:.3g} needed); K there is computed on a domain of radius {radius:.3g} that "
                            "reaches it and is NOT reliable: refine the mesh at the front (mesh.tip_h)")
        elif wanted < least:
            radius = least
            warnings.append(f"{where}: sif_radius {wanted:.3g} is below two elements ({h:.3g}) there; K uses "
                            f"domains up to radius {radius:.3g}")
        else:
            radius = min(wanted, clearance)
        radii = tuple(float(f * radius) for f in DOMAIN_FRACTIONS)
        out.append(FrontPoint(crack, k, piece, d["closed"], s0, L, xk.copy(), pr["frame"][k].copy(), hat,
                              float(pr["curvature"][k]), h, bool(d["end_on_boundary"]) and d["symmetry"] is None,
                              float(clearance), obstacle, float(radius), radii,
                              float(requested) if requested else None, clear, warnings, d["hat_before"],
                              d["hat_after"], symmetry=d["symmetry"], requested_position=d["requested"],
                              source="mirrored_domain" if d["symmetry"] else "domain"))
    if out:
        out[0].warnings[:0] = notes
    return out


# -- the integrals ----------------------------------------------------------
def _plain_rules() -> dict[int, tuple[np.ndarray, np.ndarray]]:
    return {d: (lambda r: (r["points"], r["weights"]))(_cracklip.tetrahedron_rule(d)) for d in set(PLAIN_DEGREES)}


def _quadrature(solution, crack: int, cells: np.ndarray, node_r: np.ndarray) -> dict[str, np.ndarray]:
    """Quadrature points of cells: cell, ref, x, weight, side, plain (the
    cell has no enriched node)."""
    m = solution.model
    ec, pc = split_enriched(m, cells)
    parts = []
    if ec.size:
        opts = m.scene.options.quadrature_options_3d()
        opts.degree = max(opts.degree, ENRICHED_DEGREE)
        opts.far_degree = max(opts.far_degree, FAR_DEGREE)
        q = _cracklip.compute_enriched_cell_quadrature(m.x, m.cells, m.layout, m.geometries, ec, opts)
        parts.append({"cell": q["cell"], "ref": q["ref"], "weight": q["weight"], "side": q["side"],
                      "plain": np.zeros(len(q["weight"]), dtype=bool)})
    if pc.size:
        xv = m.x[m.cells[pc]]
        diam = cell_sizes(m.x, m.cells[pc]) * 1.5
        rho = node_r[m.cells[pc]].min(axis=1) / diam
        level = np.where(rho < 1.0, 0, np.where(rho < 2.0, 1, 2))
        rules = _plain_rules()
        for lv, deg in enumerate(PLAIN_DEGREES):
            sel = level == lv
            if not np.any(sel):
                continue
            ref, w = rules[deg]
            c = pc[sel]
            e = xv[sel, 1:] - xv[sel, :1]
            detJ = np.abs(np.einsum("ci,ci->c", e[:, 0], np.cross(e[:, 1], e[:, 2])))
            parts.append({"cell": np.repeat(c, len(w)).astype(np.int32), "ref": np.tile(ref, (len(c), 1)),
                          "weight": (detJ[:, None] * w[None, :]).ravel(),
                          "side": np.zeros(len(c) * len(w), dtype=np.int8),
                          "plain": np.ones(len(c) * len(w), dtype=bool)})
    out = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    N = np.column_stack([1.0 - out["ref"].sum(axis=1), out["ref"]])
    out["x"] = np.einsum("na,nai->ni", N, m.x[m.cells[out["cell"]]])
    return out


def _frames12(pr: dict) -> np.ndarray:
    return np.ascontiguousarray(np.concatenate([pr["x"], pr["frame"].reshape(-1, 9)], axis=1))


def _shape_gradients(model, cells: np.ndarray) -> np.ndarray:
    """(c, 4, 3) gradients of the P1 shape functions of cells."""
    xv = model.x[model.cells[cells]]
    J = np.transpose(xv[:, 1:] - xv[:, :1], (0, 2, 1))
    dN = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    return np.einsum("ab,cbi->cai", dN, np.linalg.inv(J))


def _body_force(solution) -> np.ndarray | None:
    scene = solution.model.scene
    if scene.body_force is None or not np.any(scene.body_force):
        return None
    f = solution.factor(scene.body_force_group) * np.asarray(scene.body_force, dtype=float).reshape(3)
    return f if np.any(f) else None


def _node_q(nd: dict, fp: FrontPoint, radius: float) -> np.ndarray:
    """q of a front point's domain of one radius at the tube's nodes."""
    ds = _wrap(nd["s"] - fp.s, fp.length, fp.closed)
    qs = np.clip(1.0 - np.abs(ds) / np.where(ds < 0.0, fp.hat_before, fp.hat_after), 0.0, 1.0) \
        * (nd["piece"] == fp.piece)
    r_in = R_IN_FRACTION * radius
    qr = np.clip((radius - nd["r"]) / (radius - r_in), 0.0, 1.0)
    return qs * qr


def _front_rule(model, fr: Front, piece: int) -> dict[str, np.ndarray]:
    """Gauss points along a piece of the front polyline (3 per segment):
    nodes (n, 4) of their cells, shape values N (n, 4), weights (n,), e1 and
    e2 (n, 3) interpolated from the vertices' frames."""
    c = _cache(model).setdefault("front_rules", {})
    key = (id(fr), piece)
    if key in c:
        return c[key]
    mine = (fr.piece[fr.segments[:, 0]] == piece) & _owned_segments(model, fr.segment_cell)  # (summed over processes)
    seg = fr.segments[mine]
    a, b = fr.x[seg[:, 0]], fr.x[seg[:, 1]]
    g = np.array([0.5 - math.sqrt(15) / 10, 0.5, 0.5 + math.sqrt(15) / 10])
    wg = np.array([5.0, 8.0, 5.0]) / 18.0
    pts = (a[:, None, :] * (1 - g)[None, :, None] + b[:, None, :] * g[None, :, None]).reshape(-1, 3)

    def along(k: int) -> np.ndarray:
        e = (fr.frame[seg[:, 0], k][:, None, :] * (1 - g)[None, :, None]
             + fr.frame[seg[:, 1], k][:, None, :] * g[None, :, None]).reshape(-1, 3)
        return e / np.linalg.norm(e, axis=1)[:, None]
    cells = np.repeat(fr.segment_cell[mine], 3)
    xv = model.x[model.cells[cells]]
    J = np.transpose(xv[:, 1:] - xv[:, :1], (0, 2, 1))
    ref = np.linalg.solve(J, (pts - xv[:, 0])[:, :, None])[:, :, 0]
    out = {"nodes": model.cells[cells], "N": np.column_stack([1.0 - ref.sum(axis=1), ref]),
           "weight": (np.linalg.norm(b - a, axis=1)[:, None] * wg[None, :]).ravel(), "e1": along(0), "e2": along(1)}
    c[key] = out
    return out


def _front_normalisation(model, fr: Front, fp: FrontPoint, qnode_full: typing.Callable[[np.ndarray], np.ndarray]
                         ) -> tuple[np.ndarray, np.ndarray]:
    """int q (e1 . d) ds and int q (e2 . d) ds along the front polyline (3
    Gauss points per segment), d = e1 of the front point, per domain:
    qnode_full(nodes (n, 4)) gives q (n, 4, domains) at cells' nodes."""
    r = _front_rule(model, fr, fp.piece)
    q = np.einsum("na,nad->nd", r["N"], qnode_full(r["nodes"]))
    d = fp.frame[0]
    return (np.einsum("n,nd,n->d", r["weight"], q, r["e1"] @ d), np.einsum("n,nd,n->d", r["weight"], q, r["e2"] @ d))


def _domain_table(m, qn: list[np.ndarray], cells_of: list[np.ndarray], tube_index: np.ndarray
                  ) -> dict[str, np.ndarray]:
    """The cell -> front point table of the one-pass sums
    (interaction_integral_3d.h FrontDomainTable) over the cells of all
    domains: cells (c,) sorted, offsets (c + 1,), point (m,), q (m, 4,
    domains) the point's nodal q on the cell's nodes."""
    cell = np.concatenate(cells_of)
    point = np.concatenate([np.full(len(c), i, dtype=np.int32) for i, c in enumerate(cells_of)])
    q = np.empty((len(cell), 4, qn[0].shape[1]))
    start = 0
    for i, c in enumerate(cells_of):
        conn = tube_index[m.cells[c]]
        q[start:start + len(c)] = np.where(conn[:, :, None] >= 0, qn[i][np.maximum(conn, 0)], 0.0)
        start += len(c)
    order = np.argsort(cell, kind="stable")
    cell, point, q = cell[order], point[order], q[order]
    cells, counts = np.unique(cell, return_counts=True)
    return {"cells": cells, "offsets": np.concatenate([[0], np.cumsum(counts)]).astype(np.int32),
            "point": np.ascontiguousarray(point), "q": np.ascontiguousarray(q)}


def _table_part(table: dict, lo: int, hi: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """offsets, point, q of the table's cells lo .. hi - 1."""
    off = table["offsets"]
    a, b = off[lo], off[hi]
    return (np.ascontiguousarray(off[lo:hi + 1] - a, dtype=np.int32), table["point"][a:b], table["q"][a:b])


def crack_front_sifs(solution, crack: int, radius: float | None = None) -> tuple[list[FrontPoint], np.ndarray]:
    """K (num_points, num_domains, 3) at every front point of a crack on every
    domain, with the front points. One pass over the cells of all domains
    (in chunks): each quadrature point's auxiliary fields and integrands are
    computed once and summed into every front point whose domain reaches
    its cell (_cracklip.front_domain_integrals_3d). Kept on the solution
    (its _front_sifs, copies handed out); a solution that is a weighted sum
    of others of its model (Solution.combination: a load state of a growth
    step from its unit load groups) gets the weighted sum of theirs: K is
    linear in u and in the loads' factors (pressure, body force), the front
    points and their domains depend on the model only."""
    cache = getattr(solution, "_front_sifs", None)
    key = (crack, radius)
    if cache is not None and key in cache:
        return copy.deepcopy(cache[key])
    parts = getattr(solution, "combination", None)
    if parts and all(p.model is solution.model for _, p in parts):
        fps, K = _combined_front_sifs(parts, crack, radius)
    else:
        fps, K = _crack_front_sifs(solution, crack, radius)
    if cache is not None:
        cache[key] = copy.deepcopy((fps, K))
    return fps, K


def _combined_front_sifs(parts: list, crack: int, radius: float | None) -> tuple[list[FrontPoint], np.ndarray]:
    """crack_front_sifs of sum_i w_i u_i from the parts' (w_i, solution_i):
    their K (and free-surface ends' own-domain K) summed with the weights."""
    each = [crack_front_sifs(p, crack, radius) for _, p in parts]
    fps = each[0][0]
    K = sum(w * k for (w, _), (_, k) in zip(parts, each))
    for i, fp in enumerate(fps):
        if fp.K_domain is not None:
            fp.K_domain = sum(w * f[i].K_domain for (w, _), (f, _) in zip(parts, each))
    return fps, np.asarray(K, dtype=float).reshape(np.shape(each[0][1]))


def _crack_front_sifs(solution, crack: int, radius: float | None = None) -> tuple[list[FrontPoint], np.ndarray]:
    """crack_front_sifs computed (its doc)."""
    m = solution.model
    mat = m.scene.material
    E, nu = mat.E, mat.nu
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    fps = front_points(m, crack, radius)
    nd = len(DOMAIN_FRACTIONS)
    if not fps:
        return fps, np.zeros((0, nd, 3))
    fr = crack_front(m, crack)
    # The tube: nodes within the largest radius of the front (+ an element).
    rmax = max(fp.radius for fp in fps) + float(fr.segment_size.max())
    tree = node_tree(m)
    seg_len = np.linalg.norm(fr.x[fr.segments[:, 1]] - fr.x[fr.segments[:, 0]], axis=1)
    reach = rmax + 0.5 * float(seg_len.max())
    nodes = np.unique(np.concatenate([np.asarray(i, dtype=np.int64) for i in tree.query_ball_point(fr.x, reach)]))
    npr = project(m, crack, m.x[nodes])
    tube_index = -np.ones(m.x.shape[0], dtype=np.int64)
    tube_index[nodes] = np.arange(len(nodes))
    nd_ = {"s": npr["s"], "piece": npr["piece"], "r": npr["distance"]}
    node_r = np.full(m.x.shape[0], np.inf)
    node_r[nodes] = npr["distance"]
    body = _body_force(solution)
    crk = m.cracks[crack].crack
    pressure = has_lip_traction(solution, crack)
    # Per front point: its nodal q (one column per domain) and its cells.
    qn, cells_of = [], []
    for fp in fps:
        q = np.stack([_node_q(nd_, fp, r) for r in fp.radii], axis=1)
        qn.append(q)
        c = cells_of_nodes(m, nodes[q[:, -1] > 0.0])
        cells_of.append(c[m.owned_cells_only(c)])  # (under MPI the owned cells: the integrals summed below)
    table = _domain_table(m, qn, cells_of, tube_index)
    cells_all = table["cells"]
    directions = np.ascontiguousarray([fp.frame[0] for fp in fps])
    I = np.zeros((len(fps), nd, 3))
    # Chunks of cells (sorted, as the table), bounded by their quadrature points.
    per_cell = max(1, CHUNK_POINTS // 60)
    for lo in range(0, len(cells_all), per_cell):
        hi = min(lo + per_cell, len(cells_all))
        cells = cells_all[lo:hi]
        qp = _quadrature(solution, crack, cells, node_r)
        grad = _gradients(solution, qp)
        pr = project(m, crack, qp["x"])
        offsets, point, q = _table_part(table, lo, hi)
        _cracklip.front_domain_integrals_3d(
            E, nu, _frames12(pr), np.ascontiguousarray(pr["curvatures"]), np.ascontiguousarray(qp["x"]),
            np.ascontiguousarray(grad), np.ascontiguousarray(qp["side"], dtype=np.int8),
            None if body is None else tuple(body), np.ascontiguousarray(qp["weight"]),
            np.searchsorted(cells, qp["cell"]).astype(np.int32),
            np.ascontiguousarray(np.column_stack([1.0 - qp["ref"].sum(axis=1), qp["ref"]])),
            np.ascontiguousarray(_shape_gradients(m, cells)), offsets, point, q, directions, I)
    # The lip terms (subtracted): per unit q and extension (lip point, mode, l).
    lips = lip_points(m, crack)
    on = np.isin(lips["cell"], cells_all)
    lp = {k: v[on] for k, v in lips.items()}
    if len(lp["weight"]):
        values = -_lip_terms(solution, crack, lp, E, nu, lam, mu, pressure)
        _cracklip.front_domain_sums_3d(
            np.ascontiguousarray(values), np.ascontiguousarray(lp["weight"]),
            np.searchsorted(cells_all, lp["cell"]).astype(np.int32),
            np.ascontiguousarray(np.column_stack([1.0 - lp["ref"].sum(axis=1), lp["ref"]])), table["offsets"],
            table["point"], table["q"], directions, I)
    Q = np.array([_front_normalisation(m, fr, fp, lambda cn, i=i: np.where(
        (tube_index[cn] >= 0)[:, :, None], qn[i][np.maximum(tube_index[cn], 0)], 0.0)) for i, fp in enumerate(fps)])
    if _comm(m) is not None:  # each process's owned cells and front segments
        I, Q = reduced(I, "SUM", _comm(m)), reduced(Q, "SUM", _comm(m))
    K = np.zeros((len(fps), nd, 3))
    for i, fp in enumerate(fps):
        Q1, Q2 = Q[i]
        if np.any(Q1 < 0.0):
            raise InputError(f"front point {fp.index} of crack {crk.name!r} at {fp.x.round(6).tolist()}: its "
                             "direction of propagation e1 points against the front's within its hat (int q e1 . "
                             f"e1_point ds = {float(Q1.min()):.3g} < 0): the front's frames there are inconsistent")
        if np.any(Q1 == 0.0):
            raise InputError(f"front point {fp.index} of crack {crk.name!r}: its q-function vanishes along the "
                             "front (no mesh node within its hat); use a larger spacing")
        K[i] = _cracklip.front_sifs_3d(E, nu, I[i], Q1, Q2)
    K = _mirror_ends(fps, K)
    if HAT_CORRECTION:
        K = _hat_correction(fps, K)
    K = _free_surface_ends(fps, K)
    return fps, K


def _mirror_ends(fps: list[FrontPoint], K: np.ndarray) -> np.ndarray:
    """K at ends on symmetry planes on the domain and its mirror image
    (front_sampling): the hat and q of the end are symmetric about the plane,
    so the mirror adds s_m I_half to the integral of mode m and as much
    again to the normalisation int q ds: K_m = (1 + s_m) / 2 I_half / Q_half
    (K_I, K_II as on the half, K_III = 0)."""
    out = K.copy()
    for i, fp in enumerate(fps):
        if fp.symmetry is not None:
            out[i] = K[i] * 0.5 * (1.0 + front_sampling.MIRROR_SIGNS)
    return out


def _gradients(solution, qp: dict) -> np.ndarray:
    """grad u (n, 3, 3) at quadrature points: once per cell where the cell
    has no enriched node (plain P1: a constant gradient), by the enriched
    basis elsewhere."""
    plain = qp["plain"]
    grad = np.empty((len(plain), 3, 3))
    if np.any(~plain):
        _, grad[~plain] = solution._evaluate(qp["cell"][~plain], qp["ref"][~plain], qp["side"][~plain],
                                             gradient=True)
    if np.any(plain):
        cells, inverse = np.unique(qp["cell"][plain], return_inverse=True)
        centre = np.full((len(cells), 3), 0.25)
        _, g = solution._evaluate(cells, centre, np.zeros(len(cells), dtype=np.int8), gradient=True)
        grad[plain] = g[inverse]
    return grad


def _hat_correction(fps: list[FrontPoint], K: np.ndarray) -> np.ndarray:
    """K from the hat averages along each piece (HAT_CORRECTION,
    hat_deconvolve), with the mirror images of the points beyond ends on
    symmetry planes (front_sampling.mirrored_sequence: a piece between two
    planes is a loop); points at the other open ends and next to
    free-surface points keep their averages."""
    out = K.copy()
    pieces = np.array([fp.piece for fp in fps])
    for p in np.unique(pieces):
        idx = np.flatnonzero(pieces == p)
        n = len(idx)
        if fps[idx[0]].closed:
            seq, mirrored, loop = np.arange(n), np.zeros(n, dtype=bool), True
        else:
            seq, mirrored, loop = front_sampling.mirrored_sequence(n, fps[idx[0]].symmetry is not None,
                                                                   fps[idx[-1]].symmetry is not None)
        m = len(seq)
        if m < 3:
            continue
        pts = [fps[idx[j]] for j in seq]
        free = np.array([fp.free_surface for fp in pts])
        keep = np.zeros(m, dtype=bool)
        for j in range(m):
            if not loop and (j == 0 or j == m - 1):
                keep[j] = True
            elif free[(j - 1) % m] or free[(j + 1) % m]:
                keep[j] = True
        # a mirror image runs the other way: its hat's halves swap
        lm = np.array([fp.hat_after if mir else fp.hat_before for fp, mir in zip(pts, mirrored)])
        lp = np.array([fp.hat_before if mir else fp.hat_after for fp, mir in zip(pts, mirrored)])
        sign = np.where(mirrored[:, None], front_sampling.MIRROR_SIGNS[None, :], 1.0)[:, None, :]
        res = hat_deconvolve(K[idx[seq]] * sign, lm, lp, loop, keep)
        own = np.flatnonzero(~mirrored)
        out[idx[seq[own]]] = res[own]
    return out


def _free_surface_ends(fps: list[FrontPoint], K: np.ndarray) -> np.ndarray:
    """K at ends on a free surface: the end value of front_sampling.end_value
    from the piece's other points (each domain on its own), weighted by the
    front's curvature there (K kappa^(1/6) extrapolated, kappa of the conic
    through all the piece's points), the end's own domain K kept in its
    K_domain."""
    out = K.copy()
    pieces = np.array([fp.piece for fp in fps])
    for p in np.unique(pieces):
        idx = np.flatnonzero(pieces == p)
        if fps[idx[0]].closed:
            continue
        inner = np.array([i for i in idx if not fps[i].free_surface])
        for i in (idx[0], idx[-1]):
            fp = fps[i]
            if not fp.free_surface or fp.source == "end_extrapolation":
                continue
            if len(inner) < 2:
                # One interior point: its K (end_value's polynomial of degree 0) rather than the end's own domain
                # value, which belongs to the vertex singularity (on closed lips it is not even 0).
                fp.warnings.append(f"front point {fp.index} of crack {fp.crack}: the front piece has too few other "
                                   "points for an end value at the free surface (front_sampling); K there is "
                                   + ("the one interior point's" if len(inner) else
                                      "its own domain's, which depends on the mesh") + ": refine along the front "
                                   "(mesh.tip_h)")
                if not len(inner):
                    continue
            s = np.array([fps[j].s for j in inner])
            near = np.abs(s - fp.s) <= front_sampling.END_WINDOW * fp.length
            window = front_sampling.end_window(fp.length, [fp.curvature] + [fps[j].curvature for j in inner[near]])
            # The weights' curvature (front_sampling.END_SHAPE): the conic through the whole piece's points, on a
            # front curving outward.
            kappa = kappa_end = None
            if len(idx) >= 5 and np.median([fps[j].curvature for j in inner]) > 0.0:
                k = front_sampling.conic_curvatures(np.array([fps[j].x for j in idx]),
                                                    np.array([fp.x] + [fps[j].x for j in inner]))
                kappa_end, kappa = float(k[0]), k[1:]
            out[i], _ = front_sampling.end_value(s, K[inner], fp.s, window, kappa, kappa_end, fp.length)
            fp.K_domain = K[i].copy()
            fp.source = "end_extrapolation"
    return out


def hat_deconvolve(A: np.ndarray, lm: np.ndarray, lp: np.ndarray, closed: bool, keep: np.ndarray | None = None
                   ) -> np.ndarray:
    """K at the front points of a piece from their hat averages A (n, ...):
    the hat of point k (half-widths lm behind, lp ahead) averages K to K_k +
    K'_k (lp - lm) / 3 + K''_k (lp^2 - lp lm + lm^2) / 12, K' and K'' the
    differences of K at k - 1, k, k + 1 on the unequal steps; solved for K
    (one linear system per piece; equal steps l: (K_k+1 + 10 K_k + K_k-1) /
    12 = A_k).
    Points with keep (open ends, next to free-surface points) keep K = A.
    Where a point and both neighbours have equal hats the explicit K_k = A_k
    - (A_k+1 - 2 A_k + A_k-1) / 12 is used (the same to O(l^4); it passes
    point-to-point noise with a gain of 4/3 instead of 3/2: inclined penny
    at a/20, max error 0.34 % instead of 0.36 %)."""
    n = len(A)
    keep = np.zeros(n, dtype=bool) if keep is None else np.asarray(keep, dtype=bool)
    flat = np.asarray(A, dtype=float).reshape(n, -1)
    M = np.eye(n)
    rhs = flat.copy()
    for k in range(n):
        if keep[k] or (not closed and (k == 0 or k == n - 1)):
            continue
        a, c = (k - 1) % n, (k + 1) % n
        m_, p_ = lm[k], lp[k]
        hats = np.array([lm[a], lp[a], m_, p_, lm[c], lp[c]])
        if np.ptp(hats) <= 1e-9 * hats.max():
            rhs[k] = flat[k] - (flat[a] - 2.0 * flat[k] + flat[c]) / 12.0
            continue
        c1 = (p_ - m_) / 3.0
        c2 = (p_ * p_ - p_ * m_ + m_ * m_) / 12.0
        # K' ~ (m^2 (K_c - K_k) + p^2 (K_k - K_a)) / (m p (m + p)),
        # K'' ~ 2 ((K_c - K_k) / p - (K_k - K_a) / m) / (m + p)
        d1 = np.array([-p_ * p_, p_ * p_ - m_ * m_, m_ * m_]) / (m_ * p_ * (m_ + p_))
        d2 = 2.0 * np.array([1.0 / m_, -1.0 / m_ - 1.0 / p_, 1.0 / p_]) / (m_ + p_)
        row = c1 * d1 + c2 * d2
        M[k, a] += row[0]
        M[k, k] += row[1]
        M[k, c] += row[2]
    return np.linalg.solve(M, rhs).reshape(np.shape(A))


def _lip_terms(solution, crack: int, lp: dict, E: float, nu: float, lam: float, mu: float, traction: bool
               ) -> np.ndarray:
    """Per lip point (n, mode, l): the lip integrand per unit q and
    virtual-extension direction d_l, summed over the two lips, t . [grad
    u_aux]_l + t_aux . [grad u]_l - (sigma : eps_aux) n_l (t the lip's
    traction where `traction`: lip pressure, contact pressure and friction,
    lip_tractions.lip_traction; t_aux = sigma_aux n, n the outward normal of
    the lip's material; the last term vanishes on a planar crack, where
    n . d = 0): subtracted by the caller."""
    m = solution.model
    n = len(lp["weight"])
    pr = project(m, crack, lp["x"])
    fr12, curv = _frames12(pr), np.ascontiguousarray(pr["curvatures"])
    out = np.zeros((n, 3, 3))
    normal = lp["normal"]
    t_plus = lip_traction(solution, crack, lp) if traction else None   # (n, 3) on the + lip

    def stress(G: np.ndarray) -> np.ndarray:
        eps = 0.5 * (G + np.swapaxes(G, -1, -2))
        tr = np.trace(eps, axis1=-2, axis2=-1)
        return 2 * mu * eps + lam * tr[..., None, None] * np.eye(3)
    for side in (1, -1):
        sides = np.full(n, side, dtype=np.int8)
        aux = _cracklip.auxiliary_fields_3d(E, nu, fr12, curv, np.ascontiguousarray(lp["x"]), sides)
        G = aux["G"]                                              # (n, mode, i, l)
        n_out = -side * normal                                     # outward normal of the side's material
        if t_plus is not None:  # the traction on this lip: the + lip's, the - lip the opposite
            out += np.einsum("ni,nmil->nml", side * t_plus, G)
        # the auxiliary field's traction on this lip (curvature terms) times grad u there
        _, g = solution._evaluate(lp["cell"], lp["ref"], sides, gradient=True)
        ta = np.einsum("nmij,nj->nmi", stress(G), n_out)
        out += np.einsum("nmi,nil->nml", ta, g)
        # (sigma : eps_aux) n: a curved crack's lips are not along d
        W = np.einsum("nij,nmij->nm", stress(g), G)
        out -= W[:, :, None] * n_out[:, None, :]
    return out


def _with_asked_positions(model, crack: int, fps: list[FrontPoint], K: np.ndarray
                          ) -> tuple[list[FrontPoint], np.ndarray]:
    """The front points and K with the positions asked for that are not
    front points (front_sampling: K interpolated along the piece, index -1,
    source "interpolation"), in the order of pieces and arc lengths."""
    if not fps:
        return fps, K
    _, between, _ = _stations(model, crack, None)
    if not between:
        return fps, K
    fr = crack_front(model, crack)
    pieces = np.array([fp.piece for fp in fps])
    s_all = np.array([fp.s for fp in fps])
    extra, K_extra = [], []
    for d in between:
        idx = np.flatnonzero(pieces == d["piece"])
        x = _point_at(fr, d["piece"], d["s"])
        frame = project(model, crack, x[None])["frame"][0]
        near = fps[idx[np.argmin(np.abs(_wrap(s_all[idx] - d["s"], d["length"], d["closed"])))]]
        extra.append(dataclasses.replace(near, index=-1, s=d["s"], x=x, frame=frame, free_surface=False,
                                         symmetry=None, requested_position=True, source="interpolation",
                                         K_domain=None, warnings=[]))
        K_extra.append(front_sampling.interpolate(s_all[idx], K[idx], np.array([d["s"]]), d["length"],
                                                  d["closed"])[0])
    allp = fps + extra
    allK = np.concatenate([K, np.asarray(K_extra)])
    order = sorted(range(len(allp)), key=lambda i: (allp[i].piece, allp[i].s))
    return [allp[i] for i in order], allK[order]


def natural_k(solution) -> float:
    """A K that the loads could make: E' max|u| / sqrt(L) (L the part's size)."""
    m = solution.model
    size = float(np.ptp(m.x, axis=0).max())
    return m.scene.material.E_star * float(np.abs(solution.standard_displacement).max()) / math.sqrt(size)


def compute_front_sifs(solution, radius: float | None = None, cracks: typing.Sequence[int] | None = None
                       ) -> tuple[list[dict[str, typing.Any]], list[str]]:
    """K_I, K_II, K_III with their spreads at every front point of the given
    cracks (all by default), and the warnings about them. Each row has the
    keys of sif.SIF_KEYS: crack, crack_name, point, piece, s, position, x,
    y, z, parametric_angle (elliptical cracks, else None), K_I, K_II,
    K_III, K_I_spread, K_II_spread, K_III_spread, G, mode_mix_deg, radius,
    radii, radius_min, element_size, hat, curvature, limited_by,
    free_surface, domain_clear, direction (e1), normal (e2), frame [e1, e2,
    e3], K_source (front_sampling.SOURCES), requested (at a position asked
    for), symmetry (the plane of an end on one), K_domain (a free-surface
    end's own domain K_I, K_II, K_III, else None); tip, inner_radius and
    the error estimates None. Positions asked for that are not front points
    come with K interpolated (point None)."""
    m = solution.model
    mat = m.scene.material
    Ep, mu = mat.E / (1 - mat.nu ** 2), mat.E / (2 * (1 + mat.nu))
    cracks = range(len(m.cracks)) if cracks is None else cracks
    raw = []
    for ci in cracks:
        fps, K = crack_front_sifs(solution, ci, radius)
        raw.append((ci, *_with_asked_positions(m, ci, fps, K)))
    norms = [float(np.linalg.norm(K[:, -1], axis=1).max()) for _, _, K in raw if len(K)]
    nat = natural_k(solution)
    scale = max(norms + [1e-3 * nat, 1e-300])
    rows, warnings = [], []
    for ci, fps, K in raw:
        crk = m.cracks[ci].crack
        spreads = np.ptp(K, axis=1) if len(K) else np.zeros((0, 3))
        bad = [i for i, fp in enumerate(fps) if fp.clear and spreads[i].max() > SPREAD_WARNING * scale]
        for fp in fps:
            warnings += fp.warnings
        if bad:
            worst = max(bad, key=lambda i: spreads[i].max())
            fp = fps[worst]
            warnings.append(
                f"crack {crk.name!r}: K varies with the SIF domain by more than {SPREAD_WARNING * 100:g} % of the K "
                f"scale {scale:.4g} at {len(bad)} of {len(fps)} front points, up to {spreads[worst].max() / scale * 100:.2g} "
                f"% at front point {worst} (s = {fp.s:.4g}, x = ({fp.x[0]:.4g}, {fp.x[1]:.4g}, {fp.x[2]:.4g}); K_I "
                f"{', '.join(f'{v:.5g}' for v in K[worst, :, 0])} on radii "
                f"{', '.join(f'{r:.3g}' for r in fp.radii)}): the field near the front is not resolved (element "
                f"{fp.element_size:.3g}); refine the mesh at the front (mesh.tip_h) or enlarge the "
                "enrichment radius")
        for i, fp in enumerate(fps):
            kI, kII, kIII = (float(v) for v in K[i, -1])
            shear = math.hypot(kII, kIII)
            mix = math.degrees(math.atan2(shear, kI)) if math.hypot(kI, shear) > 1e-6 * nat else None
            rows.append({
                "crack": ci, "crack_name": crk.name, "point": fp.index if fp.index >= 0 else None, "piece": fp.piece,
                "s": fp.s,
                "position": fp.x.tolist(), "x": float(fp.x[0]), "y": float(fp.x[1]), "z": float(fp.x[2]),
                "parametric_angle": (float(crk.parametric_angle(fp.x[None])[0])
                                     if isinstance(crk, EllipticalCrack) else None),
                "K_I": kI, "K_II": kII, "K_III": kIII,
                "K_I_spread": float(spreads[i, 0]), "K_II_spread": float(spreads[i, 1]),
                "K_III_spread": float(spreads[i, 2]),
                "G": kI ** 2 / Ep + kII ** 2 / Ep + kIII ** 2 / (2 * mu), "mode_mix_deg": mix,
                "radius": fp.radius, "radii": list(fp.radii), "radius_min": float(min(fp.radii)),
                "element_size": fp.element_size, "hat": fp.hat,
                "curvature": fp.curvature,
                "limited_by": fp.obstacle if fp.limited or not fp.clear else None,
                "free_surface": fp.free_surface, "domain_clear": fp.clear,
                "direction": fp.frame[0].tolist(), "normal": fp.frame[1].tolist(), "frame": fp.frame.tolist(),
                "K_source": fp.source, "requested": fp.requested_position, "symmetry": fp.symmetry,
                "K_domain": None if fp.K_domain is None else fp.K_domain[-1].tolist()})
    return complete_rows(rows), warnings


__all__ = ["FrontPoint", "front_points", "crack_front_sifs", "compute_front_sifs", "DEFAULT_ELEMENTS",
           "DOMAIN_FRACTIONS", "SPREAD_WARNING"]
