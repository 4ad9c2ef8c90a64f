// Enriched dofs and the cells that carry them (layer a), in any dimension.
//
// Every enriched function lives on a "pseudo-node" numbered after the
// standard nodes: pseudo-node k is node num_std_nodes + k, with block_size
// scalar dofs (the space dimension: 2 on triangles, 3 on tetrahedra), like
// DOLFINx's P1 vector space, so all blocks share one block size. Which
// nodes get which functions is the geometry's business (2D or 3D); given
// each node's pseudo-nodes, the numbering below is the same in every
// dimension.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Scalar dof of component d of node `node` (a standard node, or
/// num_std_nodes + k for pseudo-node k) with block size bs.
constexpr std::int32_t node_dof(std::int32_t node, int d, int bs) { return bs * node + d; }

/// Cells with at least one enriched node and their pseudo-nodes.
struct EnrichedCells
{
  /// Cells with at least one enriched node (sorted), (num_enriched_cells).
  std::vector<std::int32_t> cells;
  /// CSR of pseudo-nodes per enriched cell: pseudo-nodes of cells[i] are
  /// cell_enr[cell_offsets[i]:cell_offsets[i+1]], in the order of the
  /// cell's nodes and, per node, of node_pseudo.
  std::vector<std::int32_t> cell_offsets;
  std::vector<std::int32_t> cell_enr;
  /// Position of each mesh cell in `cells` or -1, (num_cells).
  std::vector<std::int32_t> cell_index;
};

/// The enriched cells of a mesh whose cells (num_cells, nodes_per_cell)
/// list node indices, from the pseudo-nodes of every node (node_pseudo:
/// num_nodes lists). Work: one pass over the cells.
EnrichedCells create_enriched_cells(std::span<const std::int32_t> cells, int nodes_per_cell,
                                    std::span<const std::vector<std::int32_t>> node_pseudo);

} // namespace cracklip
