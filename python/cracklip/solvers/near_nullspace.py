"""The rigid-body motions GAMG takes as its near-nullspace: on the
standard dofs and the phantom (Heaviside) copies of the phantom-node
basis, 0 on the tip dofs (which have none) and on multipliers."""
from __future__ import annotations

import typing

import numpy as np

from ..errors import SolverError
from ..model.constraints import ROTATIONS
if typing.TYPE_CHECKING:
    from ..model.model import XfemModel


def rigid_modes(model: "XfemModel", size: int | None = None) -> np.ndarray:
    """(size, 3) in 2D (two translations, one rotation) or (size, 6) in 3D
    (three translations, three rotations): orthonormal rigid motions on the
    standard dofs and the phantom (Heaviside) dofs, evaluated at the base
    node; 0 on tip dofs and on any dof beyond the stiffness (multipliers).
    size defaults to model.num_dofs."""
    n = model.num_dofs if size is None else size
    nodes, xy = rigid_mode_nodes(model)
    return rigid_motions(xy - model.x.mean(axis=0), nodes, n)


def rigid_mode_nodes(model: "XfemModel") -> tuple[np.ndarray, np.ndarray]:
    """The node blocks that carry the rigid modes (the kernels' local
    numbering: every standard node, then the Heaviside pseudo-nodes) and
    their points (a pseudo-node's: its base node's)."""
    lay = model.layout
    nstd = lay.num_std_nodes
    heav = np.flatnonzero(np.asarray(lay.kind) == 0)
    nodes = np.concatenate([np.arange(nstd), nstd + heav])
    return nodes, np.concatenate([model.x, model.x[np.asarray(lay.node)[heav]]])


def rigid_motions(x: np.ndarray, nodes: np.ndarray, n: int, comm=None) -> np.ndarray:
    """(n, 3) in 2D or (n, 6) in 3D: the rigid motions of the points x
    (m, d), carried by the blocked dofs d nodes + c, orthonormalised; 0 on
    every other dof (x centred by the caller: the rotations are about 0).
    Columns: the translations along x, y(, z), then the rotations of
    model.constraints.ROTATIONS. comm: as orthonormal_columns (rows of
    this process: nodes in its local numbering of the owned rows)."""
    d = x.shape[1]
    rotations = ROTATIONS[d]
    R = np.zeros((n, d + len(rotations)))
    for c in range(d):
        R[d * nodes + c, c] = 1.0
    for r, (i, j) in enumerate(rotations):  # -x_j e_i + x_i e_j
        R[d * nodes + i, d + r] = -x[:, j]
        R[d * nodes + j, d + r] = x[:, i]
    return orthonormal_columns(R, comm)


def orthonormal_columns(R: np.ndarray, comm=None) -> np.ndarray:
    """R's columns orthonormalised (twice-repeated modified Gram-Schmidt: a
    few vector operations on a tall (n, 3) R, where LAPACK's QR took 0.3 s at
    1e6 dofs). comm (mpi4py, under MPI): R holds this process's rows of
    columns distributed over the processes; the inner products are summed
    over them (collective)."""
    Q = np.array(R, dtype=np.float64, order="F", copy=True)  # contiguous columns

    def dot(a: np.ndarray, b: np.ndarray) -> float:
        return float(a @ b) if comm is None or comm.size == 1 else float(comm.allreduce(float(a @ b)))
    for j in range(Q.shape[1]):
        for _ in range(2):
            for i in range(j):
                Q[:, j] -= dot(Q[:, i], Q[:, j]) * Q[:, i]
        norm = float(np.sqrt(dot(Q[:, j], Q[:, j])))
        if norm == 0.0:
            raise SolverError("the rigid modes are linearly dependent (a mesh with a single node?)")
        Q[:, j] /= norm
    return Q
