"""How far the lips of a partly closed 3D crack overlap, per mesh (issue 36,
acceptance 3): the shipped scenes demos/scenes/bending_crack_closure.toml
(a through crack across the neutral axis of a bent beam) and
corner_crack_closure.toml (a corner crack at a hole under compression and a
lip pressure) run at several sizes tip_h = crack_h (a local size along the
crack's edge on the bore scaled alike: a third of tip_h).

The overlap is results.json's interpenetration_max: the largest -[[u]].n
over the lip facets' vertices and the lip samples (crack_surface.vtu's
points), against gap_max, the largest opening there. Contact holds
[[u]].n >= 0 in the mean over each multiplier group (the stable P1- space),
not point by point, so the lips can overlap inside a closed group; where
the largest overlap sits is reported (its point, its distance to the bore
for the corner crack, and the pressure there).

One row per scene and size: scene, tip_h, dofs, overlap, gap_max,
overlap_pct, at (x, y, z), pressure_at, pressure_min, pressure_max,
closed_area, K_I (along the front), iterations, t_run.

    /usr/bin/python3 demos/closure_overlap_3d.py --json out/closure_overlap_3d.json [--scenes bending ...] [--sizes ...]
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

import meshio  # noqa: E402

from cracklip import cli  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402

SCENES = pathlib.Path(__file__).resolve().parent / "scenes"

#: scene name -> (file, default sizes tip_h = crack_h, extra settings per size)
RUNS = {
    "bending": ("bending_crack_closure.toml", [0.5, 0.25, 0.15, 0.125], lambda h: []),
    "corner": ("corner_crack_closure.toml", [0.3, 0.15, 0.1], lambda h: [f"mesh.refine[0].h={h / 3:.6g}"]),
}


def run(scene: str, h: float, out: pathlib.Path) -> dict:
    """One run of a scene at tip_h = crack_h = h: its row."""
    name, _, extra = RUNS[scene]
    sets = [f"mesh.tip_h={h}", f"mesh.crack_h={h}", "outputs.error_estimate=false", "outputs.png=false", *extra(h)]
    t0 = time.perf_counter()
    assert cli.main(["run", str(SCENES / name), "--out", str(out), "--quiet",
                     *[a for s in sets for a in ("--set", s)]]) == 0
    t_run = time.perf_counter() - t0
    res = json.loads((out / "results.json").read_text())
    c = res["cracks"][0]
    surf = meshio.read(out / "crack_surface.vtu")
    gap, p, x = surf.point_data["gap"], surf.point_data["pressure"], surf.points
    k = int(np.argmin(gap))
    row = {"scene": scene, "tip_h": h, "dofs": res["solution"]["dofs"], "overlap": c["interpenetration_max"],
           "gap_max": c["gap_max"], "overlap_pct": 100.0 * c["interpenetration_max"] / c["gap_max"],
           "at": x[k].tolist(), "pressure_at": float(p[k]), "pressure_min": c["pressure"]["min"],
           "pressure_max": c["pressure"]["max"], "closed_area": c["closed_area"],
           "K_I": [r["K_I"] for r in res["sifs"]], "free_surface": [r["free_surface"] for r in res["sifs"]],
           "iterations": res["contact"]["iterations"], "t_run": t_run}
    if scene == "corner":
        row["at_bore_distance"] = float(np.hypot(x[k, 0], x[k, 1]) - 4.0)
    return row


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", type=pathlib.Path, required=True)
    ap.add_argument("--scenes", nargs="+", default=list(RUNS), choices=list(RUNS))
    ap.add_argument("--sizes", nargs="+", type=float, help="tip_h = crack_h values (default: per scene)")
    a = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes:
            for h in a.sizes or RUNS[scene][1]:
                row = run(scene, h, pathlib.Path(tmp) / f"{scene}_{h}")
                rows.append(row)
                print(f"{scene} tip_h {h}: {row['dofs']} dofs, overlap {row['overlap_pct']:.2f} % of the opening "
                      f"at {np.round(row['at'], 3).tolist()} (pressure there {row['pressure_at']:.3g}), "
                      f"pressure {row['pressure_min']:.3g} .. {row['pressure_max']:.4g}, {row['t_run']:.0f} s",
                      flush=True)
    write_json(a.json, {"rows": rows})
    return 0


if __name__ == "__main__":
    sys.exit(main())
