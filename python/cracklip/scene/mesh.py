"""Meshes of parts: ``MeshData`` (a DOLFINx mesh with named boundary tags)
and its checks (``check_mesh``) for triangles and tetrahedra alike, and the
triangle meshes of planar parts from gmsh: the paper's domains at a given
size, or a .msh file (mesh_3d.py meshes solids: the geometry differs).

Every mesh comes with named boundary tags (``MeshData.tags``): the square has
``left``, ``right``, ``bottom``, ``top``; the half annulus of the hole problem
has ``hole``, ``outer``, ``symmetry``.
"""
from __future__ import annotations

import dataclasses
import functools
import logging
import math
import numbers
import pathlib
import typing

import numpy as np

from ..errors import BoundaryConditionError, CracklipError, MeshError, checked_keywords
from .processes import agree, first_error, total
from .size_field import (MAX_GROWTH, PLATEAU, refinement_expression, refinement_size,  # noqa: F401
                         size_expression, smallest_size)

if typing.TYPE_CHECKING:
    import dolfinx.mesh


logger = logging.getLogger(__name__)


@dataclasses.dataclass
class MeshData:
    """A DOLFINx mesh with its boundary facet tags: triangles in 2D
    (this module), tetrahedra in 3D (mesh_3d).

    Attributes:
        mesh: the DOLFINx mesh (triangles with geometric dimension 2, or
            tetrahedra; under mpirun distributed, with vertex patches).
        facet_tags: DOLFINx MeshTags on boundary facets.
        tags: boundary name -> tag value.
        h: nominal mesh size used to generate it (None for a file).
        refinements: the (x, y, size) of the local refinements asked for
            (checked against the mesh made: cracklip.model.checks).
        cache_standard_block: keep the assembled standard stiffness block
            (the uncracked P1 stiffness) for the next solves on this mesh
            (crack growth: the cracks change, the mesh does not).
        refine: the refine items of its size field (x, y, h_near, radius[,
            x1, y1]; cracklip.scene.size_field).
        levels: the refinement levels it was made with (x, y, x1, y1, D, L).
        size_factor: every size setting of its size field (h, h_front)
            times this (3D): 1 as asked, others for the meshes of an error
            estimate and of an accuracy target (cracklip.analysis.accuracy).
        recipe: makes the same mesh again with more refinement:
            recipe(levels=...) (2D), recipe(size_factor=...) (3D) (a gmsh
            mesh of a known geometry); None for a mesh read from a file
            (cracklip.scene.refine refines a 2D one instead).
        source: where it comes from: "generated", "geometry" (a user's .geo,
            STEP or BREP meshed by cracklip) or "file" (a .msh).
        front_refinements: in 3D, the refinements around crack fronts asked
            for (mesh_3d.FrontRefinement).
        estimate: in 3D, the size estimated before meshing (a
            mesh_estimate.MeshEstimate; None for a mesh read from a file).
    """
    mesh: dolfinx.mesh.Mesh
    facet_tags: typing.Any
    tags: dict[str, int]
    h: float | None = None
    refinements: list[tuple[float, float, float]] = dataclasses.field(default_factory=list)
    cache_standard_block: bool = False
    standard_blocks: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)
    refine: list = dataclasses.field(default_factory=list)
    levels: list = dataclasses.field(default_factory=list)
    size_factor: float = 1.0
    recipe: typing.Optional[typing.Callable[..., "MeshData"]] = dataclasses.field(default=None, repr=False,
                                                                                compare=False)
    source: str = "generated"
    front_refinements: list = dataclasses.field(default_factory=list)
    estimate: typing.Any = None

    @property
    def gdim(self) -> int:
        """2 for a triangle mesh, 3 for a tetrahedral one."""
        return self.mesh.topology.dim

    def facets(self, where: str | int) -> np.ndarray:
        """Facet indices of a named (or numbered) boundary tag."""
        tag = self.tag_value(where)
        return self.facet_tags.indices[self.facet_tags.values == tag]

    def owned_facets(self, where: str | int) -> np.ndarray:
        """The facets of a boundary tag this process counts: all in serial,
        under mpirun those of its owned cells (each facet on one process)."""
        facets = self.facets(where)
        msh = self.mesh
        if msh.comm.size == 1:
            return facets
        tdim = msh.topology.dim
        msh.topology.create_connectivity(tdim - 1, tdim)
        f2c = msh.topology.connectivity(tdim - 1, tdim)
        cell = f2c.array[f2c.offsets[facets]]  # (a boundary facet has one cell)
        return facets[cell < msh.topology.index_map(tdim).size_local]

    def num_facets(self, where: str | int) -> int:
        """How many facets a boundary tag has (collective under mpirun)."""
        return total(self.owned_facets(where).size, self.mesh.comm)

    def facet_vertices(self, where: str | int) -> np.ndarray:
        """Vertex coordinates (n, d, d) of a boundary tag's facets (segments
        in 2D, triangles in 3D); a tag without facets is an error."""
        import dolfinx.cpp.mesh
        facets = self.facets(where)
        if total(facets.size, self.mesh.comm) == 0:  # (under mpirun a process may hold none of them)
            raise BoundaryConditionError(f"boundary {where!r} has no facets")
        msh = self.mesh
        tdim = msh.topology.dim
        msh.topology.create_connectivity(tdim - 1, tdim)
        return msh.geometry.x[:, :tdim][dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)]

    def nearest_node(self, point) -> tuple[float, ...]:
        """Coordinates of the mesh node nearest to a point (for point conditions)."""
        x = self.mesh.geometry.x[:, :self.gdim]
        i = int(np.argmin(np.linalg.norm(x - np.asarray(point, dtype=float), axis=1)))
        return tuple(float(v) for v in x[i])

    def tag_value(self, where: str | int) -> int:
        if isinstance(where, str):
            if where not in self.tags:
                raise MeshError(f"unknown boundary tag {where!r}; this mesh has "
                                f"{sorted(self.tags)}")
            return self.tags[where]
        values = set(np.unique(self.facet_tags.values).tolist())
        if self.mesh.comm.size > 1:  # the tags present on any process
            values = set().union(*self.mesh.comm.allgather(values))
        if int(where) not in values:
            raise MeshError(f"no boundary facets carry tag {where}; tags present: {sorted(values)}")
        return int(where)


