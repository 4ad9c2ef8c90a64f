"""Benchmark: the whole X-FEM solve of an open interior crack against a plain
DOLFINx P1 elasticity solve on the same mesh (issue 2, acceptance 6).

Both solves use the same checked MUMPS LU (null-pivot detection and residual
check); times are medians of --repeats runs, interleaved, after a warm-up that
compiles the DOLFINx form. t_xfem covers geometry, enrichment, sparsity,
standard and enriched assembly, load, constraints and the solve; t_plain
covers DOLFINx's space, matrix creation, assembly with its Dirichlet
conditions, load and the same solve. Mesh generation is excluded from both.

    /usr/bin/python3 demos/bench_core.py --json out.json
"""
from __future__ import annotations

import argparse
import pathlib
import platform
import statistics
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

import cracklip as cl  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.scene.mesh import NODES_PER_AREA_H2  # noqa: E402  (gmsh's nodes per unit area at size h: ~1.17 / h^2)


def h_for_dofs(ndofs: float, area: float = 4.0) -> float:
    return (2.0 * NODES_PER_AREA_H2 * area / ndofs) ** 0.5


def scene_for(md, crack: bool) -> cl.Scene:
    cracks = [cl.Crack([[-0.3, 0.0123], [0.3, 0.0123]], name="interior")] if crack else []
    return cl.Scene(md, cl.Material(1.0, 0.3), cracks=cracks,
                    dirichlet=[cl.Dirichlet("bottom")],
                    tractions=[cl.Traction("top", (0.0, 1.0))])


def run_size(target: float, repeats: int, log) -> dict:
    h = h_for_dofs(target)
    t0 = time.perf_counter()
    md = cl.create_square(h)
    t_mesh = time.perf_counter() - t0
    t_x, t_p, phases, phases_plain = [], [], [], []
    for r in range(repeats):
        t0 = time.perf_counter()
        sol = cl.solve(scene_for(md, True))
        t_x.append(time.perf_counter() - t0)
        phases.append(sol.timings)
        t0 = time.perf_counter()
        u_plain, timings_plain = cl.solve_plain(scene_for(md, False))
        t_p.append(time.perf_counter() - t0)
        phases_plain.append(timings_plain)
        log(f"  run {r + 1}/{repeats}: x-fem {t_x[-1]:.3f} s, plain {t_p[-1]:.3f} s")
    t_xfem, t_plain = statistics.median(t_x), statistics.median(t_p)
    phase = {k: statistics.median(p[k] for p in phases) for k in phases[0] if k != "total"}
    phase_plain = {k: statistics.median(p[k] for p in phases_plain) for k in phases_plain[0]
                   if k != "total"}
    layout = sol.model.layout
    return {"target_dofs": target, "h": h, "ndofs": sol.model.num_dofs,
            "ndofs_plain": int(u_plain.size), "enriched_dofs": 2 * layout.num_enriched,
            "enriched_cells": int(layout.cells.size), "cells": int(sol.model.cells.shape[0]),
            "t_mesh": t_mesh, "t_xfem": t_xfem, "t_plain": t_plain, "ratio": t_xfem / t_plain,
            "t_xfem_runs": t_x, "t_plain_runs": t_p, "phases_xfem": phase,
            "phases_plain": phase_plain}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=float, nargs="+", default=[2e4, 2e5, 1e6],
                    help="target numbers of dofs (default: 2e4 2e5 1e6)")
    ap.add_argument("--repeats", type=int, default=3, help="runs per size (median reported)")
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/bench_core.json"))
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    log = (lambda *a: None) if args.quiet else (lambda m: print(m, file=sys.stderr, flush=True))

    # Warm-up: compile the DOLFINx elasticity form once.
    md = cl.create_square(0.5)
    cl.solve(scene_for(md, True))
    cl.solve_plain(scene_for(md, False))

    results = []
    for target in args.sizes:
        log(f"size ~{target:.0e} dofs")
        res = run_size(target, args.repeats, log)
        log(f"  ndofs {res['ndofs']}: t_xfem {res['t_xfem']:.3f} s, t_plain {res['t_plain']:.3f} s, "
            f"ratio {res['ratio']:.3f}")
        results.append(res)
    out = {"benchmark": "bench_core", "problem": "open interior crack (Heaviside), square [-1,1]^2",
           "solver": "MUMPS LU (PETSc), checked", "repeats": args.repeats,
           "machine": {"python": platform.python_version(), "processor": platform.processor(),
                       "cores_used": 1},
           "sizes": results}
    write_json(args.json, out)
    log(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
