"""Tip-cell quadrature (issue 3): the integral of grad(F_l) . grad(F_l) of the
four branch functions over a triangle holding the tip, by the collapsed
(quasi-polar) rule and by the paper's plain Gauss rule at degrees 5 and 20,
against an adaptive reference (scipy quad over the angle of the exact radial
integral, |grad F_l|^2 = g_l(theta) / r).

    /usr/bin/python3 demos/tip_quadrature.py --json results/tip_quadrature.json
"""
from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np
from scipy import integrate

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))

from cracklip import _cracklip  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402

#: A tip cell (not symmetric about the crack) and the tip inside it.
TRIANGLE = np.array([[-0.13, -0.07], [0.11, -0.05], [0.02, 0.12]])
TIP = np.array([0.0, 0.0])
E1 = np.array([1.0, 0.0])


def g(theta: np.ndarray) -> np.ndarray:
    """r |grad F_l|^2 at angle theta (independent of r), (n, 4)."""
    p = np.stack([np.cos(theta), np.sin(theta)], axis=-1).reshape(-1, 2)
    side = np.where(p[:, 1] >= 0, 1, -1).astype(np.int8)
    _, dF = _cracklip.branch_functions(TIP, E1, p, side)
    return np.einsum("nlj,nlj->nl", dF, dF)


def reference() -> np.ndarray:
    """Adaptive: sum over edges AB of int g(theta) R(theta) dtheta, R the ray length."""
    total = np.zeros(4)
    for k in range(3):
        A, B = TRIANGLE[k] - TIP, TRIANGLE[(k + 1) % 3] - TIP
        a0, a1 = np.arctan2(A[1], A[0]), np.arctan2(B[1], B[0])
        if a1 < a0:
            a1 += 2 * np.pi
        e = B - A

        def R(t):
            c = np.array([np.cos(t), np.sin(t)])
            return (A[0] * e[1] - A[1] * e[0]) / (c[0] * e[1] - c[1] * e[0])
        # Split at the crack line (theta = +-pi), where g jumps.
        breaks = [a0] + [b for b in (np.pi, 3 * np.pi) if a0 < b < a1] + [a1]
        for lo, hi in zip(breaks[:-1], breaks[1:]):
            for l in range(4):
                val, _ = integrate.quad(lambda t: g(np.array([t]))[0, l] * R(t), lo, hi,
                                        epsabs=1e-15, epsrel=1e-14, limit=400)
                total[l] += val
    return total


def rule_integral(options) -> tuple[np.ndarray, int]:
    pts, w = _cracklip.tip_cell_rule(TRIANGLE, TIP, options)
    d = pts - TIP
    r = np.linalg.norm(d, axis=1)
    theta = np.arctan2(d[:, 1], d[:, 0])
    return (w[:, None] * g(theta) / r[:, None]).sum(axis=0), len(w)


def run() -> dict:
    ref = reference()
    rows = []
    for radial, angular, max_angle in [(1, 4, 0.8), (1, 6, 0.6), (2, 6, 0.6), (1, 8, 0.6)]:
        o = _cracklip.QuadratureOptions()
        o.tip_radial, o.tip_angular, o.tip_max_angle = radial, angular, max_angle
        val, n = rule_integral(o)
        rows.append({"rule": f"collapsed {radial}x{angular}, max angle {max_angle}", "points": n,
                     "max_rel_error": float(np.max(np.abs(val - ref) / ref))})
    for degree in (5, 20):
        o = _cracklip.QuadratureOptions()
        o.tip_rule = _cracklip.TipQuadrature.gauss
        o.tip_degree = degree
        val, n = rule_integral(o)
        rows.append({"rule": f"plain Gauss degree {degree} (paper)", "points": n,
                     "max_rel_error": float(np.max(np.abs(val - ref) / ref))})
    return {"reference": ref.tolist(), "rows": rows}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/tip_quadrature.json"))
    args = ap.parse_args(argv)
    res = run()
    write_json(args.json, res)
    lines = ["| rule | points | max rel. error over F_1..F_4 |", "|---|---|---|"]
    lines += [f"| {r['rule']} | {r['points']} | {r['max_rel_error']:.2e} |" for r in res["rows"]]
    args.json.with_suffix(".md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines), file=sys.stderr)
    return res


if __name__ == "__main__":
    main()
