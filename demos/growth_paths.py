"""Published crack paths (issue 17, benchmark 6), and the check behind them.

1. The drilled plate of Bittencourt, Wawrzynek, Ingraffea and Sousa (1996)
   as set up in code_aster's test SSLP322: `demos/scenes/drilled_plate.toml`
   (beam 20 x 8 on a pin and a roller, unit force at the top centre, three
   holes of radius 0.25 at x = 6, edge crack at x = 5 of length 1.5), 35
   steps of 0.1 by maximum hoop stress, on three meshes. Published data: no
   path coordinates exist in any source we found (the experiments are shown
   only as figures); code_aster's test stores K1, K2 after 35 steps
   (`demos/data/sslp322_code_aster_K.csv`). We report the path (it is drawn
   to the column of holes, passes the bottom hole and runs toward the middle
   one), its mesh convergence, and K after 35 steps beside code_aster's.
2. The double cantilever beam of Belytschko and Black (1999, Fig. 9) as set
   up in MOOSE's test double_cantilever_crack_2d.i: beam [0, 11.8] x [-1.97,
   1.97], crack (0, 0) -> (3.94, 0) -> 0.3 further at 5.71 degrees, right
   edge clamped, tractions +-1000 on the top and bottom edges for x < 0.1967,
   E = 3e7, nu = 0.3, plane strain. Published data: the Belytschko-Black
   path digitised from MOOSE's documentation figure, and MOOSE's own path
   from the same figure (`demos/data/dcb_*.csv`, sources in their headers).
   The path is unstable (the T-stress is positive), so it amplifies every
   error; we report the distance between the paths for several meshes,
   increments and the corrector.
3. The check that makes the comparison mean something: K_II of a slightly
   kinked crack against Cotterell and Rice's first-order result, k_II =
   (theta / 2) K_I - sqrt(8 l / pi) T theta (the T-stress term is what turns
   the DCB crack): a Griffith crack (a = 1, sigma_yy = 1) with a kink of 5.71
   degrees and length l = 0.05 under sigma_xx = 0 and 2 (T = -1, +1).

    /usr/bin/python3 demos/growth_paths.py --out results/growth [--quick | --study]

The default (the main job's) grows the plate with a band of 0.02 and the
beam with da = 0.025 and the corrector (within 0.003 of the finest run of
--study).
"""
from __future__ import annotations

import argparse
import dataclasses
import logging
import math
import pathlib
import sys
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

import cracklip as cl  # noqa: E402
from cracklip.scene.growth import Growth
from cracklip.analysis.growth import grow  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.io.scene_file import build_scene, read_document  # noqa: E402

DATA = pathlib.Path(__file__).resolve().parent / "data"
DRILLED_PLATE = pathlib.Path(__file__).resolve().parent / "scenes" / "drilled_plate.toml"

# The double cantilever beam (MOOSE's set-up of Belytschko and Black's Fig. 9).
DCB_L, DCB_HALF_W, DCB_LOADED = 11.8, 1.97, 0.1967
DCB_CRACK = [[-0.1, 0.0], [3.94, 0.0], [3.94 + 0.3 * math.cos(math.radians(5.71)), 0.3 * math.sin(math.radians(5.71))]]
DCB_GROWTH_LENGTH = 1.25  # beyond the initial tip: the published markers end 1.2 further


def read_data(name: str) -> tuple[list[str], np.ndarray]:
    """A CSV of demos/data: its columns (after the # header) as names and rows."""
    lines = [ln for ln in (DATA / name).read_text().splitlines() if ln and not ln.startswith("#")]
    names = lines[0].split(",")
    return names, np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])


def distance_to_polyline(p: np.ndarray, poly: np.ndarray) -> float:
    """Distance from the point p to the polyline poly (n, 2)."""
    a, b = poly[:-1], poly[1:]
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
    return float(np.min(np.linalg.norm(a + t[:, None] * d - p, axis=1)))


