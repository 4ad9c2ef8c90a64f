"""Cracked block under uniform pressure (paper section 5.1, issue 4).

Square [-1, 1]^2, edge crack on y = 0 from x = -1 to the tip at x = -0.6,
pressure 0.01 on the top edge, E = 1, nu = 0.3. With the bottom edge on
vertical rollers and one node fixed in x (default) the exact field is uniform
sigma_yy = -0.01: the crack stays closed, the contact pressure is 0.01 all
along it and K_I = K_II = 0. `--supports corners` is the paper's support
(two bottom corners fixed), which has no closed-form answer.

    /usr/bin/python3 demos/block_uniform_pressure.py --n 42 --enrichment vector --json out.json
    /usr/bin/python3 demos/block_uniform_pressure.py --figures --out results/block
"""
from __future__ import annotations

import argparse
import pathlib
import sys
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

import cracklip as cl  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.contact.infsup import inf_sup_constant  # noqa: E402
from cracklip.io.scene_file import add_option_arguments  # noqa: E402

PRESSURE = 0.01
TIP_X = -0.6


def scene_for(n: int = 42, enrichment: str = "vector", radius: float = 0.2, multipliers: str = "stable",
              quadrature: str = "collapsed", degree: int = 5, contact: str = "bilateral",
              supports: str = "rollers") -> cl.Scene:
    mesh = cl.create_square(2.0 / n)
    if supports == "rollers":
        pin = np.array(mesh.nearest_node([1.0, -1.0]))
        dirichlet = [cl.Dirichlet("bottom", 1, 0.0), cl.Dirichlet(tuple(pin), 0, 0.0)]
    else:
        c0 = np.array(mesh.nearest_node([-1.0, -1.0]))
        c1 = np.array(mesh.nearest_node([1.0, -1.0]))
        dirichlet = [cl.Dirichlet(tuple(c0), None, 0.0), cl.Dirichlet(tuple(c1), None, 0.0)]
    return cl.Scene(mesh, cl.Material(1.0, 0.3),
                    cracks=[cl.Crack([[-1.5, 0.0], [TIP_X, 0.0]], name="edge crack")],
                    dirichlet=dirichlet, tractions=[cl.Traction("top", (0.0, -PRESSURE))],
                    options=cl.Options(enrichment=enrichment, radius=radius, multipliers=multipliers,
                                       quadrature=quadrature, quadrature_degree=degree, contact=contact))


def run(**kw) -> dict:
    t0 = time.perf_counter()
    scene = scene_for(**kw)
    t_mesh = time.perf_counter() - t0
    sol = cl.solve(scene)
    cp = sol.contact_pressure(0)
    K = sol.stress_intensity_factors(0)[0]
    return {**{k: v for k, v in kw.items()}, "ndofs": sol.model.num_dofs,
            "n_multipliers": sol.contact["system"].num_multipliers,
            "pressure": np.c_[cp["x"][:, 0], cp["pressure"]].tolist(),
            "gap_max": float(np.abs(cp["gap"]).max()),
            "pressure_max_rel_dev": float(np.abs(cp["pressure"] - PRESSURE).max() / PRESSURE),
            "K_I": K["K_I"], "K_II": K["K_II"], "K_ref": PRESSURE * np.sqrt(np.pi * 0.4),
            "active_set_iterations": sol.contact["iterations"],
            "timings": {"mesh": t_mesh, **sol.timings}}


def inf_sup_table(enrichment: str, multipliers: str, ns=(10, 20, 40, 80)) -> list[list[float]]:
    rows = []
    for n in ns:
        model = cl.create_model(scene_for(n, enrichment=enrichment, multipliers=multipliers))
        rows.append([2.0 / n, inf_sup_constant(model)])
    return rows


