"""A circular-arc crack (cracks[].arc) against its closed form.

An arc of radius R and half-angle alpha under equibiaxial remote tension S:
K_I = S sqrt(pi R sin(alpha)) cos(alpha / 2) / (1 + sin^2(alpha / 2)),
K_II = S sqrt(pi R sin(alpha)) sin(alpha / 2) / (1 + sin^2(alpha / 2))
(Sih, Paris and Erdogan 1962; Tada's handbook, the circular-arc crack). The
inscribed polyline the arc used to be ends along a chord, half a segment's
angle off the tangent: with the default 24 segments over 90 degrees K_II
was 4.1 % and K_I 1.8 % off, on any mesh (48 segments: 2.2 %, 0.8 %; 192:
0.7 %, 0.05 %), while the error estimate said 0.5 %.
"""
import json
import math

import numpy as np
from cracklip import cli

SCENE = """
[mesh]
domain = [-50.0, -50.0, 50.0, 50.0]
h = 5.0
tip_h = 0.01
[[mesh.refine]]
point = [0.0, 1.0]
h = 0.04
radius = 4.0
[material]
E = 1.0
nu = 0.3
[[cracks]]
arc = { center = [0.0, 0.0], radius = 1.0, angles = [45.0, 135.0] }
[[dirichlet]]
point = [-50.0, -50.0]
[[dirichlet]]
point = [50.0, -50.0]
component = "y"
[[dirichlet]]
point = [-50.0, 50.0]
component = "x"
""" + "".join(f"""
[[loads.tractions]]
tag = "{tag}"
stress = [1.0, 1.0, 0.0]
""" for tag in ("top", "bottom", "left", "right")) + """
[options]
radius = 0.1
"""


def test_arc_polyline_ends_along_the_tangents():
    from cracklip.scene.crack import arc_polyline
    t0, t1 = math.radians(45.0), math.radians(135.0)
    pts = arc_polyline([0.0, 0.0], 1.0, t0, t1, 24)
    assert len(pts) == 25 and np.allclose(pts[[0, -1]], [[math.cos(t0), math.sin(t0)], [math.cos(t1), math.sin(t1)]])
    first, last = pts[1] - pts[0], pts[-1] - pts[-2]
    assert np.allclose(first / np.linalg.norm(first), [-math.sin(t0), math.cos(t0)], atol=1e-14)
    assert np.allclose(last / np.linalg.norm(last), [-math.sin(t1), math.cos(t1)], atol=1e-14)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    assert abs(seg[0] / seg[2] - 1.0) < 2e-3      # the tip segments about as long as the others: tan d, 2 tan(d / 2)
    assert np.linalg.norm(pts, axis=1).max() < 1.0 + 2.1e-3     # R (sec(d / 2) - 1), d = 3.6 deg


def test_arc_crack_k_against_the_closed_form(tmp_path):
    (tmp_path / "arc.toml").write_text(SCENE)
    out = tmp_path / "out"
    assert cli.main(["run", str(tmp_path / "arc.toml"), "--out", str(out), "--quiet", "--accuracy", "0.01"]) == 0
    alpha = math.radians(45.0)
    f = math.sqrt(math.pi * math.sin(alpha)) / (1.0 + math.sin(alpha / 2) ** 2)
    exact = (f * math.cos(alpha / 2), f * math.sin(alpha / 2))     # 1.2011, 0.4975
    scale = math.hypot(*exact)
    for row in json.loads((out / "results.json").read_text())["sifs"]:
        K_I, K_II = row["K_I"], abs(row["K_II"])
        # Measured: K_I -0.18 %, K_II -0.46 % (before: +1.8 %, -4.1 %); the estimate brackets both.
        assert abs(K_I - exact[0]) <= min(row["K_I_error"], 0.01 * scale)
        assert abs(K_II - exact[1]) <= min(row["K_II_error"], 0.01 * scale)
