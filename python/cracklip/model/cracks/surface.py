"""A 3D crack on a tetrahedral mesh: a surface (an ellipse, a planar polygon
or a triangulated surface of scene.crack_surface) ending at its front (the
CrackModel of a solid part).

The level sets, cell classes (plain, cut, face: along mesh faces, front,
extension), sub-tetrahedra, lip facets and the front polylines with their
frames come from the C++ kernels (cpp/geometry/crack_geometry_3d); nothing
here loops over the mesh in Python.

Sub-tetrahedral mesh (``subcell_fields``): the cells the crack touches
(cut, face and front cells) split into their sub-tetrahedra, each with its
own four vertices, the displacement there evaluated on the sub-tetrahedron's
own side of the crack (so a warp by the displacement opens the crack); the
other cells whole. Cells without enriched nodes share the mesh's nodes,
whose displacement is the standard dofs (every enriched function is
shifted: it vanishes at its own node, and a node of a cell without enriched
nodes carries none); whole cells with enriched nodes get their own four
vertices (near the crack the field is not P1, and a node on the crack
belongs to both lips). Stress at each cell's (sub-tetrahedron's) centroid.
Work: numpy over the mesh a chunk of CHUNK cells at a time; the C++
evaluation only on the enriched cells' points, so it grows with the cells
near the crack, not with the mesh.

Lip facets (``lip_facets``): each crack's lip triangles (three vertices
each, physical coordinates) with both lips' displacements at the vertices,
the opening [[u]] = u+ - u-, its normal part (the gap, > 0 open) and the
size of its tangential part (slip).
"""
from __future__ import annotations

import logging
import typing

import numpy as np

from ... import _cracklip
from ...errors import CrackGeometryError, InputError
from ...scene.crack_surface import EllipticalCrack, PolygonCrack, SurfaceCrack
from ...scene.material import strain, stress
from ...scene.options import Options
from ...scene.partition import node_input_indices
from ...scene.processes import agree, total
from ...scene.stress_field import tensor_to_voigt
from . import CrackModel, with_initial_stress
from .shared_front import join_front

logger = logging.getLogger(__name__)

#: Cells per chunk of the whole-mesh loops (bounded memory at 1e6 cells).
CHUNK = 200_000

#: Points per chunk of the C++ evaluations.
POINT_CHUNK = 400_000

#: Reference vertices of the tetrahedron.
REF_VERTICES = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])

#: Voigt order of the stress columns.
VOIGT = ("xx", "yy", "zz", "yz", "xz", "xy")

#: Gradients of the P1 shape functions on the reference tetrahedron.
_DN = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


