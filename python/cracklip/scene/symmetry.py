"""Symmetry planes: a boundary tag on which the problem is mirror-symmetric
(a plane of a solid, a straight line of a planar part), so that the part
modelled is a half (a quarter, ...) of the whole.

On the plane the displacement normal to it vanishes: ``Symmetry`` becomes a
Dirichlet condition on that component (``SymmetryCondition``, one of the
scene's ``dirichlet`` list, labelled ``symmetry[i]`` in the reactions). The
component must be one of x, y, z, so the plane must be normal to an axis;
the tag must be planar. A crack that meets the plane continues in its
mirror image: it must meet it at right angles (checked on the model,
cracklip.model.symmetry), and a front end on the plane is an interior point
of the whole front (cracklip.fracture.sif_3d computes its K on the domain
and its mirror image).
"""
from __future__ import annotations

import dataclasses
import typing

import numpy as np

from ..errors import BoundaryConditionError, checked_keywords
from .conditions import Dirichlet
from .processes import reduced

#: The tag's nodes must lie within this fraction of the part's size of one
#: plane (line), its normal within this of an axis.
PLANE_TOLERANCE = 1e-6


@checked_keywords
@dataclasses.dataclass
class Symmetry:
    """A plane (line) of symmetry of the problem on a boundary tag.

    Attributes:
        where: the boundary tag's name or number.
        label: its name in messages and reactions (a scene file's
            "symmetry[i]"; default "symmetry on <tag>").
    """
    where: typing.Union[str, int]
    label: str = ""

    def __post_init__(self):
        self.label = self.label or f"symmetry on {self.where!r}"


@dataclasses.dataclass
class SymmetryCondition(Dirichlet):
    """The Dirichlet condition of a symmetry plane: u . n = 0 on the tag
    (component = the axis of n). Besides the standard and Heaviside dofs
    of a tag condition it fixes the enriched dofs whose functions move the
    plane's nodes out of it (cracklip.model.constraints).

    Attributes:
        normal: (d,) the plane's unit normal (an axis, signed outward).
        origin: (d,) a point of the plane.
    """
    normal: tuple = ()
    origin: tuple = ()


def tag_nodes(mesh, where) -> np.ndarray:
    """Coordinates (n, d) of the nodes of a boundary tag's facets (collective
    under mpirun: every process's, gathered)."""
    verts = mesh.facet_vertices(where)
    x = verts.reshape(-1, verts.shape[-1])
    comm = mesh.mesh.comm
    if comm.size > 1:
        x = np.concatenate(comm.allgather(x))
    return np.unique(x, axis=0)


def _part_centre_and_size(mesh) -> tuple[np.ndarray, float]:
    """The mean of the part's nodes and its size (largest extent); collective
    under mpirun (each node counted once, by its owner)."""
    geo = mesh.mesh.geometry
    pts = geo.x[:, :mesh.gdim]
    comm = mesh.mesh.comm
    own = pts[:geo.index_map().size_local]
    total = reduced(np.append(own.sum(axis=0), len(own)), "SUM", comm)
    lo, hi = reduced(pts.min(axis=0), "MIN", comm), reduced(pts.max(axis=0), "MAX", comm)
    return total[:-1] / total[-1], float((hi - lo).max())


def symmetry_plane(mesh, sym: Symmetry) -> tuple[np.ndarray, np.ndarray, int]:
    """The plane (line) of a symmetry tag: a point on it, its unit normal
    (pointing out of the part) and the axis of the normal; an error naming
    the tag if it is not planar or its normal is not along x, y or z.
    Collective under mpirun (the tag's nodes of every process: the same
    plane and verdict on all)."""
    x = tag_nodes(mesh, sym.where)
    centre, size = _part_centre_and_size(mesh)
    size = size or 1.0
    origin = x.mean(axis=0)
    _, sv, vt = np.linalg.svd(x - origin, full_matrices=False)
    normal = vt[-1]
    off = np.abs((x - origin) @ normal)
    shape = "plane" if mesh.gdim == 3 else "straight line"
    if len(x) < mesh.gdim or off.max() > PLANE_TOLERANCE * size:
        k = int(np.argmax(off))
        raise BoundaryConditionError(
            f"{sym.label}: boundary tag {sym.where!r} is not a {shape} (node {x[k].tolist()} lies {off[k]:.3g} off the "
            f"best-fitting one, part size {size:.3g}); a symmetry condition needs a {shape}")
    axis = int(np.argmax(np.abs(normal)))
    if abs(abs(normal[axis]) - 1.0) > PLANE_TOLERANCE:
        raise BoundaryConditionError(
            f"{sym.label}: boundary tag {sym.where!r} is a {shape} with normal "
            f"({', '.join(f'{v:.4g}' for v in normal)}), not along x, y{', z' if mesh.gdim == 3 else ''}: "
            "cracklip fixes the normal displacement as one displacement component, so a symmetry plane must be "
            "normal to an axis (turn the part)")
    normal = np.zeros(mesh.gdim)
    # outward: away from the part's centre
    normal[axis] = 1.0 if origin[axis] >= centre[axis] else -1.0
    origin = origin.copy()
    origin[axis] = float(np.mean(x[:, axis]))
    return origin, normal, axis


def symmetry_conditions(mesh, planes: typing.Sequence[Symmetry]) -> list[SymmetryCondition]:
    """The Dirichlet conditions u . n = 0 of the symmetry planes."""
    out = []
    for sym in planes:
        origin, normal, axis = symmetry_plane(mesh, sym)
        out.append(SymmetryCondition(sym.where, component=axis, value=0.0, label=sym.label,
                                     normal=tuple(normal.tolist()), origin=tuple(origin.tolist())))
    return out


def mirror(points: np.ndarray, origin: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The mirror images of points (n, d) in a plane through origin with unit normal."""
    p = np.asarray(points, dtype=float)
    return p - 2.0 * ((p - origin) @ normal)[..., None] * normal
