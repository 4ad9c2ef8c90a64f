"""The 3D X-FEM model on tetrahedra, solved end to end against exact fields:
the patch test of a crack through a whole box (rigid pieces and a uniform
stress, Heaviside only), the Williams field of a straight front, and the
opening of a penny crack (Sneddon) on a small mesh."""
import math

import numpy as np
import pytest

import cracklip as cl
from cracklip.analysis.solve import solve
from cracklip.exact.embedded_cracks import penny_opening
from cracklip.post.solution import Solution as Solution3D
from cracklip.scene.crack_surface import EllipticalCrack, PolygonCrack
from cracklip.scene.mesh_3d import FrontRefinement, create_box, front_sampling

FACES = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]


def _through_crack():
    """An inclined plane through the whole unit box (no front inside)."""
    sq = np.array([[-1, -1, 0], [2, -1, 0], [2, 2, 0], [-1, 2, 0]], float)
    sq[:, 2] = 0.43 + 0.1 * sq[:, 0] - 0.05 * sq[:, 1]
    return PolygonCrack(sq, name="through")


@pytest.fixture(scope="module")
def box():
    return create_box(0, 0, 0, 1, 1, 1, 0.25)


def _sub_tet_points(sol):
    """Centroids of every sub-tetrahedron of the crack's cells (with their
    side) and the centroids of the other cells: cell, ref, side, x."""
    m = sol.model
    g = m.geometries[0]
    cc = g.crack_cells
    cells, refs, sides = [], [], []
    for i, c in enumerate(cc["cell"]):
        for k in range(cc["sub_offsets"][i], cc["sub_offsets"][i + 1]):
            cells.append(c)
            refs.append(cc["sub"][k].reshape(4, 3).mean(axis=0))
            sides.append(cc["side"][k])
    plain = np.flatnonzero(g.cell_class == 0)
    cells = np.concatenate([cells, plain]).astype(np.int32)
    refs = np.concatenate([refs, np.full((len(plain), 3), 0.25)])
    sides = np.concatenate([sides, np.zeros(len(plain))]).astype(np.int8)
    u, grad = sol._evaluate(cells, refs, sides, gradient=True)
    x = sol._physical(cells, refs)
    N = np.column_stack([1.0 - refs.sum(axis=1), refs])
    phi = np.einsum("na,na->n", N, g.phi[m.cells[cells]])
    side = np.where(sides != 0, sides, np.where(phi >= 0, 1, -1))
    return x, side, u, grad


def test_patch_rigid_pieces(box):
    """Each piece of a box cut through by a plane moves rigidly, its own
    motion prescribed on its faces: the Heaviside functions reproduce both
    to round-off, with zero strain."""
    rng = np.random.default_rng(1)
    motion = {s: (rng.normal(size=3), 0.3 * rng.normal(size=3)) for s in (1, -1)}

    def exact(x, side):
        out = np.zeros((len(x), 3))
        for s, (a, w) in motion.items():
            on = side == s
            out[on] = a + np.cross(w, x[on])
        return out

    scene = cl.Scene(box, cl.Material(1.0, 0.3), cracks=[_through_crack()],
                     dirichlet=[cl.Dirichlet(f, value=exact) for f in FACES],
                     options=cl.Options(enrichment="none", solver="direct"))
    sol = solve(scene)
    assert isinstance(sol, Solution3D)
    assert np.asarray(sol.model.geometries[0].cell_class).tolist().count(3) == 0  # no front in the box
    x, side, u, grad = _sub_tet_points(sol)
    ue = exact(x, side)
    assert len(x) > 300 and np.unique(side).tolist() == [-1, 1]
    assert np.abs(u - ue).max() <= 1e-10 * np.abs(ue).max()
    assert np.abs(0.5 * (grad + grad.transpose(0, 2, 1))).max() <= 1e-10 * np.abs(ue).max()
    # The opening on the lips is the difference of the two motions.
    lips = sol.lip_samples()
    jump_exact = exact(lips["x"], np.ones(len(lips["x"]), int)) - exact(lips["x"], -np.ones(len(lips["x"]), int))
    assert np.abs(lips["jump"] - jump_exact).max() <= 1e-10 * np.abs(jump_exact).max()


