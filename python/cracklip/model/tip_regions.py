"""Room around each crack tip on the mesh: element size at the tip, what a domain
must stay clear of, and the SIF domains each tip has room for.

For every tip:

- the element size at the tip (the mean edge of the cells around the node
  nearest to it);
- what a domain must stay clear of: the part's boundary (holes
  included), the other tips, the other cracks, and the crack's own polyline
  beyond the straight run that ends at the tip (a kink of more than
  KINK_DEG degrees: the auxiliary fields assume a straight crack);
- the largest radius whose domain (every cell with a node inside the
  radius) stays clear of all of that, and the requested radius
  (Options.sif_radius, default DEFAULT_ELEMENTS element sizes) clipped to it;
  K is computed on DOMAIN_FRACTIONS of it (cracklip.fracture.sif);
- or, for a ring as another code defines it (Options.sif_ring: q = 1
  within r_in, 0 beyond r_out), that one ring as given, not clipped, with
  a warning when it reaches what a domain must stay clear of.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import InputError
from ..scene.cell_size import mean_cell_size
from ..scene.options import check_ring
from ..scene.processes import reduced
from .boundary import boundary_segments


#: Default radius of the largest domain, in element sizes at the tip.
DEFAULT_ELEMENTS = 6.0


#: The domains' radii as fractions of the largest.
DOMAIN_FRACTIONS = (0.5, 0.75, 1.0)


#: A turn of the crack polyline by more than this (degrees) is a kink that a
#: domain must not hold.
KINK_DEG = 1.0


#: Gauss points per crack segment for the lip term.
LIP_POINTS = 8


#: The admissible radius stops this fraction short of the node whose cell
#: reaches the obstacle: the domains' q (1 at nodes closer than the radius)
#: is then 0 at that node whatever the round-off of its distance (the C++
#: domain computes it anew). At the node's exact distance q there was a
#: coin flip: K of a tip on the hole_fatigue path jumped 2.3e-4 for a tip
#: moved by 2.5e-15, and 2-process growth paths left the serial ones.
RADIUS_MARGIN = 1e-9


@dataclasses.dataclass
class TipDomain:
    """The SIF domains of one tip.

    Attributes:
        crack, tip: crack index and tip index within the crack.
        position, direction: the tip and its unit direction e1 (2,).
        orientation: +1 if e2 points to the crack's + side (see CrackGeometry).
        element_size: mean edge length of the cells around the node nearest to the tip.
        clearance: distance from the tip to the nearest thing a domain must avoid.
        obstacle: what that is (e.g. "the boundary", "tip 1 of crack 'a'").
        admissible: the largest radius whose domain stays clear of it.
        radius: the largest domain's radius used.
        radii: the radii of the domains, increasing.
        requested: Options.sif_radius (or a caller's radius), None for the default.
        clear: False when no domain of at least one element fits (K is then
            computed on the smallest domain around the tip and is not reliable),
            or when a ring reaches the obstacle.
        warnings: messages about this tip's domains.
        inner_radius: None for cracklip's plateau q (1 within the radius); for
            a ring (Options.sif_ring) its r_in: q = 1 within it, 0 beyond
            radius (= r_out, the only entry of radii), linear between.
    """
    crack: int
    tip: int
    position: np.ndarray
    direction: np.ndarray
    orientation: int
    element_size: float
    clearance: float
    obstacle: str
    admissible: float
    radius: float
    radii: tuple[float, ...]
    requested: float | None
    clear: bool
    warnings: list[str] = dataclasses.field(default_factory=list)
    inner_radius: float | None = None

    @property
    def limited(self) -> bool:
        """Whether the obstacle made the domain smaller than asked."""
        wanted = self.requested if self.requested else DEFAULT_ELEMENTS * self.element_size
        return self.radius < wanted * (1.0 - 1e-12)


def segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances from p (2,) to segments a-b (m, 2), (m, 2)."""
    d = b - a
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / dd, 0.0, 1.0)
    return np.linalg.norm(a + t[:, None] * d - p, axis=1)


def straight_runs(points: np.ndarray, kink_deg: float = KINK_DEG) -> list[np.ndarray]:
    """The polyline split at its kinks (turns above kink_deg): a list of
    vertex-index arrays, each a straight run (consecutive runs share a vertex)."""
    d = np.diff(points, axis=0)
    ang = np.arctan2(d[:, 1], d[:, 0])
    turn = np.abs((np.diff(ang) + np.pi) % (2 * np.pi) - np.pi)
    kinks = np.flatnonzero(turn > np.radians(kink_deg)) + 1  # vertex indices
    bounds = [0, *kinks.tolist(), len(points) - 1]
    return [np.arange(bounds[i], bounds[i + 1] + 1) for i in range(len(bounds) - 1)]


def model_boundary(model) -> tuple[np.ndarray, np.ndarray]:
    seg = getattr(model, "_boundary_cache", None)
    if seg is None:
        seg = boundary_segments(model.scene.mesh)
        model._boundary_cache = seg
    return seg


