"""Solve a scene: the X-FEM system, or a plain DOLFINx P1 baseline on the same mesh."""
from __future__ import annotations

import dataclasses
import logging
import time

import numpy as np
from petsc4py import PETSc

import dolfinx.fem
import dolfinx.fem.petsc
import ufl

from ..contact.frictionless import solve_contact
from ..errors import InputError, SolverError, checked_keywords
from ..model.assembly import assemble_distributed_system, assemble_system, elasticity_form
from ..model.distributed import to_local
from ..model.model import create_model, enriched_counts
from ..post.solution import Solution, create_solution
from ..scene.mesh_estimate import release_memory
from ..scene.processes import not_parallel
from ..scene.scene import Scene, require_scene
from ..solvers.checked import condition_number_1norm, record_solves, solve_checked
from ..solvers.choice import (create_distributed_linear_solver, create_linear_solver, to_distributed_solver_basis,
                              to_solver_basis)
from ..solvers.rescaling import from_basis
from .load_path import solve_path


logger = logging.getLogger(__name__)


@checked_keywords
def solve(scene: Scene, condition_number: bool = False) -> Solution:
    """Build, assemble and solve the X-FEM model of a scene (a cl.Scene; a scene file's is
    cl.load_scene_file(path).scene) and return its Solution: K by
    .stress_intensity_factors(crack), the lips by .crack_opening(crack) and
    .contact_pressure(crack), fields by .displacement(points), doubts by .warnings.

    condition_number: also estimate the 1-norm condition number of the
    stiffness with constraints applied, raw and Jacobi-scaled (Solution.condition).

    With a load path (Scene.load_path) or friction (path-dependent), the
    steps are solved in order (load_path.solve_path) and the last step's
    Solution is returned; its .steps holds every step's.

    With Options.accuracy > 0 the mesh is refined around the tips level by
    level until the estimated error of every K is below it
    (cracklip.analysis.accuracy.solve_to_accuracy); the finest level's
    Solution is returned, its .error_estimate holds the levels.
    """
    require_scene(scene, "solve")
    if scene.options.accuracy > 0.0:
        # Refinement levels around the tips until K's estimated error is below
        # the target (cracklip.analysis.accuracy); each level solved as usual,
        # its scene keeping the target (its model's checks know the run has one).
        from .accuracy import solve_to_accuracy
        return solve_to_accuracy(scene, scene.options.accuracy, scene.options.accuracy_levels,
                                 lambda sc: _solve_mesh(sc, condition_number))
    return _solve_mesh(scene, condition_number)


def _solve_mesh(scene: Scene, condition_number: bool) -> Solution:
    """solve() on the scene's mesh as it is (one level of an accuracy target)."""
    if scene.mesh.mesh.comm.size > 1:
        return _solve_distributed(scene, condition_number)
    if scene.load_path is not None or scene.options.friction > 0.0:
        return solve_path(scene, condition_number)[-1]
    t_start = time.perf_counter()
    model = create_model(scene)
    # Solve the problem in units of E (E = 1, prescribed displacements times
    # E, u = u_1 / E): the matrix is then the same bit for bit whatever E, so
    # every output scales exactly with E and the loads (an E-scaled matrix
    # differs by round-off that the conditioning amplifies to ~1e-11), and
    # the constraint rows (1 on the diagonal) match the stiffness rows.
    E = scene.material.E
    unit = dataclasses.replace(model, scene=dataclasses.replace(scene, material=scene.material.scaled(1.0)),
                               bc_values=model.bc_values * E,
                               bc_group_values={g: v * E for g, v in model.bc_group_values.items()})
    A, b, timings = assemble_system(unit)
    linear = create_linear_solver(unit)  # Options.solver: direct or iterative (cracklip.solvers)
    A, (b_t,), T, t_basis = to_solver_basis(unit, linear, A, [b.array])
    b.array[:] = b_t
    timings.update(t_basis)
    t0 = time.perf_counter()
    contact = {}
    # The solver's PETSc objects (the iterative path's AMG hierarchy) go
    # when the solve ends, also when it fails.
    try:
        with record_solves() as solves:
            if scene.options.contact != "none" and model.cracks:
                try:
                    u, contact = solve_contact(unit, A, b, transform=T, linear=linear)
                except SolverError as e:
                    linear.destroy()
                    raise _contact_singularity(scene, A, b, e) from None
                contact["system"].g = contact["system"].g / E  # B u = g in the scene's units
                x = A.createVecRight()
                x.array[:] = u
                timings["contact_solve"] = time.perf_counter() - t0
            else:
                x = linear.solve(A, b, scene.options.residual_tol, what="X-FEM stiffness system")
                timings["solve"] = time.perf_counter() - t0
    finally:
        linear.destroy()
    # Relative residual ||A x - b|| / ||b|| of the last solve (the final
    # active set's saddle system with contact) and of every solve.
    solver = {"relative_residual": solves[-1]["relative_residual"] if solves else None,
              "solver": linear.name, "solves": solves}
    condition = {}
    if condition_number:
        t0 = time.perf_counter()
        condition = condition_number_1norm(A)
        timings["condition_number"] = time.perf_counter() - t0
    u = (x.array if T is None else T @ x.array) / E
    A.destroy()
    b.destroy()
    x.destroy()
    release_memory()  # the factors and the AMG hierarchy are gone: their pages back to the system
    timings = {**model.timings, **timings}
    timings["total"] = time.perf_counter() - t_start
    logger.info("solved %d dofs (%d enriched) in %.3f s", model.num_dofs,
                model.gdim * model.layout.num_enriched, timings["total"])
    return create_solution(model, u, timings, condition, contact, solver)