def path_distance(reference: np.ndarray, path: np.ndarray) -> dict:
    """The distances of the reference points that lie within the path's
    extent in x (the published markers beyond our last tip are not
    compared) to the path: max, mean, and at the last compared point."""
    pts = reference[reference[:, 0] <= path[-1, 0] + 1e-12]
    d = np.array([distance_to_polyline(p, path) for p in pts])
    return {"max": float(d.max()), "mean": float(d.mean()), "last": float(d[-1]), "compared_points": int(len(d))}


# ----------------------------------------------------------------------------------------------- drilled plate
def drilled_plate_holes() -> list[list[float]]:
    """The plate's holes [[cx, cy, r], ...] (bottom, middle, top)."""
    return read_document(DRILLED_PLATE)["mesh"]["holes"]


def hole_edge_distances(p, holes: list[list[float]]) -> list[float]:
    """Distance from the point p to each hole's edge."""
    return [float(math.hypot(p[0] - cx, p[1] - cy) - r) for cx, cy, r in holes]


def drilled_plate(h_band: float, on_step=None, **options) -> dict:
    """The scene file with its refinement band at h_band, grown 35 steps.
    on_step(k, records, solution) is called after every step's solve (see
    cracklip.analysis.growth.grow); options: Options fields to override
    (sif_ring=(0.1, 0.2): K at every step on code_aster's ring)."""
    doc = read_document(DRILLED_PLATE)
    for r in doc["mesh"]["refine"]:
        r["h"] = h_band
    sf = build_scene(doc, base_dir=DRILLED_PLATE.parent, path=DRILLED_PLATE)
    scene = dataclasses.replace(sf.scene, options=dataclasses.replace(sf.scene.options, **options))
    t0 = time.perf_counter()
    res = grow(scene, sf.growth, on_step=on_step)
    t = time.perf_counter() - t0
    pts = res.cracks[0].points
    tip = pts[-1]
    holes = doc["mesh"]["holes"]
    gaps = hole_edge_distances(tip, holes)
    # closest approach of the path to each hole's edge (beyond the initial crack)
    grown = pts[pts[:, 1] > 1.5]
    passing = [float(np.min(np.hypot(grown[:, 0] - cx, grown[:, 1] - cy)) - r) for cx, cy, r in holes]
    last = res.records[-1][0]
    return {"h_band": h_band, "steps": len(res.records) - 1, "stop_reason": res.stop_reason, "path": pts.tolist(),
            "tip": tip.tolist(), "tip_to_hole_edge": gaps, "closest_to_hole_edge": passing,
            "K_I": [st[0].K_I for st in res.records], "K_II": [st[0].K_II for st in res.records],
            "length": [st[0].length for st in res.records], "K_I_final": last.K_I, "K_II_final": last.K_II,
            "steps_with_warnings": sum(1 for w in res.step_warnings if w), "t_total": t}


# ----------------------------------------------------------------------------------------------- DCB
def dcb_scene(h: float, h_tip: float, **options) -> cl.Scene:
    """The beam with an element size h, refined to h_tip along the expected
    path (a band from the kink up to (5.2, 1.1)); options: Options fields to
    set (sif_ring=(0.1, 0.3): K on MOOSE's ring instead of cracklip's domains)."""
    band = [(3.9, 0.0, h_tip, 1.0, 4.6, 0.15), (4.6, 0.15, h_tip, 1.0, 5.2, 1.1)]
    md = cl.create_rectangle(0.0, -DCB_HALF_W, DCB_L, DCB_HALF_W, h, refine=band,
                             embed_points=[(DCB_LOADED, DCB_HALF_W), (DCB_LOADED, -DCB_HALF_W)])

    def end_load(sign: float):
        return lambda x: np.stack([0.0 * x[:, 0], np.where(x[:, 0] < DCB_LOADED, sign * 1000.0, 0.0)], axis=1)

    return cl.Scene(md, cl.Material(3e7, 0.3), cracks=[cl.Crack(DCB_CRACK, name="DCB crack")],
                    dirichlet=[cl.Dirichlet("right", None, 0.0)],
                    tractions=[cl.Traction("top", end_load(1.0)), cl.Traction("bottom", end_load(-1.0))],
                    options=cl.Options(radius=max(0.05, 3 * h_tip), **options))


