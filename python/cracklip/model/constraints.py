"""Dirichlet conditions on the model's dofs (standard and Heaviside), and the check
that they fix the rigid motions."""
from __future__ import annotations

import inspect

import numpy as np

import dolfinx.fem
import dolfinx.mesh

from ..errors import BoundaryConditionError, InputError
from ..scene.scene import Scene
from ..scene.symmetry import SymmetryCondition
from .symmetry import symmetry_enriched_dofs
from ..scene.processes import agree, mark_collective, reduced, total
from .loads import crack_through_node, largest_edge_at


def _accepts_side(f) -> bool:
    try:
        params = inspect.signature(f).parameters.values()
    except (TypeError, ValueError):
        return False
    required = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)
                and p.default is p.empty]
    return len(required) >= 2


def is_point_condition(bc) -> bool:
    """Whether a Dirichlet condition acts at a point (a node) rather than on a tag."""
    return isinstance(bc.where, (tuple, list, np.ndarray))


def condition_nodes(scene: Scene, V, x: np.ndarray, bc) -> np.ndarray:
    """The mesh nodes a Dirichlet condition constrains: the node at its point,
    or the nodes of its tag's facets."""
    if is_point_condition(bc):
        p = np.asarray(bc.where, dtype=float)
        d = np.linalg.norm(x - p, axis=1)
        comm = scene.mesh.mesh.comm
        if comm.size > 1:  # the nearest node of all processes; each that holds it constrains it
            near = min(comm.allgather((float(d.min()) if d.size else np.inf,
                                       x[int(np.argmin(d))].tolist() if d.size else None)))
            scale = float(max(comm.allgather(float(np.ptp(x, axis=0).max()) if d.size else 0.0)))
            if near[0] > 1e-8 * scale:
                raise mark_collective(BoundaryConditionError(
                    f"Dirichlet point {p.tolist()} is not a mesh node (nearest node {near[1]} at distance "
                    f"{near[0]:.3g}); use a node or a boundary tag"))
            return np.flatnonzero(d == near[0]).astype(np.int32)[:1]
        node = int(np.argmin(d))
        scale = float(np.ptp(x, axis=0).max())
        if d[node] > 1e-8 * scale:
            raise BoundaryConditionError(
                f"Dirichlet point {p.tolist()} is not a mesh node (nearest node "
                f"{x[node].tolist()} at distance {d[node]:.3g}); use a node or a boundary tag")
        return np.array([node], dtype=np.int32)
    facets = scene.mesh.facets(bc.where)
    if total(facets.size, scene.mesh.mesh.comm) == 0:
        raise BoundaryConditionError(f"Dirichlet boundary {bc.where!r} has no facets")
    tdim = scene.mesh.mesh.topology.dim
    return np.asarray(dolfinx.fem.locate_dofs_topological(V, tdim - 1, facets), dtype=np.int32)


def condition_dofs(model) -> list[np.ndarray]:
    """The standard dofs (d node + component, d the space dimension) each
    Dirichlet condition of the model's scene constrains, a dof shared by
    several conditions going to the first of them (for the reactions per
    condition)."""
    d = model.x.shape[1]
    taken = np.zeros(d * model.x.shape[0], dtype=bool)
    out = []
    for bc in model.scene.dirichlet:
        nodes = condition_nodes(model.scene, model.V, model.x, bc)
        comps = list(range(d)) if bc.component is None else [bc.component]
        dofs = np.sort(np.concatenate([d * nodes + c for c in comps])).astype(np.int64)
        dofs = dofs[~taken[dofs]]
        taken[dofs] = True
        out.append(dofs)
    return out


