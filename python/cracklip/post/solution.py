"""Post-processing of a solved X-FEM model: point values, crack opening, sub-cell fields."""
from __future__ import annotations

import dataclasses
import typing

import numpy as np

import dolfinx.geometry

from .. import _cracklip
from ..errors import InputError
from ..fracture.sif import compute_sifs
from ..model.checks import ModelWarning
from ..model.model import XfemModel
from ..scene.material import strain, stress
from ..scene.stress_field import evaluate_stress, tensor_to_voigt


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
        factors: on a load path, the factor of every load group at this
            state (None: every group at 1).
        step: on a load path, the step this state ends (index, name,
            factors, increments); steps: on the last one, every step's
            Solution in order.
        path: on a load path, every step's Solution (on each of them).
        error_estimate: the discretisation-error estimate of its K, when
            one was made (cracklip.analysis.accuracy): levels, dofs, K per
            level and the estimate per tip.
    """
    model: XfemModel
    u: np.ndarray
    timings: dict[str, float]
    condition: dict[str, float] = dataclasses.field(default_factory=dict)
    contact: dict[str, typing.Any] = dataclasses.field(default_factory=dict)
    solver: dict[str, typing.Any] = dataclasses.field(default_factory=dict)
    factors: typing.Optional[dict] = None
    step: typing.Optional[dict] = None
    steps: typing.Optional[list] = dataclasses.field(default=None, repr=False)
    path: typing.Optional[list] = dataclasses.field(default=None, repr=False, compare=False)
    error_estimate: typing.Optional[dict] = dataclasses.field(default=None, repr=False, compare=False)
    _sif_cache: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)

    def factor(self, group: str) -> float:
        """The factor of a load group at this state (1 without a load path)."""
        return 1.0 if self.factors is None else float(self.factors.get(group, 0.0))

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
    def lip_samples(self, crack: int = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Points along a crack (points_per_segment Gauss points on its segment
        in every cell it crosses, tau^2-graded toward a tip), sorted by s:

        s (n,) arc length from the crack's first point, x (n, 2), weight (n,)
        (the length each point stands for), normal (n, 2) into the + side,
        u_plus, u_minus (n, 2) the displacement of each lip, jump (n, 2) =
        u_plus - u_minus, gap (n,) = [[u]].n (> 0 open), slip (n,) = [[u]].t
        (t = n turned by -90 degrees), pressure (n,) the contact pressure
        (>= 0 in compression; 0 without contact), cell (n,), ref (n, 2).
        Without tip enrichment the tip cell holds no crack (the discrete
        crack ends at its edge) and is left out.
        """
        m = self.model
        if not 0 <= crack < len(m.cracks):
            raise InputError(f"crack index {crack} out of range: the scene has {len(m.cracks)} cracks")
        g = m.geometries[crack]
        pts = _cracklip.compute_crack_points(m.x, m.cells, g, int(points_per_segment))
        if m.scene.options.enrichment == "none":
            keep = ~np.isin(pts["cell"], np.asarray(g.tip_cells["cell"]))
            pts = {k: v[keep] for k, v in pts.items()}
        cells, ref, normal = pts["cell"], pts["ref"], pts["normal"]
        pressure, shear = np.zeros(len(cells)), np.zeros(len(cells))
        if self.contact:
            cs = self.contact["system"]
            pressure = -_cracklip.evaluate_multipliers(cs.space, crack, cells, ref, cs.R @ self.contact["lambda"])
            if "lambda_t" in self.contact:
                shear = -_cracklip.evaluate_multipliers(cs.space, crack, cells, ref, cs.R @ self.contact["lambda_t"])
        up = self._evaluate(cells, ref, np.ones(len(cells), dtype=np.int8))
        um = self._evaluate(cells, ref, -np.ones(len(cells), dtype=np.int8))
        jump = up - um
        tangent = np.stack([normal[:, 1], -normal[:, 0]], axis=1)
        s = arc_length(m.cracks[crack].crack.points, pts["x"]) if len(cells) else np.zeros(0)
        o = np.argsort(s, kind="stable")
        return {"s": s[o], "x": pts["x"][o], "weight": pts["weight"][o], "normal": normal[o],
                "u_plus": up[o], "u_minus": um[o], "jump": jump[o],
                "gap": np.einsum("ij,ij->i", jump, normal)[o], "slip": np.einsum("ij,ij->i", jump, tangent)[o],
                "pressure": pressure[o], "shear": shear[o], "state": self._lip_states(pressure, shear)[o],
                "cell": cells[o], "ref": ref[o]}

    def _lip_states(self, pressure: np.ndarray, shear: np.ndarray) -> np.ndarray:
        """Per point "open", "stick" or "slip" from the lip tractions: open
        where a unilateral contact carries no pressure (or without contact),
        stick where |shear| < mu p (1 - 1e-6), slip where the shear is at the
        bound (or closed without friction: the lips slide freely)."""
        out = np.full(len(pressure), "open", dtype=object)
        if not self.contact:
            return out
        opts = self.model.scene.options
        scale = max(float(np.abs(pressure).max(initial=0.0)), 1e-300)
        closed = np.ones(len(pressure), dtype=bool) if opts.contact == "bilateral" else pressure > 1e-9 * scale
        stick = closed & (np.abs(shear) < opts.friction * pressure * (1.0 - 1e-6))
        out[closed] = "slip"
        out[stick] = "stick"
        return out

    def crack_opening(self, crack: int = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Jump [[u]] = u(+) - u(-) along a crack (see lip_samples): x (n, 2),
        s (n,) arc length, jump (n, 2), normal (n,) = [[u]].n (n the + side
        normal, positive = opening), tangential (n,) = [[u]].t."""
        smp = self.lip_samples(crack, points_per_segment)
        return {"x": smp["x"], "s": smp["s"], "jump": smp["jump"], "normal": smp["gap"],
                "tangential": smp["slip"]}

    # -- whole-field quantities --------------------------------------------
    def subcell_fields(self) -> dict[str, typing.Any]:
        """Displacement and stress (xx, yy, xy at each sub-triangle's centroid;
        the total stress C eps(u) + sigma_0 with an initial stress) on the
        sub-cell mesh (see cracklip.io.paraview.write_vtu)."""
        m = self.model
        mat = m.scene.material
        f = _cracklip.compute_subcell_fields(m.x, m.cells, m.layout, m.geometries, self.u,
                                             mat.E_strain, mat.nu_strain)
        if m.scene.initial_stress is not None and self.factor(m.scene.initial_stress_group) != 0.0:
            centroids = f["points"].reshape(-1, 3, 2).mean(axis=1)
            f["stress"] = f["stress"] + self.factor(m.scene.initial_stress_group) * tensor_to_voigt(
                evaluate_stress(m.scene.initial_stress, centroids, "initial stress"))
        return f

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

    def enriched_field_points(self) -> dict[str, np.ndarray] | None:
        """field_points() on the enriched cells, computed once (the strain
        energy and results.json's quadrature counts both need them; None
        without enriched cells)."""
        if not hasattr(self, "_enriched_points"):
            enriched = np.asarray(self.model.layout.cells, dtype=np.int32)
            self._enriched_points = self.field_points(enriched) if enriched.size else None
        return self._enriched_points

    def _quadrature(self, degree: int | None):
        q = self.model.scene.options.quadrature_options()
        if degree is not None:
            q.degree = max(q.degree, int(degree))
        return q

    def strain_energy(self) -> float:
        """1/2 int sigma : eps over the domain (the stiffness quadrature; the
        enriched cells' points are enriched_field_points(), shared with
        results.json's quadrature counts)."""
        m = self.model
        plain = np.ones(m.cells.shape[0], dtype=bool)
        plain[np.asarray(m.layout.cells, dtype=np.int32)] = False
        parts = [self.enriched_field_points()]
        if plain.any():
            parts.append(self.field_points(np.flatnonzero(plain)))
        energy = 0.0
        for f in parts:
            if f is not None:
                eps = strain(f["grad_u"])
                energy += float(0.5 * np.sum(f["weight"] * np.einsum("nij,nij->n", stress(eps, m.scene.material),
                                                                     eps)))
        return energy

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

    def stress_intensity_factors(self, crack: int | None = 0, radius: float | None = None,
                                 ring: tuple[float, float] | None = None) -> list[dict[str, typing.Any]]:
        """K_I, K_II at every tip of a crack (crack=None: of every crack) by the
        domain interaction integral on three domains per tip (see cracklip.fracture.sif):
        one dict per tip with the keys of results.json's "sifs" (crack,
        crack_name, tip, x, y, direction, K_I, K_II, K_I_spread, K_II_spread,
        mode_mix_deg, G, radius, radii, element_size, limited_by, domain_clear).

        radius: the largest domain's radius (default Options.sif_radius, 0:
        6 element sizes at the tip); clipped to keep the domain inside the
        part and clear of other tips, cracks, kinks and holes.
        ring: (r_in, r_out), K on that one ring as another code defines it
        (q = 1 within r_in, 0 beyond r_out, linear between; r_in = r_out:
        the plateau of that radius), NOT clipped (default Options.sif_ring);
        a ring that reaches an obstacle is warned about, domain_clear false.
        """
        key = (crack, radius, None if ring is None else tuple(float(v) for v in ring))
        if key not in self._sif_cache:
            cracks = None if crack is None else [crack]
            if crack is not None and not 0 <= crack < len(self.model.cracks):
                raise InputError(f"crack index {crack} out of range: the scene has {len(self.model.cracks)} cracks")
            self._sif_cache[key] = compute_sifs(self, radius, cracks, ring)
        rows = [dict(r) for r in self._sif_cache[key][0]]
        est = self.error_estimate
        for r in rows:
            tip = est["tips"].get(f"{r['crack']}:{r['tip']}") if est and radius is None and ring is None else None
            for mode in ("K_I", "K_II"):
                r[f"{mode}_error"] = None if tip is None else tip[f"{mode}_error"]
                r[f"{mode}_extrapolated"] = None if tip is None else tip[f"{mode}_extrapolated"]
                r[f"{mode}_levels"] = None if tip is None else list(tip[f"{mode}_levels"])
        return rows

    def reactions(self) -> dict[str, typing.Any]:
        """Reaction forces per Dirichlet condition and point support, their
        sum and the applied load (cracklip.post.reactions.compute_reactions;
        computed once)."""
        if not hasattr(self, "_reactions"):
            from .reactions import compute_reactions
            self._reactions = compute_reactions(self)
        return self._reactions

    @property
    def warnings(self) -> list:
        """The model checks' warnings, those of the SIFs at every tip (domains
        clipped, K varying with the domain) and of the solved field
        (cracklip.post.checks: lips passing through each other without
        contact, no load, point supports carrying unbalanced loads, K's
        estimated discretisation error): model.checks.ModelWarning."""
        from .checks import point_supports, solution_warnings
        self.stress_intensity_factors(None)
        model_messages = {w.message for w in self.model.warnings}
        extra = [ModelWarning("sif_spread", m) for m in self._sif_cache[(None, None, None)][1]
                 if m not in model_messages]
        extra += [ModelWarning(code, m) for code, m in solution_warnings(self)]
        if self.model.scene.dirichlet and np.any(self.u):
            extra += [ModelWarning(code, m) for code, m in point_supports(self, self.reactions())]
        return list(self.model.warnings) + extra

    def contact_pressure(self, crack: int = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Contact pressure p = -lambda (>= 0 in compression) and normal gap
        [[u]].n at points along the crack (see lip_samples), sorted along
        it: x (n, 2), s (n,), pressure (n,), gap (n,), weight (n,) (for
        integrals along the crack), shear (n,) the friction traction on the
        + lip along the crack's direction t (0 without friction), slip (n,)
        = [[u]].t accumulated over the load path, state (n,) "open",
        "stick" or "slip"."""
        if not self.contact:
            raise InputError("this solution has no contact (Options.contact is 'none')")
        smp = self.lip_samples(crack, points_per_segment)
        return {k: smp[k] for k in ("x", "s", "pressure", "gap", "weight", "shear", "slip", "state")}

    @property
    def standard_displacement(self) -> np.ndarray:
        """(num_nodes, 2) standard dofs = displacement at the nodes (shifted enrichment)."""
        n = self.model.layout.num_std_nodes
        return self.u[: 2 * n].reshape(n, 2)


def _tree(model: XfemModel):
    tree = getattr(model, "_bb_tree", None)
    if tree is None:
        msh = model.scene.mesh.mesh
        tree = dolfinx.geometry.BoundingBoxTree(msh, msh.topology.dim)
        model._bb_tree = tree
    return tree


def arc_length(points: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Arc length along a polyline (k, 2), from its first point, of the
    projections of points x (n, 2) onto it."""
    d = np.diff(points, axis=0)
    L = np.linalg.norm(d, axis=1)
    cum = np.concatenate([[0.0], np.cumsum(L)])
    rel = x[:, None, :] - points[None, :-1, :]
    t = np.clip(np.einsum("nki,ki->nk", rel, d) / (L ** 2)[None], 0.0, 1.0)
    dist = np.linalg.norm(rel - t[..., None] * d[None], axis=2)
    k = np.argmin(dist, axis=1)
    return cum[k] + t[np.arange(len(x)), k] * L[k]
