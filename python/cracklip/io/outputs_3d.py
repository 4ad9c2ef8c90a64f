"""What a run of a 3D scene writes (outputs.write_outputs hands tetrahedral
solutions here): results.json, the ParaView files, crack_opening.png and
crack_opening.csv.

- ``solution.vtu``: the sub-tetrahedral mesh (paraview_3d.solution_mesh);
- ``crack_surface.vtu``: both lips of every crack with the opening;
- ``crack_front.vtu``: the fronts as polylines with arc length and frame;
- ``crack_opening.png`` and ``crack_opening.csv``: the normal opening at
  the vertices of the lip facets, each split in OPENING_SUBDIVISION^2
  triangles (the same samples in both), over each crack's own plane
  coordinates;
- ``results.json``: the model summary (describe_model), the solution's
  dofs, energy and solver, per crack its area in the part, opened volume,
  opening and slip statistics and its front, warnings, timings, files, and
  ``sifs``: ``front_rows(solution)``, the stress intensity factors at every
  front point (io.front_outputs);
- ``front.csv``, ``front_sifs.png``, ``front_sifs.vtu``: the same K along
  the fronts as a table, a plot and a ParaView polyline (io.front_outputs).

Files go through atomic_path (never half-written), as in 2D.
"""
from __future__ import annotations

import json
import logging
import pathlib
import time
import typing

import numpy as np

from ..errors import SolverError
from ..post.subcells_3d import lip_facets_3d, subcell_fields_3d
from .files import atomic_path
from .front_outputs import FRONT_COLUMNS, csv_rows, front_rows, front_sif_mesh, write_front_png
from .model_summary import describe_model
from .results import check_finite, ensure_output_dir, json_default, versions, write_csv
from .paraview import write_mesh
from .paraview_3d import crack_surface_mesh, front_mesh, solution_mesh
from .pictures_3d import plane_coordinates, write_crack_opening_png


logger = logging.getLogger(__name__)


#: crack_opening.png and .csv sample each lip facet on this many triangles
#: per side (4 per facet): the sqrt(r) opening of the facets touching the
#: front is drawn without dark slivers.
OPENING_SUBDIVISION = 2


def crack_statistics_3d(facets: dict, samples: dict) -> dict[str, typing.Any]:
    """Per crack: area in the part, opened volume int [[u]].n dA and the
    area-weighted mean opening (on the lip quadrature samples), the largest
    opening, slip and interpenetration (on the facet vertices and samples)."""
    w, gap = samples["weight"], samples["gap"]
    area = float(np.sum(facets["area"]))
    volume = float(np.sum(w * gap))
    gv = facets["gap"].reshape(-1)
    slip = np.concatenate([facets["slip"].reshape(-1), np.linalg.norm(samples["slip"], axis=1)])
    return {"area_in_part": area, "facets": int(len(facets["area"])), "points": int(len(w)),
            "opening_volume": volume, "gap_mean": volume / area if area > 0 else 0.0,
            "gap_max": float(max(gv.max(initial=0.0), gap.max(initial=0.0))),
            "interpenetration_max": float(max(0.0, -min(gv.min(initial=0.0), gap.min(initial=0.0)))),
            "slip_max": float(slip.max(initial=0.0))}


def opening_rows(cracks: typing.Sequence, facets: typing.Sequence[dict]) -> list[list]:
    """crack_opening.csv's rows: every vertex of every lip facet."""
    rows = []
    for c, (crack, f) in enumerate(zip(cracks, facets)):
        x = f["x"].reshape(-1, 3)
        uv = plane_coordinates(crack, x)
        nf = len(f["cell"])
        facet = np.repeat(np.arange(nf), 3)
        vertex = np.tile(np.arange(3), nf)
        weight = np.repeat(f["area"] / 3.0, 3)
        jump = f["jump"].reshape(-1, 3)
        gap, slip = f["gap"].reshape(-1), f["slip"].reshape(-1)
        for i in range(len(x)):
            rows.append([c, int(facet[i]), int(vertex[i]), x[i, 0], x[i, 1], x[i, 2], uv[i, 0], uv[i, 1], weight[i],
                         gap[i], slip[i], jump[i, 0], jump[i, 1], jump[i, 2]])
    return rows


