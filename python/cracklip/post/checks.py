"""Checks of a solved field: what the solve accepted silently and a user
must hear about. Each returns (code, message) pairs; Solution.warnings
collects them with the model's and the SIFs' warnings.

- ``interpenetration``: without contact (options.contact = "none") the lips
  are traction-free and a compressive load pushes them through each other:
  a negative K_I, and in fatigue a K_min below zero that inflates Delta K.
  Checked at every state of a load path (a fatigue cycle's minimum too), so
  the warning reaches ``grow`` through the maximum load's solution.
- ``bilateral_tension``: bilateral contact (options.contact = "bilateral")
  holds the lips together in tension too: where the load pulls them apart
  the contact "pressure" is negative and K_I is held at 0 where the open
  crack's would be positive (not conservative). Checked at every state of
  a load path.
- ``no_load``: every load and prescribed displacement is zero (the solution
  and every K are 0).
- ``unused_load_group``: a load path (load_path) that never names a load
  group the scene's loads or Dirichlet values belong to: its factor stays
  0 at every step (every factor starts at 0), so those loads are never
  applied ("default" included: a load without a group).
- ``point_supports``: two point forces or two tractions push against each
  other, as a self-equilibrated set does (the pins of a C(T), both ends of
  a pulled plate), yet point supports carry more than SUPPORT_FRACTION of
  the load: the loads do not balance and the supports act as loading points.
- ``initial_stress_unbalanced``: an initial stress sigma_0 whose traction
  sigma_0 n on the part's free boundary (facets with no Dirichlet condition,
  symmetry plane or applied traction at the state's factors; a constrained
  component does not count) is not zero: that part of sigma_0 is not held
  and relaxes (a uniform sigma_0 in a plate with free edges relaxes
  entirely: K = 0, "closed"). Measured as int |sigma_0 n| over those facets
  against int |sigma_0 n| over every facet without a Dirichlet condition,
  warned above UNBALANCED_FRACTION. A traction given on a facet is taken to
  hold sigma_0 n there with whatever service load it adds (the two cannot
  be told apart).
- ``discretisation`` and ``accuracy``: from an error estimate
  (cracklip.analysis.accuracy), a K whose estimated error exceeds
  ERROR_WARNING of the K scale, or an accuracy target not reached.
"""
from __future__ import annotations

import math

import numpy as np

from ..fracture.sif import warned_above
from ..model.boundary import owned_boundary_facets
from ..model.constraints import is_point_condition
from ..scene.processes import reduced
from ..scene.stress_field import evaluate_stress
from ..scene.symmetry import SymmetryCondition
from ..scene.scene import load_groups


#: Overlap of the lips (largest -gap) above this fraction of the largest
#: |jump| of a crack is interpenetration (below it: round-off of a crack
#: loaded in shear).
OVERLAP_FRACTION = 1e-3

#: ... and above this fraction of the largest displacement of the part: below
#: it the overlap is the solve's round-off (a plate whose uniform initial
#: stress relaxes at its free edges moved 5.46 and its closed crack's lips
#: "overlapped" by 3e-13 over all its length, K_I -2e-13: warned about before).
OVERLAP_ROUNDOFF = 1e-9


#: A bilateral contact pressure below -TENSION_FRACTION times the largest
#: lip traction (pressure or shear) is tension the lips should not carry
#: (above it: round-off of a crack in shear, ~1e-10).
TENSION_FRACTION = 1e-3


#: Point supports carrying more than this fraction of the applied load
#: (the sum of |nodal loads|) when the loads oppose each other are warned about.
SUPPORT_FRACTION = 0.01


#: Loads of one kind count as pushing against each other when each side
#: exceeds this fraction of the applied load (a pin at 1/100 of the other
#: is 1 % of their sum).
OPPOSING_FRACTION = 1e-3


#: An initial stress whose traction sigma_0 n on the free boundary exceeds
#: this fraction of its traction on every boundary without a Dirichlet
#: condition is warned about. A balanced field gives 0 up to the rounding of
#: the facet normals (~1e-16); a measured field whose free edges carry a few
#: % of its boundary traction (its noise) relaxes by as little, below the
#: K accuracy of the method (docs/sifs.md: 0.1-1 %) times the field's share.
UNBALANCED_FRACTION = 0.02

