// The stable multiplier reduction on cut edges (layer a), in any dimension.
//
// Bechet, Moes and Wohlmuth's P1- space (the "vital vertices" algorithm;
// code_aster's equality relations): every mesh edge the crack cuts is an
// edge of a graph on the mesh nodes. Score each edge by min(deg a, deg b);
// while some edge scores more than 1, drop the highest-scoring one (ties:
// the edge whose cut point is farthest from its neighbours' cut points, then
// the one whose cut point comes first in (crack, x, y, z) order) and lower
// both degrees. The edges left
// ("vital") have an end of degree 1: they form stars, each star one
// multiplier unknown, and the star functions sum to one along the crack.
// Dropping an edge needs both ends at degree >= 2, so every node that
// touched a cut edge still touches a vital one.
//
// The algorithm sees only the graph and the cut points: the same for cut
// triangles (2D) and cut tetrahedra (3D), where a node has more cut edges.
// Every choice is made by geometry, never by the order of the input: the
// edge dropped is the largest in (score, spacing, -cut point), a total order
// (two edges of one crack never share a cut point: edges of a conforming
// mesh meet only at nodes), and the greedy loop always drops the largest
// edge of the current graph. So the vital edges do not depend on how the
// nodes, cells or edges are numbered, provided the cut points do not:
// cut_point computes an edge's point from its ends taken in coordinate
// order, bit for bit the same whichever end is called a.
// Work: O(E log E) for E cut edges (a priority queue with lazy updates; the
// spacing of an edge depends only on its neighbours, updated locally).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
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

/// The point where the level set (values fp at xp, fq at xq, of opposite
/// signs) crosses the edge pq: linear interpolation from the end that comes
/// first in (x, y, z) order, so the result is the same bits whichever end
/// is passed first (the node numbering does not enter).
template <int Dim>
std::array<double, Dim> cut_point(const double* xp, const double* xq, double fp, double fq)
{
  if (std::lexicographical_compare(xq, xq + Dim, xp, xp + Dim))
  {
    std::swap(xp, xq);
    std::swap(fp, fq);
  }
  const double t = fp / (fp - fq);
  std::array<double, Dim> out;
  for (int k = 0; k < Dim; ++k)
    out[k] = xp[k] + t * (xq[k] - xp[k]);
  return out;
}

/// The vital edges of the cut-edge graph. edges (n): (crack, a, b) with
/// a < b, distinct; points (n): the cut point of each edge in Dim
/// dimensions (cut_point). Returns alive (n): 1 for a vital edge, 0 for a
/// dropped one. Edges of different cracks never share a node of the graph
/// (a node's degree is counted per crack). The result does not depend on
/// the order of the edges nor on the node numbers (header); only edges of
/// one crack with the same cut point (a degenerate mesh) fall back on their
/// order in the input.
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
  // rank[i]: place of edge i in (crack, cut point) order, the last tie-break.
  std::vector<std::size_t> by_point(n);
  std::iota(by_point.begin(), by_point.end(), std::size_t(0));
  std::stable_sort(by_point.begin(), by_point.end(), [&](std::size_t i, std::size_t j)
                   { return std::tie(edges[i][0], points[i]) < std::tie(edges[j][0], points[j]); });
  std::vector<std::int64_t> rank(n);
  for (std::size_t k = 0; k < n; ++k)
    rank[by_point[k]] = static_cast<std::int64_t>(k);
  // Max-heap on (score, spacing, -rank); entries go stale when a neighbour
  // is dropped and are re-checked when popped. Every alive edge scoring
  // above 1 has an entry with its current key (queued afresh whenever a
  // neighbour goes), so the top valid entry is the largest current key.
  using Entry = std::tuple<int, double, std::int64_t>;
  std::priority_queue<Entry> heap;
  for (std::size_t i = 0; i < n; ++i)
    if (score(i) > 1)
      heap.emplace(score(i), spacing(i), -rank[i]);
  while (!heap.empty())
  {
    const auto [s, sp, neg] = heap.top();
    heap.pop();
    const std::size_t i = by_point[static_cast<std::size_t>(-neg)];
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
          heap.emplace(score(j), spacing(j), -rank[j]);
  }
  return alive;
}

} // namespace cracklip
