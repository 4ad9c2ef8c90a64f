"""What a run writes, planar or solid: results.json, the crack's tables, the
ParaView files and the PNGs.

One results.json for both dimensions: title, scene file, dimension,
versions, the model summary (describe_model), boundary conditions and
loads, the solution (dofs, strain energy, largest displacement, solver),
units, warnings, ``sifs`` (one row schema for a 2D tip and a 3D front point:
cracklip.fracture.sif.SIF_KEYS), the error estimate of K, reactions,
per crack its statistics, contact, load-path steps, condition number,
timings and the files written. What differs is the crack's geometry:

- a 2D crack (a curve): crack.csv (samples along each crack: pressure,
  shear, gap, slip, state, per load step), sif.csv (K per tip and step),
  crack_lips.vtu, and the PNGs deformed.png, crack_pressure.png, stress.png;
  per crack its length in the part, closed / open extent, pressure;
- a 3D crack (a surface): crack_opening.csv and crack_opening.png (the
  normal opening at the vertices of the lip facets, each split in
  OPENING_SUBDIVISION^2 triangles, the same samples in both), front.csv
  (K along the fronts: FRONT_COLUMNS, per load step as sif.csv),
  front_sifs.png (every step) and front_sifs.vtu (the last step),
  crack_surface.vtu, crack_front.vtu; per crack its area in the part,
  opened volume, opening and slip, and its front.

``output_files`` lists what a run of a model writes (``cracklip check``
prints it). Every file is written under a temporary name in the output
folder and renamed when complete (``cracklip.io.files.atomic_path``), so a
folder never holds a half-written output; a folder that cannot be written
raises ``OutputError`` naming it. ``describe_model`` is the model summary
that ``cracklip check`` prints and results.json records: the counts come
from the same model and contact system objects the solver uses.

Under mpirun (a distributed model, 2D) every process computes the results
together (K, the lip samples, the energy and the counts summed over the
processes) and rank 0 writes them: results.json, crack.csv, sif.csv,
crack_lips.vtu, and from the owned cells' sub-cell fields gathered on rank
0 solution.vtu and the PNGs; results.json's "parallel" entry gives the
number of processes.
"""
from __future__ import annotations

import logging
import math
import pathlib
import time
import typing

import numpy as np

from ..contact.friction import STATE_NAMES
from ..post.solution import Solution
from ..scene.processes import reduced
from .results import (OutputError, check_finite, ensure_output_dir, json_default, versions, write_csv,  # noqa: F401
                      write_results_json)
from .model_summary import describe_model
from .paraview import crack_lips_mesh, crack_surface_mesh, front_mesh, front_sif_mesh, subcell_mesh, write_mesh
from .pictures import plane_coordinates, write_crack_contact_png, write_crack_opening_png, write_front_png, write_pngs


logger = logging.getLogger(__name__)


#: crack_opening.png and .csv sample each lip facet on this many triangles
#: per side (4 per facet): the sqrt(r) opening of the facets touching the
#: front is drawn without dark slivers.
OPENING_SUBDIVISION = 2


#: front.csv's columns (keys of the SIF rows): one line per front point and
#: per position asked for, per load step (step 0 alone without a load path;
#: a load path's last step is the run's results.json sifs, the earlier ones
#: its steps[].sifs; as sif.csv's step) (the parametric angle only for elliptical fronts:
#: parametric_angle in radians as the rows hold it, parametric_angle_deg in
#: degrees as options.sif_angles and sif_angle_step ask for it,
#: the errors empty without an error estimate,
#: limited_by empty when the domain was not clipped, free_surface 1 where
#: the front meets the part's boundary off a symmetry plane: K there is the
#: documented end value, K_source end_extrapolation; K_source and the
#: other flags: cracklip.fracture.front_sampling, docs/sifs.md).
FRONT_COLUMNS = ["step", "crack", "crack_name", "point", "piece", "s", "x", "y", "z", "parametric_angle",
                 "parametric_angle_deg", "K_I", "K_II",
                 "K_III", "K_I_error", "K_II_error", "K_III_error", "K_I_spread", "K_II_spread", "K_III_spread", "G", "mode_mix_deg", "radius", "radius_min",
                 "element_size", "hat", "curvature", "limited_by", "free_surface", "domain_clear", "K_source",
                 "requested", "symmetry"]


