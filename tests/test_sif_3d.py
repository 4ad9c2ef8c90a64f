"""K_I, K_II, K_III along 3D crack fronts (issue 28) on small meshes.

A penny crack of radius 1 in a box of half-width 4 (E = 1, nu = 0.3),
a / h_front = 6, sizes growing by 0.1 per unit distance up to 1, vector
front functions within 0.25 of the front: 3.6e4 dofs, 9 front points.
Measured there (remote tension 1): K_I +0.63 % above 2 sigma sqrt(a/pi) on
average (RMS 0.65 %, max 0.91 %: the box of half-width 4 raises K by about
that much; demos/front_sifs.py converges the penny to 0.15 % RMS at a/h = 20
in a box of half-width 10), |K_II| <= 1.6e-3 and |K_III| <= 0.7e-3 of K.
A wrong method (no curvature terms, a wrong normalisation, a wrong sign)
moves K by several per cent. These scenes keep the 9 front points (hats
of 3 elements, Options.sif_points = 8) they were measured with; the
default (at least 16 points where hats of 2 elements fit: 13 here) is
test_minimum_points_on_a_coarse_penny's.
"""
from __future__ import annotations

import csv
import json
import math
import pathlib

import numpy as np
import pytest

import cracklip as cl
from cracklip import cli
from cracklip.exact.embedded_cracks import inclined_penny_k, penny_k
from cracklip.io.outputs import FRONT_COLUMNS
from cracklip.scene.crack_surface import EllipticalCrack
from cracklip.scene.mesh_3d import create_box, crack_refinements

L, H_FAR, N = 4.0, 1.0, 6
K0 = penny_k(1.0, 1.0)
SCENES = pathlib.Path(__file__).resolve().parents[1] / "demos" / "scenes"


def penny(beta: float = 90.0, pressure: float = 0.0, tension: float = 1.0) -> cl.Scene:
    b = math.radians(beta)
    normal = (0.0, 0.0, 1.0) if beta == 90.0 else (math.cos(b), 0.0, math.sin(b))
    crack = EllipticalCrack((0.0, 0.0, 0.0), normal, 1.0, axis=(0.0, 1.0, 0.0), name="penny", pressure=pressure)
    mesh = create_box(-L, -L, -L, L, L, L, H_FAR, fronts=crack_refinements([crack], 1.0 / N, H_FAR, growth=0.1))
    tractions = [cl.Traction("zmax", (0.0, 0.0, tension)), cl.Traction("zmin", (0.0, 0.0, -tension))] if tension \
        else []
    return cl.Scene(mesh, cl.Material(1.0, 0.3), cracks=[crack],
                    dirichlet=[cl.Dirichlet((-L, -L, -L)), cl.Dirichlet((L, -L, -L), 1),
                               cl.Dirichlet((L, -L, -L), 2), cl.Dirichlet((-L, L, -L), 2)],
                    tractions=tractions, options=cl.Options(enrichment="vector", radius=0.25, solver="iterative",
                                                            sif_points=8))


def sifs_of(solution) -> tuple[list[dict], np.ndarray]:
    rows = solution.stress_intensity_factors(0)
    return rows, np.array([[r["K_I"], r["K_II"], r["K_III"]] for r in rows])


def sifs(scene) -> tuple[list[dict], np.ndarray]:
    return sifs_of(cl.solve(scene))


@pytest.fixture(scope="module")
def tension_solution():
    return cl.solve(penny())


@pytest.fixture(scope="module")
def tension(tension_solution):
    return sifs_of(tension_solution)


def test_penny_tension(tension):
    """K_I at every front point near 2 sigma sqrt(a/pi) (measured +0.63 % on
    average, 0.91 % at worst: asserted within [0.2, 1.2] %), K_II, K_III
    below 2.5e-3 of K, each K with its three domains' spread below 1 %."""
    rows, K = tension
    assert len(rows) >= 8
    e = K[:, 0] / K0 - 1.0
    assert 0.002 < e.mean() < 0.010, e
    assert np.abs(e).max() < 0.012, e
    assert np.abs(K[:, 1:]).max() < 2.5e-3 * K0
    for r in rows:
        assert r["K_I_spread"] < 0.01 * K0 and r["K_II_spread"] >= 0.0 and r["K_III_spread"] >= 0.0
        assert not r["free_surface"] and r["domain_clear"]
        assert r["G"] == pytest.approx((1 - 0.09) * (r["K_I"] ** 2 + r["K_II"] ** 2) + 1.3 * r["K_III"] ** 2)


