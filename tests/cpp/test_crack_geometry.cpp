#include "geometry/crack_geometry_2d.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace cracklip;

namespace
{
// Unit square split along its diagonal (0,0)-(1,1).
const std::vector<double> x2 = {0, 0, 1, 0, 1, 1, 0, 1};
const std::vector<std::int32_t> c2 = {0, 1, 2, 0, 2, 3};

double sub_area(const CrackCell& cc, int side)
{
  double a = 0.0;
  for (int s = 0; s < cc.num_sub; ++s)
  {
    if (cc.side[s] != side)
      continue;
    const double* t = &cc.sub[6 * s];
    a += 0.5 * std::abs((t[2] - t[0]) * (t[5] - t[1]) - (t[4] - t[0]) * (t[3] - t[1]));
  }
  return a;
}
} // namespace

TEST(SignedDistance, LineWithRays)
{
  CrackPath c{{0.0, 0.0, 1.0, 0.0}, {false, true}};
  EXPECT_DOUBLE_EQ(signed_distance(c, {0.5, 0.25}), 0.25);
  EXPECT_DOUBLE_EQ(signed_distance(c, {0.5, -0.25}), -0.25);
  // Beyond the end points the segment is extended as a ray.
  EXPECT_DOUBLE_EQ(signed_distance(c, {3.0, -0.5}), -0.5);
  EXPECT_DOUBLE_EQ(signed_distance(c, {-2.0, 0.5}), 0.5);
}

TEST(SignedDistance, KinkedPolylineIsContinuousNearTheKink)
{
  CrackPath c{{0.0, 0.0, 1.0, 0.0, 2.0, 1.0}, {false, false}};
  // Above the kink on the concave side, nearest segments agree in sign.
  EXPECT_GT(signed_distance(c, {1.0, 0.2}), 0.0);
  EXPECT_LT(signed_distance(c, {1.1, -0.2}), 0.0);
  EXPECT_NEAR(signed_distance(c, {1.0, -0.3}), -0.3, 1e-15);
}

TEST(CrackGeometry, StraightCutSplitsAreasExactly)
{
  CrackPath c{{-1.0, 0.3, 2.0, 0.3}, {false, false}};
  const CrackGeometry g = compute_crack_geometry(x2, c2, c, 1e-8);
  ASSERT_EQ(g.crack_cells.size(), 2u);
  // In reference coordinates each cell has area 1/2; above y = 0.3 lies
  // 0.7^2/2 / (1/2) of cell 0 ((0,0),(1,0),(1,1)) and 1 - 0.3^2 of cell 1.
  const CrackCell& a = g.crack_cells[0];
  EXPECT_EQ(a.cls, CellClass::cut);
  EXPECT_NEAR(sub_area(a, +1), 0.5 * 0.49, 1e-15);
  EXPECT_NEAR(sub_area(a, -1), 0.5 * 0.51, 1e-15);
  const CrackCell& b = g.crack_cells[1];
  EXPECT_NEAR(sub_area(b, +1), 0.5 * 0.91, 1e-15);
  EXPECT_NEAR(sub_area(b, -1), 0.5 * 0.09, 1e-15);
  // The segment is oriented with the + side (y > 0.3) on its left, so it
  // runs in +x. Cell 0 maps reference (xi, eta) to x = xi + eta.
  const double Px = a.segment[0] + a.segment[1], Qx = a.segment[2] + a.segment[3];
  EXPECT_LT(Px, Qx);
  EXPECT_EQ(g.num_snapped, 0);
}

TEST(CrackGeometry, CrackAlongAnEdgeGivesEdgeCells)
{
  CrackPath c{{-1.0, -1.0, 2.0, 2.0}, {false, false}};
  const CrackGeometry g = compute_crack_geometry(x2, c2, c, 1e-8);
  EXPECT_EQ(g.phi[0], 0.0);
  EXPECT_EQ(g.phi[2], 0.0);
  ASSERT_EQ(g.crack_cells.size(), 2u);
  EXPECT_EQ(g.crack_cells[0].cls, CellClass::edge);
  EXPECT_EQ(g.crack_cells[1].cls, CellClass::edge);
  EXPECT_EQ(g.cell_side[0], -1); // below the diagonal: right of the direction
  EXPECT_EQ(g.cell_side[1], +1);
  // Exactly one of the two cells owns the segment.
  EXPECT_NE(g.crack_cells[0].owns_segment, g.crack_cells[1].owns_segment);
}

TEST(CrackGeometry, TipCellAndCutCell)
{
  CrackPath c{{-1.0, 0.3, 0.5, 0.3}, {false, true}};
  const CrackGeometry g = compute_crack_geometry(x2, c2, c, 1e-8);
  EXPECT_EQ(static_cast<CellClass>(g.cell_class[0]), CellClass::tip);
  EXPECT_EQ(static_cast<CellClass>(g.cell_class[1]), CellClass::cut);
  ASSERT_EQ(g.tip_cells.size(), 1u);
  // Tip (0.5, 0.3) in reference coordinates of cell 0: x = xi + eta, y = eta.
  EXPECT_NEAR(g.tip_cells[0].segment[2], 0.2, 1e-15);
  EXPECT_NEAR(g.tip_cells[0].segment[3], 0.3, 1e-15);
  EXPECT_NEAR(g.psi[2], 0.5, 1e-15); // node (1, 1)
}

TEST(CrackGeometry, NearVertexCutIsSnapped)
{
  CrackPath c{{-1.0, 1e-12, 2.0, 1e-12}, {false, false}};
  const CrackGeometry g = compute_crack_geometry(x2, c2, c, 1e-8);
  EXPECT_EQ(g.num_snapped, 2);
  EXPECT_EQ(g.phi[0], 0.0);
  EXPECT_EQ(g.phi[1], 0.0);
  EXPECT_EQ(static_cast<CellClass>(g.cell_class[0]), CellClass::edge);
}

TEST(CrackGeometry, ZeroLengthSegmentThrows)
{
  CrackPath c{{0.0, 0.0, 0.0, 0.0}, {false, false}};
  EXPECT_THROW(compute_crack_geometry(x2, c2, c, 1e-8), std::invalid_argument);
}
