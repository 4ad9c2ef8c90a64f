"""The loads of issue 14 against exact solutions: lip pressure (Griffith,
Sneddon), plane stress, initial (residual) stress by superposition and with
closing contact, a linear (bending) traction from a scene file, point forces.
"""
import math
import pathlib
import sys

import cracklip as cl
import numpy as np
import pytest
from cracklip.exact.griffith import GriffithField, remote_in_crack_frame
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from handbook import griffith_scene, plate_scene, tada_bending  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_griffith_field_is_exact():
    """The exact field: lips carry (q, p), remote stress, K from the near-tip
    stress, Sneddon's jump, the gradient against finite differences, in
    plane strain and plane stress."""
    for plane in ("strain", "stress"):
        f = GriffithField(cl.Material(2.0, 0.3, plane), a=0.7, center=(0.1, -0.2), angle=30.0,
                          remote=(0.3, 1.0, 0.4), pressure=0.5, shear=-0.2)
        R = f.rotation
        on = np.asarray(f.center) + np.stack([np.linspace(-0.6, 0.6, 5), np.zeros(5)], axis=1) @ R.T
        for side in (1, -1):
            outward = R @ [0.0, -side]
            t = np.einsum("nij,j->ni", f.stress(on, side), outward) @ R
            assert np.allclose(t, side * np.array([-0.2, 0.5]), atol=1e-12)
        far = R.T @ f.stress(np.array([[3e4, 1e4]]))[0] @ R
        assert np.allclose(far, [[0.3, 0.4], [0.4, 1.0]], atol=1e-4)
        r = 1e-10
        ahead = R.T @ f.stress(np.asarray(f.center) + np.array([[0.7 + r, 0.0]]) @ R.T)[0] @ R
        assert ahead[1, 1] * math.sqrt(2 * math.pi * r) == pytest.approx(f.K_I, rel=1e-4)
        assert ahead[0, 1] * math.sqrt(2 * math.pi * r) == pytest.approx(f.K_II, rel=1e-4)
        x = np.asarray(f.center) + np.array([[0.3, 0.0]]) @ R.T
        jump = (f.displacement(x, 1) - f.displacement(x, -1)) @ R
        assert np.allclose(jump[0, ::-1], f.jump(np.array([0.3]))[0], rtol=1e-12)
        p, e = np.array([[0.9, 0.8]]), 1e-6
        fd = np.stack([(f.displacement(p + [e, 0]) - f.displacement(p - [e, 0])) / (2 * e),
                       (f.displacement(p + [0, e]) - f.displacement(p - [0, e])) / (2 * e)], axis=2)
        assert np.abs(fd - f.gradient(p)).max() < 1e-8


@pytest.mark.parametrize("plane", ["strain", "stress"])
def test_pressurised_griffith_crack(plane):
    """Acceptance 3: internal lip pressure p, the exact field on the boundary
    of [-1, 1]^2, a = 0.5, h = 0.05, tip_h = 0.0125 (5.5k dofs): K_I =
    p sqrt(pi a) to 2e-3 (measured 7e-4), K_II to 1e-3 of it, the opening
    to 1 % (L2) of Sneddon's 4 (1 - nu^2) p sqrt(a^2 - x^2) / E (plane
    strain; E' = E in plane stress; measured 0.42 %)."""
    mat = cl.Material(1.0, 0.3, plane)
    f = GriffithField(mat, a=0.5, pressure=1.0)
    sol = cl.solve(griffith_scene(f, 0.05, 0.0125))
    for k in sol.stress_intensity_factors(0):
        assert k["K_I"] == pytest.approx(f.K_I, rel=2e-3)
        assert abs(k["K_II"]) < 1e-3 * f.K_I
    smp = sol.lip_samples(0, 4)
    x = smp["x"][:, 0]
    sneddon = 4 * (1 - mat.nu ** 2) / mat.E * np.sqrt(0.25 - x ** 2) if plane == "strain" \
        else 4 / mat.E * np.sqrt(0.25 - x ** 2)
    assert np.allclose(sneddon, f.jump(x)[:, 0], rtol=1e-12)
    l2 = np.sqrt(np.sum(smp["weight"] * (smp["gap"] - sneddon) ** 2) / np.sum(smp["weight"] * sneddon ** 2))
    assert l2 < 0.01


