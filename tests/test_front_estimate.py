"""Issue 39: K's error estimate along 3D fronts (one more solve on the
similar mesh with every size times sqrt(2)), the default 3D grading that
scales with tip_h, and --accuracy in 3D. The convergence studies are
demos/front_estimate.py's (docs/sifs.md); these tests run small meshes and
check the pieces against closed forms."""
import json
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import cracklip as cl
from cracklip import cli
from cracklip.analysis.accuracy import RHO, Level, estimate, neighbour_max
from cracklip.analysis.front_match import FrontPiece, carry_over
from cracklip.exact.embedded_cracks import inclined_penny_k
from cracklip.io.scene_file import load_scene_file
from cracklip.scene.crack_surface import EllipticalCrack, PolygonCrack
from cracklip.scene.mesh_3d import FRONT_GROWTH, crack_refinements, crack_size, create_box, similar_mesh

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENES = ROOT / "demos" / "scenes"


def _loop(n: int, phase: float = 0.0) -> np.ndarray:
    t = phase + 2 * math.pi * np.arange(n) / n
    return np.column_stack([np.cos(t), np.sin(t), np.zeros(n)])


def test_carry_over_along_a_loop_and_an_open_piece():
    """K of one mesh's front points at another's: K_II of the inclined penny
    (cos omega) on 20 points carried to 31 others errs by less than 5e-4 of
    its amplitude (a cubic spline in arc length; linear: 1e-2)."""
    x = _loop(20)
    K = np.column_stack(inclined_penny_k(1.0, math.pi / 4, 1.0, 0.3, np.arctan2(x[:, 1], x[:, 0])))
    y = _loop(31, 0.1)
    exact = np.column_stack(inclined_penny_k(1.0, math.pi / 4, 1.0, 0.3, np.arctan2(y[:, 1], y[:, 0])))
    got = carry_over(y, [FrontPiece(x, K, True)])
    assert np.abs(got - exact).max() < 5e-4 * np.abs(exact).max()
    # An open piece (a half circle, its ends included) and a point beyond its end (clipped to the end).
    t = np.linspace(0.0, math.pi, 12)
    arc = np.column_stack([np.cos(t), np.sin(t), np.zeros(12)])
    piece = FrontPiece(arc, np.column_stack([np.sin(t)]), False)
    s = np.linspace(0.05, math.pi - 0.05, 7)
    got = carry_over(np.column_stack([np.cos(s), np.sin(s), np.zeros(7)]), [piece])
    assert np.abs(got[:, 0] - np.sin(s)).max() < 2e-3
    assert carry_over(np.array([[1.5, -0.2, 0.0]]), [piece])[0, 0] == pytest.approx(0.0, abs=1e-12)


def test_neighbour_max_wraps_round_a_loop_and_stops_at_open_ends():
    rows = [{"crack": 0, "piece": p, "s": float(s)} for p, n in ((0, 5), (1, 4)) for s in range(n)]
    v = np.array([[3.0], [0.0], [0.0], [0.0], [1.0], [0.0], [2.0], [0.0], [0.0]])
    out = neighbour_max(v, rows, {(0, 0): True, (0, 1): False})
    assert out[:5, 0].tolist() == [3.0, 3.0, 0.0, 1.0, 3.0]   # the loop's last point sees its first
    assert out[5:, 0].tolist() == [2.0, 2.0, 2.0, 0.0]        # the open piece's ends do not wrap


def _scattered_level(f: float, n: int, phase: float) -> Level:
    """A loop of n points at element sizes f: K_I = 1 - 0.01 f^2 and K_III =
    0, both with a scatter of +-2e-4 alternating along the front (opposite
    on the run's mesh, f = 1, and the other)."""
    x = _loop(n, phase)
    noise = 2e-4 * (-1.0) ** np.arange(n) * (1.0 if f == 1.0 else -1.0)
    rows = [{"crack": 0, "piece": 0, "point": i, "s": 2 * math.pi * i / n, "position": x[i].tolist(),
             "K_I": 1.0 - 0.01 * f ** 2 + noise[i], "K_II": 0.0, "K_III": noise[i], "free_surface": False}
            for i in range(n)]
    return Level(f, 10 * n, 0.0, [rows], front=True, closed={(0, 0): True}, lengths={(0, 0): 2 * math.pi})


