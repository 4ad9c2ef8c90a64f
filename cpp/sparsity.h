// Sparsity of the enriched stiffness matrix (layer a).
#pragma once

#include "enrichment.h"

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

/// Node-block pattern (block size 2) over standard nodes and pseudo-nodes:
/// two nodes couple when they are active on a common cell. Rows:
/// layout.num_nodes_total().
CSR create_block_sparsity(std::span<const std::int32_t> cells, const EnrichmentLayout& layout);

/// Expand a block pattern to scalar rows and columns with block size bs.
CSR expand_blocks(const CSR& blocks, int bs);

} // namespace cracklip
