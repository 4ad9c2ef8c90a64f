"""3D crack geometry on DOLFINx tetrahedral meshes (the C++ layer through its
bindings): an elliptical crack in a box, class counts, lip area against
pi a b, front points on the ellipse, frames, lip and cell quadrature, and bad
input as typed errors."""
import numpy as np
import pytest

pytest.importorskip("dolfinx")

from mpi4py import MPI  # noqa: E402

import dolfinx.mesh  # noqa: E402

from cracklip import _cracklip  # noqa: E402

CENTER = np.array([0.503, 0.497, 0.512])
NORMAL = np.array([0.12, -0.08, 1.0])
AXIS = np.array([1.0, 0.4, 0.0])
A, B = 0.32, 0.19


def box_mesh(n):
    """Unit cube as DOLFINx tetrahedra: node coordinates (n, 3), cells (m, 4)."""
    msh = dolfinx.mesh.create_box(MPI.COMM_WORLD, [np.zeros(3), np.ones(3)], [n, n, n],
                                  dolfinx.mesh.CellType.tetrahedron)
    x = np.ascontiguousarray(msh.geometry.x, dtype=np.float64)
    cells = msh.geometry.dofmap.array.reshape(-1, 4).astype(np.int32)
    return x, cells


def ellipse():
    return _cracklip.create_ellipse_crack(CENTER, NORMAL, AXIS, A, B)


def ellipse_frame():
    """Unit normal n and in-plane axes (ea along AXIS, eb = n x ea)."""
    n = NORMAL / np.linalg.norm(NORMAL)
    ea = AXIS - AXIS @ n * n
    ea /= np.linalg.norm(ea)
    return n, ea, np.cross(n, ea)


def rate(h, e):
    return np.polyfit(np.log(h), np.log(e), 1)[0]


@pytest.fixture(scope="module")
def geometries():
    out = {}
    for n in (8, 16, 32):
        x, cells = box_mesh(n)
        out[n] = (x, cells, _cracklip.compute_crack_geometry_3d(x, cells, ellipse(), 1e-6))
    return out


def test_class_counts_scale_with_the_crack(geometries):
    """Cut cells cover the crack's area (~ 1/h^2), front cells its front
    (~ 1/h), and the crack cells listed are exactly the cut, face and front
    ones; a generic ellipse leaves no face cell."""
    counts = {n: g.class_counts for n, (_, _, g) in geometries.items()}
    for n, (x, cells, g) in geometries.items():
        c = counts[n]
        assert sum(c.values()) == len(cells)
        assert c["face"] == 0 and c["cut"] > 0 and c["front"] > 0 and c["extension"] > 0
        cc = g.crack_cells
        assert len(cc["cell"]) == c["cut"] + c["face"] + c["front"]
        assert np.all(np.diff(cc["cell"]) > 0)
        idx = g.crack_cell_index
        assert np.all(idx[cc["cell"]] == np.arange(len(cc["cell"])))
        assert np.count_nonzero(idx >= 0) == len(cc["cell"])
    assert 3.0 < counts[16]["cut"] / counts[8]["cut"] < 5.0
    assert 3.2 < counts[32]["cut"] / counts[16]["cut"] < 4.8
    assert 1.5 < counts[16]["front"] / counts[8]["front"] < 2.6
    assert 1.6 < counts[32]["front"] / counts[16]["front"] < 2.4


def test_sub_tetrahedra_fill_each_crack_cell(geometries):
    """Sub-tetrahedron volumes (reference coordinates, positive) plus dropped
    slivers sum to the reference cell's 1/6, in every crack cell."""
    x, cells, g = geometries[16]
    cc = g.crack_cells
    s = cc["sub"]
    vol = np.einsum("ij,ij->i", s[:, 1] - s[:, 0], np.cross(s[:, 2] - s[:, 0], s[:, 3] - s[:, 0])) / 6
    assert np.all(vol > 0)
    per_cell = np.add.reduceat(vol, cc["sub_offsets"][:-1]) + cc["dropped_volume"]
    assert np.allclose(per_cell, 1 / 6, rtol=0, atol=1e-13 / 6)


