"""SIF rings: why the peers' K differ from cracklip's on the two published paths.

An independent remeshing growth code (conforming P2 elements, a new mesh per
step) lands on cracklip's drilled-plate path (final tip within 1e-3, K_I
1.85 against 1.82) and on its DCB path (within 0.005); the published
figures of code_aster and MOOSE differ from both. They take K on rings
(q = 1 within r_in, 0 beyond r_out, linear between) of fixed size, and at
these two paths the rings reach what a domain must stay clear of:

1. Drilled plate (code_aster SSLP322: rings 0.1-0.2). Grown as
   demos/growth_paths.py grows it (same function, band 0.02); at every step
   K on cracklip's domains and on code_aster's ring [0.1, 0.2] (forced:
   Options.sif_ring is not clipped), the distance from the tip to each
   hole's edge; at the final tip a sweep of radii r = 0.05 ... 0.4, as
   cracklip's plateau q of radius r (ring [r, r]) and as code_aster-shaped
   rings [r / 2, r]; and the path grown with code_aster's rings at every
   step.
2. Double cantilever beam (MOOSE: rings 0.1-0.3). Grown as
   demos/growth_paths.py grows it (default run), and again with MOOSE's
   ring [0.1, 0.3] at every step (the ring then spans the kinked, curving
   crack), with cracklip's domains of radius 0.3 (clipped at the kinks as
   they are by default: they never span them) and with cracklip's plateau
   of radius 0.3 forced through them (ring [0.3, 0.3]). How far the end
   moves, the distance to the published markers, and K_II at the first
   steps.

    /usr/bin/python3 demos/ring_study.py [--out results/rings] [--json PATH] [--no-dcb] [--quick]

Writes ring_study.json, ring_study.md, ring_sweep.csv and ring_study.png
(K_I against the ring's outer radius at the plate's final tip, the hole's
distance marked), with the DCB part dcb_rings.png (the paths), into --out
(default results/rings). The plate part takes about 10 s (the main job runs
it with --no-dcb); the DCB part 4 growths of about 40 s each.
"""
from __future__ import annotations

import argparse
import csv
import logging
import pathlib
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))

import growth_paths as gp  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.model.tip_regions import admissible_radius, node_distances, tip_domains  # noqa: E402

#: code_aster's rings in SSLP322 (CALC_G, R_INF / R_SUP) and MOOSE's in double_cantilever_crack_2d.i.
CODE_ASTER_RING = (0.1, 0.2)
MOOSE_RING = (0.1, 0.3)
#: The sweep's outer radii at the plate's final tip.
SWEEP = (0.05, 0.075, 0.1, 0.125, 0.15, 0.175, 0.2, 0.25, 0.3, 0.35, 0.4)
#: The plate's band (as growth_paths' default) and in --quick.
BAND, QUICK_BAND = 0.02, 0.03


def _k(sol, ring: tuple[float, float] | None) -> dict:
    """K_I, K_II at the tip on cracklip's domains (ring None) or on a ring."""
    k = sol.stress_intensity_factors(0, ring=ring)[0]
    return {"K_I": k["K_I"], "K_II": k["K_II"], "radius": k["radius"], "domain_clear": k["domain_clear"],
            "limited_by": k["limited_by"]}


def hole_reach(model, tip, holes: list[list[float]]) -> tuple[float, float]:
    """(distance from the tip to the nearest hole's edge, the largest radius
    whose domain cells stay clear of that hole: a domain of a larger outer
    radius has cells on the hole's edge)."""
    gap = min(gp.hole_edge_distances(tip, holes))
    return gap, admissible_radius(model, node_distances(model, np.asarray(tip)), gap)


