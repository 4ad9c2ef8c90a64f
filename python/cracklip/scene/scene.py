"""The scene: everything a solve needs (mesh, material, cracks, conditions, loads, options)."""
from __future__ import annotations

import dataclasses
import typing

import numpy as np

from ..errors import BoundaryConditionError, CrackGeometryError, InputError, checked_keywords
from .conditions import Dirichlet, LoadStep, PointForce, Traction
from .crack import Crack
from .crack_surface import EllipticalCrack, PolygonCrack, SurfaceCrack
from .material import Material
from .mesh import MeshData
from .options import Options
from .units import Units
from .stress_field import as_stress_field
from .symmetry import Symmetry, SymmetryCondition, symmetry_conditions


@checked_keywords
@dataclasses.dataclass
class Scene:
    """Everything a solve needs: cl.solve(scene) -> Solution, cl.grow(scene, cl.Growth(...)).

    Numbers are in any consistent units (units only labels them): lengths as the mesh's, E and
    stresses in force / length^2, K in stress * sqrt(length).

    Attributes:
        mesh: a MeshData (cl.create_square, create_rectangle, read_msh, create_from_geometry, ...):
            the DOLFINx mesh with its named boundary tags.
        material: a cl.Material(E, nu, plane).
        cracks: a list of cl.Crack (2D polylines; 3D: crack surfaces); a bare (k, 2) point list
            is taken as Crack(points). A crack's index here or its name selects it in a Solution.
        dirichlet: a list of cl.Dirichlet (at least one: rigid motion must be fixed).
        tractions: a list of cl.Traction (force per length in 2D, per area in 3D).
        options: a cl.Options (enrichment, contact, SIF domains, solver, accuracy target).
        body_force: constant (f_x, f_y) force per unit area (volume in 3D), or None.
        point_forces: a list of cl.PointForce at mesh nodes.
        initial_stress: residual stress sigma_0: (sxx, syy, sxy), a cl.LinearStress or a
            callable sigma_0(x) (2D only); sigma = C eps(u) + sigma_0.
        body_force_group, initial_stress_group: load groups of those loads.
        load_path: a list of cl.LoadStep (or dicts of factors per load group) solved in order;
            None: one step with every group at factor 1.
        units: a cl.Units (labels of outputs and unit conversions), or None.
        symmetry: a list of cl.Symmetry (or boundary tags): u . n = 0 on each plane.

    A wrong type of any of these is an InputError at construction.
    """
    mesh: MeshData
    material: Material
    cracks: list[Crack] = dataclasses.field(default_factory=list)
    dirichlet: list[Dirichlet] = dataclasses.field(default_factory=list)
    tractions: list[Traction] = dataclasses.field(default_factory=list)
    options: Options = dataclasses.field(default_factory=Options)
    #: Constant body force (f_x, f_y), force per unit area, or None.
    body_force: typing.Optional[typing.Sequence[float]] = None
    #: Concentrated forces at nodes.
    point_forces: list[PointForce] = dataclasses.field(default_factory=list)
    #: Initial (residual) stress sigma_0 of the part, or None: the stress is
    #: sigma = C eps(u) + sigma_0, so sigma_0 acts through its equivalent
    #: loads (-div sigma_0 inside, sigma_0 n on the boundary and the lips).
    #: 2D (sxx, syy, sxy), 3D (sxx, syy, szz, syz, sxz, sxy), a
    #: stress_field.LinearStress of the part's dimension or a callable
    #: sigma_0(x) (points (n, d) -> (n, d, d) or Voigt components).
    initial_stress: typing.Any = None
    #: Load groups of the body force and the initial stress.
    body_force_group: str = "default"
    initial_stress_group: str = "default"
    #: The load path: steps of factors per load group (LoadStep), solved in
    #: order with Options.load_steps increments per step; friction is
    #: path-dependent, so its slip and states carry over. None: one step
    #: with every group at factor 1.
    load_path: typing.Optional[list] = None
    #: The units of the scene's numbers (labels and conversions only), or None.
    units: typing.Optional[Units] = None
    #: Symmetry planes (Symmetry, or a boundary tag): each adds its
    #: SymmetryCondition (u . n = 0) to ``dirichlet`` (scene.symmetry).
    symmetry: list[Symmetry] = dataclasses.field(default_factory=list)

    def __post_init__(self):
        check_types(self)
        if self.load_path is not None:
            self.load_path = [st if isinstance(st, LoadStep) else LoadStep(dict(st), name=f"step {k + 1}")
                              for k, st in enumerate(self.load_path)]
            for k, st in enumerate(self.load_path):
                st.name = st.name or f"step {k + 1}"
            if not self.load_path:
                raise InputError("load_path is empty: give at least one step, or None for one step at factor 1")
        gdim = getattr(self.mesh, "gdim", 2)
        if self.initial_stress is not None:
            self.initial_stress = as_stress_field(self.initial_stress, "initial stress", gdim)
        for i, c in enumerate(self.cracks):
            if gdim == 3:
                if not isinstance(c, (EllipticalCrack, PolygonCrack, SurfaceCrack)):
                    raise CrackGeometryError(f"crack {i}: a 3D part takes crack surfaces (cracks[].ellipse, polygon "
                                             f"or surface), not a 2D crack (a polyline, cracks[].points)")
                c.name = c.name or f"crack {i}"
            elif not isinstance(c, Crack):
                self.cracks[i] = Crack(np.asarray(c), name=f"crack {i}")
            elif not c.name:
                c.name = f"crack {i}"
        names = {2: "(t_x, t_y)", 3: "(t_x, t_y, t_z)"}
        for tr in self.tractions:
            if tr.value is not None and not callable(tr.value) and len(np.ravel(tr.value)) != gdim:
                raise InputError(f"traction on {tr.where!r}: {len(np.ravel(tr.value))} components on a {gdim}D "
                                 f"part; give {names[gdim]}")
            if tr.stress is not None and gdim == 3 and not callable(tr.stress):
                raise InputError(f"traction on {tr.where!r}: a 3D part takes the stress of a traction as a callable "
                                 "sigma(x) returning (n, 3, 3)")
        for pf in self.point_forces:
            if len(pf.point) != gdim:
                raise InputError(f"point force at {pf.point}: {len(pf.point)} coordinates on a {gdim}D part")
        self.symmetry = [p if isinstance(p, Symmetry) else Symmetry(p) for p in self.symmetry]
        self.dirichlet = [d for d in self.dirichlet if not isinstance(d, SymmetryCondition)] \
            + symmetry_conditions(self.mesh, self.symmetry)
        if not self.dirichlet:
            raise BoundaryConditionError(f"the scene has no Dirichlet condition: rigid body motion is free; "
                                         f"{rigid_motion_hint(gdim)}")


