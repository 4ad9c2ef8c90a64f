"""The discretisation error of K, and refinement to a target accuracy: 2D
tips and 3D front points alike.

K from a displacement-based solve converges as the mesh is refined. Its
error is estimated from solves of the same part on other meshes: a Level is
one mesh, with its element sizes relative to the run's (size_factor) where
it differs. With K(f) = K0 + C f^p, the K of the finer of the two finest
meshes errs by |K(f0) - K(f1)| / ((f0 / f1)^p - 1), a coarser one by its
difference from the finest plus that. The rate is not known from two
meshes: the slowest measured, ASSUMED_RATE = 1, is taken, which bounds the
error from above for every p >= 1.

2D tips (``estimate_error``): one more solve with every element size halved
within REGION_ELEMENTS element sizes of each tip (the region measured in
the mesh's own elements: the largest element within it times
REGION_ELEMENTS; and HOLE_REGION radii around a hole within it), graded
back beyond (cracklip.scene.size_field levels). The run's K then errs by at
most 2 |K_1 - K_0|. A region measured in crack lengths halved the whole
part of most scenes (the Westergaard square at h = 2/320: 54.6 s with the
estimate, 9.0 s without); one of a few elements did not see the field that
sets K (handbook cases at h = W/20, demos/error_estimate.py: a region of 4
elements left estimates at 0.04-0.9 of the error, 8 elements and more
bracket every case). A single tip has no neighbours to average over, and
its K scatters with the mesh around it (the inclined and pressurised
Griffith cracks: +0.18, +0.24, 0.00 % at sizes x 1.41, 1, 0.71): a
coarser mesh, which scatters as much, does not bound that error; a finer
one does.

3D fronts (``estimate_error``): one more solve on the similar mesh with
every size setting times RHO = sqrt(2) (h, tip_h, crack_h, the grading's
radii kept: the mesh the scene gives at those sizes; coarser: about 0.35
of the cells, so that it costs less than the run; a finer one would cost
2-3 runs; on a front coarser than FINE_FRONT of the crack size, where K is
not yet asymptotic, the finer one, 1 / RHO, and the run's K is the coarser:
its error is the difference plus the finer one's;
cracklip.scene.mesh_3d.similar_mesh; the enrichment radius and a
given SIF radius are lengths of the part and stay, the default SIF domains
are in element sizes and scale). K scatters from front point to front
point by about 0.1 % of the K scale (hats on an unstructured mesh), as much
as its error on fine meshes, and the difference of two scattered K's,
amplified by 1 / (RHO - 1) = 2.4, would be mostly scatter. So the other
mesh's K is carried to the run's front points (a cubic spline along its
front, cracklip.analysis.front_match), the difference of the two K's is
fitted by least squares along each front piece (smooth_along: a Fourier
series in the arc length on a loop, Legendre polynomials on an open piece,
as many terms as leave-one-out cross-validation chooses, at most one per
SMOOTH_POINTS points), and a point's estimate is that fit over RHO^p - 1
plus the run's scatter: the smaller of its K about K's own fit (too large
where the fit misses K's variation) and of the difference about its fit
(too large by the other mesh's scatter), the largest within NEIGHBOURS
points on either side. It is between 1 and (RHO^p - 1) / (RHO - 1) times
a smooth error (2.4 at p = 2) plus the scatter (docs/sifs.md has the
measured ratios). The difference is fitted, not each mesh's K: K varies
along an ellipse b/a = 0.5 from 0.73 to 1.03 of the K scale in the
harmonics 0, 2, 4, ..., which a Fourier series in the arc length on 17-19
points does not fit to better than 2 % (one term per four points fitted
the first harmonic only: estimates of 12-36 % for errors of 0.1-1.2 %);
the difference between two meshes is a few per cent of that and slowly
varying.

With Options.sif_smoothing = "fit" K itself is reported as its fit along
each front piece where the fit passes the check against the other mesh
(fitted_along; cracklip.fracture.front_fit): every mesh's K projected on
that fit, the error the projection's difference over RHO^p - 1 plus
FIT_SPREAD standard deviations of the fit, the computed K and its own
estimate kept beside (K_I_unsmoothed, K_I_error_unsmoothed, ...). The
fitted K's error is smooth along the front, so the estimate follows it
(the penny at a/14: 2.33 times it at every point, docs/guide.md); modes no
fit passes (an ellipse's K_I on few points) keep the estimate above.

``solve_to_accuracy``: 2D, refinement levels (every size halved within the
regions per level, about 4 times the cells there); 3D, the RHO mesh, the
scene's and similar meshes with every size times REFINE_3D = 2^(-1/2) per
level (2.8 times the cells); until every K's estimate (3D: every front
point off the free surface) is below Options.accuracy times the K scale.
From three meshes on (2D: the scene's and two refinements; 3D: the
estimate's mesh, the scene's and a refinement) the rate is observed (2D:
of each tip's K, not when the differences change sign; 3D: of the RMS of
the fits' differences along the front, not when they do not shrink; the
smallest over every three consecutive meshes, clipped to [RATE_MIN,
RATE_MAX]) and the error is SAFETY |K_L - K_L-1| / ((f_L-1 / f_L)^p - 1),
Roache's grid convergence index (J. Fluids Eng. 116, 1994: safety factor
1.25 with an observed rate); a tip's K extrapolated is K_L + (K_L -
K_L-1) / ((f_L-1 / f_L)^p - 1). A 3D .msh file cannot be made again: no
estimate (EstimateUnavailable; give the geometry).

Neither function imports the solve itself (it is passed in), so
cracklip.analysis.solve can call them.
"""
from __future__ import annotations

