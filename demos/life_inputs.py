"""Fatigue life from the inputs engineers bring, at compiled speed (issue 38).

1. beta_table_life: a centre crack in a plate W = 100 mm wide whose
   Feddersen beta = sqrt(sec(pi a / W)) is read from a file
   (demos/data/life/centre_crack_feddersen.csv, 401 sizes), Paris C = 3e-15
   mm/cycle, m = 3 (MPa sqrt(mm)), 0 -> 80 MPa, a = 2 -> 30 mm. Exact:
   N = int_a0^a1 da / (C (dS sqrt(pi a sec(pi a / W)))^m), no closed form
   for the secant, so evaluated independently of cracklip by adaptive
   quadrature (scipy.integrate.quad, relative tolerance 1e-12).
2. dadn_file_life: a crack in an infinite plate (beta = 1 from a file),
   its da/dN a table file sampled from the same Paris law at R = 0 and 0.5
   (log-log interpolation of a Paris curve is exact), 10 -> 100 MPa (R =
   0.1), a = 1 -> 20 mm. Closed form N = [a^(1 - m/2)] / ((1 - m/2) C (dS
   sqrt(pi))^m).
3. turning_points: the ASTM E1049-85 example history as a plain file (one
   value per line) in a [spectrum] block, counted once (residue as half
   cycles): the standard's cycle table (range, count) (3, 0.5), (4, 1.5),
   (6, 0.5), (8, 1.0), (9, 0.5) (E1049-85 Fig. 6 / section 5.4.4; the same
   table in qats' docs for E1049 (2011) and in several open ports' tests).
4. speed on one core: the cycle-by-cycle kernel with Wheeler retardation
   (a Griffith crack, 1e5 random cycles per pass, 2e7 cycles per run) and
   rainflow of 1e7 random turning points (a repeated history). Rates are per
   CPU second (time.process_time: the core this process got; other jobs
   share the machine) and per wall second; best of three runs.
5. hole (--hole): the spectrum scene demos/scenes/hole_crack_spectrum.toml
   grown by `cracklip grow --beta-table`, then its life through that beta
   table (`cracklip life`, geometry beta_table) to grow's failure size.

    /usr/bin/python3 demos/life_inputs.py --json results/life_inputs.json
"""
from __future__ import annotations

import argparse
import logging
import math
import pathlib
import sys
import tempfile
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

from cracklip.analysis.table_life import create_table_life, run_life  # noqa: E402
from cracklip.fracture.laws import Paris  # noqa: E402
from cracklip.fracture.life import CycleTable, LifeLaw  # noqa: E402
from cracklip.fracture.life_kernels import KTable, integrate_cycles, new_run  # noqa: E402
from cracklip.fracture.rainflow import count_cycles  # noqa: E402
from cracklip.fracture.retardation import Retardation  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.io.life_file import build_life  # noqa: E402

DATA = HERE / "data" / "life"
C, M, W = 3e-15, 3.0, 100.0
E1049_TABLE = [(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)]


def life_of(doc: dict):
    lf = build_life(doc, DATA)
    tl = create_table_life(lf.life, lf.material, lf.spectrum, lf.units, lf.table)
    return tl, run_life(tl)


def beta_table_life() -> dict:
    from scipy.integrate import quad
    a0, a1, S = 2.0, 30.0, 80.0
    doc = {"units": {"length": "mm", "stress": "MPa"},
           "material": {"fatigue": {"law": "paris", "C": C, "m": M, "closure": "none"}},
           "spectrum": {"blocks": [{"points": [0.0, 1.0]}]},
           "life": {"geometry": "beta_table", "table": "centre_crack_feddersen.csv", "a0": a0, "a_final": a1,
                    "reference_stress": {"default": S}}}
    tl, out = life_of(doc)

    def per_cycle(a: float) -> float:
        return 1.0 / (C * (S * math.sqrt(math.pi * a / math.cos(math.pi * a / W))) ** M)
    exact, err = quad(per_cycle, a0, a1, epsabs=0.0, epsrel=1e-12, limit=200)
    return {"N": out.cycles, "N_exact": exact, "rel_error": abs(out.cycles / exact - 1.0), "quad_error": err,
            "a_end": out.rows[-1]["a"], "method": out.method, "table_sizes": int(tl.table.a.size)}


