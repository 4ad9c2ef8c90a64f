// Standard and enriched basis functions on one P1 cell (layer a).
#pragma once

#include "geometry/crack_geometry_2d.h"
#include "geometry/p1_simplex.h"
#include "enrichment/enrichment_layout.h"
#include "enrichment/tip_functions_2d.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace cracklip
{

/// The basis functions of an enriched cell: 3 standard nodes then the cell's
/// pseudo-nodes, each with two scalar dofs. `dofs` holds global scalar dof
/// indices in that order, `enr` the pseudo-node ids and `enr_local` the
/// local index of each pseudo-node's base node.
struct CellBasis
{
  std::vector<std::int32_t> enr;
  std::vector<int> enr_local;
  std::vector<std::int32_t> dofs;
  bool has_tip = false;

  CellBasis(const P1Cell& cell, const EnrichmentLayout& layout, std::int32_t c)
  {
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 2; ++d)
        dofs.push_back(2 * cell.nodes[a] + d);
    const std::int32_t ie = layout.cell_index.empty() ? -1 : layout.cell_index[c];
    if (ie < 0)
      return;
    for (std::int32_t j = layout.cell_offsets[ie]; j < layout.cell_offsets[ie + 1]; ++j)
    {
      const std::int32_t k = layout.cell_enr[j];
      enr.push_back(k);
      enr_local.push_back(cell.local(layout.node[k]));
      has_tip = has_tip or layout.kind[k] != static_cast<std::int8_t>(EnrichmentKind::heaviside);
      for (int d = 0; d < 2; ++d)
        dofs.push_back(2 * (layout.num_std_nodes + k) + d);
    }
  }
  int num_dofs() const { return static_cast<int>(dofs.size()); }
};

/// Vector value and gradient of every scalar dof's basis function at a point
/// with reference coordinates r, where the Heaviside of crack ic (and the
/// lip branch of its tip functions) is side[ic]. Fills val (ndof, 2) and
/// grad (ndof, 2, 2) with grad[(i * 2 + a) * 2 + b] = d val_a / d x_b.
inline void evaluate_basis(const P1Cell& cell, const CellBasis& basis,
                           const EnrichmentLayout& layout, std::span<const int> side,
                           std::array<double, 2> r, std::vector<double>& val,
                           std::vector<double>& grad)
{
  const int nd = basis.num_dofs();
  val.assign(2 * nd, 0.0);
  grad.assign(4 * nd, 0.0);
  const auto N = P1Cell::shape(r);
  // Scalar function phi times e_d for dofs 2f + d.
  auto scalar = [&](int f, double phi, double gx, double gy)
  {
    for (int d = 0; d < 2; ++d)
    {
      const int i = 2 * f + d;
      val[2 * i + d] = phi;
      grad[(2 * i + d) * 2 + 0] = gx;
      grad[(2 * i + d) * 2 + 1] = gy;
    }
  };
  for (int a = 0; a < 3; ++a)
    scalar(a, N[a], cell.grad[a][0], cell.grad[a][1]);
  if (basis.enr.empty())
    return;
  const std::array<double, 2> x = cell.physical(r);
  std::array<double, 4> F;
  std::array<std::array<double, 2>, 4> dF;
  std::array<std::array<double, 2>, 2> U;
  std::array<std::array<std::array<double, 2>, 2>, 2> dU;
  std::int32_t cached_tip = -1;
  // Ramp R = sum of N_a over the core tip nodes of a crack (corrected X-FEM):
  // 1 in cells whose nodes are all core nodes, 0 in cells without one. Tip
  // functions are multiplied by R and Heaviside functions by 1 - R, so that
  // in blending cells the two share the jump and both stay P1 x enrichment.
  std::int32_t ramp_crack = -1;
  double R = 1.0, dR[2] = {0.0, 0.0};
  auto ramp = [&](std::int32_t crack)
  {
    if (crack == ramp_crack)
      return;
    ramp_crack = crack;
    bool core[3] = {false, false, false};
    for (std::size_t j = 0; j < basis.enr.size(); ++j)
      if (layout.crack[basis.enr[j]] == crack and layout.core[basis.enr[j]])
        core[basis.enr_local[j]] = true;
    R = 0.0, dR[0] = 0.0, dR[1] = 0.0;
    for (int a = 0; a < 3; ++a)
      if (core[a])
        R += N[a], dR[0] += cell.grad[a][0], dR[1] += cell.grad[a][1];
  };
  for (std::size_t j = 0; j < basis.enr.size(); ++j)
  {
    const std::int32_t k = basis.enr[j];
    const int a = basis.enr_local[j];
    const int f = 3 + static_cast<int>(j);
    const double* sh = &layout.shift[4 * k];
    const auto kind = static_cast<EnrichmentKind>(layout.kind[k]);
    const int sd = side[layout.crack[k]];
    if (layout.corrected)
      ramp(layout.crack[k]);
    else
      R = 1.0, dR[0] = dR[1] = 0.0;
    if (kind == EnrichmentKind::heaviside)
    {
      const double jump = sd - sh[0];
      if (!layout.corrected)
        scalar(f, N[a] * jump, cell.grad[a][0] * jump, cell.grad[a][1] * jump);
      else // phi = N_a jump (1 - R)
        scalar(f, N[a] * jump * (1.0 - R), (cell.grad[a][0] * (1.0 - R) - N[a] * dR[0]) * jump,
               (cell.grad[a][1] * (1.0 - R) - N[a] * dR[1]) * jump);
      continue;
    }
    const std::int32_t t = layout.tip[k];
    if (kind == EnrichmentKind::tip_scalar)
    {
      if (t != cached_tip)
        branch_functions(layout.tip_frames[t], x, sd, F, dF), cached_tip = t;
      const int l = layout.function[k];
      const double v = F[l] - sh[0];
      // phi = N_a v R
      scalar(f, N[a] * v * R,
             (cell.grad[a][0] * v + N[a] * dF[l][0]) * R + N[a] * v * dR[0],
             (cell.grad[a][1] * v + N[a] * dF[l][1]) * R + N[a] * v * dR[1]);
      continue;
    }
    // tip_vector: dof 2f + m is mode m, a vector-valued function.
    williams_displacement(layout.tip_frames[t], x, sd, layout.kappa, U, dU);
    cached_tip = -1;
    for (int m = 0; m < 2; ++m)
    {
      const int i = 2 * f + m;
      for (int comp = 0; comp < 2; ++comp)
      {
        const double v = U[m][comp] - sh[2 * m + comp];
        val[2 * i + comp] = N[a] * v * R;
        for (int b = 0; b < 2; ++b)
          grad[(2 * i + comp) * 2 + b] = (cell.grad[a][b] * v + N[a] * dU[m][comp][b]) * R + N[a] * v * dR[b];
      }
    }
  }
}

