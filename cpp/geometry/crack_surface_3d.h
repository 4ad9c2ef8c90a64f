// Crack surfaces in 3D and their nodal level sets (layer a: no DOLFINx).
//
// A crack is the part {phi = 0, psi < 0} of a surface; its front is
// {phi = 0, psi = 0}:
//   phi = signed distance to the (extended) surface, > 0 on the side the
//         surface normal points to;
//   psi = signed distance to the front measured within the (extended)
//         surface, < 0 inside the crack.
// Three kinds:
//   - ellipse (or circle): planar, psi is the in-plane signed distance to the
//     ellipse, from the closest point on the ellipse (exact to round-off);
//   - polygon: planar, psi is the in-plane signed distance to the polygon's
//     boundary;
//   - triangulated surface: phi by the nearest triangle (face, edge and
//     vertex sectors signed by angle-weighted pseudo-normals; beyond the
//     front, by the plane of the boundary triangle: the surface extended by
//     its tangent plane), psi = +-sqrt(d^2 - phi^2) with d the distance to the
//     nearest boundary (front) edge, negative where the nearest point of the
//     surface is not on its boundary. For a planar triangulation both are the
//     exact in-plane distances, as for the polygon.
// A part's boundary cuts the surface where they cross: nothing here needs
// the part (a surface crack is an ellipse centred on a face).
#pragma once

#include "geometry/cut_tetrahedron.h"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace cracklip
{

/// Closest point on the ellipse (x/a)^2 + (y/b)^2 = 1 (a, b > 0, any order)
/// to the point y of its plane, in the ellipse's axes: the point, and the
/// signed distance (< 0 inside). Bisection on the Lagrange multiplier of the
/// closest-point condition to round-off (a circle in closed form).
struct EllipsePoint
{
  std::array<double, 2> x;
  double distance;
};
EllipsePoint closest_point_on_ellipse(double a, double b, std::array<double, 2> y);

namespace detail
{
struct SurfaceImpl;
}

/// A validated crack surface (create it with create_*_crack).
class CrackSurface3D
{
public:
  enum class Kind : std::int8_t
  {
    ellipse = 0,
    polygon = 1,
    triangulated = 2
  };

  explicit CrackSurface3D(std::shared_ptr<const detail::SurfaceImpl> impl);

  Kind kind() const;
  /// (phi, psi) at a point.
  std::array<double, 2> level_sets(const Point3& p) const;
  /// The crack's directions at the front point nearest p (analytic): e1 the
  /// unit propagation direction (in the surface, normal to the front, away
  /// from the crack) and e2 the unit normal (to the phi > 0 side), not
  /// necessarily orthogonal for a curved triangulated surface.
  std::array<Point3, 2> front_directions(const Point3& p) const;
  /// Bounding box of the crack (the part where psi <= 0): (lo, hi), (2, 3).
  std::array<double, 6> bounding_box() const;
  /// One line for messages, e.g. "ellipse crack (centre (0, 0, 0), ...)".
  std::string describe() const;

private:
  std::shared_ptr<const detail::SurfaceImpl> impl_;
};

/// Elliptical (or circular) planar crack. `normal` (any length > 0) points
/// to the phi > 0 side; `axis` (any length, not parallel to the normal; its
/// normal component is removed) is the direction of the semi-axis a; the
/// semi-axis b lies along normal x axis. a and b > 0 in any order (a = b: a
/// circle of radius a). Throws std::invalid_argument naming the bad value.
CrackSurface3D create_ellipse_crack(const Point3& center, const Point3& normal, const Point3& axis, double a,
                                    double b);

/// Planar polygonal crack, vertices (n, 3), n >= 3, a simple polygon. Its
/// normal (the + side) follows the right-hand rule of the vertex order
/// (counter-clockwise seen from the + side). Throws std::invalid_argument
/// for a non-planar, self-intersecting or degenerate polygon.
CrackSurface3D create_polygon_crack(std::span<const double> vertices);

/// Triangulated crack surface: vertices (nv, 3), triangles (nt, 3) vertex
/// indices. Consistently oriented triangles: the normal (x1 - x0) x (x2 - x0)
/// points to the phi > 0 side. The front is the surface's boundary (edges of
/// one triangle). Throws std::invalid_argument naming the triangle, edge or
/// vertex and the fix for: an index out of range, a degenerate triangle, an
/// edge of more than two triangles (non-manifold), two triangles traversing
/// their common edge in the same direction (inconsistent orientation), a
/// boundary vertex with more than two boundary edges, a closed surface (no
/// front).
CrackSurface3D create_triangulated_crack(std::span<const double> vertices,
                                         std::span<const std::int32_t> triangles);

/// Nodal level sets, each (num_nodes).
struct LevelSets3D
{
  std::vector<double> phi;
  std::vector<double> psi;
};

/// phi and psi at the nodes x (num_nodes, 3): one pass over the nodes
/// (O(log n) per node for triangulated and polygonal surfaces).
LevelSets3D compute_level_sets_3d(std::span<const double> x, const CrackSurface3D& surface);

} // namespace cracklip
