#include "post/fields_2d.h"

#include "assembly/elasticity.h"
#include "enrichment/enriched_basis.h"
#include "post/displacement.h"

#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
void check_size(std::span<const double> u, const EnrichmentLayout& layout)
{
  if (u.size() != 2 * static_cast<std::size_t>(layout.num_nodes_total()))
    throw std::invalid_argument("solution vector has " + std::to_string(u.size())
                                + " entries, expected "
                                + std::to_string(2 * layout.num_nodes_total()));
}
} // namespace

SubcellFields compute_subcell_fields(std::span<const double> x, std::span<const std::int32_t> cells,
                                     const EnrichmentLayout& layout,
                                     std::span<const CrackGeometry* const> cracks,
                                     std::span<const double> u, double E, double nu)
{
  check_size(u, layout);
  const auto D = elasticity_matrix<2>(E, nu);
  const std::size_t num_cells = cells.size() / 3;
  SubcellFields out;
  out.points.reserve(6 * num_cells);
  std::vector<double> val, grad;
  std::vector<int> side;
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const auto ci = static_cast<std::int32_t>(c);
    const P1Cell cell(x, cells, ci);
    const CellBasis basis(cell, layout, ci);
    const CellRegions regions(cracks, ci);
    for (int s = 0; s < regions.size(); ++s)
    {
      const auto tri = regions.triangle(s);
      const int sd = regions.side(s);
      region_sides(cracks, ci, sd, side);
      for (int i = 0; i < 3; ++i)
      {
        const auto xp = cell.physical(tri[i]);
        out.points.insert(out.points.end(), xp.begin(), xp.end());
        evaluate_basis<2>(cell, basis, layout, cracks, side, tri[i], val, grad);
        double ud[2] = {0.0, 0.0};
        add_point_values<2>(basis, u, val, grad, ud, nullptr);
        out.displacement.insert(out.displacement.end(), ud, ud + 2);
      }
      const std::array<double, 2> rc = {(tri[0][0] + tri[1][0] + tri[2][0]) / 3.0,
                                         (tri[0][1] + tri[1][1] + tri[2][1]) / 3.0};
      evaluate_basis<2>(cell, basis, layout, cracks, side, rc, val, grad);
      double g[4] = {0.0, 0.0, 0.0, 0.0};
      add_point_values<2>(basis, u, val, grad, nullptr, g);
      const double eps[3] = {g[0], g[3], g[1] + g[2]};
      for (int a = 0; a < 3; ++a)
        out.stress.push_back(D[3 * a] * eps[0] + D[3 * a + 1] * eps[1] + D[3 * a + 2] * eps[2]);
      out.parent.push_back(ci);
      out.side.push_back(static_cast<std::int8_t>(sd));
    }
  }
  return out;
}

} // namespace cracklip
