"""Condition number against mesh size, with and without the nodal rescaling
(issue 6): Westergaard mode I (exact field on the whole boundary, r_e = 0.2),
scalar and vector tip enrichment, corrected and standard blending.

For each configuration the 1-norm condition number (Hager/Higham estimate
from MUMPS solves) of: the raw stiffness, its Jacobi scaling (what the solver
factorises by default) and the nodally rescaled matrix (Options.rescale =
"nodal"); the growth exponent is the least-squares slope of log cond against
log(1/h) over n >= 20. Writes JSON, Markdown and a PNG.

Where the scalar enrichment with corrected blending stays ill-conditioned,
the spectrum study (spectrum.json, spectrum.png) shows why: the smallest
eigenvalues of the nodally rescaled stiffness, of the same matrix without
the tip dofs of the blending ring's nodes (the outer layer that corrected
blending adds) and without any tip dof, against h.

    /usr/bin/python3 demos/conditioning.py --out results/conditioning
"""
from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np
import scipy.sparse.linalg as sla

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))

import westergaard  # noqa: E402
from cracklip.model.assembly import assemble_system  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.solvers.checked import scipy_from_petsc  # noqa: E402
from cracklip.model.model import create_model  # noqa: E402
from cracklip.solvers.rescaling import nodal_transform, rescale_system  # noqa: E402

CONFIGS = [("vector", "corrected"), ("scalar", "corrected"), ("vector", "standard"), ("scalar", "standard")]


def condition(n: int, enrichment: str, blending: str, rescale: str) -> dict:
    r = westergaard.run(n, enrichment, blending=blending, rescale=rescale)
    return {"n": n, "h": r["h"], "ndofs": r["ndofs"], "cond_1norm": r["cond_1norm"],
            "cond_1norm_jacobi": r["cond_1norm_jacobi"], "energy_error": r["energy_error_rel"]}


def exponent(rows: list[dict], key: str, n_min: int = 20) -> float:
    """p in cond ~ (1/h)^p over n >= n_min."""
    rs = [r for r in rows if r["n"] >= n_min]
    return -westergaard.slope([r["h"] for r in rs], [r[key] for r in rs])


def smallest_eigenvalues(n: int, enrichment: str, blending: str = "corrected", k: int = 8) -> dict:
    """Smallest eigenvalues of the nodally rescaled Westergaard stiffness
    (constrained rows included; those are 1), of its submatrix without the
    tip dofs of ring nodes (tip-enriched nodes outside the core, which
    corrected blending adds) and of its submatrix without any tip dof. A
    submatrix is the Galerkin matrix of the space without those functions."""
    scene, _ = westergaard.scene_for(n, enrichment, blending=blending)
    model = create_model(scene)
    A, b, _ = assemble_system(model)
    As, bs = rescale_system(A, b, nodal_transform(model, A))
    M = scipy_from_petsc(As)
    for obj in (A, b, As, bs):
        obj.destroy()
    M = 0.5 * (M + M.T)
    lay = model.layout
    tip = np.asarray(lay.kind) > 0
    ring = tip & (np.asarray(lay.core) == 0)
    pseudo = 2 * (lay.num_std_nodes + np.arange(lay.num_enriched))

    def lowest(drop: np.ndarray) -> list[float]:
        keep = np.setdiff1d(np.arange(M.shape[0]), np.concatenate([pseudo[drop], pseudo[drop] + 1]))
        S = M[keep][:, keep].tocsc()
        return sorted(sla.eigsh(S, k=k, sigma=-1e-3, which="LM", return_eigenvectors=False).tolist())

    return {"n": n, "h": 2.0 / n, "enrichment": enrichment, "blending": blending,
            "ring_tip_dofs": int(2 * ring.sum()), "tip_dofs": int(2 * tip.sum()),
            "lambda_max": float(sla.eigsh(M, k=1, which="LA", return_eigenvectors=False)[0]),
            "all": lowest(np.zeros_like(tip)), "without_ring_tip_dofs": lowest(ring),
            "without_tip_dofs": lowest(tip)}


def spectrum(ns, log=lambda m: None) -> dict:
    """smallest_eigenvalues for scalar and vector enrichment, corrected blending."""
    rows = []
    for enrichment in ("scalar", "vector"):
        for n in ns:
            rows.append(smallest_eigenvalues(n, enrichment))
            r = rows[-1]
            log(f"spectrum {enrichment} n={n}: lambda_min {r['all'][0]:.3g} (5th {r['all'][4]:.3g}), "
                f"without ring tip dofs {r['without_ring_tip_dofs'][0]:.3g}, without tip dofs "
                f"{r['without_tip_dofs'][0]:.3g}")
    return {"ns": list(ns), "rows": rows}


def spectrum_table(rows: list[dict]) -> list[str]:
    """Markdown table of smallest_eigenvalues rows (spectrum.md and results.md)."""
    return ["| enrichment | n | lambda_max | lambda_1 | lambda_5 | lambda_1 without ring tip dofs | "
            "lambda_1 without tip dofs |", "|---|---|---|---|---|---|---|",
            *(f"| {r['enrichment']} | {r['n']} | {r['lambda_max']:.2f} | {r['all'][0]:.2e} | {r['all'][4]:.2e} | "
              f"{r['without_ring_tip_dofs'][0]:.2e} | {r['without_tip_dofs'][0]:.2e} |" for r in rows)]


