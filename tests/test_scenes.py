"""Scene files: every example runs small and its outputs read back; the schema
and the README's scene reference agree; bad keys and values are typed errors."""
import csv
import json
import pathlib
import re

import cracklip as cl
import meshio
import numpy as np
import pytest
from cracklip import cli
from cracklip.io import scene_file
from cracklip.io.scene_file import (SCHEMA, apply_override, build_scene, check_keys, load_scene_file,
                                    parse_settings, reference_markdown, reference_rows)
from test_scenes_3d import SMALL_3D

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENES = ROOT / "demos" / "scenes"

#: Small sizes for the tests (the files themselves hold realistic sizes).
SMALL = {
    "block_uniform_pressure": ["mesh.h=0.1"],
    "hole_crack": ["mesh.h=0.1"],
    "westergaard": ["mesh.h=0.1"],
    "partly_open_crack": ["mesh.h=0.1", "mesh.tip_h=0.04"],
    "interacting_cracks": ["mesh.h=0.1", "mesh.tip_h=0.03"],
    "pressurised_crack": ["mesh.h=2.0", "mesh.tip_h=0.05"],
    "edge_notch_bending": ["mesh.h=0.1", "mesh.tip_h=0.02"],
    "three_point_bending": ["mesh.h=0.1", "mesh.tip_h=0.02"],
    "residual_stress": ["mesh.h=0.1", "mesh.tip_h=0.02"],
    "frictional_crack": ["mesh.h=0.1", "mesh.tip_h=0.025"],
    "ct_specimen": ["mesh.h=5.0", "mesh.tip_h=0.5"],
    "brazilian_disc": ["mesh.h=8.0", "mesh.tip_h=1.0"],
    "hole_fatigue": ["mesh.h=40.0", "mesh.refine[0].h=0.5"],
    # growth scenes (grown by tests/test_growth.py)
    "fatigue_edge_crack": ["mesh.h=0.1", "mesh.refine[0].h=0.02"],
    "wing_crack": ["mesh.h=0.2", "mesh.refine[0].h=0.03"],
    "drilled_plate": ["mesh.h=1.0", "mesh.refine[0].h=0.1", "mesh.refine[1].h=0.1"],
    # the fatigue life under a spectrum (grown by tests/test_life.py)
    "hole_crack_spectrum": ["mesh.h=10.0", "mesh.refine[0].h=0.5"],
    # 3D growth (grown by tests/test_growth_3d.py)
    "surface_crack_growth": ["mesh.h=10.0", "mesh.refine[0].h=0.3", "mesh.refine[0].radius=30.0", "growth.steps=1"],
    "corner_crack_growth": ["mesh.h=8.0", "mesh.refine[0].h=0.12", "mesh.refine[0].radius=30.0", "growth.steps=2"],
    "corner_crack_gag": ["mesh.refine[0].h=0.2", "options.radius=0.5", "growth.steps=1"],
    # lives without a mesh (run as they are by tests/test_table_life.py: a second each)
    "life_hole_crack": [],
    "life_surface_crack": [],
    # 3D parts (run by tests/test_scenes_3d.py)
    **SMALL_3D,
}


def test_every_example_has_a_small_size():
    assert {p.stem for p in SCENES.glob("*.toml")} == set(SMALL)


def run_scene(name, out, *extra):
    args = ["run", str(SCENES / f"{name}.toml"), "--out", str(out), "--quiet"]
    for o in SMALL[name] + list(extra):
        args += ["--set", o]
    assert cli.main(args) == 0
    results = json.loads((out / "results.json").read_text())
    with (out / "crack.csv").open() as f:
        crack = list(csv.DictReader(f))
    with (out / "sif.csv").open() as f:
        sif = list(csv.DictReader(f))
    return results, crack, sif


def column(rows, key, crack=None):
    return np.array([float(r[key]) for r in rows if crack is None or int(r["crack"]) == crack])