_GMSH_READY = False


def _gmsh():
    global _GMSH_READY
    import gmsh
    if not _GMSH_READY:
        gmsh.initialize(readConfigFiles=False)
        _GMSH_READY = True
    gmsh.option.setNumber("General.Terminal", 0)
    return gmsh


#: The file whose syntax error broke gmsh's .geo parser in this process, if
#: one did: gmsh 4.8's parser does not recover from a syntax error (not even
#: across finalize / initialize: every later .geo parses to nothing), so a
#: later .geo is refused with the cause instead of meshing an empty model.
_PARSER_BROKEN_BY: str | None = None


def _restart_gmsh(path=None) -> None:
    """A failed parse leaves gmsh unable to mesh the next model: restart it
    (the .geo parser itself stays broken: _PARSER_BROKEN_BY)."""
    global _GMSH_READY, _PARSER_BROKEN_BY
    import gmsh
    gmsh.finalize()
    _GMSH_READY = False
    if path is not None:
        _PARSER_BROKEN_BY = str(path)


def _msh_header(path: pathlib.Path) -> bool:
    """Whether the file starts as a gmsh .msh file does ($MeshFormat). gmsh
    parses any other file as a .geo script, and a syntax error there breaks
    its parser for the rest of the process."""
    try:
        with open(path, "rb") as f:
            head = f.read(4096).lstrip()
    except OSError:
        return False
    return head.startswith(b"$MeshFormat")


def to_dolfinx(gmsh, h: float | None, entities: typing.Sequence[int] | None = None, dim: int = 2,
               fronts=(), size_factor: float = 1.0) -> MeshData:
    """The current gmsh model's mesh as MeshData: its cells of dimension dim
    (triangles of the given surfaces, tetrahedra of the given volumes, all
    if None), tags from its physical groups of dimension dim - 1 (curves,
    surfaces); removes the model. fronts: the front refinements it was made
    with (3D; MeshData.front_refinements), size_factor: MeshData.size_factor."""
    names = {}
    for gd, tag in gmsh.model.getPhysicalGroups(dim - 1):
        names[gmsh.model.getPhysicalName(gd, tag) or str(tag)] = tag
    # DOLFINx is imported here, not at the top: the command line meshes
    # while another thread loads it (cracklip.prefetch).
    from mpi4py import MPI
    from .mesh_import import model_to_mesh
    _GMSH_ON_RANK0["handed_over"] = True
    msh, facet_tags, _ = model_to_mesh(gmsh.model, MPI.COMM_WORLD, entities, dim=dim)
    gmsh.model.remove()
    check_mesh(msh)
    return MeshData(msh, facet_tags, names, h, front_refinements=list(fronts), size_factor=float(size_factor))


