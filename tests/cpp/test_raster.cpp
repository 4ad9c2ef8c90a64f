#include "post/raster.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace cracklip;

// The unit square cut along its diagonal into two triangles (one clockwise)
// with values 1 and 2: every pixel gets the triangle its centre lies in.
TEST(Raster, TwoTrianglesTileTheSquare)
{
  const std::vector<double> tris = {0, 0, 1, 0, 1, 1, /* below y = x, counter-clockwise */
                                    0, 0, 1, 1, 0, 1 /* above, clockwise */};
  const std::vector<double> vals = {1.0, 2.0};
  const int n = 10;
  auto img = rasterize_triangles(tris, vals, 0.0, 1.0, 0.0, 1.0, n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
    {
      const double v = img[i * n + j];
      if (j > i)
        EXPECT_EQ(v, 1.0) << i << " " << j;
      else if (j < i)
        EXPECT_EQ(v, 2.0) << i << " " << j;
      else // the centre lies on the shared diagonal: the later triangle
        EXPECT_EQ(v, 2.0);
    }
}

// Outside the triangles: NaN; a triangle smaller than a pixel that holds no
// pixel centre paints nothing; area of the painted region converges.
TEST(Raster, OutsideIsNanAndAreaConverges)
{
  const std::vector<double> tris = {0.1, 0.1, 0.9, 0.2, 0.3, 0.8, 0.5001, 0.5001, 0.5002, 0.5001, 0.5001, 0.5002};
  const std::vector<double> vals = {3.0, 7.0};
  const double exact = 0.5 * std::abs((0.9 - 0.1) * (0.8 - 0.1) - (0.2 - 0.1) * (0.3 - 0.1));
  for (int n : {50, 400})
  {
    auto img = rasterize_triangles(tris, vals, 0.0, 1.0, 0.0, 1.0, n, n);
    int inside = 0, nan = 0, seven = 0;
    for (double v : img)
    {
      inside += v == 3.0;
      nan += std::isnan(v);
      seven += v == 7.0;
    }
    EXPECT_EQ(inside + nan + seven, n * n);
    EXPECT_NEAR(inside / double(n * n), exact, 4.0 / n);
    EXPECT_EQ(seven, 0);
  }
}

TEST(Raster, RejectsBadInput)
{
  const std::vector<double> tris = {0, 0, 1, 0, 0, 1};
  const std::vector<double> vals = {1.0, 2.0};
  EXPECT_THROW(rasterize_triangles(tris, vals, 0, 1, 0, 1, 4, 4), std::invalid_argument);
  EXPECT_THROW(rasterize_triangles(tris, std::span<const double>(vals.data(), 1), 0, 0, 0, 1, 4, 4),
               std::invalid_argument);
}
