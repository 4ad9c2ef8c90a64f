"""What a 3D growth run writes (cracklip grow on a solid part):

- front_path.csv: one row per front point per step: step, cycles, blocks,
  crack, point, x, y, z, K_I, K_II, K_III (at the reference load state,
  the largest), da (its advance from this step), and a (its distance from
  the crack's origin), kink and twist (degrees), K_eq, the largest counted
  cycle's K_max, K_min, Delta K_eff, R, the growth per pass, the residual
  strength, free_surface, the element size there, status;
- shape.csv (per step and crack: cycles, blocks, kind, a, c, a/c, t, a/t,
  the mean radius and roundness of an embedded crack, status: empty, or
  `past failure` / `past max_length` for a front reached only after the
  stop found inside the increment to it, whose cycles are the stop's) with shape.png (a/c
  against a/t for surface and corner cracks; the radius and roundness of an
  embedded one) and a_N.png (a and c against cycles and blocks);
- crack_surface.pvd (crack_surface_<k>.vtu: the triangulated crack surface
  of each step, its triangles flagged inside the part or not) and
  crack_front.pvd (crack_front_<k>.vtu: the front points of each step with
  K_I, K_II, K_III, da, kink), the solution series growth.pvd as in 2D;
- life (a fatigue life): dadN.png, life_K.png, residual_strength.png with
  their CSVs (io.growth_outputs, per front point: the point with the largest
  K at each step);
- --beta-table: beta_front.csv (every point, every step: beta and K_I of
  each load group at factor 1), and for surface and corner cracks the
  tables of the deepest point (depth a) and of the surface point (surface
  length c): beta_deepest.csv and beta_surface.csv (the one-size layout
  `cracklip life` reads: columns a, beta_<group>; in beta_surface.csv the
  size column is c, named a for the reader), beta_ac.csv (a, c, beta_a,
  beta_c per load group along the grown path: a path, not the grid of
  (a, c) that `cracklip life`'s two-size tables need) and beta_tables.txt
  (per role and load group, '#' comment lines then 'a beta' pairs: the
  two-column layout of easigrow's beta files and of the tabular beta inputs
  of AFGROW and NASGRO; neither tool's own file layout is publicly
  documented in a source we could read, so none is claimed);
- results.json: settings, units, stops, warnings, the life, per-step summaries,
  the final surfaces' sizes, seconds and solves per step.
"""
from __future__ import annotations

import math
import pathlib
import typing

import numpy as np

from ..analysis.growth import GrowthResult
from ..analysis.life import PAST_STOP
from ..scene.units import label
from .files import atomic_path
from .growth_outputs import (SeriesWriter, growth_settings, one_cycle_per_block,  # noqa: F401 (SeriesWriter re-exported)
                             reference_stress_line, units_line, write_life_pngs)
from .outputs import ensure_output_dir, units_names, versions, write_csv
from .results import write_results_json
from .paraview import write_mesh
from .pictures import new_figure, save_png
from .vtu import VtuMesh

FRONT_COLUMNS = ["step", "cycles", "blocks", "crack", "point", "x", "y", "z", "K_I", "K_II", "K_III", "da", "a",
                 "kink_deg", "twist_deg", "K_eq", "K_max", "K_min", "delta_K_eff", "R", "da_per_pass",
                 "residual_strength", "free_surface", "element_size", "status"]

SHAPE_COLUMNS = ["step", "cycles", "blocks", "crack", "kind", "a", "c", "a_over_c", "thickness", "a_over_t",
                 "radius_mean", "roundness", "points", "status"]


def shape_rows(result: GrowthResult) -> list[list]:
    """shape.csv's rows (module doc)."""
    rows = []
    for k, (shape, recs) in enumerate(zip(result.fronts["shape"], result.records)):
        N = recs[0].N if recs else None
        blocks = recs[0].blocks if recs else None
        for ci, sh in sorted(shape.items()):
            status = next((r.status for r in recs if r.crack == ci and r.status in PAST_STOP), "")
            rows.append([k, N, blocks, ci, sh["kind"], sh.get("a"), sh.get("c"), sh.get("a_over_c"),
                         sh.get("thickness"), sh.get("a_over_t"), sh["radius_mean"], sh["roundness"], sh["points"],
                         status])
    return rows