class SurfaceCrackModel(CrackModel):
    """A crack surface on tetrahedra, with its front (module doc)."""

    DIM = 3
    #: cpp/geometry/crack_geometry_3d.h CellClass3D.
    CELL_CLASSES = {"plain": 0, "cut": 1, "face": 2, "front": 3, "extension": 4}
    CROSSED = (1, 2, 3)
    SPLIT = (1, 2)
    END = "front"
    EXTENT = "area"
    #: Tetrahedra's quadrature options: the front rules.
    QUADRATURE = Options.quadrature_options_3d
    #: The stiffness's own rules (degree 2 off the collapsed sub-tetrahedra):
    #: front functions reach beyond the sub-tetrahedra at the front, and a
    #: higher degree there integrated -sigma_0 : eps(phi) otherwise than the
    #: stiffness integrates the uniform strain that balances it: a uniform
    #: sigma_0 relaxing in a penny's box (exact in the P1 space) moved the
    #: front functions' coefficients by 0.016 at degree 4 and 7e-11 so.
    LOAD_DEGREE = None
    VOIGT = VOIGT
    #: Gauss points per lip facet direction of the lip loads and the SIFs' lip terms.
    LIP_POINTS = 6

    # -- the crack ------------------------------------------------------------
    def lip_samples(self, model, points: int) -> dict[str, np.ndarray]:
        """lip_points facet by facet (Gauss away from the front, collapsed on
        facets touching it; a point-collapsed facet may give negative
        weights), with front_vertices (n,)."""
        return dict(_cracklip.compute_lip_points(model.x, model.cells, self.geometry, int(points)))

    def ends_inside(self) -> bool:
        return len(self.geometry.front["x"]) > 0

    @staticmethod
    def slip(jump: np.ndarray, normal: np.ndarray) -> np.ndarray:
        gap = np.einsum("ij,ij->i", jump, normal)
        return jump - gap[:, None] * normal

    # -- construction ---------------------------------------------------------
    @classmethod
    def check_scene(cls, scene) -> None:
        if scene.material.plane != "strain":
            raise InputError("material.plane is a 2D setting: a 3D part is plain elasticity (leave plane = 'strain')")

    @classmethod
    def create(cls, scene, crack, x: np.ndarray, cells: np.ndarray) -> "SurfaceCrackModel":
        surface = crack_surface(crack)
        # (cells cut in the mesh's input node order and the front joined from
        # every process's cells: the same sub-tetrahedra and front on any
        # number of processes)
        node_input = node_input_indices(scene.mesh.mesh, cells, x.shape[0])
        comm = scene.mesh.mesh.comm
        try:  # (under MPI a process's part may hold none of the crack: decided over all processes below)
            geometry = _cracklip.compute_crack_geometry_3d(x, cells, surface, scene.options.snap_tol, node_input,
                                                           comm.size == 1)
        except (ValueError, RuntimeError) as e:
            raise CrackGeometryError(f"{crack.name}: {e}") from None
        if comm.size > 1:
            counts = geometry.class_counts
            crossed = total(counts["cut"] + counts["face"] + counts["front"], comm)
            agree(None if crossed else CrackGeometryError(
                f"{crack.name}: {surface!r}: no cell of the mesh is cut by the crack: the crack surface lies outside "
                "the part; move the crack into the part or check its units"), comm)
        join_front(geometry, surface, scene.mesh.mesh, x, cells, node_input)
        if geometry.num_snapped:
            logger.info("%s: %d nodes snapped onto the crack (options.snap_tol = %g)", crack.name, geometry.num_snapped,
                        scene.options.snap_tol)
        return cls(crack, (), geometry)

    @classmethod
    def check_model(cls, model) -> list:
        from ..checks import check_fronts, check_pieces
        check_pieces(model)
        return check_fronts(model)

    # -- the kernels of tetrahedra ----------------------------------------------
    @classmethod
    def cell_measures(cls, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
        xv = x[cells]
        e1, e2, e3 = xv[:, 1] - xv[:, 0], xv[:, 2] - xv[:, 0], xv[:, 3] - xv[:, 0]
        return np.abs(np.einsum("ci,ci->c", e1, np.cross(e2, e3))) / 6

    @classmethod
    def shape_gradients(cls, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
        xv = x[cells]                                          # (c, 4, 3)
        J = np.transpose(xv[:, 1:] - xv[:, :1], (0, 2, 1))     # J[:, i, a] = d x_i / d ref_a
        return np.einsum("ab,cbi->cai", _DN, np.linalg.inv(J))

    @classmethod
    def cell_rule(cls, degree: int) -> tuple[np.ndarray, np.ndarray]:
        if degree <= 1:
            return np.full((1, 4), 0.25), np.ones(1)
        r = _cracklip.tetrahedron_rule(degree)  # (reference points (k, 3), weights summing to 1/6)
        ref = np.asarray(r["points"])
        return np.column_stack([1.0 - ref.sum(axis=1), ref]), 6.0 * np.asarray(r["weights"])

    @classmethod
    def facet_normals(cls, model, where, basis: dict) -> np.ndarray:
        """Outward unit normals at a facet basis' points (the facets' own)."""
        return basis["normals"]

    @classmethod
    def enriched_cell_points(cls, model, cells: np.ndarray, degree: int) -> dict[str, np.ndarray]:
        qp = dict(_cracklip.compute_enriched_cell_quadrature(model.x, model.cells, model.layout, model.geometries,
                                                             np.asarray(cells, dtype=np.int32),
                                                             cls.quadrature_options(model.scene.options, degree)))
        qp["x"] = physical(model, qp["cell"], qp["ref"])
        return qp

    @classmethod
    def field_points(cls, model, u: np.ndarray, cells: np.ndarray | None, degree: int | None) -> dict[str, np.ndarray]:
        """Enriched cells get the stiffness's rules (sub-tetrahedra, collapsed
        at the front), Gauss degree at least `degree` elsewhere in them; the
        others a Gauss rule of `degree` (default 1: their P1 gradient is
        constant). side: the crossing crack's lip side in cells it crosses,
        else 0."""
        cell_list = (np.arange(model.cells.shape[0], dtype=np.int32) if cells is None
                     else np.asarray(cells, dtype=np.int32))
        ec, pc = split_enriched(model, cell_list)
        parts = []
        if ec.size:
            qp = _cracklip.compute_enriched_cell_quadrature(model.x, model.cells, model.layout, model.geometries, ec,
                                                            cls.quadrature_options(model.scene.options, degree))
            _, grad = cls.evaluate(model, u, qp["cell"], qp["ref"], qp["side"])
            parts.append({"cell": qp["cell"], "x": physical(model, qp["cell"], qp["ref"]), "weight": qp["weight"],
                          "side": qp["side"], "grad_u": grad})
        if pc.size:
            parts.append(_plain_points(model, u, pc, 1 if degree is None else int(degree)))
        if not parts:
            return {"cell": np.zeros(0, np.int32), "x": np.zeros((0, 3)), "weight": np.zeros(0),
                    "side": np.zeros(0, np.int8), "grad_u": np.zeros((0, 3, 3))}
        return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}

    @classmethod
    def subcell_fields(cls, solution) -> dict[str, typing.Any]:
        """The sub-tetrahedral mesh with its fields (module doc): points (P,
        3), displacement (P, 3), cells (C, 4) into points, stress (C, 6)
        Voigt (VOIGT), von_mises (C,), side (C,) int8 (the sub-tetrahedron's
        side, 0 for a whole cell), parent (C,) the mesh cell, crack (C,) the
        crack that splits it (-1 for a whole cell), and the counts:
        num_nodes (the mesh nodes, the first points), num_whole_enriched,
        num_sub."""
        m = solution.model
        mat = m.scene.material
        x, cells = m.x, m.cells
        ncells = cells.shape[0]
        enriched = np.zeros(ncells, dtype=bool)
        enriched[np.asarray(m.layout.cells, dtype=np.int32)] = True
        sub = crack_subcells(m)
        split = np.zeros(ncells, dtype=bool)
        split[sub["cell"]] = True

        # Cells without enriched nodes: the mesh's nodes, P1 stress per cell.
        plain = np.flatnonzero(~enriched & ~split).astype(np.int32)
        u_nodes = solution.standard_displacement
        plain_stress = np.empty((plain.size, 6))
        for k in range(0, plain.size, CHUNK):
            c = plain[k:k + CHUNK]
            plain_stress[k:k + CHUNK] = tensor_to_voigt(stress(strain(p1_gradients(x, cells[c], u_nodes)), mat))

        # Whole cells with enriched nodes: their own four vertices.
        whole = np.flatnonzero(enriched & ~split).astype(np.int32)
        w_cells = np.repeat(whole, 4)
        w_ref = np.tile(REF_VERTICES, (whole.size, 1))
        w_u = _evaluate(solution, w_cells, w_ref, np.zeros(w_cells.size, dtype=np.int8))
        _, w_grad = _evaluate(solution, whole, np.full((whole.size, 3), 0.25), np.zeros(whole.size, dtype=np.int8),
                              gradient=True)

        # Sub-tetrahedra: their four vertices on their own side.
        nsub = len(sub["cell"])
        s_cells = np.repeat(sub["cell"], 4)
        s_ref = sub["sub"].reshape(-1, 3)
        s_u = _evaluate(solution, s_cells, s_ref, np.repeat(sub["side"], 4))
        _, s_grad = _evaluate(solution, sub["cell"], sub["sub"].mean(axis=1), sub["side"], gradient=True)

        nn = x.shape[0]
        points = np.concatenate([x, physical(m, w_cells, w_ref), physical(m, s_cells, s_ref)])
        displacement = np.concatenate([u_nodes, w_u, s_u])
        conn = np.concatenate([cells[plain].astype(np.int64),
                               nn + np.arange(4 * whole.size, dtype=np.int64).reshape(-1, 4),
                               nn + 4 * whole.size + np.arange(4 * nsub, dtype=np.int64).reshape(-1, 4)])
        st = np.concatenate([plain_stress,
                             tensor_to_voigt(stress(strain(w_grad), mat)) if whole.size else np.zeros((0, 6)),
                             tensor_to_voigt(stress(strain(s_grad), mat)) if nsub else np.zeros((0, 6))])
        st = with_initial_stress(solution, st, lambda: points[conn].mean(axis=1))  # (total: at the centroids)
        return {"points": points, "displacement": displacement, "cells": conn, "stress": st,
                "von_mises": von_mises_3d(st),
                "side": np.concatenate([np.zeros(plain.size + whole.size, np.int8), sub["side"]]),
                "parent": np.concatenate([plain, whole, sub["cell"]]).astype(np.int32),
                "crack": np.concatenate([np.full(plain.size + whole.size, -1, np.int32), sub["crack"]]),
                "num_nodes": int(nn), "num_whole_enriched": int(whole.size), "num_sub": int(nsub)}

    def lip_facets(self, solution, crack: int, subdivide: int = 1, fields=None) -> dict[str, np.ndarray]:
        """This crack's lip facets (F triangles) with the opening at their
        vertices: x (F, 3, 3) physical vertices, cell (F,), normal (F, 3)
        unit, into the + lip, area (F,), num_front (F,) vertices on the
        front (of the parent facet), u_plus, u_minus, jump (F, 3, 3)
        (vertex, component), gap (F, 3) = [[u]].n (> 0 open), slip_vector
        (F, 3, 3) = [[u]] - gap n, slip (F, 3) its size, ref (F, 3, 3) the
        vertices' reference coordinates in their cell. subdivide: each lip
        facet split into subdivide^2
        triangles (finer samples of the sqrt(r) opening near the front; a
        lip facet is flat in its cell, so the pieces are exact). fields:
        fields(facets) -> facets with more per-facet arrays, evaluated in
        their cells (under MPI before the facets are gathered: e.g. the
        contact pressure, io.outputs.facet_contact)."""
        m = solution.model
        cc = self.geometry.crack_cells
        counts = np.diff(np.asarray(cc["facet_offsets"]))
        cell = np.repeat(np.asarray(cc["cell"], dtype=np.int32), counts)
        ref = np.asarray(cc["facets"]).reshape(-1, 3, 3)
        normal = np.asarray(cc["facet_normal"]).reshape(-1, 3)
        area = np.asarray(cc["facet_area"])
        num_front = np.asarray(cc["facet_num_front"])
        if m.distributed:  # this process's owned cells' facets; every process's gathered below
            own = m.owned_cells_only(cell)
            cell, ref, normal, area, num_front = cell[own], ref[own], normal[own], area[own], num_front[own]
        if subdivide > 1:
            ref, parent = subdivide_triangles(ref, int(subdivide))
            cell, normal, num_front = cell[parent], normal[parent], num_front[parent]
            area = area[parent] / subdivide ** 2
        nf = len(cell)
        pc, pr = np.repeat(cell, 3), ref.reshape(-1, 3)
        up = _evaluate(solution, pc, pr, np.ones(3 * nf, dtype=np.int8)).reshape(nf, 3, 3)
        um = _evaluate(solution, pc, pr, -np.ones(3 * nf, dtype=np.int8)).reshape(nf, 3, 3)
        xp = physical(m, pc, pr).reshape(nf, 3, 3)
        jump = up - um
        gap = np.einsum("fvi,fi->fv", jump, normal)
        slip = jump - gap[:, :, None] * normal[:, None, :]
        out = {"x": xp, "cell": cell, "normal": normal, "area": area, "num_front": num_front, "u_plus": up,
               "u_minus": um, "jump": jump, "gap": gap, "slip_vector": slip, "slip": np.linalg.norm(slip, axis=2),
               "ref": ref}
        if fields is not None:
            out = fields(out)
        if m.distributed:  # every process's facets, in rank order, their cells -1 (as Solution.lip_samples')
            parts = m.V.mesh.comm.allgather(out)
            out = {k: np.concatenate([q[k] for q in parts]) for k in out}
            out["cell"] = np.full(len(out["cell"]), -1, dtype=np.int32)
        return out


def crack_surface(crack) -> "_cracklip.CrackSurface3D":
    """The C++ surface of a crack description."""
    label = crack.name or "crack"
    try:
        if isinstance(crack, EllipticalCrack):
            return _cracklip.create_ellipse_crack(crack.center, crack.normal, crack.axis, crack.a, crack.b)
        if isinstance(crack, PolygonCrack):
            # The C++ polygon is counter-clockwise seen from the + side: the
            # order PolygonCrack's normal (Newell's, right-handed) follows.
            return _cracklip.create_polygon_crack(crack.points)
        if isinstance(crack, SurfaceCrack):
            return _cracklip.create_triangulated_crack(crack.vertices, crack.triangles)
    except (ValueError, RuntimeError) as e:
        source = getattr(crack, "source", "")
        # the triangles are the file's facets in its order, counted from 0
        where = f" ({source}: its triangles counted from 0 in the file's order)" if source else ""
        raise CrackGeometryError(f"{label}: {e}{where}") from None
    raise CrackGeometryError(f"{label}: a 3D part takes crack surfaces (cracks[].ellipse, polygon or surface), "
                             f"got {type(crack).__name__}")


def split_enriched(model, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(the enriched cells, the others) among cells."""
    enriched = np.zeros(model.cells.shape[0], dtype=bool)
    enriched[np.asarray(model.layout.cells, dtype=np.int32)] = True
    return cells[enriched[cells]], cells[~enriched[cells]]


def physical(model, cells: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """Physical points (n, 3) of reference points (cell, ref (n, 3))."""
    N = np.column_stack([1.0 - ref.sum(axis=1), ref])
    return np.einsum("na,nai->ni", N, model.x[model.cells[cells]])


def von_mises_3d(s: np.ndarray) -> np.ndarray:
    """von Mises stress of (n, 6) Voigt stresses."""
    xx, yy, zz, yz, xz, xy = s.T
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3.0 * (yz ** 2 + xz ** 2 + xy ** 2))


def p1_gradients(x: np.ndarray, cells: np.ndarray, u_nodes: np.ndarray) -> np.ndarray:
    """grad u (c, 3, 3) (grad[c, i, j] = d u_i / d x_j) of the P1 field with
    nodal values u_nodes (num_nodes, 3) on tetrahedra cells (c, 4)."""
    G = SurfaceCrackModel.shape_gradients(x, cells)        # (c, 4, 3) grad N_a
    return np.einsum("cai,caj->cij", u_nodes[cells], G)


def _plain_points(model, u: np.ndarray, cells: np.ndarray, degree: int) -> dict[str, np.ndarray]:
    """Gauss points of P1 cells no crack function reaches: their gradient
    is the standard dofs' (constant per cell)."""
    rule = _cracklip.tetrahedron_rule(max(degree, 1))
    ref, w = rule["points"], rule["weights"]
    nq = len(w)
    n = model.layout.num_std_nodes
    us = u[: 3 * n].reshape(n, 3)
    xv = model.x[model.cells[cells]]                       # (c, 4, 3)
    J = np.transpose(xv[:, 1:] - xv[:, :1], (0, 2, 1))     # J[:, i, a] = d x_i / d ref_a
    detJ = np.linalg.det(J)
    G = np.einsum("ab,cbi->cai", _DN, np.linalg.inv(J))   # (c, 4, 3) grad N_a
    grad = np.einsum("cai,caj->cij", us[model.cells[cells]], G)
    N = np.column_stack([1.0 - ref.sum(axis=1), ref])      # (q, 4)
    x = np.einsum("qa,cai->cqi", N, xv).reshape(-1, 3)
    return {"cell": np.repeat(cells, nq).astype(np.int32), "x": x,
            "weight": (np.abs(detJ)[:, None] * w[None, :]).ravel(),
            "side": np.zeros(len(cells) * nq, dtype=np.int8), "grad_u": np.repeat(grad, nq, axis=0)}


def _evaluate(solution, cells, ref, sides, gradient: bool = False):
    """The solution's displacement (and gradient) in chunks of POINT_CHUNK points."""
    m = solution.model
    n = len(cells)
    if n == 0:
        return (np.zeros((0, 3)), np.zeros((0, 3, 3))) if gradient else np.zeros((0, 3))
    parts = [SurfaceCrackModel.evaluate(m, solution.u, cells[i:i + POINT_CHUNK], ref[i:i + POINT_CHUNK],
                                        sides[i:i + POINT_CHUNK]) for i in range(0, n, POINT_CHUNK)]
    if gradient:
        return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])
    return np.concatenate([p[0] for p in parts])


