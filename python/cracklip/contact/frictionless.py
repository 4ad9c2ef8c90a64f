"""Frictionless crack-lip contact with Lagrange multipliers.

The multiplier space (C++) gives the full multipliers and the 0/1
prolongation R (reduced -> full); B_red = R^T B, M_red = R^T M R. The
saddle-point system

    [ K      B^T ] [ u      ]   [ f ]
    [ B      0   ] [ lambda ] = [ g ]

is solved by MUMPS; the contact pressure is p = -lambda (>= 0 in
compression), the weighted normal gap is B u (>= 0 when open). Unilateral
contact: primal-dual active set on the reduced multipliers, a multiplier
active when p_k - c g_k / m_k > 0 (m_k the lumped multiplier mass, c = E / h).
"""
from __future__ import annotations

import dataclasses
import logging
import typing

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from .. import _cracklip
from ..errors import CracklipError, SolverError
from ..model.model import XfemModel
from ..solvers.checked import scipy_from_petsc, solve_checked
from ..solvers.rescaling import times_basis
if typing.TYPE_CHECKING:
    from ..solvers.direct import LinearSolver
from ..scene.processes import gathered, reduced
from ..solvers.saddle import distributed_saddle_matrix, saddle_matrix
from .band import create_band_space, prolongation
from .stabilization import create_stabilization, stabilization_gamma


logger = logging.getLogger(__name__)


class ContactError(CracklipError, RuntimeError):
    """The active set did not settle."""


@dataclasses.dataclass
class ContactSystem:
    """Multiplier space and constraint operators of a model.

    Attributes:
        space: the C++ MultiplierSpace.
        R: (num_full, num_reduced) 0/1 prolongation.
        B: (num_reduced, num_dofs) coupling, Dirichlet columns removed.
        M: (num_reduced, num_reduced) multiplier mass.
        g: (num_reduced,) right-hand side of B u = g (prescribed enriched dofs).
        Bt: tangential coupling int lambda [[v]].t, Dirichlet columns
            removed; None without friction. 2D: (num_reduced, num_dofs), t
            = n turned by -90 degrees; 3D: (2 num_reduced, num_dofs), the
            rows of t1 then those of t2 (the tangent basis of
            cpp/contact/contact_kernels_3d.h).
        gt: (Bt rows,) its right-hand side (zeros without friction).
        g_groups, gt_groups: g and gt of each load group's prescribed values.
        band: the space of the gathered crack band (contact/band.py): the
            whole crack's pieces and groups, the same on every process
            (space is this process's, on its local mesh).
        stabilization: the multipliers' stabilization
            (contact/stabilization.py: D = -S on the closed ones), or None.
    """
    space: typing.Any
    R: sp.csr_matrix
    B: sp.csr_matrix
    M: sp.csr_matrix
    g: np.ndarray
    Bt: typing.Optional[sp.csr_matrix] = None
    gt: typing.Optional[np.ndarray] = None
    g_groups: dict = dataclasses.field(default_factory=dict)
    gt_groups: dict = dataclasses.field(default_factory=dict)
    band: typing.Any = None
    stabilization: typing.Any = None

    def S(self, active: np.ndarray) -> sp.csr_matrix | None:
        """The stabilization's S for the closed multipliers `active`, or None."""
        return None if self.stabilization is None else self.stabilization.matrix(active)

    def stabilized_gap(self, gap: np.ndarray, active: np.ndarray, lam: np.ndarray) -> np.ndarray:
        """The gap the active-set and friction tests compare, B u - g - S_a
        lambda: with the stabilization a closed multiplier's row is B u - S
        lambda = g (contact/stabilization.py), so this is 0 on the closed
        ones, as B u - g is without it."""
        S = self.S(active)
        return gap if S is None else gap - S @ lam

    @property
    def num_multipliers(self) -> int:
        return self.R.shape[1]


def create_multiplier_space(model: XfemModel):
    """The C++ multiplier space of the model's cracks (options.multipliers):
    MultiplierSpace on triangles, MultiplierSpace3D on tetrahedra.

    Pieces at the tips (2D) only with tip enrichment: a Heaviside-only
    crack ends at its last cut cell, whose group absorbs neighbours until it
    sees the full jump over 2/3 of its weight. On tetrahedra the front
    cells' pieces are taken also without front functions (stable space):
    their P0 multipliers ride on interior groups (a group mostly on front
    cells absorbs a neighbour: the 2D rule on the front band), so the
    contact pressure reaches the front and the lip term of K sees it (a
    closed Heaviside-only penny: K_I = 0 instead of -0.3 to -0.5 of the
    pressure's K with free front cells). The naive space keeps them free
    (its nodal multipliers on front cells may see no jump)."""
    opts = model.scene.options
    fronts = opts.enrichment != "none"
    if model.gdim == 2:
        return _cracklip.create_multiplier_space(model.x, model.cells, model.geometries, model.layout,
                                                 opts.multipliers, fronts)
    return _cracklip.create_multiplier_space_3d(model.x, model.cells, model.geometries, model.layout,
                                                opts.multipliers, fronts or opts.multipliers == "stable")


