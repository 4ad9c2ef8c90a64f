"""Model checks shared by ``cracklip check`` and ``run``: what would make a K
or a solve untrustworthy, found before solving. The crack model of the
part's dimension runs those of its ends (cracklip.model.cracks: a curve's
tips, a surface's fronts; create_model calls them).

Both dimensions:
- ``check_pieces(model)`` raises BoundaryConditionError when the cracks cut
  the part into pieces and one of them has no Dirichlet condition fixing
  its rigid motion (the solve would fail on a singular matrix), naming the
  cracks and every piece.

Planar parts (tips):
- ``check_tips(model)`` returns warnings: a refinement that the mesh did not
  reach (or whose point lies in a hole or outside the part), a tip element
  coarser than a tenth of the crack length or than the enrichment radius, a
  region around a tip too coarse for the crack (``tip_region``), a tip without tip enrichment (K only to O(sqrt(h))),
  a tip within an element of the boundary, SIF domains
  clipped by the boundary, other tips, other cracks, kinks or holes.

Solids (fronts), ``check_fronts(model)``:
- errors (the model cannot be right): a front piece that is neither closed
  (an embedded crack) nor ends on the part's boundary (a surface or corner
  crack: ``check_front_ends``), which happens where the P1 front touches
  itself (branch points) or breaks in degenerate cells; options.radius > 0
  that reaches no node of a front (``check_enrichment_radius``: a radius in
  the wrong units or far below the element size);
- warnings: a front whose elements are coarse for the crack's size
  (front_resolution), a radius below the element size at the front
  (enrichment_radius), front cells where the P1 front is not a line
  (degenerate_front), no front enrichment (front_enrichment), a crack
  along mesh faces whose nodes there got neither a Heaviside nor front
  functions (crack_on_faces), a triangulated crack whose front has a closed piece
  besides others: a hole in the surface, an uncracked ligament
  (crack_hole).
  ``front_element_sizes`` is the element size reached along a front (what
  ``check`` reports): the mean edge length of each front cell.

A warning is a ``ModelWarning`` (code, message, crack, tip); results.json
lists them and the command line prints them on stderr.
"""
from __future__ import annotations

import dataclasses
import typing

import numpy as np
import scipy.sparse as sp
import scipy.sparse.csgraph

from .. import _cracklip
from ..errors import BoundaryConditionError, CrackGeometryError, InputError
from ..scene.cell_size import cell_sizes
from ..scene.size_field import PLATEAU
from ..scene.units import STRESSES
from ..scene.processes import not_parallel, reduced
from .boundary import nearest_boundary_point, where_outside
from .constraints import ROTATIONS, rigid_motion_rank
from .tip_regions import length_in_part, model_boundary, part_size, segment_distance, tip_domains, tip_element_size


#: What the warning codes met along a growth run mean, in a few words (the
#: summary that counts them; docs/sifs.md has the whole table).
CODE_MEANINGS = {
    "sif_domain": "a SIF domain clipped by the boundary or another obstacle, or none fits: K NOT reliable",
    "sif_spread": "K varies with the SIF domain by more than 1 % of the K scale",
    "sif_points": "too few front points for a free-surface end value",
    "front_resolution": "the elements along a front coarser than a fifth of the crack's size",
    "enrichment_radius": "the enrichment radius below the elements at the front",
    "tip_region": "the region around a tip coarse for the crack",
    "interpenetration": "the lips overlap where contact is off",
    "discretisation": "a K's estimated discretisation error above 1 % of the K scale",
}


class CodedText(str):
    """A warning's text that carries its ModelWarning code and the crack and
    tip (3D: front point) it concerns, for the messages the SIF computation
    hands on as strings (logged, gathered, listed per growth step)."""
    code: str
    crack: int | None
    tip: int | None

    def __new__(cls, text: str, code: str, crack: int | None = None, tip: int | None = None):
        out = super().__new__(cls, text)
        out.code, out.crack, out.tip = code, crack, tip
        return out

    def __getnewargs__(self):  # (pickled between processes under mpirun)
        return str(self), self.code, self.crack, self.tip


#: A refinement whose achieved element size exceeds the asked one by this factor is warned about.
REFINEMENT_TOLERANCE = 1.5


@dataclasses.dataclass(frozen=True)
class ModelWarning:
    """Something that makes a result less trustworthy, with the fix.

    Attributes:
        code: refinement, tip_resolution, tip_region, tip_enrichment,
            enrichment_radius, tip_near_boundary, sif_domain, sif_points or
            sif_spread
            (and, from a solved field, cracklip.post.checks' codes).
        message: what, where, why it matters and what to do.
        crack, tip: the crack and tip concerned (None if not one tip).
    """
    code: str
    message: str
    crack: int | None = None
    tip: int | None = None

    def as_dict(self) -> dict[str, typing.Any]:
        return dataclasses.asdict(self)

    def __str__(self) -> str:
        return self.message


