// The stable multiplier reduction on cut edges (layer a), in any dimension.
//
// Bechet, Moes and Wohlmuth's P1- space (the "vital vertices" algorithm;
// code_aster's equality relations): every mesh edge the crack cuts is an
// edge of a graph on the mesh nodes. Score each edge by min(deg a, deg b);
// while some edge scores more than 1, drop the highest-scoring one (ties:
// the edge whose cut point is farthest from its neighbours' cut points, then
// the first in (crack, a, b) order) and lower both degrees. The edges left
// ("vital") have an end of degree 1: they form stars, each star one
// multiplier unknown, and the star functions sum to one along the crack.
// Dropping an edge needs both ends at degree >= 2, so every node that
// touched a cut edge still touches a vital one.
//
// The algorithm sees only the graph and the cut points: the same for cut
// triangles (2D) and cut tetrahedra (3D), where a node has more cut edges.
// Work: O(E log E) for E cut edges (a priority queue with lazy updates; the
// spacing of an edge depends only on its neighbours, updated locally).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <queue>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace cracklip
{

/// A cut edge: crack index and its two mesh nodes (a < b).
using CutEdge = std::array<std::int32_t, 3>;

/// The vital edges of the cut-edge graph. edges (n): (crack, a, b) with
/// a < b, distinct; points (n): the cut point of each edge in Dim
/// dimensions. Returns alive (n): 1 for a vital edge, 0 for a dropped one.
/// Edges of different cracks never share a node of the graph (a node's
/// degree is counted per crack).
template <int Dim>
std::vector<std::int8_t> select_vital_edges(std::span<const CutEdge> edges,
                                            std::span<const std::array<double, Dim>> points)
{
  const std::size_t n = edges.size();
  if (points.size() != n)
    throw std::invalid_argument("select_vital_edges: " + std::to_string(points.size()) + " cut points for "
                                + std::to_string(n) + " edges");
  // Graph nodes: (crack, mesh node) -> id; incidence lists.
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> id;
  std::vector<std::array<std::int32_t, 2>> ends(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!(edges[i][1] < edges[i][2]))
      throw std::invalid_argument("select_vital_edges: edge " + std::to_string(i) + " is not ordered (a < b)");
    for (int s = 0; s < 2; ++s)
    {
      auto [it, inserted] = id.try_emplace({edges[i][0], edges[i][1 + s]}, static_cast<std::int32_t>(id.size()));
      ends[i][s] = it->second;
    }
  }
  std::vector<std::vector<std::int32_t>> incident(id.size());
  for (std::size_t i = 0; i < n; ++i)
    for (int s = 0; s < 2; ++s)
      incident[ends[i][s]].push_back(static_cast<std::int32_t>(i));
  std::vector<int> deg(id.size());
  for (std::size_t v = 0; v < id.size(); ++v)
    deg[v] = static_cast<int>(incident[v].size());
  std::vector<std::int8_t> alive(n, 1);

  auto score = [&](std::size_t i) { return std::min(deg[ends[i][0]], deg[ends[i][1]]); };
  // Distance from edge i's cut point to the nearest cut point of an alive
  // edge sharing a node with it.
  auto spacing = [&](std::size_t i)
  {
    double d = std::numeric_limits<double>::max();
    for (int s = 0; s < 2; ++s)
      for (const std::int32_t j : incident[ends[i][s]])
        if (static_cast<std::size_t>(j) != i and alive[j])
        {
          double r2 = 0.0;
          for (int k = 0; k < Dim; ++k)
            r2 += (points[j][k] - points[i][k]) * (points[j][k] - points[i][k]);
          d = std::min(d, std::sqrt(r2));
        }
    return d;
  };
  // Max-heap on (score, spacing, -index); entries go stale when a
  // neighbour is dropped and are re-checked when popped.
  using Entry = std::tuple<int, double, std::int64_t>;
  std::priority_queue<Entry> heap;
  for (std::size_t i = 0; i < n; ++i)
    if (score(i) > 1)
      heap.emplace(score(i), spacing(i), -static_cast<std::int64_t>(i));
  while (!heap.empty())
  {
    const auto [s, sp, neg] = heap.top();
    heap.pop();
    const auto i = static_cast<std::size_t>(-neg);
    if (!alive[i])
      continue;
    const int s_now = score(i);
    if (s_now <= 1)
      continue;
    if (s_now != s or spacing(i) != sp)
    {
      heap.emplace(s_now, spacing(i), neg);
      continue;
    }
    alive[i] = 0;
    --deg[ends[i][0]];
    --deg[ends[i][1]];
    // The neighbours' scores and spacings changed: queue them afresh.
    for (int e = 0; e < 2; ++e)
      for (const std::int32_t j : incident[ends[i][e]])
        if (alive[j] and score(j) > 1)
          heap.emplace(score(j), spacing(j), -static_cast<std::int64_t>(j));
  }
  return alive;
}

} // namespace cracklip
