"""The discrete X-FEM model of a scene as data: the spaces, the cracks on the
mesh, the enrichment layout and the constraints (2D and 3D alike; model.py
and model_3d.py build it)."""
from __future__ import annotations

import dataclasses
import functools
import typing

import numpy as np

import dolfinx.fem

from ..scene.scene import Scene


#: Cell classes of CrackGeometry.cell_class (see cpp/geometry/crack_geometry_2d.h).
CELL_CLASSES = {"plain": 0, "cut": 1, "edge": 2, "tip": 3, "extension": 4}


@dataclasses.dataclass
class CrackModel:
    """One crack on the mesh: its description (a polyline in 2D, a surface in
    3D), which ends are tips (2D; empty in 3D), its geometry
    (_cracklip.CrackGeometry or CrackGeometry3D)."""
    crack: typing.Any
    tips: tuple[bool, ...]
    geometry: typing.Any


@dataclasses.dataclass
class XfemModel:
    """Discrete model of a scene.

    Attributes:
        scene: the input scene.
        V: DOLFINx P1 vector space (standard dofs, block size 2).
        x: (num_nodes, 2) node (dof block) coordinates.
        cells: (num_cells, 3) node indices per cell.
        cracks: per-crack geometry.
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

    @property
    def gdim(self) -> int:
        """The space dimension (2: triangles, 3: tetrahedra), also the block size."""
        return self.x.shape[1]

    @property
    def num_dofs(self) -> int:
        return self.gdim * self.layout.num_nodes_total

    @property
    def geometries(self) -> list:
        return [c.geometry for c in self.cracks]

    @functools.cached_property
    def h(self) -> float:
        """Mean edge length of the mesh (every cell's edges; computed once per
        model: 0.05 s at 2e6 triangles)."""
        if self.gdim == 2:  # as before, bit for bit
            x, y = np.ascontiguousarray(self.x[:, 0]), np.ascontiguousarray(self.x[:, 1])
            total = 0.0
            for a, b in ((0, 1), (1, 2), (2, 0)):
                i, j = self.cells[:, a], self.cells[:, b]
                total += float(np.hypot(x[j] - x[i], y[j] - y[i]).sum())
            return total / (3 * len(self.cells)) if len(self.cells) else 0.0
        pairs = [(a, b) for a in range(4) for b in range(a + 1, 4)]
        total = sum(float(np.linalg.norm(self.x[self.cells[:, b]] - self.x[self.cells[:, a]], axis=1).sum())
                    for a, b in pairs)
        return total / (len(pairs) * len(self.cells)) if len(self.cells) else 0.0
