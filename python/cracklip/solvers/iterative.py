"""Which linear solver runs, and the iterative (AMG) path.

This module owns the choice between the two checked solver paths
(Options.solver: "auto", "direct", "iterative") and everything the
iterative path needs:

* the phantom-node (Hansbo) basis of the Heaviside pairs: per Heaviside
  pseudo-node k (base node i, side s = H(x_i)) and component d, the standard
  dof u and the enriched dof a become p = u (the node's own-side copy) and
  q = u - 2 s a (the other-side copy): u = p, a = s (p - q) / 2. T maps the
  new dofs to the old ones (u = T y); the solved system is T^T A T y = T^T b,
  and with contact the constraints become B T. In this basis every Heaviside
  basis function is N_i times the indicator of one side of the crack, so the
  stiffness looks like two standard meshes glued along the uncut part: an
  ordinary elasticity operator that smoothed aggregation can coarsen (with a
  strength threshold that drops the rounding-level couplings across the crack);
* the rigid-body near-nullspace on the standard and phantom dofs;
* the crack band: every dof of the enriched nodes and of their first ring of
  neighbours (BAND_RINGS: in 3D the enriched nodes alone), every tip dof
  and every multiplier; with contact it is widened to ceil(0.07 m) rings
  for m multipliers;
* the outer torus (3D, a front enrichment radius of several front
  elements, no contact): the front-function dofs beyond INNER_BAND_RADIUS_H
  front elements leave the exact band, whose LDL^T costs about its length
  times the square of its cross-section, for a block of their own solved
  with their nodes' standard dofs by ICC(0) (OUTER_PC), from OUTER_FROM_H
  on so that it overlaps the band; the sweep becomes {band | outer | GAMG |
  outer | band};
* IterativeSolver: a symmetric overlapping Schwarz sweep {band by MUMPS
  LDL^T | one GAMG V-cycle on the whole transformed stiffness | band again}
  as the preconditioner of CG (also for the saddle point of contact, with
  GMRES(30) as the fallback). CG starts where the band's equations hold,
  so they hold at every iterate and the sweep's first band solve is
  skipped; the frictionless saddle point is applied block by block around
  the stiffness (no copy of it), and GAMG's coarsest solve keeps the
  coarse space's main crack-opening modes closed (_ConstrainedCoarse). The GAMG hierarchy depends on the stiffness
  only, so it is built once and reused by every active-set iteration. The
  unsymmetric saddle point of friction goes to GMRES(30) with the band
  factored by LU, applied block by block around the stiffness too
  (bordered_matrix), its coarse space closed by the closed normal rows; the
  friction iteration's early solves stop at a loose Krylov tolerance
  (contact/friction.py INEXACT_RTOL). Every solve path takes it:
  solve.solve, the load path and friction (load_path.solve_path), hence
  growth.

Every iterative solve is checked like the direct one (checked.
solve_checked): the relative residual of the original (untransformed)
system must be at most Options.residual_tol, else SolverError names the
likely cause. The Krylov tolerance is much tighter (KRYLOV_RTOL) so that
SIFs, pressures and energies equal the direct path's.
"""
from __future__ import annotations

import contextlib
import hashlib
import itertools
import logging
import math
import time
import typing
import weakref

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from ..errors import SolverError
from ..model.constraints import ROTATIONS
from .checked import record_solve, solve_checked
if typing.TYPE_CHECKING:
    from ..model.model import XfemModel
from .direct import LinearSolver
from .phantom import phantom_basis, transform_matrix
from .saddle import BorderedOperator, SaddleOperator
from .checked import scipy_from_petsc
from .checked import factor_call, create_lu_solver, out_of_memory
from .band_update import BandSolve, KeptBand
from ..scene.cell_size import mean_cell_size
from ..scene.processes import on_all


logger = logging.getLogger(__name__)


#: Relative (unpreconditioned) residual at which the Krylov iteration stops.
#: At 1e-10 the SIFs, pressures and energies equal the direct path's to
#: 1e-8 relative on the test scenes (tests/test_solvers.py; the errors there
#: are 1e-10 .. 1e-12). The last decade is the expensive one: at 1e6 dofs the
#: bilateral-contact solve needs 52 iterations to 1e-10 and 71 to 1e-11.
KRYLOV_RTOL = 1e-10


#: GMRES restart, when GMRES takes over from CG on a saddle point (see
#: IterativeSolver._solve): at 1e6 dofs (bilateral, 1-ring band) GMRES(30)
#: was faster than full GMRES (13.7 s vs 15.5 s): orthogonalising against up
#: to 54 vectors of 1e6 entries costs more than 20 extra V-cycles.
GMRES_RESTART = 30


#: With contact the band is wider: ceil(this x the number of multipliers)
#: rings of cells around the enriched nodes (15 rings for the bench crack's
#: 212 multipliers at 1e6 dofs), so that its exact solve carries the
#: multipliers' coupling to the body beyond the next cell. At 1e6 dofs
#: (bilateral) 1 ring takes 74 GMRES(30) iterations, 5 rings 50, 15 rings 42,
#: 40 rings 39: the Schur complement of the multipliers is nonlocal, and a
#: band of fixed physical width (rings ~ 1 / h ~ multipliers) keeps the
#: count from growing with the mesh.
CONTACT_BAND_RINGS_PER_MULTIPLIER = 0.07


MAX_BAND_RINGS = 60


#: On tetrahedra the multipliers cover a surface (their number grows like
#: 1 / h^2, not 1 / h), and rings around it are layers of the whole crack:
#: the per-multiplier rule made the band the whole refined region (the
#: closed penny at 5.8e4 dofs, 137 multipliers: 17 rings, a band of every
#: dof, 14 CG iterations; 1 ring: 15 203 band dofs, 25 iterations; 2 rings
#: 24; plain P1 22). So the 3D band keeps this many rings with contact.
CONTACT_BAND_RINGS_3D = 1


#: The Schwarz sweep skips its first band solve when the residual's band
#: part is below this fraction of the residual: so it is (1e-14 .. 1e-12)
#: in every CG iteration started by _Schwarz.start, whose band equations
#: hold. One MUMPS band solve per iteration instead of two (4.5 ms each at
#: 1e6 dofs with contact), and the start itself saves iterations (2e5 dofs:
#: open crack 39 -> 36, contact 44 -> 41).
BAND_RESIDUAL_SKIP = 1e-10


#: _ConstrainedCoarse keeps closed the jump modes of GAMG's coarsest space
#: whose singular values (in B_a P) are at least this fraction of the
#: largest. At 1e6 dofs (bilateral, coarsest level 3483 dofs): 0.1 and 0.01
#: (17 and 50 modes) 43 -> 36 CG iterations; 1e-3 (87 modes) 44: modes the
#: coarse space represents poorly lock it.
COARSE_CONSTRAINT_SV = 0.05


