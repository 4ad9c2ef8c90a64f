"""Crack growth benchmarks (issue 17).

1. First kink of an inclined centre crack (half length 0.5 at beta from x,
   tension along y, the exact infinite-plate field on the boundary of
   [-1, 1]^2): K_I = s sqrt(pi a) cos^2(beta), K_II = s sqrt(pi a) sin(beta)
   cos(beta), maximum hoop stress: -43.22 / -53.13 / -60.00 / -65.51 degrees
   for beta = 30 / 45 / 60 / 75 (the tip frame's convention: negative toward
   -e2).
2. A closed crack slipping under compression (the exact field, frictionless
   and with mu = 0.2): K_I = 0, the kink +-70.53 degrees (the wing crack's
   start), the same with friction.
3. Mode I growth stays straight: an edge crack in tension grows 20 steps on
   an unstructured mesh; its lateral drift against the element size.
4. Paris law: a centre crack in a plate 40 a wide, constant amplitude Delta
   sigma = 1 (R = 0), from a = 0.5 to 1: N(a) against N = [a^(1 - m/2)] /
   (C (Delta sigma sqrt(pi))^m (1 - m/2)).
5. Closure: the same crack under a cycle from -1 to +1: with contact the
   lips close at the minimum, Delta K_eff = K_max, and it grows 2^m times
   slower than without contact (the linear Delta K = 2 K_max).

    /usr/bin/python3 demos/growth_benchmarks.py --json results/growth/growth_benchmarks.json
"""
from __future__ import annotations

import argparse
import logging
import math
import pathlib
import sys
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

import cracklip as cl  # noqa: E402
import friction_crack  # noqa: E402
import handbook  # noqa: E402
from cracklip.scene.growth import Growth
from cracklip.analysis.growth import grow
from cracklip.fracture.kink import kink_angle  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402

PARIS_C, PARIS_M = 1e-3, 3.0


def kink_row(beta: float, n: int = 40) -> dict:
    """The first kink of the inclined centre crack in tension."""
    field = handbook.inclined(beta)
    sol = cl.solve(handbook.griffith_scene(field, 2.0 / n))
    ks = sol.stress_intensity_factors(0)
    kinks = [math.degrees(kink_angle(k["K_I"], k["K_II"])) for k in ks]
    exact = math.degrees(kink_angle(field.K_I, field.K_II))
    return {"beta_deg": beta, "kink_deg": float(np.mean(kinks)), "kink_tips_deg": kinks, "kink_exact_deg": exact,
            "K_I": [k["K_I"] for k in ks], "K_II": [k["K_II"] for k in ks], "K_I_exact": field.K_I,
            "K_II_exact": field.K_II, "error_deg": max(abs(v - exact) for v in kinks)}


def closed_kink_row(mu: float, beta: float = 45.0, n: int = 40) -> dict:
    """The kink of a closed crack slipping under compression."""
    field, tau_eff, _ = friction_crack.exact(beta, mu)
    sol = cl.solve(friction_crack.scene_for(field, n, mu))
    ks = sol.stress_intensity_factors(0)
    kinks = [math.degrees(kink_angle(k["K_I"], k["K_II"])) for k in ks]
    exact = math.degrees(kink_angle(0.0, tau_eff))
    return {"mu": mu, "beta_deg": beta, "kink_deg": kinks, "kink_exact_deg": exact,
            "K_I": [k["K_I"] for k in ks], "K_II": [k["K_II"] for k in ks],
            "error_deg": max(abs(v - exact) for v in kinks)}


def drift(steps: int = 20, h: float = 0.05, tip_h: float = 0.01) -> dict:
    """Symmetric mode I growth: an edge crack in [0, 1] x [-3, 3] under
    tension grows from a = 0.3 by 0.015 per step on an unstructured mesh
    refined along its path."""
    md = cl.create_rectangle(0.0, -3.0, 1.0, 3.0, h, refine=[(0.25, 0.0, tip_h, 0.0, 0.7, 0.0)])
    scene = cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-0.1, 0.0], [0.3, 0.0]], name="edge crack")],
                     dirichlet=[cl.Dirichlet(md.nearest_node((0.0, -3.0)), None, 0.0),
                                cl.Dirichlet(md.nearest_node((1.0, -3.0)), 1, 0.0)],
                     tractions=[cl.Traction("top", (0.0, 1.0)), cl.Traction("bottom", (0.0, -1.0))],
                     options=cl.Options(radius=0.1))
    t0 = time.perf_counter()
    res = grow(scene, Growth(da=0.015, steps=steps))
    pts = res.cracks[0].points
    return {"steps": steps, "tip_h": tip_h, "drift_max": float(np.abs(pts[:, 1]).max()),
            "drift_over_h": float(np.abs(pts[:, 1]).max() / tip_h), "final_length": res.records[-1][0].length,
            "path": pts.tolist(), "t_total": time.perf_counter() - t0, "stop_reason": res.stop_reason}


