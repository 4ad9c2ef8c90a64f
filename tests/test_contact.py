"""Crack-lip contact: multiplier spaces, patch test, contact SIFs, inf-sup,
unilateral active set, frictionless sliding (issue 4)."""
import dataclasses
import pathlib
import sys

import cracklip as cl
import numpy as np
import pytest
from cracklip.contact.infsup import inf_sup_constant

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
import block_uniform_pressure as block  # noqa: E402

K_REF = 0.01 * np.sqrt(np.pi * 0.4)


@pytest.mark.parametrize("n", [42, 84])
def test_heaviside_block_is_a_patch_test(n):
    r = block.run(n=n, enrichment="none", multipliers="stable")
    assert r["pressure_max_rel_dev"] <= 1e-8, r["pressure_max_rel_dev"]


@pytest.mark.parametrize("enrichment", ["scalar", "vector"])
@pytest.mark.parametrize("n", [21, 42, 84])
def test_tip_enriched_block_pressure_and_sif(enrichment, n):
    r = block.run(n=n, enrichment=enrichment, multipliers="stable", quadrature="collapsed")
    assert r["pressure_max_rel_dev"] <= 1e-4, r["pressure_max_rel_dev"]
    assert abs(r["K_I"]) <= 1e-4 * K_REF, r["K_I"]
    assert abs(r["K_II"]) <= 1e-4 * K_REF


def test_paper_gauss_rule_shows_pressure_oscillation():
    """The paper's plain rule at degree 5 leaves a visible error (paper: ~1e-2)."""
    r5 = block.run(n=42, enrichment="vector", quadrature="gauss", degree=5)
    r20 = block.run(n=42, enrichment="vector", quadrature="gauss", degree=20)
    assert r5["pressure_max_rel_dev"] > 1e-3
    assert r20["pressure_max_rel_dev"] < r5["pressure_max_rel_dev"]


def test_multiplier_space_partition_of_unity():
    """Reduced multiplier functions sum to one along the crack (constant pressure exact)."""
    model = cl.create_model(block.scene_for(42, enrichment="vector"))
    from cracklip.contact.frictionless import create_contact_system
    cs = create_contact_system(model)
    R = cs.R.toarray()
    assert np.all(R.sum(axis=1) == 1.0)  # every full multiplier in exactly one reduced one
    assert cs.num_multipliers < cs.space.num_full
    naive = cl.create_model(block.scene_for(42, enrichment="vector", multipliers="naive"))
    assert create_contact_system(naive).num_multipliers == create_contact_system(naive).space.num_full


def _inf_sup(enrichment, multipliers, ns=(10, 20, 40, 80)):
    return np.array([inf_sup_constant(cl.create_model(block.scene_for(n, enrichment=enrichment,
                                                                       multipliers=multipliers)))
                     for n in ns])


def test_inf_sup_naive_decays():
    """The naive space is not uniformly stable: its finest value is at most
    half its largest and all lie far below the stable space's bound 0.4. Which
    mesh is worst is the mesh's: n = 10 on gmsh's default mesh (0.49 .. 0.020),
    n = 10 is nearly singular already with Mesh.RandomSeed = 3 (7.7e-4)."""
    v = _inf_sup("vector", "naive")
    assert v[-1] <= 0.5 * v.max() and v[-1] < 0.1, v


@pytest.mark.parametrize("enrichment", ["none", "scalar", "vector"])
def test_inf_sup_stable_bounded(enrichment):
    """Issue 4, acceptance 3: every stable variant (Heaviside only, scalar,
    vector) is bounded below uniformly in h: never below 0.4 over n =
    10..80, and no decay over n = 20..80 (within 1.5x of the n = 20 value;
    measured 0.62..0.85 over gmsh seeds 1-5). At n = 10 a Heaviside-only
    crack crosses two cells and its end group (the last cut cell's fading
    jump, tied until 2/3 of its weight sees the full jump) may take the whole
    crack: one multiplier, sqrt(beta) 2.2..2.4 on seeds 2-5 (0.68 with two on
    seed 1): coarse but stable, so n = 10 counts for the lower bound only."""
    v = _inf_sup(enrichment, "stable")
    assert np.all(v[1:] >= v[1] / 1.5) and np.all(v[1:] <= 1.5 * v[1]), v
    assert v.min() >= 0.4, v


@pytest.mark.parametrize("enrichment", ["none", "scalar", "vector"])
def test_inf_sup_stable_over_crack_positions(enrichment):
    """The end-segment tie must work wherever the tip falls in its cell: the
    block's crack moved in x and y on three meshes, sqrt(beta_min) never below
    0.5 (the naive space reaches 0.05 at n = 40; tying the tip cell's P0
    multiplier only when its segment is short gave 0.38 for vector)."""
    vals = []
    for n in (10, 20, 40):
        for tip_x, y0 in [(-0.63, 0.0123), (-0.58, 0.0), (-0.55, 0.0371)]:
            scene = block.scene_for(n, enrichment=enrichment)
            scene = dataclasses.replace(scene, cracks=[cl.Crack([[-1.5, y0], [tip_x, y0]])])
            vals.append(inf_sup_constant(cl.create_model(scene)))
    assert min(vals) >= 0.5, vals