#: Whether GAMG's block (block 0 of the Schwarz sweep) leaves out the tip
#: dofs (by space dimension); every tip dof is in the crack band or the
#: outer block, which solve it. 3D, penny crack at 3.1e5 dofs (radius
#: 2 h_front, 3 % tip dofs): with the tip couplings GAMG's set-up took
#: 9.4 s and CG 31 iterations against plain P1's 6.8 s and 23; without them
#: 8.4 s and 25 (Heaviside-only: 8.0 s and 22): the tip rows, which have no
#: rigid modes, made the aggregates and the coarse operators denser. 2D
#: keeps them (Westergaard at 2e5 dofs: 23 iterations with, 62 without;
#: IterativeSolver). GAMG's operator is K' on the other dofs
#: (createSubMatrix; block0_dofs). Before, it was K' with the tip rows and
#: columns cut and their diagonal kept, a copy built in numpy over the
#: whole CSR (1.6 s at 5.3e5 dofs, radius 0.25 a), whose isolated tip rows
#: (9 % of them) every V-cycle's fine level carried; GAMG's coarse levels
#: were the same within 1 % either way (the isolated rows are aggregated
#: into nothing). Penny at 5.3e5 dofs, radius 0.25 a, one process each:
#: GAMG's set-up 18.1 s against plain P1's 15.5 s before, 17.1 against
#: 15.8 after; the solver's set-up 20.2 -> 17.9 s; CG 33 iterations either
#: way.
TIP_DOFS_OUT_OF_GAMG = {2: False, 3: True}


#: Rings of neighbours around the enriched nodes in the crack band, by
#: space dimension. In 3D the ring is a thick shell around the front's torus
#: of front-enriched nodes: penny crack at 8.9e4 dofs (radius 2 front
#: elements), band 49.6k dofs with the ring, 35.7k without: 23 CG
#: iterations either way, solve 20.9 -> 14.3 s, peak memory 848 -> 679 MB
#: (5.9e4 dofs: 22 -> 23 iterations, 589 -> 504 MB). 2D keeps its ring.
BAND_RINGS = {2: 1, 3: 0}


#: 3D: the front-enriched nodes farther than this many front element sizes
#: from the front (the outer torus of a large enrichment radius) leave the
#: exact (MUMPS) band, whose cost grows with the square of its
#: cross-section, for a block of their own solved inexactly (OUTER_PC);
#: 0: never (the whole band exact). The block starts OUTER_FROM_H front
#: elements from the front, so that it overlaps the exact band. Penny at
#: 5.3e5 dofs, radius 0.25 a (6 front elements), CG iterations: whole band
#: exact 24; split at 2 without overlap, outer block by ICC(0) 36, ICC(1)
#: 33, by MUMPS (exact) 33, 31 with its standard dofs: the split itself
#: costs iterations, not the incomplete factor; split at 3: 36. With the
#: overlap (from 1): ICC(0) 34, with the standard dofs 29 (ICC(1) 29);
#: split at 3 from 1: 31. Also measured and dropped: a coarse space of the
#: outer block (an aggregate per front function and component per 4 front
#: elements of front) 35 against 36; the outer tip dofs' couplings kept in
#: GAMG's operator 31 against 26 (1.1e5 dofs).
INNER_BAND_RADIUS_H = 2.0


#: Where the outer block starts (front element sizes from the front, at most
#: INNER_BAND_RADIUS_H: between the two both blocks hold the dofs).
OUTER_FROM_H = 1.0


#: Whether the outer block also holds its nodes' standard dofs (unless a
#: Heaviside pseudo-node shares the node): block Gauss-Seidel between GAMG
#: (standard dofs) and the outer block (front-function dofs) is slow where
#: the two spans nearly coincide; holding both, the block overlaps GAMG's
#: (5.3e5 dofs: 34 -> 29 iterations; band 58.5k -> 21.5k dofs).
OUTER_WITH_STANDARD = True


#: The band is split only when the front-function dofs beyond
#: INNER_BAND_RADIUS_H are at least this share of it (radius 2 h_front:
#: 12.5 % at 1e5 dofs, 10.6 % at 5e5, the nodes just beyond the mean front
#: edge, whose path stays as it was; radius 0.25 a: 29 % at 1e5).
OUTER_MIN_SHARE = 0.2


#: The outer block's inexact solve: a fixed symmetric operator (CG);
#: ICC(1) took as many iterations (29 at 5.3e5 dofs) for a larger factor.
OUTER_PC = {"pc_type": "icc", "pc_factor_levels": 0, "pc_factor_shift_type": "positive_definite"}


#: Krylov iterations before the iterative path gives up.
MAX_ITERATIONS = 1000


#: GAMG on the standard + phantom dofs (pinned: PETSc's defaults change
#: between versions). The strength threshold must be > 0: T^T A T leaves
#: rounding-level couplings across the crack, and with threshold 0 the
#: aggregates straddle the crack (78-140 iterations instead of ~40). 0.002
#: rather than 0.01: the same CG / GMRES iterations (3D penny 28, 3D
#: contact 30, 3D friction 15+7+21+9 against 15+7+22+8; 2D open crack 37
#: against 36) for a set-up 17-30 % cheaper (the coarse levels sparser:
#: 3D penny at 2e5 dofs 7.05 -> 5.90 s, plain P1 at 5e5 18.6 -> 12.8 s,
#: alternated in one process; docs/speed.md).
GAMG_OPTIONS = {
    "pc_type": "gamg",
    "pc_gamg_type": "agg",
    "pc_gamg_threshold": 0.002,
    "pc_gamg_coarse_eq_limit": 1000,
    "mg_levels_ksp_type": "chebyshev",
    "mg_levels_pc_type": "jacobi",
    "mg_levels_esteig_ksp_type": "cg",
    "mg_levels_ksp_chebyshev_esteig_steps": 20,
    # The prolongator smoother's eigenvalue estimate by CG, as GAMG does by
    # itself for a matrix flagged SPD (plain DOLFINx): K' is SPD, but the flag
    # would also make a MUMPS fallback factor it without pivoting. GMRES
    # (the default otherwise) cost 0.26 s more at 1e6 dofs.
    "pc_gamg_esteig_ksp_type": "cg",
}


_prefixes = itertools.count()


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


def tip_dofs(model: "XfemModel") -> np.ndarray:
    """Sorted dofs of the tip (front) pseudo-nodes."""
    lay = model.layout
    d = model.gdim
    k = np.flatnonzero(np.asarray(lay.kind) != 0)
    return (d * (lay.num_std_nodes + k)[:, None] + np.arange(d)).ravel().astype(np.int64)


def block0_dofs(n: int, lo: int, hi: int, tip: np.ndarray) -> np.ndarray:
    """The owned rows lo..hi of the stiffness (n dofs) that are not tip
    dofs (tip: the owned tip rows, global numbers): block 0 of the
    Schwarz sweep when GAMG leaves the tip dofs out (TIP_DOFS_OUT_OF_GAMG)."""
    keep = np.ones(max(0, min(hi, n) - lo), dtype=bool)
    keep[tip - lo] = False
    return (np.flatnonzero(keep) + lo).astype(np.int64)


def crack_band(model: "XfemModel", rings: int = 1) -> np.ndarray:
    """Sorted stiffness dofs of the crack band: both dofs of every enriched
    node and of its first `rings` rings of neighbours (nodes sharing a
    cell), and every enriched dof (phantom copies and tip dofs)."""
    lay = model.layout
    nstd = lay.num_std_nodes
    mark = np.zeros(nstd, dtype=bool)
    mark[np.asarray(lay.node)] = True
    for _ in range(rings):
        mark[model.cells[mark[model.cells].any(axis=1)]] = True
    ring = np.flatnonzero(mark)
    d = model.gdim
    std = (d * ring[:, None] + np.arange(d)).ravel()
    return np.concatenate([std, np.arange(d * nstd, model.num_dofs)]).astype(np.int64)


