"""The points along a 3D crack front where K is computed, and their SIF
domains (fracture/sif_3d.py computes the domain integrals there;
fracture/front_sampling.py places the points and gives the ends' values).

Front points. Each piece of a crack's front (a closed loop, or an open
polyline between two points of the part's boundary) carries front points at
arc-length steps of about HAT_ELEMENTS element sizes, shortened to the
front's radius of curvature where that is smaller (HAT_CURVATURE; a loop: n
steps round it; an open piece: both ends included). A point's frame (e1
propagation, e2 normal, e3 tangent) is interpolated along the front
(fracture/front.py). The hat of a point (its q along the front) spans its
neighbours.

Domains. The radius of the largest domain is sif_radius, else
DEFAULT_ELEMENTS element sizes at the point (the mean edge of the front's
cells within the hat), clipped so that the domain stays clear of the part's
boundary (except, at a point where the front meets the boundary, the free
surface it meets: K there is reported and flagged free_surface, since the
singularity is no longer the square root of the Williams fields), of other
cracks and of the front itself where it comes back (a thin crack), and
within CURVATURE_FRACTION of the radii of curvature of the front and of the
crack's surface. K is computed on DOMAIN_FRACTIONS of that radius.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import scipy.spatial

from ..errors import InputError
from ..model.checks import CodedText
from ..scene.processes import reduced
from ..scene.symmetry import SymmetryCondition
from . import front_sampling
from .front import (FIT_TURN, Front, all_points, boundary_nodes, crack_front, model_comm, owned_lip_points, project,
                    wrap)


#: Default radius of the largest domain, in element sizes at the front point.
DEFAULT_ELEMENTS = 4.0

#: The scene keys that size the elements at a front, as the warnings name them.
REFINE_AT_FRONT = "mesh.tip_h, or the h of a [[mesh.refine]] entry there"


#: The domains' radii as fractions of the largest.
DOMAIN_FRACTIONS = (0.5, 0.75, 1.0)


#: Distance between neighbouring front points (the hat's half-width), in
#: element sizes at the front (mean edges of the front's cells). Penny crack
#: at a/h = 20: scatter of K_I along the front +-0.6 % with 1, +-0.2 % with
#: 2, +-0.08 % with 3; K_II, K_III 4.8e-3, 1.2e-3, 8.6e-4 of K.
HAT_ELEMENTS = 3.0


#: Where the front curves strongly the hat's half-width also stays below
#: HAT_CURVATURE radii of curvature rho of the front (rho from the largest
#: |kappa| within the element-size hat of the point), but not below
#: MIN_HAT_ELEMENTS element sizes: the front points are spaced by the local
#: half-width l(s) = clip(HAT_CURVATURE rho, MIN_HAT_ELEMENTS h,
#: HAT_ELEMENTS h) (equal steps of the integral of ds / l), so that K does
#: not vary much more across a hat than the hat correction can remove.
#: Irwin ellipse b/a = 0.25 (rho = b^2/a at the ends of the major axis: 1.75,
#: 2.5, 3.5 elements at h = b/7, b/10, b/14; there the fixed hat spans 40
#: degrees of parametric angle where K falls by a quarter), max error with
#: fixed hats -> with these: 2.54 -> 2.99 % at b/7, 1.75 -> 1.27 % at b/10,
#: 0.91 -> 0.76 % at b/14 (both with the hat correction below); a fraction
#: 0.75 gave 1.20 % / 0.87 %. Fronts with rho >= HAT_ELEMENTS h everywhere
#: (the penny at a/10 and finer) keep equal steps.
HAT_CURVATURE = 1.0


#: Hats narrower than 2 elements scatter (penny, HAT_ELEMENTS above: +-0.6 %
#: at 1 element); Irwin b/a = 0.25 at b/7: max 3.36 % with a floor of 1, 2.99
#: % with 2 (K_II, K_III noise 1.3 % -> 1.0 %).
MIN_HAT_ELEMENTS = 2.0


#: Options.sif_points shortens the hats to this many element sizes at most:
#: on a coarse front 16 points would make two-element hats, whose K runs
#: low (penny at a/4, 12 points of 2.1 elements: K_I 4.5 % low at every
#: point; 8 points of 3.1 elements: -0.8 .. +0.4 %).
COUNT_HAT_ELEMENTS = HAT_ELEMENTS


#: A domain's radius stays below this fraction of the smallest radius of
#: curvature of the front and of the crack's surface (1 / max(|kappa_f|,
#: |kappa_11|, |kappa_33|): the curvature terms hold for h = 1 + kappa_f x1
#: - kappa_33 x2 > 0, the surface-following coordinates while the quadric
#: describes the surface; the change of the curvatures along the front is
#: not kept).
CURVATURE_FRACTION = 0.75


@dataclasses.dataclass
class FrontPoint:
    """A point of a crack's front where K is computed, with its domains.

    Attributes:
        crack, index: crack index, index of the point along the crack's front
            (piece after piece).
        piece: the front piece (CrackGeometry3D.front piece_offsets).
        closed: whether the piece is a loop.
        s: arc length from the start of the piece; length: the piece's length.
        x: (3,) the point, on the front polyline.
        frame: (3, 3) rows e1 (propagation), e2 (normal), e3 (tangent).
        hat: the larger distance to the neighbouring front points (the hat's
            half-width); hat_before, hat_after: the distances to the previous
            and the next one (the hat is 1 at the point, 0 at both).
        curvature: the front's curvature there (1/a on a penny of radius a).
        element_size: mean edge of the front's cells within the hat.
        free_surface: the point is an end of an open piece on the part's
            boundary (a surface crack meeting a free face), not on a
            symmetry plane.
        clearance, obstacle: distance to what the domain must avoid and what.
        radius, radii: the largest domain's radius, all radii (increasing).
        requested: the radius asked for (None: the default).
        clear: False when no domain of one element fits.
        warnings: messages about this point's domains.
        symmetry: the label of the symmetry plane the point (an end) lies
            on, else None (front_sampling: its domain is mirrored).
        requested_position: the point is at a position asked for
            (Options.sif_angles, sif_angle_step, sif_arc_lengths).
        source: where its K comes from (front_sampling.SOURCES).
        K_domain: a free-surface end's own domain K (domains, 3) when its K
            is the end value (front_sampling), else None.
    """
    crack: int
    index: int
    piece: int
    closed: bool
    s: float
    length: float
    x: np.ndarray
    frame: np.ndarray
    hat: float
    curvature: float
    element_size: float
    free_surface: bool
    clearance: float
    obstacle: str
    radius: float
    radii: tuple[float, ...]
    requested: float | None
    clear: bool
    warnings: list[str] = dataclasses.field(default_factory=list)
    hat_before: float = 0.0
    hat_after: float = 0.0
    symmetry: str | None = None
    requested_position: bool = False
    source: str = "domain"
    K_domain: np.ndarray | None = None

    def __post_init__(self):
        self.hat_before = self.hat_before or self.hat
        self.hat_after = self.hat_after or self.hat

    @property
    def limited(self) -> bool:
        wanted = self.requested if self.requested else DEFAULT_ELEMENTS * self.element_size
        return self.radius < wanted * (1.0 - 1e-12)


def hat_lengths(curvature: np.ndarray, h: float) -> np.ndarray:
    """The hat's half-width wanted where the front has these curvatures
    (element size h): HAT_CURVATURE / |kappa| clipped to [MIN_HAT_ELEMENTS h,
    HAT_ELEMENTS h]."""
    kap = np.abs(np.asarray(curvature, dtype=float))
    rho = np.where(kap > 0.0, HAT_CURVATURE / np.maximum(kap, 1e-300), np.inf)
    return np.clip(rho, MIN_HAT_ELEMENTS * h, HAT_ELEMENTS * h)


def wanted_hats(s: np.ndarray, curvature: np.ndarray, h: float, length: float, closed: bool) -> np.ndarray:
    """hat_lengths at vertices s of a piece from the largest |curvature|
    within HAT_ELEMENTS h of each (the hat a point there would span)."""
    s, kv = np.asarray(s, dtype=float), np.abs(np.asarray(curvature, dtype=float))
    ds = np.abs(s[:, None] - s[None, :])
    if closed:
        ds = np.minimum(ds, length - ds)
    kmax = np.where(ds <= HAT_ELEMENTS * h, kv[None, :], 0.0).max(axis=1)
    return hat_lengths(kmax, h)


def station_positions(s: np.ndarray, l: np.ndarray, length: float, closed: bool, minimum: int = 1) -> np.ndarray:
    """Arc lengths of front points along a piece whose vertices at s (from
    0, increasing) want half-widths l: equal steps of int ds / l (a loop
    from s = 0 round to length, an open piece with both ends)."""
    s, l = np.asarray(s, dtype=float), np.asarray(l, dtype=float)
    if closed:
        s, l = np.append(s, length), np.append(l, l[0])
    dens = 1.0 / l
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (dens[1:] + dens[:-1]) * np.diff(s))])
    if not closed and s[-1] < length:  # the last vertex short of the end
        cum = np.append(cum, cum[-1] + dens[-1] * (length - s[-1]))
        s = np.append(s, length)
    n = max(minimum, int(round(cum[-1])))
    targets = np.arange(n) * (cum[-1] / n) if closed else np.linspace(0.0, cum[-1], n + 1)
    out = np.interp(targets, cum, s)
    if not closed:
        out[0], out[-1] = 0.0, length
    return out


def symmetry_planes(model) -> list:
    """The scene's symmetry planes (cracklip.scene.symmetry.SymmetryCondition)."""
    return [bc for bc in model.scene.dirichlet if isinstance(bc, SymmetryCondition)]


