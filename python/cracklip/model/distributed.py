"""The X-FEM unknowns across processes (mpirun; issue 40 step 2): one global
numbering of the standard and enriched dofs, the distributed matrix, its
loads and constraints.

Every process builds the X-FEM model on its part of the mesh (owned cells
first, then the ghost cells at a vertex of an owned cell: scene/partition.py),
with the unchanged serial C++. A node of an owned cell sees its whole patch
there, so its enrichment is the one the serial model gives it.

Numbering. A pseudo-node belongs to the owner of its base node. Process r
owns the global node blocks [start_r, start_r + n_r): its owned standard
nodes in DOLFINx's order, then its owned pseudo-nodes by (base node, the
layout's order). A ghost node takes its owner's numbers (standard block,
first pseudo block, count and a signature of its pseudo-nodes' crack, kind,
function and core flag) by one forward scatter; a ghost whose pseudo-nodes differ from
its owner's (its patch is cut by the partition) is left unnumbered (-1), and
the assembly never reaches it: it is in no owned cell (checked).

The kernels keep their local numbering [standard local | pseudo local]: a
blocked local-to-global map set on the matrix carries it to the global one
(MatSetValuesLocal), and the owned cells alone are integrated, each once.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from petsc4py import PETSc

import dolfinx.la

from ..errors import CrackGeometryError
from ..scene.processes import agree


@dataclasses.dataclass
class DofMap:
    """The global numbering of one process's X-FEM node blocks.

    Attributes:
        comm: the communicator (the mesh's).
        d: the block size (space dimension).
        block: (num_nodes_total,) global block of every kernel-local node
            block (standard, then pseudo-nodes); -1 where the process never
            assembles it.
        start, num_owned: the process's owned blocks [start, start + num_owned).
        num_global: blocks over all processes.
        num_owned_cells: the owned cells, first in the kernels' cell order.
    """
    comm: object
    d: int
    block: np.ndarray
    start: int
    num_owned: int
    num_global: int
    num_owned_cells: int

    @property
    def lgmap(self) -> PETSc.LGMap:
        return PETSc.LGMap().create(self.block.astype(PETSc.IntType), bsize=self.d, comm=self.comm)

    def global_dofs(self, local: np.ndarray) -> np.ndarray:
        """Global scalar dofs of local scalar dofs (-1 where unnumbered)."""
        local = np.asarray(local, dtype=np.int64)
        b = self.block[local // self.d]
        return np.where(b >= 0, b * self.d + local % self.d, -1)

    def owned(self, dofs: np.ndarray) -> np.ndarray:
        """Which global scalar dofs this process owns."""
        lo = self.start * self.d
        return (dofs >= lo) & (dofs < lo + self.num_owned * self.d)


def _signature(layout, pseudo: np.ndarray, position: np.ndarray) -> np.ndarray:
    """A number per pseudo-node naming its crack, kind, function, core flag
    (core or blending: the ramp of the corrected blending) and position at
    its node; summed per node it tells two processes' pseudo-nodes of a
    node apart (exact in doubles)."""
    code = ((np.asarray(layout.crack)[pseudo].astype(np.int64) * 64 + np.asarray(layout.kind)[pseudo] * 8
             + np.asarray(layout.function)[pseudo]) * 2 + np.asarray(layout.core)[pseudo] + 1)
    return (code * (position + 1) * 1009 + position).astype(float)


def create_dof_map(V, cells: np.ndarray, layout, num_owned_cells: int) -> DofMap:
    """Collective: the global numbering of the process's nodes and pseudo-nodes."""
    comm = V.mesh.comm
    im = V.dofmap.index_map
    d = V.dofmap.index_map_bs
    n_own, n_std = im.size_local, im.size_local + im.num_ghosts
    if layout.num_std_nodes != n_std:
        raise ValueError(f"the layout has {layout.num_std_nodes} standard nodes, V {n_std}")
    node = np.asarray(layout.node, dtype=np.int64)
    order = np.argsort(node, kind="stable")  # pseudo-nodes by (base node, layout order)
    sorted_nodes = node[order]
    first_at = np.searchsorted(sorted_nodes, sorted_nodes, side="left")
    position = np.empty(len(node), dtype=np.int64)
    position[order] = np.arange(len(node)) - first_at
    own_pseudo = order[sorted_nodes < n_own]
    n_blocks = n_own + len(own_pseudo)
    start = int(comm.exscan(n_blocks) or 0) if comm.size > 1 else 0
    total = int(comm.allreduce(n_blocks))
    block = np.full(n_std + len(node), -1, dtype=np.int64)
    block[:n_own] = start + np.arange(n_own)
    block[n_std + own_pseudo] = start + n_own + np.arange(len(own_pseudo))

    count = np.bincount(node, minlength=n_std).astype(float)
    sig = np.bincount(node, weights=_signature(layout, np.arange(len(node)), position), minlength=n_std)
    first = np.full(n_std, -1.0)
    head = own_pseudo[position[own_pseudo] == 0]
    first[node[head]] = block[n_std + head]
    # Owners' numbers to the ghosts: (standard block, first pseudo block, count, signature) per node.
    v = dolfinx.la.create_petsc_vector(im, 4)
    with v.localForm() as loc:
        a = loc.array.reshape(n_std, 4)
        a[:n_own] = np.column_stack([block[:n_own], first[:n_own], count[:n_own], sig[:n_own]])
    v.ghostUpdate(addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
    with v.localForm() as loc:
        got = loc.array.reshape(n_std, 4)[n_own:].copy()
    v.destroy()
    ghosts = np.arange(n_own, n_std)
    block[ghosts] = got[:, 0].astype(np.int64)
    same = (got[:, 2] == count[ghosts]) & (got[:, 3] == sig[ghosts])
    in_owned_cells = np.zeros(n_std, dtype=bool)
    in_owned_cells[cells[:num_owned_cells].ravel()] = True
    bad = ghosts[~same & in_owned_cells[ghosts]]
    error = None
    if bad.size:
        error = CrackGeometryError(
            f"{bad.size} node(s) of this process's cells are enriched differently by their owning process "
            "(a crack decision taken on an incomplete patch): not available under MPI yet; run without mpirun")
    agree(error, comm)
    mine = (node >= n_own) & same[np.clip(node - n_own, 0, None)] if len(ghosts) else np.zeros(len(node), bool)
    gp = np.flatnonzero(mine)
    block[n_std + gp] = got[node[gp] - n_own, 1].astype(np.int64) + position[gp]
    return DofMap(comm, d, block, start, n_blocks, total, num_owned_cells)


def create_matrix(dm: DofMap, csr: tuple[np.ndarray, np.ndarray]) -> PETSc.Mat:
    """The distributed blocked matrix, preallocated from the process's local
    scalar CSR (kernels' numbering, every local coupling), with dm's
    local-to-global map. A coupling the local pattern misses (an owned
    row's neighbour enriched on another process only) is allocated when set."""
    indptr, indices = csr
    d = dm.d
    row = np.repeat(np.arange(len(indptr) - 1), np.diff(indptr))
    keep = (row % d == 0) & (indices % d == 0)  # the blocks' first scalar rows and columns
    r, c = dm.block[row[keep] // d], dm.block[indices[keep] // d]
    mine = (r >= dm.start) & (r < dm.start + dm.num_owned) & (c >= 0)
    r, c = r[mine] - dm.start, c[mine]
    diag = (c >= dm.start) & (c < dm.start + dm.num_owned)
    # per scalar row, in scalar columns (petsc4py's AIJ counts)
    dnnz = np.repeat(d * np.bincount(r[diag], minlength=dm.num_owned), d).astype(PETSc.IntType)
    onnz = np.repeat(d * np.bincount(r[~diag], minlength=dm.num_owned), d).astype(PETSc.IntType)
    n, N = dm.num_owned * d, dm.num_global * d
    A = PETSc.Mat().createAIJ(((n, N), (n, N)), bsize=d, nnz=(dnnz, onnz), comm=dm.comm)
    A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, False)
    lg = dm.lgmap
    A.setLGMap(lg, lg)
    return A


def vector_from_local(dm: DofMap, A: PETSc.Mat | None, local: np.ndarray) -> PETSc.Vec:
    """The distributed vector summing every process's local (kernel-ordered)
    vector (laid out as A's columns, or by dm without A)."""
    if A is not None:
        b = A.createVecRight()
    else:
        b = PETSc.Vec().createMPI((dm.num_owned * dm.d, dm.num_global * dm.d), bsize=dm.d, comm=dm.comm)
    b.set(0.0)
    g = dm.global_dofs(np.arange(len(local)))
    ok = (g >= 0) & (local != 0.0)
    b.setValues(g[ok].astype(PETSc.IntType), local[ok], addv=PETSc.InsertMode.ADD_VALUES)
    b.assemble()
    return b


def to_local(dm: DofMap, x: PETSc.Vec) -> np.ndarray:
    """The process's kernel-ordered copy of a distributed vector (0 where unnumbered)."""
    n = len(dm.block) * dm.d
    g = dm.global_dofs(np.arange(n))
    ok = g >= 0
    y = PETSc.Vec().createSeq(n, comm=PETSc.COMM_SELF)
    src = PETSc.IS().createGeneral(np.where(ok, g, 0).astype(PETSc.IntType), comm=PETSc.COMM_SELF)
    scatter = PETSc.Scatter().create(x, src, y, None)
    scatter.scatter(x, y, addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
    out = y.array.copy()
    out[~ok] = 0.0
    for o in (scatter, src, y):
        o.destroy()
    return out


def summed(dm: DofMap, local: np.ndarray) -> np.ndarray:
    """Every local dof's value summed over the processes' local vectors
    (each process's part of an assembled vector made whole; 0 where
    unnumbered)."""
    v = vector_from_local(dm, None, np.asarray(local, dtype=float))
    out = to_local(dm, v)
    v.destroy()
    return out
