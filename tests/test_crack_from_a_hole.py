"""A crack whose end lies exactly on a hole's circle (issue: audit of 2D K).

The hole's facets are chords: a point of the true circle lies up to a
sagitta inside the meshed part. The end was a tip on meshes where it is not
a vertex (at 1e-9 of the part's size) and the mouth of an edge crack where
it is: the error estimate's finer mesh then had a second tip a sagitta from
the hole, its K (1.21) was compared with the coarse mesh's real tip (2.58:
"110 % of the K scale"), and --accuracy stopped with a KeyError traceback.
"""
import json
import math

import numpy as np
from cracklip import cli
from cracklip.io.scene_file import load_scene_file
from cracklip.model.boundary import boundary_segments, nearest_boundary_point
from cracklip.model.cracks.curve import tip_flags

SCENE = """
[mesh]
kind = "plate_with_hole"
domain = [-20.0, -20.0, 20.0, 20.0]
hole_radius = 1.0
h = 2.0
tip_h = 0.05
[material]
E = 1.0
nu = 0.3
[[cracks]]
points = [[{x0}, {y0}], [{x1}, {y1}]]
[[dirichlet]]
point = [-20.0, -20.0]
[[dirichlet]]
point = [20.0, -20.0]
component = "y"
[[loads.tractions]]
tag = "top"
value = [0.0, 1.0]
[[loads.tractions]]
tag = "bottom"
value = [0.0, -1.0]
[options]
radius = 0.2
"""


def _scene(tmp_path, angle_deg: float, name="hole.toml"):
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    path = tmp_path / name
    path.write_text(SCENE.format(x0=c, y0=s, x1=2 * c, y1=2 * s))
    return path


def test_end_on_the_circle_is_the_mouth_of_an_edge_crack(tmp_path):
    scene = load_scene_file(_scene(tmp_path, 7.0)).scene
    a, b = boundary_segments(scene.mesh)
    start = scene.cracks[0].points[0]
    # Not a mesh vertex: the point lies inside the meshed part, off the chord.
    assert nearest_boundary_point(start, a, b)[1] > 1e-9 * 40.0
    assert tip_flags(scene, scene.cracks[0]) == (False, True)   # before: (True, True)


def test_a_tip_near_a_hole_stays_a_tip(tmp_path):
    """An end a tenth of the radius off the hole is a tip, as it was."""
    path = tmp_path / "near.toml"
    path.write_text(SCENE.format(x0=1.1, y0=0.0, x1=2.0, y1=0.0))
    scene = load_scene_file(path).scene
    assert tip_flags(scene, scene.cracks[0]) == (True, True)


def test_estimate_and_accuracy_of_a_crack_from_the_hole_edge(tmp_path):
    path = _scene(tmp_path, 7.0)
    out = tmp_path / "out"
    assert cli.main(["run", str(path), "--out", str(out), "--quiet", "--accuracy", "0.01"]) == 0
    sifs = json.loads((out / "results.json").read_text())["sifs"]
    assert len(sifs) == 1                                       # one tip, at 2 R
    levels = np.array(sifs[0]["K_I_levels"])
    # Tada / Bowie: one crack a = R at a hole, F about 1.34 (infinite plate): K_I about 2.37.
    assert np.all(np.abs(levels / levels[-1] - 1.0) < 0.05)
    assert sifs[0]["K_I_error"] < 0.01 * abs(sifs[0]["K_I"])


def test_the_estimate_compares_the_same_tip_on_both_meshes():
    """A tip's index counts the crack's ends that are tips: where a mesh makes
    one more end a tip, index 0 is another point. The estimate took K of the
    finer mesh's tip 0 (here the end at (1, 0), K 0.5) for the coarse mesh's
    tip 0 at (2, 0): an error of 0.5 instead of 0.02."""
    import pytest
    from cracklip.analysis.accuracy import Level, carried
    from cracklip.errors import MeshError

    def row(tip, x, K):
        return {"crack": 0, "tip": tip, "position": [x, 0.0], "K_I": K, "K_II": 0.0}

    coarse = [row(0, 2.0, 1.0)]
    fine = Level(0.5, 100, 0.1, [[row(0, 1.0, 0.5), row(1, 2.0, 1.02)]], False, {}, {})
    assert carried(fine, 0, 0, coarse, ("K_I", "K_II"))[0, 0] == 1.02    # before: 0.5
    other = Level(0.5, 100, 0.1, [[row(0, 1.0, 0.5)]], False, {}, {})
    with pytest.raises(MeshError, match=r"its end \(2, 0\) is a tip on one of the error estimate's meshes"):
        carried(other, 0, 0, coarse, ("K_I", "K_II"))
