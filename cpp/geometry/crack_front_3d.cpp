#include "geometry/crack_front_3d.h"

#include "geometry/closest_point.h"
#include "geometry/vec3.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace cracklip
{
using namespace vec3;

namespace
{
/// Points merged within tol: a hash grid of cell size tol, the 27
/// neighbouring cells searched (the first point within tol wins).
class PointMerger
{
public:
  explicit PointMerger(double tol) : tol_(tol) {}

  std::int32_t find_or_add(const Point3& p)
  {
    const std::array<std::int64_t, 3> k = key(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
        {
          const auto it = grid_.find(hash({k[0] + dx, k[1] + dy, k[2] + dz}));
          if (it == grid_.end())
            continue;
          for (std::int32_t i : it->second)
            if (dist(points[i], p) <= tol_)
              return i;
        }
    const std::int32_t i = static_cast<std::int32_t>(points.size());
    points.push_back(p);
    grid_[hash(k)].push_back(i);
    return i;
  }

  std::vector<Point3> points;

private:
  std::array<std::int64_t, 3> key(const Point3& p) const
  {
    return {static_cast<std::int64_t>(std::floor(p[0] / tol_)), static_cast<std::int64_t>(std::floor(p[1] / tol_)),
            static_cast<std::int64_t>(std::floor(p[2] / tol_))};
  }
  static std::uint64_t hash(const std::array<std::int64_t, 3>& k)
  {
    std::uint64_t h = 1469598103934665603ull;
    for (std::int64_t v : k)
      h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
    return h;
  }
  double tol_;
  // Hash collisions only cost a distance test: points of another cell are
  // farther than tol unless they are within tol, which is what we test.
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> grid_;
};

} // namespace

CrackFront3D create_crack_front_3d(std::span<const FrontSegment> segments, std::span<const double> boundary_faces,
                                   double tol)
{
  if (!(tol > 0.0))
    throw std::invalid_argument("create_crack_front_3d: tol must be > 0");
  CrackFront3D front;
  // Graph: merged points, undirected edges (first segment kept).
  PointMerger merge(tol);
  struct Edge
  {
    std::int32_t u, v; ///< oriented u -> v along e3 of its cell
    const FrontSegment* seg;
  };
  std::vector<Edge> edges;
  std::set<std::pair<std::int32_t, std::int32_t>> seen;
  for (const FrontSegment& sg : segments)
  {
    const std::int32_t u = merge.find_or_add(sg.p), v = merge.find_or_add(sg.q);
    if (u == v or !seen.insert({std::min(u, v), std::max(u, v)}).second)
      continue;
    edges.push_back({u, v, &sg});
  }
  const std::int32_t np = static_cast<std::int32_t>(merge.points.size());
  std::vector<std::vector<std::int32_t>> inc(np);
  for (std::int32_t e = 0; e < static_cast<std::int32_t>(edges.size()); ++e)
  {
    inc[edges[e].u].push_back(e);
    inc[edges[e].v].push_back(e);
  }
  for (std::int32_t n = 0; n < np; ++n)
    front.num_branch_points += inc[n].size() > 2;

  // Trace the pieces: from the ends (and branch points) first, then loops.
  std::vector<char> used(edges.size(), 0);
  auto trace = [&](std::int32_t start, std::int32_t first_edge)
  {
    std::vector<std::int32_t> nodes = {start}, path;
    std::int32_t n = start, e = first_edge;
    while (e >= 0 and !used[e])
    {
      used[e] = 1;
      path.push_back(e);
      n = edges[e].u == n ? edges[e].v : edges[e].u;
      if (n == start)
        break; // closed
      nodes.push_back(n);
      e = inc[n].size() == 2 ? (inc[n][0] == e ? inc[n][1] : inc[n][0]) : -1;
    }
    const bool closed = n == start and path.size() > 1 and inc[start].size() == 2;
    // Orientation: along the segments' own e3, by a length-weighted vote.
    double vote = 0.0;
    for (std::size_t k = 0; k < path.size(); ++k)
    {
      const Edge& ed = edges[path[k]];
      const double len = dist(merge.points[ed.u], merge.points[ed.v]);
      vote += (ed.u == nodes[k] ? 1.0 : -1.0) * len;
    }
    if (vote < 0.0)
    {
      if (closed)
      {
        // Reverse the loop, keeping its first point.
        std::reverse(nodes.begin() + 1, nodes.end());
        std::reverse(path.begin(), path.end());
      }
      else
      {
        std::reverse(nodes.begin(), nodes.end());
        std::reverse(path.begin(), path.end());
      }
    }
    // Points, arc length, cells.
    const std::int32_t offset = front.num_points();
    const std::size_t m = nodes.size();
    double s = 0.0;
    for (std::size_t k = 0; k < m; ++k)
    {
      const Point3& p = merge.points[nodes[k]];
      if (k > 0)
        s += dist(p, merge.points[nodes[k - 1]]);
      front.x.insert(front.x.end(), p.begin(), p.end());
      front.s.push_back(s);
      front.cell.push_back(edges[path[std::min(k, path.size() - 1)]].seg->cell);
      front.on_boundary.push_back(0);
    }
    for (std::size_t k = 0; k < path.size(); ++k)
    {
      front.segments.push_back(offset + static_cast<std::int32_t>(k));
      front.segments.push_back(offset + static_cast<std::int32_t>((k + 1) % m));
      front.segment_cell.push_back(edges[path[k]].seg->cell);
    }
    // Frames: e2 from the normals of the segments at the point (previous
    // and next), the tangent by the central difference of its neighbours
    // (one-sided at the ends of an open piece), e1 = e2 x e3.
    auto point = [&](std::size_t k)
    { return Point3{front.x[3 * (offset + k)], front.x[3 * (offset + k) + 1], front.x[3 * (offset + k) + 2]}; };
    for (std::size_t k = 0; k < m; ++k)
    {
      Point3 n2 = {0, 0, 0};
      for (int side = 0; side < 2; ++side)
      {
        // Segment k - 1 (into point k) and k (out of it).
        std::int64_t j = static_cast<std::int64_t>(k) - 1 + side;
        if (closed)
          j = (j + static_cast<std::int64_t>(path.size())) % static_cast<std::int64_t>(path.size());
        if (j < 0 or j >= static_cast<std::int64_t>(path.size()))
          continue;
        n2 = add(n2, unit(edges[path[j]].seg->grad_phi));
      }
      const std::size_t prev = closed ? (k + m - 1) % m : (k == 0 ? 0 : k - 1);
      const std::size_t next = closed ? (k + 1) % m : std::min(k + 1, m - 1);
      const Point3 t = sub(point(next), point(prev));
      const Point3 e2 = unit(n2);
      const Point3 e3 = unit(axpy(t, -dot(t, e2), e2));
      const Point3 e1 = cross(e2, e3);
      for (const Point3& e : {e1, e2, e3})
        front.frame.insert(front.frame.end(), e.begin(), e.end());
    }
    front.piece_offsets.push_back(front.num_points());
    front.closed.push_back(closed);
    // Ends of an open piece: on a boundary face of the part?
    if (!closed)
      for (const std::size_t k : {std::size_t(0), m - 1})
      {
        const Point3& p = merge.points[nodes[k]];
        for (std::size_t f = 0; f + 9 <= boundary_faces.size(); f += 9)
        {
          const Point3 a = {boundary_faces[f], boundary_faces[f + 1], boundary_faces[f + 2]};
          const Point3 b = {boundary_faces[f + 3], boundary_faces[f + 4], boundary_faces[f + 5]};
          const Point3 c = {boundary_faces[f + 6], boundary_faces[f + 7], boundary_faces[f + 8]};
          if (dist(closest_on_triangle(p, a, b, c).c, p) <= tol)
          {
            front.on_boundary[offset + k] = 1;
            break;
          }
        }
      }
  };
  for (std::int32_t n = 0; n < np; ++n)
    if (inc[n].size() != 2)
      for (std::int32_t e : inc[n])
        if (!used[e])
          trace(n, e);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (!used[e])
      trace(edges[e].u, static_cast<std::int32_t>(e));
  return front;
}

FrontLocator::FrontLocator(const CrackFront3D& front) : front_(front)
{
  std::vector<double> boxes;
  const std::int32_t ns = front.num_segments();
  piece_.resize(ns);
  for (std::int32_t k = 0; k < ns; ++k)
  {
    const std::int32_t a = front.segments[2 * k], b = front.segments[2 * k + 1];
    for (int d = 0; d < 3; ++d)
      boxes.push_back(std::min(front.x[3 * a + d], front.x[3 * b + d]));
    for (int d = 0; d < 3; ++d)
      boxes.push_back(std::max(front.x[3 * a + d], front.x[3 * b + d]));
    piece_[k] = static_cast<std::int32_t>(
        std::upper_bound(front.piece_offsets.begin(), front.piece_offsets.end(), a) - front.piece_offsets.begin()
        - 1);
  }
  tree_ = BoundingBoxTree<3>(boxes);
}

FrontProjection FrontLocator::project(const Point3& p, std::span<const double> frames) const
{
  if (front_.num_segments() == 0)
    throw std::runtime_error("FrontLocator: the crack has no front segment");
  if (frames.empty())
    frames = front_.frame;
  else if (frames.size() != front_.frame.size())
    throw std::invalid_argument("FrontLocator: frames must be (num_points, 3, 3) of the front");
  auto point = [&](std::int32_t i) { return Point3{front_.x[3 * i], front_.x[3 * i + 1], front_.x[3 * i + 2]}; };
  const auto [k, d2] = tree_.nearest(p,
                                     [&](std::int32_t j)
                                     {
                                       const Point3 A = point(front_.segments[2 * j]), B = point(front_.segments[2 * j + 1]);
                                       const Point3 r = sub(p, axpy(A, closest_on_segment(p, A, B), sub(B, A)));
                                       return dot(r, r);
                                     });
  FrontProjection out;
  out.segment = k;
  out.piece = piece_[k];
  const std::int32_t a = front_.segments[2 * k], b = front_.segments[2 * k + 1];
  const Point3 A = point(a), B = point(b);
  out.t = closest_on_segment(p, A, B);
  out.x = axpy(A, out.t, sub(B, A));
  out.distance = std::sqrt(d2);
  out.s = front_.s[a] + out.t * dist(A, B);
  out.nearest_point = out.t < 0.5 ? a : b;
  std::array<Point3, 3> f;
  for (int r = 0; r < 3; ++r)
    for (int d = 0; d < 3; ++d)
      f[r][d] = (1.0 - out.t) * frames[9 * a + 3 * r + d] + out.t * frames[9 * b + 3 * r + d];
  const Point3 e2 = unit(f[1]);
  const Point3 e3 = unit(axpy(f[2], -dot(f[2], e2), e2));
  out.frame = {cross(e2, e3), e2, e3};
  return out;
}

} // namespace cracklip
