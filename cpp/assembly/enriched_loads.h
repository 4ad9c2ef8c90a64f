// Loads on enriched dofs (layer a), in any dimension: tractions on the crack
// lips, and body forces and initial stresses inside enriched cells.
// Standard dofs are DOLFINx's (their functions do not see the crack); only
// the pseudo-nodes' dofs are written here. Boundary tractions go through
// facet_basis.h.
#pragma once

#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry.h"

#include <cstdint>
#include <span>

namespace cracklip
{

/// Lip tractions of crack `crack` at points on its lips (cell (n), ref (n,
/// dim), weight (n)): traction (n, dim) acts on the + lip and its opposite
/// on the - lip, so b[j] += sum_p weight_p traction_p . [[N_j]](p) ([[.]] =
/// + lip minus - lip) for every enriched dof j. A pressure p pushing the
/// lips apart is the traction p n on the + lip (n the normal pointing to the
/// + side). b: (dim layout.num_nodes_total()).
template <int dim>
void assemble_lip_load(std::span<const double> x, std::span<const std::int32_t> cells,
                       const EnrichmentLayout& layout, std::span<const CrackGeometryOf<dim>* const> cracks,
                       std::int32_t crack, std::span<const std::int32_t> point_cells, std::span<const double> ref,
                       std::span<const double> weights, std::span<const double> traction, std::span<double> b);

/// Body force f (n, dim) and initial stress s (n, voigt: 2D xx, yy, xy; 3D
/// xx, yy, zz, yz, xz, xy; or empty: none) at quadrature points (cell (n),
/// ref (n, dim), side (n) as the stiffness rules give them, weight (n)) of
/// enriched cells: b[j] += sum_p weight_p (f_p . N_j(p) - s_p : eps(N_j)(p))
/// for every enriched dof j of the cell.
template <int dim>
void assemble_cell_load(std::span<const double> x, std::span<const std::int32_t> cells,
                        const EnrichmentLayout& layout, std::span<const CrackGeometryOf<dim>* const> cracks,
                        std::span<const std::int32_t> point_cells, std::span<const double> ref,
                        std::span<const std::int8_t> sides, std::span<const double> weights,
                        std::span<const double> force, std::span<const double> stress, std::span<double> b);

} // namespace cracklip
