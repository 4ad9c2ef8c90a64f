"""Benchmark of 3D crack-lip contact on the iterative path (issue 36): the
closed penny of demos/contact_3d.py (uniaxial compression at beta = 30
degrees to the crack's normal, bilateral frictionless contact, and with
--friction mu Coulomb friction) at about 1e5, 5e5 and 1e6 dofs, against
plain DOLFINx P1 tetrahedral elasticity on the same mesh without the crack
by CG + GAMG (demos/bench_3d.py's baseline: six rigid modes, the iterative
path's GAMG options and Krylov tolerance).

One subprocess per size (peak_rss_gb is that whole run's ru_maxrss). In
it, after a warm-up on a small mesh, --repeats pairs: the plain solve, then
the contact solve, one after the other (the machine's speed drifts between
processes and with the other jobs on it). Rows: medians of the pairs'
times and ratios, and the load average of the machine over the run. With
--process-per-pair each pair runs in a process of its own, plain first and
the contact solve first in turn (demos/bench_pairs.py: why).

t_solve: the solver's own work. Contact: the phantom transform and the
contact solve (the saddle point [K B^T; B 0] by the Schwarz sweep {MUMPS
on the crack band and the multipliers | GAMG | band} inside CG, every
active-set or friction iteration included; with friction the
unsymmetric saddle point by GMRES(30), its early semi-smooth iterations
inexact: krylov_rtols, contact/friction.py INEXACT_RTOL; the multiplier
space, B and M built once, counted in t_contact_setup, not in t_solve;
ratio_solve_with_setup counts them too). Per solve of the last pair:
krylov_iterations, t_krylov_setup (the preconditioner's set-up: GAMG's
on the first, t_amg_setup, and each solve's band blocks and
factorisation, t_band_setup; band_stale: the band preconditioned by the
kept factorisation of an earlier one, solvers/band_update.py), t_solves. Plain: GAMG
set-up (t_setup_plain) and CG. t_total: X-FEM model, assembly, contact system and solve;
plain: DOLFINx assembly and solve (the mesh is made once, outside both).

The front enrichment radius is 2 h_front (bench_3d.py's default: the crack
band stays a thin tube; with the fixed 0.25 a of demos/contact_3d.py it
grows to a torus of 7.5 front elements at 1e6 dofs, see docs/speed.md).

    /usr/bin/python3 demos/bench_contact_3d.py --json docs/bench/bench_contact_3d.json
    /usr/bin/python3 demos/bench_contact_3d.py --sizes 1e5 --repeats 1 --json /tmp/b.json
"""
from __future__ import annotations

import argparse
import json
import os
import pathlib
import platform
import statistics
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[0] / "python"))
sys.path.insert(0, str(HERE))

import bench_pairs  # noqa: E402


def _xfem(scene) -> dict:
    import cracklip as cl
    t0 = time.perf_counter()
    sol = cl.solve(scene)
    t_total = time.perf_counter() - t0
    tm = sol.timings
    solves = sol.solver["solves"]
    key = "path_solve" if "path_solve" in tm else "contact_solve"
    c = sol.contact
    return {"ndofs": int(sol.model.num_dofs), "enriched_dofs": int(3 * sol.model.layout.num_enriched),
            "multipliers": int(c["system"].num_multipliers), "iterations_contact": int(c["iterations"]),
            "t_solve": tm.get("phantom_transform", 0.0) + tm[key], "t_total": t_total,
            "t_assemble_enriched": tm["assemble_enriched"], "t_assemble_standard": tm["assemble_standard"],
            "krylov_iterations": [int(s["iterations"]) for s in solves],
            "band": next((s["band"] for s in reversed(solves) if s.get("band")), None),
            "relative_residual": float(solves[-1]["relative_residual"]),
            "method": next(s["method"] for s in reversed(solves) if s["iterations"] > 0),
            # (solve.solve's contact_solve holds the contact system's set-up; the
            # load path's path_solve, which friction takes, does not)
            "setup_in_solve": key == "contact_solve", "krylov_rtols": [float(s.get("rtol", 0.0)) for s in solves],
            "t_krylov_setup": [float(s["t_setup"]) for s in solves], "t_solves": [float(s["t_total"]) for s in solves],
            "t_band_setup": [float(s.get("t_band_setup") or 0.0) for s in solves],
            "t_amg_setup": float(solves[0].get("t_amg_setup") or 0.0),
            "band_stale": [bool(s.get("band_stale")) for s in solves],
            "max_pressure": float(-c["lambda"].min())}


