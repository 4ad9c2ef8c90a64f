"""Stress intensity factors at the tips of 2D cracks: a domain chosen per tip,
K on three domains, and their spread (sif_3d.py does the fronts of 3D cracks:
the geometry differs, a disc around one point against hats along a curved
front; both give rows of one schema, SIF_KEYS).

For every tip this module

- measures the element size at the tip (the mean edge of the cells around
  the node nearest to it);
- finds what a domain must stay clear of: the part's boundary (holes
  included), the other tips, the other cracks, and the crack's own polyline
  beyond the straight run that ends at the tip (a kink of more than
  KINK_DEG degrees: the auxiliary fields assume a straight crack);
- takes the largest radius whose domain (every cell with a node inside the
  radius) stays clear of all of that, and clips the requested radius
  (Options.sif_radius, default DEFAULT_ELEMENTS element sizes) to it;
- computes K_I, K_II by the domain interaction integral on three domains
  (DOMAIN_FRACTIONS of the radius) with the lip term (tractions on the lips:
  contact pressure, lip pressure, an initial stress's sigma_0 n) and the
  body-force term (body force and div sigma_0), and reports K on the largest
  domain with the spread (max - min) over the three;
- or, with a ring (Options.sif_ring, or compute_sifs(ring=...)), computes K
  on that one annulus as another code defines it (q = 1 within r_in, 0
  beyond r_out, linear between: code_aster's R_INF / R_SUP, MOOSE's rings),
  not clipped: what it reaches is warned about (docs/growth.md shows what a
  ring through a hole does to K).

Conventions (docs/sifs.md, "Conventions"): the tip frame has e1 along the crack's
extension and e2 = e1 turned by +90 degrees; K_I > 0 opens the crack; K_II > 0
when the material on the e2 side of the crack moves along +e1 relative to the
other side behind the tip (the Williams mode-II field, cpp/enrichment/tip_functions_2d.h).
The interaction integral (q the plateau function, u^aux the auxiliary field
of unit K):

    I = int_A (sigma_ij u^aux_i,1 + sigma^aux_ij u_i,1 - sigma_kl eps^aux_kl delta_1j) q,_j dA
        - int_lips t_i u^aux_i,1 q ds - int_A b_i u^aux_i,1 q dA,      K = E* I / 2,

with sigma the stress of the displacement (C eps(u)), t the traction on each
lip and b the body force (plus div sigma_0).
"""
from __future__ import annotations

import logging
import math
import typing

import numpy as np

from .. import _cracklip
from ..errors import InputError
from ..model.checks import CodedText
from ..model.tip_regions import TipDomain, length_in_part, lip_points, node_distances, part_size, tip_domains
from ..scene.processes import reduced
from ..scene.stress_field import LinearStress, divergence
from .lip_tractions import lip_traction, lip_traction_parts


logger = logging.getLogger(__name__)


#: Spread (max - min over the domains) above this fraction of the K scale is warned about.
SPREAD_WARNING = 0.01


#: Gauss degree of the interaction integral in cells without tip functions:
#: the integrand (smooth, non-polynomial auxiliary fields) needs more than
#: the stiffness's rule.
SIF_DEGREE = 8


#: The keys of every SIF row (results.json "sifs"), tips and front points
#: alike: a 2D tip is a front of one point (piece = tip, s = 0), with None
#: where a key does not apply (K_III and its estimate, z, hat, curvature,
#: parametric_angle in 2D; tip, inner_radius and K extrapolated in 3D; the
#: error estimates without one, cracklip.analysis.accuracy).
SIF_KEYS = ("crack", "crack_name", "point", "tip", "piece", "s", "position", "x", "y", "z", "direction", "normal",
            "frame", "K_I", "K_II", "K_III", "K_I_spread", "K_II_spread", "K_III_spread", "K_I_error", "K_II_error",
            "K_III_error", "K_I_extrapolated", "K_II_extrapolated", "K_III_extrapolated", "K_I_levels", "K_II_levels",
            "K_III_levels", "mode_mix_deg", "G", "radius",
            "radii", "radius_min", "inner_radius", "element_size", "hat", "curvature", "parametric_angle",
            "limited_by", "free_surface", "domain_clear", "K_source", "requested", "symmetry", "K_domain")


