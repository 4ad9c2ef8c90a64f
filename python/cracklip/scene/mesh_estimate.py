"""How big a solid's mesh and run will be, before the mesh is made.

A mistyped size (mesh.tip_h = 0.005 for 0.05) asks gmsh for a thousand
times the tetrahedra; meshed, it fails minutes later out of memory. The
estimate comes first: the part is meshed coarsely at its element size h
(a few thousand tetrahedra, curved faces followed), and the size field the
real mesh will have (the front and surface refinements, mesh_3d) is
integrated over those coarse tetrahedra:

    cells ~ CELL_FACTOR * integral over the part of 6 / size(x)^3 dx

(6 / h^3: gmsh's tetrahedra per unit volume at a uniform size h), each
coarse tetrahedron split in eight until it is at most ACCEPT_SIZES local
sizes across (a degree-2 rule inside), so that the work grows with the
estimate's resolution, not with the mesh. Then

    nodes ~ NODES_PER_CELL cells,
    dofs  ~ 3 nodes (1 + ENRICHED_SHARE),
    peak  ~ BASE_MEMORY + BYTES_PER_DOF dofs

calibrated on measured runs (docs/speed.md, "Memory of a 3D run" and
"Size estimate before meshing"). A run whose
estimated peak exceeds the memory the machine has available
(``available_memory``: MemAvailable, or the cgroup's limit if lower) is
refused with ModelSizeError before meshing, unless forced (``--force``).
"""
from __future__ import annotations

import dataclasses
import logging
import math
import pathlib
import typing

import numpy as np

from ..errors import ModelSizeError
from .size_field import refinement_size

logger = logging.getLogger(__name__)

#: Tetrahedra of gmsh's Delaunay mesh per integral of 6 / size^3, measured
#: on nine graded meshes of 9e3 to 9e5 tetrahedra (the penny crack at
#: tip_h = a/5 .. a/200, the corner crack at a hole and the surface crack
#: at two sizes each): 0.80-0.89, mean 0.825 (docs/speed.md).
CELL_FACTOR = 0.83

#: Mesh nodes per tetrahedron: 0.163 (9e4 tetrahedra) to 0.227 (9e3, a thin
#: plate: more boundary nodes) on the same meshes.
NODES_PER_CELL = 0.18

#: Enriched dofs as a share of the standard ones (5 to 40 % on the
#: measured scenes, by the enrichment radius; a middle value).
ENRICHED_SHARE = 0.25

#: Peak memory of a whole run (import, mesh, model, assembly, solve, K,
#: outputs) = BASE_MEMORY + BYTES_PER_DOF x dofs, on the iterative path
#: (docs/speed.md "Memory of a 3D run"): command-line runs of the penny
#: crack at 5.9e4 and 9.6e4 dofs peak at 0.57 and 0.78 GB (this
#: formula: 0.64, 0.77), bench_3d's runs at 4.9e5 and 9.9e5 dofs at 1.95 and
#: 3.57 GB (2.08, 3.71); the libraries alone take 0.16 GB. A fit to the
#: small runs alone (2.5 KB per dof) underestimates the large ones by 16 %,
#: and the estimate guards against running out of memory. A solid with
#: many enriched dofs needs more: the penny at 7.6e4 dofs, 39 % enriched,
#: by the direct path 1.4 GB; with the enrichment radius 0.25 a at 9.6e5
#: dofs 5.97 GB with the front's torus in the exact band, 3.4 GB with its
#: outer part solved inexactly (solvers.schwarz; this formula 0.70, 3.6).
BASE_MEMORY = 0.45e9
BYTES_PER_DOF = 3.3e3

#: A coarse tetrahedron is accepted once it is at most this many local
#: element sizes across; finer ones are split in eight.
ACCEPT_SIZES = 2.0

#: The estimate evaluates at most about this many tetrahedra (four size
#: field values each), splitting where it matters most: 0.1-0.2 s, within
#: 0.3 % of the unlimited integral on the nine meshes of CELL_FACTOR (and
#: 1.14e6 for 9.14e5 tetrahedra made at tip_h = a/200).
MAX_TETS = 20_000

#: Elements per full turn on curved faces in the coarse mesh.
CURVATURE_ELEMENTS = 12


@dataclasses.dataclass(frozen=True)
class MeshEstimate:
    """The estimated size of a mesh and of its run.

    Attributes:
        cells: tetrahedra.
        nodes: mesh nodes.
        dofs: unknowns of the X-FEM model (standard and enriched).
        memory: peak memory of a run, bytes.
        coarse: True when the estimate stopped refining (MAX_TETS): it is
            rougher, and rather low.
    """
    cells: float
    nodes: float
    dofs: float
    memory: float
    coarse: bool = False

    def describe(self) -> str:
        return (f"about {self.cells:.3g} tetrahedra, {self.dofs:.3g} dofs and {self.memory / 1e9:.2g} GB of "
                "memory")


