// Quadrature points on a boundary facet of a cell (layer a), split where a
// crack crosses the facet so that each piece lies on one side of it: a
// segment cut at a point (2D) or a triangle cut along a line (3D). For
// Neumann loads on facets of enriched cells (assembly/facet_basis.h).
#pragma once

#include "geometry/crack_geometry.h"
#include "geometry/p1_simplex.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// The points of one facet: reference coordinates in the cell (n, dim),
/// physical weights (n, the facet's length / area measure), the side of
/// the crack crossing the cell on each point's piece (n; +1 / -1, 0 where no
/// crack crosses the cell) and the facet's outward unit normal (dim).
struct FacetPoints
{
  std::vector<double> ref;
  std::vector<double> weight;
  std::vector<std::int8_t> side;
  std::vector<double> normal;
  void clear() { ref.clear(), weight.clear(), side.clear(), normal.clear(); }
  int size() const { return static_cast<int>(weight.size()); }
};

/// Facet lf (opposite vertex lf) of cell c: Gauss-Legendre with (degree + 2)
/// / 2 points on each piece of the edge (2D), the triangle rule of `degree`
/// on each piece of the face (3D).
void compute_facet_points(const P1Cell& cell, std::span<const CrackGeometry* const> cracks, std::int32_t c, int lf,
                          int degree, FacetPoints& out);
void compute_facet_points(const P1Tetrahedron& cell, std::span<const CrackGeometry3D* const> cracks, std::int32_t c,
                          int lf, int degree, FacetPoints& out);

} // namespace cracklip
