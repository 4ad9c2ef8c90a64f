"""The C++ module's bindings written once for both dimensions: the mesh arrays
decide (x of shape (n, 2) or (n, 3)), each kernel has one name, and a crack
list, a crack or options of the other dimension is refused with a message
that says what was expected."""
from __future__ import annotations

import itertools

import numpy as np
import pytest

from cracklip import _cracklip


def _triangles(n: int = 4):
    g = np.linspace(0.0, 1.0, n + 1)
    x = np.array([[a, b] for b in g for a in g])
    cells = []
    for j, i in itertools.product(range(n), range(n)):
        a = j * (n + 1) + i
        cells += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return x, np.array(cells, dtype=np.int32)


def _tetrahedra(n: int = 3):
    g = np.linspace(0.0, 1.0, n + 1)
    x = np.array([[a, b, c] for c in g for b in g for a in g])

    def node(i, j, k):
        return (k * (n + 1) + j) * (n + 1) + i

    cells = []
    for k, j, i in itertools.product(range(n), range(n), range(n)):
        for p in itertools.permutations(range(3)):
            c = [i, j, k]
            tet = [node(*c)]
            for axis in p:
                c[axis] += 1
                tet.append(node(*c))
            cells.append(tet)
    return x, np.array(cells, dtype=np.int32)


@pytest.fixture(scope="module")
def model_2d():
    x, cells = _triangles()
    g = _cracklip.compute_crack_geometry(x, cells, np.array([[-1.0, 0.51], [0.53, 0.51]]), (False, True), 1e-8)
    layout = _cracklip.create_enrichment_layout(x, cells, [g], tip="vector", radius=0.3)
    return x, cells, g, layout


@pytest.fixture(scope="module")
def model_3d():
    x, cells = _tetrahedra()
    g = _cracklip.compute_crack_geometry_3d(x, cells, x[:, 2] - 0.51, x[:, 0] - 0.53)
    layout = _cracklip.create_enrichment_layout(x, cells, [g], tip="vector", radius=0.3)
    return x, cells, g, layout


def test_one_layout_class_and_one_name_per_kernel(model_2d, model_3d):
    """One EnrichmentLayout for both dimensions, and no second (3D) name of
    the kernels written once."""
    assert type(model_2d[3]) is type(model_3d[3]) is _cracklip.EnrichmentLayout
    assert model_2d[3].dim == 2 and model_3d[3].dim == 3
    for old in ("EnrichmentLayout3D", "create_enrichment_layout_3d", "create_sparsity_3d",
                "assemble_enriched_stiffness_3d_petsc", "assemble_enriched_stiffness_3d_coo",
                "compute_facet_basis_3d", "assemble_lip_load_3d", "assemble_cell_load_3d",
                "evaluate_displacement_3d", "compute_crack_points", "compute_lip_points_3d",
                "compute_enriched_cell_quadrature_3d"):
        assert not hasattr(_cracklip, old), old
    assert not hasattr(model_3d[3], "piece")


@pytest.mark.parametrize("dim", [2, 3])
def test_lip_points_in_both_dimensions(dim, model_2d, model_3d):
    """compute_lip_points on a crack's segments (2D) or lip facets (3D): the
    weights sum to the crack's length (area) inside the part, 0.53 (the
    crack y = 0.51 (z = 0.51) up to x = 0.53), the points lie on it, the
    normals point to its + side."""
    x, cells, g, _ = model_2d if dim == 2 else model_3d
    lp = _cracklip.compute_lip_points(x, cells, g, 4)
    assert lp["ref"].shape == lp["x"].shape == lp["normal"].shape == (len(lp["weight"]), dim)
    assert ("front_vertices" in lp) == (dim == 3)
    np.testing.assert_allclose(lp["weight"].sum(), 0.53, rtol=1e-12)
    np.testing.assert_allclose(lp["x"][:, dim - 1], 0.51, rtol=1e-12)
    assert lp["x"][:, 0].max() <= 0.53 + 1e-12
    np.testing.assert_allclose(lp["normal"], np.broadcast_to(np.eye(dim)[dim - 1], lp["normal"].shape), atol=1e-13)


def test_lip_points_refuse_what_their_dimension_does_not_have(model_2d, model_3d):
    x2, cells2, g2, _ = model_2d
    x3, cells3, g3, _ = model_3d
    with pytest.raises(ValueError, match=r"near_factor and signed_point_rule choose the rules of lip facets near a 3D"):
        _cracklip.compute_lip_points(x2, cells2, g2, 4, near_factor=1.0)
    with pytest.raises(ValueError, match=r"geometry must be a CrackGeometry3D \(compute_crack_geometry_3d\)"):
        _cracklip.compute_lip_points(x3, cells3, g2, 4)


