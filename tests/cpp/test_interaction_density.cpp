// The interaction integral written once for any dimension
// (interaction_density.h): in 2D (a tip frame) it returns K_I, K_II of an
// exact Williams field on a ring, and in 3D (per-point front frames) the
// same plane field embedded in space gives the same two integrals and no
// mode III.
#include "fracture/interaction_integral_2d.h"
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

struct Ring
{
  std::vector<double> x, w, gq, gu;
  std::vector<std::int8_t> sides;
};

// The ring R1 < r < R2 around a tip at `tip` with crack direction angle a,
// q = (R2 - r) / (R2 - R1), and the exact field of (K_I, K_II).
Ring ring(std::array<double, 2> tip, double a, double KI, double KII)
{
  const double R1 = 0.2, R2 = 0.5;
  const TipFrame f{tip, {std::cos(a), std::sin(a)}, 1};
  const auto gr = quadrature::gauss_legendre(20), gt = quadrature::gauss_legendre(60);
  const double s = 1.0 / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi));
  Ring out;
  std::array<std::array<double, 2>, 2> U;
  std::array<std::array<std::array<double, 2>, 2>, 2> dU;
  for (int ir = 0; ir < gr.size(); ++ir)
    for (int it = 0; it < gt.size(); ++it)
    {
      const double r = R1 + (R2 - R1) * gr.points[ir], t = std::numbers::pi * (2.0 * gt.points[it] - 1.0);
      const double er[2] = {std::cos(a + t), std::sin(a + t)};
      const std::array<double, 2> p = {tip[0] + r * er[0], tip[1] + r * er[1]};
      out.x.insert(out.x.end(), p.begin(), p.end());
      out.w.push_back(gr.weights[ir] * (R2 - R1) * gt.weights[it] * 2.0 * std::numbers::pi * r);
      out.gq.insert(out.gq.end(), {-er[0] / (R2 - R1), -er[1] / (R2 - R1)});
      williams_displacement(f, p, 0, 3.0 - 4.0 * nu, U, dU);
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          out.gu.push_back(s * (KI * dU[0][i][j] + KII * dU[1][i][j]));
      out.sides.push_back(0);
    }
  return out;
}
} // namespace

TEST(InteractionIntegral, TwoDimensionsGiveKOfTheWilliamsField)
{
  const double a = 0.6, KI = 1.3, KII = -0.45;
  const Ring g = ring({0.1, -0.2}, a, KI, KII);
  const TipFrame f{{0.1, -0.2}, {std::cos(a), std::sin(a)}, 1};
  const auto I = interaction_integral(f, E, nu, g.x, g.w, g.gq, g.gu, g.sides);
  EXPECT_NEAR(0.5 * Eprime * I[0], KI, 1e-10);
  EXPECT_NEAR(0.5 * Eprime * I[1], KII, 1e-10);
}

TEST(InteractionIntegral, ThreeDimensionsGiveTheSamePlaneIntegrals)
{
  const double a = -0.35;
  const Ring g = ring({0.4, 0.3}, a, 0.8, 0.6);
  const std::size_t n = g.w.size();
  const TipFrame f{{0.4, 0.3}, {std::cos(a), std::sin(a)}, 1};
  const auto I2 = interaction_integral(f, E, nu, g.x, g.w, g.gq, g.gu, g.sides);
  // The same points in the plane z = 0, the front along z.
  const Point3 e1 = {std::cos(a), std::sin(a), 0.0}, e2 = {-std::sin(a), std::cos(a), 0.0}, e3 = {0.0, 0.0, 1.0};
  std::vector<double> frames, x3, gq3, gu3;
  for (std::size_t p = 0; p < n; ++p)
  {
    frames.insert(frames.end(), {0.4, 0.3, 0.0});
    frames.insert(frames.end(), e1.begin(), e1.end());
    frames.insert(frames.end(), e2.begin(), e2.end());
    frames.insert(frames.end(), e3.begin(), e3.end());
    x3.insert(x3.end(), {g.x[2 * p], g.x[2 * p + 1], 0.0});
    gq3.insert(gq3.end(), {g.gq[2 * p], g.gq[2 * p + 1], 0.0});
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        gu3.push_back(i < 2 and j < 2 ? g.gu[4 * p + 2 * i + j] : 0.0);
  }
  const auto I3 = interaction_integral_3d(E, nu, e1, frames, x3, g.w, gq3, gu3, g.sides);
  EXPECT_NEAR(I3[0], I2[0], 1e-12 * std::abs(I2[0]));
  EXPECT_NEAR(I3[1], I2[1], 1e-12 * std::abs(I2[1]));
  EXPECT_NEAR(I3[2], 0.0, 1e-14);
  EXPECT_NEAR(0.5 * Eprime * I3[0], 0.8, 1e-10);
  EXPECT_NEAR(0.5 * Eprime * I3[1], 0.6, 1e-10);
}
