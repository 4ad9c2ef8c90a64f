"""A 3D crack closed by a residual stress: the surface crack of
demos/scenes/residual_stress_3d.toml in a shot-peened plate.

The plate 40 x 10 x 60 mm with the semi-elliptical surface crack a = 3,
c = 5 mm on its face y = 10; the residual stress sigma_0,zz = 150 - 30 y
MPa (an initial stress: compressive at the peened face, its moment carried
by the end z = 30) under a service tension of 100 MPa. On the crack's plane
the stress is -50 + 30 d at the depth d below the face: Newman and Raju's
tension S = 100 and face bending S_b = -150 MPa.

Two runs of the scene as shipped (without the error estimate):
- the lips free to overlap (options.contact = "none", linear): K_I along
  the front against Newman and Raju's K = (S + H S_b) sqrt(pi a / Q) F
  (cracklip.exact.newman_raju; their fit +-5 %), errors relative to the
  tension's K at each point (the larger of the two terms K is the
  difference of);
- with unilateral contact (the scene as written): the closed part of the
  crack, the pressure, K_I along the front.

Writes residual_stress_3d.csv (per front point: the parametric angle from
the face, K_I without and with contact, Newman and Raju's) and
residual_stress_3d.png (the same along the front) next to the JSON, and
the contact run's outputs (crack_contact.png: the closed part) in the
folder `contact`.

    /usr/bin/python3 demos/residual_stress_3d.py --json out/residual_stress_3d.json
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import pathlib
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

SCENE = HERE / "scenes" / "residual_stress_3d.toml"
#: The crack and plate of the scene (mm) and its stresses on the crack's plane (MPa).
A, C, T, B = 3.0, 5.0, 10.0, 20.0
S, S_B = 100.0, -150.0


def _run(out: pathlib.Path, *settings: str) -> tuple[dict, list[dict], float]:
    """`cracklip run` of the scene without the error estimate (its warnings,
    expected on this scene, in results.json only): results.json, front.csv's
    rows, the seconds it took."""
    import contextlib
    import io
    from cracklip import cli
    args = ["run", str(SCENE), "--out", str(out), "--quiet", "--no-estimate"]
    for s in settings:
        args += ["--set", s]
    t0 = time.perf_counter()
    with contextlib.redirect_stderr(io.StringIO()) as err:
        rc = cli.main(args)
    if rc != 0:
        raise SystemExit(f"cracklip run {SCENE.name} {' '.join(settings)} failed: {err.getvalue()}")
    seconds = time.perf_counter() - t0
    with (out / "front.csv").open() as f:
        rows = list(csv.DictReader(f))
    return json.loads((out / "results.json").read_text()), rows, seconds


def _phi(rows: list[dict]) -> list[float]:
    """Newman and Raju's parametric angle from the face (0 at the surface ends, pi/2 the deepest point)."""
    out = []
    for r in rows:
        p = abs(float(r["parametric_angle"]))
        out.append(min(p, math.pi - p))
    return out


def run(folder: pathlib.Path) -> dict:
    import numpy as np
    from cracklip.exact.newman_raju import surface_crack_k
    linear, lin_rows, t_linear = _run(folder / "linear", "options.contact=none")
    closed, con_rows, t_contact = _run(folder / "contact")
    phi = np.array(_phi(lin_rows))
    K_lin = np.array([float(r["K_I"]) for r in lin_rows])
    K_con = np.array([float(r["K_I"]) for r in con_rows])
    nr = surface_crack_k(S, A, C, T, B, phi, bending=S_B)
    scale = surface_crack_k(S, A, C, T, B, phi)
    err = (K_lin - nr) / scale
    deep = int(np.argmax(phi))
    crack = closed["cracks"][0]
    return {"dofs": closed["solution"]["dofs"], "front_points": len(lin_rows),
            "phi_deg": np.degrees(phi).round(3).tolist(), "K_I_linear": K_lin.tolist(), "K_I_contact": K_con.tolist(),
            "K_I_newman_raju": nr.tolist(), "K_tension": scale.tolist(),
            "K_I_deepest_linear": float(K_lin[deep]), "K_I_deepest_newman_raju": float(nr[deep]),
            "K_I_deepest_contact": float(K_con[deep]),
            "err_deepest": float(err[deep]), "err_max": float(np.abs(err).max()),
            "closed_fraction": crack["closed_fraction"], "pressure_max": crack["pressure"]["max"],
            "interpenetration_max": crack["interpenetration_max"], "gap_max": crack["gap_max"],
            "K_I_shut_ends": [float(K_con[0]), float(K_con[-1])], "K_I_max_contact": float(K_con.max()),
            "contact_iterations": closed["contact"]["iterations"],
            "t_linear": t_linear, "t_contact": t_contact}


def write_figure(res: dict, folder: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = res["front_points"]
    with (folder / "residual_stress_3d.csv").open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["point", "phi_deg", "K_I_linear", "K_I_newman_raju", "K_I_contact", "K_tension"])
        for k in range(n):
            w.writerow([k, res["phi_deg"][k], res["K_I_linear"][k], res["K_I_newman_raju"][k], res["K_I_contact"][k],
                        res["K_tension"][k]])
    fig, ax = plt.subplots(figsize=(7.0, 4.0))
    x = range(n)
    ax.plot(x, res["K_I_newman_raju"], "k--", label="Newman-Raju, tension 100 + bending -150 MPa")
    ax.plot(x, res["K_I_linear"], "o-", label="cracklip, lips free to overlap")
    ax.plot(x, res["K_I_contact"], "s-", label="cracklip, lip contact (mouth shut)")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("front point (surface end, deepest point, surface end)")
    ax.set_ylabel("K_I [MPa sqrt(mm)]")
    ax.set_title(f"surface crack in a peened plate: closed {100 * res['closed_fraction']:.0f} % with contact")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(folder / "residual_stress_3d.png", dpi=110)
    plt.close(fig)


def markdown(res: dict) -> str:
    return (f"Surface crack a = 3, c = 5 mm in a plate whose peened face is in compression (sigma_0,zz = 150 - "
            f"30 y MPa) under 100 MPa ({res['dofs']} dofs). Lips free to overlap: K_I at the deepest point "
            f"{res['K_I_deepest_linear']:.2f} against Newman-Raju's {res['K_I_deepest_newman_raju']:.2f} MPa "
            f"sqrt(mm) in tension and bending ({100 * res['err_deepest']:+.2f} % of the tension's K; largest along "
            f"the front {100 * res['err_max']:.1f} %, their fit +-5 %). With lip contact the mouth shuts over "
            f"{100 * res['closed_fraction']:.0f} % of the crack (pressure up to {res['pressure_max']:.1f} MPa), "
            f"K_I at the deepest point {res['K_I_deepest_contact']:.1f}, at the shut ends "
            f"{res['K_I_shut_ends'][0]:.2f}, {res['K_I_shut_ends'][1]:.2f}.\n")


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=pathlib.Path, default=pathlib.Path("results/residual_stress_3d.json"))
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    folder = args.json.parent / args.json.stem
    folder.mkdir(parents=True, exist_ok=True)
    res = run(folder)
    write_figure(res, folder)
    from cracklip.io.files import write_json
    write_json(args.json, res)
    if not args.quiet:
        print(markdown(res))
    return res


if __name__ == "__main__":
    main()
