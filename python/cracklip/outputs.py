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


def describe_model(model: XfemModel, contact_system=None, solution: Solution | None = None) -> dict[str, typing.Any]:
    """Counts of what the model holds: nodes, cells, dofs; per crack its cell
    classes, Heaviside and tip nodes (core and blending) and their dofs; the
    quadrature per kind of enriched cell; the contact multipliers.

    contact_system: the contact.ContactSystem the solve uses (None without
    contact). solution: a solution of the model, whose quadrature points
    give the counts (computed otherwise)."""
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
        from .sif import tip_domains
        domains = tip_domains(model, ci)
        cracks.append({
            "name": cm.crack.name,
            "polyline_points": int(len(pts)),
            "length": float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()),
            "kind": {0: "through (no tip inside)", 1: "edge (one tip)", 2: "interior (two tips)"}[sum(cm.tips)],
            "tips": np.asarray(g.tips).tolist(),
            "tip_element_size": [d.element_size for d in domains],
            "sif_radius": [d.radius for d in domains],
            "sif_limited_by": [d.obstacle if d.limited or not d.clear else None for d in domains],
            "lip_pressure": "function" if callable(cm.crack.pressure) else float(cm.crack.pressure),
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
        "quadrature": _describe_quadrature(model, solution),
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


def _describe_quadrature(model: XfemModel, solution: Solution | None = None) -> list[dict[str, typing.Any]]:
    """Cells of each quadrature kind with their rule and point counts (the
    points of solution.enriched_field_points() if given)."""
    layout = model.layout
    opts = model.scene.options
    ncells = model.cells.shape[0]
    enr_cells = np.asarray(layout.cells, dtype=np.int32)
    groups = [{"cells": "plain cells (standard block only)", "count": int(ncells - enr_cells.size),
               "rule": "DOLFINx's rule for the P1 stiffness", "points": None}]
    if enr_cells.size == 0:
        return groups
    fp = solution.enriched_field_points() if solution is not None else _cracklip.compute_field_points(
        model.x, model.cells, layout, model.geometries, np.zeros(model.num_dofs), enr_cells,
        opts.quadrature_options())
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
        for t, h, r, lim in zip(c["tips"], c["tip_element_size"], c["sif_radius"], c["sif_limited_by"]):
            lines.append(f"  tip ({t[0]:.6g}, {t[1]:.6g}): element size {h:.4g}, SIF domains of radius "
                         f"{0.5 * r:.4g}, {0.75 * r:.4g}, {r:.4g}" + (f" (limited by {lim})" if lim else ""))
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
        lines.append(f"contact: {c['law']}, {c['space']} space: {c['multipliers']} multipliers "
                     f"({c['full_multipliers']} full, {c['p0_multipliers']} P0 in tip cells) on "
                     f"{c['segments']} crack segments x {c['points_per_segment']} points")
    return lines


# -- along the cracks ------------------------------------------------------------------------------

def crack_samples(solution: Solution, crack: int, points_per_segment: int = 3) -> dict[str, np.ndarray]:
    """Points along a crack with the lips' displacements, gap, slip and
    contact pressure: Solution.lip_samples."""
    return solution.lip_samples(crack, points_per_segment)


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
        state = samples["state"]
        for name in ("open", "stick", "slip"):
            out[f"{name}_length"] = float(w[state == name].sum())
            out[f"{name}_s_ranges"] = _ranges(samples["s"], state == name)
        out["shear_max_abs"] = float(np.abs(samples["shear"]).max())
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
    import petsc4py
    import scipy
    from . import __version__
    from .linear_solver import blas_library
    return {"cracklip": __version__, "dolfinx": dolfinx.__version__, "petsc4py": petsc4py.__version__,
            "numpy": np.__version__, "scipy": scipy.__version__,
            "python": platform.python_version(), "blas": blas_library()}


def sif_rows(solution: Solution) -> list[dict[str, typing.Any]]:
    """K_I, K_II with their domain spread, mode mix (degrees, atan2(K_II,
    K_I); None where K is negligible) and energy release rate G = (K_I^2 +
    K_II^2) / E* at every tip of every crack (Solution.stress_intensity_factors)."""
    return solution.stress_intensity_factors(None)


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
    t_outputs = time.perf_counter()
    out = ensure_output_dir(out_dir)
    timings = dict(timings or {})
    cfg = scene_file.outputs
    m = solution.model
    files: list[str] = []

    states = solution.steps or [solution]
    t0 = time.perf_counter()
    sifs = sif_rows(solution)
    warnings = [w.as_dict() for w in solution.warnings]
    timings["sif"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    u_scale = float(np.abs(solution.standard_displacement).max()) if m.num_dofs else 0.0
    gap_tol = 1e-6 * max(u_scale, 1e-300)
    law = m.scene.options.contact if solution.contact else "none"
    per_step = []
    for st in states:
        smps = [crack_samples(st, i, cfg["crack_points"]) for i in range(len(m.cracks))]
        shut = [closed_points(smp, law, gap_tol) for smp in smps]
        per_step.append((st, smps, shut))
        for smp in smps:
            _finite("the crack samples", smp["pressure"], smp["gap"], smp["slip"], smp["shear"])
    _, samples, closed = per_step[-1]
    crack_stats = [{"crack": i, "name": m.cracks[i].crack.name, **crack_statistics(smp, closed[i], gap_tol, law)}
                   for i, smp in enumerate(samples)]
    energy = solution.strain_energy()
    timings["crack_post"] = time.perf_counter() - t0
    _finite("the displacement", solution.u)

    t0 = time.perf_counter()
    _write_csv(out / "crack.csv", ["step", "crack", "s", "x", "y", "pressure", "shear", "gap", "slip", "state",
                                   "closed"],
               [[k, i, smp["s"][j], smp["x"][j, 0], smp["x"][j, 1], smp["pressure"][j], smp["shear"][j],
                 smp["gap"][j], smp["slip"][j], smp["state"][j], int(shut[i][j])]
                for k, (_, smps, shut) in enumerate(per_step) for i, smp in enumerate(smps)
                for j in range(len(smp["s"]))])
    step_sifs = [(k, st.stress_intensity_factors(None) if st is not solution else sifs)
                 for k, (st, _, _) in enumerate(per_step)]
    _write_csv(out / "sif.csv", ["step", "crack", "tip", "x", "y", "direction_x", "direction_y", "K_I", "K_II",
                                 "K_I_spread", "K_II_spread", "mode_mix_deg", "G", "radius", "element_size",
                                 "limited_by", "domain_clear"],
               [[k, r["crack"], r["tip"], r["x"], r["y"], r["direction"][0], r["direction"][1], r["K_I"],
                 r["K_II"], r["K_I_spread"], r["K_II_spread"], r["mode_mix_deg"], r["G"], r["radius"],
                 r["element_size"], r["limited_by"], int(r["domain_clear"])] for k, rows in step_sifs for r in rows])
    files += ["crack.csv", "sif.csv"]
    timings["write_csv"] = time.perf_counter() - t0
    # The sub-cell fields, shared by the ParaView file and the PNGs.
    t0 = time.perf_counter()
    fields = solution.subcell_fields() if cfg["vtu"] or cfg["png"] else None
    timings["subcell_fields"] = time.perf_counter() - t0
    if cfg["vtu"]:
        t0 = time.perf_counter()
        write_mesh(subcell_mesh(solution, fields), out / "solution.vtu")
        write_mesh(crack_lips_mesh(samples), out / "crack_lips.vtu")
        files += ["solution.vtu", "crack_lips.vtu"]
        timings["write_vtu"] = time.perf_counter() - t0
        logger.info("wrote ParaView files solution.vtu, crack_lips.vtu")
    if cfg["png"]:
        t0 = time.perf_counter()
        files += write_pngs(solution, samples, out, cfg["magnification"], cfg["stress_component"],
                            scene_file.title, fields)
        timings["write_png"] = time.perf_counter() - t0
        logger.info("wrote PNGs")

    contact = contact_summary(solution)
    solver = getattr(solution, "solver", None) or {}
    results = {
        "title": scene_file.title,
        "scene_file": str(scene_file.path) if scene_file.path is not None else None,
        "versions": versions(),
        "model": describe_model(m, solution.contact.get("system") if solution.contact else None, solution),
        "boundary_conditions_and_loads": scene_file.notes,
        "solution": {"dofs": int(m.num_dofs), "strain_energy": energy, "max_displacement": u_scale,
                     "relative_residual": solver.get("relative_residual"),
                     "solver": solver.get("solver"), "solves": solver.get("solves", [])},
        "warnings": warnings,
        "sifs": sifs,
        "cracks": crack_stats,
        "contact": contact,
        "steps": [{"step": k, "name": st.step["name"], "factors": st.step["factors"],
                   "increments": st.step["increments"], "contact": contact_summary(st),
                   "sifs": [{key: r[key] for key in ("crack", "tip", "K_I", "K_II", "K_I_spread", "K_II_spread")}
                            for r in rows],
                   "cracks": [{"crack": i, **{key: v for key, v in crack_statistics(smp, shut[i], gap_tol, law).items()
                                               if key in ("closed_fraction", "stick_length", "slip_length",
                                                          "open_length", "slip_max_abs")}}
                              for i, smp in enumerate(smps)]}
                  for k, ((st, smps, shut), (_, rows)) in enumerate(zip(per_step, step_sifs))]
        if solution.steps else None,
        "condition_number": dict(solution.condition) if solution.condition else None,
        "timings": {},
        "files": files + ["results.json"],
    }
    # Everything written so far and results.json's content (not its dump).
    timings["outputs_total"] = time.perf_counter() - t_outputs
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


def contact_summary(solution: Solution) -> dict[str, typing.Any] | None:
    """The contact law, multipliers and iterations of a solution (with
    friction: mu, the states' counts and the method that settled them)."""
    if not solution.contact:
        return None
    m = solution.model
    c = solution.contact
    out = {"law": m.scene.options.contact, "space": m.scene.options.multipliers,
           "multipliers": int(c["system"].num_multipliers), "active": int(np.count_nonzero(c["active"])),
           "iterations": int(c["iterations"])}
    if "state" in c:
        from .friction import STATE_NAMES
        out["friction"] = m.scene.options.friction
        out["states"] = {name: int(np.count_nonzero(c["state"] == code)) for code, name in STATE_NAMES.items()}
        out["method"] = c.get("method")
        out["state_history"] = c["history"]
    else:
        out["active_history"] = [int(v) for v in c["history"]]
    if "increment_iterations" in c:
        out["increment_iterations"] = c["increment_iterations"]
    return out


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

#: crack_pressure.png draws an open crack's tangential slip on the opening's
#: axis when it is at most this fraction of the largest opening (noise).
SLIP_PLOT_FRACTION = 1e-3

def _figure(size):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    return fig


#: Resolution and margin of the PNGs (savefig's pad_inches for bbox_inches="tight").
PNG_DPI = 150
PNG_PAD_INCHES = 0.1


def _save(fig, path: pathlib.Path) -> None:
    """fig as a PNG cropped to its ink (the pixels not of the face colour)
    plus PNG_PAD_INCHES on every side, drawn once: savefig(bbox_inches=
    "tight") draws every figure twice and measures the artists' boxes
    (get_tightbbox alone took 0.05 s per figure at 2e5 dofs); the ink box
    is the same content without the few pixels of slack in the artists'
    boxes. Ink on the canvas's border may continue outside the figure (a
    title longer than the figure is wide): such a figure goes to savefig
    (three draws then), which enlarges the picture to hold it."""
    fig.set_dpi(PNG_DPI)
    canvas = fig.canvas
    canvas.draw()
    rgba = np.asarray(canvas.buffer_rgba())
    height, width = rgba.shape[:2]
    face = np.round(np.asarray(fig.get_facecolor()) * 255).astype(np.uint8)
    # Ink: RGB not the face's (alpha may differ on an opaque canvas), one
    # 32-bit compare per pixel.
    rgb_mask = np.array([255, 255, 255, 0], dtype=np.uint8).view(np.uint32)[0]
    ink = (np.ascontiguousarray(rgba).view(np.uint32)[..., 0] & rgb_mask) != (face.view(np.uint32)[0] & rgb_mask)
    rows, cols = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
    if rows.size and (rows[0] == 0 or cols[0] == 0 or rows[-1] == height - 1 or cols[-1] == width - 1):
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=PNG_DPI, bbox_inches="tight", pad_inches=PNG_PAD_INCHES, format="png",
                        pil_kwargs={"compress_level": 1})
        return
    if rows.size:
        pad = int(round(PNG_PAD_INCHES * PNG_DPI))
        r0, r1, c0, c1 = rows[0] - pad, rows[-1] + 1 + pad, cols[0] - pad, cols[-1] + 1 + pad
    else:  # nothing drawn: the whole canvas
        r0, r1, c0, c1 = 0, height, 0, width
    crop = np.empty((r1 - r0, c1 - c0, 4), dtype=np.uint8)
    crop[...] = face
    rs, cs = slice(max(r0, 0), min(r1, height)), slice(max(c0, 0), min(c1, width))
    crop[rs.start - r0:rs.stop - r0, cs.start - c0:cs.stop - c0] = rgba[rs, cs]
    from PIL import Image
    with atomic_path(path) as tmp:
        # compress_level 1: a third of the encoding time of the default 6, files ~10 % larger.
        with open(tmp, "wb") as fh:
            Image.fromarray(crop).save(fh, format="png", compress_level=1)


def magnification(solution: Solution, fields: dict, requested: float) -> float:
    """The displacement scale of deformed.png: as requested, or such that the
    largest displacement is 5 % of the part's size."""
    if requested > 0.0:
        return requested
    size = float(np.ptp(solution.model.x, axis=0).max())
    umax = float(np.linalg.norm(fields["displacement"], axis=1).max()) if len(fields["displacement"]) else 0.0
    if umax <= 0.0:
        return 1.0
    return _round_scale(0.05 * size / umax)


def _round_scale(raw: float) -> float:
    """A scale factor rounded to one significant digit."""
    if not (raw > 0.0 and math.isfinite(raw)):
        return 1.0
    exp = math.floor(math.log10(raw))
    return float(round(raw / 10 ** exp) * 10 ** exp) or raw


#: deformed.png adds a zoomed panel when the cracks' box is below this fraction of the part.
ZOOM_FRACTION = 0.25
#: stress.png's colour scale ends at this area-weighted percentile of |stress|,
#: so that a tip singularity does not wash out the far field.
STRESS_PERCENTILE = 99.0


def crack_window(solution: Solution) -> tuple[np.ndarray, np.ndarray] | None:
    """(lower, upper) corners of a window around the cracks for a zoomed
    view, or None when the cracks are not much smaller than the part."""
    m = solution.model
    if not m.cracks:
        return None
    lo_part, hi_part = m.x.min(axis=0), m.x.max(axis=0)
    pts = np.concatenate([np.clip(cm.crack.points, lo_part, hi_part) for cm in m.cracks])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = float(max(np.ptp(pts, axis=0).max(), 1e-300))
    if span > ZOOM_FRACTION * float(np.ptp(m.x, axis=0).max()):
        return None
    centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo) + 0.35 * span
    return np.maximum(centre - half, lo_part), np.minimum(centre + half, hi_part)


