"""The stress on a section of a solid part by a plane: the net-section
stress of a 3D crack (the mean stress normal to the crack's plane over the
part of the section the crack leaves intact), the 3D counterpart of the 2D
ligament stress (cracklip.analysis.life).

The section is cut from the tetrahedra exactly: every cell the plane
crosses contributes its cut polygon (a triangle or a quadrilateral, split
into triangles), and the stress is taken at each triangle's centroid in
its own cell (exact for the P1 cells, which are most of the section).
Near the front the triangles are split (SECTION_LEVELS times at most,
graded toward the front: SECTION_NEAR) so that the integrable r^(-1/2)
stress ahead of the front and the front's line are followed; one point per
triangle left the net-section stress of a corner crack in a bar 0.3-0.7 %
low at its start (a = 1.5 mm, front elements 0.05-0.2 mm), converging only
as the root of the element size. The crack's part of the section (its
level sets: psi < 0) carries no normal stress: with traction-free lips
(free_lips) the force the discrete field puts there (the lips' traction
holds weakly near the front) is counted with the ligament's; with contact,
a lip pressure or an initial stress it is left out (closed or loaded lips
carry their own share). Work: numpy over the cells the plane crosses, a
C++ evaluation at their points.
"""
from __future__ import annotations

import numpy as np

from .. import _cracklip
from ..scene.material import strain, stress
from ..scene.processes import reduced

#: The section's triangles near the front are split this many times at most
#: (net_section_stress: 4^k children each, graded toward the front).
SECTION_LEVELS = 6

#: A triangle is split when its centroid lies within this many of its own
#: (longest edge) sizes from the front.
SECTION_NEAR = 1.5


def section_triangles(x: np.ndarray, cells: np.ndarray, point: np.ndarray, normal: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
    """The section of tetrahedra (x (n, 3), cells (c, 4)) by the plane
    through `point` with unit `normal`, as triangles: corners (t, 3, 3) and
    the row of `cells` each lies in (t,)."""
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    d = (x - np.asarray(point, dtype=float)) @ n
    d = np.where(d == 0.0, 1e-300, d)  # a node on the plane counts on the + side
    dc = d[cells]
    cut = np.flatnonzero((dc.min(axis=1) < 0.0) & (dc.max(axis=1) > 0.0))
    if cut.size == 0:
        return np.zeros((0, 3, 3)), np.zeros(0, dtype=np.int64)
    edges = np.array([[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]])
    C = cells[cut]
    da, db = d[C[:, edges[:, 0]]], d[C[:, edges[:, 1]]]          # (k, 6)
    xa, xb = x[C[:, edges[:, 0]]], x[C[:, edges[:, 1]]]          # (k, 6, 3)
    crosses = (da * db) < 0.0
    t = np.where(crosses, da / np.where(crosses, da - db, 1.0), 0.0)
    P = xa + t[..., None] * (xb - xa)                            # (k, 6, 3)
    cnt = crosses.sum(axis=1)
    tris, owner = [], []
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
            tris.append(np.stack([Q[:, 0], Q[:, j], Q[:, j + 1]], axis=1))
            owner.append(cut[rows])
    return np.concatenate(tris), np.concatenate(owner)


def section_polygons(x: np.ndarray, cells: np.ndarray, point: np.ndarray, normal: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """The section of tetrahedra (x (n, 3), cells (c, 4)) by the plane
    through `point` with unit `normal`, as triangles: centroids (t, 3) and
    areas (t,)."""
    T, _ = section_triangles(x, cells, point, normal)
    return T.mean(axis=1), _areas(T)


def _areas(T: np.ndarray) -> np.ndarray:
    return 0.5 * np.linalg.norm(np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0]), axis=1)


