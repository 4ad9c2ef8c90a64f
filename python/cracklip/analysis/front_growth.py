"""Crack growth in 3D parts: fronts advanced point by point under load
spectra, the crack surface extended on the fixed mesh, life in cycles and
flights (the 3D steps of analysis.growth.GrowthRun).

Per step (the named steps of GrowthRun):

- measure: the fatigue life's load levels (analysis.life.LifeRun: a solve
  per load group at factor 1, contact solves at the closed levels), K_I,
  K_II, K_III at the front points of every crack (fracture.sif_3d through
  Solution.stress_intensity_factors) and at each of them (FrontPoints): the
  kink and twist (fracture.kink.kink_twist_3d), K_eq along the kink
  (equivalent_k_3d: the hoop-stress K with mode III's share of G), the
  counted cycles and the growth per pass of the law (rainflow per step;
  closure: contact, Newman or none; retardation per point), the net-section
  stress (post.section: the mean stress normal to the crack's plane over
  the intact section);
- count cycles: the passes of the increment just taken by the fastest
  point, K interpolated between the two geometries (LifeRun.count): each
  point of the last geometry is carried to where its increment took it and
  meets the new front's K there (FrontPoints.carry);
- check stops: K_max at K_c at any point, net-section yield,
  growth.max_length and spectrum.max_passes (all found inside the
  increment), the step count, no growing point, and the breakthrough found
  by the last advance;
- advance: every front point by da_i = growth.da x rate_i / max_j rate_j
  (the step's cycles from the fastest point), along its kink (front_kinks); the growth
  per front point interpolated along the crack's boundary loop
  (scene.surface_growth: the chains of the loop inside the part with a
  margin beyond the part's boundary), the advanced loop smoothed, re-sampled
  every growth spacing, its ends carried beyond the part's boundary, and
  the strip between the old and new fronts added to the triangulated crack
  surface; the model's level sets are recomputed from it geometrically at
  the next measure (the mesh, its standard stiffness block and the part's
  geometry are kept). A front that leaves the part anywhere but where it
  left it before (a surface crack reaching the back face, a corner crack
  another face, an embedded crack a surface) is a breakthrough: the run
  stops with the life to it (the increment's cycles up to the first
  crossing, at the rate of the step's start) and says so; the transition
  to a through crack is not modelled.

The front's resolution: the element size along the front is watched; where
the front grows into elements much coarser (RESOLUTION_FACTOR) than at the
start, a warning names the point and the size needed.
"""
from __future__ import annotations

import copy
import dataclasses
import logging
import math
import typing

import numpy as np

from ..errors import InputError
from ..fracture.kink import equivalent_k_3d, front_kinks, kink_twist_3d
from ..model.tip_regions import NEAREST_TIE
from ..scene.growth import Growth
from ..scene.processes import reduced
from ..scene.scene import Scene
from ..scene.surface_growth import GrowingSurface, StripTurnedOver, extend_ends, front_exit, resample, smooth
from .growth_run import GrowthRun
from .tips import FrontRecord, Measured

logger = logging.getLogger(__name__)

#: The growth front's vertices are this fraction of the front's element size apart.
SPACING_FRACTION = 0.5

#: The surface runs this many front element sizes beyond the part's boundary:
#: the largest size at the front's free-surface points at each step (at
#: least the start's front size), so that the strip outside the part stays
#: wider than the elements the front has grown into (SurfaceGrowth.margin).
MARGIN_ELEMENTS = 2.0

#: Default increment (growth.da = 0): this many front element sizes.
DEFAULT_DA_ELEMENTS = 2.0

#: A front point in elements larger than this factor times the front's
#: element size at the start is warned about (the mesh no longer resolves
#: the front).
RESOLUTION_FACTOR = 1.5

#: Smoothing sweeps of the advanced front's displacements (surface_growth.smooth).
SMOOTHING_PASSES = 1

#: A step whose grown strip turns over (its triangles face the other way:
#: the increment too large for the front's curvature) is retried with the
#: increment halved, at most this many times, before the run stops on it.
TURNED_OVER_HALVINGS = 4


def life_growth(scene: Scene, growth: Growth) -> Growth:
    """The growth settings as a fatigue life: [material.fatigue] as given, or
    growth.paris_C / paris_m (Walker's gamma, the threshold, growth.K_Ic as
    its toughness) as a Paris or Walker law with contact closure where the
    scene has contact. 3D fronts grow only by a law (each point by its
    rate)."""
    if growth.life:
        return growth
    if not growth.fatigue:
        raise InputError("a 3D crack grows by a fatigue law, each front point by its own rate: give "
                         "growth.paris_C and growth.paris_m with a load cycle (growth.R or cycle_min), or "
                         "[material.fatigue] with a [spectrum] (growth.da is then the largest advance along the "
                         "front in one step)")
    from ..scene.fatigue import FatigueMaterial
    walker = growth.walker_gamma != 1.0
    fm = FatigueMaterial("walker" if walker else "paris",
                         {"C": growth.paris_C, "m": growth.paris_m, **({"gamma": growth.walker_gamma} if walker
                                                                        else {})},
                         threshold=growth.threshold, K_Ic=growth.K_Ic,
                         closure="contact" if scene.options.contact != "none" else "none")
    # growth.K_Ic (in the scene's units, as the law's constants here) is the life's toughness, found inside the
    # step as [material.fatigue]'s K_Ic is: checked at the steps' fronts only, the life ran to the front past it
    # (a corner crack: 43 910 cycles against 41 063 to K_eq = K_Ic inside the step, 7 % long).
    return dataclasses.replace(growth, paris_C=None, paris_m=None, threshold=0.0, walker_gamma=1.0, K_Ic=None,
                               fatigue_material=fm)