def _end_plane(model, x: np.ndarray, h: float):
    """The symmetry plane a front end at x lies on (within half an element), or None."""
    for bc in symmetry_planes(model):
        if abs(float((x - np.asarray(bc.origin)) @ np.asarray(bc.normal))) <= 0.5 * h:
            return bc
    return None


def stations(model, crack: int, spacing: float | None) -> tuple[list[dict], list[dict], list[str]]:
    """Front points along every piece (front_sampling.piece_stations): piece,
    s, closed, length, hat, hat_before, hat_after, end, end_on_boundary,
    symmetry (the label of the plane an end lies on, else None), requested;
    the requested positions between front points (piece, s, closed,
    length); notes on positions that could not be used."""
    fr = crack_front(model, crack)
    h = float(np.median(fr.segment_size)) if len(fr.segment_size) else 0.0
    opts = model.scene.options
    floor = MIN_HAT_ELEMENTS * h if not spacing else min(MIN_HAT_ELEMENTS * h, spacing)
    crk = model.cracks[crack].crack
    out, between_all, notes_all, pieces = [], [], [], []
    for k in range(len(fr.closed)):
        L = float(fr.length[k])
        if L <= 0.0:
            continue
        closed = bool(fr.closed[k])
        idx = np.arange(fr.offsets[k], fr.offsets[k + 1])
        sv = fr.s[idx]
        pieces.append((fr.x[idx], sv, L, closed, 0.5 * h))
        if spacing or HAT_CURVATURE <= 0.0 or len(idx) < 3:
            wanted = np.full(len(idx), spacing if spacing else HAT_ELEMENTS * h)
        else:
            wanted = wanted_hats(sv, fr.curvature[idx], h, L, closed)
        asked, notes = front_sampling.requested_positions(opts, crk, fr.x[idx], sv, L, closed, 0.5 * h)
        notes_all += [n_ for n_ in notes if n_ not in notes_all]
        svals, requested, between = front_sampling.piece_stations(sv, wanted, L, closed, floor, opts.sif_points,
                                                                  asked, 0.0 if spacing else COUNT_HAT_ELEMENTS * h)
        n = len(svals)
        if closed:
            before = (svals - np.roll(svals, 1)) % L
            after = (np.roll(svals, -1) - svals) % L
            if n == 1:
                before = after = np.array([L])
        else:
            gaps = np.diff(svals)
            before = np.concatenate([gaps[:1], gaps])
            after = np.concatenate([gaps, gaps[-1:]])
        planes = [None, None]
        if not closed:
            for e, v in enumerate((fr.offsets[k], fr.offsets[k + 1] - 1)):
                if fr.on_boundary[v]:
                    planes[e] = _end_plane(model, fr.x[v], h)
        for j, sv_ in enumerate(svals):
            end = (not closed) and (j == 0 or j == n - 1)
            on_boundary = end and bool(fr.on_boundary[fr.offsets[k] if j == 0 else fr.offsets[k + 1] - 1])
            plane = planes[0 if j == 0 else 1] if on_boundary else None
            out.append({"piece": k, "s": float(sv_), "closed": closed, "length": L,
                        "hat": float(max(before[j], after[j])), "hat_before": float(before[j]),
                        "hat_after": float(after[j]), "end": end, "end_on_boundary": on_boundary,
                        "symmetry": None if plane is None else plane.label, "requested": bool(requested[j])})
        between_all += [{"piece": k, "s": float(b), "closed": closed, "length": L} for b in between]
    notes_all += [n_ for n_ in front_sampling.unmatched_positions(opts, crk, pieces) if n_ not in notes_all]
    return out, between_all, notes_all


