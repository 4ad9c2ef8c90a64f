"""What a run writes: results.json, crack.csv, sif.csv, ParaView files and PNGs.

Every file is written under a temporary name in the output folder and
renamed when complete (``io.atomic_path``), so a folder never holds a
half-written output; a folder that cannot be written raises ``OutputError``
naming it. ``describe_model`` is the model summary that ``cracklip check``
prints and results.json records: the counts come from the same model and
contact system objects the solver uses.
"""
from __future__ import annotations

import csv
import json
import logging
import math
import pathlib
import platform
import tempfile
import time
import typing

import numpy as np

from . import _cracklip
from .errors import CracklipError, SolverError
from .io import atomic_path, crack_lips_mesh, subcell_mesh, von_mises, write_mesh
from .model import CELL_CLASSES, XfemModel
from .post import Solution

logger = logging.getLogger(__name__)


class OutputError(CracklipError, OSError):
    """An output folder or file cannot be written."""


# -- the model, as check prints it -----------------------------------------------------------------

def _tip_cells(model: XfemModel) -> np.ndarray:
    cells = [np.asarray(g.tip_cells["cell"]) for g in model.geometries]
    return np.unique(np.concatenate(cells)) if cells else np.zeros(0, dtype=np.int32)


def describe_model(model: XfemModel, contact_system=None) -> dict[str, typing.Any]:
    """Counts of what the model holds: nodes, cells, dofs; per crack its cell
    classes, Heaviside and tip nodes (core and blending) and their dofs; the
    quadrature per kind of enriched cell; the contact multipliers.

    contact_system: the contact.ContactSystem the solve uses (None without
    contact)."""
    layout = model.layout
    opts = model.scene.options
    kind = np.asarray(layout.kind)
    crack_of = np.asarray(layout.crack)
    node = np.asarray(layout.node)
    core = np.asarray(layout.core)
    cracks = []
    for ci, cm in enumerate(model.cracks):
        g = cm.geometry
        cls = np.bincount(np.asarray(g.cell_class), minlength=len(CELL_CLASSES))
        heav = (crack_of == ci) & (kind == 0)
        tip = (crack_of == ci) & (kind != 0)
        tip_nodes = np.unique(node[tip])
        core_nodes = np.unique(node[tip & (core == 1)])
        pts = cm.crack.points
        cracks.append({
            "name": cm.crack.name,
            "polyline_points": int(len(pts)),
            "length": float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()),
            "kind": {0: "through (no tip inside)", 1: "edge (one tip)", 2: "interior (two tips)"}[sum(cm.tips)],
            "tips": np.asarray(g.tips).tolist(),
            "cells": {name: int(cls[v]) for name, v in CELL_CLASSES.items() if name != "plain"},
            "heaviside_nodes": int(np.unique(node[heav]).size),
            "heaviside_dofs": int(2 * np.count_nonzero(heav)),
            "tip_nodes": int(tip_nodes.size),
            "tip_core_nodes": int(core_nodes.size),
            "tip_blending_nodes": int(tip_nodes.size - core_nodes.size),
            "tip_dofs": int(2 * np.count_nonzero(tip)),
            "snapped_nodes": int(g.num_snapped),
        })
    out: dict[str, typing.Any] = {
        "nodes": int(layout.num_std_nodes),
        "cells": int(model.cells.shape[0]),
        "mean_edge": model.h,
        "dofs": {"standard": int(2 * layout.num_std_nodes), "enriched": int(2 * layout.num_enriched),
                 "total": int(model.num_dofs)},
        "enriched_nodes": int(np.unique(node).size),
        "enriched_pseudo_nodes": int(layout.num_enriched),
        "enriched_cells": int(np.asarray(layout.cells).size),
        "enrichment": {"tip": opts.enrichment, "radius": opts.radius, "blending": opts.blending},
        "cracks": cracks,
        "quadrature": _describe_quadrature(model),
    }
    if contact_system is None:
        out["contact"] = {"law": "none" if not model.cracks else opts.contact, "multipliers": 0}
    else:
        space = contact_system.space
        out["contact"] = {
            "law": opts.contact, "space": opts.multipliers,
            "multipliers": int(contact_system.num_multipliers),
            "full_multipliers": int(space.num_full),
            "p0_multipliers": int(np.count_nonzero(np.asarray(space.full_node) < 0)),
            "segments": int(space.num_segments), "points_per_segment": int(opts.contact_points),
        }
    return out


