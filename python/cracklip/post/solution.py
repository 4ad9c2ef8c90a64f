"""Post-processing of a solved X-FEM model, planar or solid: point values,
the crack's lips and opening, quadrature-point and sub-cell fields,
energies, stress intensity factors.

One ``Solution`` for both dimensions: what differs (the cells' kernels, the
lip points of a curve or a surface, the sub-cell mesh) comes from the
model's crack type (cracklip.model.cracks), the SIFs from the tips
(cracklip.fracture.sif) or the fronts (cracklip.fracture.sif_3d) in one row
schema.
"""
from __future__ import annotations

import dataclasses
import math
import typing

import numpy as np

import dolfinx.geometry

from ..contact.friction import STICK
from ..contact.tractions import contact_tractions, multiplier_values
from ..errors import InputError, checked_keywords
from ..fracture.sif import compute_sifs, complete_rows
from ..fracture.sif_3d import compute_front_sifs
from ..model.checks import ModelWarning
from ..model.model import XfemModel
from ..scene.material import strain, stress
from ..scene.mesh_estimate import release_memory
from ..scene.processes import reduced

#: Cells per chunk of the whole-mesh field loops (bounded memory at 1e6 cells).
CHUNK = 200_000

#: Gauss degree of the energy error in cells without crack functions: 6 on
#: triangles, 4 on tetrahedra (a degree-6 tetrahedron rule has several times
#: the points).
ERROR_DEGREE = {2: 6, 3: 4}


def point_label(row: dict) -> int | str:
    """A SIF row's point within its crack for the error estimate's table:
    its index, or for a position asked for between front points (no index)
    its arc length ("s=...")."""
    return int(row["point"]) if row.get("point") is not None else f"s={float(row['s']):.12g}"


def crack_index(model, crack) -> int:
    """The index of a crack of the model given by its index (an int) or its name (Crack.name,
    results.json's crack_name); anything else, or an index out of range, is an InputError that
    lists the cracks."""
    names = [getattr(c, "name", "") for c in model.scene.cracks]
    listing = ", ".join(f"{k} {n!r}" for k, n in enumerate(names))
    if isinstance(crack, str):
        if crack not in names:
            raise InputError(f"no crack named {crack!r}: the scene's cracks are {listing}")
        return names.index(crack)
    if isinstance(crack, bool) or not isinstance(crack, (int, np.integer)):
        raise InputError(f"crack must be a crack's index (an int) or its name, got {crack!r} "
                         f"({type(crack).__name__}); the scene's cracks are {listing}")
    if not 0 <= crack < len(names):
        raise InputError(f"crack index {crack} out of range: the scene has {len(names)} cracks ({listing})")
    return int(crack)