#: Scene field -> (class of its items, what to write): the lists of conditions and loads.
LIST_FIELDS = {"dirichlet": (Dirichlet, "cl.Dirichlet(where, component, value)"),
               "tractions": (Traction, "cl.Traction(where, value)"),
               "point_forces": (PointForce, "cl.PointForce(point, value)")}


def _kind(value) -> str:
    """A value for a message: its repr on one line, cut to 60 characters, and its type."""
    text = " ".join(repr(value).split())
    return f"{text if len(text) <= 60 else text[:57] + '...'} ({type(value).__name__})"


def check_types(scene: Scene) -> None:
    """A wrong type of a scene field is an InputError naming the field and what to give, here rather
    than an AttributeError deep in the model (a dolfinx Mesh for the MeshData, a single Crack for the
    list of cracks)."""
    if not isinstance(scene.mesh, MeshData):
        raise InputError(f"Scene.mesh must be a cracklip MeshData (cl.create_square, cl.create_rectangle, "
                         f"cl.read_msh, cl.create_from_geometry: the mesh with its boundary tags), got "
                         f"{_kind(scene.mesh)}")
    if not isinstance(scene.material, Material):
        raise InputError(f"Scene.material must be a cl.Material(E, nu, plane), got {_kind(scene.material)}")
    if not isinstance(scene.options, Options):
        raise InputError(f"Scene.options must be a cl.Options(...) (keywords: help(cl.Options)), got "
                         f"{_kind(scene.options)}")
    if scene.units is not None and not isinstance(scene.units, Units):
        raise InputError(f"Scene.units must be a cl.Units or None, got {_kind(scene.units)}")
    for name in ("cracks", "symmetry", *LIST_FIELDS):
        value = getattr(scene, name)
        if not isinstance(value, (list, tuple)):
            raise InputError(f"Scene.{name} must be a list, got {_kind(value)}; for one item write "
                             f"{name}=[item]")
        setattr(scene, name, list(value))
    for name, (cls, write) in LIST_FIELDS.items():
        for i, item in enumerate(getattr(scene, name)):
            if not isinstance(item, cls):
                raise InputError(f"Scene.{name}[{i}] must be a {write}, got {_kind(item)}")


def require_scene(scene, who: str) -> None:
    """An InputError unless scene is a Scene, saying what to pass instead (who: the function)."""
    if isinstance(scene, Scene):
        return
    if isinstance(getattr(scene, "scene", None), Scene):  # a SceneFile (cracklip.io, a later layer)
        hint = f"a scene file read by cl.load_scene_file holds it: {who}(scene_file.scene"
        hint += ", scene_file.growth)" if who == "grow" else ")"
    elif isinstance(scene, (str, bytes)) or hasattr(scene, "__fspath__"):
        hint = f"read the file first: {who}(cl.load_scene_file(path).scene{', ...' if who == 'grow' else ''})"
    else:
        hint = "build one with cl.Scene(mesh, material, cracks=[...], dirichlet=[...], tractions=[...])"
    raise InputError(f"{who}() takes a cl.Scene, got {_kind(scene)}; {hint}")


def rigid_motion_hint(gdim: int) -> str:
    """What to constrain so that a part of dimension gdim cannot move rigidly."""
    if gdim == 3:
        return ("fix at least u_x, u_y and u_z at one point, two more components at a second point and one more "
                "at a third (or a whole face)")
    return "fix at least u_x and u_y somewhere and one more component elsewhere"


def load_groups(scene) -> set[str]:
    """The names of the load groups the scene's loads and Dirichlet values use."""
    groups = {t.group for t in scene.tractions} | {p.group for p in scene.point_forces}
    groups |= {d.group for d in scene.dirichlet if callable(d.value) or d.value != 0.0}
    groups |= {c.pressure_group for c in scene.cracks if callable(c.pressure) or c.pressure != 0.0}
    if scene.body_force is not None and np.any(scene.body_force):
        groups.add(scene.body_force_group)
    if scene.initial_stress is not None:
        groups.add(scene.initial_stress_group)
    return groups
