"""K's estimated discretisation error along 3D fronts against its true error,
the default grading's convergence, and --accuracy in 3D (issue 39).

Every scene is a scene file (the command line's path: mesh.tip_h = size /
n and the default grading, box of side 20 crack sizes, far size 2, remote
tension 1 on the end faces, E = 1, nu = 0.3, vector front enrichment within
a quarter of the crack size, the iterative solver). Cases:

- penny (a = 1) and inclined_penny_45 (45 degrees to the load): exact K of
  the infinite body (cracklip.exact.embedded_cracks);
- irwin_0.5: the embedded ellipse b / a = 0.5 (sizes in units of b): Irwin's
  exact K_I;
- spherical_cap: the curved crack of demos/front_sifs.py (a spherical cap
  of base radius a = 1 cut at 45 degrees, triangulated at half the front
  size and given as an STL, nu = 0.22, hydrostatic tension 1 on all six
  faces): the reference K of cracklip.exact.spherical_cap;
- surface_crack_1_0.2: a semicircular surface crack (a = c = 1) in a plate
  of thickness t = 5 (a/c = 1, a/t = 0.2): no exact K (Newman-Raju is +-5
  %), so the reference is this demo's own: K on three finer meshes
  (REFERENCE), each carried to the finest's front points, extrapolated
  point by point with the rate of the front's mean K_I over the three
  (Richardson); the reference's own uncertainty is the extrapolation's
  size at the finest mesh, reported.

Part "estimate": per case and mesh, the run's K with its estimate
(cracklip.analysis.accuracy.estimate_error: one more solve with every
element size times sqrt(2), or 1 / sqrt(2) on a front coarser than a tenth
of the crack size) against the true error, per front point off the
free surface, as vectors (K_I, K_II, K_III) relative to the K scale: the
estimate's norm over the true error's norm, its smallest, median and
largest over the points (acceptance 1: 1 <= ratio <= 4 at every point of
the two finest meshes), and the largest true error per mesh (acceptance 3:
it falls at least 1.5 times per halving of tip_h; penny and inclined penny
at a/5, a/10, a/20).

--smoothing fit: every scene with options.sif_smoothing = "fit" (K reported
as its fit along the front where one passes the check against the
estimate's mesh, cracklip.analysis.accuracy.fitted_along); each row then
also has the computed K's true error and its own estimate ("unsmoothed",
from the same solves) and the modes fitted. The true error throughout is
TRUE_ERROR (the norm of the error vector over the K scale; a component's
error crossing zero along the front, as the inclined penny's K_II and
K_III may, does not make it vanish unless all three do).

Part "grading": the penny's mean and largest K error as tip_h is halved,
with the default grading (the size grows 1.4 tip_h per crack size from the
front) and with the former one (0.25 per unit length: mesh.tip_radius = (h
- tip_h) / 0.25).

Part "accuracy": `run demos/scenes/inclined_penny.toml --accuracy 0.01`
(acceptance 4): every front point's error to the exact K.

    /usr/bin/python3 demos/front_estimate.py --json out/front_estimate.json [--quick] [--parts ...] [--smoothing fit]

main(argv) returns the result (written to --json, with a CSV of the points
per case and mesh and a PNG of estimate and true error along the finest
front next to it); markdown(result) renders its tables. --quick: the
penny at a/7.07 only (the test's configuration: the coarsest front measured
where the estimate brackets, its mesh the finer one).
"""
from __future__ import annotations

import argparse
import csv
import math
import pathlib
import sys
import tempfile
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))

import cracklip as cl  # noqa: E402
import front_sifs  # noqa: E402
from cracklip.analysis.accuracy import estimate_error  # noqa: E402
from cracklip.analysis.front_match import FrontPiece, carry_over  # noqa: E402
from cracklip.exact import spherical_cap  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.io.scene_file import load_scene_file  # noqa: E402

SQ2 = math.sqrt(2.0)