def write_front_growth_outputs(scene_file, result: GrowthResult, out_dir, growth, timings: dict | None = None,
                               series: SeriesWriter | None = None) -> dict[str, typing.Any]:
    """Write the files of a 3D growth run (module doc); return results.json's content."""
    out = ensure_output_dir(out_dir)
    files = []
    rows = []
    for step in result.records:
        for r in step:
            rows.append([r.step, r.N, r.blocks, r.crack, r.end, r.x, r.y, r.z, r.K_I, r.K_II, r.K_III, r.da, r.length,
                         r.kink_deg, r.twist_deg, r.K_eq, r.K_max, r.K_min, r.delta_K_eff, r.R, r.da_per_pass,
                         r.residual_strength, int(r.free_surface), r.element_size, r.status])
    write_csv(out / "front_path.csv", FRONT_COLUMNS, rows)
    write_csv(out / "shape.csv", SHAPE_COLUMNS, shape_rows(result))
    files += ["front_path.csv", "shape.csv"]
    cfg = scene_file.outputs
    if cfg["vtu"]:
        files += write_front_series(result, out)
    if series is not None:
        files += ["growth.pvd"] + [f for _, f in series.files]
    if cfg["png"]:
        files += write_shape_pngs(scene_file, result, out)
        if result.life:
            files += write_life_pngs(scene_file, result, out, _strongest(result), growth)
    if result.beta:
        files += write_beta_tables_3d(result.beta, out, scene_file.title, getattr(scene_file.scene, "units", None),
                                      getattr(growth, "reference_stress", None))
    last = result.fronts["shape"][-1] if result.fronts["shape"] else {}
    results = {
        "title": scene_file.title,
        "scene_file": str(scene_file.path) if scene_file.path is not None else None,
        "versions": versions(),
        "dimension": 3,
        "units": units_names(getattr(scene_file.scene, "units", None)),
        "growth": growth_settings(growth),
        "front_growth": {"da": result.fronts["da"], "spacing": result.fronts["spacing"],
                         "margin": result.fronts["margin"], "front_element_size": result.fronts["h_front"],
                         "radius_scale": result.fronts["radius_scale"],
                         "origins": result.fronts["origins"], "breakthrough": result.fronts["breakthrough"]},
        "stop_criterion": result.stop_criterion,
        "stop_reason": result.stop_reason,
        "stops": result.stops,
        "warnings": result.warning_rows,
        "life": result.life,
        "boundary_conditions_and_loads": scene_file.notes,
        "steps": len(result.records) - 1,
        "cycles": result.cycles,
        "final": {"cracks": [{"name": c.name, "area": float(c.area), "triangles": int(len(c.triangles)),
                              "shape": last.get(i)} for i, c in enumerate(result.cracks)]},
        "per_step": [{"step": k, "cycles": recs[0].N if recs else None, "blocks": recs[0].blocks if recs else None,
                      "shape": {str(ci): sh for ci, sh in shape.items()},
                      "K_I_range": [min(r.K_I for r in recs), max(r.K_I for r in recs)] if recs else None,
                      "da_max": max((r.da for r in recs), default=0.0),
                      "warnings": result.step_warnings[k] if k < len(result.step_warnings) else []}
                     for k, (recs, shape) in enumerate(zip(result.records, result.fronts["shape"]))],
        "crack_names": [c.name for c in result.cracks],
        "step_seconds": result.step_times,
        "step_solves": result.step_solves,
        "timings": dict(timings or {}),
        "files": files + ["results.json"],
    }
    write_results_json(out, results)
    return results


