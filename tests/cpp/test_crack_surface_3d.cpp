// Crack surfaces and their level sets against closed forms.
#include "geometry/crack_surface_3d.h"
#include "geometry/vec3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

using namespace cracklip;
using namespace cracklip::vec3;

namespace
{
/// Distance from y to the ellipse by dense sampling of the parameter then
/// golden-section refinement of |y - (a cos t, b sin t)| (independent of
/// the bisection in closest_point_on_ellipse).
double ellipse_distance_by_search(double a, double b, std::array<double, 2> y)
{
  auto d = [&](double t) { return std::hypot(y[0] - a * std::cos(t), y[1] - b * std::sin(t)); };
  const int n = 20000;
  int best = 0;
  for (int k = 1; k < n; ++k)
    if (d(2 * std::numbers::pi * k / n) < d(2 * std::numbers::pi * best / n))
      best = k;
  double lo = 2 * std::numbers::pi * (best - 1) / n, hi = 2 * std::numbers::pi * (best + 1) / n;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 200; ++it)
  {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    (d(m1) < d(m2) ? hi : lo) = (d(m1) < d(m2) ? m2 : m1);
  }
  return d(0.5 * (lo + hi));
}
} // namespace

TEST(EllipsePoint, ClosedFormsOnTheAxesAndCircle)
{
  // Centre of a circle: distance -a; of an ellipse a >= b: -b (nearest
  // points (0, +-b)); on the major axis inside, beyond the evolute's cusp
  // x = (a^2 - b^2) / a, the vertex (a, 0) is nearest.
  EXPECT_DOUBLE_EQ(closest_point_on_ellipse(2.0, 2.0, {0.0, 0.0}).distance, -2.0);
  EXPECT_DOUBLE_EQ(closest_point_on_ellipse(2.0, 1.0, {0.0, 0.0}).distance, -1.0);
  EXPECT_DOUBLE_EQ(closest_point_on_ellipse(1.0, 2.0, {0.0, 0.0}).distance, -1.0);
  EXPECT_NEAR(closest_point_on_ellipse(2.0, 1.0, {1.9, 0.0}).distance, -0.1, 1e-15);
  EXPECT_NEAR(closest_point_on_ellipse(2.0, 1.0, {3.0, 0.0}).distance, 1.0, 1e-15);
  EXPECT_NEAR(closest_point_on_ellipse(2.0, 1.0, {0.0, -3.0}).distance, 2.0, 1e-15);
  EXPECT_NEAR(closest_point_on_ellipse(3.0, 3.0, {3.0, 4.0}).distance, 2.0, 1e-15);
  // Inside on the major axis before the cusp (x < (a^2 - b^2)/a = 1.5):
  // x0 = a^2 y / (a^2 - b^2), distance^2 = b^2 (1 - y^2 / (a^2 - b^2)).
  const EllipsePoint e = closest_point_on_ellipse(2.0, 1.0, {0.6, 0.0});
  EXPECT_NEAR(e.x[0], 4.0 * 0.6 / 3.0, 1e-15);
  EXPECT_NEAR(e.distance, -std::sqrt(1.0 - 0.36 / 3.0), 1e-15);
  EXPECT_THROW(closest_point_on_ellipse(0.0, 1.0, {0, 0}), std::invalid_argument);
}

// Random points at all distances: the closest point lies on the ellipse, the
// offset is along the ellipse's normal there, and the distance equals a
// brute-force search's.
TEST(EllipsePoint, RandomPointsAgainstSearchAndOptimality)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (const auto& [a, b] : {std::pair{2.0, 1.0}, std::pair{1.0, 0.25}, std::pair{0.5, 1.5}})
    for (int k = 0; k < 300; ++k)
    {
      const std::array<double, 2> y = {u(rng), u(rng)};
      const EllipsePoint e = closest_point_on_ellipse(a, b, y);
      EXPECT_NEAR(e.x[0] * e.x[0] / (a * a) + e.x[1] * e.x[1] / (b * b), 1.0, 2e-15);
      const double nx = e.x[0] / (a * a), ny = e.x[1] / (b * b);
      const double cr = (y[0] - e.x[0]) * ny - (y[1] - e.x[1]) * nx;
      EXPECT_NEAR(cr / std::hypot(nx, ny), 0.0, 1e-14);
      EXPECT_NEAR(std::abs(e.distance), ellipse_distance_by_search(a, b, y), 1e-12);
      const bool inside = y[0] * y[0] / (a * a) + y[1] * y[1] / (b * b) < 1.0;
      EXPECT_EQ(e.distance < 0.0, inside);
    }
}

