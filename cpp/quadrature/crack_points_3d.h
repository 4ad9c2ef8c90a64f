// Points on a crack's lip facets, for integrals over its lips in 3D (layer
// a): the 3D counterpart of crack_points_2d.
//
// Every lip facet (a triangle of phi = 0 where psi < 0, held by one cell)
// gets a rule: a Gauss rule if it does not touch the front (signed fans
// from the front if it lies near it); the 2D edge-collapsed rule if an edge
// lies on the front and the point-collapsed one if a vertex does
// (front_rules_3d.h), in which the sqrt(r) jump of
// front functions and the 1/sqrt(r) of auxiliary SIF fields are
// polynomial. For lip loads, contact terms, the lip term of the interaction
// integral and sampled outputs.
#pragma once

#include "geometry/crack_geometry_3d.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Points on the lip facets of one crack, facet by facet in the order of
/// crack_cells.
struct LipPoints3D
{
  std::vector<std::int32_t> cell; ///< (n) parent cell
  std::vector<double> ref;        ///< (n, 3) reference coordinates in the cell
  std::vector<double> x;          ///< (n, 3) physical points
  std::vector<double> weight;     ///< (n) area measure (may be negative on a point-collapsed piece)
  std::vector<double> normal;     ///< (n, 3) unit normal pointing to the + side
  std::vector<std::int8_t> front_vertices; ///< (n) num_front of the facet the point belongs to
};

/// n points per direction: Gauss of degree 2 n - 1 on facets away from the
/// front, n x n collapsed points on facets touching it (with a vertex on
/// it: the plain fan from that vertex, points inside and weights positive,
/// or with signed_point_rule the signed decomposition of
/// triangle_point_collapsed, exact for r^(-1/2) however close the front
/// passes but with points outside the facet), and the near-front rule
/// (signed fans from the cell's front line, triangle_near_front) on facets
/// whose nearest vertex is within near_factor times their diameter of that
/// line (0: never).
LipPoints3D compute_lip_points_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                  const CrackGeometry3D& g, int n, double near_factor = 0.0,
                                  bool signed_point_rule = false);

} // namespace cracklip
