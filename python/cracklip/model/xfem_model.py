"""The discrete X-FEM model of a scene as data: the spaces, the cracks on the
mesh, the enrichment layout and the constraints (2D and 3D alike;
model.create_model builds it)."""
from __future__ import annotations

import dataclasses
import functools
import typing

import numpy as np

import dolfinx.fem

from ..scene.cell_size import mean_cell_size
from ..scene.scene import Scene
from .cracks import CrackModel, crack_model_type


@dataclasses.dataclass
class XfemModel:
    """Discrete model of a scene.

    Attributes:
        scene: the input scene.
        V: DOLFINx P1 vector space (standard dofs, block size d = 2 or 3).
        x: (num_nodes, d) node (dof block) coordinates.
        cells: (num_cells, d + 1) node indices per cell.
        cracks: every crack on the mesh (cracks.CrackModel, of crack_type).
        layout: enriched pseudo-nodes and cells (_cracklip.EnrichmentLayout).
        bc_dofs: constrained scalar dofs (standard dofs only), sorted.
        bc_values: prescribed values at bc_dofs.
        bc_group_values: the prescribed values of each load group at bc_dofs
            (Dirichlet.group): bc_values is their sum.
        timings: seconds per phase.
        warnings: the model checks' findings (checks.ModelWarning).
    """
    scene: Scene
    V: dolfinx.fem.FunctionSpace
    x: np.ndarray
    cells: np.ndarray
    cracks: list[CrackModel]
    layout: typing.Any
    bc_dofs: np.ndarray
    bc_values: np.ndarray
    timings: dict[str, float]
    warnings: list = dataclasses.field(default_factory=list)
    bc_group_values: dict = dataclasses.field(default_factory=dict)
    #: Under MPI (model.distributed): the owned cells, first in `cells`, and
    #: the global numbering of the local dofs; None in serial.
    num_owned_cells: int | None = None
    dofs: typing.Any = None

    @property
    def distributed(self) -> bool:
        """Whether the model is one process's part of a model on several."""
        return self.num_owned_cells is not None

    @property
    def comm(self):
        """The communicator a collective step reduces over: the mesh's under
        MPI (model.distributed), None in serial (scene.processes.reduced
        and on_all take None as one process)."""
        return self.V.mesh.comm if self.distributed else None

    def owned_cells_only(self, cells: np.ndarray) -> np.ndarray:
        """Which of these local cells this process integrates: all in serial,
        its owned ones under MPI (each cell is owned by one process)."""
        cells = np.asarray(cells)
        return np.ones(cells.shape, dtype=bool) if self.num_owned_cells is None else cells < self.num_owned_cells

    @property
    def gdim(self) -> int:
        """The space dimension (2: triangles, 3: tetrahedra), also the block size."""
        return self.x.shape[1]

    @property
    def crack_type(self) -> type[CrackModel]:
        """The CrackModel implementation of the mesh's dimension: the crack
        geometry and the kernels of its cells (also without cracks)."""
        return crack_model_type(self.gdim)

    @property
    def num_dofs(self) -> int:
        return self.gdim * self.layout.num_nodes_total

    @property
    def geometries(self) -> list:
        return [c.geometry for c in self.cracks]

    @functools.cached_property
    def h(self) -> float:
        """Mean edge length of the mesh (every cell's edges; computed once per
        model: scene/cell_size.mean_cell_size). Under MPI collective: over every
        process's owned cells."""
        if not self.distributed:
            return mean_cell_size(self.x, self.cells)
        own = self.cells[:self.num_owned_cells]
        comm = self.V.mesh.comm
        total, count = comm.allreduce(np.array([mean_cell_size(self.x, own) * len(own), len(own)]))
        return float(total / count) if count else 0.0
