"""Fatigue life under load histories (issue 29): the checks and their numbers.

1. rainflow: the ASTM E1049 history -2, 1, -3, 5, -1, 3, -4, 4, -2 counted
   once (E1049: (3, 0.5), (4, 1.5), (6, 0.5), (8, 1), (9, 0.5)) and repeated
   (full cycles 3, 4, 7, 9).
2. block_life: a Griffith crack, Paris C = 1e-12 m/cycle (MPa sqrt(m)), m =
   3, the E1049 history x 10 MPa as a block (counted once per block, residue
   as half cycles), a = 1 -> 10 mm. Closed form: N = [a^(1 - m/2)] / ((1 -
   m/2) C pi^(m/2) sum n dS^m) = 7.09904e6 blocks. On a prescribed K = S
   sqrt(pi a) and on cracklip's K (a centre crack in a plate 2 m wide, in mm
   and MPa: C converted through [units]), grown by the life loop.
3. nasgro: the NASGRO equation against the notes' check values (7075-T6 L-T
   t = 0.1 in, Ti-6Al-4V MA t = 0.25 in; in/cycle, ksi sqrt(in)).
4. wheeler: Griffith crack, C = 1e-12, m = 3, S 0 -> 100 MPa, yield 400 MPa,
   plane stress (beta 2), gamma 1.5, a = 5 -> 6 mm: constant amplitude and
   with one 0 -> 150 MPa overload at 5 mm (cycle-by-cycle references 442,572
   and 546,061, recomputed by tests/test_life.py with a plain loop).
5. spectrum: a crack at a hole under a flight spectrum of 1.24e5 cycles per
   pass with compressive excursions (demos/scenes/hole_crack_spectrum.toml),
   grown to failure with contact closure, Newman closure and none; solves,
   load levels, the time per growth step against a constant-amplitude step
   (the old two-level cycle, solved with contact), and the lives.
6. beta (not in the issue's keys): beta = K / (S sqrt(pi a)) of a centre
   crack grown in a strip 2b wide against Tada's formula.

    /usr/bin/python3 demos/fatigue_checks.py --json results/fatigue_checks.json
"""
from __future__ import annotations

import argparse
import dataclasses
import logging
import math
import pathlib
import statistics
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))
sys.path.insert(0, str(HERE))

import cracklip as cl  # noqa: E402
from cracklip.analysis.growth import grow  # noqa: E402
from cracklip.fracture.laws import NasgroConstants, Paris, nasgro_rate, thickness_toughness  # noqa: E402
from cracklip.fracture.life import CycleTable, LifeLaw, grow_with_retardation, pass_growth, passes_between  # noqa: E402
from cracklip.fracture.rainflow import count_cycles, rainflow, rainflow_repeated  # noqa: E402
from cracklip.fracture.retardation import Retardation  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402
from cracklip.io.scene_file import load_scene_file  # noqa: E402
from cracklip.scene.fatigue import EXAMPLES, FatigueMaterial  # noqa: E402
from cracklip.scene.growth import Growth  # noqa: E402
from cracklip.scene.spectrum import Spectrum, SpectrumBlock  # noqa: E402
from cracklip.scene.units import Units  # noqa: E402

E1049 = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]
C_SI, M = 1e-12, 3.0

#: The notes' NASGRO check values [D] (notes/damage_tolerance.md, gap 2): (alloy, t, R, dK, da/dN).
NASGRO_CHECKS = [("nasgro_7075_T6_LT", 0.1, 0.1, 3.0, 3.5520e-7), ("nasgro_7075_T6_LT", 0.1, 0.1, 5.0, 1.4516e-6),
                 ("nasgro_7075_T6_LT", 0.1, 0.1, 10.0, 9.4118e-6), ("nasgro_7075_T6_LT", 0.1, 0.1, 20.0, 6.8038e-5),
                 ("nasgro_7075_T6_LT", 0.1, 0.5, 5.0, 2.8185e-6), ("nasgro_7075_T6_LT", 0.1, 0.5, 10.0, 1.9932e-5),
                 ("nasgro_Ti6Al4V_MA_LT", 0.25, 0.1, 5.0, 1.2609e-7),
                 ("nasgro_Ti6Al4V_MA_LT", 0.25, 0.1, 10.0, 1.2285e-6),
                 ("nasgro_Ti6Al4V_MA_LT", 0.25, 0.1, 20.0, 1.1919e-5)]


