"""Issue 14's reproductions: every K right to 1 % or loudly flagged.

Plate A (conftest.plate_scene): [-1, 1] x [-3, 3], sigma_yy = 1 on top and
bottom, h = 0.1, tip_h = 0.0125. References: Tada's finite-width factors
(conftest.tada_*), converged by cracklip to 1e-3 on finer meshes.
"""
import json
import pathlib
import sys

import cracklip as cl
import numpy as np
import pytest
from cracklip import cli
from cracklip.model.tip_regions import tip_domains
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from handbook import plate_scene, tada_centre_crack, tada_edge_crack  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
WESTERGAARD = ROOT / "demos" / "scenes" / "westergaard.toml"
K_CENTRE = {0.1: tada_centre_crack(0.1) * np.sqrt(np.pi * 0.1), 0.5: tada_centre_crack(0.5) * np.sqrt(np.pi * 0.5)}
K_EDGE = tada_edge_crack(0.3) * np.sqrt(np.pi * 0.3)


def codes(warnings):
    return [w.code for w in warnings]


def test_references():
    """The issue's numbers: 0.5638, 1.4867, 1.607."""
    assert K_CENTRE[0.1] == pytest.approx(0.5638, abs=1e-4)
    assert K_CENTRE[0.5] == pytest.approx(1.4867, abs=1e-4)
    assert K_EDGE == pytest.approx(1.607, abs=1e-3)


def test_refinement_reaches_tip_h(capsys):
    """Reproduction 1: tip_h = 0.005 with h = 0.2 and tip_radius 0.1 gave a
    0.115 element at the tip (149 nodes); check --json reports the size."""
    args = ["check", str(WESTERGAARD), "--set", "mesh.h=0.2", "--set", "mesh.tip_h=0.005",
            "--set", "mesh.tip_radius=0.1", "--json"]
    assert cli.main(args) == 0
    out = json.loads(capsys.readouterr().out)
    (size,) = out["model"]["cracks"][0]["tip_element_size"]
    assert size <= 1.2 * 0.005
    assert out["model"]["nodes"] > 500
    assert not [w for w in out["warnings"] if w["code"] == "refinement"]


def test_refinement_in_a_large_plate():
    """Reproduction 1: inclined centre crack (half length 1, 30 degrees) in
    [-20, 20]^2, h = 1, tip_h = 0.025, tip_radius = 0.5: K_I was 0.62 / 0.76
    instead of sigma cos^2(30) sqrt(pi) = 1.329 (plate 40 a wide: 1e-3 from
    the infinite plate)."""
    t = np.array([np.cos(np.pi / 6), np.sin(np.pi / 6)])
    scene = plate_scene([-t, t], h=1.0, tip_h=0.025, tip_radius=0.5, radius=0.1, domain=(-20, -20, 20, 20))
    sol = cl.solve(scene)
    exact_I, exact_II = 0.75 * np.sqrt(np.pi), np.sqrt(3) / 4 * np.sqrt(np.pi)
    for k in sol.stress_intensity_factors(0):
        assert k["element_size"] <= 1.2 * 0.025
        assert k["K_I"] == pytest.approx(exact_I, rel=0.01)
        assert abs(k["K_II"]) == pytest.approx(exact_II, rel=0.01)
    # K is 0.4-0.5 % low here, and the elements grow to 0.6 within two crack
    # lengths of the tips (fewer than 7.5 per crack length): the tip_region
    # rule (issue 26) says so; nothing else is warned about.
    assert {w.code for w in sol.warnings} == {"tip_region"}


def test_default_radius_stays_clear_of_the_other_tip():
    """Reproduction 2: crack (-0.1, 0)-(0.1, 0), enrichment radius 0.03: the
    old default (4 mean edges of the whole mesh, 0.38) reached the other tip
    and gave K_I = 1.01 / 0.93 instead of 0.5638."""
    sol = cl.solve(plate_scene([[-0.1, 0.0], [0.1, 0.0]], radius=0.03))
    ks = sol.stress_intensity_factors(0)
    for k in ks:
        assert k["K_I"] == pytest.approx(K_CENTRE[0.1], rel=0.01)
        assert k["radius"] < 0.2 and k["radius"] == pytest.approx(6 * k["element_size"])
        assert k["K_I_spread"] < 0.01 * k["K_I"] and k["domain_clear"]


