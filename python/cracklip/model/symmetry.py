"""Symmetry planes on the discrete model (cracklip.scene.symmetry): the
enriched dofs a plane fixes, and the check that every crack meeting a plane
meets it at right angles (then the plane is a plane of symmetry of the
crack too, and a front end on it is an interior point of the whole front).

The same code serves planar parts (a straight line of symmetry, cracks as
curves) and solids (a plane, crack surfaces): the crack's normal is the
gradient of its normal level set phi in the cells it crosses whose nodes on
the plane see phi of both signs (the crack's trace on the plane).
"""
from __future__ import annotations

import math

import numpy as np

from .. import _cracklip
from ..errors import CrackGeometryError
from ..scene.cell_size import mean_cell_size
from ..scene.processes import agree, first_error, reduced
from ..scene.symmetry import SymmetryCondition

#: The crack's normal may deviate this much (degrees) from lying in the
#: plane of symmetry (the crack perpendicular to it).
CRACK_ANGLE_DEG = 2.0

#: A 3D front must meet the plane within CRACK_ANGLE_DEG of its normal
#: where the crack's shape gives the front's tangent (an ellipse, a
#: polygon), within FRONT_FIT_ANGLE_DEG where it is fitted to the P1 front
#: polyline's vertices within FRONT_FIT_ELEMENTS element sizes of the end
#: (a triangulated surface: a curved front's fit turns by about h / rho).
FRONT_FIT_ANGLE_DEG = 20.0
FRONT_FIT_ELEMENTS = 3.0

#: Front functions at the plane's nodes whose nearest front point has its
#: tangent e3 within this angle (degrees) of the plane's normal: their mode
#: III function moves the node out of the plane, and the mirror-symmetric
#: solution has no mode III there (fixed to 0).
MODE_III_ANGLE_DEG = 15.0


def symmetry_enriched_dofs(layout, nodes: np.ndarray, bc: SymmetryCondition, geometries, x: np.ndarray
                           ) -> np.ndarray:
    """The enriched dofs a symmetry plane on `nodes` fixes besides the
    Heaviside ones of its component (constraints.compute_dirichlet): the
    normal component of the scalar front (tip) functions, and mode III of
    the vector front functions whose front crosses the plane there (3D)."""
    gdim = x.shape[1]
    kind, base = np.asarray(layout.kind), np.asarray(layout.node)
    on = np.isin(base, nodes)
    out = [gdim * (layout.num_std_nodes + np.flatnonzero(on & (kind == 1))) + bc.component]
    vec = np.flatnonzero(on & (kind == 2))
    if gdim == 3 and vec.size:
        crack = np.asarray(layout.crack)[vec]
        normal = np.asarray(bc.normal, dtype=float)
        for ic in np.unique(crack):
            sel = vec[crack == ic]
            p = _cracklip.compute_front_projection_3d(geometries[ic], np.ascontiguousarray(x[base[sel]]))
            across = np.abs(p["frame"][:, 2] @ normal) >= math.cos(math.radians(MODE_III_ANGLE_DEG))
            out.append(gdim * (layout.num_std_nodes + sel[across]) + 2)
    return np.concatenate(out).astype(np.int64)


def plane_nodes(model, bc: SymmetryCondition) -> np.ndarray:
    """Nodes (indices) on a symmetry plane's tag."""
    import dolfinx.fem
    tdim = model.scene.mesh.mesh.topology.dim
    facets = model.scene.mesh.facets(bc.where)
    return np.asarray(dolfinx.fem.locate_dofs_topological(model.V, tdim - 1, facets), dtype=np.int64)


def check_symmetry(model) -> None:
    """Raise CrackGeometryError naming the crack and the plane if a crack
    meets a symmetry plane at other than right angles, lies in it, or (3D)
    has a front that meets it obliquely. Collective under mpirun: each
    process checks the cells it holds, and all raise the first finding."""
    planes = [bc for bc in model.scene.dirichlet if isinstance(bc, SymmetryCondition)]
    if not planes or not model.cracks:
        return
    if model.distributed:
        h = [_front_cell_size(model, np.asarray(cm.geometry.front["segment_cell"])) if model.gdim == 3 else 0.0
             for cm in model.cracks]  # (collective: before any process may stop at a finding)
        agree(first_error([lambda: _check_planes(model, planes, h)]), model.V.mesh.comm)
        return
    _check_planes(model, planes, None)


