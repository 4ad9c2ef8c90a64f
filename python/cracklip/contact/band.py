"""The stable multiplier groups computed alike on every process (issue 40):
the crack band gathered, its space built in input order.

The P1- reduction (cpp/contact/multiplier_groups.h) is a graph computation
over a whole crack: vital edges are dropped greedily by degree, stars
without a jump join a neighbour, the groups at tips and fronts absorb
neighbours. Its choices are geometric (ties broken by positions, not by
numbers), so the groups do not depend on the order of nodes, cells or
edges; but a process's part of the mesh (owned cells and a ghost layer)
sees only part of the crack, and the numbering of the groups follows the
order of their members, DOLFINx's local order, which depends on the
partition. Building the space per process would give groups that differ
at the partition, numbered differently on every process.

So every process gathers every process's lip pieces of its owned cells (a
piece is one cell of one crack: 2D the segment-owning crack cells and the tip
cells, 3D the crack cells holding lip facets), keyed by the cell's input
index and its nodes' input indices (the mesh's order as given to DOLFINx,
the same on any number of processes), with the level set at the nodes, the
piece's reference coordinates and which nodes carry enriched (Heaviside)
dofs of the crack: a few hundred bytes per cut cell. The band is numbered in
input order (cells by input index, nodes by input index, the vertices of a
cell by their input indices, the reference coordinates permuted with them)
and the unchanged C++ space (create_multiplier_space(_3d)) runs on it
(python/wrappers/contact_band.cpp rebuilds the crack geometries from the
arrays). Every process and a serial run (the same path on one process) get
the same groups (in any order of the band: tests/test_contact_order.py)
numbered alike.

The process's own multiplier space (on its local mesh, for the coupling B
and the pressure at points) names its full multipliers by (crack, node) and
(crack, cell); their input keys find them in the band, whose groups give the
prolongation R (local full -> global reduced). A ghost cell's piece that the
band lacks (never integrated here) maps to no group.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import scipy.sparse as sp

from .. import _cracklip
from ..errors import SolverError
from ..scene.cell_size import cell_sizes
from ..scene.partition import node_input_indices
from ..scene.processes import agree, gathered

#: cpp/enrichment/enrichment_selection.h EnrichmentKind::heaviside, and a
#: kind standing for any other enrichment (the band space only tells
#: "enriched" from "Heaviside-enriched").
HEAVISIDE, OTHER = 0, 1

#: Input indices fit in 40 bits: a full multiplier's key packs (crack, P0 flag, input index).
_ID_BITS = 40


@dataclasses.dataclass
class BandSpace:
    """The multiplier space of the gathered band.

    Attributes:
        space: the C++ space on the band mesh (its groups are the reduced multipliers).
        node_key, cell_key: input index of every band node and cell (ascending).
        group_h: per group (reduced multiplier), the mean over its members
            of their element size: a nodal multiplier's the largest mean
            edge of the band cells at its node, a P0 one its cell's
            (the multipliers' stabilization, contact/stabilization.py).
        group_x: (num_reduced, gdim) a point of each group on its crack:
            the mean of its vital edges' cut points (group_points).
    """
    space: object
    node_key: np.ndarray
    cell_key: np.ndarray
    group_h: np.ndarray
    group_x: np.ndarray

    @property
    def num_reduced(self) -> int:
        return int(self.space.num_reduced)

    def full_keys(self) -> np.ndarray:
        """The input key of every full multiplier of the band space."""
        s = self.space
        node, cell = np.asarray(s.full_node), np.asarray(s.full_cell)
        ids = np.where(node >= 0, self.node_key[np.maximum(node, 0)], self.cell_key[np.maximum(cell, 0)])
        return _full_key(np.asarray(s.full_crack), node < 0, ids)


def _full_key(crack: np.ndarray, p0: np.ndarray, ids: np.ndarray) -> np.ndarray:
    return ((crack.astype(np.int64) * 2 + p0) << _ID_BITS) + ids.astype(np.int64)


def _node_keys(model) -> np.ndarray:
    """The input index of every local node."""
    return node_input_indices(model.V.mesh, model.cells, len(model.x))


def _cell_keys(model) -> np.ndarray:
    """The input index of every local cell."""
    return np.asarray(model.V.mesh.topology.original_cell_index, dtype=np.int64)


def _enriched_flags(model, nodes: np.ndarray, crack: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Whether local nodes (k, v) carry enriched, and Heaviside, dofs of crack (k,)."""
    lay = model.layout
    n = lay.num_std_nodes
    code = np.asarray(lay.crack, dtype=np.int64) * n + np.asarray(lay.node)
    kind = np.asarray(lay.kind)
    query = crack[:, None].astype(np.int64) * n + nodes
    return np.isin(query, code), np.isin(query, code[kind == HEAVISIDE])


def _local_pieces(model) -> dict[str, np.ndarray]:
    """This process's pieces on its owned cells (module doc), one row each."""
    cells = model.cells
    node_input, original = _node_keys(model), _cell_keys(model)
    tdim = model.gdim
    rows = {k: [] for k in ("crack", "cell", "cls", "tip", "nfacets", "ref")}
    for ic, g in enumerate(model.geometries):
        cc = g.crack_cells
        if tdim == 2:
            keep = cc["owns_segment"].astype(bool) & model.owned_cells_only(cc["cell"])
            tc = g.tip_cells
            tkeep = model.owned_cells_only(tc["cell"])
            parts = [(cc["cell"][keep], cc["cls"][keep], np.full(keep.sum(), -1), np.ones(keep.sum(), int),
                      cc["segment"][keep]),
                     (tc["cell"][tkeep], np.full(tkeep.sum(), -1), tc["tip"][tkeep], np.ones(tkeep.sum(), int),
                      tc["segment"][tkeep])]
        else:
            nf = np.diff(cc["facet_offsets"])
            keep = (nf > 0) & model.owned_cells_only(cc["cell"])
            facets = cc["facets"].reshape(-1, 3, 3)[np.repeat(keep, nf)]
            parts = [(cc["cell"][keep], cc["cls"][keep], np.full(keep.sum(), -1), nf[keep], facets)]
        for cell, cls, tip, nfacets, ref in parts:
            rows["crack"].append(np.full(len(cell), ic))
            rows["cell"].append(np.asarray(cell, dtype=np.int64))
            rows["cls"].append(cls)
            rows["tip"].append(tip)
            rows["nfacets"].append(nfacets)
            rows["ref"].append(np.asarray(ref, dtype=float).reshape(-1, tdim))
    out = {k: np.concatenate(v) if v else np.zeros(0) for k, v in rows.items()}
    cell = out["cell"].astype(np.int64)
    crack = out["crack"].astype(np.int64)
    verts = cells[cell]                                                           # (k, d + 1) local nodes
    enriched, heaviside = _enriched_flags(model, verts, crack)
    phi = np.stack([np.asarray(model.geometries[c].phi)[v] for c, v in zip(crack, verts)]) if len(cell) else \
        np.zeros((0, tdim + 1))
    return {"crack": crack, "cell": original[cell], "cls": out["cls"].astype(np.int8),
            "tip": out["tip"].astype(np.int32), "nfacets": out["nfacets"].astype(np.int32),
            "ref": out["ref"], "node": node_input[verts], "x": model.x[verts].reshape(len(cell), (tdim + 1) * tdim),
            "phi": phi, "enriched": enriched, "heaviside": heaviside}


def create_band_space(model) -> BandSpace:
    """Collective: the multiplier space of every process's gathered lip
    pieces, in input order (module doc)."""
    comm = model.V.mesh.comm
    d = model.gdim
    opts = model.scene.options
    names = ("crack", "cell", "cls", "tip", "nfacets", "ref", "node", "x", "phi", "enriched", "heaviside")
    mine = _local_pieces(model)
    p = dict(zip(names, gathered(comm, [mine[k] for k in names])))
    k = len(p["cell"])
    # Every cell's vertices in input order, its pieces' reference points
    # (2D: P, Q; 3D: 3 per facet) with them (barycentric coordinates permuted).
    perm = np.argsort(p["node"], axis=1, kind="stable")
    per_piece = p["nfacets"] * (2 if d == 2 else 3)
    piece_of = np.repeat(np.arange(k), per_piece)
    bary = np.column_stack([1.0 - p["ref"].sum(axis=1), p["ref"]])
    ref = np.take_along_axis(bary, perm[piece_of], axis=1)[:, 1:]
    # Pieces by crack, then cell (crack cells before tip cells); their points along.
    order = np.lexsort((p["cls"] == -1, p["cell"], p["crack"]))
    first = np.cumsum(per_piece) - per_piece
    ref = ref[np.repeat(first[order] - (np.cumsum(per_piece[order]) - per_piece[order]), per_piece[order])
              + np.arange(len(ref))]
    p = {key: v[order] for key, v in p.items() if key != "ref"}
    perm = perm[order]
    cell_key, cell_at = np.unique(p["cell"], return_inverse=True)
    node_key, node_at = np.unique(p["node"], return_inverse=True)
    node_at = node_at.reshape(p["node"].shape)
    x = np.zeros((len(node_key), d))
    x[node_at.ravel()] = p["x"].reshape(-1, d)
    cells = np.zeros((len(cell_key), d + 1), dtype=np.int32)
    cells[cell_at] = np.take_along_axis(node_at, perm, axis=1)
    ncr = len(model.cracks)
    phi = np.zeros((ncr, len(node_key)))
    phi[np.repeat(p["crack"], d + 1), node_at.ravel()] = p["phi"].ravel()
    # The enriched (node, crack) pairs: Heaviside ones, then other enriched ones.
    lay_node, lay_crack, lay_kind = [], [], []
    for flag, kind in ((p["heaviside"], HEAVISIDE), (p["enriched"] & ~p["heaviside"], OTHER)):
        pairs = np.unique(np.column_stack([node_at[flag], np.broadcast_to(p["crack"][:, None], flag.shape)[flag]]),
                          axis=0)
        lay_node.append(pairs[:, 0])
        lay_crack.append(pairs[:, 1])
        lay_kind.append(np.full(len(pairs), kind))
    layout = [np.concatenate(a).astype(t) for a, t in zip((lay_node, lay_crack, lay_kind),
                                                          (np.int32, np.int32, np.int8))]
    pieces = p["cls"] >= 0 if d == 2 else np.ones(k, dtype=bool)
    if d == 2:
        tips_of = [np.asarray(g.tips).reshape(-1, 2) for g in model.geometries]
        tip_offsets = np.concatenate([[0], np.cumsum([len(t) for t in tips_of])]).astype(np.int32)
        tips = np.concatenate(tips_of + [np.zeros((0, 2))])
        seg = ref.reshape(k, 4)
        tc = ~pieces
        space = _cracklip.create_band_multiplier_space(
            x, cells, phi, tips, tip_offsets, p["crack"][pieces].astype(np.int32), cell_at[pieces].astype(np.int32),
            p["cls"][pieces], seg[pieces], p["crack"][tc].astype(np.int32), cell_at[tc].astype(np.int32),
            p["tip"][tc], seg[tc], *layout, opts.multipliers, opts.enrichment != "none")
    else:
        facets = ref.reshape(-1, 9)
        offsets = np.concatenate([[0], np.cumsum(p["nfacets"])]).astype(np.int32)
        area = _facet_areas(x, cells[cell_at], facets, p["nfacets"])
        space = _cracklip.create_band_multiplier_space_3d(
            x, cells, phi, ncr, p["crack"].astype(np.int32), cell_at.astype(np.int32), p["cls"], offsets, facets,
            area, *layout, opts.multipliers, opts.enrichment != "none" or opts.multipliers == "stable")
    return BandSpace(space, node_key, cell_key, group_sizes(space, x, cells), group_points(space, x, phi))


def group_sizes(space, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """BandSpace.group_h of a space on the band mesh (x, cells)."""
    nv = cells.shape[1]
    h_cell = cell_sizes(x, cells)
    h_node = np.zeros(len(x))
    np.maximum.at(h_node, cells.ravel(), np.repeat(h_cell, nv))
    node, cell = np.asarray(space.full_node), np.asarray(space.full_cell)
    h_full = np.where(node >= 0, h_node[np.maximum(node, 0)], h_cell[np.maximum(cell, 0)])
    group = np.asarray(space.full_to_reduced)
    nr = int(space.num_reduced)
    used = group >= 0
    count = np.bincount(group[used], minlength=nr)
    return np.bincount(group[used], weights=h_full[used], minlength=nr) / np.maximum(count, 1)


def group_points(space, x: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """BandSpace.group_x of a space on the band mesh (x, level sets phi
    (cracks, nodes)): per group the mean of the points where its crack cuts
    its vital edges (linear interpolation of phi along the edge: points on
    the crack); a group without a vital edge (a crack all of whose pieces
    are front cells) takes the mean of its member nodes. Measured against
    the centroids of the group functions (int phi_g x / int phi_g) on the
    bending closure: the same K within 0.04 % of the open front's."""
    nr = int(space.num_reduced)
    d = x.shape[1]
    node, crack = np.asarray(space.full_node), np.asarray(space.full_crack)
    group = np.asarray(space.full_to_reduced)
    nodal = (node >= 0) & (group >= 0)
    of = {(int(c), int(a)): int(g) for c, a, g in zip(crack[nodal], node[nodal], group[nodal])}
    total = np.zeros((nr, d))
    count = np.zeros(nr)
    for a, b in np.asarray(space.vital_edges):
        for c in range(phi.shape[0]):
            fa, fb = phi[c, a], phi[c, b]
            g = of.get((c, int(a)))
            if g is None or not fa * fb < 0.0:
                continue
            total[g] += x[a] + fa / (fa - fb) * (x[b] - x[a])
            count[g] += 1
    lone = count == 0
    if lone.any():
        members = np.flatnonzero(nodal)
        members = members[lone[group[members]]]
        np.add.at(total, group[members], x[node[members]])
        np.add.at(count, group[members], 1.0)
    return total / np.maximum(count, 1.0)[:, None]


def _facet_areas(x: np.ndarray, cell_nodes: np.ndarray, facets: np.ndarray, nfacets: np.ndarray) -> np.ndarray:
    """Physical areas of the lip facets (F, 9) (reference coordinates of their
    cells' canonical vertices)."""
    if not len(facets):
        return np.zeros(0)
    verts = x[np.repeat(cell_nodes, nfacets, axis=0)]                  # (F, 4, 3)
    ref = facets.reshape(-1, 3, 3)
    bary = np.concatenate([1.0 - ref.sum(axis=2, keepdims=True), ref], axis=2)   # (F, 3, 4)
    phys = np.einsum("fpa,fai->fpi", bary, verts)
    return 0.5 * np.linalg.norm(np.cross(phys[:, 1] - phys[:, 0], phys[:, 2] - phys[:, 0]), axis=1)


def prolongation(model, space, band: BandSpace, used: np.ndarray) -> sp.csr_matrix:
    """R (num_full of the process's space, band reduced): 1 where a local full
    multiplier belongs to a band group (module doc). used: the full
    multipliers the process integrates (on its owned cells' pieces), which
    must all be in the band."""
    node_input, original = _node_keys(model), _cell_keys(model)
    node, cell = np.asarray(space.full_node), np.asarray(space.full_cell)
    ids = np.where(node >= 0, node_input[np.maximum(node, 0)], original[np.maximum(cell, 0)])
    keys = _full_key(np.asarray(space.full_crack), node < 0, ids)
    band_keys = band.full_keys()
    order = np.argsort(band_keys)
    at = np.clip(np.searchsorted(band_keys[order], keys), 0, max(len(band_keys) - 1, 0))
    found = (band_keys[order][at] == keys) if len(band_keys) else np.zeros(len(keys), bool)
    missing = int(np.count_nonzero(used & ~found))  # (each process's own pieces are in the band: an invariant)
    agree(SolverError(f"{missing} contact multiplier(s) of this process's cells are missing from the gathered crack "
                      "band") if missing else None, model.V.mesh.comm)
    rows = np.flatnonzero(found)
    reduced = np.asarray(band.space.full_to_reduced)[order][at]
    return sp.csr_matrix((np.ones(len(rows)), (rows, reduced[rows])), shape=(len(keys), band.num_reduced))