#: sif.csv's columns (2D tips, one line per tip and load step).
SIF_COLUMNS = ["step", "crack", "tip", "x", "y", "direction_x", "direction_y", "K_I", "K_II", "K_I_error",
               "K_II_error", "K_I_extrapolated", "K_II_extrapolated", "K_I_spread", "K_II_spread", "mode_mix_deg", "G",
               "radius", "element_size", "limited_by", "domain_clear"]


def units_names(units) -> dict[str, str] | None:
    """results.json's units: the name of each quantity's unit (None without [units])."""
    return None if units is None else {q: units.name(q) for q in ("length", "force", "stress", "K", "G")}


def output_files(model, outputs: dict) -> list[str]:
    """The files a run of the model writes with the [outputs] settings
    (results.json first)."""
    vtu, png = outputs["vtu"], outputs["png"]
    if model.crack_type.END == "front":
        fronts = any(len(cm.geometry.front["x"]) for cm in model.cracks)
        files = ["crack_opening.csv"] + (["front.csv"] if fronts else [])
        files += (["solution.vtu", "crack_surface.vtu", "crack_front.vtu"] + (["front_sifs.vtu"] if fronts else [])
                  if vtu else [])
        contact = model.scene.options.contact != "none" and bool(model.cracks)
        files += (["crack_opening.png"] + (["crack_contact.png"] if contact else [])
                  + (["front_sifs.png"] if fronts else []) if png and model.cracks else [])
    else:
        files = ["crack.csv", "sif.csv"] + (["solution.vtu", "crack_lips.vtu"] if vtu else []) \
            + (["deformed.png", "crack_pressure.png", "stress.png"] if png else [])
    return ["results.json"] + files


def writes_files(model) -> bool:
    """Whether this process writes the output files: rank 0 under mpirun, always in serial."""
    return not model.distributed or model.V.mesh.comm.rank == 0


def largest_displacement(solution: Solution) -> float:
    """The largest standard dof (over every process under mpirun)."""
    m = solution.model
    u = solution.standard_displacement
    if not m.distributed:
        return float(np.abs(u).max()) if m.num_dofs else 0.0
    return float(reduced(float(np.abs(u).max(initial=0.0)), "MAX", m.V.mesh.comm))


# -- 2D: the lips along each crack ------------------------------------------------------------------

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
        return np.ones(len(samples["gap"]), dtype=bool)
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


