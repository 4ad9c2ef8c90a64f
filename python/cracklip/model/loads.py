"""The load vector of a model: every load of a scene against every basis
function, on triangles and tetrahedra alike (the kernels of the cells
through model.crack_type, cracklip.model.cracks).

- ``assemble_load(model)``: boundary tractions (constant, f(x), or sigma n
  of a stress field), point forces, a body force, an initial stress
  and pressures on the crack lips, on standard and enriched dofs.
- Tractions: one facet quadrature for standard and enriched dofs, the
  facets split where a crack crosses them; a stress field's traction is
  sigma(x) n with the outward unit normal n of the boundary (2D: of the
  nearest boundary facet, ``boundary_normals``; 3D: of the facet itself).
- ``assemble_body_force(model, force)`` and ``assemble_initial_stress(model,
  field)``: int f . phi_j and -int sigma_0 : eps(phi_j) over the cracked
  part. Standard dofs: per cell, exactly for a linear sigma_0 (a degree-4
  rule for a callable, model.crack_type.cell_rule); enriched dofs: the
  stiffness's quadrature in the enriched cells, raised to the crack type's
  LOAD_DEGREE (2D: 4; C++ assemble_cell_load). The lips need no term of
  their own: the enriched functions jump there, so -int sigma_0 : eps(phi_j)
  already holds the lip traction sigma_0 n.
- ``lip_pressure(crack, x)`` and ``assemble_lip_pressure(model, crack)``: a
  pressure p on both lips, the load int p [[phi_j]] . n over the lips.
- Under mpirun (a distributed model) each process integrates its owned
  cells, facets and lip points only (each once): its vector is a part, the
  processes' parts sum to the load (model.distributed.vector_from_local).
"""
from __future__ import annotations

import typing

import numpy as np

from ..errors import InputError
from ..scene.cell_size import edge_pairs
from ..scene.processes import agree, reduced, total
from ..scene.stress_field import LinearStress, evaluate_stress, tensor_to_voigt


