"""cracklip: X-FEM cracks with crack-lip contact on DOLFINx.

Quick use::

    import cracklip as cl
    mesh = cl.create_square(h=0.1)
    scene = cl.Scene(mesh, cl.Material(E=1.0, nu=0.3),
                     cracks=[cl.Crack([[-1.0, 0.0], [0.0, 0.0]])],
                     dirichlet=[cl.Dirichlet("bottom")],
                     tractions=[cl.Traction("top", (0.0, 0.01))])
    solution = cl.solve(scene)
"""
try:
    from . import _cracklip  # noqa: F401
except ImportError as e:  # pragma: no cover
    raise ImportError(
        "cracklip's C++ module is not built: run "
        "`cmake -S . -B build -DPython3_EXECUTABLE=/usr/bin/python3 && cmake --build build -j2` "
        f"in the repository root ({e})") from None

from .errors import (BoundaryConditionError, CrackGeometryError, CracklipError, InputError,
                     MaterialError, MeshError, SolverError)
from .mesh import MeshData, create_half_annulus, create_rectangle, create_square, read_msh
from .model import XfemModel, create_model
from .post import Solution
from .scene import Crack, Dirichlet, LoadStep, Material, Options, PointForce, Scene, Traction
from .stress_field import LinearStress
from .solve import solve, solve_plain
from .io import write_vtu
from .contact import ContactError
from .mesh import create_plate_with_hole
from .outputs import OutputError
from .scene_file import SceneFile, load_scene_file

__version__ = "0.1.0"

__all__ = [
    "BoundaryConditionError", "Crack", "CrackGeometryError", "CracklipError", "Dirichlet",
    "InputError", "Material", "MaterialError", "MeshData", "MeshError", "Options", "Scene",
    "Solution", "SolverError", "Traction", "XfemModel", "create_half_annulus", "create_model",
    "create_rectangle", "create_square", "read_msh", "solve", "solve_plain", "write_vtu",
    "ContactError", "OutputError", "SceneFile", "create_plate_with_hole", "load_scene_file",
    "LinearStress", "LoadStep", "PointForce",
]