def check_common(out, results, crack, sif):
    """Files present, nothing half-written, ParaView files with their fields."""
    names = {p.name for p in out.iterdir()}
    assert names == {"results.json", "crack.csv", "sif.csv", "solution.vtu", "crack_lips.vtu",
                     "deformed.png", "crack_pressure.png", "stress.png"}
    assert set(results["files"]) == names
    for png in ("deformed.png", "crack_pressure.png", "stress.png"):
        assert (out / png).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert (out / png).stat().st_size > 20_000
    for key in ("versions", "model", "sifs", "cracks", "timings", "solution"):
        assert key in results
    assert results["versions"]["dolfinx"] == "0.5.2"
    assert results["timings"]["mesh"] > 0 and results["timings"]["solve.total"] > 0
    assert results["model"]["dofs"]["total"] == results["solution"]["dofs"]
    last = max(int(r["step"]) for r in sif) if sif else 0
    assert len([r for r in sif if int(r["step"]) == last]) == len(results["sifs"])
    m = meshio.read(out / "solution.vtu")
    ntri = m.cells_dict["triangle"].shape[0]
    assert ntri >= results["model"]["cells"]  # sub-cells: cut cells split
    assert m.point_data["displacement"].shape == (m.points.shape[0], 3)
    for name in ("stress_xx", "stress_yy", "stress_xy", "stress_von_mises", "side", "parent_cell"):
        assert m.cell_data[name][0].shape == (ntri,)
    assert np.all(np.isfinite(m.point_data["displacement"]))
    lips = meshio.read(out / "crack_lips.vtu")
    # Two lips per crack, one line point per crack.csv row (of the last step) on each.
    last_rows = [r for r in crack if r["step"] == max(r["step"] for r in crack)]
    assert lips.points.shape[0] == 2 * len(last_rows)
    for name in ("pressure", "shear", "gap", "slip", "state", "displacement"):
        assert name in lips.point_data
    assert set(np.unique(lips.cell_data["lip"][0]).tolist()) == {-1, 1}
    s = column(last_rows, "s")
    for c in range(len(results["cracks"])):
        sc = column(last_rows, "s", c)
        assert np.all(np.diff(sc) >= 0.0)  # sorted along each crack
    assert len(s) > 0


def test_block_scene(tmp_path):
    """Paper 5.1: closed crack, uniform contact pressure 0.01, K_I = 0."""
    results, crack, sif = run_scene("block_uniform_pressure", tmp_path)
    check_common(tmp_path, results, crack, sif)
    p = column(crack, "pressure")
    assert np.abs(p - 0.01).max() < 1e-7
    assert np.abs(column(crack, "gap")).max() < 1e-9
    assert column(crack, "closed").min() == 1
    c = results["cracks"][0]
    assert c["closed_fraction"] == pytest.approx(1.0)
    assert c["length_in_part"] == pytest.approx(0.4, rel=1e-9)
    assert c["pressure"]["normal_force"] == pytest.approx(0.004, rel=1e-6)
    assert abs(float(sif[0]["K_I"])) < 1e-8 and abs(results["sifs"][0]["K_II"]) < 1e-8
    assert results["sifs"][0]["mode_mix_deg"] is None and sif[0]["mode_mix_deg"] == ""
    assert (float(sif[0]["x"]), float(sif[0]["y"])) == pytest.approx((-0.6, 0.0))
    assert results["contact"]["law"] == "bilateral" and results["contact"]["multipliers"] > 0
    assert results["model"]["contact"]["multipliers"] == results["contact"]["multipliers"]
    # Arc length from the crack's first point, on the left edge.
    s = column(crack, "s")
    assert s.min() >= 0.0 and s.max() <= 0.4 + 1e-12
    assert np.allclose(column(crack, "x"), -1.0 + s)


def test_hole_scene(tmp_path):
    """Paper 5.2: Kirsch traction; the crack stays closed with the Kirsch pressure."""
    results, crack, sif = run_scene("hole_crack", tmp_path)
    check_common(tmp_path, results, crack, sif)
    y = column(crack, "y")
    exact = 0.01 * (1 + 1 / (2 * y ** 2) + 3 / (2 * y ** 4))
    p = column(crack, "pressure")
    assert np.all(p > 0.0)
    assert np.sqrt(np.mean((p - exact) ** 2) / np.mean(exact ** 2)) < 0.05
    assert results["cracks"][0]["closed_fraction"] == pytest.approx(1.0)
    assert results["contact"]["law"] == "unilateral" and results["contact"]["iterations"] >= 1
    assert abs(results["sifs"][0]["K_I"]) < 0.05 * 0.01 * np.sqrt(np.pi)
    assert results["model"]["cracks"][0]["kind"].startswith("edge")


