"""Penny-shaped crack under remote tension (issue 27): the 3D X-FEM core
against Sneddon's exact opening.

A crack of radius a = 1 in the plane z = 0 at the centre of a box of side
20 a, tension sigma = 1 on the faces z = +-10 (E = 1, nu = 0.3), rigid
motions held by point supports. Sneddon's opening in an infinite body:
[[u_z]] = 8 (1 - nu^2) sigma sqrt(a^2 - r^2) / (pi E); opened volume
V = 16 (1 - nu^2) sigma a^3 / (3 E).

Meshes: h_front = a/10, a/14, a/20 (a/28 with --full) at the front, twice
that over the crack's surface, sizes growing by 0.07 x (a/20) / h_front per
unit distance up to 2 (a family of similar meshes near the crack); vector
front functions within 0.25 a of the front on every mesh (geometric
enrichment: 2.5 h_front at a/10, 5 at a/20); the iterative solver.

Per mesh: the opening against Sneddon, L2 over the crack (cod_l2_rel) and
pointwise away from the front (r <= 0.9 a: cod_max_rel, the largest
relative error there); the energy-norm error. For this load the strain
energy of any discrete solution with the uniform field in its space is
U_h = U_0 + sigma V_h / 2 (Betti with the uniform field), so ||u - u_h||^2 =
2 (U - U_h) = sigma (V - V_h): the opened volume's deficit is the squared
energy error. energy_error is sqrt((V - V_h) / V) against Sneddon's V (the
box's finite size neglected); energy_error_extrapolated uses the V that
three meshes extrapolate to (Aitken), whose rate is also reported.

    /usr/bin/python3 demos/penny_crack.py --json out/penny_crack.json [--full]
"""
from __future__ import annotations

import argparse
import math
import pathlib
import sys
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

import cracklip as cl  # noqa: E402
from cracklip.exact.embedded_cracks import penny_opening  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.scene.crack_surface import EllipticalCrack  # noqa: E402
from cracklip.scene.mesh_3d import GROWTH, create_box, crack_refinements  # noqa: E402

A, E, NU, SIGMA = 1.0, 1.0, 0.3, 1.0
HALF_WIDTH = 10.0
H_FAR = 2.0
RADIUS = 0.25  # front enrichment radius / a: fixed (geometric enrichment)
DIVISIONS = (10, 14, 20)
FULL_DIVISIONS = (10, 14, 20, 28)


def exact_volume() -> float:
    return 16.0 * (1.0 - NU ** 2) * SIGMA * A ** 3 / (3.0 * E)


def penny_scene(n: int, solver: str = "iterative", enrichment: str = "vector", radius: float = RADIUS) -> cl.Scene:
    """The penny scene with h_front = a / n (module doc); radius: the front
    enrichment radius / a."""
    L = HALF_WIDTH
    h = A / n
    crack = EllipticalCrack((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), A, axis=(1.0, 0.0, 0.0), name="penny")
    mesh = create_box(-L, -L, -L, L, L, L, H_FAR,
                      fronts=crack_refinements([crack], h, H_FAR, growth=GROWTH * 20.0 / n))
    return cl.Scene(mesh, cl.Material(E, NU), cracks=[crack],
                    dirichlet=[cl.Dirichlet((-L, -L, -L)), cl.Dirichlet((L, -L, -L), 1),
                               cl.Dirichlet((L, -L, -L), 2), cl.Dirichlet((-L, L, -L), 2)],
                    tractions=[cl.Traction("zmax", (0.0, 0.0, SIGMA)), cl.Traction("zmin", (0.0, 0.0, -SIGMA))],
                    options=cl.Options(enrichment=enrichment, radius=radius * A, solver=solver))


def run(n: int, solver: str = "iterative") -> tuple[dict, dict]:
    """One mesh: its row and the opening samples (r, cod, exact)."""
    t0 = time.perf_counter()
    scene = penny_scene(n, solver)
    t_mesh = time.perf_counter() - t0
    sol = cl.solve(scene)
    op = sol.crack_opening()
    r = np.hypot(op["x"][:, 0], op["x"][:, 1])
    ex = penny_opening(r, SIGMA, A, E, NU)
    w = op["weight"]
    err = op["normal"] - ex
    away = r <= 0.9 * A
    V_h = float(np.sum(w * op["normal"]))
    V = exact_volume()
    m = sol.model
    row = {"h_front": A / n, "a_over_h": n, "ndofs": int(m.num_dofs), "enriched_dofs": int(3 * m.layout.num_enriched),
           "cells": int(m.cells.shape[0]),
           "cod_l2_rel": float(math.sqrt(np.sum(w * err ** 2) / np.sum(w * ex ** 2))),
           "cod_max_rel": float(np.max(np.abs(err[away]) / ex[away])),
           "cod_max_abs_rel": float(np.max(np.abs(err[away])) / ex.max()),
           "cod_centre_rel": float(err[np.argmin(r)] / ex[np.argmin(r)]),
           "max_sliding_rel": float(np.abs(op["tangential"]).max() / ex.max()),
           "opened_volume": V_h, "opened_volume_exact": V,
           "energy_error": float(math.sqrt(max(V - V_h, 0.0) / V)),
           "t_mesh": t_mesh, "t_solve": float(sol.timings["solve"]),
           "t_assemble": float(sol.timings["assemble_standard"] + sol.timings["assemble_enriched"]),
           "t_total": float(sol.timings["total"]), "solver": sol.solver["solver"]}
    return row, {"r": r, "cod": op["normal"], "exact": ex}