def outer_torus(model: "XfemModel", from_h: float, with_standard: bool = False,
                distance: np.ndarray | None = None) -> np.ndarray:
    """Sorted dofs of the outer torus: the front-enrichment dofs of the
    pseudo-nodes whose node lies farther than from_h front element sizes
    (the mean edge of the cells the front crosses) from its crack's front
    (|(phi, psi)|), and, with_standard, those nodes' standard dofs (unless a
    Heaviside pseudo-node shares the node). 3D only; empty if there is none
    or from_h is 0. distance: front_distance(model), if the caller has it."""
    lay = model.layout
    kind = np.asarray(lay.kind)
    tip = np.flatnonzero(kind != 0)
    if model.gdim != 3 or tip.size == 0 or not from_h:
        return np.zeros(0, dtype=np.int64)
    node = np.asarray(lay.node)
    far = (front_distance(model) if distance is None else distance) > from_h
    d = model.gdim
    pseudo = tip[far]
    dofs = [(d * (lay.num_std_nodes + pseudo)[:, None] + np.arange(d)).ravel()]
    if with_standard and pseudo.size:
        nodes = np.unique(node[pseudo])
        nodes = nodes[~np.isin(nodes, node[kind == 0])]
        dofs.append((d * nodes[:, None] + np.arange(d)).ravel())
    return np.sort(np.concatenate(dofs)).astype(np.int64)


def front_distance(model: "XfemModel") -> np.ndarray:
    """Per tip (front) pseudo-node, in the layout's order: its node's
    distance from its crack's front, |(phi, psi)|, in front element sizes
    (the mean edge of the cells the front crosses; 0 for a crack without
    front cells: never in the outer torus). 3D."""
    lay = model.layout
    tip = np.flatnonzero(np.asarray(lay.kind) != 0)
    node = np.asarray(lay.node)
    crack = np.asarray(lay.crack)
    dist = np.zeros(tip.size)
    for c, cm in enumerate(model.cracks):
        g = cm.geometry
        front_cells = np.flatnonzero(np.asarray(g.cell_class) == cm.CELL_CLASSES["front"])
        mine = crack[tip] == c
        if front_cells.size == 0 or not mine.any():
            continue
        h = mean_cell_size(model.x, model.cells[front_cells])
        nd = node[tip[mine]]
        dist[mine] = np.hypot(np.asarray(g.phi)[nd], np.asarray(g.psi)[nd]) / h
    return dist


def grow_band(K: PETSc.Mat, dofs: np.ndarray, rings: int) -> np.ndarray:
    """Sorted dofs reached from `dofs` in `rings` steps through the graph of
    K (one step = one ring of cells for P1 dofs); work proportional to the
    band, not to the mesh."""
    n = K.getSize()[0]
    mark = np.zeros(n, dtype=bool)
    mark[dofs] = True
    frontier = np.asarray(dofs)
    all_cols = PETSc.IS().createStride(n, 0, 1, comm=PETSc.COMM_SELF)
    for _ in range(rings):
        iset = PETSc.IS().createGeneral(frontier.astype(PETSc.IntType), comm=PETSc.COMM_SELF)
        sub = K.createSubMatrix(iset, all_cols)
        _, cols, _ = sub.getValuesCSR()
        sub.destroy()
        iset.destroy()
        reached = np.unique(cols)
        frontier = reached[~mark[reached]]
        if frontier.size == 0:
            break
        mark[frontier] = True
    all_cols.destroy()
    return np.flatnonzero(mark).astype(np.int64)


def _set_up_pc(A: PETSc.Mat, name: str, options: dict[str, typing.Any]) -> PETSc.PC:
    """A PC on A set up from `options` (PETSc option names without the
    prefix) under a prefix of its own (cracklip_<name><k>_), which is
    cleared again from PETSc's options database afterwards (GAMG's and the
    outer block's)."""
    prefix = f"cracklip_{name}{next(_prefixes)}_"
    pc = PETSc.PC().create(A.getComm())
    pc.setOptionsPrefix(prefix)
    pc.setOperators(A)
    db = PETSc.Options()
    for k, v in options.items():
        db[prefix + k] = v
    try:
        pc.setFromOptions()
        with product_data_cleared():
            pc.setUp()
    finally:
        for k in options:
            db.delValue(prefix + k)
    return pc


@contextlib.contextmanager
def product_data_cleared() -> typing.Iterator[None]:
    """Within it, a distributed matrix product (PtAP) frees the data it
    keeps for recomputing the product with new values (PETSc's
    -mat_product_clear), which cracklip never does: the parallel PtAP of
    the phantom transform and of GAMG's coarse levels otherwise hold about
    as much again as their results. The penny at 2.9e5 dofs on 2 processes:
    2.53 -> 1.69 GB peak over both after GAMG's set-up (serial products
    keep nothing of the kind: 0.96 GB either way); the numbers are the
    same. A value the user set is left as it is."""
    db = PETSc.Options()
    mine = not db.hasName("mat_product_clear")
    if mine:
        db["mat_product_clear"] = 1
    try:
        yield
    finally:
        if mine:
            db.delValue("mat_product_clear")