class SizeField:
    """The size field of the mesh (mesh_3d._size_fields): h, or less near
    the refinements: a front refinement's points (a k-d tree of them), a
    box refinement's box (h_front inside, growing with the distance from
    the box as gmsh's Box field does, no plateau)."""

    def __init__(self, h: float, fronts: typing.Sequence, floor: float = 0.0):
        self.h = float(h)
        self.floor = float(floor)
        self.items = []
        for fr in fronts:
            plateau, growth = refinement_size(h, fr.h_front, fr.radius)
            self.items.append((self._distance(fr), fr.h_front, 0.0 if is_box(fr) else plateau, growth))

    def _distance(self, fr) -> typing.Callable[[np.ndarray, float], np.ndarray]:
        """d(points, reach): the distance of points (n, 3) from the refinement
        (inf or any value >= reach beyond reach)."""
        if is_box(fr):
            lo, hi = np.asarray(fr.lo, dtype=float), np.asarray(fr.hi, dtype=float)
            return lambda p, reach: np.linalg.norm(np.maximum(np.maximum(lo - p, p - hi), 0.0), axis=1)
        from scipy.spatial import cKDTree
        tree = cKDTree(thinned(fr.points, 0.5 * self.floor))
        return lambda p, reach: tree.query(p, distance_upper_bound=reach)[0]

    def __call__(self, points: np.ndarray) -> np.ndarray:
        """The size at points (n, 3), at least the floor."""
        out = np.full(len(points), self.h)
        for distance, h_front, plateau, growth in self.items:
            reach = plateau + (self.h - h_front) / growth  # the size is h beyond
            d = distance(points, reach)
            out = np.minimum(out, h_front + growth * np.maximum(0.0, np.minimum(d, reach) - plateau))
        return np.maximum(out, self.floor)


def is_box(fr) -> bool:
    """A box refinement (mesh_3d.BoxRefinement: corners lo, hi) rather than
    one by points (FrontRefinement)."""
    return hasattr(fr, "lo") and hasattr(fr, "hi")


def thinned(points: np.ndarray, cell: float) -> np.ndarray:
    """One point per cube of side `cell` (all of them if cell = 0): the
    distances to the set change by at most sqrt(3) cell, which a size field
    floored well above that does not see, and the k-d tree queries stay
    fast however fine the front's sampling."""
    if cell <= 0.0:
        return points
    _, keep = np.unique(np.floor(points / cell).astype(np.int64), axis=0, return_index=True)
    return points[np.sort(keep)]


#: Sizes below this fraction of h are not resolved by the coarse integration
#: (its work would grow with the mesh): the size field is taken at least
#: that there, and what the smaller sizes add is modelled near each
#: refinement (below_floor).
FLOOR = 0.01


def below_floor(fr, h: float, floor: float) -> float:
    """integral of 6 / size^3 - 6 / floor^3 where a refinement's size is below
    the floor: the size depends on the distance s to its points only, and so
    close to them (a few floor sizes) the region is a tube around a curve
    (area 2 pi s L at distance s), a slab on both sides of a surface (2 A)
    or balls around points (4 pi s^2 each); L and A from the points' mean
    spacing (their nearest-neighbour distance). Parts of it outside the
    part are counted too (at most a few floor sizes at a front's ends)."""
    plateau, growth = refinement_size(h, fr.h_front, fr.radius)
    if fr.h_front >= floor:
        return 0.0
    if is_box(fr):  # inside the box, then a layer over its faces
        side = np.asarray(fr.hi, dtype=float) - np.asarray(fr.lo, dtype=float)
        s = np.linspace(0.0, (floor - fr.h_front) / growth, 2001)
        layer = 2.0 * (side[0] * side[1] + side[1] * side[2] + side[0] * side[2])
        inside = float(np.prod(side)) * (6.0 / fr.h_front ** 3 - 6.0 / floor ** 3)
        return inside + float(np.trapz(6.0 / (fr.h_front + growth * s) ** 3 - 6.0 / floor ** 3, s)) * layer
    from scipy.spatial import cKDTree
    pts = fr.points
    n = len(pts)
    spacing = float(np.median(cKDTree(pts).query(pts, k=2)[0][:, 1])) if n > 1 else 0.0
    top = plateau + (floor - fr.h_front) / growth  # the size reaches the floor
    s = np.linspace(0.0, top, 2001)
    size = fr.h_front + growth * np.maximum(0.0, s - plateau)
    excess = 6.0 / size ** 3 - 6.0 / floor ** 3
    if fr.kind == "surface" and n > 1:
        area = np.full_like(s, 2.0 * n * spacing ** 2)
    elif fr.kind == "curve" and n > 1:
        area = 2.0 * np.pi * s * n * spacing
    else:
        area = 4.0 * np.pi * s ** 2 * n
    return float(np.trapz(excess * area, s))


#: Degree-2 rule on the tetrahedron (barycentric points, equal weights).
_A, _B = 0.5854101966249685, 0.1381966011250105
_RULE = np.array([[_A, _B, _B, _B], [_B, _A, _B, _B], [_B, _B, _A, _B], [_B, _B, _B, _A]])