def test_westergaard_scene(tmp_path):
    """Exact mode I field on the boundary: K_I = 1, K_II = 0, the crack open."""
    results, crack, sif = run_scene("westergaard", tmp_path)
    check_common(tmp_path, results, crack, sif)
    assert float(sif[0]["K_I"]) == pytest.approx(1.0, abs=0.01)
    assert abs(float(sif[0]["K_II"])) < 0.01
    assert abs(results["sifs"][0]["mode_mix_deg"]) < 1.0
    assert results["contact"] is None and "pressure" not in results["cracks"][0]
    gap = column(crack, "gap")
    assert np.all(gap > 0.0) and results["cracks"][0]["closed_fraction"] == 0.0
    # Opening of the exact field behind the tip: 8 (1 - nu^2) K_I / E sqrt(r / (2 pi)).
    r = -column(crack, "x")
    far = r > 0.3
    exact = 8 * (1 - 0.3 ** 2) * np.sqrt(r / (2 * np.pi))
    assert np.abs(gap[far] - exact[far]).max() < 0.02 * exact[far].max()
    assert np.abs(column(crack, "slip")).max() < 0.01 * gap.max()


def test_partly_open_scene(tmp_path):
    """Cantilever under self-weight: the crack closes in the compressed lower half only."""
    results, crack, sif = run_scene("partly_open_crack", tmp_path)
    check_common(tmp_path, results, crack, sif)
    c = results["cracks"][0]
    assert 0.1 < c["closed_fraction"] < 0.9
    y = column(crack, "y")
    closed = column(crack, "closed") == 1
    p, gap = column(crack, "pressure"), column(crack, "gap")
    assert y[closed].max() < y[~closed].min()  # closed below, open above
    assert np.all(p >= -1e-12) and np.all(p[~closed] == 0.0)
    assert gap[~closed].max() > 10 * max(c["interpenetration_max"], 1e-300)
    assert len(c["closed_s_ranges"]) == 1 and c["closed_s_ranges"][0][0] < 0.05
    assert results["contact"]["iterations"] > 1  # the active set moved
    upper = max(results["sifs"], key=lambda r: r["y"])
    lower = min(results["sifs"], key=lambda r: r["y"])
    assert upper["K_I"] > 0.0 and abs(lower["K_I"]) < 0.1 * upper["K_I"]
    assert results["model"]["cracks"][0]["kind"].startswith("interior")


def test_interacting_cracks_scene(tmp_path):
    """Two en-echelon cracks: point symmetry, the inner tips shielded and sheared."""
    results, crack, sif = run_scene("interacting_cracks", tmp_path)
    check_common(tmp_path, results, crack, sif)
    assert len(sif) == 4 and {int(r["crack"]) for r in sif} == {0, 1}
    K = {(int(r["crack"]), int(r["tip"])): (float(r["K_I"]), float(r["K_II"])) for r in sif}
    outer, inner = K[(0, 0)], K[(0, 1)]
    assert outer[0] == pytest.approx(K[(1, 1)][0], rel=0.02)  # point-symmetric pair
    assert inner[0] == pytest.approx(K[(1, 0)][0], rel=0.02)
    assert inner[0] < outer[0] and abs(inner[1]) > abs(outer[1])
    assert all(c["closed_fraction"] == 0.0 for c in results["cracks"])
    assert len(results["model"]["cracks"]) == 2


# -- the schema and its reference page (docs/scene_reference.md, linked from the README) ---------

REFERENCE = ROOT / "docs" / "scene_reference.md"


def readme_reference() -> list[tuple[str, ...]]:
    section = REFERENCE.read_text()
    rows = [line for line in section.splitlines() if line.startswith("| `")]
    return [tuple(cell.strip() for cell in line.strip().strip("|").split(" | ")) for line in rows]


def sample_document(path: str) -> dict:
    """A document holding the key `path` (schema notation), all else minimal."""
    doc: dict = {}
    node = doc
    parts = path.split(".")
    for part in parts[:-1]:
        if part.endswith("[]"):
            node = node.setdefault(part[:-2], [{}])[0]
        else:
            node = node.setdefault(part, {})
    node[parts[-1]] = 1.0
    return doc


