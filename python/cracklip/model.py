"""The discrete X-FEM model of a scene: spaces, crack geometry, enrichment, constraints.

Nothing here loops over the mesh in Python: level sets, cell classes and the
enrichment layout come from the C++ kernels; Python only handles per-crack
and per-boundary arrays.
"""
from __future__ import annotations

import dataclasses
import functools
import inspect
import logging
import time
import typing

import numpy as np

import dolfinx.fem
import dolfinx.mesh

from . import _cracklip
from .errors import BoundaryConditionError, CrackGeometryError
from .mesh import check_mesh
from .scene import Crack, Scene

logger = logging.getLogger(__name__)

#: Cell classes of CrackGeometry.cell_class (see cpp/crack_geometry.h).
CELL_CLASSES = {"plain": 0, "cut": 1, "edge": 2, "tip": 3, "extension": 4}


@dataclasses.dataclass
class CrackModel:
    """One crack on the mesh: its polyline, which ends are tips, its geometry."""
    crack: Crack
    tips: tuple[bool, bool]
    geometry: typing.Any  # _cracklip.CrackGeometry


@dataclasses.dataclass
class XfemModel:
    """Discrete model of a scene.

    Attributes:
        scene: the input scene.
        V: DOLFINx P1 vector space (standard dofs, block size 2).
        x: (num_nodes, 2) node (dof block) coordinates.
        cells: (num_cells, 3) node indices per cell.
        cracks: per-crack geometry.
        layout: enriched pseudo-nodes and cells (_cracklip.EnrichmentLayout).
        bc_dofs: constrained scalar dofs (standard dofs only), sorted.
        bc_values: prescribed values at bc_dofs.
        bc_group_values: the prescribed values of each load group at bc_dofs
            (Dirichlet.group): bc_values is their sum.
        timings: seconds per phase.
        warnings: the model checks' findings (diagnostics.ModelWarning).
    """
    scene: Scene
    V: dolfinx.fem.FunctionSpace
    x: np.ndarray
    cells: np.ndarray
    cracks: list[CrackModel]
    layout: typing.Any
    bc_dofs: np.ndarray
    bc_values: np.ndarray
    timings: dict[str, float]
    warnings: list = dataclasses.field(default_factory=list)
    bc_group_values: dict = dataclasses.field(default_factory=dict)

    @property
    def num_dofs(self) -> int:
        return 2 * self.layout.num_nodes_total

    @property
    def geometries(self) -> list:
        return [c.geometry for c in self.cracks]

    @functools.cached_property
    def h(self) -> float:
        """Mean edge length of the mesh (each cell's three edges; computed
        once per model: 0.05 s at 2e6 cells)."""
        x, y = np.ascontiguousarray(self.x[:, 0]), np.ascontiguousarray(self.x[:, 1])
        total = 0.0
        for a, b in ((0, 1), (1, 2), (2, 0)):
            i, j = self.cells[:, a], self.cells[:, b]
            total += float(np.hypot(x[j] - x[i], y[j] - y[i]).sum())
        return total / (3 * len(self.cells)) if len(self.cells) else 0.0


