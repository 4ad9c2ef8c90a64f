"""The element size of simplices (cracklip.scene.cell_size) against closed
forms: the mean edge of a triangle and a tetrahedron, per cell and over
many cells in chunks."""
import math

import numpy as np

from cracklip.scene import cell_size
from cracklip.scene.cell_size import cell_sizes, edge_pairs, mean_cell_size


def test_edge_pairs_are_every_vertex_pair_once():
    assert edge_pairs(3) == ([0, 0, 1], [1, 2, 2])
    a, b = edge_pairs(4)
    assert sorted(zip(a, b)) == [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]


def test_triangle_and_tetrahedron_sizes_are_their_mean_edges():
    # The right triangle with legs 3 and 4: edges 3, 4, 5, mean 4 (in 2D and on z = 0 in 3D).
    tri = np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 4.0]])
    assert np.allclose(cell_sizes(tri, np.array([[0, 1, 2]])), [4.0], rtol=0, atol=1e-15)
    assert np.allclose(cell_sizes(np.column_stack([tri, np.zeros(3)]), np.array([[2, 0, 1]])), [4.0])
    # The unit right-corner tetrahedron: three edges 1, three sqrt(2): mean (3 + 3 sqrt 2) / 6.
    tet = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    assert math.isclose(cell_sizes(tet, np.array([[0, 1, 2, 3]]))[0], (3 + 3 * math.sqrt(2)) / 6, rel_tol=1e-15)
    # A regular tetrahedron of edge 2 (alternate corners of a cube of side sqrt 2).
    s = math.sqrt(2.0)
    reg = np.array([[0.0, 0, 0], [s, s, 0], [s, 0, s], [0, s, s]])
    assert math.isclose(cell_sizes(reg, np.array([[3, 1, 0, 2]]))[0], 2.0, rel_tol=1e-15)
    assert cell_sizes(tet, np.zeros((0, 4), dtype=int)).shape == (0,)


def test_mean_over_chunks_is_the_mean_of_every_cell(monkeypatch):
    rng = np.random.default_rng(3)
    x = rng.random((50, 3))
    cells = np.array([rng.choice(50, 4, replace=False) for _ in range(101)])
    whole = float(cell_sizes(x, cells).mean())
    monkeypatch.setattr(cell_size, "CHUNK", 7)   # 14 chunks of unequal sizes
    assert math.isclose(mean_cell_size(x, cells), whole, rel_tol=1e-14)
    assert mean_cell_size(x, cells[:0]) == 0.0
