"""Solving a load path: its increments in order on one assembled matrix.

The matrix is assembled once; each group's right-hand side too (its loads
and its prescribed values, lifted), so an increment costs only the contact
iteration. Frictional contact carries its slip and states from increment to
increment (friction is path-dependent); frictionless contact starts each
increment from the last active set. Under mpirun the distributed matrix
and each group's owned right-hand side are assembled once and every
increment is solved by parallel MUMPS, with contact and friction on the
distributed saddle point (the states, slips and active set carried from
increment to increment are the same on every process), or without contact
by the distributed iterative path (the phantom basis and GAMG set up once).
"""
from __future__ import annotations

import dataclasses
import logging
import time
import typing

import numpy as np

from ..contact.friction import STATE_NAMES, solve_friction
from ..contact.frictionless import (contact_constant, create_contact_system, distributed_saddle, in_basis,
                                   owned_product, solve_frictionless)
from ..model.assembly import assemble_distributed_system_groups, assemble_system_groups
from ..model.distributed import to_local
from ..model.model import create_model
from ..post.solution import Solution, create_solution
from ..errors import InputError
from ..scene.conditions import LoadStep
from ..scene.load_path import Increment, increments, steps
from ..scene.scene import Scene
from ..solvers.checked import condition_number_1norm, record_solves
from ..solvers.choice import (create_distributed_linear_solver, create_linear_solver, to_distributed_solver_basis,
                              to_solver_basis)
from ..solvers.rescaling import from_basis


logger = logging.getLogger(__name__)


def _combine(vectors: dict[str, np.ndarray], factors: dict[str, float], size: int) -> np.ndarray:
    out = np.zeros(size)
    for g, v in vectors.items():
        out += factors.get(g, 0.0) * v
    return out


def _assembled_groups(model, unit) -> tuple:
    """The matrix and each load group's right-hand side in the solver's
    basis, assembled once: (A, {group: b_g}, T, T_mpi, linear, timings).
    Serial: the scene's solver path (T its basis, or None). Under mpirun:
    the distributed matrix and each group's owned entries in the basis of
    the solver path the global sizes choose (create_distributed_linear_solver):
    the direct path (parallel MUMPS), nodally rescaled by T_mpi
    (options.rescale), or the iterative one in the phantom-node basis
    (T_mpi its T, which goes with linear.destroy()); its matrix transformed
    and, on the first solve, its preconditioner set up once for every
    increment or level, as serially."""
    if model.distributed:
        A, rhs, timings = assemble_distributed_system_groups(unit)
        model.num_enriched_cells_integrated = unit.num_enriched_cells_integrated
        linear = create_distributed_linear_solver(unit)
        A, values, T_mpi, t_basis = to_distributed_solver_basis(unit, linear, A, list(rhs.values()))
        T = None
    else:
        T_mpi = None
        A, rhs, timings = assemble_system_groups(unit)
        linear = create_linear_solver(unit)  # Options.solver, as solve.solve (cracklip.solvers)
        A, values, T, t_basis = to_solver_basis(unit, linear, A, list(rhs.values()))
    timings.update(t_basis)
    return A, dict(zip(rhs.keys(), values)), T, T_mpi, linear, timings


def _solved(model, linear, A, A_f, T_mpi, residual_tol: float) -> np.ndarray:
    """Solve A x = A_f (both destroyed with the solution): x in the solver's
    basis (serial; its T applied by the caller), or this process's local
    dofs (mpirun)."""
    x = linear.solve(A, A_f, residual_tol, what="X-FEM stiffness system")
    A_f.destroy()
    if model.distributed:
        return _local(model, T_mpi, x)
    y = x.array.copy()
    x.destroy()
    return y


def _local(model, T_mpi, x) -> np.ndarray:
    """This process's local dofs (owned and ghost, to_local) of a
    distributed solution x in the solver's basis (x destroyed)."""
    x = from_basis(T_mpi, x)
    y = to_local(model.dofs, x)
    x.destroy()
    return y