def test_lip_area_converges_to_pi_a_b(geometries):
    """The lip facets' area tends to pi a b at second order."""
    h, err = [], []
    for n, (_, _, g) in geometries.items():
        area = g.crack_cells["facet_area"].sum()
        h.append(1 / n)
        err.append(abs(area - np.pi * A * B) / (np.pi * A * B))
    assert rate(h, err) > 1.8, err
    assert err[-1] < 3e-3


def test_front_is_a_closed_loop_on_the_ellipse(geometries):
    """One closed front piece whose points lie on the ellipse to O(h^2)
    (their distance sqrt(phi^2 + psi^2) to the exact ellipse), ordered with
    increasing arc length, none on the part's boundary, total length
    tending to the ellipse's perimeter."""
    s = ellipse()
    h, dist = [], []
    # Perimeter of the ellipse by a fine trapezoid sum (spectrally accurate).
    t = np.linspace(0, 2 * np.pi, 20001)[:-1]
    perimeter = np.sum(np.hypot(A * np.sin(t), B * np.cos(t))) * (2 * np.pi / len(t))
    for n, (_, _, g) in geometries.items():
        f = g.front
        assert len(f["closed"]) == 1 and f["closed"][0] == 1
        assert not f["on_boundary"].any()
        assert np.all(np.diff(f["s"]) > 0)
        phi, psi = s.level_sets(f["x"])
        h.append(1 / n)
        dist.append(np.max(np.hypot(phi, psi)))
        seg = f["segments"]
        length = np.linalg.norm(f["x"][seg[:, 1]] - f["x"][seg[:, 0]], axis=1).sum()
        assert abs(length - perimeter) / perimeter < 4 / n**2
    assert rate(h, dist) > 1.7, dist


def test_front_frames(geometries):
    """Orthonormal right-handed frames; e2 the crack normal, e1 in the crack
    plane along the ellipse's outward normal at the nearest ellipse point
    (exact: the frames come from the surface), e3 along the front."""
    n, ea, eb = ellipse_frame()
    _, _, g = geometries[16]
    f = g.front
    E = f["frame"]
    assert np.allclose(np.einsum("nij,nkj->nik", E, E), np.eye(3), atol=1e-14)
    assert np.allclose(np.cross(E[:, 0], E[:, 1]), E[:, 2], atol=1e-14)
    assert np.allclose(E[:, 1], n, atol=1e-14)
    # The ellipse's outward normal at the parameter of the point's projection
    # (closest point by a dense search: independent of the C++ bisection).
    d = f["x"] - CENTER
    u, v = d @ ea, d @ eb
    t = np.linspace(0, 2 * np.pi, 200001)
    for k in range(len(u)):
        j = np.argmin((u[k] - A * np.cos(t)) ** 2 + (v[k] - B * np.sin(t)) ** 2)
        nu = np.array([np.cos(t[j]) / A, np.sin(t[j]) / B])
        nu /= np.linalg.norm(nu)
        e1 = nu[0] * ea + nu[1] * eb
        assert np.linalg.norm(E[k, 0] - e1) < 1e-4
    # e3 follows the polyline.
    seg = f["segments"]
    tangent = f["x"][seg[:, 1]] - f["x"][seg[:, 0]]
    assert np.all(np.einsum("ij,ij->i", tangent, E[seg[:, 0], 2]) > 0)


def test_front_projection(geometries):
    """The nearest front point of points near the front: on the polyline,
    no farther than the nearest front point, frame interpolated and
    orthonormal."""
    _, _, g = geometries[16]
    f = g.front
    rng = np.random.default_rng(0)
    p = f["x"][rng.integers(0, len(f["s"]), 50)] + 0.05 * rng.standard_normal((50, 3))
    pr = _cracklip.compute_front_projection_3d(g, p)
    d_points = np.min(np.linalg.norm(p[:, None, :] - f["x"][None, :, :], axis=2), axis=1)
    assert np.all(pr["distance"] <= d_points + 1e-15)
    assert np.allclose(np.linalg.norm(p - pr["x"], axis=1), pr["distance"], atol=1e-14)
    E = pr["frame"]
    assert np.allclose(np.einsum("nij,nkj->nik", E, E), np.eye(3), atol=1e-13)


