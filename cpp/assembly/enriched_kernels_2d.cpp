#include "assembly/enriched_kernels_2d.h"

#include "enrichment/enriched_basis_2d.h"
#include "quadrature/rules.h"

#include <cmath>

namespace cracklip
{

std::int32_t assemble_enriched_stiffness(const MatrixSink& sink, std::span<const double> x,
                                         std::span<const std::int32_t> cells,
                                         const EnrichmentLayout& layout,
                                         std::span<const CrackGeometry* const> cracks,
                                         double E, double nu, const QuadratureOptions& options)
{
  const auto D = plane_strain_matrix(E, nu);
  std::vector<double> val, grad, Ke, B;
  std::vector<int> side;
  CellQuadrature qp;
  for (const std::int32_t c : layout.cells)
  {
    const P1Cell cell(x, cells, c);
    const CellBasis basis(cell, layout, c);
    const int ndof = basis.num_dofs();
    Ke.assign(ndof * ndof, 0.0);
    B.assign(3 * ndof, 0.0);
    compute_cell_quadrature(cell, c, cracks, cell_tip(cell, basis, layout), options, qp);
    for (int q = 0; q < qp.size(); ++q)
    {
      region_sides(cracks, c, qp.side[q], side);
      evaluate_basis(cell, basis, layout, side, {qp.ref[2 * q], qp.ref[2 * q + 1]}, val, grad);
      // B (3, ndof): strain (xx, yy, 2xy) of each basis function.
      for (int i = 0; i < ndof; ++i)
      {
        const double* g = &grad[4 * i];
        B[i] = g[0];
        B[ndof + i] = g[3];
        B[2 * ndof + i] = g[1] + g[2];
      }
      const double w = qp.weight[q];
      for (int i = 0; i < ndof; ++i)
      {
        double DB[3];
        for (int a = 0; a < 3; ++a)
          DB[a] = w * (D[3 * a] * B[i] + D[3 * a + 1] * B[ndof + i] + D[3 * a + 2] * B[2 * ndof + i]);
        if (DB[0] == 0.0 and DB[1] == 0.0 and DB[2] == 0.0)
          continue;
        for (int j = 0; j < ndof; ++j)
          Ke[i * ndof + j] += DB[0] * B[j] + DB[1] * B[ndof + j] + DB[2] * B[2 * ndof + j];
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
    // crossing (or ending in) the cell crosses the facet.
    std::vector<double> cuts = {0.0, 1.0};
    int ic = -1;
    for (std::size_t k = 0; k < cracks.size(); ++k)
      if (cracks[k]->crack_cell_index[c] >= 0 or cracks[k]->tip_cell_index[c] >= 0)
        ic = static_cast<int>(k);
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
        const auto ip = static_cast<std::int32_t>(out.weights.size());
        out.points.insert(out.points.end(), xp.begin(), xp.end());
        out.weights.push_back(g.weights[q] * (t1 - t0) * len);
        for (int i = 0; i < basis.num_dofs(); ++i)
        {
          if (val[2 * i] == 0.0 and val[2 * i + 1] == 0.0)
            continue;
          out.entry_point.push_back(ip);
          out.entry_dof.push_back(basis.dofs[i]);
          out.entry_value.push_back(val[2 * i]);
          out.entry_value.push_back(val[2 * i + 1]);
        }
      }
    }
  }
  return out;
}

} // namespace cracklip
