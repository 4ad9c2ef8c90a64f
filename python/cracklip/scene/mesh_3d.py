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
"""
from __future__ import annotations

import dataclasses
import pathlib
import typing

import numpy as np

from ..errors import MeshError
from .mesh import MeshData, _gmsh, to_dolfinx
from .size_field import refinement_size

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
    """
    points: np.ndarray
    h_front: float
    radius: float

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


def crack_refinements(cracks, h_front: float, h: float, growth: float = GROWTH,
                      h_surface: float | None = None) -> list[FrontRefinement]:
    """Refinements for 3D cracks: h_front along each front, h_surface
    (default SURFACE_SIZE h_front) over each crack's surface, sizes growing
    by `growth` per unit distance up to h."""
    if not (h_front > 0.0 and h > 0.0 and growth > 0.0):
        raise MeshError(f"crack refinements need h_front, h and growth > 0, got {h_front!r}, {h!r}, {growth!r}")
    hs = SURFACE_SIZE * h_front if h_surface is None else float(h_surface)
    out = []
    for crack in cracks:
        out.append(FrontRefinement(crack.front_points(front_sampling(h_front)), h_front,
                                   max(h - h_front, 0.0) / growth))
        if hs < h:
            out.append(FrontRefinement(crack.surface_points(0.5 * hs), hs, (h - hs) / growth))
    return out


def front_sampling(h_front: float) -> float:
    """The largest spacing of the points of a front refinement: h_front / 2
    (the Distance field then errs by at most h_front / 8 near the front)."""
    return 0.5 * h_front


def _size_fields(gmsh, h: float, fronts: typing.Sequence[FrontRefinement], kernel: str = "occ") -> None:
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


def _finish(gmsh, groups: dict[str, list[int]], h: float, fronts) -> MeshData:
    """Name the face groups as physical surfaces 1, 2, ... (in order), the
    volumes as physical volume 1, mesh in 3D with the front size fields,
    convert."""
    gmsh.model.addPhysicalGroup(3, [v for _, v in gmsh.model.getEntities(3)], 1)
    for tag, (name, surfaces) in enumerate(groups.items(), start=1):
        gmsh.model.addPhysicalGroup(2, surfaces, tag)
        gmsh.model.setPhysicalName(2, tag, name)
    _size_fields(gmsh, h, fronts)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay: robust, deterministic in serial
    gmsh.model.mesh.generate(3)
    return to_dolfinx(gmsh, h, dim=3, fronts=fronts)


def create_box(x0: float, y0: float, z0: float, x1: float, y1: float, z1: float, h: float,
               fronts: typing.Sequence[FrontRefinement] = ()) -> MeshData:
    """The box [x0, x1] x [y0, y1] x [z0, z1] in tetrahedra of size h (h_front
    around the fronts). Tags: xmin, xmax, ymin, ymax, zmin, zmax."""
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
    return _finish(gmsh, groups, h, fronts)


def create_cylinder(center: typing.Sequence[float], axis: typing.Sequence[float], radius: float, length: float,
                    h: float, fronts: typing.Sequence[FrontRefinement] = ()) -> MeshData:
    """A solid cylinder: its bottom face centred at `center`, extruded by
    `length` along the unit vector `axis`, of the given radius; tetrahedra of
    size h (h_front around the fronts). Tags: bottom, top, side."""
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
    return _finish(gmsh, groups, h, fronts)


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


def expected_cells(volume: float, h: float) -> float:
    """About how many tetrahedra a volume meshed at size h has."""
    return TETS_PER_VOLUME_H3 * volume / h ** 3


__all__ = ["FrontRefinement", "BoxRefinement", "crack_refinements", "create_box", "create_cylinder", "read_msh_3d",
           "front_sampling", "expected_cells"]