def test_estimate_of_a_front_with_scatter():
    """Two similar meshes (sizes sqrt(2) and 1) of a loop: K = 1 - 0.01 f^2
    plus a scatter of +-2e-4 alternating along the front. The estimate is
    the fit along the front of K's difference between the meshes over
    sqrt(2) - 1 plus the scatter (the smaller of K's about its fit and of
    the difference's about its fit): at least the true error 0.01 + 2e-4
    at every point (2.4 times it at p = 2), and K_III's estimate is the
    scatter's only, the run's own 2e-4 (less where the difference's is
    smaller), not amplified by 1 / (sqrt(2) - 1)."""
    coarse, fine = _scattered_level(RHO, 14, 0.05), _scattered_level(1.0, 20, 0.0)
    est = estimate([coarse, fine])
    for i in range(20):
        row = est[(0, 0, i)]
        assert row["K_I_error"] >= 0.01 and row["K_I_error"] == pytest.approx(0.01 * (RHO ** 2 - 1) / (RHO - 1),
                                                                               abs=2.5e-3)
        assert 0.0 < row["K_III_error"] <= 2e-4 * (1 + 1e-9)
        assert row["K_I_rate"] is None and row["K_I_extrapolated"] is None
        assert len(row["K_I_levels"]) == 2
    assert max(est[(0, 0, i)]["K_III_error"] for i in range(20)) == pytest.approx(2e-4, rel=1e-9)


def _with_asked_positions(level: Level, per_gap: int) -> Level:
    """The level with `per_gap` rows asked for between every two front points
    of its loop (options.sif_angle_step: point None, K_source
    "interpolation", K the spline through the points' K)."""
    from cracklip.fracture.front_sampling import interpolate
    rows = level.rows[0]
    length = level.lengths[(0, 0)]
    s = np.array([r["s"] for r in rows])
    K = np.array([[r[m] for m in ("K_I", "K_II", "K_III")] for r in rows])
    gaps = np.diff(np.append(s, length))
    at = np.concatenate([s[i] + gaps[i] * np.arange(1, per_gap + 1) / (per_gap + 1) for i in range(len(s))])
    Ka = interpolate(s, K, at, length, True)
    extra = [{"crack": 0, "piece": 0, "point": None, "s": float(t), "position": [math.cos(t), math.sin(t), 0.0],
              "K_I": float(k[0]), "K_II": float(k[1]), "K_III": float(k[2]), "free_surface": False,
              "K_source": "interpolation"} for t, k in zip(at, Ka)]
    both = sorted(rows + extra, key=lambda r: r["s"])
    return Level(level.size_factor, level.dofs, 0.0, [both], front=True, closed=level.closed, lengths=level.lengths)


def test_asked_positions_do_not_change_the_estimate():
    """Rows asked for between front points (every 5 degrees of a corner
    crack: K interpolated, no point index) are no independent values of K:
    the estimate at the front points is the same with and without them, on
    either mesh, with and without the fit along the front, and an asked
    row's error is the larger of its two neighbouring points'. Counting
    them as points changed a flange corner crack's estimates at its 3
    interior points from 72.7, 25.0, 72.3 to 27.4, 15.6, 27.5 MPa sqrt(mm),
    fitted K on 3 interior points, and put 3.5 between 27.4 and 15.6."""
    coarse, fine = _scattered_level(RHO, 14, 0.05), _scattered_level(1.0, 20, 0.0)
    for smooth in (False, True):
        plain = estimate([coarse, fine], smooth=smooth)
        asked = estimate([_with_asked_positions(coarse, 2), _with_asked_positions(fine, 3)], smooth=smooth)
        for i in range(20):
            for key in ("K_I_error", "K_III_error", "K_I_smoothed" if smooth else "K_I_levels"):
                assert asked[(0, 0, i)][key] == pytest.approx(plain[(0, 0, i)][key], rel=1e-12, abs=1e-15)
        labels = [k for k in asked if isinstance(k[2], str)]
        assert len(labels) == 60
        s_points = [2 * math.pi * i / 20 for i in range(20)]
        for key in labels:
            s = float(key[2][2:])
            i = int(np.searchsorted(s_points, s)) - 1
            near = [plain[(0, 0, i)]["K_I_error"], plain[(0, 0, (i + 1) % 20)]["K_I_error"]]
            assert asked[key]["K_I_error"] == pytest.approx(max(near), rel=1e-12)


