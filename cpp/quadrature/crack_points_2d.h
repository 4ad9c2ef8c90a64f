// Points on a crack's segments, for integrals along its lips (layer a).
//
// Every cell the crack crosses (cut cells, the owner of an edge crack's
// edge, tip cells) carries one straight segment. Integrals along the lips
// (lip loads, contact terms, the lip term of the interaction integral,
// sampled outputs) use n Gauss points per segment, in the variable
// rho = sqrt(r) (r the distance to the crack's nearest tip) on the segments
// near a tip: the jump of tip functions grows like sqrt(r) and the gradients
// of the auxiliary SIF fields like 1/sqrt(r), both polynomial in rho.
#pragma once

#include "geometry/crack_geometry_2d.h"
#include "geometry/p1_simplex.h"
#include "quadrature/rules.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Unit normal of the crack in a cell, pointing to the phi > 0 (+) side.
std::array<double, 2> crack_normal(const P1Cell& cell, const CrackGeometry& g);

/// The rule of n points along the segment P-Q (physical points) of crack g:
/// graded in sqrt(r) toward the crack's nearest tip when that tip is closer
/// to the segment's nearer end than the segment is long (or is an end),
/// plain Gauss-Legendre otherwise (quadrature::line_toward_tip).
quadrature::Rule segment_rule(const CrackGeometry& g, std::array<double, 2> P, std::array<double, 2> Q, int n);

/// Gauss points on the segments of one crack, segment by segment in the
/// order of crack_cells (owners only) then tip_cells.
struct CrackPoints
{
  std::vector<std::int32_t> cell; ///< (n) parent cell
  std::vector<double> ref;        ///< (n, 2) reference coordinates in the cell
  std::vector<double> x;          ///< (n, 2) physical points
  std::vector<double> weight;     ///< (n) length measure
  std::vector<double> normal;     ///< (n, 2) unit normal pointing to the + side
};

/// n points per segment (t = tau^2 toward a tip end).
CrackPoints compute_crack_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                 const CrackGeometry& g, int n);

} // namespace cracklip
