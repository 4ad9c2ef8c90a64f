"""What the error estimate of K costs (issue 39, acceptance 7): whole
command-line runs, each in a fresh process, with the default estimate and
with --no-estimate, alternated, medians of --repeats:

- the Westergaard square at h = 2/320 (demos/scenes/westergaard.toml,
  every output on; K_I exact = 1): the 2D estimate (sizes halved within
  20 element sizes of the tip);
- the penny crack at tip_h = a/14 (demos/scenes/penny_crack.toml, every
  output on): the 3D estimate (one more solve with every size times
  sqrt(2), a front finer than a tenth of the crack).

Per scene: the medians' ratio (bar: at most 2), wall times, dofs of the run
and of the estimate's mesh, the estimate's own seconds (results.json), and
K with its estimate (the Westergaard's true error beside it).

    /usr/bin/python3 demos/bench_estimate.py --json docs/bench/bench_estimate.json
"""
from __future__ import annotations

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent

#: (name, scene, overrides, exact K_I or None)
CASES = [("westergaard_h2_320", "westergaard.toml", ["mesh.h=0.00625"], 1.0),
         ("penny_tip_h_a14", "penny_crack.toml", ["mesh.tip_h=0.0714285714"], None)]

#: The bar: the run with the estimate at most this many times the run without.
BAR = 2.0


def cli_run(scene: str, overrides: list[str], estimate: bool, out: pathlib.Path) -> dict:
    """One CLI run in a fresh process: wall time, dofs, the estimate."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "python"))
    cmd = [sys.executable, "-m", "cracklip", "run", str(HERE / "scenes" / scene), "--out", str(out), "-q"]
    for o in overrides:
        cmd += ["--set", o]
    if not estimate:
        cmd.append("--no-estimate")
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, env=env, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    res = json.loads((out / "results.json").read_text())
    est = res.get("error_estimate")
    inner = [r for r in res["sifs"] if not r["free_surface"]]
    worst = max(inner, key=lambda r: abs(r["K_I_error"] or 0.0))
    # the estimate's own mesh: the level that is not the run's (3D: coarser
    # or finer, first or last)
    j = next(i for i, f in enumerate(est["size_factors"]) if f != est["of_size_factor"]) if est else None
    return {"wall": wall, "dofs": res["solution"]["dofs"],
            "estimate_dofs": est["dofs"][j] if est else None,
            "estimate_seconds": est["seconds"][j] if est else None,
            "K_I": worst["K_I"], "K_I_error": worst["K_I_error"],
            "largest_relative_error": est["largest_relative_error"] if est else None}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cases", nargs="+", default=[c[0] for c in CASES], choices=[c[0] for c in CASES])
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="extra overrides for every run (a smaller mesh for a test)")
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/bench_estimate.json"))
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT / "python"))
    from cracklip.io.files import write_json
    result = {"benchmark": "bench_estimate", "repeats": args.repeats, "bar": BAR, "cases": []}
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp)
        for name, scene, overrides, exact in CASES:
            if name not in args.cases:
                continue
            sets = overrides + args.set
            with_est, without = [], []
            for _ in range(args.repeats):
                without.append(cli_run(scene, sets, False, out))
                with_est.append(cli_run(scene, sets, True, out))
            m_with = statistics.median(r["wall"] for r in with_est)
            m_without = statistics.median(r["wall"] for r in without)
            last = with_est[-1]
            row = {"case": name, "scene": f"demos/scenes/{scene}", "overrides": sets,
                   "dofs": last["dofs"], "estimate_dofs": last["estimate_dofs"],
                   "wall_with_estimate": m_with, "wall_without": m_without, "ratio": m_with / m_without,
                   "met": m_with / m_without <= BAR, "walls_with": [r["wall"] for r in with_est],
                   "walls_without": [r["wall"] for r in without],
                   "estimate_seconds": statistics.median(r["estimate_seconds"] for r in with_est),
                   "K_I": last["K_I"], "K_I_error": last["K_I_error"],
                   "largest_relative_error": last["largest_relative_error"]}
            if exact is not None:
                row["K_I_true_error"] = abs(last["K_I"] - exact)
            result["cases"].append(row)
            print(f"{name}: {row['dofs']} dofs (estimate {row['estimate_dofs']}), with the estimate {m_with:.1f} s, "
                  f"without {m_without:.1f} s, ratio {row['ratio']:.2f} (bar {BAR:g}); K_I {row['K_I']:.6g} +- "
                  f"{row['K_I_error']:.2g}" + (f" (true error {row['K_I_true_error']:.2g})" if exact else ""),
                  flush=True)
    write_json(args.json, result)
    return result


if __name__ == "__main__":
    main()
