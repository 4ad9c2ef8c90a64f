"""Model checks shared by ``cracklip check`` and ``run``: what would make a K
or a solve untrustworthy, found before solving.

- ``check_pieces(model)`` raises BoundaryConditionError when the cracks cut
  the part into pieces and one of them has no Dirichlet condition fixing
  its rigid motion (the solve would fail on a singular matrix);
- ``check_model(model)`` returns warnings: a refinement that the mesh did not
  reach, a tip element coarser than a tenth of the crack length or than the
  enrichment radius, a tip without tip enrichment (K only to O(sqrt(h))),
  a tip within an element of the boundary, SIF domains
  clipped by the boundary, other tips, other cracks, kinks or holes.

A warning is a ``ModelWarning`` (code, message, crack, tip); results.json
lists them and the command line prints them on stderr.
"""
from __future__ import annotations

import dataclasses
import typing

import numpy as np
import scipy.sparse as sp
import scipy.sparse.csgraph

from ..errors import BoundaryConditionError
from .constraints import rigid_motion_rank
from .tip_regions import lip_points, model_boundary, segment_distance, tip_domains, tip_element_size


#: A refinement whose achieved element size exceeds the asked one by this factor is warned about.
REFINEMENT_TOLERANCE = 1.5


@dataclasses.dataclass(frozen=True)
class ModelWarning:
    """Something that makes a result less trustworthy, with the fix.

    Attributes:
        code: refinement, tip_resolution, tip_enrichment, enrichment_radius,
            tip_near_boundary, sif_domain or sif_spread.
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


def check_model(model) -> list[ModelWarning]:
    """Every model check that does not need the solution (see the module doc)."""
    out: list[ModelWarning] = []
    md = model.scene.mesh
    for (x, y, size) in md.refinements:
        got = tip_element_size(model, np.array([x, y]))
        if got > REFINEMENT_TOLERANCE * size:
            out.append(ModelWarning("refinement", f"the mesh refinement at ({x:.6g}, {y:.6g}) asked for elements "
                                    f"of {size:.3g} and got {got:.3g}: the size field could not be honoured "
                                    "(check mesh.tip_h / mesh.refine against mesh.h)"))
    a, b = model_boundary(model)
    radius = model.scene.options.radius
    enrichment = model.scene.options.enrichment
    for ci, cm in enumerate(model.cracks):
        g = cm.geometry
        tips = np.asarray(g.tips).reshape(-1, 2)
        if not len(tips):
            continue
        length = float(lip_points(model, ci)["weight"].sum())
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
    return out


def _pieces(model) -> tuple[np.ndarray, np.ndarray]:
    """Connected pieces of the cracked part: for every node its component on
    its own side, and for nodes lying on a crack (phi = 0 in a crossed cell)
    the component of their other side (-1 if none). Returns (comp (N,),
    comp_other (N,))."""
    x, cells = model.x, model.cells
    N = x.shape[0]
    geos = model.geometries
    copy = np.full(N, -1, dtype=np.int64)  # the other-side copy of on-crack nodes
    special = np.zeros(cells.shape[0], dtype=bool)
    next_id = N
    for g in geos:
        cls = np.asarray(g.cell_class)
        crossed = (cls == 1) | (cls == 2)
        on = np.asarray(g.phi) == 0.0
        on_nodes = np.unique(cells[crossed][on[cells[crossed]]])
        fresh = on_nodes[copy[on_nodes] < 0]
        copy[fresh] = np.arange(next_id, next_id + fresh.size)
        next_id += fresh.size
        special |= cls != 0
    has_copy = copy >= 0
    special |= np.any(has_copy[cells], axis=1)
    rows, cols = [], []
    bulk = cells[~special]
    for i, j in ((0, 1), (1, 2)):
        rows.append(bulk[:, i])
        cols.append(bulk[:, j])

    def ident(node: int, side: int) -> int:
        return int(copy[node]) if side < 0 and copy[node] >= 0 else int(node)
    for c in np.flatnonzero(special).tolist():
        verts = cells[c]
        pieces: list[list[int]] = [[int(v) for v in verts]]
        for g in geos:
            cls = int(g.cell_class[c])
            phi = np.asarray(g.phi)[verts]
            if cls in (1, 2):  # cut / edge: one piece per side present
                sides = [s for s in (1, -1) if np.any(np.sign(phi) == s)]
                pieces = [[ident(v, s) if ph == 0.0 else int(v) for v, ph in zip(verts, phi) if ph == 0.0 or np.sign(ph) == s]
                          for s in sides]
                break
        else:
            # Not crossed: the nodes on a crack join the cell's side, or both
            # copies where the crack ends in or beyond the cell (tip, extension).
            piece = []
            for v in verts:
                piece.append(int(v))
                if copy[v] >= 0:
                    sides = [int(g.cell_side[c]) for g in geos if int(g.cell_class[c]) == 0 and g.phi[v] == 0.0]
                    if sides and all(s == sides[0] for s in sides) and sides[0] != 0:
                        piece[-1] = ident(int(v), sides[0])
                    else:
                        piece.append(int(copy[v]))
            pieces = [piece]
        for piece in pieces:
            rows.append(np.asarray(piece[:-1], dtype=np.int64))
            cols.append(np.asarray(piece[1:], dtype=np.int64))
    r, c = np.concatenate(rows), np.concatenate(cols)
    graph = sp.coo_matrix((np.ones(len(r)), (r, c)), shape=(next_id, next_id))
    _, comp = scipy.sparse.csgraph.connected_components(graph, directed=False)
    other = np.where(has_copy, comp[np.maximum(copy, 0)], -1)
    return comp[:N], other


def check_pieces(model) -> None:
    """Raise BoundaryConditionError if a crack cuts off a piece of the part
    whose rigid motion no Dirichlet condition fixes. Only cracks without a
    tip inside the part (both ends on the boundary) can cut a piece off."""
    if not any(sum(cm.tips) == 0 for cm in model.cracks):
        return
    comp, other = _pieces(model)
    labels = np.unique(comp)
    if labels.size < 2:
        return
    N = model.x.shape[0]
    layout = model.layout
    std = model.bc_dofs[model.bc_dofs < 2 * N]
    entries = [(comp[std // 2], std // 2, std % 2)]
    # A constrained Heaviside dof also fixes the other side at its node.
    enr = model.bc_dofs[model.bc_dofs >= 2 * N] // 2 - N
    if enr.size:
        base = np.asarray(layout.node)[enr]
        side_comp = _other_side_components(model, comp, other, base, np.asarray(layout.crack)[enr])
        comps = model.bc_dofs[model.bc_dofs >= 2 * N] % 2
        keep = side_comp >= 0
        entries.append((side_comp[keep], base[keep], comps[keep]))
    pc = np.concatenate([e[0] for e in entries])
    nodes = np.concatenate([e[1] for e in entries])
    dirs = np.concatenate([e[2] for e in entries])
    names = ", ".join(repr(cm.crack.name) for cm in model.cracks if sum(cm.tips) == 0)
    for lab in labels.tolist():
        mine = pc == lab
        rank, free = rigid_motion_rank(model.x, nodes[mine], dirs[mine])
        if rank < 3:
            members = np.flatnonzero(comp == lab)
            lo, hi = model.x[members].min(axis=0), model.x[members].max(axis=0)
            tiny = 1e-12 * float(np.ptp(model.x, axis=0).max())
            lo, hi = np.where(np.abs(lo) < tiny, 0.0, lo), np.where(np.abs(hi) < tiny, 0.0, hi)
            raise BoundaryConditionError(
                f"the crack(s) {names} cut the part into {labels.size} pieces; the piece of {members.size} nodes "
                f"in [{lo[0]:.6g}, {hi[0]:.6g}] x [{lo[1]:.6g}, {hi[1]:.6g}] has no Dirichlet condition fixing "
                f"its {', '.join(free)}: add a condition on that piece, or end the crack inside the part")


def _other_side_components(model, comp, other, base: np.ndarray, crack: np.ndarray) -> np.ndarray:
    """Component of the other side of the crack at each node of `base`."""
    out = np.full(base.size, -1, dtype=np.int64)
    for k, (n, c) in enumerate(zip(base.tolist(), crack.tolist())):
        if other[n] >= 0:
            out[k] = other[n]
            continue
        g = model.geometries[c]
        phi = np.asarray(g.phi)
        around = model.cells[np.any(model.cells == n, axis=1)]
        opposite = around[np.sign(phi[around]) == -np.sign(phi[n])]
        if opposite.size:
            out[k] = comp[opposite[0]]
    return out
