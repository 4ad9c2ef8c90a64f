"""Crack-lip contact and Coulomb friction in 3D (issue 36): the closed penny
crack under inclined compression against its exact solution.

A penny crack of radius a = 1 in the plane z = 0 at the centre of a box of
half-width 10 a (E = 1, nu = 0.3), the box's faces loaded by the uniform
stress -sigma e_L e_L (uniaxial compression sigma = 1 along e_L = (sin
beta, 0, cos beta), at beta to the crack's normal), rigid motions held by
point supports that take no load; contact on the lips (bilateral: the
crack stays closed), Coulomb friction mu. Exact (cracklip.exact.
closed_penny): the pressure p = sigma cos^2 beta everywhere, K_I = 0; the
shear tau = sigma sin beta cos beta along t = -e_x slips the whole crack
when tau > mu p, with K_II = 4 tau_eff sqrt(a/pi) cos(omega) / (2 - nu),
K_III = 4 (1 - nu) tau_eff sqrt(a/pi) sin(omega) / (2 - nu), tau_eff =
tau - mu p, omega the front angle from t; it sticks (K_II = K_III = 0)
when tau <= mu p (beta = 30 degrees with mu = 0.6: tan 30 = 0.577).

Meshes as demos/front_sifs.py's (mesh_3d.create_box + crack_refinements:
h_front = a / n along the front, twice that over the crack, growing away
from it); vector front functions within 0.25 a of the front.

Per case and mesh, a row (the issue's keys first): case, beta_deg, mu,
ndofs, K_I_rel (the largest |K_I| along the front over the frictionless K_II
amplitude A0 = 4 tau sqrt(a/pi) / (2 - nu)), K_II_err, K_III_err (the
largest error along the front over A0), pressure_err (the largest relative
error of the contact pressure at the lip quadrature points outside the
front cells), then pressure_rms, pressure_err_multipliers (the same over
the reduced multipliers whose groups lie off the front cells),
slip_max (the largest slip, for the stick case), the friction states'
counts, iterations, size_over_h, h_front, t_solve, t_sif. Per case,
<case>.csv and <case>.png (K along the front against the exact values,
finest mesh) next to the JSON; --json FILE writes {"rows": [...], ...}.

    /usr/bin/python3 demos/contact_3d.py --json out/contact_3d.json [--full] [--cases ...] [--sizes 6 10]
"""
from __future__ import annotations

import argparse
import csv
import math
import pathlib
import sys
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

import cracklip as cl  # noqa: E402
from cracklip.exact.closed_penny import closed_penny_inclined  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.scene.crack_surface import EllipticalCrack  # noqa: E402
from cracklip.scene.mesh_3d import GROWTH, create_box, crack_refinements  # noqa: E402

A, E, NU, SIGMA = 1.0, 1.0, 0.3, 1.0
HALF_WIDTH = 10.0
H_FAR = 2.0
RADIUS = 0.25

#: The cases: beta (degrees), mu.
CASES = {"beta30_mu0": (30.0, 0.0), "beta30_mu0.3": (30.0, 0.3), "beta45_mu0": (45.0, 0.0),
         "beta45_mu0.3": (45.0, 0.3), "beta30_stick": (30.0, 0.6)}

#: a / h_front of the default run (the main job, the demo test) and of --full.
SIZES, FULL_SIZES = (6,), (10, 14, 20)

#: The crack's normal and the shear direction t on its + face.
NORMAL = np.array([0.0, 0.0, 1.0])
SHEAR_DIRECTION = np.array([-1.0, 0.0, 0.0])


def remote_stress(beta_deg: float) -> np.ndarray:
    """-sigma e_L e_L, e_L at beta from the crack's normal in the x-z plane."""
    b = math.radians(beta_deg)
    e = np.array([math.sin(b), 0.0, math.cos(b)])
    return -SIGMA * np.outer(e, e)


FACES = {"xmin": (-1, 0, 0), "xmax": (1, 0, 0), "ymin": (0, -1, 0), "ymax": (0, 1, 0), "zmin": (0, 0, -1),
         "zmax": (0, 0, 1)}