def create_model(scene: Scene) -> XfemModel:
    """Build the discrete model: P1 space, crack geometry, enrichment, constraints."""
    timings: dict[str, float] = {}
    msh = scene.mesh.mesh
    check_mesh(msh)
    t0 = time.perf_counter()
    V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    x, cells = _cracklip.extract_node_mesh(V._cpp_object)
    timings["space"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    cracks = [_crack_model(scene, crack, x, cells) for crack in scene.cracks]
    opts = scene.options
    try:
        layout = _cracklip.create_enrichment_layout(
            x, cells, [c.geometry for c in cracks], tip=opts.enrichment, radius=opts.radius,
            kappa=scene.material.kappa, corrected=opts.blending == "corrected")
    except RuntimeError as e:
        raise CrackGeometryError(str(e)) from None
    timings["geometry"] = time.perf_counter() - t0
    logger.info("%d cracks, %d enriched nodes on %d enriched cells", len(cracks),
                layout.num_enriched, layout.cells.size)

    t0 = time.perf_counter()
    bc_dofs, bc_values, bc_group_values = _dirichlet(scene, V, x, layout, [c.geometry for c in cracks])
    check_rigid_motion(x, bc_dofs[bc_dofs < 2 * x.shape[0]])
    timings["constraints"] = time.perf_counter() - t0
    model = XfemModel(scene, V, x, cells, cracks, layout, bc_dofs, bc_values, timings,
                      bc_group_values=bc_group_values)
    t0 = time.perf_counter()
    from .diagnostics import check_model, check_pieces
    check_pieces(model)
    model.warnings = check_model(model)
    for w in model.warnings:
        logger.warning("%s", w.message)
    timings["checks"] = time.perf_counter() - t0
    return model


def _crack_model(scene: Scene, crack: Crack, x: np.ndarray, cells: np.ndarray) -> CrackModel:
    tips = _tip_flags(scene, crack)
    try:
        geometry = _cracklip.compute_crack_geometry(x, cells, crack.points, tips, scene.options.snap_tol)
    except (RuntimeError, ValueError) as e:
        raise CrackGeometryError(f"{crack.name}: {e}") from None
    classes = geometry.cell_class
    crossed = np.count_nonzero((classes == CELL_CLASSES["cut"]) | (classes == CELL_CLASSES["edge"])
                               | (classes == CELL_CLASSES["tip"]))
    if crossed == 0:
        lo, hi = x.min(axis=0), x.max(axis=0)
        raise CrackGeometryError(
            f"{crack.name} (points {crack.points.tolist()}) does not cross any cell of the mesh "
            f"(mesh bounding box [{lo[0]:g}, {hi[0]:g}] x [{lo[1]:g}, {hi[1]:g}]); "
            "check its coordinates")
    _check_off_boundary(crack, geometry, x, cells)
    if geometry.num_snapped:
        logger.info("%s: %d nodes snapped onto the crack (snap_tol=%g)", crack.name,
                    geometry.num_snapped, scene.options.snap_tol)
    return CrackModel(crack, tips, geometry)


def _check_off_boundary(crack: Crack, geometry, x: np.ndarray, cells: np.ndarray) -> None:
    """Raise if the crack runs along a boundary facet: its crack edge (the
    two nodes on the crack of an 'edge' cell) then belongs to one cell only."""
    edge_cells = np.flatnonzero(geometry.cell_class == CELL_CLASSES["edge"])
    if edge_cells.size == 0:
        return
    cc = cells[edge_cells]
    on = geometry.phi[cc] == 0.0
    pairs = np.sort(np.where(on, cc, -1), axis=1)[:, 1:]  # the two nodes with phi = 0
    near = cells[np.count_nonzero(np.isin(cells, np.unique(pairs)), axis=1) >= 2]
    count: dict[tuple[int, int], int] = {}
    for e in np.sort(near[:, [[0, 1], [1, 2], [2, 0]]], axis=2).reshape(-1, 2).tolist():
        count[tuple(e)] = count.get(tuple(e), 0) + 1
    for a, b in pairs.tolist():
        if count.get((a, b), 0) == 1:
            raise CrackGeometryError(
                f"{crack.name} runs along the domain boundary from {x[a].tolist()} to {x[b].tolist()} "
                "(a boundary facet); a crack must lie inside the domain: move it off the boundary or "
                "shorten it")


def _tip_flags(scene: Scene, crack: Crack) -> tuple[bool, bool]:
    """An end point is a tip when it lies inside the domain, off the boundary.

    Inside-ness is decided by ray casting against the boundary facets, so the
    cost is proportional to the boundary, not to the mesh.
    """
    a, b = boundary_segments(scene.mesh)
    scale = float(max(np.ptp(a, axis=0).max(), np.ptp(b, axis=0).max()))
    d = b - a
    flags = []
    for p in crack.points[[0, -1]]:
        t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
        dist = np.linalg.norm(a + t[:, None] * d - p, axis=1).min()
        # Horizontal ray to +x: count facets straddling y = p_y right of p.
        straddle = (a[:, 1] > p[1]) != (b[:, 1] > p[1])
        with np.errstate(divide="ignore", invalid="ignore"):
            xc = a[:, 0] + (p[1] - a[:, 1]) * d[:, 0] / d[:, 1]
        inside = np.count_nonzero(straddle & (xc > p[0])) % 2 == 1
        flags.append(bool(inside and dist > 1e-9 * scale))
    return flags[0], flags[1]


def boundary_segments(mesh) -> tuple[np.ndarray, np.ndarray]:
    """End points (n, 2), (n, 2) of the boundary facets (holes included) of a MeshData."""
    msh = mesh.mesh
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    facets = dolfinx.mesh.exterior_facet_indices(msh.topology)
    verts = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)
    return msh.geometry.x[verts[:, 0], :2], msh.geometry.x[verts[:, 1], :2]


