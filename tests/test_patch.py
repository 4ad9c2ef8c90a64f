"""Patch tests: the exact solution lies in the discrete space (issue 2, acceptance 1-2)."""
import cracklip as cl
import numpy as np
import pytest
from conftest import uniform_strain, uniform_stress_scene

YC = 0.013


def through_crack_scene(md, yc, material, s, **options):
    """Crack y = yc cutting the square; left rollers, one pin per piece, tension s on the right."""
    x = md.mesh.geometry.x[:, :2]
    left = np.flatnonzero(np.isclose(x[:, 0], -1.0))
    above, below = left[x[left, 1] > yc], left[x[left, 1] < yc]
    pa = x[above[np.argmin(x[above, 1])]]
    pb = x[below[np.argmax(x[below, 1])]]
    scene = cl.Scene(md, material, cracks=[cl.Crack([[-1.5, yc], [1.5, yc]])],
                     dirichlet=[cl.Dirichlet("left", 0, 0.0), cl.Dirichlet(tuple(pa), 1, 0.0),
                                cl.Dirichlet(tuple(pb), 1, 0.0)],
                     tractions=[cl.Traction("right", (s, 0.0))],
                     options=cl.Options(**options))
    eps = uniform_strain(material, [[s, 0.0], [0.0, 0.0]])

    def exact(p, side):
        ypin = pa[1] if side > 0 else pb[1]
        return np.stack([eps[0, 0] * (p[:, 0] + 1.0), eps[1, 1] * (p[:, 1] - ypin)], axis=1)
    return scene, exact


def check_through_crack(sol, exact, yc, tol):
    rng = np.random.default_rng(1)
    pts = rng.uniform(-1.0, 1.0, (400, 2))
    scale = max(np.abs(exact(pts, 1)).max(), np.abs(exact(pts, -1)).max())
    for side in (1, -1):
        p = pts[(pts[:, 1] - yc) * side > 0]
        assert np.abs(sol.displacement(p) - exact(p, side)).max() <= tol * scale
        # Both lips evaluated on the crack itself.
        on = np.stack([np.linspace(-0.999, 0.999, 50), np.full(50, yc)], axis=1)
        assert np.abs(sol.displacement(on, side=side) - exact(on, side)).max() <= tol * scale
    op = sol.crack_opening(0)
    jump_exact = exact(op["x"], 1) - exact(op["x"], -1)
    assert np.abs(op["jump"] - jump_exact).max() <= tol * np.abs(jump_exact).max()
    # Opening normal to the crack is the jump of u_y; no sliding.
    assert np.allclose(op["normal"], jump_exact[:, 1], rtol=0, atol=tol * scale)
    return op


def test_through_crack_patch_unstructured(square_h01):
    mat = cl.Material(2.0, 0.3)
    scene, exact = through_crack_scene(square_h01, YC, mat, 0.7)
    sol = cl.solve(scene)
    assert sol.model.layout.num_enriched > 0
    check_through_crack(sol, exact, YC, 1e-10)
    # Strain energy: 1/2 sigma eps |Omega| exactly (sub-cell integration).
    eps = uniform_strain(mat, [[0.7, 0], [0, 0]])
    assert sol.strain_energy() == pytest.approx(0.5 * 0.7 * eps[0, 0] * 4.0, rel=1e-12)


def test_uniform_stress_parallel_to_interior_crack():
    """An inclined interior crack in a uniform stress along it: no disturbance."""
    md = cl.create_square(0.08)
    mat = cl.Material(3.0, 0.25)
    a, b = np.array([-0.43, -0.11]), np.array([0.38, 0.27])
    t = (b - a) / np.linalg.norm(b - a)
    sigma = 0.5 * np.outer(t, t)
    scene, exact = uniform_stress_scene(md, mat, sigma, [cl.Crack([a, b])])
    x = md.mesh.geometry.x[:, :2]
    sol = cl.solve(scene)
    assert sol.model.cracks[0].tips == (True, True)
    assert sol.model.layout.num_enriched > 0
    scale = np.abs(exact(x)).max()
    s = np.linspace(0.02, 0.98, 60)[:, None]
    on = a + s * (b - a)
    for side in (1, -1):
        assert np.abs(sol.displacement(on, side=side) - exact(on)).max() <= 1e-10 * scale
    op = sol.crack_opening(0)
    assert np.abs(op["jump"]).max() <= 1e-10 * scale
    fields = sol.subcell_fields()
    stress = np.array([sigma[0, 0], sigma[1, 1], sigma[0, 1]])
    assert np.abs(fields["stress"] - stress).max() <= 1e-10 * np.abs(stress).max()
