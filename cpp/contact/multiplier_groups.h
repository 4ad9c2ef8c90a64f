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
//      enriched dof of its crack (the jump there fades to zero) joins the
//      group with a jump it shares most crack pieces with;
//   3. dimension-specific ties at crack ends (2D: tip segment; 3D: front cells);
//   4. MultiplierGroups::number: the restriction's two maps.
//
// The groups do not depend on the order of the input (node numbering, cell
// order, cut-edge order, a cell's vertex order): wherever a step chooses
// between candidates it decides by geometry, then by an order-free name.
// The vital edges by (score, spacing, cut point) (vital_edges.h); every
// other choice takes the candidate group of the largest measure (an integer
// count, or a weight or overlap integral), measures within a relative
// TIE_TOL of the largest counting as equal (their sums round off
// differently in another order), and among equals the group whose key
// (group_keys: its smallest member key) is smallest. A member's key
// (multiplier_keys) is its crack, nodal before P0, and the coordinates of
// its node, or of its cell's vertices in (x, y, z) order. Steps that let
// several groups choose (groups without a jump, front cells without an
// interior group, a 2D tip cell's neighbouring segments) choose all at once
// per round, against the groups as they were at the round's start. Only the numbering of the groups (step 4, by
// first member) follows the input order; the groups as sets of members do
// not (tests/test_contact_order.py, tests/cpp/test_vital_edges.cpp).
#pragma once

#include "contact/vital_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <span>
#include <stdexcept>
#include <tuple>
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

/// An order-free name of a full multiplier: crack, 0 (nodal) or 1 (P0), and
/// the coordinates of its node or of its cell's vertices sorted in (x, y,
/// z) order (padded with zeros to 12 numbers).
using MultiplierKey = std::tuple<std::int32_t, std::int8_t, std::array<double, 12>>;

/// The vertices of a cell of a mesh x (num_nodes, gdim), cells (num_cells,
/// gdim + 1), sorted in (x, y, z) order: an order-free name of the cell
/// (padded with zeros to 12 numbers).
inline std::array<double, 12> cell_key(std::span<const double> x, std::span<const std::int32_t> cells, int gdim,
                                       std::int32_t cell)
{
  const int npc = gdim + 1;
  std::vector<std::vector<double>> v(npc);
  for (int a = 0; a < npc; ++a)
  {
    const double* p = &x[gdim * cells[npc * cell + a]];
    v[a].assign(p, p + gdim);
  }
  std::sort(v.begin(), v.end());
  std::array<double, 12> c{};
  for (int a = 0; a < npc; ++a)
    std::copy(v[a].begin(), v[a].end(), c.begin() + gdim * a);
  return c;
}

/// The key of every full multiplier of r on a mesh x (num_nodes, gdim),
/// cells (num_cells, gdim + 1).
inline std::vector<MultiplierKey> multiplier_keys(const MultiplierRestriction& r, std::span<const double> x,
                                                  std::span<const std::int32_t> cells, int gdim)
{
  std::vector<MultiplierKey> keys(r.full_node.size());
  for (std::size_t f = 0; f < keys.size(); ++f)
  {
    auto& [crack, p0, c] = keys[f];
    crack = r.full_crack[f];
    p0 = r.full_node[f] < 0 ? 1 : 0;
    c.fill(0.0);
    if (p0)
      c = cell_key(x, cells, gdim, r.full_cell[f]);
    else
      std::copy_n(&x[gdim * r.full_node[f]], gdim, c.begin());
  }
  return keys;
}

/// The key of every group (root -> the smallest key of its members).
inline std::map<std::int32_t, MultiplierKey> group_keys(MultiplierGroups& groups, const std::vector<MultiplierKey>& keys)
{
  std::map<std::int32_t, MultiplierKey> out;
  for (std::size_t f = 0; f < keys.size(); ++f)
  {
    const auto [it, inserted] = out.try_emplace(groups.find(static_cast<std::int32_t>(f)), keys[f]);
    if (!inserted and keys[f] < it->second)
      it->second = keys[f];
  }
  return out;
}

