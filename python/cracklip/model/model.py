"""The discrete X-FEM model of a scene: spaces, crack geometry, enrichment, constraints.

Nothing here loops over the mesh in Python: level sets, cell classes and the
enrichment layout come from the C++ kernels; Python only handles per-crack
and per-boundary arrays.
"""
from __future__ import annotations

import logging
import time

import numpy as np

import dolfinx.fem
import dolfinx.mesh

from .. import _cracklip
from ..errors import CrackGeometryError
from ..scene.crack import Crack
from ..scene.mesh import check_mesh
from ..scene.scene import Scene
from .boundary import boundary_segments
from .checks import check_model, check_pieces
from .constraints import check_rigid_motion, compute_dirichlet
from .xfem_model import CELL_CLASSES, CrackModel, XfemModel


logger = logging.getLogger(__name__)


def create_model(scene: Scene) -> XfemModel:
    """Build the discrete model: P1 space, crack geometry, enrichment,
    constraints (a tetrahedral part: model_3d.create_model_3d)."""
    if scene.mesh.gdim == 3:
        from .model_3d import create_model_3d
        return create_model_3d(scene)
    timings: dict[str, float] = {}
    msh = scene.mesh.mesh
    check_mesh(msh)
    t0 = time.perf_counter()
    V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    x, cells = _cracklip.extract_node_mesh(V._cpp_object)
    timings["space"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    cracks = [_crack_model(scene, crack, x, cells) for crack in scene.cracks]
    opts = scene.options
    try:
        layout = _cracklip.create_enrichment_layout(
            x, cells, [c.geometry for c in cracks], tip=opts.enrichment, radius=opts.radius,
            kappa=scene.material.kappa, corrected=opts.blending == "corrected")
    except RuntimeError as e:
        raise CrackGeometryError(str(e)) from None
    timings["geometry"] = time.perf_counter() - t0
    logger.info("%d cracks, %d enriched nodes on %d enriched cells", len(cracks),
                layout.num_enriched, layout.cells.size)

    t0 = time.perf_counter()
    bc_dofs, bc_values, bc_group_values = compute_dirichlet(scene, V, x, layout, [c.geometry for c in cracks])
    check_rigid_motion(x, bc_dofs[bc_dofs < x.shape[1] * x.shape[0]])
    timings["constraints"] = time.perf_counter() - t0
    model = XfemModel(scene, V, x, cells, cracks, layout, bc_dofs, bc_values, timings,
                      bc_group_values=bc_group_values)
    t0 = time.perf_counter()
    check_pieces(model)
    model.warnings = check_model(model)
    for w in model.warnings:
        logger.warning("%s", w.message)
    timings["checks"] = time.perf_counter() - t0
    return model


def _crack_model(scene: Scene, crack: Crack, x: np.ndarray, cells: np.ndarray) -> CrackModel:
    tips = _tip_flags(scene, crack)
    try:
        geometry = _cracklip.compute_crack_geometry(x, cells, crack.points, tips, scene.options.snap_tol)
    except (RuntimeError, ValueError) as e:
        raise CrackGeometryError(f"{crack.name}: {e}") from None
    classes = geometry.cell_class
    crossed = np.count_nonzero((classes == CELL_CLASSES["cut"]) | (classes == CELL_CLASSES["edge"])
                               | (classes == CELL_CLASSES["tip"]))
    if crossed == 0:
        lo, hi = x.min(axis=0), x.max(axis=0)
        raise CrackGeometryError(
            f"{crack.name} (points {crack.points.tolist()}) does not cross any cell of the mesh "
            f"(mesh bounding box [{lo[0]:g}, {hi[0]:g}] x [{lo[1]:g}, {hi[1]:g}]); "
            "check its coordinates")
    _check_off_boundary(crack, geometry, x, cells)
    if geometry.num_snapped:
        logger.info("%s: %d nodes snapped onto the crack (snap_tol=%g)", crack.name,
                    geometry.num_snapped, scene.options.snap_tol)
    return CrackModel(crack, tips, geometry)


def _check_off_boundary(crack: Crack, geometry, x: np.ndarray, cells: np.ndarray) -> None:
    """Raise if the crack runs along a boundary facet: its crack edge (the
    two nodes on the crack of an 'edge' cell) then belongs to one cell only."""
    edge_cells = np.flatnonzero(geometry.cell_class == CELL_CLASSES["edge"])
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


def _tip_flags(scene: Scene, crack: Crack) -> tuple[bool, bool]:
    """An end point is a tip when it lies inside the domain, off the boundary.

    Inside-ness is decided by ray casting against the boundary facets, so the
    cost is proportional to the boundary, not to the mesh.
    """
    a, b = boundary_segments(scene.mesh)
    scale = float(max(np.ptp(a, axis=0).max(), np.ptp(b, axis=0).max()))
    d = b - a
    flags = []
    for p in crack.points[[0, -1]]:
        t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
        dist = np.linalg.norm(a + t[:, None] * d - p, axis=1).min()
        # Horizontal ray to +x: count facets straddling y = p_y right of p.
        straddle = (a[:, 1] > p[1]) != (b[:, 1] > p[1])
        with np.errstate(divide="ignore", invalid="ignore"):
            xc = a[:, 0] + (p[1] - a[:, 1]) * d[:, 0] / d[:, 1]
        inside = np.count_nonzero(straddle & (xc > p[0])) % 2 == 1
        flags.append(bool(inside and dist > 1e-9 * scale))
    return flags[0], flags[1]
