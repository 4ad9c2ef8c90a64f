"""Symmetry planes (issue 39, item 4): a boundary tag declared a plane of
symmetry holds the normal displacement at 0, its checks (planar, normal to
an axis, a crack meeting it at right angles), and K at a front end on the
plane computed on the mirrored domain (K_I, K_II as on the half, K_III =
0, no free-surface flag). Half and quarter models of a penny and an Irwin
ellipse against the full model on small meshes (demos/symmetry_models.py
has the finer ones)."""
from __future__ import annotations

import csv
import json
import math
import pathlib

import numpy as np
import pytest

import cracklip as cl
from cracklip import cli
from cracklip.errors import BoundaryConditionError, CrackGeometryError
from cracklip.exact.embedded_cracks import inclined_penny_k, irwin_k, penny_k
from cracklip.scene.crack_surface import EllipticalCrack
from cracklip.scene.mesh_3d import create_box, create_cylinder, crack_refinements
from cracklip.scene.symmetry import SymmetryCondition

L, H_FAR = 3.0, 1.0
SCENES = pathlib.Path(__file__).resolve().parents[1] / "demos" / "scenes"


def box_scene(model: str, n: int = 5, b: float = 1.0, normal=(0.0, 0.0, 1.0), center=(0.0, 0.0, 0.0),
              angles=(0.0, 90.0, 180.0, 270.0), planes=None) -> cl.Scene:
    """A crack (semi-axes 1 along x, b along y) in the box |x|, |y|, |z| <= L
    (full), its half x >= 0 or y >= 0 (half_x, half_y) or quarter x, y >= 0,
    pulled along z; point supports for the rigid motions the planes leave."""
    crack = EllipticalCrack(center, normal, 1.0, b=b, axis=(1.0, 0.0, 0.0) if normal[0] == 0 else (0.0, 1.0, 0.0),
                            name="crack")
    x0 = 0.0 if model in ("half_x", "quarter") else -L
    y0 = 0.0 if model in ("half_y", "quarter") else -L
    mesh = create_box(x0, y0, -L, L, L, L, H_FAR, fronts=crack_refinements([crack], b / n, H_FAR, growth=0.1))
    sup = {"full": [cl.Dirichlet((x0, y0, -L)), cl.Dirichlet((L, y0, -L), 1), cl.Dirichlet((L, y0, -L), 2),
                    cl.Dirichlet((x0, L, -L), 2)],
           "half_x": [cl.Dirichlet((L, y0, -L), 1), cl.Dirichlet((L, y0, -L), 2), cl.Dirichlet((L, L, -L), 2)],
           "half_y": [cl.Dirichlet((x0, L, -L), 0), cl.Dirichlet((x0, L, -L), 2), cl.Dirichlet((L, L, -L), 2)],
           "quarter": [cl.Dirichlet((L, L, -L), 2)]}[model]
    if planes is None:
        planes = {"full": [], "half_x": ["xmin"], "half_y": ["ymin"], "quarter": ["xmin", "ymin"]}[model]
    return cl.Scene(mesh, cl.Material(1.0, 0.3), cracks=[crack], dirichlet=sup,
                    tractions=[cl.Traction("zmax", (0.0, 0.0, 1.0)), cl.Traction("zmin", (0.0, 0.0, -1.0))],
                    options=cl.Options(enrichment="vector", radius=0.25 * b, solver="iterative",
                                       sif_angles=list(angles)),
                    symmetry=planes)


def at_angle(rows, deg: float) -> list[dict]:
    return [r for r in rows if abs((math.degrees(r["parametric_angle"]) - deg + 180.0) % 360.0 - 180.0) < 0.05]


@pytest.fixture(scope="module")
def pennies():
    """K of the penny (a/5) in the full box, its half x >= 0 and its quarter."""
    out = {}
    for model in ("full", "half_x", "quarter"):
        sol = cl.solve(box_scene(model))
        out[model] = (sol, sol.stress_intensity_factors(0))
    return out


