"""3D fatigue growth against closed forms (issue 37, acceptance 1).

Penny crack (radius a0 = 1) in a box of half-width L under uniform tension
sigma = 1 (E = 1, nu = 0.3), Paris law da/dN = C Delta K^m, C = 1, m = 3, R
= 0. K = 2 sigma sqrt(a / pi) all along the front, so the crack stays a
circle and

    N(a) = int_a0^a da / (C (2 sigma / sqrt(pi))^m a^(m/2))
         = 2 / ((m - 2) C (2 sigma / sqrt(pi))^m) (a0^(1 - m/2) - a^(1 - m/2))   (m != 2).

Figures: roundness = max |r - mean r| / mean r of the crack's front (its
tracked front, the surface's boundary inside the part) at the last step;
N_rel_err = (N - N(a)) / N(a) with a the front's mean radius at the last
step. Bars: roundness <= 1 %, |N_rel_err| <= 2 %. The mesh: h_front = a0 / n
in a box refinement covering the radii the crack grows through, growing by
0.1 per unit distance to H_FAR away (PENNY).

Semi-elliptical surface crack in a plate (thickness t = 1, width 2b = 10 t,
length 10 t) under tension, the same law: three starts at a/t = 0.1 with a/c
= 0.2, 0.5 and 1, grown until the depth reaches 0.8 t (growth.max_length),
each step's largest advance a tenth of the fastest point's crack size
(growth.da_fraction = DA_FRACTION). Reference: Newman and Raju's equations
(fracture.handbook.surface_crack_beta, with the plate's finite-width factor
f_w) integrated as the two-point model does, dc/da = (K_surface /
K_deepest)^m (scipy solve_ivp, rtol 1e-10; with b -> infinity it gives the
table of notes/contact_growth_mpi_3d.md §2.5 to the digit). Figure:
a_over_c_max_dev = max |a/c - a/c_NR(a/t)| over the steps with a/t <= 0.8
(a and c measured on the tracked front: a the largest depth below the face,
c half the distance between the front's ends on the face). Bar 0.03 (Newman
and Raju is a +-5 % fit of K). The mesh is graded along the path the crack
is expected to take (path_refinements): the start's front refinement
(scene.mesh_3d.crack_refinements: h0 = min(a0, c0) / n along the front, 2
h0 over the crack) and one along each of a sequence of Newman-Raju fronts
(a, c(a)) from a0 to a/t = PATH_END, at min(a, c) / n on its ellipse,
consecutive fronts at most PATH_SPACING of their sizes apart in a and in c,
the size growing by 1/n per unit distance from each. A front that follows
the path keeps n elements per min(a, c); one that strays from it by d sits
in elements of about min(a, c) / n + d / n. Why: graded from the start's
front alone (h0 + d / n after an advance d), the ends of the a/c0 = 0.5 and
1 starts reached elements of 0.08-0.24 from a/t 0.5 (under 5 per depth)
(docs/growth.md). Cells: 88 thousand (a/c0 = 1), 98 thousand (0.5), 143
thousand (0.2). Each row also has K_I at the deepest and surface points
with Newman and Raju's for the ellipse of the row's a and c.

    /usr/bin/python3 demos/growth_3d.py --json out/growth_3d.json [--small] [--cases penny surface_crack]
                                        [--starts 0.2 0.5 1] [--elements 8]

--small is the test's configuration (coarse meshes, two steps each, one
surface crack start): it checks the machinery, not the bars. Writes per case
a CSV of the steps and (not --small) PNGs next to the JSON. The full run
takes hours on a loaded 2-core machine: the JSON is rewritten after every
step, each case with "complete": false until its run ends, so a run
stopped midway keeps the figures of the steps it made (over the growth it
reached: "steps" of "steps_asked", "a_over_t_reached").
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
from cracklip.analysis.front_growth import SurfaceGrowth  # noqa: E402
from cracklip.errors import CracklipError  # noqa: E402
from cracklip.fracture.handbook import surface_crack_beta, surface_crack_k  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.scene.crack_surface import EllipticalCrack  # noqa: E402
from cracklip.scene.mesh_3d import BoxRefinement, crack_refinements, create_box  # noqa: E402

E, NU, SIGMA, C, M = 1.0, 0.3, 1.0, 1.0, 3.0
H_FAR = 2.0
#: The surface crack's plate: the largest element size (the thickness t = 1).
H_SURFACE = 1.0
#: The surface crack's step: this fraction of the fastest point's crack size.
DA_FRACTION = 0.1

#: (h_front = a0 / n, box half-width L, da, steps, growth of the element size per unit distance from the
#: refined slab) of the penny; --small's. The bulk around the crack matters: with the size growing by 0.25
#: per unit distance K was 0.9 % low at n = 14 (P1 tetrahedra are stiff where the crack's field decays,
#: scene.mesh_3d.GROWTH), with 0.1 about 0.3 %.
PENNY = {"full": (12, 6.0, 0.05, 8, 0.1), "small": (4, 4.0, 0.15, 2, 0.25)}
#: The surface crack's mesh is graded along Newman and Raju's path to this a/t (the runs stop past 0.8).
PATH_END = 0.85
#: Consecutive fronts of that grading at most this many of their element sizes apart (path_refinements).
PATH_SPACING = 2.0
#: (n: elements per crack size, starts (a/c at a/t = 0.1), a/t to reach, steps at most); --small's.
SURFACE = {"full": (8, (0.2, 0.5, 1.0), 0.8, 40), "small": (4, (0.5,), 0.8, 2)}


def _supports(lo, hi):
    x0, y0, z0 = lo
    x1, y1, _ = hi
    return [cl.Dirichlet((x0, y0, z0)), cl.Dirichlet((x1, y0, z0), 1), cl.Dirichlet((x1, y0, z0), 2),
            cl.Dirichlet((x0, y1, z0), 2)]


def _tension():
    return [cl.Traction("zmax", (0.0, 0.0, SIGMA)), cl.Traction("zmin", (0.0, 0.0, -SIGMA))]


def penny_life(a0: float, a: float, m: float = M) -> float:
    """Cycles from radius a0 to a (module doc)."""
    k = 2.0 * SIGMA / math.sqrt(math.pi)
    if m == 2.0:
        return math.log(a / a0) / (C * k * k)
    return 2.0 / ((m - 2.0) * C * k ** m) * (a0 ** (1.0 - m / 2.0) - a ** (1.0 - m / 2.0))


def run_penny(config: str, log, save=lambda case: None) -> dict:
    """The penny's figures (module doc); save(case) after every step with
    the figures so far (case["complete"] False until the run ends)."""
    n, L, da, steps, grading = PENNY[config]
    h = 1.0 / n
    r_max = 1.0 + da * steps + 4 * h
    fronts = [BoxRefinement((-r_max, -r_max, -3 * h), (r_max, r_max, 3 * h), h, (H_FAR - h) / grading)]
    mesh = create_box(-L, -L, -L, L, L, L, H_FAR, fronts=fronts)
    crack = EllipticalCrack((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 1.0, axis=(1.0, 0.0, 0.0), name="penny")
    lo, hi = (-L, -L, -L), (L, L, L)
    scene = cl.Scene(mesh, cl.Material(E, NU), cracks=[crack], dirichlet=_supports(lo, hi), tractions=_tension(),
                     options=cl.Options(enrichment="vector", radius=2.5 * h))
    growth = cl.Growth(da=da, steps=steps, paris_C=C, paris_m=M, R=0.0)
    run = SurfaceGrowth(scene, growth, False, None)
    t0 = time.perf_counter()
    rows: list[dict] = []

    def figures(complete: bool, res=None) -> dict:
        last = rows[-1]
        return {"roundness": last["roundness"], "N_rel_err": (last["N"] - last["N_exact"]) / last["N_exact"]
                if last["N_exact"] > 0 else None, "N": last["N"], "N_exact": last["N_exact"],
                "a0": rows[0]["radius_mean"], "a": last["radius_mean"], "steps": len(rows) - 1,
                "steps_asked": steps, "complete": complete, "h_front": h, "half_width": L,
                "cells": mesh.mesh.topology.index_map(3).size_global, "rows": rows,
                "step_seconds": res.step_times if res else [r["seconds"] for r in rows],
                "stop": res.stop_reason if res else None}

    def progress(k, records, sol):
        sh = run.shape[-1][0]
        a_start = rows[0]["radius_mean"] if rows else sh["radius_mean"]  # the closed form's start
        rows.append({
            "step": k, "N": records[0].N, "radius_mean": sh["radius_mean"], "roundness": sh["roundness"],
            "N_exact": penny_life(a_start, sh["radius_mean"]), "K_I_mean": float(np.mean([r.K_I for r in records])),
            "K_exact": 2 * SIGMA * math.sqrt(sh["radius_mean"] / math.pi), "points": len(records),
            "seconds": time.perf_counter() - t0})
        log(f"penny step {k}: N = {run.N:.6g}, mean radius {sh['radius_mean']:.5f}, roundness "
            f"{100 * sh['roundness']:.3f} %, K_I {min(r.K_I for r in records):.5f} .. {max(r.K_I for r in records):.5f}"
            f" ({time.perf_counter() - t0:.0f} s)")
        save(figures(False))
    run.on_step = progress
    res = run.run()
    return figures(True, res)


def newman_raju_path(a0: float, c0: float, t: float, b: float, a_end: float, m: float = M):
    """c(a) of the two-point Newman-Raju model (module doc), a callable."""
    from scipy.integrate import solve_ivp

    def rate(a, c):
        bd, bs = surface_crack_beta(a, c[0], t, b)
        return [(bs / bd) ** m]
    sol = solve_ivp(rate, (a0, a_end), [c0], dense_output=True, rtol=1e-10, atol=1e-12)
    return lambda a: float(sol.sol(a)[0])


def path_refinements(crack: EllipticalCrack, path, a0: float, a_end: float, n: int) -> list:
    """The surface crack's mesh grading (module doc): the start's front
    refinement (h0 = min(a0, c0) / n, its surface at 2 h0) and one along
    each of a sequence of Newman-Raju fronts (a, c = path(a)) from a0 to
    a_end, each at min(a, c) / n, the size growing by 1 / n per unit
    distance from each; consecutive fronts at most PATH_SPACING of the
    earlier one's size apart in a and in c (inside each other's plateau of
    4 sizes, so the swept region keeps min(a, c) / n)."""
    h_max = H_SURFACE
    out = crack_refinements([crack], min(a0, path(a0)) / n, h_max, growth=1.0 / n)
    a = a0
    while a < a_end:
        c = path(a)
        h = min(a, c) / n
        da = PATH_SPACING * h
        while path(min(a + da, a_end)) - c > PATH_SPACING * h:
            da *= 0.8
        a = min(a + da, a_end)
        c = path(a)
        front = EllipticalCrack(crack.center, crack.normal, c, b=a, axis=crack.axis)
        out += crack_refinements([front], min(a, c) / n, h_max, growth=1.0 / n, h_surface=h_max)
    return out


def run_surface(config: str, ac0: float, log, save=lambda case: None, elements: int | None = None) -> dict:
    """One start's figures (module doc); save(case) after every step as
    run_penny's."""
    n, _, at_end, steps = SURFACE[config]
    n = elements or n
    t, b, L = 1.0, 5.0, 5.0
    a0 = 0.1 * t
    c0 = a0 / ac0
    lo, hi = (-b, 0.0, -L), (b, t, L)
    h0 = min(a0, c0) / n
    crack = EllipticalCrack((0.0, t, 0.0), (0.0, 0.0, 1.0), c0, b=a0, axis=(1.0, 0.0, 0.0), name=f"a/c {ac0:g}")
    path = newman_raju_path(a0, c0, t, b, PATH_END * t)
    mesh = create_box(*lo, *hi, H_SURFACE, fronts=path_refinements(crack, path, a0, PATH_END * t, n))
    scene = cl.Scene(mesh, cl.Material(E, NU), cracks=[crack], dirichlet=_supports(lo, hi), tractions=_tension(),
                     options=cl.Options(enrichment="vector", radius=2.5 * h0))
    growth = cl.Growth(steps=steps, da_fraction=DA_FRACTION, paris_C=C, paris_m=M, R=0.0, max_length=at_end * t)
    run = SurfaceGrowth(scene, growth, False, None)
    t0 = time.perf_counter()
    rows: list[dict] = []

    def figures(complete: bool, res=None, broke: str | None = None) -> dict:
        devs = [abs(r["a_over_c"] - r["a_over_c_newman_raju"]) for r in rows
                if r["a_over_c_newman_raju"] is not None]
        return {"a_over_c0": ac0, "a_over_c_max_dev": max(devs) if devs else None,
                "steps": (len(res.records) - 1) if res else (rows[-1]["step"] if rows else 0), "steps_asked": steps,
                "complete": complete, "a_over_t_reached": rows[-1]["a_over_t"] if rows else None, "rows": rows,
                "h0": h0, "n": n, "cells": mesh.mesh.topology.index_map(3).size_global,
                "step_seconds": res.step_times if res else [r["seconds"] for r in rows],
                "stop": res.stop_reason if res else broke}

    def progress(k, records, sol):
        sh = run.shape[-1][0]
        log(f"surface a/c0 {ac0:g} step {k}: a/t = {sh.get('a_over_t', float('nan')):.4f}, a/c = "
            f"{sh.get('a_over_c', float('nan')):.4f}, {len(records)} points, N = {run.N:.6g} "
            f"({time.perf_counter() - t0:.0f} s)")
        if sh.get("a") is None:
            return
        a, c = sh["a"], sh["c"]
        # K_I at the deepest and surface points against Newman and Raju's for the ellipse of this a and c.
        at = {r.end: r for r in records if r.crack == 0}
        deep = at.get(sh.get("deepest"))
        ends = [at[i] for i in sh.get("surface_points", ()) if i in at]
        k_nr = (surface_crack_k(SIGMA, a, c, t, b, np.array([0.5 * math.pi, 0.0])) if a < 0.8 * t  # the fit's range
                else [None, None])
        rows.append({"step": k, "N": records[0].N, "a": a, "c": c, "a_over_t": a / t, "a_over_c": a / c,
                     "a_over_c_newman_raju": a / path(a) if a <= 0.8 * t else None, "points": len(records),
                     "K_I_deepest": deep.K_I if deep else None, "K_I_surface": [r.K_I for r in ends],
                     "K_I_deepest_newman_raju": k_nr[0] and float(k_nr[0]),
                     "K_I_surface_newman_raju": k_nr[1] and float(k_nr[1]),
                     "h_deepest": deep.element_size if deep else None, "seconds": time.perf_counter() - t0})
        save(figures(False))
    run.on_step = progress
    try:
        res = run.run()
    except CracklipError as e:
        # The steps made so far keep their figures (complete false), with why the run broke off.
        log(f"surface a/c0 {ac0:g}: the run broke off after step {rows[-1]['step'] if rows else 0}: {e}")
        return figures(False, broke=f"the run broke off: {e}")
    return figures(True, res)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", type=pathlib.Path)
    ap.add_argument("--small", action="store_true", help="the test's configuration (coarse, two steps)")
    ap.add_argument("--cases", nargs="+", default=["penny", "surface_crack"], choices=["penny", "surface_crack"])
    ap.add_argument("--starts", type=float, nargs="+", help="the surface crack's starts a/c at a/t = 0.1 "
                    "(default 0.2 0.5 1, --small 0.5)")
    ap.add_argument("--elements", type=int, help="the surface crack's elements per crack size n (h = min(a, c) / n "
                    "along the path; default 8, --small 4)")
    args = ap.parse_args(argv)
    config = "small" if args.small else "full"

    def log(text: str) -> None:
        if __name__ == "__main__":
            print(text, file=sys.stderr, flush=True)
    out: dict = {"config": config}

    def save() -> None:
        """The JSON as it stands (a long run killed midway keeps its steps)."""
        if args.json is not None:
            write_json(args.json, out)
    if "penny" in args.cases:
        out["penny"] = run_penny(config, log, lambda case: (out.__setitem__("penny", case), save()))
    if "surface_crack" in args.cases:
        cases: list[dict] = []

        def summary(case=None) -> dict:
            every = cases + ([case] if case is not None else [])
            devs = [c["a_over_c_max_dev"] for c in every if c["a_over_c_max_dev"] is not None]
            return {"a_over_c_max_dev": max(devs) if devs else None, "cases": every,
                    "complete": case is None and len(every) == len(starts) and all(c["complete"] for c in every)}
        starts = args.starts or SURFACE[config][1]
        for ac0 in starts:
            cases.append(run_surface(config, ac0, log,
                                     lambda case: (out.__setitem__("surface_crack", summary(case)), save()),
                                     elements=args.elements))
        out["surface_crack"] = summary()
    save()
    if args.json is not None and __name__ == "__main__" and not args.small:
        write_figures(out, args.json.parent)
    return out


