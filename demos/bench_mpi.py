"""Strong scaling under MPI (issue 40): the 3D penny of demos/penny_crack.py
on 1 and 2 processes, X-FEM (the iterative path, or --solver direct) and
plain DOLFINx P1 on the same mesh, paired in one run of this script.

Each repeat launches `mpirun -n 1` and then `mpirun -n 2` of this script's
worker (the order alternates between repeats: the VM's speed drifts
20-30 % between processes); a worker meshes the penny (gmsh on rank 0,
DOLFINx partitions), warms up on a small mesh, then solves the plain P1
system (CG + GAMG, the iterative path's options) and the X-FEM system
(cracklip.solve). Times are the slowest process's (wall clock; cpu_*:
the process's CPU time, which on a loaded machine shows the work each
process does apart from the waiting); peak_rss_gb is each process's ru_maxrss (mesh, model, assembly and solves). Rows: medians over
the repeats and the speed-ups t(1 process) / t(2 processes), each from the
pair of the same repeat.

On this 2-core VM two processes share the memory bandwidth (sparse
matrix-vector products and MUMPS' triangular solves are bandwidth-bound),
so the plain P1 solve itself bounds what X-FEM can gain.

    /usr/bin/python3 demos/bench_mpi.py --json docs/bench/bench_mpi.json              # ~5e5 dofs
    /usr/bin/python3 demos/bench_mpi.py --size 1e5 --repeats 1 --json /tmp/b.json
    /usr/bin/python3 demos/bench_mpi.py --memory 2 --size 4e6 --json docs/bench/bench_mpi_memory.json

--memory N: one run on N processes of the X-FEM solve alone (no plain P1,
no 1-process run), for the memory it takes: each process's peak resident
memory (ru_maxrss: meshing on rank 0, model, assembly, the solver's set-up
and solve) and their sum, an upper bound on the run's total at any time.
"""
from __future__ import annotations

import argparse
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[0] / "python"))
sys.path.insert(0, str(HERE))

#: The phases compared (X-FEM: cracklip.solve's timings; plain: bench_3d._plain's).
PHASES = ("t_solve_xfem", "t_total_xfem", "t_solve_plain", "t_total_plain", "t_mesh", "cpu_total_xfem",
          "cpu_total_plain")


def worker(spec: dict) -> dict:
    import resource
    from mpi4py import MPI
    import bench_3d
    import penny_crack
    comm = MPI.COMM_WORLD
    plain = spec.get("plain", True)
    small = penny_crack.penny_scene(6, solver=spec["solver"])  # warm-up: gmsh, forms, libraries
    if plain:
        bench_3d._plain(small)
    bench_3d._xfem(small)
    comm.Barrier()
    t0 = time.perf_counter()
    scene = penny_crack.penny_scene(spec["n"], solver=spec["solver"], radius=spec["radius_in_h"] / spec["n"])
    t_mesh = time.perf_counter() - t0
    comm.Barrier()
    c0 = time.process_time()
    p = bench_3d._plain(scene) if plain else {"ndofs": None, "iterations": None, "t_solve": 0.0, "t_total": 0.0}
    cpu_plain = time.process_time() - c0
    comm.Barrier()
    c0 = time.process_time()
    x = bench_3d._xfem(scene)
    cpu_xfem = time.process_time() - c0
    slowest = lambda v: comm.allreduce(v, op=MPI.MAX)  # noqa: E731
    return {"processes": comm.size, "a_over_h": spec["n"], "ndofs": x["ndofs"], "plain_ndofs": p["ndofs"],
            "enriched_dofs": x["enriched_dofs"], "band": x["band"], "method": x["method"],
            "iterations_xfem": x["iterations"], "iterations_plain": p["iterations"],
            "t_mesh": slowest(t_mesh), "t_solve_xfem": slowest(x["t_solve"]), "t_total_xfem": slowest(x["t_total"]),
            "t_solve_plain": slowest(p["t_solve"]), "t_total_plain": slowest(p["t_total"]),
            "relative_residual": x["relative_residual"],
            "cpu_total_xfem": slowest(cpu_xfem), "cpu_total_plain": slowest(cpu_plain),
            "peak_rss_gb": comm.allgather(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6)}


