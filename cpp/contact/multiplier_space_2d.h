// Lagrange multiplier spaces on the crack (layer a).
//
// Multipliers live on the crack segments of the cells the crack crosses. The
// "full" space holds one P1 nodal multiplier per mesh node whose shape
// function has a non-zero trace on a segment, and, for the stable space, one
// P0 multiplier per cell holding a tip. A reduced space is a 0/1 prolongation
// R (reduced -> full): every full multiplier maps to one reduced multiplier.
//   naive : every nodal multiplier is its own unknown (P1/P1, violates inf-sup)
//   stable: the Bechet-Moes-Wohlmuth P1- space: cut edges are dropped by
//           score min(deg a, deg b) while it exceeds 1; the remaining
//           ("vital") edges tie their end nodes' multipliers, forming stars,
//           one unknown each; the tip cell carries a P0 multiplier.
//           The end segment sees a fading jump: the tip cell's P0
//           multiplier is tied to the neighbouring segment's multiplier
//           largest at the shared point; the group of the last cut cell of
//           a Heaviside-only crack absorbs its most overlapping neighbour
//           group until at least 2/3 of its weight sees the full jump; a
//           tip-enriched crack whose tip sits on an edge or vertex ties its
//           end segment when shorter than the crack's mean segment. Equals
//           are decided by geometry (multiplier_groups.h): the groups do
//           not depend on the order of nodes, cells or edges.
#pragma once

#include "contact/multiplier_groups.h"
#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry_2d.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// One crack segment in one cell, where multipliers and jumps are integrated.
struct CrackSegment
{
  std::int32_t crack = -1;
  std::int32_t cell = -1;
  std::array<double, 4> ref = {}; ///< end points P, Q in reference coordinates
  bool tip = false;               ///< the segment ends at a crack tip (tip cell)
  int tip_end = -1;               ///< 0 or 1: which end is the tip
  std::int32_t tip_index = -1;    ///< index into CrackGeometry::tips
  /// Full multipliers active on the segment and what they are: for nodal
  /// ones the local node (0..2), for a P0 one -1.
  std::vector<std::int32_t> mult;
  std::vector<int> local;
};

/// The space: its crack segments and the restriction between full and
/// reduced multipliers (multiplier_groups.h; P0 multipliers are the tip
/// cells').
struct MultiplierSpace : MultiplierRestriction
{
  std::vector<CrackSegment> segments;
};

/// x: (num_nodes, 2); cells: (num_cells, 3). with_tip_segments: integrate
/// the segment in the tip cell (it carries a jump only with tip enrichment).
/// In the stable space a star none of whose nodes carries enriched dofs of
/// its crack (e.g. the nodes of an unenriched tip cell) sees a jump that
/// fades to zero and would be controlled by nothing: it is tied to a
/// neighbouring star (the star functions still sum to one).
MultiplierSpace create_multiplier_space(std::span<const double> x, std::span<const std::int32_t> cells,
                                        std::span<const CrackGeometry* const> cracks,
                                        const EnrichmentLayout& layout, MultiplierKind kind,
                                        bool with_tip_segments);

} // namespace cracklip
