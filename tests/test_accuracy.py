"""Issue 26: K's discretisation error, estimated and refined to a target, and
the warning of a region too coarse for the crack.

References: Tada's finite-width factors (centre crack 0.1 %, edge notch
tension 0.5 %, bending 0.2 %; demos/handbook.py) and exact fields
(inclined and pressurised Griffith cracks); for the issue's reproductions
independent fine solves, measured once and stated in each test (the
refinement levels of the tests never reach them: they are 4-16 times finer).
"""
import dataclasses
import json
import math
import pathlib
import sys

import cracklip as cl
import pytest
from cracklip import cli
from cracklip.analysis.accuracy import ASSUMED_RATE, SAFETY, Level, estimate, estimate_error
from cracklip.io.scene_file import load_scene_file
from cracklip.model.model import create_model

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENES = ROOT / "demos" / "scenes"
sys.path.insert(0, str(ROOT / "demos"))
import handbook  # noqa: E402

#: C(T) of demos/geometry/ct_specimen.geo, a/W = 0.5, P = 1000 N/mm, W = 50 mm:
#: cracklip at h = W/160, tip_h = 0.025 mm, enrichment radius 0.25 mm gives
#: 1359.35, at h = W/80 with one level (sizes halved within 75 mm) 1359.91:
#: 1359.6 +- 0.3. ASTM E399 (Srawley, 0.5 % for a/W >= 0.2, a pin's bearing
#: load): 1366.0, which the point load on the hole's edge approaches to 0.5 %.
K_CT = 1359.6
#: The disc of demos/scenes/brazilian_disc.toml at h = R/96, tip_h =
#: 0.0625 mm, radius 0.25: K_II = -44.044 and -44.043 at its two tips.
K_DISC = -44.04
#: The crack at a hole of demos/scenes/hole_fatigue.toml, every element size
#: halved 1, 2, 3 times (2e4 .. 3e5 dofs, the geometry meshed anew):
#: 666.60, 670.42, 671.50, rate 1.83, Richardson 671.92.
K_HOLE = 671.9


def e399(a_over_w: float) -> float:
    x = a_over_w
    return (2 + x) * (0.886 + 4.64 * x - 13.32 * x ** 2 + 14.72 * x ** 3 - 5.6 * x ** 4) / (1 - x) ** 1.5


def test_references():
    """The C(T) reference against E399 (its 0.5 % plus the point load)."""
    k = 1000.0 / math.sqrt(50.0) * e399(0.5)
    assert k == pytest.approx(1366.0, abs=0.1)
    assert K_CT == pytest.approx(k, rel=0.006)


def test_estimate_of_a_known_sequence():
    """K_L = 10 - 3 2^(-1.5 L): two levels bound the error (rate 1 assumed),
    three observe the rate 1.5, extrapolate to 10 exactly and give 1.25
    times the true error; a sequence changing direction is not trusted."""
    def level(L: int, k: float) -> Level:
        return Level(2.0 ** -L, 100 * 4 ** L, 0.0, [[{"crack": 0, "tip": 0, "point": 0, "K_I": k, "K_II": 0.0,
                                                      "K_III": None}]])
    K = [10.0 - 3.0 * 2.0 ** (-1.5 * L) for L in range(4)]
    lv = [level(L, k) for L, k in enumerate(K)]
    two = estimate(lv[:2])[(0, 0, 0)]
    assert two["K_I_rate"] is None and ASSUMED_RATE == 1.0
    assert two["K_I_error"] == pytest.approx(K[1] - K[0]) and two["K_I_error"] >= 10.0 - K[1]
    assert estimate(lv[:2], of=0)[(0, 0, 0)]["K_I_error"] == pytest.approx(2 * (K[1] - K[0]))
    three = estimate(lv)[(0, 0, 0)]
    assert three["K_I_rate"] == pytest.approx(1.5)
    assert three["K_I_extrapolated"] == pytest.approx(10.0, abs=1e-12)
    assert three["K_I_error"] == pytest.approx(SAFETY * (10.0 - K[3]))
    zigzag = [level(L, k) for L, k in enumerate([1.0, 1.2, 1.1])]
    assert estimate(zigzag)[(0, 0, 0)]["K_I_rate"] is None


