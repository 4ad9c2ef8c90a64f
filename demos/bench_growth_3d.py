"""Cost of a 3D growth step (issue 37, acceptance 4): seconds per step of a
front's growth against a single run of the same scene, in the same process.

The scene: the penny of demos/growth_3d.py (radius 1, box of half-width 6,
E = 1, nu = 0.3, uniform tension), h_front = 1/n in a box refinement over
the radii it grows through, the Paris law with R = 0 (one load level: one
solve per step). A single run = what `cracklip run` computes before writing
files: cl.solve (model, level sets, enrichment, full assembly, the linear
solve) and K along the front (Solution.stress_intensity_factors). A growth
step = measure (model on the new surface's level sets, assembly with the
cached standard block, the solve, K, the life's rates), count the cycles,
advance the front (the surface's strip, re-sampling, the breakthrough
test), as analysis.growth.GrowthRun.run times it (GrowthResult.step_times).
Medians: of `repeats` single runs (half before the growth run, half
after, so a drift of the machine's load weighs on both), of the steps after
the first (which fills the standard-block cache). Also the share of the front update (the
advance step) in a step.

    /usr/bin/python3 demos/bench_growth_3d.py --n 8 --json docs/bench/bench_growth_3d.json
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
from cracklip.analysis.front_growth import SurfaceGrowth  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.scene.crack_surface import EllipticalCrack  # noqa: E402
from cracklip.scene.mesh_3d import BoxRefinement, create_box  # noqa: E402

L, DA = 6.0, 0.05


def scene_for(n: int, steps: int) -> cl.Scene:
    h = 1.0 / n
    r = 1.0 + DA * steps + 4 * h
    mesh = create_box(-L, -L, -L, L, L, L, 2.0, fronts=[BoxRefinement((-r, -r, -3 * h), (r, r, 3 * h), h, 1.5)])
    crack = EllipticalCrack((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 1.0, axis=(1.0, 0.0, 0.0), name="penny")
    sup = [cl.Dirichlet((-L, -L, -L)), cl.Dirichlet((L, -L, -L), 1), cl.Dirichlet((L, -L, -L), 2),
           cl.Dirichlet((-L, L, -L), 2)]
    return cl.Scene(mesh, cl.Material(1.0, 0.3), cracks=[crack], dirichlet=sup,
                    tractions=[cl.Traction("zmax", (0.0, 0.0, 1.0)), cl.Traction("zmin", (0.0, 0.0, -1.0))],
                    options=cl.Options(enrichment="vector", radius=2.5 * h))


class _Timed(SurfaceGrowth):
    """SurfaceGrowth with the advance step timed on its own."""

    def __init__(self, *a, **k):
        super().__init__(*a, **k)
        self.advance_seconds: list[float] = []

    def advance(self, m):
        t0 = time.perf_counter()
        super().advance(m)
        self.advance_seconds.append(time.perf_counter() - t0)


def measure(n: int, steps: int, repeats: int) -> dict:
    scene = scene_for(n, steps)
    singles = []

    def single_runs(count: int):
        nonlocal sol
        for _ in range(count):
            t0 = time.perf_counter()
            sol = cl.solve(scene)
            sol.stress_intensity_factors(None)
            singles.append(time.perf_counter() - t0)
    sol = None
    # Half the single runs before the growth and half after: a drift of the machine's load weighs on both.
    single_runs(repeats - repeats // 2)
    run = _Timed(scene_for(n, steps), cl.Growth(da=DA, steps=steps, paris_C=1.0, paris_m=3.0, R=0.0), False, None)
    res = run.run()
    single_runs(repeats // 2)
    per_step = res.step_times[1:-1]  # (the last entry is the final measure without an advance)
    t_single, t_step = statistics.median(singles), statistics.median(per_step)
    return {"n": n, "h_front": 1.0 / n, "ndofs": sol.model.num_dofs, "t_single_run": t_single, "t_step": t_step,
            "ratio": t_step / t_single, "t_first_step": res.step_times[0], "steps": steps,
            "solves_per_step": res.step_solves, "t_advance_median": statistics.median(run.advance_seconds),
            "single_runs": singles, "step_seconds": res.step_times, "advance_seconds": run.advance_seconds}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, nargs="+", default=[8], help="elements per crack radius at the front")
    ap.add_argument("--steps", type=int, default=5)
    ap.add_argument("--repeats", type=int, default=4)
    ap.add_argument("--json", type=pathlib.Path)
    args = ap.parse_args(argv)
    rows = [measure(n, args.steps, args.repeats) for n in args.n]
    out = {"machine": platform.node(), "python": platform.python_version(),
           "note": f"demos/bench_growth_3d.py --n {' '.join(map(str, args.n))} --steps {args.steps} --repeats "
                   f"{args.repeats}; 2 cores shared with other jobs (timings move by 20-30 % run to run)",
           "rows": rows}
    if args.json is not None:
        write_json(args.json, out)
    return out


if __name__ == "__main__":
    for r in main()["rows"]:
        print(f"n = {r['n']}: {r['ndofs']} dofs, single run {r['t_single_run']:.2f} s, step {r['t_step']:.2f} s "
              f"(ratio {r['ratio']:.2f}; front update {r['t_advance_median']:.3f} s), solves per step "
              f"{r['solves_per_step']}")
