// Cutting one tetrahedron (and one triangle) by a linear level set, against
// closed forms that do not use the cut:
// - the volume of {f > 0} in a simplex with distinct vertex values f_i is
//   V sum_i (f_i)_+^d / prod_{j != i} (f_i - f_j) (d = 3 for a tetrahedron,
//   d = 2 for a triangle: the divided difference of (x)_+^d at the f_i,
//   i.e. the B-spline identity for the volume of a simplex slab);
// - with two zero values (one +, one -) the + part is the fraction
//   f_+ / (f_+ - f_-) of the volume (a tetrahedron on the same base);
// - the zero set is the convex hull of the edge zeros, whose area the test
//   computes from the vertex values directly.
#include "geometry/cut_tetrahedron.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace cracklip;

namespace
{
Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 cross(const Point3& a, const Point3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }

/// A random tetrahedron of volume at least 0.02 in [-1, 1]^3, either orientation.
std::array<double, 12> random_tet(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;)
  {
    std::array<double, 12> x;
    for (double& v : x)
      v = u(rng);
    const double vol = signed_volume({x[0], x[1], x[2]}, {x[3], x[4], x[5]}, {x[6], x[7], x[8]},
                                     {x[9], x[10], x[11]});
    if (std::abs(vol) > 0.02)
      return x;
  }
}

Point3 vertex(const std::array<double, 12>& x, int i) { return {x[3 * i], x[3 * i + 1], x[3 * i + 2]}; }

/// Gradient of the linear function with values f at the vertices of x.
Point3 gradient(const std::array<double, 12>& x, const std::array<double, 4>& f)
{
  // Rows e_i = x_i - x_0; grad . e_i = f_i - f_0: grad = (sum_i (f_i - f_0) c_i) / det with
  // c_1 = e_2 x e_3, c_2 = e_3 x e_1, c_3 = e_1 x e_2.
  const Point3 e1 = sub(vertex(x, 1), vertex(x, 0)), e2 = sub(vertex(x, 2), vertex(x, 0)),
               e3 = sub(vertex(x, 3), vertex(x, 0));
  const double det = dot(e1, cross(e2, e3));
  const Point3 c1 = cross(e2, e3), c2 = cross(e3, e1), c3 = cross(e1, e2);
  Point3 g;
  for (int d = 0; d < 3; ++d)
    g[d] = ((f[1] - f[0]) * c1[d] + (f[2] - f[0]) * c2[d] + (f[3] - f[0]) * c3[d]) / det;
  return g;
}

/// Exact volume fraction of {f > 0} (closed forms above).
double positive_fraction(const std::array<double, 4>& f)
{
  int npos = 0, nneg = 0;
  for (double v : f)
    npos += v > 0, nneg += v < 0;
  if (nneg == 0)
    return 1.0;
  if (npos == 0)
    return 0.0;
  if (npos + nneg == 2)
  {
    double p = 0, n = 0;
    for (double v : f)
      (v > 0 ? p : (v < 0 ? n : p)) += (v != 0) ? v : 0.0;
    return p / (p - n);
  }
  double s = 0.0;
  for (int i = 0; i < 4; ++i)
  {
    if (f[i] <= 0.0)
      continue;
    double den = 1.0;
    for (int j = 0; j < 4; ++j)
      if (j != i)
        den *= f[i] - f[j];
    s += f[i] * f[i] * f[i] / den;
  }
  return s;
}

/// Area of the zero set of f in the tetrahedron: the convex polygon of the
/// zero vertices and edge zeros (3 or 4 points), from the values directly.
/// (Translation-invariant vector area: the points are used as they are.)
double zero_set_area(const std::array<double, 12>& x, const std::array<double, 4>& f)
{
  std::vector<Point3> p;
  for (int i = 0; i < 4; ++i)
    if (f[i] == 0.0)
      p.push_back(vertex(x, i));
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (f[i] * f[j] < 0.0)
      {
        const double t = f[i] / (f[i] - f[j]);
        const Point3 a = vertex(x, i), b = vertex(x, j);
        p.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])});
      }
  if (p.size() < 3)
    return 0.0;
  // Vector area of a closed polygon; for 4 coplanar points in convex
  // position the convex order has the largest area of the three orders.
  auto polygon_area = [&](const std::vector<int>& o)
  {
    Point3 s = {0, 0, 0};
    for (std::size_t i = 0; i < o.size(); ++i)
    {
      const Point3 c = cross(p[o[i]], p[o[(i + 1) % o.size()]]);
      for (int d = 0; d < 3; ++d)
        s[d] += c[d];
    }
    return 0.5 * norm(s);
  };
  if (p.size() == 3)
    return polygon_area({0, 1, 2});
  return std::max({polygon_area({0, 1, 2, 3}), polygon_area({0, 1, 3, 2}), polygon_area({0, 2, 1, 3})});
}