TEST(EllipseCrack, LevelSetsAreDistancesInTheTiltedPlane)
{
  const Point3 c = {0.3, -0.2, 0.5};
  const Point3 n = unit(Point3{0.2, -0.1, 1.0});
  const CrackSurface3D s = create_ellipse_crack(c, scale(3.0, n), {1.0, 0.5, 0.0}, 0.8, 0.4);
  const Point3 ea = unit(axpy(Point3{1.0, 0.5, 0.0}, -dot(Point3{1.0, 0.5, 0.0}, n), n));
  const Point3 eb = cross(n, ea);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int k = 0; k < 200; ++k)
  {
    const Point3 p = {u(rng), u(rng), u(rng)};
    const auto [phi, psi] = s.level_sets(p);
    const Point3 d = sub(p, c);
    EXPECT_NEAR(phi, dot(d, n), 1e-15);
    EXPECT_NEAR(psi, closest_point_on_ellipse(0.8, 0.4, {dot(d, ea), dot(d, eb)}).distance, 1e-15);
  }
  // The front point at the end of semi-axis a, and |grad psi| = 1 near the
  // front (central differences, h = 1e-5: error O(h^2) + round-off / h).
  const Point3 f = axpy(c, 0.8, ea);
  EXPECT_NEAR(s.level_sets(f)[1], 0.0, 1e-15);
  for (const Point3 p : {axpy(f, 0.01, ea), axpy(axpy(c, 0.4 * 0.9, eb), 0.0, ea), axpy(f, -0.05, n)})
  {
    const double h = 1e-5;
    Point3 g;
    for (int d = 0; d < 3; ++d)
    {
      Point3 pp = p, pm = p;
      pp[d] += h, pm[d] -= h;
      g[d] = (s.level_sets(pp)[1] - s.level_sets(pm)[1]) / (2 * h);
    }
    EXPECT_NEAR(norm(g), 1.0, 1e-8);
    EXPECT_NEAR(dot(g, n), 0.0, 1e-8);
  }
  const auto box = s.bounding_box();
  for (int k = 0; k < 100; ++k)
  {
    const double t = 2 * std::numbers::pi * k / 100;
    const Point3 q = axpy(axpy(c, 0.8 * std::cos(t), ea), 0.4 * std::sin(t), eb);
    for (int d = 0; d < 3; ++d)
      EXPECT_TRUE(q[d] >= box[d] - 1e-15 and q[d] <= box[3 + d] + 1e-15);
  }
}