def _strongest(result: GrowthResult) -> dict[tuple[int, int], list]:
    """Per crack, the records of its point with the largest K_I at each step
    (the life pictures' one curve per crack), keyed (crack, -1)."""
    out: dict[tuple[int, int], list] = {}
    for step in result.records:
        for ci in sorted({r.crack for r in step}):
            rs = [r for r in step if r.crack == ci]
            out.setdefault((ci, -1), []).append(max(rs, key=lambda r: r.K_I))
    return out


def _pvd(out: pathlib.Path, name: str, files: list[tuple[int, str]]) -> None:
    lines = ['<?xml version="1.0"?>', '<VTKFile type="Collection" version="0.1">', "  <Collection>"]
    lines += [f'    <DataSet timestep="{s}" group="" part="0" file="{f}"/>' for s, f in files]
    lines += ["  </Collection>", "</VTKFile>"]
    with atomic_path(out / name) as tmp:
        tmp.write_text("\n".join(lines) + "\n")


def write_front_series(result: GrowthResult, out: pathlib.Path) -> list[str]:
    """crack_surface.pvd and crack_front.pvd with one .vtu per step (module doc)."""
    surf_files, front_files = [], []
    for k, (surfs, recs) in enumerate(zip(result.fronts["surfaces"], result.records)):
        pts, tris, crack = [], [], []
        off = 0
        for ci, (v, t) in enumerate(surfs):
            pts.append(v)
            tris.append(t + off)
            crack.append(np.full(len(t), ci, dtype=np.int32))
            off += len(v)
        V = np.concatenate(pts) if pts else np.zeros((0, 3))
        T = np.concatenate(tris) if tris else np.zeros((0, 3), np.int64)
        name = f"crack_surface_{k:04d}.vtu"
        write_mesh(VtuMesh(V, "triangle", T, cell_data={"crack": np.concatenate(crack) if crack else
                                                        np.zeros(0, np.int32)}), out / name)
        surf_files.append((k, name))
        X = np.array([[r.x, r.y, r.z] for r in recs]).reshape(-1, 3)
        conn = []
        for ci in sorted({r.crack for r in recs}):
            idx = [i for i, r in enumerate(recs) if r.crack == ci]
            conn += list(zip(idx[:-1], idx[1:]))
            if not any(recs[i].free_surface for i in idx) and len(idx) > 2:
                conn.append((idx[-1], idx[0]))
        data = {key: np.array([float(getattr(r, key) or 0.0) for r in recs])
                for key in ("K_I", "K_II", "K_III", "K_eq", "da", "kink_deg", "twist_deg", "length")}
        data["free_surface"] = np.array([int(r.free_surface) for r in recs], dtype=np.int32)
        name = f"crack_front_{k:04d}.vtu"
        write_mesh(VtuMesh(X, "line", np.array(conn, dtype=np.int64).reshape(-1, 2), point_data=data), out / name)
        front_files.append((k, name))
    _pvd(out, "crack_surface.pvd", surf_files)
    _pvd(out, "crack_front.pvd", front_files)
    return ["crack_surface.pvd", "crack_front.pvd"] + [f for _, f in surf_files + front_files]


