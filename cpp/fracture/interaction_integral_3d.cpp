#include "fracture/interaction_integral_3d.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cracklip
{
namespace
{
FrontFrame frame_at(std::span<const double> frames, std::size_t p)
{
  const double* f = &frames[12 * p];
  return {{f[0], f[1], f[2]}, {f[3], f[4], f[5]}, {f[6], f[7], f[8]}, {f[9], f[10], f[11]}};
}
} // namespace

std::array<double, 3> interaction_integral_3d(double E, double nu, const Point3& d, std::span<const double> frames,
                                              std::span<const double> x, std::span<const double> weights,
                                              std::span<const double> grad_q, std::span<const double> grad_u,
                                              std::span<const std::int8_t> sides)
{
  const std::size_t n = weights.size();
  if (frames.size() != 12 * n or x.size() != 3 * n or grad_q.size() != 3 * n or grad_u.size() != 9 * n
      or sides.size() != n)
    throw std::invalid_argument("interaction_integral_3d: expected frames (n, 12), x (n, 3), weights (n), "
                                "grad_q (n, 3), grad_u (n, 3, 3), sides (n)");
  if (!(E > 0.0) or !(nu > -1.0 and nu < 0.5))
    throw std::invalid_argument("interaction_integral_3d: needs E > 0 and -1 < nu < 0.5");
  const double mu = E / (2.0 * (1.0 + nu)), lmbda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double kappa = 3.0 - 4.0 * nu;
  const double scale = 1.0 / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi));
  auto stress = [&](const double g[3][3], double s[3][3])
  {
    const double tr = g[0][0] + g[1][1] + g[2][2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        s[i][j] = mu * (g[i][j] + g[j][i]) + (i == j ? lmbda * tr : 0.0);
  };
  std::array<double, 3> I = {0.0, 0.0, 0.0};
  std::array<Point3, 3> U;
  std::array<std::array<Point3, 3>, 3> dU;
  for (std::size_t p = 0; p < n; ++p)
  {
    const double gq[3] = {grad_q[3 * p], grad_q[3 * p + 1], grad_q[3 * p + 2]};
    if (gq[0] == 0.0 and gq[1] == 0.0 and gq[2] == 0.0)
      continue;
    double gu[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        gu[i][j] = grad_u[9 * p + 3 * i + j];
    double sig[3][3];
    stress(gu, sig);
    front_vector_functions(frame_at(frames, p), {x[3 * p], x[3 * p + 1], x[3 * p + 2]}, sides[p], kappa, U, dU);
    const double dq = d[0] * gq[0] + d[1] * gq[1] + d[2] * gq[2];
    for (int m = 0; m < 3; ++m)
    {
      double ga[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          ga[i][j] = scale * dU[m][i][j];
      double siga[3][3];
      stress(ga, siga);
      double t1 = 0.0, t2 = 0.0, w = 0.0;
      for (int i = 0; i < 3; ++i)
      {
        const double ua = ga[i][0] * d[0] + ga[i][1] * d[1] + ga[i][2] * d[2]; // (grad u_aux d)_i
        const double ud = gu[i][0] * d[0] + gu[i][1] * d[1] + gu[i][2] * d[2];
        t1 += (sig[i][0] * gq[0] + sig[i][1] * gq[1] + sig[i][2] * gq[2]) * ua;
        t2 += (siga[i][0] * gq[0] + siga[i][1] * gq[1] + siga[i][2] * gq[2]) * ud;
        for (int j = 0; j < 3; ++j)
          w += sig[i][j] * 0.5 * (ga[i][j] + ga[j][i]);
      }
      I[m] += weights[p] * (t1 + t2 - w * dq);
    }
  }
  return I;
}

void aux_derivative_3d(double E, double nu, const Point3& d, std::span<const double> frames,
                       std::span<const double> x, std::span<const std::int8_t> sides, std::span<double> out)
{
  const std::size_t n = sides.size();
  if (frames.size() != 12 * n or x.size() != 3 * n or out.size() != 9 * n)
    throw std::invalid_argument("aux_derivative_3d: expected frames (n, 12), x (n, 3), sides (n), out (n, 3, 3)");
  const double mu = E / (2.0 * (1.0 + nu));
  const double kappa = 3.0 - 4.0 * nu;
  const double scale = 1.0 / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi));
  std::array<Point3, 3> U;
  std::array<std::array<Point3, 3>, 3> dU;
  for (std::size_t p = 0; p < n; ++p)
  {
    front_vector_functions(frame_at(frames, p), {x[3 * p], x[3 * p + 1], x[3 * p + 2]}, sides[p], kappa, U, dU);
    for (int m = 0; m < 3; ++m)
      for (int i = 0; i < 3; ++i)
        out[9 * p + 3 * m + i] = scale * (dU[m][i][0] * d[0] + dU[m][i][1] * d[1] + dU[m][i][2] * d[2]);
  }
}

} // namespace cracklip
