"""Coulomb friction on the crack lips (issue 16) against exact solutions.

The closed inclined Griffith crack under compression (demos/friction_crack.py):
stick when tan(beta) <= mu (K_II = 0, no slip), else the whole crack slips
with K_II = (tau - mu sigma_n) sqrt(pi a), K_I = 0, the pressure sigma_n and
Sneddon's slip profile; a load-unload cycle leaves the exact locked-in slip.
"""
import dataclasses
import math
import pathlib
import sys

import cracklip as cl
import numpy as np
import pytest
from cracklip import cli
from cracklip.contact.infsup import inf_sup_constant

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
import block_uniform_pressure  # noqa: E402
import friction_crack  # noqa: E402

K_REF = math.sqrt(math.pi * friction_crack.A)  # p sqrt(pi a), p = 1


@pytest.mark.parametrize("beta,mu", [(30.0, 0.2), (60.0, 0.5), (30.0, 1.0), (45.0, 1.0)])
def test_inclined_crack_table(beta, mu):
    """Acceptance 1 at h = 0.025: |K_II - exact| <= 2e-3 p sqrt(pi a)
    (measured <= 2.7e-4), |K_I| <= 1e-3 (<= 8e-5); stick rows (tan beta <= mu,
    45 degrees with mu = 1 the limit) do not slip, slip rows slip everywhere
    with the exact profile (0.25 % L2)."""
    row = friction_crack.run(beta, mu, n=80)
    assert row["K_II_error"] <= 2e-3 and row["K_I_error"] <= 1e-3
    k_exact = {(30.0, 0.2): 0.28301, (60.0, 0.5): 0.30801, (30.0, 1.0): 0.0, (45.0, 1.0): 0.0}[beta, mu]
    assert abs(row["K_II"]) / K_REF == pytest.approx(k_exact, abs=5e-4)
    counts = row["state_counts"]
    assert counts["open"] == 0
    if row["stick_exact"]:
        assert row["slip_max_abs"] < 1e-10
        if beta == 30.0:
            assert counts["slip"] == 0
    else:
        assert counts["stick"] == 0 and row["slip_l2_rel"] < 0.005


def test_frictionless_limit_is_todays_answer():
    """Acceptance 2: the friction solver with mu = 0 gives the frictionless
    contact solution to round-off: u to 1e-12, the multipliers to 1e-10
    (their Schur complement amplifies round-off more: measured u 1.3e-14 ..
    9.5e-14, multipliers 4.7e-13 .. 1.0e-11 over gmsh seeds 1-4). friction = 0
    itself keeps the frictionless code, bit for bit."""
    from cracklip.contact.frictionless import contact_constant, create_contact_system, solve_frictionless
    from cracklip.model.assembly import assemble_system
    from cracklip.contact.friction import solve_friction
    from cracklip.solvers.checked import scipy_from_petsc
    field, _, _ = friction_crack.exact(30.0, 0.0)
    scene = friction_crack.scene_for(field, 20, 0.5)
    model = cl.create_model(scene)
    A, b, _ = assemble_system(model)
    K, f = scipy_from_petsc(A), b.array.copy()
    cs = create_contact_system(model)
    opts0 = dataclasses.replace(scene.options, friction=0.0)
    u_fric, info = solve_friction(K, f, cs, cs.g, cs.gt, np.zeros(cs.num_multipliers), opts0,
                                  contact_constant(model))
    u_free, free = solve_frictionless(K, f, cs, opts0, contact_constant(model))
    assert np.abs(u_fric - u_free).max() <= 1e-12 * np.abs(u_free).max()
    assert np.abs(info["lambda"] - free["lambda"]).max() <= 1e-10 * np.abs(free["lambda"]).max()
    assert np.abs(info["lambda_t"]).max() == 0.0
    # friction = 0 takes the frictionless path: no tangential multipliers at all.
    sol = cl.solve(dataclasses.replace(scene, options=dataclasses.replace(scene.options, friction=0.0)))
    assert "lambda_t" not in sol.contact and sol.steps is None


def test_load_unload_hysteresis():
    """Acceptance 4: hold sigma_n = 1, raise the shear to 0.7, remove it.
    mu = 0: the slip returns to zero; mu = 0.3 (0.7 > 2 mu sigma_n): reverse
    slip leaves min(0.7 - 0.3, 0.3) = 0.3; mu = 0.5: no reverse slip, 0.2
    stays. Each to 1 % of the exact slip profile (h = 0.05)."""
    for mu, locked in ((0.0, 0.0), (0.3, 0.3), (0.5, 0.2)):
        r = friction_crack.hysteresis(mu, n=40)
        clamp, up, removed = r["steps"]
        assert clamp["slip_max"] < 1e-10
        assert up["slip_error_rel"] < 0.01
        assert r["locked_exact_tau"] == pytest.approx(locked)
        if locked == 0.0:
            assert removed["slip_max"] < 1e-10
        else:
            assert removed["slip_error_rel"] < 0.01
            for k in removed["K_II"]:  # the locked-in slip holds a residual K_II
                assert k == pytest.approx(removed["K_II_exact"], rel=2e-3)