def figures(out: pathlib.Path, n: int) -> dict:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = {}
    fig, ax = plt.subplots(figsize=(6, 4))
    for label, kw in [("stable, vector, collapsed", dict(multipliers="stable")),
                      ("naive, vector, collapsed", dict(multipliers="naive")),
                      ("stable, vector, Gauss degree 5", dict(quadrature="gauss", degree=5)),
                      ("stable, vector, Gauss degree 20", dict(quadrature="gauss", degree=20))]:
        try:
            r = run(n=n, **kw)
        except cl.CracklipError as e:
            print(f"{label}: {e}", file=sys.stderr)
            continue
        res[label] = {"pressure_max_rel_dev": r["pressure_max_rel_dev"], "K_I": r["K_I"]}
        p = np.array(r["pressure"])
        ax.plot(p[:, 0], p[:, 1] / PRESSURE, ".-", ms=3, lw=0.8,
                label=f"{label} (max dev {r['pressure_max_rel_dev']:.1e})")
    ax.axhline(1.0, color="k", lw=0.8, ls=":", label="exact")
    ax.set_xlabel("x along the crack (length units; tip at -0.6)")
    ax.set_ylabel("contact pressure / 0.01")
    ax.set_title(f"Block under uniform pressure, n = {n}")
    ax.legend(fontsize=7)
    fig.savefig(out / "block_pressure.png", dpi=150, bbox_inches="tight")
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(5.5, 4))
    table = {}
    for label, enr, mult in [("naive (vector)", "vector", "naive"), ("stable, Heaviside only", "none", "stable"),
                             ("stable, scalar", "scalar", "stable"), ("stable, vector", "vector", "stable")]:
        rows = np.array(inf_sup_table(enr, mult))
        table[label] = rows.tolist()
        ax.loglog(rows[:, 0], rows[:, 1], "o-", label=label)
    ax.set_xticks(rows[:, 0], [f"{h:g}" for h in rows[:, 0]])
    ax.minorticks_off()
    ax.set_yticks([0.02, 0.05, 0.1, 0.2, 0.5, 1.0], ["0.02", "0.05", "0.1", "0.2", "0.5", "1"])
    ax.set_xlabel("h (length units)")
    ax.set_ylabel(r"$\sqrt{\beta_{min}}$")
    ax.set_title("Numerical inf-sup test (paper eqs. 16-17)")
    ax.legend(fontsize=8)
    fig.savefig(out / "block_inf_sup.png", dpi=150, bbox_inches="tight")
    plt.close(fig)
    res["inf_sup"] = table
    return res


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=42, help="divisions per edge (default 42)")
    add_option_arguments(ap, {"contact": ("bilateral", "unilateral")}, enrichment="vector", radius=0.2,
                         multipliers="stable", quadrature="collapsed", quadrature_degree=5, contact="bilateral")
    ap.add_argument("--supports", choices=["rollers", "corners"], default="rollers")
    ap.add_argument("--inf-sup", action="store_true", help="add inf_sup for n = 10..80")
    ap.add_argument("--figures", action="store_true", help="pressure and inf-sup PNGs")
    ap.add_argument("--out", type=pathlib.Path, default=pathlib.Path("results/block"))
    ap.add_argument("--json", type=pathlib.Path, default=None)
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    res = run(n=args.n, enrichment=args.enrichment, radius=args.radius, multipliers=args.multipliers,
              quadrature=args.quadrature, degree=args.degree, contact=args.contact, supports=args.supports)
    if args.inf_sup:
        res["inf_sup"] = inf_sup_table(args.enrichment, args.multipliers)
    if args.figures:
        res["figures"] = figures(args.out, args.n)
    print(f"n={args.n} {args.enrichment} {args.multipliers}: pressure max rel. dev "
          f"{res['pressure_max_rel_dev']:.2e}, K_I {res['K_I']:.3e}, K_II {res['K_II']:.3e}, "
          f"{res['n_multipliers']} multipliers", file=sys.stderr)
    path = args.json or args.out / "block.json"
    write_json(path, res)
    return res


if __name__ == "__main__":
    main()
