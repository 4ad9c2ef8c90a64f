// Post-processing of enriched P1 fields (layer a).
#pragma once

#include "crack_geometry.h"
#include "enrichment.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Displacement at points given by cell and reference coordinates.
/// u: scalar dofs (2 * layout.num_nodes_total()); point_cells (n);
/// ref_points (n, 2); sides (n): +1 / -1 evaluates the + / - lip of a crack
/// crossing the cell (the polynomial of that side), 0 the side the point lies
/// on (+ on the crack itself). Returns (n, 2).
std::vector<double> evaluate_displacement(std::span<const double> x,
                                          std::span<const std::int32_t> cells,
                                          const EnrichmentLayout& layout,
                                          std::span<const CrackGeometry* const> cracks,
                                          std::span<const double> u,
                                          std::span<const std::int32_t> point_cells,
                                          std::span<const double> ref_points,
                                          std::span<const std::int8_t> sides);

/// The solution on a mesh of sub-triangles: every uncrossed cell is one
/// sub-triangle, every crossed cell contributes its sub-triangles. Vertices
/// are not shared between sub-triangles, so an opening crack shows.
struct SubcellFields
{
  std::vector<double> points;          ///< (3 * num_sub, 2) sub-triangle vertices
  std::vector<double> displacement;    ///< (3 * num_sub, 2) at those vertices
  std::vector<double> stress;          ///< (num_sub, 3) xx, yy, xy at the centroid
  std::vector<std::int32_t> parent;    ///< (num_sub) parent cell
  std::vector<std::int8_t> side;       ///< (num_sub) side of the crossing crack, 0 if none
  double strain_energy = 0.0;          ///< 1/2 int sigma : eps over the mesh
};

SubcellFields compute_subcell_fields(std::span<const double> x, std::span<const std::int32_t> cells,
                                     const EnrichmentLayout& layout,
                                     std::span<const CrackGeometry* const> cracks,
                                     std::span<const double> u, double E, double nu);

} // namespace cracklip
