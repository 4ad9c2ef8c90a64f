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


@pytest.fixture(scope="session")
def square_h01():
    import cracklip as cl
    return cl.create_square(0.1)