def enriched_nodes(model: XfemModel) -> list[dict[str, typing.Any]]:
    """Every enriched node with its enrichments: node index, x, y and a list
    of (crack, kind) with kind "heaviside", "tip core" or "tip blending"."""
    layout = model.layout
    node = np.asarray(layout.node)
    kind = np.asarray(layout.kind)
    crack = np.asarray(layout.crack)
    core = np.asarray(layout.core)
    out: dict[int, dict[str, typing.Any]] = {}
    for k in np.argsort(node, kind="stable"):
        n = int(node[k])
        entry = out.setdefault(n, {"node": n, "x": float(model.x[n, 0]), "y": float(model.x[n, 1]),
                                   "enrichment": []})
        what = "heaviside" if kind[k] == 0 else ("tip core" if core[k] else "tip blending")
        item = [int(crack[k]), what]
        if item not in entry["enrichment"]:
            entry["enrichment"].append(item)
    return list(out.values())


def _describe_quadrature(model: XfemModel) -> list[dict[str, typing.Any]]:
    """Cells of each quadrature kind with their rule and point counts."""
    layout = model.layout
    opts = model.scene.options
    ncells = model.cells.shape[0]
    enr_cells = np.asarray(layout.cells, dtype=np.int32)
    groups = [{"cells": "plain cells (standard block only)", "count": int(ncells - enr_cells.size),
               "rule": "DOLFINx's rule for the P1 stiffness", "points": None}]
    if enr_cells.size == 0:
        return groups
    fp = _cracklip.compute_field_points(model.x, model.cells, layout, model.geometries,
                                        np.zeros(model.num_dofs), enr_cells, opts.quadrature_options())
    per_cell = np.bincount(fp["cell"], minlength=ncells)
    offsets = np.asarray(layout.cell_offsets)
    kinds = np.asarray(layout.kind)[np.asarray(layout.cell_enr)]
    has_tip = np.zeros(ncells, dtype=bool)
    has_tip[enr_cells] = np.add.reduceat((kinds != 0).astype(int), offsets[:-1]) > 0 if kinds.size else False
    crossed = np.zeros(ncells, dtype=bool)
    for g in model.geometries:
        cls = np.asarray(g.cell_class)
        crossed |= (cls == CELL_CLASSES["cut"]) | (cls == CELL_CLASSES["edge"])
    is_tip = np.zeros(ncells, dtype=bool)
    is_tip[_tip_cells(model)] = True
    enriched = np.zeros(ncells, dtype=bool)
    enriched[enr_cells] = True
    if opts.quadrature == "collapsed":
        tip_rule = (f"quasi-polar fan from the tip, {opts.tip_radial} x {opts.tip_angular} points per fan "
                    f"triangle (apex angle <= {opts.tip_max_angle:g})")
        near_rule = "quasi-polar fans from the tip (signed sums); Gauss far from the tip"
    else:
        tip_rule = f"Gauss degree {opts.quadrature_degree} on fan triangles from the tip (paper's rule)"
        near_rule = f"Gauss degree {opts.quadrature_degree} on sub-triangles (paper's rule)"
    for label, mask, rule in [
            ("tip cells", enriched & is_tip, tip_rule),
            ("other cells with tip functions", enriched & has_tip & ~is_tip, near_rule),
            ("cut or edge cells, Heaviside only", enriched & crossed & ~has_tip & ~is_tip,
             f"Gauss degree {opts.degree} on each sub-triangle"),
            ("uncut cells with Heaviside nodes", enriched & ~crossed & ~has_tip & ~is_tip,
             f"Gauss degree {opts.degree}")]:
        n = per_cell[mask]
        if n.size:
            groups.append({"cells": label, "count": int(n.size), "rule": rule, "points": int(n.sum()),
                           "points_per_cell": [int(n.min()), int(n.max())]})
    return groups


