// Crack geometry on a P1 tetrahedral mesh given as plain arrays (layer a):
// the 3D counterpart of crack_geometry_2d.
//
// From the nodal level sets phi (normal) and psi (in-surface distance to the
// front, < 0 where the crack is) of one crack: snapped values, a class per
// cell, and for every cell the crack touches its sub-tetrahedra (reference
// coordinates, side, which vertices lie on the front), its lip facets
// (triangles of phi = 0 where psi < 0, parent reference coordinates, area,
// normal) and its front segment; then the front as ordered polylines of
// front points with frames (crack_front_3d.h). Everything is stored per
// cell the crack touches (crack_cells, found through crack_cell_index) or
// per front point: no global array beyond the per-node and per-cell ones.
//
// Reference coordinates refer to the cell's node order: vertex a of the
// cell is (0,0,0), (1,0,0), (0,1,0), (0,0,1) for a = 0..3, x = x0 + J xi.
#pragma once

#include "geometry/crack_front_3d.h"
#include "geometry/crack_surface_3d.h"

#include <array>
#include <limits>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace cracklip
{

/// Class of a tetrahedron with respect to one crack (numbered as the 2D
/// CellClass: face <-> edge, front <-> tip).
enum class CellClass3D : std::int8_t
{
  plain = 0,    ///< not crossed by the crack (may touch it at a vertex or an edge)
  cut = 1,      ///< crossed by phi = 0 where the crack is present (psi < 0 on the crossing)
  face = 2,     ///< the crack covers one of its faces (the cell lies on one side)
  front = 3,    ///< the front (phi = psi = 0) meets the closed cell: a segment, or a point
  extension = 4 ///< crossed by phi = 0 where the crack is absent (psi > 0 on the crossing)
};

/// A cell the crack touches (cut, face or front class).
struct CrackCell3D
{
  std::int32_t cell = -1;
  CellClass3D cls = CellClass3D::plain;

  /// Sub-tetrahedra, reference coordinates (num_sub, 4, 3), positively
  /// oriented in reference coordinates, the vertices on the front first:
  /// vertices 0, 1 when num_front == 2 (an edge on the front), vertex 0 when
  /// num_front == 1. Cut cells: the pieces on both sides of phi = 0 (2 to 6);
  /// face cells: the cell itself; front cells: the pieces of the cut by phi
  /// (or the cell), each cut again by psi. Slivers below 1e-12 of the
  /// cell's volume are dropped (their reference volume in dropped_volume).
  std::vector<double> sub;
  std::vector<std::int8_t> side;      ///< (num_sub) +1: phi >= 0, -1: phi <= 0
  std::vector<std::int8_t> psi_side;  ///< (num_sub) front cells: -1 psi <= 0 (crack), +1 psi >= 0; else 0
  std::vector<std::int8_t> num_front; ///< (num_sub) 0, 1 or 2 vertices on the front
  double dropped_volume = 0.0;        ///< reference volume of dropped slivers (of 1/6)

  /// Lip facets held by this cell (triangles of phi = 0 where psi <= 0; a
  /// face on the crack belongs to the + side cell only), reference
  /// coordinates (num_facets, 3, 3), vertices on the front first (as for
  /// sub), ordered so that the physical normal (x1 - x0) x (x2 - x0) points
  /// to the + side.
  std::vector<double> facets;
  std::vector<double> facet_area;           ///< (num_facets) physical area
  std::vector<double> facet_normal;         ///< (num_facets, 3) physical unit normal, to phi > 0
  std::vector<std::int8_t> facet_num_front; ///< (num_facets) 0, 1 or 2

  /// Front cells: the front segment in the cell (phi = psi = 0 of the P1
  /// level sets), reference coordinates (P, Q) (2, 3), P -> Q along
  /// e3 ~ grad psi x grad phi, and its physical length (0 when the front
  /// only touches the cell at a point). A segment on a face or an edge is
  /// held by every front cell around it; the front polyline takes it from
  /// the cells where the crack is present (psi < 0 on their crossing).
  std::array<double, 6> front_segment = {};
  double front_length = 0.0;

  int num_sub() const { return static_cast<int>(side.size()); }
  int num_facets() const { return static_cast<int>(facet_area.size()); }
};

/// Geometry of one crack on the mesh.
struct CrackGeometry3D
{
  /// Level sets at the nodes after snapping, (num_nodes) each.
  std::vector<double> phi, psi;
  /// Class of each cell, values of CellClass3D, (num_cells).
  std::vector<std::int8_t> cell_class;
  /// Side of each cell, (num_cells): +1/-1 for plain and face cells, 0 for
  /// cut, front and extension cells (their sub-tetrahedra carry the side).
  std::vector<std::int8_t> cell_side;
  /// Cut, face and front cells, sorted by cell index.
  std::vector<CrackCell3D> crack_cells;
  /// Position of each cell in crack_cells or -1, (num_cells).
  std::vector<std::int32_t> crack_cell_index;
  /// The front: ordered pieces of front points with frames.
  CrackFront3D front;
  /// The front segments the front was joined from (one per front cell where
  /// the crack is present, by cell), and the smallest front cell's size
  /// (largest edge; the scale of the joining tolerance, infinity without
  /// front cells): a front held by several processes is joined again from
  /// every process's segments (set_crack_front_3d).
  std::vector<FrontSegment> front_segments;
  double front_cell_size = std::numeric_limits<double>::infinity();
  /// Number of nodes whose phi or psi was snapped to zero.
  std::int32_t num_snapped = 0;
  /// Front cells where P1 psi vanishes on the whole zero set of phi (a
  /// triangle or quad): there the P1 front is not a line (e.g. a polygon
  /// crack's corner on a node, its edges along mesh edges); their
  /// sub-tetrahedra may touch the front along a face, of which num_front
  /// reports one edge. 0 in generic positions; move the crack off the nodes
  /// by a fraction of h to remove them.
  std::int32_t num_degenerate_front_cells = 0;
};

/// The level sets define no crack in the mesh (no cut, face or front cell).
class CrackOutsideMesh : public std::invalid_argument
{
public:
  using std::invalid_argument::invalid_argument;
};

/// Compute the geometry of the crack given by its nodal level sets phi, psi
/// (num_nodes) on the mesh (x: (num_nodes, 3) node coordinates; cells:
/// (num_cells, 4) node indices per tetrahedron). Snapping as in 2D: a node
/// whose |phi| (or |psi|) is below snap_tol times the shortest edge at the
/// node gets the value 0 (snapping.h). Work: one pass over the cells' signs,
/// then proportional to the cells phi = 0 meets.
/// Throws CrackOutsideMesh (an std::invalid_argument) when no cell is cut,
/// face or front, std::invalid_argument for bad arrays, and
/// std::runtime_error for a cell with phi = 0 at all four nodes (a
/// degenerate cell, or snap_tol too large). node_keys (num_nodes, or
/// empty: the node indices): the order in which each cell's vertices are
/// cut, which decides its sub-tetrahedra; a numbering independent of the
/// local one (the mesh's input node indices) gives the same sub-tetrahedra
/// on any number of processes. require_crack false: no CrackOutsideMesh
/// (one process's part of a mesh may hold none of the crack; the caller
/// decides over all processes).
CrackGeometry3D compute_crack_geometry_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                          std::span<const double> phi, std::span<const double> psi, double snap_tol,
                                          std::span<const std::int64_t> node_keys = {}, bool require_crack = true);