def mixed_scene(start: str, n: int = 20) -> cl.Scene:
    """An inclined crack under compression plus bending (sigma_xx = -0.5,
    sigma_yy = -1 + 2.5 x on the ends): open where the bending pulls, stuck
    where the shear is small against the pressure, slipping between."""
    h = 2.0 / n
    b = math.radians(30.0)
    t = np.array([math.cos(b), math.sin(b)])
    tips = np.array([[0.2, 0.0] - 0.6 * t, [0.2, 0.0] + 0.6 * t])
    md = cl.create_rectangle(-1, -2, 1, 2, h, refine=[(p[0], p[1], h / 4, 0.0) for p in tips])
    stress = cl.LinearStress((-0.5, -1.0, 0.0), gradient=((0.0, 2.5, 0.0), (0.0, 0.0, 0.0)))
    return cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack(tips)],
                    dirichlet=[cl.Dirichlet(md.nearest_node((-1, -2)), None, 0.0),
                               cl.Dirichlet(md.nearest_node((1, -2)), 1, 0.0)],
                    tractions=[cl.Traction(s, stress=stress) for s in ("left", "right", "top", "bottom")],
                    options=cl.Options(radius=0.1, contact="unilateral", friction=0.3, active_set_start=start))


def test_open_stick_slip_from_both_starts():
    """Acceptance 4: one crack with open, stick and slip zones reaches the
    same states and tractions from the closed and the open start."""
    a, b = cl.solve(mixed_scene("closed")), cl.solve(mixed_scene("open"))
    assert np.array_equal(a.contact["state"], b.contact["state"])
    ca, cb = a.contact_pressure(0), b.contact_pressure(0)
    assert set(ca["state"]) == {"open", "stick", "slip"}
    scale = ca["pressure"].max()
    assert np.abs(ca["pressure"] - cb["pressure"]).max() < 1e-10 * scale
    assert np.abs(ca["shear"] - cb["shear"]).max() < 1e-10 * scale
    # Coulomb holds pointwise: |shear| <= mu p, = where slipping, 0 where open.
    mu = 0.3
    closed = ca["state"] != "open"
    assert np.all(np.abs(ca["shear"][closed]) <= mu * ca["pressure"][closed] * (1 + 1e-9) + 1e-12 * scale)
    slip = ca["state"] == "slip"
    assert np.allclose(np.abs(ca["shear"][slip]), mu * ca["pressure"][slip], rtol=1e-6, atol=1e-9 * scale)
    assert np.all(ca["pressure"][~closed] == 0.0) and np.all(ca["shear"][~closed] == 0.0)


def test_iterations_do_not_grow_with_refinement():
    """Acceptance 4: friction iterations per step at h = 0.1, 0.05, 0.025 (2, 2, 2)."""
    its = [friction_crack.run(60.0, 0.5, n=n)["iterations"] for n in (20, 40, 80)]
    assert max(its) <= 3


def test_inf_sup_of_normal_and_tangential_multipliers():
    """Acceptance 5: sqrt(beta_min) of [B_n; B_t] on the paper's block
    (h = 0.1 .. 0.025: 0.541, 0.532, 0.563) stays within 1.5x."""
    values = [inf_sup_constant(cl.create_model(block_uniform_pressure.scene_for(n)), tangential=True)
              for n in (20, 40, 80)]
    assert min(values) > 0.3 and max(values) / min(values) < 1.5


def test_tangential_lip_term_makes_K_II_domain_independent():
    """SIFs with friction: the lip term takes the friction traction. Without
    its tangential part, K_II of the slipping crack (beta = 60, mu = 0.5)
    changes with the domain radius by several per cent; with it the domains
    agree to 1e-3 and K_II is the exact one."""
    from cracklip.fracture.sif import compute_sifs
    field, tau_eff, _ = friction_crack.exact(60.0, 0.5)
    sol = cl.solve(friction_crack.scene_for(field, 40, 0.5))
    exact = tau_eff * K_REF
    with_shear = [k["K_II"] for k in sol.stress_intensity_factors(0)]
    spread_with = max(k["K_II_spread"] for k in sol.stress_intensity_factors(0))
    normal_only = dataclasses.replace(sol, contact={k: v for k, v in sol.contact.items() if k != "lambda_t"},
                                      _sif_cache={})
    rows, _ = compute_sifs(normal_only)
    spread_without = max(r["K_II_spread"] for r in rows)
    assert spread_with < 1e-3 * abs(exact) and spread_without > 20 * spread_with
    assert all(k == pytest.approx(exact, rel=2e-3) for k in with_shear)
    assert all(abs(r["K_II"] - exact) > 0.01 * abs(exact) for r in rows)


