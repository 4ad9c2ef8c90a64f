"""What a growth run writes: path.csv, results.json, path.png, sif_history.png,
a_N.png (fatigue) and a ParaView time series (growth.pvd, one .vtu per step);
a fatigue life adds dadN.png, life_K.png and residual_strength.png, and
--beta-table beta.csv and beta_afgrow.txt. Every PNG but path.png has a CSV
of its data beside it (same name).

Files are written through cracklip.io.files.atomic_path (complete or absent), like a run's.
"""
from __future__ import annotations

import pathlib
import typing

import numpy as np

from ..analysis.growth import GrowthResult, TipRecord
from ..analysis.life import PAST_STOP
from .files import atomic_path
from .outputs import ensure_output_dir, gathered_subcell_fields, units_names, versions, write_csv, writes_files
from .results import write_results_json
from .paraview import subcell_mesh, write_mesh
from ..scene.units import label
from .pictures import new_figure, save_png, window_around


PATH_COLUMNS = ["step", "crack", "tip", "x", "y", "length", "K_I", "K_II", "K_I_spread", "K_II_spread", "kink_deg",
                "K_eq", "closed_fraction", "da", "K_I_min", "K_II_min", "delta_K", "dN", "N", "status"]

#: The columns a fatigue life adds to path.csv (cracklip.analysis.tips.TipRecord).
LIFE_COLUMNS = ["a", "K_max", "K_min", "delta_K_eff", "R", "da_per_pass", "passes", "blocks", "residual_strength"]


class SeriesWriter:
    """The ParaView time series: step k's sub-cell mesh as growth_k.vtu, the
    collection growth.pvd listing them (rewritten at every step, so an
    interrupted run leaves a readable series). Under mpirun add is
    collective: the owned cells' sub-cells gathered on rank 0, which writes."""

    def __init__(self, out: pathlib.Path):
        self.out = out
        self.files: list[tuple[int, str]] = []

    def add(self, k: int, solution) -> None:
        name = f"growth_{k:04d}.vtu"
        self.files.append((k, name))
        if solution.model.distributed:
            fields = gathered_subcell_fields(solution)
            if not writes_files(solution.model):
                return
            write_mesh(subcell_mesh(solution, fields), self.out / name)
        else:
            write_mesh(subcell_mesh(solution), self.out / name)
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
    life = result.life is not None
    write_csv(out / "path.csv", PATH_COLUMNS + (LIFE_COLUMNS if life else []),
              [[r["step"], r["crack"], r["end"], r["x"], r["y"], r["length"], r["K_I"], r["K_II"], r["K_I_spread"],
                r["K_II_spread"], r["kink_deg"], r["K_eq"], r["closed_fraction"], r["da"], r["K_I_min"],
                r["K_II_min"], r["delta_K"], r["dN"], r["N"], r["status"]]
               + ([r[c] for c in LIFE_COLUMNS] if life else []) for r in rows])
    files.append("path.csv")
    if result.beta:
        files += write_beta_table(result.beta, out, scene_file.title, getattr(scene_file.scene, "units", None),
                                  getattr(growth, "reference_stress", None))
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
        "growth": growth_settings(growth),
        "units": units_names(getattr(scene_file.scene, "units", None)),
        "stop_criterion": result.stop_criterion,
        "life": result.life,
        "boundary_conditions_and_loads": scene_file.notes,
        "stop_reason": result.stop_reason,
        "stops": result.stops,
        "warnings": result.warning_rows,
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
    write_results_json(out, results)
    return results


