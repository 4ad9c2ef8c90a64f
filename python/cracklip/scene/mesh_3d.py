"""Tetrahedral meshes from gmsh: boxes and cylinders at a given size, refined
around crack fronts, or a user's .msh file (a pair with mesh.py, the
planar parts, because the geometry differs: a solid is meshed in volumes
and refined along crack fronts rather than around tips; MeshData, the mesh
checks and the conversion to DOLFINx are mesh.py's, for both).

Every mesh comes with named boundary tags on its faces (``MeshData.tags``):
the box has ``xmin``, ``xmax``, ``ymin``, ``ymax``, ``zmin``, ``zmax``; the
cylinder ``bottom``, ``top`` (its end faces) and ``side``; a file its named
physical surfaces.

Refinement around a front: the element size is h_front within a plateau of
PLATEAU x h_front of the front and grows linearly (at most MAX_GROWTH per
unit distance) to h away from it, as the 2D refinement around a tip. The
front is given as points sampled along it (every front_sampling(h_front) or
closer); gmsh's Distance field measures the distance to them.

The default grading of a crack (crack_refinements without a growth) grows
the size by FRONT_GROWTH h_front per crack size (crack_size: twice the
crack's area over its perimeter, a penny's radius): every size near the
crack then scales with h_front, and K converges as h_front is refined (a
growth fixed per unit length leaves the region beyond the front as coarse
as it was, and K's error stalls: docs/guide.md, the 3D meshing recipe).

Every mesh has a recipe (MeshData.recipe) that makes it again with every
size setting times a factor (size_factor: h and every h_front, the
grading's radii kept, so that its plateau and its growth scale too): the
mesh the scene gives with every size times the factor, for the error
estimate of K and refinement to an accuracy (cracklip.analysis.accuracy).
(gmsh's Mesh.MeshSizeFactor scales the sizes but not the plateau, 4
h_front: on the penny at a/20 that family's K converged faster than the
scene's own, p about 3 against 2.4, and an estimate at the rate 1 was 5
times the error instead of 3.)
"""
from __future__ import annotations

import dataclasses
import functools
import logging
import pathlib
import typing

import numpy as np

from ..errors import MeshError, ModelSizeError
from .mesh import MeshData, _gmsh, gmsh_on_rank0, to_dolfinx
from .mesh_estimate import CURVATURE_ELEMENTS, MeshEstimate, check_estimate, estimate
from .size_field import refinement_size

logger = logging.getLogger(__name__)

#: Tetrahedra per unit volume of gmsh's mesh of size h: about 6 / h^3 (each
#: node ~1 / (0.95 h^3)); used to say how big a mesh will be before making it.
TETS_PER_VOLUME_H3 = 6.0


@dataclasses.dataclass(frozen=True)
class FrontRefinement:
    """A refinement around a crack front.

    Attributes:
        points: (m, 3) points along the front, at most about h_front / 2
            apart (front_points of the crack surfaces give them).
        h_front: element size at the front.
        radius: the distance over which the size grows from h_front to the
            mesh size (lengthened if the growth would exceed MAX_GROWTH).
        kind: what the points sample: "curve" (a front, a segment),
            "surface" (a crack's surface) or "points" (isolated points);
            the size estimate before meshing models each by its shape.
    """
    points: np.ndarray
    h_front: float
    radius: float
    kind: str = "curve"

    def __post_init__(self):
        pts = np.asarray(self.points, dtype=float).reshape(-1, 3)
        if len(pts) == 0 or not np.all(np.isfinite(pts)):
            raise MeshError("a front refinement needs finite front points (m, 3), m >= 1")
        if not (self.h_front > 0.0 and self.radius >= 0.0):
            raise MeshError(f"a front refinement needs h_front > 0 and radius >= 0, got {self.h_front!r}, "
                            f"{self.radius!r}")
        object.__setattr__(self, "points", pts)