def test_lip_points_and_cell_quadrature(geometries):
    """Lip quadrature weights sum to the lip area; each cell's quadrature
    weights sum to its volume (front cells included), with the points'
    sides those of the sub-tetrahedra."""
    x, cells, g = geometries[8]
    lp = _cracklip.compute_lip_points(x, cells, g, 4)
    assert np.isclose(lp["weight"].sum(), g.crack_cells["facet_area"].sum(), rtol=1e-13)
    assert np.allclose(lp["normal"] @ (NORMAL / np.linalg.norm(NORMAL)), 1.0, atol=1e-13)
    cc = g.crack_cells
    for c in list(cc["cell"][cc["cls"] == 3][:10]) + [0]:
        q = _cracklip.compute_cell_quadrature_3d(x, cells, g, int(c))
        X = x[cells[c]]
        vol = abs(np.linalg.det(X[1:] - X[0])) / 6
        assert np.isclose(q["weight"].sum(), vol, rtol=1e-12)
        assert set(np.unique(q["side"])) <= ({-1, 1} if g.crack_cell_index[c] >= 0 else {0})


def test_rules_exposed():
    r = _cracklip.tetrahedron_rule(4)
    assert np.isclose(r["weights"].sum(), 1 / 6, rtol=1e-15)
    xv = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    e = _cracklip.tetrahedron_edge_collapsed_rule(xv, 6, 8, 3)
    assert e["points"].shape == (6 * 8 * 3, 3)
    # int 1/r over the unit tetrahedron, r = sqrt(y^2 + z^2): ln(1 + sqrt 2) / sqrt 2.
    r_ = np.hypot(e["points"][:, 1], e["points"][:, 2])
    assert np.isclose(np.sum(e["weights"] / r_), np.log(1 + np.sqrt(2)) / np.sqrt(2), rtol=1e-13)


def test_bad_input_is_a_typed_error():
    x, cells = box_mesh(3)
    far = _cracklip.create_ellipse_crack([5.0, 5.0, 0.5], [0, 0, 1], [1, 0, 0], 0.3, 0.2)
    with pytest.raises(ValueError, match=r"bounding box .* outside the part"):
        _cracklip.compute_crack_geometry_3d(x, cells, far, 1e-6)
    with pytest.raises(ValueError, match="normal is zero"):
        _cracklip.create_ellipse_crack([0, 0, 0], [0, 0, 0], [1, 0, 0], 1, 1)
    with pytest.raises(ValueError, match="semi-axes must be"):
        _cracklip.create_ellipse_crack([0, 0, 0], [0, 0, 1], [1, 0, 0], 1, 0)
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [-1, -1, 0.0]])
    with pytest.raises(ValueError, match="non-manifold"):
        _cracklip.create_triangulated_crack(v, np.array([[0, 1, 2], [1, 0, 3], [0, 1, 5]], dtype=np.int32))
    with pytest.raises(ValueError, match="inconsistent orientation.*reverse the vertex order of triangle 1"):
        _cracklip.create_triangulated_crack(v, np.array([[0, 1, 2], [4, 1, 2]], dtype=np.int32))
    with pytest.raises(ValueError, match=r"shape \(n, 4\)"):
        _cracklip.compute_crack_geometry_3d(x, cells[:, :3].copy(), far, 1e-6)


def test_triangulated_planar_surface_matches_the_polygon():
    """A planar square crack given as triangles and as a polygon: the same
    level sets, classes and lip area on a DOLFINx mesh."""
    x, cells = box_mesh(10)
    sq = np.array([[0.23, 0.21, 0.47], [0.81, 0.21, 0.47], [0.81, 0.77, 0.47], [0.23, 0.77, 0.47]])
    poly = _cracklip.create_polygon_crack(sq)
    tri = _cracklip.create_triangulated_crack(sq, np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int32))
    gp = _cracklip.compute_crack_geometry_3d(x, cells, poly, 1e-6)
    gt = _cracklip.compute_crack_geometry_3d(x, cells, tri, 1e-6)
    assert np.allclose(gp.phi, gt.phi, atol=1e-15) and np.allclose(gp.psi, gt.psi, atol=1e-14)
    assert np.array_equal(gp.cell_class, gt.cell_class)
    # psi is linear along the sides (exact there) but not around the corners,
    # which the P1 front cuts: the area falls short by O(h^2) (h = 0.1).
    deficit = 0.58 * 0.56 - gp.crack_cells["facet_area"].sum()
    assert 0 < deficit < 0.1**2
    assert gp.front["closed"].tolist() == [1]