#: Meshes (crack size / tip_h) per case: --quick, the full study.
MESHES = {
    "penny": ((5 * SQ2,), (5.0, 5 * SQ2, 10.0, 10 * SQ2, 20.0)),
    "inclined_penny_45": ((), (5.0, 5 * SQ2, 10.0, 10 * SQ2, 20.0)),
    "irwin_0.5": ((), (4 * SQ2, 8.0, 8 * SQ2)),
    "surface_crack_1_0.2": ((), (5 * SQ2, 10.0, 10 * SQ2)),
    "spherical_cap": ((), (10 * SQ2, 20.0)),
}

#: The surface crack's reference meshes (Richardson, module doc).
REFERENCE = (10 * SQ2, 20.0, 20 * SQ2)

#: The grading part's meshes (penny, a / tip_h).
GRADING = ((5 * SQ2,), (5.0, 5 * SQ2, 10.0, 10 * SQ2))

#: The former default growth per unit length (mesh.tip_radius = 0 before issue 39).
OLD_GROWTH = 0.25

H_FAR = 2.0

MODES = ("K_I", "K_II", "K_III")

#: What "true error" and "estimate" mean in the JSON (per front point).
TRUE_ERROR = ("|K - K_exact| over the K scale: the norm of the error vector (K_I, K_II, K_III) at the point over "
              "the largest |K_exact| along the front; the estimate likewise the norm of (K_I_error, K_II_error, "
              "K_III_error) over the same scale; front points on a free surface left out")


def scene_text(case: str, n: float, tip_radius: float = 0.0, smoothing: str = "none") -> str:
    """The scene file of a case with mesh.tip_h = size / n (options.sif_smoothing = smoothing)."""
    supports = ""
    nu, axes = 0.3, "z"
    if case == "spherical_cap":
        # the cap of demos/front_sifs.py (base radius a = 1, alpha = 45 degrees, nu = 0.22, hydrostatic tension),
        # its triangulation in cap.stl next to the scene (scene_files)
        box = [-10.0, -10.0, -10.0, 10.0, 10.0, 10.0]
        crack = 'surface = "cap.stl"'
        size, nu, axes = 1.0, spherical_cap.REFERENCE_NU, "xyz"
    elif case.startswith("surface"):
        a, c, t = 1.0, 1.0, 5.0
        b, L = 10.0 * c, max(10.0 * c, 4.0 * t)
        box = [-b, 0.0, -L, b, t, L]
        crack = (f'ellipse = {{ center = [0.0, {t}, 0.0], normal = [0.0, 0.0, 1.0], a = {c}, b = {a}, '
                 'a_direction = [1.0, 0.0, 0.0] }')
        size = a
    else:
        box = [-10.0, -10.0, -10.0, 10.0, 10.0, 10.0]
        if case == "penny":
            normal, axis, a, b = (0.0, 0.0, 1.0), (0.0, 1.0, 0.0), 1.0, 1.0
        elif case.startswith("inclined_penny"):
            beta = math.radians(float(case.rsplit("_", 1)[1]))
            normal, axis, a, b = (math.cos(beta), 0.0, math.sin(beta)), (0.0, 1.0, 0.0), 1.0, 1.0
        else:
            normal, axis, a, b = (0.0, 0.0, 1.0), (1.0, 0.0, 0.0), 1.0, float(case.split("_")[1])
        crack = (f"ellipse = {{ center = [0.0, 0.0, 0.0], normal = [{normal[0]!r}, {normal[1]!r}, {normal[2]!r}], "
                 f"a = {a}, b = {b}, a_direction = [{axis[0]}, {axis[1]}, {axis[2]}] }}")
        size = min(a, b)
    tractions = ""
    for i, ax in enumerate("xyz"):
        if ax in axes:
            t = ["0.0"] * 3
            t[i] = "1.0"
            m = ["0.0"] * 3
            m[i] = "-1.0"
            tractions += (f'[[loads.tractions]]\ntag = "{ax}max"\nvalue = [{", ".join(t)}]\n'
                          f'[[loads.tractions]]\ntag = "{ax}min"\nvalue = [{", ".join(m)}]\n')
    x0, y0, z0, x1, y1, _ = box
    for p, comp in (((x0, y0, z0), None), ((x1, y0, z0), "y"), ((x1, y0, z0), "z"), ((x0, y1, z0), "z")):
        supports += f"\n[[dirichlet]]\npoint = [{p[0]}, {p[1]}, {p[2]}]\n" + (f'component = "{comp}"\n' if comp else "")
    return f"""title = "{case}, size / tip_h = {n:.4g}"
[mesh]
kind = "box"
box = {box}
h = {H_FAR}
tip_h = {size / n!r}
tip_radius = {tip_radius!r}
[material]
E = 1.0
nu = {nu!r}
[[cracks]]
name = "{case}"
{crack}
{supports}
{tractions}
[options]
radius = {0.25 * size!r}
solver = "iterative"
sif_smoothing = "{smoothing}"
"""


