"""Paper section 5.2: crack from a hole under remote compression (issue 5)."""
import pathlib
import sys

import numpy as np
import pytest
from cracklip.exact.kirsch import crack_pressure, kirsch_stress

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
import hole_crack  # noqa: E402


def test_kirsch_field_facts():
    S = -0.01
    # Traction-free hole.
    t = np.linspace(0.05, np.pi - 0.05, 20)
    p = np.c_[np.cos(t), np.sin(t)]
    assert np.abs(np.einsum("nij,nj->ni", kirsch_stress(p, S), p)).max() <= 1e-16
    # Remote field.
    far = kirsch_stress(np.array([[3e3, 4e3]]), S)[0]
    assert np.allclose(far, [[S, 0], [0, 0]], atol=1e-8)
    # On x = 0: no shear, compressive sigma_xx = the crack pressure, no sigma_yy jump issue.
    y = np.linspace(1.0, 2.0, 11)
    s = kirsch_stress(np.c_[0 * y, y], S)
    assert np.abs(s[:, 0, 1]).max() <= 1e-16
    assert np.allclose(-s[:, 0, 0], crack_pressure(y, -S), rtol=1e-14)
    assert crack_pressure(np.array([1.0]), 0.01)[0] == pytest.approx(0.03)
    # Equilibrium: div sigma = 0 (central differences).
    rng = np.random.default_rng(2)
    x = rng.uniform(-2.5, 2.5, (30, 2))
    x = x[np.linalg.norm(x, axis=1) > 1.2]
    d = 1e-5
    div = np.zeros((len(x), 2))
    for j in range(2):
        e = np.zeros(2)
        e[j] = d
        div += (kirsch_stress(x + e, S)[:, :, j] - kirsch_stress(x - e, S)[:, :, j]) / (2 * d)
    assert np.abs(div).max() <= 1e-8


@pytest.fixture(scope="module")
def vector_runs():
    return {h: hole_crack.run(h, enrichment="vector")[0] for h in (0.1, 0.05, 0.025)}


def _rate(runs, key):
    h = np.array(sorted(runs))
    return np.polyfit(np.log(h), np.log([runs[v][key] for v in h]), 1)[0]


def test_hole_energy_and_pressure_rates(vector_runs):
    assert all(r["all_closed"] for r in vector_runs.values())
    assert _rate(vector_runs, "energy_error") >= 0.95
    assert _rate(vector_runs, "pressure_l2_error") >= 0.95
    assert vector_runs[0.025]["energy_error"] <= 0.011
    assert vector_runs[0.025]["pressure_l2_error"] <= 0.007


def test_hole_sif_is_zero(vector_runs):
    r = vector_runs[0.025]
    assert r["K_I_normalised"] <= 1e-3
    assert abs(r["K_II"]) <= 1e-3 * 0.01 * np.sqrt(np.pi)


def test_hole_scalar_enrichment_and_condition():
    v, _ = hole_crack.run(0.1, condition=True, enrichment="vector")
    s, _ = hole_crack.run(0.1, condition=True, enrichment="scalar")
    assert s["energy_error"] == pytest.approx(v["energy_error"], rel=0.02)
    assert 10 * v["cond_1norm"] <= s["cond_1norm"]
