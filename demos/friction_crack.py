"""Coulomb friction on a closed crack (issue 16): exact checks.

1. The closed inclined Griffith crack (half length a = 0.5 at beta from the x
   axis) under uniaxial compression p along y: sigma_n = p cos^2(beta) presses
   the lips (uniform contact pressure), tau = p sin(beta) cos(beta) shears
   them. It sticks (K_II = 0, no slip) when tau <= mu sigma_n, else slips as a
   whole: K_II = (tau - mu sigma_n) sqrt(pi a), K_I = 0, slip 4 (1 - nu^2) /
   E (tau - mu sigma_n) sqrt(a^2 - x^2). The exact field (uniform stress plus
   the Westergaard mode-II field of tau_eff, cracklip.griffith) is imposed on
   the boundary of [-1, 1]^2.
2. Load-unload hysteresis: hold sigma_n, raise the shear to tau_max, remove
   it: the locked-in slip is 4 (1 - nu^2) / E min(tau_max - mu sigma_n, mu
   sigma_n) sqrt(a^2 - x^2) (reverse slip when tau_max > 2 mu sigma_n; none
   left with mu = 0). Each stage's exact field on the boundary.

    /usr/bin/python3 demos/friction_crack.py --out results/friction
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
from cracklip.io.files import write_json  # noqa: E402

A = 0.5
P = 1.0
MAT = cl.Material(1.0, 0.3)


def exact(beta: float, mu: float, p: float = P, a: float = A, material: cl.Material = MAT
          ) -> tuple[GriffithField, float, float]:
    """(exact field, tau_eff, sigma_n) of the closed crack under compression p along y."""
    s_tt, s_nn, s_tn = remote_in_crack_frame((0.0, -p, 0.0), beta)
    sigma_n = -s_nn
    if abs(s_tn) <= mu * sigma_n:  # stick: the lips carry the whole shear
        tau_eff, q = 0.0, -s_tn
    else:
        tau_eff = math.copysign(abs(s_tn) - mu * sigma_n, s_tn)
        q = tau_eff - s_tn
    return GriffithField(material, a=a, angle=beta, remote=(s_tt, s_nn, s_tn), pressure=sigma_n, shear=q), \
        tau_eff, sigma_n


def scene_for(field: GriffithField, n: int, mu: float, contact: str = "unilateral", radius: float = 0.1,
              tip_h: float | None = None, **options) -> cl.Scene:
    """The exact field on the boundary of [-1, 1]^2 (n divisions per side), tips refined to h / 4."""
    h = 2.0 / n
    tips = field.tips
    md = cl.create_square(h, refine=[(t[0], t[1], tip_h or h / 4, 0.0) for t in tips])
    return cl.Scene(md, field.material, cracks=[cl.Crack(tips, name="closed crack")],
                    dirichlet=[cl.Dirichlet(side, None, lambda x, s: field.displacement(x, s))
                               for side in ("left", "right", "bottom", "top")],
                    options=cl.Options(radius=radius, contact=contact, friction=mu, **options))


def profile_errors(sol: cl.Solution, field: GriffithField) -> dict:
    """Pressure and slip along the crack against the exact ones."""
    smp = sol.lip_samples(0, 4)
    x = (smp["x"] - np.asarray(field.center)) @ field.rotation[:, 0]
    exact_slip = field.jump(x)[:, 1]
    w = smp["weight"]
    sigma_n = field.pressure
    p = smp["pressure"]
    scale = max(float(np.sqrt(np.sum(w * exact_slip ** 2) / np.sum(w))), 1e-300)
    return {"pressure_max_rel_dev": float(np.abs(p - sigma_n).max() / sigma_n),
            "pressure_l2_rel": float(np.sqrt(np.sum(w * (p - sigma_n) ** 2) / np.sum(w * sigma_n ** 2))),
            "slip_l2": float(np.sqrt(np.sum(w * (smp["slip"] - exact_slip) ** 2) / np.sum(w))),
            "slip_l2_rel": (float(np.sqrt(np.sum(w * (smp["slip"] - exact_slip) ** 2) / np.sum(w))) / scale
                            if np.any(exact_slip) else None),
            "slip_max_abs": float(np.abs(smp["slip"]).max()),
            "interpenetration_max": float(max(0.0, -smp["gap"].min()))}


def run(beta: float, mu: float, n: int = 40, contact: str = "unilateral", radius: float = 0.1) -> dict:
    """One row of the table (issue 16, acceptance 1)."""
    field, tau_eff, sigma_n = exact(beta, mu)
    t0 = time.perf_counter()
    sol = cl.solve(scene_for(field, n, mu, contact, radius))
    t_solve = time.perf_counter() - t0
    ks = sol.stress_intensity_factors(0)
    c = sol.contact
    states = c.get("state")
    counts = ({name: int(np.count_nonzero(states == code)) for code, name in ((0, "open"), (1, "stick"), (2, "slip"))}
              if states is not None else {"open": 0, "stick": 0, "slip": int(np.count_nonzero(c["active"]))})
    k_ref = P * math.sqrt(math.pi * A)
    return {"beta_deg": beta, "mu": mu, "n": n, "h": 2.0 / n, "ndofs": sol.model.num_dofs, "contact": contact,
            "K_I": max((k["K_I"] for k in ks), key=abs), "K_II": float(np.mean([k["K_II"] for k in ks])),
            "K_II_tips": [k["K_II"] for k in ks], "K_II_exact": tau_eff * math.sqrt(math.pi * A),
            "K_II_error": max(abs(k["K_II"] - tau_eff * math.sqrt(math.pi * A)) for k in ks) / k_ref,
            "K_I_error": max(abs(k["K_I"]) for k in ks) / k_ref, "sigma_n": sigma_n, "tau_eff": tau_eff,
            "stick_exact": tau_eff == 0.0, **profile_errors(sol, field), "state_counts": counts,
            "iterations": int(c["iterations"]), "method": c.get("method", "frictionless"), "t_solve": t_solve}


def hysteresis(mu: float, sigma_n: float = 1.0, tau_max: float = 0.7, n: int = 40, load_steps: int = 1) -> dict:
    """Hold sigma_n on a crack along x (a = 0.5), raise the shear to tau_max
    and remove it. The boundary carries each stage's exact field (the
    uniform stress and the crack's mode-II perturbation of that stage's
    effective shear: load groups "clamp", "shear" and "slip"). Returns the
    locked-in slip against 4 (1 - nu^2) / E min(tau_max - mu sigma_n, mu
    sigma_n) sqrt(a^2 - x^2)."""
    base = GriffithField(MAT, a=A)
    clamp = GriffithField(MAT, a=A, remote=(0.0, -sigma_n, 0.0), pressure=sigma_n)  # closed, uniform
    shear = GriffithField(MAT, a=A, remote=(0.0, 0.0, 1.0), shear=-1.0)  # uniform shear 1, no slip
    pert = GriffithField(MAT, a=A, remote=(0.0, 0.0, 1.0), shear=0.0)  # unit slip field ...
    unit_shear_u = lambda x, s: shear.displacement(x, s)  # noqa: E731
    slip_u = lambda x, s: pert.displacement(x, s) - unit_shear_u(x, s)  # ... minus the uniform part  # noqa: E731
    tau1 = max(tau_max - mu * sigma_n, 0.0)                       # slip while loading
    tau_back = max(tau_max - 2 * mu * sigma_n, 0.0)               # reverse slip while unloading
    locked = tau1 - tau_back                                      # = min(tau_max - mu sigma_n, mu sigma_n)
    h = 2.0 / n
    md = cl.create_square(h, refine=[(t[0], t[1], h / 4, 0.0) for t in base.tips])
    dirichlet = []
    for side in ("left", "right", "bottom", "top"):
        dirichlet += [cl.Dirichlet(side, None, lambda x, s: clamp.displacement(x, s), group="clamp"),
                      cl.Dirichlet(side, None, unit_shear_u, group="shear"),
                      cl.Dirichlet(side, None, slip_u, group="slip")]
    path = [cl.LoadStep({"clamp": 1.0}, "clamp"), cl.LoadStep({"shear": tau_max, "slip": tau1}, "shear up"),
            cl.LoadStep({"shear": 0.0, "slip": locked}, "shear removed")]
    scene = cl.Scene(md, MAT, cracks=[cl.Crack(base.tips, name="crack")], dirichlet=dirichlet, load_path=path,
                     options=cl.Options(radius=0.1, contact="bilateral", friction=mu, load_steps=load_steps))
    t0 = time.perf_counter()
    sol = cl.solve(scene)
    out = {"mu": mu, "sigma_n": sigma_n, "tau_max": tau_max, "n": n, "t_solve": time.perf_counter() - t0,
           "locked_exact_tau": locked, "steps": []}
    for st in sol.steps:
        smp = st.lip_samples(0, 4)
        x = smp["s"] - A
        expect = {"clamp": 0.0, "shear up": tau1, "shear removed": locked}[st.step["name"]]
        exact_slip = (MAT.kappa + 1) / (2 * MAT.mu) * expect * np.sqrt(np.maximum(A ** 2 - x ** 2, 0.0))
        w = smp["weight"]
        ref = max(float(np.abs(exact_slip).max()), 1e-300)
        out["steps"].append({"name": st.step["name"], "slip_max": float(np.abs(smp["slip"]).max()),
                             "slip_exact_max": float(np.abs(exact_slip).max()),
                             "slip_error_rel": float(np.abs(smp["slip"] - exact_slip).max() / ref)
                             if expect else None,
                             "K_II": [k["K_II"] for k in st.stress_intensity_factors(0)],
                             "K_II_exact": expect * math.sqrt(math.pi * A),
                             "iterations": st.contact["iterations"]})
    return out


def inf_sup_rows(ns=(10, 20, 40, 80)) -> list[dict]:
    """sqrt(beta_min) of the normal multipliers and of the pair [B_n; B_t] on
    the paper's block (section 5.1), h = 2 / n."""
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    import block_uniform_pressure
    from cracklip.contact.infsup import inf_sup_constant
    rows = []
    for n in ns:
        model = cl.create_model(block_uniform_pressure.scene_for(n))
        rows.append({"n": n, "h": 2.0 / n, "normal": inf_sup_constant(model),
                     "normal_and_tangential": inf_sup_constant(model, tangential=True)})
    return rows


