#include "assembly/facet_basis.h"

#include "enrichment/enriched_basis.h"
#include "quadrature/facet_points.h"

#include <stdexcept>
#include <string>

namespace cracklip
{

template <int dim>
FacetBasis compute_facet_basis(std::span<const double> x, std::span<const std::int32_t> cells,
                               const EnrichmentLayout& layout, std::span<const CrackGeometryOf<dim>* const> cracks,
                               std::span<const std::int32_t> facet_cells, std::span<const std::int32_t> facet_local,
                               int degree)
{
  layout.require_dimension(dim, "compute_facet_basis");
  if (facet_cells.size() != facet_local.size())
    throw std::invalid_argument("compute_facet_basis: facet arrays differ in length");
  FacetBasis out;
  out.dim = dim;
  std::vector<double> val, grad;
  std::vector<int> side;
  FacetPoints fp;
  std::array<double, dim> r;
  for (std::size_t f = 0; f < facet_cells.size(); ++f)
  {
    const std::int32_t c = facet_cells[f];
    const int lf = facet_local[f];
    if (lf < 0 or lf > dim)
      throw std::invalid_argument("compute_facet_basis: local facet index must lie in 0 .. " + std::to_string(dim)
                                  + ", got " + std::to_string(lf));
    const P1Simplex<dim> cell(x, cells, c);
    const EnrichedCellBasis<dim> basis(cell, layout, c);
    compute_facet_points(cell, cracks, c, lf, degree, fp);
    for (int q = 0; q < fp.size(); ++q)
    {
      for (int i = 0; i < dim; ++i)
        r[i] = fp.ref[dim * q + i];
      region_sides(cracks, c, fp.side[q], side);
      evaluate_basis<dim>(cell, basis, layout, cracks, side, r, val, grad);
      const auto xp = cell.physical(r);
      const auto ip = static_cast<std::int32_t>(out.weights.size());
      out.points.insert(out.points.end(), xp.begin(), xp.end());
      out.normals.insert(out.normals.end(), fp.normal.begin(), fp.normal.end());
      out.weights.push_back(fp.weight[q]);
      for (int i = 0; i < basis.num_dofs(); ++i)
      {
        const double* v = &val[dim * i];
        bool zero = true;
        for (int a = 0; a < dim; ++a)
          zero = zero and v[a] == 0.0;
        if (zero)
          continue;
        out.entry_point.push_back(ip);
        out.entry_dof.push_back(basis.dofs[i]);
        out.entry_value.insert(out.entry_value.end(), v, v + dim);
      }
    }
  }
  return out;
}

template FacetBasis compute_facet_basis<2>(std::span<const double>, std::span<const std::int32_t>,
                                           const EnrichmentLayout&, std::span<const CrackGeometry* const>,
                                           std::span<const std::int32_t>, std::span<const std::int32_t>, int);
template FacetBasis compute_facet_basis<3>(std::span<const double>, std::span<const std::int32_t>,
                                           const EnrichmentLayout&, std::span<const CrackGeometry3D* const>,
                                           std::span<const std::int32_t>, std::span<const std::int32_t>, int);

} // namespace cracklip
