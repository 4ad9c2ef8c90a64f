"""[mesh]: the part and its mesh: the keys (KEYS) and the mesh they build
(``build_mesh``): generated plates and half annuli (2D), boxes and cylinders
(3D, refined along the crack fronts), a user's geometry (.geo, STEP, BREP)
or .msh file; the queries of a built mesh the other sections use (boundary
tags, the node nearest to a point, the mean edge)."""
from __future__ import annotations

import pathlib

import numpy as np

from ...errors import BoundaryConditionError, MeshError
from ...scene.cell_size import mean_cell_size
from ...scene.mesh import MeshData, create_half_annulus, create_plate_with_holes, create_rectangle, read_msh
from ...scene.processes import mark_collective, total
from .schema import (REQUIRED, UNSET, Key, p_box, p_choice, p_float, p_holes, p_point, p_point3, p_point_any,
                     p_segment, p_solid_box, p_str, p_vector3)


MESH_KINDS = ("rectangle", "plate_with_hole", "plate_with_holes", "half_annulus", "box", "cylinder", "geometry",
              "file")


GENERATED = ("rectangle", "plate_with_hole", "plate_with_holes", "half_annulus")


#: Generated 3D parts (tetrahedra).
SOLIDS = ("box", "cylinder")


#: Kinds that cracklip meshes with gmsh (mesh.h applies).
MESHED = GENERATED + SOLIDS + ("geometry",)


#: Kinds whose mesh can be 3D (crack surfaces, front refinement).
KINDS_3D = SOLIDS + ("geometry", "file")


PLATES = ("rectangle", "plate_with_hole", "plate_with_holes")


KEYS: list[Key] = [
    Key("mesh.kind", "string", "rectangle",
        "`rectangle`, `plate_with_hole`, `plate_with_holes` (a drilled plate), `half_annulus` (r between hole_radius and outer_radius, "
        "y >= 0, centre at the origin), 3D: `box`, `cylinder` (tetrahedra, refined along the crack fronts), "
        "`geometry` (your part as a gmsh .geo, STEP or BREP file, meshed by cracklip "
        "with h, tip_h and refine; a solid is meshed in tetrahedra) or `file` (a gmsh .msh mesh, refined locally "
        "by cracklip for tip_h and refine; 3D: tetrahedra, used as they are)",
        p_choice(*MESH_KINDS)),
    Key("mesh.h", "float", REQUIRED, "element size", p_float(positive=True), MESHED),
    Key("mesh.box", "[x0, y0, z0, x1, y1, z1]", REQUIRED,
        "the box (3D); tags `xmin`, `xmax`, `ymin`, `ymax`, `zmin`, `zmax`", p_solid_box, ("box",)),
    Key("mesh.center", "[x, y, z]", REQUIRED, "centre of the cylinder's bottom face (tag `bottom`)", p_point3,
        ("cylinder",)),
    Key("mesh.axis", "[x, y, z]", [0.0, 0.0, 1.0], "direction from the cylinder's bottom face to its top face "
        "(tag `top`; the curved face is `side`)", p_vector3, ("cylinder",)),
    Key("mesh.radius", "float", REQUIRED, "radius of the cylinder", p_float(positive=True), ("cylinder",)),
    Key("mesh.length", "float", REQUIRED, "length of the cylinder along its axis", p_float(positive=True),
        ("cylinder",)),
    Key("mesh.domain", "[x0, y0, x1, y1]", [-1.0, -1.0, 1.0, 1.0],
        "the rectangle; tags `left`, `right`, `bottom`, `top`", p_box, PLATES),
    Key("mesh.hole_center", "[x, y]", [0.0, 0.0], "centre of the hole (tag `hole`)", p_point,
        ("plate_with_hole",)),
    Key("mesh.hole_radius", "float", REQUIRED, "radius of the hole (tag `hole`)", p_float(positive=True),
        ("plate_with_hole", "half_annulus")),
    Key("mesh.holes", "[[x, y, r], ...]", REQUIRED, "the holes' centres and radii (tag `hole`: every hole's edge)",
        p_holes, ("plate_with_holes",)),
    Key("mesh.outer_radius", "float", REQUIRED,
        "outer radius of the half annulus (tag `outer`; `symmetry` on y = 0)", p_float(positive=True),
        ("half_annulus",)),
    Key("mesh.path", "string", REQUIRED,
        "the file, relative to the scene file: a gmsh .geo script, STEP or BREP file (kind geometry; named "
        "physical curves are the boundary tags, without any every boundary curve N is tag `curve N`; a solid: "
        "named physical surfaces, else `surface N`) or a gmsh "
        ".msh mesh (kind file; named physical curves as boundary tags, a Physical Surface for the triangles; 3D: "
        "named physical surfaces as boundary tags, a Physical Volume for the tetrahedra)",
        p_str, ("file", "geometry")),
    Key("mesh.tip_h", "float", 0.0,
        "element size at crack tips inside the part (3D: along the crack fronts); 0: no tip refinement (kind "
        "file: the file's mesh is refined around the tips until its cells are that small; not for 3D files)",
        p_float(0.0)),
    Key("mesh.tip_radius", "float", 0.0,
        "distance over which the size grows from tip_h to h beyond a plateau of 4 tip_h around the tip (3D: "
        "the front); never faster than 0.25 per unit length (a shorter radius is lengthened); 0: that fastest "
        "growth (kind file: up to the file's own element size); 3D, 0: the size grows by 1.4 tip_h per crack "
        "size (twice the crack's area over its perimeter, a penny's radius) from the front, so that every size "
        "near the crack scales with tip_h and K converges as tip_h is refined",
        p_float(0.0)),
    Key("mesh.crack_h", "float", 0.0,
        "3D: element size over the crack surfaces (within 4 crack_h of them), growing back to h as from the "
        "front; 0: no refinement beyond the front's", p_float(0.0), SOLIDS + ("geometry",)),
    Key("mesh.refine[].point", "[x, y] or [x, y, z]", UNSET, "centre of a local refinement (one of point, "
        "segment)", p_point_any),
    Key("mesh.refine[].segment", "[[x0, y0], [x1, y1]]", UNSET, "a segment refined along its length (a band "
        "along a crack's expected path; one of point, segment; 3D: [[x0, y0, z0], [x1, y1, z1]])", p_segment),
    Key("mesh.refine[].box", "[x0, y0, z0, x1, y1, z1]", UNSET, "3D: a box refined throughout (the region a "
        "crack grows into; one of point, segment, box)", p_solid_box),
    Key("mesh.refine[].h", "float", REQUIRED, "element size at the point (and within 4 times that size of it; "
        "a box: inside it)",
        p_float(positive=True)),
    Key("mesh.refine[].radius", "float", 0.0, "distance over which the size grows back to h beyond that "
        "plateau, never faster than 0.25 per unit length; 0: that fastest growth", p_float(0.0)),
]