def _obstacles(model, crack: int, tip: int) -> list[tuple[float, str]]:
    """(distance, description) of everything a domain at this tip must avoid."""
    g = model.geometries[crack]
    p = np.asarray(g.tips)[tip]
    out: list[tuple[float, str]] = []
    a, b = model_boundary(model)
    out.append((float(segment_distance(p, a, b).min()), "the boundary of the part"))
    names = [cm.crack.name for cm in model.cracks]
    for ci, cm in enumerate(model.cracks):
        tips = np.asarray(cm.geometry.tips).reshape(-1, 2)
        for j, q in enumerate(tips):
            if ci == crack and j == tip:
                continue
            out.append((float(np.linalg.norm(q - p)), f"tip {j} of crack {names[ci]!r} at "
                                                       f"({q[0]:.6g}, {q[1]:.6g})"))
        pts = cm.crack.points
        if ci != crack:
            out.append((float(segment_distance(p, pts[:-1], pts[1:]).min()), f"crack {names[ci]!r}"))
            continue
        # The crack itself beyond the straight run ending at this tip.
        end = 0 if np.linalg.norm(pts[0] - p) <= np.linalg.norm(pts[-1] - p) else len(pts) - 1
        runs = straight_runs(pts)
        run = runs[0] if end == 0 else runs[-1]
        rest = np.setdiff1d(np.arange(len(pts) - 1), run[:-1])  # segment indices off the run
        if rest.size:
            kink = pts[run[-1]] if end == 0 else pts[run[0]]
            d = float(segment_distance(p, pts[rest], pts[rest + 1]).min())
            out.append((d, f"the kink of crack {names[ci]!r} at ({kink[0]:.6g}, {kink[1]:.6g})"))
    return out


def node_distances(model, p: np.ndarray) -> np.ndarray:
    return np.linalg.norm(model.x - p, axis=1)


#: Nodes whose distances to a point agree to this relative tolerance are tied
#: for the nearest (tip_element_size, analysis.front_growth.
#: front_element_size): a tie is decided by the nodes themselves, not by their
#: numbering, so that one and several processes pick alike.
NEAREST_TIE = 1e-9


def tip_element_size(model, p: np.ndarray, dist: np.ndarray | None = None) -> float:
    """Mean edge length of the cells around the node nearest to point p; of
    nodes tied for the nearest (NEAREST_TIE), the smallest such mean
    (collective on a distributed model: the nearest owned node of all
    processes, whose patch its owner holds whole)."""
    dist = node_distances(model, p) if dist is None else dist
    if model.distributed:
        dist = dist[:model.V.dofmap.index_map.size_local]
    best = (math.inf, math.inf)
    if dist.size:
        d0 = float(dist.min())
        sizes = []
        for node in np.flatnonzero(dist <= d0 * (1.0 + NEAREST_TIE)):
            cells = model.cells[np.any(model.cells == node, axis=1)]
            sizes.append(mean_cell_size(model.x, cells) if len(cells) else math.inf)
        best = (d0, min(sizes))
    found = model.V.mesh.comm.allgather(best) if model.distributed else [best]
    d0 = min(d for d, _ in found)
    return min(size for d, size in found if d <= d0 * (1.0 + NEAREST_TIE))


def nearest_node_distance(model, dist: np.ndarray) -> float:
    """The smallest of the nodes' distances (over every process)."""
    d = float(dist.min()) if dist.size else math.inf
    return reduced(d, "MIN", model.V.mesh.comm) if model.distributed else d


def admissible_radius(model, dist: np.ndarray, clearance: float) -> float:
    """Largest radius r such that every cell with a node closer than r to the
    tip has all its nodes closer than `clearance` (the domain's cells stay
    clear of the obstacle), RADIUS_MARGIN short of the first node whose
    cell does not."""
    return _first_reaching(model, dist, clearance) * (1.0 - RADIUS_MARGIN)


def _first_reaching(model, dist: np.ndarray, clearance: float) -> float:
    dc = dist[model.cells]
    dmin, dmax = dc.min(axis=1), dc.max(axis=1)
    near = dmin < clearance
    dmin, dmax = dmin[near], dmax[near]
    if model.distributed:
        # = the smallest dmin of a near cell reaching the clearance: a minimum over processes
        reach = dmin[dmax >= clearance]
        local = float(reach.min()) if reach.size else math.inf
        return min(float(reduced(local, "MIN", model.V.mesh.comm)), float(clearance))
    order = np.argsort(dmin, kind="stable")
    reach = np.maximum.accumulate(dmax[order])
    bad = np.flatnonzero(reach >= clearance)
    return float(dmin[order][bad[0]]) if bad.size else float(clearance)


