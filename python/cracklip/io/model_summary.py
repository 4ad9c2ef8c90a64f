"""The model summary that ``cracklip check`` prints and results.json records: the
counts come from the same model and contact system objects the solver uses.

One summary for both dimensions: the mesh, dofs, enriched nodes, boundary
tags and quadrature groups alike; per crack a polyline's tips in 2D, a
surface's cut cells, front (pieces, points, length, boundary ends) and the
element size reached along it in 3D.

Under MPI (a distributed model) every count is over the processes' owned
nodes and cells, summed: the serial run's numbers."""
from __future__ import annotations

import typing

import numpy as np

from ..model.model import XfemModel
from ..post.solution import Solution, enriched_chunks
from ..scene.processes import reduced


def _kind(tips: int, pieces: list[dict], model: XfemModel) -> str:
    """What a crack is in the part: through, edge or interior by its tips,
    or, when its polyline leaves the part between its ends (a crack drawn
    across a hole), the pieces it makes."""
    plain = {0: "through (no tip inside)", 1: "edge (one tip)", 2: "interior (two tips)"}[tips]
    if len(pieces) <= 1:
        return plain
    from ..model.boundary import boundary_loops, nearest_boundary_point
    from ..model.tip_regions import model_boundary
    a, b = model_boundary(model)
    labels, outer = boundary_loops(a, b)

    def edge(x) -> str:
        return "a hole's edge" if labels[nearest_boundary_point(x, a, b)[2]] != outer else "the boundary"
    parts = []
    for pc in pieces:
        if pc["start_on_boundary"] and pc["end_on_boundary"]:
            parts.append(f"a through piece from {edge(pc['start'])} to {edge(pc['end'])}")
        elif pc["start_on_boundary"] or pc["end_on_boundary"]:
            parts.append(f"an edge crack from {edge(pc['start'] if pc['start_on_boundary'] else pc['end'])}")
        else:
            parts.append("an interior crack")
        parts[-1] += f" ({pc['length']:.6g} long)"
    holes = sum(1 for p, q in zip(pieces[:-1], pieces[1:]) if labels[nearest_boundary_point(p["end"], a, b)[2]] != outer)
    across = f"it crosses {'a hole' if holes == 1 else f'{holes} holes' if holes else 'the boundary'}"
    return f"{len(pieces)} pieces in the part ({across}): " + "; ".join(parts)


def _owned(model: XfemModel) -> tuple[int, int]:
    """(nodes, cells) this process counts: its owned ones, first in the
    local arrays (all of them in serial)."""
    if not model.distributed:
        return int(model.layout.num_std_nodes), int(model.cells.shape[0])
    return int(model.V.dofmap.index_map.size_local), int(model.num_owned_cells)


def _summed(model: XfemModel, value, op: str = "SUM"):
    """A count (or an array of counts) over every process's owned entities
    (itself in serial)."""
    return reduced(value, op, model.V.mesh.comm) if model.distributed else value


def _tip_cells(model: XfemModel) -> np.ndarray:
    cells = [np.asarray(g.tip_cells["cell"]) for g in model.geometries]
    return np.unique(np.concatenate(cells)) if cells else np.zeros(0, dtype=np.int32)


