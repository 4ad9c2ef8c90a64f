#include "post/raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cracklip
{
std::vector<double> rasterize_triangles(std::span<const double> triangles, std::span<const double> values,
                                        double x0, double x1, double y0, double y1, int ny, int nx)
{
  if (ny <= 0 || nx <= 0 || !(x1 > x0) || !(y1 > y0))
    throw std::invalid_argument("rasterize_triangles: need a non-empty box and image");
  if (triangles.size() != 6 * values.size())
    throw std::invalid_argument("rasterize_triangles: need 6 coordinates per value");
  std::vector<double> image(static_cast<std::size_t>(ny) * nx, std::numeric_limits<double>::quiet_NaN());
  const double dx = (x1 - x0) / nx, dy = (y1 - y0) / ny;
  const double scale = std::max(x1 - x0, y1 - y0);
  const double tol = 1e-12 * scale * scale;
  for (std::size_t t = 0; t < values.size(); ++t)
  {
    const double* p = triangles.data() + 6 * t;
    const double xmin = std::min({p[0], p[2], p[4]}), xmax = std::max({p[0], p[2], p[4]});
    const double ymin = std::min({p[1], p[3], p[5]}), ymax = std::max({p[1], p[3], p[5]});
    // Pixel-centre index ranges of the bounding box, clipped to the image.
    const int j0 = std::max(0, static_cast<int>(std::ceil((xmin - x0) / dx - 0.5)));
    const int j1 = std::min(nx - 1, static_cast<int>(std::floor((xmax - x0) / dx - 0.5)));
    const int i0 = std::max(0, static_cast<int>(std::ceil((ymin - y0) / dy - 0.5)));
    const int i1 = std::min(ny - 1, static_cast<int>(std::floor((ymax - y0) / dy - 0.5)));
    if (j0 > j1 || i0 > i1)
      continue;
    // Edge functions a x + b y + c, >= 0 inside whatever the orientation.
    const double area2 = (p[2] - p[0]) * (p[5] - p[1]) - (p[3] - p[1]) * (p[4] - p[0]);
    const double o = area2 < 0.0 ? -1.0 : 1.0;
    double a[3], b[3], c[3];
    for (int e = 0; e < 3; ++e)
    {
      const double* s = p + 2 * e;
      const double* f = p + 2 * ((e + 1) % 3);
      a[e] = -(f[1] - s[1]) * o;
      b[e] = (f[0] - s[0]) * o;
      c[e] = -(a[e] * s[0] + b[e] * s[1]);
    }
    for (int i = i0; i <= i1; ++i)
    {
      const double y = y0 + (i + 0.5) * dy;
      for (int j = j0; j <= j1; ++j)
      {
        const double x = x0 + (j + 0.5) * dx;
        if (a[0] * x + b[0] * y + c[0] >= -tol && a[1] * x + b[1] * y + c[1] >= -tol
            && a[2] * x + b[2] * y + c[2] >= -tol)
          image[static_cast<std::size_t>(i) * nx + j] = values[t];
      }
    }
  }
  return image;
}
} // namespace cracklip