def test_patch_uniform_stress(box):
    """A uniform stress whose traction on the crack plane vanishes (sigma =
    s t t with t in the plane), prescribed as the linear displacement on the
    faces: the crack changes nothing, stress uniform to round-off."""
    crack = _through_crack()
    n = crack.normal
    t = np.cross(n, [0.3, 1.0, 0.2])
    t /= np.linalg.norm(t)
    E, nu, s = 2.0, 0.3, 1.5
    sig = s * np.outer(t, t)
    eps = ((1 + nu) * sig - nu * np.trace(sig) * np.eye(3)) / E

    def exact(x, side=None):
        return x @ eps.T

    scene = cl.Scene(box, cl.Material(E, nu), cracks=[crack], dirichlet=[cl.Dirichlet(f, value=exact) for f in FACES],
                     options=cl.Options(enrichment="none", solver="direct"))
    sol = solve(scene)
    x, side, u, grad = _sub_tet_points(sol)
    assert np.abs(u - exact(x)).max() <= 1e-10 * np.abs(exact(x)).max()
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    e = 0.5 * (grad + grad.transpose(0, 2, 1))
    stress = 2 * mu * e + lam * np.trace(e, axis1=1, axis2=2)[:, None, None] * np.eye(3)
    assert np.abs(stress - sig).max() <= 1e-10 * s
    assert np.abs(sol.lip_samples()["jump"]).max() <= 1e-10 * np.abs(exact(x)).max()
    # The strain energy is the uniform field's times the volume.
    assert sol.strain_energy() == pytest.approx(0.5 * np.sum(sig * eps), rel=1e-10)


def _williams(mode: int, E: float, nu: float, x0: float, z0: float):
    """Unit-K plane-strain Williams field (mode 0: I, 1: II; 2: anti-plane
    III) of a half-plane crack x < x0 in the plane z = z0, front along y;
    and its gradient by central differences."""
    mu, kappa = E / (2 * (1 + nu)), 3 - 4 * nu

    def field(x, side):
        x1, x2 = x[:, 0] - x0, x[:, 2] - z0
        r, th = np.hypot(x1, x2), np.arctan2(x2, x1)
        th = np.where((x1 < 0) & (side != 0), np.where(side > 0, np.abs(th), -np.abs(th)), th)
        c = np.sqrt(r) / (2 * mu * math.sqrt(2 * math.pi))
        out = np.zeros((len(x), 3))
        if mode == 0:
            out[:, 0] = c * np.cos(th / 2) * (kappa - np.cos(th))
            out[:, 2] = c * np.sin(th / 2) * (kappa - np.cos(th))
        elif mode == 1:
            out[:, 0] = c * np.sin(th / 2) * (kappa + 2 + np.cos(th))
            out[:, 2] = -c * np.cos(th / 2) * (kappa - 2 + np.cos(th))
        else:
            out[:, 1] = -4 * c * np.sin(th / 2)
        return out

    def gradient(x, side, step=1e-6):
        side = np.where(side != 0, side, np.where(x[:, 2] >= z0, 1, -1))
        g = np.zeros((len(x), 3, 3))
        for j in range(3):
            xp, xm = x.copy(), x.copy()
            xp[:, j] += step
            xm[:, j] -= step
            g[:, :, j] = (field(xp, side) - field(xm, side)) / (2 * step)
        return g
    return field, gradient


