#include "post/displacement.h"

#include "enrichment/enriched_basis.h"

#include <stdexcept>
#include <string>

namespace cracklip
{

template <int dim>
std::vector<double> evaluate_displacement(std::span<const double> x, std::span<const std::int32_t> cells,
                                          const EnrichmentLayout& layout,
                                          std::span<const CrackGeometryOf<dim>* const> cracks,
                                          std::span<const double> u, std::span<const std::int32_t> point_cells,
                                          std::span<const double> ref_points, std::span<const std::int8_t> sides,
                                          std::vector<double>* grad_out)
{
  layout.require_dimension(dim, "evaluate_displacement");
  const std::size_t n = point_cells.size();
  if (ref_points.size() != dim * n or sides.size() != n)
    throw std::invalid_argument("evaluate_displacement: " + std::to_string(n) + " cells but "
                                + std::to_string(ref_points.size()) + " reference values and "
                                + std::to_string(sides.size()) + " sides; expected ref_points (n, "
                                + std::to_string(dim) + ") and sides (n)");
  if (u.size() != dim * static_cast<std::size_t>(layout.num_nodes_total()))
    throw std::invalid_argument("evaluate_displacement: the solution vector has " + std::to_string(u.size())
                                + " entries, the layout " + std::to_string(dim * layout.num_nodes_total()));
  const std::size_t num_cells = cells.size() / (dim + 1);
  std::vector<double> out(dim * n, 0.0), val, grad;
  if (grad_out)
    grad_out->assign(dim * dim * n, 0.0);
  std::vector<int> side;
  std::array<double, dim> r;
  for (std::size_t p = 0; p < n; ++p)
  {
    const std::int32_t c = point_cells[p];
    if (c < 0 or static_cast<std::size_t>(c) >= num_cells)
      throw std::invalid_argument("evaluate_displacement: cell index " + std::to_string(c) + " out of range");
    const P1Simplex<dim> cell(x, cells, c);
    const EnrichedCellBasis<dim> basis(cell, layout, c);
    for (int i = 0; i < dim; ++i)
      r[i] = ref_points[dim * p + i];
    int s = sides[p];
    if (s == 0)
    {
      // The side the point lies on, for the crack crossing or ending in c.
      for (const auto* g : cracks)
        if (crosses(*g, c))
        {
          const auto N = P1Simplex<dim>::shape(r);
          double phi = 0.0;
          for (int a = 0; a <= dim; ++a)
            phi += N[a] * g->phi[cell.nodes[a]];
          s = phi >= 0.0 ? 1 : -1;
        }
    }
    region_sides(cracks, c, s, side);
    evaluate_basis<dim>(cell, basis, layout, cracks, side, r, val, grad);
    for (int i = 0; i < basis.num_dofs(); ++i)
    {
      const double ui = u[basis.dofs[i]];
      if (ui == 0.0)
        continue;
      for (int a = 0; a < dim; ++a)
      {
        out[dim * p + a] += val[dim * i + a] * ui;
        if (grad_out)
          for (int b = 0; b < dim; ++b)
            (*grad_out)[dim * dim * p + dim * a + b] += grad[(dim * i + a) * dim + b] * ui;
      }
    }
  }
  return out;
}

template std::vector<double> evaluate_displacement<2>(std::span<const double>, std::span<const std::int32_t>,
                                                      const EnrichmentLayout&, std::span<const CrackGeometry* const>,
                                                      std::span<const double>, std::span<const std::int32_t>,
                                                      std::span<const double>, std::span<const std::int8_t>,
                                                      std::vector<double>*);
template std::vector<double> evaluate_displacement<3>(std::span<const double>, std::span<const std::int32_t>,
                                                      const EnrichmentLayout&, std::span<const CrackGeometry3D* const>,
                                                      std::span<const double>, std::span<const std::int32_t>,
                                                      std::span<const double>, std::span<const std::int8_t>,
                                                      std::vector<double>*);

} // namespace cracklip
