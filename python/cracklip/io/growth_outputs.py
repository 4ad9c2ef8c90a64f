"""What a growth run writes: path.csv, results.json, path.png, sif_history.png,
a_N.png (fatigue) and a ParaView time series (growth.pvd, one .vtu per step).

Files are written through cracklip.io.files.atomic_path (complete or absent), like a run's.
"""
from __future__ import annotations

import json
import pathlib
import typing

import numpy as np

from ..analysis.growth import GrowthResult, TipRecord
from .files import atomic_path
from .outputs import ensure_output_dir, json_default, versions, write_csv
from .paraview import subcell_mesh, write_mesh
from ..scene.units import label as unit_label
from .pictures import new_figure, save_png, window_around


PATH_COLUMNS = ["step", "crack", "tip", "x", "y", "length", "K_I", "K_II", "K_I_spread", "K_II_spread", "kink_deg",
                "K_eq", "closed_fraction", "da", "K_I_min", "K_II_min", "delta_K", "dN", "N", "status"]


class SeriesWriter:
    """The ParaView time series: step k's sub-cell mesh as growth_k.vtu, the
    collection growth.pvd listing them (rewritten at every step, so an
    interrupted run leaves a readable series)."""

    def __init__(self, out: pathlib.Path):
        self.out = out
        self.files: list[tuple[int, str]] = []

    def add(self, k: int, solution) -> None:
        name = f"growth_{k:04d}.vtu"
        write_mesh(subcell_mesh(solution), self.out / name)
        self.files.append((k, name))
        lines = ['<?xml version="1.0"?>', '<VTKFile type="Collection" version="0.1">', "  <Collection>"]
        lines += [f'    <DataSet timestep="{s}" group="" part="0" file="{f}"/>' for s, f in self.files]
        lines += ["  </Collection>", "</VTKFile>"]
        with atomic_path(self.out / "growth.pvd") as tmp:
            tmp.write_text("\n".join(lines) + "\n")


def write_growth_outputs(scene_file, result: GrowthResult, out_dir, growth, timings: dict | None = None,
                         series: SeriesWriter | None = None) -> dict[str, typing.Any]:
    """Write path.csv, results.json and the PNGs of a growth run; return the results."""
    out = ensure_output_dir(out_dir)
    files = []
    rows = result.rows
    write_csv(out / "path.csv", PATH_COLUMNS,
               [[r["step"], r["crack"], r["end"], r["x"], r["y"], r["length"], r["K_I"], r["K_II"], r["K_I_spread"],
                 r["K_II_spread"], r["kink_deg"], r["K_eq"], r["closed_fraction"], r["da"], r["K_I_min"],
                 r["K_II_min"], r["delta_K"], r["dN"], r["N"], r["status"]] for r in rows])
    files.append("path.csv")
    cfg = scene_file.outputs
    if cfg["png"]:
        files += write_growth_pngs(scene_file, result, out, growth.fatigue)
    if series is not None:
        files += ["growth.pvd"] + [f for _, f in series.files]
    names = [c.name for c in scene_file.scene.cracks]
    results = {
        "title": scene_file.title,
        "scene_file": str(scene_file.path) if scene_file.path is not None else None,
        "versions": versions(),
        "growth": {k: v for k, v in vars(growth).items()},
        "boundary_conditions_and_loads": scene_file.notes,
        "stop_reason": result.stop_reason,
        "stops": result.stops,
        "warnings": result.warnings,
        "steps": len(result.records) - 1,
        "cycles": result.cycles if growth.fatigue else None,
        "final": {"cracks": [{"name": c.name, "points": np.asarray(c.points).tolist(),
                              "polyline_length": float(np.linalg.norm(np.diff(c.points, axis=0), axis=1).sum()),
                              "length_in_part": next((r.length for r in result.records[-1] if r.crack == i), None)}
                             for i, c in enumerate(result.cracks)],
                  "tips": [r.row() for r in result.records[-1]]},
        "per_step": [{"step": k, "tips": [{key: r.row()[key] for key in ("crack", "end", "x", "y", "length", "K_I",
                                                                          "K_II", "kink_deg", "N", "status")}
                                          for r in step],
                      "warnings": result.step_warnings[k] if k < len(result.step_warnings) else []}
                     for k, step in enumerate(result.records)],
        "crack_names": names,
        "step_seconds": result.step_times,
        "step_solves": result.step_solves,
        "timings": dict(timings or {}),
        "files": files + ["results.json"],
    }
    text = json.dumps(results, indent=2, allow_nan=False, default=json_default)
    with atomic_path(out / "results.json") as tmp:
        tmp.write_text(text + "\n")
    return results