def solve_path(scene: Scene, condition_number: bool = False) -> list[Solution]:
    """Solve every increment of the scene's load path; return one Solution
    per step (its last increment), each with .factors and .step, the last
    also with .steps (all of them)."""
    t_start = time.perf_counter()
    model = create_model(scene)
    opts = scene.options
    E = scene.material.E
    # In units of E, as solve.solve does (exact scaling with E and the loads).
    unit = dataclasses.replace(model, scene=dataclasses.replace(scene, material=scene.material.scaled(1.0)),
                               bc_values=model.bc_values * E,
                               bc_group_values={g: v * E for g, v in model.bc_group_values.items()})
    A, rhs, T, T_mpi, linear, timings = _assembled_groups(model, unit)
    contact = opts.contact != "none" and bool(model.cracks)
    friction = contact and opts.friction > 0.0
    # The stiffness as the contact solves take it: the solver path builds
    # the saddle point, frictionless or frictional (the direct path from a
    # scipy copy, the iterative one around A, no copy). Under mpirun both
    # border the distributed A itself.
    distributed = model.distributed
    K = None if not contact else A if distributed else linear.stiffness(A)
    physical = cs = None
    if contact:
        physical = create_contact_system(unit)
        cs = in_basis(physical, T if T is not None else T_mpi)  # (B T, B_t T in the solver's basis)
    c = contact_constant(unit)
    n = A.getLocalSize()[0]  # (the model's dofs in serial; this process's owned ones under mpirun)
    m = cs.num_multipliers if cs is not None else 0
    mt = cs.Bt.shape[0] if friction else m  # tangential rows: m in 2D, 2 m in 3D
    s_old = np.zeros(mt)
    state = sign = active = None
    out: list[Solution] = []
    step_list = steps(scene)
    incs = increments(scene)
    iterations: list[int] = []
    t0 = time.perf_counter()
    try:  # the solver's PETSc objects go when the path ends, also when a solve fails
        with record_solves() as solves:
            for inc in incs:
                f = _combine(rhs, inc.factors, n)
                info: dict[str, typing.Any] = {}
                if not contact:
                    A_f = A.createVecRight()
                    A_f.array[:] = f
                    y = _solved(model, linear, A, A_f, T_mpi, opts.residual_tol)
                else:
                    g_n = _combine(cs.g_groups, inc.factors, m)
                    work = dataclasses.replace(cs, g=g_n)
                    if friction:
                        g_t = _combine(cs.gt_groups, inc.factors, mt)
                        y, info = solve_friction(K, f, work, g_n, g_t, s_old, opts, c, state, sign, linear,
                                                 distributed)
                        state, sign = info["state"], info["sign"]
                        s_old = (owned_product(A, cs.Bt, y) if distributed else cs.Bt @ y) - g_t
                    else:
                        saddle = distributed_saddle(A, f, work, opts.residual_tol, linear) if distributed else None
                        y, info = solve_frictionless(K, f, work, opts, c, active, linear, saddle)
                        active = info["active"]
                    iterations.append(int(info["iterations"]))
                    if distributed:  # (y this process's owned dofs: its local ones, owned and ghost)
                        x = A.createVecRight()
                        x.array[:] = y
                        y = _local(model, T_mpi, x)
                if inc.index == opts.load_steps:
                    out.append(_step_solution(model, unit, physical, y, T, E, info, inc, step_list[inc.step],
                                              iterations, timings, solves, linear.name))
                    iterations = []
                    logger.info("load step %d/%d (%s) solved", inc.step + 1, len(step_list), step_list[inc.step].name)
    finally:
        linear.destroy()
    timings["path_solve"] = time.perf_counter() - t0
    if condition_number:
        out[-1].condition = condition_number_1norm(A)
    A.destroy()
    if T_mpi is not None:
        T_mpi.destroy()
    timings["total"] = time.perf_counter() - t_start
    for sol in out:
        sol.timings = {**model.timings, **timings}
        sol.path = out  # every state sees the path (a warning about its minimum load reaches its maximum)
    out[-1].steps = out
    return out


def _step_solution(model, unit, physical, y, T, E, info, inc: Increment, step: LoadStep,
                   iterations: list[int], timings, solves, solver_name: str = "direct") -> Solution:
    u = (y if T is None else T @ y) / E
    contact = {}
    if physical is not None:
        system = dataclasses.replace(
            physical, g=_combine(physical.g_groups, inc.factors, physical.num_multipliers) / E,
            gt=None if physical.Bt is None else _combine(physical.gt_groups, inc.factors, physical.Bt.shape[0]) / E,
            g_groups={k: v / E for k, v in physical.g_groups.items()},
            gt_groups={k: v / E for k, v in physical.gt_groups.items()})
        contact = {"system": system, **{k: (v.copy() if isinstance(v, np.ndarray) else v) for k, v in info.items()},
                   "increment_iterations": list(iterations)}
        contact["iterations"] = int(sum(iterations))
    solver = {"relative_residual": solves[-1]["relative_residual"] if solves else None, "solver": solver_name,
              "solves": list(solves)}
    if model.distributed:
        solver["processes"] = model.V.mesh.comm.size
    sol = create_solution(model, u, dict(timings), {}, contact, solver)
    sol.factors = dict(inc.factors)
    sol.step = {"index": inc.step, "name": step.name, "factors": dict(inc.factors),
                "increments": len(iterations) or 1}
    return sol