def _check_planes(model, planes: list, front_h: list | None) -> None:
    """check_symmetry's findings on this process's cells (front_h: each
    crack's front cell size, computed here if None)."""
    kind = type(model.cracks[0])
    gdim = model.x.shape[1]
    tol = math.sin(math.radians(CRACK_ANGLE_DEG))
    for bc in planes:
        normal = np.asarray(bc.normal, dtype=float)
        on_plane = np.zeros(model.x.shape[0], dtype=bool)
        on_plane[plane_nodes(model, bc)] = True
        for ic, cm in enumerate(model.cracks):
            # the cells the crack crosses where its trace meets the plane: phi
            # of both signs (or 0) at their nodes on the plane
            cells = np.flatnonzero(cm.crossed())
            onp = on_plane[model.cells[cells]]
            phi = cm.phi[model.cells[cells]]
            meets = onp.any(axis=1) & (np.where(onp, phi, np.inf).min(axis=1) <= 0.0) \
                & (np.where(onp, phi, -np.inf).max(axis=1) >= 0.0)
            cells = cells[meets]
            if cells.size:
                g = np.einsum("ca,cai->ci", cm.phi[model.cells[cells]], kind.shape_gradients(model.x, model.cells[cells]))
                g /= np.maximum(np.linalg.norm(g, axis=1), 1e-300)[:, None]
                cos = np.abs(g @ normal)
                worst = int(np.argmax(cos))
                if cos[worst] > tol:
                    dihedral = math.degrees(math.acos(min(1.0, float(cos[worst]))))
                    what = ("lies in it: a crack on a symmetry plane is a free part of that face of the part, which "
                            "the symmetry condition would hold shut; model the whole crack inside the part"
                            if dihedral < 1.0 else
                            f"meets it at {dihedral:.3g} degrees instead of 90 (at most {CRACK_ANGLE_DEG:g} off)")
                    raise CrackGeometryError(
                        f"crack {cm.crack.name!r} and {bc.label} (tag {bc.where!r}): the crack {what}; a crack must "
                        "meet a symmetry plane at right angles, so that its mirror image continues it")
            if gdim == 3:
                _check_front_ends(model, cm, bc, normal, None if front_h is None else front_h[ic])


def _check_front_ends(model, cm, bc: SymmetryCondition, normal: np.ndarray, h: float | None) -> None:
    """A 3D front ending on the plane must meet it at right angles
    (CRACK_ANGLE_DEG, or FRONT_FIT_ANGLE_DEG for a fitted tangent); h: the
    front's cell size (None: computed here)."""
    f = cm.geometry.front
    x = np.asarray(f["x"])
    off = np.asarray(f["piece_offsets"])
    closed = np.asarray(f["closed"]).astype(bool)
    if not len(x):
        return
    if h is None:
        h = _front_cell_size(model, np.asarray(f["segment_cell"]))
    origin = np.asarray(bc.origin, dtype=float)
    for k in np.flatnonzero(~closed):
        idx = np.arange(off[k], off[k + 1])
        for end in (idx, idx[::-1]):
            if abs((x[end[0]] - origin) @ normal) > 0.5 * h or len(end) < 2:
                continue
            t, limit = front_tangent(cm.crack, x[end], h)
            angle = math.degrees(math.acos(min(1.0, abs(float(t @ normal)))))
            if angle > limit:
                raise CrackGeometryError(
                    f"crack {cm.crack.name!r} and {bc.label} (tag {bc.where!r}): its front meets the plane at "
                    f"({', '.join(f'{v:.6g}' for v in x[end[0]])}) {angle:.3g} degrees off the plane's normal (at "
                    f"most {limit:g}): mirrored, the front would have a kink there; a crack must meet a symmetry "
                    "plane at right angles (an ellipse centred on the plane with an axis in it does)")


def _front_cell_size(model, segment_cell: np.ndarray) -> float:
    """Mean edge of the front segments' cells; under mpirun (collective)
    each segment counted by the process owning its cell (-1: not on this
    process)."""
    if not model.distributed:
        return mean_cell_size(model.x, model.cells[segment_cell])
    own = segment_cell[(segment_cell >= 0) & model.owned_cells_only(segment_cell)]
    total, count = reduced(np.array([mean_cell_size(model.x, model.cells[own]) * len(own), len(own)]),
                           "SUM", model.V.mesh.comm)
    return float(total / count) if count else 0.0


def front_tangent(crack, pts: np.ndarray, h: float) -> tuple[np.ndarray, float]:
    """The unit tangent of a front at its end pts[0] (pts: the front
    polyline's vertices from that end) and the angle (degrees) it is
    checked to: from the crack's shape for an ellipse (the derivative in
    the parametric angle) or a polygon (the nearest edge), else fitted to
    the vertices (a quadratic in arc length)."""
    p0 = pts[0]
    if hasattr(crack, "parametric_angle") and hasattr(crack, "axis2"):
        th = float(crack.parametric_angle(p0[None])[0])
        t = -crack.a * math.sin(th) * crack.axis + crack.b * math.cos(th) * crack.axis2
        return t / np.linalg.norm(t), CRACK_ANGLE_DEG
    if hasattr(crack, "points") and np.ndim(crack.points) == 2 and np.shape(crack.points)[1] == 3:
        v = np.asarray(crack.points, dtype=float)
        a, b = v, np.roll(v, -1, axis=0)
        d = b - a
        u = np.clip(np.einsum("ij,ij->i", p0 - a, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
        k = int(np.argmin(np.linalg.norm(a + u[:, None] * d - p0, axis=1)))
        return d[k] / np.linalg.norm(d[k]), CRACK_ANGLE_DEG
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    near = s <= max(FRONT_FIT_ELEMENTS * h, s[min(2, len(s) - 1)])
    deg = min(2, int(near.sum()) - 1)
    t = np.array([np.polyfit(s[near], pts[near, i], deg)[-2] for i in range(3)])
    return t / np.linalg.norm(t), FRONT_FIT_ANGLE_DEG