@dataclasses.dataclass(frozen=True)
class BoxRefinement:
    """A refinement of a box-shaped region (where a 3D crack will grow: its
    front must stay in elements of the size it started in).

    Attributes:
        lo, hi: (3,) the box's opposite corners.
        h_front: element size inside the box.
        radius: the distance over which the size grows back to the mesh size
            outside it (lengthened if the growth would exceed MAX_GROWTH).
    """
    lo: tuple[float, float, float]
    hi: tuple[float, float, float]
    h_front: float
    radius: float

    def __post_init__(self):
        lo, hi = np.asarray(self.lo, dtype=float).reshape(-1), np.asarray(self.hi, dtype=float).reshape(-1)
        if lo.shape != (3,) or hi.shape != (3,) or not np.all(hi > lo) or not np.all(np.isfinite(np.r_[lo, hi])):
            raise MeshError(f"a box refinement needs corners lo < hi (3 finite numbers each), got {self.lo!r}, "
                            f"{self.hi!r}")
        if not (self.h_front > 0.0 and self.radius >= 0.0):
            raise MeshError(f"a box refinement needs h > 0 and radius >= 0, got {self.h_front!r}, {self.radius!r}")
        object.__setattr__(self, "lo", tuple(float(v) for v in lo))
        object.__setattr__(self, "hi", tuple(float(v) for v in hi))


#: Element size over a crack's surface, in front sizes (crack_refinements).
SURFACE_SIZE = 2.0

#: Growth of the element size per unit distance from a crack (crack_refinements):
#: the opening of a penny crack at a/h = 20 at the front, the rest scaled
#: alike, is 1.5 % low with 0.1 and 1.2 % with 0.07 (3e5 dofs; the error
#: is the bulk's: P1 tetrahedra are stiff where the crack's field decays).
GROWTH = 0.07

#: The default grading (crack_refinements without a growth): the size grows
#: by FRONT_GROWTH h_front per crack size away from the front (GROWTH at
#: h_front = crack size / 20; demos/front_sifs.py's meshes, on which the
#: penny's K converges at rate 2: 0.67, 0.34, 0.16 % RMS at a/10, 14, 20).
FRONT_GROWTH = 20.0 * GROWTH


def crack_size(crack) -> float:
    """A crack's size for its grading: twice its area over its perimeter
    (a circle's radius; 0.65 a for an ellipse of semi-axes a and a / 2)."""
    return 2.0 * float(crack.area) / float(crack.perimeter)


def default_growth(crack, h_front: float) -> float:
    """The default grading's growth per unit distance (FRONT_GROWTH)."""
    return FRONT_GROWTH * h_front / crack_size(crack)


def crack_refinements(cracks, h_front: float, h: float, growth: float | None = None,
                      h_surface: float | None = None) -> list[FrontRefinement]:
    """Refinements for 3D cracks: h_front along each front, h_surface
    (default SURFACE_SIZE h_front; h or more: none) over each crack's
    surface, sizes growing by `growth` per unit distance up to h (default:
    default_growth of each crack)."""
    if not (h_front > 0.0 and h > 0.0 and (growth is None or growth > 0.0)):
        raise MeshError(f"crack refinements need h_front, h and growth > 0, got {h_front!r}, {h!r}, {growth!r}")
    hs = SURFACE_SIZE * h_front if h_surface is None else float(h_surface)
    out = []
    for crack in cracks:
        g = default_growth(crack, h_front) if growth is None else growth
        out.append(FrontRefinement(crack.front_points(front_sampling(h_front)), h_front,
                                   max(h - h_front, 0.0) / g))
        if hs < h:
            out.append(FrontRefinement(crack.surface_points(0.5 * hs), hs, (h - hs) / g, "surface"))
    return out


def front_sampling(h_front: float) -> float:
    """The largest spacing of the points of a front refinement: h_front / 2
    (the Distance field then errs by at most h_front / 8 near the front)."""
    return 0.5 * h_front


def scaled(fronts: typing.Sequence[FrontRefinement], factor: float) -> list[FrontRefinement]:
    """Front refinements with every h_front times factor, radii kept."""
    return [dataclasses.replace(f, h_front=f.h_front * factor) for f in fronts]


