#include "fracture/interaction_integral_3d.h"

#include "fracture/interaction_density.h"

#include "enrichment/williams_local.h"

#include <algorithm>
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

FrontCurvatures curvatures_at(std::span<const double> curvatures, std::size_t p)
{
  const double* k = &curvatures[4 * p];
  return {k[0], k[1], k[2], k[3]};
}

/// The field at tube coordinates (x1, x2) of a front point, in the frame's
/// components (e1, e2, e3): U[m][a], G[m][a][b] = e_a . grad u e_b, and the
/// derivatives of U[m][a] in the surface-following (xi1, xi2) (header).
/// h = 1 + kappa_f x1 - kappa_33 x2 > 0.
struct LocalAux
{
  double U[3][3], G[3][3][3], dxi[3][3][2];
};

void local_aux(const Elasticity& el, const FrontCurvatures& k, double x1, double x2, int side, LocalAux& a)
{
  const double h = 1.0 + k.front * x1 - k.along * x2;
  const double xi1 = x1, xi2 = x2 - 0.5 * k.across * x1 * x1;
  // Gradients of x1, xi2 and s in the frame's components.
  const double g1[3] = {1.0, 0.0, k.torsion * x2 / h};
  const double gx2[3] = {0.0, 1.0, -k.torsion * x1 / h};
  double g2[3];
  for (int j = 0; j < 3; ++j)
    g2[j] = gx2[j] - k.across * x1 * g1[j];
  const double r = std::hypot(xi1, xi2);
  const double t = continued_front_angle(xi1, xi2, side);
  const double c = std::cos(t), s = std::sin(t);
  const WilliamsAngular w = williams_angular(std::sin(0.5 * t), std::cos(0.5 * t), c, s, el.kappa);
  const double sr = std::sqrt(r);
  for (int m = 0; m < 3; ++m)
  {
    for (int i = 0; i < 3; ++i)
    {
      a.U[m][i] = el.scale * sr * w.h[m][i];
      const auto d = r > 0.0 ? polar_to_local(r, c, s, el.scale * 0.5 * w.h[m][i] / sr, el.scale * sr * w.ht[m][i])
                             : std::array<double, 2>{0.0, 0.0};
      a.dxi[m][i][0] = d[0], a.dxi[m][i][1] = d[1];
    }
    // u_k e_k' (x) grad s: e1' = kf e3 + tau e2, e2' = -k33 e3 - tau e1,
    // e3' = -kf e1 + k33 e2, grad s = e3 / h.
    const double* u = a.U[m];
    const double hoop[3] = {-k.torsion * u[1] - k.front * u[2], k.torsion * u[0] + k.along * u[2],
                            k.front * u[0] - k.along * u[1]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        a.G[m][i][j] = r > 0.0 ? a.dxi[m][i][0] * g1[j] + a.dxi[m][i][1] * g2[j] + (j == 2 ? hoop[i] / h : 0.0)
                               : 0.0;
  }
}

/// Relative step of the central differences of div sigma_aux (header).
constexpr double DIV_STEP = 1e-4;

void aux_point(const Elasticity& el, const FrontFrame& f, const FrontCurvatures& k, const Point3& x, int side,
               AuxPoint& a)
{
  const LocalCoordinates lc = frame_coordinates(f, x);
  const double x1 = lc.x1, x2 = lc.x2;
  const double h = 1.0 + k.front * x1 - k.along * x2;
  if (!(h > 0.05))
    throw std::invalid_argument("interaction integral: a point lies beyond the centre of curvature of its front "
                                "point (1 + kappa x1 = " + std::to_string(h) + "): the domain is too large for "
                                "the front's curvature");
  LocalAux L;
  local_aux(el, k, x1, x2, side, L);
  double div[3][3];
  if (k.across == 0.0 and k.along == 0.0 and k.torsion == 0.0)
  {
    // A planar crack: the closed form (header).
    const double ir = k.front / h;
    for (int m = 0; m < 3; ++m)
    {
      const auto& d = L.dxi[m];
      div[m][0] = (el.lmbda + 2.0 * el.mu) * (d[0][0] - L.U[m][0] * ir) * ir;
      div[m][1] = (el.mu * d[1][0] + (el.lmbda + el.mu) * d[0][1]) * ir;
      div[m][2] = el.mu * (d[2][0] - L.U[m][2] * ir) * ir;
    }
  }
  else
  {
    // sigma_ab depends on (x1, x2) only, the frame on s alone:
    //   div sigma = sum_ab (sigma_ab,1 (e_b . grad x1) + sigma_ab,2 (e_b . grad x2)) e_a
    //               + (sigma_a3 e_a' + sigma_ab (e_b' . e3) e_a) / h,
    // the partial derivatives by central differences (side kept: a point
    // off the crack takes the branch of its own xi2).
    const double xi2 = x2 - 0.5 * k.across * x1 * x1;
    const int s_eff = side != 0 ? side : (xi2 >= 0.0 ? 1 : -1);
    const double step = DIV_STEP * std::max(std::hypot(x1, x2), 1e-300);
    double ds[2][3][3][3]; // [direction][mode][a][b]
    for (int dir = 0; dir < 2; ++dir)
    {
      LocalAux P, M;
      local_aux(el, k, x1 + (dir == 0 ? step : 0.0), x2 + (dir == 1 ? step : 0.0), s_eff, P);
      local_aux(el, k, x1 - (dir == 0 ? step : 0.0), x2 - (dir == 1 ? step : 0.0), s_eff, M);
      for (int m = 0; m < 3; ++m)
      {
        double sp[3][3], sm[3][3];
        el.stress(P.G[m], sp);
        el.stress(M.G[m], sm);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            ds[dir][m][i][j] = (sp[i][j] - sm[i][j]) / (2.0 * step);
      }
    }
    const double g1[3] = {1.0, 0.0, k.torsion * x2 / h}, g2[3] = {0.0, 1.0, -k.torsion * x1 / h};
    const double de[3][3] = {{0.0, k.torsion, k.front}, {-k.torsion, 0.0, -k.along}, {-k.front, k.along, 0.0}};
    const double de3[3] = {k.front, -k.along, 0.0}; // e_b' . e3
    for (int m = 0; m < 3; ++m)
    {
      double sig[3][3];
      el.stress(L.G[m], sig);
      for (int i = 0; i < 3; ++i)
      {
        double v = 0.0;
        for (int b = 0; b < 3; ++b)
          v += ds[0][m][i][b] * g1[b] + ds[1][m][i][b] * g2[b] + (sig[b][2] * de[b][i] + sig[i][b] * de3[b]) / h;
        div[m][i] = v;
      }
    }
  }
  // To global components.
  const Point3* e[3] = {&f.e1, &f.e2, &f.e3};
  for (int m = 0; m < 3; ++m)
  {
    for (int i = 0; i < 3; ++i)
    {
      a.local[m][i] = L.U[m][i];
      double u = 0.0, dv = 0.0;
      for (int k3 = 0; k3 < 3; ++k3)
        u += L.U[m][k3] * (*e[k3])[i], dv += div[m][k3] * (*e[k3])[i];
      a.U[m][i] = u, a.div[m][i] = dv;
    }
    double T[3][3]; // G e_b rows: T[a][j] = sum_b G[a][b] e_b,j
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        T[i][j] = L.G[m][i][0] * f.e1[j] + L.G[m][i][1] * f.e2[j] + L.G[m][i][2] * f.e3[j];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        a.G[m][i][j] = f.e1[i] * T[0][j] + f.e2[i] * T[1][j] + f.e3[i] * T[2][j];
  }
}

/// aux_point at every point p (frames (n, 12), curvatures (n, 4), x (n, 3),
/// sides (n)), then f(p, fields).
template <typename F>
void for_each_aux_point(const Elasticity& el, std::span<const double> frames, std::span<const double> curvatures,
                        std::span<const double> x, std::span<const std::int8_t> sides, F&& f)
{
  AuxPoint a;
  for (std::size_t p = 0; p < sides.size(); ++p)
  {
    aux_point(el, frame_at(frames, p), curvatures_at(curvatures, p), {x[3 * p], x[3 * p + 1], x[3 * p + 2]},
              sides[p], a);
    f(p, a);
  }
}
} // namespace

