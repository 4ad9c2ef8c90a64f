// Quadrature of whole cells and lip facets near a 3D front.
#include "adaptive_reference.h"
#include "geometry/crack_geometry_3d.h"
#include "geometry/p1_simplex.h"
#include "geometry/vec3.h"
#include "meshes.h"
#include "quadrature/cell_quadrature_3d.h"
#include "quadrature/crack_points_3d.h"
#include "quadrature/rules.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace cracklip;
using namespace cracklip::vec3;

namespace
{
struct PennyMesh
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  CrackGeometry3D g;
  explicit PennyMesh(int n)
  {
    test::kuhn_cube(n, x, cells);
    const CrackSurface3D s = create_ellipse_crack({0.51, 0.49, 0.503}, {0.1, 0.2, 1.0}, {1, 0, 0}, 0.3, 0.3);
    g = compute_crack_geometry_3d(x, cells, s, 1e-6);
  }
};

double cubic(const Point3& p) { return 1.0 + p[0] * p[0] * p[1] - 2.0 * p[2] * p[2] * p[2] + p[0] * p[1] * p[2]; }
} // namespace

// Every cell: the weights sum to its volume (to round-off amplified by the
// signed pieces of the point-collapsed and near-front rules) and a cubic
// polynomial is
// integrated as the plain Gauss rule of degree 3 on the whole cell does (that
// one exactly; the collapsed rules are exact in rho and along the front and
// converge exponentially around it, through the sinh map: 2e-11 with the
// default 8 points).
TEST(CellQuadrature3D, VolumesAndPolynomialsOnEveryCell)
{
  const PennyMesh m(8);
  // The signed rules with their exact settings, then the defaults (plain
  // vertex collapse with 4 radial points, exact to degree 7 in tau: a cubic
  // is degree 11 there; 6 sinh-mapped angular points instead of 8 leave
  // 3e-11 of the volume).
  for (const bool defaults : {false, true})
  {
  QuadratureOptions3D opt;
  if (!defaults)
  {
    opt.signed_point_rule = true;
    opt.near_factor = 1.0;
    opt.front_radial = 6, opt.front_angular = 8, opt.front_axial = 3;
  }
  opt.degree = 3;
  const quadrature::Rule whole = quadrature::tetrahedron(3);
  CellQuadrature3D q;
  double worst_vol = 0.0, worst_poly = 0.0;
  int front_cells = 0;
  for (std::int32_t c = 0; c < static_cast<std::int32_t>(m.cells.size() / 4); ++c)
  {
    compute_cell_quadrature_3d(m.x, m.cells, m.g, c, opt, q);
    const P1Tetrahedron T(m.x, m.cells, c);
    double vol = 0.0, poly = 0.0, exact = 0.0;
    for (int k = 0; k < q.size(); ++k)
    {
      vol += q.weight[k];
      poly += q.weight[k] * cubic(T.physical({q.ref[3 * k], q.ref[3 * k + 1], q.ref[3 * k + 2]}));
    }
    for (int k = 0; k < whole.size(); ++k)
      exact += 6 * T.volume() * whole.weights[k]
               * cubic(T.physical({whole.points[3 * k], whole.points[3 * k + 1], whole.points[3 * k + 2]}));
    worst_vol = std::max(worst_vol, std::abs(vol - T.volume()) / T.volume());
    worst_poly = std::max(worst_poly, std::abs(poly - exact) / std::abs(exact));
    front_cells += m.g.cell_class[c] == static_cast<std::int8_t>(CellClass3D::front);
  }
  std::printf("cell quadrature (%s): %d front cells; worst relative volume error %.2e, cubic %.2e\n",
              defaults ? "defaults" : "signed, 6x8x3, near 1", front_cells, worst_vol, worst_poly);
  EXPECT_GT(front_cells, 20);
  EXPECT_LT(worst_vol, defaults ? 1e-10 : 1e-12);
  EXPECT_LT(worst_poly, defaults ? 1e-4 : 1e-10);
  }
}

