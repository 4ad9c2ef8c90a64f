"""The PNGs of a run, cropped to their ink; the plots that differ by dimension
are functions here side by side.

- A planar part (``write_pngs``): deformed.png (the deformed part, with a
  zoom on small cracks), crack_pressure.png (pressure and gap, or opening
  and slip, along each crack), stress.png.
- A solid (``write_crack_opening_png``): crack_opening.png, one panel per
  crack, the normal opening [[u]].n at the vertices of the lip facets
  (SurfaceCrackModel.lip_facets) drawn over the facets in the crack's own
  plane coordinates (from the crack's plane() origin, along its directions:
  the semi-axes of an ellipse, a polygon's first edge, the principal
  directions of a triangulated surface, onto which it is projected), with
  the front in black and a labelled colour bar (in the scene's units when
  it gives them); the same samples go to crack_opening.csv.
- Contact on a solid's cracks (``write_crack_contact_png``):
  crack_contact.png, one row per crack in its plane coordinates: the
  open / stick / slip regions (the state at each lip facet's centre) with
  the friction shear's direction on the slipping facets, and the contact
  pressure at the facet vertices with a labelled colour bar.
- K along 3D fronts (``write_front_png``): front_sifs.png, K_I, K_II, K_III
  against the arc length (against the parametric angle for elliptical
  fronts) per crack, with the estimated discretisation error as error bars
  (when the run made the estimate; else half the spread of the three
  domains) and marked: free-surface points (their end values, K_source
  end_extrapolation, as open diamonds) and positions asked for between
  front points (interpolated, open circles); on a load path the last
  step so, each earlier step's K a dotted line with a marker of its own,
  labelled with the step's number and name.
"""
from __future__ import annotations

import math
import pathlib
import typing

import numpy as np

from ..post.solution import Solution
from ..scene.units import label as unit_label
from .files import atomic_path


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


#: The PNG text key under which save_png records where its named axes are.
PNG_AXES_KEY = "cracklip:axes"