def write_spectrum(res: dict, out: pathlib.Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    write_json(out / "spectrum.json", res)
    lines = ["# Smallest eigenvalues of the nodally rescaled stiffness (Westergaard, corrected blending)", "",
             "lambda_1 and lambda_5 of the whole matrix; lambda_1 without the ring nodes' tip dofs and "
             "without any tip dof (Galerkin submatrices).", "", *spectrum_table(res["rows"])]
    (out / "spectrum.md").write_text("\n".join(lines) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for enrichment, colour in (("scalar", "C3"), ("vector", "C0")):
        rs = [r for r in res["rows"] if r["enrichment"] == enrichment]
        inv_h = [1.0 / r["h"] for r in rs]
        ax.loglog(inv_h, [r["all"][0] for r in rs], "-o", color=colour, ms=3, label=f"{enrichment}: lambda_1")
        ax.loglog(inv_h, [r["all"][4] for r in rs], "--o", color=colour, ms=3, label=f"{enrichment}: lambda_5")
        ax.loglog(inv_h, [r["without_ring_tip_dofs"][0] for r in rs], ":s", color=colour, ms=3,
                  label=f"{enrichment}: lambda_1 without ring tip dofs")
    rs = [r for r in res["rows"] if r["enrichment"] == "scalar"]
    ax.loglog([1.0 / r["h"] for r in rs], [r["without_tip_dofs"][0] for r in rs], "k-", lw=0.8,
              label="lambda_1 without any tip dof")
    ax.set_xlabel("1/h (1/length)")
    ax.set_ylabel("eigenvalue of the rescaled stiffness (-)")
    ax.set_title("corrected blending: smallest eigenvalues, nodal rescaling")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "spectrum.png", dpi=140)
    plt.close(fig)


def run(ns, log=lambda m: None) -> dict:
    res = {"ns": list(ns), "configs": []}
    for enrichment, blending in CONFIGS:
        rows = []
        for n in ns:
            none = condition(n, enrichment, blending, "none")
            nodal = condition(n, enrichment, blending, "nodal")
            rows.append({"n": n, "h": none["h"], "ndofs": none["ndofs"], "cond_raw": none["cond_1norm"],
                         "cond_jacobi": none["cond_1norm_jacobi"], "cond_nodal": nodal["cond_1norm"],
                         "energy_error": none["energy_error"], "energy_error_nodal": nodal["energy_error"]})
            log(f"{enrichment}/{blending} n={n}: raw {rows[-1]['cond_raw']:.3g}, jacobi "
                f"{rows[-1]['cond_jacobi']:.3g}, nodal {rows[-1]['cond_nodal']:.3g}")
        res["configs"].append({"enrichment": enrichment, "blending": blending, "rows": rows,
                               "exponent_raw": exponent(rows, "cond_raw"),
                               "exponent_jacobi": exponent(rows, "cond_jacobi"),
                               "exponent_nodal": exponent(rows, "cond_nodal")})
    return res


def write(res: dict, out: pathlib.Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    write_json(out / "conditioning.json", res)
    lines = ["# Condition number vs mesh size (Westergaard, r_e = 0.2)", "",
             "Growth exponent p in cond ~ (1/h)^p, least squares over n >= 20 (standard P1 FE: 2).", "",
             "| enrichment | blending | raw | Jacobi | nodal rescaling | cond at finest n (raw / Jacobi / nodal) |",
             "|---|---|---|---|---|---|"]
    for c in res["configs"]:
        last = c["rows"][-1]
        lines.append(f"| {c['enrichment']} | {c['blending']} | {c['exponent_raw']:.2f} | {c['exponent_jacobi']:.2f} | "
                     f"{c['exponent_nodal']:.2f} | {last['cond_raw']:.2e} / {last['cond_jacobi']:.2e} / "
                     f"{last['cond_nodal']:.2e} (n = {last['n']}) |")
    (out / "conditioning.md").write_text("\n".join(lines) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, blending in zip(axes, ("corrected", "standard")):
        for c in res["configs"]:
            if c["blending"] != blending:
                continue
            inv_h = [1.0 / r["h"] for r in c["rows"]]
            for key, ls in (("cond_raw", ":"), ("cond_jacobi", "--"), ("cond_nodal", "-")):
                ax.loglog(inv_h, [r[key] for r in c["rows"]], ls, marker="o", ms=3,
                          label=f"{c['enrichment']}, {key[5:]} (p = {c['exponent_' + key[5:]]:.2f})")
        x = np.array([1.0 / r["h"] for r in res["configs"][0]["rows"]])
        ax.loglog(x, 50.0 * x ** 2, "k-", lw=0.6, label="slope 2 (standard FE)")
        ax.set_xlabel("1/h (1/length)")
        ax.set_title(f"{blending} blending")
        ax.legend(fontsize=7)
    axes[0].set_ylabel("1-norm condition number (-)")
    fig.tight_layout()
    fig.savefig(out / "conditioning.png", dpi=140)
    plt.close(fig)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, nargs="+", default=[10, 20, 40, 80, 160], help="divisions per side")
    ap.add_argument("--out", type=pathlib.Path, default=pathlib.Path("results/conditioning"))
    ap.add_argument("--spectrum-n", type=int, nargs="*", default=[20, 40, 80],
                    help="divisions per side of the eigenvalue study (none: skip it)")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    log = (lambda m: None) if args.quiet else (lambda m: print(m, file=sys.stderr, flush=True))
    res = run(args.n, log)
    write(res, args.out)
    if args.spectrum_n:
        res["spectrum"] = spectrum(args.spectrum_n, log)
        write_spectrum(res["spectrum"], args.out)
    for c in res["configs"]:
        log(f"{c['enrichment']}/{c['blending']}: exponent raw {c['exponent_raw']:.2f}, jacobi "
            f"{c['exponent_jacobi']:.2f}, nodal {c['exponent_nodal']:.2f}")
    return res


if __name__ == "__main__":
    main()
