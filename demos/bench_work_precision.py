"""Work-precision benchmark (issue 5): error against wall time for the
Westergaard check and the crack from a hole, per configuration (tip
enrichment, tip quadrature, multiplier space), over a mesh sweep, with a plain
DOLFINx P1 solve on the same meshes as the baseline measured in the same run.

Times are medians of --repeats runs of the whole solve (model, assembly,
checked MUMPS solve, contact iterations); mesh generation and error
evaluation are excluded. The plain baseline is a P1 elasticity solve on the
same mesh with the same solver (bench_core's scene on the square, a clamped
symmetry line and a constant traction on the half annulus).

    /usr/bin/python3 demos/bench_work_precision.py --json results/work_precision.json
"""
from __future__ import annotations

import argparse
import dataclasses
import pathlib
import statistics
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))

import cracklip as cl  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
import hole_crack  # noqa: E402
import westergaard  # noqa: E402
from cracklip.exact.kirsch import crack_pressure, kirsch_strain  # noqa: E402

CONFIGS = {
    "westergaard": [dict(enrichment="vector", quadrature="collapsed"),
                    dict(enrichment="scalar", quadrature="collapsed"),
                    dict(enrichment="vector", quadrature="gauss", quadrature_degree=5),
                    dict(enrichment="vector", blending="standard")],
    "hole": [dict(enrichment="vector", quadrature="collapsed", multipliers="stable"),
             dict(enrichment="scalar", quadrature="collapsed", multipliers="stable"),
             dict(enrichment="vector", quadrature="gauss", quadrature_degree=20, multipliers="stable")],
}


def label(cfg: dict) -> str:
    return ", ".join(f"{v}" if k != "quadrature_degree" else f"degree {v}" for k, v in cfg.items())


def westergaard_case(n: int):
    base, exact = westergaard.scene_for(n)
    mesh, mat = base.mesh, base.material

    def scene(cfg):
        return dataclasses.replace(base, options=cl.Options(radius=0.2, **cfg))

    def errors(sol):
        k = sol.stress_intensity_factors(0)[0]
        return {"energy_error": sol.energy_error(lambda p, s: exact.gradient(p, s))[1],
                "sif_error": abs(k["K_I"] - 1.0)}

    plain = cl.Scene(mesh, mat, dirichlet=[cl.Dirichlet("bottom")], tractions=[cl.Traction("top", (0.0, 1.0))])
    return scene, errors, plain


def hole_case(h: float):
    mesh_scene = hole_crack.scene_for(h)
    mesh, mat = mesh_scene.mesh, mesh_scene.material

    def scene(cfg):
        sc = cl.Scene(mesh, mat, cracks=mesh_scene.cracks, dirichlet=mesh_scene.dirichlet,
                      tractions=mesh_scene.tractions, options=cl.Options(radius=0.3, contact="unilateral", **cfg))
        return sc

    def errors(sol):
        cp = sol.contact_pressure(0)
        ex = crack_pressure(cp["x"][:, 1], hole_crack.SIGMA_INF)
        k = sol.stress_intensity_factors(0)[0]
        return {"energy_error": sol.energy_error(lambda p, s: kirsch_strain(p, -hole_crack.SIGMA_INF, 1.0, mat))[1],
                "pressure_error": float(np.sqrt(np.sum(cp["weight"] * (cp["pressure"] - ex) ** 2)
                                                / np.sum(cp["weight"] * ex ** 2))),
                "sif_error": abs(k["K_I"]) / (hole_crack.SIGMA_INF * np.sqrt(np.pi))}

    plain = cl.Scene(mesh, mat, dirichlet=[cl.Dirichlet("symmetry")], tractions=[cl.Traction("outer", (-0.01, 0.0))])
    return scene, errors, plain


def timed(f, repeats):
    ts, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = f()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts), ts, out


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--westergaard-n", type=int, nargs="+", default=[20, 40, 80, 160, 320, 700],
                    help="divisions per side (700: about 1.1e6 dofs)")
    ap.add_argument("--hole-h", type=float, nargs="+", default=[0.1, 0.05, 0.025, 0.0125])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--scalar-max-dofs", type=float, default=3e5,
                    help="skip the scalar enrichment above this size: its nearly dependent branch-function "
                         "dofs make MUMPS slow and memory-hungry (default 3e5)")
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/work_precision.json"))
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    log = (lambda m: None) if args.quiet else (lambda m: print(m, file=sys.stderr, flush=True))
    cl.solve_plain(westergaard_case(10)[2])  # warm-up (form compilation)
    rows = []
    for problem, sizes, case in (("westergaard", args.westergaard_n, westergaard_case),
                                 ("hole", args.hole_h, hole_case)):
        for size in sizes:
            scene, errors, plain = case(size)
            t_plain, runs_plain, (u_plain, ph_plain) = timed(lambda: cl.solve_plain(plain), args.repeats)
            for cfg in CONFIGS[problem]:
                if cfg["enrichment"] == "scalar" and 2 * u_plain.size > 2 * args.scalar_max_dofs:
                    log(f"{problem} {size} [{label(cfg)}] skipped (above --scalar-max-dofs)")
                    continue
                t_x, runs_x, sol = timed(lambda: cl.solve(scene(cfg)), args.repeats)
                row = {"problem": problem, "size": size, "config": label(cfg), "ndofs": sol.model.num_dofs,
                       "ndofs_plain": int(u_plain.size), "t_xfem": t_x, "t_plain": t_plain,
                       "ratio": t_x / t_plain, "t_xfem_runs": runs_x, "t_plain_runs": runs_plain,
                       "phases_xfem": sol.timings, "phases_plain": ph_plain, **errors(sol)}
                log(f"{problem} {size} [{row['config']}] dofs={row['ndofs']} t={t_x:.3f}s plain={t_plain:.3f}s "
                    f"ratio={row['ratio']:.2f} energy={row['energy_error']:.2e} sif={row['sif_error']:.2e}")
                rows.append(row)
                save(args, rows)  # after every row: a long run keeps what it measured
    res = save(args, rows)
    plot(res, args.json.with_suffix(".png"))
    return res


def save(args, rows: list) -> dict:
    res = {"benchmark": "work_precision", "repeats": args.repeats, "rows": rows}
    write_json(args.json, res)
    return res


def plot(res: dict, path: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    for col, problem in enumerate(("westergaard", "hole")):
        rows = [r for r in res["rows"] if r["problem"] == problem]
        for row_i, key in enumerate(("energy_error", "sif_error")):
            ax = axes[row_i, col]
            for cfg in dict.fromkeys(r["config"] for r in rows):
                rs = [r for r in rows if r["config"] == cfg]
                ax.loglog([r["t_xfem"] for r in rs], [max(r[key], 1e-16) for r in rs], "o-", label=cfg)
            plain = sorted({(r["size"], r["t_plain"]) for r in rows})
            for _, t in plain:
                ax.axvline(t, color="gray", lw=0.5, ls=":")
            ax.set_xlabel("wall time of the whole solve (s); dotted: plain DOLFINx P1 on the same meshes")
            ax.set_ylabel({"energy_error": "relative energy error", "sif_error": "SIF error (rel. to K)"}[key])
            ax.set_title(f"{problem}: {key.replace('_', ' ')} vs time")
            ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=140)
    plt.close(fig)


if __name__ == "__main__":
    main()