def _axes_record(ax, height: int, r0: int, c0: int) -> dict:
    """Where an axes is in the cropped picture: its box [left, top, right,
    bottom] in pixels (row 0 at the top), its data limits [x0, x1, y0, y1]
    and its axis labels."""
    box = ax.get_window_extent()
    return {"box": [float(box.x0 - c0), float(height - box.y1 - r0), float(box.x1 - c0), float(height - box.y0 - r0)],
            "limits": [*map(float, ax.get_xlim()), *map(float, ax.get_ylim())],
            "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(), "title": ax.get_title()}


def read_png_axes(path: str | pathlib.Path) -> dict:
    """The axes save_png recorded in a PNG (name -> box, limits, labels)."""
    import json
    from PIL import Image
    with Image.open(path) as img:
        return json.loads(img.text.get(PNG_AXES_KEY, "{}"))


def save_png(fig, path: pathlib.Path, axes: dict | None = None) -> None:
    """fig as a PNG cropped to its ink (the pixels not of the face colour)
    plus PNG_PAD_INCHES on every side, drawn once: savefig(bbox_inches=
    "tight") draws every figure twice and measures the artists' boxes
    (get_tightbbox alone took 0.05 s per figure at 2e5 dofs); the ink box
    boxes. Ink on the canvas's border may continue outside the figure (a
    title longer than the figure is wide): such a figure goes to savefig
    (three draws then), which enlarges the picture to hold it.

    axes: named axes whose place in the picture (box in pixels, data
    limits, labels) goes into the PNG's text chunk PNG_AXES_KEY, so that a
    test reads the pixels of a panel (read_png_axes); not on savefig's path."""
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
    from PIL import Image, PngImagePlugin
    info = None
    if axes:
        import json
        info = PngImagePlugin.PngInfo()
        info.add_text(PNG_AXES_KEY, json.dumps({name: _axes_record(ax, height, r0, c0) for name, ax in axes.items()}))
    with atomic_path(path) as tmp:
        # compress_level 1: a third of the encoding time of the default 6, files ~10 % larger.
        with open(tmp, "wb") as fh:
            Image.fromarray(crop).save(fh, format="png", compress_level=1, pnginfo=info)


def magnification(solution: Solution, fields: dict, requested: float) -> float:
    """The displacement scale of deformed.png: as requested, or such that the
    largest displacement is 5 % of the part's size."""
    if requested > 0.0:
        return requested
    size = float(np.ptp(part_points(solution, fields), axis=0).max())
    umax = float(np.linalg.norm(fields["displacement"], axis=1).max()) if len(fields["displacement"]) else 0.0
    return _scale_for(0.05 * size, umax)


def _scale_for(length: float, umax: float) -> float:
    """The displacement scale that makes umax `length` long (rounded), 1
    for no displacement (no load: nothing to magnify)."""
    if not (umax > 1e-300 * max(length, 1e-300)) or not math.isfinite(length / umax):
        return 1.0
    return _round_scale(length / umax)


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


def crack_window(solution: Solution, fields: dict | None = None) -> tuple[np.ndarray, np.ndarray] | None:
    """(lower, upper) corners of a window around the cracks for a zoomed
    view, or None when the cracks are not much smaller than the part."""
    m = solution.model
    if not m.cracks:
        return None
    return window_around([cm.crack.points for cm in m.cracks], part_points(solution, fields))


def part_points(solution: Solution, fields: dict | None) -> np.ndarray:
    """Points spanning the whole part: the mesh nodes, or under mpirun (each
    process holding its part of them) the gathered sub-cell fields' points."""
    if solution.model.distributed:
        return fields["points"]
    return solution.model.x


def window_around(polylines, x: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """(lower, upper) corners of a window around polylines (each (k, 2)) in
    a part with nodes x, or None when they are not much smaller than the
    part (ZOOM_FRACTION)."""
    lo_part, hi_part = x.min(axis=0), x.max(axis=0)
    pts = np.concatenate([np.clip(np.asarray(p, dtype=float), lo_part, hi_part) for p in polylines])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = float(max(np.ptp(pts, axis=0).max(), 1e-300))
    if span > ZOOM_FRACTION * float(np.ptp(x, axis=0).max()):
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


def _part_and_zoom(extent: np.ndarray, window, height: float):
    """The figure and its panels: the part alone (8 in wide, `height` tall),
    or the part and the zoom on the cracks side by side, each panel as wide
    as its own aspect ratio asks at a common height (equal-width halves left
    a slender part's panel half empty beside a tall zoom, a gap between
    them), the whole about 14 in wide."""
    if window is None:
        fig = new_figure((8.0, height))
        return fig, [fig.add_subplot()]
    span = np.ptp(np.asarray(window, dtype=float), axis=0)
    ratios = [float(np.clip(extent[0] / max(extent[1], 1e-300), 0.2, 8.0)),
              float(np.clip(span[0] / max(span[1], 1e-300), 0.2, 8.0))]
    ratios[1] = max(ratios[1], 0.75)  # room for a tall zoom's labels and title
    panel_height = float(np.clip(12.0 / sum(ratios), 2.5, 7.0))
    width = float(np.clip(panel_height * sum(ratios) + 3.0, 8.0, 16.0))
    fig = new_figure((width, panel_height + 1.6))
    grid = fig.add_gridspec(1, 2, width_ratios=ratios)
    panels = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1])]
    if span[0] < 0.75 * span[1]:  # a narrow zoom: fewer ticks along x
        from matplotlib.ticker import MaxNLocator
        panels[1].xaxis.set_major_locator(MaxNLocator(3))
    return fig, panels


def _fit(ax, points: np.ndarray) -> None:
    """Limits around the drawn points with matplotlib's default margins, on
    both paths of _draw_field (imshow's limits are the image's edges, so an
    autoscale leaves the part touching the frame, its corners cut off)."""
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = np.asarray(ax.margins()) * np.maximum(hi - lo, 1e-300)
    ax.set_xlim(lo[0] - pad[0], hi[0] + pad[0])
    ax.set_ylim(lo[1] - pad[1], hi[1] + pad[1])