#: gmsh_on_rank0's state on rank 0: inside a mesh entry (nested entries run
#: plainly), and whether to_dolfinx has handed the mesh to DOLFINx yet.
_GMSH_ON_RANK0 = {"inside": False, "handed_over": False}
#: MeshData fields sent from rank 0 to the others (the mesh and tags are
#: DOLFINx's; the recipe, when it pickles, is added).
_SENT_FIELDS = ("tags", "h", "refinements", "cache_standard_block", "refine", "levels", "source",
                "front_refinements", "estimate", "size_factor")


def gmsh_on_rank0(make: typing.Callable[..., "MeshData"]) -> typing.Callable[..., "MeshData"]:
    """A mesh entry (gmsh meshes, then to_dolfinx) that under mpirun runs
    gmsh on rank 0 only: the other processes take their part of the mesh
    from DOLFINx (mesh_import), then rank 0's MeshData fields. Rank 0's
    error before the hand-over is raised on all (agree, matching the
    others' first collective in model_to_mesh), after it by a broadcast.
    In serial: make itself."""
    @functools.wraps(make)
    def entry(*args, **kwargs):
        from .processes import agree, is_collective, mark_collective, world
        comm = world() if _several_processes() else None
        if comm is None or _GMSH_ON_RANK0["inside"]:
            return make(*args, **kwargs)
        _GMSH_ON_RANK0.update(inside=True, handed_over=False)
        try:
            if comm.rank == 0:
                try:
                    md = make(*args, **kwargs)
                except (CracklipError, OSError) as e:
                    if is_collective(e):  # (check_mesh: the others raised it too)
                        raise
                    if not _GMSH_ON_RANK0["handed_over"]:
                        agree(e, comm)  # the others wait in model_to_mesh's first agree
                    comm.bcast(("error", type(e), str(e)), root=0)
                    raise mark_collective(e)
                fields = {f: getattr(md, f) for f in _SENT_FIELDS}
                # The recipe too when it pickles (a partial of a mesh entry: it
                # meshes on rank 0 again); else no process has one.
                md.recipe = fields["recipe"] = md.recipe if _picklable(md.recipe) else None
                comm.bcast(("ok", fields), root=0)
                return md
            from .mesh_import import model_to_mesh
            msh, facet_tags, names = model_to_mesh(None, comm, None, dim=0)
            check_mesh(msh)
            outcome = comm.bcast(None, root=0)
            if outcome[0] == "error":
                raise mark_collective(outcome[1](outcome[2]))
            md = MeshData(msh, facet_tags, names)
            for f, v in outcome[1].items():
                setattr(md, f, v)
            return md
        finally:
            _GMSH_ON_RANK0.update(inside=False, handed_over=False)
    return entry


def _picklable(value) -> bool:
    import pickle
    try:
        pickle.dumps(value)
    except Exception:  # (a closure, a lambda: whatever pickle refuses)
        return False
    return True


def _several_processes() -> bool:
    import sys
    mpi = sys.modules.get("mpi4py.MPI")
    return mpi is not None and mpi.Is_initialized() and mpi.COMM_WORLD.size > 1


#: Per cell kind: the dimension, what a cell's measure is called and what makes it non-zero.
_CELLS = {"triangle": (2, "area", "every triangle must have three distinct, non-collinear vertices"),
          "tetrahedron": (3, "volume", "every tetrahedron must have four non-coplanar vertices")}


def check_mesh(msh: dolfinx.mesh.Mesh) -> None:
    """Raise MeshError unless msh is a first-order mesh of triangles
    (a planar part, z = 0) or of tetrahedra (a solid), with finite, unique
    nodes and cells of non-zero area (volume)."""
    name = msh.topology.cell_type.name
    if name not in _CELLS:
        raise MeshError(f"cracklip needs triangles (a planar part) or tetrahedra (a solid), the mesh has {name} "
                        "cells; mesh with gmsh without recombination")
    d, measure, fix = _CELLS[name]
    # Under mpirun each process checks its own cells and nodes (owned and
    # ghost); all raise the first process's finding (local indices).
    agree(first_error([lambda: _check_cells(msh, d, measure, fix)]), msh.comm)


