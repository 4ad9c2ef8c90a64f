"""The blocked-system recipe: one PETSc matrix over standard and enriched dofs.

Order of the unknowns: the DOLFINx P1 vector dofs (node i: d i + c, d the
space dimension, c < d), then the enriched pseudo-nodes (pseudo-node k:
d (num_nodes + k) + c). The matrix has block size d and is preallocated with
every coupling; DOLFINx
assembles the standard block into it on the whole mesh, the C++ kernels add
the enriched blocks on the enriched cells only, then Dirichlet rows and
columns are eliminated symmetrically (with lifting of the load).
"""
from __future__ import annotations

import time

import numpy as np
from petsc4py import PETSc

import dolfinx.fem
import dolfinx.fem.petsc
import ufl

from . import distributed
from ..scene.processes import reduced
from .loads import assemble_loads
from .xfem_model import XfemModel


def elasticity_form(V, E: float, nu: float):
    """Stiffness form a(u, v) = int sigma(u) : eps(v): plane strain on a 2D
    space (plane stress: pass Material.E_strain, Material.nu_strain),
    isotropic elasticity on a 3D one."""
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    mu = E / (2.0 * (1.0 + nu))
    lmbda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))

    def eps(w):
        return ufl.sym(ufl.grad(w))

    def sigma(w):
        return 2.0 * mu * eps(w) + lmbda * ufl.tr(eps(w)) * ufl.Identity(V.mesh.geometry.dim)

    return dolfinx.fem.form(ufl.inner(sigma(u), eps(v)) * ufl.dx)


def create_matrix(model: XfemModel) -> PETSc.Mat:
    """Preallocated AIJ matrix (block size = the space dimension) with every
    standard/enriched coupling."""
    d = model.gdim
    indptr, indices = model.crack_type.sparsity(model.cells, model.layout)
    n = model.num_dofs
    A = PETSc.Mat().createAIJ((n, n), bsize=d, csr=(indptr, indices), comm=PETSc.COMM_SELF)
    lgmap = PETSc.LGMap().create(np.arange(n // d, dtype=PETSc.IntType), bsize=d,
                                 comm=PETSc.COMM_SELF)
    A.setLGMap(lgmap, lgmap)
    A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, True)
    return A


def material_constants(model: XfemModel) -> tuple[float, float]:
    """(E, nu) of the kernels: the plane-strain pair of the material
    (Material.E_strain, nu_strain: plane stress maps onto it in 2D; a 3D
    part is in "plane strain", the pair is its E and nu)."""
    mat = model.scene.material
    return mat.E_strain, mat.nu_strain


def assemble_standard_block(model: XfemModel, A: PETSc.Mat) -> None:
    """Add the standard (uncracked P1) stiffness into A, assembled by DOLFINx;
    with MeshData.cache_standard_block the block is kept as CSR and copied
    into the next matrices of the same mesh and material (crack growth)."""
    mesh = model.scene.mesh
    key = material_constants(model)
    cached = mesh.standard_blocks.get(key) if mesh.cache_standard_block else None
    if cached is not None:
        ip, indices, data = cached
        rows = A.getSize()[0]  # the enriched rows take nothing from the standard block
        ip = np.concatenate([ip, np.full(rows + 1 - len(ip), ip[-1], dtype=ip.dtype)])
        A.setValuesCSR(ip, indices, data, addv=PETSc.InsertMode.ADD_VALUES)
        return
    a = elasticity_form(model.V, *key)
    dolfinx.fem.petsc.assemble_matrix(A, a)
    if mesh.cache_standard_block:
        A.assemble()
        n = model.gdim * model.layout.num_std_nodes
        indptr, indices, data = A.getValuesCSR()
        rows = np.repeat(np.arange(len(indptr) - 1), np.diff(indptr))
        keep = (rows < n) & (indices < n)
        counts = np.bincount(rows[keep], minlength=n)
        ip = np.concatenate([[0], np.cumsum(counts)]).astype(PETSc.IntType)
        mesh.standard_blocks = {key: (ip, indices[keep].astype(PETSc.IntType), data[keep].copy())}


def assemble_system(model: XfemModel) -> tuple[PETSc.Mat, PETSc.Vec, dict[str, float]]:
    """Assemble the full X-FEM system with Dirichlet conditions applied.

    Returns (A, b, timings); Dirichlet rows/columns are replaced by identity,
    b carries the lifted load and the prescribed values, every load group at
    factor 1.
    """
    A, loads, timings = assemble_system_groups(model)
    b = A.createVecRight()
    b.array[:] = sum(loads.values(), np.zeros(model.num_dofs))
    return A, b, timings


