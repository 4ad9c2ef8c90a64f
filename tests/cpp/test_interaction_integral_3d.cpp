// The 3D interaction integral on exact straight-front fields: it returns
// the K of each mode, whatever the mix, on a ring domain and with a hat
// along the front.
#include "fracture/interaction_integral_3d.h"
#include "quadrature/rules.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

using namespace cracklip;

namespace
{
constexpr double E = 2.0, nu = 0.3;
const double mu = E / (2.0 * (1.0 + nu)), Eprime = E / (1.0 - nu * nu);

FrontFrame oblique()
{
  const double a = 0.4, b = 0.9;
  const Point3 e1 = {std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b)};
  Point3 e2 = {-std::sin(a), std::cos(a), 0.0};
  const Point3 e3 = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return {{0.2, -0.1, 0.3}, e1, e2, e3};
}

// The exact field u = sum_m K_m U_m / (2 mu sqrt(2 pi)): its gradient at x.
std::array<std::array<double, 3>, 3> exact_gradient(const FrontFrame& f, const Point3& x, const double K[3])
{
  std::array<Point3, 3> U;
  std::array<std::array<Point3, 3>, 3> dU;
  front_vector_functions(f, x, 0, 3.0 - 4.0 * nu, U, dU);
  const double s = 1.0 / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi));
  std::array<std::array<double, 3>, 3> g{};
  for (int m = 0; m < 3; ++m)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        g[i][j] += K[m] * s * dU[m][i][j];
  return g;
}

// Points of a tensor Gauss rule on r in [r0, r1], theta in (-pi, pi), x3 in
// [-l, l] around the front, with q = q_r(r) q_s(x3): q_r = 1 below R1, linear
// to 0 at R2; q_s = 1 (hat = false) or 1 - |x3| / l (hat = true).
std::array<double, 3> integrate(const FrontFrame& f, const double K[3], double R1, double R2, double l, bool hat)
{
  const auto gr = quadrature::gauss_legendre(24), gt = quadrature::gauss_legendre(48), gz = quadrature::gauss_legendre(8);
  std::vector<double> frames, x, w, gq, gu;
  std::vector<std::int8_t> sides;
  // r in [R1, R2] (the ring), and for the hat also [0, R1] (q_r = 1 there):
  // one rule per piece where q is smooth; the hat's kink at x3 = 0 splits z.
  std::vector<std::array<double, 2>> pieces = {{R1, R2}};
  if (hat)
    pieces.push_back({0.0, R1});
  for (const auto& [r0, r1] : pieces)
    for (int half = 0; half < (hat ? 2 : 1); ++half)
      for (int ir = 0; ir < gr.size(); ++ir)
        for (int it = 0; it < gt.size(); ++it)
          for (int iz = 0; iz < gz.size(); ++iz)
          {
            const double r = r0 + (r1 - r0) * gr.points[ir];
            const double t = std::numbers::pi * (2.0 * gt.points[it] - 1.0);
            const double z = hat ? (half == 0 ? -l + l * gz.points[iz] : l * gz.points[iz])
                                 : -l + 2 * l * gz.points[iz];
            const double dz = hat ? l : 2 * l;
            const double weight = gr.weights[ir] * (r1 - r0) * gt.weights[it] * 2 * std::numbers::pi
                                  * gz.weights[iz] * dz * r;
            const double x1 = r * std::cos(t), x2 = r * std::sin(t);
            Point3 p;
            for (int i = 0; i < 3; ++i)
              p[i] = f.origin[i] + x1 * f.e1[i] + x2 * f.e2[i] + z * f.e3[i];
            const double qr = r < R1 ? 1.0 : (R2 - r) / (R2 - R1), dqr = r < R1 ? 0.0 : -1.0 / (R2 - R1);
            const double qs = hat ? 1.0 - std::abs(z) / l : 1.0, dqs = hat ? (z < 0 ? 1.0 / l : -1.0 / l) : 0.0;
            for (int i = 0; i < 3; ++i)
              gq.push_back(dqr * qs * (std::cos(t) * f.e1[i] + std::sin(t) * f.e2[i]) + qr * dqs * f.e3[i]);
            const auto g = exact_gradient(f, p, K);
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                gu.push_back(g[i][j]);
            for (const auto& v : {f.origin, f.e1, f.e2, f.e3})
              frames.insert(frames.end(), v.begin(), v.end());
            x.insert(x.end(), p.begin(), p.end());
            w.push_back(weight);
            sides.push_back(0);
          }
  return interaction_integral_3d(E, nu, f.e1, frames, x, w, gq, gu, sides);
}
} // namespace

TEST(InteractionIntegral3D, RingDomainGivesEachK)
{
  const FrontFrame f = oblique();
  const double K[3] = {1.3, -0.7, 0.4};
  const double l = 0.25;
  const auto I = integrate(f, K, 0.1, 0.3, l, false);
  const double weight = 2 * l; // int q_s ds
  EXPECT_NEAR(0.5 * Eprime * I[0] / weight, K[0], 1e-10);
  EXPECT_NEAR(0.5 * Eprime * I[1] / weight, K[1], 1e-10);
  EXPECT_NEAR(mu * I[2] / weight, K[2], 1e-10);
}

TEST(InteractionIntegral3D, HatAlongTheFrontGivesEachK)
{
  // q_s = 1 - |x3| / l: q varies along the front too, and the integral runs
  // down to the front (r from 0, where the integrand ~ 1/r times r dr).
  const FrontFrame f = oblique();
  for (const auto& K : {std::array<double, 3>{1.0, 0.0, 0.0}, std::array<double, 3>{0.0, 1.0, 0.0},
                        std::array<double, 3>{0.0, 0.0, 1.0}, std::array<double, 3>{0.6, -0.2, 0.9}})
  {
    const double l = 0.2;
    const auto I = integrate(f, K.data(), 0.1, 0.3, l, true);
    const double weight = l; // int (1 - |s| / l) ds over [-l, l]
    EXPECT_NEAR(0.5 * Eprime * I[0] / weight, K[0], 1e-10);
    EXPECT_NEAR(0.5 * Eprime * I[1] / weight, K[1], 1e-10);
    EXPECT_NEAR(mu * I[2] / weight, K[2], 1e-10);
  }
}
