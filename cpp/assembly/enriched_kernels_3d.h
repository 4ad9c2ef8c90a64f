// Enriched element kernels on tetrahedra with an enriched node (layer a).
#pragma once

#include "assembly/matrix_sink.h"
#include "enrichment/enriched_basis_3d.h"
#include "enrichment/enrichment_layout_3d.h"

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace cracklip
{

/// Quadrature points of one cell: reference coordinates (n, 3), physical
/// weights (n) (volume measure) and the side (n) of the crack crossing the
/// cell (+1 / -1; 0 where no crack crosses it).
struct CellQuadrature3D
{
  std::vector<double> ref;
  std::vector<double> weight;
  std::vector<std::int8_t> side;
  void clear() { ref.clear(), weight.clear(), side.clear(); }
  int size() const { return static_cast<int>(weight.size()); }
};

/// Fills the quadrature of a cell (sub-tetrahedra where a crack crosses it,
/// collapsed rules at the front: the geometry's per-cell rules).
using CellRule3D = std::function<void(std::int32_t cell, CellQuadrature3D& out)>;

/// The side of every crack at a quadrature point of cell c: the point's side
/// for the crack crossing the cell (class cut, face or front), the cell's
/// side for the others (0 on their extension cells).
void region_sides_3d(std::span<const CrackFields3D> cracks, std::int32_t c, int crossing_side, std::vector<int>& side);

/// Stiffness of every enriched cell: each cell's element matrix over
/// (standard dofs, enriched dofs) with its standard-standard block set to
/// zero (DOLFINx assembles that block on the whole mesh), through `sink`.
/// x: (num_nodes, 3); cells: (num_cells, 4); E, nu: isotropic material.
/// Returns the number of cells integrated.
std::int32_t assemble_enriched_stiffness_3d(const MatrixSink& sink, std::span<const double> x,
                                            std::span<const std::int32_t> cells, const EnrichmentLayout3D& layout,
                                            std::span<const CrackFields3D> cracks, double E, double nu,
                                            const CellRule3D& rule);

/// Displacement (n, 3) and, if grad is not null, its gradient (n, 3, 3)
/// (grad[p][i][j] = d u_i / d x_j) at points given by cell and reference
/// coordinates (n, 3). u: scalar dofs (3 * layout.num_nodes_total()); sides
/// (n): +1 / -1 evaluates that lip of a crack crossing the cell, 0 the side
/// the point lies on (sign of phi there; + on the crack).
std::vector<double> evaluate_displacement_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                             const EnrichmentLayout3D& layout, std::span<const CrackFields3D> cracks,
                                             std::span<const double> u, std::span<const std::int32_t> point_cells,
                                             std::span<const double> ref_points, std::span<const std::int8_t> sides,
                                             std::vector<double>* grad = nullptr);

} // namespace cracklip