void auxiliary_fields_3d(double E, double nu, std::span<const double> frames, std::span<const double> curvatures,
                         std::span<const double> x, std::span<const std::int8_t> sides, std::span<double> U,
                         std::span<double> G, std::span<double> local, std::span<double> div_sigma)
{
  const std::size_t n = sides.size();
  if (frames.size() != 12 * n or curvatures.size() != 4 * n or x.size() != 3 * n or U.size() != 9 * n
      or G.size() != 27 * n or local.size() != 9 * n or div_sigma.size() != 9 * n)
    throw std::invalid_argument("auxiliary_fields_3d: expected frames (n, 12), curvatures (n, 4), x (n, 3), sides (n), "
                                "U (n, 3, 3), G (n, 3, 3, 3), local (n, 3, 3), div_sigma (n, 3, 3)");
  const Elasticity el(E, nu, "auxiliary_fields_3d");
  for_each_aux_point(el, frames, curvatures, x, sides,
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

namespace
{
/// The body force at point p: the constant one (3), or point p's of a body
/// force per point (n, 3) (an initial stress's divergence varies), or none.
std::span<const double> body_at(std::span<const double> body, std::size_t p)
{
  return body.size() <= 3 ? body : body.subspan(3 * p, 3);
}

/// T (mode, j, l) and D (mode, l) of one point (header of
/// interaction_integrand_3d) from its auxiliary fields and g = grad u.
void integrand_point(const Elasticity& el, const AuxPoint& a, const double g[3][3], std::span<const double> body,
                     double* T, double* D)
{
  double sig[3][3];
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
        T[9 * m + 3 * j + l] = v;
      }
    for (int l = 0; l < 3; ++l)
    {
      double v = 0.0;
      for (int i = 0; i < 3; ++i)
        v += a.div[m][i] * g[i][l] - (body.empty() ? 0.0 : body[i] * Ga[i][l]);
      D[3 * m + l] = v;
    }
  }
}

void load_gradient(std::span<const double> grad_u, std::size_t p, double g[3][3])
{
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      g[i][j] = grad_u[9 * p + 3 * i + j];
}

/// Checks of a FrontDomainTable against n points of c cells.
void check_table(const FrontDomainTable& t, std::size_t num_cells, std::size_t num_front_points,
                 std::span<const double> I, const char* who)
{
  const std::string w(who);
  if (t.num_domains < 1)
    throw std::invalid_argument(w + ": needs at least one domain per front point");
  if (t.offsets.size() != num_cells + 1 or t.offsets[0] != 0)
    throw std::invalid_argument(w + ": cell offsets must be (num_cells + 1) starting at 0");
  const auto m = static_cast<std::size_t>(t.offsets[num_cells]);
  if (t.point.size() != m or t.q.size() != 4 * m * static_cast<std::size_t>(t.num_domains))
    throw std::invalid_argument(w + ": expected point (m) and q (m, 4, num_domains) for the table's m entries");
  for (std::size_t c = 0; c < num_cells; ++c)
    if (t.offsets[c + 1] < t.offsets[c])
      throw std::invalid_argument(w + ": cell offsets must not decrease");
  for (const std::int32_t k : t.point)
    if (k < 0 or static_cast<std::size_t>(k) >= num_front_points)
      throw std::invalid_argument(w + ": front point index " + std::to_string(k) + " out of range");
  if (I.size() != num_front_points * static_cast<std::size_t>(t.num_domains) * 3)
    throw std::invalid_argument(w + ": I must be (num_front_points, num_domains, 3)");
}

/// For every table entry of point p's cell: f(k, entry) with k its front
/// point.
template <typename F>
void for_each_entry(const FrontDomainTable& t, std::int32_t cell, F&& f)
{
  for (std::int32_t e = t.offsets[cell]; e < t.offsets[cell + 1]; ++e)
    f(t.point[e], e);
}
} // namespace