def test_readme_reference_is_the_schema():
    rows = readme_reference()
    documented = [r[0].strip("`") for r in rows]
    assert len(documented) == len(set(documented))
    assert set(documented) == {k.path for k in SCHEMA}
    # Types, defaults and meanings too: the README table is the generated one.
    assert [(f"`{k}`", t, d, m.replace("|", "/")) for k, t, d, m in reference_rows()] == rows, \
        "docs/scene_reference.md is stale: replace its table by `python3 -m cracklip reference`"
    assert reference_markdown() in REFERENCE.read_text()
    assert "(docs/scene_reference.md)" in (ROOT / "README.md").read_text()


def test_parser_accepts_exactly_the_documented_keys():
    for path in (r[0].strip("`") for r in readme_reference()):
        check_keys(sample_document(path))  # accepted
        with pytest.raises(cl.InputError, match=re.escape(f"did you mean {path.replace('[]', '[0]')}?")):
            check_keys(sample_document(path + "x"))


def test_every_option_of_the_solver_is_a_key():
    import dataclasses
    assert {f"options.{f.name}" for f in dataclasses.fields(cl.Options)} < {k.path for k in SCHEMA}


# -- errors ----------------------------------------------------------------------------------------

BASE = {"mesh": {"h": 0.5}, "material": {"E": 1.0, "nu": 0.3},
        "dirichlet": [{"tag": "bottom"}]}


def doc_with(**sections):
    import copy
    d = copy.deepcopy(BASE)
    for k, v in sections.items():
        d[k] = v
    return d


@pytest.mark.parametrize("doc, match", [
    (doc_with(mesh={"hh": 0.1}), r"unknown key mesh\.hh; did you mean mesh\.h\?"),
    (doc_with(options={"enrichmnt": "vector"}), r"did you mean options\.enrichment\?"),
    (doc_with(options={"h": 0.1}), r"unknown key options\.h; did you mean mesh\.h\?"),
    (doc_with(cracks=[{"pionts": [[0, 0], [1, 0]]}]),
     r"unknown key cracks\[0\]\.pionts; did you mean cracks\[0\]\.points\?"),
    (doc_with(materal={"E": 1}), r"unknown key materal; did you mean material\?"),
    (doc_with(loads={"tractions": [{"tag": "top", "kirsch": {"sigma": 1}}]}),
     r"loads\.tractions\[0\]\.kirsch\.sigma"),
])
def test_unknown_keys_name_the_nearest_valid_key(doc, match):
    with pytest.raises(cl.InputError, match=match):
        parse_settings(doc)


@pytest.mark.parametrize("doc, error, match", [
    (doc_with(mesh={"h": -1.0}), cl.InputError, r"mesh\.h must be a positive number"),
    (doc_with(mesh={"kind": "rectangle"}), cl.InputError, r"mesh\.h is required"),
    (doc_with(mesh={"kind": "disk", "h": 0.1}), cl.InputError, r"mesh\.kind must be one of"),
    (doc_with(mesh={"h": 0.1, "outer_radius": 3.0}), cl.InputError,
     r"mesh\.outer_radius applies to mesh kind 'half_annulus' only"),
    (doc_with(material={"E": 1.0}), cl.InputError, r"material\.nu is required"),
    (doc_with(material={"E": 1.0, "nu": 0.5}), cl.MaterialError, r"Poisson"),
    (doc_with(options={"contact": "unilaterl"}), cl.InputError, r"did you mean 'unilateral'"),
    # A capital letter: the same choice in lower case, not the nearest spelling ('z' before the fix).
    (doc_with(dirichlet=[{"tag": "bottom", "component": "Y"}]), cl.InputError, r"got 'Y'; did you mean 'y'\?"),
    (doc_with(options={"quadrature_degree": 2.5}), cl.InputError, r"options\.quadrature_degree must be an integer"),
    (doc_with(cracks=[{"points": [[0, 0]]}]), cl.InputError,
     r"cracks\[0\]\.points must be a list of at least two points"),
    (doc_with(cracks=[{"name": "a"}]), cl.InputError, r"cracks\[0\] needs exactly one of points"),
    (doc_with(dirichlet=[{"tag": "bottom", "point": [0, 0]}]), cl.InputError,
     r"dirichlet\[0\] needs exactly one of tag, box or point"),
    (doc_with(dirichlet=[{"tag": "bottom", "component": "y", "value": [1, 2]}]), cl.InputError,
     r"dirichlet\[0\]\.value is a vector"),
    (doc_with(dirichlet=[]), cl.BoundaryConditionError, r"no \[\[dirichlet\]\]"),
    (doc_with(loads={"tractions": [{"tag": "top"}]}), cl.InputError,
     r"exactly one of value, stress, williams or kirsch"),
    (doc_with(mesh="fine"), cl.InputError, r"mesh must be a table"),
])
def test_bad_values_are_typed_errors(doc, error, match):
    with pytest.raises(error, match=match):
        build_scene(doc)