def describe_model(model: XfemModel, contact_system=None, solution: Solution | None = None) -> dict[str, typing.Any]:
    """Counts of what the model holds: nodes, cells, dofs; per crack its cell
    classes, Heaviside and tip nodes (core and blending) and their dofs; the
    quadrature per kind of enriched cell; the contact multipliers.

    contact_system: the contact.ContactSystem the solve uses (None without
    contact). solution: a solution of the model, whose quadrature points
    give the counts (computed otherwise)."""
    layout = model.layout
    opts = model.scene.options
    own_nodes, own_cells = _owned(model)
    node = np.asarray(layout.node)
    node = node[node < own_nodes]
    nodes, pseudo = int(_summed(model, own_nodes)), int(_summed(model, node.size))
    d = model.gdim
    describe_cracks = _DESCRIBE[model.crack_type.END]
    out: dict[str, typing.Any] = {
        "dimension": d,
        "nodes": nodes,
        "cells": int(_summed(model, own_cells)),
        "mean_edge": model.h,
        "dofs": {"standard": d * nodes, "enriched": d * pseudo, "total": d * (nodes + pseudo)},
        "enriched_nodes": int(_summed(model, np.unique(node).size)),
        "enriched_pseudo_nodes": pseudo,
        "enriched_cells": int(_summed(model, np.count_nonzero(np.asarray(layout.cells) < own_cells))),
        "enrichment": {"tip": opts.enrichment, "radius": opts.radius, "blending": opts.blending},
        "boundary_tags": {name: int(v) for name, v in sorted(model.scene.mesh.tags.items())},
        "cracks": describe_cracks(model),
        "quadrature": _describe_quadrature(model, solution),
    }
    est = getattr(model.scene.mesh, "estimate", None)
    if est is not None:  # a solid meshed by cracklip: the size estimated before meshing
        out["estimate"] = {"cells": round(est.cells), "nodes": round(est.nodes), "dofs": round(est.dofs),
                           "memory_GB": round(est.memory / 1e9, 3), "coarse": bool(est.coarse)}
    if contact_system is None:
        out["contact"] = {"law": "none" if not model.cracks else opts.contact, "multipliers": 0}
    else:
        space = contact_system.band  # (the whole crack's, the same on every process)
        out["contact"] = {
            "law": opts.contact, "space": opts.multipliers,
            "multipliers": int(contact_system.num_multipliers),
            "full_multipliers": int(space.num_full),
            "p0_multipliers": int(np.count_nonzero(np.asarray(space.full_node) < 0)),
        }
        if d == 2:
            out["contact"].update({"segments": int(space.num_segments), "points_per_segment": int(opts.contact_points)})
        else:  # the lip pieces (one per crack and cell), those of front cells, points per facet direction
            pieces = space.pieces
            out["contact"].update({"lip_pieces": int(space.num_pieces),
                                   "front_pieces": int(np.count_nonzero(np.asarray(pieces["front"]))),
                                   "points_per_direction": int(opts.contact_points)})
    return out


def _enriched_counts(model: XfemModel, ci: int, cell_class: np.ndarray, classes: dict[str, int], prefix: str,
                     d: int) -> dict[str, typing.Any]:
    """Cells of each class, and Heaviside and tip/front nodes and dofs of
    crack ci (keys `<prefix>_nodes`, ...: "tip" in 2D, "front" in 3D; d
    dofs per pseudo-node)."""
    layout = model.layout
    own_nodes, own_cells = _owned(model)
    node = np.asarray(layout.node)
    own = node < own_nodes
    node = node[own]
    kind = np.asarray(layout.kind)[own]
    crack_of = np.asarray(layout.crack)[own]
    core = np.asarray(layout.core)[own]
    cls = np.bincount(np.asarray(cell_class)[:own_cells], minlength=len(classes))
    heav = (crack_of == ci) & (kind == 0)
    tip = (crack_of == ci) & (kind != 0)
    tip_nodes = np.unique(node[tip])
    core_nodes = np.unique(node[tip & (core == 1)])
    counts = _summed(model, np.array([np.unique(node[heav]).size, np.count_nonzero(heav), tip_nodes.size,
                                      core_nodes.size, np.count_nonzero(tip)], dtype=np.int64))
    cls = _summed(model, cls.astype(np.int64))
    return {"cells": {name: int(cls[v]) for name, v in classes.items() if name != "plain"},
            "heaviside_nodes": int(counts[0]),
            "heaviside_dofs": int(d * counts[1]),
            f"{prefix}_nodes": int(counts[2]),
            f"{prefix}_core_nodes": int(counts[3]),
            f"{prefix}_blending_nodes": int(counts[2] - counts[3]),
            f"{prefix}_dofs": int(d * counts[4])}


