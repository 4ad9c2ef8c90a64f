"""Rasterise a piecewise-constant field on triangles into an image.

The PNGs of a large mesh (outputs.write_pngs) are drawn as an image, not as
one matplotlib polygon per triangle: matplotlib builds a Path object per
polygon (1.5 s for 1.9e5 sub-triangles) and draws each (0.4 s), while the
C++ kernel (cpp/post/raster.cpp) paints the pixels whose centres lie in each
triangle in milliseconds. A pixel takes the value of the triangle that
contains its centre (the later one where triangles overlap, e.g. magnified
lips); pixels outside every triangle are NaN (transparent in imshow).
"""
from __future__ import annotations

import numpy as np

from .. import _cracklip


def image_shape(extent: tuple[float, float, float, float], longest: int) -> tuple[int, int]:
    """(rows, columns) of an image of `extent` = (x0, x1, y0, y1) with
    `longest` pixels along its longer side and square pixels."""
    x0, x1, y0, y1 = extent
    w, h = max(x1 - x0, 1e-300), max(y1 - y0, 1e-300)
    if w >= h:
        return max(1, round(longest * h / w)), longest
    return longest, max(1, round(longest * w / h))


def rasterize(triangles: np.ndarray, values: np.ndarray, extent: tuple[float, float, float, float],
              shape: tuple[int, int]) -> np.ndarray:
    """Image (rows, columns), row 0 at y0 (imshow origin="lower"), of the
    field `values` (n,) constant on `triangles` (n, 3, 2) over `extent` =
    (x0, x1, y0, y1); NaN where no triangle covers a pixel's centre. A
    degenerate extent (all points on a line) is widened by a pixel."""
    x0, x1, y0, y1 = (float(v) for v in extent)
    pad = 1e-9 * max(abs(x1 - x0), abs(y1 - y0), abs(x0), abs(y0), 1.0)
    if x1 - x0 <= pad:
        x0, x1 = x0 - pad, x1 + pad
    if y1 - y0 <= pad:
        y0, y1 = y0 - pad, y1 + pad
    tris = np.ascontiguousarray(triangles, dtype=np.float64).reshape(-1, 6)
    vals = np.ascontiguousarray(values, dtype=np.float64).ravel()
    return _cracklip.rasterize_triangles(tris, vals, x0, x1, y0, y1, int(shape[0]), int(shape[1]))