def point_at(fr: Front, piece: int, s: float) -> np.ndarray:
    idx = np.arange(fr.offsets[piece], fr.offsets[piece + 1])
    xs, ss = fr.x[idx], fr.s[idx]
    if fr.closed[piece]:
        xs = np.vstack([xs, xs[:1]])
        ss = np.concatenate([ss, [fr.length[piece]]])
    return np.array([np.interp(s, ss, xs[:, i]) for i in range(3)])


def front_points(model, crack: int, requested: float | None = None, spacing: float | None = None
                 ) -> list[FrontPoint]:
    """The front points of a crack and their SIF domains (module doc).
    requested: the largest domain's radius (None or 0: Options.sif_radius,
    else DEFAULT_ELEMENTS element sizes at each point); spacing: distance
    between front points (default HAT_ELEMENTS element sizes)."""
    if requested is not None and not (isinstance(requested, (int, float, np.floating))
                                      and math.isfinite(requested) and requested > 0.0):
        raise InputError(f"the SIF domain radius must be a finite number > 0, got {requested!r}")
    if requested is None:
        requested = model.scene.options.sif_radius or None
    fr = crack_front(model, crack)
    if fr.segments.size == 0:
        return []
    name = model.cracks[crack].crack.name
    st, _, notes = stations(model, crack, spacing)
    notes = [CodedText(n, "sif_points", crack) for n in notes] + [CodedText(n, "sif_domain", crack)
                                                                  for n in _kink_notes(fr, name)]
    pr = project(model, crack, np.array([point_at(fr, d["piece"], d["s"]) for d in st]))
    sizes = _HatSizes(fr)
    obstacles = _Obstacles(model, crack, fr, st, requested)
    out = []
    for k, d in enumerate(st):
        xk = pr["x"][k]
        where = f"front point {k} of crack {name!r} at ({xk[0]:.6g}, {xk[1]:.6g}, {xk[2]:.6g})"
        h = sizes.at(d)
        wanted = float(requested) if requested else DEFAULT_ELEMENTS * h
        clearance, obstacle, distance = obstacles.nearest(d, xk, h, wanted)
        radius, clear, warnings = _domain_radius(where, h, wanted, clearance, obstacle, distance)
        warnings = [CodedText(w, "sif_domain", crack, k) for w in warnings]
        out.append(FrontPoint(crack, k, d["piece"], d["closed"], d["s"], d["length"], xk.copy(), pr["frame"][k].copy(),
                              d["hat"], float(pr["curvature"][k]), h,
                              bool(d["end_on_boundary"]) and d["symmetry"] is None, float(clearance), obstacle,
                              float(radius), tuple(float(f * radius) for f in DOMAIN_FRACTIONS),
                              float(requested) if requested else None, clear, warnings, d["hat_before"],
                              d["hat_after"], symmetry=d["symmetry"], requested_position=d["requested"],
                              source="mirrored_domain" if d["symmetry"] else "domain"))
    if out:
        out[0].warnings[:0] = notes
    return out