import dataclasses
import logging
import math
import time
import typing

import numpy as np

from ..errors import InputError, MeshError
from ..scene.mesh_3d import similar_mesh
from ..scene.refine import with_levels
from ..scene.scene import Scene
from ..scene.processes import mark_collective, reduced
from ..post.solution import point_label
from ..fracture.front_fit import fit_spread, loo_fit, piece_basis
from ..fracture.sif import K_ZERO, k_scale, warned_above
from .front_match import FrontPiece, carry_over


logger = logging.getLogger(__name__)


#: 2D: the refined region around a tip, in element sizes (the largest
#: element within it).
REGION_ELEMENTS = 20.0

#: 2D: the refined region around a hole within a tip's region: this many
#: times the hole's radius from its centre.
HOLE_REGION = 4.0

#: 3D: the estimate's mesh, every element size times this (coarser).
RHO = math.sqrt(2.0)

#: 3D: size factor per accuracy level (finer).
REFINE_3D = 1.0 / math.sqrt(2.0)

#: 3D: the estimate's mesh is the coarser one (RHO) when the front size is
#: at most this fraction of the crack size, else the finer one (1 / RHO):
#: below about a tenth K has not reached its asymptotic rate between the two
#: meshes (the penny at a/7 against a/5: estimates 0.38-1.38 times the
#: error; against a/10: 1.27-2.16), and a coarse front is cheap to refine.
#: At a/5 neither brackets (0.75-1.25 against a/7: K's rate is about 0.6
#: between a/5 and a/7, below the assumed 1); the model warns there (front
#: elements above a fifth of the crack size).
FINE_FRONT = 0.1

#: The rate of K assumed while it cannot be observed: the slowest of the
#: cases measured, so that the estimate bounds the error.
ASSUMED_RATE = 1.0

#: Safety factor on the error estimated with an observed rate (Roache's 1.25).
SAFETY = 1.25

#: An observed rate is clipped to this range (2: K with geometric
#: enrichment; 0.5: K without tip enrichment).
RATE_MIN, RATE_MAX = 0.5, 2.0

#: Along a front, a point's scatter is the largest within this many points
#: on either side (module doc).
NEIGHBOURS = 1

#: Along a front, K is fitted with at most one degree of freedom per this
#: many points of a piece, as many as leave-one-out cross-validation
#: chooses (smooth_along).
SMOOTH_POINTS = 4

#: Options.sif_smoothing = "fit": the error of a fitted K includes this
#: many standard deviations of the fit from the scatter about it.
FIT_SPREAD = 1.0

MODES = ("K_I", "K_II", "K_III")

Solver = typing.Callable[[Scene], typing.Any]


class EstimateUnavailable(InputError):
    """The error estimate needs a mesh cracklip cannot make (a 3D .msh file)."""


def scene_on(scene: Scene, mesh) -> Scene:
    """The scene on another mesh of the same part: point conditions go to the
    new mesh's node at (or nearest to) their point."""
    dirichlet = []
    for bc in scene.dirichlet:
        if isinstance(bc.where, (tuple, list, np.ndarray)) and not isinstance(bc.where, str):
            bc = dataclasses.replace(bc, where=mesh.nearest_node(bc.where))
        dirichlet.append(bc)
    return dataclasses.replace(scene, mesh=mesh, dirichlet=dirichlet)


def refined_scene(scene: Scene, regions: list, level: int) -> Scene:
    """The 2D scene with every size halved `level` times in the tips'
    regions (tip_regions): its mesh made again by its recipe, or a file's
    mesh refined. Under mpirun a file's mesh (no recipe) is refused
    (EstimateUnavailable, on every process alike): refining a distributed
    mesh read from a file is serial yet."""
    if scene.mesh.recipe is None and scene.mesh.mesh.comm.size > 1:
        raise mark_collective(EstimateUnavailable(
            "no error estimate of K and no options.accuracy under mpirun for a mesh read from a file (refining "
            "it is serial yet): run without mpirun, or let cracklip mesh the part ([mesh] kind)"))
    return scene_on(scene, with_levels(scene.mesh, level_items(regions, level)))


def similar_scene(scene: Scene, factor: float) -> Scene:
    """The 3D scene on the similar mesh with every size setting times
    `factor` (relative to the scene's mesh: cracklip.scene.mesh_3d.similar_mesh)."""
    try:
        return scene_on(scene, similar_mesh(scene.mesh, factor))
    except MeshError as e:
        raise EstimateUnavailable(f"no error estimate of K: {e}") from None


def region_radius(model, point: np.ndarray, elements: float = REGION_ELEMENTS) -> float:
    """The radius of the region `elements` element sizes around a point: D =
    elements x the largest element (mean edge) whose centroid lies within D
    (from the point's own element, grown until it holds; the part's size at
    most). Collective under mpirun: over every process's owned cells."""
    x, cells = model.x, model.cells
    distributed = model.distributed
    if distributed:
        cells = cells[:model.num_owned_cells]
    xc = x[cells]
    centroid = xc.mean(axis=1)
    k = cells.shape[1]
    size = np.mean([np.linalg.norm(xc[:, (i + 1) % k] - xc[:, i], axis=1) for i in range(k)], axis=0)
    dist = np.linalg.norm(centroid - np.asarray(point, dtype=float)[:x.shape[1]], axis=1)
    if not distributed:
        part = float(np.ptp(x, axis=0).max())
        D = elements * float(size[np.argmin(dist)])

        def largest(D: float) -> float:
            return float(size[dist <= D].max())
    else:
        comm = model.V.mesh.comm
        part = max(reduced(float(hi), "MAX", comm) - reduced(float(lo), "MIN", comm)
                   for hi, lo in zip(x.max(axis=0), x.min(axis=0)))
        i = int(np.argmin(dist)) if dist.size else -1
        D = elements * min(comm.allgather((float(dist[i]), float(size[i])) if dist.size else (np.inf, 0.0)))[1]

        def largest(D: float) -> float:
            return float(reduced(float(size[dist <= D].max(initial=0.0)), "MAX", comm))
    while D < part:
        grown = elements * largest(D)
        if grown <= D * (1.0 + 1e-9):
            break
        D = grown
    return min(D, part)


