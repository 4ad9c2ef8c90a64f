#include "enrichment/front_functions_3d.h"
#include "enrichment/williams_local.h"

#include <cmath>
#include <numbers>

namespace cracklip
{
namespace
{
/// Polar quantities of local coordinates and the global gradients of r and
/// theta: grad r = (x1 g1 + x2 g2) / r, grad theta = (x1 g2 - x2 g1) / r^2.
struct Polar3
{
  double r, theta, c, s;
  Point3 grad_r, grad_t;
};

Polar3 polar(const LocalCoordinates& lc, int side)
{
  Polar3 p;
  p.r = std::hypot(lc.x1, lc.x2);
  p.theta = front_angle(lc.x1, lc.x2, side);
  p.c = std::cos(p.theta);
  p.s = std::sin(p.theta);
  p.grad_r = {0.0, 0.0, 0.0};
  p.grad_t = {0.0, 0.0, 0.0};
  if (p.r > 0.0)
    for (int j = 0; j < 3; ++j)
    {
      p.grad_r[j] = (lc.x1 * lc.g1[j] + lc.x2 * lc.g2[j]) / p.r;
      p.grad_t[j] = (lc.x1 * lc.g2[j] - lc.x2 * lc.g1[j]) / (p.r * p.r);
    }
  return p;
}
} // namespace

LocalCoordinates frame_coordinates(const FrontFrame& f, const Point3& x)
{
  const double d[3] = {x[0] - f.origin[0], x[1] - f.origin[1], x[2] - f.origin[2]};
  LocalCoordinates lc;
  lc.x1 = f.e1[0] * d[0] + f.e1[1] * d[1] + f.e1[2] * d[2];
  lc.x2 = f.e2[0] * d[0] + f.e2[1] * d[1] + f.e2[2] * d[2];
  lc.g1 = f.e1;
  lc.g2 = f.e2;
  lc.e = {f.e1, f.e2, f.e3};
  for (auto& dk : lc.de)
    for (auto& row : dk)
      row = {0.0, 0.0, 0.0};
  return lc;
}

double front_angle(double x1, double x2, int side)
{
  const double t = std::atan2(x2, x1);
  if (side != 0 and x1 < 0.0)
    return side > 0 ? std::abs(t) : -std::abs(t);
  return t;
}

double continued_front_angle(double x1, double x2, int side)
{
  const double t = std::atan2(x2, x1);
  if (side > 0 and x1 < 0.0 and t < 0.0)
    return t + 2.0 * std::numbers::pi;
  if (side < 0 and x1 < 0.0 and t > 0.0)
    return t - 2.0 * std::numbers::pi;
  return t;
}

void front_vector_functions(const LocalCoordinates& lc, int side, double kappa, std::array<Point3, 3>& U,
                            std::array<std::array<Point3, 3>, 3>& dU)
{
  const Polar3 p = polar(lc, side);
  const double sr = std::sqrt(p.r);
  const WilliamsAngular w = williams_angular(std::sin(0.5 * p.theta), std::cos(0.5 * p.theta), p.c, p.s, kappa);
  for (int m = 0; m < 3; ++m)
  {
    // Local components u[k] = sqrt(r) h(theta) and their global gradients.
    double u[3];
    Point3 g[3];
    for (int k = 0; k < 3; ++k)
    {
      u[k] = sr * w.h[m][k];
      const double g_r = p.r > 0.0 ? 0.5 * w.h[m][k] / sr : 0.0, g_t = sr * w.ht[m][k];
      for (int j = 0; j < 3; ++j)
        g[k][j] = p.r > 0.0 ? g_r * p.grad_r[j] + g_t * p.grad_t[j] : 0.0;
    }
    // U = sum_k u_k e_k; grad U = sum_k (e_k (x) grad u_k + u_k grad e_k).
    for (int i = 0; i < 3; ++i)
    {
      U[m][i] = u[0] * lc.e[0][i] + u[1] * lc.e[1][i] + u[2] * lc.e[2][i];
      for (int j = 0; j < 3; ++j)
      {
        double v = 0.0;
        for (int k = 0; k < 3; ++k)
          v += lc.e[k][i] * g[k][j] + u[k] * lc.de[k][i][j];
        dU[m][i][j] = p.r > 0.0 ? v : 0.0;
      }
    }
  }
}

void front_branch_functions(const LocalCoordinates& lc, int side, std::array<double, 4>& F,
                            std::array<Point3, 4>& dF)
{
  const Polar3 p = polar(lc, side);
  const double sr = std::sqrt(p.r);
  const auto [h, ht] = branch_angular(std::sin(0.5 * p.theta), std::cos(0.5 * p.theta), p.c, p.s);
  for (int l = 0; l < 4; ++l)
  {
    F[l] = sr * h[l];
    for (int j = 0; j < 3; ++j)
      dF[l][j] = p.r > 0.0 ? 0.5 * h[l] / sr * p.grad_r[j] + sr * ht[l] * p.grad_t[j] : 0.0;
  }
}

void front_vector_functions(const FrontFrame& f, const Point3& x, int side, double kappa,
                            std::array<Point3, 3>& U, std::array<std::array<Point3, 3>, 3>& dU)
{
  front_vector_functions(frame_coordinates(f, x), side, kappa, U, dU);
}

void front_branch_functions(const FrontFrame& f, const Point3& x, int side, std::array<double, 4>& F,
                            std::array<Point3, 4>& dF)
{
  front_branch_functions(frame_coordinates(f, x), side, F, dF);
}

} // namespace cracklip