def test_errors_after_meshing_name_the_entry():
    with pytest.raises(cl.MeshError, match=r"loads\.pressures\[0\]: unknown boundary tag 'lid'"):
        build_scene(doc_with(loads={"pressures": [{"tag": "lid", "value": 1.0}]}))
    with pytest.raises(cl.BoundaryConditionError, match=r"dirichlet\[0\]\.point \[5\.0, 5\.0\]"):
        build_scene(doc_with(dirichlet=[{"point": [5.0, 5.0]}]))
    with pytest.raises(cl.InputError, match=r"williams\.tip \[0\.5, 0\.5\] is not an end point"):
        build_scene(doc_with(cracks=[{"points": [[-1, 0], [0, 0]]}],
                             dirichlet=[{"tag": "left", "williams": {"K_I": 1.0, "tip": [0.5, 0.5]}}]))


def test_bad_toml_is_an_input_error(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[mesh]\nh = = 0.1\n")
    with pytest.raises(cl.InputError, match=r"bad\.toml: not valid TOML"):
        load_scene_file(f)


def test_overrides():
    doc = {"mesh": {"h": 0.5}, "cracks": [{"points": [[0, 0], [1, 0]]}]}
    apply_override(doc, "mesh.h=0.1")
    apply_override(doc, "mesh.kind=rectangle")  # a bare word is a string
    apply_override(doc, "cracks[0].points=[[0, 0], [0.5, 0]]")
    apply_override(doc, "options.radius = 0.3")
    assert doc == {"mesh": {"h": 0.1, "kind": "rectangle"}, "cracks": [{"points": [[0, 0], [0.5, 0]]}],
                   "options": {"radius": 0.3}}
    with pytest.raises(cl.InputError, match="KEY=VALUE"):
        apply_override(doc, "mesh.h")
    with pytest.raises(cl.InputError, match=r"cracks has 1 entries, no \[3\]"):
        apply_override(doc, "cracks[3].name=x")
    # a dotted index, as a newcomer writes it first: the message gives the bracket form (it said
    # 'cracks is not a table')
    with pytest.raises(cl.InputError, match=r"cracks is an array of tables; index it with brackets: "
                                            r"cracks\[0\]\.points"):
        apply_override(doc, "cracks.0.points=[[0, 0], [1, 0]]")


def test_option_errors_name_the_scene_key(capsys):
    """An [options] value out of range names its scene key, options.KEY
    (it said 'options: accuracy must be ...', the Python field)."""
    scene = str(ROOT / "demos" / "scenes" / "block_uniform_pressure.toml")
    assert cli.main(["check", scene, "-q", "--set", "options.accuracy=2"]) == 2
    assert "cracklip: error: options.accuracy must be a number in [0, 1)" in capsys.readouterr().err


# -- meshes, cracks, boundary conditions, loads ----------------------------------------------------

def test_scene_building_blocks(tmp_path):
    """Plate with a hole, an arc crack with tip refinement, box and point
    conditions, a uniform-stress traction, a pressure and a body force."""
    doc = {
        "title": "plate",
        "mesh": {"kind": "plate_with_hole", "domain": [-2.0, -1.0, 2.0, 1.0], "hole_radius": 0.3,
                 "h": 0.25, "tip_h": 0.08, "refine": [{"point": [1.5, 0.5], "h": 0.1, "radius": 0.3}]},
        "material": {"E": 2.0, "nu": 0.25},
        "cracks": [{"name": "arc", "arc": {"center": [0.0, 0.0], "radius": 0.6, "angles": [30.0, 90.0],
                                           "segments": 8}}],
        "dirichlet": [{"box": [-2.0, -1.0, -2.0, 1.0], "component": "x"}, {"point": [-2.0, -1.0], "component": "y"}],
        "loads": {"body_force": [0.0, -0.01], "pressures": [{"tag": "hole", "value": 0.02}],
                  "tractions": [{"tag": "right", "stress": [0.05, 0.0, 0.0]}]},
    }
    sf = build_scene(doc)
    scene = sf.scene
    assert set(scene.mesh.tags) == {"left", "right", "bottom", "top", "hole"}
    pts = scene.cracks[0].points
    # 8 segments, ends on the circle, every segment along a tangent of it (scene.crack.arc_polyline).
    assert pts.shape == (9, 2) and np.allclose(np.linalg.norm(pts[[0, -1]], axis=1), 0.6)
    seg = np.diff(pts, axis=0)
    assert np.allclose(np.abs(np.cross(seg, pts[:-1])) / np.linalg.norm(seg, axis=1), 0.6)
    assert scene.body_force == [0.0, -0.01]
    left_nodes = np.count_nonzero(np.isclose(scene.mesh.mesh.geometry.x[:, 0], -2.0))
    assert len(scene.dirichlet) == left_nodes + 1 and all(d.component == 0 for d in scene.dirichlet[:-1])
    # Tip refinement: smaller cells near both tips of the interior arc crack.
    x = scene.mesh.mesh.geometry.x[:, :2]
    for tip in pts[[0, -1]]:
        near = np.sort(np.linalg.norm(x - tip, axis=1))[1]
        assert near < 0.15
    # Pressure and uniform stress as tractions sigma n / -p n.
    hole, right = scene.tractions[1], scene.tractions[0]
    q = np.array([[0.3, 0.0], [0.0, -0.3]])  # on the hole: the pressure pushes into the plate
    # (the stress -p I, whose sigma n takes the normals of the mesh it is integrated on: n = -q / R here)
    assert hole.value is None
    assert np.allclose(np.einsum("nij,nj->ni", hole.stress(q), -q / 0.3), [[0.02, 0.0], [0.0, -0.02]], atol=1e-14)
    assert right.value is None and np.allclose(right.stress(np.array([[2.0, 0.1]]))[0] @ [1.0, 0.0], [0.05, 0.0])
    sol = cl.solve(scene)
    assert sol.model.cracks[0].tips == (True, True)
    # Force balance: the box reactions carry the pressure-free x load, so just check finiteness
    # and that both tips have SIFs.
    assert len(sol.stress_intensity_factors(0)) == 2


def test_body_force_matches_subcell_integration():
    """int f . phi_j for Heaviside enrichment against an independent
    integration over the linear sub-triangles."""
    from cracklip import _cracklip
    from cracklip.model.loads import assemble_body_force
    mesh = cl.create_square(0.25)
    scene = cl.Scene(mesh, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-0.55, 0.03], [0.45, 0.1]])],
                     dirichlet=[cl.Dirichlet("bottom")], options=cl.Options(enrichment="none"))
    m = cl.create_model(scene)
    f = np.array([0.3, -1.0])
    b = assemble_body_force(m, f)
    assert np.sum(b[0:2 * m.layout.num_std_nodes:2]) == pytest.approx(0.3 * 4.0)
    rng = np.random.default_rng(1)
    for _ in range(3):
        u = rng.standard_normal(m.num_dofs)
        sub = _cracklip.compute_subcell_fields(m.x, m.cells, m.layout, m.geometries, u, 1.0, 0.3)
        P, D = sub["points"].reshape(-1, 3, 2), sub["displacement"].reshape(-1, 3, 2)
        e1, e2 = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]
        area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
        assert b @ u == pytest.approx(np.sum(area * (D.mean(axis=1) @ f)), rel=1e-12)


