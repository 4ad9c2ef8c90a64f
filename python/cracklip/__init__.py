"""cracklip: X-FEM cracks with crack-lip contact on DOLFINx.

Quick use::

    import cracklip as cl
    mesh = cl.create_square(h=0.1)
    scene = cl.Scene(mesh, cl.Material(E=1.0, nu=0.3),
                     cracks=[cl.Crack([[-1.0, 0.0], [0.0, 0.0]])],
                     dirichlet=[cl.Dirichlet("bottom")],
                     tractions=[cl.Traction("top", (0.0, 0.01))])
    solution = cl.solve(scene)

The names below are loaded on first use (PEP 562): ``import cracklip``
alone costs nothing, so the command line can start meshing while DOLFINx,
PETSc and the C++ module load (cracklip.prefetch).
"""
import importlib
import importlib.util
import sys
import types

if importlib.util.find_spec(f"{__name__}._cracklip") is None:  # pragma: no cover
    raise ImportError(
        "cracklip's C++ module is not built: run "
        "`cmake -S . -B build -DPython3_EXECUTABLE=/usr/bin/python3 && cmake --build build -j2` "
        "in the repository root")

__version__ = "0.1.0"

#: Public name -> submodule that defines it.
_EXPORTS = {
    "BoundaryConditionError": "errors", "CrackGeometryError": "errors", "CracklipError": "errors",
    "InputError": "errors", "MaterialError": "errors", "MeshError": "errors", "SolverError": "errors",
    "MeshData": "mesh", "create_half_annulus": "mesh", "create_rectangle": "mesh", "create_square": "mesh",
    "read_msh": "mesh", "create_plate_with_hole": "mesh", "create_plate_with_holes": "mesh",
    "XfemModel": "model", "create_model": "model",
    "Solution": "post",
    "Crack": "scene", "Dirichlet": "scene", "LoadStep": "scene", "Material": "scene", "Options": "scene",
    "PointForce": "scene", "Scene": "scene", "Traction": "scene",
    "LinearStress": "stress_field",
    "solve": "solve", "solve_plain": "solve",
    "write_vtu": "io",
    "ContactError": "contact",
    "OutputError": "outputs",
    "SceneFile": "scene_file", "load_scene_file": "scene_file",
}

__all__ = sorted(_EXPORTS)


class _Package(types.ModuleType):
    """The package module: importing the submodule cracklip.solve must not
    replace the function cracklip.solve (importlib sets a package attribute
    for every submodule it loads; the eager __init__ rebound it after)."""

    def __setattr__(self, name: str, value) -> None:
        if isinstance(value, types.ModuleType) and name in _EXPORTS:
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package


def __getattr__(name: str):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