def build(case: str, n: int, **options) -> cl.Scene:
    """The scene of a case with h_front = a / n; options: Options overrides."""
    beta, mu = CASES[case]
    crack = EllipticalCrack((0.0, 0.0, 0.0), tuple(NORMAL), A, axis=(1.0, 0.0, 0.0), name="penny")
    L = HALF_WIDTH
    h = A / n
    mesh = create_box(-L, -L, -L, L, L, L, H_FAR, fronts=crack_refinements([crack], h, H_FAR, growth=GROWTH * 20.0 * h))
    S = remote_stress(beta)
    tractions = [cl.Traction(face, tuple(S @ np.array(nv, float))) for face, nv in FACES.items()]
    supports = [cl.Dirichlet((-L, -L, -L)), cl.Dirichlet((L, -L, -L), 1), cl.Dirichlet((L, -L, -L), 2),
                cl.Dirichlet((-L, L, -L), 2)]
    opts = {"enrichment": "vector", "radius": RADIUS * A, "contact": "bilateral", "friction": mu, **options}
    return cl.Scene(mesh, cl.Material(E, NU), cracks=[crack], dirichlet=supports, tractions=tractions,
                    options=cl.Options(**opts))


def front_angles(rows: list[dict]) -> np.ndarray:
    """omega of each SIF point: the angle of the shear direction t in the
    point's frame (t = cos omega e1 + sin omega e3)."""
    fr = np.array([r["frame"] for r in rows])
    return np.arctan2(fr[:, 2] @ SHEAR_DIRECTION, fr[:, 0] @ SHEAR_DIRECTION)


def pressure_errors(sol: cl.Solution, p: float) -> dict:
    """The pressure's largest and RMS relative error at the lip quadrature
    points outside the front cells, and the largest over the reduced
    multipliers none of whose members is a front cell's P0 or a node of a
    front cell."""
    smp = sol.lip_samples(0)
    cm = sol.model.cracks[0]
    front_cell = cm.cell_class == cm.CELL_CLASSES["front"]
    off = ~front_cell[smp["cell"]]
    e = np.abs(smp["pressure"][off] - p) / p
    cs = sol.contact["system"]
    space = cs.space
    node = np.asarray(space.full_node)
    front_nodes = np.zeros(sol.model.x.shape[0], dtype=bool)
    front_nodes[sol.model.cells[front_cell].ravel()] = True
    touch = (node < 0) | front_nodes[np.maximum(node, 0)]
    group_touch = np.zeros(cs.num_multipliers, dtype=bool)
    np.logical_or.at(group_touch, np.asarray(space.full_to_reduced), touch)
    lam = -sol.contact["lambda"]
    em = np.abs(lam[~group_touch] - p) / p
    return {"pressure_err": float(e.max()), "pressure_rms": float(np.sqrt(np.mean(e ** 2))),
            "pressure_err_multipliers": float(em.max(initial=0.0)), "multipliers_off_front": int(em.size)}


def run(case: str, n: int, **options) -> tuple[dict, dict]:
    """One case on one mesh: its row and the front profile."""
    beta, mu = CASES[case]
    ex = closed_penny_inclined(SIGMA, math.radians(beta), mu, A, NU)
    A0 = 4.0 * ex.tau * math.sqrt(A / math.pi) / (2.0 - NU)   # the frictionless K_II amplitude
    t0 = time.perf_counter()
    scene = build(case, n, **options)
    t_mesh = time.perf_counter() - t0
    t0 = time.perf_counter()
    sol = cl.solve(scene)
    t_solve = time.perf_counter() - t0
    t0 = time.perf_counter()
    rows = sol.stress_intensity_factors(0)
    t_sif = time.perf_counter() - t0
    K = np.array([[r["K_I"], r["K_II"], r["K_III"]] for r in rows])
    omega = front_angles(rows)
    Kx = np.column_stack(ex.k(omega))
    err = np.abs(K - Kx) / A0
    slip = sol.lip_samples(0)["slip"]
    c = sol.contact
    states = {name: int(np.count_nonzero(c["state"] == code)) for code, name in ((0, "open"), (1, "stick"),
                                                                                 (2, "slip"))} if "state" in c else None
    row = {"case": case, "beta_deg": beta, "mu": mu, "ndofs": int(sol.model.num_dofs),
           "K_I_rel": float(np.abs(K[:, 0]).max() / A0), "K_II_err": float(err[:, 1].max()),
           "K_III_err": float(err[:, 2].max()), **pressure_errors(sol, ex.p),
           "state_exact": ex.state, "slip_max": float(np.linalg.norm(slip, axis=1).max()), "states": states,
           "iterations": int(c.get("iterations", 1)), "multipliers": int(c["system"].num_multipliers),
           "size_over_h": n, "h_front": A / n, "front_points": len(rows), "amplitude": A0,
           "t_mesh": t_mesh, "t_solve": t_solve, "t_sif": t_sif}
    return row, {"omega": omega, "K": K, "exact": Kx, "rows": rows, "amplitude": A0}