def check_tips(model) -> list[ModelWarning]:
    """Every model check of a planar part's tips that does not need the
    solution (see the module doc)."""
    out: list[ModelWarning] = []
    md = model.scene.mesh
    a, b = model_boundary(model)
    for (x, y, size) in md.refinements:
        outside = where_outside((x, y), a, b)
        if outside is not None:
            q, d, _ = nearest_boundary_point(np.array([x, y]), a, b)
            reach = PLATEAU * size
            got = tip_element_size(model, q)
            out.append(ModelWarning("refinement", (
                f"the mesh refinement at ({x:.6g}, {y:.6g}) lies {outside} ({d:.3g} from its nearest point "
                f"({q[0]:.6g}, {q[1]:.6g})): there is no element at the point, and its size {size:.3g} holds only "
                f"within {reach:.3g} of it, growing beyond; "
                + ("it does not reach the part at all" if d > reach else f"the element at that nearest point is {got:.3g}")
                + "; put the refinement's point on the part (e.g. on the hole's edge where the crack starts), or "
                  "refine along a segment inside the part")))
            continue
        got = tip_element_size(model, np.array([x, y]))
        if got > REFINEMENT_TOLERANCE * size:
            out.append(ModelWarning("refinement", f"the mesh refinement at ({x:.6g}, {y:.6g}) asked for elements "
                                    f"of {size:.3g} and got {got:.3g}: the size field could not be honoured "
                                    "(check mesh.tip_h / mesh.refine against mesh.h)"))
    radius = model.scene.options.radius
    enrichment = model.scene.options.enrichment
    for ci, cm in enumerate(model.cracks):
        g = cm.geometry
        tips = np.asarray(g.tips).reshape(-1, 2)
        if not len(tips):
            continue
        length = length_in_part(model, ci)
        name = cm.crack.name
        for j, p in enumerate(tips):
            where = f"tip {j} of crack {name!r} at ({p[0]:.6g}, {p[1]:.6g})"
            h = tip_element_size(model, p)
            if h > 0.1 * length:
                out.append(ModelWarning(
                    "tip_resolution", f"{where}: the element there ({h:.3g}) is coarser than a tenth of the "
                    f"crack's length in the part ({length:.3g}): the crack is not resolved and K is not "
                    f"reliable; refine the mesh at the tip (mesh.tip_h <= {0.1 * length:.3g})", ci, j))
            if enrichment == "none":
                out.append(ModelWarning(
                    "tip_enrichment", f"{where}: without tip enrichment (options.enrichment = 'none') the crack "
                    "ends at the edge of the cell holding the tip and the tip field is not represented: K is "
                    "off by several per cent on ordinary meshes (5 % with 0.05 elements on a crack 1 long) and "
                    "converges like sqrt(h); use enrichment = 'vector' for K", ci, j))
            elif radius > 0.0 and h > radius:
                out.append(ModelWarning(
                    "enrichment_radius", f"{where}: the enrichment radius {radius:.3g} is smaller than the element "
                    f"there ({h:.3g}), so only the tip cell's nodes are tip-enriched and the rate is that of "
                    f"radius 0; use a radius of a few elements or refine the mesh at the tip", ci, j))
            d = float(segment_distance(p, a, b).min())
            if d < h:
                out.append(ModelWarning(
                    "tip_near_boundary", f"{where} is {d:.3g} from the boundary, within one element ({h:.3g}): "
                    "the ligament is not resolved and the tip is taken as an interior tip; if the crack starts "
                    "at the boundary, put its end point on or beyond the boundary (an edge crack), else refine "
                    "the mesh there", ci, j))
        for dom in tip_domains(model, ci):
            out += [ModelWarning("sif_domain", w, ci, dom.tip) for w in dom.warnings]
            if enrichment != "none" and not any(w.code == "tip_resolution" and w.tip == dom.tip and w.crack == ci
                                                for w in out):
                w = _tip_region(model, ci, dom, length, radius)
                if w is not None:
                    out.append(w)
    return out


#: The region around a tip is coarse when the largest element sizes there
#: (the REGION_PERCENTILE-th percentile of the cells within REGION_EXTENT
#: crack scales of the tip) exceed the crack scale over REGION_ELEMENTS.
#: The crack scale is the crack's length in the part, or the distance to the
#: nearest boundary, hole, tip or crack if shorter. Calibrated against K's
#: error on the handbook cases, a C(T), a Brazilian disc and a crack at a
#: hole (docs/guide.md): it fires on every case with K more than 1 % low
#: whose enrichment reaches a few elements, never on the handbook cases at
#: h = W/40 (0.06-0.30 % off; largest value 0.129 against 1/7.5 = 0.133).
REGION_ELEMENTS = 7.5
REGION_EXTENT = 2.0
REGION_PERCENTILE = 95.0


