#include "fields.h"

#include "enriched_basis.h"

#include <stdexcept>

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

std::vector<double> evaluate_displacement(std::span<const double> x,
                                          std::span<const std::int32_t> cells,
                                          const EnrichmentLayout& layout,
                                          std::span<const CrackGeometry* const> cracks,
                                          std::span<const double> u,
                                          std::span<const std::int32_t> point_cells,
                                          std::span<const double> ref_points,
                                          std::span<const std::int8_t> sides)
{
  check_size(u, layout);
  const std::size_t n = point_cells.size();
  if (ref_points.size() != 2 * n or sides.size() != n)
    throw std::invalid_argument("evaluate_displacement: expected ref_points (n, 2) and sides (n)");
  std::vector<double> out(2 * n, 0.0), val, grad;
  std::vector<int> side;
  const std::size_t num_cells = cells.size() / 3;
  for (std::size_t p = 0; p < n; ++p)
  {
    const std::int32_t c = point_cells[p];
    if (c < 0 or static_cast<std::size_t>(c) >= num_cells)
      throw std::invalid_argument("evaluate_displacement: cell index out of range");
    const P1Cell cell(x, cells, c);
    const CellBasis basis(cell, layout, c);
    const std::array<double, 2> r = {ref_points[2 * p], ref_points[2 * p + 1]};
    int s = sides[p];
    const int ic = crossing_crack(cracks, c);
    if (s == 0 and ic >= 0)
    {
      const auto N = P1Cell::shape(r);
      double phi = 0.0;
      for (int a = 0; a < 3; ++a)
        phi += N[a] * cracks[ic]->phi[cell.nodes[a]];
      s = phi >= 0.0 ? 1 : -1;
    }
    region_sides(cracks, c, s, side);
    evaluate_basis(cell, basis, layout, side, r, val, grad);
    for (int f = 0; f < basis.num_functions(); ++f)
      for (int d = 0; d < 2; ++d)
        out[2 * p + d] += val[f] * u[basis.dofs[2 * f + d]];
  }
  return out;
}

SubcellFields compute_subcell_fields(std::span<const double> x, std::span<const std::int32_t> cells,
                                     const EnrichmentLayout& layout,
                                     std::span<const CrackGeometry* const> cracks,
                                     std::span<const double> u, double E, double nu)
{
  check_size(u, layout);
  const auto D = plane_strain_matrix(E, nu);
  const std::size_t num_cells = cells.size() / 3;
  SubcellFields out;
  out.points.reserve(6 * num_cells);
  std::vector<double> val, grad;
  std::vector<int> side;
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const P1Cell cell(x, cells, static_cast<std::int32_t>(c));
    const CellBasis basis(cell, layout, static_cast<std::int32_t>(c));
    const CellRegions regions(cracks, static_cast<std::int32_t>(c));
    for (int s = 0; s < regions.size(); ++s)
    {
      const auto tri = regions.triangle(s);
      const int sd = regions.side(s);
      region_sides(cracks, static_cast<std::int32_t>(c), sd, side);
      for (int i = 0; i < 3; ++i)
      {
        const auto xp = cell.physical(tri[i]);
        out.points.insert(out.points.end(), xp.begin(), xp.end());
        evaluate_basis(cell, basis, layout, side, tri[i], val, grad);
        double ud[2] = {0.0, 0.0};
        for (int f = 0; f < basis.num_functions(); ++f)
          for (int d = 0; d < 2; ++d)
            ud[d] += val[f] * u[basis.dofs[2 * f + d]];
        out.displacement.push_back(ud[0]);
        out.displacement.push_back(ud[1]);
      }
      const std::array<double, 2> rc = {(tri[0][0] + tri[1][0] + tri[2][0]) / 3.0,
                                         (tri[0][1] + tri[1][1] + tri[2][1]) / 3.0};
      evaluate_basis(cell, basis, layout, side, rc, val, grad);
      double eps[3] = {0.0, 0.0, 0.0};
      for (int f = 0; f < basis.num_functions(); ++f)
      {
        const double ux = u[basis.dofs[2 * f]], uy = u[basis.dofs[2 * f + 1]];
        eps[0] += grad[2 * f] * ux;
        eps[1] += grad[2 * f + 1] * uy;
        eps[2] += grad[2 * f + 1] * ux + grad[2 * f] * uy;
      }
      double sig[3];
      for (int a = 0; a < 3; ++a)
        sig[a] = D[3 * a] * eps[0] + D[3 * a + 1] * eps[1] + D[3 * a + 2] * eps[2];
      out.stress.insert(out.stress.end(), sig, sig + 3);
      const double area = cell.detJ * regions.area(s);
      out.strain_energy += 0.5 * area * (sig[0] * eps[0] + sig[1] * eps[1] + sig[2] * eps[2]);
      out.parent.push_back(static_cast<std::int32_t>(c));
      out.side.push_back(static_cast<std::int8_t>(sd));
    }
  }
  return out;
}

} // namespace cracklip
