#include "geometry/crack_surface_3d.h"

#include "geometry/bounding_box_tree.h"
#include "geometry/closest_point.h"
#include "geometry/vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace cracklip
{
using namespace vec3;

namespace detail
{
struct SurfaceImpl
{
  virtual ~SurfaceImpl() = default;
  virtual CrackSurface3D::Kind kind() const = 0;
  virtual std::array<double, 2> level_sets(const Point3& p) const = 0;
  virtual std::array<Point3, 2> front_directions(const Point3& p) const = 0;
  virtual std::array<double, 6> bounding_box() const = 0;
  virtual std::string describe() const = 0;
};
} // namespace detail

namespace
{
std::string fmt(const Point3& p)
{
  std::ostringstream s;
  s.precision(6);
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

std::string fmt(double v)
{
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

void require_finite(const Point3& p, const std::string& what)
{
  for (double v : p)
    if (!std::isfinite(v))
      throw std::invalid_argument(what + " " + fmt(p) + " is not finite; give finite coordinates");
}

/// Unit vectors (e1, e2) of the plane normal to the unit vector n, e1 along
/// the part of `axis` normal to n (or any, if axis is empty).
std::array<Point3, 2> plane_frame(const Point3& n, const Point3& axis)
{
  Point3 e1 = axpy(axis, -dot(axis, n), n);
  if (!(norm(e1) > 1e-12 * norm(axis)) or norm(axis) == 0.0)
  {
    // Any direction normal to n: the coordinate axis least aligned with it.
    int k = 0;
    for (int d = 1; d < 3; ++d)
      if (std::abs(n[d]) < std::abs(n[k]))
        k = d;
    Point3 ek = {0, 0, 0};
    ek[k] = 1.0;
    e1 = axpy(ek, -dot(ek, n), n);
  }
  e1 = unit(e1);
  return {e1, cross(n, e1)};
}

// ---------------------------------------------------------------- ellipse
struct EllipseSurface final : detail::SurfaceImpl
{
  Point3 c, n, ea, eb;
  double a, b;

  CrackSurface3D::Kind kind() const override { return CrackSurface3D::Kind::ellipse; }

  std::array<double, 2> level_sets(const Point3& p) const override
  {
    const Point3 d = sub(p, c);
    return {dot(d, n), closest_point_on_ellipse(a, b, {dot(d, ea), dot(d, eb)}).distance};
  }

  std::array<Point3, 2> front_directions(const Point3& p) const override
  {
    // In-plane normal of the ellipse at the closest point: (x0 / a^2, x1 / b^2).
    const Point3 d = sub(p, c);
    const EllipsePoint e = closest_point_on_ellipse(a, b, {dot(d, ea), dot(d, eb)});
    const double u = e.x[0] / (a * a), v = e.x[1] / (b * b);
    return {unit(axpy(scale(u, ea), v, eb)), n};
  }

  std::array<double, 6> bounding_box() const override
  {
    std::array<double, 6> box;
    for (int k = 0; k < 3; ++k)
    {
      const double h = std::hypot(a * ea[k], b * eb[k]);
      box[k] = c[k] - h;
      box[3 + k] = c[k] + h;
    }
    return box;
  }

  std::string describe() const override
  {
    return "ellipse crack (centre " + fmt(c) + ", normal " + fmt(n) + ", semi-axis a = " + fmt(a) + " along "
           + fmt(ea) + ", b = " + fmt(b) + ")";
  }
};

// ---------------------------------------------------------------- polygon
struct PolygonSurface final : detail::SurfaceImpl
{
  Point3 c, n, e1, e2;
  std::vector<Point3> v;                   ///< vertices (3D)
  std::vector<std::array<double, 2>> q;    ///< vertices in the plane (e1, e2)
  std::vector<std::array<double, 2>> m;    ///< outward unit normal of edge (q_i, q_i+1)
  BoundingBoxTree<2> tree;

  CrackSurface3D::Kind kind() const override { return CrackSurface3D::Kind::polygon; }

  std::array<double, 2> level_sets(const Point3& p) const override
  {
    const Point3 d = sub(p, c);
    const std::array<double, 2> y = {dot(d, e1), dot(d, e2)};
    const std::size_t nv = q.size();
    auto closest = [&](std::int32_t i, double& t)
    {
      const auto& A = q[i];
      const auto& B = q[(i + 1) % nv];
      const double dx = B[0] - A[0], dy = B[1] - A[1];
      t = std::clamp(((y[0] - A[0]) * dx + (y[1] - A[1]) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      return std::array<double, 2>{A[0] + t * dx, A[1] + t * dy};
    };
    const auto [i, d2] = tree.nearest(y,
                                      [&](std::int32_t k)
                                      {
                                        double t;
                                        const auto cp = closest(k, t);
                                        return (y[0] - cp[0]) * (y[0] - cp[0]) + (y[1] - cp[1]) * (y[1] - cp[1]);
                                      });
    double t;
    const auto cp = closest(i, t);
    // Pseudo-normal: the edge's outward normal, the sum of both at a vertex.
    std::array<double, 2> pn = m[i];
    if (t == 0.0)
      pn = {pn[0] + m[(i + nv - 1) % nv][0], pn[1] + m[(i + nv - 1) % nv][1]};
    else if (t == 1.0)
      pn = {pn[0] + m[(i + 1) % nv][0], pn[1] + m[(i + 1) % nv][1]};
    const double side = (y[0] - cp[0]) * pn[0] + (y[1] - cp[1]) * pn[1];
    return {dot(d, n), (side >= 0.0 ? 1.0 : -1.0) * std::sqrt(d2)};
  }

  std::array<Point3, 2> front_directions(const Point3& p) const override
  {
    // The nearest edge's outward normal; at a vertex, the mean of both.
    const Point3 d = sub(p, c);
    const std::array<double, 2> y = {dot(d, e1), dot(d, e2)};
    const std::size_t nv = q.size();
    auto param = [&](std::int32_t i)
    {
      const auto& A = q[i];
      const auto& B = q[(i + 1) % nv];
      const double dx = B[0] - A[0], dy = B[1] - A[1];
      return std::clamp(((y[0] - A[0]) * dx + (y[1] - A[1]) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    };
    const std::int32_t i = tree
                               .nearest(y,
                                        [&](std::int32_t k)
                                        {
                                          const double t = param(k);
                                          const auto& A = q[k];
                                          const auto& B = q[(k + 1) % nv];
                                          const double cx = A[0] + t * (B[0] - A[0]) - y[0];
                                          const double cy = A[1] + t * (B[1] - A[1]) - y[1];
                                          return cx * cx + cy * cy;
                                        })
                               .first;
    const double t = param(i);
    std::array<double, 2> mm = m[i];
    if (t == 0.0)
      mm = {mm[0] + m[(i + nv - 1) % nv][0], mm[1] + m[(i + nv - 1) % nv][1]};
    else if (t == 1.0)
      mm = {mm[0] + m[(i + 1) % nv][0], mm[1] + m[(i + 1) % nv][1]};
    return {unit(axpy(scale(mm[0], e1), mm[1], e2)), n};
  }

  std::array<double, 6> bounding_box() const override
  {
    std::array<double, 6> box = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                                 std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                 -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const Point3& p : v)
      for (int k = 0; k < 3; ++k)
        box[k] = std::min(box[k], p[k]), box[3 + k] = std::max(box[3 + k], p[k]);
    return box;
  }

  std::string describe() const override
  {
    return "polygon crack (" + std::to_string(v.size()) + " vertices, normal " + fmt(n) + ")";
  }
};

// ---------------------------------------------------------------- triangulated
struct TriangulatedSurface final : detail::SurfaceImpl
{
  std::vector<Point3> v;                       ///< vertices
  std::vector<std::array<std::int32_t, 3>> t;  ///< triangles
  std::vector<Point3> face_normal;             ///< unit, (nt)
  std::vector<std::array<std::int32_t, 3>> te; ///< edge of each triangle's side k (v_k, v_k+1)
  std::vector<Point3> edge_normal;             ///< pseudo-normal of each edge (sum of face normals)
  std::vector<std::int8_t> edge_boundary;      ///< edge of one triangle (a front edge)
  std::vector<std::int32_t> edge_triangle;     ///< a triangle of each edge
  std::vector<Point3> vertex_normal;           ///< angle-weighted pseudo-normal
  std::vector<std::int8_t> vertex_boundary;
  std::vector<std::array<std::int32_t, 2>> front; ///< boundary edges as vertex pairs
  std::vector<Point3> front_out;                  ///< unit outward in-surface normal of each front edge
  std::vector<std::int32_t> front_tri;            ///< the triangle of each front edge
  std::vector<std::array<std::int32_t, 2>> vertex_front; ///< the front edges at each boundary vertex
  BoundingBoxTree<3> tri_tree, front_tree;

  CrackSurface3D::Kind kind() const override { return CrackSurface3D::Kind::triangulated; }

  std::array<double, 2> level_sets(const Point3& p) const override
  {
    const auto [k, d2] = tri_tree.nearest(p,
                                          [&](std::int32_t i)
                                          {
                                            const auto& T = t[i];
                                            const Point3 cp = closest_on_triangle(p, v[T[0]], v[T[1]], v[T[2]]).c;
                                            const Point3 e = sub(p, cp);
                                            return dot(e, e);
                                          });
    const auto& T = t[k];
    const TrianglePoint tp = closest_on_triangle(p, v[T[0]], v[T[1]], v[T[2]]);
    const Point3 e = sub(p, tp.c);
    bool boundary = false;
    Point3 pn;
    if (tp.feature == 0)
      pn = face_normal[k];
    else if (tp.feature <= 3)
    {
      const std::int32_t ed = te[k][tp.feature - 1];
      boundary = edge_boundary[ed];
      pn = boundary ? face_normal[edge_triangle[ed]] : edge_normal[ed];
    }
    else
    {
      const std::int32_t vi = T[tp.feature - 4];
      boundary = vertex_boundary[vi];
      pn = vertex_normal[vi];
    }
    double phi;
    if (boundary)
      phi = dot(e, unit(pn)); // distance to the surface extended by its tangent plane
    else
      phi = (dot(e, pn) >= 0.0 ? 1.0 : -1.0) * std::sqrt(d2);
    // psi: distance to the nearest front point, without its component along
    // the surface normal (exact in-plane distance for a planar surface; no
    // cancellation far off the surface).
    const Point3 nu = unit(pn);
    auto closest_on_front_edge = [&](std::int32_t i)
    {
      const Point3 A = v[front[i][0]], B = v[front[i][1]];
      const Point3 AB = sub(B, A);
      return axpy(A, std::clamp(dot(sub(p, A), AB) / dot(AB, AB), 0.0, 1.0), AB);
    };
    const std::int32_t fi = front_tree
                                .nearest(p,
                                         [&](std::int32_t i)
                                         {
                                           const Point3 r = sub(p, closest_on_front_edge(i));
                                           return dot(r, r);
                                         })
                                .first;
    const Point3 cf = closest_on_front_edge(fi);
    const Point3 ef = sub(p, cf);
    const double psi = (boundary ? 1.0 : -1.0) * norm(axpy(ef, -dot(ef, nu), nu));
    return {phi, psi};
  }

  std::array<Point3, 2> front_directions(const Point3& p) const override
  {
    // The nearest front edge: the outward normal within its triangle and
    // the triangle's normal; at a front vertex, the means over its two edges.
    auto param = [&](std::int32_t i) { return closest_on_segment(p, v[front[i][0]], v[front[i][1]]); };
    const std::int32_t i = front_tree
                               .nearest(p,
                                        [&](std::int32_t k)
                                        {
                                          const Point3 r = sub(p, axpy(v[front[k][0]], param(k), sub(v[front[k][1]], v[front[k][0]])));
                                          return dot(r, r);
                                        })
                               .first;
    const double s = param(i);
    if (s > 0.0 and s < 1.0)
      return {front_out[i], face_normal[front_tri[i]]};
    const std::int32_t vtx = front[i][s == 0.0 ? 0 : 1];
    const auto& fe = vertex_front[vtx];
    return {unit(add(front_out[fe[0]], front_out[fe[1]])),
            unit(add(face_normal[front_tri[fe[0]]], face_normal[front_tri[fe[1]]]))};
  }

  std::array<double, 6> bounding_box() const override
  {
    std::array<double, 6> box = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                                 std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                 -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const auto& T : t)
      for (std::int32_t i : T)
        for (int d = 0; d < 3; ++d)
          box[d] = std::min(box[d], v[i][d]), box[3 + d] = std::max(box[3 + d], v[i][d]);
    return box;
  }

  std::string describe() const override
  {
    return "triangulated crack (" + std::to_string(t.size()) + " triangles, " + std::to_string(front.size())
           + " front edges)";
  }
};

double angle_between(const Point3& a, const Point3& b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

} // namespace

// ------------------------------------------------------------------ ellipse point
EllipsePoint closest_point_on_ellipse(double a, double b, std::array<double, 2> y)
{
  if (!(a > 0.0 and b > 0.0))
    throw std::invalid_argument("closest_point_on_ellipse: semi-axes must be > 0");
  if (a < b)
  {
    const EllipsePoint r = closest_point_on_ellipse(b, a, {y[1], y[0]});
    return {{r.x[1], r.x[0]}, r.distance};
  }
  // First quadrant, a >= b.
  const double s0 = y[0] < 0.0 ? -1.0 : 1.0, s1 = y[1] < 0.0 ? -1.0 : 1.0;
  const double z0 = std::abs(y[0]), z1 = std::abs(y[1]);
  double x0, x1;
  bool inside;
  if (a == b)
  {
    const double r = std::hypot(z0, z1);
    if (r == 0.0)
      return {{a, 0.0}, -a};
    return {{s0 * a * z0 / r, s1 * a * z1 / r}, r - a};
  }
  if (z1 > 0.0)
  {
    if (z0 > 0.0)
    {
      // x = (r0 z0 / (u + r0 - 1), z1 / u) (scaled by the semi-axes) with u
      // the root of G(u) = (r0 n0 / (u + r0 - 1))^2 + (n1 / u)^2 - 1, which
      // decreases on the bracket below (u = s + 1 for the multiplier s of
      // the closest-point condition; in u, small denominators carry no
      // cancellation); bisection to round-off.
      const double n0 = z0 / a, n1 = z1 / b, r0 = (a / b) * (a / b);
      const double g = n0 * n0 + n1 * n1 - 1.0;
      inside = g < 0.0;
      if (g != 0.0)
      {
        double lo = n1, hi = g < 0.0 ? 1.0 : std::hypot(r0 * n0, n1);
        double u = 0.5 * (lo + hi);
        for (int it = 0; it < 2200; ++it)
        {
          u = 0.5 * (lo + hi);
          if (u == lo or u == hi)
            break;
          const double q0 = r0 * n0 / (u + (r0 - 1.0)), q1 = n1 / u;
          const double G = q0 * q0 + q1 * q1 - 1.0;
          if (G > 0.0)
            lo = u;
          else if (G < 0.0)
            hi = u;
          else
            break;
        }
        x0 = r0 * z0 / (u + (r0 - 1.0));
        x1 = z1 / u;
      }
      else
        x0 = z0, x1 = z1;
    }
    else
    {
      x0 = 0.0, x1 = b;
      inside = z1 < b;
    }
  }
  else
  {
    const double num = a * z0, den = a * a - b * b;
    if (num < den)
    {
      const double xa = num / den;
      x0 = a * xa;
      x1 = b * std::sqrt(std::max(0.0, 1.0 - xa * xa));
    }
    else
      x0 = a, x1 = 0.0;
    inside = z0 < a;
  }
  const double d = std::hypot(x0 - z0, x1 - z1);
  return {{s0 * x0, s1 * x1}, inside ? -d : d};
}

// ------------------------------------------------------------------ surface
CrackSurface3D::CrackSurface3D(std::shared_ptr<const detail::SurfaceImpl> impl) : impl_(std::move(impl)) {}
CrackSurface3D::Kind CrackSurface3D::kind() const { return impl_->kind(); }
std::array<double, 2> CrackSurface3D::level_sets(const Point3& p) const { return impl_->level_sets(p); }
std::array<Point3, 2> CrackSurface3D::front_directions(const Point3& p) const { return impl_->front_directions(p); }
std::array<double, 6> CrackSurface3D::bounding_box() const { return impl_->bounding_box(); }
std::string CrackSurface3D::describe() const { return impl_->describe(); }

CrackSurface3D create_ellipse_crack(const Point3& center, const Point3& normal, const Point3& axis, double a,
                                    double b)
{
  require_finite(center, "ellipse crack: centre");
  require_finite(normal, "ellipse crack: normal");
  require_finite(axis, "ellipse crack: axis");
  if (!(norm(normal) > 0.0))
    throw std::invalid_argument("ellipse crack: the normal is zero; give a non-zero normal vector (it points to "
                                "the phi > 0 side)");
  if (!(std::isfinite(a) and a > 0.0) or !(std::isfinite(b) and b > 0.0))
    throw std::invalid_argument("ellipse crack: semi-axes must be finite and > 0, got a = " + fmt(a)
                                + ", b = " + fmt(b) + "; give both semi-axes (a = b for a circle)");
  auto s = std::make_shared<EllipseSurface>();
  s->c = center;
  s->n = unit(normal);
  const Point3 ax = axpy(axis, -dot(axis, s->n), s->n);
  if (!(norm(ax) > 1e-12 * norm(axis)) or norm(axis) == 0.0)
    throw std::invalid_argument("ellipse crack: the axis " + fmt(axis) + " is zero or parallel to the normal "
                                + fmt(normal) + "; give the direction of semi-axis a within the crack plane");
  const auto [e1, e2] = plane_frame(s->n, ax);
  s->ea = e1;
  s->eb = e2;
  s->a = a;
  s->b = b;
  return CrackSurface3D(s);
}

CrackSurface3D create_polygon_crack(std::span<const double> vertices)
{
  if (vertices.size() % 3 != 0 or vertices.size() < 9)
    throw std::invalid_argument("polygon crack: vertices must be an array of shape (n, 3) with n >= 3, got "
                                + std::to_string(vertices.size()) + " numbers");
  auto s = std::make_shared<PolygonSurface>();
  const std::size_t nv = vertices.size() / 3;
  for (std::size_t i = 0; i < nv; ++i)
  {
    s->v.push_back({vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2]});
    require_finite(s->v.back(), "polygon crack: vertex " + std::to_string(i));
  }
  // Newell's normal (twice the vector area) and the centroid of the vertices.
  Point3 nn = {0, 0, 0}, c = {0, 0, 0};
  double diam = 0.0;
  for (std::size_t i = 0; i < nv; ++i)
  {
    const Point3& p = s->v[i];
    const Point3& q = s->v[(i + 1) % nv];
    nn = add(nn, cross(p, q));
    c = axpy(c, 1.0 / nv, p);
    const double len = dist(p, q);
    if (!(len > 0.0))
      throw std::invalid_argument("polygon crack: vertices " + std::to_string(i) + " and "
                                  + std::to_string((i + 1) % nv) + " coincide; remove the repeated vertex");
    for (std::size_t j = 0; j < i; ++j)
      diam = std::max(diam, dist(p, s->v[j]));
  }
  if (!(norm(nn) > 1e-12 * diam * diam))
    throw std::invalid_argument("polygon crack: the polygon has zero area (collinear vertices); give the "
                                "vertices of a planar polygon with an area");
  s->n = unit(nn);
  s->c = c;
  std::size_t worst = 0;
  double off = 0.0;
  for (std::size_t i = 0; i < nv; ++i)
    if (const double o = std::abs(dot(sub(s->v[i], c), s->n)); o > off)
      off = o, worst = i;
  if (off > 1e-9 * diam)
    throw std::invalid_argument("polygon crack: vertex " + std::to_string(worst) + " " + fmt(s->v[worst])
                                + " lies " + fmt(off) + " off the polygon's plane (normal " + fmt(s->n)
                                + "); a polygon crack must be planar: move the vertex into the plane or give "
                                  "a triangulated surface");
  const auto [e1, e2] = plane_frame(s->n, sub(s->v[1], s->v[0]));
  s->e1 = e1;
  s->e2 = e2;
  for (const Point3& p : s->v)
    s->q.push_back({dot(sub(p, c), e1), dot(sub(p, c), e2)});
  // Counter-clockwise in (e1, e2) by construction (e2 = n x e1, Newell's n):
  // the outward normal of edge p -> q is (dy, -dx) / len.
  std::vector<double> boxes;
  for (std::size_t i = 0; i < nv; ++i)
  {
    const auto& A = s->q[i];
    const auto& B = s->q[(i + 1) % nv];
    const double dx = B[0] - A[0], dy = B[1] - A[1], len = std::hypot(dx, dy);
    s->m.push_back({dy / len, -dx / len});
    boxes.insert(boxes.end(), {std::min(A[0], B[0]), std::min(A[1], B[1]), std::max(A[0], B[0]), std::max(A[1], B[1])});
  }
  // Simple polygon: no two edges meet except consecutive ones at their vertex.
  auto orient = [](const std::array<double, 2>& p, const std::array<double, 2>& q, const std::array<double, 2>& r)
  { return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]); };
  for (std::size_t i = 0; i < nv; ++i)
  {
    const auto& A = s->q[i];
    const auto& B = s->q[(i + 1) % nv];
    const auto& C = s->q[(i + 2) % nv];
    const double cr = orient(A, B, C);
    const double dt = (B[0] - A[0]) * (C[0] - B[0]) + (B[1] - A[1]) * (C[1] - B[1]);
    if (std::abs(cr) <= 1e-14 * diam * diam and dt < 0.0)
      throw std::invalid_argument("polygon crack: the boundary folds back on itself at vertex "
                                  + std::to_string((i + 1) % nv) + "; remove that vertex");
    for (std::size_t j = i + 2; j < nv; ++j)
    {
      if ((j + 1) % nv == i)
        continue; // consecutive (last and first edges)
      const auto& P = s->q[j];
      const auto& Q = s->q[(j + 1) % nv];
      const double o1 = orient(A, B, P), o2 = orient(A, B, Q), o3 = orient(P, Q, A), o4 = orient(P, Q, B);
      const bool cross_ = (o1 * o2 <= 0.0) and (o3 * o4 <= 0.0);
      const bool collinear = o1 == 0.0 and o2 == 0.0;
      bool overlap = !collinear;
      if (collinear)
      {
        // Projections on AB overlap?
        const double dx = B[0] - A[0], dy = B[1] - A[1], l2 = dx * dx + dy * dy;
        const double tp = ((P[0] - A[0]) * dx + (P[1] - A[1]) * dy) / l2;
        const double tq = ((Q[0] - A[0]) * dx + (Q[1] - A[1]) * dy) / l2;
        overlap = std::max(tp, tq) >= 0.0 and std::min(tp, tq) <= 1.0;
      }
      if (cross_ and overlap)
        throw std::invalid_argument("polygon crack: edges " + std::to_string(i) + " and " + std::to_string(j)
                                    + " intersect (the polygon is not simple); list the vertices in order "
                                      "around the boundary");
    }
  }
  s->tree = BoundingBoxTree<2>(boxes);
  return CrackSurface3D(s);
}

CrackSurface3D create_triangulated_crack(std::span<const double> vertices, std::span<const std::int32_t> triangles)
{
  if (vertices.size() % 3 != 0 or triangles.size() % 3 != 0 or triangles.empty())
    throw std::invalid_argument("triangulated crack: vertices must be (nv, 3) and triangles (nt, 3), nt >= 1");
  auto s = std::make_shared<TriangulatedSurface>();
  const std::int32_t nv = static_cast<std::int32_t>(vertices.size() / 3);
  const std::int32_t nt = static_cast<std::int32_t>(triangles.size() / 3);
  for (std::int32_t i = 0; i < nv; ++i)
  {
    s->v.push_back({vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2]});
    require_finite(s->v.back(), "triangulated crack: vertex " + std::to_string(i));
  }
  // Triangles: indices, non-degenerate, unit normals.
  for (std::int32_t k = 0; k < nt; ++k)
  {
    std::array<std::int32_t, 3> T = {triangles[3 * k], triangles[3 * k + 1], triangles[3 * k + 2]};
    for (std::int32_t i : T)
      if (i < 0 or i >= nv)
        throw std::invalid_argument("triangulated crack: triangle " + std::to_string(k) + " refers to vertex "
                                    + std::to_string(i) + "; vertex indices must lie in [0, " + std::to_string(nv)
                                    + ")");
    const Point3 nrm = cross(sub(s->v[T[1]], s->v[T[0]]), sub(s->v[T[2]], s->v[T[0]]));
    const double lmax = std::max({dist(s->v[T[0]], s->v[T[1]]), dist(s->v[T[1]], s->v[T[2]]),
                                  dist(s->v[T[2]], s->v[T[0]])});
    if (T[0] == T[1] or T[1] == T[2] or T[2] == T[0] or !(norm(nrm) > 1e-12 * lmax * lmax))
      throw std::invalid_argument("triangulated crack: triangle " + std::to_string(k) + " (vertices "
                                  + std::to_string(T[0]) + ", " + std::to_string(T[1]) + ", " + std::to_string(T[2])
                                  + ") is degenerate (zero area); remove it or merge its vertices");
    s->t.push_back(T);
    s->face_normal.push_back(unit(nrm));
  }
  // Edges: sort the directed half-edges by their undirected key.
  struct HalfEdge
  {
    std::int32_t lo, hi, tri;
    int side;     ///< local side k: (v_k, v_k+1)
    bool forward; ///< traversed lo -> hi
  };
  std::vector<HalfEdge> he;
  for (std::int32_t k = 0; k < nt; ++k)
    for (int j = 0; j < 3; ++j)
    {
      const std::int32_t a = s->t[k][j], b = s->t[k][(j + 1) % 3];
      he.push_back({std::min(a, b), std::max(a, b), k, j, a < b});
    }
  std::sort(he.begin(), he.end(), [](const HalfEdge& x, const HalfEdge& y)
            { return std::tie(x.lo, x.hi, x.tri) < std::tie(y.lo, y.hi, y.tri); });
  s->te.assign(nt, {-1, -1, -1});
  std::vector<int> boundary_degree(nv, 0);
  for (std::size_t i = 0; i < he.size();)
  {
    std::size_t j = i;
    while (j < he.size() and he[j].lo == he[i].lo and he[j].hi == he[i].hi)
      ++j;
    const std::int32_t e = static_cast<std::int32_t>(s->edge_normal.size());
    const std::string name = "edge (" + std::to_string(he[i].lo) + ", " + std::to_string(he[i].hi) + ")";
    if (j - i > 2)
      throw std::invalid_argument("triangulated crack: " + name + " belongs to " + std::to_string(j - i)
                                  + " triangles (" + std::to_string(he[i].tri) + ", " + std::to_string(he[i + 1].tri)
                                  + ", " + std::to_string(he[i + 2].tri)
                                  + ", ...): the surface is non-manifold; split it into separate cracks or remove "
                                    "the extra triangles");
    if (j - i == 2 and he[i].forward == he[i + 1].forward)
      throw std::invalid_argument("triangulated crack: triangles " + std::to_string(he[i].tri) + " and "
                                  + std::to_string(he[i + 1].tri) + " traverse their common " + name
                                  + " in the same direction: inconsistent orientation; reverse the vertex order of "
                                    "triangle "
                                  + std::to_string(he[i + 1].tri) + " (orient all triangles consistently)");
    Point3 pn = {0, 0, 0};
    for (std::size_t k = i; k < j; ++k)
    {
      s->te[he[k].tri][he[k].side] = e;
      pn = add(pn, s->face_normal[he[k].tri]);
    }
    s->edge_normal.push_back(pn);
    s->edge_triangle.push_back(he[i].tri);
    const bool boundary = j - i == 1;
    s->edge_boundary.push_back(boundary);
    if (boundary)
    {
      s->front.push_back({he[i].lo, he[i].hi});
      ++boundary_degree[he[i].lo];
      ++boundary_degree[he[i].hi];
      // Outward in-surface normal: edge x triangle normal, away from the
      // triangle's third vertex.
      const auto& T = s->t[he[i].tri];
      const std::int32_t third = T[(he[i].side + 2) % 3];
      const Point3 ed = sub(s->v[he[i].hi], s->v[he[i].lo]);
      Point3 out = unit(cross(ed, s->face_normal[he[i].tri]));
      if (dot(out, sub(s->v[third], s->v[he[i].lo])) > 0.0)
        out = scale(-1.0, out);
      s->front_out.push_back(out);
      s->front_tri.push_back(he[i].tri);
    }
    i = j;
  }
  if (s->front.empty())
    throw std::invalid_argument("triangulated crack: the surface is closed (every edge has two triangles), so it "
                                "has no front; a crack surface needs a boundary");
  for (std::int32_t i = 0; i < nv; ++i)
    if (boundary_degree[i] > 2)
      throw std::invalid_argument("triangulated crack: vertex " + std::to_string(i) + " " + fmt(s->v[i])
                                  + " has " + std::to_string(boundary_degree[i])
                                  + " boundary edges: the surface is non-manifold there (two sheets touch at a "
                                    "vertex), so the front branches; split the surface into separate cracks");
  s->vertex_front.assign(nv, {-1, -1});
  for (std::int32_t e = 0; e < static_cast<std::int32_t>(s->front.size()); ++e)
    for (std::int32_t vi : s->front[e])
      s->vertex_front[vi][s->vertex_front[vi][0] < 0 ? 0 : 1] = e;
  // Angle-weighted vertex pseudo-normals.
  s->vertex_normal.assign(nv, {0, 0, 0});
  s->vertex_boundary.assign(nv, 0);
  for (std::int32_t k = 0; k < nt; ++k)
    for (int j = 0; j < 3; ++j)
    {
      const std::int32_t a = s->t[k][j], b = s->t[k][(j + 1) % 3], c = s->t[k][(j + 2) % 3];
      const double w = angle_between(sub(s->v[b], s->v[a]), sub(s->v[c], s->v[a]));
      s->vertex_normal[a] = axpy(s->vertex_normal[a], w, s->face_normal[k]);
    }
  for (std::int32_t i = 0; i < nv; ++i)
    s->vertex_boundary[i] = boundary_degree[i] > 0;
  // Trees over the triangles and the front edges.
  std::vector<double> boxes;
  for (const auto& T : s->t)
  {
    for (int d = 0; d < 3; ++d)
      boxes.push_back(std::min({s->v[T[0]][d], s->v[T[1]][d], s->v[T[2]][d]}));
    for (int d = 0; d < 3; ++d)
      boxes.push_back(std::max({s->v[T[0]][d], s->v[T[1]][d], s->v[T[2]][d]}));
  }
  s->tri_tree = BoundingBoxTree<3>(boxes);
  boxes.clear();
  for (const auto& E : s->front)
  {
    for (int d = 0; d < 3; ++d)
      boxes.push_back(std::min(s->v[E[0]][d], s->v[E[1]][d]));
    for (int d = 0; d < 3; ++d)
      boxes.push_back(std::max(s->v[E[0]][d], s->v[E[1]][d]));
  }
  s->front_tree = BoundingBoxTree<3>(boxes);
  return CrackSurface3D(s);
}

LevelSets3D compute_level_sets_3d(std::span<const double> x, const CrackSurface3D& surface)
{
  if (x.size() % 3 != 0)
    throw std::invalid_argument("compute_level_sets_3d: x must be an array of shape (num_nodes, 3)");
  const std::size_t n = x.size() / 3;
  LevelSets3D ls;
  ls.phi.resize(n);
  ls.psi.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Point3 p = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    if (!std::isfinite(p[0]) or !std::isfinite(p[1]) or !std::isfinite(p[2]))
      throw std::invalid_argument("compute_level_sets_3d: mesh node " + std::to_string(i)
                                  + " has a non-finite coordinate; node coordinates must be finite");
    const auto [phi, psi] = surface.level_sets(p);
    ls.phi[i] = phi;
    ls.psi[i] = psi;
  }
  return ls;
}

} // namespace cracklip