def _ellipse_level(f: float, n: int, phase: float, a: float = 1.0, b: float = 0.5) -> tuple[Level, np.ndarray]:
    """A loop of n points equally spaced in arc length (from `phase` of the
    perimeter on) along the ellipse a x b, K_I = Irwin's exact K times (1 -
    0.01 f^2 (1 + 0.5 cos 2 phi)) plus a scatter of +-1e-3 of K's scale
    (alternating along the front, opposite on the two meshes); the Level
    and the exact K_I. The error falls as f^2 (K's rate with geometric
    enrichment)."""
    from cracklip.exact.embedded_cracks import irwin_k
    ph = np.linspace(0.0, 2 * math.pi, 4001)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(a * np.cos(ph)), np.diff(b * np.sin(ph))))])
    s = np.mod(phase + np.arange(n) / n, 1.0) * arc[-1]
    phi = np.interp(s, arc, ph)
    exact = irwin_k(1.0, a, b, phi)
    noise = 1e-3 * exact.max() * (-1.0) ** np.arange(n) * (1.0 if f == 1.0 else -1.0)
    K = exact * (1.0 - 0.01 * f ** 2 * (1.0 + 0.5 * np.cos(2 * phi))) + noise
    rows = [{"crack": 0, "piece": 0, "point": i, "s": float(np.mod(s[i] - s[0], arc[-1])), "free_surface": False,
             "position": [a * math.cos(phi[i]), b * math.sin(phi[i]), 0.0], "K_I": float(K[i]), "K_II": 0.0,
             "K_III": 0.0} for i in range(n)]
    return Level(f, 10 * n, 0.0, [rows], front=True, closed={(0, 0): True}, lengths={(0, 0): float(arc[-1])}), exact


def test_estimate_along_an_ellipse_follows_k_variation():
    """Irwin's ellipse b/a = 0.5 (K_I from 0.71 to 1 of its largest along
    the front: the harmonics 0, 2, 4, ... of the angle) on 17 points (b/6)
    and the finer mesh's 24, K erring by 0.5-1.1 % (rate 2) plus a scatter of
    +-0.1 %: the estimate is at least the true error at every point and at
    most 3 % of the K scale (the rate 1 assumed: 1.7 times a smooth
    error). A fit of K itself along the front with one term per four
    points (the first harmonic only) left K's variation in the
    estimate: 12-36 % of the K scale on the meshes of the Irwin study."""
    run, exact = _ellipse_level(1.0, 17, 0.013)
    finer, _ = _ellipse_level(1 / RHO, 24, 0.29)
    est = estimate([run, finer], of=0)
    err = np.array([est[(0, 0, i)]["K_I_error"] for i in range(17)])
    true = np.abs(np.array([r["K_I"] for r in run.rows[0]]) - exact)
    scale = exact.max()
    assert 0.008 < true.max() / scale < 0.015
    assert np.all(err >= true)
    assert err.max() < 0.03 * scale
    assert np.median(err / true) < 3.0


def test_smoothed_front_k_and_its_estimate():
    """options.sif_smoothing = "fit" on the loop of
    test_estimate_of_a_front_with_scatter (K = 1 - 0.01 f^2, scatter +-2e-4
    alternating, opposite on the two meshes): K is reported as its fit along
    the front, 0.99 at every point (the scatter gone: the true error 0.01
    everywhere instead of 0.0098-0.0102), K_III's scatter fitted to 0, and
    the estimate is the same fit's difference between the meshes over
    sqrt(2) - 1 plus a standard deviation of the fit: 2.4 times the true
    error at every point (p = 2), within [1, 4]; the estimate without the
    fit is kept beside it."""
    coarse, fine = _scattered_level(RHO, 14, 0.05), _scattered_level(1.0, 20, 0.0)
    plain = estimate([coarse, fine])
    est = estimate([coarse, fine], smooth=True)
    for i in range(20):
        row = est[(0, 0, i)]
        assert row["K_I_smoothed"] == pytest.approx(0.99, abs=1e-12)
        assert row["K_III_smoothed"] == pytest.approx(0.0, abs=1e-12)
        assert 1.0 <= row["K_I_error"] / 0.01 <= 4.0
        assert row["K_I_error"] == pytest.approx(0.01 * (RHO ** 2 - 1) / (RHO - 1), abs=1.5e-3)
        assert row["K_I_error_unsmoothed"] == plain[(0, 0, i)]["K_I_error"]
        assert 0.0 < row["K_III_error"] < 2e-4