def test_minimum_points_on_a_coarse_penny(tension_solution):
    """The default sampling (Options.sif_points = 16) on the same solution:
    on the loop of length 2 pi with front elements of 0.227 the count does
    not shorten the hats below COUNT_HAT_ELEMENTS = 3 elements (9 points,
    as the spacing rule alone); two-element hats (13 points) had K_I up to
    1.20 % off here and 4.5 % low everywhere on a penny at a/4."""
    from cracklip.fracture.front_points import COUNT_HAT_ELEMENTS
    from cracklip.fracture.sif_3d import compute_front_sifs
    opts = tension_solution.model.scene.options
    old = opts.sif_points
    try:
        opts.sif_points = 16
        rows, _ = compute_front_sifs(tension_solution)
    finally:
        opts.sif_points = old
    K = np.array([[r["K_I"], r["K_II"], r["K_III"]] for r in rows])
    h = rows[0]["element_size"]
    assert len(rows) == int(2 * math.pi / (COUNT_HAT_ELEMENTS * h) + 0.1) == 9
    e = K[:, 0] / K0 - 1.0
    assert 0.002 < e.mean() < 0.010 and np.abs(e).max() < 0.012, e
    assert np.abs(K[:, 1:]).max() < 5e-3 * K0
    assert all(r["K_source"] == "domain" and not r["requested"] for r in rows)


def test_lip_pressure_equals_remote_tension(tension):
    """Superposition: a pressure 1 on the lips with no remote load gives the
    K of remote tension 1 (measured within 0.05 %; asserted 0.5 %)."""
    _, K_t = tension
    _, K_p = sifs(penny(pressure=1.0, tension=0.0))
    assert np.abs(K_p[:, 0] - K_t[:, 0]).max() < 0.005 * K0
    assert np.abs(K_p[:, 1:]).max() < 2.5e-3 * K0


def test_inclined_penny_modes():
    """beta = 45 degrees: K_II follows cos(omega) and K_III sin(omega) with
    the closed form's signs (omega from the shear direction s towards n x s),
    each within 2 % of the K scale on this mesh; a sign or mode mix-up would
    be off by the whole amplitude."""
    beta = math.radians(45.0)
    n = np.array([math.cos(beta), 0.0, math.sin(beta)])
    rows, K = sifs(penny(beta=45.0))
    z = np.array([0.0, 0.0, 1.0])
    s = z - (z @ n) * n
    s /= np.linalg.norm(s)
    t = np.cross(n, s)
    x = np.array([[r["x"], r["y"], r["z"]] for r in rows])
    omega = np.arctan2(x @ t, x @ s)
    Kx = np.column_stack(inclined_penny_k(1.0, beta, 1.0, 0.3, omega))
    scale = np.linalg.norm(Kx, axis=1).max()
    # The shapes: least-squares amplitudes of cos and sin.
    a_II = np.sum(K[:, 1] * np.cos(omega)) / np.sum(np.cos(omega) ** 2)
    a_III = np.sum(K[:, 2] * np.sin(omega)) / np.sum(np.sin(omega) ** 2)
    assert a_II == pytest.approx(4 * 0.5 * math.sqrt(1 / math.pi) / 1.7, rel=0.03)
    assert a_III == pytest.approx(4 * 0.7 * 0.5 * math.sqrt(1 / math.pi) / 1.7, rel=0.03)
    assert np.abs(K - Kx).max() < 0.02 * scale


