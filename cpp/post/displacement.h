// The X-FEM displacement and its gradient at points (layer a), in any
// dimension.
#pragma once

#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Displacement (n, dim) and, if grad is not null, its gradient (n, dim,
/// dim) (grad[p][i][j] = d u_i / d x_j) at points given by cell (n) and
/// reference coordinates (n, dim). u: scalar dofs (dim *
/// layout.num_nodes_total()); sides (n): +1 / -1 evaluates the + / - lip of a
/// crack crossing the cell (the polynomial of that side), 0 the side the
/// point lies on (sign of phi there; + on the crack itself).
template <int dim>
std::vector<double> evaluate_displacement(std::span<const double> x, std::span<const std::int32_t> cells,
                                          const EnrichmentLayout& layout,
                                          std::span<const CrackGeometryOf<dim>* const> cracks,
                                          std::span<const double> u, std::span<const std::int32_t> point_cells,
                                          std::span<const double> ref_points, std::span<const std::int8_t> sides,
                                          std::vector<double>* grad = nullptr);

} // namespace cracklip