def drilled_plate(h_band: float) -> dict:
    """The plate grown as growth_paths grows it, K on cracklip's domains and
    on code_aster's ring at every step, the sweep at the final tip, and the
    path grown with code_aster's ring."""
    holes = gp.drilled_plate_holes()
    steps: list[dict] = []
    final: dict = {}

    def on_step(k, records, sol):
        rec = records[0]
        default, ring = _k(sol, None), _k(sol, CODE_ASTER_RING)
        _, reach = hole_reach(sol.model, (rec.x, rec.y), holes)
        steps.append({"step": k, "x": rec.x, "y": rec.y, "hole_edge": gp.hole_edge_distances((rec.x, rec.y), holes),
                      "K_I": default["K_I"], "K_II": default["K_II"], "radius": default["radius"],
                      "K_I_ring": ring["K_I"], "K_II_ring": ring["K_II"], "ring_reaches_hole": CODE_ASTER_RING[1] > reach})
        final["solution"] = sol

    path = gp.drilled_plate(h_band, on_step=on_step)
    sol = final.pop("solution")
    dom = tip_domains(sol.model, 0)[0]
    tip = dom.position
    gaps = gp.hole_edge_distances(tip, holes)
    _, reach = hole_reach(sol.model, tip, holes)
    sweep = []
    for r in SWEEP:
        plateau, ring = _k(sol, (r, r)), _k(sol, (r / 2, r))
        sweep.append({"r_out": r, "K_I_plateau": plateau["K_I"], "K_II_plateau": plateau["K_II"],
                      "K_I_ring": ring["K_I"], "K_II_ring": ring["K_II"], "reaches_hole": r > reach})
    default, aster = _k(sol, None), _k(sol, CODE_ASTER_RING)
    t0 = time.perf_counter()
    grown_with_ring = gp.drilled_plate(h_band, sif_ring=CODE_ASTER_RING)
    clear = [s for s in sweep if not s["reaches_hole"]]
    return {
        "h_band": h_band, "tip": tip.tolist(), "steps": len(steps) - 1, "hole_edge": gaps,
        "nearest_hole": int(np.argmin(gaps)), "hole_distance": float(min(gaps)),
        "hole_clear_radius": reach, "admissible_radius": dom.admissible, "obstacle": dom.obstacle,
        "element_size": dom.element_size,
        "default": default, "code_aster_ring": {"ring": list(CODE_ASTER_RING), **aster},
        "ring_over_default_K_I": aster["K_I"] / default["K_I"],
        "clear_sweep_K_I_range": [min(min(s["K_I_plateau"], s["K_I_ring"]) for s in clear),
                                  max(max(s["K_I_plateau"], s["K_I_ring"]) for s in clear)],
        "sweep": sweep, "per_step": steps, "path": path["path"], "t_growth": path["t_total"],
        "grown_with_code_aster_ring": {
            "tip": grown_with_ring["tip"], "K_I_final": grown_with_ring["K_I_final"],
            "K_II_final": grown_with_ring["K_II_final"], "stop_reason": grown_with_ring["stop_reason"],
            "steps": grown_with_ring["steps"], "tip_to_hole_edge": grown_with_ring["tip_to_hole_edge"],
            "tip_moved": float(np.hypot(*np.subtract(grown_with_ring["tip"], tip))),
            "t_total": time.perf_counter() - t0},
        "code_aster_K": gp._code_aster_K(),
    }


def _end_distance(a: list, b: list) -> float:
    return float(np.hypot(*np.subtract(a[-1], b[-1])))


#: The DCB's SIF domains: (name, Options fields).
DCB_VARIANTS = (("default", {}), ("moose_ring", {"sif_ring": MOOSE_RING}),
                ("radius_0.3_clipped", {"sif_radius": 0.3}), ("plateau_0.3_forced", {"sif_ring": (0.3, 0.3)}))