class IterativeSolver(LinearSolver):
    """Krylov + overlapping symmetric multiplicative Schwarz in the
    phantom-node basis (module docstring): CG for the stiffness and for the
    frictionless saddle point (the sweep ends with the band's exact solve,
    so CG works on the constrained problem; GMRES(30) if CG breaks down),
    GMRES(30) for friction's unsymmetric saddle point.

    Block 0 is in 2D the whole transformed stiffness K', tip dofs included
    (no copy, no scatter: the stiffness's dofs come first in every system;
    the tip dofs' rows have no rigid modes, and the band solves them
    exactly): Westergaard at 2e5 dofs, radius 0.2, takes 23 iterations so
    and 62 with K' without its tip dofs as block 0 (a hole in the AMG's
    operator). In 3D it is K' without the tip dofs (TIP_DOFS_OUT_OF_GAMG),
    which the band and the outer block hold. Its
    GAMG hierarchy is built on the first solve and reused by every later
    one (the active-set iterations of contact only change multiplier rows);
    with contact its coarsest solve is constrained by the active
    multipliers (_ConstrainedCoarse), set anew for every solve.
    """
    name = "iterative"

    def __init__(self, model: "XfemModel", fallback: bool = False):
        self.model = model
        self.fallback = fallback
        self.basis = self._phantom_basis()
        self.n = self._num_dofs()
        self._band_k = self._crack_band(BAND_RINGS[self.model.gdim])
        self._outer, beyond = self._outer_torus()
        # The exact band of a solve without contact when the outer torus
        # has its own block: without the outer torus beyond its overlap.
        self._band_inner = np.setdiff1d(self._band_k, beyond) if self._outer.size else self._band_k
        self._bands: dict[int, np.ndarray] = {}
        self._T_inv_t: sp.csr_matrix | None = None
        self._K: PETSc.Mat | None = None
        self._amg: PETSc.PC | None = None
        self._K_amg: PETSc.Mat | None = None
        #: Block 0's owned rows (GAMG's), or None: the whole stiffness.
        self._block0: np.ndarray | None = None
        self._n_amg = self.n  # (GAMG's operator's size, over the processes)
        self._coarse: _ConstrainedCoarse | None = None
        # The hierarchy holds a Python PC (its coarse solve), which PETSc must
        # not destroy after the interpreter's shutdown (a segfault at exit):
        # destroy() frees it, and so does this finalizer, at the latest when
        # the interpreter exits.
        self._owned: list[typing.Any] = []
        self._release = weakref.finalize(self, _release, self._owned)
        #: The last crack band factored, updated where the next one changed
        #: in few rows (a contact or friction state iteration's solves).
        self._kept_band = KeptBand(_factor_band, self.n)
        self._owned.append(self._kept_band)

    #: Whether GAMG's coarsest solve is replaced by _ConstrainedCoarse (the
    #: contact solves' constrained coarse space; a serial LU of the coarse
    #: operator).
    constrained_coarse = True

    # What the model's numbering gives (serial: the kernels' local dofs;
    # solvers.distributed_iterative overrides them with the global, owned ones).
    def _phantom_basis(self):
        return phantom_basis(self.model)

    def _num_dofs(self) -> int:
        return self.model.num_dofs

    def _crack_band(self, rings: int) -> np.ndarray:
        return crack_band(self.model, rings)

    def _rigid_modes(self) -> np.ndarray:
        return rigid_modes(self.model)

    def _outer_torus(self) -> tuple[np.ndarray, np.ndarray]:
        """(the outer block's dofs, the dofs the exact band leaves to it);
        both empty unless the front-function dofs beyond
        INNER_BAND_RADIUS_H are at least OUTER_MIN_SHARE of the band."""
        none = np.zeros(0, dtype=np.int64)
        if self.model.gdim != 3 or not INNER_BAND_RADIUS_H or not np.any(np.asarray(self.model.layout.kind) != 0):
            return none, none
        dist = front_distance(self.model)  # (once: the three selections below share it)
        beyond = outer_torus(self.model, INNER_BAND_RADIUS_H, distance=dist)
        if beyond.size < OUTER_MIN_SHARE * self._band_k.size:
            return none, none
        return (outer_torus(self.model, OUTER_FROM_H, OUTER_WITH_STANDARD, dist),
                outer_torus(self.model, INNER_BAND_RADIUS_H, OUTER_WITH_STANDARD, dist))

    def _tip_dofs(self) -> np.ndarray:
        return tip_dofs(self.model)

    # The system in the phantom basis.
    def transform(self, A: PETSc.Mat) -> tuple[PETSc.Mat, sp.csr_matrix]:
        A_t = transform_matrix(self.basis, A)
        A_t.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        self._K = A_t
        return A_t, self.basis.T

    def stiffness(self, A: PETSc.Mat) -> PETSc.Mat:
        """The stiffness itself: saddle_matrix() does not copy it."""
        return A

    def saddle_matrix(self, K: PETSc.Mat, B: sp.csr_matrix, active: np.ndarray,
                      S: sp.csr_matrix | None = None) -> PETSc.Mat:
        """[K B_a^T; B_a D] as a Python PETSc matrix applied blockwise around
        K (SaddleOperator; no copy of the stiffness: at 1e6 dofs the
        assembled saddle point cost 0.1-0.25 s and the scipy copy of K it
        needs another 0.25-0.3 s)."""
        op = SaddleOperator(K, B, active, S)
        size = op.n + op.m
        A = PETSc.Mat().createPython([size, size], context=op, comm=PETSc.COMM_SELF)
        A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        A.setUp()
        return A

    def bordered_matrix(self, K: PETSc.Mat, C: sp.csr_matrix, rows: sp.csr_matrix,
                        constraints: sp.csr_matrix) -> PETSc.Mat:
        """Friction's [K C^T; rows] as a Python PETSc matrix applied
        blockwise around K (BorderedOperator: no copy of the stiffness);
        constraints (rows of C) keep GAMG's coarse space closed as B_a does
        for the frictionless saddle point."""
        op = BorderedOperator(K, C, rows, constraints)
        size = op.n + op.m
        A = PETSc.Mat().createPython([size, size], context=op, comm=PETSc.COMM_SELF)
        A.setUp()
        return A

    def destroy(self) -> None:
        self._release()
        self._amg = self._coarse = None

    def _contact_band(self, m: int) -> np.ndarray:
        """The stiffness dofs of the band: one ring without contact; with m
        multipliers, ceil(CONTACT_BAND_RINGS_PER_MULTIPLIER m) rings in 2D,
        CONTACT_BAND_RINGS_3D in 3D (grown through the stiffness's graph),
        kept for later solves."""
        if m == 0:
            rings = 1
        elif self.model.gdim == 3:
            rings = CONTACT_BAND_RINGS_3D
        else:
            rings = min(MAX_BAND_RINGS, max(1, math.ceil(CONTACT_BAND_RINGS_PER_MULTIPLIER * m)))
        if rings not in self._bands:
            K = self._K
            self._bands[rings] = self._band_k if rings == 1 or K is None else self._grow_band(K, rings - 1)
        return self._bands[rings]

    def _grow_band(self, K: PETSc.Mat, rings: int) -> np.ndarray:
        """The band dofs grown by `rings` rings through K's graph."""
        return grow_band(K, self._band_k, rings)

    def _multiplier_rows(self, A: PETSc.Mat) -> np.ndarray:
        """The rows of A beyond the stiffness's (the multipliers') that
        belong to the band: all of them (under MPI the owned ones)."""
        return np.arange(self.n, A.getSize()[0])

    def _block0_pc(self, A: PETSc.Mat) -> tuple[PETSc.PC, bool]:
        """The GAMG PC of block 0, built once ((pc, reused)): on the
        stiffness given to transform(), or on its rows and columns
        self._block0 when GAMG leaves the tip dofs out (TIP_DOFS_OUT_OF_GAMG)."""
        if self._amg is not None:
            return self._amg, True
        if self._K is None:
            raise SolverError("IterativeSolver.solve needs the system from IterativeSolver.transform")
        K = self._K
        modes = self._rigid_modes()
        tip = self._tip_dofs()
        if TIP_DOFS_OUT_OF_GAMG[self.model.gdim] and K.getComm().tompi4py().allreduce(tip.size):
            lo, hi = K.getOwnershipRange()
            self._block0 = block0_dofs(self.n, lo, hi, tip)
            iset = PETSc.IS().createGeneral(self._block0.astype(PETSc.IntType), comm=K.getComm())
            iset.setBlockSize(K.getBlockSize())  # (whole nodes: GAMG aggregates nodes)
            K = self._K_amg = self._K.createSubMatrix(iset, iset)
            iset.destroy()
            self._n_amg = K.getSize()[0]
            self._owned.append(K)
            modes = modes[self._block0 - lo]  # (0 on the tip rows: still orthonormal)
        self._amg = self._gamg(K, modes)
        self._owned.append(self._amg)
        if self.constrained_coarse:
            self._coarse = _ConstrainedCoarse(self._amg, self._block0)
            self._owned.append(self._coarse)
        return self._amg, False

    def _gamg(self, A: PETSc.Mat, modes: np.ndarray) -> PETSc.PC:
        """A set-up GAMG PC on A with the rigid modes (orthonormal columns,
        rows of A: rigid_modes) as near-nullspace."""
        vecs = []
        for j in range(modes.shape[1]):
            v = A.createVecRight()
            v.array[:] = modes[:, j]
            vecs.append(v)
        A.setNearNullSpace(PETSc.NullSpace().create(vectors=vecs, comm=A.getComm()))
        return _set_up_pc(A, "amg", GAMG_OPTIONS)

    def solve(self, A: PETSc.Mat, b: PETSc.Vec, residual_tol: float, what: str,
              x0: np.ndarray | None = None, symmetric: bool = True,
              contact_points: int | None = None, rtol: float | None = None) -> PETSc.Vec:
        """Solve A y = b (A in the phantom basis: the stiffness given to
        transform(), or a saddle-point system extending it, unsymmetric
        with friction); check the residual of the original system. With
        fallback (solver = "auto") a failed iterative solve is repeated by
        MUMPS (LDL^T, or LU if not symmetric), which either solves the
        system or names what is singular. rtol: an inexact solve
        (LinearSolver.solve): the Krylov iteration stops at this relative
        residual, and the check takes 10 rtol as residual_tol (the original
        basis's residual is not the phantom basis's)."""
        if rtol is not None:
            residual_tol = max(residual_tol, 10.0 * rtol)
        try:
            return self._solve(A, b, residual_tol, what, x0, symmetric, contact_points, rtol)
        except SolverError as e:
            if not self.fallback:
                raise
            logger.warning("%s: the iterative solver failed (%s); solving with MUMPS instead", what, e)
            if A.getType() == PETSc.Mat.Type.PYTHON:  # saddle_matrix's: MUMPS needs it assembled
                A_aij = A.getPythonContext().assembled()
                try:
                    return solve_checked(A_aij, b, residual_tol, what=what, symmetric=symmetric)
                finally:
                    A_aij.destroy()
            return solve_checked(A, b, residual_tol, what=what, symmetric=symmetric)

    def _solve(self, A: PETSc.Mat, b: PETSc.Vec, residual_tol: float, what: str,
               x0: np.ndarray | None, symmetric: bool = True, contact_points: int | None = None,
               rtol: float | None = None) -> PETSc.Vec:
        size = A.getSize()[0]
        m = size - self.n
        t0 = time.perf_counter()
        if x0 is not None:
            y = self._started(A, b, x0, KRYLOV_RTOL if rtol is None else rtol, residual_tol)
            if y is not None:  # (the friction iteration's last check, most often)
                record_solve({"what": what, "size": size, "relative_residual": self._original_residual(A, y, b),
                              "solver": "iterative", "method": _method("cg" if symmetric else "gmres"),
                              "iterations": 0, "amg_dofs": self._n_amg, "setup_reused": True,
                              "rtol": KRYLOV_RTOL if rtol is None else rtol, "t_setup": 0.0,
                              "t_total": time.perf_counter() - t0})
                return y
        shell = None
        try:
            pc0, reused = self._block0_pc(A)
            t_amg = time.perf_counter() - t0
            # The band's width follows the contact points (friction has two
            # multipliers per point: normal, tangential).
            # Without contact the outer torus (if any) is a block of its own.
            split = m == 0 and symmetric and self._outer.size > 0
            band_dofs = self._band_inner if split else np.concatenate([
                self._contact_band(m if contact_points is None else contact_points), self._multiplier_rows(A)])
            shell = _Schwarz(A, pc0, self.n, band_dofs, symmetric, self._outer if split else None, self._block0,
                             self._kept_band.factor)
            t_band = time.perf_counter() - t0 - t_amg
            if A.getType() == PETSc.Mat.Type.PYTHON and m > 0 and self._coarse is not None:
                self._coarse.constrain(A.getPythonContext().Ba_petsc)
            t_setup = time.perf_counter() - t0
            # CG also for the saddle point: the sweep ends with an exact solve
            # of the band, which holds every multiplier and every dof they
            # touch, so the preconditioned residual always satisfies the
            # constraints and CG works on the constrained (positive definite)
            # problem, as with a constraint preconditioner. If it breaks down
            # anyway, GMRES (which needs no definiteness) takes over.
            # An unsymmetric system (friction) goes to GMRES at once.
            attempts = ["gmres"] if not symmetric else ["cg"] if m == 0 else ["cg", "gmres"]
            for krylov in attempts:
                y, its, reason = self._krylov(A, b, shell, krylov, x0, what, rtol)
                rel = self._original_residual(A, y, b)
                ok = on_all(bool(np.all(np.isfinite(y.array))), y.getComm().tompi4py()) and rel <= residual_tol
                if ok or krylov == attempts[-1]:
                    break
                logger.info("%s: CG stopped at relative residual %.3g after %d iterations (reason %s); "
                            "GMRES(%d) instead", what, rel, its, reason, GMRES_RESTART)
                y.destroy()
        finally:
            if shell is not None:
                shell.free()
            if self._coarse is not None:
                self._coarse.clear()
        method = _method(krylov)
        record_solve({"what": what, "size": size, "relative_residual": rel, "solver": "iterative",
                      "method": method, "iterations": int(its),
                      "band": int(A.getComm().tompi4py().allreduce(band_dofs.size)),  # (over the processes)
                      "outer": int(shell.outer.size if shell is not None and shell.outer is not None else 0),
                      # (the band solved from the kept factorisation of an earlier one: band_update.py)
                      "band_updated": bool(shell is not None and shell.band.updated),
                      "band_update_rank": int(shell.band.rank if shell is not None else 0),
                      "amg_dofs": self._n_amg, "setup_reused": reused, "rtol": KRYLOV_RTOL if rtol is None else rtol,
                      "t_setup": t_setup, "t_amg_setup": t_amg, "t_band_setup": t_band,
                      "t_total": time.perf_counter() - t0})
        logger.info("%s: %d iterations (%s), relative residual %.3g", what, its, method, rel)
        if not ok:
            cause = ("it stopped after the iteration limit" if reason == PETSc.KSP.ConvergedReason.DIVERGED_MAX_IT
                     else f"PETSc reason {reason}")
            y.destroy()
            raise SolverError(
                f"the iterative solve of the {what} is inaccurate: relative residual {rel:.3g} > "
                f"{residual_tol:g} after {its} iterations ({cause}); the matrix is singular (a piece of the "
                "domain cut free by a crack, a multiplier without a jump) or too ill-conditioned for the "
                "AMG preconditioner (slivers cut by the crack, a large tip enrichment radius): use "
                "solver = 'direct'")
        return y

    def _started(self, A: PETSc.Mat, b: PETSc.Vec, x0: np.ndarray, rtol: float,
                 residual_tol: float) -> PETSc.Vec | None:
        """x0 as a vector if it already solves A y = b to the Krylov
        tolerance and passes the check (no preconditioner set up: a band
        factorisation saved), else None."""
        y = A.createVecRight()
        y.array[:] = x0
        r = b.duplicate()
        A.mult(y, r)
        r.axpy(-1.0, b)
        done = r.norm() <= rtol * b.norm()
        r.destroy()
        if done and self._original_residual(A, y, b) <= residual_tol:
            return y
        y.destroy()
        return None

    def _krylov(self, A: PETSc.Mat, b: PETSc.Vec, shell: "_Schwarz", krylov: str, x0: np.ndarray | None,
                what: str, rtol: float | None = None) -> tuple[PETSc.Vec, int, int]:
        """One Krylov solve of A y = b preconditioned by the Schwarz sweep: (y, iterations, reason)."""
        ksp = PETSc.KSP().create(A.getComm())
        try:
            ksp.setOperators(A)
            ksp.setType(krylov)
            if krylov == "gmres":
                ksp.setGMRESRestart(GMRES_RESTART)
                ksp.setPCSide(PETSc.PC.Side.RIGHT)  # (the unpreconditioned norm; _Schwarz.start)
            ksp.setTolerances(rtol=KRYLOV_RTOL if rtol is None else rtol, atol=0.0, max_it=MAX_ITERATIONS)
            ksp.setNormType(PETSc.KSP.NormType.UNPRECONDITIONED)
            pc = ksp.getPC()
            pc.setType("python")
            pc.setPythonContext(shell)
            # No wrapper of the PC may outlive ksp.destroy(): PETSc then keeps
            # the PC, and the PC the matrix (K' leaked, 0.2 GB per solve at
            # 1e6 dofs).
            del pc
            y = b.duplicate()
            y.set(0.0)
            if x0 is not None:
                y.array[:] = x0
            shell.start(A, b, y)  # (CG, and GMRES on the right: _Schwarz's doc)
            ksp.setInitialGuessNonzero(True)
            shell.cg = ksp if krylov == "cg" else None
            try:
                ksp.solve(b, y)
            except PETSc.Error as e:
                raise SolverError(f"the iterative solve of the {what} failed in PETSc ({e}); the crack band "
                                  "block is probably singular: check that every piece of the domain has "
                                  "Dirichlet conditions fixing its rigid motion, or use solver = 'direct'") from None
            return y, ksp.getIterationNumber(), ksp.getConvergedReason()
        finally:
            shell.cg = None
            ksp.destroy()

    def _original_residual(self, A: PETSc.Mat, y: PETSc.Vec, b: PETSc.Vec) -> float:
        """||A_orig u - b_orig|| / ||b_orig|| from the transformed system:
        r_orig = T^-T r (T^T r_orig = r), on the stiffness rows; multiplier
        rows are the same in both bases."""
        r = b.duplicate()
        A.mult(y, r)
        r.axpy(-1.0, b)
        ra, ba = r.array.copy(), b.array.copy()
        r.destroy()
        if self._T_inv_t is None:
            self._T_inv_t = self.basis.T_inv.T.tocsr()
        Ti = self._T_inv_t
        ra[:self.n] = Ti @ ra[:self.n]
        ba[:self.n] = Ti @ ba[:self.n]
        bn = float(np.linalg.norm(ba))
        rn = float(np.linalg.norm(ra))
        return rn / bn if bn > 0 else rn


