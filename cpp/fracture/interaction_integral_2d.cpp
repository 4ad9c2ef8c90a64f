#include "fracture/interaction_integral_2d.h"

#include "enrichment/enriched_basis.h"
#include "fracture/interaction_density.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cracklip
{

std::array<double, 2> interaction_integral(const TipFrame& tip, double E, double nu, std::span<const double> points,
                                           std::span<const double> weights, std::span<const double> grad_q,
                                           std::span<const double> grad_u, std::span<const std::int8_t> sides)
{
  const std::size_t n = weights.size();
  if (points.size() != 2 * n or grad_q.size() != 2 * n or grad_u.size() != 4 * n or sides.size() != n)
    throw std::invalid_argument("interaction_integral: expected points (n,2), weights (n), "
                                "grad_q (n,2), grad_u (n,2,2), sides (n)");
  const IsotropicElasticity<2> el(E, nu, "interaction_integral (plane strain)");
  const double e1[2] = {tip.e1[0], tip.e1[1]};
  std::array<std::array<double, 2>, 2> U;
  const auto aux = [&](std::size_t p, std::array<std::array<std::array<double, 2>, 2>, 2>& dU)
  { williams_displacement(tip, {points[2 * p], points[2 * p + 1]}, sides[p], el.kappa, U, dU); };
  return interaction_sum<2>(el, e1, weights, grad_q, grad_u, aux);
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