def complete_rows(rows: list[dict[str, typing.Any]]) -> list[dict[str, typing.Any]]:
    """The rows with every key of SIF_KEYS (None where it does not apply),
    in that order."""
    return [{**{k: r.get(k) for k in SIF_KEYS}, **r} for r in rows]


def _aux_derivative(material, domain: TipDomain, x: np.ndarray, sides: np.ndarray) -> np.ndarray:
    """d u^aux / d x_1 (n, mode, component) of the unit-K auxiliary fields."""
    _, dU = _cracklip.williams_displacement(domain.position, domain.direction, material.kappa, x,
                                            np.asarray(sides, dtype=np.int8), domain.orientation)
    scale = 1.0 / (2.0 * material.mu * math.sqrt(2.0 * math.pi))
    return scale * np.einsum("nmij,j->nmi", dU, domain.direction)


def nodal_q(dist: np.ndarray, radius: float, inner_radius: float | None = None) -> np.ndarray:
    """q at nodes at distances dist from the tip, as the C++ domain_q: the
    plateau (1 closer than radius, else 0) without inner_radius (or with
    inner_radius >= radius), else the ring (1 within inner_radius, 0 from
    radius on, linear between)."""
    if inner_radius is None or inner_radius >= radius:
        return (dist < radius).astype(float)
    return np.clip((radius - dist) / (radius - inner_radius), 0.0, 1.0)


def _q_at(model, dist: np.ndarray, radius: float, cells: np.ndarray, ref: np.ndarray,
          inner_radius: float | None = None) -> np.ndarray:
    """q (nodal_q, interpolated by P1) at points (cell, ref)."""
    qn = nodal_q(dist, radius, inner_radius)[model.cells[cells]]
    N = np.stack([1.0 - ref[:, 0] - ref[:, 1], ref[:, 0], ref[:, 1]], axis=1)
    return np.einsum("na,na->n", N, qn)


def interaction_integrals(solution, domain: TipDomain, radius: float) -> np.ndarray:
    """(I_I, I_II) on the domain of one radius (a ring from domain.inner_radius
    to it if the domain has one): domain, lip and body-force terms."""
    m = solution.model
    mat = m.scene.material
    q_opts = m.scene.options.quadrature_options()
    q_opts.degree = max(q_opts.degree, SIF_DEGREE)
    body = body_force(solution)
    d = _cracklip.compute_domain_points(m.x, m.cells, m.layout, m.geometries, domain.position,
                                        domain.direction, radius, q_opts, body is not None, domain.inner_radius)
    distributed = m.distributed
    if distributed:  # each process its owned cells; the integrals summed below
        keep = m.owned_cells_only(d["cell"])
        d = {k: v[keep] for k, v in d.items()}
    if not (reduced(bool(np.any(d["grad_q"])), "LOR", m.V.mesh.comm) if distributed else np.any(d["grad_q"])):
        raise InputError(f"no cell crosses the SIF domain circle of radius {radius:.4g} around tip "
                         f"{domain.position.tolist()}: the q-function is constant; use a larger radius")
    _, grad = _cracklip.evaluate_displacement(m.x, m.cells, m.layout, m.geometries, solution.u,
                                              d["cell"], d["ref"], d["side"])
    I = np.asarray(_cracklip.interaction_integral(domain.position, domain.direction, mat.E_strain, mat.nu_strain,
                                                  d["x"], d["weight"], d["grad_q"], grad, d["side"],
                                                  domain.orientation))
    if body is not None:
        b = body(d["x"])
        daux = _aux_derivative(mat, domain, d["x"], d["side"])
        I = I - np.einsum("n,n,nmi,ni->m", d["weight"], d["q"], daux, b)
    pts = lip_points(m, domain.crack)
    if distributed:
        keep = m.owned_cells_only(pts["cell"])
        pts = {k: v[keep] for k, v in pts.items()}
    dist = node_distances(m, domain.position)
    q = _q_at(m, dist, radius, pts["cell"], pts["ref"], domain.inner_radius)
    on = q > 0.0
    if np.any(on):
        sub = {k: v[on] for k, v in pts.items()}
        t = lip_traction(solution, domain.crack, sub)
        if np.any(t):
            jump = (_aux_derivative(mat, domain, sub["x"], np.ones(len(t), dtype=np.int8))
                    - _aux_derivative(mat, domain, sub["x"], -np.ones(len(t), dtype=np.int8)))
            I = I - np.einsum("n,n,nmi,ni->m", sub["weight"], q[on], jump, t)
    if distributed:
        I = reduced(np.asarray(I, dtype=float), "SUM", m.V.mesh.comm)
    return I