def _curve_outputs(scene_file, solution: Solution, out: pathlib.Path, sifs: list[dict], summary: dict,
                   timings: dict, files: list[str]) -> dict[str, typing.Any]:
    """The files of 2D cracks (module doc) and their part of results.json."""
    cfg = scene_file.outputs
    m = solution.model
    states = solution.steps or [solution]
    t0 = time.perf_counter()
    u_scale = largest_displacement(solution)
    gap_tol = 1e-6 * max(u_scale, 1e-300)
    law = m.scene.options.contact if solution.contact else "none"
    write = writes_files(m)
    per_step = []
    for st in states:
        smps = [crack_samples(st, i, cfg["crack_points"]) for i in range(len(m.cracks))]
        shut = [closed_points(smp, law, gap_tol) for smp in smps]
        per_step.append((st, smps, shut))
        for smp in smps:
            check_finite("the crack samples", smp["pressure"], smp["gap"], smp["slip"], smp["shear"])
    _, samples, closed = per_step[-1]
    crack_stats = [{"crack": i, "name": m.cracks[i].crack.name, **crack_statistics(smp, closed[i], gap_tol, law)}
                   for i, smp in enumerate(samples)]
    timings["crack_post"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    step_sifs = [(k, st.stress_intensity_factors(None) if st is not solution else sifs)
                 for k, (st, _, _) in enumerate(per_step)]
    if write:
        _write_curve_csv(out, per_step, step_sifs)
    files += ["crack.csv", "sif.csv"]
    timings["write_csv"] = time.perf_counter() - t0
    if not m.distributed:
        _write_fields(scene_file, solution, out, samples, timings, files)
    elif cfg["vtu"] or cfg["png"]:  # the sub-cell fields gathered on rank 0, which writes and draws them
        t0 = time.perf_counter()
        fields = gathered_subcell_fields(solution)
        timings["subcell_fields"] = time.perf_counter() - t0
        written: list[str] = []
        if write:
            _write_fields(scene_file, solution, out, samples, timings, written, fields)
        files += m.V.mesh.comm.bcast(written, root=0)
    return {"cracks": crack_stats, "steps": _curve_steps(solution, per_step, step_sifs, gap_tol, law)}


def gathered_subcell_fields(solution: Solution) -> dict | None:
    """Under mpirun: the sub-cell fields (Solution.subcell_fields) of every
    process's owned cells on rank 0 (None on the others), the sub-cells in
    rank order, each with its own vertices; parent is the cell's input index
    (the mesh generator's)."""
    m = solution.model
    comm = m.V.mesh.comm
    f = solution.subcell_fields()
    own = f["parent"] < m.num_owned_cells
    original = np.asarray(m.scene.mesh.mesh.topology.original_cell_index, dtype=np.int64)
    conn = f["cells"][own]  # (each sub-cell with its own vertices: a 3D plain cell's are the mesh's nodes)
    mine = {"points": f["points"][conn], "parent": original[f["parent"][own]], "displacement": f["displacement"][conn],
            **{k: f[k][own] for k in ("stress", "side", "von_mises", "crack") if k in f}}
    parts = comm.gather(mine, root=0)
    if parts is None:
        return None
    out = {k: np.concatenate([p[k] for p in parts]) for k in mine}
    n, nv = len(out["parent"]), conn.shape[1]
    out["points"], out["displacement"] = out["points"].reshape(nv * n, -1), out["displacement"].reshape(nv * n, -1)
    out["cells"] = np.arange(nv * n, dtype=np.int64).reshape(-1, nv)
    return out


def _write_curve_csv(out: pathlib.Path, per_step: list, step_sifs: list) -> None:
    """crack.csv and sif.csv of 2D cracks (module doc)."""
    write_csv(out / "crack.csv", ["step", "crack", "s", "x", "y", "pressure", "shear", "gap", "slip", "state",
                                   "closed"],
              [[k, i, smp["s"][j], smp["x"][j, 0], smp["x"][j, 1], smp["pressure"][j], smp["shear"][j],
                smp["gap"][j], smp["slip"][j], smp["state"][j], int(shut[i][j])]
               for k, (_, smps, shut) in enumerate(per_step) for i, smp in enumerate(smps)
               for j in range(len(smp["s"]))])
    write_csv(out / "sif.csv", SIF_COLUMNS,
              [[k, r["crack"], r["tip"], r["x"], r["y"], r["direction"][0], r["direction"][1], r["K_I"],
                r["K_II"], r["K_I_error"], r["K_II_error"], r["K_I_extrapolated"], r["K_II_extrapolated"],
                r["K_I_spread"], r["K_II_spread"], r["mode_mix_deg"], r["G"], r["radius"],
                r["element_size"], r["limited_by"], int(r["domain_clear"])] for k, rows in step_sifs for r in rows])


def _write_fields(scene_file, solution: Solution, out: pathlib.Path, samples: list[dict], timings: dict,
                  files: list[str], fields: dict | None = None) -> None:
    """solution.vtu, crack_lips.vtu and the PNGs of 2D cracks (module doc);
    fields: the sub-cell fields if the caller has them (under mpirun rank 0
    the gathered ones; it alone calls this, which then makes no collective
    call)."""
    cfg = scene_file.outputs
    # The sub-cell fields, shared by the ParaView file and the PNGs.
    if fields is None:
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


#: The keys of results.json's steps[].sifs rows of a 2D load path: which tip
#: (crack, tip) and where (x, y), as sif.csv's rows of that step have them.
STEP_SIF_KEYS_2D = ("crack", "tip", "x", "y", "K_I", "K_II", "K_I_spread", "K_II_spread", "G", "mode_mix_deg")


def _curve_steps(solution: Solution, per_step: list, step_sifs: list, gap_tol: float, law: str) -> list | None:
    """results.json's load-path steps of 2D cracks (None without a load path)."""
    steps = None
    if solution.steps:
        steps = [{"step": k, "name": st.step["name"], "factors": st.step["factors"],
                  "increments": st.step["increments"], "contact": contact_summary(st),
                  "sifs": [{key: r.get(key) for key in STEP_SIF_KEYS_2D} for r in rows],
                  "cracks": [{"crack": i, **{key: v for key, v in crack_statistics(smp, shut[i], gap_tol, law).items()
                                              if key in ("closed_fraction", "stick_length", "slip_length",
                                                         "open_length", "slip_max_abs")}}
                             for i, smp in enumerate(smps)]}
                 for k, ((st, smps, shut), (_, rows)) in enumerate(zip(per_step, step_sifs))]
    return steps


# -- 3D: the lip surfaces and the fronts ------------------------------------------------------------

def crack_statistics_3d(facets: dict | None, samples: dict, closed: np.ndarray | None = None,
                        contact: str = "none") -> dict[str, typing.Any]:
    """Per crack: area in the part, opened volume int [[u]].n dA and the
    area-weighted mean opening (on the lip quadrature samples), the largest
    opening, slip and interpenetration (on the facet vertices and samples);
    closed (n,): which samples are closed (closed_points): the closed and
    open areas; with contact the pressure (largest, smallest, mean over the
    crack, normal force), the largest shear and the stick, slip and open
    areas. facets None: from the samples alone (area their weights' sum)."""
    w, gap = samples["weight"], samples["gap"]
    area = float(np.sum(facets["area"])) if facets is not None else float(w.sum())
    volume = float(np.sum(w * gap))
    gv = facets["gap"].reshape(-1) if facets is not None else gap
    slip = np.linalg.norm(samples["slip"], axis=1)
    if facets is not None:
        slip = np.concatenate([facets["slip"].reshape(-1), slip])
    out = {"area_in_part": area, "facets": int(len(facets["area"])) if facets is not None else None,
           "points": int(len(w)),
           "opening_volume": volume, "gap_mean": volume / area if area > 0 else 0.0,
           "gap_max": float(max(gv.max(initial=0.0), gap.max(initial=0.0))),
           "interpenetration_max": float(max(0.0, -min(gv.min(initial=0.0), gap.min(initial=0.0)))),
           "slip_max": float(slip.max(initial=0.0))}
    if closed is not None:
        total = float(w.sum())
        out.update({"closed_area": float(w[closed].sum()), "open_area": float(w[~closed].sum()),
                    "closed_fraction": float(w[closed].sum() / total) if total > 0 else 0.0})
    if contact != "none" and len(w):
        p = samples["pressure"]
        pv = facets["pressure"].reshape(-1) if facets is not None and "pressure" in facets else p
        out["pressure"] = {"max": float(max(p.max(), pv.max(initial=p.max()))),
                           "min": float(min(p.min(), pv.min(initial=p.min()))),
                           "mean": float((w * p).sum() / w.sum()) if w.sum() > 0 else 0.0,
                           "normal_force": float((w * p).sum())}
        state = samples["state"]
        for name in ("open", "stick", "slip"):
            out[f"{name}_area"] = float(w[state == name].sum())
        out["shear_max"] = float(np.linalg.norm(samples["shear"], axis=1).max(initial=0.0))
    return out


def facet_contact(solution: Solution, crack: int, facets: dict) -> dict:
    """The facets (SurfaceCrackModel.lip_facets) with the contact at their
    vertices added: pressure (F, 3), shear (F, 3, 3) (the friction traction
    on the + lip), state (F, 3) "open" / "stick" / "slip"
    (Solution.lip_contact), and at the facets' centres centre_state (F,)
    and centre_shear (F, 3)."""
    nf = len(facets["cell"])
    c = solution.lip_contact(crack, np.repeat(facets["cell"], 3), facets["ref"].reshape(-1, 3),
                             np.repeat(facets["normal"], 3, axis=0))
    centre = solution.lip_contact(crack, facets["cell"], facets["ref"].mean(axis=1), facets["normal"])
    return {**facets, "pressure": c["pressure"].reshape(nf, 3), "shear": c["shear"].reshape(nf, 3, 3),
            "state": c["state"].reshape(nf, 3), "centre_state": centre["state"], "centre_shear": centre["shear"]}


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


def front_csv_rows(rows: typing.Sequence[dict], step: int = 0) -> list[list]:
    """front.csv's rows of one load step (FRONT_COLUMNS; flags as 0 / 1)."""
    def value(r: dict, k: str):
        if k == "step":
            return step
        if k == "parametric_angle_deg":
            return None if r.get("parametric_angle") is None else math.degrees(r["parametric_angle"])
        return r.get(k)
    return [[int(v) if isinstance(v, bool) else v for v in (value(r, k) for k in FRONT_COLUMNS)] for r in rows]


def _surface_outputs(scene_file, solution: Solution, out: pathlib.Path, sifs: list[dict], summary: dict,
                     timings: dict, files: list[str]) -> dict[str, typing.Any]:
    """The files of 3D cracks (module doc) and their part of results.json."""
    cfg = scene_file.outputs
    m = solution.model
    t0 = time.perf_counter()
    law = m.scene.options.contact if solution.contact else "none"
    facets = [cm.lip_facets(solution, i, fields=(lambda f, i=i: facet_contact(solution, i, f))
                            if solution.contact else None) for i, cm in enumerate(m.cracks)]
    fine = [cm.lip_facets(solution, i, OPENING_SUBDIVISION) for i, cm in enumerate(m.cracks)]
    samples = [solution.lip_samples(i, cfg["crack_points"]) for i in range(len(m.cracks))]
    for f, g, smp in zip(facets, fine, samples):
        check_finite("the crack opening", f["jump"], g["jump"], smp["jump"], smp["pressure"], smp["shear"])
    fronts = [g.front for g in m.geometries]
    u_scale = largest_displacement(solution)
    gap_tol = 1e-6 * max(u_scale, 1e-300)
    crack_stats = [{"crack": i, "name": cm.crack.name,
                    **crack_statistics_3d(facets[i], samples[i], closed_points(samples[i], law, gap_tol), law),
                    "gap_tolerance": gap_tol, "front": summary["cracks"][i]["front"]}
                   for i, cm in enumerate(m.cracks)]
    timings["crack_post"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    step_sifs = surface_step_sifs(solution, sifs)
    timings["step_sifs"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    cracks = [cm.crack for cm in m.cracks]
    gathered = gathered_subcell_fields(solution) if m.distributed and cfg["vtu"] else None
    if not writes_files(m):  # under mpirun rank 0 writes the files (every process computed their content)
        files += m.V.mesh.comm.bcast(None, root=0)
        return {"cracks": crack_stats,
                "steps": _surface_steps(solution, samples, facets, step_sifs, cfg, law, gap_tol)}
    written = len(files)
    write_csv(out / "crack_opening.csv", ["crack", "facet", "vertex", "x", "y", "z", "p1", "p2", "weight", "gap",
                                           "slip", "jump_x", "jump_y", "jump_z"], opening_rows(cracks, fine))
    files.append("crack_opening.csv")
    if sifs:
        write_csv(out / "front.csv", FRONT_COLUMNS, [row for k, rows in enumerate(step_sifs)
                                                     for row in front_csv_rows(rows, k)])
        files.append("front.csv")
    timings["write_csv"] = time.perf_counter() - t0
    if cfg["vtu"]:
        t0 = time.perf_counter()
        # (under mpirun the owned cells' sub-tetrahedral fields gathered on rank 0)
        fields = gathered if m.distributed else solution.subcell_fields()
        check_finite("the sub-tetrahedral fields", fields["displacement"], fields["stress"])
        timings["subcell_fields"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        write_mesh(subcell_mesh(solution, fields), out / "solution.vtu")
        write_mesh(crack_surface_mesh(facets), out / "crack_surface.vtu")
        write_mesh(front_mesh(fronts), out / "crack_front.vtu")
        files += ["solution.vtu", "crack_surface.vtu", "crack_front.vtu"]
        logger.info("wrote ParaView files solution.vtu (%d points, %d cells: %d sub-tetrahedra), "
                    "crack_surface.vtu, crack_front.vtu", len(fields["points"]), len(fields["cells"]),
                    fields.get("num_sub", np.count_nonzero(fields["side"])))
        if sifs:
            write_mesh(front_sif_mesh(sifs, lambda c, p: bool(m.cracks[c].geometry.front["closed"][p])),
                       out / "front_sifs.vtu")
            files.append("front_sifs.vtu")
        timings["write_vtu"] = time.perf_counter() - t0
    if cfg["png"] and cracks:
        t0 = time.perf_counter()
        write_crack_opening_png(cracks, fine, fronts, out / "crack_opening.png", scene_file.title, m.scene.units)
        files.append("crack_opening.png")
        if solution.contact:
            write_crack_contact_png(cracks, facets, fronts, out / "crack_contact.png", scene_file.title,
                                    m.scene.units, m.scene.options.friction)
            files.append("crack_contact.png")
        if sifs:
            write_front_png(sifs, out / "front_sifs.png", scene_file.title,
                            None if m.scene.units is None else m.scene.units.name("K"), m.scene.units,
                            [(st.step["name"], rows) for st, rows in zip(solution.steps, step_sifs)]
                            if solution.steps else None)
            files.append("front_sifs.png")
        timings["write_png"] = time.perf_counter() - t0
        logger.info("wrote crack_opening.png" + (", crack_contact.png" if solution.contact else "")
                    + (", front_sifs.png" if sifs else ""))
    if m.distributed:  # the others' list of files
        m.V.mesh.comm.bcast(files[written:], root=0)
    return {"cracks": crack_stats, "steps": _surface_steps(solution, samples, facets, step_sifs, cfg, law, gap_tol)}


#: The keys of results.json's steps[].sifs rows of a 3D load path: which
#: point (crack, point) and where (piece, s, x, y, z, the parametric angle
#: of an elliptical front), as front.csv's rows of that step have them.
STEP_SIF_KEYS_3D = ("crack", "point", "piece", "s", "x", "y", "z", "parametric_angle", "K_I", "K_II", "K_III",
                    "K_I_spread", "K_II_spread", "K_III_spread", "G", "mode_mix_deg", "K_source", "domain_clear")


def surface_step_sifs(solution: Solution, sifs: list[dict]) -> list[list[dict]]:
    """The SIF rows of every load step of a 3D solution, first to last (the
    last step's: sifs, the run's rows); without a load path [sifs]."""
    if not solution.steps:
        return [sifs]
    return [sifs if st is solution else st.stress_intensity_factors(None) for st in solution.steps]


def _surface_steps(solution: Solution, samples: list, facets: list, step_sifs: list, cfg: dict, law: str,
                   gap_tol: float) -> list | None:
    """results.json's steps of a 3D load path (None without one); step_sifs:
    surface_step_sifs."""
    m = solution.model
    steps = None
    if solution.steps:
        steps = []
        for k, (st, rows) in enumerate(zip(solution.steps, step_sifs)):
            smps = samples if st is solution else [st.lip_samples(i, cfg["crack_points"]) for i in range(len(m.cracks))]
            stats = [crack_statistics_3d(facets[i] if st is solution else None, smp, closed_points(smp, law, gap_tol),
                                         law) for i, smp in enumerate(smps)]
            steps.append({"step": k, "name": st.step["name"], "factors": st.step["factors"],
                          "increments": st.step["increments"], "contact": contact_summary(st),
                          "sifs": [{key: r.get(key) for key in STEP_SIF_KEYS_3D} for r in rows],
                          "cracks": [{"crack": i, **{key: v for key, v in st_.items()
                                                     if key in ("closed_fraction", "closed_area", "stick_area",
                                                                "slip_area", "open_area", "slip_max",
                                                                "interpenetration_max", "pressure")}}
                                     for i, st_ in enumerate(stats)]})
    return steps


#: The crack files of each kind of crack end (CrackModel.END): a curve's
#: tips, a surface's fronts.
CRACK_OUTPUTS = {"tip": _curve_outputs, "front": _surface_outputs}


def write_outputs(scene_file, solution: Solution, out_dir: str | pathlib.Path,
                  timings: dict[str, float] | None = None) -> dict[str, typing.Any]:
    """Write every output of a solved scene file into out_dir and return the
    results (what results.json holds). timings: phases measured by the
    caller (a "sif" phase there is the K already computed)."""
    t_outputs = time.perf_counter()
    out = ensure_output_dir(out_dir)
    timings = dict(timings or {})
    m = solution.model
    files: list[str] = []
    check_finite("the displacement", solution.u)

    t0 = time.perf_counter()
    sifs = solution.stress_intensity_factors(None)
    warnings = [w.as_dict() for w in solution.warnings]
    timings.setdefault("sif", time.perf_counter() - t0)
    summary = describe_model(m, solution.contact.get("system") if solution.contact else None, solution)
    part = CRACK_OUTPUTS[m.crack_type.END](scene_file, solution, out, sifs, summary, timings, files)
    t0 = time.perf_counter()
    energy = solution.strain_energy()
    timings["strain_energy"] = time.perf_counter() - t0

    contact = contact_summary(solution)
    solver = getattr(solution, "solver", None) or {}
    t0 = time.perf_counter()
    reactions = solution.reactions() if m.scene.dirichlet else None
    timings["reactions"] = time.perf_counter() - t0
    units = m.scene.units
    u_scale = largest_displacement(solution)
    estimate = None
    if solution.error_estimate:
        estimate = {k: v for k, v in solution.error_estimate.items() if k != "tips"}
    results = {
        "title": scene_file.title,
        "scene_file": str(scene_file.path) if scene_file.path is not None else None,
        "dimension": m.gdim,
        "versions": versions(),
        "model": summary,
        "boundary_conditions_and_loads": scene_file.notes,
        "solution": {"dofs": int(summary["dofs"]["total"]), "strain_energy": energy, "max_displacement": u_scale,
                     "relative_residual": solver.get("relative_residual"),
                     "solver": solver.get("solver"), "solves": solver.get("solves", [])},
        "units": units_names(units),
        "warnings": warnings,
        "sifs": sifs,
        "error_estimate": estimate,
        "reactions": reactions,
        "cracks": part["cracks"],
        "contact": contact,
        "steps": part["steps"],
        "condition_number": dict(solution.condition) if solution.condition else None,
        "timings": {},
        "files": files + ["results.json"],
    }
    # Everything written so far and results.json's content (not its dump).
    timings["outputs_total"] = time.perf_counter() - t_outputs
    timings = {**timings, **{f"solve.{k}": v for k, v in solution.timings.items()}}
    results["timings"] = timings
    if m.distributed:  # how many processes solved it
        results["parallel"] = {"processes": m.V.mesh.comm.size}
    if writes_files(m):
        write_results_json(out, results)
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
        out["friction"] = m.scene.options.friction
        out["states"] = {name: int(np.count_nonzero(c["state"] == code)) for code, name in STATE_NAMES.items()}
        out["method"] = c.get("method")
        out["state_history"] = c["history"]
    else:
        out["active_history"] = [int(v) for v in c["history"]]
    if "increment_iterations" in c:
        out["increment_iterations"] = c["increment_iterations"]
    return out