@pytest.mark.parametrize("dim", [2, 3])
def test_stiffness_is_symmetric_and_its_points_cover_the_enriched_cells(dim, model_2d, model_3d):
    x, cells, g, layout = model_2d if dim == 2 else model_3d
    opts = _cracklip.QuadratureOptions() if dim == 2 else _cracklip.QuadratureOptions3D()
    rows, cols, vals, ncells = _cracklip.assemble_enriched_stiffness_coo(x, cells, layout, [g], 1.0, 0.3, opts)
    assert ncells == len(layout.cells)
    n = dim * layout.num_nodes_total
    K = np.zeros((n, n))
    np.add.at(K, (rows, cols), vals)
    assert np.abs(K - K.T).max() <= 1e-13 * np.abs(K).max()
    q = _cracklip.compute_enriched_cell_quadrature(x, cells, layout, [g], np.asarray(layout.cells, dtype=np.int32), opts)
    assert q["ref"].shape == (len(q["weight"]), dim)
    assert set(np.unique(q["cell"])) == set(np.asarray(layout.cells))
    # The weights of a cell sum to its measure (2D: area; 3D: volume).
    xc = x[cells[np.asarray(layout.cells)]]
    measure = np.abs(np.linalg.det(xc[:, 1:] - xc[:, :1])) / (2.0 if dim == 2 else 6.0)
    sums = np.bincount(q["cell"], weights=q["weight"], minlength=len(cells))[np.asarray(layout.cells)]
    np.testing.assert_allclose(sums, measure, rtol=1e-10)


@pytest.mark.parametrize("dim", [2, 3])
def test_initial_stress_load_in_both_dimensions(dim, model_2d, model_3d):
    """The cell load of a constant initial stress s is minus the stiffness
    times the linear field of that stress, in 2D (s: xx, yy, xy) and now in
    3D (s: xx, yy, zz, yz, xz, xy)."""
    x, cells, g, layout = model_2d if dim == 2 else model_3d
    opts = _cracklip.QuadratureOptions() if dim == 2 else _cracklip.QuadratureOptions3D()
    E, nu = 1.0, 0.3
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    G = np.arange(1, dim * dim + 1, dtype=float).reshape(dim, dim) / 10.0
    eps = 0.5 * (G + G.T)
    sigma = lam * np.trace(eps) * np.eye(dim) + 2 * mu * eps
    pairs = [(0, 0), (1, 1), (0, 1)] if dim == 2 else [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
    q = _cracklip.compute_enriched_cell_quadrature(x, cells, layout, [g], np.asarray(layout.cells, dtype=np.int32), opts)
    npts = len(q["weight"])
    s = np.tile([sigma[i, j] for i, j in pairs], (npts, 1))
    b = _cracklip.assemble_cell_load(x, cells, layout, [g], q["cell"], q["ref"], q["side"], q["weight"],
                                     np.zeros((npts, dim)), s)
    rows, cols, vals, _ = _cracklip.assemble_enriched_stiffness_coo(x, cells, layout, [g], E, nu, opts)
    u = np.zeros(dim * layout.num_nodes_total)
    u[: dim * layout.num_std_nodes] = (x @ G.T).ravel()
    Ku = np.bincount(rows, weights=vals * u[cols], minlength=len(u))
    enriched = slice(dim * layout.num_std_nodes, None)
    assert np.abs(Ku[enriched]).max() > 1e-3
    np.testing.assert_allclose(b[enriched], -Ku[enriched], atol=1e-12 * np.abs(Ku).max())


def test_the_other_dimension_is_refused_with_a_message(model_2d, model_3d):
    x2, cells2, g2, layout2 = model_2d
    x3, cells3, g3, layout3 = model_3d
    with pytest.raises(ValueError, match=r"cracks must be a list of CrackGeometry3D"):
        _cracklip.create_enrichment_layout(x3, cells3, [g2])
    with pytest.raises(ValueError, match=r"options must be QuadratureOptions3D on a tetrahedral mesh"):
        _cracklip.assemble_enriched_stiffness_coo(x3, cells3, layout3, [g3], 1.0, 0.3, _cracklip.QuadratureOptions())
    with pytest.raises(ValueError, match=r"the enrichment layout belongs to a 2D mesh, the arrays to a 3D one"):
        _cracklip.assemble_enriched_stiffness_coo(x3, cells3, layout2, [g3], 1.0, 0.3, _cracklip.QuadratureOptions3D())
    with pytest.raises(ValueError, match=r"cells \(node indices per tetrahedron\) must be an array of shape \(n, 4\)"):
        _cracklip.evaluate_displacement(x3, cells2, layout3, [g3], np.zeros(3), np.zeros(0, dtype=np.int32),
                                        np.zeros((0, 3)), np.zeros(0, dtype=np.int8))


@pytest.mark.parametrize("dim", [2, 3])
def test_field_points_of_a_linear_field(dim, model_2d, model_3d):
    """compute_field_points on every cell (plain and enriched, 2D or 3D): the
    weights sum to the part's measure and grad u is the field's gradient."""
    x, cells, g, layout = model_2d if dim == 2 else model_3d
    opts = _cracklip.QuadratureOptions() if dim == 2 else _cracklip.QuadratureOptions3D()
    G = np.arange(1, dim * dim + 1, dtype=float).reshape(dim, dim) / 7.0
    u = np.zeros(dim * layout.num_nodes_total)
    u[: dim * layout.num_std_nodes] = (x @ G.T).ravel()
    f = _cracklip.compute_field_points(x, cells, layout, [g], u, np.zeros(0, dtype=np.int32), opts)
    assert f["grad_u"].shape == (len(f["weight"]), dim, dim)
    assert set(np.unique(f["cell"])) == set(range(len(cells)))
    np.testing.assert_allclose(f["weight"].sum(), 1.0, rtol=1e-12)
    np.testing.assert_allclose(f["grad_u"], np.broadcast_to(G, f["grad_u"].shape), atol=1e-12)
