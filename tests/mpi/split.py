"""A chosen partition for the tests/mpi scripts: `--cells-below=Y` as their
first argument gives the cells whose centroid lies below y = Y to rank 1
and the others to rank 0 (on 2 processes; alone, all to rank 0), instead of DOLFINx's SCOTCH
partition, which varies from run to run. The ghosts are still cracklip's
(scene.partition.vertex_patch_partitioner): only the owners change.

    python3 tests/mpi/SCRIPT.py --cells-below=-0.12 SCENE [KEY=VALUE ...]

Used to pin a partition that once gave a wrong answer (the block under
pressure at mesh.h = 0.1 and Y = -0.12: rank 1 owns a node next to the
crack's mouth whose enriched neighbours it holds as ghosts without their
cut cells)."""
import sys

import numpy as np


def from_argv() -> None:
    """Install the partition if sys.argv[1] is --cells-below=Y (and drop it)."""
    if len(sys.argv) > 1 and sys.argv[1].startswith("--cells-below="):
        cells_below(float(sys.argv.pop(1).split("=", 1)[1]))


def cells_below(y: float) -> None:
    """Every mesh made from now on: the cells below y on rank 1, the rest on rank 0."""
    import dolfinx.cpp.graph
    import dolfinx.cpp.mesh
    import dolfinx.mesh
    create = dolfinx.mesh.create_mesh

    def create_mesh(comm, cells, x, domain, partitioner=None):
        def owners(comm_, nparts, tdim, graph, ghost_mode):
            if graph.num_nodes == 0:
                return dolfinx.cpp.graph.AdjacencyList_int32(np.zeros((0, 1), dtype=np.int32))
            below = (np.asarray(x)[np.asarray(cells)].mean(axis=1)[:, 1] < y) & (nparts > 1)
            return dolfinx.cpp.graph.AdjacencyList_int32(below.astype(np.int32).reshape(-1, 1))

        def partition(comm_, nparts, tdim, graph, ghost_mode):
            default = dolfinx.cpp.mesh.create_cell_partitioner
            dolfinx.cpp.mesh.create_cell_partitioner = lambda *a, **k: owners
            try:
                return partitioner(comm_, nparts, tdim, graph, ghost_mode)
            finally:
                dolfinx.cpp.mesh.create_cell_partitioner = default
        return create(comm, cells, x, domain, partitioner=partition)
    dolfinx.mesh.create_mesh = create_mesh
