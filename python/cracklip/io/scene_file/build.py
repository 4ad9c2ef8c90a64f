"""Building a scene file: its mesh, material, cracks, conditions, loads,
options and growth, section by section (the modules beside this one), into
a cracklip Scene (``SceneFile``); each condition and load leaves a line in
the notes saying what it became."""
from __future__ import annotations

import dataclasses
import pathlib
import time
import typing

from ...errors import InputError, MeshError, checked_keywords
from ...scene.options import Options
from ...scene.processes import replicated
from ...scene.scene import Scene
from .conditions import build_conditions, build_load_path, build_loads, build_symmetry
from .cracks import build_crack, crack_surface, describe_crack
from .dimension import check_dimension, scene_dimension
from .growth import check_growth, read_growth
from .material import build_material, build_units
from .mesh import build_mesh, scene_path
from .reader import apply_override, parse_settings, read_document


@dataclasses.dataclass(repr=False)
class SceneFile:
    """A scene file read and built.

    Attributes:
        path: the file (None for a document given directly).
        title: the title (or the file's stem).
        settings: every key with its value (parse_settings).
        scene: the cracklip Scene.
        growth: the [growth] settings (cracklip.scene.growth.Growth), or None.
        outputs: the [outputs] settings.
        notes: one line per boundary condition and load, saying what it became.
        timings: seconds spent meshing ("mesh").
    """
    path: pathlib.Path | None
    title: str
    settings: dict
    scene: Scene
    outputs: dict
    notes: list[str]
    timings: dict[str, float]
    growth: typing.Any = None

    def __repr__(self) -> str:
        """The file and what it built, on one line (the dataclass's repr printed every setting)."""
        sc = self.scene
        names = ", ".join(repr(getattr(c, "name", "")) for c in sc.cracks) or "none"
        return (f"SceneFile({self.title!r}; {self.path}; {sc.mesh.gdim}D mesh, {sc.mesh.mesh.topology.index_map(0).size_global}"
                f" nodes; cracks [{names}]; {len(sc.dirichlet)} Dirichlet, {len(sc.tractions)} tractions; growth "
                f"{'yes' if self.growth is not None else 'none'}; .scene for cl.solve, .growth for cl.grow, .settings, "
                f".notes)")


@checked_keywords
def load_scene_file(path: str | pathlib.Path, overrides: typing.Sequence[str] = ()) -> SceneFile:
    """Read, validate and build a scene file (TOML, keys: docs/scene_reference.md, or
    ``python3 -m cracklip reference``); returns a SceneFile: .scene for cl.solve, .growth (the
    [growth] table, or None) for cl.grow. overrides: ``KEY=VALUE`` strings (one, or a list) that
    replace the file's values, as ``--set`` does on the command line (e.g. "mesh.h=0.05")."""
    if isinstance(overrides, str):  # one override: not its characters one by one
        overrides = [overrides]
    path = pathlib.Path(path)
    doc = read_document(path)
    for o in overrides:
        apply_override(doc, o)
    return build_scene(doc, base_dir=path.parent, path=path)


def _before_mesh(doc: dict, base_dir: pathlib.Path):
    """The settings, units, material, dimension (and why), growth settings
    (with the fatigue inputs' files) and cracks of a scene document, and
    its mesh file checked to exist: what needs no mesh."""
    s = parse_settings(doc)
    units = build_units(s)
    material = build_material(s)
    dim, why = scene_dimension(s)
    growth = read_growth(s, "life" in doc, units, base_dir)  # with the fatigue inputs' files: before meshing
    if dim == 3:
        cracks = [crack_surface(c, i, base_dir) for i, c in enumerate(s["cracks"])]
    else:
        cracks = [build_crack(c, i) for i, c in enumerate(s["cracks"])]
    if s["mesh"]["kind"] in ("file", "geometry"):
        scene_path(s["mesh"], base_dir)
    return s, units, material, dim, why, growth, cracks


def build_scene(doc: dict, base_dir: str | pathlib.Path = ".", path: pathlib.Path | None = None,
                memory_limit: float | None = None) -> SceneFile:
    """Validate a scene document and build its mesh and Scene. memory_limit:
    a solid whose run is estimated to need more bytes is refused before
    meshing (ModelSizeError; None: no limit; the command line gives the
    machine's available memory unless --force)."""
    base_dir = pathlib.Path(base_dir)
    # Everything before the mesh is read by every process alike (under
    # mpirun): an error there (a material out of range, a missing spectrum,
    # crack surface or mesh file) is raised on all, printed once.
    s, units, material, dim, why, growth, cracks = replicated(lambda: _before_mesh(doc, base_dir))
    t0 = time.perf_counter()
    points = [bc["point"] for bc in s["dirichlet"] if "point" in bc] + \
        [pf["point"] for pf in s["loads"]["point_forces"]]
    mesh = build_mesh(s["mesh"], cracks, base_dir, points, dim, memory_limit)
    t_mesh = time.perf_counter() - t0
    gdim = mesh.gdim
    if dim is None:
        check_dimension(doc, s, gdim, f"mesh.path {s['mesh']['path']!r} holds a {'solid' if gdim == 3 else 'planar part'}")
    elif gdim != dim:
        raise MeshError(f"mesh.path {s['mesh']['path']!r} holds a {gdim}D part ({'tetrahedra' if gdim == 3 else 'triangles'}) "
                        f"but {why}: the scene is {dim}D; give "
                        + ("crack surfaces (ellipse, polygon, surface)" if gdim == 3 else "2D cracks (points, arc)")
                        + " or the matching part")
    notes: list[str] = []
    if gdim == 3:
        notes += [f"cracks[{i}] {describe_crack(c)}" for i, c in enumerate(cracks)]
    dirichlet = build_conditions(s, mesh, material, cracks, notes)
    symmetry = build_symmetry(s, mesh, notes)
    loads = build_loads(s, mesh, material, cracks, notes)
    try:
        options = Options(**s["options"])
    except InputError as e:  # Options' messages begin with the field: name it as the scene key
        text = str(e)
        field = text.split(" ", 1)[0]
        raise InputError(f"options.{text}" if field in {f.name for f in dataclasses.fields(Options)}
                         else f"options: {text}") from None
    load_path = build_load_path(s, options, notes)
    scene = Scene(mesh, material, cracks=cracks, dirichlet=dirichlet, tractions=loads["tractions"],
                  options=options, body_force=loads["body_force"], point_forces=loads["point_forces"],
                  initial_stress=loads["initial_stress"], body_force_group=s["loads"]["body_force_group"],
                  initial_stress_group=s["loads"].get("initial_stress", {}).get("group", "default"),
                  load_path=load_path, units=units, symmetry=symmetry)
    if load_path is not None:
        from ...scene.load_path import steps
        steps(scene)  # unknown groups are an InputError now, not at the solve
    title = s["title"] or (path.stem if path is not None else "scene")
    check_growth(growth, scene, notes)
    return SceneFile(path, title, s, scene, s["outputs"], notes, {"mesh": t_mesh}, growth)