def front_element_size(mesh, cracks) -> float:
    """The mean edge of the cells at the cracks' fronts (before any model:
    the cells of the mesh nodes nearest to points sampled along the fronts).
    Collective under mpirun: each point's nearest node of every process's
    owned nodes (nearest_nodes: found alike on all by its position), the
    edges of the owned cells around them summed over the processes."""
    import scipy.spatial
    msh = mesh.mesh
    comm = msh.comm
    x = msh.geometry.x
    cells = msh.geometry.dofmap.array.reshape(-1, 4)
    pts = []
    for c in cracks:
        size = float(np.sqrt(max(c.area, 1e-300)))
        pts.append(c.front_points(0.05 * size))
    pts = np.concatenate(pts)
    owned = msh.geometry.index_map().size_local
    near_x = nearest_nodes(x[:owned], pts, comm)                # each point's nearest node, on every process
    d_local, nodes = scipy.spatial.cKDTree(x).query(near_x)
    nodes = nodes[d_local == 0.0]                                # those this process holds (owned or ghost)
    cells = cells[:msh.topology.index_map(3).size_local]         # each cell counted by its owner
    near = np.isin(cells, np.unique(nodes)).any(axis=1)
    xv = x[cells[near]]
    e = np.array([np.linalg.norm(xv[:, j] - xv[:, i], axis=1)
                  for i, j in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))])
    total, count = reduced(np.array([e.sum(), float(e.size)]), "SUM", comm)
    return float(total / count)


def nearest_nodes(x: np.ndarray, pts: np.ndarray, comm) -> np.ndarray:
    """(m, 3): the coordinates of each point's nearest node among every
    process's nodes x (each process its owned ones), on every process. Nodes
    tied for the nearest (tip_regions.NEAREST_TIE) are decided by their
    coordinates (the lowest x, then y, then z), not by their numbering or
    process, so that one and several processes pick the same node."""
    import scipy.spatial
    m = len(pts)
    near = np.full((m, 3), np.inf)
    dist = np.full(m, np.inf)
    if len(x):
        k = min(8, len(x))
        d, i = scipy.spatial.cKDTree(x).query(pts, k=k)
        d, i = d.reshape(m, k), i.reshape(m, k)
        for j in range(m):
            tied = x[i[j][d[j] <= d[j, 0] * (1.0 + NEAREST_TIE)]]
            near[j] = tied[np.lexsort(tied.T[::-1])[0]]
            dist[j] = d[j, 0]
    if comm.size == 1:
        return near
    every_d = np.array(comm.allgather(dist))                    # (processes, points)
    every_x = np.array(comm.allgather(near))                    # (processes, points, 3)
    for j in range(m):
        tied = every_x[every_d[:, j] <= every_d[:, j].min() * (1.0 + NEAREST_TIE), j]
        near[j] = tied[np.lexsort(tied.T[::-1])[0]]
    return near


