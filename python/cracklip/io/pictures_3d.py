"""The PNG of a 3D run: the crack opening over each crack surface.

``crack_opening.png``: one panel per crack, the normal opening [[u]].n at
the vertices of the lip facets (post.subcells_3d.lip_facets_3d), drawn
over the facets in the crack's own plane coordinates (from the crack's
plane() origin, along its directions: the semi-axes of an ellipse, a polygon's first edge, the
principal directions of a triangulated surface, onto which it is
projected), with the front in black and a labelled colour bar (in the
scene's units when it gives them). The same samples go to
crack_opening.csv (outputs_3d).
"""
from __future__ import annotations

import pathlib
import typing

import numpy as np

from ..scene.units import label as unit_label
from .pictures import new_figure, save_png


def axis_text(v: np.ndarray) -> str:
    """'x', '-z' for a coordinate direction, else 'along [0.6, 0.8, 0]'."""
    v = np.where(np.abs(v) < 1e-12, 0.0, np.asarray(v, dtype=float))
    k = int(np.argmax(np.abs(v)))
    if abs(abs(v[k]) - 1.0) < 1e-9:
        return ("-" if v[k] < 0 else "") + "xyz"[k]
    return "along [" + ", ".join(f"{c:.3g}" for c in v) + "]"


def plane_coordinates(crack, x: np.ndarray) -> np.ndarray:
    """In-plane coordinates (n, 2) of points (n, 3) in the crack's plane()."""
    origin, e1, e2 = crack.plane()
    d = np.asarray(x, dtype=float).reshape(-1, 3) - origin
    return np.column_stack([d @ e1, d @ e2])


def write_crack_opening_png(cracks: typing.Sequence, facets: typing.Sequence[dict], fronts: typing.Sequence[dict],
                            path: pathlib.Path, title: str = "", units=None) -> pathlib.Path:
    """crack_opening.png (module doc): cracks (the scene's crack surfaces),
    facets (lip_facets_3d per crack), fronts (CrackGeometry3D.front per crack)."""
    from matplotlib.collections import LineCollection
    from matplotlib.tri import Triangulation
    from mpl_toolkits.axes_grid1 import make_axes_locatable
    n = len(cracks)
    uvs = [plane_coordinates(c, f["x"]) for c, f in zip(cracks, facets)]
    # Panel height from the widest crack's aspect ratio (a colour bar as tall as each picture).
    aspect = max([float(np.ptp(uv[:, 1]) / max(np.ptp(uv[:, 0]), 1e-300)) for uv in uvs if len(uv)] or [1.0])
    fig = new_figure((6.0 * n, 1.6 + 4.2 * min(max(aspect, 0.35), 1.4)))
    axes = {}
    for k, (crack, f, fr, uv) in enumerate(zip(cracks, facets, fronts, uvs)):
        ax = fig.add_subplot(1, n, k + 1)
        gap = f["gap"].reshape(-1)
        if len(gap):
            tri = Triangulation(uv[:, 0], uv[:, 1], np.arange(len(uv)).reshape(-1, 3))
            lo, hi = min(0.0, float(gap.min())), float(gap.max())
            coll = ax.tripcolor(tri, gap, shading="gouraud", cmap="viridis", vmin=lo, vmax=hi if hi > lo else lo + 1.0)
            cax = make_axes_locatable(ax).append_axes("right", size="4%", pad=0.12)
            bar = fig.colorbar(coll, cax=cax)
            bar.set_label(unit_label(units, "displacement", "normal opening [[u]].n"))
        fx = np.asarray(fr["x"]).reshape(-1, 3)
        if len(fx):
            q = plane_coordinates(crack, fx)
            seg = np.asarray(fr["segments"]).reshape(-1, 2)
            ax.add_collection(LineCollection(q[seg], colors="k", linewidths=1.2, label="front"))
        origin, e1, e2 = crack.plane()
        ax.set_xlabel(unit_label(units, "length", axis_text(e1)))
        ax.set_ylabel(unit_label(units, "length", axis_text(e2)))
        ax.set_aspect("equal")
        ax.autoscale_view()
        vmax = float(gap.max()) if len(gap) else 0.0
        ax.set_title(f"{crack.name}: max opening {vmax:.3g}" + (f" {units.name('displacement')}" if units else "")
                     + "\ncoordinates from its centre (" + ", ".join(f"{c:.4g}" for c in origin) + ")", fontsize=10)
        axes[f"crack {k}"] = ax
    if title:
        fig.suptitle(title)
    save_png(fig, path, axes)
    return path


__all__ = ["write_crack_opening_png", "plane_coordinates", "axis_text"]