def test_plane_stress_constants():
    """Plane stress (E, nu) is plane strain (E (1 + 2 nu) / (1 + nu)^2, nu / (1 + nu)):
    same shear modulus, kappa = (3 - nu) / (1 + nu), E* = E, sigma_zz = 0."""
    m = cl.Material(3.0, 0.25, "stress")
    s = cl.Material(m.E_strain, m.nu_strain)
    assert s.mu == pytest.approx(m.mu) and s.kappa == pytest.approx((3 - 0.25) / 1.25)
    assert m.E_star == pytest.approx(3.0) and m.sigma_zz_ratio == 0.0
    assert cl.Material(3.0, 0.5, "stress").nu_strain == pytest.approx(1 / 3)
    with pytest.raises(cl.MaterialError, match="plane must be 'strain' or 'stress'"):
        cl.Material(1.0, 0.3, "membrane")


def test_initial_stress_superposition():
    """Acceptance 3: a residual stress sigma_0,yy = s (1 - 2 x^2), equilibrated
    in the uncracked plate (tractions sigma_0 n on top and bottom), gives the
    K of the crack-face pressure p(x) = s (1 - 2 x^2) on the same mesh."""
    def s0(x):
        return np.stack([0 * x[:, 0], 1.0 - 2.0 * x[:, 0] ** 2, 0 * x[:, 0]], axis=1)
    crack = [[-0.5, 0.0], [0.5, 0.0]]
    residual = plate_scene(crack, stress=0.0)
    residual.initial_stress = s0
    residual.tractions = [cl.Traction("top", stress=s0), cl.Traction("bottom", stress=s0)]
    pressurised = plate_scene(crack, stress=0.0)
    pressurised.cracks[0].pressure = lambda x: 1.0 - 2.0 * x[:, 0] ** 2
    pressurised.tractions = []
    a, b = cl.solve(residual), cl.solve(pressurised)
    scale = max(abs(k["K_I"]) for k in b.stress_intensity_factors(0))
    assert scale > 1.0
    for ka, kb in zip(a.stress_intensity_factors(0), b.stress_intensity_factors(0)):
        assert abs(ka["K_I"] - kb["K_I"]) < 1e-3 * scale
        assert abs(ka["K_II"] - kb["K_II"]) < 1e-3 * scale
    # The displacements are the same field (the uncracked state has u = 0).
    assert np.abs(a.u - b.u).max() < 1e-6 * np.abs(b.u).max()
    # The reported stress is the total one: sigma_0 far from the crack.
    far = a.subcell_fields()
    c = far["points"].reshape(-1, 3, 2).mean(axis=1)
    top = np.flatnonzero(c[:, 1] > 2.5)
    assert np.allclose(far["stress"][top, 1], 1.0 - 2.0 * c[top, 0] ** 2, atol=0.02)


@pytest.mark.parametrize("contact,tip_h", [("bilateral", 0.0125), ("unilateral", 0.0125), ("bilateral", 0.01)])
def test_compressive_residual_stress_closes_the_crack(contact, tip_h):
    """Acceptance 3: a residual stress that compresses an aligned crack
    (sigma_0,yy = -1 along it, with a residual bending sigma_0,xx = 0.3 y
    parallel to it; equilibrated, its tractions on every side) closes the
    lips: the contact pressure equals -sigma_0,yy at every point (the issue
    asks 1e-3; measured 7e-13) and K_I = 0 (asked: 1e-6 of the K scale, 1.48,
    the K of the same crack opened by +1; measured 1e-13). Exact because the
    lip integrals are graded in sqrt(r) toward the tip on every segment near
    it: with plain Gauss on the segment next to the tip cell the pressure
    was off by 2e-4 and K_I by 2e-5 on a mesh whose tip sat near its cell's
    edge (tip_h = 0.01)."""
    s0 = cl.LinearStress((0.0, -1.0, 0.0), gradient=((0.0, 0.0, 0.0), (0.3, 0.0, 0.0)))
    scene = plate_scene([[-0.5, 0.0], [0.5, 0.0]], tip_h=tip_h, stress=0.0, contact=contact)
    scene.initial_stress = s0
    scene.tractions = [cl.Traction(side, stress=s0) for side in ("left", "right", "top", "bottom")]
    sol = cl.solve(scene)
    cp = sol.contact_pressure(0)
    assert np.abs(cp["pressure"] - 1.0).max() < 1e-9
    k_scale = 1.48
    for k in sol.stress_intensity_factors(0):
        assert abs(k["K_I"]) < 1e-9 * k_scale and abs(k["K_II"]) < 1e-9 * k_scale


