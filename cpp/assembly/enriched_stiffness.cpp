#include "assembly/enriched_stiffness.h"

#include "assembly/elasticity.h"
#include "enrichment/enriched_basis.h"

#include <vector>

namespace cracklip
{
namespace
{
/// Ke += w B^T D B for B (nv, nd) row-major (DB: scratch). The same product
/// in both dimensions, summed in two orders:
///   - 3D: DB = D B once, then Ke += (w B_k)^T DB_k component by component
///     on the upper triangle, row by row over contiguous columns
///     (vectorisable), skipping the zeros of B (a standard or Heaviside dof
///     strains 3 of the 6 components); the caller mirrors the lower triangle.
///   - 2D: entry by entry, Ke_ij += (w D B_i) . B_j, on the whole matrix: the
///     order of the published 2D results. Any other order moves them by
///     round-off first, which the solve amplifies (K by up to 5e-8 relative
///     on the shipped scenes) and crack growth turns into other paths (a
///     kink angle 2 % off after 20 steps of drilled_plate).
template <int dim>
void add_btdb(double w, const std::array<double, voigt_size<dim> * voigt_size<dim>>& D, const std::vector<double>& B,
              int nd, std::vector<double>& DB, std::vector<double>& Ke)
{
  constexpr int nv = voigt_size<dim>;
  if constexpr (dim == 3)
  {
    DB.assign(nv * static_cast<std::size_t>(nd), 0.0);
    for (int k = 0; k < nv; ++k)
      for (int s = 0; s < nv; ++s)
        if (const double d = D[nv * k + s]; d != 0.0)
          for (int i = 0; i < nd; ++i)
            DB[k * nd + i] += d * B[s * nd + i];
    for (int k = 0; k < nv; ++k)
    {
      const double* Bk = &B[k * nd];
      const double* DBk = &DB[k * nd];
      for (int i = 0; i < nd; ++i)
      {
        const double b = w * Bk[i];
        if (b == 0.0)
          continue;
        double* row = &Ke[i * nd];
        for (int j = i; j < nd; ++j)
          row[j] += b * DBk[j];
      }
    }
  }
  else
  {
    for (int i = 0; i < nd; ++i)
    {
      double DBi[nv];
      bool zero = true;
      for (int k = 0; k < nv; ++k)
      {
        double v = D[nv * k] * B[i];
        for (int s = 1; s < nv; ++s)
          v += D[nv * k + s] * B[s * nd + i];
        DBi[k] = w * v;
        zero = zero and DBi[k] == 0.0;
      }
      if (zero)
        continue;
      for (int j = 0; j < nd; ++j)
      {
        double v = DBi[0] * B[j];
        for (int k = 1; k < nv; ++k)
          v += DBi[k] * B[k * nd + j];
        Ke[i * nd + j] += v;
      }
    }
  }
}
} // namespace

template <int dim>
std::int32_t assemble_enriched_stiffness(const MatrixSink& sink, std::span<const double> x,
                                         std::span<const std::int32_t> cells, const EnrichmentLayout& layout,
                                         std::span<const CrackGeometryOf<dim>* const> cracks, double E, double nu,
                                         const QuadratureOptionsOf<dim>& options)
{
  layout.require_dimension(dim, "assemble_enriched_stiffness");
  constexpr int nv = voigt_size<dim>;
  const auto D = elasticity_matrix<dim>(E, nu);
  CellQuadratureOf<dim> q;
  std::vector<double> val, grad, B, DB, Ke;
  std::vector<int> side;
  std::array<double, dim> r;
  for (const std::int32_t c : layout.cells)
  {
    const P1Simplex<dim> cell(x, cells, c);
    const EnrichedCellBasis<dim> basis(cell, layout, c);
    const int nd = basis.num_dofs();
    Ke.assign(static_cast<std::size_t>(nd) * nd, 0.0);
    compute_enriched_cell_quadrature(x, cells, layout, cracks, c, options, q);
    for (int p = 0; p < q.size(); ++p)
    {
      region_sides(cracks, c, q.side[p], side);
      for (int i = 0; i < dim; ++i)
        r[i] = q.ref[dim * p + i];
      evaluate_basis<dim>(cell, basis, layout, cracks, side, r, val, grad);
      // B (nv, nd): Voigt strains (engineering shears) of each basis function.
      B.assign(nv * static_cast<std::size_t>(nd), 0.0);
      for (int i = 0; i < nd; ++i)
      {
        const auto e = voigt_strain<dim>(&grad[dim * dim * i]);
        for (int k = 0; k < nv; ++k)
          B[k * nd + i] = e[k];
      }
      add_btdb<dim>(q.weight[p], D, B, nd, DB, Ke);
    }
    if constexpr (dim == 3) // the lower triangle, from the upper one
      for (int i = 0; i < nd; ++i)
        for (int j = 0; j < i; ++j)
          Ke[i * nd + j] = Ke[j * nd + i];
    constexpr int ns = EnrichedCellBasis<dim>::num_standard_dofs; // the standard-standard block is DOLFINx's
    for (int i = 0; i < ns; ++i)
      for (int j = 0; j < ns; ++j)
        Ke[i * nd + j] = 0.0;
    sink(basis.dofs, basis.dofs, Ke);
  }
  return static_cast<std::int32_t>(layout.cells.size());
}

template std::int32_t assemble_enriched_stiffness<2>(const MatrixSink&, std::span<const double>,
                                                     std::span<const std::int32_t>, const EnrichmentLayout&,
                                                     std::span<const CrackGeometry* const>, double, double,
                                                     const QuadratureOptions&);
template std::int32_t assemble_enriched_stiffness<3>(const MatrixSink&, std::span<const double>,
                                                     std::span<const std::int32_t>, const EnrichmentLayout&,
                                                     std::span<const CrackGeometry3D* const>, double, double,
                                                     const QuadratureOptions3D&);

} // namespace cracklip
