"""Issue 26: refinement on any geometry. A user's gmsh .geo, STEP or BREP
meshed by cracklip with the built-in shapes' size fields; a user's .msh
refined locally (tags kept); messages that name the real cause.

Reference for K: the C(T) of demos/geometry/ct_specimen.geo (a/W = 0.5,
P = 1000 N/mm, W = 50 mm), converged to 1359.6 +- 0.3 by cracklip on
independent fine meshes (h = W/160, tip_h = 0.025 mm: 1359.35; W/80 with a
level: 1359.91); ASTM E399 gives 1366.0 (0.5 %, a pin's bearing load; see
tests/test_accuracy.py::test_references).
"""
import json
import pathlib

import cracklip as cl
import numpy as np
import pytest
from cracklip import cli
from cracklip.io.scene_file import load_scene_file
from cracklip.scene.geometry_file import create_from_geometry
from cracklip.scene.refine import cell_sizes, refine_file_mesh

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENES = ROOT / "demos" / "scenes"
CT_GEO = ROOT / "demos" / "geometry" / "ct_specimen.geo"
K_CT = 1359.6
POINTS = [(0.0, 20.0), (0.0, -20.0), (50.0, 0.0), (50.0, 30.0)]


def gmsh_session():
    """gmsh, initialised as cracklip does it (quiet)."""
    from cracklip.scene.mesh import _gmsh
    return _gmsh()


def write_msh(geo_text: str, path: pathlib.Path, size: float | None = None) -> pathlib.Path:
    """Mesh a .geo text as a user would with gmsh and write the .msh."""
    gmsh = gmsh_session()
    geo = path.with_suffix(".geo")
    geo.write_text(geo_text)
    gmsh.open(str(geo))
    if size is not None:
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.model.mesh.generate(2)
    gmsh.write(str(path))
    gmsh.model.remove()
    return path


def msh_scene(tmp_path, msh: pathlib.Path) -> pathlib.Path:
    """ct_specimen.toml with the mesh from a .msh file (mesh.kind = "file")."""
    text = (SCENES / "ct_specimen.toml").read_text()
    text = text.replace('kind = "geometry"', 'kind = "file"').replace('path = "../geometry/ct_specimen.geo"',
                                                                      f'path = "{msh}"').replace("h = 2.5\n", "")
    scene = tmp_path / "ct_msh.toml"
    scene.write_text(text)
    return scene


def test_geo_is_meshed_with_the_size_fields():
    """The .geo's physical curves are the tags, the point loads and supports
    are nodes, the tip gets tip_h (the .geo's own lc, W/20, is replaced)."""
    md = create_from_geometry(CT_GEO, 2.5, embed_points=POINTS, tips=[(25.0, 0.0), (-13.0, 0.0)], tip_h=0.1)
    assert set(md.tags) == {"bottom", "back", "top", "front", "pin_top", "pin_bottom"}
    x = md.mesh.geometry.x[:, :2]
    for p in POINTS:
        assert np.linalg.norm(x - p, axis=1).min() < 1e-12
    cells = md.mesh.geometry.dofmap.array.reshape(-1, 3)
    size, centroid = cell_sizes(x, cells), x[cells].mean(axis=1)
    assert size[np.argmin(np.linalg.norm(centroid - (25.0, 0.0), axis=1))] <= 1.25 * 0.1
    assert size.max() <= 1.5 * 2.5
    assert md.refinements == [(25.0, 0.0, 0.1)]  # the crack's mouth (-13, 0) is outside: no tip there
    # A level halves the sizes around a point: the recipe makes the mesh again.
    fine = md.recipe(levels=[(25.0, 0.0, 25.0, 0.0, 75.0, 1)])
    assert fine.mesh.topology.index_map(2).size_local > 3 * md.mesh.topology.index_map(2).size_local


def test_ct_from_a_users_geo_with_tip_h():
    """Acceptance 2: the C(T) from the user's .geo, h = 0.8 mm, tip_h = 0.1 mm
    (enrichment radius 0.5 mm, five tip elements): K within 0.5 % of K_CT
    (measured 1358.0, -0.12 %), no warning."""
    sf = load_scene_file(SCENES / "ct_specimen.toml", ["mesh.h=0.8", "mesh.tip_h=0.1", "options.radius=0.5"])
    sol = cl.solve(sf.scene)
    (r,) = sol.stress_intensity_factors(0)
    assert abs(r["K_I"] - K_CT) <= 0.005 * K_CT and r["element_size"] <= 1.25 * 0.1
    assert not sol.warnings