def info(case: str) -> dict:
    """What front_sifs.exact needs for a case."""
    if case == "spherical_cap":
        return {"kind": "cap"}
    if case.startswith("surface"):
        return {"kind": "surface", "a": 1.0, "c": 1.0, "t": 5.0, "b": 10.0}
    if case.startswith("irwin"):
        return {"kind": "irwin", "a": 1.0, "b": float(case.split("_")[1])}
    beta = math.radians(90.0 if case == "penny" else float(case.rsplit("_", 1)[1]))
    normal = np.array([0.0, 0.0, 1.0]) if case == "penny" else np.array([math.cos(beta), 0.0, math.sin(beta)])
    return {"kind": "penny", "beta": beta, "normal": normal}


def solve_case(case: str, n: float, estimate: bool, folder: pathlib.Path, tip_radius: float = 0.0,
               smoothing: str = "none") -> dict:
    """Solve (and estimate) one mesh; the rows and timings."""
    path = folder / f"{case}_{n:.3f}_{tip_radius:g}_{smoothing}.toml"
    path.write_text(scene_text(case, n, tip_radius, smoothing))
    if case == "spherical_cap":  # the triangulation at half the front size, as front_sifs.build makes it
        alpha = spherical_cap.REFERENCE_ALPHA_DEG
        depth = (1.0 - math.cos(math.radians(alpha))) / math.sin(math.radians(alpha))
        v, t = spherical_cap.cap_triangulation(1.0, alpha, 0.5 / n, pole=(0.0, 0.0, -0.5 * depth))
        spherical_cap.write_stl(folder / "cap.stl", v, t)
    t0 = time.perf_counter()
    sf = load_scene_file(path)
    t_mesh = time.perf_counter() - t0
    t0 = time.perf_counter()
    sol = cl.solve(sf.scene)
    rows = sol.stress_intensity_factors(None)
    t_run = time.perf_counter() - t0
    t_est = 0.0
    if estimate:
        t0 = time.perf_counter()
        estimate_error(sf.scene, sol, cl.solve)
        t_est = time.perf_counter() - t0
        rows = sol.stress_intensity_factors(None)
    return {"rows": rows, "dofs": int(sol.model.num_dofs), "t_mesh": t_mesh, "t_run": t_run, "t_estimate": t_est,
            "estimate_dofs": _other_dofs(sol.error_estimate)}


def _other_dofs(summary: dict | None) -> int | None:
    """The dofs of the estimate's own mesh (the level whose size factor is
    not the run's 1: coarser on a fine front, finer on a coarse one)."""
    if not summary:
        return None
    return next(d for f, d in zip(summary["size_factors"], summary["dofs"]) if f != 1.0)


def _K(rows: list[dict]) -> np.ndarray:
    return np.array([[r["K_I"], r["K_II"], r["K_III"]] for r in rows])