@pytest.mark.parametrize("n, tip, angle", [(20, (-0.6593, -0.0380), 0.1502), (15, (-0.6446, -0.0543), 0.2820),
                                           (20, (-0.6570, 0.0223), 0.1830), (30, (-0.5560, 0.0537), -0.1309)])
def test_inf_sup_heaviside_end_on_inclined_cracks(n, tip, angle):
    """Inclined Heaviside-only cracks whose last cut cell's group sees the
    full jump over only 29..52 % of its weight: tying that group only to the
    multiplier continuous at its start (a no-op here) gave sqrt(beta) = 0.21,
    0.22, and a share threshold of 1/2 instead of 2/3 gave 0.44 and 0.47."""
    length = tip[0] + 1.5
    start = [tip[0] - length * np.cos(angle), tip[1] - length * np.sin(angle)]
    scene = dataclasses.replace(block.scene_for(n, enrichment="none"), cracks=[cl.Crack([start, list(tip)])])
    assert inf_sup_constant(cl.create_model(scene)) >= 0.5


def _bending_scene(start, n=40):
    md = cl.create_square(2.0 / n)
    c0 = np.array(md.nearest_node([-1, -1]))
    c1 = np.array(md.nearest_node([1, -1]))

    def syy(p):
        return -0.01 + 0.03 * p[:, 0]  # compression on the left, tension on the right
    return cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-0.5, 0.013], [0.5, 0.013]])],
                    dirichlet=[cl.Dirichlet(tuple(c0), None, 0.0), cl.Dirichlet(tuple(c1), 1, 0.0)],
                    tractions=[cl.Traction("top", lambda p: np.stack([0 * p[:, 0], syy(p)], axis=1)),
                               cl.Traction("bottom", lambda p: np.stack([0 * p[:, 0], -syy(p)], axis=1))],
                    options=cl.Options(enrichment="vector", radius=0.2, contact="unilateral",
                                       active_set_start=start))


def test_unilateral_partly_open_crack():
    sols = {start: cl.solve(_bending_scene(start)) for start in ("closed", "open")}
    for sol in sols.values():
        c = sol.contact
        cs = c["system"]
        gap = cs.B @ sol.u - cs.g
        pressure = -c["lambda"]
        active = c["active"]
        assert 0 < active.sum() < active.size  # part open, part closed
        assert c["iterations"] <= 20
        assert np.abs(gap[active]).max() <= 1e-10          # closed: no gap
        assert pressure.min() >= -1e-12                      # no tension
        assert np.abs(pressure * gap).max() <= 1e-12         # complementarity
        assert gap[~active].min() >= -1e-12                  # open: no penetration
        assert sol.contact_pressure(0)["pressure"].min() >= -1e-12
    assert np.abs(sols["closed"].u - sols["open"].u).max() <= 1e-12


def test_unilateral_equals_bilateral_when_all_closed():
    bil = cl.solve(block.scene_for(42, contact="bilateral"))
    for start in ("closed", "open"):
        sc = block.scene_for(42, contact="unilateral")
        sc.options.active_set_start = start
        uni = cl.solve(sc)
        assert uni.contact["active"].all()
        assert np.abs(uni.u - bil.u).max() <= 1e-10 * np.abs(bil.u).max()


def test_active_set_failure_is_reported():
    sc = _bending_scene("open")
    sc.options.max_active_set_iterations = 1
    with pytest.raises(cl.CracklipError, match="did not settle"):
        cl.solve(sc)


def test_closed_inclined_crack_slides_frictionless():
    """Pressed and sheared inclined crack: K_I ~ 0, K_II non-zero and converging."""
    import sliding_crack
    rows = [sliding_crack.run(n) for n in (20, 40, 80)]
    assert all(r["all_closed"] for r in rows)
    K = np.array([[(s["K_I"], s["K_II"]) for s in r["tips"]] for r in rows])  # (mesh, tip, mode)
    K_inf = abs(sliding_crack.shear_on_crack()) * np.sqrt(np.pi * sliding_crack.HALF_LENGTH)
    assert np.all(np.abs(K[-1, :, 1]) >= 0.9 * K_inf)                       # non-zero K_II
    assert np.all(np.abs(K[-1, :, 0]) <= 1e-3 * np.abs(K[-1, :, 1]))        # K_I ~ 0
    d1 = np.abs(K[1, :, 1] - K[0, :, 1])
    d2 = np.abs(K[2, :, 1] - K[1, :, 1])
    assert np.all(d2 < d1), (d1, d2)                                       # converging


def test_block_demo_cli(tmp_path):
    import json
    import subprocess
    root = pathlib.Path(__file__).resolve().parents[1]
    out = tmp_path / "b.json"
    subprocess.run([sys.executable, str(root / "demos" / "block_uniform_pressure.py"), "--n", "21",
                    "--inf-sup", "--json", str(out), "--out", str(tmp_path)], check=True,
                   capture_output=True, env={"PYTHONPATH": str(root / "python"), "PATH": "/usr/bin:/bin"},
                   timeout=600)
    res = json.loads(out.read_text())
    for key in ("ndofs", "n_multipliers", "pressure", "pressure_max_rel_dev", "K_I", "K_II",
                "active_set_iterations", "timings", "inf_sup"):
        assert key in res
    assert len(res["inf_sup"]) == 4 and all(v > 0 for _, v in res["inf_sup"])
    p = np.array(res["pressure"])
    assert np.all(p[:, 1] > 0)  # compression positive