class FrontPoints:
    """Where a 3D life is measured: the front points of every crack (the SIF
    points of fracture.sif_3d), as analysis.life.TipPoints for 2D tips (its
    docstring lists what locate returns). A point's crack size a is its
    distance from its crack's origin (the ellipse's centre: the radius of a
    penny, the depth at a surface crack's deepest point, about c at the
    surface); its key is (crack, index along the crack's front)."""

    def __init__(self, run: "SurfaceGrowth"):
        self.run = run
        self.nu = run.scene.material.nu

    # -- one geometry -------------------------------------------------------------------------------------------
    def locate(self, model, rows: list[dict], cracks) -> "FrontPoints":
        out = FrontPoints.__new__(FrontPoints)
        out.run, out.nu, out.model, out.rows = self.run, self.nu, model, rows
        count: dict[int, int] = {}
        out.keys = []
        for r in rows:
            ci = r["crack"]
            out.keys.append((ci, count.get(ci, 0)))
            count[ci] = count.get(ci, 0) + 1
        out.X = np.array([[r["x"], r["y"], r["z"]] for r in rows]).reshape(-1, 3)
        origins = np.array([self.run.surfaces[ci].origin for ci, _ in out.keys]).reshape(-1, 3)
        out.a = np.linalg.norm(out.X - origins, axis=1)
        out.lengths = [float(out.a[[k for k, key in enumerate(out.keys) if key[0] == ci]].max(initial=0.0))
                       for ci in range(len(cracks))]
        return out

    def values(self, sifs: list[list[dict]], name: str) -> np.ndarray:
        """A SIF column at the points, (solutions, points). K_I, K_II, K_III
        at a free-surface point (where the front meets the part's boundary)
        are sif_3d's end values (fracture.front_sampling, K_source
        "end_extrapolation": the interior distribution's least-squares
        quadratic carried to the end, through K kappa^(1/6) since the
        seventh sitting), not the end's own domain integral,
        which belongs to the vertex singularity and a clipped domain. One
        rule for K and growth: the growth no longer re-extrapolates (it took
        the line through the two nearest interior points, which on the
        surface crack a/c = 0.2, a/t = 0.1 at a/8 gave the end 8.6 % above
        Newman and Raju where sif_3d's rule gives 5.0 %, and on a/c = 1
        -3.7 % where it gives -2.2 %: K runs curved towards the ends)."""
        return np.array([[r[name] for r in s] for s in sifs], dtype=float)

    def size(self, j: int) -> float:
        return float(self.a[j])

    def position(self, j: int) -> tuple[float, float, float]:
        return float(self.X[j, 0]), float(self.X[j, 1]), float(self.X[j, 2])

    @staticmethod
    def basis(j: int, groups, KI, KII, KIII) -> dict[str, tuple[float, ...]]:
        return {g: (float(KI[i, j]), float(KII[i, j]), float(KIII[i, j])) for i, g in enumerate(groups)}

    @staticmethod
    def magnitude(KI: np.ndarray, KII: np.ndarray, KIII: np.ndarray) -> np.ndarray:
        return np.sqrt(np.maximum(KI, 0.0) ** 2 + KII ** 2 + KIII ** 2)

    def kink(self, KI: float, KII: float, KIII: float, criterion: str) -> tuple[float, float]:
        return kink_twist_3d(KI, KII, KIII, self.nu)

    def k_eq(self, KI: np.ndarray, KII: np.ndarray, KIII: np.ndarray, theta: float) -> np.ndarray:
        return np.asarray(equivalent_k_3d(KI, KII, KIII, theta, self.nu, clamp=False), dtype=float).reshape(-1)

    def k_eq_one(self, KI: float, KII: float, KIII: float, theta: float, clamp: bool = False) -> float:
        return float(equivalent_k_3d(KI, KII, KIII, theta, self.nu, clamp=clamp))

    @staticmethod
    def near(x: float, y: float, *z: float) -> str:
        return f"the front point near ({x:.6g}, {y:.6g}, {z[0] if z else 0.0:.6g})"

    def net_stresses(self, basis, wanted: bool):
        """s(j, theta): the net-section stress of point j's crack for each
        basis solution (post.section), or None."""
        if not wanted:
            return None
        from ..model.cracks.surface import crack_surface
        from ..post.section import net_section_stress
        per_crack: dict[int, np.ndarray] = {}
        sc = self.model.scene
        loaded_lips = sc.initial_stress is not None or any(
            callable(c.crack.pressure) or c.crack.pressure != 0.0 for c in self.model.cracks)
        for ci in sorted({key[0] for key in self.keys}):
            idx = [k for k, key in enumerate(self.keys) if key[0] == ci]
            point = self.X[idx].mean(axis=0)
            normal = np.array([self.rows[k]["normal"] for k in idx]).mean(axis=0)
            surf = crack_surface(self.model.cracks[ci].crack)
            per_crack[ci] = np.array([net_section_stress(b, surf, point, normal,
                                                         free_lips=not b.contact and not loaded_lips) for b in basis])

        def at(j: int, theta: float) -> np.ndarray:
            return per_crack[self.keys[j][0]]
        return at

    def record(self, k: int, j: int, lv, spread_I: float, spread_II: float, keq: float, closed: float, N: float):
        r0 = self.rows[j]
        ci, idx = lv.key
        return FrontRecord(k, ci, idx, float(self.X[j, 0]), float(self.X[j, 1]), float(self.a[j]),
                           float(lv.K_I[lv.ref]), float(lv.K_II[lv.ref]), spread_I, spread_II, math.degrees(lv.theta),
                           keq, closed, N=N, sif_radius=float(r0["radius"]), z=float(self.X[j, 2]),
                           K_III=float(lv.K_III[lv.ref]) if lv.K_III is not None else 0.0,
                           K_III_spread=float(r0["K_III_spread"]), twist_deg=math.degrees(lv.twist),
                           free_surface=bool(r0["free_surface"]), element_size=float(r0["element_size"]))

    # -- between geometries ----------------------------------------------------------------------------------
    def carry(self, prev: dict, now: dict) -> dict:
        """The new geometry's levels at the points of the last one: each old
        point where its increment took it (SurfaceGrowth.advanced_to),
        projected on the new front of its crack, the levels of the two new
        points around it blended linearly."""
        moved = self.run.advanced_to
        out = {}
        by_crack: dict[int, list] = {}
        for key in sorted(now):
            by_crack.setdefault(key[0], []).append(key)
        for key, lv in prev.items():
            keys = by_crack.get(key[0])
            if not keys:
                continue
            P = np.array([[now[q].x, now[q].y, now[q].z] for q in keys])
            x = moved.get(key, np.array([lv.x, lv.y, lv.z]))
            if len(keys) == 1:
                out[key] = now[keys[0]]
                continue
            closed = self.run.closed_front.get(key[0], False)
            i, w = _nearest_on_polyline(P, x, closed)
            out[key] = _blend(now[keys[i]], now[keys[(i + 1) % len(keys)]], w)
        return out


def _nearest_on_polyline(P: np.ndarray, x: np.ndarray, closed: bool) -> tuple[int, float]:
    """(segment i, fraction w) of the point of the polyline P (n, 3) nearest to x."""
    A = P if closed else P[:-1]
    B = np.roll(P, -1, axis=0) if closed else P[1:]
    d = B - A
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    t = np.clip(np.einsum("ij,ij->i", x - A, d) / dd, 0.0, 1.0)
    dist = np.linalg.norm(A + t[:, None] * d - x, axis=1)
    i = int(np.argmin(dist))
    return i, float(t[i])


def _blend(a, b, w: float):
    """TipLevels between two points: arrays and positions linear in w, the
    discrete parts (cycles, reference state) of the nearer point."""
    near = a if w <= 0.5 else b
    lin = (lambda u, v: None if u is None or v is None else (1.0 - w) * np.asarray(u) + w * np.asarray(v))  # noqa
    return dataclasses.replace(
        near, a=float((1 - w) * a.a + w * b.a), K_lin=lin(a.K_lin, b.K_lin), K_con=lin(a.K_con, b.K_con),
        K_I=lin(a.K_I, b.K_I), K_II=lin(a.K_II, b.K_II), K_III=lin(a.K_III, b.K_III),
        sigma_net=lin(a.sigma_net, b.sigma_net), sigma_basis=lin(a.sigma_basis, b.sigma_basis),
        x=float((1 - w) * a.x + w * b.x), y=float((1 - w) * a.y + w * b.y), z=float((1 - w) * a.z + w * b.z),
        basis={g: tuple((1 - w) * np.asarray(a.basis[g]) + w * np.asarray(b.basis[g])) for g in a.basis})


