"""Which dofs each block of the iterative path's Schwarz sweep holds.

The sweep (solvers/schwarz.py) works on the stiffness in the phantom-node
basis (solvers/phantom.py) and, with contact, its multipliers:

* block 0, GAMG's: the stiffness's dofs; in 3D without the tip (front)
  dofs (TIP_DOFS_OUT_OF_GAMG, block0_dofs), which the band and the outer
  block hold;
* the crack band, solved exactly: every dof of the enriched nodes and of
  BAND_RINGS rings of their neighbours, every enriched dof and every
  multiplier (crack_band); with contact it is grown through the
  stiffness's graph (CONTACT_BAND_RINGS_*, grow_band);
* the outer torus (3D, a front enrichment radius of several front
  elements, no contact): the front-function dofs beyond
  INNER_BAND_RADIUS_H front elements leave the exact band for a block of
  their own (outer_torus, front_distance, OUTER_*).

The numbers are the kernels' local dofs (serial);
solvers/distributed_iterative.py takes the owned global rows instead.
"""
from __future__ import annotations

import math
import typing

import numpy as np
from petsc4py import PETSc

from ..scene.cell_size import mean_cell_size
if typing.TYPE_CHECKING:
    from ..model.model import XfemModel


#: With contact the band is wider: ceil(this x the number of multipliers)
#: rings of cells around the enriched nodes (15 rings for the bench crack's
#: 212 multipliers at 1e6 dofs), so that its exact solve carries the
#: multipliers' coupling to the body beyond the next cell. At 1e6 dofs
#: (bilateral) 1 ring takes 74 GMRES(30) iterations, 5 rings 50, 15 rings 42,
#: 40 rings 39: the Schur complement of the multipliers is nonlocal, and a
#: band of fixed physical width (rings ~ 1 / h ~ multipliers) keeps the
#: count from growing with the mesh.
CONTACT_BAND_RINGS_PER_MULTIPLIER = 0.07


MAX_BAND_RINGS = 60


#: On tetrahedra the multipliers cover a surface (their number grows like
#: 1 / h^2, not 1 / h), and rings around it are layers of the whole crack:
#: the per-multiplier rule made the band the whole refined region (the
#: closed penny at 5.8e4 dofs, 137 multipliers: 17 rings, a band of every
#: dof, 14 CG iterations; 1 ring: 15 203 band dofs, 25 iterations; 2 rings
#: 24; plain P1 22). So the 3D band keeps this many rings with contact.
CONTACT_BAND_RINGS_3D = 1


#: Whether GAMG's block (block 0 of the Schwarz sweep) leaves out the tip
#: dofs (by space dimension); every tip dof is in the crack band or the
#: outer block, which solve it. 3D, penny crack at 3.1e5 dofs (radius
#: 2 h_front, 3 % tip dofs): with the tip couplings GAMG's set-up took
#: 9.4 s and CG 31 iterations against plain P1's 6.8 s and 23; without them
#: 8.4 s and 25 (Heaviside-only: 8.0 s and 22): the tip rows, which have no
#: rigid modes, made the aggregates and the coarse operators denser. 2D
#: keeps them (Westergaard at 2e5 dofs: 23 iterations with, 62 without;
#: IterativeSolver). GAMG's operator is K' on the other dofs
#: (createSubMatrix; block0_dofs). Before, it was K' with the tip rows and
#: columns cut and their diagonal kept, a copy built in numpy over the
#: whole CSR (1.6 s at 5.3e5 dofs, radius 0.25 a), whose isolated tip rows
#: (9 % of them) every V-cycle's fine level carried; GAMG's coarse levels
#: were the same within 1 % either way (the isolated rows are aggregated
#: into nothing). Penny at 5.3e5 dofs, radius 0.25 a, one process each:
#: GAMG's set-up 18.1 s against plain P1's 15.5 s before, 17.1 against
#: 15.8 after; the solver's set-up 20.2 -> 17.9 s; CG 33 iterations either
#: way.
TIP_DOFS_OUT_OF_GAMG = {2: False, 3: True}


#: Rings of neighbours around the enriched nodes in the crack band, by
#: space dimension. In 3D the ring is a thick shell around the front's torus
#: of front-enriched nodes: penny crack at 8.9e4 dofs (radius 2 front
#: elements), band 49.6k dofs with the ring, 35.7k without: 23 CG
#: iterations either way, solve 20.9 -> 14.3 s, peak memory 848 -> 679 MB
#: (5.9e4 dofs: 22 -> 23 iterations, 589 -> 504 MB). 2D keeps its ring.
BAND_RINGS = {2: 1, 3: 0}