def body_force(solution) -> typing.Callable[[np.ndarray], np.ndarray] | None:
    """b(x) (n, d) at points (n, d) = body force + div sigma_0 (at their load
    factors), the body force of the interaction integral (2D tips and 3D
    fronts), or None if both vanish."""
    model = solution.model
    scene = model.scene
    f = None if scene.body_force is None else solution.factor(scene.body_force_group) * np.asarray(
        scene.body_force, dtype=float)
    s0 = scene.initial_stress
    if s0 is not None and solution.factor(scene.initial_stress_group) == 0.0:
        s0 = None
    k0 = 1.0 if s0 is None else solution.factor(scene.initial_stress_group)
    if (f is None or not np.any(f)) and s0 is None:
        return None
    if isinstance(s0, LinearStress) and s0.is_uniform and (f is None or not np.any(f)):
        return None
    size = part_size(model)  # (alike on every process)

    def b(x):
        d = model.gdim
        out = np.zeros((len(x), d)) if f is None else np.broadcast_to(f, (len(x), d)).copy()
        if s0 is not None:
            out += k0 * divergence(s0, x, size, "initial stress")
        return out
    return b


def natural_k(solution) -> float:
    """A K that the scene's loads could make: E* max|u| / sqrt(L) (L the
    part's size), or, if larger, the largest lip traction of any cause
    (contact pressure, lip pressure, sigma_0 n) times sqrt(pi a) (a half a
    crack's length), the K of the crack were it open: the scale of a crack
    held closed."""
    m = solution.model
    k = m.scene.material.E_star * float(np.abs(solution.standard_displacement).max()) / math.sqrt(part_size(m))
    for ci in range(len(m.cracks)):
        pts = lip_points(m, ci)
        traction = max([float(np.linalg.norm(t, axis=1).max()) for t in lip_traction_parts(solution, ci, pts)]
                       if len(pts["weight"]) else [], default=0.0)
        if m.distributed:  # the largest over the crack, each process holding its part of it
            traction = reduced(traction, "MAX", m.V.mesh.comm)
        k = max(k, traction * math.sqrt(math.pi * 0.5 * length_in_part(m, ci)))  # (collective: the whole crack)
    if m.distributed:  # a scale, alike on every process (each saw its part)
        k = reduced(k, "MAX", m.V.mesh.comm)
    return k


#: A K below this fraction of the loads' natural K (natural_k) counts as
#: zero: the K scale's floor (a scene whose cracks are all held closed has
#: K = 0), and then also the size of an error or a spread worth a warning
#: (warned_above).
K_ZERO = 1e-3


def warned_above(fraction: float, scale: float, floor: float) -> float:
    """The size of a K error or spread that is warned about: `fraction` of
    the K scale, or, where no K of the scene reaches the floor (K_ZERO of
    the natural K: every crack held closed), the floor itself: K zero to
    that is the answer there, not a mesh too coarse (the paper's closed
    crack at a hole, demos/scenes/hole_crack.toml: K_I 8.0e-6 +- 9.1e-6
    against a natural K of 0.041 was warned as "the mesh is too coarse",
    22 % of the floor, and its domain spread as 1.2 %)."""
    return floor if scale <= floor else fraction * scale


def k_scale(sizes: typing.Iterable[float], natural: float) -> float:
    """The scale against which a spread or error of K is judged (2D and 3D):
    the largest |K| (sizes: |K| at each tip or front point), at least
    K_ZERO times the natural K (natural_k; a floor for scenes whose cracks
    are all closed, K = 0)."""
    return max([*sizes, K_ZERO * natural, 1e-300])


