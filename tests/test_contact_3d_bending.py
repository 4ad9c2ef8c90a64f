"""A 3D crack partly pressed shut, checked against its 2D section (issue
36, acceptance 3): demos/scenes/bending_crack_closure.toml, a through crack
across the neutral axis of a bent cantilever, between two planes of
symmetry (u_z = 0 on z = 0 and z = 2), so the 3D model is the plane strain
section exactly. The upper front opens, the lower part of the crack is
pressed shut (unilateral, frictionless). Checked: the lips' largest overlap
at most 1 % of the largest opening, the contact pressure never negative,
K_I > 0 along the open front and equal to the 2D plane strain K_I of the
same section, K_I = 0 along the closed front (to the discretisation error),
the closed part's extent as in 2D; and the same run without contact, whose
lips pass through each other and whose closed front has a negative K_I."""
import json
import pathlib

import meshio
import numpy as np
import pytest

from cracklip import cli

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENE = ROOT / "demos" / "scenes" / "bending_crack_closure.toml"

#: The same section in 2D, plane strain (the 3D scene's material, load and
#: crack; tip_h = 0.05).
SECTION_2D = """
title = "2D section of bending_crack_closure.toml"
[units]
length = "mm"
stress = "MPa"
[mesh]
kind = "rectangle"
domain = [0.0, 0.0, 40.0, 10.0]
h = 0.5
tip_h = 0.05
[material]
E = 200000.0
nu = 0.3
plane = "strain"
[[cracks]]
name = "section"
points = [[10.0, 2.0], [10.0, 8.0]]
[[dirichlet]]
tag = "left"
[[loads.tractions]]
tag = "right"
value = [0.0, -5.0]
[options]
enrichment = "vector"
radius = 0.5
contact = "unilateral"
multipliers = "stable"
[outputs]
error_estimate = false
png = false
vtu = false
"""

THICKNESS = 2.0


def _run(args, out):
    assert cli.main(["run", *args, "--out", str(out), "--quiet"]) == 0
    return json.loads((out / "results.json").read_text())