void interaction_integrand_3d(double E, double nu, std::span<const double> frames, std::span<const double> curvatures,
                              std::span<const double> x, std::span<const double> grad_u,
                              std::span<const std::int8_t> sides, std::span<const double> body, std::span<double> T,
                              std::span<double> D)
{
  const std::size_t n = sides.size();
  if (frames.size() != 12 * n or curvatures.size() != 4 * n or x.size() != 3 * n or grad_u.size() != 9 * n
      or T.size() != 27 * n or D.size() != 9 * n
      or (!body.empty() and body.size() != 3 and body.size() != 3 * n))
    throw std::invalid_argument("interaction_integrand_3d: expected frames (n, 12), curvatures (n, 4), x (n, 3), "
                                "grad_u (n, 3, 3), sides (n), body (3), (n, 3) or empty, T (n, 3, 3, 3), D (n, 3, 3)");
  const Elasticity el(E, nu, "interaction_integrand_3d");
  for_each_aux_point(el, frames, curvatures, x, sides,
                     [&](std::size_t p, const AuxPoint& a)
                     {
                       double g[3][3];
                       load_gradient(grad_u, p, g);
                       integrand_point(el, a, g, body_at(body, p), &T[27 * p], &D[9 * p]);
                     });
}

void front_domain_integrals_3d(double E, double nu, std::span<const double> frames,
                               std::span<const double> curvatures, std::span<const double> x,
                               std::span<const double> grad_u, std::span<const std::int8_t> sides,
                               std::span<const double> body, std::span<const double> weights,
                               std::span<const std::int32_t> point_cell, std::span<const double> shape,
                               std::span<const double> cell_gradients, const FrontDomainTable& table,
                               std::span<const double> directions, std::span<double> I)
{
  const std::size_t n = sides.size(), nc = cell_gradients.size() / 12, K = directions.size() / 3;
  if (frames.size() != 12 * n or curvatures.size() != 4 * n or x.size() != 3 * n or grad_u.size() != 9 * n
      or weights.size() != n or point_cell.size() != n or shape.size() != 4 * n or cell_gradients.size() != 12 * nc
      or directions.size() != 3 * K
      or (!body.empty() and body.size() != 3 and body.size() != 3 * n))
    throw std::invalid_argument("front_domain_integrals_3d: expected frames (n, 12), curvatures (n, 4), x (n, 3), "
                                "grad_u (n, 3, 3), sides (n), weights (n), point_cell (n), shape (n, 4), "
                                "cell_gradients (c, 4, 3), directions (K, 3), body (3), (n, 3) or empty");
  check_table(table, nc, K, I, "front_domain_integrals_3d");
  const int nd = table.num_domains;
  const Elasticity el(E, nu, "front_domain_integrals_3d");
  double T[27], D[9];
  for_each_aux_point(el, frames, curvatures, x, sides,
                     [&](std::size_t p, const AuxPoint& a)
                     {
                       const std::int32_t c = point_cell[p];
                       if (c < 0 or static_cast<std::size_t>(c) >= nc)
                         throw std::invalid_argument("front_domain_integrals_3d: point cell out of range");
                       if (table.offsets[c] == table.offsets[c + 1])
                         return;
                       double g[3][3];
                       load_gradient(grad_u, p, g);
                       integrand_point(el, a, g, body_at(body, p), T, D);
                       const double* N = &shape[4 * p];
                       const double* dN = &cell_gradients[12 * c];
                       for_each_entry(table, c,
                                      [&](std::int32_t k, std::int32_t e)
                                      {
                                        const double* d = &directions[3 * k];
                                        double Td[3][3], Dd[3];
                                        for (int m = 0; m < 3; ++m)
                                        {
                                          Dd[m] = D[3 * m] * d[0] + D[3 * m + 1] * d[1] + D[3 * m + 2] * d[2];
                                          for (int j = 0; j < 3; ++j)
                                            Td[m][j] = T[9 * m + 3 * j] * d[0] + T[9 * m + 3 * j + 1] * d[1]
                                                       + T[9 * m + 3 * j + 2] * d[2];
                                        }
                                        const double* q = &table.q[4 * nd * static_cast<std::size_t>(e)];
                                        for (int dm = 0; dm < nd; ++dm)
                                        {
                                          double qv = 0.0, gq[3] = {0.0, 0.0, 0.0};
                                          for (int v = 0; v < 4; ++v)
                                          {
                                            const double qa = q[nd * v + dm];
                                            qv += N[v] * qa;
                                            for (int j = 0; j < 3; ++j)
                                              gq[j] += qa * dN[3 * v + j];
                                          }
                                          double* out = &I[3 * (nd * static_cast<std::size_t>(k) + dm)];
                                          for (int m = 0; m < 3; ++m)
                                            out[m] += weights[p] * (gq[0] * Td[m][0] + gq[1] * Td[m][1]
                                                                    + gq[2] * Td[m][2] + qv * Dd[m]);
                                        }
                                      });
                     });
}

