#include "assembly/loads_2d.h"

#include "enrichment/enriched_basis_2d.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace cracklip
{
namespace
{
void check(std::size_t n, std::span<const double> ref, std::span<const double> weights,
           std::span<const double> b, const EnrichmentLayout& layout, const char* what)
{
  if (ref.size() != 2 * n or weights.size() != n)
    throw std::invalid_argument(std::string(what) + ": expected ref (n, 2) and weights (n)");
  if (b.size() != 2 * static_cast<std::size_t>(layout.num_nodes_total()))
    throw std::invalid_argument(std::string(what) + ": the load vector has the wrong size");
}
} // namespace

void assemble_lip_load(std::span<const double> x, std::span<const std::int32_t> cells,
                       const EnrichmentLayout& layout, std::span<const CrackGeometry* const> cracks,
                       std::int32_t crack, std::span<const std::int32_t> point_cells,
                       std::span<const double> ref, std::span<const double> weights,
                       std::span<const double> traction, std::span<double> b)
{
  const std::size_t n = point_cells.size();
  check(n, ref, weights, b, layout, "assemble_lip_load");
  if (traction.size() != 2 * n)
    throw std::invalid_argument("assemble_lip_load: expected traction (n, 2)");
  if (crack < 0 or static_cast<std::size_t>(crack) >= cracks.size())
    throw std::invalid_argument("assemble_lip_load: crack index out of range");
  std::vector<double> vp, vm, grad;
  std::vector<int> side;
  for (std::size_t p = 0; p < n; ++p)
  {
    const double tx = traction[2 * p], ty = traction[2 * p + 1];
    if (tx == 0.0 and ty == 0.0)
      continue;
    const std::int32_t c = point_cells[p];
    const P1Cell cell(x, cells, c);
    const CellBasis basis(cell, layout, c);
    const std::array<double, 2> r = {ref[2 * p], ref[2 * p + 1]};
    region_sides(cracks, c, 1, side);
    side[crack] = 1;
    evaluate_basis(cell, basis, layout, side, r, vp, grad);
    side[crack] = -1;
    evaluate_basis(cell, basis, layout, side, r, vm, grad);
    for (int j = 6; j < basis.num_dofs(); ++j) // standard functions (first 6) do not jump
      b[basis.dofs[j]] += weights[p] * ((vp[2 * j] - vm[2 * j]) * tx + (vp[2 * j + 1] - vm[2 * j + 1]) * ty);
  }
}

void assemble_cell_load(std::span<const double> x, std::span<const std::int32_t> cells,
                        const EnrichmentLayout& layout, std::span<const CrackGeometry* const> cracks,
                        std::span<const std::int32_t> point_cells, std::span<const double> ref,
                        std::span<const std::int8_t> sides, std::span<const double> weights,
                        std::span<const double> force, std::span<const double> stress,
                        std::span<double> b)
{
  const std::size_t n = point_cells.size();
  check(n, ref, weights, b, layout, "assemble_cell_load");
  if (sides.size() != n or force.size() != 2 * n or stress.size() != 3 * n)
    throw std::invalid_argument("assemble_cell_load: expected sides (n), force (n, 2), stress (n, 3)");
  std::vector<double> val, grad;
  std::vector<int> side;
  for (std::size_t p = 0; p < n; ++p)
  {
    const std::int32_t c = point_cells[p];
    const P1Cell cell(x, cells, c);
    const CellBasis basis(cell, layout, c);
    if (basis.enr.empty())
      continue;
    const std::array<double, 2> r = {ref[2 * p], ref[2 * p + 1]};
    region_sides(cracks, c, sides[p], side);
    evaluate_basis(cell, basis, layout, side, r, val, grad);
    const double fx = force[2 * p], fy = force[2 * p + 1];
    const double sxx = stress[3 * p], syy = stress[3 * p + 1], sxy = stress[3 * p + 2];
    for (int j = 6; j < basis.num_dofs(); ++j)
    {
      const double* g = &grad[4 * j]; // d val_a / d x_b at g[2 a + b]
      const double work = fx * val[2 * j] + fy * val[2 * j + 1]
                          - (sxx * g[0] + syy * g[3] + sxy * (g[1] + g[2]));
      b[basis.dofs[j]] += weights[p] * work;
    }
  }
}

} // namespace cracklip
