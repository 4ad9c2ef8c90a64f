"""Post-processing of a solved X-FEM model: point values, crack opening, sub-cell fields."""
from __future__ import annotations

import dataclasses
import typing

import numpy as np

import dolfinx.geometry

from . import _cracklip
from .errors import InputError
from .model import XfemModel


#: Gauss degree of the interaction integral in cells without tip functions:
#: the integrand (smooth, non-polynomial auxiliary fields) needs more than the
#: stiffness's rule.
SIF_DEGREE = 8


@dataclasses.dataclass
class Solution:
    """Displacement dofs of a model and what can be derived from them.

    Attributes:
        model: the discrete model.
        u: (num_dofs,) standard dofs then enriched dofs (see assembly).
        timings: seconds per phase of the solve.
        condition: 1-norm condition numbers if asked (cond_1norm, cond_1norm_jacobi).
        contact: with contact, the ContactSystem ("system"), reduced
            multipliers ("lambda"), active set, iterations and history.
        solver: "relative_residual" ||A x - b|| / ||b|| of the final linear
            solve, and "solves": one record per MUMPS solve (what, size,
            relative_residual).
    """
    model: XfemModel
    u: np.ndarray
    timings: dict[str, float]
    condition: dict[str, float] = dataclasses.field(default_factory=dict)
    contact: dict[str, typing.Any] = dataclasses.field(default_factory=dict)
    solver: dict[str, typing.Any] = dataclasses.field(default_factory=dict)

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

    def displacement_gradient(self, points: np.ndarray, side: int = 0) -> np.ndarray:
        """Displacement gradient (n, 2, 2), [p, i, j] = d u_i / d x_j, at points."""
        cells, ref = self.locate(points)
        sides = np.full(len(cells), side, dtype=np.int8)
        return self._evaluate(cells, ref, sides, gradient=True)[1]

    def _evaluate(self, cells, ref, sides, gradient: bool = False):
        m = self.model
        u, grad = _cracklip.evaluate_displacement(m.x, m.cells, m.layout, m.geometries, self.u,
                                                  cells, ref, sides)
        return (u, grad) if gradient else u

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
        s = self._along_crack(crack, x)
        order = np.argsort(s, kind="stable")
        return {"x": x[order], "s": s[order], "jump": jump[order],
                "normal": np.einsum("ij,ij->i", jump, normal)[order],
                "tangential": np.einsum("ij,ij->i", jump, tang)[order]}

    def _along_crack(self, crack: int, x: np.ndarray) -> np.ndarray:
        """Coordinate of points along a crack's chord, from its first point."""
        pts = self.model.cracks[crack].crack.points
        direction = pts[-1] - pts[0]
        return (x - pts[0]) @ (direction / np.linalg.norm(direction))

    # -- whole-field quantities --------------------------------------------
    def subcell_fields(self) -> dict[str, typing.Any]:
        """Displacement and stress on the sub-cell mesh (see io.write_vtu)."""
        m = self.model
        mat = m.scene.material
        return _cracklip.compute_subcell_fields(m.x, m.cells, m.layout, m.geometries, self.u,
                                                mat.E, mat.nu)

    def field_points(self, cells: np.ndarray | None = None, degree: int | None = None
                     ) -> dict[str, np.ndarray]:
        """Quadrature points of the stiffness rules on `cells` (all cells by
        default) with grad u there: cell, x (n, 2), weight, side, grad_u (n, 2, 2).
        degree: Gauss degree in cells without tip functions (default: the
        stiffness's)."""
        m = self.model
        cell_list = np.zeros(0, dtype=np.int32) if cells is None else np.asarray(cells, dtype=np.int32)
        return _cracklip.compute_field_points(m.x, m.cells, m.layout, m.geometries, self.u, cell_list,
                                              self._quadrature(degree))

    def _quadrature(self, degree: int | None):
        q = self.model.scene.options.quadrature_options()
        if degree is not None:
            q.degree = max(q.degree, int(degree))
        return q

    def strain_energy(self) -> float:
        """1/2 int sigma : eps over the domain (the stiffness quadrature)."""
        f = self.field_points()
        eps = strain(f["grad_u"])
        return float(0.5 * np.sum(f["weight"] * np.einsum("nij,nij->n", stress(eps, self.model.scene.material), eps)))

    def energy_error(self, exact_gradient: typing.Callable[[np.ndarray, np.ndarray], np.ndarray]
                     ) -> tuple[float, float]:
        """Energy norm of u - u_exact, absolute and relative to the exact field's.

        exact_gradient(x (n, 2), side (n,)) returns grad u_exact (n, 2, 2);
        side is +1 / -1 on a crack's lips region (0 elsewhere), for fields
        that jump across the crack.
        """
        mat = self.model.scene.material
        err2 = ref2 = 0.0
        # In chunks of cells, so that memory stays bounded on large meshes.
        ncells = self.model.cells.shape[0]
        for chunk in np.array_split(np.arange(ncells, dtype=np.int32), max(1, ncells // 100_000)):
            f = self.field_points(chunk, degree=6)
            g_ex = np.asarray(exact_gradient(f["x"], f["side"]), dtype=float)
            e = strain(f["grad_u"] - g_ex)
            eex = strain(g_ex)
            err2 += float(np.sum(f["weight"] * np.einsum("nij,nij->n", stress(e, mat), e)))
            ref2 += float(np.sum(f["weight"] * np.einsum("nij,nij->n", stress(eex, mat), eex)))
        return float(np.sqrt(err2)), float(np.sqrt(err2 / ref2))

    def stress_intensity_factors(self, crack: int = 0, radius: float | None = None
                                 ) -> list[dict[str, typing.Any]]:
        """K_I, K_II at every tip of a crack by the domain interaction integral.

        radius: of the plateau q-function (default 4 mean edge lengths); it
        must stay inside the domain and away from other cracks.
        """
        m = self.model
        if radius is None:
            radius = 4.0 * m.h
        if not (isinstance(radius, (int, float, np.floating)) and np.isfinite(radius) and radius > 0.0):
            raise InputError(f"the SIF domain radius must be a finite number > 0 (default: 4 mean edge "
                             f"lengths, {4.0 * m.h:.3g} here), got {radius!r}")
        g = m.geometries[crack]
        mat = m.scene.material
        out = []
        for j in range(g.tips.shape[0]):
            tip, e1 = g.tips[j], g.tip_tangents[j]
            d = _cracklip.compute_domain_points(m.x, m.cells, m.layout, m.geometries, tip, e1,
                                                radius, self._quadrature(SIF_DEGREE))
            if d["weight"].size == 0:
                dist = np.linalg.norm(m.x - tip, axis=1)
                raise InputError(f"no cell crosses the SIF domain circle of radius {radius} "
                                 f"around tip {tip.tolist()}: the q-function is constant (nodes within "
                                 f"the radius: {int(np.count_nonzero(dist < radius))} of {len(dist)}); use "
                                 f"a radius above the nearest node's distance {dist.min():.3g} that keeps "
                                 "the circle inside the domain")
            _, grad = _cracklip.evaluate_displacement(m.x, m.cells, m.layout, m.geometries, self.u,
                                                      d["cell"], d["ref"], d["side"])
            I = _cracklip.interaction_integral(tip, e1, mat.E, mat.nu, d["x"], d["weight"],
                                               d["grad_q"], grad, d["side"],
                                               int(g.tip_orientation[j]))
            I = np.asarray(I)
            if self.contact:
                I = I + np.asarray(self._lip_term(crack, j, radius))
            K = 0.5 * mat.E_star * I
            out.append({"tip": tip.tolist(), "direction": e1.tolist(), "K_I": float(K[0]),
                        "K_II": float(K[1]), "radius": float(radius)})
        return out

    def _lip_term(self, crack: int, tip: int, radius: float):
        m = self.model
        g = m.geometries[crack]
        cs = self.contact["system"]
        lam_full = cs.R @ self.contact["lambda"]
        return _cracklip.lip_interaction_integral(
            m.x, m.cells, m.geometries, cs.space, lam_full, g.tips[tip], g.tip_tangents[tip],
            int(g.tip_orientation[tip]), crack, radius, m.scene.material.E, m.scene.material.nu,
            max(m.scene.options.contact_points, 8))

    def contact_pressure(self, crack: int = 0) -> dict[str, np.ndarray]:
        """Contact pressure p = -lambda (>= 0 in compression) and normal gap
        [[u]].n at the quadrature points of the crack segments, sorted along
        the crack: x (n, 2), s (n,), pressure (n,), gap (n,), weight (n,) (the
        quadrature weights, for integrals along the crack)."""
        if not self.contact:
            raise InputError("this solution has no contact (Options.contact is 'none')")
        m = self.model
        cs = self.contact["system"]
        sp_ = _cracklip.compute_segment_points(m.x, m.cells, m.geometries, cs.space, 3)
        lam_full = cs.R @ self.contact["lambda"]
        p = np.zeros(len(sp_["weight"]))
        np.add.at(p, sp_["entry_point"], -sp_["entry_value"] * lam_full[sp_["entry_mult"]])
        keep = cs.space.segment_crack[sp_["segment"]] == crack
        up = self._evaluate(sp_["cell"], sp_["ref"], np.ones(len(p), dtype=np.int8))
        um = self._evaluate(sp_["cell"], sp_["ref"], -np.ones(len(p), dtype=np.int8))
        gap = np.einsum("ij,ij->i", up - um, sp_["normal"])
        s = self._along_crack(crack, sp_["x"])
        order = np.argsort(s[keep], kind="stable")
        return {"x": sp_["x"][keep][order], "s": s[keep][order], "pressure": p[keep][order],
                "gap": gap[keep][order], "weight": sp_["weight"][keep][order]}

    @property
    def standard_displacement(self) -> np.ndarray:
        """(num_nodes, 2) standard dofs = displacement at the nodes (shifted enrichment)."""
        n = self.model.layout.num_std_nodes
        return self.u[: 2 * n].reshape(n, 2)


def strain(grad: np.ndarray) -> np.ndarray:
    """Symmetric part of gradients (n, 2, 2)."""
    return 0.5 * (grad + np.swapaxes(grad, 1, 2))


def stress(eps: np.ndarray, material) -> np.ndarray:
    """Plane-strain stress (n, 2, 2) of strains (n, 2, 2)."""
    lmbda = material.E * material.nu / ((1 + material.nu) * (1 - 2 * material.nu))
    tr = eps[:, 0, 0] + eps[:, 1, 1]
    return 2 * material.mu * eps + lmbda * tr[:, None, None] * np.eye(2)[None]


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