// The singular integrals over whole front cells: int_cell g / r and
// g r^(-1/2), r the distance to the cell's (P1) front line, against the sum
// of adaptive references over the cell's sub-tetrahedra (collapsed at the
// front edge or vertex, or at the vertex nearest the front). The collapsed
// and near-front rules are accurate to round-off amplified by their signed
// pieces; what limits a whole cell is the plain Gauss rule on sub-tetrahedra
// a diameter or more from the front line: with the defaults (degree 2 there,
// near-front rule within 1 diameter) 1e-4 of a small sub-tetrahedron's
// integral, 7e-9 of the cell's; with the near-front rule within 3
// diameters, 3e-11.
// Plain Gauss of degree 5 on the sub-tetrahedra touching the front misses by
// far more.
TEST(CellQuadrature3D, SingularIntegralsOverFrontCells)
{
  const PennyMesh m(6);
  int checked = 0;
  double worst_default = 0.0, worst_fine = 0.0, worst_gauss = 0.0;
  for (const CrackCell3D& cc : m.g.crack_cells)
  {
    if (cc.cls != CellClass3D::front or cc.front_length == 0.0 or checked >= 8)
      continue;
    ++checked;
    const P1Tetrahedron T(m.x, m.cells, cc.cell);
    const Point3 P = T.physical({cc.front_segment[0], cc.front_segment[1], cc.front_segment[2]});
    const Point3 e = front_direction(m.x, m.cells, m.g, cc.cell);
    auto dist = [&](const Point3& p)
    {
      const Point3 v = sub(p, P);
      return norm(axpy(v, -dot(v, e), e));
    };
    for (const double pw : {-1.0, -0.5})
    {
      auto f = [&](const Point3& p, double r) { return cubic(p) * std::pow(r, pw); };
      // Reference: per sub-tetrahedron, collapsed at its front edge or
      // vertex, or (no front vertex) at its vertex nearest the front line,
      // with r measured from the collapse point (no cancellation).
      double ref = 0.0;
      for (int k = 0; k < cc.num_sub(); ++k)
      {
        std::array<Point3, 4> X;
        for (int a = 0; a < 4; ++a)
          X[a] = T.physical({cc.sub[12 * k + 3 * a], cc.sub[12 * k + 3 * a + 1], cc.sub[12 * k + 3 * a + 2]});
        const int nf = cc.num_front[k];
        if (nf == 2)
          ref += test::edge_reference(X, f, 1e-12);
        else
        {
          if (nf == 0)
          {
            int best = 0;
            for (int a = 1; a < 4; ++a)
              if (dist(X[a]) < dist(X[best]))
                best = a;
            std::swap(X[0], X[best]);
          }
          // r from the line through X0 along e: exact for a front vertex; for
          // nf == 0 use the true distance (r = dist(x)).
          if (nf == 1)
            ref += test::point_reference(X, e, f, 1e-12);
          else
            ref += test::point_reference(X, e, [&](const Point3& p, double) { return f(p, dist(p)); }, 1e-12);
        }
      }
      auto integrate = [&](const QuadratureOptions3D& opt)
      {
        CellQuadrature3D q;
        compute_cell_quadrature_3d(m.x, m.cells, m.g, cc.cell, opt, q);
        double s = 0.0;
        for (int k = 0; k < q.size(); ++k)
        {
          const Point3 p = T.physical({q.ref[3 * k], q.ref[3 * k + 1], q.ref[3 * k + 2]});
          s += q.weight[k] * f(p, dist(p));
        }
        return std::abs(s - ref) / std::abs(ref);
      };
      QuadratureOptions3D opt;
      opt.signed_point_rule = true;
      opt.near_factor = 1.0;
      opt.front_radial = 6, opt.front_angular = 8, opt.front_axial = 3;
      worst_default = std::max(worst_default, integrate(opt));
      opt.near_factor = 3.0;
      worst_fine = std::max(worst_fine, integrate(opt));
      opt.near_factor = 1.0;
      opt.front_rule = FrontQuadrature::gauss;
      worst_gauss = std::max(worst_gauss, integrate(opt));
    }
  }
  std::printf("front cells: worst relative error, defaults (6x8x3, near 1) %.2e, near-front within 3 diameters "
              "%.2e, Gauss degree 5 %.2e\n",
              worst_default, worst_fine, worst_gauss);
  EXPECT_EQ(checked, 8);
  EXPECT_LT(worst_default, 1e-7);
  EXPECT_LT(worst_fine, 1e-10);
  EXPECT_GT(worst_gauss, 1e-3);
}

