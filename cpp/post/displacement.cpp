#include "post/displacement.h"

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
    add_point_values<dim>(basis, u, val, grad, &out[dim * p], grad_out ? &(*grad_out)[dim * dim * p] : nullptr);
  }
  return out;
}

template <int dim>
FieldPoints compute_field_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                 const EnrichmentLayout& layout, std::span<const CrackGeometryOf<dim>* const> cracks,
                                 std::span<const double> u, std::span<const std::int32_t> cell_list,
                                 const QuadratureOptionsOf<dim>& options)
{
  layout.require_dimension(dim, "compute_field_points");
  if (u.size() != dim * static_cast<std::size_t>(layout.num_nodes_total()))
    throw std::invalid_argument("solution vector has " + std::to_string(u.size()) + " entries, expected "
                                + std::to_string(dim * layout.num_nodes_total()));
  const auto num_cells = static_cast<std::int32_t>(cells.size() / (dim + 1));
  FieldPoints out;
  std::vector<double> val, grad;
  std::vector<int> side;
  CellQuadratureOf<dim> q;
  std::array<double, dim> r;
  const std::int32_t n = cell_list.empty() ? num_cells : static_cast<std::int32_t>(cell_list.size());
  for (std::int32_t k = 0; k < n; ++k)
  {
    const std::int32_t c = cell_list.empty() ? k : cell_list[k];
    if (c < 0 or c >= num_cells)
      throw std::invalid_argument("compute_field_points: cell index out of range");
    const P1Simplex<dim> cell(x, cells, c);
    const EnrichedCellBasis<dim> basis(cell, layout, c);
    compute_enriched_cell_quadrature(x, cells, layout, cracks, c, options, q);
    for (int p = 0; p < q.size(); ++p)
    {
      for (int i = 0; i < dim; ++i)
        r[i] = q.ref[dim * p + i];
      region_sides(cracks, c, q.side[p], side);
      evaluate_basis<dim>(cell, basis, layout, cracks, side, r, val, grad);
      std::array<double, dim * dim> g{};
      add_point_values<dim>(basis, u, val, grad, nullptr, g.data());
      const auto xp = cell.physical(r);
      out.cell.push_back(c);
      out.ref.insert(out.ref.end(), r.begin(), r.end());
      out.x.insert(out.x.end(), xp.begin(), xp.end());
      out.weight.push_back(q.weight[p]);
      out.side.push_back(q.side[p]);
      out.grad_u.insert(out.grad_u.end(), g.begin(), g.end());
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

template FieldPoints compute_field_points<2>(std::span<const double>, std::span<const std::int32_t>,
                                             const EnrichmentLayout&, std::span<const CrackGeometry* const>,
                                             std::span<const double>, std::span<const std::int32_t>,
                                             const QuadratureOptions&);
template FieldPoints compute_field_points<3>(std::span<const double>, std::span<const std::int32_t>,
                                             const EnrichmentLayout&, std::span<const CrackGeometry3D* const>,
                                             std::span<const double>, std::span<const std::int32_t>,
                                             const QuadratureOptions3D&);

} // namespace cracklip
