// Collapsed rules near a crack front against an adaptive reference.
//
// The reference integrates in plain collapsed coordinates (Duffy: rho linear,
// eta and t plain) with nested global adaptive Gauss-Kronrod, which resolves
// the r^(-1/2) endpoint singularity in rho and the near-singular angular
// factor by bisection, independently of the rules' tau^2, sinh and
// decomposition. It is first checked against closed forms on the unit
// tetrahedron (derived in the test) and shown to converge with its
// tolerance.
#include "adaptive_reference.h"
#include "geometry/cut_tetrahedron.h"
#include "geometry/p1_simplex.h"
#include "geometry/vec3.h"
#include "quadrature/front_rules_3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

using namespace cracklip;
using namespace cracklip::quadrature;
using namespace cracklip::vec3;

namespace
{
using Tet = std::array<double, 12>;
using Fn = std::function<double(const Point3&)>;

Point3 vtx(const Tet& t, int i) { return {t[3 * i], t[3 * i + 1], t[3 * i + 2]}; }
double volume(const Tet& t) { return std::abs(signed_volume(vtx(t, 0), vtx(t, 1), vtx(t, 2), vtx(t, 3))); }

/// Distance from x to the line through A with direction e (unit).
double line_distance(const Point3& x, const Point3& A, const Point3& e)
{
  const Point3 v = sub(x, A);
  return norm(axpy(v, -dot(v, e), e));
}

using test::Fr;

double edge_reference(const Tet& T, const Fr& f, double tol)
{
  return test::edge_reference({vtx(T, 0), vtx(T, 1), vtx(T, 2), vtx(T, 3)}, f, tol);
}

double point_reference(const Tet& T, const Point3& e, const Fr& f, double tol)
{
  return test::point_reference({vtx(T, 0), vtx(T, 1), vtx(T, 2), vtx(T, 3)}, e, f, tol);
}

/// A rule on T's own coordinates applied to f.
double apply(const Rule& r, const Tet& T, const Fn& f)
{
  const Point3 A = vtx(T, 0), B = vtx(T, 1), C = vtx(T, 2), D = vtx(T, 3);
  double s = 0.0;
  for (int q = 0; q < r.size(); ++q)
  {
    const double* p = &r.points[3 * q];
    s += r.weights[q] * f(axpy(axpy(axpy(A, p[0], sub(B, A)), p[1], sub(C, A)), p[2], sub(D, A)));
  }
  return 6.0 * volume(T) * s;
}

/// Integrands: r^(-1), r^(-1/2), r^(1/2), times 1, a linear and a cubic
/// polynomial in the physical coordinates.
std::vector<std::pair<std::string, std::function<double(const Point3&, double)>>> integrands()
{
  auto p1 = [](const Point3& x) { return 1.0 + x[0] - 2.0 * x[1] + 3.0 * x[2]; };
  auto p3 = [](const Point3& x) { return 2.0 + x[0] * x[0] * x[1] - x[2] * x[2] * x[2] + x[0] * x[1] * x[2]; };
  return {{"1/r", [](const Point3&, double r) { return 1.0 / r; }},
          {"r^-1/2", [](const Point3&, double r) { return 1.0 / std::sqrt(r); }},
          {"p1/r", [=](const Point3& x, double r) { return p1(x) / r; }},
          {"p3/r", [=](const Point3& x, double r) { return p3(x) / r; }},
          {"p3 r^-1/2", [=](const Point3& x, double r) { return p3(x) / std::sqrt(r); }},
          {"p1 r^1/2", [=](const Point3& x, double r) { return p1(x) * std::sqrt(r); }}};
}
} // namespace