def test_body_force_column_under_gravity():
    """A column on rollers under its own weight, nu = 0, with a vertical crack:
    exactly sigma_yy = rho g (y - H), sigma_xx = sigma_xy = 0, so the crack
    carries no load; the top settles by rho g H^2 / (2 E) and the discrete
    opening (P1 cannot hold the quadratic field) shrinks with h."""
    def opening(h):
        doc = {"mesh": {"domain": [0.0, 0.0, 1.0, 2.0], "h": h},
               "material": {"E": 1.0, "nu": 0.0},
               "cracks": [{"points": [[0.5, 0.6], [0.5, 1.4]]}],
               "dirichlet": [{"tag": "bottom", "component": "y"}, {"point": [0.0, 0.0], "component": "x"}],
               "loads": {"body_force": [0.0, -0.01]},
               "options": {"radius": 0.2}}
        sol = cl.solve(build_scene(doc).scene)
        u = np.abs(sol.standard_displacement).max()
        assert u == pytest.approx(0.01 * 2.0 ** 2 / 2, rel=1e-3)
        return np.abs(sol.crack_opening(0)["normal"]).max() / u
    # (Sampled on every cell the crack crosses, the tip cells included:
    # 2.95e-3 at h = 0.2, where the tip cell is 1/4 of the crack.)
    coarse, fine = opening(0.1), opening(0.05)
    assert coarse < 1e-3 and fine < 0.5 * coarse