/// The same from a crack surface (compute_level_sets_3d, then the above);
/// a crack outside the part is reported with both bounding boxes, and the
/// front frames come from the surface's analytic directions at the front
/// points (CrackSurface3D::front_directions: exact directions at an O(h^2)
/// accurate point) instead of the P1 polyline's (O(h)).
CrackGeometry3D compute_crack_geometry_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                          const CrackSurface3D& surface, double snap_tol,
                                          std::span<const std::int64_t> node_keys = {}, bool require_crack = true);

/// Replace g's front by the one joined from the given segments (in the
/// order given: their points merge first-come, so one order gives one front)
/// and the part's boundary faces near the front (n, 3, 3) within
/// JOIN_TOLERANCE * h_front; frames from the surface's directions when
/// surface is given (as compute_crack_geometry_3d from a surface), else the
/// polyline's. For a front whose cells are spread over processes: every
/// process passes every process's segments in one canonical order and gets
/// the same front.
void set_crack_front_3d(CrackGeometry3D& g, std::span<const FrontSegment> segments,
                        std::span<const double> boundary_faces, double h_front, const CrackSurface3D* surface);

/// Front points within JOIN_TOLERANCE * (smallest front cell size) are one.
inline constexpr double JOIN_TOLERANCE = 1e-9;

} // namespace cracklip