/// Measures (weights, overlaps) within this relative distance of the
/// largest count as equal when a group is chosen (header).
constexpr double TIE_TOL = 1e-9;

/// The candidate of the largest measure, equals (within TIE_TOL of the
/// largest) decided by the smallest key; candidates: (measure, key, payload)
/// in any order. Returns an iterator to the chosen one (end() if empty).
template <class Candidates>
auto pick_largest(const Candidates& candidates)
{
  auto best = candidates.end();
  double top = -std::numeric_limits<double>::infinity();
  for (const auto& c : candidates)
    top = std::max(top, std::get<0>(c));
  for (auto it = candidates.begin(); it != candidates.end(); ++it)
    if (std::get<0>(*it) >= top - TIE_TOL * std::abs(top)
        and (best == candidates.end() or std::get<1>(*it) < std::get<1>(*best)))
      best = it;
  return best;
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
/// controlled by nothing: it joins the group with a jump it shares most
/// pieces with (each piece has a `mult` list of full multipliers; equals
/// by key). All such groups next to a group with a jump choose at once,
/// then again until none is left that has one. The group functions still
/// sum to one.
template <class Pieces>
void tie_groups_without_jump(const Pieces& pieces, const MultiplierRestriction& r,
                             const std::set<std::pair<std::int32_t, std::int32_t>>& enriched,
                             const std::vector<MultiplierKey>& keys, MultiplierGroups& groups)
{
  const std::int32_t nfull = r.num_full();
  for (;;)
  {
    std::map<std::int32_t, bool> has_jump; // root -> any enriched node (or P0)
    for (std::int32_t f = 0; f < nfull; ++f)
    {
      const bool j = r.full_node[f] < 0 or enriched.count({r.full_crack[f], r.full_node[f]});
      has_jump[groups.find(f)] = has_jump[groups.find(f)] or j;
    }
    // (group without a jump, group with one) -> pieces shared
    std::map<std::pair<std::int32_t, std::int32_t>, int> shared;
    for (const auto& piece : pieces)
    {
      std::set<std::int32_t> roots;
      for (const std::int32_t f : piece.mult)
        roots.insert(groups.find(f));
      for (const std::int32_t a : roots)
        if (!has_jump[a])
          for (const std::int32_t b : roots)
            if (has_jump[b])
              ++shared[{a, b}];
    }
    if (shared.empty())
      return;
    const auto gkey = group_keys(groups, keys);
    std::map<std::int32_t, std::vector<std::tuple<double, MultiplierKey, std::int32_t>>> candidates;
    for (const auto& [ab, n] : shared)
      candidates[ab.first].emplace_back(n, gkey.at(ab.second), ab.second);
    std::vector<std::pair<std::int32_t, std::int32_t>> joins;
    for (const auto& [a, c] : candidates)
      joins.emplace_back(a, std::get<2>(*pick_largest(c)));
    for (const auto& [a, b] : joins)
      groups.unite(a, b);
  }
}

/// Steps 1 and 2 together (the stars, then the stars without a jump joined
/// to a neighbour) on the pieces of a space: `vital_edges` of r receives
/// the vital edges; keys: multiplier_keys of r. Returns the (crack, node)
/// pairs carrying Heaviside dofs (for dimension-specific steps).
template <int Dim, class Pieces, class Layout>
std::set<std::pair<std::int32_t, std::int32_t>>
tie_stars(const Pieces& pieces, std::span<const CutEdge> cut_edges, std::span<const std::array<double, Dim>> cut_points,
          const NodalMultipliers& nodal, const Layout& layout, std::int8_t heaviside_kind, MultiplierRestriction& r,
          const std::vector<MultiplierKey>& keys, MultiplierGroups& groups)
{
  tie_vital_edges<Dim>(cut_edges, cut_points, nodal, groups, r.vital_edges);
  std::set<std::pair<std::int32_t, std::int32_t>> enriched, heaviside; // (crack, node)
  enriched_nodes(layout, heaviside_kind, enriched, heaviside);
  tie_groups_without_jump(pieces, r, enriched, keys, groups);
  return heaviside;
}

} // namespace cracklip