def markdown(rows: list[dict]) -> str:
    betas = sorted({r["beta_deg"] for r in rows})
    mus = sorted({r["mu"] for r in rows})
    n = max(r["n"] for r in rows)
    lines = [f"K_II / (p sqrt(pi a)) at h = {2.0 / n:g} (computed; exact in brackets):", "",
             "| beta | " + " | ".join(f"mu = {m:g}" for m in mus) + " |", "|---|" + "---|" * len(mus)]
    for b in betas:
        cells = []
        for m in mus:
            r = next((r for r in rows if r["beta_deg"] == b and r["mu"] == m and r["n"] == n), None)
            kref = P * math.sqrt(math.pi * A)
            cells.append("" if r is None else f"{abs(r['K_II']) / kref:.5f} ({abs(r['K_II_exact']) / kref:.5f})"
                         + (" stick" if r["stick_exact"] else ""))
        lines.append(f"| {b:g} | " + " | ".join(cells) + " |")
    lines += ["", "| beta | mu | h | K_II error | K_I | pressure max dev | pressure L2 | slip L2 (rel) | states "
                  "(open/stick/slip) | iterations |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        sc = r["state_counts"]
        lines.append(f"| {r['beta_deg']:g} | {r['mu']:g} | {r['h']:g} | {r['K_II_error']:.1e} | {r['K_I_error']:.1e} | "
                     f"{100 * r['pressure_max_rel_dev']:.2f} % | {100 * r['pressure_l2_rel']:.3f} % | "
                     + ("-" if r["slip_l2_rel"] is None else f"{100 * r['slip_l2_rel']:.2f} %")
                     + f" | {sc['open']}/{sc['stick']}/{sc['slip']} | {r['iterations']} |")
    return "\n".join(lines) + "\n"


def extras_markdown(result: dict) -> str:
    """The hysteresis and inf-sup tables, when computed."""
    lines = []
    if result.get("hysteresis"):
        lines += ["", "Load-unload cycle (sigma_n = 1, shear up to 0.7 and back to 0; slip max against the exact):", "",
                  "| mu | sheared: slip (exact) | K_II (exact) | unloaded: slip (exact) | K_II (exact) |",
                  "|---|---|---|---|---|"]
        for r in result["hysteresis"]:
            up, end = r["steps"][1], r["steps"][2]
            lines.append(f"| {r['mu']:g} | {up['slip_max']:.5f} ({up['slip_exact_max']:.5f}) | "
                         f"{np.mean(up['K_II']):.5f} ({up['K_II_exact']:.5f}) | {end['slip_max']:.3g} "
                         f"({end['slip_exact_max']:.5f}) | {np.mean(end['K_II']):.3g} ({end['K_II_exact']:.5f}) |")
    if result.get("inf_sup"):
        lines += ["", "Inf-sup sqrt(beta_min) on the paper's block:", "", "| h | normal | normal and tangential |",
                  "|---|---|---|"]
        lines += [f"| {r['h']:g} | {r['normal']:.3f} | {r['normal_and_tangential']:.3f} |" for r in result["inf_sup"]]
    return "\n".join(lines) + ("\n" if lines else "")


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--betas", type=float, nargs="+", default=[30.0, 45.0, 60.0])
    ap.add_argument("--mus", type=float, nargs="+", default=[0.0, 0.2, 0.3, 0.5, 1.0])
    ap.add_argument("--ns", type=int, nargs="+", default=[80], help="divisions per side of [-1, 1]^2")
    ap.add_argument("--contact", default="unilateral", choices=["bilateral", "unilateral"])
    ap.add_argument("--json", type=pathlib.Path, default=None)
    ap.add_argument("--out", type=pathlib.Path, default=None, help="folder for friction.{json,md,png}")
    ap.add_argument("--no-hysteresis", action="store_true")
    ap.add_argument("--inf-sup", action="store_true", help="also the inf-sup values of [B_n; B_t] on the block")
    args = ap.parse_args(argv)
    rows = []
    for n in args.ns:
        for b in args.betas:
            for m in args.mus:
                rows.append(run(b, m, n, args.contact))
                r = rows[-1]
                print(f"beta {b:g}, mu {m:g}, n {n}: K_II {r['K_II']:.5f} (exact {r['K_II_exact']:.5f}), "
                      f"{r['iterations']} iterations, {r['t_solve']:.2f} s", file=sys.stderr)
    result = {"rows": rows}
    if not args.no_hysteresis:
        result["hysteresis"] = [hysteresis(mu, n=min(args.ns)) for mu in (0.0, 0.3, 0.5)]
    if args.inf_sup:
        result["inf_sup"] = inf_sup_rows()
    if args.json:
        write_json(args.json, result)
    if args.out:
        write_json(args.out / "friction.json", result)
        (args.out / "friction.md").write_text(markdown(rows) + extras_markdown(result))
        if __name__ == "__main__":
            plot(rows, args.out / "friction.png")
    return result


def plot(rows: list[dict], path: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4))
    kref = P * math.sqrt(math.pi * A)
    mu = np.linspace(0.0, 1.0, 101)
    for k, b in enumerate(sorted({r["beta_deg"] for r in rows})):
        br = math.radians(b)
        ex = np.maximum(math.sin(br) * math.cos(br) - mu * math.cos(br) ** 2, 0.0)
        ax.plot(mu, ex, "-", color=f"C{k}", lw=0.8, label=f"beta = {b:g} exact")
        pts = [(r["mu"], abs(r["K_II"]) / kref) for r in rows if r["beta_deg"] == b and r["n"] == max(x["n"] for x in rows)]
        ax.plot(*zip(*pts), "o", color=f"C{k}", label=f"beta = {b:g} cracklip")
    ax.set_xlabel("friction coefficient mu")
    ax.set_ylabel("K_II / (p sqrt(pi a))")
    ax.set_title("closed inclined crack under compression")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


if __name__ == "__main__":
    main()