def _check_cells(msh: dolfinx.mesh.Mesh, d: int, measure: str, fix: str) -> None:
    """check_mesh on this process's nodes and cells."""
    if d == 2 and msh.geometry.dim != 2 and not np.allclose(msh.geometry.x[:, 2], 0.0):
        raise MeshError("cracklip needs a planar mesh (z = 0)")
    if msh.geometry.cmap.degree != 1:
        raise MeshError(f"cracklip needs straight (first-order) {msh.topology.cell_type.name}s")
    x = msh.geometry.x[:, :d]
    cells = msh.geometry.dofmap.array.reshape(-1, d + 1)
    if not np.all(np.isfinite(x)):
        i = int(np.flatnonzero(~np.all(np.isfinite(x), axis=1))[0])
        raise MeshError(f"mesh node {i} has coordinates {x[i].tolist()}; node coordinates must be finite")
    scale = float(np.ptp(x, axis=0).max()) if len(x) else 1.0
    # Duplicated vertices: two nodes at one place leave the cells on either
    # side unconnected (a hidden slit).
    order = np.lexsort(x.T[::-1])
    same = np.all(np.abs(np.diff(x[order], axis=0)) <= 1e-12 * scale, axis=1)
    if same.any():
        k = int(np.flatnonzero(same)[0])
        i, j = sorted((int(order[k]), int(order[k + 1])))
        raise MeshError(f"mesh nodes {i} and {j} both lie at {x[i].tolist()} ({int(same.sum())} duplicated "
                        "node(s)): the cells on either side are not connected; every node must be unique "
                        "(merge duplicates, e.g. gmsh's Coherence Mesh / removeDuplicateNodes)")
    e = x[cells[:, 1:]] - x[cells[:, :1]]                       # (c, d, d): the edges from vertex 0
    size = np.abs(np.linalg.det(e))                              # d! times the area (volume)
    longest = np.linalg.norm(e, axis=2).max(axis=1)
    flat = np.flatnonzero(size <= 1e-12 * longest ** d)
    if flat.size:
        c = int(flat[0])
        raise MeshError(f"mesh cell {c} with vertices {x[cells[c]].tolist()} has zero {measure} ({flat.size} such "
                        f"cell(s)); {fix}")


def _check_box(x0: float, y0: float, x1: float, y1: float, h: float) -> None:
    for name, value in (("x0", x0), ("y0", y0), ("x1", x1), ("y1", y1), ("h", h)):
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise MeshError(f"the rectangle's {name} must be a number, got {value!r} ({type(value).__name__})")
    if not (x1 > x0 and y1 > y0):
        raise MeshError(f"empty rectangle [{x0}, {x1}] x [{y0}, {y1}]")
    if not (0.0 < h <= max(x1 - x0, y1 - y0)):
        raise MeshError(f"mesh size h = {h} must be positive and at most the domain size")


def _box_sides(gmsh, x0: float, y0: float, x1: float, y1: float, eps: float) -> dict[str, list[int]]:
    """Curves on the sides of the box [x0, x1] x [y0, y1] by their centre of
    mass (left, right, bottom, top), and the remaining ones ("other")."""
    groups: dict[str, list[int]] = {"left": [], "right": [], "bottom": [], "top": [], "other": []}
    for _, c in gmsh.model.getEntities(1):
        px, py, _ = gmsh.model.occ.getCenterOfMass(1, c)
        side = ("left" if abs(px - x0) < eps else "right" if abs(px - x1) < eps else
                "bottom" if abs(py - y0) < eps else "top" if abs(py - y1) < eps else "other")
        groups[side].append(c)
    return groups


def _finish(gmsh, classify: typing.Callable[[], dict[str, list[int]]], h: float, refine, levels=(),
            recipe=None) -> MeshData:
    """Cut a large domain into strips (_cut_into_strips), sort its boundary
    curves into named groups (classify(), by geometry: the cuts renumber
    the curves), name them as physical tags 1, 2, ... (in order), mesh,
    convert."""
    cuts = _cut_into_strips(gmsh, h)
    curve_groups = {name: [c for c in curves if not _on_cut(gmsh, c, cuts)]
                    for name, curves in classify().items()}
    gmsh.model.addPhysicalGroup(2, [s for _, s in gmsh.model.getEntities(2)], 1)
    for tag, (name, curves) in enumerate(curve_groups.items(), start=1):
        gmsh.model.addPhysicalGroup(1, curves, tag)
        gmsh.model.setPhysicalName(1, tag, name)
    _mesh_2d(gmsh, h, refine, levels)
    md = to_dolfinx(gmsh, h)
    md.refinements = [(float(r[0]), float(r[1]), float(r[2])) for r in refine]
    md.refine = [tuple(float(v) for v in r) for r in refine]
    md.levels = [tuple(v) for v in levels]
    md.recipe = recipe
    return md


#: A domain expected to have more than STRIP_NODES nodes is cut by straight
#: lines across its longer side into strips of about STRIP_NODES nodes
#: before meshing (at most MAX_STRIPS, and no strip narrower than
#: STRIP_MIN_WIDTH element sizes). gmsh's frontal-Delaunay mesher costs more
#: than linearly in a surface's size, and the strips are meshed one after
#: the other (one thread: gmsh's parallel 2D meshing gives a different mesh
#: from run to run). On [-1, 1]^2 at h = 0.0125 (30k nodes): 4 strips 0.49 s
#: against 0.84 s in one piece, smallest angle 33.5 vs 35.9 degrees (mean of
#: the cells' smallest angles 59.4 vs 59.6).
STRIP_NODES = 8_000