def richardson_reference(runs: list[dict]) -> tuple[np.ndarray, float, float]:
    """K extrapolated at the finest run's points from three runs (coarse to
    fine, sizes in the ratio sqrt(2)): the rate p of the mean K_I over the
    front points off the free surface, then K0 = K3 + (K3 - K2) / (sqrt(2)^p
    - 1) point by point. Returns (K0 (n, 3), p, the largest |K0 - K3|)."""
    finest = runs[-1]["rows"]
    x = np.array([r["position"] for r in finest])
    Ks = []
    for run in runs:
        rows = run["rows"]
        pieces = []
        for p in sorted({r["piece"] for r in rows}):
            pts = sorted((r for r in rows if r["piece"] == p), key=lambda r: r["s"])
            pieces.append(FrontPiece(np.array([r["position"] for r in pts]), _K(pts), False))
        Ks.append(carry_over(x, pieces))
    inner = ~np.array([bool(r["free_surface"]) for r in finest])
    m = [float(np.mean(K[inner, 0])) for K in Ks]
    d1, d2 = m[1] - m[0], m[2] - m[1]
    p = 2.0 * math.log(abs(d1 / d2)) / math.log(2.0) if d1 * d2 > 0.0 and abs(d2) < abs(d1) else 1.0
    K0 = Ks[2] + (Ks[2] - Ks[1]) / (SQ2 ** p - 1.0)
    return K0, p, float(np.abs(K0 - Ks[2])[inner].max())


def compare(case: str, n: float, run: dict, reference=None) -> dict:
    """Per front point of one run: K, reference, estimate, errors (vectors
    over the K scale), and the row's summary."""
    rows = run["rows"]
    K = _K(rows)
    if reference is None:
        Kx, ang, scale = front_sifs.exact(info(case), rows)
    else:
        Kx = reference
        _, ang, _ = front_sifs.exact(info(case), rows)
        scale = float(np.linalg.norm(Kx, axis=1).max())
    est = np.array([[r.get(m) if r.get(m) is not None else np.nan for m in ("K_I_error", "K_II_error", "K_III_error")]
                    for r in rows])
    inner = ~np.array([bool(r["free_surface"]) for r in rows])
    true = np.linalg.norm(K - Kx, axis=1) / scale
    eta = np.linalg.norm(est, axis=1) / scale
    ratio = eta / np.maximum(true, 1e-300)
    fitted = {}
    if any(r.get("K_I_unsmoothed") is not None for r in rows):
        # options.sif_smoothing = "fit": the computed K and its own estimate, beside the fitted ones
        K0 = np.array([[r[f"{m}_unsmoothed"] if r.get(f"{m}_unsmoothed") is not None else r[m] for m in MODES]
                       for r in rows])
        e0 = np.array([[r[f"{m}_error_unsmoothed"] if r.get(f"{m}_error_unsmoothed") is not None else r[f"{m}_error"]
                        for m in MODES] for r in rows])
        t0, n0 = np.linalg.norm(K0 - Kx, axis=1) / scale, np.linalg.norm(e0, axis=1) / scale
        r0 = n0[inner] / np.maximum(t0[inner], 1e-300)
        fitted = {"unsmoothed": {"true_max": float(t0[inner].max()), "true_min": float(t0[inner].min()),
                                 "ratio_min": float(r0.min()), "ratio_median": float(np.median(r0)),
                                 "ratio_max": float(r0.max()), "true": t0.tolist(), "estimate": n0.tolist()},
                  "fitted_modes": [m for m in MODES if any(r.get(f"{m}_unsmoothed") is not None
                                                           and r[m] != r[f"{m}_unsmoothed"] for r in rows)]}
    out = {"case": case, "size_over_h": n, "dofs": run["dofs"], "estimate_dofs": run["estimate_dofs"],
           "points": int(inner.sum()), "t_run": run["t_run"], "t_estimate": run["t_estimate"],
           "true_max": float(true[inner].max()), "true_min": float(true[inner].min()),
           "K_I_mean_error": float(np.mean((K - Kx)[inner, 0]) / scale),
           "angle": ang.tolist(), "true": true.tolist(), "free": (~inner).tolist(), **fitted}
    if np.all(np.isfinite(eta[inner])):
        out.update({"estimate_max": float(eta[inner].max()), "ratio_min": float(ratio[inner].min()),
                    "ratio_median": float(np.median(ratio[inner])), "ratio_max": float(ratio[inner].max()),
                    "brackets": bool(np.all(eta[inner] >= true[inner])),
                    "within_4": bool(np.all(ratio[inner] <= 4.0)), "estimate": eta.tolist()})
    return out


