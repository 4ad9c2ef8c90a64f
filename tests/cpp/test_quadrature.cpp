#include "quadrature/rules.h"

#include <cmath>
#include <gtest/gtest.h>
#include <stdexcept>

using namespace cracklip::quadrature;

// Exact: int_0^1 x^k dx = 1 / (k + 1).
TEST(GaussLegendre, ExactForDegree2nMinus1)
{
  for (int n = 1; n <= 12; ++n)
  {
    const Rule r = gauss_legendre(n);
    for (int k = 0; k <= 2 * n - 1; ++k)
    {
      double s = 0.0;
      for (int q = 0; q < r.size(); ++q)
        s += r.weights[q] * std::pow(r.points[q], k);
      EXPECT_NEAR(s, 1.0 / (k + 1), 1e-14) << "n=" << n << " k=" << k;
    }
  }
}

// Exact on the reference triangle: int x^a y^b = a! b! / (a + b + 2)!.
TEST(TriangleRule, ExactForItsDegree)
{
  auto fact = [](int n) { double f = 1; for (int i = 2; i <= n; ++i) f *= i; return f; };
  for (int deg = 1; deg <= 20; ++deg)
  {
    const Rule r = triangle(deg);
    for (int a = 0; a <= deg; ++a)
      for (int b = 0; a + b <= deg; ++b)
      {
        double s = 0.0;
        for (int q = 0; q < r.size(); ++q)
          s += r.weights[q] * std::pow(r.points[2 * q], a) * std::pow(r.points[2 * q + 1], b);
        EXPECT_NEAR(s, fact(a) * fact(b) / fact(a + b + 2), 1e-14) << deg << " " << a << " " << b;
      }
  }
}

// Exact on the reference tetrahedron: int x^a y^b z^c = a! b! c! / (a + b + c + 3)!.
TEST(TetrahedronRule, ExactForItsDegree)
{
  auto fact = [](int n) { double f = 1; for (int i = 2; i <= n; ++i) f *= i; return f; };
  for (int deg = 0; deg <= 14; ++deg)
  {
    const Rule r = tetrahedron(deg);
    double wsum = 0.0;
    for (int q = 0; q < r.size(); ++q)
    {
      wsum += r.weights[q];
      EXPECT_GT(r.weights[q], 0.0);
      const double* p = &r.points[3 * q];
      EXPECT_TRUE(p[0] >= 0 and p[1] >= 0 and p[2] >= 0 and p[0] + p[1] + p[2] <= 1.0);
    }
    EXPECT_NEAR(wsum, 1.0 / 6.0, 1e-15);
    for (int a = 0; a <= deg; ++a)
      for (int b = 0; a + b <= deg; ++b)
        for (int c = 0; a + b + c <= deg; ++c)
        {
          double s = 0.0;
          for (int q = 0; q < r.size(); ++q)
            s += r.weights[q] * std::pow(r.points[3 * q], a) * std::pow(r.points[3 * q + 1], b)
                 * std::pow(r.points[3 * q + 2], c);
          const double exact = fact(a) * fact(b) * fact(c) / fact(a + b + c + 3);
          EXPECT_NEAR(s, exact, 1e-15) << deg << " " << a << " " << b << " " << c;
        }
  }
  EXPECT_THROW(tetrahedron(-1), std::invalid_argument);
}

TEST(TriangleRule, RejectsNegativeDegree) { EXPECT_THROW(triangle(-1), std::invalid_argument); }

// Along a segment at distances r0 (t = 0) .. r1 (t = 1) from a tip on its
// line, r = r0 + (r1 - r0) t: int_0^1 r^(k + 1/2) dt and int_0^1 r^(k - 1/2)
// dt in closed form, with the tip on an end (r0 = 0), just beyond the
// near end (r0 = 1e-6) or far (plain Gauss is exact there only in the limit).
TEST(LineTowardTip, ExactForRootPowersOfTheDistance)
{
  const int n = 6;
  for (const auto& [r0, r1] : {std::pair{0.0, 1.0}, std::pair{1.0, 0.0}, std::pair{1e-6, 0.5},
                               std::pair{0.3, 2e-7}, std::pair{2.0, 3.0}})
  {
    const Rule rule = line_toward_tip(n, r0, r1);
    for (int k = 0; k <= n - 2; ++k) // 2 rho^(2k + 2) d rho: degree 2n - 2 <= 2n - 1
      for (const double half : {0.5, -0.5})
      {
        const double p = k + half;
        double s = 0.0;
        for (int q = 0; q < rule.size(); ++q)
          s += rule.weights[q] * std::pow(r0 + (r1 - r0) * rule.points[q], p);
        const double exact = (std::pow(r1, p + 1) - std::pow(r0, p + 1)) / ((p + 1) * (r1 - r0));
        EXPECT_NEAR(s, exact, 1e-12 * std::abs(exact)) << "r0=" << r0 << " r1=" << r1 << " p=" << p;
      }
  }
}

// Plain Gauss-Legendre misses the near-singular end by far more: the
// reason the graded rule exists (6 points, tip 1e-4 beyond the segment).
TEST(LineTowardTip, PlainGaussMissesTheNearSingularEnd)
{
  const Rule g = gauss_legendre(6);
  const double r0 = 1e-4, r1 = 1.0;
  double s = 0.0;
  for (int q = 0; q < g.size(); ++q)
    s += g.weights[q] / std::sqrt(r0 + (r1 - r0) * g.points[q]);
  const double exact = 2.0 * (std::sqrt(r1) - std::sqrt(r0)) / (r1 - r0);
  EXPECT_GT(std::abs(s - exact), 1e-3 * exact);
  EXPECT_EQ(line_toward_tip(6, 0.5, 0.5).points, g.points);
}

// One collapsed rule for every simplex: int over the reference simplex of
// prod x_k^a_k = prod a_k! / (sum a_k + dim)! (Dirichlet), in 1, 2 and 3
// dimensions, and the cached rule is the same object each time.
TEST(SimplexRule, ExactInEveryDimension)
{
  auto fact = [](int n) { double f = 1; for (int i = 2; i <= n; ++i) f *= i; return f; };
  for (int dim = 1; dim <= 3; ++dim)
    for (int deg = 0; deg <= 10; ++deg)
    {
      const Rule& r = simplex(dim, deg);
      EXPECT_EQ(&r, &simplex(dim, deg));
      EXPECT_EQ(r.dim, dim);
      int e[3] = {0, 0, 0};
      for (e[0] = 0; e[0] <= deg; ++e[0])
        for (e[1] = 0; e[1] <= (dim > 1 ? deg - e[0] : 0); ++e[1])
          for (e[2] = 0; e[2] <= (dim > 2 ? deg - e[0] - e[1] : 0); ++e[2])
          {
            double s = 0.0;
            for (int q = 0; q < r.size(); ++q)
            {
              double m = r.weights[q];
              for (int k = 0; k < dim; ++k)
                m *= std::pow(r.points[dim * q + k], e[k]);
              s += m;
            }
            EXPECT_NEAR(s, fact(e[0]) * fact(e[1]) * fact(e[2]) / fact(e[0] + e[1] + e[2] + dim), 1e-14)
                << "dim " << dim << " degree " << deg;
          }
    }
  EXPECT_THROW(simplex(4, 2), std::invalid_argument);
  EXPECT_THROW(simplex(2, -1), std::invalid_argument);
}