@pytest.mark.parametrize("case", [c for c in handbook.CASES if not c.startswith("crack closed")])
def test_estimate_brackets_the_handbook_error(case):
    """Acceptance 1 (handbook part): at h = W/20 (demos/handbook.py's
    meshes) the estimate of every K is at least its error to the handbook or
    exact value; with options.accuracy = 0.01 K lands within 1 % of it and
    its estimate still brackets the error (measured: docs/guide.md's table)."""
    width, build, (kI, kII), _ = handbook.CASES[case]
    scene = build(width / 20)
    sol = cl.solve(scene)
    estimate_error(scene, sol, cl.solve)
    fine = cl.solve(dataclasses.replace(scene, options=dataclasses.replace(scene.options, accuracy=0.01)))
    assert fine.error_estimate["reached"]
    for coarse, target in ((sol, None), (fine, 0.01)):
        for r in coarse.stress_intensity_factors(0):
            for mode, ref in (("K_I", kI), ("K_II", math.copysign(kII, r["K_II"]))):
                if ref == 0.0:
                    continue
                err = abs(r[mode] - ref)
                assert r[f"{mode}_error"] >= err, (mode, r[mode], ref, r[f"{mode}_error"])
                if target is not None:
                    assert err <= target * abs(kI if abs(kI) >= abs(kII) else kII)


def test_ct_at_w20_warns_and_accuracy_refines():
    """The issue's C(T): W/20, no tip refinement, the default enrichment
    radius: K 4.6 % low (1296.6 against K_CT); the run warns (tip_region
    before the solve, discretisation from the estimate, which brackets the
    error); options.accuracy = 0.01 lands within 1 % of K_CT with an estimate
    that brackets its error and an extrapolated K within 0.2 %."""
    scene = load_scene_file(SCENES / "ct_specimen.toml", ["mesh.tip_h=0.0", "options.radius=0.0"]).scene
    sol = cl.solve(scene)
    estimate_error(scene, sol, cl.solve)
    (r,) = sol.stress_intensity_factors(0)
    assert r["K_I"] == pytest.approx(0.954 * K_CT, rel=0.005)
    assert r["K_I_error"] >= K_CT - r["K_I"]
    codes = {w.code for w in sol.warnings}
    assert {"tip_region", "discretisation"} <= codes
    text = " ".join(w.message for w in sol.warnings if w.code == "discretisation")
    assert "options.accuracy = 0.01" in text
    fine = cl.solve(dataclasses.replace(scene, options=dataclasses.replace(scene.options, accuracy=0.01)))
    (r,) = fine.stress_intensity_factors(0)
    est = fine.error_estimate
    assert est["reached"] and est["refinement_levels"] >= 2 and len(est["dofs"]) == len(est["size_factors"])
    assert abs(r["K_I"] - K_CT) <= 0.01 * K_CT
    assert r["K_I_error"] >= abs(r["K_I"] - K_CT) - 0.3
    assert r["K_I_extrapolated"] == pytest.approx(K_CT, rel=0.002)
    assert not [w for w in fine.warnings if w.code in ("discretisation", "accuracy")]


def test_disc_with_contact_and_friction():
    """The Brazilian disc at h = R/12 (tip_h 0.5 mm): each tip's K_II is
    within 1 % of K_DISC or warned about; with accuracy 0.01 both are within
    1 % of it."""
    sf = load_scene_file(SCENES / "brazilian_disc.toml")
    sol = cl.solve(sf.scene)
    estimate_error(sf.scene, sol, cl.solve)
    warned = {w.message.split(":")[0] for w in sol.warnings if w.code == "discretisation"}
    for r in sol.stress_intensity_factors(0):
        assert abs(r["K_II"] - K_DISC) <= 0.01 * abs(K_DISC) or any(f"tip {r['tip']} " in w for w in warned)
        assert r["K_II_error"] >= abs(r["K_II"] - K_DISC) - 0.01  # (the reference's own +-0.01)
    fine = cl.solve(dataclasses.replace(sf.scene, options=dataclasses.replace(sf.scene.options, accuracy=0.01)))
    for r in fine.stress_intensity_factors(0):
        assert abs(r["K_II"] - K_DISC) <= 0.01 * abs(K_DISC)
        assert abs(r["K_I"]) <= 0.01 * abs(K_DISC)  # closed: K_I = 0


