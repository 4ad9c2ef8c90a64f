"""The discrete X-FEM model of a scene: spaces, cracks on the mesh, enrichment,
constraints, model checks; one ``create_model`` for triangles and tetrahedra.

The crack geometry is the one thing that differs between a planar and a
solid part, and it comes through one interface (cracklip.model.cracks:
a curve with tips on triangles, a surface with fronts on tetrahedra).
Nothing here loops over the mesh in Python: level sets, cell classes and
the enrichment layout come from the C++ kernels; Python only handles
per-crack and per-boundary arrays.
"""
from __future__ import annotations

import logging
import time

import dolfinx.fem
import numpy as np

from .. import _cracklip
from ..errors import CrackGeometryError
from ..scene.mesh import check_mesh
from ..scene.processes import total
from ..scene.scene import Scene
from .checks import check_units
from .constraints import check_point_supports, check_rigid_motion, compute_dirichlet
from .cracks import CrackModel, crack_model_type
from .distributed import create_dof_map
from .symmetry import check_symmetry
from .xfem_model import XfemModel


logger = logging.getLogger(__name__)


def _create_crack(kind, scene: Scene, i: int, x: np.ndarray, cells: np.ndarray) -> CrackModel:
    """The model of scene.cracks[i]; a geometry error names the scene key
    (cracks[i]) beside the crack's name, as the scene file's errors do."""
    crack = scene.cracks[i]
    try:
        return kind.create(scene, crack, x, cells)
    except CrackGeometryError as e:  # (the same error, its marks kept: under mpirun it may be collective)
        msg = str(e)
        if msg.startswith(f"{crack.name}: "):
            msg = msg[len(crack.name) + 2:]
        e.args = (f"cracks[{i}] ({crack.name}): {msg}",)
        raise


def create_model(scene: Scene) -> XfemModel:
    """Build the discrete model of a scene (a planar part of triangles or a
    solid of tetrahedra): P1 space, the cracks on the mesh, enrichment,
    constraints; then the model checks (errors raise, warnings go to
    model.warnings).

    Under mpirun (issue 40) this builds one process's part of a
    distributed model (model.distributed: the global numbering of its
    dofs), and every scene option runs on it: open cracks in 2D and 3D
    under any load, symmetry planes, crack-lip contact (frictionless and
    with Coulomb friction), load paths and a life's load levels, by the
    direct solver (also nodally rescaled) or the iterative one. What does
    not run on several processes yet is refused, collectively and by
    name, where it is checked: a crack without a tip inside the part
    (checks.check_pieces), `cracklip check --nodes`, the condition
    number."""
    timings: dict[str, float] = {}
    msh = scene.mesh.mesh
    check_mesh(msh)
    kind = crack_model_type(scene.mesh.gdim)
    kind.check_scene(scene)
    t0 = time.perf_counter()
    V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    x, cells = _cracklip.extract_node_mesh(V._cpp_object)
    timings["space"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    cracks = [_create_crack(kind, scene, i, x, cells) for i in range(len(scene.cracks))]
    try:
        layout = kind.enrichment_layout(scene, x, cells, cracks)
    except RuntimeError as e:
        raise CrackGeometryError(str(e)) from None
    timings["geometry"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    bc_dofs, bc_values, bc_group_values = compute_dirichlet(scene, V, x, layout, [c.geometry for c in cracks])
    check_rigid_motion(x, bc_dofs[bc_dofs < x.shape[1] * x.shape[0]], msh.comm)
    timings["constraints"] = time.perf_counter() - t0
    model = XfemModel(scene, V, x, cells, cracks, layout, bc_dofs, bc_values, timings,
                      bc_group_values=bc_group_values)
    if msh.comm.size > 1:  # one process's part: the global numbering of its dofs (model.distributed)
        model.num_owned_cells = msh.topology.index_map(msh.topology.dim).size_local
        model.dofs = create_dof_map(V, cells, layout, model.num_owned_cells)
    logger.info("%d cracks, %d enriched pseudo-nodes on %d enriched cells", len(cracks), *enriched_counts(model))
    t0 = time.perf_counter()
    check_symmetry(model)
    check_point_supports(model)
    model.warnings = kind.check_model(model) + check_units(model)  # raises on what makes the model unusable
    for w in model.warnings:
        logger.warning("%s", w.message)
    timings["checks"] = time.perf_counter() - t0
    return model


def enriched_counts(model: XfemModel) -> tuple[int, int]:
    """(enriched pseudo-nodes, enriched cells) of the whole model: under
    mpirun every process's owned ones summed (collective; a process's layout
    also holds its ghosts'), the layout's in serial."""
    layout = model.layout
    if not model.distributed:
        return int(layout.num_enriched), int(layout.cells.size)
    own_nodes = model.V.dofmap.index_map.size_local
    comm = model.V.mesh.comm
    return (total(np.count_nonzero(np.asarray(layout.node) < own_nodes), comm),
            total(np.count_nonzero(np.asarray(layout.cells) < model.num_owned_cells), comm))


__all__ = ["create_model", "XfemModel", "CrackModel"]