def test_surface_crack_front_outputs(tmp_path):
    """The shipped surface-crack scene on a coarse mesh: front.csv with its
    columns, results.json's sifs with spreads, the points where the front
    meets the free face flagged, and the coarse front warned about."""
    args = ["run", str(SCENES / "surface_crack_plate.toml"), "--out", str(tmp_path), "--quiet"]
    for o in ("mesh.h=8.0", "mesh.tip_h=0.6", "mesh.crack_h=0.0", "options.radius=1.2"):
        args += ["--set", o]
    assert cli.main(args) == 0
    with (tmp_path / "front.csv").open() as f:
        reader = csv.DictReader(f)
        assert reader.fieldnames == FRONT_COLUMNS
        rows = list(reader)
    res = json.loads((tmp_path / "results.json").read_text())
    assert len(res["sifs"]) == len(rows) >= 5
    for key in ("front_sifs.png", "front_sifs.vtu", "front.csv"):
        assert key in res["files"] and (tmp_path / key).exists()
    free = [int(r["free_surface"]) for r in rows]
    assert free[0] == 1 and free[-1] == 1 and sum(free) == 2
    # The parametric angle also in degrees, the unit options.sif_angles asks in
    # (parametric_angle is in radians: 1.5708 at the deepest point).
    for r in rows:
        assert float(r["parametric_angle_deg"]) == pytest.approx(math.degrees(float(r["parametric_angle"])),
                                                                 rel=1e-9)
    for r in res["sifs"]:
        assert {"K_I_spread", "K_II_spread", "K_III_spread"} <= set(r)
        assert r["parametric_angle"] is not None
    # The deepest front point: K_I within 10 % of Newman-Raju's at its
    # angle on this coarse mesh (a / h_front = 5).
    from cracklip.exact.newman_raju import surface_crack_k
    deep = min(res["sifs"], key=lambda r: r["y"])
    phi = math.atan2(abs(math.sin(deep["parametric_angle"])), abs(math.cos(deep["parametric_angle"])))
    assert deep["K_I"] == pytest.approx(float(surface_crack_k(100.0, 3.0, 5.0, 10.0, 20.0, phi)), rel=0.10)
    codes = [w for w in res["warnings"] if "SIF domain" in w["message"] or "K varies" in w["message"]]
    assert codes, res["warnings"]
    # The ends' K: front_sampling's end value through K kappa^(1/6) of the
    # interior points (kappa of the conic through all the front's points,
    # from the reported positions), not the ends' own domains.
    from cracklip.fracture import front_sampling
    inner = [r for r in res["sifs"] if not r["free_surface"]]
    s = np.array([r["s"] for r in inner])
    X = np.array([r["position"] for r in inner])
    every = np.array([r["position"] for r in sorted(res["sifs"], key=lambda r: r["s"])])
    L = max(r["s"] for r in res["sifs"])
    for end in (r for r in res["sifs"] if r["free_surface"]):
        assert end["K_source"] == "end_extrapolation" and end["K_domain"] is not None
        near = [r["curvature"] for r in inner if abs(r["s"] - end["s"]) <= front_sampling.END_WINDOW * L]
        window = front_sampling.end_window(L, [end["curvature"]] + near)
        k = front_sampling.conic_curvatures(every, np.vstack([end["position"], X]))
        want, _ = front_sampling.end_value(s, np.array([r["K_I"] for r in inner]), end["s"], window, k[1:], k[0], L)
        assert end["K_I"] == pytest.approx(float(want), rel=1e-9)
        plain, _ = front_sampling.end_value(s, np.array([r["K_I"] for r in inner]), end["s"], window)
        assert abs(float(plain) / end["K_I"] - 1.0) > 1e-6   # the weight does something on this ellipse


