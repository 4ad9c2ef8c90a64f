"""Handbook and exact stress intensity factors (issue 14): cracklip's K against
Tada's finite-width factors and exact Griffith fields, at two meshes.

Cases: centre crack in a strip (a/b = 0.2, 0.5; Tada), single edge notch in
tension (a/W = 0.3, 0.5; Tada) and in pure bending (a/W = 0.3; Tada, the
linear traction), inclined centre cracks (30, 60 degrees; the exact
infinite-plate field on the boundary), a pressurised Griffith crack in plane
strain and plane stress (exact field), and a crack closed by a compressive
residual stress (K = 0, the contact pressure equal to the residual stress).
Meshes: h = W / 20 and W / 40 (W the part's width), tip_h = 0.01,
enrichment radius 0.1, default SIF domains.

    /usr/bin/python3 demos/handbook.py --out results/handbook
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
from cracklip.exact.griffith import GriffithField, remote_in_crack_frame  # noqa: E402
from cracklip.fracture.handbook import centre_crack, edge_crack  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402

TIP_H = 0.01


def tada_centre_crack(a_over_b: float) -> float:
    """Tada's finite-width correction of a centre crack in a strip under
    uniform tension: K = F sigma sqrt(pi a), F = (1 - 0.025 x^2 + 0.06 x^4)
    sqrt(sec(pi x / 2)), x = a / b (b the half width); 0.1 % for any x
    (cracklip.fracture.handbook.centre_crack)."""
    return float(centre_crack(a_over_b, 2.0, "tada"))


def tada_edge_crack(a_over_w: float) -> float:
    """Tada's single-edge-notch tension factor (ends free to rotate): K = F
    sigma sqrt(pi a), F = sqrt(2 / (pi x) tan(pi x / 2)) (0.752 + 2.02 x +
    0.37 (1 - sin(pi x / 2))^3) / cos(pi x / 2), x = a / W; 0.5 % for any x
    (cracklip.fracture.handbook.edge_crack)."""
    return float(edge_crack(a_over_w, 1.0))


def tada_bending(a_over_w: float) -> float:
    """Tada's single-edge-notch pure-bending factor: K = F sigma_b sqrt(pi a),
    sigma_b = 6 M / W^2, F = 1.122 - 1.40 x + 7.33 x^2 - 13.08 x^3 + 14.0 x^4;
    0.2 % for x <= 0.6."""
    x = a_over_w
    return 1.122 - 1.40 * x + 7.33 * x ** 2 - 13.08 * x ** 3 + 14.0 * x ** 4


def plate_scene(crack, h=0.1, tip_h=0.0125, tip_radius=0.0, radius=0.1, domain=(-1.0, -3.0, 1.0, 3.0),
                stress=1.0, material=None, **options) -> cl.Scene:
    """Issue 14's "plate A": a rectangle (default [-1, 1] x [-3, 3]) under
    sigma_yy = stress on top and bottom, point supports at the bottom corners
    (both components at the left one, y at the right one), tips refined to
    tip_h, enrichment radius `radius`."""
    pts = np.asarray(crack, dtype=float)
    x0, y0, x1, y1 = domain
    refine = [(p[0], p[1], tip_h, tip_radius) for p in pts[[0, -1]] if x0 < p[0] < x1 and y0 < p[1] < y1]
    md = cl.create_rectangle(x0, y0, x1, y1, h, refine=refine)
    return cl.Scene(md, material or cl.Material(1.0, 0.3), cracks=[cl.Crack(pts)],
                    dirichlet=[cl.Dirichlet(md.nearest_node((x0, y0)), None, 0.0),
                               cl.Dirichlet(md.nearest_node((x1, y0)), 1, 0.0)],
                    tractions=[cl.Traction("top", (0.0, stress)), cl.Traction("bottom", (0.0, -stress))],
                    options=cl.Options(radius=radius, **options))


def griffith_scene(field: GriffithField, h: float, tip_h: float = TIP_H, half_width: float = 1.0,
                   **options) -> cl.Scene:
    """The exact field of a Griffith crack imposed on the boundary of a square."""
    tips = field.tips
    md = cl.create_square(h, half_width, refine=[(t[0], t[1], tip_h, 0.0) for t in tips])
    return cl.Scene(md, field.material, cracks=[cl.Crack(tips, pressure=field.pressure)],
                    dirichlet=[cl.Dirichlet(side, None, lambda x, s: field.displacement(x, s))
                               for side in ("left", "right", "bottom", "top")],
                    options=cl.Options(radius=0.1, **options))


def bending_scene(a: float, h: float) -> cl.Scene:
    """Single edge notch of depth a in [0, 1] x [-3, 3] under the bending
    stress sigma_yy = 1 - 2 x on its ends (sigma_b = 1)."""
    field = cl.LinearStress((0.0, 1.0, 0.0), gradient=((0.0, -2.0, 0.0), (0.0, 0.0, 0.0)))
    scene = plate_scene([[-0.1, 0.0], [a, 0.0]], h=h, tip_h=TIP_H, domain=(0.0, -3.0, 1.0, 3.0))
    scene.tractions = [cl.Traction("top", stress=field), cl.Traction("bottom", stress=field)]
    return scene


def residual_scene(h: float) -> cl.Scene:
    """The crack (-0.5, 0)-(0.5, 0) of plate A in a residual stress
    sigma_0,yy = -1 (with a bending sigma_0,xx = 0.3 y), its tractions on
    every side, unilateral contact: closed, pressure 1, K = 0."""
    s0 = cl.LinearStress((0.0, -1.0, 0.0), gradient=((0.0, 0.0, 0.0), (0.3, 0.0, 0.0)))
    scene = plate_scene([[-0.5, 0.0], [0.5, 0.0]], h=h, tip_h=TIP_H, stress=0.0, contact="unilateral")
    scene.initial_stress = s0
    scene.tractions = [cl.Traction(side, stress=s0) for side in ("left", "right", "top", "bottom")]
    return scene


def inclined(beta: float) -> GriffithField:
    return GriffithField(cl.Material(1.0, 0.3), a=0.5, angle=beta,
                         remote=remote_in_crack_frame((0.0, 1.0, 0.0), beta))


#: name -> (part width W, scene builder of h, (K_I, K_II) reference, reference's source)
CASES = {
    "centre crack a/b = 0.2": (2.0, lambda h: plate_scene([[-0.2, 0.0], [0.2, 0.0]], h=h, tip_h=TIP_H),
                               (tada_centre_crack(0.2) * math.sqrt(math.pi * 0.2), 0.0), "Tada"),
    "centre crack a/b = 0.5": (2.0, lambda h: plate_scene([[-0.5, 0.0], [0.5, 0.0]], h=h, tip_h=TIP_H),
                               (tada_centre_crack(0.5) * math.sqrt(math.pi * 0.5), 0.0), "Tada"),
    "edge notch tension a/W = 0.3": (1.0, lambda h: plate_scene([[-0.1, 0.0], [0.3, 0.0]], h=h, tip_h=TIP_H,
                                                                domain=(0.0, -3.0, 1.0, 3.0)),
                                     (tada_edge_crack(0.3) * math.sqrt(math.pi * 0.3), 0.0), "Tada"),
    "edge notch tension a/W = 0.5": (1.0, lambda h: plate_scene([[-0.1, 0.0], [0.5, 0.0]], h=h, tip_h=TIP_H,
                                                                domain=(0.0, -3.0, 1.0, 3.0)),
                                     (tada_edge_crack(0.5) * math.sqrt(math.pi * 0.5), 0.0), "Tada"),
    "edge notch bending a/W = 0.3": (1.0, lambda h: bending_scene(0.3, h),
                                     (tada_bending(0.3) * math.sqrt(math.pi * 0.3), 0.0), "Tada"),
    "inclined crack 30 deg": (2.0, lambda h: griffith_scene(inclined(30.0), h),
                              (inclined(30.0).K_I, inclined(30.0).K_II), "exact"),
    "inclined crack 60 deg": (2.0, lambda h: griffith_scene(inclined(60.0), h),
                              (inclined(60.0).K_I, inclined(60.0).K_II), "exact"),
    "pressurised crack, plane strain": (
        2.0, lambda h: griffith_scene(GriffithField(cl.Material(1.0, 0.3), a=0.5, pressure=1.0), h),
        (math.sqrt(math.pi * 0.5), 0.0), "exact"),
    "pressurised crack, plane stress": (
        2.0, lambda h: griffith_scene(GriffithField(cl.Material(1.0, 0.3, "stress"), a=0.5, pressure=1.0), h),
        (math.sqrt(math.pi * 0.5), 0.0), "exact"),
    "crack closed by residual stress": (2.0, residual_scene, (0.0, 0.0), "exact (K = 0)"),
}


def run(name: str, divisions: int) -> dict:
    """One case at h = W / divisions."""
    width, build, (kI, kII), source = CASES[name]
    h = width / divisions
    t0 = time.perf_counter()
    sol = cl.solve(build(h))
    ks = sol.stress_intensity_factors(0)
    scale = max(abs(kI), abs(kII)) or 1.0
    if name.startswith("crack closed"):
        scale = tada_centre_crack(0.5) * math.sqrt(math.pi * 0.5)  # the K of the same crack opened by 1
    row = {"case": name, "divisions": divisions, "h": h, "ndofs": sol.model.num_dofs, "reference": source,
           "K_I_exact": kI, "K_II_exact": kII, "K_scale": scale,
           "K_I": [k["K_I"] for k in ks], "K_II": [k["K_II"] for k in ks],
           "K_I_spread": [k["K_I_spread"] for k in ks],
           "error_I": max(abs(k["K_I"] - kI) for k in ks) / scale,
           "error_II": max(abs(abs(k["K_II"]) - abs(kII)) for k in ks) / scale,
           "warnings": [w.code for w in sol.warnings], "t_solve": time.perf_counter() - t0}
    if sol.contact:
        p = sol.contact_pressure(0)["pressure"]
        row["pressure_max_dev"] = float(np.abs(p - 1.0).max())
    return row


def markdown(rows: list[dict]) -> str:
    lines = ["| case | reference | K_I exact | h = W/20: max K error | h = W/40: max K error | dofs (W/40) |",
             "|---|---|---|---|---|---|"]
    by = {}
    for r in rows:
        by.setdefault(r["case"], {})[r["divisions"]] = r
    for name, d in by.items():
        cells = []
        for n in (20, 40):
            r = d.get(n)
            cells.append("" if r is None else f"{100 * max(r['error_I'], r['error_II']):.2f} %")
        last = d.get(40) or d[max(d)]
        lines.append(f"| {name} | {last['reference']} | {last['K_I_exact']:.5g} | {cells[0]} | {cells[1]} | "
                     f"{last['ndofs']} |")
    lines += ["", "Error: the largest |K - K_exact| over the tips and both modes, relative to the K scale "
                  "(the exact |K|; for the closed crack, the K of the same crack opened by 1)."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=pathlib.Path, default=None, help="folder for handbook.{json,md,png}")
    ap.add_argument("--json", type=pathlib.Path, default=None)
    ap.add_argument("--divisions", type=int, nargs="+", default=[20, 40], help="W / h of the meshes")
    ap.add_argument("--cases", nargs="+", default=None, help="case names (default: all)")
    args = ap.parse_args(argv)
    rows = []
    for name in args.cases or CASES:
        for n in args.divisions:
            rows.append(run(name, n))
            print(f"{name}, W/{n}: K error {100 * max(rows[-1]['error_I'], rows[-1]['error_II']):.3f} %",
                  file=sys.stderr)
    result = {"rows": rows}
    if args.json:
        write_json(args.json, result)
    if args.out:
        write_json(args.out / "handbook.json", result)
        (args.out / "handbook.md").write_text(markdown(rows))
        if __name__ == "__main__":
            plot(rows, args.out / "handbook.png")
    return result


def plot(rows: list[dict], path: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(dict.fromkeys(r["case"] for r in rows))
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for k, n in enumerate(sorted({r["divisions"] for r in rows})):
        err = [max(max(r["error_I"], r["error_II"]), 1e-8) for name in names for r in rows
               if r["case"] == name and r["divisions"] == n]
        ax.bar(np.arange(len(names)) + 0.4 * k - 0.2, err, width=0.4, label=f"h = W/{n}")
    ax.axhline(5e-3, color="k", ls="--", lw=0.8, label="0.5 %")
    ax.set_yscale("log")
    ax.set_xticks(np.arange(len(names)))
    ax.set_xticklabels(names, rotation=30, ha="right", fontsize=7)
    ax.set_ylabel("max |K - K_ref| / K scale")
    ax.set_title("cracklip K against handbook and exact values")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


if __name__ == "__main__":
    main()
