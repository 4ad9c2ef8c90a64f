"""A 2D crack on a triangle mesh: a polyline (scene.crack.Crack) whose ends
inside the part are tips, each a front of one point (the CrackModel of a
planar part).

The level sets, cell classes (plain, cut, edge: along mesh edges, tip,
extension), sub-triangles and crack segments come from the C++ kernels
(cpp/geometry/crack_geometry_2d); nothing here loops over the mesh in
Python. An end point is a tip when it lies inside the part, off its
boundary (ray casting against the boundary facets: cost proportional to
the boundary).
"""
from __future__ import annotations

import logging
import typing

import numpy as np

from ... import _cracklip
from ...errors import CrackGeometryError
from ...scene.options import Options
from ...scene.processes import agree, first_error, mark_collective, reduced, total, world
from ..boundary import boundary_normals, boundary_segments, inside_segments, on_boundary
from . import CrackModel, with_initial_stress

logger = logging.getLogger(__name__)


class CurveCrackModel(CrackModel):
    """A polyline crack on triangles, with its tips (module doc)."""

    DIM = 2
    #: cpp/geometry/crack_geometry_2d.h CellClass.
    CELL_CLASSES = {"plain": 0, "cut": 1, "edge": 2, "tip": 3, "extension": 4}
    CROSSED = (1, 2)
    SPLIT = (1, 2)
    END = "tip"
    EXTENT = "length"
    #: Triangles' quadrature options: the tip rules.
    QUADRATURE = Options.quadrature_options
    #: Exact for a body force and an initial stress up to degree 4 in cells
    #: without tip functions (a P1 x Heaviside gradient is piecewise
    #: constant); tip cells keep their own rules.
    LOAD_DEGREE = 4
    VOIGT = ("xx", "yy", "xy")
    #: Gauss points per crack segment of the lip loads and the SIFs' lip terms.
    LIP_POINTS = 8

    # -- the crack ------------------------------------------------------------
    def lip_samples(self, model, points: int) -> dict[str, np.ndarray]:
        """lip_points sorted by the arc length s from the crack's first point.
        Without tip enrichment the tip cell holds no crack (the discrete
        crack ends at its edge) and is left out."""
        pts = dict(_cracklip.compute_lip_points(model.x, model.cells, self.geometry, int(points)))
        if model.scene.options.enrichment == "none":
            keep = ~np.isin(pts["cell"], np.asarray(self.geometry.tip_cells["cell"]))
            pts = {k: v[keep] for k, v in pts.items()}
        s = arc_length(self.crack.points, pts["x"]) if len(pts["cell"]) else np.zeros(0)
        o = np.argsort(s, kind="stable")
        out = {k: v[o] for k, v in pts.items()}
        out["s"] = s[o]
        return out

    def ends_inside(self) -> bool:
        return any(self.tips)

    @staticmethod
    def slip(jump: np.ndarray, normal: np.ndarray) -> np.ndarray:
        tangent = np.stack([normal[:, 1], -normal[:, 0]], axis=1)
        return np.einsum("ij,ij->i", jump, tangent)

    # -- construction ---------------------------------------------------------
    @classmethod
    def check_scene(cls, scene) -> None:
        """Cracks that cross or overlap (a junction) stop with the scene keys
        and the place, before the enrichment finds a cell cut twice."""
        for i, j, where in crossings([c.points for c in scene.cracks]):
            raise CrackGeometryError(
                f"cracks[{i}] ({scene.cracks[i].name}) and cracks[{j}] ({scene.cracks[j].name}) "
                f"{where}: crossing, branching or overlapping cracks (junctions) are not supported; "
                "end one crack short of the other (by a few elements) or join them into one polyline")

    @classmethod
    def create(cls, scene, crack, x: np.ndarray, cells: np.ndarray) -> "CurveCrackModel":
        tips = tip_flags(scene, crack)
        try:
            geometry = _cracklip.compute_crack_geometry(x, cells, crack.points, tips, scene.options.snap_tol)
        except (RuntimeError, ValueError) as e:
            raise CrackGeometryError(f"{crack.name}: {e}") from None
        classes = geometry.cell_class
        C = cls.CELL_CLASSES
        crossed = total(np.count_nonzero((classes == C["cut"]) | (classes == C["edge"]) | (classes == C["tip"])))
        if crossed == 0:
            lo, hi = x.min(axis=0), x.max(axis=0)
            if world().size > 1:  # the part's box, not this process's
                lo, hi = reduced(lo, "MIN"), reduced(hi, "MAX")
            raise mark_collective(CrackGeometryError(  # (found alike on every process: printed once)
                f"{crack.name} (points {crack.points.tolist()}) does not cross any cell of the mesh "
                f"(mesh bounding box [{lo[0]:g}, {hi[0]:g}] x [{lo[1]:g}, {hi[1]:g}]); "
                "check its coordinates"))
        # On several processes each checks its owned cells (whose neighbours it holds).
        owned = scene.mesh.mesh.topology.index_map(scene.mesh.mesh.topology.dim).size_local
        agree(first_error([lambda: _check_off_boundary(crack, geometry, x, cells, owned)]))
        if geometry.num_snapped:
            logger.info("%s: %d nodes snapped onto the crack (options.snap_tol = %g)", crack.name,
                        geometry.num_snapped, scene.options.snap_tol)
        return cls(crack, tips, geometry)

    @classmethod
    def check_model(cls, model) -> list:
        from ..checks import check_pieces, check_tips
        check_pieces(model)
        return check_tips(model)

    # -- the kernels of triangles ---------------------------------------------
    @classmethod
    def cell_measures(cls, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
        xv = x[cells]
        e1, e2 = xv[:, 1] - xv[:, 0], xv[:, 2] - xv[:, 0]
        return 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])

    @classmethod
    def shape_gradients(cls, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
        xv = x[cells]
        e1, e2 = xv[:, 1] - xv[:, 0], xv[:, 2] - xv[:, 0]
        det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
        inv = np.stack([np.stack([e2[:, 1], -e2[:, 0]], axis=1), np.stack([-e1[:, 1], e1[:, 0]], axis=1)],
                       axis=1) / det[:, None, None]  # rows of J^-T: (c, 2 (xi, eta), 2 (x, y))
        return np.stack([-inv[:, 0] - inv[:, 1], inv[:, 0], inv[:, 1]], axis=1)

    @classmethod
    def cell_rule(cls, degree: int) -> tuple[np.ndarray, np.ndarray]:
        if degree <= 1:
            return np.full((1, 3), 1.0 / 3.0), np.ones(1)
        # Strang-Fix / Dunavant 6-point rule, degree 4.
        a, b = 0.445948490915965, 0.091576213509771
        wa, wb = 0.223381589678011, 0.109951743655322
        pts = np.array([[a, a, 1 - 2 * a], [a, 1 - 2 * a, a], [1 - 2 * a, a, a],
                        [b, b, 1 - 2 * b], [b, 1 - 2 * b, b], [1 - 2 * b, b, b]])
        return pts, np.array([wa, wa, wa, wb, wb, wb])

    @classmethod
    def facet_normals(cls, model, where, basis: dict) -> np.ndarray:
        """Outward unit normals at a facet basis' points of a tag (the
        nearest facet's: model.boundary.boundary_normals)."""
        cache = model.__dict__.setdefault("_normals_cache", {})
        if where not in cache:
            cache[where] = boundary_normals(model.scene.mesh, where)
        return cache[where](basis["points"])

    @classmethod
    def enriched_cell_points(cls, model, cells: np.ndarray, degree: int) -> dict[str, np.ndarray]:
        return cls.field_points(model, np.zeros(model.num_dofs), cells, degree)

    @classmethod
    def field_points(cls, model, u: np.ndarray, cells: np.ndarray | None, degree: int | None) -> dict[str, np.ndarray]:
        """The stiffness's rules on the cells (C++ compute_field_points; no
        cells: all), Gauss degree at least `degree` in cells without tip
        functions."""
        cell_list = np.zeros(0, dtype=np.int32) if cells is None else np.asarray(cells, dtype=np.int32)
        return _cracklip.compute_field_points(model.x, model.cells, model.layout, model.geometries, u, cell_list,
                                              cls.quadrature_options(model.scene.options, degree))

    @classmethod
    def subcell_fields(cls, solution) -> dict[str, typing.Any]:
        """Sub-triangles (points (3 C, 2), three per sub-triangle: cells =
        (C, 3) consecutive) with the displacement at their vertices on their
        own side and the stress xx, yy, xy at their centroids (the total
        stress C eps(u) + sigma_0 with an initial stress; von_mises with
        sigma_zz = Material.sigma_zz_ratio (xx + yy)), side, parent (C++
        compute_subcell_fields)."""
        m = solution.model
        mat = m.scene.material
        f = _cracklip.compute_subcell_fields(m.x, m.cells, m.layout, m.geometries, solution.u,
                                             mat.E_strain, mat.nu_strain)
        f["stress"] = with_initial_stress(solution, f["stress"], lambda: f["points"].reshape(-1, 3, 2).mean(axis=1))
        f["cells"] = np.arange(f["points"].shape[0], dtype=np.int64).reshape(-1, 3)
        f["von_mises"] = von_mises(f["stress"], mat.sigma_zz_ratio)
        return f


def von_mises(stress: np.ndarray, zz_ratio: float) -> np.ndarray:
    """von Mises stress of (n, 3) xx, yy, xy stresses with sigma_zz = zz_ratio
    (xx + yy) (Material.sigma_zz_ratio: nu in plane strain, 0 in plane stress)."""
    sxx, syy, sxy = stress[:, 0], stress[:, 1], stress[:, 2]
    szz = zz_ratio * (sxx + syy)
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxy ** 2)