MAX_STRIPS = 64


STRIP_MIN_WIDTH = 8.0


#: Where the cuts sit within their strip's nominal position (as a fraction
#: of the strip width): away from round coordinates, so that a crack tip or
#: a crack segment a user places at a round coordinate does not fall on a
#: cut line.
STRIP_OFFSET = 0.1234


def _cut_into_strips(gmsh, h: float) -> tuple[int, list[float]]:
    """Cut the model's surfaces into strips when the mesh is expected to be
    large (STRIP_NODES): by vertical lines if the domain is at least as wide
    as it is tall, else by horizontal ones. Returns (axis, positions): the
    cut lines are x = position (axis 0) or y = position (axis 1); no
    positions for a small mesh. The mesh conforms to the cut lines, which
    are otherwise invisible: interior, no tag, no crack, no material change."""
    occ = gmsh.model.occ
    surfaces = gmsh.model.getEntities(2)
    lo_x, lo_y, _, hi_x, hi_y, _ = gmsh.model.getBoundingBox(-1, -1)
    axis = 0 if hi_x - lo_x >= hi_y - lo_y else 1
    lo, hi = (lo_x, hi_x) if axis == 0 else (lo_y, hi_y)
    across = (lo_y, hi_y) if axis == 0 else (lo_x, hi_x)
    strips = min(MAX_STRIPS, math.ceil(_expected_nodes(gmsh, h) / STRIP_NODES),
                 int((hi - lo) / (STRIP_MIN_WIDTH * h)))
    if strips < 2:
        return axis, []
    width = (hi - lo) / strips
    pad = 0.01 * (across[1] - across[0])
    cuts = [lo + (i + STRIP_OFFSET) * width for i in range(1, strips)]

    def point(t: float, u: float) -> int:
        return occ.addPoint(t, u, 0.0) if axis == 0 else occ.addPoint(u, t, 0.0)
    lines = [(1, occ.addLine(point(t, across[0] - pad), point(t, across[1] + pad))) for t in cuts]
    occ.fragment(surfaces, lines)
    occ.synchronize()
    # The parts of the cut lines outside the domain (beyond its ends, in its
    # holes) bound no surface: they go.
    loose = [(1, c) for _, c in gmsh.model.getEntities(1) if len(gmsh.model.getAdjacencies(1, c)[0]) == 0]
    if loose:
        occ.remove(loose, recursive=True)
        occ.synchronize()
    return axis, cuts


def _on_cut(gmsh, curve: int, cuts: tuple[int, list[float]]) -> bool:
    """Is the curve a piece of one of the cut lines (_cut_into_strips)?"""
    axis, positions = cuts
    if not positions:
        return False
    box = gmsh.model.getBoundingBox(1, curve)
    lo, hi = box[axis], box[axis + 3]                # across the cut line
    along = box[4 - axis] - box[1 - axis]            # along it
    tol = 1e-6 * max(along, 1.0)
    return hi - lo <= 2 * tol and min(abs(0.5 * (lo + hi) - t) for t in positions) <= 2 * tol


@gmsh_on_rank0
def create_rectangle(x0: float, y0: float, x1: float, y1: float, h: float,
                     refine: typing.Sequence[tuple[float, float, float, float]] = (),
                     embed_lines: typing.Sequence[tuple[tuple[float, float], tuple[float, float]]] = (),
                     embed_points: typing.Sequence[tuple[float, float]] = (), levels=()) -> MeshData:
    """Unstructured triangles of [x0, x1] x [y0, y1] with size h.

    refine: optional (x, y, h_near, radius) local refinements around points
    (e.g. crack tips): the size is h_near at and near the point (within
    4 h_near) and grows linearly to h over `radius` beyond that, never
    faster than 0.25 per unit distance (see refinement_size); 0 takes the
    fastest growth. (x, y, h_near, radius, x1, y1) refines along the
    segment (x, y)-(x1, y1) alike (a band along a crack's expected path).
    embed_lines / embed_points: segments and points the mesh must conform to
    (mesh edges along the segments, nodes at the points), inside the domain.
    levels: (x, y, x1, y1, D, L) items dividing the size by 2^L within D of
    a point or segment (cracklip.scene.size_field). Tags: left, right,
    bottom, top.
    """
    _check_box(x0, y0, x1, y1, h)
    gmsh = _gmsh()
    gmsh.model.add("rectangle")
    occ = gmsh.model.occ
    rect = occ.addRectangle(x0, y0, 0.0, x1 - x0, y1 - y0)
    tools = [(1, occ.addLine(occ.addPoint(a[0], a[1], 0.0), occ.addPoint(b[0], b[1], 0.0)))
             for (a, b) in embed_lines]
    tools += [(0, occ.addPoint(p[0], p[1], 0.0)) for p in embed_points]
    if tools:
        occ.fragment([(2, rect)], tools)
    occ.synchronize()

    def classify() -> dict[str, list[int]]:
        groups = _box_sides(gmsh, x0, y0, x1, y1, 1e-9 * max(x1 - x0, y1 - y0))
        del groups["other"]  # embedded lines
        return groups
    recipe = functools.partial(create_rectangle, x0, y0, x1, y1, h, refine=refine, embed_lines=embed_lines,
                               embed_points=embed_points)
    return _finish(gmsh, classify, h, refine, levels, recipe)


