"""Handbook checks (issue 14, acceptance 4): demos/handbook.py's cases at a
modest mesh (h = W / 40, W the part's width; tip_h = 0.01, enrichment
radius 0.1, default SIF domains): centre crack in a strip (a/b = 0.2, 0.5;
Tada), single edge notch in tension (a/W = 0.3, 0.5; Tada, which the
Gross-Brown polynomial matches to 0.3 %) and in bending (a/W = 0.3), inclined
centre cracks (30, 60 degrees; exact field on the boundary), a pressurised
crack in plane strain and stress (exact), a crack closed by residual stress
(K = 0). Each K within 0.5 % of its scale; K_II within 1e-3 where it
vanishes. Measured (results/handbook.md): 0.30, 0.18, 0.11, 0.32, 0.02,
0.08, 0.06, 0.04, 0.03 % and 1e-11; at h = W / 20 up to 0.88 % (the edge
notch a/W = 0.5: P1's error in the bending of the ligament, not the tip's).
"""
import math
import pathlib
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
import handbook  # noqa: E402


@pytest.mark.parametrize("case", list(handbook.CASES))
def test_handbook_case(case):
    row = handbook.run(case, 40)
    # Closed by residual stress: u = 0 and K = 0 up to the solve's round-off, which the conditioning
    # of the mesh's enriched dofs amplifies (measured 1e-15 .. 3.7e-9 over gmsh seeds 1-4: 1-norm
    # condition 1e7, 1.5e11 unscaled on seed 2's mesh); open, K would be ~1.
    limit = 1e-7 if case.startswith("crack closed") else 5e-3
    assert row["error_I"] < limit and row["error_II"] < limit
    if row["K_II_exact"] == 0.0:
        assert max(abs(k) for k in row["K_II"]) < 1e-3 * row["K_scale"]
    assert not [w for w in row["warnings"] if w not in ("sif_domain",)]


def test_edge_notch_references_agree():
    """Tada's edge-notch factor against the Gross-Brown polynomial (0.5 %)."""
    for x in (0.3, 0.5):
        gross_brown = 1.12 - 0.231 * x + 10.55 * x ** 2 - 21.72 * x ** 3 + 30.39 * x ** 4
        assert gross_brown == pytest.approx(handbook.tada_edge_crack(x), rel=3e-3)
    assert handbook.tada_centre_crack(0.5) * math.sqrt(math.pi * 0.5) == pytest.approx(1.4867, abs=1e-4)