def block_closed_form(a0: float, a1: float, ranges: list[tuple[float, float]], C: float = C_SI, m: float = M) -> float:
    """Blocks of a Griffith crack from a0 to a1 (m) under blocks of counted
    ranges (MPa, count): [a^(1 - m/2)] / ((1 - m/2) C pi^(m/2) sum n dS^m)."""
    s = sum(c * r ** m for r, c in ranges)
    return (a1 ** (1 - m / 2) - a0 ** (1 - m / 2)) / ((1 - m / 2) * C * math.pi ** (m / 2) * s)


def block_life_prescribed(residue: str = "half") -> float:
    """Blocks from 1 to 10 mm on K = S sqrt(pi a) (SI), the E1049 block x 10 MPa."""
    v = np.asarray(E1049) * 10.0
    ct = count_cycles(v, "rainflow", repeated=residue == "close")
    cycles = CycleTable(ct.lo, ct.hi, ct.count).unique()
    law = LifeLaw(Paris(C_SI, M), "none")
    return passes_between(lambda a: pass_growth(v * math.sqrt(math.pi * a), cycles, law, a), 1e-3, 1e-2)


def griffith_plate(half_width: float = 1000.0, a0: float = 1.0, band: float = 0.05, h: float = 50.0,
                   grading: float = 0.05) -> cl.Scene:
    """A centre crack (half length a0 mm) in a square plate [-L, L]^2 (mm) under
    10 MPa at factor 1, the mesh refined to `band` along y = 0 for |x| < 11
    and growing away from it by `grading` per mm (K_I / (S sqrt(pi a)) =
    0.9992, 0.9994, 0.9995 at a = 1, 5, 9.5 mm; the plate's width changes it
    by 6e-5 at most; growing by 0.17 per mm instead, K is 0.8 % low)."""
    L = half_width
    md = cl.create_rectangle(-L, -L, L, L, h, refine=[(-11.0, 0.0, band, (h - band) / grading, 11.0, 0.0)])
    return cl.Scene(md, cl.Material(71000.0, 0.33), cracks=[cl.Crack([[-a0, 0.0], [a0, 0.0]], name="centre crack")],
                    dirichlet=[cl.Dirichlet(md.nearest_node((-L, -L)), None, 0.0),
                               cl.Dirichlet(md.nearest_node((L, -L)), 1, 0.0)],
                    tractions=[cl.Traction("top", (0.0, 10.0)), cl.Traction("bottom", (0.0, -10.0))],
                    options=cl.Options(radius=0.3), units=Units("mm", stress="MPa"))


def block_life_fe(da: float = 1.0, band: float = 0.05, h: float = 50.0) -> dict:
    """The block life on cracklip's K: Paris in m and MPa sqrt(m), converted to
    the scene's mm and MPa; grown until a reaches 10 mm (the last increment
    lands there)."""
    scene = griffith_plate(band=band, h=h)
    fm = FatigueMaterial("paris", {"C": C_SI, "m": M}, units=("m", "MPa"), closure="none")
    sp = Spectrum([SpectrumBlock(np.asarray(E1049), 1, "E1049 block")], residue="half", block_name="block")
    steps = int(round((10.0 - 1.0) / da))
    t0 = time.perf_counter()
    res = grow(scene, Growth(da=da, steps=steps, fatigue_material=fm, spectrum=sp))
    a = np.array([st[0].a for st in res.records])
    blocks = np.array([st[0].blocks for st in res.records])
    exact = np.array([block_closed_form(1e-3, x * 1e-3, [(10 * r, c) for r, c in rainflow(E1049)]) if x > 1.0
                      else 0.0 for x in a])
    beta = np.array([st[0].K_max / (50.0 * math.sqrt(math.pi * st[0].a)) for st in res.records])  # max of the block: 5 x 10 MPa
    return {"a_mm": a.tolist(), "blocks": blocks.tolist(), "blocks_exact": exact.tolist(), "beta": beta.tolist(),
            "N": float(np.interp(10.0, a, blocks)), "a_end": float(a[-1]), "steps": steps,
            "solves": int(sum(res.step_solves)), "seconds": time.perf_counter() - t0}


def nasgro_rows() -> list[dict]:
    rows = []
    for name, t, R, dk, check in NASGRO_CHECKS:
        c = dict(EXAMPLES[name]["constants"])
        kc = thickness_toughness(c["K_Ic"], t, c["yield_stress"], c["A_k"], c["B_k"])
        nc = NasgroConstants(c["C"], c["n"], c["p"], c["q"], c["dK1"], c["C_th_plus"], c["C_th_minus"], c["alpha"],
                             c["smax_over_flow"], 0.0, kc)
        rate = float(nasgro_rate(dk, R, dk / (1 - R), 1.0, nc))
        rows.append({"alloy": name, "t_in": t, "R": R, "dK": dk, "dadN": rate, "dadN_check": check,
                     "rel_error": abs(rate / check - 1.0), "K_c": kc})
    return rows