#: With the tip enrichment on the tip cell's nodes only (options.radius
#: below TIP_RADIUS_ELEMENTS tip elements), K converges like h (not h^2):
#: a tip element above the crack scale over TIP_ELEMENTS is warned about
#: (the C(T) at h = W/20, 4.6 % low, has 9 tip elements per crack scale).
TIP_RADIUS_ELEMENTS = 2.0
TIP_ELEMENTS = 40.0


def _cell_sizes(model) -> tuple[np.ndarray, np.ndarray]:
    """(mean edge (n,), centroid (n, 2)) of every cell (under mpirun: of the
    owned cells), computed once per model."""
    cached = model.__dict__.get("_cell_sizes_cache")
    if cached is None:
        cells = model.cells if not model.distributed else model.cells[:model.num_owned_cells]
        cached = (cell_sizes(model.x, cells), model.x[cells].mean(axis=1))
        model._cell_sizes_cache = cached
    return cached


def _tip_region(model, ci: int, dom, length: float, radius: float) -> ModelWarning | None:
    """The 'tip_region' warning of one tip, or None (the rules above)."""
    scale = min(length, dom.clearance)
    if not scale > 0.0:
        return None
    size, centroid = _cell_sizes(model)
    near = size[np.linalg.norm(centroid - dom.position, axis=1) < REGION_EXTENT * scale]
    if model.distributed:  # every process's near cells (a percentile does not add up)
        near = np.concatenate(model.V.mesh.comm.allgather(near))
    coarse = float(np.percentile(near, REGION_PERCENTILE)) if near.size else dom.element_size
    name = model.cracks[ci].crack.name
    where = f"tip {dom.tip} of crack {name!r} at ({dom.position[0]:.6g}, {dom.position[1]:.6g})"
    what = (f"the crack scale there is {scale:.3g} (" + ("the crack's length in the part" if scale == length else
                                                        f"the distance to {dom.obstacle}") + ")")
    if radius < TIP_RADIUS_ELEMENTS * dom.element_size and dom.element_size > scale / TIP_ELEMENTS:
        return ModelWarning("tip_region", (
            f"{where}: the tip element ({dom.element_size:.3g}) is coarse for a tip enriched on its own cell only "
            f"(options.radius = {radius:g}); {what}: K converges only like h there and is likely more than 1 % low "
            f"(4.6 % for a C(T) with 9 elements per crack scale). Set options.radius to a few tip elements (e.g. "
            f"{5 * dom.element_size:.3g}) and refine the tip (mesh.tip_h <= {scale / TIP_ELEMENTS:.3g})"
            + _let_cracklip_refine(model)), ci, dom.tip)
    if coarse > scale / REGION_ELEMENTS:
        return ModelWarning("tip_region", (
            f"{where}: the mesh around the tip is coarse for the crack: elements up to {coarse:.3g} within "
            f"{REGION_EXTENT * scale:.3g} of it while {what}, fewer than {REGION_ELEMENTS:g} elements across it; K "
            "converges from below and is likely 0.5-2 % low (a refined tip alone does not help: the field around "
            f"the crack sets K). Refine the region (mesh.h, or mesh.refine around the crack with h <= "
            f"{scale / REGION_ELEMENTS / 1.5:.3g})" + _let_cracklip_refine(model)), ci, dom.tip)
    return None


def _let_cracklip_refine(model) -> str:
    """The tip warnings' last fix: the accuracy target, unless the run has
    one (this mesh is then one of its levels, and its estimate says more)."""
    if model.scene.options.accuracy > 0.0:
        return " (this run's accuracy target refined the mesh: its estimate of K's error says how far)"
    return ", or let cracklip refine: options.accuracy = 0.01 (--accuracy 0.01)"


