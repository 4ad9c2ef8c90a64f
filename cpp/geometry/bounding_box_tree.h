// A static bounding-box tree for nearest-primitive queries (layer a).
//
// Built once over the axis-aligned boxes of a set of primitives (triangles,
// segments) by median splits along the longest axis, it answers "which
// primitive is nearest to p" in O(log n) typical time with a caller-given
// exact distance, so level sets of a triangulated surface cost one pass over
// the mesh nodes, never nodes x triangles. Same code in 2D and 3D.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace cracklip
{

template <int Dim>
class BoundingBoxTree
{
public:
  using Point = std::array<double, Dim>;

  BoundingBoxTree() = default;

  /// boxes: (n, 2, Dim), the lower then the upper corner of each primitive.
  explicit BoundingBoxTree(std::span<const double> boxes)
  {
    if (boxes.size() % (2 * Dim) != 0)
      throw std::invalid_argument("BoundingBoxTree: boxes must be an array of shape (n, 2, dim)");
    const std::int32_t n = static_cast<std::int32_t>(boxes.size() / (2 * Dim));
    boxes_.assign(boxes.begin(), boxes.end());
    order_.resize(n);
    for (std::int32_t i = 0; i < n; ++i)
      order_[i] = i;
    if (n > 0)
      build(0, n);
  }

  std::int32_t size() const { return static_cast<std::int32_t>(order_.size()); }

  /// The primitive nearest to p and its squared distance, given dist2(i),
  /// the exact squared distance from p to primitive i (at least the squared
  /// distance to its box). Ties keep the first primitive met. (-1, inf) for
  /// an empty tree.
  template <typename Dist2>
  std::pair<std::int32_t, double> nearest(const Point& p, Dist2&& dist2) const
  {
    std::int32_t best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    if (nodes_.empty())
      return {best, best_d2};
    std::vector<std::int32_t> stack = {0};
    while (!stack.empty())
    {
      const Node& node = nodes_[stack.back()];
      stack.pop_back();
      if (box_distance2(node.lo, node.hi, p) >= best_d2)
        continue;
      if (node.left < 0)
      {
        for (std::int32_t k = node.begin; k < node.end; ++k)
        {
          const double d2 = dist2(order_[k]);
          if (d2 < best_d2)
            best_d2 = d2, best = order_[k];
        }
        continue;
      }
      const double dl = box_distance2(nodes_[node.left].lo, nodes_[node.left].hi, p);
      const double dr = box_distance2(nodes_[node.right].lo, nodes_[node.right].hi, p);
      // The nearer child is examined first (pushed last).
      if (dl <= dr)
        stack.insert(stack.end(), {node.right, node.left});
      else
        stack.insert(stack.end(), {node.left, node.right});
    }
    return {best, best_d2};
  }

private:
  struct Node
  {
    Point lo, hi;
    std::int32_t left = -1, right = -1; ///< children, -1 for a leaf
    std::int32_t begin = 0, end = 0;    ///< leaf: primitives order_[begin, end)
  };

  static double box_distance2(const Point& lo, const Point& hi, const Point& p)
  {
    double d2 = 0.0;
    for (int d = 0; d < Dim; ++d)
    {
      const double e = std::max({lo[d] - p[d], 0.0, p[d] - hi[d]});
      d2 += e * e;
    }
    return d2;
  }

  double lo(std::int32_t i, int d) const { return boxes_[2 * Dim * i + d]; }
  double hi(std::int32_t i, int d) const { return boxes_[2 * Dim * i + Dim + d]; }

  std::int32_t build(std::int32_t begin, std::int32_t end)
  {
    const std::int32_t id = static_cast<std::int32_t>(nodes_.size());
    nodes_.emplace_back();
    Node node;
    node.begin = begin;
    node.end = end;
    node.lo.fill(std::numeric_limits<double>::infinity());
    node.hi.fill(-std::numeric_limits<double>::infinity());
    for (std::int32_t k = begin; k < end; ++k)
      for (int d = 0; d < Dim; ++d)
      {
        node.lo[d] = std::min(node.lo[d], lo(order_[k], d));
        node.hi[d] = std::max(node.hi[d], hi(order_[k], d));
      }
    if (end - begin > leaf_size)
    {
      int axis = 0;
      for (int d = 1; d < Dim; ++d)
        if (node.hi[d] - node.lo[d] > node.hi[axis] - node.lo[axis])
          axis = d;
      const std::int32_t mid = begin + (end - begin) / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                       [&](std::int32_t a, std::int32_t b)
                       { return lo(a, axis) + hi(a, axis) < lo(b, axis) + hi(b, axis); });
      node.left = build(begin, mid);
      node.right = build(mid, end);
    }
    nodes_[id] = node;
    return id;
  }

  static constexpr std::int32_t leaf_size = 4;
  std::vector<double> boxes_;
  std::vector<std::int32_t> order_;
  std::vector<Node> nodes_;
};

} // namespace cracklip
