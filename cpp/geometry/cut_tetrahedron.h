// One tetrahedron (or triangle) cut by the zero set of a linear function
// (layer a: no DOLFINx). Marching tetrahedra with one cut point per
// sign-changing edge, for every sign pattern of the four vertex values,
// zeros included:
//
//   signs (+, -, 0) | interface         | sub-tetrahedra
//   1, 3, 0         | triangle          | 1 (tet) + 3 (prism)        = 4
//   2, 2, 0         | quad (2 triangles)| 3 (prism) + 3 (prism)      = 6
//   1, 2, 1         | triangle          | 1 (tet) + 2 (pyramid)      = 3
//   1, 1, 2         | triangle          | 1 + 1                      = 2
//   one side only   | the zero face, if three values vanish, else none; the
//                   | tetrahedron itself (it touches the zero set at a
//                   | vertex, an edge or a face, or not at all)
//
// Works in whatever coordinates the vertices are given (the parent cell's
// reference coordinates in crack_geometry_3d, a sub-tetrahedron's for a
// second cut). A cut point records the edge and parameter it came from, so
// a caller can interpolate other linear fields (a second level set) exactly,
// keeping exact zeros exact.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace cracklip
{

using Point3 = std::array<double, 3>;

/// How a simplex meets the zero set of its level set.
enum class ZeroSet : std::int8_t
{
  none = 0,   ///< all values strictly of one sign
  vertex = 1, ///< one side only, one vertex value is zero
  edge = 2,   ///< one side only, two values are zero (an edge on the zero set)
  face = 3,   ///< one side only, three values are zero (a tetrahedron's face)
  cut = 4     ///< values of both signs: the zero set crosses the interior
};

/// Origin of a point of a cut: the input vertex a (b == a, t == 0) or the
/// zero of the level set on the edge (a, b): x = x_a + t (x_b - x_a),
/// t = f_a / (f_a - f_b) in (0, 1).
struct CutPoint
{
  int a = 0, b = 0;
  double t = 0.0;
  /// Value at this point of another linear field g given at the input
  /// vertices: (1 - t) g_a + t g_b (exactly 0 when g_a = g_b = 0).
  double interpolate(std::span<const double> g) const
  {
    return a == b ? g[a] : (1.0 - t) * g[a] + t * g[b];
  }
};

/// A tetrahedron cut by the zero set of a linear level set f.
struct TetrahedronCut
{
  ZeroSet kind = ZeroSet::none;
  /// Points (num_points): the 4 input vertices, then the cut points.
  int num_points = 0;
  std::array<Point3, 8> x;
  std::array<CutPoint, 8> from;
  /// Sub-tetrahedra (num_tets) as 4 indices into x, each positively
  /// oriented in the input coordinates (det[x1 - x0, x2 - x0, x3 - x0] >= 0),
  /// and the side (+1: f > 0, -1: f < 0) of each. Their volumes sum to the
  /// input's. Not cut: the input tetrahedron (reordered if needed).
  int num_tets = 0;
  std::array<std::array<int, 4>, 6> tets;
  std::array<std::int8_t, 6> side;
  /// Triangles of the zero set in the tetrahedron (num_interface: 1 or 2
  /// when cut or when a face is on the zero set, else 0), as 3 indices into
  /// x, oriented so that (x1 - x0) x (x2 - x0) points to the f > 0 side.
  int num_interface = 0;
  std::array<std::array<int, 3>, 2> interface;
};

/// Cut the tetrahedron with vertices x (4, 3) by the zero set of the linear
/// function with values f (4) at its vertices; the signs of f decide the
/// case, so exact zeros are honoured (the caller snaps). Throws
/// std::invalid_argument if all four values are zero or one is not finite.
void cut_tetrahedron(std::span<const double, 12> x, std::array<double, 4> f, TetrahedronCut& out);

/// A triangle (in 3D) cut by the zero set of a linear function.
struct TriangleCut
{
  ZeroSet kind = ZeroSet::none; ///< none, vertex, edge (an edge on the zero set) or cut
  /// Points (num_points): the 3 input vertices, then the cut points (<= 2).
  int num_points = 0;
  std::array<Point3, 5> x;
  std::array<CutPoint, 5> from;
  /// Sub-triangles (num_tris) as 3 indices into x, with the orientation of
  /// the input triangle, and the side of each (+1 / -1).
  int num_tris = 0;
  std::array<std::array<int, 3>, 3> tris;
  std::array<std::int8_t, 3> side;
  /// The zero segment inside the triangle as 2 indices into x (cut or edge
  /// kind), else -1.
  std::array<int, 2> zero_segment = {-1, -1};
};

/// Cut the triangle with vertices x (3, 3) by the zero set of the linear
/// function with values f (3). Throws std::invalid_argument if all values
/// are zero or one is not finite.
void cut_triangle(std::span<const double, 9> x, std::array<double, 3> f, TriangleCut& out);

/// Signed volume of the tetrahedron (a, b, c, d): det[b - a, c - a, d - a] / 6.
double signed_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

} // namespace cracklip
