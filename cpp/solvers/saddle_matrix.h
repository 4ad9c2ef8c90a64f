// The CSR arrays of the contact saddle-point matrix [K B_a^T; B_a D].
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{
/// CSR (row pointers, columns, values) of the (n + m) x (n + m) matrix
///   [K      B_a^T]
///   [B_a    D    ]
/// from K (n x n CSR) and B (m x n CSR, columns sorted within each row):
/// B_a is B with the rows of inactive multipliers emptied and D = 1 on the
/// inactive multipliers' diagonal (an inactive multiplier is held at 0);
/// on the active ones' rows the active columns of a given block S (m x m
/// CSR, columns sorted; empty row pointers: none), D = -S there (the
/// multipliers' stabilisation, contact/stabilisation.py). Row k of the top block is K's row followed
/// by B_a^T's (columns n + j, ascending), so sorted K rows stay sorted.
/// Work and memory linear in nnz(K) + nnz(B).
struct SaddleCsr
{
  std::vector<std::int32_t> indptr, indices;
  std::vector<double> data;
};

SaddleCsr saddle_csr(std::span<const std::int32_t> k_indptr, std::span<const std::int32_t> k_indices,
                     std::span<const double> k_data, std::span<const std::int32_t> b_indptr,
                     std::span<const std::int32_t> b_indices, std::span<const double> b_data,
                     std::span<const std::int8_t> active, std::span<const std::int32_t> s_indptr = {},
                     std::span<const std::int32_t> s_indices = {}, std::span<const double> s_data = {});
} // namespace cracklip
