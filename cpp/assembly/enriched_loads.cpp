#include "assembly/enriched_loads.h"

#include "assembly/elasticity.h"
#include "enrichment/enriched_basis.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace cracklip
{
namespace
{
template <int dim>
void check(std::size_t n, std::span<const double> ref, std::span<const double> weights, std::span<const double> b,
           const EnrichmentLayout& layout, const char* what)
{
  layout.require_dimension(dim, what);
  if (ref.size() != dim * n or weights.size() != n)
    throw std::invalid_argument(std::string(what) + ": expected ref (n, " + std::to_string(dim) + ") and weights (n)");
  if (b.size() != dim * static_cast<std::size_t>(layout.num_nodes_total()))
    throw std::invalid_argument(std::string(what) + ": the load vector has the wrong size");
}

template <int dim>
std::array<double, dim> point(std::span<const double> a, std::size_t p)
{
  std::array<double, dim> r;
  for (int i = 0; i < dim; ++i)
    r[i] = a[dim * p + i];
  return r;
}
} // namespace

template <int dim>
void assemble_lip_load(std::span<const double> x, std::span<const std::int32_t> cells,
                       const EnrichmentLayout& layout, std::span<const CrackGeometryOf<dim>* const> cracks,
                       std::int32_t crack, std::span<const std::int32_t> point_cells, std::span<const double> ref,
                       std::span<const double> weights, std::span<const double> traction, std::span<double> b)
{
  const std::size_t n = point_cells.size();
  check<dim>(n, ref, weights, b, layout, "assemble_lip_load");
  if (traction.size() != dim * n)
    throw std::invalid_argument("assemble_lip_load: expected traction (n, " + std::to_string(dim) + ")");
  if (crack < 0 or static_cast<std::size_t>(crack) >= cracks.size())
    throw std::invalid_argument("assemble_lip_load: crack index out of range");
  constexpr int ns = EnrichedCellBasis<dim>::num_standard_dofs;
  std::vector<double> vp, vm, grad;
  std::vector<int> side;
  for (std::size_t p = 0; p < n; ++p)
  {
    const auto t = point<dim>(traction, p);
    bool zero = true;
    for (int i = 0; i < dim; ++i)
      zero = zero and t[i] == 0.0;
    if (zero)
      continue;
    const std::int32_t c = point_cells[p];
    const P1Simplex<dim> cell(x, cells, c);
    const EnrichedCellBasis<dim> basis(cell, layout, c);
    const auto r = point<dim>(ref, p);
    region_sides(cracks, c, 1, side);
    side[crack] = 1;
    evaluate_basis<dim>(cell, basis, layout, cracks, side, r, vp, grad);
    side[crack] = -1;
    evaluate_basis<dim>(cell, basis, layout, cracks, side, r, vm, grad);
    for (int j = ns; j < basis.num_dofs(); ++j) // standard functions do not jump
    {
      double work = (vp[dim * j] - vm[dim * j]) * t[0];
      for (int i = 1; i < dim; ++i)
        work += (vp[dim * j + i] - vm[dim * j + i]) * t[i];
      b[basis.dofs[j]] += weights[p] * work;
    }
  }
}

template <int dim>
void assemble_cell_load(std::span<const double> x, std::span<const std::int32_t> cells,
                        const EnrichmentLayout& layout, std::span<const CrackGeometryOf<dim>* const> cracks,
                        std::span<const std::int32_t> point_cells, std::span<const double> ref,
                        std::span<const std::int8_t> sides, std::span<const double> weights,
                        std::span<const double> force, std::span<const double> stress, std::span<double> b)
{
  constexpr int nv = voigt_size<dim>;
  const std::size_t n = point_cells.size();
  check<dim>(n, ref, weights, b, layout, "assemble_cell_load");
  if (sides.size() != n or force.size() != dim * n or (!stress.empty() and stress.size() != nv * n))
    throw std::invalid_argument("assemble_cell_load: expected sides (n), force (n, " + std::to_string(dim)
                                + ") and stress (n, " + std::to_string(nv) + ") or none");
  constexpr int ns = EnrichedCellBasis<dim>::num_standard_dofs;
  std::vector<double> val, grad;
  std::vector<int> side;
  for (std::size_t p = 0; p < n; ++p)
  {
    const std::int32_t c = point_cells[p];
    const P1Simplex<dim> cell(x, cells, c);
    const EnrichedCellBasis<dim> basis(cell, layout, c);
    if (basis.enr.empty())
      continue;
    region_sides(cracks, c, sides[p], side);
    evaluate_basis<dim>(cell, basis, layout, cracks, side, point<dim>(ref, p), val, grad);
    for (int j = ns; j < basis.num_dofs(); ++j)
    {
      double work = force[dim * p] * val[dim * j];
      for (int i = 1; i < dim; ++i)
        work += force[dim * p + i] * val[dim * j + i];
      if (!stress.empty())
      {
        // s : eps(N_j) in Voigt form (engineering shears).
        const auto e = voigt_strain<dim>(&grad[dim * dim * j]);
        double se = stress[nv * p] * e[0];
        for (int k = 1; k < nv; ++k)
          se += stress[nv * p + k] * e[k];
        work -= se;
      }
      b[basis.dofs[j]] += weights[p] * work;
    }
  }
}

template void assemble_lip_load<2>(std::span<const double>, std::span<const std::int32_t>, const EnrichmentLayout&,
                                   std::span<const CrackGeometry* const>, std::int32_t,
                                   std::span<const std::int32_t>, std::span<const double>, std::span<const double>,
                                   std::span<const double>, std::span<double>);
template void assemble_lip_load<3>(std::span<const double>, std::span<const std::int32_t>, const EnrichmentLayout&,
                                   std::span<const CrackGeometry3D* const>, std::int32_t,
                                   std::span<const std::int32_t>, std::span<const double>, std::span<const double>,
                                   std::span<const double>, std::span<double>);
template void assemble_cell_load<2>(std::span<const double>, std::span<const std::int32_t>, const EnrichmentLayout&,
                                    std::span<const CrackGeometry* const>, std::span<const std::int32_t>,
                                    std::span<const double>, std::span<const std::int8_t>, std::span<const double>,
                                    std::span<const double>, std::span<const double>, std::span<double>);
template void assemble_cell_load<3>(std::span<const double>, std::span<const std::int32_t>, const EnrichmentLayout&,
                                    std::span<const CrackGeometry3D* const>, std::span<const std::int32_t>,
                                    std::span<const double>, std::span<const std::int8_t>, std::span<const double>,
                                    std::span<const double>, std::span<const double>, std::span<double>);

} // namespace cracklip
