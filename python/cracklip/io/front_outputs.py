"""Stress intensity factors along 3D crack fronts as files: front.csv,
front_sifs.png and front_sifs.vtu, and the rows of results.json's "sifs".

The rows come from Solution3D.stress_intensity_factors(None)
(cracklip.fracture.sif_3d): one per front point of every crack.

- ``front.csv``: FRONT_COLUMNS, one line per front point (the parametric
  angle only for elliptical fronts, limited_by empty when the domain was
  not clipped, free_surface 1 where the front meets the part's boundary:
  K there is not the square-root singularity's and is flagged);
- ``front_sifs.png``: K_I, K_II, K_III against the arc length (against the
  parametric angle for elliptical fronts) per crack, with the spread of the
  three domains as error bars and the free-surface points marked;
- ``front_sifs.vtu``: the front points as polylines per front piece (a
  closed loop closes) carrying K_I, K_II, K_III, the spreads, G, the mode
  mix, the domain radius, the free-surface flag and the local frame, to
  colour the front in ParaView.
"""
from __future__ import annotations

import math
import pathlib
import typing

import numpy as np

from .vtu import VtuMesh

#: front.csv's columns (keys of the rows).
FRONT_COLUMNS = ["crack", "crack_name", "point", "piece", "s", "x", "y", "z", "parametric_angle", "K_I", "K_II",
                 "K_III", "K_I_spread", "K_II_spread", "K_III_spread", "G", "mode_mix_deg", "radius", "radius_min",
                 "element_size", "hat", "curvature", "limited_by", "free_surface", "domain_clear"]


def front_rows(solution) -> list[dict[str, typing.Any]]:
    """results.json's "sifs" of a 3D solution: one row per front point of
    every crack (Solution3D.stress_intensity_factors(None)), the smallest
    domain's radius added as radius_min."""
    rows = solution.stress_intensity_factors(None)
    for r in rows:
        r["radius_min"] = float(min(r["radii"])) if r.get("radii") else None
    return rows


def csv_rows(rows: typing.Sequence[dict]) -> list[list]:
    out = []
    for r in rows:
        line = []
        for k in FRONT_COLUMNS:
            v = r.get(k)
            if isinstance(v, bool):
                v = int(v)
            line.append(v)
        out.append(line)
    return out


def _pieces(rows: typing.Sequence[dict]) -> dict[tuple[int, int], list[int]]:
    groups: dict[tuple[int, int], list[int]] = {}
    for i, r in enumerate(rows):
        groups.setdefault((int(r["crack"]), int(r["piece"])), []).append(i)
    for idx in groups.values():
        idx.sort(key=lambda i: rows[i]["s"])
    return groups


def front_sif_mesh(rows: typing.Sequence[dict], closed: typing.Callable[[int, int], bool] | None = None) -> VtuMesh:
    """The front points as polylines carrying K (closed(crack, piece): whether
    the piece is a loop; default: a piece without free-surface points)."""
    if not rows:
        return VtuMesh(np.zeros((0, 3)), "line", np.zeros((0, 2), dtype=np.int64))
    x = np.array([[r["x"], r["y"], r["z"]] for r in rows], dtype=float)
    conn = []
    for (c, p), idx in _pieces(rows).items():
        conn += [(a, b) for a, b in zip(idx[:-1], idx[1:])]
        loop = closed(c, p) if closed is not None else not any(rows[i]["free_surface"] for i in idx)
        if loop and len(idx) > 2:
            conn.append((idx[-1], idx[0]))
    data = {k: np.array([float(r[k]) if r[k] is not None else math.nan for r in rows])
            for k in ("s", "K_I", "K_II", "K_III", "K_I_spread", "K_II_spread", "K_III_spread", "G", "mode_mix_deg",
                      "radius", "element_size")}
    data["mode_mix_deg"] = np.nan_to_num(data["mode_mix_deg"], nan=0.0)
    data["free_surface"] = np.array([int(r["free_surface"]) for r in rows], dtype=np.int32)
    data["crack"] = np.array([int(r["crack"]) for r in rows], dtype=np.int32)
    data["e1"] = np.array([r["direction"] for r in rows], dtype=float)
    data["e2"] = np.array([r["normal"] for r in rows], dtype=float)
    return VtuMesh(x, "line", np.array(conn, dtype=np.int64).reshape(-1, 2), point_data=data)


def write_front_png(rows: typing.Sequence[dict], path: pathlib.Path, title: str = "", k_unit: str | None = None
                    ) -> None:
    """K_I, K_II, K_III along each crack's front (see the module)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cracks = sorted({int(r["crack"]) for r in rows})
    fig, axes = plt.subplots(len(cracks), 1, figsize=(7, 3.2 * len(cracks)), squeeze=False)
    for ax, c in zip(axes[:, 0], cracks):
        mine = [r for r in rows if int(r["crack"]) == c]
        angle = all(r["parametric_angle"] is not None for r in mine)
        t = np.array([math.degrees(r["parametric_angle"]) if angle else r["s"] for r in mine])
        o = np.argsort(t)
        free = np.array([bool(r["free_surface"]) for r in mine])
        for name, col in (("K_I", "C0"), ("K_II", "C1"), ("K_III", "C2")):
            k = np.array([r[name] for r in mine])
            sp = np.array([r[f"{name}_spread"] for r in mine])
            ax.errorbar(t[o], k[o], yerr=0.5 * sp[o], fmt="o-", color=col, ms=3, lw=1, capsize=2, label=name)
            if free.any():
                ax.plot(t[free], k[free], "kx", ms=8)
        if free.any():
            ax.plot([], [], "kx", label="free surface (flagged)")
        ax.axhline(0.0, color="0.7", lw=0.5)
        ax.set_xlabel("parametric angle [deg]" if angle else "arc length along the front")
        ax.set_ylabel(f"K [{k_unit}]" if k_unit else "K")
        ax.set_title(f"{title}{': ' if title else ''}crack {mine[0]['crack_name'] or c}", fontsize=9)
        ax.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


__all__ = ["FRONT_COLUMNS", "front_rows", "csv_rows", "front_sif_mesh", "write_front_png"]