// Closed forms on the unit tetrahedron 0, e1, e2, e3 with the front on the
// edge along e1, r = sqrt(y^2 + z^2): the length in x at (y, z) is
// 1 - y - z, so in polar coordinates (y, z) = s (cos a, sin a), s <= R(a) =
// 1 / (cos a + sin a):
//   int 1/r = int_0^{pi/2} int_0^R (1 - s (cos a + sin a)) ds da
//           = 1/2 int_0^{pi/2} da / (cos a + sin a) = ln(1 + sqrt 2) / sqrt 2;
//   int r^(-1/2) = (2/3 - 2/5) int_0^{pi/2} R^(3/2) da
//                = (4/15) 2^(-3/4) int_{pi/4}^{3 pi/4} sin(b)^(-3/2) db,
// the last a smooth integral (computed with 60 Gauss points). The adaptive
// reference reaches both to its tolerance, and converges as it is tightened.
TEST(AdaptiveReference, MatchesClosedFormsAndConverges)
{
  const Tet T = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const Point3 e = {1, 0, 0};
  const double exact1 = std::log(1.0 + std::sqrt(2.0)) / std::sqrt(2.0);
  const Rule g = gauss_legendre(60);
  double smooth = 0.0;
  for (int q = 0; q < g.size(); ++q)
  {
    const double b = std::numbers::pi / 4 + g.points[q] * std::numbers::pi / 2;
    smooth += g.weights[q] * std::numbers::pi / 2 * std::pow(std::sin(b), -1.5);
  }
  const double exact2 = 4.0 / 15.0 * std::pow(2.0, -0.75) * smooth;
  double prev1 = 1.0, prev2 = 1.0;
  for (const double tol : {1e-6, 1e-8, 1e-10, 1e-12})
  {
    const double r1 = edge_reference(T, [](const Point3&, double r) { return 1.0 / r; }, tol);
    const double r2 = edge_reference(T, [](const Point3&, double r) { return 1.0 / std::sqrt(r); }, tol);
    const double e1 = std::abs(r1 - exact1), e2 = std::abs(r2 - exact2);
    std::printf("adaptive reference tol %.0e: |1/r error| %.2e, |r^-1/2 error| %.2e\n", tol, e1, e2);
    EXPECT_LE(e1, 10 * tol);
    EXPECT_LE(e2, 10 * tol);
    EXPECT_LE(e1, prev1 + 1e-15);
    EXPECT_LE(e2, prev2 + 1e-15);
    prev1 = e1, prev2 = e2;
  }
  EXPECT_LT(prev1, 1e-12);
  EXPECT_LT(prev2, 1e-12);
  // The point-collapsed reference (collapsed at vertex A) on the same
  // closed form: the singular direction along the edge AB is a corner
  // singularity of its angular integrand, which the bisection resolves too.
  const double rp = point_reference(T, e, [](const Point3&, double r) { return 1.0 / r; }, 1e-11);
  EXPECT_NEAR(rp, exact1, 1e-10);
}

