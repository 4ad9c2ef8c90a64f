#include "assembly/sparsity.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cracklip
{

CSR create_block_sparsity(std::span<const std::int32_t> cells, int nodes_per_cell, std::int32_t num_std_nodes,
                          std::int32_t num_pseudo, const EnrichedCells& enriched)
{
  const std::int32_t n = num_std_nodes + num_pseudo;
  const std::size_t num_cells = cells.size() / nodes_per_cell;
  if (enriched.cell_index.size() != num_cells)
    throw std::invalid_argument("create_block_sparsity: the enriched cells are numbered on "
                                + std::to_string(enriched.cell_index.size()) + " cells, the mesh has "
                                + std::to_string(num_cells));
  // Node lists of every cell: its standard nodes, plus pseudo-nodes.
  auto cell_nodes = [&](std::size_t c, std::vector<std::int32_t>& out)
  {
    out.assign(cells.begin() + nodes_per_cell * c, cells.begin() + nodes_per_cell * (c + 1));
    if (const std::int32_t ie = enriched.cell_index[c]; ie >= 0)
      for (std::int32_t j = enriched.cell_offsets[ie]; j < enriched.cell_offsets[ie + 1]; ++j)
        out.push_back(num_std_nodes + enriched.cell_enr[j]);
  };

  // Node -> cells (counting sort).
  std::vector<std::int32_t> count(n + 1, 0);
  std::vector<std::int32_t> nodes;
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    cell_nodes(c, nodes);
    for (auto v : nodes)
      ++count[v + 1];
  }
  for (std::int32_t i = 0; i < n; ++i)
    count[i + 1] += count[i];
  std::vector<std::int32_t> node_cells(count[n]);
  std::vector<std::int32_t> pos(count.begin(), count.end() - 1);
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    cell_nodes(c, nodes);
    for (auto v : nodes)
      node_cells[pos[v]++] = static_cast<std::int32_t>(c);
  }

  CSR csr;
  csr.offsets.reserve(n + 1);
  csr.offsets.push_back(0);
  csr.indices.reserve(static_cast<std::size_t>(4 * nodes_per_cell) * static_cast<std::size_t>(n));
  std::vector<std::int32_t> row;
  for (std::int32_t i = 0; i < n; ++i)
  {
    row.clear();
    for (std::int32_t k = count[i]; k < count[i + 1]; ++k)
    {
      cell_nodes(node_cells[k], nodes);
      row.insert(row.end(), nodes.begin(), nodes.end());
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    csr.indices.insert(csr.indices.end(), row.begin(), row.end());
    csr.offsets.push_back(static_cast<std::int32_t>(csr.indices.size()));
  }
  return csr;
}

CSR expand_blocks(const CSR& blocks, int bs)
{
  const std::size_t nb = blocks.offsets.size() - 1;
  CSR out;
  out.offsets.resize(nb * bs + 1);
  out.indices.resize(blocks.indices.size() * bs * bs);
  out.offsets[0] = 0;
  std::size_t p = 0;
  for (std::size_t i = 0; i < nb; ++i)
    for (int a = 0; a < bs; ++a)
    {
      for (std::int32_t k = blocks.offsets[i]; k < blocks.offsets[i + 1]; ++k)
        for (int b = 0; b < bs; ++b)
          out.indices[p++] = bs * blocks.indices[k] + b;
      out.offsets[i * bs + a + 1] = static_cast<std::int32_t>(p);
    }
  return out;
}

} // namespace cracklip