// Lip points on a straight front (exact P1 level sets): the weights sum to
// the lip area and int_lips r^(-1/2) has a closed form. The crack is the
// part of the plane z = z0 + ax x + ay y where x < x0 + k y; in (x, y) the
// area element is J dx dy (J = sqrt(1 + ax^2 + ay^2)) and the distance to the
// front within the plane is u / c, u = x0 + k y - x, c^2 = m . G^{-1} m with
// m = (1, -k) and G = I + a a^T the plane's metric (G^{-1} = I - a a^T / J^2):
//   int r^(-1/2) = J sqrt(c) int_0^1 int_0^{x0 + k y} u^(-1/2) dx dy
//                = J sqrt(c) 4 ((x0 + k)^(3/2) - x0^(3/2)) / (3 k).
TEST(LipPoints3D, AreaAndInverseSquareRootOnAStraightFront)
{
  const double z0 = 0.43, ax = 0.07, ay = 0.11, x0 = 0.61, k = 0.13;
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  test::kuhn_cube(6, x, cells);
  std::vector<double> v;
  for (const auto& [px, py] : {std::pair{-5.0, -3.0}, std::pair{x0 - 3 * k, -3.0}, std::pair{x0 + 4 * k, 4.0}, std::pair{-5.0, 4.0}})
    v.insert(v.end(), {px, py, z0 + ax * px + ay * py});
  const CrackGeometry3D g = compute_crack_geometry_3d(x, cells, create_polygon_crack(v), 1e-6);
  const double J = std::sqrt(1 + ax * ax + ay * ay);
  const double c2 = 1 + k * k - (ax - k * ay) * (ax - k * ay) / (J * J);
  const double exact = J * std::pow(c2, 0.25) * 4 * (std::pow(x0 + k, 1.5) - std::pow(x0, 1.5)) / (3 * k);
  const Point3 A = {x0, 0, z0 + ax * x0}, B = {x0 + k, 1, z0 + ax * (x0 + k) + ay};
  const Point3 e = unit(sub(B, A));
  // The signed and near-front rules (exact), then the defaults (plain fans,
  // Gauss near the front: 8.6e-5 at n = 4, 1.3e-6 at n = 8).
  for (const bool defaults : {false, true})
  for (const int n : {4, 6, 8})
  {
    const LipPoints3D lp = defaults ? compute_lip_points_3d(x, cells, g, n) : compute_lip_points_3d(x, cells, g, n, 1.0, true);
    double area = 0.0, s = 0.0, s_touch = 0.0, s_near = 0.0;
    for (std::size_t q = 0; q < lp.weight.size(); ++q)
    {
      const Point3 p = {lp.x[3 * q], lp.x[3 * q + 1], lp.x[3 * q + 2]};
      const Point3 w = sub(p, A);
      const double r = norm(axpy(w, -dot(w, e), e));
      area += lp.weight[q];
      s += lp.weight[q] / std::sqrt(r);
      (lp.front_vertices[q] > 0 ? s_touch : s_near) += lp.weight[q] / std::sqrt(r);
    }
    std::printf("lip points (%s) n=%d: area error %.2e, int r^-1/2 relative error %.2e (facets on the front "
                "%.4f, others %.4f)\n",
                defaults ? "defaults" : "signed, near 1", n, std::abs(area - (x0 + k / 2) * J),
                std::abs(s - exact) / exact, s_touch, s_near);
    EXPECT_NEAR(area, (x0 + k / 2) * J, 1e-12);
    if (n == 8)
      EXPECT_LT(std::abs(s - exact) / exact, defaults ? 1e-5 : 1e-10);
    if (n == 4 and defaults)
      EXPECT_LT(std::abs(s - exact) / exact, 1e-4);
  }
}