def test_smoothing_leaves_an_ellipse_k_it_cannot_fit():
    """The ellipse b/a = 0.5 of test_estimate_along_an_ellipse_follows_k_variation
    (17 points, K_I in the harmonics 0, 2, 4, ...): a fit of at most one
    term per four points misses K_I's shape (leave-one-out alone takes the
    mean: K_I off by 17 % of the K scale, against 1.1 % as computed), the
    finer mesh's residuals share it, so K_I is not fitted (K_I_smoothed
    None) and its estimate is the one without the fit."""
    from cracklip.fracture.front_fit import loo_fit, piece_basis
    run, exact = _ellipse_level(1.0, 17, 0.013)
    finer, _ = _ellipse_level(1 / RHO, 24, 0.29)
    K = np.array([[r["K_I"]] for r in run.rows[0]])
    basis, sizes = piece_basis(np.array([r["s"] for r in run.rows[0]]), True, run.lengths[(0, 0)], 17 // 4)
    blind, _ = loo_fit(basis, np.ones(17, dtype=bool), K, sizes)
    miss = np.abs(blind[:, 0] - exact).max()
    assert miss > 0.1 * exact.max() and miss > 10 * np.abs(K[:, 0] - exact).max()
    plain = estimate([run, finer], of=0)
    est = estimate([run, finer], of=0, smooth=True)
    for i in range(17):
        assert est[(0, 0, i)]["K_I_smoothed"] is None
        assert est[(0, 0, i)]["K_I_error"] == plain[(0, 0, i)]["K_I_error"]


def test_front_rate_observed_over_three_meshes():
    """Three similar meshes (sizes sqrt(2), 1, 1/sqrt(2)) of a loop with K =
    1 - 0.01 f^2: the rate 2 observed from the fits' differences, the
    finest K's error 1.25 |dK| / (2 - 1) = 1.25 times its true error."""
    def level(f: float, n: int) -> Level:
        x = _loop(n, 0.03 * n)
        rows = [{"crack": 0, "piece": 0, "point": i, "s": 2 * math.pi * i / n, "position": x[i].tolist(),
                 "K_I": 1.0 - 0.01 * f ** 2, "K_II": 0.0, "K_III": 0.0, "free_surface": False} for i in range(n)]
        return Level(f, 10 * n, 0.0, [rows], front=True, closed={(0, 0): True}, lengths={(0, 0): 2 * math.pi})
    levels = [level(RHO, 14), level(1.0, 20), level(1 / RHO, 28)]
    est = estimate(levels)
    row = est[(0, 0, 5)]
    assert row["K_I_rate"] == pytest.approx(2.0, abs=1e-6)
    assert row["K_I_error"] == pytest.approx(1.25 * 0.01 * 0.5, rel=1e-6)
    # K fitted along the front (--accuracy with options.sif_smoothing = "fit"): the same, K itself fitted exactly
    fitted = estimate(levels, smooth=True)[(0, 0, 5)]
    assert fitted["K_I_smoothed"] == pytest.approx(1.0 - 0.01 * 0.5, abs=1e-12)
    assert fitted["K_I_error"] == pytest.approx(1.25 * 0.01 * 0.5, rel=1e-6)


def test_crack_size_and_the_default_grading():
    """The crack's size is twice its area over its perimeter (a penny's
    radius, 0.648 for the ellipse 1 x 0.5, a square's half side); the
    default grading grows by FRONT_GROWTH h_front per crack size, so that
    halving h_front halves every size near the crack."""
    penny = EllipticalCrack((0, 0, 0), (0, 0, 1), 2.0)
    assert crack_size(penny) == pytest.approx(2.0, rel=1e-12)
    assert crack_size(EllipticalCrack((0, 0, 0), (0, 0, 1), 1.0, b=0.5)) == pytest.approx(0.6485, abs=1e-4)
    assert crack_size(PolygonCrack(np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]], float))) == \
        pytest.approx(1.0)
    for h_front in (0.2, 0.1):
        (fr,) = crack_refinements([penny], h_front, 4.0, h_surface=4.0)
        growth = (4.0 - h_front) / fr.radius
        assert growth == pytest.approx(FRONT_GROWTH * h_front / 2.0)


