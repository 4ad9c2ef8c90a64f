"""Stress intensity factors K_I, K_II, K_III along 3D crack fronts: the
domain interaction integral on three domains per front point, and their
spread (sif.py does the tips of 2D cracks: the geometry differs, hats along
a curved front against a disc around one point; both give rows of one
schema, sif.SIF_KEYS). The front as a curve: fracture/front.py; the front
points, their hats and domains: fracture/front_points.py; the positions
asked for and the ends' values: fracture/front_sampling.py.

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

Domains (front_points.py: their radii, clear of the boundary, other
cracks and the front's own curvature): K is computed on DOMAIN_FRACTIONS of
the largest radius; the largest gives K, the three their spread, and a
spread above SPREAD_WARNING of the K scale is warned about.

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

from .. import _cracklip
from ..errors import InputError
from ..model.checks import CodedText
from ..model.cracks.surface import split_enriched
from ..model.tip_regions import part_size
from ..scene.cell_size import cell_sizes
from ..scene.crack_surface import EllipticalCrack
from ..scene.processes import reduced
from . import front_sampling
from .front import (Front, cells_of_nodes, crack_front, lip_points, model_cache, model_comm, node_tree, owned_segments,
                    project, wrap)
from .front_points import DOMAIN_FRACTIONS, REFINE_AT_FRONT, FrontPoint, front_points, point_at, stations
from .lip_tractions import has_lip_traction, lip_traction
from .sif import K_ZERO, body_force, complete_rows, k_scale, warned_above

logger = logging.getLogger(__name__)


#: q_r is 1 up to this fraction of the domain radius, then linear to 0
#: (0: linear from the front; on a penny crack at a/h = 20 it halved the
#: scatter of K_II against 0.5).
R_IN_FRACTION = 0.0


#: K on the hat is the hat's average of K along the front: with half-widths
#: l- behind and l+ ahead, K + K' (l+ - l-) / 3 + K'' (l+^2 - l+ l- + l-^2)
#: / 12 (equal l: K + K'' l^2 / 12); K' and K'' from the neighbours'
#: averages (non-uniform differences) remove those terms (equal l: K_k -
#: (K_k+1 - 2 K_k + K_k-1) / 12) where both neighbours exist and are not
#: free-surface points.
HAT_CORRECTION = True


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


#: Quadrature points per chunk of front points (bounds the memory).
CHUNK_POINTS = 400_000


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


def _node_q(nd: dict, fp: FrontPoint, radius: float) -> np.ndarray:
    """q of a front point's domain of one radius at the tube's nodes."""
    ds = wrap(nd["s"] - fp.s, fp.length, fp.closed)
    qs = np.clip(1.0 - np.abs(ds) / np.where(ds < 0.0, fp.hat_before, fp.hat_after), 0.0, 1.0) \
        * (nd["piece"] == fp.piece)
    r_in = R_IN_FRACTION * radius
    qr = np.clip((radius - nd["r"]) / (radius - r_in), 0.0, 1.0)
    return qs * qr


def _front_rule(model, fr: Front, piece: int) -> dict[str, np.ndarray]:
    """Gauss points along a piece of the front polyline (3 per segment):
    nodes (n, 4) of their cells, shape values N (n, 4), weights (n,), e1 and
    e2 (n, 3) interpolated from the vertices' frames."""
    c = model_cache(model).setdefault("front_rules", {})
    key = (id(fr), piece)
    if key in c:
        return c[key]
    mine = (fr.piece[fr.segments[:, 0]] == piece) & owned_segments(model, fr.segment_cell)  # (summed over processes)
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
    body = body_force(solution)
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
            None if body is None else np.ascontiguousarray(body(qp["x"])), np.ascontiguousarray(qp["weight"]),
            np.searchsorted(cells, qp["cell"]).astype(np.int32),
            np.ascontiguousarray(np.column_stack([1.0 - qp["ref"].sum(axis=1), qp["ref"]])),
            np.ascontiguousarray(m.crack_type.shape_gradients(m.x, m.cells[cells])), offsets, point, q,
            directions, I)
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
    if model_comm(m) is not None:  # each process's owned cells and front segments
        I, Q = reduced(I, "SUM", model_comm(m)), reduced(Q, "SUM", model_comm(m))
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
    K = _free_surface_ends(fps, K, crk.name)
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