def compute_dirichlet(scene: Scene, V, x: np.ndarray, layout, geometries) -> tuple[np.ndarray, np.ndarray, dict]:
    """Constrained scalar dofs, their values (every group at factor 1) and
    the values of each load group (Dirichlet.group; conditions of different
    groups on one dof add up).

    A value callable f(x) is continuous; f(x, side) may jump across a crack
    (side (n,) = +1 / -1, the side of the crack nearest to each point). On a
    tagged boundary the Heaviside dofs of the boundary's nodes are fixed too,
    because their functions do not vanish between the nodes of a boundary
    facet that the crack crosses: to 0 for a continuous value, to the jump
    (f(x_i, -H_i) - f(x_i, H_i)) / (-2 H_i) otherwise. Only where the crack
    meets the boundary (_straddled): a Heaviside node of a face the crack
    does not reach has its function vanish on that face, and fixing its dof
    would pin the other side's material there (a piece cut off by the crack
    held by a support on the far side of the crack). Tip dofs stay free.
    A symmetry plane (SymmetryCondition) also fixes the enriched dofs
    that would move its nodes out of the plane (symmetry_enriched_dofs).
    A point condition fixes only the node's standard dofs. Conditions that
    constrain the same dof (two sides sharing a corner node) must agree.
    """
    msh = scene.mesh.mesh
    tdim = msh.topology.dim
    gdim = x.shape[1]
    msh.topology.create_connectivity(tdim - 1, tdim)
    cells = V.dofmap.list.array.reshape(-1, tdim + 1)
    # Side of every node with respect to its nearest crack (+1 without cracks).
    node_side = np.ones(x.shape[0], dtype=np.int8)
    if geometries:
        phis = np.stack([g.phi for g in geometries])
        nearest = phis[np.argmin(np.abs(phis), axis=0), np.arange(x.shape[0])]
        node_side = np.where(nearest >= 0.0, 1, -1).astype(np.int8)
    # Per load group: the values of one group must agree where conditions
    # meet; the groups' values add up (superposed loads).
    values: dict[str, dict[int, float]] = {}
    owner: dict[tuple[str, int], int] = {}
    clashes: list[tuple[int, int, int, float, float]] = []

    def prescribe(dofs: np.ndarray, vals: np.ndarray, k: int) -> None:
        grp = scene.dirichlet[k].group
        mine = values.setdefault(grp, {})
        for dof, val in zip(dofs.tolist(), vals.tolist()):
            old = mine.get(dof)
            if old is not None and old != val:
                clashes.append((dof, owner[grp, dof], k, old, val))
            mine[dof] = val
            owner[grp, dof] = k
    for k_bc, bc in enumerate(scene.dirichlet):
        is_point = is_point_condition(bc)
        nodes = condition_nodes(scene, V, x, bc)
        if bc.component is not None and bc.component >= gdim:
            raise BoundaryConditionError(f"Dirichlet condition {k_bc} ({bc.where!r}): component {bc.component} "
                                         f"does not exist in {gdim}D (0 .. {gdim - 1})")
        comps = list(range(gdim)) if bc.component is None else [bc.component]
        with_side = callable(bc.value) and _accepts_side(bc.value)

        def evaluate(points, sides):
            if not callable(bc.value):
                return np.full((len(points), len(comps)), float(bc.value))
            out = np.asarray(bc.value(points, sides) if with_side else bc.value(points), dtype=float)
            if out.size != len(points) * len(comps):
                raise BoundaryConditionError(
                    f"Dirichlet condition {k_bc} ({bc.where!r}): its value function returned shape "
                    f"{out.shape} for {len(points)} points; it must return ({len(points)},) for one "
                    f"component or ({len(points)}, {gdim}) for {'both' if gdim == 2 else 'all'}")
            return out.reshape(len(points), len(comps))
        v = evaluate(x[nodes], node_side[nodes])
        if not np.all(np.isfinite(v)):
            raise BoundaryConditionError(f"Dirichlet values on {bc.where!r} contain NaN or infinity")
        for j, c in enumerate(comps):
            prescribe(gdim * nodes + c, v[:, j], k_bc)
        if not is_point:
            pseudo = np.flatnonzero(np.isin(layout.node, nodes) & (layout.kind == 0))
            pseudo = pseudo[_straddled(nodes, cells, geometries, layout.node[pseudo], layout.crack[pseudo])]
            jump = np.zeros((len(pseudo), len(comps)))
            if with_side and len(pseudo):
                H = layout.node_side[pseudo].astype(float)
                xp = x[layout.node[pseudo]]
                jump = (evaluate(xp, -H.astype(np.int8)) - evaluate(xp, H.astype(np.int8))) / (-2.0 * H[:, None])
            for j, c in enumerate(comps):
                prescribe(gdim * (layout.num_std_nodes + pseudo) + c, jump[:, j], k_bc)
        if isinstance(bc, SymmetryCondition):
            extra = symmetry_enriched_dofs(layout, nodes, bc, geometries, x)
            prescribe(extra, np.zeros(len(extra)), k_bc)
    for grp, mine in values.items():
        _check_clashes(scene, x, layout, mine, [c for c in clashes if scene.dirichlet[c[1]].group == grp])
    dofs = np.array(sorted(set().union(*values.values())), dtype=np.int32)
    group_values = {grp: np.array([mine.get(d, 0.0) for d in dofs.tolist()], dtype=np.float64)
                    for grp, mine in values.items()}
    return dofs, sum(group_values.values(), np.zeros(len(dofs))), group_values


