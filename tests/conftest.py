import contextlib
import os
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


# -- mesh robustness: another gmsh mesh realisation --------------------------------------
# CRACKLIP_TEST_GMSH_SEED=N sets gmsh's Mesh.RandomSeed (default 1) before every mesh
# generation in the test process, so a developer sees the suite on another mesh of the same
# geometry and size field (as another CPU's gmsh produces): a bound that holds only on one
# mesh fails there. Subprocesses (CLI and demo runs) keep gmsh's default. The fixture
# gmsh_seed(N) meshes a block with seed N (a realisation that once exposed a weakness).
GMSH_SEED = os.environ.get("CRACKLIP_TEST_GMSH_SEED")
_seeds = [int(GMSH_SEED)] if GMSH_SEED else []


def pytest_configure(config):
    import gmsh
    generate = gmsh.model.mesh.generate

    def seeded_generate(*args, **kwargs):
        gmsh.option.setNumber("Mesh.RandomSeed", _seeds[-1] if _seeds else 1)  # 1: gmsh's default
        return generate(*args, **kwargs)
    gmsh.model.mesh.generate = seeded_generate


def pytest_report_header(config):
    return f"gmsh Mesh.RandomSeed: {GMSH_SEED or 'default (1)'} (CRACKLIP_TEST_GMSH_SEED)"


@pytest.fixture
def gmsh_seed():
    """gmsh_seed(N): a context in which gmsh meshes with Mesh.RandomSeed = N."""
    @contextlib.contextmanager
    def seeded(seed: int):
        _seeds.append(int(seed))
        try:
            yield
        finally:
            _seeds.pop()
    return seeded