def _kink_notes(fr: Front, name: str) -> list[str]:
    """The warning about a triangulated surface's vertices where the fit was
    not kept (FIT_TURN), if any."""
    if fr.unfitted is None or not np.any(fr.unfitted):
        return []
    bad = np.flatnonzero(fr.unfitted)
    return [f"crack {name!r}: the triangulated surface is kinked near {len(bad)} front vertices (arc lengths "
            f"{fr.s[bad].min():.4g} .. {fr.s[bad].max():.4g}): a smooth fit through it turned the normal by up to "
            f"{fr.fit_turn[bad].max():.0f} degrees from the mesh's there (more than {FIT_TURN:g}); those vertices "
            "keep the mesh's frame and the front's own curvature, the surface's curvatures taken as 0"]


class _HatSizes:
    """The element size at a front point: the mean size of the front's own
    segments within its hat (all of its piece's if none)."""

    def __init__(self, fr: Front):
        self.fr = fr
        self.mid_s = 0.5 * (fr.s[fr.segments[:, 0]] + fr.s[fr.segments[:, 1]])
        self.length = np.linalg.norm(fr.x[fr.segments[:, 1]] - fr.x[fr.segments[:, 0]], axis=1)
        for k in np.flatnonzero(fr.closed):  # a loop's closing segment: its middle arc length
            last = fr.offsets[k + 1] - 1
            closing = np.flatnonzero((fr.segments[:, 0] == last) & (fr.segments[:, 1] == fr.offsets[k]))
            self.mid_s[closing] = fr.s[last] + 0.5 * self.length[closing]
        self.piece = fr.piece[fr.segments[:, 0]]

    def at(self, d: dict) -> float:
        """d: a station (stations())."""
        in_hat = (self.piece == d["piece"]) & (np.abs(wrap(self.mid_s - d["s"], d["length"], d["closed"]))
                                              <= d["hat"] + 0.5 * self.length)
        if not np.any(in_hat):
            in_hat = self.piece == d["piece"]
        return float(np.mean(self.fr.segment_size[in_hat]))


