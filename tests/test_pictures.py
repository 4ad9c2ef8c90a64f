"""Issue 26, acceptance 4: the pictures, read back pixel by pixel.

save_png records where each panel is (cracklip.io.pictures.read_png_axes:
its box in pixels, data limits and labels), so the tests look at the
pixels of a panel: the colours used (deformed.png's colour limits come from
the data, not floored at 1 length unit), the background between a panel's
frame and the part (no cropping on the raster path), a zoom panel filled
to its edges (no saw-tooth gaps) and showing the crack's opening, zooms on
stress.png and path.png, units on every axis.
"""
import dataclasses
import pathlib

import cracklip as cl
import numpy as np
from cracklip import cli
from cracklip.io.growth_outputs import write_growth_pngs
from cracklip.io.pictures import RASTER_MIN_TRIANGLES, read_png_axes
from cracklip.io.scene_file import load_scene_file

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENES = ROOT / "demos" / "scenes"
WHITE = np.array([255, 255, 255])


def pixels(path):
    from PIL import Image
    with Image.open(path) as img:
        return np.asarray(img.convert("RGB")).astype(int)


def panel(img, box, inset=2):
    """The pixels inside a panel's frame (inset by the frame's width)."""
    left, top, right, bottom = (int(round(v)) for v in box)
    return img[top + inset:bottom - inset, left + inset:right - inset]


def to_pixel(ax, x, y):
    """(column, row) of a data point in a recorded panel."""
    left, top, right, bottom = ax["box"]
    x0, x1, y0, y1 = ax["limits"]
    return (int(round(left + (x - x0) / (x1 - x0) * (right - left))),
            int(round(bottom - (y - y0) / (y1 - y0) * (bottom - top))))


def run(tmp_path, name, *sets):
    args = ["run", str(SCENES / f"{name}.toml"), "--out", str(tmp_path), "-q", "--no-estimate",
            "--set", "outputs.vtu=false"]
    for s in sets:
        args += ["--set", s]
    assert cli.main(args) == 0
    return tmp_path


def viridis_index(rgb):
    """Index (0..255) in viridis of each pixel, -1 where no viridis colour is near."""
    from matplotlib import colormaps
    from scipy.spatial import cKDTree
    lut = colormaps["viridis"](np.linspace(0.0, 1.0, 256))[:, :3] * 255
    d, idx = cKDTree(lut).query(rgb.reshape(-1, 3))
    return np.where(d < 12, idx, -1)


def test_deformed_colours_span_the_data(tmp_path):
    """The C(T) in mm moves at most 0.2 mm: with the limit floored at 1 every
    pixel was in the bottom fifth of viridis. Now the part's colours run
    from the map's bottom to its top; the colour bar and the axes carry mm."""
    out = run(tmp_path, "ct_specimen", "mesh.h=2.5")
    axes = read_png_axes(out / "deformed.png")
    idx = viridis_index(panel(pixels(out / "deformed.png"), axes["part"]["box"]))
    idx = idx[idx >= 0]
    assert np.percentile(idx, 1) < 40 and np.percentile(idx, 99.9) > 215
    assert axes["colorbar"]["ylabel"] == "|u| [mm]"
    assert axes["part"]["xlabel"] == "x [mm]" and axes["part"]["ylabel"] == "y [mm]"
    stress = read_png_axes(out / "stress.png")
    assert stress["colorbar"]["ylabel"].startswith("stress yy [MPa]")
    along = read_png_axes(out / "crack_pressure.png")["along"]
    assert along["xlabel"].endswith("[mm]") and along["ylabel"].endswith("[mm]")


def test_raster_path_keeps_a_margin(tmp_path):
    """Above RASTER_MIN_TRIANGLES sub-triangles the field is an image, whose
    limits were its own edges: the part touched the frame, its corners cut.
    Now background shows between the frame and the part on every side."""
    out = run(tmp_path, "ct_specimen", "mesh.h=0.4", "outputs.stress_component=\"von_mises\"")
    import json
    assert json.loads((out / "results.json").read_text())["model"]["cells"] > RASTER_MIN_TRIANGLES
    for name in ("deformed.png", "stress.png"):
        inner = panel(pixels(out / name), read_png_axes(out / name)["part"]["box"])
        for band in (inner[:4], inner[-4:], inner[:, :4], inner[:, -4:]):
            assert np.all(band == WHITE), name
        assert np.mean(np.all(inner == WHITE, axis=2)) < 0.35  # (the part fills the rest)


def test_zoom_panels_fill_their_window_and_show_the_opening(tmp_path):
    """The crack at a hole (4 mm in a 400 mm plate): deformed.png's zoom is
    filled with material to its frame right of the hole (the centroid test
    left saw-tooth gaps at its edges), its lips (red) are there and open
    (background between them: the motion relative to the window's mean is
    magnified, not the plate's translation); stress.png has the same zoom
    with the crack (black) in it."""
    out = run(tmp_path, "hole_fatigue")
    img = pixels(out / "deformed.png")
    axes = read_png_axes(out / "deformed.png")
    zoom = axes["zoom"]
    assert zoom["xlabel"] == "x [mm]" and "around the cracks" in zoom["title"]
    inner = panel(img, zoom["box"])
    red = (inner[..., 0] > 200) & (inner[..., 1] < 80) & (inner[..., 2] < 80)
    assert red.sum() > 100
    c0, r0 = to_pixel(zoom, 10.6, 0.0)
    left, top = (int(round(v)) for v in zoom["box"][:2])
    material = inner[:, c0 - left:]
    edges = np.concatenate([material[:3].reshape(-1, 3), material[-3:].reshape(-1, 3),
                            material[:, -3:].reshape(-1, 3)])
    assert not np.any(np.all(edges == WHITE, axis=1))
    c, _ = to_pixel(zoom, 12.0, 0.0)
    column = inner[:, c - left]
    reds = np.flatnonzero((column[:, 0] > 200) & (column[:, 1] < 80))
    between = column[reds.min():reds.max() + 1]
    assert reds.max() - reds.min() > 4 and np.any(np.all(between == WHITE, axis=1))
    stress = read_png_axes(out / "stress.png")
    inner = panel(pixels(out / "stress.png"), stress["zoom"]["box"])
    assert (inner.sum(axis=2) < 200).sum() > 50  # (coolwarm's darkest colour sums to 222)


def test_path_png_zooms_on_a_small_crack(tmp_path):
    """path.png of the crack at a hole: a zoom panel in which the path (C0)
    spans a third of the width or more (on the whole plate it is a dot)."""
    sf = load_scene_file(SCENES / "hole_fatigue.toml", ["mesh.h=40.0", "options.contact=\"unilateral\""])
    result = cl.grow(sf.scene, dataclasses.replace(sf.growth, steps=2))
    write_growth_pngs(sf, result, tmp_path, True)
    axes = read_png_axes(tmp_path / "path.png")
    assert set(axes) == {"part", "zoom"} and axes["zoom"]["xlabel"] == "x [mm]"
    inner = panel(pixels(tmp_path / "path.png"), axes["zoom"]["box"])
    c0 = np.array([31, 119, 180])
    cols = np.flatnonzero(np.any(np.linalg.norm(inner - c0, axis=2) < 30, axis=0))
    assert cols.size and (cols.max() - cols.min()) > 0.33 * inner.shape[1]
    whole = panel(pixels(tmp_path / "path.png"), axes["part"]["box"])
    cols = np.flatnonzero(np.any(np.linalg.norm(whole - c0, axis=2) < 30, axis=0))
    assert (cols.max() - cols.min()) < 0.05 * whole.shape[1]