def test_similar_mesh_scales_every_size():
    """The recipe with every size setting times sqrt(2) (h, h_front; the
    grading's radius kept): the front's elements sqrt(2) larger, fewer
    cells."""
    crack = EllipticalCrack((0, 0, 0), (0, 0, 1), 1.0)
    md = create_box(-3, -3, -3, 3, 3, 3, 1.5, fronts=crack_refinements([crack], 0.12, 1.5))
    coarse = similar_mesh(md, RHO)
    assert coarse.size_factor == pytest.approx(RHO) and coarse.front_refinements[0].h_front == pytest.approx(0.12 * RHO)

    def front_edges(m):
        x = m.mesh.geometry.x
        c = m.mesh.geometry.dofmap.array.reshape(-1, 4)
        near = np.abs(np.linalg.norm(x[c].mean(axis=1)[:, :2], axis=1) - 1.0) + np.abs(x[c].mean(axis=1)[:, 2]) < 0.3
        return np.median(np.linalg.norm(x[c[near, 1]] - x[c[near, 0]], axis=1)), len(c)
    (e0, n0), (e1, n1) = front_edges(md), front_edges(coarse)
    assert e1 / e0 == pytest.approx(RHO, rel=0.15)
    assert 1.8 < n0 / n1 < RHO ** 3  # 2^(3/2) where the graded sizes fill the part; 1.96 in this small box


def test_run_the_inclined_penny_with_the_estimate(tmp_path, capsys):
    """`run` on a 3D part makes the estimate by default: K_*_error in
    results.json's sifs and front.csv, the summary's largest estimated error,
    the front's line with it. On the inclined penny at a/4 (a front coarser
    than a tenth of the crack: the estimate's mesh is the finer one, every
    size times 1/sqrt(2); K 1-3 % off the exact, mixed modes) the
    estimate is of the error's size."""
    from test_scenes_3d import SMALL_3D
    args = ["run", str(SCENES / "inclined_penny.toml"), "--set", "outputs.vtu=false", "--set", "outputs.png=false",
            "--out", str(tmp_path)] + [a for o in SMALL_3D["inclined_penny"] for a in ("--set", o)]
    assert cli.main(args) == 0
    out = capsys.readouterr().out
    assert "K +- its estimated discretisation error (from one more solve, every element size times 0.707" in out
    assert "estimated error up to" in out
    res = json.loads((tmp_path / "results.json").read_text())
    est = res["error_estimate"]
    assert est["size_factors"] == [1.0, pytest.approx(1 / RHO)] and est["dofs"][0] < est["dofs"][1]
    assert est["largest_relative_error"] > 0.0 and est["largest_at"]["mode"] in ("K_I", "K_II", "K_III")
    x = np.array([r["position"] for r in res["sifs"]])
    n = np.array([1.0, 0.0, 1.0]) / math.sqrt(2.0)
    shear = np.array([-1.0, 0.0, 1.0]) / math.sqrt(2.0)   # the load's in-plane part
    omega = np.arctan2(x @ np.cross(n, shear), x @ shear)
    exact = np.column_stack(inclined_penny_k(1.0, math.pi / 4, 1.0, 0.3, omega))
    errs, ests = [], []
    for r, k in zip(res["sifs"], exact):
        assert all(r[f"{m}_error"] > 0.0 for m in ("K_I", "K_II", "K_III")) and len(r["K_I_levels"]) == 2
        errs.append(np.linalg.norm(np.array([r["K_I"], r["K_II"], r["K_III"]]) - k))
        ests.append(np.linalg.norm([r["K_I_error"], r["K_II_error"], r["K_III_error"]]))
        assert 0.005 < errs[-1] / np.linalg.norm(exact, axis=1).max() < 0.05
    # a/4 is below the estimate's range (K not yet asymptotic: the penny at
    # a/5 gave 0.75-1.25 of its error); here, with six front points, the
    # estimate is 0.46-1.12 of the error: of its size, not a bound. The
    # pointwise bracket is asserted where it holds: the quick demo test at
    # a/7.07.
    assert all(1.0 / 3.0 < e / r < 3.0 for e, r in zip(ests, errs)), [e / r for e, r in zip(ests, errs)]
    header = (tmp_path / "front.csv").read_text().splitlines()[0].split(",")
    assert {"K_I_error", "K_II_error", "K_III_error"} <= set(header)
    # Without it: no estimate, one solve.
    assert cli.main(args + ["--no-estimate"]) == 0
    assert json.loads((tmp_path / "results.json").read_text())["error_estimate"] is None


