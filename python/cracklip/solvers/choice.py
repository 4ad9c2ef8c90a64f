"""Which checked solver path runs (Options.solver: "auto", "direct", "iterative"),
and the system in that path's basis."""
from __future__ import annotations

import time
import typing

import numpy as np
import scipy.sparse as sp
from petsc4py import PETSc

from ..errors import InputError
if typing.TYPE_CHECKING:
    from ..model.model import XfemModel
    from ..scene.options import Options
from .direct import DirectSolver, LinearSolver
from .distributed_iterative import DistributedIterativeSolver
from .iterative import IterativeSolver
from .rescaling import nodal_transform, rescale_distributed, rescale_matrix, transposed_products


#: Options.solver = "auto": measured on this kind of machine (2 cores,
#: OpenBLAS, medians of 3; demos/bench_solvers.py and the Westergaard scene).
#: Where the enriched dofs are few, MUMPS LDL^T and the iterative path are
#: about as fast up to 1e6 dofs and the iterative one wins beyond: the bench
#: scene (a 0.6-long crack, tip functions on the tip cell only, about 0.1 %
#: enriched dofs; docs/bench/bench_solvers.json) direct / iterative: open
#: crack 1.09 / 1.50 s at 2e5, 6.05 / 6.20 s at 1e6, 31.3 / 25.7 s at 4e6;
#: contact 1.19 / 1.32, 6.03 / 6.69, 32.7 / 29.1 s; and the direct path's
#: memory (2.3 GB per 1e6 dofs with contact, 9.6 GB at 4e6; iterative 0.93
#: and 3.4 GB) nears a 24 GB machine's between 4e6 and 1e7 dofs. A
#: tip-enrichment disk (Westergaard, radius 0.2, vector tip functions, 3.4 %
#: enriched) makes the factorisation dearer and the iterative path wins from
#: 6e4 dofs (0.33 vs 0.59 s at 6.2e4, 1.3 vs 2.2 s at 2e5). So auto goes
#: iterative from AUTO_ITERATIVE_DOFS dofs while the enriched fraction lies
#: in [AUTO_MIN_ENRICHED_FRACTION, AUTO_MAX_ENRICHED_FRACTION], and at any
#: enrichment from AUTO_DIRECT_MAX_DOFS dofs on.
AUTO_ITERATIVE_DOFS = 50_000


AUTO_MIN_ENRICHED_FRACTION = 0.01


AUTO_DIRECT_MAX_DOFS = 2_000_000


#: ... and while enriched dofs are at most this fraction of the dofs: the
#: crack band (all enriched dofs and a ring) is factored, and a large tip
#: enrichment disk slows the Krylov iteration. Westergaard at 2e5 dofs,
#: radius 0.2: vector tip functions (3.4 % enriched) iterative 1.2 s vs
#: direct 1.6 s; scalar ones (12 %) iterative 7.6 s vs direct 6.6 s.
AUTO_MAX_ENRICHED_FRACTION = 0.05


#: The same bound for solids. The factors of a 3D mesh fill far more than a
#: planar one's (MUMPS: 10 KB per dof at 3.4e4 dofs Heaviside-only, 13 KB at
#: 7.6e4 with front functions), so the iterative path, whose crack band is
#: a thin layer, wins on memory at any enrichment and on time up to about
#: 30 %: penny crack, 2 cores, direct / iterative solve and peak memory:
#: 5.9e4 dofs, 21 % enriched 17.6 / 12.6 s, 0.96 / 0.64 GB; 7.6e4, 21 %:
#: 22.8 / 17.6 s, 1.24 / 0.77 GB; 6.9e4, 33 %: 20.6 / 23.1 s, 1.19 / 0.98 GB;
#: 7.6e4, 39 %: 24.7 / 37.1 s, 1.3 / 1.24 GB (docs/speed.md).
AUTO_MAX_ENRICHED_FRACTION_3D = 0.3