def aitken(h: list[float], V: list[float]) -> tuple[float, float] | None:
    """The limit V and rate p of V_h = V - C h^(2 p) through the last three
    meshes (None if the differences do not shrink monotonically)."""
    (h1, h2, h3), (v1, v2, v3) = h[-3:], V[-3:]
    d1, d2 = v2 - v1, v3 - v2
    if not (d1 > 0.0 and d2 > 0.0 and d2 < d1):
        return None
    lo, hi = 1e-3, 4.0  # solve (h1^q - h2^q) / (h2^q - h3^q) = d1 / d2 for q = 2 p
    f = lambda q: (h1 ** q - h2 ** q) / (h2 ** q - h3 ** q) - d1 / d2  # noqa: E731
    if f(lo) * f(hi) > 0.0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(lo) * f(mid) > 0.0 else (lo, mid)
    q = 0.5 * (lo + hi)
    C = d2 / (h2 ** q - h3 ** q)
    return v3 + C * h3 ** q, q / 2.0


def plot(rows: list[dict], profile: dict, path: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    o = np.argsort(profile["r"])
    a1.plot(profile["r"][o], profile["exact"][o], "k-", label="Sneddon")
    a1.plot(profile["r"][o], profile["cod"][o], ".", ms=1.5, label=f"cracklip, a/h = {rows[-1]['a_over_h']}")
    a1.set_xlabel("r / a")
    a1.set_ylabel("opening [[u_z]] E / (sigma a)")
    a1.legend()
    h = np.array([r["h_front"] for r in rows])
    for key, label in (("cod_l2_rel", "opening, L2"), ("cod_max_rel", "opening, max (r <= 0.9 a)"),
                       ("energy_error", "energy norm")):
        a2.loglog(h, [r[key] for r in rows], "o-", label=label)
    a2.loglog(h, 0.5 * rows[-1]["energy_error"] * h / h[-1], "k:", label="slope 1")
    a2.set_xlabel("h at the front / a")
    a2.set_ylabel("relative error")
    a2.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/penny_crack.json"))
    ap.add_argument("--full", action="store_true", help=f"meshes a/h = {FULL_DIVISIONS} (default {DIVISIONS})")
    ap.add_argument("--divisions", type=int, nargs="+", help="a/h at the front of each mesh")
    ap.add_argument("--solver", default="iterative", choices=("iterative", "direct", "auto"))
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    divisions = args.divisions or (FULL_DIVISIONS if args.full else DIVISIONS)
    rows, profile = [], None
    for n in divisions:
        row, profile = run(n, args.solver)
        rows.append(row)
        if not args.quiet:
            print(f"a/h = {n}: {row['ndofs']} dofs, opening L2 {100 * row['cod_l2_rel']:.2f} %, max "
                  f"{100 * row['cod_max_rel']:.2f} %, energy error {100 * row['energy_error']:.2f} %, solve "
                  f"{row['t_solve']:.1f} s", flush=True)
    out = {"case": "penny crack, remote tension", "a": A, "E": E, "nu": NU, "sigma": SIGMA,
           "box_half_width": HALF_WIDTH, "rows": rows}
    h = [r["h_front"] for r in rows]
    if len(rows) >= 2:
        e = [r["energy_error"] for r in rows]
        out["energy_rate"] = math.log(e[-2] / e[-1]) / math.log(h[-2] / h[-1])
        c = [r["cod_l2_rel"] for r in rows]
        out["cod_l2_rate"] = math.log(c[-2] / c[-1]) / math.log(h[-2] / h[-1])
    if len(rows) >= 3:
        fit = aitken(h, [r["opened_volume"] for r in rows])
        if fit is not None:
            V_ref, p = fit
            out["opened_volume_extrapolated"] = V_ref
            out["energy_rate_extrapolated"] = p
            for r in rows:
                r["energy_error_extrapolated"] = float(math.sqrt(max(V_ref - r["opened_volume"], 0.0) / V_ref))
    args.json.parent.mkdir(parents=True, exist_ok=True)
    write_json(args.json, out)
    plot(rows, profile, args.json.with_suffix(".png"))
    if not args.quiet:
        print(f"energy-error rate {out.get('energy_rate', float('nan')):.2f} (last two meshes), "
              f"{out.get('energy_rate_extrapolated', float('nan')):.2f} (three meshes, Aitken); wrote {args.json}")
    return out


if __name__ == "__main__":
    main()