@pytest.mark.slow
def test_bending_crack_closure_against_its_plane_strain_section(tmp_path):
    """Measured (tip_h = crack_h = 0.15 as shipped, 53 814 dofs, the
    multipliers' stabilization at its 3D default gamma = 8, the rim rows at
    a quarter, contact/stabilization.py): overlap 0.36 % of the largest
    opening 9.44e-4 mm (at the edge of the closed part, where a multiplier group is
    closed over part of its support and open over the rest); pressure >= 0
    (largest 51.5 MPa, 2D 51.1); K_I 98.96 .. 99.06 along the open front
    against 98.80 in 2D; -0.94 .. -0.33 along the closed front (0.95 % of
    the open K; -0.91 .. -0.31 at gamma 2); closed length 1.91 mm against
    1.93 in 2D. Without the stabilization: 0.45 %,
    54.0 MPa, closed front -0.75 .. -0.11 (0.76 %). The multiplier groups no longer depend on the node
    order (multiplier_groups.h); while they did (tip_h 0.5: overlap 2.7 %,
    0.25: 0.95 %, 0.2: 1.17 %, 0.125: 0.41 %, measured in DOLFINx's serial
    order), the shipped mesh gave 0.33 % and K_I -0.71 .. -0.11 in DOLFINx's
    order, 0.38 % and -1.14 .. -0.26 (1.16 %) in input order, for which this
    bound had been loosened to 1.2 %; it is back at 1 %."""
    res = _run([str(SCENE), "--set", "outputs.error_estimate=false", "--set", "outputs.png=false"], tmp_path / "3d")
    (tmp_path / "section.toml").write_text(SECTION_2D)
    ref = _run([str(tmp_path / "section.toml")], tmp_path / "2d")
    c, c2 = res["cracks"][0], ref["cracks"][0]
    # The overlap: the acceptance line, on the shipped mesh.
    assert c["gap_max"] > 5e-4
    assert c["interpenetration_max"] <= 0.01 * c["gap_max"], (c["interpenetration_max"], c["gap_max"])
    # The pressure: never negative, pressing the lower part.
    surf = meshio.read(tmp_path / "3d" / "crack_surface.vtu")
    p, y = surf.point_data["pressure"], surf.points[:, 1]
    assert p.max() > 30.0 and p.min() >= -1e-12 * p.max(), (p.min(), p.max())
    assert c["pressure"]["min"] >= -1e-12 * p.max()
    pressed = p > 1e-9 * p.max()
    assert y[pressed].max() < 5.0 and y[pressed].min() < 2.1       # from the lower front up, below the axis
    # The closed part's extent (closed area / thickness) as the section's
    # closed length (the closure point sits within a mesh size of 3.9 mm).
    assert 0.25 < c["closed_fraction"] < 0.4
    assert abs(c["closed_area"] / THICKNESS - c2["closed_length"]) <= 0.15, (c["closed_area"], c2["closed_length"])
    # K along the fronts against the section's tips.
    k2 = {round(r["y"]): r for r in ref["sifs"]}
    upper = [r for r in res["sifs"] if abs(r["y"] - 8.0) < 1e-6]
    lower = [r for r in res["sifs"] if abs(r["y"] - 2.0) < 1e-6]
    assert len(upper) >= 3 and len(lower) >= 3 and len(upper) + len(lower) == len(res["sifs"])
    assert not any(r["free_surface"] for r in res["sifs"])           # both ends on planes of symmetry
    k_open = k2[8]["K_I"]
    assert k_open > 90.0 and abs(k2[2]["K_I"]) < 0.005 * k_open
    for r in upper:
        assert abs(r["K_I"] - k_open) <= 0.01 * k_open, (r["K_I"], k_open)
        assert abs(abs(r["K_II"]) - abs(k2[8]["K_II"])) <= 0.02 * abs(k2[8]["K_II"])
    for r in lower:
        assert abs(r["K_I"]) <= 0.01 * k_open, (r["K_I"], k_open)
        assert abs(abs(r["K_II"]) - abs(k2[2]["K_II"])) <= 0.02 * abs(k2[2]["K_II"])
    assert max(abs(r["K_III"]) for r in res["sifs"]) <= 1e-3 * k_open   # plane strain: no mode III


def test_bending_crack_without_contact_interpenetrates(tmp_path):
    """The contrast (coarse, tip_h = crack_h = 0.5): without contact the
    lower lips pass through each other by about as much as the upper part
    opens (7.5e-4 against 7.5e-4 mm) and K_I along the lower front is
    negative (-86.6 against 97.7 with contact); with contact on the same
    mesh the overlap is 2.7 % of the opening (3.3 % of the overlap without
    contact) and K_I there -3.6 .. -3.8
    against 97.7 along the open front (the 1 % needs the shipped mesh)."""
    coarse = ["--set", "mesh.tip_h=0.5", "--set", "mesh.crack_h=0.5", "--set", "outputs.error_estimate=false",
              "--set", "outputs.png=false", "--set", "outputs.vtu=false"]
    on = _run([str(SCENE), *coarse], tmp_path / "on")
    off = _run([str(SCENE), *coarse, "--set", "options.contact=none"], tmp_path / "off")
    c, f = on["cracks"][0], off["cracks"][0]
    assert f["interpenetration_max"] > 0.5 * f["gap_max"]
    assert c["interpenetration_max"] <= 0.05 * c["gap_max"]
    assert c["interpenetration_max"] <= 0.05 * f["interpenetration_max"]   # 3.3 %
    k_open = max(r["K_I"] for r in on["sifs"])
    lower_off = [r["K_I"] for r in off["sifs"] if abs(r["y"] - 2.0) < 1e-6]
    lower_on = [r["K_I"] for r in on["sifs"] if abs(r["y"] - 2.0) < 1e-6]
    assert max(lower_off) < -0.2 * k_open, lower_off
    assert min(lower_on) > -0.05 * k_open, lower_on
