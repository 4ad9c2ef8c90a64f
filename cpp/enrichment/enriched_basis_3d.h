// Standard and enriched basis functions on one P1 tetrahedron (layer a).
#pragma once

#include "enrichment/dof_numbering.h"
#include "enrichment/enrichment_layout_3d.h"
#include "enrichment/front_functions_3d.h"
#include "geometry/p1_simplex.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace cracklip
{

/// The basis functions of a cell: 4 standard nodes then the cell's
/// pseudo-nodes, each with three scalar dofs (global indices in `dofs`, in
/// that order); `enr` the pseudo-node ids, `enr_local` the local index of
/// each one's base node.
struct CellBasis3D
{
  std::vector<std::int32_t> enr;
  std::vector<int> enr_local;
  std::vector<std::int32_t> dofs;
  bool has_front = false;

  CellBasis3D(const P1Tetrahedron& cell, const EnrichmentLayout3D& layout, std::int32_t c)
  {
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        dofs.push_back(node_dof(cell.nodes[a], d, 3));
    const std::int32_t ie = layout.cell_index.empty() ? -1 : layout.cell_index[c];
    if (ie < 0)
      return;
    for (std::int32_t j = layout.cell_offsets[ie]; j < layout.cell_offsets[ie + 1]; ++j)
    {
      const std::int32_t k = layout.cell_enr[j];
      enr.push_back(k);
      int a = 0;
      while (a < 4 and cell.nodes[a] != layout.node[k])
        ++a;
      enr_local.push_back(a);
      has_front = has_front or layout.kind[k] != static_cast<std::int8_t>(EnrichmentKind::heaviside);
      for (int d = 0; d < 3; ++d)
        dofs.push_back(node_dof(layout.num_std_nodes + k, d, 3));
    }
  }
  int num_dofs() const { return static_cast<int>(dofs.size()); }
};

/// The local front coordinates of crack ic at reference point r of a cell
/// (every node of which has a frame for ic: the layout guarantees it on
/// cells carrying front functions): x1 = psi, x2 = phi interpolated, their
/// (constant) gradients, the interpolated directions and their gradients.
inline LocalCoordinates front_coordinates(const P1Tetrahedron& cell, const EnrichmentLayout3D& layout,
                                          const CrackGeometry3D& crack, std::int32_t ic, const std::array<double, 4>& N)
{
  LocalCoordinates lc{};
  const double* f[4];
  for (int a = 0; a < 4; ++a)
  {
    f[a] = layout.frame(cell.nodes[a], ic);
    if (f[a] == nullptr)
      throw std::logic_error("front_coordinates: node " + std::to_string(cell.nodes[a]) + " has no frame");
  }
  for (int a = 0; a < 4; ++a)
  {
    const double psi = crack.psi[cell.nodes[a]], phi = crack.phi[cell.nodes[a]];
    lc.x1 += N[a] * psi;
    lc.x2 += N[a] * phi;
    for (int j = 0; j < 3; ++j)
    {
      lc.g1[j] += psi * cell.grad[a][j];
      lc.g2[j] += phi * cell.grad[a][j];
    }
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
      {
        lc.e[k][i] += N[a] * f[a][3 * k + i];
        for (int j = 0; j < 3; ++j)
          lc.de[k][i][j] += f[a][3 * k + i] * cell.grad[a][j];
      }
  }
  return lc;
}

/// Vector value and gradient of every scalar dof's basis function at a point
/// with reference coordinates r, where the Heaviside of crack ic (and the
/// lip branch of its front functions) is side[ic]. Fills val (ndof, 3) and
/// grad (ndof, 3, 3) with grad[(i * 3 + a) * 3 + b] = d val_a / d x_b.
inline void evaluate_basis_3d(const P1Tetrahedron& cell, const CellBasis3D& basis, const EnrichmentLayout3D& layout,
                              std::span<const CrackGeometry3D* const> cracks, std::span<const int> side, const Point3& r,
                              std::vector<double>& val, std::vector<double>& grad)
{
  const int nd = basis.num_dofs();
  val.assign(3 * nd, 0.0);
  grad.assign(9 * nd, 0.0);
  const auto N = P1Tetrahedron::shape(r);
  // Scalar function phi times e_d for dofs 3f + d.
  auto scalar = [&](int f, double phi, const Point3& g)
  {
    for (int d = 0; d < 3; ++d)
    {
      const int i = 3 * f + d;
      val[3 * i + d] = phi;
      for (int b = 0; b < 3; ++b)
        grad[(3 * i + d) * 3 + b] = g[b];
    }
  };
  for (int a = 0; a < 4; ++a)
    scalar(a, N[a], cell.grad[a]);
  if (basis.enr.empty())
    return;
  // Per crack: the ramp R (sum of N_a over its core front nodes) and the
  // front functions at the point, computed once.
  std::int32_t ramp_crack = -1;
  double R = 1.0;
  Point3 dR = {0.0, 0.0, 0.0};
  auto ramp = [&](std::int32_t crack)
  {
    if (crack == ramp_crack)
      return;
    ramp_crack = crack;
    bool core[4] = {false, false, false, false};
    for (std::size_t j = 0; j < basis.enr.size(); ++j)
      if (layout.crack[basis.enr[j]] == crack and layout.core[basis.enr[j]])
        core[basis.enr_local[j]] = true;
    R = 0.0, dR = {0.0, 0.0, 0.0};
    for (int a = 0; a < 4; ++a)
      if (core[a])
      {
        R += N[a];
        for (int b = 0; b < 3; ++b)
          dR[b] += cell.grad[a][b];
      }
  };
  std::int32_t fn_crack = -1;
  LocalCoordinates lc{};
  std::array<Point3, 3> U;
  std::array<std::array<Point3, 3>, 3> dU;
  std::array<double, 4> F;
  std::array<Point3, 4> dF;
  bool have_vector = false, have_scalar = false;
  for (std::size_t j = 0; j < basis.enr.size(); ++j)
  {
    const std::int32_t k = basis.enr[j];
    const int a = basis.enr_local[j];
    const int f = 4 + static_cast<int>(j);
    const double* sh = &layout.shift[9 * k];
    const auto kind = static_cast<EnrichmentKind>(layout.kind[k]);
    const std::int32_t ic = layout.crack[k];
    const int sd = side[ic];
    if (layout.corrected)
      ramp(ic);
    else
      R = 1.0, dR = {0.0, 0.0, 0.0};
    if (kind == EnrichmentKind::heaviside)
    {
      const double jump = sd - sh[0];
      Point3 g;
      if (!layout.corrected)
      {
        for (int b = 0; b < 3; ++b)
          g[b] = cell.grad[a][b] * jump;
        scalar(f, N[a] * jump, g);
      }
      else // N_a jump (1 - R)
      {
        for (int b = 0; b < 3; ++b)
          g[b] = (cell.grad[a][b] * (1.0 - R) - N[a] * dR[b]) * jump;
        scalar(f, N[a] * jump * (1.0 - R), g);
      }
      continue;
    }
    if (ic != fn_crack)
    {
      fn_crack = ic, have_vector = have_scalar = false;
      lc = front_coordinates(cell, layout, *cracks[ic], ic, N);
    }
    if (kind == EnrichmentKind::tip_scalar)
    {
      if (!have_scalar)
        front_branch_functions(lc, sd, F, dF), have_scalar = true;
      const int l = layout.function[k];
      const double v = F[l] - sh[0];
      Point3 g;
      for (int b = 0; b < 3; ++b) // grad (N_a v R)
        g[b] = (cell.grad[a][b] * v + N[a] * dF[l][b]) * R + N[a] * v * dR[b];
      scalar(f, N[a] * v * R, g);
      continue;
    }
    // tip_vector: dof 3f + m is mode m, a vector-valued function.
    if (!have_vector)
      front_vector_functions(lc, sd, layout.kappa, U, dU), have_vector = true;
    for (int m = 0; m < 3; ++m)
    {
      const int i = 3 * f + m;
      for (int comp = 0; comp < 3; ++comp)
      {
        const double v = U[m][comp] - sh[3 * m + comp];
        val[3 * i + comp] = N[a] * v * R;
        for (int b = 0; b < 3; ++b)
          grad[(3 * i + comp) * 3 + b] = (cell.grad[a][b] * v + N[a] * dU[m][comp][b]) * R + N[a] * v * dR[b];
      }
    }
  }
}

/// Isotropic elasticity in Voigt order (xx, yy, zz, yz, xz, xy; engineering
/// shears), row-major 6 x 6.
inline std::array<double, 36> elasticity_matrix_3d(double E, double nu)
{
  if (!(E > 0.0) or !(nu > -1.0 and nu < 0.5))
    throw std::invalid_argument("3D elasticity needs E > 0 and -1 < nu < 0.5");
  const double lmbda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu = E / (2.0 * (1.0 + nu));
  std::array<double, 36> D{};
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
      D[6 * i + j] = lmbda;
    D[6 * i + i] += 2.0 * mu;
    D[6 * (i + 3) + i + 3] = mu;
  }
  return D;
}

} // namespace cracklip
