// Multiplier groups (layer a), in any dimension: the steps of the stable
// multiplier space that see only multipliers and a graph, shared by the cut
// triangles (multiplier_space_2d) and the cut tetrahedra (multiplier_space_3d).
//
// A multiplier space has "full" multipliers (one P1 nodal function per crack
// and node whose trace on the crack is not zero, and P0 functions on the
// pieces at a tip or front) and "reduced" ones: every full multiplier belongs
// to exactly one group, a group is one reduced unknown, and the reduced
// function of a group is the sum of its members. The full functions sum to
// one on the crack, hence so do the group functions: a constant pressure is
// exact in any such space. The steps:
//   1. tie_vital_edges: the vital edges of the cut-edge graph
//      (vital_edges.h) join their end nodes' multipliers: stars;
//   2. tie_groups_without_jump: a group none of whose members carries an
//      enriched dof of its crack (the jump there fades to zero) joins a
//      group it shares a crack piece with;
//   3. dimension-specific ties at crack ends (2D: tip segment; 3D: front cells);
//   4. MultiplierGroups::number: the restriction's two maps.
#pragma once

#include "contact/vital_edges.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace cracklip
{

enum class MultiplierKind : std::int8_t
{
  naive = 0, ///< every full multiplier its own unknown (P1/P1: violates inf-sup)
  stable = 1 ///< the P1- groups (Bechet, Moes, Wohlmuth; code_aster's equality relations)
};

/// The restriction between full and reduced multipliers, with both maps:
/// full -> reduced (full_to_reduced, the 0/1 prolongation R: R[f, r] = 1 iff
/// full_to_reduced[f] == r) and reduced -> full (the members of each
/// reduced multiplier, CSR: reduced_full[reduced_offsets[r] ..
/// reduced_offsets[r + 1]), ascending).
struct MultiplierRestriction
{
  MultiplierKind kind = MultiplierKind::stable;
  /// Full multipliers (num_full each): mesh node (nodal) or -1 (P0), crack,
  /// and for a P0 multiplier its cell (-1 for nodal ones).
  std::vector<std::int32_t> full_node, full_crack, full_cell;
  std::vector<std::int32_t> full_to_reduced;                ///< (num_full)
  std::vector<std::int32_t> reduced_offsets, reduced_full; ///< (num_reduced + 1), (num_full)
  std::int32_t num_reduced = 0;
  /// Vital (tied) edges of the stable space, (num_vital, 2) mesh nodes.
  std::vector<std::int32_t> vital_edges;
  std::int32_t num_full() const { return static_cast<std::int32_t>(full_node.size()); }
};

/// Union-find over the full multipliers.
class MultiplierGroups
{
public:
  explicit MultiplierGroups(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::int32_t find(std::int32_t i)
  {
    while (parent_[i] != i)
      i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  /// Join the groups of a and b (the root of b's group stays the root).
  void unite(std::int32_t a, std::int32_t b) { parent_[find(a)] = find(b); }

  /// Number the groups in the order of their first member and fill both
  /// maps of the restriction.
  void number(MultiplierRestriction& r)
  {
    const auto n = static_cast<std::int32_t>(parent_.size());
    r.full_to_reduced.assign(n, -1);
    r.num_reduced = 0;
    std::map<std::int32_t, std::int32_t> root_to_reduced;
    for (std::int32_t f = 0; f < n; ++f)
    {
      auto [it, inserted] = root_to_reduced.try_emplace(find(f), r.num_reduced);
      if (inserted)
        ++r.num_reduced;
      r.full_to_reduced[f] = it->second;
    }
    r.reduced_offsets.assign(r.num_reduced + 1, 0);
    for (std::int32_t f = 0; f < n; ++f)
      ++r.reduced_offsets[r.full_to_reduced[f] + 1];
    std::partial_sum(r.reduced_offsets.begin(), r.reduced_offsets.end(), r.reduced_offsets.begin());
    r.reduced_full.assign(n, -1);
    std::vector<std::int32_t> next(r.reduced_offsets.begin(), r.reduced_offsets.end() - 1);
    for (std::int32_t f = 0; f < n; ++f)
      r.reduced_full[next[r.full_to_reduced[f]]++] = f;
  }

private:
  std::vector<std::int32_t> parent_;
};

/// The identity restriction (naive space): every full multiplier alone.
inline void number_naive(MultiplierRestriction& r)
{
  MultiplierGroups(r.full_node.size()).number(r);
}

/// Full index of every (crack, node) nodal multiplier.
using NodalMultipliers = std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t>;

/// The full index of the nodal multiplier of (crack ic, mesh node), added
/// to r (and to nodal) when new.
inline std::int32_t add_nodal_multiplier(MultiplierRestriction& r, NodalMultipliers& nodal, std::int32_t ic,
                                         std::int32_t node)
{
  auto [it, inserted] = nodal.try_emplace({ic, node}, r.num_full());
  if (inserted)
  {
    r.full_node.push_back(node);
    r.full_crack.push_back(ic);
    r.full_cell.push_back(-1);
  }
  return it->second;
}

/// A new P0 multiplier of crack ic on a cell: its full index.
inline std::int32_t add_cell_multiplier(MultiplierRestriction& r, std::int32_t ic, std::int32_t cell)
{
  r.full_node.push_back(-1);
  r.full_crack.push_back(ic);
  r.full_cell.push_back(cell);
  return r.num_full() - 1;
}

/// Step 1: cut_edges (crack, a, b) with a < b, possibly repeated (once per
/// cell holding the edge), and their cut points. The distinct edges, in
/// (crack, a, b) order, go through select_vital_edges; each vital edge
/// joins its end nodes' multipliers and is appended to vital_edges.
template <int Dim>
void tie_vital_edges(std::span<const CutEdge> cut_edges, std::span<const std::array<double, Dim>> cut_points,
                     const NodalMultipliers& nodal, MultiplierGroups& groups, std::vector<std::int32_t>& vital_edges)
{
  std::vector<std::size_t> order(cut_edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return cut_edges[i] < cut_edges[j]; });
  std::vector<CutEdge> edges;
  std::vector<std::array<double, Dim>> points;
  for (std::size_t k = 0; k < order.size(); ++k)
    if (k == 0 or cut_edges[order[k]] != cut_edges[order[k - 1]])
    {
      edges.push_back(cut_edges[order[k]]);
      points.push_back(cut_points[order[k]]);
    }
  const std::vector<std::int8_t> alive = select_vital_edges<Dim>(edges, points);
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (alive[i])
    {
      const std::int32_t ic = edges[i][0];
      const auto a = nodal.find({ic, edges[i][1]}), b = nodal.find({ic, edges[i][2]});
      if (a == nodal.end() or b == nodal.end())
        throw std::logic_error("multiplier space: cut edge node without a multiplier");
      groups.unite(a->second, b->second);
      vital_edges.push_back(edges[i][1]);
      vital_edges.push_back(edges[i][2]);
    }
}

/// The (crack, node) pairs carrying enriched dofs, and those carrying
/// Heaviside ones, of a 2D or 3D enrichment layout.
template <class Layout>
void enriched_nodes(const Layout& layout, std::int8_t heaviside_kind, std::set<std::pair<std::int32_t, std::int32_t>>& enriched,
                    std::set<std::pair<std::int32_t, std::int32_t>>& heaviside)
{
  for (std::int32_t k = 0; k < layout.num_enriched(); ++k)
  {
    enriched.insert({layout.crack[k], layout.node[k]});
    if (layout.kind[k] == heaviside_kind)
      heaviside.insert({layout.crack[k], layout.node[k]});
  }
}

/// Step 2: a group none of whose members is a P0 multiplier or a nodal one
/// of an enriched (crack, node) sees a jump that fades to zero and would be
/// controlled by nothing: it joins the first group with a jump among the
/// multipliers of a piece it shares (pieces in order, each with a `mult`
/// list of full multipliers), until no such group is left that has one.
/// The group functions still sum to one.
template <class Pieces>
void tie_groups_without_jump(const Pieces& pieces, const MultiplierRestriction& r,
                             const std::set<std::pair<std::int32_t, std::int32_t>>& enriched, MultiplierGroups& groups)
{
  const std::int32_t nfull = r.num_full();
  for (bool changed = true; changed;)
  {
    changed = false;
    std::map<std::int32_t, bool> has_jump; // root -> any enriched node (or P0)
    for (std::int32_t f = 0; f < nfull; ++f)
    {
      const bool j = r.full_node[f] < 0 or enriched.count({r.full_crack[f], r.full_node[f]});
      has_jump[groups.find(f)] = has_jump[groups.find(f)] or j;
    }
    for (const auto& piece : pieces)
      for (std::size_t a = 0; a < piece.mult.size() and !changed; ++a)
      {
        const std::int32_t ra = groups.find(piece.mult[a]);
        if (has_jump[ra])
          continue;
        for (std::size_t b = 0; b < piece.mult.size(); ++b)
          if (const std::int32_t rb = groups.find(piece.mult[b]); rb != ra and has_jump[rb])
          {
            groups.unite(ra, rb);
            changed = true;
            break;
          }
      }
  }
}

/// Steps 1 and 2 together (the stars, then the stars without a jump joined
/// to a neighbour) on the pieces of a space: `vital_edges` of r receives
/// the vital edges. Returns the (crack, node) pairs carrying Heaviside dofs
/// (for dimension-specific steps).
template <int Dim, class Pieces, class Layout>
std::set<std::pair<std::int32_t, std::int32_t>>
tie_stars(const Pieces& pieces, std::span<const CutEdge> cut_edges, std::span<const std::array<double, Dim>> cut_points,
          const NodalMultipliers& nodal, const Layout& layout, std::int8_t heaviside_kind, MultiplierRestriction& r,
          MultiplierGroups& groups)
{
  tie_vital_edges<Dim>(cut_edges, cut_points, nodal, groups, r.vital_edges);
  std::set<std::pair<std::int32_t, std::int32_t>> enriched, heaviside; // (crack, node)
  enriched_nodes(layout, heaviside_kind, enriched, heaviside);
  tie_groups_without_jump(pieces, r, enriched, groups);
  return heaviside;
}

} // namespace cracklip