def _split(T: np.ndarray) -> np.ndarray:
    """Each triangle (t, 3, 3) into its 4 midpoint triangles (4 t, 3, 3)."""
    m01, m12, m20 = 0.5 * (T[:, 0] + T[:, 1]), 0.5 * (T[:, 1] + T[:, 2]), 0.5 * (T[:, 2] + T[:, 0])
    return np.concatenate([np.stack(c, axis=1) for c in ((T[:, 0], m01, m20), (m01, T[:, 1], m12),
                                                          (m20, m12, T[:, 2]), (m01, m12, m20))])


def net_section_stress(solution, crack_surface, point: np.ndarray, normal: np.ndarray,
                       free_lips: bool = False) -> float:
    """The mean of sigma_nn over the section of the part by the plane
    (point, normal) outside the crack (module doc); crack_surface: the
    crack's C++ surface (model.cracks.surface.crack_surface) whose psi < 0
    marks the cracked part of the section. free_lips: the lips carry no
    traction (no contact, no lip pressure, no initial stress): the force
    the discrete field puts on the cracked part (its traction-free lips hold
    only weakly, near the front) is the ligament's, added to it. On a corner
    crack in a bar under tension (tests/test_growth_3d.py) that force was
    0.3-1.0 % of the load, and the net-section stress that much low."""
    m = solution.model
    cache = solution.__dict__.setdefault("_sections", {})
    key = (tuple(np.round(point, 12)), tuple(np.round(normal, 12)), id(crack_surface), free_lips)
    if key in cache:
        return cache[key]
    # (under mpirun each process cuts its owned cells; the sums are over every process)
    owned = np.flatnonzero(m.owned_cells_only(np.arange(len(m.cells))))
    T, which = section_triangles(m.x, m.cells[owned], point, normal)
    cell = owned[which]
    force, intact = 0.0, 0.0
    if len(T):
        T, cell, psi = _graded_near_front(T, cell, crack_surface)
        keep = psi > 0.0
        if keep.any():
            if not free_lips:
                T, cell = T[keep], cell[keep]
            cent, area = T.mean(axis=1), _areas(T)
            X = m.x[m.cells[cell]]                                            # (t, 4, 3) each triangle's cell
            J = np.transpose(X[:, 1:] - X[:, :1], (0, 2, 1))                  # columns x_j - x_0
            ref = np.linalg.solve(J, (cent - X[:, 0])[..., None])[..., 0]     # the centroid in its own cell
            _, grad = solution._evaluate(cell, ref, np.zeros(len(cell), dtype=np.int8), gradient=True)
            sig = stress(strain(grad), m.scene.material)
            nn = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
            snn = np.einsum("i,nij,j->n", nn, sig, nn)
            force, intact = float(np.sum(snn * area)), float(np.sum(area[keep] if free_lips else area))
    if m.distributed:
        force, intact = reduced(np.array([force, intact]), "SUM", m.V.mesh.comm)
    out = float(force / intact) if intact > 0.0 else 0.0
    cache[key] = out
    return out


def _graded_near_front(T: np.ndarray, cell: np.ndarray, crack_surface) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The section's triangles split (4 midpoint triangles each, at most
    SECTION_LEVELS times) where their centroid lies within SECTION_NEAR of
    their size from the front (|psi| small): the integrable r^(-1/2) stress
    ahead of the front and the front's own line, which one point per
    triangle misses. Returns the triangles, their cells and psi at their
    centroids."""
    for level in range(SECTION_LEVELS + 1):
        _, psi = _cracklip.compute_level_sets_3d(np.ascontiguousarray(T.mean(axis=1)), crack_surface)
        psi = np.asarray(psi)
        if level == SECTION_LEVELS:
            break
        size = np.max(np.linalg.norm(T - np.roll(T, 1, axis=1), axis=2), axis=1)
        near = np.abs(psi) < SECTION_NEAR * size
        if not near.any():
            break
        T = np.concatenate([T[~near], _split(T[near])])
        cell = np.concatenate([cell[~near], np.tile(cell[near], 4)])
    return T, cell, psi


__all__ = ["section_triangles", "section_polygons", "net_section_stress"]