def _solve_distributed(scene: Scene, condition_number: bool) -> Solution:
    """solve() on several processes (mpirun; issue 40 steps 2 and 4): open
    cracks in 2D and 3D and frictionless contact (the saddle point
    distributed, the active set the same on every process); the direct
    solver (parallel MUMPS, also nodally rescaled) or the iterative one
    (Options.solver, choose_solver; solvers.distributed_iterative); a load
    path, with or without contact, and friction by load_path.solve_path on
    the same distributed matrix. The
    Solution holds this process's model and its local displacement (owned
    and ghost nodes); K (Solution.stress_intensity_factors) is summed over
    processes."""
    comm = scene.mesh.mesh.comm
    if condition_number:
        not_parallel("the condition number", comm)
    if scene.load_path is not None or scene.options.friction > 0.0:
        return solve_path(scene)[-1]
    t_start = time.perf_counter()
    model = create_model(scene)
    E = scene.material.E  # in units of E, as solve()
    unit = dataclasses.replace(model, scene=dataclasses.replace(scene, material=scene.material.scaled(1.0)),
                               bc_values=model.bc_values * E,
                               bc_group_values={g: v * E for g, v in model.bc_group_values.items()})
    A, b, timings = assemble_distributed_system(unit)
    model.num_enriched_cells_integrated = unit.num_enriched_cells_integrated
    contacting = scene.options.contact != "none" and bool(model.cracks)
    linear = create_distributed_linear_solver(unit)  # Options.solver on the global sizes
    what = "X-FEM stiffness system"
    contact = {}
    try:
        # options.rescale (direct path) or the phantom-node basis (iterative path; T is linear's)
        A, (b_t,), T, t_basis = to_distributed_solver_basis(unit, linear, A, [b.array])
        b.array[:] = b_t
        timings.update(t_basis)
        with record_solves() as solves:
            t0 = time.perf_counter()
            if contacting:  # the saddle point distributed, the active set alike on every process
                u_owned, contact = solve_contact(unit, A, b, transform=T, linear=linear)
                contact["system"].g = contact["system"].g / E  # B u = g in the scene's units
                x = A.createVecRight()
                x.array[:] = u_owned
                timings["contact_solve"] = time.perf_counter() - t0
            else:  # parallel MUMPS, or the serial iterative path's solver on the global numbering
                x = linear.solve(A, b, scene.options.residual_tol, what=what)
                timings["solve"] = time.perf_counter() - t0
        x = from_basis(T, x)
    finally:
        linear.destroy()
    u = to_local(model.dofs, x) / E
    for o in (A, b, x) + ((T,) if T is not None else ()):
        o.destroy()  # (the phantom basis's T went with linear: destroying it again does nothing)
    release_memory()
    timings = {**model.timings, **timings}
    timings["total"] = time.perf_counter() - t_start
    logger.info("solved %d dofs (%d enriched) in %.3f s", model.dofs.num_global * model.gdim,
                model.gdim * enriched_counts(model)[0], timings["total"])
    solver = {"relative_residual": solves[-1]["relative_residual"] if solves else None,
              "solver": linear.name, "solves": solves, "processes": comm.size}
    return create_solution(model, u, timings, {}, contact, solver)