def choose_solver(options: "Options", num_dofs: int, num_enriched_dofs: int = 0, gdim: int = 2) -> str:
    """The path Options.solver names for a system of num_dofs stiffness
    dofs, num_enriched_dofs of them enriched, of a part of dimension gdim:
    "direct" or "iterative" ("auto": iterative from AUTO_DIRECT_MAX_DOFS
    on, and from AUTO_ITERATIVE_DOFS on while the enriched fraction lies
    between AUTO_MIN_ENRICHED_FRACTION and AUTO_MAX_ENRICHED_FRACTION
    (AUTO_MAX_ENRICHED_FRACTION_3D for a solid); direct otherwise, and
    always with rescale = "nodal", a direct-solver option)."""
    if options.solver == "auto":
        if options.rescale == "nodal":
            return "direct"
        if num_dofs >= AUTO_DIRECT_MAX_DOFS:
            return "iterative"
        fraction = num_enriched_dofs / max(num_dofs, 1)
        top = AUTO_MAX_ENRICHED_FRACTION_3D if gdim == 3 else AUTO_MAX_ENRICHED_FRACTION
        band = AUTO_MIN_ENRICHED_FRACTION <= fraction <= top
        return "iterative" if num_dofs >= AUTO_ITERATIVE_DOFS and band else "direct"
    if options.solver == "iterative" and options.rescale == "nodal":
        raise InputError("rescale = 'nodal' conditions the matrix for the direct solver; the iterative "
                         "solver uses its own (phantom-node) basis: use rescale = 'none' with "
                         "solver = 'iterative', or solver = 'direct'")
    return options.solver


def to_solver_basis(model: "XfemModel", linear: LinearSolver, A: PETSc.Mat, rhs: typing.Sequence[np.ndarray]
                    ) -> tuple[PETSc.Mat, list[np.ndarray], sp.csr_matrix | None, dict[str, float]]:
    """The system the solver path solves, T^T A T y = T^T b with u = T y:
    in the phantom-node basis for the iterative path, nodally rescaled for
    Options.rescale = "nodal" (direct path), else as assembled (T None).
    Returns (T^T A T, [T^T b for b in rhs], T, {timing key: seconds}). A is
    consumed: reused or destroyed. (solve.solve and load_path.solve_path
    share this step.)"""
    t0 = time.perf_counter()
    if linear.name == "iterative":
        A_t, T = linear.transform(A)  # may reuse A's storage (A_t is A)
        key = "phantom_transform"
    elif model.scene.options.rescale == "nodal":
        T = nodal_transform(model, A)
        A_t = rescale_matrix(A, T)
        key = "rescale"
    else:
        return A, list(rhs), None, {}
    if A_t is not A:
        A.destroy()
    return A_t, [T.T @ v for v in rhs], T, {key: time.perf_counter() - t0}


def create_linear_solver(model: "XfemModel") -> LinearSolver:
    """The solver path for a model (Options.solver, choose_solver)."""
    which = choose_solver(model.scene.options, model.num_dofs, model.gdim * model.layout.num_enriched, model.gdim)
    if which == "direct":
        return DirectSolver()
    return IterativeSolver(model, fallback=model.scene.options.solver == "auto")


def create_distributed_linear_solver(model: "XfemModel") -> LinearSolver:
    """The solver path for one process's part of a distributed model
    (model.distributed): choose_solver on the global sizes (the same answer
    on every process and as serially): DirectSolver (parallel MUMPS) or
    DistributedIterativeSolver."""
    dm = model.dofs
    n = dm.num_global * dm.d
    which = choose_solver(model.scene.options, n, n - model.gdim * model.V.dofmap.index_map.size_global, model.gdim)
    if which == "direct":
        return DirectSolver()
    return DistributedIterativeSolver(model, fallback=model.scene.options.solver == "auto")


def to_distributed_solver_basis(model: "XfemModel", linear: LinearSolver, A: PETSc.Mat,
                                rhs: typing.Sequence[np.ndarray]
                                ) -> tuple[PETSc.Mat, list[np.ndarray], PETSc.Mat | None, dict[str, float]]:
    """to_solver_basis on a distributed model (collective): T^T A T y =
    T^T b, u = T y, with T a distributed PETSc matrix laid out as A: the
    phantom-node basis for the iterative path (T belongs to linear: it goes
    with linear.destroy()), the nodal rescaling for Options.rescale =
    "nodal" (the caller destroys T), else (A, rhs, None, {}). The
    right-hand sides are this process's owned entries. A is consumed:
    reused or destroyed."""
    if linear.name != "iterative":
        return rescale_distributed(model, A, list(rhs))
    t0 = time.perf_counter()
    A_t, basis = linear.transform(A)  # (A itself, changed, when its pattern allows)
    if A_t is not A:
        A.destroy()
    return A_t, transposed_products(basis.T, rhs), basis.T, {"phantom_transform": time.perf_counter() - t0}