def _method(krylov: str) -> str:
    """The iterative path's method as solve records name it."""
    return (f"{'CG' if krylov == 'cg' else f'GMRES({GMRES_RESTART})'} + "
            "Schwarz {MUMPS crack band | GAMG | band} (phantom basis)")


class _Schwarz:
    """PCSHELL context: a symmetric multiplicative sweep over two
    overlapping blocks, the crack band (exact, MUMPS) before and after one
    GAMG V-cycle on block 0 (the leading n0 dofs, the stiffness, or the
    given part of them: IterativeSolver._block0):

        z  = R1^T A11^-1 R1 r
        z += R0^T GAMG(R0 (r - A z))
        z += R1^T A11^-1 R1 (r - A z)

    i.e. I - M A = (I - B1 A)(I - B0 A)(I - B1 A): symmetric, and positive
    definite for a positive definite A (CG). Only the band's rows and
    columns of A are needed for the residual updates (small matrices).
    When R1 r = 0 the first line gives z = 0 and is skipped: one band solve
    per iteration. So it is in a Krylov iteration started by start(): the
    sweep ends with the band's exact solve, so R1 A M r = R1 r for every r;
    CG's residuals then keep R1 r = 0, and so do the basis vectors of
    GMRES preconditioned on the right (Arnoldi's v_j+1 combines A M v_j and
    the v_i; rounding grows as the iteration converges, and the sweep then
    does its first band solve). 3D friction at 4.9e5 dofs (56 GMRES
    iterations, one process, alternated twice): the sweeps 9.1 and 9.7 s
    started, 10.3 and 12.2 s not."""

    def __init__(self, A: PETSc.Mat, amg: PETSc.PC, n0: int, band_dofs: np.ndarray, symmetric: bool = True,
                 outer_dofs: np.ndarray | None = None, block0: np.ndarray | None = None,
                 band_factor: typing.Callable[[np.ndarray, PETSc.Mat, bool], BandSolve] | None = None):
        # Under MPI (a distributed A) band_dofs are this process's owned band
        # rows (global numbers) and block 0 its owned rows below n0, or of
        # block0 (sorted: a part of them, GAMG's operator's rows) if given.
        comm = A.getComm()
        size = A.getSize()[0]
        lo, hi = A.getOwnershipRange()
        self.amg = amg
        band = np.sort(band_dofs).astype(PETSc.IntType)
        self.is1 = PETSc.IS().createGeneral(band, comm=comm)
        if block0 is None:
            self.is0 = PETSc.IS().createStride(max(0, min(hi, n0) - lo), lo, 1, comm=comm)
        else:
            self.is0 = PETSc.IS().createGeneral(block0.astype(PETSc.IntType), comm=comm)
            n0 = comm.tompi4py().allreduce(block0.size)
        if A.getType() == PETSc.Mat.Type.PYTHON:  # IterativeSolver.saddle_matrix's (serial)
            self.A1, self.A01, A11 = A.getPythonContext().band_blocks(band)
            if block0 is not None:  # (A01: every stiffness row; block 0's)
                cols = PETSc.IS().createStride(self.A01.getSize()[1], 0, 1, comm=comm)
                A01 = self.A01.createSubMatrix(self.is0, cols)
                cols.destroy()
                self.A01.destroy()
                self.A01 = A01
        else:
            all_cols = PETSc.IS().createStride(hi - lo, lo, 1, comm=comm)  # (the owned columns)
            self.A1 = A.createSubMatrix(self.is1, all_cols)  # band rows, all columns
            all_cols.destroy()
            # Block 0's rows and the band's columns: for a symmetric A the
            # transpose of A1's (no copy: 0.06 GB at 8e4 dofs in 3D).
            self.A01 = None if symmetric else A.createSubMatrix(self.is0, self.is1)
            A11 = A.createSubMatrix(self.is1, self.is1)
        # The band's exact solve: factored, or a kept factorisation updated
        # (band_factor: KeptBand.factor, which takes A11 over;
        # solvers/band_update.py).
        if band_factor is None:
            self.band = BandSolve(_factor_band(A11, symmetric), owned=True)
            A11.destroy()
        else:
            self.band = band_factor(band, A11, symmetric)
        self.r0 = PETSc.Vec().create(comm)
        self.r0.setSizes((self.is0.getLocalSize(), n0))
        self.r0.setUp()
        self.z0, self.t0 = self.r0.duplicate(), self.r0.duplicate()
        self.r1, self.z1, self.t1 = (self.A1.createVecLeft() for _ in range(3))
        self.full = self.A1.createVecRight() if self.A01 is None else None  # A1^T z1
        r = PETSc.Vec().create(comm)
        r.setSizes((hi - lo, size))
        r.setUp()
        # Block 0 by a scatter made once (VecGetSubVector of a general
        # index set makes one per call: 10 ms a sweep at 1e5 dofs).
        self.s0 = PETSc.Scatter().create(r, self.is0, self.r0, None)
        self.s1 = PETSc.Scatter().create(r, self.is1, self.r1, None)
        r.destroy()
        #: The outer torus's inexact block (serial, symmetric A), or None.
        self.outer = None if outer_dofs is None or outer_dofs.size == 0 else _InexactBlock(A, outer_dofs)
        #: The CG KSP this sweep preconditions (set by IterativeSolver._krylov
        #: for the solve), whose residual norm apply() reads.
        self.cg: PETSc.KSP | None = None

    def apply(self, pc: PETSc.PC, r: PETSc.Vec, z: PETSc.Vec) -> None:
        fwd, rev = PETSc.ScatterMode.FORWARD, PETSc.ScatterMode.REVERSE
        ins, add = PETSc.InsertMode.INSERT_VALUES, PETSc.InsertMode.ADD_VALUES
        self.s1.scatter(r, self.r1, ins, fwd)
        # ||r||: CG has just computed it (unpreconditioned norm) before
        # calling the preconditioner.
        rnorm = self.cg.getResidualNorm() if self.cg is not None else r.norm()
        # r vanishes on the band (CG started by start(): every residual does,
        # up to rounding): the first band solve would give 0, and the V-cycle
        # acts on r itself. Else band first, and the V-cycle on r - A z (z the
        # band correction so far).
        band_first = self.r1.norm() > BAND_RESIDUAL_SKIP * rnorm
        self.s0.scatter(r, self.r0, ins, fwd)
        if band_first:
            self.band.solve(self.r1, self.z1)
            self.z1.scale(-1.0)
            if self.A01 is None:  # A01 = (A1's block-0 columns)^T
                self.A1.multTranspose(self.z1, self.full)
                self.s0.scatter(self.full, self.r0, add, fwd)  # r0 - A01 z1
            else:
                self.A01.multAdd(self.z1, self.r0, self.r0)  # r0 - A01 z1
            self.z1.scale(-1.0)
        z.set(0.0)
        if self.outer is not None:
            # The outer torus on r - A z, and block 0's residual updated by its
            # correction (z is the band's so far; serial and symmetric A).
            if band_first:
                self.s1.scatter(self.z1, z, add, rev)
            self.s0.scatter(self.outer.correct(r, z, z_zero=not band_first), self.t0, ins, fwd)
            self.r0.axpy(-1.0, self.t0)
        self.amg.apply(self.r0, self.z0)
        self.s0.scatter(self.z0, z, add, rev)
        if self.outer is not None:
            self.outer.correct(r, z, product=False)  # (no product: the band's A1 z follows)
        elif band_first:
            self.s1.scatter(self.z1, z, add, rev)
        # Band again on r - A z.
        self.A1.mult(z, self.t1)
        self.t1.aypx(-1.0, self.r1)
        self.band.solve(self.t1, self.z1)
        self.s1.scatter(self.z1, z, add, rev)

    def start(self, A: PETSc.Mat, b: PETSc.Vec, y: PETSc.Vec) -> None:
        """y += R1^T A11^-1 R1 (b - A y): the band's equations hold at y,
        and then at every CG iterate (R1 A z = R1 r for each preconditioned
        residual z, so R1 r stays 0), which lets apply() skip its first
        band solve."""
        r = b.duplicate()
        A.mult(y, r)
        r.aypx(-1.0, b)
        self.s1.scatter(r, self.r1, PETSc.InsertMode.INSERT_VALUES, PETSc.ScatterMode.FORWARD)
        r.destroy()
        self.band.solve(self.r1, self.z1)
        self.s1.scatter(self.z1, y, PETSc.InsertMode.ADD_VALUES, PETSc.ScatterMode.REVERSE)

    def destroy(self, pc: PETSc.PC) -> None:
        """Called by PETSc when a PC using this context is destroyed: the
        context outlives it (several Krylov attempts share it); free() frees."""

    def free(self) -> None:
        """Free the PETSc objects (idempotent)."""
        for obj in (self.is0, self.is1, self.A1, self.A01, self.band, self.r0, self.z0, self.t0, self.r1, self.z1,
                    self.t1, self.s0, self.s1, self.full):
            if obj is not None:
                obj.destroy()
        if self.outer is not None:
            self.outer.free()
        self.amg = self.cg = None


