"""Closed inclined crack with frictionless sliding (issue 4): an interior crack
of half-length a = 0.3 at 30 degrees in the square [-1, 1]^2 under the uniform
stress sigma_xx = 0, sigma_yy = -0.01, sigma_xy = 0.004 applied as tractions on
its sides: the lips are pressed together (sigma_nn < 0) and sheared, so they
slide: K_I ~ 0 and K_II != 0 (infinite-plate value tau_nt sqrt(pi a)).

    /usr/bin/python3 demos/sliding_crack.py --json results/sliding_crack.json
"""
from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

import cracklip as cl  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402

HALF_LENGTH = 0.3
ANGLE = np.radians(30.0)
SIGMA = np.array([[0.0, 0.004], [0.004, -0.01]])


def direction() -> np.ndarray:
    return np.array([np.cos(ANGLE), np.sin(ANGLE)])


def shear_on_crack() -> float:
    t = direction()
    return float(t @ SIGMA @ np.array([-t[1], t[0]]))


def run(n: int, sif_radius: float = 0.1) -> dict:
    t = direction()
    mesh = cl.create_square(2.0 / n)
    c0 = np.array(mesh.nearest_node([-1, -1]))
    c1 = np.array(mesh.nearest_node([1, -1]))
    normals = {"left": (-1, 0), "right": (1, 0), "bottom": (0, -1), "top": (0, 1)}
    scene = cl.Scene(mesh, cl.Material(1.0, 0.3), cracks=[cl.Crack([-HALF_LENGTH * t, HALF_LENGTH * t])],
                     dirichlet=[cl.Dirichlet(tuple(c0), None, 0.0), cl.Dirichlet(tuple(c1), 1, 0.0)],
                     tractions=[cl.Traction(k, tuple(SIGMA @ np.array(v, float))) for k, v in normals.items()],
                     options=cl.Options(enrichment="vector", radius=0.1, contact="unilateral"))
    sol = cl.solve(scene)
    sifs = sol.stress_intensity_factors(0, radius=sif_radius)
    return {"n": n, "ndofs": sol.model.num_dofs, "all_closed": bool(sol.contact["active"].all()),
            "active_set_iterations": sol.contact["iterations"],
            "tips": [{"tip": s["tip"], "K_I": s["K_I"], "K_II": s["K_II"]} for s in sifs]}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ns", type=int, nargs="+", default=[20, 40, 80])
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/sliding_crack.json"))
    args = ap.parse_args(argv)
    rows = [run(n) for n in args.ns]
    res = {"K_II_infinite_plate": shear_on_crack() * np.sqrt(np.pi * HALF_LENGTH), "rows": rows}
    write_json(args.json, res)
    for r in rows:
        print(f"n={r['n']}: " + ", ".join(f"K_I={s['K_I']:.2e} K_II={s['K_II']:.6f}" for s in r["tips"]),
              file=sys.stderr)
    return res


if __name__ == "__main__":
    main()
