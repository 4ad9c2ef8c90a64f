"""A synthetic flight spectrum for the fatigue-life demos (not a standard one).

Three flight types (A mild, B moderate, C severe), each a ground-air-ground
cycle with gusts: on the ground the wing is in compression (factor -0.25,
taxi bumps down to -0.4), in the air at 1 g (0.6) with gust cycles of
amplitudes drawn from a seeded generator, quantised to 0.05 so the pass has a
few discrete load levels (the life solves K at each level, not at each
cycle). One pass: 400 A, 90 B and 10 C flights of 500 turning points each
(1.2e5 cycles counted by rainflow). The numbers are made up for the
demo; TWIST and FALSTAFF are the standard spectra an engineer would use.

    /usr/bin/python3 demos/make_flight_spectrum.py demos/data/spectrum
"""
from __future__ import annotations

import argparse
import pathlib

import numpy as np

TYPES = {"A": (0.10, 0.25), "B": (0.15, 0.35), "C": (0.20, 0.55)}   # typical and largest gust amplitude


def flight(kind: str, points: int = 500, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    typical, largest = TYPES[kind]
    out = [-0.25, -0.4, -0.25]                       # taxi
    n_gust = (points - 8) // 2
    amp = np.clip(rng.exponential(typical, n_gust), 0.05, largest)   # every gust at least one 0.05 step
    for a in amp:
        out += [0.6 + a, 0.6 - a]
    out += [0.6, -0.25, -0.4, -0.25, 0.0]            # landing, taxi, parked
    q = np.round(np.asarray(out) / 0.05) * 0.05
    return q[:points]


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", type=pathlib.Path)
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    for i, kind in enumerate(TYPES):
        f = flight(kind, seed=i)
        lines = [f"# synthetic flight type {kind} (demos/make_flight_spectrum.py): load factor of group 'default'",
                 "default"] + [f"{v:.2f}" for v in f]
        (args.out / f"flight_{kind}.csv").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