def _data_limits(values: np.ndarray) -> tuple[float, float]:
    """Colour limits from the data (a constant field gets a small band around its value)."""
    if not len(values):
        return 0.0, 1.0
    lo, hi = float(np.min(values)), float(np.max(values))
    if hi > lo:
        return lo, hi
    pad = max(abs(hi) * 1e-6, 1e-300)
    return lo - pad, hi + pad


def _in_window(tris: np.ndarray, window, margin: float = 0.0) -> np.ndarray:
    """Triangles (n, 3, 2) whose bounding box meets the window [lo, hi]
    (grown by margin times its size): every triangle that shows in it, none cut
    off at its edges by a centroid test."""
    lo, hi = np.asarray(window[0], dtype=float), np.asarray(window[1], dtype=float)
    grow = margin * (hi - lo)
    return np.all((tris.max(axis=1) >= lo - grow) & (tris.min(axis=1) <= hi + grow), axis=1)


def _label_axes(ax, units) -> None:
    ax.set_xlabel(unit_label(units, "length", "x"))
    ax.set_ylabel(unit_label(units, "length", "y"))


def write_pngs(solution: Solution, samples: list[dict], out: pathlib.Path, scale: float,
               component: str, title: str, fields: dict | None = None) -> list[str]:
    """deformed.png (sub-cells displaced, magnified, coloured by |u| between
    its smallest and largest value; with a zoom on the cracks when they are
    small in the part), crack_pressure.png (pressure and gap, or opening and
    slip, along each crack) and stress.png (a stress component on the
    sub-cells, colour scale clipped at the STRESS_PERCENTILE area-weighted
    percentile; with the same zoom). Axes carry the scene's units
    (Scene.units) when it has them. fields: solution.subcell_fields() if
    the caller has it already."""
    f = solution.subcell_fields() if fields is None else fields
    frame = _Frame.of(solution, f)
    return [_deformed_png(solution, f, frame, samples, out, scale, title),
            _crack_pressure_png(solution, frame.units, samples, out, title),
            _stress_png(f, frame, samples, out, component, title)]


class _Frame(typing.NamedTuple):
    """What the part's pictures share: the scene's units (or None), the
    sub-cells (n, 3, 2), the part's extent, the figure's height, the zoom
    window around the cracks (None: no zoom)."""
    units: typing.Any
    tris: np.ndarray
    extent: np.ndarray
    height: float
    window: typing.Any

    @classmethod
    def of(cls, solution: Solution, f: dict) -> "_Frame":
        extent = np.ptp(part_points(solution, f), axis=0)
        return cls(solution.model.scene.units, f["points"].reshape(-1, 3, 2), extent,
                   float(np.clip(8.0 * extent[1] / max(extent[0], 1e-300), 3.0, 8.0)), crack_window(solution, f))


