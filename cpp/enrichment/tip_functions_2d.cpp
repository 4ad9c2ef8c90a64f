#include "enrichment/tip_functions_2d.h"
#include "enrichment/williams_local.h"

#include <cmath>
#include <numbers>

namespace cracklip
{
namespace
{
/// Global gradient from polar derivatives g_r, g_t of a function of (r, t).
std::array<double, 2> polar_gradient(const TipFrame& f, const Polar& p, double g_r, double g_t)
{
  const auto [d1, d2] = polar_to_local(p.r, p.c, p.s, g_r, g_t);
  // x_loc = R (x - T), rows of R: e1, e2 = (-e1y, e1x); grad_glob = R^T grad_loc.
  const double e1x = f.e1[0], e1y = f.e1[1];
  return {e1x * d1 - e1y * d2, e1y * d1 + e1x * d2};
}
} // namespace

Polar tip_polar(const TipFrame& f, std::array<double, 2> x, int side)
{
  const double dx = x[0] - f.tip[0], dy = x[1] - f.tip[1];
  Polar p;
  p.x1 = f.e1[0] * dx + f.e1[1] * dy;
  p.x2 = -f.e1[1] * dx + f.e1[0] * dy;
  p.r = std::hypot(p.x1, p.x2);
  p.theta = std::atan2(p.x2, p.x1);
  if (side != 0 and p.x1 < 0.0)
    p.theta = side * f.orientation > 0 ? std::abs(p.theta) : -std::abs(p.theta);
  p.c = std::cos(p.theta);
  p.s = std::sin(p.theta);
  return p;
}

void branch_functions(const TipFrame& f, std::array<double, 2> x, int side,
                      std::array<double, 4>& F, std::array<std::array<double, 2>, 4>& dF)
{
  const Polar p = tip_polar(f, x, side);
  const double sr = std::sqrt(p.r);
  const double sh = std::sin(0.5 * p.theta), ch = std::cos(0.5 * p.theta);
  const auto [h, ht] = branch_angular(sh, ch, p.c, p.s);
  for (int l = 0; l < 4; ++l)
  {
    F[l] = sr * h[l];
    dF[l] = p.r > 0.0 ? polar_gradient(f, p, 0.5 * h[l] / sr, sr * ht[l])
                      : std::array<double, 2>{0.0, 0.0};
  }
}

void williams_displacement(const TipFrame& f, std::array<double, 2> x, int side, double kappa,
                           std::array<std::array<double, 2>, 2>& U,
                           std::array<std::array<std::array<double, 2>, 2>, 2>& dU)
{
  const Polar p = tip_polar(f, x, side);
  const double sr = std::sqrt(p.r);
  const double sh = std::sin(0.5 * p.theta), ch = std::cos(0.5 * p.theta);
  // h[m][k]: angular part of local component k of mode m, ht its derivative.
  const WilliamsAngular w = williams_angular(sh, ch, p.c, p.s, kappa);
  const auto& h = w.h;
  const auto& ht = w.ht;
  const double e1x = f.e1[0], e1y = f.e1[1];
  for (int m = 0; m < 2; ++m)
  {
    // Local components and their global gradients.
    const double u1 = sr * h[m][0], u2 = sr * h[m][1];
    std::array<double, 2> g1 = {0.0, 0.0}, g2 = {0.0, 0.0};
    if (p.r > 0.0)
    {
      g1 = polar_gradient(f, p, 0.5 * h[m][0] / sr, sr * ht[m][0]);
      g2 = polar_gradient(f, p, 0.5 * h[m][1] / sr, sr * ht[m][1]);
    }
    // Global vector: u1 e1 + u2 e2, e2 = (-e1y, e1x).
    U[m] = {u1 * e1x - u2 * e1y, u1 * e1y + u2 * e1x};
    for (int j = 0; j < 2; ++j)
    {
      dU[m][0][j] = g1[j] * e1x - g2[j] * e1y;
      dU[m][1][j] = g1[j] * e1y + g2[j] * e1x;
    }
  }
}

} // namespace cracklip