def arc_length(points: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Arc length along a polyline (k, 2), from its first point, of the
    projections of points x (n, 2) onto it."""
    d = np.diff(points, axis=0)
    L = np.linalg.norm(d, axis=1)
    cum = np.concatenate([[0.0], np.cumsum(L)])
    rel = x[:, None, :] - points[None, :-1, :]
    t = np.clip(np.einsum("nki,ki->nk", rel, d) / (L ** 2)[None], 0.0, 1.0)
    dist = np.linalg.norm(rel - t[..., None] * d[None], axis=2)
    k = np.argmin(dist, axis=1)
    return cum[k] + t[np.arange(len(x)), k] * L[k]


def _check_off_boundary(crack, geometry, x: np.ndarray, cells: np.ndarray, num_owned: int) -> None:
    """Raise if the crack runs along a boundary facet: its crack edge (the
    two nodes on the crack of an 'edge' cell) then belongs to one cell only.
    Edge cells below num_owned are checked (all in serial)."""
    edge_cells = np.flatnonzero(geometry.cell_class[:num_owned] == CurveCrackModel.CELL_CLASSES["edge"])
    if edge_cells.size == 0:
        return
    cc = cells[edge_cells]
    on = geometry.phi[cc] == 0.0
    pairs = np.sort(np.where(on, cc, -1), axis=1)[:, 1:]  # the two nodes with phi = 0
    near = cells[np.count_nonzero(np.isin(cells, np.unique(pairs)), axis=1) >= 2]
    count: dict[tuple[int, int], int] = {}
    for e in np.sort(near[:, [[0, 1], [1, 2], [2, 0]]], axis=2).reshape(-1, 2).tolist():
        count[tuple(e)] = count.get(tuple(e), 0) + 1
    for a, b in pairs.tolist():
        if count.get((a, b), 0) == 1:
            raise CrackGeometryError(
                f"{crack.name} runs along the domain boundary from {x[a].tolist()} to {x[b].tolist()} "
                "(a boundary facet); a crack must lie inside the domain: move it off the boundary or "
                "shorten it")


def crossings(polylines: list[np.ndarray]):
    """(i, j, 'cross at (x, y)' or 'overlap at (x, y)') for every pair of
    polylines whose segments meet (2D)."""
    for i in range(len(polylines)):
        for j in range(i + 1, len(polylines)):
            P, Q = np.asarray(polylines[i], dtype=float), np.asarray(polylines[j], dtype=float)
            scale = float(np.ptp(np.concatenate([P, Q]), axis=0).max()) or 1.0
            if np.any(P.min(axis=0) > Q.max(axis=0) + 1e-12 * scale) or \
                    np.any(Q.min(axis=0) > P.max(axis=0) + 1e-12 * scale):
                continue
            hit = _meet(P, Q, 1e-12 * scale)
            if hit is not None:
                yield i, j, hit


def _meet(P: np.ndarray, Q: np.ndarray, tol: float) -> str | None:
    for p0, p1 in zip(P[:-1], P[1:]):
        d = p1 - p0
        for q0, q1 in zip(Q[:-1], Q[1:]):
            e = q1 - q0
            den = d[0] * e[1] - d[1] * e[0]
            w = q0 - p0
            if abs(den) > tol * (np.linalg.norm(d) + np.linalg.norm(e)):
                t = (w[0] * e[1] - w[1] * e[0]) / den
                u = (w[0] * d[1] - w[1] * d[0]) / den
                if -1e-12 <= t <= 1 + 1e-12 and -1e-12 <= u <= 1 + 1e-12:
                    x = p0 + t * d
                    return f"cross at ({x[0]:.6g}, {x[1]:.6g})"
            elif abs(w[0] * d[1] - w[1] * d[0]) <= tol * np.linalg.norm(d):  # collinear
                L2 = float(np.dot(d, d))
                lo, hi = sorted((float(np.dot(q0 - p0, d)) / L2, float(np.dot(q1 - p0, d)) / L2))
                a, b = max(lo, 0.0), min(hi, 1.0)
                if b >= a:
                    x = p0 + 0.5 * (a + b) * d
                    return f"overlap at ({x[0]:.6g}, {x[1]:.6g})"
    return None


def tip_flags(scene, crack) -> tuple[bool, bool]:
    """An end point is a tip when it lies inside the domain, off the boundary.

    Inside-ness is decided by ray casting against the boundary facets, so the
    cost is proportional to the boundary, not to the mesh. "Off the
    boundary" allows for a curved boundary's facets being chords
    (boundary.boundary_tolerance): an end on a hole's circle lies up to
    the sagitta inside the meshed part, and is the mouth of an edge crack
    on every mesh, not a tip on some (a tip a sagitta from the hole).
    """
    a, b = boundary_segments(scene.mesh)
    scale = float(max(np.ptp(a, axis=0).max(), np.ptp(b, axis=0).max()))
    return tuple(bool(inside_segments(p, a, b) and not on_boundary(p, a, b, scale))
                 for p in crack.points[[0, -1]])


__all__ = ["CurveCrackModel", "arc_length", "crossings", "tip_flags", "von_mises"]