def test_accuracy_in_3d_refines_every_size():
    """options.accuracy on a 3D part: the scene's mesh, then sizes times
    2^(-1/2) per level (a front coarser than a tenth of the crack: no
    coarser mesh first); an unreachable target after one level is warned
    about with the level count."""
    sf = load_scene_file(SCENES / "penny_crack.toml", ["mesh.h=2.0", "mesh.tip_h=0.3", "options.accuracy=1e-4",
                                                       "options.accuracy_levels=1"])
    sol = cl.solve(sf.scene)
    est = sol.error_estimate
    assert est["size_factors"] == [1.0, pytest.approx(1 / RHO)] and est["refinement_levels"] == 1
    assert est["dofs"][0] < est["dofs"][1] and est["reached"] is False
    (w,) = [w for w in sol.warnings if w.code == "accuracy"]
    assert "not reached in 1 refinement level" in w.message
    assert all(len(r["K_I_levels"]) == 2 for r in sol.stress_intensity_factors(0))


def test_3d_msh_file_has_no_estimate(tmp_path):
    """A 3D .msh file cannot be made again at other sizes: accuracy is
    refused before meshing, the default estimate is left out."""
    from cracklip.errors import InputError, MeshError
    from cracklip.scene.mesh_3d import read_msh_3d
    path = tmp_path / "p.toml"
    path.write_text('[mesh]\nkind = "file"\npath = "x.msh"\n[material]\nE = 1.0\nnu = 0.3\n[[cracks]]\n'
                    'ellipse = { center = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0], a = 1.0 }\n'
                    '[[dirichlet]]\ntag = "zmin"\n[options]\naccuracy = 0.01\n')
    with pytest.raises(InputError, match="refines the mesh, which a 3D .msh file cannot be"):
        load_scene_file(path)
    import gmsh
    from cracklip.scene.mesh import _gmsh
    msh = tmp_path / "b.msh"
    g = _gmsh()
    g.model.add("b")
    g.model.occ.addBox(-2, -2, -2, 4, 4, 4)
    g.model.occ.synchronize()
    g.model.addPhysicalGroup(3, [1], 1)
    g.model.addPhysicalGroup(2, [s for _, s in g.model.getEntities(2)], 1)
    g.model.setPhysicalName(2, 1, "faces")
    g.option.setNumber("Mesh.MeshSizeMax", 1.0)
    g.model.mesh.generate(3)
    gmsh.write(str(msh))
    g.model.remove()
    with pytest.raises(MeshError, match="cannot be made from a 3D .msh file"):
        similar_mesh(read_msh_3d(msh), RHO)


def test_front_estimate_demo_quick(tmp_path):
    out = tmp_path / "fe.json"
    env = {"PYTHONPATH": str(ROOT / "python"), "MPLBACKEND": "Agg", "PATH": "/usr/bin:/bin"}
    subprocess.run([sys.executable, str(ROOT / "demos" / "front_estimate.py"), "--quick", "--parts", "estimate",
                    "--json", str(out), "--quiet"], check=True, env=env, cwd=ROOT, capture_output=True, timeout=600)
    res = json.loads(out.read_text())
    rows = res["estimate"]
    assert [r["size_over_h"] for r in rows] == [pytest.approx(5 * math.sqrt(2.0))]
    (r,) = rows
    # a/7.07: a front coarser than a tenth of the crack, so the estimate's
    # mesh is the finer one (a/10); measured 1.27-2.16 times the true error
    assert r["estimate_dofs"] > r["dofs"]
    assert r["brackets"] and r["within_4"] and r["estimate_max"] >= r["true_max"] > 0.0
    assert (tmp_path / "fe" / "points.csv").is_file() and (tmp_path / "fe" / "front_estimate.png").is_file()


