// Lagrange multiplier spaces on the crack lips of a tetrahedral mesh (layer
// a): the 3D counterpart of multiplier_space_2d, with the same groups
// (multiplier_groups.h) on the graph of cut tetrahedron edges.
//
// Multipliers live on the lip pieces: the lip facets a cell holds
// (crack_geometry_3d.h: the triangulated cut polygons where psi <= 0). The
// full space holds one P1 nodal multiplier per crack and mesh node whose
// shape function has a non-zero trace on a piece, and, for the stable
// space, one P0 multiplier per front cell's piece.
//   naive : every nodal multiplier its own unknown (P1/P1, violates inf-sup);
//           front cells carry their nodes' P1 multipliers too.
//   stable: the P1- space. The graph is the edges of the cut cells (class
//           cut) whose ends lie on opposite sides (phi_a phi_b < 0, so never
//           an edge cut at a node), one per mesh edge; vital edges tie their
//           end nodes' multipliers into stars, one unknown each; a star
//           without an enriched node joins a neighbour. Front cells: a P0
//           multiplier on the piece of every front cell, tied to the
//           interior group that weighs most on that piece
//           (int_piece sum of its members' N_a); a front cell none of whose
//           nodes is in an interior group takes the group of the front cell
//           sharing most nodes with it that has one (all such cells at
//           once, repeated along the front), and the front cells of a crack
//           left without any join one group. Equals are decided by
//           geometry (multiplier_groups.h): the groups do not depend on the
//           order of nodes, cells or edges. This is the 2D tip cell's rule on a band of cells:
//           the jump fades like sqrt(r) across the front cells, and a
//           multiplier of its own there is barely controlled (the inf-sup
//           constant drops); tied, the pressure on a front cell is the
//           neighbouring star's, a constant pressure stays exact, and there
//           is no unknown more than the interior stars. Then, as 2D's rule
//           for the end of a Heaviside-only crack, a group with more than a
//           third of its weight (int of its function) on front cells
//           absorbs the group it overlaps most on the other pieces until
//           at least 2/3 of its weight lies off the front cells: a star
//           next to the front collects several front cells and would
//           otherwise live mostly where the jump fades (penny crack, a/h =
//           3, 6, 8.6: sqrt(beta_min) 0.40, 0.21, 0.30 without this step,
//           0.58, 0.33, 0.39 with it; naive P1: 5e-4, 1e-4).
#pragma once

#include "contact/multiplier_groups.h"
#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry_3d.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// The lip facets of one crack held by one cell, where multipliers and jumps
/// are integrated.
struct LipPiece3D
{
  std::int32_t crack = -1;
  std::int32_t cell = -1;
  bool front = false; ///< a front cell's piece
  /// Full multipliers active on the piece and what they are: for nodal ones
  /// the local node (0..3), for a P0 one -1.
  std::vector<std::int32_t> mult;
  std::vector<int> local;
};

/// The space: its pieces and the restriction between full and reduced
/// multipliers (P0 multipliers are the front cells').
struct MultiplierSpace3D : MultiplierRestriction
{
  std::vector<LipPiece3D> pieces;
};

/// x: (num_nodes, 3); cells: (num_cells, 4); layout: the enrichment of the
/// cracks (which nodes carry a jump). with_front_pieces: integrate the
/// pieces of the front cells (they carry a jump only with front
/// enrichment; without it the lips there are left free, as the 2D tip cell
/// without tip enrichment).
MultiplierSpace3D create_multiplier_space_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                             std::span<const CrackGeometry3D* const> cracks,
                                             const EnrichmentLayout& layout, MultiplierKind kind,
                                             bool with_front_pieces);

} // namespace cracklip