def test_quarter_and_half_penny_against_full(pennies):
    """The axis ends (parametric angles 0 and 90 degrees: on the planes of
    the quarter model, 90 on the half's) against the full model's (the mean
    of its two symmetric points, which differ by up to 0.33 % on this mesh):
    within 1 % at a/5 (measured: quarter -0.12 % / -0.48 %, half +0.41 % /
    -0.03 %; the 0.5 % of issue 39 is demos/symmetry_models.py's, on
    finer meshes). K_I everywhere 2.2 % above 2 sigma sqrt(a / pi) on
    average in all three (the box of half-width 3 a; at most 3.5 %); no
    free-surface flag, K_III exactly 0 at the mirrored ends, no domain
    clipped by a symmetry plane."""
    K0 = penny_k(1.0, 1.0)
    full = pennies["full"][1]
    for end, copies in ((0.0, (0.0, 180.0)), (90.0, (90.0, 270.0))):
        ref = np.mean([at_angle(full, c)[0]["K_I"] for c in copies])
        for model in ("half_x", "quarter"):
            k = at_angle(pennies[model][1], end)[0]["K_I"]
            assert abs(k / ref - 1.0) < 0.01, (model, end, k / ref - 1.0)
    mean_full = np.mean([r["K_I"] / K0 - 1.0 for r in full])
    for model, (sol, rows) in pennies.items():
        e = np.array([r["K_I"] / K0 - 1.0 for r in rows])
        assert np.abs(e).max() < 0.035 and abs(e.mean() - mean_full) < 0.005, model
        assert not any(r["free_surface"] for r in rows)
        mirrored = [r for r in rows if r["K_source"] == "mirrored_domain"]
        assert len(mirrored) == {"full": 0, "half_x": 2, "quarter": 2}[model]
        assert all(r["K_III"] == 0.0 and r["symmetry"] and r["domain_clear"] for r in mirrored)
        assert all(r["limited_by"] != "the boundary of the part" for r in rows)


def test_symmetry_plane_holds_the_normal_displacement(pennies):
    """On the quarter's planes the normal displacement is 0 (to round-off)
    at the nodes and, with the normal Heaviside dofs of the plane faces the
    crack crosses and the mode III front dofs of the plane's nodes fixed, at the centroids of most enriched cells' faces
    on the plane; near the front the mode I and II functions' directions,
    interpolated from the nodal frames of the P1 front (tilted by about h /
    2 rho from the plane), leave up to 1.2e-3 of the displacement scale
    (measured; bounded at 3e-3)."""
    sol, _ = pennies["quarter"]
    m = sol.model
    planes = [bc for bc in m.scene.dirichlet if isinstance(bc, SymmetryCondition)]
    assert [bc.label for bc in planes] == ["symmetry on 'xmin'", "symmetry on 'ymin'"]
    from cracklip.model.symmetry import plane_nodes
    kind, base = np.asarray(m.layout.kind), np.asarray(m.layout.node)
    fixed = set(np.asarray(m.bc_dofs).tolist())
    for bc in planes:
        nodes = plane_nodes(m, bc)
        u_std = sol.standard_displacement.reshape(-1, 3)
        assert np.abs(u_std[nodes, bc.component]).max() < 1e-10 * np.abs(u_std).max()
        front = np.flatnonzero(np.isin(base, nodes) & (kind == 2))
        assert front.size and all(3 * (m.layout.num_std_nodes + k) + 2 in fixed for k in front)
        # the Heaviside dofs of the nodes of plane faces the crack crosses are
        # fixed (elsewhere on the plane H - H_i vanishes: nothing to fix)
        cells = np.flatnonzero(np.isin(m.cells, nodes).sum(axis=1) == 3)
        phi = np.asarray(m.geometries[0].phi)
        faces = [c[np.isin(c, nodes)] for c in m.cells[cells]]
        crossed = np.unique(np.concatenate([f for f in faces if phi[f].min() < 0.0 < phi[f].max()]))
        heav = np.flatnonzero(np.isin(base, crossed) & (kind == 0))
        assert heav.size and all(3 * (m.layout.num_std_nodes + k) + bc.component in fixed for k in heav)
        # points of the enriched cells with a face on the plane, both sides of the crack
        cells = cells[np.isin(cells, m.layout.cells)]
        face = np.isin(m.cells[cells], nodes)
        ref_nodes = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
        ref = np.array([ref_nodes[f].mean(axis=0) for f in face])      # the face's centroid
        # each face on its own side, both sides where the crack crosses it
        faces = [c[np.isin(c, nodes)] for c in m.cells[cells]]
        on_face = np.array([phi[f].mean() for f in faces])
        both = np.array([phi[f].min() < 0.0 < phi[f].max() for f in faces])
        for side in (1, -1):
            sel = both | (np.sign(on_face) == side)
            u = sol._evaluate(cells[sel].astype(np.int32), ref[sel], np.full(sel.sum(), side, dtype=np.int8))
            un = np.abs(u[:, bc.component]) / np.abs(u).max()
            assert np.median(un) < 1e-12 and un.max() < 3e-3, (np.median(un), un.max())