def _describe_cracks_2d(model: XfemModel) -> list[dict[str, typing.Any]]:
    """Per polyline crack: its kind, length, tips, cells, enriched nodes, SIF domains."""
    layout = model.layout
    cracks = []
    from ..model.boundary import polyline_pieces
    from ..model.tip_regions import model_boundary
    a_bnd, b_bnd = model_boundary(model)
    pieces = [polyline_pieces(cm.crack.points, a_bnd, b_bnd) for cm in model.cracks]
    for ci, cm in enumerate(model.cracks):
        g = cm.geometry
        pts = cm.crack.points
        from ..model.tip_regions import tip_domains
        domains = tip_domains(model, ci)
        cracks.append({
            "name": cm.crack.name,
            "polyline_points": int(len(pts)),
            "length": float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()),
            "length_in_part": float(sum(pc["length"] for pc in pieces[ci])),
            "kind": _kind(sum(cm.tips), pieces[ci], model),
            "tips": np.asarray(g.tips).tolist(),
            "tip_element_size": [d.element_size for d in domains],
            "sif_radius": [d.radius for d in domains],
            "sif_inner_radius": [d.inner_radius for d in domains],
            "sif_limited_by": [d.obstacle if d.limited or not d.clear else None for d in domains],
            "lip_pressure": "function" if callable(cm.crack.pressure) else float(cm.crack.pressure),
            **_enriched_counts(model, ci, g.cell_class, cm.CELL_CLASSES, "tip", 2),
            "snapped_nodes": None if model.distributed else int(g.num_snapped),  # (a per-process count)
        })
    return cracks


def _describe_cracks_3d(model: XfemModel) -> list[dict[str, typing.Any]]:
    """Per crack surface: what it is, its area in the part, its cells, its
    enriched nodes, its front (pieces, points, length, boundary ends) and the
    element size reached along the front."""
    from ..model.checks import front_element_sizes
    from .scene_file.cracks import describe_crack
    layout = model.layout
    out = []
    for ci, cm in enumerate(model.cracks):
        g = cm.geometry
        fr = g.front
        offsets = np.asarray(fr["piece_offsets"])
        x = np.asarray(fr["x"]).reshape(-1, 3)
        seg = np.asarray(fr["segments"]).reshape(-1, 2)
        on = np.asarray(fr["on_boundary"])
        s_arc = np.asarray(fr["s"])
        pieces = []
        for k, closed in enumerate(np.asarray(fr["closed"])):
            first, last = int(offsets[k]), int(offsets[k + 1]) - 1
            length = float(s_arc[last]) if last >= first else 0.0
            if closed:  # and its closing segment
                length += float(np.linalg.norm(x[last] - x[first]))
            pieces.append({"points": last - first + 1, "closed": bool(closed), "length": length,
                           "ends_on_boundary": 0 if closed else int(on[first]) + int(on[last])})
        sizes = front_element_sizes(model, ci)
        cc = g.crack_cells  # (the facets of the owned cells, summed over the processes)
        own = np.repeat(np.asarray(cc["cell"]) < _owned(model)[1], np.diff(np.asarray(cc["facet_offsets"])))
        area = float(_summed(model, float(np.asarray(cc["facet_area"])[own].sum())))
        out.append({
            "name": cm.crack.name,
            "kind": {"EllipticalCrack": "ellipse", "PolygonCrack": "polygon"}.get(type(cm.crack).__name__,
                                                                                    "triangulated surface"),
            "description": describe_crack(cm.crack),
            "area": float(cm.crack.area),
            "area_in_part": area,
            "lip_pressure": "function" if callable(cm.crack.pressure) else float(cm.crack.pressure),
            **_enriched_counts(model, ci, g.cell_class, cm.CELL_CLASSES, "front", 3),
            "front": {"points": int(len(x)), "segments": int(len(seg)), "pieces": pieces,
                      "length": float(sum(p["length"] for p in pieces)),
                      "branch_points": int(fr["num_branch_points"])},
            "front_element_size": ({"mean": float(sizes.mean()), "min": float(sizes.min()), "max": float(sizes.max()),
                                    "cells": int(sizes.size)} if sizes.size else None),
            "snapped_nodes": None if model.distributed else int(g.num_snapped),  # (a per-process count)
            "degenerate_front_cells": int(g.num_degenerate_front_cells),
        })
    return out


def enriched_nodes(model: XfemModel) -> list[dict[str, typing.Any]]:
    """Every enriched node with its enrichments: node index, x, y (and z in
    3D) and a list of (crack, kind) with kind "heaviside", "tip core" or "tip
    blending" ("front core", "front blending" in 3D)."""
    layout = model.layout
    node = np.asarray(layout.node)
    kind = np.asarray(layout.kind)
    crack = np.asarray(layout.crack)
    core = np.asarray(layout.core)
    out: dict[int, dict[str, typing.Any]] = {}
    fn = model.crack_type.END
    for k in np.argsort(node, kind="stable"):
        n = int(node[k])
        entry = out.setdefault(n, {"node": n, **{a: float(v) for a, v in zip("xyz", model.x[n])}, "enrichment": []})
        what = "heaviside" if kind[k] == 0 else (f"{fn} core" if core[k] else f"{fn} blending")
        item = [int(crack[k]), what]
        if item not in entry["enrichment"]:
            entry["enrichment"].append(item)
    return list(out.values())