def crack_subcells(model) -> dict[str, np.ndarray]:
    """The sub-tetrahedra of every crack's cut, face and front cells: cell
    (N,), sub (N, 4, 3) reference coordinates, side (N,) int8, crack (N,)."""
    cells, subs, sides, crack = [], [], [], []
    for ci, g in enumerate(model.geometries):
        cc = g.crack_cells
        counts = np.diff(np.asarray(cc["sub_offsets"]))
        cells.append(np.repeat(np.asarray(cc["cell"], dtype=np.int32), counts))
        subs.append(np.asarray(cc["sub"]).reshape(-1, 4, 3))
        sides.append(np.asarray(cc["side"], dtype=np.int8))
        crack.append(np.full(int(counts.sum()), ci, dtype=np.int32))
    if not cells:
        return {"cell": np.zeros(0, np.int32), "sub": np.zeros((0, 4, 3)), "side": np.zeros(0, np.int8),
                "crack": np.zeros(0, np.int32)}
    return {"cell": np.concatenate(cells), "sub": np.concatenate(subs), "side": np.concatenate(sides),
            "crack": np.concatenate(crack)}


def subdivide_triangles(tri: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Each triangle (F, 3, d) split into n^2 equal ones: (F n^2, 3, d) and
    the parent of each (F n^2,)."""
    local = []
    for i in range(n):
        for j in range(n - i):
            local.append([(i, j), (i + 1, j), (i, j + 1)])
            if i + j < n - 1:
                local.append([(i + 1, j), (i + 1, j + 1), (i, j + 1)])
    bary = np.array([[[1.0 - (a + b) / n, a / n, b / n] for a, b in t] for t in local])   # (n^2, 3, 3)
    out = np.einsum("svk,fkd->fsvd", bary, tri).reshape(-1, 3, tri.shape[2])
    return out, np.repeat(np.arange(len(tri)), len(local))


__all__ = ["SurfaceCrackModel", "crack_surface", "crack_subcells", "subdivide_triangles", "p1_gradients",
           "von_mises_3d", "physical", "VOIGT"]