@checked_keywords
def create_square(h: float, half_width: float = 1.0,
                  refine: typing.Sequence[tuple[float, float, float, float]] = (),
                  embed_lines: typing.Sequence[tuple[tuple[float, float], tuple[float, float]]] = (),
                  embed_points: typing.Sequence[tuple[float, float]] = (), levels=()) -> MeshData:
    """The paper's square [-1, 1]^2 ([-half_width, half_width]^2), triangles of size h (tags
    left, right, bottom, top); refine, embed_lines, embed_points, levels as in create_rectangle."""
    return create_rectangle(-half_width, -half_width, half_width, half_width, h, refine=refine,
                            embed_lines=embed_lines, embed_points=embed_points, levels=levels)


@gmsh_on_rank0
def create_half_annulus(h: float, radius: float = 1.0, outer_radius: float = 3.0,
                        refine: typing.Sequence[tuple[float, float, float, float]] = (), levels=()) -> MeshData:
    """Half annulus radius <= r <= outer_radius, y >= 0 (paper section 5.2).

    Tags: hole (r = radius), outer (r = outer_radius), symmetry (y = 0). The
    points (0, radius) and (0, outer_radius) are mesh nodes.
    """
    if not (0.0 < radius < outer_radius):
        raise MeshError(f"need 0 < radius < outer_radius, got {radius}, {outer_radius}")
    gmsh = _gmsh()
    gmsh.model.add("half_annulus")
    occ = gmsh.model.occ
    outer = occ.addDisk(0, 0, 0, outer_radius, outer_radius)
    inner = occ.addDisk(0, 0, 0, radius, radius)
    box = occ.addRectangle(-2 * outer_radius, 0, 0, 4 * outer_radius, 2 * outer_radius)
    ring, _ = occ.cut([(2, outer)], [(2, inner)])
    half, _ = occ.intersect(ring, [(2, box)])
    # Nodes at the top of both arcs (on the symmetry line x = 0).
    tops = [(0, occ.addPoint(0.0, outer_radius, 0.0)), (0, occ.addPoint(0.0, radius, 0.0))]
    half, _ = occ.fragment(half, tops)
    half = [e for e in half if e[0] == 2]
    occ.synchronize()

    def classify() -> dict[str, list[int]]:
        groups: dict[str, list[int]] = {"hole": [], "outer": [], "symmetry": []}
        for _, c in gmsh.model.getEntities(1):
            # By the curve's middle point (a piece of the outer arc cut into
            # strips may end below the hole's top).
            lo, hi = gmsh.model.getParametrizationBounds(1, c)
            px, py, _ = gmsh.model.getValue(1, c, [0.5 * (lo[0] + hi[0])])
            r = math.hypot(px, py)
            if abs(py) < 1e-9 * outer_radius:
                groups["symmetry"].append(c)
            elif abs(r - radius) < 1e-6 * outer_radius:
                groups["hole"].append(c)
            elif abs(r - outer_radius) < 1e-6 * outer_radius:
                groups["outer"].append(c)
            # (else: a cut line inside the ring)
        return groups
    recipe = functools.partial(create_half_annulus, h, radius, outer_radius, refine=refine)
    return _finish(gmsh, classify, h, refine, levels, recipe)