#: A 3-point rule on a facet (barycentric points, weights summing to 1):
#: Gauss on an edge (degree 5), the interior rule of degree 2 on a triangle.
_GAUSS = np.array([0.5 - 0.5 * np.sqrt(0.6), 0.5, 0.5 + 0.5 * np.sqrt(0.6)])
_FACET_RULE = {
    2: (np.stack([1.0 - _GAUSS, _GAUSS], axis=1), np.array([5.0, 8.0, 5.0]) / 18.0),
    3: (np.array([[2 / 3, 1 / 6, 1 / 6], [1 / 6, 2 / 3, 1 / 6], [1 / 6, 1 / 6, 2 / 3]]), np.full(3, 1 / 3)),
}


def initial_stress_unbalanced(solution) -> list[tuple[str, str]]:
    """sigma_0 n not held on the free boundary (module doc): the worst state
    of a load path. Under mpirun each process sums its owned facets and the
    sums are reduced: every process gets the same answer."""
    m = solution.model
    scene = m.scene
    if scene.initial_stress is None:
        return []
    mesh = scene.mesh
    d = m.gdim
    facets, verts, size, n = owned_boundary_facets(mesh)
    bary, w = _FACET_RULE[d]
    pts = np.einsum("qa,fai->fqi", bary, verts)  # (f, q, d)
    sig = evaluate_stress(scene.initial_stress, pts.reshape(-1, d), "initial stress").reshape(
        len(facets), len(w), d, d)
    t0 = np.einsum("fqij,fj->fqi", sig, n)  # sigma_0 n (f, q, d)
    # Components held by a Dirichlet condition or symmetry plane (on a tag).
    held = np.ones((len(facets), d))
    for dc in scene.dirichlet:
        if is_point_condition(dc):  # (a point holds no facet)
            continue
        on = np.isin(facets, mesh.facets(dc.where))
        if isinstance(dc, SymmetryCondition):  # u . n = 0: the normal component
            t0[on] -= np.einsum("fqi,fi->fq", t0[on], n[on])[..., None] * n[on][:, None, :]
        elif dc.component is None:
            held[on] = 0.0
        else:
            held[on, dc.component] = 0.0
    t0 = t0 * held[:, None, :]
    mag = np.linalg.norm(t0, axis=2) @ w * size  # int |sigma_0 n| per facet
    tags = sorted({tr.where for tr in scene.tractions}, key=str)
    tag_of = {t: np.isin(facets, mesh.facets(t)) for t in tags}
    names = [str(k) for k in mesh.tags]
    named = {k: np.isin(facets, mesh.facets(k)) for k in mesh.tags}
    worst = None
    states = _states(solution)
    for st in states:
        if st.factor(scene.initial_stress_group) == 0.0:
            continue
        loaded = np.zeros(len(facets), dtype=bool)
        for tr in scene.tractions:
            if st.factor(tr.group) != 0.0:
                loaded |= tag_of[tr.where]
        free = mag * ~loaded
        per_tag = [float(free[named[k]].sum()) for k in mesh.tags]
        sums = np.array([float(free.sum()), float(mag.sum())] + per_tag)
        if mesh.mesh.comm.size > 1:
            sums = reduced(sums, "SUM", mesh.mesh.comm)
        if sums[1] > 0.0 and (worst is None or sums[0] / sums[1] > worst[0]):
            worst = (sums[0] / sums[1], st, sums[2:])
    if worst is None or worst[0] <= UNBALANCED_FRACTION:
        return []
    frac, st, per_tag = worst
    order = [k for k in np.argsort(-per_tag) if per_tag[k] > 1e-6 * per_tag.sum()]
    where = ", ".join(f"{names[k]!r} ({100 * per_tag[k] / per_tag.sum():.3g} %)" for k in order)
    tag = " / ".join(repr(names[k]) for k in order) or "... (tag the free edges)"
    at = _at_step(st, states)
    return [("initial_stress_unbalanced", (
        f"the initial stress (loads.initial_stress) is not balanced on the part's boundary{at}: "
        f"{100 * frac:.3g} % of its traction sigma_0 n (integral of |sigma_0 n| over the boundary without a "
        "Dirichlet condition) falls on free edges (3D: faces), where no traction (loads.tractions) holds it"
        + (f" (on the tags {where})" if where else " (on untagged facets)")
        + ": that part of sigma_0 relaxes, and K and the opening see only the rest. Apply sigma_0 n there: "
        f"[[loads.tractions]] with tag = {tag} and stress / stress_gradient equal to loads.initial_stress's "
        "value / gradient (plus any service load), in a load group with a factor wherever the initial "
        "stress's has one; or accept that this part of the field relaxes (a field measured in a part cut "
        "from a larger one)"))]