def _deformed_png(solution: Solution, f: dict, frame: _Frame, samples: list[dict], out: pathlib.Path, scale: float,
                  title: str) -> str:
    """deformed.png (write_pngs)."""
    units, tris, extent, height, window = frame
    disp = f["displacement"].reshape(-1, 3, 2)
    mag = magnification(solution, f, scale)
    umag = np.linalg.norm(disp, axis=2).mean(axis=1)
    moving = bool(np.any(umag > 0.0))

    fig, panels = _part_and_zoom(extent, window, height)
    for k, ax in enumerate(panels):
        zoom = k == 1
        sel, m, shift = slice(None), mag, np.zeros(2)
        if zoom:
            sel = _in_window(tris, window, 0.25)
            # Its own scale, of the motion relative to the window's mean (a
            # rigid translation would hide the opening): the largest such
            # displacement is 5 % of the window.
            shift = disp[sel].reshape(-1, 2).mean(axis=0) if np.any(sel) else shift
            rel = float(np.linalg.norm(disp[sel] - shift, axis=2).max(initial=0.0))
            m = scale if scale > 0.0 else _scale_for(0.05 * float(np.ptp(window, axis=0).max()), rel)
        coll = _draw_field(ax, (tris + m * (disp - shift))[sel], umag[sel], "viridis", _data_limits(umag), edges=True)
        for smp in samples:
            for key in ("u_plus", "u_minus"):
                xy = smp["x"] + m * (smp[key] - shift)
                ax.plot(xy[:, 0], xy[:, 1], "r-", lw=0.8)
        if not zoom:
            _fit(ax, np.concatenate([(tris + m * disp).reshape(-1, 2)]
                                    + [smp["x"] + m * smp[key] for smp in samples for key in ("u_plus", "u_minus")]))
        if zoom:
            ax.set_xlim(window[0][0], window[1][0])
            ax.set_ylim(window[0][1], window[1][1])
            ax.set_title("around the cracks: displacement\nrelative to the window's mean, " f"x{m:g}", fontsize=9)
        elif window is not None:
            ax.add_patch(_rectangle(window))
            ax.set_title(f"displacement x{mag:g}", fontsize=9)
        ax.set_aspect("equal")
        _label_axes(ax, units)
    bar = fig.colorbar(coll, ax=panels, label=unit_label(units, "displacement", "|u|") if units is not None else
                       "|u| (length units)")
    head = ("" if window is not None else f", displacement x{mag:g}") if moving else ": no displacement (no load)"
    fig.suptitle(f"{title}\ndeformed mesh{head}", fontsize=10)
    save_png(fig, out / "deformed.png", {"part": panels[0], "colorbar": bar.ax,
                                         **({"zoom": panels[1]} if window is not None else {})})
    return "deformed.png"


def _crack_pressure_png(solution: Solution, units, samples: list[dict], out: pathlib.Path, title: str) -> str:
    """crack_pressure.png (write_pngs)."""
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
    ax.set_xlabel(unit_label(units, "length", "arc length along the crack (from its first point)"))
    ax.set_ylabel(unit_label(units, "stress", "contact pressure (>= 0 in compression)") if contact else
                  unit_label(units, "length", "normal opening and tangential slip" if slip_small else "normal opening"))
    if slip_small:
        ax2.set_axis_off()
    ax2.set_ylabel(unit_label(units, "length", "normal gap" if contact else "tangential slip"))
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
        bx.set_xlabel(unit_label(units, "length", "arc length along the crack (from its first point)"))
        bx.set_ylabel(unit_label(units, "stress", "friction traction"))
        bx2.set_ylabel(unit_label(units, "length", "slip (accumulated)"))
        h1, l1 = bx.get_legend_handles_labels()
        h2, l2 = bx2.get_legend_handles_labels()
        bx.legend(h1 + h2, l1 + l2, fontsize=6, ncol=2)
        bx.set_title("friction: shear against its bound, slip, states (stick green, slip red, open grey)",
                     fontsize=9)
        fig.tight_layout()
    save_png(fig, out / "crack_pressure.png", {"along": ax})
    return "crack_pressure.png"


def _stress_png(f: dict, frame: _Frame, samples: list[dict], out: pathlib.Path, component: str, title: str) -> str:
    """stress.png (write_pngs)."""
    units, tris, extent, height, window = frame
    fig, panels = _part_and_zoom(extent, window, height)
    s = f["stress"]
    values = {"xx": s[:, 0], "yy": s[:, 1], "xy": s[:, 2]}.get(component)
    if values is None:
        values = f["von_mises"]
    cmap = "viridis" if component == "von_mises" else "coolwarm"
    lim = 1.0
    if len(values):
        e1, e2 = tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
        area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
        lim = _weighted_percentile(np.abs(values), area, STRESS_PERCENTILE) or float(np.abs(values).max()) or 1.0
    name = "von Mises stress" if component == "von_mises" else f"stress {component}"
    for k, ax in enumerate(panels):
        zoom = k == 1
        sel = _in_window(tris, window, 0.25) if zoom else slice(None)
        coll = _draw_field(ax, tris[sel], values[sel], cmap, (0.0 if component == "von_mises" else -lim, lim),
                           edges=False)
        for smp in samples:
            ax.plot(smp["x"][:, 0], smp["x"][:, 1], "k-", lw=0.8)
        if zoom:
            ax.set_xlim(window[0][0], window[1][0])
            ax.set_ylim(window[0][1], window[1][1])
            ax.set_title("around the cracks", fontsize=9)
        else:
            _fit(ax, tris)
            if window is not None:
                ax.add_patch(_rectangle(window))
        ax.set_aspect("equal")
        _label_axes(ax, units)
    unit_text = (f"[{units.name('stress')}]" if units is not None else "(the input's stress units")
    bar = fig.colorbar(coll, ax=panels, extend="max" if component == "von_mises" else "both",
                       label=f"{name} {unit_text}" + (";\n" if units is None else "\n(")
                             + f"scale clipped at the {STRESS_PERCENTILE:g}th percentile)")
    if window is None:
        panels[0].set_title(f"{title}\n{name}", fontsize=10)
    else:
        fig.suptitle(f"{title}\n{name}", fontsize=10)
    save_png(fig, out / "stress.png", {"part": panels[0], "colorbar": bar.ax,
                                       **({"zoom": panels[1]} if window is not None else {})})
    return "stress.png"