def test_friction_scene_file(tmp_path, capsys):
    """options.friction, load groups and a load path from a scene file: the
    per-step results, crack.csv's shear and state, and bad paths named."""
    scene = tmp_path / "friction.toml"
    scene.write_text("""
[mesh]
domain = [-1.0, -1.0, 1.0, 1.0]
h = 0.1
tip_h = 0.025
[material]
E = 1.0
nu = 0.3
[[cracks]]
points = [[-0.5, 0.0], [0.5, 0.0]]
[[dirichlet]]
point = [-1.0, -1.0]
[[dirichlet]]
point = [1.0, -1.0]
component = "y"
[[loads.tractions]]
tag = "top"
value = [0.0, -1.0]
group = "clamp"
[[loads.tractions]]
tag = "bottom"
value = [0.0, 1.0]
group = "clamp"
[[loads.tractions]]
tag = "top"
value = [0.7, 0.0]
group = "shear"
[[loads.tractions]]
tag = "bottom"
value = [-0.7, 0.0]
group = "shear"
[[loads.tractions]]
tag = "left"
value = [0.0, -0.7]
group = "shear"
[[loads.tractions]]
tag = "right"
value = [0.0, 0.7]
group = "shear"
[[load_path]]
name = "clamp"
factors = { clamp = 1.0 }
[[load_path]]
name = "shear up"
factors = { shear = 1.0 }
[[load_path]]
name = "shear removed"
factors = { shear = 0.0 }
[options]
radius = 0.1
contact = "bilateral"
friction = 0.3
load_steps = 2
""")
    out = tmp_path / "o"
    assert cli.main(["run", str(scene), "--out", str(out), "--quiet", "--set", "outputs.vtu=false"]) == 0
    import csv
    import json
    results = json.loads((out / "results.json").read_text())
    assert [s["name"] for s in results["steps"]] == ["clamp", "shear up", "shear removed"]
    assert results["steps"][1]["factors"] == {"clamp": 1.0, "default": 0.0, "shear": 1.0}
    assert results["contact"]["friction"] == 0.3 and results["contact"]["increment_iterations"]
    k_up = results["steps"][1]["sifs"][0]["K_II"]
    k_end = results["steps"][2]["sifs"][0]["K_II"]
    assert abs(k_up) > 0.05 and 0.0 < abs(k_end) < abs(k_up)  # locked-in slip after unloading
    with (out / "crack.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert {r["step"] for r in rows} == {"0", "1", "2"}
    assert {r["state"] for r in rows if r["step"] == "1"} <= {"slip", "stick"}
    # each step's K where sif.csv has it: the tip's position with it (steps[].sifs had no x, y)
    with (out / "sif.csv").open() as f:
        sif = list(csv.DictReader(f))
    for k, st in enumerate(results["steps"]):
        mine = [r for r in sif if r["step"] == str(k)]
        assert len(mine) == len(st["sifs"]) > 0
        for a, b in zip(mine, st["sifs"]):
            assert (float(a["x"]), float(a["y"]), float(a["K_II"])) == pytest.approx((b["x"], b["y"], b["K_II"]),
                                                                                    rel=1e-9, abs=1e-12)
    assert (out / "crack_pressure.png").stat().st_size > 20_000
    bad = tmp_path / "bad.toml"
    bad.write_text(scene.read_text().replace("factors = { shear = 0.0 }", "factors = { sheer = 0.0 }"))
    status = cli.main(["run", str(bad), "--out", str(tmp_path / "b"), "--quiet"])
    assert status == 2
    assert "load step 'shear removed' names load group(s) ['sheer']" in capsys.readouterr().err


def test_shear_at_the_friction_limit_sticks(tmp_path):
    """A closed crack whose uniform shear is exactly at the friction bound
    (biaxial p = 1, tau = 0.5, mu = 0.5; 20 x 20 plate, a = 1): the sticking
    start is the exact (uniform) field, K = 0 at both tips. Its multipliers
    carry round-off of 5e-11 above the bound: with a stick->slip test at
    1e-12 of the shear, 14 of 48 multipliers slipped on it, the states
    wandered 20 iterations and the run stopped with a ContactError (status
    2); at LIMIT_TOLERANCE (1e-8) the start settles in one iteration."""
    scene = tmp_path / "limit.toml"
    text = """
[mesh]
domain = [-10.0, -10.0, 10.0, 10.0]
h = 1.0
tip_h = 0.01
[[mesh.refine]]
segment = [[-1.3, 0.0], [1.3, 0.0]]
h = 0.05
[material]
E = 1.0
nu = 0.3
[[cracks]]
points = [[-1.0, 0.0], [1.0, 0.0]]
[[dirichlet]]
point = [-10.0, -10.0]
[[dirichlet]]
point = [10.0, -10.0]
component = "y"
"""
    for tag in ("top", "bottom", "left", "right"):
        text += f'[[loads.tractions]]\ntag = "{tag}"\nstress = [-1.0, -1.0, 0.5]\n'
    text += """[options]
radius = 0.2
contact = "bilateral"
friction = 0.5
[outputs]
vtu = false
png = false
error_estimate = false
"""
    scene.write_text(text)
    out = tmp_path / "o"
    assert cli.main(["run", str(scene), "--out", str(out), "--quiet"]) == 0
    import json
    results = json.loads((out / "results.json").read_text())
    for tip in results["sifs"]:
        assert abs(tip["K_I"]) < 1e-8 and abs(tip["K_II"]) < 1e-8
    assert results["contact"]["states"]["slip"] == 0 and results["contact"]["iterations"] == 1


def test_load_group_the_path_never_names_warns(tmp_path):
    """demos/scenes/frictional_crack.toml with a load path of its clamp
    alone: the four shear tractions (group "shear") get no factor in any
    step, so they stay at 0 and are never applied (K_II = 0, the crack
    only clamped). That ran silently (no warning, status 0); it now warns
    (unused_load_group, naming the group). The shipped path names both
    groups: no such warning."""
    import json
    scene = pathlib.Path(__file__).resolve().parents[1] / "demos" / "scenes" / "frictional_crack.toml"
    small = ["--set", "mesh.h=0.2", "--set", "mesh.tip_h=0.05", "--set", "outputs.vtu=false", "--set",
             "outputs.png=false", "--no-estimate", "--quiet"]
    out = tmp_path / "clamp_only"
    assert cli.main(["run", str(scene), "--out", str(out), *small,
                     "--set", 'load_path=[{name="clamp",factors={clamp=1.0}}]']) == 0
    warnings = json.loads((out / "results.json").read_text())["warnings"]
    unused = [w for w in warnings if w["code"] == "unused_load_group"]
    assert len(unused) == 1 and "['shear']" in unused[0]["message"], warnings
    out = tmp_path / "shipped"
    assert cli.main(["run", str(scene), "--out", str(out), *small]) == 0
    warnings = json.loads((out / "results.json").read_text())["warnings"]
    assert not [w for w in warnings if w["code"] == "unused_load_group"], warnings


def test_bilateral_contact_in_tension_warns(tmp_path):
    """demos/scenes/frictional_crack.toml with its clamp reversed (the
    crack pulled open by sigma_yy = +1, then sheared): bilateral contact
    holds the lips together, so K_I = 0 (measured 5e-5) where the open
    crack's is sigma sqrt(pi a) = 1.25 (infinite plate; more in this one) and the contact
    pressure is -1 (tension). That ran silently; it now warns
    (bilateral_tension). The shipped scene (compression at every step)
    does not."""
    import json
    scene = pathlib.Path(__file__).resolve().parents[1] / "demos" / "scenes" / "frictional_crack.toml"
    small = ["--set", "mesh.h=0.2", "--set", "mesh.tip_h=0.05", "--set", "outputs.vtu=false", "--set",
             "outputs.png=false", "--no-estimate", "--quiet"]
    out = tmp_path / "pulled"
    assert cli.main(["run", str(scene), "--out", str(out), *small, "--set", "loads.tractions[0].value=[0.0, 1.0]",
                     "--set", "loads.tractions[1].value=[0.0, -1.0]"]) == 0
    results = json.loads((out / "results.json").read_text())
    assert abs(results["steps"][0]["sifs"][0]["K_I"]) < 1e-3  # held shut (5e-5): the reason for the warning
    tension = [w for w in results["warnings"] if w["code"] == "bilateral_tension"]
    assert len(tension) == 1 and "100 % of its length" in tension[0]["message"], results["warnings"]
    out = tmp_path / "shipped"
    assert cli.main(["run", str(scene), "--out", str(out), *small]) == 0
    warnings = json.loads((out / "results.json").read_text())["warnings"]
    assert not [w for w in warnings if w["code"] == "bilateral_tension"], warnings