/// Checks one cut: volumes (total and per side), positive orientation,
/// interface on the zero set, oriented to +, with the exact area.
void check_cut(const std::array<double, 12>& x, const std::array<double, 4>& f, bool generic)
{
  TetrahedronCut cut;
  cut_tetrahedron(x, f, cut);
  const double V = std::abs(signed_volume(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3)));
  double vol[2] = {0.0, 0.0};
  for (int k = 0; k < cut.num_tets; ++k)
  {
    const auto& t = cut.tets[k];
    const double v = signed_volume(cut.x[t[0]], cut.x[t[1]], cut.x[t[2]], cut.x[t[3]]);
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0);
    if (generic)
      EXPECT_GT(v, 1e-9 * V) << "degenerate sub-tetrahedron in a generic configuration";
    vol[cut.side[k] > 0] += v;
  }
  EXPECT_NEAR(vol[0] + vol[1], V, 1e-13 * V);
  const double frac = positive_fraction(f);
  EXPECT_NEAR(vol[1], frac * V, 1e-12 * V) << f[0] << " " << f[1] << " " << f[2] << " " << f[3];
  // Interface.
  const Point3 g = gradient(x, f);
  double fmax = 0.0;
  for (double v : f)
    fmax = std::max(fmax, std::abs(v));
  double area = 0.0;
  for (int k = 0; k < cut.num_interface; ++k)
  {
    const auto& t = cut.interface[k];
    for (int i = 0; i < 3; ++i)
    {
      const CutPoint& fr = cut.from[t[i]];
      EXPECT_LE(std::abs(fr.interpolate(f)), 1e-15 * fmax);
    }
    const Point3 n = cross(sub(cut.x[t[1]], cut.x[t[0]]), sub(cut.x[t[2]], cut.x[t[0]]));
    if (generic)
      EXPECT_GT(dot(n, g), 0.0) << "interface triangle not oriented to the + side";
    else // a triangle of round-off size may have any orientation
      EXPECT_GE(dot(n, g), -1e-14 * norm(g)) << "interface triangle not oriented to the + side";
    area += 0.5 * norm(n);
  }
  int nzero = 0;
  for (double v : f)
    nzero += v == 0.0;
  const bool crossed = cut.kind == ZeroSet::cut or cut.kind == ZeroSet::face;
  EXPECT_EQ(cut.num_interface > 0, crossed);
  if (crossed)
    EXPECT_NEAR(area, zero_set_area(x, f), 1e-13 * std::pow(V, 2.0 / 3.0) * 10)
        << f[0] << " " << f[1] << " " << f[2] << " " << f[3];
  else
    EXPECT_EQ(cut.num_interface, 0);
  // Point origins reproduce the points.
  for (int p = 0; p < cut.num_points; ++p)
  {
    const CutPoint& fr = cut.from[p];
    for (int d = 0; d < 3; ++d)
    {
      std::array<double, 4> xd = {x[d], x[3 + d], x[6 + d], x[9 + d]};
      EXPECT_NEAR(fr.interpolate(xd), cut.x[p][d], 1e-15 * 4);
    }
  }
}
} // namespace

// All 3^4 - 1 sign patterns (not all zero), random magnitudes in [0.05, 1],
// random tetrahedra of both orientations.
TEST(CutTetrahedron, EverySignPatternSplitsVolumeExactly)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mag(0.05, 1.0);
  int patterns = 0;
  for (int code = 0; code < 81; ++code)
  {
    std::array<int, 4> s;
    int c = code;
    bool all_zero = true;
    for (int i = 0; i < 4; ++i)
    {
      s[i] = c % 3 - 1;
      c /= 3;
      all_zero = all_zero and s[i] == 0;
    }
    if (all_zero)
      continue;
    ++patterns;
    for (int trial = 0; trial < 40; ++trial)
    {
      const auto x = random_tet(rng);
      std::array<double, 4> f;
      for (int i = 0; i < 4; ++i)
        f[i] = s[i] * mag(rng);
      check_cut(x, f, true);
    }
  }
  EXPECT_EQ(patterns, 80);
}