def growth_settings(growth) -> dict[str, typing.Any]:
    """The growth settings for results.json: the spectrum as its shape (the
    turning points are the user's file), the fatigue material with its source."""
    out = {k: v for k, v in vars(growth).items() if k not in ("fatigue_material", "spectrum")
           and not (k == "da_fraction" and not v)}  # (3D only)
    fm = growth.fatigue_material
    if fm is not None:
        out["fatigue_material"] = {**{k: v for k, v in vars(fm).items()}, "description": fm.describe()}
    sp = growth.spectrum
    if sp is not None:
        pts, _ = sp.pass_points()
        out["spectrum"] = {"groups": list(sp.groups), "counting": sp.counting, "residue": sp.residue,
                           "steady": sp.steady, "block_name": sp.block_name, "contact_levels": sp.contact_levels,
                           "max_passes": sp.max_passes, "blocks_per_pass": sp.blocks_per_pass,
                           "turning_points_per_pass": int(len(pts)),
                           "blocks": [{"name": b.name, "repeat": b.repeat, "points": int(len(b.points))}
                                      for b in sp.blocks]}
    return out


def reference_stress_line(groups: typing.Iterable[str], reference_stress: dict[str, float] | None, units=None) -> str:
    """The comment line of a beta table that gives S of each load group
    (beta = K / (S sqrt(pi a))): `cracklip life` reads it and refuses a
    life.reference_stress that differs (scene.input_files)."""
    ref = dict(reference_stress or {})
    pairs = ", ".join(f"{g} = {float(ref.get(g, 1.0))!r}" for g in groups)
    unit = f" in {units.name('stress')}" if units is not None else ""
    return (f"# reference_stress: {pairs} (S of beta{unit}, growth.reference_stress: give `cracklip life` the same "
            "life.reference_stress)")


def units_line(units) -> list[str]:
    """The comment line of a beta table that gives its units (a and S; K
    in stress sqrt(length)): `cracklip life` refuses a scene in other units."""
    if units is None:
        return []
    return [f"# units: length = {units.length}, stress = {units.name('stress')} (a, and S of beta; `cracklip life` "
            "reads the table in its scene's [units], which must be these)"]


def write_beta_table(rows: list[dict[str, typing.Any]], out: pathlib.Path, title: str, units=None,
                     reference_stress: dict[str, float] | None = None) -> list[str]:
    """beta.csv (every column of the rows: step, crack, end, x, y, a, beta and
    K of each load group at factor 1, K_residual, beta at each contact level)
    and beta_afgrow.txt (per tip and load case, '#' comment lines then 'a
    beta' pairs: the two-column table of easigrow's beta file and of a
    tabular beta; AFGROW's own file format could not be checked in a source,
    see docs/life.md)."""
    cols: list[str] = []
    for r in rows:
        cols += [c for c in r if c not in cols]
    write_csv(out / "beta.csv", cols, [[r.get(c) for c in cols] for r in rows])
    lines = [f"# cracklip beta table: {title}",
             "# beta = K_I / (S sqrt(pi a)) along the grown path, a = crack length of the tip (length in the part over",
             "# its number of tips)" + (f", in {units.length}" if units is not None else "") + "; one table per tip and "
             "load case, each: '# tip ...' then lines 'a beta'"]
    cases = [c for c in cols if c.startswith("beta_")]
    lines.append(reference_stress_line([c[5:] for c in cases if "_at_" not in c], reference_stress, units))
    lines += units_line(units)
    for key in sorted({(r["crack"], r["end"]) for r in rows}):
        tip_rows = [r for r in rows if (r["crack"], r["end"]) == key]
        for c in cases:
            pts = [(r["a"], r[c]) for r in tip_rows if r.get(c) is not None]
            if not pts:
                continue
            lines.append(f"# tip: crack {key[0]} end {key[1]}; case: {c[5:]}")
            lines += [f"{a:.8g} {b:.8g}" for a, b in pts]
    with atomic_path(out / "beta_afgrow.txt") as tmp:
        tmp.write_text("\n".join(lines) + "\n")
    return ["beta.csv", "beta_afgrow.txt"]


