"""Benchmark of the 3D X-FEM iterative path (issue 27): the penny scene of
demos/penny_crack.py at about 1e5, 5e5 and 1e6 dofs, against plain DOLFINx
P1 tetrahedral elasticity on the same mesh without the crack, by CG + GAMG
(six rigid modes as near-nullspace, the iterative path's GAMG options and
Krylov tolerance).

One subprocess per size (peak_rss_gb is that whole run's ru_maxrss: mesh,
model, assembly and solves). In it, --repeats pairs: the plain solve, then
the X-FEM solve, one after the other (the VM's speed drifts 20-30 % between
processes), after a warm-up on a small mesh. Rows: medians of the pairs'
times and ratios. With --process-per-pair each pair runs in a process of
its own, plain first and X-FEM first in turn (demos/bench_pairs.py: why).

t_solve: the solver's own work (X-FEM: phantom transform, GAMG and crack
band set-up, CG; plain: GAMG set-up and CG). t_total: X-FEM model,
assembly (standard + enriched), loads and solve; plain: DOLFINx assembly
and solve (the mesh is made once, outside both). band, outer: the dofs of
the crack band (solved exactly, MUMPS) and of the outer block (ICC; 0 when
the band is not split, solvers/sweep_blocks.py).

    /usr/bin/python3 demos/bench_3d.py --json results/bench_3d.json          # radius 2 h_front
    /usr/bin/python3 demos/bench_3d.py --geometric --json results/b.json    # radius 0.25 a
    /usr/bin/python3 demos/bench_3d.py --sizes 1e5 --repeats 1 --json /tmp/b.json
    /usr/bin/python3 demos/bench_3d.py --geometric --sizes 1e6 --process-per-pair --json /tmp/b.json
"""
from __future__ import annotations

import argparse
import json
import pathlib
import platform
import statistics
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[0] / "python"))
sys.path.insert(0, str(HERE))

import bench_pairs  # noqa: E402

#: dofs of the penny family at a/h = 20 (demos/penny_crack.py) with its
#: enrichment radius 0.25 a, and with a radius of 2 h_front: the size grows
#: as (a/h)^2.67 (measured between a/h = 20 and 28-29: the far size is fixed).
DOFS_AT_20 = {None: 3.25e5, "in_h": 3.06e5}
DOFS_EXPONENT = 2.67


def divisions_for(ndofs: float, radius_in_h: float | None = None) -> int:
    n20 = DOFS_AT_20[None if radius_in_h is None else "in_h"]
    return max(6, int(round(20.0 * (ndofs / n20) ** (1.0 / DOFS_EXPONENT))))


def _plain(scene) -> dict:
    """Plain DOLFINx P1 elasticity of the scene without its crack: DOLFINx
    assembles the form and the tractions, the point supports become
    Dirichlet rows; CG + GAMG."""
    import numpy as np
    import ufl
    from petsc4py import PETSc
    import dolfinx.fem
    import dolfinx.fem.petsc
    from cracklip.model.assembly import elasticity_form
    t0 = time.perf_counter()
    md = scene.mesh
    msh = md.mesh
    V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    bcs = []
    for bc in scene.dirichlet:
        p = np.asarray(bc.where, dtype=float)
        dofs = dolfinx.fem.locate_dofs_geometrical(
            (V.sub(bc.component), V.sub(bc.component).collapse()[0]) if bc.component is not None else V,
            lambda x, p=p: np.linalg.norm(x.T - p[None], axis=1) < 1e-9)
        if bc.component is None:
            bcs.append(dolfinx.fem.dirichletbc(np.zeros(3, dtype=PETSc.ScalarType), dofs, V))
        else:
            zero = dolfinx.fem.Function(V.sub(bc.component).collapse()[0])
            bcs.append(dolfinx.fem.dirichletbc(zero, dofs, V.sub(bc.component)))
    v = ufl.TestFunction(V)
    ds = ufl.Measure("ds", domain=msh, subdomain_data=md.facet_tags)
    L = sum(ufl.inner(dolfinx.fem.Constant(msh, PETSc.ScalarType(tuple(tr.value))), v) * ds(md.tags[tr.where])
            for tr in scene.tractions)
    L = dolfinx.fem.form(L)
    a = elasticity_form(V, scene.material.E, scene.material.nu)
    A = dolfinx.fem.petsc.assemble_matrix(a, bcs=bcs)
    A.assemble()
    b = dolfinx.fem.petsc.assemble_vector(L)
    dolfinx.fem.petsc.apply_lifting(b, [a], bcs=[bcs])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    dolfinx.fem.petsc.set_bc(b, bcs)
    t_assemble = time.perf_counter() - t0
    t1 = time.perf_counter()
    n = A.getSize()[0]
    import bench_solvers
    owned = V.dofmap.index_map.size_local  # (all nodes in serial)
    x, its, rel, t_setup = bench_solvers.plain_cg_gamg(A, b, V.tabulate_dof_coordinates()[:owned], "plain3d_")
    t_solve = time.perf_counter() - t1
    for obj in (A, b, x):
        obj.destroy()
    return {"ndofs": int(n), "t_solve": t_solve, "t_setup": t_setup, "t_total": t_assemble + t_solve,
            "iterations": its, "relative_residual": rel}