def test_file_mesh(tmp_path):
    """A gmsh .msh file with named physical curves, path relative to the scene."""
    import gmsh
    from cracklip.scene.mesh import _gmsh
    g = _gmsh()
    gmsh.model.add("file_test")
    occ = gmsh.model.occ
    occ.addRectangle(0.0, 0.0, 0.0, 2.0, 1.0)
    occ.synchronize()
    gmsh.model.addPhysicalGroup(2, [1], 1)
    curves = {}
    for _, c in gmsh.model.getEntities(1):
        x, y, _ = occ.getCenterOfMass(1, c)
        curves.setdefault("fixed" if x < 1e-9 else "loaded" if x > 2 - 1e-9 else "free", []).append(c)
    for i, (name, cs) in enumerate(curves.items(), start=1):
        gmsh.model.addPhysicalGroup(1, cs, i)
        gmsh.model.setPhysicalName(1, i, name)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.2)
    gmsh.model.mesh.generate(2)
    (tmp_path / "meshes").mkdir()
    gmsh.write(str(tmp_path / "meshes" / "part.msh"))
    gmsh.model.remove()
    assert g is gmsh
    scene = tmp_path / "part.toml"
    scene.write_text('[mesh]\nkind = "file"\npath = "meshes/part.msh"\n[material]\nE = 1.0\nnu = 0.3\n'
                     '[[cracks]]\npoints = [[1.0, -0.5], [1.0, 0.5]]\n'
                     '[[dirichlet]]\ntag = "fixed"\n[[loads.tractions]]\ntag = "loaded"\nvalue = [0.01, 0.0]\n')
    sf = load_scene_file(scene)
    assert set(sf.scene.mesh.tags) == {"fixed", "loaded", "free"}
    sol = cl.solve(sf.scene)
    assert sol.crack_opening(0)["normal"].max() > 0.0
    with pytest.raises(cl.InputError, match=r"mesh\.h applies to mesh kind"):
        load_scene_file(scene, overrides=["mesh.h=0.1"])
    with pytest.raises(cl.MeshError, match=r"mesh\.path 'nowhere\.msh': no such file .*nowhere\.msh \(a relative "
                                           r"path is read from the scene file's folder, "):
        load_scene_file(scene, overrides=["mesh.path=nowhere.msh"])


def test_scene_file_module_documents_every_key():
    for k in SCHEMA:
        assert k.meaning and k.type
        assert scene_file.KEYS[k.path] is k