def _component_dofs(nodes: np.ndarray, component: int | None) -> np.ndarray:
    comps = [0, 1] if component is None else [component]
    return np.sort(np.concatenate([2 * nodes + c for c in comps])).astype(np.int32)


def _accepts_side(f) -> bool:
    try:
        params = inspect.signature(f).parameters.values()
    except (TypeError, ValueError):
        return False
    required = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)
                and p.default is p.empty]
    return len(required) >= 2


def _dirichlet(scene: Scene, V, x: np.ndarray, layout, geometries) -> tuple[np.ndarray, np.ndarray, dict]:
    """Constrained scalar dofs, their values (every group at factor 1) and
    the values of each load group (Dirichlet.group; conditions of different
    groups on one dof add up).

    A value callable f(x) is continuous; f(x, side) may jump across a crack
    (side (n,) = +1 / -1, the side of the crack nearest to each point). On a
    tagged boundary the Heaviside dofs of the boundary's nodes are fixed too,
    because their functions do not vanish between the nodes of a boundary
    facet that the crack crosses: to 0 for a continuous value, to the jump
    (f(x_i, -H_i) - f(x_i, H_i)) / (-2 H_i) otherwise. Tip dofs stay free.
    A point condition fixes only the node's standard dofs. Conditions that
    constrain the same dof (two sides sharing a corner node) must agree.
    """
    msh = scene.mesh.mesh
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
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
        is_point = isinstance(bc.where, (tuple, list, np.ndarray))
        if is_point:
            p = np.asarray(bc.where, dtype=float)
            d = np.linalg.norm(x - p, axis=1)
            node = int(np.argmin(d))
            scale = float(np.ptp(x, axis=0).max())
            if d[node] > 1e-8 * scale:
                raise BoundaryConditionError(
                    f"Dirichlet point {p.tolist()} is not a mesh node (nearest node "
                    f"{x[node].tolist()} at distance {d[node]:.3g}); use a node or a boundary tag")
            nodes = np.array([node], dtype=np.int32)
        else:
            facets = scene.mesh.facets(bc.where)
            if facets.size == 0:
                raise BoundaryConditionError(f"Dirichlet boundary {bc.where!r} has no facets")
            nodes = dolfinx.fem.locate_dofs_topological(V, tdim - 1, facets)
        comps = [0, 1] if bc.component is None else [bc.component]
        with_side = callable(bc.value) and _accepts_side(bc.value)

        def evaluate(points, sides):
            if not callable(bc.value):
                return np.full((len(points), len(comps)), float(bc.value))
            out = np.asarray(bc.value(points, sides) if with_side else bc.value(points), dtype=float)
            if out.size != len(points) * len(comps):
                raise BoundaryConditionError(
                    f"Dirichlet condition {k_bc} ({bc.where!r}): its value function returned shape "
                    f"{out.shape} for {len(points)} points; it must return ({len(points)},) for one "
                    f"component or ({len(points)}, 2) for both")
            return out.reshape(len(points), len(comps))
        v = evaluate(x[nodes], node_side[nodes])
        if not np.all(np.isfinite(v)):
            raise BoundaryConditionError(f"Dirichlet values on {bc.where!r} contain NaN or infinity")
        for j, c in enumerate(comps):
            prescribe(2 * nodes + c, v[:, j], k_bc)
        if not is_point:
            pseudo = np.flatnonzero(np.isin(layout.node, nodes) & (layout.kind == 0))
            jump = np.zeros((len(pseudo), len(comps)))
            if with_side and len(pseudo):
                H = layout.node_side[pseudo].astype(float)
                xp = x[layout.node[pseudo]]
                jump = (evaluate(xp, -H.astype(np.int8)) - evaluate(xp, H.astype(np.int8))) / (-2.0 * H[:, None])
            for j, c in enumerate(comps):
                prescribe(2 * (layout.num_std_nodes + pseudo) + c, jump[:, j], k_bc)
    for grp, mine in values.items():
        _check_clashes(scene, x, layout, mine, [c for c in clashes if scene.dirichlet[c[1]].group == grp])
    dofs = np.array(sorted(set().union(*values.values())), dtype=np.int32)
    group_values = {grp: np.array([mine.get(d, 0.0) for d in dofs.tolist()], dtype=np.float64)
                    for grp, mine in values.items()}
    return dofs, sum(group_values.values(), np.zeros(len(dofs))), group_values