def test_estimate_on_a_coarse_irwin_ellipse(tmp_path):
    """The embedded ellipse b/a = 0.5 at b/6 (demos/front_estimate.py's
    scene; the estimate's mesh the finer one, b/8.5), against Irwin's exact
    K_I: K errs by up to 1.8 % of the K scale; the estimate is at least
    0.9 times the true error at every front point (measured 1.03) and at
    most 3 % of the K scale (measured 2.0 %; a fit of each mesh's K along
    the front gave 60 %)."""
    sys.path.insert(0, str(ROOT / "demos"))
    import front_estimate as fe
    row = fe.compare("irwin_0.5", 6.0, fe.solve_case("irwin_0.5", 6.0, True, tmp_path))
    assert row["estimate_dofs"] > row["dofs"]
    assert 0.005 < row["true_max"] < 0.03
    assert row["ratio_min"] >= 0.9
    assert row["estimate_max"] < 0.03


def test_fitted_k_on_a_small_penny(tmp_path):
    """The penny at a/7.07 (demos/front_estimate.py's scene, the estimate's
    mesh the finer a/10) with options.sif_smoothing = "fit": K_I is reported
    as its fit along the front (the computed K kept as K_I_unsmoothed, G
    from the fitted K), which errs less than the computed K at its worst
    point (measured 1.15 % against 1.35 % of the K scale), and the estimate
    of the fitted K is at least its true error and at most 4 times it at
    every front point (measured 1.45-1.47; the computed K's own: 1.34-1.91)."""
    sys.path.insert(0, str(ROOT / "demos"))
    import front_estimate as fe
    run = fe.solve_case("penny", 5 * math.sqrt(2.0), True, tmp_path, smoothing="fit")
    row = fe.compare("penny", 5 * math.sqrt(2.0), run)
    assert "K_I" in row["fitted_modes"]
    assert row["true_max"] < 0.95 * row["unsmoothed"]["true_max"]
    assert row["brackets"] and row["within_4"] and 1.0 <= row["ratio_min"] <= row["ratio_max"] <= 4.0
    KI = np.array([r["K_I"] for r in run["rows"]])
    assert np.ptp(KI) < 0.2 * np.ptp([r["K_I_unsmoothed"] for r in run["rows"]])
    r = run["rows"][0]
    Ep = 1.0 / (1 - 0.3 ** 2)
    assert r["G"] == pytest.approx((r["K_I"] ** 2 + r["K_II"] ** 2) / Ep + r["K_III"] ** 2 * (1 + 0.3), rel=1e-12)


def test_front_summary_names_the_fitted_modes():
    """The printed summary says which modes are reported fitted along the
    front and where the computed K is."""
    from cracklip.cli import front_summary
    rows = [{"crack": 0, "crack_name": "c", "point": i, "position": [float(i), 0.0, 0.0], "parametric_angle": None,
             "free_surface": False, "domain_clear": True, "K_I": 1.0, "K_II": 0.1 * i, "K_III": 0.0,
             "K_I_unsmoothed": 1.0 + 0.01 * (-1) ** i, "K_II_unsmoothed": 0.1 * i, "K_III_unsmoothed": 0.0}
            for i in range(4)]
    text = "\n".join(front_summary(rows, None, None))
    assert 'K_I fitted along the front (options.sif_smoothing = "fit"' in text and "K_II," not in text
    assert not any("fitted" in line for line in front_summary([{k: v for k, v in r.items() if "unsmoothed" not in k}
                                                               for r in rows], None, None))