def test_ct_from_a_users_msh_refined_locally(tmp_path):
    """Acceptance 2 with the user's .msh: meshed by gmsh from the same .geo
    at 0.625 mm, read with mesh.kind = "file", tip_h = 0.1 refines it around
    the tip (DOLFINx Plaza): K within 0.5 % of K_CT (measured 1357.9,
    -0.12 %); the tags survive the refinement."""
    msh = write_msh(CT_GEO.read_text(), tmp_path / "ct.msh", size=0.625)
    sf = load_scene_file(msh_scene(tmp_path, msh), ["mesh.tip_h=0.1", "options.radius=0.5"])
    sol = cl.solve(sf.scene)
    (r,) = sol.stress_intensity_factors(0)
    assert abs(r["K_I"] - K_CT) <= 0.005 * K_CT and r["element_size"] <= 1.25 * 0.1
    assert set(sf.scene.mesh.tags) == {"bottom", "back", "top", "front", "pin_top", "pin_bottom"}
    assert not sol.warnings


def test_refinement_of_a_file_mesh_keeps_its_tags(tmp_path):
    """Every refined facet of a tag lies on one of the tag's old facets and
    the tag's length is unchanged (to 1e-12): the facets are halves of the old
    ones, none lost, none added."""
    import dolfinx.cpp.mesh
    md = cl.read_msh(write_msh(CT_GEO.read_text(), tmp_path / "ct.msh"))
    fine = refine_file_mesh(md, [(0.0, 20.0, 0.05, 0.0)])  # at the upper pin: its tag is refined
    for tag in md.tags:
        def segments(m):
            f = m.facets(tag)
            g = dolfinx.cpp.mesh.entities_to_geometry(m.mesh._mesh, 1, f, False)
            x = m.mesh.geometry.x[:, :2]
            return x[g[:, 0]], x[g[:, 1]]
        a, b = segments(md)
        p, q = segments(fine)
        assert np.linalg.norm(q - p, axis=1).sum() == pytest.approx(np.linalg.norm(b - a, axis=1).sum(), rel=1e-12)
        mid = 0.5 * (p + q)
        d = b - a
        t = np.clip(np.einsum("mki,ki->mk", mid[:, None, :] - a[None], d) / np.einsum("ki,ki->k", d, d), 0, 1)
        dist = np.linalg.norm(a[None] + t[..., None] * d[None] - mid[:, None, :], axis=2).min(axis=1)
        assert dist.max() < 1e-9
    assert fine.facets("pin_top").size > md.facets("pin_top").size


def test_step_and_brep_through_opencascade(tmp_path):
    """The same C(T) drawn with OpenCASCADE, saved as BREP and STEP: cracklip
    meshes each (tags 'curve N': the 6 curves, the back face and both holes
    split at the points that become nodes, 9);
    at the settings of acceptance 2 K is within 0.5 % of K_CT, as from the
    .geo (the meshes differ: K moves by 0.1-0.2 % between them)."""
    gmsh = gmsh_session()
    gmsh.model.add("ct")
    occ = gmsh.model.occ
    plate = occ.addRectangle(-12.5, -30.0, 0.0, 62.5, 60.0)
    occ.cut([(2, plate)], [(2, occ.addDisk(0.0, 13.75, 0.0, 6.25, 6.25)), (2, occ.addDisk(0.0, -13.75, 0.0, 6.25, 6.25))])
    occ.synchronize()
    for suffix in (".brep", ".step"):
        gmsh.write(str(tmp_path / f"ct{suffix}"))
    gmsh.model.remove()
    over = ["mesh.h=0.8", "mesh.tip_h=0.1", "options.radius=0.5"]
    for suffix in (".brep", ".step"):
        sf = load_scene_file(SCENES / "ct_specimen.toml", over + [f'mesh.path="{tmp_path / ("ct" + suffix)}"'])
        assert all(name.startswith("curve ") for name in sf.scene.mesh.tags) and len(sf.scene.mesh.tags) == 9
        k = cl.solve(sf.scene).stress_intensity_factors(0)[0]["K_I"]
        assert abs(k - K_CT) <= 0.005 * K_CT


def test_msh_without_physical_groups(tmp_path):
    """The issue: '2 node(s) belong to no triangle ... remove unused nodes'.
    The cause is named: no physical groups, so gmsh saved the construction
    points (the holes' centres) and no boundary has a name."""
    text = "\n".join(line for line in CT_GEO.read_text().splitlines() if not line.startswith("Physical"))
    msh = write_msh(text, tmp_path / "nophys.msh")
    with pytest.raises(cl.MeshError, match=r"no physical groups.*construction points.*node\(s\) in no triangle.*"
                                           r"Physical Surface.*Physical Curve"):
        cl.read_msh(msh)


