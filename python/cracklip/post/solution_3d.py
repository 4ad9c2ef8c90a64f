"""Post-processing of a solved tetrahedral model: point values, the crack's
lips and opening, quadrature-point fields, energies.

Solution3D is Solution (solution.py) where the geometry differs: points are
(n, 3), the crack is a surface sampled by its lip facets, the fields come
from the C++ kernels on tetrahedra (evaluate_displacement_3d, the enriched
cells' quadrature). Cells the crack does not touch are P1 cells: their
gradients are computed here in numpy, a chunk of cells at a time.
"""
from __future__ import annotations

import typing

import numpy as np

import dolfinx.geometry

from .. import _cracklip
from ..errors import InputError
from ..fracture.sif_3d import compute_front_sifs
from ..model.checks import ModelWarning
from ..scene.material import strain, stress
from .solution import Solution, _tree

#: Cells per chunk of the whole-mesh field loops (bounded memory at 1e6 cells).
CHUNK = 200_000


class Solution3D(Solution):
    """A solved tetrahedral model (see Solution for the attributes)."""

    # -- point values -------------------------------------------------------
    def locate(self, points: np.ndarray, prefer_crossed: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """Cell and reference coordinates of each point (n, 3); a point on a
        cell boundary goes to a cell a crack crosses if there is one."""
        pts = np.ascontiguousarray(np.asarray(points, dtype=float).reshape(-1, 3))
        msh = self.model.scene.mesh.mesh
        cand = dolfinx.geometry.compute_collisions(_tree(self.model), pts)
        coll = dolfinx.geometry.compute_colliding_cells(msh, cand, pts)
        crossed = np.zeros(self.model.cells.shape[0], dtype=bool)
        for g in self.model.geometries:
            crossed[np.isin(g.cell_class, (1, 2, 3))] = True
        cells = np.empty(len(pts), dtype=np.int32)
        for i in range(len(pts)):
            links = coll.links(i)
            if len(links) == 0:
                raise InputError(f"point {pts[i].tolist()} is outside the mesh")
            hit = links[crossed[links]] if prefer_crossed else links[:0]
            cells[i] = hit[0] if len(hit) else links[0]
        xv = self.model.x[self.model.cells[cells]]
        J = np.stack([xv[:, 1] - xv[:, 0], xv[:, 2] - xv[:, 0], xv[:, 3] - xv[:, 0]], axis=2)
        ref = np.linalg.solve(J, (pts - xv[:, 0])[:, :, None])[:, :, 0]
        return cells, np.clip(ref, 0.0, 1.0)

    def _evaluate(self, cells, ref, sides, gradient: bool = False):
        m = self.model
        u, grad = _cracklip.evaluate_displacement_3d(m.x, m.cells, m.layout, m.geometries, self.u,
                                                     np.asarray(cells, dtype=np.int32),
                                                     np.ascontiguousarray(ref, dtype=float),
                                                     np.asarray(sides, dtype=np.int8))
        return (u, grad) if gradient else u

    # -- on the crack -------------------------------------------------------
    def lip_samples(self, crack: int = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Points on a crack's lip facets (points_per_segment per direction:
        Gauss away from the front, collapsed on facets touching it), facet
        by facet: x (n, 3), weight (n,) (area measure; a point-collapsed
        facet may give negative weights), normal (n, 3) into the + side,
        u_plus, u_minus (n, 3), jump (n, 3) = u_plus - u_minus, gap (n,) =
        [[u]].n (> 0 open), slip (n, 3) the tangential part of the jump,
        pressure (n,) (0: no contact in 3D), cell (n,), ref (n, 3),
        front_vertices (n,)."""
        m = self.model
        if not 0 <= crack < len(m.cracks):
            raise InputError(f"crack index {crack} out of range: the scene has {len(m.cracks)} cracks")
        lp = _cracklip.compute_lip_points_3d(m.x, m.cells, m.geometries[crack], int(points_per_segment), 0.0)
        n = len(lp["weight"])
        up = self._evaluate(lp["cell"], lp["ref"], np.ones(n, dtype=np.int8))
        um = self._evaluate(lp["cell"], lp["ref"], -np.ones(n, dtype=np.int8))
        jump = up - um
        gap = np.einsum("ij,ij->i", jump, lp["normal"])
        return {"x": lp["x"], "weight": lp["weight"], "normal": lp["normal"], "u_plus": up, "u_minus": um,
                "jump": jump, "gap": gap, "slip": jump - gap[:, None] * lp["normal"], "pressure": np.zeros(n),
                "cell": lp["cell"], "ref": lp["ref"], "front_vertices": lp["front_vertices"]}

    def crack_opening(self, crack: int = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Jump [[u]] over a crack surface (see lip_samples): x (n, 3),
        weight (n,), jump (n, 3), normal (n,) = [[u]].n (positive = opening),
        tangential (n,) = |tangential part of [[u]]|."""
        smp = self.lip_samples(crack, points_per_segment)
        return {"x": smp["x"], "weight": smp["weight"], "jump": smp["jump"], "normal": smp["gap"],
                "tangential": np.linalg.norm(smp["slip"], axis=1)}

    def opening_volume(self, crack: int = 0) -> float:
        """int [[u]].n dA over a crack's lips: the volume the crack opens."""
        smp = self.lip_samples(crack)
        return float(np.sum(smp["weight"] * smp["gap"]))

    def subcell_fields(self) -> dict[str, typing.Any]:
        """The sub-tetrahedral mesh with displacement and stress
        (post.subcells_3d.subcell_fields_3d)."""
        from .subcells_3d import subcell_fields_3d
        return subcell_fields_3d(self)

    # -- whole-field quantities --------------------------------------------
    def field_points(self, cells: np.ndarray | None = None, degree: int | None = None
                     ) -> dict[str, np.ndarray]:
        """Quadrature points on `cells` (all by default) with grad u there:
        cell, x (n, 3), weight, side (the crossing crack's lip side in cells
        it crosses, else 0), grad_u (n, 3, 3). Enriched cells get the
        stiffness's rules (sub-tetrahedra, collapsed at the front); the
        others a Gauss rule of `degree` (default 1: their P1 gradient is
        constant)."""
        m = self.model
        cell_list = (np.arange(m.cells.shape[0], dtype=np.int32) if cells is None
                     else np.asarray(cells, dtype=np.int32))
        enriched = np.zeros(m.cells.shape[0], dtype=bool)
        enriched[np.asarray(m.layout.cells, dtype=np.int32)] = True
        parts = []
        ec = cell_list[enriched[cell_list]]
        if ec.size:
            q = _cracklip.compute_enriched_cell_quadrature_3d(m.x, m.cells, m.layout, m.geometries, ec,
                                                              self._quadrature(degree))
            _, grad = self._evaluate(q["cell"], q["ref"], q["side"], gradient=True)
            parts.append({"cell": q["cell"], "x": self._physical(q["cell"], q["ref"]), "weight": q["weight"],
                          "side": q["side"], "grad_u": grad})
        pc = cell_list[~enriched[cell_list]]
        if pc.size:
            parts.append(self._plain_points(pc, 1 if degree is None else int(degree)))
        if not parts:
            return {"cell": np.zeros(0, np.int32), "x": np.zeros((0, 3)), "weight": np.zeros(0),
                    "side": np.zeros(0, np.int8), "grad_u": np.zeros((0, 3, 3))}
        return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}

    def _physical(self, cells: np.ndarray, ref: np.ndarray) -> np.ndarray:
        xv = self.model.x[self.model.cells[cells]]
        N = np.column_stack([1.0 - ref.sum(axis=1), ref])
        return np.einsum("na,nai->ni", N, xv)

    def _plain_points(self, cells: np.ndarray, degree: int) -> dict[str, np.ndarray]:
        """Gauss points of P1 cells no crack function reaches: their gradient
        is the standard dofs' (constant per cell)."""
        m = self.model
        rule = _cracklip.tetrahedron_rule(max(degree, 1))
        ref, w = rule["points"], rule["weights"]
        nq = len(w)
        us = self.standard_displacement
        xv = m.x[m.cells[cells]]                               # (c, 4, 3)
        J = np.transpose(xv[:, 1:] - xv[:, :1], (0, 2, 1))     # J[:, i, a] = d x_i / d ref_a
        detJ = np.linalg.det(J)
        dN = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
        G = np.einsum("ab,cbi->cai", dN, np.linalg.inv(J))    # (c, 4, 3) grad N_a
        grad = np.einsum("cai,caj->cij", us[m.cells[cells]], G)
        N = np.column_stack([1.0 - ref.sum(axis=1), ref])      # (q, 4)
        x = np.einsum("qa,cai->cqi", N, xv).reshape(-1, 3)
        return {"cell": np.repeat(cells, nq).astype(np.int32), "x": x,
                "weight": (np.abs(detJ)[:, None] * w[None, :]).ravel(),
                "side": np.zeros(len(cells) * nq, dtype=np.int8), "grad_u": np.repeat(grad, nq, axis=0)}

    def _quadrature(self, degree: int | None):
        q = self.model.scene.options.quadrature_options_3d()
        if degree is not None:
            q.degree = max(q.degree, int(degree))
        return q

    def _chunks(self):
        n = self.model.cells.shape[0]
        return np.array_split(np.arange(n, dtype=np.int32), max(1, -(-n // CHUNK)))

    def strain_energy(self) -> float:
        """1/2 int sigma : eps over the part (the stiffness's quadrature)."""
        mat = self.model.scene.material
        energy = 0.0
        for chunk in self._chunks():
            f = self.field_points(chunk)
            eps = strain(f["grad_u"])
            energy += float(0.5 * np.sum(f["weight"] * np.einsum("nij,nij->n", stress(eps, mat), eps)))
        return energy

    def energy_error(self, exact_gradient: typing.Callable[[np.ndarray, np.ndarray], np.ndarray],
                     degree: int = 4) -> tuple[float, float]:
        """Energy norm of u - u_exact, absolute and relative to the exact
        field's: exact_gradient(x (n, 3), side (n,)) returns grad u_exact
        (n, 3, 3); side is +1 / -1 in cells a crack crosses (0 elsewhere).
        degree: Gauss degree in cells away from the crack's functions."""
        mat = self.model.scene.material
        err2 = ref2 = 0.0
        for chunk in self._chunks():
            f = self.field_points(chunk, degree=degree)
            g_ex = np.asarray(exact_gradient(f["x"], f["side"]), dtype=float)
            e, eex = strain(f["grad_u"] - g_ex), strain(g_ex)
            err2 += float(np.sum(f["weight"] * np.einsum("nij,nij->n", stress(e, mat), e)))
            ref2 += float(np.sum(f["weight"] * np.einsum("nij,nij->n", stress(eex, mat), eex)))
        return float(np.sqrt(err2)), float(np.sqrt(err2 / ref2))

    def stress_intensity_factors(self, crack: int | None = 0, radius: float | None = None
                                 ) -> list[dict[str, typing.Any]]:
        """K_I, K_II, K_III at the front points of a crack (crack=None: of every
        crack) by the domain interaction integral on three domains per point
        (cracklip.fracture.sif_3d): one dict per front point with crack,
        crack_name, point, piece, s (arc length), x, y, z, parametric_angle
        (elliptical cracks), K_I, K_II, K_III and their spreads, G,
        mode_mix_deg, radius, radii, element_size, hat, curvature, limited_by,
        free_surface, domain_clear, direction (e1), normal (e2).

        radius: the largest domain's radius (default Options.sif_radius, 0:
        DEFAULT_ELEMENTS element sizes at each point); clipped to keep the
        domain inside the part, clear of other cracks and within the front's
        curvature.
        """
        key = (crack, radius)
        cache = self.__dict__.setdefault("_sif3d", {})
        if key not in cache:
            if crack is not None and not 0 <= crack < len(self.model.cracks):
                raise InputError(f"crack index {crack} out of range: the scene has {len(self.model.cracks)} cracks")
            cache[key] = compute_front_sifs(self, radius, None if crack is None else [crack])
        return [dict(r) for r in cache[key][0]]

    @property
    def warnings(self) -> list:
        """The model checks' warnings and those of the SIFs along every front
        (domains clipped, K varying with the domain): model.checks.ModelWarning."""
        self.stress_intensity_factors(None)
        model_messages = {w.message for w in self.model.warnings}
        extra = [ModelWarning("sif_spread", msg) for msg in self._sif3d[(None, None)][1] if msg not in model_messages]
        return list(self.model.warnings) + extra

    @property
    def standard_displacement(self) -> np.ndarray:
        """(num_nodes, 3) standard dofs = displacement at the nodes."""
        n = self.model.layout.num_std_nodes
        return self.u[: 3 * n].reshape(n, 3)


def create_solution(model, u: np.ndarray, timings: dict, *args, **kwargs) -> Solution:
    """The Solution of a model: Solution3D on tetrahedra, Solution on triangles."""
    cls = Solution3D if model.gdim == 3 else Solution
    return cls(model, u, timings, *args, **kwargs)


__all__ = ["Solution3D", "create_solution"]