def worker(spec: dict) -> dict:
    import resource
    import bench_3d
    import contact_3d
    from cracklip.contact import frictionless

    # The contact system's set-up time (multiplier space, B, M), measured
    # where the solve builds it.
    setup = []
    create = frictionless.create_contact_system

    def timed(model):
        t0 = time.perf_counter()
        out = create(model)
        setup.append(time.perf_counter() - t0)
        return out
    frictionless.create_contact_system = timed
    import cracklip.analysis.load_path as load_path
    load_path.create_contact_system = timed
    case = "beta30_mu0.3" if spec["friction"] else "beta30_mu0"
    warm = contact_3d.build(case, 6, solver="iterative", radius=2.0 / 6)
    bench_3d._plain(warm)
    _xfem(warm)
    t0 = time.perf_counter()
    n = spec["n"]
    scene = contact_3d.build(case, n, solver="iterative", radius=2.0 / n)
    t_mesh = time.perf_counter() - t0
    load0 = os.getloadavg()[0]
    pairs = []
    for _ in range(spec["repeats"]):
        setup.clear()
        p, x = bench_pairs.in_order(spec, lambda: bench_3d._plain(scene), lambda: _xfem(scene))
        x["t_contact_setup"] = sum(setup)
        # The contact system's set-up (B, M) out of t_solve, in t_solve_with_setup.
        if x["setup_in_solve"]:
            x["t_solve_with_setup"] = x["t_solve"]
            x["t_solve"] -= x["t_contact_setup"]
        else:
            x["t_solve_with_setup"] = x["t_solve"] + x["t_contact_setup"]
        pairs.append((p, x))
    med = lambda key, which: statistics.median(pr[which][key] for pr in pairs)  # noqa: E731
    p_last, x_last = pairs[-1]
    return {"case": case, "a_over_h": n, "radius": 2.0 / n, "ndofs": x_last["ndofs"], "plain_ndofs": p_last["ndofs"],
            "cells": int(scene.mesh.mesh.topology.index_map(3).size_local), "t_mesh": t_mesh,
            "enriched_dofs": x_last["enriched_dofs"], "multipliers": x_last["multipliers"], "band": x_last["band"],
            "t_solve_contact": med("t_solve", 1), "t_solve_plain": med("t_solve", 0),
            "t_setup_plain": med("t_setup", 0),
            "t_contact_setup": med("t_contact_setup", 1),
            "t_total_contact": med("t_total", 1), "t_total_plain": med("t_total", 0),
            "t_assemble_enriched": med("t_assemble_enriched", 1),
            "ratio_solve": statistics.median(x["t_solve"] / p["t_solve"] for p, x in pairs),
            "ratio_solve_with_setup": statistics.median(x["t_solve_with_setup"] / p["t_solve"] for p, x in pairs),
            "ratio_total": statistics.median(x["t_total"] / p["t_total"] for p, x in pairs),
            "ratios_solve": [x["t_solve"] / p["t_solve"] for p, x in pairs],
            "t_solve_pairs": [[p["t_solve"], x["t_solve"]] for p, x in pairs],
            "contact_iterations": x_last["iterations_contact"], "krylov_iterations": x_last["krylov_iterations"],
            "krylov_rtols": x_last["krylov_rtols"], "t_krylov_setup": x_last["t_krylov_setup"],
            "t_solves": x_last["t_solves"], "t_band_setup": x_last["t_band_setup"],
            "t_amg_setup": x_last["t_amg_setup"], "band_stale": x_last["band_stale"],
            "iterations_plain": p_last["iterations"], "method": x_last["method"],
            "relative_residual": x_last["relative_residual"], "max_pressure": x_last["max_pressure"],
            "repeats": spec["repeats"], "xfem_first": bool(spec.get("xfem_first")), "load_average": [load0, os.getloadavg()[0]],
            "peak_rss_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", nargs="+", default=["1e5", "5e5", "1e6"], help="target X-FEM dofs")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--friction", action="store_true", help="Coulomb friction mu = 0.3 (the crack slips)")
    bench_pairs.add_argument(ap)
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/bench_contact_3d.json"))
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        print(json.dumps(worker(json.loads(args.worker))))
        return {}
    import bench_3d
    rows = []
    for size in args.sizes:
        spec = {"n": bench_3d.divisions_for(float(size), 2.0), "repeats": args.repeats, "friction": args.friction}
        row = bench_pairs.run(__file__, spec, args.process_per_pair)
        row["target_dofs"] = float(size)
        rows.append(row)
        if "status" in row:
            print(row["status"], flush=True)
            continue
        print(f"{row['ndofs']} dofs, {row['multipliers']} multipliers: contact solve {row['t_solve_contact']:.1f} s "
              f"({row['contact_iterations']} contact it., Krylov {row['krylov_iterations']}), plain "
              f"{row['t_solve_plain']:.1f} s ({row['iterations_plain']} its): ratio {row['ratio_solve']:.2f}; totals "
              f"{row['t_total_contact']:.1f} / {row['t_total_plain']:.1f} s; peak {row['peak_rss_gb']:.2f} GB; load "
              f"{row['load_average'][0]:.1f} .. {row['load_average'][1]:.1f}", flush=True)
    out = {"machine": platform.node(), "python": platform.python_version(), "cores": os.cpu_count(),
           "friction": args.friction, "rows": rows}
    args.json.parent.mkdir(parents=True, exist_ok=True)
    from cracklip.io.files import write_json
    write_json(args.json, out)
    return out


if __name__ == "__main__":
    main()
