#include "quadrature/cell_quadrature_2d.h"
#include "quadrature/rules.h"
#include "enrichment/tip_functions_2d.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>

using namespace cracklip;

namespace
{
// An inclined tip frame.
const TipFrame frame{{0.3, -0.2}, {std::cos(0.7), std::sin(0.7)}};
constexpr double kappa = 1.8; // nu = 0.3, plane strain
constexpr double E = 1.0, nu = 0.3;

std::array<double, 2> at(double r, double t)
{
  const double c = std::cos(t), s = std::sin(t);
  const double x1 = r * c, x2 = r * s;
  return {frame.tip[0] + frame.e1[0] * x1 - frame.e1[1] * x2,
          frame.tip[1] + frame.e1[1] * x1 + frame.e1[0] * x2};
}

// Plane-strain stress (xx, yy, xy) from a displacement gradient.
std::array<double, 3> stress(const std::array<std::array<double, 2>, 2>& g)
{
  const double lmbda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const double tr = g[0][0] + g[1][1];
  return {lmbda * tr + 2 * mu * g[0][0], lmbda * tr + 2 * mu * g[1][1], mu * (g[0][1] + g[1][0])};
}

std::array<double, 3> williams_stress(int mode, std::array<double, 2> x, int side)
{
  std::array<std::array<double, 2>, 2> U;
  std::array<std::array<std::array<double, 2>, 2>, 2> dU;
  williams_displacement(frame, x, side, kappa, U, dU);
  return stress(dU[mode]);
}
} // namespace

TEST(TipFunctions, GradientsMatchFiniteDifferences)
{
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> ur(0.05, 1.0), ut(-3.0, 3.0);
  for (int k = 0; k < 50; ++k)
  {
    const auto x = at(ur(gen), ut(gen));
    const double h = 1e-6;
    std::array<double, 4> F, Fp, Fm;
    std::array<std::array<double, 2>, 4> dF, tmp;
    branch_functions(frame, x, 0, F, dF);
    std::array<std::array<double, 2>, 2> U, Up, Um;
    std::array<std::array<std::array<double, 2>, 2>, 2> dU, tmpU;
    williams_displacement(frame, x, 0, kappa, U, dU);
    for (int j = 0; j < 2; ++j)
    {
      auto xp = x, xm = x;
      xp[j] += h;
      xm[j] -= h;
      branch_functions(frame, xp, 0, Fp, tmp);
      branch_functions(frame, xm, 0, Fm, tmp);
      for (int l = 0; l < 4; ++l)
      {
        const double fd = (Fp[l] - Fm[l]) / (2 * h);
        EXPECT_NEAR(dF[l][j], fd, 1e-7 * std::max(1.0, std::abs(dF[l][j]))) << "F" << l;
      }
      williams_displacement(frame, xp, 0, kappa, Up, tmpU);
      williams_displacement(frame, xm, 0, kappa, Um, tmpU);
      for (int m = 0; m < 2; ++m)
        for (int i = 0; i < 2; ++i)
        {
          const double fd = (Up[m][i] - Um[m][i]) / (2 * h);
          EXPECT_NEAR(dU[m][i][j], fd, 1e-7 * std::max(1.0, std::abs(dU[m][i][j]))) << "U" << m;
        }
    }
  }
}

// The two linear identities that make P1 x {F1..F4} linearly dependent under
// a partition of unity (the reason the corrected scheme drops F1, F2 at one
// node per tip): x2 F1 + x1 F3 - x2 F4 = 0 and x2 F2 - x2 F3 - x1 F4 = 0,
// (x1, x2) in the tip frame, on both lips too.
TEST(TipFunctions, BranchFunctionIdentities)
{
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> rr(1e-3, 2.0), tt(-std::numbers::pi, std::numbers::pi);
  for (int k = 0; k < 200; ++k)
  {
    const double r = rr(gen), t = k < 2 ? (k == 0 ? std::numbers::pi : -std::numbers::pi) : tt(gen);
    const double x1 = r * std::cos(t), x2 = r * std::sin(t);
    std::array<double, 4> F;
    std::array<std::array<double, 2>, 4> dF;
    branch_functions(frame, at(r, t), t >= 0.0 ? 1 : -1, F, dF);
    EXPECT_NEAR(x2 * F[0] + x1 * F[2] - x2 * F[3], 0.0, 1e-14 * std::pow(r, 1.5));
    EXPECT_NEAR(x2 * F[1] - x2 * F[2] - x1 * F[3], 0.0, 1e-14 * std::pow(r, 1.5));
  }
}

