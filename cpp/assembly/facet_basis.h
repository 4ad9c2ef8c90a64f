// The basis functions on boundary facets (layer a), in any dimension: for
// Neumann loads of any form on facets of the X-FEM model.
#pragma once

#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Quadrature points of the facets (split where a crack crosses them,
/// quadrature/facet_points.h), their outward unit normals, and for each
/// point the vector value of every scalar dof's basis function that is
/// non-zero there.
struct FacetBasis
{
  int dim = 2;
  std::vector<double> points;            ///< (num_points, dim)
  std::vector<double> normals;           ///< (num_points, dim) outward unit normal
  std::vector<double> weights;           ///< (num_points), physical length / area measure
  std::vector<std::int32_t> entry_point; ///< (num_entries) point index
  std::vector<std::int32_t> entry_dof;   ///< (num_entries) global scalar dof
  std::vector<double> entry_value;       ///< (num_entries, dim) basis function value
};

/// facet_cells, facet_local: (num_facets) cell and local facet index (facet
/// f is opposite vertex f). `degree`: Gauss degree on each facet piece.
template <int dim>
FacetBasis compute_facet_basis(std::span<const double> x, std::span<const std::int32_t> cells,
                               const EnrichmentLayout& layout, std::span<const CrackGeometryOf<dim>* const> cracks,
                               std::span<const std::int32_t> facet_cells, std::span<const std::int32_t> facet_local,
                               int degree);

} // namespace cracklip