#: 3D: the front-enriched nodes farther than this many front element sizes
#: from the front (the outer torus of a large enrichment radius) leave the
#: exact (MUMPS) band, whose cost grows with the square of its
#: cross-section, for a block of their own solved inexactly (OUTER_PC);
#: 0: never (the whole band exact). The block starts OUTER_FROM_H front
#: elements from the front, so that it overlaps the exact band. Penny at
#: 5.3e5 dofs, radius 0.25 a (6 front elements), CG iterations: whole band
#: exact 24; split at 2 without overlap, outer block by ICC(0) 36, ICC(1)
#: 33, by MUMPS (exact) 33, 31 with its standard dofs: the split itself
#: costs iterations, not the incomplete factor; split at 3: 36. With the
#: overlap (from 1): ICC(0) 34, with the standard dofs 29 (ICC(1) 29);
#: split at 3 from 1: 31. Also measured and dropped: a coarse space of the
#: outer block (an aggregate per front function and component per 4 front
#: elements of front) 35 against 36; the outer tip dofs' couplings kept in
#: GAMG's operator 31 against 26 (1.1e5 dofs).
INNER_BAND_RADIUS_H = 2.0


#: Where the outer block starts (front element sizes from the front, at most
#: INNER_BAND_RADIUS_H: between the two both blocks hold the dofs).
OUTER_FROM_H = 1.0


#: Whether the outer block also holds its nodes' standard dofs (unless a
#: Heaviside pseudo-node shares the node): block Gauss-Seidel between GAMG
#: (standard dofs) and the outer block (front-function dofs) is slow where
#: the two spans nearly coincide; holding both, the block overlaps GAMG's
#: (5.3e5 dofs: 34 -> 29 iterations; band 58.5k -> 21.5k dofs).
OUTER_WITH_STANDARD = True


#: The band is split only when the front-function dofs beyond
#: INNER_BAND_RADIUS_H are at least this share of it (radius 2 h_front:
#: 12.5 % at 1e5 dofs, 10.6 % at 5e5, the nodes just beyond the mean front
#: edge, whose path stays as it was; radius 0.25 a: 29 % at 1e5).
OUTER_MIN_SHARE = 0.2


def tip_dofs(model: "XfemModel") -> np.ndarray:
    """Sorted dofs of the tip (front) pseudo-nodes."""
    lay = model.layout
    d = model.gdim
    k = np.flatnonzero(np.asarray(lay.kind) != 0)
    return (d * (lay.num_std_nodes + k)[:, None] + np.arange(d)).ravel().astype(np.int64)


def block0_dofs(n: int, lo: int, hi: int, tip: np.ndarray) -> np.ndarray:
    """The owned rows lo..hi of the stiffness (n dofs) that are not tip
    dofs (tip: the owned tip rows, global numbers): block 0 of the
    Schwarz sweep when GAMG leaves the tip dofs out (TIP_DOFS_OUT_OF_GAMG)."""
    keep = np.ones(max(0, min(hi, n) - lo), dtype=bool)
    keep[tip - lo] = False
    return (np.flatnonzero(keep) + lo).astype(np.int64)


def crack_band(model: "XfemModel", rings: int = 1) -> np.ndarray:
    """Sorted stiffness dofs of the crack band: both dofs of every enriched
    node and of its first `rings` rings of neighbours (nodes sharing a
    cell), and every enriched dof (phantom copies and tip dofs)."""
    lay = model.layout
    nstd = lay.num_std_nodes
    mark = np.zeros(nstd, dtype=bool)
    mark[np.asarray(lay.node)] = True
    for _ in range(rings):
        mark[model.cells[mark[model.cells].any(axis=1)]] = True
    ring = np.flatnonzero(mark)
    d = model.gdim
    std = (d * ring[:, None] + np.arange(d)).ravel()
    return np.concatenate([std, np.arange(d * nstd, model.num_dofs)]).astype(np.int64)


