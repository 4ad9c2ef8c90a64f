#include "enrichment/front_functions_3d.h"
#include "enrichment/williams_local.h"

#include <cmath>

namespace cracklip
{
namespace
{
/// Global gradient of a function of (r, theta) with polar derivatives g_r, g_t
/// (and no dependence on x3).
Point3 global_gradient(const FrontFrame& f, const FrontPolar& p, double g_r, double g_t)
{
  const auto [d1, d2] = polar_to_local(p.r, p.c, p.s, g_r, g_t);
  return {d1 * f.e1[0] + d2 * f.e2[0], d1 * f.e1[1] + d2 * f.e2[1], d1 * f.e1[2] + d2 * f.e2[2]};
}
} // namespace

FrontPolar front_polar(const FrontFrame& f, const Point3& x, int side)
{
  const double d[3] = {x[0] - f.origin[0], x[1] - f.origin[1], x[2] - f.origin[2]};
  FrontPolar p;
  p.x1 = f.e1[0] * d[0] + f.e1[1] * d[1] + f.e1[2] * d[2];
  p.x2 = f.e2[0] * d[0] + f.e2[1] * d[1] + f.e2[2] * d[2];
  p.x3 = f.e3[0] * d[0] + f.e3[1] * d[1] + f.e3[2] * d[2];
  p.r = std::hypot(p.x1, p.x2);
  p.theta = std::atan2(p.x2, p.x1);
  if (side != 0 and p.x1 < 0.0)
    p.theta = side > 0 ? std::abs(p.theta) : -std::abs(p.theta);
  p.c = std::cos(p.theta);
  p.s = std::sin(p.theta);
  return p;
}

void front_vector_functions(const FrontFrame& f, const Point3& x, int side, double kappa,
                            std::array<Point3, 3>& U, std::array<std::array<Point3, 3>, 3>& dU)
{
  const FrontPolar p = front_polar(f, x, side);
  const double sr = std::sqrt(p.r);
  const WilliamsAngular w = williams_angular(std::sin(0.5 * p.theta), std::cos(0.5 * p.theta), p.c, p.s, kappa);
  const Point3* e[3] = {&f.e1, &f.e2, &f.e3};
  for (int m = 0; m < 3; ++m)
  {
    // Local components k and their global gradients g[k].
    double u[3];
    Point3 g[3];
    for (int k = 0; k < 3; ++k)
    {
      u[k] = sr * w.h[m][k];
      g[k] = p.r > 0.0 ? global_gradient(f, p, 0.5 * w.h[m][k] / sr, sr * w.ht[m][k]) : Point3{0.0, 0.0, 0.0};
    }
    for (int i = 0; i < 3; ++i)
    {
      U[m][i] = u[0] * (*e[0])[i] + u[1] * (*e[1])[i] + u[2] * (*e[2])[i];
      for (int j = 0; j < 3; ++j)
        dU[m][i][j] = g[0][j] * (*e[0])[i] + g[1][j] * (*e[1])[i] + g[2][j] * (*e[2])[i];
    }
  }
}

void front_branch_functions(const FrontFrame& f, const Point3& x, int side, std::array<double, 4>& F,
                            std::array<Point3, 4>& dF)
{
  const FrontPolar p = front_polar(f, x, side);
  const double sr = std::sqrt(p.r);
  const auto [h, ht] = branch_angular(std::sin(0.5 * p.theta), std::cos(0.5 * p.theta), p.c, p.s);
  for (int l = 0; l < 4; ++l)
  {
    F[l] = sr * h[l];
    dF[l] = p.r > 0.0 ? global_gradient(f, p, 0.5 * h[l] / sr, sr * ht[l]) : Point3{0.0, 0.0, 0.0};
  }
}

} // namespace cracklip