def format_model(summary: dict[str, typing.Any]) -> list[str]:
    """Human-readable lines of describe_model's summary (for `cracklip check`)."""
    d = summary["dofs"]
    e = summary["enrichment"]
    lines = [f"mesh: {summary['nodes']} nodes, {summary['cells']} cells, mean edge {summary['mean_edge']:.4g}",
             f"dofs: {d['total']} = {d['standard']} standard + {d['enriched']} enriched "
             f"({summary['enriched_nodes']} enriched nodes, {summary['enriched_pseudo_nodes']} "
             f"enriched pseudo-nodes on {summary['enriched_cells']} cells)",
             f"enrichment: tip {e['tip']}, radius {e['radius']:g}, {e['blending']} blending"]
    for c in summary["cracks"]:
        cells = ", ".join(f"{v} {k}" for k, v in c["cells"].items())
        tips = "; ".join(f"({t[0]:.6g}, {t[1]:.6g})" for t in c["tips"]) or "none"
        lines += [f"crack {c['name']!r}: {c['kind']}, length {c['length']:.6g}, tips {tips}",
                  f"  cells: {cells}",
                  f"  Heaviside: {c['heaviside_nodes']} nodes, {c['heaviside_dofs']} dofs",
                  f"  tip: {c['tip_nodes']} nodes ({c['tip_core_nodes']} core, {c['tip_blending_nodes']} "
                  f"blending), {c['tip_dofs']} dofs"
                  + (f"; {c['snapped_nodes']} node(s) snapped onto the crack" if c["snapped_nodes"] else "")]
    lines.append("quadrature:")
    for q in summary["quadrature"]:
        pts = "" if q["points"] is None else (f", {q['points']} points "
                                              f"({q['points_per_cell'][0]}-{q['points_per_cell'][1]} per cell)")
        lines.append(f"  {q['count']} {q['cells']}: {q['rule']}{pts}")
    c = summary["contact"]
    if c["law"] == "none":
        lines.append("contact: none (traction-free lips), 0 multipliers")
    else:
        lines.append(f"contact: {c['law']}, {c['space']} space: {c['multipliers']} multipliers "
                     f"({c['full_multipliers']} full, {c['p0_multipliers']} P0 in tip cells) on "
                     f"{c['segments']} crack segments x {c['points_per_segment']} points")
    return lines


# -- along the cracks ------------------------------------------------------------------------------

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