TEST(CutTetrahedron, CaseCountsMatchTheTable)
{
  const std::array<double, 12> x = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  TetrahedronCut cut;
  auto count = [&](std::array<double, 4> f)
  {
    cut_tetrahedron(x, f, cut);
    return std::array<int, 3>{cut.num_tets, cut.num_interface, static_cast<int>(cut.kind)};
  };
  EXPECT_EQ(count({1, -1, -1, -1}), (std::array<int, 3>{4, 1, 4}));
  EXPECT_EQ(count({1, 1, -1, -1}), (std::array<int, 3>{6, 2, 4}));
  EXPECT_EQ(count({0, 1, -1, -1}), (std::array<int, 3>{3, 1, 4}));
  EXPECT_EQ(count({0, 0, 1, -1}), (std::array<int, 3>{2, 1, 4}));
  EXPECT_EQ(count({0, 0, 0, -1}), (std::array<int, 3>{1, 1, 3}));
  EXPECT_EQ(count({0, 0, 1, 1}), (std::array<int, 3>{1, 0, 2}));
  EXPECT_EQ(count({0, 1, 1, 1}), (std::array<int, 3>{1, 0, 1}));
  EXPECT_EQ(count({1, 1, 1, 1}), (std::array<int, 3>{1, 0, 0}));
  EXPECT_THROW(count({0, 0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(count({0, 1, NAN, 0}), std::invalid_argument);
}

// Fuzz: values spread over 30 orders of magnitude with random zeros (the
// cuts land within round-off of vertices and edges): every sub-volume is
// finite and non-negative and the volumes still sum to the parent's.
TEST(CutTetrahedron, FuzzNearDegenerateValues)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> expo(-30.0, 0.0);
  std::uniform_int_distribution<int> sign(-1, 1);
  for (int trial = 0; trial < 5000; ++trial)
  {
    const auto x = random_tet(rng);
    std::array<double, 4> f;
    bool all_zero = true;
    for (double& v : f)
    {
      v = sign(rng) * std::pow(10.0, expo(rng));
      all_zero = all_zero and v == 0.0;
    }
    if (all_zero)
      continue;
    check_cut(x, f, false);
    if (::testing::Test::HasFailure())
      return;
  }
}

TEST(CutTriangle, AreasOrientationAndZeroSegment)
{
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0), mag(0.05, 1.0);
  for (int code = 0; code < 27; ++code)
  {
    std::array<int, 3> s;
    int c = code;
    for (int i = 0; i < 3; ++i)
      s[i] = c % 3 - 1, c /= 3;
    if (s[0] == 0 and s[1] == 0 and s[2] == 0)
      continue;
    for (int trial = 0; trial < 20; ++trial)
    {
      std::array<double, 9> x;
      for (double& v : x)
        v = u(rng);
      const Point3 a = {x[0], x[1], x[2]}, b = {x[3], x[4], x[5]}, cc = {x[6], x[7], x[8]};
      const Point3 n0 = cross(sub(b, a), sub(cc, a));
      const double A = 0.5 * norm(n0);
      if (A < 0.05)
        continue;
      std::array<double, 3> f;
      for (int i = 0; i < 3; ++i)
        f[i] = s[i] * mag(rng);
      TriangleCut cut;
      cut_triangle(x, f, cut);
      double area[2] = {0, 0};
      for (int k = 0; k < cut.num_tris; ++k)
      {
        const auto& t = cut.tris[k];
        const Point3 n = cross(sub(cut.x[t[1]], cut.x[t[0]]), sub(cut.x[t[2]], cut.x[t[0]]));
        EXPECT_GT(dot(n, n0), 0.0) << "sub-triangle lost the orientation";
        area[cut.side[k] > 0] += 0.5 * norm(n);
      }
      // Area of {f > 0}: sum_i (f_i)_+^2 / prod_{j != i} (f_i - f_j) for
      // distinct values; one zero between + and -: the fraction is
      // f_+ / (f_+ - f_-) (same apex).
      int npos = 0, nneg = 0;
      for (double v : f)
        npos += v > 0, nneg += v < 0;
      double frac;
      if (nneg == 0)
        frac = 1.0;
      else if (npos == 0)
        frac = 0.0;
      else if (npos + nneg == 2)
      {
        double p = 0, m = 0;
        for (double v : f)
          (v > 0 ? p : m) += v;
        frac = p / (p - m);
      }
      else
      {
        frac = 0.0;
        for (int i = 0; i < 3; ++i)
          if (f[i] > 0)
          {
            double den = 1.0;
            for (int j = 0; j < 3; ++j)
              if (j != i)
                den *= f[i] - f[j];
            frac += f[i] * f[i] / den;
          }
      }
      EXPECT_NEAR(area[0] + area[1], A, 1e-14);
      EXPECT_NEAR(area[1], frac * A, 1e-13);
      int nzero = 3 - npos - nneg;
      const bool has_segment = cut.kind == ZeroSet::cut or nzero == 2;
      EXPECT_EQ(cut.zero_segment[0] >= 0, has_segment);
      if (has_segment)
        for (int e : cut.zero_segment)
          EXPECT_LE(std::abs(cut.from[e].interpolate(f)), 1e-15);
    }
  }
}