def _weighted_percentile(values: np.ndarray, weights: np.ndarray, q: float) -> float:
    order = np.argsort(values)
    c = np.cumsum(weights[order])
    return float(values[order][min(np.searchsorted(c, q / 100.0 * c[-1]), len(c) - 1)])


#: Above this many sub-triangles in a panel, a field is drawn as an image
#: (cracklip.raster) instead of one polygon per triangle with its edges
#: (at 1.9e5 sub-triangles: polygons 3.9 s, image 0.1 s; the edges of that
#: many cells would blacken the picture anyway).
RASTER_MIN_TRIANGLES = 20_000
#: Pixels along the longer side of a rasterised panel.
RASTER_PIXELS = 1000


def _draw_field(ax, tris: np.ndarray, values: np.ndarray, cmap: str, clim: tuple[float, float],
                edges: bool):
    """Draw the field `values` constant on `tris` (n, 3, 2) into ax and
    return the mappable: polygons (with the mesh's edges if `edges`) up to
    RASTER_MIN_TRIANGLES, an image beyond."""
    if len(tris) <= RASTER_MIN_TRIANGLES:
        from matplotlib.collections import PolyCollection
        coll = PolyCollection(tris, array=values, cmap=cmap, edgecolors="k" if edges else "none",
                              linewidths=0.1 if edges else 0.0)
        coll.set_clim(*clim)
        ax.add_collection(coll)
        return coll
    from .raster import image_shape, rasterize
    lo, hi = tris.reshape(-1, 2).min(axis=0), tris.reshape(-1, 2).max(axis=0)
    extent = (float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1]))
    image = rasterize(tris, values, extent, image_shape(extent, RASTER_PIXELS))
    return ax.imshow(image, origin="lower", extent=extent, cmap=cmap, vmin=clim[0], vmax=clim[1],
                     interpolation="nearest", aspect="equal")