def tip_regions(solution) -> list[tuple[int, int, float, float, float]]:
    """The 2D regions refined per level: (crack, tip, x, y, D) of every tip,
    D = region_radius (REGION_ELEMENTS element sizes), and (-1, k, x, y, D)
    of every hole that comes within D of a tip: its centre, D = HOLE_REGION
    x its radius (the hole's stress concentration sets K of a crack beside
    it: for a 4 mm crack at a 10 mm hole, demos/scenes/hole_fatigue.toml,
    the tip's region alone gave an estimate of 1.1 for an error of 17.2;
    with the hole's region of 2 radii 13.6, of 4 radii 20.7, of the whole
    plate 23.8)."""
    from ..model.boundary import boundary_loops
    from ..model.tip_regions import model_boundary, segment_distance
    m = solution.model
    out = []
    for ci, cm in enumerate(m.cracks):
        for j, p in enumerate(np.asarray(cm.geometry.tips).reshape(-1, 2)):
            out.append((ci, j, float(p[0]), float(p[1]), region_radius(m, p)))
    if not out:
        return out
    a, b = model_boundary(m)
    labels, outer = boundary_loops(a, b)
    tips = list(out)
    for k, lab in enumerate(sorted(set(labels.tolist()) - {outer})):
        la, lb = a[labels == lab], b[labels == lab]
        w = np.linalg.norm(lb - la, axis=1)
        centre = (0.5 * (la + lb) * w[:, None]).sum(axis=0) / w.sum()
        radius = float(np.linalg.norm(np.concatenate([la, lb]) - centre, axis=1).max())
        if any(segment_distance(np.array([x, y]), la, lb).min() < D for (_, _, x, y, D) in tips):
            out.append((-1, k, float(centre[0]), float(centre[1]), HOLE_REGION * radius))
    return out


def level_items(regions, level: int) -> list[tuple[float, float, float, float, float, int]]:
    """The size-field levels (x, y, x, y, D, level) of the regions."""
    return [(x, y, x, y, D, level) for (_, _, x, y, D) in regions]


@dataclasses.dataclass
class Level:
    """One solve of a sequence of meshes of the part: its element sizes
    relative to the run's (2D: within the tips' regions; 3D: everywhere),
    dofs, seconds, the SIF rows of every state of its load path
    (cracklip.fracture.sif.SIF_KEYS), whether they are front points and,
    along 3D fronts, whether each (crack, piece) is a loop and its length."""
    size_factor: float
    dofs: int
    seconds: float
    rows: list[list[dict]]
    front: bool = False
    closed: dict[tuple[int, int], bool] = dataclasses.field(default_factory=dict)
    lengths: dict[tuple[int, int], float] = dataclasses.field(default_factory=dict)


def _states(solution) -> list:
    return solution.path or [solution]


def _front(solution) -> bool:
    return solution.model.crack_type.END == "front"


def _num_dofs(model) -> int:
    """The model's dofs (over every process under mpirun)."""
    if not model.distributed:
        return int(model.num_dofs)
    return int(model.dofs.num_global * model.gdim)


def level_of(solution, size_factor: float, seconds: float) -> Level:
    """The Level of a solved mesh."""
    closed, lengths = {}, {}
    if _front(solution):
        from ..fracture.front import crack_front
        for ci in range(len(solution.model.cracks)):
            fr = crack_front(solution.model, ci)
            closed.update({(ci, k): bool(c) for k, c in enumerate(fr.closed)})
            lengths.update({(ci, k): float(v) for k, v in enumerate(fr.length)})
    rows = [[dict(r) for r in st.stress_intensity_factors(None)] for st in _states(solution)]
    return Level(float(size_factor), _num_dofs(solution.model), float(seconds), rows, _front(solution), closed,
                 lengths)


def _modes(rows: list[dict]) -> tuple[str, ...]:
    return MODES if rows and rows[0].get("K_III") is not None else MODES[:2]


def _values(rows: list[dict], modes) -> np.ndarray:
    return np.array([[float(r[m]) for m in modes] for r in rows]).reshape(len(rows), len(modes))


def _same_tip(mine: list[dict], row: dict, crack: int) -> dict:
    """The row of `mine` at the tip of `row` (by position: a tip's index
    counts the crack's ends that are tips, which another mesh may count
    otherwise)."""
    if row.get("position") is None:  # rows without positions (synthetic sequences): by index
        return next(r for r in mine if r["tip"] == row["tip"])
    p = np.asarray(row["position"], dtype=float)
    scale = max(1.0, float(np.abs(p).max()))
    for r in mine:
        if np.linalg.norm(np.asarray(r["position"], dtype=float) - p) <= 1e-9 * scale:
            return r
    others = ", ".join(f"({r['position'][0]:g}, {r['position'][1]:g})" for r in mine) or "none"
    raise MeshError(f"crack {crack}: its end ({p[0]:g}, {p[1]:g}) is a tip on one of the error estimate's meshes "
                    f"and not on another (whose tips are: {others}): the end lies on the boundary within the "
                    "meshes' resolution of it; put it on or beyond the boundary (an edge crack) or clearly inside "
                    "the part")