@pytest.mark.parametrize("mode", [0, 2])
def test_straight_front_williams_field(mode):
    """The exact field of a straight front (mode I and III), prescribed on the
    box's faces: with the vector front functions on a fixed radius the
    energy error converges at the P1 rate (1 in h; measured 0.98 over h =
    0.2 ... 0.07 in mode I) and is a third of the Heaviside-only model's
    (rate 1/2), and the jump on the lips is the exact sqrt(r) jump to a
    few per cent."""
    E, nu, x0, z0 = 1.0, 0.3, 0.013, 0.007
    crack = PolygonCrack([[-3, -3, z0], [x0, -3, z0], [x0, 3, z0], [-3, 3, z0]], name="half")
    field, gradient = _williams(mode, E, nu, x0, z0)
    errors = {}
    for enrichment, h in (("vector", 0.2), ("vector", 0.1), ("none", 0.2)):
        md = create_box(-1, -1, -1, 1, 1, 1, h)
        scene = cl.Scene(md, cl.Material(E, nu), cracks=[crack], dirichlet=[cl.Dirichlet(f, value=field) for f in FACES],
                         options=cl.Options(enrichment=enrichment, radius=0.3, solver="direct"))
        sol = solve(scene)
        errors[enrichment, h] = sol.energy_error(gradient)[1]
        if enrichment == "vector" and h == 0.1:
            lips = sol.lip_samples()
            away = np.hypot(lips["x"][:, 0] - x0, lips["x"][:, 2] - z0) > 0.1
            side = np.ones(len(lips["x"]), int)
            jump = field(lips["x"], side) - field(lips["x"], -side)
            jerr = np.abs(lips["jump"] - jump)[away].max() / np.abs(jump).max()
    # The P1 rate (1) from two unstructured meshes: measured 0.83 .. 0.94 over gmsh seeds 1-4
    # (Heaviside only: 1/2).
    rate = math.log(errors["vector", 0.2] / errors["vector", 0.1]) / math.log(2.0)
    assert rate > 0.75, errors
    assert errors["vector", 0.2] < 0.34 * errors["none", 0.2], errors
    assert jerr < 0.03, jerr


def test_penny_crack_opening_small_mesh():
    """A penny crack (a = 1) in a box of side 8 under remote tension, front
    at a/h = 8 (the crack's disk at a/4, sizes growing by 0.2 per unit
    distance): the opening follows Sneddon's 8 (1 - nu^2) sigma sqrt(a^2 -
    r^2) / (pi E) (measured: 2.3 % L2, the opened volume 2.2 % low: the
    coarse mesh's stiffness; demos/penny_crack.py measures fine meshes),
    without sliding."""
    L, a, E, nu, sig, h, h_disk, growth, h_far = 4.0, 1.0, 1.0, 0.3, 1.0, 0.125, 0.25, 0.2, 1.0
    crack = EllipticalCrack((0, 0, 0), (0, 0, 1), a, axis=(1, 0, 0), name="penny")
    g1 = np.arange(-a, a + 1e-9, h_disk / 2)
    X, Y = np.meshgrid(g1, g1)
    disk = np.column_stack([X.ravel(), Y.ravel(), 0 * X.ravel()])[(X ** 2 + Y ** 2 <= a * a).ravel()]
    md = create_box(-L, -L, -L, L, L, L, h_far,
                    fronts=[FrontRefinement(crack.front_points(front_sampling(h)), h, (h_far - h) / growth),
                            FrontRefinement(disk, h_disk, (h_far - h_disk) / growth)])
    scene = cl.Scene(md, cl.Material(E, nu), cracks=[crack],
                     dirichlet=[cl.Dirichlet((-L, -L, -L)), cl.Dirichlet((L, -L, -L), 1), cl.Dirichlet((L, -L, -L), 2),
                                cl.Dirichlet((-L, L, -L), 2)],
                     tractions=[cl.Traction("zmax", (0, 0, sig)), cl.Traction("zmin", (0, 0, -sig))],
                     options=cl.Options(radius=2.5 * h))
    sol = solve(scene)
    op = sol.crack_opening()
    r = np.hypot(op["x"][:, 0], op["x"][:, 1])
    assert r.max() <= a * (1 + 1e-9)  # every sample on the crack
    exact = penny_opening(r, sig, a, E, nu)
    w = op["weight"]
    assert w.min() > 0.0
    l2 = math.sqrt(np.sum(w * (op["normal"] - exact) ** 2) / np.sum(w * exact ** 2))
    assert l2 < 0.035, l2
    assert np.abs(op["tangential"]).max() < 0.02 * exact.max()
    volume = 16 * (1 - nu ** 2) * sig * a ** 3 / (3 * E)
    assert sol.opening_volume() == pytest.approx(volume, rel=0.035)