@pytest.mark.parametrize("radius", [0.55, 0.9])
def test_requested_radius_is_clipped_and_reported(radius, caplog):
    """Reproduction 3: sif_radius 0.55 / 0.9 around the tips of the crack
    (-0.5, 0)-(0.5, 0) left the part (1.330 / 0.880 instead of 1.4867)."""
    scene = plate_scene([[-0.5, 0.0], [0.5, 0.0]], sif_radius=radius)
    sol = cl.solve(scene)
    for k in sol.stress_intensity_factors(0):
        assert k["K_I"] == pytest.approx(K_CENTRE[0.5], rel=0.01)
        assert k["radius"] < 0.5 and k["limited_by"] == "the boundary of the part"
    messages = [w.message for w in sol.warnings if w.code == "sif_domain"]
    assert len(messages) == 2 and all(f"sif_radius {radius:g} would reach the boundary" in m for m in messages)


def test_edge_crack_radius_beyond_the_mouth():
    """Reproduction 3: edge crack (0, 0)-(0.3, 0) in [0, 1] x [-3, 3] with
    sif_radius 0.35 (> the crack) gave 1.584 instead of 1.607."""
    scene = plate_scene([[0.0, 0.0], [0.3, 0.0]], domain=(0.0, -3.0, 1.0, 3.0), sif_radius=0.35)
    sol = cl.solve(scene)
    (k,) = sol.stress_intensity_factors(0)
    assert k["K_I"] == pytest.approx(K_EDGE, rel=0.01)
    assert k["radius"] < 0.3 and "sif_domain" in codes(sol.warnings)
    # The default domain (6 elements) fits.
    (k0,) = cl.solve(plate_scene([[0.0, 0.0], [0.3, 0.0]], domain=(0.0, -3.0, 1.0, 3.0))).stress_intensity_factors(0)
    assert k0["K_I"] == pytest.approx(K_EDGE, rel=0.01) and k0["limited_by"] is None


def test_api_and_cli_agree(tmp_path):
    """Reproduction 4: load_scene_file(p).scene dropped options.sif_radius, so
    Python gave 1.011 and the CLI 0.553 on the same file."""
    scene = tmp_path / "short.toml"
    scene.write_text("""
[mesh]
domain = [-1.0, -3.0, 1.0, 3.0]
h = 0.1
tip_h = 0.0125
[material]
E = 1.0
nu = 0.3
[[cracks]]
points = [[-0.1, 0.0], [0.1, 0.0]]
[[dirichlet]]
point = [-1.0, -3.0]
[[dirichlet]]
point = [1.0, -3.0]
component = "y"
[[loads.tractions]]
tag = "top"
value = [0.0, 1.0]
[[loads.tractions]]
tag = "bottom"
value = [0.0, -1.0]
[options]
radius = 0.03
sif_radius = 0.05
""")
    sf = cl.load_scene_file(scene)
    assert sf.scene.options.sif_radius == 0.05
    python = cl.solve(sf.scene).stress_intensity_factors(0)
    assert cli.main(["run", str(scene), "--out", str(tmp_path / "o"), "--quiet", "--set", "outputs.png=false",
                     "--set", "outputs.vtu=false"]) == 0
    results = json.loads((tmp_path / "o" / "results.json").read_text())
    for p, c in zip(python, results["sifs"]):
        assert set(p) == set(c)
        assert all(p[key] == pytest.approx(c[key]) for key in ("K_I", "K_II", "K_I_spread", "radius", "x", "y"))
        assert p["radius"] == pytest.approx(0.05) and p["K_I"] == pytest.approx(K_CENTRE[0.1], rel=0.01)


def test_tip_one_element_from_the_boundary():
    """Reproduction 5: an edge crack written as (0.001, 0)-(0.3, 0) is an
    interior crack with a 0.001 ligament the mesh cannot hold (K_I = 1.14
    instead of 1.60): warned, naming the cause and the fix."""
    sol = cl.solve(plate_scene([[0.001, 0.0], [0.3, 0.0]], domain=(0.0, -3.0, 1.0, 3.0)))
    near = [w for w in sol.warnings if w.code == "tip_near_boundary"]
    assert len(near) == 1 and near[0].tip == 0
    assert "put its end point on or beyond the boundary" in near[0].message
    k0 = sol.stress_intensity_factors(0)[0]
    assert not k0["domain_clear"] and k0["limited_by"] == "the boundary of the part"
    assert any("NOT reliable" in w.message for w in sol.warnings if w.tip == 0)