// Tetrahedra with the front on the edge AB. A sub-tetrahedron of a front
// cell lies in one quadrant of (phi, psi), so its dihedral angle at a front
// edge is at most the angle between the zero planes (about 90 degrees for
// distance level sets); the cases span that range: the unit tetrahedron
// (90 degrees, equal legs), a right angle with legs 1:10 (the sinh
// substitution's hardest case there), a thin one (5 degrees), an obtuse one
// (110 degrees), a long one and random ones (dihedral below 100 degrees).
// The edge-collapsed rule with 6 x 12 x 4 points matches the reference to
// 1e-10 (relative) for every integrand; plain Gauss of degree 12 does not
// come close.
TEST(EdgeCollapsedRule, SingularIntegrandsToTenDigits)
{
  std::vector<std::pair<std::string, Tet>> tets = {
      {"unit", {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}},
      {"legs 1:10", {0, 0, 0, 1, 0, 0, 0.3, 0.1, 0, 0.6, 0, 1.0}},
      {"thin", {0, 0, 0, 1, 0, 0, 0.4, 1, 0.0, 0.5, 1, 0.0875}},
      {"obtuse", {0, 0, 0, 1, 0, 0, 0.2, 1, 0, 0.7, -0.364, 1}},
      {"long", {0, 0, 0, 3, 0.2, 0.1, 1.5, 0.2, 0.3, 1.7, 0.1, 0.35}}};
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  while (tets.size() < 8)
  {
    Tet t;
    for (double& v : t)
      v = u(rng);
    // Dihedral angle at AB: between the parts of AC and AD normal to AB.
    const Point3 e = unit(sub(vtx(t, 1), vtx(t, 0)));
    const Point3 c = sub(vtx(t, 2), vtx(t, 0)), d = sub(vtx(t, 3), vtx(t, 0));
    const Point3 cn = axpy(c, -dot(c, e), e), dn = axpy(d, -dot(d, e), e);
    if (volume(t) > 0.02 and dot(cn, dn) > -0.17 * norm(cn) * norm(dn))
      tets.push_back({"random" + std::to_string(tets.size()), t});
  }
  const Rule gauss = tetrahedron(12);
  double worst = 0.0, worst_gauss = 0.0;
  for (const auto& [name, T] : tets)
  {
    const Point3 A = vtx(T, 0), e = unit(sub(vtx(T, 1), A));
    const Rule rule = tetrahedron_edge_collapsed(T, 6, 12, 4);
    double wsum = 0.0;
    for (double w : rule.weights)
      wsum += w;
    EXPECT_NEAR(wsum, 1.0 / 6.0, 1e-15);
    for (const auto& [fname, f] : integrands())
    {
      const Fn fx = [&](const Point3& x) { return f(x, line_distance(x, A, e)); };
      const double ref = edge_reference(T, f, 1e-13 * volume(T));
      const double err = std::abs(apply(rule, T, fx) - ref) / std::abs(ref);
      const double err_g = std::abs(apply(gauss, T, fx) - ref) / std::abs(ref);
      worst = std::max(worst, err);
      if (fname.find("r^1/2") == std::string::npos)
        worst_gauss = std::max(worst_gauss, err_g);
      EXPECT_LT(err, 1e-10) << name << " " << fname;
    }
  }
  std::printf("edge-collapsed 6x12x4: worst relative error %.2e (Gauss degree 12: %.2e)\n", worst, worst_gauss);
  EXPECT_GT(worst_gauss, 1e-4);
}

// Convergence in the angular direction on the flat tetrahedron: the sinh
// substitution makes it exponential; without it (a tetrahedron where it is
// the identity is not available, so compare point counts) the error falls
// by orders of magnitude from 4 to 12 points.
TEST(EdgeCollapsedRule, AngularConvergenceIsExponential)
{
  const Tet T = {0, 0, 0, 1, 0, 0, 0.3, 1, 0.05, 0.6, -1, 0.08};
  const Point3 A = vtx(T, 0), e = {1, 0, 0};
  const Fr fr = [](const Point3& x, double r) { return (2.0 + x[0] * x[1] - x[2]) / r; };
  const Fn f = [&](const Point3& x) { return fr(x, line_distance(x, A, e)); };
  const double ref = edge_reference(T, fr, 1e-13 * volume(T));
  std::vector<double> errs;
  for (const int n : {2, 4, 8, 12})
  {
    errs.push_back(std::abs(apply(tetrahedron_edge_collapsed(T, 6, n, 4), T, f) - ref) / std::abs(ref));
    std::printf("edge-collapsed angular points %d: relative error %.2e\n", n, errs.back());
  }
  EXPECT_LT(errs[3], 1e-11);
  EXPECT_LT(errs[3], 1e-6 * errs[0]);
}

// A vertex A on the front, the front line through A outside the
// tetrahedron: a generic direction, one in the plane of the face ABC close
// to the edge AB (grazing), one parallel to BCD (no intersection: plain
// collapse) and one whose intersection with BCD's plane is far.
TEST(PointCollapsedRule, SingularIntegrandsToTenDigits)
{
  struct Case
  {
    std::string name;
    Tet T;
    Point3 d;
  };
  const Tet unit_tet = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<Case> cases = {
      {"generic", unit_tet, {1.0, -0.5, 0.2}},
      {"in face, 1:2", unit_tet, {2, -1, 0}},
      {"grazing AB", unit_tet, {1, -0.1, 0}},
      {"parallel to BCD", unit_tet, {1, -1, 0}},
      {"far", unit_tet, {1.0, -0.95, -0.1}},
      {"random", {0.1, -0.2, 0.3, 0.9, 0.1, -0.2, 0.2, 0.7, 0.1, -0.1, 0.2, 1.0}, {-1.0, 0.8, 0.1}}};
  double worst = 0.0;
  for (const auto& [name, T, dir] : cases)
  {
    const Point3 A = vtx(T, 0), e = unit(dir);
    const Rule rule = tetrahedron_point_collapsed(T, dir, 6, 12, 4);
    double wsum = 0.0;
    for (double w : rule.weights)
      wsum += w;
    EXPECT_NEAR(wsum, 1.0 / 6.0, 1e-14) << name;
    for (const auto& [fname, f] : integrands())
    {
      const Fn fx = [&](const Point3& x) { return f(x, line_distance(x, A, e)); };
      const double ref = point_reference(T, e, f, 1e-13 * volume(T));
      const double err = std::abs(apply(rule, T, fx) - ref) / std::abs(ref);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-10) << name << " " << fname;
    }
  }
  std::printf("point-collapsed 6x12x4: worst relative error %.2e\n", worst);
}

