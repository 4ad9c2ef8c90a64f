"""A user's own geometry meshed by cracklip: a gmsh .geo script, or a STEP or
BREP file read through gmsh's OpenCASCADE kernel.

The geometry gets the size field of the built-in shapes
(cracklip.scene.size_field: the element size h, refinements around points
and along segments, tip refinement, growth-path bands, and the levels of an
error estimate), so a user's part is refined like a generated one. The
.geo's own characteristic lengths and size fields are replaced by it.

Boundary tags: the .geo's named physical curves (a physical curve without a
name is tagged by its number). A file without physical curves (a STEP or
BREP file, or a bare .geo) gets one tag per boundary curve, named
``curve N`` with value N (gmsh's curve number). With physical surfaces,
only their triangles make the part (gmsh's rule when it writes a .msh);
without, every surface.

Points that must be mesh nodes (point supports and point forces) are
embedded in the surface or the boundary curve that holds them; a point
outside the part is an error that says where the part's boundary is.

A geometry with volumes is a 3D part (``_create_3d``): tetrahedra of size
h, refined around the crack fronts (and surfaces) given as
mesh_3d.FrontRefinement items; boundary tags are its named physical
surfaces (without any, every boundary surface N is tag ``surface N``), the
part its physical volumes (without any, every volume). Point conditions in
3D take the nearest mesh node (no embedding).
"""
from __future__ import annotations

import contextlib
import functools
import logging
import math
import pathlib
import typing

import numpy as np

from ..errors import MeshError
from .mesh import MeshData, _gmsh, _mesh_2d, _restart_gmsh, gmsh_on_rank0, to_dolfinx


logger = logging.getLogger(__name__)


#: File endings meshed here (gmsh reads STEP and BREP with OpenCASCADE).
GEOMETRY_SUFFIXES = (".geo", ".step", ".stp", ".brep", ".brp")


#: Points per boundary curve when the boundary is sampled for inside tests
#: and the part's area (a circular arc sampled so is within 1e-3 of its
#: radius for quarter circles).
CURVE_SAMPLES = 64


def _open(path: pathlib.Path):
    from . import mesh as mesh_module
    geo = path.suffix.lower() == ".geo"
    if geo and mesh_module._PARSER_BROKEN_BY is not None:
        raise MeshError(f"{path}: gmsh's .geo parser cannot read another script in this process after the syntax "
                        f"error in {mesh_module._PARSER_BROKEN_BY} (gmsh 4.8 does not recover from one); fix that "
                        "file and start again (a new python3 / cracklip command)")
    gmsh = _gmsh()
    try:
        gmsh.open(str(path))
    except Exception as e:  # gmsh raises a bare Exception for a bad file
        _restart_gmsh(path if geo else None)
        raise MeshError(f"{path}: gmsh cannot read this geometry ({e}); cracklip meshes gmsh .geo scripts and "
                        "STEP / BREP files (through OpenCASCADE) that describe a planar part in z = 0 or a "
                        "solid") from None
    gmsh.option.setNumber("General.Terminal", 0)
    return gmsh


def _sample_curve(gmsh, curve: int, samples: int = CURVE_SAMPLES) -> np.ndarray:
    """Points (samples + 1, 2) along a curve, its ends included."""
    lo, hi = gmsh.model.getParametrizationBounds(1, curve)
    t = np.linspace(float(lo[0]), float(hi[0]), samples + 1)
    return np.asarray(gmsh.model.getValue(1, curve, t), dtype=float).reshape(-1, 3)[:, :2]


def surface_outline(gmsh, surface: int) -> tuple[np.ndarray, np.ndarray]:
    """The boundary of a surface as segments (a (n, 2), b (n, 2)), each of
    its curves sampled at CURVE_SAMPLES points."""
    a, b = [], []
    for _, c in gmsh.model.getBoundary([(2, surface)], combined=False, oriented=False):
        pts = _sample_curve(gmsh, abs(c))
        a.append(pts[:-1])
        b.append(pts[1:])
    return np.concatenate(a), np.concatenate(b)


