"""The PNGs of a run: the deformed part (with a zoom on small cracks), the crack
pressure and opening, the stress; cropped to their ink."""
from __future__ import annotations

import math
import pathlib

import numpy as np

from ..post.solution import Solution
from .files import atomic_path
from .paraview import von_mises


#: crack_pressure.png draws an open crack's tangential slip on the opening's
#: axis when it is at most this fraction of the largest opening (noise).
SLIP_PLOT_FRACTION = 1e-3


def new_figure(size):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    return fig


#: Resolution and margin of the PNGs (savefig's pad_inches for bbox_inches="tight").
PNG_DPI = 150


PNG_PAD_INCHES = 0.1


def save_png(fig, path: pathlib.Path) -> None:
    """fig as a PNG cropped to its ink (the pixels not of the face colour)
    plus PNG_PAD_INCHES on every side, drawn once: savefig(bbox_inches=
    "tight") draws every figure twice and measures the artists' boxes
    (get_tightbbox alone took 0.05 s per figure at 2e5 dofs); the ink box
    is the same content without the few pixels of slack in the artists'
    boxes. Ink on the canvas's border may continue outside the figure (a
    title longer than the figure is wide): such a figure goes to savefig
    (three draws then), which enlarges the picture to hold it."""
    fig.set_dpi(PNG_DPI)
    canvas = fig.canvas
    canvas.draw()
    rgba = np.asarray(canvas.buffer_rgba())
    height, width = rgba.shape[:2]
    face = np.round(np.asarray(fig.get_facecolor()) * 255).astype(np.uint8)
    # Ink: RGB not the face's (alpha may differ on an opaque canvas), one
    # 32-bit compare per pixel.
    rgb_mask = np.array([255, 255, 255, 0], dtype=np.uint8).view(np.uint32)[0]
    ink = (np.ascontiguousarray(rgba).view(np.uint32)[..., 0] & rgb_mask) != (face.view(np.uint32)[0] & rgb_mask)
    rows, cols = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
    if rows.size and (rows[0] == 0 or cols[0] == 0 or rows[-1] == height - 1 or cols[-1] == width - 1):
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=PNG_DPI, bbox_inches="tight", pad_inches=PNG_PAD_INCHES, format="png",
                        pil_kwargs={"compress_level": 1})
        return
    if rows.size:
        pad = int(round(PNG_PAD_INCHES * PNG_DPI))
        r0, r1, c0, c1 = rows[0] - pad, rows[-1] + 1 + pad, cols[0] - pad, cols[-1] + 1 + pad
    else:  # nothing drawn: the whole canvas
        r0, r1, c0, c1 = 0, height, 0, width
    crop = np.empty((r1 - r0, c1 - c0, 4), dtype=np.uint8)
    crop[...] = face
    rs, cs = slice(max(r0, 0), min(r1, height)), slice(max(c0, 0), min(c1, width))
    crop[rs.start - r0:rs.stop - r0, cs.start - c0:cs.stop - c0] = rgba[rs, cs]
    from PIL import Image
    with atomic_path(path) as tmp:
        # compress_level 1: a third of the encoding time of the default 6, files ~10 % larger.
        with open(tmp, "wb") as fh:
            Image.fromarray(crop).save(fh, format="png", compress_level=1)


def magnification(solution: Solution, fields: dict, requested: float) -> float:
    """The displacement scale of deformed.png: as requested, or such that the
    largest displacement is 5 % of the part's size."""
    if requested > 0.0:
        return requested
    size = float(np.ptp(solution.model.x, axis=0).max())
    umax = float(np.linalg.norm(fields["displacement"], axis=1).max()) if len(fields["displacement"]) else 0.0
    if umax <= 0.0:
        return 1.0
    return _round_scale(0.05 * size / umax)


def _round_scale(raw: float) -> float:
    """A scale factor rounded to one significant digit."""
    if not (raw > 0.0 and math.isfinite(raw)):
        return 1.0
    exp = math.floor(math.log10(raw))
    return float(round(raw / 10 ** exp) * 10 ** exp) or raw


#: deformed.png adds a zoomed panel when the cracks' box is below this fraction of the part.
ZOOM_FRACTION = 0.25


#: stress.png's colour scale ends at this area-weighted percentile of |stress|,
#: so that a tip singularity does not wash out the far field.
STRESS_PERCENTILE = 99.0


def crack_window(solution: Solution) -> tuple[np.ndarray, np.ndarray] | None:
    """(lower, upper) corners of a window around the cracks for a zoomed
    view, or None when the cracks are not much smaller than the part."""
    m = solution.model
    if not m.cracks:
        return None
    lo_part, hi_part = m.x.min(axis=0), m.x.max(axis=0)
    pts = np.concatenate([np.clip(cm.crack.points, lo_part, hi_part) for cm in m.cracks])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = float(max(np.ptp(pts, axis=0).max(), 1e-300))
    if span > ZOOM_FRACTION * float(np.ptp(m.x, axis=0).max()):
        return None
    centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo) + 0.35 * span
    return np.maximum(centre - half, lo_part), np.minimum(centre + half, hi_part)


