// Post-processing of enriched P1 fields on triangles (layer a): the
// solution on sub-triangles, and at the enriched quadrature points of cells
// (the point values in any dimension are displacement.h's).
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

/// Quadrature points of a set of cells (the rules of the stiffness), with the
/// solution's displacement gradient there: for energies and error norms.
struct FieldPoints
{
  std::vector<std::int32_t> cell; ///< (n)
  std::vector<double> ref;        ///< (n, 2) reference coordinates in the cell
  std::vector<double> x;          ///< (n, 2) physical points
  std::vector<double> weight;     ///< (n)
  std::vector<std::int8_t> side;  ///< (n) side of the crack crossing the cell, 0 if none
  std::vector<double> grad_u;     ///< (n, 2, 2) d u_i / d x_j
};

/// cell_list: cells to integrate over (all cells if empty).
FieldPoints compute_field_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                 const EnrichmentLayout& layout,
                                 std::span<const CrackGeometry* const> cracks,
                                 std::span<const double> u,
                                 std::span<const std::int32_t> cell_list,
                                 const QuadratureOptions& options);

} // namespace cracklip
