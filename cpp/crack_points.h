// Points on a crack's segments, for integrals along its lips (layer a).
//
// Every cell the crack crosses (cut cells, the owner of an edge crack's
// edge, tip cells) carries one straight segment. Integrals along the lips
// (lip loads, the lip term of the interaction integral, sampled outputs)
// use n Gauss points per segment, in the variable t = tau^2 from an end that
// is a crack tip: the jump of tip functions grows like sqrt(r) and the
// gradients of the auxiliary SIF fields like 1/sqrt(r) there, both
// polynomial in tau.
#pragma once

#include "crack_geometry.h"
#include "enriched_basis.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Unit normal of the crack in a cell, pointing to the phi > 0 (+) side.
std::array<double, 2> crack_normal(const P1Cell& cell, const CrackGeometry& g);

/// Which end of the segment P-Q (physical points) is a tip of the crack:
/// 0 (P), 1 (Q) or -1 (neither).
int tip_end_of(const CrackGeometry& g, std::array<double, 2> P, std::array<double, 2> Q);

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