def assemble_system_groups(model: XfemModel) -> tuple[PETSc.Mat, dict[str, np.ndarray], dict[str, float]]:
    """The X-FEM matrix with Dirichlet conditions applied and the right-hand
    side of every load group (loads and prescribed values of that group,
    lifted): b = sum_g factor_g b_g solves the scene at those factors.

    Returns (A, {group: b_g (num_dofs,)}, timings).
    """
    timings = {}
    t0 = time.perf_counter()
    A = create_matrix(model)
    timings["sparsity"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    assemble_standard_block(model, A)
    timings["assemble_standard"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    E, nu = material_constants(model)
    model.num_enriched_cells_integrated = model.crack_type.assemble_stiffness(A, model, E, nu)
    A.assemble()
    timings["assemble_enriched"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    loads = assemble_loads(model)
    groups = set(loads) | {g for g, v in model.bc_group_values.items() if np.any(v)}
    out: dict[str, np.ndarray] = {}
    g, Ag = A.createVecRight(), A.createVecRight()
    for group in sorted(groups):
        b = loads.get(group, np.zeros(model.num_dofs)).copy()
        values = model.bc_group_values.get(group, np.zeros(len(model.bc_dofs)))
        if np.any(values):
            # Lifting: b - A g over the free rows, the prescribed values on the constrained ones.
            g.set(0.0)
            g.array[model.bc_dofs] = values
            A.mult(g, Ag)
            b -= Ag.array
        b[model.bc_dofs] = values
        out[group] = b
    for v in (g, Ag):
        v.destroy()
    A.zeroRowsColumns(model.bc_dofs, diag=1.0)
    timings["load_and_constraints"] = time.perf_counter() - t0
    return A, out, timings


def assemble_distributed_system(model: XfemModel) -> tuple[PETSc.Mat, PETSc.Vec, dict[str, float]]:
    """assemble_system on one process's part of a distributed model: the
    matrix of assemble_distributed_system_groups and the right-hand side of
    every load group at factor 1, summed (a distributed vector laid out as
    A's columns)."""
    A, loads, timings = assemble_distributed_system_groups(model)
    b = A.createVecRight()
    b.array[:] = sum(loads.values(), np.zeros(b.getLocalSize()))
    return A, b, timings


def assemble_distributed_system_groups(model: XfemModel) -> tuple[PETSc.Mat, dict[str, np.ndarray], dict[str, float]]:
    """assemble_system_groups on one process's part of a distributed model
    (model.distributed; collective): the matrix over the global numbering
    (model.dofs), DOLFINx's standard block and the kernels' enriched blocks
    on the owned cells, the Dirichlet rows and columns of the owned dofs
    replaced by identity; per load group its right-hand side (the group's
    loads on the owned cells and facets summed over processes, its
    prescribed values lifted) as this process's owned entries of A's
    column layout (A.createVecRight().array)."""
    dm = model.dofs
    comm = model.V.mesh.comm
    timings = {}
    t0 = time.perf_counter()
    A = distributed.create_matrix(dm, model.crack_type.sparsity(model.cells, model.layout))
    timings["sparsity"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    E, nu = material_constants(model)
    dolfinx.fem.petsc.assemble_matrix(A, elasticity_form(model.V, E, nu))
    timings["assemble_standard"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    model.num_enriched_cells_integrated = model.crack_type.assemble_stiffness(A, model, E, nu)
    A.assemble()
    timings["assemble_enriched"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    loads = assemble_loads(model)
    rows = dm.global_dofs(model.bc_dofs)
    mine = dm.owned(rows)
    rows = rows[mine].astype(PETSc.IntType)
    # every process the same groups, in the same order (the collective calls below)
    groups = sorted(set().union(*comm.allgather(set(loads) | {g for g, v in model.bc_group_values.items()
                                                              if np.any(v)})))
    out: dict[str, np.ndarray] = {}
    g, Ag = A.createVecRight(), A.createVecRight()
    for group in groups:
        b = distributed.vector_from_local(dm, A, loads.get(group, np.zeros(model.num_dofs)))
        values = np.asarray(model.bc_group_values.get(group, np.zeros(len(model.bc_dofs))), dtype=float)[mine]
        if reduced(bool(np.any(values)), "LOR", comm):
            # Lifting: b - A g over the free rows, the prescribed values on the constrained ones.
            g.set(0.0)
            g.setValues(rows, values)
            g.assemble()
            A.mult(g, Ag)
            b.axpy(-1.0, Ag)
        b.setValues(rows, values)
        b.assemble()
        out[group] = b.array.copy()
        b.destroy()
    for v in (g, Ag):
        v.destroy()
    A.zeroRowsColumns(rows, diag=1.0)
    timings["load_and_constraints"] = time.perf_counter() - t0
    return A, out, timings