def centre_crack_scene(a0: float = 0.5, L: float = 20.0, contact: str = "none") -> cl.Scene:
    """A centre crack (half length a0) in [-L, L]^2 under sigma_yy = 1 (group
    "default"), the mesh refined (0.0125) along y = 0 for |x| < 1.2."""
    md = cl.create_rectangle(-L, -L, L, L, 1.0, refine=[(-1.2, 0.0, 0.0125, 8.0, 1.2, 0.0)])
    return cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-a0, 0.0], [a0, 0.0]], name="centre crack")],
                    dirichlet=[cl.Dirichlet(md.nearest_node((-L, -L)), None, 0.0),
                               cl.Dirichlet(md.nearest_node((L, -L)), 1, 0.0)],
                    tractions=[cl.Traction("top", (0.0, 1.0)), cl.Traction("bottom", (0.0, -1.0))],
                    options=cl.Options(radius=0.1, contact=contact))


def paris_closed_form(a: np.ndarray, a0: float, C: float = PARIS_C, m: float = PARIS_M, ds: float = 1.0) -> np.ndarray:
    """Cycles to grow a Griffith crack from a0 to a: [a^(1 - m/2)] / (C (ds sqrt(pi))^m (1 - m/2))."""
    return (np.asarray(a) ** (1 - m / 2) - a0 ** (1 - m / 2)) / (C * (ds * math.sqrt(math.pi)) ** m * (1 - m / 2))


def paris(steps: int = 20, da: float = 0.025) -> dict:
    """Constant amplitude (R = 0) fatigue of the centre crack from a = 0.5 to 1."""
    t0 = time.perf_counter()
    res = grow(centre_crack_scene(), Growth(da=da, steps=steps, paris_C=PARIS_C, paris_m=PARIS_M,
                                            cycle_min={"default": 0.0}))
    a = np.array([st[0].length / 2 for st in res.records])
    N = np.array([st[0].N for st in res.records])
    exact = paris_closed_form(a, 0.5)
    err = np.abs(N[1:] - exact[1:]) / exact[1:]
    return {"a": a.tolist(), "N": N.tolist(), "N_exact": exact.tolist(), "N_error_max": float(err.max()),
            "C": PARIS_C, "m": PARIS_M, "delta_sigma": 1.0, "t_total": time.perf_counter() - t0,
            "step_seconds": res.step_times}


def closure(steps: int = 8, da: float = 0.025) -> dict:
    """The cycle from -1 to +1 with and without contact."""
    out = {}
    for contact in ("unilateral", "none"):
        res = grow(centre_crack_scene(contact=contact),
                   Growth(da=da, steps=steps, paris_C=PARIS_C, paris_m=PARIS_M, cycle_min={"default": -1.0}))
        r0 = res.records[0][0]
        out[contact] = {"N": res.cycles, "a": [st[0].length / 2 for st in res.records],
                        "N_steps": [st[0].N for st in res.records], "delta_K_over_K_max": [st[0].delta_K / st[0].K_eq for st in res.records],
                        "K_I_min": [st[0].K_I_min for st in res.records], "K_max": [st[0].K_I for st in res.records],
                        "closed_fraction_min": _closed_at_min(contact, r0)}
    out["slowdown"] = out["unilateral"]["N"] / out["none"]["N"]
    return out