def _tips(result: GrowthResult) -> dict[tuple[int, int], list[TipRecord]]:
    out: dict[tuple[int, int], list[TipRecord]] = {}
    for step in result.records:
        for r in step:
            out.setdefault((r.crack, r.end), []).append(r)
    return out


def one_cycle_per_block(pairs) -> bool:
    """Whether every (cycles, blocks) pair is equal: a block of one cycle
    (a constant-amplitude flight), so a life needs one axis, not two."""
    return all(abs(n - b) <= 1e-9 * max(1.0, abs(n)) for n, b in pairs)


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
        for c in scene.cracks:  # (wider than the paths drawn over them, which start on them: a grey rim)
            ax.plot(c.points[:, 0], c.points[:, 1], "-", color="0.5", lw=4.5, solid_capstyle="butt")
        for i, c in enumerate(result.cracks):
            ax.plot(c.points[:, 0], c.points[:, 1], ".-", ms=2, lw=1.0, color=f"C{i % 10}", label=c.name)
        ax.set_aspect("equal")
        ax.set_xlabel(label(scene.units, "length", "x"))
        ax.set_ylabel(label(scene.units, "length", "y"))
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

    units = getattr(scene, "units", None)
    tips = _tips(result)
    fig = new_figure((7, 4.5))
    ax = fig.add_subplot()
    sif_rows = []
    for n, ((ci, end), recs) in enumerate(tips.items()):
        L = [r.length for r in recs]
        label_ = f"{result.cracks[ci].name} end {end}"
        ax.plot(L, [r.K_I for r in recs], "o-", ms=3, color=f"C{n}", label=f"{label_}: K_I" + (" (max)" if fatigue else ""))
        ax.plot(L, [r.K_II for r in recs], "s--", ms=3, color=f"C{n}", label=f"{label_}: K_II")
        if fatigue:
            kmin = [r.K_I_min for r in recs]
            dk = [r.delta_K for r in recs]
            if any(v is not None for v in kmin):
                ax.plot(L, [np.nan if v is None else v for v in kmin], "v:", ms=3, color=f"C{n}",
                        label=f"{label_}: K_I at the minimum")
            if any(v is not None for v in dk):
                ax.plot(L, [np.nan if v is None else v for v in dk], "^-.", ms=3, color=f"C{n}", alpha=0.7,
                        label=f"{label_}: Delta K_eff")
        sif_rows += [[r.step, ci, end, r.length, r.K_I, r.K_II, r.K_I_min, r.K_II_min, r.delta_K] for r in recs]
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(label(units, "length", "crack length"))
    ax.set_ylabel(label(units, "K", "K"))
    ax.set_title(f"{scene_file.title}\nstress intensity factors along the growth", fontsize=10)
    ax.legend(fontsize=7)
    save_png(fig, out / "sif_history.png")
    write_csv(out / "sif_history.csv", ["step", "crack", "end", "length", "K_I", "K_II", "K_I_min", "K_II_min",
                                        "delta_K_eff"], sif_rows)
    names += ["sif_history.png", "sif_history.csv"]

    if fatigue:
        life = result.life
        # with a life, a panel against blocks too, unless a block is one cycle (one panel, both names)
        one = not life or one_cycle_per_block([(r.N, r.blocks) for recs in tips.values() for r in recs])
        fig = new_figure((7, 4.5) if one else (10, 4.5))
        axes = [fig.add_subplot()] if one else [fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)]
        rows = []
        for n, ((ci, end), recs) in enumerate(tips.items()):
            recs = [r for r in recs if r.status not in PAST_STOP]  # (its N is the stop's: not an (a, N) point)
            lab = f"{result.cracks[ci].name} end {end}"
            axes[0].plot([r.N for r in recs], [r.length for r in recs], "o-", ms=3, color=f"C{n}", label=lab)
            if not one:
                axes[1].plot([r.blocks for r in recs], [r.length for r in recs], "o-", ms=3, color=f"C{n}", label=lab)
            rows += [[r.step, ci, end, r.length, r.a, r.N, r.passes, r.blocks] if life else
                     [r.step, ci, end, r.length, r.N] for r in recs]
        axes[0].set_xlabel(f"cycles N = {life['block_name']}s (one cycle each)" if life and one else "cycles N")
        for ax in axes:
            ax.set_ylabel(label(units, "length", "crack length a"))
            ax.legend(fontsize=7)
        if life:
            if not one:
                axes[1].set_xlabel(f"{life['block_name']}s")
            fail = life.get("failure")
            if fail:
                for ax, x in zip(axes, (fail["cycles"], fail["blocks"])):
                    ax.axvline(x, color="r", lw=0.8, ls="--")
                axes[0].text(fail["cycles"], ax.get_ylim()[0], f" failure ({fail['criterion']})", color="r",
                             fontsize=7, rotation=90, va="bottom")
        axes[0].set_title(f"{scene_file.title}\nfatigue: crack length against cycles", fontsize=10)
        save_png(fig, out / "a_N.png")
        # (a, passes and blocks are a spectrum life's: constant amplitude has the length and the cycles)
        write_csv(out / "a_N.csv", ["step", "crack", "end", "length", "a", "cycles", "passes", "blocks"] if life else
                  ["step", "crack", "end", "length", "cycles"], rows)
        names += ["a_N.png", "a_N.csv"]
    if result.life:
        names += write_life_pngs(scene_file, result, out, tips)
    return names