def test_hat_follows_front_curvature():
    """Front points on an ellipse a = 1, b = 0.25 (radius of curvature rho =
    (a^2 sin^2 phi + b^2 cos^2 phi)^(3/2) / (a b): b^2/a = 0.0625 at the
    ends of the major axis, a^2/b = 4 at the minor axis) with elements h =
    b/10: steps of HAT_ELEMENTS h = 0.075 where rho is larger, shortened to
    HAT_CURVATURE rho_min = 0.0625 within a hat of the ends; each step spans
    the same integral of ds / l; on a circle the steps stay equal."""
    from cracklip.fracture import front_points
    a, b, h = 1.0, 0.25, 0.025
    phi = np.linspace(0.0, 2 * np.pi, 4001)[:-1]
    x = np.column_stack([a * np.cos(phi), b * np.sin(phi)])
    seg = np.linalg.norm(np.diff(np.vstack([x, x[:1]]), axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)[:-1]])
    L = float(seg.sum())
    rho = (a * a * np.sin(phi) ** 2 + b * b * np.cos(phi) ** 2) ** 1.5 / (a * b)
    l = front_points.wanted_hats(s, 1.0 / rho, h, L, True)
    assert l.max() == pytest.approx(front_points.HAT_ELEMENTS * h)
    end = front_points.HAT_CURVATURE * b * b / a
    assert l.min() == pytest.approx(end, rel=1e-6)
    assert np.all(l[np.minimum(s, L - s) <= front_points.HAT_ELEMENTS * h] == pytest.approx(end, rel=1e-6))
    st = front_points.station_positions(s, l, L, True)
    steps = np.diff(np.append(st, L))
    sl, ll = np.append(s, L), np.append(l, l[0])
    fine = np.linspace(0.0, L, 200001)
    cum = np.concatenate([[0.0], np.cumsum(np.diff(fine) / np.interp(0.5 * (fine[1:] + fine[:-1]), sl, ll))])
    per_step = np.diff(np.interp(np.append(st, L), fine, cum))
    assert np.ptp(per_step) < 1e-3 * per_step.mean() and abs(per_step.mean() - 1.0) < 0.05
    at_end = np.argmin(np.minimum(st, L - st))       # phi = 0, the end of the major axis
    assert steps[at_end] == pytest.approx(end, rel=0.05)
    assert steps[np.argmin(np.abs(st - 0.25 * L))] == pytest.approx(front_points.HAT_ELEMENTS * h, rel=0.05)
    # a circle of radius 1 at h = 0.05: equal steps of about 3 h
    c = np.linspace(0.0, 2 * np.pi, 1001)[:-1]
    st = front_points.station_positions(c, front_points.wanted_hats(c, np.ones_like(c), 0.05, 2 * np.pi, True), 2 * np.pi,
                                  True)
    assert len(st) == round(2 * np.pi / (front_points.HAT_ELEMENTS * 0.05))
    assert np.ptp(np.diff(np.append(st, 2 * np.pi))) < 1e-9


def test_hat_deconvolution_unequal_steps():
    """The hat average of K over half-widths l- behind and l+ ahead is K +
    K' (l+ - l-) / 3 + K'' (l+^2 - l+ l- + l-^2) / 12 + O(l^3);
    hat_deconvolve solves the averages along a loop for K. K = 1 + 0.3
    sin(s) + 0.1 cos(3 s) on a loop of length 2 pi: equal steps and steps
    shrinking to a third over part of the loop leave errors far below the
    averages' (measured ratio below 1/20)."""
    from cracklip.fracture import front_points, sif_3d

    def f(s):
        return 1.0 + 0.3 * np.sin(s) + 0.1 * np.cos(3 * s)

    def average(s0, lm, lp):
        g, w = np.polynomial.legendre.leggauss(20)
        left, right = s0 - lm + 0.5 * lm * (g + 1), s0 + 0.5 * lp * (g + 1)
        num = np.sum(w * 0.5 * lm * (1 - (s0 - left) / lm) * f(left)) + \
            np.sum(w * 0.5 * lp * (1 - (right - s0) / lp) * f(right))
        return num / (0.5 * (lm + lp))

    L = 2 * np.pi
    for st in (np.linspace(0.0, L, 41)[:-1],
               front_points.station_positions(np.linspace(0, L, 2001)[:-1], np.where(
                   np.abs(np.linspace(0, L, 2001)[:-1] - 2.0) < 0.6, 0.05, 0.15), L, True)):
        lm = (st - np.roll(st, 1)) % L
        lp = (np.roll(st, -1) - st) % L
        A = np.array([average(s0, a, b) for s0, a, b in zip(st, lm, lp)])
        K = sif_3d.hat_deconvolve(A, lm, lp, True)
        raw, err = np.abs(A - f(st)).max(), np.abs(K - f(st)).max()
        assert err < raw / 20, (err, raw)


