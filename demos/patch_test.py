"""Through-crack patch test (issue 2): a crack y = 0.013 cuts the square on an
unstructured mesh; left edge on rollers, one pinned node per piece, uniform
tension on the right edge. Each piece carries the exact uniform plane-strain
state; the demo reports the errors of both sides' displacement and of the
opening, and draws the deformed sub-cell mesh (magnified) and the opening.

    /usr/bin/python3 demos/patch_test.py --h 0.1 --out results/patch_test
"""
from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

import cracklip as cl  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402


def run(h: float = 0.1, yc: float = 0.013, tension: float = 0.01, E: float = 1.0,
        nu: float = 0.3) -> tuple[dict, cl.Solution]:
    md = cl.create_square(h)
    x = md.mesh.geometry.x[:, :2]
    left = np.flatnonzero(np.isclose(x[:, 0], -1.0))
    above, below = left[x[left, 1] > yc], left[x[left, 1] < yc]
    pa, pb = x[above[np.argmin(x[above, 1])]], x[below[np.argmax(x[below, 1])]]
    mat = cl.Material(E, nu)
    scene = cl.Scene(md, mat, cracks=[cl.Crack([[-1.5, yc], [1.5, yc]], name="through crack")],
                     dirichlet=[cl.Dirichlet("left", 0, 0.0), cl.Dirichlet(tuple(pa), 1, 0.0),
                                cl.Dirichlet(tuple(pb), 1, 0.0)],
                     tractions=[cl.Traction("right", (tension, 0.0))])
    sol = cl.solve(scene)
    exx = (1 - nu ** 2) / E * tension
    eyy = -nu * (1 + nu) / E * tension

    def exact(p, side):
        ypin = pa[1] if side > 0 else pb[1]
        return np.stack([exx * (p[:, 0] + 1.0), eyy * (p[:, 1] - ypin)], axis=1)

    rng = np.random.default_rng(0)
    pts = rng.uniform(-1, 1, (2000, 2))
    err = {}
    for side, name in ((1, "top"), (-1, "bottom")):
        p = pts[(pts[:, 1] - yc) * side > 0]
        e = np.abs(sol.displacement(p) - exact(p, side)).max()
        err[f"displacement_rel_error_{name}"] = float(e / np.abs(exact(p, side)).max())
    op = sol.crack_opening(0)
    jex = exact(op["x"], 1) - exact(op["x"], -1)
    err["opening_rel_error"] = float(np.abs(op["jump"] - jex).max() / np.abs(jex).max())
    energy_exact = 0.5 * tension * exx * 4.0
    result = {"h": h, "tension": tension, "ndofs": sol.model.num_dofs, "enriched_dofs": 2 * sol.model.layout.num_enriched,
              "enriched_cells": int(sol.model.layout.cells.size), **err,
              "strain_energy": sol.strain_energy(), "strain_energy_exact": energy_exact,
              "opening": op["normal"].tolist(), "opening_s": op["s"].tolist(),
              "timings": sol.timings}
    return result, sol


def plot(sol: cl.Solution, result: dict, out: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    f = sol.subcell_fields()
    pts, disp = f["points"], f["displacement"]
    scale = 0.15 / np.abs(disp).max()
    tris = (pts + scale * disp).reshape(-1, 3, 2)
    fig, ax = plt.subplots(figsize=(6, 5.5))
    piece = np.where(f["points"].reshape(-1, 3, 2)[:, :, 1].mean(axis=1) > sol.model.cracks[0].crack.points[0, 1], 1, 0)
    coll = PolyCollection(tris, array=piece, cmap="coolwarm", edgecolors="k", linewidths=0.1)
    ax.add_collection(coll)
    ax.autoscale()
    ax.set_aspect("equal")
    sxx = f["stress"][:, 0]
    ax.set_title(f"Patch test, deformed x{scale:.0f} (sub-cells; colour = piece)\n"
                 f"$\\sigma_{{xx}}$ in [{sxx.min():.6g}, {sxx.max():.6g}], exact {result['tension']:g}")
    ax.set_xlabel("x (length units)")
    ax.set_ylabel("y (length units)")
    p1 = out / "patch_test_deformed.png"
    fig.savefig(p1, dpi=150, bbox_inches="tight")
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(result["opening_s"], result["opening"], "o", ms=3, label="cracklip [[u]].n")
    ax.set_xlabel("position along the crack, x (length units)")
    ax.set_ylabel("opening [[u]].n (length units)")
    ax.set_title(f"opening; max rel. error {result['opening_rel_error']:.1e}")
    ax.legend()
    p2 = out / "patch_test_opening.png"
    fig.savefig(p2, dpi=150, bbox_inches="tight")
    plt.close(fig)
    return [p1, p2]


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--h", type=float, default=0.1, help="mesh size (default 0.1)")
    ap.add_argument("--out", type=pathlib.Path, default=pathlib.Path("results/patch_test"))
    ap.add_argument("--json", type=pathlib.Path, default=None, help="JSON output (default OUT/patch_test.json)")
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    result, sol = run(args.h)
    path = args.json or args.out / "patch_test.json"
    write_json(path, result)
    cl.write_vtu(sol, args.out / "patch_test.vtu")
    result["files"] = [str(path), str(args.out / "patch_test.vtu")]
    if not args.no_plots:
        result["files"] += [str(p) for p in plot(sol, result, args.out)]
    print(f"patch test h={args.h}: opening rel. error {result['opening_rel_error']:.2e}, "
          f"displacement rel. errors {result['displacement_rel_error_top']:.2e} / "
          f"{result['displacement_rel_error_bottom']:.2e}", file=sys.stderr)
    return result


if __name__ == "__main__":
    main()