#: The eight children of a tetrahedron (Bey's split) by its vertices 0-3 and
#: edge midpoints 4: 01, 5: 02, 6: 03, 7: 12, 8: 13, 9: 23.
_CHILDREN = np.array([[0, 4, 5, 6], [4, 1, 7, 8], [5, 7, 2, 9], [6, 8, 9, 3],
                      [4, 5, 6, 8], [4, 5, 7, 8], [5, 6, 8, 9], [5, 7, 8, 9]])


def integrate_cells(tets: np.ndarray, h: float, fronts: typing.Sequence) -> tuple[float, bool]:
    """integral of 6 / size^3 over tetrahedra (m, 4, 3): (value, stopped
    early). Each is split in eight while it is more than ACCEPT_SIZES local
    sizes across (sizes below FLOOR h: below_floor), within a budget of
    MAX_TETS tetrahedra evaluated: past it,
    only those whose rule values spread most (volume x (max - min)) are
    split, the others taken as they are (the estimate is then coarse, and
    rather low: a rule's points miss the smallest sizes)."""
    floor = FLOOR * h
    total = sum(below_floor(fr, h, floor) for fr in fronts)
    stopped, spent = False, 0
    size_at = SizeField(h, fronts, floor)
    t = np.asarray(tets, dtype=float)
    while len(t):
        spent += len(t)
        e = t[:, [1, 2, 3, 2, 3, 3]] - t[:, [0, 0, 0, 1, 1, 2]]
        across = np.linalg.norm(e, axis=2).max(axis=1)
        vol = np.abs(np.einsum("ni,ni->n", e[:, 0], np.cross(e[:, 1], e[:, 2]))) / 6.0
        q = np.einsum("qa,nai->nqi", _RULE, t).reshape(-1, 3)
        f = 6.0 / size_at(q).reshape(len(t), 4) ** 3
        split = across > ACCEPT_SIZES * f.max(axis=1) ** (-1.0 / 3.0) * 6.0 ** (1.0 / 3.0)
        room = max(0, (MAX_TETS - spent) // 8)
        if np.count_nonzero(split) > room:
            stopped = True
            spread = np.where(split, vol * (f.max(axis=1) - f.min(axis=1)), -1.0)
            keep = np.argsort(spread)[::-1][:room]
            split[:] = False
            split[keep] = True
        total += float(np.sum(vol[~split] * f[~split].mean(axis=1)))
        rest = t[split]
        if not len(rest):
            break
        mid = 0.5 * (rest[:, [0, 0, 0, 1, 1, 2]] + rest[:, [1, 2, 3, 2, 3, 3]])
        t = np.concatenate([rest, mid], axis=1)[:, _CHILDREN].reshape(-1, 4, 3)
    return total, stopped


def estimate(tets: np.ndarray, h: float, fronts: typing.Sequence) -> MeshEstimate:
    """The estimate (module doc) from a coarse mesh's tetrahedra."""
    integral, stopped = integrate_cells(tets, h, fronts)
    cells = CELL_FACTOR * integral
    nodes = NODES_PER_CELL * cells
    dofs = 3.0 * nodes * (1.0 + ENRICHED_SHARE)
    return MeshEstimate(cells, nodes, dofs, BASE_MEMORY + BYTES_PER_DOF * dofs, stopped)


def available_memory() -> float:
    """Bytes of memory this process can still take: the kernel's
    MemAvailable, or what the cgroup's limit leaves if lower; inf if neither
    can be read."""
    out = math.inf
    try:
        for line in pathlib.Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemAvailable:"):
                out = float(line.split()[1]) * 1024.0
    except OSError:
        pass
    try:
        limit = pathlib.Path("/sys/fs/cgroup/memory.max").read_text().strip()
        if limit != "max":
            used = float(pathlib.Path("/sys/fs/cgroup/memory.current").read_text().strip())
            out = min(out, float(limit) - used)
    except (OSError, ValueError):
        pass
    return out


def release_memory() -> None:
    """Give the heap's free pages back to the system (glibc malloc_trim):
    after a phase that freed much (the solve, K along the fronts), so that
    the next one starts from what is live. Without it the freed memory
    stayed with the process and the next phase's arrays, not fitting the
    fragments, grew it further: command-line runs of the penny crack at
    5.9e4 and 9.6e4 dofs peaked at 0.62 and 0.86 GB, 0.57 and 0.78 GB with
    it (docs/speed.md). Nothing happens where there is no glibc."""
    import ctypes
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):  # pragma: no cover - not glibc
        pass


def check_estimate(est: MeshEstimate, limit: float | None, what: str) -> None:
    """Raise ModelSizeError if the estimated run needs more than `limit`
    bytes (None: no limit)."""
    if limit is None or est.memory <= limit:
        return
    raise ModelSizeError(
        f"{what}: the mesh asked for would have {est.describe()} (estimated before meshing), more than the "
        f"{limit / 1e9:.2g} GB this machine has available: check mesh.h, mesh.tip_h, mesh.crack_h and "
        "mesh.refine (a size typed 10 times too small makes 1000 times the tetrahedra), or give --force to mesh "
        "it anyway")


__all__ = ["MeshEstimate", "estimate", "integrate_cells", "SizeField", "available_memory", "release_memory",
           "check_estimate"]
