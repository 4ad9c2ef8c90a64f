"""Post-processing of a solved X-FEM model: point values, crack opening, sub-cell fields."""
from __future__ import annotations

import dataclasses
import typing

import numpy as np

import dolfinx.geometry

from . import _cracklip
from .errors import InputError
from .model import XfemModel


@dataclasses.dataclass
class Solution:
    """Displacement dofs of a model and what can be derived from them.

    Attributes:
        model: the discrete model.
        u: (num_dofs,) standard dofs then enriched dofs (see assembly).
        timings: seconds per phase of the solve.
    """
    model: XfemModel
    u: np.ndarray
    timings: dict[str, float]

    # -- point values -------------------------------------------------------
    def locate(self, points: np.ndarray, prefer_crossed: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """Cell and reference coordinates of each point (n, 2).

        A point on a cell boundary goes to a cell crossed by a crack if there
        is one (so that both lips can be evaluated there).
        """
        pts = np.asarray(points, dtype=float).reshape(-1, 2)
        msh = self.model.scene.mesh.mesh
        p3 = np.zeros((len(pts), 3))
        p3[:, :2] = pts
        tree = _tree(self.model)
        cand = dolfinx.geometry.compute_collisions(tree, p3)
        coll = dolfinx.geometry.compute_colliding_cells(msh, cand, p3)
        crossed = np.zeros(self.model.cells.shape[0], dtype=bool)
        for g in self.model.geometries:
            crossed[g.cell_class == 1] = True
            crossed[g.cell_class == 2] = True
        cells = np.empty(len(pts), dtype=np.int32)
        for i in range(len(pts)):
            links = coll.links(i)
            if len(links) == 0:
                raise InputError(f"point {pts[i].tolist()} is outside the mesh")
            pick = links[0]
            if prefer_crossed:
                for c in links:
                    if crossed[c]:
                        pick = c
                        break
            cells[i] = pick
        xv = self.model.x[self.model.cells[cells]]
        J = np.stack([xv[:, 1] - xv[:, 0], xv[:, 2] - xv[:, 0]], axis=2)
        ref = np.linalg.solve(J, (pts - xv[:, 0])[:, :, None])[:, :, 0]
        return cells, np.clip(ref, 0.0, 1.0)

    def displacement(self, points: np.ndarray, side: int = 0) -> np.ndarray:
        """Displacement (n, 2) at points; side +1 / -1 picks a lip of a crack
        crossing the point's cell, 0 the side the point lies on."""
        cells, ref = self.locate(points)
        sides = np.full(len(cells), side, dtype=np.int8)
        return self._evaluate(cells, ref, sides)

    def _evaluate(self, cells, ref, sides) -> np.ndarray:
        m = self.model
        return _cracklip.evaluate_displacement(m.x, m.cells, m.layout, m.geometries, self.u,
                                               cells, ref, sides)

    # -- along the crack ----------------------------------------------------
    def crack_opening(self, crack: int = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Jump [[u]] = u(+) - u(-) along a crack, sampled on each cut cell.

        Returns dict with x (n, 2) points, s (n,) arc-length-like coordinate
        along the crack direction, jump (n, 2), normal (n,) = [[u]].n (n the
        + side normal, positive = opening), tangential (n,) = [[u]].t.
        """
        g = self.model.geometries[crack]
        cc = g.crack_cells
        own = cc["owns_segment"].astype(bool)
        cells = cc["cell"][own]
        seg = cc["segment"][own]  # (k, 2, 2) reference P, Q
        t = np.linspace(0.0, 1.0, points_per_segment)
        ref = (seg[:, None, 0, :] * (1 - t)[None, :, None] + seg[:, None, 1, :] * t[None, :, None])
        ref = ref.reshape(-1, 2)
        cell_rep = np.repeat(cells, points_per_segment).astype(np.int32)
        up = self._evaluate(cell_rep, ref, np.ones(len(cell_rep), dtype=np.int8))
        um = self._evaluate(cell_rep, ref, -np.ones(len(cell_rep), dtype=np.int8))
        xv = self.model.x[self.model.cells[cell_rep]]
        x = xv[:, 0] + ref[:, :1] * (xv[:, 1] - xv[:, 0]) + ref[:, 1:] * (xv[:, 2] - xv[:, 0])
        # + side normal: segment direction rotated by -90 degrees (+ side on its left).
        xP = _phys(self.model, cells, seg[:, 0])
        xQ = _phys(self.model, cells, seg[:, 1])
        d = xQ - xP
        tang = d / np.linalg.norm(d, axis=1)[:, None]
        tang = np.repeat(tang, points_per_segment, axis=0)
        normal = np.stack([-tang[:, 1], tang[:, 0]], axis=1)
        jump = up - um
        # Normal points into the + side; the jump u(+) - u(-) along it is an opening.
        start = self.model.cracks[crack].crack.points[0]
        direction = self.model.cracks[crack].crack.points[-1] - start
        s = (x - start) @ (direction / np.linalg.norm(direction))
        order = np.argsort(s, kind="stable")
        return {"x": x[order], "s": s[order], "jump": jump[order],
                "normal": np.einsum("ij,ij->i", jump, normal)[order],
                "tangential": np.einsum("ij,ij->i", jump, tang)[order]}

    # -- whole-field quantities --------------------------------------------
    def subcell_fields(self) -> dict[str, typing.Any]:
        """Displacement and stress on the sub-cell mesh (see io.write_vtu)."""
        m = self.model
        mat = m.scene.material
        return _cracklip.compute_subcell_fields(m.x, m.cells, m.layout, m.geometries, self.u,
                                                mat.E, mat.nu)

    def strain_energy(self) -> float:
        """1/2 int sigma : eps over the domain (sub-cell exact for P1 + Heaviside)."""
        return float(self.subcell_fields()["strain_energy"])

    @property
    def standard_displacement(self) -> np.ndarray:
        """(num_nodes, 2) standard dofs = displacement at the nodes (shifted enrichment)."""
        n = self.model.layout.num_std_nodes
        return self.u[: 2 * n].reshape(n, 2)


def _phys(model: XfemModel, cells: np.ndarray, ref: np.ndarray) -> np.ndarray:
    xv = model.x[model.cells[cells]]
    return xv[:, 0] + ref[:, :1] * (xv[:, 1] - xv[:, 0]) + ref[:, 1:] * (xv[:, 2] - xv[:, 0])


def _tree(model: XfemModel):
    tree = getattr(model, "_bb_tree", None)
    if tree is None:
        msh = model.scene.mesh.mesh
        tree = dolfinx.geometry.BoundingBoxTree(msh, msh.topology.dim)
        model._bb_tree = tree
    return tree