def outer_torus(model: "XfemModel", from_h: float, with_standard: bool = False,
                distance: np.ndarray | None = None) -> np.ndarray:
    """Sorted dofs of the outer torus: the front-enrichment dofs of the
    pseudo-nodes whose node lies farther than from_h front element sizes
    (the mean edge of the cells the front crosses) from its crack's front
    (|(phi, psi)|), and, with_standard, those nodes' standard dofs (unless a
    Heaviside pseudo-node shares the node). 3D only; empty if there is none
    or from_h is 0. distance: front_distance(model), if the caller has it."""
    lay = model.layout
    kind = np.asarray(lay.kind)
    tip = np.flatnonzero(kind != 0)
    if model.gdim != 3 or tip.size == 0 or not from_h:
        return np.zeros(0, dtype=np.int64)
    node = np.asarray(lay.node)
    far = (front_distance(model) if distance is None else distance) > from_h
    d = model.gdim
    pseudo = tip[far]
    dofs = [(d * (lay.num_std_nodes + pseudo)[:, None] + np.arange(d)).ravel()]
    if with_standard and pseudo.size:
        nodes = np.unique(node[pseudo])
        nodes = nodes[~np.isin(nodes, node[kind == 0])]
        dofs.append((d * nodes[:, None] + np.arange(d)).ravel())
    return np.sort(np.concatenate(dofs)).astype(np.int64)


def front_distance(model: "XfemModel") -> np.ndarray:
    """Per tip (front) pseudo-node, in the layout's order: its node's
    distance from its crack's front, |(phi, psi)|, in front element sizes
    (the mean edge of the cells the front crosses; 0 for a crack without
    front cells: never in the outer torus). 3D."""
    lay = model.layout
    tip = np.flatnonzero(np.asarray(lay.kind) != 0)
    node = np.asarray(lay.node)
    crack = np.asarray(lay.crack)
    dist = np.zeros(tip.size)
    for c, cm in enumerate(model.cracks):
        g = cm.geometry
        front_cells = np.flatnonzero(np.asarray(g.cell_class) == cm.CELL_CLASSES["front"])
        mine = crack[tip] == c
        if front_cells.size == 0 or not mine.any():
            continue
        h = mean_cell_size(model.x, model.cells[front_cells])
        nd = node[tip[mine]]
        dist[mine] = np.hypot(np.asarray(g.phi)[nd], np.asarray(g.psi)[nd]) / h
    return dist


def band_rings(gdim: int, m: int) -> int:
    """Rings of cells of the crack band with m multipliers, counted from
    the enriched nodes (1: crack_band's first ring): one without contact;
    ceil(CONTACT_BAND_RINGS_PER_MULTIPLIER m) (at most MAX_BAND_RINGS) in
    2D, CONTACT_BAND_RINGS_3D in 3D."""
    if m == 0:
        return 1
    if gdim == 3:
        return CONTACT_BAND_RINGS_3D
    return min(MAX_BAND_RINGS, max(1, math.ceil(CONTACT_BAND_RINGS_PER_MULTIPLIER * m)))


def outer_block(model: "XfemModel", band_size: int) -> tuple[np.ndarray, np.ndarray]:
    """(the outer block's dofs, the dofs the exact band leaves to it) for a
    crack band of band_size dofs; both empty unless the front-function dofs
    beyond INNER_BAND_RADIUS_H are at least OUTER_MIN_SHARE of the band
    (3D, front enrichment)."""
    none = np.zeros(0, dtype=np.int64)
    if model.gdim != 3 or not INNER_BAND_RADIUS_H or not np.any(np.asarray(model.layout.kind) != 0):
        return none, none
    dist = front_distance(model)  # (once: the three selections below share it)
    beyond = outer_torus(model, INNER_BAND_RADIUS_H, distance=dist)
    if beyond.size < OUTER_MIN_SHARE * band_size:
        return none, none
    return (outer_torus(model, OUTER_FROM_H, OUTER_WITH_STANDARD, dist),
            outer_torus(model, INNER_BAND_RADIUS_H, OUTER_WITH_STANDARD, dist))


def grow_band(K: PETSc.Mat, dofs: np.ndarray, rings: int) -> np.ndarray:
    """Sorted dofs reached from `dofs` in `rings` steps through the graph of
    K (one step = one ring of cells for P1 dofs); work proportional to the
    band, not to the mesh."""
    n = K.getSize()[0]
    mark = np.zeros(n, dtype=bool)
    mark[dofs] = True
    frontier = np.asarray(dofs)
    all_cols = PETSc.IS().createStride(n, 0, 1, comm=PETSc.COMM_SELF)
    for _ in range(rings):
        iset = PETSc.IS().createGeneral(frontier.astype(PETSc.IntType), comm=PETSc.COMM_SELF)
        sub = K.createSubMatrix(iset, all_cols)
        _, cols, _ = sub.getValuesCSR()
        sub.destroy()
        iset.destroy()
        reached = np.unique(cols)
        frontier = reached[~mark[reached]]
        if frontier.size == 0:
            break
        mark[frontier] = True
    all_cols.destroy()
    return np.flatnonzero(mark).astype(np.int64)