def _inside(m: dict, p: np.ndarray) -> bool:
    """Whether p lies strictly inside a generated mesh's domain."""
    kind = m["kind"]
    if kind in PLATES:
        x0, y0, x1, y1 = m["domain"]
        inside = x0 < p[0] < x1 and y0 < p[1] < y1
        for cx, cy, r in _holes(m):
            inside = inside and np.hypot(p[0] - cx, p[1] - cy) > r
        return bool(inside)
    r = float(np.hypot(*p))
    return bool(m["hole_radius"] < r < m["outer_radius"] and p[1] > 0.0)


def _holes(m: dict) -> list[tuple[float, float, float]]:
    """The holes (x, y, r) of a generated plate."""
    if m["kind"] == "plate_with_hole":
        return [(m["hole_center"][0], m["hole_center"][1], m["hole_radius"])]
    if m["kind"] == "plate_with_holes":
        return [tuple(h) for h in m["holes"]]
    return []


def build_mesh(m: dict, cracks: list, base_dir: pathlib.Path, points=(), dim: int | None = 2,
               memory_limit: float | None = None) -> MeshData:
    """The mesh of the [mesh] settings; `points` (point supports and forces)
    inside or on a generated rectangle or plate become mesh nodes. dim: the
    scene's dimension if known (3: mesh_3d; None: a geometry
    or .msh file without cracks, whose own dimension decides).
    memory_limit: a solid whose run is estimated to need more bytes is
    refused before meshing (ModelSizeError; None: no limit)."""
    kind = m["kind"]
    if dim is None and kind == "file":
        dim = mesh_file_dimension(scene_path(m, base_dir))
    if dim == 3:
        return mesh_3d(m, cracks, base_dir, memory_limit)
    refine = [(r["point"][0], r["point"][1], r["h"], r["radius"]) if "point" in r else
              (r["segment"][0][0], r["segment"][0][1], r["h"], r["radius"], r["segment"][1][0], r["segment"][1][1])
              for r in m["refine"]]
    ends = [tuple(float(v) for v in p) for c in cracks for p in c.points[[0, -1]]]
    if kind in ("file", "geometry"):
        f = scene_path(m, base_dir)
        if kind == "geometry":
            from ...scene.geometry_file import create_from_geometry
            return create_from_geometry(f, m["h"], refine=refine, embed_points=points,
                                        tips=ends if m["tip_h"] > 0.0 else (), tip_h=m["tip_h"],
                                        tip_radius=m["tip_radius"])
        if f.suffix.lower() in (".geo", ".step", ".stp", ".brep", ".brp"):
            raise MeshError(f"mesh.path {m['path']!r} is a geometry, not a mesh: use mesh.kind = \"geometry\" with "
                            "mesh.h (cracklip meshes it, with tip_h and refine)")
        from ...scene.refine import inside_mesh, refine_file_mesh
        md = read_msh(f)
        if m["tip_h"] > 0.0:
            refine += [(p[0], p[1], m["tip_h"], m["tip_radius"]) for p, inside in zip(ends, inside_mesh(md, ends))
                       if inside]
        return refine_file_mesh(md, refine, (), f"mesh file {f}")
    h = m["h"]
    if m["tip_h"] > 0.0:
        radius = m["tip_radius"]
        for c in cracks:
            for p in c.points[[0, -1]]:
                if _inside(m, p):
                    refine.append((float(p[0]), float(p[1]), m["tip_h"], radius))
    if kind in PLATES:
        x0, y0, x1, y1 = m["domain"]
        tol = 1e-12 * max(x1 - x0, y1 - y0)
        embed = [tuple(p) for p in points if x0 - tol <= p[0] <= x1 + tol and y0 - tol <= p[1] <= y1 + tol]
        holes = _holes(m)
        embed = [p for p in embed if all(np.hypot(p[0] - cx, p[1] - cy) > r * (1 + 1e-9) for cx, cy, r in holes)]
        if holes:
            return create_plate_with_holes(*m["domain"], h, holes, refine=refine, embed_points=embed)
        return create_rectangle(*m["domain"], h, refine=refine, embed_points=embed)
    if not m["hole_radius"] < m["outer_radius"]:
        raise MeshError(f"mesh.hole_radius ({m['hole_radius']}) must be smaller than mesh.outer_radius "
                        f"({m['outer_radius']})")
    return create_half_annulus(h, m["hole_radius"], m["outer_radius"], refine=refine)


