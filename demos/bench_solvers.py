"""Benchmark of the solver paths (issue 15): X-FEM direct (MUMPS LDL^T on
OpenBLAS), X-FEM iterative (phantom basis, GAMG / Schwarz with the crack
band), and plain DOLFINx P1 elasticity on the same mesh without the crack
(CG + GAMG, and MUMPS LDL^T), for an open interior crack and the
bilateral-contact block.

Scene (research note "solvers at scale"): the square [-1, 1]^2 split into
n x n squares (two triangles each), crack (-0.3, 0.0123)-(0.3, 0.0123),
bottom clamped, traction (0, +1) on top for the open crack and (0, -1) with
bilateral contact; E = 1, nu = 0.3, vector tip enrichment, radius 0.

Every (size, solver, case) runs in its own subprocess, so that peak_rss_gb
(ru_maxrss of that process) is the memory of that solver; times are medians
of --repeats solves in that process after one warm-up solve on a small mesh.
t_solve is the solver's own work (X-FEM: phantom transform, AMG/Schwarz
setup, Krylov iterations or the MUMPS factorisation and solve, with contact
the saddle-point construction too; plain: GAMG setup + CG, or MUMPS);
t_total adds the model, the assembly and the constraints (not the mesh).
Rows of the X-FEM paths carry t_plain_gamg (the plain CG + GAMG solve of
the same mesh, same Krylov tolerance) and ratio_to_plain_gamg.

--untuned adds the reference row of acceptance 3: the X-FEM direct solve
with MUMPS LU in a subprocess that loads the netlib reference BLAS/LAPACK
first (LD_LIBRARY_PATH), as before issue 15. --orderings records, for the
open-crack matrix, MUMPS' factor size, flops and time per ordering
(ICNTL(7)). --threads adds the direct solve with 2 OpenBLAS threads. These
three run at sizes up to 1.1e6 dofs only.
--paired measures only acceptance 1 (iterative / plain CG + GAMG), in
pairs: one process per size solves the plain problem and then each X-FEM
case, --repeats times in turn, and reports the median of the pairs' ratios
(a ratio of two subprocesses' medians moves by +-0.2 on this VM).
A solver whose subprocess fails (out of memory: the direct path at large
sizes) gets a row with "status" saying so; --max-direct-dofs skips the
direct solves beyond a size.

    /usr/bin/python3 demos/bench_solvers.py --json results/bench_solvers.json
    /usr/bin/python3 demos/bench_solvers.py --sizes 2e4 2e5 1e6 4e6 1e7 --untuned --orderings --threads \\
        --json results/bench_solvers.json
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
import typing

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[0] / "python"))
sys.path.insert(0, str(HERE))

CRACK = [[-0.3, 0.0123], [0.3, 0.0123]]
CASES = ("open", "contact")
XFEM_SOLVERS = ("xfem-direct", "xfem-iterative")
PLAIN_SOLVERS = ("plain-gamg", "plain-mumps")
REFERENCE_BLAS = ["/usr/lib/x86_64-linux-gnu/blas", "/usr/lib/x86_64-linux-gnu/lapack"]
#: The untuned reference, the 2-thread row and the orderings run up to this
#: size (acceptance 3 is at 1e6 dofs; netlib LU at 1e7 would take hours).
REFERENCE_MAX_DOFS = 1.1e6
#: Orderings of Debian's MUMPS (no METIS, no SCOTCH): ICNTL(7) value -> name.
ORDERINGS = {0: "AMD", 2: "AMF", 4: "PORD", 6: "QAMD", 7: "auto"}


def divisions(ndofs: float) -> int:
    """n of the n x n structured square with about ndofs P1 dofs (2 (n + 1)^2)."""
    return max(2, int(round((ndofs / 2.0) ** 0.5)) - 1)


# -- worker side (one subprocess per measurement) ---------------------------------------------------

def _scene(md, case: str, crack: bool = True):
    import cracklip as cl
    contact = "bilateral" if case == "contact" else "none"
    return cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack(CRACK, name="interior")] if crack else [],
                    dirichlet=[cl.Dirichlet("bottom")],
                    tractions=[cl.Traction("top", (0.0, -1.0 if contact != "none" else 1.0))],
                    options=cl.Options(contact=contact, enrichment="vector", radius=0.0))


def _xfem(md, case: str, solver: str) -> dict:
    import dataclasses
    import cracklip as cl
    scene = _scene(md, case)
    scene = dataclasses.replace(scene, options=dataclasses.replace(scene.options, solver=solver))
    t0 = time.perf_counter()
    sol = cl.solve(scene)
    t_total = time.perf_counter() - t0
    tm = sol.timings
    t_solve = tm.get("phantom_transform", 0.0) + tm.get("solve", 0.0) + tm.get("contact_solve", 0.0)
    solves = sol.solver["solves"]
    return {"ndofs": sol.model.num_dofs, "t_solve": t_solve, "t_total": t_total,
            "iterations": int(sum(s["iterations"] for s in solves)),
            "relative_residual": max(s["relative_residual"] for s in solves),
            "method": solves[0]["method"], "band": solves[0].get("band"),
            "enriched_dofs": 2 * sol.model.layout.num_enriched,
            "multipliers": int(sol.contact["system"].num_multipliers) if sol.contact else 0,
            "energy": sol.strain_energy()}


def plain_cg_gamg(A, b, x_nodes, prefix: str) -> tuple:
    """CG + GAMG on a plain P1 elasticity system A x = b (blocked dofs, one
    node per row of x_nodes (m, d)): the nodes' rigid motions as
    near-nullspace, the iterative path's GAMG options and Krylov tolerance
    (options under `prefix`). (x, iterations, relative residual, GAMG set-up
    seconds); raises unless the residual is below 1e-8. The baseline of
    bench_solvers and bench_3d."""
    import numpy as np
    from petsc4py import PETSc
    from cracklip.solvers import iterative, near_nullspace
    comm = A.getComm().tompi4py()  # under mpirun: x_nodes are this process's owned nodes
    n = A.getLocalSize()[0]
    total = comm.allreduce(np.concatenate([x_nodes.sum(axis=0), [len(x_nodes)]]))
    Q = near_nullspace.rigid_motions(x_nodes - total[:-1] / total[-1], np.arange(len(x_nodes)), n, comm)
    vecs = []
    for j in range(Q.shape[1]):
        w = A.createVecRight()
        w.array[:] = Q[:, j]
        vecs.append(w)
    A.setNearNullSpace(PETSc.NullSpace().create(vectors=vecs, comm=A.getComm()))
    A.setOption(PETSc.Mat.Option.SPD, True)
    opts = PETSc.Options()
    for k, val in iterative.GAMG_OPTIONS.items():
        opts[prefix + k] = val
    ksp = PETSc.KSP().create(A.getComm())
    ksp.setOptionsPrefix(prefix)
    ksp.setOperators(A)
    ksp.setType("cg")
    ksp.setTolerances(rtol=iterative.KRYLOV_RTOL, atol=0.0, max_it=iterative.MAX_ITERATIONS)
    ksp.setNormType(PETSc.KSP.NormType.UNPRECONDITIONED)
    ksp.setFromOptions()
    t0 = time.perf_counter()
    ksp.setUp()
    t_setup = time.perf_counter() - t0
    x = A.createVecRight()
    ksp.solve(b, x)
    its = ksp.getIterationNumber()
    r = b.duplicate()
    A.mult(x, r)
    r.axpy(-1.0, b)
    rel = r.norm() / b.norm()
    ksp.destroy()
    for obj in (r, *vecs):
        obj.destroy()
    if not rel <= 1e-8:
        raise RuntimeError(f"plain CG + GAMG did not converge: relative residual {rel:.3g}")
    return x, int(its), float(rel), t_setup


def _plain(md, solver: str) -> dict:
    """Plain DOLFINx P1 elasticity on the mesh (no crack): DOLFINx assembles
    with its Dirichlet conditions; CG + GAMG (rigid-mode near-nullspace, the
    iterative path's GAMG options and Krylov tolerance) or MUMPS LDL^T."""
    import numpy as np
    import ufl
    from petsc4py import PETSc
    import dolfinx.fem
    import dolfinx.fem.petsc
    from cracklip.model.assembly import elasticity_form
    from cracklip.solvers.checked import solve_checked
    t0 = time.perf_counter()
    msh = md.mesh
    V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    dofs = dolfinx.fem.locate_dofs_topological(V, 1, md.facets("bottom"))
    bc = dolfinx.fem.dirichletbc(np.zeros(2, dtype=PETSc.ScalarType), dofs, V)
    v = ufl.TestFunction(V)
    ds = ufl.Measure("ds", domain=msh, subdomain_data=md.facet_tags)
    L = dolfinx.fem.form(ufl.inner(dolfinx.fem.Constant(msh, PETSc.ScalarType((0.0, 1.0))), v) * ds(md.tags["top"]))
    a = elasticity_form(V, 1.0, 0.3)
    A = dolfinx.fem.petsc.assemble_matrix(a, bcs=[bc])
    A.assemble()
    b = dolfinx.fem.petsc.assemble_vector(L)
    dolfinx.fem.petsc.apply_lifting(b, [a], bcs=[[bc]])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    dolfinx.fem.petsc.set_bc(b, [bc])
    t_assemble = time.perf_counter() - t0
    t1 = time.perf_counter()
    if solver == "plain-mumps":
        x = solve_checked(A, b, 1e-8, what="plain P1 system", symmetric=True)
        its, rel = 1, None
    else:
        x, its, rel, _ = plain_cg_gamg(A, b, V.tabulate_dof_coordinates()[:, :2], "plain_")
    t_solve = time.perf_counter() - t1
    A.destroy()
    return {"ndofs": int(b.getSize()), "t_solve": t_solve, "t_total": t_assemble + t_solve,
            "iterations": int(its), "relative_residual": rel}


def _orderings(md) -> list[dict]:
    """Factor size, flops and time of the open-crack X-FEM matrix per MUMPS ordering."""
    from petsc4py import PETSc
    import cracklip as cl
    from cracklip.model.assembly import assemble_system
    model = cl.create_model(_scene(md, "open"))
    A, b, _ = assemble_system(model)
    A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
    rows = []
    for icntl, name in ORDERINGS.items():
        ksp = PETSc.KSP().create(PETSc.COMM_SELF)
        ksp.setOptionsPrefix("ord_")
        ksp.setOperators(A)
        ksp.setType("preonly")
        pc = ksp.getPC()
        pc.setType("cholesky")
        pc.setFactorSolverType("mumps")
        opts = PETSc.Options()
        opts["ord_mat_mumps_icntl_7"] = icntl
        opts["ord_mat_mumps_icntl_4"] = 0
        ksp.setFromOptions()
        t0 = time.perf_counter()
        ksp.setUp()
        x = A.createVecRight()
        ksp.solve(b, x)
        t = time.perf_counter() - t0
        F = pc.getFactorMatrix()
        used = F.getMumpsInfog(7)
        rows.append({"icntl_7": icntl, "requested": name, "used": ORDERINGS.get(used, str(used)),
                     "factor_entries": int(F.getMumpsInfog(29)), "flops": float(F.getMumpsRinfog(3)),
                     "t_factor_solve": t, "ndofs": int(A.getSize()[0])})
        F.destroy()
        x.destroy()
        del pc  # no wrapper may outlive ksp.destroy() (PETSc would keep the PC and its factors)
        ksp.destroy()
    return rows


def _paired(md, cases: typing.Sequence[str], repeats: int) -> list[dict]:
    """Acceptance 1 measured in pairs: each repeat solves the plain P1
    problem by CG + GAMG and then each case by the X-FEM iterative path, one
    after the other in this process, so that every ratio compares solves
    made a few seconds apart (the VM's speed drifts by 20-30 % between
    subprocesses). Rows per case: the times, the ratio of each pair and
    their median."""
    runs: dict[str, list[tuple[float, float, int]]] = {c: [] for c in cases}
    for _ in range(repeats):
        plain = _plain(md, "plain-gamg")
        for case in cases:
            r = _xfem(md, case, "iterative")
            runs[case].append((plain["t_solve"], r["t_solve"], r["iterations"]))
            ndofs, plain_its = r["ndofs"], plain["iterations"]
    return [{"case": case, "ndofs": ndofs, "t_plain_gamg_runs": [p for p, _, _ in rs],
             "t_iterative_runs": [x for _, x, _ in rs], "ratios": [x / p for p, x, _ in rs],
             "ratio_median": statistics.median(x / p for p, x, _ in rs), "iterations": rs[-1][2],
             "plain_iterations": plain_its} for case, rs in runs.items()]


def worker(spec: dict) -> dict:
    """One measurement (run in a subprocess): spec = {n, case, solver, repeats}."""
    import resource
    import hard_cases as hc
    from cracklip.solvers.checked import blas_library
    if spec.get("lu"):  # the untuned direct path: MUMPS LU as before issue 15
        from cracklip.solvers import checked as linear_solver, direct

        def lu(self, A, b, residual_tol, what, x0=None, **_):
            return linear_solver.solve_checked(A, b, residual_tol, what=what, symmetric=False)
        direct.DirectSolver.solve = lu
    # Warm-up: compile the forms, load the libraries.
    small = hc.structured_square(8)
    if spec["solver"] == "paired":
        _plain(small, "plain-gamg")
        for case in spec["cases"]:
            _xfem(small, case, "iterative")
    elif spec["solver"] in PLAIN_SOLVERS:
        _plain(small, spec["solver"])
    elif spec["solver"] == "orderings":
        pass
    else:
        _xfem(small, spec["case"], spec["solver"].split("-")[1])
    t0 = time.perf_counter()
    md = hc.structured_square(spec["n"])
    t_mesh = time.perf_counter() - t0
    if spec["solver"] == "paired":
        return {"paired": _paired(md, spec["cases"], spec["repeats"]), "t_mesh": t_mesh, "blas": blas_library()}
    if spec["solver"] == "orderings":
        out = {"orderings": _orderings(md)}
    else:
        runs = []
        for _ in range(spec["repeats"]):
            if spec["solver"] in PLAIN_SOLVERS:
                runs.append(_plain(md, spec["solver"]))
            else:
                runs.append(_xfem(md, spec["case"], spec["solver"].split("-")[1]))
        out = dict(runs[-1])
        for key in ("t_solve", "t_total"):
            out[key] = statistics.median(r[key] for r in runs)
            out[key + "_runs"] = [r[key] for r in runs]
    out.update({"t_mesh": t_mesh, "blas": blas_library(),
                "peak_rss_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2 ** 20})
    return out


# -- driver ------------------------------------------------------------------------------------------

def run_subprocess(spec: dict, env: dict[str, str] | None = None, timeout: float | None = None) -> dict:
    """Run worker(spec) in a fresh interpreter; a failure becomes {"status": ...}."""
    cmd = [sys.executable, str(pathlib.Path(__file__).resolve()), "--worker", json.dumps(spec)]
    full_env = {**os.environ, **(env or {})}
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, env=full_env, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": f"timed out after {timeout:g} s"}
    if p.returncode != 0:
        tail = " ".join((p.stderr or "").strip().splitlines()[-2:])[-300:]
        killed = p.returncode in (-9, 137)
        return {"status": ("killed (out of memory)" if killed else f"failed (exit {p.returncode}): {tail}")}
    return {"status": "ok", **json.loads(p.stdout.strip().splitlines()[-1])}


def benchmark(sizes: typing.Sequence[float], repeats: int, cases: typing.Sequence[str], untuned: bool,
              orderings: bool, threads: bool, max_direct_dofs: float, timeout: float | None, log) -> dict:
    from cracklip.scene.options import Options
    from cracklip.solvers import choice
    rows: list[dict] = []
    ordering_rows: list[dict] = []
    choices: list[dict] = []

    def add(spec, env=None, **extra):
        label = extra.pop("label", spec["solver"])
        log(f"  {label} ({spec.get('case', '-')}, n = {spec['n']}) ...")
        res = run_subprocess(spec, env, timeout)
        row = {"case": spec.get("case", "plain"), "target_dofs": spec["target"], "n": spec["n"], "solver": label,
               **extra, **res}
        row.setdefault("ndofs", 2 * (spec["n"] + 1) ** 2)
        for k in ("t_solve", "t_total", "iterations", "peak_rss_gb"):
            row.setdefault(k, None)
        log(f"    {row['status']}: t_solve {row['t_solve']}, iterations {row['iterations']}, "
            f"peak {row['peak_rss_gb']} GB")
        rows.append(row)
        return row

    for target in sizes:
        n = divisions(target)
        log(f"size ~{target:.0e} dofs (n = {n})")
        base = {"n": n, "target": target, "repeats": repeats}
        plain = {s: add({**base, "solver": s, "case": "plain"}, label=s)
                 for s in PLAIN_SOLVERS if s == "plain-gamg" or target <= max_direct_dofs}
        t_gamg = plain["plain-gamg"].get("t_solve")
        for case in cases:
            measured = {}
            for s in XFEM_SOLVERS:
                if s == "xfem-direct" and target > max_direct_dofs:
                    rows.append({"case": case, "target_dofs": target, "n": n, "solver": s, "ndofs": None,
                                 "t_solve": None, "t_total": None, "iterations": None, "peak_rss_gb": None,
                                 "status": f"skipped (--max-direct-dofs {max_direct_dofs:g})"})
                    continue
                row = add({**base, "solver": s, "case": case})
                if row["status"] == "ok" and t_gamg:
                    row["t_plain_gamg"] = t_gamg
                    row["ratio_to_plain_gamg"] = row["t_solve"] / t_gamg
                    measured[s] = row
            if threads and target <= min(max_direct_dofs, REFERENCE_MAX_DOFS) and case == "open":
                add({**base, "solver": "xfem-direct", "case": case}, env={"OPENBLAS_NUM_THREADS": "2"},
                    label="xfem-direct (2 BLAS threads)")
            if untuned and case == "open" and target <= min(max_direct_dofs, REFERENCE_MAX_DOFS):
                ld = ":".join(REFERENCE_BLAS + [os.environ.get("LD_LIBRARY_PATH", "")]).rstrip(":")
                row = add({**base, "solver": "xfem-direct", "case": case, "lu": True}, env={"LD_LIBRARY_PATH": ld},
                          label="xfem-direct-untuned (netlib BLAS, LU)")
                if row["status"] == "ok" and "xfem-direct" in measured:
                    measured["xfem-direct"]["ratio_to_untuned"] = measured["xfem-direct"]["t_solve"] / row["t_solve"]
            ndofs = next((r["ndofs"] for r in measured.values() if r.get("ndofs")), None)
            if ndofs:
                enriched = next((r["enriched_dofs"] for r in measured.values() if r.get("enriched_dofs")), 0)
                auto = choice.choose_solver(Options(), ndofs, enriched)
                ok = {k.split("-")[1]: r["t_solve"] for k, r in measured.items()}
                best = min(ok, key=ok.get) if ok else None
                choices.append({"case": case, "ndofs": ndofs, "auto": auto, "fastest": best, "t_solve": ok,
                                "auto_is_fastest": best is None or auto == best})
        if orderings and target <= min(max_direct_dofs, REFERENCE_MAX_DOFS):
            res = run_subprocess({**base, "solver": "orderings", "case": "open", "repeats": 1}, None, timeout)
            ordering_rows += [dict(r, target_dofs=target) for r in res.get("orderings", [])] or \
                [{"target_dofs": target, "status": res["status"]}]
    return {"rows": rows, "orderings": ordering_rows, "auto_choice": choices}


def plot(result: dict, path: pathlib.Path) -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(7.0, 4.5))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    series: dict[tuple[str, str], list[tuple[int, float]]] = {}
    for r in result["rows"]:
        if r.get("status") == "ok" and r.get("t_solve"):
            series.setdefault((r["case"], r["solver"]), []).append((r["ndofs"], r["t_solve"]))
    for (case, solver), pts in sorted(series.items()):
        pts.sort()
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"{solver} ({case})")
    ax.set_xlabel("dofs")
    ax.set_ylabel("t_solve [s]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def markdown(result: dict) -> str:
    """The README's speed table from a result: one row per (case, size) with
    t_solve of each path, the X-FEM iterative path's ratio to plain CG +
    GAMG, iterations and peak memory."""
    by: dict[tuple, dict] = {}
    for r in result["rows"]:
        by.setdefault((r["target_dofs"], r["case"]), {})[r["solver"]] = r
    plain = {t: rows for (t, c), rows in by.items() if c == "plain"}

    def cell(r: dict | None, what: str = "t_solve") -> str:
        if r is None:
            return "-"
        if r.get("status") != "ok":
            return str(r.get("status", "-")).split(" (")[0]
        v = r.get(what)
        return "-" if v is None else f"{v:.3g}"
    lines = ["| case | dofs | X-FEM direct (s) | X-FEM iterative (s) | its | ratio to plain GAMG | plain CG + GAMG (s) "
             "| plain MUMPS (s) | peak GB (direct / iterative) |", "|---|---|---|---|---|---|---|---|---|"]
    for (t, case), rows in sorted(by.items(), key=lambda kv: (kv[0][1], kv[0][0])):
        if case == "plain":
            continue
        d, it = rows.get("xfem-direct"), rows.get("xfem-iterative")
        p = plain.get(t, {})
        ndofs = next((r["ndofs"] for r in (d, it) if r and r.get("ndofs")), None)
        ratio = it.get("ratio_to_plain_gamg") if it else None
        mem = f"{cell(d, 'peak_rss_gb')} / {cell(it, 'peak_rss_gb')}"
        lines.append(f"| {case} | {ndofs if ndofs else f'~{t:.0e}'} | {cell(d)} | {cell(it)} | "
                     f"{it.get('iterations') if it else '-'} | {'-' if ratio is None else f'{ratio:.2f}'} | "
                     f"{cell(p.get('plain-gamg'))} | {cell(p.get('plain-mumps'))} | {mem} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=float, nargs="+", default=[2e4, 2e5],
                    help="target numbers of dofs (default: 2e4 2e5; the full sweep: 2e4 2e5 1e6 4e6 1e7)")
    ap.add_argument("--repeats", type=int, default=3, help="solves per measurement (median reported)")
    ap.add_argument("--cases", nargs="+", choices=CASES, default=list(CASES))
    ap.add_argument("--untuned", action="store_true",
                    help="add the untuned direct reference (netlib BLAS first on LD_LIBRARY_PATH, MUMPS LU)")
    ap.add_argument("--orderings", action="store_true", help="measure MUMPS orderings (sizes <= 1e6)")
    ap.add_argument("--threads", action="store_true", help="add the direct solve with 2 OpenBLAS threads")
    ap.add_argument("--max-direct-dofs", type=float, default=1e7,
                    help="skip direct solves (X-FEM and plain MUMPS) above this size (default 1e7)")
    ap.add_argument("--timeout", type=float, default=None, help="seconds per subprocess")
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/bench_solvers.json"))
    ap.add_argument("--quiet", action="store_true")
    ap.add_argument("--table", type=pathlib.Path, metavar="JSON",
                    help="print the Markdown speed table of an earlier run's JSON and stop")
    ap.add_argument("--paired", action="store_true",
                    help="only acceptance 1 in pairs: plain CG + GAMG then the X-FEM iterative cases, alternately "
                         "in one process per size (--repeats pairs), the median of the pairs' ratios")
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.table:
        print(markdown(json.loads(args.table.read_text())))
        return 0
    if args.worker:
        print(json.dumps(worker(json.loads(args.worker))))
        return 0
    from cracklip.io.files import write_json
    from cracklip.solvers.checked import blas_library
    log = (lambda *a: None) if args.quiet else (lambda m: print(m, file=sys.stderr, flush=True))
    t0 = time.perf_counter()
    if args.paired:
        result = {"paired": []}
        for target in args.sizes:
            n = divisions(target)
            log(f"paired, size ~{target:.0e} dofs (n = {n}), {args.repeats} pairs ...")
            res = run_subprocess({"n": n, "target": target, "repeats": args.repeats, "solver": "paired",
                                  "cases": list(args.cases)}, None, args.timeout)
            for row in res.get("paired", [{"status": res["status"]}]):
                result["paired"].append({"target_dofs": target, **row})
                log(f"  {row}")
    else:
        result = benchmark(args.sizes, args.repeats, args.cases, args.untuned, args.orderings, args.threads,
                           args.max_direct_dofs, args.timeout, log)
    out = {"benchmark": "bench_solvers", "repeats": args.repeats, "crack": CRACK,
           "problem": "square [-1,1]^2, n x n structured, bottom clamped, traction on top; "
                      "open: (0, 1); contact: (0, -1) with bilateral contact; vector tip enrichment, radius 0",
           "machine": {"python": platform.python_version(), "processor": platform.processor(),
                       "cpus": os.cpu_count(), "blas": blas_library(),
                       "openblas_num_threads": os.environ.get("OPENBLAS_NUM_THREADS")},
           "wall_time": time.perf_counter() - t0, **result}
    write_json(args.json, out)
    log(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    status = main()
    if not {"--worker", "--table", "--paired"} & set(sys.argv):
        import matplotlib
        matplotlib.use("Agg")
        args_json = pathlib.Path(sys.argv[sys.argv.index("--json") + 1]) if "--json" in sys.argv else \
            pathlib.Path("results/bench_solvers.json")
        plot(json.loads(args_json.read_text()), args_json.with_suffix(".png"))
    sys.exit(status)