def _full_coupling(model: XfemModel, space, tangential: bool) -> tuple[tuple, tuple, list[tuple]]:
    """COO triplets (rows, cols, values) of the full B and M and of each
    tangential coupling (one in 2D, t1 and t2 in 3D; none without
    tangential)."""
    n = model.scene.options.contact_points
    if model.gdim == 2:
        coo = _cracklip.assemble_coupling(model.x, model.cells, model.layout, model.geometries, space, n,
                                          tangential=tangential)
        return coo[0:3], coo[3:6], [coo[6:9]] if tangential else []
    d = _cracklip.assemble_coupling_3d(model.x, model.cells, model.layout, model.geometries, space, n,
                                       tangential=tangential)
    return d["B"], d["M"], [d["Bt1"], d["Bt2"]] if tangential else []


def create_contact_system(model: XfemModel) -> ContactSystem:
    """Multiplier space and B, M for the model's cracks (options.multipliers);
    with friction (options.friction > 0) also the tangential coupling Bt.

    The groups (reduced multipliers) come from the gathered crack band
    (contact/band.py), the same on any number of processes; the coupling is
    integrated on the process's own space, on its owned cells under MPI,
    and summed over the processes: B, M and g are then whole on every
    process, B's columns the global dofs (model.dofs)."""
    opts = model.scene.options
    space = create_multiplier_space(model)
    nf = space.num_full
    friction = opts.friction > 0.0
    owned = _cracklip.multiplier_space_on_cells(space, model.num_owned_cells) if model.distributed else space
    (br, bc, bv), (mr, mc, mv), tangential = _full_coupling(model, owned, friction)
    used = np.zeros(nf, dtype=bool)
    used[mr] = True
    band = create_band_space(model)
    R = prolongation(model, space, band, used)
    nr = R.shape[1]
    column, n = _columns(model)
    Bf = sp.csr_matrix((bv, (br, column[bc])), shape=(nf, n))
    Mf = sp.csr_matrix((mv, (mr, mc)), shape=(nf, nf))
    B = _summed(model, (R.T @ Bf).tocsr())
    M = _summed(model, (R.T @ Mf @ R).tocsr())
    Bts = [_summed(model, (R.T @ sp.csr_matrix((v, (r, column[c])), shape=(nf, n))).tocsr()) for r, c, v in tangential]
    Bt = (Bts[0] if len(Bts) == 1 else sp.vstack(Bts).tocsr()) if friction else None
    # Dirichlet dofs: move their known values to the right-hand side, per load group.
    bc_dofs, group_values = _dirichlet_columns(model, column)
    fixed = np.zeros(n, dtype=bool)
    fixed[bc_dofs] = True
    g_groups, gt_groups = {}, {}
    for group, values in sorted(group_values.items()):
        ufix = np.zeros(n)
        ufix[bc_dofs] = values
        g_groups[group] = -(B @ ufix)
        if friction:
            gt_groups[group] = -(Bt @ ufix)
    g = sum(g_groups.values(), np.zeros(nr))
    gt = sum(gt_groups.values(), np.zeros(Bt.shape[0] if friction else nr))
    free = sp.diags((~fixed).astype(float))
    B = B @ free
    B.eliminate_zeros()
    if friction:
        Bt = (Bt @ free).tocsr()
        Bt.eliminate_zeros()
    rownorm = np.sqrt(np.asarray(B.multiply(B).sum(axis=1))).ravel()
    dead = np.flatnonzero(rownorm <= 1e-14 * max(rownorm.max(initial=0.0), 1e-300))
    if dead.size:
        raise SolverError(f"{dead.size} contact multiplier(s) see no jump of the displacement (e.g. "
                          f"reduced multiplier {int(dead[0])}): the crack there has no enriched dofs "
                          "(check the enrichment and the Dirichlet conditions near the crack)")
    S = create_stabilization(M, band.group_x, band.group_h, model.scene.material.E,
                             stabilization_gamma(opts.multiplier_stabilization, model.gdim))
    return ContactSystem(space, R, B.tocsr(), M, g, Bt, gt, g_groups, gt_groups, band.space, S)