def traction_values(tr, points: np.ndarray, stress: typing.Callable[[np.ndarray], np.ndarray],
                    normals: typing.Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """t (n, d) of a Traction at boundary points (n, d), in 2D and 3D: sigma n
    if it is given by a stress (`stress(points)`: its checked sigma (n, d, d);
    `normals(points)`: the outward unit normals, only called then), else its
    value, a function of the points or a constant vector."""
    d = points.shape[1]
    if tr.stress is not None:
        t = np.einsum("nij,nj->ni", stress(points), normals(points))
    elif callable(tr.value):
        t = np.asarray(tr.value(points), dtype=float)
        if t.shape != (len(points), d):
            raise InputError(f"traction on {tr.where!r}: its value function returned shape {t.shape} "
                             f"for points of shape {points.shape}; it must return (n, {d}) "
                             f"({', '.join(('t_x', 't_y', 't_z')[:d])})")
    else:
        t = np.broadcast_to(np.asarray(tr.value, dtype=float).reshape(1, d), (len(points), d))
    if not np.all(np.isfinite(t)):
        raise InputError(f"traction on {tr.where!r} evaluates to NaN or infinity")
    return t


def _boundary_facets(model, where) -> tuple[np.ndarray, np.ndarray]:
    """(cells, local facet indices) of the boundary facets of a tag."""
    msh = model.scene.mesh.mesh
    tdim = msh.topology.dim
    facets = model.scene.mesh.facets(where)
    if total(facets.size, msh.comm) == 0:
        raise InputError(f"traction boundary {where!r} has no facets")
    msh.topology.create_connectivity(tdim - 1, tdim)
    msh.topology.create_connectivity(tdim, tdim - 1)
    f2c = msh.topology.connectivity(tdim - 1, tdim)
    c2f = msh.topology.connectivity(tdim, tdim - 1).array.reshape(-1, tdim + 1)
    fcells = f2c.array[f2c.offsets[facets]].astype(np.int32)
    flocal = np.argmax(c2f[fcells] == facets[:, None], axis=1).astype(np.int32)
    return fcells, flocal


def assemble_tractions(model, group: str | None = None) -> np.ndarray:
    """int t . phi_j over the loaded boundaries (one facet quadrature for
    standard and enriched dofs, split where a crack crosses a facet); only
    the tractions of `group` if given."""
    scene = model.scene
    kind = model.crack_type
    b = np.zeros(model.num_dofs)
    for tr in scene.tractions:
        if group is not None and tr.group != group:
            continue
        fcells, flocal = _boundary_facets(model, tr.where)
        if model.distributed:  # each facet once: on the process owning its cell
            keep = model.owned_cells_only(fcells)
            fcells, flocal = fcells[keep], flocal[keep]
        fb = kind.facet_basis(model, fcells, flocal, scene.options.facet_degree)
        t = traction_values(tr, fb["points"], lambda p: evaluate_stress(tr.stress, p, f"traction on {tr.where!r}"),
                            lambda p: kind.facet_normals(model, tr.where, fb))
        q, dof, val = fb["entry_point"], fb["entry_dof"], fb["entry_value"]
        np.add.at(b, dof, fb["weights"][q] * np.einsum("ij,ij->i", val, t[q]))
    return b


def assemble_point_forces(model, group: str | None = None) -> np.ndarray:
    """Each force on the standard dofs of the node nearest to its point (every
    enriched function vanishes at the nodes: the enrichment is shifted);
    only the forces of `group` if given. Under mpirun (collective) the
    nearest owned node of all processes takes it, on its owner (whose patch
    of cells is whole there; a tie goes to the lowest rank)."""
    b = np.zeros(model.num_dofs)
    if not model.scene.point_forces:
        return b
    d = model.gdim
    comm = model.comm
    n_own = model.V.dofmap.index_map.size_local if comm is not None else len(model.x)
    x = model.x[:n_own]
    scale = float(np.ptp(x, axis=0).max()) if n_own else 0.0
    if comm is not None:
        scale = float(reduced(scale, "MAX", comm))
    for k, pf in enumerate(model.scene.point_forces):
        if group is not None and pf.group != group:
            continue
        dist = np.linalg.norm(x - np.asarray(pf.point), axis=1)
        node = int(np.argmin(dist)) if n_own else -1
        mine = comm is None or min(comm.allgather((float(dist[node]) if n_own else np.inf, comm.rank)))[1] == comm.rank
        error = None
        if mine:
            edge = largest_edge_at(model, node)
            lip = crack_through_node(model, node, edge, scale)
            if dist[node] > max(edge, 1e-12 * scale):
                error = InputError(f"point force {k} (loads.point_forces[{k}]) at {list(pf.point)}: the nearest "
                                   f"mesh node {model.x[node].tolist()} is {dist[node]:.3g} away, more than an "
                                   f"element ({edge:.3g}); put the point on the part")
            elif lip is not None:
                error = InputError(
                    f"point force {k} (loads.point_forces[{k}]) at {list(pf.point)} acts on the mesh node "
                    f"{model.x[node].tolist()}, which lies on {lip}: a force there loads one lip or the other "
                    "depending on the mesh, not the one meant (and two opposite forces there cancel); to load "
                    "a lip, put the point off the crack on that lip's side by a fraction of an element "
                    f"({edge:.3g}) and give that position a mesh node (a refinement point there, or "
                    "mesh.kind = \"geometry\"), or use cracks[].pressure")
            else:
                b[d * node:d * node + d] += pf.value
        if comm is not None:
            agree(error, comm)
        elif error is not None:
            raise error
    return b


def largest_edge_at(model, node: int) -> float:
    """The longest edge of the cells around a node (the element size a point
    load or support there is measured against)."""
    ea, eb = edge_pairs(model.cells.shape[1])
    cells = model.cells[np.any(model.cells == node, axis=1)]
    return float(np.linalg.norm(model.x[cells[:, eb]] - model.x[cells[:, ea]], axis=2).max())


def crack_through_node(model, node: int, edge: float, scale: float) -> str | None:
    """The crack (as messages name it) whose lips meet at `node` (2D: a node
    on the crack's polyline, snapped onto it or lying on it, other than at a
    tip), else None."""
    if model.gdim != 2:
        return None
    p = model.x[node, :2]
    tol = max(2.0 * model.scene.options.snap_tol * edge, 1e-12 * scale)
    for cm in model.cracks:
        if not (node < len(cm.phi) and abs(cm.phi[node]) <= 1e-12 * scale):
            continue
        pts = np.asarray(cm.crack.points, dtype=float)
        a, d = pts[:-1], np.diff(pts, axis=0)
        t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
        on = np.linalg.norm(a + t[:, None] * d - p, axis=1).min() <= tol
        tips = pts[[0, -1]][np.asarray(cm.tips, dtype=bool)]
        if on and not np.any(np.linalg.norm(tips - p, axis=1) <= tol):
            return f"crack '{cm.crack.name}'"
    return None


def _enriched_points(model) -> dict:
    """Quadrature points of the enriched cells (cell, ref, x, weight, side):
    the stiffness's rules, at least the crack type's LOAD_DEGREE."""
    cache = model.__dict__.get("_enriched_points_cache")
    if cache is None:
        cells = np.asarray(model.layout.cells, dtype=np.int32)
        cells = cells[model.owned_cells_only(cells)]  # under MPI each cell once: on its owner
        cache = model.crack_type.enriched_cell_points(model, cells, model.crack_type.LOAD_DEGREE)
        model._enriched_points_cache = cache
    return cache


def _cell_loads(model, force: np.ndarray | None, stress_field) -> np.ndarray:
    """int f . phi_j - int sigma_0 : eps(phi_j) for every dof (standard:
    per cell in numpy; enriched: C++ on the enriched cells' quadrature)."""
    b = np.zeros(model.num_dofs)
    d = model.gdim
    nv = d + 1
    cells = model.cells if not model.distributed else model.cells[:model.num_owned_cells]  # each cell once
    if force is not None:
        measure = model.crack_type.cell_measures(model.x, cells)
        for c in range(d):
            np.add.at(b, d * cells.ravel() + c, np.repeat(force[c] * measure / nv, nv))
    if stress_field is not None:
        _add_initial_stress_standard(b, model, cells, stress_field)
    if model.layout.num_enriched == 0:
        return b
    fp = _enriched_points(model)
    n = len(fp["weight"])
    f_at = np.zeros((n, d)) if force is None else np.broadcast_to(force, (n, d)).copy()
    s_at = None
    if stress_field is not None:
        s_at = tensor_to_voigt(evaluate_stress(stress_field, fp["x"], "initial stress"))
    b += model.crack_type.assemble_cell_load(model, fp, f_at, s_at)
    return b


def _add_initial_stress_standard(b: np.ndarray, model, cells: np.ndarray, stress_field) -> None:
    """Add -int sigma_0 : eps(N_a e_i) over the cells (triangles or
    tetrahedra: node indices into model.x) on their standard dofs to b: the
    mean of sigma_0 per cell (exact for a LinearStress, a degree-4 rule
    else) against the P1 gradients, -|cell| sum_j sigma_ij dN_a / dx_j."""
    kind = model.crack_type
    xv = model.x[cells]
    bary, w = kind.cell_rule(1 if isinstance(stress_field, LinearStress) else 4)
    mean = 0.0
    for k in range(len(w)):
        mean = mean + w[k] * evaluate_stress(stress_field, np.einsum("a,cai->ci", bary[k], xv), "initial stress")
    f = -np.einsum("cij,caj->cai", mean, kind.shape_gradients(model.x, cells)) \
        * kind.cell_measures(model.x, cells)[:, None, None]
    d = model.gdim
    np.add.at(b, (d * cells[:, :, None] + np.arange(d)).ravel(), f.ravel())


def assemble_body_force(model, force: typing.Sequence[float]) -> np.ndarray:
    """Load vector (num_dofs,) of a constant body force f: int f . phi_j dx for every dof j."""
    f = np.asarray(force, dtype=float).reshape(model.gdim)
    if not np.all(np.isfinite(f)):
        raise InputError(f"body force {f.tolist()} contains NaN or infinity")
    if not np.any(f):
        return np.zeros(model.num_dofs)
    return _cell_loads(model, f, None)


def assemble_initial_stress(model, field) -> np.ndarray:
    """Load vector (num_dofs,) of an initial stress: -int sigma_0 : eps(phi_j) dx."""
    return _cell_loads(model, None, field)


def lip_pressure(crack, x: np.ndarray) -> np.ndarray:
    """The crack's lip pressure (n,) at points (n, d) (> 0 pushes the lips apart)."""
    p = crack.pressure
    if callable(p):
        pts = np.asarray(x, dtype=float)
        d = pts.shape[1] if pts.ndim == 2 else 2
        v = np.asarray(p(pts.reshape(-1, d)), dtype=float).reshape(-1)
        if v.shape != (len(x),) or not np.all(np.isfinite(v)):
            raise InputError(f"{crack.name}: the lip pressure function must return ({len(x)},) finite "
                             f"values for points ({len(x)}, {d}), got shape {v.shape}")
        return v
    return np.full(len(x), float(p))


def assemble_lip_pressure(model, crack: int) -> np.ndarray:
    """int p [[phi_j]] . n over a crack's lips: the pressure p pushes
    the + lip along n (into the + side) and the - lip along -n."""
    cm = model.cracks[crack]
    pts = cm.lip_points(model, cm.LIP_POINTS)
    if model.distributed:  # each lip segment once: on the process owning its cell
        keep = model.owned_cells_only(pts["cell"])
        pts = {k: v[keep] for k, v in pts.items()}
    t = lip_pressure(cm.crack, pts["x"])[:, None] * pts["normal"]
    return model.crack_type.assemble_lip_load(model, crack, pts, t)


def assemble_loads(model) -> dict[str, np.ndarray]:
    """The load vector (num_dofs,) of each load group (Scene.load_path scales them)."""
    scene = model.scene
    force = None if scene.body_force is None else np.asarray(scene.body_force, dtype=float).reshape(model.gdim)
    if force is not None and not np.all(np.isfinite(force)):
        raise InputError(f"body force {force.tolist()} contains NaN or infinity")
    if force is not None and not np.any(force):
        force = None
    out: dict[str, np.ndarray] = {}

    def add(group: str, b: np.ndarray) -> None:
        out[group] = out[group] + b if group in out else b
    for group in sorted({t.group for t in scene.tractions} | {p.group for p in scene.point_forces}):
        add(group, assemble_tractions(model, group) + assemble_point_forces(model, group))
    if force is not None or scene.initial_stress is not None:
        if force is not None and scene.initial_stress is not None and scene.body_force_group != scene.initial_stress_group:
            add(scene.body_force_group, _cell_loads(model, force, None))
            add(scene.initial_stress_group, _cell_loads(model, None, scene.initial_stress))
        else:
            group = scene.body_force_group if force is not None else scene.initial_stress_group
            add(group, _cell_loads(model, force, scene.initial_stress))
    for ci, cm in enumerate(model.cracks):
        if callable(cm.crack.pressure) or cm.crack.pressure != 0.0:
            add(cm.crack.pressure_group, assemble_lip_pressure(model, ci))
    return out


def assemble_load(model) -> np.ndarray:
    """The load vector (num_dofs,) of every load of the model's scene, each
    group at factor 1."""
    return sum(assemble_loads(model).values(), np.zeros(model.num_dofs))