def _check_clashes(scene: Scene, x: np.ndarray, layout, values: dict, clashes: list) -> None:
    """Raise if two Dirichlet conditions prescribe different values to a dof
    (beyond round-off: 1e-10 relative and 1e-12 of the largest value)."""
    if not clashes:
        return
    vmax = max(abs(v) for v in values.values())
    for dof, k0, k1, a, b in clashes:
        if abs(a - b) <= 1e-10 * max(abs(a), abs(b)) or abs(a - b) <= 1e-12 * vmax:
            continue
        node, comp = divmod(dof, 2)
        what = f"u_{'xy'[comp]}"
        if node >= layout.num_std_nodes:
            node = int(layout.node[node - layout.num_std_nodes])
            what = f"the jump (Heaviside dof) of u_{'xy'[comp]}"
        w0, w1 = scene.dirichlet[k0].where, scene.dirichlet[k1].where
        raise BoundaryConditionError(
            f"Dirichlet conditions {k0} ({w0!r}) and {k1} ({w1!r}) prescribe different values to {what} "
            f"at node {x[node].tolist()}: {a:.6g} and {b:.6g}; conditions that share a node (two sides "
            "meeting at a corner, a point on a tagged side) must prescribe the same value there")


def rigid_motion_rank(x: np.ndarray, nodes: np.ndarray, comps: np.ndarray) -> tuple[int, list[str]]:
    """How many of the three rigid motions of the plane the constraints of
    components `comps` (0 x, 1 y) at nodes fix, and the names of those left free."""
    R = np.zeros((nodes.size, 3))
    R[comps == 0, 0] = 1.0
    R[comps == 1, 1] = 1.0
    # rotation about the centroid: u = (-(y - yc), x - xc)
    c = x.mean(axis=0)
    R[comps == 0, 2] = -(x[nodes[comps == 0], 1] - c[1])
    R[comps == 1, 2] = x[nodes[comps == 1], 0] - c[0]
    scale = float(np.ptp(x, axis=0).max()) or 1.0
    R[:, 2] /= scale
    s = np.linalg.svd(R, compute_uv=False) if R.shape[0] else np.zeros(0)
    rank = int(np.sum(s > 1e-10 * (s.max() if s.size else 1.0)))
    free = []
    if rank < 3:
        if not np.any(comps == 0):
            free.append("translation in x")
        if not np.any(comps == 1):
            free.append("translation in y")
        if not free:
            free.append("rotation")
    return rank, free


def check_rigid_motion(x: np.ndarray, bc_dofs: np.ndarray) -> None:
    """Raise unless the constraints remove the three rigid motions of the plane.

    (A crack that cuts the part into pieces is checked piece by piece:
    diagnostics.check_pieces.)
    """
    rank, free = rigid_motion_rank(x, bc_dofs // 2, bc_dofs % 2)
    if rank < 3:
        raise BoundaryConditionError(
            f"the Dirichlet conditions leave rigid motion free ({', '.join(free)}); "
            f"{bc_dofs.size} constrained dofs fix only {rank} of the 3 rigid motions")