class _Obstacles:
    """What a front point's domains must stay clear of (module doc): the
    front's and the crack surface's curvature, the part's boundary near the
    front (but the free surface a piece ends on and the symmetry planes it
    ends on), other cracks' lips and fronts, and the front itself where it
    comes back. Gathered once per crack (every process's points under MPI)."""

    def __init__(self, model, crack: int, fr: Front, st: list[dict], requested: float | None):
        self.fr, self.name = fr, model.cracks[crack].crack.name
        wanted_max = max(requested or 0.0, DEFAULT_ELEMENTS * float(fr.segment_size.max()))
        reach = wanted_max + 2.0 * max(d["hat"] for d in st) + float(fr.segment_size.max())
        bnodes = boundary_nodes(model)
        near_b = np.unique(np.concatenate([np.asarray(i, dtype=np.int64) for i in
                                           scipy.spatial.cKDTree(model.x[bnodes]).query_ball_point(fr.x, reach)]
                                          + [np.zeros(0, np.int64)])) if bnodes.size else np.zeros(0, np.int64)
        bx = all_points(model, model.x[bnodes[near_b]])  # (every process's under MPI)
        self.boundary = project(model, crack, bx) if len(bx) else None
        # A symmetry plane that a piece ends on is no obstacle of that piece's
        # domains: they continue in the mirror image.
        lo, hi = model.x.min(axis=0), model.x.max(axis=0)
        if model_comm(model) is not None:
            lo, hi = reduced(lo, "MIN", model_comm(model)), reduced(hi, "MAX", model_comm(model))
        size = float((hi - lo).max())
        self.mirror_of = {}
        for bc in symmetry_planes(model):
            on = np.abs((bx - np.asarray(bc.origin)) @ np.asarray(bc.normal)) <= 1e-9 * size
            pieces = {d["piece"] for d in st if d["symmetry"] == bc.label}
            self.mirror_of[bc.label] = (on, pieces)
        self.others = [(model.cracks[ci].crack.name,
                        np.vstack([all_points(model, owned_lip_points(model, ci)),
                                   np.asarray(model.geometries[ci].front["x"])]))
                       for ci in range(len(model.cracks)) if ci != crack]

    def nearest(self, d: dict, xk: np.ndarray, h: float, wanted: float) -> tuple[float, str, float]:
        """(clearance: the largest radius clear of the nearest obstacle, what
        it is, its distance) for the station d at xk, element size h, the
        radius wanted (inf, "", inf: none)."""
        fr, piece, s0, hat, L = self.fr, d["piece"], d["s"], d["hat"], d["length"]
        # The curvature of the front wherever the domain's points may project:
        # the front within its reach (the hat, the radius, an element).
        near = (fr.piece == piece) & (np.linalg.norm(fr.x - xk, axis=1) <= hat + wanted + 2.0 * h)
        kap = float(np.abs(fr.curvatures[near, :3]).max()) if np.any(near) else 0.0
        obstacles = []
        if kap > 0:
            room = min(CURVATURE_FRACTION / kap, 0.95 / kap - h)
            obstacles.append((room, f"{CURVATURE_FRACTION:g} of the smallest radius of curvature of the front and "
                                    f"the crack's surface ({1 / kap:.3g})", room))
        b = self.boundary
        if b is not None:
            ds = wrap(b["s"] - s0, L, d["closed"])
            hit = (b["piece"] == piece) & (np.clip(1.0 - np.abs(ds) / hat, 0.0, 1.0) >= 0.05)
            if d["end_on_boundary"]:  # the free surface the front meets is not an obstacle
                end_s = 0.0 if s0 == 0.0 else L
                hit &= np.abs(b["s"] - end_s) > h
            for on, pieces in self.mirror_of.values():
                if piece in pieces:
                    hit &= ~on
            if np.any(hit):
                k = int(np.argmin(np.where(hit, b["distance"], np.inf)))
                dist = float(b["distance"][k])
                # the boundary toward an end of the front within this point's hat: the surface the front ends on
                ends = [] if d["closed"] else [e for e in (0.0, L) if 0.0 < abs(e - s0) <= hat]
                toward_end = any((float(b["s"][k]) - s0) * (e - s0) > 0.0 for e in ends)
                obstacles.append((dist - h, "the surface the front ends on (its end is within this point's hat: "
                                            "more points along the front, finer there)" if toward_end else
                                  "the boundary of the part", dist))
        for other, pts in self.others:
            dist = float(np.linalg.norm(pts - xk, axis=1).min())
            obstacles.append((dist - hat - h, f"crack {other!r}", dist))
        # The own front where it comes back (a thin crack): front vertices
        # off the hat whose distance is less than their arc-length distance.
        own = fr.piece == piece
        dso = np.abs(wrap(fr.s[own] - s0, L, d["closed"]))
        dxo = np.linalg.norm(fr.x[own] - xk, axis=1)
        back = dso > hat + 2.0 * dxo
        if np.any(back):
            dist = float(dxo[back].min())
            obstacles.append((0.5 * (dist - hat), f"the opposite part of the front of crack {self.name!r}", dist))
        return min(obstacles, key=lambda o: o[0]) if obstacles else (math.inf, "", math.inf)