def _contact_singularity(scene: Scene, A, b, error: SolverError) -> SolverError:
    """The error to raise for a failed contact solve: if the saddle-point
    system is singular but the stiffness alone is not, the multiplier space
    is at fault (B without full row rank), which the message then says."""
    if "singular" not in str(error):
        return error
    try:
        solve_checked(A, b, scene.options.residual_tol, what="stiffness").destroy()
    except SolverError:
        return error  # the stiffness is singular itself: the original cause stands
    if scene.options.multipliers == "naive":
        hint = ("multipliers='naive' puts one P1 multiplier on every node of the cut cells, whose traces "
                "on the crack are linearly dependent; use multipliers='stable'")
    else:
        hint = "the stable space should not be rank-deficient: please report this scene"
    return SolverError(f"{error}. The stiffness alone is regular, so the contact multiplier space "
                       f"({scene.options.multipliers!r}) is singular: its constraints B are not "
                       f"independent ({hint})")


def solve_plain(scene: Scene) -> tuple[np.ndarray, dict[str, float]]:
    """Plain DOLFINx P1 elasticity solve of the scene without its cracks.

    The baseline for benchmarks: DOLFINx creates, assembles (with its
    Dirichlet conditions) and the same checked MUMPS solve runs. Only
    constant tractions and Dirichlet values are supported here. 2D or 3D;
    under mpirun on the distributed mesh (parallel MUMPS).
    Returns (dofs (d num_nodes,), timings): under mpirun this process's
    owned dofs (V's order).
    """
    t_start = time.perf_counter()
    timings: dict[str, float] = {}
    msh = scene.mesh.mesh
    tdim = msh.topology.dim
    V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    msh.topology.create_connectivity(tdim - 1, tdim)
    bcs = []
    for bc in scene.dirichlet:
        if callable(bc.value) or not isinstance(bc.where, (str, int)):
            raise InputError("solve_plain supports constant Dirichlet values on tagged boundaries")
        facets = scene.mesh.facets(bc.where)
        comps = list(range(tdim)) if bc.component is None else [bc.component]
        for c in comps:
            dofs = dolfinx.fem.locate_dofs_topological(V.sub(c), tdim - 1, facets)
            bcs.append(dolfinx.fem.dirichletbc(PETSc.ScalarType(bc.value), dofs, V.sub(c)))
    v = ufl.TestFunction(V)
    ds = ufl.Measure("ds", domain=msh, subdomain_data=scene.mesh.facet_tags)
    L = ufl.inner(dolfinx.fem.Constant(msh, PETSc.ScalarType((0.0,) * tdim)), v) * ufl.dx
    for tr in scene.tractions:
        if callable(tr.value):
            raise InputError("solve_plain supports constant tractions only")
        t = dolfinx.fem.Constant(msh, PETSc.ScalarType(tuple(tr.value)))
        L += ufl.inner(t, v) * ds(scene.mesh.tag_value(tr.where))
    a = elasticity_form(V, scene.material.E_strain, scene.material.nu_strain)
    L = dolfinx.fem.form(L)
    timings["setup"] = time.perf_counter() - t_start

    t0 = time.perf_counter()
    A = dolfinx.fem.petsc.assemble_matrix(a, bcs=bcs)
    A.assemble()
    b = dolfinx.fem.petsc.assemble_vector(L)
    dolfinx.fem.petsc.apply_lifting(b, [a], bcs=[bcs])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    dolfinx.fem.petsc.set_bc(b, bcs)
    timings["assemble"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    x = solve_checked(A, b, scene.options.residual_tol, what="plain P1 system")
    timings["solve"] = time.perf_counter() - t0
    u = x.array.copy()
    for obj in (A, b, x):
        obj.destroy()
    timings["total"] = time.perf_counter() - t_start
    return u, timings