class SurfaceGrowth(GrowthRun):
    """3D: crack surfaces grown at their fronts (module doc)."""

    SIZE_NAME = "size (a surface or corner crack's depth a, an embedded crack's mean radius)"
    END = "point"

    def __init__(self, scene: Scene, growth: Growth, keep_solutions: bool, on_step=None, beta_table: bool = False):
        if growth.corrections:
            raise InputError("growth.corrections (the 2D corrector) is not available for 3D fronts: leave it 0")
        growth = life_growth(scene, growth)
        self.h_front = front_element_size(scene.mesh, scene.cracks)
        self.spacing = SPACING_FRACTION * self.h_front
        self.margin = MARGIN_ELEMENTS * self.h_front
        self.margins: list[float] = []     # per step (_scale_margin)
        self.advanced_to: dict[tuple[int, int], np.ndarray] = {}
        self.closed_front: dict[int, bool] = {}
        self.exits: dict[int, list[np.ndarray]] = {}   # per crack: the outward normals where its front leaves the part
        self.faces: dict[int, dict[str, typing.Any]] = {}  # per crack: the faces it starts on (measure_shape)
        self._free: dict[tuple[int, int], bool] = {}
        self.radius_scale: list[float] = [1.0]
        self.breakthrough: dict[str, typing.Any] | None = None
        self.surfaces_per_step: list[list[tuple[np.ndarray, np.ndarray]]] = []
        self.h_start: float | None = None
        super().__init__(scene, growth, keep_solutions, on_step, beta_table)
        if self.da <= 0.0:
            self.da = DEFAULT_DA_ELEMENTS * self.h_front
            self.growth = dataclasses.replace(self.growth, da=self.da)
        self.shape: list[dict[str, typing.Any]] = []

    # -- set-up -----------------------------------------------------------------------------------------------
    def initial_cracks(self, scene: Scene) -> list:
        self.surfaces = [GrowingSurface.from_crack(c, self.spacing) for c in scene.cracks]
        return [s.crack for s in self.surfaces]

    def create_life(self):
        from .life import LifeRun
        return LifeRun(self.scene, self.growth, points=FrontPoints(self))

    def inside(self, points: np.ndarray) -> np.ndarray:
        from ..model.boundary import points_inside
        return points_inside(self.scene.mesh, points)

    def where(self, r, how: str = "tip") -> str:
        z = getattr(r, "z", 0.0)
        return f"({r.x:.6g}, {r.y:.6g}, {z:.6g})" if how == "at" else f"the front point ({r.x:.6g}, {r.y:.6g}, {z:.6g})"

    def describe_step(self, records) -> str:
        out = []
        for ci in sorted({r.crack for r in records}):
            rs = [r for r in records if r.crack == ci]
            out.append(f"crack {self.cracks[ci].name!r}: {len(rs)} front points, K_I {min(r.K_I for r in rs):.4g} .. "
                       f"{max(r.K_I for r in rs):.4g}, N = {self.N:.4g}")
        return "; ".join(out)

    # -- the named steps of a front --------------------------------------------------------------------------
    def measure(self) -> Measured:
        self._scale_radii()
        m = self.life.measure(self.cracks, self.k, self.N, self.stopped)
        self._free = {(r.crack, r.end): r.free_surface for r in m.records}
        self._check_resolution(m)
        self._scale_margin(m)
        shape = self.measure_shape(m)
        self.shape.append(shape)
        # A crack's size (growth.max_length): a surface or corner crack's depth a, an embedded one's mean radius.
        m.lengths = [shape[ci].get("a", shape[ci]["radius_mean"]) if ci in shape else 0.0
                     for ci in range(len(self.surfaces))]
        self.measure_done()
        return m

    def record_beta(self, m: Measured) -> int:
        """The beta rows of every front point (K of each load group at factor
        1 over S sqrt(pi a)); the writer picks the deepest and surface points."""
        if not self.beta_table:
            return 0
        ref = dict(self.growth.reference_stress or {})
        shape = self.shape[-1]
        for key, lv in m.levels.items():
            row = {"step": self.k, "crack": key[0], "point": key[1], "x": lv.x, "y": lv.y, "z": lv.z, "a": lv.a}
            for g, b in lv.basis.items():
                S = ref.get(g, 1.0)
                row[f"K_I_{g}"] = b[0]
                row[f"beta_{g}"] = b[0] / (S * math.sqrt(math.pi * lv.a)) if lv.a > 0 else None
            sh = shape.get(key[0], {})
            row["depth_a"], row["surface_c"] = sh.get("a"), sh.get("c")
            row["role"] = ("deepest" if sh.get("deepest") == key[1] else
                           "surface" if key[1] in sh.get("surface_points", ()) else "")
            self.beta.append(row)
        return 0

    def check_geometry_stops(self, m: Measured) -> bool:
        return False

    def advance(self, m: Measured) -> None:
        """Advance every front point by its share of growth.da along its kink,
        extend the crack surfaces (module doc); a breakthrough sets the stop
        that ends the run."""
        rates = m.rates
        fast = max(rates, key=lambda q: rates[q])
        rate_max = rates[fast]
        if self.growth.da_fraction:
            self.da = self.growth.da_fraction * m.levels[fast].a
        da = {key: self.da * rates.get(key, 0.0) / rate_max for key in m.levels}
        for r in m.records:
            r.da = da.get((r.crack, r.end), 0.0)
        self._check_increment(m, fast)
        self.advanced_to = {}
        plans = []  # per crack: its chains and each chain's vertices and displacements
        for ci, surf in enumerate(self.surfaces):
            keys = [key for key in m.levels if key[0] == ci]
            if not keys:
                continue
            X = np.array([[m.levels[q].x, m.levels[q].y, m.levels[q].z] for q in keys])
            d_pt = np.array([da[q] for q in keys])
            beta = front_kinks([m.levels[q].theta for q in keys], [self._free.get(q, False) for q in keys], X)
            for r in m.records:  # the kink each point takes (fracture.kink.front_kinks), not the criterion's
                if r.crack == ci and (r.crack, r.end) in keys:
                    r.kink_deg = math.degrees(float(beta[keys.index((r.crack, r.end))]))
            chains = surf.chains(self.inside, self.margin)
            if not chains:
                continue
            e1, e2 = surf.outward()
            moves = []
            for ch in chains:
                C = surf.loop_points[ch.positions]
                s_v, L = _arc(C, ch.closed)
                s_pt = np.array([_project(C, x, ch.closed) for x in X])
                order = np.argsort(s_pt)
                if ch.closed:
                    sp = np.concatenate([s_pt[order] - L, s_pt[order], s_pt[order] + L])
                    dav = np.interp(s_v, sp, np.tile(d_pt[order], 3))
                    bv = np.interp(s_v, sp, np.tile(beta[order], 3))
                else:
                    dav = np.interp(s_v, s_pt[order], d_pt[order])
                    bv = np.interp(s_v, s_pt[order], beta[order])
                direction = np.cos(bv)[:, None] * e1[ch.positions] + np.sin(bv)[:, None] * e2[ch.positions]
                moves.append((C, smooth(dav[:, None] * direction, SMOOTHING_PASSES, ch.closed)))
                self.closed_front[ci] = ch.closed
                # Where each front point went (for the cycles' interpolation).
                for q, x, sq in zip(keys, X, s_pt):
                    dv = np.array([np.interp(sq, s_v, direction[:, c]) for c in range(3)])
                    self.advanced_to[q] = x + da[q] * dv / max(np.linalg.norm(dv), 1e-300)
            plans.append((ci, surf, chains, moves))
        news = {ci: self._new_fronts(chains, moves, 1.0) for ci, _, chains, moves in plans}
        notes = [n for ci, _, chains, _ in plans for n in [self._breakthrough(ci, chains, news[ci])] if n]
        if notes:
            # The fraction of the increment at which the front first leaves the part (bisection).
            lo, hi = 0.0, 1.0
            for _ in range(12):
                mid = 0.5 * (lo + hi)
                if any(self._breakthrough(ci, chains, self._new_fronts(chains, moves, mid), record=False)
                       for ci, _, chains, moves in plans):
                    hi = mid
                else:
                    lo = mid
            self._break(m, notes[0], hi)
            return
        scale = self._extend(plans, news)
        if scale < 1.0:
            da = {q: scale * v for q, v in da.items()}
            for r in m.records:
                r.da *= scale
            for q, x in self.advanced_to.items():
                x0 = np.array([m.levels[q].x, m.levels[q].y, m.levels[q].z])
                self.advanced_to[q] = x0 + scale * (x - x0)
        self.cracks = [s.crack for s in self.surfaces]
        self.life.advanced(m, {q: v for q, v in da.items() if v > 0.0})

    def _check_increment(self, m: Measured, fast) -> None:
        """Warn once (growth_increment, as 2D) when the step's largest advance
        is beyond the SIF domain at the fastest point: its kink and rate come
        from the field within that radius and are carried beyond it (a crack
        of 1.5 mm given growth.da = 5 mm went to 6.5 mm in one step without a
        word)."""
        r = next((r for r in m.records if (r.crack, r.end) == fast), None)
        if r is None or r.sif_radius <= 0.0 or self.da <= r.sif_radius or "large" in self.warned:
            return
        self.warned.add("large")
        key = "growth.da_fraction" if self.growth.da_fraction else "growth.da"
        self.warn("growth_increment", f"the step's largest advance {self.da:.3g} at {self.where(r, 'at')} is larger "
                  f"than the SIF domain there (radius {r.sif_radius:.3g}; the crack's size there {r.length:.3g}): the "
                  f"kink and the rates come from the field within that radius and are carried beyond it; use a "
                  f"smaller {key} (said once)", r.crack, r.end)

    def _extend(self, plans, news) -> float:
        """Extend every crack's surface by its new fronts; where a grown strip
        turns over, every crack's increment is halved and the step retried
        (TURNED_OVER_HALVINGS times at most, warned): the fraction of the
        increment taken."""
        t = 1.0
        for halving in range(TURNED_OVER_HALVINGS + 1):
            trials = [copy.deepcopy(surf) for _, surf, _, _ in plans]
            try:
                for trial, (ci, _, chains, _) in zip(trials, plans):
                    trial.extend(chains, news[ci])
            except StripTurnedOver as e:
                if halving == TURNED_OVER_HALVINGS:
                    raise StripTurnedOver(f"{e} (also with the increment halved {halving} times)") from e
                t *= 0.5
                news = {ci: self._new_fronts(chains, moves, t) for ci, _, chains, moves in plans}
                continue
            for trial, (ci, _, _, _) in zip(trials, plans):
                self.surfaces[ci] = trial
            if t < 1.0:
                self.warn("growth_strip", "the grown strip turned over at the full increment (too large for the "
                          f"front's curvature); the step took {t:g} of it")
            return t
        raise AssertionError("unreachable")

    def _new_fronts(self, chains, moves, t: float) -> list[np.ndarray]:
        """Each chain's new polyline with its displacements scaled by t:
        re-sampled, an open one's ends carried beyond the part."""
        out = []
        for ch, (C, move) in zip(chains, moves):
            B = resample(C + t * move, self.spacing, ch.closed)
            if not ch.closed:
                B = extend_ends(B, self.inside, self.margin)
            out.append(B)
        return out

    # -- breakthrough ---------------------------------------------------------------------------------------
    def _breakthrough(self, ci: int, chains, news: list[np.ndarray], record: bool = True) -> str | None:
        """Where a crack's new fronts leave the part other than where they did:
        a note, else None (record: the first time, the exits are remembered)."""
        for ch, B in zip(chains, news):
            note = self._leaves(ci, ch, B, record)
            if note:
                return note
        return None

    def _leaves(self, ci: int, ch, B: np.ndarray, record: bool) -> str | None:
        (kind, i), ins = front_exit(B, ch.closed, self.inside)
        name = self.cracks[ci].name
        if kind == "surface":
            return f"the front of crack {name!r} reached the part's surface near ({B[i][0]:.6g}, {B[i][1]:.6g}, " \
                   f"{B[i][2]:.6g})"
        if kind == "gone":
            return f"the front of crack {name!r} left the part"
        if kind == "split":
            return (f"the front of crack {name!r} broke through the part's surface near ({B[i][0]:.6g}, "
                    f"{B[i][1]:.6g}, {B[i][2]:.6g}): it is now in two pieces (a through crack)")
        if ch.closed:
            return None
        idx = np.flatnonzero(ins)
        normals = [self._exit_normal(B[idx[0]], B[max(idx[0] - 1, 0)]),
                   self._exit_normal(B[idx[-1]], B[min(idx[-1] + 1, len(B) - 1)])]
        known = self.exits.get(ci)
        if known is None:
            if record:
                self.exits[ci] = normals
            return None
        for end, (n0, n1) in enumerate(zip(known, normals)):
            if float(np.dot(n0, n1)) < math.cos(math.radians(45.0)):
                p = B[idx[0]] if end == 0 else B[idx[-1]]
                return (f"the front of crack {self.cracks[ci].name!r} reached another face of the part near "
                        f"({p[0]:.6g}, {p[1]:.6g}, {p[2]:.6g}) (the face's normal turned by "
                        f"{math.degrees(math.acos(max(-1.0, min(1.0, float(np.dot(n0, n1)))))):.0f} degrees): "
                        "breakthrough")
        return None

    def _crossing(self, inside_pt: np.ndarray, outside_pt: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Where the segment from a point inside the part to one outside
        crosses its boundary: the last inside and first outside points of 40
        bisections (2^-40 of the segment apart)."""
        lo, hi = np.asarray(inside_pt, float), np.asarray(outside_pt, float)
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if bool(self.inside(mid[None])[0]):
                lo = mid
            else:
                hi = mid
        return lo, hi

    def _exit_normal(self, inside_pt: np.ndarray, outside_pt: np.ndarray) -> np.ndarray:
        """The outward normal of the part's boundary facet nearest to where
        the segment between the two points crosses it."""
        from ..model.boundary import exterior_facets
        lo, _ = self._crossing(inside_pt, outside_pt)
        verts, _, normals = exterior_facets(self.scene.mesh)
        c = verts.mean(axis=1)
        return normals[int(np.argmin(np.linalg.norm(c - lo, axis=1)))]

    def _break(self, m: Measured, note: str, frac: float) -> None:
        """Stop at a breakthrough: the cycles of the fraction `frac` of the
        increment before the front leaves the part, at the rate of the
        step's start (the fastest point's)."""
        fast = max(m.rates, key=lambda q: m.rates[q])
        life = self.life
        life.passes += frac * self.da / m.rates[fast]
        life.N = life.passes * (life.cycles_per_pass or 0.0)
        self.N = life.N
        blocks = life.passes * life.blocks_per_pass
        self.pending = (f"breakthrough during step {self.k}: {note}; life to breakthrough {life.N:.6g} cycles = "
                        f"{blocks:.6g} {life.spectrum.block_name}s ({frac:.3g} of this step's increment, at the rate "
                        "of its start). The transition to a through crack is not modelled: the run stops here",
                        "breakthrough")
        self.breakthrough = {"step": self.k, "fraction": frac, "cycles": life.N, "blocks": blocks,
                             "passes": life.passes, "note": note}

    # -- shape of surface and corner cracks -------------------------------------------------------------------
    def measure_shape(self, m: Measured) -> dict[int, dict[str, typing.Any]]:
        """Per crack, what its front's shape is (crack_shape): kind, a, c, t,
        the deepest and surface points; the first step fixes which faces of
        the part the crack starts on and its depth direction."""
        out = {}
        for ci in range(len(self.surfaces)):
            keys = [key for key in m.levels if key[0] == ci]
            if not keys:
                continue
            X = np.array([[m.levels[q].x, m.levels[q].y, m.levels[q].z] for q in keys])
            free = [j for j, q in enumerate(keys) if self._free.get(q, False)]
            if ci not in self.faces:
                self.faces[ci] = self._start_faces(ci, X, free)
            out[ci] = crack_shape(self.surfaces[ci].origin, X, [q[1] for q in keys], free, self.faces[ci],
                                  self.tracked_front(ci))
        return out

    def tracked_front(self, ci: int) -> np.ndarray:
        """The crack's front as the surface's loop draws it inside the part
        (the geometry the level sets come from, not the SIF points on their
        P1 interpolation): the loop when it is inside, else its longest run
        inside with the points where it crosses the part's boundary at both
        ends (bisection)."""
        P = self.surfaces[ci].loop_points
        ins = self.inside(P)
        if ins.all():
            return P
        m = len(P)
        best: list[int] = []
        start = int(np.flatnonzero(~ins)[0])
        run: list[int] = []
        for i in range(1, m + 1):
            p = (start + i) % m
            if ins[p]:
                run.append(p)
            else:
                if len(run) > len(best):
                    best = run
                run = []
        if not best:
            return P[:0]
        ends = []
        for inner, outer in ((best[0], (best[0] - 1) % m), (best[-1], (best[-1] + 1) % m)):
            lo, hi = self._crossing(P[inner], P[outer])
            ends.append(0.5 * (lo + hi))
        return np.vstack([ends[0], P[best], ends[1]])

    def _start_faces(self, ci: int, X: np.ndarray, free: list[int]) -> dict[str, typing.Any]:
        """The faces the crack's front ends on at the start (tags, outward
        normals, areas), its kind and depth direction u and the part's
        thickness t along u from the crack's origin."""
        from ..model.boundary import exterior_facet_tags, exterior_facets
        o = self.surfaces[ci].origin
        if len(free) < 2:
            return {"kind": "embedded"}
        verts, areas, normals = exterior_facets(self.scene.mesh)
        tags = exterior_facet_tags(self.scene.mesh)
        cent = verts.mean(axis=1)
        ends = [free[0], free[-1]]
        near = [int(np.argmin(np.linalg.norm(cent - X[e], axis=1))) for e in ends]
        n = [normals[f] for f in near]
        names = [tags[f] for f in near]
        if float(np.dot(n[0], n[1])) > math.cos(math.radians(30.0)):
            kind, u = "surface", -0.5 * (n[0] + n[1])
            a_end = c_end = None
        else:
            # A corner crack: a runs down the smaller of the two faces (a bore, an edge face: through the
            # thickness), c along the larger (the plate's face); untagged faces: the first end is a's.
            tag_area = {}
            for name in set(names):
                if name is not None:
                    tag_area[name] = float(sum(ar for ar, t in zip(areas, tags) if t == name))
            small = 0
            if names[0] in tag_area and names[1] in tag_area and tag_area[names[1]] < tag_area[names[0]]:
                small = 1
            a_end, c_end = ends[small], ends[1 - small]
            kind, u = "corner", -n[1 - small]
        u = u / np.linalg.norm(u)
        return {"kind": kind, "u": u, "faces": names, "end_points": ends, "a_end": a_end, "c_end": c_end,
                "thickness": self._thickness(o, u)}

    def _thickness(self, o: np.ndarray, u: np.ndarray) -> float:
        """The part's extent from o along u (the first exit, by marching and bisection)."""
        step = self.h_front
        lo = 0.0
        for _ in range(100000):
            if not bool(self.inside((o + (lo + step) * u)[None])[0]):
                break
            lo += step
        hi = lo + step
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if bool(self.inside((o + mid * u)[None])[0]):
                lo = mid
            else:
                hi = mid
        return float(0.5 * (lo + hi))

    def _scale_radii(self) -> None:
        """Keep the enrichment radius (options.radius) and a given sif_radius
        constant in element sizes at the front: where the front has grown
        into coarser elements they grow in proportion (never below the
        scene's own)."""
        if self.h_start is None or not self.records:
            return
        sizes = [r.element_size for r in self.records[-1] if not r.free_surface and r.element_size > 0.0]
        ratio = max(1.0, float(np.median(sizes)) / self.h_start) if sizes else 1.0
        o = self.scene.options
        self.radius_scale.append(ratio)
        self.life.scene = dataclasses.replace(self.life.scene, options=dataclasses.replace(
            o, radius=o.radius * ratio, sif_radius=o.sif_radius * ratio))

    def _scale_margin(self, m: Measured) -> None:
        """The margin beyond the part's boundary (MARGIN_ELEMENTS) in the
        element sizes at the front's free-surface points now. Kept at the
        start's 2 front sizes, it fell under one element where the front had
        grown into coarser ones: the surface's boundary loop outside the part
        (the strip beyond the face, along the crack's mouth) came within an
        element of the mesh nodes on the face, and the front points next to
        the free surface lost their domain independence (surface crack a/c0
        = 1 on a graded mesh, K_I's spread over the 3 domains of the points
        next to the ends over the deepest point's K: 1.0-1.6 % at steps
        7-10, 3.1 % at step 11, then 2.5-24 % as the ends' elements (0.033
        at step 12) passed the margin (about 0.034); the two ends' K up to
        16 % apart and the fastest point alternating between the ends and
        the deepest point. Re-sized: 0.1-1.0 % at steps 8-20, the ends
        within 2 %: docs/growth.md)."""
        sizes = [r.element_size for r in m.records if r.free_surface and r.element_size > 0.0]
        self.margin = MARGIN_ELEMENTS * max([self.h_front] + sizes)
        self.margins.append(self.margin)

    # -- the mesh's resolution ------------------------------------------------------------------------------
    def _check_resolution(self, m: Measured) -> None:
        """The start's front element size (h_start: the median over the
        interior points; a front whose points all lie on the free surface,
        as a coarse corner crack's two, takes every point's, else the mean
        size along the fronts before the model), then a warning once where
        an interior point lies in elements RESOLUTION_FACTOR times coarser.
        (With only free-surface points at the start h_start was 0: the
        warning said "inf times those at the start (0)", and the next step's
        radius scaling divided by it: ZeroDivisionError.)"""
        interior = [r for r in m.records if not r.free_surface and r.element_size > 0.0]
        if self.h_start is None:
            every = [r.element_size for r in (interior or m.records) if r.element_size > 0.0]
            self.h_start = float(np.median(every)) if every else self.h_front
            return
        if not interior:
            return
        sizes = np.array([r.element_size for r in interior])
        worst = int(np.argmax(sizes))
        if sizes[worst] > RESOLUTION_FACTOR * self.h_start and "resolution" not in self.warned:
            self.warned.add("resolution")
            r = interior[worst]
            self.warn(
                "growth_resolution", f"the front at ({r.x:.4g}, {r.y:.4g}, {r.z:.4g}) lies in elements of "
                f"{sizes[worst]:.3g}, {sizes[worst] / self.h_start:.1f} times those at the start ({self.h_start:.3g}): "
                "the mesh no longer resolves the front there; refine the region the crack grows into to about "
                f"{self.h_start:.3g} ([[mesh.refine]] box = [...], h = ...) (said once)", r.crack)

    # -- the result -----------------------------------------------------------------------------------------
    def measure_done(self) -> None:
        """Keep this step's crack surfaces (the ParaView series)."""
        self.surfaces_per_step.append([(s.vertices.copy(), s.triangles.copy()) for s in self.surfaces])

    def result(self):
        out = super().result()
        if out.life is not None:
            # A crack's residual strength: the least over its front points, per step.
            least: dict[tuple[int, int], dict] = {}
            for c in out.life["residual_strength"]:
                key = (c["step"], c["crack"])
                if key not in least or c["multiple"] < least[key]["multiple"]:
                    least[key] = dict(c, end=-1, point=c["end"])
            out.life["residual_strength"] = [least[k] for k in sorted(least)]
        out.fronts = {"shape": self.shape, "surfaces": self.surfaces_per_step, "spacing": self.spacing,
                      "margin": self.margin, "margins": self.margins, "h_front": self.h_front, "da": self.da,
                      "radius_scale": self.radius_scale, "faces": self.faces,
                      "origins": [s.origin.tolist() for s in self.surfaces], "breakthrough": self.breakthrough}
        return out


