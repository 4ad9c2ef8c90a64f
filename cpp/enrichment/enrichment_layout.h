// Which nodes carry enriched dofs, and their numbering (layer a).
//
// Every enriched function lives on a "pseudo-node" with two dofs, numbered
// after the standard nodes: pseudo-node k has global node index
// num_std_nodes + k and scalar dofs 2 (num_std_nodes + k) + {0, 1}. All
// blocks therefore have block size 2, like DOLFINx's P1 vector space.
//   heaviside  : N_i (H - H_i) e_d,                 d = x, y
//   tip_scalar : N_i (F_l - F_l(x_i)) e_d,          l = 0..3 (one pseudo-node each)
//                (corrected scheme: F_1, F_2 are left out at one node per
//                tip, which removes the functions' two exact linear
//                dependencies per component, see enrichment.cpp)
//   tip_vector : N_i (U_m - U_m(x_i)),              m = mode I, mode II (the two dofs)
#pragma once

#include "geometry/crack_geometry_2d.h"
#include "enrichment/dof_numbering.h"
#include "enrichment/enrichment_selection.h"
#include "enrichment/tip_functions_2d.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

struct EnrichmentOptions
{
  TipEnrichment tip = TipEnrichment::none;
  /// Geometric enrichment radius: nodes within it of a tip get tip dofs
  /// (besides the nodes of the cell holding the tip).
  double radius = 0.0;
  /// kappa = 3 - 4 nu, for the vector (Williams) functions.
  double kappa = 1.8;
  /// Corrected X-FEM (Fries 2008): tip functions are multiplied by the ramp
  /// R = sum of N_i over the "core" tip nodes, and every node of a cell with a
  /// core node carries them. In blending cells the enrichment then reproduces
  /// R (F - I_h F), which removes the O(sqrt(h)) blending error of the
  /// standard scheme; inside the core R = 1 and nothing changes.
  bool corrected = true;
};

/// Enriched pseudo-nodes and the cells on which they live (EnrichedCells:
/// cells, cell_offsets, cell_enr, cell_index).
struct EnrichmentLayout : EnrichedCells
{
  std::int32_t num_std_nodes = 0;
  /// Per pseudo-node (num_enriched): base mesh node, crack index, kind,
  /// function index (l for tip_scalar, else 0), tip (index into tip_frames,
  /// -1 for heaviside), side of the base node (+1 / -1, sign of phi; +1 on
  /// the crack) and the shift values at the base node (num_enriched, 4):
  /// heaviside: H_i; tip_scalar: F_l(x_i); tip_vector: U_I(x_i), U_II(x_i).
  std::vector<std::int32_t> node;
  std::vector<std::int32_t> crack;
  std::vector<std::int8_t> kind;
  std::vector<std::int8_t> function;
  std::vector<std::int32_t> tip;
  std::vector<std::int8_t> node_side;
  std::vector<double> shift;
  /// Per pseudo-node: 1 if its base node is a core tip node (within the
  /// radius or on the tip cell), 0 for blending nodes of the corrected
  /// scheme and for Heaviside pseudo-nodes.
  std::vector<std::int8_t> core;
  /// Tips of all cracks: frames and (crack, tip index in that crack).
  std::vector<TipFrame> tip_frames;
  std::vector<std::int32_t> tip_crack, tip_local;
  double kappa = 1.8;
  /// Tip functions carry the core ramp (corrected X-FEM).
  bool corrected = false;

  std::int32_t num_enriched() const { return static_cast<std::int32_t>(node.size()); }
  std::int32_t num_nodes_total() const { return num_std_nodes + num_enriched(); }
};

/// Enrichment of every crack.
///
/// Tip: with options.tip != none, every node within options.radius of a tip
/// and every node of a cell whose closure holds the tip (the core) gets tip
/// functions; with options.corrected, so does every node of a cell with a
/// core node, and all tip functions are multiplied by the core's ramp.
/// Heaviside: a node that is not tip-enriched for a crack is enriched when
/// its support contains a cut cell of that crack, or an edge cell whose crack
/// edge the node lies on, and no tip or extension cell (where a Heaviside
/// function would open a crack that is not there): exactly the nodes whose
/// function N_i (H - H_i) is not zero. Throws if one cell is crossed by two
/// cracks.
///
/// x: (num_nodes, 2); cells: (num_cells, 3).
EnrichmentLayout create_enrichment_layout(std::span<const double> x,
                                          std::span<const std::int32_t> cells,
                                          std::span<const CrackGeometry* const> cracks,
                                          const EnrichmentOptions& options);

} // namespace cracklip
