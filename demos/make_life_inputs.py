"""The input files of the life-without-a-mesh demos and examples
(demos/data/life/), each written from a formula stated here -- nothing is
measured data:

- centre_crack_feddersen.csv: beta = sqrt(sec(pi a / W)) of a centre crack
  in a plate W = 100 mm wide (Feddersen), a = 1 .. 45 mm, 401 sizes spaced
  geometrically (demos/life_inputs.py reads it and integrates the life);
- griffith_beta.csv: beta = 1 (a crack in an infinite plate), a = 0.1 ..
  1000 mm: two rows are the whole table (K / sqrt(a) is constant);
- paris_dadn.csv: a da/dN table in the csv layout sampled from Paris, C =
  3e-15 mm/cycle, m = 3 (Delta K in MPa sqrt(mm)), the same curve at R = 0
  and 0.5 (log-log interpolation of a Paris curve is exact);
- e1049.txt: the ASTM E1049-85 example history -2, 1, -3, 5, -1, 3, -4, 4,
  -2, one value per line, as test labs write a sequence;
- nasgro_7075_T6.dadn: a da/dN table in easigrow's layout sampled from the
  nasgro_7075_T6_LT example constants (cracklip.scene.fatigue.EXAMPLES: in
  in/cycle, ksi sqrt(in); Newman's f, long crack, thickness 0.1 in) at R =
  0, 0.3, 0.5, 0.7: for each rate, the Delta K giving it (bisection);
- block_loads.csv: a block-load table (max, min, cycles) of four load
  levels, made up for the surface-crack example (not a standard spectrum).

    /usr/bin/python3 demos/make_life_inputs.py demos/data/life
"""
from __future__ import annotations

import argparse
import math
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

W_CENTRE = 100.0
PARIS_C, PARIS_M = 3e-15, 3.0
E1049 = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]


def feddersen_table() -> str:
    a = np.geomspace(1.0, 45.0, 401)
    beta = np.sqrt(1.0 / np.cos(np.pi * a / W_CENTRE))
    lines = [f"# Feddersen's beta = sqrt(sec(pi a / W)) of a centre crack, W = {W_CENTRE:g} mm "
             "(demos/make_life_inputs.py)", "a,beta"]
    return "\n".join(lines + [f"{x:.17g},{b:.17g}" for x, b in zip(a, beta)]) + "\n"


def paris_table() -> str:
    rates = np.geomspace(1e-10, 1e-3, 15)
    dk = (rates / PARIS_C) ** (1.0 / PARIS_M)
    lines = [f"# Paris da/dN = {PARIS_C:g} dK^{PARIS_M:g} (mm/cycle, MPa sqrt(mm)) sampled at R = 0 and 0.5 "
             "(demos/make_life_inputs.py)", "dadn,R=0,R=0.5"]
    return "\n".join(lines + [f"{r:.17g},{k:.17g},{k:.17g}" for r, k in zip(rates, dk)]) + "\n"


def nasgro_table() -> str:
    from cracklip.fracture.laws import NasgroConstants, nasgro_rate, thickness_toughness
    from cracklip.scene.fatigue import EXAMPLES
    c = EXAMPLES["nasgro_7075_T6_LT"]["constants"]
    kc = thickness_toughness(c["K_Ic"], 0.1, c["yield_stress"], c["A_k"], c["B_k"])
    nc = NasgroConstants(c["C"], c["n"], c["p"], c["q"], c["dK1"], c["C_th_plus"], c["C_th_minus"], c["alpha"],
                         c["smax_over_flow"], 0.0, kc)
    Rs = [0.0, 0.3, 0.5, 0.7]
    rates = np.geomspace(1e-9, 1e-3, 19)

    def dk_for(rate: float, R: float) -> float:
        lo, hi = 1e-3, kc * (1 - R) * (1 - 1e-9)
        for _ in range(200):
            mid = math.sqrt(lo * hi)
            if float(nasgro_rate(mid, R, mid / (1 - R), 1.0, nc)) < rate:
                lo = mid
            else:
                hi = mid
        return math.sqrt(lo * hi)
    lines = ["# da/dN (in/cycle) against Delta K (ksi sqrt(in)) of the nasgro_7075_T6_LT example constants, "
             "thickness 0.1 in,", "# Newman's f, long crack; easigrow's layout: first line the R values "
             "(demos/make_life_inputs.py)", "  ".join(f"{R:g}" for R in Rs)]
    for r in rates:
        lines.append(f"{r:.6e}  " + "  ".join(f"{dk_for(r, R):.8g}" for R in Rs))
    return "\n".join(lines) + "\n"


def block_table() -> str:
    rows = [(1.0, 0.1, 2000), (1.3, 0.1, 200), (0.8, 0.2, 8000), (1.6, 0.0, 20)]
    lines = ["# a block-load table: cycles from min to max in a row, four levels (made up for the example; "
             "demos/make_life_inputs.py)", "max,min,cycles"]
    return "\n".join(lines + [f"{a:g},{b:g},{n}" for a, b, n in rows]) + "\n"


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", type=pathlib.Path)
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "centre_crack_feddersen.csv").write_text(feddersen_table())
    (args.out / "griffith_beta.csv").write_text("# beta = 1: a crack in an infinite plate (demos/make_life_inputs.py)"
                                                "\na,beta\n0.1,1\n1000,1\n")
    (args.out / "paris_dadn.csv").write_text(paris_table())
    (args.out / "e1049.txt").write_text("# ASTM E1049-85 example history, one turning point per line\n"
                                        + "\n".join(f"{x:g}" for x in E1049) + "\n")
    (args.out / "nasgro_7075_T6.dadn").write_text(nasgro_table())
    (args.out / "block_loads.csv").write_text(block_table())


if __name__ == "__main__":
    main()