def write_life_pngs(scene_file, result: GrowthResult, out: pathlib.Path, tips, growth=None) -> list[str]:
    """dadN.png (da/dN against Delta K: the law's curves at the R of the
    largest cycles, and each step's largest cycle on them; the CSV adds the
    mean growth per counted cycle), life_K.png (K_max, K_min, Delta K_eff of each tip's largest cycle
    against cycles), residual_strength.png (against a); each with its CSV.
    growth: the settings run (default the scene file's; 3D: with the
    fatigue material made of growth.paris_C, front_growth.life_growth)."""
    from ..analysis.life import create_law
    units = getattr(scene_file.scene, "units", None)
    life = result.life
    fm = (growth if growth is not None else scene_file.growth).fatigue_material.converted(units)
    law = create_law(fm)
    names = []
    fig = new_figure((7, 4.5))
    ax = fig.add_subplot()
    rows = []
    dks = [r.delta_K_eff for recs in tips.values() for r in recs if r.delta_K_eff]
    Rs = sorted({round(r.R, 2) for recs in tips.values() for r in recs if r.R is not None})[:4] or [0.0]
    if dks:
        dk = np.geomspace(min(dks) / 3.0, max(dks) * 1.5, 200)
        for j, R in enumerate(Rs):
            km = dk / max(1.0 - R, 1e-9)
            rate = law.law.rate(dk, np.full_like(dk, R), km, max(r.a or 1.0 for recs in tips.values() for r in recs))
            ok = np.isfinite(rate) & (rate > 0)
            ax.loglog(dk[ok], rate[ok], "-", color="0.3", lw=0.8 + 0.4 * j, label=f"law, R = {R:g}")
    for n, ((ci, end), recs) in enumerate(tips.items()):
        pts = [(r.delta_K_eff, float(law.rates(np.array([r.K_max]), np.array([r.K_min]), r.a or 1.0)[0]),
                r.da_per_pass / max(life["cycles_per_pass"] or 1.0, 1e-300)) for r in recs
               if r.delta_K_eff and r.K_max is not None and r.da_per_pass]
        if pts:
            x, y, _ = zip(*pts)
            ax.loglog(x, y, "o", ms=4, color=f"C{n}", label=f"{result.cracks[ci].name} end {end}: each step's "
                      "largest counted cycle")
        rows += [[r.step, ci, end, r.a, r.delta_K_eff, r.R, r.K_max, r.K_min, r.da_per_pass,
                  r.da_per_pass / max(life["cycles_per_pass"] or 1.0, 1e-300) if r.da_per_pass else None]
                 for r in recs]
    ax.set_xlabel(label(units, "K", "Delta K (as the law sees it)"))
    ax.set_ylabel("da/dN" + (f" [{units.length}/cycle]" if units else ""))
    ax.set_title(f"{scene_file.title}\n{law.law.describe()}; closure {life['closure']}", fontsize=9)
    ax.legend(fontsize=7)
    save_png(fig, out / "dadN.png")
    write_csv(out / "dadN.csv", ["step", "crack", "end", "a", "delta_K_eff", "R", "K_max", "K_min", "da_per_pass",
                                 "mean_da_per_cycle"], rows)
    names += ["dadN.png", "dadN.csv"]

    fig = new_figure((7, 4.5))
    ax = fig.add_subplot()
    rows = []
    for n, ((ci, end), recs) in enumerate(tips.items()):
        N = [r.N for r in recs]
        lab = f"{result.cracks[ci].name} end {end}"
        for attr, style, text in (("K_max", "o-", "K_max"), ("K_min", "v:", "K_min"), ("delta_K_eff", "^--", "Delta K_eff")):
            ax.plot(N, [np.nan if getattr(r, attr) is None else getattr(r, attr) for r in recs], style, ms=3,
                    color=f"C{n}", label=f"{lab}: {text}")
        rows += [[r.step, ci, end, r.a, r.N, r.blocks, r.K_max, r.K_min, r.delta_K_eff, r.R] for r in recs]
    if life.get("K_crit"):
        ax.axhline(life["K_crit"], color="r", lw=0.8, ls="--", label="K_c")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("cycles N")
    ax.set_ylabel(label(units, "K", "K of the largest counted cycle"))
    ax.set_title(f"{scene_file.title}\nK_max, K_min, Delta K_eff along the life", fontsize=10)
    ax.legend(fontsize=7)
    save_png(fig, out / "life_K.png")
    write_csv(out / "life_K.csv", ["step", "crack", "end", "a", "cycles", "blocks", "K_max", "K_min", "delta_K_eff",
                                   "R"], rows)
    names += ["life_K.png", "life_K.csv"]

    curve = life.get("residual_strength") or []
    fig = new_figure((7, 4.5))
    ax = fig.add_subplot()
    stress = all(c["stress"] is not None for c in curve) and bool(curve)
    for n, key in enumerate(sorted({(c["crack"], c["end"]) for c in curve})):
        pts = [c for c in curve if (c["crack"], c["end"]) == key]
        ax.plot([c["a"] for c in pts], [c["stress"] if stress else c["multiple"] for c in pts], "o-", ms=3,
                color=f"C{n}", label=f"{result.cracks[key[0]].name} end {key[1]}")
    if curve:
        ax.axhline(max((c["stress"] / c["multiple"]) for c in curve) if stress else 1.0, color="k", lw=0.8, ls="--",
                   label="the spectrum's maximum load")
    fail = life.get("failure")
    if fail:
        ax.axvline(fail["a"], color="r", lw=0.8, ls=":", label=f"failure ({fail['criterion']})")
    ax.set_xlabel(label(units, "length", "crack length a"))
    ax.set_ylabel(label(units, "stress", "residual strength (critical remote stress)") if stress
                  else "residual strength / maximum load")
    ax.set_title(f"{scene_file.title}\nresidual strength against crack length", fontsize=10)
    if curve:
        ax.legend(fontsize=7)
    save_png(fig, out / "residual_strength.png")
    write_csv(out / "residual_strength.csv", ["step", "crack", "end", "a", "multiple", "stress"],
              [[c["step"], c["crack"], c["end"], c["a"], c["multiple"], c["stress"]] for c in curve])
    names += ["residual_strength.png", "residual_strength.csv"]
    return names