def dcb(run: tuple[float, float, float, int]) -> dict:
    """The beam grown as growth_paths' run, with cracklip's domains, MOOSE's
    ring [0.1, 0.3], cracklip's domains of radius 0.3 (clipped at the kinks,
    as they are by default) and the plateau of radius 0.3 forced through
    them; the ends, the SIF domain used and K_II at the first steps."""
    runs = {}
    for name, options in DCB_VARIANTS:
        runs[name] = gp.dcb(*run, **options)
        print(f"DCB, {name}: end ({runs[name]['path'][-1][0]:.4f}, {runs[name]['path'][-1][1]:.4f}) "
              f"({runs[name]['t_total']:.1f} s)", file=sys.stderr)
    base = runs["default"]
    out = {"run": {"h": run[0], "h_tip": run[1], "da": run[2], "corrections": run[3]}, "runs": {}}
    for (name, options), r in zip(DCB_VARIANTS, runs.values()):
        out["runs"][name] = {
            "options": {k: list(v) if isinstance(v, tuple) else v for k, v in options.items()},
            "end": r["path"][-1], "end_moved": _end_distance(r["path"], base["path"]),
            "K_I_first": r["K_I"][:5], "K_II_first": r["K_II"][:5],
            "K_II_difference_first": [a - b for a, b in zip(r["K_II"][:5], base["K_II"][:5])],
            "sif_radius_range": [min(r["sif_radius"]), max(r["sif_radius"])],
            "to_belytschko_black": r["to_belytschko_black"], "path": r["path"], "t_total": r["t_total"]}
    out["moose_to_belytschko_black"] = base["moose_to_belytschko_black"]
    return out


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=pathlib.Path, default=pathlib.Path("results") / "rings",
                    help="write ring_study.json, ring_sweep.csv and ring_study.png here")
    ap.add_argument("--json", type=pathlib.Path, default=None, help="the JSON's path (default OUT/ring_study.json)")
    ap.add_argument("--no-dcb", action="store_true", help="the drilled plate only (about 10 s; the main job's)")
    ap.add_argument("--quick", action="store_true", help=f"band {QUICK_BAND} on the plate, a coarse DCB run")
    args = ap.parse_args(argv)
    logging.getLogger("cracklip").setLevel(logging.ERROR)  # forced rings warn at every step: in the results
    t0 = time.perf_counter()
    result = {"drilled_plate": drilled_plate(QUICK_BAND if args.quick else BAND)}
    p = result["drilled_plate"]
    print(f"drilled plate: K_I {p['default']['K_I']:.4f} (cracklip), {p['code_aster_ring']['K_I']:.4f} "
          f"(ring 0.1-0.2), hole {p['hole_distance']:.4f} away ({time.perf_counter() - t0:.1f} s)", file=sys.stderr)
    if not args.no_dcb:
        result["dcb"] = dcb((0.1, 0.0125, 0.05, 0) if args.quick else (0.05, 0.0125, 0.025, 2))
    result["t_total"] = time.perf_counter() - t0
    args.out.mkdir(parents=True, exist_ok=True)
    write_json(args.json or args.out / "ring_study.json", result)
    write_sweep_csv(result, args.out / "ring_sweep.csv")
    (args.out / "ring_study.md").write_text(markdown(result))
    plot(result, args.out / "ring_study.png")
    return result


def write_sweep_csv(r: dict, path: pathlib.Path) -> None:
    """The sweep at the plate's final tip, one row per outer radius (the figure's numbers)."""
    p = r["drilled_plate"]
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["r_out", "K_I_plateau", "K_II_plateau", "K_I_ring_half", "K_II_ring_half", "reaches_hole",
                    "hole_distance", "K_I_default"])
        for s in p["sweep"]:
            w.writerow([s["r_out"], f"{s['K_I_plateau']:.6g}", f"{s['K_II_plateau']:.6g}", f"{s['K_I_ring']:.6g}",
                        f"{s['K_II_ring']:.6g}", int(s["reaches_hole"]), f"{p['hole_distance']:.6g}",
                        f"{p['default']['K_I']:.6g}"])


def markdown(r: dict) -> str:
    p = r["drilled_plate"]
    a, d = p["code_aster_ring"], p["default"]
    g = p["grown_with_code_aster_ring"]
    ca = p["code_aster_K"]
    out = ["## SIF rings on the published paths (`demos/ring_study.py`)", "",
           f"Drilled plate, final tip ({p['tip'][0]:.4f}, {p['tip'][1]:.4f}) after {p['steps']} steps (band "
           f"{p['h_band']:g}), {p['hole_distance']:.4f} from the middle hole's edge (domains of radius up to "
           f"{p['hole_clear_radius']:.4f} stay clear of it; cracklip's stay within {p['admissible_radius']:.4f}, "
           f"{p['obstacle']}): K_I {d['K_I']:.4f}, K_II {d['K_II']:.4f} on cracklip's domains "
           f"(radius {d['radius']:.4f}); on code_aster's ring [0.1, 0.2] K_I {a['K_I']:.4f}, K_II {a['K_II']:.4f} "
           f"({a['K_I'] / d['K_I']:.3f} x); code_aster's own values K1 {min(c['K1'] for c in ca):.2f}-"
           f"{max(c['K1'] for c in ca):.2f}. Grown with that ring at every step: tip "
           f"({g['tip'][0]:.4f}, {g['tip'][1]:.4f}), {g['tip_moved']:.4f} from cracklip's, K_I {g['K_I_final']:.4f}.",
           "", "| r_out | K_I, plateau r | K_I, ring [r/2, r] | K_II, plateau | K_II, ring | reaches the hole |",
           "|---|---|---|---|---|---|"]
    for s in p["sweep"]:
        out.append(f"| {s['r_out']:g} | {s['K_I_plateau']:.4f} | {s['K_I_ring']:.4f} | {s['K_II_plateau']:.4f} | "
                   f"{s['K_II_ring']:.4f} | {'yes' if s['reaches_hole'] else 'no'} |")
    if "dcb" in r:
        d = r["dcb"]
        out += ["", f"Double cantilever beam (element {d['run']['h']:g}, {d['run']['h_tip']:g} along the path, da "
                f"{d['run']['da']:g}, {d['run']['corrections']} corrector solves), grown with each SIF domain at every "
                "step:", "",
                "| SIF domain | end | end moved | K_II at steps 0-4 | max / mean distance to Belytschko-Black |",
                "|---|---|---|---|---|"]
        for name, b in d["runs"].items():
            dist = b["to_belytschko_black"]
            out.append(f"| {name} {b['options'] or ''} | ({b['end'][0]:.4f}, {b['end'][1]:.4f}) | {b['end_moved']:.4f} | "
                       + ", ".join(f"{k:.2f}" for k in b["K_II_first"])
                       + f" | {dist['max']:.3f} / {dist['mean']:.3f} |")
        out += ["", f"MOOSE's own path (digitised): max {d['moose_to_belytschko_black']['max']:.3f} from the markers."]
    return "\n".join(out) + "\n"


