// Rasterising a piecewise-constant field on triangles into an image (the
// PNGs of large meshes): a pixel takes the value of the (last) triangle
// that contains its centre.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{
/// Image of `values` (n,), constant on `triangles` (n x 3 x 2, row major),
/// over the box [x0, x1] x [y0, y1] cut into ny rows x nx columns of pixels;
/// row 0 at y0. Pixels whose centre lies in no triangle are NaN. Triangles
/// of either orientation; a centre on a shared edge goes to the later one.
/// Work: the pixels of each triangle's bounding box.
std::vector<double> rasterize_triangles(std::span<const double> triangles, std::span<const double> values,
                                        double x0, double x1, double y0, double y1, int ny, int nx);
} // namespace cracklip