def compute_sifs(solution, radius: float | None = None, cracks: typing.Sequence[int] | None = None,
                 ring: tuple[float, float] | None = None) -> tuple[list[dict[str, typing.Any]], list[str]]:
    """K_I, K_II with their spreads at every tip of the given cracks (all by
    default), and the warnings about them (domains clipped, spreads above
    SPREAD_WARNING of the K scale). radius: the largest domain's radius,
    overriding Options.sif_radius and sif_ring; ring: (r_in, r_out), K on
    that one ring, not clipped (Options.sif_ring; spreads 0: one domain).
    Each row holds the keys of results.json's "sifs" (SIF_KEYS): crack,
    crack_name, point = tip = piece (a tip is a front of one point), s = 0,
    position, x, y, direction (e1), normal (e2 = e1 turned by +90
    degrees), frame [e1, e2], K_I, K_II, K_I_spread, K_II_spread,
    mode_mix_deg, G, radius, radii, radius_min, inner_radius (a ring's
    r_in, else None), element_size, limited_by, free_surface (False),
    domain_clear, K_source ("domain"), requested (False); the 3D keys
    None."""
    m = solution.model
    mat = m.scene.material
    cracks = range(len(m.cracks)) if cracks is None else cracks
    rows, warnings, raw = [], [], []
    for ci in cracks:
        doms = tip_domains(m, ci, radius, ring)
        if radius is not None or ring is not None:  # a caller's domain: say what became of it (the model
            # checks did the default)
            for dom in doms:
                for w in dom.warnings:
                    logger.warning("%s", w)
        for dom in doms:
            K = np.array([0.5 * mat.E_star * interaction_integrals(solution, dom, r) for r in dom.radii])
            raw.append((dom, K))
    natural = natural_k(solution)
    scale = k_scale([math.hypot(*K[-1]) for _, K in raw], natural)
    spread_warned = warned_above(SPREAD_WARNING, scale, K_ZERO * natural)
    negligible = 1e-6 * natural
    for dom, K in raw:
        kI, kII = float(K[-1, 0]), float(K[-1, 1])
        spread = np.ptp(K, axis=0)
        name = m.cracks[dom.crack].crack.name
        warnings += dom.warnings
        if dom.clear and max(spread) > spread_warned:
            warnings.append(CodedText(
                f"tip {dom.tip} of crack {name!r} at ({dom.position[0]:.6g}, {dom.position[1]:.6g}): K varies "
                f"with the SIF domain by {max(spread) / scale * 100:.2g} % of the K scale {scale:.4g} (K_I "
                f"{', '.join(f'{v:.5g}' for v in K[:, 0])}, K_II {', '.join(f'{v:.5g}' for v in K[:, 1])} on "
                f"radii {', '.join(f'{r:.3g}' for r in dom.radii)}): the field near the tip is not resolved "
                f"(element {dom.element_size:.3g}); refine the mesh at the tip (mesh.tip_h) or enlarge the "
                "enrichment radius (options.radius)", "sif_spread", dom.crack, dom.tip))
        mix = math.degrees(math.atan2(kII, kI)) if math.hypot(kI, kII) > negligible else None
        e1 = dom.direction.tolist()
        e2 = [-e1[1], e1[0]]
        rows.append({"crack": dom.crack, "crack_name": name, "point": dom.tip, "tip": dom.tip, "piece": dom.tip,
                     "s": 0.0, "position": dom.position.tolist(),
                     "x": float(dom.position[0]), "y": float(dom.position[1]),
                     "direction": e1, "normal": e2, "frame": [e1, e2], "K_I": kI, "K_II": kII,
                     "K_I_spread": float(spread[0]), "K_II_spread": float(spread[1]),
                     "mode_mix_deg": mix, "G": (kI ** 2 + kII ** 2) / mat.E_star,
                     "radius": dom.radius, "radii": list(dom.radii), "radius_min": float(min(dom.radii)),
                     "inner_radius": dom.inner_radius, "element_size": dom.element_size,
                     "limited_by": dom.obstacle if dom.limited or not dom.clear else None,
                     "free_surface": False, "domain_clear": dom.clear, "K_source": "domain", "requested": False})
    return complete_rows(rows), warnings
