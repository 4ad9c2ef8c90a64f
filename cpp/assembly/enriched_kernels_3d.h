// Enriched element kernels on tetrahedra with an enriched node (layer a).
#pragma once

#include "assembly/matrix_sink.h"
#include "enrichment/enriched_basis_3d.h"
#include "enrichment/enrichment_layout_3d.h"
#include "geometry/crack_geometry_3d.h"
#include "quadrature/cell_quadrature_3d.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Quadrature of an enriched cell: the crack geometry's per-cell rule where
/// a crack crosses the cell (sub-tetrahedra, collapsed at the front; Gauss
/// graded by the distance (front_function_degree) on the sub-tetrahedra away from the
/// front when the cell carries front functions); in a
/// cell that carries front functions without being crossed, the near-front
/// rule (signed cones from the cell's P1 front line) when that line passes
/// within options.near_factor diameters of its nearest vertex, else Gauss of
/// front_function_degree (graded by the distance to the front); Gauss of
/// options.degree otherwise. Sides: the crossing crack's sub-tetrahedra, else 0.
void compute_enriched_cell_quadrature_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                         const EnrichmentLayout3D& layout,
                                         std::span<const CrackGeometry3D* const> cracks, std::int32_t c,
                                         const QuadratureOptions3D& options, CellQuadrature3D& out);

/// The side of every crack at a quadrature point of cell c: the point's side
/// for the crack crossing the cell (class cut, face or front), the cell's
/// side for the others (0 on their extension cells).
void region_sides_3d(std::span<const CrackGeometry3D* const> cracks, std::int32_t c, int crossing_side,
                     std::vector<int>& side);

/// Stiffness of every enriched cell: each cell's element matrix over
/// (standard dofs, enriched dofs) with its standard-standard block set to
/// zero (DOLFINx assembles that block on the whole mesh), through `sink`.
/// x: (num_nodes, 3); cells: (num_cells, 4); E, nu: isotropic material.
/// Returns the number of cells integrated.
std::int32_t assemble_enriched_stiffness_3d(const MatrixSink& sink, std::span<const double> x,
                                            std::span<const std::int32_t> cells, const EnrichmentLayout3D& layout,
                                            std::span<const CrackGeometry3D* const> cracks, double E, double nu,
                                            const QuadratureOptions3D& options);

/// Displacement (n, 3) and, if grad is not null, its gradient (n, 3, 3)
/// (grad[p][i][j] = d u_i / d x_j) at points given by cell and reference
/// coordinates (n, 3). u: scalar dofs (3 * layout.num_nodes_total()); sides
/// (n): +1 / -1 evaluates that lip of a crack crossing the cell, 0 the side
/// the point lies on (sign of phi there; + on the crack).
std::vector<double> evaluate_displacement_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                             const EnrichmentLayout3D& layout,
                                             std::span<const CrackGeometry3D* const> cracks, std::span<const double> u,
                                             std::span<const std::int32_t> point_cells,
                                             std::span<const double> ref_points, std::span<const std::int8_t> sides,
                                             std::vector<double>* grad = nullptr);

} // namespace cracklip
