"""Where the closed penny's contact pressure errs (issue 36, acceptance 1):
the cases of demos/contact_3d.py, per mesh, the reduced multipliers (the
stable groups' pressures) against the exact uniform p.

Per case and a / h_front, over the groups whose nodes' centroid lies within
rho < 0.7 a (away from the front cells): the RMS and largest relative error
of the group values; the correlation of each group's error with the mean
error of its neighbours (the groups it shares multiplier mass with; near -1:
a checkerboard); the RMS after averaging each group with its neighbours;
the largest and RMS error per number of members of a group. And over the
lip samples off the front cells (demos/contact_3d.pressure_errors): the
largest error per band of distance from the front.

    /usr/bin/python3 demos/contact_3d_pressure_modes.py --json out/contact_3d_pressure_modes.json \
        [--cases beta45_mu0 beta30_stick] [--sizes 6 10 14]
"""
from __future__ import annotations

import argparse
import math
import pathlib
import sys

import numpy as np
import scipy.sparse as sps

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

import cracklip as cl  # noqa: E402
import contact_3d  # noqa: E402
from cracklip.exact.closed_penny import closed_penny_inclined  # noqa: E402
from cracklip.io.files import write_json  # noqa: E402

INNER = 0.7                      # groups with centroid rho < INNER a
BANDS = (0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.5, 1.01)


def group_errors(sol: cl.Solution, p: float) -> dict:
    """The reduced multipliers' errors (see the module's doc)."""
    cs = sol.contact["system"]
    f2r, node = np.asarray(cs.space.full_to_reduced), np.asarray(cs.space.full_node)
    e = (-sol.contact["lambda"] - p) / p
    nodal = node >= 0
    members = np.bincount(f2r, minlength=cs.num_multipliers)
    count = np.bincount(f2r[nodal], minlength=cs.num_multipliers)
    centre = np.column_stack([np.bincount(f2r[nodal], weights=sol.model.x[node[nodal], k],
                                          minlength=cs.num_multipliers) for k in range(3)])
    centre /= np.maximum(count, 1)[:, None]
    inner = (count > 0) & (np.hypot(centre[:, 0], centre[:, 1]) < INNER * contact_3d.A)
    adj = sps.csr_matrix(cs.M if cs.M.shape[0] == cs.num_multipliers else cs.R.T @ cs.M @ cs.R)
    adj.setdiag(0)
    adj.eliminate_zeros()
    adj.data[:] = np.abs(adj.data)
    neighbours = (adj @ e) / np.maximum(np.asarray(adj.sum(axis=1)).ravel(), 1e-300)
    ei, ni = e[inner], neighbours[inner]
    per_size = {int(k): {"groups": int(np.count_nonzero(members[inner] == k)),
                         "max": float(np.abs(ei[members[inner] == k]).max()),
                         "rms": float(np.sqrt(np.mean(ei[members[inner] == k] ** 2)))}
                for k in np.unique(members[inner])}
    return {"groups_inner": int(inner.sum()), "rms": float(np.sqrt(np.mean(ei ** 2))),
            "max": float(np.abs(ei).max()), "neighbour_correlation": float(np.corrcoef(ei, ni)[0, 1]),
            "rms_neighbour_averaged": float(np.sqrt(np.mean((0.5 * (ei + ni)) ** 2))), "per_members": per_size}


def band_errors(sol: cl.Solution, p: float) -> list[dict]:
    """The largest pressure error at the lip samples off the front cells per
    band of distance a - rho from the front."""
    smp = sol.lip_samples(0)
    cm = sol.model.cracks[0]
    off = cm.cell_class[smp["cell"]] != cm.CELL_CLASSES["front"]
    dist = contact_3d.A - np.hypot(smp["x"][:, 0], smp["x"][:, 1])
    e = np.abs(smp["pressure"] - p) / p
    out = []
    for lo, hi in zip(BANDS[:-1], BANDS[1:]):
        m = off & (dist >= lo) & (dist < hi)
        if m.any():
            out.append({"from": lo, "to": hi, "points": int(m.sum()), "max": float(e[m].max())})
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", type=pathlib.Path, required=True)
    ap.add_argument("--cases", nargs="+", default=["beta45_mu0", "beta30_stick"], choices=list(contact_3d.CASES))
    ap.add_argument("--sizes", nargs="+", type=int, default=[6, 10, 14])
    a = ap.parse_args(argv)
    rows = []
    for case in a.cases:
        beta, mu = contact_3d.CASES[case]
        ex = closed_penny_inclined(contact_3d.SIGMA, math.radians(beta), mu, contact_3d.A, contact_3d.NU)
        for n in a.sizes:
            sol = cl.solve(contact_3d.build(case, n))
            row = {"case": case, "size_over_h": n, "ndofs": int(sol.model.num_dofs),
                   **contact_3d.pressure_errors(sol, ex.p), "groups": group_errors(sol, ex.p),
                   "bands": band_errors(sol, ex.p)}
            rows.append(row)
            g = row["groups"]
            print(f"{case} a/h {n}: pressure_err {100 * row['pressure_err']:.2f} %, groups inside rho < {INNER}: "
                  f"RMS {100 * g['rms']:.2f} %, neighbour correlation {g['neighbour_correlation']:.2f}, "
                  f"averaged with neighbours {100 * g['rms_neighbour_averaged']:.2f} %", flush=True)
    write_json(a.json, {"rows": rows})
    return 0


if __name__ == "__main__":
    sys.exit(main())
