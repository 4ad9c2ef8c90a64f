// The X-FEM displacement and its gradient (layer a), in any dimension: at
// given points, and at the quadrature points of cells.
#pragma once

#include "enrichment/enrichment_layout.h"
#include "enrichment/enriched_basis.h"
#include "geometry/crack_geometry.h"
#include "quadrature/cell_quadrature.h"

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

/// Quadrature points of a set of cells (the enriched stiffness's rules,
/// compute_enriched_cell_quadrature), with the solution's displacement
/// gradient there: for energies and error norms.
struct FieldPoints
{
  std::vector<std::int32_t> cell; ///< (n)
  std::vector<double> ref;        ///< (n, dim) reference coordinates in the cell
  std::vector<double> x;          ///< (n, dim) physical points
  std::vector<double> weight;     ///< (n)
  std::vector<std::int8_t> side;  ///< (n) side of the crack crossing the cell, 0 if none
  std::vector<double> grad_u;     ///< (n, dim, dim) d u_i / d x_j
};

/// cell_list: cells to integrate over (all cells if empty).
template <int dim>
FieldPoints compute_field_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                 const EnrichmentLayout& layout, std::span<const CrackGeometryOf<dim>* const> cracks,
                                 std::span<const double> u, std::span<const std::int32_t> cell_list,
                                 const QuadratureOptionsOf<dim>& options);

/// u (dim) and grad u (dim, dim) at one point from the basis values there
/// (evaluate_basis: val, grad), added into u_out and grad_out (either may
/// be null).
template <int dim>
void add_point_values(const EnrichedCellBasis<dim>& basis, std::span<const double> u, const std::vector<double>& val,
                      const std::vector<double>& grad, double* u_out, double* grad_out)
{
  for (int i = 0; i < basis.num_dofs(); ++i)
  {
    const double ui = u[basis.dofs[i]];
    if (ui == 0.0)
      continue;
    for (int a = 0; a < dim; ++a)
    {
      if (u_out)
        u_out[a] += val[dim * i + a] * ui;
      if (grad_out)
        for (int b = 0; b < dim; ++b)
          grad_out[dim * a + b] += grad[(dim * i + a) * dim + b] * ui;
    }
  }
}

} // namespace cracklip
