// Which nodes carry enriched dofs, and their numbering (layer a).
//
// Every enriched function lives on a "pseudo-node" with two dofs (x, y),
// numbered after the standard nodes: pseudo-node k has global node index
// num_std_nodes + k and scalar dofs 2 (num_std_nodes + k) + {0, 1}. All
// blocks therefore have block size 2, like DOLFINx's P1 vector space.
#pragma once

#include "crack_geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Kind of enrichment function of a pseudo-node.
enum class EnrichmentKind : std::int8_t
{
  heaviside = 0 ///< shifted Heaviside N_i (H(x) - H(x_i))
};

/// Enriched pseudo-nodes and the cells on which they live.
struct EnrichmentLayout
{
  std::int32_t num_std_nodes = 0;
  /// Per pseudo-node (num_enriched): base mesh node, crack index, kind, and
  /// for Heaviside the value H(x_i) at the base node (+1 or -1; +1 for a
  /// node on the crack).
  std::vector<std::int32_t> node;
  std::vector<std::int32_t> crack;
  std::vector<std::int8_t> kind;
  std::vector<double> node_sign;
  /// Cells with at least one enriched node (sorted), (num_enriched_cells).
  std::vector<std::int32_t> cells;
  /// CSR of pseudo-nodes per enriched cell: pseudo-nodes of cells[i] are
  /// cell_enr[cell_offsets[i]:cell_offsets[i+1]].
  std::vector<std::int32_t> cell_offsets;
  std::vector<std::int32_t> cell_enr;
  /// Position of each mesh cell in `cells` or -1, (num_cells).
  std::vector<std::int32_t> cell_index;

  std::int32_t num_enriched() const { return static_cast<std::int32_t>(node.size()); }
  std::int32_t num_nodes_total() const { return num_std_nodes + num_enriched(); }
};

/// Heaviside enrichment of every crack. A node is enriched for a crack when
/// its support contains a cut cell of that crack, or an edge cell whose crack
/// edge the node lies on, and no tip or extension cell (where a Heaviside
/// function would open a crack that is not there): exactly the nodes whose
/// function N_i (H - H_i) is not zero. Throws if one cell is crossed by two
/// cracks.
///
/// cells: (num_cells, 3) node indices; num_nodes: number of mesh nodes.
EnrichmentLayout create_heaviside_layout(std::span<const std::int32_t> cells,
                                         std::int32_t num_nodes,
                                         std::span<const CrackGeometry* const> cracks);

} // namespace cracklip