def write_pngs(solution: Solution, samples: list[dict], out: pathlib.Path, scale: float,
               component: str, title: str, fields: dict | None = None) -> list[str]:
    """deformed.png (sub-cells displaced, magnified; with a zoom on the
    cracks when they are small in the part), crack_pressure.png (pressure
    and gap, or opening and slip, along each crack) and stress.png (a
    stress component on the sub-cells, colour scale clipped at the
    STRESS_PERCENTILE area-weighted percentile). fields:
    solution.subcell_fields() if the caller has it already."""
    f = solution.subcell_fields() if fields is None else fields
    tris = f["points"].reshape(-1, 3, 2)
    disp = f["displacement"].reshape(-1, 3, 2)
    mag = magnification(solution, f, scale)
    names = []
    extent = np.ptp(solution.model.x, axis=0)
    height = float(np.clip(8.0 * extent[1] / max(extent[0], 1e-300), 3.0, 8.0))
    window = crack_window(solution)
    umag = np.linalg.norm(disp, axis=2).mean(axis=1)

    fig = _figure((15.0, height) if window is not None else (8.0, height))
    panels = [fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)] if window is not None else [fig.add_subplot()]
    for k, ax in enumerate(panels):
        zoom = k == 1
        sel, m = slice(None), mag
        if zoom:
            c = tris.mean(axis=1)
            span = np.ptp(window, axis=0)
            sel = np.all((c >= window[0] - 0.1 * span) & (c <= window[1] + 0.1 * span), axis=1)
            # Its own scale: the largest displacement in the window is 5 % of the window.
            m = scale if scale > 0.0 else _round_scale(0.05 * float(span.max()) / max(float(umag[sel].max(initial=0.0)), 1e-300))
        coll = _draw_field(ax, (tris + m * disp)[sel], umag[sel], "viridis",
                           (float(umag.min(initial=0.0)), float(umag.max(initial=1.0))), edges=True)
        for smp in samples:
            for key in ("u_plus", "u_minus"):
                xy = smp["x"] + m * smp[key]
                ax.plot(xy[:, 0], xy[:, 1], "r-", lw=0.8)
        ax.autoscale()
        if zoom:
            ax.set_xlim(window[0][0], window[1][0])
            ax.set_ylim(window[0][1], window[1][1])
            ax.set_title(f"around the cracks, displacement x{m:g}", fontsize=9)
        elif window is not None:
            ax.add_patch(_rectangle(window))
            ax.set_title(f"displacement x{m:g}", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    fig.colorbar(coll, ax=panels, label="|u| (length units)")
    fig.suptitle(f"{title}\ndeformed mesh" + ("" if window is not None else f", displacement x{mag:g}"), fontsize=10)
    _save(fig, out / "deformed.png")
    names.append("deformed.png")

    contact = bool(solution.contact)
    mu = solution.model.scene.options.friction if contact and "lambda_t" in solution.contact else 0.0
    fig = _figure((7, 6.5) if mu else (7, 4))
    ax = fig.add_subplot(2, 1, 1) if mu else fig.add_subplot()
    ax2 = ax.twinx()
    # A slip below 1e-3 of the opening (pure mode I: discretisation noise)
    # goes on the opening's axis, where it reads as the zero it is, instead of
    # an axis of its own that would blow the noise up to full height.
    peak = max([float(np.abs(smp[k]).max(initial=0.0)) for smp in samples for k in ("gap", "slip")] or [0.0])
    slip_small = not contact and all(np.abs(smp["slip"]).max(initial=0.0) <= SLIP_PLOT_FRACTION * peak
                                     for smp in samples)
    for i, smp in enumerate(samples):
        label = solution.model.cracks[i].crack.name
        if contact:
            ax.plot(smp["s"], smp["pressure"], ".-", ms=3, lw=0.8, label=f"{label}: pressure")
            ax2.plot(smp["s"], smp["gap"], "x:", ms=3, lw=0.8, color=f"C{i + 3}", label=f"{label}: gap")
        else:
            ax.plot(smp["s"], smp["gap"], ".-", ms=3, lw=0.8, label=f"{label}: opening [[u]].n")
            tail = f" (|slip| <= {SLIP_PLOT_FRACTION:g} x the opening)" if slip_small else ""
            (ax if slip_small else ax2).plot(smp["s"], smp["slip"], "x:", ms=3, lw=0.8, color=f"C{i + 3}",
                                             label=f"{label}: slip [[u]].t{tail}")
    ax.set_xlabel("arc length along the crack (from its first point)")
    ax.set_ylabel("contact pressure (>= 0 in compression)" if contact else
                  "normal opening and tangential slip" if slip_small else "normal opening")
    if slip_small:
        ax2.set_axis_off()
    ax2.set_ylabel("normal gap" if contact else "tangential slip")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    if h1 or h2:
        ax.legend(h1 + h2, l1 + l2, fontsize=7)
    ax.set_title(f"{title}\nalong the crack" + (" (traction-free lips: no pressure)" if not contact else ""),
                 fontsize=10)
    if mu:
        # Friction: the shear against its bound mu p, the slip, and the states.
        bx = fig.add_subplot(2, 1, 2, sharex=ax)
        bx2 = bx.twinx()
        for i, smp in enumerate(samples):
            label = solution.model.cracks[i].crack.name
            bx.plot(smp["s"], np.abs(smp["shear"]), ".-", ms=3, lw=0.8, color=f"C{i}", label=f"{label}: |shear|")
            bx.plot(smp["s"], mu * np.maximum(smp["pressure"], 0.0), "--", lw=0.8, color=f"C{i}",
                    label=f"{label}: mu p = {mu:g} p")
            bx2.plot(smp["s"], smp["slip"], "x:", ms=3, lw=0.8, color=f"C{i + 3}", label=f"{label}: slip [[u]].t")
            for name, colour in (("stick", "tab:green"), ("slip", "tab:red"), ("open", "0.6")):
                on = smp["state"] == name
                if np.any(on):
                    bx.plot(smp["s"][on], np.zeros(np.count_nonzero(on)), "|", color=colour, ms=6,
                            label=f"{label}: {name}" if i == 0 else None)
        bx.set_xlabel("arc length along the crack (from its first point)")
        bx.set_ylabel("friction traction")
        bx2.set_ylabel("slip (accumulated)")
        h1, l1 = bx.get_legend_handles_labels()
        h2, l2 = bx2.get_legend_handles_labels()
        bx.legend(h1 + h2, l1 + l2, fontsize=6, ncol=2)
        bx.set_title("friction: shear against its bound, slip, states (stick green, slip red, open grey)",
                     fontsize=9)
        fig.tight_layout()
    _save(fig, out / "crack_pressure.png")
    names.append("crack_pressure.png")

    fig = _figure((8.0, height))
    ax = fig.add_subplot()
    s = f["stress"]
    values = {"xx": s[:, 0], "yy": s[:, 1], "xy": s[:, 2]}.get(component)
    if values is None:
        values = von_mises(s, solution.model.scene.material.sigma_zz_ratio)
    cmap = "viridis" if component == "von_mises" else "coolwarm"
    lim = 1.0
    if len(values):
        e1, e2 = tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
        area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
        lim = _weighted_percentile(np.abs(values), area, STRESS_PERCENTILE) or float(np.abs(values).max()) or 1.0
    coll = _draw_field(ax, tris, values, cmap, (0.0 if component == "von_mises" else -lim, lim), edges=False)
    for smp in samples:
        ax.plot(smp["x"][:, 0], smp["x"][:, 1], "k-", lw=0.8)
    ax.autoscale()
    ax.set_aspect("equal")
    label = "von Mises stress" if component == "von_mises" else f"stress {component}"
    fig.colorbar(coll, ax=ax, extend="max" if component == "von_mises" else "both",
                 label=f"{label} (the input's stress units; scale clipped at the "
                       f"{STRESS_PERCENTILE:g}th percentile)")
    ax.set_title(f"{title}\n{label}", fontsize=10)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    _save(fig, out / "stress.png")
    names.append("stress.png")
    return names


def _rectangle(window):
    from matplotlib.patches import Rectangle
    (x0, y0), (x1, y1) = window
    return Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ec="r", lw=0.8, ls="--")


__all__ = ["OutputError", "describe_model", "format_model", "crack_samples", "crack_statistics",
           "write_outputs", "ensure_output_dir", "sif_rows", "versions"]