def check_tag(mesh: MeshData, tag, where: str) -> None:
    """A boundary tag a scene key names: known and with facets. Collective
    under mpirun (every process holds the tag names and sums the facets):
    the error is raised alike on all, printed once."""
    try:
        facets = mesh.facets(tag)
    except MeshError as e:
        raise mark_collective(MeshError(f"{where}: {e}")) from None
    if total(facets.size, mesh.mesh.comm) == 0:
        raise mark_collective(MeshError(f"{where}: boundary tag {tag!r} has no facets"))


def _mean_edge(mesh: MeshData) -> float:
    msh = mesh.mesh
    return mean_cell_size(msh.geometry.x, msh.geometry.dofmap.array.reshape(-1, mesh.gdim + 1))


def nearest_node(mesh: MeshData, point, where: str) -> tuple[float, ...]:
    """The mesh node nearest to a point given in a scene file; an error
    naming the key if it is more than a mean edge length away."""
    x = mesh.mesh.geometry.x[:, :mesh.gdim]
    p = np.asarray(point)
    d = np.linalg.norm(x - p, axis=1)
    node = int(np.argmin(d))
    edge = _mean_edge(mesh)
    comm = mesh.mesh.comm
    dist, nearest = float(d[node]), x[node]
    if comm.size > 1:  # the nearest node over all processes (ties: the lowest rank), the mean of their mean edges
        dist, nearest = min(comm.allgather((dist, x[node].tolist())), key=lambda v: v[0])
        nearest = np.asarray(nearest)
        edge = comm.allreduce(edge) / comm.size
    if dist > edge:  # (decided on the same numbers on every process: raised alike, printed once)
        raise mark_collective(BoundaryConditionError(
            f"{where} {p.tolist()}: the nearest mesh node {nearest.tolist()} is {dist:.3g} away, more than "
            f"the mean edge length {edge:.3g}; put the point on the part"))
    return tuple(float(v) for v in nearest)



