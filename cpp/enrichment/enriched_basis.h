// Standard and enriched basis functions on one P1 cell (layer a), in any
// dimension: dim + 1 standard nodes then the cell's pseudo-nodes
// (enrichment_layout.h), each with dim scalar dofs. The tip (front)
// functions come from cell_tip_functions.h, where the geometry differs.
#pragma once

#include "enrichment/cell_tip_functions.h"
#include "enrichment/dof_numbering.h"
#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry.h"
#include "geometry/p1_simplex.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// The basis functions of a cell: dim + 1 standard nodes then the cell's
/// pseudo-nodes, each with dim scalar dofs (global indices in `dofs`, in
/// that order); `enr` the pseudo-node ids, `enr_local` the local index of
/// each one's base node; has_tip: some pseudo-node carries tip (front)
/// functions.
template <int dim>
struct EnrichedCellBasis
{
  std::vector<std::int32_t> enr;
  std::vector<int> enr_local;
  std::vector<std::int32_t> dofs;
  bool has_tip = false;

  EnrichedCellBasis(const P1Simplex<dim>& cell, const EnrichmentLayout& layout, std::int32_t c)
  {
    for (int a = 0; a <= dim; ++a)
      for (int d = 0; d < dim; ++d)
        dofs.push_back(node_dof(cell.nodes[a], d, dim));
    const std::int32_t ie = layout.cell_index.empty() ? -1 : layout.cell_index[c];
    if (ie < 0)
      return;
    for (std::int32_t j = layout.cell_offsets[ie]; j < layout.cell_offsets[ie + 1]; ++j)
    {
      const std::int32_t k = layout.cell_enr[j];
      enr.push_back(k);
      enr_local.push_back(cell.local(layout.node[k]));
      has_tip = has_tip or layout.kind[k] != static_cast<std::int8_t>(EnrichmentKind::heaviside);
      for (int d = 0; d < dim; ++d)
        dofs.push_back(node_dof(layout.num_std_nodes + k, d, dim));
    }
  }
  int num_dofs() const { return static_cast<int>(dofs.size()); }
  /// Number of standard scalar dofs (the first ones).
  static constexpr int num_standard_dofs = dim * (dim + 1);
};

/// Vector value and gradient of every scalar dof's basis function at a point
/// with reference coordinates r, where the Heaviside of crack ic (and the
/// lip branch of its tip functions) is side[ic]. Fills val (ndof, dim) and
/// grad (ndof, dim, dim) with grad[(i dim + a) dim + b] = d val_a / d x_b.
template <int dim>
void evaluate_basis(const P1Simplex<dim>& cell, const EnrichedCellBasis<dim>& basis, const EnrichmentLayout& layout,
                    std::span<const CrackGeometryOf<dim>* const> cracks, std::span<const int> side,
                    const std::array<double, dim>& r, std::vector<double>& val, std::vector<double>& grad)
{
  using Vec = std::array<double, dim>;
  const int nd = basis.num_dofs();
  val.assign(dim * nd, 0.0);
  grad.assign(dim * dim * nd, 0.0);
  const auto N = P1Simplex<dim>::shape(r);
  // Scalar function phi times e_d for dofs dim f + d.
  auto scalar = [&](int f, double phi, const Vec& g)
  {
    for (int d = 0; d < dim; ++d)
    {
      const int i = dim * f + d;
      val[dim * i + d] = phi;
      for (int b = 0; b < dim; ++b)
        grad[(dim * i + d) * dim + b] = g[b];
    }
  };
  for (int a = 0; a <= dim; ++a)
    scalar(a, N[a], cell.grad[a]);
  if (basis.enr.empty())
    return;
  // Ramp R = sum of N_a over the core tip nodes of a crack (corrected X-FEM):
  // 1 in cells whose nodes are all core nodes, 0 in cells without one. Tip
  // functions are multiplied by R and Heaviside functions by 1 - R, so that
  // in blending cells the two share the jump and both stay P1 x enrichment.
  std::int32_t ramp_crack = -1;
  double R = 1.0;
  Vec dR{};
  auto ramp = [&](std::int32_t crack)
  {
    if (crack == ramp_crack)
      return;
    ramp_crack = crack;
    std::array<bool, dim + 1> core{};
    for (std::size_t j = 0; j < basis.enr.size(); ++j)
      if (layout.crack[basis.enr[j]] == crack and layout.core[basis.enr[j]])
        core[basis.enr_local[j]] = true;
    R = 0.0, dR = {};
    for (int a = 0; a <= dim; ++a)
      if (core[a])
      {
        R += N[a];
        for (int b = 0; b < dim; ++b)
          dR[b] += cell.grad[a][b];
      }
  };
  CellTipFunctions<dim> tips(cell, layout, cracks, N, r);
  for (std::size_t j = 0; j < basis.enr.size(); ++j)
  {
    const std::int32_t k = basis.enr[j];
    const int a = basis.enr_local[j];
    const int f = dim + 1 + static_cast<int>(j);
    const double* sh = &layout.shift[dim * dim * k];
    const auto kind = static_cast<EnrichmentKind>(layout.kind[k]);
    const int sd = side[layout.crack[k]];
    if (layout.corrected)
      ramp(layout.crack[k]);
    else
      R = 1.0, dR = {};
    Vec g;
    if (kind == EnrichmentKind::heaviside)
    {
      const double jump = sd - sh[0];
      if (!layout.corrected)
      {
        for (int b = 0; b < dim; ++b)
          g[b] = cell.grad[a][b] * jump;
        scalar(f, N[a] * jump, g);
      }
      else // N_a jump (1 - R)
      {
        for (int b = 0; b < dim; ++b)
          g[b] = (cell.grad[a][b] * (1.0 - R) - N[a] * dR[b]) * jump;
        scalar(f, N[a] * jump * (1.0 - R), g);
      }
      continue;
    }
    if (kind == EnrichmentKind::tip_scalar)
    {
      const BranchValues<dim>& t = tips.branch(k, sd);
      const int l = layout.function[k];
      const double v = t.F[l] - sh[0];
      for (int b = 0; b < dim; ++b) // grad (N_a v R)
        g[b] = (cell.grad[a][b] * v + N[a] * t.dF[l][b]) * R + N[a] * v * dR[b];
      scalar(f, N[a] * v * R, g);
      continue;
    }
    // tip_vector: dof dim f + m is mode m, a vector-valued function.
    const VectorValues<dim>& t = tips.vector(k, sd);
    for (int m = 0; m < dim; ++m)
    {
      const int i = dim * f + m;
      for (int comp = 0; comp < dim; ++comp)
      {
        const double v = t.U[m][comp] - sh[dim * m + comp];
        val[dim * i + comp] = N[a] * v * R;
        for (int b = 0; b < dim; ++b)
          grad[(dim * i + comp) * dim + b] = (cell.grad[a][b] * v + N[a] * t.dU[m][comp][b]) * R + N[a] * v * dR[b];
      }
    }
  }
}

/// The names cpp/contact (2D) uses: a triangle's basis, and the 2D
/// evaluation, whose tip functions need no crack geometry.
using CellBasis = EnrichedCellBasis<2>;

inline void evaluate_basis(const P1Cell& cell, const CellBasis& basis, const EnrichmentLayout& layout,
                           std::span<const int> side, std::array<double, 2> r, std::vector<double>& val,
                           std::vector<double>& grad)
{
  evaluate_basis<2>(cell, basis, layout, {}, side, r, val, grad);
}

} // namespace cracklip