def write_shape_pngs(scene_file, result: GrowthResult, out: pathlib.Path) -> list[str]:
    """shape.png (a/c against a/t, or the radius and roundness of an embedded
    crack, against the step) and a_N.png (a and c against cycles and blocks)."""
    units = getattr(scene_file.scene, "units", None)
    rows = shape_rows(result)
    names = [c.name for c in result.cracks]
    cracks = sorted({r[3] for r in rows})
    fig = new_figure((7, 4.5))
    ax = fig.add_subplot()
    embedded = False
    for n, ci in enumerate(cracks):
        rs = [r for r in rows if r[3] == ci]
        if rs[0][4] in ("surface", "corner"):
            ax.plot([r[9] for r in rs], [r[7] for r in rs], "o-", ms=3, color=f"C{n}",
                    label=f"{names[ci]} ({rs[0][4]} crack)")
        else:
            embedded = True
            ax.plot([r[0] for r in rs], [100.0 * r[11] for r in rs], "o-", ms=3, color=f"C{n}",
                    label=f"{names[ci]}: roundness max|r - mean r| / mean r [%]")
    if embedded:
        ax.set_xlabel("step")
        ax.set_ylabel("roundness [%]")
    else:
        ax.set_xlabel("a / t (depth over the part's thickness along the depth)")
        ax.set_ylabel("a / c")
    ax.set_title(f"{scene_file.title}\nshape of the front", fontsize=10)
    ax.legend(fontsize=7)
    save_png(fig, out / "shape.png")
    life = result.life
    block = f"{life['block_name']}s" if life else "blocks"
    # a geometry reached only past the failure (or growth.max_length) found inside the increment to it: no (a, N) point
    past = {k for k, recs in enumerate(result.records) if recs and recs[0].status in PAST_STOP}
    rows = [r for r in rows if r[0] not in past]
    # One cycle per block (a constant-amplitude "flight"): one panel, both names on its axis.
    one = one_cycle_per_block([(r[1], r[2]) for r in rows])
    fig = new_figure((6, 4.5) if one else (10, 4.5))
    axes = [fig.add_subplot()] if one else [fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)]
    for n, ci in enumerate(cracks):
        rs = [r for r in rows if r[3] == ci]
        for ax, col in zip(axes, (1, 2)):
            x = [r[col] for r in rs]
            if rs[0][4] in ("surface", "corner"):
                ax.plot(x, [r[5] for r in rs], "o-", ms=3, color=f"C{n}", label=f"{names[ci]}: depth a")
                ax.plot(x, [r[6] for r in rs], "s--", ms=3, color=f"C{n}", label=f"{names[ci]}: surface length c")
            else:
                ax.plot(x, [r[10] for r in rs], "o-", ms=3, color=f"C{n}", label=f"{names[ci]}: mean radius")
    axes[0].set_xlabel(f"cycles N = {block} (one cycle each)" if one else "cycles N")
    if not one:
        axes[1].set_xlabel(block)
    for ax in axes:
        ax.set_ylabel(label(units, "length", "crack size"))
        ax.legend(fontsize=7)
    if life and life.get("failure"):
        for ax, x in zip(axes, (life["failure"]["cycles"], life["failure"]["blocks"])):
            ax.axvline(x, color="r", lw=0.8, ls="--")
    axes[0].set_title(f"{scene_file.title}\ncrack size against cycles", fontsize=10)
    save_png(fig, out / "a_N.png")
    return ["shape.png", "a_N.png"]