void front_domain_sums_3d(std::span<const double> values, std::span<const double> weights,
                          std::span<const std::int32_t> point_cell, std::span<const double> shape,
                          std::size_t num_cells, const FrontDomainTable& table, std::span<const double> directions,
                          std::span<double> I)
{
  const std::size_t n = weights.size(), K = directions.size() / 3;
  if (values.size() != 9 * n or point_cell.size() != n or shape.size() != 4 * n or directions.size() != 3 * K)
    throw std::invalid_argument("front_domain_sums_3d: expected values (n, 3, 3), weights (n), point_cell (n), "
                                "shape (n, 4), directions (K, 3)");
  check_table(table, num_cells, K, I, "front_domain_sums_3d");
  const int nd = table.num_domains;
  for (std::size_t p = 0; p < n; ++p)
  {
    const std::int32_t c = point_cell[p];
    if (c < 0 or static_cast<std::size_t>(c) >= num_cells)
      throw std::invalid_argument("front_domain_sums_3d: point cell out of range");
    const double* N = &shape[4 * p];
    for_each_entry(table, c,
                   [&](std::int32_t k, std::int32_t e)
                   {
                     const double* d = &directions[3 * k];
                     const double* q = &table.q[4 * nd * static_cast<std::size_t>(e)];
                     for (int dm = 0; dm < nd; ++dm)
                     {
                       const double qv = N[0] * q[dm] + N[1] * q[nd + dm] + N[2] * q[2 * nd + dm]
                                         + N[3] * q[3 * nd + dm];
                       double* out = &I[3 * (nd * static_cast<std::size_t>(k) + dm)];
                       for (int m = 0; m < 3; ++m)
                         out[m] += weights[p] * qv
                                   * (values[9 * p + 3 * m] * d[0] + values[9 * p + 3 * m + 1] * d[1]
                                      + values[9 * p + 3 * m + 2] * d[2]);
                     }
                   });
  }
}

std::array<double, 3> front_sifs_3d(double E, double nu, const std::array<double, 3>& I, double q_e1, double q_e2)
{
  if (!(q_e1 != 0.0) or !std::isfinite(q_e1) or !std::isfinite(q_e2))
    throw std::invalid_argument("front_sifs_3d: int q (e1 . d) ds must be finite and nonzero");
  const Elasticity el(E, nu, "front_sifs_3d");
  const double Ep = E / (1.0 - nu * nu), rho = q_e2 / q_e1;
  const double a = 0.5 * Ep * I[0] / q_e1, b = 0.5 * Ep * I[1] / q_e1, det = 1.0 - rho * rho;
  return {(a + rho * b) / det, (b + rho * a) / det, el.mu * I[2] / q_e1};
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