class _InexactBlock:
    """A block of the Schwarz sweep solved inexactly by a fixed symmetric
    operator B, OUTER_PC's factor of its diagonal block (serial, symmetric
    A): correct(r, z) does z += R^T B R (r - A z) and returns A R^T (that
    correction) (the length of A), for the next block's residual."""

    def __init__(self, A: PETSc.Mat, dofs: np.ndarray):
        comm = A.getComm()
        self.size = int(dofs.size)
        self.idx = dofs
        iset = PETSc.IS().createGeneral(dofs.astype(PETSc.IntType), comm=comm)
        all_cols = PETSc.IS().createStride(A.getSize()[0], 0, 1, comm=comm)
        self.A2 = A.createSubMatrix(iset, all_cols)  # its rows, all columns
        all_cols.destroy()
        A22 = A.createSubMatrix(iset, iset)
        iset.destroy()
        A22.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        pc = _set_up_pc(A22, "outer", OUTER_PC)
        # Only the factor is kept (what the PC applies), not A22 (0.2-0.3 GB
        # at 1e6 dofs).
        self.factor = pc.getFactorMatrix()
        pc.destroy()
        A22.destroy()
        self.r2, self.z2 = self.A2.createVecLeft(), self.A2.createVecLeft()
        self.full = self.A2.createVecRight()

    def correct(self, r: PETSc.Vec, z: PETSc.Vec, z_zero: bool = False, product: bool = True) -> PETSc.Vec | None:
        """z_zero: z is 0 (its product skipped); product: whether the
        caller needs A R^T (the correction) (else None)."""
        if z_zero:
            self.r2.array[:] = r.array[self.idx]
        else:
            self.A2.mult(z, self.r2)
            self.r2.array[:] = r.array[self.idx] - self.r2.array
        self.factor.solve(self.r2, self.z2)
        z.array[self.idx] += self.z2.array
        if not product:
            return None
        self.A2.multTranspose(self.z2, self.full)
        return self.full

    def free(self) -> None:
        for obj in (self.A2, self.factor, self.r2, self.z2, self.full):
            obj.destroy()