def test_inclined_penny_half_model():
    """The penny inclined at 45 degrees (normal (cos b, 0, sin b)) is
    symmetric about y = 0, which its front meets where K_II is largest and
    K_III vanishes (omega = 0, pi from the shear direction). Its half y >=
    0: at the mirrored ends K_III = 0 exactly, K_II within 3 % of the K
    scale of the closed form (measured 1.0 %), like the interior points
    (K_III there following sin omega)."""
    beta = math.radians(45.0)
    n = np.array([math.cos(beta), 0.0, math.sin(beta)])
    sol = cl.solve(box_scene("half_y", normal=tuple(n), angles=()))
    rows = sol.stress_intensity_factors(0)
    z = np.array([0.0, 0.0, 1.0])
    s = z - (z @ n) * n
    s /= np.linalg.norm(s)
    x = np.array([[r["x"], r["y"], r["z"]] for r in rows])
    omega = np.arctan2(x @ np.cross(n, s), x @ s)
    K = np.array([[r["K_I"], r["K_II"], r["K_III"]] for r in rows])
    Kx = np.column_stack(inclined_penny_k(1.0, beta, 1.0, 0.3, omega))
    scale = np.linalg.norm(Kx, axis=1).max()
    ends = [i for i, r in enumerate(rows) if r["K_source"] == "mirrored_domain"]
    assert len(ends) == 2 and not any(r["free_surface"] for r in rows)
    for i in ends:
        assert K[i, 2] == 0.0 and abs(abs(K[i, 1]) - np.abs(Kx[:, 1]).max()) < 0.03 * scale
    assert np.abs(K - Kx).max() < 0.03 * scale
    assert np.abs(K[:, 2]).max() > 0.1 * scale


def test_quarter_ellipse_against_full():
    """Irwin's ellipse b/a = 0.5 at b/5: the quarter model's axis-end K
    against the full model's (the mean of its symmetric points, which
    differ by 0.97 % at phi = 0 on this mesh) within 1 % (measured +0.21 %
    at phi = 0, -0.45 % at 90 degrees; demos/symmetry_models.py at b/8 and
    b/11 for issue 39's 0.5 %). Wrong ends fail it (measured on this mesh):
    without the neighbours' mirror images in the hat correction (the ends
    keeping their hat averages) phi = 0 is +2.05 % off; with the ends read
    as free-surface ends (extrapolated, by the end rule before its
    curvature weight K kappa^(1/6), fracture/front_sampling.py) -12.1 % and
    -3.0 %."""
    full = cl.solve(box_scene("full", b=0.5)).stress_intensity_factors(0)
    quarter = cl.solve(box_scene("quarter", b=0.5)).stress_intensity_factors(0)
    for end, copies in ((0.0, (0.0, 180.0)), (90.0, (90.0, 270.0))):
        ref = np.mean([at_angle(full, c)[0]["K_I"] for c in copies])
        k = at_angle(quarter, end)[0]
        assert k["K_source"] == "mirrored_domain" and abs(k["K_I"] / ref - 1.0) < 0.01, (end, k["K_I"] / ref)