def dcb(h: float, h_tip: float, da: float, corrections: int, **options) -> dict:
    """The beam's crack grown by da to 1.25 beyond its initial tip, compared
    with the Belytschko-Black markers and MOOSE's path (options: see dcb_scene)."""
    _, bb = read_data("dcb_belytschko_black_path.csv")
    _, moose = read_data("dcb_moose_path.csv")
    bb, moose = bb[:, 1:], moose[:, 1:]
    t0 = time.perf_counter()
    res = grow(dcb_scene(h, h_tip, **options), Growth(da=da, steps=int(round(DCB_GROWTH_LENGTH / da)),
                                                     corrections=corrections))
    t = time.perf_counter() - t0
    pts = res.cracks[0].points
    path = pts[pts[:, 0] >= 3.94 - 1e-9]
    first = res.records[0][0]
    return {"h": h, "h_tip": h_tip, "da": da, "corrections": corrections, "steps": len(res.records) - 1,
            "path": path.tolist(), "K_I_initial": first.K_I, "K_II_initial": first.K_II,
            "kink_initial_deg": first.kink_deg, "K_I": [st[0].K_I for st in res.records],
            "K_II": [st[0].K_II for st in res.records], "sif_radius": [st[0].sif_radius for st in res.records],
            "to_belytschko_black": path_distance(bb[1:], path),
            "moose_to_belytschko_black": path_distance(bb[1:], moose), "t_total": t,
            "solves": int(sum(res.step_solves))}


# ----------------------------------------------------------------------------------------------- Cotterell-Rice
def kinked_crack_check(l: float = 0.05, theta_deg: float = 5.71, h_tip: float = 0.005) -> dict:
    """K_II at the tip of a kink (angle theta, length l) off the right tip of
    a Griffith crack (a = 1, sigma_yy = 1 on [-10, 10]^2) under sigma_xx = 0
    and 2 (T = -1 and +1), against Cotterell and Rice (1980): k_II = (theta /
    2) K_I - sqrt(8 l / pi) T theta to first order in theta."""
    th = math.radians(theta_deg)
    tip = (1.0 + l * math.cos(th), l * math.sin(th))
    rows = []
    for sxx in (0.0, 2.0):
        md = cl.create_rectangle(-10, -10, 10, 10, 0.5, refine=[(-1.2, 0.0, 0.05, 2.0, 1.2, 0.0),
                                                                 (tip[0], tip[1], h_tip, 0.3)])
        scene = cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-1.0, 0.0], [1.0, 0.0], list(tip)])],
                         dirichlet=[cl.Dirichlet(md.nearest_node((-10, -10)), None, 0.0),
                                    cl.Dirichlet(md.nearest_node((10, -10)), 1, 0.0)],
                         tractions=[cl.Traction(t, stress=(sxx, 1.0, 0.0)) for t in ("top", "bottom", "left", "right")],
                         options=cl.Options(radius=min(0.02, l / 3)))
        k = max(cl.solve(scene).stress_intensity_factors(0), key=lambda k: k["x"])
        rows.append({"sigma_xx": sxx, "T": sxx - 1.0, "K_I": k["K_I"], "K_II": k["K_II"],
                     "K_II_spread": k["K_II_spread"]})
    t_term = -(rows[1]["K_II"] - rows[0]["K_II"]) / 2
    k_term = (rows[1]["K_II"] + rows[0]["K_II"]) / 2
    K_I = (rows[0]["K_I"] + rows[1]["K_I"]) / 2
    return {"l": l, "theta_deg": theta_deg, "rows": rows,
            "T_term": t_term, "T_term_first_order": math.sqrt(8 * l / math.pi) * th,
            "K_term": k_term, "K_term_first_order": th / 2 * K_I}