def _release(owned: list[typing.Any]) -> None:
    """Free an IterativeSolver's PETSc objects (last made, first freed)."""
    while owned:
        obj = owned.pop()
        (obj.free if isinstance(obj, _ConstrainedCoarse) else obj.destroy)()


class _ConstrainedCoarse:
    """Python PC of the coarsest solve of the GAMG hierarchy: the LU solve
    of the coarse operator A_c and, while a contact solve runs, the solve
    constrained to keep the coarse space's strongest crack-opening modes
    closed:

        y = A_c^-1 r - W S^-1 W^T r,   W = A_c^-1 C^T,  S = C W,

    C (k x n_c, orthonormal rows) = the right singular vectors of B_a P
    (P: coarse space -> stiffness dofs, the product of GAMG's
    interpolations) whose singular values are at least COARSE_CONSTRAINT_SV
    times the largest: the jumps the multipliers see best. Without it the
    V-cycle's coarse correction opens the crack over its whole length, and
    the band, a few cells wide, closes it again only locally. Symmetric
    positive semidefinite, so the V-cycle stays symmetric (CG)."""

    def __init__(self, amg: PETSc.PC, block0: np.ndarray | None = None):
        """block0: the stiffness dofs GAMG's operator holds (None: all of
        them, in order)."""
        ksp = amg.getMGCoarseSolve()
        self.Ac = ksp.getOperators()[0]
        self.lu = PETSc.PC().create(PETSc.COMM_SELF)
        self.lu.setOperators(self.Ac)
        self.lu.setType(PETSc.PC.Type.LU)
        # As GAMG's own coarse solve: a coarse operator may be singular
        # (rigid modes of a small hierarchy).
        self.lu.setFactorShift(PETSc.Mat.FactorShiftType.INBLOCKS)
        self.lu.setUp()
        ksp.setType(PETSc.KSP.Type.PREONLY)
        pc = ksp.getPC()
        pc.setType(PETSc.PC.Type.PYTHON)
        pc.setPythonContext(self)
        levels = amg.getMGLevels()
        self.interpolations = [amg.getMGInterpolation(level) for level in range(levels - 1, 0, -1)]  # finest first
        self.block0 = block0
        self.C: np.ndarray | None = None
        self.G: np.ndarray | None = None
        # The last constraint's (key, (C, G)): the friction iteration's
        # solves keep the same closed rows (bilateral: all of them), and the
        # dense SVD on the coarse space is then done once.
        self._last: tuple[bytes, tuple] | None = None

    @property
    def rank(self) -> int:
        """The number of constrained coarse modes (0: the plain LU solve)."""
        return 0 if self.C is None else self.C.shape[0]

    def constrain(self, B: PETSc.Mat) -> None:
        """Constrain the coarse solve by the multipliers' rows B (m x n,
        stiffness columns in the solver's basis; the same B as the last
        time: its C and G again)."""
        indptr, indices, data = B.getValuesCSR()
        key = hashlib.sha1(b"".join(np.ascontiguousarray(a).tobytes() for a in (indptr, indices, data))).digest()
        if self._last is not None and self._last[0] == key:
            self.C, self.G = self._last[1]
            return
        self._constrain(B)
        self._last = (key, (self.C, self.G))

    def _constrain(self, B: PETSc.Mat) -> None:
        Bc = B
        if self.block0 is not None:  # (B's columns of GAMG's rows; freed as the products are)
            rows = PETSc.IS().createStride(B.getSize()[0], 0, 1, comm=B.getComm())
            cols = PETSc.IS().createGeneral(self.block0.astype(PETSc.IntType), comm=B.getComm())
            Bc = B.createSubMatrix(rows, cols)
            rows.destroy()
            cols.destroy()
        for P in self.interpolations:
            nxt = Bc.matMult(P)
            if Bc is not B:
                Bc.destroy()
            Bc = nxt
        dense = scipy_from_petsc(Bc).toarray()
        if Bc is not B:
            Bc.destroy()
        _, sv, Vt = np.linalg.svd(dense, full_matrices=False)
        k = int((sv >= COARSE_CONSTRAINT_SV * sv[0]).sum()) if sv.size and sv[0] > 0 else 0
        self.clear()
        if k == 0:
            return
        C = Vt[:k]
        W = np.empty((C.shape[1], k))
        x, y = self.Ac.createVecs()
        for j in range(k):
            x.array[:] = C[j]
            self.lu.apply(x, y)
            W[:, j] = y.array
        x.destroy()
        y.destroy()
        S = C @ W
        # S = C A_c^-1 C^T is symmetric positive definite unless A_c is
        # singular (GAMG's shifted LU then solves it): a pseudo-inverse.
        self.C, self.G = C, W @ np.linalg.pinv(0.5 * (S + S.T), rcond=1e-12, hermitian=True)

    def clear(self) -> None:
        """Back to the plain LU solve (solves without contact)."""
        self.C = self.G = None

    def apply(self, pc: PETSc.PC, x: PETSc.Vec, y: PETSc.Vec) -> None:
        self.lu.apply(x, y)
        if self.C is not None:
            ya = y.array
            ya -= self.G @ (self.C @ ya)

    def free(self) -> None:
        """Free the LU and drop every PETSc object this context holds: the
        coarse PC holding the context does not release it when GAMG is
        destroyed, and wrappers kept here kept the stiffness alive (0.2 GB
        per solve at 1e6 dofs)."""
        self.lu.destroy()
        self.Ac = None
        self.interpolations = []
        self.clear()
        self._last = None