def _plain_group(ncells: int, num_enriched: int) -> dict[str, typing.Any]:
    return {"cells": "plain cells (standard block only)", "count": int(ncells - num_enriched),
            "rule": "DOLFINx's rule for the P1 stiffness", "points": None}


def _enriched_flags(layout, ncells: int) -> tuple[np.ndarray, np.ndarray]:
    """(enriched, has_tip): cells with enriched nodes, and those among them
    with tip (2D) or front (3D) functions, as masks over the mesh's cells."""
    enr_cells = np.asarray(layout.cells, dtype=np.int32)
    offsets = np.asarray(layout.cell_offsets)
    kinds = np.asarray(layout.kind)[np.asarray(layout.cell_enr)]
    has_tip = np.zeros(ncells, dtype=bool)
    has_tip[enr_cells] = np.add.reduceat((kinds != 0).astype(int), offsets[:-1]) > 0 if kinds.size else False
    enriched = np.zeros(ncells, dtype=bool)
    enriched[enr_cells] = True
    return enriched, has_tip


def _rule_groups(model: XfemModel, per_cell: np.ndarray, rows: list[tuple[str, np.ndarray, str]]
                 ) -> list[dict[str, typing.Any]]:
    """One group per (label, cell mask, rule) holding cells: count, points and their range per cell."""
    groups = []
    for label, mask, rule in rows:
        n = per_cell[mask]
        count, points = (int(v) for v in _summed(model, np.array([n.size, n.sum()], dtype=np.int64)))
        lo = _summed(model, int(n.min()) if n.size else np.iinfo(np.int64).max, "MIN")
        hi = _summed(model, int(n.max()) if n.size else -1, "MAX")
        if count:
            groups.append({"cells": label, "count": count, "rule": rule, "points": points,
                           "points_per_cell": [int(lo), int(hi)]})
    return groups


def _describe_quadrature(model: XfemModel, solution: Solution | None = None) -> list[dict[str, typing.Any]]:
    """Cells of each quadrature kind with their rule and point counts (the
    points of solution.enriched_quadrature() if given, else the same
    stiffness rules computed here): the plain cells, then the enriched
    ones by kind (_RULES of the crack's end, tips or fronts)."""
    layout = model.layout
    ncells = model.cells.shape[0]
    own_cells = _owned(model)[1]
    enr_cells = np.asarray(layout.cells, dtype=np.int32)
    num_enriched = int(_summed(model, np.count_nonzero(enr_cells < own_cells)))
    groups = [_plain_group(int(_summed(model, own_cells)), num_enriched)]
    if num_enriched == 0:
        return groups
    if solution is not None:
        per_cell = solution.enriched_quadrature()[1]
    else:  # the same rules, a chunk of cells at a time
        per_cell = np.zeros(ncells, dtype=np.int64)
        for chunk in enriched_chunks(model):
            per_cell += np.bincount(model.crack_type.enriched_cell_points(model, chunk, 0)["cell"], minlength=ncells)
    enriched, has_tip = _enriched_flags(layout, ncells)
    enriched[own_cells:] = False  # (under MPI: each process its owned cells)
    classes = model.crack_type.CELL_CLASSES
    cls = {name: np.zeros(ncells, dtype=bool) for name in classes}
    for g in model.geometries:
        for name, code in classes.items():
            cls[name] |= np.asarray(g.cell_class) == code
    return groups + _rule_groups(model, per_cell, _RULES[model.crack_type.END](model, enriched, has_tip, cls))


