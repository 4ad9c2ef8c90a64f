// Quadrature points of one cell for enriched integrands (layer a).
//
// Regions: a cell crossed by a crack is split into its sub-triangles; the
// cell holding a tip is fanned from the tip over its boundary (with the
// crack's entry point inserted), so every region lies on one side of the
// crack. Rules: polynomial regions get a Gauss rule of a given degree;
// regions carrying tip functions get the quasi-polar rule fanned from the
// tip (a signed sum of fans when the tip lies outside the region), with
// every fan triangle's angle at the apex kept below max_angle: this removes
// the 1/r singularity in the tip cell and the near-singularity next to it.
// For comparison with the paper, the plain n x n conical Gauss rule is
// available.
#pragma once

#include "enrichment/enriched_basis.h"
#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry_2d.h"
#include "geometry/p1_simplex.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace cracklip
{

enum class TipQuadrature : std::int8_t
{
  collapsed = 0, ///< quasi-polar fan with rho = t^2 (default)
  gauss = 1      ///< the paper's plain rule: ((p + 3) / 2)^2 points per sub-triangle
};

struct QuadratureOptions
{
  int degree = 2; ///< Gauss degree where no tip function lives
  TipQuadrature tip_rule = TipQuadrature::collapsed;
  int tip_radial = 6;           ///< collapsed: points along each ray (t)
  int tip_angular = 6;          ///< collapsed: points across each fan triangle (eta)
  double tip_max_angle = 0.6;   ///< collapsed: largest apex angle of a fan triangle (radians)
  int tip_degree = 5;           ///< gauss: degree p, n = (p + 3) / 2
  /// collapsed: cells farther from the tip than far_factor times their
  /// diameter carry a smooth integrand and get the Gauss rule of far_degree.
  double far_factor = 3.0;
  int far_degree = 10;
};

/// Quadrature points of a cell: reference coordinates (n, 2), physical
/// weights (n) and the side (n) of the crack crossing or ending in the cell
/// (+1 / -1; 0 where no crack crosses the cell).
struct CellQuadrature
{
  std::vector<double> ref;
  std::vector<double> weight;
  std::vector<std::int8_t> side;
  void clear() { ref.clear(), weight.clear(), side.clear(); }
  int size() const { return static_cast<int>(weight.size()); }
};

/// Integration regions of a cell: the sub-triangles of a crossed cell (with
/// the side of the crossing crack), else the cell itself (side 0).
struct CellRegions
{
  const CrackCell* crack_cell = nullptr;

  CellRegions(std::span<const CrackGeometry* const> cracks, std::int32_t c)
  {
    const int ic = crossing_crack(cracks, c);
    if (ic >= 0)
      crack_cell = &cracks[ic]->crack_cells[cracks[ic]->crack_cell_index[c]];
  }
  int size() const { return crack_cell ? crack_cell->num_sub : 1; }
  int side(int s) const { return crack_cell ? crack_cell->side[s] : 0; }
  /// Vertices of region s in reference coordinates.
  std::array<std::array<double, 2>, 3> triangle(int s) const
  {
    std::array<std::array<double, 2>, 3> tri = {{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}};
    if (crack_cell)
      for (int i = 0; i < 3; ++i)
        tri[i] = {crack_cell->sub[6 * s + 2 * i], crack_cell->sub[6 * s + 2 * i + 1]};
    return tri;
  }
  /// Reference area of region s.
  double area(int s) const
  {
    const auto t = triangle(s);
    return 0.5 * std::abs((t[1][0] - t[0][0]) * (t[2][1] - t[0][1])
                          - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]));
  }
};

using Point2 = std::array<double, 2>;
using Triangle2 = std::array<Point2, 3>;

/// Fan triangles (apex, p_k, p_k+1) over a closed polygon around or through
/// the apex (physical coordinates), each split so that its angle at the apex
/// is at most max_angle; degenerate triangles are skipped. The apex is
/// vertex 0 of every triangle.
std::vector<Triangle2> fan_triangles(Point2 apex, std::span<const Point2> polygon, double max_angle);

/// A triangle as a signed sum of fan triangles (apex, v_k, v_k+1) from an
/// apex inside or outside it, each of apex angle at most max_angle: the
/// pairs are (fan triangle, +1 / -1).
std::vector<std::pair<Triangle2, double>> signed_fans(Point2 apex, const Triangle2& tri,
                                                      double max_angle);

/// The collapsed rule over fan triangles: physical points (n, 2) and weights.
void fan_rule(std::span<const Triangle2> fans, const QuadratureOptions& options,
              std::vector<double>& points, std::vector<double>& weights);

/// A rule over a polygon (physical coordinates, e.g. a tip cell) fanned from
/// the tip inside it: the collapsed rule, or with options.tip_rule == gauss
/// the paper's plain ((p + 3) / 2)^2-point rule on each fan triangle.
void tip_polygon_rule(Point2 apex, std::span<const Point2> polygon, const QuadratureOptions& options,
                      std::vector<double>& points, std::vector<double>& weights);

/// Fill `out` for cell c. `tip` is the tip frame the cell's tip functions
/// belong to, or nullptr if the cell carries none.
void compute_cell_quadrature(const P1Cell& cell, std::int32_t c,
                             std::span<const CrackGeometry* const> cracks, const TipFrame* tip,
                             const QuadratureOptions& options, CellQuadrature& out);

/// The tip frame a cell's tip functions belong to (nearest tip among its
/// pseudo-nodes), or nullptr.
const TipFrame* cell_tip(const P1Cell& cell, const CellBasis& basis, const EnrichmentLayout& layout);

/// The rule of an enriched cell c (x (num_nodes, 2), cells (num_cells, 3)):
/// compute_cell_quadrature with the tip of its tip functions, if any (the
/// 2D geometry's answer to the enriched kernels, enriched_stiffness.h).
void compute_enriched_cell_quadrature(std::span<const double> x, std::span<const std::int32_t> cells,
                                      const EnrichmentLayout& layout, std::span<const CrackGeometry* const> cracks,
                                      std::int32_t c, const QuadratureOptions& options, CellQuadrature& out);

} // namespace cracklip