def test_quarter_ellipse_scene(tmp_path):
    """demos/scenes/quarter_ellipse.toml through `run` (the [[symmetry]]
    key; mesh.h = 2 far from the crack, the scene's front size): in
    front.csv both ends are on their planes (K_source mirrored_domain,
    symmetry naming the scene key, K_III = 0 to round-off, not free_surface) and K_I
    there is within 2 % of Irwin's (measured -0.9 % at phi = 0 and -1.2 %
    at 90 degrees, the box of half-width 5 a); K asked for every 15 degrees
    is reported at every asked angle; no warning about a front point (a
    domain too small, a free surface; the error estimate's discretisation
    warning may rightly fire: K is about 1 % off here). Were the planes read as
    free surfaces, the ends would be extrapolated (K_source
    end_extrapolation) and flagged."""
    from test_scenes_3d import SMALL_3D
    args = ["run", str(SCENES / "quarter_ellipse.toml"), "--out", str(tmp_path), "--quiet"]
    for o in SMALL_3D["quarter_ellipse"]:
        args += ["--set", o]
    assert cli.main(args) == 0
    results = json.loads((tmp_path / "results.json").read_text())
    with (tmp_path / "front.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert not [w for w in results["warnings"] if w["code"] != "discretisation"
                and ("front point" in w["message"] or "free surface" in w["message"])]
    assert all(r["free_surface"] == "0" for r in rows)
    deg = np.array([math.degrees(float(r["parametric_angle"])) for r in rows])
    ends = {0.0: "symmetry[1]", 90.0: "symmetry[0]"}     # phi = 0 on y = 0 (ymin), 90 on x = 0 (xmin)
    for angle, key in ends.items():
        k = np.flatnonzero(np.abs(deg - angle) < 1e-6)
        assert k.size == 1, angle
        r = rows[k[0]]
        assert r["K_source"] == "mirrored_domain" and r["symmetry"] == key
        assert abs(float(r["K_III"])) < 1e-12       # 0 by the mirror (round-off of the hat correction)
        exact = float(irwin_k(1.0, 1.0, 0.5, np.radians([angle]))[0])
        assert abs(float(r["K_I"]) / exact - 1.0) < 0.02, (angle, float(r["K_I"]) / exact)
    assert sum(r["K_source"] == "mirrored_domain" for r in rows) == 2
    asked = sorted(round(d) for d, r in zip(deg, rows) if r["requested"] == "1")
    assert asked == [0, 15, 30, 45, 60, 75, 90]


# -- the checks --------------------------------------------------------------------------------------

def _tiny(center=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0), lo=(0.0, -1.0, -1.0), planes=("xmin",)):
    crack = EllipticalCrack(center, normal, 0.5, axis=(1.0, 0.0, 0.0) if abs(normal[0]) < 0.5 else (0.0, 1.0, 0.0))
    mesh = create_box(*lo, 1.0, 1.0, 1.0, 0.5, fronts=crack_refinements([crack], 0.15, 0.5))
    return cl.Scene(mesh, cl.Material(1.0, 0.3), cracks=[crack],
                    dirichlet=[cl.Dirichlet((1.0, 1.0, -1.0)), cl.Dirichlet((1.0, -1.0, -1.0), 2),
                               cl.Dirichlet((1.0, 1.0, 1.0), 1)],
                    tractions=[cl.Traction("zmax", (0.0, 0.0, 1.0))], options=cl.Options(radius=0.2),
                    symmetry=list(planes))


