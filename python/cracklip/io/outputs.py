"""What a run writes: results.json, crack.csv, sif.csv, ParaView files and PNGs.

Every file is written under a temporary name in the output folder and
renamed when complete (``cracklip.io.files.atomic_path``), so a folder never holds a
half-written output; a folder that cannot be written raises ``OutputError``
naming it. ``describe_model`` is the model summary that ``cracklip check``
prints and results.json records: the counts come from the same model and
contact system objects the solver uses.
"""
from __future__ import annotations

import json
import logging
import pathlib
import time
import typing

import numpy as np

from ..contact.friction import STATE_NAMES
from ..errors import SolverError
from ..post.solution import Solution
from .files import atomic_path
from .results import OutputError, check_finite, ensure_output_dir, json_default, versions, write_csv  # noqa: F401
from .model_summary import describe_model
from .paraview import crack_lips_mesh, subcell_mesh, write_mesh
from .pictures import write_pngs


logger = logging.getLogger(__name__)


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


def sif_rows(solution: Solution) -> list[dict[str, typing.Any]]:
    """K_I, K_II with their domain spread, mode mix (degrees, atan2(K_II,
    K_I); None where K is negligible) and energy release rate G = (K_I^2 +
    K_II^2) / E* at every tip of every crack (Solution.stress_intensity_factors)."""
    return solution.stress_intensity_factors(None)


def write_outputs(scene_file, solution: Solution, out_dir: str | pathlib.Path,
                  timings: dict[str, float] | None = None) -> dict[str, typing.Any]:
    """Write every output of a solved scene file into out_dir and return the
    results (what results.json holds); a tetrahedral part's: outputs_3d."""
    if solution.model.gdim == 3:
        from .outputs_3d import write_outputs_3d
        return write_outputs_3d(scene_file, solution, out_dir, timings)
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
            check_finite("the crack samples", smp["pressure"], smp["gap"], smp["slip"], smp["shear"])
    _, samples, closed = per_step[-1]
    crack_stats = [{"crack": i, "name": m.cracks[i].crack.name, **crack_statistics(smp, closed[i], gap_tol, law)}
                   for i, smp in enumerate(samples)]
    energy = solution.strain_energy()
    timings["crack_post"] = time.perf_counter() - t0
    check_finite("the displacement", solution.u)

    t0 = time.perf_counter()
    write_csv(out / "crack.csv", ["step", "crack", "s", "x", "y", "pressure", "shear", "gap", "slip", "state",
                                   "closed"],
               [[k, i, smp["s"][j], smp["x"][j, 0], smp["x"][j, 1], smp["pressure"][j], smp["shear"][j],
                 smp["gap"][j], smp["slip"][j], smp["state"][j], int(shut[i][j])]
                for k, (_, smps, shut) in enumerate(per_step) for i, smp in enumerate(smps)
                for j in range(len(smp["s"]))])
    step_sifs = [(k, st.stress_intensity_factors(None) if st is not solution else sifs)
                 for k, (st, _, _) in enumerate(per_step)]
    write_csv(out / "sif.csv", ["step", "crack", "tip", "x", "y", "direction_x", "direction_y", "K_I", "K_II",
                                 "K_I_error", "K_II_error", "K_I_extrapolated", "K_II_extrapolated",
                                 "K_I_spread", "K_II_spread", "mode_mix_deg", "G", "radius", "element_size",
                                 "limited_by", "domain_clear"],
               [[k, r["crack"], r["tip"], r["x"], r["y"], r["direction"][0], r["direction"][1], r["K_I"],
                 r["K_II"], r["K_I_error"], r["K_II_error"], r["K_I_extrapolated"], r["K_II_extrapolated"],
                 r["K_I_spread"], r["K_II_spread"], r["mode_mix_deg"], r["G"], r["radius"],
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
    t0 = time.perf_counter()
    reactions = solution.reactions() if m.scene.dirichlet else None
    timings["reactions"] = time.perf_counter() - t0
    units = m.scene.units
    estimate = None
    if solution.error_estimate:
        estimate = {k: v for k, v in solution.error_estimate.items() if k != "tips"}
    results = {
        "title": scene_file.title,
        "scene_file": str(scene_file.path) if scene_file.path is not None else None,
        "versions": versions(),
        "model": describe_model(m, solution.contact.get("system") if solution.contact else None, solution),
        "boundary_conditions_and_loads": scene_file.notes,
        "solution": {"dofs": int(m.num_dofs), "strain_energy": energy, "max_displacement": u_scale,
                     "relative_residual": solver.get("relative_residual"),
                     "solver": solver.get("solver"), "solves": solver.get("solves", [])},
        "units": None if units is None else {q: units.name(q) for q in ("length", "force", "stress", "K", "G")},
        "warnings": warnings,
        "sifs": sifs,
        "error_estimate": estimate,
        "reactions": reactions,
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
        text = json.dumps(results, indent=2, allow_nan=False, default=json_default)
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
        out["friction"] = m.scene.options.friction
        out["states"] = {name: int(np.count_nonzero(c["state"] == code)) for code, name in STATE_NAMES.items()}
        out["method"] = c.get("method")
        out["state_history"] = c["history"]
    else:
        out["active_history"] = [int(v) for v in c["history"]]
    if "increment_iterations" in c:
        out["increment_iterations"] = c["increment_iterations"]
    return out