@dataclasses.dataclass(repr=False)
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
            one was made (cracklip.analysis.accuracy): the similar meshes'
            size factors, dofs and seconds, the largest error, and per tip
            or front point ("points", "crack:point") the estimate and K on
            each mesh.
        combination: [(weight, Solution), ...] of the same model when u is
            their weighted sum (a load state from unit load groups, linear):
            K along 3D fronts is then the weighted sum of the parts' (their
            domain integrals reused, fracture.sif_3d.crack_front_sifs).
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
    combination: typing.Optional[list] = dataclasses.field(default=None, repr=False, compare=False)
    _sif_cache: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)
    _front_sifs: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)

    def factor(self, group: str) -> float:
        """The factor of a load group at this state (1 without a load path)."""
        return 1.0 if self.factors is None else float(self.factors.get(group, 0.0))

    # -- point values -------------------------------------------------------
    def locate(self, points: np.ndarray, prefer_crossed: bool = True,
               owned: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """Cell and reference coordinates of each point (n, d).

        A point on a cell boundary goes to a cell crossed by a crack if there
        is one (so that both lips can be evaluated there). owned: among this
        process's owned cells only (under mpirun), -1 where none holds it.
        """
        m = self.model
        d = m.gdim
        pts = np.asarray(points, dtype=float).reshape(-1, d)
        msh = m.scene.mesh.mesh
        p3 = np.zeros((len(pts), 3))
        p3[:, :d] = pts
        cand = dolfinx.geometry.compute_collisions(_tree(m), p3)
        coll = dolfinx.geometry.compute_colliding_cells(msh, cand, p3)
        crossed = np.zeros(m.cells.shape[0], dtype=bool)
        for cm in m.cracks:
            crossed |= cm.crossed()
        cells = np.empty(len(pts), dtype=np.int32)
        for i in range(len(pts)):
            links = coll.links(i)
            if owned:
                links = links[m.owned_cells_only(links)]
                if len(links) == 0:
                    cells[i] = -1
                    continue
            if len(links) == 0:
                raise InputError(f"point {pts[i].tolist()} is outside the mesh")
            hit = links[crossed[links]] if prefer_crossed else links[:0]
            cells[i] = hit[0] if len(hit) else links[0]
        xv = m.x[m.cells[np.maximum(cells, 0)]]
        J = np.stack([xv[:, k] - xv[:, 0] for k in range(1, d + 1)], axis=2)
        ref = np.linalg.solve(J, (pts - xv[:, 0])[:, :, None])[:, :, 0]
        return cells, np.clip(ref, 0.0, 1.0)

    def gradient_anywhere(self, points: np.ndarray) -> np.ndarray:
        """displacement_gradient at points anywhere in the part; collective
        under mpirun: each point evaluated by the lowest process owning a
        cell that holds it, the values on every process."""
        m = self.model
        if not m.distributed:
            return self.displacement_gradient(points)
        comm = m.V.mesh.comm
        pts = np.asarray(points, dtype=float).reshape(-1, m.gdim)
        cells, ref = self.locate(pts, owned=True)
        holder = reduced(np.where(cells >= 0, comm.rank, comm.size).astype(np.int64), "MIN", comm)
        if np.any(holder == comm.size):
            raise InputError(f"point {pts[holder == comm.size][0].tolist()} is outside the mesh")
        out = np.zeros((len(pts), m.gdim, m.gdim))
        mine = holder == comm.rank
        if mine.any():
            out[mine] = self._evaluate(cells[mine], ref[mine], np.zeros(int(mine.sum()), dtype=np.int8),
                                       gradient=True)[1]
        return reduced(out, "SUM", comm)

    @checked_keywords
    def displacement(self, points: np.ndarray, side: int = 0) -> np.ndarray:
        """Displacement (n, d) at points; side +1 / -1 picks a lip of a crack
        crossing the point's cell, 0 the side the point lies on."""
        cells, ref = self.locate(points)
        sides = np.full(len(cells), side, dtype=np.int8)
        return self._evaluate(cells, ref, sides)

    def displacement_gradient(self, points: np.ndarray, side: int = 0) -> np.ndarray:
        """Displacement gradient (n, d, d), [p, i, j] = d u_i / d x_j, at points."""
        cells, ref = self.locate(points)
        sides = np.full(len(cells), side, dtype=np.int8)
        return self._evaluate(cells, ref, sides, gradient=True)[1]

    def _physical(self, cells: np.ndarray, ref: np.ndarray) -> np.ndarray:
        """Physical points (n, d) of reference points (cell (n,), ref (n, d))."""
        N = np.column_stack([1.0 - ref.sum(axis=1), ref])
        return np.einsum("na,nai->ni", N, self.model.x[self.model.cells[cells]])

    def _evaluate(self, cells, ref, sides, gradient: bool = False):
        u, grad = self.model.crack_type.evaluate(self.model, self.u, cells, ref, sides)
        return (u, grad) if gradient else u

    # -- on the crack -------------------------------------------------------
    @checked_keywords
    def lip_samples(self, crack: int | str = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Points on a crack's lips (points_per_segment Gauss points per crack
        segment, tau^2-graded toward a tip, in 2D; per direction of each lip
        facet, collapsed at the front, in 3D) with what the lips do there:

        crack: its index in Scene.cracks or its name (Crack.name), here and
        in crack_opening, opening_volume, contact_pressure.

        x (n, d), weight (n,) (the length or area each point stands for; a
        point-collapsed facet may give negative weights), normal (n, d) into
        the + side, u_plus, u_minus (n, d) the displacement of each lip,
        jump (n, d) = u_plus - u_minus, gap (n,) = [[u]].n (> 0 open), slip
        the tangential part of the jump (2D: (n,) [[u]].t, t = n turned by
        -90 degrees; 3D: (n, 3)), pressure (n,) the contact pressure (>= 0
        in compression; 0 without contact), shear the friction traction on
        the + lip (2D: (n,) along t; 3D: (n, 3), in the crack's plane),
        state (n,) "open", "stick" or "slip", cell (n,), ref (n,
        d); in 2D sorted by s (n,) the arc length from the crack's first
        point (without tip enrichment the tip cell holds no crack and is
        left out), in 3D facet by facet with front_vertices (n,). Under MPI
        (a distributed model) every process gets every process's samples
        (those of its owned cells), cell -1.
        """
        m = self.model
        crack = crack_index(m, crack)
        cm = m.cracks[crack]
        pts = cm.lip_samples(m, int(points_per_segment))
        if m.distributed:  # the points of this process's owned cells (each cell's once over the processes)
            keep = m.owned_cells_only(pts["cell"])
            pts = {k: v[keep] for k, v in pts.items()}
        cells, ref, normal = pts["cell"], pts["ref"], pts["normal"]
        up = self._evaluate(cells, ref, np.ones(len(cells), dtype=np.int8))
        um = self._evaluate(cells, ref, -np.ones(len(cells), dtype=np.int8))
        jump = up - um
        out = {"x": pts["x"], "weight": pts["weight"], "normal": normal, "u_plus": up, "u_minus": um, "jump": jump,
               "gap": np.einsum("ij,ij->i", jump, normal), "slip": cm.slip(jump, normal),
               **self.lip_contact(crack, cells, ref, normal), "cell": cells, "ref": ref}
        out.update({k: pts[k] for k in ("s", "front_vertices") if k in pts})
        if m.distributed:
            out = _gathered_samples(out, m.V.mesh.comm)
        return out

    def lip_contact(self, crack: int, cells: np.ndarray, ref: np.ndarray, normal: np.ndarray
                    ) -> dict[str, np.ndarray]:
        """The contact at points (cell (n,), ref (n, d)) of a crack with unit
        normals (n, d) into its + side: pressure (n,) (>= 0 in compression;
        0 without contact), shear the friction traction on the + lip (2D:
        (n,) along t; 3D: (n, 3), in the crack's plane; 0 without
        friction), state (n,) "open", "stick" or "slip"
        (cracklip.contact.tractions)."""
        m = self.model
        n = len(cells)
        pressure = np.zeros(n)
        shear = np.zeros(n) if m.gdim == 2 else np.zeros((n, m.gdim))
        if self.contact:
            ct = contact_tractions(m, self.contact, crack, cells, ref, normal)
            pressure = ct["pressure"]
            # 2D: the signed shear along t; 3D: the shear vector in the crack's plane.
            shear = ct["shear"][:, 0] if m.gdim == 2 else np.einsum("nk,nkd->nd", ct["shear"], ct["tangents"])
        return {"pressure": pressure, "shear": shear,
                "state": self._lip_states(pressure, shear, crack, cells, ref)}

    def _lip_states(self, pressure: np.ndarray, shear: np.ndarray, crack: int | None = None,
                    cells: np.ndarray | None = None, ref: np.ndarray | None = None) -> np.ndarray:
        """Per point "open", "stick" or "slip" from the lip tractions: open
        where a unilateral contact carries no pressure (or without contact),
        stick where |shear| < mu p (1 - 1e-6) and a sticking friction
        multiplier has weight at the point, slip where the shear is at the
        bound or only slipping multipliers carry the point (or closed
        without friction: the lips slide freely). In 3D each slipping
        multiplier has its own direction, so between them the interpolated
        shear is below mu p (a spread of 0.22-0.31 degrees: by up to 3e-6 of
        it): the test on the shear alone called 20 % (1.3 % on a finer mesh)
        of the closed penny that slips everywhere "stick" (results.json
        stick_area, crack_contact.png). Without the multipliers' states
        (cells not given): the shear alone."""
        out = np.full(len(pressure), "open", dtype=object)
        if not self.contact:
            return out
        opts = self.model.scene.options
        scale = max(float(np.abs(pressure).max(initial=0.0)), 1e-300)
        closed = np.ones(len(pressure), dtype=bool) if opts.contact == "bilateral" else pressure > 1e-9 * scale
        size = np.abs(shear) if shear.ndim == 1 else np.linalg.norm(shear, axis=1)
        stick = closed & (size < opts.friction * pressure * (1.0 - 1e-6))
        states = self.contact.get("state")
        if opts.friction > 0.0 and states is not None and cells is not None:
            cs = self.contact["system"]
            sticking = cs.R @ (np.asarray(states) == STICK).astype(float)
            stick &= multiplier_values(self.model, cs.space, crack, cells, ref, sticking) > 0.0
        out[closed] = "slip"
        out[stick] = "stick"
        return out

    def __repr__(self) -> str:
        """What the solution holds, on one line (the dataclass's repr printed the whole model)."""
        m, sc = self.model, self.model.scene
        names = ", ".join(repr(getattr(c, "name", "")) for c in sc.cracks) or "none"
        dofs = f"{len(self.u)} dofs"
        if m.distributed:  # u holds this process's part (owned and ghost dofs)
            dofs += f" on process {m.comm.rank} of {m.comm.size}"
        parts = [f"{sc.mesh.gdim}D", dofs, f"cracks [{names}]", f"contact {sc.options.contact!r}"]
        if sc.options.friction > 0.0:
            parts.append(f"friction {sc.options.friction:g}")
        if self.step is not None:
            parts.append(f"load step {self.step.get('name', self.step.get('index'))!r}")
        if self.factors is not None:
            parts.append("factors " + ", ".join(f"{g}={f:g}" for g, f in self.factors.items()))
        if self.condition:
            parts.append(", ".join(f"{k}={v:.3g}" for k, v in self.condition.items()
                                   if isinstance(v, (int, float))))
        if self.error_estimate is not None:
            parts.append("with an error estimate")
        if isinstance(self.timings.get("total"), (int, float)):
            parts.append(f"solved in {self.timings['total']:.3g} s")
        return (f"Solution({'; '.join(parts)}; K: .stress_intensity_factors(crack), lips: .crack_opening(crack)"
                f"{', .contact_pressure(crack)' if self.contact else ''}, .displacement(points), .warnings)")

    @checked_keywords
    def crack_opening(self, crack: int | str = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Jump [[u]] = u(+) - u(-) over a crack (see lip_samples): x (n, d),
        weight (n,), jump (n, d), normal (n,) = [[u]].n (n the + side
        normal, positive = opening), tangential (n,) = [[u]].t in 2D, the
        size of the tangential part of [[u]] in 3D; s (n,) the arc length in
        2D."""
        smp = self.lip_samples(crack, points_per_segment)
        slip = smp["slip"]
        out = {"x": smp["x"], "weight": smp["weight"], "jump": smp["jump"], "normal": smp["gap"],
               "tangential": slip if slip.ndim == 1 else np.linalg.norm(slip, axis=1)}
        if "s" in smp:
            out["s"] = smp["s"]
        return out

    @checked_keywords
    def opening_volume(self, crack: int | str = 0) -> float:
        """int [[u]].n over a crack's lips: the area (2D, per unit thickness)
        or the volume (3D) the crack opens."""
        smp = self.lip_samples(crack)
        return float(np.sum(smp["weight"] * smp["gap"]))

    @checked_keywords
    def contact_pressure(self, crack: int | str = 0, points_per_segment: int = 3) -> dict[str, np.ndarray]:
        """Contact pressure p = -lambda (>= 0 in compression) and normal gap
        [[u]].n at points on the crack (see lip_samples): x (n, d),
        pressure (n,), gap (n,), weight (n,) (for integrals over the
        crack), shear the friction traction on the + lip (2D: (n,) along
        the crack's direction t; 3D: (n, 3) in its plane; 0 without
        friction), slip the tangential jump accumulated over the load path
        (2D: (n,) = [[u]].t; 3D: (n, 3)), state (n,) "open", "stick" or
        "slip"; in 2D sorted along the crack with s (n,), in 3D facet by
        facet with front_vertices (n,)."""
        if not self.contact:
            raise InputError("this solution has no contact (options.contact = 'none')")
        smp = self.lip_samples(crack, points_per_segment)
        keys = ("x", "s", "pressure", "gap", "weight", "shear", "slip", "state", "front_vertices")
        return {k: smp[k] for k in keys if k in smp}

    # -- whole-field quantities --------------------------------------------
    def subcell_fields(self) -> dict[str, typing.Any]:
        """The solution on the sub-cell mesh: the cells a crack splits cut into
        their sub-cells, with vertices not shared across a crack (a warp by
        the displacement opens it): points, displacement, stress (Voigt: xx,
        yy, xy in 2D, the total stress with an initial stress; xx, yy, zz,
        yz, xz, xy in 3D), side, parent (see the crack type's
        subcell_fields; cracklip.io.paraview writes them)."""
        return self.model.crack_type.subcell_fields(self)

    def field_points(self, cells: np.ndarray | None = None, degree: int | None = None
                     ) -> dict[str, np.ndarray]:
        """Quadrature points of the stiffness rules on `cells` (all cells by
        default) with grad u there: cell, x (n, d), weight, side, grad_u (n,
        d, d). degree: Gauss degree in cells without tip or front functions
        (default: the stiffness's)."""
        return self.model.crack_type.field_points(self.model, self.u, cells, degree)

    def enriched_quadrature(self) -> tuple[float, np.ndarray]:
        """(strain energy of the enriched cells, quadrature points per cell
        (num_cells,)) on the stiffness's rules, computed once, a chunk of
        enriched cells at a time (enriched_chunks: the points of all of them
        at once, with their gradients, took 0.46 GB at 6e4 dofs in 3D); the
        strain energy and results.json's quadrature counts both need them."""
        if not hasattr(self, "_enriched_quadrature"):
            m = self.model
            counts = np.zeros(m.cells.shape[0], dtype=np.int64)
            energy = 0.0
            for chunk in enriched_chunks(m):
                f = self.field_points(chunk)
                counts += np.bincount(f["cell"], minlength=len(counts))
                energy += _energy(f, m.scene.material)
            self._enriched_quadrature = (energy, counts)
        return self._enriched_quadrature

    def _plain_chunks(self) -> list[np.ndarray]:
        """The cells without enriched nodes, in chunks of at most CHUNK."""
        m = self.model
        plain = np.ones(m.cells.shape[0], dtype=bool)
        plain[np.asarray(m.layout.cells, dtype=np.int32)] = False
        if m.distributed:  # each process its owned cells
            plain[m.num_owned_cells:] = False
        cells = np.flatnonzero(plain).astype(np.int32)
        return np.array_split(cells, max(1, -(-len(cells) // CHUNK))) if len(cells) else []

    def strain_energy(self) -> float:
        """1/2 int sigma : eps over the domain (the stiffness quadrature; the
        enriched cells' part is enriched_quadrature()'s, shared with
        results.json's quadrature counts)."""
        mat = self.model.scene.material
        energy = self.enriched_quadrature()[0] + sum(_energy(self.field_points(c), mat) for c in self._plain_chunks())
        return float(self.model.V.mesh.comm.allreduce(energy)) if self.model.distributed else energy

    def energy_error(self, exact_gradient: typing.Callable[[np.ndarray, np.ndarray], np.ndarray],
                     degree: int | None = None) -> tuple[float, float]:
        """Energy norm of u - u_exact, absolute and relative to the exact field's.

        exact_gradient(x (n, d), side (n,)) returns grad u_exact (n, d, d);
        side is +1 / -1 on a crack's lips region (0 elsewhere), for fields
        that jump across the crack. degree: Gauss degree in cells away from
        the crack's functions (default ERROR_DEGREE).
        """
        m = self.model
        mat = m.scene.material
        degree = ERROR_DEGREE[m.gdim] if degree is None else int(degree)
        err2 = ref2 = 0.0
        # In chunks of cells, so that memory stays bounded on large meshes.
        ncells = m.cells.shape[0]
        for chunk in np.array_split(np.arange(ncells, dtype=np.int32), max(1, -(-ncells // CHUNK))):
            f = self.field_points(chunk, degree=degree)
            g_ex = np.asarray(exact_gradient(f["x"], f["side"]), dtype=float)
            e = strain(f["grad_u"] - g_ex)
            eex = strain(g_ex)
            err2 += float(np.sum(f["weight"] * np.einsum("nij,nij->n", stress(e, mat), e)))
            ref2 += float(np.sum(f["weight"] * np.einsum("nij,nij->n", stress(eex, mat), eex)))
        return float(np.sqrt(err2)), float(np.sqrt(err2 / ref2))

    @checked_keywords
    def stress_intensity_factors(self, crack: int | str | None = 0, radius: float | None = None,
                                 ring: tuple[float, float] | None = None) -> list[dict[str, typing.Any]]:
        """K at every tip (2D) or front point (3D) of a crack (its index in
        Scene.cracks or its name; crack=None: of every crack) by the domain interaction integral on three domains per
        point: one dict per point with the keys of results.json's "sifs"
        (cracklip.fracture.sif.SIF_KEYS: crack, crack_name, point, tip,
        piece, s, position, x, y, z, direction, normal, frame, K_I, K_II,
        K_III (None in 2D), their spreads and error estimates, mode_mix_deg,
        G, radius, radii, radius_min, inner_radius, element_size, hat,
        curvature, parametric_angle, limited_by, free_surface,
        domain_clear).

        radius: the largest domain's radius (default Options.sif_radius, 0:
        a few element sizes at the point); clipped to keep the domain inside
        the part and clear of other tips, cracks, kinks, holes (and within
        a front's curvature).
        ring: 2D only, (r_in, r_out), K on that one ring as another code
        defines it (q = 1 within r_in, 0 beyond r_out, linear between; r_in
        = r_out: the plateau of that radius), NOT clipped (default
        Options.sif_ring); a ring that reaches an obstacle is warned about,
        domain_clear false.
        """
        crack = None if crack is None else crack_index(self.model, crack)
        key = (crack, radius, None if ring is None else tuple(float(v) for v in ring))
        if key not in self._sif_cache:
            cracks = None if crack is None else [crack]
            if self.model.crack_type.END == "front":
                if ring is not None:
                    raise InputError("a SIF ring (options.sif_ring) is a 2D setting: 3D fronts take sif_radius")
                self._sif_cache[key] = compute_front_sifs(self, radius, cracks)
                release_memory()  # the domains' quadrature points are gone
            else:
                self._sif_cache[key] = compute_sifs(self, radius, cracks, ring)
        rows = [dict(r) for r in self._sif_cache[key][0]]
        est = self.error_estimate
        for r in rows:
            point = est["points"].get(f"{r['crack']}:{point_label(r)}") if est and radius is None and ring is None \
                else None
            for mode in ("K_I", "K_II", "K_III"):
                if point is None or f"{mode}_error" not in point:
                    continue
                r[f"{mode}_error"] = point[f"{mode}_error"]
                r[f"{mode}_extrapolated"] = point[f"{mode}_extrapolated"]
                r[f"{mode}_levels"] = list(point[f"{mode}_levels"])
            if point is not None and any(point.get(f"{m}_smoothed") is not None for m in ("K_I", "K_II", "K_III")):
                self._fitted(r, point)
        return complete_rows(rows)

    def _fitted(self, row: dict[str, typing.Any], point: dict[str, typing.Any]) -> None:
        """A front point's K replaced by its fit along the front where the
        estimate made one (Options.sif_smoothing = "fit"), the computed K
        kept as K_I_unsmoothed ... and its own estimate (the one without the
        fit) as K_I_error_unsmoothed ...; G and the mode mix from the fitted
        K."""
        for mode in ("K_I", "K_II", "K_III"):
            row[f"{mode}_unsmoothed"] = row[mode]
            row[f"{mode}_error_unsmoothed"] = point.get(f"{mode}_error_unsmoothed")
            if point.get(f"{mode}_smoothed") is not None:
                row[mode] = point[f"{mode}_smoothed"]
        mat = self.model.scene.material
        Ep, mu = mat.E / (1 - mat.nu ** 2), mat.E / (2 * (1 + mat.nu))
        kI, kII, kIII = row["K_I"], row["K_II"], row["K_III"]
        row["G"] = (kI ** 2 + kII ** 2) / Ep + kIII ** 2 / (2 * mu)
        if row.get("mode_mix_deg") is not None:
            row["mode_mix_deg"] = math.degrees(math.atan2(math.hypot(kII, kIII), kI))

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
        """The model checks' warnings, those of the SIFs at every tip or front
        point (domains clipped, K varying with the domain) and of the solved
        field (cracklip.post.checks: lips passing through each other without
        contact, no load, point supports carrying unbalanced loads, K's
        estimated discretisation error): model.checks.ModelWarning."""
        from .checks import point_supports, solution_warnings
        self.stress_intensity_factors(None)
        model_messages = {w.message for w in self.model.warnings}
        extra = [ModelWarning(getattr(m, "code", "sif_spread"), str(m), getattr(m, "crack", None),
                              getattr(m, "tip", None))
                 for m in self._sif_cache[(None, None, None)][1] if m not in model_messages]
        extra += [ModelWarning(code, m) for code, m in solution_warnings(self)]
        moving = np.any(self.u)
        if self.model.distributed:  # (each process its part of u)
            moving = reduced(bool(moving), "LOR", self.model.V.mesh.comm)
        if self.model.scene.dirichlet and moving:
            extra += [ModelWarning(code, m) for code, m in point_supports(self, self.reactions())]
        return list(self.model.warnings) + extra

    @property
    def standard_displacement(self) -> np.ndarray:
        """(num_nodes, d) standard dofs = displacement at the nodes (shifted enrichment)."""
        n = self.model.layout.num_std_nodes
        d = self.model.gdim
        return self.u[: d * n].reshape(n, d)


#: Quadrature points per chunk of the enriched cells' passes (about: the
#: chunks are sized by POINTS_GUESS).
ENRICHED_CHUNK_POINTS = 200_000

#: The points a cell is taken to hold when the chunks are sized: the cells
#: holding a tip or the front (3D: 900-2700 measured on the penny crack),
#: the other crossed cells (50-220), any other enriched cell (12-36).
POINTS_GUESS = {"end": 2000, "crossed": 200, "other": 40}


def enriched_chunks(model) -> list[np.ndarray]:
    """The model's enriched cells in chunks of about ENRICHED_CHUNK_POINTS
    quadrature points each (by POINTS_GUESS of each cell's class), so that
    a pass over their points (with gradients: 150 bytes a point) holds one
    chunk at a time."""
    cells = np.asarray(model.layout.cells, dtype=np.int32)
    cells = cells[model.owned_cells_only(cells)]  # (under MPI each process its owned cells)
    if not cells.size:
        return []
    kind = model.crack_type
    guess = np.full(cells.size, POINTS_GUESS["other"], dtype=np.int64)
    for g in model.geometries:
        cls = np.asarray(g.cell_class)[cells]
        guess = np.maximum(guess, np.where(np.isin(cls, kind.CROSSED), POINTS_GUESS["crossed"], 0))
        guess = np.maximum(guess, np.where(cls == kind.CELL_CLASSES.get("tip", kind.CELL_CLASSES.get("front")),
                                           POINTS_GUESS["end"], 0))
    bounds = np.searchsorted(np.cumsum(guess), np.arange(ENRICHED_CHUNK_POINTS, int(guess.sum()),
                                                         ENRICHED_CHUNK_POINTS))
    return [c for c in np.split(cells, np.unique(bounds)) if c.size]


def _energy(f: dict, material) -> float:
    """1/2 sum w sigma : eps over field points (Solution.field_points)."""
    if not len(f["weight"]):
        return 0.0
    eps = strain(f["grad_u"])
    return float(0.5 * np.sum(f["weight"] * np.einsum("nij,nij->n", stress(eps, material), eps)))


def _gathered_samples(local: dict[str, np.ndarray], comm) -> dict[str, np.ndarray]:
    """Every process's lip samples (those of its owned cells) on every
    process, in the serial order: sorted by the arc length s in 2D (3D:
    in rank order). Cell indices are each process's own: "cell" is -1 in
    the gathered samples."""
    parts = comm.allgather(local)
    out = {k: np.concatenate([p[k] for p in parts]) for k in local}
    out["cell"] = np.full(len(out["cell"]), -1, dtype=np.asarray(local["cell"]).dtype)
    if "s" in out:
        o = np.argsort(out["s"], kind="stable")
        out = {k: v[o] for k, v in out.items()}
    return out


def create_solution(model, u: np.ndarray, timings: dict, *args, **kwargs) -> Solution:
    """The Solution of a model (planar or solid)."""
    return Solution(model, u, timings, *args, **kwargs)


def _tree(model: XfemModel):
    tree = getattr(model, "_bb_tree", None)
    if tree is None:
        msh = model.scene.mesh.mesh
        tree = dolfinx.geometry.BoundingBoxTree(msh, msh.topology.dim)
        model._bb_tree = tree
    return tree


__all__ = ["Solution", "create_solution"]
