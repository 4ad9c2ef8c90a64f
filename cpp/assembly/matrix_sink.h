// Where assemblers write (layer a), in any dimension: "add these values at
// these global indices". The same kernel then fills a PETSc matrix
// (dolfinx_glue.h petsc_add_sink), a COO collector in a test, or a future
// distributed matrix; it never sees the storage.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <vector>

namespace cracklip
{

/// Receives a dense block: values is row-major (rows.size(), cols.size()),
/// indices are global scalar dofs. Negative indices are to be ignored.
using MatrixSink = std::function<void(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                                      std::span<const double> values)>;

/// Triplets (row, col, value): a COO matrix.
struct Triplets
{
  std::vector<std::int32_t> row, col;
  std::vector<double> value;
};

/// A sink appending every block to `out` as triplets, skipping negative
/// indices and exact zeros.
inline MatrixSink coo_sink(Triplets& out)
{
  return [&out](std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                std::span<const double> values)
  {
    if (values.size() != rows.size() * cols.size())
      throw std::invalid_argument("coo_sink: block values do not match its rows x columns");
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < cols.size(); ++j)
        if (const double v = values[i * cols.size() + j]; rows[i] >= 0 and cols[j] >= 0 and v != 0.0)
        {
          out.row.push_back(rows[i]);
          out.col.push_back(cols[j]);
          out.value.push_back(v);
        }
  };
}

} // namespace cracklip