def _refine_items(m: dict, h: float) -> list:
    """mesh.refine items of a 3D scene as front refinements (a point, or a
    segment sampled every h_near / 2)."""
    from ...scene.mesh_3d import BoxRefinement, FrontRefinement
    out = []
    for r in m["refine"]:
        if "box" in r:
            out.append(BoxRefinement(tuple(r["box"][:3]), tuple(r["box"][3:]), min(r["h"], h), r["radius"]))
            continue
        if "point" in r:
            pts = np.asarray([r["point"]], dtype=float)
        else:
            a, b = (np.asarray(p, dtype=float) for p in r["segment"])
            k = max(1, int(np.ceil(np.linalg.norm(b - a) / (0.5 * r["h"]))))
            pts = a + np.linspace(0.0, 1.0, k + 1)[:, None] * (b - a)
        out.append(FrontRefinement(pts, min(r["h"], h), r["radius"], "points" if "point" in r else "curve"))
    return out


def mesh_3d(m: dict, cracks: list, base_dir: pathlib.Path, memory_limit: float | None = None) -> MeshData:
    """The tetrahedral mesh of [mesh] settings: box, cylinder, a solid
    geometry file (all refined to tip_h along the cracks' fronts, crack_h
    over their surfaces, and the refine items; estimated first, refused
    above memory_limit bytes), or a .msh file as it is."""
    from ...scene import mesh_3d as m3
    kind = m["kind"]
    if kind == "file":
        return m3.read_msh_3d(scene_path(m, base_dir))
    h = m["h"]
    fronts = []
    if m["tip_h"] > 0.0 and cracks:
        # tip_radius as in 2D: the distance over which the size grows back to
        # h; 0: the default grading, every size near the crack in proportion
        # to tip_h (mesh_3d.default_growth); no refinement over the surfaces
        # unless crack_h asks (h_surface = h).
        growth = max((h - m["tip_h"]) / m["tip_radius"], 1e-12) if m["tip_radius"] > 0.0 else None
        fronts = m3.crack_refinements(cracks, m["tip_h"], h, growth=growth,
                                      h_surface=m["crack_h"] if m.get("crack_h", 0.0) > 0.0 else h)
    elif m.get("crack_h", 0.0) > 0.0:
        fronts = [m3.FrontRefinement(c.surface_points(0.5 * m["crack_h"]), m["crack_h"], m["tip_radius"], "surface")
                  for c in cracks]
    fronts += _refine_items(m, h)
    if kind == "box":
        return m3.create_box(*m["box"], h, fronts=fronts, memory_limit=memory_limit)
    if kind == "cylinder":
        return m3.create_cylinder(m["center"], m["axis"], m["radius"], m["length"], h, fronts=fronts,
                                  memory_limit=memory_limit)
    from ...scene.geometry_file import create_from_geometry
    return create_from_geometry(scene_path(m, base_dir), h, fronts=fronts, memory_limit=memory_limit)


def scene_path(m: dict, base_dir: pathlib.Path) -> pathlib.Path:
    """The file mesh.path names (relative: to the scene file's folder);
    MeshError naming the key and where it was looked for if it is not a
    file."""
    f = pathlib.Path(m["path"])
    f = f if f.is_absolute() else pathlib.Path(base_dir) / f
    if not f.is_file():
        raise MeshError(f"mesh.path {m['path']!r}: no such file {f.resolve()}"
                        + ("" if pathlib.Path(m["path"]).is_absolute() else
                           f" (a relative path is read from the scene file's folder, {pathlib.Path(base_dir).resolve()})"))
    return f


def mesh_file_dimension(path: pathlib.Path) -> int:
    """The dimension of the mesh in a .msh file (2: triangles, 3: tetrahedra)."""
    from ...scene.mesh import _gmsh, _msh_header
    if not path.is_file():
        raise MeshError(f"mesh file {path} does not exist")
    if not _msh_header(path):
        return 2  # read_msh names the problem
    gmsh = _gmsh()
    try:
        gmsh.open(str(path))
    except Exception as e:  # gmsh raises a bare Exception for an unreadable file
        raise MeshError(f"{path}: gmsh cannot read this file ({e})") from None
    try:
        return 3 if gmsh.model.getDimension() == 3 else 2
    finally:
        gmsh.model.remove()


