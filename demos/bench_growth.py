"""Cost of a growth step (issue 17, benchmark 7): seconds per step of
cracklip.grow against a single solve of the same mesh, in the same run.

The scene: an edge crack in [0, 1] x [-3, 3] under tension growing by fixed
increments on a uniform unstructured mesh of size h (about 2e4 dofs at
h = 0.025, 2e5 at 0.008). A step = solve (model, assembly with the cached
standard block, MUMPS), SIFs on three domains, kink, polyline update; the
single solve = cl.solve of the initial scene (model, full assembly, MUMPS).
Medians: of 3 single solves, of the steps after the first (which fills the
standard-block cache).

    /usr/bin/python3 demos/bench_growth.py --hs 0.025 0.008 --json results/bench_growth.json
"""
from __future__ import annotations

import argparse
import logging
import pathlib
import statistics
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

import cracklip as cl  # noqa: E402
from cracklip.scene.growth import Growth
from cracklip.analysis.growth import grow  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402


def scene_for(h: float) -> cl.Scene:
    md = cl.create_rectangle(0.0, -3.0, 1.0, 3.0, h)
    return cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-0.1, 0.0], [0.3, 0.0]], name="edge crack")],
                    dirichlet=[cl.Dirichlet(md.nearest_node((0.0, -3.0)), None, 0.0),
                               cl.Dirichlet(md.nearest_node((1.0, -3.0)), 1, 0.0)],
                    tractions=[cl.Traction("top", (0.0, 1.0)), cl.Traction("bottom", (0.0, -1.0))],
                    options=cl.Options(radius=3 * h))


def measure(h: float, steps: int, repeats: int) -> dict:
    scene = scene_for(h)
    singles = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        sol = cl.solve(scene)
        sol.stress_intensity_factors(None)
        singles.append(time.perf_counter() - t0)
    res = grow(scene_for(h), Growth(da=3 * h, steps=steps))
    per_step = res.step_times[1:]
    t_single, t_step = statistics.median(singles), statistics.median(per_step)
    return {"h": h, "ndofs": sol.model.num_dofs, "t_single_solve": t_single, "t_step": t_step,
            "ratio": t_step / t_single, "t_first_step": res.step_times[0], "steps": steps,
            "single_solves": singles, "step_seconds": res.step_times}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--hs", type=float, nargs="+", default=[0.025, 0.008], help="mesh sizes (default: about 2e4 "
                    "and 2e5 dofs)")
    ap.add_argument("--steps", type=int, default=6)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--json", type=pathlib.Path, default=None)
    args = ap.parse_args(argv)
    logging.getLogger("cracklip").setLevel(logging.ERROR)
    rows = []
    for h in args.hs:
        rows.append(measure(h, args.steps, args.repeats))
        r = rows[-1]
        print(f"h = {h:g}, {r['ndofs']} dofs: single solve {r['t_single_solve']:.3f} s, growth step "
              f"{r['t_step']:.3f} s (ratio {r['ratio']:.2f}; first step {r['t_first_step']:.3f} s)", file=sys.stderr)
    result = {"rows": rows}
    if args.json:
        write_json(args.json, result)
    return result


if __name__ == "__main__":
    main()
