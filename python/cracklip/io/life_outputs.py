"""What `cracklip life` writes: results.json (the life, its stop and
criterion, the critical crack size, the inspection threshold and interval,
the law, closure, K source), a_N.csv and a_N.png (crack size against
cycles and against blocks, failure and the detectable size marked) and
beta.csv and beta.png (the geometry factor the life used, K per unit load
over sqrt(pi a) of each load case against a). Files are written through
cracklip.io.files.atomic_path, like a run's.
"""
from __future__ import annotations

import math
import pathlib
import typing

import numpy as np

from ..scene.units import label
from .outputs import ensure_output_dir, versions, write_csv
from .results import write_results_json
from .pictures import new_figure, save_png


def write_life_outputs(life_file, setup, result, summary: dict, out_dir, timings: dict | None = None,
                       png: bool = True) -> dict[str, typing.Any]:
    """Write the life's files into out_dir; return results.json's content."""
    out = ensure_output_dir(out_dir)
    rows = result.rows
    two = "c" in rows[0]
    cols = ["a"] + (["c"] if two else []) + ["cycles", "passes", "blocks", "K_max"] + (["K_max_c"] if two else [])
    write_csv(out / "a_N.csv", cols, [[r[c] for c in cols] for r in rows])
    files = ["a_N.csv"]
    beta_cols, beta_rows = beta_table(setup, rows)
    write_csv(out / "beta.csv", beta_cols, beta_rows)
    files.append("beta.csv")
    if png:
        files += write_life_pngs(life_file, setup, result, summary, out, beta_cols, beta_rows)
    results = {
        "title": life_file.title,
        "scene_file": str(life_file.path) if life_file.path is not None else None,
        "versions": versions(),
        "life": summary,
        "notes": life_file.notes,
        "a_N": rows,
        "timings": dict(timings or {}),
        "files": files + ["results.json"],
    }
    write_results_json(out, _finite(results))
    return results


def _finite(o):
    """o with every non-finite float as None (results.json holds no NaN or inf)."""
    if isinstance(o, dict):
        return {k: _finite(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_finite(v) for v in o]
    if isinstance(o, (float, np.floating)) and not math.isfinite(o):
        return None
    return o


def beta_table(setup, rows: list[dict]) -> tuple[list[str], list[list[float]]]:
    """beta = K per unit load / sqrt(pi a) of each case at the a-N sizes (and
    at the surface point of a two-size crack)."""
    table = setup.table
    a = np.array([r["a"] for r in rows])
    if table.sizes == 1:
        K = table.evaluate(a)
        cols = ["a"] + [f"K_{g}" for g in table.cases] + [f"beta_{g}" for g in table.cases]
        beta = K / np.sqrt(math.pi * a)[:, None] / np.array([setup.life.stress(g) for g in table.cases])
        return cols, np.column_stack([a, K, beta]).tolist()
    c = np.array([r["c"] for r in rows])
    K = table.evaluate(a, c)
    S = np.array([setup.life.stress(g) for g in table.cases])
    cols = ["a", "c"] + [f"K_{p}_{g}" for p in ("a", "c") for g in table.cases] + \
        [f"beta_{p}_{g}" for p in ("a", "c") for g in table.cases]
    Ka, Kc = K[:, 0, :], K[:, 1, :]
    root = np.sqrt(math.pi * a)[:, None]
    return cols, np.column_stack([a, c, Ka, Kc, Ka / root / S, Kc / root / S]).tolist()


def write_life_pngs(life_file, setup, result, summary: dict, out: pathlib.Path, beta_cols, beta_rows) -> list[str]:
    units = life_file.units
    rows = result.rows
    two = "c" in rows[0]
    fig = new_figure((11, 4.5))
    axes = [fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)]
    block = setup.spectrum.block_name
    for ax, x, xlabel in ((axes[0], "cycles", "cycles N"), (axes[1], "blocks", f"{block}s")):
        ax.plot([r[x] for r in rows], [r["a"] for r in rows], "-", lw=1.2, label="a")
        if two:
            ax.plot([r[x] for r in rows], [r["c"] for r in rows], "--", lw=1.2, label="c")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(label(units, "length", "crack size"))
        if result.stop in ("K_max >= K_c", "net-section yield"):
            ax.axvline(rows[-1][x], color="r", lw=0.8, ls="--", label=f"failure ({result.stop})")
        if setup.life.detectable_size is not None:
            ax.axhline(setup.life.detectable_size, color="0.4", lw=0.8, ls=":", label="detectable size")
        ax.legend(fontsize=7)
    fig.suptitle(f"{life_file.title}\nlife: {summary['cycles']:.6g} cycles = {summary['blocks']:.6g} {block}s; "
                 f"{result.stop_reason}", fontsize=9)
    save_png(fig, out / "a_N.png", {"cycles": axes[0], "blocks": axes[1]})
    fig = new_figure((7, 4.5))
    ax = fig.add_subplot()
    data = np.asarray(beta_rows)
    for j, name in enumerate(beta_cols):
        if name.startswith("beta_"):
            ax.plot(data[:, 0], data[:, j], "-", lw=1.2, label=name)
    ax.set_xlabel(label(units, "length", "crack size a"))
    ax.set_ylabel("beta = K / (S sqrt(pi a))")
    ax.set_title(f"{life_file.title}\ngeometry factor: {setup.life.describe()}", fontsize=9)
    ax.legend(fontsize=7)
    save_png(fig, out / "beta.png")
    return ["a_N.png", "beta.png"]


__all__ = ["write_life_outputs", "beta_table"]