TEST(TipFunctions, WilliamsFieldsAreTractionFreeOnTheLips)
{
  // Lip normal e2 = e1 rotated by +90 degrees; traction sigma . e2.
  const double n[2] = {-frame.e1[1], frame.e1[0]};
  for (int mode = 0; mode < 2; ++mode)
    for (int side : {1, -1})
      for (double r : {0.01, 0.3, 2.0})
      {
        // A point on the crack line behind the tip, evaluated on each lip.
        const auto x = at(r, std::numbers::pi);
        const auto s = williams_stress(mode, x, side);
        const double tx = s[0] * n[0] + s[2] * n[1], ty = s[2] * n[0] + s[1] * n[1];
        const double scale = std::abs(s[0]) + std::abs(s[1]) + std::abs(s[2]) + 1.0 / std::sqrt(r);
        EXPECT_NEAR(tx, 0.0, 1e-13 * scale) << mode << " " << side << " " << r;
        EXPECT_NEAR(ty, 0.0, 1e-13 * scale) << mode << " " << side << " " << r;
      }
}

TEST(TipFunctions, WilliamsStressIsDivergenceFree)
{
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> ur(0.1, 1.0), ut(-3.0, 3.0);
  for (int mode = 0; mode < 2; ++mode)
    for (int k = 0; k < 30; ++k)
    {
      const double r = ur(gen);
      const auto x = at(r, ut(gen));
      const double h = 1e-5 * r;
      auto shifted = [&](int j, double d)
      {
        auto y = x;
        y[j] += d;
        return williams_stress(mode, y, 0);
      };
      const auto sxp = shifted(0, h), sxm = shifted(0, -h), syp = shifted(1, h), sym = shifted(1, -h);
      const double divx = (sxp[0] - sxm[0]) / (2 * h) + (syp[2] - sym[2]) / (2 * h);
      const double divy = (sxp[2] - sxm[2]) / (2 * h) + (syp[1] - sym[1]) / (2 * h);
      // Stress ~ r^-1/2, its derivatives ~ r^-3/2: relative check.
      const double scale = std::pow(r, -1.5);
      EXPECT_NEAR(divx, 0.0, 1e-6 * scale);
      EXPECT_NEAR(divy, 0.0, 1e-6 * scale);
    }
}

TEST(TipFunctions, WilliamsModeIMatchesClosedFormStress)
{
  // sigma_22 ahead of the tip (theta = 0) is K / sqrt(2 pi r) for K = 1,
  // i.e. the stress of U / (2 mu sqrt(2 pi)).
  const double mu = E / (2 * (1 + nu));
  for (double r : {0.01, 0.5})
  {
    const auto s = williams_stress(0, at(r, 0.0), 0);
    // Rotate to the tip frame: sigma_22 = n . sigma n with n = e2.
    const double n[2] = {-frame.e1[1], frame.e1[0]};
    const double s22 = s[0] * n[0] * n[0] + 2 * s[2] * n[0] * n[1] + s[1] * n[1] * n[1];
    EXPECT_NEAR(s22 / (2 * mu * std::sqrt(2 * std::numbers::pi)), 1.0 / std::sqrt(2 * std::numbers::pi * r), 1e-12 / std::sqrt(r));
  }
}

TEST(TipFan, IntegratesInverseDistanceOverATipCell)
{
  // A tip T inside a triangle: int 1 / (4 r) over it is the sum over its edges
  // AB of |TAB| / (2 L) (asinh((s0 + L) / d) - asinh(s0 / d)) (polar fan).
  const Point2 T = {0.31, 0.22};
  const std::vector<Point2> tri = {{0.0, 0.0}, {1.0, 0.1}, {0.2, 0.9}};
  double exact = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const Point2 A = {tri[k][0] - T[0], tri[k][1] - T[1]};
    const Point2 B = {tri[(k + 1) % 3][0] - T[0], tri[(k + 1) % 3][1] - T[1]};
    const double area = 0.5 * std::abs(A[0] * B[1] - A[1] * B[0]);
    const double dx = B[0] - A[0], dy = B[1] - A[1], L = std::hypot(dx, dy);
    const double s0 = (A[0] * dx + A[1] * dy) / L, d = std::abs(A[0] * dy - A[1] * dx) / L;
    exact += 0.5 * area / L * (std::asinh((s0 + L) / d) - std::asinh(s0 / d));
  }
  QuadratureOptions opt;
  opt.tip_radial = 1; // the fan's rho cancels 1/r: one point along each ray is exact
  opt.tip_angular = 8;
  opt.tip_max_angle = 0.8;
  const auto fans = fan_triangles(T, tri, opt.tip_max_angle);
  std::vector<double> pts, w;
  fan_rule(fans, opt, pts, w);
  double s = 0.0;
  for (std::size_t q = 0; q < w.size(); ++q)
    s += w[q] / (4.0 * std::hypot(pts[2 * q] - T[0], pts[2 * q + 1] - T[1]));
  EXPECT_LE(w.size(), 100u);
  EXPECT_NEAR(s, exact, 1e-12 * exact);
}
