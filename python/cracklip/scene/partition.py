"""The mesh's cells over MPI processes, with vertex patches: every process
also holds (as ghosts) every cell that shares a vertex with one of its own
(in 3D also the next layer: RINGS).

X-FEM decides per node from the node's whole patch of cells (is the node's
support cut by the crack, does it hold a tip, which pieces of its support
lie on either side). DOLFINx 0.5.2 ghosts only the cells across a facet
(GhostMode.shared_facet; shared_vertex is refused), so an owned node at the
edge of a process's cells may see part of its patch only. A cell
partitioner may return ghost destinations too (DOLFINx's
CellPartitionFunction: the owner first, then the processes that ghost the
cell): ``vertex_patch_partitioner`` takes the owners from DOLFINx's own
partitioner (SCOTCH on the dual graph), then adds as ghost destinations of
a cell every process that owns a cell sharing one of its vertices. Then
every owned node's patch is whole on its process
(``incomplete_patches`` counts the exceptions; 0 is asserted by the tests).

It works on meshes given on rank 0 (cracklip meshes there: gmsh runs once).
"""
from __future__ import annotations

import numpy as np

#: Layers of cells around a process's own cells that it holds as ghosts, per
#: cell dimension: 1 = the vertex patches of its cells' nodes. A 3D node's
#: front enrichment also depends on cells further out: a node of an
#: extension cell is a core node when another node of that cell lies on a
#: cut cell (cpp/enrichment/crack_enrichment_3d.cpp), and a node next to a
#: core node carries the blending ramp. So a node of an own cell (layer 0)
#: needs its neighbour's patch (layer 2) and whether that patch's nodes lie
#: on cut cells (layer 3). With one layer, 1-3 nodes of a 2-process penny
#: (21617 cells) were enriched differently by two processes; with two, a
#: blending node of the bench penny (a/h = 8, radius 2 h) was, in 1 of 7
#: runs (the run refused: model/distributed.py checks every run); with
#: three, none in 8. Likewise a surface crack's node (surface_crack_growth,
#: mesh.refine[0].h = 1.0, 4176 cells): with two, 5 of 16 runs refused;
#: with three, none of 14.
RINGS = {2: 1, 3: 3}


def vertex_patch_partitioner(comm, nparts: int, tdim: int, cells, ghost_mode):
    """A DOLFINx cell partitioner (the signature of
    dolfinx.mesh.create_mesh's `partitioner`): owners by DOLFINx's default,
    ghosts by shared vertices. Collective; the cells must all be on rank 0."""
    import dolfinx.cpp.graph
    import dolfinx.cpp.mesh
    import scipy.sparse
    if comm.allreduce(cells.num_nodes if comm.rank != 0 else 0) != 0:
        raise ValueError("vertex_patch_partitioner: the cells must all be given on rank 0")
    default = dolfinx.cpp.mesh.create_cell_partitioner()
    owners = default(comm, nparts, tdim, cells, dolfinx.cpp.mesh.GhostMode.none)
    n = cells.num_nodes
    if n == 0:
        return dolfinx.cpp.graph.AdjacencyList_int32(np.zeros((0, 1), dtype=np.int32))
    owner = np.asarray(owners.array, dtype=np.int32)
    assert owner.size == n, "one owner per cell"
    c = np.asarray(cells.array, dtype=np.int64).reshape(n, -1)
    num_vertices = int(c.max()) + 1
    ones = np.ones(c.size, dtype=np.int8)
    # cell -> vertex incidence (n x V), cell -> owner (n x P): the processes
    # owning a cell at each vertex (V x P), then at each cell's vertices (n x P).
    cv = scipy.sparse.csr_matrix((ones, (np.repeat(np.arange(n), c.shape[1]), c.ravel())), shape=(n, num_vertices))
    cp = scipy.sparse.csr_matrix((np.ones(n, dtype=np.int8), (np.arange(n), owner)), shape=(n, nparts))
    reach = cp
    for _ in range(RINGS[tdim]):  # (0/1 entries: bool products)
        reach = (cv @ (cv.T @ reach)).astype(bool).astype(np.int8)
    reach = reach.tocsr()
    reach.sum_duplicates()
    reach.sort_indices()
    # Each cell's row: its owner first, then the other processes reaching it (ascending).
    rows = np.repeat(np.arange(n), np.diff(reach.indptr))
    others = reach.indices != owner[rows]
    r = rows[others]
    k = np.bincount(r, minlength=n)
    offsets = np.zeros(n + 1, dtype=np.int32)
    np.cumsum(1 + k, out=offsets[1:])
    dest = np.empty(offsets[-1], dtype=np.int32)
    dest[offsets[:-1]] = owner
    place_in_row = np.arange(r.size) - (np.cumsum(k) - k)[r]
    dest[offsets[r] + 1 + place_in_row] = reach.indices[others]
    return dolfinx.cpp.graph.AdjacencyList_int32(dest, offsets)


def node_input_indices(msh, cells: np.ndarray, num_nodes: int) -> np.ndarray:
    """The input index (the mesh's node order as given to DOLFINx, the same
    on any number of processes) of each of num_nodes P1 nodes numbered by
    cells (num_cells, tdim + 1): a P1 space's dofs, in the mesh's cell order."""
    out = np.empty(num_nodes, dtype=np.int64)
    out[np.asarray(cells).ravel()] = np.asarray(msh.geometry.input_global_indices, dtype=np.int64)[
        msh.geometry.dofmap.array]
    return out


def incomplete_patches(V) -> int:
    """Collective: how many owned nodes of a P1 space V (over all processes)
    have fewer local cells (owned and ghost) than cells at them in the whole
    mesh; 0 with vertex patches."""
    msh = V.mesh
    comm = msh.comm
    tdim = msh.topology.dim
    dofs = V.dofmap.list.array.reshape(-1, tdim + 1)
    imap = V.dofmap.index_map
    owned = imap.size_local
    node_input = node_input_indices(msh, dofs, owned + imap.num_ghosts)
    num_inputs = comm.allreduce(int(node_input.max(initial=-1)) + 1, op=_max())
    own_cells = msh.topology.index_map(tdim).size_local
    whole = np.bincount(node_input[dofs[:own_cells]].ravel(), minlength=num_inputs).astype(np.int64)
    total = np.zeros_like(whole)
    comm.Allreduce(whole, total)
    local = np.bincount(dofs.ravel(), minlength=owned + imap.num_ghosts)[:owned]
    return int(comm.allreduce(int(np.count_nonzero(local != total[node_input[:owned]]))))


def _max():
    from mpi4py import MPI
    return MPI.MAX