def write_beta_tables_3d(rows: list[dict[str, typing.Any]], out: pathlib.Path, title: str, units=None,
                         reference_stress: dict[str, float] | None = None) -> list[str]:
    """beta_front.csv, and for surface and corner cracks beta_deepest.csv,
    beta_surface.csv, beta_ac.csv, beta_tables.txt (module doc)."""
    cols: list[str] = []
    for r in rows:
        cols += [c for c in r if c not in cols]
    write_csv(out / "beta_front.csv", cols, [[r.get(c) for c in cols] for r in rows])
    files = ["beta_front.csv"]
    groups = [c[5:] for c in cols if c.startswith("beta_")]
    unit = f" [{units.length}]" if units is not None else ""
    deep = [r for r in rows if r.get("role") == "deepest" and r.get("depth_a") is not None]
    surf = [r for r in rows if r.get("role") == "surface" and r.get("surface_c") is not None]
    if not deep and not surf:
        return files

    def one_size(path: pathlib.Path, rs: list[dict], size: str, what: str) -> None:
        # One row per step (a corner crack's surface row: its c end; a surface crack's: the two ends' mean).
        by_step: dict[int, list[dict]] = {}
        for r in rs:
            by_step.setdefault(r["step"], []).append(r)
        lines = [f"# cracklip beta table ({what}): {title}",
                 f"# a{unit}: {'the depth a of the crack' if size == 'depth_a' else 'the surface length c of the crack'}"
                 " (the column is named a for `cracklip life`'s table reader); beta = K_I / (S sqrt(pi a)) of the "
                 "load group at factor 1, S its reference stress (growth.reference_stress, default 1)",
                 reference_stress_line(groups, reference_stress, units), *units_line(units),
                 "a, " + ", ".join(f"beta_{g}" for g in groups)]
        last = -math.inf
        for step in sorted(by_step):
            sel = by_step[step]
            a = float(sel[0][size])
            if not a > last:
                continue
            last = a
            betas = [float(np.mean([s[f"K_I_{g}"] for s in sel])) / (_stress(sel[0], g) * math.sqrt(math.pi * a))
                     for g in groups]
            lines.append(f"{a:.8g}, " + ", ".join(f"{v:.8g}" for v in betas))
        with atomic_path(path) as tmp:
            tmp.write_text("\n".join(lines) + "\n")

    if deep:
        one_size(out / "beta_deepest.csv", deep, "depth_a", "the deepest point")
        files.append("beta_deepest.csv")
    if surf:
        one_size(out / "beta_surface.csv", surf, "surface_c", "the surface point")
        files.append("beta_surface.csv")
    # a, c, beta_a, beta_c along the path, and the two-column tables.
    steps = sorted({r["step"] for r in deep} & {r["step"] for r in surf})
    ac_rows, pairs = [], {}
    for step in steps:
        d = [r for r in deep if r["step"] == step][0]
        ss = [r for r in surf if r["step"] == step]
        a, c = float(d["depth_a"]), float(d["surface_c"])
        row = [step, a, c]
        for g in groups:
            S = _stress(d, g)
            ba = float(d[f"K_I_{g}"]) / (S * math.sqrt(math.pi * a))
            bc = float(np.mean([s[f"K_I_{g}"] for s in ss])) / (S * math.sqrt(math.pi * c))
            row += [ba, bc]
            pairs.setdefault(("deepest", g), []).append((a, ba))
            pairs.setdefault(("surface", g), []).append((c, bc))
        ac_rows.append(row)
    write_csv(out / "beta_ac.csv", ["step", "a", "c"] + [f"{b}_{g}" for g in groups for b in ("beta_a", "beta_c")],
              ac_rows)
    lines = [f"# cracklip beta tables: {title}",
             "# two columns 'a beta' per table (beta = K_I / (S sqrt(pi a)), S: growth.reference_stress); deepest: a = "
             "the depth, surface: a = the surface length c" + (f", in {units.length}" if units is not None else ""),
             "# AFGROW's and NASGRO's own table file layouts are not publicly documented: this is the two-column "
             "layout of easigrow's beta files, to paste into their tabular beta inputs",
             reference_stress_line(groups, reference_stress, units), *units_line(units)]
    for (role, g), pts in sorted(pairs.items()):
        lines.append(f"# table: {role} point; case: {g}")
        lines += [f"{a:.8g} {b:.8g}" for a, b in pts]
    with atomic_path(out / "beta_tables.txt") as tmp:
        tmp.write_text("\n".join(lines) + "\n")
    return files + ["beta_ac.csv", "beta_tables.txt"]


def _stress(row: dict, g: str) -> float:
    """The reference stress of a group from a beta row (K_I / beta / sqrt(pi a))."""
    b, K, a = row.get(f"beta_{g}"), row.get(f"K_I_{g}"), row.get("a")
    if b in (None, 0.0) or not a:
        return 1.0
    return float(K / (b * math.sqrt(math.pi * a)))


__all__ = ["write_front_growth_outputs", "write_front_series", "write_shape_pngs", "write_beta_tables_3d",
           "FRONT_COLUMNS", "SHAPE_COLUMNS"]