def _kinked_penny(radius: float, spacing: float, offsets: list[float]):
    """A triangulated penny (rings `spacing` apart, as a grown surface's
    strips) whose ring j from the front lies offsets[j] spacings above the
    plane (the last offset for the rings further in): a kinked strip."""
    from cracklip.scene.crack_surface import SurfaceCrack
    m, rings_n = int(round(2 * math.pi * radius / spacing)), int(radius / spacing) - 1
    pts, rings = [], []
    for j in range(rings_n):
        r = radius - j * spacing
        th = 2 * math.pi * (np.arange(m) + 0.5 * (j % 2)) / m
        rings.append(len(pts))
        pts += [(r * math.cos(t), r * math.sin(t), offsets[min(j, len(offsets) - 1)] * spacing) for t in th]
    pts.append((0.0, 0.0, offsets[-1] * spacing))
    tri = []
    for j in range(rings_n - 1):
        a, b = rings[j], rings[j + 1]
        tri += [t for i in range(m) for t in ((a + i, a + (i + 1) % m, b + i), (a + (i + 1) % m, b + (i + 1) % m, b + i))]
    tri += [(rings[-1] + i, rings[-1] + (i + 1) % m, len(pts) - 1) for i in range(m)]
    return SurfaceCrack(np.array(pts, dtype=float), np.array(tri), name="kinked penny")


def test_kinked_triangulated_surface_keeps_the_mesh_frame():
    """A grown surface crack (a/c0 = 1, a/t 0.24 on a mesh of a/8) broke off
    its run: a strip next to a free-surface end had kinked by about 30
    degrees, the smooth fit through it turned the normal by 90-127 degrees,
    e1 pointed into the crack and int q (e1 . d) ds came out negative. Here
    the penny's strips two and three behind the front are raised by 0.65 and
    1 spacing (33 degrees): the fit alone turned the normal by 50-94 degrees
    and gave K_I from -623 to +46 (K0 1.128); the mesh's frame where the fit
    turns it by more than FIT_TURN gives K_I within 2 % of the flat penny's
    (1.135 .. 1.156 measured) with a warning naming the kink."""
    from cracklip.fracture import front, front_points
    crack = _kinked_penny(1.0, 0.1, [0.0, 0.0, 0.65, 1.0])
    flat = EllipticalCrack((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 1.0, axis=(0.0, 1.0, 0.0), name="penny")
    mesh = create_box(-L, -L, -L, L, L, L, H_FAR, fronts=crack_refinements([flat], 1.0 / N, H_FAR, growth=0.1))
    scene = cl.Scene(mesh, cl.Material(1.0, 0.3), cracks=[crack],
                     dirichlet=[cl.Dirichlet((-L, -L, -L)), cl.Dirichlet((L, -L, -L), 1),
                                cl.Dirichlet((L, -L, -L), 2), cl.Dirichlet((-L, L, -L), 2)],
                     tractions=[cl.Traction("zmax", (0.0, 0.0, 1.0)), cl.Traction("zmin", (0.0, 0.0, -1.0))],
                     options=cl.Options(enrichment="vector", radius=0.25, solver="iterative", sif_points=8))
    sol = cl.solve(scene)
    fr = front.crack_front(sol.model, 0)
    assert fr.fit_turn.max() > 45.0 and np.all(fr.unfitted == (fr.fit_turn > front.FIT_TURN))
    geo = np.asarray(sol.model.geometries[0].front["frame"])
    assert np.all(np.einsum("ni,ni->n", fr.frame[:, 0], geo[:, 0]) > math.cos(math.radians(front.FIT_TURN)))
    _, K = sifs_of(sol)
    assert np.all(np.abs(K[:, 0] / K0 - 1.0) < 0.03), K[:, 0] / K0
    notes = front_points.front_points(sol.model, 0)[0].warnings
    assert any("kinked near" in w and "keep the mesh's frame" in w for w in notes), notes