#: gmsh's smoothing pass after meshing (Mesh.Smoothing = 1) runs while the
#: mesh is expected to have at most this many nodes (NODES_PER_AREA_H2 x
#: area / h^2, refinements not counted) and is skipped on larger meshes,
#: where it costs half the meshing time: on [-1, 1]^2 at h = 0.0125 (30k
#: nodes) 0.8 s of 1.6 s, for a smallest angle of 40.9 instead of 35.9
#: degrees (1st percentile of the cells' smallest angles 48.0 vs 45.1, mean
#: 59.6 either way); with a tip refinement 20 x finer, 36.0 vs 28.5.
SMOOTHING_MAX_NODES = 20_000


#: Nodes per unit area of gmsh's frontal-Delaunay mesh of size h: ~1.17 / h^2.
NODES_PER_AREA_H2 = 1.17


def _expected_nodes(gmsh, h: float) -> float:
    """Nodes of a mesh of size h of the model's surfaces (refinements not
    counted): NODES_PER_AREA_H2 x area / h^2."""
    area = sum(gmsh.model.occ.getMass(2, tag) for _, tag in gmsh.model.getEntities(2))
    return NODES_PER_AREA_H2 * area / h ** 2


def _mesh_2d(gmsh, h: float, refine, levels=(), area: float | None = None) -> None:
    """Mesh the model's surfaces with the size field of h, refine and levels
    (cracklip.scene.size_field): one MathEval field per refinement and their
    minimum, or with levels the whole field as one expression. area: the
    part's area if the model is not OpenCASCADE's (for the smoothing rule)."""
    nodes = _expected_nodes(gmsh, h) if area is None else NODES_PER_AREA_H2 * area / h ** 2
    smoothing = 1 if nodes <= SMOOTHING_MAX_NODES else 0
    gmsh.option.setNumber("Mesh.Smoothing", smoothing)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeMin", smallest_size(h, refine, levels))
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    if any(int(v[5]) > 0 for v in levels):
        f = gmsh.model.mesh.field.add("MathEval")
        gmsh.model.mesh.field.setString(f, "F", size_expression(h, refine, levels))
        gmsh.model.mesh.field.setAsBackgroundMesh(f)
    elif refine:
        fields = []
        for item in refine:
            f = gmsh.model.mesh.field.add("MathEval")
            gmsh.model.mesh.field.setString(f, "F", refinement_expression(h, item))
            fields.append(f)
        fmin = gmsh.model.mesh.field.add("Min")
        gmsh.model.mesh.field.setNumbers(fmin, "FieldsList", fields)
        gmsh.model.mesh.field.setAsBackgroundMesh(fmin)
    gmsh.model.mesh.generate(2)


@gmsh_on_rank0
def read_msh(path: str | pathlib.Path) -> MeshData:
    """Read a gmsh .msh file with named physical curves as boundary tags."""
    path = pathlib.Path(path)
    if not path.is_file():
        raise MeshError(f"mesh file {path} does not exist")
    if not _msh_header(path):
        raise MeshError(f"{path}: gmsh cannot read this file (it does not start with $MeshFormat); cracklip reads "
                        "gmsh .msh files (format 2 or 4) with a 2D triangle mesh")
    gmsh = _gmsh()
    try:
        gmsh.open(str(path))
    except Exception as e:  # gmsh raises a bare Exception for an unreadable file
        _restart_gmsh()
        raise MeshError(f"{path}: gmsh cannot read this file ({e}); cracklip reads gmsh .msh files "
                        "(format 2 or 4) with a 2D triangle mesh") from None
    groups = gmsh.model.getPhysicalGroups()
    types = gmsh.model.mesh.getElementTypes(2) if gmsh.model.getDimension() >= 2 else []
    if (gmsh.model.getDimension() <= 2 and len(types) == 0 and any(d == 1 for d, _ in groups)
            and not any(d >= 2 for d, _ in groups)):
        gmsh.model.remove()
        raise MeshError(f"{path}: the file holds the line elements of its Physical Curves but no triangle: it has "
                        "no Physical Surface, and once any physical group is defined gmsh saves only the elements "
                        "of physical groups. Add Physical Surface(\"part\") = {...}; (the part's surfaces) to the "
                        ".geo and mesh again (or set Mesh.SaveAll = 1), or give cracklip the .geo itself "
                        "(mesh.kind = \"geometry\")")
    if gmsh.model.getDimension() != 2:
        dim = gmsh.model.getDimension()
        gmsh.model.remove()
        raise MeshError(f"{path}: cracklip needs a 2D mesh, this one has dimension {dim}")
    if any(t != 2 for t in types) or len(types) == 0:
        names = [gmsh.model.mesh.getElementProperties(t)[0] for t in types]
        gmsh.model.remove()
        raise MeshError(f"{path}: only 3-node triangles are supported, the file has "
                        f"{names or 'no 2D elements'}; mesh with Mesh.ElementOrder = 1 and without "
                        "recombination")
    tags = gmsh.model.mesh.getNodes()[0]
    unused = np.setdiff1d(tags, gmsh.model.mesh.getElementsByType(2)[1])
    if unused.size:
        coord = gmsh.model.mesh.getNode(int(unused[0]))[0][:2].tolist()
        gmsh.model.remove()
        if not groups:
            raise MeshError(
                f"{path}: the file has no physical groups, so gmsh saved every entity of the geometry, construction "
                f"points too ({unused.size} node(s) in no triangle, e.g. node {int(unused[0])} at {coord}: a circle's "
                "centre?), and no boundary has a name for the scene's conditions and loads. In the .geo add "
                "Physical Surface(\"part\") = {...}; and a Physical Curve(\"name\") = {...}; for every boundary "
                "you load or support, and mesh again; or give cracklip the .geo itself (mesh.kind = \"geometry\")")
        raise MeshError(f"{path}: {unused.size} node(s) belong to no triangle (e.g. node {int(unused[0])} at "
                        f"{coord}); every node must be a vertex of a triangle: remove unused nodes")
    return to_dolfinx(gmsh, None)