#: A K whose estimated discretisation error exceeds this fraction of the K scale is warned about.
ERROR_WARNING = 0.01


def _states(solution) -> list:
    return getattr(solution, "path", None) or [solution]


def _at_step(st, states: list) -> str:
    """' at <step name>' for a warning of one state of a load path ('' for a
    single solve)."""
    return f" at {st.step['name']!r}" if getattr(st, "step", None) and len(states) > 1 else ""


def interpenetration(solution) -> list[tuple[str, str]]:
    """Lips passing through each other without contact (module doc)."""
    m = solution.model
    if m.scene.options.contact != "none" or not m.cracks:
        return []
    out = []
    states = _states(solution)
    for ci, cm in enumerate(m.cracks):
        worst = None
        for st in states:
            smp = st.lip_samples(ci, 2)
            if not len(smp["gap"]):
                continue
            jump = float(np.linalg.norm(smp["jump"], axis=1).max())
            overlap = float(max(0.0, -smp["gap"].min()))
            u = getattr(st, "u", None)
            tol = max(OVERLAP_FRACTION * jump, OVERLAP_ROUNDOFF * (float(np.abs(u).max()) if u is not None and
                                                                     np.size(u) else 0.0))
            if jump > 0.0 and overlap > tol:
                w = smp["weight"]
                frac = float(w[smp["gap"] < -tol].sum() / w.sum())
                if worst is None or overlap > worst[1]:
                    worst = (st, overlap, frac)
        if worst is None:
            continue
        st, overlap, frac = worst
        rows = st.stress_intensity_factors(ci)
        unit = "" if m.scene.units is None else f" {m.scene.units.name('length')}"
        at = _at_step(st, states)
        out.append(("interpenetration", (
            f"crack {cm.crack.name!r}{at}: the lips pass through each other over {100 * frac:.0f} % of its "
            f"{cm.EXTENT} (largest overlap {overlap:.3g}{unit}{_negative_k(rows, cm.END)}): contact is off "
            "(options.contact = \"none\"), so nothing stops them; the K_I < 0 of overlapping lips is not physical, "
            "and in fatigue it makes K_min negative and Delta K too large (life too short). " + CONTACT_FIX[cm.END])))
    return out


def bilateral_tension(solution) -> list[tuple[str, str]]:
    """Bilateral contact carrying tension (module doc)."""
    m = solution.model
    if m.scene.options.contact != "bilateral" or not solution.contact or not m.cracks:
        return []
    out = []
    states = _states(solution)
    for ci, cm in enumerate(m.cracks):
        worst = None
        for st in states:
            smp = st.lip_samples(ci, 2)
            p = smp["pressure"]
            if not len(p):
                continue
            shear = smp["shear"] if smp["shear"].ndim == 1 else np.linalg.norm(smp["shear"], axis=1)
            scale = max(float(np.abs(p).max()), float(np.abs(shear).max()))
            tensile = p < -TENSION_FRACTION * scale
            if scale > 0.0 and np.any(tensile):
                w = smp["weight"]
                frac = float(w[tensile].sum() / w.sum())
                if worst is None or p.min() < worst[1]:
                    worst = (st, float(p.min()), frac)
        if worst is None:
            continue
        st, lowest, frac = worst
        at = _at_step(st, states)
        out.append(("bilateral_tension", (
            f"crack {cm.crack.name!r}{at}: bilateral contact holds its lips together against tension over "
            f"{100 * frac:.0f} % of its {cm.EXTENT} (contact pressure down to {lowest:.4g}): bilateral lips cannot "
            "open, so where the load pulls them apart K_I is held at 0 while the open crack's is positive (not "
            "conservative). Set options.contact = \"unilateral\" (the lips open where pulled, touch where pressed), "
            "or check the sign of the load")))
    return out


#: The fix named by the interpenetration warning, per kind of crack end
#: (CrackModel.END): contact on the lips, or the load's sign.
CONTACT_FIX = {
    "tip": "Set options.contact = \"unilateral\": the lips then touch and carry the pressure; or check the sign "
           "of the load",
    "front": "Set options.contact = \"unilateral\" (3D lip contact: the lips then touch and carry the pressure), or "
             "check the sign of the load",
}