TEST(EllipseCrack, BadInputNamesTheCause)
{
  auto msg = [](auto&& f)
  {
    try
    {
      f();
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(msg([] { create_ellipse_crack({0, 0, 0}, {0, 0, 0}, {1, 0, 0}, 1, 1); }).find("normal is zero"),
            std::string::npos);
  EXPECT_NE(msg([] { create_ellipse_crack({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.0, 1); }).find("semi-axes must be"),
            std::string::npos);
  EXPECT_NE(msg([] { create_ellipse_crack({0, 0, 0}, {0, 0, 1}, {0, 0, 2}, 1, 1); }).find("parallel to the normal"),
            std::string::npos);
  EXPECT_NE(msg([] { create_ellipse_crack({0, NAN, 0}, {0, 0, 1}, {1, 0, 0}, 1, 1); }).find("not finite"),
            std::string::npos);
}

// Square crack [0, 1]^2 in the plane z = 0.25, counter-clockwise seen from
// +z: phi = z - 0.25; psi = -(distance to the nearest side) inside, the
// distance to the square outside (to a side or a corner).
TEST(PolygonCrack, SquareClosedForm)
{
  const std::vector<double> v = {0, 0, 0.25, 1, 0, 0.25, 1, 1, 0.25, 0, 1, 0.25};
  const CrackSurface3D s = create_polygon_crack(v);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  for (int k = 0; k < 500; ++k)
  {
    const Point3 p = {u(rng), u(rng), u(rng)};
    const auto [phi, psi] = s.level_sets(p);
    EXPECT_NEAR(phi, p[2] - 0.25, 1e-15);
    const double dx = std::max({-p[0], 0.0, p[0] - 1.0}), dy = std::max({-p[1], 0.0, p[1] - 1.0});
    const bool inside = dx == 0.0 and dy == 0.0;
    const double exact = inside ? -std::min({p[0], 1 - p[0], p[1], 1 - p[1]}) : std::hypot(dx, dy);
    EXPECT_NEAR(psi, exact, 1e-15);
  }
  // Reversed vertex order: the normal flips, so phi changes sign.
  const std::vector<double> r = {0, 1, 0.25, 1, 1, 0.25, 1, 0, 0.25, 0, 0, 0.25};
  EXPECT_NEAR(create_polygon_crack(r).level_sets({0.5, 0.5, 1.0})[0], -0.75, 1e-15);
}

// An L-shaped (non-convex) polygon: the reflex corner (1, 1) is inside-
// adjacent; psi at points near it from either side.
TEST(PolygonCrack, NonConvexPolygonSigns)
{
  const std::vector<double> v = {0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0};
  const CrackSurface3D s = create_polygon_crack(v);
  EXPECT_NEAR(s.level_sets({1.2, 1.3, 0.3})[1], 0.2, 1e-15);                      // in the notch
  EXPECT_NEAR(s.level_sets({1.1, 1.1, 0.0})[1], 0.1, 1e-15);                      // on its diagonal
  EXPECT_NEAR(s.level_sets({0.9, 0.95, 0.0})[1], -std::hypot(0.1, 0.05), 1e-15); // inside: the corner
  EXPECT_NEAR(s.level_sets({0.95, 0.95, 0.0})[1], -std::hypot(0.05, 0.05), 1e-15);
  EXPECT_NEAR(s.level_sets({0.5, 1.5, 0.0})[1], -0.5, 1e-15);
  EXPECT_NEAR(s.level_sets({2.5, 1.5, 0.0})[1], std::hypot(0.5, 0.5), 1e-15);    // convex corner
}

TEST(PolygonCrack, BadInputNamesTheCause)
{
  auto msg = [](std::vector<double> v)
  {
    try
    {
      create_polygon_crack(v);
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(msg({0, 0, 0, 1, 0, 0, 1, 1, 0.1, 0, 1, 0}).find("off the polygon's plane"), std::string::npos);
  // Edge 2 ((4, 2) -> (2, -1)) crosses edge 0 (y = 0).
  EXPECT_NE(msg({0, 0, 0, 4, 0, 0, 4, 2, 0, 2, -1, 0, 0, 2, 0}).find("edges 0 and 2 intersect"), std::string::npos);
  EXPECT_NE(msg({0, 0, 0, 1, 0, 0, 2, 0, 0}).find("zero area"), std::string::npos);
  EXPECT_NE(msg({0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0}).find("coincide"), std::string::npos);
}

namespace
{
/// The unit square [0, 1]^2 at z = 0.25 as 2 n^2 triangles, oriented +z.
void square_triangulation(int n, std::vector<double>& v, std::vector<std::int32_t>& t)
{
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      v.insert(v.end(), {double(i) / n, double(j) / n, 0.25});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      t.insert(t.end(), {a, b, c, a, c, d});
    }
}
} // namespace

// A planar triangulation gives the polygon's (exact) level sets.
TEST(TriangulatedCrack, PlanarTriangulationEqualsThePolygon)
{
  std::vector<double> v;
  std::vector<std::int32_t> t;
  square_triangulation(5, v, t);
  const CrackSurface3D s = create_triangulated_crack(v, t);
  const CrackSurface3D sq = create_polygon_crack(std::vector<double>{0, 0, 0.25, 1, 0, 0.25, 1, 1, 0.25, 0, 1, 0.25});
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  for (int k = 0; k < 2000; ++k)
  {
    const Point3 p = {u(rng), u(rng), u(rng)};
    const auto a = s.level_sets(p), b = sq.level_sets(p);
    EXPECT_NEAR(a[0], b[0], 1e-14);
    EXPECT_NEAR(a[1], b[1], 1e-14) << p[0] << " " << p[1] << " " << p[2];
  }
}

// A curved surface (a cap of the sphere of radius R about the origin, as a
// latitude-longitude triangulation): |phi| equals the brute-force distance
// to the triangles (the tree finds the nearest one), and its sign is
// outward (the triangles are oriented outward).
TEST(TriangulatedCrack, CurvedSurfaceNearestTriangleAndSign)
{
  const double R = 1.0;
  const int nr = 6, nth = 16;
  std::vector<double> v = {0, 0, R};
  std::vector<std::int32_t> t;
  for (int i = 1; i <= nr; ++i)
    for (int j = 0; j < nth; ++j)
    {
      const double th = 0.8 * i / nr, ph = 2 * std::numbers::pi * j / nth;
      v.insert(v.end(), {R * std::sin(th) * std::cos(ph), R * std::sin(th) * std::sin(ph), R * std::cos(th)});
    }
  auto id = [&](int i, int j) { return i == 0 ? 0 : 1 + (i - 1) * nth + (j % nth); };
  for (int j = 0; j < nth; ++j)
    t.insert(t.end(), {0, id(1, j), id(1, j + 1)});
  for (int i = 1; i < nr; ++i)
    for (int j = 0; j < nth; ++j)
      t.insert(t.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1)});
  const CrackSurface3D s = create_triangulated_crack(v, t);
  auto brute = [&](const Point3& p)
  {
    double best = 1e300;
    for (std::size_t k = 0; k < t.size() / 3; ++k)
    {
      // Distance to the triangle by projection and clamping on a fine grid of
      // barycentric coordinates: an independent, slower reference.
      const Point3 a = {v[3 * t[3 * k]], v[3 * t[3 * k] + 1], v[3 * t[3 * k] + 2]};
      const Point3 b = {v[3 * t[3 * k + 1]], v[3 * t[3 * k + 1] + 1], v[3 * t[3 * k + 1] + 2]};
      const Point3 c = {v[3 * t[3 * k + 2]], v[3 * t[3 * k + 2] + 1], v[3 * t[3 * k + 2] + 2]};
      const int m = 60;
      for (int i = 0; i <= m; ++i)
        for (int j = 0; i + j <= m; ++j)
          best = std::min(best, dist(p, axpy(axpy(a, double(i) / m, sub(b, a)), double(j) / m, sub(c, a))));
    }
    return best;
  };
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-0.6, 0.6), w(0.5, 1.4);
  for (int k = 0; k < 40; ++k)
  {
    const Point3 p = {u(rng), u(rng), w(rng)};
    const auto [phi, psi] = s.level_sets(p);
    const double d = brute(p);
    // Inside the cap's cone, phi is the true signed distance (the grid
    // reference is within ~h^2/8 of the exact distance, h = side / 60).
    if (psi < -0.05)
    {
      EXPECT_NEAR(std::abs(phi), d, 5e-4);
      EXPECT_EQ(phi > 0.0, norm(p) > R);
    }
  }
}

TEST(TriangulatedCrack, BadInputNamesTheTriangleAndTheFix)
{
  auto msg = [](std::vector<double> v, std::vector<std::int32_t> t)
  {
    try
    {
      create_triangulated_crack(v, t);
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::vector<double> v = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0, -1, -1, 0};
  // Three triangles on edge (0, 1).
  const std::string nm = msg(v, {0, 1, 2, 1, 0, 3, 0, 1, 5});
  EXPECT_NE(nm.find("edge (0, 1) belongs to 3 triangles"), std::string::npos) << nm;
  EXPECT_NE(nm.find("non-manifold"), std::string::npos);
  // Triangles 0 and 1 both traverse (1, 2) from 1 to 2.
  const std::string io = msg(v, {0, 1, 2, 4, 1, 2});
  EXPECT_NE(io.find("triangles 0 and 1"), std::string::npos) << io;
  EXPECT_NE(io.find("inconsistent orientation"), std::string::npos);
  EXPECT_NE(io.find("reverse the vertex order of triangle 1"), std::string::npos);
  EXPECT_NE(msg(v, {0, 1, 1}).find("triangle 0 (vertices 0, 1, 1) is degenerate"), std::string::npos);
  EXPECT_NE(msg({0, 0, 0, 1, 0, 0, 2, 0, 0}, {0, 1, 2}).find("degenerate"), std::string::npos);
  EXPECT_NE(msg(v, {0, 1, 9}).find("refers to vertex 9"), std::string::npos);
  // A closed surface (tetrahedron) has no front.
  EXPECT_NE(msg(v, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}).find("closed"), std::string::npos);
  // Two triangles touching at vertex 0 only: four boundary edges there.
  const std::string bow = msg(v, {0, 1, 2, 0, 5, 3});
  EXPECT_NE(bow.find("vertex 0"), std::string::npos) << bow;
  EXPECT_NE(bow.find("boundary edges"), std::string::npos);
}