def wheeler(block: int = 1000) -> dict:
    """The notes' Wheeler check (module doc) through the life code's
    cycle-by-cycle integrator (chunks with a predictor-corrector)."""
    law = LifeLaw(Paris(C_SI, M), "none")
    S = np.array([0.0, 100.0, 150.0])
    K = lambda a: S * math.sqrt(math.pi * a)  # noqa: E731
    ret = Retardation("wheeler", 400.0, 2.0, 1.5)
    first = CycleTable(np.zeros(block, int), np.r_[2, np.ones(block - 1, int)], np.ones(block))
    rest = CycleTable(np.zeros(block, int), np.ones(block, int), np.ones(block))
    t0 = time.perf_counter()
    ca = grow_with_retardation(K, lambda i: rest, law, ret, 5e-3, 6e-3)
    ol = grow_with_retardation(K, lambda i: first if i == 0 else rest, law, ret, 5e-3, 6e-3)
    closed = (6e-3 ** -0.5 - 5e-3 ** -0.5) / (-0.5 * C_SI * (100 * math.sqrt(math.pi)) ** 3)
    return {"N_ca": ca.cycles, "N_overload": ol.cycles, "N_ca_closed_form": closed, "N_ca_check": 442572,
            "N_overload_check": 546061, "delay": ol.cycles - ca.cycles, "seconds": time.perf_counter() - t0}


def hole_scene(closure: str, steps: int, da: float, h: float, band: float):
    sf = load_scene_file(HERE / "scenes" / "hole_crack_spectrum.toml",
                         [f"material.fatigue.closure={closure!r}".replace("'", '"'), f"growth.steps={steps}",
                          f"growth.da={da}", f"mesh.h={h}", f"mesh.refine[0].h={band}"])
    return sf


def spectrum_life(steps: int = 40, da: float = 1.5, h: float = 5.0, band: float = 0.25, ca_steps: int = 3) -> dict:
    """The crack at a hole under the flight spectrum, to failure, with each
    closure; then a constant-amplitude run (the old growth.paris_C path:
    both ends of the cycle 1.15 / -0.4 solved with contact) for the time per
    step."""
    out: dict = {"life_passes": {}, "life_blocks": {}, "life_cycles": {}, "failure": {}, "stop": {}, "a_N": {}}
    for closure in ("contact", "newman", "none"):
        sf = hole_scene(closure, steps, da, h, band)
        t0 = time.perf_counter()
        res = grow(sf.scene, sf.growth)
        t = time.perf_counter() - t0
        lf = res.life
        out["life_passes"][closure] = lf["passes"]
        out["life_blocks"][closure] = lf["blocks"]
        out["life_cycles"][closure] = lf["cycles"]
        out["failure"][closure] = lf["failure"]
        out["stop"][closure] = res.stop_reason
        out["a_N"][closure] = [[st[0].a, st[0].N, st[0].blocks] for st in res.records]
        if closure == "contact":
            out.update({"cycles_per_pass": lf["cycles_per_pass"], "blocks_per_pass": lf["blocks_per_pass"],
                        "load_states": lf["load_states"], "growth_steps": len(res.records) - 1,
                        "solves": int(sum(res.step_solves)), "load_levels": max(lf["load_levels_per_step"]),
                        "t_step": statistics.median(res.step_times[1:]) if len(res.step_times) > 1 else res.step_times[0],
                        "t_total_contact": t, "residual_strength": lf["residual_strength"]})
    # Constant amplitude: the old path, max 1.15, min -0.4 of the same loads, with contact.
    sf = hole_scene("contact", ca_steps, da, h, band)
    g = dataclasses.replace(sf.growth, fatigue_material=None, spectrum=None, paris_C=1e-10, paris_m=3.0,
                            cycle_max={"default": 1.15}, cycle_min={"default": -0.4})
    res = grow(sf.scene, g)
    out["t_step_constant_amplitude"] = statistics.median(res.step_times[1:])
    out["solves_per_step_constant_amplitude"] = 2
    out["step_time_ratio"] = out["t_step"] / out["t_step_constant_amplitude"]
    out["solves_bound"] = out["growth_steps"] * (out["load_levels"] + 2)
    return out