def test_front_summary_marks_flagged_extremes():
    """The printed min and max say when they sit at a free-surface end (the
    end value) or at a point whose K is NOT reliable, and name a position
    between front points by its arc length, not 'point None'."""
    from cracklip.cli import front_summary
    rows = [{"crack": 0, "crack_name": "c", "point": i, "s": float(i), "position": [float(i), 0.0, 0.0],
             "parametric_angle": None, "free_surface": i == 0, "domain_clear": i != 2, "K_I": K, "K_II": 0.0,
             "K_III": 0.0} for i, K in enumerate([3.0, 2.0, 1.0, 2.0])]
    rows.append(dict(rows[1], point=None, s=1.5, K_II=-1.0))
    text = "\n".join(front_summary(rows, None, None))
    assert "max 3 at point 0 (0, 0, 0, the end value at a free surface)" in text
    assert "min 1 at point 2 (2, 0, 0, NOT reliable)" in text
    assert "K_II: min -1 at s = 1.5 (between front points) (1, 0, 0)" in text and "point None" not in text


def test_worst_estimate_between_front_points_is_named_by_its_position():
    """The largest estimated error of K sits at a position asked for between
    front points (options.sif_angle_step: `point` None) on a corner crack's
    coarse front: the summary line and the `discretisation` warning named
    it 'point None' / 'front point None' and counted the interpolated rows as
    front points; they now give its arc length and parametric angle."""
    import math
    from types import SimpleNamespace
    from cracklip.cli import front_summary
    from cracklip.post import checks
    rows = [{"crack": 0, "crack_name": "c", "tip": None, "point": i, "s": float(i), "x": float(i), "y": 0.0,
             "z": 0.0, "position": [float(i), 0.0, 0.0], "parametric_angle": 0.1 * i, "free_surface": False,
             "domain_clear": True, "K_I": 1.0, "K_II": 0.0, "K_III": 0.0, "K_I_error": 0.001, "K_II_error": 0.0,
             "K_III_error": 0.0, "K_I_levels": [1.0, 1.0]} for i in range(4)]
    rows.append(dict(rows[1], point=None, s=1.5, x=1.5, position=[1.5, 0.0, 0.0], parametric_angle=0.15,
                     K_I_error=0.05, K_I_levels=[1.0, 1.05]))
    est = {"K_scale": 1.0, "target": None, "size_factors": [1.0, math.sqrt(2)], "of_size_factor": 1.0,
           "meshes": "every element size times 1.41", "largest_relative_error": 0.05}
    text = "\n".join(front_summary(rows, None, None))
    assert "point None" not in text
    assert "estimated error up to 0.05 at s = 1.5 (between front points) (1.5, 0, 0, parametric angle 8.6 deg)" in text
    sol = SimpleNamespace(error_estimate=est, model=SimpleNamespace(cracks=[SimpleNamespace(crack=SimpleNamespace(
        name="c"))]), stress_intensity_factors=lambda crack: rows)
    (code, message), = checks.estimate(sol)
    assert code == "discretisation" and "None" not in message
    assert message.startswith("the front at s = 1.5 (between front points, parametric angle 8.594 deg) of crack 'c'")
    assert "(1 of 5 positions along its front above 1 %)" in message
    # A tie (an asked row takes the larger estimate of its two neighbouring points): the point is named.
    rows[2].update(K_I_error=0.05, K_I_levels=[1.0, 1.05])
    (code, message), = checks.estimate(sol)
    assert message.startswith("front point 2 of crack 'c'") and "(2 of 5 positions" in message
    text = "\n".join(front_summary(rows, None, None))
    assert "estimated error up to 0.05 at point 2 (2, 0, 0, parametric angle 11.5 deg)" in text


def test_demo_cap_scene_loads(tmp_path):
    """demos/front_estimate.py's spherical cap: the STL next to the scene,
    nu = 0.22, hydrostatic tension on all six faces."""
    sys.path.insert(0, str(ROOT / "demos"))
    import front_estimate as fe
    from cracklip.exact import spherical_cap
    from cracklip.scene.crack_surface import SurfaceCrack
    path = tmp_path / "cap.toml"
    path.write_text(fe.scene_text("spherical_cap", 5.0))
    alpha = spherical_cap.REFERENCE_ALPHA_DEG
    v, t = spherical_cap.cap_triangulation(1.0, alpha, 0.1)
    spherical_cap.write_stl(tmp_path / "cap.stl", v, t)
    sf = load_scene_file(path)
    assert isinstance(sf.scene.cracks[0], SurfaceCrack) and sf.scene.material.nu == pytest.approx(0.22)
    assert sorted(tr.where for tr in sf.scene.tractions) == ["xmax", "xmin", "ymax", "ymin", "zmax", "zmin"]