def _negative_k(rows: list[dict], end: str) -> str:
    """'; K_I = ... at ...' for the points of a crack with K_I < 0: each of
    them when there are at most two, else their count and the lowest."""
    neg = sorted((r for r in rows if r["K_I"] < 0.0), key=lambda r: r["K_I"])
    if not neg:
        return ""

    def where(r):
        return f"({', '.join(f'{v:.6g}' for v in r['position'])})"
    if len(neg) <= 2:
        return "; " + "; ".join(f"K_I = {r['K_I']:.4g} at the {end} {where(r)}" for r in neg)
    return (f"; K_I < 0 at {len(neg)} of the {len(rows)} {end} points, down to {neg[0]['K_I']:.4g} at "
            f"{where(neg[0])}")


def no_load(solution) -> list[tuple[str, str]]:
    """Every state's displacement exactly zero: no load at all."""
    moving = any(np.any(st.u) for st in _states(solution))
    m = solution.model
    if m.distributed:  # (each process its part of u)
        moving = bool(reduced(moving, "LOR", m.V.mesh.comm))
    if moving:
        return []
    return [("no_load", "every load and prescribed displacement of the scene is zero (tractions, pressures, point "
                        "forces, body force, lip pressures, initial stress, Dirichlet values): the displacement and "
                        "every K are 0; give the part a load")]


def unused_load_groups(solution) -> list[tuple[str, str]]:
    """Load groups with loads that no step of the load path names (their
    factor is 0 throughout: the loads are never applied)."""
    scene = solution.model.scene
    if not scene.load_path:
        return []
    named = set().union(*(st.factors for st in scene.load_path))
    unused = sorted(load_groups(scene) - named)
    if not unused:
        return []
    return [("unused_load_group", (
        f"load group(s) {unused} of the scene's loads or Dirichlet values are named by no step of the load path "
        f"([[load_path]], or a fatigue cycle's growth.cycle_max / cycle_min; it names {sorted(named)}): "
        "every factor starts at 0, so these loads are never applied; give "
        "them a factor in a load step (factors = { " + ", ".join(f"{g} = 1.0" for g in unused) + " }) or put the "
        "loads in a group the path names (group = ...)"))]


def point_supports(solution, reactions: dict | None = None) -> list[tuple[str, str]]:
    """Point supports carrying the imbalance of loads that push against each
    other: two point forces, or two tractions, opposed along x or y (as the
    pins of a C(T) or both ends of a pulled plate, meant to balance), while
    the point supports carry more than SUPPORT_FRACTION of the applied load.
    A load that the supports are meant to carry (three-point bending, a
    traction against a point force) is not judged."""
    if reactions is None:
        from .reactions import compute_reactions
        reactions = compute_reactions(solution)
    gross = reactions["gross_load"]
    # Loads that cancel node by node (an initial stress against the tractions
    # it puts on the boundary) leave round-off: measured against the loads'
    # own size before they add up.
    noise = 1e-9 * reactions["load_magnitude"]
    if gross <= noise:
        return []
    points = [r for r in reactions["conditions"] if r["kind"] == "point"]
    carried = float(sum(np.linalg.norm(r["force"]) for r in points))
    if not points or carried <= max(SUPPORT_FRACTION * gross, noise):
        return []
    for kind in ("point force", "traction"):
        items = [np.asarray(i["resultant"]) for i in reactions["load_items"] if i["kind"] == kind]
        for k in range(solution.model.gdim):
            pos = sum(f[k] for f in items if f[k] > OPPOSING_FRACTION * gross)
            neg = -sum(f[k] for f in items if f[k] < -OPPOSING_FRACTION * gross)
            if pos > 0.0 and neg > 0.0:
                detail = ", ".join(f"{r['condition']} ({', '.join(f'{v:.4g}' for v in r['force'])})" for r in points
                                   if np.linalg.norm(r["force"]) > 0.0)
                return [("point_supports", (
                    f"the {kind}s push against each other (in {'xyz'[k]}: +{pos:.4g} and -{neg:.4g}) as a set meant "
                    f"to balance does (the pins of a C(T), both ends of a pulled plate), yet the point supports "
                    f"carry {carried:.4g} ({100 * carried / gross:.2g} % of the applied load {gross:.4g}): {detail}. "
                    "The loads do not balance and the supports act as loading points (one pin loaded more than "
                    "the other?); check the load values, or support the part where it really is held"))]
    return []