def crack_samples(solution: Solution, crack: int, points_per_segment: int = 3) -> dict[str, np.ndarray]:
    """Points along a crack (Gauss points of its segments in each cell) with
    s (arc length from the crack's first point), x (n, 2), weight (length
    each point stands for), normal (n, 2, into the + side), u_plus, u_minus
    (n, 2: displacement of each lip), gap = [[u]].n (> 0 open), slip =
    [[u]].t (t = n turned by -90 degrees), pressure (>= 0 in compression,
    0 without contact). Sorted by s."""
    m = solution.model
    g = m.geometries[crack]
    crack_points = m.cracks[crack].crack.points
    if solution.contact:
        cs = solution.contact["system"]
        sp_ = _cracklip.compute_segment_points(m.x, m.cells, m.geometries, cs.space, points_per_segment)
        lam_full = cs.R @ solution.contact["lambda"]
        p = np.zeros(len(sp_["weight"]))
        np.add.at(p, sp_["entry_point"], -sp_["entry_value"] * lam_full[sp_["entry_mult"]])
        keep = np.asarray(cs.space.segment_crack)[sp_["segment"]] == crack
        cells, ref, x = sp_["cell"][keep], sp_["ref"][keep], sp_["x"][keep]
        weight, normal, pressure = sp_["weight"][keep], sp_["normal"][keep], p[keep]
    else:
        cc = g.crack_cells
        own = np.asarray(cc["owns_segment"]).astype(bool)
        tc = g.tip_cells
        seg_cells = np.concatenate([cc["cell"][own], tc["cell"]]).astype(np.int32)
        seg = np.concatenate([cc["segment"][own], tc["segment"]])
        t, w = np.polynomial.legendre.leggauss(points_per_segment)
        t, w = 0.5 * (t + 1.0), 0.5 * w
        ref = (seg[:, None, 0, :] * (1 - t)[None, :, None] + seg[:, None, 1, :] * t[None, :, None]).reshape(-1, 2)
        cells = np.repeat(seg_cells, points_per_segment)
        xv = m.x[m.cells[cells]]
        x = xv[:, 0] + ref[:, :1] * (xv[:, 1] - xv[:, 0]) + ref[:, 1:] * (xv[:, 2] - xv[:, 0])
        xs = m.x[m.cells[seg_cells]]
        P = xs[:, 0] + seg[:, 0, :1] * (xs[:, 1] - xs[:, 0]) + seg[:, 0, 1:] * (xs[:, 2] - xs[:, 0])
        Q = xs[:, 0] + seg[:, 1, :1] * (xs[:, 1] - xs[:, 0]) + seg[:, 1, 1:] * (xs[:, 2] - xs[:, 0])
        length = np.linalg.norm(Q - P, axis=1)
        weight = (length[:, None] * w[None]).ravel()
        tangent = np.repeat((Q - P) / np.maximum(length, 1e-300)[:, None], points_per_segment, axis=0)
        normal = np.stack([-tangent[:, 1], tangent[:, 0]], axis=1)
        # Point the normal into the + side (phi > 0).
        probe = x + 1e-6 * max(m.h, 1e-300) * normal
        sign = np.where(np.asarray(_cracklip.signed_distance(crack_points, probe)) >= 0.0, 1.0, -1.0)
        normal *= sign[:, None]
        pressure = np.zeros(len(x))
    cells = np.asarray(cells, dtype=np.int32)
    up, _ = _cracklip.evaluate_displacement(m.x, m.cells, m.layout, m.geometries, solution.u, cells, ref,
                                            np.ones(len(cells), dtype=np.int8))
    um, _ = _cracklip.evaluate_displacement(m.x, m.cells, m.layout, m.geometries, solution.u, cells, ref,
                                            -np.ones(len(cells), dtype=np.int8))
    jump = up - um
    tangent = np.stack([normal[:, 1], -normal[:, 0]], axis=1)
    s = arc_length(crack_points, x) if len(x) else np.zeros(0)
    order = np.argsort(s, kind="stable")
    return {"s": s[order], "x": x[order], "weight": weight[order], "normal": normal[order],
            "u_plus": up[order], "u_minus": um[order], "pressure": pressure[order],
            "gap": np.einsum("ij,ij->i", jump, normal)[order],
            "slip": np.einsum("ij,ij->i", jump, tangent)[order]}


def closed_points(samples: dict[str, np.ndarray], contact: str, gap_tol: float) -> np.ndarray:
    """Which sample points are closed: all of them with bilateral contact
    (the lips are held together), those with a positive contact pressure
    with unilateral contact, those whose normal gap is at most gap_tol
    (touching or interpenetrating) without contact."""
    if contact == "bilateral":
        return np.ones(len(samples["s"]), dtype=bool)
    if contact == "unilateral":
        p = samples["pressure"]
        return p > 1e-12 * max(float(np.abs(p).max(initial=0.0)), 1e-300)
    return samples["gap"] <= gap_tol


def crack_statistics(samples: dict[str, np.ndarray], closed: np.ndarray, gap_tol: float,
                     contact: str = "none") -> dict[str, typing.Any]:
    """Pressure statistics (with contact) and open / closed extent of one crack's samples."""
    w, p, gap = samples["weight"], samples["pressure"], samples["gap"]
    total = float(w.sum())
    out = {"length_in_part": total, "points": int(len(w)),
           "closed_length": float(w[closed].sum()), "open_length": float(w[~closed].sum()),
           "closed_fraction": float(w[closed].sum() / total) if total > 0 else 0.0,
           "gap_max": float(gap.max()) if len(gap) else 0.0,
           "interpenetration_max": float(max(0.0, -gap.min())) if len(gap) else 0.0,
           "slip_max_abs": float(np.abs(samples["slip"]).max()) if len(gap) else 0.0,
           "gap_tolerance": float(gap_tol)}
    if contact != "none" and len(p):
        out["pressure"] = {"max": float(p.max()), "min": float(p.min()),
                           "mean": float((w * p).sum() / total) if total > 0 else 0.0,
                           "normal_force": float((w * p).sum())}
    if len(w):
        s = samples["s"]
        out["closed_s_ranges"] = _ranges(s, closed)
    return out