def estimate_part(cases, quick: bool, folder: pathlib.Path, log, sizes=None, smoothing: str = "none",
                  reference_meshes=REFERENCE) -> list[dict]:
    out = []
    for case in cases:
        meshes = MESHES[case][0 if quick else 1]
        if sizes:
            meshes = tuple(n for n in meshes if any(abs(n - s) < 0.01 for s in sizes))
        if not meshes:
            continue
        runs = {n: solve_case(case, n, True, folder, smoothing=smoothing) for n in meshes}
        reference = None
        if case.startswith("surface") and not quick:
            ref_runs = [runs[n] if n in runs and smoothing == "none" else solve_case(case, n, False, folder)
                        for n in reference_meshes]
            K0, p, spread = richardson_reference(ref_runs)
            reference = {"meshes": list(reference_meshes), "rate": p, "uncertainty_abs": spread}
        for n in meshes:
            ref = None
            if reference is not None:
                ref = carry_over(np.array([r["position"] for r in runs[n]["rows"]]),
                                 [FrontPiece(np.array([r["position"] for r in ref_runs[-1]["rows"]]), K0, False)])
            row = compare(case, n, runs[n], ref)
            if reference is not None:
                row["reference"] = reference
            out.append(row)
            log(f"{case:22s} size/h {n:6.2f} {row['dofs']:8d} dofs  true max {100 * row['true_max']:.3f} %  "
                + (f"estimate max {100 * row['estimate_max']:.3f} %  ratio {row['ratio_min']:.2f} .. "
                   f"{row['ratio_median']:.2f} .. {row['ratio_max']:.2f}" if "ratio_min" in row else "")
                + (f"  (unsmoothed: true max {100 * row['unsmoothed']['true_max']:.3f} %, ratio "
                   f"{row['unsmoothed']['ratio_min']:.2f} .. {row['unsmoothed']['ratio_median']:.2f} .. "
                   f"{row['unsmoothed']['ratio_max']:.2f}; fitted {row['fitted_modes']})" if "unsmoothed" in row else "")
                + f"  run {row['t_run']:.1f} s, estimate {row['t_estimate']:.1f} s")
    return out


def grading_part(quick: bool, folder: pathlib.Path, log) -> list[dict]:
    out = []
    for name, radius in (("default", None), ("former (0.25 per unit length)", 1.0)):
        for n in GRADING[0 if quick else 1]:
            tip = 1.0 / n
            r = 0.0 if radius is None else (H_FAR - tip) / OLD_GROWTH
            run = solve_case("penny", n, False, folder, r)
            row = compare("penny", n, run)
            row["grading"] = name
            out.append(row)
            log(f"grading {name:30s} a/h {n:6.2f} {row['dofs']:8d} dofs  K_I mean {100 * row['K_I_mean_error']:+.3f} % "
                f"max {100 * row['true_max']:.3f} %")
    return out