def _straddled(nodes: np.ndarray, cells: np.ndarray, geometries, pseudo_nodes: np.ndarray,
               pseudo_cracks: np.ndarray) -> np.ndarray:
    """Mask over Heaviside pseudo-nodes (their base node and crack) of those
    where their crack meets the condition's boundary: the node lies on the
    crack, or shares a cell with another of the condition's nodes on the
    other side of it (a boundary facet the crack crosses, or close to one)."""
    keep = np.zeros(len(pseudo_nodes), dtype=bool)
    if not len(pseudo_nodes):
        return keep
    on_boundary = np.zeros(int(max(cells.max(), nodes.max())) + 1, dtype=bool)
    on_boundary[nodes] = True
    in_cond = on_boundary[cells]
    near = np.any(in_cond, axis=1)
    for c in np.unique(pseudo_cracks).tolist():
        phi = np.asarray(geometries[c].phi)
        sub, ph = in_cond[near], phi[cells[near]]
        crossed = (np.any(sub & (ph > 0.0), axis=1) & np.any(sub & (ph < 0.0), axis=1)) | np.any(sub & (ph == 0.0),
                                                                                                 axis=1)
        marked = np.zeros(len(on_boundary), dtype=bool)
        marked[cells[near][crossed][sub[crossed]]] = True
        mine = pseudo_cracks == c
        keep[mine] = marked[pseudo_nodes[mine]]
    return keep


def _check_clashes(scene: Scene, x: np.ndarray, layout, values: dict, clashes: list) -> None:
    """Raise if two Dirichlet conditions prescribe different values to a dof
    (beyond round-off: 1e-10 relative and 1e-12 of the largest value)."""
    if not clashes:
        return
    vmax = max(abs(v) for v in values.values())
    for dof, k0, k1, a, b in clashes:
        if abs(a - b) <= 1e-10 * max(abs(a), abs(b)) or abs(a - b) <= 1e-12 * vmax:
            continue
        node, comp = divmod(dof, x.shape[1])
        what = f"u_{'xyz'[comp]}"
        if node >= layout.num_std_nodes:
            node = int(layout.node[node - layout.num_std_nodes])
            what = f"the jump (Heaviside dof) of u_{'xyz'[comp]}"
        w0, w1 = scene.dirichlet[k0].where, scene.dirichlet[k1].where
        raise BoundaryConditionError(
            f"Dirichlet conditions {k0} ({w0!r}) and {k1} ({w1!r}) prescribe different values to {what} "
            f"at node {x[node].tolist()}: {a:.6g} and {b:.6g}; conditions that share a node (two sides "
            "meeting at a corner, a point on a tagged side) must prescribe the same value there")


