#include "solvers/rescaling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cracklip
{

bool inverse_cholesky_transpose(std::vector<double>& a, int n, std::vector<double>& out, double tol)
{
  for (int j = 0; j < n; ++j)
  {
    const double ajj = a[j * n + j];
    double d = ajj;
    for (int k = 0; k < j; ++k)
      d -= a[j * n + k] * a[j * n + k];
    // Scale-free test: the part of the dof's diagonal left after removing
    // what the previous dofs of the block explain.
    if (!(ajj > 0.0 and d > tol * ajj))
      return false;
    const double ljj = std::sqrt(d);
    a[j * n + j] = ljj;
    for (int i = j + 1; i < n; ++i)
    {
      double s = a[i * n + j];
      for (int k = 0; k < j; ++k)
        s -= a[i * n + k] * a[j * n + k];
      a[i * n + j] = s / ljj;
    }
  }
  // X = L^-1 (lower), by forward substitution column by column; out = X^T.
  out.assign(static_cast<std::size_t>(n) * n, 0.0);
  for (int c = 0; c < n; ++c)
    for (int i = c; i < n; ++i)
    {
      double s = i == c ? 1.0 : 0.0;
      for (int k = c; k < i; ++k)
        s -= a[i * n + k] * out[k * n + c];
      out[i * n + c] = s / a[i * n + i];
    }
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      std::swap(out[i * n + j], out[j * n + i]);
  return true;
}

BlockTransform nodal_block_transform(std::span<const std::int32_t> indptr,
                                     std::span<const std::int32_t> indices,
                                     std::span<const double> data,
                                     std::span<const std::int32_t> group_offsets,
                                     std::span<const std::int32_t> group_dofs)
{
  const auto n = static_cast<std::int32_t>(indptr.size()) - 1;
  BlockTransform T;
  std::vector<char> grouped(n, 0);
  for (std::int32_t d : group_dofs)
  {
    if (d < 0 or d >= n)
      throw std::invalid_argument("nodal_block_transform: group dof " + std::to_string(d)
                                  + " outside the matrix (size " + std::to_string(n) + ")");
    grouped[d] = 1;
  }
  auto entry = [&](std::int32_t i, std::int32_t j)
  {
    const auto b = indices.begin() + indptr[i], e = indices.begin() + indptr[i + 1];
    const auto it = std::lower_bound(b, e, j);
    return it != e and *it == j ? data[indptr[i] + (it - indices.begin() - indptr[i])] : 0.0;
  };
  for (std::int32_t i = 0; i < n; ++i)
    if (!grouped[i])
    {
      const double d = std::abs(entry(i, i));
      T.rows.push_back(i);
      T.cols.push_back(i);
      T.values.push_back(d > 0.0 ? 1.0 / std::sqrt(d) : 1.0);
    }
  std::vector<double> block, inv;
  const std::size_t num_groups = group_offsets.empty() ? 0 : group_offsets.size() - 1;
  for (std::size_t g = 0; g < num_groups; ++g)
  {
    const auto dofs = group_dofs.subspan(group_offsets[g], group_offsets[g + 1] - group_offsets[g]);
    const int m = static_cast<int>(dofs.size());
    block.assign(static_cast<std::size_t>(m) * m, 0.0);
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b)
        block[a * m + b] = entry(dofs[a], dofs[b]);
    if (!inverse_cholesky_transpose(block, m, inv))
      throw std::runtime_error("nodal rescaling: the stiffness block of the node with dof "
                               + std::to_string(dofs[0])
                               + " is not positive definite (an enriched dof sees no stiffness)");
    for (int a = 0; a < m; ++a)
      for (int b = a; b < m; ++b)
        if (inv[a * m + b] != 0.0)
        {
          T.rows.push_back(dofs[a]);
          T.cols.push_back(dofs[b]);
          T.values.push_back(inv[a * m + b]);
        }
  }
  return T;
}

} // namespace cracklip