def _tip_rules(model: XfemModel, enriched: np.ndarray, has_tip: np.ndarray, cls: dict) -> list:
    """(label, cells, rule) of the enriched cells of a planar part."""
    opts = model.scene.options
    crossed = cls["cut"] | cls["edge"]
    is_tip = np.zeros(len(enriched), dtype=bool)
    is_tip[_tip_cells(model)] = True
    if opts.quadrature == "collapsed":
        tip_rule = (f"quasi-polar fan from the tip, {opts.tip_radial} x {opts.tip_angular} points per fan "
                    f"triangle (apex angle <= {opts.tip_max_angle:g})")
        near_rule = "quasi-polar fans from the tip (signed sums); Gauss far from the tip"
    else:
        tip_rule = f"Gauss degree {opts.quadrature_degree} on fan triangles from the tip (paper's rule)"
        near_rule = f"Gauss degree {opts.quadrature_degree} on sub-triangles (paper's rule)"
    return [("tip cells", enriched & is_tip, tip_rule),
            ("other cells with tip functions", enriched & has_tip & ~is_tip, near_rule),
            ("cut or edge cells, Heaviside only", enriched & crossed & ~has_tip & ~is_tip,
             f"Gauss degree {opts.degree} on each sub-triangle"),
            ("uncut cells with Heaviside nodes", enriched & ~crossed & ~has_tip & ~is_tip,
             f"Gauss degree {opts.degree}")]


def _front_rules(model: XfemModel, enriched: np.ndarray, has_front: np.ndarray, cls: dict) -> list:
    """(label, cells, rule) of the enriched cells of a solid."""
    opts = model.scene.options
    crossed, front = cls["cut"] | cls["face"], cls["front"]
    if opts.quadrature == "collapsed":
        front_rule = ("sub-tetrahedra split by the crack and the front: edge- and point-collapsed rules on those "
                      "touching the front, Gauss graded by the distance to it elsewhere")
    else:
        front_rule = f"Gauss degree {opts.quadrature_degree} on the sub-tetrahedra"
    degree = model.crack_type.quadrature_options(opts).degree
    return [("front cells", enriched & front, front_rule),
            ("cut cells with front functions", enriched & crossed & has_front & ~front,
             "sub-tetrahedra, Gauss graded by the distance to the front"),
            ("other cells with front functions", enriched & has_front & ~crossed & ~front,
             "Gauss graded by the distance to the front"),
            ("cut or face cells, Heaviside only", enriched & crossed & ~has_front & ~front,
             f"Gauss degree {degree} on each sub-tetrahedron"),
            ("uncut cells with Heaviside nodes", enriched & ~crossed & ~has_front & ~front,
             f"Gauss degree {degree}")]


#: The enriched cells' quadrature kinds by what the cracks end at (CrackModel.END).
_RULES = {"tip": _tip_rules, "front": _front_rules}


#: How the cracks are described, by what they end at (CrackModel.END): a
#: curve's tips, a surface's fronts.
_DESCRIBE = {"tip": _describe_cracks_2d, "front": _describe_cracks_3d}


def format_model(summary: dict[str, typing.Any]) -> list[str]:
    """Human-readable lines of describe_model's summary (for `cracklip check`)."""
    d = summary["dofs"]
    e = summary["enrichment"]
    solid = summary.get("dimension") == 3
    lines = [f"mesh: {summary['nodes']} nodes, {summary['cells']} {'tetrahedra' if solid else 'cells'}, mean edge "
             f"{summary['mean_edge']:.4g}",
             f"dofs: {d['total']} = {d['standard']} standard + {d['enriched']} enriched "
             f"({summary['enriched_nodes']} enriched nodes, {summary['enriched_pseudo_nodes']} "
             f"enriched pseudo-nodes on {summary['enriched_cells']} cells)",
             f"enrichment: {'front' if solid else 'tip'} {e['tip']}, radius {e['radius']:g}, {e['blending']} blending",
             "boundary tags: " + (", ".join(f"{n!r}" for n in summary["boundary_tags"]) or "none")]
    if "estimate" in summary:
        est = summary["estimate"]
        lines.insert(2, f"estimated before meshing: {est['cells']} tetrahedra, {est['dofs']} dofs, a run peaking at "
                        f"about {est['memory_GB']:.2g} GB")
    for c in summary["cracks"]:
        lines += (_format_surface if solid else _format_curve)(c)
        if c["lip_pressure"] != 0.0:
            lines.append(f"  lip pressure: {c['lip_pressure']}")
    lines.append("quadrature:")
    for q in summary["quadrature"]:
        pts = "" if q["points"] is None else (f", {q['points']} points "
                                              f"({q['points_per_cell'][0]}-{q['points_per_cell'][1]} per cell)")
        lines.append(f"  {q['count']} {q['cells']}: {q['rule']}{pts}")
    c = summary["contact"]
    if c["law"] == "none":
        lines.append("contact: none (traction-free lips), 0 multipliers")
    else:
        where = (f"{c['segments']} crack segments x {c['points_per_segment']} points" if "segments" in c else
                 f"{c['lip_pieces']} lip pieces ({c['front_pieces']} in front cells) x {c['points_per_direction']} "
                 "points per facet direction")
        cells = "tip" if "segments" in c else "front"
        lines.append(f"contact: {c['law']}, {c['space']} space: {c['multipliers']} multipliers "
                     f"({c['full_multipliers']} full, {c['p0_multipliers']} P0 in {cells} cells, "
                     f"grouped into the {c['multipliers']} unknowns) on {where}")
    return lines