def front_row_name(r) -> str:
    """A 3D front row as messages name it: "front point k" for a front
    point, and for a row interpolated between front points (a position asked
    for by options.sif_angles, sif_angle_step, sif_arc_lengths: its `point`
    is None) its arc length s and parametric angle."""
    if r.get("point") is not None:
        return f"front point {r['point']}"
    angle = r.get("parametric_angle")
    angle = "" if angle is None else f", parametric angle {math.degrees(angle):.4g} deg"
    return f"the front at s = {r['s']:.4g} (between front points{angle})"


def estimate(solution) -> list[tuple[str, str]]:
    """Warnings of an error estimate (cracklip.analysis.accuracy): every 2D
    tip, and along each 3D front the worst point off the free surface
    (with how many exceed it), whose estimated error exceeds ERROR_WARNING
    of the K scale; an accuracy target not reached."""
    est = getattr(solution, "error_estimate", None)
    if not est:
        return []
    out = []
    scale = est["K_scale"]
    warned = warned_above(ERROR_WARNING, scale, est.get("K_floor", 0.0))
    names = [cm.crack.name for cm in solution.model.cracks]
    if est["target"] is None:
        rows = [r for r in solution.stress_intensity_factors(None)
                if not r["free_surface"] and r.get("K_I_error") is not None]
        for crack in sorted({r["crack"] for r in rows}):
            mine = [r for r in rows if r["crack"] == crack]
            modes = [m for m in ("K_I", "K_II", "K_III") if mine[0].get(f"{m}_error") is not None]
            over = [(r, max(modes, key=lambda m: r[f"{m}_error"])) for r in mine]
            over = [(r, m) for r, m in over if r[f"{m}_error"] > warned]
            if not over:
                continue
            front = mine[0]["tip"] is None
            # the worst (a front point where an asked position between points ties with it: their
            # estimate is the larger of their neighbouring points')
            for r, mode in (over if not front else [max(over, key=lambda o: (o[0][f"{o[1]}_error"],
                                                                             o[0].get("point") is not None))]):
                what = (f"{front_row_name(r)} of crack {names[crack]!r} at ({r['x']:.6g}, {r['y']:.6g}, "
                        f"{r['z']:.6g})" if front else f"tip {r['tip']} of crack {names[crack]!r} at ({r['x']:.6g}, "
                        f"{r['y']:.6g})")
                other = next(j for j, f in enumerate(est["size_factors"]) if f != est["of_size_factor"])
                elsewhere = r[f"{mode}_levels"][other]
                many = f" ({len(over)} of {len(mine)} positions along its front above 1 %)" if front else ""
                out.append(("discretisation", (
                    f"{what}: {mode} = {r[mode]:.6g} has an estimated discretisation error of {r[f'{mode}_error']:.3g} "
                    f"({100 * r[f'{mode}_error'] / scale:.2g} % of the K scale {scale:.4g}; with {est['meshes']} it "
                    f"is {elsewhere:.6g}){many}: the mesh is too "
                    "coarse for this crack; refine it (mesh.h around the crack, mesh.tip_h, options.radius of a few "
                    "tip elements) or let cracklip refine it: options.accuracy = 0.01 (command line --accuracy "
                    "0.01)")))
    elif not est["reached"]:
        out.append(("accuracy", (
            f"the accuracy target {100 * est['target']:.3g} % was not reached in {est['refinement_levels']} "
            f"refinement level(s) (element sizes x {est['size_factors'][-1]:.3g}, {est['dofs'][-1]} dofs): the "
            f"largest estimated error of K is {100 * est['largest_relative_error']:.3g} % of the K scale; raise "
            "options.accuracy_levels, or start from a finer mesh (mesh.h, mesh.tip_h)")))
    return out


def solution_warnings(solution) -> list[tuple[str, str]]:
    """Every check of this module that needs no reactions (those are in the outputs)."""
    return (interpenetration(solution) + bilateral_tension(solution) + no_load(solution)
            + unused_load_groups(solution) + initial_stress_unbalanced(solution) + estimate(solution))