def _ranges(s: np.ndarray, mask: np.ndarray) -> list[list[float]]:
    """[s_first, s_last] of each run of consecutive True samples."""
    out, start = [], None
    for i, flag in enumerate(mask):
        if flag and start is None:
            start = i
        if start is not None and (not flag or i == len(mask) - 1):
            end = i if flag else i - 1
            out.append([float(s[start]), float(s[end])])
            start = None
    return out


# -- results ---------------------------------------------------------------------------------------

def versions() -> dict[str, str]:
    import dolfinx
    import meshio
    import petsc4py
    import scipy
    from . import __version__
    return {"cracklip": __version__, "dolfinx": dolfinx.__version__, "petsc4py": petsc4py.__version__,
            "numpy": np.__version__, "scipy": scipy.__version__, "meshio": meshio.__version__,
            "python": platform.python_version()}


def sif_rows(solution: Solution, radius: float | None) -> list[dict[str, typing.Any]]:
    """K_I, K_II, mode mix (degrees, atan2(K_II, K_I)) and energy release
    rate G = (K_I^2 + K_II^2) / E* at every tip of every crack.

    The mode mix is None where K is negligible: below 1e-6 of the scale
    E* max|u| / sqrt(L) of the solution (L the part's size)."""
    rows = []
    m = solution.model
    E_star = m.scene.material.E_star
    size = float(np.ptp(m.x, axis=0).max())
    k_scale = E_star * float(np.abs(solution.standard_displacement).max()) / math.sqrt(size)
    for ci, cm in enumerate(solution.model.cracks):
        if np.asarray(cm.geometry.tips).size == 0:
            continue
        for j, k in enumerate(solution.stress_intensity_factors(ci, radius=radius)):
            rows.append({"crack": ci, "crack_name": cm.crack.name, "tip": j, "x": k["tip"][0], "y": k["tip"][1],
                         "direction": k["direction"], "K_I": k["K_I"], "K_II": k["K_II"],
                         "mode_mix_deg": (math.degrees(math.atan2(k["K_II"], k["K_I"]))
                                          if math.hypot(k["K_I"], k["K_II"]) > 1e-6 * k_scale else None),
                         "G": (k["K_I"] ** 2 + k["K_II"] ** 2) / E_star, "radius": k["radius"]})
    return rows


def ensure_output_dir(path: str | pathlib.Path) -> pathlib.Path:
    """Create the output folder and check that files can be written in it
    (before a long solve); OutputError naming the folder otherwise."""
    path = pathlib.Path(path)
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path, prefix=".cracklip-write-test"):
            pass
    except OSError as e:
        raise OutputError(f"cannot write to the output folder {path}: {e.strerror or e}") from None
    return path


def _finite(name: str, *arrays) -> None:
    for a in arrays:
        if not np.all(np.isfinite(np.asarray(a, dtype=float))):
            raise SolverError(f"{name} holds NaN or infinity: the solution is not usable")


