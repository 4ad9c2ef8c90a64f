// The stiffness of the enriched cells (layer a), in any dimension.
#pragma once

#include "assembly/matrix_sink.h"
#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry.h"
#include "quadrature/cell_quadrature.h"

#include <cstdint>
#include <span>

namespace cracklip
{

/// Stiffness of every enriched cell (compute_enriched_cell_quadrature:
/// sub-cells in crossed cells, rules collapsed onto a tip / the front where
/// tip functions live). Writes each cell's element matrix over (standard
/// dofs, enriched dofs), symmetric, with its standard-standard block set to
/// zero (DOLFINx assembles that block on the whole mesh), through `sink`.
///
/// x: (num_nodes, dim); cells: (num_cells, dim + 1); E, nu: the isotropic
/// material (plane strain in 2D). Returns the number of cells integrated
/// (= layout.cells.size()).
template <int dim>
std::int32_t assemble_enriched_stiffness(const MatrixSink& sink, std::span<const double> x,
                                         std::span<const std::int32_t> cells, const EnrichmentLayout& layout,
                                         std::span<const CrackGeometryOf<dim>* const> cracks, double E, double nu,
                                         const QuadratureOptionsOf<dim>& options);

} // namespace cracklip