def inside(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> bool:
    """Even-odd ray casting of point p against the segments a-b."""
    straddle = (a[:, 1] > p[1]) != (b[:, 1] > p[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[:, 0] + (p[1] - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return bool(np.count_nonzero(straddle & (xc > p[0])) % 2 == 1)


def _distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
    return float(np.linalg.norm(a + t[:, None] * d - p, axis=1).min())


def _area(a: np.ndarray, b: np.ndarray) -> float:
    """|sum of the signed areas| of the segments' loops (shoelace, even-odd
    holes counted negative when the loops run the other way) - used only
    for the node estimate, so the sampled area suffices."""
    return abs(0.5 * float(np.sum(a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1])))


def _part_surfaces(gmsh, path: pathlib.Path) -> list[int]:
    if gmsh.model.getDimension() != 2:
        dim = gmsh.model.getDimension()
        raise MeshError(f"{path}: the geometry has dimension {dim}; give a planar part (surfaces in z = 0) or a "
                        "solid (volumes)")
    xlo, ylo, zlo, xhi, yhi, zhi = gmsh.model.getBoundingBox(-1, -1)
    # (OpenCASCADE pads its boxes by its tolerance, 1e-7)
    if abs(zhi - zlo) > max(1e-6 * max(xhi - xlo, yhi - ylo), 1e-6):
        raise MeshError(f"{path}: the geometry is not flat (z from {zlo:g} to {zhi:g}); cracklip needs a planar "
                        "part in the plane z = 0")
    surfaces = [s for _, s in gmsh.model.getEntities(2)]
    if not surfaces:
        raise MeshError(f"{path}: the geometry has no surface; close the part's boundary with a Curve Loop and "
                        "make it a Plane Surface (holes as further curve loops of the same surface)")
    physical = [s for dim, tag in gmsh.model.getPhysicalGroups(2) for s in gmsh.model.getEntitiesForPhysicalGroup(dim, tag)]
    return sorted(set(physical)) if physical else surfaces


def _boundary_tags(gmsh, surfaces: list[int]) -> None:
    """Without physical curves: one physical group per boundary curve of the
    part, value = the curve's number, name 'curve N'."""
    if gmsh.model.getPhysicalGroups(1):
        return
    curves = sorted({abs(c) for _, c in gmsh.model.getBoundary([(2, s) for s in surfaces], combined=True,
                                                                 oriented=False)})
    for c in curves:
        gmsh.model.addPhysicalGroup(1, [c], c)
        gmsh.model.setPhysicalName(1, c, f"curve {c}")


def _embed(gmsh, path: pathlib.Path, surfaces: list[int], points, outlines, scale: float) -> None:
    """Make every point a mesh node: a geometry point already there, or one
    embedded in the curve or the surface holding it."""
    tol = 1e-9 * scale
    curves = sorted({abs(c) for _, c in gmsh.model.getBoundary([(2, s) for s in surfaces], combined=False,
                                                                 oriented=False)})
    # The part's corners: the ends of its boundary curves (not construction
    # points such as a circle's centre).
    ends = {abs(t) for c in curves for _, t in gmsh.model.getBoundary([(1, c)], combined=False, oriented=False)}
    corners = [np.asarray(gmsh.model.getValue(0, t, []), dtype=float)[:2] for t in ends]
    for p in points:
        p = np.asarray(p, dtype=float)
        if any(np.linalg.norm(q - p) <= tol for q in corners):
            continue
        on = None
        for c in curves:
            q, _ = gmsh.model.getClosestPoint(1, c, [p[0], p[1], 0.0])
            if np.linalg.norm(np.asarray(q)[:2] - p) <= tol:
                on = c
                break
        holder = None if on is not None else next((s for s, (a, b) in zip(surfaces, outlines) if inside(p, a, b)),
                                                  None)
        if on is None and holder is None:
            a = np.concatenate([o[0] for o in outlines])
            b = np.concatenate([o[1] for o in outlines])
            d = b - a
            t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0, 1)
            near = a + t[:, None] * d
            k = int(np.argmin(np.linalg.norm(near - p, axis=1)))
            raise MeshError(f"{path}: the point ({p[0]:.6g}, {p[1]:.6g}) of a point support or force lies outside "
                            f"the part (in a hole or beyond its boundary; the nearest boundary point is "
                            f"({near[k, 0]:.6g}, {near[k, 1]:.6g}), {np.linalg.norm(near[k] - p):.3g} away); put it "
                            "on or inside the part")
        if path.suffix.lower() != ".geo":
            # A STEP or BREP part (OpenCASCADE, no physical groups to keep):
            # split it at the point, which also works on a closed curve (a
            # full circle), where gmsh 4.8 does not honour an embedding.
            occ = gmsh.model.occ
            occ.fragment([(2, s) for s in surfaces], [(0, occ.addPoint(float(p[0]), float(p[1]), 0.0))])
            occ.synchronize()
            surfaces[:] = [s for _, s in gmsh.model.getEntities(2)]
            continue
        tag = gmsh.model.geo.addPoint(float(p[0]), float(p[1]), 0.0)
        gmsh.model.geo.synchronize()
        if on is not None:
            gmsh.model.mesh.embed(0, [tag], 1, on)
        else:
            gmsh.model.mesh.embed(0, [tag], 2, holder)


def _check_nodes(gmsh, path: pathlib.Path, points, scale: float) -> None:
    """Every point a mesh node, or an error saying how to make it one."""
    if not len(points):
        return
    x = np.asarray(gmsh.model.mesh.getNodes()[1], dtype=float).reshape(-1, 3)[:, :2]
    for p in points:
        p = np.asarray(p, dtype=float)
        if np.linalg.norm(x - p, axis=1).min() > 1e-9 * scale:
            raise MeshError(f"{path}: the point ({p[0]:.6g}, {p[1]:.6g}) of a point support or force did not become "
                            "a mesh node (gmsh does not embed a point in a closed curve such as a full circle): in the "
                            ".geo, draw that curve through a Point there (e.g. the circle as arcs meeting at it)")


def _volumes(gmsh) -> list[int]:
    physical = [v for dim, tag in gmsh.model.getPhysicalGroups(3) for v in gmsh.model.getEntitiesForPhysicalGroup(dim, tag)]
    return sorted(set(physical)) if physical else [v for _, v in gmsh.model.getEntities(3)]


def _create_3d(gmsh, path: pathlib.Path, h: float, fronts, memory_limit: float | None = None,
               size_factor: float = 1.0) -> MeshData:
    """Tetrahedra of a 3D part (module doc); gmsh holds the opened file."""
    from .mesh_3d import _size_fields, estimate_size, scaled
    volumes = _volumes(gmsh)
    lo_x, lo_y, lo_z, hi_x, hi_y, hi_z = gmsh.model.getBoundingBox(-1, -1)
    scale = max(hi_x - lo_x, hi_y - lo_y, hi_z - lo_z)
    if h > scale:
        raise MeshError(f"mesh size h = {h:g} is larger than the part ({scale:g} across)")
    if not gmsh.model.getPhysicalGroups(2):
        surfaces = sorted({abs(s) for _, s in gmsh.model.getBoundary([(3, v) for v in volumes], combined=True,
                                                                      oriented=False)})
        for s in surfaces:
            gmsh.model.addPhysicalGroup(2, [s], s)
            gmsh.model.setPhysicalName(2, s, f"surface {s}")
    gmsh.model.mesh.clear()
    est = estimate_size(gmsh, h * size_factor, scaled(fronts, size_factor), memory_limit, f"{path.name}")
    gmsh.model.mesh.clear()
    gmsh.option.setNumber("Mesh.ElementOrder", 1)
    gmsh.option.setNumber("Mesh.RecombineAll", 0)
    gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 0)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay, as the generated shapes
    # The points of the size field in the kernel the part was built with.
    _size_fields(gmsh, h, fronts, kernel="occ" if gmsh.model.occ.getEntities(3) else "geo", size_factor=size_factor)
    gmsh.model.mesh.generate(3)
    md = to_dolfinx(gmsh, h, volumes, dim=3, fronts=scaled(fronts, size_factor), size_factor=size_factor)
    md.source = "geometry"
    md.estimate = est
    md.recipe = functools.partial(create_from_geometry, path, h, fronts=fronts)
    return md


@contextlib.contextmanager
def _gmsh_errors(gmsh, message: str):
    """Meshing in gmsh: on any error its model is removed (the next part
    starts clean); a MeshError passes as it is, gmsh's own errors become a
    MeshError `message (gmsh's words)`."""
    try:
        yield
    except MeshError:
        if gmsh.model.list():
            gmsh.model.remove()
        raise
    except Exception as e:  # gmsh's own errors while meshing
        if gmsh.model.list():
            gmsh.model.remove()
        raise MeshError(f"{message} ({e})") from None


@gmsh_on_rank0
def create_from_geometry(path: str | pathlib.Path, h: float,
                         refine: typing.Sequence[typing.Sequence[float]] = (),
                         embed_points: typing.Sequence[tuple[float, float]] = (),
                         levels: typing.Sequence[typing.Sequence[float]] = (),
                         tips: typing.Sequence[tuple[float, float]] = (), tip_h: float = 0.0,
                         tip_radius: float = 0.0, fronts: typing.Sequence = (),
                         memory_limit: float | None = None, size_factor: float = 1.0) -> MeshData:
    """Triangles of size h (with the refinements and levels of
    cracklip.scene.size_field) of the part a .geo, STEP or BREP file
    describes; embed_points become mesh nodes; each of `tips` inside the
    part (a crack end off the boundary) is refined to tip_h over
    tip_radius. Tags: the physical curves' names (see the module doc).

    A geometry with volumes is meshed in tetrahedra instead, refined by
    `fronts` (mesh_3d.FrontRefinement items, e.g. mesh_3d.crack_refinements
    of the cracks), every size times size_factor (a similar mesh); refine,
    levels, tips and embed_points are 2D settings and must be empty then; a
    3D mesh whose run is estimated to need more than memory_limit bytes is
    refused before meshing (ModelSizeError; None: no limit)."""
    path = pathlib.Path(path)
    if not path.is_file():
        raise MeshError(f"geometry file {path} does not exist")
    if path.suffix.lower() not in GEOMETRY_SUFFIXES:
        raise MeshError(f"{path}: a geometry is a gmsh .geo script or a STEP (.step, .stp) or BREP (.brep) file; "
                        "a gmsh .msh mesh is mesh.kind = 'file'")
    if not (isinstance(h, (int, float)) and math.isfinite(h) and h > 0.0):
        raise MeshError(f"mesh size h = {h!r} must be a positive number")
    gmsh = _open(path)
    if gmsh.model.getDimension() == 3:
        if refine or levels or tips:
            gmsh.model.remove()
            raise MeshError(f"{path} is a 3D part: refine it around its cracks' fronts (fronts; in a scene file "
                            "mesh.tip_h, mesh.crack_h), not with 2D refinement points or tips")
        with _gmsh_errors(gmsh, f"{path}: gmsh could not mesh the 3D geometry"):
            return _create_3d(gmsh, path, h, fronts, memory_limit, size_factor)
    with _gmsh_errors(gmsh, f"{path}: gmsh could not mesh the geometry"):
        surfaces = _part_surfaces(gmsh, path)
        outlines = [surface_outline(gmsh, s) for s in surfaces]
        lo_x, lo_y, _, hi_x, hi_y, _ = gmsh.model.getBoundingBox(-1, -1)
        scale = max(hi_x - lo_x, hi_y - lo_y)
        if h > scale:
            raise MeshError(f"mesh size h = {h:g} is larger than the part ({scale:g} across)")
        _embed(gmsh, path, surfaces, embed_points, outlines, scale)
        _boundary_tags(gmsh, surfaces)
        outlines = [surface_outline(gmsh, s) for s in surfaces]
        given = list(refine)
        if tip_h > 0.0:
            a = np.concatenate([o[0] for o in outlines])
            b = np.concatenate([o[1] for o in outlines])
            for p in tips:
                q = np.asarray(p, dtype=float)
                off = _distance(q, a, b) > 1e-9 * scale
                if off and any(inside(q, *o) for o in outlines):
                    refine = list(refine) + [(float(q[0]), float(q[1]), float(tip_h), float(tip_radius))]
        # The script's own mesh settings give way to cracklip's.
        gmsh.model.mesh.clear()
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        gmsh.option.setNumber("Mesh.RecombineAll", 0)
        gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 0)
        area = sum(_area(a, b) for a, b in outlines)
        _mesh_2d(gmsh, h, refine, levels, area=area)
        _check_nodes(gmsh, path, embed_points, scale)
        md = to_dolfinx(gmsh, h, surfaces)  # (checks the mesh)
    md.refinements = [(float(r[0]), float(r[1]), float(r[2])) for r in refine]
    md.refine = [tuple(float(v) for v in r) for r in refine]
    md.levels = [tuple(v) for v in levels]
    md.source = "geometry"
    md.recipe = functools.partial(create_from_geometry, path, h, refine=given, embed_points=embed_points, tips=tips,
                                  tip_h=tip_h, tip_radius=tip_radius)
    return md
