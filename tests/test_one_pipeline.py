"""One pipeline for 2D and 3D (issue 35): the words a user meets say what
the program does in both dimensions, `run` and `check` agree on a 3D
part's files, and a 2D tip and a 3D front point share one SIF row schema.

The stale sentences of the second pipeline are looked for where a user
meets them: `--help`, `grow`'s words on a 3D part, the material and
rigid-motion messages of a 3D part, the warnings of a clipped 3D SIF
domain, and the docs."""
import json
import pathlib
import re

import pytest

import cracklip as cl
from cracklip import cli
from cracklip.fracture.sif import SIF_KEYS
from cracklip.io.scene_file import build_scene, parse_settings

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENES = ROOT / "demos" / "scenes"

#: Sentences of the second pipeline that must not come back.
STALE = ["2D X-FEM cracks", "3D fronts come first", "sifs` stays empty", "stays empty until", "FrontRefinement h_front",
         "use a SurfaceCrack", "Solution3D", "create_model_3d", "io/front_outputs.py", "outputs_3d",
         "scene_file_3d"]


def _penny_doc(**tables):
    import tomllib
    doc = tomllib.loads((SCENES / "penny_crack.toml").read_text())
    doc["mesh"].update({"h": 2.0, "tip_h": 0.3, "crack_h": 0.0})
    doc.update(tables)
    return doc


def test_help_names_both_dimensions(capsys):
    text = cli.build_parser().format_help()
    assert not any(s in text for s in STALE), text
    assert "planar parts" in text and "solids" in text


def test_grow_on_a_3d_part_asks_for_a_growth_law():
    """3D fronts grow (issue 37) by a law, each point by its own rate: a 3D
    [growth] without one is told the scene keys that give it, not that
    growth is unavailable; with a Paris law it is accepted."""
    with pytest.raises(cl.InputError) as e:
        parse_settings(_penny_doc(growth={"da": 0.1}))
    msg = str(e.value)
    assert "is 3D" in msg and "growth.paris_C" in msg and "[material.fatigue]" in msg, msg
    assert "not available" not in msg and "come first" not in msg, msg
    parse_settings(_penny_doc(growth={"da": 0.1, "paris_C": 1.0, "paris_m": 3.0, "R": 0.0}))


def test_3d_material_and_rigid_motion_messages():
    """A 3D part's bad Poisson's ratio does not speak of plane strain only,
    and a 3D part without supports is told about u_z."""
    parse_settings(_penny_doc())  # valid as it is
    with pytest.raises(cl.MaterialError) as e:
        build_scene(_penny_doc(material={"E": 1.0, "nu": 0.5}))
    assert "3D part" in str(e.value), str(e.value)
    doc = _penny_doc()
    del doc["dirichlet"]
    with pytest.raises(cl.BoundaryConditionError) as e:
        parse_settings(doc)
    assert "u_z" in str(e.value) and "fix at least u_x and u_y somewhere" not in str(e.value)


def test_docs_and_sources_hold_no_stale_sentence():
    texts = {p: p.read_text() for p in [ROOT / "README.md", *(ROOT / "docs").rglob("*.md"),
                                        *(ROOT / "python" / "cracklip").rglob("*.py")]}
    for path, text in texts.items():
        for s in STALE:
            assert s not in text, f"{path.relative_to(ROOT)} says {s!r}"


def test_one_create_model_and_no_second_pipeline():
    """One public create_model; at most two module pairs X.py / X_3d.py,
    each saying in its docstring why the geometry makes it a pair."""
    assert cl.create_model.__module__ == "cracklip.model.model"
    package = ROOT / "python" / "cracklip"
    pairs = [p for p in package.rglob("*_3d.py") if p.with_name(p.name.replace("_3d.py", ".py")).exists()]
    assert len(pairs) <= 2, pairs
    import ast
    for p in pairs:
        doc = ast.get_docstring(ast.parse(p.read_text())) or ""
        assert "differ" in doc, f"{p.relative_to(ROOT)}: its docstring does not say why it is a pair"


def test_3d_run_and_check_agree_and_share_the_sif_schema(tmp_path, capsys):
    """`check` lists every file `run` writes on a 3D part (front.csv,
    front_sifs.png, front_sifs.vtu included); `run` prints K along the
    front (smallest and largest and where); every SIF row of a 3D front and
    of a 2D tip has the keys of SIF_KEYS; a clipped domain's warning gives
    a distance >= 0; K has its own timed phase."""
    from test_scenes_3d import SMALL_3D
    scene = SCENES / "surface_crack_plate.toml"
    sets = [a for o in SMALL_3D["surface_crack_plate"] for a in ("--set", o)]
    assert cli.main(["check", str(scene), *sets]) == 0
    listed = re.search(r"run writes: (.*)", capsys.readouterr().out).group(1).split(", ")
    assert cli.main(["run", str(scene), "--out", str(tmp_path), *sets]) == 0
    out = capsys.readouterr()
    results = json.loads((tmp_path / "results.json").read_text())
    assert sorted(listed) == sorted(results["files"])
    assert {"front.csv", "front_sifs.png", "front_sifs.vtu"} <= set(listed)
    assert "K along its front at" in out.out and re.search(r"K_I: min [-0-9.e]+ .* at point \d+ .*, max", out.out)
    assert results["dimension"] == 3 and results["sifs"]
    for r in results["sifs"]:
        assert list(r)[:len(SIF_KEYS)] == list(SIF_KEYS)
        assert r["K_III"] is not None and r["tip"] is None and len(r["frame"]) == 3
    assert results["timings"]["sif"] > 0.0
    for w in results["warnings"]:
        for d in re.findall(r"\(([-0-9.e+]+) away", w["message"]):
            assert float(d) >= 0.0, w["message"]
    # A 2D tip: the same keys, a front of one point.
    sf = build_scene({"mesh": {"h": 0.25}, "material": {"E": 1.0, "nu": 0.3},
                      "cracks": [{"points": [[-1.0, 0.0], [0.0, 0.0]]}], "dirichlet": [{"tag": "bottom"}],
                      "loads": {"tractions": [{"tag": "top", "value": [0.0, 1.0]}]}})
    rows = cl.solve(sf.scene).stress_intensity_factors(None)
    assert [list(r)[:len(SIF_KEYS)] for r in rows] == [list(SIF_KEYS)]
    r = rows[0]
    assert r["point"] == r["tip"] == r["piece"] == 0 and r["s"] == 0.0 and r["K_III"] is None
    assert r["position"] == [r["x"], r["y"]] and r["frame"] == [r["direction"], r["normal"]]