def write_case(case: str, row: dict, profile: dict, folder: pathlib.Path) -> None:
    """<case>.csv and <case>.png: K along the front against the exact values."""
    folder.mkdir(parents=True, exist_ok=True)
    deg = np.degrees(profile["omega"])
    with (folder / f"{case}.csv").open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["point", "omega_deg", "K_I", "K_II", "K_III", "K_I_exact", "K_II_exact", "K_III_exact"])
        for i, r in enumerate(profile["rows"]):
            w.writerow([r["point"], deg[i], *profile["K"][i], *profile["exact"][i]])
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4))
    o = np.argsort(deg)
    A0 = profile["amplitude"]
    for m, (name, col) in enumerate((("K_I", "C0"), ("K_II", "C1"), ("K_III", "C2"))):
        ax.plot(deg[o], profile["exact"][o, m] / A0, "-", color=col, lw=1, label=f"{name} exact")
        ax.plot(deg[o], profile["K"][o, m] / A0, "o", color=col, ms=3, label=f"{name} cracklip")
    ax.axhline(0.0, color="0.7", lw=0.5)
    ax.set_xlabel("front angle omega from the shear direction [deg]")
    ax.set_ylabel("K / A0 (A0 = frictionless K_II amplitude)")
    ax.set_title(f"{case}: a/h = {row['size_over_h']}, {row['ndofs']} dofs; errors / A0: K_I {100 * row['K_I_rel']:.2f} "
                 f"%, K_II {100 * row['K_II_err']:.2f} %, K_III {100 * row['K_III_err']:.2f} %", fontsize=8)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(folder / f"{case}.png", dpi=110)
    plt.close(fig)


def markdown(out: dict) -> str:
    """The rows as a markdown table."""
    lines = ["| case | a/h | dofs | K_I / A0 | K_II err | K_III err | pressure err (max, rms) | iterations | solve s |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in out["rows"]:
        dofs = f"{r['ndofs']:,}".replace(",", " ")
        lines.append(f"| {r['case']} | {r['size_over_h']} | {dofs} | {100 * r['K_I_rel']:.2f} % | "
                     f"{100 * r['K_II_err']:.2f} % | {100 * r['K_III_err']:.2f} % | {100 * r['pressure_err']:.2f} %, "
                     f"{100 * r['pressure_rms']:.2f} % | {r['iterations']} | {r['t_solve']:.1f} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/contact_3d.json"))
    ap.add_argument("--full", action="store_true", help=f"the meshes a/h = {FULL_SIZES}")
    ap.add_argument("--sizes", type=int, nargs="+", help="a / h_front of the meshes (overrides --full)")
    ap.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    sizes = args.sizes or (FULL_SIZES if args.full else SIZES)
    rows = []
    folder = args.json.parent / args.json.stem
    for case in args.cases:
        last = profile = None
        for n in sizes:
            row, profile = run(case, n)
            rows.append(row)
            last = row
            if not args.quiet:
                print(f"{case:14s} a/h = {n:3d} {row['ndofs']:8d} dofs  K_I {100 * row['K_I_rel']:.3f} %  K_II "
                      f"{100 * row['K_II_err']:.3f} %  K_III {100 * row['K_III_err']:.3f} %  pressure "
                      f"{100 * row['pressure_err']:.2f} % (rms {100 * row['pressure_rms']:.2f} %)  "
                      f"{row['iterations']} it, solve {row['t_solve']:.1f} s, K {row['t_sif']:.1f} s", flush=True)
        write_case(case, last, profile, folder)
    out = {"E": E, "nu": NU, "sigma": SIGMA, "a": A, "half_width": HALF_WIDTH, "sizes": list(sizes), "rows": rows}
    args.json.parent.mkdir(parents=True, exist_ok=True)
    write_json(args.json, out)
    if not args.quiet:
        print(markdown(out))
    return out


if __name__ == "__main__":
    main()