def accuracy_part(folder: pathlib.Path, target: float, log) -> dict:
    from cracklip import cli
    out_dir = folder / "accuracy"
    args = ["run", str(HERE / "scenes" / "inclined_penny.toml"), "--accuracy", str(target), "--out", str(out_dir),
            "--quiet", "--set", "outputs.vtu=false", "--set", "outputs.png=false"]
    t0 = time.perf_counter()
    cli.main(args)
    seconds = time.perf_counter() - t0
    import json
    res = json.loads((out_dir / "results.json").read_text())
    rows = res["sifs"]
    row = compare("inclined_penny_45", float("nan"), {"rows": rows, "dofs": res["solution"]["dofs"],
                                                       "estimate_dofs": None, "t_run": seconds, "t_estimate": 0.0})
    row.update({"target": target, "reached": res["error_estimate"]["reached"],
                "size_factors": res["error_estimate"]["size_factors"], "level_dofs": res["error_estimate"]["dofs"],
                "largest_estimate": res["error_estimate"]["largest_relative_error"], "seconds": seconds})
    log(f"accuracy {target:g}: sizes x {row['size_factors']}, {row['level_dofs']} dofs, reached {row['reached']}, "
        f"largest estimate {100 * row['largest_estimate']:.3f} %, true max {100 * row['true_max']:.3f} % ({seconds:.0f} s)")
    return row


def write_points(rows: list[dict], folder: pathlib.Path) -> None:
    """A CSV of every point per case and mesh, and a PNG of the finest
    estimate and true error along each case's front."""
    folder.mkdir(parents=True, exist_ok=True)
    with (folder / "points.csv").open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "size_over_h", "angle_deg", "true_error_rel", "estimate_rel", "free_surface"])
        for r in rows:
            for i, a in enumerate(r["angle"]):
                w.writerow([r["case"], f"{r['size_over_h']:.4g}", a, r["true"][i],
                            r["estimate"][i] if "estimate" in r else "", int(r["free"][i])])
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cases = sorted({r["case"] for r in rows if "estimate" in r})
    if not cases:
        return
    fig, axes = plt.subplots(len(cases), 1, figsize=(7, 2.8 * len(cases)), squeeze=False)
    for ax, case in zip(axes[:, 0], cases):
        mine = [r for r in rows if r["case"] == case and "estimate" in r][-2:]
        for r, style in zip(mine, ("--", "-")):
            o = np.argsort(r["angle"])
            a = np.array(r["angle"])[o]
            ax.plot(a, 100 * np.array(r["true"])[o], "o" + style, color="C3", ms=3, lw=1,
                    label=f"true error, size/h = {r['size_over_h']:.3g}")
            ax.plot(a, 100 * np.array(r["estimate"])[o], "s" + style, color="C0", ms=3, lw=1,
                    label=f"estimate, size/h = {r['size_over_h']:.3g}")
        ax.set_xlabel("angle along the front [deg]")
        ax.set_ylabel("|K error| / K scale [%]")
        ax.set_title(case, fontsize=9)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(folder / "front_estimate.png", dpi=110)
    plt.close(fig)


def halving(rows: list[dict]) -> dict:
    """Acceptance 3: the largest true error at size/h = 5, 10, 20 and its
    fall per halving."""
    out = {}
    for case in ("penny", "inclined_penny_45"):
        e = {round(r["size_over_h"], 3): r["true_max"] for r in rows if r["case"] == case}
        if all(k in e for k in (5.0, 10.0, 20.0)):
            out[case] = {"true_max": [e[5.0], e[10.0], e[20.0]], "falls": [e[5.0] / e[10.0], e[10.0] / e[20.0]]}
    return out