def _launch(n: int, spec: dict) -> dict:
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    cmd = ["mpirun", "--allow-run-as-root", "-n", str(n), sys.executable, __file__, "--worker", json.dumps(spec)]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        raise RuntimeError(f"{n} process(es) failed: {proc.stderr.strip()[-800:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _write(path: pathlib.Path, row: dict) -> dict:
    """The bench JSON: the machine and the row."""
    out = {"machine": platform.node(), "cpus": os.cpu_count(), "python": platform.python_version(),
           "load_average_at_end": os.getloadavg(), "rows": [row]}
    path.parent.mkdir(parents=True, exist_ok=True)
    from cracklip.io.files import write_json
    write_json(path, out)
    return out


def _memory(args, spec: dict) -> dict:
    """--memory N: one run, its peak memory per process and their sum."""
    run = _launch(args.memory, {**spec, "plain": False})
    peaks = run["peak_rss_gb"]
    row = {k: run[k] for k in ("processes", "ndofs", "enriched_dofs", "a_over_h", "band", "method", "iterations_xfem",
                               "relative_residual", "t_mesh", "t_solve_xfem", "t_total_xfem")}
    row.update(solver=args.solver, radius_in_h=args.radius_in_h, peak_rss_gb=peaks, peak_rss_sum_gb=sum(peaks))
    print(f"{row['ndofs']} dofs on {args.memory} processes: peak memory {' + '.join(f'{g:.2f}' for g in peaks)} "
          f"= {sum(peaks):.2f} GB; mesh {row['t_mesh']:.0f} s, X-FEM {row['t_total_xfem']:.0f} s "
          f"({row['iterations_xfem']} iterations)", flush=True)
    return _write(args.json, row)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size", default="5e5", help="target X-FEM dofs (default 5e5)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--solver", choices=("iterative", "direct"), default="iterative")
    ap.add_argument("--radius-in-h", type=float, default=2.0,
                    help="front enrichment radius in front element sizes (default 2, as bench_3d)")
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/bench_mpi.json"))
    ap.add_argument("--memory", type=int, metavar="N",
                    help="one X-FEM run on N processes for its peak memory (module doc)")
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        out = worker(json.loads(args.worker))
        from mpi4py import MPI
        if MPI.COMM_WORLD.rank == 0:
            print(json.dumps(out), flush=True)
        return {}
    import bench_3d
    spec = {"n": bench_3d.divisions_for(float(args.size), args.radius_in_h), "solver": args.solver,
            "radius_in_h": args.radius_in_h}
    if args.memory:
        return _memory(args, spec)
    pairs = []
    for rep in range(args.repeats):
        order = (1, 2) if rep % 2 == 0 else (2, 1)
        runs = {n: _launch(n, spec) for n in order}
        pairs.append(runs)
        one, two = runs[1], runs[2]
        print(f"repeat {rep + 1}: {one['ndofs']} dofs; X-FEM solve {one['t_solve_xfem']:.1f} / "
              f"{two['t_solve_xfem']:.1f} s ({one['iterations_xfem']} / {two['iterations_xfem']} its), plain "
              f"{one['t_solve_plain']:.1f} / {two['t_solve_plain']:.1f} s on 1 / 2 processes", flush=True)
    med = lambda n, key: statistics.median(p[n][key] for p in pairs)  # noqa: E731
    speedup = lambda key: statistics.median(p[1][key] / p[2][key] for p in pairs)  # noqa: E731
    row = {"ndofs": pairs[-1][1]["ndofs"], "plain_ndofs": pairs[-1][1]["plain_ndofs"],
           "enriched_dofs": pairs[-1][1]["enriched_dofs"], "a_over_h": spec["n"], "solver": args.solver,
           "method": pairs[-1][2]["method"], "repeats": args.repeats,
           "iterations_xfem": {n: pairs[-1][n]["iterations_xfem"] for n in (1, 2)},
           "iterations_plain": {n: pairs[-1][n]["iterations_plain"] for n in (1, 2)},
           "band": {n: pairs[-1][n]["band"] for n in (1, 2)},
           "peak_rss_gb": {n: pairs[-1][n]["peak_rss_gb"] for n in (1, 2)}}
    for key in PHASES:
        row[key] = {n: med(n, key) for n in (1, 2)}
        name = key[2:] if key.startswith("t_") else key
        row["speedup_" + name] = speedup(key)
        row["speedups_" + name] = [p[1][key] / p[2][key] for p in pairs]
    print(f"{row['ndofs']} dofs: X-FEM solve speed-up {row['speedup_solve_xfem']:.2f} "
          f"(total {row['speedup_total_xfem']:.2f}), plain P1 {row['speedup_solve_plain']:.2f} "
          f"(total {row['speedup_total_plain']:.2f}); peak per process {row['peak_rss_gb']}", flush=True)
    return _write(args.json, row)


if __name__ == "__main__":
    main()
