// Sparsity of the enriched stiffness matrix (layer a), in any dimension.
#pragma once

#include "enrichment/dof_numbering.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Compressed sparse rows: offsets (num_rows + 1), sorted column indices.
struct CSR
{
  std::vector<std::int32_t> offsets;
  std::vector<std::int32_t> indices;
};

/// Node-block pattern over standard nodes (0 .. num_std_nodes - 1) and
/// pseudo-nodes (num_std_nodes + k, k < num_pseudo): two nodes couple when
/// they are active on a common cell (cells: (num_cells, nodes_per_cell),
/// 3 for triangles, 4 for tetrahedra). Rows: num_std_nodes + num_pseudo.
/// Expand with expand_blocks (block size = the space dimension).
CSR create_block_sparsity(std::span<const std::int32_t> cells, int nodes_per_cell, std::int32_t num_std_nodes,
                          std::int32_t num_pseudo, const EnrichedCells& enriched);

/// Expand a block pattern to scalar rows and columns with block size bs.
CSR expand_blocks(const CSR& blocks, int bs);

} // namespace cracklip
