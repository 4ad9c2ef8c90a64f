"""Scene input: gmsh meshes with named tags, .msh files, several and kinked cracks."""
import cracklip as cl
import numpy as np
import pytest


def _area(md):
    x = md.mesh.geometry.x[:, :2]
    c = md.mesh.geometry.dofmap.array.reshape(-1, 3)
    e1, e2 = x[c[:, 1]] - x[c[:, 0]], x[c[:, 2]] - x[c[:, 0]]
    return 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]).sum()


def test_half_annulus_tags_and_area():
    md = cl.create_half_annulus(0.2)
    assert set(md.tags) == {"hole", "outer", "symmetry"}
    assert _area(md) == pytest.approx(0.5 * np.pi * (9 - 1), rel=2e-2)  # polygonal arcs
    x = md.mesh.geometry.x[:, :2]
    r = np.linalg.norm(x, axis=1)
    assert r.min() == pytest.approx(1.0, abs=1e-9) and r.max() == pytest.approx(3.0, abs=1e-9)
    assert x[:, 1].min() == pytest.approx(0.0, abs=1e-12)
    for name in md.tags:
        assert md.facets(name).size > 0


def test_plate_with_holes_tags_area_and_errors():
    holes = [(4.0, 2.25, 0.25), (4.0, 4.25, 0.25), (4.0, 6.25, 0.25)]
    md = cl.create_plate_with_holes(0.0, 0.0, 20.0, 8.0, 0.2, holes)
    assert set(md.tags) == {"left", "right", "bottom", "top", "hole"}
    assert _area(md) == pytest.approx(160.0 - 3 * np.pi * 0.25 ** 2, rel=1e-3)
    # Every hole's edge is tagged: the facets' vertices on one of the three circles.
    x = md.mesh.geometry.x[:, :2]
    md.mesh.topology.create_connectivity(1, 0)
    f2v = md.mesh.topology.connectivity(1, 0)
    mids = np.array([x[f2v.links(f)] for f in md.facets("hole")]).reshape(-1, 2)
    d = np.stack([np.hypot(mids[:, 0] - cx, mids[:, 1] - cy) - r for cx, cy, r in holes], axis=1)
    assert np.all(np.abs(d).min(axis=1) < 1e-9)
    assert set(np.abs(d).argmin(axis=1)) == {0, 1, 2}
    with pytest.raises(cl.MeshError, match="holes 0 and 1 overlap"):
        cl.create_plate_with_holes(0.0, 0.0, 20.0, 8.0, 0.5, [(4.0, 2.0, 0.5), (4.0, 2.8, 0.5)])
    with pytest.raises(cl.MeshError, match="hole 1 .* must lie strictly inside"):
        cl.create_plate_with_holes(0.0, 0.0, 20.0, 8.0, 0.5, [(4.0, 2.0, 0.5), (19.8, 2.0, 0.5)])
    from cracklip.io.scene_file import build_scene
    doc = {"mesh": {"kind": "plate_with_holes", "h": 0.5, "domain": [0, 0, 20, 8], "holes": [list(h) for h in holes]},
           "material": {"E": 1.0, "nu": 0.3}, "dirichlet": [{"tag": "left"}]}
    assert build_scene(doc).scene.mesh.facets("hole").size > 0
    doc["mesh"]["holes"] = [[4.0, 2.0]]
    with pytest.raises(cl.InputError, match=r"mesh\.holes\[0\]"):
        build_scene(doc)


def test_read_msh_round_trip(tmp_path):
    import gmsh
    from cracklip.scene.mesh import _gmsh
    g = _gmsh()
    g.model.add("file")
    g.model.occ.addRectangle(0, 0, 0, 2, 1)
    g.model.occ.synchronize()
    g.model.addPhysicalGroup(2, [1], 1)
    for i, (_, c) in enumerate(g.model.getEntities(1), start=1):
        g.model.addPhysicalGroup(1, [c], i)
        g.model.setPhysicalName(1, i, f"side{i}")
    g.option.setNumber("Mesh.MeshSizeMax", 0.2)
    g.model.mesh.generate(2)
    path = tmp_path / "rect.msh"
    gmsh.write(str(path))
    g.model.remove()
    md = cl.read_msh(path)
    assert set(md.tags) == {"side1", "side2", "side3", "side4"}
    assert _area(md) == pytest.approx(2.0, rel=1e-12)
    with pytest.raises(cl.MeshError, match="does not exist"):
        cl.read_msh(tmp_path / "missing.msh")


def test_kinked_through_crack_pieces_translate_rigidly():
    """A kinked polyline cutting the square; no load, each piece held at two
    nodes with its own translation: the pieces translate, the opening along
    the kinked crack is the difference of translations."""
    md = cl.create_square(0.1)
    crack = cl.Crack([[-1.5, -0.2], [-0.1, 0.07], [0.4, -0.05], [1.5, 0.31]])
    x = md.mesh.geometry.x[:, :2]
    from cracklip import _cracklip
    d = _cracklip.signed_distance(crack.points, x)
    shift = {1: np.array([0.01, -0.02]), -1: np.array([-0.005, 0.003])}
    bcs = []
    for side in (1, -1):
        nodes = np.flatnonzero(d * side > 0.3)
        for k, node in enumerate([nodes[np.argmin(x[nodes, 0])], nodes[np.argmax(x[nodes, 0])]]):
            value = (lambda q, v=shift[side]: np.tile(v, (len(q), 1))) if k == 0 else shift[side][1]
            bcs.append(cl.Dirichlet(tuple(x[node]), None if k == 0 else 1, value))
    sol = cl.solve(cl.Scene(md, cl.Material(1.0, 0.3), cracks=[crack], dirichlet=bcs))
    op = sol.crack_opening(0)
    assert np.abs(op["jump"] - (shift[1] - shift[-1])).max() <= 1e-12
    rng = np.random.default_rng(3)
    p = rng.uniform(-0.95, 0.95, (300, 2))
    side = np.where(_cracklip.signed_distance(crack.points, p) >= 0, 1, -1)
    expected = np.where(side[:, None] > 0, shift[1], shift[-1])
    far = np.abs(_cracklip.signed_distance(crack.points, p)) > 0.1  # P1 crack = polyline away from kinks
    assert np.abs(sol.displacement(p[far]) - expected[far]).max() <= 1e-12