def write_outputs(scene_file, solution: Solution, out_dir: str | pathlib.Path,
                  timings: dict[str, float] | None = None) -> dict[str, typing.Any]:
    """Write every output of a solved scene file into out_dir and return the
    results (what results.json holds)."""
    out = ensure_output_dir(out_dir)
    timings = dict(timings or {})
    cfg = scene_file.outputs
    m = solution.model
    files: list[str] = []

    t0 = time.perf_counter()
    sifs = sif_rows(solution, scene_file.sif_radius)
    timings["sif"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    samples = [crack_samples(solution, i, cfg["crack_points"]) for i in range(len(m.cracks))]
    u_scale = float(np.abs(solution.standard_displacement).max()) if m.num_dofs else 0.0
    gap_tol = 1e-6 * max(u_scale, 1e-300)
    law = m.scene.options.contact if solution.contact else "none"
    closed = [closed_points(smp, law, gap_tol) for smp in samples]
    crack_stats = [{"crack": i, "name": m.cracks[i].crack.name, **crack_statistics(smp, closed[i], gap_tol, law)}
                   for i, smp in enumerate(samples)]
    energy = solution.strain_energy()
    timings["crack_post"] = time.perf_counter() - t0
    _finite("the displacement", solution.u)
    for smp in samples:
        _finite("the crack samples", smp["pressure"], smp["gap"], smp["slip"])

    t0 = time.perf_counter()
    _write_csv(out / "crack.csv", ["crack", "s", "x", "y", "pressure", "gap", "slip", "closed"],
               [[i, smp["s"][k], smp["x"][k, 0], smp["x"][k, 1], smp["pressure"][k], smp["gap"][k],
                 smp["slip"][k], int(closed[i][k])]
                for i, smp in enumerate(samples) for k in range(len(smp["s"]))])
    _write_csv(out / "sif.csv", ["crack", "tip", "x", "y", "direction_x", "direction_y", "K_I", "K_II",
                                 "mode_mix_deg", "G", "radius"],
               [[r["crack"], r["tip"], r["x"], r["y"], r["direction"][0], r["direction"][1], r["K_I"],
                 r["K_II"], r["mode_mix_deg"], r["G"], r["radius"]] for r in sifs])
    files += ["crack.csv", "sif.csv"]
    timings["write_csv"] = time.perf_counter() - t0
    if cfg["vtu"]:
        t0 = time.perf_counter()
        write_mesh(subcell_mesh(solution), out / "solution.vtu")
        write_mesh(crack_lips_mesh(samples), out / "crack_lips.vtu")
        files += ["solution.vtu", "crack_lips.vtu"]
        timings["write_vtu"] = time.perf_counter() - t0
        logger.info("wrote ParaView files solution.vtu, crack_lips.vtu")
    if cfg["png"]:
        t0 = time.perf_counter()
        files += write_pngs(solution, samples, out, cfg["magnification"], cfg["stress_component"],
                            scene_file.title)
        timings["write_png"] = time.perf_counter() - t0
        logger.info("wrote PNGs")

    contact = None
    if solution.contact:
        c = solution.contact
        contact = {"law": m.scene.options.contact, "space": m.scene.options.multipliers,
                   "multipliers": int(c["system"].num_multipliers), "active": int(np.count_nonzero(c["active"])),
                   "iterations": int(c["iterations"]), "active_history": [int(v) for v in c["history"]]}
    solver = getattr(solution, "solver", None) or {}
    results = {
        "title": scene_file.title,
        "scene_file": str(scene_file.path) if scene_file.path is not None else None,
        "versions": versions(),
        "model": describe_model(m, solution.contact.get("system") if solution.contact else None),
        "boundary_conditions_and_loads": scene_file.notes,
        "solution": {"dofs": int(m.num_dofs), "strain_energy": energy, "max_displacement": u_scale,
                     "relative_residual": solver.get("relative_residual")},
        "sifs": sifs,
        "cracks": crack_stats,
        "contact": contact,
        "condition_number": dict(solution.condition) if solution.condition else None,
        "timings": {},
        "files": files + ["results.json"],
    }
    timings = {**timings, **{f"solve.{k}": v for k, v in solution.timings.items()}}
    results["timings"] = timings
    try:
        text = json.dumps(results, indent=2, allow_nan=False, default=_json_default)
    except ValueError as e:
        raise SolverError(f"results.json would hold NaN or infinity ({e}); nothing written") from None
    with atomic_path(out / "results.json") as tmp:
        tmp.write_text(text + "\n")
    logger.info("wrote %s", ", ".join(results["files"]))
    return results


def _json_default(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"cannot write {type(value).__name__} to JSON")


def _write_csv(path: pathlib.Path, header: list[str], rows: list[list]) -> None:
    with atomic_path(path) as tmp:
        with tmp.open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            for r in rows:
                w.writerow(["" if v is None else f"{v:.12g}" if isinstance(v, (float, np.floating)) else v
                            for v in r])


# -- pictures --------------------------------------------------------------------------------------

def _figure(size):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    return fig


def _save(fig, path: pathlib.Path) -> None:
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=150, bbox_inches="tight", format="png")


def magnification(solution: Solution, fields: dict, requested: float) -> float:
    """The displacement scale of deformed.png: as requested, or such that the
    largest displacement is 5 % of the part's size."""
    if requested > 0.0:
        return requested
    size = float(np.ptp(solution.model.x, axis=0).max())
    umax = float(np.linalg.norm(fields["displacement"], axis=1).max()) if len(fields["displacement"]) else 0.0
    if umax <= 0.0:
        return 1.0
    raw = 0.05 * size / umax
    exp = math.floor(math.log10(raw))
    return float(round(raw / 10 ** exp) * 10 ** exp) or raw


