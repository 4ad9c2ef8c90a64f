// Crack geometry on a P1 triangle mesh given as plain arrays (layer a).
//
// Level sets at the mesh nodes: phi (signed distance to the crack polyline,
// positive on the left of its direction of travel) and, for every tip, psi
// (signed distance along the tip tangent, negative behind the tip). Each
// cell is classified from the vertex values; cells crossed by the crack are
// split into sub-triangles and carry their crack segment in parent-cell
// (reference) coordinates.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// A crack given as a polyline.
struct CrackPath
{
  /// Polyline vertices, row-major (num_points, 2), num_points >= 2.
  std::vector<double> points;
  /// tip[0]: the first point is a crack tip (inside the domain);
  /// tip[1]: the last point is. A non-tip end lies on/outside the boundary.
  std::array<bool, 2> tip = {false, false};
};

/// Class of a cell with respect to one crack.
enum class CellClass : std::int8_t
{
  plain = 0,    ///< not crossed by the crack (may touch it at a vertex)
  cut = 1,      ///< crossed completely through its interior
  edge = 2,     ///< the crack runs along one of its edges
  tip = 3,      ///< holds a crack tip (crack only partly present)
  extension = 4 ///< crossed by the zero line of phi, but the crack is absent
};

/// A cell crossed (cut) by the crack or bordered by it (edge). Reference
/// coordinates refer to the cell's node order (0,0), (1,0), (0,1).
struct CrackCell
{
  std::int32_t cell = -1;
  CellClass cls = CellClass::plain;
  /// Number of sub-triangles (1 for an edge cell, 2 for a cut cell).
  int num_sub = 0;
  /// Sub-triangle vertices in reference coordinates, (num_sub, 3, 2).
  std::array<double, 18> sub = {};
  /// Side (+1: phi > 0, -1: phi < 0) of each sub-triangle.
  std::array<std::int8_t, 3> side = {0, 0, 0};
  /// Crack segment in the cell, reference coordinates (P_x, P_y, Q_x, Q_y);
  /// oriented so that the + side is on its left.
  std::array<double, 4> segment = {};
  /// True if this cell carries the segment for contact integrals (a crack on
  /// an edge borders two cells; only the + side one owns it).
  bool owns_segment = false;
};

/// A cell holding a crack tip.
struct TipCell
{
  std::int32_t cell = -1;
  int tip = -1; ///< index of the tip (0 or 1 into CrackGeometry::tips)
  /// Crack segment from where it enters the cell to the tip, reference
  /// coordinates (P_x, P_y, T_x, T_y).
  std::array<double, 4> segment = {};
};

/// Geometry of one crack on the mesh.
struct CrackGeometry
{
  /// phi at the nodes, (num_nodes), after snapping.
  std::vector<double> phi;
  /// psi at the nodes for each tip, row-major (num_tips, num_nodes).
  std::vector<double> psi;
  /// Tip coordinates (num_tips, 2) and unit tangents (num_tips, 2), the
  /// tangent pointing out of the crack (direction of propagation).
  std::vector<double> tips, tip_tangents;
  /// Per tip (num_tips): +1 if e2 = e1 rotated by +90 degrees points to the
  /// phi > 0 side (the last point of the polyline), -1 otherwise (the first).
  std::vector<int> tip_orientation;
  /// Class of each cell, (num_cells), values of CellClass.
  std::vector<std::int8_t> cell_class;
  /// Side of each cell, (num_cells): +1/-1 for plain and edge cells, 0 for
  /// cut, tip and extension cells (which have no single side).
  std::vector<std::int8_t> cell_side;
  /// Cut and edge cells, sorted by cell index.
  std::vector<CrackCell> crack_cells;
  /// Position of each cell in crack_cells or -1, (num_cells).
  std::vector<std::int32_t> crack_cell_index;
  /// Cells holding a tip.
  std::vector<TipCell> tip_cells;
  /// Position of each cell in tip_cells or -1, (num_cells).
  std::vector<std::int32_t> tip_cell_index;
  /// Number of nodes whose phi or psi was snapped to zero.
  std::int32_t num_snapped = 0;
};

/// Compute the geometry of `crack` on the mesh (x: (num_nodes, 2) node
/// coordinates; cells: (num_cells, 3) node indices per cell).
///
/// Snapping rule: a node whose |phi| (or |psi|) is below snap_tol times the
/// shortest edge at that node is moved onto the crack (its level set value
/// becomes exactly 0). No sub-cell is then thinner than snap_tol * h, which
/// bounds the conditioning of the enriched system; the crack is moved by at
/// most snap_tol * h.
CrackGeometry compute_crack_geometry(std::span<const double> x,
                                     std::span<const std::int32_t> cells,
                                     const CrackPath& crack, double snap_tol);

/// Signed distance from point p to the polyline (rays extended beyond the
/// two end points), positive on the left. Exposed for tests.
double signed_distance(const CrackPath& crack, std::array<double, 2> p);

} // namespace cracklip
