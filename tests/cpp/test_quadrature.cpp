#include <quadrature.h>

#include <cmath>
#include <gtest/gtest.h>

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

TEST(TriangleRule, RejectsNegativeDegree) { EXPECT_THROW(triangle(-1), std::invalid_argument); }