def _pieces(model) -> tuple[np.ndarray, np.ndarray]:
    """Connected pieces of the cracked part (triangles or tetrahedra): for
    every node its component on its own side, and for nodes lying on a
    crack (phi = 0 in a cell the crack splits whole) the component of their
    other side (-1 if none). Returns (comp (N,), comp_other (N,)).

    The graph's vertices are the nodes and a copy of every node on a crack
    (the node stands for the crack's + side there, the copy for its - side).
    A cell no crack touches joins its nodes; a cell a crack splits whole
    (crack_type.SPLIT) joins the nodes of each side with the on-crack
    nodes' copies of that side; any other cell with on-crack nodes joins
    them on the side it lies on (cell_side), or both copies where the crack
    ends in or beyond it (a tip or front cell, the extension). numpy over
    the cells, no Python loop over the mesh."""
    x, cells = model.x, model.cells
    N, nv = x.shape[0], cells.shape[1]
    C = cells.shape[0]
    split_classes = model.crack_type.SPLIT
    geos = [(np.asarray(g.phi), np.asarray(g.cell_class), np.asarray(g.cell_side)) for g in model.geometries]
    copy = np.full(N, -1, dtype=np.int64)  # the other-side copy of on-crack nodes
    split_by = np.full(C, -1, dtype=np.int64)  # the first crack splitting each cell whole
    touched = np.zeros(C, dtype=bool)
    next_id = N
    for k, (phi, cls, _) in enumerate(geos):
        split = np.isin(cls, split_classes)
        on_nodes = np.unique(cells[split][phi[cells[split]] == 0.0])
        fresh = on_nodes[copy[on_nodes] < 0]
        copy[fresh] = np.arange(next_id, next_id + fresh.size)
        next_id += fresh.size
        split_by[(split_by < 0) & split] = k
        touched |= cls != 0
    has_copy = copy >= 0
    special = touched | np.any(has_copy[cells], axis=1)
    rows, cols = [], []

    def star(ids: np.ndarray, include: np.ndarray) -> None:
        """Join the included vertices of each row of ids to the row's first included one."""
        keep = include.any(axis=1)
        ids, include = ids[keep], include[keep]
        first = ids[np.arange(len(ids)), include.argmax(axis=1)]
        rows.append(np.broadcast_to(first[:, None], ids.shape)[include])
        cols.append(ids[include])

    bulk = cells[~special]
    star(bulk, np.ones(bulk.shape, dtype=bool))
    for k, (phi, _, _) in enumerate(geos):
        c = cells[split_by == k]
        ph = phi[c]
        for s in (1, -1):
            present = np.any(np.sign(ph) == s, axis=1)[:, None]
            ids = np.where(ph == 0.0, c if s > 0 else copy[c], c)
            star(ids, ((np.sign(ph) == s) | (ph == 0.0)) & present)
    other = np.flatnonzero(special & (split_by < 0))
    c = cells[other]
    # The side each on-crack vertex joins: +1 / -1 from the cells' sides of
    # the cracks it lies on (where the cell is plain for that crack), 2 where
    # they disagree, 0 where no crack says (the crack ends in or beyond the cell).
    side = np.zeros(c.shape, dtype=np.int8)
    for phi, cls, cside in geos:
        s = np.where((phi[c] == 0.0) & (cls[other] == 0)[:, None], cside[other][:, None], 0).astype(np.int8)
        side = np.where((side != 0) & (s != 0) & (side != s), np.int8(2), np.where(side == 0, s, side))
    own = np.where(has_copy[c] & (side == -1), copy[c], c)
    star(own, np.ones(c.shape, dtype=bool))
    both = has_copy[c] & ((side == 0) | (side == 2))
    rows.append(c[both])
    cols.append(copy[c[both]])
    r, cc = np.concatenate(rows), np.concatenate(cols)
    graph = sp.coo_matrix((np.ones(len(r)), (r, cc)), shape=(next_id, next_id))
    _, comp = scipy.sparse.csgraph.connected_components(graph, directed=False)
    other_side = np.where(has_copy, comp[np.maximum(copy, 0)], -1)
    return comp[:N], other_side


