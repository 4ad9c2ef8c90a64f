// Which nodes of a tetrahedral mesh carry enriched dofs, and their numbering
// (layer a).
//
// Every enriched function lives on a pseudo-node with three dofs, numbered
// after the standard nodes (enrichment/dof_numbering.h, block size 3):
//   heaviside  : N_i (H - H_i) e_d,                   d = x, y, z
//   tip_scalar : N_i (F_l - F_l(x_i)) e_d,            l = 0..3 (one pseudo-node each)
//   tip_vector : N_i (U_m - U_m(x_i)),                m = modes I, II, III (the three dofs)
// The front functions are those of front_functions_3d.h in the level sets'
// local coordinates (x1 = psi, x2 = phi) with the directions interpolated
// from nodal frames (the frame of each node's nearest point on the front),
// times the ramp R of corrected blending. The selection rules are the ones
// shared with 2D (enrichment_selection.h); core front nodes are the nodes
// within the enrichment radius of the front and the nodes of the cells
// holding it.
#pragma once

#include "enrichment/dof_numbering.h"
#include "enrichment/enrichment_selection.h"
#include "enrichment/front_functions_3d.h"
#include "geometry/crack_geometry_3d.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

struct EnrichmentOptions3D
{
  TipEnrichment front = TipEnrichment::vector;
  /// Geometric enrichment radius: nodes within it of the front get front
  /// dofs (besides the nodes of the cells holding the front).
  double radius = 0.0;
  /// kappa = 3 - 4 nu of the vector functions (plane strain at the front).
  double kappa = 1.8;
  /// Corrected blending (as in 2D).
  bool corrected = true;
};

/// Enriched pseudo-nodes of a tetrahedral mesh (EnrichedCells: cells,
/// cell_offsets, cell_enr, cell_index).
struct EnrichmentLayout3D : EnrichedCells
{
  std::int32_t num_std_nodes = 0;
  /// Per pseudo-node (num_enriched): base node, crack, kind, function (l of
  /// a scalar function, else 0), front piece (global over the cracks; -1
  /// for heaviside), side of the base node (+1 / -1, sign of phi; +1 on the
  /// crack), core flag, and shift values (num_enriched, 9): heaviside H_i;
  /// tip_scalar F_l(x_i); tip_vector U_I, U_II, U_III at x_i (3 x 3).
  std::vector<std::int32_t> node, crack;
  std::vector<std::int8_t> kind, function;
  std::vector<std::int32_t> piece;
  std::vector<std::int8_t> node_side, core;
  std::vector<double> shift;
  /// Front pieces of all cracks: (crack, piece within the crack).
  std::vector<std::int32_t> piece_crack, piece_local;
  /// Nodal frames (e1, e2, e3 of the nearest front point), for every node
  /// of every cell that carries front functions: frame_node sorted,
  /// node_frames (len(frame_node), 9), frame_crack the crack they belong to.
  std::vector<std::int32_t> frame_node, frame_crack;
  std::vector<double> node_frames;
  double kappa = 1.8;
  bool corrected = false;

  std::int32_t num_enriched() const { return static_cast<std::int32_t>(node.size()); }
  std::int32_t num_nodes_total() const { return num_std_nodes + num_enriched(); }
  /// The frame (9 values) of a node for crack ic, or nullptr if it has none.
  const double* frame(std::int32_t n, std::int32_t ic) const;
};

/// Enrichment of every crack (see the file header). x: (num_nodes, 3);
/// cells: (num_cells, 4). Throws if one cell is crossed by two cracks.
EnrichmentLayout3D create_enrichment_layout_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                               std::span<const CrackGeometry3D* const> cracks,
                                               const EnrichmentOptions3D& options);

} // namespace cracklip
