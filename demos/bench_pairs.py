"""Benchmark pairs in worker processes (bench_3d.py, bench_contact_3d.py):
a plain DOLFINx P1 solve and an X-FEM solve of one mesh, timed one after
the other in one process.

With --process-per-pair each pair runs in a process of its own (the mesh
made in each), plain first and X-FEM first in turn, and the rows of the
processes are merged: medians of their times, every pair's ratio. Why: on
this VM, with glibc's default 4 KB pages, the memory-bound kernels of a
solve slow down as the process ages (the same 1e6-dof solve's matrix
products 46.6 s, then 85.0 s; CPU time = wall, no steal, few page faults),
so pairs late in one process measure its age as much as the solver, and
the later solve of a pair is the slower. With huge pages
(GLIBC_TUNABLES=glibc.malloc.hugetlb=1, docs/speed.md) that slowing was
gone.
"""
from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import typing


def add_argument(ap: argparse.ArgumentParser) -> None:
    ap.add_argument("--process-per-pair", action="store_true",
                    help="each pair in a fresh process (the mesh made in each), plain first and X-FEM first in "
                         "turn (docs/speed.md: a process's later solves are slower on this VM)")


def in_order(spec: dict, plain: typing.Callable[[], dict], xfem: typing.Callable[[], dict]) -> tuple[dict, dict]:
    """(plain's row, X-FEM's row), run in the order spec["xfem_first"] asks (default: plain first)."""
    if spec.get("xfem_first"):
        x = xfem()
        return plain(), x
    p = plain()
    return p, xfem()


def run(script: pathlib.Path | str, spec: dict, process_per_pair: bool) -> dict:
    """The row of one size: one worker process running spec["repeats"]
    pairs, or with process_per_pair that many processes of one pair each
    (merged). A failed worker gives {"status": "failed: ..."}."""
    specs = ([dict(spec, repeats=1, xfem_first=bool(k % 2)) for k in range(spec["repeats"])]
             if process_per_pair else [spec])
    parts = []
    for sp in specs:
        proc = subprocess.run([sys.executable, str(script), "--worker", json.dumps(sp)], capture_output=True,
                              text=True)
        if proc.returncode != 0:
            return {"status": f"failed: {proc.stderr.strip()[-600:]}"}
        parts.append(json.loads(proc.stdout.strip().splitlines()[-1]))
    return parts[0] if len(parts) == 1 else merged(parts)


#: The merged row's keys that are medians over the processes.
MEDIAN_PREFIXES = ("t_solve_", "t_setup_", "t_total_", "t_assemble", "t_contact_setup", "ratio_")


def merged(parts: list[dict]) -> dict:
    """One row from the rows of one-pair processes: medians of their times
    and ratios, every pair's ratio and order, the largest peak memory; the
    rest (sizes, iteration counts, per-solve details) from the last."""
    row = dict(parts[-1])
    for key in [k for k, v in row.items() if k.startswith(MEDIAN_PREFIXES) and isinstance(v, (int, float))]:
        row[key] = statistics.median(p[key] for p in parts)
    for key in ("ratios_solve", "t_solve_pairs"):
        if key in row:
            row[key] = [r for p in parts for r in p[key]]
    row["xfem_first"] = [bool(p.get("xfem_first")) for p in parts]
    row["repeats"] = row["processes"] = len(parts)
    row["peak_rss_gb"] = max(p["peak_rss_gb"] for p in parts)
    if "load_average" in row:
        row["load_average"] = [parts[0]["load_average"][0], parts[-1]["load_average"][1]]
    return row