def markdown(result: dict) -> str:
    fit = any("unsmoothed" in r for r in result.get("estimate", []))
    lines = ["| case | size/h | dofs (estimate's) | true max | estimate max | estimate / true: min, median, max | "
             + ("K computed: true max | its estimate / true | fitted modes | " if fit else "")
             + "run s | estimate s |", "|---|---|---|---|---|---|" + ("---|---|---|" if fit else "") + "---|---|"]
    for r in result.get("estimate", []):
        ratio = (f"{r['ratio_min']:.2f}, {r['ratio_median']:.2f}, {r['ratio_max']:.2f}" if "ratio_min" in r else "-")
        est = f"{100 * r['estimate_max']:.3f} %" if "estimate_max" in r else "-"
        extra = ""
        if fit:
            u = r.get("unsmoothed")
            extra = (f"{100 * u['true_max']:.3f} % | {u['ratio_min']:.2f}, {u['ratio_median']:.2f}, "
                     f"{u['ratio_max']:.2f} | {', '.join(r['fitted_modes']) or '-'} | " if u else "- | - | - | ")
        lines.append(f"| {r['case']} | {r['size_over_h']:.3g} | {r['dofs']} ({r['estimate_dofs']}) | "
                     f"{100 * r['true_max']:.3f} % | {est} | {ratio} | {extra}{r['t_run']:.1f} | {r['t_estimate']:.1f} |")
    if result.get("grading"):
        lines += ["", "| grading | a/tip_h | dofs | K_I mean error | largest error |", "|---|---|---|---|---|"]
        for r in result["grading"]:
            lines.append(f"| {r['grading']} | {r['size_over_h']:.3g} | {r['dofs']} | {100 * r['K_I_mean_error']:+.3f} % | "
                         f"{100 * r['true_max']:.3f} % |")
    if result.get("halving"):
        lines += ["", "| case | largest error at a/5, a/10, a/20 | fall per halving |", "|---|---|---|"]
        for case, h in result["halving"].items():
            lines.append(f"| {case} | {', '.join(f'{100 * v:.3f} %' for v in h['true_max'])} | "
                         f"{', '.join(f'{v:.2f}' for v in h['falls'])} |")
    acc = result.get("accuracy")
    if acc:
        lines += ["", f"accuracy {acc['target']:g} on demos/scenes/inclined_penny.toml: sizes x "
                  f"{', '.join(f'{v:.3g}' for v in acc['size_factors'])} ({', '.join(map(str, acc['level_dofs']))} "
                  f"dofs), reached {acc['reached']}, largest estimate {100 * acc['largest_estimate']:.3f} %, largest "
                  f"true error {100 * acc['true_max']:.3f} % ({acc['seconds']:.0f} s)"]
    return "\n".join(lines) + "\n"


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/front_estimate.json"))
    ap.add_argument("--quick", action="store_true", help="the penny at a/7.07 only (a test)")
    ap.add_argument("--parts", nargs="+", default=["estimate", "grading", "accuracy"],
                    choices=["estimate", "grading", "accuracy"])
    ap.add_argument("--cases", nargs="+", default=list(MESHES), choices=list(MESHES))
    ap.add_argument("--sizes", nargs="+", type=float, default=None,
                    help="only these size / tip_h of each case's meshes (to 0.01; e.g. 5 10 14.14 20)")
    ap.add_argument("--smoothing", choices=["none", "fit"], default="none",
                    help="options.sif_smoothing of every scene (fit: K reported fitted along the front)")
    ap.add_argument("--reference", nargs=3, type=float, default=list(REFERENCE),
                    help="the surface crack's three reference meshes (a / tip_h, ratio sqrt(2)), default "
                         + " ".join(f"{v:.4g}" for v in REFERENCE))
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)

    def log(text: str) -> None:
        if not args.quiet:
            print(text, flush=True)
    result: dict = {"quick": bool(args.quick), "smoothing": args.smoothing, "true_error": TRUE_ERROR}
    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        if "estimate" in args.parts:
            result["estimate"] = estimate_part(args.cases, args.quick, folder, log, args.sizes, args.smoothing,
                                               tuple(args.reference))
            result["halving"] = halving(result["estimate"])
        if "grading" in args.parts:
            result["grading"] = grading_part(args.quick, folder, log)
        if "accuracy" in args.parts and not args.quick:
            result["accuracy"] = accuracy_part(folder, 0.01, log)
    args.json.parent.mkdir(parents=True, exist_ok=True)
    write_json(args.json, result)
    if result.get("estimate"):
        write_points(result["estimate"], args.json.parent / args.json.stem)
    log(markdown(result))
    return result


if __name__ == "__main__":
    main()