def test_kinks_and_other_cracks_limit_the_domain():
    """A domain must not hold a kink of its crack or another crack."""
    scene = plate_scene([[-0.5, 0.0], [0.0, 0.0], [0.3, 0.1]])
    model = cl.create_model(scene)
    d = tip_domains(model, 0)[1]  # at (0.3, 0.1), the kink at (0, 0)
    kink = np.hypot(0.3, 0.1)
    assert d.clearance == pytest.approx(kink) and d.obstacle == "the kink of crack 'crack 0' at (0, 0)"
    assert d.admissible < kink
    two = plate_scene([[-0.5, 0.0], [0.5, 0.0]])
    two.cracks.append(cl.Crack([[-0.3, 0.25], [0.3, 0.25]], name="upper"))
    model = cl.create_model(two)
    d = tip_domains(model, 0, 0.45)[1]  # at (0.5, 0): the upper crack's tip is 0.32 away
    assert d.obstacle == "tip 1 of crack 'upper' at (0.3, 0.25)"
    assert d.clearance == pytest.approx(np.hypot(0.2, 0.25)) and d.radius < d.clearance
    assert "sif_radius 0.45 would reach tip 1 of crack 'upper'" in d.warnings[0]


def test_westergaard_spread_is_small():
    """Acceptance 2: on demos/scenes/westergaard.toml at h = 0.0125 the K of
    the three domains agree to better than 1e-3 (K_I = 1)."""
    sf = cl.load_scene_file(WESTERGAARD, overrides=["mesh.h=0.0125"])
    (k,) = cl.solve(sf.scene).stress_intensity_factors(0)
    assert k["K_I_spread"] < 1e-3 and k["K_II_spread"] < 1e-3
    assert k["K_I"] == pytest.approx(1.0, abs=1e-3)
    assert len(k["radii"]) == 3 and k["radii"][0] < k["radii"][1] < k["radii"][2] == k["radius"]


def test_spread_warning_on_an_unresolved_tip():
    """Tips whose field is not resolved (no tip enrichment, 4 elements on
    the crack): K varies with the domain by 6 .. 85 % of the K scale, and
    each such tip is flagged: by the spread warning where its SIF domains are
    clear, else by the domain warning (no domain of one element fits). Which
    tip is which is the mesh's: on gmsh's default mesh one of each, with
    Mesh.RandomSeed = 2 two spread warnings, with 3 two domain warnings.
    Besides, the resolution and the enrichment are warned about."""
    scene = plate_scene([[-0.5, 0.0], [0.5, 0.0]], h=0.25, tip_h=0.25, enrichment="none", radius=0.0)
    sol = cl.solve(scene)
    ks = sol.stress_intensity_factors(0)
    scale = max(abs(k["K_I"]) for k in ks)
    unresolved = [max(k["K_I_spread"], k["K_II_spread"]) > 0.01 * scale for k in ks]  # sif.SPREAD_WARNING
    assert any(unresolved)
    for k, bad in zip(ks, unresolved):
        said = {w.code for w in sol.warnings if w.message.startswith(f"tip {k['tip']} of crack")}
        assert ("sif_spread" in said) == (bad and k["domain_clear"]), (k, said)
        assert not bad or k["domain_clear"] or "sif_domain" in said, (k, said)
    for w in sol.warnings:
        assert w.code != "sif_spread" or "varies with the SIF domain" in w.message
    assert {"tip_resolution", "tip_enrichment", "sif_domain"} <= set(codes(sol.warnings))


def test_heaviside_only_tips_are_flagged():
    """Without tip enrichment K is 5 % low here (1.412 vs 1.4867) while its
    domains agree to 0.1 %: the enrichment warning is what flags it."""
    sol = cl.solve(plate_scene([[-0.5, 0.0], [0.5, 0.0]], h=0.2, tip_h=0.05, enrichment="none", radius=0.0))
    ks = sol.stress_intensity_factors(0)
    assert all(k["K_I"] < 0.97 * K_CENTRE[0.5] and k["K_I_spread"] < 0.002 * k["K_I"] for k in ks)
    assert codes(sol.warnings).count("tip_enrichment") == 2