# ----------------------------------------------------------------------------------------------- driver
def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=pathlib.Path, default=None, help="write growth_paths.json, .md and the PNGs here")
    ap.add_argument("--quick", action="store_true", help="coarse, one run per benchmark (a smoke test)")
    ap.add_argument("--study", action="store_true", help="meshes, increments and the corrector (about 6 minutes)")
    args = ap.parse_args(argv)
    logging.getLogger("cracklip").setLevel(logging.ERROR)  # per-step model warnings: counted in the results
    t0 = time.perf_counter()
    bands = (0.03,) if args.quick else (0.03, 0.02, 0.012) if args.study else (0.02,)
    plates = [drilled_plate(h) for h in bands]
    print(f"drilled plate: {len(plates)} meshes, {time.perf_counter() - t0:.1f} s", file=sys.stderr)
    # (element size, along the path, increment, corrector solves)
    runs = [(0.1, 0.0125, 0.05, 0)] if args.quick else \
        [(0.25, 0.0125, 0.05, 0), (0.05, 0.0125, 0.05, 0), (0.05, 0.0125, 0.0125, 0), (0.1, 0.0125, 0.05, 2),
         (0.05, 0.0125, 0.025, 2), (0.05, 0.00625, 0.025, 2)] if args.study else [(0.05, 0.0125, 0.025, 2)]
    beams = []
    for r in runs:
        beams.append(dcb(*r))
        b = beams[-1]
        print(f"DCB h {r[0]}, tip {r[1]}, da {r[2]}, corrections {r[3]}: largest distance to the "
              f"Belytschko-Black path {b['to_belytschko_black']['max']:.3f} ({b['t_total']:.1f} s)", file=sys.stderr)
    result = {"drilled_plate": plates, "code_aster_K": _code_aster_K(), "dcb": beams, "kinked_crack": kinked_crack_check(),
              "mode": "quick" if args.quick else "study" if args.study else "default", "t_total": time.perf_counter() - t0}
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        write_json(args.out / "growth_paths.json", result)
        (args.out / "growth_paths.md").write_text(markdown(result))
        plot(result, args.out)
    return result


def _code_aster_K() -> list[dict]:
    lines = [ln for ln in (DATA / "sslp322_code_aster_K.csv").read_text().splitlines() if ln and ln[0] != "#"]
    return [{"source": s, "K1": float(k1), "K2": float(k2)} for s, k1, k2 in (ln.split(",") for ln in lines[1:])]


