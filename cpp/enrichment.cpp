#include "enrichment.h"

#include <stdexcept>
#include <string>

namespace cracklip
{

EnrichmentLayout create_heaviside_layout(std::span<const std::int32_t> cells,
                                         std::int32_t num_nodes,
                                         std::span<const CrackGeometry* const> cracks)
{
  const std::size_t num_cells = cells.size() / 3;
  EnrichmentLayout layout;
  layout.num_std_nodes = num_nodes;

  // One cell may be crossed by one crack only.
  std::vector<std::int32_t> crossed_by(num_cells, -1);
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const CrackGeometry& g = *cracks[ic];
    if (g.cell_class.size() != num_cells or g.phi.size() != static_cast<std::size_t>(num_nodes))
      throw std::invalid_argument("create_heaviside_layout: crack geometry of crack "
                                  + std::to_string(ic) + " does not match the mesh");
    for (std::size_t c = 0; c < num_cells; ++c)
    {
      const auto cls = static_cast<CellClass>(g.cell_class[c]);
      if (cls == CellClass::plain)
        continue;
      if (cls != CellClass::extension and crossed_by[c] >= 0)
        throw std::runtime_error("cell " + std::to_string(c) + " is crossed by cracks "
                                 + std::to_string(crossed_by[c]) + " and " + std::to_string(ic)
                                 + ": cracks closer than the mesh size are not supported; "
                                   "refine the mesh near them");
      if (cls != CellClass::extension)
        crossed_by[c] = static_cast<std::int32_t>(ic);
    }
  }

  // pseudo-node id per (crack, node), -1 if none.
  std::vector<std::vector<std::int32_t>> enr_id(cracks.size());
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const CrackGeometry& g = *cracks[ic];
    std::vector<std::int8_t> split(num_nodes, 0), forbidden(num_nodes, 0);
    for (std::size_t c = 0; c < num_cells; ++c)
    {
      const auto cls = static_cast<CellClass>(g.cell_class[c]);
      // A node's Heaviside function N_i (H - H_i) is non-zero on a cut cell,
      // and on an edge cell only if the node lies on the crack edge (a node
      // off the edge is on the cell's own side, where the function is 0).
      for (int i = 0; i < 3; ++i)
      {
        const std::int32_t v = cells[3 * c + i];
        if (cls == CellClass::cut or (cls == CellClass::edge and g.phi[v] == 0.0))
          split[v] = 1;
        else if (cls == CellClass::tip or cls == CellClass::extension)
          forbidden[v] = 1;
      }
    }
    enr_id[ic].assign(num_nodes, -1);
    for (std::int32_t i = 0; i < num_nodes; ++i)
    {
      if (split[i] and !forbidden[i])
      {
        enr_id[ic][i] = layout.num_enriched();
        layout.node.push_back(i);
        layout.crack.push_back(static_cast<std::int32_t>(ic));
        layout.kind.push_back(static_cast<std::int8_t>(EnrichmentKind::heaviside));
        layout.node_sign.push_back(g.phi[i] >= 0.0 ? 1.0 : -1.0);
      }
    }
  }

  // Enriched cells and their pseudo-nodes.
  layout.cell_index.assign(num_cells, -1);
  layout.cell_offsets.push_back(0);
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const std::size_t before = layout.cell_enr.size();
    for (std::size_t ic = 0; ic < cracks.size(); ++ic)
      for (int i = 0; i < 3; ++i)
        if (const std::int32_t k = enr_id[ic][cells[3 * c + i]]; k >= 0)
          layout.cell_enr.push_back(k);
    if (layout.cell_enr.size() > before)
    {
      layout.cell_index[c] = static_cast<std::int32_t>(layout.cells.size());
      layout.cells.push_back(static_cast<std::int32_t>(c));
      layout.cell_offsets.push_back(static_cast<std::int32_t>(layout.cell_enr.size()));
    }
  }
  return layout;
}

} // namespace cracklip