def beta_check(b: float = 1.0, h: float = 0.05, band: float = 0.005, steps: int = 6, da: float = 0.05) -> dict:
    """A centre crack (half length 0.2) in a strip [-b, b] x [-3b, 3b] grown in
    steps of da with the beta table: beta against Tada's (1 - 0.025 x^2 +
    0.06 x^4) sqrt(sec(pi x / 2)), x = a / b, and Feddersen's sqrt(sec(pi x / 2))."""
    import handbook
    md = cl.create_rectangle(-b, -3 * b, b, 3 * b, h, refine=[(-0.7 * b, 0.0, band, 0.5, 0.7 * b, 0.0)])
    scene = cl.Scene(md, cl.Material(1.0, 0.3), cracks=[cl.Crack([[-0.2, 0.0], [0.2, 0.0]])],
                     dirichlet=[cl.Dirichlet(md.nearest_node((-b, -3 * b)), None, 0.0),
                                cl.Dirichlet(md.nearest_node((b, -3 * b)), 1, 0.0)],
                     tractions=[cl.Traction("top", (0.0, 1.0)), cl.Traction("bottom", (0.0, -1.0))],
                     options=cl.Options(radius=0.05))
    res = grow(scene, Growth(da=da, steps=steps), beta_table=True)
    rows = []
    for r in res.beta:
        x = r["a"] / b
        rows.append({"step": r["step"], "end": r["end"], "a": r["a"], "beta": r["beta_default"],
                     "tada": handbook.tada_centre_crack(x), "feddersen": math.sqrt(1 / math.cos(math.pi * x / 2))})
    err = max(abs(r["beta"] / r["tada"] - 1) for r in rows)
    return {"rows": rows, "max_rel_error_tada": err}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=pathlib.Path, default=None)
    ap.add_argument("--out", type=pathlib.Path, default=None, help="folder for fatigue_checks.{json,md,png}")
    ap.add_argument("--spectrum-steps", type=int, default=40, help="growth steps of the spectrum life (to failure)")
    ap.add_argument("--hole-h", type=float, default=5.0, help="element size of the hole plate (mm)")
    ap.add_argument("--hole-band", type=float, default=0.25, help="element size along the hole crack's path (mm)")
    ap.add_argument("--griffith-band", type=float, default=0.05, help="element size along the Griffith crack (mm)")
    ap.add_argument("--griffith-da", type=float, default=1.0, help="growth increment of the Griffith crack (mm)")
    ap.add_argument("--quick", action="store_true", help="coarse and short (smoke test)")
    args = ap.parse_args(argv)
    logging.getLogger("cracklip").setLevel(logging.ERROR)
    if args.quick:
        args.spectrum_steps, args.hole_h, args.hole_band = 4, 10.0, 0.5
        args.griffith_band, args.griffith_da = 0.3, 3.0
    t0 = time.perf_counter()
    r: dict = {"rainflow": [list(x) for x in rainflow(E1049)], "rainflow_repeated": [list(x) for x in rainflow_repeated(E1049)]}
    fe = block_life_fe(args.griffith_da, args.griffith_band)
    exact = block_closed_form(1e-3, 1e-2, [(10 * rr, c) for rr, c in rainflow(E1049)])
    r["block_life"] = {"N": fe["N"], "N_exact": exact, "N_prescribed": block_life_prescribed("half"),
                       "N_prescribed_closed_residue": block_life_prescribed("close"),
                       "N_exact_closed_residue": block_closed_form(1e-3, 1e-2, [(10 * rr, c) for rr, c in
                                                                                 rainflow_repeated(E1049)]),
                       "fe": fe}
    r["block_life"]["rel_error"] = abs(fe["N"] / exact - 1)
    r["block_life"]["rel_error_prescribed"] = abs(r["block_life"]["N_prescribed"] / exact - 1)
    r["nasgro"] = nasgro_rows()
    r["wheeler"] = wheeler()
    r["spectrum"] = spectrum_life(args.spectrum_steps, 1.5, args.hole_h, args.hole_band, 2 if args.quick else 3)
    r["beta"] = beta_check(steps=2 if args.quick else 6, band=0.02 if args.quick else 0.005)
    r["seconds"] = time.perf_counter() - t0
    sp = r["spectrum"]
    print(f"rainflow {r['rainflow']}; repeated {r['rainflow_repeated']}", file=sys.stderr)
    print(f"block life {r['block_life']['N']:.6g} (exact {exact:.6g}, {r['block_life']['rel_error']:.2%}); prescribed "
          f"{r['block_life']['N_prescribed']:.6g}", file=sys.stderr)
    print(f"NASGRO largest error {max(x['rel_error'] for x in r['nasgro']):.1e}; Wheeler {r['wheeler']['N_ca']:.0f} / "
          f"{r['wheeler']['N_overload']:.0f}", file=sys.stderr)
    print(f"spectrum: {sp['cycles_per_pass']:.0f} cycles per pass, {sp['growth_steps']} steps, {sp['solves']} solves "
          f"(bound {sp['solves_bound']}), step {sp['t_step']:.3f} s vs {sp['t_step_constant_amplitude']:.3f} s "
          f"constant amplitude; passes {sp['life_passes']}; beta error {r['beta']['max_rel_error_tada']:.2%}",
          file=sys.stderr)
    if args.json:
        write_json(args.json, r)
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        write_json(args.out / "fatigue_checks.json", r)
        (args.out / "fatigue_checks.md").write_text(markdown(r))
        plot(r, args.out)
    return r