def _free_surface_ends(fps: list[FrontPoint], K: np.ndarray, name: str) -> np.ndarray:
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
                fp.warnings.append(CodedText(
                    f"front point {fp.index} of crack {name!r}: the front piece has too few other points for an "
                    "end value at the free surface; K there is "
                    + ("the one interior point's" if len(inner) else "its own domain's, which depends on the mesh")
                    + f": refine along the front ({REFINE_AT_FRONT})", "sif_points", fp.crack, fp.index))
                if not len(inner):
                    continue
            elif len(inner) < front_sampling.END_POINTS:
                # The quadratic goes through every interior point: no least squares, their scatter extrapolated.
                fp.warnings.append(CodedText(
                    f"front point {fp.index} of crack {name!r}: the end value at the free surface rests on "
                    f"{len(inner)} interior points (the quadratic through them; a least-squares fit wants at least "
                    f"{front_sampling.END_POINTS}): it extrapolates their scatter (a corner crack at a hole's end "
                    f"values moved 13 % on 4 to 6 front points, docs/sifs.md): refine along the front "
                    f"({REFINE_AT_FRONT})", "sif_points", fp.crack, fp.index))
            s = np.array([fps[j].s for j in inner])
            near = np.abs(s - fp.s) <= front_sampling.END_WINDOW * fp.length
            window = front_sampling.end_window(fp.length, [fp.curvature] + [fps[j].curvature for j in inner[near]])
            # The weights' curvature (front_sampling.END_SHAPE): the conic through the whole piece's points, on a
            # front curving outward.
            kappa = kappa_end = None
            if len(idx) >= 5 and np.median([fps[j].curvature for j in inner]) > 0.0:
                k = front_sampling.end_curvatures(np.array([fps[j].x for j in idx]),
                                                  np.array([fp.x] + [fps[j].x for j in inner]), K[inner])
                if k is not None:
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
    _, between, _ = stations(model, crack, None)
    if not between:
        return fps, K
    fr = crack_front(model, crack)
    pieces = np.array([fp.piece for fp in fps])
    s_all = np.array([fp.s for fp in fps])
    extra, K_extra = [], []
    for d in between:
        idx = np.flatnonzero(pieces == d["piece"])
        x = point_at(fr, d["piece"], d["s"])
        frame = project(model, crack, x[None])["frame"][0]
        near = fps[idx[np.argmin(np.abs(wrap(s_all[idx] - d["s"], d["length"], d["closed"])))]]
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
    """A K that the loads could make: E' max|u| / sqrt(L) (L the part's
    size; collective under mpirun: the whole part's, alike on every
    process)."""
    m = solution.model
    umax = float(np.abs(solution.standard_displacement).max())
    if m.distributed:
        umax = reduced(umax, "MAX", m.V.mesh.comm)
    return m.scene.material.E_star * umax / math.sqrt(part_size(m))


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
    scale = k_scale(norms, nat)
    spread_warned = warned_above(SPREAD_WARNING, scale, K_ZERO * nat)
    rows, warnings = [], []
    for ci, fps, K in raw:
        crk = m.cracks[ci].crack
        spreads = np.ptp(K, axis=1) if len(K) else np.zeros((0, 3))
        bad = [i for i, fp in enumerate(fps) if fp.clear and spreads[i].max() > spread_warned]
        for fp in fps:
            warnings += fp.warnings
        if bad:
            worst = max(bad, key=lambda i: spreads[i].max())
            fp = fps[worst]
            warnings.append(CodedText(
                f"crack {crk.name!r}: K varies with the SIF domain by more than {SPREAD_WARNING * 100:g} % of the K "
                f"scale {scale:.4g} at {len(bad)} of {len(fps)} front points, up to {spreads[worst].max() / scale * 100:.2g} "
                f"% at front point {worst} (s = {fp.s:.4g}, x = ({fp.x[0]:.4g}, {fp.x[1]:.4g}, {fp.x[2]:.4g}); K_I "
                f"{', '.join(f'{v:.5g}' for v in K[worst, :, 0])} on radii "
                f"{', '.join(f'{r:.3g}' for r in fp.radii)}): the field near the front is not resolved (element "
                f"{fp.element_size:.3g}); refine the mesh at the front ({REFINE_AT_FRONT}) or enlarge the "
                "enrichment radius (options.radius)", "sif_spread", ci))
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


__all__ = ["crack_front_sifs", "compute_front_sifs", "natural_k", "hat_deconvolve", "SPREAD_WARNING"]