def _size_fields(gmsh, h: float, fronts: typing.Sequence[FrontRefinement], kernel: str = "occ",
                 size_factor: float = 1.0) -> None:
    h, fronts = h * size_factor, scaled(fronts, size_factor)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeMin", min([h] + [f.h_front for f in fronts]))
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    if not fronts:
        return
    fields = []
    # The points in the kernel of the part's own model (occ for the
    # generated shapes and OpenCASCADE files, geo for a built-in .geo): the
    # other kernel's numbering would reuse the tags of the part's own
    # points, and synchronizing would replace them.
    factory = getattr(gmsh.model, kernel)
    for fr in fronts:
        if isinstance(fr, BoxRefinement):
            # gmsh's Box field: h_front inside, growing linearly to h over a layer of (h - h_front) / growth.
            plateau, growth = refinement_size(h, fr.h_front, fr.radius)
            f = gmsh.model.mesh.field.add("Box")
            for key, v in zip(("XMin", "YMin", "ZMin", "XMax", "YMax", "ZMax"), fr.lo + fr.hi):
                gmsh.model.mesh.field.setNumber(f, key, float(v))
            gmsh.model.mesh.field.setNumber(f, "VIn", float(fr.h_front))
            gmsh.model.mesh.field.setNumber(f, "VOut", float(h))
            gmsh.model.mesh.field.setNumber(f, "Thickness", float(max(h - fr.h_front, 0.0) / max(growth, 1e-12)))
            fields.append(f)
            continue
        tags = [factory.addPoint(*map(float, p)) for p in fr.points]
        factory.synchronize()
        dist = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(dist, "PointsList", tags)
        plateau, growth = refinement_size(h, fr.h_front, fr.radius)
        f = gmsh.model.mesh.field.add("MathEval")
        gmsh.model.mesh.field.setString(
            f, "F", "Min(({0!r}), ({1!r}) + ({2!r}) * Max(0, F{3} - ({4!r})))".format(
                float(h), float(fr.h_front), float(growth), dist, float(plateau)))
        fields.append(f)
    fmin = gmsh.model.mesh.field.add("Min")
    gmsh.model.mesh.field.setNumbers(fmin, "FieldsList", fields)
    gmsh.model.mesh.field.setAsBackgroundMesh(fmin)


#: The coarse mesh of a size estimate has at most about this many tetrahedra
#: (coarser than h for a part of many elements).
COARSE_CELLS = 50_000


def estimate_size(gmsh, h: float, fronts: typing.Sequence[FrontRefinement], memory_limit: float | None,
                  what: str) -> MeshEstimate:
    """Estimate the mesh gmsh's current model will get at size h with the
    fronts' refinements, before making it (cracklip.scene.mesh_estimate: a
    coarse mesh at h, or coarser for a part of more than COARSE_CELLS
    elements, following curved faces; cleared afterwards); raise
    ModelSizeError if its run would need more than memory_limit bytes."""
    x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(-1, -1)
    volume = (x1 - x0) * (y1 - y0) * (z1 - z0)
    coarse = max(h, (TETS_PER_VOLUME_H3 * volume / COARSE_CELLS) ** (1.0 / 3.0))
    gmsh.option.setNumber("Mesh.MeshSizeMax", coarse)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", CURVATURE_ELEMENTS)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)
    gmsh.model.mesh.generate(3)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = np.zeros((int(tags.max()) + 1 if len(tags) else 0, 3))
    xyz[tags.astype(np.int64)] = coords.reshape(-1, 3)
    tets = []
    for etype, _, enodes in zip(*gmsh.model.mesh.getElements(3)):
        if etype == 4:  # 4-node tetrahedra
            tets.append(xyz[np.asarray(enodes, dtype=np.int64).reshape(-1, 4)])
    gmsh.model.mesh.clear()
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    est = estimate(np.concatenate(tets) if tets else np.zeros((0, 4, 3)), h, fronts)
    logger.info("%s: %s expected (estimated before meshing)", what, est.describe())
    try:
        check_estimate(est, memory_limit, what)
    except ModelSizeError:
        gmsh.model.remove()
        raise
    return est