def _domain_radius(where: str, h: float, wanted: float, clearance: float, obstacle: str, distance: float
                   ) -> tuple[float, bool, list[str]]:
    """(the largest domain's radius, whether a domain of one element fits,
    warnings): the radius wanted within the clearance, at least two
    elements (the smallest domain, half the largest, spans an element)."""
    least = 2.0 * h
    if clearance < least:
        return least, False, [
            f"{where}: no SIF domain of at least one element ({h:.3g}) fits between the front and {obstacle} "
            f"({distance:.3g} away: room for a domain of radius {max(clearance, 0.0):.3g}, {least:.3g} needed); K "
            f"there is computed on a domain of radius {least:.3g} that reaches it and is NOT reliable: refine the "
            f"mesh at the front ({REFINE_AT_FRONT})"]
    if wanted < least:
        return least, True, [f"{where}: sif_radius {wanted:.3g} is below two elements ({h:.3g}) there; K uses "
                             f"domains up to radius {least:.3g}"]
    return min(wanted, clearance), True, []


__all__ = ["FrontPoint", "front_points", "stations", "point_at", "hat_lengths", "wanted_hats", "station_positions",
           "symmetry_planes", "DEFAULT_ELEMENTS", "REFINE_AT_FRONT", "DOMAIN_FRACTIONS", "HAT_ELEMENTS", "HAT_CURVATURE",
           "MIN_HAT_ELEMENTS", "COUNT_HAT_ELEMENTS", "CURVATURE_FRACTION"]
