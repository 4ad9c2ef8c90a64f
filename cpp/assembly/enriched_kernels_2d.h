// Enriched element kernels on cells with an enriched node (layer a).
#pragma once

#include "quadrature/cell_quadrature_2d.h"
#include "geometry/crack_geometry_2d.h"
#include "assembly/matrix_sink.h"
#include "enrichment/enrichment_layout.h"

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace cracklip
{


/// Stiffness of every enriched cell (cell_quadrature: sub-cells in crossed
/// cells, quasi-polar rule where tip functions live). Writes each cell's
/// element matrix over (standard dofs, enriched dofs) with its
/// standard-standard block set to zero (DOLFINx assembles that block on the
/// whole mesh), through `sink`.
///
/// x: (num_nodes, 2); cells: (num_cells, 3); E, nu: plane-strain material.
/// Returns the number of cells integrated (= layout.cells.size()).
std::int32_t assemble_enriched_stiffness(const MatrixSink& sink, std::span<const double> x,
                                         std::span<const std::int32_t> cells,
                                         const EnrichmentLayout& layout,
                                         std::span<const CrackGeometry* const> cracks,
                                         double E, double nu, const QuadratureOptions& options);

/// Basis functions on boundary facets, for Neumann loads of any form:
/// quadrature points of the facets (split at a crack crossing them), and for
/// each point the vector value of every scalar dof's basis function that is
/// non-zero there.
struct FacetBasis
{
  std::vector<double> points;            ///< (num_points, 2)
  std::vector<double> weights;           ///< (num_points), physical length measure
  std::vector<std::int32_t> entry_point; ///< (num_entries) point index
  std::vector<std::int32_t> entry_dof;   ///< (num_entries) global scalar dof
  std::vector<double> entry_value;       ///< (num_entries, 2) basis function value
};

/// facet_cells, facet_local: (num_facets) cell and local facet index (facet
/// f is opposite vertex f). `degree`: Gauss degree on each facet piece.
FacetBasis compute_facet_basis(std::span<const double> x, std::span<const std::int32_t> cells,
                               const EnrichmentLayout& layout,
                               std::span<const CrackGeometry* const> cracks,
                               std::span<const std::int32_t> facet_cells,
                               std::span<const std::int32_t> facet_local, int degree);

} // namespace cracklip