def _closed_at_min(contact: str, r) -> float | None:
    """The closed fraction at the minimum load (-1) of the initial crack."""
    if contact == "none":
        return None
    scene = centre_crack_scene(contact=contact)
    scene.tractions = [cl.Traction("top", (0.0, -1.0)), cl.Traction("bottom", (0.0, 1.0))]
    sol = cl.solve(scene)
    smp = sol.lip_samples(0, 2)
    return float(smp["weight"][smp["state"] != "open"].sum() / smp["weight"].sum())


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=pathlib.Path, default=None)
    ap.add_argument("--out", type=pathlib.Path, default=None, help="folder for growth_benchmarks.{json,md,png}")
    ap.add_argument("--quick", action="store_true", help="fewer steps (smoke test)")
    args = ap.parse_args(argv)
    logging.getLogger("cracklip").setLevel(logging.ERROR)
    result = {"kink_rows": [kink_row(b) for b in (30.0, 45.0, 60.0, 75.0)],
              "closed_kink_rows": [closed_kink_row(mu) for mu in (0.0, 0.2)]}
    result["drift"] = drift(steps=4 if args.quick else 20)
    result["drift_over_h"] = result["drift"]["drift_over_h"]
    result["paris"] = paris(steps=4 if args.quick else 20)
    result["closure"] = closure(steps=2 if args.quick else 8)
    for r in result["kink_rows"]:
        print(f"beta {r['beta_deg']:g}: kink {r['kink_deg']:.2f} (exact {r['kink_exact_deg']:.2f})", file=sys.stderr)
    print(f"drift / h = {result['drift_over_h']:.2e}; Paris N error {result['paris']['N_error_max']:.2%}; closure "
          f"slows growth {result['closure']['slowdown']:.2f}x", file=sys.stderr)
    if args.json:
        write_json(args.json, result)
    if args.out:
        write_json(args.out / "growth_benchmarks.json", result)
        (args.out / "growth_benchmarks.md").write_text(markdown(result))
        plot(result, args.out)
    return result


def markdown(r: dict) -> str:
    lines = ["| beta | kink (computed, both tips) | exact |", "|---|---|---|"]
    lines += [f"| {k['beta_deg']:g} | {', '.join(f'{v:.2f}' for v in k['kink_tips_deg'])} | {k['kink_exact_deg']:.2f} |"
              for k in r["kink_rows"]]
    lines += ["", "| closed crack, beta 45 | kink (both tips) | exact |", "|---|---|---|"]
    lines += [f"| mu = {k['mu']:g} | {', '.join(f'{v:.2f}' for v in k['kink_deg'])} | {k['kink_exact_deg']:.2f} |"
              for k in r["closed_kink_rows"]]
    d, p, c = r["drift"], r["paris"], r["closure"]
    lines += ["", f"Mode I growth, {d['steps']} steps: lateral drift {d['drift_max']:.2e} = {d['drift_over_h']:.2e} "
                  f"tip elements.", "",
              f"Paris law (C = {p['C']:g}, m = {p['m']:g}, Delta sigma = 1, a from 0.5 to {p['a'][-1]:.3f}): N = "
              f"{p['N'][-1]:.4g} against {p['N_exact'][-1]:.4g}; largest error over the steps {p['N_error_max']:.2%}.",
              "", f"Closure (cycle -1 .. +1): with contact N = {c['unilateral']['N']:.4g}, without {c['none']['N']:.4g} "
                  f"({c['slowdown']:.2f}x; 2^m = {2 ** PARIS_M:g} expected); Delta K_eff / K_max with contact "
                  f"{min(c['unilateral']['delta_K_over_K_max']):.4f} .. {max(c['unilateral']['delta_K_over_K_max']):.4f}, "
                  f"closed fraction at the minimum {c['unilateral']['closed_fraction_min']:.3f}."]
    return "\n".join(lines) + "\n"


def plot(r: dict, out: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    p = r["paris"]
    fig, ax = plt.subplots(figsize=(6, 4))
    a = np.linspace(p["a"][0], p["a"][-1], 200)
    ax.plot(paris_closed_form(a, p["a"][0]), a, "k-", lw=0.8, label="closed form")
    ax.plot(p["N"], p["a"], "o", ms=4, label="cracklip")
    ax.set_xlabel("cycles N")
    ax.set_ylabel("half length a")
    ax.set_title("Paris law, centre crack, constant amplitude")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "paris_a_N.png", dpi=150)
    plt.close(fig)

    c = r["closure"]
    fig, ax = plt.subplots(figsize=(6, 4))
    for key, label in (("unilateral", "contact: lips close at the minimum"), ("none", "no contact (linear Delta K)")):
        ax.plot(c[key]["N_steps"], c[key]["a"], "o-", ms=4, label=label)
    ax.set_xlabel("cycles N")
    ax.set_ylabel("half length a")
    ax.set_title(f"Closure: cycle -1 .. +1, growth {c['slowdown']:.2f}x slower with contact")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "closure_a_N.png", dpi=150)
    plt.close(fig)

    d = r["drift"]
    path = np.asarray(d["path"])
    fig, ax = plt.subplots(figsize=(6, 3))
    ax.plot(path[:, 0], path[:, 1] / d["tip_h"], "o-", ms=3)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("x")
    ax.set_ylabel("y / h (tip elements)")
    ax.set_title(f"Mode I growth, {d['steps']} steps: largest drift {d['drift_over_h']:.1e} h")
    fig.tight_layout()
    fig.savefig(out / "drift.png", dpi=150)
    plt.close(fig)


if __name__ == "__main__":
    main()