def markdown(r: dict) -> str:
    b, w, sp = r["block_life"], r["wheeler"], r["spectrum"]
    lines = ["| check | measured | reference |", "|---|---|---|",
             f"| rainflow, E1049 history (range, count) | {r['rainflow']} | (3, 0.5), (4, 1.5), (6, 0.5), (8, 1), (9, 0.5) |",
             f"| rainflow, repeated history | {r['rainflow_repeated']} | full cycles 3, 4, 7, 9 |",
             f"| block life, prescribed K | {b['N_prescribed']:.6g} blocks | {b['N_exact']:.6g} (closed form) |",
             f"| block life, cracklip's K (plate 2 m wide, a 1 -> 10 mm) | {b['N']:.6g} blocks ({b['rel_error']:.2%}) | "
             f"{b['N_exact']:.6g} |",
             f"| NASGRO equation, {len(r['nasgro'])} check values | largest error "
             f"{max(x['rel_error'] for x in r['nasgro']):.1e} | notes' values |",
             f"| Wheeler, constant amplitude / one 1.5x overload | {w['N_ca']:.0f} / {w['N_overload']:.0f} | "
             f"{w['N_ca_check']} / {w['N_overload_check']} (cycle by cycle) |",
             f"| beta of a centre crack in a strip | largest error {r['beta']['max_rel_error_tada']:.2%} | Tada |", "",
             f"Spectrum life, crack at a hole ({sp['cycles_per_pass']:.0f} cycles and {sp['blocks_per_pass']} flights "
             f"per pass, {sp['load_states']} load states): {sp['growth_steps']} growth steps, {sp['solves']} solves "
             f"(bound steps x (levels + 2) = {sp['solves_bound']}), {sp['load_levels']} levels per step; "
             f"{sp['t_step']:.3f} s per step against {sp['t_step_constant_amplitude']:.3f} s for a "
             f"constant-amplitude step ({sp['step_time_ratio']:.2f}x).", "",
             "| closure | passes | flights | cycles | failure |", "|---|---|---|---|---|"]
    for c in ("contact", "newman", "none"):
        f = sp["failure"][c]
        lines.append(f"| {c} | {sp['life_passes'][c]:.4g} | {sp['life_blocks'][c]:.5g} | {sp['life_cycles'][c]:.4g} | "
                     + (f"{f['criterion']} at a = {f['a']:.3g} mm" if f else sp["stop"][c]) + " |")
    return "\n".join(lines) + "\n"


def plot(r: dict, out: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fe = r["block_life"]["fe"]
    fig, ax = plt.subplots(figsize=(6, 4))
    a = np.asarray(fe["a_mm"])
    fine = np.linspace(1.0, a[-1], 200)
    ranges = [(10 * rr, c) for rr, c in rainflow(E1049)]
    ax.plot([block_closed_form(1e-3, x * 1e-3, ranges) if x > 1.0 else 0.0 for x in fine], fine, "k-", lw=0.8,
            label="closed form")
    ax.plot(fe["blocks"], a, "o", ms=4, label="cracklip (K solved at each growth step)")
    ax.set_xlabel("blocks (E1049 history x 10 MPa)")
    ax.set_ylabel("half length a [mm]")
    ax.set_title("Griffith crack under a block of the E1049 history")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "block_life.png", dpi=150)
    plt.close(fig)
    sp = r["spectrum"]
    fig, ax = plt.subplots(figsize=(6, 4))
    for closure, rows in sp["a_N"].items():
        an = np.asarray(rows)
        ax.plot(an[:, 2], an[:, 0], "o-", ms=3, label=f"closure {closure}: {sp['life_blocks'][closure]:.0f} flights")
    ax.set_xlabel("flights")
    ax.set_ylabel("crack length from the hole [mm]")
    ax.set_title("Crack at a hole, flight spectrum, to failure", fontsize=10)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "spectrum_life.png", dpi=150)
    plt.close(fig)


if __name__ == "__main__":
    main()