class LevelSolver:
    """A scene assembled once and solved at any number of load states: the
    fatigue life's K against load level at one crack geometry.

    solve(states, contact) solves each state (factors per load group, every
    group not named at 0) in the order given: with contact=False linearly
    (lips free to pass through each other: the superposition basis; exact
    wherever the lips stay open), with contact=True with the scene's
    frictionless contact, each state starting from the last one's active
    set. The matrix and each group's load vector are assembled once, as in
    solve_path; every state costs one solve (linear) or its active-set
    iterations (contact). Friction is path-dependent and not taken here.
    Under mpirun the matrix is distributed (parallel MUMPS, or without
    contact the distributed iterative path, set up once for every level)
    and each contact state is solved on the distributed saddle point
    (distributed_saddle): every process takes the same active sets. Call
    close() when done (the solver's PETSc objects)."""

    def __init__(self, scene: Scene):
        if scene.options.friction > 0.0:
            raise InputError("the fatigue life's load levels need frictionless contact: set options.friction = 0 "
                             "(friction makes K depend on the load path, not on the load level alone)")
        self.scene = dataclasses.replace(scene, load_path=None,
                                         options=dataclasses.replace(scene.options, load_steps=1))
        self.model = create_model(self.scene)
        self.E = E = self.scene.material.E
        model = self.model
        self.unit = dataclasses.replace(model, scene=dataclasses.replace(self.scene,
                                                                         material=self.scene.material.scaled(1.0)),
                                        bc_values=model.bc_values * E,
                                        bc_group_values={g: v * E for g, v in model.bc_group_values.items()})
        # (under mpirun the distributed system, each group's owned entries, _assembled_groups' solver path)
        self.A, self.rhs, self.T, self.T_mpi, self.linear, self.timings = _assembled_groups(model, self.unit)
        self.has_contact = self.scene.options.contact != "none" and bool(model.cracks)
        self.K = self.physical = self.cs = None
        self.active = None
        self.solves = 0

    def _contact_system(self):
        if self.cs is None:
            # (under mpirun the distributed saddle takes A itself: no serial copy of the stiffness)
            self.K = self.A if self.model.distributed else self.linear.stiffness(self.A)
            self.physical = create_contact_system(self.unit)  # (collective; whole on every process)
            self.cs = in_basis(self.physical, self.T if self.T is not None else self.T_mpi)
        return self.cs

    def solve(self, states: list[dict[str, float]], contact: bool, names: list[str] | None = None) -> list[Solution]:
        """One Solution per state (its .factors the state's; .step its name)."""
        opts = self.scene.options
        contact = contact and self.has_contact
        n = self.A.getLocalSize()[0]  # (the model's dofs in serial; this process's owned ones under mpirun)
        out = []
        with record_solves() as solves:
            for k, factors in enumerate(states):
                inc = Increment(k, 1, dict(factors))
                f = _combine(self.rhs, factors, n)
                info: dict[str, typing.Any] = {}
                if not contact:
                    A_f = self.A.createVecRight()
                    A_f.array[:] = f
                    y = _solved(self.model, self.linear, self.A, A_f, self.T_mpi, opts.residual_tol)
                    physical = None
                else:
                    cs = self._contact_system()
                    work = dataclasses.replace(cs, g=_combine(cs.g_groups, factors, cs.num_multipliers))
                    y, info = self._contact_level(f, work)
                    self.active = info["active"]
                    physical = self.physical
                name = names[k] if names else f"level {k}"
                sol = _step_solution(self.model, self.unit, physical, y, self.T, self.E, info, inc,
                                     LoadStep(dict(factors), name), [int(info.get("iterations", 1))], self.timings,
                                     solves, self.linear.name)
                out.append(sol)
                self.solves += 1
        return out

    def _contact_level(self, f: np.ndarray, work) -> tuple[np.ndarray, dict]:
        """One state with frictionless contact from the last state's active
        set: (y, info) as solve_frictionless gives them. Under mpirun the
        saddle point is distributed_saddle's (parallel MUMPS; the multipliers
        and the gap alike on every process, so every process takes the same
        active set) and y this process's local dofs."""
        opts, c = self.scene.options, contact_constant(self.unit)
        if not self.model.distributed:
            return solve_frictionless(self.K, f, work, opts, c, self.active, self.linear)
        u, info = solve_frictionless(self.A, f, work, opts, c, self.active,
                                     saddle=distributed_saddle(self.A, f, work, opts.residual_tol, self.linear))
        x = self.A.createVecRight()
        x.array[:] = u
        return _local(self.model, self.T_mpi, x), info

    def close(self) -> None:
        self.linear.destroy()
        self.A.destroy()
        if self.T_mpi is not None:
            self.T_mpi.destroy()


def state_names(codes: np.ndarray) -> list[str]:
    return [STATE_NAMES[int(c)] for c in codes]