def tip_domains(model, crack: int, requested: float | None = None,
                ring: tuple[float, float] | None = None) -> list[TipDomain]:
    """The SIF domains of every tip of a crack. requested: the largest
    domain's radius (None or 0: Options.sif_radius, else DEFAULT_ELEMENTS
    element sizes). ring: (r_in, r_out), one ring taken as given (not
    clipped; see Options.sif_ring); without requested or ring,
    Options.sif_ring if set."""
    if requested is not None and not (isinstance(requested, (int, float, np.floating))
                                      and math.isfinite(requested) and requested > 0.0):
        raise InputError(f"the SIF domain radius must be a finite number > 0, got {requested!r}")
    if requested is not None and ring is not None:
        raise InputError("give a SIF domain radius or a ring (r_in, r_out), not both")
    if requested is None and ring is None:
        ring = model.scene.options.sif_ring
    if ring is not None:
        ring = check_ring(ring, "the SIF ring")
    if requested is None:
        requested = model.scene.options.sif_radius or None
    g = model.geometries[crack]
    tips = np.asarray(g.tips).reshape(-1, 2)
    name = model.cracks[crack].crack.name
    out = []
    for j, p in enumerate(tips):
        dist = node_distances(model, p)
        h = tip_element_size(model, p, dist)
        obstacles = _obstacles(model, crack, j)
        clearance, obstacle = min(obstacles, key=lambda o: o[0])
        admissible = admissible_radius(model, dist, clearance)
        wanted = float(requested) if requested else DEFAULT_ELEMENTS * h
        where = f"tip {j} of crack {name!r} at ({p[0]:.6g}, {p[1]:.6g})"
        warnings = []
        if ring is not None:
            r_in, r_out = ring
            clear = r_out <= admissible
            if not clear:
                warnings.append(
                    f"{where}: the SIF ring [{r_in:.4g}, {r_out:.4g}] reaches {obstacle} ({clearance:.3g} away; "
                    f"domains up to radius {admissible:.3g} stay clear of it); K on this ring is taken as asked "
                    "and is NOT reliable: a smaller ring, or options.sif_ring unset (cracklip's domains)")
            out.append(TipDomain(crack, j, p.copy(), np.asarray(g.tip_tangents).reshape(-1, 2)[j].copy(),
                                 int(np.asarray(g.tip_orientation)[j]), h, clearance, obstacle, admissible,
                                 r_out, (r_out,), r_out, clear, warnings, r_in))
            continue
        # The smallest usable radius: one element, and the smallest domain
        # (DOMAIN_FRACTIONS[0] of it) must hold the node nearest to the tip.
        least = max(h, 1.01 * nearest_node_distance(model, dist) / DOMAIN_FRACTIONS[0])
        clear = admissible >= least
        if not clear:
            radius = least
            warnings.append(
                f"{where}: no SIF domain of at least one element ({h:.3g}) fits between the tip and "
                f"{obstacle} ({clearance:.3g} away); K there is computed on a domain of radius "
                f"{radius:.3g} that reaches it and is NOT reliable: refine the mesh at the tip "
                "(mesh.tip_h) or move the crack")
        elif wanted < least:
            radius = least
            warnings.append(f"{where}: sif_radius {wanted:.3g} is below one element ({h:.3g}) there; K uses "
                            f"domains up to radius {radius:.3g}")
        else:
            radius = min(wanted, admissible)
            if radius < wanted * (1.0 - 1e-12):
                asked = f"sif_radius {wanted:.4g}" if requested else \
                    f"the default SIF domain ({DEFAULT_ELEMENTS:g} elements, {wanted:.3g})"
                warnings.append(
                    f"{where}: {asked} would reach {obstacle} ({clearance:.3g} away); K uses domains up to "
                    f"radius {radius:.3g} ({radius / h:.1f} elements of {h:.3g})"
                    + (": fewer than 3 elements, refine the mesh at the tip (mesh.tip_h)" if radius < 3 * h else ""))
        radii = tuple(float(f * radius) for f in DOMAIN_FRACTIONS)
        out.append(TipDomain(crack, j, p.copy(), np.asarray(g.tip_tangents).reshape(-1, 2)[j].copy(),
                             int(np.asarray(g.tip_orientation)[j]), h, clearance, obstacle, admissible,
                             float(radius), radii, float(requested) if requested else None, clear,
                             warnings))
    return out


def lip_points(model, crack: int):
    """The crack's lip points of the SIFs' lip terms (LIP_POINTS per segment), computed once."""
    return model.cracks[crack].lip_points(model, LIP_POINTS)


def part_size(model) -> float:
    """The part's size: the largest side of its bounding box (collective
    under mpirun: every process's nodes, not its own part of the mesh)."""
    lo, hi = model.x.min(axis=0), model.x.max(axis=0)
    if model.distributed:
        lo, hi = reduced(lo, "MIN", model.V.mesh.comm), reduced(hi, "MAX", model.V.mesh.comm)
    return float((hi - lo).max())


def length_in_part(model, crack: int) -> float:
    """The length (2D; area in 3D) of a crack inside the part: its lip
    points' weights summed exactly rounded (math.fsum: the same whatever
    their order; collective under mpirun: every process's owned cells'
    weights). The tip checks compare it with distances (a crack as long as
    its tip is far from the boundary): the same bits on any number of
    processes."""
    pts = lip_points(model, crack)
    w = np.asarray(pts["weight"], dtype=float)
    if model.distributed:
        w = np.concatenate(model.V.mesh.comm.allgather(w[model.owned_cells_only(pts["cell"])]))
    return math.fsum(w.tolist())
