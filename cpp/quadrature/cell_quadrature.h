// The quadrature of enriched cells behind one name (layer a): where the
// geometry differs, each dimension has its own rules (cell_quadrature_2d.h:
// sub-triangles and fans from a tip; cell_quadrature_3d.h: sub-tetrahedra
// and rules collapsed onto a front), and both answer
// compute_enriched_cell_quadrature(x, cells, layout, cracks, c, options,
// out) with points in reference coordinates (n, dim), weights (n) and sides
// (n). Code written once for any dimension names the types below.
#pragma once

#include "quadrature/cell_quadrature_2d.h"
#include "quadrature/cell_quadrature_3d.h"

#include <type_traits>

namespace cracklip
{

/// QuadratureOptions (tip rules, 2D) or QuadratureOptions3D (front rules).
template <int dim>
using QuadratureOptionsOf = std::conditional_t<dim == 2, QuadratureOptions, QuadratureOptions3D>;

/// CellQuadrature (2D) or CellQuadrature3D.
template <int dim>
using CellQuadratureOf = std::conditional_t<dim == 2, CellQuadrature, CellQuadrature3D>;

} // namespace cracklip
