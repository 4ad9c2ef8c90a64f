#include "solvers/saddle_matrix.h"

#include <limits>
#include <stdexcept>

namespace cracklip
{
SaddleCsr saddle_csr(std::span<const std::int32_t> k_indptr, std::span<const std::int32_t> k_indices,
                     std::span<const double> k_data, std::span<const std::int32_t> b_indptr,
                     std::span<const std::int32_t> b_indices, std::span<const double> b_data,
                     std::span<const std::int8_t> active, std::span<const std::int32_t> s_indptr,
                     std::span<const std::int32_t> s_indices, std::span<const double> s_data)
{
  if (k_indptr.empty() || b_indptr.empty())
    throw std::invalid_argument("saddle_csr: empty row pointers");
  const std::size_t n = k_indptr.size() - 1, m = b_indptr.size() - 1;
  if (active.size() != m || k_indices.size() != std::size_t(k_indptr[n]) || k_data.size() != k_indices.size()
      || b_indices.size() != std::size_t(b_indptr[m]) || b_data.size() != b_indices.size())
    throw std::invalid_argument("saddle_csr: inconsistent CSR arrays");
  const bool with_s = !s_indptr.empty();
  if (with_s
      && (s_indptr.size() != m + 1 || s_indices.size() != std::size_t(s_indptr[m]) || s_data.size() != s_indices.size()))
    throw std::invalid_argument("saddle_csr: inconsistent CSR arrays of S");
  // Entries of S kept: active rows, active columns.
  auto kept = [&](std::int32_t p)
  {
    if (s_indices[p] < 0 || std::size_t(s_indices[p]) >= m)
      throw std::invalid_argument("saddle_csr: a column of S is outside the multipliers");
    return bool(active[s_indices[p]]);
  };
  // B_a^T by counting: entries of active rows per column of B.
  std::vector<std::int64_t> t_ptr(n + 1, 0);
  for (std::size_t j = 0; j < m; ++j)
    if (active[j])
      for (std::int32_t p = b_indptr[j]; p < b_indptr[j + 1]; ++p)
      {
        if (b_indices[p] < 0 || std::size_t(b_indices[p]) >= n)
          throw std::invalid_argument("saddle_csr: a column of B is outside K");
        ++t_ptr[b_indices[p] + 1];
      }
  for (std::size_t i = 0; i < n; ++i)
    t_ptr[i + 1] += t_ptr[i];
  std::vector<std::int32_t> t_col(t_ptr[n]);
  std::vector<double> t_val(t_ptr[n]);
  {
    std::vector<std::int64_t> next(t_ptr.begin(), t_ptr.end() - 1);
    for (std::size_t j = 0; j < m; ++j) // j ascending: each row of B_a^T comes out sorted
      if (active[j])
        for (std::int32_t p = b_indptr[j]; p < b_indptr[j + 1]; ++p)
        {
          const std::int64_t q = next[b_indices[p]]++;
          t_col[q] = static_cast<std::int32_t>(n + j);
          t_val[q] = b_data[p];
        }
  }
  std::size_t bottom = 0;
  for (std::size_t j = 0; j < m; ++j)
  {
    bottom += active[j] ? std::size_t(b_indptr[j + 1] - b_indptr[j]) : 1;
    if (with_s && active[j])
      for (std::int32_t p = s_indptr[j]; p < s_indptr[j + 1]; ++p)
        bottom += kept(p);
  }
  const std::size_t nnz = k_indices.size() + t_col.size() + bottom;
  if (nnz > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw std::overflow_error("saddle_csr: more entries than 32-bit PETSc indices hold");
  SaddleCsr s;
  s.indptr.resize(n + m + 1);
  s.indices.resize(nnz);
  s.data.resize(nnz);
  std::size_t q = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    s.indptr[i] = static_cast<std::int32_t>(q);
    for (std::int32_t p = k_indptr[i]; p < k_indptr[i + 1]; ++p, ++q)
    {
      s.indices[q] = k_indices[p];
      s.data[q] = k_data[p];
    }
    for (std::int64_t p = t_ptr[i]; p < t_ptr[i + 1]; ++p, ++q)
    {
      s.indices[q] = t_col[p];
      s.data[q] = t_val[p];
    }
  }
  for (std::size_t j = 0; j < m; ++j)
  {
    s.indptr[n + j] = static_cast<std::int32_t>(q);
    if (active[j])
    {
      for (std::int32_t p = b_indptr[j]; p < b_indptr[j + 1]; ++p, ++q)
      {
        s.indices[q] = b_indices[p];
        s.data[q] = b_data[p];
      }
      if (with_s) // (columns n + i after B's, i ascending: the row stays sorted)
        for (std::int32_t p = s_indptr[j]; p < s_indptr[j + 1]; ++p)
          if (kept(p))
          {
            s.indices[q] = static_cast<std::int32_t>(n + s_indices[p]);
            s.data[q++] = -s_data[p];
          }
    }
    else
    {
      s.indices[q] = static_cast<std::int32_t>(n + j);
      s.data[q++] = 1.0;
    }
  }
  s.indptr[n + m] = static_cast<std::int32_t>(q);
  return s;
}
} // namespace cracklip
