// The crack front in 3D: ordered polylines of front points with local
// frames, and the nearest point of the front to any point (layer a).
//
// Every front cell holds one straight front segment (phi = psi = 0 for the
// P1 level sets). The segments are joined across cells into pieces: open
// pieces end where the front leaves the part (a surface crack), closed
// pieces are loops (a penny crack). The front points are the polyline's
// vertices (the segments' end points, on the faces of the front cells), in
// order along each piece, with their arc length and a right-handed
// orthonormal frame:
//   e2 = crack normal (grad phi, toward phi > 0),
//   e3 = tangent of the front (the polyline's, orthogonalised against e2),
//        oriented so that e1 below points away from the crack,
//   e1 = e2 x e3 = propagation direction (in the crack plane, normal to the
//        front, ~ grad psi).
#pragma once

#include "geometry/bounding_box_tree.h"
#include "geometry/cut_tetrahedron.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// One front segment of a front cell, physical coordinates: P -> Q oriented
/// along grad psi x grad phi (= e3), and the cell's level-set gradients.
struct FrontSegment
{
  Point3 p, q;
  std::int32_t cell = -1;
  Point3 grad_phi, grad_psi;
};

/// The front of one crack.
struct CrackFront3D
{
  /// Front points (num_points, 3), piece after piece, in order along each.
  std::vector<double> x;
  /// Arc length from the start of the point's piece, (num_points).
  std::vector<double> s;
  /// Frame of each point, (num_points, 3, 3): rows e1, e2, e3.
  std::vector<double> frame;
  /// A front cell holding the point (the cell of the segment that leaves it,
  /// or enters it at the end of an open piece), (num_points).
  std::vector<std::int32_t> cell;
  /// 1 if the point lies on the part's boundary (the ends of an open piece
  /// that leaves the part), (num_points).
  std::vector<std::int8_t> on_boundary;
  /// Piece k holds the points [piece_offsets[k], piece_offsets[k + 1]),
  /// (num_pieces + 1).
  std::vector<std::int32_t> piece_offsets = {0};
  /// 1 for a closed piece (a loop: its last point joins its first), (num_pieces).
  std::vector<std::int8_t> closed;
  /// Segments of the polyline (num_segments, 2) as point indices, in piece
  /// order (a closed piece's last segment joins its last and first points),
  /// and the front cell holding each, (num_segments).
  std::vector<std::int32_t> segments;
  std::vector<std::int32_t> segment_cell;
  /// Points where more than two front segments meet (0 for a manifold front).
  std::int32_t num_branch_points = 0;

  std::int32_t num_points() const { return static_cast<std::int32_t>(s.size()); }
  std::int32_t num_pieces() const { return static_cast<std::int32_t>(closed.size()); }
  std::int32_t num_segments() const { return static_cast<std::int32_t>(segment_cell.size()); }
};

/// Join front segments (sorted by cell) into ordered pieces. End points
/// closer than tol are the same point; duplicate segments (a front on a
/// face or an edge is held by every cell around it) count once, for the
/// lowest cell. boundary_faces (n, 3, 3): triangles of the part's boundary
/// near the front; a piece's end within tol of one is on the boundary.
/// Where more than two segments meet (the P1 front of a degenerate
/// configuration touching itself at a point) the pieces end: counted in
/// num_branch_points, their ends there not on the boundary.
CrackFront3D create_crack_front_3d(std::span<const FrontSegment> segments, std::span<const double> boundary_faces,
                                   double tol);

/// The point of the front polyline nearest to a point, with the frame
/// interpolated along its segment.
struct FrontProjection
{
  std::int32_t segment = -1; ///< index into CrackFront3D::segments
  double t = 0.0;            ///< position along the segment, [0, 1]
  Point3 x;                  ///< the nearest point of the front
  double distance = 0.0;     ///< from the query point
  double s = 0.0;            ///< arc length of x in its piece
  std::int32_t piece = -1;
  std::int32_t nearest_point = -1; ///< the nearer end of the segment (a front point)
  /// Frame at x, rows e1, e2, e3: the end frames interpolated linearly in
  /// t, then e2 normalised, e3 orthogonalised against it, e1 = e2 x e3.
  std::array<Point3, 3> frame;
};

/// Nearest-point queries on a front (a bounding-box tree over its segments:
/// O(log n) per query). Keeps a reference to the front.
class FrontLocator
{
public:
  explicit FrontLocator(const CrackFront3D& front);
  /// Throws std::runtime_error for a front without segments. frames
  /// (num_points, 3, 3), if given, replace the front's own frames (e.g.
  /// frames fitted to a triangulated surface), interpolated the same way.
  FrontProjection project(const Point3& p, std::span<const double> frames = {}) const;

private:
  const CrackFront3D& front_;
  std::vector<std::int32_t> piece_; ///< piece of each segment
  BoundingBoxTree<3> tree_;
};

} // namespace cracklip
