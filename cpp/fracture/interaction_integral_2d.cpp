#include "fracture/interaction_integral_2d.h"

#include "enrichment/enriched_basis_2d.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cracklip
{

std::array<double, 2> interaction_integral(const TipFrame& tip, double E, double nu,
                                           std::span<const double> points,
                                           std::span<const double> weights,
                                           std::span<const double> grad_q,
                                           std::span<const double> grad_u,
                                           std::span<const std::int8_t> sides)
{
  const std::size_t n = weights.size();
  if (points.size() != 2 * n or grad_q.size() != 2 * n or grad_u.size() != 4 * n or sides.size() != n)
    throw std::invalid_argument("interaction_integral: expected points (n,2), weights (n), "
                                "grad_q (n,2), grad_u (n,2,2), sides (n)");
  const auto D = plane_strain_matrix(E, nu);
  const double mu = E / (2.0 * (1.0 + nu));
  const double kappa = 3.0 - 4.0 * nu;
  const double scale = 1.0 / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi));
  const double e1[2] = {tip.e1[0], tip.e1[1]};
  std::array<double, 2> I = {0.0, 0.0};
  std::array<std::array<double, 2>, 2> U;
  std::array<std::array<std::array<double, 2>, 2>, 2> dU;
  auto stress = [&](const double g[2][2], double s[2][2])
  {
    const double exx = g[0][0], eyy = g[1][1], gxy = g[0][1] + g[1][0];
    const double sxx = D[0] * exx + D[1] * eyy + D[2] * gxy;
    const double syy = D[3] * exx + D[4] * eyy + D[5] * gxy;
    const double sxy = D[6] * exx + D[7] * eyy + D[8] * gxy;
    s[0][0] = sxx, s[0][1] = sxy, s[1][0] = sxy, s[1][1] = syy;
  };
  for (std::size_t p = 0; p < n; ++p)
  {
    const double gq[2] = {grad_q[2 * p], grad_q[2 * p + 1]};
    if (gq[0] == 0.0 and gq[1] == 0.0)
      continue;
    const double gu[2][2] = {{grad_u[4 * p], grad_u[4 * p + 1]}, {grad_u[4 * p + 2], grad_u[4 * p + 3]}};
    double sig[2][2];
    stress(gu, sig);
    williams_displacement(tip, {points[2 * p], points[2 * p + 1]}, sides[p], kappa, U, dU);
    for (int m = 0; m < 2; ++m)
    {
      double ga[2][2];
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          ga[i][j] = scale * dU[m][i][j];
      double siga[2][2];
      stress(ga, siga);
      double t1 = 0.0, t2 = 0.0, w = 0.0;
      for (int i = 0; i < 2; ++i)
      {
        const double ua1 = ga[i][0] * e1[0] + ga[i][1] * e1[1]; // (grad u_aux e1)_i
        const double u1 = gu[i][0] * e1[0] + gu[i][1] * e1[1];
        t1 += (sig[i][0] * gq[0] + sig[i][1] * gq[1]) * ua1;
        t2 += (siga[i][0] * gq[0] + siga[i][1] * gq[1]) * u1;
        for (int j = 0; j < 2; ++j)
          w += sig[i][j] * 0.5 * (ga[i][j] + ga[j][i]);
      }
      I[m] += weights[p] * (t1 + t2 - w * (e1[0] * gq[0] + e1[1] * gq[1]));
    }
  }
  return I;
}

double domain_q(double distance, double radius, std::optional<double> inner_radius)
{
  if (!inner_radius or *inner_radius >= radius)
    return distance < radius ? 1.0 : 0.0;
  if (distance <= *inner_radius)
    return 1.0;
  if (distance >= radius)
    return 0.0;
  return (radius - distance) / (radius - *inner_radius);
}

DomainPoints compute_domain_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                   const EnrichmentLayout& layout,
                                   std::span<const CrackGeometry* const> cracks,
                                   const TipFrame& tip, double radius,
                                   const QuadratureOptions& options, bool interior,
                                   std::optional<double> inner_radius)
{
  if (!(radius > 0.0))
    throw std::invalid_argument("interaction integral: the domain radius must be positive");
  if (inner_radius and !(*inner_radius >= 0.0 and *inner_radius <= radius))
    throw std::invalid_argument("interaction integral: the inner radius of a ring must lie in [0, radius]");
  const std::size_t num_cells = cells.size() / 3;
  DomainPoints out;
  CellQuadrature qp;
  std::vector<double> val, grad;
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const std::int32_t* v = &cells[3 * c];
    double q[3];
    for (int a = 0; a < 3; ++a)
      q[a] = domain_q(std::hypot(x[2 * v[a]] - tip.tip[0], x[2 * v[a] + 1] - tip.tip[1]), radius, inner_radius);
    if (q[0] == q[1] and q[1] == q[2] and (!interior or q[0] == 0.0))
      continue;
    const auto ci = static_cast<std::int32_t>(c);
    const P1Cell cell(x, cells, ci);
    const CellBasis basis(cell, layout, ci);
    double gq[2] = {0.0, 0.0};
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 2; ++d)
        gq[d] += q[a] * cell.grad[a][d];
    compute_cell_quadrature(cell, ci, cracks, cell_tip(cell, basis, layout), options, qp);
    for (int k = 0; k < qp.size(); ++k)
    {
      const std::array<double, 2> r = {qp.ref[2 * k], qp.ref[2 * k + 1]};
      const auto xp = cell.physical(r);
      out.cell.push_back(ci);
      out.ref.insert(out.ref.end(), r.begin(), r.end());
      out.x.insert(out.x.end(), xp.begin(), xp.end());
      out.weight.push_back(qp.weight[k]);
      out.side.push_back(qp.side[k]);
      const auto N = P1Cell::shape(r);
      out.q.push_back(N[0] * q[0] + N[1] * q[1] + N[2] * q[2]);
      out.grad_q.insert(out.grad_q.end(), gq, gq + 2);
    }
  }
  return out;
}

} // namespace cracklip
