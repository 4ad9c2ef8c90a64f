// Which nodes carry which enrichment (layer a), in any dimension.
//
// The rules are the same on triangles and tetrahedra; only the inputs come
// from the geometry of the dimension (crack_enrichment_2d.cpp,
// crack_enrichment_3d.cpp):
//   - core tip (front) nodes: given by the caller (nodes within the
//     enrichment radius of a tip / the front, and the nodes of the cells
//     holding it), each with the tip (front piece) whose functions it takes;
//   - corrected blending (Fries 2008): every other node of a cell with a
//     core node takes the functions of that cell's first core node, and all
//     tip functions carry the core's ramp R = sum of N_i over core nodes;
//   - Heaviside: a node that is not core (or is core on a crossed cell that
//     also holds a non-core node, where 1 - R does not vanish) gets N_i (H -
//     H_i) when its support holds a cut cell, or a cell whose crack face /
//     edge holds the node, and no tip or extension cell (unless the ramp is
//     1 on that cell: every node core), where a Heaviside function would
//     open a crack that is not there;
//   - scalar branch functions with corrected blending: F_1, F_2 are left
//     out at one node per tip (the node farthest from the crack's plane),
//     which removes the functions' two exact linear dependencies per
//     component (see enrichment_selection.cpp), when the tip's functions cover
//     the whole support of its ramp.
// Cell class codes (CellClass in 2D, CellClass3D in 3D): 0 plain, 1 cut,
// 2 crack along an edge (2D) / a face (3D), 3 tip / front, 4 extension.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace cracklip
{

/// Kind of enrichment function of a pseudo-node.
enum class EnrichmentKind : std::int8_t
{
  heaviside = 0,
  tip_scalar = 1,
  tip_vector = 2
};

/// Tip (front) enrichment of the scene.
enum class TipEnrichment : std::int8_t
{
  none = 0,
  scalar = 1,
  vector = 2
};

/// One pseudo-node as selected: base node, kind, function index (l of a
/// scalar branch function, else 0), tip (-1 for Heaviside), core flag.
struct PseudoNode
{
  std::int32_t node;
  EnrichmentKind kind;
  std::int8_t function;
  std::int32_t tip;
  bool core;
};

/// One crack's selection input. cells: (num_cells, nodes_per_cell);
/// cell_class (num_cells) codes as above; phi (num_nodes) the crack's
/// normal level set (phi == 0 marks nodes on the crack); core_tip
/// (num_nodes) the tip each core node takes (-1 for others); tips: the tip
/// ids of this crack; plane_distance(node, tip): the distance of a node to
/// the crack's plane (its line in 2D) at that tip, which picks the node that
/// drops F_1, F_2 (called only for scalar functions with corrected blending).
struct SelectionInput
{
  std::span<const std::int32_t> cells;
  int nodes_per_cell;
  std::span<const std::int8_t> cell_class;
  std::span<const double> phi;
  std::span<const std::int32_t> core_tip;
  std::span<const std::int32_t> tips;
  std::function<double(std::int32_t, std::int32_t)> plane_distance;
  /// Optional: opens(cell, node) says whether a cut cell has volume on the
  /// side of the crack opposite the node (where the node's Heaviside
  /// function is not zero). Without it every cut cell does (2D: snapping
  /// leaves no sub-cell thinner than snap_tol h; in 3D a sliver below the
  /// cutting's tolerance is dropped, and a Heaviside function living only
  /// there would have no stiffness).
  std::function<bool(std::int32_t, std::int32_t)> opens = nullptr;
  /// Optional: keep_heaviside(node, is_core) says whether a node that
  /// qualifies for a Heaviside function N_i (H - H_i) (1 - R) keeps it,
  /// given which nodes are core: the function may be so small (the crack
  /// passing far from the node in its cells, (1 - R) small where it opens)
  /// that it carries next to no jump and only ruins the conditioning.
  /// Without it every qualifying node keeps it.
  std::function<bool(std::int32_t, std::span<const std::int8_t>)> keep_heaviside = nullptr;
};

/// The pseudo-nodes of one crack, in the order they are numbered: for each
/// node in turn, its tip functions (4 scalar or 1 vector) then its
/// Heaviside function. Appends each pseudo-node's position (first_index +
/// its rank) to node_pseudo[node].
std::vector<PseudoNode> select_enrichment(const SelectionInput& in, TipEnrichment tip, bool corrected,
                                          std::int32_t first_index,
                                          std::vector<std::vector<std::int32_t>>& node_pseudo);

} // namespace cracklip