def _rectangle(window):
    from matplotlib.patches import Rectangle
    (x0, y0), (x1, y1) = window
    return Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ec="r", lw=0.8, ls="--")


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
    facets (lip facets per crack), fronts (CrackGeometry3D.front per crack)."""
    from matplotlib.collections import LineCollection
    from matplotlib.tri import Triangulation
    from mpl_toolkits.axes_grid1 import make_axes_locatable
    n = len(cracks)
    uvs = [plane_coordinates(c, f["x"]) for c, f in zip(cracks, facets)]
    # Panel height from the widest crack's aspect ratio (a colour bar as tall as each picture).
    aspect = max([float(np.ptp(uv[:, 1]) / max(np.ptp(uv[:, 0]), 1e-300)) for uv in uvs if len(uv)] or [1.0])
    fig = new_figure((6.0 * n, 1.6 + 4.2 * min(max(aspect, 0.35), 1.4)))
    fig.subplots_adjust(right=0.84)  # room for the colour bar's label beside a wide panel
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


#: The colours of the contact states in crack_contact.png.
STATE_COLOURS = {"open": "#f2f2f2", "stick": "#3b75af", "slip": "#ef8636"}


#: At most this many shear arrows per crack in crack_contact.png.
MAX_ARROWS = 400


def write_crack_contact_png(cracks: typing.Sequence, facets: typing.Sequence[dict], fronts: typing.Sequence[dict],
                            path: pathlib.Path, title: str = "", units=None, friction: float = 0.0) -> pathlib.Path:
    """crack_contact.png (module doc): cracks (the scene's crack surfaces),
    facets (lip facets per crack with io.outputs.facet_contact's fields),
    fronts (CrackGeometry3D.front per crack); friction: mu (0: no stick or
    slip, the closed lips slide freely)."""
    from matplotlib.collections import LineCollection
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    from matplotlib.tri import Triangulation
    from mpl_toolkits.axes_grid1 import make_axes_locatable
    n = len(cracks)
    uvs = [plane_coordinates(c, f["x"]) for c, f in zip(cracks, facets)]
    aspect = max([float(np.ptp(uv[:, 1]) / max(np.ptp(uv[:, 0]), 1e-300)) for uv in uvs if len(uv)] or [1.0])
    h = 1.4 + 4.0 * min(max(aspect, 0.35), 1.4)
    fig = new_figure((12.0, h * n))
    axes = {}
    names = list(STATE_COLOURS)
    cmap = ListedColormap([STATE_COLOURS[k] for k in names])
    for k, (crack, f, fr, uv) in enumerate(zip(cracks, facets, fronts, uvs)):
        ax, bx = fig.add_subplot(n, 2, 2 * k + 1), fig.add_subplot(n, 2, 2 * k + 2)
        nf = len(f["cell"])
        fx = np.asarray(fr["x"]).reshape(-1, 3)
        seg = np.asarray(fr["segments"]).reshape(-1, 2)
        origin, e1, e2 = crack.plane()
        if nf:
            tri = Triangulation(uv[:, 0], uv[:, 1], np.arange(len(uv)).reshape(-1, 3))
            code = np.array([names.index(s) for s in f["centre_state"]], dtype=float)
            ax.tripcolor(tri, facecolors=code, cmap=cmap, vmin=-0.5, vmax=2.5, edgecolors="none")
            slipping = np.flatnonzero(f["centre_state"] == "slip")
            if friction > 0.0 and slipping.size:
                pick = slipping[:: max(1, slipping.size // MAX_ARROWS)]
                c = uv.reshape(-1, 3, 2).mean(axis=1)[pick]
                sh = f["centre_shear"][pick]
                d = np.column_stack([sh @ e1, sh @ e2])
                d /= np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
                ax.quiver(c[:, 0], c[:, 1], d[:, 0], d[:, 1], color="k", width=0.002, scale=40)
            p = f["pressure"].reshape(-1)
            lo, hi = min(0.0, float(p.min())), float(p.max())
            coll = bx.tripcolor(tri, p, shading="gouraud", cmap="magma_r", vmin=lo, vmax=hi if hi > lo else lo + 1.0)
            cax = make_axes_locatable(bx).append_axes("right", size="4%", pad=0.12)
            fig.colorbar(coll, cax=cax).set_label(unit_label(units, "stress", "contact pressure"))
        area = {s: float(np.sum(f["area"][f["centre_state"] == s])) if nf else 0.0 for s in names}
        total = max(sum(area.values()), 1e-300)
        shown = names if friction > 0.0 else ["open", "slip"]
        legend = [Patch(facecolor=STATE_COLOURS[s], edgecolor="0.5",
                        label=f"{s if friction > 0.0 or s == 'open' else 'closed (frictionless)'} "
                              f"{100 * area[s] / total:.0f} %") for s in shown]
        ax.legend(handles=legend, fontsize=7, loc="upper right")
        for a, what in ((ax, "open / stick / slip" + (" (arrows: friction on the + lip)" if friction > 0 else "")),
                        (bx, f"contact pressure, max {float(f['pressure'].max(initial=0.0)):.4g}")):
            if len(fx):
                q = plane_coordinates(crack, fx)
                a.add_collection(LineCollection(q[seg], colors="k", linewidths=1.2))
            a.set_xlabel(unit_label(units, "length", axis_text(e1)))
            a.set_ylabel(unit_label(units, "length", axis_text(e2)))
            a.set_aspect("equal")
            a.autoscale_view()
            a.set_title(f"{crack.name}: {what}", fontsize=9)
        axes[f"crack {k} states"], axes[f"crack {k} pressure"] = ax, bx
    if title:
        fig.suptitle(title)
    save_png(fig, path, axes)
    return path


#: front_sifs.png: the markers of a load path's earlier steps.
STEP_MARKERS = ("^", "v", "s", "<", ">", "d")


def _earlier_step(ax, rows: list[dict], angle: bool, mode: str, colour: str, marker: str) -> None:
    """One earlier load step's K (mode) along a front, each piece a thin
    dotted line (write_front_png)."""
    if not rows:
        return
    t = np.array([math.degrees(r["parametric_angle"]) if angle else r["s"] for r in rows])
    k = np.array([r[mode] for r in rows])
    piece = np.array([int(r.get("piece") or 0) for r in rows])
    for p in sorted(set(piece.tolist())):
        on = np.flatnonzero(piece == p)
        o = on[np.argsort(t[on])]
        ax.plot(t[o], k[o], ls=":", lw=0.6, marker=marker, ms=4, color=colour, alpha=0.7)


def write_front_png(rows: typing.Sequence[dict], path: pathlib.Path, title: str = "", k_unit: str | None = None,
                    units=None, steps: typing.Sequence[tuple[str, typing.Sequence[dict]]] | None = None) -> None:
    """front_sifs.png: K_I, K_II, K_III along each crack's front (module doc);
    each front piece a line of its own (a crack with two fronts: solid,
    dashed, ...), the free-surface end values, flagged free-surface points,
    interpolated positions and points whose K is NOT reliable marked.
    steps: a load path's (name, rows) per step, the last one's rows those
    drawn as above; each earlier step's K a thin line of its own marker,
    labelled with the step's number and name."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cracks = sorted({int(r["crack"]) for r in rows})
    fig, axes = plt.subplots(len(cracks), 1, figsize=(7, 3.2 * len(cracks)), squeeze=False)
    for ax, c in zip(axes[:, 0], cracks):
        mine = [r for r in rows if int(r["crack"]) == c]
        angle = all(r["parametric_angle"] is not None for r in mine)
        t = np.array([math.degrees(r["parametric_angle"]) if angle else r["s"] for r in mine])
        source = np.array([r.get("K_source") or "domain" for r in mine])
        ends = source == "end_extrapolation"
        between = source == "interpolation"
        free = np.array([bool(r["free_surface"]) for r in mine]) & ~ends
        unclear = ~np.array([bool(r.get("domain_clear", True)) for r in mine])
        piece = np.array([int(r.get("piece") or 0) for r in mine])
        pieces = sorted(set(piece.tolist()))
        marks = ((free, dict(marker="x", ms=8, color="k"), "free surface (flagged)"),
                 (ends, dict(marker="D", ms=6, mfc="none", color="k"), "free-surface end value (extrapolated)"),
                 (between, dict(marker="o", ms=6, mfc="none", color="k"), "asked position (interpolated)"),
                 (unclear, dict(marker="s", ms=9, mfc="none", color="r"), "NOT reliable (domain reaches an obstacle)"))
        for name, col in (("K_I", "C0"), ("K_II", "C1"), ("K_III", "C2")):
            k = np.array([r[name] for r in mine])
            err = [r.get(f"{name}_error") for r in mine]
            estimated = all(e is not None for e in err)
            bar = (np.array(err, dtype=float) if estimated else
                   0.5 * np.array([r[f"{name}_spread"] for r in mine]))
            for j, p in enumerate(pieces):
                on = np.flatnonzero(piece == p)
                o = on[np.argsort(t[on])]
                label = ((f"{name} +- estimated error" if estimated else name) if j == 0 else None)
                ax.errorbar(t[o], k[o], yerr=bar[o], fmt="o", ls=("-", "--", ":", "-.")[j % 4], color=col, ms=3,
                            lw=1, capsize=2, label=label)
            for mask, style, _ in marks:
                if mask.any():
                    ax.plot(t[mask], k[mask], ls="none", **style)
            for j, (_, srows) in enumerate((steps or [])[:-1]):
                _earlier_step(ax, [r for r in srows if int(r["crack"]) == c], angle, name, col,
                              STEP_MARKERS[j % len(STEP_MARKERS)])
        for j, (sname, _) in enumerate((steps or [])[:-1]):
            ax.plot([], [], color="0.4", lw=0.6, ls=":", marker=STEP_MARKERS[j % len(STEP_MARKERS)], ms=4,
                    label=f"step {j} ({sname})" if sname else f"step {j}")
        if steps:
            ax.plot([], [], color="0.4", lw=1, marker="o", ms=3,
                    label=f"step {len(steps) - 1} ({steps[-1][0]}), last" if steps[-1][0] else
                    f"step {len(steps) - 1}, last")
        for mask, style, label in marks:
            if mask.any():
                ax.plot([], [], ls="none", label=label, **style)
        for j, p in enumerate(pieces if len(pieces) > 1 else []):
            ax.plot([], [], color="0.4", lw=1, ls=("-", "--", ":", "-.")[j % 4], label=f"front piece {p}")
        ax.axhline(0.0, color="0.7", lw=0.5)
        ax.set_xlabel("parametric angle [deg]" if angle else
                      unit_label(units, "length", "arc length along the front"
                                 + (" (each piece from its start)" if len(pieces) > 1 else "")))
        ax.set_ylabel(f"K [{k_unit}]" if k_unit else "K")
        ax.set_title(f"{title}{': ' if title else ''}crack {mine[0]['crack_name'] or c}", fontsize=9)
        ax.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