def test_loads_scenes(tmp_path):
    """The scenes of issue 14's loads at their small sizes, against the
    references in their comments (looser than at the files' own sizes)."""
    results, crack, sif = run_scene("pressurised_crack", tmp_path / "p")
    check_common(tmp_path / "p", results, crack, sif)
    assert results["model"]["cracks"][0]["lip_pressure"] == 1.0
    assert column(sif, "K_I") == pytest.approx(1.7971, rel=0.02)
    assert np.all(column(crack, "gap") > 0.0)
    results, crack, sif = run_scene("edge_notch_bending", tmp_path / "b")
    assert column(sif, "K_I")[0] == pytest.approx(1.0892, rel=0.03)
    results, crack, sif = run_scene("three_point_bending", tmp_path / "t")
    assert column(sif, "K_I")[0] == pytest.approx(10.650, rel=0.03)
    assert any("force [0.0, -1.0] at node (0, 1)" in n for n in results["boundary_conditions_and_loads"])
    results, crack, sif = run_scene("residual_stress", tmp_path / "r")
    c = results["cracks"][0]
    assert 0.3 < c["closed_fraction"] < 0.8 and c["pressure"]["min"] >= -1e-12
    closed = column(crack, "closed") == 1
    assert column(crack, "x")[closed].max() < column(crack, "x")[~closed].min()  # the mouth is closed
    assert column(sif, "K_I")[0] > 0.0


def test_pictures(tmp_path, monkeypatch):
    """Issue 14 item 7 and the pictures that show the crack: stress.png's
    colour bar names the input's units (not "units of E") and its scale is
    clipped below the tip singularity; deformed.png zooms on a crack much
    smaller than the part, with its own scale."""
    from cracklip.io import pictures
    figures = {}
    monkeypatch.setattr(pictures, "save_png", lambda fig, path, axes=None: figures.__setitem__(path.name, fig))
    run_scene("pressurised_crack", tmp_path)
    stress = figures["stress.png"]
    bar = stress.axes[-1]
    assert "the input's stress units" in bar.get_ylabel() and "units of E" not in bar.get_ylabel()
    coll = stress.axes[0].collections[0]
    lo, hi = coll.get_clim()
    assert lo == -hi and hi < 0.5 * np.abs(coll.get_array()).max()
    deformed = figures["deformed.png"]
    full, zoom = deformed.axes[0], deformed.axes[1]
    assert "around the cracks" in zoom.get_title()
    assert np.ptp(zoom.get_xlim()) < 0.25 * np.ptp(full.get_xlim())
    scale = lambda title: float(title.rsplit("x", 1)[1])  # noqa: E731
    assert scale(zoom.get_title()) < scale(full.get_title())


def test_check_quiet_prints_nothing(capsys):
    """Issue 14 item 7: check --quiet printed the summary."""
    assert cli.main(["check", str(SCENES / "westergaard.toml"), "--set", "mesh.h=0.1", "--quiet"]) == 0
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err == ""
    # Warnings still reach stderr.
    assert cli.main(["check", str(SCENES / "westergaard.toml"), "--set", "mesh.h=0.2", "--quiet"]) == 0
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.startswith("cracklip: warning: ")
    assert cli.main(["check", str(SCENES / "westergaard.toml"), "--set", "mesh.h=0.2"]) == 0
    out = capsys.readouterr().out
    assert "valid" in out and "tip (0, 0): element size" in out and "SIF domains of radius" in out


def test_create_rectangle_documents_its_refinement():
    """Issue 14 item 7: the docstring said the size was h_near within the radius."""
    doc = " ".join(cl.create_rectangle.__doc__.split())
    assert "within 4 h_near" in doc and "never faster than 0.25" in doc


def test_frictional_scene(tmp_path):
    """Clamp, shear up, shear removed with mu = 0.3: the locked-in K_II after
    unloading is 0.3 / 0.4 of the sheared one (the infinite plate's ratio;
    the plate's width factor cancels), every step in the outputs."""
    results, crack, sif = run_scene("frictional_crack", tmp_path)
    check_common(tmp_path, results, crack, sif)
    names = [s["name"] for s in results["steps"]]
    assert names == ["clamp", "shear up", "shear removed"]
    k = [np.mean([r["K_II"] for r in s["sifs"]]) for s in results["steps"]]
    assert abs(k[0]) < 1e-8 and k[2] / k[1] == pytest.approx(0.75, rel=0.01)
    assert results["steps"][1]["contact"]["states"]["slip"] == results["contact"]["multipliers"]
    assert {r["step"] for r in crack} == {"0", "1", "2"}