def _factor_band(A11: PETSc.Mat, symmetric: bool = True) -> PETSc.KSP:
    """MUMPS LDL^T of the crack band (symmetric indefinite with multipliers;
    LU if not symmetric: friction's slip rows),
    with solve_checked's checks: a factorisation that runs out of workspace
    (INFOG(1) = -8, -9: delayed pivots of the ill-conditioned tip dofs) is
    retried with more (ICNTL(14)); an error or a null pivot raises."""
    for relax in (20, 100, 400):
        ksp = create_lu_solver(A11, symmetric=symmetric)
        factor_call(ksp, "setMumpsIcntl", 14, relax)
        error = None
        try:
            ksp.setUp()
        except PETSc.Error as e:
            error = e
        info = factor_call(ksp, "getMumpsInfog", 1)
        if info in (-8, -9) and relax < 400:
            ksp.destroy()
            continue
        break
    oom = out_of_memory(ksp, error, "crack band block of the iterative solver", A11.getSize()[0])
    if oom is not None and info not in (-8, -9):
        ksp.destroy()
        raise oom
    null = factor_call(ksp, "getMumpsInfog", 28)
    if error is not None or info < 0 or null > 0:
        ksp.destroy()
        what = (f"MUMPS INFOG(1) = {info} (out of workspace even with ICNTL(14) = 400)" if info in (-8, -9) else
                f"MUMPS INFOG(1) = {info}, {null} null pivot(s)")
        cause = ("the band is too large or too ill-conditioned for the workspace" if info in (-8, -9) else
                 "a piece of the domain next to the crack has no Dirichlet condition, or a contact multiplier "
                 "sees no jump")
        verdict = "could not be factored" if info in (-8, -9) else "is singular"
        raise SolverError(f"the crack band block {verdict} ({what}): {cause}; use solver = 'direct'")
    return ksp