def test_crack_at_a_hole():
    """The crack at a hole, default size growth from the band: K 2.6 % low,
    warned (tip_region and discretisation, the estimate bracketing); with
    accuracy 0.01 within 1 % of K_HOLE."""
    sf = load_scene_file(SCENES / "hole_fatigue.toml")
    sol = cl.solve(sf.scene)
    estimate_error(sf.scene, sol, cl.solve)
    (r,) = sol.stress_intensity_factors(0)
    assert K_HOLE - r["K_I"] > 0.02 * K_HOLE and r["K_I_error"] >= K_HOLE - r["K_I"]
    assert {"tip_region", "discretisation"} <= {w.code for w in sol.warnings}
    fine = cl.solve(dataclasses.replace(sf.scene, options=dataclasses.replace(sf.scene.options, accuracy=0.01)))
    (r,) = fine.stress_intensity_factors(0)
    assert abs(r["K_I"] - K_HOLE) <= 0.01 * K_HOLE and r["K_I_error"] >= abs(r["K_I"] - K_HOLE)


@pytest.mark.parametrize("case", [c for c in handbook.CASES if not c.startswith("crack closed")])
def test_tip_region_rule_quiet_on_converged_handbook_meshes(case):
    """The rule (model.checks, tip_region) stays quiet at h = W/40, where
    every handbook K is within 0.33 % of its reference (demos/handbook.py)."""
    width, build, _, _ = handbook.CASES[case]
    model = create_model(build(width / 40))
    assert not [w for w in model.warnings if w.code == "tip_region"]


@pytest.mark.parametrize("name, overrides", [("ct_specimen", ["mesh.tip_h=0.0", "options.radius=0.0"]),
                                             ("brazilian_disc", []), ("hole_fatigue", [])])
def test_tip_region_rule_fires_on_the_coarse_cases(name, overrides):
    """...and fires before any solve on the issue's coarse cases: the C(T) at
    W/20 (4.6 % low), the disc at R/12 (up to 0.7 % low), the crack at a hole
    (2.6 % low); the message names the cause and the fix."""
    model = create_model(load_scene_file(SCENES / f"{name}.toml", overrides).scene)
    warnings = [w for w in model.warnings if w.code == "tip_region"]
    assert warnings and all("options.accuracy = 0.01" in w.message for w in warnings)


def test_accuracy_not_reached_is_warned():
    """A target below what the levels allowed reach: the 'accuracy' warning."""
    scene = handbook.CASES["centre crack a/b = 0.2"][1](0.1)
    scene.options = dataclasses.replace(scene.options, accuracy=1e-5, accuracy_levels=1)
    sol = cl.solve(scene)
    assert sol.error_estimate["reached"] is False and sol.error_estimate["size_factors"] == [1.0, 0.5]
    (w,) = [w for w in sol.warnings if w.code == "accuracy"]
    assert "was not reached in 1 refinement level" in w.message and "accuracy_levels" in w.message


