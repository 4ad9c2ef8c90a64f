// Which nodes carry enriched dofs, and their numbering (layer a), in any
// dimension.
//
// Every enriched function lives on a "pseudo-node" with dim dofs, numbered
// after the standard nodes (dof_numbering.h, block size dim like DOLFINx's
// P1 vector space): pseudo-node k is node num_std_nodes + k.
//   heaviside  : N_i (H - H_i) e_d,                 d = 1 .. dim
//   tip_scalar : N_i (F_l - F_l(x_i)) e_d,          l = 0..3 (one pseudo-node each)
//                (corrected scheme: F_1, F_2 are left out at one node per
//                tip, which removes the functions' two exact linear
//                dependencies per component, enrichment_selection.h)
//   tip_vector : N_i (U_m - U_m(x_i)),              m = modes I, II (, III in 3D): the dim dofs
// The selection rules are shared (enrichment_selection.h); what the crack's
// geometry decides (the core nodes around a 2D tip or a 3D front, and the
// tip functions' values there) is crack_enrichment.h's, in 2D from the tip
// frames, in 3D from the level sets and nodal frames of the nearest front
// point (front_functions_3d.h).
#pragma once

#include "enrichment/dof_numbering.h"
#include "enrichment/enrichment_selection.h"
#include "enrichment/tip_functions_2d.h"
#include "geometry/crack_geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

struct EnrichmentOptions
{
  /// Tip (2D) / front (3D) functions.
  TipEnrichment tip = TipEnrichment::none;
  /// Geometric enrichment radius: nodes within it of a tip / the front get
  /// tip dofs (besides the nodes of the cells holding it).
  double radius = 0.0;
  /// kappa = 3 - 4 nu, for the vector (Williams) functions (plane strain at
  /// a 3D front).
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
  /// Space dimension: 2 (triangles) or 3 (tetrahedra), the dofs per node.
  int dim = 2;
  std::int32_t num_std_nodes = 0;
  /// Per pseudo-node (num_enriched): base mesh node, crack index, kind,
  /// function index (l for tip_scalar, else 0), tip (a 2D tip or a 3D front
  /// piece, numbered over all cracks; -1 for heaviside), side of the base
  /// node (+1 / -1, sign of phi; +1 on the crack), core flag (1 if its base
  /// node is a core tip node: within the radius or on the cells holding the
  /// tip; 0 for blending nodes of the corrected scheme and for Heaviside
  /// pseudo-nodes) and the shift values at the base node (num_enriched, dim
  /// * dim): heaviside: H_i; tip_scalar: F_l(x_i); tip_vector: U_m(x_i) (dim
  /// x dim, row m the mode).
  std::vector<std::int32_t> node;
  std::vector<std::int32_t> crack;
  std::vector<std::int8_t> kind;
  std::vector<std::int8_t> function;
  std::vector<std::int32_t> tip;
  std::vector<std::int8_t> node_side;
  std::vector<std::int8_t> core;
  std::vector<double> shift;
  /// Per tip / front piece: its crack and its index within the crack.
  std::vector<std::int32_t> tip_crack, tip_local;
  /// 2D: the frame of every tip.
  std::vector<TipFrame> tip_frames;
  /// 3D: nodal frames (e1, e2, e3 of the nearest front point), for every
  /// node of every cell that carries front functions: frame_node sorted by
  /// (node, crack), node_frames (len(frame_node), 9), frame_crack the crack
  /// they belong to.
  std::vector<std::int32_t> frame_node, frame_crack;
  std::vector<double> node_frames;
  double kappa = 1.8;
  /// Tip functions carry the core ramp (corrected X-FEM).
  bool corrected = false;

  std::int32_t num_enriched() const { return static_cast<std::int32_t>(node.size()); }
  std::int32_t num_nodes_total() const { return num_std_nodes + num_enriched(); }
  /// 3D: the frame (9 values) of node n for crack ic, or nullptr if it has none.
  const double* frame(std::int32_t n, std::int32_t ic) const;
  /// Throws unless the layout was made on a mesh of dimension d (who: the
  /// caller, for the message).
  void require_dimension(int d, const char* who) const;
};

/// Enrichment of every crack on a mesh with coordinates x (num_nodes, dim)
/// and cells (num_cells, dim + 1) (dim from the cracks' geometry).
///
/// Tip: with options.tip != none, every node within options.radius of a tip
/// (the front) and every node of the cells holding it (the core) gets tip
/// functions (in 3D also the nodes of the extension cells next to the crack's
/// cells, crack_enrichment.h); with options.corrected, so does every node of
/// a cell with a core node, and all tip functions are multiplied by the
/// core's ramp. Heaviside: a node that is not tip-enriched for a crack is
/// enriched when its support contains a cut cell of that crack, or a cell
/// whose crack edge / face the node lies on, and no tip (front) or extension
/// cell (where a Heaviside function would open a crack that is not there):
/// exactly the nodes whose function N_i (H - H_i) is not zero (in 3D less
/// those whose share of the jump the ramp leaves negligible). Throws if one
/// cell is crossed by two cracks or a geometry belongs to another mesh.
EnrichmentLayout create_enrichment_layout(std::span<const double> x, std::span<const std::int32_t> cells,
                                          std::span<const CrackGeometry* const> cracks,
                                          const EnrichmentOptions& options);
EnrichmentLayout create_enrichment_layout(std::span<const double> x, std::span<const std::int32_t> cells,
                                          std::span<const CrackGeometry3D* const> cracks,
                                          const EnrichmentOptions& options);

/// The same layout with only the enriched cells below num_cells (a process's
/// owned cells under MPI, which come first): every pseudo-node is kept, so
/// the dof numbering is unchanged; the kernels that loop over layout.cells
/// then integrate each cell on one process only.
EnrichmentLayout with_cells_below(const EnrichmentLayout& layout, std::int32_t num_cells);

} // namespace cracklip