def in_basis(physical: ContactSystem, T: "sp.spmatrix | PETSc.Mat | None") -> ContactSystem:
    """The contact system on u = T y (a solver path's basis: the nodal
    rescaling, the phantom-node basis): B T and B_t T (solvers.rescaling.
    times_basis; collective for a distributed T), the rest unchanged;
    physical itself without T."""
    if T is None:
        return physical
    return dataclasses.replace(physical, B=times_basis(physical.B, T),
                               Bt=None if physical.Bt is None else times_basis(physical.Bt, T))


def _columns(model: XfemModel) -> tuple[np.ndarray, int]:
    """The column of B of every local dof and the number of columns: the dof
    itself in serial, its global dof under MPI (model.dofs)."""
    if not model.distributed:
        return np.arange(model.num_dofs), model.num_dofs
    dm = model.dofs
    return dm.global_dofs(np.arange(model.num_dofs)), dm.num_global * dm.d


def _summed(model: XfemModel, A: sp.csr_matrix) -> sp.csr_matrix:
    """Collective: the sum of every process's A (A in serial)."""
    if not model.distributed:
        return A
    coo = A.tocoo()
    r, c, v = gathered(model.V.mesh.comm, [coo.row, coo.col, coo.data])
    return sp.csr_matrix((v, (r, c)), shape=A.shape)


def _dirichlet_columns(model: XfemModel, column: np.ndarray) -> tuple[np.ndarray, dict]:
    """Collective: the prescribed dofs as columns of B and each load group's
    values there (under MPI every process's, gathered)."""
    if not model.distributed:
        return model.bc_dofs, model.bc_group_values
    comm = model.V.mesh.comm
    cols = column[model.bc_dofs]
    ok = cols >= 0
    groups = sorted(set().union(*comm.allgather(set(model.bc_group_values))))
    zero = np.zeros(len(cols))
    parts = gathered(comm, [cols[ok]] + [np.asarray(model.bc_group_values.get(k, zero))[ok] for k in groups])
    dofs, first = np.unique(parts[0], return_index=True)  # (a dof prescribed on its owner and its ghosts)
    return dofs, {k: v[first] for k, v in zip(groups, parts[1:])}


