// Quadrature points of one tetrahedron for enriched integrands (layer a):
// the 3D counterpart of cell_quadrature_2d.
//
// A cell the crack touches is integrated over its sub-tetrahedra, each on one
// side of the crack: a Gauss rule on those away from the front, the
// edge-collapsed rule on those with an edge on the front and the
// point-collapsed rule on those with a vertex on it (front_rules_3d.h), so
// that the 1/r and 1/sqrt(r) of front-enriched integrands are integrated to
// round-off. Other cells get the Gauss rule on the whole cell. For
// comparison the collapsed rules can be replaced by a plain Gauss rule of a
// given degree. Sub-tetrahedra of crack cells that do not touch the front
// but lie near the cell's front line (the zero line of its P1 level sets)
// see a nearly singular integrand: they get the near-front rule (signed
// cones from the line, tetrahedron_near_front). Cells the crack does not
// touch get the Gauss rule; for those near the front the enrichment's
// assembly can call tetrahedron_near_front with the front from FrontLocator.
#pragma once

#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

enum class FrontQuadrature : std::int8_t
{
  collapsed = 0, ///< edge- and point-collapsed rules (default)
  gauss = 1      ///< plain Gauss of degree front_degree on sub-tetrahedra touching the front
};

struct QuadratureOptions3D
{
  int degree = 2; ///< Gauss degree on sub-tetrahedra away from the front and on other cells
  FrontQuadrature front_rule = FrontQuadrature::collapsed;
  int front_radial = 4;  ///< collapsed: points in tau (rho = tau^2, across the front)
  int front_angular = 6; ///< collapsed: points around the front (sinh-mapped)
  int front_axial = 2;   ///< collapsed: points along the front
  int front_degree = 5;  ///< gauss: degree on sub-tetrahedra touching the front
  /// collapsed: sub-tetrahedra of crack cells not touching the front whose
  /// nearest vertex is within near_factor times their diameter of the
  /// cell's front line get the near-front rule (0: never, the default: its
  /// negative weights cost the stiffness its positivity, and on a penny
  /// crack at a/h = 20 near_factor 1 raised the opening's L2 error from
  /// 2.5 to 3.0 % and tripled the enriched assembly).
  double near_factor = 0.0;
  /// collapsed: sub-tetrahedra with a vertex on the front by the signed
  /// decomposition (tetrahedron_point_collapsed: exact for r^-1 however
  /// close the front passes, weights of both signs) instead of the plain
  /// collapse onto the vertex (tetrahedron_vertex_collapsed, the default:
  /// positive weights). The signed weights make stiffness matrices
  /// indefinite by round-off-sized amounts, which stops CG (penny crack at
  /// a/h = 20: PETSc's indefinite-preconditioner exit after 2 iterations),
  /// while the plain collapse changed its opening by 0.1 %.
  bool signed_point_rule = false;
  /// Gauss degree on sub-tetrahedra (and cells) carrying front functions
  /// within a diameter of the front; graded down with the distance
  /// (front_function_degree). Used where `front_functions` is set. Penny
  /// crack at a/h = 14: the opened volume moves by 1e-4 from 6 to 4 (36
  /// points instead of 80 on the nearest pieces; 3: 3e-4).
  int far_degree = 4;
  /// The integrand carries front functions (set by the enriched kernels):
  /// sub-tetrahedra away from the front get front_function_degree instead
  /// of `degree`.
  bool front_functions = false;
};

/// Largest distance between two of the points (a piece's diameter).
double diameter(std::span<const Point3> points);

/// A piece lies near a line (a point on it, its unit direction): its
/// nearest vertex within factor times its diameter of the line (never for
/// factor <= 0). Decides where the near-front rules take over.
bool near_line(std::span<const Point3> vertices, const Point3& on_line, const Point3& direction, double factor);

/// Gauss degree for a piece carrying front functions (smooth there but not
/// polynomial, varying on the scale of the distance r to the front) whose
/// nearest vertex lies rho diameters from the front line: far_degree below
/// one diameter, 2 less below two, 4 less below four, 5 less beyond (never
/// below `degree`).
int front_function_degree(const QuadratureOptions3D& options, double rho);

/// Quadrature points of a cell: reference coordinates (n, 3) in the cell,
/// physical weights (n, summing to the cell's volume; a point-collapsed
/// piece may contribute negative weights, see front_rules_3d.h), and the
/// side (n) of the crack for each point: +1 / -1 in cut, face and front
/// cells (from the sub-tetrahedron), 0 in other cells. `front_vertices`
/// (n): 0, 1 or 2, the num_front of the sub-tetrahedron the point belongs
/// to (which rule made it).
struct CellQuadrature3D
{
  std::vector<double> ref;
  std::vector<double> weight;
  std::vector<std::int8_t> side;
  std::vector<std::int8_t> front_vertices;
  void clear() { ref.clear(), weight.clear(), side.clear(), front_vertices.clear(); }
  int size() const { return static_cast<int>(weight.size()); }
};

/// Fill `out` for cell c of the mesh (x (num_nodes, 3), cells (num_cells, 4))
/// with crack geometry g.
void compute_cell_quadrature_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                const CrackGeometry3D& g, std::int32_t c, const QuadratureOptions3D& options,
                                CellQuadrature3D& out);

/// Unit direction of the front line in a cell (grad psi x grad phi of its
/// P1 level sets, physical; along e3), or (0, 0, 0) where the gradients are
/// parallel.
Point3 front_direction(std::span<const double> x, std::span<const std::int32_t> cells, const CrackGeometry3D& g,
                       std::int32_t c);

/// The front line of a cell's P1 level sets (phi = psi = 0, extended beyond
/// the cell): its point nearest the cell's centroid and unit direction (as
/// front_direction). False where the gradients are parallel.
bool front_line(std::span<const double> x, std::span<const std::int32_t> cells, const CrackGeometry3D& g,
                std::int32_t c, Point3& point, Point3& direction);

/// Quadrature of an enriched cell: the crack geometry's per-cell rule where
/// a crack crosses the cell (sub-tetrahedra, collapsed at the front; Gauss
/// graded by the distance (front_function_degree) on the sub-tetrahedra away
/// from the front when the cell carries front functions); in a cell that
/// carries front functions without being crossed, the near-front rule
/// (signed cones from the cell's P1 front line) when that line passes within
/// options.near_factor diameters of its nearest vertex, else Gauss of
/// front_function_degree (graded by the distance to the front); Gauss of
/// options.degree otherwise. Sides: the crossing crack's sub-tetrahedra,
/// else 0. (The 3D geometry's answer to the enriched kernels,
/// enriched_stiffness.h.)
void compute_enriched_cell_quadrature(std::span<const double> x, std::span<const std::int32_t> cells,
                                      const EnrichmentLayout& layout, std::span<const CrackGeometry3D* const> cracks,
                                      std::int32_t c, const QuadratureOptions3D& options, CellQuadrature3D& out);

} // namespace cracklip
