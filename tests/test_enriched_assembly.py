"""Enriched kernels: oracles and locality (issue 2, acceptance 3)."""
import cracklip as cl
import numpy as np
import pytest
import scipy.sparse as sp
from cracklip import _cracklip
from cracklip.model.assembly import assemble_system, create_matrix, elasticity_form
from cracklip.solvers.checked import scipy_from_petsc

import dolfinx.fem
import dolfinx.fem.petsc


def _plain_scene(md, cracks=(), enrichment="none"):
    return cl.Scene(md, cl.Material(1.0, 0.3), cracks=list(cracks),
                    dirichlet=[cl.Dirichlet("left")], tractions=[cl.Traction("right", (1.0, 0.0))],
                    options=cl.Options(enrichment=enrichment))


def test_no_crack_equals_dolfinx_assembly(square_h01):
    """Standard block through our matrix path equals DOLFINx's own matrix."""
    model = cl.create_model(_plain_scene(square_h01))
    A = create_matrix(model)
    a = elasticity_form(model.V, 1.0, 0.3)
    dolfinx.fem.petsc.assemble_matrix(A, a)
    A.assemble()
    B = dolfinx.fem.petsc.assemble_matrix(a)
    B.assemble()
    diff = scipy_from_petsc(A) - scipy_from_petsc(B)
    assert abs(diff).max() <= 1e-12 * abs(scipy_from_petsc(B)).max()


def _clip_area(poly, yc, above):
    """Area of a polygon's part above (or below) y = yc (Sutherland-Hodgman)."""
    out = []
    n = len(poly)
    inside = (lambda p: p[1] >= yc) if above else (lambda p: p[1] <= yc)
    for i in range(n):
        p, q = poly[i], poly[(i + 1) % n]
        if inside(p):
            out.append(p)
        if inside(p) != inside(q):
            t = (yc - p[1]) / (q[1] - p[1])
            out.append(p + t * (q - p))
    if len(out) < 3:
        return 0.0
    out = np.array(out)
    return 0.5 * abs(np.dot(out[:, 0], np.roll(out[:, 1], -1)) - np.dot(out[:, 1], np.roll(out[:, 0], -1)))


def test_kernel_matches_numpy_reference():
    """Enriched blocks of a horizontal through crack against an independent NumPy
    integration (polygon clipping instead of the C++ sub-triangulation)."""
    md = cl.create_square(0.25)
    yc = 0.0731
    E, nu = 1.7, 0.28
    model = cl.create_model(_plain_scene(md, [cl.Crack([[-2, yc], [2, yc]])]))
    L = model.layout
    rows, cols, vals, ncells = _cracklip.assemble_enriched_stiffness_coo(
        model.x, model.cells, L, model.geometries, E, nu, cl.Options().quadrature_options())
    n = model.num_dofs
    K = sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()

    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    D = np.array([[lam + 2 * mu, lam, 0], [lam, lam + 2 * mu, 0], [0, 0, mu]])
    R = sp.lil_matrix((n, n))
    ns = L.num_std_nodes
    for ie, c in enumerate(L.cells):
        v = model.cells[c]
        xv = model.x[v]
        J = np.array([xv[1] - xv[0], xv[2] - xv[0]]).T
        G = np.linalg.solve(J.T, np.array([[-1, 1, 0], [-1, 0, 1]], dtype=float)).T  # (3, 2)
        funcs = [(2 * v[a], G[a], None) for a in range(3)]
        for k in L.cell_enr[L.cell_offsets[ie]:L.cell_offsets[ie + 1]]:
            a = int(np.flatnonzero(v == L.node[k])[0])
            funcs.append((2 * (ns + k), G[a], L.node_side[k]))
        for side, above in ((1.0, True), (-1.0, False)):
            area = _clip_area(list(xv), yc, above)
            if area == 0.0:
                continue
            Bm = np.zeros((3, 2 * len(funcs)))
            dofs = []
            for f, (d0, g, Hi) in enumerate(funcs):
                w = 1.0 if Hi is None else side - Hi
                Bm[:, 2 * f] = [w * g[0], 0, w * g[1]]
                Bm[:, 2 * f + 1] = [0, w * g[1], w * g[0]]
                dofs += [d0, d0 + 1]
            Ke = area * Bm.T @ D @ Bm
            Ke[:6, :6] = 0.0
            for i, di in enumerate(dofs):
                for j, dj in enumerate(dofs):
                    R[di, dj] += Ke[i, j]
    assert ncells == L.cells.size
    assert abs(K - R.tocsr()).max() <= 1e-12 * abs(K).max()


@pytest.mark.parametrize("h", [0.1, 0.05, 0.025])
def test_enriched_cells_scale_with_crack_length(h):
    """Kernel calls ~ crack length / h, not ~ number of cells."""
    md = cl.create_square(h)
    crack_length = 1.2
    model = cl.create_model(_plain_scene(md, [cl.Crack([[-0.6, 0.011], [0.6, 0.011]])]))
    A, b, _ = assemble_system(model)
    count = model.num_enriched_cells_integrated
    # Every integrated cell carries an enriched node; cells = layout.cells.
    assert count == model.layout.cells.size
    # A band of ~3 cells across the crack: count * h / length is O(1) and
    # far below the share of all cells.
    per_length = count * h / crack_length
    assert 2.0 <= per_length <= 8.0, per_length
    assert count <= 40 * crack_length / h
    assert count < 0.25 * model.cells.shape[0] * (h / 0.1)
    # Tip enrichment (radius 0) adds a fixed number of cells per tip, not ~1/h.
    tip_model = cl.create_model(_plain_scene(md, [cl.Crack([[-0.6, 0.011], [0.6, 0.011]])], "vector"))
    extra = tip_model.layout.cells.size - count
    assert 0 < extra <= 2 * 40, extra