def solve_saddle(K: "sp.csr_matrix | PETSc.Mat", f: np.ndarray, cs: ContactSystem, active: np.ndarray,
                 residual_tol: float, linear: "LinearSolver | None" = None,
                 x0: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Solve with the constraints of the active multipliers; inactive ones are 0.

    K: the stiffness as linear.stiffness() gives it (scipy CSR without
    linear); linear: the solver path (cracklip.solvers; default:
    solve_checked's MUMPS LU, as the load-path and friction solvers use),
    which also builds the saddle-point matrix; x0: an
    initial guess (u, lambda) for an iterative path (the previous active
    set's solution)."""
    m = cs.num_multipliers
    if cs.space.kind == "naive":
        check_constraint_rank(cs.B[np.flatnonzero(active)])
    S = cs.S(active)
    A = saddle_matrix(K, cs.B, active, S) if linear is None else linear.saddle_matrix(K, cs.B, active, S)
    b = PETSc.Vec().createWithArray(np.concatenate([f, np.where(active, cs.g, 0.0)]), comm=PETSc.COMM_SELF)
    what = "contact saddle-point system"
    if linear is None:
        x = solve_checked(A, b, residual_tol, what=what)
    else:
        x = linear.solve(A, b, residual_tol, what=what, x0=x0)
    sol = x.array.copy()
    A.destroy()
    b.destroy()
    x.destroy()
    return sol[:-m] if m else sol, sol[-m:] if m else np.zeros(0)


#: Relative singular value of the active constraints B below which they are
#: dependent: round-off leaves 1e-18 .. 1e-16 of the largest on the naive
#: space's exact dependencies (gmsh meshes of the block, Mesh.RandomSeed 1 to
#: 4), its smallest genuine one was 4e-8.
RANK_TOL = 1e-12


def check_constraint_rank(B: sp.csr_matrix) -> None:
    """Raise SolverError if the rows of B (the active multipliers'
    constraints) are linearly dependent. MUMPS' null-pivot detection alone
    misses a dependency that round-off leaves a tiny nonzero pivot (the naive
    space's on most meshes: the system was then solved with an arbitrary
    multiplier component). Dense SVD: for the naive space only, whose
    multipliers are few (a comparison with the paper), not the stable one."""
    if B.shape[0] == 0:
        return
    cols = np.unique(B.indices)
    s = np.linalg.svd(B[:, cols].toarray(), compute_uv=False)
    dependent = int(np.sum(s <= RANK_TOL * s[0])) + max(0, B.shape[0] - s.size)
    if dependent:
        raise SolverError(f"the contact saddle-point system is singular: the {B.shape[0]} active contact "
                          f"constraints have {dependent} linear dependenc{'y' if dependent == 1 else 'ies'} "
                          f"(smallest singular value {s[-1] / s[0]:.1e} of the largest)")


class _VisitedSets:
    """Active sets met so far. Each iteration depends only on its active set,
    so meeting one again means the iteration cycles for ever: stop at once
    instead of running into the iteration limit."""

    def __init__(self, start: np.ndarray):
        self._first = {start.tobytes(): 0}

    def first_visit(self, key: bytes) -> int | None:
        """The iteration that first met this set (0: the start), or None."""
        return self._first.get(key)

    def visit(self, active: np.ndarray, it: int, history: list[int]) -> None:
        key = active.tobytes()
        if key in self._first:
            k = self._first[key]
            raise ContactError(f"the active set cycles: iteration {it} gives the set of "
                               f"{'the start' if k == 0 else f'iteration {k}'} again (period {it - k}; active "
                               f"counts per iteration: {history}); the primal-dual active set method cannot "
                               "settle here: refine the mesh near the crack, or use contact='bilateral' if "
                               "the crack stays closed")
        self._first[key] = it


def contact_constant(model: XfemModel) -> float:
    """c = E / h of the active-set tests (a stiffness per length: pressure
    minus c times the mean gap)."""
    return model.scene.material.E / model.h


def solve_contact(model: XfemModel, A: PETSc.Mat, b: PETSc.Vec,
                  transform: sp.spmatrix | None = None,
                  linear: "LinearSolver | None" = None) -> tuple[np.ndarray, dict]:
    """Solve the contact problem on the assembled stiffness A (constraints
    applied) and load b. Returns (u, info) with info: system, lambda (reduced),
    active, iterations, history.

    transform: if A and b are rescaled (T^T K T, T^T f), the T: the
    constraints act on u = T y, the returned u is y, info["system"] keeps
    the unscaled B. Under mpirun A is distributed, T too (solvers.choice.
    to_distributed_solver_basis) and u this process's owned entries of y.
    linear: the solver path of every saddle-point solve (cracklip.solvers;
    default: solve_checked's MUMPS LU; under mpirun the distributed
    iterative path if given, else parallel MUMPS)."""
    physical = create_contact_system(model)
    cs = in_basis(physical, transform)
    if model.distributed:
        saddle = distributed_saddle(A, b.array_r, cs, model.scene.options.residual_tol, linear)
        u, info = solve_frictionless(A, b.array_r.copy(), cs, model.scene.options, contact_constant(model),
                                     saddle=saddle)
        info["system"] = physical
        return u, info
    K = scipy_from_petsc(A) if linear is None else linear.stiffness(A)
    u, info = solve_frictionless(K, b.array.copy(), cs, model.scene.options,
                                 contact_constant(model), linear=linear)
    info["system"] = physical
    return u, info


def distributed_saddle(A: PETSc.Mat, f: np.ndarray, cs: ContactSystem, residual_tol: float,
                       linear: "LinearSolver | None" = None):
    """The saddle solve of solve_frictionless on several processes: A the
    distributed stiffness (constraints applied; in the basis of linear, the
    solver path, if given: the iterative one's phantom-node basis), f this
    process's owned entries of the load, cs whole on every process
    (create_contact_system, in A's basis). Returns solve(active, x0) -> (u,
    lambda, gap): u this process's owned dofs, lambda and the gap B u - g
    the same on every process (the multipliers broadcast by the process
    holding them, the gap summed over the processes' owned dofs and
    broadcast by rank 0: solve_bordered, owned_product), so every process
    takes the same active set."""

    # The direct path factors it by MUMPS LU (solve_checked's default, as
    # serially); the iterative one takes it as symmetric (CG).
    iterative = linear is not None and linear.name == "iterative"

    def solve(active: np.ndarray, x0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if cs.space.kind == "naive":
            check_constraint_rank(cs.B[np.flatnonzero(active)])
        S = distributed_saddle_matrix(A, cs.B, active, cs.S(active))
        u, lam = solve_bordered(S, f, np.where(active, cs.g, 0.0), residual_tol, "contact saddle-point system",
                                symmetric=iterative, linear=linear if iterative else None, x0=x0)
        return u, lam, owned_product(A, cs.B, u) - cs.g
    return solve


def solve_bordered(S: PETSc.Mat, f: np.ndarray, rhs: np.ndarray, residual_tol: float, what: str,
                   symmetric: bool = False, linear: "LinearSolver | None" = None, x0: np.ndarray | None = None,
                   contact_points: int | None = None, rtol: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Collective: solve the distributed [K C^T; rows] (solvers/saddle.py
    bordered_matrix) with the right-hand side [f; rhs] (f this process's
    owned entries, rhs the multiplier rows', whole on every process) by
    parallel MUMPS, or by linear (the solver path: the distributed
    iterative one, from x0 = (this process's owned u, every multiplier)
    if given; contact_points sizes its band and rtol loosens its Krylov
    tolerance, as LinearSolver.solve).
    Returns (u, lambda): u this process's owned dofs, the multipliers on
    every process (broadcast by the last process, which holds their rows)."""
    comm = S.getComm().tompi4py()
    holder = comm.size - 1
    n = len(f)
    b = S.createVecLeft()
    b.array[:n] = f
    if comm.rank == holder:
        b.array[n:] = rhs
    if linear is None:
        x = solve_checked(S, b, residual_tol, what=what, symmetric=symmetric)
    else:
        start = None if x0 is None else x0[:n] if comm.rank != holder else x0
        x = linear.solve(S, b, residual_tol, what=what, x0=start, symmetric=symmetric,
                         contact_points=contact_points, rtol=rtol)
    u = x.array_r[:n].copy()
    lam = comm.bcast(x.array_r[n:].copy() if comm.rank == holder else None, root=holder)
    for o in (S, b, x):
        o.destroy()
    return u, lam


def owned_product(A: PETSc.Mat, C: sp.csr_matrix, u: np.ndarray) -> np.ndarray:
    """Collective: C u for C whole on every process (columns A's global
    dofs) and u this process's owned dofs of A: each process's columns
    times its u, summed, broadcast by rank 0 (the same bits on every
    process, whatever order the sum took)."""
    comm = A.getComm().tompi4py()
    lo, hi = A.getOwnershipRange()
    return comm.bcast(reduced(C[:, lo:hi] @ u, "SUM", comm), root=0)


def solve_frictionless(K: "sp.csr_matrix | PETSc.Mat", f: np.ndarray, cs: ContactSystem, opts,
                       c: float, active: np.ndarray | None = None,
                       linear: "LinearSolver | None" = None, saddle=None) -> tuple[np.ndarray, dict]:
    """Frictionless contact on the stiffness K (constraints applied; as
    linear.stiffness() gives it, scipy CSR without linear), load f
    and the constraints B u = cs.g: bilateral (all multipliers active) or
    unilateral by the primal-dual active set, a multiplier active when its
    pressure exceeds c times its mean gap. active: the starting set (default
    options.active_set_start). linear: the solver path of every
    saddle-point solve (default: solve_checked's MUMPS LU). saddle: the solve
    itself, solve(active, x0) -> (u, lambda, gap B u - g) (default: by
    solve_saddle; under MPI distributed_saddle's). Returns (u, info: lambda,
    active, iterations, history)."""
    m = cs.num_multipliers
    if saddle is None:
        def saddle(act: np.ndarray, x0: np.ndarray | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            u, lam = solve_saddle(K, f, cs, act, opts.residual_tol, linear, x0)
            return u, lam, cs.B @ u - cs.g
    if opts.contact == "bilateral":
        active = np.ones(m, dtype=bool)
        u, lam, _ = saddle(active, None)
        return u, {"lambda": lam, "active": active, "iterations": 1, "history": [m]}
    if active is None:
        active = np.full(m, opts.active_set_start == "closed")
    lumped = np.asarray(cs.M.sum(axis=1)).ravel()
    history = []
    seen = _VisitedSets(active)
    x0 = None
    for it in range(1, opts.max_active_set_iterations + 1):
        u, lam, gap = saddle(active, x0)       # gap: weighted normal gap (>= 0 open)
        gap = cs.stabilized_gap(gap, active, lam)
        x0 = np.concatenate([u, lam])
        pressure = -lam                        # >= 0 in compression
        new_active = pressure - c * gap / lumped > 0.0
        history.append(int(new_active.sum()))
        logger.info("active set iteration %d: %d of %d multipliers active", it, new_active.sum(), m)
        if np.array_equal(new_active, active):
            return u, {"lambda": lam, "active": active, "iterations": it, "history": history}
        seen.visit(new_active, it, history)
        active = new_active
    raise ContactError(f"the active set did not settle in {opts.max_active_set_iterations} iterations "
                       f"(active counts per iteration: {history}); raise options.max_active_set_iterations "
                       "or check that the load keeps the crack partly closed")