#: The rotations of the plane and of space as pairs (i, j): the motion
#: -x_j e_i + x_i e_j (about z; in space also about y and x).
ROTATIONS = {2: ((0, 1),), 3: ((0, 1), (2, 0), (1, 2))}


def rigid_motion_rank(x: np.ndarray, nodes: np.ndarray, comps: np.ndarray) -> tuple[int, list[str]]:
    """How many of the rigid motions (3 in the plane, 6 in space) the
    constraints of components `comps` (0 x, 1 y, 2 z) at nodes fix, and the
    names of those left free."""
    d = x.shape[1]
    rotations = ROTATIONS[d]
    R = np.zeros((nodes.size, d + len(rotations)))
    c = x.mean(axis=0)
    scale = float(np.ptp(x, axis=0).max()) or 1.0
    p = (x[nodes] - c) / scale
    for k in range(d):
        R[comps == k, k] = 1.0
    for r, (i, j) in enumerate(rotations):
        R[comps == i, d + r] = -p[comps == i, j]
        R[comps == j, d + r] = p[comps == j, i]
    s = np.linalg.svd(R, compute_uv=False) if R.shape[0] else np.zeros(0)
    rank = int(np.sum(s > 1e-10 * (s.max() if s.size else 1.0)))
    free = [f"translation in {a}" for k, a in enumerate("xyz"[:d]) if not np.any(comps == k)]
    if rank < R.shape[1] and not free:
        free.append("rotation")
    return rank, free


def check_rigid_motion(x: np.ndarray, bc_dofs: np.ndarray, comm=None) -> None:
    """Raise unless the constraints remove the rigid motions (3 in the plane,
    6 in space).

    (A crack that cuts the part into pieces is checked piece by piece:
    checks.check_pieces.)
    """
    d = x.shape[1]
    need = d + len(ROTATIONS[d])
    if comm is not None and comm.size > 1:  # every process's constrained nodes, gathered
        pts = np.concatenate(comm.allgather(x[bc_dofs // d]))
        comps = np.concatenate(comm.allgather(bc_dofs % d))
        x, bc_dofs = pts, np.arange(len(pts)) * d + comps
    rank, free = rigid_motion_rank(x, bc_dofs // d, bc_dofs % d)
    if rank < need:
        raise BoundaryConditionError(
            f"the Dirichlet conditions leave rigid motion free ({', '.join(free)}); "
            f"{bc_dofs.size} constrained dofs fix only {rank} of the {need} rigid motions")


def check_point_supports(model) -> None:
    """A point Dirichlet condition on a node of a crack's line (2D, not at a
    tip) fixes the node's standard dofs, which are one lip's or the other's
    by the level set's sign there, not the one meant: an error naming the
    condition (collective under mpirun), as for a point force there."""
    scene = model.scene
    points = [(k, bc) for k, bc in enumerate(scene.dirichlet) if is_point_condition(bc)]
    if not points or model.gdim != 2 or not model.cracks:
        return
    comm = model.comm
    scale = float(np.ptp(model.x, axis=0).max()) if len(model.x) else 0.0
    if comm is not None:
        scale = float(reduced(scale, "MAX", comm))
    for k, bc in points:
        nodes = condition_nodes(scene, model.V, model.x, bc)
        error = None
        if nodes.size:
            node = int(nodes[0])
            edge = largest_edge_at(model, node)
            lip = crack_through_node(model, node, edge, scale)
            if lip is not None:
                name = bc.label.split(":")[0] if bc.label else f"Dirichlet condition {k}"
                error = InputError(
                    f"{name} at {[float(v) for v in bc.where]} holds the mesh node {model.x[node].tolist()}, which "
                    f"lies on {lip}: a support there holds one lip or the other depending on the mesh, not the one "
                    "meant, and leaves the other free; support a point off the crack on that lip's side by a "
                    f"fraction of an element ({edge:.3g}) with a mesh node there (a refinement point, or "
                    "mesh.kind = \"geometry\"), or a boundary tag")
        if comm is not None:
            agree(error, comm)
        elif error is not None:
            raise error
