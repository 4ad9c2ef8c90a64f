"""cracklip: X-FEM cracks on DOLFINx, in planar parts (triangles: crack-lip
contact, growth, fatigue life) and in solids (tetrahedra: K along the crack
fronts), through one pipeline: the dimension is the mesh's.

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
PETSc and the C++ module load (cracklip.cli.prefetch).

The package follows the method, one subpackage per step in the order data
flows; a module imports only from its own step or earlier ones
(tests/test_layering.py checks it, from LAYERS below):

    scene     what the user describes: mesh, material, cracks, loads, options
    model     the discrete X-FEM model: the cracks on the mesh (one interface,
              a curve with tips or a surface with fronts), enrichment,
              constraints, room around the tips, model checks, assembly
    solvers   checked linear solves: direct, phantom basis + AMG, saddle point
    contact   crack-lip contact and friction on the stable multiplier space
    fracture  stress intensity factors, kink criteria, growth laws, cycle
              counting, retardation, life integration (pure functions)
    post      a solved model: Solution, fields along the crack and in the part
    analysis  drivers that solve: one scene, a load path, crack growth, the
              fatigue life's load levels
    exact     closed-form fields for demos, tests and exact boundary values
    io        scene files and output writers (JSON, CSV, VTU, PNG)
    cli       the command line
"""
import importlib
import importlib.util

if importlib.util.find_spec(f"{__name__}._cracklip") is None:  # pragma: no cover
    raise ImportError(
        "cracklip's C++ module is not built: run "
        "`cmake -S . -B build -DPython3_EXECUTABLE=/usr/bin/python3 && cmake --build build -j2` "
        "in the repository root")

__version__ = "0.1.0"

#: The steps of the method, in the order data flows (see the docstring).
#: errors and the C++ module _cracklip come before all of them.
LAYERS = ("scene", "model", "solvers", "contact", "fracture", "post", "analysis", "exact", "io", "cli")

#: Public name -> submodule that defines it.
_EXPORTS = {
    "BoundaryConditionError": "errors", "CrackGeometryError": "errors", "CracklipError": "errors",
    "InputError": "errors", "InputFileError": "errors", "MaterialError": "errors", "MeshError": "errors",
    "SolverError": "errors",
    "ModelSizeError": "errors", "KeywordError": "errors",
    "MeshData": "scene.mesh", "create_half_annulus": "scene.mesh", "create_rectangle": "scene.mesh",
    "create_square": "scene.mesh", "read_msh": "scene.mesh", "create_plate_with_hole": "scene.mesh",
    "create_plate_with_holes": "scene.mesh", "create_from_geometry": "scene.geometry_file",
    "refine_file_mesh": "scene.refine",
    "Crack": "scene.crack", "Material": "scene.material", "Options": "scene.options", "Scene": "scene.scene",
    "Dirichlet": "scene.conditions", "Symmetry": "scene.symmetry", "LoadStep": "scene.conditions",
    "PointForce": "scene.conditions",
    "Traction": "scene.conditions",
    "LinearStress": "scene.stress_field",
    "Growth": "scene.growth",
    "FatigueMaterial": "scene.fatigue", "Spectrum": "scene.spectrum", "SpectrumBlock": "scene.spectrum",
    "Units": "scene.units",
    "count_cycles": "fracture.rainflow", "rainflow": "fracture.rainflow", "LifeLaw": "fracture.life",
    "XfemModel": "model.model", "create_model": "model.model", "CrackModel": "model.model",
    "ContactError": "contact.frictionless",
    "Solution": "post.solution",
    "solve": "analysis.solve", "solve_plain": "analysis.solve", "grow": "analysis.growth",
    "estimate_error": "analysis.accuracy",
    "write_vtu": "io.paraview",
    "OutputError": "io.outputs",
    "SceneFile": "io.scene_file", "load_scene_file": "io.scene_file",
    "life": "analysis.table_life", "LifeFile": "io.life_file", "load_life_file": "io.life_file",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