def create_plate_with_hole(x0: float, y0: float, x1: float, y1: float, h: float,
                           center: tuple[float, float], radius: float,
                           refine: typing.Sequence[tuple[float, float, float, float]] = (),
                           embed_points: typing.Sequence[tuple[float, float]] = (), levels=()) -> MeshData:
    """Rectangle [x0, x1] x [y0, y1] with a circular hole, triangles of size h.

    The hole (centre, radius) must lie strictly inside the rectangle.
    refine: optional (x, y, h_near, radius) local refinements (see
    create_rectangle); embed_points: points that must be mesh nodes (point
    supports, point forces). Tags: left, right, bottom, top, hole.
    """
    return create_plate_with_holes(x0, y0, x1, y1, h, [(center[0], center[1], radius)], refine, embed_points, levels)


@gmsh_on_rank0
def create_plate_with_holes(x0: float, y0: float, x1: float, y1: float, h: float,
                            holes: typing.Sequence[tuple[float, float, float]],
                            refine: typing.Sequence[tuple[float, float, float, float]] = (),
                            embed_points: typing.Sequence[tuple[float, float]] = (), levels=()) -> MeshData:
    """Rectangle [x0, x1] x [y0, y1] with circular holes (x, y, radius),
    each strictly inside the rectangle and apart from the others (a drilled
    plate). refine, embed_points: as create_plate_with_hole. Tags: left,
    right, bottom, top, hole (every hole's edge)."""
    _check_box(x0, y0, x1, y1, h)
    holes = [(float(cx), float(cy), float(r)) for cx, cy, r in holes]
    if not holes:
        raise MeshError("a plate with holes needs at least one hole (x, y, radius)")
    for i, (cx, cy, r) in enumerate(holes):
        if not (r > 0.0 and x0 < cx - r and cx + r < x1 and y0 < cy - r and cy + r < y1):
            raise MeshError(f"hole {i} (centre ({cx:g}, {cy:g}), radius {r:g}) must lie strictly inside "
                            f"the plate [{x0:g}, {x1:g}] x [{y0:g}, {y1:g}]")
        for j, (dx, dy, dr) in enumerate(holes[:i]):
            if math.hypot(cx - dx, cy - dy) <= r + dr:
                raise MeshError(f"holes {j} and {i} overlap or touch (centres ({dx:g}, {dy:g}) and "
                                f"({cx:g}, {cy:g}), radii {dr:g} and {r:g})")
    gmsh = _gmsh()
    gmsh.model.add("plate_with_holes")
    occ = gmsh.model.occ
    plate = occ.addRectangle(x0, y0, 0.0, x1 - x0, y1 - y0)
    disks = [(2, occ.addDisk(cx, cy, 0.0, r, r)) for cx, cy, r in holes]
    body, _ = occ.cut([(2, plate)], disks)
    if embed_points:
        body, _ = occ.fragment(body, [(0, occ.addPoint(p[0], p[1], 0.0)) for p in embed_points])
        body = [e for e in body if e[0] == 2]
    occ.synchronize()

    def classify() -> dict[str, list[int]]:
        groups = _box_sides(gmsh, x0, y0, x1, y1, 1e-7 * max(x1 - x0, y1 - y0))
        groups["hole"] = groups.pop("other")
        return groups
    recipe = functools.partial(create_plate_with_holes, x0, y0, x1, y1, h, holes, refine=refine,
                               embed_points=embed_points)
    return _finish(gmsh, classify, h, refine, levels, recipe)