def write_figures(out: dict, folder: pathlib.Path) -> None:
    """growth_3d_penny.png (N against the radius with the closed form;
    roundness per step) and growth_3d_surface.png (a/c against a/t with the
    Newman-Raju paths), with their CSVs."""
    import csv
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    folder.mkdir(parents=True, exist_ok=True)
    if "penny" in out:
        rows = out["penny"]["rows"]
        with (folder / "growth_3d_penny.csv").open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(list(rows[0]))
            w.writerows([list(r.values()) for r in rows])
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
        a = np.linspace(rows[0]["radius_mean"], rows[-1]["radius_mean"], 100)
        ax1.plot([penny_life(rows[0]["radius_mean"], x) for x in a], a, "-", color="0.3", label="closed form")
        ax1.plot([r["N"] for r in rows], [r["radius_mean"] for r in rows], "o", label="cracklip")
        ax1.set_xlabel("cycles N")
        ax1.set_ylabel("mean radius a")
        ax1.set_title(f"penny, Paris m = {M:g}: N error {100 * out['penny']['N_rel_err']:.2f} %", fontsize=9)
        ax1.legend(fontsize=8)
        ax2.plot([r["step"] for r in rows], [100 * r["roundness"] for r in rows], "o-")
        ax2.axhline(1.0, color="r", ls="--", lw=0.8, label="bar 1 %")
        ax2.set_xlabel("step")
        ax2.set_ylabel("roundness max|r - mean r| / mean r [%]")
        ax2.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(folder / "growth_3d_penny.png", dpi=110)
        plt.close(fig)
    if "surface_crack" in out:
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        t, b = 1.0, 5.0
        with (folder / "growth_3d_surface.csv").open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["a_over_c0", "step", "N", "a", "c", "a_over_t", "a_over_c", "a_over_c_newman_raju",
                        "K_I_deepest", "K_I_deepest_newman_raju", "K_I_surface_1", "K_I_surface_2",
                        "K_I_surface_newman_raju"])
            for n, case in enumerate(out["surface_crack"]["cases"]):
                rows = case["rows"]
                for r in rows:
                    ks = (list(r.get("K_I_surface") or []) + [None, None])[:2]
                    w.writerow([case["a_over_c0"], r["step"], r["N"], r["a"], r["c"], r["a_over_t"], r["a_over_c"],
                                r["a_over_c_newman_raju"], r.get("K_I_deepest"), r.get("K_I_deepest_newman_raju"),
                                *ks, r.get("K_I_surface_newman_raju")])
                a0 = 0.1 * t
                path = newman_raju_path(a0, a0 / case["a_over_c0"], t, b, 0.8 * t)
                at = np.linspace(0.1, 0.8, 100)
                ax.plot(at, [x / path(x) for x in at], "-", color=f"C{n}", lw=1,
                        label=f"Newman-Raju, a/c0 = {case['a_over_c0']:g}")
                ax.plot([r["a_over_t"] for r in rows], [r["a_over_c"] for r in rows], "o", color=f"C{n}", ms=4,
                        label=f"cracklip (max dev {case['a_over_c_max_dev']:.3f})")
        ax.set_xlabel("a / t")
        ax.set_ylabel("a / c")
        ax.set_title(f"surface crack in a plate, Paris m = {M:g}: the front's shape", fontsize=9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(folder / "growth_3d_surface.png", dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    res = main()
    brief = {k: ({kk: vv for kk, vv in v.items() if kk not in ("rows", "cases", "step_seconds")}
                 if isinstance(v, dict) else v) for k, v in res.items()}
    print(brief)