def _format_curve(c: dict[str, typing.Any]) -> list[str]:
    """format_model's lines of a 2D crack: its kind, length, tips, cells,
    enriched nodes and SIF domains."""
    cells = ", ".join(f"{v} {k}" for k, v in c["cells"].items())
    tips = "; ".join(f"({t[0]:.6g}, {t[1]:.6g})" for t in c["tips"]) or "none"
    length = (f"length {c['length']:.6g}" if abs(c["length"] - c["length_in_part"]) <= 1e-9 * c["length"] else
              f"length {c['length_in_part']:.6g} in the part ({c['length']:.6g} along its polyline)")
    lines = [f"crack {c['name']!r}: {c['kind']}, {length}, tips {tips}",
             f"  cells: {cells}",
             f"  Heaviside: {c['heaviside_nodes']} nodes, {c['heaviside_dofs']} dofs",
             f"  tip: {c['tip_nodes']} nodes ({c['tip_core_nodes']} core, {c['tip_blending_nodes']} "
             f"blending), {c['tip_dofs']} dofs"
             + (f"; {c['snapped_nodes']} node(s) snapped onto the crack" if c["snapped_nodes"] else "")]
    for t, h, r, ri, lim in zip(c["tips"], c["tip_element_size"], c["sif_radius"], c["sif_inner_radius"],
                                c["sif_limited_by"]):
        if ri is not None:  # options.sif_ring: one ring, as given
            lines.append(f"  tip ({t[0]:.6g}, {t[1]:.6g}): element size {h:.4g}, SIF ring [{ri:.4g}, {r:.4g}] "
                         "(options.sif_ring, not clipped)" + (f" (reaches {lim})" if lim else ""))
            continue
        lines.append(f"  tip ({t[0]:.6g}, {t[1]:.6g}): element size {h:.4g}, SIF domains of radius "
                     f"{0.5 * r:.4g}, {0.75 * r:.4g}, {r:.4g}" + (f" (limited by {lim})" if lim else ""))
    return lines


def _format_surface(c: dict[str, typing.Any]) -> list[str]:
    """format_model's lines of a 3D crack: what it is, its area, cells,
    enriched nodes, front and the element size along it."""
    cells = ", ".join(f"{v} {k}" for k, v in c["cells"].items())
    fr = c["front"]
    pieces = "; ".join(("closed" if p["closed"] else f"open, {p['ends_on_boundary']} of 2 ends on the boundary")
                       + f", {p['points']} points, length {p['length']:.4g}" for p in fr["pieces"]) or "none"
    lines = [f"crack {c['description']}",
             f"  area in the part {c['area_in_part']:.6g} (of {c['area']:.6g})",
             f"  cells: {cells}",
             f"  Heaviside: {c['heaviside_nodes']} nodes, {c['heaviside_dofs']} dofs",
             f"  front functions: {c['front_nodes']} nodes ({c['front_core_nodes']} core, "
             f"{c['front_blending_nodes']} blending), {c['front_dofs']} dofs"
             + (f"; {c['snapped_nodes']} node(s) snapped onto the crack" if c["snapped_nodes"] else ""),
             f"  front: {fr['points']} points in {len(fr['pieces'])} piece(s): {pieces}"]
    if c["front_element_size"]:
        fs = c["front_element_size"]
        lines.append(f"  element size at the front: {fs['mean']:.4g} (from {fs['min']:.4g} to {fs['max']:.4g} "
                     f"over {fs['cells']} front cells)")
    return lines