def _finish(gmsh, groups: dict[str, list[int]], h: float, fronts, size_factor: float = 1.0, recipe=None,
            memory_limit: float | None = None, what: str = "the part") -> MeshData:
    """Name the face groups as physical surfaces 1, 2, ... (in order), the
    volumes as physical volume 1, estimate the mesh (refused above
    memory_limit bytes), mesh in 3D with the front size fields (every size
    times size_factor), convert; recipe(size_factor=...) makes it again."""
    gmsh.model.addPhysicalGroup(3, [v for _, v in gmsh.model.getEntities(3)], 1)
    for tag, (name, surfaces) in enumerate(groups.items(), start=1):
        gmsh.model.addPhysicalGroup(2, surfaces, tag)
        gmsh.model.setPhysicalName(2, tag, name)
    est = estimate_size(gmsh, h * size_factor, scaled(fronts, size_factor), memory_limit, what)
    _size_fields(gmsh, h, fronts, size_factor=size_factor)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay: robust, deterministic in serial
    gmsh.model.mesh.generate(3)
    md = to_dolfinx(gmsh, h, dim=3, fronts=scaled(fronts, size_factor), size_factor=size_factor)
    md.recipe = recipe
    md.estimate = est
    return md


@gmsh_on_rank0
def create_box(x0: float, y0: float, z0: float, x1: float, y1: float, z1: float, h: float,
               fronts: typing.Sequence[FrontRefinement] = (), memory_limit: float | None = None,
               size_factor: float = 1.0) -> MeshData:
    """The box [x0, x1] x [y0, y1] x [z0, z1] in tetrahedra of size h (h_front
    around the fronts; every size times size_factor). Tags: xmin, xmax,
    ymin, ymax, zmin, zmax. memory_limit: refuse (ModelSizeError) a mesh
    whose run is estimated to need more bytes (None: no limit)."""
    lo, hi = np.array([x0, y0, z0], dtype=float), np.array([x1, y1, z1], dtype=float)
    if not np.all(hi > lo) or not np.all(np.isfinite(lo)) or not np.all(np.isfinite(hi)):
        raise MeshError(f"empty or infinite box [{x0}, {x1}] x [{y0}, {y1}] x [{z0}, {z1}]")
    if not (0.0 < h <= float(np.max(hi - lo))):
        raise MeshError(f"mesh size h = {h} must be positive and at most the box size")
    gmsh = _gmsh()
    gmsh.model.add("box")
    gmsh.model.occ.addBox(x0, y0, z0, x1 - x0, y1 - y0, z1 - z0)
    gmsh.model.occ.synchronize()
    eps = 1e-7 * float(np.max(hi - lo))
    groups: dict[str, list[int]] = {k: [] for k in ("xmin", "xmax", "ymin", "ymax", "zmin", "zmax")}
    for _, s in gmsh.model.getEntities(2):
        c = np.array(gmsh.model.occ.getCenterOfMass(2, s))
        for axis, name in enumerate("xyz"):
            if abs(c[axis] - lo[axis]) < eps:
                groups[f"{name}min"].append(s)
            elif abs(c[axis] - hi[axis]) < eps:
                groups[f"{name}max"].append(s)
    return _finish(gmsh, groups, h, fronts, size_factor,
                   functools.partial(create_box, x0, y0, z0, x1, y1, z1, h, fronts=fronts), memory_limit, "the box")


