"""Cost of friction (issue 16, acceptance 6): a frictional contact solve against
the frictionless unilateral solve of the same scene, same mesh, same run.

The scene is demos/friction_crack.py's closed inclined crack (beta = 60
degrees, mu = 0.5: the whole crack slips) with its exact field on the
boundary of [-1, 1]^2. Rows: n, ndofs, t_frictionless, t_friction (medians
of the whole solve: model, assembly, contact iterations), their ratio, and
the iterations of each.

    /usr/bin/python3 demos/bench_friction.py --ns 60 300 --json results/bench_friction.json
"""
from __future__ import annotations

import argparse
import dataclasses
import logging
import pathlib
import statistics
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

import cracklip as cl  # noqa: E402
import friction_crack  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402


def measure(n: int, repeats: int, beta: float = 60.0, mu: float = 0.5) -> dict:
    field, _, _ = friction_crack.exact(beta, mu)
    scene = friction_crack.scene_for(field, n, mu)
    frictionless = dataclasses.replace(scene, options=dataclasses.replace(scene.options, friction=0.0))
    times = {"frictionless": [], "friction": []}
    its = {}
    for _ in range(repeats):
        for name, sc in (("frictionless", frictionless), ("friction", scene)):
            t0 = time.perf_counter()
            sol = cl.solve(sc)
            times[name].append(time.perf_counter() - t0)
            its[name] = int(sol.contact["iterations"])
            ndofs = sol.model.num_dofs
    t_free, t_fric = statistics.median(times["frictionless"]), statistics.median(times["friction"])
    return {"n": n, "ndofs": ndofs, "t_frictionless": t_free, "t_friction": t_fric, "ratio": t_fric / t_free,
            "iterations_frictionless": its["frictionless"], "iterations_friction": its["friction"],
            "repeats": repeats, "times": times}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ns", type=int, nargs="+", default=[60], help="divisions per side (300: about 2e5 dofs)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--json", type=pathlib.Path, default=None)
    args = ap.parse_args(argv)
    logging.getLogger("cracklip").setLevel(logging.ERROR)
    rows = []
    for n in args.ns:
        rows.append(measure(n, args.repeats))
        r = rows[-1]
        print(f"n = {n}, {r['ndofs']} dofs: frictionless {r['t_frictionless']:.2f} s ({r['iterations_frictionless']} "
              f"it.), friction {r['t_friction']:.2f} s ({r['iterations_friction']} it.), ratio {r['ratio']:.2f}",
              file=sys.stderr)
    result = {"rows": rows}
    if args.json:
        write_json(args.json, result)
    return result


if __name__ == "__main__":
    main()
