// The tip (front) enrichment functions at one point of a cell (layer a):
// what the enriched basis (enriched_basis.h) asks of the crack's geometry.
// The functions are the same (williams_local.h); where their local
// coordinates come from differs:
//   - 2D: the frame of the pseudo-node's tip (tip_functions_2d.h);
//   - 3D: the crack's level sets (x1 = psi, x2 = phi, P1 on the cell) and
//     the frames of the nodes' nearest front points, interpolated
//     (front_functions_3d.h, EnrichmentLayout::frame).
// Values are computed once per tip (2D) or crack (3D) and lip branch, and
// kept for the other pseudo-nodes of the cell that share them.
#pragma once

#include "enrichment/enrichment_layout.h"
#include "enrichment/front_functions_3d.h"
#include "enrichment/tip_functions_2d.h"
#include "geometry/crack_geometry.h"
#include "geometry/p1_simplex.h"

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

namespace cracklip
{

/// The four scalar branch functions F and their gradients dF[l][j].
template <int dim>
struct BranchValues
{
  std::array<double, 4> F;
  std::array<std::array<double, dim>, 4> dF;
};

/// The dim vector (Williams) functions: U[m][i] component i of mode m,
/// dU[m][i][j] = d U[m][i] / d x_j (without K / (2 mu sqrt(2 pi))).
template <int dim>
struct VectorValues
{
  std::array<std::array<double, dim>, dim> U;
  std::array<std::array<std::array<double, dim>, dim>, dim> dU;
};

template <int dim>
class CellTipFunctions;

/// 2D: in the frame of each pseudo-node's tip, at the point's physical
/// coordinates.
template <>
class CellTipFunctions<2>
{
public:
  CellTipFunctions(const P1Cell& cell, const EnrichmentLayout& layout, std::span<const CrackGeometry* const>,
                   const std::array<double, 3>&, const std::array<double, 2>& r)
      : layout_(layout), x_(cell.physical(r))
  {
  }
  /// The branch functions of pseudo-node k's tip on lip branch `side`.
  const BranchValues<2>& branch(std::int32_t k, int side)
  {
    const std::int32_t t = layout_.tip[k];
    if (t != branch_key_[0] or side != branch_key_[1])
    {
      branch_functions(layout_.tip_frames[t], x_, side, branch_.F, branch_.dF);
      branch_key_ = {t, side};
    }
    return branch_;
  }
  /// The vector functions of pseudo-node k's tip on lip branch `side`.
  const VectorValues<2>& vector(std::int32_t k, int side)
  {
    const std::int32_t t = layout_.tip[k];
    if (t != vector_key_[0] or side != vector_key_[1])
    {
      williams_displacement(layout_.tip_frames[t], x_, side, layout_.kappa, vector_.U, vector_.dU);
      vector_key_ = {t, side};
    }
    return vector_;
  }

private:
  const EnrichmentLayout& layout_;
  std::array<double, 2> x_;
  std::array<std::int32_t, 2> branch_key_ = {-1, 0}, vector_key_ = {-1, 0};
  BranchValues<2> branch_;
  VectorValues<2> vector_;
};

/// 3D: from the local coordinates of the point in the level sets of the
/// pseudo-node's crack and the interpolated nodal frames (every node of a
/// cell carrying front functions has a frame for that crack: the layout
/// guarantees it).
template <>
class CellTipFunctions<3>
{
public:
  CellTipFunctions(const P1Tetrahedron& cell, const EnrichmentLayout& layout,
                   std::span<const CrackGeometry3D* const> cracks, const std::array<double, 4>& N,
                   const std::array<double, 3>&)
      : cell_(cell), layout_(layout), cracks_(cracks), N_(N)
  {
  }
  const BranchValues<3>& branch(std::int32_t k, int side)
  {
    const std::int32_t ic = coordinates(k);
    if (ic != branch_key_[0] or side != branch_key_[1])
    {
      front_branch_functions(lc_, side, branch_.F, branch_.dF);
      branch_key_ = {ic, side};
    }
    return branch_;
  }
  const VectorValues<3>& vector(std::int32_t k, int side)
  {
    const std::int32_t ic = coordinates(k);
    if (ic != vector_key_[0] or side != vector_key_[1])
    {
      front_vector_functions(lc_, side, layout_.kappa, vector_.U, vector_.dU);
      vector_key_ = {ic, side};
    }
    return vector_;
  }

  /// The local front coordinates of crack ic at the point: x1 = psi, x2 =
  /// phi interpolated, their (constant) gradients, the interpolated
  /// directions and their gradients.
  static LocalCoordinates front_coordinates(const P1Tetrahedron& cell, const EnrichmentLayout& layout,
                                            const CrackGeometry3D& crack, std::int32_t ic,
                                            const std::array<double, 4>& N)
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

private:
  /// The coordinates of pseudo-node k's crack, computed once per crack.
  std::int32_t coordinates(std::int32_t k)
  {
    const std::int32_t ic = layout_.crack[k];
    if (ic != lc_crack_)
      lc_ = front_coordinates(cell_, layout_, *cracks_[ic], ic, N_), lc_crack_ = ic;
    return ic;
  }

  const P1Tetrahedron& cell_;
  const EnrichmentLayout& layout_;
  std::span<const CrackGeometry3D* const> cracks_;
  std::array<double, 4> N_;
  std::int32_t lc_crack_ = -1;
  LocalCoordinates lc_{};
  std::array<std::int32_t, 2> branch_key_ = {-1, 0}, vector_key_ = {-1, 0};
  BranchValues<3> branch_;
  VectorValues<3> vector_;
};

} // namespace cracklip
