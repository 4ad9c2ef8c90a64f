"""The stress on a section of a solid part by a plane: the net-section
stress of a 3D crack (the mean stress normal to the crack's plane over the
part of the section the crack leaves intact), the 3D counterpart of the 2D
ligament stress (cracklip.analysis.life).

The section is cut from the tetrahedra exactly: every cell the plane
crosses contributes its cut polygon (a triangle or a quadrilateral, split
into triangles), and the stress is taken at each triangle's centroid
(exact for the P1 cells, which are most of the section; one point of the
enriched field in the cells next to the crack). Points on the crack itself
(its level sets: psi < 0 within a cell of the surface) are left out: the
crack carries no normal stress (with contact the closed lips do, and the
section then over-counts the ligament's share; documented where used).
Work: numpy over the cells the plane crosses, a C++ evaluation at their
points.
"""
from __future__ import annotations

import numpy as np

from .. import _cracklip
from ..scene.material import strain, stress
from ..scene.processes import reduced


def section_polygons(x: np.ndarray, cells: np.ndarray, point: np.ndarray, normal: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """The section of tetrahedra (x (n, 3), cells (c, 4)) by the plane
    through `point` with unit `normal`, as triangles: centroids (t, 3) and
    areas (t,)."""
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    d = (x - np.asarray(point, dtype=float)) @ n
    d = np.where(d == 0.0, 1e-300, d)  # a node on the plane counts on the + side
    dc = d[cells]
    cut = np.flatnonzero((dc.min(axis=1) < 0.0) & (dc.max(axis=1) > 0.0))
    if cut.size == 0:
        return np.zeros((0, 3)), np.zeros(0)
    edges = np.array([[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]])
    C = cells[cut]
    da, db = d[C[:, edges[:, 0]]], d[C[:, edges[:, 1]]]          # (k, 6)
    xa, xb = x[C[:, edges[:, 0]]], x[C[:, edges[:, 1]]]          # (k, 6, 3)
    crosses = (da * db) < 0.0
    t = np.where(crosses, da / np.where(crosses, da - db, 1.0), 0.0)
    P = xa + t[..., None] * (xb - xa)                            # (k, 6, 3)
    cnt = crosses.sum(axis=1)
    cents, areas = [], []
    for k in (3, 4):
        rows = np.flatnonzero(cnt == k)
        if rows.size == 0:
            continue
        idx = np.argsort(~crosses[rows], axis=1, kind="stable")[:, :k]
        Q = np.take_along_axis(P[rows], idx[..., None], axis=1)  # (r, k, 3) the polygon's corners
        c = Q.mean(axis=1)
        # Order the corners by angle about the centroid in the plane.
        e1 = Q[:, 0] - c
        e1 /= np.maximum(np.linalg.norm(e1, axis=1), 1e-300)[:, None]
        e2 = np.cross(n[None], e1)
        ang = np.arctan2(np.einsum("rki,ri->rk", Q - c[:, None], e2), np.einsum("rki,ri->rk", Q - c[:, None], e1))
        Q = np.take_along_axis(Q, np.argsort(ang, axis=1)[..., None], axis=1)
        for j in range(1, k - 1):  # a fan from corner 0
            a, b, cc = Q[:, 0], Q[:, j], Q[:, j + 1]
            cents.append((a + b + cc) / 3.0)
            areas.append(0.5 * np.linalg.norm(np.cross(b - a, cc - a), axis=1))
    return np.concatenate(cents), np.concatenate(areas)


def net_section_stress(solution, crack_surface, point: np.ndarray, normal: np.ndarray) -> float:
    """The mean of sigma_nn over the section of the part by the plane
    (point, normal) outside the crack (module doc); crack_surface: the
    crack's C++ surface (model.cracks.surface.crack_surface) whose psi < 0
    marks the cracked part of the section."""
    m = solution.model
    cache = solution.__dict__.setdefault("_sections", {})
    key = (tuple(np.round(point, 12)), tuple(np.round(normal, 12)), id(crack_surface))
    if key in cache:
        return cache[key]
    # (under mpirun each process cuts its owned cells; the sums are over every process)
    cent, area = section_polygons(m.x, m.cells[m.owned_cells_only(np.arange(len(m.cells)))], point, normal)
    force, intact = 0.0, 0.0
    if area.size:
        _, psi = _cracklip.compute_level_sets_3d(np.ascontiguousarray(cent), crack_surface)
        keep = np.asarray(psi) > 0.0
        if keep.any():
            grad = solution.displacement_gradient(cent[keep])
            sig = stress(strain(grad), m.scene.material)
            nn = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
            snn = np.einsum("i,nij,j->n", nn, sig, nn)
            force, intact = float(np.sum(snn * area[keep])), float(np.sum(area[keep]))
    if m.distributed:
        force, intact = reduced(np.array([force, intact]), "SUM", m.V.mesh.comm)
    out = float(force / intact) if intact > 0.0 else 0.0
    cache[key] = out
    return out


__all__ = ["section_polygons", "net_section_stress"]
