#include "heaviside_kernels.h"

#include "enriched_basis.h"
#include "quadrature.h"

#include <cmath>

namespace cracklip
{

std::int32_t assemble_enriched_stiffness(const MatrixSink& sink, std::span<const double> x,
                                         std::span<const std::int32_t> cells,
                                         const EnrichmentLayout& layout,
                                         std::span<const CrackGeometry* const> cracks,
                                         double E, double nu, int degree)
{
  const auto D = plane_strain_matrix(E, nu);
  const quadrature::Rule rule = quadrature::triangle(degree);
  std::vector<double> val, grad, Ke, B;
  std::vector<int> side;
  for (const std::int32_t c : layout.cells)
  {
    const P1Cell cell(x, cells, c);
    const CellBasis basis(cell, layout, c);
    const int nf = basis.num_functions();
    const int ndof = 2 * nf;
    Ke.assign(ndof * ndof, 0.0);
    B.assign(3 * ndof, 0.0);

    const CellRegions regions(cracks, c);
    for (int s = 0; s < regions.size(); ++s)
    {
      const auto tri = regions.triangle(s);
      region_sides(cracks, c, regions.side(s), side);
      const double area_ref = 2.0 * regions.area(s);
      for (int q = 0; q < rule.size(); ++q)
      {
        const double u = rule.points[2 * q], v = rule.points[2 * q + 1];
        const std::array<double, 2> r = {tri[0][0] + u * (tri[1][0] - tri[0][0]) + v * (tri[2][0] - tri[0][0]),
                                          tri[0][1] + u * (tri[1][1] - tri[0][1]) + v * (tri[2][1] - tri[0][1])};
        const double w = rule.weights[q] * area_ref * cell.detJ;
        evaluate_basis(cell, basis, layout, side, r, val, grad);
        // B (3, ndof): strain (xx, yy, 2xy) of each vector basis function.
        for (int f = 0; f < nf; ++f)
        {
          const double gx = grad[2 * f], gy = grad[2 * f + 1];
          B[0 * ndof + 2 * f] = gx;
          B[1 * ndof + 2 * f + 1] = gy;
          B[2 * ndof + 2 * f] = gy;
          B[2 * ndof + 2 * f + 1] = gx;
        }
        for (int i = 0; i < ndof; ++i)
        {
          double DB[3];
          for (int a = 0; a < 3; ++a)
            DB[a] = D[3 * a] * B[i] + D[3 * a + 1] * B[ndof + i] + D[3 * a + 2] * B[2 * ndof + i];
          for (int j = 0; j < ndof; ++j)
            Ke[i * ndof + j] += w * (DB[0] * B[j] + DB[1] * B[ndof + j] + DB[2] * B[2 * ndof + j]);
        }
      }
    }
    // DOLFINx owns the standard-standard block.
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        Ke[i * ndof + j] = 0.0;
    sink(basis.dofs, basis.dofs, Ke);
  }
  return static_cast<std::int32_t>(layout.cells.size());
}

FacetBasis compute_facet_basis(std::span<const double> x, std::span<const std::int32_t> cells,
                               const EnrichmentLayout& layout,
                               std::span<const CrackGeometry* const> cracks,
                               std::span<const std::int32_t> facet_cells,
                               std::span<const std::int32_t> facet_local, int degree)
{
  if (facet_cells.size() != facet_local.size())
    throw std::invalid_argument("compute_facet_basis: facet arrays differ in length");
  const quadrature::Rule g = quadrature::gauss_legendre(std::max(1, (degree + 2) / 2));
  constexpr std::array<std::array<double, 2>, 3> ref = {{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}};
  FacetBasis out;
  std::vector<double> val, grad;
  std::vector<int> side;
  for (std::size_t f = 0; f < facet_cells.size(); ++f)
  {
    const std::int32_t c = facet_cells[f];
    const int lf = facet_local[f];
    if (lf < 0 or lf > 2)
      throw std::invalid_argument("compute_facet_basis: local facet index must be 0, 1 or 2");
    const P1Cell cell(x, cells, c);
    const CellBasis basis(cell, layout, c);
    const int a = (lf + 1) % 3, b = (lf + 2) % 3;
    const double len = std::hypot(cell.xv[b][0] - cell.xv[a][0], cell.xv[b][1] - cell.xv[a][1]);
    // Pieces of the facet in parameter t in [0, 1], split where a crack
    // crossing the cell crosses the facet.
    std::vector<double> cuts = {0.0, 1.0};
    const int ic = crossing_crack(cracks, c);
    if (ic >= 0)
    {
      const double fa = cracks[ic]->phi[cell.nodes[a]], fb = cracks[ic]->phi[cell.nodes[b]];
      if (fa * fb < 0.0)
        cuts = {0.0, fa / (fa - fb), 1.0};
    }
    for (std::size_t p = 0; p + 1 < cuts.size(); ++p)
    {
      const double t0 = cuts[p], t1 = cuts[p + 1];
      // Side of the crossing crack on this piece: sign of phi at its middle.
      int s = 0;
      if (ic >= 0)
      {
        const double tm = 0.5 * (t0 + t1);
        const double fm = (1 - tm) * cracks[ic]->phi[cell.nodes[a]] + tm * cracks[ic]->phi[cell.nodes[b]];
        s = fm >= 0.0 ? 1 : -1;
      }
      region_sides(cracks, c, s, side);
      for (int q = 0; q < g.size(); ++q)
      {
        const double t = t0 + (t1 - t0) * g.points[q];
        const std::array<double, 2> r = {ref[a][0] + t * (ref[b][0] - ref[a][0]),
                                          ref[a][1] + t * (ref[b][1] - ref[a][1])};
        evaluate_basis(cell, basis, layout, side, r, val, grad);
        const auto xp = cell.physical(r);
        const std::int32_t ip = static_cast<std::int32_t>(out.weights.size());
        out.points.insert(out.points.end(), xp.begin(), xp.end());
        out.weights.push_back(g.weights[q] * (t1 - t0) * len);
        for (int fn = 0; fn < basis.num_functions(); ++fn)
        {
          if (val[fn] == 0.0)
            continue;
          out.entry_point.push_back(ip);
          out.entry_node.push_back(basis.dofs[2 * fn] / 2);
          out.entry_value.push_back(val[fn]);
        }
      }
    }
  }
  return out;
}

} // namespace cracklip