// Lip facets: a triangle with the edge AB on the front: r = beta dist(C, AB),
// and int_T (1 + alpha) beta^(k +- 1/2) in closed form; with 7 points in tau
// the integrand, of degree up to 2 k + 6 in tau, is integrated exactly.
TEST(TriangleCollapsedRules, EdgeRuleExactAndPointRuleToTenDigits)
{
  const Rule r = triangle_edge_collapsed(7, 4);
  for (int k = 0; k <= 3; ++k)
    for (const double half : {-0.5, 0.5})
    {
      double s = 0.0;
      for (int q = 0; q < r.size(); ++q)
        s += r.weights[q] * std::pow(r.points[2 * q + 1], k + half) * (1.0 + r.points[2 * q]);
      // int_0^1 int_0^{1-b} (1 + a) b^p da db = int (1 - b + (1 - b)^2 / 2) b^p db.
      const double p = k + half;
      const double exact = 1 / (p + 1) - 1 / (p + 2) + 0.5 * (1 / (p + 1) - 2 / (p + 2) + 1 / (p + 3));
      EXPECT_NEAR(s, exact, 1e-14 * exact) << k << " " << half;
    }
  // Point rule: triangle ABC in 3D, the front through A in its plane; the
  // reference in (rho, eta) collapsed coordinates, adaptive.
  const std::array<double, 9> X = {0.1, 0.2, 0.3, 1.1, 0.4, 0.2, 0.3, 1.2, 0.6};
  const Point3 A = {X[0], X[1], X[2]}, B = {X[3], X[4], X[5]}, C = {X[6], X[7], X[8]};
  const double area = 0.5 * norm(cross(sub(B, A), sub(C, A)));
  double worst = 0.0;
  for (const double mix : {-0.3, -0.05, 1.2, 2.5, 6.0})
  {
    // Directions in the plane, outside the angle at A: B - A + mix (C - B) for
    // mix < 0 or > 1 (mix = 6: the plain fan).
    const Point3 d = axpy(sub(B, A), mix, sub(C, B));
    const Point3 e = unit(d);
    const Rule rp = triangle_point_collapsed(X, d, 6, 12);
    for (const double pw : {-0.5, 0.5})
    {
      auto fr = [&](const Point3& x, double r) { return (1.0 + x[0] - x[1] * x[2]) * std::pow(r, pw); };
      auto f = [&](const Point3& x) { return fr(x, line_distance(x, A, e)); };
      // x = A + rho P(eta), P = (1 - eta) (B - A) + eta (C - A), r = rho |P'|.
      const double ref = 2 * area * test::adaptive_square(
                                        [&](double rho, double eta)
                                        {
                                          const Point3 P = axpy(scale(1 - eta, sub(B, A)), eta, sub(C, A));
                                          return rho * fr(axpy(A, rho, P), rho * norm(axpy(P, -dot(P, e), e)));
                                        },
                                        1e-14);
      double s = 0.0;
      for (int q = 0; q < rp.size(); ++q)
        s += rp.weights[q] * f(axpy(axpy(A, rp.points[2 * q], sub(B, A)), rp.points[2 * q + 1], sub(C, A)));
      s *= 2 * area;
      const double err = std::abs(s - ref) / std::abs(ref);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-10) << "mix " << mix << " power " << pw;
    }
  }
  std::printf("triangle point-collapsed 6x12: worst relative error %.2e\n", worst);
}