def test_bending_scene_file(tmp_path):
    """Acceptance 3: single edge notch in pure bending from a scene file with
    the linear traction sigma_yy = 1 - 2 x on the ends of [0, 1] x [-3, 3]
    (a = 0.3, h = 0.025, tip_h = 0.01): K_I within 0.5 % of Tada's
    sigma_b sqrt(pi a) F(a / W) = 1.0892 (measured 1.0890)."""
    scene = tmp_path / "senb.toml"
    scene.write_text("""
title = "single edge notch, pure bending"
[mesh]
domain = [0.0, -3.0, 1.0, 3.0]
h = 0.025
tip_h = 0.01
[material]
E = 1.0
nu = 0.3
[[cracks]]
points = [[-0.1, 0.0], [0.3, 0.0]]
[[dirichlet]]
point = [0.0, -3.0]
[[dirichlet]]
point = [1.0, -3.0]
component = "y"
[[loads.tractions]]
tag = "top"
stress = [0.0, 1.0, 0.0]
stress_gradient = [[0.0, -2.0, 0.0], [0.0, 0.0, 0.0]]
[[loads.tractions]]
tag = "bottom"
stress = [0.0, 1.0, 0.0]
stress_gradient = [[0.0, -2.0, 0.0], [0.0, 0.0, 0.0]]
[options]
radius = 0.1
""")
    sf = cl.load_scene_file(scene)
    assert any("linear sigma" in n for n in sf.notes)
    (k,) = cl.solve(sf.scene).stress_intensity_factors(0)
    reference = tada_bending(0.3) * math.sqrt(math.pi * 0.3)
    assert reference == pytest.approx(1.0892, abs=1e-4)
    assert k["K_I"] == pytest.approx(reference, rel=5e-3)
    assert abs(k["K_II"]) < 1e-3 * reference


def test_point_forces_are_consistent_nodal_loads():
    """Point forces at every node of the top edge, each the traction times
    half its adjacent edges (the consistent load of a uniform traction),
    give the uniform-traction solution exactly."""
    md = cl.create_square(0.25)
    base = dict(dirichlet=[cl.Dirichlet("bottom", 1), cl.Dirichlet(md.nearest_node((-1, -1)), 0)])
    mat = cl.Material(1.0, 0.3)
    uniform = cl.solve(cl.Scene(md, mat, tractions=[cl.Traction("top", (0.2, -1.0))], **base))
    x = md.mesh.geometry.x[:, :2]
    top = np.flatnonzero(np.abs(x[:, 1] - 1.0) < 1e-12)
    top = top[np.argsort(x[top, 0])]
    half = np.diff(x[top, 0]) / 2
    share = np.concatenate([[0.0], half]) + np.concatenate([half, [0.0]])
    forces = [cl.PointForce(tuple(x[n]), (0.2 * w, -1.0 * w)) for n, w in zip(top, share)]
    pointwise = cl.solve(cl.Scene(md, mat, point_forces=forces, **base))
    assert np.abs(pointwise.u - uniform.u).max() < 1e-12 * np.abs(uniform.u).max()
    with pytest.raises(cl.InputError, match=r"point force 0 \(loads.point_forces\[0\]\) at .* more than an element"):
        cl.solve(cl.Scene(md, mat, point_forces=[cl.PointForce((5.0, 5.0), (1.0, 0.0))], **base))


def test_inclined_remote_stress_in_crack_frame():
    """remote_in_crack_frame: uniaxial sigma_yy = 1 on a crack at beta gives
    (sin^2 beta, cos^2 beta, sin beta cos beta)."""
    b = math.radians(30.0)
    assert remote_in_crack_frame((0.0, 1.0, 0.0), 30.0) == pytest.approx(
        (math.sin(b) ** 2, math.cos(b) ** 2, math.sin(b) * math.cos(b)))


@pytest.mark.parametrize("load", [[], ["loads.pressures=[{tag = \"hole\", value = 0.01}]"]],
                         ids=["kirsch traction", "pressure"])
def test_field_traction_on_another_mesh(load):
    """A scene file's Kirsch traction (sigma n) and pressure (-p n) on a
    curved boundary take the normals of the mesh they are integrated on: the
    scene moved onto a finer mesh of the same part (as the error estimate's
    and --accuracy's levels do, accuracy.scene_on) loads it exactly as the
    scene built on that mesh. They took the normals of the mesh the scene
    was built on (the coarse polygon's here: the load vector 1.1e-3 off; under
    mpirun only a process's part of that mesh, which made the estimate's
    K_I 0.006 for an exact 0 on some partitions of hole_crack.toml)."""
    from cracklip.analysis.accuracy import scene_on
    from cracklip.model.loads import assemble_load
    from cracklip.model.model import create_model
    scene = ROOT / "demos" / "scenes" / "hole_crack.toml"
    coarse = cl.load_scene_file(scene, overrides=["mesh.h=0.3", *load]).scene
    fine = cl.load_scene_file(scene, overrides=["mesh.h=0.15", *load]).scene
    moved = assemble_load(create_model(scene_on(coarse, fine.mesh)))
    built = assemble_load(create_model(fine))
    assert np.abs(moved - built).max() <= 1e-14 * np.abs(built).max()