def write_outputs_3d(scene_file, solution, out_dir: str | pathlib.Path,
                     timings: dict[str, float] | None = None) -> dict[str, typing.Any]:
    """Write every output of a solved 3D scene file into out_dir and return
    the results (what results.json holds)."""
    t_outputs = time.perf_counter()
    out = ensure_output_dir(out_dir)
    timings = dict(timings or {})
    cfg = scene_file.outputs
    m = solution.model
    files: list[str] = []
    check_finite("the displacement", solution.u)

    t0 = time.perf_counter()
    sifs = front_rows(solution)
    warnings = [w.as_dict() for w in solution.warnings]
    facets = [lip_facets_3d(solution, i) for i in range(len(m.cracks))]
    fine = [lip_facets_3d(solution, i, OPENING_SUBDIVISION) for i in range(len(m.cracks))]
    samples = [solution.lip_samples(i, cfg["crack_points"]) for i in range(len(m.cracks))]
    for f, g, smp in zip(facets, fine, samples):
        check_finite("the crack opening", f["jump"], g["jump"], smp["jump"])
    fronts = [g.front for g in m.geometries]
    summary = describe_model(m, None, solution)
    crack_stats = [{"crack": i, "name": cm.crack.name, **crack_statistics_3d(facets[i], samples[i]),
                    "front": summary["cracks"][i]["front"]} for i, cm in enumerate(m.cracks)]
    energy = solution.strain_energy()
    timings["crack_post"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    cracks = [cm.crack for cm in m.cracks]
    write_csv(out / "crack_opening.csv", ["crack", "facet", "vertex", "x", "y", "z", "p1", "p2", "weight", "gap",
                                           "slip", "jump_x", "jump_y", "jump_z"], opening_rows(cracks, fine))
    files.append("crack_opening.csv")
    if sifs:
        write_csv(out / "front.csv", FRONT_COLUMNS, csv_rows(sifs))
        files.append("front.csv")
    timings["write_csv"] = time.perf_counter() - t0
    if cfg["vtu"]:
        t0 = time.perf_counter()
        fields = subcell_fields_3d(solution)
        check_finite("the sub-tetrahedral fields", fields["displacement"], fields["stress"])
        timings["subcell_fields"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        write_mesh(solution_mesh(fields), out / "solution.vtu")
        write_mesh(crack_surface_mesh(facets), out / "crack_surface.vtu")
        write_mesh(front_mesh(fronts), out / "crack_front.vtu")
        files += ["solution.vtu", "crack_surface.vtu", "crack_front.vtu"]
        if sifs:
            write_mesh(front_sif_mesh(sifs), out / "front_sifs.vtu")
            files.append("front_sifs.vtu")
        timings["write_vtu"] = time.perf_counter() - t0
        logger.info("wrote ParaView files solution.vtu (%d points, %d cells: %d sub-tetrahedra), crack_surface.vtu, "
                    "crack_front.vtu", len(fields["points"]), len(fields["cells"]), fields["num_sub"])
    if cfg["png"] and cracks:
        t0 = time.perf_counter()
        write_crack_opening_png(cracks, fine, fronts, out / "crack_opening.png", scene_file.title, m.scene.units)
        files.append("crack_opening.png")
        timings["write_png"] = time.perf_counter() - t0
        logger.info("wrote crack_opening.png")
        if sifs:
            write_front_png(sifs, out / "front_sifs.png", scene_file.title,
                            None if m.scene.units is None else m.scene.units.name("K"))
            files.append("front_sifs.png")

    solver = getattr(solution, "solver", None) or {}
    units = m.scene.units
    u_scale = float(np.abs(solution.standard_displacement).max()) if m.num_dofs else 0.0
    results = {
        "title": scene_file.title,
        "scene_file": str(scene_file.path) if scene_file.path is not None else None,
        "dimension": 3,
        "versions": versions(),
        "model": summary,
        "boundary_conditions_and_loads": scene_file.notes,
        "solution": {"dofs": int(m.num_dofs), "strain_energy": energy, "max_displacement": u_scale,
                     "relative_residual": solver.get("relative_residual"),
                     "solver": solver.get("solver"), "solves": solver.get("solves", [])},
        "units": None if units is None else {q: units.name(q) for q in ("length", "force", "stress", "K", "G")},
        "warnings": warnings,
        "sifs": sifs,
        "error_estimate": None,
        "cracks": crack_stats,
        "contact": None,
        "timings": {},
        "files": files + ["results.json"],
    }
    timings["outputs_total"] = time.perf_counter() - t_outputs
    results["timings"] = {**timings, **{f"solve.{k}": v for k, v in solution.timings.items()}}
    try:
        text = json.dumps(results, indent=2, allow_nan=False, default=json_default)
    except ValueError as e:
        raise SolverError(f"results.json would hold NaN or infinity ({e}); nothing written") from None
    with atomic_path(out / "results.json") as tmp:
        tmp.write_text(text + "\n")
    logger.info("wrote %s", ", ".join(results["files"]))
    return results


__all__ = ["write_outputs_3d", "front_rows", "crack_statistics_3d", "opening_rows"]