def _tips(result: GrowthResult) -> dict[tuple[int, int], list[TipRecord]]:
    out: dict[tuple[int, int], list[TipRecord]] = {}
    for step in result.records:
        for r in step:
            out.setdefault((r.crack, r.end), []).append(r)
    return out


def write_growth_pngs(scene_file, result: GrowthResult, out: pathlib.Path, fatigue: bool) -> list[str]:
    """path.png (the part, the initial cracks, the paths), sif_history.png (K
    against crack length per tip), a_N.png (crack length against cycles)."""
    from ..model.boundary import boundary_segments
    scene = scene_file.scene
    a, b = boundary_segments(scene.mesh)
    names = []
    # A zoom on the paths when they are small in the part (a 12 mm crack at
    # a hole of a 400 mm plate is a dot on the whole part).
    window = window_around([c.points for c in scene.cracks] + [c.points for c in result.cracks],
                           np.concatenate([a, b]))
    fig = new_figure((13, 6) if window is not None else (7, 6))
    panels = [fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)] if window is not None else [fig.add_subplot()]
    for k, ax in enumerate(panels):
        for p, q in zip(a, b):
            ax.plot([p[0], q[0]], [p[1], q[1]], "k-", lw=0.8)
        for c in scene.cracks:
            ax.plot(c.points[:, 0], c.points[:, 1], "-", color="0.5", lw=2.0)
        for i, c in enumerate(result.cracks):
            ax.plot(c.points[:, 0], c.points[:, 1], ".-", ms=2, lw=1.0, color=f"C{i % 10}", label=c.name)
        ax.set_aspect("equal")
        ax.set_xlabel(unit_label(scene.units, "length", "x"))
        ax.set_ylabel(unit_label(scene.units, "length", "y"))
        if k == 1:
            ax.set_xlim(window[0][0], window[1][0])
            ax.set_ylim(window[0][1], window[1][1])
            ax.set_title("around the cracks", fontsize=9)
        elif window is not None:
            from matplotlib.patches import Rectangle
            ax.add_patch(Rectangle(tuple(window[0]), *(window[1] - window[0]), fill=False, ec="r", lw=0.8, ls="--"))
    title = f"{scene_file.title}\ncrack paths ({len(result.records) - 1} steps; grey: initial)"
    if window is None:
        panels[0].set_title(title, fontsize=10)
    else:
        fig.suptitle(title, fontsize=10)
    panels[-1].legend(fontsize=7)
    save_png(fig, out / "path.png", {"part": panels[0], **({"zoom": panels[1]} if window is not None else {})})
    names.append("path.png")

    tips = _tips(result)
    fig = new_figure((7, 4.5))
    ax = fig.add_subplot()
    for n, ((ci, end), recs) in enumerate(tips.items()):
        L = [r.length for r in recs]
        label = f"{result.cracks[ci].name} end {end}"
        ax.plot(L, [r.K_I for r in recs], "o-", ms=3, color=f"C{n}", label=f"{label}: K_I")
        ax.plot(L, [r.K_II for r in recs], "s--", ms=3, color=f"C{n}", label=f"{label}: K_II")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("crack length")
    ax.set_ylabel("K (maximum load)" if fatigue else "K")
    ax.set_title(f"{scene_file.title}\nstress intensity factors along the growth", fontsize=10)
    ax.legend(fontsize=7)
    save_png(fig, out / "sif_history.png")
    names.append("sif_history.png")

    if fatigue:
        fig = new_figure((7, 4.5))
        ax = fig.add_subplot()
        for n, ((ci, end), recs) in enumerate(tips.items()):
            ax.plot([r.N for r in recs], [r.length for r in recs], "o-", ms=3, color=f"C{n}",
                    label=f"{result.cracks[ci].name} end {end}")
        ax.set_xlabel("cycles N")
        ax.set_ylabel("crack length a")
        ax.set_title(f"{scene_file.title}\nfatigue: crack length against cycles", fontsize=10)
        ax.legend(fontsize=7)
        save_png(fig, out / "a_N.png")
        names.append("a_N.png")
    return names