def markdown(r: dict) -> str:
    p = r["drilled_plate"][-1]
    ca = r["code_aster_K"]
    out = ["## Published crack paths (`demos/growth_paths.py`)", "",
           "Drilled plate (Bittencourt et al. 1996; code_aster SSLP322 set-up, `demos/scenes/drilled_plate.toml`), "
           "35 steps of 0.1, maximum hoop stress. No published path coordinates exist (the experiments are "
           "figures only); code_aster stores K after 35 steps.", "",
           "| band element | tip after 35 steps | tip to middle hole's edge | closest to bottom hole's edge | "
           "K_I | K_II | s |", "|---|---|---|---|---|---|---|"]
    for q in r["drilled_plate"]:
        out.append(f"| {q['h_band']:g} | ({q['tip'][0]:.4f}, {q['tip'][1]:.4f}) | {q['tip_to_hole_edge'][1]:.3f} | "
                   f"{q['closest_to_hole_edge'][0]:.3f} | {q['K_I_final']:.4f} | {q['K_II_final']:.4f} | "
                   f"{q['t_total']:.1f} |")
    out += ["", "code_aster after 35 steps (its own regression values, three versions): K1 "
            + ", ".join(f"{c['K1']:.4f}" for c in ca) + "; K2 " + ", ".join(f"{c['K2']:.4f}" for c in ca) + ".", "",
            "Double cantilever beam (Belytschko and Black 1999, Fig. 9; MOOSE's set-up), grown 1.25 beyond the "
            "initial kink; distance of the digitised Belytschko-Black markers to our path "
            f"(MOOSE's own path from the same figure: max {r['dcb'][0]['moose_to_belytschko_black']['max']:.3f}).",
            "", "| element (far / path) | da | corrector solves | K_I initial | K_II initial | max distance | "
            "mean distance | s |", "|---|---|---|---|---|---|---|---|"]
    for b in r["dcb"]:
        d = b["to_belytschko_black"]
        out.append(f"| {b['h']:g} / {b['h_tip']:g} | {b['da']:g} | {b['corrections']} | {b['K_I_initial']:.1f} | "
                   f"{b['K_II_initial']:.2f} | {d['max']:.3f} | {d['mean']:.3f} | {b['t_total']:.1f} |")
    k = r["kinked_crack"]
    out += ["", f"Kinked crack (kink {k['theta_deg']} degrees, length {k['l']}) against Cotterell-Rice: T-stress "
            f"term of K_II {k['T_term']:.5f} (first order {k['T_term_first_order']:.5f}), K_I term "
            f"{k['K_term']:.5f} (first order {k['K_term_first_order']:.5f}).", ""]
    return "\n".join(out)


def plot(r: dict, out: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    doc = read_document(DRILLED_PLATE)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [1.6, 1]})
    for ax, zoom in zip(axes, (False, True)):
        ax.plot([0, 20, 20, 0, 0], [0, 0, 8, 8, 0], "k-", lw=1)
        for cx, cy, rad in doc["mesh"]["holes"]:
            ax.add_patch(plt.Circle((cx, cy), rad, fill=False, color="k"))
        ax.plot([1, 19], [0, 0], "k^", ms=8)
        ax.annotate("", xy=(10, 8), xytext=(10, 9.2), arrowprops={"arrowstyle": "->"})
        for q in r["drilled_plate"]:
            path = np.asarray(q["path"])
            ax.plot(path[:, 0], np.maximum(path[:, 1], 0.0), "-", lw=1.2, label=f"band element {q['h_band']:g}")
        ax.set_aspect("equal")
        if zoom:
            ax.set_xlim(4.3, 7.0)
            ax.set_ylim(0.0, 5.3)
            ax.legend(fontsize=8, loc="lower right")
        else:
            ax.set_xlim(-0.5, 20.5)
            ax.set_ylim(-0.6, 9.4)
    axes[0].set_title("Drilled plate (Bittencourt et al. 1996; SSLP322): 35 steps of 0.1")
    axes[1].set_title("near the holes")
    fig.tight_layout()
    fig.savefig(out / "drilled_plate_path.png", dpi=150)
    plt.close(fig)

    _, bb = read_data("dcb_belytschko_black_path.csv")
    _, moose = read_data("dcb_moose_path.csv")
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(bb[:, 1], bb[:, 2], "ks", ms=5, label="Belytschko & Black 1999 (digitised)")
    ax.plot(moose[:, 1], moose[:, 2], "c-", lw=2, label="MOOSE 2D (digitised)")
    for b in r["dcb"]:
        path = np.asarray(b["path"])
        ax.plot(path[:, 0], path[:, 1], ".-", ms=3, lw=1,
                label=f"cracklip h {b['h']:g}/{b['h_tip']:g}, da {b['da']:g}, corr. {b['corrections']}")
    ax.set_xlim(3.8, 5.4)
    ax.set_ylim(-0.05, 1.0)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_title("Double cantilever beam (Belytschko & Black Fig. 9, kink 5.71 deg)")
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(out / "dcb_path.png", dpi=150)
    plt.close(fig)


if __name__ == "__main__":
    main()