def dadn_file_life() -> dict:
    a0, a1, smin, smax = 1.0, 20.0, 10.0, 100.0
    doc = {"units": {"length": "mm", "stress": "MPa"},
           "material": {"fatigue": {"law": "tabular", "table_file": "paris_dadn.csv", "closure": "none"}},
           "spectrum": {"blocks": [{"points": [smin / smax, 1.0]}]},
           "life": {"geometry": "beta_table", "table": "griffith_beta.csv", "a0": a0, "a_final": a1,
                    "reference_stress": {"default": smax}}}
    tl, out = life_of(doc)
    dS = smax - smin
    exact = (a1 ** (1 - M / 2) - a0 ** (1 - M / 2)) / ((1 - M / 2) * C * (dS * math.sqrt(math.pi)) ** M)
    return {"N": out.cycles, "N_exact": exact, "rel_error": abs(out.cycles / exact - 1.0), "law": tl.law.law.describe()}


def turning_points() -> dict:
    doc = {"material": {"fatigue": {"law": "paris", "C": C, "m": M, "closure": "none"}},
           "spectrum": {"residue": "half", "blocks": [{"file": "e1049.txt"}]},
           "life": {"geometry": "beta_table", "table": "griffith_beta.csv", "a0": 1.0}}
    lf = build_life(doc, DATA)
    pts, _ = lf.spectrum.pass_points()
    got = count_cycles(pts[:, 0], "rainflow", repeated=False).table(pts[:, 0])
    tl = create_table_life(lf.life, lf.material, lf.spectrum, lf.units, lf.table)
    F = tl.load.F[:, 0]
    through_life = {}
    for lo, hi, n in zip(tl.cycles.lo, tl.cycles.hi, tl.cycles.count):
        through_life[float(F[hi] - F[lo])] = through_life.get(float(F[hi] - F[lo]), 0.0) + float(n)
    life_table = sorted(through_life.items())
    return {"ok": got == E1049_TABLE and life_table == E1049_TABLE, "points": pts[:, 0].tolist(),
            "cycles": [list(x) for x in got], "cycles_in_the_life": [list(x) for x in life_table],
            "reference": [list(x) for x in E1049_TABLE]}


def speed(cycles: float = 2e7, points: int = 10_000_000, repeats: int = 3) -> dict:
    rng = np.random.default_rng(38)
    n = 100_000
    F = np.r_[0.0, rng.uniform(50.0, 120.0, n)][:, None]
    ct = CycleTable(np.zeros(n, int), np.arange(1, n + 1), np.ones(n))
    table = KTable(1, np.array([1e-3, 1.0]), np.sqrt(np.pi * np.array([[1e-3], [1.0]])), ("default",))
    law = LifeLaw(Paris(1e-13, 3.0), "none")
    ret = Retardation("wheeler", 400.0, 2.0, 1.5)
    best_cpu = best_wall = 0.0
    for _ in range(repeats):
        c0, w0 = time.process_time(), time.perf_counter()
        run = integrate_cycles(table, F, ct, law, ret, new_run([5e-3]), [1.0], max_cycles=cycles)
        c1, w1 = time.process_time(), time.perf_counter()
        best_cpu = max(best_cpu, run["cycles"] / max(c1 - c0, 1e-9))
        best_wall = max(best_wall, run["cycles"] / max(w1 - w0, 1e-9))
    x = rng.normal(size=points)
    rf_cpu = rf_wall = 0.0
    for _ in range(repeats):
        c0, w0 = time.process_time(), time.perf_counter()
        counted = count_cycles(x, "rainflow", repeated=True)
        c1, w1 = time.process_time(), time.perf_counter()
        rf_cpu = max(rf_cpu, points / max(c1 - c0, 1e-9))
        rf_wall = max(rf_wall, points / max(w1 - w0, 1e-9))
    return {"cycles_per_s": best_cpu, "rainflow_points_per_s": rf_cpu, "cycles_per_wall_s": best_wall,
            "rainflow_points_per_wall_s": rf_wall, "cycles_per_run": run["cycles"], "a_after_run": run["size"][0],
            "rainflow_points": points, "rainflow_cycles": int(len(counted)), "clock": "CPU time (time.process_time)"}


