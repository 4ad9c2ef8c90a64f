// Nodal block rescaling of the stiffness (layer a).
//
// Enriched dofs with small supports or nearly parallel functions make the
// stiffness badly conditioned. The rescaling replaces the dofs of every
// group (a node's standard dofs together with all its enriched dofs) by the
// basis in which the group's diagonal block is the identity: with
// K_gg = L L^T (Cholesky), the group's columns of T are L^-T, so that
// T^T K T has identity diagonal blocks (Bechet, Minnebo, Moes, Burgardt
// 2005 precondition the enriched nodes this way). Dofs outside any group are
// Jacobi-scaled (T_ii = K_ii^-1/2). The solution is u = T y.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// COO entries of the block-diagonal transformation T.
struct BlockTransform
{
  std::vector<std::int32_t> rows, cols;
  std::vector<double> values;
};

/// K as scalar CSR (indptr, indices sorted in each row, data; square,
/// symmetric). Groups as CSR:
/// dofs of group g are group_dofs[group_offsets[g]:group_offsets[g+1]]; every
/// dof not in a group gets a 1x1 Jacobi block. Throws std::runtime_error
/// naming the group's first dof if a block is not positive definite.
BlockTransform nodal_block_transform(std::span<const std::int32_t> indptr,
                                     std::span<const std::int32_t> indices,
                                     std::span<const double> data,
                                     std::span<const std::int32_t> group_offsets,
                                     std::span<const std::int32_t> group_dofs);

/// In-place Cholesky K = L L^T of a dense n x n row-major SPD block (lower
/// triangle of `a` overwritten by L), then the inverse of L^T, upper
/// triangular, returned row-major. Returns false if a pivot is <= tol times
/// its row's diagonal entry (not positive definite, or a dof of the block is
/// a combination of the others to that tolerance).
bool inverse_cholesky_transpose(std::vector<double>& a, int n, std::vector<double>& out,
                                double tol = 1e-14);

} // namespace cracklip