def _weighted_percentile(values: np.ndarray, weights: np.ndarray, q: float) -> float:
    order = np.argsort(values)
    c = np.cumsum(weights[order])
    return float(values[order][min(np.searchsorted(c, q / 100.0 * c[-1]), len(c) - 1)])


#: Above this many sub-triangles in a panel, a field is drawn as an image
#: (cracklip.io.raster) instead of one polygon per triangle with its edges
#: (at 1.9e5 sub-triangles: polygons 3.9 s, image 0.1 s; the edges of that
#: many cells would blacken the picture anyway).
RASTER_MIN_TRIANGLES = 20_000


#: Pixels along the longer side of a rasterised panel.
RASTER_PIXELS = 1000


def _draw_field(ax, tris: np.ndarray, values: np.ndarray, cmap: str, clim: tuple[float, float],
                edges: bool):
    """Draw the field `values` constant on `tris` (n, 3, 2) into ax and
    return the mappable: polygons (with the mesh's edges if `edges`) up to
    RASTER_MIN_TRIANGLES, an image beyond."""
    if len(tris) <= RASTER_MIN_TRIANGLES:
        from matplotlib.collections import PolyCollection
        coll = PolyCollection(tris, array=values, cmap=cmap, edgecolors="k" if edges else "none",
                              linewidths=0.1 if edges else 0.0)
        coll.set_clim(*clim)
        ax.add_collection(coll)
        return coll
    from .raster import image_shape, rasterize
    lo, hi = tris.reshape(-1, 2).min(axis=0), tris.reshape(-1, 2).max(axis=0)
    extent = (float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1]))
    image = rasterize(tris, values, extent, image_shape(extent, RASTER_PIXELS))
    return ax.imshow(image, origin="lower", extent=extent, cmap=cmap, vmin=clim[0], vmax=clim[1],
                     interpolation="nearest", aspect="equal")


