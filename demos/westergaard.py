"""Westergaard / Williams crack-tip check (issue 3): square [-1, 1]^2, edge crack
from the left edge to the tip at the centre (optionally inclined), the exact
Williams field (mode I, II or mixed) imposed on the whole outer boundary. Reports
the energy-norm error, K_I and K_II by the interaction integral against the
exact values, the 1-norm condition number (raw and Jacobi-scaled) and timings.

    /usr/bin/python3 demos/westergaard.py --n 40 --enrichment vector --json out.json
    /usr/bin/python3 demos/westergaard.py --sweep --out results/westergaard
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
from cracklip.io.scene_file import add_option_arguments  # noqa: E402
from cracklip.exact.williams import WilliamsField  # noqa: E402

MODES = {"I": (1.0, 0.0), "II": (0.0, 1.0), "mixed": (1.0, 1.0)}


def scene_for(n: int, enrichment: str = "vector", radius: float = 0.2, quadrature: str = "collapsed",
              degree: int = 5, mode: str = "I", angle: float = 0.0, blending: str = "corrected",
              E: float = 1.0, nu: float = 0.3, rescale: str = "none") -> tuple[cl.Scene, WilliamsField]:
    """The Westergaard scene on [-1, 1]^2 with n divisions per side (crack
    tip at the origin, inclined by angle degrees) and its exact field."""
    K_I, K_II = MODES[mode]
    mat = cl.Material(E, nu)
    a = np.radians(angle)
    e1 = np.array([np.cos(a), np.sin(a)])
    exact = WilliamsField(mat, K_I=K_I, K_II=K_II, tip=(0.0, 0.0), e1=tuple(e1))
    scene = cl.Scene(
        cl.create_square(2.0 / n), mat, cracks=[cl.Crack([-3.0 * e1, [0.0, 0.0]], name="edge crack")],
        dirichlet=[cl.Dirichlet(side, None, lambda p, s: exact.displacement(p, s))
                   for side in ("left", "right", "bottom", "top")],
        options=cl.Options(enrichment=enrichment, radius=radius, quadrature=quadrature,
                           quadrature_degree=degree, blending=blending, rescale=rescale))
    return scene, exact


def run(n: int = 20, enrichment: str = "vector", radius: float = 0.2, quadrature: str = "collapsed",
        degree: int = 5, mode: str = "I", angle: float | None = None, blending: str = "corrected",
        sif_radius: float | None = None, condition: bool = True, E: float = 1.0, nu: float = 0.3,
        rescale: str = "none") -> dict:
    """One Westergaard solve; angle in degrees (default 0, or 30 for mixed)."""
    if angle is None:
        angle = 30.0 if mode == "mixed" else 0.0
    K_I, K_II = MODES[mode]
    t0 = time.perf_counter()
    scene, exact = scene_for(n, enrichment, radius, quadrature, degree, mode, angle, blending, E, nu, rescale)
    t_mesh = time.perf_counter() - t0
    sol = cl.solve(scene, condition_number=condition)
    t0 = time.perf_counter()
    err_abs, err_rel = sol.energy_error(lambda p, s: exact.gradient(p, s))
    t_err = time.perf_counter() - t0
    t0 = time.perf_counter()
    sif = sol.stress_intensity_factors(0, radius=sif_radius)[0]
    t_sif = time.perf_counter() - t0
    return {"n": n, "h": 2.0 / n, "mean_edge": sol.model.h, "ndofs": sol.model.num_dofs,
            "enriched_dofs": 2 * sol.model.layout.num_enriched, "enrichment": enrichment,
            "blending": blending, "radius": radius, "quadrature": quadrature, "degree": degree,
            "mode": mode, "angle_deg": angle,
            "energy_error_abs": err_abs, "energy_error_rel": err_rel,
            "K_I": sif["K_I"], "K_II": sif["K_II"], "K_I_exact": K_I, "K_II_exact": K_II,
            "sif_radius": sif["radius"],
            "cond_1norm": sol.condition.get("cond_1norm"),
            "cond_1norm_jacobi": sol.condition.get("cond_1norm_jacobi"),
            "timings": {"mesh": t_mesh, **sol.timings, "energy_error": t_err, "sif": t_sif}}


def slope(h, y) -> float:
    """Least-squares slope of log y against log h."""
    return float(np.polyfit(np.log(h), np.log(y), 1)[0])


def sweep(args) -> dict:
    runs = []
    for enrichment in ("vector", "scalar"):
        for n in (10, 20, 40, 80):
            r = run(n, enrichment, args.radius, args.quadrature, args.degree, args.mode, args.angle,
                    args.blending, args.sif_radius)
            print(f"{enrichment:6s} n={n:3d} dofs={r['ndofs']:6d} energy err={r['energy_error_rel']:.3e} "
                  f"K_I={r['K_I']:.6f} K_II={r['K_II']:.6f} cond={r['cond_1norm']:.2e}",
                  file=sys.stderr, flush=True)
            runs.append(r)
    summary = {}
    for enrichment in ("vector", "scalar"):
        rs = [r for r in runs if r["enrichment"] == enrichment]
        h = np.array([r["h"] for r in rs])
        fine = h <= 0.1 + 1e-12  # n >= 20: h below the enrichment radius
        cond = np.array([r["cond_1norm"] for r in rs])
        condj = np.array([r["cond_1norm_jacobi"] for r in rs])
        summary[enrichment] = {
            "energy_rate": slope(h, [r["energy_error_rel"] for r in rs]),
            "energy_rate_n20_80": slope(h[fine], [r["energy_error_rel"] for r in rs if r["h"] <= 0.1 + 1e-12]),
            # cond ~ (1/h)^p, fitted over n >= 20
            "cond_growth_exponent": -slope(h[fine], cond[fine]),
            "cond_jacobi_growth_exponent": -slope(h[fine], condj[fine]),
        }
    return {"runs": runs, "summary": summary}


def plot_sweep(res: dict, out: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    files = []
    styles = {"vector": ("o-", "C0"), "scalar": ("s--", "C1")}
    runs = res["runs"]

    def series(enr, key):
        rs = [r for r in runs if r["enrichment"] == enr]
        return np.array([r["h"] for r in rs]), np.array([r[key] for r in rs], dtype=float)

    fig, ax = plt.subplots(figsize=(5.5, 4))
    for enr, (st, c) in styles.items():
        h, e = series(enr, "energy_error_rel")
        ax.loglog(h, e, st, color=c, label=f"{enr} (rate {res['summary'][enr]['energy_rate']:.2f})")
    h = series("vector", "energy_error_rel")[0]
    ax.loglog(h, 0.5 * h, "k:", label="slope 1")
    ax.set_xlabel("h (length units)")
    ax.set_ylabel("relative energy-norm error")
    ax.set_title("Westergaard: energy error")
    ax.legend()
    files.append(out / "westergaard_energy_error.png")
    fig.savefig(files[-1], dpi=150, bbox_inches="tight")
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(5.5, 4))
    for enr, (st, c) in styles.items():
        rs = [r for r in runs if r["enrichment"] == enr]
        h = np.array([r["h"] for r in rs])
        for key, ex, mk in (("K_I", "K_I_exact", ""), ("K_II", "K_II_exact", "")):
            err = np.array([abs(r[key] - r[ex]) for r in rs])
            ax.loglog(h, np.maximum(err, 1e-16), st, color=c, alpha=1.0 if key == "K_I" else 0.5,
                      label=f"{enr} |{key} - exact|")
    ax.axhline(1e-3, color="gray", lw=0.8, ls=":", label="1e-3 target at n = 40")
    ax.set_xlabel("h (length units)")
    ax.set_ylabel("SIF error (units of K)")
    ax.set_title("Westergaard: SIF error (interaction integral)")
    ax.legend(fontsize=7)
    files.append(out / "westergaard_sif_error.png")
    fig.savefig(files[-1], dpi=150, bbox_inches="tight")
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(5.5, 4))
    for enr, (st, c) in styles.items():
        h, k = series(enr, "cond_1norm")
        ax.loglog(h, k, st, color=c, label=f"{enr}, raw")
        h, k = series(enr, "cond_1norm_jacobi")
        ax.loglog(h, k, st, color=c, alpha=0.5, label=f"{enr}, Jacobi-scaled")
    ax.set_xlabel("h (length units)")
    ax.set_ylabel("1-norm condition number (estimate)")
    ax.set_title("Westergaard: conditioning")
    ax.legend(fontsize=7)
    files.append(out / "westergaard_condition.png")
    fig.savefig(files[-1], dpi=150, bbox_inches="tight")
    plt.close(fig)
    return files


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=20, help="divisions per side (default 20)")
    add_option_arguments(ap, enrichment="vector", radius=0.2, blending="corrected", quadrature="collapsed",
                         quadrature_degree=5)
    ap.add_argument("--mode", choices=list(MODES), default="I")
    ap.add_argument("--angle", type=float, default=None, help="crack angle in degrees (mixed: 30)")
    ap.add_argument("--sif-radius", type=float, default=None, help="interaction-integral radius")
    ap.add_argument("--sweep", action="store_true", help="n = 10, 20, 40, 80, both enrichments, PNGs")
    ap.add_argument("--out", type=pathlib.Path, default=pathlib.Path("results/westergaard"))
    ap.add_argument("--json", type=pathlib.Path, default=None)
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    if args.sweep:
        res = sweep(args)
        res["files"] = [str(p) for p in plot_sweep(res, args.out)]
        path = args.json or args.out / "westergaard_sweep.json"
    else:
        res = run(args.n, args.enrichment, args.radius, args.quadrature, args.degree, args.mode,
                  args.angle, args.blending, args.sif_radius)
        print(f"n={args.n} {args.enrichment}: energy error {res['energy_error_rel']:.3e}, "
              f"K_I {res['K_I']:.6f} (exact {res['K_I_exact']}), K_II {res['K_II']:.6f} "
              f"(exact {res['K_II_exact']}), cond {res['cond_1norm']:.2e}", file=sys.stderr)
        path = args.json or args.out / "westergaard.json"
    write_json(path, res)
    return res


if __name__ == "__main__":
    main()
