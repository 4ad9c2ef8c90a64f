"""The element size of a simplex mesh: the mean length of a cell's edges
(a triangle's 3, a tetrahedron's 6), per cell or over many cells. One
definition for every caller in 2D and 3D (refinement, model checks, SIF
domains, the contact groups, the scene's point checks, the solvers' front
size)."""
from __future__ import annotations

import itertools

import numpy as np

#: Cells handled at a time by mean_cell_size (bounds cell_sizes' (c, k, d)
#: array of the cells' nodes on a large 3D mesh: 2e5 tetrahedra, 19 MB).
CHUNK = 200_000


def edge_pairs(vertices: int) -> tuple[list[int], list[int]]:
    """The (first, second) vertex of every edge of a simplex with this many
    vertices: (0, 1), (0, 2), (1, 2) for a triangle, six pairs for a
    tetrahedron."""
    pairs = list(itertools.combinations(range(vertices), 2))
    return [a for a, _ in pairs], [b for _, b in pairs]


def cell_sizes(x: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Mean edge length of every cell (c,): x (n, d) node coordinates (d
    may exceed the cells' dimension), cells (c, k) node indices of simplices."""
    cells = np.asarray(cells)
    if len(cells) == 0:
        return np.zeros(0)
    xv = np.asarray(x)[cells]                      # (c, k, d): only the cells' own nodes
    total = np.zeros(len(cells))
    first, second = edge_pairs(cells.shape[1])
    for a, b in zip(first, second):                # (an edge at a time: no (c, edges, d) array)
        e = xv[:, b] - xv[:, a]
        total += np.sqrt(np.einsum("ij,ij->i", e, e))
    return total / len(first)


def mean_cell_size(x: np.ndarray, cells: np.ndarray) -> float:
    """Mean edge length over all the cells' edges (0 for no cells), a chunk
    of CHUNK cells at a time."""
    cells = np.asarray(cells)
    if len(cells) == 0:
        return 0.0
    total = sum(float(cell_sizes(x, c).sum()) for c in np.array_split(cells, max(1, len(cells) // CHUNK)))
    return total / len(cells)


__all__ = ["CHUNK", "cell_sizes", "edge_pairs", "mean_cell_size"]
