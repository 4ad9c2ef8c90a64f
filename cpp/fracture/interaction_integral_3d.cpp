#include "fracture/interaction_integral_3d.h"

#include "fracture/interaction_density.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
FrontFrame frame_at(std::span<const double> frames, std::size_t p)
{
  const double* f = &frames[12 * p];
  return {{f[0], f[1], f[2]}, {f[3], f[4], f[5]}, {f[6], f[7], f[8]}, {f[9], f[10], f[11]}};
}

/// The unit-K auxiliary fields of one point (header of auxiliary_fields_3d).
struct AuxPoint
{
  double U[3][3], G[3][3][3], local[3][3], div[3][3];
};

using Elasticity = IsotropicElasticity<3>;

void aux_point(const Elasticity& el, const FrontFrame& f, double curvature, const Point3& x, int side, AuxPoint& a)
{
  const LocalCoordinates lc = frame_coordinates(f, x);
  std::array<Point3, 3> Uf;
  std::array<std::array<Point3, 3>, 3> dUf;
  front_vector_functions(lc, side, el.kappa, Uf, dUf);
  const double h = 1.0 + curvature * lc.x1;
  if (!(h > 0.05))
    throw std::invalid_argument("interaction integral: a point lies beyond the centre of curvature of its front "
                                "point (1 + kappa x1 = " + std::to_string(h) + "): the domain is too large for "
                                "the front's curvature");
  const double ir = curvature / h; // 1 / R
  const Point3* e[3] = {&f.e1, &f.e2, &f.e3};
  for (int m = 0; m < 3; ++m)
  {
    double d1[3], d2[3]; // u_k,1 and u_k,2
    for (int k = 0; k < 3; ++k)
    {
      a.U[m][k] = el.scale * Uf[m][k];
      double l = 0.0, g1 = 0.0, g2 = 0.0;
      for (int i = 0; i < 3; ++i)
      {
        l += el.scale * Uf[m][i] * (*e[k])[i];
        for (int j = 0; j < 3; ++j)
        {
          const double v = el.scale * dUf[m][i][j] * (*e[k])[i];
          g1 += v * f.e1[j];
          g2 += v * f.e2[j];
        }
      }
      a.local[m][k] = l, d1[k] = g1, d2[k] = g2;
    }
    const double u1 = a.local[m][0], u3 = a.local[m][2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        a.G[m][i][j] = el.scale * dUf[m][i][j] + ir * (u1 * f.e3[i] - u3 * f.e1[i]) * f.e3[j];
    const double dR = (el.lmbda + 2.0 * el.mu) * (d1[0] - u1 * ir) * ir;
    const double dz = (el.mu * d1[1] + (el.lmbda + el.mu) * d2[0]) * ir;
    const double d3 = el.mu * (d1[2] - u3 * ir) * ir;
    for (int i = 0; i < 3; ++i)
      a.div[m][i] = dR * f.e1[i] + dz * f.e2[i] + d3 * f.e3[i];
  }
}

/// aux_point at every point p (frames (n, 12), curvature (n), x (n, 3),
/// sides (n)), then f(p, fields).
template <typename F>
void for_each_aux_point(const Elasticity& el, std::span<const double> frames, std::span<const double> curvature,
                        std::span<const double> x, std::span<const std::int8_t> sides, F&& f)
{
  AuxPoint a;
  for (std::size_t p = 0; p < sides.size(); ++p)
  {
    aux_point(el, frame_at(frames, p), curvature[p], {x[3 * p], x[3 * p + 1], x[3 * p + 2]}, sides[p], a);
    f(p, a);
  }
}
} // namespace

void auxiliary_fields_3d(double E, double nu, std::span<const double> frames, std::span<const double> curvature,
                         std::span<const double> x, std::span<const std::int8_t> sides, std::span<double> U,
                         std::span<double> G, std::span<double> local, std::span<double> div_sigma)
{
  const std::size_t n = sides.size();
  if (frames.size() != 12 * n or curvature.size() != n or x.size() != 3 * n or U.size() != 9 * n
      or G.size() != 27 * n or local.size() != 9 * n or div_sigma.size() != 9 * n)
    throw std::invalid_argument("auxiliary_fields_3d: expected frames (n, 12), curvature (n), x (n, 3), sides (n), "
                                "U (n, 3, 3), G (n, 3, 3, 3), local (n, 3, 3), div_sigma (n, 3, 3)");
  const Elasticity el(E, nu, "auxiliary_fields_3d");
  for_each_aux_point(el, frames, curvature, x, sides,
                     [&](std::size_t p, const AuxPoint& a)
                     {
                       for (int m = 0; m < 3; ++m)
                         for (int i = 0; i < 3; ++i)
                         {
                           U[9 * p + 3 * m + i] = a.U[m][i];
                           local[9 * p + 3 * m + i] = a.local[m][i];
                           div_sigma[9 * p + 3 * m + i] = a.div[m][i];
                           for (int j = 0; j < 3; ++j)
                             G[27 * p + 9 * m + 3 * i + j] = a.G[m][i][j];
                         }
                     });
}

void interaction_integrand_3d(double E, double nu, std::span<const double> frames, std::span<const double> curvature,
                              std::span<const double> x, std::span<const double> grad_u,
                              std::span<const std::int8_t> sides, std::span<const double> body, std::span<double> T,
                              std::span<double> D)
{
  const std::size_t n = sides.size();
  if (frames.size() != 12 * n or curvature.size() != n or x.size() != 3 * n or grad_u.size() != 9 * n
      or T.size() != 27 * n or D.size() != 9 * n or (!body.empty() and body.size() != 3))
    throw std::invalid_argument("interaction_integrand_3d: expected frames (n, 12), curvature (n), x (n, 3), "
                                "grad_u (n, 3, 3), sides (n), body (3) or empty, T (n, 3, 3, 3), D (n, 3, 3)");
  const Elasticity el(E, nu, "interaction_integrand_3d");
  const auto integrand = [&](std::size_t p, const AuxPoint& a)
  {
    double g[3][3], sig[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        g[i][j] = grad_u[9 * p + 3 * i + j];
    el.stress(g, sig);
    for (int m = 0; m < 3; ++m)
    {
      const auto& Ga = a.G[m];
      double siga[3][3];
      el.stress(Ga, siga);
      double W = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          W += sig[i][j] * 0.5 * (Ga[i][j] + Ga[j][i]);
      for (int j = 0; j < 3; ++j)
        for (int l = 0; l < 3; ++l)
        {
          double v = j == l ? -W : 0.0;
          for (int i = 0; i < 3; ++i)
            v += sig[i][j] * Ga[i][l] + siga[i][j] * g[i][l];
          T[27 * p + 9 * m + 3 * j + l] = v;
        }
      for (int l = 0; l < 3; ++l)
      {
        double v = 0.0;
        for (int i = 0; i < 3; ++i)
          v += a.div[m][i] * g[i][l] - (body.empty() ? 0.0 : body[i] * Ga[i][l]);
        D[9 * p + 3 * m + l] = v;
      }
    }
  };
  for_each_aux_point(el, frames, curvature, x, sides, integrand);
}

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
  const Elasticity el(E, nu, "interaction_integral_3d");
  std::array<Point3, 3> U;
  const auto aux = [&](std::size_t p, std::array<std::array<Point3, 3>, 3>& dU)
  { front_vector_functions(frame_at(frames, p), {x[3 * p], x[3 * p + 1], x[3 * p + 2]}, sides[p], el.kappa, U, dU); };
  return interaction_sum<3>(el, d.data(), weights, grad_q, grad_u, aux);
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