def test_command_line_accuracy_and_what_the_plus_minus_is(tmp_path, capsys):
    """run --accuracy prints the levels and K +- its estimated error, names
    the SIF domain spread as what it is; results.json and sif.csv carry them."""
    args = ["run", str(SCENES / "ct_specimen.toml"), "--set", "mesh.h=5.0", "--set", "mesh.tip_h=0.5",
            "--set", "outputs.png=false", "--set", "outputs.vtu=false", "--out", str(tmp_path)]
    assert cli.main(args + ["--accuracy", "0.01"]) == 0
    out = capsys.readouterr().out
    assert "accuracy target 1 %: refinement levels 0.." in out and "reached" in out
    assert "K_I = " in out and " +- " in out and "MPa sqrt(mm)" in out and "not an error bar" in out
    res = json.loads((tmp_path / "results.json").read_text())
    assert res["error_estimate"]["reached"] and res["units"]["K"] == "MPa sqrt(mm)"
    assert res["sifs"][0]["K_I_error"] > 0.0 and len(res["sifs"][0]["K_I_levels"]) == len(res["error_estimate"]["size_factors"])
    assert "K_I_error" in (tmp_path / "sif.csv").read_text().splitlines()[0]
    # The default run: one estimate, the +- is the estimate of the K on this mesh.
    assert cli.main(args) == 0
    out = capsys.readouterr().out
    assert "K +- its estimated discretisation error" in out
    res = json.loads((tmp_path / "results.json").read_text())
    assert res["error_estimate"]["size_factors"] == [1.0, 0.5] and res["error_estimate"]["target"] is None


def test_grow_refines_every_step():
    """grow with options.accuracy: every step's solve goes through the levels
    (its solution carries the estimate; its mesh is finer than the scene's)."""
    sf = load_scene_file(SCENES / "hole_fatigue.toml", ["mesh.h=40.0", "options.contact=\"unilateral\"",
                                                         "options.accuracy=0.05", "options.accuracy_levels=1"])
    growth = dataclasses.replace(sf.growth, steps=1)
    result = cl.grow(sf.scene, growth, keep_solutions=True)
    assert len(result.solutions) == 2
    for sol in result.solutions:
        assert sol.error_estimate is not None and sol.error_estimate["size_factors"] == [1.0, 0.5]
        assert sol.model.num_dofs > 2 * sf.scene.mesh.mesh.geometry.x.shape[0]


def test_a_closed_crack_is_zero_to_the_floor_not_a_mesh_too_coarse(tmp_path, capsys):
    """The paper's crack from a hole under compression (5.2), closed: every
    K is below the K scale's floor (1e-3 of a K the loads could make), so
    its estimated error and domain spread are judged against the floor
    itself: K_I = 8.0e-6 +- 9.1e-6 with a natural K of 0.041 was warned as
    "the mesh is too coarse for this crack" (22 % of the floor) and as a
    1.2 % domain spread. Now neither (the estimate and the spread are below
    the floor) and the run says K is zero to the floor, and an accuracy
    target is reached once K is zero to the floor. (The error is not
    negligible against the floor, 22 % of it: the floor decides.)"""
    from cracklip import cli
    from cracklip.fracture.sif import K_ZERO, natural_k
    sf = load_scene_file(SCENES / "hole_crack.toml")
    sol = cl.solve(sf.scene)
    estimate_error(sf.scene, sol, cl.solve)
    (r,) = sol.stress_intensity_factors(0)
    floor = K_ZERO * natural_k(sol)
    assert sol.error_estimate["K_floor"] == pytest.approx(floor) and sol.error_estimate["K_scale"] == floor
    assert abs(r["K_I"]) + r["K_I_error"] < floor and r["K_I_error"] > 0.1 * floor
    assert not [w for w in sol.warnings if w.code in ("discretisation", "sif_spread")], \
        [w.message for w in sol.warnings]
    assert cli.main(["run", str(SCENES / "hole_crack.toml"), "--out", str(tmp_path)]) == 0
    out = capsys.readouterr()
    assert "too coarse" not in out.err and "K varies with the SIF domain" not in out.err
    assert f"every K below {floor:.3g}, 1e-3 of a K the loads could make (K is zero to that)" in out.out
    # An accuracy target: zero to the floor is reached on the first level (it refined 3 levels to 2.8e5
    # dofs and warned "the accuracy target 1 % was not reached": 3.5 % of the floor).
    assert cli.main(["run", str(SCENES / "hole_crack.toml"), "--accuracy", "0.01", "--out", str(tmp_path / "a")]) == 0
    out = capsys.readouterr()
    assert "refinement levels 0..1" in out.out and "reached: every K below" in out.out
    assert "not reached" not in out.err
