"""Degenerate crack geometry: finite, correct answers (issue 2, acceptance 4).

Rule (see Options.snap_tol and cpp/geometry/crack_geometry_2d.h): a node closer to the
crack than snap_tol x its shortest edge is put on the crack (phi = 0); a
crack through a node splits the cells there through the node, a crack along
mesh edges makes "edge" cells whose Heaviside side is the cell's side, and a
tip on a node or an edge makes no tip cell (the crack ends at that node).
"""
import cracklip as cl
import numpy as np
from conftest import side_tractions, uniform_strain, uniform_stress_scene
from test_patch import check_through_crack, through_crack_scene


def _interior_node_near(md, p):
    x = md.mesh.geometry.x[:, :2]
    inner = np.flatnonzero(np.all(np.abs(x) < 0.9, axis=1))
    return x[inner[np.argmin(np.linalg.norm(x[inner] - p, axis=1))]]


def _inclined_through_crack(md, p, angle, offset, material, s=0.4):
    """Through crack along the line through p at `angle`, shifted by `offset`
    along its normal. Stress s t(x)t along the crack; each piece is held at two
    nodes by the exact field eps.x plus its own translation, so the exact
    opening is the (constant) difference of the translations."""
    t = np.array([np.cos(angle), np.sin(angle)])
    n = np.array([-t[1], t[0]])
    p = np.asarray(p) + offset * n
    sigma = s * np.outer(t, t)
    eps = uniform_strain(material, sigma)
    shift = {1: np.array([0.002, -0.001]), -1: np.array([-0.003, 0.004])}
    x = md.mesh.geometry.x[:, :2]
    dist = (x - p) @ n
    bcs = []
    for side in (1, -1):
        nodes = np.flatnonzero(dist * side > 0.2)
        a = nodes[np.argmin(x[nodes] @ t)]
        b = nodes[np.argmax(x[nodes] @ t)]
        f = (lambda sd: lambda q: q @ eps.T + shift[sd])(side)
        bcs += [cl.Dirichlet(tuple(x[a]), None, f),
                cl.Dirichlet(tuple(x[b]), 1, (lambda g: lambda q: g(q)[:, 1])(f))]
    crack = cl.Crack([p - 3.0 * t, p + 3.0 * t])
    scene = cl.Scene(md, material, cracks=[crack], dirichlet=bcs,
                     tractions=[cl.Traction(k, v) for k, v in side_tractions(sigma).items()])

    def exact(q, side):
        return q @ eps.T + shift[side]
    return scene, exact, p, t, dist


def _check_inclined(sol, exact, p, t, tol):
    scale = 0.4
    s = np.linspace(-0.9, 0.9, 40)[:, None]
    on = p + s * t
    on = on[np.all(np.abs(on) < 0.99, axis=1)]
    for side in (1, -1):
        assert np.abs(sol.displacement(on, side=side) - exact(on, side)).max() <= tol * scale
    op = sol.crack_opening(0)
    jump_exact = exact(op["x"], 1) - exact(op["x"], -1)
    assert np.abs(op["jump"] - jump_exact).max() <= tol * np.abs(jump_exact).max()


def test_crack_through_a_vertex():
    md = cl.create_square(0.1)
    p = _interior_node_near(md, [0.05, -0.02])
    scene, exact, p, t, dist = _inclined_through_crack(md, p, np.radians(23.0), 0.0,
                                                       cl.Material(1.0, 0.3))
    # Only the chosen node lies on the line; no other node within 1e-4 h.
    assert np.count_nonzero(np.abs(dist) < 1e-5) == 1
    sol = cl.solve(scene)
    g = sol.model.geometries[0]
    assert np.count_nonzero(g.phi == 0.0) == 1  # (snapped from round-off if need be)
    _check_inclined(sol, exact, p, t, 1e-10)


def test_cut_leaving_1e9_of_a_cell():
    """The line passes 1e-9 h from a node: the node is snapped onto it
    (moving the crack by 1e-10), so no sub-cell is thinner than snap_tol h."""
    md = cl.create_square(0.1)
    p = _interior_node_near(md, [0.05, -0.02])
    scene, exact, p, t, dist = _inclined_through_crack(md, p, np.radians(23.0), 1e-10,
                                                       cl.Material(1.0, 0.3))
    sol = cl.solve(scene)
    assert sol.model.geometries[0].num_snapped == 1
    assert np.all(np.isfinite(sol.u))
    _check_inclined(sol, exact, p, t, 1e-8)
    # Without snapping the answer stays finite (the tiny sub-cell is kept).
    scene.options = cl.Options(snap_tol=0.0)
    sol0 = cl.solve(scene)
    assert np.all(np.isfinite(sol0.u))


def test_crack_along_mesh_edges():
    yc = 0.1
    md = cl.create_square(0.1, embed_lines=[((-1.0, yc), (1.0, yc))])
    scene, exact = through_crack_scene(md, yc, cl.Material(1.0, 0.3), 0.4)
    sol = cl.solve(scene)
    g = sol.model.geometries[0]
    assert np.all(g.crack_cells["cls"] == 2)  # all crack cells are edge cells
    check_through_crack(sol, exact, yc, 1e-10)


def test_tips_on_vertices_and_crack_along_edges():
    """Interior crack whose two tips are mesh nodes, along embedded edges,
    in uniform stress parallel to it: displacement continuous and exact."""
    a, b = (-0.5, 0.1), (0.45, 0.1)
    md = cl.create_square(0.1, embed_lines=[(a, b)])
    sigma = np.array([[0.3, 0.0], [0.0, 0.0]])
    scene, exact = uniform_stress_scene(md, cl.Material(1.0, 0.3), sigma, [cl.Crack([a, b])])
    x = md.mesh.geometry.x[:, :2]
    sol = cl.solve(scene)
    g = sol.model.geometries[0]
    assert sol.model.cracks[0].tips == (True, True)
    assert g.tip_cells["cell"].size == 0  # tips on nodes: no tip cell
    assert sol.model.layout.num_enriched > 0
    scale = np.abs(exact(x)).max()
    on = np.stack([np.linspace(-0.49, 0.44, 40), np.full(40, 0.1)], axis=1)
    for side in (1, -1):
        assert np.abs(sol.displacement(on, side=side) - exact(on)).max() <= 1e-10 * scale
    assert np.abs(sol.crack_opening(0)["jump"]).max() <= 1e-10 * scale