def crack_shape(origin: np.ndarray, X: np.ndarray, index: list[int], free: list[int], faces: dict,
                front: np.ndarray) -> dict[str, typing.Any]:
    """The shape of a crack, NASGRO's names, measured on its tracked front
    `front` (m, 3) (SurfaceGrowth.tracked_front: the surface's own front in
    the part, its crossings of the part's boundary at the ends of an open
    one); X (n, 3) are the growth points (their indices `index`, the
    free-surface ones at positions `free`), which give the roles:

    - embedded (a closed front): radius_mean and roundness max |r - mean r|
      / mean r of the front's distances r from the origin;
    - surface crack (both ends on one face): a the largest depth (x - o).u
      of the front below the face, c half the distance between its ends;
    - corner crack (the ends on two faces): a the distance from the origin
      of the end on the smaller face (down the bore or edge: through the
      thickness), c that of the end on the larger face;
    t the part's thickness along u from the origin; deepest: the growth
    point of the largest depth; surface_points: the growth points at the
    ends (corner: [a end, c end]); radius_mean_points, roundness_points:
    the same measures on the growth points."""
    r = np.linalg.norm(X - origin, axis=1)
    rf = np.linalg.norm(front - origin, axis=1) if len(front) else r
    out: dict[str, typing.Any] = {"kind": faces.get("kind", "embedded"), "points": len(X),
                                  "radius_mean": float(rf.mean()), "roundness": float(np.abs(rf - rf.mean()).max()
                                                                                       / rf.mean()),
                                  "radius_mean_points": float(r.mean()),
                                  "roundness_points": float(np.abs(r - r.mean()).max() / r.mean())}
    if out["kind"] == "embedded" or len(free) < 2 or len(front) < 2:
        out["kind"] = "embedded" if len(free) < 2 else out["kind"]
        return out
    u = faces["u"]
    depth = (X - origin) @ u
    # (the first of the points tied for the deepest: a round-off apart under
    # mpirun must not change which point is reported)
    deep = int(np.flatnonzero(depth >= depth.max() - NEAREST_TIE * np.abs(depth).max())[0])
    ends = [free[0], free[-1]]
    if out["kind"] == "surface":
        a = float(((front - origin) @ u).max())
        c = float(0.5 * np.linalg.norm(front[0] - front[-1]))
        surface = ends
    else:
        # The ends keep their faces: the one nearer the start's a end is a's.
        e_a = ends[0] if faces["a_end"] == faces["end_points"][0] else ends[1]
        e_c = ends[1] if e_a == ends[0] else ends[0]
        fa = front[0] if np.linalg.norm(front[0] - X[e_a]) <= np.linalg.norm(front[-1] - X[e_a]) else front[-1]
        fc = front[-1] if fa is front[0] else front[0]
        a, c = float(np.linalg.norm(fa - origin)), float(np.linalg.norm(fc - origin))
        surface = [e_a, e_c]
    t = faces["thickness"]
    out.update({"a": a, "c": c, "a_over_c": a / c if c > 0 else None, "thickness": t, "a_over_t": a / t,
                "deepest": index[deep], "surface_points": [index[e] for e in surface], "faces": faces["faces"]})
    return out


def _arc(C: np.ndarray, closed: bool) -> tuple[np.ndarray, float]:
    Q = np.vstack([C, C[:1]]) if closed else C
    seg = np.linalg.norm(np.diff(Q, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    return s[:len(C)], float(s[-1])


def _project(C: np.ndarray, x: np.ndarray, closed: bool) -> float:
    """The arc length along the polyline C of the point nearest to x."""
    s, _ = _arc(C, closed)
    i, w = _nearest_on_polyline(C, x, closed)
    j = (i + 1) % len(C)
    seg = float(np.linalg.norm(C[j] - C[i]))
    return float(s[i] + w * seg)


__all__ = ["SurfaceGrowth", "FrontPoints", "life_growth", "front_element_size", "crack_shape"]