def test_crack_must_meet_the_plane_at_right_angles():
    """A penny tilted by 11 degrees about y meets x = 0 at 79 degrees: an
    error naming the crack, the plane and the angle; a penny centred off
    the plane meets it at right angles in its plane but its front does
    not: an error about the front."""
    t = math.radians(11.0)
    with pytest.raises(CrackGeometryError, match=r"meets it at 79 degrees instead of 90"):
        cl.solve(_tiny(normal=(math.sin(t), 0.0, math.cos(t))))
    with pytest.raises(CrackGeometryError, match=r"its front meets the plane .* degrees off the plane's normal"):
        cl.solve(_tiny(center=(0.25, 0.0, 0.0)))


def test_symmetry_tag_must_be_an_axis_plane():
    """A curved tag (a cylinder's side) is not a plane; a cylinder along
    (1, 1, 0) has planar end faces normal to no axis: errors naming the
    tag; an unknown tag is named too."""
    for axis, tag, msg in (((0.0, 0.0, 1.0), "side", "is not a plane"),
                           ((1.0, 1.0, 0.0), "bottom", "not along x, y, z")):
        mesh = create_cylinder((0.0, 0.0, 0.0), axis, 1.0, 2.0, 0.5)
        with pytest.raises(BoundaryConditionError, match=msg):
            cl.Scene(mesh, cl.Material(1.0, 0.3), dirichlet=[cl.Dirichlet("top")], symmetry=[tag])


def test_symmetry_in_2d():
    """The same concept on a planar part: half of a centre-cracked plate
    (crack 2a = 0.6 in [-1, 1]^2 under tension) with the line x = 0 of
    symmetry gives the right tip's K_I of the full plate within 0.3 %
    (measured +0.03 %; the full plate's two tips differ by 0.09 %), K_II
    below 1e-3 of K_I; a crack at 72 degrees to the line is refused."""
    h, tip = 0.05, [(0.3, 0.0, 0.01, 0.1)]
    full_mesh = cl.create_rectangle(-1.0, -1.0, 1.0, 1.0, h, refine=tip + [(-0.3, 0.0, 0.01, 0.1)])
    half_mesh = cl.create_rectangle(0.0, -1.0, 1.0, 1.0, h, refine=tip)
    tension = [cl.Traction("top", (0.0, 1.0)), cl.Traction("bottom", (0.0, -1.0))]
    full = cl.Scene(full_mesh, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-0.3, 0.0], [0.3, 0.0]])],
                    dirichlet=[cl.Dirichlet((-1.0, -1.0)), cl.Dirichlet((1.0, -1.0), 1)], tractions=tension,
                    options=cl.Options(radius=0.05))
    half = cl.Scene(half_mesh, cl.Material(1.0, 0.3), cracks=[cl.Crack([[0.0, 0.0], [0.3, 0.0]])],
                    dirichlet=[cl.Dirichlet((1.0, -1.0), 1)], tractions=tension, options=cl.Options(radius=0.05),
                    symmetry=["left"])
    k_full = max(cl.solve(full).stress_intensity_factors(0), key=lambda r: r["x"])
    rows = cl.solve(half).stress_intensity_factors(0)
    assert len(rows) == 1
    assert rows[0]["K_I"] == pytest.approx(k_full["K_I"], rel=3e-3)
    assert abs(rows[0]["K_II"]) < 1e-3 * rows[0]["K_I"]
    inclined = cl.Scene(half_mesh, cl.Material(1.0, 0.3), cracks=[cl.Crack([[0.0, 0.0], [0.3, 0.1]])],
                        dirichlet=[cl.Dirichlet((1.0, -1.0), 1)], tractions=tension, symmetry=["left"])
    with pytest.raises(CrackGeometryError, match="instead of 90"):
        cl.solve(inclined)
