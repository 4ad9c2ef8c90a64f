"""The discrete X-FEM model of a tetrahedral part: P1 space, crack surfaces
on the mesh (level sets, cut cells, lip facets, the front), enrichment,
constraints.

As in 2D, nothing here loops over the mesh in Python: the level sets, cell
classes, sub-tetrahedra, front and enrichment come from the C++ kernels
(cpp/geometry/crack_geometry_3d, cpp/enrichment/enrichment_layout_3d).
"""
from __future__ import annotations

import logging
import time

import numpy as np

import dolfinx.fem

from .. import _cracklip
from ..errors import CrackGeometryError, InputError
from ..scene.crack_surface import EllipticalCrack, PolygonCrack, SurfaceCrack
from ..scene.mesh_3d import check_mesh_3d
from ..scene.scene import Scene
from .checks_3d import check_model_3d
from .constraints import check_rigid_motion, compute_dirichlet
from .xfem_model import CrackModel, XfemModel

logger = logging.getLogger(__name__)


def crack_surface(crack) -> "_cracklip.CrackSurface3D":
    """The C++ surface of a crack description."""
    label = crack.name or "crack"
    try:
        if isinstance(crack, EllipticalCrack):
            return _cracklip.create_ellipse_crack(crack.center, crack.normal, crack.axis, crack.a, crack.b)
        if isinstance(crack, PolygonCrack):
            # The C++ polygon is counter-clockwise seen from the + side: the
            # order PolygonCrack's normal (Newell's, right-handed) follows.
            return _cracklip.create_polygon_crack(crack.points)
        if isinstance(crack, SurfaceCrack):
            return _cracklip.create_triangulated_crack(crack.vertices, crack.triangles)
    except (ValueError, RuntimeError) as e:
        raise CrackGeometryError(f"{label}: {e}") from None
    raise CrackGeometryError(f"{label}: not a 3D crack surface ({type(crack).__name__})")


def _crack_model(scene: Scene, crack, x: np.ndarray, cells: np.ndarray) -> CrackModel:
    surface = crack_surface(crack)
    try:
        geometry = _cracklip.compute_crack_geometry_3d(x, cells, surface, scene.options.snap_tol)
    except ValueError as e:
        raise CrackGeometryError(f"{crack.name}: {e}") from None
    except RuntimeError as e:
        raise CrackGeometryError(f"{crack.name}: {e}") from None
    if geometry.num_snapped:
        logger.info("%s: %d nodes snapped onto the crack (snap_tol=%g)", crack.name, geometry.num_snapped,
                    scene.options.snap_tol)
    return CrackModel(crack, (), geometry)


def create_model_3d(scene: Scene) -> XfemModel:
    """Build the discrete model of a tetrahedral part (module doc)."""
    timings: dict[str, float] = {}
    msh = scene.mesh.mesh
    check_mesh_3d(msh)
    if scene.material.plane != "strain":
        raise InputError("material.plane is a 2D setting: a 3D part is plain elasticity (leave plane = 'strain')")
    t0 = time.perf_counter()
    V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    x, cells = _cracklip.extract_node_mesh(V._cpp_object)
    timings["space"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    cracks = [_crack_model(scene, crack, x, cells) for crack in scene.cracks]
    opts = scene.options
    try:
        layout = _cracklip.create_enrichment_layout_3d(
            x, cells, [c.geometry for c in cracks], front=opts.enrichment, radius=opts.radius,
            kappa=3.0 - 4.0 * scene.material.nu, corrected=opts.blending == "corrected")
    except RuntimeError as e:
        raise CrackGeometryError(str(e)) from None
    timings["geometry"] = time.perf_counter() - t0
    logger.info("%d cracks, %d enriched pseudo-nodes on %d enriched cells", len(cracks), layout.num_enriched,
                layout.cells.size)

    t0 = time.perf_counter()
    bc_dofs, bc_values, bc_group_values = compute_dirichlet(scene, V, x, layout, [c.geometry for c in cracks])
    check_rigid_motion(x, bc_dofs[bc_dofs < 3 * x.shape[0]])
    timings["constraints"] = time.perf_counter() - t0
    model = XfemModel(scene, V, x, cells, cracks, layout, bc_dofs, bc_values, timings,
                      bc_group_values=bc_group_values)
    t0 = time.perf_counter()
    model.warnings = check_model_3d(model)  # raises on a broken front or a radius that reaches no node
    for w in model.warnings:
        logger.warning("%s", w.message)
    timings["checks"] = time.perf_counter() - t0
    return model


__all__ = ["create_model_3d", "crack_surface"]