/// Side of every crack at a point of cell c. For the crack that crosses the
/// cell or ends in it (if any) the side is `crossing_side`; every other crack
/// has a constant side on the cell (0 on its extension cells).
inline void region_sides(std::span<const CrackGeometry* const> cracks, std::int32_t c,
                         int crossing_side, std::vector<int>& side)
{
  side.resize(cracks.size());
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const CrackGeometry& g = *cracks[ic];
    const bool crossing = g.crack_cell_index[c] >= 0 or g.tip_cell_index[c] >= 0;
    side[ic] = crossing ? crossing_side : g.cell_side[c];
  }
}

/// The crack (index) whose crack cell (cut or edge) c is, or -1.
inline int crossing_crack(std::span<const CrackGeometry* const> cracks, std::int32_t c)
{
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
    if (cracks[ic]->crack_cell_index[c] >= 0)
      return static_cast<int>(ic);
  return -1;
}

/// Integration regions of a cell: the sub-triangles of a crossed cell (with
/// the side of the crossing crack), else the cell itself (side 0).
struct CellRegions
{
  const CrackCell* crack_cell = nullptr;

  CellRegions(std::span<const CrackGeometry* const> cracks, std::int32_t c)
  {
    const int ic = crossing_crack(cracks, c);
    if (ic >= 0)
      crack_cell = &cracks[ic]->crack_cells[cracks[ic]->crack_cell_index[c]];
  }
  int size() const { return crack_cell ? crack_cell->num_sub : 1; }
  int side(int s) const { return crack_cell ? crack_cell->side[s] : 0; }
  /// Vertices of region s in reference coordinates.
  std::array<std::array<double, 2>, 3> triangle(int s) const
  {
    std::array<std::array<double, 2>, 3> tri = {{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}};
    if (crack_cell)
      for (int i = 0; i < 3; ++i)
        tri[i] = {crack_cell->sub[6 * s + 2 * i], crack_cell->sub[6 * s + 2 * i + 1]};
    return tri;
  }
  /// Reference area of region s.
  double area(int s) const
  {
    const auto t = triangle(s);
    return 0.5 * std::abs((t[1][0] - t[0][0]) * (t[2][1] - t[0][1])
                          - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]));
  }
};

/// Plane-strain elasticity matrix in Voigt order (xx, yy, 2xy), row-major 3x3.
inline std::array<double, 9> plane_strain_matrix(double E, double nu)
{
  if (!(E > 0.0) or !(nu > -1.0 and nu < 0.5))
    throw std::invalid_argument("plane strain needs E > 0 and -1 < nu < 0.5");
  const double lmbda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = E / (2.0 * (1.0 + nu));
  return {lmbda + 2 * mu, lmbda, 0.0, lmbda, lmbda + 2 * mu, 0.0, 0.0, 0.0, mu};
}

} // namespace cracklip