def write_pngs(solution: Solution, samples: list[dict], out: pathlib.Path, scale: float,
               component: str, title: str, fields: dict | None = None) -> list[str]:
    """deformed.png (sub-cells displaced, magnified; with a zoom on the
    cracks when they are small in the part), crack_pressure.png (pressure
    and gap, or opening and slip, along each crack) and stress.png (a
    stress component on the sub-cells, colour scale clipped at the
    STRESS_PERCENTILE area-weighted percentile). fields:
    solution.subcell_fields() if the caller has it already."""
    f = solution.subcell_fields() if fields is None else fields
    tris = f["points"].reshape(-1, 3, 2)
    disp = f["displacement"].reshape(-1, 3, 2)
    mag = magnification(solution, f, scale)
    names = []
    extent = np.ptp(solution.model.x, axis=0)
    height = float(np.clip(8.0 * extent[1] / max(extent[0], 1e-300), 3.0, 8.0))
    window = crack_window(solution)
    umag = np.linalg.norm(disp, axis=2).mean(axis=1)

    fig = new_figure((15.0, height) if window is not None else (8.0, height))
    panels = [fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)] if window is not None else [fig.add_subplot()]
    for k, ax in enumerate(panels):
        zoom = k == 1
        sel, m = slice(None), mag
        if zoom:
            c = tris.mean(axis=1)
            span = np.ptp(window, axis=0)
            sel = np.all((c >= window[0] - 0.1 * span) & (c <= window[1] + 0.1 * span), axis=1)
            # Its own scale: the largest displacement in the window is 5 % of the window.
            m = scale if scale > 0.0 else _round_scale(0.05 * float(span.max()) / max(float(umag[sel].max(initial=0.0)), 1e-300))
        coll = _draw_field(ax, (tris + m * disp)[sel], umag[sel], "viridis",
                           (float(umag.min(initial=0.0)), float(umag.max(initial=1.0))), edges=True)
        for smp in samples:
            for key in ("u_plus", "u_minus"):
                xy = smp["x"] + m * smp[key]
                ax.plot(xy[:, 0], xy[:, 1], "r-", lw=0.8)
        ax.autoscale()
        if zoom:
            ax.set_xlim(window[0][0], window[1][0])
            ax.set_ylim(window[0][1], window[1][1])
            ax.set_title(f"around the cracks, displacement x{m:g}", fontsize=9)
        elif window is not None:
            ax.add_patch(_rectangle(window))
            ax.set_title(f"displacement x{m:g}", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    fig.colorbar(coll, ax=panels, label="|u| (length units)")
    fig.suptitle(f"{title}\ndeformed mesh" + ("" if window is not None else f", displacement x{mag:g}"), fontsize=10)
    save_png(fig, out / "deformed.png")
    names.append("deformed.png")

    contact = bool(solution.contact)
    mu = solution.model.scene.options.friction if contact and "lambda_t" in solution.contact else 0.0
    fig = new_figure((7, 6.5) if mu else (7, 4))
    ax = fig.add_subplot(2, 1, 1) if mu else fig.add_subplot()
    ax2 = ax.twinx()
    # A slip below 1e-3 of the opening (pure mode I: discretisation noise)
    # goes on the opening's axis, where it reads as the zero it is, instead of
    # an axis of its own that would blow the noise up to full height.
    peak = max([float(np.abs(smp[k]).max(initial=0.0)) for smp in samples for k in ("gap", "slip")] or [0.0])
    slip_small = not contact and all(np.abs(smp["slip"]).max(initial=0.0) <= SLIP_PLOT_FRACTION * peak
                                     for smp in samples)
    for i, smp in enumerate(samples):
        label = solution.model.cracks[i].crack.name
        if contact:
            ax.plot(smp["s"], smp["pressure"], ".-", ms=3, lw=0.8, label=f"{label}: pressure")
            ax2.plot(smp["s"], smp["gap"], "x:", ms=3, lw=0.8, color=f"C{i + 3}", label=f"{label}: gap")
        else:
            ax.plot(smp["s"], smp["gap"], ".-", ms=3, lw=0.8, label=f"{label}: opening [[u]].n")
            tail = f" (|slip| <= {SLIP_PLOT_FRACTION:g} x the opening)" if slip_small else ""
            (ax if slip_small else ax2).plot(smp["s"], smp["slip"], "x:", ms=3, lw=0.8, color=f"C{i + 3}",
                                             label=f"{label}: slip [[u]].t{tail}")
    ax.set_xlabel("arc length along the crack (from its first point)")
    ax.set_ylabel("contact pressure (>= 0 in compression)" if contact else
                  "normal opening and tangential slip" if slip_small else "normal opening")
    if slip_small:
        ax2.set_axis_off()
    ax2.set_ylabel("normal gap" if contact else "tangential slip")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    if h1 or h2:
        ax.legend(h1 + h2, l1 + l2, fontsize=7)
    ax.set_title(f"{title}\nalong the crack" + (" (traction-free lips: no pressure)" if not contact else ""),
                 fontsize=10)
    if mu:
        # Friction: the shear against its bound mu p, the slip, and the states.
        bx = fig.add_subplot(2, 1, 2, sharex=ax)
        bx2 = bx.twinx()
        for i, smp in enumerate(samples):
            label = solution.model.cracks[i].crack.name
            bx.plot(smp["s"], np.abs(smp["shear"]), ".-", ms=3, lw=0.8, color=f"C{i}", label=f"{label}: |shear|")
            bx.plot(smp["s"], mu * np.maximum(smp["pressure"], 0.0), "--", lw=0.8, color=f"C{i}",
                    label=f"{label}: mu p = {mu:g} p")
            bx2.plot(smp["s"], smp["slip"], "x:", ms=3, lw=0.8, color=f"C{i + 3}", label=f"{label}: slip [[u]].t")
            for name, colour in (("stick", "tab:green"), ("slip", "tab:red"), ("open", "0.6")):
                on = smp["state"] == name
                if np.any(on):
                    bx.plot(smp["s"][on], np.zeros(np.count_nonzero(on)), "|", color=colour, ms=6,
                            label=f"{label}: {name}" if i == 0 else None)
        bx.set_xlabel("arc length along the crack (from its first point)")
        bx.set_ylabel("friction traction")
        bx2.set_ylabel("slip (accumulated)")
        h1, l1 = bx.get_legend_handles_labels()
        h2, l2 = bx2.get_legend_handles_labels()
        bx.legend(h1 + h2, l1 + l2, fontsize=6, ncol=2)
        bx.set_title("friction: shear against its bound, slip, states (stick green, slip red, open grey)",
                     fontsize=9)
        fig.tight_layout()
    save_png(fig, out / "crack_pressure.png")
    names.append("crack_pressure.png")

    fig = new_figure((8.0, height))
    ax = fig.add_subplot()
    s = f["stress"]
    values = {"xx": s[:, 0], "yy": s[:, 1], "xy": s[:, 2]}.get(component)
    if values is None:
        values = von_mises(s, solution.model.scene.material.sigma_zz_ratio)
    cmap = "viridis" if component == "von_mises" else "coolwarm"
    lim = 1.0
    if len(values):
        e1, e2 = tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
        area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
        lim = _weighted_percentile(np.abs(values), area, STRESS_PERCENTILE) or float(np.abs(values).max()) or 1.0
    coll = _draw_field(ax, tris, values, cmap, (0.0 if component == "von_mises" else -lim, lim), edges=False)
    for smp in samples:
        ax.plot(smp["x"][:, 0], smp["x"][:, 1], "k-", lw=0.8)
    ax.autoscale()
    ax.set_aspect("equal")
    label = "von Mises stress" if component == "von_mises" else f"stress {component}"
    fig.colorbar(coll, ax=ax, extend="max" if component == "von_mises" else "both",
                 label=f"{label} (the input's stress units; scale clipped at the "
                       f"{STRESS_PERCENTILE:g}th percentile)")
    ax.set_title(f"{title}\n{label}", fontsize=10)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    save_png(fig, out / "stress.png")
    names.append("stress.png")
    return names


def _rectangle(window):
    from matplotlib.patches import Rectangle
    (x0, y0), (x1, y1) = window
    return Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ec="r", lw=0.8, ls="--")