def carried(level: Level, state: int, crack: int, rows: list[dict], modes) -> np.ndarray:
    """K (n, modes) of `level` at the points of `rows` (another level's
    points of that crack and state): the same tip in 2D, carried along the
    front in 3D (front_match)."""
    mine = [r for r in level.rows[state] if r["crack"] == crack]
    if level.front:  # rows interpolated between front points (positions asked for) are no points of it
        mine = [r for r in mine if not interpolated(r)]
    if not level.front:  # tips: one point each, the same end point of the crack on every mesh
        return np.array([[float(_same_tip(mine, r, crack)[m]) for m in modes] for r in rows]).reshape(
            len(rows), len(modes))
    values = _values(mine, modes)
    pieces = []
    for p in sorted({r["piece"] for r in mine}):
        idx = sorted((i for i, r in enumerate(mine) if r["piece"] == p), key=lambda i: mine[i]["s"])
        pieces.append(FrontPiece(np.array([mine[i]["position"] for i in idx]), values[idx],
                                 level.closed[(crack, p)]))
    return carry_over(np.array([r["position"] for r in rows]), pieces)


def _rate(values: np.ndarray, factors: np.ndarray) -> float | None:
    """The observed rate of K(f) = K0 + C f^p over three or more meshes (f
    decreasing): the smallest over every three consecutive ones (a rate
    still rising toward its asymptote is not trusted: the C(T)'s 1.3 then
    1.8), None if any three do not converge monotonically."""
    if len(values) < 3:
        return None
    rates = []
    for k in range(len(values) - 2):
        (v0, v1, v2), (f0, f1, f2) = values[k:k + 3], factors[k:k + 3]
        d1, d2 = v1 - v0, v2 - v1
        if d1 == 0.0 or d2 == 0.0 or d1 * d2 < 0.0:
            return None
        ratio = d1 / d2

        def g(p: float) -> float:
            return (f0 ** p - f1 ** p) / (f1 ** p - f2 ** p) - ratio
        lo, hi = 0.05, 8.0
        if g(lo) * g(hi) > 0.0:
            return None
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if g(lo) * g(mid) <= 0.0 else (mid, hi)
        rates.append(0.5 * (lo + hi))
    return float(min(max(min(rates), RATE_MIN), RATE_MAX))


def neighbour_max(values: np.ndarray, rows: list[dict], closed: dict[tuple[int, int], bool]) -> np.ndarray:
    """values (n, m) replaced by their largest within NEIGHBOURS points on
    either side along each front piece (a loop wraps round)."""
    out = np.array(values, dtype=float)
    keys = [(r["crack"], r["piece"]) for r in rows]
    for key in set(keys):
        idx = np.array(sorted((i for i, k in enumerate(keys) if k == key), key=lambda i: rows[i]["s"]))
        v = values[idx]
        best = v.copy()
        for shift in range(1, NEIGHBOURS + 1):
            if closed.get(key, False):
                best = np.maximum(best, np.maximum(np.roll(v, shift, axis=0), np.roll(v, -shift, axis=0)))
            else:
                best[shift:] = np.maximum(best[shift:], v[:-shift])
                best[:-shift] = np.maximum(best[:-shift], v[shift:])
        out[idx] = best
    return out


def smooth_along(rows: list[dict], values: np.ndarray, level: Level) -> np.ndarray:
    """values (n, m) at front points fitted by least squares along each piece
    (its points off the free surface): a Fourier series in the arc length on
    a loop, Legendre polynomials on an open piece, the number of terms of
    each mode chosen by leave-one-out cross-validation (front_fit.loo_fit) up to one
    per SMOOTH_POINTS points; the fit at every point. K along an ellipse b/a
    = 0.5 needs the harmonics 0, 2, 4 (K_I from 0.73 to 1.03 of its
    largest, the fourth harmonic 1 % of it) where a penny's needs the mean
    only and an inclined penny's the first: a fixed count of one term per
    four points (one harmonic on 19 points) left the ellipse's variation in
    the estimate (12-36 % of the K scale for errors of 0.1-1.2 %)."""
    out = np.array(values, dtype=float)
    for idx, use, basis, sizes in _piece_bases(rows, level, 3):
        out[idx] = loo_fit(basis, use, values[idx], sizes)[0]
    return out