@gmsh_on_rank0
def create_cylinder(center: typing.Sequence[float], axis: typing.Sequence[float], radius: float, length: float,
                    h: float, fronts: typing.Sequence[FrontRefinement] = (),
                    memory_limit: float | None = None, size_factor: float = 1.0) -> MeshData:
    """A solid cylinder: its bottom face centred at `center`, extruded by
    `length` along the unit vector `axis`, of the given radius; tetrahedra of
    size h (h_front around the fronts; every size times size_factor). Tags:
    bottom, top, side. memory_limit: as create_box's."""
    c = np.asarray(center, dtype=float).reshape(3)
    a = np.asarray(axis, dtype=float).reshape(3)
    if not (np.all(np.isfinite(c)) and np.linalg.norm(a) > 0 and radius > 0 and length > 0):
        raise MeshError(f"a cylinder needs a finite centre, a non-zero axis, radius > 0 and length > 0; got "
                        f"centre {c.tolist()}, axis {a.tolist()}, radius {radius!r}, length {length!r}")
    if not (0.0 < h <= max(2 * radius, length)):
        raise MeshError(f"mesh size h = {h} must be positive and at most the cylinder's size")
    a = a / np.linalg.norm(a)
    gmsh = _gmsh()
    gmsh.model.add("cylinder")
    d = a * length
    gmsh.model.occ.addCylinder(*c, *d, radius)
    gmsh.model.occ.synchronize()
    groups: dict[str, list[int]] = {"bottom": [], "top": [], "side": []}
    eps = 1e-7 * max(radius, length)
    for _, s in gmsh.model.getEntities(2):
        m = np.array(gmsh.model.occ.getCenterOfMass(2, s))
        t = float(np.dot(m - c, a))
        groups["bottom" if abs(t) < eps else "top" if abs(t - length) < eps else "side"].append(s)
    return _finish(gmsh, groups, h, fronts, size_factor,
                   functools.partial(create_cylinder, center, axis, radius, length, h, fronts=fronts), memory_limit,
                   "the cylinder")


@gmsh_on_rank0
def read_msh_3d(path: str | pathlib.Path) -> MeshData:
    """Read a gmsh .msh file of first-order tetrahedra, its named physical
    surfaces as boundary tags."""
    path = pathlib.Path(path)
    if not path.is_file():
        raise MeshError(f"mesh file {path} does not exist")
    gmsh = _gmsh()
    try:
        gmsh.open(str(path))
    except Exception as e:  # gmsh raises a bare Exception for an unreadable file
        raise MeshError(f"{path}: gmsh cannot read this file ({e}); cracklip reads gmsh .msh files (format 2 "
                        "or 4) with a 3D tetrahedral mesh") from None
    dim = gmsh.model.getDimension()
    if dim != 3:
        gmsh.model.remove()
        raise MeshError(f"{path}: a 3D part needs a 3D (tetrahedral) mesh, this one has dimension {dim}")
    if not gmsh.model.getPhysicalGroups(3):
        gmsh.model.remove()
        raise MeshError(f"{path}: the mesh has no Physical Volume: gmsh then saves only the elements of physical "
                        "groups (or none of the tetrahedra); add `Physical Volume(\"part\") = {...};` (and a "
                        "Physical Surface for every face that carries a load or a support)")
    return to_dolfinx(gmsh, None, dim=3)


def similar_mesh(md: MeshData, factor: float) -> MeshData:
    """The tetrahedral mesh of md's recipe with every size setting times
    `factor` (h and every h_front, the grading's radii kept; relative to md:
    md.size_factor x factor); MeshError for a mesh read from a .msh file."""
    if md.recipe is None:
        raise MeshError(f"a mesh with every element size times {factor:.3g} cannot be made from a 3D .msh file: give "
                        "the part as a geometry (mesh.kind = \"geometry\" with its .geo, STEP or BREP file), or a box "
                        "or cylinder, that cracklip meshes")
    return md.recipe(size_factor=md.size_factor * factor)


def expected_cells(volume: float, h: float) -> float:
    """About how many tetrahedra a volume meshed at size h has."""
    return TETS_PER_VOLUME_H3 * volume / h ** 3


__all__ = ["FrontRefinement", "BoxRefinement", "crack_refinements", "create_box", "create_cylinder", "read_msh_3d",
           "front_sampling", "expected_cells", "crack_size", "default_growth", "FRONT_GROWTH", "similar_mesh"]