def test_msh_with_curves_but_no_physical_surface(tmp_path):
    """The issue: 'mesh with Mesh.ElementOrder = 1'. The cause: no Physical
    Surface, so gmsh saved only the physical curves' lines."""
    text = "\n".join(line for line in CT_GEO.read_text().splitlines() if not line.startswith("Physical Surface"))
    msh = write_msh(text, tmp_path / "nosurf.msh")
    with pytest.raises(cl.MeshError, match=r"no Physical Surface.*saves only the elements of physical groups.*"
                                           r"Physical Surface\(\"part\"\)"):
        cl.read_msh(msh)


def test_geometry_given_as_a_mesh_file_and_points_off_the_part(tmp_path):
    """A .geo under mesh.kind = 'file' says to use kind 'geometry'; a point
    support in a pin hole is refused with the nearest point of the part."""
    with pytest.raises(cl.MeshError, match=r"is a geometry, not a mesh: use mesh.kind = \"geometry\""):
        load_scene_file(msh_scene(tmp_path, CT_GEO))
    with pytest.raises(cl.MeshError, match=r"\(0, 13.75\) of a point support or force lies outside the part \(in a "
                                           r"hole or beyond its boundary; the nearest boundary point is"):
        load_scene_file(SCENES / "ct_specimen.toml", ["dirichlet[1].point=[0.0, 13.75]"])


HOLE_SCENE = """
title = "crack across a hole"
[mesh]
kind = "plate_with_hole"
domain = [-40.0, -40.0, 40.0, 40.0]
hole_radius = 5.0
h = 4.0
tip_h = 0.5
[[mesh.refine]]
point = [0.0, 0.0]
h = 0.5
[material]
E = 70000.0
nu = 0.3
[[cracks]]
points = [[-10.0, 0.0], [10.0, 0.0]]
[[dirichlet]]
tag = "bottom"
[[loads.tractions]]
tag = "top"
value = [0.0, 100.0]
"""


def test_check_names_a_crack_across_a_hole_and_a_refinement_in_it(tmp_path, capsys):
    """The issue: check called a crack crossing a hole 'interior (two tips),
    length 20' and said a refinement centred in the hole 'could not be
    honoured'. Now: two edge cracks from the hole's edge, 5 each, 10 in the
    part; the refinement's point lies in a hole and does not reach the part."""
    scene = tmp_path / "hole.toml"
    scene.write_text(HOLE_SCENE)
    assert cli.main(["check", str(scene), "--json"]) == 0
    captured = capsys.readouterr()
    crack = json.loads(captured.out)["model"]["cracks"][0]
    assert crack["kind"] == ("2 pieces in the part (it crosses a hole): an edge crack from a hole's edge (5 long); "
                             "an edge crack from a hole's edge (5 long)")
    assert crack["length_in_part"] == pytest.approx(10.0) and crack["length"] == pytest.approx(20.0)
    (w,) = [w for w in json.loads(captured.out)["warnings"] if w["code"] == "refinement"]
    assert "lies in a hole of the part" in w["message"] and "does not reach the part" in w["message"]
    assert "could not be honoured" not in w["message"]


def test_a_geo_syntax_error_is_named_and_does_not_break_the_rest(tmp_path):
    """gmsh 4.8's .geo parser does not recover from a syntax error (every
    later script parses to nothing, and its meshes came out empty): the error
    names the file, a later .geo is refused with the cause, and the built-in
    shapes and STEP/BREP parts still mesh. In a subprocess (the parser stays
    broken for the rest of the process)."""
    import subprocess
    import sys
    bad = tmp_path / "bad.geo"
    bad.write_text("Point(1) = {0, 0, 0;\n")
    code = f"""
import cracklip as cl
from cracklip.scene.geometry_file import create_from_geometry
for path in ({str(bad)!r}, {str(CT_GEO)!r}):
    try:
        create_from_geometry(path, 5.0)
    except cl.MeshError as e:
        print(e)
print(cl.create_square(0.2).mesh.topology.index_map(2).size_local)
"""
    env = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin"}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300,
                         check=True).stdout.splitlines()
    assert "bad.geo: gmsh cannot read this geometry" in out[0] and "syntax error" in out[0]
    assert "cannot read another script in this process after the syntax error in" in out[1] and "bad.geo" in out[1]
    assert int(out[2]) > 100
