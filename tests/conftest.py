import pathlib
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))


def uniform_strain(material, sigma):
    """Plane-strain strain (2x2) of a uniform stress (2x2)."""
    E, nu = material.E, material.nu
    sxx, syy, sxy = sigma[0][0], sigma[1][1], sigma[0][1]
    exx = ((1 - nu ** 2) * sxx - nu * (1 + nu) * syy) / E
    eyy = ((1 - nu ** 2) * syy - nu * (1 + nu) * sxx) / E
    exy = (1 + nu) / E * sxy
    return np.array([[exx, exy], [exy, eyy]])


def side_tractions(sigma):
    """Tractions sigma.n on the four sides of an axis-aligned rectangle."""
    s = np.asarray(sigma, dtype=float)
    normals = {"left": (-1, 0), "right": (1, 0), "bottom": (0, -1), "top": (0, 1)}
    return {k: tuple(s @ np.array(n, dtype=float)) for k, n in normals.items()}


def uniform_stress_scene(md, material, sigma, cracks):
    """Scene of a uniform stress on the square: tractions sigma.n on its sides,
    the exact field eps.x held at the corner nodes (-1,-1) (both components)
    and (1,-1) (y). Returns (scene, exact displacement function)."""
    import cracklip as cl
    eps = uniform_strain(material, sigma)
    n0 = np.array(md.nearest_node([-1, -1]))
    n1 = np.array(md.nearest_node([1, -1]))

    def exact(p):
        return p @ eps.T
    scene = cl.Scene(md, material, cracks=list(cracks),
                     dirichlet=[cl.Dirichlet(tuple(n0), None, exact),
                                cl.Dirichlet(tuple(n1), 1, lambda p: exact(p)[:, 1])],
                     tractions=[cl.Traction(k, v) for k, v in side_tractions(sigma).items()])
    return scene, exact


@pytest.fixture(scope="session")
def square_h01():
    import cracklip as cl
    return cl.create_square(0.1)


def plate_scene(crack, h=0.1, tip_h=0.0125, tip_radius=0.0, radius=0.1, domain=(-1.0, -3.0, 1.0, 3.0),
                stress=1.0, material=None, **options):
    """Issue 14's "plate A": a rectangle (default [-1, 1] x [-3, 3]) under
    sigma_yy = stress on top and bottom, point supports at the bottom corners
    (both components at the left one, y at the right one), tips refined to
    tip_h, enrichment radius `radius`. Returns the Scene."""
    import cracklip as cl
    pts = np.asarray(crack, dtype=float)
    x0, y0, x1, y1 = domain
    refine = [(p[0], p[1], tip_h, tip_radius) for p in pts[[0, -1]] if x0 < p[0] < x1 and y0 < p[1] < y1]
    md = cl.create_rectangle(x0, y0, x1, y1, h, refine=refine)
    return cl.Scene(md, material or cl.Material(1.0, 0.3), cracks=[cl.Crack(pts)],
                    dirichlet=[cl.Dirichlet(md.nearest_node((x0, y0)), None, 0.0),
                               cl.Dirichlet(md.nearest_node((x1, y0)), 1, 0.0)],
                    tractions=[cl.Traction("top", (0.0, stress)), cl.Traction("bottom", (0.0, -stress))],
                    options=cl.Options(radius=radius, **options))


def tada_centre_crack(a_over_b: float) -> float:
    """Tada's finite-width correction of a centre crack in a strip under
    uniform tension: K = F sigma sqrt(pi a), F = (1 - 0.025 x^2 + 0.06 x^4)
    sqrt(sec(pi x / 2)), x = a / b (b the half width); 0.1 % for any x."""
    x = a_over_b
    return (1 - 0.025 * x ** 2 + 0.06 * x ** 4) * np.sqrt(1.0 / np.cos(np.pi * x / 2))


def tada_edge_crack(a_over_w: float) -> float:
    """Tada's single-edge-notch tension factor (ends free to rotate): K = F
    sigma sqrt(pi a), F = sqrt(2 / (pi x) tan(pi x / 2)) (0.752 + 2.02 x +
    0.37 (1 - sin(pi x / 2))^3) / cos(pi x / 2), x = a / W; 0.5 % for any x."""
    x = a_over_w
    t = np.pi * x / 2
    return np.sqrt(2 / (np.pi * x) * np.tan(t)) * (0.752 + 2.02 * x + 0.37 * (1 - np.sin(t)) ** 3) / np.cos(t)


def tada_bending(a_over_w: float) -> float:
    """Tada's single-edge-notch pure-bending factor: K = F sigma_b sqrt(pi a),
    sigma_b = 6 M / W^2, F = 1.122 - 1.40 x + 7.33 x^2 - 13.08 x^3 + 14.0 x^4;
    0.2 % for x <= 0.6."""
    x = a_over_w
    return 1.122 - 1.40 * x + 7.33 * x ** 2 - 13.08 * x ** 3 + 14.0 * x ** 4