def test_two_parallel_interior_cracks_in_uniform_stress():
    from conftest import uniform_stress_scene
    md = cl.create_square(0.08)
    cracks = [cl.Crack([[-0.6, 0.31], [0.2, 0.31]]), cl.Crack([[-0.1, -0.27], [0.7, -0.27]])]
    scene, _ = uniform_stress_scene(md, cl.Material(1.0, 0.2), np.array([[0.2, 0.0], [0.0, 0.0]]), cracks)
    sol = cl.solve(scene)
    assert [c.tips for c in sol.model.cracks] == [(True, True), (True, True)]
    assert set(sol.model.layout.crack.tolist()) == {0, 1}
    scale = np.abs(sol.standard_displacement).max()
    for i in range(2):
        assert np.abs(sol.crack_opening(i)["jump"]).max() <= 1e-10 * scale


def _tagged_length(md, name):
    x = md.mesh.geometry.x[:, :2]
    md.mesh.topology.create_connectivity(1, 0)
    f2v = md.mesh.topology.connectivity(1, 0)
    ends = np.array([x[f2v.links(f)] for f in md.facets(name)])
    return float(np.linalg.norm(ends[:, 1] - ends[:, 0], axis=1).sum())


@pytest.mark.parametrize("make, lengths", [
    (lambda: cl.create_rectangle(-1.0, -0.5, 1.0, 0.5, 0.05),
     {"left": 1.0, "right": 1.0, "bottom": 2.0, "top": 2.0}),
    (lambda: cl.create_rectangle(0.0, 0.0, 0.2, 4.0, 0.01),  # tall: horizontal cuts
     {"left": 4.0, "right": 4.0, "bottom": 0.2, "top": 0.2}),
    (lambda: cl.create_plate_with_holes(0.0, 0.0, 4.0, 2.0, 0.06, [(1.0, 1.0, 0.3), (3.0, 1.0, 0.4)]),
     {"left": 2.0, "right": 2.0, "bottom": 4.0, "top": 4.0, "hole": 2 * np.pi * 0.7}),
    (lambda: cl.create_half_annulus(0.08),
     {"hole": np.pi, "outer": 3 * np.pi, "symmetry": 4.0}),
])
def test_large_meshes_cut_into_strips_keep_their_tags(monkeypatch, make, lengths):
    """A large domain is meshed in strips (mesh.STRIP_NODES, here made small
    so that these meshes count as large), cut across its longer side, no
    strip narrower than STRIP_MIN_WIDTH elements: every boundary keeps its
    tag over its whole length, the cut lines carry none, and the mesh is the
    same every time (gmsh meshes the strips one at a time)."""
    from cracklip.scene import mesh as cm
    monkeypatch.setattr(cm, "STRIP_NODES", 300)
    made = []
    cut = cm._cut_into_strips
    monkeypatch.setattr(cm, "_cut_into_strips", lambda gmsh, h: made.append(cut(gmsh, h)) or made[-1])
    md = make()
    (axis, positions), = made
    x = md.mesh.geometry.x[:, :2]
    span = np.ptp(x, axis=0)
    assert axis == (0 if span[0] >= span[1] else 1)
    assert len(positions) >= 3
    assert np.diff(positions).min() >= cm.STRIP_MIN_WIDTH * md.h
    for t in positions:  # a row of nodes along every cut (OCC bounding boxes carry 1e-7)
        assert np.count_nonzero(np.abs(x[:, axis] - t) < 1e-6) >= 5
    for name, length in lengths.items():
        # Polygonal arcs are a little shorter than the circles.
        assert _tagged_length(md, name) == pytest.approx(length, rel=2e-3), name
    tagged = sum(_tagged_length(md, name) for name in md.tags)
    assert tagged == pytest.approx(sum(lengths.values()), rel=2e-3)  # nothing on the cuts
    again = make()
    assert np.array_equal(again.mesh.geometry.x, md.mesh.geometry.x)
    assert np.array_equal(again.mesh.geometry.dofmap.array, md.mesh.geometry.dofmap.array)


def test_strips_never_narrower_than_eight_elements(monkeypatch):
    from cracklip.scene import mesh as cm
    monkeypatch.setattr(cm, "STRIP_NODES", 50)
    made = []
    cut = cm._cut_into_strips
    monkeypatch.setattr(cm, "_cut_into_strips", lambda gmsh, h: made.append(cut(gmsh, h)) or made[-1])
    cl.create_rectangle(0.0, 0.0, 0.32, 0.3, 0.02)  # ~280 nodes: 6 strips by count, 2 by width
    assert made == [(0, [pytest.approx(0.16 * (1 + cm.STRIP_OFFSET))])]