def check_pieces(model) -> None:
    """Raise BoundaryConditionError if the cracks cut the part (planar or
    solid) into pieces and one of them has no Dirichlet condition fixing
    its rigid motion: the error names the cracks and every piece (its
    nodes, its bounding box, what fixes it or what it leaves free). Only
    cracks that do not end inside the part (no tip, no front there) can
    cut a piece off."""
    if all(cm.ends_inside() for cm in model.cracks):
        return
    if model.distributed:
        not_parallel("a crack without a tip inside the part (the pieces it may cut off are checked on one "
                     "process only)", model.V.mesh.comm)
    comp, other = _pieces(model)
    labels = np.unique(comp)
    if labels.size < 2:
        return
    N, d = model.x.shape
    layout = model.layout
    bc = np.asarray(model.bc_dofs)
    std = bc[bc < d * N]
    entries = [(comp[std // d], std // d, std % d)]
    # A constrained enriched (Heaviside) dof also fixes the other side at its node.
    enr = bc[bc >= d * N] // d - N
    if enr.size:
        base = np.asarray(layout.node)[enr]
        side_comp = _other_side_components(model, comp, other, base, np.asarray(layout.crack)[enr])
        comps = bc[bc >= d * N] % d
        keep = side_comp >= 0
        entries.append((side_comp[keep], base[keep], comps[keep]))
    pc = np.concatenate([e[0] for e in entries])
    nodes = np.concatenate([e[1] for e in entries])
    dirs = np.concatenate([e[2] for e in entries])
    names = ", ".join(repr(cm.crack.name) for cm in model.cracks if not cm.ends_inside())
    tiny = 1e-12 * float(np.ptp(model.x, axis=0).max())
    loose, held = [], []
    for lab in labels.tolist():
        members = np.flatnonzero(comp == lab)
        lo, hi = model.x[members].min(axis=0), model.x[members].max(axis=0)
        lo, hi = np.where(np.abs(lo) < tiny, 0.0, lo), np.where(np.abs(hi) < tiny, 0.0, hi)
        box = " x ".join(f"[{a:.6g}, {b:.6g}]" for a, b in zip(lo, hi))
        mine = pc == lab
        rank, free = rigid_motion_rank(model.x, nodes[mine], dirs[mine])
        piece = f"the piece of {members.size} nodes in {box}"
        if rank < d + len(ROTATIONS[d]):
            loose.append(f"{piece} has no Dirichlet condition fixing its {', '.join(free)}")
        else:
            held.append(f"{piece} is held")
    if loose:
        raise BoundaryConditionError(
            f"the crack(s) {names} cut the part into {labels.size} pieces; " + "; ".join(loose + held)
            + ". The solve would meet a singular matrix: add a Dirichlet condition on every loose piece (a tag, "
            "box or point on it), or end the crack inside the part")


def _other_side_components(model, comp, other, base: np.ndarray, crack: np.ndarray) -> np.ndarray:
    """Component of the other side of the crack at each node of `base` (the
    node's other-side copy, else a node sharing a cell with it on the other
    side of that crack; -1 if none). Work proportional to the nodes given."""
    out = np.where(other[base] >= 0, other[base], -1)
    todo = np.flatnonzero(out < 0)
    if not todo.size:
        return out
    cells = model.cells
    N = model.x.shape[0]
    incidence = sp.csr_matrix((np.ones(cells.size), (cells.ravel(), np.repeat(np.arange(cells.shape[0]),
                                                                            cells.shape[1]))),
                              shape=(N, cells.shape[0]))
    neighbours = (incidence[base[todo]] @ incidence.T).tocsr()  # (todo, N): nodes sharing a cell
    for c in np.unique(crack[todo]).tolist():
        phi = np.asarray(model.geometries[c].phi)
        for j in np.flatnonzero(crack[todo] == c).tolist():
            row = neighbours.indices[neighbours.indptr[j]:neighbours.indptr[j + 1]]
            n = base[todo[j]]
            opposite = row[np.sign(phi[row]) == -np.sign(phi[n])]
            if opposite.size:
                out[todo[j]] = comp[opposite[0]]
    return out


# -- solids: the crack fronts ------------------------------------------------------------

#: Cell class of the cells holding the front (CellClass3D::front).
FRONT_CLASS = 3


#: A front whose elements exceed this fraction of the crack's size is warned
#: about (the penny crack at a / h = 8 opens 2.3 % off Sneddon's; at a / h =
#: 4 the front cells span a quarter of the radius).
FRONT_RESOLUTION = 0.2


def front_cells(geometry) -> np.ndarray:
    """The cells holding a crack's front."""
    return np.flatnonzero(np.asarray(geometry.cell_class) == FRONT_CLASS).astype(np.int32)


def front_element_sizes(model, crack: int) -> np.ndarray:
    """The element size (mean edge length) of every cell holding a crack's
    front (empty without a front). Collective under MPI: every process's
    owned front cells, in rank order."""
    fc = front_cells(model.geometries[crack])
    if not model.distributed:
        return cell_sizes(model.x, model.cells[fc])
    fc = fc[model.owned_cells_only(fc)]
    return np.concatenate(model.V.mesh.comm.allgather(cell_sizes(model.x, model.cells[fc])))


def crack_size(crack) -> float:
    """A crack's size: its smaller semi-axis for an ellipse, else twice its
    area over the length of its whole boundary (the radius of a circle)."""
    if hasattr(crack, "b") and hasattr(crack, "a"):
        return float(min(crack.a, crack.b))
    if hasattr(crack, "boundary_edges"):
        e = crack.boundary_edges()
        length = float(np.linalg.norm(crack.vertices[e[:, 1]] - crack.vertices[e[:, 0]], axis=1).sum())
    else:
        p = crack.points
        length = float(np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1).sum())
    return 2.0 * crack.area / length if length > 0 else 0.0


def check_front_ends(name: str, front: dict) -> None:
    """Raise CrackGeometryError if an open piece of the front (dict of
    CrackGeometry3D.front) has an end that is not on the part's boundary."""
    offsets = np.asarray(front["piece_offsets"])
    on = np.asarray(front["on_boundary"])
    x = np.asarray(front["x"]).reshape(-1, 3)
    for k, closed in enumerate(np.asarray(front["closed"])):
        if closed:
            continue
        for end in (int(offsets[k]), int(offsets[k + 1]) - 1):
            if not on[end]:
                branch = int(front["num_branch_points"])
                why = (f" (the P1 front meets itself at {branch} point(s) there: the crack surface touches itself "
                       "or runs along mesh faces)" if branch else "")
                raise CrackGeometryError(
                    f"{name}: the front (piece {k} of {len(offsets) - 1}) ends at "
                    f"({', '.join(f'{v:.6g}' for v in x[end])}) inside the part, off its boundary{why}: a front must "
                    "be closed (an embedded crack) or end on the part's boundary (a surface or corner crack). Check "
                    "that the crack does not fold onto itself, move it off the mesh nodes by a fraction of the "
                    "element size, or refine the mesh along its front (mesh.tip_h)")


def check_enrichment_radius(model) -> None:
    """Raise InputError when options.radius > 0 reaches no node of a crack's front."""
    opts = model.scene.options
    if opts.radius <= 0.0 or opts.enrichment == "none":
        return
    r = opts.radius
    comm = model.V.mesh.comm  # (a serial model's: one process)
    for cm in model.cracks:
        g = cm.geometry
        if not len(g.front["x"]):  # (the joined front: alike on every process)
            continue
        phi, psi = np.asarray(g.phi), np.asarray(g.psi)
        cand = np.flatnonzero((np.abs(phi) <= r) & (np.abs(psi) <= r))
        reached = bool(cand.size) and bool(np.any(
            _cracklip.compute_front_projection_3d(g, np.ascontiguousarray(model.x[cand]))["distance"] <= r))
        # Under MPI a process may hold no node near the front: the verdict and
        # the nearest node are the whole mesh's.
        if reduced(reached, "LOR", comm):
            continue
        nodes = np.unique(model.cells[front_cells(g)])
        d = _cracklip.compute_front_projection_3d(g, np.ascontiguousarray(model.x[nodes]))["distance"]
        nearest = float(reduced(float(np.min(d, initial=np.inf)), "MIN", comm))
        h = float(front_element_sizes(model, model.cracks.index(cm)).mean())
        raise InputError(
            f"{cm.crack.name}: the enrichment radius options.radius = {r:.3g} reaches no node (the nearest node is "
            f"{nearest:.3g} from the front, where the elements are {h:.3g}): only the front cells' own nodes would "
            f"get front functions; give a radius of 2 to 3 elements there (e.g. {2.5 * h:.3g}), or 0 for the front "
            "cells' nodes only")


def check_fronts(model) -> list[ModelWarning]:
    """The checks of a solid's crack fronts: raise on a broken front or a
    radius that reaches no node; return the warnings (module doc)."""
    out: list[ModelWarning] = []
    opts = model.scene.options
    for ci, cm in enumerate(model.cracks):
        g = cm.geometry
        front = g.front
        name = cm.crack.name
        check_front_ends(name, front)
        w = _unopened_faces(model, ci)
        if w is not None:
            out.append(w)
        if not len(front["x"]):
            continue
        h = front_element_sizes(model, ci)
        size = crack_size(cm.crack)
        hm = float(h.mean())
        if size > 0.0 and hm > FRONT_RESOLUTION * size:
            out.append(ModelWarning(
                "front_resolution", f"crack {name!r}: the elements along its front ({hm:.3g} on average) are coarser "
                f"than {FRONT_RESOLUTION:g} times the crack's size ({size:.3g}): the opening near the front is not "
                f"resolved; refine along the front (mesh.tip_h <= {0.1 * size:.3g})", ci))
        if opts.enrichment == "none":
            out.append(ModelWarning(
                "front_enrichment", f"crack {name!r}: without front enrichment (options.enrichment = 'none') the "
                "crack ends at the faces of the front cells and the sqrt(r) field is not represented", ci))
        elif 0.0 < opts.radius < hm:
            out.append(ModelWarning(
                "enrichment_radius", f"crack {name!r}: the enrichment radius {opts.radius:.3g} is smaller than the "
                f"elements along the front ({hm:.3g}): few nodes beyond the front cells' get front functions; use a "
                "radius of 2 to 3 elements", ci))
        hole = _crack_hole(cm.crack, name, front, ci)
        if hole is not None:
            out.append(hole)
        if g.num_degenerate_front_cells:
            out.append(ModelWarning(
                "degenerate_front", f"crack {name!r}: {g.num_degenerate_front_cells} front cell(s) where the P1 front "
                "is not a line (a corner of the crack on a mesh node, or its edge along mesh edges); move the crack "
                "off the nodes by a fraction of the element size", ci))
    check_enrichment_radius(model)
    return out


def _crack_hole(crack, name: str, front: dict, ci: int) -> ModelWarning | None:
    """The 'crack_hole' warning: a triangulated crack (STL, .msh) whose front
    has a closed piece besides other pieces. The closed piece is the edge
    of a hole in the triangulation inside the part: cracklip models it as
    an uncracked ligament whose edge is a front (K computed along it, the
    lips joined across it), which a gap left in an exported STL makes
    without a word (an ellipse's half-disc with a hole of radius 0.3
    inside the part: a closed front piece of 13 points, 1.59 long, and no
    warning)."""
    if not hasattr(crack, "boundary_edges"):
        return None
    closed = np.asarray(front["closed"], dtype=bool)
    if len(closed) < 2 or not closed.any() or surface_holes(crack) == 0:
        return None
    offsets = np.asarray(front["piece_offsets"])
    x = np.asarray(front["x"]).reshape(-1, 3)
    pieces = []
    for k in np.flatnonzero(closed):
        px = x[int(offsets[k]):int(offsets[k + 1])]
        pieces.append((float(np.linalg.norm(np.diff(np.vstack([px, px[:1]]), axis=0), axis=1).sum()), int(k), px))
    if closed.all():  # an embedded crack: its longest loop is its outer edge
        pieces.remove(max(pieces, key=lambda p: p[0]))
    if not pieces:
        return None
    where = [f"piece {k}: {len(px)} points, length {length:.4g}, around "
             f"({', '.join(f'{v:.4g}' for v in px.mean(axis=0))})" for length, k, px in pieces]
    return ModelWarning("crack_hole", (
        f"crack {name!r}: its front has {len(closed)} pieces, {len(pieces)} of them closed loops inside the "
        f"surface ({'; '.join(where)}): the triangulated surface has a hole there, modelled as an uncracked "
        "ligament whose "
        "edge is a front (K is computed along it and the lips stay joined inside it). If the file has a gap there "
        "(a missing triangle, vertices not merged), close it; if the ligament is meant, ignore this"), ci)


def surface_holes(crack) -> int:
    """The holes of a triangulated crack: its boundary loops less its
    connected pieces (each piece a disc with holes: a piece's outer edge is
    one loop, every hole another)."""
    t = np.asarray(crack.triangles)
    e = np.sort(t[:, [[0, 1], [1, 2], [2, 0]]].reshape(-1, 2), axis=1)
    uniq, inv, count = np.unique(e, axis=0, return_inverse=True, return_counts=True)
    n = len(crack.vertices)
    # triangles joined through their shared edges
    tri = np.repeat(np.arange(len(t)), 3)
    g = sp.coo_matrix((np.ones(len(tri)), (tri, inv.reshape(-1))), shape=(len(t), len(uniq))).tocsr()
    pieces = scipy.sparse.csgraph.connected_components(g @ g.T, directed=False)[0]
    b = uniq[count == 1]
    if not len(b):
        return 0
    used = np.unique(b)
    adj = sp.coo_matrix((np.ones(len(b)), (b[:, 0], b[:, 1])), shape=(n, n))
    labels = scipy.sparse.csgraph.connected_components(adj, directed=False)[1]
    loops = len(np.unique(labels[used]))
    return max(0, loops - pieces)


#: CellClass3D::face: a cell with a face on the crack, lying on one side;
#: front: the front meets it; extension: phi = 0 crosses it beyond the front.
FACE_CLASS, FRONT_CLASS, EXTENSION_CLASS = 2, 3, 4


def _unopened_faces(model, ci: int) -> ModelWarning | None:
    """The 'crack_on_faces' warning when a crack runs along mesh faces and
    the nodes on it there got no Heaviside function: nothing lets the lips
    open across those faces (hard case 3D-3, a through crack on a node
    layer, got no enriched dof at all before face cells counted in the 3D
    selection's ramp shares: the energy error stayed at 100 %). Nodes with
    front functions (they carry the jump there) and the nodes of front and
    extension cells (where the crack ends as it does through cut cells; no
    front enrichment is warned about as front_enrichment) are not counted."""
    g = model.geometries[ci]
    cls = np.asarray(g.cell_class)
    face = cls == FACE_CLASS
    if not face.any():
        return None
    phi = np.asarray(g.phi)
    cells = model.cells[face]
    on = np.unique(cells[phi[cells] == 0.0])
    lay = model.layout
    enriched = np.asarray(lay.node)[np.asarray(lay.crack) == ci]  # Heaviside or front functions
    ends = np.unique(model.cells[(cls == FRONT_CLASS) | (cls == EXTENSION_CLASS)])
    bare = np.setdiff1d(np.setdiff1d(on, enriched), ends)
    if not bare.size:
        return None
    name = model.cracks[ci].crack.name
    return ModelWarning("crack_on_faces", (
        f"crack {name!r} runs along mesh faces ({int(face.sum())} cells have a face on it) and {bare.size} of the "
        f"{on.size} nodes on it there got no Heaviside function: the lips cannot open across those faces, so the "
        "opening, the stiffness and K are wrong there. Move the crack off the mesh nodes by a small fraction of the "
        "element size (e.g. 1e-3 of it along its normal)"), ci)


# -- the scene's scale: units ---------------------------------------------------------------------

#: Young's moduli of the solids fracture mechanics deals with, in Pa: from
#: engineering polymers (PMMA 3 GPa, epoxy 2.5 GPa; 0.1 GPa leaves room for
#: soft ones) to diamond (1.05-1.2 TPa). An E outside, in the scene's
#: stress unit, is a unit slip: E in Pa with stresses in MPa is 1e6 times
#: too stiff (openings 1e6 times too small), E in GPa with MPa 1e3 too soft.
E_RANGE_PA = (1e8, 1.5e12)

#: Sizes of a part cracklip models, in metres: a part whose largest extent
#: lies outside was most likely drawn in another length unit than
#: units.length says (a 40 mm plate read in m is 40 m long; one of 40 m read
#: in mm 40 um).
SIZE_RANGE_M = (1e-4, 10.0)

#: Without [units]: loads below this fraction of E strain the part by less
#: than elastic round-off matters for, but more to the point are the mark
#: of E and the loads in different units (E in Pa, stresses in MPa: 1e-9).
LOAD_OVER_E_MIN = 1e-7


def check_units(model) -> list[ModelWarning]:
    """Warnings when the scene's numbers do not fit its units (module doc of
    the constants): material.E against the usual range in units.stress,
    the part's size against units.length, and without [units] constant
    tractions and lip pressures far below E."""
    scene = model.scene
    units = scene.units
    E = scene.material.E
    size = part_size(model)  # (the whole part under mpirun, alike on every process)
    out = []
    if units is not None:
        E_pa = E * units.stress_si
        lo, hi = E_RANGE_PA
        if not lo <= E_pa <= hi:
            fits = [name for name, f in STRESSES.items() if lo <= E * f <= hi]
            likely = f"; {E:g} would be a usual E in {' or '.join(fits)}" if fits else ""
            out.append(ModelWarning("units", (
                f"material.E = {E:g} {units.stress_name} (the stress unit of [units]) is "
                f"{E_pa / 1e9:.3g} GPa, outside the {lo / 1e9:g} GPa .. {hi / 1e12:g} TPa of solids (polymers to "
                f"diamond){likely}: every displacement and opening scales with 1 / E, so a unit slip makes them "
                f"{'too small' if E_pa > hi else 'too large'} by that factor (K from loads alone is not affected; "
                "with prescribed displacements it is too). Give material.E in the stress unit of [units] (e.g. "
                "70000 for aluminium in MPa), or fix units.stress")))
        size_m = size * units.length_si
        lo, hi = SIZE_RANGE_M
        if not lo <= size_m <= hi:
            slip = ("a part drawn in mm read in m is 1000 times too large" if size_m > hi else
                    "a part drawn in m read in mm is 1000 times too small")
            out.append(ModelWarning("units", (
                f"the part is {size:.4g} {units.length} across (the largest side of its bounding box)"
                + ("" if units.length == "m" else f", i.e. {size_m:.3g} m") + ", "
                f"{'more' if size_m > hi else 'less'} than the {lo * 1e3:g} mm .. {hi:g} m of the "
                f"parts cracklip models: was the geometry drawn in another unit than units.length = "
                f"{units.length!r} ({slip})? Every length of the "
                "scene (mesh.h, tip_h, the cracks, the loads' positions) is in units.length; set it to the "
                "geometry's unit")))
    else:
        loads = [abs(float(v)) for tr in scene.tractions if tr.value is not None and not callable(tr.value)
                 for v in np.ravel(tr.value)]
        loads += [abs(float(c.pressure)) for c in scene.cracks if not callable(getattr(c, "pressure", 0.0))
                  and getattr(c, "pressure", 0.0)]
        largest = max(loads, default=0.0)
        if largest > 0.0 and largest < LOAD_OVER_E_MIN * E:
            out.append(ModelWarning("units", (
                f"the largest traction or lip pressure ({largest:.3g}) is {largest / E:.2g} of material.E "
                f"({E:.4g}): strains of that size are the mark of E and the loads in different units (E in Pa "
                "with stresses in MPa gives 1e-9); the displacements and openings scale with 1 / E. Give E in the "
                "loads' unit, and name them in a [units] table (units.length, units.stress)")))
    return out
