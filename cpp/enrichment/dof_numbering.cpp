#include "enrichment/dof_numbering.h"

#include <stdexcept>
#include <string>

namespace cracklip
{

EnrichedCells create_enriched_cells(std::span<const std::int32_t> cells, int nodes_per_cell,
                                    std::span<const std::vector<std::int32_t>> node_pseudo)
{
  if (nodes_per_cell < 1 or cells.size() % nodes_per_cell != 0)
    throw std::invalid_argument("create_enriched_cells: " + std::to_string(cells.size())
                                + " cell entries are not a whole number of cells of "
                                + std::to_string(nodes_per_cell) + " nodes");
  const std::size_t num_cells = cells.size() / nodes_per_cell;
  EnrichedCells out;
  out.cell_index.assign(num_cells, -1);
  out.cell_offsets.push_back(0);
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const std::size_t before = out.cell_enr.size();
    for (int a = 0; a < nodes_per_cell; ++a)
    {
      const std::int32_t v = cells[nodes_per_cell * c + a];
      if (v < 0 or static_cast<std::size_t>(v) >= node_pseudo.size())
        throw std::invalid_argument("create_enriched_cells: cell " + std::to_string(c) + " names node "
                                    + std::to_string(v) + " of " + std::to_string(node_pseudo.size()));
      out.cell_enr.insert(out.cell_enr.end(), node_pseudo[v].begin(), node_pseudo[v].end());
    }
    if (out.cell_enr.size() > before)
    {
      out.cell_index[c] = static_cast<std::int32_t>(out.cells.size());
      out.cells.push_back(static_cast<std::int32_t>(c));
      out.cell_offsets.push_back(static_cast<std::int32_t>(out.cell_enr.size()));
    }
  }
  return out;
}

} // namespace cracklip