def hole(steps: int = 40) -> dict:
    """grow with --beta-table on the spectrum scene, then the life through that table."""
    import json
    from cracklip import cli
    scene = HERE / "scenes" / "hole_crack_spectrum.toml"
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp)
        t0 = time.perf_counter()
        assert cli.main(["grow", str(scene), "--out", str(out / "grow"), "--beta-table", "--quiet",
                         "--set", "outputs.vtu=false", "--set", "outputs.png=false",
                         "--set", f"growth.steps={steps}"]) == 0
        t_grow = time.perf_counter() - t0
        g = json.loads((out / "grow" / "results.json").read_text())["life"]
        a_end = g["failure"]["a"] if g["failure"] else g["steps"][-1]["tips"][0]["a"]
        t0 = time.perf_counter()
        assert cli.main(["life", str(scene), "--out", str(out / "life"), "--quiet", "--no-png",
                         "--set", 'life.geometry="beta_table"', "--set", f'life.table="{out / "grow" / "beta.csv"}"',
                         "--set", "life.a0=1.5", "--set", f"life.a_final={a_end!r}"]) == 0
        t_life = time.perf_counter() - t0
        lf = json.loads((out / "life" / "results.json").read_text())["life"]
    return {"grow_passes": g["passes"], "life_passes": lf["passes"], "grow_blocks": g["blocks"],
            "life_blocks": lf["blocks"], "rel_difference": abs(lf["passes"] / g["passes"] - 1.0), "a_end": a_end,
            "grow_stop": g["failure"]["criterion"] if g["failure"] else "growth.steps", "seconds_grow": t_grow,
            "seconds_life": t_life}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=pathlib.Path, default=None)
    ap.add_argument("--quick", action="store_true", help="smaller speed runs (smoke test)")
    ap.add_argument("--hole", action="store_true", help="also grow the hole-crack spectrum scene and compare its "
                    "life through its own beta table (about 10-30 s)")
    args = ap.parse_args(argv)
    logging.getLogger("cracklip").setLevel(logging.ERROR)
    t0 = time.perf_counter()
    r: dict = {"beta_table_life": beta_table_life(), "dadn_file_life": dadn_file_life(),
               "turning_points": turning_points(),
               "speed": speed(2e6, 1_000_000, 1) if args.quick else speed()}
    if args.hole:
        r["hole"] = hole(3 if args.quick else 40)
    r["seconds"] = time.perf_counter() - t0
    b, d, s = r["beta_table_life"], r["dadn_file_life"], r["speed"]
    print(f"beta table life {b['N']:.8g} cycles (exact {b['N_exact']:.8g}, {b['rel_error']:.1e}); da/dN file life "
          f"{d['N']:.8g} (exact {d['N_exact']:.8g}, {d['rel_error']:.1e}); E1049 file ok: {r['turning_points']['ok']}; "
          f"{s['cycles_per_s']:.3g} Wheeler cycles and {s['rainflow_points_per_s']:.3g} rainflow points per CPU second "
          f"({s['cycles_per_wall_s']:.3g}, {s['rainflow_points_per_wall_s']:.3g} per wall second)", file=sys.stderr)
    if "hole" in r:
        h = r["hole"]
        print(f"hole scene: grow {h['grow_passes']:.8g} passes, life through its beta table {h['life_passes']:.8g} "
              f"({h['rel_difference']:.1e})", file=sys.stderr)
    if args.json:
        write_json(args.json, r)
    return r


def markdown(r: dict) -> str:
    b, d, s = r["beta_table_life"], r["dadn_file_life"], r["speed"]
    lines = ["| check | measured | reference |", "|---|---|---|",
             f"| centre crack, Feddersen beta table file, Paris, a 2 -> 30 mm | {b['N']:.8g} cycles "
             f"({b['rel_error']:.1e}) | {b['N_exact']:.8g} (adaptive quadrature) |",
             f"| da/dN table file sampled from Paris, a 1 -> 20 mm | {d['N']:.8g} cycles ({d['rel_error']:.1e}) | "
             f"{d['N_exact']:.8g} (closed form) |",
             f"| E1049 history as a plain turning-point file | {r['turning_points']['cycles']} | "
             f"{r['turning_points']['reference']} |",
             f"| cycle by cycle with Wheeler, one core | {s['cycles_per_s']:.3g} cycles per CPU second "
             f"({s['cycles_per_wall_s']:.3g} per wall second) | >= 1e7 |",
             f"| rainflow, one core | {s['rainflow_points_per_s']:.3g} points per CPU second "
             f"({s['rainflow_points_per_wall_s']:.3g} per wall second) | >= 1e7 |"]
    if "hole" in r:
        h = r["hole"]
        lines.append(f"| hole-crack spectrum scene: life through grow's beta table | {h['life_passes']:.8g} passes "
                     f"({h['rel_difference']:.1e}) | grow: {h['grow_passes']:.8g} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