def _xfem(scene) -> dict:
    import numpy as np
    import cracklip as cl
    t0 = time.perf_counter()
    sol = cl.solve(scene)
    t_total = time.perf_counter() - t0
    tm = sol.timings
    s = sol.solver["solves"][-1]
    m = sol.model
    if m.distributed:  # (under mpirun: the global counts)
        ndofs = m.dofs.num_global * 3
        enriched = 3 * m.V.mesh.comm.allreduce(int((np.asarray(m.layout.node) < m.V.dofmap.index_map.size_local).sum()))
    else:
        ndofs, enriched = m.num_dofs, 3 * m.layout.num_enriched
    return {"ndofs": int(ndofs), "enriched_dofs": int(enriched),
            "t_solve": tm.get("phantom_transform", 0.0) + tm["solve"], "t_setup": s.get("t_setup"),
            "t_total": t_total, "t_assemble_enriched": tm["assemble_enriched"],
            "t_assemble_standard": tm["assemble_standard"], "iterations": int(s["iterations"]),
            "band": s.get("band"), "outer": s.get("outer"), "relative_residual": float(s["relative_residual"]), "method": s["method"]}


def worker(spec: dict) -> dict:
    import resource
    import penny_crack
    penny_crack.penny_scene(6)  # warm-up: gmsh, forms, libraries
    _plain(penny_crack.penny_scene(6))
    _xfem(penny_crack.penny_scene(6))
    t0 = time.perf_counter()
    n = spec["n"]
    radius = penny_crack.RADIUS if spec["radius_in_h"] is None else spec["radius_in_h"] / n
    scene = penny_crack.penny_scene(n, solver="iterative", radius=radius)
    t_mesh = time.perf_counter() - t0
    pairs = []
    for _ in range(spec["repeats"]):
        pairs.append(bench_pairs.in_order(spec, lambda: _plain(scene), lambda: _xfem(scene)))
    med = lambda key, which: statistics.median(pr[which][key] for pr in pairs)  # noqa: E731
    p_last, x_last = pairs[-1]
    return {"a_over_h": spec["n"], "radius": radius, "ndofs": x_last["ndofs"], "plain_ndofs": p_last["ndofs"],
            "cells": int(scene.mesh.mesh.topology.index_map(3).size_local), "t_mesh": t_mesh,
            "enriched_dofs": x_last["enriched_dofs"], "band": x_last["band"], "outer": x_last["outer"],
            "t_solve_xfem": med("t_solve", 1), "t_solve_plain": med("t_solve", 0),
            "t_setup_xfem": med("t_setup", 1), "t_setup_plain": med("t_setup", 0),
            "t_total_xfem": med("t_total", 1), "t_total_plain": med("t_total", 0),
            "t_assemble_enriched": med("t_assemble_enriched", 1),
            "ratio_solve": statistics.median(x["t_solve"] / p["t_solve"] for p, x in pairs),
            "ratio_total": statistics.median(x["t_total"] / p["t_total"] for p, x in pairs),
            "ratios_solve": [x["t_solve"] / p["t_solve"] for p, x in pairs],
            "iterations_xfem": x_last["iterations"], "iterations_plain": p_last["iterations"],
            "repeats": spec["repeats"], "xfem_first": bool(spec.get("xfem_first")),
            "peak_rss_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", nargs="+", default=["1e5", "5e5", "1e6"], help="target X-FEM dofs")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--radius-in-h", type=float, default=2.0,
                    help="front enrichment radius in front element sizes (default 2)")
    ap.add_argument("--geometric", action="store_true",
                    help="penny_crack's fixed radius 0.25 a instead (7.5 front elements at 1e6 dofs: the tip "
                         "dofs' torus, split into the exact band and the inexact outer block, docs/speed.md)")
    bench_pairs.add_argument(ap)
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/bench_3d.json"))
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        print(json.dumps(worker(json.loads(args.worker))))
        return {}
    if args.geometric:
        args.radius_in_h = None
    rows = []
    for size in args.sizes:
        spec = {"n": divisions_for(float(size), args.radius_in_h), "repeats": args.repeats, "radius_in_h": args.radius_in_h}
        row = bench_pairs.run(__file__, spec, args.process_per_pair)
        row["target_dofs"] = float(size)
        rows.append(row)
        if "status" in row:
            continue
        print(f"{row['ndofs']} dofs: X-FEM solve {row['t_solve_xfem']:.1f} s ({row['iterations_xfem']} its), "
              f"plain {row['t_solve_plain']:.1f} s ({row['iterations_plain']} its): ratio "
              f"{row['ratio_solve']:.2f}; totals {row['t_total_xfem']:.1f} / {row['t_total_plain']:.1f} s; "
              f"peak {row['peak_rss_gb']:.2f} GB", flush=True)
    out = {"machine": platform.node(), "python": platform.python_version(), "rows": rows}
    args.json.parent.mkdir(parents=True, exist_ok=True)
    from cracklip.io.files import write_json
    write_json(args.json, out)
    return out


if __name__ == "__main__":
    main()
