// The X-FEM solution on sub-triangles (layer a): the picture of a 2D field
// with its cracks open (point values in any dimension: displacement.h).
#pragma once

#include "quadrature/cell_quadrature_2d.h"
#include "geometry/crack_geometry_2d.h"
#include "enrichment/enrichment_layout.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// The solution on a mesh of sub-triangles: every uncrossed cell is one
/// sub-triangle, every crossed cell contributes its sub-triangles. Vertices
/// are not shared between sub-triangles, so an opening crack shows.
struct SubcellFields
{
  std::vector<double> points;       ///< (3 * num_sub, 2) sub-triangle vertices
  std::vector<double> displacement; ///< (3 * num_sub, 2) at those vertices
  std::vector<double> stress;       ///< (num_sub, 3) xx, yy, xy at the centroid
  std::vector<std::int32_t> parent; ///< (num_sub) parent cell
  std::vector<std::int8_t> side;    ///< (num_sub) side of the crossing crack, 0 if none
};

SubcellFields compute_subcell_fields(std::span<const double> x, std::span<const std::int32_t> cells,
                                     const EnrichmentLayout& layout,
                                     std::span<const CrackGeometry* const> cracks,
                                     std::span<const double> u, double E, double nu);

} // namespace cracklip
