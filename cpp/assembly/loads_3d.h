// Loads on a tetrahedral X-FEM model (layer a): the basis on boundary
// facets (any traction), tractions on the crack lips, and body forces inside
// enriched cells. The 3D counterparts of loads_2d and compute_facet_basis.
#pragma once

#include "enrichment/enrichment_layout_3d.h"
#include "geometry/crack_geometry_3d.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Basis functions on boundary facets: quadrature points of the facets
/// (split where a crack crosses them), their outward unit normals, and for
/// each point the vector value of every scalar dof's basis function that is
/// non-zero there.
struct FacetBasis3D
{
  std::vector<double> points;            ///< (num_points, 3)
  std::vector<double> normals;           ///< (num_points, 3) outward unit normal
  std::vector<double> weights;           ///< (num_points), physical area measure
  std::vector<std::int32_t> entry_point; ///< (num_entries) point index
  std::vector<std::int32_t> entry_dof;   ///< (num_entries) global scalar dof
  std::vector<double> entry_value;       ///< (num_entries, 3) basis function value
};

/// facet_cells, facet_local: (num_facets) cell and local facet index (facet
/// f is opposite vertex f). `degree`: Gauss degree on each facet piece.
FacetBasis3D compute_facet_basis_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                    const EnrichmentLayout3D& layout, std::span<const CrackGeometry3D* const> cracks,
                                    std::span<const std::int32_t> facet_cells,
                                    std::span<const std::int32_t> facet_local, int degree);

/// Lip tractions of crack `crack` at points on its lip facets (cell (n),
/// ref (n, 3), weight (n)): traction (n, 3) acts on the + lip and its
/// opposite on the - lip, so b[j] += sum_p w_p traction_p . [[N_j]](p)
/// ([[.]] = + lip minus - lip) for every enriched dof j. A pressure p
/// pushing the lips apart is the traction p n (n the normal to the + side).
/// b: (3 layout.num_nodes_total()).
void assemble_lip_load_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                          const EnrichmentLayout3D& layout, std::span<const CrackGeometry3D* const> cracks,
                          std::int32_t crack, std::span<const std::int32_t> point_cells, std::span<const double> ref,
                          std::span<const double> weights, std::span<const double> traction, std::span<double> b);

/// Body force f (n, 3) at quadrature points (cell (n), ref (n, 3), side (n)
/// as the stiffness rules give them, weight (n)) of enriched cells:
/// b[j] += sum_p w_p f_p . N_j(p) for every enriched dof j.
void assemble_cell_load_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                           const EnrichmentLayout3D& layout, std::span<const CrackGeometry3D* const> cracks,
                           std::span<const std::int32_t> point_cells, std::span<const double> ref,
                           std::span<const std::int8_t> sides, std::span<const double> weights,
                           std::span<const double> force, std::span<double> b);

} // namespace cracklip