def _piece_bases(rows: list[dict], level: Level, fewest: int):
    """Per front piece of rows with at least `fewest` points off the free
    surface: its rows' indices, which of them are off the free surface, the
    fit basis at them (front_fit.piece_basis, at most one term per
    SMOOTH_POINTS of those points) and the fit sizes to try."""
    keys = [(r["crack"], r["piece"]) for r in rows]
    for key in sorted(set(keys)):
        idx = np.array([i for i, k in enumerate(keys) if k == key])
        s = np.array([rows[i]["s"] for i in idx], dtype=float)
        use = ~np.array([bool(rows[i].get("free_surface")) for i in idx])
        n = int(use.sum())
        if n < fewest:
            continue
        basis, sizes = piece_basis(s, level.closed.get(key, False), level.lengths.get(key, 1.0),
                                   max(2, n // SMOOTH_POINTS))
        yield idx, use, basis, sizes


def fitted_along(rows: list[dict], K: np.ndarray, of: int, other: int, level: Level
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The fit of K along each front piece (Options.sif_smoothing = "fit"):
    K (levels, n, modes) of every mesh at the points of level `of`; per
    piece and mode, the fit of K[of] (front_fit.loo_fit: Fourier or
    Legendre, at most one term per SMOOTH_POINTS points, the size by
    leave-one-out) that passes the check against K[other] (the adjacent
    mesh: the two residuals scatter, they do not share a shape). Returns
    (every mesh's K projected on that fit's basis, the mode unchanged where
    no fit passed; the number of terms (n, modes), 0: not fitted; the fit's
    standard deviation from the scatter (n, modes), NaN where not fitted).
    Points on a free surface are not fitted and keep their K, nor are
    pieces with an end on a symmetry plane (K_III and the mirror's odd
    modes vanish there, which a Legendre fit would not keep: a quarter
    ellipse's K_III at its ends went from 0 to 3e-5)."""
    out = np.array(K, dtype=float)
    terms = np.zeros(K.shape[1:], dtype=int)
    spread = np.full(K.shape[1:], np.nan)
    for idx, use, basis, sizes in _piece_bases(rows, level, 2 * SMOOTH_POINTS):
        if any(rows[i].get("symmetry") is not None for i in idx):
            continue  # an end on a symmetry plane: K_III = 0 there by the mirror, which the basis does not keep
        _, chosen = loo_fit(basis, use, K[of][idx], sizes, other=K[other][idx])
        for m, k in enumerate(chosen):
            if k == 0:
                continue
            B = basis[use, :k]
            coef = np.linalg.lstsq(B, K[:, idx[use], m].T, rcond=None)[0]          # (k, levels)
            fitted = (basis[:, :k] @ coef).T                                     # (levels, piece points)
            out[:, idx[use], m] = fitted[:, use]
            terms[idx[use], m] = k
        spread[idx[use]] = fit_spread(basis, use, K[of][idx], chosen)[use]
    return out, terms, spread


def _front_rate(dS: list[np.ndarray], factors: np.ndarray) -> float | None:
    """The rate of the smooth K along a front over three or more similar
    meshes: from the RMS (points and modes) of the fitted differences
    between consecutive meshes (dS[k] (n, modes): mesh k + 1's K less mesh
    k's at one mesh's points), the smallest over every three, clipped to
    [RATE_MIN, RATE_MAX]; None when the differences do not shrink."""
    if len(dS) < 2:
        return None
    rates = []
    for k in range(len(dS) - 1):
        d1 = float(np.sqrt(np.mean(dS[k] ** 2)))
        d2 = float(np.sqrt(np.mean(dS[k + 1] ** 2)))
        ratio = factors[k + 1] / factors[k + 2]
        if d2 <= 0.0 or d2 >= d1 or abs(factors[k] / factors[k + 1] - ratio) > 1e-6 * ratio:
            return None
        rates.append(math.log(d1 / d2) / math.log(ratio))
    return float(min(max(min(rates), RATE_MIN), RATE_MAX))


def estimate(levels: list[Level], of: int = -1, smooth: bool = False
             ) -> dict[tuple[int, int, int], dict[str, typing.Any]]:
    """Per (state, crack, point) of level `of` (levels from coarse to fine;
    by default the finest): the estimated error of each K, the rate used
    (None: not observed, ASSUMED_RATE), K on every level at that point and
    K extrapolated (2D, an observed rate only). The finest K errs by the
    difference from the next coarser mesh over (ratio^p - 1); a coarser one
    by its difference from the finest plus that. Along a front the
    difference (every mesh's K carried to these points) is fitted along it
    (smooth_along), plus the scatter (the smaller of K's about its own fit
    and of the difference from the adjacent mesh about its fit; the largest
    within NEIGHBOURS points): the scatter is not amplified by 1 / (ratio^p
    - 1) as the differences of two scattered K would be.

    smooth (Options.sif_smoothing = "fit"): along a front, K of level `of`
    is also fitted along each piece (fitted_along), reported as
    <mode>_smoothed where a fit passed (None elsewhere), and its error is the
    same fit of every mesh's K: its difference from the next coarser mesh's
    over (ratio^p - 1), plus its difference from the finest's, plus
    FIT_SPREAD standard deviations of the fit from the scatter; modes no
    fit passed keep the estimate above."""
    mine = levels[of]
    factors = np.array([lv.size_factor for lv in levels])
    ratio = factors[-2] / factors[-1]
    rated = factors <= 1.0  # 2D: the rate from the run's mesh and finer ones (the tip regions' levels)
    out: dict[tuple[int, int, int], dict[str, typing.Any]] = {}
    for s, rows_s in enumerate(mine.rows):
        for crack in sorted({r["crack"] for r in rows_s}):
            rows = [r for r in rows_s if r["crack"] == crack]
            between = [r for r in rows if mine.front and interpolated(r)]
            rows = [r for r in rows if not (mine.front and interpolated(r))]
            modes = _modes(rows)
            K = np.stack([_values(rows, modes) if lv is mine else carried(lv, s, crack, rows, modes)
                          for lv in levels])                                       # (levels, n, modes)
            if mine.front:
                # K's differences between meshes at these points, fitted along the front
                dS = [smooth_along(rows, K[j + 1] - K[j], mine) for j in range(len(levels) - 1)]
                observed = _front_rate(dS, factors)
                p = ASSUMED_RATE if observed is None else observed
                factor = (1.0 if observed is None else SAFETY) / abs(ratio ** p - 1.0)
                # the scatter: the smaller of K's own about its fit and of the difference from the
                # adjacent mesh about its fit (each above it: by K's misfit, by the other's scatter)
                nxt = of % len(levels) + (1 if of % len(levels) < len(levels) - 1 else -1)
                D = K[nxt] - K[of]
                scatter = neighbour_max(np.minimum(np.abs(D - smooth_along(rows, D, mine)),
                                                   np.abs(K[of] - smooth_along(rows, K[of], mine))), rows, mine.closed)
                to_finest = smooth_along(rows, K[-1] - K[of], mine) if mine is not levels[-1] else 0.0 * D
                err = np.abs(dS[-1]) * factor + np.abs(to_finest) + scatter
                terms, raw = np.zeros(err.shape, dtype=int), err
                if smooth:
                    F, terms, spread = fitted_along(rows, K, of, nxt, mine)
                    fit_err = np.abs(F[-1] - F[-2]) * factor + np.abs(F[-1] - F[of]) + FIT_SPREAD * spread
                    err = np.where(terms > 0, fit_err, err)
            for i, r in enumerate(rows):
                row: dict[str, typing.Any] = {}
                for m, mode in enumerate(modes):
                    if mine.front:
                        row[f"{mode}_error"] = float(err[i, m])
                        row[f"{mode}_extrapolated"] = None
                        if smooth:
                            row[f"{mode}_smoothed"] = float(F[of, i, m]) if terms[i, m] > 0 else None
                            row[f"{mode}_error_unsmoothed"] = float(raw[i, m])
                    else:
                        observed = _rate(K[rated, i, m], factors[rated])
                        p = ASSUMED_RATE if observed is None else observed
                        factor = 1.0 / abs(ratio ** p - 1.0)
                        row[f"{mode}_error"] = ((1.0 if observed is None else SAFETY) * abs(K[-1, i, m] - K[-2, i, m])
                                                * factor + abs(K[of, i, m] - K[-1, i, m]))
                        row[f"{mode}_extrapolated"] = (None if observed is None else
                                                       float(K[-1, i, m] + (K[-1, i, m] - K[-2, i, m]) * factor))
                    row[f"{mode}_rate"] = observed
                    row[f"{mode}_levels"] = [float(v) for v in K[:, i, m]]
                out[(s, crack, point_label(r))] = row
            if between:
                out.update({(s, crack, label): v
                            for label, v in between_points(rows, [out[(s, crack, point_label(r))] for r in rows],
                                                           between, mine).items()})
    return out


def interpolated(row: dict) -> bool:
    """Whether a front row is a position asked for between front points
    (K_source "interpolation": its K a spline through the points', no
    point index) rather than a front point."""
    return row.get("point") is None and row.get("tip") is None


def between_points(rows: list[dict], est: list[dict], between: list[dict], level: Level
                   ) -> dict[int | str, dict[str, typing.Any]]:
    """The estimate at rows interpolated between front points (positions
    asked for, front_sampling) from the estimate at the points (rows, est):
    the error the larger of the two neighbouring points' along the piece
    (a spline through the errors undershoots between a large and a small
    one), K on every mesh and the fitted K by the spline the run
    interpolated K with (front_sampling.interpolate), the rate the
    neighbours'. The estimate itself is made on the points only: asked
    positions are not independent values of K, and counting them as points
    let a 5-degree sampling of a corner crack's 5-point front change its
    points' own estimates (K_I 27.4, 15.6, 27.5 against 72.7, 25.0, 72.3
    without it) and put 3.5 between 27.4 and 15.6."""
    from ..fracture.front_sampling import interpolate
    out = {}
    for key in sorted({(r["crack"], r["piece"]) for r in between}):
        idx = sorted((i for i, r in enumerate(rows) if (r["crack"], r["piece"]) == key), key=lambda i: rows[i]["s"])
        want = [r for r in between if (r["crack"], r["piece"]) == key]
        if not idx:
            continue
        sp = np.array([rows[i]["s"] for i in idx], dtype=float)
        closed, length = level.closed.get(key, False), level.lengths.get(key, 0.0)
        at = np.array([r["s"] for r in want], dtype=float)
        # the neighbouring points of every asked position (a loop wraps round)
        hi = np.searchsorted(sp, at)
        if closed:
            lo, hi = (hi - 1) % len(sp), hi % len(sp)
        else:
            lo, hi = np.clip(hi - 1, 0, len(sp) - 1), np.clip(hi, 0, len(sp) - 1)
        e0 = est[idx[0]]
        modes = [k[:-len("_error")] for k in e0 if k.endswith("_error") and not k.endswith("_error_unsmoothed")]

        def spline(values: np.ndarray) -> np.ndarray:
            return interpolate(sp, values, at, length, closed)
        cols = {}
        for mode in modes:
            cols[f"{mode}_levels"] = spline(np.array([est[i][f"{mode}_levels"] for i in idx], dtype=float))
            smoothed = [est[i].get(f"{mode}_smoothed") for i in idx]
            if any(v is not None for v in smoothed):
                # the fitted K where the fit holds, the computed K at the points it leaves (free-surface ends)
                vals = np.array([v if v is not None else rows[i][mode] for v, i in zip(smoothed, idx)], dtype=float)
                cols[f"{mode}_smoothed"] = spline(vals)
        for j, r in enumerate(want):
            a, b = est[idx[lo[j]]], est[idx[hi[j]]]
            row: dict[str, typing.Any] = {}
            for mode in modes:
                row[f"{mode}_error"] = max(a[f"{mode}_error"], b[f"{mode}_error"])
                row[f"{mode}_extrapolated"] = None
                if f"{mode}_error_unsmoothed" in a:
                    row[f"{mode}_error_unsmoothed"] = max(a[f"{mode}_error_unsmoothed"],
                                                          b[f"{mode}_error_unsmoothed"])
                    row[f"{mode}_smoothed"] = (float(cols[f"{mode}_smoothed"][j]) if f"{mode}_smoothed" in cols
                                               and (a.get(f"{mode}_smoothed") is not None
                                                    or b.get(f"{mode}_smoothed") is not None) else None)
                row[f"{mode}_rate"] = a[f"{mode}_rate"]
                row[f"{mode}_levels"] = [float(v) for v in cols[f"{mode}_levels"][j]]
            out[point_label(r)] = row
    return out


def _natural(solution) -> float:
    """A K the loads of a state could make (natural_k, 2D or 3D): its K
    scale's floor is K_ZERO of it (below it K counts as zero)."""
    if _front(solution):
        from ..fracture.sif_3d import natural_k
    else:
        from ..fracture.sif import natural_k
    return natural_k(solution)


def _scale(rows: list[dict], natural: float) -> float:
    """The K scale of a state: the largest |K| over its points, at least its
    floor (k_scale)."""
    return k_scale([math.hypot(*(float(r[m]) for m in _modes(rows))) for r in rows], natural)


def _attach(solution, levels: list[Level], est, target: float | None, method: str, of: int = -1
            ) -> dict[str, typing.Any]:
    """Put the estimate of level `of` on every state of its solution's load
    path (Solution.error_estimate, its own points each) and return the
    summary of the whole: the largest error (front points on a free surface
    left out) relative to the largest K scale, and where."""
    states = _states(solution)
    mine = levels[of]
    naturals = [_natural(st) for st in states]  # (collective under mpirun: once per state)
    scale = max(_scale(rows, nat) for rows, nat in zip(mine.rows, naturals))
    worst, where = 0.0, None
    for s, rows in enumerate(mine.rows):
        for r in rows:
            if r.get("free_surface") or (mine.front and interpolated(r)):
                continue  # (an asked position's estimate is its neighbouring points')
            e = est[(s, r["crack"], point_label(r))]
            for mode in _modes(rows):
                if e[f"{mode}_error"] > worst:
                    worst, where = e[f"{mode}_error"], {"state": s, "crack": r["crack"], "point": r["point"],
                                                        "mode": mode}
    floor = K_ZERO * max(naturals)
    summary = {"method": method, "meshes": _meshes(levels), "of_size_factor": mine.size_factor,
               "size_factors": [lv.size_factor for lv in levels], "dofs": [lv.dofs for lv in levels],
               "seconds": [lv.seconds for lv in levels],
               "refinement_levels": sum(1 for lv in levels if lv.size_factor < 1.0), "K_scale": scale,
               "K_floor": floor,
               "largest_error": worst,
               "largest_relative_error": worst / scale if scale > 0 else 0.0, "largest_at": where,
               # (every K below the floor: zero to the floor is the answer, as for the warnings)
               "target": target,
               "reached": None if target is None else bool(worst <= warned_above(target, scale, floor))}
    for i, st in enumerate(states):
        st.error_estimate = {**summary, "points": {f"{c}:{p}": v for (s, c, p), v in est.items() if s == i}}
    return summary


def _meshes(levels: list[Level]) -> str:
    """The meshes of an estimate in a few words."""
    f = [lv.size_factor for lv in levels]
    if levels[-1].front:
        return f"every element size times {[x for x in f if x != 1.0][0]:.3g}" if len(f) == 2 else \
            f"every element size times {f[0]:.3g} .. {f[-1]:.3g}"
    return (f"element sizes halved within {REGION_ELEMENTS:g} element sizes of each tip" if len(f) == 2 else
            f"element sizes times 1 .. {f[-1]:.3g} within {REGION_ELEMENTS:g} element sizes of each tip")


def _smooth(scene: Scene) -> bool:
    """Whether K along 3D fronts is reported fitted (Options.sif_smoothing)."""
    return getattr(scene.options, "sif_smoothing", "none") == "fit"


def _method(levels: list[Level], of: int, smooth: bool = False) -> str:
    if levels[-1].front and smooth:
        return ("similar meshes (every size setting times " + ", ".join(f"{lv.size_factor:.3g}" for lv in levels)
                + "); K reported fitted along each front piece (Fourier or Legendre, the size by leave-one-out, "
                "checked against the other mesh's K; options.sif_smoothing = \"fit\") where a fit passed: its error "
                "is the same fit's difference between the meshes over ratio^p - 1 plus "
                f"{FIT_SPREAD:g} standard deviation(s) of the fit; elsewhere the least-squares fit along the front "
                "of the difference over ratio^p - 1 plus the scatter; p observed over three meshes "
                f"(times a safety factor {SAFETY:g}), else {ASSUMED_RATE:g} (an upper bound for p >= 1)")
    if levels[-1].front:
        return ("similar meshes (every size setting times " + ", ".join(f"{lv.size_factor:.3g}" for lv in levels)
                + "); the error of the finest K is the least-squares fit along the front of its difference from "
                "the next coarser mesh's K over ratio^p - 1, plus the scatter (the smaller of K's and of that "
                f"difference's about their fits; the largest within {NEIGHBOURS} point(s) on either side); p observed "
                "over three meshes from the fits' differences "
                f"(times a safety factor {SAFETY:g}), else {ASSUMED_RATE:g} (an upper bound for p >= 1)")
    text = (f"refinement levels {levels[0].size_factor:g} .. {levels[-1].size_factor:g} (every element size "
            f"halved per level within {REGION_ELEMENTS:g} element sizes of each tip and {HOLE_REGION:g} radii "
            "around a hole within that)")
    if of == 0:
        return text + (f"; the error of the run's K is 2 |K_1 - K_0| (the rate {ASSUMED_RATE:g} assumed: an upper "
                       "bound for p >= 1)")
    return text + (f"; the error of the finest K is |K_L - K_L-1| / (2^p - 1), the rate p observed over three levels "
                   f"where K converges monotonically (times a safety factor {SAFETY:g}), else {ASSUMED_RATE:g} (an "
                   "upper bound for p >= 1)")


def fine_front(scene: Scene) -> bool:
    """Whether the scene's fronts are fine enough for the coarser estimate
    mesh (3D): the smallest front size asked for (mesh.tip_h; the mesh size
    without one) at most FINE_FRONT times the smallest crack size
    (cracklip.scene.mesh_3d.crack_size)."""
    from ..scene.mesh_3d import crack_size
    md = scene.mesh
    sizes = [f.h_front for f in md.front_refinements] or ([md.h * md.size_factor] if md.h else [])
    if not sizes or not scene.cracks:
        return False
    return min(sizes) <= FINE_FRONT * min(crack_size(c) for c in scene.cracks) * (1.0 + 1e-9)


def _solve_timed(solve_once: Solver, scene: Scene, factor: float) -> tuple[typing.Any, Level]:
    """Solve a scene whose element sizes are `factor` times the run's."""
    t0 = time.perf_counter()
    sol = solve_once(scene)
    return sol, level_of(sol, factor, time.perf_counter() - t0)


def estimate_error(scene: Scene, solution, solve_once: Solver) -> dict[str, typing.Any] | None:
    """One more solve (2D: sizes halved within the tips' regions; 3D: the
    similar mesh with every size times RHO): the error estimate of every K
    of `solution`, attached to it (and every state of its load path:
    Solution.error_estimate) and returned (the summary). None without a
    crack tip or front point; EstimateUnavailable on a 3D .msh file.

    scene: the Scene `solution` solved; solution: what cl.solve(scene)
    returned; solve_once: how to solve a scene on the similar mesh, a
    callable Scene -> Solution: cl.solve (or a lambda adding its
    condition_number). K's error is then in every row of
    solution.stress_intensity_factors() (K_I_error, ...): e.g.
    cl.estimate_error(scene, sol, cl.solve)."""
    base = level_of(solution, 1.0, float(solution.timings.get("total", 0.0)))
    if not any(base.rows):
        return None
    if base.front:
        factor = RHO if fine_front(scene) else 1.0 / RHO
        logger.info("estimating the discretisation error of K: one more solve, every element size times %.3g",
                    factor)
        _, aux = _solve_timed(solve_once, similar_scene(scene, factor), factor)
        levels, of = ([aux, base], -1) if factor > 1.0 else ([base, aux], 0)
    else:
        regions = tip_regions(solution)
        logger.info("estimating the discretisation error of K: one more solve, the element sizes halved within "
                    "%g elements of each tip", REGION_ELEMENTS)
        _, aux = _solve_timed(solve_once, refined_scene(scene, regions, 1), 0.5)
        levels, of = [base, aux], 0
    smooth = _smooth(scene)
    summary = _attach(solution, levels, estimate(levels, of, smooth), None, _method(levels, of, smooth), of)
    logger.info("error estimate: %d dofs (%.2f s); largest estimated error %.3g %% of the K scale", aux.dofs,
                aux.seconds, 100 * summary["largest_relative_error"])
    return summary


def solve_to_accuracy(scene: Scene, accuracy: float, max_levels: int, solve_once: Solver):
    """Solve the scene, then finer meshes level by level (2D: every size
    halved within the tips' regions per level; 3D: after the estimate's
    coarser mesh, every size times REFINE_3D per level) until the largest
    estimated error of K is below `accuracy` times the K scale or
    max_levels refinements are done; the finest solution, with
    Solution.error_estimate on every state of its load path."""
    sol, base = _solve_timed(solve_once, scene, 1.0)
    if not any(base.rows):
        logger.info("accuracy: no crack tip or front in the part, nothing to refine")
        return sol
    levels = [base]
    if base.front and fine_front(scene):  # (a coarse front: straight to the finer meshes)
        _, coarse = _solve_timed(solve_once, similar_scene(scene, RHO), RHO)
        levels.insert(0, coarse)
        summary = _attach(sol, levels, estimate(levels, smooth=_smooth(scene)), accuracy,
                          _method(levels, -1, _smooth(scene)))
        logger.info("accuracy: the scene's mesh, %d dofs, largest estimated error %.3g %% (target %.3g %%)",
                    base.dofs, 100 * summary["largest_relative_error"], 100 * accuracy)
        if summary["reached"]:
            return sol
    regions = None if base.front else tip_regions(sol)
    factor = 1.0
    for level in range(1, max_levels + 1):
        if regions is None:
            factor *= REFINE_3D
            finer = similar_scene(scene, factor)
        else:
            factor *= 0.5
            finer = refined_scene(scene, regions, level)
        sol, lv = _solve_timed(solve_once, finer, factor)
        levels.append(lv)
        summary = _attach(sol, levels, estimate(levels, smooth=_smooth(scene)), accuracy,
                          _method(levels, -1, _smooth(scene)))
        logger.info("accuracy: level %d (sizes x %.3g), %d dofs (%.2f s), largest estimated error %.3g %% "
                    "(target %.3g %%)", level, factor, lv.dofs, lv.seconds, 100 * summary["largest_relative_error"],
                    100 * accuracy)
        if summary["reached"]:
            break
    return sol


__all__ = ["estimate_error", "solve_to_accuracy", "estimate", "tip_regions", "region_radius", "similar_scene",
           "fine_front",
           "scene_on", "Level", "level_of", "EstimateUnavailable", "RHO", "REGION_ELEMENTS", "ASSUMED_RATE",
           "SAFETY"]