def plot(r: dict, path: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = r["drilled_plate"]
    sw = p["sweep"]
    rr = [s["r_out"] for s in sw]
    fig, ax = plt.subplots(figsize=(7, 4.6))
    ax.plot(rr, [s["K_I_plateau"] for s in sw], "o-", label="cracklip's plateau q of radius r (ring [r, r])")
    ax.plot(rr, [s["K_I_ring"] for s in sw], "s-", label="ring [r/2, r] (code_aster's shape)")
    ax.axhline(p["default"]["K_I"], color="k", lw=0.8, ls=":",
               label=f"cracklip's domains (radius {p['default']['radius']:.3f}): {p['default']['K_I']:.3f}")
    ax.axvline(p["hole_distance"], color="r", lw=1.0,
               label=f"tip to the middle hole's edge: {p['hole_distance']:.3f}")
    ax.axvspan(p["hole_clear_radius"], max(rr) * 1.02, color="r", alpha=0.06,
               label=f"domain cells on the hole's edge (r > {p['hole_clear_radius']:.3f})")
    a = p["code_aster_ring"]
    ax.plot([0.2], [a["K_I"]], "k*", ms=12, label=f"code_aster's ring [0.1, 0.2]: {a['K_I']:.3f}")
    g = p["grown_with_code_aster_ring"]
    ax.plot([0.2], [g["K_I_final"]], "D", color="m", ms=7,
            label=f"ring [0.1, 0.2], path grown with it too: {g['K_I_final']:.3f}")
    k1 = [c["K1"] for c in p["code_aster_K"]]
    ax.errorbar([0.207], [(min(k1) + max(k1)) / 2], yerr=[[(max(k1) - min(k1)) / 2]], fmt="none", ecolor="g",
                capsize=5, lw=2, label=f"code_aster's SSLP322 values {min(k1):.2f}-{max(k1):.2f}")
    ax.set_xlabel("outer radius of the SIF domain r (length)")
    ax.set_ylabel("K_I at the final tip (force / length^1.5)")
    ax.set_xlim(0.0, max(rr) * 1.02)
    ax.set_title(f"Drilled plate after {p['steps']} steps: K_I against the SIF ring")
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)
    if "dcb" not in r:
        return
    _, bb = gp.read_data("dcb_belytschko_black_path.csv")
    _, moose = gp.read_data("dcb_moose_path.csv")
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(bb[:, 1], bb[:, 2], "ks", ms=5, label="Belytschko & Black 1999 (digitised)")
    ax.plot(moose[:, 1], moose[:, 2], "c-", lw=2, label="MOOSE 2D, rings 0.1-0.3 (digitised)")
    for name, b in r["dcb"]["runs"].items():
        q = np.asarray(b["path"])
        ax.plot(q[:, 0], q[:, 1], ".-", ms=3, lw=1, label=f"cracklip, {name} (end moved {b['end_moved']:.3f})")
    ax.set_xlim(3.8, 5.4)
    ax.set_ylim(-0.7, 1.0)
    ax.set_aspect("equal")
    ax.set_xlabel("x (length)")
    ax.set_ylabel("y (length)")
    ax.set_title("Double cantilever beam: the path with each SIF domain")
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(path.with_name("dcb_rings.png"), dpi=150)
    plt.close(fig)


if __name__ == "__main__":
    main()