def write_pngs(solution: Solution, samples: list[dict], out: pathlib.Path, scale: float,
               component: str, title: str) -> list[str]:
    """deformed.png (sub-cells displaced, magnified), crack_pressure.png
    (pressure and gap, or opening and slip, along each crack) and
    stress.png (a stress component on the sub-cells)."""
    from matplotlib.collections import PolyCollection
    f = solution.subcell_fields()
    tris = f["points"].reshape(-1, 3, 2)
    disp = f["displacement"].reshape(-1, 3, 2)
    mag = magnification(solution, f, scale)
    names = []
    extent = np.ptp(solution.model.x, axis=0)
    size = (8.0, float(np.clip(8.0 * extent[1] / max(extent[0], 1e-300), 3.0, 8.0)))

    fig = _figure(size)
    ax = fig.add_subplot()
    umag = np.linalg.norm(disp, axis=2).mean(axis=1)
    coll = PolyCollection(tris + mag * disp, array=umag, cmap="viridis", edgecolors="k", linewidths=0.1)
    ax.add_collection(coll)
    for smp in samples:
        for key in ("u_plus", "u_minus"):
            xy = smp["x"] + mag * smp[key]
            ax.plot(xy[:, 0], xy[:, 1], "r-", lw=0.8)
    ax.autoscale()
    ax.set_aspect("equal")
    fig.colorbar(coll, ax=ax, label="|u| (length units)")
    ax.set_title(f"{title}\ndeformed mesh, displacement x{mag:g}", fontsize=10)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    _save(fig, out / "deformed.png")
    names.append("deformed.png")

    fig = _figure((7, 4))
    ax = fig.add_subplot()
    ax2 = ax.twinx()
    contact = bool(solution.contact)
    for i, smp in enumerate(samples):
        label = solution.model.cracks[i].crack.name
        if contact:
            ax.plot(smp["s"], smp["pressure"], ".-", ms=3, lw=0.8, label=f"{label}: pressure")
            ax2.plot(smp["s"], smp["gap"], "x:", ms=3, lw=0.8, color=f"C{i + 3}", label=f"{label}: gap")
        else:
            ax.plot(smp["s"], smp["gap"], ".-", ms=3, lw=0.8, label=f"{label}: opening [[u]].n")
            ax2.plot(smp["s"], smp["slip"], "x:", ms=3, lw=0.8, color=f"C{i + 3}", label=f"{label}: slip [[u]].t")
    ax.set_xlabel("arc length along the crack (from its first point)")
    ax.set_ylabel("contact pressure (>= 0 in compression)" if contact else "normal opening")
    ax2.set_ylabel("normal gap" if contact else "tangential slip")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    if h1 or h2:
        ax.legend(h1 + h2, l1 + l2, fontsize=7)
    ax.set_title(f"{title}\nalong the crack" + (" (traction-free lips: no pressure)" if not contact else ""),
                 fontsize=10)
    _save(fig, out / "crack_pressure.png")
    names.append("crack_pressure.png")

    fig = _figure(size)
    ax = fig.add_subplot()
    s = f["stress"]
    values = {"xx": s[:, 0], "yy": s[:, 1], "xy": s[:, 2]}.get(component)
    if values is None:
        values = von_mises(s, solution.model.scene.material.nu)
    cmap = "viridis" if component == "von_mises" else "coolwarm"
    coll = PolyCollection(tris, array=values, cmap=cmap, edgecolors="none")
    if component != "von_mises" and len(values):
        lim = float(np.abs(values).max()) or 1.0
        coll.set_clim(-lim, lim)
    ax.add_collection(coll)
    for smp in samples:
        ax.plot(smp["x"][:, 0], smp["x"][:, 1], "k-", lw=0.8)
    ax.autoscale()
    ax.set_aspect("equal")
    label = "von Mises stress" if component == "von_mises" else f"stress {component}"
    fig.colorbar(coll, ax=ax, label=f"{label} (units of E)")
    ax.set_title(f"{title}\n{label}", fontsize=10)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    _save(fig, out / "stress.png")
    names.append("stress.png")
    return names


__all__ = ["OutputError", "describe_model", "format_model", "crack_samples", "crack_statistics",
           "write_outputs", "ensure_output_dir", "sif_rows", "versions"]
